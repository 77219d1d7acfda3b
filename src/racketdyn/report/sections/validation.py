"""Predicted against measured rebound (``racketdyn validate``, issue 15)."""

from __future__ import annotations

import math
from typing import Any

from racketdyn.plotting.registry import in_section
from racketdyn.report.folder import RunFolder, read_csv
from racketdyn.report.formatting import fmt

HOW_TO_RUN = "racketdyn validate MEASURED.csv --racket R.toml --out DIR/validate"

"""validate's figures, in the order shown (racketdyn.plotting.validate)."""

_MODELS = {"approx": "approximate method", "transient": "transient simulation"}


def gather(run: RunFolder) -> dict[str, Any] | None:
    """``validation.csv`` and its run.json (the summary per model, the calibration applied) and
    the three figures."""
    folder = run.first("validation.csv")
    if folder is None:
        return None
    rows = read_csv(folder / "validation.csv", ("measured", "support"))
    record = run.record(folder)
    summary = record.get("summary")
    summary = summary if isinstance(summary, dict) else {}
    table, glance = [], []
    for key, name in _MODELS.items():
        s = summary.get(key)
        if not isinstance(s, dict):
            continue
        table.append(
            (
                name,
                fmt(s.get("n_compared"), ".0f"),
                fmt(s.get("n_flagged"), ".0f"),
                fmt(s.get("rms"), ".4f"),
                fmt(s.get("bias"), "+.4f"),
                fmt(s.get("rms_speed_mps"), ".2f"),
                fmt(s.get("rms_speed_percent"), ".1f"),
            )
        )
        percent = s.get("rms_speed_percent")
        if isinstance(percent, int | float) and math.isfinite(percent):
            glance.append(
                f"measured rebound, {name}: RMS error {percent:.1f} % of the outgoing speed "
                f"over {s.get('n_compared')} rows"
            )
    values = record.get("calibrated_values")
    calibration = (
        ", ".join(f"{k} = {fmt(v, '.4g')}" for k, v in values.items())
        if isinstance(values, dict)
        else ""
    )
    supports = sorted({r.get("support", "") for r in rows})
    return {
        "n_rows": len(rows),
        "supports": ", ".join(supports),
        "source": str(record.get("measured_file", "")),
        "calibration": calibration,
        "summary": table,
        "figures": run.group([(folder / figure.file, "") for figure in in_section("validation")]),
        "glance": glance,
    }
