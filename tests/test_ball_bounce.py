"""The ball in a bounce and e_BG from ball + strings, held to measurements (issue 22).

Sources and numbers: docs/references.md, "The ball in a bounce".  The built-in ball's law has
one parameter from the ball's own bounce (6 mm of flattening at 7.06 m/s on a rigid surface,
Cross) and its own COR (ITF rebound); the string bed's energy return has one from a ball on
clamped strings (Cross's 1 m drop, e_BG 0.84).  Everything else below is a prediction held to a
*different* measurement.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from racketdyn.ball import (
    BOUNCE_COMPRESSION_M,
    BOUNCE_SPEED_MPS,
    ITF_FORWARD_DEFORMATION_M,
    ITF_FORWARD_LOAD_N,
    STATIC_WALL_STIFFNESS_N_PER_M,
    Ball,
    RestoringForce,
    default_ball_law,
)
from racketdyn.contact import (
    CROSS_DROP_E_BG,
    CROSS_DROP_SPEED_MPS,
    ball_string_cor,
    clamped_bounce,
    compound_law,
    string_bed_cor,
    with_ball_string_cor,
)
from racketdyn.errors import InputError
from racketdyn.impact import predict
from racketdyn.impact.approximate import vibration_cor_squared
from racketdyn.impact.bounce import BALL_COLUMNS, SURFACES, ball_bounces
from racketdyn.impact.result import (
    STATUS_FRAME_CONTACT,
    STATUS_VIBRATION_LOSS,
    STATUS_VIBRATION_SHARE,
)
from racketdyn.impact.transient import predict_transient, simulate_contact
from racketdyn.io import default_racket
from racketdyn.racket import TIP_INSET_M, landmark_points

DROP_100_IN_MPS = math.sqrt(2 * 9.81 * 2.54)  # 7.06 m/s
DROP_1_M_MPS = math.sqrt(2 * 9.81 * 1.0)  # 4.43 m/s


@pytest.fixture(scope="module")
def racket():  # type: ignore[no-untyped-def]
    return default_racket()


def test_the_drop_speeds_are_the_papers_heights() -> None:
    assert pytest.approx(BOUNCE_SPEED_MPS, abs=0.01) == DROP_100_IN_MPS
    assert pytest.approx(CROSS_DROP_SPEED_MPS, abs=0.01) == DROP_1_M_MPS


def test_rigid_surface_bounce_at_100_in() -> None:
    """Dropped from 100 in onto a rigid surface (simulated with the transient model's
    hysteretic contact on an immovable racket): ≈ 6 ± 1 mm of flattening (Cross; the tolerance
    is his "about 6 mm") and a COR in the ITF rebound band 0.729–0.761.  Both were put into
    the law; this checks the law's fit, its inversion and the hysteresis carry them through."""
    ball = Ball()
    bounce = simulate_contact(
        ball.mass_kg, ball.rigid_cor, ball.restoring_force, math.inf, DROP_100_IN_MPS
    )
    assert bounce.peak_deflection_m == pytest.approx(BOUNCE_COMPRESSION_M, abs=1e-3)
    assert 0.729 <= bounce.rebound_speed_mps / DROP_100_IN_MPS <= 0.761


def test_a_bounce_is_stiffer_than_the_slow_plate_test() -> None:
    """The ITF plate test (80.1 N, 5.6–7.4 mm between two plates) is slow: the same ball in a
    bounce is ≈ 3× stiffer (Haake, Carré and Goodwill 2003: dynamic above static).  The
    static law still meets the ITF test it came from: a separate check of a different test."""
    bounce, static = (
        default_ball_law(),
        default_ball_law(wall_stiffness_n_per_m=STATIC_WALL_STIFFNESS_N_PER_M),
    )
    two_sided = 2 * float(static.deflection(ITF_FORWARD_LOAD_N))
    assert 5.6e-3 <= two_sided <= 7.4e-3
    assert two_sided == pytest.approx(ITF_FORWARD_DEFORMATION_M, rel=0.02)
    assert 2.5 < bounce.stiffness(1e-4) / static.stiffness(1e-4) < 4.0


CROSS_DROP_XFAIL = pytest.mark.xfail(
    strict=True,
    reason="issue 22, second session: on the played bed (30 % of the pull tension lost, Cross "
    "and Bower) the ball flattens 1.78 mm (2.01 at the pull tension) and stays 5.98 ms (5.26): "
    "a linear ball that flattens 6 mm on a rigid surface at 7.06 m/s cannot also flatten 3 mm "
    "on a bed this soft; Cross's drop figures are informal ('about') and his racket's tension "
    "is not stated (docs/develop.md, issue 22)",
)


@CROSS_DROP_XFAIL
def test_head_clamped_strings_at_1_m(racket) -> None:  # type: ignore[no-untyped-def]
    """Dropped 1 m onto head-clamped strings the ball flattens ≈ 3 mm (Cross; ± 1 mm, his
    "about 3 mm"): a prediction of the ball and bed laws, not an input.  The built-in ball
    gives ≈ 2.0 mm — at the soft end of the band; the bed takes the rest (≈ 5 mm)."""
    bounce = clamped_bounce(racket, Ball(), DROP_1_M_MPS)
    assert 2.0e-3 <= float(bounce["ball_compression"]) <= 4.0e-3
    assert float(bounce["bed_deflection"]) > float(bounce["ball_compression"])


def test_the_string_bed_loses_less_than_the_ball_and_more_than_strings_alone() -> None:
    """e_S, from Cross's 1 m drop on clamped strings (contact.string_bed_cor), lies between
    the ball's own COR on a rigid surface (0.745, ITF: the ball is the lossier part, Cross:
    "the strings give back almost all") and the 0.97 of strings struck by a rigid impactor."""
    assert Ball().rigid_cor < string_bed_cor() < 0.97


def test_the_string_bed_cor_bounces_crosss_drop_as_measured(racket) -> None:  # type: ignore[no-untyped-def]
    """e_S is defined by Cross's drop: with it the ball on the clamped bed returns e_BG = 0.84
    at 1 m (:func:`ball_string_cor`'s energy balance, solved for e_S in closed form), to
    rounding."""
    e_bg = ball_string_cor(racket, Ball(), CROSS_DROP_SPEED_MPS, string_bed_cor())
    assert float(e_bg) == pytest.approx(CROSS_DROP_E_BG, abs=1e-12)


def test_e_bg_follows_kawazoe_and_haake(racket) -> None:  # type: ignore[no-untyped-def]
    """e_BG from ball + strings over 10–40 m/s: within Kawazoe's measured 0.8–0.9 ("almost
    independent of speed and tension"), falling slowly with speed (Haake, Carré and Goodwill
    2003), and lower at a higher tension (Vallatta, Casolo and Caffi) by little (Kawazoe: no
    effect within the scatter at 25–65 lb, so less than 0.03)."""
    speeds = np.array([10.0, 20.0, 30.0, 40.0])
    cor = ball_string_cor(racket, Ball(), speeds)
    assert np.all((cor >= 0.80) & (cor <= 0.90))
    assert np.all(np.diff(cor) < 0)
    loose = replace(racket, strings=replace(racket.strings, tension_n=25 * 4.448))
    tight = replace(racket, strings=replace(racket.strings, tension_n=65 * 4.448))
    low, high = ball_string_cor(loose, Ball(), 20.0), ball_string_cor(tight, Ball(), 20.0)
    assert 0.0 < float(low - high) < 0.03


def test_a_given_e_bg_is_kept_and_an_unresolved_one_is_refused(racket) -> None:  # type: ignore[no-untyped-def]
    given = Ball(e_bg=0.8)
    assert with_ball_string_cor(racket, given) is given
    with pytest.raises(InputError, match="with_ball_string_cor"):
        Ball().e_bg_at(20.0)
    resolved = with_ball_string_cor(racket, Ball())
    assert resolved.e_bg_record()["kind"].startswith("ball + strings")
    assert float(resolved.e_bg_at(CROSS_DROP_SPEED_MPS)) == pytest.approx(0.84, abs=0.002)


def test_transient_on_clamped_strings_returns_the_derived_e_bg(racket) -> None:  # type: ignore[no-untyped-def]
    ball = with_ball_string_cor(racket, Ball())
    for speed in (5.0, 20.0):
        e = float(ball.e_bg_at(speed))
        run = simulate_contact(ball.mass_kg, e, compound_law(racket, ball), math.inf, speed)
        assert run.rebound_speed_mps / speed == pytest.approx(e, rel=1e-5)


def test_contact_time_at_the_centre_of_a_free_racket(racket) -> None:  # type: ignore[no-untyped-def]
    """4.0–5.0 ms at 20 m/s (Kawazoe and Cross, measured: 4–5 ms in ordinary strokes) and
    falling with speed, in both models (the old soft ball gave 5.1–5.6 ms)."""
    centre = [landmark_points(racket)["centre"]]
    speeds = [10.0, 20.0, 30.0, 40.0]
    for model in (predict, predict_transient):
        result = model(racket, Ball(), centre, speeds, ("free",))
        times = result.contact_time[0, :, 0]
        assert 4.0e-3 <= times[1] <= 5.0e-3, model.__name__
        assert np.all(np.diff(times) < 0), model.__name__


def test_the_coupled_charge_limits() -> None:
    """No vibration: e_r = e_BG under either charge.  The coupled charge balances momentum and
    energy at once: its e_r, with the energies scaled to the impulse (1 + e_r) μ V, meets the
    energy balance e_r² = e_BG² − (E_vib − (1 − e_BG²) E_turn) / E_rel exactly; a charge no
    e_r ≥ 0 balances is negative."""
    e = np.array([0.83, 0.83, 0.83, 1.0])
    vib, turn, rel = np.array([0.0, 0.2, 0.2, 0.2]), np.array([0.0, 0.0, 0.1, 0.1]), 1.0
    paper = vibration_cor_squared(e, vib, turn, rel, "paper")
    coupled = vibration_cor_squared(e, vib, turn, rel, "coupled")
    assert paper[0] == pytest.approx(0.83**2)
    assert coupled[0] == pytest.approx(0.83**2)
    scale = ((1 + np.sqrt(coupled)) / (1 + e)) ** 2
    balance = e**2 - scale * (vib - (1 - e**2) * turn) / rel
    assert coupled == pytest.approx(balance, rel=1e-12)
    # less charged than eq 8's impulse says: the pulse of a slower rebound is weaker
    assert np.all(coupled[1:] > e[1:] ** 2 - (vib - (1 - e**2) * turn)[1:] / rel)
    assert vibration_cor_squared(0.5, 5.0, 0.0, 1.0) < 0.0


def test_on_a_rigid_racket_the_forces_are_the_elastic_contacts_and_the_papers_are_eq_11(
    racket,
) -> None:  # type: ignore[no-untyped-def]
    """A rigid racket (no modes): the coupled charge's contact is the transient model's — X_p
    where the spring holds ½ μ V², F_MAX = F_GB(X_p), F_MEAN T_c = (1 + e_BG) μ V (eq 8,
    e_r = e_BG) and T_c that of loading along F_GB and unloading along its hysteresis, to the
    integrator's tolerance.  The paper's charge keeps eq 7's half period and eq 11's half sine,
    F_MAX = π F_MEAN / 2, of the same impulse."""
    points, speeds = [landmark_points(racket)["centre"]], [10.0, 30.0]
    rigid = predict(racket, Ball(), points, speeds, ("free",), modal_model=None)
    paper = predict(
        racket, Ball(), points, speeds, ("free",), modal_model=None, vibration_charge="paper"
    )
    law = compound_law(racket, Ball())
    m_b, m_r = Ball().mass_kg, rigid.reduced_mass[0, 0]
    mu = m_b * m_r / (m_b + m_r)
    held = 0.5 * mu * np.asarray(speeds) ** 2
    deflection = rigid.peak_deflection[0, :, 0]
    assert law.energy(deflection) == pytest.approx(held, rel=1e-9)
    assert rigid.peak_force[0, :, 0] == pytest.approx(law.force(deflection), rel=1e-12)
    impulse = (1.0 + rigid.cor[0, :, 0]) * mu * np.asarray(speeds)
    assert rigid.cor[0, :, 0] == pytest.approx(ball_string_cor(racket, Ball(), speeds))
    for result in (rigid, paper):
        assert result.mean_force[0, :, 0] * result.contact_time[0, :, 0] == pytest.approx(impulse)
    assert paper.peak_force == pytest.approx(np.pi * paper.mean_force / 2.0)
    # the stiffening spring's pulse is peaked: its peak above the half sine's of one impulse
    assert np.all(rigid.peak_force > 1.1 * paper.peak_force)
    transient = predict_transient(racket, Ball(), points, speeds, ("free",), modal_model=None)
    for name in ("contact_time", "peak_force", "peak_deflection", "impulse"):
        ours, theirs = getattr(rigid, name), getattr(transient, name)
        np.testing.assert_allclose(ours, theirs, rtol=1e-6, err_msg=name)
    assert np.all(paper.contact_time < 0.97 * rigid.contact_time)


@pytest.mark.parametrize(
    "first_bending_hz",
    [120.0, 130.0, 190.0],
)
def test_the_approximate_method_is_within_0_015_of_the_transient_where_it_gives_a_number(
    racket, first_bending_hz
) -> None:  # type: ignore[no-untyped-def]
    """Issue 22's protocol: the built-in racket (120 Hz), a flexible (130 Hz) and a stiff
    (190 Hz) frame; along the long axis and 40 mm off it; 10–40 m/s; free and pinned.  Every
    row the approximate method gives a number for is within 0.015 of the transient model's
    rebound ratio (the coupled charge; rows where the frame takes over 30 % of the approach
    energy are NaN with their status); the paper's charge is further off on the same rows, and
    the stiff frame leaves most rows with a number."""
    frame = replace(racket, first_bending_hz=first_bending_hz)
    head = frame.head
    # from the throat to the tip landmark: nearer the hoop a ball pressed into the strings
    # meets the frame (a frame shot, which neither model simulates; was 15 mm before frame
    # shots were marked)
    xs = np.linspace(head.throat_x_m + TIP_INSET_M, head.tip_x_m - TIP_INSET_M, 9)
    speeds = [10.0, 20.0, 30.0, 40.0]
    for y in (0.0, 0.04):
        points = np.column_stack([xs, np.full_like(xs, head.centre_y_m + y)])
        points = points[head.contains(points)]
        supports = ("free", "pinned")
        transient = predict_transient(frame, Ball(), points, speeds, supports)
        coupled = predict(frame, Ball(), points, speeds, supports)
        paper = predict(frame, Ball(), points, speeds, supports, vibration_charge="paper")
        given = (coupled.status == "ok") & (transient.status == "ok")  # a second contact
        assert set(np.unique(coupled.status)) <= {
            "ok",
            STATUS_VIBRATION_SHARE,
            STATUS_VIBRATION_LOSS,
            STATUS_FRAME_CONTACT,  # 40 mm off the axis, the ends of the line
        }
        error = np.abs(coupled.rebound_ratio - transient.rebound_ratio)[given]
        assert np.all(error <= 0.015)
        _forces_meet_the_transients(coupled, transient, given)
        both = given & (paper.status == "ok")  # the paper's charge leaves rows beyond 30 %
        paper_error = np.abs(paper.rebound_ratio - transient.rebound_ratio)[both]
        error_on_both = np.abs(coupled.rebound_ratio - transient.rebound_ratio)[both]
        assert np.sqrt(np.mean(paper_error**2)) > np.sqrt(np.mean(error_on_both**2))
        if first_bending_hz == 190.0:
            assert np.mean(given) > 0.75
        else:
            assert np.mean(given) > 0.6


def _forces_meet_the_transients(coupled, transient, given) -> None:  # type: ignore[no-untyped-def]
    """The coupled charge's contact against the transient model's, row by row (measured over the
    protocol's 370 rows; docs/validation.md, "The contact: time and forces"): the peak force and
    deflection where the spring holds the approach energy less the frame's at the turn (0.05–2.3
    % and 0.05–1.8 % high; eq 11's half sine of eq 8's impulse was 3–22 % low in force, the
    rigid racket's X_p up to 8.5 % deep); the impulse F_MEAN T_c = (1 + e_r) μ V, the ball's
    change of momentum (within 0.4 %; eq 8's (1 + e_BG) μ V was up to 11 % high); T_c from
    loading along F_GB and unloading along its hysteresis (−8.8 … +0.4 %, the shortest where the
    2-node mode is near the contact's frequency; eq 7's elastic half period was 4–14 % short),
    and so F_MEAN (−0.2 … +9.9 %; was 4–27 % high)."""
    pairs = {
        "peak_force": (coupled.peak_force, transient.peak_force, -0.005, 0.025),
        "peak_deflection": (coupled.peak_deflection, transient.peak_deflection, 0.0, 0.02),
        "impulse": (
            coupled.mean_force * coupled.contact_time,
            transient.mean_force * transient.contact_time,
            -0.005,
            0.005,
        ),
        "contact_time": (coupled.contact_time, transient.contact_time, -0.095, 0.01),
        "mean_force": (coupled.mean_force, transient.mean_force, -0.01, 0.105),
    }
    for name, (ours, theirs, low, high) in pairs.items():
        ratio = (ours / theirs - 1.0)[given]
        assert np.all((ratio >= low) & (ratio <= high)), (name, ratio.min(), ratio.max())


@CROSS_DROP_XFAIL
def test_clamped_contact_lasts_about_5_ms_at_1_m(racket) -> None:  # type: ignore[no-untyped-def]
    """Cross: the ball dropped 1 m on clamped strings stays ≈ 5 ms (± 0.5 ms, "about")."""
    bounces = ball_bounces(Ball(), [DROP_1_M_MPS], ("strings",), racket)
    assert 4.5e-3 <= float(bounces.contact_time[0, 0]) <= 5.5e-3
    assert float(bounces.cor[0, 0]) == pytest.approx(CROSS_DROP_E_BG, abs=0.002)


def test_bounces_table_and_loops(racket) -> None:  # type: ignore[no-untyped-def]
    bounces = ball_bounces(Ball(), [5.0, 20.0], SURFACES, racket, samples=50)
    rows = bounces.rows()
    assert [r["surface"] for r in rows] == ["rigid", "rigid", "strings", "strings"]
    assert set(rows[0]) == set(BALL_COLUMNS)
    # the loop's largest force is the peak force; the contact ends unloaded
    assert np.nanmax(bounces.loop_force, axis=-1) == pytest.approx(bounces.peak_force, rel=0.02)
    assert np.all(np.abs(bounces.loop_force[..., -1]) < 1e-6 * bounces.peak_force)
    data = bounces.to_xarray()
    assert data["cor"].sel(surface="rigid").values == pytest.approx([0.745, 0.745], abs=1e-6)
    with pytest.raises(InputError, match="racket"):
        ball_bounces(Ball(), [5.0], ("strings",))
    with pytest.raises(InputError, match="surfaces"):
        ball_bounces(Ball(), [5.0], ("grass",), racket)
    with pytest.raises(InputError, match="above 0"):
        ball_bounces(Ball(), [0.0], ("rigid",))


def test_ball_command_writes_its_files(tmp_path: Path) -> None:
    from racketdyn.cli import main

    out = tmp_path / "ball"
    assert main(["ball", "--speed", "4.43,20", "--tension", "220", "--out", str(out)]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == ["ball.csv", "ball.nc", "ball_hysteresis.png", "figures.nc", "run.json"]
    with (out / "ball.csv").open() as handle:
        header = handle.readline().strip().split(",")
    assert tuple(header) == BALL_COLUMNS
    record = json.loads((out / "run.json").read_text())
    assert record["string_tension_n"] == 220.0


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--surface", "grass"], "--surface"),
        (["--speed", "0"], "--speed"),
        (["--speed", "90"], "--speed"),
        (["--tension", "50"], "--tension"),
    ],
)
def test_ball_command_bad_input_is_one_line(tmp_path: Path, capsys, argv, words) -> None:  # type: ignore[no-untyped-def]
    from racketdyn.cli import main

    assert main(["ball", *argv, "--out", str(tmp_path / "b")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert words in err


def test_ball_command_says_the_rigid_cor_is_one_number(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A new user read 0.745 at 7 and at 40 m/s in ``ball``'s table as a prediction; measured
    balls lose more at speed (docs/references.md): the command says the number is one input,
    an upper bound at speeds above the ITF test's."""
    from racketdyn.cli import main

    out = tmp_path / "ball"
    assert main(["ball", "--speed", "7.06,30", "--surface", "rigid", "--out", str(out)]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "one number, 0.745" in printed
    assert "upper bound" in printed


@pytest.mark.parametrize("kind", ["polynomial", "power"])
def test_the_laws_unloading_exponent_is_the_transient_kernels(racket, kind) -> None:  # type: ignore[no-untyped-def]
    """``RestoringForce.unloading_exponent`` on arrays and the transient model's compiled
    solver give one p, and the curve gives back cor² of the energy stored at the peak."""
    from racketdyn.impact.transient import unloading_exponent

    law = compound_law(racket, Ball())
    if kind == "power":
        law = RestoringForce("power", (4.0e6, 1.5), 0.03, 0.0, "test")
    peaks = np.array([[1e-3, 5e-3, 1.2e-2]] * 3)
    cors = np.array([[0.6], [0.83], [1.0]])
    ours = law.unloading_exponent(peaks, cors)
    for (i, j), p in np.ndenumerate(ours):
        assert p == pytest.approx(unloading_exponent(law, cors[i, 0], peaks[i, j]), abs=1e-10)
        given = law.unloading_energy(peaks[i, j], peaks[i, j], p)
        assert given == pytest.approx(cors[i, 0] ** 2 * law.energy(peaks[i, j]), rel=1e-10)
