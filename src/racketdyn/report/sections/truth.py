"""Identified modes against the virtual rig's truth (issue 12).

Shown when the folder holds the rig's ``modal_truth_<support>.json`` and an identification of
that support: per truth mode in the band, its identified frequency, damping ratio and the MAC
of the shapes at the identified points; every truth mode that was not found, with why — outside
the band, on a node at the accelerometer, or dropped by the evidence (``dropped_modes.csv``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from racketdyn.errors import InputError
from racketdyn.modal.mac import mac
from racketdyn.modal.model import ModalModel
from racketdyn.report.folder import RunFolder, damaged, number, read_csv
from racketdyn.report.formatting import fmt

HOW_TO_RUN = (
    "racketdyn rig --out DIR/rig; racketdyn frf DIR/rig/hammer_free.uff --out DIR/frf_free; "
    "racketdyn identify DIR/frf_free/frfs.uff --out DIR/identify"
)
FREQUENCY_WINDOW = 0.03
"""An identified mode within 3 % of a truth mode's frequency may be it (pairs by MAC)."""
MIN_PAIR_MAC = 0.5
"""An identified mode whose shape's MAC with a truth mode's is below this is not that mode,
however near its frequency."""
NODE_AT_ACCELEROMETER = 0.05
"""A truth mode whose shape at the accelerometer is below 5 % of its largest at the points is
on a node there (the identification's weak driving point, :mod:`racketdyn.modal.identify`)."""
DROPPED_WINDOW = 0.01
"""A ``dropped_modes.csv`` row within 1 % of a missed truth mode's frequency is why it went."""


def _model(path: Path) -> ModalModel:
    try:
        return ModalModel.read_json(path)
    except InputError as error:
        raise damaged(path, str(error)) from error


def compare_with_truth(
    found: ModalModel,
    truth: ModalModel,
    reference_m: tuple[float, ...] | None,
    dropped: list[tuple[float, str]],
) -> tuple[list[tuple[str, ...]], list[tuple[str, str, str]]]:
    """Rows of found truth modes and of missed ones (name, frequency, why).

    Parameters
    ----------
    found : ModalModel
        The identified model (its ``metadata["band_hz"]`` the band used).
    truth : ModalModel
        The rig's modal truth.
    reference_m : tuple of float or None
        The accelerometer's location, m.
    dropped : list of (float, str)
        ``dropped_modes.csv``'s frequency (Hz) and reason of every row.
    """
    band = found.metadata.get("band_hz") or [0.0, np.inf]
    low, high = float(band[0]), float(band[1])
    points = np.asarray(found.locations, dtype=float)
    two_d = points.shape[1] == 2 and not np.isnan(points).any()
    truth_at = truth.mode_shapes_at(points) if two_d else None
    at_reference = (
        truth.mode_shapes_at(np.asarray([reference_m[:2]], dtype=float))[0]
        if reference_m is not None and two_d
        else None
    )
    pairs, scores, unlike = _pairs(found, truth, truth_at)
    rows: list[tuple[str, ...]] = []
    missed: list[tuple[str, str, str]] = []
    for k in range(truth.n_modes):
        if truth.kinds[k] == "rigid-body":
            continue
        f, zeta, name = float(truth.frequency[k]), float(truth.damping_ratio[k]), truth.names[k]
        if k in pairs:
            j = pairs[k]
            rows.append(
                (
                    name,
                    fmt(f, ".2f"),
                    fmt(found.frequency[j], ".2f"),
                    fmt(100 * (found.frequency[j] / f - 1), "+.3f"),
                    fmt(100 * zeta, ".3f"),
                    fmt(100 * found.damping_ratio[j], ".3f"),
                    fmt(100 * (found.damping_ratio[j] / zeta - 1), "+.1f"),
                    fmt(scores[k, j], ".3f"),
                )
            )
            continue
        if k in unlike:
            j = unlike[k]
            missed.append(
                (
                    name,
                    fmt(f, ".1f"),
                    f"not found: the mode identified at {found.frequency[j]:.1f} Hz is near it "
                    + (
                        f"but of another shape (MAC {scores[k, j]:.2f})"
                        if np.isfinite(scores[k, j])
                        else "but nearer another truth mode (no shapes to tell them apart)"
                    ),
                )
            )
            continue
        if not low <= f <= high:
            if f > 2 * high:
                continue  # far above the band: not a miss worth a row
            missed.append((name, fmt(f, ".1f"), f"outside the band {low:g}–{high:g} Hz"))
            continue
        if at_reference is not None and truth_at is not None:
            largest = float(np.max(np.abs(truth_at[:, k])))
            share = abs(float(at_reference[k])) / largest if largest > 0 else 0.0
            if share < NODE_AT_ACCELEROMETER:
                missed.append(
                    (
                        name,
                        fmt(f, ".1f"),
                        f"on a node at the accelerometer (its shape there {100 * share:.1f} % "
                        "of its largest)",
                    )
                )
                continue
        reasons = [
            (abs(fd / f - 1), reason) for fd, reason in dropped if abs(fd / f - 1) < DROPPED_WINDOW
        ]
        why = f"dropped: {min(reasons)[1]}" if reasons else "not found: no stable pole near it"
        missed.append((name, fmt(f, ".1f"), why))
    return rows, missed


def _pairs(
    found: ModalModel, truth: ModalModel, truth_at: Any
) -> tuple[dict[int, int], Any, dict[int, int]]:
    """Truth mode → identified mode, the MAC of every pair, and the truth modes whose only
    identified neighbour is of another shape.

    Over every pair within :data:`FREQUENCY_WINDOW`, the assignment of largest summed MAC
    (:func:`scipy.optimize.linear_sum_assignment`; the nearer frequency breaks ties, and alone
    decides without shapes); a pair under :data:`MIN_PAIR_MAC` is no pair."""
    from scipy.optimize import linear_sum_assignment

    flexible = [k for k in range(truth.n_modes) if truth.kinds[k] != "rigid-body"]
    ratio = np.abs(found.frequency[None, :] / truth.frequency[:, None] - 1)
    near = ratio < FREQUENCY_WINDOW
    near[[k for k in range(truth.n_modes) if k not in flexible]] = False
    if truth_at is not None:
        scores = np.asarray(mac(found.mode_shapes, truth_at), dtype=float).T  # (truth, found)
    else:
        scores = np.full(near.shape, np.nan)
    merit = np.where(near, np.nan_to_num(scores, nan=1.0) - ratio, -1e6)
    rows, cols = linear_sum_assignment(merit, maximize=True)
    pairs: dict[int, int] = {}
    unlike: dict[int, int] = {}
    for k, j in zip(rows.tolist(), cols.tolist(), strict=True):
        if not near[k, j]:
            continue
        if truth_at is not None and scores[k, j] < MIN_PAIR_MAC:
            unlike[k] = j
        else:
            pairs[k] = j
    for k in flexible:  # near an identified mode that is another truth mode's
        if k not in pairs and k not in unlike and near[k].any():
            unlike[k] = int(np.argmin(np.where(near[k], ratio[k], np.inf)))
    return pairs, scores, unlike


def glance_line(label: str, rows: list[tuple[str, ...]], missed: list[tuple[str, str, str]]) -> str:
    """The "At a glance" line: modes found of those in the band, and how many lie outside it
    (those are not misses of the identification)."""
    outside = sum(why.startswith("outside the band") for _, _, why in missed)
    in_band = len(rows) + len(missed) - outside
    more = f", {outside} more outside it" if outside else ""
    return f"{label}: {len(rows)} of the rig's {in_band} modes in the band found{more}"


def gather(run: RunFolder) -> dict[str, Any] | None:
    """Every identification whose support has a ``modal_truth_<support>.json`` in the folder."""
    truths = {
        path.stem.removeprefix("modal_truth_"): path
        for folder in run.with_file("modal_truth_*.json")
        for path in sorted(folder.glob("modal_truth_*.json"))
    }
    if not truths:
        return None
    rig = run.first("modal_truth_*.json")
    reference = run.record(rig).get("reference_location_m")
    blocks = []
    glance = []
    for label, folder, suffix in run.identifications:
        support = str(run.record(folder).get("support") or label)
        truth_path = truths.get(label) or truths.get(support)
        model_path = folder / f"modal_model{suffix}.json"
        if truth_path is None or not model_path.is_file():
            continue
        found = _model(model_path)
        dropped_path = folder / f"dropped_modes{suffix}.csv"
        dropped = (
            [
                (number(r, "frequency_hz"), r.get("reason", ""))
                for r in read_csv(dropped_path, ("frequency_hz", "reason"))
            ]
            if dropped_path.is_file()
            else []
        )
        rows, missed = compare_with_truth(
            found, _model(truth_path), None if reference is None else tuple(reference), dropped
        )
        blocks.append(
            {
                "label": label,
                "truth": run.rel(truth_path),
                "identified": run.rel(model_path),
                "rows": rows,
                "missed": missed,
            }
        )
        glance.append(glance_line(label, rows, missed))
    if not blocks:
        return None
    return {"blocks": blocks, "glance": glance}
