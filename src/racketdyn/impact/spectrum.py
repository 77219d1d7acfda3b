"""The half-sine impact pulse and its Fourier spectrum (paper, eq 11 and Fig. 13)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["half_sine_force", "half_sine_spectrum"]


def half_sine_force(
    time: ArrayLike, contact_time: ArrayLike, peak_force: ArrayLike
) -> NDArray[np.float64]:
    """Impact force F(t) = F_MAX sin(π t / T_c) for 0 ≤ t ≤ T_c, zero otherwise (eq 11), N.

    Parameters
    ----------
    time : array_like
        Time from first contact, s.
    contact_time : array_like
        Contact time T_c, s.
    peak_force : array_like
        Peak force F_MAX = π F_MEAN / 2, N.
    """
    t = np.asarray(time, dtype=float)
    tc = np.asarray(contact_time, dtype=float)
    inside = (t >= 0) & (t <= tc)
    return np.asarray(np.where(inside, np.asarray(peak_force) * np.sin(np.pi * t / tc), 0.0))


def half_sine_spectrum(
    frequency: ArrayLike, contact_time: ArrayLike, peak_force: ArrayLike
) -> NDArray[np.float64]:
    """Magnitude of the Fourier transform of the half-sine pulse, ``|S(f)|`` in N·s (N/Hz).

    ``S(f) = ∫ F(t) e^{-2πift} dt``; in closed form, with ``u = f T_c``,

    ``|S(f)| = F_MAX T_c (2/π) |cos(π u)| / |1 − 4u²|  =  F_MAX T_c |sinc(½ − u)| / (1 + 2u)``

    where ``sinc(v) = sin(πv)/(πv)``.  The second form has no removable singularity at
    u = ½ (where the first is 0/0; its value there is F_MAX T_c / 2), so no special case is
    needed.  The first zero is at u = 3/2, the spectrum at f → 0 is the impulse
    ``2 F_MAX T_c / π = F_MEAN T_c``.  Arguments broadcast against each other.

    Parameters
    ----------
    frequency : array_like
        Frequency f, Hz (non-negative).
    contact_time : array_like
        Contact time T_c, s.
    peak_force : array_like
        Peak force F_MAX, N.
    """
    u = np.asarray(frequency, dtype=float) * np.asarray(contact_time, dtype=float)
    magnitude = (
        np.asarray(peak_force) * np.asarray(contact_time) * np.sinc(0.5 - u) / (1.0 + 2.0 * u)
    )
    return np.asarray(np.abs(magnitude))
