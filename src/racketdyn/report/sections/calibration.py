"""Calibrated against measured rebound (``racketdyn calibrate``, issue 15): the fitted values
with their standard errors, what the data could not identify and why, the correlations, and
the fit, held-out and leave-one-out errors."""

from __future__ import annotations

import math
from typing import Any

from racketdyn.plotting.registry import in_section
from racketdyn.report.folder import RunFolder, read_json
from racketdyn.report.formatting import LABELS, UNITS, finite, fmt, split_unit, unit_symbol

HOW_TO_RUN = (
    "racketdyn calibrate MEASURED.csv --racket R.toml --fit e_bg,roll_inertia_kgm2 "
    "--holdout 3,7 --out DIR/calibrate"
)

_MODELS = {"approx": "approximate method", "transient": "transient simulation"}

STRONG_CORRELATION = 0.9
"""|r| from which two fitted parameters are said to trade off against each other."""


def _unit(name: str) -> tuple[str, str, float]:
    """(label, unit on the page, factor from SI) of a parameter name of
    :data:`racketdyn.impact.calibration.PARAMETERS`."""
    base, suffix = split_unit(name)
    unit, factor = unit_symbol(suffix), 1.0
    if suffix in UNITS:
        unit, factor = UNITS[suffix]
    return LABELS.get(base, base.replace("_", " ")), unit, factor


def _number(value: Any, factor: float) -> str:
    return fmt(float(value) * factor, ".4g") if finite(value) else "–"


def _parameter_row(p: dict[str, Any]) -> tuple[str, ...]:
    label, unit, factor = _unit(str(p.get("name", "")))
    bounds = p.get("bounds") or [None, None]
    identifiable = bool(p.get("identifiable"))
    value, error = p.get("value"), p.get("standard_error")
    if identifiable and isinstance(value, int | float) and finite(value):
        fitted = f"{_number(value, factor)} ± {_number(error, factor)}"
        relative = (
            f"{100.0 * abs(error / value):.1f} %"
            if isinstance(error, int | float) and finite(error) and value != 0.0
            else "–"
        )
        status = "identified"
    else:  # never a confident number for what the data cannot tell
        fitted, relative = "not identifiable", "–"
        status = str(p.get("status", "not identifiable")).removeprefix("not identifiable: ")
    return (
        label,
        unit or "1",
        _number(p.get("start"), factor),
        f"{_number(bounds[0], factor)} – {_number(bounds[1], factor)}",
        fitted,
        relative,
        status,
    )


def gather(run: RunFolder) -> dict[str, Any] | None:
    """``calibration.json`` (and the run's run.json): one row per fitted parameter, the
    correlation matrix of the identified ones, and the errors."""
    folder = run.first("calibration.json")
    if folder is None:
        return None
    data = read_json(folder / "calibration.json")
    record = run.record(folder)
    parameters = [p for p in data.get("parameters", []) if isinstance(p, dict)]
    rows = [_parameter_row(p) for p in parameters]
    names = [_unit(str(p.get("name", "")))[0] for p in parameters]
    matrix = data.get("correlation") or []
    shown = [i for i, p in enumerate(parameters) if p.get("identifiable")]
    correlation = [
        (names[i], *(_correlation(matrix, i, j) for j in shown)) for i in shown if len(shown) > 1
    ]
    pairs = [
        f"{names[i]} and {names[j]} (r = {float(matrix[i][j]):+.2f})"
        for a, i in enumerate(shown)
        for j in shown[a + 1 :]
        if _finite_at(matrix, i, j) and abs(float(matrix[i][j])) >= STRONG_CORRELATION
    ]
    given = data.get("rows")
    counts: dict[str, Any] = given if isinstance(given, dict) else {}
    errors = [
        ("fit (rows fitted)", fmt(data.get("fit_rms"), ".4f"), fmt(counts.get("fitted"), ".0f")),
        ("held out", fmt(data.get("holdout_rms"), ".4f"), fmt(counts.get("held_out"), ".0f")),
        (
            "leave-one-out",
            fmt(data.get("leave_one_out_rms"), ".4f"),
            fmt(counts.get("fitted"), ".0f") if finite(data.get("leave_one_out_rms")) else "–",
        ),
    ]
    identified = [
        f"{row[0]} {row[4]}{'' if row[1] == '1' else ' ' + row[1]}"
        for row, p in zip(rows, parameters, strict=True)
        if p.get("identifiable")
    ]
    missing = [row[0] for row, p in zip(rows, parameters, strict=True) if not p.get("identifiable")]
    glance = []
    if identified:
        glance.append(f"calibration: {'; '.join(identified)}")
    if missing:
        glance.append(f"calibration: not identifiable from the rows: {', '.join(missing)}")
    poor = data.get("poor_fit")  # calibration.json since issue 27
    if isinstance(poor, str) and poor:
        glance.append(f"calibration: the fit is poor ({poor.split(':')[0]})")
    return {
        "poor_fit": poor if isinstance(poor, str) else "",
        "model": _MODELS.get(str(data.get("method")), str(data.get("method", ""))),
        "source": str(record.get("measured_file", "")),
        "n_flagged": fmt(counts.get("flagged_left_out"), ".0f"),
        "weighted": bool(data.get("weighted_by_sd")),
        "reduced_chi2": fmt(data.get("reduced_chi2"), ".3g"),
        "parameters": rows,
        "correlation_header": ("", *(names[j] for j in shown)),
        "correlation": correlation,
        "trade_offs": pairs,
        "errors": errors,
        "string_bed": str(record.get("string_bed", "uniform")),
        "glance": glance,
        "figures": run.group([(folder / f.file, "") for f in in_section("calibration")]),
    }


def _finite_at(matrix: Any, i: int, j: int) -> bool:
    try:
        return finite(matrix[i][j]) and math.isfinite(float(matrix[i][j]))
    except (IndexError, TypeError):
        return False


def _correlation(matrix: Any, i: int, j: int) -> str:
    return f"{float(matrix[i][j]):+.2f}" if _finite_at(matrix, i, j) else "–"
