"""A run folder holds one whole run (issue 13, "Output folders"): nothing stale, nothing mixed,
nothing half-written; `workflows.run.run_step` is the one place that does it."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from racketdyn.cli import main
from racketdyn.workflows.run import LOCK_NAME, STAGING_PREFIX

QUICK = ["--grid", "3", "--speed", "20", "--no-figures"]


def _files(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir()) if p.is_file()}


@pytest.mark.slow
def test_a_second_run_leaves_only_its_own_files(tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert main(["predict", *QUICK, "--model", "both", "--out", str(out)]) == 0
    assert (out / "impact_transient.csv").exists()
    (out / "my_notes.txt").write_text("mine", encoding="utf-8")
    assert main(["predict", *QUICK, "--out", str(out)]) == 0
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    names = {p.name for p in out.iterdir()}
    # the first run's transient table and comparison are gone; the user's file stays
    assert names == {*record["outputs"], "my_notes.txt"}
    assert not (out / "impact_transient.csv").exists()
    assert not (out / "comparison.csv").exists()


def test_a_second_run_removes_the_report_of_the_first(tmp_path: Path) -> None:
    """New-user trial (issue 13): ``report`` on a swing folder, then ``swing --no-figures``
    into it again: the old report.html stayed, its figures those of the first run (no longer
    in the folder).  The page is the earlier run's output too: a new run removes it."""
    out = tmp_path / "out"
    assert main(["predict", *QUICK, "--out", str(out)]) == 0
    assert main(["report", str(out)]) == 0
    assert (out / "report.html").exists()
    assert main(["predict", *QUICK, "--speed", "25", "--out", str(out)]) == 0
    assert not (out / "report.html").exists()


def test_a_failing_run_leaves_the_folder_as_it_was(tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert main(["predict", *QUICK, "--out", str(out)]) == 0
    before = _files(out)
    points = tmp_path / "points.csv"
    points.write_text("x_m,y_m\n0.5,0.0\n0.1,0.0\n", encoding="utf-8")  # 0.1 m: off the face
    assert main(["predict", "--no-figures", "--points", str(points), "--out", str(out)]) == 2
    assert _files(out) == before
    assert [p.name for p in out.iterdir() if p.name.startswith(".")] == []


def test_a_failing_run_into_a_new_folder_leaves_no_folder(tmp_path: Path) -> None:
    out = tmp_path / "new"
    points = tmp_path / "points.csv"
    points.write_text("x_m,y_m\n0.1,0.0\n", encoding="utf-8")
    assert main(["predict", "--no-figures", "--points", str(points), "--out", str(out)]) == 2
    assert not out.exists()


def test_a_folder_being_written_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / LOCK_NAME).write_text(str(os.getpid()), encoding="utf-8")  # a live run holds it
    assert main(["predict", *QUICK, "--out", str(out)]) == 2
    (line,) = capsys.readouterr().err.splitlines()
    assert "another racketdyn run" in line
    assert str(out) in line
    assert not (out / "impact.csv").exists()


def test_the_lock_of_an_ended_run_is_taken_over(tmp_path: Path) -> None:
    ended = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout.strip()
    out = tmp_path / "out"
    (out / f"{STAGING_PREFIX}{ended}").mkdir(parents=True)
    (out / f"{STAGING_PREFIX}{ended}" / "impact.csv").write_text("half", encoding="utf-8")
    (out / LOCK_NAME).write_text(ended, encoding="utf-8")
    assert main(["predict", *QUICK, "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["figures.nc", "impact.csv", "run.json"]


@pytest.mark.slow
def test_the_rig_tests_both_supports_into_one_folder(tmp_path: Path) -> None:
    out = tmp_path / "rig"
    argv = ["rig", "--support", "free,hand", "--averages", "1", "--out", str(out)]
    assert main(argv) == 0
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    assert record["supports"] == ["free", "hand"]
    assert set(record["outputs"]) == {
        "hammer_free.uff",
        "modal_truth_free.json",
        "hammer_hand.uff",
        "modal_truth_hand.json",
        "run.json",
    }
    assert {p.name for p in out.iterdir()} == set(record["outputs"])


@pytest.mark.slow
def test_a_folder_holding_another_steps_run_is_refused_and_kept(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # trial of 2026-11-23: `predict --out` on a copy of a rig folder deleted the rig's hammer
    # UFF files and modal truth (its run.json listed them as the previous run's outputs)
    out = tmp_path / "rig"
    assert main(["rig", "--averages", "1", "--out", str(out)]) == 0
    before = _files(out)
    capsys.readouterr()
    assert main(["predict", *QUICK, "--out", str(out)]) == 2
    message = capsys.readouterr().err.strip().splitlines()
    assert len(message) == 1
    assert "racketdyn rig" in message[0]
    assert "--out" in message[0]
    assert _files(out) == before


def test_a_step_re_run_under_a_report_says_the_report_is_old(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    """A step re-run inside a report's folder (as ``predict --out demo/predict`` after
    ``demo``) leaves that report telling the old run: the command says so and how to remake
    it, and leaves the report alone (it is the user's)."""
    report = tmp_path / "report.html"
    report.write_text("<html>an earlier report</html>", encoding="utf-8")
    argv = ["predict", "--grid", "3", "--speed", "10", "--no-figures", "--out"]
    assert main([*argv, str(tmp_path / "predict")]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert f"{report} still shows this step's previous run" in printed
    assert f"racketdyn report {tmp_path} makes it again" in printed
    assert report.read_text(encoding="utf-8") == "<html>an earlier report</html>"
    # a folder with no report above says nothing of one
    assert main([*argv, str(tmp_path / "predict" / "inner")]) == 0
    assert "still shows" not in capsys.readouterr().out


def test_a_new_folder_beside_a_report_is_not_said_to_be_in_it(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    """A new user's report, made with ``--steps`` over their step folders, was then said to
    "still show this step's previous run" after every new folder beside it (a sweep, another
    predict) — folders it never showed — and the advised ``racketdyn report .`` failed (two
    predict runs there).  The page now records the folders it shows: a new folder says
    nothing, a shown one says so with the ``--steps`` the page was made with."""
    from racketdyn.report import write_report

    argv = ["predict", "--grid", "3", "--speed", "10", "--no-figures", "--out"]
    assert main([*argv, str(tmp_path / "first")]) == 0
    write_report(tmp_path, steps=[("predict", "first")])
    capsys.readouterr()
    assert main([*argv, str(tmp_path / "second")]) == 0  # never in the page
    assert "still shows" not in capsys.readouterr().out
    assert main([*argv, str(tmp_path / "first")]) == 0  # the page's own predict folder
    printed = " ".join(capsys.readouterr().out.split())
    assert "still shows this step's previous run" in printed
    assert f"racketdyn report {tmp_path} --steps predict=first makes it again" in printed
