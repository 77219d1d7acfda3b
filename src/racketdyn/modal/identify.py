"""From FRFs to a modal model of any structure: poles, selection, constants, mass normalisation.

:func:`identify` chains the steps — stabilisation diagram (:mod:`~racketdyn.modal.poles`),
automatic pole selection, LSFD modal constants (:mod:`~racketdyn.modal.residues`) and mass
normalisation from the driving point — and returns an :class:`Identification` holding every
intermediate result, so nothing is lost and every figure can be drawn from it.

The modes are named neutrally, ``"mode 1 (123.4 Hz)"``, of kind ``unknown``: what a mode is
depends on the structure, and a caller that knows it names them from their shapes (a racket:
:func:`racketdyn.racket_modal.identify.identify_racket`) with :meth:`Identification.renamed`.
"""

from __future__ import annotations

import csv
import logging
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn._grammar import plural
from racketdyn.errors import InputError
from racketdyn.measurement.quality import NoiseOnly, noise_only_frfs
from racketdyn.measurement.records import (
    ANALYSER_BANDWIDTH_FACTOR,
    FORCE_DROP_DB,
    FrfReferences,
    FrfSet,
)
from racketdyn.modal.mac import mac
from racketdyn.modal.misfit import Misfit, misfit
from racketdyn.modal.model import ModalModel
from racketdyn.modal.peaks import (
    PEAK_NOISE,
    PEAK_PROMINENCE,
    PeakMode,
    clear_peaks,
    half_power_span,
    mode_at_peak,
    peaks_beside,
    phase_turns,
    resolved_peaks,
)
from racketdyn.modal.poles import (
    DroppedMode,
    NoModeError,
    SelectedPoles,
    SelectionRules,
    Stabilisation,
    _combine,
    _within_a_line,
    edge_margin,
    pole_of,
    require_rules,
    second_difference_noise,
    select_poles,
    stabilisation,
)
from racketdyn.modal.polyreference import DEFAULT_MAX_ORDER, poly_stabilisation
from racketdyn.modal.refine import (
    MOVE_LINES,
    REFINE_LINES,
    fit_poles,
    local_misfit,
    refine_narrow_poles,
)
from racketdyn.modal.residues import (
    WEAK_DRIVING_POINT,
    ModalFit,
    design_columns,
    fit_modal_constants,
    half_power_lines,
    mass_normalised_shapes,
    unscaled_shapes,
)
from racketdyn.numerics import find_peaks  # scipy.signal's, without its import (≈ 0.35 s)

__all__ = [
    "CLEAR_PEAK_GAIN",
    "DEFAULT_LOW_HZ",
    "EDGE_CLEAR",
    "EDGE_LINES",
    "EDGE_WIDTHS",
    "FIT_GAIN_MIN",
    "LINE_DAMPING",
    "LINE_TOLERANCE_HZ",
    "MAINS_HZ",
    "NO_FORCE",
    "ONE_PEAK_LINES",
    "SELECTION",
    "STRONG_NEGATIVE",
    "Identification",
    "default_band",
    "identify",
    "no_force_words",
]

log = logging.getLogger(__name__)

DEFAULT_LOW_HZ = 40.0
"""Lower band edge by default, Hz: above the rigid-body modes of a light structure on soft
supports (≤ 15 Hz for a racket on a sponge or in a hand) and below a racket's first bending
mode; lower where the data's first flexible mode lies below it (:func:`default_band`)."""
CLEAR_PEAK = 3.0
"""A clear peak of the data: its summed ``|H|`` this many times the median over the file's band
(the must-hold references' own definition, tests/test_realdata_must_hold.py)."""
SUSPENSION_GAP = 5.0
"""Rigid-body modes on a soft support lie below a fifth of the first flexible mode (the usual
rule for a free test's suspension, 10–20 %: docs/references.md, "Modal testing") ..."""
SUSPENSION_MAX_HZ = 10.0
"""... and below this, Hz (bungees and sponges under a structure a person can lift: 1–3 Hz; a
hand holding a racket: 3.5–7 Hz).  A clear peak below it with the next one at least
:data:`SUSPENSION_GAP` times higher is the support's; a clamped structure's first mode (the
wing's 13.5 Hz, 6.3 times below its second) is the structure's."""
FIRST_MODE_OCTAVE = 2.0
"""The default band starts this factor below the first flexible mode's peak: room for its
half-power width and the edge margin (:data:`EDGE_LINES`, :data:`EDGE_WIDTHS`)."""
SKIPPED_LINES = 3
"""Lines at the bottom of a file not searched for peaks (DC and the window's leakage there)."""
FIT_GAIN_MIN = 1.5
"""A selected pole is a mode of the data when the fit near its frequency (three half-power
bandwidths either side) is at least this many times worse without it.  A pole where the data
have no mode scores 1.00 (its constants fit to nothing: tests/test_lab_identify.py); a weak
real mode among misfit neighbours scores 2–3 (the rig's third membrane mode at 1.24 kHz: 2.5),
strong modes 30–1000."""
STRONG_NEGATIVE = 0.25
"""A negative driving-point constant at least this fraction of the largest positive one there
cannot be a fit's error on a small value: the reference is not a true driving point.  Smaller
negative ones (a mode nearly still at the accelerometer, e.g. a string-bed mode at a hoop point)
leave that mode out of a mass-normalised model."""


EDGE_LINES = 3.0
"""Line spacings in a mode's edge margin, where the fit's computational poles fall and no mode
is taken (:func:`racketdyn.modal.poles.select_poles`' ``edge_lines``)."""
EDGE_WIDTHS = 1.0
"""Of a mode's own half-power width ``2ζf`` in its edge margin (``edge_widths``): a peak the
band's edge cuts is not fitted whole.  The margin follows the data, not the band's width: 2 %
of pff_lms's 40-20,000 Hz (399 Hz) took its 150 Hz mode (tests/test_realdata.py)."""
SELECTION = SelectionRules(edge_lines=EDGE_LINES, edge_widths=EDGE_WIDTHS)
"""The rules of the automatic pole selection here (:func:`racketdyn.modal.poles.select_poles`)
unless :func:`identify` is given others: the default ones with the edge margin of
:data:`EDGE_LINES` and :data:`EDGE_WIDTHS`."""
EDGE_CLEAR = 0.1
"""A mode dropped in the edge margin is reported as a clear mode (stage ``edge``, one warning
naming the option that keeps it) when it is stable in more than three orders and its peak is at
least this fraction of the median kept mode's (20 dB): the bar's 873 Hz mode 7 Hz below an
880 Hz top scores ≈ 0.9, edge poles of noise ≤ 0.01 (tests/test_band.py).  A pole on the
flank of a mode beyond the band may score as a mode does (the trial racket's 846 Hz, 70 Hz
below its 917.6 Hz mode: 0.10; its 1929 Hz on the fall of its 1856 Hz mode: 0.25): the data
must also peak there (:func:`_data_peak`, tests/test_edge_hints.py)."""
WITHIN_RTOL = 1e-3
"""A band an edge row names keeps its mode when the fit over it finds one this close (0.1 %):
the trial racket's 846.19 Hz edge pole had none within 3 % over the wider band."""
MAINS_HZ = (50.0, 60.0)
"""Mains frequencies whose harmonics an accelerometer's cable picks up (electrical lines)."""
LINE_TOLERANCE_HZ = 0.1
"""A dropped candidate this close to a harmonic of :data:`MAINS_HZ` may be an electrical line."""
LINE_DAMPING = 5e-4
"""... when its damping ratio is below this (0.05 %): a sine of constant amplitude over the
record is a pole on the unit circle, ζ ≈ 0 (hum added to synthetic records: ζ ≤ 0.03 %).
A structure's mode on a harmonic keeps its damping and stays a mode (pyFRF's 900 Hz, 18 × 50
Hz, ζ 0.11 %, decays in every hit: tests/test_realdata.py)."""
EDGE_SCAN = 0.05
"""Part of the band's width at each end searched for a clear peak of the data that the fit
missed: so near an edge of a wide band the LSCF (the band zoomed onto the unit circle, its two
ends meeting) may find no stable pole at all (pff_lms's 150 Hz over 40-20,000 Hz, the wing's
13.5 Hz over 5-1000 Hz)."""
EDGE_PEAK = 10.0
"""... a clear peak: its summed ``|H|`` this many times (20 dB) above the surroundings it rises
from (prominence), its phase turning by more than 90° across it."""
EDGE_TRIES = 2
"""Clear peaks tried at each end (the most prominent), each with one narrower band's fit."""

ONE_PEAK_LINES = 3
"""Line spacings within which two poles are one peak however small their fitted damping (an
edge fragment's is often a third of the mode's): the edge scan's and the clear peaks' rule,
beside the half-power widths."""

NO_PEAK = "no peak of the data there"
"""Said of a candidate stable in too few orders, as clear as the kept modes by its modal peak,
where the data have no peak (:func:`_data_peak`): a pole a wide band's fit puts between two
modes for both (:func:`_named_rows`)."""

CLEAR_PEAK_GAIN = 3.0
"""A candidate stable in too few orders (but more than three) and one peak with no kept mode
is kept when the fit near it, with the kept modes, is at least this many times worse without
it (:func:`fit_gain`): the data hold its peak, only its poles wander over the orders.  A pole
of noise scores 1.0; the trial racket's 3-node twisting at 665 Hz, 14 Hz below its membrane,
stable in 10 of 60 orders, 5.7 (issue 25 item 8).  Between :data:`FIT_GAIN_MIN` and this, the
candidate is named ``unsettled`` with the ``pin_hz`` that keeps it."""
PAIR_WIDTHS = 3.0
"""Half-width of a close pair's local fit, in the broader pole's half-power widths ``2ζf``
(refitted while the fit widens it): a broad mode under a narrow one is held by its skirts."""
PAIR_TRIES = 3
"""Local fits of one close pair at most, each over the window the one before gives."""
PAIR_BAND = 2.5
"""A close pair's weaker mode is tried on the band from the bottom to this many times its
frequency, before it is named: fewer modes in the band, more orders for each."""
PAIR_MAC = 0.5
"""Largest MAC of a close pair's two shapes: under one peak two modes are told apart by their
shapes alone, so they must be clearly unlike (the hand-held racket's bending and twisting
0.00; one mode's peak split by the local fit into two poles of like damping 0.61-0.79)."""
BROAD_START = 4.0
"""A kept mode with no neighbour under its peak is tried for a broader one hidden there (its
FRFs' coherence known): a second pole started this many times its damping, one half-power
width above it (the held racket's 4-node twisting, ζ 3.6 %, 10 Hz above its 4-node bending,
ζ 0.57 %: a shoulder of the bending's peak)."""
BROAD_WIDTHS = 1.5
"""... fitted over this many of the broader pole's half-power widths ``2ζf`` either side (not
:data:`PAIR_WIDTHS`: over three, ±180 Hz, the held racket's 4-node pair's window reaches the
651.8 and 971.1 Hz modes, which the two poles' local model does not hold, and its second pole
runs to one of them)."""
BROAD_SCREEN = 2.0
"""... when the local model with the started pair fits at least this many times better than
with the mode alone (no fit yet, a cost screen: the held racket's 4-node bending 6.9 with
rig noise, 2.6 at 40/50 dB; other modes there 1.2-3.6 and 1.2-1.8)."""
PAIR_STEPS_PER_POLE = 50
"""A close pair's (or three modes') local fit stops after this many steps of the nonlinear fit
a pole, and is not taken: every pair the rig's rackets keep converges within 39 steps (two
poles), three modes within 79; the wing's export had two fits wander 258 and 345 steps
(seconds each) to be refused after."""
BROAD_STEPS = 40
"""... in at most this many steps of the nonlinear fit (the held racket's pair: 5–15; a fit
wandering over a window with no broader mode took hundreds, seconds each)."""
WANDERING_PEAK = 0.5
"""A clear peak whose poles agree in frequency but not in damping is named when its modal peak
over the noise is at least this share of the kept modes' median (the frame's 2.164 Hz, its
clearest peak: 0.7-1.8 × on four synthetic sets like it; a single hit's noise up to 18.5 kHz,
pff_lms: 0.002-0.16 ×, none named)."""
NOISE_FLOOR = 1e-3
"""An FRF's noise (from its coherence) is taken as at least this fraction of the noisiest
FRF's: a coherence of 1 (noise-free lines) weights no FRF infinitely."""
HEADER_DIGITS_RTOL = 1e-5
"""A band top this far (relative) above the last line is the last line: the UFF header keeps
the step with 6 significant digits (E13.5), so a 1000 Hz export reads 999.997 Hz."""

DEFAULT_ORDER = 60
"""The highest model order against one reference unless the band's peaks ask for more."""
ORDERS_PER_PEAK = 5
"""Model orders a clear peak of the band takes (:func:`racketdyn.modal.peaks.resolved_peaks`):
a free spruce plate's 20 peaks over 40-2,000 Hz (0.5 Hz lines, one FRF) needed order 100 for
20 of the lab's 21 (14 at 60, 18 at 80); 45 well-separated synthetic modes (4 FRFs, 0.1 %
noise) needed 66 (17 kept at 60): real data's noise takes poles too."""
MAX_RAISED_ORDER = 120
"""The highest order the default raises itself to (run time grows with it: benchmarks/
bench_orders.py); beyond it the order that would fit the peaks is said."""
PEAK_TOP_SHARE = 0.5
"""A band whose clear peaks all lie in its lower part, below this share of its width: the
lines above them are noise that takes the orders' poles (the cause named when no mode is
found)."""


def default_band(frfs: FrfSet) -> tuple[float, float]:
    """From below the data's first flexible mode (at most 40 Hz) to the FRFs' bandwidth, Hz.

    The bottom is :data:`DEFAULT_LOW_HZ` unless the data's first flexible mode lies below it:
    then :data:`FIRST_MODE_OCTAVE` below its peak (issue 25, item 1: a clear mode below 40 Hz
    was lost without a word).  The first flexible mode is the lowest clear peak
    (:data:`CLEAR_PEAK`, standing :data:`~racketdyn.modal.peaks.PEAK_PROMINENCE` over the line
    it sits on: the bumps of a mass line's noise do not) of the summed ``|H|`` above the
    support's rigid-body modes — clear peaks
    below :data:`SUSPENSION_MAX_HZ` and a gap of :data:`SUSPENSION_GAP` (a wing clamped at its
    root has none; an aircraft frame on bungees shows two near 1 Hz below its 18.8 Hz mode).
    A racket's first bending mode (≥ 100 Hz) leaves the bottom at 40 Hz, above the hand's
    modes.

    The top is :attr:`~racketdyn.measurement.records.FrfSet.bandwidth_hz`: the last
    spectral line of FRFs another system exported (they end at its analyser bandwidth, e.g.
    1000 Hz from fs = 2560 Hz), fs / 2.56 of FRFs racketdyn estimated from time records (whose
    lines above it are the anti-alias filter's roll-off; :data:`ANALYSER_BANDWIDTH_FACTOR`) —
    or, lower, :attr:`~racketdyn.measurement.records.FrfSet.force_band_hz` of FRFs estimated
    from time records: where the hammer's force envelope is
    :data:`~racketdyn.measurement.records.FORCE_DROP_DB` below its plateau, above which the
    FRF is the response's noise over almost no force.

    Parameters
    ----------
    frfs : FrfSet
        The FRFs to identify.

    Returns
    -------
    tuple of float
        (low, high), Hz.
    """
    return _default_band(frfs)[0]


def _default_band(frfs: FrfSet) -> tuple[tuple[float, float], str]:
    """:func:`default_band` and why it is that band, in words (:attr:`Identification.band_note`)."""
    high = float(frfs.bandwidth_hz)
    top = f"to {high:.6g} Hz, the FRFs' bandwidth" + (
        f" (fs/{ANALYSER_BANDWIDTH_FACTOR:g} of the time records)"
        if high < float(frfs.frequency[-1])
        else " (their last line)"
    )
    force = frfs.force_band_hz
    if force is not None and DEFAULT_LOW_HZ < force < high:
        # above it the FRF is the response's noise over no force (issue 25: a 51.2 kHz hit's
        # peaks at 3.9-14.6 kHz, its force 53-105 dB down, were offered as clear modes)
        top = (
            f"to {force:.6g} Hz: {no_force_words(force)} (a harder tip puts force higher; "
            f"`band_hz` up to the FRFs' bandwidth, {high:.6g} Hz, looks above it anyway)"
        )
        high = force
    first, suspension = _first_flexible_peak(frfs, high)
    if first is None or first >= DEFAULT_LOW_HZ:
        # no frequency named: of accelerances, whose level rises with ω², a low mode is often
        # no clear peak over the band's median (a racket's 175 Hz bending read "first clear
        # peak, 469 Hz")
        seen = f"no clear peak in the data below {DEFAULT_LOW_HZ:g} Hz"
        return (DEFAULT_LOW_HZ, high), f"from {DEFAULT_LOW_HZ:g} Hz ({seen}) {top}"
    lowest = float(frfs.frequency[min(SKIPPED_LINES, frfs.frequency.size - 1)])
    low = max(first / FIRST_MODE_OCTAVE, lowest)
    why = f"an octave below the data's first clear peak, {first:.3g} Hz"
    if suspension:
        why += f", above {suspension} suspension peak{'s' * (suspension > 1)} under " + (
            f"{SUSPENSION_MAX_HZ:g} Hz"
        )
    if low > first / FIRST_MODE_OCTAVE:
        why += f"; the lowest line used, {SKIPPED_LINES} lines up"
    return (low, high), f"from {low:.3g} Hz ({why}) {top}"


def no_force_words(force_band_hz: float) -> str:
    """ "the hammer's force is 40 dB down above 2.9 kHz": the top of the band the force fills."""
    return f"the hammer's force is {FORCE_DROP_DB:g} dB down above {force_band_hz / 1e3:.2g} kHz"


def _first_flexible_peak(frfs: FrfSet, high: float) -> tuple[float | None, int]:
    """The lowest clear peak above the support's rigid-body modes, Hz (None: no clear peak),
    and how many clear peaks below it were taken as the support's (:func:`default_band`)."""
    keep = (frfs.frequency <= high) & (np.arange(frfs.frequency.size) >= SKIPPED_LINES)
    f = frfs.frequency[keep]
    level = np.abs(frfs.values[:, keep]).sum(axis=0)
    if f.size < 8 or not np.all(np.isfinite(level)):
        return None, 0
    # a peak over the band's median that does not stand over the line it sits on is that
    # line's noise: on a free structure's mass line, over a band whose median is far below it
    # (a spruce plate's to 18.75 kHz: 0.53 against the mass line's ≈ 2), its bumps every line
    # or two left no gap between the support's peaks and the first flexible mode
    logs = np.log10(np.maximum(level, np.finfo(float).tiny))
    found, _ = find_peaks(
        logs,
        height=math.log10(CLEAR_PEAK * float(np.median(level))),
        prominence=math.log10(PEAK_PROMINENCE),
    )
    peaks = f[found]
    support = (peaks[:-1] < SUSPENSION_MAX_HZ) & (peaks[1:] / peaks[:-1] >= SUSPENSION_GAP)
    gaps = np.flatnonzero(support)
    below = int(gaps[-1] + 1) if gaps.size else 0
    peaks = peaks[below:]
    return (float(peaks[0]) if peaks.size else None), below


def _checked_band(frfs: FrfSet, band: tuple[float, float]) -> tuple[float, float]:
    """The band within the FRFs; a top within the header's rounding of the last line is it."""
    last = float(frfs.frequency[-1])
    low, high = float(band[0]), float(band[1])
    if last < high <= last * (1 + HEADER_DIGITS_RTOL):
        high = last
    if not 0 <= low < high <= last:
        default = default_band(frfs)
        raise InputError(
            f"{frfs.source}: band {low:g}–{high:g} Hz must lie within the FRFs' "
            f"{float(frfs.frequency[0]):g}–{last:.7g} Hz (their last line; the default band "
            f"is {default[0]:g}–{default[1]:g} Hz); give `band_hz` LOW,HIGH inside it"
        )
    return (low, high)


def _data_peak(frfs: FrfSet, frequency: float, damping_ratio: float, edge: bool = True) -> bool:
    """Whether the summed ``|H|`` (every line, the band's and beyond) peaks at ``frequency``.

    A local maximum within the mode's half half-power width ``ζf``: for a pole in the edge
    margin (``edge``) at least :data:`ONE_PEAK_LINES` line spacings (an edge fragment's fitted
    damping may be a third of its mode's), else ``ζf`` and half a line (the lines put a peak
    within half a line of its mode).  The pole the LSCF puts in the edge margin for the flank
    of a mode beyond the band has none: the data rise or fall straight through it (the trial
    racket's 846 Hz, on the rise to its 917.6 Hz mode; its 1929 Hz, on its 1855.9 Hz mode's
    fall), however stable the pole and large its fitted peak; nor has the pole a wide band's
    fit puts between two modes for both (tests/test_edge_hints.py: 20.82 Hz between modes at
    19.77 and 21.16 Hz of one sign, an anti-resonance between them).
    """
    found, _ = find_peaks(np.abs(frfs.values).sum(axis=0))
    own, spacing = max(damping_ratio, 0.0) * frequency, _spacing(frfs)
    reach = max(own, ONE_PEAK_LINES * spacing) if edge else own + spacing / 2
    return bool(np.any(np.abs(frfs.frequency[found] - frequency) <= reach))


def _edge_modes(
    selected: SelectedPoles, frfs: FrfSet, band: tuple[float, float], choices: _Choices
) -> SelectedPoles:
    """Clear modes dropped in the band's edge margin: one row each, naming what keeps them.

    The edge margin (the ``choices``' rules' ``edge_lines`` line spacings and ``edge_widths`` of the
    mode's half-power width, :data:`EDGE_LINES` and :data:`EDGE_WIDTHS` by default, and their
    ``edge_margin`` of the band's width) keeps the fit's computational poles out; a mode of
    the data there (stable in more than three orders, peak within 20 dB of the kept modes',
    :data:`EDGE_CLEAR`) is not dropped silently.  Clusters of one peak split by the edge are
    one row (the strongest).  The reason names ``band_hz`` (low, high) when the FRFs' bandwidth
    (:attr:`~racketdyn.measurement.records.FrfSet.bandwidth_hz`: lines above it are the
    anti-alias filter's roll-off) reaches far enough to put the mode out of the margin, else
    ``pin_hz`` [F].  A hint is only given where following it keeps a mode: the data must peak
    there (:func:`_data_peak`), and a band named is fitted first (the row then holds the mode
    it gives, else it names the pin).
    """
    rules = choices.rules
    low, high = band
    spacing = float(frfs.frequency[1] - frfs.frequency[0])
    reference = float(np.median(selected.peak_to_noise)) if selected.n_modes else 0.0
    strong = [
        d
        for d in selected.dropped_modes
        if d.stage == "selection"
        and d.reason.startswith("within")
        and d.orders_stable > 3
        and d.peak_to_noise >= EDGE_CLEAR * reference
    ]
    clear = [d for d in strong if _data_peak(frfs, d.frequency_hz, d.damping_ratio)]
    flanks = {
        id(d): replace(d, reason=f"{d.reason}; no peak of the data there (a flank's pole)")
        for d in strong
        if all(d is not c for c in clear)
    }
    if flanks:
        selected = replace(
            selected,
            dropped_modes=tuple(flanks.get(id(d), d) for d in selected.dropped_modes),
        )
    if not clear:
        return selected
    rows: list[DroppedMode] = []
    for top in (False, True):
        side = [d for d in clear if (d.frequency_hz > (low + high) / 2) == top]
        if not side:
            continue
        mode = max(side, key=lambda d: d.peak_to_noise)
        f, zeta = mode.frequency_hz, mode.damping_ratio
        margin = (
            rules.edge_margin * (high - low)
            + rules.edge_lines * spacing
            + rules.edge_widths * 2 * max(zeta, 0.0) * f
        )
        room = 3 * 2 * zeta * f + 2 * spacing + margin
        if top:
            wanted = f + room
            edge = f"the band's top {high:g} Hz"
            new = float(np.ceil(wanted / 5.0) * 5.0)
            fits = new <= float(frfs.bandwidth_hz)
            option = f"`band_hz` {low:g},{new:g}"
            end = f"the FRFs' bandwidth ends at {float(frfs.bandwidth_hz):.6g} Hz"
        else:
            wanted = f - room
            edge = f"the band's bottom {low:g} Hz"
            new = float(np.floor(wanted / 5.0) * 5.0)
            fits = new >= float(frfs.frequency[0])
            option = f"`band_hz` {new:g},{high:g}"
            end = f"the FRFs start at {float(frfs.frequency[0]):.6g} Hz"
        tried = (min(low, new), max(high, new))
        there = _mode_in(frfs, tried, choices, f, WITHIN_RTOL * f) if fits else None
        if there is not None:
            mode = replace(mode, frequency_hz=there[0], damping_ratio=there[1])
            keep = f"{option} keeps it"
        elif fits:
            keep = f"{_pin(f, spacing)} keeps it ({option} does not: the fit there finds no mode)"
        else:
            keep = (
                f"{end}: {_pin(f, spacing)} keeps it (fitted with part of its peak beyond the data)"
            )
        rows.append(
            replace(
                mode,
                stage="edge",
                reason=(
                    f"a clear mode (stable in {mode.orders_stable} orders, peak "
                    f"{mode.peak_to_noise:.2g} × the noise) within {margin:.3g} Hz of {edge}, "
                    f"where no mode is taken; {keep}"
                ),
            )
        )
    rest = tuple(d for d in selected.dropped_modes if all(d is not c for c in clear))
    return replace(selected, dropped_modes=(*rest, *rows))


@dataclass(frozen=True)
class _Choices:
    """The caller's say in the selection (:func:`identify`'s parameters): the modes pinned and
    excluded, the rules and the highest model order, for every selection made here."""

    pin_hz: Sequence[float]
    exclude_hz: Sequence[float]
    rules: SelectionRules
    max_order: int
    references: FrfReferences | None = None
    """Several references: every fit made here is the poly-reference LSCF of them all."""

    def stabilisation(self, frfs: FrfSet, band: tuple[float, float]) -> Stabilisation:
        """The poles of a band: the pLSCF of the references, else the LSCF of ``frfs``."""
        if self.references is not None:
            return poly_stabilisation(self.references, band, self.max_order)
        return stabilisation(frfs, band, max_order=self.max_order)

    def fitted(self, frfs: FrfSet) -> FrfSet:
        """The FRFs a selection's residues stand for: every reference's, stacked reference by
        reference as the pLSCF's residues are, else ``frfs``."""
        return frfs if self.references is None else _combine(self.references.sets)


def _missed_peaks(
    selected: SelectedPoles,
    stab: Stabilisation,
    frfs: FrfSet,
    band: tuple[float, float],
    choices: _Choices,
) -> SelectedPoles:
    """Clear peaks of the data near the band's edges that no mode or row explains: one row
    each (stage ``edge``) naming the ``band_hz`` that keeps the mode, tried before it is named.

    Over a band many times wider than a mode's distance from its edge the fit may find no
    stable pole there at all, so :func:`_edge_modes` has nothing to name: its pole errors,
    about one size in rad/s for every mode and growing with the band's width, are large
    against a slowly decaying mode's decay rate (:func:`_slow_decay`, which the row quotes;
    a band's first mode is often its slowest).  The data are
    searched instead: within :data:`EDGE_SCAN` of the band's width from each end, peaks of the
    summed ``|H|`` standing :data:`EDGE_PEAK` above their surroundings whose phase (in the FRF
    where the peak is largest) turns by more than 90° across them, below the FRFs' bandwidth.
    A peak within a half-power width (or three lines) of a kept mode or of a named row is
    explained, but for an ``unsettled`` row (whose pin keeps the wide band's pole): a row
    found here takes its place.  For the :data:`EDGE_TRIES` most prominent others at each end
    a band ten times the peak's distance from the edge is fitted, and a row is written
    when a mode comes out there, else when the mode at the peak
    (:func:`racketdyn.modal.peaks.mode_at_peak` over ``stab``, the band's own poles or a local
    fit) stands :data:`WANDERING_PEAK` of the kept modes' median over the noise, naming the
    ``pin_hz`` that keeps it (a first mode near the bottom beside a mode of one sign, shaken,
    stable in 7 of 60 orders over the narrower band too, had no row).  Near a wide band's top,
    in the anti-alias roll-off or a force's spectral zero, many peaks are noise's: untried or
    unconfirmed ones are logged at DEBUG.
    """
    low, high = band
    data = frfs.band(low, high)
    f = data.frequency
    if f.size < 8:
        return selected
    spacing = float(np.median(np.diff(f)))
    level = np.abs(data.values).sum(axis=0)
    logs = np.log10(np.maximum(level, np.finfo(float).tiny))
    found, props = find_peaks(logs, prominence=np.log10(EDGE_PEAK))
    scan = EDGE_SCAN * (high - low)
    explained = [
        (float(fk), 2 * max(float(zk), 0.0) * float(fk))
        for fk, zk in zip(selected.frequency, selected.damping_ratio, strict=True)
    ] + [
        (d.frequency_hz, 2 * max(d.damping_ratio, 0.0) * d.frequency_hz)
        for d in selected.dropped_modes
        if d.stage not in ("selection", "unsettled")
    ]
    # an unsettled row's pin keeps the wide band's pole; a band fitted round the peak may do
    # better (pff_lms's 150.3 Hz over 40-20,000 Hz at order 80: the pin 150.98 Hz, 40-1150 Hz
    # 150.29 Hz): it is tried, and its row takes the unsettled row's place
    unsettled = [d for d in selected.dropped_modes if d.stage == "unsettled"]
    reference = float(np.median(selected.peak_to_noise)) if selected.n_modes else np.inf
    replaced: list[DroppedMode] = []
    rows: list[DroppedMode] = []
    tries = {True: EDGE_TRIES, False: EDGE_TRIES}
    for index, prominence in sorted(
        zip(found, props["prominences"], strict=True), key=lambda pair: -pair[1]
    ):
        peak = float(f[index])
        bottom = peak - low < high - peak
        if scan < min(peak - low, high - peak) or peak > frfs.bandwidth_hz:
            continue
        if any(abs(peak - fe) <= max(we, ONE_PEAK_LINES * spacing) for fe, we in explained):
            continue
        left, right = half_power_span(level, int(index))
        if not phase_turns(data.values, int(index), left, right):
            continue
        if tries[bottom] == 0:
            log.debug("clear peak at %.1f Hz near the band's edge: not tried", peak)
            continue
        tries[bottom] -= 1
        reach = max(
            10 * (peak - low if bottom else high - peak), (2 * choices.max_order + 2) * spacing
        )
        if bottom:
            tried = (low, min(float(np.ceil((low + reach) / 5.0) * 5.0), high))
        else:
            tried = (max(float(np.floor((high - reach) / 5.0) * 5.0), low), high)
        mode = _mode_in(frfs, tried, choices, peak, max(3, right - left) * spacing)
        one_peak = max(float(right - left), ONE_PEAK_LINES) * spacing
        where = (
            f"a clear peak of the data at {peak:.1f} Hz ({20 * prominence:.0f} dB above its "
            f"surroundings, {peak - low if bottom else high - peak:.3g} Hz from the band's "
            f"{'bottom' if bottom else 'top'}) where the fit over {low:g}–{high:g} Hz finds no "
            "stable pole"
        )
        if mode is not None:
            reason = (
                f"{where}: {_slow_decay(mode, selected)}; `band_hz` {tried[0]:g},{tried[1]:g} "
                f"keeps it (there {mode[0]:.2f} Hz, ζ {100 * mode[1]:.2g} %)"
            )
            orders, peak_to_noise = 0, math.nan
        else:
            # an unsettled row already names this peak's pin from the same evidence
            named = any(abs(d.frequency_hz - peak) <= one_peak for d in unsettled)
            at_peak = None if named else mode_at_peak(stab, frfs, peak, choices.rules)
            if at_peak is None or at_peak.peak_to_noise < WANDERING_PEAK * reference:
                log.debug("clear peak at %.1f Hz: no mode over %g–%g Hz either", peak, *tried)
                continue
            mode = (at_peak.frequency_hz, at_peak.damping_ratio)
            reason = (
                f"{where}, nor over {tried[0]:g}–{tried[1]:g} Hz: "
                f"{at_peak.damping_words(int(stab.orders.size))}; "
                f"{_pin(at_peak.frequency_hz, spacing)} keeps it"
            )
            orders, peak_to_noise = at_peak.settled_orders, at_peak.peak_to_noise
        rows.append(
            DroppedMode(mode[0], mode[1], orders, "edge", reason, peak_to_noise=peak_to_noise)
        )
        explained.append((peak, float(right - left) * spacing))  # one row a peak
        replaced += [d for d in unsettled if abs(d.frequency_hz - peak) <= one_peak]
    if not rows:
        return selected
    kept = [d for d in selected.dropped_modes if not any(d is r for r in replaced)]
    return replace(selected, dropped_modes=(*kept, *rows))


def _slow_decay(mode: tuple[float, float], selected: SelectedPoles) -> str:
    """Why a wide band's fit holds no stable pole of a mode (frequency Hz, ζ): its pole errors,
    about one size in rad/s for every mode and growing with the band's width, are large
    against this mode's decay rate ζω (the virtual rig's 120 Hz over 60–1,953 Hz, 3.8 rad/s:
    ±40 % in damping from order to order, while the modes decaying at 18–56 rad/s settle;
    the band's bottom moved from 60 to 5 Hz, no better: docs/develop.md, issue 25); a mode
    decaying no slower than the kept modes' median is said to be too near the band's edge."""
    decay = 2 * np.pi * mode[0] * mode[1]
    rates = 2 * np.pi * selected.frequency * selected.damping_ratio
    slower = float(np.median(rates)) / decay if rates.size and decay > 0 else np.nan
    if not slower > 1:
        return "too near the edge of so wide a band"
    return (
        f"over so wide a band the fit's pole errors, about one size for every mode, are large "
        f"against this mode's slow decay (ζω {decay:.2g} rad/s, {slower:.2g} × below the kept "
        "modes' median)"
    )


def _mode_in(
    frfs: FrfSet, band: tuple[float, float], choices: _Choices, near: float, within: float
) -> tuple[float, float] | None:
    """The mode a narrower band gives within ``within`` Hz of ``near`` (frequency, ζ), if any."""
    try:
        stab = choices.stabilisation(frfs, band)
        found = select_poles(stab, rules=choices.rules, log=False)
    except InputError:
        return None
    close = np.flatnonzero(np.abs(found.frequency - near) <= within)
    if close.size == 0:
        return None
    k = int(close[np.argmin(np.abs(found.frequency[close] - near))])
    return (float(found.frequency[k]), float(found.damping_ratio[k]))


def _harmonics(frequency: float) -> list[str]:
    """The mains harmonics within :data:`LINE_TOLERANCE_HZ` of ``frequency`` ("5 × 50 Hz")."""
    found = []
    for mains in MAINS_HZ:
        k = round(frequency / mains)
        if k >= 1 and abs(frequency - k * mains) <= LINE_TOLERANCE_HZ:
            found.append(f"{k} × {mains:g} Hz")
    return found


def _named_rows(selected: SelectedPoles, frfs: FrfSet) -> SelectedPoles:
    """Dropped candidates that are not noise, named: electrical lines and unsettled clear peaks.

    A candidate left out by the stabilisation rules (stage ``selection``) is

    - likely an electrical ``line`` when it sits on a mains harmonic
      (:data:`LINE_TOLERANCE_HZ`) with a damping ratio of about zero (:data:`LINE_DAMPING`):
      it stays out, its row says what it likely is (from FRFs alone the pole of a hammer
      pulse's spectral zero on a harmonic looks the same: a 1 ms half-sine's at 1500 Hz);
    - ``unsettled`` when it was stable in too few orders (but more than three) while its peak
      is at least the median kept mode's, the data peak there (:func:`_data_peak`: its modal
      peak is the fit's, not the data's) and it does not overlap a kept mode's or a named
      row's (their half-power widths and :data:`ONE_PEAK_LINES` lines of the FRFs' spacing
      apart): a clear peak whose poles move from order to order (pyFRF's 4128 Hz, 10⁵ × the
      noise, stable in 6 of 60 orders); its row names the ``pin_hz`` that keeps it.  With
      no peak of the data there it stays out, its reason saying so (:data:`NO_PEAK`), and
      :func:`_peaks_either_side` names the clear peaks beside it.
    """
    spacing_hz = _spacing(frfs)
    reference = float(np.median(selected.peak_to_noise)) if selected.n_modes else np.inf
    named = [d for d in selected.dropped_modes if d.stage != "selection"]
    centre = np.concatenate([selected.frequency, [d.frequency_hz for d in named]])
    width = 2 * np.concatenate(
        [
            np.maximum(selected.damping_ratio, 0.0) * selected.frequency,
            [max(d.damping_ratio, 0.0) * d.frequency_hz for d in named],
        ]
    )
    one_peak = ONE_PEAK_LINES * spacing_hz

    def own(d: DroppedMode) -> float:
        return 2 * max(d.damping_ratio, 0.0) * d.frequency_hz

    rows: list[DroppedMode] = []
    for d in selected.dropped_modes:
        if d.stage != "selection":
            rows.append(d)
            continue
        harmonics = _harmonics(d.frequency_hz)
        if harmonics and abs(d.damping_ratio) < LINE_DAMPING:
            rows.append(
                replace(
                    d,
                    stage="line",
                    reason=(
                        f"likely an electrical line, not a mode: on the mains harmonic "
                        f"{' or '.join(harmonics)} with ζ {100 * d.damping_ratio:.3f} % "
                        f"(< {100 * LINE_DAMPING:g} %: a hum of constant amplitude); "
                        f"{d.reason}"
                    ),
                )
            )
        elif (
            d.reason.startswith("stable in")
            and d.orders_stable > 3
            and d.peak_to_noise >= reference
            and not np.any(np.abs(centre - d.frequency_hz) < np.maximum(width + own(d), one_peak))
        ):
            if not _data_peak(frfs, d.frequency_hz, d.damping_ratio, edge=False):
                rows.append(replace(d, reason=f"{d.reason}; {NO_PEAK}"))
                continue
            rows.append(
                replace(
                    d,
                    stage="unsettled",
                    reason=(
                        f"a clear peak ({d.peak_to_noise:.2g} × the noise, the kept modes' "
                        f"median {reference:.2g}) whose poles move from order to order: "
                        f"{d.reason}; {_pin(d.frequency_hz, spacing_hz)} keeps it"
                    ),
                )
            )
        else:
            rows.append(d)
    return replace(selected, dropped_modes=tuple(rows))


NO_FORCE = "no force"
"""The stage of a clear peak above the hammer's force band (:attr:`FrfSet.force_band_hz`)."""


def _above_force(frequency_hz: float, frfs: FrfSet) -> bool:
    """Whether a frequency lies above the band the hammer's force fills."""
    top = frfs.force_band_hz
    return top is not None and frequency_hz > top


def _beyond_force(rows: Sequence[DroppedMode], frfs: FrfSet) -> tuple[DroppedMode, ...]:
    """Rows that offer a ``pin_hz`` or a ``band_hz`` for a peak above the hammer's force band
    turned into rows of stage :data:`NO_FORCE` saying why it is no mode to keep.

    Above :attr:`~racketdyn.measurement.records.FrfSet.force_band_hz` the FRF is the response's
    noise over almost no force: its peaks stand high over the FRF's own noise (a 51.2 kHz
    hit's 3.9-14.6 kHz peaks, 120-1100 × it) and are no evidence of a mode.
    """
    top = frfs.force_band_hz
    if top is None:
        return tuple(rows)
    return tuple(
        replace(
            d,
            stage=NO_FORCE,
            reason=f"{no_force_words(top)}: the peak is the response's noise over almost no "
            "force, no mode to keep; a harder hammer tip puts force there",
        )
        if d.frequency_hz > top and d.stage in ("edge", "unsettled")
        else d
        for d in rows
    )


def _clear_peaks(
    selected: SelectedPoles,
    stab: Stabilisation,
    frfs: FrfSet,
    band: tuple[float, float],
    choices: _Choices,
) -> tuple[SelectedPoles, list[str]]:
    """Candidates stable in too few orders whose peak the data hold: kept, or named.

    A candidate left out only for its orders (stage ``selection`` or ``unsettled``, stable in
    more than three), further from every kept mode and every row already named (``edge``,
    ``merged``, ``line``) than their mean half-power width (``ζf`` each: not one peak with it,
    as :func:`racketdyn.modal.poles.select_poles` merges) and than :data:`ONE_PEAK_LINES` line
    spacings (an edge row's fitted damping may be a third of its mode's) is fitted with the
    kept modes (one per peak: the one stable in most orders).  With a :func:`fit_gain` of
    :data:`CLEAR_PEAK_GAIN` or more it is kept, as a pin would keep it (not marked pinned);
    with :data:`FIT_GAIN_MIN` or more it is an ``unsettled`` row naming the ``pin_hz`` that
    keeps it.  A close pair whose lower mode only a few orders resolve (a
    twisting mode 14 Hz below a membrane mode) lost that mode, and every mode of its kind
    above it was named a node short (issue 25 item 8).

    Returns
    -------
    SelectedPoles, list of str
        The selection (re-run with the kept candidates pinned when there are any) and one line
        per kept candidate saying why.
    """
    # one peak with a kept mode or with a row already named (edge, merged, line) is theirs
    named_rows = [d for d in selected.dropped_modes if d.stage in ("edge", "merged", "line")]
    centre = np.concatenate([selected.frequency, [d.frequency_hz for d in named_rows]])
    reach = np.concatenate(
        [
            selected.damping_ratio * selected.frequency,
            [max(d.damping_ratio, 0.0) * d.frequency_hz for d in named_rows],
        ]
    )
    spacing = _spacing(frfs)
    one_peak = ONE_PEAK_LINES * spacing
    candidates = [
        d
        for d in selected.dropped_modes
        if d.stage in ("selection", "unsettled")
        and "stable in" in d.reason
        and d.orders_stable > 3
        and not _above_force(d.frequency_hz, frfs)
        and 0.0 < d.damping_ratio < 1.0
        and np.all(
            np.abs(centre - d.frequency_hz)
            >= np.maximum(reach + d.damping_ratio * d.frequency_hz, one_peak)
        )
    ]
    chosen: list[DroppedMode] = []
    for d in sorted(candidates, key=lambda d: (-d.orders_stable, -d.peak_to_noise)):
        own = d.damping_ratio * d.frequency_hz
        if all(
            abs(d.frequency_hz - c.frequency_hz) >= own + c.damping_ratio * c.frequency_hz
            for c in chosen
        ):
            chosen.append(d)
    if not chosen:
        return selected, []
    found = pole_of([d.frequency_hz for d in chosen], [d.damping_ratio for d in chosen])
    poles = np.concatenate([selected.pole, found])
    gains = fit_gain(frfs, fit_modal_constants(frfs, poles, band))[selected.n_modes :]
    keep: list[tuple[DroppedMode, float]] = []
    named: dict[float, float] = {}  # by frequency: the same clusters after a re-selection
    for d, gain in zip(chosen, gains, strict=True):
        if gain >= CLEAR_PEAK_GAIN:
            keep.append((d, float(gain)))
        elif (
            gain >= FIT_GAIN_MIN
            and d.stage == "selection"
            and _data_peak(frfs, d.frequency_hz, d.damping_ratio, edge=False)
        ):
            named[round(d.frequency_hz, 6)] = float(gain)

    def relabelled(rows: tuple[DroppedMode, ...]) -> tuple[DroppedMode, ...]:
        out = []
        for d in rows:
            gain = named.get(round(d.frequency_hz, 6)) if d.stage == "selection" else None
            out.append(
                d
                if gain is None
                else replace(
                    d,
                    stage="unsettled",
                    fit_gain=gain,
                    reason=(
                        f"a peak of the data (the fit near it {gain:.2g} × better with it) "
                        f"whose poles move from order to order: {d.reason}; "
                        f"{_pin(d.frequency_hz, spacing)} keeps it"
                    ),
                )
            )
        return tuple(out)

    if not keep:
        return replace(selected, dropped_modes=relabelled(selected.dropped_modes)), []
    pins = [d.frequency_hz for d, _ in keep]
    again = select_poles(  # the user's pins said once, the kept candidates by `lines`
        stab,
        pin_hz=[*choices.pin_hz, *pins],
        exclude_hz=choices.exclude_hz,
        rules=choices.rules,
        log=False,
    )
    user = np.zeros(again.n_modes, dtype=bool)
    for f in choices.pin_hz:  # the user's own pins stay pinned, the kept candidates do not
        user[int(np.argmin(np.abs(again.frequency - f)))] = True
    again = _named_rows(
        _edge_modes(replace(again, pinned=again.pinned & user), frfs, band, choices), frfs
    )
    again = replace(again, dropped_modes=relabelled(again.dropped_modes))
    lines = [
        f"{d.frequency_hz:.2f} Hz: a peak of the data (the fit near it {gain:.2g} × better with "
        f"it, ≥ {CLEAR_PEAK_GAIN:g}) apart from every mode, though stable in "
        f"{d.orders_stable} of {stab.orders.size} orders only"
        for d, gain in keep
    ]
    return again, lines


def _wandering_peaks(
    selected: SelectedPoles,
    stab: Stabilisation,
    frfs: FrfSet,
    band: tuple[float, float],
    choices: _Choices,
) -> SelectedPoles:
    """Clear peaks of the data whose poles agree in frequency but not in damping: named.

    A peak of the summed ``|H|`` standing :data:`EDGE_PEAK` above its surroundings, further
    than :data:`EDGE_SCAN` of the band's width from its ends (:func:`_missed_peaks`' part) and
    from every kept mode and named row (their half-power widths, at least
    :data:`ONE_PEAK_LINES` lines), where the fit's poles agree with one frequency in the
    ``min_fraction`` of the orders the selection asks (:func:`racketdyn.modal.peaks.
    mode_at_peak`) while too few of them agree in damping to make a cluster, and whose modal
    peak is at least :data:`WANDERING_PEAK` of the kept modes' median over the noise, is an
    ``unsettled`` row naming the ``pin_hz`` that keeps it and saying that its damping is not
    settled (an unseen lab's frame: 2.164 Hz, 74 × the noise, a pole there in ≈ 45 of 60
    orders with ζ 0.07–0.5 %, was dropped with no line on the console).  A peak that stands
    less than :data:`EDGE_PEAK` above its surroundings only because a larger one beside it
    fills the valley between (:func:`racketdyn.modal.peaks.peaks_beside`: no anti-resonance
    parts two modes whose constants have opposite signs) is named so too, anywhere in the
    band (the edge scan looks for clear peaks only) and with its poles in any number of
    orders: its phase turning through it and its height over the noise are the evidence (a
    LabVIEW record's 19.77 Hz, 5.5 × above the valley towards 21.15 Hz and 16 Hz from the
    band's bottom, 2505 × the noise, was dropped with no line).
    """
    low, high = band
    scan = EDGE_SCAN * (high - low)
    n_orders = int(stab.orders.size)
    peaks = [
        (
            p,
            f"a clear peak of the data ({20 * np.log10(rise):.0f} dB above its surroundings) "
            "whose damping is not settled",
            choices.rules.min_fraction * n_orders,
        )
        for p, rise in clear_peaks(frfs, (low + scan, high - scan), EDGE_PEAK)
    ] + [
        (
            p,
            f"a clear peak of the data beside a larger one ({20 * np.log10(other):.0f} dB above "
            f"the lowest point on its other side, {20 * np.log10(valley):.0f} dB above the "
            "valley between, its phase turning through it) that the selection left out",
            0.0,
        )
        for p, other, valley in peaks_beside(frfs, band, EDGE_PEAK)
    ]
    return _peak_rows(selected, stab, frfs, choices, peaks)


def _peak_rows(
    selected: SelectedPoles,
    stab: Stabilisation,
    frfs: FrfSet,
    choices: _Choices,
    peaks: list[tuple[float, str, float]],
) -> SelectedPoles:
    """The selection with an ``unsettled`` row for each of the data's ``peaks`` (frequency Hz,
    words, the orders its mode must stand in) that no kept mode or named row explains, whose
    data and mode (:func:`racketdyn.modal.peaks.mode_at_peak`) stand :data:`WANDERING_PEAK` of
    the kept modes' median over the noise (with no kept mode, of the clearest such mode's):
    :func:`_wandering_peaks`' rule."""
    spacing = _spacing(frfs)
    if selected.n_modes:
        reference = float(np.median(selected.peak_to_noise))
    else:  # no kept mode: the clearest of the peaks' modes stands for them
        modes = [(mode_at_peak(stab, frfs, p, choices.rules), orders) for p, _, orders in peaks]
        reference = max(
            (m.peak_to_noise for m, orders in modes if m is not None and m.orders >= orders),
            default=np.inf,
        )
    named = [  # a row already named, or a mode the caller excluded
        d
        for d in selected.dropped_modes
        if d.stage != "selection" or d.reason.startswith("excluded")
    ]
    explained = [
        (float(f), 2 * max(float(z), 0.0) * float(f))
        for f, z in zip(selected.frequency, selected.damping_ratio, strict=True)
    ] + [(d.frequency_hz, 2 * max(d.damping_ratio, 0.0) * d.frequency_hz) for d in named]
    noise = stab.noise_rms if stab.noise_rms.size == frfs.n_points else np.min(stab.noise_rms)
    n_orders = int(stab.orders.size)
    rows: list[DroppedMode] = []
    for peak, words, orders in peaks:
        if any(abs(peak - f) <= max(w, ONE_PEAK_LINES * spacing) for f, w in explained):
            continue
        line = int(np.argmin(np.abs(frfs.frequency - peak)))
        with np.errstate(divide="ignore", invalid="ignore"):  # the data's own peak first
            if not np.max(np.abs(frfs.values[:, line]) / noise) >= WANDERING_PEAK * reference:
                continue
        mode = mode_at_peak(stab, frfs, peak, choices.rules)
        if mode is None or mode.orders < orders or mode.peak_to_noise < WANDERING_PEAK * reference:
            continue
        rows.append(
            DroppedMode(
                mode.frequency_hz,
                mode.damping_ratio,
                mode.settled_orders,
                "unsettled",
                f"{words}: {mode.damping_words(n_orders)}; {_pin(mode.frequency_hz, spacing)} "
                "keeps it",
                peak_to_noise=mode.peak_to_noise,
            )
        )
        explained.append((mode.frequency_hz, 2 * mode.damping_ratio * mode.frequency_hz))
    if not rows:
        return selected
    return replace(selected, dropped_modes=(*selected.dropped_modes, *rows))


def _peaks_either_side(
    selected: SelectedPoles,
    stab: Stabilisation,
    frfs: FrfSet,
    band: tuple[float, float],
    choices: _Choices,
) -> SelectedPoles:
    """The clear peaks (:data:`EDGE_PEAK`) nearest below and above each candidate left out
    with no peak of the data at it (:data:`NO_PEAK`) that nothing explains yet: named as
    :func:`_wandering_peaks` names a peak, with its poles in any number of orders.

    A wide band's fit stood for two modes of one sign with one pole between them (20.82 Hz,
    ζ 0.5 %, 9 orders, between 19.77 and 21.16 Hz: an anti-resonance parts them), which was
    named ``unsettled`` where the data have no peak; the peaks beside it are the modes the fit
    missed.  Run after :func:`_missed_peaks`, whose narrower band's fit gives a peak near the
    band's edge a better mode than the poles of the wide band.
    """
    between = [
        d.frequency_hz
        for d in selected.dropped_modes
        if d.stage == "selection" and d.reason.endswith(NO_PEAK)
    ]
    found = clear_peaks(frfs, band, EDGE_PEAK)
    peaks: dict[float, tuple[float, str, float]] = {}
    for f in between:
        for p, rise in [*[q for q in found if q[0] < f][-1:], *[q for q in found if q[0] > f][:1]]:
            words = (
                f"a clear peak of the data ({20 * np.log10(rise):.0f} dB above its "
                f"surroundings) beside a pole the fit put between peaks ({f:.5g} Hz, {NO_PEAK}) "
                "that the selection left out"
            )
            peaks.setdefault(p, (p, words, 0.0))
    return _peak_rows(selected, stab, frfs, choices, sorted(peaks.values()))


def _peak_pins(
    stab: Stabilisation, frfs: FrfSet, choices: _Choices
) -> tuple[_Choices, list[tuple[float, PeakMode]]]:
    """The pins the selection's clusters cannot keep at the data's peak, taken from the data.

    A pin with no mode of the automatic selection within ``pin_tolerance`` of it, near which
    (within ``pin_tolerance``) the data stand a clear peak (:data:`EDGE_PEAK`, or a peak
    beside a larger one: :func:`racketdyn.modal.peaks.peaks_beside`; the nearest) with no
    cluster of its own there (:func:`_cluster_at`), is kept as
    :func:`racketdyn.modal.peaks.mode_at_peak` finds that peak's mode: a hint's ``pin_hz``
    keeps the mode it names even where no cluster of the fit is stable there (the wing's
    13.5 Hz near its band's bottom was refused, "no stable pole within 5 %") or where the
    nearest cluster is a fragment beside the peak (the wing's time records: 13.18 Hz, ζ 2.5 %,
    for a peak at 13.52 Hz).  Returns the choices with the other pins, and each
    pin so kept with its mode.
    """
    if not choices.pin_hz:
        return choices, []
    tolerance = choices.rules.pin_tolerance
    try:
        automatic = select_poles(
            stab, (), choices.exclude_hz, rules=choices.rules, log=False
        ).frequency
    except InputError:
        automatic = np.zeros(0)
    peaks = [p for p, _ in clear_peaks(frfs, stab.band_hz, EDGE_PEAK)]
    peaks += [p for p, _, _ in peaks_beside(frfs, stab.band_hz, EDGE_PEAK)]
    rest: list[float] = []
    taken: list[tuple[float, PeakMode]] = []
    for f in choices.pin_hz:
        f = float(f)
        near = [p for p in peaks if abs(p - f) <= tolerance * f]
        mode = None
        if near and not np.any(np.abs(automatic - f) <= tolerance * f):
            peak = min(near, key=lambda p: abs(p - f))
            mode = mode_at_peak(stab, frfs, peak, choices.rules)
        if mode is None or _cluster_at(stab, f, mode, choices):
            rest.append(f)
        else:
            taken.append((f, mode))
    return replace(choices, pin_hz=tuple(rest)), taken


def _cluster_at(stab: Stabilisation, pin: float, mode: PeakMode, choices: _Choices) -> bool:
    """Whether the cluster the selection pins at ``pin`` is a mode of its own at the peak's
    ``mode``: stable in more than three orders (fewer are the noise's) and within the peak
    mode's half half-power width and half a line of it (a cluster below ``min_fraction`` at
    the peak keeps its own pole, as pins always did)."""
    try:
        found = select_poles(stab, [pin], choices.exclude_hz, rules=choices.rules, log=False)
    except InputError:
        return False
    k = int(np.argmin(np.abs(np.where(found.pinned, found.frequency, np.inf) - pin)))
    reach = mode.damping_ratio * mode.frequency_hz + stab.line_spacing_hz / 2
    return bool(found.n_orders[k] > 3 and abs(found.frequency[k] - mode.frequency_hz) <= reach)


def _with_peak_modes(
    selected: SelectedPoles,
    taken: list[tuple[float, PeakMode]],
    stab: Stabilisation,
    frfs: FrfSet,
) -> tuple[SelectedPoles, list[str]]:
    """The selection with the pins kept at the data's peaks (:func:`_peak_pins`) added,
    pinned and :attr:`~racketdyn.modal.poles.SelectedPoles.at_peak` (no orders count is
    reported for them), their rows (``edge``, ``unsettled``) gone, and one line each saying
    how."""
    if not taken:
        return selected, []
    spacing = _spacing(frfs)
    modes = [m for _, m in taken]
    frequency = np.array([m.frequency_hz for m in modes])
    zeta = np.array([m.damping_ratio for m in modes])
    near = [
        max(2 * m.damping_ratio * m.frequency_hz, ONE_PEAK_LINES * spacing, m.frequency_hz * 1e-3)
        for m in modes
    ]
    rows = tuple(
        d
        for d in selected.dropped_modes
        if d.stage not in ("edge", "unsettled")
        or not any(abs(d.frequency_hz - f) <= w for f, w in zip(frequency, near, strict=True))
    )
    merged = replace(
        selected,
        frequency=np.concatenate([selected.frequency, frequency]),
        damping_ratio=np.concatenate([selected.damping_ratio, zeta]),
        pole=np.concatenate([selected.pole, pole_of(frequency, zeta)]),
        n_orders=np.concatenate([selected.n_orders, [m.settled_orders for m in modes]]),
        frequency_spread_hz=np.concatenate(
            [selected.frequency_spread_hz, [m.frequency_spread_hz for m in modes]]
        ),
        damping_spread=np.concatenate(
            [selected.damping_spread, [np.std(m.damping_range) for m in modes]]
        ),
        peak_to_noise=np.concatenate([selected.peak_to_noise, [m.peak_to_noise for m in modes]]),
        residues=np.concatenate(
            [selected.residues, np.column_stack([m.residues for m in modes])], axis=1
        ),
        pinned=np.concatenate([selected.pinned, np.ones(len(modes), dtype=bool)]),
        dropped_modes=rows,
        pair_fitted=np.concatenate([selected.flags("pair_fitted"), np.zeros(len(modes), bool)]),
        at_peak=np.concatenate([selected.flags("at_peak"), np.ones(len(modes), bool)]),
    )
    lines = [
        f"{m.frequency_hz:.4f} Hz: pinned at {f:g} Hz, kept at the data's peak, where "
        f"{m.damping_words(int(stab.orders.size))}"
        for f, m in taken
    ]
    return merged.select(np.argsort(merged.frequency, kind="stable")), lines


def _close_pairs(
    selected: SelectedPoles,
    frfs: FrfSet,
    band: tuple[float, float],
    choices: _Choices,
    narrower: bool = True,
) -> tuple[SelectedPoles, list[str]]:
    """Two modes under one peak that the LSCF over a wide band does not part: fitted locally.

    Over a band holding many modes the orders computed resolve two modes closer than their
    half-power width late or never: the low orders fit one pole of mixed shape and damping
    for both, and the broader mode's own poles appear in a few high orders only.  The
    selection then keeps the mixed pole, or the narrow mode alone, and drops the broader one
    for its orders (a hand-held racket's 3-node bending and 2-node twisting 0.14 Hz apart, ζ 1
    and 4 %: the twisting's damping 71 % low, its pole dropped, the shapes unscaled; issue 25).
    For each kept mode with a neighbour within their mean half-power width (a kept mode, or a
    candidate dropped for its orders, as :func:`_clear_peaks` takes them) two poles are
    fitted to the FRFs' own lines around it (every reference's with several references:
    the pLSCF's residues stack them; :func:`racketdyn.modal.refine.fit_poles`, over
    :data:`PAIR_WIDTHS` of the broader pole's half-power width either side, refitted while that
    widens), started from the mode and the neighbour least like it in damping.  The two are
    taken, in place of the mode and every kept mode within one peak of it or of them (one at
    most: where the wide band's fit kept three or more under one peak, two poles would lose one,
    and the selection stays), when they stay one peak, their shapes are unlike (MAC under
    :data:`PAIR_MAC`: one mode split in two has one shape) and each holds a peak of the data
    over the whole band (:func:`fit_gain`, fitted with every other mode kept,
    :data:`FIT_GAIN_MIN` or more for one within one peak of a mode the selection kept,
    :data:`CLEAR_PEAK_GAIN` for one it left out); else the selection stays as it is, and a
    weaker mode of the two between :data:`FIT_GAIN_MIN` and :data:`CLEAR_PEAK_GAIN` that no kept
    mode stands for is an ``unsettled`` row naming the ``band_hz`` that keeps it
    (:func:`_weak_of_pair`; ``narrower`` False: not tried, as in that band's own fit).  The
    local fit and its gains weight each FRF by its noise (:func:`_noise_weights`, from the
    coherence), and a kept mode with no neighbour is tried for a broader mode hidden under its
    peak (:data:`BROAD_START`, :data:`BROAD_SCREEN`; taken by the same rules, never named); a
    mode of the pair in the band's edge margin (:func:`racketdyn.modal.poles.edge_margin`) is
    not taken.  A candidate left under the peak of a pair taken is fitted with it as a third
    mode, kept or named (:func:`_third_mode`).

    Returns
    -------
    SelectedPoles, list of str
        The selection, and one line per pair (or three) fitted saying what it replaced.
    """
    rules = choices.rules
    spacing = _spacing(frfs)
    stacked = choices.fitted(frfs)
    lines: list[str] = []
    tried: list[float] = []
    while True:
        untried = [
            int(j)
            for j in np.argsort(-selected.n_orders, kind="stable")
            if not np.any(np.isclose(selected.frequency[j], tried))
        ]
        if not untried:
            break
        k = untried[0]
        fk, zk = float(selected.frequency[k]), float(selected.damping_ratio[k])
        tried.append(fk)
        kept, other = _neighbours(selected, k, rules)
        hidden = other is None
        if other is None:  # a broader mode whose peak is a shoulder of this one's, if any
            if frfs.coherence is None or zk <= 0:
                continue
            other = (fk * (1 + zk), BROAD_START * zk, 0, float("nan"))
        # fitted on the FRFs the residues stand for (every reference's under the pLSCF): the
        # pair's constants join them, and its shapes are told apart as the stabilisation's are
        found = _pair_fit(stacked, (fk, zk), [other[:2]], spacing, rules.max_damping_ratio, hidden)
        if found is None:
            continue
        pair, window = found
        frequency, zeta, constants = pair
        margins = np.array(
            [edge_margin(rules, band, spacing, f, z) for f, z in zip(frequency, zeta, strict=True)]
        )
        if not np.all(np.abs(frequency - np.mean(band)) <= (band[1] - band[0]) / 2 - margins):
            log.debug("close pair at %.2f Hz: a mode of the pair in the band's edge margin", fk)
            continue
        if abs(frequency[1] - frequency[0]) >= float(np.sum(zeta * frequency)):
            log.debug("close pair at %.2f Hz: the local fit's poles are two peaks", fk)
            continue
        agree = float(mac(constants[:, :1], constants[:, 1:])[0, 0])
        if agree >= PAIR_MAC:
            log.debug("close pair at %.2f Hz: the local fit's shapes alike (MAC %.2f)", fk, agree)
            continue
        if _within_a_line(
            spacing, (frequency[0], frequency[1]), (zeta[0], zeta[1]), rules.damping_tolerance
        ):
            # a kept mode is not parted into two under a line apart: a peak drifting from FRF
            # to FRF fits so, its local shapes unlike (the wing's 326.23 Hz: MAC 0.19)
            log.debug("close pair at %.2f Hz: the local fit's poles within a line", fk)
            continue
        rest = np.ones(selected.n_modes, dtype=bool)
        rest[[k, *kept]] = False
        # a mode kept within one peak of the pair found is one of the pair: replaced too
        reach = selected.damping_ratio[:, None] * selected.frequency[:, None] + zeta * frequency
        found_again = [
            int(j)
            for j in np.flatnonzero(rest)
            if np.any(np.abs(selected.frequency[j] - frequency) < reach[j])
        ]
        if hidden and found_again:
            log.debug("close pair at %.2f Hz: the broader pole is a kept mode's", fk)
            continue
        kept += found_again
        if len(kept) > 1:  # the wide band's fit parted three or more here: two poles lose one
            log.debug(
                "close pair at %.2f Hz: %d kept modes under one peak, not refitted as two",
                fk,
                len(kept) + 1,
            )
            continue
        rest[kept] = False
        poles = pole_of(frequency, zeta)
        fit = fit_modal_constants(frfs, np.concatenate([selected.pole[rest], poles]), band)
        # each of these FRFs weighted by its own noise over the pair's window, as the pair was
        gains = fit_gain(frfs, fit, _noise_weights(frfs, window))[-2:]
        # a mode the selection kept needs a peak of the data, one it left out a clear peak: the
        # first stands for mode k, the second for a kept mode if it started from one or the
        # selection kept it apart from mode k (found again by the fit)
        kept_second = bool(found_again) or any(
            np.isclose(other[0], selected.frequency[j]) for j in kept
        )
        needed = np.array([FIT_GAIN_MIN, FIT_GAIN_MIN if kept_second else CLEAR_PEAK_GAIN])
        if not np.all(gains >= needed):
            log.debug("close pair at %.2f Hz: the local fit's gains %s", fk, gains)
            weak = int(np.argmin(gains))
            if (
                gains[1 - weak] >= needed[1 - weak]
                and gains[weak] >= FIT_GAIN_MIN
                and narrower
                and not hidden
                and needed[weak] == CLEAR_PEAK_GAIN
            ):
                row = _weak_of_pair(frfs, band, choices, (fk, agree), pair, gains)
                selected = replace(selected, dropped_modes=(*selected.dropped_modes, row))
            continue
        peaks, third_from, named = [other[3]], None, None
        third = _third_mode(selected, frfs, band, choices, (rest, needed), (pair, window))
        if isinstance(third, DroppedMode):
            named = third  # a third mode under the peak, not one the second stands for
            selected = replace(selected, dropped_modes=_renamed(selected.dropped_modes, third))
        elif third is not None:
            pair, gains, agree, third_from = third
            peaks.append(third_from[3])
        was = ", ".join(
            f"{selected.frequency[j]:.2f} Hz ζ {100 * selected.damping_ratio[j]:.3g} %"
            for j in sorted([k, *kept])
        )
        second = (frequency[1], zeta[1])
        selected, started = _candidates_kept(selected, second, other, rules, named)
        if third_from is not None:  # the third's candidate row goes too
            selected, _ = _candidates_kept(selected, third_from[:2], third_from, rules)
        had = f"{band[0]:g}–{band[1]:g} Hz had {was}{started}"
        lines.append(_under_one_peak(pair, gains, agree, had))
        selected = _with_pair(selected, rest, k, pair, peaks)
        tried.extend(float(f) for f in pair[0])
    return selected, lines


def _under_one_peak(
    pair: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.complex128]],
    gains: NDArray[np.float64],
    agree: float,
    had: str,
) -> str:
    """The line saying which modes were fitted under one peak (two or three; ``agree`` their
    shapes' largest MAC) in place of what the wide band's fit ``had``."""
    frequency, zeta, _ = pair
    order = np.argsort(frequency)

    def listed(items: list[str]) -> str:
        return " and ".join([", ".join(items[:-1]), items[-1]])

    most = " at most" if frequency.size > 2 else ""
    return (
        f"{listed([f'{frequency[j]:.2f} Hz (ζ {100 * zeta[j]:.3g} %)' for j in order])}: "
        f"{['two', 'three'][frequency.size - 2]} modes under one peak (shapes' MAC {agree:.2f}"
        f"{most}, the fit near each {listed([f'{gains[j]:.3g}' for j in order])} × better "
        f"with it) fitted on their own lines; the fit over {had}"
    )


def _third_mode(
    selected: SelectedPoles,
    frfs: FrfSet,
    band: tuple[float, float],
    choices: _Choices,
    kept: tuple[NDArray[np.bool_], NDArray[np.float64]],
    found: tuple[
        tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.complex128]],
        tuple[float, float],
    ],
) -> (
    tuple[
        tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.complex128]],
        NDArray[np.float64],
        float,
        tuple[float, float, int, float],
    ]
    | DroppedMode
    | None
):
    """A third mode under a close pair's peak (the pair just taken, with the gains it needed):
    three poles fitted, or the candidate named, or None.

    Three modes within one another's half-power widths that the wide band's fit keeps as two
    become a pair, and the third stays a candidate dropped for its orders (299, 300 and 301.2
    Hz at ζ 0.6 %: the pair 299.26/301.20 Hz, the candidate 300.29 Hz stable in 4 of 60).
    The candidate (as :func:`_neighbours` takes them; the one stable in most orders) within
    one peak of a mode of the pair and further than :data:`ONE_PEAK_LINES` lines from both is
    fitted with the pair on the pair's lines (:func:`_pair_fit`, started from the pair and
    it).  The three are taken when each stays in the band's margins and one peak with
    another, their shapes are unlike (MAC under :data:`PAIR_MAC`, pair by pair), the pair's
    gains still pass and the third's is :data:`CLEAR_PEAK_GAIN` or more (a mode the selection
    left out, as for the pair's).  Else, where the candidate's own pole gains
    :data:`FIT_GAIN_MIN` or more beside the pair (fitted with every other mode kept), its row
    becomes ``unsettled`` naming the ``pin_hz`` that keeps it.

    Returns
    -------
    tuple, DroppedMode or None
        The three modes (frequencies, damping ratios, constants), their gains, their shapes'
        largest MAC and the candidate (frequency, ζ, orders, peak over the noise); or its row
        named; or None (no candidate, or no peak of its own).
    """
    (rest, needed), ((frequency, zeta, _), window) = kept, found
    rules, spacing = choices.rules, _spacing(frfs)
    candidates = [
        d
        for d in _dropped_for_orders(selected, rules)
        if np.any(
            np.abs(frequency - d.frequency_hz) < zeta * frequency + d.damping_ratio * d.frequency_hz
        )
        and np.all(np.abs(frequency - d.frequency_hz) > ONE_PEAK_LINES * spacing)
    ]
    if not candidates:
        return None
    d = max(candidates, key=lambda d: (d.orders_stable, d.peak_to_noise))
    weights = _noise_weights(frfs, window)
    three = _pair_fit(
        choices.fitted(frfs),
        (float(frequency[0]), float(zeta[0])),
        [(float(frequency[1]), float(zeta[1])), (d.frequency_hz, d.damping_ratio)],
        spacing,
        rules.max_damping_ratio,
    )
    if three is not None:
        (f3, z3, constants), _ = three
        margins = np.array(
            [edge_margin(rules, band, spacing, f, z) for f, z in zip(f3, z3, strict=True)]
        )
        reach = z3[:, None] * f3[:, None] + z3 * f3
        apart = np.abs(f3[:, None] - f3)
        agree = float(np.max(mac(constants, constants)[np.triu_indices(3, 1)]))
        gains = fit_gain(
            frfs,
            fit_modal_constants(frfs, np.concatenate([selected.pole[rest], pole_of(f3, z3)]), band),
            weights,
        )[-3:]
        if (
            np.all(np.abs(f3 - np.mean(band)) <= (band[1] - band[0]) / 2 - margins)
            and np.all(np.sum(apart < reach, axis=1) >= 2)  # itself and another
            and np.min(apart[np.triu_indices(3, 1)]) > ONE_PEAK_LINES * spacing
            and agree < PAIR_MAC
            and np.all(gains >= [*needed, CLEAR_PEAK_GAIN])
        ):
            return (f3, z3, constants), gains, agree, _as_neighbour(d)
        log.debug(
            "close pair at %.2f Hz: no third mode at %.2f Hz (gains %s, MAC %.2f)",
            frequency[0],
            d.frequency_hz,
            gains,
            agree,
        )
    poles = pole_of([*frequency, d.frequency_hz], [*zeta, d.damping_ratio])
    gain = float(
        fit_gain(
            frfs,
            fit_modal_constants(frfs, np.concatenate([selected.pole[rest], poles]), band),
            weights,
        )[-1]
    )
    if d.stage != "selection" or not gain >= FIT_GAIN_MIN:  # named once
        return None
    return replace(
        d,
        stage="unsettled",
        fit_gain=gain,
        reason=(
            f"a third mode under the peak of {frequency[0]:.2f} and {frequency[1]:.2f} Hz "
            f"(the fit near it {gain:.2g} × better with it) that three poles fitted on their "
            f"own lines do not part: {d.reason}; {_pin(d.frequency_hz, _spacing(frfs))} keeps "
            f"the wide band's pole there, its neighbours as that fit has them"
        ),
    )


def _renamed(rows: tuple[DroppedMode, ...], row: DroppedMode) -> tuple[DroppedMode, ...]:
    """``rows`` with the row of ``row``'s frequency (and orders) replaced by ``row``."""
    return tuple(
        row if (d.frequency_hz, d.orders_stable) == (row.frequency_hz, row.orders_stable) else d
        for d in rows
    )


def _neighbours(
    selected: SelectedPoles, k: int, rules: SelectionRules
) -> tuple[list[int], tuple[float, float, int, float] | None]:
    """Mode ``k``'s neighbours within their mean half-power width: the kept ones (indices),
    and of them and the candidates dropped for their orders (stable in more than three, as
    :func:`_clear_peaks` takes them) the one least like it in damping (frequency, ζ, orders,
    peak over the noise), None if none."""
    fk, zk = float(selected.frequency[k]), float(selected.damping_ratio[k])
    reach = zk * fk + selected.damping_ratio * selected.frequency
    kept = [int(j) for j in np.flatnonzero(np.abs(selected.frequency - fk) < reach) if j != k]
    near = [
        (
            float(selected.frequency[j]),
            float(selected.damping_ratio[j]),
            int(selected.n_orders[j]),
            float(selected.peak_to_noise[j]),
        )
        for j in kept
    ] + [
        _as_neighbour(d)
        for d in _dropped_for_orders(selected, rules)
        if abs(d.frequency_hz - fk) < zk * fk + d.damping_ratio * d.frequency_hz
    ]
    if not near or zk <= 0:
        return kept, None
    return kept, max(near, key=lambda p: abs(np.log(p[1] / zk)))


def _as_neighbour(d: DroppedMode) -> tuple[float, float, int, float]:
    """A candidate as :func:`_neighbours` gives one: frequency, ζ, orders, peak over noise."""
    return (d.frequency_hz, d.damping_ratio, d.orders_stable, d.peak_to_noise)


def _dropped_for_orders(selected: SelectedPoles, rules: SelectionRules) -> list[DroppedMode]:
    """The candidates dropped for their orders that a close pair may take: stable in more than
    three (as :func:`_clear_peaks` takes them), damped within the rules."""
    return [
        d
        for d in selected.dropped_modes
        if d.stage in ("selection", "unsettled")
        and "stable in" in d.reason
        and d.orders_stable > 3
        and 0.0 < d.damping_ratio < rules.max_damping_ratio
    ]


def _candidates_kept(
    selected: SelectedPoles,
    second: tuple[float, float],
    start: tuple[float, float, int, float],
    rules: SelectionRules,
    named: DroppedMode | None = None,
) -> tuple[SelectedPoles, str]:
    """The selection without the rows of the candidates a close pair's second mode (frequency
    Hz, ζ) stands for — the one its fit started from (``start``: frequency, ζ, orders, peak)
    and every other stable in more than three orders within its half-power width and its
    damping within :attr:`~racketdyn.modal.poles.SelectionRules.damping_tolerance` — which
    ``dropped_modes.csv`` would list as left out though the mode is kept, but for the row
    ``named`` (a third mode under the peak, :func:`_third_mode`); and a clause naming the
    candidate it started from ("" for a guess: the broad-mode search)."""
    f, zeta = second
    tolerance = np.log(1 + rules.damping_tolerance)

    def stands_for(d: DroppedMode) -> bool:
        if d == named:
            return False
        if d.stage not in ("selection", "unsettled") or "stable in" not in d.reason:
            return False
        if np.isclose(d.frequency_hz, start[0]) and d.orders_stable == start[2]:
            return True
        return bool(
            d.orders_stable > 3
            and abs(d.frequency_hz - f) < zeta * f
            and d.damping_ratio > 0
            and abs(np.log(d.damping_ratio / zeta)) < tolerance
        )

    gone = [d for d in selected.dropped_modes if stands_for(d)]
    if not gone:
        return selected, ""
    said = tuple(f"{d.frequency_hz:.2f} Hz," for d in gone)
    selected = replace(
        selected,
        dropped_modes=tuple(d for d in selected.dropped_modes if not stands_for(d)),
        dropped=tuple(line for line in selected.dropped if not line.startswith(said)),
    )
    started = [d for d in gone if np.isclose(d.frequency_hz, start[0])]
    if not started:
        return selected, ""
    return selected, (
        f"; the second started from the candidate at {started[0].frequency_hz:.2f} Hz "
        f"({started[0].reason})"
    )


def _weak_of_pair(
    frfs: FrfSet,
    band: tuple[float, float],
    choices: _Choices,
    peak: tuple[float, float],
    pair: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.complex128]],
    gains: NDArray[np.float64],
) -> DroppedMode:
    """The row of a close pair's weaker mode (stage ``unsettled``), naming the ``band_hz``
    (from the band's bottom to :data:`PAIR_BAND` × the peak's frequency) that keeps both where
    a fit over it does."""
    (fk, agree), (frequency, zeta, _) = peak, pair
    weak = int(np.argmin(gains))
    top = float(np.ceil(PAIR_BAND * fk / 10.0) * 10.0)
    option = f"a narrower `band_hz` round {fk:.0f} Hz did not keep it either"
    if top < band[1]:
        try:
            stab = choices.stabilisation(frfs, (band[0], top))
            there, _ = _close_pairs(
                select_poles(stab, rules=choices.rules, log=False),
                frfs,
                (band[0], top),
                choices,
                False,
            )
        except InputError:
            there = None
        if there is not None:
            close = np.abs(there.frequency - frequency[weak]) < zeta[weak] * frequency[weak]
            alike = np.abs(np.log(np.maximum(there.damping_ratio, 1e-12) / zeta[weak])) < np.log(
                1 + choices.rules.damping_tolerance
            )
            if np.any(close & alike):
                j = int(np.flatnonzero(close & alike)[0])
                option = (
                    f"`band_hz` {band[0]:g},{top:g} keeps it (there {there.frequency[j]:.2f} "
                    f"Hz, ζ {100 * there.damping_ratio[j]:.3g} %)"
                )
    return DroppedMode(
        float(frequency[weak]),
        float(zeta[weak]),
        0,
        "unsettled",
        f"a second mode under the peak of {fk:.2f} Hz (shapes' MAC {agree:.2f}) that the fit "
        f"over {band[0]:g}–{band[1]:g} Hz did not part: fitted on their own lines, the fit "
        # cut, not rounded, to two decimals: 2.97 never reads as the threshold's 3
        f"near it {np.floor(gains[weak] * 100) / 100:.2f} × better with it "
        f"(< {CLEAR_PEAK_GAIN:g}); {option}",
        fit_gain=float(gains[weak]),
    )


def _pair_fit(
    frfs: FrfSet,
    mode: tuple[float, float],
    others: Sequence[tuple[float, float]],
    spacing: float,
    max_damping: float,
    hidden: bool = False,
) -> (
    tuple[
        tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.complex128]],
        tuple[float, float],
    ]
    | None
):
    """Two poles (or more) fitted on the lines around ``mode`` started from it and ``others``
    (frequency Hz, ζ each), each FRF weighted by its noise there (:func:`_noise_weights`):
    frequencies, damping ratios and constants, the mode's first, and the last window fitted
    (Hz); None if no pair.  ``hidden``: the other is a guess (:data:`BROAD_START`), the window
    :data:`BROAD_WIDTHS` of the broader pole's width either side, and the fit stops as soon as
    its poles are not the mode (within its ``ζf``) and a broader one under its peak."""
    frequency = np.array([mode[0], *(f for f, _ in others)])
    zeta = np.array([mode[1], *(z for _, z in others)])
    widths = BROAD_WIDTHS if hidden else PAIR_WIDTHS

    def half_width() -> float:  # of the window round the mode the poles now ask for, Hz
        return max(REFINE_LINES * spacing, widths * float(np.max(2 * zeta * frequency)))

    if hidden:  # worth a nonlinear fit only if the started pair explains more than the mode
        window = (mode[0] - half_width(), mode[0] + half_width())
        weights = _noise_weights(frfs, window)
        alone = local_misfit(frfs, frequency[:1], zeta[:1], window, weights)
        if not alone >= BROAD_SCREEN * local_misfit(frfs, frequency, zeta, window, weights):
            log.debug("close pair at %.2f Hz: no broader mode under its peak", mode[0])
            return None
    half = 0.0
    for _ in range(PAIR_TRIES):
        wanted = half_width()
        if wanted <= 1.2 * half:
            break
        half = wanted
        window = (mode[0] - half, mode[0] + half)
        weights = _noise_weights(frfs, window)
        steps = BROAD_STEPS if hidden else PAIR_STEPS_PER_POLE * frequency.size
        found = fit_poles(frfs, frequency, zeta, window, weights, steps)
        if found is None:
            return None
        frequency, zeta, constants, _ = found
        if not (
            np.all((zeta > 0) & (zeta < max_damping)) and np.all(np.abs(frequency - mode[0]) < half)
        ):
            return None
        if hidden and not (
            abs(frequency[0] - mode[0]) <= mode[1] * mode[0]
            and zeta[1] > zeta[0]
            and abs(frequency[1] - frequency[0]) < float(np.sum(zeta * frequency))
        ):
            log.debug("close pair at %.2f Hz: no broader mode under its peak", mode[0])
            return None
    return (frequency, zeta, constants), (mode[0] - half, mode[0] + half)


def _noise_weights(frfs: FrfSet, window_hz: tuple[float, float]) -> NDArray[np.float64] | None:
    """One weight an FRF, one over its noise over ``window_hz`` as its coherence says (H1's
    variance ``(1 − γ²)/γ² |H|²`` over the averages, the random error of an H1 estimate:
    Bendat and Piersol, *Random Data*, ch. 9), at least
    :data:`NOISE_FLOOR` of the largest; None without coherence.  Where a few FRFs carry most of
    the noise — a racket's bed points, struck through the strings' long contact, have 30–300 ×
    its frame points' at 830 Hz — an unweighted fit follows them."""
    if frfs.coherence is None:
        return None
    near = (frfs.frequency >= window_hz[0]) & (frfs.frequency <= window_hz[1])
    coherence = np.clip(frfs.coherence[:, near], 1e-12, 1.0)
    variance = np.mean((1 - coherence) / coherence * np.abs(frfs.values[:, near]) ** 2, axis=1)
    noise = np.sqrt(variance)
    if not (noise.size and np.all(np.isfinite(noise)) and np.max(noise) > 0):
        return None
    weights: NDArray[np.float64] = 1.0 / np.maximum(noise, NOISE_FLOOR * np.max(noise))
    return weights


def _with_pair(
    selected: SelectedPoles,
    rest: NDArray[np.bool_],
    k: int,
    pair: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.complex128]],
    peaks: Sequence[float],
) -> SelectedPoles:
    """The selection of ``rest`` with a fitted pair (or three) added in place of mode ``k``
    (and the neighbours ``rest`` leaves out): the first with mode ``k``'s orders, spreads and
    peak, each other :attr:`~racketdyn.modal.poles.SelectedPoles.pair_fitted` with mode
    ``k``'s orders (no cluster of the band's orders is its own, so no count is reported for
    it), the peak of the candidate it started from (``peaks``) and no spreads (NaN), pinned
    if mode ``k`` was; the local fit's constants as their residues, in order of frequency."""
    frequency, zeta, constants = pair
    pole = pole_of(frequency, zeta)

    def two(values: NDArray[Any], others: Sequence[float]) -> NDArray[Any]:
        return np.concatenate([values[rest], [values[k], *others]])

    nan = [np.nan] * len(peaks)
    fitted, at_peak = selected.flags("pair_fitted"), selected.flags("at_peak")
    merged = replace(
        selected,
        frequency=np.concatenate([selected.frequency[rest], frequency]),
        damping_ratio=np.concatenate([selected.damping_ratio[rest], zeta]),
        pole=np.concatenate([selected.pole[rest], pole]),
        n_orders=two(selected.n_orders, [selected.n_orders[k]] * len(peaks)),
        frequency_spread_hz=two(selected.frequency_spread_hz, nan),
        damping_spread=two(selected.damping_spread, nan),
        peak_to_noise=two(selected.peak_to_noise, peaks),
        residues=np.concatenate([selected.residues[:, rest], constants], axis=1),
        pinned=np.concatenate([selected.pinned[rest], [selected.pinned[k]], [False] * len(peaks)]),
        pair_fitted=np.concatenate([fitted[rest], [False], [True] * len(peaks)]),
        at_peak=np.concatenate([at_peak[rest], [at_peak[k]], [False] * len(peaks)]),
    )
    return merged.select(np.argsort(merged.frequency, kind="stable"))


def _pin(frequency_hz: float, spacing_hz: float) -> str:
    """The words of a hint's pin, `` `pin_hz` F ``: ``F`` to the decimals that put it within a
    tenth of a line of ``frequency_hz`` (half a unit of its last digit, at most
    ``spacing_hz / 10``), so that it is the nearest candidate's wherever the next lies two
    tenths of a line away or more (one decimal put a pin a fifth of a 0.125 Hz line off its
    candidate, several lines off at finer lines)."""
    decimals = max(0, math.ceil(math.log10(5.0 / spacing_hz)))
    return f"`pin_hz` {frequency_hz:.{decimals}f}"


def _spacing(frfs: FrfSet) -> float:
    """The FRFs' line spacing (the median step), Hz."""
    return float(np.median(np.diff(frfs.frequency)))


def _still(line: str, frequency: NDArray[np.float64], spacing_hz: float) -> bool:
    """Whether the mode ``line`` names (its first frequency) is still a mode of the model.

    Within half a line: a narrow mode's refined frequency may move that far
    (:data:`racketdyn.modal.refine.MOVE_LINES`).
    """
    f = float(line.split(" Hz")[0])
    return bool(np.any(np.abs(frequency - f) <= max(0.01, MOVE_LINES * spacing_hz)))


@dataclass(frozen=True, eq=False)
class Identification:
    """Everything an identification produced.

    Attributes
    ----------
    model : ModalModel
        Frequencies, damping (window removed), mass-normalised shapes at the FRF points, names
        and kinds (neutral unless a caller named them: :meth:`renamed`).
    frfs : FrfSet
        The FRFs identified.
    stabilisation : Stabilisation
        Poles at every model order.
    selected : SelectedPoles
        The poles picked, with what was dropped and why.
    fit : ModalFit
        Modal constants, residuals, synthesised FRFs and the fit error of every FRF.
    band_hz : tuple of float
        Band used, Hz.
    band_note : str
        Why the band is what it is: given, or what set the default's bottom and top
        (:func:`default_band`).
    scaling_note : str
        How the shapes were scaled and, when they could not be mass-normalised or the
        driving point's sign was reversed, why (empty for a plain mass-normalised model).
    references : tuple of int
        The reference nodes whose FRFs the poles came from (one: the single-reference LSCF;
        several: the poly-reference LSCF, :mod:`racketdyn.modal.polyreference`).  ``frfs``
        is the set against the first, whose modal constants give the shapes.
    participation : ndarray, shape (n_references, n_modes)
        Each reference's participation in each mode relative to the shape reference's (1 for
        it): the least-squares factor ``l`` with which its LSFD modal constants (the same
        poles) are ``l`` times the shape reference's; NaN where a mode's constants are all
        zero.  One row of ones for a single reference.
    misfit : Misfit, optional
        Where the fit misses the FRFs and what that says (:mod:`racketdyn.modal.misfit`):
        the verdict on the fit error.
    noise_frfs : NoiseOnly, optional
        Each FRF's median coherence over the band and those that measured noise alone
        (:func:`racketdyn.measurement.quality.noise_only_frfs`); None where the FRFs carry no
        coherence.
    """

    model: ModalModel
    frfs: FrfSet
    stabilisation: Stabilisation
    selected: SelectedPoles
    fit: ModalFit
    band_hz: tuple[float, float]
    band_note: str = ""
    scaling_note: str = ""
    references: tuple[int, ...] = ()
    participation: NDArray[np.float64] | None = None
    misfit: Misfit | None = None
    noise_frfs: NoiseOnly | None = None

    @property
    def dropped_modes(self) -> tuple[DroppedMode, ...]:
        """Every candidate mode left out, with its evidence (``dropped_modes.csv``)."""
        return self.selected.dropped_modes

    @property
    def half_power_lines(self) -> NDArray[np.float64]:
        """Each mode's half-power width 2ζf in lines of the FRFs (Δf their median spacing).

        Under one line the lines do not resolve the peak's width: the damping rests on the
        fit's model of the peak alone (a lab's 1 Hz lines and ζ 0.013–0.068 % below 1 kHz),
        and a longer record (finer lines) is what confirms it.
        """
        return half_power_lines(self.model.frequency, self.model.damping_ratio, self.frfs.frequency)

    def write_dropped_csv(self, path: Path) -> None:
        """``dropped_modes.csv``: one row per candidate left out (:class:`DroppedMode`)."""
        with Path(path).open("w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(DroppedMode.COLUMNS)
            for row in sorted(self.dropped_modes, key=lambda d: d.frequency_hz):
                writer.writerow(row.row())

    def renamed(self, names: Sequence[str], kinds: Sequence[str]) -> Identification:
        """The same identification with its modes named (e.g. from their shapes).

        Parameters
        ----------
        names : sequence of str
            One name per mode.
        kinds : sequence of str
            One kind per mode (:data:`racketdyn.modal.model.MODE_KINDS`).

        Returns
        -------
        Identification
            A copy whose model carries the names and kinds; everything else is shared.
        """
        return replace(self, model=replace(self.model, names=tuple(names), kinds=tuple(kinds)))

    def write_modes_csv(self, path: Path) -> None:
        """``mode, frequency_hz, damping_ratio, name`` (+ kind, orders stable, fit spread); the
        orders stable empty for a close pair's second mode (fitted on the FRFs' own lines) and
        a mode pinned at the data's peak (:meth:`SelectedPoles.orders_stable`)."""
        with Path(path).open("w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(
                [
                    "mode",
                    "frequency_hz",
                    "damping_ratio",
                    "name",
                    "kind",
                    "orders_stable",
                    "frequency_spread_hz",
                ]
            )
            model, selected = self.model, self.selected
            orders = selected.orders_stable()
            for k in range(model.n_modes):
                writer.writerow(
                    [
                        k + 1,
                        f"{model.frequency[k]:.6g}",
                        f"{model.damping_ratio[k]:.6g}",
                        model.names[k],
                        model.kinds[k],
                        "" if orders[k] is None else orders[k],
                        f"{selected.frequency_spread_hz[k]:.3g}",
                    ]
                )


def identify(
    frfs: FrfSet | FrfReferences,
    band_hz: tuple[float, float] | None = None,
    max_order: int | None = None,
    pin_hz: Sequence[float] = (),
    exclude_hz: Sequence[float] = (),
    support: str = "free",
    *,
    rules: SelectionRules = SELECTION,
) -> Identification:
    """Identify a modal model of any structure from its FRFs against one reference or several.

    Any number of FRFs (one is enough for frequencies and damping ratios).  What the modal
    constants show decides what is kept and how the shapes are scaled:

    - a selected pole with no peak in the data — the fit near it hardly worse without it
      (:data:`FIT_GAIN_MIN`) — is left out, unless pinned;
    - with a driving point (an FRF at the reference node) whose constants are all positive
      (a true driving point: ``A_rr = φ_r² > 0``) the shapes are mass-normalised (eq 12); a
      mode whose driving-point constant is negative but small sits (nearly) on a node at the
      accelerometer and is left out (it cannot be normalised);
    - all clear driving-point constants negative: the response was measured against the
      hammer (a sensor in −z, or opposite sign conventions); the FRFs are taken with the
      opposite sign and normalised;
    - negative constants as large as the positive ones (:data:`STRONG_NEGATIVE`: not a true
      driving point — other directions at one node, or the sensor beside the hammer point),
      or no driving point at all: every mode kept, shapes unscaled (largest magnitude 1),
      ``model.scaling == "unscaled"``; smaller negative ones leave their mode out.

    A mode narrower than one line whose LSCF poles do not settle over the orders gets its
    frequency and damping from a local fit of its peak
    (:func:`racketdyn.modal.refine.refine_narrow_poles`; logged, ``metadata["refined"]``).

    Everything left out is in ``selected.dropped_modes`` (``dropped_modes.csv``).  A set whose
    phase rises through its resonances (the conjugate convention e^{−iωt} of some analysers)
    is conjugated first (:meth:`~racketdyn.measurement.records.FrfSet.with_usual_phase`,
    logged, ``frfs.metadata["conjugated"]``).

    Against several references (an
    :class:`~racketdyn.measurement.records.FrfReferences`, e.g. ``read_frfs(path,
    reference="all")``) the poles come from the poly-reference LSCF of them all
    (:func:`racketdyn.modal.polyreference.poly_stabilisation`), which tells apart close modes
    that the references see differently; the shapes come from one reference's modal
    constants (the first with a driving point, else the first:
    :attr:`~racketdyn.measurement.records.FrfReferences.shape_reference`), and every
    reference's participation is kept (``participation``).

    Parameters
    ----------
    frfs : FrfSet or FrfReferences
        FRFs of the points against one reference, or against several (2-D or 3-D locations,
        every point and the
        reference with coordinates, or none: a model without coordinates,
        ``model.has_locations`` False; some without them is an InputError naming
        ``--geometry``); an exponential window recorded on the set is taken off the damping.
    band_hz : tuple of float, optional
        Band to identify in, Hz (default :func:`default_band`: from below the data's first
        flexible mode, at most 40 Hz, to the FRFs' bandwidth);
        a top within the UFF header's 6-digit rounding of the last line is the last line.
    max_order : int, optional
        Highest model order of the stabilisation diagram: the denominator's degree.  Default
        60 against one reference (:data:`DEFAULT_ORDER`), raised to :data:`ORDERS_PER_PEAK`
        times the band's clear peaks (:func:`racketdyn.modal.peaks.resolved_peaks`) up to
        :data:`MAX_RAISED_ORDER` (logged, ``metadata["orders_note"]``); 30 against several
        (:data:`racketdyn.modal.polyreference.DEFAULT_MAX_ORDER`: each order brings one pole
        per reference, and higher orders split modes into fragments), raised alike when the
        peaks ask for more poles (:data:`ORDERS_PER_PEAK` a peak over the references, up to
        :data:`MAX_RAISED_ORDER` poles).  An order given that the peaks outnumber is kept and
        the order that would fit them said.
    pin_hz, exclude_hz : sequence of float
        Modes to force in or leave out, by approximate frequency, Hz.
    support : str
        Support the structure was tested on (``free``, ``hand`` …), recorded on the model.
    rules : SelectionRules
        The rules of the automatic pole selection (default :data:`SELECTION`, equal to
        :data:`racketdyn.modal.poles.DEFAULT_SELECTION`), followed by every selection made here
        (:func:`racketdyn.modal.poles.select_poles`).

    Returns
    -------
    Identification
        The model's modes are named ``"mode k (f Hz)"``, of kind ``unknown``; its
        ``model`` is a :class:`~racketdyn.modal.model.ModalModel` that the impact models take
        as it is (``modal_model=``) once its shapes are mass-normalised and at coordinates of
        the racket's face (docs/modal.md, "From FRFs to a model the impact models use").

    Examples
    --------
    >>> import numpy as np
    >>> from racketdyn.modal import SelectionRules, identify
    >>> from racketdyn.testing import beam_frfs
    >>> test = beam_frfs(np.linspace(0.0, 0.8, 9), reference_s=0.0, noise=0.01, seed=1)
    >>> rules = SelectionRules(min_fraction=0.5)  # stable in half the orders at least
    >>> model = identify(test.frfs, band_hz=(40.0, 1000.0), rules=rules).model
    >>> np.round(model.frequency, 1)
    array([ 65.4, 180.3, 353.5, 584.4, 873. ])
    """
    require_rules("identify", rules)
    references = _references(frfs)
    if references is not None:
        frfs = references.shape_reference
    elif isinstance(frfs, FrfReferences):
        frfs = frfs.sets[0]
    if not np.isnan(frfs.locations).all():  # none: a model without coordinates
        frfs.require_locations("identification (the mode shapes at the points)")
    frfs = frfs.with_usual_phase()  # a set of the conjugate convention (read_frfs does it too)
    if band_hz is None:
        default, band_note = _default_band(frfs)
        band = _checked_band(frfs, default)
    else:
        band, band_note = _checked_band(frfs, band_hz), "given"
    peaks = resolved_peaks(frfs, band)
    max_order, orders_note = _orders_for(len(peaks), max_order, references, frfs, band)
    if orders_note:
        log.warning("%s", orders_note)
    choices = _Choices(pin_hz, exclude_hz, rules, max_order, references)
    stab = choices.stabilisation(frfs, band)
    try:
        selected, kept, refined = _selected_poles(stab, frfs, band, choices)
    except NoModeError as error:
        unsettled = () if error.selected is None else error.selected.dropped_modes
        cause = _no_mode_cause(peaks, max_order, frfs, band, unsettled)
        raise InputError(f"{error.head}. {cause}") from None
    fitted, no_peak = _with_peaks_only(frfs, selected, band, references, peaks)
    scaled = _scaled(fitted, band)
    fitted, note = scaled.fitted, scaled.note
    late = [*no_peak, *scaled.on_node]
    for row in late:
        log.warning("%.2f Hz left out: %s", row.frequency_hz, row.reason)
    if note:
        log.warning("%s: %s", fitted.frfs.source, note)
    frfs, selected, fit = fitted.frfs, fitted.selected, fitted.fit
    if low := _peaks_low(peaks, band, _peaks_without(peaks, _kept_widths(selected), frfs)):
        log.warning("the %s", low)
        orders_note = "; ".join(filter(None, (orders_note, f"the {low}")))
    unexplained = _unexplained_peaks(peaks, selected, late, frfs)
    peaks_note = _unexplained_words(unexplained, len(peaks)) if unexplained else ""
    if peaks_note:
        log.warning("%s", peaks_note)
    noise = noise_only_frfs(frfs, band)
    if noise is not None and noise.noise_nodes:
        log.warning("%s: %s", frfs.source, noise.sentence())
    where = misfit(
        frfs,
        fit,
        _left_out_in_data((*selected.dropped_modes, *late), selected, frfs),
        () if noise is None else noise.noise_nodes,
    )
    mass = scaled.scaling == "mass"
    shapes = mass_normalised_shapes(frfs, fit) if mass else unscaled_shapes(fit)
    names = tuple(f"mode {k + 1} ({f:.1f} Hz)" for k, f in enumerate(selected.frequency))
    dropped = (*selected.dropped, *(f"{d.frequency_hz:.2f} Hz: {d.reason}" for d in late))
    model = ModalModel(
        frequency=selected.frequency,
        damping_ratio=selected.damping_ratio,
        locations=frfs.locations,
        mode_shapes=shapes,
        names=names,
        kinds=("unknown",) * len(names),
        support=support,
        source=f"identified from {frfs.source}",
        metadata={
            "band_hz": list(band),
            "band_note": band_note,
            "max_order": max_order,
            "peaks_in_band": len(peaks),
            "orders_note": orders_note,
            "unexplained_peaks_hz": unexplained,
            "peaks_note": peaks_note,
            "references": [frfs.reference_node]
            if references is None
            else [
                frfs.reference_node,
                *(r for r in references.references if r != frfs.reference_node),
            ],
            **_fit_record(fitted, note),
            "fit_error_median": where.median_error,  # the verdict's: the noise FRFs' left out
            "misfit": where.record(),
            **({} if noise is None else {"noise_frfs": noise.record()}),
            **_left_out_record(fitted, kept, refined, late),
        },
        scaling=scaled.scaling,
    )
    log.info("identified %d modes in %g–%g Hz", model.n_modes, *band)
    selected = replace(selected, dropped=dropped, dropped_modes=(*selected.dropped_modes, *late))
    order = model.metadata["references"]
    sets = [frfs] if references is None else [frfs, *(references.against(r) for r in order[1:])]
    participation = _participation(fit, [s.with_usual_phase() for s in sets], band)
    if frfs.metadata.get("sign_reversed"):  # the others as read, against the set as read
        participation[1:] *= -1
    return Identification(
        model,
        frfs,
        stab,
        selected,
        fit,
        band,
        band_note,
        note,
        tuple(order),
        participation,
        where,
        noise,
    )


def _orders_for(
    n_peaks: int,
    max_order: int | None,
    references: FrfReferences | None,
    frfs: FrfSet,
    band: tuple[float, float],
) -> tuple[int, str]:
    """The highest model order, and a line when the band's ``n_peaks`` clear peaks ask for
    more than it (:data:`ORDERS_PER_PEAK` poles each) ("" if not).

    The default order is raised to fit them, up to :data:`MAX_RAISED_ORDER` poles and below
    half the band's lines, and lowered to what the lines hold where they hold less (a stepped
    sine's 41 lines round one mode); an order given is kept and the order that would fit them
    said.  Against several references each order brings one pole a reference: the default
    (30) is raised to ``ORDERS_PER_PEAK × n_peaks / n_references``, at most
    ``MAX_RAISED_ORDER / n_references`` (45 synthetic modes against two references: 3 kept at
    30, every one at 60).
    """
    n_refs = 1 if references is None else len(references.references)
    need = -(-ORDERS_PER_PEAK * n_peaks // n_refs)
    given = max_order is not None
    default = DEFAULT_ORDER if references is None else DEFAULT_MAX_ORDER
    order = max_order if max_order is not None else default
    lines, fitting = _orders_of_lines(frfs, band)
    if not given and fitting < order:
        # a short record of lines (a stepped sine round one mode: 41 lines) takes the orders
        # its lines allow, not a default it cannot hold
        few = "" if need <= fitting else f", too few for its {n_peaks} clear peaks"
        return fitting, (
            f"`max_order` lowered from {order} to {fitting}: the band {band[0]:g}–{band[1]:g} "
            f"Hz holds {lines} lines (an order takes two){few}"
        )
    if need <= order:
        return order, ""
    fits = f"{ORDERS_PER_PEAK} orders a peak" + (
        "" if n_refs == 1 else f" over {n_refs} references"
    )
    peaks = f"the band {band[0]:g}–{band[1]:g} Hz holds {n_peaks} clear peaks of the data"
    if given:
        return order, (
            f"{peaks}, more than `max_order` {order} can fit ({fits}): give `max_order` {need} "
            "or narrow `band_hz`"
        )
    raised = min(need, MAX_RAISED_ORDER // n_refs, fitting)
    if raised <= order:
        return order, (
            f"{peaks}, more than `max_order` {order} can fit ({fits}); too few lines for more: "
            "narrow `band_hz`"
        )
    short = (
        "" if raised == need else f"; `max_order` {need} would fit them all, or narrow `band_hz`"
    )
    return raised, f"`max_order` raised from {order} to {raised}: {peaks} ({fits}){short}"


def _orders_of_lines(frfs: FrfSet, band: tuple[float, float]) -> tuple[int, int]:
    """The band's lines and the highest model order they hold: an order takes two lines
    (:func:`racketdyn.modal.poles.stabilisation` needs more than ``2 · max_order``)."""
    lines = int(np.count_nonzero((frfs.frequency >= band[0]) & (frfs.frequency <= band[1])))
    return lines, (lines - 1) // 2


def _left_out_in_data(
    rows: Sequence[DroppedMode], selected: SelectedPoles, frfs: FrfSet
) -> list[float]:
    """Frequencies (Hz) of left-out candidates that stand in the data, for the misfit to name
    with its worst frequencies (:func:`racketdyn.modal.misfit.misfit`, ``pin_hz`` keeps one):
    rows of stage ``unsettled`` or ``edge`` (a clear peak of the data stands there), and rows
    left out for their orders whose modal peak stands :data:`~racketdyn.modal.peaks.PEAK_NOISE`
    times over the FRFs' noise within the hammer's force band — a mode under a line wide
    stabilises in a few orders only (pyLMS's 78.6 Hz, ζ 0.15 % on 1 Hz lines: 3 of 60 orders,
    687 × the noise, where the misfit said the model lacked a mode at 79 Hz), while a pole of
    the noise stands 2-4 times over it — and apart from every kept mode (their half-power
    widths and :data:`ONE_PEAK_LINES` lines apart, as :func:`_named_rows` keeps them): one
    peak, one mode.
    """
    width = 2 * np.maximum(selected.damping_ratio, 0.0) * selected.frequency
    one_peak = ONE_PEAK_LINES * _spacing(frfs)

    def apart(d: DroppedMode) -> bool:
        own = 2 * max(d.damping_ratio, 0.0) * d.frequency_hz
        near = np.abs(selected.frequency - d.frequency_hz) < np.maximum(width + own, one_peak)
        return not bool(np.any(near))

    return [
        d.frequency_hz
        for d in rows
        if d.stage in ("unsettled", "edge")
        or (
            d.stage == "selection"
            and d.reason.startswith("stable in")
            and d.peak_to_noise >= PEAK_NOISE
            and not _above_force(d.frequency_hz, frfs)
            and apart(d)
        )
    ]


def _unexplained_peaks(
    peaks: list[float], selected: SelectedPoles, late: Sequence[DroppedMode], frfs: FrfSet
) -> list[float]:
    """The band's clear peaks (:func:`racketdyn.modal.peaks.resolved_peaks`) with no kept
    mode and no named row (any stage but ``selection``) within its half-power width ``2ζf``
    or :data:`ONE_PEAK_LINES` lines, Hz."""
    rows = [
        (d.frequency_hz, 2 * abs(d.damping_ratio) * d.frequency_hz)
        for d in (*selected.dropped_modes, *late)
        if d.stage != "selection"
    ]
    return _peaks_without(peaks, [*_kept_widths(selected), *rows], frfs)


def _kept_widths(selected: SelectedPoles) -> list[tuple[float, float]]:
    """Each kept mode's frequency and half-power width ``2ζf``, Hz."""
    return [
        (float(f), 2 * abs(float(z)) * float(f))
        for f, z in zip(selected.frequency, selected.damping_ratio, strict=True)
    ]


def _peaks_without(
    peaks: list[float], near: list[tuple[float, float]], frfs: FrfSet
) -> list[float]:
    """The peaks with none of ``near`` (frequency, width) within the width or
    :data:`ONE_PEAK_LINES` lines, Hz."""
    one_peak = ONE_PEAK_LINES * _spacing(frfs)
    return [p for p in peaks if not any(abs(p - f) <= max(w, one_peak) for f, w in near)]


def _unexplained_words(unexplained: list[float], n_peaks: int) -> str:
    """The line saying the clear peaks :func:`_unexplained_peaks` found."""
    listed = ", ".join(f"{f:.1f}" for f in unexplained)
    return (
        f"{len(unexplained)} of the band's {n_peaks} clear peaks of the data have no mode and "
        f"no row: {listed} Hz; `pin_hz` at one, or a narrower `band_hz` round them, may keep "
        "them"
    )


def _peaks_low(
    peaks: list[float], band: tuple[float, float], lost: list[float] | None = None
) -> str:
    """A line when the band's clear peaks all lie below :data:`PEAK_TOP_SHARE` of it (the
    lines above them noise whose poles take the orders) and some have no mode, else "".

    ``lost`` are the peaks with no kept mode (None: no mode found, all of them).  Where every
    peak has its mode the line is not said: the band it gives moved a synthetic set's ten
    kept modes by 5e-5 in frequency and 2.5 % of their damping, and lost a real file's one
    mode (docs/develop.md, issue 25, "Sixteenth session: the low-peaks note")."""
    if not peaks or peaks[-1] >= band[0] + PEAK_TOP_SHARE * (band[1] - band[0]):
        return ""
    if lost is not None and not lost:
        return ""
    one = len(peaks) == 1
    if lost is None:
        some = ""
    elif one:
        some = ", with no mode"
    else:
        some = f", and {len(lost)} of them {'has' if len(lost) == 1 else 'have'} no mode"
    return (
        f"band's {len(peaks)} clear peak{'' if one else 's'} of the data "
        f"{'lies' if one else 'all lie'} below {peaks[-1]:.0f} Hz, in its "
        f"lowest {PEAK_TOP_SHARE:.0%}{some}; the lines above {'it' if one else 'them'} are "
        f"noise whose poles take the orders: give `band_hz` {band[0]:g},{1.2 * peaks[-1]:.0f}"
    )


def _no_mode_cause(
    peaks: list[float],
    max_order: int,
    frfs: FrfSet,
    band: tuple[float, float],
    rows: tuple[DroppedMode, ...] = (),
) -> str:
    """Why no mode was found: the data's peaks the rules named (``unsettled`` ``rows``, each
    with the pin that keeps it), else from the band's clear peaks (:func:`_orders_for`'s
    count): too many for the orders, all low in a band of noise above them, none at all, or a
    fit that does not settle on them; widening the band is advised only for a band short of
    the data's that holds no clear peak."""
    named = [f"{d.frequency_hz:.2f} Hz, {d.reason}" for d in rows if d.stage == "unsettled"]
    named_line = "The band holds " + "; ".join(named) if named else ""
    n = len(peaks)
    need = ORDERS_PER_PEAK * n
    holds = f"The band holds {plural(n, 'clear peak')} of the data"
    if n and need > max_order:
        return " ".join(
            filter(
                None,
                (
                    f"{holds}, more than `max_order` {max_order} can fit ({ORDERS_PER_PEAK} "
                    f"orders a peak): give `max_order` {need} or narrow `band_hz`.",
                    named_line,
                ),
            )
        ).removesuffix(".")
    if named_line:
        return named_line
    if low := _peaks_low(peaks, band):
        return f"The {low} or raise `max_order`"
    if n:
        # no higher order where the band's lines hold no more (a stepped sine's 41 lines)
        higher = "raise `max_order` or " if max_order < _orders_of_lines(frfs, band)[1] else ""
        pins = " or ".join(_pin(p, _spacing(frfs)) for p in peaks[:3])
        return (
            f"{holds}, yet no pole of the fit settles over the orders: {higher}pin a mode ({pins})"
        )
    whole = band[0] <= frfs.frequency[1] and band[1] >= frfs.frequency[-1]
    where = "The band, the data's whole band," if whole else "The band"
    wider = "" if whole else "widen `band_hz`, "
    higher = "raise `max_order` or " if max_order < _orders_of_lines(frfs, band)[1] else ""
    # a peak about as wide as the band (a stepped sine round one mode) stands no factor above
    # the band's ends, yet the data's largest value inside the band is where a pin keeps it
    inside = np.flatnonzero((frfs.frequency >= band[0]) & (frfs.frequency <= band[1]))
    level = np.abs(frfs.values[:, inside]).sum(axis=0)
    top = int(np.argmax(level))
    noise = float(np.sqrt(second_difference_noise(frfs.values[:, inside])).sum())
    pin = (
        f"{_pin(float(frfs.frequency[inside[top]]), _spacing(frfs))}, the data's largest peak"
        if 0 < top < inside.size - 1 and level[top] >= PEAK_NOISE * noise
        else "`pin_hz`"
    )
    return (
        f"{where} holds no clear peak of the data above its noise: {wider}{higher}pin a mode "
        f"({pin})"
    )


def _references(frfs: FrfSet | FrfReferences) -> FrfReferences | None:
    """Several references to fit together, or None (one set, or references of one set)."""
    if isinstance(frfs, FrfReferences):
        if len(frfs.sets) > 1:
            return FrfReferences(tuple(s.with_usual_phase() for s in frfs.sets))
        return None
    if not isinstance(frfs, FrfSet):
        raise InputError(
            f"identify: `frfs` must be an FrfSet or FrfReferences (got {type(frfs).__name__}); "
            "read them with racketdyn.io.read_frfs"
        )
    return None


def _participation(
    fit: ModalFit, sets: Sequence[FrfSet], band: tuple[float, float]
) -> NDArray[np.float64]:
    """Each set's modal constants (the same poles) as a factor of the first's, per mode."""
    shapes = fit.constants  # (n_points, n_modes), the first set's
    norm = np.sum(shapes**2, axis=0)
    rows = [np.ones(shapes.shape[1])]
    for other in sets[1:]:
        constants = fit_modal_constants(other, fit.poles, band).constants
        with np.errstate(invalid="ignore", divide="ignore"):
            rows.append(np.where(norm > 0, np.sum(shapes * constants, axis=0) / norm, np.nan))
    return np.asarray(rows, dtype=float)


def _within_band(choices: _Choices, band: tuple[float, float]) -> None:
    """Refuse a pin or an exclusion outside the band, quoted as the console quotes it (the
    fitted lines' own ends, 41.5039 Hz for a 40 Hz band, are checked by select_poles)."""
    for name, values in (("pin_hz", choices.pin_hz), ("exclude_hz", choices.exclude_hz)):
        outside = [f for f in values if not band[0] <= f <= band[1]]
        if outside:
            raise InputError(
                f"`{name}`: {outside[0]:g} Hz lies outside the band {band[0]:g}–{band[1]:g} "
                f"Hz; give `band_hz` a band that holds it"
            )


def _selected_poles(
    stab: Stabilisation, frfs: FrfSet, band: tuple[float, float], choices: _Choices
) -> tuple[SelectedPoles, list[str], list[str]]:
    """The poles selected, and the clear peaks kept and the narrow modes refined (logged).

    The automatic selection, the edge's clear modes and electrical lines named, clear peaks
    stable in too few orders kept, close pairs under one peak fitted on their own lines, peaks
    the fit missed found, narrow modes refined.  A selection that keeps no mode goes through
    the same rules (a band's one clear peak whose damping settles in too few orders was lost
    unnamed, and a pin at it refused: SigLab case 2 in 40-231 Hz); raises
    :class:`~racketdyn.modal.poles.NoModeError` if none keeps one, with the data's peaks they
    named (``unsettled`` rows) as ``selected``'s rows.
    """
    _within_band(choices, band)
    choices, at_peaks = _peak_pins(stab, frfs, choices)
    none: NoModeError | None = None
    try:
        selected = select_poles(stab, choices.pin_hz, choices.exclude_hz, rules=choices.rules)
    except NoModeError as error:
        if error.selected is None:
            raise
        none, selected = error, error.selected
    selected = _named_rows(_edge_modes(selected, frfs, band, choices), frfs)
    selected, kept = _clear_peaks(selected, stab, frfs, band, choices)
    selected = _wandering_peaks(selected, stab, frfs, band, choices)
    selected, pairs = _close_pairs(selected, frfs, band, choices)
    selected = _missed_peaks(selected, stab, frfs, band, choices)
    selected = _peaks_either_side(selected, stab, frfs, band, choices)
    selected = replace(selected, dropped_modes=_beyond_force(selected.dropped_modes, frfs))
    selected, refined = refine_narrow_poles(frfs, selected)
    for line in refined:
        log.info("refined %s", line)
    selected, pinned = _with_peak_modes(selected, at_peaks, stab, frfs)
    if none is not None and selected.n_modes == 0:
        raise NoModeError(none.head, "", selected)
    kept = [*kept, *pairs, *pinned]
    for line in kept:
        log.warning("kept %s", line)
    for row in selected.dropped_modes:
        if row.stage in ("edge", "unsettled"):
            log.warning("%.1f Hz left out: %s", row.frequency_hz, row.reason)
        elif row.stage == "line":
            log.info("%.2f Hz left out: %s", row.frequency_hz, row.reason)
    return selected, kept, refined


@dataclass(frozen=True, eq=False)
class _Fitted:
    """The FRFs, the poles kept and their modal constants, with each mode's fit gain."""

    frfs: FrfSet
    selected: SelectedPoles
    fit: ModalFit
    gain: NDArray[np.float64]

    def keeping(self, modes: NDArray[np.bool_], band: tuple[float, float]) -> _Fitted:
        """Only some modes, their constants fitted again."""
        selected = self.selected.select(modes)
        fit = fit_modal_constants(self.frfs, selected.pole, band)
        return _Fitted(self.frfs, selected, fit, self.gain[modes])


def _with_peaks_only(
    frfs: FrfSet,
    selected: SelectedPoles,
    band: tuple[float, float],
    references: FrfReferences | None = None,
    peaks: Sequence[float] = (),
) -> tuple[_Fitted, list[DroppedMode]]:
    """The modal constants of the poles with a peak in the data (:data:`FIT_GAIN_MIN`, or
    pinned), and the rows of those without.  Against several references a mode has a peak
    if the FRFs of any reference hold it (its best gain over them).

    A pole left out so whose half-power width (at least :data:`ONE_PEAK_LINES` lines) holds
    one of the band's clear ``peaks`` (:func:`racketdyn.modal.peaks.resolved_peaks`) that no
    kept mode holds does not say "no peak": its row names the ``pin_hz`` at that peak (a
    pinned mode is kept whatever its gain; the nearest such row names it).  Badiane's spruce
    plate's 1370.5 Hz, a clear peak, had only two poles near it whose constants the fit
    hardly needed (1365.7 Hz, 1.25 ×; 1397.3 Hz, 1.43 ×), and was lost under their "no peak in
    the data".

    A mode without a peak that the selection kept over a neighbour of one peak with it (a
    ``merged`` row, :attr:`~racketdyn.modal.poles.DroppedMode.merged_into_hz`) gives its place
    to that neighbour when the neighbour has the peak: the merge keeps the cluster stable in
    more orders, which on a dense, lightly damped structure (Badiane's spruce plate: 1366.84
    Hz kept over 1370.78 Hz) may be a broad pole the data do not hold — the peak was left
    with no mode, and the neighbour's row named a mode the model did not have."""

    def gains(poles: NDArray[np.complex128]) -> tuple[ModalFit, NDArray[np.float64]]:
        fit = fit_modal_constants(frfs, poles, band)
        gain = fit_gain(frfs, fit)
        for other in () if references is None else references.sets:
            if other.reference_node != frfs.reference_node:
                other_fit = fit_modal_constants(other, poles, band)
                gain = np.maximum(gain, fit_gain(other, other_fit))
        return fit, gain

    fit, gain = gains(selected.pole)
    selected, fit, gain, placed = _merged_in_place(selected, fit, gain, gains)
    real = (gain >= FIT_GAIN_MIN) | selected.pinned
    if not real.any():
        real = gain == gain.max()  # the best of them rather than nothing: select_poles chose
    at_peak = _peaks_of_poles_left_out(frfs, selected, real, peaks)
    no_peak = []
    for k in np.flatnonzero(~real):
        # cut, not rounded, to two decimals: 1.49 never reads as the threshold's 1.5
        only = f"{np.floor(gain[k] * 100) / 100:.2f} × better with it (< {FIT_GAIN_MIN:g})"
        peak = at_peak.get(int(k))
        reason = (
            f"no peak in the data: the fit near it is only {only}"
            if peak is None
            else f"the data's clear peak at {peak:.1f} Hz has no kept mode, and the fit near "
            f"this pole is only {only}; {_pin(peak, _spacing(frfs))} keeps a mode there"
        )
        no_peak.append(_dropped(selected, int(k), reason, gain=gain[k]))
    fitted = _Fitted(frfs, selected, fit, gain)
    return (fitted if real.all() else fitted.keeping(real, band)), [*placed, *no_peak]


def _peaks_of_poles_left_out(
    frfs: FrfSet,
    selected: SelectedPoles,
    real: NDArray[np.bool_],
    peaks: Sequence[float],
) -> dict[int, float]:
    """The clear ``peaks`` no kept mode (``real``) holds, each by the nearest pole left out
    whose half-power width ``2ζf`` (at least :data:`ONE_PEAK_LINES` lines) holds it: {the
    pole's index: the peak, Hz} (:func:`_with_peaks_only`)."""
    one_peak = ONE_PEAK_LINES * _spacing(frfs)
    width = np.maximum(2 * np.abs(selected.damping_ratio) * selected.frequency, one_peak)
    held: dict[int, float] = {}
    for peak in peaks:
        distance = np.abs(selected.frequency - peak)
        if np.any(real & (distance <= width)):
            continue
        near = np.flatnonzero(~real & (distance <= width))
        if near.size:
            held[int(near[np.argmin(distance[near])])] = float(peak)
    return held


def _in_place_of(
    selected: SelectedPoles,
    k: int,
    row: DroppedMode,
    poles: NDArray[np.complex128],
    constants: NDArray[Any],
) -> SelectedPoles:
    """The selection with mode ``k`` replaced by the dropped ``row`` (its poles ``poles``):
    the row's own orders and peak, no spreads (NaN), ``constants`` as its residues."""

    def at_k(values: NDArray[Any], value: object) -> NDArray[Any]:
        out = values.copy()
        out[k] = value
        return out

    residues = selected.residues
    if residues.shape[0] == constants.shape[0]:  # stacked references keep the LSCF's
        residues = at_k(residues.T, constants).T
    return replace(
        selected,
        frequency=at_k(selected.frequency, row.frequency_hz),
        damping_ratio=at_k(selected.damping_ratio, row.damping_ratio),
        pole=poles,
        n_orders=at_k(selected.n_orders, row.orders_stable),
        frequency_spread_hz=at_k(selected.frequency_spread_hz, np.nan),
        damping_spread=at_k(selected.damping_spread, np.nan),
        peak_to_noise=at_k(selected.peak_to_noise, row.peak_to_noise),
        residues=residues,
    )


def _merged_in_place(
    selected: SelectedPoles,
    fit: ModalFit,
    gain: NDArray[np.float64],
    gains: Callable[[NDArray[np.complex128]], tuple[ModalFit, NDArray[np.float64]]],
) -> tuple[SelectedPoles, ModalFit, NDArray[np.float64], list[DroppedMode]]:
    """Each mode without a peak (not pinned) replaced by the ``merged`` row merged into it
    that has one (:data:`FIT_GAIN_MIN`; the one stable in most orders first): the selection,
    fit and gains after, and the rows of the modes replaced.  The replacement keeps its own
    orders and peak, no spreads (NaN) and the fit's constants as its residues."""
    placed: list[DroppedMode] = []
    rows = list(selected.dropped_modes)
    for k in np.flatnonzero((gain < FIT_GAIN_MIN) & ~selected.pinned):
        f_k = float(selected.frequency[k])
        partners = sorted(
            (d for d in rows if d.stage == "merged" and abs(d.merged_into_hz - f_k) < 1e-6 * f_k),
            key=lambda d: -d.orders_stable,
        )
        for d in partners:
            poles = selected.pole.copy()
            poles[k] = pole_of(d.frequency_hz, d.damping_ratio)
            trial_fit, trial = gains(poles)
            if trial[k] < FIT_GAIN_MIN:  # said: the mode its row names is left out too
                rows[rows.index(d)] = replace(
                    d,
                    fit_gain=float(trial[k]),
                    reason=f"{d.reason}; {f_k:.2f} Hz was then left out (no peak in the "
                    f"data), and in its place the fit near this one is only "
                    f"{np.floor(trial[k] * 100) / 100:.2f} × better with it (< {FIT_GAIN_MIN:g})",
                )
                continue
            placed.append(
                _dropped(
                    selected,
                    int(k),
                    f"no peak in the data: the fit near it is only "
                    f"{np.floor(gain[k] * 100) / 100:.2f} × better with it (< {FIT_GAIN_MIN:g}); "
                    f"{d.frequency_hz:.2f} Hz, merged into it as one peak, holds the peak (the "
                    f"fit near it {trial[k]:.2g} × better with it): kept in its place",
                    gain=gain[k],
                )
            )
            log.warning(
                "kept %.2f Hz in place of %.2f Hz, the mode it was merged into, which has no "
                "peak in the data (the fit near it %.2f × better with it, < %g; %.2g × with "
                "%.2f Hz)",
                d.frequency_hz,
                f_k,
                np.floor(gain[k] * 100) / 100,
                FIT_GAIN_MIN,
                trial[k],
                d.frequency_hz,
            )
            selected = _in_place_of(selected, int(k), d, poles, trial_fit.constants[:, k])
            rows = [r for r in rows if r is not d]
            kept_line = f"{d.frequency_hz:.2f} Hz, "
            selected = replace(
                selected,
                dropped=tuple(
                    line
                    for line in selected.dropped
                    if not (line.startswith(kept_line) and "merged into it" in line)
                ),
            )
            fit, gain = trial_fit, trial
            break
    selected = replace(selected, dropped_modes=tuple(rows))
    if placed:
        order = np.argsort(selected.frequency, kind="stable")
        selected = selected.select(order)
        fit, gain = gains(selected.pole)
    return selected, fit, gain, placed


@dataclass(frozen=True, eq=False)
class _Scaled:
    """How the shapes are scaled (``mass`` or ``unscaled``) and why, with the modes left out
    on a node at the accelerometer."""

    fitted: _Fitted
    scaling: str
    note: str
    on_node: tuple[DroppedMode, ...] = ()


def _scaled(fitted: _Fitted, band: tuple[float, float]) -> _Scaled:
    """Mass-normalisable from the driving point, or unscaled and why (:func:`identify`)."""
    frfs = fitted.frfs
    driving = frfs.driving_point
    transmissibility = frfs.metadata.get("transmissibility")
    if transmissibility:
        return _Scaled(
            fitted,
            "unscaled",
            f"a transmissibility ({transmissibility}, a base-excited shaker test or two "
            "sensors): the poles are the structure's, but with no force the shapes are "
            "unscaled; measure the force (an impact hammer, or a force cell at the shaker's "
            "stinger) for mass-normalised shapes",
        )
    if driving is None:
        return _Scaled(
            fitted,
            "unscaled",
            f"no driving point (no FRF at the reference node {frfs.reference_node}): shapes "
            "unscaled; strike the reference node too for mass-normalised shapes",
        )
    ratio = fitted.fit.constants[driving] / np.abs(fitted.fit.constants).max(axis=0)
    clear = np.abs(ratio) >= WEAK_DRIVING_POINT
    note = ""
    if clear.any() and np.all(ratio[clear] < 0):
        fitted, ratio = _sign_reversed(fitted, band), -ratio
        note = (
            f"every mode's driving-point constant (node {frfs.reference_node}) was "
            "negative: the response is measured against the hammer (a sensor in −z or "
            "opposite sign conventions); the FRFs are taken with the opposite sign"
        )
    at_driving = fitted.fit.constants[driving]
    kept_scale = float(at_driving[clear & (ratio > 0)].max(initial=0.0))
    strong = clear & (ratio < 0) & (-at_driving >= STRONG_NEGATIVE * kept_scale)
    if kept_scale > 0 and strong.any():
        negative = ", ".join(f"{f:.1f}" for f in fitted.selected.frequency[strong])
        note = (
            f"node {frfs.reference_node} is not a true driving point: modes at {negative} "
            "Hz have clearly negative constants there (φ_r² cannot be): the hammer and the "
            "sensor differ in direction or place, or those modes are mis-fitted (two close "
            "modes fitted as a wrong pair: a narrower `band_hz` round them tells); every mode "
            "kept, shapes unscaled"
        )
        return _Scaled(fitted, "unscaled", note)
    if not clear.any():
        note = (
            f"every mode is weak at the driving point (node {frfs.reference_node}): shapes "
            "unscaled; move the accelerometer where the modes move"
        )
        return _Scaled(fitted, "unscaled", note)
    return _mass_normalisable(fitted, ratio, note, band)


def _sign_reversed(fitted: _Fitted, band: tuple[float, float]) -> _Fitted:
    """The FRFs taken with the opposite sign (measured against the hammer), fitted again."""
    frfs = fitted.frfs
    frfs = replace(frfs, values=-frfs.values, metadata={**frfs.metadata, "sign_reversed": True})
    fit = fit_modal_constants(frfs, fitted.selected.pole, band)
    return _Fitted(frfs, fitted.selected, fit, fitted.gain)


def _mass_normalisable(
    fitted: _Fitted, ratio: NDArray[np.float64], note: str, band: tuple[float, float]
) -> _Scaled:
    """Mass-normalised shapes, the modes on a node at the accelerometer (a driving-point
    constant ``ratio`` of their largest ≤ 0) left out."""
    on_node = ratio <= 0
    rows = tuple(
        _dropped(
            fitted.selected,
            int(k),
            "on a node at the accelerometer (driving-point constant "
            f"{ratio[k]:.2g} of its largest): cannot be mass-normalised; move the "
            "accelerometer off its node",
            gain=fitted.gain[k],
            ratio=ratio[k],
        )
        for k in np.flatnonzero(on_node)
    )
    if on_node.any():
        fitted = fitted.keeping(~on_node, band)
    return _Scaled(fitted, "mass", note, rows)


def _fit_record(fitted: _Fitted, note: str) -> dict[str, Any]:
    """The model's metadata on the data and the fit."""
    frfs = fitted.frfs
    return {
        "exponential_window_s": frfs.exponential_window_s,
        "nodes": list(frfs.nodes),
        "reference_node": frfs.reference_node,
        "directions": frfs.metadata.get("directions") or {},
        "design_condition_number": fitted.fit.condition_number,
        "orders_stable": fitted.selected.orders_stable(),
        "scaling_note": note,
    }


def _left_out_record(
    fitted: _Fitted, kept: list[str], refined: list[str], late: list[DroppedMode]
) -> dict[str, Any]:
    """The model's metadata on what was kept, refined and dropped (substantial drops only)."""
    frequency, spacing = fitted.selected.frequency, _spacing(fitted.frfs)
    return {
        "kept": [line for line in kept if _still(line, frequency, spacing)],
        "refined": [line for line in refined if _still(line, frequency, spacing)],
        "dropped": [
            f"{d.frequency_hz:.2f} Hz: {d.reason}"
            for d in (*fitted.selected.dropped_modes, *late)
            if d.stage == "constants" or d.orders_stable > 3
        ],
    }


def fit_gain(
    frfs: FrfSet, fit: ModalFit, weights: NDArray[np.float64] | None = None
) -> NDArray[np.float64]:
    """How much worse the fit is near each mode without it: the peak each mode has in the data.

    Over the lines within three half-power bandwidths (``6 ζ f``, at least five lines) of the
    mode, every FRF: ``‖residual + the mode's term‖ / ‖residual‖``, the residual the smaller
    of the fit's and that of the best real constants turned by one phase common to every FRF
    (the peak's evidence whatever the phase a delay gives its constants).  A mode of the data
    scores its peak over the misfit (tens to thousands); a pole that fits noise about 1; a
    pole with no line near it ``inf`` (nothing to judge by).

    Parameters
    ----------
    frfs : FrfSet
        The FRFs fitted.
    fit : ModalFit
        Their fit (:func:`racketdyn.modal.residues.fit_modal_constants`).
    weights : ndarray, shape (n_points,), optional
        One a FRF, weighting its misfit (e.g. one over its noise); every FRF alike by default.

    Returns
    -------
    ndarray, shape (n_modes,)
    """
    lines = np.searchsorted(frfs.frequency, fit.frequency)
    weight = np.ones(frfs.n_points) if weights is None else np.asarray(weights, dtype=float)
    residual = (frfs.values[:, lines] - fit.synthesised) * weight[:, None]
    constants = fit.constants * weight[:, None]
    step = float(np.median(np.diff(fit.frequency))) if fit.frequency.size > 1 else 1.0
    gains = np.empty(fit.poles.size)
    for k, (f, zeta) in enumerate(zip(fit.frequency_hz, fit.damping_ratio, strict=True)):
        half = max(6 * zeta * f, 5 * step)
        near = np.flatnonzero(np.abs(fit.frequency - f) <= half)
        if near.size == 0:  # no line near it: nothing to judge by, keep it
            gains[k] = np.inf
            continue
        term = design_columns(frfs, fit.poles[k : k + 1], fit.frequency[near])[:, 0]
        without = residual[:, near] + constants[:, k, None] * term[None, :]
        # the evidence is the peak's, not the real constant's: real constants turned by one
        # phase common to every FRF (a mode whose peak the analyser's delay turns off ±90° —
        # pyFRF's 7092 Hz at 168° — fits no real constant, yet is in the data; one phase, not
        # one per FRF, so that noise gains no more freedom than a delay gives).  With
        # a_j = <term, FRF_j>, the best phase is ½ arg Σ a_j² (closed form)
        norm2 = max(float(np.vdot(term, term).real), 1e-300)
        projection = without @ term.conj()
        turn = np.exp(0.5j * np.angle(np.sum(projection**2)))
        best = turn * np.real(projection / turn) / norm2
        misfit = float(np.linalg.norm(without - best[:, None] * term[None, :]))
        misfit = min(misfit, float(np.linalg.norm(residual[:, near])))
        gains[k] = float(np.linalg.norm(without)) / max(misfit, 1e-300)
    return gains


def _dropped(
    selected: SelectedPoles,
    k: int,
    reason: str,
    *,
    gain: float = float("nan"),
    ratio: float = float("nan"),
) -> DroppedMode:
    return DroppedMode(
        float(selected.frequency[k]),
        float(selected.damping_ratio[k]),
        int(selected.n_orders[k]),
        "constants",
        reason,
        peak_to_noise=float(selected.peak_to_noise[k]),
        fit_gain=float(gain),
        driving_point_ratio=float(ratio),
    )
