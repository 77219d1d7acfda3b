"""The contact model at real stroke speeds: relative speeds of 30–70 m/s (issue 13).

Published numbers and trends are those of docs/references.md ("Ball and strings", "Stroke
speeds", "High-speed contact"); the numbers at stroke speeds that the tests read are in
tests/data/published_stroke_speeds.csv, each with its conditions and tolerance.  No table of
contact time, peak force and COR against speed at 40–70 m/s could be read for this work
(docs/references.md says what was searched), so the high-speed checks are those published
numbers (a serve's outgoing speed, the rebound power coefficient, the effect of tension), the
published ranges and trends, and the model's own physics: conservation, monotone laws, eq 11.
"""

from __future__ import annotations

import csv
import json
import logging
from pathlib import Path

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.ball import ball_physical_force, default_ball_law, dynamic_wall_stiffness
from racketdyn.cli import main
from racketdyn.contact import string_bed_law, string_tension
from racketdyn.errors import InputError
from racketdyn.impact.approximate import predict
from racketdyn.impact.result import STATUS_BEYOND_LAW
from racketdyn.impact.transient import predict_transient, simulate_contact
from racketdyn.workflows.inputs import ball_from

SPEEDS = (30.0, 50.0, 70.0)
CENTRE = (0.505, 0.0)  # centre of the paper's racket's face, m


@pytest.fixture(autouse=True)
def _quiet() -> object:
    logging.disable(logging.WARNING)
    yield
    logging.disable(logging.NOTSET)


def test_groundstroke_has_no_row_beyond_the_law(tmp_path: Path) -> None:
    """``predict --speed 25 --racket-speed 30`` (an ordinary groundstroke, 55 m/s relative) left
    85 of 138 rows NaN "beyond the law" before the high-speed laws; now none."""
    code = main(
        ["predict", "--speed", "25", "--racket-speed", "30", "--no-figures", "--out", str(tmp_path)]
    )
    assert code == 0
    with (tmp_path / "impact.csv").open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == 138
    assert not [row for row in rows if row["status"] == STATUS_BEYOND_LAW]
    centre = [row for row in rows if abs(float(row["x_m"]) - 0.505) < 1e-3 and row["y_m"] == "0"]
    assert centre
    assert all(np.isfinite(float(row["rebound_speed_mps"])) for row in centre)


@pytest.mark.parametrize("support", ["free", "hand"])
def test_no_nan_up_to_70_mps_relative(racket: rd.Racket, ball: rd.Ball, support: str) -> None:
    """Every relative speed of play up to 70 m/s gives numbers on the paper's racket, over the
    middle of the face (the tip's vibration-loss flags are physics, not the law's end)."""
    points = [CENTRE, (0.48, 0.0), (0.53, 0.0), (0.505, 0.04), (0.505, -0.04)]
    result = predict_transient(
        racket, ball, points, [20.0, 35.0, 40.0], support, racket_speed=[30.0, 35.0, 30.0]
    )
    assert np.all(result.status == "ok"), result.status
    assert np.all(np.isfinite(result.rebound_speed))
    if support == "free":
        approx = predict(racket, ball, points, [20.0, 35.0, 40.0], support, [30.0, 35.0, 30.0])
        assert np.all(approx.status == "ok")


def _centre(racket: rd.Racket, ball: rd.Ball) -> tuple[rd.ImpactResult, rd.ImpactResult]:
    speeds = [10.0, *SPEEDS]
    return (
        predict(racket, ball, [CENTRE], speeds, "free"),
        predict_transient(racket, ball, [CENTRE], speeds, "free"),
    )


def test_contact_time_at_30_mps_is_that_of_ordinary_strokes(racket, ball) -> None:
    """Contact time ≈ 4–5 ms for ordinary strokes (Kawazoe; Cross, measured), falling with
    speed to ≈ 3.5 ms in a filmed professional forehand (Kawazoe with NHK).  Tolerance: the
    band is for hand-held rackets in play at unstated speeds (scatter ≈ ±0.5 ms) and the model
    puts the ball's mass at its centre, one side deforming (≈ 10 %): at 30 m/s 3.5–5.5 ms
    (since issue 22's ball from its bounce: 3.94 ms approximate, 4.22 ms transient)."""
    for result in _centre(racket, ball):
        contact_ms = result.contact_time[0, 1, 0] * 1e3
        assert 3.5 <= contact_ms <= 5.5, contact_ms


def test_contact_time_at_50_and_70_mps_is_that_of_a_hard_forehand(racket, ball) -> None:
    """A filmed professional topspin forehand: the ball leaves ≈ 3.5 ms after first contact
    (measured).  Its relative speed is not given; our estimate is 40–70 m/s.  Tolerance: one
    filmed stroke at ≈ 1 frame per 0.1 ms (±0.3 ms), an unknown speed within our 50–70 m/s,
    and the model's approximations (≈ 10 %): 3.0–4.6 ms."""
    for result in _centre(racket, ball):
        contact_ms = result.contact_time[0, 2:, 0] * 1e3
        assert np.all((contact_ms >= 3.0) & (contact_ms <= 4.6)), contact_ms


def test_contact_time_falls_and_peak_force_rises_with_speed(racket, ball) -> None:
    """Contact time falls as the speed rises (Kawazoe; Cross, measured) because the dynamic
    stiffness rises with speed (Haake, Carré and Goodwill 2003, measured)."""
    for result in _centre(racket, ball):
        assert np.all(np.diff(result.contact_time[0, :, 0]) < 0)
        assert np.all(np.diff(result.peak_force[0, :, 0]) > 0)
        assert np.all(np.diff(result.stiffness[0, :, 0]) > 0)


def test_peak_force_against_the_half_sine_of_the_impulse(racket, ball, law) -> None:
    """On a head-clamped bed the impulse is (1 + e_BG) m_B V (eqs 6, 8); a half-sine pulse of
    that impulse peaks at π/2 times impulse / contact time (eq 11).  A stiffening spring's
    pulse is peakier than a half-sine, the more so the faster: the simulated peak is at least
    the half-sine's and its excess grows with speed (measured here: 1.34, 1.52, 1.69 at 30, 50,
    70 m/s).  No published force table at 40–70 m/s was readable (docs/references.md), so the
    test is the pulse's physics, not a measured peak."""
    ratios = []
    for speed in SPEEDS:
        impact = simulate_contact(ball.mass_kg, ball.e_bg, law, np.inf, speed)
        impulse = (1.0 + ball.e_bg) * ball.mass_kg * speed
        assert impact.impulse_ns == pytest.approx(impulse, rel=1e-6)
        ratios.append(impact.peak_force_n * impact.contact_time_s / (0.5 * np.pi * impulse))
    assert ratios[0] >= 1.0
    assert np.all(np.diff(ratios) > 0)
    assert ratios[-1] < 2.0  # a pulse no peakier than a triangle of the same impulse


@pytest.mark.parametrize("speed", SPEEDS)
def test_rebound_on_a_clamped_head_is_e_bg(racket, ball, law, speed) -> None:
    """Ball on a head-clamped string bed: the COR is e_BG ≈ 0.83, in the measured 0.8–0.9
    (Kawazoe; Casolo), at every speed of the default ball, to the integrator's 1e-6."""
    impact = simulate_contact(ball.mass_kg, ball.e_bg, law, np.inf, speed)
    assert impact.rebound_speed_mps / speed == pytest.approx(ball.e_bg, abs=1e-6)
    assert 0.8 <= impact.rebound_speed_mps / speed <= 0.9


def test_e_bg_falling_with_speed_is_followed(racket, law) -> None:
    """Haake, Carré and Goodwill (2003) measured the COR on clamped rackets falling with speed;
    a ball given such a table rebounds from a clamped head with the table's e_BG at each
    relative speed (interpolated), to 1e-6."""
    table = ((10.0, 0.88), (40.0, 0.82), (70.0, 0.76))
    ball = rd.Ball(e_bg_table=table)
    expected = {30.0: 0.84, 50.0: 0.80, 70.0: 0.76}
    for speed, e_bg in expected.items():
        assert float(ball.e_bg_at(speed)) == pytest.approx(e_bg)
        impact = simulate_contact(ball.mass_kg, float(ball.e_bg_at(speed)), law, np.inf, speed)
        assert impact.rebound_speed_mps / speed == pytest.approx(e_bg, abs=1e-6)
    # the impact methods take e_BG at each impact's relative speed: a rigid free racket
    # rebounds as Cross's apparent COR with that e_BG (eq of docs/references.md, "Rebound")
    racket = rd.default_racket()
    for method in (predict, predict_transient):
        result = method(racket, ball, [CENTRE], [20.0, 50.0], "free", 10.0, modal_model=None)
        mass_ratio = ball.mass_kg / result.reduced_mass[0, 0]
        for j, speed in enumerate((30.0, 60.0)):
            e_bg = float(ball.e_bg_at(speed))
            apparent = (e_bg - mass_ratio) / (1.0 + mass_ratio)
            assert result.rebound_ratio[0, j, 0] == pytest.approx(apparent, abs=2e-4)


def test_energy_is_conserved_at_e_1_at_70_mps(law) -> None:
    """e_BG = 1 on a rigid free racket of 0.25 kg: the ball's energy out plus the racket's is
    the energy in, and the COR is 1, at 70 m/s (elastic limit, to the integrator's 1e-6)."""
    impact = simulate_contact(0.0577, 1.0, law, 0.25, 70.0)
    assert impact.cor == pytest.approx(1.0, abs=1e-6)
    energy_in = 0.5 * 0.0577 * 70.0**2
    energy_out = 0.5 * 0.0577 * impact.rebound_speed_mps**2 + impact.racket_energy_j
    assert energy_out == pytest.approx(energy_in, rel=1e-6)


def test_laws_are_monotone_over_their_ranges(racket, ball, law) -> None:
    """Ball, string bed and compound laws: force and stiffness rise over the whole range (no
    softening a polynomial fit could bring), and the compound law covers 70 m/s on a rigid
    clamped head (½ m V² stored within its range)."""
    strings = string_bed_law(racket, ball)
    for each in (ball.restoring_force, strings, law):
        x = np.linspace(0.0, each.max_deflection_m, 2001)[1:]
        assert np.all(each.stiffness(x) > 0)
        # stiffening beyond 5 mm (below it the ball fit's slope wanders by < 1 % of k₁)
        stiffening = np.diff(each.stiffness(x[x > 5e-3]))
        assert np.all(stiffening > 0), each.source
    assert law.energy(law.max_deflection_m) > 0.5 * ball.mass_kg * 70.0**2
    bare = ball.restoring_force  # ball alone on a rigid plate: 70 m/s within range too
    assert bare.energy(bare.max_deflection_m) > 0.5 * ball.mass_kg * 70.0**2


def test_ball_law_follows_its_physics_and_the_old_law_at_small_flattening() -> None:
    """The fit stays within 3 % of the adiabatic-gas + ITF wall force it stands for; below
    10 mm (≈ 10 m/s on strings) it is the earlier cubic k₁X + (3π/2)γpX³/R within 3 %, so the
    paper's low-speed numbers hardly move; at one radius the exact geometry is ≈ 14 % softer."""
    law = default_ball_law()  # the bounce's dynamic wall since issue 22
    x = np.linspace(1e-4, law.max_deflection_m, 400)
    wall = dynamic_wall_stiffness()
    np.testing.assert_allclose(
        law.force(x), ball_physical_force(x, wall_stiffness_n_per_m=wall), rtol=0.03
    )
    radius, absolute = 0.0335, 83.0e3 + 101.325e3
    cubic = 80.1 / 3.25e-3 * x + 1.5 * np.pi * 1.4 * absolute / radius * x**3
    small = x < 0.010
    np.testing.assert_allclose(ball_physical_force(x[small]), cubic[small], rtol=0.03)
    at_radius = float(ball_physical_force(radius) / (80.1 / 3.25e-3 * radius + 1365.4))
    assert 0.8 < at_radius < 0.9


def test_string_tension_is_the_law_s_own_elongation(racket, ball) -> None:
    """Kawazoe's string law per string is 2 S(X) X / L with S(X) = S0 + A E X²/(2L²): the law
    summed over the engaged strings equals the tensions of :func:`string_tension`."""
    x = np.linspace(0.0, 0.08, 9)
    mains, crosses = string_tension(racket, x)
    spacing_mains, spacing_crosses = racket.strings.spacing_m(racket.head)
    total = ball.diameter_m / spacing_mains * 2.0 * mains * x / racket.head.half_length_m
    total += ball.diameter_m / spacing_crosses * 2.0 * crosses * x / racket.head.half_width_m
    np.testing.assert_allclose(string_bed_law(racket, ball).force(x), total, rtol=1e-12)
    # at 70 m/s on the clamped centre the bed deflects ≈ 53 mm: crosses at ≈ 0.87 kN
    assert float(crosses[5]) < 1.1e3  # 50 mm


def test_tangent_reading_works_at_70_mps(racket, ball) -> None:
    """The paper's tangent reading of eq (10) needs F/sqrt(K) rising: true of the new laws."""
    result = predict(racket, ball, [CENTRE], list(SPEEDS), "free", stiffness_reading="tangent")
    assert np.all(result.status == "ok")
    assert np.all(np.diff(result.contact_time[0, :, 0]) < 0)


def test_e_bg_table_file_and_run_record(tmp_path: Path) -> None:
    """``--e-bg-table`` reads speed_mps, e_bg and run.json records the law."""
    table = tmp_path / "ebg.csv"
    table.write_text("speed_mps,e_bg\n10,0.88\n70,0.76\n", encoding="utf-8")
    out = tmp_path / "run"
    code = main(
        ["predict", "--speed", "20", "--grid", "3", "--e-bg-table", str(table), "--no-figures",
         "--out", str(out)]
    )  # fmt: skip
    assert code == 0
    text = (out / "run.json").read_text(encoding="utf-8")
    assert "e_bg_law" in text
    assert "0.76" in json.dumps(json.loads(text))
    assert main(["predict", "--e-bg", "0.8", "--e-bg-table", str(table), "--out", str(out)]) == 2


@pytest.mark.parametrize(
    ("table", "message"),
    [
        (((20.0, 0.8), (10.0, 0.85)), "strictly rising"),
        (((10.0, 0.8), (20.0, 1.2)), "at most 1"),
        (((10.0, 0.8, 1.0),), "pairs"),
    ],
)
def test_bad_e_bg_tables_are_refused(table, message) -> None:
    with pytest.raises(InputError, match=message):
        rd.Ball(e_bg_table=table)


def test_e_bg_table_in_percent_is_a_unit_slip(tmp_path: Path) -> None:
    path = tmp_path / "ebg.csv"
    path.write_text("speed_mps,e_bg\n10,88\n70,76\n", encoding="utf-8")
    with pytest.raises(InputError, match="fraction"):
        ball_from(e_bg_table=path)


# --- published numbers at stroke speeds (tests/data/published_stroke_speeds.csv) ----------------
PUBLISHED = Path(__file__).parent / "data" / "published_stroke_speeds.csv"


def _published(row_id: str) -> dict[str, str]:
    """One row of the published-numbers table (docs/references.md, "Stroke speeds")."""
    with PUBLISHED.open(newline="", encoding="utf-8") as handle:
        rows = {row["id"]: row for row in csv.DictReader(handle)}
    return rows[row_id]


@pytest.mark.parametrize("support", ["pinned", "free"])
def test_a_serve_leaves_at_about_1_4_times_the_racket_speed(racket, ball, support) -> None:
    """A serve sends the ball out at ≈ 1.4 times the racket's speed at the impact point
    (Kawazoe), i.e. a rebound power coefficient e_A ≈ 0.4 at the centre (Kawazoe; 0.45 typical,
    USRSA).  Tolerance 1.3–1.55: both sources say "about", for rackets of 290–370 g designed to
    the same power, and 0.45 + 0.1 covers the typical value with a racket's spread; the serve's
    racket speeds are 35–45 m/s (docs/references.md, "Stroke speeds")."""
    row = _published("serve_ratio")
    low, high = float(row["low"]), float(row["high"])
    centre = [(racket.head.centre_x_m, racket.head.centre_y_m)]
    for racket_speed in (35.0, 40.0, 45.0):
        result = predict(racket, ball, centre, [0.0], support, racket_speed=[racket_speed])
        ratio = result.rebound_speed[0, 0, 0] / racket_speed
        assert low <= ratio <= high, (racket_speed, ratio)


def test_rebound_power_at_the_centre_is_the_published_one_at_every_speed(racket, ball) -> None:
    """e_A at the centre of a hand-held racket at rest: ≈ 0.4 (Kawazoe), 0.45 typical (USRSA);
    30–55 % covers both with a racket's spread.  Kawazoe's hand-held rackets keep it as the
    impact speed rises at the centre; here it stays within 0.02 from 10 to 50 m/s."""
    row = _published("acor_centre")
    low, high = float(row["low"]), float(row["high"])
    centre = [(racket.head.centre_x_m, racket.head.centre_y_m)]
    result = predict(racket, ball, centre, [10.0, 20.0, 30.0, 40.0, 50.0], "pinned")
    e = result.rebound_ratio[0, :, 0]
    assert np.all((e >= low) & (e <= high)), e
    assert np.ptp(e) < 0.02, e


@pytest.mark.parametrize("speed", [20.0, 40.0])
def test_the_throat_rebounds_better_than_the_centre(racket, ball, speed) -> None:
    """Typical ACORs: 0.50 at the throat against 0.45 at the centre (USRSA); Kawazoe measured the
    rebound power rising towards the throat on a suspended racket.  The order is the test (the
    sources' throat is not a stated point); the point is 40 mm inside the bed's throat end."""
    head = racket.head
    throat = (head.centre_x_m - head.half_length_m + 0.04, head.centre_y_m)
    centre = (head.centre_x_m, head.centre_y_m)
    transient = predict_transient(racket, ball, [throat, centre], [speed], "pinned")
    assert np.all(transient.status == "ok")
    assert transient.rebound_ratio[0, 0, 0] > transient.rebound_ratio[1, 0, 0]
    # the approximate method, where it gives a number (since issue 22 not where the frame takes
    # over 30 % of the approach energy: the throat at 40 m/s)
    result = predict(racket, ball, [throat, centre], [speed], "pinned")
    assert result.status[1, 0, 0] == "ok"
    if result.status[0, 0, 0] == "ok":
        assert result.rebound_ratio[0, 0, 0] > result.rebound_ratio[1, 0, 0]


def test_string_tension_hardly_changes_a_groundstroke(racket, ball) -> None:
    """Bower and Cross measured 180 N strings sending groundstrokes (≈ 110 km/h out) ≈ 3 km/h
    faster than 280 N; Kawazoe measured no tension effect on the ball–string COR at 20–30 m/s.
    racketdyn's e_BG does not depend on tension (Kawazoe), so the model's difference comes only
    from the contact time's effect on the vibration loss: it must stay within 0–5 km/h of
    either source (the measured 3 km/h and its scatter)."""
    from dataclasses import replace

    row = _published("tension_out_speed")
    high = float(row["high"])
    centre = [(racket.head.centre_x_m, racket.head.centre_y_m)]
    out = []
    for tension in (180.0, 280.0):
        strung = replace(racket, strings=replace(racket.strings, tension_n=tension))
        result = predict(strung, ball, centre, [15.0], "pinned", racket_speed=[20.0])
        out.append(result.rebound_speed[0, 0, 0] * 3.6)
    assert 100.0 < out[0] < 140.0  # the measured strokes' ≈ 110 km/h
    assert abs(out[0] - out[1]) <= high


def test_tension_changes_contact_time_at_low_speed_only(racket, ball) -> None:
    """Brody's contact time against impact speed for several tensions (as read by Kawazoe): the
    looser bed holds the ball longer at 10 m/s, the curves nearly meet at 30–35 m/s.  Here on a
    head-clamped bed (180 vs 290 N): longer at 10 m/s, a difference at 35 m/s under 0.4 ms
    (≈ 8 % of the contact time, what "nearly meet" can be read as on a printed figure) and
    under 60 % of the difference at 10 m/s."""
    from dataclasses import replace

    limit_ms = float(_published("tension_contact_time")["high"])
    times = {}
    for tension in (180.0, 290.0):
        strung = replace(racket, strings=replace(racket.strings, tension_n=tension))
        law = rd.compound_law(strung, ball)
        times[tension] = [
            simulate_contact(ball.mass_kg, ball.e_bg, law, np.inf, speed).contact_time_s * 1e3
            for speed in (10.0, 35.0)
        ]
    slow = times[180.0][0] - times[290.0][0]
    fast = times[180.0][1] - times[290.0][1]
    assert slow > 0.0
    assert 0.0 <= fast < limit_ms
    assert fast < 0.6 * slow
