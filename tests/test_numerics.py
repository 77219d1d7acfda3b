"""Small numerical building blocks held to the libraries they stand in for."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.signal import find_peaks as scipy_find_peaks

from racketdyn.numerics import find_peaks

# few levels: flat tops and flat valleys of every width, ties between peaks and bases; NaN too
_SAMPLE = st.one_of(st.integers(0, 4).map(float), st.just(float("nan")))


def _same(values: np.ndarray, **conditions: float) -> None:
    peaks, properties = find_peaks(values, **conditions)
    expected, expected_properties = scipy_find_peaks(values, **conditions)
    np.testing.assert_array_equal(peaks, expected)
    assert peaks.dtype == expected.dtype
    assert properties.keys() == expected_properties.keys()
    for name, value in expected_properties.items():
        np.testing.assert_array_equal(properties[name], value, err_msg=name)


@settings(max_examples=300, deadline=None)
@given(
    values=st.lists(_SAMPLE, max_size=40),
    height=st.one_of(st.none(), st.floats(0, 4)),
    prominence=st.one_of(st.none(), st.floats(0, 4)),
)
@pytest.mark.slow
def test_find_peaks_is_scipys(
    values: list[float], height: float | None, prominence: float | None
) -> None:
    conditions = {
        name: value
        for name, value in (("height", height), ("prominence", prominence))
        if value is not None
    }
    _same(np.array(values, dtype=float), **conditions)


@pytest.mark.parametrize("seed", range(5))
def test_find_peaks_is_scipys_on_noisy_spectra(seed: int) -> None:
    # what identify gives it: a summed |H| over a few thousand lines, and its log
    rng = np.random.default_rng(seed)
    f = np.linspace(0, 1000, 3001)
    level = sum(1 / np.abs(fk**2 - f**2 + 2j * 0.01 * fk * f) for fk in (90, 160, 430, 610))
    level *= 1 + 0.05 * rng.standard_normal(f.size)
    _same(level, height=3 * float(np.median(level)))
    _same(np.log10(level), prominence=0.3)
