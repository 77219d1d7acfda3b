"""Real measured files of other labs (tests/realdata.py; skipped where the folder is absent)."""

from __future__ import annotations

from pathlib import Path

import realdata
from racketdyn.io.uff import read_hammer_csv
from racketdyn.measurement.frf import estimate_frfs


def test_wing_quantised_hits_are_not_double_hits(tmp_path: Path) -> None:
    # wing_openmodal's time records: one clean hit a point, 2 kHz, volts, the hammer quantised
    # in 4.88 mV steps (hits of 15-65 steps).  13 of the 18 hits, the driving point among them,
    # were rejected as double hits: the quiet force is constant, so its noise estimate was 0
    # and a one-step flicker passed 5 % of the peak.
    records = read_hammer_csv(
        realdata.file("wing_openmodal/wing_openmodal_time.csv.xz", tmp_path),
        realdata.file("wing_openmodal/wing_openmodal_geometry_m.csv", tmp_path),
    )
    estimate = estimate_frfs(records)
    assert [c for c in estimate.checks if not c.accepted] == []
    assert estimate.frfs is not None
    assert estimate.frfs.nodes == tuple(range(1, 19))
