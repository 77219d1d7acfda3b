"""Public test helper: hammer records of a known modal system, computed independently of the rig.

Responses are computed on a grid 32 times finer than the sampling, by linear convolution in the
frequency domain with the continuous accelerance, then both channels pass the same zero-phase
FIR anti-alias filter and are decimated — what an anti-aliased acquisition does.  So the
ratio of their spectra is the continuous FRF within the pass band.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.signal import decimate

from racketdyn.measurement import HammerRecords

OVERSAMPLE = 32


@dataclass(frozen=True)
class Modes:
    """Modes of a test system: frequencies (Hz), damping ratios, modal constants A (1/kg)."""

    frequency: NDArray[np.float64]
    damping_ratio: NDArray[np.float64]
    constants: NDArray[np.float64]  # (n_points, n_modes): A = φ_i φ_ref

    def accelerance(self, s: NDArray[np.complex128]) -> NDArray[np.complex128]:
        """H(s) = Σ A s² / (s² + 2ζω s + ω²), for each point, shaped (n_points, len(s))."""
        omega = 2 * np.pi * self.frequency
        denominator = s[:, None] ** 2 + 2 * self.damping_ratio * omega * s[:, None] + omega**2
        return np.asarray(
            (self.constants[:, None, :] * (s[:, None] ** 2 / denominator)[None]).sum(-1)
        )


def half_sine(
    t: NDArray[np.float64], start: float, duration: float, peak: float
) -> NDArray[np.float64]:
    inside = (t >= start) & (t <= start + duration)
    return np.where(
        inside, peak * np.sin(np.pi * (t - start) / np.where(duration > 0, duration, 1)), 0.0
    )


# 13 parameters: a test's knobs (the acquisition, the faults, the seed), each set alone by
# keyword in the tests; grouping them would only wrap the keywords
def records_for(
    modes: Modes,
    pulse_s: float = 1.0e-3,
    n_averages: int = 4,
    n_samples: int = 2048,
    dt: float = 2.0e-4,
    pretrigger_samples: int = 20,
    response_noise: float = 0.0,
    force_noise: float = 0.0,
    offset_n: float = 0.0,
    second_hit: tuple[float, float] | None = None,
    clip_n: float | None = None,
    seed: int = 0,
    start_jitter_s: float = 0.0,
) -> HammerRecords:
    """Records of every point of ``modes``.

    ``second_hit`` = (start of a second pulse after the first one starts, s; its relative size).
    ``start_jitter_s``: each pulse starts at a random time in [0, start_jitter_s) after the
    trigger, s (the hit between two samples, as a free-running trigger leaves it).
    """
    rng = np.random.default_rng(seed)
    fine_dt = dt / OVERSAMPLE
    n_fine = n_samples * OVERSAMPLE
    t = np.asarray(np.arange(n_fine) * fine_dt - pretrigger_samples * dt, dtype=np.float64)
    # linear convolution: pad until the slowest mode has decayed by 1e-7 (no wrap-around)
    decay_s = np.log(1e7) / np.min(2 * np.pi * modes.frequency * modes.damping_ratio)
    n_pad = 1 << int(np.ceil(np.log2(n_fine + decay_s / fine_dt)))
    s = np.asarray(2j * np.pi * np.fft.rfftfreq(n_pad, fine_dt), dtype=np.complex128)
    h = modes.accelerance(s)
    forces, responses = [], []
    for point in range(modes.constants.shape[0]):
        f_avg, r_avg = [], []
        for _ in range(n_averages):
            peak = rng.uniform(50.0, 150.0)
            start = rng.uniform(0.0, start_jitter_s) if start_jitter_s else 0.0
            force = half_sine(t, start, pulse_s, peak)
            if second_hit is not None:
                force += half_sine(t, start + second_hit[0], pulse_s, second_hit[1] * peak)
            spectrum = np.fft.rfft(force, n_pad) * fine_dt
            response = np.fft.irfft(h[point] * spectrum, n_pad)[:n_fine] / fine_dt
            f = decimate(force, OVERSAMPLE, n=8 * OVERSAMPLE, ftype="fir", zero_phase=True)
            r = decimate(response, OVERSAMPLE, n=8 * OVERSAMPLE, ftype="fir", zero_phase=True)
            if response_noise:
                r = r + rng.normal(0, response_noise * np.max(np.abs(r)), r.size)
            if force_noise:
                f = f + rng.normal(0, force_noise * peak, f.size)
            f = f + offset_n
            if clip_n is not None:
                f = np.clip(f, -clip_n, clip_n)
            f_avg.append(f)
            r_avg.append(r)
        forces.append(np.array(f_avg))
        responses.append(np.array(r_avg))
    n = modes.constants.shape[0]
    return HammerRecords(
        sampling_interval_s=dt,
        force=tuple(forces),
        response=tuple(responses),
        response_type="acceleration",
        nodes=tuple(range(1, n + 1)),
        locations=np.column_stack([np.linspace(0.35, 0.65, n), np.zeros(n)]),
        reference_node=1,
        reference_location=(0.35, 0.0),
        pretrigger_s=pretrigger_samples * dt,
        source="synthetic test records",
    )
