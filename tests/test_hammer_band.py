"""The default band's top follows the hammer's force spectrum (issue 25: a 51.2 kHz single hit
took the band 40-20000 Hz and offered ``--pin`` on peaks of noise where its force was 53-105 dB
down).  The rule: :func:`racketdyn.measurement.frf.force_band_top`,
:data:`racketdyn.measurement.records.FORCE_DROP_DB`."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import realdata
from racketdyn.io import read_frfs, read_hammer_csv, write_frf_uff
from racketdyn.measurement.frf import estimate_frfs, force_band_top
from racketdyn.measurement.records import FORCE_DROP_DB, FrfSet
from racketdyn.modal.identify import NO_FORCE, default_band, identify
from racketdyn.testing.records import Modes, records_for


def _half_sine_top(pulse_s: float) -> float:
    """Where a half sine's side-lobe envelope is FORCE_DROP_DB below its plateau, Hz.

    |F(f)|² ∝ cos²(πfT) / (1 − (2fT)²)², whose side lobes average cos² = 1/2 over a third of
    an octave: 1/2 / ((2fT)² − 1)² = 10^(−drop/10).
    """
    ratio = 10.0 ** (-FORCE_DROP_DB / 10.0)
    return float(np.sqrt((np.sqrt(0.5 / ratio) + 1.0) / 4.0) / pulse_s)


@pytest.mark.parametrize("pulse_s", [0.25e-3, 1e-3, 3e-3])
def test_the_force_band_is_where_a_half_sines_envelope_is_40_db_down(pulse_s: float) -> None:
    # The exact spectrum of a half sine on 1 Hz lines to 20 kHz.  Tolerance 5 %: the third
    # octave's mean of cos² is 1/2 only on average over whole lobes (3.2 % high at 1 ms).
    f = np.arange(0.0, 20000.0, 1.0)
    x = 2 * f * pulse_s
    near_one = np.abs(x - 1) < 1e-9
    amplitude = np.where(
        near_one, np.pi / 4, np.cos(np.pi * f * pulse_s) / np.where(near_one, 1, 1 - x**2)
    )
    top = force_band_top(f, amplitude**2, 20000.0)
    assert top == pytest.approx(_half_sine_top(pulse_s), rel=0.05)
    # the nulls are not the top: the first (1.5/T) lies far below it
    assert top > 2.5 * 1.5 / pulse_s


def test_a_force_that_never_falls_40_db_keeps_the_bandwidth() -> None:
    f = np.arange(0.0, 1000.0, 1.0)
    assert force_band_top(f, np.full(f.size, 3.0), 781.25) == 781.25


MODES = Modes(
    frequency=np.array([300.0, 900.0, 1800.0]),
    damping_ratio=np.array([0.02, 0.02, 0.02]),
    constants=np.array([[4.0, 3.0, 2.0], [2.0, -3.0, 2.5], [-3.0, 1.0, 3.0]]),
)
"""Three modes, the last on the 1 ms pulse's side lobe (its first null 1.5 kHz, 24 dB down at
1.8 kHz), as the rig's 1.5-1.8 kHz modes under its string pulses."""


def _short_hard_hits(modes: Modes = MODES, n_samples: int = 8192) -> FrfSet:
    """1 ms hits sampled at 51.2 kHz (bandwidth 20 kHz): the force 40 dB down at ≈ 4.3 kHz,
    the response's noise above it over almost no force, as the tool tip's single hit."""
    records = records_for(
        modes,
        pulse_s=1e-3,
        n_averages=1,
        n_samples=n_samples,
        dt=1 / 51200,
        pretrigger_samples=40,
        response_noise=1e-4,
        seed=3,
    )
    frfs = estimate_frfs(records).frfs
    assert frfs is not None
    return frfs


@pytest.fixture(scope="module")
def short_hits() -> FrfSet:
    return _short_hard_hits()


def test_the_default_band_ends_where_the_hammers_force_is_40_db_down(short_hits: FrfSet) -> None:
    top = _half_sine_top(1e-3)
    assert short_hits.bandwidth_hz == pytest.approx(20000.0)
    assert short_hits.force_band_hz == pytest.approx(top, rel=0.05)
    assert default_band(short_hits)[1] == pytest.approx(short_hits.force_band_hz)
    found = identify(short_hits)
    assert "the hammer's force is 40 dB down above 4.4 kHz" in found.band_note
    # the side lobe's mode stays in the band and is identified, within issue 25's 0.1 %
    for f in MODES.frequency:
        assert np.min(np.abs(found.model.frequency / f - 1)) < 1e-3
    # nothing above the force's band is offered
    assert all(d.frequency_hz <= top * 1.05 for d in found.dropped_modes)


def test_the_phase_convention_is_read_where_the_hammer_gave_force(short_hits: FrfSet) -> None:
    # Over the whole 20 kHz bandwidth the noise over no force read +0.08 (a rising phase) and
    # the set was conjugated: no mode was found at all.
    assert short_hits.phase_direction() < 0
    assert not short_hits.with_usual_phase().metadata.get("conjugated")


def test_a_given_band_is_the_users_but_no_pin_is_offered_above_the_force(
    short_hits: FrfSet,
) -> None:
    found = identify(short_hits, band_hz=(40.0, 20000.0))
    assert found.band_hz == (40.0, 20000.0)
    above = [d for d in found.dropped_modes if d.frequency_hz > short_hits.force_band_hz]
    offered = [d for d in above if "keeps it" in d.reason or "`band_hz`" in d.reason]
    assert offered == []
    assert all("40 dB down" in d.reason for d in above if d.stage == NO_FORCE)


def test_the_force_band_travels_with_the_frfs_file(short_hits: FrfSet, tmp_path: Path) -> None:
    again = read_frfs(write_frf_uff(short_hits, tmp_path / "frfs.uff"))
    assert again.force_band_hz == pytest.approx(short_hits.force_band_hz, rel=1e-6)


def test_the_tool_tips_hit_offers_no_pin_where_the_hammer_gave_no_force(tmp_path: Path) -> None:
    # leekunhwee/Vibration-Signal-Processing @ d9edffe, ImpactTesting/Point1_Channel1_CH1.txt
    # (time, force N, acceleration m/s², 51.2 kHz, 1 s) in racketdyn's CSV layout.  Its force
    # spectrum is 10/20/40 dB below its 100 Hz level at 958/1324/2900 Hz (1 Hz lines); the
    # default band 40-20000 Hz offered `--pin` on 87 peaks at 3.9-14.6 kHz (seven "clear
    # peaks" 120-1100 × the noise).  The lab's own modes (its README, peak picking on 1 Hz
    # lines): 1074, 1961, 2617 Hz; 0.5 %: the independent results for this 3.4 %-damped
    # first mode differ by as much (sdypy 1068.3-1071.3 Hz, the lab 1074 Hz).
    path = realdata.file("leekunhwee_tool_tip/tool_tip_hit.csv", tmp_path)
    frfs = estimate_frfs(read_hammer_csv(path)).frfs
    assert frfs is not None
    assert frfs.force_band_hz == pytest.approx(2900.0, rel=0.02)
    found = identify(frfs)
    assert found.band_hz[1] == pytest.approx(frfs.force_band_hz)
    assert all(d.frequency_hz < 3000.0 for d in found.dropped_modes)
    assert np.min(np.abs(found.model.frequency / 1074.0 - 1)) < 0.005
    assert np.min(np.abs(found.model.frequency / 2617.0 - 1)) < 0.005


@pytest.mark.slow
def test_identify_says_where_the_top_came_from(
    short_hits: FrfSet, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from racketdyn.cli import main

    path = write_frf_uff(short_hits, tmp_path / "frfs.uff")
    assert main(["identify", str(path), "--out", str(tmp_path / "a")]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "the hammer's force is 40 dB down above 4.4 kHz" in printed
    assert "--band up to the FRFs' bandwidth, 20000 Hz, looks above it anyway" in printed
    given = ["--band", "40,20000", "--out", str(tmp_path / "b")]
    assert main(["identify", str(path), *given]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "as given (--band) the hammer's force is 40 dB down above 4.4 kHz" in printed


LIGHT = Modes(
    frequency=np.array([600.0, 1500.0, 2400.0, 3400.0]),
    damping_ratio=np.array([0.004, 0.003, 0.0015, 0.003]),
    constants=np.array([[4.0, 3.0, 2.0, 2.0], [2.0, -3.0, 2.5, -2.0], [-3.0, 1.0, 3.0, 1.5]]),
)
"""Four well-separated modes under the 1 ms pulse's 4.4 kHz, 2400 Hz lightly damped (ζ 0.15 %,
half-power width 7.2 Hz, 18 lines of a 0.32 s record): as pff_lms's 6,007 Hz mode in the
middle of a band whose force ends at 10.9 kHz."""


@pytest.mark.slow
def test_a_well_separated_modes_damping_does_not_move_with_the_bands_top() -> None:
    # pff_lms's 6,007 Hz damping moved with the band's top (0.187 % over 40-10,864 Hz, 0.160 %
    # over 40-20,000 Hz); sdypy's LSCF moves alike (0.186/0.146 %) and both follow the orders
    # a kHz, not the top (tests/test_realdata.py): on a linear system the top alone moves
    # nothing.  Over the force's band and up to 10 and 20 kHz, its upper part the response's
    # noise over almost no force (orders raised to 60-115), the damping is within 0.04 % of the
    # truth over seeds 0-3: 1 %, a twentieth of the must-hold's 20 %, is 25 times that
    frfs = _short_hard_hits(LIGHT, n_samples=16384)
    for band in (None, (40.0, 10000.0), (40.0, 20000.0)):
        model = identify(frfs, band).model
        k = int(np.argmin(np.abs(model.frequency - 2400.0)))
        assert model.frequency[k] == pytest.approx(2400.0, rel=1e-4), band
        assert model.damping_ratio[k] == pytest.approx(0.0015, rel=0.01), band
