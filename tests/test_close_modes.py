"""Several modes under one peak (racketdyn.modal.identify's close pairs): what the wide band's
fit already parts is never fitted again with fewer poles.

The twelfth session's close-pair fit refits two poles on the lines round a kept mode with a
neighbour within their half-power width, in place of the mode and every kept mode within one
peak of them.  Three modes under one peak that the wide band's LSCF had all kept became two:
the third was lost without a word.
"""

from __future__ import annotations

import numpy as np
import pytest

from racketdyn.measurement.records import FrfSet
from racketdyn.modal.identify import identify

POINTS = np.linspace(0.0, 1.0, 15)


def _frfs(modes: list[tuple[float, float]], seed: int = 1) -> FrfSet:
    """Accelerances at 15 points along a line against the second, of modes with the shapes
    sin/cos of a few half-waves (unlike one another), 0–800 Hz on 0.2 Hz lines, white noise at
    0.1 % of each FRF's largest magnitude."""
    shapes = [
        np.sin(np.pi * POINTS + 0.2),
        np.cos(2 * np.pi * POINTS),
        np.sin(3 * np.pi * POINTS + 0.3),
        np.cos(5 * np.pi * POINTS),
        np.sin(4 * np.pi * POINTS + 0.5),
    ]
    frequency = np.linspace(0.0, 800.0, 4001)
    w = 2 * np.pi * frequency
    values = np.zeros((POINTS.size, frequency.size), dtype=complex)
    for (f_n, zeta), phi in zip(modes, shapes, strict=False):
        wn = 2 * np.pi * f_n
        modal = -(w**2) / (wn**2 - w**2 + 2j * zeta * wn * w)
        values += (phi * phi[1])[:, None] * modal[None, :]
    rng = np.random.default_rng(seed)
    noise = rng.standard_normal(values.shape) + 1j * rng.standard_normal(values.shape)
    values += 1e-3 * np.abs(values).max(axis=1, keepdims=True) * noise / np.sqrt(2)
    return FrfSet(
        frequency=frequency,
        values=values,
        nodes=np.arange(1, POINTS.size + 1),
        locations=np.column_stack([POINTS, np.zeros_like(POINTS)]),
        frf_type="accelerance",
        reference_node=2,
        reference_location=(float(POINTS[1]), 0.0),
        source="three modes under one peak",
    )


def test_three_modes_the_wide_fit_parts_are_all_kept() -> None:
    """297, 300 and 303.5 Hz at ζ 0.6 % (half-power widths 3.6 Hz: each within one of the
    next), with 120 and 520 Hz apart: the wide band's LSCF parts the three; the close-pair fit
    replaced them with two (297.01, 299.99 Hz) and 303.5 Hz was gone."""
    truth = [(120.0, 0.005), (297.0, 0.006), (300.0, 0.006), (303.5, 0.006), (520.0, 0.005)]
    found = identify(_frfs(truth), (40.0, 780.0))
    assert found.model.n_modes == len(truth)
    for f_n, zeta in truth:
        k = int(np.argmin(np.abs(found.model.frequency - f_n)))
        assert found.model.frequency[k] == pytest.approx(f_n, rel=1e-3)
        assert found.model.damping_ratio[k] == pytest.approx(zeta, rel=0.2)
