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
    assert (out / "sweep.zarr" / "zarr.json").is_file()
    assert (out / "run.json").is_file()


@pytest.mark.slow
def test_workers_on_a_small_sweep(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A pool gives the serial numbers (while a forkserver's pool starts, a design computed
    here, one in the pool); on a sweep this small the command says it does not pay, and where
    the time went."""
    import json

    (tmp_path / "spec.toml").write_text(SPEC)
    runs = {}
    for engine in (["--serial"], ["--workers", "1"]):
        out = tmp_path / engine[0].strip("-")
        argv = ["sweep", str(tmp_path / "spec.toml"), *engine, "--no-figures", "--out", str(out)]
        assert main(argv) == 0
        from racketdyn.sweep import open_sweep

        with open_sweep(out) as ds:
            runs[engine[0]] = ds.load()
        printed = " ".join(capsys.readouterr().out.split())
        assert "time: start" in printed
        assert "finishing the store" in printed
        assert ("--serial is as fast or faster" in printed) == (engine[0] == "--workers")
        if engine[0] == "--workers":
            # a forked pool is up at once; while a forkserver's pool starts, one design went
            # to it and one ran here (this process may run threads of earlier tests)
            record = json.loads((out / "run.json").read_text())
            forked = record["worker_start_method"] == "fork"
            assert record["ran_in_main_process"] == (0 if forked else 1)
    for name in runs["--serial"].data_vars:
        assert runs["--serial"][name].values.tobytes() == runs["--workers"][name].values.tobytes()


def test_bad_spec_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "spec.toml").write_text(SPEC.replace("[226.0, 266.0]", '"high"'))
    assert main(["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert "tension_n" in err[0]


HAND_SPEC = """
name = "arm"
[impacts]
grid = 3
ball_speeds_mps = [20.0]
method = "transient"
[variables]
support = ["pinned", "hand"]
hand.arm_mass_kg = [0.5, 1.5]
"""


@pytest.mark.usefixtures("strings_only")  # the hand's machinery at every point of a 3 × 3 grid
def test_transient_sweep_with_the_hand(tmp_path: Path) -> None:
    import json

    (tmp_path / "spec.toml").write_text(HAND_SPEC)
    out = tmp_path / "out"
    argv = ["sweep", str(tmp_path / "spec.toml"), "--serial", "--no-figures", "--out", str(out)]
    assert main(argv) == 0
    from racketdyn.sweep import open_sweep

    with open_sweep(out) as ds:
        assert ds.attrs["method"] == "transient"
        assert list(ds["support"].values) == ["pinned", "hand"]
        assert list(ds["hand.arm_mass_kg"].values) == [0.5, 1.5]
        assert int((ds["status"] != 0).sum()) == 0
    record = json.loads((out / "run.json").read_text())
    assert record["status_counts"]["ok"] == record["impacts"]


def test_hand_with_the_approximate_method_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "spec.toml").write_text(HAND_SPEC.replace('"transient"', '"approximate"'))
    assert main(["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert "'hand' needs [impacts].method = 'transient'" in err[0]


def test_notes_keep_their_brackets_and_a_resumed_run_stops_no_engine(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The coarse-grid note names "[impacts] grid", which the console took for a style and
    dropped ("give a finer  grid"); a run that resumed every design printed "engine shutdown
    0.0 s" although no engine ran (a trial of 2026-11-26)."""
    (tmp_path / "spec.toml").write_text(SPEC)
    argv = ["sweep", str(tmp_path / "spec.toml"), "--workers", "1", "--no-figures"]
    out = tmp_path / "out"
    assert main([*argv, "--out", str(out)]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "give a finer [impacts] grid" in printed
    assert "engine shutdown" in printed
    assert main([*argv, "--out", str(out)]) == 0  # the same folder again: all resumed
    printed = " ".join(capsys.readouterr().out.split())
    assert "2 resumed" in printed
    assert "engine shutdown" not in printed


@pytest.mark.slow
def test_a_changed_spec_in_the_same_folder_leaves_no_figure_of_the_old_one(
    tmp_path: Path,
) -> None:
    """A second spec run into the folder of the first kept the first's summary figure of a
    variable it does not have (``summary_tension_n.png`` beside the new spec's results: a
    new-user trial of 2026-11-26); the files a user put there stay."""
    (tmp_path / "tension.toml").write_text(SPEC)
    (tmp_path / "ebg.toml").write_text(
        SPEC.replace("tension_n = [226.0, 266.0]", "e_bg = [0.8, 0.86]")
    )
    out = tmp_path / "out"
    assert main(["sweep", str(tmp_path / "tension.toml"), "--serial", "--out", str(out)]) == 0
    assert (out / "summary_tension_n.png").is_file()
    (out / "my notes.txt").write_text("mine")
    assert main(["sweep", str(tmp_path / "ebg.toml"), "--serial", "--out", str(out)]) == 0
    assert (out / "summary_e_bg.png").is_file()
    assert not (out / "summary_tension_n.png").exists()
    assert (out / "my notes.txt").read_text() == "mine"


@pytest.mark.parametrize("option", ["--workers", "--dask-local"])
def test_a_worker_count_below_one_is_one_line_naming_the_option(
    option: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``--dask-local 0`` printed the study's size and the "--serial is faster" advice, then
    "workers must be a whole number" — without the option's name — after starting a
    forkserver for nothing (a new-user trial, 2026-11-26)."""
    (tmp_path / "spec.toml").write_text(SPEC)
    argv = ["sweep", str(tmp_path / "spec.toml"), option, "0", "--out", str(tmp_path / "o")]
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    err = captured.err.strip().splitlines()
    assert len(err) == 1
    assert f"{option} must be a whole number of at least 1 (got 0)" in err[0]
    assert not (tmp_path / "o").exists()


def test_another_command_into_a_sweep_folder_is_refused_and_the_sweep_kept(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``racketdyn predict --out STUDY`` on a sweep's folder deleted sweep.nc, summary.csv,
    the figures and every part (the sweep's run.json named no command, so the folder was
    taken for a predict run's): a new-user trial, 2026-11-26.  And a sweep into another
    command's folder must not remove that run's files."""
    (tmp_path / "spec.toml").write_text(SPEC)
    study = tmp_path / "study"
    assert main(["sweep", str(tmp_path / "spec.toml"), "--serial", "--out", str(study)]) == 0
    kept = sorted(p.name for p in study.rglob("*"))
    capsys.readouterr()
    assert main(["predict", "--grid", "3", "--no-figures", "--out", str(study)]) == 2
    assert "holds a `racketdyn sweep` run" in capsys.readouterr().err
    assert sorted(p.name for p in study.rglob("*")) == kept
    predicted = tmp_path / "predicted"
    assert main(["predict", "--grid", "3", "--no-figures", "--out", str(predicted)]) == 0
    before = sorted(p.name for p in predicted.rglob("*"))
    sweep = ["sweep", str(tmp_path / "spec.toml"), "--serial", "--out", str(predicted)]
    assert main(sweep) == 2
    assert "holds a `racketdyn predict` run" in capsys.readouterr().err
    assert sorted(p.name for p in predicted.rglob("*")) == before


def test_a_sweep_folder_without_a_command_is_refused_too(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A folder written by ``run_sweep`` from Python, or by the command before its run.json
    named it (the trial above), records no command: ``predict --out`` took it for a predict
    run's and deleted sweep.nc and every part.  The sweep's run.json ``format`` says what it
    is."""
    import json

    (tmp_path / "spec.toml").write_text(SPEC)
    study = tmp_path / "study"
    assert main(["sweep", str(tmp_path / "spec.toml"), "--serial", "--out", str(study)]) == 0
    record = json.loads((study / "run.json").read_text(encoding="utf-8"))
    record.pop("command", None)  # as run_sweep from Python, or an older sweep, wrote it
    (study / "run.json").write_text(json.dumps(record), encoding="utf-8")
    kept = sorted(p.name for p in study.rglob("*"))
    capsys.readouterr()
    assert main(["predict", "--grid", "3", "--no-figures", "--out", str(study)]) == 2
    assert "holds a `racketdyn sweep` run" in capsys.readouterr().err
    assert sorted(p.name for p in study.rglob("*")) == kept


def test_a_second_sweep_into_a_folder_in_use_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Two sweeps of different specs run at once into one folder both ended with exit 0,
    and the folder's sweep.nc had 7 of 27 designs NaN as "task failed" (their parts
    overwritten by the other sweep's) with ``n_failed`` 0 (a new-user trial, 2026-11-26): the
    sweep took no folder lock, unlike every other command."""
    import os

    from racketdyn.workflows.run import LOCK_NAME

    (tmp_path / "spec.toml").write_text(SPEC)
    out = tmp_path / "out"
    out.mkdir()
    (out / LOCK_NAME).write_text(str(os.getppid()))  # a live process holds the folder
    argv = ["sweep", str(tmp_path / "spec.toml"), "--serial", "--no-figures", "--out", str(out)]
    assert main(argv) == 2
    assert f"another racketdyn run (process {os.getppid()}) is writing into it" in (
        capsys.readouterr().err
    )
    assert not (out / "sweep.zarr").exists()
    (out / LOCK_NAME).unlink()
    assert main(argv) == 0
    assert not (out / LOCK_NAME).exists()  # released at the end


def test_dask_engines_without_distributed_are_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """``racketdyn sweep --dask-local 2`` where dask.distributed is not installed (the README's
    plain ``pip install .``) ended in a ModuleNotFoundError traceback, before the engine's own
    message could say what to install (found 2026-11-26, third session, in a fresh venv)."""
    import sys

    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed: ImportError
    (tmp_path / "spec.toml").write_text(SPEC)
    for engine in (["--dask-local", "2"], ["--scheduler", "tcp://127.0.0.1:8786"]):
        argv = ["sweep", str(tmp_path / "spec.toml"), *engine, "--out", str(tmp_path / "o")]
        assert main(argv) == 2
        captured = capsys.readouterr()
        err = captured.err.strip().splitlines()
        assert len(err) == 1, captured.err
        assert "pip install 'racketdyn[dask]'" in err[0]
        assert engine[0] in err[0]
        assert not (tmp_path / "o").exists()


@pytest.mark.slow
def test_the_sweep_command_prints_bracketed_paths_whole(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """``racketdyn sweep --out 'study[v1]'`` printed "→ study" and "wrote study/sweep.nc" (rich
    read "[v1]" as markup) while it wrote into ``study[v1]``: the other commands were mended
    in the same session, the sweep command was left (found 2026-11-26, closing review)."""
    monkeypatch.setenv("COLUMNS", "400")  # one line a message: the paths are long
    (tmp_path / "spec.toml").write_text(SPEC)
    for out in (tmp_path / "study[v1]", tmp_path / "o[/b]"):
        assert main(["sweep", str(tmp_path / "spec.toml"), "--serial", "--out", str(out)]) == 0
        printed = capsys.readouterr().out
        assert f"→ {out}\n" in printed
        assert f"wrote {out / 'sweep.zarr'}\n" in printed
