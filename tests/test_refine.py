"""The local fit of a narrow mode's peak (``racketdyn.modal.refine``).

Oracle: the DFT of ringing cut at a record's end (3.2 s, 0.3125 Hz lines; no window) of four
modes with known poles, 0.1 % noise.  The 34.05 Hz mode's half-power width, 0.014 Hz, is a
twentieth of a line (vtb_siglab case 1's, whose LSCF damping was +56 % off sdypy-EMA's: the
real-data repro is ``tests/test_realdata_must_hold.py``).  An unsettled narrow mode given a
damping 60 % too high comes back within 5 % of the truth; a settled or a wide one is left alone.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from racketdyn.measurement.records import FrfSet
from racketdyn.modal.poles import SelectedPoles, select_poles, stabilisation
from racketdyn.modal.refine import refine_narrow_poles

RATE_HZ, SAMPLES = 1280.0, 4096
MODES = ((34.05, 0.0002), (121.3, 0.002), (212.1, 0.0009), (305.0, 0.003))  # Hz, ζ


def _ringing_frfs() -> FrfSet:
    """Receptances of four points from the DFT of each one's impulse response, cut at 3.2 s."""
    time = np.arange(SAMPLES) / RATE_HZ
    rng = np.random.default_rng(1)
    rows = []
    for point in range(4):
        response = np.zeros(SAMPLES)
        for j, (f, zeta) in enumerate(MODES):
            omega = 2 * np.pi * f
            damped = omega * np.sqrt(1 - zeta**2)
            shape = np.cos(0.7 * (point + 1) * (j + 1))
            response += shape * np.exp(-zeta * omega * time) * np.sin(damped * time) / damped
        rows.append(np.fft.rfft(response) / RATE_HZ)
    frequency = np.fft.rfftfreq(SAMPLES, 1 / RATE_HZ)
    keep = (frequency > 0) & (frequency <= 500)
    values = np.array(rows)[:, keep]
    noise = rng.standard_normal(values.shape) + 1j * rng.standard_normal(values.shape)
    return FrfSet(
        frequency=frequency[keep],
        values=values + 1e-3 * np.abs(values).max() * noise,
        frf_type="receptance",
        nodes=(1, 2, 3, 4),
        locations=np.full((4, 2), np.nan),
        reference_node=1,
        reference_location=(np.nan, np.nan),
        source="ringing",
    )


def _off(selected: SelectedPoles, k: int, *, orders: int) -> SelectedPoles:
    """The selection with mode ``k``'s damping 60 % high, stable in ``orders`` orders."""
    zeta = selected.damping_ratio.copy()
    zeta[k] *= 1.6
    omega = 2 * np.pi * selected.frequency
    n_orders = selected.n_orders.copy()
    n_orders[k] = orders
    pole = -zeta * omega + 1j * omega * np.sqrt(1 - zeta**2)
    return replace(selected, damping_ratio=zeta, pole=pole, n_orders=n_orders)


@pytest.fixture(scope="module")
def ringing() -> tuple[FrfSet, SelectedPoles]:
    frfs = _ringing_frfs()
    selected = select_poles(stabilisation(frfs, (20.0, 450.0)))
    assert selected.frequency == pytest.approx([f for f, _ in MODES], rel=1e-3)
    return frfs, selected


def test_an_unsettled_narrow_mode_gets_its_damping_from_its_peak(
    ringing: tuple[FrfSet, SelectedPoles],
) -> None:
    frfs, selected = ringing
    refined, lines = refine_narrow_poles(frfs, _off(selected, 0, orders=5))
    (line,) = lines
    assert line.startswith("34.05 Hz")
    assert refined.damping_ratio[0] == pytest.approx(MODES[0][1], rel=0.05)
    assert refined.frequency[0] == pytest.approx(MODES[0][0], rel=1e-5)
    assert abs(refined.pole[0]) / (2 * np.pi) == pytest.approx(refined.frequency[0])
    np.testing.assert_array_equal(refined.damping_ratio[1:], selected.damping_ratio[1:])


def test_a_settled_or_wide_mode_keeps_its_pole(ringing: tuple[FrfSet, SelectedPoles]) -> None:
    frfs, selected = ringing
    settled = _off(selected, 0, orders=selected.n_orders_computed)
    assert refine_narrow_poles(frfs, settled) == (settled, [])
    wide = _off(selected, 3, orders=5)  # 305 Hz: 2ζf = 1.8 Hz, six lines
    assert refine_narrow_poles(frfs, wide) == (wide, [])
