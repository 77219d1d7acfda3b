"""Impact force and contact time against ball speed (Figs 11–13)."""

from __future__ import annotations

from typing import Any

import numpy as np

from racketdyn._display import case_words
from racketdyn.impact.result import model_note
from racketdyn.plotting.registry import in_section
from racketdyn.report.folder import RunFolder, shown_case
from racketdyn.report.formatting import fmt

HOW_TO_RUN = "racketdyn predict --out DIR/predict"


def gather(run: RunFolder) -> dict[str, Any] | None:
    """Figs 11–13 of ``racketdyn predict``, and from ``impact.csv`` the contact time and forces
    at the point nearest the face centre, per support and speed."""
    folder = run.predict_dir
    if folder is None:
        return None
    figures = [run.group([(folder / figure.file, "")]) for figure in in_section("impact")]
    figures = [g for g in figures if g is not None]
    impacts = run.impacts()
    if impacts is None:
        if not figures:
            return None
        return {"figures": figures, "centre": None, "rows": [], "glance": []}
    x, y = run.centre(impacts)
    rows = [
        (
            support,
            impacts.case_cell(case),
            fmt(impacts["contact_time_s"][i] * 1e3, ".2f"),
            fmt(impacts["mean_force_n"][i], ".0f"),
            fmt(impacts["peak_force_n"][i], ".0f"),
            fmt(impacts["peak_deflection_m"][i] * 1e3, ".1f"),
            fmt(impacts["stiffness_n_per_m"][i] / 1e3, ".1f"),
        )
        for support, case, _, i in impacts.cases(x, y)
    ]
    i0 = impacts.nearest(np.arange(impacts.support.size), x, y)
    glance = []
    speed, racket_speed = shown_case(run.record(folder), impacts)
    for support in ("pinned", "free"):
        selected = impacts.rows((speed, racket_speed), support)
        if selected.size:
            i = impacts.nearest(selected, x, y)
            glance.append(
                f"face centre, {case_words(speed, racket_speed, support)}: contact time "
                f"{fmt(impacts['contact_time_s'][i] * 1e3, '.2f')} ms, mean force "
                f"{fmt(impacts['mean_force_n'][i], '.0f')} N, rebound ratio "
                f"{fmt(impacts['rebound_ratio'][i], '.3f')}{model_note(impacts.status[i])}"
            )
            break
    return {
        "figures": figures,
        "centre": (f"{impacts['x_m'][i0] * 1e3:.0f}", f"{impacts['y_m'][i0] * 1e3:.0f}"),
        "rows": rows,
        "glance": glance,
    }
