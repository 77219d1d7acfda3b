"""Step ``calibrate``: uncertain inputs fitted to measured rebound (issue 15).

Writes ``calibration.json`` (:meth:`racketdyn.impact.calibration.Calibration.as_dict`: values,
standard errors, identifiability, correlation, fit / held-out / leave-one-out RMS),
``calibration_rows.csv`` (each measured row: fitted or held out, measured, predicted before and
after, residual, leave-one-out residual, the residual in standard deviations), the
figure's data (``figures.nc``: the rows before and after, for ``calibration_parity.png``), the
calibrated inputs as files the other commands
take — ``racket.toml`` (roll inertia, string bed scaled; with ``modal.json`` when the frame
damping was fitted) — and ``run.json``.  ``validate --calibration calibration.json`` applies
every identifiable value, the ball's and the hand's included.
"""

from __future__ import annotations

import json
import logging
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.errors import InputError
from racketdyn.impact.calibration import (
    Calibration,
    bounds_from_spreads,
    calibrate,
    priors_from_spreads,
)
from racketdyn.impact.measured import (
    METHODS,
    Method,
    ModelInputs,
    outlier_rank,
    standardised_residuals,
)
from racketdyn.impact.uncertainty import Uncertainty
from racketdyn.io.measured import MeasuredRebound
from racketdyn.io.racket_file import load_racket, write_racket_toml
from racketdyn.racket import Racket
from racketdyn.workflows.figure_data import defer_figure_data
from racketdyn.workflows.run import (
    StepResult,
    report,
    run_step,
    write_rows,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup
from racketdyn.workflows.validate import measured_setup

log = logging.getLogger(__name__)

__all__ = ["CALIBRATION_ROW_COLUMNS", "CalibrateResult", "run_calibrate"]

CALIBRATION_ROW_COLUMNS = (
    "row",
    "point",
    "x_m",
    "y_m",
    "ball_speed_mps",
    "racket_speed_mps",
    "support",
    "role",
    "measured",
    "measured_sd",
    "predicted_before",
    "predicted_after",
    "residual_after",
    "residual_leave_one_out",
    "z_after",
    "status",
)
"""Columns of ``calibration_rows.csv``: ``role`` is ``fitted``, ``held out`` or ``flagged``
(the model gives no number there at the start); rebound ratios, residual = predicted −
measured; ``z_after`` the residual after in standard deviations
(:func:`racketdyn.impact.measured.standardised_residuals`: beyond ± 3 an outlier)."""


@dataclass
class CalibrateResult(StepResult):
    """What :func:`run_calibrate` computed and wrote.

    Attributes
    ----------
    calibration : Calibration
        The fit.
    inputs, calibrated : ModelInputs
        The inputs before and after.
    measured : MeasuredRebound
        The rows.
    before, after : ndarray
        Predicted rebound ratio per row before and after.
    holdout : list of int
        Held-out rows, 0-based.
    standardised : ndarray
        Each row's residual after, in standard deviations
        (:func:`racketdyn.impact.measured.standardised_residuals`).
    """

    calibration: Calibration | None = None
    inputs: ModelInputs | None = None
    calibrated: ModelInputs | None = None
    measured: MeasuredRebound | None = None
    before: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    after: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    holdout: list[int] = field(default_factory=list)
    standardised: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))

    def roles(self) -> NDArray[np.str_]:
        """Each row's role: ``fitted``, ``held out`` or ``flagged`` (no number at the start)."""
        role = np.where(np.isfinite(self.before), "fitted", "flagged").astype(object)
        role[self.holdout] = "held out"
        return np.asarray(role, dtype=str)

    @property
    def parity_predicted(self) -> dict[str, NDArray[np.float64]]:
        """What the parity figure draws: the rebound ratio ``before`` and ``after`` at every row
        (NaN where flagged)."""
        return {"before": self.before, "after": self.after}

    @property
    def parity_outliers(self) -> dict[str, NDArray[np.int64]]:
        """Each row's rank among the outliers ``after`` (1 the worst; 0 not one): what the
        figure names."""
        return {"after": outlier_rank(self.standardised)}

    @property
    def held_out(self) -> NDArray[np.bool_]:
        """Which rows were held out of the fit."""
        mask = np.zeros(self.after.shape, bool)
        mask[self.holdout] = True
        return mask


@run_step
def run_calibrate(
    out: str | os.PathLike[str],
    measured: MeasuredRebound | str | os.PathLike[str],
    fit: Sequence[str],
    setup: Setup = DEFAULT_SETUP,
    *,
    holdout: Sequence[int] = (),
    method: Method = "transient",
    leave_one_out: bool = True,
    engine: str = "auto",
    uncertainty: Uncertainty | None = None,
) -> CalibrateResult:
    """Fit the named parameters to measured rebound and write the run folder.

    Parameters
    ----------
    out : path
        Output folder (created if missing).
    measured : MeasuredRebound or path
        Measured rebound (:func:`racketdyn.io.read_measured`).
    fit : sequence of str
        Parameters to fit (:data:`racketdyn.impact.calibration.PARAMETERS`).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, calibrate uses the racket and its
        modes, the ball, the hand, the string bed and ``allow_implausible``; and the run
        (command, figures: ``calibration_parity.png``, progress).
    holdout : sequence of int
        Rows held out of the fit, numbered from 1 (the first data row).
    method : {"approx", "transient"}
        The model fitted.
    leave_one_out : bool
        Refit once per fitted row without it (leave-one-out residuals).
    engine : {"auto", "compiled", "reference"}
        As for :func:`racketdyn.workflows.validate.run_validate`.
    uncertainty : Uncertainty, optional
        Its ranges (and the span of equally likely values) bound the fitted parameters
        (:func:`racketdyn.impact.calibration.bounds_from_spreads`); its normal spreads are
        priors about the start when the rows carry standard deviations
        (:func:`racketdyn.impact.calibration.priors_from_spreads`).

    Returns
    -------
    CalibrateResult
    """
    if method not in METHODS:
        raise InputError(f"`method` must be one of {', '.join(METHODS)} (got {method!r})")
    inputs, rows, provenance, defaults_used = measured_setup(setup, measured, engine)
    held = [int(i) for i in holdout]
    if any(i < 1 or i > len(rows) for i in held):
        raise InputError(f"`holdout`: rows are numbered 1 to {len(rows)} (got {held})")
    held0 = [i - 1 for i in held]
    report(setup.progress, f"fitting {', '.join(fit)} to {len(rows) - len(held)} rows ({method})")
    limits = {} if uncertainty is None else bounds_from_spreads(uncertainty.spreads)
    priors = {} if uncertainty is None else priors_from_spreads(uncertainty.spreads)
    priors = {name: priors[name] for name in fit if name in priors}
    if priors and rows.rebound_ratio_sd is None:
        log.warning(
            "calibrate: the normal spreads of %s are not taken as priors: the measured rows "
            "carry no standard deviation to weigh them against",
            ", ".join(priors),
        )
        priors = {}
    calibration, calibrated = calibrate(
        inputs,
        rows,
        fit,
        method=method,
        holdout=held0,
        leave_one_out=leave_one_out,
        bounds={name: limits[name] for name in fit if name in limits},
        priors=priors,
        progress=setup.progress,
    )
    before, status = calibration.predicted_start, calibration.status_start
    after, status_after = calibration.predicted, calibration.status
    out_dir = Path(out)
    result = CalibrateResult(
        out_dir,
        calibration=calibration,
        inputs=inputs,
        calibrated=calibrated,
        measured=rows,
        before=before,
        after=after,
        holdout=held0,
        standardised=standardised_residuals(rows, after),
    )
    defer_figure_data(
        result,
        {
            "measured": rows,
            "parity_predicted": result.parity_predicted,
            "parity_outliers": result.parity_outliers,
            "held_out": result.held_out,
        },
    )
    record = calibration.as_dict()
    files = _calibrated_files(calibrated, calibration, out_dir)
    record["calibrated_files"] = {
        "racket.toml": f"{_racket_holds(calibration)} (predict --racket, validate --racket)",
        **({"modal.json": "its modes with the fitted damping (named by racket.toml)"}
           if "frame_damping_scale" in calibration.values else {}),
        "options": _options(calibration),
        "validate": "validate --calibration calibration.json applies every identifiable value",
    }  # fmt: skip
    path = out_dir / "calibration.json"
    path.write_text(json.dumps(record, indent=2), encoding="utf-8")
    result.written += [path, *files]
    result.written.append(
        write_rows(out_dir / "calibration_rows.csv", _rows(result, status, status_after))
    )
    inputs_record = {
        **provenance,
        "fit": list(fit),
        "method": method,
        "holdout_rows": held,
        "leave_one_out": leave_one_out,
        "engine": engine,
        "string_bed": setup.string_bed,
        "n_rows": len(rows),
        "summary": {
            key: record[key]
            for key in ("fit_rms", "holdout_rms", "leave_one_out_rms", "rows", "reduced_chi2")
        },
        "columns": {"calibration_rows.csv": list(CALIBRATION_ROW_COLUMNS)},
        "defaults_used": [*defaults_used, *setup.defaults],
    }
    return setup.finish(result, inputs_record, "calibrate")


_IN_RACKET_TOML = {
    "roll_inertia_kgm2": "roll inertia",
    "string_stiffness_scale": "string-bed scale",
    "frame_damping_scale": "frame damping (its modal.json)",
}
"""The fitted values racket.toml carries, with the words calibration.json names them by."""


def _racket_holds(calibration: Calibration) -> str:
    """What racket.toml holds of the fit: the fitted values it carries, if any."""
    values = calibration.values
    held = [words for name, words in _IN_RACKET_TOML.items()
            if math.isfinite(values.get(name, math.nan))]  # fmt: skip
    if not held:
        return "the racket as given: it carries none of the fitted values"
    return f"the racket with the fitted {' and '.join(held)}"


def _options(calibration: Calibration) -> str:
    """The command-line options carrying the fitted values racket.toml cannot hold."""
    values = calibration.values
    parts = [
        f"{option} {values[name]:{spec}}"
        for name, option, spec in (
            ("e_bg", "--e-bg", ".4f"),
            ("hand_arm_mass_kg", "--hand-arm-mass", ".4f"),
            ("hand_stiffness_n_per_m", "--hand-stiffness", ".5g"),
            ("hand_damping_ns_per_m", "--hand-damping", ".4g"),
        )
        if math.isfinite(values.get(name, math.nan))
    ]
    return " ".join(parts) if parts else "none"


def _calibrated_files(calibrated: ModelInputs, calibration: Calibration, out: Path) -> list[Path]:
    """racket.toml (and modal.json with a fitted damping), read back to prove them."""
    racket = calibrated.effective_racket
    written = []
    if math.isfinite(calibration.values.get("frame_damping_scale", math.nan)):
        model = calibrated.modes()
        assert model is not None
        model.write_json(out / "modal.json")
        written.append(out / "modal.json")
        racket = _with_modal_file(racket, out / "modal.json")
    path = write_racket_toml(
        racket, out / "racket.toml", "written by racketdyn calibrate (calibration.json beside)"
    )
    try:
        load_racket(path)
    except InputError as error:  # a fitted value beyond the plausible range: say so in the file
        text = path.read_text(encoding="utf-8")
        path.write_text(
            f"# a fitted value lies outside the plausible range ({error})\n"
            + text
            + "[checks]\nallow_implausible = true\n",
            encoding="utf-8",
        )
        load_racket(path)
    written.append(path)
    return written


def _with_modal_file(racket: Racket, path: Path) -> Racket:
    return replace(racket, modal_model_file=path)


def _rows(
    result: CalibrateResult, status: NDArray[np.str_], status_after: NDArray[np.str_]
) -> list[dict[str, Any]]:
    rows, calibration = result.measured, result.calibration
    assert rows is not None
    assert calibration is not None
    loo = calibration.loo if calibration.loo.size else np.full(len(rows), np.nan)
    sd = rows.rebound_ratio_sd
    roles = result.roles()
    table = []
    for i in range(len(rows)):
        role = roles[i]
        table.append(
            {
                "row": i + 1,
                "point": rows.labels[i],
                "x_m": rows.locations[i, 0],
                "y_m": rows.locations[i, 1],
                "ball_speed_mps": rows.ball_speed[i],
                "racket_speed_mps": rows.racket_speed[i],
                "support": rows.support[i],
                "role": role,
                "measured": rows.rebound_ratio[i],
                "measured_sd": None if sd is None else sd[i],
                "predicted_before": result.before[i],
                "predicted_after": result.after[i],
                "residual_after": result.after[i] - rows.rebound_ratio[i],
                "residual_leave_one_out": loo[i],
                "z_after": result.standardised[i],
                "status": status_after[i] if status_after[i] != "ok" else status[i],
            }
        )
    return table
