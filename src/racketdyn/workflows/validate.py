"""Step ``validate``: predicted against measured rebound, for both impact models (issue 15).

Writes ``validation.csv`` (:data:`VALIDATION_COLUMNS`: each measured row with both models'
predictions, residuals and statuses) and ``run.json`` (the summary per model: rows compared,
rows flagged, RMS error and bias of the rebound ratio, RMS of the outgoing speed in m/s and in
per cent); the figures come from the caller's hook.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn._grammar import noun
from racketdyn.errors import InputError
from racketdyn.impact.calibration import PARAMETERS, apply
from racketdyn.impact.measured import (
    METHODS,
    ModelInputs,
    outlier_labels,
    outlier_rank,
    predict_rows,
    standardised_residuals,
)
from racketdyn.impact.transient import ENGINES
from racketdyn.impact.uncertainty import RowBands, Uncertainty, propagate_rows
from racketdyn.io import racket_to_dict
from racketdyn.io.measured import MeasuredRebound, read_measured
from racketdyn.workflows.figure_data import defer_figure_data
from racketdyn.workflows.run import (
    StepResult,
    check_workers,
    report,
    run_step,
    sample_pool,
    sha256,
    write_rows,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

__all__ = [
    "BAND_COLUMNS",
    "VALIDATION_COLUMNS",
    "MethodSummary",
    "ValidateResult",
    "load_calibration",
    "measured_setup",
    "run_validate",
    "summarise",
]

VALIDATION_COLUMNS = (
    "row",
    "point",
    "x_m",
    "y_m",
    "ball_speed_mps",
    "racket_speed_mps",
    "support",
    "measured",
    "measured_sd",
    "predicted_approx",
    "predicted_transient",
    "residual_approx",
    "residual_transient",
    "status_approx",
    "status_transient",
    "z_approx",
    "z_transient",
)
"""Columns of ``validation.csv``: rebound ratios (measured, predicted, residual = predicted −
measured); a row a model flags holds NaN in its predicted and residual columns, its status
says why; ``z_*`` the residual in standard deviations
(:func:`racketdyn.impact.measured.standardised_residuals`: beyond ± 3 an outlier).
``row`` is the row's number in the measured file (1 = first data row)."""

BAND_COLUMNS = (
    "p05_approx",
    "p95_approx",
    "inside_approx",
    "p05_transient",
    "p95_transient",
    "inside_transient",
)
"""With an uncertainty, after :data:`VALIDATION_COLUMNS`: each model's 90 % band of the
predicted rebound ratio and whether the measured value lies in it (empty where the band is
not given: fewer than 90 % of the samples valid)."""


@dataclass(frozen=True)
class MethodSummary:
    """Predicted against measured for one model.

    Attributes
    ----------
    method : str
        ``approx`` or ``transient``.
    n_compared, n_flagged : int
        Rows with a prediction, and rows the model flags (NaN, left out).
    rms, bias : float
        RMS and mean of predicted − measured rebound ratio (NaN with no row compared).
    rms_speed_mps : float
        RMS of predicted − measured outgoing ball speed, m/s.
    rms_speed_percent : float
        RMS of (predicted − measured) / measured outgoing speed, %.
    n_banded, n_inside : int
        With an uncertainty: rows with a 90 % band, and rows whose measured value lies in it.
    median_band_width : float
        Median width of the 90 % band over the rows with one (NaN without).
    outside : tuple of str
        Labels of the rows whose measured value lies outside their band.
    """

    method: str
    n_compared: int
    n_flagged: int
    rms: float
    bias: float
    rms_speed_mps: float
    rms_speed_percent: float
    n_banded: int = 0
    n_inside: int = 0
    median_band_width: float = math.nan
    outside: tuple[str, ...] = ()

    def as_dict(self) -> dict[str, Any]:
        """For run.json (NaN as null)."""
        return {
            key: (None if isinstance(v, float) and not math.isfinite(v) else v)
            for key, v in vars(self).items()
        }


def summarise(
    method: str, measured: MeasuredRebound, predicted: NDArray[np.float64]
) -> MethodSummary:
    """RMS error and bias of one model's predictions (flagged rows left out, counted)."""
    ok = np.isfinite(predicted)
    residual = (predicted - measured.rebound_ratio)[ok]
    approach = (measured.ball_speed + measured.racket_speed)[ok]
    out = measured.outgoing_speed[ok]
    speed_error = residual * approach  # v_out = e v_b + (1 + e) v_r: dv_out = de (v_b + v_r)
    nan = math.nan
    if not residual.size:
        return MethodSummary(method, 0, int((~ok).sum()), nan, nan, nan, nan)
    with np.errstate(divide="ignore", invalid="ignore"):
        relative = speed_error / out
    return MethodSummary(
        method,
        int(ok.sum()),
        int((~ok).sum()),
        float(np.sqrt(np.mean(residual**2))),
        float(np.mean(residual)),
        float(np.sqrt(np.mean(speed_error**2))),
        float(100.0 * np.sqrt(np.mean(relative**2))) if np.all(out > 0) else nan,
    )


@dataclass
class ValidateResult(StepResult):
    """What :func:`run_validate` computed and wrote.

    Attributes
    ----------
    measured : MeasuredRebound
        The measured rows.
    inputs : ModelInputs
        Racket, ball, hand, modes and scales the predictions used (calibrated if asked).
    predicted, status : dict of str to ndarray
        Per model: predicted rebound ratio per row (NaN where flagged) and its status.
    summary : dict of str to MethodSummary
        Per model.
    calibration : dict of str to float
        The calibrated values applied (empty without ``calibration``).
    bands : dict of str to RowBands
        With an uncertainty: per model, the 90 % band at every row.
    standardised : dict of str to ndarray
        Per model: each row's residual in standard deviations
        (:func:`racketdyn.impact.measured.standardised_residuals`); the outliers are beyond
        ± :data:`racketdyn.impact.measured.OUTLIER_LIMIT`.
    """

    measured: MeasuredRebound | None = None
    inputs: ModelInputs | None = None
    predicted: dict[str, NDArray[np.float64]] = field(default_factory=dict)
    status: dict[str, NDArray[np.str_]] = field(default_factory=dict)
    summary: dict[str, MethodSummary] = field(default_factory=dict)
    calibration: dict[str, float] = field(default_factory=dict)
    bands: dict[str, RowBands] = field(default_factory=dict)
    standardised: dict[str, NDArray[np.float64]] = field(default_factory=dict)

    @property
    def outlier_rank(self) -> dict[str, NDArray[np.int64]]:
        """Per model, each row's rank among its outliers (1 the worst; 0 not one): what the
        parity figure names."""
        return {method: outlier_rank(z) for method, z in self.standardised.items()}

    def outliers(self, method: str) -> tuple[str, ...]:
        """The labels of one model's outlying rows (absolute z beyond the limit), worst first."""
        assert self.measured is not None
        return outlier_labels(self.measured, self.standardised[method])


def load_calibration(path: str | os.PathLike[str]) -> dict[str, float]:
    """The identifiable fitted values of a ``calibration.json`` (calibrate's output)."""
    file = Path(path)
    try:
        data = json.loads(file.read_text(encoding="utf-8"))
        parameters = data["parameters"]
        values = {
            str(p["name"]): float(p["value"]) for p in parameters if p.get("value") is not None
        }
    except FileNotFoundError:
        raise InputError(f"`calibration` {file}: no such file") from None
    except (OSError, ValueError, KeyError, TypeError) as error:
        raise InputError(
            f"`calibration` {file}: not a calibration.json written by racketdyn calibrate "
            f"({type(error).__name__}: {error})"
        ) from None
    unknown = [name for name in values if name not in PARAMETERS]
    if unknown:
        raise InputError(
            f"`calibration` {file}: unknown {noun(len(unknown), 'parameter')} {', '.join(unknown)}"
        )
    return values


def measured_setup(
    setup: Setup,
    measured: MeasuredRebound | str | os.PathLike[str],
    engine: str,
) -> tuple[ModelInputs, MeasuredRebound, dict[str, Any], list[str]]:
    """The measured rows (checked on the racket's face) and the model inputs (with
    ``setup.string_bed="local"``, the string-bed law of each point:
    :func:`racketdyn.contact.local_string_bed_law`).

    Returns
    -------
    inputs : ModelInputs
    measured : MeasuredRebound
    provenance : dict
        Racket, modes and measured file, for run.json.
    defaults : list of str
        Defaults used.
    """
    if engine not in ENGINES:
        raise InputError(f"`engine` must be one of {', '.join(ENGINES)} (got {engine!r})")
    rows = (
        measured
        if isinstance(measured, MeasuredRebound)
        else read_measured(Path(measured), allow_implausible=setup.allow_implausible)
    )
    used = setup.racket_setup()
    outside = np.flatnonzero(~used.racket.head.contains(rows.locations))
    if outside.size:
        i = int(outside[0])
        x, y = rows.locations[i]
        raise InputError(
            f"{rows.source}: line {rows.lines[i]}: the point x={x:.4f} m, y={y:.4f} m lies "
            f"outside the string bed of {used.racket.name} (give points on its strings, or "
            "the racket file of the racket measured: `racket`)"
        )
    the_ball, ball_defaults = setup.ball_used()
    the_hand, hand_defaults = setup.hand_used(rows.support)
    provenance = dict(used.provenance)
    if not isinstance(measured, MeasuredRebound):
        provenance["measured_file"] = str(Path(measured).resolve())
        provenance["measured_sha256"] = sha256(Path(measured))
    # the built-in model follows the racket (a fitted roll inertia changes its twisting mode)
    follows = (
        used.modal_model is not None
        and setup.modal_model is None
        and used.racket.modal_model_file is None
    )
    inputs = ModelInputs(
        used.racket,
        the_ball,
        the_hand,
        "racket" if follows else (None if setup.rigid else used.modal_model),
        engine=engine,
        string_bed=setup.string_bed,
    )
    return inputs, rows, provenance, [*used.defaults, *ball_defaults, *hand_defaults]


@run_step
def run_validate(
    out: str | os.PathLike[str],
    measured: MeasuredRebound | str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    *,
    calibration: str | os.PathLike[str] | dict[str, float] | None = None,
    engine: str = "auto",
    uncertainty: Uncertainty | None = None,
    workers: int | None = None,
) -> ValidateResult:
    """Predict every measured row by both models and write the run folder.

    Parameters
    ----------
    out : path
        Output folder (created if missing).
    measured : MeasuredRebound or path
        Measured rebound (a CSV file: :func:`racketdyn.io.read_measured`).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, validate uses the racket and its
        modes, the ball, the hand (with a ``hand`` row), the string bed and
        ``allow_implausible``; and the run (command, figures, progress).
    calibration : path or dict, optional
        A ``calibration.json`` (calibrate's output) or ``{name: value}``: its values applied.
    engine : {"auto", "compiled", "reference"}
        Transient engine.
    uncertainty : Uncertainty, optional
        Uncertain inputs: each model's 90 % band at every row (:data:`BAND_COLUMNS`), the
        coverage in the summary, the rows outside their band named.
    workers : int, optional
        Worker processes for the samples (a local pool,
        :func:`racketdyn.sweep.executors.make_executor`); by default this process.

    Returns
    -------
    ValidateResult
    """
    check_workers(workers, uncertainty)
    inputs, rows, provenance, defaults_used = measured_setup(setup, measured, engine)
    values: dict[str, float] = {}
    if isinstance(calibration, dict):
        values = {str(k): float(v) for k, v in calibration.items()}
        provenance["calibration"] = "values given from Python"
    elif calibration is not None:
        values = load_calibration(calibration)
        provenance["calibration_file"] = str(Path(calibration).resolve())
        provenance["calibration_sha256"] = sha256(Path(calibration))
    try:
        inputs = apply(inputs, values)
    except InputError as error:  # a value the model refuses: name where it came from
        source = "calibration" if isinstance(calibration, dict) else f"`calibration` {calibration}"
        raise InputError(f"{source}: {error}") from None
    result = ValidateResult(Path(out), measured=rows, inputs=inputs, calibration=values)
    for method in METHODS:
        report(setup.progress, f"{method}: {len(rows)} measured impacts")
        predicted, status = predict_rows(inputs, rows, method)
        result.predicted[method], result.status[method] = predicted, status
        result.summary[method] = summarise(method, rows, predicted)
        result.standardised[method] = standardised_residuals(rows, predicted)
        if uncertainty is not None:
            report(
                setup.progress, f"{method}: {uncertainty.samples} samples of the uncertain inputs"
            )
            with sample_pool(workers) as executor:
                band = propagate_rows(inputs, rows, uncertainty, method, executor=executor)
            result.bands[method] = band
            result.summary[method] = _coverage(result.summary[method], band, rows)
    result.written.append(write_rows(Path(out) / "validation.csv", _rows(result)))
    defer_figure_data(
        result,
        {
            "measured": rows,
            "predicted": result.predicted,
            "outlier_rank": result.outlier_rank,
            "inputs": {"effective_racket": inputs.effective_racket},
        },
    )
    record = {
        **provenance,
        "racket": racket_to_dict(inputs.effective_racket),
        "ball_e_bg": inputs.ball.e_bg_record(),
        "hand": None if inputs.hand is None else vars(inputs.hand),
        "scales": {
            "string_stiffness_scale": inputs.string_stiffness_scale,
            "frame_damping_scale": inputs.frame_damping_scale,
        },
        "calibrated_values": values,
        "engine": engine,
        "string_bed": setup.string_bed,
        "string_bed_law": _law_words(setup.string_bed),
        "n_rows": len(rows),
        "measured_column": rows.given,
        "rebound_ratio": "e = (v_out - v_racket) / (v_ball + v_racket)",
        "summary": {m: s.as_dict() for m, s in result.summary.items()},
        "columns": {
            "validation.csv": [*VALIDATION_COLUMNS, *(BAND_COLUMNS if result.bands else ())]
        },
        "uncertainty": None if uncertainty is None else uncertainty.record(),
        "defaults_used": [*defaults_used, *setup.defaults],
    }
    return setup.finish(result, record, "validate")


def _rows(result: ValidateResult) -> list[dict[str, Any]]:
    rows = result.measured
    assert rows is not None
    sd = rows.rebound_ratio_sd
    table = []
    for i in range(len(rows)):
        approx, transient = result.predicted["approx"][i], result.predicted["transient"][i]
        table.append(
            {
                "row": i + 1,
                "point": rows.labels[i],
                "x_m": rows.locations[i, 0],
                "y_m": rows.locations[i, 1],
                "ball_speed_mps": rows.ball_speed[i],
                "racket_speed_mps": rows.racket_speed[i],
                "support": rows.support[i],
                "measured": rows.rebound_ratio[i],
                "measured_sd": None if sd is None else sd[i],
                "predicted_approx": approx,
                "predicted_transient": transient,
                "residual_approx": approx - rows.rebound_ratio[i],
                "residual_transient": transient - rows.rebound_ratio[i],
                "status_approx": result.status["approx"][i],
                "status_transient": result.status["transient"][i],
                "z_approx": result.standardised["approx"][i],
                "z_transient": result.standardised["transient"][i],
                **_band_cells(result, i),
            }
        )
    return table


def _band_cells(result: ValidateResult, i: int) -> dict[str, Any]:
    cells: dict[str, Any] = {}
    assert result.measured is not None
    for method, band in result.bands.items():
        given = bool(band.given[i])
        inside = bool(band.inside(result.measured.rebound_ratio)[i])
        cells[f"p05_{method}"] = band.p05[i] if given else None
        cells[f"p95_{method}"] = band.p95[i] if given else None
        cells[f"inside_{method}"] = (1 if inside else 0) if given else None
    return cells


def _coverage(summary: MethodSummary, band: RowBands, rows: MeasuredRebound) -> MethodSummary:
    """The summary with how many measured rows lie in their band, and which do not."""
    given = band.given
    inside = band.inside(rows.rebound_ratio)
    width = (band.p95 - band.p05)[given]
    return replace(
        summary,
        n_banded=int(given.sum()),
        n_inside=int(inside.sum()),
        median_band_width=float(np.median(width)) if width.size else math.nan,
        outside=tuple(rows.labels[i] for i in np.flatnonzero(given & ~inside)),
    )


def _law_words(string_bed: str) -> str:
    """How the string bed's law was taken, for run.json."""
    if string_bed == "local":
        return (
            "local: Kawazoe's law with the main and cross strings through each point "
            "(racketdyn.contact.local_string_bed_law)"
        )
    return "one law for the whole face: the face centre's (racketdyn.contact.string_bed_law)"
