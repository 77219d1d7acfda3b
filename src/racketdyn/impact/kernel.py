"""Compiled batch integrator of the transient impact (numba), over many impacts at once.

Each impact is the ball (mass m_B, ``ẍ_B = −F/m_B``) on the hysteretic compound spring
(:mod:`racketdyn.impact.transient`) against a racket given by its receptance at the point in
pole–residue form (:class:`racketdyn.impact.system.PoleResidue`):

    ``w = c ρ + Σ_k weight_k Re(r_k u_k)``,  ``ρ̈ = F``,  ``u̇_k = λ_k u_k + F``.

The scheme is an exponential integrator with the contact force linear over each step (a
first-order hold): the racket's linear part is integrated exactly for that force, the ball's
too, so the only approximation is the force's linear interpolation — second order in the step
h.  The end-of-step force is implicit, ``X_{n+1} = X_free − α F(X_{n+1})`` with α > 0, solved by
a safeguarded Newton iteration (unique root because F rises with X) from ``X_free − α F̃`` with
F̃ the force extrapolated from the last three steps: one correction per step.  Events inside a
step:

* the turn (X stops rising): the peak X_p is the vertex of the parabola through the last three
  compressions (error O(h³)), the unloading exponent p is solved for it and the step is redone
  on the unloading curve;
* separation (X reaches 0 while unloading): the step is shortened to the crossing (secant on
  the step length, the force ramping to zero), so the state at separation is consistent;
* reloading past X_p goes back onto F_GB;
* after separation the ball and the racket move freely (exact for F = 0) for
  :func:`recontact_horizon`, or until a bound shows the gap can no longer close; a compression
  above ``RECONTACT_TOLERANCE · X_p`` then is a second contact (status
  ``STATUS_CODE_SECOND_CONTACT``: the vibrating frame caught the ball again).

By default (``extrapolate``) each contact is run at h and at 2h and the separation states are
combined as ``y_h + (y_h − y_2h)/3`` (Richardson: the h² term cancels, order ≈ 3), the search
for a second contact starting from the combined state.  Per impact everything is computed
alone (no state shared across a batch), so an impact's bits do not depend on its batch.

Tested against the reference engine (scipy's DOP853 in physical coordinates), shown to
converge at order 2 as h halves without extrapolation and faster with it
(``tests/test_kernel.py``).  Without numba the same functions
run as plain Python (correct, ~100× slower); :func:`racketdyn.impact.transient.predict_transient`
then uses the reference engine instead.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple, TypeVar, cast

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

    def _inlined(function: F) -> F:
        """A step of a kernel, compiled into its caller (numba IR inlining: a call per contact
        of a helper with arrays for arguments cost the kernel 2-2.5 % in a paired A/B)."""
        into_caller = numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
        return cast(F, into_caller(function))

except ImportError:  # pragma: no cover - exercised only without numba
    NUMBA_AVAILABLE = False

    def _compiled(function: F) -> F:
        return function

    _inlined = _compiled


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
REFINEMENTS = 2
"""Extrapolated contacts: where the runs at h and 2h disagree (in status, or on the contact time
by more than a step: they followed different paths) or the extrapolated contact is followed by
a second one after a gap narrower than :data:`DIP_GAP` (which may be a dip of the compression
the steps were too coarse to follow), the step is halved (h/2 against h, then h/4 against h/2)
at most this often; runs still apart leave the finest run alone."""
DIP_GAP = 1e-2
"""A second contact after the ball had left by more than this fraction of X_p stands without
refinement: 100× the compression error of a 64-step run (≈ 1e-4 X_p).  Seen near the tip of
the built-in racket: dips that finer steps follow opened ≤ 4e-4 X_p at 128 steps, real second
contacts 3e-4 to 0.12 X_p (so narrow ones are refined too, and confirmed)."""


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
    # Σ c_i x^i and Σ (i + 1) c_i x^i by Horner in x² over the even and the odd terms: four
    # independent chains of half the length (the law is evaluated once or twice a step)
    y = x * x
    even, odd, slope_even, slope_odd = 0.0, 0.0, 0.0, 0.0
    top = coefficients.size - 1
    for i in range(top - top % 2, -1, -2):
        c = coefficients[i]
        even = even * y + c
        slope_even = slope_even * y + (i + 1) * c
    for i in range(top - 1 + top % 2, 0, -2):
        c = coefficients[i]
        odd = odd * y + c
        slope_odd = slope_odd * y + (i + 1) * c
    return (even + x * odd) * x, slope_even + x * slope_odd


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
    terms = np.empty(coefficients.size)  # c_i X_p^(i+2), once (not a power per iteration)
    power = peak * peak
    target = 0.0
    for i in range(coefficients.size):
        terms[i] = coefficients[i] * power
        target += terms[i] / (i + 2.0)
        power *= peak
    target *= e_bg * e_bg
    p = 0.0
    for _ in range(200):
        value = -target
        slope = 0.0
        for i in range(coefficients.size):
            share = terms[i] / (i + 2.0 + p)
            value += share
            slope -= share / (i + 2.0 + p)
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


NEWTON_ACCEPT = 1e-6
"""The Newton iteration for the end-of-step compression stops once its correction δ is below
this fraction of X_free.  The corrected X is then within ≈ 1e-15 of the root (the iteration
converges quadratically with a constant α F'' X_free / 2 ≲ 1e-3 at ≥ 64 steps per contact),
and the force taken on the tangent differs from the law's by ½ F'' δ² ≲ 1e-11 of F (F'' X²/F
≲ 20 on the unloading curves here), far below the scheme's error (≈ 1e-6).  At 1e-7 a step
cost 1.27 evaluations of the law on average, at 1e-6 1.03 (bench case, 128 steps)."""


@_compiled
def _solve_compression(
    free: float, alpha: float, guess: float, loading: bool, peak: float, exponent: float,
    kind: int, coefficients: NDArray[np.float64],
) -> tuple[float, float]:  # fmt: skip
    """X and F with ``X + α F = X_free``, F = F(X) (F rises with X, so the root is unique).

    Newton from ``guess``, safeguarded by bisection on [0, X_free].  Once a correction δ is
    below ``NEWTON_ACCEPT · X_free`` the corrected X is returned with the force on the tangent,
    F(x) − F'(x) δ: that pair solves the step's equation exactly and differs from the law's
    F(X) by ½ F'' δ² (≲ 1e-11 of F), so a step costs one evaluation of the law where the
    predictor is good.
    """
    if free <= 0.0:
        return free, 0.0
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
        if abs(step) <= NEWTON_ACCEPT * free:
            return x - step, force - slope * step
        trial = x - step
        if trial <= low or trial >= high:
            trial = 0.5 * (low + high)
        x = trial
    return x, _contact_force(x, loading, peak, exponent, kind, coefficients)[0]


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
        if z.real * z.real + z.imag * z.imag < 0.0025:  # |z| < 0.05: series to z⁷ (error
            # < 1e-16); the closed form would cancel here
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


# 11 parameters: the end state's scalars, as tests/test_kernel.py passes them
@_compiled
def _steps_until_apart(
    poles: NDArray[np.complex128], residues: NDArray[np.complex128],
    weights: NDArray[np.float64], compliance: float, modal: NDArray[np.complex128],
    x_b: float, v_b: float, rho: float, rho_dot: float, peak: float, h: float,
) -> int:  # fmt: skip
    """Free steps after which the ball provably cannot touch the racket again.

    With no force the compression is ``X(t) = (x_B − c ρ) + (v_B − c ρ̇) t − Σ wt Re(r_k u_k
    e^{λ_k t})`` and, every pole decaying (Re λ ≤ 0), the modal sum is bounded by
    ``A = Σ wt |r_k u_k|``.  Once ``(x_B − c ρ) + (v_B − c ρ̇) t + A`` is below half the
    second-contact threshold ``RECONTACT_TOLERANCE · X_p`` no later step can reach it, so the
    free flight stops there: the status is the one the whole horizon gives (only steps that
    cannot detect anything are skipped).  Returns a large number when the bound does not
    apply (a growing pole, or the gap not opening).
    """
    never = 1 << 62
    drift = v_b - compliance * rho_dot
    if drift >= 0.0:
        return never
    amplitude = 0.0
    for k in range(poles.size):
        if weights[k] == 0.0:
            continue
        if poles[k].real > 0.0:
            return never
        amplitude += weights[k] * abs(residues[k] * modal[k])
    gap = x_b - compliance * rho + amplitude - 0.5 * RECONTACT_TOLERANCE * peak
    if gap <= 0.0:
        return 0
    steps = np.ceil(gap / (-drift * h))
    return never if steps > 1e18 else int(steps)


class _Receptance(NamedTuple):
    """The racket at one impact point in pole–residue form (one row of a batch's systems)."""

    poles: NDArray[np.complex128]
    """λ_k, 1/s."""
    residues: NDArray[np.complex128]
    """r_k, s/kg."""
    weights: NDArray[np.float64]
    """2 for a complex pole standing for its conjugate too, 1 for a real pole, 0 for padding."""
    compliance: float
    """c = 1/M_r, 1/kg."""


class _Spring(NamedTuple):
    """The hysteretic compound spring of one impact."""

    e_bg: float
    """COR of the ball on head-clamped strings (sets the unloading curves)."""
    kind: int
    """``LAW_POLYNOMIAL`` or ``LAW_POWER``."""
    coefficients: NDArray[np.float64]
    """The loading law's coefficients, SI."""
    max_deflection: float
    """End of the law's range, m."""


class _Propagators(NamedTuple):
    """Per pole over one step: e^{λh} and the first-order hold's two integrals (see
    :func:`_step_coefficients`)."""

    decay: NDArray[np.complex128]
    first: NDArray[np.complex128]
    second: NDArray[np.complex128]


@_compiled
def _caught_again(
    racket: _Receptance, modal: NDArray[np.complex128], state: NDArray[np.float64], h: float,
    max_steps: int,
) -> float:  # fmt: skip
    """Free flight after separation: does the vibrating frame catch the ball up again?

    F = 0: the ball keeps its speed, ρ drifts, u_k decays exactly, sampled every h over
    :func:`recontact_horizon`, stopped early where :func:`_steps_until_apart` proves the gap
    can no longer close.  ``state`` is the separation's (see :func:`_contact`).  Returns −1
    when it does not, else the widest gap before it did, as a fraction of X_p.
    """
    poles, residues, weights, compliance = racket
    t, peak, x_b, v_b, rho, rho_dot = state[1], state[2], state[3], state[4], state[5], state[6]
    n_check = min(int(np.ceil(recontact_horizon(poles, weights, t) / h)), max_steps)
    n_check = min(n_check, _steps_until_apart(poles, residues, weights, compliance,
                                              modal, x_b, v_b, rho, rho_dot, peak, h))  # fmt: skip
    n_poles = poles.size
    decay = np.empty(n_poles, np.complex128)
    moving = np.empty(n_poles, np.complex128)
    for k in range(n_poles):
        decay[k] = np.exp(poles[k] * h)
        moving[k] = modal[k]
    x_free, rho_free = x_b, rho
    widest = 0.0
    for _ in range(n_check):
        x_free += h * v_b
        rho_free += h * rho_dot
        w_free = compliance * rho_free
        for k in range(n_poles):
            moving[k] = decay[k] * moving[k]
            w_free += weights[k] * (residues[k] * moving[k]).real
        widest = min(widest, x_free - w_free)
        if x_free - w_free > RECONTACT_TOLERANCE * peak:
            return float(-widest / peak)
    return -1.0


@_inlined
def _step_arrays(
    racket: _Receptance, ball_mass: float, h: float, propagators: _Propagators,
    work: NDArray[np.float64],
) -> float:  # fmt: skip
    """Fill ``propagators`` for the step h and ``work``'s rows (real and imaginary parts of
    e^{λh}, of the two hold integrals, of weight_k r_k, and u_k = 0); return α, the compliance
    of the end-of-step equation ``X + α F = X_free``."""
    poles, residues, weights, compliance = racket
    decay, first, second = propagators
    _step_coefficients(poles, h, decay, first, second)
    d_re, d_im, f_re, f_im, s_re, s_im = work[0], work[1], work[2], work[3], work[4], work[5]
    r_re, r_im, u_re, u_im = work[6], work[7], work[8], work[9]
    alpha = h * h / 6.0 * (1.0 / ball_mass + compliance)
    for k in range(poles.size):
        weighted = weights[k] * residues[k]
        alpha += (weighted * second[k]).real
        d_re[k], d_im[k] = decay[k].real, decay[k].imag
        f_re[k], f_im[k] = first[k].real, first[k].imag
        s_re[k], s_im[k] = second[k].real, second[k].imag
        r_re[k], r_im[k] = weighted.real, weighted.imag
        u_re[k], u_im[k] = 0.0, 0.0
    return alpha


@_inlined
def _peak_at_turn(before: float, now: float, x_new: float) -> float:
    """X_p where X turned inside the last step: the vertex of the parabola through the last
    three compressions (error O(h³)), at least each of them."""
    curvature = 0.5 * (x_new - 2.0 * now + before)
    slope = 0.5 * (x_new - before)
    peak = now
    if curvature < 0.0:
        tau = -slope / (2.0 * curvature)
        if -1.0 <= tau <= 1.0:
            peak = now - slope * slope / (4.0 * curvature)
    return max(peak, now, x_new)


@_inlined
def _ramp(
    racket: _Receptance, ball_mass: float, length: float,
    start: tuple[float, float, float, float], force: float, work: NDArray[np.float64],
    propagators: _Propagators, modal: NDArray[np.complex128],
) -> tuple[float, float, float, float]:  # fmt: skip
    """x_B, v_B, ρ and ρ̇ after a step of ``length`` from ``start`` (the same four) with the
    force ramping from ``force`` to zero; u_k into ``modal`` (``propagators`` for that length,
    u_k at the start in ``work``'s rows 8 and 9)."""
    x_b, v_b, rho, rho_dot = start
    m = ball_mass
    u_re, u_im = work[8], work[9]
    decay, first = propagators.decay, propagators.first
    for k in range(decay.size):
        modal[k] = decay[k] * complex(u_re[k], u_im[k]) + first[k] * force
    return (
        x_b + length * v_b - length * length * force / (3.0 * m),
        v_b - length * force / (2.0 * m),
        rho + length * rho_dot + length * length * force / 3.0,
        rho_dot + length * force / 2.0,
    )


@_inlined
def _crossing_guess(h: float, before: float, now: float, x_new: float) -> float:
    """First guess of the step's length to X = 0: the root of the parabola through (before,
    now, new) in (0, h] (the line through (now, new) where that has none): two secant steps
    fewer."""
    h_cross = h * now / (now - x_new)
    linear = 0.5 * (x_new - before)
    curvature = 0.5 * (x_new - 2.0 * now + before)
    discriminant = linear * linear - 4.0 * curvature * now
    if linear < 0.0 and discriminant >= 0.0:
        tau = 2.0 * now / (np.sqrt(discriminant) - linear)
        if 0.0 < tau <= 1.0:
            h_cross = h * tau
    return h_cross


@_inlined
def _crossing_length(
    racket: _Receptance, ball_mass: float, h: float, start: tuple[float, float, float, float],
    force: float, peak: float, compressions: tuple[float, float, float],
    work: NDArray[np.float64], propagators: _Propagators,
) -> float:  # fmt: skip
    """Separation inside the step: its length to the crossing X = 0, the force ramping to zero.

    Secant on the length from :func:`_crossing_guess`, bisection where it leaves the bracket;
    each trial takes the compression at the end of :func:`_ramp`'s step (u_k not kept).
    ``compressions`` are X before, now and at the end of the full step; ``start``, ``work``
    and ``propagators`` as for :func:`_ramp`, which ``propagators`` are left for (those of
    the last length tried).
    """
    poles, residues, weights, compliance = racket
    decay, first, second = propagators
    x_b, v_b, rho, rho_dot = start
    u_re, u_im = work[8], work[9]
    m = ball_mass
    before, now, x_new = compressions
    low, high = 0.0, h
    h_cross = _crossing_guess(h, before, now, x_new)
    previous, value_previous = h, x_new
    for _ in range(60):
        _step_coefficients(poles, h_cross, decay, first, second)
        x_try = x_b + h_cross * v_b - h_cross * h_cross * force / (3.0 * m)
        w_try = compliance * (rho + h_cross * rho_dot + h_cross * h_cross * force / 3.0)
        for k in range(poles.size):
            u = decay[k] * complex(u_re[k], u_im[k]) + first[k] * force
            w_try += weights[k] * (residues[k] * u).real
        value = x_try - w_try
        if value > 0.0:
            low = h_cross
        else:
            high = h_cross
        if abs(value) <= 1e-13 * peak or high - low <= 1e-14 * h:
            break
        # secant through the last two lengths, bisection where it leaves the bracket
        trial = 0.5 * (low + high)
        if value != value_previous:
            trial = h_cross - value * (h_cross - previous) / (value - value_previous)
            if not low < trial < high:
                trial = 0.5 * (low + high)
        previous, value_previous = h_cross, value
        h_cross = trial
    return h_cross


@_compiled
def _contact(
    racket: _Receptance, spring: _Spring, ball_mass: float, approach: float, h: float,
    max_steps: int, modal: NDArray[np.complex128], state: NDArray[np.float64],
) -> None:  # fmt: skip
    """One contact at step h, in the frame where the racket starts at rest, first touch to
    separation.  Fills ``modal`` with u_k at the end and ``state`` with: status, time t, X_max,
    x_B, ball velocity, ρ, ρ̇, steps taken.

    The modal part is kept as real and imaginary arrays (``work`` rows), so the per-pole
    update of each step is plain arithmetic over contiguous arrays; the propagators e^{λh}
    and the two hold integrals are computed once per contact (:func:`_step_arrays`).
    """
    poles, compliance = racket.poles, racket.compliance
    n_poles = poles.size
    e_bg, kind, coefficients, max_deflection = spring
    propagators = _Propagators(
        np.empty(n_poles, np.complex128), np.empty(n_poles, np.complex128),
        np.empty(n_poles, np.complex128),
    )  # fmt: skip
    work = np.empty((12, n_poles))
    alpha = _step_arrays(racket, ball_mass, h, propagators, work)
    d_re, d_im, f_re, f_im, s_re, s_im = work[0], work[1], work[2], work[3], work[4], work[5]
    r_re, r_im, u_re, u_im, p_re, p_im = work[6], work[7], work[8], work[9], work[10], work[11]
    # the step's constants (the ball's and ρ's updates for a force linear over the step)
    m = ball_mass
    ball_first, ball_second, ball_mean = h * h / (3.0 * m), h * h / (6.0 * m), h / (2.0 * m)
    rho_first, rho_second, rho_mean = h * h / 3.0, h * h / 6.0, h / 2.0
    x_b, v_b, rho, rho_dot = 0.0, approach, 0.0, 0.0
    force, force_before, force_earlier = 0.0, 0.0, 0.0  # F at the last three steps
    before, now = 0.0, 0.0  # X at the last two steps
    loading, peak, exponent = True, 0.0, 0.0
    status = STATUS_CODE_NO_SEPARATION
    t = 0.0
    steps = 0
    separated = False
    while steps < max_steps:
        x_pred = x_b + h * v_b - ball_first * force
        rho_pred = rho + h * rho_dot + rho_first * force
        for k in range(n_poles):
            p_re[k] = d_re[k] * u_re[k] - d_im[k] * u_im[k] + f_re[k] * force
            p_im[k] = d_re[k] * u_im[k] + d_im[k] * u_re[k] + f_im[k] * force
        w_pred = compliance * rho_pred
        for k in range(n_poles):
            w_pred += r_re[k] * p_re[k] - r_im[k] * p_im[k]
        free = x_pred - w_pred
        # predictor: the free part is exact, the force extrapolated (error O(h³) in F, so
        # O(h⁵) in X: one Newton correction reaches the tolerance)
        guess = free - alpha * (3.0 * (force - force_before) + force_earlier)
        x_new, force_new = _solve_compression(
            free, alpha, guess, loading, peak, exponent, kind, coefficients
        )
        if loading and steps > 0 and x_new < now:  # turned inside the step
            peak = _peak_at_turn(before, now, x_new)
            if peak > max_deflection:
                status = STATUS_CODE_BEYOND_LAW
                break
            exponent = _unloading_exponent(peak, e_bg, kind, coefficients)
            loading = False
            x_new, force_new = _solve_compression(
                free, alpha, x_new, loading, peak, exponent, kind, coefficients
            )
        if loading and x_new > max_deflection:
            status = STATUS_CODE_BEYOND_LAW
            break
        if not loading and x_new > peak * (1.0 + RELOAD_MARGIN):
            loading = True
            x_new, force_new = _solve_compression(
                free, alpha, x_new, loading, peak, exponent, kind, coefficients
            )
        if not loading and x_new <= 0.0:
            # separation inside the step: shorten it to the crossing (force ramping to zero)
            start = (x_b, v_b, rho, rho_dot)
            h_cross = _crossing_length(racket, m, h, start, force, peak, (before, now, x_new),
                                       work, propagators)  # fmt: skip
            x_b, v_b, rho, rho_dot = _ramp(racket, m, h_cross, start, force, work, propagators,
                                           modal)  # fmt: skip
            t += h_cross
            steps += 1
            status = STATUS_CODE_OK
            separated = True
            break
        x_b = x_pred - ball_second * force_new
        v_b = v_b - ball_mean * (force + force_new)
        rho = rho_pred + rho_second * force_new
        rho_dot = rho_dot + rho_mean * (force + force_new)
        for k in range(n_poles):
            u_re[k] = p_re[k] + s_re[k] * force_new
            u_im[k] = p_im[k] + s_im[k] * force_new
        before, now = now, x_new
        force_earlier, force_before, force = force_before, force, force_new
        t += h
        steps += 1
    if not separated:
        for k in range(n_poles):
            modal[k] = complex(u_re[k], u_im[k])
    state[0] = status
    state[1] = t
    state[2] = peak
    state[3] = x_b
    state[4] = v_b
    state[5] = rho
    state[6] = rho_dot
    state[7] = steps


@_compiled
def _integrate_one(
    racket: _Receptance, spring: _Spring, ball_mass: float, approach: float, h: float,
    max_steps: int, extrapolate: bool, modal: NDArray[np.complex128],
    result: NDArray[np.float64],
) -> None:  # fmt: skip
    """One impact, in the frame where the racket starts at rest.  Fills ``modal`` with u_k
    at separation and ``result`` with: status, contact time, F_GB(X_max), X_max, ball
    velocity, ρ, ρ̇, steps taken (both runs when extrapolated).

    ``extrapolate``: the contact is run at h and at 2h and the separation state (time, X_max,
    ball, ρ, ρ̇, u_k) extrapolated as ``y_h + (y_h − y_2h)/3`` (Richardson: the scheme's error
    is C h² + O(h³), so the O(h²) term cancels); the impact is flagged if either run is.  The
    free flight that looks for a second contact then starts from the extrapolated state.
    """
    state = np.empty(8)
    _contact(racket, spring, ball_mass, approach, h, max_steps, modal, state)
    if not extrapolate:
        if state[0] == STATUS_CODE_OK and _caught_again(racket, modal, state, h, max_steps) >= 0.0:
            state[0] = STATUS_CODE_SECOND_CONTACT
        _write_result(state, spring.kind, spring.coefficients, result)
        return
    coarse = np.empty(8)
    coarse_modal = np.empty_like(modal)
    _contact(racket, spring, ball_mass, approach, 2.0 * h, max(max_steps // 2, 1), coarse_modal,
             coarse)  # fmt: skip
    answer = np.empty(8)
    answer_modal = np.empty_like(modal)
    steps = state[7] + coarse[7]
    finest = h
    for attempt in range(REFINEMENTS + 1):
        if (
            state[0] == STATUS_CODE_OK
            and coarse[0] == STATUS_CODE_OK
            and abs(state[1] - coarse[1]) <= finest
        ):
            _richardson(state, coarse, modal, coarse_modal, answer, answer_modal)
            gap = -1.0
            if answer[2] > spring.max_deflection:
                answer[0] = STATUS_CODE_BEYOND_LAW
            else:
                gap = _caught_again(racket, answer_modal, answer, h, max_steps)
                if gap >= 0.0:
                    answer[0] = STATUS_CODE_SECOND_CONTACT
            if gap < 0.0 or gap >= DIP_GAP:
                break  # no second contact, or one after the ball had clearly left
        else:
            answer[:] = state
            answer_modal[:] = modal
            if state[0] != STATUS_CODE_OK and state[0] == coarse[0]:
                break  # both runs flag the impact alike (beyond the law, no separation)
            if (
                state[0] == STATUS_CODE_OK
                and _caught_again(racket, modal, state, h, max_steps) >= 0.0
            ):
                answer[0] = STATUS_CODE_SECOND_CONTACT
        if attempt == REFINEMENTS:
            break
        # runs that disagree followed different paths, and a second contact after a narrow gap
        # may be a dip of the compression the steps were too coarse to follow (it separated at
        # the dip before the frame pressed again): halve the step, compare with the previous run
        coarse[:] = state
        coarse_modal[:] = modal
        finest *= 0.5
        _contact(racket, spring, ball_mass, approach, finest, int(max_steps * h / finest), modal,
                 state)  # fmt: skip
        steps += state[7]
    modal[:] = answer_modal
    answer[7] = steps
    _write_result(answer, spring.kind, spring.coefficients, result)


@_inlined
def _richardson(
    fine: NDArray[np.float64], coarse: NDArray[np.float64], fine_modal: NDArray[np.complex128],
    coarse_modal: NDArray[np.complex128], answer: NDArray[np.float64],
    answer_modal: NDArray[np.complex128],
) -> None:  # fmt: skip
    """``answer`` (status ok) and ``answer_modal`` from runs at h and 2h: ``y_h + (y_h − y_2h)/3``
    for the time, X_max, ball, ρ, ρ̇ and u_k (the steps are left to the caller)."""
    for i in range(1, 7):
        answer[i] = fine[i] + (fine[i] - coarse[i]) / 3.0
    for k in range(fine_modal.size):
        answer_modal[k] = fine_modal[k] + (fine_modal[k] - coarse_modal[k]) / 3.0
    answer[0] = STATUS_CODE_OK


@_compiled
def _write_result(
    state: NDArray[np.float64], kind: int, coefficients: NDArray[np.float64],
    result: NDArray[np.float64],
) -> None:  # fmt: skip
    """``result`` from a contact's ``state`` (see :func:`_integrate_one`)."""
    result[0] = state[0]
    result[1] = state[1]
    result[2] = _law(state[2], kind, coefficients)[0]
    result[3] = state[2]
    result[4] = state[4]
    result[5] = state[5]
    result[6] = state[6]
    result[7] = state[7]


@_compiled
def _integrate_batch(
    system_index: NDArray[np.int64], approach: NDArray[np.float64], step: NDArray[np.float64],
    poles: NDArray[np.complex128], residues: NDArray[np.complex128],
    weights: NDArray[np.float64], compliance: NDArray[np.float64], ball_mass: float,
    e_bg: NDArray[np.float64], kind: int, coefficients: NDArray[np.float64],
    max_deflection: float, max_steps: int, extrapolate: bool, modal: NDArray[np.complex128],
    result: NDArray[np.float64],
) -> None:  # fmt: skip
    # 16 parameters: the batch's arrays as integrate_impacts passes them (numba's entry point,
    # called positionally by tests/test_kernel.py); each impact gets them grouped
    for i in range(approach.size):
        s = system_index[i]
        racket = _Receptance(poles[s], residues[s], weights[s], compliance[s])
        spring = _Spring(e_bg[i], kind, coefficients, max_deflection)
        _integrate_one(
            racket, spring, ball_mass, approach[i], step[i], max_steps, extrapolate, modal[i],
            result[i],
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
    extrapolate: bool = True,
) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:  # 14: the batch's arrays, positional
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
    extrapolate : bool
        Run each contact at h and 2h and extrapolate (order ≈ 3 instead of 2, 1.5× the
        steps); False: one run at h.

    Returns
    -------
    modal : ndarray (n_impacts, n_poles), complex
        u_k at separation.
    result : ndarray (n_impacts, 8)
        Status code, contact time (s), F_GB(X_max) (N), X_max (m), ball velocity at
        separation (m/s, + into the strings), ρ (N·s²), ρ̇ (N·s), steps taken (both runs).
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
        bool(extrapolate),
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
