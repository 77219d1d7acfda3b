"""Sweeps that meet faults: a worker that dies or hangs, Ctrl-C, the main process killed.

Each fault is made for real: a pool worker ends with ``os._exit`` or sleeps for an hour inside a
task (``tests/sweep_faults.py``, shipped to the workers by name), and a sweep run as a
subprocess in its own session gets SIGINT on its whole process group (as a terminal sends
Ctrl-C) or SIGKILL on its main process.
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from concurrent.futures import Executor, Future
from pathlib import Path
from typing import Any

import pytest
import xarray as xr

import racketdyn as rd
import racketdyn.sweep.task as sweep_task
import sweep_faults
from racketdyn.sweep import SerialExecutor, SweepSpec, TaskOptions, make_executor, run_sweep
from terminal import popen_as_from_a_terminal

SCRIPT = Path(sweep_faults.__file__)


class Sabotaged(Executor):
    """An executor whose tasks go through a fault (``fault(*fault_args, fn, *args)``)."""

    def __init__(self, inner: Executor, fault: Callable[..., Any], *fault_args: Any) -> None:
        self.inner, self.fault, self.fault_args = inner, fault, fault_args

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Future[Any]:
        return self.inner.submit(self.fault, *self.fault_args, fn, *args, **kwargs)

    def __getattr__(self, name: str) -> Any:
        return getattr(self.inner, name)


assert_same_bits = sweep_faults.assert_same_bits


# --- a worker that dies ----------------------------------------------------------------------
@pytest.mark.slow
def test_a_dead_worker_costs_only_its_tasks(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    marker = str(tmp_path / "died")
    with make_executor("process", 2) as pool:
        executor = Sabotaged(pool, sweep_faults.die_once, marker, "design-00002")
        result = run_sweep(small_spec, tmp_path / "out", executor, figures=None)
    assert Path(marker).exists()  # a worker did die
    assert result.attrs["n_failed"] == 0
    assert_same_bits(serial_result, result)
    record = json.loads((tmp_path / "out" / "run.json").read_text())
    assert record["pools_replaced"] >= 1
    assert record["ran"] == 6


@pytest.mark.slow
def test_a_task_that_always_kills_its_worker_fails_alone(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    with make_executor("process", 2) as pool:
        executor = Sabotaged(pool, sweep_faults.die_always, "design-00004")
        result = run_sweep(small_spec, tmp_path, executor, figures=None)
    failures = json.loads((tmp_path / "failures.json").read_text())
    assert [f["task_id"] for f in failures] == ["design-00004"]
    assert "worker process died" in failures[0]["error"]
    others = [0, 1, 2, 3, 5]
    for name in serial_result.data_vars:
        expected, actual = serial_result[name].isel(design=others), result[name].isel(design=others)
        assert expected.values.tobytes() == actual.values.tobytes(), name


# --- a worker that hangs ---------------------------------------------------------------------
@pytest.mark.parametrize("engine", ["process", "dask-local"])
@pytest.mark.slow
def test_a_hung_task_is_retried_elsewhere(
    engine: str, small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    marker = str(tmp_path / "hung")
    started = time.perf_counter()
    with make_executor(engine, 2) as inner:  # type: ignore[arg-type]
        executor = Sabotaged(inner, sweep_faults.hang_once, marker, "design-00001")
        result = run_sweep(
            small_spec,
            tmp_path / "out",
            executor,
            options=TaskOptions(task_timeout=3.0),
            figures=None,
        )
    assert Path(marker).exists()  # a task did hang
    assert time.perf_counter() - started < 120  # not the hour it slept
    assert result.attrs["n_failed"] == 0
    assert_same_bits(serial_result, result)
    record = json.loads((tmp_path / "out" / "run.json").read_text())
    assert record["timed_out"] == 1


def test_the_task_timeout_is_checked(small_spec: SweepSpec, tmp_path: Path) -> None:
    with pytest.raises(rd.InputError, match="task_timeout"):
        run_sweep(
            small_spec,
            tmp_path,
            SerialExecutor(),
            options=TaskOptions(task_timeout=-1.0),
            figures=None,
        )


# --- signals to a sweep run as a command -----------------------------------------------------
SLOW_SPEC = """
name = "slow"
[impacts]
grid = 3
ball_speeds_mps = [20.0]
method = "slow"
[variables]
e_bg = { start = 0.78, stop = 0.88, num = 16 }
"""


def _start(
    tmp_path: Path, engine: tuple[str, ...] = ("--workers", "2")
) -> tuple[subprocess.Popen[bytes], Path, list[str]]:
    """``racketdyn sweep`` on 2 workers in a session of its own, with tasks of 0.4 s each;
    its output in ``stdout.txt`` and ``stderr.txt`` (files: a pipe would stay open as long as
    any child process lives)."""
    spec = tmp_path / "slow.toml"
    spec.write_text(SLOW_SPEC, encoding="utf-8")
    out = tmp_path / "out"
    argv = ["sweep", str(spec), *engine, "--no-figures", "--out", str(out)]
    # a user's environment: not the variables an earlier Dask cluster of this test process
    # wrote into it (its nannies set their workers' variables in the parent's os.environ)
    env = {k: v for k, v in os.environ.items() if not k.startswith(("DASK_", "MALLOC_"))}
    env["PYTHONPATH"] = os.pathsep.join(sys.path)
    with (
        (tmp_path / "stdout.txt").open("wb") as stdout,
        (tmp_path / "stderr.txt").open("wb") as stderr,
    ):
        process = popen_as_from_a_terminal(
            [sys.executable, str(SCRIPT), *argv],
            stdout=stdout,
            stderr=stderr,
            env=env,
            start_new_session=True,
        )
    deadline = time.monotonic() + 120
    while len(sweep_faults.designs_done(out)) < 2:
        if process.poll() is not None or time.monotonic() > deadline:
            process.kill()
            process.wait()
            raise AssertionError(f"the sweep did not start: {_output(tmp_path)}")
        time.sleep(0.05)
    return process, out, argv


def _output(tmp_path: Path) -> tuple[str, str]:
    return tuple(  # type: ignore[return-value]
        (tmp_path / name).read_text(encoding="utf-8") for name in ("stdout.txt", "stderr.txt")
    )


def _alive_in_group(group: int) -> list[str]:
    """Processes of a process group that still run (zombies, waiting to be reaped, do not)."""
    alive = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            command = (entry / "cmdline").read_text().replace("\0", " ")
        except OSError:
            continue
        if int(fields[2]) == group and fields[0] != "Z":
            alive.append(f"{entry.name} {command[:80]}")
    return alive


def _wait_until_gone(group: int, seconds: float) -> list[str]:
    deadline = time.monotonic() + seconds
    while (alive := _alive_in_group(group)) and time.monotonic() < deadline:
        time.sleep(0.1)
    return alive


needs_proc = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")


@needs_proc
@pytest.mark.parametrize("engine", [("--workers", "2"), ("--dask-local", "2")])
@pytest.mark.slow
def test_ctrl_c_keeps_the_finished_parts_and_says_how_to_resume(
    engine: tuple[str, ...], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    process, out, argv = _start(tmp_path, engine)
    os.killpg(process.pid, signal.SIGINT)  # the whole group, as a terminal does
    process.wait(timeout=60)
    stdout, stderr = _output(tmp_path)
    assert process.returncode == 130, (stdout, stderr)
    assert "Traceback" not in stdout + stderr
    assert "KeyboardInterrupt" not in stdout + stderr
    assert not stderr.strip()  # workers say nothing either
    lines = [line for line in (stdout + stderr).splitlines() if "interrupted" in line]
    assert len(lines) == 1, stdout + stderr
    kept = len(sweep_faults.designs_done(out))
    assert 2 <= kept < 16
    assert f"{kept} of 16 designs" in lines[0]
    command = "racketdyn " + " ".join(argv)
    assert command in " ".join(stdout.split())  # the line may wrap on a narrow console
    assert not _wait_until_gone(process.pid, 10), "workers left running"
    # the resumed sweep computes the rest and equals one run straight through; here, with the
    # signal sent, the slow method need not wait (the same numbers: 11 s of the test's 17)
    monkeypatch.setitem(sweep_task.METHODS, "slow", sweep_faults.slow)
    monkeypatch.setattr(sweep_faults, "SLOW_TASK_S", 0.0)
    spec = rd.sweep.load_sweep_spec(tmp_path / "slow.toml")
    counted: list[str] = []
    resumed = run_sweep(
        spec,
        out,
        SerialExecutor(),
        figures=None,
        progress=lambda done, total: counted.append(f"{done}/{total}"),
    )
    assert counted[0] == f"{kept}/16"
    straight = run_sweep(spec, tmp_path / "straight", SerialExecutor(), figures=None)
    assert_same_bits(straight, resumed)


@needs_proc
@pytest.mark.parametrize("engine", [("--workers", "2"), ("--dask-local", "2")])
@pytest.mark.slow
def test_workers_exit_when_the_main_process_is_killed(
    engine: tuple[str, ...], tmp_path: Path
) -> None:
    process, _, _ = _start(tmp_path, engine)
    assert len(_alive_in_group(process.pid)) >= 3  # main and workers (forkserver, tracker)
    process.kill()
    process.wait(timeout=30)
    alive = _wait_until_gone(process.pid, 10)
    for line in alive:  # do not leave them behind for the next test
        os.kill(int(line.split()[0]), signal.SIGKILL)
    assert not alive, f"left running after the main process was killed: {alive}"


@needs_proc
@pytest.mark.slow
def test_a_killed_sweep_costs_only_the_designs_in_flight(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """SIGKILL to the main process mid-study: its store is never read as complete, and the
    same sweep run again computes only the designs not recorded, to the bits of a run
    straight through."""
    process, out, _ = _start(tmp_path)
    process.kill()
    process.wait(timeout=30)
    for line in _wait_until_gone(process.pid, 10):
        os.kill(int(line.split()[0]), signal.SIGKILL)
    kept = sweep_faults.designs_done(out)
    assert 2 <= len(kept) < 16
    assert not sweep_faults.store_complete(out)
    with pytest.raises(rd.InputError, match="has not finished"):
        rd.sweep.open_sweep(out)
    monkeypatch.setitem(sweep_task.METHODS, "slow", sweep_faults.slow)
    monkeypatch.setattr(sweep_faults, "SLOW_TASK_S", 0.0)  # in this process: the same numbers
    spec = rd.sweep.load_sweep_spec(tmp_path / "slow.toml")
    submitted: list[str] = []

    class Counting(SerialExecutor):
        def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Future[Any]:
            submitted.extend(task.task_id for task in args[0])
            return super().submit(fn, *args, **kwargs)

    resumed = run_sweep(spec, out, Counting(), figures=None)
    assert sorted(submitted) == [f"design-{i:05d}" for i in range(16) if i not in kept]
    straight = run_sweep(spec, tmp_path / "straight", SerialExecutor(), figures=None)
    assert_same_bits(straight, resumed)


@pytest.mark.slow
def test_the_command_says_when_tasks_ran_past_the_task_timeout(tmp_path: Path) -> None:
    """A ``--task-timeout`` shorter than the tasks made them time out, the pool replaced and
    the tasks run again — and the command said nothing of it (run.json counted it; a
    new-user trial of 2026-11-26: the wall time doubled)."""
    spec = tmp_path / "slow.toml"
    spec.write_text(SLOW_SPEC.replace("num = 16", "num = 3"), encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("DASK_", "MALLOC_"))}
    env["PYTHONPATH"] = os.pathsep.join(sys.path)
    argv = ["sweep", str(spec), "--workers", "1", "--task-timeout", "0.1", "--no-figures"]
    done = subprocess.run(
        [sys.executable, str(SCRIPT), *argv, "--out", str(tmp_path / "out")],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )
    record = json.loads((tmp_path / "out" / "run.json").read_text(encoding="utf-8"))
    assert record["timed_out"] > 0, done.stdout  # the first task had 600 s, the others 0.1 s
    printed = " ".join(done.stdout.split())
    tasks = f"{record['timed_out']} task{'s' if record['timed_out'] != 1 else ''}"
    assert f"ran again: {tasks} ran past the task timeout (0.1 s)" in printed
    assert f"{record['pools_replaced']} process pools replaced" in printed


# --- a chunk that goes away under a running sweep --------------------------------------------
@pytest.mark.slow
def test_a_chunk_gone_when_finishing_is_a_failure_not_silent_nan(
    small_spec: SweepSpec, tmp_path: Path
) -> None:
    """A design whose part was gone, or of another spec, when the parts were combined ended
    NaN with status 3 while ``n_failed`` stayed 0 and nothing was said (two sweeps sharing a
    folder, a new-user trial of 2026-11-26): it is a failure, with the reason, and a rerun
    computes it.  The same for a chunk of the store gone before the sweep finishes."""
    run_sweep(small_spec, tmp_path, SerialExecutor(), figures=None)
    victim = sweep_faults.chunk_file(tmp_path, "status", 2)  # design 2's (one design a chunk)

    def lose_a_part(done: int, total: int) -> None:
        victim.unlink(missing_ok=True)  # after the resume check, before finishing

    result = run_sweep(small_spec, tmp_path, SerialExecutor(), lose_a_part, figures=None)
    assert result.attrs["n_failed"] == 1
    failures = json.loads((tmp_path / "failures.json").read_text())
    assert [f["task_id"] for f in failures] == ["design-00002"]
    assert "chunk" in failures[0]["error"]
    record = json.loads((tmp_path / "run.json").read_text())
    assert record["failed"] == ["design-00002"]
    rerun = run_sweep(small_spec, tmp_path, SerialExecutor(), figures=None)
    assert rerun.attrs["n_failed"] == 0


def test_a_task_cancelled_before_its_result_is_gathered_ends_its_future_quietly() -> None:
    """A Ctrl-C of a local Dask sweep under load printed distributed's traceback (CI of the
    eighth session): a task finished, then the closing client cancelled it before
    ``cfexecutor._cascade_future`` gathered its result, and the FutureCancelledError raised
    there went to tornado, which logs it with its traceback.  racketdyn's cascade takes it as
    the task cancelled."""
    import asyncio
    from concurrent.futures import Future

    from distributed.cfexecutor import _cascade_future as distributeds
    from distributed.client import FutureCancelledError

    from racketdyn.sweep import executors

    class CancelledWhileGathered:
        status = "cancelled"

        async def _result(self, raiseit: bool = True) -> object:
            raise FutureCancelledError("task", reason="closing")

    async def cascade(function: Any, future: Future[Any]) -> None:
        await function(CancelledWhileGathered(), future)

    with pytest.raises(FutureCancelledError):  # distributed's own: into the event loop
        asyncio.run(cascade(distributeds, Future()))
    quiet: Future[Any] = Future()
    asyncio.run(cascade(executors._cascade_future, quiet))
    assert quiet.cancelled()


def test_an_interrupted_cluster_keeps_its_cancelled_tasks_off_the_console() -> None:
    """CI (twelfth session): after Ctrl-C on a local Dask sweep the scheduler in this process
    printed "ERROR distributed.scheduler: Couldn't gather keys … 'forgotten'" and the client
    "Couldn't gather 1 keys, rescheduling" for a task the sweep had just cancelled (the test
    above, 1 run in a few).  Those loggers go quiet at the interrupt, unless -v shows
    distributed's info, and are set back when the cluster has closed."""
    import logging

    from racketdyn.sweep.executors import (
        INTERRUPT_LOGGERS,
        _LoggerLevels,
        quiet_interrupted_cluster,
    )

    top = logging.getLogger("distributed")
    before = top.level
    try:
        top.setLevel(logging.WARNING)
        with _LoggerLevels(INTERRUPT_LOGGERS):
            quiet_interrupted_cluster()
            for name in ("distributed.scheduler", "distributed.client"):
                assert not logging.getLogger(name).isEnabledFor(logging.ERROR)
        for name in INTERRUPT_LOGGERS:
            assert logging.getLogger(name).isEnabledFor(logging.ERROR)
        top.setLevel(logging.INFO)  # -v: the user asked to see it
        with _LoggerLevels(INTERRUPT_LOGGERS):
            quiet_interrupted_cluster()
            assert logging.getLogger("distributed.scheduler").isEnabledFor(logging.ERROR)
    finally:
        top.setLevel(before)


def test_a_local_workers_lost_heartbeat_stays_off_the_quiet_console(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """CI (fifteenth session's stop): after Ctrl-C on a ``--dask-local`` sweep a worker, whose
    scheduler (in the main process) had just closed, logged "Failed to communicate with
    scheduler during heartbeat." with a Traceback at error level — the level a quiet sweep
    lets its workers print (1 run in several).  A local worker's scheduler lives in the main
    process, so that failure means the sweep is ending: its preload drops it unless -v asked
    for distributed's info; other errors still print."""
    import inspect
    import logging

    from distributed.worker import Worker

    from racketdyn.sweep import _dask_worker

    assert _dask_worker.HEARTBEAT_LOST in inspect.getsource(Worker.heartbeat)
    worker_log = logging.getLogger("distributed.worker")
    handler = logging.StreamHandler()  # as dask's logging config gives the worker
    top = logging.getLogger("distributed")
    before = top.level, list(worker_log.filters)
    top.addHandler(handler)
    try:
        monkeypatch.setenv("DASK_LOGGING__DISTRIBUTED", "error")
        _dask_worker.dask_setup(None)
        try:
            raise OSError("Stream is closed")
        except OSError:
            worker_log.exception("Failed to communicate with scheduler during heartbeat.")
            worker_log.error("a task's own error")
        err = capsys.readouterr().err
        assert "heartbeat" not in err
        assert "Traceback" not in err
        assert "a task's own error" in err
        for flt in list(worker_log.filters):
            worker_log.removeFilter(flt)
        monkeypatch.setenv("DASK_LOGGING__DISTRIBUTED", "info")  # -v: shown
        _dask_worker.dask_setup(None)
        worker_log.error("Failed to communicate with scheduler during heartbeat.")
        assert "heartbeat" in capsys.readouterr().err
    finally:
        top.removeHandler(handler)
        top.setLevel(before[0])
        for flt in list(worker_log.filters):
            worker_log.removeFilter(flt)
        for flt in before[1]:
            worker_log.addFilter(flt)


@pytest.mark.skipif(not hasattr(signal, "SIGINT"), reason="needs SIGINT")
def test_a_ctrl_c_swallowed_where_it_lands_still_stops_a_dask_sweep() -> None:
    # A CI run under load: the interrupted --dask-local sweep ran to its end with exit status
    # 0, its stderr holding asyncio's "KeyboardInterrupt" from `_write_to_self` — the Ctrl-C
    # had been raised inside the event loop's wake-up, which logged and swallowed it.  On a
    # Dask executor a Ctrl-C is a flag the sweep's loop raises between its polls.
    from racketdyn.sweep.executors import ctrl_c_as_flag

    class Dask:
        ctrl_c_at_polls = True

    def ctrl_c() -> None:
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(0.05)

    # Python's own Ctrl-C, as a command has it (a test worker of pytest-xdist ignores SIGINT)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with ctrl_c_as_flag(Dask()) as pressed:
            with contextlib.suppress(KeyboardInterrupt):  # as asyncio's callback wrapper does
                ctrl_c()
            assert pressed()
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
        with ctrl_c_as_flag(object()), pytest.raises(KeyboardInterrupt):
            ctrl_c()  # other executors: Python's own KeyboardInterrupt
    finally:
        signal.signal(signal.SIGINT, previous)
