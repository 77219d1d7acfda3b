"""Electrical lines (mains harmonics) in the response are named as such, not taken as modes.

A hum picked up by the accelerometer's cable is a sine of constant amplitude over the record:
in an FRF a pole on the unit circle (damping ≈ 0) at a multiple of 50 or 60 Hz.  Its damping
never settles from order to order, so the selection never keeps it (1-6 orders of 60 with a
hum of 1-3 % of the response, in or out of phase with the hits, with or without an
exponential window); the row it leaves says it is a line.  A mode that happens to sit on a
harmonic keeps its damping and stays a mode (tests/test_realdata.py: pyFRF's 900 Hz).

From FRFs alone a line cannot be told from the pole a hammer pulse's spectral zero leaves
(these records' 1 ms half-sine has one at 1500 Hz = 30 × 50 Hz, ζ ≈ 0, named a line too):
both are "likely" lines, and neither is kept as a mode.
"""

from __future__ import annotations

import csv
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from racketdyn.measurement.frf import estimate_frfs
from racketdyn.measurement.records import HammerRecords
from racketdyn.modal.identify import identify
from racketdyn.testing.records import Modes, records_for

X = np.linspace(0.0, 1.0, 9)
SHAPES = np.array([np.cos((k + 1) * np.pi * X + 0.3) for k in range(4)]).T
MODES = Modes(
    np.array([130.0, 340.0, 610.0, 870.0]),
    np.array([0.01, 0.008, 0.006, 0.005]),
    SHAPES * SHAPES[0],
)


def _with_hum(records: HammerRecords, hz: float, level: float) -> HammerRecords:
    """A sine of ``level`` × each record's peak added to the response, any phase per hit."""
    rng = np.random.default_rng(0)
    time = records.time
    response = []
    for hits in records.response:
        phase = rng.uniform(0.0, 2 * np.pi, (hits.shape[0], 1))
        hum = level * np.abs(hits).max() * np.sin(2 * np.pi * hz * time[None, :] + phase)
        response.append(hits + hum)
    return replace(records, response=tuple(response))


@pytest.mark.slow
def test_a_mains_harmonic_is_named_an_electrical_line(tmp_path: Path) -> None:
    records = records_for(MODES, n_averages=5, n_samples=4096, dt=2e-4, response_noise=1e-4)
    frfs = estimate_frfs(_with_hum(records, 250.0, 0.01)).frfs
    assert frfs is not None
    found = identify(frfs)
    np.testing.assert_allclose(found.model.frequency, MODES.frequency, rtol=1e-3)
    lines = [d for d in found.dropped_modes if d.stage == "line" and abs(d.frequency_hz - 250) < 1]
    assert lines
    assert "electrical line" in lines[0].reason
    assert "5 × 50 Hz" in lines[0].reason
    found.write_dropped_csv(tmp_path / "dropped_modes.csv")
    with (tmp_path / "dropped_modes.csv").open(encoding="utf-8") as handle:
        assert any(row["stage"] == "line" for row in csv.DictReader(handle))


@pytest.mark.slow
def test_without_a_hum_no_line_is_named() -> None:
    records = records_for(MODES, n_averages=5, n_samples=4096, dt=2e-4, response_noise=1e-4)
    frfs = estimate_frfs(records).frfs
    assert frfs is not None
    assert not [d for d in identify(frfs).dropped_modes if d.stage == "line"]
