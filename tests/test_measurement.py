"""FRF estimation, windows, quality checks and contact time against known systems."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import least_squares

from racketdyn.measurement import HammerRecords
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.measurement.pulse import contact_time
from racketdyn.measurement.quality import quantisation_step
from racketdyn.testing.records import Modes, half_sine, records_for

# Three modes like a racket's (Hz, ζ, modal constants at two points against the reference).
MODES = Modes(
    frequency=np.array([120.0, 330.0, 560.0]),
    damping_ratio=np.array([0.03, 0.02, 0.02]),
    constants=np.array([[6.0, 4.0, 9.0], [-3.0, 2.5, -5.0]]),
)
LIGHT = Modes(MODES.frequency, np.array([0.004, 0.004, 0.005]), MODES.constants)


def _band(frf, low: float = 20.0, high: float = 1000.0) -> np.ndarray:
    return (frf.frequency > low) & (frf.frequency < high)


def test_h1_is_the_analytic_frf() -> None:
    # No windows, responses decayed within the 0.41 s record (ζ ≥ 2 %): the estimate is the
    # continuous accelerance within 0.5 % over 20–1000 Hz (the anti-alias filter is common to
    # both channels; what is left is the response not yet decayed, < 1e-4).
    frf = estimate_frfs(records_for(MODES)).frfs
    assert frf is not None
    assert frf.frf_type == "accelerance"
    band = _band(frf)
    truth = MODES.accelerance(2j * np.pi * frf.frequency[band])
    np.testing.assert_allclose(frf.values[:, band], truth, rtol=5e-3)
    np.testing.assert_allclose(frf.coherence[:, band], 1.0, atol=1e-6)


def test_windows_give_the_frf_with_poles_moved_by_one_over_tau() -> None:
    # Lightly damped modes ring past the record: an exponential window on both channels makes
    # the windowed response the response of a system with s → s + 1/τ, so the estimate must be
    # H(iω + 1/τ) exactly — same residues (no renormalisation; pyFRF's H1 was 3–4.7× off).
    tau = 0.06
    estimate = estimate_frfs(records_for(LIGHT), force_window_s=0.01, exponential_window_s=tau)
    frf = estimate.frfs
    assert frf is not None
    assert frf.exponential_window_s == tau
    band = _band(frf)
    truth = LIGHT.accelerance(2j * np.pi * frf.frequency[band] + 1.0 / tau)
    scale = np.abs(truth).max(axis=1, keepdims=True)  # relative to the peak: zeros are zeros
    assert np.abs(frf.values[:, band] - truth).max() < 2e-3 * scale.min()


def _modal_fit(frequency: np.ndarray, values: np.ndarray, guess: Modes) -> np.ndarray:
    """Poles (σ, ω_d in rad/s) of all modes fitted at once to one accelerance over 40–800 Hz."""
    band = (frequency > 40) & (frequency < 800)
    s = 2j * np.pi * frequency[band]
    n = guess.frequency.size

    def model(p: np.ndarray) -> np.ndarray:
        sigma, damped, a = p[:n], p[n : 2 * n], p[2 * n : 3 * n]
        poles = -sigma + 1j * damped
        terms = a * s[:, None] ** 2 / ((s[:, None] - poles) * (s[:, None] - np.conj(poles)))
        return terms.sum(axis=1)

    def residual(p: np.ndarray) -> np.ndarray:
        diff = model(p) - values[band]
        return np.concatenate([diff.real, diff.imag])

    omega = 2 * np.pi * guess.frequency
    start = np.concatenate([0.03 * omega, omega, guess.constants[0]])
    fit = least_squares(residual, start, x_scale="jac", xtol=1e-14, ftol=1e-14)
    return fit.x[: 2 * n].reshape(2, n)


def test_exponential_window_damping_is_removed_by_the_recorded_tau() -> None:
    # The window moves every pole left by 1/τ (σ → σ + 1/τ, ω_d unchanged).  Poles fitted to the
    # windowed FRF, less the 1/τ recorded on the FrfSet, give back the true damping within 5 %.
    tau = 0.1
    frf = estimate_frfs(records_for(LIGHT, n_averages=2), exponential_window_s=tau).frfs
    assert frf is not None
    sigma, damped = _modal_fit(frf.frequency, frf.values[0], LIGHT)
    sigma_true = sigma - 1.0 / frf.exponential_window_s
    zeta = sigma_true / np.hypot(sigma_true, damped)
    np.testing.assert_allclose(zeta, LIGHT.damping_ratio, rtol=0.05)
    assert np.all(sigma / np.hypot(sigma, damped) > 1.5 * LIGHT.damping_ratio)  # window's share


def test_noise_is_averaged_and_coherence_drops_between_modes() -> None:
    clean = estimate_frfs(records_for(MODES)).frfs
    noisy = estimate_frfs(records_for(MODES, n_averages=10, response_noise=0.01, seed=3)).frfs
    assert clean is not None
    assert noisy is not None
    peak = np.argmin(np.abs(noisy.frequency - 120.0))
    assert noisy.values[0, peak] == pytest.approx(clean.values[0, peak], rel=0.02)
    assert noisy.coherence[0, peak] > 0.99
    assert noisy.coherence[0, _band(noisy)].min() < 0.99  # anti-resonance and high lines


def test_h2_is_unbiased_by_force_noise_where_h1_is_not() -> None:
    # Noise on the force biases H1 = S_fr/S_ff low by S_nn/S_ff; H2 = S_rr/S_rf does not see it.
    records = records_for(MODES, n_averages=20, force_noise=0.02, seed=5)
    h1 = estimate_frfs(records, "H1", force_window_s=None).frfs
    h2 = estimate_frfs(records, "H2").frfs
    truth = MODES.accelerance(2j * np.pi * h1.frequency)
    band = (h1.frequency > 700) & (h1.frequency < 1000)  # weak force spectrum: noise matters
    error_h1 = np.median(np.abs(np.abs(h1.values[0, band]) / np.abs(truth[0, band]) - 1))
    error_h2 = np.median(np.abs(np.abs(h2.values[0, band]) / np.abs(truth[0, band]) - 1))
    assert error_h2 < error_h1


@pytest.mark.parametrize("delay_s", [0.5e-3, 1e-3, 2e-3, 4e-3])
@pytest.mark.parametrize("pulse_s", [0.4e-3, 3.0e-3])  # a frame and a string impact
def test_double_hits_are_caught(delay_s: float, pulse_s: float) -> None:
    # Second hit 20 % of the first, delay_s after the first one ends (on the strings the
    # hammer comes back 1–3 ms later; pyFRF missed 0.5–2 ms).
    records = records_for(MODES, pulse_s=pulse_s, n_averages=2, second_hit=(pulse_s + delay_s, 0.2))
    estimate = estimate_frfs(records)
    assert estimate.frfs is None
    assert all("double hit" in c.reasons for c in estimate.checks)


def test_second_hit_on_the_tail_is_caught() -> None:
    records = records_for(MODES, pulse_s=3e-3, n_averages=1, second_hit=(2.2e-3, 0.6))
    assert "double hit" in estimate_frfs(records).checks[0].reasons


def _quantised(records: HammerRecords, step_n: float) -> HammerRecords:
    """The records with the force rounded to a converter's steps of ``step_n``."""
    return replace(records, force=tuple(np.round(f / step_n) * step_n for f in records.force))


def test_quantised_clean_hits_pass() -> None:
    # A coarse hammer channel (wing_openmodal: 4.88 mV steps, hits of 15-65 steps): the quiet
    # force is constant, its robust noise 0, and a one-step flicker stood out of the record by
    # more than 5 % of the peak: clean hits were double hits.  Here 5 N steps, hits of 17-27
    # steps, the offset half a step so the quiet force flickers between two steps.
    records = _quantised(
        records_for(MODES, n_averages=3, force_noise=0.001, offset_n=2.5, seed=4), 5.0
    )
    estimate = estimate_frfs(records)
    assert [c.reasons for c in estimate.checks] == [()] * 6
    assert estimate.frfs is not None


def test_quantised_double_hit_is_caught() -> None:
    # the noise floored at the step (6 steps to stand out) still sees a second hit of half the
    # first on the same coarse channel
    records = records_for(
        MODES, n_averages=3, force_noise=0.001, offset_n=2.5, second_hit=(2e-3, 0.5), seed=4
    )
    estimate = estimate_frfs(_quantised(records, 5.0))
    assert all("double hit" in c.reasons for c in estimate.checks)


def test_clean_hits_pass_and_clipping_is_caught() -> None:
    clean = estimate_frfs(records_for(MODES, n_averages=3, force_noise=0.002, response_noise=0.01))
    assert all(c.accepted for c in clean.checks)
    clipped = estimate_frfs(records_for(MODES, n_averages=2, clip_n=20.0))
    assert all("force overload" in c.reasons for c in clipped.checks)


def _inverted(records: HammerRecords) -> HammerRecords:
    """The records of a hammer channel that reads compression as negative volts."""
    return replace(records, force=tuple(-f for f in records.force))


def test_a_negative_hammer_channel_is_read_by_its_pulse() -> None:
    # A hammer channel wired to read compression as negative (the Tokyo Sokki frame's:
    # -924, +258, +228, +118 V at 50 Hz) took its positive undershoot for the pulse: peak
    # 2.2 N for a 7.9 N hit, the pulse start one sample late.  The pulse is the largest
    # excursion either way; the FRFs then take their sign from the driving point, as a
    # negated set's do.
    records = records_for(MODES, n_averages=3, force_noise=0.002, response_noise=0.01)
    upright = estimate_frfs(records)
    inverted = estimate_frfs(_inverted(records))
    assert all(c.accepted for c in inverted.checks)
    for up, down in zip(upright.checks, inverted.checks, strict=True):
        assert down.peak_force_n == pytest.approx(up.peak_force_n, rel=1e-9)
        assert down.pulse_start_s == pytest.approx(up.pulse_start_s)
    assert upright.frfs is not None
    assert inverted.frfs is not None
    np.testing.assert_allclose(inverted.frfs.values, upright.frfs.values, rtol=1e-9)
    force = half_sine(np.arange(512) * 2e-4 - 40 * 2e-4, 0.0, 3.3e-3, 100.0)
    assert contact_time(-force, 2e-4, 40 * 2e-4) == pytest.approx(3.3e-3, rel=0.02)


@pytest.mark.parametrize("seed", range(4))
def test_noise_of_a_long_record_is_no_second_hit(seed: int) -> None:
    # A 50 Hz, 178 s record (the Tokyo Sokki frame's driving point): its quiet force noise
    # (1 % of the peak) gave dips and bumps whose prominence reached the detection level
    # (6 × the noise), read as a second hit though no bump stood above it.  A second pulse
    # must rise above the detection level from the baseline, as the first must.
    records = records_for(
        MODES, n_averages=4, n_samples=8192, pretrigger_samples=4, force_noise=0.01, seed=seed
    )
    assert [c.reasons for c in estimate_frfs(records).checks] == [()] * 8


def _replace_point(records: HammerRecords, index: int, force: np.ndarray) -> HammerRecords:
    forces = list(records.force)
    forces[index] = force
    return HammerRecords(
        records.sampling_interval_s,
        tuple(forces),
        records.response,
        records.response_type,
        records.nodes,
        records.locations,
        records.reference_node,
        records.reference_location,
        records.pretrigger_s,
        records.source,
    )


def test_all_rejected_point_is_reported_and_the_rest_goes_on() -> None:
    records = records_for(MODES, n_averages=3)
    bad = records.force[1].copy()
    bad[0, 5] = np.nan
    bad[1:] = 0.0  # no pulse at all
    estimate = estimate_frfs(_replace_point(records, 1, bad))
    assert estimate.rejected_points == (2,)
    assert estimate.frfs is not None
    assert estimate.frfs.nodes == (1,)
    reasons = {c.average: c.reasons for c in estimate.checks if c.node == 2}
    assert reasons == {1: ("non-finite",), 2: ("empty",), 3: ("empty",)}
    assert estimate.summary()["accepted"] == 3


def _without_pretrigger(records: HammerRecords) -> HammerRecords:
    """The same records with t = 0 at the first sample (a pre-trigger exported as t ≥ 0)."""
    from dataclasses import replace

    return replace(records, pretrigger_s=0.0)


def test_pulse_anywhere_in_the_record_is_found() -> None:
    # Issue 12, item 1: the pulse starts 10 ms into records whose t = 0 is the first sample
    # (50 samples of pre-trigger, exported without negative times).  Every average is kept and
    # the FRF is the analytic one as in test_h1_is_the_analytic_frf (a common delay of force
    # and response cancels in S_fr / S_ff).
    records = _without_pretrigger(records_for(MODES, pretrigger_samples=50))
    estimate = estimate_frfs(records)
    assert estimate.summary()["accepted"] == estimate.summary()["averages"] == 8
    assert all(c.pulse_start_s == pytest.approx(0.010, abs=2.1e-4) for c in estimate.checks)
    frf = estimate.frfs
    assert frf is not None
    band = _band(frf)
    truth = MODES.accelerance(2j * np.pi * frf.frequency[band])
    np.testing.assert_allclose(frf.values[:, band], truth, rtol=5e-3)


def test_force_window_counts_from_the_detected_pulse() -> None:
    # A 5 ms force window on records whose pulse starts at 10 ms keeps the pulse: the FRF is
    # the analytic one (it cut the whole pulse away when it counted from t = 0).
    records = _without_pretrigger(records_for(MODES, pretrigger_samples=50))
    frf = estimate_frfs(records, force_window_s=0.005).frfs
    assert frf is not None
    assert frf.metadata["force_window_s"] == 0.005
    band = _band(frf)
    truth = MODES.accelerance(2j * np.pi * frf.frequency[band])
    np.testing.assert_allclose(frf.values[:, band], truth, rtol=5e-3)


def test_pulse_starting_away_from_the_other_averages_is_a_trigger_fault() -> None:
    records = records_for(MODES, n_averages=3)
    late = records.force[0].copy()
    late[1] = np.roll(late[1], 40)  # average 2 of node 1: 8 ms after the other two
    estimate = estimate_frfs(_replace_point(records, 0, late))
    reasons = {c.average: c.reasons for c in estimate.checks if c.node == 1}
    assert reasons == {1: (), 2: ("trigger",), 3: ()}


def test_pulse_cut_by_the_record_start_or_end_is_a_trigger_fault() -> None:
    records = records_for(MODES, n_averages=2, pretrigger_samples=20)
    cut = records.force[0].copy()
    cut[0] = np.roll(cut[0], -22)  # the pulse (5 samples long) already on at the first sample
    cut[1] = np.roll(cut[1], cut.shape[1] - 22)  # and running off the end
    estimate = estimate_frfs(_replace_point(records, 0, cut))
    reasons = {c.average: c.reasons for c in estimate.checks if c.node == 1}
    assert reasons == {1: ("trigger",), 2: ("trigger",)}


@pytest.mark.parametrize("duration", [2.0e-3, 3.3e-3, 4.7e-3])
def test_contact_time_of_a_half_sine(duration: float) -> None:
    # 200 µs sampling (the paper), random sub-sample start, 30 N offset, 0.5 % noise:
    # the half-sine duration comes back within 2 %.
    rng = np.random.default_rng(11)
    dt = 2e-4
    t = np.arange(512) * dt - 40 * dt
    for _ in range(20):
        start = rng.uniform(-dt, dt)
        force = half_sine(t, start, duration, 100.0) + 30.0 + rng.normal(0, 0.5, t.size)
        assert contact_time(force, dt, 40 * dt) == pytest.approx(duration, rel=0.02)


def test_contact_times_per_point_skip_rejected_averages(tmp_path) -> None:
    from racketdyn.measurement.pulse import contact_times

    records = records_for(MODES, pulse_s=3e-3, n_averages=4)
    estimate = estimate_frfs(records)
    times = contact_times(records, estimate.checks)
    np.testing.assert_allclose(times.mean_s, 3e-3, rtol=0.02)
    assert list(times.n_averages) == [4, 4]
    doubled = records_for(MODES, pulse_s=3e-3, n_averages=2, second_hit=(4.5e-3, 0.3))
    rejected = contact_times(doubled, estimate_frfs(doubled).checks)
    assert list(rejected.n_averages) == [0, 0]
    assert np.all(np.isnan(rejected.mean_s))
    times.write_csv(tmp_path / "contact.csv")
    estimate.write_quality_csv(tmp_path / "quality.csv")
    assert (tmp_path / "contact.csv").read_text().startswith("node,x_m,y_m,contact_time_mean_s")
    assert len((tmp_path / "quality.csv").read_text().splitlines()) == 1 + 8


def test_the_rail_needs_three_hits_or_flat_tops() -> None:
    """``rail_level``: clipped hits share the converter's rail.  Two unclipped hits that peak
    at one quantised value of a coarse converter are no rail (review, 2026-11-26); three hits
    there, or two that stay there two samples each, are."""
    from racketdyn.measurement.quality import QualitySettings, rail_level

    t = np.arange(200)
    pulse = np.clip(100.0 * np.sin(np.pi * (t - 50) / 20.0), 0.0, None) * (t >= 50) * (t <= 70)
    one_peak = np.round(pulse, 0)  # a single-sample top of 100 N
    settings = QualitySettings()
    point = np.stack([one_peak, one_peak * 0.5])
    assert (
        rail_level([point, np.stack([one_peak, one_peak * 0.7])], settings).overload_level_n is None
    )
    three = [np.stack([one_peak, one_peak]), np.stack([one_peak, one_peak * 0.3])]
    assert rail_level(three, settings).overload_level_n == pytest.approx(100.0, rel=1e-5)
    flat = np.minimum(pulse, 80.0)  # clipped: several samples at 80 N
    assert rail_level(
        [np.stack([flat, flat * 0.5]), np.stack([flat])], settings
    ).overload_level_n == (pytest.approx(80.0, rel=1e-5))


def test_quantisation_step_is_the_converters_step() -> None:
    rng = np.random.default_rng(0)
    counts = rng.integers(-3, 40, 500)
    assert quantisation_step(counts * 0.0048828125 + 0.1) == pytest.approx(0.0048828125)
    assert quantisation_step(rng.normal(0, 1, 8192)) < 1e-5  # unquantised: no floor
    assert quantisation_step(np.zeros(10)) == 0.0
