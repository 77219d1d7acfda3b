"""Oblique impacts and spin: the tangential ball–string contact (issue 5).

A ball meets the string bed at an angle θ to the face normal with spin ω.  The normal part of
the impact is the transient simulation of :mod:`racketdyn.impact.transient`; this module adds
the tangential interaction of ball and strings and integrates it along the normal force history
F_n(t) of that simulation.

Axes and signs
--------------
``n̂`` is the face normal pointing out of the face towards the incoming ball, ``t̂`` a unit vector
in the face plane chosen by the caller (for example along the long axis towards the tip).  The
incoming ball velocity is ``v (−cos θ n̂ + sin θ t̂)``: the ball approaches the face with the
normal speed ``v cos θ`` and moves along the face with the tangential velocity ``v_t = v sin θ``
(θ > 0: along +t̂).  Spin ω is the angular velocity about ``n̂ × t̂``, so that ω > 0 is the sense
of a ball *rolling along +t̂* on the face.  The velocity of the ball's contact point relative to
the face is then

    ``u = v_t − R ω − V_f``,

with R the ball radius and V_f the face's own tangential velocity (``racket_tangential_speed``).
A ball with u = 0 rolls.  Example: a forehand with n̂ towards the net and t̂ up; a racket face
brushing up the back of the ball (V_f > 0) makes u < 0, the friction force pushes the ball up
(+t̂) and drives ω negative, which about n̂ × t̂ is topspin for the outgoing ball.  Outgoing
angles are measured from the face normal in the same sense: ``atan2(v_t,out, v_n,out)``, with
v_n,out the rebound speed away from the face.

Model
-----
Ball: mass m, radius R, moment of inertia ``I = k_I m R²``.  Default ``k_I = 0.55``, the model
value Cross uses for a tennis ball, a thick hollow shell (R. Cross, "Grip-slip behavior of a
bouncing ball", Am. J. Phys. 70, 1093 (2002); "Bounce of a spinning ball near normal
incidence", Am. J. Phys. 73, 914 (2005)).  For comparison, a uniform shell of outer radius
33.5 mm and a 3–4 mm wall gives 0.59–0.61; a thin shell 2/3, a solid ball 2/5.

Tangential contact (:class:`TangentialContact`), an elastic–Coulomb element between the ball's
contact point and the face: a tangential spring of stiffness k_t (the strings' lateral stiffness
in series with the shear of the ball's wall) carries the tangential force ``F_t = −k_t s``, s its
deflection, and the spring slides on the strings with Coulomb friction μ when the force it would
need exceeds μ F_n: ``|k_t s| ≤ μ F_n(t)`` always.  With ``J_t(t) = ∫ F_t dt`` (the tangential
impulse on the ball),

    ``m dv_t/dt = F_t``,   ``I dω/dt = −R F_t``,   so   ``m_eff du/dt = F_t``,
    ``m_eff = m / (1 + m R²/I) = m k_I / (1 + k_I)``,

and ``v_t = v_t,in + J_t/m``, ``ω = ω_in − R J_t/I``, ``J_t = m_eff (u − u_in)``: the whole
tangential problem is a single degree of freedom, a mass m_eff on the elastic–Coulomb element.

* **Grip** (the spring holds): ``ds/dt = u`` and ``m_eff du/dt = −k_t s``, harmonic motion of
  period ``2π √(m_eff/k_t)``; it lasts while ``|k_t s| < μ F_n``.
* **Slide**: the spring sits at its limit, ``s = σ μ F_n/k_t`` (σ = ±1, the sliding direction),
  ``F_t = −σ μ F_n`` and the ball slides at ``w = u − ds/dt = u − σ μ Ḟ_n/k_t`` with ``σ w > 0``.
  Sliding stops when ``σ w`` falls to zero; gripping stops when ``|k_t s|`` reaches ``μ F_n``.
* ``k_t = inf`` is the rigid grip of the classical models (Brody): slide until u = 0, then roll.

Energy.  In the face frame the tangential energy is ``E = ½ m (v_t − V_f)² + ½ I ω² + ½ k_t s²``
``= ½ m_eff u² + ½ k_t s² + const``: constant while gripping, falling at the rate
``μ F_n σ w ≥ 0`` while sliding.  So the friction loss plus the energy left in the spring never
exceed ``½ m_eff u_in²``.  The spring energy at separation is zero when F_n(T) = 0 (the limit
μ F_n forces the spring to let go as the ball leaves); it is reported for histories that end
above zero.

Defaults (:class:`TangentialContact`)
-------------------------------------
* μ = 0.4: the order of the sliding friction Cross reports for a tennis ball on strings
  (Am. J. Phys. 73, 2005), taken as an assumed model value: ball–string friction depends on the
  string material and on the direction (lower along a string than across it).
* k_t = 1.0·10⁴ N/m, chosen so that the grip oscillation has a half period
  ``π √(m_eff/k_t)`` ≈ 4.5 ms (with the default ball, m_eff = 20.5 g), the middle of the
  4–5 ms contact times of ordinary strokes (docs/references.md).  A ball that grips during the
  contact then springs back within it and leaves with its contact-point velocity reversed (spin
  beyond rolling), the grip–reverse behaviour Cross measured (Am. J. Phys. 70, 2002).  The order
  is that of the strings: the mains under the ball (≈ 4 of them, 2 S₀/L ≈ 3 kN/m each for the
  built-in racket, L the half length) moving sideways give ≈ 13 kN/m, in series with the
  ball's shear.

Modelling assumptions (one-way coupling)
----------------------------------------
1. The normal dynamics drives the tangential, not the reverse: F_n(t) is that of the normal
   impact alone.  The tangential force acts in the face plane, through the racket's mid-plane,
   so it exerts no moment that moves the face along its normal; the string bed's tangential
   deflection (at most |u_in| √(m_eff/k_t), 14 mm at 20 m/s and 30° with the defaults, against
   strings 240–330 mm long) changes the normal stiffness only at second order in s/L (< 1 %).
   Cross's finding that the normal force acts a little behind the ball's centre (extra spin,
   Am. J. Phys. 70, 2002) is left out, and the lever arm of the friction force is the
   undeformed radius R.
2. The racket does not move in its plane: the face's tangential velocity V_f is constant.  The
   tangential impulse is shared between the ball's m_eff ≈ 20 g and the racket's in-plane
   effective mass at the face: its whole mass (0.36 kg) for a force along the long axis, ≈ 0.18 kg
   across it at the centre of a free racket (yaw inertia ≈ pitch + roll inertia).  Neglecting
   that motion overstates the tangential impulse by ``m_eff/M_t`` ≈ 6 % along and ≈ 11 % across
   the long axis, less for a hand-held racket; in-plane frame modes are not excited.

Caveat: the grip is lossless
----------------------------
The spring has no damping, so whatever it stores while gripping it gives back.  With the
default k_t the grip half period matches the contact time, and a ball that grips early leaves
with its contact-point velocity almost reversed: 20 m/s at 30° on the face centre of the
built-in racket gives u_out/u_in = −0.96, R ω/v_t = 4.2, 378 rad/s.  The outgoing spin is very
sensitive to k_t (157–378 rad/s for k_t from 3·10³ to 10⁶ N/m in that case; 193 rad/s for the
rigid grip).  Treat spin from the default as the upper end of the model's range until k_t, and
a tangential loss, are fitted to measured rebound spin.

Integration
-----------
The equations are linear within each phase, so each phase is integrated in closed form: a grip
phase is the harmonic oscillator's exact solution, a slide phase ``u(t) = u_a − σ μ (P(t) −
P(t_a))/m_eff`` with P the antiderivative of F_n.  The phase changes are located by bracketing
on a grid of at least 64 points per grip period and ``_MIN_CHECKPOINTS`` over the contact, then
Brent's method to machine precision.  The only discretisation error is that of F_n itself:
sampled histories (:meth:`NormalForce.from_samples`, e.g. a :class:`TransientImpact`) are
interpolated by a not-a-knot cubic spline, fourth order in the sample spacing
(``tests/test_oblique.py`` measures the order).  With the transient simulation's 400 samples
per contact time the spline's impulse matches the ball's momentum change to ≈ 1e-10.
"""

from __future__ import annotations

import itertools
import logging
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

from racketdyn.ball import Ball
from racketdyn.errors import InputError, require_finite, require_positive, require_range
from racketdyn.impact.result import STATUS_OK
from racketdyn.impact.transient import TransientImpact, simulate_impact
from racketdyn.racket import Racket

if TYPE_CHECKING:
    import xarray as xr

__all__ = [
    "DEFAULT_TANGENTIAL_CONTACT",
    "NormalForce",
    "ObliqueCurve",
    "ObliqueImpact",
    "TangentialContact",
    "TangentialImpact",
    "oblique_curve",
    "require_friction",
    "require_tangential_stiffness",
    "simulate_oblique",
    "simulate_tangential",
]

log = logging.getLogger(__name__)

Phase = Literal["grip", "slide"]
FloatFunction = Callable[[NDArray[np.float64]], NDArray[np.float64]]

_HISTORY_SAMPLES = 400  # history samples over the contact
_MIN_CHECKPOINTS = 2000  # bracketing grid for the phase changes over the contact
_CHECKPOINTS_PER_PERIOD = 64  # … and at least this many per grip period
_END_FRACTION = 1e-12  # a phase change this close to separation is separation
_LIMIT_TOLERANCE = 1e-12  # relative slack on |k_t s| ≤ μ F_n before a grip lets go
_MAX_PHASES = 10_000


# --- inputs --------------------------------------------------------------------------------------
def require_friction(name: str, value: object) -> float:
    """The ball–string friction coefficient μ, a finite number ≥ 0, else InputError naming
    ``name`` (the caller's parameter) and the fix."""
    try:
        mu = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        mu = math.nan
    if isinstance(value, bool) or not math.isfinite(mu) or mu < 0:
        raise InputError(
            f"{name} is the ball–string friction coefficient μ: give a number of 0 or more "
            f"(got {value!r}; 0.4 is the order Cross measured)"
        )
    return mu


def require_tangential_stiffness(name: str, value: object) -> float:
    """The tangential stiffness k_t, N/m, above 0 (``inf``: the rigid grip), else InputError
    naming ``name`` (the caller's parameter) and the fix."""
    try:
        stiffness = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        stiffness = math.nan
    if isinstance(value, bool) or math.isnan(stiffness) or stiffness <= 0:
        raise InputError(
            f"{name} is the tangential stiffness k_t of strings and ball: give a number above "
            f"0 in N/m, or inf for a rigid grip (got {value!r}; 1e4 N/m by default)"
        )
    return stiffness


@dataclass(frozen=True)
class TangentialContact:
    """The elastic–Coulomb tangential contact of ball and strings.

    Parameters
    ----------
    friction_coefficient : float
        Coulomb friction coefficient μ of the ball sliding on the strings, ≥ 0 (default 0.4, the
        order Cross reports for a tennis ball on strings, Am. J. Phys. 73, 2005; an assumed
        model value).
    stiffness_n_per_m : float
        Tangential stiffness k_t of the strings' lateral give and the ball's shear in series,
        N/m, > 0; ``inf`` for the rigid grip (slide, then roll).  Default 1.0·10⁴ N/m: the grip
        oscillation's half period π √(m_eff/k_t) is then ≈ 4.5 ms with the default ball, of the
        order of the contact time (module docstring).
    inertia_factor : float
        k_I = I / (m R²) of the ball, 0 < k_I ≤ 2/3 (default 0.55, Cross's model value for a
        tennis ball; 2/3 is a thin shell, 2/5 a solid ball).
    """

    friction_coefficient: float = 0.4
    stiffness_n_per_m: float = 1.0e4
    inertia_factor: float = 0.55

    def __post_init__(self) -> None:
        require_friction("`friction_coefficient`", self.friction_coefficient)
        require_tangential_stiffness("`stiffness_n_per_m`", self.stiffness_n_per_m)
        require_range("`inertia_factor` I/(m R²)", self.inertia_factor, 0.0, 2.0 / 3.0)
        if self.inertia_factor == 0:
            raise InputError(
                "`inertia_factor` I/(m R²) must be above 0 (0.55 for a tennis ball, 2/3 for "
                "a thin shell)"
            )

    @property
    def rigid(self) -> bool:
        """True for the rigid grip (k_t = inf)."""
        return math.isinf(self.stiffness_n_per_m)

    def effective_mass(self, ball: Ball) -> float:
        """m_eff = m k_I/(1 + k_I): the ball's mass at its contact point along the face, kg."""
        return ball.mass_kg * self.inertia_factor / (1.0 + self.inertia_factor)

    def grip_period(self, ball: Ball) -> float:
        """Period 2π √(m_eff/k_t) of the tangential oscillation while gripping, s (0: rigid)."""
        return 2.0 * math.pi * math.sqrt(self.effective_mass(ball) / self.stiffness_n_per_m)


DEFAULT_TANGENTIAL_CONTACT = TangentialContact()
"""The default tangential contact (μ = 0.4, k_t = 1.0·10⁴ N/m, k_I = 0.55)."""


@dataclass(frozen=True, eq=False)
class NormalForce:
    """The normal contact force F_n(t) from first contact (t = 0) to separation (t = T).

    Build it with :meth:`from_impact`, :meth:`from_samples` or :meth:`half_sine`.

    Attributes
    ----------
    contact_time_s : float
        T, s.
    impulse_ns : float
        ∫₀ᵀ F_n dt, N·s.
    peak_force_n : float
        Largest F_n, N.
    force, rate, integral : callable
        Vectorised F_n(t) (N), dF_n/dt (N/s) and ∫₀ᵗ F_n dt (N·s), for t in s.
    source : str
        Where the history came from.
    """

    contact_time_s: float
    impulse_ns: float
    peak_force_n: float
    force: FloatFunction
    rate: FloatFunction
    integral: FloatFunction
    source: str = ""

    @classmethod
    def half_sine(cls, peak_force_n: float, contact_time_s: float) -> NormalForce:
        """``F_n = F_max sin(π t/T)``: the approximate method's pulse (eq 11), exact functions.

        Parameters
        ----------
        peak_force_n : float
            F_max, N.
        contact_time_s : float
            T, s.
        """
        peak = require_positive("peak force", peak_force_n)
        duration = require_positive("contact time", contact_time_s)
        w = math.pi / duration

        def force(t: NDArray[np.float64]) -> NDArray[np.float64]:
            return np.asarray(peak * np.sin(w * np.asarray(t)))

        def rate(t: NDArray[np.float64]) -> NDArray[np.float64]:
            return np.asarray(peak * w * np.cos(w * np.asarray(t)))

        def integral(t: NDArray[np.float64]) -> NDArray[np.float64]:
            return np.asarray(peak / w * (1.0 - np.cos(w * np.asarray(t))))

        return cls(duration, 2.0 * peak / w, peak, force, rate, integral, "half-sine")

    @classmethod
    def from_samples(
        cls, time_s: ArrayLike, force_n: ArrayLike, source: str = "samples"
    ) -> NormalForce:
        """A not-a-knot cubic spline through samples of F_n (fourth order in the spacing).

        Parameters
        ----------
        time_s : array_like, shape (n,)
            Sample times, s, non-decreasing (repeated times, as at the phase boundaries of a
            transient history, are merged); the contact starts at the first.
        force_n : array_like, shape (n,)
            Normal force at those times, N, ≥ 0.
        source : str
            Where the samples came from.
        """
        t = np.asarray(time_s, dtype=float)
        f = np.asarray(force_n, dtype=float)
        if t.ndim != 1 or t.shape != f.shape:
            raise InputError("normal force history: give 1-D time and force arrays of one length")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(f))):
            raise InputError("normal force history: times and forces must be finite")
        step = np.diff(t)
        if np.any(step < 0):
            raise InputError("normal force history: times must not decrease")
        keep = np.concatenate([[True], step > 0])
        t, f = t[keep] - t[0], f[keep]
        if t.size < 4:
            raise InputError("normal force history: give at least 4 distinct sample times")
        if np.any(f < 0):
            raise InputError("normal force history: the contact force must be ≥ 0 (N)")
        spline = CubicSpline(t, f)
        derivative = spline.derivative()
        antiderivative = spline.antiderivative()
        return cls(
            contact_time_s=float(t[-1]),
            impulse_ns=float(antiderivative(t[-1])),
            peak_force_n=float(f.max()),
            force=lambda x: np.asarray(spline(x)),
            rate=lambda x: np.asarray(derivative(x)),
            integral=lambda x: np.asarray(antiderivative(x)),
            source=source,
        )

    @classmethod
    def from_impact(cls, impact: TransientImpact) -> NormalForce:
        """The force history of a simulated normal impact (:func:`simulate_impact`)."""
        if impact.status != STATUS_OK:
            raise InputError(f"the normal impact has no force history: {impact.status}")
        return cls.from_samples(impact.time_s, impact.force_n, "transient normal impact")


# --- results -------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class TangentialImpact:
    """The tangential part of an impact, from first contact to separation.

    Velocities are along t̂, spins about n̂ × t̂ (positive: the sense of rolling along +t̂);
    energies are in the frame of the face (moving at ``face_speed_mps`` along t̂).

    Attributes
    ----------
    incoming_tangential_speed_mps, outgoing_tangential_speed_mps : float
        Ball centre velocity along t̂ before and after, m/s.
    incoming_spin_radps, outgoing_spin_radps : float
        Spin ω before and after, rad/s.
    face_speed_mps : float
        Tangential velocity V_f of the face, m/s.
    gripped : bool
        Whether the ball gripped (stopped sliding) at any time during the contact; a ball that
        arrives rolling (u = 0, μ > 0) counts as gripped from t = 0.
    grip_time_s : float
        When it first gripped, s from first contact (NaN if it never did).
    tangential_impulse_ns : float
        J_t = ∫F_t dt on the ball along t̂, N·s.
    friction_loss_j : float
        Energy lost to sliding, ∫ μ F_n |w| dt ≥ 0, J.
    spring_energy_j : float
        Energy left in the tangential spring at separation, ½ k_t s², J.
    incoming_energy_j : float
        ½ m (v_t − V_f)² + ½ I ω² before the impact, J.
    ball_mass_kg, ball_radius_m, inertia_kgm2, effective_mass_kg : float
        m, R, I = k_I m R² and m_eff = m/(1 + m R²/I).
    contact : TangentialContact
        The contact model used.
    phases : tuple of (str, float, float)
        ``("grip" | "slide", start, end)`` in s, in order.
    time_s : ndarray (n_t,)
        History times from first contact, s.
    normal_force_n, tangential_force_n : ndarray (n_t,)
        F_n and F_t (on the ball, along t̂), N.
    contact_velocity_mps : ndarray (n_t,)
        u = v_t − R ω − V_f, the ball's contact point relative to the face, m/s.
    sliding_velocity_mps : ndarray (n_t,)
        w, the sliding of the spring on the strings (0 while gripping), m/s.
    tangential_velocity_mps, spin_radps : ndarray (n_t,)
        Ball centre velocity along t̂ (m/s) and spin (rad/s).
    tangential_deflection_m : ndarray (n_t,)
        Spring deflection s, m (0 for a rigid grip).
    """

    incoming_tangential_speed_mps: float
    incoming_spin_radps: float
    face_speed_mps: float
    outgoing_tangential_speed_mps: float
    outgoing_spin_radps: float
    gripped: bool
    grip_time_s: float
    tangential_impulse_ns: float
    friction_loss_j: float
    spring_energy_j: float
    incoming_energy_j: float
    ball_mass_kg: float
    ball_radius_m: float
    inertia_kgm2: float
    effective_mass_kg: float
    contact: TangentialContact
    phases: tuple[tuple[Phase, float, float], ...]
    time_s: NDArray[np.float64]
    normal_force_n: NDArray[np.float64]
    tangential_force_n: NDArray[np.float64]
    contact_velocity_mps: NDArray[np.float64]
    sliding_velocity_mps: NDArray[np.float64]
    tangential_velocity_mps: NDArray[np.float64]
    spin_radps: NDArray[np.float64]
    tangential_deflection_m: NDArray[np.float64]

    @property
    def outgoing_energy_j(self) -> float:
        """½ m (v_t − V_f)² + ½ I ω² after the impact (face frame), J."""
        return float(
            self._energy(self.outgoing_tangential_speed_mps, self.outgoing_spin_radps, 0.0)
        )

    @property
    def energy_j(self) -> NDArray[np.float64]:
        """History of ½ m (v_t − V_f)² + ½ I ω² + ½ k_t s² (face frame), J."""
        return np.asarray(
            self._energy(
                self.tangential_velocity_mps, self.spin_radps, self.tangential_deflection_m
            )
        )

    @property
    def rolling_ratio(self) -> float:
        """R ω_out / (v_t,out − V_f): 1 if the ball leaves rolling, > 1 with spin beyond it."""
        relative = self.outgoing_tangential_speed_mps - self.face_speed_mps
        if relative == 0:
            return math.nan
        return self.ball_radius_m * self.outgoing_spin_radps / relative

    def _energy(self, v: Any, omega: Any, s: Any) -> Any:
        spring = 0.0 if self.contact.rigid else 0.5 * self.contact.stiffness_n_per_m * s**2
        relative = v - self.face_speed_mps
        return 0.5 * self.ball_mass_kg * relative**2 + 0.5 * self.inertia_kgm2 * omega**2 + spring


@dataclass(frozen=True, eq=False)
class ObliqueImpact:
    """An oblique impact with spin at one point of the racket face.

    Attributes
    ----------
    ball_speed_mps : float
        Incoming ball speed, m/s.
    incoming_angle_deg : float
        Angle θ of the incoming velocity to the face normal, degrees (θ > 0: moving along +t̂).
    incoming_spin_radps : float
        Incoming spin about n̂ × t̂, rad/s.
    racket_speed_mps : float
        Speed of the impact point towards the ball (normal), m/s.
    racket_tangential_speed_mps : float
        Velocity of the face along t̂, m/s.
    normal_speed_mps : float
        Outgoing ball speed along the normal, away from the face, m/s.
    tangential_speed_mps : float
        Outgoing ball velocity along t̂, m/s.
    outgoing_angle_deg : float
        ``atan2(tangential_speed, normal_speed)``, degrees from the normal.
    outgoing_spin_radps : float
        Outgoing spin about n̂ × t̂, rad/s.
    status : str
        ``ok`` or why the numbers are NaN (that of the normal impact).
    normal : TransientImpact
        The normal impact at ``ball_speed · cos θ``.
    tangential : TangentialImpact or None
        The tangential part (None when the normal impact failed).
    """

    ball_speed_mps: float
    incoming_angle_deg: float
    incoming_spin_radps: float
    racket_speed_mps: float
    racket_tangential_speed_mps: float
    normal_speed_mps: float
    tangential_speed_mps: float
    outgoing_angle_deg: float
    outgoing_spin_radps: float
    status: str
    normal: TransientImpact
    tangential: TangentialImpact | None

    def _tangential(self, name: str) -> Any:
        return math.nan if self.tangential is None else getattr(self.tangential, name)

    @property
    def gripped(self) -> bool:
        """Whether the ball gripped the strings at any time."""
        return bool(self.tangential is not None and self.tangential.gripped)

    @property
    def grip_time_s(self) -> float:
        """When the ball first gripped, s from first contact (NaN: never)."""
        return float(self._tangential("grip_time_s"))

    @property
    def tangential_impulse_ns(self) -> float:
        """Tangential impulse on the ball along t̂, N·s."""
        return float(self._tangential("tangential_impulse_ns"))

    @property
    def friction_loss_j(self) -> float:
        """Energy lost to sliding on the strings, J."""
        return float(self._tangential("friction_loss_j"))

    @property
    def spring_energy_j(self) -> float:
        """Energy left in the tangential spring at separation, J."""
        return float(self._tangential("spring_energy_j"))

    @property
    def time_s(self) -> NDArray[np.float64]:
        """Times of the tangential histories, s."""
        return self._history("time_s")

    @property
    def tangential_force_n(self) -> NDArray[np.float64]:
        """History of the tangential force on the ball along t̂, N."""
        return self._history("tangential_force_n")

    @property
    def sliding_velocity_mps(self) -> NDArray[np.float64]:
        """History of the sliding velocity on the strings (0 while gripping), m/s."""
        return self._history("sliding_velocity_mps")

    @property
    def contact_velocity_mps(self) -> NDArray[np.float64]:
        """History of the contact point's velocity relative to the face, m/s."""
        return self._history("contact_velocity_mps")

    @property
    def spin_radps(self) -> NDArray[np.float64]:
        """History of the spin, rad/s."""
        return self._history("spin_radps")

    def _history(self, name: str) -> NDArray[np.float64]:
        if self.tangential is None:
            return np.zeros(0)
        return np.asarray(getattr(self.tangential, name))


@dataclass(frozen=True, eq=False)
class ObliqueCurve:
    """Outgoing angle and spin over incoming angles (and spins), from :func:`oblique_curve`.

    Every array has the broadcast shape of the incoming angles and spins.

    Attributes
    ----------
    ball_speed_mps : float
        Incoming ball speed, m/s.
    incoming_angle_deg, incoming_spin_radps : ndarray
        Incoming angle to the normal (degrees) and spin (rad/s).
    outgoing_angle_deg, outgoing_spin_radps : ndarray
        Outgoing angle to the normal (degrees) and spin (rad/s).
    normal_speed_mps, tangential_speed_mps : ndarray
        Outgoing velocity components (away from the face; along t̂), m/s.
    gripped : ndarray of bool
        Whether the ball gripped.
    grip_time_s : ndarray
        When it first gripped, s (NaN: never).
    tangential_impulse_ns, friction_loss_j : ndarray
        Tangential impulse (N·s) and friction loss (J).
    status : ndarray of str
        ``ok`` or why a row is NaN.
    racket_speed_mps : float
        The racket's speed towards the ball at the point, m/s (0: at rest), so that every
        figure and table of the curve names it beside the ball's.
    """

    ball_speed_mps: float
    incoming_angle_deg: NDArray[np.float64]
    incoming_spin_radps: NDArray[np.float64]
    outgoing_angle_deg: NDArray[np.float64]
    outgoing_spin_radps: NDArray[np.float64]
    normal_speed_mps: NDArray[np.float64]
    tangential_speed_mps: NDArray[np.float64]
    gripped: NDArray[np.bool_]
    grip_time_s: NDArray[np.float64]
    tangential_impulse_ns: NDArray[np.float64]
    friction_loss_j: NDArray[np.float64]
    status: NDArray[np.str_]
    racket_speed_mps: float = 0.0

    _LABELS: ClassVar[dict[str, tuple[str, str]]] = {
        "incoming_angle_deg": ("degree", "incoming angle to the face normal"),
        "incoming_spin_radps": ("rad s-1", "incoming spin (+: rolling along the face)"),
        "outgoing_angle_deg": ("degree", "outgoing angle to the face normal"),
        "outgoing_spin_radps": ("rad s-1", "outgoing spin"),
        "normal_speed_mps": ("m s-1", "outgoing speed away from the face"),
        "tangential_speed_mps": ("m s-1", "outgoing speed along the face"),
        "grip_time_s": ("s", "time of the first grip (NaN: never)"),
        "tangential_impulse_ns": ("N s", "tangential impulse"),
        "friction_loss_j": ("J", "friction loss"),
    }
    """Units (UDUNITS) and long names of the curve's arrays in :meth:`to_xarray`."""

    def to_xarray(self) -> xr.Dataset:
        """The curve as an :class:`xarray.Dataset`: one ``impact`` per incoming angle × spin
        (the rows of oblique.csv, in C order of the broadcast shape).

        Coordinates ``incoming_angle_deg`` and ``incoming_spin_radps`` on ``impact``; every
        other array a variable with ``units`` and ``long_name`` (``gripped``; ``status``, ``ok``
        or why the row is NaN); the attributes ``ball_speed_mps`` and ``racket_speed_mps``.

        Returns
        -------
        xarray.Dataset
            Writable as netCDF.
        """
        import xarray as xr

        def labelled(name: str) -> tuple[str, NDArray[Any], dict[str, str]]:
            units, long_name = self._LABELS[name]
            values = np.ravel(getattr(self, name))
            return ("impact", values, {"units": units, "long_name": long_name})

        incoming = ("incoming_angle_deg", "incoming_spin_radps")
        data: dict[str, Any] = {
            name: labelled(name) for name in self._LABELS if name not in incoming
        }
        data["gripped"] = ("impact", np.ravel(self.gripped), {"long_name": "the ball gripped"})
        data["status"] = ("impact", np.ravel(self.status), {"long_name": "ok, or why NaN"})
        return xr.Dataset(
            data,
            coords={name: labelled(name) for name in incoming},
            attrs={
                "ball_speed_mps": float(self.ball_speed_mps),
                "racket_speed_mps": float(self.racket_speed_mps),
            },
        )


# --- the tangential integration ------------------------------------------------------------------
@dataclass(frozen=True)
class _Piece:
    """One phase: grip from (u_a, s_a) at ``start``, or slide in direction σ from u_a."""

    kind: Phase
    start: float
    end: float
    u_a: float
    s_a: float
    sigma: float


@dataclass(frozen=True, eq=False)
class _Element:
    """The one-degree-of-freedom problem: m_eff on the elastic–Coulomb element, in closed form."""

    force: NormalForce
    m_eff: float
    mu: float
    k: float

    @property
    def rigid(self) -> bool:
        return math.isinf(self.k)

    @property
    def omega(self) -> float:
        """Angular frequency √(k_t/m_eff) of the grip oscillation, rad/s (inf: rigid)."""
        return math.sqrt(self.k / self.m_eff)

    def state(
        self, piece: _Piece, t: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Contact-point velocity u, spring deflection s and sliding velocity w at times t."""
        t = np.asarray(t, dtype=float)
        zero = np.zeros_like(t)
        if piece.kind == "grip":
            if self.rigid:
                return zero, zero, zero
            w = self.omega
            c, s = np.cos(w * (t - piece.start)), np.sin(w * (t - piece.start))
            return piece.u_a * c - w * piece.s_a * s, piece.s_a * c + piece.u_a / w * s, zero
        sigma, mu = piece.sigma, self.mu
        p_a = self.force.integral(np.asarray(piece.start))
        u = piece.u_a - sigma * mu * (self.force.integral(t) - p_a) / self.m_eff
        if self.rigid:
            return u, zero, u
        return (
            u,
            sigma * mu * self.force.force(t) / self.k,
            u - sigma * mu * self.force.rate(t) / self.k,
        )

    def leaves(self, piece: _Piece, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """Rises through 0 where the phase ends: −σ w (slide) or |k_t s| − μ F_n (grip)."""
        _, s, w = self.state(piece, t)
        if piece.kind == "slide":
            return -piece.sigma * w
        return np.asarray(self.k * np.abs(s) - self.mu * self.force.force(t))

    def friction_loss(self, piece: _Piece) -> float:
        """∫ μ F_n σ w dt over a slide phase, in closed form (module docstring), J."""
        integral, force = self.force.integral, self.force.force
        dp = float(integral(np.asarray(piece.end)) - integral(np.asarray(piece.start)))
        loss = self.mu * (piece.sigma * piece.u_a * dp - self.mu * dp**2 / (2.0 * self.m_eff))
        if not self.rigid:
            f_a, f_b = float(force(np.asarray(piece.start))), float(force(np.asarray(piece.end)))
            loss -= self.mu**2 * (f_b**2 - f_a**2) / (2.0 * self.k)
        return loss


def _phase_end(
    element: _Element, piece: _Piece, grid: NDArray[np.float64], threshold: float
) -> float | None:
    """First t after the start where ``element.leaves`` rises above ``threshold`` (or None).

    Brackets the change on ``grid``, then Brent's method to machine precision.
    """
    t = np.concatenate([[piece.start], grid[grid > piece.start]])
    values = element.leaves(piece, t) - threshold
    above = np.nonzero(values[1:] > 0.0)[0]
    if above.size == 0:
        return None
    i = int(above[0]) + 1
    low, high = float(t[i - 1]), float(t[i])
    if values[i - 1] >= 0.0:  # a phase that ends where it starts
        return low

    def g(x: float) -> float:
        return float(element.leaves(piece, np.asarray(x))) - threshold

    return float(brentq(g, low, high, xtol=1e-15 * high, rtol=1e-15))


def _phases(element: _Element, u0: float, grid: NDArray[np.float64]) -> list[_Piece]:
    """Grip and slide phases from first contact to separation."""
    force, mu, k = element.force, element.mu, element.k
    T = force.contact_time_s
    t_end = T * (1.0 - _END_FRACTION)
    slack = _LIMIT_TOLERANCE * mu * force.peak_force_n
    sigma = math.copysign(1.0, u0)
    if u0 == 0.0:  # arrives rolling: no tangential force at all
        return [_Piece("grip", 0.0, T, 0.0, 0.0, 0.0)]
    f0, rate0 = float(force.force(np.asarray(0.0))), float(force.rate(np.asarray(0.0)))
    if element.rigid or (mu * f0 <= 0.0 and k * abs(u0) > mu * rate0):
        piece = _Piece("slide", 0.0, T, u0, 0.0, sigma)
    else:  # the limit μ F_n grows faster than the slip could load the spring, or starts loaded
        piece = _Piece("grip", 0.0, T, u0, 0.0, 0.0)
    pieces: list[_Piece] = []
    while len(pieces) < _MAX_PHASES:
        if piece.kind == "grip" and element.rigid:
            pieces.append(piece)
            break
        stop = _phase_end(element, piece, grid, 0.0 if piece.kind == "slide" else slack)
        if stop is None or stop >= t_end:
            pieces.append(piece)
            break
        pieces.append(_Piece(piece.kind, piece.start, stop, piece.u_a, piece.s_a, piece.sigma))
        u, s, _ = (float(v) for v in element.state(piece, np.asarray(stop)))
        if piece.kind == "slide":
            piece = _Piece("grip", stop, T, 0.0 if element.rigid else u, s, 0.0)
        else:
            piece = _Piece("slide", stop, T, u, 0.0, math.copysign(1.0, s))
    else:
        raise RuntimeError(f"tangential contact: more than {_MAX_PHASES} grip/slide phases")
    return pieces


def simulate_tangential(
    normal_force: NormalForce,
    ball: Ball,
    tangential_speed: float,
    spin: float = 0.0,
    contact: TangentialContact = DEFAULT_TANGENTIAL_CONTACT,
    face_speed: float = 0.0,
    n_samples: int = _HISTORY_SAMPLES,
) -> TangentialImpact:
    """Integrate the tangential ball–string contact along a normal force history.

    Parameters
    ----------
    normal_force : NormalForce
        F_n(t) from first contact to separation.
    ball : Ball
        Mass m and diameter 2R of the ball.
    tangential_speed : float
        Incoming ball centre velocity along t̂, m/s (any sign).
    spin : float
        Incoming spin about n̂ × t̂, rad/s (positive: the sense of rolling along +t̂).
    contact : TangentialContact
        Friction coefficient, tangential stiffness and the ball's inertia factor.
    face_speed : float
        Tangential velocity V_f of the face along t̂, m/s.
    n_samples : int
        History samples over the contact (phase changes are added), ≥ 2.

    Returns
    -------
    TangentialImpact
    """
    v_in = require_finite("tangential speed", tangential_speed)
    omega_in = require_finite("spin", spin)
    v_face = require_finite("face tangential speed", face_speed)
    if not isinstance(n_samples, int | np.integer) or n_samples < 2:
        raise InputError(f"n_samples must be an integer ≥ 2 (got {n_samples!r})")
    m = ball.mass_kg
    radius = 0.5 * ball.diameter_m
    inertia = contact.inertia_factor * m * radius**2
    element = _Element(
        normal_force,
        contact.effective_mass(ball),
        float(contact.friction_coefficient),
        float(contact.stiffness_n_per_m),
    )
    T = normal_force.contact_time_s
    u0 = v_in - radius * omega_in - v_face

    n_check = _MIN_CHECKPOINTS
    if not element.rigid:
        n_check = max(n_check, math.ceil(_CHECKPOINTS_PER_PERIOD * T * element.omega / math.tau))
    pieces = _phases(element, u0, np.linspace(0.0, T, n_check + 1))

    samples = np.linspace(0.0, T, n_samples)
    times: list[NDArray[np.float64]] = []
    states: list[tuple[NDArray[np.float64], ...]] = []
    forces: list[NDArray[np.float64]] = []
    for i, piece in enumerate(pieces):
        inside = samples[(samples > piece.start) & (samples < piece.end)]
        x = np.concatenate([[piece.start], inside, [piece.end] if i == len(pieces) - 1 else []])
        u_x, s_x, w_x = element.state(piece, x)
        times.append(x)
        states.append((u_x, s_x, w_x))
        if element.rigid:
            slide = piece.kind == "slide"
            forces.append(-piece.sigma * element.mu * normal_force.force(x) if slide else 0 * x)
        else:
            forces.append(-element.k * s_x)
    time = np.concatenate(times)
    u_t, s_t, w_t = (np.concatenate([state[j] for state in states]) for j in range(3))
    u_end, s_end = float(u_t[-1]), float(s_t[-1])
    friction_loss = sum(element.friction_loss(p) for p in pieces if p.kind == "slide")
    for before, after in itertools.pairwise(pieces):
        if before.kind == "grip" and after.kind == "slide" and not element.rigid:
            # the grip lets go within _LIMIT_TOLERANCE of the limit: the spring sheds the excess
            # by sliding at once
            s_grip = float(element.state(before, np.asarray(before.end))[1])
            s_slide = float(element.state(after, np.asarray(after.start))[1])
            friction_loss += 0.5 * element.k * (s_grip**2 - s_slide**2)
    impulse = element.m_eff * (u_end - u0)
    impulse_history = element.m_eff * (u_t - u0)
    first_grip = next((p.start for p in pieces if p.kind == "grip" and element.mu > 0.0), math.nan)
    result = TangentialImpact(
        incoming_tangential_speed_mps=v_in,
        incoming_spin_radps=omega_in,
        face_speed_mps=v_face,
        outgoing_tangential_speed_mps=v_in + impulse / m,
        outgoing_spin_radps=omega_in - radius * impulse / inertia,
        gripped=not math.isnan(first_grip),
        grip_time_s=first_grip,
        tangential_impulse_ns=impulse,
        friction_loss_j=float(friction_loss),
        spring_energy_j=0.0 if element.rigid else 0.5 * element.k * s_end**2,
        incoming_energy_j=0.5 * m * (v_in - v_face) ** 2 + 0.5 * inertia * omega_in**2,
        ball_mass_kg=m,
        ball_radius_m=radius,
        inertia_kgm2=inertia,
        effective_mass_kg=element.m_eff,
        contact=contact,
        phases=tuple((p.kind, p.start, p.end) for p in pieces),
        time_s=time,
        normal_force_n=np.maximum(normal_force.force(time), 0.0),
        tangential_force_n=np.concatenate(forces),
        contact_velocity_mps=u_t,
        sliding_velocity_mps=w_t,
        tangential_velocity_mps=v_in + impulse_history / m,
        spin_radps=omega_in - radius * impulse_history / inertia,
        tangential_deflection_m=s_t,
    )
    log.debug(
        "tangential contact: phases %s, J_t = %.4g N·s",
        "".join(p.kind[0] for p in pieces),
        impulse,
    )
    return result


# --- racket-level entry points -------------------------------------------------------------------
def _check_angle(angle_deg: float) -> float:
    angle = require_finite("incoming angle (degrees)", angle_deg)
    if not -90.0 < angle < 90.0:
        raise InputError(
            f"incoming angle must lie strictly between -90 and 90 degrees from the face normal "
            f"(got {angle_deg!r})"
        )
    return angle


@dataclass(frozen=True)
class _Incoming:
    """An oblique impact's incoming state: the ball's speed (m/s), angle to the face normal
    (degrees) and spin (rad/s); the racket's speed along the normal and the face's along t̂
    (m/s)."""

    speed: float
    angle: float
    spin: float
    racket_speed: float
    face_speed: float

    @property
    def normal_speed(self) -> float:
        """The ball's speed along the normal, ``V cos θ``, m/s."""
        return self.speed * math.cos(math.radians(self.angle))

    @property
    def tangential_speed(self) -> float:
        """The ball's speed along t̂, ``V sin θ``, m/s."""
        return self.speed * math.sin(math.radians(self.angle))


def _nan_impact(incoming: _Incoming, normal: TransientImpact) -> ObliqueImpact:
    log.warning(
        "oblique impact at %.3g m/s, %.3g°: %s (results are NaN)",
        incoming.speed,
        incoming.angle,
        normal.status,
    )
    nan = math.nan
    return ObliqueImpact(
        incoming.speed,
        incoming.angle,
        incoming.spin,
        incoming.racket_speed,
        incoming.face_speed,
        nan,
        nan,
        nan,
        nan,
        normal.status,
        normal,
        None,
    )


def _combine(
    incoming: _Incoming, normal: TransientImpact, tangential: TangentialImpact
) -> ObliqueImpact:
    v_n, v_t = normal.rebound_speed_mps, tangential.outgoing_tangential_speed_mps
    return ObliqueImpact(
        ball_speed_mps=incoming.speed,
        incoming_angle_deg=incoming.angle,
        incoming_spin_radps=incoming.spin,
        racket_speed_mps=incoming.racket_speed,
        racket_tangential_speed_mps=incoming.face_speed,
        normal_speed_mps=v_n,
        tangential_speed_mps=v_t,
        outgoing_angle_deg=math.degrees(math.atan2(v_t, v_n)),
        outgoing_spin_radps=tangential.outgoing_spin_radps,
        status=normal.status,
        normal=normal,
        tangential=tangential,
    )


# 10 parameters and **kwargs: the ball's incoming state and the racket's motion, each one the
# paper's quantity and a CLI option of `oblique`; no object of them reads better for callers
def simulate_oblique(
    racket: Racket,
    ball: Ball,
    location: ArrayLike,
    ball_speed: float,
    angle_deg: float,
    spin_radps: float = 0.0,
    support: str = "free",
    racket_speed: float = 0.0,
    tangential: TangentialContact = DEFAULT_TANGENTIAL_CONTACT,
    racket_tangential_speed: float = 0.0,
    **kwargs: Any,
) -> ObliqueImpact:
    """Simulate an oblique impact with spin at one point of the racket face.

    The normal component ``ball_speed · cos θ`` goes to :func:`simulate_impact` (with the racket
    speed), the tangential component ``ball_speed · sin θ`` and the spin to
    :func:`simulate_tangential` along the normal force history (one-way coupling, see the module
    docstring for the axes, signs and assumptions).

    Parameters
    ----------
    racket : Racket
        The racket.
    ball : Ball
        The ball (mass, diameter, e_BG).
    location : array_like, shape (2,)
        Impact point (x, y) on the string bed, m.
    ball_speed : float
        Incoming ball speed, m/s, ≥ 0.
    angle_deg : float
        Angle of the incoming velocity to the face normal, degrees, in (−90, 90); positive:
        the ball moves along +t̂.
    spin_radps : float
        Incoming spin about n̂ × t̂, rad/s (positive: the sense of rolling along +t̂).
    support : str
        Support condition of the normal impact (see :func:`simulate_impact`).
    racket_speed : float
        Speed of the impact point towards the ball along the normal, m/s.
    tangential : TangentialContact
        Friction coefficient, tangential stiffness and ball inertia factor.
    racket_tangential_speed : float
        Velocity of the face along t̂, m/s (the racket brushing the ball).
    **kwargs
        Passed to :func:`simulate_impact` (``modal_model``, ``law``, ``rtol``, …).

    Returns
    -------
    ObliqueImpact
        NaN outputs (and ``status`` saying why) when the normal impact has no valid result.
    """
    incoming = _Incoming(
        require_positive("ball speed", ball_speed, allow_zero=True),
        _check_angle(angle_deg),
        require_finite("spin", spin_radps),
        face_speed=require_finite("racket tangential speed", racket_tangential_speed),
        racket_speed=require_finite("racket speed", racket_speed),
    )
    normal = simulate_impact(
        racket, ball, location, incoming.normal_speed, support, incoming.racket_speed, **kwargs
    )
    if normal.status != STATUS_OK:
        return _nan_impact(incoming, normal)
    force = NormalForce.from_impact(normal)
    return _combine(incoming, normal, _tangential_part(force, ball, incoming, tangential))


def _tangential_part(
    force: NormalForce, ball: Ball, incoming: _Incoming, contact: TangentialContact
) -> TangentialImpact:
    """:func:`simulate_tangential` of the incoming state along the normal force history."""
    return simulate_tangential(
        force, ball, incoming.tangential_speed, incoming.spin, contact, incoming.face_speed
    )


# 10 parameters and **kwargs: those of simulate_oblique, angles and spins as arrays
def oblique_curve(
    racket: Racket,
    ball: Ball,
    location: ArrayLike,
    ball_speed: float,
    angles_deg: ArrayLike,
    spins_radps: ArrayLike = 0.0,
    support: str = "free",
    racket_speed: float = 0.0,
    tangential: TangentialContact = DEFAULT_TANGENTIAL_CONTACT,
    racket_tangential_speed: float = 0.0,
    **kwargs: Any,
) -> ObliqueCurve:
    """Outgoing angle and spin against incoming angle (and spin) at one point.

    One :func:`simulate_oblique` per incoming angle × spin (broadcast together); angles with
    the same normal speed (±θ) share one normal impact.

    Parameters
    ----------
    racket, ball, location, ball_speed, support, racket_speed, tangential,
    racket_tangential_speed, **kwargs
        As for :func:`simulate_oblique`.
    angles_deg : array_like
        Incoming angles to the face normal, degrees, each in (−90, 90).
    spins_radps : array_like
        Incoming spins, rad/s, broadcast against ``angles_deg``.

    Returns
    -------
    ObliqueCurve
        Arrays of the broadcast shape.
    """
    speed = require_positive("ball speed", ball_speed, allow_zero=True)
    angles, spins = _incoming_grid(angles_deg, spins_radps)
    face_speed = require_finite("racket tangential speed", racket_tangential_speed)
    v_racket = require_finite("racket speed", racket_speed)

    normals: dict[float, tuple[TransientImpact, NormalForce | None]] = {}
    impacts = []
    for angle, spin in zip(angles.flat, spins.flat, strict=True):
        incoming = _Incoming(speed, float(angle), float(spin), v_racket, face_speed)
        if incoming.normal_speed not in normals:  # ±θ share one normal impact
            normal = simulate_impact(
                racket, ball, location, incoming.normal_speed, support, v_racket, **kwargs
            )
            force = NormalForce.from_impact(normal) if normal.status == STATUS_OK else None
            normals[incoming.normal_speed] = (normal, force)
        normal, force = normals[incoming.normal_speed]
        if force is None:
            impacts.append(_nan_impact(incoming, normal))
        else:
            impacts.append(
                _combine(incoming, normal, _tangential_part(force, ball, incoming, tangential))
            )
    return _curve((speed, v_racket), angles, spins, impacts)


def _incoming_grid(
    angles_deg: ArrayLike, spins_radps: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The incoming angles and spins broadcast together, each checked."""
    try:
        angles, spins = np.broadcast_arrays(
            np.asarray(angles_deg, dtype=float), np.asarray(spins_radps, dtype=float)
        )
    except (TypeError, ValueError):
        raise InputError(
            "angles_deg and spins_radps must be numbers that broadcast together "
            f"(got shapes {np.shape(angles_deg)} and {np.shape(spins_radps)})"
        ) from None
    if angles.size == 0:
        raise InputError("angles_deg: give one or more incoming angles in degrees")
    for angle, spin in zip(angles.flat, spins.flat, strict=True):
        _check_angle(float(angle))
        require_finite("spin", float(spin))
    return angles, spins


_CURVE_VALUES = (
    "outgoing_angle_deg",
    "outgoing_spin_radps",
    "normal_speed_mps",
    "tangential_speed_mps",
    "grip_time_s",
    "tangential_impulse_ns",
    "friction_loss_j",
)
"""The :class:`ObliqueImpact` values an :class:`ObliqueCurve` gives at every angle × spin."""


def _curve(
    speeds: tuple[float, float],
    angles: NDArray[np.float64],
    spins: NDArray[np.float64],
    impacts: list[ObliqueImpact],
) -> ObliqueCurve:
    """The curve of the impacts, one per incoming angle × spin (in their flat order), of a
    ball and a racket at ``speeds`` (m/s)."""

    def values(name: str, dtype: Any) -> NDArray[Any]:
        return np.array([getattr(i, name) for i in impacts], dtype=dtype).reshape(angles.shape)

    return ObliqueCurve(
        ball_speed_mps=speeds[0],
        racket_speed_mps=float(speeds[1]),
        incoming_angle_deg=np.array(angles, dtype=float),
        incoming_spin_radps=np.array(spins, dtype=float),
        gripped=values("gripped", bool),
        status=values("status", object).astype(str),
        **{name: values(name, float) for name in _CURVE_VALUES},
    )
