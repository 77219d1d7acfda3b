"""``oblique`` states the racket speed wherever it shows a number (new-user trial, ninth
session): the report's headline said "oblique impact at 30°, ball 25 m/s, free: leaves at
11.0° with 456 rad/s" of a run with the racket at 10 m/s, and neither ``oblique.png``'s title
nor the figure data the folder holds (``read_step_data``) carried the racket speed."""

from __future__ import annotations

import csv
from pathlib import Path

import matplotlib
import pytest

from racketdyn.cli import main
from racketdyn.report.folder import RunFolder
from racketdyn.report.sections import oblique
from racketdyn.workflows.figure_data import read_step_data

matplotlib.use("Agg")

RACKET_SPEED = 10.0


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Two oblique impacts with the racket moving at 10 m/s (a few seconds)."""
    out = tmp_path_factory.mktemp("oblique") / "run"
    argv = ["oblique", "--speed", "20", "--racket-speed", str(RACKET_SPEED), "--angles", "0,30"]
    assert main([*argv, "--no-figures", "--out", str(out / "oblique")]) == 0
    return out


def test_the_folder_s_figure_data_and_table_carry_the_racket_speed(run: Path) -> None:
    data = read_step_data(run / "oblique")
    assert data["curve"].racket_speed_mps == RACKET_SPEED
    with (run / "oblique" / "oblique.csv").open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert {float(r["racket_speed_mps"]) for r in rows} == {RACKET_SPEED}


def test_the_figure_title_names_the_racket_speed(run: Path) -> None:
    from racketdyn.plotting.figures import figure_oblique

    data = read_step_data(run / "oblique")
    figure = figure_oblique(data["curve"], data["point"], data["support"], data["contact"])
    title = figure.get_suptitle()
    assert f"ball 20 m/s, racket {RACKET_SPEED:g} m/s, free" in title


def test_the_report_s_headline_names_the_racket_speed_and_the_caveat(run: Path) -> None:
    data = oblique.gather(RunFolder.scan(run))
    assert data is not None
    (line,) = [g for g in data["glance"] if g.startswith("oblique impact")]
    assert f"ball 20 m/s, racket {RACKET_SPEED:g} m/s, free: leaves at" in line
    assert "the upper end of the model's range" in line
    assert f"racket {RACKET_SPEED:g} m/s" in data["oblique"]["settings"]["speed"]
