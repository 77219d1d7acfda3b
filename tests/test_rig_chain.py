"""The chain without a lab: rig → hammer records → UFF → FRFs, checked against the rig's truth."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

import racketdyn as rd
from pull_tension import pull_tension_racket
from racketdyn.io import read_hammer_uff, write_hammer_uff
from racketdyn.measurement.frf import FORCE_NOISE_RATIO, FORCE_NOISE_SHARE, estimate_frfs
from racketdyn.measurement.quality import QualitySettings, noise_only_frfs
from racketdyn.modal.identify import default_band
from racketdyn.rig import (
    Acquisition,
    HammerFaults,
    RigModel,
    SensorNoise,
    hammer_points,
    rig_model,
    simulate_hammer_test,
)


@pytest.fixture(scope="module")
def free_rig() -> RigModel:
    return rig_model(pull_tension_racket(), "free")


def test_rig_records_through_uff_give_the_rigs_frfs(free_rig, tmp_path: Path) -> None:
    # Four points (frame tip, frame side, string centre, throat), 10 noisy averages, written to
    # UFF and read back, windowed and estimated: H1 must match the rig's analytic FRF with the
    # window's pole shift, H(iω + 1/τ), at its resonances within 3 % (sensor noise, 10 averages).
    racket = free_rig.racket
    points = np.array([[0.675, 0.0], [0.60, 0.10], [racket.head.centre_x_m, 0.0], [0.36, 0.0]])
    nodes = (1, 2, 3, 4)
    records = simulate_hammer_test(free_rig, points, nodes, (0.675, 0.0), 1, seed=4)
    write_hammer_uff(records, tmp_path / "t.uff")
    again = read_hammer_uff(tmp_path / "t.uff")
    tau = 0.1
    frfs = estimate_frfs(again, exponential_window_s=tau).frfs
    assert frfs is not None
    assert frfs.driving_point == 0
    # the analytic FRF of the windowed structure: H(s) at s = iω + 1/τ
    phi_i = free_rig.mode_shapes_at([[0.675, 0.0]])
    phi_j = free_rig.mode_shapes_at(points)
    s = 2j * np.pi * frfs.frequency + 1.0 / tau
    wk, zk = free_rig.omega, free_rig.damping_ratio
    modal = 1.0 / (s[None, :] ** 2 + 2 * (zk * wk)[:, None] * s[None, :] + (wk**2)[:, None])
    truth = np.einsum("k,jk,kf->jf", phi_i[0], phi_j, modal) * s**2
    for mode in (120.0, 325.9, 361.0):
        line = np.argmin(np.abs(frfs.frequency - mode))
        peak = slice(line - 2, line + 3)
        measured = np.abs(frfs.values[:, peak]).max(axis=1)
        expected = np.abs(truth[:, peak]).max(axis=1)
        strong = expected > 0.05 * expected.max()
        np.testing.assert_allclose(measured[strong], expected[strong], rtol=0.03)


def test_quality_checks_find_the_rigs_faults(free_rig) -> None:
    # The rig records where it put double hits and overloads; with the hammer's range known the
    # checks must find exactly those averages.
    locations, nodes = hammer_points(free_rig.racket, n_frame=6, n_strings=8)
    records = simulate_hammer_test(
        free_rig,
        locations,
        nodes,
        tuple(locations[3]),
        nodes[3],
        faults=HammerFaults(double_hit_probability=0.2, overload_probability=0.1),
        seed=9,
    )
    estimate = estimate_frfs(records, quality=QualitySettings(overload_level_n=200.0))
    n = records.force[0].shape[0]
    found_double = np.array(
        [
            ["double hit" in c.reasons for c in estimate.checks[i * n : (i + 1) * n]]
            for i in range(len(nodes))
        ]
    )
    found_overload = np.array(
        [
            ["force overload" in c.reasons for c in estimate.checks[i * n : (i + 1) * n]]
            for i in range(len(nodes))
        ]
    )
    np.testing.assert_array_equal(found_double, np.array(records.metadata["double_hit"]))
    np.testing.assert_array_equal(found_overload, np.array(records.metadata["overload"]))
    assert found_double.sum() > 0
    assert found_overload.sum() > 0


def test_hammer_contact_on_the_strings() -> None:
    # At the centre the hammer meets a main of half-length a and a cross of half-width b:
    # T = π sqrt(μ/k), k = 2 S₀ (1/a + 1/b) (within the 1e-4 edge guard: 0.01 %); shorter near
    # the frame; hand-held (pinned) ≈ free (paper, section 3.1: within 2 %).
    from racketdyn.rig import string_contact_time
    from racketdyn.rig.hammer import HAMMER_MASS_KG

    racket = rd.default_racket()
    head = racket.head
    centre = [[head.centre_x_m, 0.0]]
    k = 2 * racket.strings.bed_tension_n * (1 / head.half_length_m + 1 / head.half_width_m)
    m_r = racket.reduced_mass(centre, "free")[0]
    mu = HAMMER_MASS_KG * m_r / (HAMMER_MASS_KG + m_r)
    assert string_contact_time(racket, centre)[0] == pytest.approx(
        np.pi * np.sqrt(mu / k), rel=2e-4
    )
    ring = [
        [head.centre_x_m + 0.85 * head.half_length_m, 0.0],
        [head.centre_x_m, 0.85 * head.half_width_m],
    ]
    assert np.all(string_contact_time(racket, ring) < string_contact_time(racket, centre)[0])
    free = string_contact_time(racket, racket.head.grid(7), "free")
    pinned = string_contact_time(racket, racket.head.grid(7), "pinned")
    np.testing.assert_allclose(pinned, free, rtol=0.02)


@pytest.mark.slow
def test_an_overload_is_found_without_the_hammers_range(free_rig) -> None:
    """New-user trial (2026-11-26, second session): ``rig --overloads 0.02`` put 17 clipped
    hits in a test and ``frf`` (no ``--force-range``) rejected 7: a clipped frame pulse
    (0.4 ms, two samples at 5 kHz) has no three-sample flat top.  Every clipped hit stops at
    the converter's one rail, so averages sharing the set's largest |force| (to 1e-6) are
    overloads whatever their pulse; a test without overloads loses none."""
    locations, nodes = hammer_points(free_rig.racket, n_frame=6, n_strings=8)
    records = simulate_hammer_test(
        free_rig, locations, nodes, tuple(locations[3]), nodes[3],
        faults=HammerFaults(overload_probability=0.1), seed=9,
    )  # fmt: skip
    truth = np.array(records.metadata["overload"])
    assert truth.sum() >= 2
    estimate = estimate_frfs(records)
    n = records.force[0].shape[0]
    found = np.array(
        [
            ["force overload" in c.reasons for c in estimate.checks[i * n : (i + 1) * n]]
            for i in range(len(nodes))
        ]
    )
    np.testing.assert_array_equal(found, truth)
    at = (tuple(locations[3]), nodes[3])
    clean = simulate_hammer_test(free_rig, locations, nodes, *at, seed=9)
    assert all(c.accepted for c in estimate_frfs(clean).checks)


@pytest.mark.slow
def test_frf_says_when_the_force_noise_needs_a_force_window(free_rig) -> None:
    """New-user trial (2026-11-26, second session): with ``rig --force-snr 50`` and no force
    window the junior's FRFs identified with a median fit error of 58–92 % (5 % with
    ``--force-window 0.01``), and nothing said why: H1 divides by the force's autospectrum,
    which the noise of the whole record fills where the pulse's spectrum is weak.  The estimate
    reports the share of each point's band where the force's noise is over a tenth of its
    spectrum, and names ``--force-window`` when it matters; with a window, or with the quiet
    default force channel, it is silent."""
    locations, nodes = hammer_points(free_rig.racket, n_frame=6, n_strings=8)
    at = (tuple(locations[3]), nodes[3])
    noisy = simulate_hammer_test(
        free_rig, locations, nodes, *at, noise=SensorNoise(force_snr_db=50.0), seed=4
    )
    estimate = estimate_frfs(noisy, exponential_window_s=0.1)
    assert "`force_window_s` 0.01" in estimate.force_noise_hint()  # frf prints --force-window
    windowed = estimate_frfs(noisy, exponential_window_s=0.1, force_window_s=0.01)
    assert np.median(windowed.force_noise_share) < np.median(estimate.force_noise_share) - 0.05
    assert windowed.force_noise_share == pytest.approx(estimate.force_noise_share_windowed, abs=0.1)
    assert windowed.force_noise_hint() == ""
    quiet = simulate_hammer_test(free_rig, locations, nodes, *at, seed=4)
    assert estimate_frfs(quiet, exponential_window_s=0.1).force_noise_hint() == ""


def test_the_force_noise_hint_on_the_rigs_default_noise_is_h1s_bias(free_rig) -> None:
    """New-user trial (2026-11-27, ninth session): ``frf`` on ``rig``'s records with the rig's
    default noise (0.02 N rms on the force) named ``--force-window`` (32 % of the band up to
    1953 Hz on the trial's racket), where docs/commands/rig.md called that noise clean
    ("coherence ≈ 1.000") and docs/commands/frf.md ran frf on the rig's records without a
    window.  The hint's share is H1's bias, measured: the share of each point's lines where H1
    reads 9 % or more below the force-windowed FRF is the share the hint reports, within 3 %
    of the band, at every point (0 on the frame, whose short pulse fills the band; 20-27 % on
    the strings).  So the threshold stands and the pages say what the rig's floor does.

    Seeded, within 5 %: unseeded, the noise differed run to run and one point of 14 missed the
    first tolerance, 3 %, by 0.003–0.006 (CI and the dev machine, the same day); the two shares
    count lines either side of a threshold on a noisy ratio, and their worst point differs by
    1.6–5.0 % of the band over seeds 0–19 (2.4 % with seed 0)."""
    locations, nodes = hammer_points(free_rig.racket, n_frame=6, n_strings=8)
    records = simulate_hammer_test(
        free_rig, locations, nodes, tuple(locations[3]), nodes[3], seed=0
    )
    bare = estimate_frfs(records)
    assert bare.frfs is not None
    windowed = estimate_frfs(records, force_window_s=0.01).frfs
    assert windowed is not None
    top = bare.frfs.metadata["bandwidth_hz"]
    lines = (bare.frfs.frequency > 0) & (bare.frfs.frequency <= top)
    ratio = np.abs(bare.frfs.values[:, lines]) / np.abs(windowed.values[:, lines])
    low = np.mean(ratio < 1 / (1 + FORCE_NOISE_RATIO), axis=1)
    assert low == pytest.approx(np.array(bare.force_noise_share), abs=0.05)
    assert np.median(low) > FORCE_NOISE_SHARE  # the default floor biases H1: the hint holds
    assert f"of the band up to {top:.0f} Hz" in bare.force_noise_hint()
    docs = Path(__file__).resolve().parents[1] / "docs" / "commands"
    frf_page = (docs / "frf.md").read_text(encoding="utf-8")
    on_rig_records = [
        line for line in frf_page.splitlines() if line.startswith("racketdyn frf lab/hammer_")
    ]
    assert on_rig_records
    assert all("--force-window 0.01" in line for line in on_rig_records), on_rig_records
    rig_page = " ".join((docs / "rig.md").read_text(encoding="utf-8").split())
    assert "(coherence ≈ 1.000) |" not in rig_page


def test_a_healthy_rig_test_names_no_frf_of_noise_and_an_unplugged_channel_is_named(
    free_rig,
) -> None:
    """Issue 25 (the SigLab cantilever: two of three FRFs noise, said nowhere): an FRF whose
    median coherence is under ``NOISE_COHERENCE`` is named as noise.  The rig's racket at a
    lab's noise (40 dB response, 50 dB force SNR) with 3 averages, a force window, over frf's
    band and identify's default band, names none; the same test with one point's response
    left at the accelerometer's noise alone (0.05 m/s² rms, the rig's default floor: a cable
    pulled out) names that point and no other."""
    locations, nodes = hammer_points(free_rig.racket, n_frame=6, n_strings=8)
    at = (tuple(locations[3]), nodes[3])
    lab = SensorNoise(response_snr_db=40.0, force_snr_db=50.0)
    records = simulate_hammer_test(
        free_rig, locations, nodes, *at, acquisition=Acquisition(n_averages=3), noise=lab, seed=5
    )
    estimate = estimate_frfs(records, exponential_window_s=0.1, force_window_s=0.01)
    assert estimate.frfs is not None
    found = estimate.noise_only()
    assert found is not None
    assert found.noise_nodes == ()
    in_band = noise_only_frfs(estimate.frfs, default_band(estimate.frfs))
    assert in_band is not None
    assert in_band.noise_nodes == ()
    unplugged = 6  # a string-bed point, not the driving point
    rng = np.random.default_rng(2)
    response = tuple(
        rng.normal(0.0, SensorNoise().acceleration_noise_ms2, r.shape) if k == unplugged else r
        for k, r in enumerate(records.response)
    )
    broken = estimate_frfs(
        dataclasses.replace(records, response=response),
        exponential_window_s=0.1,
        force_window_s=0.01,
    ).noise_only()
    assert broken is not None
    assert broken.noise_nodes == (nodes[unplugged],)
