"""The virtual rig's racket: a beam frame with a coupled string bed, free or held in a hand.

A structural model good enough to stand in for a real racket in a modal test (issue 3).  Its
modes are the rig's *modal truth*: identification from simulated hammer records is checked
against them.

Frame
    Euler–Bernoulli beam elements along the long axis (bending: Hermite cubics, DOFs ``w`` and
    ``w'`` at each node) and linear torsion elements (DOF ``θ``), the same elements and the same
    68-element mesh as the built-in modal model (:mod:`racketdyn.racket_modal.beam`).  The frame
    moves normal to the face by ``w(x) + θ(x)·y``: each section, the hoop included, is rigid in its
    own plane.
String bed
    A tensioned membrane on the head ellipse, attached to the frame.  Its displacement is the
    frame's motion carried across the bed plus Ritz functions that vanish on the edge::

        u(x, y) = w(x) + θ(x)·y + Σ_j q_j ψ_j(ξ, η),   ψ_j = (1 − ξ² − η²) ξ^a η^b,  a + b ≤ 3

    (ξ, η the coordinates scaled by the half-axes).  The membrane's mass (``strings.mass_kg``,
    else 4 % of the racket, paper section 2) is spread evenly and couples the Ritz coordinates
    to the frame through the mass matrix; its tension per unit width (``tension / spacing`` of
    the mains along x and of the crosses along y, as in the built-in model) stiffens the Ritz
    coordinates only.  The carried field's own gradient energy is left out: for rigid motion the
    strings' tension and the frame's compression balance exactly (a pre-stressed, self-
    equilibrated body has no geometric stiffness against rigid motion), and the cross terms
    with the Ritz functions vanish for a linear carried field (integrate by parts: ψ = 0 on the
    edge, ∇²u = 0).  The frame therefore takes part in the string-bed modes through inertia,
    as Cross measured (docs/references.md: string-bed modes 500–600 Hz, one test 615 Hz).
    The tension is the played bed's (``strings.bed_tension_n``: 30 % below the pull tension by
    default, Cross and Bower).  For the built-in racket the coupled membrane mode is then at
    586 Hz, in Cross's range, where it veers with the frame's 4-node bending (721 Hz; both
    modes share frame and bed, their strain energy 55/45 and 44/56 in strings/frame).  At the
    pull tension it sits at 806.8 Hz (725 Hz on a rigid frame; the built-in one-term estimate
    739 Hz), above the 4-node bending's 624.4 Hz.  (On the smooth frame the rig had before
    issue 22's sixth session: 600 and 677 Hz played, 772 and 629 Hz at the pull tension.)
Mass
    The frame's mass per unit length is the built-in model's,
    :func:`racketdyn.racket_modal.beam.mass_along`: the frame's shape (shaft, throat arms, hoop,
    handle and the head's top, :func:`~racketdyn.racket_modal.beam.frame_mass_per_length`) where
    its parts meet the frame's mass, balance and inertia with none negative, else the smooth
    distribution (:func:`~racketdyn.racket_modal.beam.beam_mass_per_length`); which one is
    ``metadata["mass_model"]`` (``"frame"`` or ``"smooth"``), as in the built-in model.  Its
    targets are the racket's mass, balance and inertia less the strings' share (integrated
    with the same quadrature that builds the membrane; no string mass is spread along the
    beam: the membrane carries it), so the assembled frame + strings have the racket's mass,
    balance, pitch inertia and roll inertia exactly (the roll inertia per unit length, ∝ the
    mass per length times the section's half-width squared, is put on the hoop as in the
    built-in model).  Point masses sit at their exact ``(x, y)`` on the frame, added after
    calibration so lead tape moves the frequencies.  On the frame's shape the paper racket's
    3-node bending is 355.7 Hz (325.4 Hz on the smooth frame), 5.3 Hz below its 2-node
    twisting: two peaks 2.2 of the rig records' 2.44 Hz lines apart, each 1.8 Hz wide (ζf).
Stiffness (calibration)
    EI ∝ the frame's tubes per section (two side by side in the throat arms and the hoop, one
    elsewhere; uniform on the smooth fallback) and uniform GJ, found by fixed-point iteration
    so that the free racket's first bending mode sits at ``racket.first_bending_hz`` and its
    first twisting mode at ``racket.twisting_hz`` *with the strings coupled in* (the built-in
    model's targets); ``metadata["bending_stiffness_nm2"]`` is one tube's EI.
Free support
    The racket on a soft sponge (paper, section 2).  Modelled as an ideal soft suspension: a
    stiffness ``M R Ω² Rᵀ M`` on the mass-orthonormal rigid-body modes ``R`` (heave, pitch,
    roll) only, giving them :data:`SUSPENSION_HZ` and :data:`SUSPENSION_DAMPING_RATIO` while the
    flexible modes stay exactly those of the free–free racket (a real 2–3 Hz sponge moves a
    120 Hz mode by well under 0.1 %).
Hand support
    :class:`racketdyn.hand.Hand`, the one hand of every model (the transient impact model's
    too): its mass (the part of the hand that moves with the handle at the racket's
    frequencies) spread evenly over the grip, with its roll inertia; distributed springs and
    dashpots from the grip to an arm of mass ``arm_mass_kg`` (one more DOF, ``dofs["arm"]``),
    in translation, and to the non-rotating arm in roll; the shoulder's soft spring holds the
    arm.  The hand–racket rigid-body modes lie below 60 Hz (default hand: 3.5–7 Hz, and the
    racket pitching on the palm against the arm at ≈ 54 Hz, ζ ≈ 9 %), and there is no
    clamped-handle cantilever mode (20–35 Hz in a vice, absent when hand-held: Kawazoe,
    section 2).  Defaults and their sources are on :class:`racketdyn.hand.Hand`.
Damping
    The racket's own damping is modal: :data:`FRAME_DAMPING_RATIO` (0.5 %, the built-in model's
    value; composite frames measured free are typically 0.3–1 %) on every flexible mode of the
    free racket, i.e. ``C_r = M Φ diag(2ζω) Φᵀ M``.  The support adds its dashpots.  The rig's
    modes are the real (undamped) modes of ``(K, M)`` with modal damping
    ``ζ_k = φ_kᵀ C φ_k / (2 ω_k)``: exact for the free racket (proportional damping) and for the
    hand the classical diagonal approximation (the hand's dashpots are not proportional).
    Against the complex modes of the full ``(M, C, K)`` with the default hand: the bending
    modes within 0.1 % in frequency and 0.3 % in damping, the twisting modes (more damped,
    closer together) within 2 % and 6 %.  The rig *is* this modal model: the hammer simulation
    uses exactly these modes, so the truth it writes is exact for the records it makes.

Shapes are mass-normalised (``φᵀ M φ = 1``, 1/√kg), normal to the face; the frame's DOFs come
first (``w, w'`` at each node, then ``θ`` at each node), then the Ritz coordinates.
"""

from __future__ import annotations

import hashlib
import logging
import threading
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Literal, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import eigh

from racketdyn.errors import InputError, one_of, require_positive
from racketdyn.hand import Hand
from racketdyn.modal.model import ModalModel
from racketdyn.racket import Racket, as_locations
from racketdyn.racket_modal.beam import (
    DEFAULT_DAMPING_RATIO,
    N_ELEMENTS,
    STRING_MASS_FRACTION,
    _bending_matrices,
    _section_radius,
    _torsion_matrices,
    mass_along,
)
from racketdyn.racket_modal.grip import frame_rows, hand_matrices
from racketdyn.racket_modal.shapes import membrane_names, sign_changes
from racketdyn.rig.patch import BallPatch

__all__ = [
    "FRAME_DAMPING_RATIO",
    "RIG_SUPPORTS",
    "SUSPENSION_DAMPING_RATIO",
    "SUSPENSION_HZ",
    "HandModel",
    "RigModel",
    "RigSupport",
    "rig_model",
]

logger = logging.getLogger(__name__)

RigSupport = Literal["free", "hand"]
"""Support of the racket on the rig: ``free`` (soft sponge) or ``hand`` (held by a hand)."""
RIG_SUPPORTS: tuple[str, ...] = get_args(RigSupport)

FRAME_DAMPING_RATIO = DEFAULT_DAMPING_RATIO
"""Damping ratio of every flexible mode of the free racket (the built-in model's 0.5 %)."""
SUSPENSION_HZ = (3.0, 2.0, 2.5)
"""Frequencies of the free racket's heave, pitch and roll on the sponge, Hz (assumed)."""
SUSPENSION_DAMPING_RATIO = 0.10
"""Damping ratio of the suspension modes (a foam sponge is lossy; assumed)."""
FRAME_WIDTH_M = 0.025
"""How far past the string bed's half-width a location may lie and still be on the frame, m."""
MEMBRANE_DEGREE = 3
"""Highest degree of the polynomial multiplying ``1 − ρ²`` in the Ritz functions (10 of them)."""
MAX_FREQUENCY_HZ = 10_000.0
"""Modes above this are left out of the rig (well above any hammer test's band), Hz."""

_GAUSS_X = np.polynomial.legendre.leggauss(8)
_CALIBRATION_TOLERANCE = 1e-7  # eigenvalue noise of the stiff Hermite mesh is ~1e-8


HandModel = Hand
"""The rig's hand: :class:`racketdyn.hand.Hand`, the one hand (the name kept for old code)."""


@dataclass(frozen=True, eq=False)
class RigModel:
    """The rig's structure: matrices, DOF map and modes of a racket on a support.

    Build it with :func:`rig_model`.  Displacement normal to the face at ``(x, y)`` is
    ``displacement_rows(locations) @ q`` for a DOF vector ``q``: ``w(x) + θ(x)·y`` on the
    frame, plus the Ritz functions on the string bed.

    Parameters
    ----------
    racket : Racket
        The racket modelled.
    support : {"free", "hand"}
        Its support.
    hand : Hand or None
        The hand (``support="hand"`` only).
    nodes_x : ndarray, shape (n_nodes,)
        Beam nodes along the long axis, m.
    membrane_powers : tuple of (int, int)
        Powers ``(a, b)`` of the Ritz functions ``(1 − ξ² − η²) ξ^a η^b``.
    mass, stiffness, damping : ndarray, shape (n_dof, n_dof)
        Assembled M (kg, kg·m, kg·m²), K (N/m …) and C (N·s/m …) with the support included.
    frequency : ndarray, shape (n_modes,)
        Natural frequencies of the modes kept, Hz (ascending).
    damping_ratio : ndarray, shape (n_modes,)
        Modal damping ratios ``φᵀCφ / (2ω)``.
    modes : ndarray, shape (n_dof, n_modes)
        Mass-normalised mode vectors, 1/√kg.
    names, kinds : tuple of str
        Mode names (``"2-node bending"`` …) and kinds (``bending``, ``twisting``,
        ``string-bed``, ``other`` for the support's rigid-body modes).
    metadata : dict
        Calibrated stiffnesses, string mass, the frame's mass model (``mass_model``: ``"frame"``
        or ``"smooth"``, as the built-in model's), support parameters.
    patch : BallPatch or None
        Where a ball fixed on the strings presses the membrane (its own Ritz function,
        ``dofs["patch"]``: :mod:`racketdyn.rig.patch`); None without a ball.
    """

    racket: Racket
    support: str
    hand: Hand | None
    nodes_x: NDArray[np.float64]
    membrane_powers: tuple[tuple[int, int], ...]
    mass: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    frequency: NDArray[np.float64]
    damping_ratio: NDArray[np.float64]
    modes: NDArray[np.float64]
    names: tuple[str, ...]
    kinds: tuple[str, ...]
    metadata: dict[str, Any] = field(default_factory=dict)
    patch: BallPatch | None = None

    @property
    def n_dof(self) -> int:
        """Number of degrees of freedom."""
        return int(self.mass.shape[0])

    @property
    def n_modes(self) -> int:
        """Number of modes kept."""
        return int(self.frequency.size)

    @property
    def omega(self) -> NDArray[np.float64]:
        """Natural angular frequencies, rad/s."""
        return np.asarray(2 * np.pi * self.frequency)

    @property
    def dofs(self) -> dict[str, slice]:
        """Where each kind of DOF sits: ``bending`` (w, w' per node), ``twist``, ``membrane``,
        ``arm`` (the hand's arm: empty on the sponge), ``patch`` (the membrane's dip under a
        ball's patch) and ``ball`` (both empty unless a ball is fixed on the strings:
        :mod:`racketdyn.rig.ball`)."""
        n = self.nodes_x.size
        end = 3 * n + len(self.membrane_powers)
        arm = end + (0 if self.hand is None else 1)
        patch = arm + (0 if self.patch is None else 1)
        return {
            "bending": slice(0, 2 * n),
            "twist": slice(2 * n, 3 * n),
            "membrane": slice(3 * n, end),
            "arm": slice(end, arm),
            "patch": slice(arm, patch),
            "ball": slice(patch, self.n_dof),
        }

    def on_string_bed(self, locations: ArrayLike) -> NDArray[np.bool_]:
        """True where a location lies inside the string bed (the frame's edge excluded)."""
        return np.asarray(self.racket.head.normalised_radius(locations) < 1.0 - 1e-9)

    def displacement_rows(self, locations: ArrayLike) -> NDArray[np.float64]:
        """Rows mapping the DOFs to the normal displacement at each location, ``(n, n_dof)``.

        ``w(x) + θ(x)·y`` everywhere, plus ``Σ q_j ψ_j`` (and a ball's patch function, if
        any) inside the string bed.  Raises InputError for a location off the racket.
        """
        xy = as_locations(locations)
        racket = self.racket
        reach = racket.head.half_width_m + abs(racket.head.centre_y_m) + FRAME_WIDTH_M
        off = np.flatnonzero(
            (xy[:, 0] < -1e-9) | (xy[:, 0] > racket.length_m + 1e-9) | (np.abs(xy[:, 1]) > reach)
        )
        if off.size:
            i = int(off[0])
            raise InputError(
                f"location {i + 1} at x={xy[i, 0]:.4f} m, y={xy[i, 1]:.4f} m is off the racket "
                f"(0 ≤ x ≤ {racket.length_m} m, |y| ≤ {reach:.3f} m)"
            )
        rows = np.zeros((xy.shape[0], self.n_dof))
        rows[:, : 3 * self.nodes_x.size] = frame_rows(self.nodes_x, xy[:, 0], xy[:, 1])
        bed = self.on_string_bed(xy)
        if np.any(bed):
            psi, _, _ = _membrane_functions(racket, self.membrane_powers, xy[bed])
            membrane = self.dofs["membrane"]
            rows[np.ix_(bed, np.arange(membrane.start, membrane.stop))] = psi
        if self.patch is not None:
            rows[:, self.dofs["patch"].start] = self.patch.values(racket.head, xy)
        return rows

    def mode_shapes_at(self, locations: ArrayLike) -> NDArray[np.float64]:
        """Mass-normalised mode shapes at the locations, ``(n, n_modes)``, 1/√kg."""
        return np.asarray(self.displacement_rows(locations) @ self.modes)

    def modal_truth(
        self, locations: ArrayLike, max_frequency_hz: float | None = None
    ) -> ModalModel:
        """The rig's modes at the locations, as a :class:`ModalModel` (the truth for checks).

        Real modes with modal damping (see the module docstring); the support's rigid-body
        modes are included with kind ``other``.

        Parameters
        ----------
        locations : array_like, shape (n, 2)
            Where to give the shapes, (x, y) in m (3 or more, all different).
        max_frequency_hz : float or None
            Keep only modes up to this frequency, Hz; None keeps every mode of the rig.
        """
        keep = np.ones(self.n_modes, dtype=bool)
        if max_frequency_hz is not None:
            require_positive("max_frequency_hz", max_frequency_hz)
            keep = self.frequency <= max_frequency_hz
        xy = as_locations(locations)
        return ModalModel(
            frequency=self.frequency[keep],
            damping_ratio=self.damping_ratio[keep],
            locations=xy,
            mode_shapes=self.mode_shapes_at(xy)[:, keep],
            names=tuple(n for n, k in zip(self.names, keep, strict=True) if k),
            kinds=tuple(n for n, k in zip(self.kinds, keep, strict=True) if k),
            support=self.support,
            source=f"virtual rig model of {self.racket.name} ({self.support})",
            metadata={
                "damping": "real modes with modal damping phi^T C phi / (2 omega)",
                **{k: v for k, v in self.metadata.items() if k != "strain_energy_shares"},
            },
        )

    def frf(
        self,
        response: ArrayLike,
        excitation: ArrayLike,
        frequency: ArrayLike,
        frf_type: str = "accelerance",
    ) -> NDArray[np.complex128]:
        """The rig's FRFs by modal superposition, shaped ``(n_response, n_excitation, n_freq)``.

        ``H_ij(ω) = Σ_k φ_ik φ_jk (iω)^p / (ω_k² − ω² + 2iζ_k ω_k ω)`` with p = 0, 1, 2 for
        receptance (m/N), mobility (m/(N·s)) and accelerance (m/(N·s²)).

        Parameters
        ----------
        response, excitation : array_like, shape (n, 2)
            Response and force locations, m.
        frequency : array_like
            Frequencies, Hz.
        frf_type : {"accelerance", "mobility", "receptance"}
            What the FRF relates.
        """
        power = {"receptance": 0, "mobility": 1, "accelerance": 2}
        one_of("frf_type", frf_type, power)
        omega = 2 * np.pi * np.atleast_1d(np.asarray(frequency, dtype=float))
        phi_i = self.mode_shapes_at(response)
        phi_j = self.mode_shapes_at(excitation)
        wk, zk = self.omega, self.damping_ratio
        modal = 1.0 / (wk[:, None] ** 2 - omega**2 + 2j * zk[:, None] * wk[:, None] * omega)
        values = np.einsum("ik,jk,kf->ijf", phi_i, phi_j, modal)
        return np.asarray(values * (1j * omega) ** power[frf_type])


def rig_model(
    racket: Racket,
    support: RigSupport,
    hand: Hand | None = None,
    *,
    frame_damping_ratio: float = FRAME_DAMPING_RATIO,
    max_frequency_hz: float = MAX_FREQUENCY_HZ,
) -> RigModel:
    """Build the rig's model of a racket on a support (see the module docstring).

    Steps: string bed, frame and matrices; EI and GJ calibrated on the bare racket, then the
    point masses; the racket's modal damping; the support; the real modes, signed and named.

    Parameters
    ----------
    racket : Racket
        Mass properties, head, strings, point masses and the two frequency targets
        (``first_bending_hz``, ``twisting_hz``: the free racket's, strings included).
    support : {"free", "hand"}
        ``free``: on a soft sponge; ``hand``: held by ``hand``.
    hand : Hand or None
        The hand for ``support="hand"`` (None: the default :class:`racketdyn.hand.Hand`); must
        be None for ``free``.
    frame_damping_ratio : float
        Modal damping ratio of the free racket's flexible modes.
    max_frequency_hz : float
        Modes above this frequency are left out, Hz.

    Returns
    -------
    RigModel
        Matrices, DOF map and modes (ascending frequency).
    """
    hand = _checked_hand(support, hand, frame_damping_ratio, max_frequency_hz)
    mesh = _Mesh(np.linspace(0.0, racket.length_m, N_ELEMENTS + 1))
    bed = _string_bed(racket, mesh)
    parts = _racket_matrices(racket, mesh, bed)

    # --- calibration on the bare racket (strings in, point masses out), held on the sponge --
    k_suspension, _ = _suspension(parts.mass, mesh.x, mesh.n_dof)
    ei, gj = _calibrate(
        racket, parts.mass, parts.k_bend, parts.k_twist, parts.k_strings + k_suspension
    )
    stiffness = ei * parts.k_bend + gj * parts.k_twist + parts.k_strings
    mass = _with_point_masses(racket, parts.mass, mesh)

    # --- the free racket's own damping (modal) and the support ------------------------------
    suspension = _suspension(mass, mesh.x, mesh.n_dof)
    c_racket = _racket_damping(mass, stiffness, suspension[0], frame_damping_ratio)
    held = _on_sponge(suspension, mass) if hand is None else _in_hand(hand, racket, mesh)
    metadata: dict[str, Any] = {
        "elements": N_ELEMENTS,
        "membrane_functions": len(mesh.powers),
        "bending_stiffness_nm2": float(ei),
        "torsional_stiffness_nm2_per_rad": float(gj),
        "string_mass_kg": bed.mass_kg,
        "mass_model": "smooth" if parts.tubes is None else "frame",
        "string_tension_per_width_n_per_m": [float(t) for t in bed.tension_per_width],
        "frame_damping_ratio": float(frame_damping_ratio),
        "max_frequency_hz": float(max_frequency_hz),
        **held.metadata,
    }
    # the support's own DOFs (the hand's arm) after the racket's
    extra = held.mass.shape[0] - mesh.n_dof
    mass, stiffness, c_racket, k_bend, k_twist, k_strings = (
        np.pad(matrix, (0, extra))
        for matrix in (mass, stiffness, c_racket, parts.k_bend, parts.k_twist, parts.k_strings)
    )
    mass_total = mass + held.mass
    stiffness_total = stiffness + held.stiffness
    damping_total = c_racket + held.damping
    omega2, vectors, zeta = _real_modes(
        (mass_total, stiffness_total, damping_total), max_frequency_hz, support
    )
    vectors = _signed_modes(vectors, racket, mesh)
    shares = _strain_energy(vectors, (ei * k_bend, gj * k_twist, k_strings, held.stiffness))
    names, kinds = _name_modes(shares, _ModeShapes(vectors, mesh, racket, bed), held.label)
    metadata["strain_energy_shares"] = {
        "order": ["bending", "twisting", "string-bed", held.label],
        "values": (shares / omega2).T.round(6).tolist(),
    }
    omega, x, powers = np.sqrt(omega2), mesh.x, mesh.powers
    logger.debug("rig model (%s): %d modes up to %.0f Hz", support, omega.size, max_frequency_hz)
    return RigModel(
        racket=racket,
        support=support,
        hand=hand,
        nodes_x=x,
        membrane_powers=powers,
        mass=mass_total,
        stiffness=stiffness_total,
        damping=damping_total,
        frequency=omega / (2 * np.pi),
        damping_ratio=zeta,
        modes=vectors,
        names=names,
        kinds=kinds,
        metadata=metadata,
    )


# --- the steps of rig_model ----------------------------------------------------------------

_REMEMBERED: OrderedDict[bytes, Any] = OrderedDict()
_REMEMBERED_LOCK = threading.Lock()
_REMEMBER_AT_MOST = 16
"""The bare racket's calibration and damping, and the supported racket's eigenproblem, of the
last few rackets: every support of a racket (``rig --support free,hand``), and every rig of one
racket in a process, start from the same bare racket, and a rig of the same racket on the same
support solves the same eigenproblem; these solves are most of a model's build."""


def _remembered(kind: str, args: tuple[Any, ...], compute: Callable[[], Any]) -> Any:
    """``compute()``, or what it returned before for inputs of the same content.

    The key is a hash of ``kind`` and every argument's bytes (arrays with their dtype and
    shape, numbers by ``repr``): the same matrices give the same result, whatever built them
    (a frame patched in a test, another racket of equal parts).  Treat the result as read-only.
    """
    digest = hashlib.blake2b(kind.encode(), digest_size=20)
    for arg in args:
        if isinstance(arg, np.ndarray):
            digest.update(f"{arg.dtype.str}{arg.shape}".encode())
            digest.update(np.ascontiguousarray(arg).data)
        else:
            digest.update(repr(arg).encode())
    key = digest.digest()
    with _REMEMBERED_LOCK:
        if key in _REMEMBERED:
            _REMEMBERED.move_to_end(key)
            return _REMEMBERED[key]
    value = compute()
    with _REMEMBERED_LOCK:
        _REMEMBERED[key] = value
        while len(_REMEMBERED) > _REMEMBER_AT_MOST:
            _REMEMBERED.popitem(last=False)
    return value


def _checked_hand(
    support: str, hand: Hand | None, frame_damping_ratio: float, max_frequency_hz: float
) -> Hand | None:
    """The hand of the support (the default one for ``hand``, None for ``free``), the other
    inputs checked."""
    one_of("support", support, RIG_SUPPORTS)
    if support == "free" and hand is not None:
        raise InputError("a hand is given but support is 'free'; use support='hand'")
    if support == "hand" and hand is None:
        hand = Hand()
    if not 0.0 <= frame_damping_ratio < 0.2:
        raise InputError(f"frame_damping_ratio must lie in [0, 0.2) (got {frame_damping_ratio!r})")
    require_positive("max_frequency_hz", max_frequency_hz)
    return hand


@dataclass(frozen=True)
class _Mesh:
    """The racket's DOFs: beam nodes along the long axis (``w, w'`` then ``θ`` at each node),
    then the Ritz coordinates of the membrane's functions (powers ``(a, b)``)."""

    x: NDArray[np.float64]
    powers: tuple[tuple[int, int], ...] = tuple(
        (a, d - a) for d in range(MEMBRANE_DEGREE + 1) for a in range(d, -1, -1)
    )

    @property
    def n_frame(self) -> int:
        """The frame's DOFs (three per node)."""
        return 3 * self.x.size

    @property
    def n_dof(self) -> int:
        """The racket's DOFs: the frame's and the membrane's."""
        return self.n_frame + len(self.powers)


@dataclass(frozen=True)
class _StringBed:
    """The string bed on the mesh: its mass (kg) and mass matrix (every DOF), the membrane's
    stiffness (its Ritz coordinates), tension per width along x and y (N/m), and the mass
    quadrature's points (m) and weights (kg)."""

    mass_kg: float
    mass: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    tension_per_width: tuple[float, float]
    qx: NDArray[np.float64]
    qy: NDArray[np.float64]
    weight: NDArray[np.float64]


def _string_bed(racket: Racket, mesh: _Mesh) -> _StringBed:
    """The string bed: quadrature, mass and membrane stiffness."""
    head, strings, x = racket.head, racket.strings, mesh.x
    string_mass = float(strings.mass_kg or STRING_MASS_FRACTION * racket.mass_kg)
    qx, qy, qw = _bed_quadrature(racket, x)
    sigma = string_mass / qw.sum()  # areal density, the quadrature's mass exactly m_s
    weight = sigma * qw
    bed_rows = np.zeros((qx.size, mesh.n_dof))
    bed_rows[:, : mesh.n_frame] = frame_rows(x, qx, qy)
    psi, dpsi_x, dpsi_y = _membrane_functions(racket, mesh.powers, np.column_stack([qx, qy]))
    bed_rows[:, mesh.n_frame :] = psi
    bed_mass = bed_rows.T @ (weight[:, None] * bed_rows)
    spacing_mains, spacing_crosses = strings.spacing_m(head)
    tension_x = strings.bed_tension_n / spacing_mains
    tension_y = strings.bed_tension_n / spacing_crosses
    k_membrane = tension_x * dpsi_x.T @ (qw[:, None] * dpsi_x) + tension_y * dpsi_y.T @ (
        qw[:, None] * dpsi_y
    )
    return _StringBed(string_mass, bed_mass, k_membrane, (tension_x, tension_y), qx, qy, weight)


@dataclass(frozen=True)
class _RacketMatrices:
    """The bare racket's mass (frame and string bed), unit-EI bending and unit-GJ torsion
    stiffness, the strings' stiffness (all on the racket's DOFs) and the frame's tubes per
    section (None: the smooth mass model)."""

    mass: NDArray[np.float64]
    k_bend: NDArray[np.float64]
    k_twist: NDArray[np.float64]
    k_strings: NDArray[np.float64]
    tubes: NDArray[np.float64] | None


def _racket_matrices(racket: Racket, mesh: _Mesh, bed: _StringBed) -> _RacketMatrices:
    """The frame's mass per length for the racket less the strings, and the racket's matrices."""
    head, x, weight = racket.head, mesh.x, bed.weight
    frame_mass = racket.mass_kg - bed.mass_kg
    first = racket.mass_kg * racket.balance_m - float(weight @ bed.qx)
    second = (
        racket.inertia_cg_kgm2 + racket.mass_kg * racket.balance_m**2 - float(weight @ bed.qx**2)
    )
    frame_balance = first / frame_mass
    frame_inertia = second - frame_mass * frame_balance**2
    # the built-in model's frame (its shape, else the smooth fallback); the strings are the
    # membrane's, so none is spread along the beam here
    density, tubes = mass_along(
        racket.length_m, head, (frame_mass, frame_balance, frame_inertia), 0.0
    )
    mid, step = 0.5 * (x[:-1] + x[1:]), np.diff(x)
    frame_roll = racket.roll_inertia_kgm2 - weight @ bed.qy**2
    if frame_roll <= 0:
        raise InputError(
            f"racket: roll inertia {racket.roll_inertia_kgm2} kg·m² is less than the string "
            f"bed's own ({weight @ bed.qy**2:.3g} kg·m²); check roll_inertia / twistweight"
        )
    roll_density = density * _section_radius(head, mid) ** 2
    roll_density *= frame_roll / np.sum(roll_density * step)
    kb_unit, mb = _bending_matrices(x, density, tubes)
    kt_unit, mt = _torsion_matrices(x, roll_density)

    n_nodes, n_dof = x.size, mesh.n_dof
    bending, twist = slice(0, 2 * n_nodes), slice(2 * n_nodes, mesh.n_frame)
    membrane = slice(mesh.n_frame, n_dof)
    mass = bed.mass.copy()
    mass[bending, bending] += mb
    mass[twist, twist] += mt
    k_bend = np.zeros((n_dof, n_dof))
    k_bend[bending, bending] = kb_unit
    k_twist = np.zeros((n_dof, n_dof))
    k_twist[twist, twist] = kt_unit
    k_strings = np.zeros((n_dof, n_dof))
    k_strings[membrane, membrane] = bed.stiffness
    return _RacketMatrices(mass, k_bend, k_twist, k_strings, tubes)


def _with_point_masses(
    racket: Racket, mass: NDArray[np.float64], mesh: _Mesh
) -> NDArray[np.float64]:
    """The mass matrix with the racket's point masses at their exact ``(x, y)`` on the frame."""
    mass = mass.copy()
    for p in racket.point_masses:
        row = np.zeros(mesh.n_dof)
        row[: mesh.n_frame] = frame_rows(mesh.x, np.array([p.x_m]), np.array([p.y_m]))[0]
        mass += p.mass_kg * np.outer(row, row)
    return mass


def _racket_damping(
    mass: NDArray[np.float64],
    stiffness: NDArray[np.float64],
    k_suspension: NDArray[np.float64],
    damping_ratio: float,
) -> NDArray[np.float64]:
    """The free racket's own damping ``C_r = M Φ diag(2ζω) Φᵀ M`` on its flexible modes
    (remembered for the same matrices: a copy of the first computation's)."""

    def computed() -> NDArray[np.float64]:
        free_omega2, free_vectors = eigh(stiffness + k_suspension, mass)
        flexible = _support_share(free_vectors, k_suspension, free_omega2) < 0.5
        phi_f, omega_f = free_vectors[:, flexible], np.sqrt(free_omega2[flexible])
        mphi = mass @ phi_f
        return np.asarray(mphi @ np.diag(2 * damping_ratio * omega_f) @ mphi.T)

    args = (mass, stiffness, k_suspension, damping_ratio)
    return np.array(_remembered("damping", args, computed))


@dataclass(frozen=True)
class _Held:
    """The support's name in the mode names, its mass, stiffness and damping (the racket's DOFs
    and its own after them) and its entries of the model's metadata."""

    label: str
    mass: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    metadata: dict[str, Any]


def _on_sponge(
    suspension: tuple[NDArray[np.float64], NDArray[np.float64]], mass: NDArray[np.float64]
) -> _Held:
    """The free support: the suspension's stiffness and damping, no mass of its own."""
    k_suspension, c_suspension = suspension
    metadata = {
        "suspension_hz": list(SUSPENSION_HZ),
        "suspension_damping_ratio": SUSPENSION_DAMPING_RATIO,
    }
    return _Held("suspension", np.zeros_like(mass), k_suspension, c_suspension, metadata)


def _in_hand(hand: Hand, racket: Racket, mesh: _Mesh) -> _Held:
    """The hand support: the hand's and arm's matrices (the hand checked against the racket)."""
    head = racket.head
    if hand.grip_end_m >= head.throat_x_m or hand.grip_end_m > racket.length_m:
        raise InputError(
            f"hand.grip_end_m ({hand.grip_end_m} m) must lie on the handle, below the "
            f"string bed's throat end ({head.throat_x_m:.3f} m)"
        )
    if hand.shoulder_stiffness_n_per_m <= 0:
        raise InputError(
            "hand.shoulder_stiffness_n_per_m must be positive on the rig: without the "
            "shoulder the held racket floats away on its arm (a mode of 0 Hz)"
        )
    m_support, k_support, c_support = hand_matrices(hand, mesh.x, mesh.n_dof)
    metadata = {"hand": {k: float(v) for k, v in vars(hand).items()}}
    return _Held("hand", m_support, k_support, c_support, metadata)


def _real_modes(
    matrices: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
    max_frequency_hz: float,
    support: str,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """``ω²``, the mass-normalised vectors and the modal damping ratios ``φᵀCφ / (2ω)`` of the
    real modes of ``(M, K, C)`` up to ``max_frequency_hz`` (the eigenproblem's solution
    remembered for the same matrices)."""
    mass, stiffness, damping = matrices
    omega2, vectors = _remembered("modes", (stiffness, mass), lambda: eigh(stiffness, mass))
    keep = omega2 <= (2 * np.pi * max_frequency_hz) ** 2
    omega2, vectors = omega2[keep], vectors[:, keep]
    if np.any(omega2 <= 0):
        raise InputError(f"rig model ({support}): a mode has no stiffness; check the support")
    omega = np.sqrt(omega2)
    zeta = np.einsum("ik,ij,jk->k", vectors, damping, vectors) / (2 * omega)
    if np.any(zeta >= 1.0):
        k = int(np.argmax(zeta))
        raise InputError(
            f"rig model ({support}): the mode at {omega[k] / (2 * np.pi):.2f} Hz is over-damped "
            f"(damping ratio {zeta[k]:.2f}); lower the support's damping or raise its stiffness"
        )
    return omega2, vectors, zeta


def _signed_modes(vectors: NDArray[np.float64], racket: Racket, mesh: _Mesh) -> NDArray[np.float64]:
    """The sign convention: the largest displacement over the racket (sampled) positive."""
    x = mesh.x
    probe = frame_rows(
        x, np.concatenate([x, x]), np.repeat([0.0, racket.head.half_width_m], x.size)
    )
    sampled = np.vstack(
        [
            probe @ vectors[: mesh.n_frame],
            _bed_centre_row(racket, mesh.powers) @ vectors[: mesh.n_dof],
        ]
    )
    largest = sampled[np.argmax(np.abs(sampled), axis=0), np.arange(vectors.shape[1])]
    return np.asarray(vectors * np.where(largest < 0, -1.0, 1.0))


def _strain_energy(
    vectors: NDArray[np.float64], stiffnesses: tuple[NDArray[np.float64], ...]
) -> NDArray[np.float64]:
    """``φᵀKφ`` of each mode in each stiffness (bending, twisting, strings, support), (4, n)."""
    return np.vstack([np.einsum("ik,ij,jk->k", vectors, k, vectors) for k in stiffnesses])


# --- pieces --------------------------------------------------------------------------------


def _membrane_functions(
    racket: Racket, powers: tuple[tuple[int, int], ...], xy: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Ritz functions ψ and their x and y derivatives at the locations, each ``(n, n_psi)``."""
    head = racket.head
    a, b = head.half_length_m, head.half_width_m
    xi = (xy[:, 0] - head.centre_x_m) / a
    eta = (xy[:, 1] - head.centre_y_m) / b
    bubble = 1 - xi**2 - eta**2
    psi, dx, dy = [], [], []
    for p, q in powers:
        mono = xi**p * eta**q
        dmono_xi = p * xi ** max(p - 1, 0) * eta**q
        dmono_eta = q * xi**p * eta ** max(q - 1, 0)
        psi.append(bubble * mono)
        dx.append((bubble * dmono_xi - 2 * xi * mono) / a)
        dy.append((bubble * dmono_eta - 2 * eta * mono) / b)
    return np.column_stack(psi), np.column_stack(dx), np.column_stack(dy)


def _bed_centre_row(racket: Racket, powers: tuple[tuple[int, int], ...]) -> NDArray[np.float64]:
    """Row giving the displacement at the string bed's centre (frame part excluded)."""
    x = np.linspace(0.0, racket.length_m, N_ELEMENTS + 1)
    centre = np.array([[racket.head.centre_x_m, racket.head.centre_y_m]])
    row = np.zeros((1, 3 * x.size + len(powers)))
    row[:, : 3 * x.size] = frame_rows(x, centre[:, 0], centre[:, 1])
    row[:, 3 * x.size :] = _membrane_functions(racket, powers, centre)[0]
    return row


def _bed_quadrature(
    racket: Racket, x: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Quadrature points (x, y) and area weights (m²) over the string-bed ellipse.

    ``ξ = sin s`` removes the square-root ends of the chord; s is cut at the beam nodes so each
    piece sees one element's smooth shape functions (Gauss–Legendre, 8 points), and each chord
    is integrated with 8 Gauss points (exact for the polynomial Ritz products).
    """
    head = racket.head
    a, b = head.half_length_m, head.half_width_m
    cuts = np.arcsin(np.clip((x - head.centre_x_m) / a, -1.0, 1.0))
    edges = np.unique(np.concatenate([[-np.pi / 2, np.pi / 2], cuts]))
    gx, gw = _GAUSS_X
    s = (0.5 * (edges[:-1, None] + edges[1:, None]) + 0.5 * np.diff(edges)[:, None] * gx).ravel()
    ws = (0.5 * np.diff(edges)[:, None] * gw).ravel()
    t, wt = _GAUSS_X
    xs = head.centre_x_m + a * np.sin(s)
    chord = np.cos(s)
    qx = np.repeat(xs, t.size)
    qy = head.centre_y_m + b * np.outer(chord, t).ravel()
    qw = (a * b * np.outer(ws * chord**2, wt)).ravel()
    return qx, qy, qw


def _rigid_modes(mass: NDArray[np.float64], x: NDArray[np.float64], n_dof: int) -> NDArray[Any]:
    """Mass-orthonormal rigid-body vectors: heave, pitch (about the centre of mass), roll."""
    n = x.size
    rigid = np.zeros((n_dof, 3))
    rigid[0 : 2 * n : 2, 0] = 1.0
    rigid[0 : 2 * n : 2, 1] = x
    rigid[1 : 2 * n : 2, 1] = 1.0
    rigid[2 * n : 3 * n, 2] = 1.0
    for k in range(3):  # Gram–Schmidt in the mass inner product, in that order
        for j in range(k):
            rigid[:, k] -= (rigid[:, j] @ mass @ rigid[:, k]) * rigid[:, j]
        rigid[:, k] /= np.sqrt(rigid[:, k] @ mass @ rigid[:, k])
    return rigid


def _suspension(
    mass: NDArray[np.float64], x: NDArray[np.float64], n_dof: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Stiffness and damping of the ideal soft suspension (rigid-body modes only)."""
    rigid = _rigid_modes(mass, x, n_dof)
    omega = 2 * np.pi * np.asarray(SUSPENSION_HZ)
    mr = mass @ rigid
    return (
        mr @ np.diag(omega**2) @ mr.T,
        mr @ np.diag(2 * SUSPENSION_DAMPING_RATIO * omega) @ mr.T,
    )


def _support_share(
    vectors: NDArray[np.float64], k_support: NDArray[np.float64], omega2: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Share of each mode's strain energy held by the support."""
    return np.asarray(np.einsum("ik,ij,jk->k", vectors, k_support, vectors) / omega2)


def _calibrate(
    racket: Racket,
    mass: NDArray[np.float64],
    k_bend: NDArray[np.float64],
    k_twist: NDArray[np.float64],
    k_fixed: NDArray[np.float64],
) -> tuple[float, float]:
    """EI and GJ putting the free racket's first bending and twisting modes on their targets
    (remembered for the same targets and matrices)."""

    def search() -> tuple[float, float]:
        target_b = 2 * np.pi * racket.first_bending_hz
        target_t = 2 * np.pi * racket.twisting_hz
        ei, gj = 100.0, 100.0
        n_search = 12  # the lowest modes: 3 suspension + 2-node bending + twisting among them
        for _ in range(60):
            stiffness = ei * k_bend + gj * k_twist + k_fixed
            omega2, vectors = eigh(stiffness, mass, subset_by_index=[0, n_search - 1])
            energy_b = np.einsum("ik,ij,jk->k", vectors, ei * k_bend, vectors) / omega2
            energy_t = np.einsum("ik,ij,jk->k", vectors, gj * k_twist, vectors) / omega2
            bend = np.flatnonzero(energy_b > 0.5)
            tors = np.flatnonzero(energy_t > 0.5)
            if bend.size == 0 or tors.size == 0:
                ei, gj = ei * 4.0 if bend.size == 0 else ei, gj * 4.0 if tors.size == 0 else gj
                continue
            ratio_b = target_b**2 / omega2[bend[0]]
            ratio_t = target_t**2 / omega2[tors[0]]
            ei, gj = ei * ratio_b, gj * ratio_t
            if (
                abs(ratio_b - 1) < _CALIBRATION_TOLERANCE
                and abs(ratio_t - 1) < _CALIBRATION_TOLERANCE
            ):
                return float(ei), float(gj)
        raise InputError(  # pragma: no cover - the fixed point converges for any physical racket
            f"rig model of {racket.name}: the stiffness calibration did not converge"
        )

    args = (racket.first_bending_hz, racket.twisting_hz, mass, k_bend, k_twist, k_fixed)
    ei, gj = _remembered("calibrate", args, search)
    return ei, gj


@dataclass(frozen=True)
class _ModeShapes:
    """The rig's mode vectors with what reads their shapes: the mesh, the racket, the bed."""

    vectors: NDArray[np.float64]
    mesh: _Mesh
    racket: Racket
    bed: _StringBed

    def bending_nodes(self, k: int) -> int:
        """Sign changes of ``w`` along the beam, butt to tip: n-node bending."""
        return sign_changes(self.vectors[0 : 2 * self.mesh.x.size : 2, k])

    def twisting_nodes(self, k: int) -> int:
        """Sign changes of ``θ`` along the beam, plus the long axis: n-node twisting."""
        n = self.mesh.x.size
        return sign_changes(self.vectors[2 * n : 3 * n, k]) + 1

    def membrane_names(self) -> list[str | None]:
        """Each mode's name from the bed's own mode its Ritz part (the strings' own motion)
        matches (:func:`racketdyn.racket_modal.shapes.membrane_names`), read on a lattice
        over the bed."""
        head = self.racket.head
        grid = np.linspace(-0.95, 0.95, 39)
        gx, gy = np.meshgrid(grid, grid)
        inside = gx**2 + gy**2 < 0.95**2
        xy = np.column_stack(
            [
                head.centre_x_m + head.half_length_m * gx[inside],
                head.centre_y_m + head.half_width_m * gy[inside],
            ]
        )
        psi = _membrane_functions(self.racket, self.mesh.powers, xy)[0]
        own = psi @ self.vectors[self.mesh.n_frame : self.mesh.n_dof]
        tension_x, tension_y = self.bed.tension_per_width
        ratio = (tension_y / head.half_width_m**2) / (tension_x / head.half_length_m**2)
        return membrane_names(own, xy, head, ratio)[0]


def _name_modes(
    shares: NDArray[np.float64], shapes: _ModeShapes, support_label: str
) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Names and kinds: the kind from each mode's largest strain energy (bending, twist,
    strings, support), the name from its shape — node counts along the beam, the bed's own
    mode its strings' own motion matches — as identification names them
    (:func:`racketdyn.racket_modal.shapes.classify_modes`).  Of two string-bed modes of one
    bed shape (a veering pair: the trial racket's 917.7 and 993.0 Hz share the (1, 0)
    membrane and the 4-node bending, their strain energy 51 and 55 % in the strings) the one
    with more of its strain energy in the strings is the membrane, the other the frame's
    mode it veers with.  Likewise of two frame modes of one node count (the trial racket's
    1484.7 and 1512.1 Hz, the 6-node twisting and the (1, 1) membrane mixed, 51 and 50 % of
    their strain energy in the twist) the one with more of it in the frame keeps the count and
    the other is the membrane its strings match, where no other mode has that name."""
    dominant = np.argmax(shares, axis=0)
    membrane = shapes.membrane_names()
    for name in {m for m, d in zip(membrane, dominant, strict=True) if d == 2 and m}:
        sharing = [k for k, d in enumerate(dominant) if d == 2 and membrane[k] == name]
        kept = max(sharing, key=lambda k: shares[2, k] / shares[:, k].sum())
        for k in sharing:
            if k != kept:
                dominant[k] = int(np.argmax(shares[:2, k]))
    counted = {
        k: (int(d), shapes.bending_nodes(k) if d == 0 else shapes.twisting_nodes(k))
        for k, d in enumerate(dominant)
        if d in (0, 1)
    }
    for count in set(counted.values()):
        sharing = [k for k, c in counted.items() if c == count]
        kept = max(sharing, key=lambda k: shares[count[0], k] / shares[:, k].sum())
        for k in sharing:
            taken = {membrane[j] for j, d in enumerate(dominant) if d == 2}
            if k != kept and membrane[k] is not None and membrane[k] not in taken:
                dominant[k] = 2
    counts = 0
    names, kinds = [], []
    for k, d in enumerate(dominant):
        if d == 0:
            names.append(f"{shapes.bending_nodes(k)}-node bending")
            kinds.append("bending")
        elif d == 1:
            names.append(f"{shapes.twisting_nodes(k)}-node twisting")
            kinds.append("twisting")
        elif d == 2:
            frequency = np.sqrt(shares[:, k].sum()) / (2 * np.pi)
            names.append(membrane[k] or f"string-bed membrane ({frequency:.1f} Hz)")
            kinds.append("string-bed")
        else:
            counts += 1
            names.append(f"{support_label} rigid-body {counts}")
            kinds.append("rigid-body")
    return tuple(names), tuple(kinds)
