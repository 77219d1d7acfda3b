"""The hand's stiffness and damping as options of every command that takes ``--support hand``
(issue 15): units, plausible ranges with the unit slips, run.json, and calibrate naming them."""

from __future__ import annotations

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.cli import main
from racketdyn.impact.hand import Hand
from racketdyn.impact.transient import predict_transient

POINTS = [(0.505, 0.0), (0.60, 0.03)]


def test_the_options_reach_the_model_and_run_json(tmp_path: Path) -> None:
    """predict --support hand --hand-stiffness 60000 --hand-damping 30 is predict_transient with
    that Hand, and run.json records it."""
    (tmp_path / "points.csv").write_text("x_m,y_m\n0.505,0\n0.60,0.03\n", encoding="utf-8")
    argv = ["predict", "--model", "transient", "--support", "hand", "--speed", "20"]
    argv += ["--points", str(tmp_path / "points.csv"), "--no-figures"]
    argv += ["--hand-stiffness", "60000", "--hand-damping", "30", "--out", str(tmp_path / "p")]
    assert main(argv) == 0
    record = json.loads((tmp_path / "p" / "run.json").read_text(encoding="utf-8"))
    assert record["hand"]["stiffness_n_per_m"] == 60000.0
    assert record["hand"]["damping_ns_per_m"] == 30.0
    assert record["hand"]["arm_mass_kg"] == 1.0
    assert any("default arm 1000 g" in d for d in record["defaults_used"])
    assert not any("stiffness" in d for d in record["defaults_used"])
    hand = Hand(stiffness_n_per_m=6e4, damping_ns_per_m=30.0)
    direct = predict_transient(rd.default_racket(), rd.Ball(), POINTS, [20.0], "hand", hand=hand)
    rows = (tmp_path / "p" / "impact.csv").read_text(encoding="utf-8").splitlines()
    header = rows[0].split(",")
    column = header.index("rebound_ratio")
    values = [float(r.split(",")[column]) for r in rows[1:]]
    np.testing.assert_allclose(values, direct.rebound_ratio[:, 0, 0], rtol=5e-9)  # 9 digits


@pytest.mark.parametrize(
    ("option", "value", "words"),
    [
        ("--hand-stiffness", "20", "did you give kN/m (20 kN/m = 20000 N/m)"),
        ("--hand-stiffness", "50", "N/mm (50 N/mm = 50000 N/m)"),
        ("--hand-damping", "0.012", "kN·s/m (0.012 kN·s/m = 12 N·s/m)"),
        ("--hand-damping", "1e6", "outside 0–100000 N·s/m: refused"),
    ],
)
def test_a_slipped_unit_is_named(
    option: str, value: str, words: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = ["predict", "--model", "transient", "--support", "hand", "--grid", "3"]
    argv += ["--speed", "20", "--no-figures", option, value, "--out", str(tmp_path)]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert option in err[0]
    assert words in err[0]


def test_an_unusual_hand_passes_with_the_override(tmp_path: Path) -> None:
    """A clamp-like grip of 2·10⁶ N/m is implausible for a hand, not impossible."""
    argv = ["twist", "--support", "hand", "--offsets", "0", "--hand-stiffness", "2e6"]
    argv += ["--no-figures", "--out", str(tmp_path)]
    assert main(argv) == 2
    assert main([*argv, "--allow-implausible"]) == 0
    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert record["hand"]["stiffness_n_per_m"] == 2e6


@pytest.mark.parametrize("command", ["swing", "oblique", "validate", "calibrate"])
def test_every_hand_command_has_the_options(
    command: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit):
        main([command, "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "--hand-stiffness N/M" in text
    assert "N/m, for --support hand (default 20000" in text
    assert "--hand-damping N·S/M" in text
    assert "N·s/m, for --support hand (default 12" in text


def test_calibrate_names_the_hand_options() -> None:
    """calibration.json's "calibrated_files" names the option for every identified value."""
    from racketdyn.workflows.calibrate import _options

    fitted = SimpleNamespace(
        values={
            "e_bg": 0.8312,
            "hand_stiffness_n_per_m": 31234.5,
            "hand_damping_ns_per_m": 17.25,
            "hand_arm_mass_kg": math.nan,
        }
    )
    text = _options(fitted)  # type: ignore[arg-type]
    assert text == "--e-bg 0.8312 --hand-stiffness 31234 --hand-damping 17.25"
    assert _options(SimpleNamespace(values={"e_bg": math.nan})) == "none"  # type: ignore[arg-type]


def test_validate_takes_the_hand_options(tmp_path: Path) -> None:
    measured = tmp_path / "measured.csv"
    measured.write_text(
        "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio\n0.5,0,20,0,hand,0.38\n",
        encoding="utf-8",
    )
    argv = ["validate", str(measured), "--hand-stiffness", "40000", "--hand-damping", "25"]
    assert main([*argv, "--no-figures", "--out", str(tmp_path / "v")]) == 0
    record = json.loads((tmp_path / "v" / "run.json").read_text(encoding="utf-8"))
    assert record["hand"]["stiffness_n_per_m"] == 40000.0
    assert record["hand"]["damping_ns_per_m"] == 25.0
