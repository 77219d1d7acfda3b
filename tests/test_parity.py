"""Measured against predicted with the measured standard deviations and the outliers named.

A lab that calibrates wants to see, on one figure, how far each row misses in its own scatter
and which rows miss most: ``validate``'s and ``calibrate``'s parity figures draw the measured
standard deviations as error bars and name the rows whose standardised residual is beyond ±3
(:func:`racketdyn.impact.measured.standardised_residuals`); the z values are in the CSVs and
the console names the rows.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.collections import LineCollection

from racketdyn.ball import Ball
from racketdyn.cli import main
from racketdyn.impact.calibration import apply, simulate_measurements
from racketdyn.impact.measured import (
    OUTLIER_LIMIT,
    ModelInputs,
    outlier_labels,
    outlier_rank,
    outliers,
    standardised_residuals,
)
from racketdyn.io.measured import MeasuredRebound
from racketdyn.io.racket_file import default_racket

FACE = [(0.45, 0.0), (0.50, 0.0), (0.55, 0.0), (0.60, 0.0), (0.50, 0.06), (0.55, -0.06)]


def _rows(ratio: list[float], sd: list[float] | None, labels: list[str]) -> MeasuredRebound:
    n = len(ratio)
    return MeasuredRebound(
        locations=np.tile([0.5, 0.0], (n, 1)),
        ball_speed=np.full(n, 20.0),
        racket_speed=np.zeros(n),
        support=("free",) * n,
        rebound_ratio=np.array(ratio),
        rebound_ratio_sd=None if sd is None else np.array(sd),
        labels=tuple(labels),
        lines=tuple(range(2, n + 2)),
    )


def test_with_measured_sd_the_residual_is_counted_in_it() -> None:
    rows = _rows([0.40, 0.40, 0.40], [0.01, 0.02, 0.0], ["A", "B", "C"])
    z = standardised_residuals(rows, np.array([0.43, 0.39, np.nan]))
    # 0.03 / 0.01 and −0.01 / 0.02; no number where the prediction is NaN
    np.testing.assert_allclose(z[:2], [3.0, -0.5])
    assert np.isnan(z[2])


def test_without_sd_an_odd_row_stands_out_of_the_others_pattern() -> None:
    n = 400
    rng = np.random.default_rng(7)
    residual = rng.normal(0.02, 0.005, n)  # a model 0.02 high throughout, 0.005 of scatter
    residual = np.clip(residual, 0.02 - 0.0125, 0.02 + 0.0125)  # the others within 2.5 scatters
    residual[11] = 0.02 + 0.05  # one row 10 scatters off
    rows = _rows([0.4] * n, None, [f"P{i}" for i in range(n)])
    z = standardised_residuals(rows, 0.4 + residual)
    assert outlier_labels(rows, z) == ("P11",)
    # the bias is not an outlier (the median is taken out) and the spread is the scatter's:
    # the MAD's estimate of a normal sd has a relative sd of ≈ 1.17/√n = 6 % at n = 400
    assert z[11] == pytest.approx(10.0, rel=0.2)


def test_no_spread_no_number() -> None:
    rows = _rows([0.4, 0.4], None, ["A", "B"])
    assert np.all(np.isnan(standardised_residuals(rows, np.array([0.41, 0.45]))))
    assert not np.any(outliers(np.array([np.nan, 5.0, -2.0]))[[0, 2]])


def test_outliers_are_named_worst_first_with_their_row_when_a_point_repeats() -> None:
    rows = _rows([0.4] * 4, [0.01] * 4, ["C", "C", "D", "E"])
    z = standardised_residuals(rows, np.array([0.45, 0.36, 0.46, 0.41]))
    assert outlier_labels(rows, z) == ("D", "C (row 1)", "C (row 2)")


def test_the_parity_figure_draws_the_sd_and_names_the_outliers() -> None:
    from racketdyn.plotting.validate import figure_validation_parity

    rows = _rows([0.40, 0.35, 0.30], [0.01, 0.02, 0.01], ["A", "B", "C"])
    predicted = {"transient": np.array([0.41, 0.36, 0.36])}
    rank = {"transient": outlier_rank(standardised_residuals(rows, predicted["transient"]))}
    figure = figure_validation_parity(rows, predicted, rank)
    try:
        ax = figure.axes[0]
        bars = [c for c in ax.collections if isinstance(c, LineCollection)]
        assert len(bars) == 1
        widths = sorted(float(abs(s[1][0] - s[0][0])) / 2 for s in bars[0].get_segments())
        np.testing.assert_allclose(widths, [0.01, 0.01, 0.02])
        assert [t.get_text() for t in ax.texts] == ["C"]  # 0.06 / 0.01 = 6 sd
        legend = [t.get_text() for t in ax.get_legend().get_texts()]
        assert "transient simulation (1 beyond ±3σ)" in legend
        assert "± 1 standard deviation" in ax.get_xlabel()
    finally:
        plt.close(figure)


def _measured(tmp_path: Path) -> Path:
    """A ball-cannon table of the built-in racket (approximate method, e_BG 0.78), sd 0.005,
    its fourth row 0.05 off (ten of its standard deviations)."""
    truth = apply(ModelInputs(default_racket(), Ball()), {"e_bg": 0.78})
    measured = simulate_measurements(truth, FACE, 20.0, sd=0.0, method="approx")
    lines = ["point,x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio,rebound_ratio_sd"]
    for i in range(len(measured)):
        x, y = measured.locations[i]
        ratio = float(measured.rebound_ratio[i]) + (0.05 if i == 3 else 0.0)
        lines.append(f"P{i + 1},{x},{y},20,0,free,{ratio!r},0.005")
    path = tmp_path / "measured.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_calibrate_draws_before_and_after_and_names_the_row_that_misses(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = _measured(tmp_path)
    out = tmp_path / "cal"
    argv = ["calibrate", str(path), "--model", "approx", "--fit", "e_bg", "--no-loo"]
    assert main([*argv, "--holdout", "6", "--out", str(out)]) == 0
    said = " ".join(capsys.readouterr().out.split())
    assert "beyond ±3 standard deviations after: P4 (z_after in calibration_rows.csv)" in said
    with (out / "calibration_rows.csv").open(encoding="utf-8") as f:
        table = list(csv.DictReader(f))
    z = [float(r["z_after"]) for r in table]
    assert [r["measured_sd"] for r in table] == ["0.005"] * 6
    assert abs(z[3]) > OUTLIER_LIMIT
    assert max(abs(v) for k, v in enumerate(z) if k != 3) < OUTLIER_LIMIT
    run = json.loads((out / "run.json").read_text(encoding="utf-8"))
    assert "calibration_parity.png" in run["outputs"]
    assert (out / "calibration_parity.png").stat().st_size > 0

    from racketdyn.plotting.registry import draw
    from racketdyn.workflows.figure_data import read_step_data

    figure = draw("calibration_parity", read_step_data(out))
    try:
        ax = figure.axes[0]
        assert [t.get_text() for t in ax.texts] == ["P4"]
        legend = [t.get_text() for t in ax.get_legend().get_texts()]
        assert legend == [
            "before calibration",
            "after calibration (1 beyond ±3σ)",
            "1:1",
            "held out of the fit",
        ]
    finally:
        plt.close(figure)


def test_calibrate_without_figures_writes_none(tmp_path: Path) -> None:
    path = _measured(tmp_path)
    argv = ["calibrate", str(path), "--model", "approx", "--fit", "e_bg", "--no-loo"]
    assert main([*argv, "--no-figures", "--out", str(tmp_path / "cal")]) == 0
    assert not list((tmp_path / "cal").glob("*.png"))
