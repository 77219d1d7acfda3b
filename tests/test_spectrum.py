"""The half-sine pulse spectrum (eq 11, Fig. 13) against direct integration."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from racketdyn.impact import half_sine_force, half_sine_spectrum

TC, FMAX = 4.2e-3, 900.0


def _numeric(f: float) -> float:
    def part(w: float) -> float:
        return float(quad(lambda t: FMAX * np.sin(np.pi * t / TC) * w(t), 0, TC, limit=200)[0])

    re = part(lambda t: np.cos(2 * np.pi * f * t))
    im = part(lambda t: np.sin(2 * np.pi * f * t))
    return float(np.hypot(re, im))


@pytest.mark.parametrize("u", [0.0, 0.1, 0.3, 0.5, 0.7, 1.0, 1.5, 2.2, 4.9])
def test_closed_form_matches_quadrature(u: float) -> None:
    f = u / TC
    assert half_sine_spectrum(f, TC, FMAX) == pytest.approx(_numeric(f), rel=1e-9, abs=1e-12)


def test_zero_frequency_is_the_impulse() -> None:
    assert half_sine_spectrum(0.0, TC, FMAX) == pytest.approx(2 * FMAX * TC / np.pi, rel=1e-15)


def test_removable_singularity_is_continuous() -> None:
    # cos(πu)/(1 − 4u²) is 0/0 at u = ½; its limit π/4 gives |S| = F_MAX T_c / 2.
    f_half = 0.5 / TC
    assert half_sine_spectrum(f_half, TC, FMAX) == pytest.approx(FMAX * TC / 2, rel=1e-15)
    near = half_sine_spectrum(f_half * (1 + np.array([-1e-9, 1e-9])), TC, FMAX)
    np.testing.assert_allclose(near, FMAX * TC / 2, rtol=1e-8)


def test_first_zero_at_one_and_a_half_over_tc() -> None:
    assert half_sine_spectrum(1.5 / TC, TC, FMAX) == pytest.approx(0.0, abs=1e-15 * FMAX * TC)


def test_pulse_integrates_to_mean_force_times_contact_time() -> None:
    t = np.linspace(-1e-3, TC + 1e-3, 200001)
    impulse = np.trapezoid(half_sine_force(t, TC, FMAX), t)
    assert impulse == pytest.approx(2 * FMAX * TC / np.pi, rel=1e-6)  # trapezoid error O(h²)
