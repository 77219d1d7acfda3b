"""Per-average quality checks of hammer records: each average is accepted or rejected with reasons.

Checks (each named in the reasons it gives):

``non-finite``
    NaN or inf in either channel.
``empty``
    No force pulse above the noise (peak under 6 × the noise rms).
``force overload`` / ``response overload``
    Clipping: three samples or more at the channel's extreme value (within 1e-6 of it), the
    flat top an overloaded amplifier or converter leaves.  A known overload level (the
    hammer's range) also rejects any force reaching it.
``double hit``
    A second force pulse: more than one peak standing out of the force record by more than the
    detection level (``max(5 % of the peak, 6 × noise rms)``), whether the second pulse follows
    after the first has ended or rides on its tail.  Found with ``scipy.signal.find_peaks``
    (prominence), so a second hit 0.5–4 ms after the first is caught on frame and string
    pulses alike.
``trigger``
    The pulse does not start within ``trigger_tolerance_s`` of the trigger time (t = 0), or it
    is cut by the end of the record.

The noise level comes from the pre-trigger samples when there are at least 8, else from the
last quarter of the record (robust estimate: 1.4826 × median absolute deviation).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.signal import find_peaks

__all__ = ["AverageCheck", "QualitySettings", "check_average", "force_baseline_and_noise"]


@dataclass(frozen=True)
class QualitySettings:
    """Thresholds of the quality checks.

    Parameters
    ----------
    relative_level : float
        Detection level of a pulse as a fraction of the force peak.
    noise_factor : float
        Detection level as a multiple of the force noise rms (whichever is higher).
    trigger_tolerance_s : float
        Largest allowed distance between the pulse start and the trigger time, s.
    overload_level_n : float or None
        Hammer force range, N: a force reaching it is an overload.
    """

    relative_level: float = 0.05
    noise_factor: float = 6.0
    trigger_tolerance_s: float = 1.0e-3
    overload_level_n: float | None = None


@dataclass(frozen=True)
class AverageCheck:
    """The verdict on one average of one hammer point."""

    node: int
    average: int
    accepted: bool
    reasons: tuple[str, ...]
    peak_force_n: float


def force_baseline_and_noise(
    force: NDArray[np.float64], pretrigger_samples: int
) -> tuple[float, float]:
    """Offset (N) and noise rms (N) of a force record, robust to the pulse."""
    quiet = (
        force[:pretrigger_samples] if pretrigger_samples >= 8 else force[-max(force.size // 4, 8) :]
    )
    baseline = float(np.median(quiet))
    noise = float(1.4826 * np.median(np.abs(quiet - baseline)))
    return baseline, noise


def _clipped(signal: NDArray[np.float64]) -> bool:
    extreme = np.max(np.abs(signal))
    if extreme == 0:
        return False
    at_rail = np.abs(np.abs(signal) - extreme) <= 1e-6 * extreme
    return bool(np.count_nonzero(at_rail) >= 3)


def check_average(
    node: int,
    average: int,
    force: NDArray[np.float64],
    response: NDArray[np.float64],
    sampling_interval_s: float,
    pretrigger_s: float,
    settings: QualitySettings,
) -> AverageCheck:
    """Run every check on one average; see the module docstring for what each check means."""
    reasons: list[str] = []
    if not (np.all(np.isfinite(force)) and np.all(np.isfinite(response))):
        return AverageCheck(node, average, False, ("non-finite",), float("nan"))
    pretrigger = round(pretrigger_s / sampling_interval_s)
    baseline, noise = force_baseline_and_noise(force, pretrigger)
    pulse = force - baseline
    peak = float(np.max(pulse))
    level = max(settings.relative_level * peak, settings.noise_factor * noise)
    if peak <= settings.noise_factor * noise or peak <= 0:
        return AverageCheck(node, average, False, ("empty",), peak)
    if _clipped(force) or (
        settings.overload_level_n is not None and np.max(np.abs(force)) >= settings.overload_level_n
    ):
        reasons.append("force overload")
    if _clipped(response):
        reasons.append("response overload")
    peaks, _ = find_peaks(pulse, prominence=level)
    if peaks.size > 1:
        reasons.append("double hit")
    above = np.flatnonzero(pulse > level)
    start_time = (above[0] - pretrigger) * sampling_interval_s
    if abs(start_time) > settings.trigger_tolerance_s or above[-1] >= force.size - 1:
        reasons.append("trigger")
    return AverageCheck(node, average, not reasons, tuple(reasons), peak)
