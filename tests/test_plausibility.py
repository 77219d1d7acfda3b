"""Plausibility (issue 13, "any unit a person might slip into"): a value off by a unit factor is
refused in one line naming the likely slip; an unusual object goes on when the user says so."""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path

import pytest

import racketdyn as rd
from racketdyn.cli import main
from racketdyn.errors import InputError
from racketdyn.io import read_load_deflection
from racketdyn.io.racket_file import _PLAUSIBLE, _SCHEMA
from racketdyn.plausibility import RANGES, check, check_speeds
from racketdyn.workflows.inputs import ball_from, hand_for

DEFAULT_TOML = Path(rd.__file__).parent / "data" / "kawazoe_2002.toml"
DOCS = Path(__file__).resolve().parents[1] / "docs"
# A ball pressed by 2 mm … 20 mm, written in millimetres under the deflection_m header
MM_CSV = "deflection_m,force_n\n0,0\n2,60\n5,170\n10,420\n15,760\n20,1200\n"
# The same in metres, but the forces in kN
KN_CSV = "deflection_m,force_n\n0,0\n0.002,0.06\n0.005,0.17\n0.01,0.42\n0.015,0.76\n0.02,1.2\n"
GOOD_CSV = "deflection_m,force_n\n0,0\n0.002,60\n0.005,170\n0.01,420\n0.015,760\n0.02,1200\n"
JUNIOR = """
name = "junior 25 in"
[racket]
mass_kg = 0.210
length_m = 0.635
balance_m = 0.300
inertia_cg_kgm2 = 0.0090
[head]
centre_x_m = 0.465
half_length_m = 0.150
area_cm2 = 600.0
"""


def _toml(tmp_path: Path, old: str, new: str) -> Path:
    """The built-in racket file with one edit (``old`` empty: ``new`` appended)."""
    text = DEFAULT_TOML.read_text(encoding="utf-8")
    if old:
        assert old in text, old
        text = text.replace(old, new, 1)
    else:
        text += new
    path = tmp_path / "racket.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _file(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _predict(tmp_path: Path, *extra: str) -> list[str]:
    out = str(tmp_path / "out")
    return ["predict", "--grid", "2", "--speed", "20", *extra, "--no-figures", "--out", out]


# slip -> (arguments given tmp_path, words the one line must hold)
def _step(*argv: str, figures: bool = True) -> Callable[[Path], list[str]]:
    """A command line into ``tmp/out`` (without figures where the command draws any)."""
    return lambda tmp: [*argv, *(["--no-figures"] if figures else []), "--out", str(tmp / "out")]


SLIPS = {
    "ball-law-csv-in-mm": (
        lambda tmp: _predict(tmp, "--ball-law", str(_file(tmp, "ball.csv", MM_CSV))),
        ("ball.csv", "deflection_m", "did you give millimetres"),
    ),
    "ball-law-csv-in-kN": (
        lambda tmp: _predict(tmp, "--ball-law", str(_file(tmp, "ball.csv", KN_CSV))),
        ("ball.csv", "force_n", "kN"),
    ),
    "string-bed-csv-in-mm": (
        lambda tmp: _predict(
            tmp,
            "--racket",
            str(
                _toml(
                    _file(tmp, "bed.csv", MM_CSV).parent,
                    "[strings]\n",
                    '[strings]\nload_deflection_file = "bed.csv"\n',
                )
            ),
        ),
        ("bed.csv", "did you give millimetres"),
    ),
    "ball-mass-in-grams": (
        lambda tmp: _predict(tmp, "--ball-mass", "57.7"),
        ("--ball-mass 57.7", "56–59.4 g", "did you give grams"),
    ),
    "string-diameter-in-mm": (
        lambda tmp: _predict(
            tmp,
            "--racket",
            str(_toml(tmp, "string_diameter_m = 0.00130", "string_diameter_m = 1.30")),
        ),
        ("string_diameter_m = 1.3", "1.05–1.45 mm", "did you give millimetres"),
    ),
    "tension-55e3": (
        lambda tmp: _predict(
            tmp, "--racket", str(_toml(tmp, "tension_n = 246.0", "tension_n = 55e3"))
        ),
        ("tension_n", "147–343 N", "15–35 kg"),
    ),
    "tension-in-pounds": (
        lambda tmp: _predict(
            tmp, "--racket", str(_toml(tmp, "tension_n = 246.0", "tension_n = 55"))
        ),
        ("tension_n = 55", "did you give pounds", "allow_implausible"),
    ),
    "point-mass-5-kg": (
        lambda tmp: _predict(
            tmp,
            "--racket",
            str(_toml(tmp, "", "\n[[point_masses]]\nmass_kg = 5.0\nx_m = 0.675\n")),
        ),
        ("[[point_masses]] 1.mass_kg = 5", "did you give grams"),
    ),
    "racket-mass-in-grams": (
        lambda tmp: _predict(tmp, "--racket", str(_toml(tmp, "mass_kg = 0.360", "mass_kg = 300"))),
        ("[racket].mass_kg = 300", "0.23–0.4 kg", "did you give grams"),
    ),
    "length-in-cm": (
        lambda tmp: _predict(
            tmp, "--racket", str(_toml(tmp, "length_m = 0.680", "length_m = 68.5"))
        ),
        ("length_m = 68.5", "did you give centimetres"),
    ),
    "speed-in-km/h": (
        lambda tmp: ["predict", "--speed", "90", "--no-figures", "--out", str(tmp / "out")],
        ("--speed 90", "up to 75 m/s", "did you give km/h"),
    ),
    "racket-speed-in-km/h": (
        lambda tmp: _predict(tmp, "--racket-speed", "100"),
        ("--racket-speed 100", "did you give km/h"),
    ),
    "oblique-speed-in-km/h": (
        lambda tmp: ["oblique", "--speed", "90", "--no-figures", "--out", str(tmp / "out")],
        ("--speed 90", "did you give km/h"),
    ),
    # trial of 2026-11-23: these ran with exit 0 (or blamed the ball speed)
    "swing-axis-in-mm": (
        lambda tmp: ["swing", "--axis-to-butt", "607", "--no-figures", "--out", str(tmp / "out")],
        ("--axis-to-butt 607", "did you give millimetres"),
    ),
    "swing-angular-speed-in-deg/s": (
        lambda tmp: ["swing", "--angular-speed", "900", "--no-figures", "--out", str(tmp / "out")],
        ("--angular-speed 900", "did you give degrees per second"),
    ),
    # trial of 2026-11-26 (issue 13): these ran with exit 0 or named neither option nor slip
    "racket-speed-in-mph": (
        lambda tmp: _predict(tmp, "--racket-speed", "67"),
        ("--racket-speed 67", "up to 55 m/s", "did you give", "mph (67 mph = 30 m/s)"),
    ),
    "swing-angle-in-radians": (
        lambda tmp: [
            "swing",
            "--swing-angle-deg",
            "1.57",
            "--no-figures",
            "--out",
            str(tmp / "out"),
        ],
        ("--swing-angle-deg 1.57", "did you give radians (1.57 rad = 90 °)"),
    ),
    "e-bg-in-percent": (
        lambda tmp: _predict(tmp, "--e-bg", "83"),
        ("--e-bg 83", "between 0 and 1", "did you give a percentage (83 % = 0.83)"),
    ),
    "twist-point-in-mm": (
        lambda tmp: ["twist", "--x", "520", "--no-figures", "--out", str(tmp / "out")],
        ("x=520", "did you give millimetres"),
    ),
    # trial of 2026-11-26, second session: compound took a 5000 N preload (a 169 kN/m spring)
    "compound-preload-in-grams": (
        _step("compound", "--preload", "500"),
        ("--preload 500", "up to 50 N", "did you give grams (gf) (500 g = 4.9 N)"),
    ),
    # trial of 2026-11-26, second session: offsets in mm blamed "impact point 1", a ball's
    # point in cm said "give points on the strings", and one point was numbered "--point 1"
    "twist-offsets-in-mm": (
        _step("twist", "--offsets=-50,0,50"),
        ("--offsets", "y=-50", "did you give millimetres"),
    ),
    "compound-point-in-cm": (
        _step("compound", "--ball-at=51,0"),
        ("--ball-at at x=51", "did you give centimetres"),
    ),
    "swing-torque-in-n-mm": (
        _step("swing", "--torque", "56900"),
        ("--torque 56900", "did you give N·mm (56900 N·mm = 56.9 N·m)"),
    ),
    "identify-band-in-khz": (
        _step("identify", "nothing.uff", "--band", "0.04,0.85", figures=False),
        ("--band 0.04,0.85", "did you give kHz (0.04–0.85 kHz = 40–850 Hz)"),
    ),
    "oblique-point-in-mm": (
        lambda tmp: ["oblique", "--point=500,0", "--no-figures", "--out", str(tmp / "out")],
        ("x=500", "did you give millimetres"),
    ),
}


@pytest.mark.parametrize("slip", list(SLIPS))
def test_a_unit_slip_is_one_line_and_exit_2(
    slip: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    build, words = SLIPS[slip]
    code = main(build(tmp_path))
    err = capsys.readouterr().err
    lines = err.splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith("racketdyn: error:")
    for word in words:
        assert word in lines[0], f"{word!r} not in {lines[0]!r}"
    assert code == 2
    assert not (tmp_path / "out" / "impact.csv").exists()


# --- from Python, where each check lives ------------------------------------------------------
@pytest.mark.parametrize(
    ("old", "new", "words"),
    [
        ("mass_kg = 0.360", "mass_kg = 300", "did you give grams"),
        ("length_m = 0.680", "length_m = 68.5", "did you give centimetres"),
        ("length_m = 0.680", "length_m = 27", "did you give inches"),
        ("balance_m = 0.308", "balance_m = 30.8", "did you give centimetres"),
        ("inertia_cg_kgm2 = 0.0131", "inertia_cg_kgm2 = 13.1", "did you give g·m²"),
        ("inertia_cg_kgm2 = 0.0131", "inertia_cg_kgm2 = 131", "did you give kg·cm²"),
        ("area_cm2 = 628.0", "area_cm2 = 97", "did you give square inches"),
        ("string_diameter_m = 0.00130", "string_diameter_m = 1.30", "did you give millimetres"),
        ("string_diameter_m = 0.00130", "string_diameter_m = 17", "a gauge number (gauge 17 ≈ 1.2"),
        ("string_modulus_pa = 5.0e9", "string_modulus_pa = 5.0", "did you give GPa"),
        ("tension_n = 246.0", "tension_n = 25", "did you give kilograms"),
        ("first_bending_hz = 120.0", "first_bending_hz = 754", "did you give rad/s"),
    ],
)
def test_load_racket_names_the_slip(tmp_path: Path, old: str, new: str, words: str) -> None:
    with pytest.raises(InputError, match=re.escape(words)):
        rd.load_racket(_toml(tmp_path, old, new))


def test_a_derived_swingweight_is_checked(tmp_path: Path) -> None:
    # each number plausible alone, together a swingweight of 412 kg·cm²
    path = _toml(tmp_path, "inertia_cg_kgm2 = 0.0131", "inertia_cg_kgm2 = 0.0250")
    with pytest.raises(InputError, match=r"swingweight .* 250–380 kg·cm²"):
        rd.load_racket(path)


def test_ball_and_hand_from_python() -> None:
    with pytest.raises(InputError, match="did you give grams"):
        ball_from(mass_kg=57.7)
    with pytest.raises(InputError, match="set `allow_implausible`"):
        ball_from(mass_kg=0.045)  # a stage-2 (orange) ball
    assert ball_from(mass_kg=0.045, allow_implausible=True)[0].mass_kg == 0.045
    with pytest.raises(InputError, match="did you give grams"):
        ball_from(mass_kg=57.7, allow_implausible=True)  # a slip stays refused
    with pytest.raises(InputError, match="did you give grams"):
        hand_for(["hand"], 1000.0)
    assert hand_for(["free"], 1000.0) == (None, [])  # no hand, nothing to check


def test_a_ball_object_refuses_a_unit_slip() -> None:
    with pytest.raises(InputError, match="did you give grams"):
        rd.Ball(mass_kg=57.7)
    with pytest.raises(InputError, match="did you give millimetres"):
        rd.Ball(diameter_m=67.0)
    assert rd.Ball(mass_kg=0.045).mass_kg == 0.045  # a stage ball object is taken as given


def test_speeds_from_python() -> None:
    check_speeds("--speed", [10.0, 75.0])
    with pytest.raises(InputError, match=r"did you give km/h \(90 km/h = 25 m/s\)"):
        check_speeds("--speed", [10.0, 90.0])
    check_speeds("--speed", [90.0], allow_implausible=True)
    with pytest.raises(InputError, match="refused even with `allow_implausible`"):
        check_speeds("--speed", [400.0], allow_implausible=True)


def test_load_deflection_scale(tmp_path: Path) -> None:
    deflection, force = read_load_deflection(_file(tmp_path, "good.csv", GOOD_CSV))
    assert deflection.max() == 0.02
    assert force.max() == 1200.0
    with pytest.raises(InputError, match="did you give millimetres"):
        read_load_deflection(_file(tmp_path, "mm.csv", MM_CSV))
    with pytest.raises(InputError, match="in kN"):
        read_load_deflection(_file(tmp_path, "kn.csv", KN_CSV))


# --- what must still pass ----------------------------------------------------------------------
def test_the_built_in_racket_ball_and_hand_are_plausible() -> None:
    racket = rd.default_racket()
    assert RANGES["swingweight_kgcm2"].low <= racket.swingweight_kgcm2
    assert racket.swingweight_kgcm2 <= RANGES["swingweight_kgcm2"].high
    ball = rd.Ball()
    check("ball_mass_kg", ball.mass_kg, "ball")
    check("ball_diameter_m", ball.diameter_m, "ball")
    from racketdyn.impact.hand import Hand

    check("hand_arm_mass_kg", Hand().arm_mass_kg, "hand")


def test_the_documented_racket_file_passes(tmp_path: Path) -> None:
    page = (DOCS / "racket-file.md").read_text(encoding="utf-8")
    block = re.search(r"```toml\n(.*?)```", page, re.S)
    assert block is not None
    racket = rd.load_racket(_file(tmp_path, "doc.toml", block.group(1)))
    assert racket.mass_kg == 0.300


def test_every_number_of_the_racket_file_has_a_range() -> None:
    for kind, keys in _SCHEMA.items():
        numbers = {key for key, wanted in keys.items() if wanted in (float, int)}
        assert numbers == set(_PLAUSIBLE.get(kind, {})), kind
    assert all(key in RANGES for table in _PLAUSIBLE.values() for key in table.values())


def test_ranges_read_well() -> None:
    assert RANGES["mass_kg"].text() == "a strung racket weighs 0.23–0.4 kg (230–400 g)"
    assert RANGES["area_cm2"].text() == "a string bed covers 516–903 cm² (80–140 sq in)"
    assert RANGES["length_m"].text() == "a racket is 0.6–0.737 m (23.6–29 in) long"


# --- the override -------------------------------------------------------------------------------
def test_an_unusual_racket_goes_on_when_its_file_says_so(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    junior = _file(tmp_path, "junior.toml", JUNIOR)
    with pytest.raises(InputError, match=r"\[checks\] allow_implausible = true"):
        rd.load_racket(junior)
    assert rd.load_racket(junior, allow_implausible=True).mass_kg == 0.210
    allowed = _file(tmp_path, "junior.toml", JUNIOR + "[checks]\nallow_implausible = true\n")
    assert main(_predict(tmp_path, "--racket", str(allowed))) == 0
    assert (tmp_path / "out" / "impact.csv").exists()
    # a slip in an allowed file is refused still
    slipped = _file(tmp_path, "slip.toml", allowed.read_text().replace("0.635", "63.5"))
    with pytest.raises(InputError, match="did you give centimetres"):
        rd.load_racket(slipped)
    with pytest.raises(InputError, match="true or false"):
        rd.load_racket(_file(tmp_path, "bad.toml", JUNIOR + "[checks]\nallow_implausible = 1\n"))
    capsys.readouterr()


def test_allow_implausible_on_the_command_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = _predict(tmp_path, "--ball-mass", "0.045")
    assert main(argv) == 2
    assert "--allow-implausible" in capsys.readouterr().err
    assert main([*argv, "--allow-implausible"]) == 0
    assert main([*_predict(tmp_path, "--ball-mass", "45"), "--allow-implausible"]) == 2
    assert "did you give grams" in capsys.readouterr().err


def test_a_value_at_a_printed_end_of_a_range_is_taken() -> None:
    """New-user trial (2026-11-26, second session): ``tension_n = 147`` (15 kg) was refused
    with "a string is strung at 147–343 N (15–35 kg)": the range starts at 15 × 9.80665 =
    147.0998 N and prints as 147.  A value at an end as printed (3 significant figures) is
    taken; one beyond it still refused."""
    assert check("tension_n", 147.0, "[strings].tension_n") == 147.0
    assert check("tension_n", 343.0, "[strings].tension_n") == 343.0
    with pytest.raises(InputError, match="147–343 N"):
        check("tension_n", 146.0, "[strings].tension_n")
    with pytest.raises(InputError, match="up to 75 m/s"):
        check("ball_speed_mps", 75.6, "--speed")


def test_angles_in_radians_are_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``oblique --angles 0,0.5,1.0`` (radians) ran as three angles within a degree of the
    normal (new-user trial, 2026-11-26): one line naming radians and the degrees meant."""
    assert main(["oblique", "--angles", "0,0.5,1.0", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert "did you give radians (--angles=0,28.6,57.3 in degrees)" in err
    assert "\n" not in err
    from racketdyn.plausibility import check_degrees

    check_degrees("--angles", [0.0, 15.0, 30.0])  # degrees as written
    check_degrees("--angles", [0.0, 1.0])  # whole numbers: degrees
    check_degrees("--angles", [0.5, 1.0], allow_implausible=True)
