"""Traits of real exports the project had not seen (issue 25's hidden judge), each reproduced
without the file: the file, its source and what racketdyn made of it are in docs/develop.md
("Fourteenth session: a second round of unseen files")."""

from __future__ import annotations

import numpy as np
import pytest

from racketdyn.measurement import HammerRecords
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.testing.records import Modes, records_for

MODES = Modes(
    frequency=np.array([60.0, 170.0, 330.0]),
    damping_ratio=np.array([0.01, 0.01, 0.01]),
    constants=np.array([[6.0, 4.0, 9.0], [-3.0, 2.5, -5.0]]),
)


def _sub_sample_hits(**faults: object) -> HammerRecords:
    """Hits of 0.6 ms sampled at 1024 Hz through the anti-alias filter, as lvm_read's record."""
    return records_for(
        MODES, pulse_s=0.6e-3, dt=1 / 1024, n_samples=4096, pretrigger_samples=85, **faults
    )  # type: ignore[arg-type]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_hit_shorter_than_a_sample_rings_but_is_one_hit(seed: int) -> None:
    # ladisk/lvm_read's LabVIEW record (1024 Hz, a metal tip): the hit lasts less than a
    # sample, so the converter's anti-alias filter spreads it over its neighbours with lobes
    # of alternating sign, up to 28 % of the peak after it and 16 % before.  Each lobe of the
    # compression's sign read as a second hit, and the first lobe above the detection level as
    # the pulse's start, which moved by up to three samples from hit to hit (two clean hits
    # both rejected, "double hit" and "trigger").  A hammer pushes: a bump with a pull (a lobe
    # of the other sign as deep as the bump is high) between it and the pulse is the filter's
    # ringing, and the pulse starts where its own lobe does.
    records = _sub_sample_hits(n_averages=4, force_noise=1e-4, start_jitter_s=1 / 1024, seed=seed)
    estimate = estimate_frfs(records)
    assert [c.reasons for c in estimate.checks] == [()] * 8


def test_a_second_hit_through_the_same_filter_is_still_one() -> None:
    # The ringing rule must not hide a real second hit sampled alike: 8 ms after the first,
    # half its size.
    records = _sub_sample_hits(n_averages=2, second_hit=(8e-3, 0.5))
    assert all("double hit" in c.reasons for c in estimate_frfs(records).checks)
