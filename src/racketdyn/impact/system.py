"""The racket's linear equations of motion under a normal force at the impact point.

Both engines of the transient model (:mod:`racketdyn.impact.transient`) start here:

    ``M q̈ + C q̇ + K q = b_j F``,   w_j = b_jᵀ q  (the face's displacement at point j),

with coordinates ``q`` chosen by the support (a parameter, never a copy of the code):

* ``free``: the racket's rigid body — translation of the centre of mass and the two in-plane
  rotations about it (the full in-plane inertia tensor, so off-axis lead counts) — plus the
  flexible modes;
* ``pinned``: the two rotations about the grip pivot (the paper's eq 4 with roll) plus the
  flexible modes, which stay those of the model given, as in the approximate method;
* ``hand``: the ``free`` coordinates plus an arm mass joined to the grip by springs and dashpots
  in translation and roll (:class:`racketdyn.hand.Hand`, the rig's hand too; the shoulder,
  which stores nothing over a contact, is left out).

The flexible modes (mass-normalised, ``q_k`` with unit modal mass) carry no momentum, so for
``free`` and ``pinned`` the rigid and modal blocks of ``M`` are uncoupled and ``b_jᵀ M⁻¹ b_j``
of the rigid block is the reduced mass's compliance ``1/M_r`` (eq 4).  The hand's palm mass
couples them; the split into rigid-body motions (K r = C r = 0) and the rest stays exact.

The reference engine integrates these equations as they stand.  The compiled engine uses the
same equations in pole–residue form (:meth:`ImpactSystem.pole_residue`): the receptance at j is

    ``H_j(s) = c_j / s² + Σ_k r_jk / (s − λ_k)``,

``c_j`` the rigid-body compliance (modes with K = C = 0, split off exactly) and λ_k, r_jk the
poles and residues of the rest, which may be non-proportionally damped (the hand).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import Literal

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray

from racketdyn.errors import InputError, one_of
from racketdyn.impact.hand import Hand
from racketdyn.modal import ModalModel
from racketdyn.racket import Racket, as_locations

__all__ = [
    "TRANSIENT_SUPPORTS",
    "CoordinateKind",
    "ImpactSystem",
    "PoleResidue",
    "impact_system",
    "point_system",
]

TRANSIENT_SUPPORTS: tuple[str, ...] = ("free", "pinned", "hand")
Engine = Literal["auto", "compiled", "reference"]
ENGINES: tuple[str, ...] = ("auto", "compiled", "reference")
"""The transient model's integrators (:func:`racketdyn.impact.transient.predict_transient`);
here, beside its supports, so that a caller checking its options need not import the model
(and numba with it)."""
_TWIST_PROBE_M = 0.010
"""Half the distance across the handle over which the hand reads the handle's turn, m (the
rigid roll exactly; a mode's twist from its shapes either side of the axis)."""
"""Supports of the transient model; the approximate method has ``free`` and ``pinned``."""

CoordinateKind = Literal["rigid", "mode", "arm"]
log = logging.getLogger(__name__)
_MAX_CONDITION = 1e10  # eigenvector condition number beyond which the modal form is refused
_POLE_IMAG_TOL = 1e-9  # a pole with |Im λ| below this × |λ| is real (an overdamped motion)


@dataclass(frozen=True, eq=False)
class PoleResidue:
    """The receptance at each impact point in pole–residue form.

    ``H_j(s) = rigid_compliance[j] / s² + Σ_k weight[k] · Re-part of r_jk / (s − λ_k)``:
    each complex pole stands for itself and its conjugate (``weight`` 2), a real pole for
    itself (``weight`` 1), so the displacement is ``c_j ρ + Σ_k weight_k Re(r_jk u_k)`` with
    ``ρ̈ = F`` and ``u̇_k = λ_k u_k + F``.

    Attributes
    ----------
    rigid_compliance : ndarray (n_points,)
        ``c_j = 1/M_r``, 1/kg (0 if the support leaves no rigid-body motion).
    poles : ndarray (n_poles,), complex
        λ_k with Im λ_k ≥ 0, 1/s.
    residues : ndarray (n_points, n_poles), complex
        r_jk, s/kg.
    weights : ndarray (n_poles,)
        2 for a complex pole (and its conjugate), 1 for a real pole.
    state_vectors : ndarray (n_points, n_poles, 2 n), complex
        ``v_jk`` such that the physical state ``(q, q̇)`` of the non-rigid part is
        ``Σ_k weight_k Re(v_jk u_k)``.
    rigid_vectors : ndarray (n_points, n)
        ``R Rᵀ b_j``: the physical displacement (velocity) of the rigid part is this times ρ (ρ̇).
    """

    rigid_compliance: NDArray[np.float64]
    poles: NDArray[np.complex128]
    residues: NDArray[np.complex128]
    weights: NDArray[np.float64]
    state_vectors: NDArray[np.complex128]
    rigid_vectors: NDArray[np.float64]

    def receptance(self, frequency_hz: ArrayLike) -> NDArray[np.complex128]:
        """H_j(iω) at each point, shaped ``(n_points, n_frequencies)``, m/N."""
        s = 2j * np.pi * np.atleast_1d(np.asarray(frequency_hz, dtype=float))
        flexible = self.residues[:, :, None] / (s[None, None, :] - self.poles[None, :, None])
        conjugate = np.conj(self.residues)[:, :, None] / (
            s[None, None, :] - np.conj(self.poles)[None, :, None]
        )
        pair = self.weights[None, :, None] == 2.0
        total = flexible + np.where(pair, conjugate, 0.0)
        return np.asarray(self.rigid_compliance[:, None] / s[None, :] ** 2 + total.sum(axis=1))


@dataclass(frozen=True, eq=False)
class ImpactSystem:
    """Equations of motion ``M q̈ + C q̇ + K q = b_j F`` of a supported racket.

    Attributes
    ----------
    support : str
        ``free``, ``pinned``, ``hand`` or ``point`` (a reduced mass and modes, no racket).
    coordinate_names : tuple of str
        One name per coordinate of ``q``.
    coordinate_kinds : tuple of {"rigid", "mode", "arm"}
        Rigid-body coordinates of the racket, flexible modal coordinates, the arm.
    mass, damping, stiffness : ndarray (n, n)
        M (kg, kg·m², 1), C and K in the same coordinates.
    force_input : ndarray (n_points, n)
        b_j: the generalised forces of a unit normal force at each impact point.
    locations : ndarray (n_points, 2)
        Impact points (x, y), m.
    omega : ndarray (n_modes,)
        Natural angular frequencies of the flexible modes, rad/s (energy per mode).
    mode_names : tuple of str
        Names of the flexible modes.
    racket_mass : ndarray (n, n)
        The racket body's own share of M (without the hand and arm): its rigid-body energy is
        ``½ q̇ᵀ racket_mass q̇`` over the rigid coordinates.
    """

    support: str
    coordinate_names: tuple[str, ...]
    coordinate_kinds: tuple[CoordinateKind, ...]
    mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    force_input: NDArray[np.float64]
    locations: NDArray[np.float64]
    omega: NDArray[np.float64]
    mode_names: tuple[str, ...]
    racket_mass: NDArray[np.float64]

    @property
    def n_coordinates(self) -> int:
        """Number of coordinates in q."""
        return len(self.coordinate_names)

    @property
    def rigid_index(self) -> NDArray[np.intp]:
        """Indices of the racket's rigid-body coordinates in q."""
        return np.flatnonzero(np.array(self.coordinate_kinds) == "rigid")

    def rigid_point_velocity(self, velocity: NDArray[np.float64]) -> NDArray[np.float64]:
        """Velocity of each impact point from the racket's rigid-body motion alone, m/s.

        Parameters
        ----------
        velocity : ndarray (..., n)
            q̇.

        Returns
        -------
        ndarray (..., n_points)
        """
        idx = self.rigid_index
        return np.asarray(np.asarray(velocity)[..., idx] @ self.force_input[:, idx].T)

    @property
    def mode_index(self) -> NDArray[np.intp]:
        """Indices of the flexible modal coordinates in q."""
        return np.flatnonzero(np.array(self.coordinate_kinds) == "mode")

    def rigid_basis(self) -> NDArray[np.float64]:
        """M-orthonormal basis R of the rigid-body motions (K R = C R = 0), shaped (n, n_rigid).

        The motions with ω² below ``1e-12`` of the largest of the generalised eigenproblem
        K v = ω² M v (mass-scaled, so a soft grip spring beside kHz modes stays elastic).
        """
        omega_sq, vectors = scipy.linalg.eigh(self.stiffness, self.mass)
        rigid = vectors[:, omega_sq < 1e-12 * max(float(omega_sq.max(initial=0.0)), 1.0)]
        if rigid.size and not np.allclose(
            self.damping @ rigid, 0.0, atol=1e-9 * max(1.0, _norm(self.damping))
        ):
            raise InputError(
                f"{self.support} support: a dashpot acts on a motion no spring resists; give it a "
                "spring too"
            )
        return np.asarray(rigid)

    def pole_residue(self) -> PoleResidue:
        """The receptance at every point in pole–residue form (for the compiled engine).

        The rigid-body motions are split off exactly (``R``, M-orthonormal); the rest of the
        coordinates, M-orthogonal to them, have ``M_e ë + C_e ė + K_e e = E ᵀ b F`` with K_e
        positive definite, written first-order and diagonalised once for all points.
        """
        rigid = self.rigid_basis()
        n = self.n_coordinates
        elastic = scipy.linalg.null_space(rigid.T @ self.mass) if rigid.size else np.eye(n)
        n_e = elastic.shape[1]
        m_e = elastic.T @ self.mass @ elastic
        c_e = elastic.T @ self.damping @ elastic
        k_e = elastic.T @ self.stiffness @ elastic
        b = self.force_input
        rigid_modal = b @ rigid  # (n_points, n_rigid)
        rigid_compliance = np.sum(rigid_modal**2, axis=1)
        rigid_vectors = rigid_modal @ rigid.T
        if n_e == 0:
            empty = np.zeros((b.shape[0], 0), dtype=complex)
            return PoleResidue(
                rigid_compliance, np.zeros(0, complex), empty, np.zeros(0),
                np.zeros((b.shape[0], 0, 2 * n), complex), rigid_vectors,
            )  # fmt: skip
        m_inv = np.linalg.inv(m_e)
        first_order = np.block([[np.zeros((n_e, n_e)), np.eye(n_e)], [-m_inv @ k_e, -m_inv @ c_e]])
        eigenvalues, right = np.linalg.eig(first_order)
        condition = float(np.linalg.cond(right))
        log.debug("%s support: eigenvector condition number %.3g", self.support, condition)
        if condition > _MAX_CONDITION:
            raise InputError(
                f"{self.support} support: the equations of motion are nearly defective (a mode "
                "damped almost exactly critically?); change a damping value slightly"
            )
        left = np.linalg.inv(right)
        keep = eigenvalues.imag > -_POLE_IMAG_TOL * np.abs(eigenvalues)
        real = np.abs(eigenvalues.imag) <= _POLE_IMAG_TOL * np.abs(eigenvalues)
        poles = eigenvalues[keep]
        weights = np.where(real[keep], 1.0, 2.0)
        b_e = b @ elastic  # (n_points, n_e)
        inputs = np.concatenate([np.zeros_like(b_e), b_e @ m_inv.T], axis=1)  # (n_points, 2 n_e)
        beta = inputs @ left[keep].T  # (n_points, n_poles)
        gamma = b_e @ right[:n_e, keep]  # output w = b_eᵀ e
        residues = gamma * beta
        # physical (q, q̇) = blockdiag(E, E) · Σ V_k β_k u_k
        lift = np.zeros((2 * n, 2 * n_e))
        lift[:n, :n_e] = elastic
        lift[n:, n_e:] = elastic
        physical = lift @ right[:, keep]  # (2n, n_poles)
        state_vectors = physical.T[None, :, :] * beta[:, :, None]
        return PoleResidue(rigid_compliance, poles, residues, weights, state_vectors, rigid_vectors)

    def energies(
        self, displacement: NDArray[np.float64], velocity: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """The racket's rigid-body kinetic energy, energy per flexible mode and the rest, J.

        Parameters
        ----------
        displacement, velocity : ndarray (..., n)
            q and q̇.

        Returns
        -------
        rigid, modes, support : ndarray (...,), (..., n_modes), (...,)
            ``½ q̇_Rᵀ M_racket q̇_R`` of the racket body's rigid-body coordinates;
            ``½ q̇_k² + ½ ω_k² q_k²`` per flexible mode of the racket (for ``hand`` a snapshot:
            after separation the held system's modes exchange it with the hand); and the rest of
            ``½ q̇ᵀMq̇ + ½ qᵀKq`` — the hand, palm and arm and the grip's springs (zero without a
            hand).
        """
        q, v = np.asarray(displacement), np.asarray(velocity)
        total = 0.5 * np.einsum("...i,ij,...j->...", v, self.mass, v) + 0.5 * np.einsum(
            "...i,ij,...j->...", q, self.stiffness, q
        )
        r = self.rigid_index
        v_r = v[..., r]
        rigid = 0.5 * np.einsum("...i,ij,...j->...", v_r, self.racket_mass[np.ix_(r, r)], v_r)
        idx = self.mode_index
        modes = 0.5 * v[..., idx] ** 2 + 0.5 * self.omega**2 * q[..., idx] ** 2
        return rigid, modes, total - rigid - modes.sum(axis=-1)


def _norm(matrix: NDArray[np.float64]) -> float:
    return float(np.abs(matrix).max(initial=0.0))


def _kinds(kind: CoordinateKind, count: int) -> tuple[CoordinateKind, ...]:
    return (kind,) * count


# --- building systems ---------------------------------------------------------------------------
def point_system(
    reduced_mass: float,
    mode_shapes: ArrayLike = (),
    omega: ArrayLike = (),
    damping_ratio: ArrayLike = (),
) -> ImpactSystem:
    """One impact point: a rigid reduced mass M_r (eq 4) plus flexible modes.

    Parameters
    ----------
    reduced_mass : float
        M_r at the point, kg; ``inf`` for a clamped head (no rigid-body motion).
    mode_shapes, omega, damping_ratio : array_like (n_modes,)
        φ_k at the point (1/√kg), natural angular frequencies (rad/s) and damping ratios.

    Returns
    -------
    ImpactSystem
    """
    phi = np.atleast_1d(np.asarray(mode_shapes, dtype=float))
    w_k = np.atleast_1d(np.asarray(omega, dtype=float))
    zeta = np.atleast_1d(np.asarray(damping_ratio, dtype=float))
    rigid = not np.isinf(reduced_mass)
    rigid_names: tuple[str, ...] = ("point",) if rigid else ()
    names = rigid_names + tuple(f"mode {k + 1}" for k in range(phi.size))
    kinds = _kinds("rigid", int(rigid)) + _kinds("mode", phi.size)
    mass = np.diag(np.concatenate([[reduced_mass] if rigid else [], np.ones(phi.size)]))
    damping = np.diag(np.concatenate([[0.0] if rigid else [], 2.0 * zeta * w_k]))
    stiffness = np.diag(np.concatenate([[0.0] if rigid else [], w_k**2]))
    force = np.concatenate([[1.0] if rigid else [], phi])[None, :]
    return ImpactSystem(
        "point", names, kinds, mass, damping, stiffness, force, np.full((1, 2), np.nan), w_k,
        tuple(names[int(rigid):]), mass.copy(),
    )  # fmt: skip


def impact_system(
    racket: Racket,
    model: ModalModel | None,
    support: str,
    locations: ArrayLike,
    hand: Hand | None = None,
) -> ImpactSystem:
    """The racket's equations of motion for a support, at the given impact points.

    Parameters
    ----------
    racket : Racket
        Mass properties (point masses included).
    model : ModalModel or None
        Flexible modes (mass-normalised); None for a rigid racket.
    support : {"free", "pinned", "hand"}
        Support condition.
    locations : array_like (n_points, 2)
        Impact points (x, y), m.
    hand : Hand, optional
        The hand and arm for ``support="hand"`` (default :class:`Hand`).

    Returns
    -------
    ImpactSystem
    """
    one_of("support", support, TRANSIENT_SUPPORTS)
    xy = as_locations(locations)
    props = racket.mass_properties
    if support == "pinned":
        origin, inertia = racket.pivot_m, props.inertia_about(racket.pivot_m)
        names: tuple[str, ...] = ()
    else:
        origin, inertia, names = props.centre_m, props.inertia_kgm2, ("translation",)
    rigid_names = (*names, "roll", "pitch")
    n_rigid = len(rigid_names)
    rigid_mass = np.zeros((n_rigid, n_rigid))
    if support != "pinned":
        rigid_mass[0, 0] = props.mass_kg
    rigid_mass[-2:, -2:] = inertia

    def rigid_input(points: NDArray[np.float64]) -> NDArray[np.float64]:
        lever = np.column_stack([points[:, 1] - origin[1], -(points[:, 0] - origin[0])])
        if support == "pinned":
            return lever
        return np.column_stack([np.ones(len(points)), lever])

    n_modes = 0 if model is None else model.n_modes
    omega = np.zeros(0) if model is None else model.omega
    zeta = np.zeros(0) if model is None else model.damping_ratio
    mode_names = () if model is None else tuple(model.names)
    arm = 1 if support == "hand" else 0
    n = n_rigid + n_modes + arm
    mass = np.zeros((n, n))
    damping = np.zeros((n, n))
    stiffness = np.zeros((n, n))
    mass[:n_rigid, :n_rigid] = rigid_mass
    modal = slice(n_rigid, n_rigid + n_modes)
    mass[modal, modal] = np.eye(n_modes)
    damping[modal, modal] = np.diag(2.0 * zeta * omega)
    stiffness[modal, modal] = np.diag(omega**2)

    def displacement_map(points: NDArray[np.float64]) -> NDArray[np.float64]:
        """Rows mapping q to the normal displacement at each point."""
        rows = np.zeros((len(points), n))
        rows[:, :n_rigid] = rigid_input(points)
        if model is not None:
            rows[:, modal] = model.mode_shapes_at(points)
        return rows

    force_input = displacement_map(xy)
    racket_mass = mass.copy()
    kinds = _kinds("rigid", n_rigid) + _kinds("mode", n_modes)
    coordinate_names = rigid_names + mode_names
    if support == "hand":
        hand = hand or Hand()
        if model is not None and model.support == "hand":
            raise InputError(
                "support 'hand' adds the hand to a free racket, but the modal model is already "
                "hand-held; give a free–free model, or use this one with 'free' or 'pinned'"
            )
        grip = np.array([[x, 0.0] for x in hand.grip_points_m])
        share = 1.0 / len(grip)
        relative = displacement_map(grip)
        relative[:, -1] = -1.0  # the grip's springs pull towards the arm
        # the handle's turn about the long axis at each grip point, flexible twist included
        # (the rigid roll's row is exactly 1): the fingers' roll spring and dashpot and the
        # hand's roll inertia act on it, as in the rig's hand (racketdyn.hand)
        across = np.array([0.0, _TWIST_PROBE_M])
        turn = (displacement_map(grip + across) - displacement_map(grip - across)) / (
            2.0 * _TWIST_PROBE_M
        )
        for row, twist in zip(relative, turn, strict=True):
            mass[:-1, :-1] += share * hand.hand_mass_kg * np.outer(row[:-1], row[:-1])
            mass += share * hand.roll_inertia_kgm2 * np.outer(twist, twist)
            stiffness += share * hand.stiffness_n_per_m * np.outer(row, row)
            stiffness += share * hand.roll_stiffness_nm_per_rad * np.outer(twist, twist)
            damping += share * hand.damping_ns_per_m * np.outer(row, row)
            damping += share * hand.roll_damping_nms_per_rad * np.outer(twist, twist)
        # the shoulder (hand.shoulder_stiffness_n_per_m, periods of a good fraction of a
        # second) stores nothing over a contact of a few milliseconds: left out, the arm is
        # free beyond the grip and the held system keeps its exact rigid-body motion (the
        # compiled engine's c_j; a shoulder's slow pole in its place halved the kernel's
        # convergence order on the axis)
        mass[-1, -1] = hand.arm_mass_kg
        kinds = kinds + _kinds("arm", 1)
        coordinate_names = (*coordinate_names, "arm")
    elif hand is not None:
        raise InputError(f"a hand is given but the support is {support!r}; use support='hand'")
    return ImpactSystem(
        support, coordinate_names, kinds, mass, damping, stiffness, force_input, xy, omega,
        mode_names, racket_mass,
    )  # fmt: skip
