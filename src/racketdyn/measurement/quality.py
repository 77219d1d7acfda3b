"""Per-average quality checks of hammer records: each average is accepted or rejected with reasons.

Checks (each named in the reasons it gives):

``non-finite``
    NaN or inf in either channel.
``empty``
    No force pulse above the noise (peak under 6 × the noise rms).
``force overload`` / ``response overload``
    Clipping: three samples or more at the channel's extreme value (within 1e-6 of it), the
    flat top an overloaded amplifier or converter leaves.  A known overload level (the
    hammer's range) also rejects any force reaching it; without one, the force's largest
    magnitude shared by two averages or more (within 1e-6: a converter's rail, which no two
    hits reach by chance) is taken as that level (:func:`rail_level`), so that a clipped
    frame pulse, too short for a three-sample flat top, is rejected too.
``double hit``
    A second force pulse: more than one peak standing out of the force record by more than the
    detection level (``max(5 % of the peak, 6 × noise rms)``), whether the second pulse follows
    after the first has ended or rides on its tail, and rising above that level from the
    baseline as the first must (a long record's quiet noise has dips and bumps whose
    prominence reaches six times its rms: the Tokyo Sokki frame's 178 s driving point).
    Found with ``scipy.signal.find_peaks`` (height and prominence), so a second hit 0.5–4 ms
    after the first is caught on frame and string pulses alike.  A hit shorter than a sample
    leaves the converter's anti-alias filter ringing on both sides of it, lobes of alternating
    sign (ladisk/lvm_read's 1024 Hz record: 28 % of the peak after it, 16 % before): a bump
    with a pull at least as deep between it and the pulse is that ringing, not a hit (a hammer
    only pushes).
``trigger``
    The pulse is cut by the start or the end of the record, or it starts more than
    ``trigger_tolerance_s`` away from the other averages of its point (their median start;
    :func:`check_point_starts`).  The pulse may lie anywhere in the record: a record whose
    t = 0 is its first sample and whose pulse comes 10 ms later (an acquisition with a
    pre-trigger that exports no negative times) is as good as one triggered at t = 0.

The pulse is the force's largest excursion from its baseline, whichever its sign: a hammer
channel may read compression as negative (the Tokyo Sokki frame's: −924 V then a +258 V
undershoot); its size is the peak force (:func:`pulse_polarity`).  The FRFs are estimated from
the channel as recorded and take their sign from the driving point, as a negated set's do.

The noise level comes from the pre-trigger samples when there are at least 8, else from the
last quarter of the record (robust estimate: 1.4826 × median absolute deviation), and is never
taken below the force channel's quantisation step (:func:`quantisation_step`): a coarse
converter's quiet force is constant (its robust noise 0) but for a flicker of one step, which
must not count as a pulse (wing_openmodal's hammer, 4.88 mV steps and hits of 15–65 steps:
13 of 18 clean hits were double hits).  On such a channel a pulse, or a second pulse, must
stand out by ``noise_factor`` steps.  The pulse starts at the first sample above the detection
level in the pulse's own lobe (not a ringing lobe before it); windows count from there.

Beside the checks of each average, one of each FRF: an FRF whose coherence says it measured
noise alone (:func:`noise_only_frfs`, used by ``frf`` and ``identify`` alike).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.measurement.records import FrfSet

__all__ = [
    "NOISE_COHERENCE",
    "REASONS",
    "AverageCheck",
    "NoiseOnly",
    "QualitySettings",
    "check_average",
    "check_point_starts",
    "force_baseline_and_noise",
    "noise_only_frfs",
    "pulse_polarity",
    "quantisation_step",
    "rail_level",
]

REASONS = {
    "non-finite": "NaN or infinite samples",
    "empty": "no force pulse above the noise",
    "force overload": "the force clips (flat top) or reaches --force-range",
    "response overload": "the response clips (flat top)",
    "double hit": "a second hammer pulse",
    "trigger": "the pulse is cut by the record's start or end, or starts away from the other "
    "averages of its point",
}
"""What each rejection reason means, for summaries."""


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
        Largest allowed distance between the pulse start of an average and the median start of
        its point's averages, s.
    overload_level_n : float or None
        Hammer force range, N: a force reaching it is an overload.
    """

    relative_level: float = 0.05
    noise_factor: float = 6.0
    trigger_tolerance_s: float = 1.0e-3
    overload_level_n: float | None = None


@dataclass(frozen=True)
class AverageCheck:
    """The verdict on one average of one hammer point.

    Attributes
    ----------
    node, average : int
        Hammer node and average number (from 1).
    accepted : bool
        No reason to reject it.
    reasons : tuple of str
        Why it was rejected (:data:`REASONS`).
    peak_force_n : float
        Peak of the force pulse above its baseline, N.
    pulse_start_s : float
        Time of the pulse start (first sample above the detection level) on the records' time
        axis (from the trigger), s; NaN without a pulse.
    """

    node: int
    average: int
    accepted: bool
    reasons: tuple[str, ...]
    peak_force_n: float
    pulse_start_s: float = float("nan")


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


def pulse_polarity(pulse: NDArray[np.float64]) -> float:
    """+1, or −1 when the largest excursion of ``pulse`` (a force less its baseline) is negative:
    a hammer channel that reads compression as negative."""
    values = np.asarray(pulse, dtype=float)
    return -1.0 if values.size and -float(np.min(values)) > float(np.max(values)) else 1.0


def quantisation_step(signal: NDArray[np.float64]) -> float:
    """The step of the converter that quantised ``signal``: the smallest difference between
    two of its distinct values (0 for a constant record).

    A record quantised in steps q takes values k·q (plus an offset), and its noise or its
    pulse's flanks give neighbouring levels, so the smallest difference is q; an unquantised
    record's values differ by next to nothing (range / samples²), a floor that changes no
    detection level.  Differences below 1e-9 of the record's range (rounding of a scale
    factor) are not steps.
    """
    values = np.unique(np.asarray(signal, dtype=float)[np.isfinite(signal)])
    if values.size < 2:
        return 0.0
    gaps = np.diff(values)
    steps = gaps[gaps > 1e-9 * (values[-1] - values[0])]
    return float(steps.min()) if steps.size else 0.0


def _clipped(signal: NDArray[np.float64]) -> bool:
    extreme = np.max(np.abs(signal))
    if extreme == 0:
        return False
    at_rail = np.abs(np.abs(signal) - extreme) <= 1e-6 * extreme
    return bool(np.count_nonzero(at_rail) >= 3)


def _filter_lobe(pulse: NDArray[np.float64], main: int, bump: int) -> bool:
    """Whether the bump at ``bump`` is a lobe of the anti-alias filter's ringing around the
    pulse at ``main``: between them the force pulls (a lobe of the other sign) at least as far
    as the bump pushes, which a hammer cannot do between two hits."""
    between = pulse[min(main, bump) + 1 : max(main, bump)]
    return bool(between.size) and float(np.min(between)) <= -float(pulse[bump])


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
    noise = max(noise, quantisation_step(force))
    pulse = force - baseline
    pulse = pulse_polarity(pulse) * pulse
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
    # imported here: scipy.signal costs ≈ 0.7 s to import, and the report and identify load
    # this module only for its tables (benchmarks/bench_cli.py)
    from scipy.signal import find_peaks

    peaks, _ = find_peaks(pulse, height=level, prominence=level)
    # the pulse's own peak among those found: a clipped pulse's plateau is found at its middle,
    # where argmax gives its first sample (the rig's overloads read as double hits)
    main = int(peaks[np.argmax(pulse[peaks])]) if peaks.size else int(np.argmax(pulse))
    if any(p != main and not _filter_lobe(pulse, main, int(p)) for p in peaks):
        reasons.append("double hit")
    above = pulse > level
    quiet_before = np.flatnonzero(~above[:main])
    start = int(quiet_before[-1]) + 1 if quiet_before.size else 0  # where the pulse's lobe rises
    start_time = (start - pretrigger) * sampling_interval_s
    if above[0] or above[-1]:  # cut by the record's start or end
        reasons.append("trigger")
    return AverageCheck(node, average, not reasons, tuple(reasons), peak, float(start_time))


def rail_level(force: Sequence[NDArray[np.float64]], settings: QualitySettings) -> QualitySettings:
    """The settings with the force channel's rail as its overload level, when the records show
    one and the hammer's range is not given.

    A clipped hit stops at the converter's one rail: the largest magnitude of the force over
    every average of every point, shared (within 1e-6 of it) by three averages or more, or by
    two that each stay there for two samples or more (a flat top).  Two unclipped hits may
    peak at one quantised value of a coarse converter, but not three, nor with flat tops
    (review of 2026-11-26).  The new-user trial of 2026-11-26 (second session) found 10 of
    17 clipped frame pulses (0.4 ms: two samples) accepted for want of a three-sample flat top.

    Parameters
    ----------
    force : sequence of ndarray (n_averages, n_samples)
        The force records of each point, N.
    settings : QualitySettings
        The checks' settings; returned as they are when ``overload_level_n`` is set.
    """
    if settings.overload_level_n is not None:
        return settings
    records = [
        np.abs(np.nan_to_num(np.asarray(f, dtype=float))).reshape(-1, np.shape(f)[-1])
        for f in force
        if np.size(f)
    ]
    if not records:
        return settings
    top = max(float(r.max()) for r in records)  # points may have records of other lengths
    if top <= 0:
        return settings
    at_top = np.concatenate([np.count_nonzero(r >= top * (1.0 - 1e-6), axis=-1) for r in records])
    sharing = at_top[at_top > 0]  # samples at the top, per average that reaches it
    if sharing.size >= 3 or (sharing.size == 2 and np.all(sharing >= 2)):
        return replace(settings, overload_level_n=top * (1.0 - 1e-6))
    return settings


def check_point_starts(checks: list[AverageCheck], settings: QualitySettings) -> list[AverageCheck]:
    """Reject (``trigger``) the averages of one point whose pulse starts away from the others.

    The reference is the median pulse start of the point's averages that have a pulse; an
    average more than ``settings.trigger_tolerance_s`` from it was triggered differently (a
    false trigger, a hit during the pre-trigger).

    Parameters
    ----------
    checks : list of AverageCheck
        The checks of every average of one point (:func:`check_average`).
    settings : QualitySettings
        The tolerance.

    Returns
    -------
    list of AverageCheck
        The same checks, ``trigger`` added where the start disagrees.
    """
    starts = np.array([c.pulse_start_s for c in checks])
    usable = np.isfinite(starts)
    if np.count_nonzero(usable) < 2:
        return checks
    median = float(np.median(starts[usable]))
    out = []
    for check, start in zip(checks, starts, strict=True):
        if (
            np.isfinite(start)
            and abs(start - median) > settings.trigger_tolerance_s
            and "trigger" not in check.reasons
        ):
            check = replace(check, accepted=False, reasons=(*check.reasons, "trigger"))
        out.append(check)
    return out


NOISE_COHERENCE = 0.5
"""An FRF whose median coherence over the band is under this measured noise alone.

H1's random error (Bendat and Piersol, *Random Data*, ch. 9) is
``ε[|Ĥ|] = √(1 − γ²) / (|γ| √(2 n_d))`` over n_d averages: ``(1 − γ²)/γ² = 2 n_d ε²`` is the
response's noise over the part of it the force explains, one average's error.  At γ² = 1/2 they
are equal, and under it on most of the band's lines (the median) the channel's noise outweighs
the structure's response almost everywhere, the peaks included: more averages shrink the error
as 1/√n_d but never make the FRF measure what the response does not hold.  Pure noise stays
under it at any count of averages: independent signals give an estimated coherence with
``P(γ̂² ≤ x) = 1 − (1 − x)^(n_d − 1)`` (the estimator's bias, E γ̂² = 1/n_d; ibid.), whose median
``1 − 2^(−1/(n_d − 1))`` is 0.29 at 3 averages, 0.16 at 5 and 0.07 at 10 (1/2 at 2, where a
coherence hardly tells anything).  Measured: the SigLab cantilever's two noise channels 0.36
and 0.36, its measured one 0.58 (peaks narrower than a line: leakage lowers it); the rig's
racket ≥ 0.64 at every point even at 20 dB response SNR with 2 averages, ≥ 0.98 at its
default noise (docs/develop.md, issue 25, "FRFs that are only noise").
"""


@dataclass(frozen=True)
class NoiseOnly:
    """Each FRF's median coherence over a band, and those that measured noise alone.

    Attributes
    ----------
    band_hz : tuple of float
        The band the medians are over, Hz.
    nodes : tuple of int
        The FRFs' nodes (the hammer points against the reference).
    median_coherence : tuple of float
        Each FRF's median coherence over the band (0–1).
    """

    band_hz: tuple[float, float]
    nodes: tuple[int, ...]
    median_coherence: tuple[float, ...]

    @property
    def noise_only(self) -> tuple[bool, ...]:
        """Per FRF: its median coherence is under :data:`NOISE_COHERENCE`."""
        return tuple(bool(m < NOISE_COHERENCE) for m in self.median_coherence)

    @property
    def noise_nodes(self) -> tuple[int, ...]:
        """The nodes of the FRFs that measured noise alone."""
        return tuple(n for n, low in zip(self.nodes, self.noise_only, strict=True) if low)

    def sentence(self) -> str:
        """One line naming the FRFs of noise, what that likely means and what to do; empty
        when there are none."""
        nodes = self.noise_nodes
        if not nodes:
            return ""
        medians = [m for m, low in zip(self.median_coherence, self.noise_only, strict=True) if low]
        one = len(nodes) == 1
        return (
            f"{'node' if one else 'nodes'} {', '.join(map(str, nodes))}: median coherence "
            f"{', '.join(f'{m:.2f}' for m in medians)} over {self.band_hz[0]:.4g}–"
            f"{self.band_hz[1]:.4g} Hz (under {NOISE_COHERENCE:g}): {len(nodes)} of "
            f"{len(self.nodes)} FRFs {'is' if one else 'are'} noise, the response measured "
            "nothing there — an accelerometer unplugged or loose, a wrong channel, or a "
            "sensitivity that leaves its signal under the noise; check "
            f"{'that channel' if one else 'those channels'} and measure again (a mode shape's "
            f"values at {'this point are' if one else 'these points are'} noise)"
        )

    def record(self) -> dict[str, Any]:
        """What run.json keeps of it."""
        return {
            "nodes": list(self.noise_nodes),
            "band_hz": list(self.band_hz),
            "median_coherence": {
                str(n): round(m, 4) for n, m in zip(self.nodes, self.median_coherence, strict=True)
            },
            "threshold": NOISE_COHERENCE,
            "sentence": self.sentence(),
        }


def noise_only_frfs(frfs: FrfSet, band_hz: tuple[float, float]) -> NoiseOnly | None:
    """Each FRF's median coherence over ``band_hz`` and those under :data:`NOISE_COHERENCE`
    (noise alone); None where the FRFs carry no coherence (nothing is said).

    Parameters
    ----------
    frfs : FrfSet
        The FRFs, with their coherence.
    band_hz : tuple of float
        (low, high), Hz: the band used (inclusive).

    Returns
    -------
    NoiseOnly or None
        The medians and the FRFs of noise; None without coherence or lines in the band.
    """
    if frfs.coherence is None:
        return None
    lines = (frfs.frequency >= band_hz[0]) & (frfs.frequency <= band_hz[1]) & (frfs.frequency > 0)
    if not np.any(lines):
        return None
    coherence = np.nan_to_num(np.asarray(frfs.coherence[:, lines], dtype=float), nan=0.0)
    return NoiseOnly(
        (float(band_hz[0]), float(band_hz[1])),
        frfs.nodes,
        tuple(float(m) for m in np.median(coherence, axis=1)),
    )
