"""What ``racketdyn calibrate`` says on the console (issue 27).

The new-user trial: calibrate ran 29 s without a line, printed "held out nan (0 rows)" when no
row was held out, and called every parameter "ok" beside a reduced χ² of 16.8 — a fit that does
not explain the measurements within their standard deviations.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from racketdyn.ball import Ball
from racketdyn.cli import main
from racketdyn.impact.calibration import apply, simulate_measurements
from racketdyn.impact.measured import ModelInputs
from racketdyn.io.racket_file import default_racket

FACE = [(0.45, 0.0), (0.50, 0.0), (0.55, 0.0), (0.60, 0.0), (0.50, 0.06), (0.55, -0.06)]


def _measured(tmp_path: Path, sd: float, scatter: float) -> Path:
    """A ball-cannon table of the built-in racket (approximate method's truth, e_BG 0.78),
    with ``scatter`` of noise on the ratios and ``sd`` stated for each."""
    start = ModelInputs(default_racket(), Ball())
    truth = apply(start, {"e_bg": 0.78})
    measured = simulate_measurements(truth, FACE, 20.0, sd=0.0, method="approx")
    noise = np.random.default_rng(3).normal(0.0, scatter, len(measured))
    lines = ["x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio,rebound_ratio_sd"]
    for i in range(len(measured)):
        x, y = measured.locations[i]
        ratio = float(measured.rebound_ratio[i] + noise[i])
        lines.append(f"{x},{y},20,0,free,{ratio!r},{sd}")
    path = tmp_path / "measured.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _calibrate(path: Path, out: Path, *extra: str) -> int:
    argv = ["calibrate", str(path), "--model", "approx", "--fit", "e_bg", *extra]
    return main([*argv, "--out", str(out)])


def test_no_held_out_rows_is_not_nan(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _measured(tmp_path, sd=0.01, scatter=0.01)
    capsys.readouterr()
    assert _calibrate(path, tmp_path / "cal", "--no-loo") == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "nan" not in out
    assert "held out" not in out  # none was
    assert "leave-one-out" not in out  # not run
    assert "RMS of the rebound ratio: fit" in out


@pytest.mark.slow
def test_progress_lines_name_the_fit_and_the_refits(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = _measured(tmp_path, sd=0.01, scatter=0.01)
    capsys.readouterr()
    assert _calibrate(path, tmp_path / "cal", "--holdout", "6") == 0
    out = " ".join(capsys.readouterr().out.split())
    # not a terminal: the progress goes as lines
    assert "fitting e_bg to 5 rows (approx)" in out
    assert re.search(r"leave-one-out: refit 1 of \d", out)
    assert "held out" in out
    assert "(1 row)" in out


def test_a_poor_fit_is_said(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _measured(tmp_path, sd=0.002, scatter=0.02)  # residuals ≈ 10 sd
    capsys.readouterr()
    assert _calibrate(path, tmp_path / "cal", "--no-loo") == 0
    out = " ".join(capsys.readouterr().out.split())
    record = json.loads((tmp_path / "cal" / "calibration.json").read_text(encoding="utf-8"))
    chi2 = record["reduced_chi2"]
    assert chi2 > 10
    assert f"the fit is poor: reduced χ² {chi2:.3g}" in out
    assert "ok, poor fit" in out  # the parameter's status says it too (short: 80 columns)
    assert record["poor_fit"].startswith("reduced χ²")
    from racketdyn.report import write_report

    page = write_report(tmp_path / "cal").read_text(encoding="utf-8")
    assert '<p class="warn">The fit is poor: reduced χ²' in page


def test_a_good_fit_is_not_called_poor(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _measured(tmp_path, sd=0.01, scatter=0.01)
    capsys.readouterr()
    assert _calibrate(path, tmp_path / "cal", "--no-loo") == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "poor" not in out
    record = json.loads((tmp_path / "cal" / "calibration.json").read_text(encoding="utf-8"))
    assert record["poor_fit"] is None


@pytest.mark.slow
def test_the_table_fits_80_columns_with_whole_names(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """At 80 columns the parameter column cut ``hand_stiffness_n_per_m`` to
    ``hand_stiffness_n_pe…`` (the name a user types into --fit) and the status cell wrapped a
    not-identifiable reason over three lines (issue 27, "console wrapping")."""
    monkeypatch.setenv("COLUMNS", "80")
    path = _measured(tmp_path, sd=0.01, scatter=0.01)
    capsys.readouterr()
    fit = "e_bg,first_bending_hz,hand_stiffness_n_per_m"
    argv = ["calibrate", str(path), "--model", "approx", "--fit", fit, "--no-loo"]
    assert main([*argv, "--out", str(tmp_path / "cal")]) == 0
    out = capsys.readouterr().out
    table = [line for line in out.splitlines() if line.startswith(("│", "┃"))]
    assert all(len(line) <= 80 for line in table)
    rows = [line for line in table if "hand_stiffness" in line]
    assert len(rows) == 1
    assert "hand_stiffness_n_per_m" in rows[0]
    assert all(line.count("│") == 6 for line in table if line.startswith("│"))  # one line a row
    words = " ".join(out.split())
    assert "hand_stiffness_n_per_m: not identifiable: the data do not change with it" in words
