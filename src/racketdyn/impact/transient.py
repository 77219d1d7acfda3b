"""Transient simulation of a normal ball–racket impact: the check on the approximate method.

The approximate method (:mod:`racketdyn.impact.approximate`) assumes the contact force is a
half-sine and charges the vibration it leaves against e_BG.  Here the contact is integrated in
time instead, for a normal impact at one point j = (x, y) of the face:

* the ball, a point mass m_B at displacement x_B (positive into the strings), meets the racket
  through the compound ball+string spring F_GB(X) (section 3.4), X = x_B − w the compression;
* the racket — its rigid-body freedom under the support (``free``, ``pinned`` or ``hand``) and
  its flexible modes from any :class:`~racketdyn.modal.model.ModalModel` — is the linear system
  ``M q̈ + C q̇ + K q = b_j F``, ``w = b_jᵀ q`` of :mod:`racketdyn.impact.system`; for ``free``
  and ``pinned`` its rigid part is exactly the reduced mass of eq 4 at the point.

So ``m_B ẍ_B = −F`` and the racket's equations, with F = 0 once the ball leaves the strings,
integrated in the frame where the racket is at rest before impact (its rigid-body motion is a
free motion, so only the approach speed matters) and reported in the lab frame.

Two engines give the same numbers: ``reference`` (:func:`simulate_system_contact`, scipy's
DOP853 in physical coordinates with events, one impact at a time) and ``compiled``
(:mod:`racketdyn.impact.kernel`, numba, all impacts at once, second order in the step);
:func:`predict_transient` chooses.

Hysteresis
----------
The ball on head-clamped strings returns e_BG of its speed at every speed (Kawazoe), so the
spring loads along F_GB and unloads along the lower curve

    ``F_un(X) = F_GB(X) · (X / X_p)^p``,  X_p the largest compression so far,

with the exponent p ≥ 0 chosen per X_p so that the energy returned is e_BG² times that stored:
``∫₀^{X_p} F_GB(X) (X/X_p)^p dX = e_BG² E_GB(X_p)`` (:func:`unloading_exponent`).  The
left side falls strictly from E_GB(X_p) (p = 0) to 0 (p → ∞) because F_GB > 0 on (0, X_p], so p
is unique; for the polynomial and power laws the integral is closed-form.  The curve meets F_GB
at the peak (the force is continuous), reaches zero at X = 0 (the ball leaves where it arrived)
and is F_GB itself for e_BG = 1.  Below X_p the unloading curve is elastic (reloading retraces
it); past X_p the spring loads along F_GB again and X_p grows.  Hence the energy lost in the
spring by separation is exactly ``(1 − e_BG²) E_GB(X_max)``.

Proof of the clamped COR: on a fixed rigid racket X = x_B, and ``½ m_B V² = E_GB(X_p)`` at the
turn; unloading gives back ``½ m_B V_out² = e_BG² E_GB(X_p)``, so V_out = e_BG V at every speed
(``tests/test_transient.py`` checks it at 5, 20 and 40 m/s to 1e-6).

The contact is integrated with :func:`scipy.integrate.solve_ivp` phase by phase (loading,
unloading, …), each ending on an event: the turn (Ẋ = 0), separation (X = 0) or reloading past
X_p; the force law is smooth within each phase.

Second contact
--------------
At separation the frame may still be swinging towards the ball: near the tip of a pinned
racket its first mode can catch the ball up a fraction of a millisecond after it left.  Both
engines follow the ball and the racket with no force for the racket's slowest period (at most
two contact times, :func:`racketdyn.impact.kernel.recontact_horizon`); if the compression
becomes positive again the row's status is ``STATUS_SECOND_CONTACT`` and its results are NaN —
the second contact is not simulated, so the end state would not be the impact's.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field, replace
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp

from racketdyn._display import number
from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law, with_ball_string_cor
from racketdyn.errors import (
    InputError,
    one_of,
    require_positive,
    require_range,
    require_speeds,
    require_whole,
)
from racketdyn.impact.approximate import elastic_contact
from racketdyn.impact.grid import (
    ImpactGrid,
    StringBed,
    check_string_bed,
    impact_grid,
    predict_by_point_law,
    resolve_modal_model,
    support_reduced_mass,
)
from racketdyn.impact.hand import Hand
from racketdyn.impact.kernel import (
    NUMBA_AVAILABLE,
    RECONTACT_TOLERANCE,
    RELOAD_MARGIN,
    STATUS_CODE_BEYOND_LAW,
    STATUS_CODE_NO_SEPARATION,
    STATUS_CODE_OK,
    STATUS_CODE_SECOND_CONTACT,
    integrate_impacts,
    law_arrays,
    recontact_horizon,
)
from racketdyn.impact.kernel import _law as kernel_law
from racketdyn.impact.kernel import _unloading_exponent as kernel_unloading_exponent
from racketdyn.impact.result import (
    STATUS_BEYOND_LAW,
    STATUS_FRAME_CONTACT,
    STATUS_NO_SEPARATION,
    STATUS_OK,
    STATUS_SECOND_CONTACT,
    ImpactResult,
)
from racketdyn.impact.system import (
    ENGINES,
    TRANSIENT_SUPPORTS,
    Engine,
    ImpactSystem,
    impact_system,
    point_system,
)
from racketdyn.modal import ModalModel
from racketdyn.racket import SUPPORTS, Racket, as_locations

__all__ = [
    "COMPILED_SCHEME",
    "ENERGY_TERMS",
    "ENGINES",
    "EXTRAPOLATE",
    "INTEGRATORS",
    "STATUS_NO_SEPARATION",
    "STATUS_SECOND_CONTACT",
    "STEPS_PER_CONTACT",
    "TRANSIENT_SUPPORTS",
    "Engine",
    "TransientImpact",
    "predict_transient",
    "simulate_contact",
    "simulate_impact",
    "simulate_system_contact",
    "unloading_exponent",
]

log = logging.getLogger(__name__)

Integrator = Literal["DOP853", "Radau"]
INTEGRATORS: tuple[str, ...] = ("DOP853", "Radau")

_HISTORY_SAMPLES = 400  # samples of the time histories over one estimated contact time
_MAX_PHASES = 200


@dataclass(frozen=True, eq=False)
class TransientImpact:
    """One simulated impact, from first contact to separation.

    Attributes
    ----------
    ball_speed_mps, racket_speed_mps : float
        Incoming ball speed and racket (impact point) speed towards each other, m/s.
    reduced_mass_kg : float
        Reduced mass M_r of the racket at the impact point, kg (inf: clamped head).
    mu_kg : float
        Two-body mass μ = m_B M_r / (m_B + M_r), kg.
    contact_time_s : float
        From first contact to separation, s.
    peak_force_n, mean_force_n : float
        Largest contact force and impulse / contact time, N.
    impulse_ns : float
        ∫F dt = m_B (change of ball velocity), N·s.
    peak_deflection_m : float
        Largest compression X_max of the compound spring, m.
    rebound_speed_mps : float
        Outgoing ball speed (away from the racket), m/s.
    racket_velocity_mps : float
        Rigid-body velocity of the impact point at separation, along the ball's incoming
        direction (away from the ball), m/s.
    rebound_ratio : float
        ``(e_r − m_B/M_r)/(1 + m_B/M_r)``: rebound / incident speed on a racket at rest.
    cor : float
        Ball–racket COR e_r from the rigid-body relative velocities at separation,
        ``(V_r,out − v_B,out)/(v_B,in − V_r,in)`` along the ball's incoming direction.
    mode_energy_j : ndarray (n_modes,)
        Vibration energy per mode at separation, ½ q̇² + ½ ω² q², J.
    vibration_energy_j : float
        Their sum, J.
    hysteresis_loss_j : float
        Energy lost in the ball+string spring, (1 − e_BG²) E_GB(X_max), J.
    damping_loss_j : float
        Energy lost to damping during contact — the modes' and, for ``hand``, the grip's
        dashpots — ∫ q̇ᵀ C q̇ dt, J.
    racket_energy_j : float
        The racket body's rigid-body kinetic energy at separation, in the frame where it was at
        rest before the impact, J.
    status : str
        ``ok`` or why the numbers are NaN.
    time_s, force_n, ball_displacement_m, deflection_m : ndarray (n_t,)
        Time histories from first contact: time, contact force, ball displacement (into the
        strings) and compression X.
    modal_coordinates : ndarray (n_t, n_modes)
        Modal coordinates q_k, m·√kg.
    support_energy_j : float
        Energy held by the hand and arm at separation (their motion and the grip's springs
        relative to the rigid-body motion), J; 0 for ``free`` and ``pinned``.
    coordinate_names : tuple of str
        Names of the racket's coordinates q (:class:`~racketdyn.impact.system.ImpactSystem`).
    final_displacement, final_velocity : ndarray (n_coordinates,)
        q and q̇ at separation, in the frame where the racket was at rest before the impact
        (m or rad; m/s or rad/s; modal coordinates in m·√kg).
    """

    ball_speed_mps: float
    racket_speed_mps: float
    reduced_mass_kg: float
    mu_kg: float
    contact_time_s: float
    peak_force_n: float
    mean_force_n: float
    impulse_ns: float
    peak_deflection_m: float
    rebound_speed_mps: float
    racket_velocity_mps: float
    rebound_ratio: float
    cor: float
    mode_energy_j: NDArray[np.float64]
    vibration_energy_j: float
    hysteresis_loss_j: float
    damping_loss_j: float
    racket_energy_j: float
    status: str
    time_s: NDArray[np.float64]
    force_n: NDArray[np.float64]
    ball_displacement_m: NDArray[np.float64]
    deflection_m: NDArray[np.float64]
    modal_coordinates: NDArray[np.float64]
    support_energy_j: float = 0.0
    coordinate_names: tuple[str, ...] = ()
    final_displacement: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    final_velocity: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))

    @property
    def stiffness_n_per_m(self) -> float:
        """Linear stiffness with the same half period, π² μ / T_c², N/m (eq 7 solved for K)."""
        return float(np.pi**2 * self.mu_kg / self.contact_time_s**2)

    def __repr__(self) -> str:
        return (
            f"<TransientImpact status {self.status!r}: ball_speed_mps="
            f"{number(self.ball_speed_mps)}, racket_speed_mps={number(self.racket_speed_mps)}, "
            f"contact_time_s={number(self.contact_time_s)}, peak_force_n="
            f"{number(self.peak_force_n)}, rebound_speed_mps={number(self.rebound_speed_mps)}, "
            f"cor={number(self.cor)}, vibration_energy_j={number(self.vibration_energy_j)}; "
            f"{self.time_s.size} time steps, {self.mode_energy_j.size} modes>"
        )


# --- the hysteresis law --------------------------------------------------------------------------
def unloading_exponent(law: RestoringForce, e_bg: float, peak: float) -> float:
    """Exponent p of the unloading curve ``F_un(X) = F_GB(X) (X/X_p)^p``.

    Solves ``∫₀^{X_p} F_GB(X) (X/X_p)^p dX = e_BG² E_GB(X_p)``: unloading from X_p returns
    e_BG² of the stored energy, so a ball on a clamped head rebounds with e_BG of its speed.

    Parameters
    ----------
    law : RestoringForce
        Loading curve F_GB(X).
    e_bg : float
        COR of the ball on head-clamped strings, 0 < e_BG ≤ 1.
    peak : float
        Peak compression X_p > 0, m.

    Returns
    -------
    float
        p ≥ 0 (0 for e_BG = 1: unloading along F_GB itself).
    """
    require_range("e_bg", e_bg, 0.0, 1.0)
    require_positive("peak compression", peak)
    if e_bg == 1.0:
        return 0.0
    return float(kernel_unloading_exponent(peak, e_bg, *law_arrays(law.kind, law.coefficients)))


def _scalar_force(law: RestoringForce) -> Callable[[float], float]:
    """F(X) for a float X (0 for X ≤ 0): the kernel's own scalar law."""
    kind, coefficients = law_arrays(law.kind, law.coefficients)
    return lambda x: float(kernel_law(x, kind, coefficients)[0])


# --- the reference engine -----------------------------------------------------------------------
def simulate_contact(
    ball_mass: float,
    e_bg: float,
    law: RestoringForce,
    reduced_mass: float,
    ball_speed: float,
    racket_speed: float = 0.0,
    mode_shapes: ArrayLike = (),
    omega: ArrayLike = (),
    damping_ratio: ArrayLike = (),
    rtol: float = 1e-10,
    method: Integrator = "DOP853",
) -> TransientImpact:  # 11 parameters: public, called positionally (kept as they are)
    """Integrate one normal impact on a reduced mass with flexible modes (reference engine).

    Parameters
    ----------
    ball_mass : float
        m_B, kg.
    e_bg : float
        COR of the ball on head-clamped strings (sets the hysteresis).
    law : RestoringForce
        Compound ball+string loading curve F_GB(X), N for X in m.
    reduced_mass : float
        Racket reduced mass M_r at the impact point, kg; ``inf`` for a clamped head.
    ball_speed : float
        Incoming ball speed towards the strings, m/s.
    racket_speed : float
        Speed of the impact point towards the ball, m/s.
    mode_shapes : array_like, shape (n_modes,)
        Mass-normalised shapes φ_k at the impact point, 1/√kg.
    omega : array_like, shape (n_modes,)
        Natural angular frequencies, rad/s.
    damping_ratio : array_like, shape (n_modes,)
        Modal damping ratios.
    rtol : float
        Relative tolerance of the integrator; absolute tolerances are rtol times the scale of
        each state.
    method : {"DOP853", "Radau"}
        :func:`scipy.integrate.solve_ivp` method.

    Returns
    -------
    TransientImpact
    """
    m_r = float(reduced_mass)
    if math.isnan(m_r) or m_r <= 0:
        raise InputError(f"reduced mass must be positive (inf for a clamped head), got {m_r:g}")
    phi = np.atleast_1d(np.asarray(mode_shapes, dtype=float))
    w_k = np.atleast_1d(np.asarray(omega, dtype=float))
    zeta = np.atleast_1d(np.asarray(damping_ratio, dtype=float))
    if not (phi.shape == w_k.shape == zeta.shape) or phi.ndim != 1:
        raise InputError("give one mode shape value, omega and damping ratio per mode")
    if not (np.all(np.isfinite(phi)) and np.all(w_k > 0) and np.all(zeta >= 0)):
        raise InputError("mode shapes must be finite, omega positive, damping ratios ≥ 0")
    system = point_system(m_r, phi, w_k, zeta)
    return simulate_system_contact(
        system, 0, ball_mass, e_bg, law, ball_speed, racket_speed, m_r, rtol, method
    )


def _check_contact_inputs(
    ball_mass: float, e_bg: float, ball_speed: float, racket_speed: float, rtol: float, method: str
) -> tuple[float, float]:
    require_positive("ball mass", ball_mass)
    require_range("e_bg", e_bg, 0.0, 1.0)
    if e_bg == 0:
        raise InputError("e_bg must be above 0")
    v_ball = require_speeds("ball speed", ball_speed)
    v_racket = require_speeds("racket speed", racket_speed)
    if v_ball.size != 1 or v_racket.size != 1:
        raise InputError("simulate one impact at a time: give one ball speed and one racket speed")
    v_in, v_r = float(v_ball[0]), float(v_racket[0])
    if v_in + v_r <= 0:
        raise InputError(
            "ball speed + racket speed must be positive: the ball must reach the strings"
        )
    one_of("method", method, INTEGRATORS)
    require_range("rtol", rtol, 1e-14, 1e-3)
    return v_in, v_r


def simulate_system_contact(
    system: ImpactSystem,
    point: int,
    ball_mass: float,
    e_bg: float,
    law: RestoringForce,
    ball_speed: float,
    racket_speed: float = 0.0,
    reduced_mass: float | None = None,
    rtol: float = 1e-10,
    method: Integrator = "DOP853",
) -> TransientImpact:
    """Integrate one normal impact on a racket's equations of motion (reference engine).

    ``M q̈ + C q̇ + K q = b_j F`` (:class:`~racketdyn.impact.system.ImpactSystem`) with the ball
    ``m_B ẍ_B = −F`` on the hysteretic spring, in the frame where the racket starts at rest
    (its rigid-body motion is a free motion, so the impact depends only on the approach speed);
    speeds are reported in the lab frame, the racket moving at ``racket_speed`` towards the
    ball in the rigid-body motion of least energy (the reduced-mass picture).

    Parameters
    ----------
    system : ImpactSystem
        The racket and its support.
    point : int
        Which of the system's impact points.
    ball_mass, e_bg, law, ball_speed, racket_speed, rtol, method
        As for :func:`simulate_contact`.
    reduced_mass : float, optional
        The support's reduced mass for the ``cor`` column (default: the rigid-body one,
        ``1/c_j``).

    Returns
    -------
    TransientImpact
    """
    v_in, v_r = _check_contact_inputs(ball_mass, e_bg, ball_speed, racket_speed, rtol, method)
    m_b = float(ball_mass)
    approach = v_in + v_r
    equations = _Equations.of(system, point, m_b)
    rigid_modal = system.rigid_basis().T @ equations.b
    compliance = float(rigid_modal @ rigid_modal)
    m_r = (
        (1.0 / compliance if compliance > 0 else math.inf) if reduced_mass is None else reduced_mass
    )
    mu = m_b / (1.0 + m_b * compliance)
    solver = _solver(equations, law, mu, approach, rtol, method)
    phases = _integrate_phases(equations, law, e_bg, approach, solver)
    setting = _ImpactSetting(v_in, v_r, m_b, e_bg, law, m_r)
    return _reference_result(setting, mu, point, equations, phases)


@dataclass(frozen=True, eq=False)
class _Equations:
    """The ball on the spring against ``M q̈ + C q̇ + K q = b_j F`` as first-order ODEs.

    State ``y``: ball x_B, v_B; q; q̇; the damping loss ∫ q̇ᵀ C q̇ dt (+: into the strings).
    """

    system: ImpactSystem
    n: int
    """Number of the racket's coordinates q."""
    b: NDArray[np.float64]
    """b_j, the force input at the impact point."""
    ball_mass: float
    """m_B, kg."""
    input_acc: NDArray[np.float64]
    """M⁻¹ b_j."""
    damping_acc: NDArray[np.float64]
    """M⁻¹ C."""
    stiffness_acc: NDArray[np.float64]
    """M⁻¹ K."""

    @classmethod
    def of(cls, system: ImpactSystem, point: int, ball_mass: float) -> _Equations:
        """``M⁻¹ b_j``, ``M⁻¹ C`` and ``M⁻¹ K`` of the racket at impact point ``point``."""
        b = system.force_input[point]
        mass_inv = np.linalg.inv(system.mass)
        return cls(
            system, system.n_coordinates, b, ball_mass, mass_inv @ b, mass_inv @ system.damping,
            mass_inv @ system.stiffness,
        )  # fmt: skip

    def deflection(self, y: NDArray[np.float64]) -> float:
        """Compression X = x_B − b_jᵀ q."""
        n = self.n
        return float(y[0] - self.b @ y[2 : 2 + n])

    def deflection_rate(self, y: NDArray[np.float64]) -> float:
        """Ẋ = v_B − b_jᵀ q̇."""
        n = self.n
        return float(y[1] - self.b @ y[2 + n : 2 + 2 * n])

    def histories(
        self, time: NDArray[np.float64], states: NDArray[np.float64], force: NDArray[np.float64]
    ) -> _Histories:
        """The time histories from the states (one column per sample) and the force."""
        n = self.n
        compression = states[0] - self.b @ states[2 : 2 + n]
        return _Histories(
            time, force, states[0], compression, states[2 : 2 + n][self.system.mode_index].T
        )

    def rhs(self, force: Callable[[float], float]) -> Callable[[float, Any], NDArray[np.float64]]:
        """dy/dt with the contact force ``force(X)``."""
        n, m_b, deflection = self.n, self.ball_mass, self.deflection
        input_acc, damping_acc, stiffness_acc = self.input_acc, self.damping_acc, self.stiffness_acc
        damping = self.system.damping

        def rhs(t: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
            f = force(deflection(y))
            q, q_dot = y[2 : 2 + n], y[2 + n : 2 + 2 * n]
            dy = np.empty_like(y)
            dy[0] = y[1]
            dy[1] = -f / m_b
            dy[2 : 2 + n] = q_dot
            dy[2 + n : 2 + 2 * n] = input_acc * f - damping_acc @ q_dot - stiffness_acc @ q
            dy[-1] = float(q_dot @ damping @ q_dot)
            return dy

        return rhs


@dataclass(frozen=True)
class _Solver:
    """solve_ivp's settings for one impact, and the time it may take."""

    method: Integrator
    rtol: float
    atol: NDArray[np.float64]
    t_estimate: float
    """Estimated contact time, s (the histories' sampling and the time allowed)."""

    def settings(self) -> dict[str, Any]:
        """The keywords of :func:`scipy.integrate.solve_ivp`."""
        return {"method": self.method, "rtol": self.rtol, "atol": self.atol}


def _solver(
    equations: _Equations, law: RestoringForce, mu: float, approach: float, rtol: float,
    method: Integrator,
) -> _Solver:  # fmt: skip
    """Absolute tolerances from the scales of each state (1 % of generous scales) and the
    elastic contact time estimate."""
    peak_estimate, time_estimate, _ = elastic_contact(law, mu, approach)
    elastic_peak, t_estimate = float(peak_estimate), float(time_estimate)
    impulse_scale = 2.0 * mu * approach
    speed_scale = np.maximum(np.abs(equations.input_acc) * impulse_scale, 1e-6 * approach)
    eigenvalues = np.linalg.eigvals(equations.stiffness_acc)
    omega_max = float(np.sqrt(np.abs(eigenvalues).max(initial=0.0)))
    length_scale = speed_scale * (min(t_estimate, 1.0 / omega_max) if omega_max > 0 else t_estimate)
    scale = np.concatenate(
        [[elastic_peak, approach], length_scale, speed_scale, [0.5 * mu * approach**2]]
    )
    return _Solver(method, rtol, 1e-2 * rtol * scale, t_estimate)


def _event(fn: Callable[[NDArray[np.float64]], float], direction: float) -> Any:
    """A terminal solve_ivp event where ``fn(y)`` crosses zero in ``direction``."""

    def wrapped(t: float, y: NDArray[np.float64]) -> float:
        return fn(y)

    wrapped.terminal = True  # type: ignore[attr-defined]
    wrapped.direction = direction  # type: ignore[attr-defined]
    return wrapped


@dataclass(frozen=True, eq=False)
class _Phases:
    """The contact integrated phase by phase: how it ended, its end state and its histories."""

    status: str
    t_end: float
    """Time of the last event (separation when ok), s."""
    y_end: NDArray[np.float64]
    """The state there (see :class:`_Equations`)."""
    peak: float
    """X_max, m."""
    histories: _Histories


def _phase_law(
    equations: _Equations, law: RestoringForce, e_bg: float, peak: float, loading: bool
) -> tuple[Callable[[float], float], list[Any]]:
    """Force and events of a phase: F_GB with the turn and the law's end while ``loading``,
    ``F_GB (X/X_p)^p`` with separation and reloading past X_p while unloading."""
    loading_force = _scalar_force(law)
    deflection = equations.deflection
    if loading:
        turn = _event(equations.deflection_rate, -1.0)
        beyond = _event(lambda y: deflection(y) - law.max_deflection_m, 1.0)
        return loading_force, [turn, beyond]
    exponent = unloading_exponent(law, e_bg, peak)

    def force(x: float, _p: float = exponent, _xp: float = peak) -> float:
        return loading_force(x) * (x / _xp) ** _p if x > 0.0 else 0.0

    def past_peak(y: NDArray[np.float64], _xp: float = peak) -> float:
        return deflection(y) - _xp * (1.0 + RELOAD_MARGIN)

    return force, [_event(deflection, -1.0), _event(past_peak, 1.0)]


def _integrate_phases(
    equations: _Equations, law: RestoringForce, e_bg: float, approach: float, solver: _Solver
) -> _Phases:
    """The contact from first touch, phase by phase (loading, unloading, …), each ending on an
    event: the turn (Ẋ = 0), separation (X = 0), reloading past X_p or the law's end."""
    # state: ball x, v; q; q̇; damping loss.  +: into the strings; racket at rest at first.
    y0 = np.zeros(3 + 2 * equations.n)
    y0[1] = approach
    t0, peak, loading, status = 0.0, 0.0, True, STATUS_NO_SEPARATION
    times: list[NDArray[np.float64]] = []
    states: list[NDArray[np.float64]] = []
    forces: list[NDArray[np.float64]] = []
    for _ in range(_MAX_PHASES):
        force, events = _phase_law(equations, law, e_bg, peak, loading)
        solution = _solve_phase(equations, force, events, t0, y0, solver)
        t_phase, y_phase = _sample_phase(solution, t0, solver.t_estimate)
        times.append(t_phase)
        states.append(y_phase)
        forces.append(np.array([force(equations.deflection(y)) for y in y_phase.T]))
        hit = [len(t) > 0 for t in solution.t_events]
        if solution.status != 1 or not any(hit):
            break  # out of time
        which = hit.index(True)
        t0, y0 = float(solution.t_events[which][0]), np.array(solution.y_events[which][0])
        if loading and which == 0:  # turn: start unloading from the new peak
            peak, loading = equations.deflection(y0), False
        elif loading:  # beyond the law's range
            status = STATUS_BEYOND_LAW
            break
        elif which == 0:  # separation
            status = STATUS_OK
            free_flight = equations.rhs(_no_force)
            settings = solver.settings()
            if _caught_again(
                free_flight, equations.deflection, y0, t0, peak, equations.system, settings
            ):
                status = STATUS_SECOND_CONTACT
            break
        else:  # reload past the old peak along F_GB
            loading = True
    histories = equations.histories(
        np.concatenate(times), np.concatenate(states, axis=1), np.concatenate(forces)
    )
    return _Phases(status, t0, y0, peak, histories)


def _solve_phase(
    equations: _Equations, force: Callable[[float], float], events: list[Any], t0: float,
    y0: NDArray[np.float64], solver: _Solver,
) -> Any:  # fmt: skip
    """One phase from ``(t0, y0)`` to its first event, within 50 estimated contact times."""
    solution: Any = solve_ivp(
        equations.rhs(force),
        (t0, 50.0 * solver.t_estimate),
        y0,
        events=events,
        dense_output=True,
        **solver.settings(),
    )
    if not solution.success:
        raise RuntimeError(f"transient impact: the integrator failed ({solution.message})")
    return solution


def _sample_phase(
    solution: Any, t0: float, t_estimate: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A phase's times and states on ``_HISTORY_SAMPLES`` per estimated contact time (the
    damping loss at the end taken from the solver's last step)."""
    t_end = float(solution.t[-1])
    n_samples = max(int(np.ceil(_HISTORY_SAMPLES * (t_end - t0) / t_estimate)), 4)
    t_phase = np.linspace(t0, t_end, n_samples)
    y_phase = solution.sol(t_phase)
    y_phase[:, -1] = solution.y[:, -1]
    return t_phase, y_phase


def _reference_result(
    setting: _ImpactSetting, mu: float, point: int, equations: _Equations, phases: _Phases
) -> TransientImpact:
    """The :class:`TransientImpact` of an integrated contact (NaN numbers unless it is ok)."""
    system, n, histories = equations.system, equations.n, phases.histories
    if phases.status != STATUS_OK:
        v_in, v_r, m_r = setting.speeds_and_mass()
        log.warning("transient impact at %.3g m/s: %s (results are NaN)", v_in + v_r, phases.status)
        nan = math.nan
        return TransientImpact(
            v_in, v_r, m_r, mu, nan, nan, nan, nan, nan, nan, nan, nan,
            nan, np.full(system.mode_index.size, nan), nan, nan, nan, nan, phases.status,
            histories.time, histories.force, histories.ball_displacement, histories.compression,
            histories.modal_coordinates, nan,
        )  # fmt: skip
    y_end = phases.y_end
    q_end, q_dot_end = y_end[2 : 2 + n], y_end[2 + n : 2 + 2 * n]
    rigid_energy, mode_energy, support_energy = system.energies(q_end, q_dot_end)
    end = _RestFrameEnd(
        point_velocity=float(system.rigid_point_velocity(q_dot_end)[point]),
        ball_velocity=float(y_end[1]),
        contact_time=phases.t_end,
        peak=phases.peak,
        rigid_energy=float(rigid_energy),
        mode_energy=mode_energy,
        support_energy=float(support_energy),
        damping_loss=float(y_end[-1]),
    )
    return replace(
        _assemble(setting, end, histories),
        coordinate_names=system.coordinate_names,
        final_displacement=np.array(q_end),
        final_velocity=np.array(q_dot_end),
    )


def _no_force(x: float) -> float:
    return 0.0


def _caught_again(
    free_flight: Callable[[float, Any], NDArray[np.float64]],
    deflection: Callable[[NDArray[np.float64]], float],
    state: NDArray[np.float64],
    t0: float,
    peak: float,
    system: ImpactSystem,
    solver: dict[str, Any],
) -> bool:
    """Whether the vibrating frame catches the ball up again after separation.

    Follows the ball and the racket with no force for
    :func:`~racketdyn.impact.kernel.recontact_horizon` (the racket's slowest period) and
    watches for the compression to exceed ``RECONTACT_TOLERANCE · X_p`` (as the compiled
    engine does).
    """
    form = system.pole_residue()
    horizon = float(recontact_horizon(form.poles, form.weights, t0))
    if horizon <= 0.0:
        return False

    def gap(t: float, y: NDArray[np.float64]) -> float:
        return deflection(y) - RECONTACT_TOLERANCE * peak

    gap.terminal = True  # type: ignore[attr-defined]
    gap.direction = 1.0  # type: ignore[attr-defined]
    solution: Any = solve_ivp(free_flight, (t0, t0 + horizon), state, events=[gap], **solver)
    return bool(len(solution.t_events[0]))


@dataclass(frozen=True, eq=False)
class _ImpactSetting:
    """What impacts start from, lab frame (arrays broadcast together in the compiled engine)."""

    v_in: ArrayLike
    """Incoming ball speed, m/s."""
    v_r: ArrayLike
    """Speed of the impact point towards the ball, m/s."""
    m_b: float
    """Ball mass, kg."""
    e_bg: ArrayLike
    """COR of the ball on head-clamped strings."""
    law: RestoringForce
    """Compound law F_GB."""
    m_r: ArrayLike
    """Reduced mass M_r for the ``cor`` column, kg (inf: clamped head)."""

    def speeds_and_mass(self) -> tuple[float, float, float]:
        """v_in, v_r and M_r of a single impact, as floats."""
        return (
            float(np.asarray(self.v_in)),
            float(np.asarray(self.v_r)),
            float(np.asarray(self.m_r)),
        )


@dataclass(frozen=True, eq=False)
class _RestFrameEnd:
    """Impacts' end states at separation, in the frame where the racket was at rest before."""

    point_velocity: ArrayLike
    """Impact point's velocity from the racket's rigid-body motion, m/s."""
    ball_velocity: ArrayLike
    """Ball velocity, m/s (+ into the strings)."""
    contact_time: ArrayLike
    """s."""
    peak: ArrayLike
    """Largest compression X_max, m."""
    rigid_energy: ArrayLike
    """Rigid-body kinetic energy of the racket body, J."""
    mode_energy: ArrayLike
    """Vibration energy per mode (modes on the last axis), J."""
    support_energy: ArrayLike
    """Energy held by the hand and arm, J."""
    damping_loss: ArrayLike | None
    """Energy lost to damping, J; None: what the other terms of the balance leave."""


@dataclass(frozen=True, eq=False)
class _Histories:
    """One impact's time histories from first contact (see :class:`TransientImpact`)."""

    time: NDArray[np.float64]
    force: NDArray[np.float64]
    ball_displacement: NDArray[np.float64]
    compression: NDArray[np.float64]
    modal_coordinates: NDArray[np.float64]


def _lab_numbers(setting: _ImpactSetting, end: _RestFrameEnd) -> dict[str, NDArray[np.float64]]:
    """The lab-frame numbers of impacts from their rest-frame end states (both engines).

    With ``end.damping_loss=None`` (compiled engine) the damping loss is what the other terms
    of the energy balance leave; the reference engine integrates it.
    """
    m_b, law = setting.m_b, setting.law
    v_in, v_r, m_r, v_point, v_out_rest, t_c, x_max = (
        np.asarray(x, dtype=float)
        for x in (
            setting.v_in, setting.v_r, setting.m_r, end.point_velocity, end.ball_velocity,
            end.contact_time, end.peak,
        )
    )  # fmt: skip
    modes = np.asarray(end.mode_energy, dtype=float)
    approach = v_in + v_r
    impulse = m_b * (approach - v_out_rest)
    rebound = v_r - v_out_rest  # lab, + away from the strings
    rebound_ratio = (rebound - v_r) / approach
    mass_ratio = np.where(np.isinf(m_r), 0.0, m_b / m_r)
    hysteresis = (1.0 - np.asarray(setting.e_bg, dtype=float) ** 2) * np.asarray(law.energy(x_max))
    vibration = modes.sum(axis=-1)
    damping_loss = end.damping_loss
    if damping_loss is None:
        damping_loss = (
            0.5 * m_b * (approach**2 - v_out_rest**2) - np.asarray(end.rigid_energy)
            - vibration - np.asarray(end.support_energy) - hysteresis
        )  # fmt: skip
    mu = m_b / (1.0 + mass_ratio)
    return {
        "mu": mu,
        "contact_time": t_c,
        "peak_force": np.asarray(law.force(x_max)),
        "mean_force": impulse / t_c,
        "impulse": impulse,
        "peak_deflection": x_max,
        "rebound_speed": rebound,
        "racket_velocity": v_point - v_r,
        "rebound_ratio": rebound_ratio,
        "cor": rebound_ratio * (1.0 + mass_ratio) + mass_ratio,
        "vibration_energy": vibration,
        "hysteresis_loss": hysteresis,
        "damping_loss": np.asarray(damping_loss, dtype=float),
        "racket_energy": np.asarray(end.rigid_energy, dtype=float),
        "stiffness": np.pi**2 * mu / t_c**2,
    }


def _assemble(
    setting: _ImpactSetting, end: _RestFrameEnd, histories: _Histories
) -> TransientImpact:
    """One impact's :class:`TransientImpact` from its rest-frame end state."""
    n = _lab_numbers(setting, end)
    v_in, v_r, m_r = setting.speeds_and_mass()
    return TransientImpact(
        ball_speed_mps=v_in,
        racket_speed_mps=v_r,
        reduced_mass_kg=m_r,
        mu_kg=float(n["mu"]),
        contact_time_s=float(n["contact_time"]),
        peak_force_n=float(n["peak_force"]),
        mean_force_n=float(n["mean_force"]),
        impulse_ns=float(n["impulse"]),
        peak_deflection_m=float(n["peak_deflection"]),
        rebound_speed_mps=float(n["rebound_speed"]),
        racket_velocity_mps=float(n["racket_velocity"]),
        rebound_ratio=float(n["rebound_ratio"]),
        cor=float(n["cor"]),
        mode_energy_j=np.asarray(end.mode_energy, dtype=float),
        vibration_energy_j=float(n["vibration_energy"]),
        hysteresis_loss_j=float(n["hysteresis_loss"]),
        damping_loss_j=float(n["damping_loss"]),
        racket_energy_j=float(n["racket_energy"]),
        status=STATUS_OK,
        time_s=histories.time,
        force_n=histories.force,
        ball_displacement_m=histories.ball_displacement,
        deflection_m=histories.compression,
        modal_coordinates=histories.modal_coordinates,
        support_energy_j=float(np.asarray(end.support_energy)),
    )


# --- racket-level entry points -------------------------------------------------------------------
def simulate_impact(
    racket: Racket,
    ball: Ball,
    location: ArrayLike,
    ball_speed: float,
    support: str = "free",
    racket_speed: float = 0.0,
    modal_model: ModalModel | Literal["racket"] | None = "racket",
    law: RestoringForce | None = None,
    include_string_bed: bool = False,
    rtol: float = 1e-10,
    method: Integrator = "DOP853",
    hand: Hand | None = None,
) -> TransientImpact:  # 12 parameters: public, called positionally (kept as they are)
    """Simulate a normal impact of the ball at one point of the racket face (reference engine).

    Parameters
    ----------
    racket : Racket
        Mass properties (reduced mass, eq 4), head and strings.
    ball : Ball
        Ball mass and e_BG.
    location : array_like, shape (2,)
        Impact point (x, y) on the string bed, m.
    ball_speed : float
        Incoming ball speed towards the strings, m/s.
    support : {"free", "pinned", "hand"}
        Support condition (:mod:`racketdyn.impact.system`).
    racket_speed : float
        Speed of the impact point towards the ball, m/s.
    modal_model : ModalModel, None or "racket"
        Flexible modes; ``"racket"`` takes the racket's own; ``None`` is a rigid racket.
    law : RestoringForce, optional
        Compound ball+string law F_GB; default :func:`racketdyn.contact.compound_law`.
    include_string_bed : bool
        Keep string-bed modes in the model (off: the compound spring already carries the
        string bed, as in the approximate method).
    rtol : float
        Integrator relative tolerance.
    method : {"DOP853", "Radau"}
        Integrator.
    hand : Hand, optional
        The hand and arm of the ``hand`` support (default :class:`~racketdyn.impact.hand.Hand`).

    Returns
    -------
    TransientImpact
    """
    xy = as_locations(location, "impact point")
    if xy.shape[0] != 1:
        raise InputError(f"impact point: give one (x, y) point (got {xy.shape[0]})")
    racket.head.check_inside(xy)
    one_of("support", support, TRANSIENT_SUPPORTS)
    model = resolve_modal_model(racket, modal_model, include_string_bed)
    law = law or compound_law(racket, ball)
    system = impact_system(racket, model, support, xy, hand if support == "hand" else None)
    reduced = support_reduced_mass(racket, xy, support, hand)[0]
    approach = require_speeds("ball speed", ball_speed) + require_speeds(
        "racket speed", racket_speed
    )
    e_bg = float(with_ball_string_cor(racket, ball).e_bg_at(approach)[0])
    return simulate_system_contact(
        system, 0, ball.mass_kg, e_bg, law, ball_speed, racket_speed, float(reduced),
        rtol, method,
    )  # fmt: skip


STEPS_PER_CONTACT = 128
"""Default steps of the compiled engine over one estimated contact time, extrapolated from a
second run at half as many (:data:`EXTRAPOLATE`): over the bench's face map rebound speed
within ≈ 3e-5 m/s, contact time within ≈ 7e-9 s and vibration energy within ≈ 5e-5 J of the
reference engine (``benchmarks/bench_transient.py``, ``docs/develop.md``)."""
EXTRAPOLATE = True
"""Default of the compiled engine's Richardson extrapolation (runs at h and 2h)."""
COMPILED_SCHEME = (
    f"{STEPS_PER_CONTACT} steps per contact, extrapolated from h and 2h, the step halved where "
    "they disagree (issue 16)"
)
"""The compiled engine's default numerics, as a sweep's hash records them (a sweep made with
another scheme is recomputed, not resumed: the numbers differ at the scheme's accuracy).
Change it whenever the compiled engine's numbers change."""


def predict_transient(
    racket: Racket,
    ball: Ball,
    locations: ArrayLike,
    ball_speed: ArrayLike,
    supports: Sequence[str] | str = SUPPORTS,
    racket_speed: ArrayLike = 0.0,
    modal_model: ModalModel | Literal["racket"] | None = "racket",
    labels: Sequence[str] | None = None,
    law: RestoringForce | None = None,
    include_string_bed: bool = False,
    rtol: float = 1e-10,
    method: Integrator = "DOP853",
    engine: Engine = "auto",
    hand: Hand | None = None,
    steps_per_contact: int = STEPS_PER_CONTACT,
    string_bed: StringBed = "uniform",
    extrapolate: bool = EXTRAPOLATE,
) -> ImpactResult:  # 17 keywords: the public API's, each a documented option and CLI flag
    """Simulate every point × speed × support and collect an :class:`ImpactResult`.

    The arrays are those of :func:`racketdyn.impact.predict`, so ``write_csv`` writes the same
    columns; ``stiffness`` is the linear stiffness with the same half period (π² μ / T_c²).

    Parameters
    ----------
    racket, ball : Racket, Ball
        As for :func:`simulate_impact`; the racket taken as given, as by
        :func:`racketdyn.impact.predict` (check one built in Python with
        :func:`racketdyn.io.check_racket`).
    locations : array_like, shape (n, 2)
        Impact points (x, y), m.
    ball_speed : array_like, shape (s,)
        Incoming ball speeds, m/s.
    supports : str or sequence of {"free", "pinned", "hand"}
        Support conditions (one text of comma-separated names too, ``"free,hand"``).
    racket_speed : float or array_like, shape (s,)
        Speed of the impact point towards the ball, m/s (one, or one per ball speed).
    modal_model : ModalModel, None or "racket"
        Flexible modes (see :func:`simulate_impact`).
    labels : sequence of str, optional
        Point labels (default 1, 2, …).
    law : RestoringForce, optional
        Compound law F_GB.
    include_string_bed : bool
        Keep string-bed modes.
    rtol : float
        Relative tolerance of the reference engine.
    method : {"DOP853", "Radau"}
        Integrator of the reference engine.
    engine : {"auto", "compiled", "reference"}
        ``compiled``: the numba batch integrator (:mod:`racketdyn.impact.kernel`, second order,
        ``steps_per_contact``); ``reference``: one :func:`scipy.integrate.solve_ivp` per
        impact (``rtol``, ``method``); ``auto``: compiled when numba is installed.
    hand : Hand, optional
        The hand and arm of the ``hand`` support.
    steps_per_contact : int
        Steps of the compiled engine over one estimated contact time.
    string_bed : {"uniform", "local"}
        ``uniform``: the face centre's law at every point (the paper's); ``local``: each
        point's own (:func:`racketdyn.impact.grid.predict_by_point_law`).
    extrapolate : bool
        Compiled engine: also run each contact with half as many steps and extrapolate
        (Richardson; order ≈ 3 instead of 2 for 1.5× the steps).

    Returns
    -------
    ImpactResult
        Arrays shaped ``(n_points, n_speeds, n_supports)``; ``inputs["method"]`` is
        ``"transient"``.
    """
    one_of("engine", engine, ENGINES)
    require_whole("steps_per_contact", steps_per_contact, least=16)
    check_string_bed(string_bed, law, racket)
    if string_bed == "local":
        engine_settings = {
            "rtol": rtol, "method": method, "engine": engine, "hand": hand,
            "extrapolate": extrapolate,
        }  # fmt: skip
        return predict_by_point_law(  # type: ignore[no-any-return]
            predict_transient, racket, ball, locations, labels, modal_model, include_string_bed,
            ball_speed=ball_speed, supports=supports, racket_speed=racket_speed,
            steps_per_contact=steps_per_contact, **engine_settings,
        )  # fmt: skip
    grid = impact_grid(
        racket, ball, locations, ball_speed, supports, racket_speed, modal_model, labels, law,
        include_string_bed, allowed_supports=TRANSIENT_SUPPORTS, hand=hand,
    )  # fmt: skip
    if hand is not None and "hand" not in grid.supports:
        raise InputError("a hand is given but no support is 'hand'; add support 'hand'")
    engine = _resolve_engine(engine)
    systems = [
        impact_system(racket, grid.model, s, grid.locations, hand if s == "hand" else None)
        for s in grid.supports
    ]
    run = _run_compiled if engine == "compiled" else _run_reference
    outputs = run(grid, systems, grid.ball, rtol, method, steps_per_contact, extrapolate)
    _flag_frame_shots(grid, outputs)
    inputs = grid.inputs(
        ball,
        "transient",
        integrator=_integrator_settings(engine, rtol, method, steps_per_contact, extrapolate),
        hysteresis="F_un = F_GB(X) (X/X_p)^p, p from e_BG",
        include_string_bed=include_string_bed,
        hand=None if "hand" not in grid.supports else asdict(hand or Hand()),
    )
    return _impact_result(grid, outputs, inputs)


def _impact_result(grid: ImpactGrid, outputs: _Outputs, inputs: dict[str, Any]) -> ImpactResult:
    """The :class:`ImpactResult` of the grid's simulated impacts."""
    out, mode_energy, status, terms = outputs
    return ImpactResult(
        locations=grid.locations,
        labels=grid.labels,
        ball_speed=grid.ball_speed,
        racket_speed=grid.racket_speed,
        supports=grid.supports,
        reduced_mass=grid.reduced_mass,
        mode_energy=mode_energy,
        status=status.astype(str),
        modal_model=grid.model,
        inputs=inputs,
        energy_terms=terms,
        **out,
    )


def _resolve_engine(engine: Engine) -> Engine:
    """``auto``: compiled when numba is installed; ``compiled`` without numba is an error."""
    if engine == "auto":
        engine = "compiled" if NUMBA_AVAILABLE else "reference"
    if engine == "compiled" and not NUMBA_AVAILABLE:
        raise InputError("engine 'compiled' needs numba (pip install numba); use 'reference'")
    return engine


def _flag_frame_shots(grid: ImpactGrid, outputs: _Outputs) -> None:
    """Mark the impacts whose ball reaches the frame (``STATUS_FRAME_CONTACT``), in place."""
    out, _, status, _ = outputs
    frame = (status == STATUS_OK) & grid.reaches_frame(out["peak_deflection"])
    status[frame] = STATUS_FRAME_CONTACT
    if np.any(frame):
        log.warning(
            "%d of %d impacts: %s (their results are NaN)",
            int(frame.sum()), status.size, STATUS_FRAME_CONTACT,
        )  # fmt: skip


def _integrator_settings(
    engine: Engine, rtol: float, method: str, steps_per_contact: int, extrapolate: bool
) -> dict[str, Any]:
    """The engine's numerics as the run record shows them."""
    if engine != "compiled":
        return {"engine": "reference", "method": method, "rtol": rtol}
    return {
        "engine": "compiled",
        "steps_per_contact": steps_per_contact,
        "extrapolation": "from h and 2h (Richardson)" if extrapolate else "none",
        "order": (
            "3 (1 + n for a power law F = c Xⁿ with n < 1)"
            if extrapolate
            else "2 (1 + n for a power law F = c Xⁿ with n < 1)"
        ),
    }


_FIELDS = (
    "stiffness",
    "peak_deflection",
    "contact_time",
    "mean_force",
    "peak_force",
    "vibration_energy",
    "cor",
    "rebound_ratio",
    "rebound_speed",
)


def _values(impact: TransientImpact) -> dict[str, float]:
    return {
        "stiffness": impact.stiffness_n_per_m,
        "peak_deflection": impact.peak_deflection_m,
        "contact_time": impact.contact_time_s,
        "mean_force": impact.mean_force_n,
        "peak_force": impact.peak_force_n,
        "vibration_energy": impact.vibration_energy_j,
        "cor": impact.cor,
        "rebound_ratio": impact.rebound_ratio,
        "rebound_speed": impact.rebound_speed_mps,
    }


_Outputs = tuple[
    dict[str, NDArray[np.float64]],
    NDArray[np.float64],
    NDArray[Any],
    dict[str, NDArray[np.float64]],
]

ENERGY_TERMS: tuple[str, ...] = (
    "energy_in_j",
    "ball_energy_out_j",
    "racket_energy_j",
    "vibration_energy_j",
    "support_energy_j",
    "hysteresis_loss_j",
    "damping_loss_j",
)
"""Where the ball's energy goes, J, in the frame where the racket is at rest before impact:
the first term is the sum of the others (``ImpactResult.energy_terms``)."""


def _energy_terms(impact: TransientImpact, ball_mass: float) -> dict[str, float]:
    """The energy balance of one impact in the racket's rest frame before impact, J."""
    v_r = impact.racket_speed_mps
    approach = impact.ball_speed_mps + v_r
    return {
        "energy_in_j": 0.5 * ball_mass * approach**2,
        "ball_energy_out_j": 0.5 * ball_mass * (impact.rebound_speed_mps - v_r) ** 2,
        "racket_energy_j": impact.racket_energy_j,
        "vibration_energy_j": impact.vibration_energy_j,
        "support_energy_j": impact.support_energy_j,
        "hysteresis_loss_j": impact.hysteresis_loss_j,
        "damping_loss_j": impact.damping_loss_j,
    }


def _empty_outputs(
    shape: tuple[int, int, int], n_modes: int
) -> tuple[dict[str, NDArray[np.float64]], NDArray[np.float64], NDArray[Any]]:
    out = {name: np.full(shape, np.nan) for name in _FIELDS}
    return out, np.full((*shape, n_modes), np.nan), np.full(shape, STATUS_OK, dtype=object)


def _run_reference(
    grid: ImpactGrid, systems: list[ImpactSystem], ball: Ball, rtol: float, method: str,
    steps_per_contact: int, extrapolate: bool,
) -> _Outputs:  # fmt: skip
    """One solve_ivp per impact, in physical coordinates."""
    n_modes = 0 if grid.model is None else grid.model.n_modes
    out, mode_energy, status = _empty_outputs(grid.shape, n_modes)
    terms = {name: np.full(grid.shape, np.nan) for name in ENERGY_TERMS}
    for i, j, k in np.ndindex(grid.shape):
        approach = float(grid.ball_speed[j] + grid.racket_speed[j])
        impact = simulate_system_contact(
            systems[k], i, ball.mass_kg, float(ball.e_bg_at(approach)), grid.law,
            float(grid.ball_speed[j]),
            float(grid.racket_speed[j]), float(grid.reduced_mass[i, k]), rtol,
            method,  # type: ignore[arg-type]
        )  # fmt: skip
        status[i, j, k] = impact.status
        for name, value in _values(impact).items():
            out[name][i, j, k] = value
        mode_energy[i, j, k] = impact.mode_energy_j
        for name, value in _energy_terms(impact, ball.mass_kg).items():
            terms[name][i, j, k] = value
    return out, mode_energy, status, terms


def _run_compiled(
    grid: ImpactGrid, systems: list[ImpactSystem], ball: Ball, rtol: float, method: str,
    steps_per_contact: int, extrapolate: bool,
) -> _Outputs:  # fmt: skip
    """All impacts in one call of the numba kernel, then the energies vectorised."""
    n_points, n_speeds, n_supports = grid.shape
    law, m_b = grid.law, ball.mass_kg
    forms = [system.pole_residue() for system in systems]
    n_poles = max(form.poles.size for form in forms)
    n_sys = n_points * n_supports  # one system row per (point, support)
    poles = np.full((n_sys, n_poles), -1.0 + 0j)
    residues = np.zeros((n_sys, n_poles), complex)
    weights = np.zeros((n_sys, n_poles))
    compliance = np.zeros(n_sys)
    for k, form in enumerate(forms):
        rows = np.arange(n_points) * n_supports + k
        poles[rows, : form.poles.size] = form.poles
        residues[rows, : form.poles.size] = form.residues
        weights[rows, : form.poles.size] = form.weights
        compliance[rows] = form.rigid_compliance
    index = np.arange(n_sys).reshape(n_points, 1, n_supports)
    system_index = np.broadcast_to(index, grid.shape).ravel()
    v_in = np.broadcast_to(grid.ball_speed[None, :, None], grid.shape).ravel()
    v_r = np.broadcast_to(grid.racket_speed[None, :, None], grid.shape).ravel()
    approach = v_in + v_r
    c_r = compliance[system_index]
    mu = m_b / (1.0 + m_b * c_r)
    step = elastic_contact(law, mu, approach)[1] / steps_per_contact
    e_bg = ball.e_bg_at(approach)  # per impact, at its relative speed
    kind, coefficients = law_arrays(law.kind, law.coefficients)
    modal, raw = integrate_impacts(
        system_index, approach, step, poles, residues, weights, compliance, m_b, e_bg,
        kind, coefficients, law.max_deflection_m, 50 * steps_per_contact, extrapolate,
    )  # fmt: skip
    n_modes = 0 if grid.model is None else grid.model.n_modes
    out, mode_energy, status = _empty_outputs(grid.shape, n_modes)
    code = raw[:, 0].astype(int)
    texts = {
        STATUS_CODE_OK: STATUS_OK,
        STATUS_CODE_BEYOND_LAW: STATUS_BEYOND_LAW,
        STATUS_CODE_NO_SEPARATION: STATUS_NO_SEPARATION,
        STATUS_CODE_SECOND_CONTACT: STATUS_SECOND_CONTACT,
    }
    status[...] = np.array([texts[c] for c in code], dtype=object).reshape(grid.shape)
    # physical end state per impact: rigid part + Σ weight Re(v_k u_k), per support
    rigid_energy = np.zeros(code.size)
    support_energy = np.zeros(code.size)
    point_velocity = np.zeros(code.size)
    modes = np.zeros((code.size, n_modes))
    for k, (system, form) in enumerate(zip(systems, forms, strict=True)):
        flat = np.flatnonzero(np.arange(code.size) % n_supports == k)
        point = flat // (n_speeds * n_supports)
        p = form.poles.size
        state = np.einsum(
            "ipn,ip->in", form.state_vectors[point] * form.weights[None, :, None], modal[flat, :p]
        ).real
        n_q = system.n_coordinates
        q = state[:, :n_q] + form.rigid_vectors[point] * raw[flat, 5][:, None]
        q_dot = state[:, n_q:] + form.rigid_vectors[point] * raw[flat, 6][:, None]
        rigid_energy[flat], modes[flat], support_energy[flat] = system.energies(q, q_dot)
        point_velocity[flat] = np.take_along_axis(
            system.rigid_point_velocity(q_dot), point[:, None], axis=1
        )[:, 0]
    reduced = np.broadcast_to(grid.reduced_mass[:, None, :], grid.shape).ravel()
    ok = code == STATUS_CODE_OK
    with np.errstate(invalid="ignore", divide="ignore"):
        numbers = _lab_numbers(
            _ImpactSetting(v_in, v_r, m_b, e_bg, law, reduced),
            _RestFrameEnd(
                point_velocity, raw[:, 4], raw[:, 1], raw[:, 3], rigid_energy, modes,
                support_energy, None,
            ),
        )  # fmt: skip
    for name in _FIELDS:
        out[name] = np.where(ok, numbers[name], np.nan).reshape(grid.shape)
    rest = {
        "energy_in_j": 0.5 * m_b * approach**2,
        "ball_energy_out_j": 0.5 * m_b * raw[:, 4] ** 2,
        "racket_energy_j": rigid_energy,
        "vibration_energy_j": numbers["vibration_energy"],
        "support_energy_j": support_energy,
        "hysteresis_loss_j": numbers["hysteresis_loss"],
        "damping_loss_j": numbers["damping_loss"],
    }
    terms = {name: np.where(ok, rest[name], np.nan).reshape(grid.shape) for name in ENERGY_TERMS}
    mode_energy = np.where(ok[:, None], modes, np.nan).reshape((*grid.shape, n_modes))
    if np.any(code != STATUS_CODE_OK):
        log.warning(
            "transient: %d of %d impacts have no valid numbers (see the status column)",
            int(np.sum(code != STATUS_CODE_OK)), code.size,
        )  # fmt: skip
    return out, mode_energy, status, terms
