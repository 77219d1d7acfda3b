"""Racket twist against the offset of an off-axis hit.

Oracles: a rigid free racket turns about its long axis at J (y − y_G)/I_roll after a normal
impulse J at offset y (angular impulse about the centre of mass; y_G = 0 and no product of
inertia for the built-in racket); mirror symmetry of a symmetric racket; the hand's roll
spring and damper can only hold the racket back.
"""

from __future__ import annotations

import numpy as np
import pytest

from racketdyn.errors import InputError
from racketdyn.impact.transient import simulate_impact
from racketdyn.impact.twist import twist_curve

OFFSETS = np.array([-0.07, -0.035, 0.0, 0.035, 0.07])


def test_rigid_roll_rate_is_the_angular_impulse(racket, ball) -> None:
    """Rigid free racket: roll rate = J y / I_roll to 1e-9 at every offset."""
    curve = twist_curve(racket, ball, 0.52, OFFSETS, 25.0, "free", modal_model=None)
    i_roll = racket.mass_properties.inertia_kgm2[0, 0]
    for y, rate in zip(OFFSETS, curve.roll_rate_radps, strict=True):
        impulse = simulate_impact(
            racket, ball, (0.52, y), 25.0, "free", modal_model=None
        ).impulse_ns
        assert rate == pytest.approx(impulse * y / i_roll, rel=1e-9, abs=1e-12)
    np.testing.assert_array_equal(curve.flexible_twist_rad, 0.0)


def test_twist_is_odd_and_the_rebound_even_in_the_offset(racket, ball, model) -> None:
    """Mirror symmetry: twist(−y) = −twist(y), rebound(−y) = rebound(y) (1e-9 of the largest);
    the twist grows and the rebound falls with |y|."""
    curve = twist_curve(racket, ball, 0.52, OFFSETS, 25.0, "free", modal_model=model)
    scale = np.abs(curve.total_twist_rad).max()
    np.testing.assert_allclose(
        curve.total_twist_rad, -curve.total_twist_rad[::-1], atol=1e-9 * scale
    )
    np.testing.assert_allclose(curve.rebound_speed_mps, curve.rebound_speed_mps[::-1], rtol=1e-9)
    assert np.all(np.diff(curve.roll_angle_rad) > 0)
    assert np.argmax(curve.rebound_speed_mps) == 2


def test_the_hand_holds_the_racket_back(racket, ball, model) -> None:
    """The grip's roll spring and damper lower the roll rate at every off-axis point."""
    free = twist_curve(racket, ball, 0.52, OFFSETS[3:], 25.0, "free", modal_model=model)
    held = twist_curve(racket, ball, 0.52, OFFSETS[3:], 25.0, "hand", modal_model=model)
    assert np.all(held.roll_rate_radps < free.roll_rate_radps)


def test_bad_input(racket, ball) -> None:
    with pytest.raises(InputError, match="offsets_m"):
        twist_curve(racket, ball, 0.52, [], 25.0)
    with pytest.raises(InputError, match="outside the string"):
        twist_curve(racket, ball, 0.52, [0.3], 25.0)
    with pytest.raises(InputError, match="ball speed"):
        twist_curve(racket, ball, 0.52, [0.0], float("nan"))
