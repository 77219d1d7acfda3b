"""Transient simulation of a normal ball–racket impact (issue 5, first increment).

The approximate method (:mod:`racketdyn.impact.approximate`) assumes the contact force is a
half-sine and charges the vibration it leaves against e_BG.  Here the contact is integrated in
time instead, for a normal impact at one point j = (x, y) of the face:

* the ball, a point mass m_B at displacement x_B (positive into the strings), meets the racket
  through the compound ball+string spring F_GB(X) (section 3.4), X = x_B − w the compression;
* the racket's rigid-body freedom under the support is the reduced mass M_r at the impact point
  (eq 4, :meth:`racketdyn.racket.Racket.reduced_mass`): a force F at j gives the point the
  acceleration F/M_r, exactly, for the rigid-body part of the response;
* its flexible modes are those of a :class:`~racketdyn.modal.model.ModalModel` (mass-normalised
  shapes φ_k, frame modes by default):
  ``q̈_k + 2 ζ_k ω_k q̇_k + ω_k² q_k = φ_k(j) F``, and the face moves by
  ``w = w_rigid + Σ_k φ_k(j) q_k``.

So ``m_B ẍ_B = −F``, ``ẅ_rigid = F/M_r`` and the modal equations above, with F = 0 once the ball
leaves the strings.  The free-body receptance at j is exactly rigid + Σ flexible modes; for
``pinned`` the modes are still those of the model given (the free modes by default), as in the
approximate method.

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
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law
from racketdyn.errors import InputError, one_of, require_positive, require_range, require_speeds
from racketdyn.impact.approximate import elastic_contact_time
from racketdyn.impact.grid import impact_grid, resolve_modal_model
from racketdyn.impact.result import STATUS_BEYOND_LAW, STATUS_OK, ImpactResult
from racketdyn.modal import ModalModel
from racketdyn.racket import SUPPORTS, Racket, as_locations

__all__ = [
    "INTEGRATORS",
    "STATUS_NO_SEPARATION",
    "TransientImpact",
    "predict_transient",
    "simulate_contact",
    "simulate_impact",
    "unloading_exponent",
]

log = logging.getLogger(__name__)

Integrator = Literal["DOP853", "Radau"]
INTEGRATORS: tuple[str, ...] = ("DOP853", "Radau")
STATUS_NO_SEPARATION = "ball did not leave the strings within the time allowed"

_HISTORY_SAMPLES = 400  # samples of the time histories over one estimated contact time
_RELOAD_MARGIN = 1e-9  # reload onto F_GB once X exceeds X_p by this fraction
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
        Energy lost to modal damping during contact, ∫ Σ 2 ζ ω q̇² dt, J.
    racket_energy_gain_j : float
        Change of the racket's rigid-body kinetic energy ½ M_r V_r², J.
    status : str
        ``ok`` or why the numbers are NaN.
    time_s, force_n, ball_displacement_m, deflection_m : ndarray (n_t,)
        Time histories from first contact: time, contact force, ball displacement (into the
        strings) and compression X.
    modal_coordinates : ndarray (n_t, n_modes)
        Modal coordinates q_k, m·√kg.
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
    racket_energy_gain_j: float
    status: str
    time_s: NDArray[np.float64]
    force_n: NDArray[np.float64]
    ball_displacement_m: NDArray[np.float64]
    deflection_m: NDArray[np.float64]
    modal_coordinates: NDArray[np.float64]

    @property
    def stiffness_n_per_m(self) -> float:
        """Linear stiffness with the same half period, π² μ / T_c², N/m (eq 7 solved for K)."""
        return float(np.pi**2 * self.mu_kg / self.contact_time_s**2)


# --- the hysteresis law --------------------------------------------------------------------------
def _unloading_area(law: RestoringForce, peak: float, exponent: float) -> float:
    """``∫₀^{X_p} F(X) (X/X_p)^p dX`` in closed form, J."""
    if law.kind == "power":
        c, n = law.coefficients
        return float(c * peak ** (n + 1.0) / (n + 1.0 + exponent))
    c_k = np.asarray(law.coefficients)
    k = np.arange(1, c_k.size + 1)
    return float(np.sum(c_k * peak ** (k + 1.0) / (k + 1.0 + exponent)))


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
    target = e_bg**2 * float(law.energy(peak))
    high = 1.0
    while _unloading_area(law, peak, high) > target:
        high *= 2.0
    return float(
        brentq(lambda p: _unloading_area(law, peak, p) - target, 0.0, high, xtol=1e-14, rtol=1e-15)
    )


def _scalar_force(law: RestoringForce) -> Callable[[float], float]:
    """F(X) for a float X ≥ 0, in plain Python (no numpy call per evaluation)."""
    if law.kind == "power":
        c, n = law.coefficients
        return lambda x: c * x**n if x > 0.0 else 0.0
    coefficients = tuple(reversed(law.coefficients))

    def force(x: float) -> float:
        if x <= 0.0:
            return 0.0
        total = 0.0
        for c in coefficients:
            total = total * x + c
        return total * x

    return force


# --- the core ------------------------------------------------------------------------------------
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
) -> TransientImpact:
    """Integrate one normal impact from first contact to separation.

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
    m_b = require_positive("ball mass", ball_mass)
    require_range("e_bg", e_bg, 0.0, 1.0)
    if e_bg == 0:
        raise InputError("e_bg must be above 0")
    m_r = float(reduced_mass)
    if not math.isinf(m_r):
        require_positive("reduced mass", m_r)
    elif m_r < 0:
        raise InputError("reduced mass must be positive (inf for a clamped head)")
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
    phi = np.atleast_1d(np.asarray(mode_shapes, dtype=float))
    w_k = np.atleast_1d(np.asarray(omega, dtype=float))
    zeta = np.atleast_1d(np.asarray(damping_ratio, dtype=float))
    if not (phi.shape == w_k.shape == zeta.shape) or phi.ndim != 1:
        raise InputError("give one mode shape value, omega and damping ratio per mode")
    if not (np.all(np.isfinite(phi)) and np.all(w_k > 0) and np.all(zeta >= 0)):
        raise InputError("mode shapes must be finite, omega positive, damping ratios ≥ 0")
    n_modes = phi.size
    compliance = 0.0 if math.isinf(m_r) else 1.0 / m_r
    stiffness_w, damping_w = w_k**2, 2.0 * zeta * w_k
    loading_force = _scalar_force(law)

    # scales for the absolute tolerances and the time allowed
    approach = v_in + v_r
    mu = m_b / (1.0 + m_b * compliance)
    elastic_peak = float(law.deflection_at_energy(0.5 * mu * approach**2))
    if not math.isfinite(elastic_peak):
        elastic_peak = law.max_deflection_m
    t_estimate = float(elastic_contact_time(law, mu, elastic_peak))
    modal_speed = np.maximum(np.abs(phi), 1e-3 * max(float(np.abs(phi).max(initial=0.0)), 1.0))
    modal_speed = modal_speed * 2.0 * mu * approach
    scale = np.concatenate(
        [
            [elastic_peak, approach, elastic_peak, approach],
            modal_speed / w_k,
            modal_speed,
            [0.5 * mu * approach**2],
        ]
    )
    atol = rtol * scale

    def deflection(y: NDArray[np.float64]) -> float:
        return float(y[0] - y[2] - phi @ y[4 : 4 + n_modes])

    def deflection_rate(y: NDArray[np.float64]) -> float:
        return float(y[1] - y[3] - phi @ y[4 + n_modes : 4 + 2 * n_modes])

    def make_rhs(force: Callable[[float], float]) -> Callable[[float, Any], NDArray[np.float64]]:
        def rhs(t: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
            f = force(deflection(y))
            q, q_dot = y[4 : 4 + n_modes], y[4 + n_modes : 4 + 2 * n_modes]
            dy = np.empty_like(y)
            dy[0] = y[1]
            dy[1] = -f / m_b
            dy[2] = y[3]
            dy[3] = f * compliance
            dy[4 : 4 + n_modes] = q_dot
            dy[4 + n_modes : 4 + 2 * n_modes] = phi * f - damping_w * q_dot - stiffness_w * q
            dy[-1] = float(damping_w @ (q_dot * q_dot))
            return dy

        return rhs

    def event(fn: Callable[[NDArray[np.float64]], float], direction: float) -> Any:
        def wrapped(t: float, y: NDArray[np.float64]) -> float:
            return fn(y)

        wrapped.terminal = True  # type: ignore[attr-defined]
        wrapped.direction = direction  # type: ignore[attr-defined]
        return wrapped

    turn = event(deflection_rate, -1.0)
    beyond = event(lambda y: deflection(y) - law.max_deflection_m, 1.0)
    separation = event(deflection, -1.0)

    # state: ball x, v; racket rigid w, v; q; q̇; damping loss.  +: into the strings.
    y0 = np.zeros(5 + 2 * n_modes)
    y0[1], y0[3] = v_in, -v_r
    t0, peak, loading, status = 0.0, 0.0, True, STATUS_NO_SEPARATION
    t_allowed = 50.0 * t_estimate
    times: list[NDArray[np.float64]] = []
    states: list[NDArray[np.float64]] = []
    forces: list[NDArray[np.float64]] = []
    for _ in range(_MAX_PHASES):
        if loading:
            force = loading_force
            events = [turn, beyond]
        else:
            exponent = unloading_exponent(law, e_bg, peak)

            def force(x: float, _p: float = exponent, _xp: float = peak) -> float:
                return loading_force(x) * (x / _xp) ** _p if x > 0.0 else 0.0

            def past_peak(y: NDArray[np.float64], _xp: float = peak) -> float:
                return deflection(y) - _xp * (1.0 + _RELOAD_MARGIN)

            reload = event(past_peak, 1.0)
            events = [separation, reload]
        solution: Any = solve_ivp(
            make_rhs(force),
            (t0, t_allowed),
            y0,
            method=method,
            rtol=rtol,
            atol=atol,
            events=events,
            dense_output=True,
        )
        if not solution.success:
            raise RuntimeError(f"transient impact: the integrator failed ({solution.message})")
        t_end = float(solution.t[-1])
        n_samples = max(int(np.ceil(_HISTORY_SAMPLES * (t_end - t0) / t_estimate)), 4)
        t_phase = np.linspace(t0, t_end, n_samples)
        y_phase = solution.sol(t_phase)
        y_phase[:, -1] = solution.y[:, -1]
        times.append(t_phase)
        states.append(y_phase)
        forces.append(np.array([force(deflection(y)) for y in y_phase.T]))
        hit = [len(t) > 0 for t in solution.t_events]
        if solution.status != 1 or not any(hit):
            break  # out of time
        which = hit.index(True)
        t0, y0 = float(solution.t_events[which][0]), np.array(solution.y_events[which][0])
        if loading and which == 0:  # turn: start unloading from the new peak
            peak, loading = deflection(y0), False
        elif loading:  # beyond the law's range
            status = STATUS_BEYOND_LAW
            break
        elif which == 0:  # separation
            status = STATUS_OK
            break
        else:  # reload past the old peak along F_GB
            loading = True

    time = np.concatenate(times)
    history = np.concatenate(states, axis=1)
    force_history = np.concatenate(forces)
    q_history = history[4 : 4 + n_modes].T
    compression = history[0] - history[2] - q_history @ phi
    if status != STATUS_OK:
        log.warning("transient impact at %.3g m/s: %s (results are NaN)", approach, status)
        nan = math.nan
        return TransientImpact(
            v_in, v_r, m_r, mu, nan, nan, nan, nan, nan, nan, nan, nan, nan,
            np.full(n_modes, nan), nan, nan, nan, nan, status,
            time, force_history, history[0], compression, q_history,
        )  # fmt: skip

    y_end = y0
    v_ball_out, v_racket_out = float(y_end[1]), float(y_end[3])
    q_end, q_dot_end = y_end[4 : 4 + n_modes], y_end[4 + n_modes : 4 + 2 * n_modes]
    mode_energy = 0.5 * q_dot_end**2 + 0.5 * stiffness_w * q_end**2
    impulse = m_b * (v_in - v_ball_out)
    cor = (v_racket_out - v_ball_out) / (v_in + v_r)
    mass_ratio = m_b * compliance
    gain = 0.0 if compliance == 0 else 0.5 * m_r * (v_racket_out**2 - v_r**2)
    return TransientImpact(
        ball_speed_mps=v_in,
        racket_speed_mps=v_r,
        reduced_mass_kg=m_r,
        mu_kg=mu,
        contact_time_s=t0,
        peak_force_n=loading_force(peak),  # F_un ≤ F_GB ≤ F_GB(X_max) everywhere
        mean_force_n=impulse / t0,
        impulse_ns=impulse,
        peak_deflection_m=peak,
        rebound_speed_mps=-v_ball_out,
        racket_velocity_mps=v_racket_out,
        rebound_ratio=(cor - mass_ratio) / (1.0 + mass_ratio),
        cor=cor,
        mode_energy_j=mode_energy,
        vibration_energy_j=float(mode_energy.sum()),
        hysteresis_loss_j=(1.0 - e_bg**2) * float(law.energy(peak)),
        damping_loss_j=float(y_end[-1]),
        racket_energy_gain_j=gain,
        status=status,
        time_s=time,
        force_n=force_history,
        ball_displacement_m=history[0],
        deflection_m=compression,
        modal_coordinates=q_history,
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
) -> TransientImpact:
    """Simulate a normal impact of the ball at one point of the racket face.

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
    support : {"free", "pinned"}
        Support condition for the rigid-body reduced mass.
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

    Returns
    -------
    TransientImpact
    """
    xy = as_locations(location, "impact point")
    if xy.shape[0] != 1:
        raise InputError(f"impact point: give one (x, y) point (got {xy.shape[0]})")
    racket.head.check_inside(xy)
    one_of("support", support, SUPPORTS)
    model = resolve_modal_model(racket, modal_model, include_string_bed)
    law = law or compound_law(racket, ball)
    shapes = np.zeros(0) if model is None else model.mode_shapes_at(xy)[0]
    return simulate_contact(
        ball.mass_kg,
        ball.e_bg,
        law,
        float(racket.reduced_mass(xy, support)[0]),
        ball_speed,
        racket_speed,
        shapes,
        np.zeros(0) if model is None else model.omega,
        np.zeros(0) if model is None else model.damping_ratio,
        rtol=rtol,
        method=method,
    )


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
) -> ImpactResult:
    """Simulate every point × speed × support and collect an :class:`ImpactResult`.

    The arrays are those of :func:`racketdyn.impact.predict`, so ``write_csv`` writes the same
    columns; ``stiffness`` is the linear stiffness with the same half period (π² μ / T_c²).

    Parameters
    ----------
    racket, ball : Racket, Ball
        As for :func:`simulate_impact`.
    locations : array_like, shape (n, 2)
        Impact points (x, y), m.
    ball_speed : array_like, shape (s,)
        Incoming ball speeds, m/s.
    supports : str or sequence of {"free", "pinned"}
        Support conditions.
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
        Integrator relative tolerance.
    method : {"DOP853", "Radau"}
        Integrator.

    Returns
    -------
    ImpactResult
        Arrays shaped ``(n_points, n_speeds, n_supports)``; ``inputs["method"]`` is
        ``"transient"``.
    """
    grid = impact_grid(
        racket,
        ball,
        locations,
        ball_speed,
        supports,
        racket_speed,
        modal_model,
        labels,
        law,
        include_string_bed,
    )
    xy, model, law, reduced = grid.locations, grid.model, grid.law, grid.reduced_mass
    v_ball, v_racket = grid.ball_speed, grid.racket_speed
    shapes = np.zeros((len(xy), 0)) if model is None else model.mode_shapes_at(xy)
    omega = np.zeros(0) if model is None else model.omega
    zeta = np.zeros(0) if model is None else model.damping_ratio

    shape = grid.shape
    fields = (
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
    out = {name: np.full(shape, np.nan) for name in fields}
    mode_energy = np.full((*shape, omega.size), np.nan)
    status = np.full(shape, STATUS_OK, dtype=object)
    # Plain path: one solve_ivp per impact.  The compiled batch path (numba: a fixed-step or
    # embedded RK over all impacts at once, with the same phase/event logic) goes here, with
    # this loop kept as its fallback and reference.
    for i, j, k in np.ndindex(shape):
        impact = simulate_contact(
            ball.mass_kg,
            ball.e_bg,
            law,
            float(reduced[i, k]),
            float(v_ball[j]),
            float(v_racket[j]),
            shapes[i],
            omega,
            zeta,
            rtol=rtol,
            method=method,
        )
        status[i, j, k] = impact.status
        values = {
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
        for name, value in values.items():
            out[name][i, j, k] = value
        mode_energy[i, j, k] = impact.mode_energy_j

    inputs = grid.inputs(
        ball,
        "transient",
        integrator={"method": method, "rtol": rtol},
        hysteresis="F_un = F_GB(X) (X/X_p)^p, p from e_BG",
        include_string_bed=include_string_bed,
    )
    return ImpactResult(
        locations=xy,
        labels=grid.labels,
        ball_speed=v_ball,
        racket_speed=v_racket,
        supports=grid.supports,
        reduced_mass=reduced,
        mode_energy=mode_energy,
        status=status.astype(str),
        modal_model=model,
        inputs=inputs,
        **out,
    )
