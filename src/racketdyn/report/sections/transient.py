"""The approximate method against the transient simulation (``predict --model both``)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn._display import case_words
from racketdyn.impact.comparison import MODELS_DIFFER
from racketdyn.impact.result import shown_speed_index
from racketdyn.plotting.registry import in_section
from racketdyn.report.folder import RunFolder, number, read_csv, shown_case
from racketdyn.report.formatting import fmt

HOW_TO_RUN = "racketdyn predict --model both --out DIR/predict"


def gather(run: RunFolder) -> dict[str, Any] | None:
    """The engine and integrator (run.json), the comparison figures, and from
    ``comparison.csv`` the difference of the rebound ratios per support and speed."""
    folder = run.model_comparison_dir
    if folder is None:
        return None
    record = run.record(folder)
    engine = record.get("engine")
    integrator = record.get("integrator")
    settings = None
    if isinstance(engine, dict) or isinstance(integrator, dict):
        used = engine.get("used", "–") if isinstance(engine, dict) else "–"
        steps = (
            ", ".join(f"{str(k).replace('_', ' ')} {v}" for k, v in integrator.items())
            if isinstance(integrator, dict)
            else "–"
        )
        settings = (str(used), steps)
    figures = [
        g
        for figure in in_section("transient")
        if (g := run.group([(folder / figure.file, "")])) is not None
    ]
    data: dict[str, Any] = {"settings": settings, "figures": figures, "rows": [], "glance": []}
    rows = read_csv(folder / "comparison.csv", ("x_m", "y_m", "support", "ball_speed_mps"))
    if not rows:
        return data

    def column(name: str) -> NDArray[np.float64]:
        return np.array([number(r, name) for r in rows])

    x, y, speed = column("x_m"), column("y_m"), column("ball_speed_mps")
    support = np.array([r.get("support", "") for r in rows])
    delta = column("difference_rebound_ratio")
    e_approx = column("approx_rebound_ratio")
    e_transient = column("transient_rebound_ratio")
    contact = column("relative_difference_contact_time")
    differ = np.array([str(r.get("models_differ", "")).strip().lower() == "true" for r in rows])
    head = run.head()
    centre_x, centre_y = (
        (head.centre_x_m, head.centre_y_m) if head else (float(np.nanmean(x)), float(np.nanmean(y)))
    )
    speeds = sorted({float(v) for v in speed if math.isfinite(v)})
    chosen, chosen_racket = shown_case(record)
    if chosen not in speeds:
        chosen = speeds[shown_speed_index(speeds)] if speeds else math.nan
        chosen_racket = math.nan
    for name in dict.fromkeys(support.tolist()):
        for value in speeds:
            selected = np.flatnonzero((support == name) & (speed == value))
            if not selected.size:
                continue
            centre = int(
                selected[np.argmin(np.hypot(x[selected] - centre_x, y[selected] - centre_y))]
            )
            finite = selected[np.isfinite(delta[selected])]
            if finite.size:
                worst = int(finite[np.argmax(np.abs(delta[finite]))])
                largest = f"{abs(delta[worst]):.3f}"
                where = f"{x[worst] * 1e3:.0f}, {y[worst] * 1e3:.0f}"
                median = fmt(float(np.median(delta[finite])), "+.3f")
                median_contact = fmt(100 * float(np.nanmedian(contact[finite])), "+.1f")
            else:
                largest, where, median, median_contact = "–", "–", "–", "–"
            data["rows"].append(
                (
                    name,
                    f"{value:g}",
                    largest,
                    where,
                    median,
                    fmt(e_approx[centre], ".3f"),
                    fmt(e_transient[centre], ".3f"),
                    median_contact,
                    str(int(selected.size - finite.size)),
                    str(int(np.sum(differ[selected]))),
                )
            )
            if value == chosen and name == support[0] and finite.size:
                data["glance"].append(
                    "approximate against transient, "
                    + (
                        case_words(value, chosen_racket, name)
                        if math.isfinite(chosen_racket)
                        else f"ball {value:g} m/s, {name}"
                    )
                    + ": rebound ratio at "
                    f"the centre {fmt(e_approx[centre], '.3f')} against "
                    f"{fmt(e_transient[centre], '.3f')}; largest |Δ| {largest} at "
                    f"x, y = {where} mm"
                )
    if np.any(differ):
        data["glance"].append(
            f"{int(np.sum(differ))} of {len(rows)} rows of comparison.csv differ by more than "
            f"{MODELS_DIFFER:g} in rebound ratio between the two models (models_differ): "
            "the transient model is the reference there"
        )
    return data
