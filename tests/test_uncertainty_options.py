"""Issue 24's leftovers: ``--uncertainty none``, Sobol' indices on the valid samples."""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

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
