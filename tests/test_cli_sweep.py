"""`racketdyn sweep` end to end (serial) and a bad spec."""

from __future__ import annotations

from pathlib import Path

import pytest

from racketdyn.cli import main

SPEC = """
name = "tension"
racket = "builtin"
[impacts]
grid = 3
ball_speeds_mps = [20.0]
[variables]
tension_n = [226.0, 266.0]
"""


def test_sweep_command(tmp_path: Path) -> None:
    (tmp_path / "spec.toml").write_text(SPEC)
    out = tmp_path / "out"
    assert (
        main(["sweep", str(tmp_path / "spec.toml"), "--serial", "--no-figures", "--out", str(out)])
        == 0
    )
    assert (out / "sweep.nc").stat().st_size > 1000
    assert (out / "run.json").is_file()


def test_bad_spec_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "spec.toml").write_text(SPEC.replace("[226.0, 266.0]", '"high"'))
    assert main(["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert "tension_n" in err[0]
