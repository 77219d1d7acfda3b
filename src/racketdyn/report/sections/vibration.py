"""Frame vibration after the impact (Fig. 14, eq 12)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.impact.approximate import approach_energy
from racketdyn.impact.result import STATUS_FROM_TRANSIENT, extreme_row, is_valid, model_note
from racketdyn.plotting.registry import in_section
from racketdyn.report.folder import Impacts, RunFolder, to_float
from racketdyn.report.formatting import fmt

HOW_TO_RUN = "racketdyn predict --out DIR/predict"


def gather(run: RunFolder) -> dict[str, Any] | None:
    """Fig. 14, and from ``impact.csv`` the vibration energy left in the frame (eq 12): at the
    centre, the largest and smallest over the face (every valid row, those filled from the
    transient model marked so), and the rows flagged; the modal model's modes of unknown kind,
    which the prediction took as frame modes (also "At a glance")."""
    folder = run.predict_dir
    if folder is None:
        return None
    figure = run.group([(folder / figure.file, "") for figure in in_section("vibration")])
    impacts = run.impacts()
    ball_mass = to_float(str(run.record(folder).get("ball", {}).get("mass_kg", "")))
    rows: list[tuple[str, ...]] = []
    flagged: list[tuple[int, str]] = []
    filled = 0
    has_energy = impacts is not None and "vibration_energy_j" in impacts.numbers
    if impacts is not None and has_energy:
        rows = _rows(run, impacts, ball_mass)
        filled = int(np.sum(impacts.status == STATUS_FROM_TRANSIENT))
        bad = ~is_valid(impacts.status)
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
        "filled": filled,
        "unknown": unknown,
        "glance": glance,
        "share_of": SHARE_OF,
    }


SHARE_OF = "of the approach energy"
"""What the vibration's share is of: the approach energy ½ μ V² of ball and racket
(:func:`~racketdyn.impact.approximate.approach_energy`), as the 30 % validity rule's."""


def _rows(run: RunFolder, impacts: Impacts, ball_mass: float) -> list[tuple[str, ...]]:
    """One row per support and speed: the energy at the centre and its share of the approach
    energy, the largest and the smallest over the face and where, the rows flagged."""
    x, y = run.centre(impacts)
    energy, status = impacts["vibration_energy_j"], impacts.status
    approach = approach_energy(
        ball_mass,
        impacts["reduced_mass_kg"],
        impacts["ball_speed_mps"] + np.nan_to_num(impacts["racket_speed_mps"]),
    )
    rows: list[tuple[str, ...]] = []
    for support, case, selected, i in impacts.cases(x, y):
        # a flagged row's energy is not a valid result (issue 13): never the largest
        largest = extreme_row(energy, status, selected)
        smallest = extreme_row(energy, status, selected, smallest=True)
        rows.append(
            (
                support,
                impacts.case_cell(case),
                *(
                    (
                        fmt(energy[i], ".3g") + model_note(status[i]),
                        fmt(100 * energy[i] / approach[i], ".2g"),
                    )
                    if is_valid(status[i])
                    else (f"flagged: {status[i]}", "–")
                ),
                *_at(impacts, energy, largest),
                *_at(impacts, energy, smallest),
                str(int(np.sum(~is_valid(status[selected])))),
            )
        )
    return rows


def _at(impacts: Impacts, energy: NDArray[np.float64], row: int | None) -> tuple[str, str]:
    """A row's energy (marked when filled from the transient model) and where; dashes for
    none."""
    if row is None:
        return "–", "–"
    return f"{energy[row]:.3g}{model_note(impacts.status[row])}", impacts.where(row)
