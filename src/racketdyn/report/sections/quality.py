"""Measurement quality: averages by verdict, FRF settings, coherence and the interactive FRF."""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.errors import InputError
from racketdyn.plotting.registry import file_of
from racketdyn.report.figures import interactive
from racketdyn.report.folder import RunFolder, damaged, number, read_csv
from racketdyn.report.formatting import finite, fmt, rounded

HOW_TO_RUN = "racketdyn frf DIR/rig/hammer_free.uff --exp-window 0.1 --out DIR/frf_free"

log = logging.getLogger(__name__)

MAX_FRF_LINES = 4000
"""Frequency lines of the interactive FRF plot; more are thinned."""
SERIES_COLOURS = ("#1f77b4", "#222222", "#d62728", "#2ca02c", "#9467bd", "#8c564b")
SUPPORT_COLOURS = {"free": "#1f77b4", "hand": "#222222", "pinned": "#222222"}
_FRF_UNITS = {"receptance": "m/N", "mobility": "m/(N·s)", "accelerance": "m/(N·s²)"}


def _counts(path: Path) -> dict[str, Any]:
    rows = read_csv(path, ("node", "accepted"))
    reasons: dict[str, int] = {}
    nodes: dict[str, list[int]] = {}
    forces = []
    for row in rows:
        accepted = row.get("accepted") == "1"
        nodes.setdefault(row.get("node", ""), []).append(int(accepted))
        if accepted:
            forces.append(number(row, "peak_force_n"))
        for reason in filter(None, (row.get("reasons") or "").split(";")):
            reasons[reason] = reasons.get(reason, 0) + 1
    return {
        "averages": len(rows),
        "accepted": sum(int(r.get("accepted") == "1") for r in rows),
        "reasons": reasons,
        "points": len(nodes),
        "dead_points": [n for n, v in nodes.items() if not any(v)],
        "forces": np.array(forces, dtype=float),
    }


def gather(run: RunFolder) -> dict[str, Any] | None:
    """Every ``quality.csv`` (averages accepted and rejected by reason), the FRF settings of
    each run.json, and the FRFs of ``frfs.uff`` for the interactive plot."""
    folders = run.frf_dirs
    if not folders:
        return None
    labels = [label for label, _ in folders]
    counts = {label: _counts(folder / "quality.csv") for label, folder in folders}
    reasons = sorted({r for c in counts.values() for r in c["reasons"]})
    rows: list[list[str]] = [
        ["hammer points", *(str(counts[k]["points"]) for k in labels)],
        ["averages", *(str(counts[k]["averages"]) for k in labels)],
        ["accepted", *(str(counts[k]["accepted"]) for k in labels)],
    ]
    rows += [
        [f"rejected: {reason}", *(str(counts[k]["reasons"].get(reason, 0)) for k in labels)]
        for reason in reasons
    ]
    if not reasons:
        rows.append(["rejected (any reason)", *("0" for _ in labels)])
    rows.append(
        [
            "points with every average rejected",
            *(", ".join(counts[k]["dead_points"]) or "none" for k in labels),
        ]
    )
    rows.append(
        [
            "peak hammer force, accepted (N)",
            *(
                f"{np.nanmin(f):.0f}–{np.nanmax(f):.0f}" if (f := counts[k]["forces"]).size else "–"
                for k in labels
            ),
        ]
    )
    settings = []
    for name, key, spec, factor in (
        ("estimator", "estimator", "", 1.0),
        ("exponential window τ (ms)", "exponential_window_s", "g", 1e3),
        ("force window (ms)", "force_window_s", "g", 1e3),
        ("hammer range (N)", "force_range_n", "g", 1.0),
    ):
        values = []
        for _, folder in folders:
            value = run.record(folder).get(key)
            if isinstance(value, int | float) and finite(value):
                value = value * factor
            values.append("not set" if value is None else fmt(value, spec) if spec else value)
        settings.append([name, *map(str, values)])
    glance = [
        f"hammer test ({label}): {c['accepted']} of {c['averages']} averages accepted "
        f"at {c['points']} points"
        for label, c in counts.items()
    ]
    frf = _frf_data(run, folders)
    return {
        "labels": labels,
        "verdicts": rows,
        "settings": settings,
        "coherence": frf["coherence"] if frf else [],
        "coherence_band": frf["band"] if frf else "",
        "frf_plot": frf["figure"] if frf else None,
        "fig2": run.group(
            [(folder / file_of("fig2_frf_frame"), label) for label, folder in folders]
        ),
        "fig3": run.group(
            [(folder / file_of("fig3_frf_string_centre"), label) for label, folder in folders]
        ),
        "glance": glance,
        "plots": {"frf": [frf["spec"]]} if frf else {},
    }


def _frf_data(run: RunFolder, folders: Sequence[tuple[str, Path]]) -> dict[str, Any] | None:
    """Coherence rows and the data of the interactive FRF plot (driving point and string-bed
    centre of every FRF set, with the identified natural frequencies)."""
    from racketdyn.io import read_frf_uff

    head = run.head()
    idents = {label: (folder, suffix) for label, folder, suffix in run.identifications}
    band = None
    for _, folder, _ in run.identifications:
        value = run.record(folder).get("band_hz")
        if isinstance(value, list) and len(value) == 2:
            band = (float(value[0]), float(value[1]))
            break
    views: dict[str, list[dict[str, Any]]] = {"frame": [], "centre": []}
    modes: list[dict[str, Any]] = []
    coherence_rows = []
    frequency: NDArray[np.float64] | None = None
    unit = ""
    for n, (label, folder) in enumerate(folders):
        path = folder / "frfs.uff"
        if not path.is_file():
            continue
        try:
            frfs = read_frf_uff(path)
        except (InputError, OSError, ValueError) as error:
            raise damaged(path, f"not read ({str(error).removeprefix(f'{path}: ')})") from None
        keep = frfs.frequency > 0
        if frequency is None:
            frequency = frfs.frequency[keep]
            unit = _FRF_UNITS[frfs.frf_type]
        elif frfs.frequency[keep].shape != frequency.shape or not np.allclose(
            frfs.frequency[keep], frequency
        ):
            log.warning("%s: frequency lines differ from the first FRF set; left out", path)
            continue
        colour = SUPPORT_COLOURS.get(label, SERIES_COLOURS[n % len(SERIES_COLOURS)])
        frame = frfs.driving_point if frfs.driving_point is not None else 0
        centre_xy = (
            np.array([head.centre_x_m, head.centre_y_m])
            if head is not None
            else frfs.locations.mean(axis=0)
        )
        centre = int(np.argmin(np.linalg.norm(frfs.locations - centre_xy, axis=1)))
        for view, index in (("frame", frame), ("centre", centre)):
            coherence = None if frfs.coherence is None else frfs.coherence[index, keep]
            views[view].append(
                {
                    "label": f"{label}, node {frfs.nodes[index]}",
                    "colour": colour,
                    "mag": rounded(np.abs(frfs.values[index, keep])),
                    "coh": None if coherence is None else rounded(coherence, 3),
                }
            )
        if frfs.coherence is not None:
            lines = frequency >= (band[0] if band else 0.0)
            lines &= frequency <= (band[1] if band else np.inf)
            per_point = np.median(frfs.coherence[:, keep][:, lines], axis=1)
            worst = int(np.argmin(per_point))
            coherence_rows.append(
                [
                    label,
                    f"{np.median(per_point):.3f}",
                    f"{per_point[frame]:.3f}",
                    f"{per_point[worst]:.3f} (node {frfs.nodes[worst]})",
                ]
            )
        if label in idents:
            ident_folder, suffix = idents[label]
            rows = read_csv(ident_folder / f"modes{suffix}.csv", ("frequency_hz",))
            modes += [
                {
                    "f": number(r, "frequency_hz"),
                    "label": f"{r.get('name', '')} ({label})",
                    "colour": colour,
                }
                for r in rows
                if finite(number(r, "frequency_hz"))
            ]
    if frequency is None or not views["frame"]:
        return None
    step = max(1, math.ceil(frequency.size / MAX_FRF_LINES))
    if step > 1:
        for series in views["frame"] + views["centre"]:
            series["mag"] = series["mag"][::step]
            series["coh"] = None if series["coh"] is None else series["coh"][::step]
    spec = {
        "id": "frf-plot",
        "f": rounded(frequency[::step], 6),
        "unit": unit,
        "views": [
            {"label": "driving point on the frame (Fig. 2)", "series": views["frame"]},
            {"label": "string-bed centre (Fig. 3)", "series": views["centre"]},
        ],
        "modes": modes,
    }
    figure = interactive(
        "frf-plot",
        "frf",
        "Figs 2–3",
        "interactive FRF magnitude |H| (log scale) and coherence, free against hand-held, at "
        "the driving point (Fig. 2) or the string-bed centre (Fig. 3); dashed lines mark the "
        "identified natural frequencies",
        "frfs.uff",
    )
    return {
        "spec": spec,
        "figure": figure,
        "coherence": coherence_rows,
        "band": f"{band[0]:g}–{band[1]:g} Hz" if band else "all lines above 0 Hz",
    }
