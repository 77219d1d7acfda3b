"""The rig's random draws per support: one seed, a separate reproducible stream for each test.

Issue 27: one seed gave the free and the hand-held test identical fault counts (double hits,
overloads), the same draws hit for hit: both tests took ``numpy.random.default_rng(seed)``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from racketdyn.workflows.rig import RigOptions, run_rig, support_stream

FAULTS = {"averages": 2, "double_hits": 0.3, "overloads": 0.3, "seed": 7}


@pytest.fixture(scope="module")
def both(tmp_path_factory: pytest.TempPathFactory) -> object:
    return run_rig(
        tmp_path_factory.mktemp("both"), options=RigOptions(support=("free", "hand"), **FAULTS)
    )


def _pattern(result: object, support: str) -> np.ndarray:
    metadata = result.records[support].metadata  # type: ignore[attr-defined]
    return np.concatenate(
        [np.asarray(metadata["double_hit"]).ravel(), np.asarray(metadata["overload"]).ravel()]
    )


@pytest.mark.slow
def test_the_supports_draw_their_own_faults(both: object) -> None:
    free, hand = _pattern(both, "free"), _pattern(both, "hand")
    assert free.size == hand.size
    assert not np.array_equal(free, hand)
    for fault in ("double_hit", "overload"):  # each kind of fault drawn anew, hit by hit
        records = both.records  # type: ignore[attr-defined]
        assert not np.array_equal(
            records["free"].metadata[fault], records["hand"].metadata[fault]
        ), fault
    faults = both.faults  # type: ignore[attr-defined]
    assert faults["free"] != faults["hand"]


@pytest.mark.slow
def test_each_stream_is_reproducible_alone(both: object, tmp_path: Path) -> None:
    alone = run_rig(tmp_path, options=RigOptions(support="hand", **FAULTS))
    np.testing.assert_array_equal(_pattern(alone, "hand"), _pattern(both, "hand"))
    assert alone.faults["hand"] == both.faults["hand"]  # type: ignore[attr-defined]


def test_the_streams_are_named_by_support() -> None:
    def first(seed: int, support: str) -> float:
        return float(np.random.default_rng(support_stream(seed, support)).random())

    assert first(7, "free") == first(7, "free")
    assert first(7, "free") != first(7, "hand")
    assert first(7, "hand") != first(8, "hand")
    # the free test keeps the seed's own stream: its records are those of earlier versions
    assert first(7, "free") == float(np.random.default_rng(7).random())
