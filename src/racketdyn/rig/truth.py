"""An identification held against the virtual rig's truth (issue 12; computed by the step since
issue 23).

Per truth mode: the identified mode paired with it, or why none was — outside the band, on a
node at the accelerometer, dropped by the evidence (``dropped_modes.csv``), or near an
identified mode of another shape.  :func:`compare_with_truth` computes it from the two models;
``identify`` and ``compare`` write it as ``truth_comparison<label>.csv``
(:mod:`racketdyn.workflows.truth`) and the report only reads that file.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from racketdyn.modal.mac import mac
from racketdyn.modal.model import ModalModel

__all__ = [
    "DROPPED_WINDOW",
    "FREQUENCY_WINDOW",
    "MIN_PAIR_MAC",
    "NODE_AT_ACCELEROMETER",
    "TruthMode",
    "compare_with_truth",
]

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


@dataclass(frozen=True)
class TruthMode:
    """One flexible truth mode against the identification.

    Attributes
    ----------
    name : str
        The truth mode's name.
    frequency_hz : float
        The truth's natural frequency, Hz.
    damping_ratio : float
        The truth's damping ratio (fraction of critical).
    identified_frequency_hz, identified_damping_ratio : float
        Of the identified mode paired with it (Hz; fraction of critical); NaN when not found.
    mac : float
        MAC of the pair's shapes at the identified points; NaN when not found or without
        shapes to compare.
    why : str
        Why no identified mode is it; empty when one is.
    """

    name: str
    frequency_hz: float
    damping_ratio: float
    identified_frequency_hz: float = math.nan
    identified_damping_ratio: float = math.nan
    mac: float = math.nan
    why: str = ""

    @property
    def found(self) -> bool:
        """Whether an identified mode is this truth mode."""
        return not self.why

    @property
    def frequency_error(self) -> float:
        """Identified over truth frequency, less one (NaN when not found)."""
        return self.identified_frequency_hz / self.frequency_hz - 1

    @property
    def damping_ratio_error(self) -> float:
        """Identified over truth damping ratio, less one (NaN when not found)."""
        return self.identified_damping_ratio / self.damping_ratio - 1


def compare_with_truth(
    found: ModalModel,
    truth: ModalModel,
    reference_m: Sequence[float] | None,
    dropped: Sequence[tuple[float, str]],
) -> list[TruthMode]:
    """Every flexible truth mode up to twice the band's top, found or with why not.

    Pairs are taken by shape over every identified mode within :data:`FREQUENCY_WINDOW` of a
    truth mode (see :func:`_pairs`); the truth is evaluated at the identified points
    (:meth:`ModalModel.mode_shapes_at`).

    Parameters
    ----------
    found : ModalModel
        The identified model (its ``metadata["band_hz"]`` the band used, Hz).
    truth : ModalModel
        The rig's modal truth.
    reference_m : sequence of float or None
        The accelerometer's location (x, y), m.
    dropped : sequence of (float, str)
        The frequency (Hz) and reason of every mode the identification dropped
        (``dropped_modes.csv``).

    Returns
    -------
    list of TruthMode
        In the truth's order; rigid-body modes and modes above twice the band's top left out.
    """
    band = found.metadata.get("band_hz") or [0.0, np.inf]
    low, high = float(band[0]), float(band[1])
    points = np.asarray(found.locations, dtype=float)
    two_d = points.shape[1] == 2 and not np.isnan(points).any()
    truth_at = truth.mode_shapes_at(points) if two_d else None
    at_reference = (
        truth.mode_shapes_at(np.asarray([tuple(reference_m)[:2]], dtype=float))[0]
        if reference_m is not None and two_d
        else None
    )
    pairs, scores, unlike = _pairs(found, truth, truth_at)
    modes: list[TruthMode] = []
    for k in range(truth.n_modes):
        if truth.kinds[k] == "rigid-body":
            continue
        f, zeta = float(truth.frequency[k]), float(truth.damping_ratio[k])
        mode = TruthMode(truth.names[k], f, zeta)
        if k in pairs:
            j = pairs[k]
            modes.append(
                TruthMode(
                    mode.name,
                    f,
                    zeta,
                    float(found.frequency[j]),
                    float(found.damping_ratio[j]),
                    float(scores[k, j]),
                )
            )
            continue
        why = _why_missed(k, mode, found, scores, unlike, (low, high), truth_at, at_reference)
        if why is None:
            continue  # far above the band: not a miss worth a row
        if not why:
            reasons = [
                (abs(fd / f - 1), reason)
                for fd, reason in dropped
                if abs(fd / f - 1) < DROPPED_WINDOW
            ]
            why = f"dropped: {min(reasons)[1]}" if reasons else "not found: no stable pole near it"
        modes.append(TruthMode(mode.name, f, zeta, why=why))
    return modes


def _why_missed(
    k: int,
    mode: TruthMode,
    found: ModalModel,
    scores: Any,
    unlike: dict[int, int],
    band: tuple[float, float],
    truth_at: Any,
    at_reference: Any,
) -> str | None:
    """Why truth mode ``k`` has no pair: near a mode of another shape, outside the band, on a
    node at the accelerometer; empty when none of these (the dropped list says), None when it
    lies above twice the band's top (no row)."""
    f = mode.frequency_hz
    if k in unlike:
        j = unlike[k]
        return f"not found: the mode identified at {found.frequency[j]:.1f} Hz is near it " + (
            f"but of another shape (MAC {scores[k, j]:.2f})"
            if np.isfinite(scores[k, j])
            else "but nearer another truth mode (no shapes to tell them apart)"
        )
    low, high = band
    if not low <= f <= high:
        return None if f > 2 * high else f"outside the band {low:g}–{high:g} Hz"
    if at_reference is not None and truth_at is not None:
        largest = float(np.max(np.abs(truth_at[:, k])))
        share = abs(float(at_reference[k])) / largest if largest > 0 else 0.0
        if share < NODE_AT_ACCELEROMETER:
            return (
                f"on a node at the accelerometer (its shape there {100 * share:.1f} % "
                "of its largest)"
            )
    return ""


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
