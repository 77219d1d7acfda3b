"""Contact time of the hammer over the face (Fig. 7)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from racketdyn.plotting.registry import file_of
from racketdyn.report.figures import interactive
from racketdyn.report.folder import RunFolder, number, read_csv
from racketdyn.report.plots import map_spec

HOW_TO_RUN = (
    "racketdyn contact DIR/rig/hammer_free.uff DIR/rig/hammer_hand.uff "
    "--labels free,hand --out DIR/contact"
)


def gather(run: RunFolder) -> dict[str, Any] | None:
    """Fig. 7, and every ``contact_*.csv``: a summary on the strings and the frame, and the
    contact time at each point on the strings for the interactive map."""
    folder = run.first("contact_*.csv") or run.first(file_of("fig7_contact_time"))
    if folder is None:
        return None
    head = run.head()
    labels = [str(v) for v in run.record(folder).get("labels", [])]
    tables = []
    for path in sorted(folder.glob("contact_*.csv")):
        label = path.stem.removeprefix("contact_")
        rows = read_csv(path, ("x_m", "y_m", "contact_time_mean_s"))
        if not rows:
            continue
        xy = np.array([[number(r, "x_m"), number(r, "y_m")] for r in rows])
        mean = np.array([number(r, "contact_time_mean_s") for r in rows])
        spread = np.array([number(r, "contact_time_std_s") for r in rows])
        n = np.array([number(r, "n_averages") for r in rows])
        node = np.array([number(r, "node") for r in rows])
        tables.append((label, xy, mean, spread, n, node))
    if labels and len(labels) == len(tables):
        order = {name: i for i, name in enumerate(labels)}
        tables.sort(key=lambda t: order.get(t[0], len(order)))
    summary = []
    panels: list[dict[str, Any]] = []
    for label, xy, mean, spread, n, node in tables:
        on_bed = head.contains(xy) if head is not None else np.ones(len(xy), bool)
        for where, mask in (("strings", on_bed), ("frame", ~on_bed)):
            values = mean[mask & np.isfinite(mean)] * 1e3
            if values.size:
                summary.append(
                    (
                        label,
                        where,
                        str(values.size),
                        f"{values.min():.2f}",
                        f"{np.median(values):.2f}",
                        f"{values.max():.2f}",
                    )
                )
        keep = np.flatnonzero(on_bed)
        rows_json = [
            [
                round(float(xy[i, 0]) * 1e3, 1),
                round(float(xy[i, 1]) * 1e3, 1),
                round(float(mean[i]) * 1e3, 4) if math.isfinite(mean[i]) else None,
                round(float(spread[i]) * 1e3, 4) if math.isfinite(spread[i]) else None,
                int(n[i]) if math.isfinite(n[i]) else None,
                int(node[i]) if math.isfinite(node[i]) else None,
                "" if math.isfinite(mean[i]) else "no contact time",
            ]
            for i in keep
        ]
        panels.append({"label": label, "rows": rows_json, "xy": xy[keep]})
    figure = run.group([(folder / file_of("fig7_contact_time"), "")])
    plots = {}
    contact_map = None
    if panels and any(p["rows"] for p in panels):
        values = [r[2] for p in panels for r in p["rows"] if r[2] is not None]
        group = {
            "label": "hammer",
            "range": [min(values), max(values)] if values else [0.0, 1.0],
            "panels": [{"label": p["label"], "rows": p["rows"]} for p in panels],
        }
        fields = [
            ("x", "mm", 0),
            ("y", "mm", 0),
            ("contact time", "ms", 2),
            ("spread (std)", "ms", 3),
            ("averages", "", 0),
            ("node", "", 0),
        ]
        every_xy = np.vstack([p["xy"] for p in panels])
        spec = map_spec(head, "map-contact", [group], fields, 2, 0, every_xy, [], "")
        plots["maps"] = [spec]
        contact_map = interactive(
            "map-contact",
            "map",
            "Fig. 7",
            "hammer contact time at each hammer point on the strings; hover for the values",
            "contact_*.csv",
        )
    if not (figure or summary or contact_map):
        return None
    return {"fig7": figure, "summary": summary, "map": contact_map, "plots": plots}
