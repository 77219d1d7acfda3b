"""Issue 24's leftovers: ``--uncertainty none``, Sobol' indices on the valid samples."""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from racketdyn.cli import main


def _racket_with_tables(tmp_path: Path) -> Path:
    text = resources.files("racketdyn.data").joinpath("kawazoe_2002.toml").read_text("utf-8")
    racket = tmp_path / "r.toml"
    racket.write_text(text + "\n[uncertainty.e_bg]\nrange = [0.80, 0.88]\n", encoding="utf-8")
    return racket


def test_uncertainty_none_switches_off_a_racket_file_s_tables_for_one_run(
    tmp_path: Path,
) -> None:
    racket = _racket_with_tables(tmp_path)
    out = tmp_path / "run"
    argv = ["predict", "--racket", str(racket), "--grid", "3", "--speed", "20"]
    argv += ["--support", "free", "--no-figures", "--uncertainty", "none", "--out", str(out)]
    assert main(argv) == 0
    assert "rebound_ratio_p05" not in pd.read_csv(out / "impact.csv")
    assert not (out / "uncertainty.nc").exists()
    assert json.loads((out / "run.json").read_text())["uncertainty"] is None


def test_samples_with_uncertainty_none_is_refused_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    racket = _racket_with_tables(tmp_path)
    argv = ["predict", "--racket", str(racket), "--grid", "3", "--speed", "20", "--no-figures"]
    argv += ["--uncertainty", "none", "--samples", "16", "--out", str(tmp_path / "run")]
    assert main(argv) != 0
    assert "--uncertainty none" in capsys.readouterr().err


def test_sobol_indices_are_given_on_the_valid_samples_where_90_percent_are_valid() -> None:
    """Before: a point with a single sample beyond the method had no indices (NaN).  Now the
    Saltelli estimators run on the base samples whose every evaluation is valid, where those
    are 90 % or more, and the share is said (``valid_share``, ``samples_valid`` in the rows)."""
    from racketdyn.ball import Ball
    from racketdyn.impact.measured import ModelInputs
    from racketdyn.impact.uncertainty import Spread, Uncertainty, sensitivity
    from racketdyn.io.racket_file import default_racket

    racket = default_racket()
    x, y = racket.head.centre_x_m, racket.head.centre_y_m
    points = {"centre": (x, y), "near the edge": (x, y + 0.080), "frame": (x, y + 0.090)}
    spreads = (Spread("e_bg", bounds=(0.80, 0.88)), Spread("location_m", sd=0.004))
    found = sensitivity(
        ModelInputs(racket, Ball()), points, 20.0, Uncertainty(spreads, seed=1), n=128
    )
    assert found.valid_share[0] == 1.0
    assert 0.9 <= found.valid_share[1] < 1.0
    assert found.valid_share[2] < 0.9
    assert np.all(np.isfinite(found.total_order[:, :2]))
    assert np.all(np.isnan(found.total_order[:, 2]))
    assert found.dominant(1) != ""
    rows = pd.DataFrame(found.rows())
    near = rows[rows["point"] == "near the edge"]
    assert set(near["samples_valid"]) == {found.valid_share[1]}


@pytest.mark.slow
def test_predict_runs_the_transient_samples_on_worker_processes(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    racket = _racket_with_tables(tmp_path)
    argv = ["predict", "--racket", str(racket), "--grid", "3", "--speed", "20", "--no-figures"]
    argv += ["--support", "free", "--model", "transient", "--samples", "8"]
    assert main([*argv, "--workers", "2", "--out", str(tmp_path / "pool")]) == 0
    assert main([*argv, "--out", str(tmp_path / "here")]) == 0
    pooled, here = (pd.read_csv(tmp_path / run / "impact.csv") for run in ("pool", "here"))
    np.testing.assert_allclose(pooled["rebound_ratio_p95"], here["rebound_ratio_p95"])
    argv = ["predict", "--grid", "3", "--speed", "20", "--no-figures", "--workers", "2"]
    assert main([*argv, "--out", str(tmp_path / "none")]) != 0
    assert "--workers" in capsys.readouterr().err


@pytest.mark.slow
def test_swing_and_validate_run_their_samples_on_worker_processes(tmp_path: Path) -> None:
    """``--workers N`` is predict's, swing's and validate's: the same bands as in one process."""
    spec = tmp_path / "u.toml"
    spec.write_text("[e_bg]\nrange = [0.80, 0.88]\n[location_m]\nsd = 0.005\n")
    swing = ["swing", "--uncertainty", str(spec), "--samples", "8", "--grid", "3", "--no-figures"]
    measured = tmp_path / "measured.csv"
    measured.write_text(
        "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio\n"
        "0.50,0.0,20,0,free,0.40\n0.55,0.01,20,0,free,0.35\n"
    )
    validate = ["validate", str(measured), "--uncertainty", str(spec), "--samples", "8"]
    validate += ["--no-figures"]
    for argv, table, columns in (
        (swing, "swing.csv", ["rebound_speed_mps_p95"]),
        (validate, "validation.csv", ["p95_approx", "p95_transient"]),
    ):
        runs = (tmp_path / f"{argv[0]}_here", tmp_path / f"{argv[0]}_pool")
        assert main([*argv, "--out", str(runs[0])]) == 0
        assert main([*argv, "--workers", "2", "--out", str(runs[1])]) == 0
        here, pooled = (pd.read_csv(run / table) for run in runs)
        np.testing.assert_allclose(pooled[columns], here[columns], rtol=1e-12)
