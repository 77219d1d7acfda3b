"""``racketdyn swing``, ``twist`` and ``oblique``: the files they write, their columns checked
against independent recomputations and the laws behind them, bad input, and the report
sections they feed.

Small grids, few offsets and angles keep these fast (≈ 1 s a command with its figures).
"""

from __future__ import annotations

import csv
import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

import racketdyn as rd
from costly import costly
from racketdyn.cli import main
from racketdyn.impact.result import CSV_COLUMNS
from racketdyn.impact.swing import (
    DEFAULT_ARM_GYRATION_M,
    DEFAULT_ARM_MASS_KG,
    DEFAULT_AXIS_TO_BUTT_M,
    Swing,
    predict_swing,
)
from racketdyn.report import SECTIONS, write_report
from racketdyn.workflows.oblique import OBLIQUE_COLUMNS
from racketdyn.workflows.swing import SWEET_SPOT_COLUMNS
from racketdyn.workflows.twist import TWIST_COLUMNS

# The paper's racket (docs/references.md, section 2): 360 g, CG 308 mm, I_G 13.1 g·m², grip
# axis 70 mm from the butt; the built-in racket holds exactly these numbers.
MASS_KG, CG_M, INERTIA_CG_KGM2, GRIP_M = 0.360, 0.308, 0.0131, 0.070
TORQUE_NM = 56.9  # Kawazoe, ACMD 2002 (docs/references.md)
# CSV cells carry 9 significant digits: a value read back is within 5e-9 of the one written,
# so 1e-8 relative for a value read once, 1e-7 for relations between several columns.
CSV_REL = 1e-8
RELATION_REL = 1e-7
SWING_GRID = 5
OFFSETS = "-0.06,-0.03,0,0.03,0.06"
ANGLES = "0,20,40"


def _read(path: Path) -> list[dict[str, str]]:
    with path.open(newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def _header(path: Path) -> list[str]:
    with path.open(newline="", encoding="utf-8") as handle:
        return next(csv.reader(handle))


@pytest.fixture(scope="module")
@costly
def swing_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The default swing (56.9 N·m over 90°, pinned, approximate model) at 20 m/s, with figures."""
    out = tmp_path_factory.mktemp("run") / "swing"
    assert main(["swing", "--grid", str(SWING_GRID), "--out", str(out)]) == 0
    return out


@pytest.fixture(scope="module")
@costly
def twist_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("run") / "twist"
    argv = ["twist", "--support", "free,hand", f"--offsets={OFFSETS}", "--out", str(out)]
    assert main(argv) == 0
    return out


@pytest.fixture(scope="module")
@costly
def oblique_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("run") / "oblique"
    assert main(["oblique", "--angles", ANGLES, "--out", str(out)]) == 0
    return out


# --- swing ---------------------------------------------------------------------------------------
@pytest.mark.slow
def test_swing_writes_its_files(swing_dir: Path, racket: rd.Racket) -> None:
    header = _header(swing_dir / "swing.csv")
    assert header[: len(CSV_COLUMNS)] == list(CSV_COLUMNS)
    assert header[len(CSV_COLUMNS) :] == [
        "energy_2_node_bending_j",
        "energy_3_node_bending_j",
        "energy_2_node_twisting_j",
    ]
    rows = _read(swing_dir / "swing.csv")
    assert len(rows) == len(racket.head.grid(SWING_GRID))  # one speed, one support
    assert {r["support"] for r in rows} == {"pinned"}
    assert _header(swing_dir / "sweet_spots.csv") == list(SWEET_SPOT_COLUMNS)
    record = json.loads((swing_dir / "run.json").read_text(encoding="utf-8"))
    written = [
        "swing.csv",
        "sweet_spots.csv",
        "figures.nc",
        "swing_map.png",
        "swing_along_axis.png",
    ]
    assert record["outputs"] == [*written, "run.json"]
    for name in written:
        assert (swing_dir / name).stat().st_size > 0, name
    assert record["swing"]["torque_nm"] == TORQUE_NM
    assert record["impact_model"] == "approximate"
    assert record["racketdyn_version"] == rd.__version__


def test_swing_angular_speed_is_the_work_of_the_torque(swing_dir: Path) -> None:
    """½ I Ω² = T Δθ with I = arm + racket about the shoulder (parallel axes, paper's racket),
    and every point's racket speed is Ω (x + d)."""
    d = DEFAULT_AXIS_TO_BUTT_M
    inertia = (
        DEFAULT_ARM_MASS_KG * DEFAULT_ARM_GYRATION_M**2
        + INERTIA_CG_KGM2
        + MASS_KG * (CG_M + d) ** 2
    )
    omega = math.sqrt(2.0 * TORQUE_NM * (math.pi / 2.0) / inertia)
    record = json.loads((swing_dir / "run.json").read_text(encoding="utf-8"))
    assert record["swing"]["angular_speed_radps"] == pytest.approx(omega, rel=1e-12)
    assert record["swing"]["axis_to_butt_m"] == pytest.approx(d, rel=1e-12)
    for row in _read(swing_dir / "swing.csv"):
        expected = omega * (float(row["x_m"]) + d)
        assert float(row["racket_speed_mps"]) == pytest.approx(expected, rel=RELATION_REL)


def test_swing_csv_equals_a_direct_predict_swing(
    swing_dir: Path, racket: rd.Racket, ball: rd.Ball, model: rd.ModalModel
) -> None:
    """The CSV's outgoing speed at two points is that of an independent predict_swing call, and
    obeys Cross's v_out = e v + (1 + e) V with the CSV's own e and V."""
    rows = [r for r in _read(swing_dir / "swing.csv") if r["status"] == "ok"]
    x = np.array([float(r["x_m"]) for r in rows])
    y = np.array([float(r["y_m"]) for r in rows])
    centre = int(np.argmin(np.hypot(x - racket.head.centre_x_m, y)))
    tip = int(np.argmax(x))
    for i in (centre, tip):
        direct = predict_swing(  # the command's ball: e_BG from ball + strings (issue 22)
            racket, rd.Ball(), [(x[i], y[i])], [20.0], Swing(), "pinned", modal_model=model
        )
        assert float(rows[i]["rebound_speed_mps"]) == pytest.approx(
            direct.rebound_speed[0, 0, 0], rel=CSV_REL
        )
    for row in rows:
        e, v_racket = float(row["rebound_ratio"]), float(row["racket_speed_mps"])
        expected = e * float(row["ball_speed_mps"]) + (1.0 + e) * v_racket
        assert float(row["rebound_speed_mps"]) == pytest.approx(expected, rel=RELATION_REL)


def test_sweet_spots_csv_names_the_four_sweet_spots(swing_dir: Path) -> None:
    spots = {r["key"]: r for r in _read(swing_dir / "sweet_spots.csv")}
    assert set(spots) == {
        "centre_of_percussion_swing",
        "centre_of_percussion_grip",
        "first_mode_node",
        "max_rebound_ratio",
        "max_rebound_speed",
    }
    # centre of percussion about the grip: x_grip + I_grip / (M (x_G − x_grip)), the paper's
    # numbers (I_grip = 33.5 g·m², docs/references.md)
    arm = CG_M - GRIP_M
    cop = GRIP_M + (INERTIA_CG_KGM2 + MASS_KG * arm**2) / (MASS_KG * arm)
    assert float(spots["centre_of_percussion_grip"]["x_m"]) == pytest.approx(cop, rel=CSV_REL)
    # the largest outgoing speed: no impact of the run on the long axis beats it, and the
    # outgoing speed written at the spot is the value maximised
    best = spots["max_rebound_speed"]
    value = float(best["value"])
    assert float(best["rebound_speed_mps"]) == pytest.approx(value, rel=RELATION_REL)
    on_axis = [  # with a number (the throat and tip are beyond the approximate method)
        r for r in _read(swing_dir / "swing.csv") if float(r["y_m"]) == 0.0 and r["status"] == "ok"
    ]
    assert on_axis
    assert all(float(r["rebound_speed_mps"]) <= value * (1 + CSV_REL) for r in on_axis)
    # the swing adds (1 + e) Ω (x + d), growing towards the tip: the best point for the swing
    # lies beyond the best point of the racket at rest
    assert float(best["x_m"]) > float(spots["max_rebound_ratio"]["x_m"])
    # racket speed at each spot: Ω (x + d)
    record = json.loads((swing_dir / "run.json").read_text(encoding="utf-8"))
    omega, d = record["swing"]["angular_speed_radps"], record["swing"]["axis_to_butt_m"]
    for row in spots.values():
        expected = omega * (float(row["x_m"]) + d)
        assert float(row["racket_speed_mps"]) == pytest.approx(expected, rel=RELATION_REL)


@pytest.mark.slow
def test_swing_prints_the_sweet_spots(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["swing", "--grid", "3", "--angular-speed", "10", "--no-figures"]
    assert main([*argv, "--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    for name in ("centre of percussion", "first-mode node", "maximum outgoing"):
        assert name in printed
    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert record["swing"]["angular_speed_radps"] == 10.0
    assert record["outputs"] == ["swing.csv", "sweet_spots.csv", "figures.nc", "run.json"]


# --- twist ---------------------------------------------------------------------------------------
@pytest.mark.slow
def test_twist_writes_its_files_with_mirror_symmetry(twist_dir: Path) -> None:
    assert _header(twist_dir / "twist.csv") == list(TWIST_COLUMNS)
    rows = _read(twist_dir / "twist.csv")
    offsets = [float(v) for v in OFFSETS.split(",")]
    assert [(r["support"], float(r["y_m"])) for r in rows] == [
        (s, y) for s in ("free", "hand") for y in offsets
    ]
    assert all(r["status"] == "ok" for r in rows)
    assert (twist_dir / "twist.png").stat().st_size > 0
    record = json.loads((twist_dir / "run.json").read_text(encoding="utf-8"))
    assert record["outputs"] == ["twist.csv", "figures.nc", "twist.png", "run.json"]
    assert record["supports"] == ["free", "hand"]
    # the built-in racket is symmetric about its long axis: roll odd, outgoing speed even in y
    # (reference engine, rtol 1e-10; test_twist.py holds the library to 1e-9)
    for support in ("free", "hand"):
        mine = [r for r in rows if r["support"] == support]
        roll = np.array([float(r["roll_angle_rad"]) for r in mine])
        speed = np.array([float(r["rebound_speed_mps"]) for r in mine])
        np.testing.assert_allclose(roll, -roll[::-1], atol=1e-7 * np.max(np.abs(roll)))
        np.testing.assert_allclose(speed, speed[::-1], rtol=RELATION_REL)
        assert np.all(np.diff(roll) > 0)  # a hit at +y turns the +y side away from the ball


def test_twist_rigid_roll_rate_is_the_angular_impulse(tmp_path: Path, racket: rd.Racket) -> None:
    """Rigid free racket: I_roll ω = J y, J = m_B (v_in + v_out) the normal impulse, from the
    CSV's own columns (the roll inertia is the racket's twistweight)."""
    argv = ["twist", "--rigid", f"--offsets={OFFSETS}", "--no-figures", "--out", str(tmp_path)]
    assert main(argv) == 0
    i_roll = racket.derived_properties()["twistweight_kgcm2"] * 1e-4
    for row in _read(tmp_path / "twist.csv"):
        impulse = rd.Ball().mass_kg * (
            float(row["ball_speed_mps"]) + float(row["rebound_speed_mps"])
        )
        expected = impulse * float(row["y_m"]) / i_roll
        assert float(row["roll_rate_radps"]) == pytest.approx(expected, rel=RELATION_REL, abs=1e-12)
        assert float(row["flexible_twist_rad"]) == 0.0


# --- oblique -------------------------------------------------------------------------------------
def test_oblique_writes_its_files_and_obeys_its_kinematics(
    oblique_dir: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert _header(oblique_dir / "oblique.csv") == list(OBLIQUE_COLUMNS)
    rows = _read(oblique_dir / "oblique.csv")
    assert [float(r["incoming_angle_deg"]) for r in rows] == [0.0, 20.0, 40.0]
    assert (oblique_dir / "oblique.png").stat().st_size > 0
    record = json.loads((oblique_dir / "run.json").read_text(encoding="utf-8"))
    assert record["outputs"] == ["oblique.csv", "figures.nc", "oblique.png", "run.json"]
    assert "tangential stiffness" in record["caveat"]
    contact = record["tangential_contact"]
    ball = rd.Ball()
    radius = 0.5 * ball.diameter_m
    inertia = contact["inertia_factor"] * ball.mass_kg * radius**2
    # a normal impact has nothing along the face: no spin, no tangential speed
    assert float(rows[0]["outgoing_angle_deg"]) == 0.0
    assert float(rows[0]["outgoing_spin_radps"]) == 0.0
    for row in rows:
        speed, theta = float(row["ball_speed_mps"]), math.radians(float(row["incoming_angle_deg"]))
        impulse = float(row["tangential_impulse_ns"])
        v_n, v_t = float(row["normal_speed_mps"]), float(row["tangential_speed_mps"])
        # the impulse along the face changes the ball's momentum and spin: m Δv_t = J_t,
        # I Δω = −R J_t (oblique.py, module docstring)
        assert v_t == pytest.approx(
            speed * math.sin(theta) + impulse / ball.mass_kg, rel=RELATION_REL, abs=1e-9
        )
        assert float(row["outgoing_spin_radps"]) == pytest.approx(
            -radius * impulse / inertia, rel=RELATION_REL, abs=1e-9
        )
        assert float(row["outgoing_angle_deg"]) == pytest.approx(
            math.degrees(math.atan2(v_t, v_n)), rel=RELATION_REL, abs=1e-9
        )
        assert row["gripped"] in ("True", "False")
        assert row["status"] == "ok"


def test_oblique_prints_the_spin_caveat(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["oblique", "--angles", "30", "--tangential-stiffness", "inf", "--no-figures"]
    assert main([*argv, "--out", str(tmp_path)]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "spin depends strongly on the tangential stiffness" in printed
    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert math.isinf(record["tangential_contact"]["stiffness_n_per_m"])


# --- bad input: one line on stderr, exit status 2, nothing written ----------------------------
BAD_INPUT: dict[str, tuple[list[str], tuple[str, ...]]] = {
    "negative-torque": (["swing", "--torque", "-5"], ("--torque",)),
    "swing-angle-beyond-a-turn": (["swing", "--swing-angle-deg", "400"], ("--swing-angle-deg",)),
    "torque-and-angular-speed": (
        ["swing", "--torque", "50", "--angular-speed", "10"],
        ("--angular-speed", "--torque"),
    ),
    "hand-with-the-approximate-model": (
        ["swing", "--support", "hand", "--model", "approx"],
        ("--support hand", "--model transient"),
    ),
    "oblique-angle-of-90-degrees": (["oblique", "--angles", "0,90"], ("angle", "90")),
    "oblique-point-off-the-strings": (
        ["oblique", "--point", "0.2,0"],
        ("impact point", "outside the string bed"),
    ),
    "oblique-point-not-a-pair": (["oblique", "--point", "0.5"], ("--point",)),
    "negative-friction": (["oblique", "--friction", "-0.1"], ("friction",)),
    "twist-offset-off-the-strings": (
        ["twist", "--offsets", "0,0.3"],
        ("impact point", "outside the string bed"),
    ),
    "twist-unknown-support": (["twist", "--support", "free,clamped"], ("--support", "clamped")),
}


@pytest.mark.parametrize("case", list(BAD_INPUT))
def test_bad_input_is_one_line_and_exit_2(
    case: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv, words = BAD_INPUT[case]
    out = tmp_path / "out"

    code = main([*argv, "--no-figures", "--out", str(out)])

    err = capsys.readouterr().err
    assert "Traceback" not in err
    lines = err.splitlines()
    assert len(lines) == 1, f"expected one line on stderr, got {lines!r}"
    assert lines[0].startswith("racketdyn: error:"), lines[0]
    for word in words:
        assert word in lines[0], f"{word!r} not named in {lines[0]!r}"
    assert code == 2
    assert not out.exists()


# --- the report ----------------------------------------------------------------------------------
def _section(page: str, key: str) -> str:
    start = page.index(f'<section id="{key}">')
    return page[start : page.index("</section>", start)]


def test_report_sections_follow_the_folders(
    swing_dir: Path, twist_dir: Path, oblique_dir: Path, tmp_path: Path, racket: rd.Racket
) -> None:
    run = tmp_path / "run"
    shutil.copytree(swing_dir, run / "swing")
    page = write_report(run, racket).read_text(encoding="utf-8")
    swing = _section(page, "swing")
    assert SECTIONS["swing"].title in swing
    for name in ("swing/swing_map.png", "swing/swing_along_axis.png"):
        assert name in swing
    for spot in ("centre of percussion (grip)", "first-mode node", "maximum outgoing speed"):
        assert spot in swing
    assert "section 4.2" in swing
    assert "ACMD 2002" in swing
    not_run = page[page.index('<section id="not-run">') :]
    assert SECTIONS["oblique"].title in not_run
    assert '<section id="oblique">' not in page

    shutil.copytree(twist_dir, run / "twist")
    page = write_report(run, racket).read_text(encoding="utf-8")
    section = _section(page, "oblique")
    assert "twist/twist.png" in section
    assert "Oblique impacts not run" in section  # the other half is named, with its command
    assert SECTIONS["oblique"].title not in page[page.index('<section id="not-run">') :]

    shutil.copytree(oblique_dir, run / "oblique")
    page = write_report(run, racket).read_text(encoding="utf-8")
    section = _section(page, "oblique")
    assert "oblique/oblique.png" in section
    assert "Caveat" in section
    assert "not run" not in section

    shutil.rmtree(run / "swing")
    page = write_report(run, racket).read_text(encoding="utf-8")
    assert '<section id="swing">' not in page
    assert SECTIONS["swing"].title in page[page.index('<section id="not-run">') :]


def test_oblique_says_the_racket_speed_it_used(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """New-user trial (issue 13): ``oblique --speed 40 --racket-speed 10`` printed "ball 40
    m/s" above its table and nothing of the racket's 10 m/s the numbers include."""
    argv = ["oblique", "--speed", "40", "--racket-speed", "10", "--angles", "0,30"]
    assert main([*argv, "--no-figures", "--out", str(tmp_path / "o")]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "ball 40 m/s, racket 10 m/s towards it" in out
