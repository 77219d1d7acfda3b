"""The approximate method (eqs 1–12) against closed-form limits and conservation laws."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp, trapezoid
from scipy.optimize import brentq
from scipy.special import beta

import racketdyn as rd
from racketdyn.impact import half_sine_spectrum, predict
from racketdyn.impact.approximate import contact_spectra, elastic_contact_time
from racketdyn.impact.result import (
    STATUS_BEYOND_LAW,
    STATUS_VIBRATION_LOSS,
    STATUS_VIBRATION_SHARE,
)

LINEAR_K = 2.0e4  # N/m

# analytic limits of the contact with test laws far softer than a ball's, over the whole grid:
# the contact's mechanics, not the hoop's geometry (tests/test_frame_shots.py tests that)
pytestmark = pytest.mark.usefixtures("strings_only")


@pytest.fixture(scope="module")
def linear() -> rd.RestoringForce:
    return rd.RestoringForce("polynomial", (LINEAR_K,), 0.2, 0.0, "linear test spring")


def _single_mode(racket: rd.Racket, shape: float, frequency: float) -> rd.ModalModel:
    """One mode with the same (mass-normalised) amplitude everywhere on the face."""
    grid = racket.head.grid(6)
    return rd.ModalModel(
        np.array([frequency]), np.array([0.0]), grid, np.full((len(grid), 1), shape), ("test mode",)
    )


def test_linear_spring_contact_time_is_half_period(racket, ball, linear) -> None:
    # the paper's charge: eq 7's half period, eq 8's impulse and eq 11's half sine
    points = racket.head.grid(5)
    speeds = [5, 20, 40]
    paper = predict(
        racket, ball, points, speeds, modal_model=None, law=linear, vibration_charge="paper"
    )
    m_r = paper.reduced_mass[:, None, :]
    mu = ball.mass_kg * m_r / (ball.mass_kg + m_r)
    expected = np.broadcast_to(np.pi * np.sqrt(mu / LINEAR_K), paper.shape)
    np.testing.assert_allclose(paper.contact_time, expected, rtol=1e-12)
    speed = paper.ball_speed[None, :, None]
    np.testing.assert_allclose(paper.impulse, (1 + ball.e_bg) * mu * speed, rtol=1e-12)
    np.testing.assert_allclose(paper.peak_force, np.pi * paper.mean_force / 2, rtol=1e-14)
    np.testing.assert_allclose(
        paper.peak_force, (1 + ball.e_bg) * speed * np.sqrt(mu * LINEAR_K) / 2, rtol=1e-9
    )
    # the coupled charge (default): the spring's force where it holds ½ μ V², V_rel·sqrt(μ k),
    # the same impulse, and a contact that loads in a quarter period and unloads along the
    # hysteresis curve F = k X (X/X_p)^p, a power law of exponent 1 + p with 2 + p = 2/e²:
    # its quarter period is sqrt(μ m / 2k) B(1/m, ½) / m with m = 2/e², whatever the speed
    coupled = predict(racket, ball, points, speeds, modal_model=None, law=linear)
    np.testing.assert_allclose(coupled.peak_force, speed * np.sqrt(mu * LINEAR_K), rtol=1e-9)
    np.testing.assert_allclose(coupled.impulse, paper.impulse, rtol=1e-12)
    m = 2.0 / ball.e_bg**2
    unloading = np.sqrt(mu * m / (2 * LINEAR_K)) * beta(1 / m, 0.5) / m
    np.testing.assert_allclose(coupled.contact_time, expected / 2 + unloading, rtol=1e-8)


def _direct_contact(law: rd.RestoringForce, mu: float, speed: float) -> tuple[float, float]:
    """Contact time and peak deflection of μ ẍ = −F(x) from x = 0, ẋ = V, integrated."""

    def rhs(t: float, state: np.ndarray) -> list[float]:
        return [state[1], -float(law.force(max(state[0], 0.0))) / mu]

    def separation(t: float, state: np.ndarray) -> float:
        return state[0] if t > 0 else 1.0

    separation.terminal = True  # type: ignore[attr-defined]
    separation.direction = -1  # type: ignore[attr-defined]
    solution = solve_ivp(
        rhs,
        (0, 0.05),
        [0.0, speed],
        events=separation,
        rtol=1e-12,
        atol=1e-15,
        method="DOP853",
        dense_output=True,
    )
    t_c = float(solution.t_events[0][0])
    peak = float(solution.sol(t_c / 2)[0])
    return t_c, peak


@pytest.mark.parametrize("speed", [5.0, 20.0, 40.0])
def test_period_reading_is_the_exact_contact_time(racket, ball, law, speed) -> None:
    # Default reading of eq 10: the half period of the nonlinear ball+string contact itself
    # (the paper's charge; the coupled charge's contact unloads along the hysteresis, held to
    # the transient model in test_ball_bounce.py).  Oracle: a time integration of
    # μ ẍ = −F_GB(x) (tolerances 1e-12); the Gauss–Legendre quadrature must agree to 1e-6.
    point = [racket.head.centre_x_m + 0.05, 0.02]
    result = predict(
        racket, ball, point, [speed], ("free",), modal_model=None, law=law, vibration_charge="paper"
    )
    mu = ball.mass_kg * result.reduced_mass[0, 0] / (ball.mass_kg + result.reduced_mass[0, 0])
    t_c, peak = _direct_contact(law, mu, speed)
    assert result.contact_time[0, 0, 0] == pytest.approx(t_c, rel=1e-6)
    assert result.peak_deflection[0, 0, 0] == pytest.approx(peak, rel=1e-6)
    assert result.stiffness[0, 0, 0] == pytest.approx(np.pi**2 * mu / t_c**2, rel=2e-6)  # eq 7


def test_tangent_reading_is_the_papers_shortcut(racket, ball, law, linear) -> None:
    # The tangent stiffness at the peak is the stiffest the contact gets: T_c shorter than the
    # exact one for a stiffening law, F_MAX = F_GB(X_p), and equal to the period reading for a
    # linear spring.
    centre = [racket.head.centre_x_m, 0.0]
    speeds = [10.0, 20.0, 30.0]
    tangent = predict(
        racket, ball, centre, speeds, modal_model=None, law=law, stiffness_reading="tangent"
    )
    period = predict(racket, ball, centre, speeds, modal_model=None, law=law)
    assert np.all(tangent.contact_time < period.contact_time)
    np.testing.assert_allclose(tangent.peak_force, law.force(tangent.peak_deflection), rtol=1e-10)
    np.testing.assert_allclose(
        tangent.stiffness, law.stiffness(tangent.peak_deflection), rtol=1e-12
    )
    lin_t = predict(
        racket, ball, centre, speeds, modal_model=None, law=linear, stiffness_reading="tangent"
    )
    lin_p = predict(
        racket, ball, centre, speeds, modal_model=None, law=linear, vibration_charge="paper"
    )
    np.testing.assert_allclose(lin_t.contact_time, lin_p.contact_time, rtol=1e-12)
    # the tangent reading is the paper's shortcut whatever the charge: eq 11's half sine
    np.testing.assert_allclose(lin_t.peak_force, lin_p.peak_force, rtol=1e-12)
    np.testing.assert_allclose(lin_t.mean_force, lin_p.mean_force, rtol=1e-12)


def test_rigid_racket_rebound_from_momentum_and_e(racket, ball, law) -> None:
    # Two bodies, ball m and reduced mass M, COR e_BG: solve momentum and restitution directly
    # in the lab frame with the racket moving towards the ball.
    points = racket.head.grid(4)
    v_ball = np.array([10.0, 25.0])
    v_racket = np.array([0.0, 15.0])
    result = predict(racket, ball, points, v_ball, racket_speed=v_racket, modal_model=None, law=law)
    m, e = ball.mass_kg, ball.e_bg
    big_m = result.reduced_mass[:, None, :]
    u_ball, u_racket = -v_ball[None, :, None], v_racket[None, :, None]  # normal points off the face
    out = (m * u_ball + big_m * u_racket + big_m * e * (u_racket - u_ball)) / (m + big_m)
    np.testing.assert_allclose(result.rebound_speed, out, rtol=1e-12)
    np.testing.assert_allclose(result.cor, e, rtol=1e-15)
    expected = np.broadcast_to((e * big_m - m) / (big_m + m), result.shape)
    np.testing.assert_allclose(result.rebound_ratio, expected, rtol=1e-12)
    np.testing.assert_allclose(result.vibration_energy, 0.0)


def test_free_and_pinned_agree_at_centre_of_percussion(racket, ball, law) -> None:
    cop = [racket.centre_of_percussion_m(), 0.0]
    result = predict(racket, ball, cop, [10, 30], modal_model=None, law=law)
    free, pinned = result.support_index("free"), result.support_index("pinned")
    np.testing.assert_allclose(
        result.rebound_ratio[..., free], result.rebound_ratio[..., pinned], rtol=1e-12
    )
    np.testing.assert_allclose(
        result.contact_time[..., free], result.contact_time[..., pinned], rtol=1e-12
    )


def test_mode_energy_vanishes_at_its_node(racket, ball, model, law) -> None:
    def first_mode(x: float) -> float:
        return float(model.mode_shapes_at([x, 0.0])[0, 0])

    node = brentq(first_mode, racket.head.centre_x_m - 0.05, racket.head.tip_x_m - 0.01, xtol=1e-12)
    tip = racket.head.centre_x_m + 0.06  # within the approximate method's vibration share
    result = predict(racket, ball, [[node, 0.0], [tip, 0.0]], [20.0], modal_model=model, law=law)
    assert np.all(result.status == "ok")
    at_node, at_tip = result.mode_energy[0, 0, :, 0], result.mode_energy[1, 0, :, 0]
    assert np.all(at_node < 1e-12 * at_tip)
    # the other modes still take energy there
    assert result.mode_energy[0, 0, 0, 1:].sum() > 0


@pytest.mark.parametrize("charge", ["paper", "coupled"])
def test_single_mode_energy_closed_form_against_time_integration(
    racket, ball, linear, charge
) -> None:
    # Eq 12's energy ½ φ² |S(ω)|² for an undamped mode driven by the half-sine: integrate
    # q'' + ω² q = φ F(t) through the pulse and compare the energy left (quadrature 1e-10).
    # On a linear law the contact's own pulse is that half sine: the coupled charge takes it
    # at the impulse (1 + e_r) μ V the rebound gives, not eq 8's (1 + e_BG) μ V.
    phi, frequency = 1.0, 150.0  # (3.0 takes over 30 % of the energy: beyond the method)
    single = _single_mode(racket, phi, frequency)
    result = predict(
        racket,
        ball,
        [racket.head.centre_x_m, 0.0],
        [20.0],
        ("free",),
        modal_model=single,
        law=linear,
        vibration_charge=charge,
    )
    assert result.status[0, 0, 0] == "ok"
    e_bg = ball.e_bg_at(20.0)
    # the pulse charged: eq 11's half sine of eq 8's impulse (1 + e_BG) μ V, then (coupled)
    # scaled to the rebound's (1 + e_r) μ V, the impulse F_MEAN T_c the result gives
    impulse_ratio = 1.0 if charge == "paper" else (1 + result.cor[0, 0, 0]) / (1 + e_bg)
    assert impulse_ratio < 1.0 or charge == "paper"
    # the charged pulse's duration: eq 7's elastic half period (the coupled charge's T_c is the
    # hysteretic contact's, longer)
    m_r = float(result.reduced_mass[0, 0])
    tc = np.pi * np.sqrt(ball.mass_kg * m_r / (ball.mass_kg + m_r) / LINEAR_K)
    fmax = np.pi * float(result.impulse[0, 0, 0]) / tc / 2 / impulse_ratio
    omega = 2 * np.pi * frequency

    def rhs(t: float, state: np.ndarray) -> list[float]:
        return [state[1], -(omega**2) * state[0] + phi * fmax * np.sin(np.pi * t / tc)]

    solution = solve_ivp(rhs, (0, tc), [0.0, 0.0], rtol=1e-12, atol=1e-15, method="DOP853")
    q, q_dot = solution.y[:, -1]
    energy = 0.5 * (q_dot**2 + omega**2 * q**2)
    assert energy == pytest.approx(
        0.5 * phi**2 * half_sine_spectrum(frequency, tc, fmax) ** 2, rel=1e-8
    )
    assert result.mode_energy[0, 0, 0, 0] == pytest.approx(energy * impulse_ratio**2, rel=1e-8)


@pytest.mark.parametrize(
    ("charge", "status"), [("paper", STATUS_VIBRATION_LOSS), ("coupled", STATUS_VIBRATION_SHARE)]
)
def test_vibration_loss_beyond_e_bg_is_flagged(racket, ball, linear, charge, status) -> None:
    # A mode so compliant that its energy exceeds what e_BG leaves: no number that looks valid,
    # and the status in the charge's own words
    huge = _single_mode(racket, 60.0, 80.0)
    result = predict(
        racket, ball, [racket.head.centre_x_m, 0.0], [30.0], modal_model=huge, law=linear,
        vibration_charge=charge,
    )  # fmt: skip
    assert np.all(result.status == status)
    assert np.all(np.isnan(result.cor))
    assert np.all(np.isnan(result.rebound_speed))
    # the vibration energy exceeds what the ball brings: not reported either (issue 13)
    assert np.all(np.isnan(result.vibration_energy))
    assert np.all(np.isnan(result.contact_time))


@pytest.mark.parametrize("modal_mass", [3e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5])
@pytest.mark.parametrize("frequency", [100.0, 200.0, 600.0, 1000.0, 2000.0])
def test_the_coupled_charge_creates_no_energy(racket, ball, law, modal_mass, frequency) -> None:
    """Energy is conserved: the ball's rebound and the frame's vibration never hold more than
    the approach energy ½ μ V² (``e_r² ½ μ V² + E_vib ≤ ½ μ V²``, so e_r ≤ 1).  A mode as soft
    as the strings and several cycles over the contact holds at the turn more than the
    approach brought, beyond the rigid racket's pulse the method assumes: NaN with the
    vibration-share status.  Before: 1 kHz and 0.3 g gave e_r = 1.19 and a rebound ratio of
    0.64 marked ``ok`` (the transient model: 0.46).

    A row the coupled balances cannot close (no e_r ≥ 0: a heavy slow mode, or a light one
    holding at the turn many times the approach energy, k ≤ −1) is the same case — the frame
    holds over 30 % of the approach energy — and says so; before, it said "vibration loss
    exceeds e_BG", the paper's charge's words (100 Hz at 30 g, 1 kHz at 0.03 g)."""
    soft = _single_mode(racket, 1.0 / np.sqrt(modal_mass), frequency)
    result = predict(racket, ball, [racket.head.centre_x_m, 0.0], [10.0, 20.0, 40.0],
                     modal_model=soft, law=law)  # fmt: skip
    mu = (
        ball.mass_kg
        * result.reduced_mass[:, None, :]
        / (ball.mass_kg + result.reduced_mass[:, None, :])
    )
    approach = 0.5 * mu * result.ball_speed[None, :, None] ** 2
    ok = result.status == "ok"
    assert np.all(result.cor[ok] ** 2 * approach[ok] + result.vibration_energy[ok] <= approach[ok])
    assert set(np.unique(result.status[~ok])) <= {STATUS_VIBRATION_SHARE}
    if (frequency, modal_mass) == (1000.0, 3e-4):
        assert np.all(result.status == STATUS_VIBRATION_SHARE)
    assert np.all(np.isnan(result.cor[~ok]))


def test_deflection_beyond_the_law_is_flagged(racket, ball, law) -> None:
    result = predict(
        racket, ball, [racket.head.centre_x_m, 0.0], [20.0, 250.0], modal_model=None, law=law
    )
    assert np.all(result.status[:, 0] == "ok")
    assert np.all(result.status[:, 1] == STATUS_BEYOND_LAW)
    assert np.all(np.isnan(result.contact_time[:, 1]))


def test_contact_time_falls_with_speed(racket, ball, model, law) -> None:
    points = racket.head.grid(6)
    result = predict(racket, ball, points, np.linspace(2, 40, 39), modal_model=model, law=law)
    # flagged rows (vibration loss beyond e_BG near the rim) hold NaN: compare the others
    assert np.mean(result.status == "ok") > 0.6  # the frame over 30 % near the rim (issue 22)
    falls, rises = np.diff(result.contact_time, axis=1), np.diff(result.mean_force, axis=1)
    assert np.all(falls[np.isfinite(falls)] < 0)
    assert np.all(rises[np.isfinite(rises)] > 0)


def test_contact_time_in_the_published_range(racket, ball, model, law) -> None:
    # Paper, section 1: contact time ≈ 3–6 ms; docs/references.md: 4–5 ms for ordinary strokes
    # (ball ≈ 20 m/s on a racket at rest), falling with speed: ≈ 3.5 ms in a filmed
    # professional forehand (Kawazoe with NHK).  At 20 m/s the narrower range, at 30 m/s
    # between the forehand and the top of the ordinary strokes.
    centre = [racket.head.centre_x_m, 0.0]
    result = predict(racket, ball, centre, [20.0, 30.0], modal_model=model, law=law)
    assert np.all((result.contact_time[:, 0] > 4e-3) & (result.contact_time[:, 0] < 5e-3))
    assert np.all((result.contact_time[:, 1] > 3.5e-3) & (result.contact_time[:, 1] < 5e-3))
    # Paper, section 3.1: the grip hardly changes the contact time (reduced masses close).
    free, pinned = result.contact_time[0, 0]
    assert pinned == pytest.approx(free, rel=0.02)


def test_hand_held_rebounds_better_at_the_top(racket, ball, model, law) -> None:
    # Paper, conclusion (5): slightly higher rebound for the hand-held racket at the top of the
    # face, from its larger reduced mass there; near the centre of percussion no difference.
    top = [racket.head.centre_x_m + 0.5 * racket.head.half_length_m, 0.0]
    result = predict(racket, ball, top, [20.0], modal_model=model, law=law)
    free, pinned = result.rebound_ratio[0, 0]
    assert pinned > free


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"ball_speed": []}, "give one or more speeds"),
        ({"ball_speed": [10.0, float("nan")]}, "finite speeds"),
        ({"ball_speed": [10.0, 20.0, 30.0], "racket_speed": [1.0, 2.0]}, "one per ball speed"),
        ({"supports": ["free", "free"]}, "each support once"),
        ({"supports": "clamped"}, "support must be one of"),
        ({"modal_model": "foo"}, "modal_model must be"),
        ({"locations": np.zeros((0, 2))}, "at least one point"),
        ({"stiffness_reading": "secant"}, "stiffness_reading must be one of"),
    ],
)
def test_bad_api_input(racket, ball, law, kwargs, message) -> None:
    arguments = {
        "locations": [racket.head.centre_x_m, 0.0],
        "ball_speed": [20.0],
        "law": law,
        "modal_model": None,
        **kwargs,
    }
    with pytest.raises(rd.InputError, match=message):
        predict(racket, ball, **arguments)


def test_single_support_string(racket, ball, law) -> None:
    result = predict(
        racket, ball, [racket.head.centre_x_m, 0.0], [20.0], "pinned", modal_model=None, law=law
    )
    assert result.supports == ("pinned",)


@settings(max_examples=60, deadline=None)
@given(
    radius=st.floats(0.0, 0.98),
    angle=st.floats(0.0, 2 * np.pi),
    speed=st.floats(1.0, 45.0),
    racket_speed=st.floats(0.0, 30.0),
    e_bg=st.floats(0.5, 0.95),
)
@pytest.mark.slow
def test_cor_never_exceeds_e_bg(
    racket, model, law, radius, angle, speed, racket_speed, e_bg
) -> None:
    head = racket.head
    point = [
        head.centre_x_m + radius * head.half_length_m * np.cos(angle),
        head.centre_y_m + radius * head.half_width_m * np.sin(angle),
    ]
    ball = rd.Ball(e_bg=e_bg)
    result = predict(
        racket, ball, point, [speed], racket_speed=racket_speed, modal_model=model, law=law,
        vibration_charge="paper",
    )  # fmt: skip
    ok = result.status == "ok"
    assert np.all((result.cor[ok] >= 0) & (result.cor[ok] <= e_bg + 1e-15))
    # the coupled charge: energy the frame holds at the turn escapes the strings' loss, so e_r
    # may pass e_BG (as in the transient model), never 1
    coupled = predict(
        racket, ball, point, [speed], racket_speed=racket_speed, modal_model=model, law=law
    )
    fine = coupled.status == "ok"
    assert np.all((coupled.cor[fine] >= 0) & (coupled.cor[fine] <= 1.0))
    assert np.all(np.isnan(result.cor[~ok]))
    # the racket's recoil only takes energy away: e < e_r, and vibration never gives any back
    assert np.all(result.rebound_ratio[ok] < result.cor[ok])
    assert np.all(result.vibration_energy[ok] >= 0)


def test_string_bed_modes_are_excluded_unless_asked(racket, ball, model, law) -> None:
    # 10 m/s: from 20 m/s the membrane mode holds over 30 % of the approach energy at the
    # contact's turn, beyond the approximate method (test_the_coupled_charge_creates_no_energy)
    centre = [racket.head.centre_x_m, 0.0]
    without = predict(racket, ball, centre, [10.0], modal_model=model, law=law)
    with_bed = predict(
        racket, ball, centre, [10.0], modal_model=model, law=law, include_string_bed=True
    )
    assert "string-bed membrane" not in without.modal_model.names
    assert with_bed.vibration_energy[0, 0, 0] > without.vibration_energy[0, 0, 0]


def test_amplitude_is_eq12(racket, ball, model, law) -> None:
    # within the method's vibration share (nearer the tip its rows are NaN, and were compared
    # NaN with NaN before)
    tip = [racket.head.centre_x_m + 0.06, 0.0]
    handle = np.array([[0.0, 0.0], [0.2, 0.0]])
    result = predict(
        racket, ball, tip, [10.0, 20.0], modal_model=model, law=law, vibration_charge="paper"
    )
    amplitude = result.displacement_amplitude(handle)
    phi_i = model.frame_modes.mode_shapes_at(handle)
    phi_j = model.frame_modes.mode_shapes_at(tip)
    s = half_sine_spectrum(
        result.modal_model.frequency, result.contact_time[..., None], result.peak_force[..., None]
    )
    expected = (
        np.abs(phi_i[:, None, None, None, :] * phi_j[None, :, None, None, :])
        * s
        / (2 * np.pi * result.modal_model.frequency)
    )
    np.testing.assert_allclose(amplitude, expected, rtol=1e-12)
    # energy and amplitude agree under either charge: E = ½ ω² q² with modal amplitude
    # q = X_jj / φ_j (bending modes; the twisting mode has φ_j = 0 on the axis)
    for charge in ("paper", "coupled"):
        result = predict(
            racket, ball, tip, [10.0, 20.0], modal_model=model, law=law, vibration_charge=charge
        )
        at_tip = result.displacement_amplitude(tip)[0, 0, ..., :2]
        q = at_tip / np.abs(phi_j[0, :2])
        omega = 2 * np.pi * result.modal_model.frequency[:2]
        assert np.all(np.isfinite(q))
        np.testing.assert_allclose(
            result.mode_energy[0, ..., :2], 0.5 * omega**2 * q**2, rtol=1e-10
        )


@pytest.mark.parametrize("reading", ["period", "tangent"])
def test_power_law_runs_clean(racket, ball, reading) -> None:
    # A power law (K(0) = 0) must not raise 0/0 warnings (warnings are errors in this suite)
    # and must keep T_c falling with speed.
    law = rd.RestoringForce("power", (5.0e6, 1.5), 0.06, 0.0, "power test law")
    result = predict(
        racket,
        ball,
        [racket.head.centre_x_m, 0.0],
        [5.0, 20.0, 35.0],
        modal_model=None,
        law=law,
        stiffness_reading=reading,
    )
    assert np.all(result.status == "ok")
    assert np.all(np.diff(result.contact_time, axis=1) < 0)


def test_shown_speed_is_20_or_the_middle_of_the_sorted_speeds() -> None:
    """One rule for the CLI and the report: 20 m/s if given, else the median speed, whatever
    the order the speeds were given in."""
    from racketdyn.impact.result import shown_speed_index

    assert shown_speed_index([10.0, 20.0, 30.0]) == 1
    assert shown_speed_index([40.0, 20.0]) == 1
    assert shown_speed_index([30.0, 10.0, 40.0]) == 0
    assert shown_speed_index([15.0]) == 0


def test_beyond_the_law_every_number_is_nan(racket, ball) -> None:
    """A row past the law's range carries NaN in every impact quantity, not the law's end."""
    import logging

    logging.disable(logging.WARNING)
    try:
        # 160 m/s: past the compound law's range (≈ 130 m/s at the free racket's centre)
        result = predict(racket, ball, [(0.505, 0.0)], [160.0], "free")
    finally:
        logging.disable(logging.NOTSET)
    assert result.status[0, 0, 0] != "ok"
    for name in ("peak_deflection", "contact_time", "stiffness", "peak_force", "rebound_ratio"):
        assert np.isnan(getattr(result, name)[0, 0, 0]), name


def test_the_contact_pulse_is_the_half_sine_on_a_linear_law(linear) -> None:
    """A linear spring's elastic contact is eq 11's half sine: its spectrum per unit impulse
    is half_sine_spectrum's, and to the turn the pulse holds half the impulse at ω → 0."""
    mu, peak = 0.05, 0.02
    tc = np.pi * np.sqrt(mu / LINEAR_K)
    frequency = np.array([1e-3, 50.0, 120.0, 190.0, 361.0, 567.0])
    whole, to_turn = contact_spectra(linear, mu, peak, 2 * np.pi * frequency)
    expected = half_sine_spectrum(frequency, tc, np.pi / (2 * tc))  # impulse 1
    np.testing.assert_allclose(whole, expected, rtol=1e-10)
    # a mode of many cycles over the contact (a 100 × stiffer frame's: f T_c ≈ 54) is resolved
    # (48 nodes alone gave it 0.18 of the impulse, 2600 × the half sine's)
    cycles = np.array([40.0, 54.0, 100.0])
    high, _ = contact_spectra(linear, mu, peak, 2 * np.pi * cycles / tc)
    np.testing.assert_allclose(
        high, half_sine_spectrum(cycles / tc, tc, np.pi / (2 * tc)), rtol=1e-8
    )
    assert to_turn[0] == pytest.approx(0.5, rel=1e-9)
    # the half sine to its middle in closed form: (a − iω e^{−iωT/2}) / (a² − ω²) a T / 2
    omega, a = 2 * np.pi * frequency[1:], np.pi / tc
    half = np.abs(a - 1j * omega * np.exp(-0.5j * omega * tc)) / np.abs(a**2 - omega**2)
    np.testing.assert_allclose(to_turn[1:], half * a / 2, rtol=1e-10)


def test_the_contact_pulse_against_time_integration(law) -> None:
    """The stiffening compound law's own pulse (μ ẍ = −F(x) from first touch back to 0),
    integrated in time, against the quadrature: spectrum per unit impulse at the frame's
    frequencies, whole and to the turn."""
    mu, speed = 0.049, 30.0
    peak = float(law.deflection_at_energy(0.5 * mu * speed**2))
    frequency = np.array([120.0, 190.0, 361.0, 567.0])

    def rhs(t: float, state: np.ndarray) -> list[float]:
        return [state[1], -float(law.force(max(state[0], 0.0))) / mu]

    def apart(t: float, state: np.ndarray) -> float:
        return state[0] if t > 0 else 1.0

    apart.terminal, apart.direction = True, -1  # type: ignore[attr-defined]
    solution = solve_ivp(
        rhs, (0, 0.02), [0.0, speed], events=apart, rtol=1e-11, atol=1e-14, dense_output=True
    )
    tc = float(solution.t_events[0][0])
    t = np.linspace(0.0, tc, 20001)
    force = law.force(np.maximum(solution.sol(t)[0], 0.0))
    kernel = force * np.exp(-2j * np.pi * frequency[:, None] * t)
    impulse = trapezoid(force, t)
    turn = t <= tc / 2
    whole, to_turn = contact_spectra(law, mu, peak, 2 * np.pi * frequency)
    np.testing.assert_allclose(whole, np.abs(trapezoid(kernel, t)) / impulse, rtol=1e-5)
    np.testing.assert_allclose(
        to_turn, np.abs(trapezoid(kernel[:, turn], t[turn])) / impulse, rtol=1e-3
    )
    assert tc == pytest.approx(float(elastic_contact_time(law, mu, peak)), rel=1e-6)
