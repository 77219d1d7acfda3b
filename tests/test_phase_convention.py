"""FRFs written with the conjugate phase convention (e^{-iωt}) are read back as usual."""

from __future__ import annotations

import logging
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from racketdyn.io import write_frf_uff
from racketdyn.io.frf_layout import read_frf_uff, read_frfs
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.measurement.records import CONJUGATE_LEVEL, FrfSet
from racketdyn.modal.identify import identify
from racketdyn.testing.records import Modes, records_for

MODES = Modes(
    frequency=np.array([120.0, 330.0, 560.0]),
    damping_ratio=np.array([0.03, 0.02, 0.02]),
    constants=np.array([[6.0, 4.0, 9.0], [-3.0, 2.5, -5.0], [2.0, -3.0, 4.0]]),
)


@pytest.fixture(scope="module")
def usual():
    frfs = estimate_frfs(records_for(MODES, n_averages=1)).frfs
    assert frfs is not None
    return frfs.band(1.0, frfs.bandwidth_hz)  # no 0 Hz line (finite when written)


def test_the_usual_convention_is_left_alone(usual, tmp_path: Path, caplog) -> None:
    with caplog.at_level(logging.INFO):
        read = read_frf_uff(write_frf_uff(usual, tmp_path / "usual.uff"))
    np.testing.assert_allclose(read.values, usual.values, rtol=1e-9)
    assert "conjugated" not in read.metadata
    assert "conjugat" not in caplog.text
    assert usual.phase_direction() < 0  # the phase falls through a resonance


@pytest.mark.parametrize("reader", [read_frf_uff, read_frfs])
def test_the_conjugate_convention_is_conjugated(usual, tmp_path: Path, caplog, reader) -> None:
    # An analyser with e^{-iωt} (vtb_siglab's case 2): the phase rises through a resonance.
    # The driving point's imaginary part then reads negative too, so without conjugating the
    # set was negated as well, and identification saw no mode.
    conjugate = replace(usual, values=np.conj(usual.values))
    with caplog.at_level(logging.WARNING):
        read = reader(write_frf_uff(conjugate, tmp_path / "conjugate.uff"))
    np.testing.assert_allclose(read.values, usual.values, rtol=1e-9)
    assert "conjugated" in read.metadata
    assert "phase rises through the resonances" in caplog.text
    assert "conjugated" in caplog.text
    found = identify(read).model.frequency
    np.testing.assert_allclose(found, MODES.frequency, rtol=2e-3)
    assert conjugate.phase_direction() > 0


def test_identify_conjugates_a_set_built_in_python(usual) -> None:
    conjugate = replace(usual, values=np.conj(usual.values))
    found = identify(conjugate)
    np.testing.assert_allclose(found.model.frequency, MODES.frequency, rtol=2e-3)
    assert "conjugated" in found.frfs.metadata


@pytest.mark.slow
def test_lines_beyond_the_analyser_bandwidth_do_not_turn_the_phase() -> None:
    # FRFs racketdyn estimated run to fs/2; above fs/2.56 the anti-alias filter has taken the
    # force away while the response's noise stays, so |H| there is noise over nothing, large,
    # and it outweighed the resonances: 4 lightly damped modes, 5 hits, 0.01 % response noise
    # read as the conjugate convention (+0.38, every FRF conjugated, then "no mode found")
    x = np.linspace(0.0, 1.0, 9)
    shapes = np.array([np.cos((k + 1) * np.pi * x + 0.3) for k in range(4)]).T
    modes = Modes(
        np.array([130.0, 340.0, 610.0, 870.0]),
        np.array([0.01, 0.008, 0.006, 0.005]),
        shapes * shapes[0],
    )
    records = records_for(modes, n_averages=5, n_samples=4096, dt=2e-4, response_noise=1e-4, seed=2)
    frfs = estimate_frfs(records).frfs
    assert frfs is not None
    assert frfs.phase_direction() < 0
    assert "conjugated" not in frfs.with_usual_phase().metadata
    found = identify(frfs).model.frequency
    np.testing.assert_allclose(found, modes.frequency, rtol=1e-3)


def test_one_loud_frf_does_not_decide_the_convention(usual) -> None:
    # The convention is the analyser's, one for the file: each FRF is one witness whatever its
    # scale.  An unseen lab's 50 Hz frame test (three points, the driving point struck with
    # 1.2 N against 8-15 N elsewhere, no force window): its driving-point FRF, 6-9 x the
    # others and its phase steps mostly noise, read +0.12 against the others' -0.07 and -0.28;
    # weighted by |H| the set read +0.10, was conjugated, and no mode was found.  Here one
    # FRF of three, 8 x the others, turns the other way.
    values = usual.values.copy()
    values[2] = 8.0 * np.conj(values[2])
    mixed = replace(usual, values=values)
    assert mixed.phase_direction() < 0
    assert "conjugated" not in mixed.with_usual_phase().metadata


def _unwindowed(seed: int, pulse_s: float, n_averages: int) -> FrfSet:
    """Healthy FRFs of the three modes as a lab estimates them without an exponential window:
    1 % response noise, hits of ``pulse_s`` (a half sine: its spectrum's nulls at
    (k + ½)/``pulse_s`` lie inside the force's band from 1 ms up)."""
    records = records_for(
        MODES, pulse_s=pulse_s, n_averages=n_averages, response_noise=0.01, seed=seed
    )
    frfs = estimate_frfs(records).frfs
    assert frfs is not None
    return frfs


def test_the_force_spectrums_nulls_do_not_turn_the_phase() -> None:
    # A healthy set without an exponential window read +0.14 (the sixteenth session: 1 ms
    # hits, whose spectrum's null at 1.5 kHz leaves |H| the response's noise over almost no
    # force, its phase steps random and the largest of the band); these 24 sets read -0.32
    # ... +0.60, 11 of them conjugated.  Their coherence says which lines the force explains:
    # read there they turn the usual way, -0.14 ... -0.13, clear of the level (+0.05).
    read = [
        _unwindowed(seed, pulse, n).phase_direction()
        for seed in (1, 2, 3, 4)
        for pulse in (1e-3, 2e-3, 3e-3)
        for n in (3, 5)
    ]
    assert max(read) < -CONJUGATE_LEVEL, np.round(read, 3)


def test_a_coherence_over_one_is_not_read_as_one() -> None:
    # an analyser's "coherence" that exceeds 1 (a SigLab export reaches 1.6 on channels of
    # noise) is not Bendat and Piersol's: the lines' magnitudes decide, as without one
    frfs = _unwindowed(1, 5e-4, 3)
    bare = replace(frfs, coherence=None)
    junk = np.full(frfs.values.shape, 0.3)
    junk[:, ::7] = 1.4
    assert replace(frfs, coherence=junk).phase_direction() == bare.phase_direction()
