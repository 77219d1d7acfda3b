"""A mode at a clear peak of the data whose LSCF poles do not settle over the orders.

The automatic selection (:func:`racketdyn.modal.poles.select_poles`) takes clusters of poles
stable in frequency *and* damping.  A clear peak of the data may have neither: the fit puts a
pole at its frequency in most orders while the damping wanders from order to order (an unseen
lab's 3-storey frame on a shaker table: 2.164 Hz, 74 × the noise, a pole there in ≈ 45 of 60
orders with ζ 0.07–0.5 %, stable in both in 2 — the base's random shaking of the mode fills
its peak), or a wide band's fit holds no pole there at all (the wing's 13.5 Hz near its band's
bottom, decaying 93 × slower than the kept modes).  Its pole is then taken from the data at the
peak (:func:`mode_at_peak`): the medians of the poles that agree in frequency there when they
stand in ``min_fraction`` of the orders (their damping's spread said: it is not settled), else
a local fit of the peak's lines (:func:`racketdyn.modal.refine.fit_poles`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from racketdyn.measurement.records import FrfSet
from racketdyn.modal.poles import (
    PoleStability,
    SelectionRules,
    Stabilisation,
    modal_peak,
    second_difference_noise,
)
from racketdyn.modal.refine import REFINE_LINES, fit_poles
from racketdyn.numerics import find_peaks

__all__ = [
    "NOISE_LINES",
    "PEAK_LINES",
    "PEAK_NOISE",
    "PEAK_PROMINENCE",
    "PeakMode",
    "clear_peaks",
    "half_power_span",
    "mode_at_peak",
    "peaks_beside",
    "phase_turns",
    "resolved_peaks",
]

PEAK_LINES = 3
"""Line spacings either side of a peak's line searched first for the poles at it."""

PEAK_PROMINENCE = 2.0
"""A peak of the data :func:`resolved_peaks` counts stands this factor above its
surroundings on the summed ``|H|`` (:func:`clear_peaks`)."""
PEAK_NOISE = 30.0
"""... and this factor above the noise of the lines round it: the summed noise of the FRFs
(:func:`racketdyn.modal.poles.second_difference_noise`) over :data:`NOISE_LINES` lines either
side.  The noise's own peaks stand 2-4 times over it; on a free spruce plate (48 kHz, 0.5 Hz
lines) a factor of 30 counts the same 20 peaks over 40-2,000 Hz as over 40-18,750 Hz, where
prominence alone counts 20 and 5,550 (the force is 40 dB down above 7 kHz)."""
NOISE_LINES = 100
"""Lines either side of a peak over which its noise is measured (the median of second
differences: a mode's own curvature at a few lines does not move it)."""


@dataclass(frozen=True)
class PeakMode:
    """A mode taken at a clear peak of the data (:func:`mode_at_peak`).

    Attributes
    ----------
    frequency_hz : float
        Its frequency, Hz.
    damping_ratio : float
        Its damping ratio: the median of the orders' (``source`` ``poles``) or the local fit's.
    orders : int
        Model orders holding a pole that agrees with it in frequency (for a local fit, with
        the peak's poles that do not: the evidence of a mode there).
    settled_orders : int
        Of those, orders whose pole is stable in damping too.
    damping_range : tuple of float
        The 10th and 90th percentiles of the orders' damping ratios (the local fit's twice).
    frequency_spread_hz : float
        Standard deviation of the orders' frequencies, Hz (NaN for a local fit).
    residues : ndarray, complex, shape (n_points,)
        Its residues (the nearest pole's, or the local fit's constants).
    peak_to_noise : float
        Its largest modal peak ``|A| / σ`` over that FRF's noise.
    source : str
        ``poles`` (the orders' medians) or ``local fit``.
    """

    frequency_hz: float
    damping_ratio: float
    orders: int
    settled_orders: int
    damping_range: tuple[float, float]
    frequency_spread_hz: float
    residues: NDArray[np.complex128]
    peak_to_noise: float
    source: str

    def damping_words(self, n_orders: int) -> str:
        """Where its damping comes from and how far it is settled, in words."""
        low, high = (100 * z for z in self.damping_range)
        if self.source == "poles":
            return (
                f"the fit's poles agree with it in frequency in {self.orders} of {n_orders} "
                f"orders, in damping in {self.settled_orders}: ζ {low:.2g}–{high:.2g} % from "
                f"order to order, not settled (the median {100 * self.damping_ratio:.2g} %)"
            )
        fit = f"ζ {100 * self.damping_ratio:.2g} % from a local fit of the peak's lines"
        if self.orders:
            return (
                f"the fit's poles stand near it in {self.orders} of {n_orders} orders, beside "
                f"the peak's lines: {fit}, its damping not settled"
            )
        return f"no settled pole of the fit there: {fit}, its damping not settled"


def clear_peaks(
    frfs: FrfSet, band_hz: tuple[float, float], prominence: float
) -> list[tuple[float, float]]:
    """The peaks of the summed ``|H|`` in ``band_hz`` standing ``prominence`` (a factor)
    above their surroundings: (frequency Hz, prominence as a factor), by frequency."""
    inside = (frfs.frequency >= band_hz[0]) & (frfs.frequency <= band_hz[1])
    f = frfs.frequency[inside]
    if f.size < 3:
        return []
    level = np.abs(frfs.values[:, inside]).sum(axis=0)
    logs = np.log10(np.maximum(level, np.finfo(float).tiny))
    found, props = find_peaks(logs, prominence=math.log10(prominence))
    return [(float(f[k]), float(10**p)) for k, p in zip(found, props["prominences"], strict=True)]


def resolved_peaks(frfs: FrfSet, band_hz: tuple[float, float]) -> list[float]:
    """The data's clear peaks in ``band_hz`` that stand for modes, Hz, by frequency: those
    :func:`clear_peaks` finds at :data:`PEAK_PROMINENCE` that also stand :data:`PEAK_NOISE`
    times over the noise round them and span two lines or more at half power (a line of
    noise does not).  A count of the modes the band must hold, not a list of them: two modes
    under one peak count once, and a peak narrower than a line is not counted.

    Parameters
    ----------
    frfs : FrfSet
        The FRFs.
    band_hz : tuple of float
        The band, Hz.

    Returns
    -------
    list of float
    """
    inside = (frfs.frequency >= band_hz[0]) & (frfs.frequency <= band_hz[1])
    values = frfs.values[:, inside]
    level = np.abs(values).sum(axis=0)
    found = []
    for peak, _ in clear_peaks(frfs, band_hz, PEAK_PROMINENCE):
        k = int(np.searchsorted(frfs.frequency[inside], peak))
        around = values[:, max(k - NOISE_LINES, 0) : k + NOISE_LINES + 1]
        noise = float(np.sqrt(second_difference_noise(around)).sum())
        left, right = half_power_span(level, k)
        if level[k] >= PEAK_NOISE * noise and right - left >= 2:
            found.append(peak)
    return found


def peaks_beside(
    frfs: FrfSet, band_hz: tuple[float, float], prominence: float
) -> list[tuple[float, float, float]]:
    """The peaks of the summed ``|H|`` in ``band_hz`` that :func:`clear_peaks` leaves only
    because a larger peak beside them fills the valley between: standing ``prominence`` (a
    factor) above the lowest point on their other side, more than ``√2`` above the valley
    (their half-power span closes on both sides), their phase turning by more than 90° across
    them (:func:`phase_turns`), yet less than ``prominence`` above the valley, beyond which
    the larger peak rises (a broad bump whose lower side runs out at the band's end is none).

    Two modes whose constants in an FRF have opposite signs have no anti-resonance between
    them there: a LabVIEW record's 19.77 Hz peak (22 (m/s²)/N) stood 5.5 × above the valley
    towards its neighbour's (27 at 21.15 Hz) and 45 × above its other side.

    Returns
    -------
    list of (float, float, float)
        Each peak's frequency (Hz), its factor above its other side and above the valley, by
        frequency.
    """
    inside = (frfs.frequency >= band_hz[0]) & (frfs.frequency <= band_hz[1])
    f, values = frfs.frequency[inside], frfs.values[:, inside]
    if f.size < 3:
        return []
    level = np.abs(values).sum(axis=0)
    logs = np.log10(np.maximum(level, np.finfo(float).tiny))
    found, props = find_peaks(logs, prominence=math.log10(2.0) / 2)
    out = []
    for k, valley, left_base, right_base in zip(
        found, props["prominences"], props["left_bases"], props["right_bases"], strict=True
    ):
        other = logs[k] - min(logs[left_base], logs[right_base])
        if valley >= math.log10(prominence) or other < math.log10(prominence):
            continue
        # the valley's side must rise to a larger peak, not run out at the band's end
        beyond = logs[:left_base] if logs[left_base] > logs[right_base] else logs[right_base:]
        if not np.any(beyond > logs[k]):
            continue
        if phase_turns(values, int(k), *half_power_span(level, int(k))):
            out.append((float(f[k]), float(10**other), float(10**valley)))
    return out


def phase_turns(values: NDArray[np.complex128], index: int, left: int, right: int) -> bool:
    """Whether the phase turns by more than 90° across the peak at line ``index`` whose
    half-power span is ``left``–``right``: in the FRF (row of ``values``) where the peak is
    largest, between the lines as far outside the span as its ends are from the peak."""
    strongest = int(np.argmax(np.abs(values[:, index])))
    before = values[strongest, max(2 * left - index, 0)]
    after = values[strongest, min(2 * right - index, values.shape[1] - 1)]
    return bool(abs(np.angle(after * np.conj(before))) >= np.pi / 2)


def mode_at_peak(
    stab: Stabilisation, frfs: FrfSet, peak_hz: float, rules: SelectionRules
) -> PeakMode | None:
    """The mode at the data's peak ``peak_hz`` (module docstring), or None.

    The poles stable in frequency (class ``FREQUENCY`` or better, ``0 < ζ <
    max_damping_ratio``) within :data:`PEAK_LINES` lines of the peak are taken, then, twice,
    those within the larger of a line and their median half half-power width ``ζf`` of their
    median frequency.  Standing in ``rules.min_fraction`` of the orders, the mode is their
    median frequency and damping ratio, if that frequency lies within the local fit's (below)
    half half-power width and half a line of the local fit's.  Else the FRFs' lines within
    :data:`~racketdyn.modal.refine.REFINE_LINES` of the peak are fitted with one pole started
    at it (the damping from its half-power width in the summed ``|H|``); a fit that does not
    improve on its start, leaves ``0 < ζ < max_damping_ratio`` or lands more than a line from
    the peak gives None, as does no pole and no fit.

    Parameters
    ----------
    stab : Stabilisation
        The stabilisation diagram of the band.
    frfs : FrfSet
        The FRFs fitted.
    peak_hz : float
        The peak's line, Hz.
    rules : SelectionRules
        The selection's rules (``min_fraction``, ``max_damping_ratio``).

    Returns
    -------
    PeakMode or None
    """
    spacing = float(np.median(np.diff(frfs.frequency)))
    usable = (
        (stab.stability >= int(PoleStability.FREQUENCY))
        & (stab.damping_ratio > 0)
        & (stab.damping_ratio < rules.max_damping_ratio)
    )
    centre, reach, zeta = peak_hz, PEAK_LINES * spacing, 0.0
    for _ in range(3):
        near = np.flatnonzero(usable & (np.abs(stab.frequency - centre) <= reach))
        if near.size == 0:
            break
        centre = float(np.median(stab.frequency[near]))
        zeta = float(np.median(stab.damping_ratio[near]))
        reach = max(spacing, zeta * centre)
    near = np.flatnonzero(usable & (np.abs(stab.frequency - centre) <= reach))
    orders = int(np.unique(stab.order[near]).size)
    local = _local_mode(stab, frfs, peak_hz, spacing, rules)
    # the orders' poles must be the peak's: within the local fit's half half-power width (and
    # half a line) of its frequency; else they stand for something broader (the wing's time
    # records: poles at 13.25 Hz, ζ 0.3-2.5 %, beside a peak the lines put at 13.52 Hz)
    agree = local is None or abs(centre - local.frequency_hz) <= (
        local.damping_ratio * local.frequency_hz + spacing / 2
    )
    if agree and near.size and orders >= max(1, math.ceil(rules.min_fraction * stab.orders.size)):
        settled = near[stab.stability[near] >= int(PoleStability.DAMPING)]
        nearest = int(near[np.argmin(np.abs(stab.frequency[near] - centre))])
        low, high = np.percentile(stab.damping_ratio[near], [10, 90])
        return PeakMode(
            frequency_hz=centre,
            damping_ratio=zeta,
            orders=orders,
            settled_orders=int(np.unique(stab.order[settled]).size),
            damping_range=(float(low), float(high)),
            frequency_spread_hz=float(np.std(stab.frequency[near])),
            residues=stab.residues[:, nearest],
            peak_to_noise=modal_peak(stab, stab.residues[:, nearest], 2 * np.pi * zeta * centre)[1],
            source="poles",
        )
    return None if local is None else replace(local, orders=orders)


def half_power_span(level: NDArray[np.float64], index: int) -> tuple[int, int]:
    """The first lines either side of the peak ``level[index]`` at or under its half power
    (``1/√2`` of it), or the ends."""
    half, left, right = level[index] / math.sqrt(2), index, index
    while left > 0 and level[left] > half:
        left -= 1
    while right < level.size - 1 and level[right] > half:
        right += 1
    return left, right


def _local_mode(
    stab: Stabilisation, frfs: FrfSet, peak_hz: float, spacing: float, rules: SelectionRules
) -> PeakMode | None:
    """The local fit's mode at the peak (:func:`mode_at_peak`), or None."""
    if stab.residues.shape[0] != frfs.n_points:  # stacked references: no local constants
        return None
    level = np.abs(frfs.values).sum(axis=0)
    left, right = half_power_span(level, int(np.argmin(np.abs(frfs.frequency - peak_hz))))
    start = max((right - left) * spacing, spacing) / (2 * peak_hz)
    window = REFINE_LINES * spacing
    found = fit_poles(
        frfs, np.array([peak_hz]), np.array([start]), (peak_hz - window, peak_hz + window)
    )
    if found is None:
        return None
    frequency, zeta, constants, improved = found
    f, z = float(frequency[0]), float(zeta[0])
    if not (improved and 0 < z < rules.max_damping_ratio and abs(f - peak_hz) <= spacing):
        return None
    return PeakMode(
        frequency_hz=f,
        damping_ratio=z,
        orders=0,
        settled_orders=0,
        damping_range=(z, z),
        frequency_spread_hz=math.nan,
        residues=constants[:, 0],
        peak_to_noise=modal_peak(stab, constants[:, 0], 2 * np.pi * z * f)[1],
        source="local fit",
    )
