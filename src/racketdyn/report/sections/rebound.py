"""Rebound ratio over the face and the sweet spots (Fig. 15 and the interactive map)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn._display import case_words
from racketdyn.impact.result import extreme_row, model_note, shown_speed_index
from racketdyn.plotting.registry import file_of
from racketdyn.racket import HeadEllipse
from racketdyn.report.figures import Figure, FigureGroup, interactive
from racketdyn.report.folder import Case, Impacts, RunFolder, read_csv, shown_case
from racketdyn.report.formatting import fmt
from racketdyn.report.plots import map_spec

HOW_TO_RUN = "racketdyn predict --out DIR/predict"

MAX_MAP_POINTS = 2500
"""Points per speed and support in the interactive map; more are thinned."""
MAX_MAP_SPEEDS = 7
"""Cases (ball and racket speed) in the interactive map; more are thinned (the shown case is
kept)."""
FIELDS = [
    ("x", "mm", 0),
    ("y", "mm", 0),
    ("rebound ratio", "", 3),
    ("contact time", "ms", 2),
    ("rebound speed", "m/s", 1),
    ("vibration energy", "J", 3),
    ("reduced mass", "g", 0),
]
"""Columns of a point of the map: name, unit, decimals."""


def gather(run: RunFolder) -> dict[str, Any] | None:
    """Fig. 15 (predicted and with the identified models), the face maps, and from
    ``impact.csv`` the interactive map and the sweet spots per support and speed.

    The steps: the figures (:func:`_figures`), the conditions of the impacts
    (:func:`_conditions`), the cases of the map (:func:`_map_cases`), each case's panels
    and sweet spots (:func:`_case_group`), the map (:func:`_map`), the spots named on the
    axis (:func:`_axis_spots`), the note on negative rebound ratios and the bands."""
    folder = run.predict_dir
    compare = run.first(file_of("fig15_identified"))
    if folder is None and compare is None:
        return None
    fig15, face_maps = _figures(run, folder, compare)
    data: dict[str, Any] = {
        "fig15": fig15,
        "face_maps": face_maps,
        "map": None,
        "sweet": [],
        "spots": [],
        "glance": [],
        "plots": {},
        "conditions": "racket at rest",
    }
    impacts = run.impacts()
    if impacts is None:
        return data if (fig15 or face_maps) else None
    data["conditions"] = _conditions(impacts)
    cop = run.derived().get("centre_of_percussion_m")
    nodes = run.first_mode_nodes()
    head = run.head()
    marks = _marks(cop, nodes, head)
    cases, chosen = _map_cases(run, folder, impacts)
    groups: list[dict[str, Any]] = []
    all_xy: list[NDArray[np.float64]] = []
    sweet: list[tuple[int, _SweetRow]] = []
    thinned = False
    for n, case in enumerate(cases):
        group, xy, rows, thin = _case_group(run, impacts, case)
        groups.append(group)
        all_xy += xy
        sweet += [(n, row) for row, _ in rows]
        thinned = thinned or thin
        if case == chosen:
            data["glance"] += [
                f"highest rebound ratio, {case_words(*chosen, support)}: "
                f"{impacts['rebound_ratio'][best]:.3f} at "
                f"x = {impacts['x_m'][best] * 1e3:.0f} mm, "
                f"y = {impacts['y_m'][best] * 1e3:.0f} mm{model_note(impacts.status[best])}"
                for (support, *_), best in rows
                if support == "pinned"
            ]
    spec = map_spec(
        head,
        "map-rebound",
        groups,
        FIELDS,
        2,
        cases.index(chosen),
        np.vstack(all_xy),
        marks,
        "max",
    )
    data["plots"] = {"maps": [spec]}
    data["map"] = _map(thinned)
    order = {support: n for n, support in enumerate(impacts.supports)}
    sweet.sort(key=lambda item: (order[item[1][0]], item[0]))
    data["sweet"] = [row for _, row in sweet]
    data["spots"] = _axis_spots(cop, nodes)
    data["negative"] = _negative_note(impacts, run.record(folder))
    data["glance"] += _bands(run, impacts, chosen)
    return data


def _figures(
    run: RunFolder, folder: Path | None, compare: Path | None
) -> tuple[FigureGroup | None, FigureGroup | None]:
    """Fig. 15's group (predicted, and with the identified models) and the face maps'."""
    fig15 = run.group(
        [
            (path, "")
            for path in (
                folder / file_of("fig15_rebound_along_axis") if folder else None,
                compare / file_of("fig15_identified") if compare else None,
            )
            if path is not None
        ]
    )
    face_maps = run.group([(folder / file_of("face_maps"), "")]) if folder is not None else None
    return fig15, face_maps


def _conditions(impacts: Impacts) -> str:
    """The racket's motion in the impacts: at rest, or its speeds at the impact point."""
    racket_speeds = sorted(
        {float(v) for v in impacts["racket_speed_mps"] if math.isfinite(float(v))}
    )
    return (
        "racket at rest"
        if not any(racket_speeds)
        else "racket moving at "
        + ", ".join(f"{v:g}" for v in racket_speeds)
        + " m/s at the impact point (its speed paired with each ball speed as in impact.csv; "
        "the rebound ratio relative to the racket)"
    )


def _marks(
    cop: Any, nodes: dict[str, list[float]], head: HeadEllipse | None
) -> list[dict[str, Any]]:
    """The map's lines on the axis: the centre of percussion ``cop`` (m) and the first-mode
    ``nodes`` of each support on the head (m)."""
    marks = []
    if isinstance(cop, int | float):
        marks.append({"x": round(cop * 1e3, 1), "label": "CoP"})
    for support, values in nodes.items():
        for node in values:
            if head is None or abs(node - head.centre_x_m) < head.half_length_m:
                marks.append({"x": round(node * 1e3, 1), "label": f"node ({support})"})
    return marks


def _map_cases(run: RunFolder, folder: Path | None, impacts: Impacts) -> tuple[list[Case], Case]:
    """The map's cases, (ball speed, racket speed) in m/s (at most :data:`MAX_MAP_SPEEDS`, the
    shown one kept), and the shown case."""
    cases = impacts.case_list
    chosen = shown_case(run.record(folder), impacts)
    if chosen not in cases:
        speeds = [ball for ball, _ in cases]
        chosen = cases[shown_speed_index(speeds)]
    if len(cases) > MAX_MAP_SPEEDS:
        picks = np.unique(np.linspace(0, len(cases) - 1, MAX_MAP_SPEEDS).round().astype(int))
        cases = sorted({cases[i] for i in picks} | {chosen})
    return cases, chosen


_SweetRow = tuple[str, str, str, str, str, str]
"""A row of the sweet-spot table: support, speed, best rebound ratio and where, the centre's,
and the quietest point."""


def _case_group(
    run: RunFolder, impacts: Impacts, case: Case
) -> tuple[dict[str, Any], list[NDArray[np.float64]], list[tuple[_SweetRow, int]], bool]:
    """One case of the map (ball speed, racket speed; m/s): its group of panels (one per
    support), the points drawn, each support's sweet-spot row with its best row of
    ``impacts``, and whether points were thinned."""
    panels: list[dict[str, Any]] = []
    all_xy: list[NDArray[np.float64]] = []
    sweet: list[tuple[_SweetRow, int]] = []
    thinned = False
    for support in impacts.supports:
        selected = impacts.rows(case, support)
        if selected.size > MAX_MAP_POINTS:
            selected = selected[:: math.ceil(selected.size / MAX_MAP_POINTS)]
            thinned = True
        panels.append({"label": support, "rows": _panel_rows(impacts, selected)})
        all_xy.append(np.column_stack([impacts["x_m"][selected], impacts["y_m"][selected]]))
        found = _sweet_row(run, impacts, selected, (support, case))
        if found is not None:
            sweet.append(found)
    values = [r[2] for p in panels for r in p["rows"] if r[2] is not None]
    group = {
        "label": case_words(*case) if impacts.moving else f"{case[0]:g} m/s",
        "range": [min(values), max(values)] if values else [0.0, 1.0],
        "panels": panels,
    }
    return group, all_xy, sweet, thinned


def _panel_rows(impacts: Impacts, selected: NDArray[np.intp]) -> list[list[Any]]:
    """The map's points of ``selected`` rows: x, y (mm), the :data:`FIELDS` numbers (None if
    not finite) and the status (empty if ok)."""
    e = impacts["rebound_ratio"]
    return [
        [
            round(float(impacts["x_m"][i]) * 1e3, 1),
            round(float(impacts["y_m"][i]) * 1e3, 1),
            *(
                None if not math.isfinite(v) else float(f"{v:.5g}")
                for v in (
                    e[i],
                    impacts["contact_time_s"][i] * 1e3,
                    impacts["rebound_speed_mps"][i],
                    impacts["vibration_energy_j"][i],
                    impacts["reduced_mass_kg"][i] * 1e3,
                )
            ),
            "" if impacts.status[i] == "ok" else str(impacts.status[i]),
        ]
        for i in selected
    ]


def _sweet_row(
    run: RunFolder, impacts: Impacts, selected: NDArray[np.intp], case: tuple[str, Case]
) -> tuple[_SweetRow, int] | None:
    """The sweet-spot row of one support and case (ball speed, racket speed) and its best row:
    the highest rebound ratio of the valid rows of ``selected`` (the approximate method's and
    those filled from the transient model, marked so) and where, the centre's (nearest of
    ``selected``), and the quietest valid row; None when no row is valid."""
    support, speeds = case
    e, status = impacts["rebound_ratio"], impacts.status
    best = extreme_row(e, status, selected)
    if best is None:
        return None
    x, y = run.centre(impacts)
    centre = impacts.nearest(selected, x, y)
    quiet = extreme_row(impacts["vibration_energy_j"], status, selected, smallest=True)
    row = (
        support,
        impacts.case_cell(speeds),
        f"{e[best]:.3f}{model_note(status[best])}",
        impacts.where(best),
        fmt(e[centre], ".3f") + model_note(status[centre]),
        "–" if quiet is None else impacts.where(quiet) + model_note(status[quiet]),
    )
    return row, best


def _map(thinned: bool) -> Figure:
    """The interactive map's figure (points ``thinned`` for the page or not)."""
    notes = " (points thinned for the page)" if thinned else ""
    return interactive(
        "map-rebound",
        "map",
        None,
        f"rebound ratio over the face from impact.csv{notes}, one panel per support, "
        "one shared colour scale per speed; hover a point for x, y, rebound ratio, contact "
        "time and more; the ringed point is the highest rebound ratio, dashed lines the "
        "centre of percussion (CoP) and the first-mode nodes; the paper shows the long axis "
        "only (Fig. 15)",
        "impact.csv",
    )


def _axis_spots(cop: Any, nodes: dict[str, list[float]]) -> list[str]:
    """The spots on the axis in words: the centre of percussion ``cop`` (m), the least shock
    to the hand, and each support's first-mode ``nodes`` (m), the least vibration."""
    spots = []
    if isinstance(cop, int | float):
        spots.append(
            f"centre of percussion (pivot at the grip): x = {cop * 1e3:.0f} mm — the least "
            "shock to the hand"
        )
    for support, values in nodes.items():
        spots.append(
            f"first-mode nodes on the axis, {support}: "
            + ", ".join(f"x = {v * 1e3:.0f} mm" for v in values)
            + " — the least vibration"
        )
    return spots


def _bands(run: RunFolder, impacts: Impacts, case: Case) -> list[str]:
    """With ``predict --uncertainty``: the centre's rebound ratio with its 90 % band, one
    sentence per support at the shown case (ball speed, racket speed; m/s), and the dominant
    input at each point of ``sensitivity.csv``."""
    if "rebound_ratio_p05" not in impacts.numbers:
        return []
    folder = run.predict_dir
    record = run.record(folder).get("uncertainty") or {}
    spread = ", ".join(record.get("inputs", {})) if isinstance(record, dict) else ""
    x, y = run.centre(impacts)
    lines = []
    for support in impacts.supports:
        rows = impacts.rows(case, support)
        if not rows.size:
            continue
        i = impacts.nearest(rows, x, y)
        e, low, high = (
            impacts[k][i] for k in ("rebound_ratio", "rebound_ratio_p05", "rebound_ratio_p95")
        )
        band = (
            f"({low:.3f}–{high:.3f}, 90 %)"
            if math.isfinite(low) and math.isfinite(high)
            else "(no band: under 90 % of the samples valid)"
        )
        lines.append(
            f"rebound ratio at the centre, {case_words(*case, support)}: "
            f"{fmt(e, '.3f')} {band}" + (f" — uncertain: {spread}" if spread else "")
        )
    sensitivity = folder / "sensitivity.csv" if folder is not None else None
    if sensitivity is not None and sensitivity.is_file():
        lines.append(_dominant(sensitivity))
    return lines


def _dominant(path: Path) -> str:
    """The input with the largest total Sobol' index of the rebound ratio at each point, the
    inputs it is not told from and why a point has none, as ``sensitivity.csv`` says them
    (:meth:`racketdyn.impact.uncertainty.Sensitivity.rows`; a file of an earlier racketdyn,
    without those columns: the largest total index alone)."""
    parts: dict[str, str] = {}
    best: dict[str, float] = {}
    rivals: dict[str, list[str]] = {}
    for row in read_csv(path, ("point", "output", "input", "total_order")):
        if row["output"] != "rebound_ratio":
            continue
        label, total = row["point"], float(row["total_order"] or "nan")
        if row.get("note") or (row.get("note") is None and not math.isfinite(total)):
            parts[label] = f"{label} not known ({row.get('note') or 'samples beyond the method'})"
        elif row.get("dominant") == "True" or (
            row.get("dominant") is None and total > best.get(label, -math.inf)
        ):
            parts[label], best[label] = f"{label} {row['input']}", total
        if row.get("not_told_from_dominant") == "True":
            rivals.setdefault(label, []).append(row["input"])
    return "dominant input of the rebound ratio (largest total Sobol' index, sensitivity.csv): " + (
        "; ".join(
            text + (f", not told from {', '.join(rivals[label])}" if label in rivals else "")
            for label, text in parts.items()
        )
    )


def _rigid_rebound_ratio(impacts: Impacts, record: dict[str, Any]) -> NDArray[np.float64]:
    """Rebound ratio of each row on a rigid racket, (e_BG − μ)/(1 + μ) with μ = m_B/M_r (eq 4,
    no vibration): negative only where the racket recoils too much to send the ball back.
    e_BG is the run's (a table at the row's relative speed); NaN where the run.json does not
    say (an old folder)."""
    ball = record.get("ball") if isinstance(record.get("ball"), dict) else {}
    mass = ball.get("mass_kg") if isinstance(ball, dict) else None
    law = ball.get("e_bg_law") if isinstance(ball, dict) else None
    table = law.get("table") if isinstance(law, dict) else None
    e_bg: Any = ball.get("e_bg") if isinstance(ball, dict) else None
    relative = impacts["ball_speed_mps"] + np.nan_to_num(impacts["racket_speed_mps"])
    if isinstance(table, list) and table:
        rows = np.asarray(table, dtype=float)
        e_bg = np.interp(relative, rows[:, 0], rows[:, 1])
    if not isinstance(mass, int | float) or e_bg is None:
        return np.full(relative.shape, np.nan)
    mu = float(mass) / impacts["reduced_mass_kg"]
    return np.asarray((np.asarray(e_bg, dtype=float) - mu) / (1.0 + mu), dtype=float)


def _negative_note(impacts: Impacts, record: dict[str, Any] | None = None) -> str | None:
    """What negative rebound ratios mean, where the run has any (issue 13): recoil (a rigid
    racket would not send the ball back either) or the approximate method's vibration charge
    (a rigid racket would)."""
    e = impacts["rebound_ratio"]
    negative = np.isfinite(e) & (e < 0) & (impacts.status == "ok")
    if not negative.any():
        return None
    x_mm = impacts["x_m"] * 1e3

    y_mm = impacts["y_m"] * 1e3

    def span(rows: NDArray[np.bool_]) -> str:
        return (
            f"x from {x_mm[rows].min():.0f} to {x_mm[rows].max():.0f} mm, "
            f"y from {y_mm[rows].min():.0f} to {y_mm[rows].max():.0f} mm"
        )

    rigid = _rigid_rebound_ratio(impacts, record or {})
    vibration = negative & (rigid >= 0)
    recoil = negative & ~vibration
    words = [f"{int(negative.sum())} of {e.size} impacts have a negative rebound ratio."]
    if recoil.any():
        words.append(
            f"{int(recoil.sum())} of them ({span(recoil)}) are recoil: the racket's reduced "
            "mass there is small, so even a rigid racket would not send the ball back "
            "((e_BG − m_B/M_r)/(1 + m_B/M_r) < 0); the ball carries on forward, slower."
        )
    if vibration.any():
        words.append(
            f"{int(vibration.sum())} of them ({span(vibration)}) are not recoil: a rigid "
            "racket would send the ball back there ((e_BG − m_B/M_r)/(1 + m_B/M_r) > 0); the "
            "frame's vibration takes the difference."
        )
    words.append(
        "Near the frame the ball also reaches the hoop, which neither model includes. Where "
        "the approximate method and the transient simulation disagree, trust the transient "
        "simulation (racketdyn predict --model both compares them in comparison.csv)."
    )
    return " ".join(words)
