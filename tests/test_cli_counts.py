"""Counts on the console take the noun in the number they need: ``frf`` printed "1 averages
rejected", ``predict`` at one point "1 impacts (1 points × 1 speeds × 1 supports)" (the closing
notes of issues 14-15)."""

from __future__ import annotations

import dataclasses
import io
import re
from pathlib import Path

import numpy as np
import pytest
from rich.console import Console

from racketdyn.cli import main
from racketdyn.cli import options as opt
from racketdyn.testing.records import Modes, records_for

MODES = Modes(np.array([120.0, 330.0]), np.array([0.03, 0.02]), np.array([[6.0, 4.0], [-3.0, 2.5]]))
# "1 <noun>s" for every noun the commands count
ONE_PLURAL = re.compile(
    r"(?<![\d.])1 (averages|impacts|points|speeds|supports|offsets|rows|modes|FRFs|"
    r"candidate poles|double hits|overloads)\b"
)


@pytest.fixture(autouse=True)
def _wide(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COLUMNS", "400")


def test_plural() -> None:
    assert opt.plural(0, "average") == "0 averages"
    assert opt.plural(1, "average") == "1 average"
    assert opt.plural(2, "average") == "2 averages"
    assert opt.plural(1, "candidate pole") == "1 candidate pole"
    assert opt.plural(3, "double hit") == "3 double hits"
    assert opt.plural(1, "FRF") == "1 FRF"


@pytest.mark.slow
def test_frf_says_one_average_rejected(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from racketdyn.io import write_hammer_csv

    records = records_for(MODES, n_averages=3)
    records = dataclasses.replace(records, force=tuple(f.copy() for f in records.force))
    records.force[1][0] = 0.0  # one average of six without a pulse
    data, _ = write_hammer_csv(records, tmp_path / "h.csv", tmp_path / "g.csv")
    assert main(["frf", str(data), "--out", str(tmp_path / "o")]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "1 average rejected: empty" in printed
    assert not ONE_PLURAL.search(printed), ONE_PLURAL.search(printed)


def test_predict_at_one_point_speed_and_support(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    points = tmp_path / "one.csv"
    points.write_text("x_m,y_m\n0.52,0.0\n", encoding="utf-8")
    argv = ["predict", "--points", str(points), "--speed", "20", "--support", "free"]
    assert main([*argv, "--no-figures", "--out", str(tmp_path / "o")]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "1 impact (1 point × 1 speed × 1 support)" in printed
    assert "none of 1 row in impact.csv" in printed
    assert not ONE_PLURAL.search(printed), ONE_PLURAL.search(printed)


def test_twist_at_one_offset(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["twist", "--offsets", "0.03", "--support", "free", "--no-figures"]
    assert main([*argv, "--out", str(tmp_path / "o")]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "1 offset × 1 support" in printed
    assert not ONE_PLURAL.search(printed), ONE_PLURAL.search(printed)


def test_one_failed_impact_is_one_impact() -> None:
    sink = io.StringIO()
    console = Console(file=sink, width=400, color_system=None)
    opt.print_status(console, np.array(["ok", "beyond the law"]), "impact.csv")
    assert "1 impact: beyond the law; NaN in impact.csv" in sink.getvalue()


def test_library_messages_take_the_number_of_their_count(tmp_path: Path) -> None:
    """Library messages wrote "missing column(s) x", "node(s) 12", "unknown parameter(s)":
    one missing column reads "missing column", two "missing columns"."""
    import racketdyn as rd
    from racketdyn.io.measured import read_measured

    header = "x_m,y_m,ball_speed_mps,support,rebound_ratio"
    one = tmp_path / "one.csv"
    one.write_text(header + "\n0.5,0,20,free,0.4\n", encoding="utf-8")
    with pytest.raises(rd.InputError) as error:
        read_measured(one)
    assert "missing column racket_speed_mps;" in str(error.value)
    two = tmp_path / "two.csv"
    two.write_text("x_m,y_m,support,rebound_ratio\n0.5,0,free,0.4\n", encoding="utf-8")
    with pytest.raises(rd.InputError) as error:
        read_measured(two)
    assert "missing columns ball_speed_mps, racket_speed_mps;" in str(error.value)
    assert "(s)" not in str(error.value)
