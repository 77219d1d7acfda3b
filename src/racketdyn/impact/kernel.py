"""Compiled batch integrator of the transient impact (numba), over many impacts at once.

Each impact is the ball (mass m_B, ``ẍ_B = −F/m_B``) on the hysteretic compound spring
(:mod:`racketdyn.impact.transient`) against a racket given by its receptance at the point in
pole–residue form (:class:`racketdyn.impact.system.PoleResidue`):

    ``w = c ρ + Σ_k weight_k Re(r_k u_k)``,  ``ρ̈ = F``,  ``u̇_k = λ_k u_k + F``.

The scheme is an exponential integrator with the contact force linear over each step (a
first-order hold): the racket's linear part is integrated exactly for that force, the ball's
too, so the only approximation is the force's linear interpolation — second order in the step
h.  The end-of-step force is implicit, ``X_{n+1} = X_free − α F(X_{n+1})`` with α > 0, solved by
a safeguarded Newton iteration (unique root because F rises with X).  Events inside a step:

* the turn (X stops rising): the peak X_p is the vertex of the parabola through the last three
  compressions (error O(h³)), the unloading exponent p is solved for it and the step is redone
  on the unloading curve;
* separation (X reaches 0 while unloading): the step is shortened to the crossing (secant on
  the step length, the force ramping to zero), so the state at separation is consistent;
* reloading past X_p goes back onto F_GB;
* after separation the ball and the racket move freely (exact for F = 0) for
  :func:`recontact_horizon`; a compression above ``RECONTACT_TOLERANCE · X_p`` then is a second
  contact (status ``STATUS_CODE_SECOND_CONTACT``: the vibrating frame caught the ball again).

Tested against the reference engine (scipy's DOP853 in physical coordinates) and shown to
converge at order 2 as h halves (``tests/test_kernel.py``).  Without numba the same functions
run as plain Python (correct, ~100× slower); :func:`racketdyn.impact.transient.predict_transient`
then uses the reference engine instead.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar, cast

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "NUMBA_AVAILABLE",
    "RECONTACT_TOLERANCE",
    "RELOAD_MARGIN",
    "STATUS_CODE_BEYOND_LAW",
    "STATUS_CODE_NO_SEPARATION",
    "STATUS_CODE_OK",
    "STATUS_CODE_SECOND_CONTACT",
    "integrate_impacts",
    "law_arrays",
]

F = TypeVar("F", bound=Callable[..., Any])

try:  # numba is a dependency; the plain path is kept for platforms without a wheel
    import numba

    NUMBA_AVAILABLE = True

    def _compiled(function: F) -> F:
        return cast(F, numba.njit(cache=True, nogil=True, error_model="numpy")(function))

except ImportError:  # pragma: no cover - exercised only without numba
    NUMBA_AVAILABLE = False

    def _compiled(function: F) -> F:
        return function


STATUS_CODE_OK = 0
STATUS_CODE_BEYOND_LAW = 1
STATUS_CODE_NO_SEPARATION = 2
STATUS_CODE_SECOND_CONTACT = 3
LAW_POLYNOMIAL = 0
LAW_POWER = 1
RELOAD_MARGIN = 1e-9
"""Reload onto F_GB once X exceeds the peak X_p by this fraction (both engines)."""
RECONTACT_TOLERANCE = 1e-6
"""After separation, a compression above this fraction of X_p is a second contact (both
engines)."""


@_compiled
def recontact_horizon(
    poles: NDArray[np.complex128], weights: NDArray[np.float64], contact_time: float
) -> float:
    """How long to follow the ball after it leaves, s: one period 2π/|λ| of the racket's
    slowest pole, at most twice the contact time (0 for a rigid racket, which cannot catch
    the ball up).

    The gap opens at the rigid-body separation speed while the vibration that could close it
    is bounded and decays, so the frame comes back within its slowest period or not at all.
    Motions slower than the contact (the hand and arm's poles, a few Hz) act on the impact as
    the support does, and their return a tenth of a second later belongs to the stroke's
    follow-through, which no support model here drives: hence the cap.
    """
    slowest = 0.0
    for k in range(poles.size):
        size = abs(poles[k])
        if weights[k] > 0.0 and size > 0.0 and (slowest == 0.0 or size < slowest):
            slowest = size
    if slowest == 0.0:
        return 0.0
    return min(2.0 * np.pi / slowest, 2.0 * contact_time)


@_compiled
def _law(x: float, kind: int, coefficients: NDArray[np.float64]) -> tuple[float, float]:
    """Loading curve F_GB(x) and its slope, N and N/m (0 for x ≤ 0)."""
    if x <= 0.0:
        return 0.0, 0.0
    if kind == LAW_POWER:
        c, n = float(coefficients[0]), float(coefficients[1])
        force = c * x**n
        return force, n * force / x
    total = 0.0
    slope = 0.0
    for i in range(coefficients.size - 1, -1, -1):
        c = coefficients[i]
        total = total * x + c
        slope = slope * x + (i + 1) * c
    return total * x, slope


@_compiled
def _energy(x: float, kind: int, coefficients: NDArray[np.float64], exponent: float) -> float:
    """``∫₀^x F_GB(X) (X/x)^p dX`` (p = exponent; p = 0 is the stored energy), J."""
    if kind == LAW_POWER:
        c, n = float(coefficients[0]), float(coefficients[1])
        return float(c * x ** (n + 1.0) / (n + 1.0 + exponent))
    total = 0.0
    for i in range(coefficients.size):
        total += float(coefficients[i]) * x ** (i + 2.0) / (i + 2.0 + exponent)
    return total


@_compiled
def _unloading_exponent(
    peak: float, e_bg: float, kind: int, coefficients: NDArray[np.float64]
) -> float:
    """p with ``∫₀^{X_p} F_GB (X/X_p)^p dX = e_BG² E_GB(X_p)`` (Newton; the left side is
    convex and falling in p, so Newton from p = 0 rises monotonically to the root)."""
    if e_bg >= 1.0:
        return 0.0
    if kind == LAW_POWER:
        return (float(coefficients[1]) + 1.0) * (1.0 / (e_bg * e_bg) - 1.0)
    target = e_bg * e_bg * _energy(peak, kind, coefficients, 0.0)
    p = 0.0
    for _ in range(200):
        value = -target
        slope = 0.0
        for i in range(coefficients.size):
            term = coefficients[i] * peak ** (i + 2.0)
            value += term / (i + 2.0 + p)
            slope -= term / (i + 2.0 + p) ** 2
        step = value / slope
        p -= step
        if abs(step) <= 1e-15 * (1.0 + p):
            break
    return p


@_compiled
def _contact_force(
    x: float, loading: bool, peak: float, exponent: float, kind: int,
    coefficients: NDArray[np.float64],
) -> tuple[float, float]:  # fmt: skip
    """Force and slope on the current branch: F_GB loading, F_GB (x/X_p)^p unloading."""
    force, slope = _law(x, kind, coefficients)
    if loading or force == 0.0 or exponent == 0.0:
        return force, slope
    ratio = (x / peak) ** exponent
    return force * ratio, slope * ratio + force * exponent * ratio / x


@_compiled
def _solve_compression(
    free: float, alpha: float, guess: float, loading: bool, peak: float, exponent: float,
    kind: int, coefficients: NDArray[np.float64],
) -> float:  # fmt: skip
    """X with ``X + α F(X) = X_free`` (F rises with X, so the root is unique)."""
    if free <= 0.0:
        return free
    low, high = 0.0, free
    x = min(max(guess, low), high)
    if x <= 0.0:
        x = 0.5 * free
    for _ in range(100):
        force, slope = _contact_force(x, loading, peak, exponent, kind, coefficients)
        residual = x + alpha * force - free
        if residual > 0.0:
            high = x
        else:
            low = x
        step = residual / (1.0 + alpha * slope)
        trial = x - step
        if abs(step) <= 1e-14 * free:  # quadratic convergence: the next error is ~ step²
            return trial
        if trial <= low or trial >= high:
            trial = 0.5 * (low + high)
        x = trial
    return x


@_compiled
def _step_coefficients(
    poles: NDArray[np.complex128], h: float, decay: NDArray[np.complex128],
    first: NDArray[np.complex128], second: NDArray[np.complex128],
) -> None:  # fmt: skip
    """e^{λh}, ∫₀ʰ e^{λ(h−s)}(1 − s/h) ds and ∫₀ʰ e^{λ(h−s)} s/h ds for each pole."""
    for k in range(poles.size):
        z = poles[k] * h
        e = np.exp(z)
        decay[k] = e
        if abs(z) < 0.05:  # series to z⁷ (error < 1e-16); the closed form would cancel here
            e1 = 0.0 + 0.0j
            e2 = 0.0 + 0.0j
            term = 1.0 + 0.0j
            factorial = 1.0
            for j in range(8):
                factorial *= j + 1.0
                e1 += term / factorial  # z^j / (j + 1)!
                e2 += term / (factorial * (j + 2.0))  # z^j / (j + 2)!
                term *= z
            e1 *= h
            e2 *= h
        else:
            e1 = (e - 1.0) / poles[k]
            e2 = (e - 1.0 - z) / (poles[k] * z)
        first[k] = e1 - e2
        second[k] = e2


@_compiled
def _integrate_one(
    poles: NDArray[np.complex128], residues: NDArray[np.complex128],
    weights: NDArray[np.float64], compliance: float, approach: float, h: float,
    ball_mass: float, e_bg: float, kind: int, coefficients: NDArray[np.float64],
    max_deflection: float, max_steps: int, modal: NDArray[np.complex128],
    result: NDArray[np.float64],
) -> None:  # fmt: skip
    """One impact, in the frame where the racket starts at rest.  Fills ``modal`` with u_k
    at separation and ``result`` with: status, contact time, F_GB(X_max), X_max, ball
    velocity, ρ, ρ̇, steps taken."""
    n_poles = poles.size
    decay = np.empty(n_poles, np.complex128)
    first = np.empty(n_poles, np.complex128)
    second = np.empty(n_poles, np.complex128)
    predicted = np.empty(n_poles, np.complex128)
    _step_coefficients(poles, h, decay, first, second)
    m = ball_mass
    alpha = h * h / 6.0 * (1.0 / m + compliance)
    for k in range(n_poles):
        alpha += weights[k] * (residues[k] * second[k]).real
    for k in range(n_poles):
        modal[k] = 0.0
    x_b, v_b, rho, rho_dot, force = 0.0, approach, 0.0, 0.0, 0.0
    earlier, before, now = 0.0, 0.0, 0.0  # X at the last three steps
    loading, peak, exponent = True, 0.0, 0.0
    status = STATUS_CODE_NO_SEPARATION
    t = 0.0
    steps = 0
    while steps < max_steps:
        x_pred = x_b + h * v_b - h * h * force / (3.0 * m)
        rho_pred = rho + h * rho_dot + h * h * force / 3.0
        w_pred = compliance * rho_pred
        for k in range(n_poles):
            predicted[k] = decay[k] * modal[k] + first[k] * force
            w_pred += weights[k] * (residues[k] * predicted[k]).real
        free = x_pred - w_pred
        guess = 3.0 * (now - before) + earlier  # quadratic extrapolation
        x_new = _solve_compression(free, alpha, guess, loading, peak, exponent, kind, coefficients)
        if loading and steps > 0 and x_new < now:
            # turned inside the step: the peak is the vertex of the parabola (before, now, new)
            curvature = 0.5 * (x_new - 2.0 * now + before)
            slope = 0.5 * (x_new - before)
            peak = now
            if curvature < 0.0:
                tau = -slope / (2.0 * curvature)
                if -1.0 <= tau <= 1.0:
                    peak = now - slope * slope / (4.0 * curvature)
            peak = max(peak, now, x_new)
            if peak > max_deflection:
                status = STATUS_CODE_BEYOND_LAW
                break
            exponent = _unloading_exponent(peak, e_bg, kind, coefficients)
            loading = False
            x_new = _solve_compression(
                free, alpha, x_new, loading, peak, exponent, kind, coefficients
            )
        if loading and x_new > max_deflection:
            status = STATUS_CODE_BEYOND_LAW
            break
        if not loading and x_new > peak * (1.0 + RELOAD_MARGIN):
            loading = True
            x_new = _solve_compression(
                free, alpha, x_new, loading, peak, exponent, kind, coefficients
            )
        if not loading and x_new <= 0.0:
            # separation inside the step: shorten it to the crossing (force ramping to zero)
            low, high = 0.0, h
            value_low, value_high = now, x_new
            h_cross = h * now / (now - x_new)
            for _ in range(60):
                _step_coefficients(poles, h_cross, decay, first, second)
                x_try = x_b + h_cross * v_b - h_cross * h_cross * force / (3.0 * m)
                w_try = compliance * (rho + h_cross * rho_dot + h_cross * h_cross * force / 3.0)
                for k in range(n_poles):
                    w_try += (
                        weights[k] * (residues[k] * (decay[k] * modal[k] + first[k] * force)).real
                    )
                value = x_try - w_try
                if value > 0.0:
                    low, value_low = h_cross, value
                else:
                    high, value_high = h_cross, value
                if abs(value) <= 1e-13 * peak or high - low <= 1e-14 * h:
                    break
                h_cross = low + (high - low) * value_low / (value_low - value_high)
                h_cross = min(max(h_cross, low + 1e-3 * (high - low)), high - 1e-3 * (high - low))
            x_b = x_b + h_cross * v_b - h_cross * h_cross * force / (3.0 * m)
            v_b = v_b - h_cross * force / (2.0 * m)
            rho = rho + h_cross * rho_dot + h_cross * h_cross * force / 3.0
            rho_dot = rho_dot + h_cross * force / 2.0
            for k in range(n_poles):
                modal[k] = decay[k] * modal[k] + first[k] * force
            t += h_cross
            steps += 1
            status = STATUS_CODE_OK
            break
        force_new = _contact_force(x_new, loading, peak, exponent, kind, coefficients)[0]
        x_b = x_pred - h * h * force_new / (6.0 * m)
        v_b = v_b - h * (force + force_new) / (2.0 * m)
        rho = rho_pred + h * h * force_new / 6.0
        rho_dot = rho_dot + h * (force + force_new) / 2.0
        for k in range(n_poles):
            modal[k] = predicted[k] + second[k] * force_new
        earlier, before, now, force = before, now, x_new, force_new
        t += h
        steps += 1
    if status == STATUS_CODE_OK:
        # free flight: does the vibrating frame catch the ball up again?  (F = 0: the ball
        # keeps its speed, ρ drifts, u_k decays exactly; state copied, the outputs stay at
        # the separation)
        _step_coefficients(poles, h, decay, first, second)
        n_check = min(int(np.ceil(recontact_horizon(poles, weights, t) / h)), max_steps)
        for k in range(n_poles):
            predicted[k] = modal[k]
        x_free, rho_free = x_b, rho
        for _ in range(n_check):
            x_free += h * v_b
            rho_free += h * rho_dot
            w_free = compliance * rho_free
            for k in range(n_poles):
                predicted[k] = decay[k] * predicted[k]
                w_free += weights[k] * (residues[k] * predicted[k]).real
            if x_free - w_free > RECONTACT_TOLERANCE * peak:
                status = STATUS_CODE_SECOND_CONTACT
                break
    result[0] = status
    result[1] = t
    result[2] = _law(peak, kind, coefficients)[0]
    result[3] = peak
    result[4] = v_b
    result[5] = rho
    result[6] = rho_dot
    result[7] = steps


@_compiled
def _integrate_batch(
    system_index: NDArray[np.int64], approach: NDArray[np.float64], step: NDArray[np.float64],
    poles: NDArray[np.complex128], residues: NDArray[np.complex128],
    weights: NDArray[np.float64], compliance: NDArray[np.float64], ball_mass: float,
    e_bg: NDArray[np.float64], kind: int, coefficients: NDArray[np.float64],
    max_deflection: float, max_steps: int, modal: NDArray[np.complex128],
    result: NDArray[np.float64],
) -> None:  # fmt: skip
    for i in range(approach.size):
        s = system_index[i]
        _integrate_one(
            poles[s], residues[s], weights[s], compliance[s], approach[i], step[i], ball_mass,
            e_bg[i], kind, coefficients, max_deflection, max_steps, modal[i], result[i],
        )  # fmt: skip


def integrate_impacts(
    system_index: NDArray[np.int64],
    approach_speed: NDArray[np.float64],
    step_s: NDArray[np.float64],
    poles: NDArray[np.complex128],
    residues: NDArray[np.complex128],
    weights: NDArray[np.float64],
    rigid_compliance: NDArray[np.float64],
    ball_mass: float,
    e_bg: float | NDArray[np.float64],
    law_kind: int,
    law_coefficients: NDArray[np.float64],
    max_deflection: float,
    max_steps: int,
) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
    """Integrate a batch of impacts from first contact to separation.

    Parameters
    ----------
    system_index : ndarray (n_impacts,) of int
        Which row of ``poles``/``residues``/``rigid_compliance`` each impact uses.
    approach_speed : ndarray (n_impacts,)
        Ball speed towards the racket, which starts at rest, m/s.
    step_s : ndarray (n_impacts,)
        Time step h, s.
    poles, residues : ndarray (n_systems, n_poles), complex
        λ_k (1/s) and r_k (s/kg) of each system (pad with residue 0 and weight 0).
    weights : ndarray (n_systems, n_poles)
        2 for a complex pole standing for its conjugate too, 1 for a real pole, 0 for padding.
    rigid_compliance : ndarray (n_systems,)
        c = 1/M_r, 1/kg.
    ball_mass : float
        m_B, kg.
    e_bg : float or ndarray (n_impacts,)
        COR of the ball on head-clamped strings (one, or one per impact).
    law_kind : int
        ``LAW_POLYNOMIAL`` (F = Σ c_i X^{i+1}) or ``LAW_POWER`` (F = c Xⁿ).
    law_coefficients : ndarray
        The law's coefficients (SI).
    max_deflection : float
        End of the law's range, m.
    max_steps : int
        Steps allowed before the impact is given up (status no separation).

    Returns
    -------
    modal : ndarray (n_impacts, n_poles), complex
        u_k at separation.
    result : ndarray (n_impacts, 8)
        Status code, contact time (s), F_GB(X_max) (N), X_max (m), ball velocity at
        separation (m/s, + into the strings), ρ (N·s²), ρ̇ (N·s), steps taken.
    """
    n = approach_speed.size
    modal = np.zeros((n, poles.shape[1]), np.complex128)
    result = np.zeros((n, 8))
    _integrate_batch(
        np.ascontiguousarray(system_index, np.int64),
        np.ascontiguousarray(approach_speed, float),
        np.ascontiguousarray(step_s, float),
        np.ascontiguousarray(poles, np.complex128),
        np.ascontiguousarray(residues, np.complex128),
        np.ascontiguousarray(weights, float),
        np.ascontiguousarray(rigid_compliance, float),
        float(ball_mass),
        np.ascontiguousarray(np.broadcast_to(np.asarray(e_bg, float), (n,)), float),
        int(law_kind),
        np.ascontiguousarray(law_coefficients, float),
        float(max_deflection),
        int(max_steps),
        modal,
        result,
    )
    return modal, result


def law_arrays(kind: str, coefficients: tuple[float, ...]) -> tuple[int, NDArray[np.float64]]:
    """The kernel's law code and coefficients for a :class:`~racketdyn.ball.RestoringForce`.

    Parameters
    ----------
    kind : {"polynomial", "power"}
        The law's form: F = Σ c_i X^(i+1) (c_i in N/m^(i+1)) or F = c Xⁿ (c in N/mⁿ, n –).
    coefficients : tuple of float
        Its coefficients, SI as above.
    """
    if kind == "power":
        return LAW_POWER, np.asarray(coefficients, float)
    return LAW_POLYNOMIAL, np.asarray(coefficients, float)
