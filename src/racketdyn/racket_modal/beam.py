"""The built-in modal model: a free–free beam racket with a twisting head and a string membrane.

Derivation (documented in docs/develop.md, "Built-in modal model"):

* **Mass along the racket** (issue 22: the frame's shape).  Euler–Bernoulli beam elements of
  equal length along the long axis.  A frame is a composite tube laid along its centreline: a
  shaft from the butt, two throat arms (:data:`THROAT_LENGTH_M`) and the hoop around the string
  bed, with the handle's pallet and grip on its first :data:`HANDLE_LENGTH_M` and the strings
  spread over the bed by its width.  Makers weight a frame at its two ends — in the handle
  (steel plates and pins, a heavier pallet) and under the bumper guard at the head's top
  (docs/references.md, "Racket dynamics") — so the head's top (:data:`HEAD_TOP_DEG` either side
  of 12 o'clock) is a fifth part, extra to the hoop's tube there.  The mass per unit length
  along x is each part's length per unit x (two sides of the hoop, steepest where it turns
  across the racket at the tip and the throat) times its mass per length.  The five amounts meet
  the racket's mass, balance point and moment of inertia about it exactly; of the amounts that
  do, the one closest to a single tube (shaft and arms as heavy per length as the hoop, nothing
  extra at the head's top) with none negative is taken: a racket whose swingweight the tube can
  give carries nothing extra there (the paper's racket), one of today's head-light rackets with
  a high swingweight carries 25–45 g.  Where no such amounts exist, the smooth distribution is
  used instead: the smallest departure from a uniform racket (least squares) with the same three
  moments (``metadata["mass_model"]`` says which).  The
  cubic (Hermite) element reproduces rigid-body motion exactly, so the FE model has exactly
  those rigid-body properties.  Point masses are lumped on the nearest node after the
  stiffnesses are calibrated, so lead tape shifts the frequencies.
* **Bending.**  Bending stiffness proportional to the number of frame tubes in a section (two in
  the throat arms and the hoop, one in the shaft and handle: two equal tubes side by side bend
  with twice one tube's stiffness; uniform with the smooth distribution), scaled so that the
  first flexible (2-node bending) mode of the free beam sits at ``racket.first_bending_hz``
  (paper, section 3.2: ≈ 120 Hz).
* **Twisting.**  Linear torsion elements; the roll inertia per unit length puts each section's
  mass on the frame hoop, at the string bed's half-width (at least a handle radius of 12.5 mm),
  scaled so the total equals the racket's roll inertia; uniform GJ is scaled so the first
  flexible twisting mode sits at ``racket.twisting_hz`` (docs/references.md: 361 Hz measured).
* **String bed.**  The fundamental mode of an elliptic membrane of the strings' mass (4 % of the
  racket, paper section 2) under the played bed's tension per unit width of the mains and
  crosses (``bed tension / spacing``, :attr:`racketdyn.racket.StringBed.bed_tension_n`), with
  the trial shape ``ψ = 1 − ρ²`` (ρ the elliptic radius); its Rayleigh quotient
  ``ω² = 3 (T_x/a² + T_y/b²) / σ`` gives the frequency.  The membrane is not coupled to the
  frame.
* **Damping.**  The identified damping of a freely supported racket is ≈ 0.5 % of critical;
  the approximate method does not use it (eq 12 gives the amplitude just after the impact).

The shape normal to the face at ``(x, y)`` is ``w(x)`` for bending, ``θ(x)·y`` for twisting and
``φ_m(x, y)`` for the membrane, each mass-normalised.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh, null_space
from scipy.special import ellipeinc

from racketdyn.errors import InputError
from racketdyn.hand import Hand
from racketdyn.modal.model import ModalModel
from racketdyn.numerics import one_blas_thread
from racketdyn.racket import HeadEllipse, Racket
from racketdyn.racket_modal.grip import hand_matrices
from racketdyn.racket_modal.shapes import SHAPES_FRAME_MODEL, ReferenceShapes, sign_changes

__all__ = [
    "FRAME_REFERENCE_MODES",
    "HANDLE_LENGTH_M",
    "HANDLE_RADIUS_M",
    "HEAD_TOP_DEG",
    "STRING_MASS_FRACTION",
    "THROAT_LENGTH_M",
    "beam_mass_per_length",
    "builtin_modal_model",
    "frame_mass_per_length",
    "hoop_roll_inertia",
    "mass_along",
    "reference_shapes",
]

STRING_MASS_FRACTION = 0.04
"""Strings ≈ 4 % of the strung racket's mass (paper, section 2)."""
HANDLE_RADIUS_M = 0.0125
"""Radius of gyration of a handle section about the long axis (a 25 mm grip), m."""
HANDLE_LENGTH_M = 0.19
"""Length of the handle (pallet and grip) from the butt, m: a 7½-inch grip, the usual length."""
THROAT_LENGTH_M = 0.10
"""Length of the throat's two arms below the string bed, m (the open throat of a current frame,
≈ 90–110 mm; an assumption of the built-in model, like :data:`HANDLE_LENGTH_M`)."""
HEAD_TOP_DEG = 60.0
"""Half-angle of the head's top, the weighted part under the bumper guard, about 12 o'clock, °
(10 to 2 o'clock, where bumper guards run; an assumption of the built-in model)."""
THROAT_SPREAD = 0.5
"""Half-spread of the throat arms where they meet the hoop, as a share of the bed's half-width."""
DEFAULT_DAMPING_RATIO = 0.005
N_ELEMENTS = 68


def _nodes(length_m: float, n_elements: int) -> NDArray[np.float64]:
    return np.linspace(0.0, length_m, n_elements + 1)


def beam_mass_per_length(
    length_m: float,
    mass_kg: float,
    balance_m: float,
    inertia_cg_kgm2: float,
    n_elements: int = N_ELEMENTS,
) -> NDArray[np.float64]:
    """Mass per unit length of each element, kg/m, matching M, balance and I_G exactly.

    Minimum-norm departure from a uniform beam under the three moment constraints
    ``∫m dx = M``, ``∫m x dx = M x_G``, ``∫m x² dx = I_G + M x_G²`` (exact for piecewise-constant
    m).  Raises InputError if the racket's inertia cannot be met by a positive distribution.
    """
    x = _nodes(length_m, n_elements)
    moments = _element_moments(x)
    target = np.array([mass_kg, mass_kg * balance_m, inertia_cg_kgm2 + mass_kg * balance_m**2])
    uniform = np.full(n_elements, mass_kg / length_m)
    correction = moments.T @ np.linalg.solve(moments @ moments.T, target - moments @ uniform)
    density = uniform + correction
    if np.any(density <= 0):
        raise InputError(
            f"racket: no positive mass distribution along {length_m} m has mass {mass_kg} kg, "
            f"balance {balance_m} m and inertia {inertia_cg_kgm2} kg·m² about it; check inertia_cg"
        )
    return np.asarray(density)


def _element_moments(x: NDArray[np.float64]) -> NDArray[np.float64]:
    """∫1, ∫x, ∫x² over each element: rows of the moment equations of a stepwise density."""
    lo, hi = x[:-1], x[1:]
    return np.vstack([hi - lo, (hi**2 - lo**2) / 2, (hi**3 - lo**3) / 3])


@dataclass(frozen=True)
class _FrameLayout:
    """Where the frame's tube runs: the hoop ellipse, the throat arms and the single shaft."""

    head: HeadEllipse
    length_m: float

    @property
    def offset_m(self) -> float:
        """The tube's centreline outside the bed's edge: half the frame beyond the bed's tip."""
        return float(np.clip((self.length_m - self.head.tip_x_m) / 2, 0.0, 0.01))

    @property
    def hoop_axes(self) -> tuple[float, float]:
        return self.head.half_length_m + self.offset_m, self.head.half_width_m + self.offset_m

    @property
    def arms(self) -> tuple[float, float, float]:
        """(x where the arms leave the shaft, x where they join the hoop, half-spread there)."""
        a, b = self.hoop_axes
        join = self.head.centre_x_m - a * np.sqrt(1 - THROAT_SPREAD**2)
        return float(max(join - THROAT_LENGTH_M, 0.0)), float(join), THROAT_SPREAD * b

    def hoop_length(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """Length of hoop (both sides) within each element, m: Legendre's incomplete E."""
        a, b = self.hoop_axes
        angle = np.arccos(np.clip((x - self.head.centre_x_m) / a, -1.0, 1.0))
        arc = b * ellipeinc(angle, 1.0 - (a / b) ** 2)  # from the tip, one side
        return np.asarray(2.0 * np.abs(np.diff(arc)))

    def parts(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """Length of shaft, arms (both), hoop (both sides), handle and the head's top within each
        element, m."""
        start, join, spread = self.arms
        lo, hi = x[:-1], x[1:]
        arm = np.clip(np.minimum(hi, join) - np.maximum(lo, start), 0.0, None)
        shaft = np.clip(np.minimum(hi, start) - lo, 0.0, None)
        slope = np.hypot(join - start, spread) / max(join - start, 1e-12)
        handle = np.clip(np.minimum(hi, HANDLE_LENGTH_M) - lo, 0.0, None)
        top = self.head.centre_x_m + self.hoop_axes[0] * np.cos(np.deg2rad(HEAD_TOP_DEG))
        head_top = self.hoop_length(np.maximum(x, top))
        return np.vstack([shaft, 2.0 * slope * arm, self.hoop_length(x), handle, head_top])

    def tubes(self, x_mid: NDArray[np.float64]) -> NDArray[np.float64]:
        """Frame tubes side by side in each section: 2 in the arms and the hoop, else 1."""
        return np.where(x_mid > self.arms[0], 2.0, 1.0)


def frame_mass_per_length(
    length_m: float,
    head: HeadEllipse,
    targets: tuple[float, float, float],
    string_mass_kg: float = 0.0,
    n_elements: int = N_ELEMENTS,
) -> NDArray[np.float64] | None:
    """Mass per unit length of each element from the frame's shape, kg/m (module docstring).

    Five parts, each of a uniform mass per length of its own: the shaft (one tube from the butt
    to the throat), the two throat arms, the hoop, the handle's pallet and grip (over
    :data:`HANDLE_LENGTH_M`) and the head's top (:data:`HEAD_TOP_DEG`), extra to the hoop
    there.  Their five amounts meet the three moments exactly; of the plane of amounts that do,
    the one closest to one tube — shaft and arms as heavy per length as the hoop, nothing extra
    at the head's top (least squares) — with no amount negative is taken.

    Parameters
    ----------
    length_m : float
        Overall length, m.
    head : HeadEllipse
        The string bed; the hoop runs around it.
    targets : tuple of float
        ``(M, x_G, I_G)``: mass (kg), balance (m from the butt) and inertia about the balance
        point (kg·m²) of everything this density carries.
    string_mass_kg : float
        Strings spread over the bed by its width (0: not carried, the rig models them apart).
    n_elements : int
        Beam elements.

    Returns
    -------
    ndarray or None
        The density, matching the three targets exactly; None where no non-negative amounts of
        the five parts meet them (the caller takes :func:`beam_mass_per_length`).
    """
    x = _nodes(length_m, n_elements)
    parts = _FrameLayout(head, length_m).parts(x) / np.diff(x)
    strings = string_mass_kg / head.area_m2 * 2.0 * head.half_width_at(0.5 * (x[:-1] + x[1:]))
    moments = _element_moments(x)
    mass, balance, inertia = targets
    target = np.array([mass, mass * balance, inertia + mass * balance**2]) - moments @ strings
    amounts = _closest_to_one_tube(moments @ parts.T, target)
    if amounts is None:
        return None
    density = parts.T @ amounts + strings
    return np.asarray(density) if np.all(density > 0) else None


ONE_TUBE = np.array(
    [[1.0, 0.0, -1.0, 0.0, 0.0], [0.0, 1.0, -1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 1.0]]
)
"""Departures from one tube of the amounts (shaft, arms, hoop, handle, head's top): shaft and
arms from the hoop, and anything extra at the head's top."""


def _closest_to_one_tube(
    equations: NDArray[np.float64], target: NDArray[np.float64]
) -> NDArray[np.float64] | None:
    """Amounts (shaft, arms, hoop, handle, head's top) meeting ``equations @ c = target``, none
    negative, closest to one tube (:data:`ONE_TUBE`); None if no such amounts exist.

    A convex quadratic over the amounts that meet the equations, bounded below by zero.  Its
    minimum lies on a face of that set, where some amounts are zero and the rest solve the
    equations; the best face is found by trying each set of zero amounts no larger than the
    plane's dimension — at most 16 small least-squares solves, exact and deterministic (a
    general optimiser would put its tolerance into the model's numbers).
    """
    unknowns = equations.shape[1]
    freedom = unknowns - np.linalg.matrix_rank(equations)
    best: tuple[float, NDArray[np.float64]] | None = None
    for count in range(freedom + 1):
        for zeros in combinations(range(unknowns), count):
            amounts = _on_face(equations, target, list(zeros))
            if amounts is None or np.any(amounts < -1e-12):
                continue
            departure = float(np.sum((ONE_TUBE @ amounts) ** 2))
            if best is None or departure < best[0] - 1e-15:
                best = (departure, np.clip(amounts, 0.0, None))
    return None if best is None else best[1]


def _on_face(
    equations: NDArray[np.float64], target: NDArray[np.float64], zeros: list[int]
) -> NDArray[np.float64] | None:
    """The amounts closest to one tube that meet the equations with ``zeros`` held at zero."""
    free = [i for i in range(equations.shape[1]) if i not in zeros]
    reduced = equations[:, free]
    particular, *_ = np.linalg.lstsq(reduced, target, rcond=None)
    if not np.allclose(reduced @ particular, target, rtol=1e-10, atol=1e-14):
        return None
    direction = null_space(reduced)
    amounts = np.zeros(equations.shape[1])
    if direction.shape[1]:
        spread = ONE_TUBE[:, free]
        step, *_ = np.linalg.lstsq(spread @ direction, -spread @ particular, rcond=None)
        particular = particular + direction @ step
    amounts[free] = particular
    return amounts


def _section_radius(head: HeadEllipse, x_mid: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.asarray(np.maximum(head.half_width_at(x_mid), HANDLE_RADIUS_M))


def hoop_roll_inertia(
    length_m: float, mass_kg: float, balance_m: float, inertia_cg_kgm2: float, head: HeadEllipse
) -> float:
    """Roll inertia (about the long axis) with each section's mass on the frame hoop, kg·m².

    ``I_roll = ∫ m(x) r(x)² dx`` with m(x) from :func:`beam_mass_per_length` and r(x) the string
    bed's half-width (at least :data:`HANDLE_RADIUS_M`).  Used when a racket file gives no
    roll inertia or twistweight.
    """
    # the smooth distribution, not the frame's shape (issue 22, fourth session): on the paper's
    # racket the frame's light hoop gives 11.4 kg·cm², below the 13–16 said of rackets on sale,
    # where the smooth one gives 15.2; left so until measured twistweights can judge
    density = beam_mass_per_length(length_m, mass_kg, balance_m, inertia_cg_kgm2)
    x = _nodes(length_m, density.size)
    mid, step = 0.5 * (x[:-1] + x[1:]), np.diff(x)
    return float(np.sum(density * _section_radius(head, mid) ** 2 * step))


def mass_along(
    length_m: float,
    head: HeadEllipse,
    targets: tuple[float, float, float],
    string_mass_kg: float = 0.0,
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """The built-in model's mass per length and frame tubes per section (None: uniform EI).

    :func:`frame_mass_per_length` where the frame's shape meets ``targets`` with a positive
    density, else :func:`beam_mass_per_length` (smooth, uniform bending stiffness).
    """
    density = frame_mass_per_length(length_m, head, targets, string_mass_kg)
    if density is None:
        return beam_mass_per_length(length_m, *targets), None
    x = _nodes(length_m, density.size)
    return density, _FrameLayout(head, length_m).tubes(0.5 * (x[:-1] + x[1:]))


def _bending_matrices(
    x: NDArray[np.float64],
    density: NDArray[np.float64],
    rigidity: NDArray[np.float64] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Stiffness (EI in units of ``rigidity``, 1 if None) and consistent mass matrices for
    Hermite beam elements (w, θ at nodes)."""
    n = x.size
    stiffness = np.zeros((2 * n, 2 * n))
    mass = np.zeros((2 * n, 2 * n))
    scale = np.ones(density.size) if rigidity is None else rigidity
    for e, (h, rho, ei) in enumerate(zip(np.diff(x), density, scale, strict=True)):
        k = (
            ei
            * np.array(
                [
                    [12, 6 * h, -12, 6 * h],
                    [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                    [-12, -6 * h, 12, -6 * h],
                    [6 * h, 2 * h * h, -6 * h, 4 * h * h],
                ]
            )
            / h**3
        )
        m = (
            rho
            * h
            / 420
            * np.array(
                [
                    [156, 22 * h, 54, -13 * h],
                    [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                    [54, 13 * h, 156, -22 * h],
                    [-13 * h, -3 * h * h, -22 * h, 4 * h * h],
                ]
            )
        )
        dofs = slice(2 * e, 2 * e + 4)
        stiffness[dofs, dofs] += k
        mass[dofs, dofs] += m
    return stiffness, mass


def _torsion_matrices(
    x: NDArray[np.float64], roll_density: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Unit-GJ stiffness and consistent inertia matrices for linear torsion elements."""
    n = x.size
    stiffness = np.zeros((n, n))
    inertia = np.zeros((n, n))
    for e, (h, j) in enumerate(zip(np.diff(x), roll_density, strict=True)):
        stiffness[e : e + 2, e : e + 2] += np.array([[1, -1], [-1, 1]]) / h
        inertia[e : e + 2, e : e + 2] += j * h / 6 * np.array([[2, 1], [1, 2]])
    return stiffness, inertia


def _flexible_modes(
    stiffness: NDArray[np.float64], mass: NDArray[np.float64], n_rigid: int, n_modes: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Lowest flexible eigenpairs (ω², mass-normalised vectors) of a free structure.

    On one BLAS thread: OpenBLAS splits this small problem (138 × 138) over its threads for
    no gain (on a loaded two-core machine 0.4 s a solve against 1 ms on one thread), and the
    last digits of its answer depend on how many it has; on one, the model is the same on
    every machine, in a sweep's tasks (one thread each) as in a single run.
    """
    with one_blas_thread():
        values, vectors = eigh(stiffness, mass, subset_by_index=[0, n_rigid + n_modes - 1])
    return values[n_rigid:], vectors[:, n_rigid:]


@dataclass(frozen=True)
class _BeamFrame:
    """The built-in beam's nodes (m), mass per length (kg/m), tubes per element (None:
    uniform EI), roll inertia per length (kg·m), the node nearest each point mass, and the
    strings' mass (kg)."""

    x: NDArray[np.float64]
    density: NDArray[np.float64]
    tubes: NDArray[np.float64] | None
    roll_density: NDArray[np.float64]
    nearest: list[int]
    string_mass_kg: float


def _beam_frame(racket: Racket) -> _BeamFrame:
    """The built-in beam of a racket: its mass along the racket (:func:`mass_along`) and its
    roll inertia per length, the section's mass on the hoop, scaled to the racket's roll
    inertia."""
    x = _nodes(racket.length_m, N_ELEMENTS)
    string_mass = float(racket.strings.mass_kg or STRING_MASS_FRACTION * racket.mass_kg)
    targets = (racket.mass_kg, racket.balance_m, racket.inertia_cg_kgm2)
    density, tubes = mass_along(racket.length_m, racket.head, targets, string_mass)
    mid, step = 0.5 * (x[:-1] + x[1:]), np.diff(x)
    roll_density = density * _section_radius(racket.head, mid) ** 2
    roll_density *= racket.roll_inertia_kgm2 / np.sum(roll_density * step)
    nearest = [int(np.argmin(np.abs(x - p.x_m))) for p in racket.point_masses]
    return _BeamFrame(x, density, tubes, roll_density, nearest, string_mass)


def _calibrated(
    stiffness: NDArray[np.float64],
    mass: NDArray[np.float64],
    n_rigid: int,
    n_modes: int,
    target_hz: float,
) -> float:
    """The factor on a unit stiffness that puts the bare frame's first flexible mode at
    ``target_hz`` (the racket's measured frequency; point masses then shift it, as on the
    racket)."""
    omega2, _ = _flexible_modes(stiffness, mass, n_rigid, n_modes)
    return float((2 * np.pi * target_hz) ** 2 / omega2[0])


def _with_point_masses(
    frame: _BeamFrame, racket: Racket, mass: NDArray[np.float64], inertia: NDArray[np.float64]
) -> None:
    """The racket's point masses added, in place, to the bending mass matrix (on ``w`` at the
    nearest node) and the roll inertia matrix (``m y²``)."""
    for node, p in zip(frame.nearest, racket.point_masses, strict=True):
        mass[2 * node, 2 * node] += p.mass_kg
        inertia[node, node] += p.mass_kg * p.y_m**2


def builtin_modal_model(racket: Racket, n_bending: int = 2) -> ModalModel:
    """The built-in free–free modal model of a racket (see the module docstring).

    Parameters
    ----------
    racket : Racket
        Mass properties, head, strings, point masses and the two frequency targets.
    n_bending : int
        Number of flexible bending modes (2: the 2- and 3-node modes).

    Returns
    -------
    ModalModel
        ``n_bending`` bending modes, one twisting mode and the string-bed mode, sampled on the
        beam's nodes along the axis and across the head.
    """
    frame = _beam_frame(racket)
    x, density, tubes = frame.x, frame.density, frame.tubes
    string_mass = frame.string_mass_kg

    # Stiffnesses are calibrated on the racket as described (without point masses): the targets
    # are its measured frequencies; lead tape then shifts the modes, as it would on the racket.
    stiffness, mass = _bending_matrices(x, density, tubes)
    bending_stiffness = _calibrated(stiffness, mass, 2, n_bending, racket.first_bending_hz)
    t_stiffness, t_inertia = _torsion_matrices(x, frame.roll_density)
    torsional_stiffness = _calibrated(t_stiffness, t_inertia, 1, 1, racket.twisting_hz)
    _with_point_masses(frame, racket, mass, t_inertia)
    omega2, vectors = _flexible_modes(stiffness, mass, 2, n_bending)
    bending_omega = np.sqrt(omega2 * bending_stiffness)
    bending_shapes = vectors[0::2, :]  # displacement DOFs, mass-normalised

    t_omega2, t_vectors = _flexible_modes(t_stiffness, t_inertia, 1, 1)
    twist_omega = np.sqrt(t_omega2[0] * torsional_stiffness)
    twist_shape = t_vectors[:, 0]

    head, strings = racket.head, racket.strings
    spacing_mains, spacing_crosses = strings.spacing_m(head)
    areal_density = string_mass / head.area_m2
    membrane_omega = np.sqrt(
        3.0
        * (
            strings.bed_tension_n / spacing_mains / head.half_length_m**2
            + strings.bed_tension_n / spacing_crosses / head.half_width_m**2
        )
        / areal_density
    )
    membrane_scale = np.sqrt(3.0 / string_mass)  # ∫σψ² dA = m_s / 3 for ψ = 1 − ρ²

    locations = _sample_locations(x, head)
    along = np.interp(locations[:, 0], x, np.arange(x.size))  # fractional node index
    lower = np.clip(np.floor(along).astype(int), 0, x.size - 2)
    frac = along - lower

    def on_nodes(values: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(values[lower] * (1 - frac) + values[lower + 1] * frac)

    rho = head.normalised_radius(locations)
    columns = [on_nodes(bending_shapes[:, k]) for k in range(n_bending)]
    columns.append(on_nodes(twist_shape) * locations[:, 1])  # roll about the long axis
    columns.append(np.where(rho < 1.0, membrane_scale * (1.0 - rho**2), 0.0))
    frequency = np.concatenate([bending_omega, [twist_omega, membrane_omega]]) / (2 * np.pi)
    names = (
        *(f"{k + 2}-node bending" for k in range(n_bending)),
        "2-node twisting",
        "string-bed membrane",
    )
    kinds = (*("bending",) * n_bending, "twisting", "string-bed")
    order = np.argsort(frequency)
    return ModalModel(
        frequency=frequency[order],
        damping_ratio=np.full(frequency.size, DEFAULT_DAMPING_RATIO),
        locations=locations,
        mode_shapes=np.column_stack(columns)[:, order],
        names=tuple(names[i] for i in order),
        kinds=tuple(kinds[i] for i in order),
        support="free",
        source=f"built-in beam model of {racket.name}",
        metadata={
            # EI of one tube's section (the shaft's); twice that where two tubes run side by side
            "bending_stiffness_nm2": float(bending_stiffness),
            "torsional_stiffness_nm2_per_rad": float(torsional_stiffness),
            "string_mass_kg": float(string_mass),
            "mass_model": "smooth" if tubes is None else "frame",
            "elements": N_ELEMENTS,
            # the beam's deflection is the frame's at every point, the strings' own give is
            # the ball-string law's: nothing to take off (racket_modal.shapes.frame_under_bed)
            "shapes_on_strings": SHAPES_FRAME_MODEL,
        },
    )


FRAME_REFERENCE_MODES = 8
"""How many of the frame's own bending and twisting modes :func:`reference_shapes` gives
(2- to 9-node bending, 2- to 9-node twisting)."""


def reference_shapes(racket: Racket, hand: Hand | None = None) -> ReferenceShapes:
    """What a racket's measured modes are named against
    (:func:`racketdyn.racket_modal.shapes.classify_modes`).

    The frame's own bending modes ``w(x)`` and twisting modes ``θ(x)`` (the built-in model's
    beam: its mass along the racket, its tubes, the point masses; the strings' mass on the
    beam, no membrane), each with its node count from its sign changes along the racket
    (n-node bending: n sign changes of ``w`` from butt to tip; n-node twisting: n − 1 of
    ``θ``, the long axis being a nodal line too), and the bed's tensions for its own modes.

    Free, the shapes do not depend on the frame's stiffness.  Held, they do: the hand's
    springs pull the grip towards the arm against the frame's own stiffness, so the beam's
    EI and GJ are those of the built-in model (its bare first bending at
    ``racket.first_bending_hz``, its first twisting at ``racket.twisting_hz``) and the hand
    is the rig's and the impact model's (:func:`racketdyn.racket_modal.grip.hand_matrices`):
    its mass and roll inertia over the grip, its springs to the arm, the shoulder's spring.
    The frame's own modes are then those holding most of their strain energy in the frame
    (bending or twisting, as the rig names its modes), not the racket swinging and rolling
    on the hand.  On a 300 g, 100 sq in racket held so, the hand moves the twist along the
    racket enough that the hoop's points matched the free frame's 3-node twisting better
    than its 4-node for the held 4-node twisting (0.82 against 0.69); against the held
    frame's the rig's held twisting modes match their own counts at MAC ≥ 0.99 along the
    beam (``tests/test_racket_data.py``).

    Parameters
    ----------
    racket : Racket
        The racket.
    hand : Hand, optional
        The hand holding the racket in the test (its ``hand`` support); None: the frame free.

    Returns
    -------
    ReferenceShapes
    """
    frame = _beam_frame(racket)
    stiffness, mass = _bending_matrices(frame.x, frame.density, frame.tubes)
    t_stiffness, t_inertia = _torsion_matrices(frame.x, frame.roll_density)
    if hand is None:
        _with_point_masses(frame, racket, mass, t_inertia)
        bending = _flexible_modes(stiffness, mass, 2, FRAME_REFERENCE_MODES)[1][0::2, :]
        twisting = _flexible_modes(t_stiffness, t_inertia, 1, FRAME_REFERENCE_MODES)[1]
    else:
        bending, twisting = _held_frame_modes(
            frame, racket, hand, (stiffness, mass), (t_stiffness, t_inertia)
        )
    head, strings = racket.head, racket.strings
    spacing_mains, spacing_crosses = strings.spacing_m(head)
    return ReferenceShapes(
        bed_stiffness_ratio=(spacing_mains / head.half_width_m**2)
        / (spacing_crosses / head.half_length_m**2),
        frame_x=frame.x,
        bending=bending,
        twisting=twisting,
        bending_nodes=tuple(sign_changes(bending[:, k]) for k in range(bending.shape[1])),
        twisting_nodes=tuple(sign_changes(twisting[:, k]) + 1 for k in range(twisting.shape[1])),
    )


HAND_MODES = 3
"""Modes of the racket on the hand that the held frame's lowest modes may hold besides its own,
in bending (heave, pitch on the palm, the arm against the shoulder) and fewer in twisting
(the roll in the fingers): :func:`reference_shapes` solves for this many more."""


def _held_frame_modes(
    frame: _BeamFrame,
    racket: Racket,
    hand: Hand,
    bending: tuple[NDArray[np.float64], NDArray[np.float64]],
    twisting: tuple[NDArray[np.float64], NDArray[np.float64]],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The lowest :data:`FRAME_REFERENCE_MODES` bending ``w(x)`` and twisting ``θ(x)`` modes of
    the beam held by ``hand`` (:func:`reference_shapes`), from the unit-stiffness bending and
    torsion matrices and their mass and inertia matrices (without the point masses).

    The hand's matrices (:func:`racketdyn.racket_modal.grip.hand_matrices`) couple the grip's
    ``w`` to the arm and its ``θ`` to nothing else, so bending (``w``, ``w'`` and the arm) and
    twisting are two eigenproblems; of each one's lowest modes, those holding over half their
    strain energy in the frame are the frame's own."""
    (k_bend, m_bend), (k_twist, m_twist) = bending, twisting
    scale_bend = _calibrated(k_bend, m_bend, 2, 1, racket.first_bending_hz)
    scale_twist = _calibrated(k_twist, m_twist, 1, 1, racket.twisting_hz)
    m_bend, m_twist = m_bend.copy(), m_twist.copy()
    _with_point_masses(frame, racket, m_bend, m_twist)
    nodes = frame.x.size
    mass, stiffness, _ = hand_matrices(hand, frame.x, 3 * nodes)
    arm = [3 * nodes]
    kept = []
    for dofs, own_mass, own_stiffness in (
        (np.r_[0 : 2 * nodes, arm], m_bend, scale_bend * k_bend),
        (np.r_[2 * nodes : 3 * nodes], m_twist, scale_twist * k_twist),
    ):
        n_own = own_mass.shape[0]
        own = np.zeros((dofs.size, dofs.size))
        own[:n_own, :n_own] = own_stiffness
        held_mass = mass[np.ix_(dofs, dofs)]
        held_mass[:n_own, :n_own] += own_mass
        held_stiffness = stiffness[np.ix_(dofs, dofs)] + own
        count = min(FRAME_REFERENCE_MODES + HAND_MODES, dofs.size) - 1
        with one_blas_thread():
            _, vectors = eigh(held_stiffness, held_mass, subset_by_index=[0, count])
        with np.errstate(invalid="ignore", divide="ignore"):  # NaN: a mode of no stiffness
            share = np.einsum("ik,ij,jk->k", vectors, own, vectors) / np.einsum(
                "ik,ij,jk->k", vectors, held_stiffness, vectors
            )
        frame_modes = np.flatnonzero(np.nan_to_num(share) > 0.5)[:FRAME_REFERENCE_MODES]
        kept.append(vectors[:n_own, frame_modes])
    return kept[0][0::2], kept[1]


def _sample_locations(x: NDArray[np.float64], head: HeadEllipse) -> NDArray[np.float64]:
    """Beam nodes on the axis and on the handle's sides, a 1 cm lattice across the head, and
    two rings on the frame.

    The handle's sides (y = ±:data:`HANDLE_RADIUS_M`, nodes up to the throat) give the twist
    along the handle, where a hand reads the handle's turn (:class:`racketdyn.hand.Hand`):
    without them the interpolation took it from the head, half the beam's.

    The rings (on the bed's edge and 8 % outside it, every 5°) pin the membrane shape to zero
    on the frame, so the interpolation neither bulges past the edge nor extrapolates onto it.
    """
    points = [np.column_stack([x, np.zeros_like(x)])]
    # the handle's sides (the hand's grip reads the handle's turn there: racketdyn.hand)
    handle = x[x <= head.throat_x_m]
    for side in (-HANDLE_RADIUS_M, HANDLE_RADIUS_M):
        points.append(np.column_stack([handle, np.full(handle.size, side)]))
    in_head = x[(x > head.throat_x_m) & (x < head.tip_x_m)]
    for xi in in_head:
        half = float(head.half_width_at(xi))
        count = max(int(np.ceil(half / 0.01)), 1)
        offsets = np.linspace(-half, half, 2 * count + 1)[1:-1]
        offsets = offsets[np.abs(offsets) > 1e-12]
        points.append(np.column_stack([np.full(offsets.size, xi), head.centre_y_m + offsets]))
    angle = np.deg2rad(np.arange(0.0, 360.0, 5.0))
    for scale in (1.0, 1.08):
        ring = np.column_stack(
            [
                head.centre_x_m + scale * head.half_length_m * np.cos(angle),
                head.centre_y_m + scale * head.half_width_m * np.sin(angle),
            ]
        )
        points.append(ring[(ring[:, 0] > 0) & (np.abs(ring[:, 1]) > 1e-12)])
    return np.vstack(points)
