"""Calibration: the uncertain inputs fitted to measured rebound, with honest uncertainties.

A weighted least-squares fit (:func:`scipy.optimize.least_squares`, bounded) of named
parameters (:data:`PARAMETERS`) to the measured rebound ratios of a
:class:`~racketdyn.io.measured.MeasuredRebound`, by either model
(:func:`racketdyn.impact.measured.predict_rows`).

Residuals are ``(predicted − measured) / sd`` with the rows' ``rebound_ratio_sd``; without it
every row weighs 1 and the noise is estimated from the fit (``s² = RSS / (n − p)``).  The
covariance is ``s² (JᵀJ)⁻¹`` (s² = 1 with measured standard deviations) with J the Jacobian of
the residuals by central differences at the solution, in parameters scaled by their starting
values.  A parameter is **not identifiable** — reported so, with no value claimed — when the
data do not move with it (its Jacobian column is nil), when it lies along a near-null direction
of J (with another parameter it trades off exactly: relative singular value below
:data:`NULL_SINGULAR_VALUE`), or when its two-standard-error interval is wider than its bounds.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import least_squares

from racketdyn.ball import Ball
from racketdyn.contact import with_ball_string_cor
from racketdyn.errors import InputError
from racketdyn.impact.hand import Hand
from racketdyn.impact.measured import Method, ModelInputs, first_bending_index, predict_rows
from racketdyn.io.measured import MeasuredRebound

__all__ = [
    "NULL_SINGULAR_VALUE",
    "PARAMETERS",
    "POOR_FIT_P",
    "Calibration",
    "Parameter",
    "apply",
    "bounds_from_spreads",
    "calibrate",
    "parse_fit",
    "priors_from_spreads",
    "shifted_e_bg",
    "simulate_measurements",
]

log = logging.getLogger(__name__)

NULL_SINGULAR_VALUE = 1e-3
"""Relative singular value of the column-normalised Jacobian below which the parameters of
that direction cannot be told apart (their correlation is beyond 1 − 5e-7)."""

POOR_FIT_P = 1e-3
"""A weighted fit is called poor when its χ² is this unlikely under the measured standard
deviations (:attr:`Calibration.poor_fit`)."""

DIFF_STEP = 1e-3
"""Relative step of the central differences (the compiled engine's results move smoothly at
this step: its time step is a fixed fraction of the contact time)."""


@dataclass(frozen=True)
class Parameter:
    """An uncertain input a calibration may fit.

    Attributes
    ----------
    name : str
        Its name on the command line and in calibration.json.
    unit : str
        Its unit ("1" for a factor or a ratio).
    description : str
        What it is and what it changes.
    get : callable
        ``get(inputs) -> float``: its value in a :class:`ModelInputs`.
    set : callable
        ``set(inputs, value) -> ModelInputs``.
    bounds : callable
        ``bounds(start) -> (low, high)``: the fit's bounds from the starting value.
    support : str
        The support whose rows it needs (``hand`` for the hand's parameters), else empty.
    prior_sd : float or None
        Standard deviation of a normal prior about the starting value (a normal spread of an
        uncertainty file, :func:`priors_from_spreads`), in the parameter's unit; None: none.
    """

    name: str
    unit: str
    description: str
    get: Callable[[ModelInputs], float]
    set: Callable[[ModelInputs, float], ModelInputs]
    bounds: Callable[[float], tuple[float, float]]
    support: str = ""
    prior_sd: float | None = None


def _hand(inputs: ModelInputs) -> Hand:
    return inputs.hand or Hand()


def _set_hand(name: str) -> Callable[[ModelInputs, float], ModelInputs]:
    return lambda inputs, value: replace(inputs, hand=replace(_hand(inputs), **{name: value}))


def _first_bending_hz(inputs: ModelInputs) -> float:
    model = inputs.modes()
    if model is None:
        raise InputError("`first_bending_hz`: a rigid racket has no bending mode")
    return float(model.frequency[first_bending_index(model)])


def _e_bg_at_20(inputs: ModelInputs, value: float) -> Ball:
    """The ball with e_BG ``value`` at 20 m/s: a constant e_BG replaced; e_BG against speed
    (derived from ball and strings, or a table given) shifted by the same amount at every
    speed, so a sample or a fit moves the level and keeps the law's fall with speed (a
    constant in its place biased the band at high speed: the trial of 2026-11-27, 60 m/s)."""
    ball = inputs.ball
    tables = shifted_e_bg(inputs, np.array([value]))
    if tables is None:
        return replace(ball, e_bg=value)
    speeds, shifted = tables
    table = tuple((float(v), float(e)) for v, e in zip(speeds, shifted[0], strict=True))
    resolved = with_ball_string_cor(inputs.racket, ball)
    shift = value - float(resolved.e_bg_at(20.0))
    source = resolved.e_bg_source or "the e_BG table given"
    return replace(
        ball,
        e_bg=value,
        e_bg_table=table,
        e_bg_source=f"{source}; shifted {shift:+.4f} (to {value:.4g} at 20 m/s)",
    )


def shifted_e_bg(
    inputs: ModelInputs, values: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
    """The ball's e_BG table moved to each of ``values`` at 20 m/s (the ``e_bg`` parameter).

    Parameters
    ----------
    inputs : ModelInputs
        The nominal inputs (their ball's e_BG: a constant, a table, or from ball + strings).
    values : ndarray
        ``(k,)`` e_BG at 20 m/s.

    Returns
    -------
    (ndarray, ndarray) or None
        The table's speeds ``(m,)``, m/s, and each value's e_BG at them ``(k, m)`` (held in
        ``(0, 1]``); None where the ball's e_BG is one constant (each value replaces it).
    """
    ball = inputs.ball
    if ball.e_bg is not None and not ball.e_bg_table:
        return None
    resolved = with_ball_string_cor(inputs.racket, ball)
    table = np.asarray(resolved.e_bg_table, dtype=float)
    shift = np.asarray(values, dtype=float)[:, None] - float(resolved.e_bg_at(20.0))
    return table[:, 0], np.clip(table[None, :, 1] + shift, 1e-6, 1.0)


def _factor(low: float, high: float) -> Callable[[float], tuple[float, float]]:
    return lambda start: (start * low, start * high)


PARAMETERS: dict[str, Parameter] = {
    p.name: p
    for p in (
        Parameter(
            "e_bg",
            "1",
            "COR of the ball on the head-clamped strings at 20 m/s (a constant e_BG given as "
            "one; else the ball's e_BG against speed shifted to it)",
            lambda i: float(with_ball_string_cor(i.racket, i.ball).e_bg_at(20.0)),
            lambda i, v: replace(i, ball=_e_bg_at_20(i, v)),
            lambda start: (0.3, 0.99),
        ),
        Parameter(
            "string_stiffness_scale",
            "1",
            "factor on the string bed's restoring force (tension and string modulus together)",
            lambda i: i.string_stiffness_scale,
            lambda i, v: replace(i, string_stiffness_scale=v),
            lambda start: (0.3, 3.0),
        ),
        Parameter(
            "roll_inertia_kgm2",
            "kg·m²",
            "the racket's inertia about its long axis (twistweight × 1e-4)",
            lambda i: i.racket.roll_inertia_kgm2,
            lambda i, v: replace(i, racket=replace(i.racket, roll_inertia_kgm2=v)),
            _factor(0.3, 3.0),
        ),
        Parameter(
            "frame_damping_scale",
            "1",
            "factor on every mode's damping ratio",
            lambda i: i.frame_damping_scale,
            lambda i, v: replace(i, frame_damping_scale=v),
            lambda start: (0.05, 20.0),
        ),
        Parameter(
            "first_bending_hz",
            "Hz",
            "the frame's first bending frequency (its shape and the other modes kept)",
            lambda i: _first_bending_hz(i),
            lambda i, v: replace(i, first_bending_hz=v),
            _factor(0.5, 2.0),
        ),
        Parameter(
            "ball_stiffness_scale",
            "1",
            "factor on the ball's restoring force in a bounce",
            lambda i: i.ball_stiffness_scale,
            lambda i, v: replace(i, ball_stiffness_scale=v),
            lambda start: (0.3, 3.0),
        ),
        Parameter(
            "hand_stiffness_n_per_m",
            "N/m",
            "translational stiffness between handle and arm (hand support)",
            lambda i: _hand(i).stiffness_n_per_m,
            _set_hand("stiffness_n_per_m"),
            _factor(0.05, 20.0),
            "hand",
        ),
        Parameter(
            "hand_damping_ns_per_m",
            "N·s/m",
            "translational damping between handle and arm (hand support)",
            lambda i: _hand(i).damping_ns_per_m,
            _set_hand("damping_ns_per_m"),
            _factor(0.05, 20.0),
            "hand",
        ),
        Parameter(
            "hand_arm_mass_kg",
            "kg",
            "mass of the arm behind the grip's springs (hand support)",
            lambda i: _hand(i).arm_mass_kg,
            _set_hand("arm_mass_kg"),
            lambda start: (0.2, 6.0),
            "hand",
        ),
    )
}
"""The parameters a calibration can fit, by name."""


def parse_fit(names: Sequence[str], inputs: ModelInputs) -> list[Parameter]:
    """The parameters named (``--fit``), each once, each one the inputs can take."""
    chosen = []
    for name in names:
        if name not in PARAMETERS:
            raise InputError(
                f"`fit`: {name!r} is not a parameter; choose from {', '.join(PARAMETERS)}"
            )
        chosen.append(PARAMETERS[name])
    if not chosen or len({p.name for p in chosen}) != len(chosen):
        raise InputError(f"`fit`: name each parameter once (got {','.join(names)})")
    if "e_bg" in names and inputs.ball.e_bg_table and not inputs.ball.e_bg_source:
        raise InputError(
            "`fit` e_bg: the ball's e_BG is a table against speed; fit a constant e_BG "
            "(drop the ball's `e_bg_table`) or leave e_bg out"
        )
    return chosen


def apply(inputs: ModelInputs, values: dict[str, float]) -> ModelInputs:
    """The inputs with these parameter values (names of :data:`PARAMETERS`)."""
    for name, value in values.items():
        if name not in PARAMETERS:
            raise InputError(f"calibration: unknown parameter {name!r}")
        if math.isfinite(value):
            inputs = PARAMETERS[name].set(inputs, float(value))
    return inputs


@dataclass
class Calibration:
    """A calibration's result.

    Attributes
    ----------
    names : list of str
        Fitted parameters, in order.
    start, value, standard_error : ndarray
        Starting values, fitted values and standard errors (NaN where not identifiable), in
        each parameter's unit.
    low, high : ndarray
        Bounds.
    identifiable : list of bool
        Whether the data tell each parameter apart.
    why : list of str
        For each: empty, or why it is not identifiable.
    correlation : ndarray (p, p)
        Correlation matrix of the estimates (NaN rows for parameters not identifiable).
    singular_values : ndarray
        Of the column-normalised Jacobian, largest first.
    condition : float
        Their ratio (largest / smallest).
    fit_rms, holdout_rms : float
        RMS of predicted − measured rebound ratio on the fitted rows and on the held-out rows
        (NaN without held-out rows).
    n_fit, n_holdout, n_flagged : int
        Rows fitted, held out, and left out because the model gives no number there.
    reduced_chi2 : float
        Weighted RSS / (n − p).
    degrees_of_freedom : int
        n − p of ``reduced_chi2`` (n counts the data rows and one row per prior).
    priors : dict
        ``name → sd`` of the normal priors the fit took (about each start).
    weighted : bool
        Rows weighted by their measured standard deviations.
    method : str
        The model fitted.
    evaluations : int
        Model evaluations of the optimiser.
    success : bool, message : str
        The optimiser's outcome.
    residual_fit, residual_holdout : ndarray
        Predicted − measured per row (NaN for flagged rows).
    loo : ndarray
        Leave-one-out residuals (empty unless asked for).
    predicted_start, predicted : ndarray
        Every row's rebound ratio predicted with the starting and with the fitted inputs
        (NaN where the model gives none), dimensionless.
    status_start, status : ndarray of str
        Why a row has no prediction (``ok`` where it has one), with each set of inputs.
    poor_fit : str or None
        Why the fit is poor (a weighted fit whose reduced χ² the measured standard deviations
        make unlikely, p < :data:`POOR_FIT_P`), else None.
    """

    names: list[str]
    start: NDArray[np.float64]
    value: NDArray[np.float64]
    standard_error: NDArray[np.float64]
    low: NDArray[np.float64]
    high: NDArray[np.float64]
    identifiable: list[bool]
    why: list[str]
    correlation: NDArray[np.float64]
    singular_values: NDArray[np.float64]
    condition: float
    fit_rms: float
    holdout_rms: float
    n_fit: int
    n_holdout: int
    n_flagged: int
    reduced_chi2: float
    weighted: bool
    method: str
    evaluations: int
    success: bool
    message: str
    residual_fit: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    residual_holdout: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    loo: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    predicted_start: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    predicted: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    status_start: NDArray[np.str_] = field(default_factory=lambda: np.zeros(0, dtype=str))
    status: NDArray[np.str_] = field(default_factory=lambda: np.zeros(0, dtype=str))
    degrees_of_freedom: int = 0
    priors: dict[str, float] = field(default_factory=dict)

    @property
    def poor_fit(self) -> str | None:
        """Why the fit is poor, or None: with the rows weighted by their standard deviations,
        a reduced χ² the χ² distribution of its degrees of freedom puts beyond p =
        :data:`POOR_FIT_P` (issue 27: χ² 16.8 had been shown beside every status "ok")."""
        dof = self.degrees_of_freedom
        if not (self.weighted and dof > 0 and math.isfinite(self.reduced_chi2)):
            return None
        from scipy.stats import chi2

        p = float(chi2.sf(self.reduced_chi2 * dof, dof))
        if p >= POOR_FIT_P:
            return None
        said = "p < 0.001" if p < 1e-3 else f"p = {p:.2g}"
        return (
            f"reduced χ² {self.reduced_chi2:.3g} on {dof} degrees of freedom ({said}): the "
            f"residuals are about {math.sqrt(self.reduced_chi2):.2g} × the measured standard "
            "deviations, so the model (or those deviations) does not describe these "
            "measurements and the standard errors, which assume it does, are too small"
        )

    @property
    def values(self) -> dict[str, float]:
        """Fitted values by name (NaN where not identifiable)."""
        return {
            n: float(v) if ok else math.nan
            for n, v, ok in zip(self.names, self.value, self.identifiable, strict=True)
        }

    @property
    def loo_rms(self) -> float:
        """RMS of the leave-one-out residuals (NaN without)."""
        finite = self.loo[np.isfinite(self.loo)]
        return float(np.sqrt(np.mean(finite**2))) if finite.size else math.nan

    def as_dict(self) -> dict[str, Any]:
        """For calibration.json: numbers a parameter cannot have are null with the reason."""

        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        return {
            "method": self.method,
            "parameters": [
                {
                    "name": n,
                    "unit": PARAMETERS[n].unit,
                    "description": PARAMETERS[n].description,
                    "start": float(s),
                    "bounds": [float(lo), float(hi)],
                    "value": num(v) if ok else None,
                    "standard_error": num(se) if ok else None,
                    "identifiable": ok,
                    "status": "ok" if ok else f"not identifiable: {why}",
                    "best_fit_value": float(v),
                    "prior_sd": self.priors.get(n),
                }
                for n, s, lo, hi, v, se, ok, why in zip(
                    self.names,
                    self.start,
                    self.low,
                    self.high,
                    self.value,
                    self.standard_error,
                    self.identifiable,
                    self.why,
                    strict=True,
                )
            ],
            "correlation": [[num(c) for c in row] for row in self.correlation],
            "jacobian_singular_values": [float(s) for s in self.singular_values],
            "jacobian_condition": num(self.condition),
            "fit_rms": num(self.fit_rms),
            "holdout_rms": num(self.holdout_rms),
            "leave_one_out_rms": num(self.loo_rms),
            "leave_one_out_residuals": [num(r) for r in self.loo],
            "rows": {
                "fitted": self.n_fit,
                "held_out": self.n_holdout,
                "flagged_left_out": self.n_flagged,
            },
            "weighted_by_sd": self.weighted,
            "reduced_chi2": num(self.reduced_chi2),
            "degrees_of_freedom": self.degrees_of_freedom,
            "poor_fit": self.poor_fit,
            "optimiser": {
                "evaluations": self.evaluations,
                "success": self.success,
                "message": self.message,
            },
        }


def _residual_function(
    inputs: ModelInputs,
    parameters: Sequence[Parameter],
    start: NDArray[np.float64],
    measured: MeasuredRebound,
    method: Method,
    sd: NDArray[np.float64],
    progress: Callable[[int], None] | None = None,
) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
    calls = [0]

    def residual(scaled: NDArray[np.float64]) -> NDArray[np.float64]:
        calls[0] += 1
        if progress is not None:
            progress(calls[0])
        values = scaled * start
        trial = inputs
        for p, v in zip(parameters, values, strict=True):
            trial = p.set(trial, float(v))
        predicted, _ = predict_rows(trial, measured, method)
        r = (predicted - measured.rebound_ratio) / sd
        # a row that turns flagged during the fit weighs as a large miss, not as nothing
        data = np.where(np.isfinite(r), r, 10.0)
        return np.concatenate([data, _prior_rows(parameters, values, start)])

    return residual


def _prior_rows(
    parameters: Sequence[Parameter], values: NDArray[np.float64], start: NDArray[np.float64]
) -> NDArray[np.float64]:
    """One residual per parameter with a normal prior: (value − start) / prior sd.

    Least squares with these rows is the maximum of the posterior of a Gaussian likelihood
    and Gaussian priors (the rows' sd weighting the data), so the standard errors from the
    whole Jacobian are the posterior's (linearised)."""
    return np.array(
        [
            (v - s0) / p.prior_sd
            for p, v, s0 in zip(parameters, values, start, strict=True)
            if p.prior_sd is not None
        ],
        dtype=float,
    )


def _jacobian(
    f: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    x: NDArray[np.float64],
    low: NDArray[np.float64],
    high: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Central differences, one-sided at a bound."""
    columns = []
    for k in range(x.size):
        h = DIFF_STEP * max(abs(x[k]), 1e-12)
        up, down = x.copy(), x.copy()
        up[k] = min(x[k] + h, high[k])
        down[k] = max(x[k] - h, low[k])
        columns.append((f(up) - f(down)) / (up[k] - down[k]))
    return np.column_stack(columns)


def calibrate(
    inputs: ModelInputs,
    measured: MeasuredRebound,
    fit: Sequence[str],
    *,
    method: Method = "transient",
    holdout: Sequence[int] = (),
    leave_one_out: bool = False,
    bounds: Mapping[str, tuple[float, float]] | None = None,
    priors: Mapping[str, float] | None = None,
    progress: Callable[[str, int, int], None] | None = None,
) -> tuple[Calibration, ModelInputs]:
    """Fit the named parameters to the measured rebound ratios.

    Parameters
    ----------
    inputs : ModelInputs
        The starting inputs (the parameters' starting values are theirs).
    measured : MeasuredRebound
        All measured rows.
    fit : sequence of str
        Names of :data:`PARAMETERS`.
    method : {"approx", "transient"}
        The model fitted.
    holdout : sequence of int
        Rows (0-based) left out of the fit and predicted with the fitted values.
    leave_one_out : bool
        Also refit once per fitted row without it and predict it (the leave-one-out
        residuals; costs one fit per row).
    bounds : mapping, optional
        ``name → (low, high)`` in place of a parameter's own bounds (e.g. an uncertainty
        file's ranges: :func:`bounds_from_spreads`); a start outside them starts at their
        middle.
    priors : mapping, optional
        ``name → sd``: a normal prior about the parameter's start (an uncertainty file's
        normal spreads: :func:`priors_from_spreads`), the fit the posterior's maximum and its
        standard errors the posterior's.  Identifiability is judged on the data alone: a
        parameter the data cannot tell stays at its start (its prior's mean).
    progress : callable, optional
        ``progress(what, done, total)``: the fit's model evaluations (total 0: not known
        ahead) and the leave-one-out refits.

    Returns
    -------
    Calibration
        Values, standard errors, identifiability, correlation, RMS.
    ModelInputs
        The inputs with the identifiable fitted values (the others keep their start).
    """
    parameters = [_bounded(p, (bounds or {}).get(p.name)) for p in parse_fit(fit, inputs)]
    parameters = [_with_prior(p, (priors or {}).get(p.name)) for p in parameters]
    if any(p.prior_sd is not None for p in parameters) and measured.rebound_ratio_sd is None:
        raise InputError(
            "calibrate: `priors` need the rows' standard deviations (rebound_ratio_sd) to weigh "
            "the data against them; give the measured sd or fit without priors"
        )
    inputs = _start_within(inputs, parameters)
    n = len(measured)
    held = sorted({int(i) for i in holdout})
    if any(not 0 <= i < n for i in held):
        raise InputError(f"`holdout`: rows are numbered 1 to {n}")
    kept = sorted(set(range(n)) - set(held))
    for p in parameters:
        if p.support and p.support not in measured.support:
            log.info("%s: no %s rows; it will be reported not identifiable", p.name, p.support)
    # rows the model flags at the start are left out (counted), as validate leaves them out
    start_ratio, start_status = predict_rows(inputs, measured, method)
    flagged = [i for i in kept if not math.isfinite(start_ratio[i])]
    fitted = [i for i in kept if math.isfinite(start_ratio[i])]
    if len(fitted) < len(parameters):
        raise InputError(
            f"calibrate: {len(fitted)} rows left to fit ({len(held)} held out, {len(flagged)} "
            f"without a number from the {method} model), fewer than the {len(parameters)} "
            "parameters to fit; hold out fewer rows (`holdout`), measure more points or fit fewer"
        )

    def evaluations(what: str) -> Callable[[int], None] | None:
        if progress is None:
            return None
        shown = progress
        return lambda done: shown(f"{what}: model evaluation {done}", done, 0)

    result, fitted_inputs = _fit(
        inputs, parameters, measured.subset(fitted), method, evaluations("fitting")
    )
    result.n_flagged = len(flagged)
    result.n_holdout = len(held)
    result.priors = {p.name: p.prior_sd for p in parameters if p.prior_sd is not None}
    predicted, status = predict_rows(fitted_inputs, measured, method)
    result.predicted_start, result.status_start = start_ratio, start_status
    result.predicted, result.status = predicted, status
    residual = predicted - measured.rebound_ratio
    result.residual_fit = residual
    result.fit_rms = _rms(residual[fitted])
    result.holdout_rms = _rms(residual[held]) if held else math.nan
    result.residual_holdout = residual[held] if held else np.zeros(0)
    if leave_one_out:
        loo = np.full(n, np.nan)
        for k, i in enumerate(fitted, 1):
            others = [j for j in fitted if j != i]
            if len(others) < len(parameters):
                continue
            if progress is not None:
                progress(f"leave-one-out: refit {k} of {len(fitted)}", k - 1, len(fitted))
            _, refit = _fit(inputs, parameters, measured.subset(others), method)
            one, _ = predict_rows(refit, measured.subset([i]), method)
            loo[i] = one[0] - measured.rebound_ratio[i]
        result.loo = loo
    return result, fitted_inputs


def _rms(values: NDArray[np.float64]) -> float:
    finite = values[np.isfinite(values)]
    return float(np.sqrt(np.mean(finite**2))) if finite.size else math.nan


def _bounded(parameter: Parameter, given: tuple[float, float] | None) -> Parameter:
    """The parameter with given bounds (checked: 0 < low < high)."""
    if given is None:
        return parameter
    low, high = float(given[0]), float(given[1])
    if not (math.isfinite(low) and math.isfinite(high) and 0.0 < low < high):
        raise InputError(
            f"`bounds` of {parameter.name}: give 0 < low < high, not [{low:g}, {high:g}]"
        )
    return replace(parameter, bounds=lambda start: (low, high))


def _with_prior(parameter: Parameter, sd: float | None) -> Parameter:
    """The parameter with a normal prior of this sd (checked: finite, above 0)."""
    if sd is None:
        return parameter
    if not (math.isfinite(sd) and sd > 0.0):
        raise InputError(f"`priors` of {parameter.name}: give an sd above 0, not {sd:g}")
    return replace(parameter, prior_sd=float(sd))


def _start_within(inputs: ModelInputs, parameters: Sequence[Parameter]) -> ModelInputs:
    """The inputs with every parameter that starts outside its bounds at their middle."""
    for p in parameters:
        value = p.get(inputs)
        low, high = p.bounds(value)
        if not low <= value <= high:
            log.info("%s starts at %g, outside [%g, %g]: at their middle", p.name, value, low, high)
            inputs = p.set(inputs, 0.5 * (low + high))
    return inputs


def bounds_from_spreads(spreads: Sequence[Any]) -> dict[str, tuple[float, float]]:
    """Calibration bounds from an uncertainty's spreads (:class:`racketdyn.impact.uncertainty.
    Spread`): a range as it is, equally likely values from the least to the greatest; a normal
    spread bounds nothing (its centre is the start, not a limit).  The impact's own inputs
    (location, ball speed) are not calibrated."""
    found: dict[str, tuple[float, float]] = {}
    for spread in spreads:
        if spread.name not in PARAMETERS:
            continue
        if spread.bounds is not None and spread.bounds[0] < spread.bounds[1]:
            found[spread.name] = (float(spread.bounds[0]), float(spread.bounds[1]))
        elif len(set(spread.values)) > 1:
            found[spread.name] = (float(min(spread.values)), float(max(spread.values)))
    return found


def priors_from_spreads(spreads: Sequence[Any]) -> dict[str, float]:
    """Calibration priors from an uncertainty's normal spreads: ``name → sd`` about the
    parameter's start, for the names a calibration fits (a zero sd pins nothing here: a
    parameter fixed at its value is one not fitted)."""
    return {
        spread.name: float(spread.sd)
        for spread in spreads
        if spread.name in PARAMETERS and spread.sd is not None and spread.sd > 0.0
    }


def _fit(
    inputs: ModelInputs,
    parameters: Sequence[Parameter],
    measured: MeasuredRebound,
    method: Method,
    progress: Callable[[int], None] | None = None,
) -> tuple[Calibration, ModelInputs]:
    """Fit, and refit the identifiable parameters alone when some are not: a parameter the
    data cannot tell stays at its start, and the others' values and standard errors are those
    of the fit without it."""
    first, fitted = _fit_once(inputs, parameters, measured, method, progress)
    keep = [k for k, ok in enumerate(first.identifiable) if ok]
    if len(keep) in (0, len(parameters)):
        return first, fitted
    second, fitted = _fit(inputs, [parameters[k] for k in keep], measured, method, progress)
    p = len(parameters)
    merged_se = np.full(p, np.nan)
    correlation = np.full((p, p), np.nan)
    identifiable = [False] * p
    why = list(first.why)
    value = first.value.copy()
    for a, ka in enumerate(keep):
        value[ka] = second.value[a]
        merged_se[ka] = second.standard_error[a]
        identifiable[ka] = second.identifiable[a]
        why[ka] = second.why[a]
        for b, kb in enumerate(keep):
            correlation[ka, kb] = second.correlation[a, b]
    first.value, first.standard_error, first.correlation = value, merged_se, correlation
    first.identifiable, first.why = identifiable, why
    first.evaluations += second.evaluations
    first.reduced_chi2 = second.reduced_chi2
    first.degrees_of_freedom = second.degrees_of_freedom
    return first, fitted


def _fit_once(
    inputs: ModelInputs,
    parameters: Sequence[Parameter],
    measured: MeasuredRebound,
    method: Method,
    progress: Callable[[int], None] | None = None,
) -> tuple[Calibration, ModelInputs]:
    """One bounded least-squares fit on these rows, with the statistics at its solution."""
    start = np.array([p.get(inputs) for p in parameters], dtype=float)
    if np.any(start <= 0):
        raise InputError("calibrate: every fitted parameter must start above 0")
    bounds = [p.bounds(float(s)) for p, s in zip(parameters, start, strict=True)]
    low = np.array([b[0] for b in bounds]) / start
    high = np.array([b[1] for b in bounds]) / start
    weighted = measured.rebound_ratio_sd is not None
    sd = (
        measured.rebound_ratio_sd
        if measured.rebound_ratio_sd is not None
        else np.ones(len(measured))
    )
    f = _residual_function(inputs, parameters, start, measured, method, sd, progress)
    x0 = np.clip(np.ones(start.size), low, high)
    solution = least_squares(
        f, x0, bounds=(low, high), method="trf", diff_step=DIFF_STEP, x_scale=1.0
    )
    x = solution.x
    r = f(x)
    jac = _jacobian(f, x, low, high)
    data_jac = jac[: len(measured)]  # identifiability from the data alone, not the priors
    n, p = r.size, x.size
    rss = float(r @ r)
    dof = n - p
    reduced = rss / dof if dof > 0 else math.nan
    s2 = 1.0 if weighted else reduced
    norms = np.linalg.norm(data_jac, axis=0)
    biggest = float(np.max(norms)) if norms.size else 0.0
    inert = norms <= 1e-9 * max(biggest, 1e-300)
    why = ["the data do not change with it" if dead else "" for dead in inert]
    live = ~inert
    singular = np.zeros(0)
    condition = math.inf
    cov = np.full((p, p), np.nan)
    if np.any(live):
        normalised = data_jac[:, live] / norms[live]
        _, singular, vt = np.linalg.svd(normalised, full_matrices=False)
        condition = float(singular[0] / singular[-1]) if singular[-1] > 0 else math.inf
        relative = singular / singular[0]
        live_index = [int(i) for i in np.flatnonzero(live)]
        null = vt[relative < NULL_SINGULAR_VALUE]
        for direction in null:
            for k, weight in zip(live_index, direction, strict=True):
                if abs(weight) > 0.1 and not why[k]:
                    others = [
                        parameters[j].name
                        for j, w in zip(live_index, direction, strict=True)
                        if j != k and abs(w) > 0.1
                    ]
                    why[k] = (
                        "the data cannot tell it apart from " + ", ".join(others)
                        if others
                        else "its effect is below the data's resolution"
                    )
        good = [k for k in live_index if not why[k]]
        if good and dof > 0 and math.isfinite(s2):
            sub = jac[:, good]
            try:
                inverse = np.linalg.inv(sub.T @ sub) * s2
            except np.linalg.LinAlgError:
                inverse = np.full((len(good), len(good)), np.nan)
            for a, ka in enumerate(good):
                for b, kb in enumerate(good):
                    cov[ka, kb] = inverse[a, b]
    se_scaled = np.sqrt(np.diag(cov))
    value = x * start
    se = se_scaled * start
    for k in range(p):
        if not why[k] and math.isfinite(se[k]) and 4.0 * se[k] > (high[k] - low[k]) * start[k]:
            why[k] = f"its two-standard-error interval (±{2 * se[k]:.3g}) is wider than its bounds"
        if not why[k] and not math.isfinite(se[k]):
            why[k] = "no standard error (too few rows for the parameters)"
    identifiable = [not w for w in why]
    with np.errstate(invalid="ignore", divide="ignore"):
        d = np.sqrt(np.diag(cov))
        correlation = cov / np.outer(d, d)
    fitted_values = {
        prm.name: float(v) for prm, v, ok in zip(parameters, value, identifiable, strict=True) if ok
    }
    data_r = r[: len(measured)]  # the prior rows are not the rows' residuals
    sd_free = np.where(np.isfinite(data_r), data_r * sd, np.nan)
    result = Calibration(
        names=[prm.name for prm in parameters],
        start=start,
        value=value,
        standard_error=np.where(identifiable, se, np.nan),
        low=low * start,
        high=high * start,
        identifiable=identifiable,
        why=why,
        correlation=correlation,
        singular_values=singular,
        condition=condition,
        fit_rms=_rms(sd_free),
        holdout_rms=math.nan,
        n_fit=n,
        n_holdout=0,
        n_flagged=0,
        reduced_chi2=reduced,
        degrees_of_freedom=max(dof, 0),
        weighted=weighted,
        method=method,
        evaluations=int(solution.nfev),
        success=bool(solution.success),
        message=str(solution.message),
    )
    return result, apply(inputs, fitted_values)


def simulate_measurements(
    inputs: ModelInputs,
    locations: ArrayLike,
    ball_speed: float | Sequence[float],
    support: str | Sequence[str] = "free",
    *,
    sd: float = 0.005,
    racket_speed: float = 0.0,
    method: Method = "transient",
    rng: np.random.Generator | int | None = None,
) -> MeasuredRebound:
    """Measurements a model would give, with Gaussian noise: a synthetic truth for testing a
    calibration, or for checking before a test whether its points can identify a parameter.

    Parameters
    ----------
    inputs : ModelInputs
        The "true" racket, ball, hand and scales.
    locations : array_like (n, 2)
        Impact points (x, y), m.
    ball_speed : float or sequence of float
        Incoming ball speed of every row, or one per row, m/s.
    support : str or sequence of str
        Support of every row, or one per row.
    sd : float
        Standard deviation of the noise on the rebound ratio (also the rows'
        ``rebound_ratio_sd``); 0 for exact values (then no sd is recorded).
    racket_speed : float
        Racket speed of every row, m/s.
    method : {"approx", "transient"}
        The model making the truth.
    rng : Generator or int, optional
        Random generator or seed.

    Returns
    -------
    MeasuredRebound
        ``source`` says it is synthetic; rows the model flags are dropped.
    """
    xy = np.asarray(locations, dtype=float).reshape(-1, 2)
    n = len(xy)
    speeds = np.broadcast_to(np.asarray(ball_speed, dtype=float), (n,)).copy()
    supports = (support,) * n if isinstance(support, str) else tuple(support)
    if len(supports) != n:
        raise InputError(f"simulate_measurements: {len(supports)} supports for {n} points")
    rows = MeasuredRebound(
        xy,
        speeds,
        np.full(n, float(racket_speed)),
        supports,
        np.zeros(n),
        None,
        tuple(str(i + 1) for i in range(n)),
        tuple(range(1, n + 1)),
        f"synthetic ({method} model)",
    )
    clean, _ = predict_rows(inputs, rows, method)
    noise = np.random.default_rng(rng).normal(0.0, sd, n) if sd > 0 else np.zeros(n)
    keep = np.flatnonzero(np.isfinite(clean))
    synthetic = MeasuredRebound(
        xy,
        speeds,
        rows.racket_speed,
        supports,
        clean + noise,
        np.full(n, sd) if sd > 0 else None,
        rows.labels,
        rows.lines,
        rows.source,
    )
    return synthetic.subset(keep)
