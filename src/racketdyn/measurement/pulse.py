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

import numpy as np
from numpy.typing import NDArray

from racketdyn.measurement.quality import force_baseline_and_noise

__all__ = ["HALF_SINE_FWHM_FACTOR", "contact_time"]

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
