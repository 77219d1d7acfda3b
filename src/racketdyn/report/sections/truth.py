"""Identified modes against the virtual rig's truth (issue 12).

Shown for every identification whose step wrote ``truth_comparison<label>.csv`` (its FRFs came
from the virtual rig: :mod:`racketdyn.workflows.truth`, computed by
:func:`racketdyn.rig.truth.compare_with_truth`): per truth mode in the band, its identified
frequency, damping ratio and the MAC of the shapes at the identified points; every truth mode
that was not found, with why.  The section reads that file and evaluates no model.  An
identification without the file, in a folder that holds the rig's ``modal_truth_<support>.json``
of its support (an older racketdyn wrote no such file), gets one line saying so: recomputing it
here would put the rig's model back into the page (issue 23).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from racketdyn.report.folder import RunFolder, number, read_csv
from racketdyn.report.formatting import fmt
from racketdyn.workflows.truth import TRUTH_COMPARISON, TRUTH_FILES

HOW_TO_RUN = (
    "racketdyn rig --out DIR/rig; racketdyn frf DIR/rig/hammer_free.uff --out DIR/frf_free; "
    "racketdyn identify DIR/frf_free/frfs.uff --out DIR/identify"
)
REQUIRED = ("truth_mode", "truth_frequency_hz", "found", "why")
"""Columns of ``truth_comparison<label>.csv`` the section cannot do without."""


def read_truth_comparison(
    path: Path,
) -> tuple[list[tuple[str, ...]], list[tuple[str, str, str]]]:
    """The table's rows of found truth modes and of missed ones (name, frequency, why).

    Parameters
    ----------
    path : Path
        ``truth_comparison<label>.csv`` (:data:`racketdyn.workflows.truth.TRUTH_COLUMNS`).
    """
    rows: list[tuple[str, ...]] = []
    missed: list[tuple[str, str, str]] = []
    for row in read_csv(path, REQUIRED):
        name, frequency = row["truth_mode"] or "", number(row, "truth_frequency_hz")
        if row["found"] != "true":
            missed.append((name, fmt(frequency, ".1f"), row["why"] or ""))
            continue
        rows.append(
            (
                name,
                fmt(frequency, ".2f"),
                fmt(number(row, "identified_frequency_hz"), ".2f"),
                fmt(100 * number(row, "frequency_error"), "+.3f"),
                fmt(100 * number(row, "truth_damping_ratio"), ".3f"),
                fmt(100 * number(row, "identified_damping_ratio"), ".3f"),
                fmt(100 * number(row, "damping_ratio_error"), "+.1f"),
                fmt(number(row, "mac"), ".3f"),
            )
        )
    return rows, missed


def glance_line(label: str, rows: list[tuple[str, ...]], missed: list[tuple[str, str, str]]) -> str:
    """The "At a glance" line: modes found of those in the band, and how many lie outside it
    (those are not misses of the identification)."""
    outside = sum(why.startswith("outside the band") for _, _, why in missed)
    in_band = len(rows) + len(missed) - outside
    more = f", {outside} more outside it" if outside else ""
    return f"{label}: {len(rows)} of the rig's {in_band} modes in the band found{more}"


def gather(run: RunFolder) -> dict[str, Any] | None:
    """Every identification held against the rig's truth by its step, and a line for each one
    that was not where the folder holds the truth of its support."""
    truths = {
        path.stem.removeprefix("modal_truth_"): path
        for folder in run.with_file("modal_truth_*.json")
        for path in sorted(folder.glob("modal_truth_*.json"))
    }
    blocks = []
    glance = []
    notes = []
    for label, folder, suffix in run.identifications:
        model_path = folder / f"modal_model{suffix}.json"
        table = folder / TRUTH_COMPARISON.format(label=suffix)
        record = run.record(folder)
        if not table.is_file():
            truth_path = truths.get(label) or truths.get(str(record.get("support") or label))
            if truth_path is not None and model_path.is_file():
                notes.append(
                    f"{label}: no {run.rel(table)} beside {run.rel(model_path)} (identified by "
                    "an older racketdyn, or from FRFs that are not this rig's test as it is "
                    f"now): identify again to hold it against the rig's truth "
                    f"{run.rel(truth_path)}"
                )
            continue
        rows, missed = read_truth_comparison(table)
        truth_file = (record.get(TRUTH_FILES) or {}).get(table.name)
        blocks.append(
            {
                "label": label,
                "truth": run.rel(Path(truth_file)) if truth_file else "(not recorded)",
                "identified": run.rel(model_path),
                "rows": rows,
                "missed": missed,
            }
        )
        glance.append(glance_line(label, rows, missed))
    if not blocks and not notes:
        return None
    return {"blocks": blocks, "glance": glance, "notes": notes}
