"""Oblique impacts and spin against analytic limits, conservation laws and symmetry.

Oracles (derivations in the module docstring of racketdyn.impact.oblique):
- pure sliding: F_t = −σ μ F_n throughout, so Δv_t = −σ μ J_n/m and Δω = σ μ J_n R/I exactly;
- no friction: nothing changes;
- rigid grip (k_t = inf): angular momentum about the contact point, m R v_t + I ω, is conserved
  and the ball leaves rolling: v_t,out = (v_t + k_I R ω_in)/(1 + k_I) (face at rest);
- elastic grip (μ → ∞): the contact point is a harmonic oscillator of mass m_eff = m/(1 + mR²/I)
  on k_t, energy ½ m v_t² + ½ I ω² + ½ k_t s² is conserved, and after half a period
  π √(m_eff/k_t) the contact-point velocity is reversed exactly (Cross's grip–reverse);
- energy is never created: friction loss ≥ 0 and in + out balance.

Synthetic half-sine normal forces (racketdyn.impact.oblique.NormalForce.half_sine) make the
unit tests exact; a few tests use the transient normal impact of the built-in racket.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import racketdyn.impact.oblique as oblique
from racketdyn.errors import InputError
from racketdyn.impact.oblique import (
    NormalForce,
    TangentialContact,
    oblique_curve,
    simulate_oblique,
    simulate_tangential,
)
from racketdyn.impact.transient import simulate_contact, simulate_impact

CENTRE = (0.505, 0.0)  # face centre of the built-in racket, m
PEAK = 1000.0  # N, a typical peak force at 15–20 m/s
DURATION = 0.005  # s, a typical contact time
ROUNDING = 1e-12  # relative: closed-form phases, only rounding and Brent's tolerance remain


@pytest.fixture(scope="module")
def pulse() -> NormalForce:
    return NormalForce.half_sine(PEAK, DURATION)


def _slip(ball, v_t: float, spin: float, face: float = 0.0) -> float:
    return v_t - 0.5 * ball.diameter_m * spin - face


def _inertia(ball, contact: TangentialContact) -> float:
    return contact.inertia_factor * ball.mass_kg * (0.5 * ball.diameter_m) ** 2


# --- 1. pure sliding ----------------------------------------------------------------------------
@pytest.mark.parametrize(("v_t", "spin"), [(10.0, 0.0), (-10.0, 0.0), (2.0, -200.0), (-3.0, 150.0)])
def test_pure_sliding_changes_velocity_and_spin_by_mu_times_the_normal_impulse(
    ball, pulse, v_t, spin
) -> None:
    """μ = 0.05 never stops the slip (μ J_n/m_eff < |u|): Δv = −σ μ J_n/m, Δω = σ μ J_n R/I."""
    contact = TangentialContact(friction_coefficient=0.05)
    impact = simulate_tangential(pulse, ball, v_t, spin, contact)
    assert [p[0] for p in impact.phases] == ["slide"]
    assert not impact.gripped
    assert math.isnan(impact.grip_time_s)
    sigma = math.copysign(1.0, _slip(ball, v_t, spin))
    j_n = 2.0 * PEAK * DURATION / math.pi  # ∫ F_max sin(πt/T) dt
    dv = -sigma * 0.05 * j_n / ball.mass_kg
    dw = sigma * 0.05 * j_n * 0.5 * ball.diameter_m / _inertia(ball, contact)
    assert impact.outgoing_tangential_speed_mps - v_t == pytest.approx(dv, rel=ROUNDING)
    assert impact.outgoing_spin_radps - spin == pytest.approx(dw, rel=ROUNDING)
    assert impact.tangential_impulse_ns == pytest.approx(-sigma * 0.05 * j_n, rel=ROUNDING)
    # the force is μ F_n against the slip at every sample
    np.testing.assert_allclose(
        impact.tangential_force_n, -sigma * 0.05 * impact.normal_force_n, rtol=1e-12, atol=1e-12
    )


def test_pure_sliding_on_the_transient_force_history(racket, ball) -> None:
    """Same law on the built-in racket's normal impact: J_n is the ball's momentum change.

    Tolerance 1e-8: the cubic spline's ∫F_n dt matches the transient impulse to ≈ 1e-10.
    """
    normal = simulate_impact(racket, ball, CENTRE, 17.0)
    force = NormalForce.from_impact(normal)
    contact = TangentialContact(friction_coefficient=0.03)
    impact = simulate_tangential(force, ball, 10.0, 0.0, contact)
    assert [p[0] for p in impact.phases] == ["slide"]
    dv = -0.03 * normal.impulse_ns / ball.mass_kg
    dw = 0.03 * normal.impulse_ns * 0.5 * ball.diameter_m / _inertia(ball, contact)
    assert impact.outgoing_tangential_speed_mps - 10.0 == pytest.approx(dv, rel=1e-8)
    assert impact.outgoing_spin_radps == pytest.approx(dw, rel=1e-8)


# --- 2. no friction ----------------------------------------------------------------------------
@pytest.mark.parametrize("stiffness", [1.0e4, math.inf])
def test_zero_friction_leaves_velocity_and_spin_unchanged(ball, pulse, stiffness) -> None:
    impact = simulate_tangential(pulse, ball, 7.0, 120.0, TangentialContact(0.0, stiffness))
    assert impact.outgoing_tangential_speed_mps == 7.0
    assert impact.outgoing_spin_radps == 120.0
    assert impact.tangential_impulse_ns == 0.0
    assert impact.friction_loss_j == 0.0
    assert not np.any(impact.tangential_force_n)


# --- 3. rigid grip -----------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("v_t", "spin", "face"), [(10.0, 0.0, 0.0), (5.0, -150.0, 0.0), (-4.0, 300.0, 0.0), (0, 0, 8.0)]
)
def test_rigid_grip_leaves_rolling_with_angular_momentum_about_the_contact_conserved(
    ball, pulse, v_t, spin, face
) -> None:
    """k_t = inf, μ = 0.4 (μ J_n ≫ m_eff |u|, so it grips): v_out = (v + k_I R ω)/(1 + k_I).

    In the face frame (v → v − V_f).  Tolerance: rounding (the phases are closed-form).
    """
    contact = TangentialContact(0.4, math.inf)
    impact = simulate_tangential(pulse, ball, v_t, spin, contact, face_speed=face)
    radius, k_i = 0.5 * ball.diameter_m, contact.inertia_factor
    assert impact.gripped
    v_out, w_out = impact.outgoing_tangential_speed_mps, impact.outgoing_spin_radps
    scale = abs(v_t - face) + radius * abs(spin)
    assert abs(v_out - face - radius * w_out) <= ROUNDING * scale
    expected = face + (v_t - face + k_i * radius * spin) / (1.0 + k_i)
    assert v_out == pytest.approx(expected, rel=ROUNDING, abs=ROUNDING * scale)
    assert impact.rolling_ratio == pytest.approx(1.0, rel=1e-9)
    # the slide lasts exactly until μ ∫F_n dt = m_eff |u_in|
    t_grip = impact.grip_time_s
    j_grip = PEAK * DURATION / math.pi * (1.0 - math.cos(math.pi * t_grip / DURATION))
    assert 0.4 * j_grip == pytest.approx(impact.effective_mass_kg * scale, rel=1e-12)


def test_stiff_tangential_spring_tends_to_the_rigid_grip(ball, pulse) -> None:
    """k_t → ∞ approaches the rigid grip, the error falling at least ~k_t^-1/2.

    Bound: after the first grip ½ m_eff u² + ½ k_t s² never grows, and at the grip it is at most
    ½ m_eff (μ Ḟ_max/k_t)² + ½ (μ F_max)²/k_t, so |u_out| ≤ μ √((Ḟ_max/k_t)² + F_max²/(k_t m_eff)).
    """
    rigid = simulate_tangential(pulse, ball, 10.0, -50.0, TangentialContact(0.4, math.inf))
    errors = []
    for k_t in (1.0e7, 1.0e8, 1.0e9):
        impact = simulate_tangential(pulse, ball, 10.0, -50.0, TangentialContact(0.4, k_t))
        m_eff, rate = impact.effective_mass_kg, PEAK * math.pi / DURATION
        bound = 0.4 * math.sqrt((rate / k_t) ** 2 + PEAK**2 / (k_t * m_eff))
        assert abs(impact.contact_velocity_mps[-1]) <= bound
        errors.append(
            abs(impact.outgoing_tangential_speed_mps - rigid.outgoing_tangential_speed_mps)
        )
    assert errors[1] < errors[0] / math.sqrt(10.0)
    assert errors[2] < errors[1] / math.sqrt(10.0)


# --- 4. elastic grip ---------------------------------------------------------------------------
@pytest.mark.parametrize(("periods", "reversal"), [(0.5, -1.0), (1.0, 1.0)])
def test_elastic_grip_is_a_harmonic_oscillation_of_the_effective_mass(
    ball, periods, reversal
) -> None:
    """μ = 1000 (never slides), k_t = 10⁴ N/m, contact time = ½ or 1 period 2π √(m_eff/k_t).

    After half a period the contact-point velocity is reversed (u_out = −u_in: the ball leaves
    with spin beyond rolling), after a full period restored; the tangential energy is constant
    at every sample.  Tolerance: rounding.
    """
    contact = TangentialContact(1.0e3, 1.0e4)
    m_eff = ball.mass_kg / (
        1.0 + ball.mass_kg * (0.5 * ball.diameter_m) ** 2 / _inertia(ball, contact)
    )
    assert contact.effective_mass(ball) == pytest.approx(m_eff, rel=1e-15)
    period = 2.0 * math.pi * math.sqrt(m_eff / 1.0e4)
    assert contact.grip_period(ball) == pytest.approx(period, rel=1e-15)
    force = NormalForce.half_sine(800.0, periods * period)
    v_t, spin = 5.0, 40.0
    impact = simulate_tangential(force, ball, v_t, spin, contact)
    u_in = _slip(ball, v_t, spin)
    assert [p[0] for p in impact.phases] == ["grip"]
    assert impact.grip_time_s == 0.0
    assert impact.contact_velocity_mps[-1] == pytest.approx(reversal * u_in, rel=ROUNDING)
    energy = impact.energy_j
    assert np.max(np.abs(energy - impact.incoming_energy_j)) <= ROUNDING * impact.incoming_energy_j
    assert impact.friction_loss_j == 0.0
    # u(t) = u_in cos(ω t) while gripping
    omega = 2.0 * math.pi / period
    np.testing.assert_allclose(
        impact.contact_velocity_mps, u_in * np.cos(omega * impact.time_s), rtol=0, atol=1e-12
    )


@pytest.mark.xfail(
    strict=True,
    reason="with the bounce-stiff ball the default tangential contact grips from the first "
    "instant at 30° (grip time 0; it still reverses the force); at 50° it slides first and "
    "grips at 4.2 ms. Cross (2003, measured) has the ball slide a short way first at such "
    "angles; the default k_t (grip half period = contact time) stays until spin or e_x "
    "measured on strings can be read (docs/references.md, 'Oblique impacts and spin')",
)
def test_default_contact_grips_and_the_friction_force_reverses(racket, ball) -> None:
    """The default k_t (grip half period ≈ contact time) reproduces Cross's grip–reverse.

    20 m/s at 30° to the normal on the face centre: the ball slides, grips, the tangential force
    changes sign during the contact and the ball leaves with spin beyond rolling (Rω > v_t).
    """
    impact = simulate_oblique(racket, ball, CENTRE, 20.0, 30.0)
    assert impact.gripped
    assert 0.0 < impact.grip_time_s < impact.normal.contact_time_s
    force = impact.tangential_force_n
    assert force.min() < 0.0 < force.max()
    assert impact.tangential is not None
    assert impact.tangential.rolling_ratio > 1.0


# --- 4b. against measurement: the ball on head-clamped strings ----------------------------------
def _on_clamped_strings(ball, law, angle_deg: float, speed: float = 20.0):
    """The tangential part of a ball at ``speed`` and ``angle_deg`` (no spin) on the head-clamped
    strings at the face centre: the frame held still (reduced mass inf), as in Cross's rig."""
    v_n = speed * math.cos(math.radians(angle_deg))
    normal = simulate_contact(ball.mass_kg, float(ball.e_bg_at(v_n)), law, math.inf, v_n)
    force = NormalForce.from_impact(normal)
    return simulate_tangential(force, ball, speed * math.sin(math.radians(angle_deg)))


@pytest.mark.parametrize("angle", [40.0, 45.0])
def test_nearer_the_normal_the_ball_slides_then_grips_clamped_strings(ball, law, angle) -> None:
    """Cross, Sports Eng. 6 (2003) 235–254 (measured, head-clamped racket; docs/references.md,
    "Oblique impacts and spin"): at angles of incidence more than about 40° to the string plane
    (less than about 50° from the normal) the ball slides across the strings a short way and
    then grips them.  40° and 45° from the normal lie 5–10° inside that "about"."""
    impact = _on_clamped_strings(ball, law, angle)
    assert impact.phases[0][0] == "slide"
    assert impact.gripped
    assert 0.0 < impact.grip_time_s < impact.time_s[-1]


@pytest.mark.xfail(
    strict=True,
    reason="the ball grips before it leaves (at 55°: 4.6 of 5.7 ms; at 60°: 5.2 of 5.8 ms). "
    "With μ = 0.4 it can slide throughout only where μ J_n < m_eff u_in, tan θ > μ (1 + e) "
    "(1 + k_I)/k_I: beyond ≈ 64° from the normal, ≈ 14° past Cross's ≈ 50°. Cross's own "
    "sliding μ and spin against angle (the paper's body) were not readable, so neither μ nor "
    "k_t was changed (docs/references.md, 'Oblique impacts and spin')",
)
@pytest.mark.parametrize("angle", [55.0, 60.0])
def test_far_from_the_normal_the_ball_slides_throughout_on_clamped_strings(
    ball, law, angle
) -> None:
    """Cross, Sports Eng. 6 (2003) 235–254 (measured, head-clamped racket): at angles of
    incidence below about 40° to the string plane (beyond about 50° from the normal) the ball
    slides across the strings for the whole bounce.  55° and 60° from the normal lie 5–10°
    beyond that "about"."""
    impact = _on_clamped_strings(ball, law, angle)
    assert [phase[0] for phase in impact.phases] == ["slide"]
    assert not impact.gripped


# --- 5. convergence ------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("mu", "k_t", "spin"), [(0.05, 1.0e4, 0.0), (0.4, 1.0e5, -100.0), (0.3, 3.0e4, 0.0)]
)
def test_sampled_force_history_converges_at_fourth_order(ball, pulse, mu, k_t, spin) -> None:
    """The only discretisation is the cubic-spline F_n: error ∝ h⁴ as the sampling halves.

    Half-sine sampled at 50 … 800 intervals against the exact functions; fitted order within
    3.5–4.6 (measured 3.9–4.0 for these slide / slide–grip–slide cases).
    """
    contact = TangentialContact(mu, k_t)
    exact = simulate_tangential(pulse, ball, 10.0, spin, contact).outgoing_spin_radps
    n_intervals = np.array([50, 100, 200, 400, 800])
    errors = []
    for n in n_intervals:
        t = np.linspace(0.0, DURATION, n + 1)
        force = np.maximum(PEAK * np.sin(np.pi * t / DURATION), 0.0)
        sampled = NormalForce.from_samples(t, force)
        spin_out = simulate_tangential(sampled, ball, 10.0, spin, contact).outgoing_spin_radps
        errors.append(abs(spin_out - exact) / abs(exact))
    order = -np.polyfit(np.log(n_intervals), np.log(errors), 1)[0]
    assert 3.5 < order < 4.6


def test_phase_changes_do_not_depend_on_the_bracketing_grid(ball, pulse, monkeypatch) -> None:
    """Brent's method finds each phase change to machine precision once it is bracketed."""
    contact = TangentialContact(0.4, 1.0e6)  # 9 grip/slide phases
    coarse = simulate_tangential(pulse, ball, 10.0, -50.0, contact)
    monkeypatch.setattr(oblique, "_MIN_CHECKPOINTS", 4 * oblique._MIN_CHECKPOINTS)
    monkeypatch.setattr(oblique, "_CHECKPOINTS_PER_PERIOD", 4 * oblique._CHECKPOINTS_PER_PERIOD)
    fine = simulate_tangential(pulse, ball, 10.0, -50.0, contact)
    assert len(coarse.phases) == len(fine.phases) > 3
    for (kind_a, start_a, _), (kind_b, start_b, _) in zip(coarse.phases, fine.phases, strict=True):
        assert kind_a == kind_b
        assert start_a == pytest.approx(start_b, rel=1e-12, abs=1e-15)
    assert fine.outgoing_spin_radps == pytest.approx(coarse.outgoing_spin_radps, rel=1e-11)


# --- 6. normal impact and symmetry -------------------------------------------------------------
def test_normal_impact_without_spin_has_no_tangential_force(racket, ball) -> None:
    impact = simulate_oblique(racket, ball, CENTRE, 20.0, 0.0)
    assert impact.tangential_speed_mps == 0.0
    assert impact.outgoing_spin_radps == 0.0
    assert impact.outgoing_angle_deg == 0.0
    assert impact.friction_loss_j == 0.0
    assert not np.any(impact.tangential_force_n)
    normal = simulate_impact(racket, ball, CENTRE, 20.0)
    assert impact.normal_speed_mps == normal.rebound_speed_mps


def test_mirrored_impact_mirrors_the_tangential_outputs(racket, ball) -> None:
    """θ → −θ, ω → −ω, V_f → −V_f flips every tangential output and keeps the energies."""
    a = simulate_oblique(racket, ball, CENTRE, 20.0, 30.0, 100.0, racket_tangential_speed=2.0)
    b = simulate_oblique(racket, ball, CENTRE, 20.0, -30.0, -100.0, racket_tangential_speed=-2.0)
    assert b.normal_speed_mps == a.normal_speed_mps
    for name in ("tangential_speed_mps", "outgoing_angle_deg", "outgoing_spin_radps"):
        assert getattr(b, name) == pytest.approx(-getattr(a, name), rel=ROUNDING)
    assert b.tangential_impulse_ns == pytest.approx(-a.tangential_impulse_ns, rel=ROUNDING)
    assert b.friction_loss_j == pytest.approx(a.friction_loss_j, rel=ROUNDING)
    np.testing.assert_allclose(b.tangential_force_n, -a.tangential_force_n, rtol=1e-12, atol=1e-9)


# --- 7. energy -----------------------------------------------------------------------------------
@settings(max_examples=60, deadline=None)
@given(
    v_t=st.floats(-20.0, 20.0),
    spin=st.floats(-400.0, 400.0),
    face=st.floats(-10.0, 10.0),
    mu=st.floats(0.0, 2.0),
    log_k=st.floats(3.0, 8.0),
    peak=st.floats(100.0, 3000.0),
    duration=st.floats(0.002, 0.008),
)
def test_energy_is_never_created(ball, v_t, spin, face, mu, log_k, peak, duration) -> None:
    """Friction loss ≥ 0; in = out + friction + spring (to 1e-10 of the incoming energy); the
    face-frame energy never rises during the contact; |u_out| ≤ |u_in|."""
    force = NormalForce.half_sine(peak, duration)
    impact = simulate_tangential(force, ball, v_t, spin, TangentialContact(mu, 10.0**log_k), face)
    energy_in = impact.incoming_energy_j
    scale = max(energy_in, 1e-12)
    assert impact.friction_loss_j >= -1e-12 * scale
    balance = energy_in - impact.outgoing_energy_j - impact.friction_loss_j
    assert abs(balance - impact.spring_energy_j) <= 1e-10 * scale
    assert np.all(np.diff(impact.energy_j) <= 1e-10 * scale)
    u_in = _slip(ball, v_t, spin, face)
    assert abs(impact.contact_velocity_mps[-1]) <= abs(u_in) * (1.0 + 1e-9) + 1e-12


def test_friction_only_lowers_the_outgoing_angle(racket, ball) -> None:
    """Face at rest, no incoming spin: 0 ≤ v_t,out ≤ v_t,in, so the outgoing angle lies below
    the frictionless one atan(v sin θ / v_n,out) and the ball gains spin in the rolling sense."""
    for angle in (15.0, 30.0, 50.0):
        impact = simulate_oblique(racket, ball, CENTRE, 20.0, angle)
        v_t = 20.0 * math.sin(math.radians(angle))
        frictionless = math.degrees(math.atan2(v_t, impact.normal_speed_mps))
        assert 0.0 <= impact.tangential_speed_mps < v_t
        assert 0.0 <= impact.outgoing_angle_deg < frictionless
        assert impact.outgoing_spin_radps > 0.0


# --- the curve -----------------------------------------------------------------------------------
def test_oblique_curve_matches_single_impacts_and_is_odd_in_the_angle(racket, ball) -> None:
    angles = np.array([-40.0, -20.0, 0.0, 20.0, 40.0])
    curve = oblique_curve(racket, ball, CENTRE, 20.0, angles)
    assert curve.outgoing_angle_deg.shape == angles.shape
    assert np.all(curve.status == "ok")
    single = simulate_oblique(racket, ball, CENTRE, 20.0, 20.0)
    assert curve.outgoing_angle_deg[3] == pytest.approx(single.outgoing_angle_deg, rel=1e-12)
    assert curve.outgoing_spin_radps[3] == pytest.approx(single.outgoing_spin_radps, rel=1e-12)
    np.testing.assert_allclose(curve.outgoing_angle_deg, -curve.outgoing_angle_deg[::-1], atol=1e-9)
    np.testing.assert_allclose(
        curve.outgoing_spin_radps, -curve.outgoing_spin_radps[::-1], atol=1e-7
    )
    # spins broadcast against angles
    grid = oblique_curve(racket, ball, CENTRE, 20.0, [[10.0], [30.0]], [0.0, 200.0])
    assert grid.outgoing_spin_radps.shape == (2, 2)


# --- bad input ---------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "kwargs",
    [
        {"friction_coefficient": -0.1},
        {"friction_coefficient": math.nan},
        {"stiffness_n_per_m": 0.0},
        {"stiffness_n_per_m": -1.0e4},
        {"stiffness_n_per_m": math.nan},
        {"inertia_factor": 0.0},
        {"inertia_factor": 0.7},
    ],
)
def test_bad_contact_is_an_input_error(kwargs) -> None:
    with pytest.raises(InputError):
        TangentialContact(**kwargs)


@pytest.mark.parametrize(
    ("angle", "spin", "speed"),
    [(90.0, 0.0, 20.0), (-90.0, 0.0, 20.0), (120.0, 0.0, 20.0), (math.nan, 0.0, 20.0),
     (30.0, math.nan, 20.0), (30.0, math.inf, 20.0), (30.0, 0.0, -5.0)],
)  # fmt: skip
def test_bad_impact_is_an_input_error(racket, ball, angle, spin, speed) -> None:
    with pytest.raises(InputError):
        simulate_oblique(racket, ball, CENTRE, speed, angle, spin)


def test_bad_inputs_to_the_tangential_model(ball, pulse) -> None:
    with pytest.raises(InputError):
        simulate_tangential(pulse, ball, math.nan)
    with pytest.raises(InputError):
        simulate_tangential(pulse, ball, 1.0, face_speed=math.inf)
    with pytest.raises(InputError):
        NormalForce.from_samples([0.0, 1e-3, 2e-3, 3e-3], [0.0, 10.0, -1.0, 0.0])
    with pytest.raises(InputError):
        NormalForce.from_samples([0.0, 2e-3, 1e-3, 3e-3], [0.0, 10.0, 5.0, 0.0])
    with pytest.raises(InputError):
        NormalForce.half_sine(-1.0, 1e-3)
    with pytest.raises(InputError):
        oblique_curve(racket=None, ball=ball, location=CENTRE, ball_speed=20.0, angles_deg=[95.0])  # type: ignore[arg-type]
