"""A lab's chain keeps its racket: a step reading another step's file takes the racket file
that run's run.json names (:func:`racketdyn.workflows.inputs.with_racket_of_run`).

New-user trial, eleventh session: ``rig --racket my_racket.toml`` then ``frf`` without
``--racket`` recorded the built-in racket, and ``report`` refused the folder ("its runs used 2
rackets").
"""

from __future__ import annotations

import dataclasses
import json
import logging
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from racketdyn.cli import main
from racketdyn.io import write_hammer_uff
from racketdyn.testing.records import Modes, records_for
from racketdyn.workflows.run import sha256

MODES = Modes(np.array([120.0, 330.0]), np.array([0.03, 0.02]), np.array([[6.0, 4.0], [-3.0, 2.5]]))


def _rig_like_run(folder: Path) -> tuple[Path, Path]:
    """A folder as a rig run leaves it: hammer records and a run.json naming a racket file."""
    folder.mkdir()
    racket = folder.parent / "my_racket.toml"
    text = resources.files("racketdyn.data").joinpath("kawazoe_2002.toml").read_text("utf-8")
    racket.write_text(text.replace("Kawazoe", "My lab's", 1), encoding="utf-8")
    records = dataclasses.replace(
        records_for(MODES, pulse_s=3e-3, n_averages=2, second_hit=None),
        locations=np.array([[0.505, 0.0], [0.55, 0.03]]),
        reference_location=(0.505, 0.0),
    )
    tests = folder / "hammer_free.uff"
    write_hammer_uff(records, tests)
    record = {"command": ["racketdyn", "rig"], "racket_file": str(racket.resolve()),
              "racket_file_sha256": sha256(racket)}  # fmt: skip
    (folder / "run.json").write_text(json.dumps(record), encoding="utf-8")
    return racket, tests


@pytest.mark.slow
def test_frf_and_identify_take_the_racket_the_rig_ran(tmp_path: Path) -> None:
    racket, tests = _rig_like_run(tmp_path / "lab")
    assert main(["frf", str(tests), "--exp-window", "0.1", "--out", str(tmp_path / "frf")]) == 0
    frf = json.loads((tmp_path / "frf" / "run.json").read_text(encoding="utf-8"))
    assert frf["racket_file"] == str(racket.resolve())
    assert frf["racket_from_run"] == str((tmp_path / "lab" / "run.json").resolve())
    frfs = tmp_path / "frf" / "frfs.uff"
    assert main(["identify", str(frfs), "--out", str(tmp_path / "id")]) == 0
    found = json.loads((tmp_path / "id" / "run.json").read_text(encoding="utf-8"))
    assert found["racket_file"] == str(racket.resolve())


@pytest.mark.slow
def test_a_racket_given_wins_and_a_changed_file_is_not_taken(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    racket, tests = _rig_like_run(tmp_path / "lab")
    other = tmp_path / "other.toml"
    other.write_text(racket.read_text(encoding="utf-8"), encoding="utf-8")
    args = ["frf", str(tests), "--exp-window", "0.1", "--racket", str(other)]
    assert main([*args, "--out", str(tmp_path / "given")]) == 0
    given = json.loads((tmp_path / "given" / "run.json").read_text(encoding="utf-8"))
    assert given["racket_file"] == str(other.resolve())
    assert "racket_from_run" not in given
    racket.write_text(racket.read_text(encoding="utf-8") + "\n# edited\n", encoding="utf-8")
    with caplog.at_level(logging.WARNING):
        assert main(["frf", str(tests), "--exp-window", "0.1", "--out", str(tmp_path / "o")]) == 0
    record = json.loads((tmp_path / "o" / "run.json").read_text(encoding="utf-8"))
    assert record["racket_file"].startswith("built-in")
    assert "racket_from_run" not in record
    assert "has changed since" in caplog.text
