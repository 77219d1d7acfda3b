"""The compound ball–racket system: a ball fixed on the strings (paper, section 3.2, Figs 8–9).

Kawazoe glued a ball to the centre of the string face and ran a modal test: a new mode
appeared (103 Hz, below the 120 Hz 2-node bending mode) in which ball and frame push and pull
against each other through the strings, and half its period matched the contact time of a
real impact.  This module builds that system linearly:

    ``[M 0; 0 m_B] q̈ + C q̇ + K q = 0``,  with the ball–string spring k and dashpot c between
    the ball coordinate u_B and the face's displacement under it, w_j = b_jᵀ q_r,

the racket's own equations ``M, C, K, b_j`` coming from :func:`racketdyn.impact.system.
impact_system` (rigid body + flexible modes, ``free``, ``pinned`` or ``hand``).  The racket's
string-bed (membrane) modes are left out: the ball–string spring already carries the strings'
deflection (the compound law F_GB is ball and string bed in series, section 3.4), so keeping
the membrane mode too would count the strings twice (as ``include_string_bed=False`` in the
approximate method).

The spring (:func:`ball_spring`): a ball stuck on the strings sits on a slightly preloaded bed
(its weight and the press that sticks it), so the small-amplitude stiffness is the tangent
dF_GB/dX of the compound law at that preload (:data:`PRELOAD_N`; the compound law's tangent
hardly changes over 0–20 N, which run.json records).  The dashpot gives the linear spring the
ball's coefficient of restitution on head-clamped strings e_BG:
``e = exp(−π ζ/√(1 − ζ²))``, i.e. ``ζ = −ln e / √(π² + ln² e)``, c = 2 ζ √(k m_B) — an
equivalent viscous loss for the ball's hysteresis, which is not viscous (assumption).

Analytic limits (tested): a rigid, infinitely heavy racket gives f = √(k/m_B)/2π; a rigid free
racket f = √(k (1/m_B + 1/M_r))/2π (M_r the reduced mass, eq 4); a flexible mode far above
leaves it unchanged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import Ball
from racketdyn.contact import (
    compound_law,
    local_compound_law,
    local_string_bed_law,
    string_bed_law,
    with_ball_string_cor,
)
from racketdyn.errors import InputError, require_positive
from racketdyn.impact.grid import resolve_modal_model
from racketdyn.impact.hand import Hand
from racketdyn.impact.system import ImpactSystem, impact_system
from racketdyn.modal import ModalModel
from racketdyn.racket import Racket, as_locations
from racketdyn.racket_modal.shapes import BALL_MODE_NAME

__all__ = [
    "BALL_MODE_NAME",
    "PRELOAD_N",
    "BallSpring",
    "CompoundSystem",
    "ball_spring",
    "compound_modes",
    "racket_modes",
    "resting_patch_radius",
    "restitution_damping_ratio",
    "small_amplitude_e_bg",
    "spring_split",
    "stiffer_frame",
]

PRELOAD_N = 5.0
"""Preload of the ball stuck on the strings, N: its weight (0.57 N) and the press that sticks
it, a few newtons (assumption; the compound law's tangent stiffness changes by ≈ 0.3 % from
0 to 20 N for the built-in racket, so the choice hardly matters)."""


_RIGID_TOL = 1e-6  # |λ| below this × the largest |λ| is a rigid-body motion
_POINT_TOL = 1e-9  # a face displacement below this × the mode's largest is a node (ratio NaN)


@dataclass(frozen=True)
class BallSpring:
    """The linear ball–string spring and dashpot of a ball fixed on the strings.

    Attributes
    ----------
    stiffness : float
        k = dF_GB/dX at the preload, N/m.
    damping_ratio : float
        ζ of the ball on head-clamped strings, from e_BG.
    preload_n : float
        Preload the tangent is taken at, N.
    deflection : float
        Compound deflection at the preload, m.
    source : str
        What the law was.
    bed_stiffness : float
        The string bed's part k_G = dF_G/dX at the preload, N/m (k is k_G in series with the
        ball's k_B: :func:`spring_split`).
    location : tuple of float or None
        Where the laws were taken (x, y), m; None: the face centre's laws.
    """

    stiffness: float
    damping_ratio: float
    preload_n: float
    deflection: float
    source: str
    bed_stiffness: float
    location: tuple[float, float] | None = None


def restitution_damping_ratio(cor: float) -> float:
    """Damping ratio of a linear spring–dashpot contact with coefficient of restitution ``cor``.

    A linear contact separates after half a damped period with speed ratio
    ``e = exp(−π ζ/√(1 − ζ²))``, so ``ζ = −ln e / √(π² + ln² e)``.

    Parameters
    ----------
    cor : float
        Coefficient of restitution, 0 < e ≤ 1.
    """
    if not 0.0 < cor <= 1.0:
        raise InputError(f"coefficient of restitution {cor:g}: must lie in (0, 1]")
    log_e = math.log(cor)
    return -log_e / math.sqrt(math.pi**2 + log_e**2)


def small_amplitude_e_bg(racket: Racket, ball: Ball) -> float:
    """e_BG of a ball held on the strings at small amplitude: the given e_BG, or ball + strings
    (:func:`racketdyn.contact.with_ball_string_cor`) at its slowest tabulated speed."""
    resolved = with_ball_string_cor(racket, ball)
    return float(resolved.e_bg_at(0.0))


def ball_spring(
    racket: Racket,
    ball: Ball,
    preload_n: float = PRELOAD_N,
    location: ArrayLike | None = None,
) -> BallSpring:
    """The small-amplitude ball–string spring: tangent of F_GB at a preload.

    Parameters
    ----------
    racket, ball : Racket, Ball
        String bed and ball laws (:func:`racketdyn.contact.compound_law`, section 3.4).
    preload_n : float
        Force the ball presses on the strings with, N (≥ 0).
    location : array_like (2,), optional
        Where the ball sits (x, y), m, for the string bed's law there
        (:func:`racketdyn.contact.local_compound_law`: stiffer towards the frame); default the
        face centre's law, the paper's one law.

    Returns
    -------
    BallSpring
    """
    preload = require_positive("preload", preload_n, allow_zero=True)
    if location is None:
        law, bed, where = compound_law(racket, ball), string_bed_law(racket, ball), None
    else:
        xy = as_locations(location)[0]
        where = (float(xy[0]), float(xy[1]))
        law = local_compound_law(racket, ball, where)
        bed = local_string_bed_law(racket, ball, where)
    deflection = float(law.deflection(preload))
    if not math.isfinite(deflection):
        raise InputError(f"preload {preload:g} N: beyond the compound law's range")
    return BallSpring(
        float(law.stiffness(deflection)),
        restitution_damping_ratio(small_amplitude_e_bg(racket, ball)),
        preload,
        deflection,
        law.source,
        float(bed.stiffness(bed.deflection(preload))),
        where,
    )


@dataclass(frozen=True, eq=False)
class CompoundSystem:
    """The elastic modes of a racket (with or without a ball fixed on its strings).

    Attributes
    ----------
    support : str
        ``free``, ``pinned`` or ``hand``.
    location : ndarray (2,)
        Where the ball sits (x, y), m.
    frequency : ndarray (n_modes,)
        Undamped natural frequencies ``abs(λ)/2π``, Hz, ascending.
    damping_ratio : ndarray (n_modes,)
        ``−Re(λ)/abs(λ)``.
    names : tuple of str
        :data:`BALL_MODE_NAME` for the ball mode, else the racket coordinate with the largest
        share of the mode's kinetic energy (a flexible mode's name, ``rigid body (pitch)`` …,
        ``hand–arm``).
    ball_to_frame_ratio : ndarray (n_modes,)
        Re(u_B / w_j): the ball's displacement over the frame's under it (negative: they move
        against each other); NaN where the mode has a node at the ball (no racket: NaN).
    ball_energy_share : ndarray (n_modes,)
        The ball's share of the mode's kinetic energy (0 without a ball).
    shapes : ndarray (n_coordinates, n_modes), complex
        Displacement part of the eigenvectors, scaled so the largest entry is 1.
    coordinate_names : tuple of str
        The coordinates of ``shapes`` (the racket's, then ``ball``).
    rows : ndarray (n_points, n_coordinates)
        Map the coordinates to the face's normal displacement at each point (the ball's point
        first, then the extra points).
    with_ball : bool
        Whether a ball is on the strings.
    mass, damping, stiffness : ndarray (n_coordinates, n_coordinates)
        M, C and K of the whole system (the ball's coordinate last).
    """

    support: str
    location: NDArray[np.float64]
    frequency: NDArray[np.float64]
    damping_ratio: NDArray[np.float64]
    names: tuple[str, ...]
    ball_to_frame_ratio: NDArray[np.float64]
    ball_energy_share: NDArray[np.float64]
    shapes: NDArray[np.complex128]
    coordinate_names: tuple[str, ...]
    rows: NDArray[np.float64]
    with_ball: bool
    mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    stiffness: NDArray[np.float64]

    @property
    def ball_mode(self) -> int:
        """Index of the ball mode (the largest ball energy share); −1 without a ball."""
        if not self.with_ball or self.frequency.size == 0:
            return -1
        return int(np.argmax(self.ball_energy_share))

    @property
    def ball_frequency(self) -> float:
        """Frequency of the ball mode, Hz (NaN without a ball)."""
        k = self.ball_mode
        return float(self.frequency[k]) if k >= 0 else math.nan

    @property
    def half_period(self) -> float:
        """Half the ball mode's damped period, 1/(2 f_d), s — the contact time of section 3.2."""
        k = self.ball_mode
        if k < 0:
            return math.nan
        damped = self.frequency[k] * math.sqrt(1.0 - self.damping_ratio[k] ** 2)
        return float(0.5 / damped)

    def load(self, excitation: int | ArrayLike) -> NDArray[np.float64]:
        """The generalised force of a unit blow: a point's row (an index), or a load vector."""
        if isinstance(excitation, int | np.integer):
            return np.asarray(self.rows[int(excitation)], dtype=float)
        load = np.asarray(excitation, dtype=float)
        if load.shape != (self.mass.shape[0],):
            raise InputError(f"a load vector needs {self.mass.shape[0]} coordinates")
        return load

    def string_blow(self, hammer: int, share: float, ball_fraction: float) -> NDArray[np.float64]:
        """The load of a unit blow on the strings near the ball, shared through the strings.

        The strings are folded into the ball's spring, so a blow on them is shared out by hand:
        the part ``share`` that the strings under the ball take (:func:`racketdyn.contact.
        net_share`) reaches a massless string patch between the ball's spring k_B and the
        bed's k_G and splits as ``k_B/(k_B + k_G)`` (``ball_fraction``) to the ball and the
        rest to the frame under it; the remainder ``1 − share`` goes to the frame at the
        hammer's point.  The parts add up to the blow (momentum is kept).

        Parameters
        ----------
        hammer : int
            Index of the hammer's point.
        share : float
            Share of the blow the patch under the ball takes, 0–1.
        ball_fraction : float
            k_B/(k_B + k_G), 0–1.
        """
        load = (1.0 - share) * self.rows[hammer] + share * (1.0 - ball_fraction) * self.rows[0]
        if self.with_ball:
            load = load.copy()
            load[-1] += share * ball_fraction
        return np.asarray(load, dtype=float)

    def receptance(
        self, frequency_hz: ArrayLike, excitation: int | ArrayLike, response: int
    ) -> NDArray[np.complex128]:
        """Receptance between two of the points, ``w_r/F_e`` (m/N), by a direct solve.

        ``H(ω) = r_rᵀ (K − ω² M + iω C)⁻¹ r_e``; at ω = 0 a free system has no finite
        receptance (NaN).

        Parameters
        ----------
        frequency_hz : array_like
            Frequencies, Hz.
        excitation : int or array_like
            Index of the point struck (0: the ball's point), or a load vector
            (:meth:`string_blow`).
        response : int
            Index of the point.
        """
        omega = 2.0 * np.pi * np.atleast_1d(np.asarray(frequency_hz, dtype=float))
        drive, out = self.load(excitation), self.rows[response]
        values = np.empty(omega.size, dtype=complex)
        for i, w in enumerate(omega):
            matrix = self.stiffness - w**2 * self.mass + 1j * w * self.damping
            try:
                values[i] = out @ np.linalg.solve(matrix, drive)
            except np.linalg.LinAlgError:
                values[i] = np.nan
        return values

    def impulse_acceleration(
        self, times: ArrayLike, excitation: int | ArrayLike, response: int
    ) -> NDArray[np.float64]:
        """Acceleration at ``response`` after a unit impulse at ``excitation``, m/s² per N·s.

        The first-order system ``ẋ = A x`` from ``q = 0, q̇ = M⁻¹ r_e`` is stepped exactly with
        ``exp(A Δt)`` (scipy's ``expm``; no eigenvectors: a free racket's rigid-body motion
        makes A defective); the acceleration is ``r_rᵀ M⁻¹ (−K q − C q̇)``.

        Parameters
        ----------
        times : array_like
            Equally spaced times from 0, s.
        excitation : int or array_like
            Index of the point struck, or a load vector (:meth:`string_blow`).
        response : int
            Index of the point.
        """
        return self.blow_acceleration(times, excitation, response, 0.0)

    def blow_acceleration(
        self, times: ArrayLike, excitation: int | ArrayLike, response: int, duration_s: float
    ) -> NDArray[np.float64]:
        """Acceleration at ``response`` after a half-sine blow of unit impulse, m/s² per N·s.

        The force ``F(t) = (π/2T) sin(πt/T)`` for ``0 ≤ t ≤ T`` (impulse 1 N·s) acts at
        ``excitation``: a hammer on the strings, whose contact lasts a few milliseconds (the
        paper, section 2: the blow's spectrum "does not reach a high frequency"; Fig. 8b).  The
        force is generated by a two-state oscillator appended to ``ẋ = A x``, so the whole is
        stepped exactly with ``exp(A Δt)`` (to T exactly, then free); T = 0 is the unit
        impulse (``q̇(0) = M⁻¹ r_e``).  The acceleration is ``r_rᵀ M⁻¹ (r_e F − K q − C q̇)``.

        Parameters
        ----------
        times : array_like
            Equally spaced times from 0, s.
        excitation : int or array_like
            Index of the point struck, or a load vector (:meth:`string_blow`).
        response : int
            Index of the point.
        duration_s : float
            Length T of the half-sine, s (0: an impulse).
        """
        t = np.asarray(times, dtype=float)
        n = self.mass.shape[0]
        if t.size < 2 or n == 0:
            return np.zeros(t.size)
        duration = require_positive("blow duration", duration_s, allow_zero=True)
        step = float(t[1] - t[0])
        m_inv = np.linalg.inv(self.mass)
        drive = m_inv @ self.load(excitation)
        out = self.rows[response] @ np.hstack([-m_inv @ self.stiffness, -m_inv @ self.damping])
        free = np.block(
            [[np.zeros((n, n)), np.eye(n)], [-m_inv @ self.stiffness, -m_inv @ self.damping]]
        )
        values = np.empty(t.size)
        if duration == 0.0:
            state = np.concatenate([np.zeros(n), drive])
            propagate = scipy.linalg.expm(free * step)
            for i in range(t.size):
                values[i] = out @ state
                state = propagate @ state
            return values
        # [x; s; c] with s = sin(Ωt), c = cos(Ωt): ṡ = Ω c, ċ = −Ω s; F = a s
        omega, amplitude = math.pi / duration, math.pi / (2.0 * duration)
        forced = np.zeros((2 * n + 2, 2 * n + 2))
        forced[: 2 * n, : 2 * n] = free
        forced[n : 2 * n, 2 * n] = amplitude * drive
        forced[2 * n, 2 * n + 1], forced[2 * n + 1, 2 * n] = omega, -omega
        start = np.zeros(2 * n + 2)
        start[-1] = 1.0
        during = t < duration
        state = start
        propagate = scipy.linalg.expm(forced * step)
        for i in np.flatnonzero(during).tolist():
            force = amplitude * state[2 * n]
            values[i] = out @ state[: 2 * n] + self.rows[response] @ drive * force
            state = propagate @ state
        after = np.flatnonzero(~during)
        if after.size:
            at_end = (scipy.linalg.expm(forced * duration) @ start)[: 2 * n]
            state = scipy.linalg.expm(free * (t[after[0]] - duration)) @ at_end
            propagate = scipy.linalg.expm(free * step)
            for i in after.tolist():
                values[i] = out @ state
                state = propagate @ state
        return values

    def modal_parts(
        self, times: ArrayLike, response: ArrayLike, start_s: float
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Split a free response into the system's own damped modes, from ``start_s`` on.

        After the blow the response is a sum of the modes' damped oscillations
        ``e^{σt}(a cos ω_d t + b sin ω_d t)`` (rigid-body motion adds no acceleration), so a
        least-squares fit on them is exact; the amplitude is ``√(a² + b²)`` at ``start_s``.

        Parameters
        ----------
        times : array_like
            Times of the response, s.
        response : array_like
            A response of this system after a blow that ends at ``start_s``.
        start_s : float
            When the blow ends, s.

        Returns
        -------
        frequency : ndarray (n,)
            The oscillating modes' frequencies abs(λ)/2π, Hz.
        amplitude : ndarray (n,)
            Their amplitudes at ``start_s``, in the response's unit.
        parts : ndarray (n, n_times)
            Each mode's part of the response (0 before ``start_s``).
        decay : ndarray (n,)
            Their decay rates −Re λ, 1/s (the envelope is ``amplitude·e^{−decay·(t − start)}``).
        """
        t = np.asarray(times, dtype=float)
        values = np.asarray(response, dtype=float)
        n = self.mass.shape[0]
        m_inv = np.linalg.inv(self.mass)
        first_order = np.block(
            [[np.zeros((n, n)), np.eye(n)], [-m_inv @ self.stiffness, -m_inv @ self.damping]]
        )
        lam = np.linalg.eigvals(first_order)
        lam = np.sort_complex(lam[lam.imag > _RIGID_TOL * max(1.0, float(np.abs(lam).max()))])
        after = t >= start_s
        local = t[after] - start_s
        columns = []
        for value in lam:
            decay = np.exp(value.real * local)
            columns += [decay * np.cos(value.imag * local), decay * np.sin(value.imag * local)]
        basis = np.column_stack(columns)
        fit = np.linalg.lstsq(basis, values[after], rcond=None)[0]
        parts = np.zeros((lam.size, t.size))
        for k in range(lam.size):
            parts[k, after] = basis[:, 2 * k : 2 * k + 2] @ fit[2 * k : 2 * k + 2]
        return np.abs(lam) / (2 * np.pi), np.hypot(fit[0::2], fit[1::2]), parts, -lam.real

    def frequency_of(self, name: str) -> float:
        """Frequency of the mode named ``name``, Hz (NaN if there is none)."""
        return next(
            (float(f) for f, n in zip(self.frequency, self.names, strict=True) if n == name),
            math.nan,
        )


def resting_patch_radius(racket: Racket) -> float:
    """Radius of the patch of strings a ball resting on the bed pushes, m: half the larger
    string spacing (its lowest point sits in a cell of the weave, on the two mains and two
    crosses around it).  Used to share a hammer's blow on the strings
    (:meth:`CompoundSystem.string_blow`)."""
    return 0.5 * max(racket.strings.spacing_m(racket.head))


def spring_split(spring: BallSpring) -> tuple[float, float]:
    """The ball's and the bed's parts of the spring at its preload, k_B and k_G (N/m).

    ``1/k = 1/k_B + 1/k_G`` (in series, section 3.4); k_G is the string-bed law's tangent at
    the preload (:attr:`BallSpring.bed_stiffness`), k_B what is left.
    """
    k_bed = spring.bed_stiffness
    return 1.0 / (1.0 / spring.stiffness - 1.0 / k_bed), k_bed


def racket_modes(
    racket: Racket,
    model: ModalModel | None,
    support: str,
    location: ArrayLike,
    spring: BallSpring | None,
    ball: Ball | None = None,
    hand: Hand | None = None,
    points: ArrayLike = (),
) -> CompoundSystem:
    """Elastic modes of the racket, with a ball fixed at ``location`` if a spring is given.

    Parameters
    ----------
    racket : Racket
        Mass properties.
    model : ModalModel or None
        The racket's flexible modes (mass-normalised); string-bed modes are left out (module
        docstring), and a measured model's shapes on the strings are the frame's motion under
        the bed (:func:`racketdyn.impact.grid.resolve_modal_model`); None for a rigid racket.
    support : {"free", "pinned", "hand"}
        Support (:func:`racketdyn.impact.system.impact_system`).
    location : array_like (2,)
        Where the ball sits (x, y), m.
    spring : BallSpring or None
        The ball–string spring; None for the racket alone.
    ball : Ball, optional
        The ball (its mass m_B, kg); default :class:`~racketdyn.ball.Ball`.
    hand : Hand, optional
        The hand of ``support="hand"``.
    points : array_like (n, 2), optional
        More points whose responses are wanted (a hammer, an accelerometer), m.
    """
    xy = as_locations(location)
    if xy.shape[0] != 1:
        raise InputError("`point`: give one point x,y for the ball")
    extra = np.asarray(points, dtype=float).reshape(-1, 2)
    frame = resolve_modal_model(racket, model, include_string_bed=False)
    system = impact_system(
        racket, frame, support, np.vstack([xy, extra]), hand if support == "hand" else None
    )
    return compound_modes(system, spring, (ball or Ball()).mass_kg)


def compound_modes(
    system: ImpactSystem, spring: BallSpring | None, ball_mass: float
) -> CompoundSystem:
    """Elastic modes of a racket's equations with a ball on a spring at its (one) point.

    Parameters
    ----------
    system : ImpactSystem
        The racket's ``M, C, K`` and ``b_j`` at its points, the ball's first (an infinitely
        heavy, rigid racket has no coordinates: then only the ball moves).
    spring : BallSpring or None
        The ball–string spring and dashpot; None for the racket alone.
    ball_mass : float
        m_B, kg.

    Returns
    -------
    CompoundSystem
    """
    mass, damping, stiffness = system.mass, system.damping, system.stiffness
    rows = system.force_input
    row = rows[0]
    names = system.coordinate_names
    if spring is not None:
        m_b = require_positive("ball mass", ball_mass)
        n = system.n_coordinates + 1
        link = np.concatenate([-row, [1.0]])  # u_B − w_j
        c = 2.0 * spring.damping_ratio * math.sqrt(spring.stiffness * m_b)
        mass = scipy.linalg.block_diag(mass, [[m_b]])
        damping = scipy.linalg.block_diag(damping, [[0.0]]) + c * np.outer(link, link)
        stiffness = scipy.linalg.block_diag(stiffness, [[0.0]]) + spring.stiffness * np.outer(
            link, link
        )
        rows = np.hstack([rows, np.zeros((rows.shape[0], 1))])
        names = (*names, "ball")
    n = len(names)
    location = system.locations[0]
    if n == 0:
        return _empty(system.support, location, spring is not None, rows)
    first_order = np.block(
        [
            [np.zeros((n, n)), np.eye(n)],
            [-np.linalg.solve(mass, stiffness), -np.linalg.solve(mass, damping)],
        ]
    )
    eigenvalues, vectors = np.linalg.eig(first_order)
    size = np.abs(eigenvalues)
    elastic = (size > _RIGID_TOL * max(float(size.max(initial=0.0)), 1.0)) & (
        eigenvalues.imag > 0.0
    )
    order = np.flatnonzero(elastic)[np.argsort(size[elastic])]
    lam = eigenvalues[order]
    shapes = vectors[:n, order]
    shapes = shapes / shapes[np.argmax(np.abs(shapes), axis=0), np.arange(order.size)]
    kinetic = np.real(np.conj(shapes) * (mass @ shapes))
    share = kinetic / kinetic.sum(axis=0)
    face = rows[0] @ shapes
    biggest = np.abs(shapes).max(axis=0)
    if spring is not None:
        ball = shapes[-1]
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(np.abs(face) > _POINT_TOL * biggest, np.real(ball / face), np.nan)
        ball_share = share[-1]
    else:
        ratio = np.full(order.size, np.nan)
        ball_share = np.zeros(order.size)
    kinds = dict(zip(system.coordinate_names, system.coordinate_kinds, strict=True))
    mode_names = []
    ball_mode = int(np.argmax(ball_share)) if spring is not None and order.size else -1
    for k in range(order.size):
        if k == ball_mode:
            mode_names.append(BALL_MODE_NAME)
            continue
        racket_share = share[: system.n_coordinates, k]
        coordinate = system.coordinate_names[int(np.argmax(racket_share))] if n > 1 else "ball"
        kind = kinds.get(coordinate, "")
        if kind in ("rigid", "arm"):
            held = "arm" in kinds.values()
            coordinate = f"{'hand–arm' if held else 'rigid body'} ({coordinate})"
        mode_names.append(coordinate)
    plain = list(mode_names)
    for k, name in enumerate(plain):  # one name per mode: number the repeats
        repeats = [j for j, other in enumerate(plain) if other == name]
        if len(repeats) > 1:
            mode_names[k] = f"{name} {repeats.index(k) + 1}"
    return CompoundSystem(
        system.support,
        location,
        size[order] / (2.0 * np.pi),
        -lam.real / size[order],
        tuple(mode_names),
        np.asarray(ratio, dtype=float),
        np.asarray(ball_share, dtype=float),
        shapes,
        names,
        rows,
        spring is not None,
        mass,
        damping,
        stiffness,
    )


def _empty(
    support: str, location: NDArray[np.float64], with_ball: bool, rows: NDArray[np.float64]
) -> CompoundSystem:
    none, square = np.zeros(0), np.zeros((0, 0))
    return CompoundSystem(
        support, location, none, none, (), none, none, np.zeros((0, 0), complex), (),
        rows, with_ball, square, square, square,
    )  # fmt: skip


def stiffer_frame(model: ModalModel, factor: float = 4.0) -> ModalModel:
    """The same racket with its frame ``factor`` times stiffer and the same mass.

    Every flexible mode's stiffness scales by ``factor`` with the mass unchanged, so the
    frequencies scale by √factor and the mass-normalised shapes stay as they are (paper,
    section 3.2: "a racket with almost identical mass, but approximately 4 times the frame
    rigidity").  String-bed modes are left as they are (the strings are not the frame).

    Parameters
    ----------
    model : ModalModel
        The racket's modes.
    factor : float
        Stiffness factor (> 0).
    """
    scale = math.sqrt(require_positive("frame stiffness factor", factor))
    frequency = np.where(
        np.array(model.kinds) == "string-bed", model.frequency, model.frequency * scale
    )
    return replace(model, frequency=frequency, source=f"{model.source}, frame ×{factor:g} stiffer")
