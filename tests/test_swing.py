"""The swinging racket: swing energy, racket speed per point, outgoing speed, sweet spots."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from scipy.optimize import brentq

import racketdyn as rd
from racketdyn.impact import predict
from racketdyn.impact.swing import Swing, predict_swing, sweet_spots

SPEED = 20.0  # m/s, the incoming ball speed the report quotes


def _racket_inertia_about(racket: rd.Racket, d: float) -> float:
    """I_G + M (x_G + d)², from the racket's published numbers (no point masses)."""
    return racket.inertia_cg_kgm2 + racket.mass_kg * (racket.balance_m + d) ** 2


@pytest.mark.parametrize(
    "swing",
    [
        Swing(),
        Swing(torque_nm=30.0, swing_angle_rad=2.0),
        Swing(arm_mass_kg=0.0, axis_to_butt_m=0.0),
    ],
)
def test_swing_energy_balance(racket: rd.Racket, swing: Swing) -> None:
    # ½ I Ω² = T Δθ with I = m_arm k² + I_G + M (x_G + d)², computed here from the raw
    # numbers; only round-off differs (1e-12).
    inertia = swing.arm_mass_kg * swing.arm_gyration_m**2 + _racket_inertia_about(
        racket, swing.axis_to_butt_m
    )
    omega = swing.angular_speed(racket)
    assert 0.5 * inertia * omega**2 == pytest.approx(
        swing.torque_nm * swing.swing_angle_rad, rel=1e-12
    )


def test_lead_at_the_tip_slows_the_swing(racket: rd.Racket) -> None:
    # 10 g of lead at the tip adds m (x + d)² to the inertia about the shoulder, so with the
    # same work T Δθ, Ω falls by sqrt(I / (I + m (x + d)²)) exactly (1e-12: round-off).
    swing = Swing()
    d, tip, lead = swing.axis_to_butt_m, racket.length_m, 0.010
    leaded = racket.with_point_masses(rd.PointMass(lead, tip, 0.0, "tip"))
    inertia = swing.arm_inertia_kgm2 + _racket_inertia_about(racket, d)
    ratio = swing.angular_speed(leaded) / swing.angular_speed(racket)
    assert ratio < 1.0
    assert ratio == pytest.approx(math.sqrt(inertia / (inertia + lead * (tip + d) ** 2)), rel=1e-12)
    # a heavier swingweight swings slower
    assert leaded.swingweight_kgcm2 > racket.swingweight_kgcm2


def test_impact_point_speed_is_omega_times_distance(racket: rd.Racket) -> None:
    swing = Swing()
    points = np.array([[0.40, 0.0], [0.40, 0.08], [0.60, -0.05], [racket.length_m, 0.0]])
    speed = swing.impact_point_speed(racket, points)
    omega = swing.angular_speed(racket)
    # the swing axis is parallel to y: the speed depends on x only (exact)
    np.testing.assert_allclose(speed, omega * (points[:, 0] + swing.axis_to_butt_m), rtol=1e-15)
    assert speed[0] == speed[1]
    plain = Swing(angular_speed_radps=20.0, axis_to_butt_m=0.5)
    np.testing.assert_allclose(
        plain.impact_point_speed(racket, points), 20.0 * (points[:, 0] + 0.5)
    )


def _cross_rebound(
    racket: rd.Racket,
    ball: rd.Ball,
    xy: np.ndarray,
    v_ball: float,
    v_racket: np.ndarray,
    support: str,
) -> np.ndarray:
    """Cross's rigid-racket rebound v_out = e_A v + (1 + e_A) V, e_A = (e M_r − m)/(M_r + m).

    The reduced mass from the paper's numbers: free, 1/M_r = 1/M + (x − x_G)²/I_G + y²/I_roll;
    pinned at the grip, 1/M_r = (x − x_g)²/I_grip + y²/I_roll (eq 4 with the roll term).
    """
    x, y = xy[:, 0], xy[:, 1]
    i_g, i_roll, m, x_g = (
        racket.inertia_cg_kgm2,
        racket.roll_inertia_kgm2,
        racket.mass_kg,
        racket.balance_m,
    )
    if support == "free":
        compliance = 1.0 / m + (x - x_g) ** 2 / i_g + y**2 / i_roll
    else:
        i_grip = i_g + m * (x_g - racket.grip_m) ** 2
        compliance = (x - racket.grip_m) ** 2 / i_grip + y**2 / i_roll
    m_r = 1.0 / compliance
    e_a = (ball.e_bg * m_r - ball.mass_kg) / (m_r + ball.mass_kg)
    return e_a * v_ball + (1.0 + e_a) * v_racket


@pytest.mark.usefixtures("strings_only")  # a closed form over the grid
def test_rigid_racket_gives_cross_rebound(racket: rd.Racket, ball: rd.Ball) -> None:
    # A rigid racket loses no energy to vibration, so e_r = e_BG and the outgoing speed is the
    # closed form at every point with V = Ω (x + d).  Same algebra, different route: 1e-12.
    swing = Swing()
    points = racket.head.grid(7)
    result = predict_swing(
        racket, ball, points, [10.0, SPEED], swing, ("free", "pinned"), modal_model=None
    )
    v_racket = swing.angular_speed(racket) * (points[:, 0] + swing.axis_to_butt_m)
    np.testing.assert_allclose(result.racket_speed, v_racket, rtol=1e-15)
    for p, support in enumerate(result.supports):
        for s, v_ball in enumerate(result.ball_speed):
            expected = _cross_rebound(racket, ball, points, v_ball, v_racket, support)
            np.testing.assert_allclose(result.rebound_speed[:, s, p], expected, rtol=1e-12)
    assert np.all(result.status == "ok")


def test_transient_rigid_racket_gives_cross_rebound(racket: rd.Racket, ball: rd.Ball) -> None:
    # The transient contact returns e_BG of the approach speed for any two masses, so a rigid
    # racket gives Cross's result too.  Tolerance 2e-5: the compiled engine's default (128 steps
    # per contact, extrapolated) is within ≈ 1e-6 here (4e-6 at the previous 400 steps, order
    # 2); the reference engine is good to its rtol.
    swing = Swing()
    points = np.array([[0.45, 0.0], [0.55, 0.03]])
    result = predict_swing(
        racket, ball, points, [SPEED], swing, "pinned", model="transient", modal_model=None
    )
    expected = _cross_rebound(racket, ball, points, SPEED, result.racket_speed, "pinned")
    np.testing.assert_allclose(result.rebound_speed[:, 0, 0], expected, rtol=2e-5)
    assert result.inputs["method"] == "transient"


def test_points_merge_back_in_order(racket: rd.Racket, ball: rd.Ball, tmp_path) -> None:
    # Points with the same x share one call; every point must equal a call of its own with
    # its own racket speed, in the order and with the labels given.
    swing = Swing()
    points = np.array([[0.55, 0.02], [0.45, 0.0], [0.55, -0.04], [0.60, 0.0]])
    labels = ["a", "b", "c", "d"]
    result = predict_swing(
        racket, ball, points, [10.0, SPEED], swing, ("pinned", "free"), labels=labels
    )
    assert result.labels == tuple(labels)
    for i, point in enumerate(points):
        v = float(swing.impact_point_speed(racket, point)[0])
        alone = predict(racket, ball, [point], [10.0, SPEED], ("pinned", "free"), racket_speed=v)
        np.testing.assert_allclose(result.rebound_speed[i], alone.rebound_speed[0], rtol=1e-12)
        np.testing.assert_allclose(result.mode_energy[i], alone.mode_energy[0], rtol=1e-12)
        np.testing.assert_allclose(result.reduced_mass[i], alone.reduced_mass[0], rtol=1e-15)
    # the table carries each point's own racket speed
    path = tmp_path / "swing.csv"
    result.write_csv(path)
    with path.open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == np.prod(result.shape)
    written = {row["point"]: float(row["racket_speed_mps"]) for row in rows}
    for label, speed in zip(labels, result.racket_speed, strict=True):
        assert written[label] == pytest.approx(speed, rel=1e-8)
    # inputs record the swing for reproducibility
    recorded = result.inputs["swing"]
    assert recorded["torque_nm"] == swing.torque_nm
    assert recorded["swing_angle_rad"] == swing.swing_angle_rad
    assert recorded["angular_speed_radps"] == result.angular_speed_radps


@pytest.mark.usefixtures("strings_only")  # a closed form over the grid
def test_map_is_symmetric_in_y(racket: rd.Racket, ball: rd.Ball) -> None:
    # A racket symmetric about its long axis, the swing axis across it: mirror points hit
    # alike.  The interpolated mode shapes are mirror-symmetric to round-off (1e-9).
    points = racket.head.grid(9)
    result = predict_swing(racket, ball, points, [SPEED, 30.0], Swing(), ("pinned", "free"))
    index = {(round(x, 9), round(y, 9)): i for i, (x, y) in enumerate(points)}
    mirror = np.array([index[(round(x, 9), round(-y, 9) + 0.0)] for x, y in points])
    np.testing.assert_array_equal(result.status, result.status[mirror])
    np.testing.assert_allclose(result.rebound_speed, result.rebound_speed[mirror], rtol=1e-9)
    # since issue 22 the approximate method leaves the throat and the tip (frame over 30 %)
    assert np.sum(result.status == "ok") > 0.6 * result.status.size


def test_centre_of_percussion_closed_form(racket: rd.Racket, ball: rd.Ball) -> None:
    # A rigid body turning about an axis at x_a: x_cop = x_a + I_a / (M (x_G − x_a)).  And what
    # makes it the centre of percussion: an impulse J there leaves the axis at rest,
    # J/M − (J (x_cop − x_G)/I_G)(x_G − x_a) = 0.  Round-off only: 1e-12.
    swing = Swing()
    spots = sweet_spots(racket, ball, swing, SPEED, modal_model=None, n_axis=21)
    m, x_g, i_g = racket.mass_kg, racket.balance_m, racket.inertia_cg_kgm2
    for key, x_a in (
        ("centre_of_percussion_swing", -swing.axis_to_butt_m),
        ("centre_of_percussion_grip", racket.grip_m),
    ):
        i_a = i_g + m * (x_g - x_a) ** 2
        x_cop = spots[key].x_m
        assert x_cop == pytest.approx(x_a + i_a / (m * (x_g - x_a)), rel=1e-12)
        axis_speed = 1.0 / m - (x_cop - x_g) / i_g * (x_g - x_a)  # per unit impulse
        assert abs(axis_speed) < 1e-12 / m
    # the grip inertia the paper quotes: 33.5 g·m² (docs/references.md), to its 3 digits
    assert i_g + m * (x_g - racket.grip_m) ** 2 == pytest.approx(33.5e-3, abs=0.05e-3)
    # no modal model: no node
    assert "first_mode_node" not in spots


def test_first_mode_node_matches_the_beam(racket: rd.Racket, ball: rd.Ball, model) -> None:
    spots = sweet_spots(racket, ball, Swing(), SPEED, modal_model=model, n_axis=21)
    node = spots["first_mode_node"]
    assert node.on_face
    # the beam model's own samples on the axis, 10 mm apart: their zero crossing, linearly
    # interpolated, is the node to within 0.5 mm (curvature over one 10 mm element)
    head = racket.head
    on_axis = (
        (model.locations[:, 1] == 0.0)
        & (model.locations[:, 0] >= head.throat_x_m)
        & (model.locations[:, 0] <= head.tip_x_m)
    )
    x = model.locations[on_axis, 0]
    order = np.argsort(x)
    x, shape = x[order], model.mode_shapes[on_axis, 0][order]
    i = np.flatnonzero(np.sign(shape[:-1]) * np.sign(shape[1:]) < 0)
    assert i.size == 1
    crossing = x[i] - shape[i] * (x[i + 1] - x[i]) / (shape[i + 1] - shape[i])
    assert node.x_m == pytest.approx(float(crossing[0]), abs=0.5e-3)


def test_first_mode_node_of_a_uniform_racket(ball: rd.Ball) -> None:
    # A uniform free–free beam: the 2-node mode's nodes are the zeros of
    # cosh βx + cos βx − σ (sinh βx + sin βx), βL = 4.730041 (0.2242 L from each end).  The
    # interpolated shape is within 1e-3 of its peak of the analytic one (test_modal), which
    # moves the node by ≈ 0.1 mm: 0.5 mm allowed.
    length, mass = 0.68, 0.36
    head = rd.HeadEllipse(0.50, 0.15, 0.11)
    uniform = rd.Racket("uniform", mass, length, length / 2, mass * length**2 / 12, 1.5e-3, head)
    spots = sweet_spots(uniform, ball, Swing(), SPEED, n_axis=11)
    beta_l = 4.730041
    sigma = (np.cosh(beta_l) - np.cos(beta_l)) / (np.sinh(beta_l) - np.sin(beta_l))

    def shape(u: float) -> float:
        z = beta_l * u
        return float(np.cosh(z) + np.cos(z) - sigma * (np.sinh(z) + np.sin(z)))

    exact = brentq(shape, 0.6, 0.9) * length
    assert spots["first_mode_node"].x_m == pytest.approx(exact, abs=0.5e-3)


@pytest.mark.parametrize("support", ["free", "pinned"])
@pytest.mark.slow
def test_max_outgoing_speed_moves_towards_the_tip(
    racket: rd.Racket, ball: rd.Ball, model, support: str
) -> None:
    # Racket speed Ω (x + d) rises towards the tip, so the best point for outgoing speed lies
    # beyond the best point for rebound ratio (further by much more than the 8 mm search step
    # of 41 samples), and moves on as Ω grows; with Ω = 0 they coincide (refined to 1e-6 m).
    spots = [
        sweet_spots(
            racket, ball, Swing(angular_speed_radps=w), SPEED, support, modal_model=model, n_axis=41
        )
        for w in (0.0, 10.0, Swing().angular_speed(racket))
    ]
    ratio = [s["max_rebound_ratio"].x_m for s in spots]
    speed = [s["max_rebound_speed"].x_m for s in spots]
    assert ratio[0] == ratio[1] == ratio[2]  # the racket at rest: the swing plays no part
    assert speed[0] == pytest.approx(ratio[0], abs=1e-5)
    assert speed[1] > ratio[1] + 0.016  # two search steps (19 mm since issue 22's ball)
    assert speed[2] > speed[1]
    # and the maximum is one: no sampled point on the axis does better
    best = spots[2]["max_rebound_speed"]
    x = np.linspace(racket.head.throat_x_m + 0.005, racket.head.tip_x_m - 0.005, 31)
    along = predict_swing(
        racket, ball, np.column_stack([x, np.zeros_like(x)]), [SPEED], Swing(), support,
        modal_model=model,
    )  # fmt: skip
    assert best.value is not None
    assert np.nanmax(along.rebound_speed) <= best.value * (1 + 1e-9)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"torque_nm": -56.9},
        {"torque_nm": float("nan")},
        {"torque_nm": 0.0},
        {"swing_angle_rad": 0.0},
        {"swing_angle_rad": -1.0},
        {"swing_angle_rad": float("nan")},
        {"swing_angle_rad": 7.0},
        {"axis_to_butt_m": -0.1},
        {"arm_mass_kg": -1.0},
        {"arm_gyration_m": float("inf")},
        {"angular_speed_radps": -1.0},
        {"angular_speed_radps": float("nan")},
    ],
)
def test_bad_swing_is_refused(kwargs: dict[str, float]) -> None:
    with pytest.raises(rd.InputError, match="swing"):
        Swing(**kwargs)


def test_bad_impacts_are_refused(racket: rd.Racket, ball: rd.Ball) -> None:
    swing = Swing()
    with pytest.raises(rd.InputError, match="outside the string bed"):
        predict_swing(racket, ball, [[0.50, 0.0], [0.69, 0.0]], [SPEED], swing)
    with pytest.raises(rd.InputError, match="finite"):
        predict_swing(racket, ball, [[np.nan, 0.0]], [SPEED], swing)
    with pytest.raises(rd.InputError, match="model"):
        predict_swing(racket, ball, [[0.50, 0.0]], [SPEED], swing, model="exact")  # type: ignore[arg-type]
    with pytest.raises(rd.InputError, match="swing must be a Swing"):
        predict_swing(racket, ball, [[0.50, 0.0]], [SPEED], 20.0)  # type: ignore[arg-type]
    with pytest.raises(rd.InputError, match="ball speed"):
        predict_swing(racket, ball, [[0.50, 0.0]], [-5.0], swing)
    with pytest.raises(rd.InputError, match="off the racket"):
        swing.impact_point_speed(racket, [[0.75, 0.0]])
    with pytest.raises(rd.InputError, match="n_axis"):
        sweet_spots(racket, ball, swing, SPEED, n_axis=2)


def test_plots_mark_the_sweet_spots(racket: rd.Racket, ball: rd.Ball, model) -> None:
    import matplotlib.pyplot as plt

    from racketdyn.plotting import plot_swing_along_axis, plot_swing_map

    swing = Swing()
    spots = sweet_spots(racket, ball, swing, SPEED, modal_model=model, n_axis=21)
    face = predict_swing(racket, ball, racket.head.grid(9), [SPEED], swing, modal_model=model)
    ax = plot_swing_map(face, racket, spots)
    labels = ax.get_legend_handles_labels()[1]
    assert all(any(s.name in label for label in labels) for s in spots.values())
    x = np.linspace(racket.head.throat_x_m + 0.01, racket.head.tip_x_m - 0.01, 15)
    line = predict_swing(
        racket, ball, np.column_stack([x, np.zeros_like(x)]), [10.0, SPEED], swing,
        modal_model=model,
    )  # fmt: skip
    ax2 = plot_swing_along_axis([line], spots)
    curves = [ln for ln in ax2.get_lines() if ln.get_label() != "_flagged rows"]
    assert len(curves) == 2 + len(spots)
    plt.close("all")
