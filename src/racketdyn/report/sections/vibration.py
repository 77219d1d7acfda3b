"""Frame vibration after the impact (Fig. 14, eq 12)."""

from __future__ import annotations

from typing import Any

import numpy as np

from racketdyn.impact.result import STATUS_FROM_TRANSIENT
from racketdyn.plotting.registry import in_section
from racketdyn.report.folder import RunFolder, to_float
from racketdyn.report.formatting import fmt

HOW_TO_RUN = "racketdyn predict --out DIR/predict"


def gather(run: RunFolder) -> dict[str, Any] | None:
    """Fig. 14, and from ``impact.csv`` the vibration energy left in the frame (eq 12): at the
    centre, the largest and smallest over the face, and the rows flagged; the modal model's
    modes of unknown kind, which the prediction took as frame modes (also "At a glance")."""
    folder = run.predict_dir
    if folder is None:
        return None
    figure = run.group([(folder / figure.file, "") for figure in in_section("vibration")])
    impacts = run.impacts()
    ball_mass = to_float(str(run.record(folder).get("ball", {}).get("mass_kg", "")))
    rows = []
    flagged: list[tuple[int, str]] = []
    has_energy = impacts is not None and "vibration_energy_j" in impacts.numbers
    if impacts is not None and has_energy:
        x, y = run.centre(impacts)
        energy = impacts["vibration_energy_j"]
        for support in impacts.supports:
            for speed in impacts.speeds:
                selected = impacts.rows(speed, support)
                if not selected.size:
                    continue
                i = impacts.nearest(selected, x, y)
                # a flagged row's energy is not a valid result (issue 13): never the largest
                valid = np.isfinite(energy[selected]) & (impacts.status[selected] == "ok")
                finite = selected[valid]
                largest = int(finite[np.argmax(energy[finite])]) if finite.size else None
                smallest = int(finite[np.argmin(energy[finite])]) if finite.size else None
                incoming = 0.5 * ball_mass * speed**2
                rows.append(
                    (
                        support,
                        f"{speed:g}",
                        *(
                            (fmt(energy[i], ".3g"), fmt(100 * energy[i] / incoming, ".2g"))
                            if impacts.status[i] == "ok"
                            else (f"flagged: {impacts.status[i]}", "–")
                        ),
                        "–" if largest is None else f"{energy[largest]:.3g}",
                        "–" if largest is None else impacts.where(largest),
                        "–" if smallest is None else f"{energy[smallest]:.3g}",
                        "–" if smallest is None else impacts.where(smallest),
                        str(int(np.sum(impacts.status[selected] != "ok"))),
                    )
                )
        filled = int(np.sum(impacts.status == STATUS_FROM_TRANSIENT))
        bad = (impacts.status != "ok") & (impacts.status != STATUS_FROM_TRANSIENT)
        if np.any(bad):
            reasons, counts = np.unique(impacts.status[bad], return_counts=True)
            flagged = [(int(c), str(r)) for r, c in zip(reasons, counts, strict=True)]
    unknown = run.unknown_modes(folder)
    if figure is None and not has_energy and not unknown:
        return None
    glance = (
        [
            f"modal model: {', '.join(unknown)} of unknown kind, taken as frame "
            f"mode{'s' if len(unknown) > 1 else ''} (see Frame vibration)"
        ]
        if unknown
        else []
    )
    return {
        "figure": figure,
        "energy": has_energy,
        "under_bed": run.shapes_under_bed(folder),
        "rows": rows,
        "flagged": flagged,
        "filled": filled if has_energy else 0,
        "unknown": unknown,
        "glance": glance,
    }
