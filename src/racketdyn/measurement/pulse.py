"""Contact time of a hammer impact from its force pulse (paper, section 3.1, Fig. 7).

Method: the half-sine-equivalent duration from the full width at half maximum.  The baseline
(median of the pre-trigger samples, or of the record's last quarter) is taken off; the
half-maximum crossings either side of the main peak are located by linear interpolation
between samples; for a half-sine of duration T the width at a level α·F_max is
``T (1 − 2 arcsin(α)/π)``, so ``T = 1.5 × FWHM`` at α = ½.  Half maximum is where the pulse is
steepest, so noise and the sampling grid move the crossings least; the result does not depend
on the amplitude or on an offset.
"""

from __future__ import annotations

import csv
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from racketdyn.measurement.quality import AverageCheck, force_baseline_and_noise, pulse_polarity
from racketdyn.measurement.records import HammerRecords

__all__ = ["HALF_SINE_FWHM_FACTOR", "ContactTimes", "contact_time", "contact_times"]

HALF_SINE_FWHM_FACTOR = 1.5
"""T / FWHM of a half-sine pulse: 1 / (1 − 2 arcsin(½)/π)."""


def contact_time(
    force: NDArray[np.float64], sampling_interval_s: float, pretrigger_s: float = 0.0
) -> float:
    """Half-sine-equivalent contact time of one force record, s (NaN if no clean pulse).

    Parameters
    ----------
    force : ndarray
        One force record, N.
    sampling_interval_s : float
        Sampling period, s.
    pretrigger_s : float
        Pre-trigger time (for the baseline), s.
    """
    pretrigger = round(pretrigger_s / sampling_interval_s)
    baseline, _ = force_baseline_and_noise(force, pretrigger)
    pulse = np.asarray(force, dtype=float) - baseline
    pulse = pulse_polarity(pulse) * pulse  # a channel reading compression as negative
    top = int(np.argmax(pulse))
    half = 0.5 * pulse[top]
    if half <= 0:
        return float("nan")
    left = np.flatnonzero(pulse[: top + 1] < half)
    right = np.flatnonzero(pulse[top:] < half)
    if left.size == 0 or right.size == 0:
        return float("nan")
    i, j = int(left[-1]), top + int(right[0])
    rise = i + (half - pulse[i]) / (pulse[i + 1] - pulse[i])
    fall = j - 1 + (pulse[j - 1] - half) / (pulse[j - 1] - pulse[j])
    return float(HALF_SINE_FWHM_FACTOR * (fall - rise) * sampling_interval_s)


@dataclass(frozen=True, eq=False)
class ContactTimes:
    """Contact time of the hammer at each point: mean and spread over the accepted averages.

    Attributes
    ----------
    nodes : tuple of int
        Hammer point nodes.
    locations : ndarray, shape (n, 2)
        Their (x, y), m.
    mean_s, std_s : ndarray
        Mean and sample standard deviation of the contact time, s (NaN without a clean pulse).
    n_averages : ndarray of int
        Averages that gave a contact time.
    """

    nodes: tuple[int, ...]
    locations: NDArray[np.float64]
    mean_s: NDArray[np.float64]
    std_s: NDArray[np.float64]
    n_averages: NDArray[np.int_]

    def write_csv(self, path: Path) -> None:
        """``node, x_m, y_m, contact_time_mean_s, contact_time_std_s, n_averages``."""
        with Path(path).open("w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(
                ["node", "x_m", "y_m", "contact_time_mean_s", "contact_time_std_s", "n_averages"]
            )
            for row in zip(
                self.nodes, *self.locations.T, self.mean_s, self.std_s, self.n_averages, strict=True
            ):
                writer.writerow([f"{v:.9g}" if isinstance(v, float) else v for v in row])


def contact_times(records: HammerRecords, checks: Sequence[AverageCheck] = ()) -> ContactTimes:
    """Contact time at every hammer point (see :func:`contact_time` for the method).

    Parameters
    ----------
    records : HammerRecords
        The hammer records.
    checks : sequence of AverageCheck
        Quality verdicts (:func:`racketdyn.measurement.frf.estimate_frfs`); rejected averages
        are left out.  Empty: every average is used.
    """
    rejected = {(c.node, c.average) for c in checks if not c.accepted}
    means, stds, counts = [], [], []
    for node, force in zip(records.nodes, records.force, strict=True):
        times = np.array(
            [
                contact_time(row, records.sampling_interval_s, records.pretrigger_s)
                for k, row in enumerate(force)
                if (node, k + 1) not in rejected
            ]
        )
        times = times[np.isfinite(times)]
        counts.append(times.size)
        means.append(float(np.mean(times)) if times.size else float("nan"))
        stds.append(float(np.std(times, ddof=1)) if times.size > 1 else float("nan"))
    return ContactTimes(
        records.nodes, records.locations, np.array(means), np.array(stds), np.array(counts)
    )
