"""FRF estimation from hammer records: windows, H1/H2, coherence, linear averaging.

Written here rather than taken from pyFRF 1.5.0, which (measured, see the measurement issue)
scales H1 wrongly with force + exponential windows, does not record the exponential window's
added damping, misses second hits 0.5–2 ms after the first and rejects float sampling rates.

Windows
    *Force window*: the force is kept from the start of the record to ``force_window_s`` after
    the start of the pulse (detected in each average, wherever it lies in the record) and set
    to its baseline afterwards, removing the noise the hammer channel
    records once the pulse is over.  *Exponential window* ``w(t) = exp(−t/τ)`` (t from the
    trigger): applied to the response **and** the force, so that the windowed response is
    exactly the response of the structure with every pole moved left by 1/τ to the windowed
    force.  The estimated FRF is then exactly the FRF of that structure: same residues (no
    amplitude renormalisation), each mode's damping ratio raised by ``1/(τ ω_k)``.  τ is
    recorded on the :class:`FrfSet` so identification can take it off.
Estimators
    ``H1 = S_fr / S_ff`` (noise on the response averages out) and ``H2 = S_rr / S_rf`` (noise on
    the force), with cross- and auto-spectra summed over the accepted averages (linear
    averaging); coherence ``γ² = |S_fr|² / (S_ff S_rr)``.
"""

from __future__ import annotations

import csv
import logging
from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from racketdyn.errors import InputError, logs_warnings, require_positive
from racketdyn.measurement.quality import (
    REASONS,
    AverageCheck,
    NoiseOnly,
    QualitySettings,
    check_average,
    check_point_starts,
    force_baseline_and_noise,
    noise_only_frfs,
    rail_level,
)
from racketdyn.measurement.records import (
    ANALYSER_BANDWIDTH_FACTOR,
    FORCE_DROP_DB,
    FRF_TYPE_OF_RESPONSE,
    FrfSet,
    HammerRecords,
)

__all__ = [
    "FORCE_NOISE_RATIO",
    "FORCE_NOISE_SHARE",
    "SUGGESTED_FORCE_WINDOW_S",
    "FrfEstimate",
    "estimate_frfs",
    "force_band_top",
]

FORCE_NOISE_RATIO = 0.1
"""The force's noise over its autospectrum above which a line counts as noisy (H1 low by
1/(1 + 0.1), 9 %)."""
FORCE_NOISE_SHARE = 0.05
"""The share of the band of noisy lines at the median point above which ``frf`` names
``force_window_s`` (the CLI's ``--force-window``)."""

SUGGESTED_FORCE_WINDOW_S = 0.01
"""The force window ``frf`` suggests, s: over twice the longest string pulse (≈ 4 ms)."""

FORCE_SMOOTHING_OCTAVE = 1.0 / 3.0
"""The force's autospectrum is averaged over this fraction of an octave about each line before
it is held to :data:`~racketdyn.measurement.records.FORCE_DROP_DB`: the envelope of the
pulse's side lobes (a third of an octave spans about one lobe where a half sine is 40 dB
down), not its nulls, and no single line of a noisy spectrum decides."""

_WINDOW_LIMIT = 10.0
"""A force or exponential window longer than this many records does nothing: a unit slip
(milliseconds given as seconds; new-user trial of 2026-11-26, second session)."""

log = logging.getLogger(__name__)

Estimator = Literal["H1", "H2"]


@dataclass(frozen=True, eq=False)
class FrfEstimate:
    """FRFs with the verdict on every average.

    Attributes
    ----------
    frfs : FrfSet or None
        FRFs of the points with at least one accepted average (None if there are none).
    checks : tuple of AverageCheck
        One per average of every point, accepted or not, with the reasons.
    rejected_points : tuple of int
        Nodes whose every average was rejected (left out of ``frfs``).
    force_noise_share : tuple of float
        Per FRF: the share of its lines up to the bandwidth where the force's noise (its
        pre-trigger rms over the windowed record) is over :data:`FORCE_NOISE_RATIO` of the
        force's autospectrum, biasing H1 low by 9 % or more there.
    force_noise_share_windowed : tuple of float
        The same with a force window of :data:`SUGGESTED_FORCE_WINDOW_S` (without a force
        window: what one would leave; with one, equal to ``force_noise_share``).  The string
        pulses' spectra fall off above ≈ 1.5/T, so part of the band is noisy with any window.
    force_window_s : float or None
        The force window used, s.
    """

    frfs: FrfSet | None
    checks: tuple[AverageCheck, ...]
    rejected_points: tuple[int, ...]
    force_noise_share: tuple[float, ...] = ()
    force_noise_share_windowed: tuple[float, ...] = ()
    force_window_s: float | None = None

    def force_noise_hint(self) -> str:
        """A line naming ``force_window_s`` when no force window was given and one would take
        the force's noise off more than :data:`FORCE_NOISE_SHARE` of the band at the median
        point; empty otherwise."""
        if self.force_window_s is not None or not self.force_noise_share:
            return ""
        now = float(np.median(self.force_noise_share))
        windowed = float(np.median(self.force_noise_share_windowed))
        if now - windowed <= FORCE_NOISE_SHARE:
            return ""
        top = None if self.frfs is None else self.frfs.metadata.get("bandwidth_hz")
        band = "the band" if top is None else f"the band up to {top:.0f} Hz"
        return (
            f"the force's noise after the pulse is over {FORCE_NOISE_RATIO:.0%} of its spectrum "
            f"on {now:.0%} of {band} at the median point (H1 reads low there; "
            f"{windowed:.0%} with a force window): give `force_window_s` "
            f"{SUGGESTED_FORCE_WINDOW_S:g} (s, longer than the longest pulse)"
        )

    def noise_only(self) -> NoiseOnly | None:
        """The FRFs whose coherence over the lines up to the bandwidth says they measured noise
        alone (:func:`racketdyn.measurement.quality.noise_only_frfs`); None without coherence
        (one average a point)."""
        if self.frfs is None:
            return None
        return noise_only_frfs(self.frfs, (0.0, self.frfs.bandwidth_hz))

    def write_quality_csv(self, path: Path) -> None:
        """``node, average, accepted, reasons, peak_force_n``: every average and its verdict."""
        with Path(path).open("w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(["node", "average", "accepted", "reasons", "peak_force_n"])
            for c in self.checks:
                writer.writerow(
                    [
                        c.node,
                        c.average,
                        int(c.accepted),
                        ";".join(c.reasons),
                        f"{c.peak_force_n:.6g}",
                    ]
                )

    def rejections(self) -> str:
        """Why averages were rejected, most frequent reason first, each with its meaning.

        Empty when none was.  E.g. ``"trigger 38 (the pulse is cut by the record's start or
        end, or starts away from the other averages of its point); empty 2 (…)"``.
        """
        counts = Counter(reason for check in self.checks for reason in check.reasons)
        return "; ".join(
            f"{reason} {count} ({REASONS.get(reason, reason)})"
            for reason, count in counts.most_common()
        )

    def summary(self) -> dict[str, int]:
        """Counts of averages by verdict and reason."""
        counts: dict[str, int] = {"averages": len(self.checks)}
        counts["accepted"] = sum(c.accepted for c in self.checks)
        for check in self.checks:
            for reason in check.reasons:
                counts[reason] = counts.get(reason, 0) + 1
        return counts


def force_band_top(
    frequency: NDArray[np.float64], autospectrum: NDArray[np.float64], bandwidth_hz: float
) -> float:
    """The highest frequency up to which the hammer's force still excites the structure, Hz.

    The force's autospectrum, averaged over :data:`FORCE_SMOOTHING_OCTAVE` of an octave about
    each line (its envelope), is held to its largest value (the pulse's low-frequency
    plateau): the top is the last line at or below ``bandwidth_hz`` where it is within
    :data:`~racketdyn.measurement.records.FORCE_DROP_DB` of it; above, it stays more than
    that below.  A force whose envelope never falls that far (a short hit, or the force's own
    noise within 40 dB of the plateau) gives ``bandwidth_hz``.

    Parameters
    ----------
    frequency : ndarray
        Spectral lines, Hz, rising evenly from 0.
    autospectrum : ndarray
        The force's autospectrum at those lines, N²/Hz² (any constant scale).
    bandwidth_hz : float
        The analyser's bandwidth, Hz: lines above it are not looked at.

    Returns
    -------
    float
        The top, Hz (at most ``bandwidth_hz``).
    """
    inside = (frequency > 0) & (frequency <= bandwidth_hz)
    f, power = frequency[inside], np.asarray(autospectrum, dtype=float)[inside]
    if f.size < 2 or not np.all(np.isfinite(power)) or not np.any(power > 0):
        return float(bandwidth_hz)
    half = 2.0 ** (FORCE_SMOOTHING_OCTAVE / 2)
    total = np.concatenate([[0.0], np.cumsum(power)])
    start = np.searchsorted(f, f / half, side="left")
    stop = np.searchsorted(f, f * half, side="right")
    envelope = (total[stop] - total[start]) / (stop - start)
    level = float(np.max(envelope)) * 10.0 ** (-FORCE_DROP_DB / 10.0)
    last = int(np.flatnonzero(envelope >= level)[-1])
    return float(bandwidth_hz) if last == f.size - 1 else float(f[last])


@logs_warnings(log)
def estimate_frfs(
    records: HammerRecords,
    estimator: Estimator = "H1",
    force_window_s: float | None = None,
    exponential_window_s: float | None = None,
    quality: QualitySettings | None = None,
) -> FrfEstimate:
    """Estimate one FRF per hammer point from its accepted averages.

    Parameters
    ----------
    records : HammerRecords
        Force and response records.
    estimator : {"H1", "H2"}
        Spectral estimator.
    force_window_s : float, optional
        Keep the force up to this time after the pulse start (detected in each average), s;
        None keeps the whole record.
    exponential_window_s : float, optional
        Time constant τ of the exponential window on both channels, s; None for none.
    quality : QualitySettings, optional
        Thresholds of the per-average checks (:mod:`racketdyn.measurement.quality`).

    Returns
    -------
    FrfEstimate
        The FRF set (frf_type from the response: accelerance, mobility or receptance), the
        checks of every average, and the points with none accepted.
    """
    if estimator not in ("H1", "H2"):
        raise InputError(f"estimator must be H1 or H2 (got {estimator!r})")
    if force_window_s is not None:
        require_positive("force window", force_window_s)
    if exponential_window_s is not None:
        require_positive("exponential window time constant", exponential_window_s)
    settings = rail_level(records.force, quality or QualitySettings())
    dt = records.sampling_interval_s
    time = records.time
    record_s = float(time[-1] - time[0]) + dt
    for option, window in (
        ("`force_window_s`", force_window_s),
        ("`exponential_window_s`", exponential_window_s),
    ):
        if window is not None and window > _WINDOW_LIMIT * record_s:
            raise InputError(
                f"{option} {window:g}: a window is given in s, and {window:g} s is over "
                f"{_WINDOW_LIMIT:g} times the record ({record_s:.3g} s); did you give milliseconds "
                f"({window:g} ms = {window * 1e-3:g} s)?"
            )
    pretrigger = records.pretrigger_samples
    exponential = (
        np.ones_like(time) if exponential_window_s is None else np.exp(-time / exponential_window_s)
    )

    checks: list[AverageCheck] = []
    values, coherence, counts, kept = [], [], [], []
    noise_shares: list[float] = []
    windowed_shares: list[float] = []
    force_tops: list[float] = []
    bandwidth_hz = 1.0 / (ANALYSER_BANDWIDTH_FACTOR * dt)
    lines = np.fft.rfftfreq(records.n_samples, dt)
    in_band = (lines > 0) & (lines <= bandwidth_hz)
    for index, node in enumerate(records.nodes):
        force, response = records.force[index], records.response[index]
        verdicts = check_point_starts(
            [
                check_average(
                    node, k + 1, force[k], response[k], dt, records.pretrigger_s, settings
                )
                for k in range(force.shape[0])
            ],
            settings,
        )
        checks.extend(verdicts)
        accepted = [k for k, v in enumerate(verdicts) if v.accepted]
        if not accepted:
            log.warning("node %d: every average rejected; left out", node)
            continue
        f = force[accepted].copy()
        r = response[accepted].copy()
        noise_ff = 0.0  # the force noise's autospectrum, flat: σ² Σ w(t)² dt² per average
        noise_windowed = 0.0  # the same within the suggested force window
        for row_f, row_r, k in zip(f, r, accepted, strict=True):
            # the quiet samples before the pulse give the offsets: the pre-trigger when the
            # pulse starts on the trigger, else those before the detected pulse (a pre-trigger
            # exported with t >= 0)
            start = round(float(verdicts[k].pulse_start_s - time[0]) / dt)
            on_trigger = abs(verdicts[k].pulse_start_s) <= settings.trigger_tolerance_s
            quiet = pretrigger if on_trigger and pretrigger > 0 else max(start - 2, 0)
            baseline, noise = force_baseline_and_noise(row_f, quiet)
            kept_window = exponential**2
            if force_window_s is not None:
                cut = time > verdicts[k].pulse_start_s + force_window_s
                row_f[cut] = baseline
                kept_window = np.where(cut, 0.0, kept_window)
            noise_ff += noise**2 * float(np.sum(kept_window)) * dt**2
            inside = time <= verdicts[k].pulse_start_s + SUGGESTED_FORCE_WINDOW_S
            noise_windowed += noise**2 * float(np.sum(kept_window[inside])) * dt**2
            row_f -= baseline
            row_r -= np.mean(row_r[: max(quiet, 1)])
        spectrum_f = np.fft.rfft(f * exponential, axis=1) * dt
        spectrum_r = np.fft.rfft(r * exponential, axis=1) * dt
        s_ff = np.sum(np.abs(spectrum_f) ** 2, axis=0)
        s_rr = np.sum(np.abs(spectrum_r) ** 2, axis=0)
        s_fr = np.sum(np.conj(spectrum_f) * spectrum_r, axis=0)
        with np.errstate(divide="ignore", invalid="ignore"):
            h = s_fr / s_ff if estimator == "H1" else s_rr / np.conj(s_fr)
            gamma2 = np.abs(s_fr) ** 2 / (s_ff * s_rr)
        values.append(h)
        force_tops.append(
            force_band_top(
                np.asarray(lines, dtype=np.float64),
                np.asarray(s_ff, dtype=np.float64),
                bandwidth_hz,
            )
        )
        for share, level in ((noise_shares, noise_ff), (windowed_shares, noise_windowed)):
            noisy = level > FORCE_NOISE_RATIO * s_ff[in_band]
            share.append(float(np.mean(noisy)) if noisy.size else 0.0)
        coherence.append(np.nan_to_num(gamma2, nan=0.0))
        counts.append(len(accepted))
        kept.append(index)

    rejected = tuple(records.nodes[i] for i in range(records.n_points) if i not in kept)
    if not kept:
        return FrfEstimate(None, tuple(checks), rejected, (), (), force_window_s)
    frequency = np.asarray(np.fft.rfftfreq(records.n_samples, dt), dtype=float)
    frfs = FrfSet(
        frequency=frequency,
        values=np.array(values),
        frf_type=FRF_TYPE_OF_RESPONSE[records.response_type],  # type: ignore[arg-type]
        nodes=tuple(records.nodes[i] for i in kept),
        locations=records.locations[kept],
        reference_node=records.reference_node,
        reference_location=records.reference_location,
        # one average a point: γ² = 1 by definition, no measure of anything
        coherence=np.array(coherence) if max(counts) > 1 else None,
        n_averages=np.array(counts),
        exponential_window_s=exponential_window_s,
        estimator=estimator,
        source=records.source,
        metadata={
            "force_window_s": force_window_s,
            "bandwidth_hz": bandwidth_hz,
            # a mode is seen where any point's hit excites it: the largest point's top (the
            # rig's string points, 3-5 ms pulses, reach 1.0-1.3 kHz, its frame points' 0.4 ms
            # the bandwidth: its modes at 1.5-1.8 kHz stay in the band)
            "force_band_hz": max(force_tops),
        },
    ).with_positive_driving_point()
    return FrfEstimate(
        frfs, tuple(checks), rejected, tuple(noise_shares), tuple(windowed_shares), force_window_s
    )
