"""The racket's equations of motion by support, and the hand model, against closed forms.

Oracles: the reduced mass of eq 4 (racketdyn.racket, itself tested against the paper's grip
inertia); the receptance b_jᵀ(−ω²M + iωC + K)⁻¹b_j solved directly; Kawazoe's measurements of
a held racket (section 2; docs/references.md): frequencies a little lower, damping at least
twice the free racket's; Grabiner et al. (1983): grip firmness hardly changes the rebound.
"""

from __future__ import annotations

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.errors import InputError
from racketdyn.impact.hand import Hand
from racketdyn.impact.system import impact_system, point_system
from racketdyn.impact.transient import simulate_impact

POINTS = np.array([[0.505, 0.0], [0.62, 0.0], [0.55, 0.06], [0.42, -0.05]])


def _direct_receptance(system, frequency_hz):
    out = []
    for omega in 2 * np.pi * np.atleast_1d(frequency_hz):
        dynamic = -(omega**2) * system.mass + 1j * omega * system.damping + system.stiffness
        response = np.linalg.solve(dynamic, system.force_input.T).T
        out.append(np.einsum("pi,pi->p", system.force_input, response))
    return np.array(out).T


@pytest.mark.parametrize("support", ["free", "pinned", "hand"])
def test_pole_residue_is_the_receptance(racket, model, support) -> None:
    """Pole–residue form = direct solve of the equations of motion, 1e-10 (round-off of a
    12-coordinate eigen-decomposition), from below the rigid-body modes to above the modes."""
    system = impact_system(racket, model, support, POINTS)
    form = system.pole_residue()
    frequency = np.array([0.7, 13.0, 95.0, 240.0, 700.0, 2500.0])
    np.testing.assert_allclose(
        form.receptance(frequency), _direct_receptance(system, frequency), rtol=1e-10
    )


@pytest.mark.parametrize("support", ["free", "pinned"])
def test_rigid_compliance_is_the_reduced_mass(racket, model, support) -> None:
    """c_j = 1/M_r of eq 4 (free: with the roll term) to 1e-12."""
    form = impact_system(racket, model, support, POINTS).pole_residue()
    np.testing.assert_allclose(
        1.0 / form.rigid_compliance, racket.reduced_mass(POINTS, support), rtol=1e-12
    )


def test_free_modes_keep_their_frequency_and_damping(racket, model) -> None:
    """Free and pinned: the flexible poles are the model's ω_k, ζ_k exactly (1e-12)."""
    for support in ("free", "pinned"):
        poles = impact_system(racket, model, support, POINTS).pole_residue().poles
        order = np.argsort(np.abs(poles))
        np.testing.assert_allclose(np.abs(poles[order]), np.sort(model.omega), rtol=1e-12)
        zeta = -poles[order].real / np.abs(poles[order])
        np.testing.assert_allclose(zeta, model.damping_ratio[np.argsort(model.omega)], rtol=1e-9)


def test_point_system_without_rigid_body(ball) -> None:
    """A clamped head (M_r = ∞) has no rigid-body motion: zero rigid compliance."""
    system = point_system(np.inf, [0.3], [2 * np.pi * 100.0], [0.01])
    form = system.pole_residue()
    assert form.rigid_compliance[0] == 0.0
    assert form.poles.size == 1


def test_hand_held_racket_rings_lower_and_is_damped_more(racket, model) -> None:
    """Kawazoe section 2: held, the 2-node mode is a little lower (here within 10 %) and at
    least twice as damped as free."""
    free = impact_system(racket, model, "free", POINTS).pole_residue().poles
    held = impact_system(racket, model, "hand", POINTS).pole_residue().poles
    first = model.omega[0]
    near = held[np.argmin(np.abs(np.abs(held) - first))]
    free_pole = free[np.argmin(np.abs(np.abs(free) - first))]
    assert 0.9 * first < abs(near) < first
    assert -near.real / abs(near) > 2.0 * (-free_pole.real / abs(free_pole))


def test_hand_rigid_motion_is_racket_and_arm_together(racket, model) -> None:
    """With the arm free beyond the grip, the only rigid-body motion is the whole held system
    translating: c_j = 1/(M + m_hand + m_arm) at every point, 1e-10."""
    hand = Hand()
    form = impact_system(racket, model, "hand", POINTS, hand).pole_residue()
    total = racket.mass_kg + hand.hand_mass_kg + hand.arm_mass_kg
    np.testing.assert_allclose(form.rigid_compliance, 1.0 / total, rtol=1e-10)


def test_grip_firmness_hardly_changes_the_rebound(racket, ball, model) -> None:
    """Grabiner et al. (1983), measured at 10.6 m/s: grip firmness has no significant effect.
    Halving or doubling the grip's stiffness and damping moves the rebound ratio at the face
    centre by under 1 %."""
    base = simulate_impact(racket, ball, (0.505, 0.0), 10.6, "hand", modal_model=model)
    free = simulate_impact(racket, ball, (0.505, 0.0), 10.6, "free", modal_model=model)
    assert abs(base.rebound_ratio - free.rebound_ratio) > 1e-3 * free.rebound_ratio  # it acts
    for factor in (0.5, 2.0):
        hand = Hand(
            stiffness_n_per_m=Hand().stiffness_n_per_m * factor,
            damping_ns_per_m=Hand().damping_ns_per_m * factor,
        )
        held = simulate_impact(
            racket, ball, (0.505, 0.0), 10.6, "hand", modal_model=model, hand=hand
        )
        assert held.rebound_ratio == pytest.approx(base.rebound_ratio, rel=0.01)


def test_hand_energy_balance_and_reduced_mass(racket, ball, model) -> None:
    """Energy closes with the hand's share (1e-6); the held racket's own rigid-body energy is
    within 10 % of the free racket's at the same point (the grip is soft over 5 ms) while the
    hand, palm and arm take a small, positive share (under 5 % of the energy in); the hand's
    reduced mass is Kawazoe's arm at the handle: above free everywhere, barely at the centre."""
    point = (0.60, 0.03)
    held = simulate_impact(racket, ball, point, 20.0, "hand", modal_model=model)
    free = simulate_impact(racket, ball, point, 20.0, "free", modal_model=model)
    energy_in = 0.5 * ball.mass_kg * 20.0**2
    out = (
        0.5 * ball.mass_kg * held.rebound_speed_mps**2
        + held.racket_energy_j
        + held.vibration_energy_j
        + held.support_energy_j
        + held.hysteresis_loss_j
        + held.damping_loss_j
    )
    assert abs(out - energy_in) < 1e-6 * energy_in
    assert held.racket_energy_j == pytest.approx(free.racket_energy_j, rel=0.10)
    assert 0 < held.support_energy_j < 0.05 * energy_in
    assert free.support_energy_j == pytest.approx(0.0, abs=1e-9 * energy_in)
    free_mass = racket.reduced_mass(POINTS, "free")
    held_mass = Hand().reduced_mass(racket, POINTS)
    assert np.all(held_mass > free_mass)
    assert held_mass[0] < 1.05 * free_mass[0]


def test_hand_model_from_a_hand_held_model_is_refused(racket, model) -> None:
    """Adding a hand to modes measured in the hand would count the hand twice."""
    from dataclasses import replace

    held_model = replace(model, support="hand")
    with pytest.raises(InputError, match="already hand-held"):
        impact_system(racket, held_model, "hand", POINTS)


def test_critically_damped_mode_is_refused() -> None:
    """ζ = 1 makes the first-order eigenproblem defective: a clear error, not wrong numbers."""
    with pytest.raises(InputError, match="defective"):
        point_system(0.2, [0.5], [2 * np.pi * 100.0], [1.0]).pole_residue()
    assert point_system(0.2, [0.5], [2 * np.pi * 100.0], [1.2]).pole_residue().poles.size == 2


def test_bad_hand_and_support(racket, model) -> None:
    with pytest.raises(InputError, match="arm_mass_kg"):
        Hand(arm_mass_kg=-1.0)
    with pytest.raises(InputError, match="damping_ns_per_m"):
        Hand(damping_ns_per_m=float("nan"))
    with pytest.raises(InputError, match="grip"):
        Hand(grip_start_m=0.2, grip_end_m=0.1)
    with pytest.raises(InputError, match="support"):
        impact_system(racket, model, "clamped", POINTS)
    with pytest.raises(InputError, match="hand"):
        impact_system(racket, model, "free", POINTS, Hand())
    with pytest.raises(InputError, match="transient"):
        rd.impact.predict(racket, rd.Ball(), POINTS, [20.0], "hand")
