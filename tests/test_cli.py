"""End-to-end tests of the ``racketdyn`` command line, run in-process through ``main``."""

from __future__ import annotations

import csv
import json
import re
from collections.abc import Callable
from pathlib import Path

import pytest

import racketdyn
from racketdyn.cli import main

DEFAULT_TOML = Path(racketdyn.__file__).parent / "data" / "kawazoe_2002.toml"

IMPACT_COLUMNS = [
    "point",
    "x_m",
    "y_m",
    "support",
    "ball_speed_mps",
    "racket_speed_mps",
    "reduced_mass_kg",
    "stiffness_n_per_m",
    "contact_time_s",
    "mean_force_n",
    "peak_force_n",
    "vibration_energy_j",
    "cor",
    "rebound_ratio",
    "rebound_speed_mps",
]

FIGURE_NAMES = [
    "fig11_12_force_contact_time.png",
    "fig13_pulse_spectrum.png",
    "fig14_frame_vibration.png",
    "fig15_rebound_along_axis.png",
    "face_maps.png",
]


def _read_csv(path: Path) -> tuple[list[str], list[dict[str, str]]]:
    with path.open(newline="", encoding="utf-8") as handle:
        reader = csv.DictReader(handle)
        rows = list(reader)
        return list(reader.fieldnames or []), rows


def _write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def _edited_toml(tmp_path: Path, old: str, new: str) -> Path:
    """The built-in racket file with one exact edit, written into ``tmp_path``."""
    text = DEFAULT_TOML.read_text(encoding="utf-8")
    assert old in text, f"{old!r} not found in {DEFAULT_TOML.name}; update the test"
    return _write(tmp_path / "racket.toml", text.replace(old, new, 1))


def _without_head(tmp_path: Path) -> Path:
    text = DEFAULT_TOML.read_text(encoding="utf-8")
    start, end = text.index("[head]"), text.index("[strings]")
    return _write(tmp_path / "racket.toml", text[:start] + text[end:])


def _predict(tmp_path: Path, *extra: str, speed: str = "10") -> list[str]:
    out = tmp_path / "out"
    return ["predict", *extra, "--speed", speed, "--no-figures", "--out", str(out)]


# --- happy paths -------------------------------------------------------------------------------


def test_predict_writes_csv_and_run_record(tmp_path: Path) -> None:
    args = ["predict", "--speed", "10,20", "--support", "free,pinned", "--grid", "5"]
    code = main([*args, "--no-figures", "--out", str(tmp_path)])

    assert code == 0
    header, rows = _read_csv(tmp_path / "impact.csv")
    assert header[: len(IMPACT_COLUMNS)] == IMPACT_COLUMNS
    n_points = len(racketdyn.default_racket().head.grid(5))
    assert n_points > 0
    assert len(rows) == n_points * 2 * 2
    assert {row["support"] for row in rows} == {"free", "pinned"}
    assert {float(row["ball_speed_mps"]) for row in rows} == {10.0, 20.0}

    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert record["racketdyn_version"] == racketdyn.__version__
    assert record["speeds_mps"] == [10.0, 20.0]
    assert record["supports"] == ["free", "pinned"]
    assert isinstance(record["defaults_used"], list)
    assert record["defaults_used"]
    assert record["n_points"] == n_points


def test_predict_with_points_file(tmp_path: Path) -> None:
    points = _write(tmp_path / "points.csv", "x_m,y_m\n0.505,0.0\n0.45,0.02\n0.56,-0.03\n")
    out = tmp_path / "out"
    code = main(
        ["predict", "--points", str(points), "--speed", "15", "--no-figures", "--out", str(out)]
    )

    assert code == 0
    _, rows = _read_csv(out / "impact.csv")
    assert len(rows) == 3 * 1 * 2
    assert {(float(r["x_m"]), float(r["y_m"])) for r in rows} == {
        (0.505, 0.0),
        (0.45, 0.02),
        (0.56, -0.03),
    }


def test_predict_with_point_off_the_strings_exits_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    points = _write(tmp_path / "points.csv", "x_m,y_m\n0.505,0.0\n0.2,0.0\n")
    assert main(_predict(tmp_path, "--points", str(points))) == 2
    assert "racketdyn: error:" in capsys.readouterr().err


@pytest.mark.slow
def test_predict_draws_figures(tmp_path: Path) -> None:
    code = main(["predict", "--speed", "20", "--grid", "4", "--out", str(tmp_path)])

    assert code == 0
    for name in FIGURE_NAMES:
        figure = tmp_path / name
        assert figure.is_file(), f"{name} was not written"
        assert figure.stat().st_size > 0, f"{name} is empty"
    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert set(FIGURE_NAMES) <= set(record["outputs"])


def test_racket_prints_properties(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["racket"]) == 0
    assert "swingweight" in capsys.readouterr().out


def test_racket_prints_one_unit_per_quantity_and_its_defaults(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """New-user trial (issue 13): ``racket`` printed the inertia about the balance point twice
    (0.0158 kg·m² and, as the recoil weight, 158 kg·cm²), inertias in two units, lengths in m
    where the field quotes mm, and a 2-node twisting mode at 361 Hz for a racket file that gives
    none: the paper's racket's frequency, with no word that it is a default."""
    text = DEFAULT_TOML.read_text(encoding="utf-8")
    assert "twisting_hz" in text
    racket = _write(tmp_path / "r.toml", re.sub(r"(?m)^twisting_hz.*\n", "", text))
    assert main(["racket", "--racket", str(racket)]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "kg·m²" not in out
    assert "recoil weight" in out
    assert "balance point, from the butt │ 308 │ mm" in out
    assert "[modal] twisting_hz not in the file" in out
    assert "default 361 Hz" in out


# --- bad input: one line on stderr, exit status 2, no traceback ------------------------------

# Each case builds the arguments (given tmp_path) and names the words the message must contain.
BAD_INPUT: dict[str, tuple[Callable[[Path], list[str]], tuple[str, ...]]] = {
    "point-outside-the-string-bed": (
        lambda tmp: _predict(
            tmp, "--points", str(_write(tmp / "points.csv", "x_m,y_m\n0.2,0.0\n"))
        ),
        ("impact point", "outside the string bed"),
    ),
    "zero-mass": (
        lambda tmp: _predict(
            tmp, "--racket", str(_edited_toml(tmp, "mass_kg = 0.360", "mass_kg = 0"))
        ),
        ("mass_kg",),
    ),
    "negative-mass": (
        lambda tmp: _predict(
            tmp, "--racket", str(_edited_toml(tmp, "mass_kg = 0.360", "mass_kg = -0.3"))
        ),
        ("mass_kg",),
    ),
    "balance-beyond-the-tip": (
        lambda tmp: _predict(
            tmp, "--racket", str(_edited_toml(tmp, "balance_m = 0.308", "balance_m = 0.700"))
        ),
        ("balance_m",),
    ),
    "malformed-TOML": (
        lambda tmp: _predict(tmp, "--racket", str(_edited_toml(tmp, "[racket]", "[racket"))),
        ("racket.toml", "malformed TOML"),
    ),
    "unknown-support": (
        lambda tmp: _predict(tmp, "--support", "free,clamped"),
        ("--support", "clamped"),
    ),
    "non-numeric-speed": (
        lambda tmp: _predict(tmp, speed="10,fast"),
        ("--speed", "fast"),
    ),
    "negative-speed": (
        lambda tmp: _predict(tmp, speed="10,-5"),
        ("--speed", "-5"),
    ),
    "unknown-key": (
        lambda tmp: _predict(
            tmp, "--racket", str(_edited_toml(tmp, "mass_kg = 0.360", "mas_kg = 0.360"))
        ),
        ("mas_kg",),
    ),
    "missing-head-table": (
        lambda tmp: _predict(tmp, "--racket", str(_without_head(tmp))),
        ("[head]", "missing"),
    ),
    "nonexistent-racket-file": (
        lambda tmp: _predict(tmp, "--racket", str(tmp / "no_such_racket.toml")),
        ("no_such_racket.toml",),
    ),
    "points-without-y_m": (
        lambda tmp: _predict(
            tmp, "--points", str(_write(tmp / "points.csv", "x_m,z_m\n0.5,0.0\n"))
        ),
        ("y_m",),
    ),
    "points-with-a-non-number": (
        lambda tmp: _predict(
            tmp, "--points", str(_write(tmp / "points.csv", "x_m,y_m\n0.5,0.0\n0.5,abc\n"))
        ),
        ("y_m", "abc"),
    ),
    # review of issue 11: these raised FileExistsError / NotADirectoryError with a traceback
    "out-is-a-file": (
        lambda tmp: ["predict", "--no-figures", "--out", str(_write(tmp / "my.toml", "x"))],
        ("--out", "my.toml", "is a file"),
    ),
    "out-below-a-file": (
        lambda tmp: [
            "swing",
            "--no-figures",
            "--out",
            str(_write(tmp / "notes.txt", "x") / "sub"),
        ],
        ("--out", "notes.txt", "is a file"),
    ),
}


@pytest.mark.parametrize("case", list(BAD_INPUT))
def test_bad_input_is_one_line_and_exit_2(
    case: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    build, words = BAD_INPUT[case]

    code = main(build(tmp_path))

    err = capsys.readouterr().err
    assert "Traceback" not in err
    lines = err.splitlines()
    assert len(lines) == 1, f"expected one line on stderr, got {lines!r}"
    assert lines[0].startswith("racketdyn: error:"), lines[0]
    for word in words:
        assert word in lines[0], f"{word!r} not named in {lines[0]!r}"
    assert code == 2
    assert not (tmp_path / "out" / "impact.csv").exists()


def test_run_record_names_the_command_as_called(tmp_path: Path) -> None:
    """run.json records the arguments given to main (not the Python process's own argv)."""
    argv = ["predict", "--speed", "10", "--grid", "2", "--no-figures", "--out", str(tmp_path)]
    assert main(argv) == 0
    record = json.loads((tmp_path / "run.json").read_text())
    assert record["command"] == ["racketdyn", *argv]


def test_report_takes_the_racket_the_runs_recorded(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Review of issue 11: `racketdyn report` showed the built-in racket for a run on another."""
    toml = _edited_toml(
        tmp_path, 'name = "Kawazoe test racket (360 g, 97 sq in)"', 'name = "Lab racket 300 g"'
    )
    toml = _write(
        toml, toml.read_text(encoding="utf-8").replace("mass_kg = 0.360", "mass_kg = 0.300")
    )
    run_dir = tmp_path / "run"
    argv = ["predict", "--racket", str(toml), "--speed", "20", "--grid", "3", "--no-figures"]
    assert main([*argv, "--out", str(run_dir / "predict")]) == 0
    assert main(["report", str(run_dir)]) == 0
    page = (run_dir / "report.html").read_text(encoding="utf-8")
    assert "Lab racket 300 g" in page
    assert "Kawazoe test racket" not in page
