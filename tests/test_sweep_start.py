"""How a sweep's engine starts its workers (issue 16, "use every core").

A process pool forks its workers from this process while it runs a single thread (ready in
milliseconds, racketdyn already imported) and falls back to a forkserver otherwise; a forked
pool is not helped by the main process while it starts (nothing to wait for).  The forkserver
imports the main script once instead of in every worker (a CPython bug, worked around in
``racketdyn.sweep.executors._start_forkserver``).  Each check runs in a fresh interpreter: how
many threads the test process runs depends on the tests before it.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import racketdyn as rd
import sweep_faults


def _python(script: str, tmp_path: Path, *args: str) -> str:
    """Run ``script`` as a file (its own ``__main__``) in a fresh interpreter; its stdout."""
    path = tmp_path / "script.py"
    path.write_text(textwrap.dedent(script), encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("DASK_", "MALLOC_"))}
    env["PYTHONPATH"] = os.pathsep.join(sys.path)
    done = subprocess.run(
        [sys.executable, str(path), *args],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    return done.stdout


_WORKER_PIDS = """
if __name__ == "__main__":
    import logging
    from racketdyn.sweep import make_executor

    logging.getLogger("distributed").setLevel(logging.ERROR)
    stop = threading.Event()  # a thread: the pool takes the forkserver, not fork
    other = threading.Thread(target=stop.wait)
    other.start()
    with make_executor(ENGINE, 2) as executor:
        pids = {executor.submit(os.getpid).result() for _ in range(8)}
    stop.set()
    other.join()
    print(" ".join(map(str, sorted(pids))))
"""
"""A script's guarded part: two workers on ENGINE, started while a thread runs; prints the
workers' process ids."""


def _assert_ran_once_and_not_in_workers(stdout: str, note: Path) -> None:
    """The script's top level (which notes each process running it in ``note``) ran in the
    script and once in the forkserver, never in a worker (whose pids ``stdout`` ends with)."""
    workers = {int(pid) for pid in stdout.strip().splitlines()[-1].split()}
    ran = [int(line) for line in note.read_text().split()]
    assert workers
    assert not workers & set(ran), (workers, ran)
    assert len(ran) == 2  # the script itself, and the forkserver's preload


@pytest.mark.slow
def test_a_pool_forks_while_one_thread_runs_else_uses_a_forkserver(tmp_path: Path) -> None:
    """Single-threaded: fork, every worker up before any task is submitted.  With a thread
    running (a progress display, a Dask client), a fork could copy a held lock: forkserver."""
    out = _python(
        """
        import json, threading
        from racketdyn.sweep import ProcessPool

        def describe(pool):
            pool.submit(sum, [1, 2]).result()
            return {"method": pool.start_method, "at_once": pool.started_at_once}

        if __name__ == "__main__":
            pool = ProcessPool(2)
            up_before_any_task = len(pool._pool._processes)
            one = describe(pool)
            pool.shutdown()
            stop = threading.Event()
            other = threading.Thread(target=stop.wait)
            other.start()
            pool = ProcessPool(2)
            two = describe(pool)
            pool.shutdown()
            stop.set()
            other.join()
            print(json.dumps({"one": one, "up": up_before_any_task, "two": two}))
        """,
        tmp_path,
    )
    seen = json.loads(out.strip().splitlines()[-1])
    assert seen["one"] == {"method": "fork", "at_once": True}
    assert seen["up"] == 2
    assert seen["two"] == {"method": "forkserver", "at_once": False}


@pytest.mark.slow
def test_a_forked_pool_gives_the_serial_bits_with_no_design_run_here(tmp_path: Path) -> None:
    """While a forkserver's pool starts (a second), the main process computes designs itself;
    a forked pool is up at once, so the main process leaves every design to it (it had run
    one while the workers were long up, three processes on two cores)."""
    out = _python(
        f"""
        import json, sys
        import racketdyn as rd
        from racketdyn.sweep import SerialExecutor, TaskOptions, make_executor, run_sweep
        sys.path.insert(0, {str(Path(sweep_faults.__file__).parent)!r})
        from sweep_faults import small_spec

        if __name__ == "__main__":
            spec = small_spec(rd.default_racket(), rd.Ball(), "fork")
            run_sweep(spec, "serial", SerialExecutor(), figures=None)
            with make_executor("process", 2) as pool:
                one_a_task = TaskOptions(designs_per_task=1)
                run_sweep(spec, "pool", pool, options=one_a_task, figures=None)
            record = json.load(open("pool/run.json"))
            print(json.dumps({{k: record[k] for k in ("worker_start_method",
                                                      "ran_in_main_process", "ran")}}))
        """,
        tmp_path,
    )
    record = json.loads(out.strip().splitlines()[-1])
    assert record == {"worker_start_method": "fork", "ran_in_main_process": 0, "ran": 6}
    with (
        rd.sweep.open_sweep(tmp_path / "serial") as serial,
        rd.sweep.open_sweep(tmp_path / "pool") as pooled,
    ):
        sweep_faults.assert_same_bits(serial.load(), pooled.load())


@pytest.mark.parametrize("engine", ["process", "dask-local"])
@pytest.mark.slow
def test_the_forkserver_runs_the_main_script_once_not_in_every_worker(
    engine: str, tmp_path: Path
) -> None:
    """Python before 3.13.8 asked the forkserver to preload ``__main__`` and never did: each
    worker ran the script's top level again (its imports: 0.3 s more per local Dask worker
    for a script importing xarray).  The script's top level notes each process that runs it;
    the workers must not be among them."""
    if engine == "dask-local":
        pytest.importorskip("distributed")
    out = _python(
        textwrap.dedent(
            """
            import os, threading
            with open("ran_top_level.txt", "a") as note:
                note.write(f"{os.getpid()}\\n")

            """
        )
        + _WORKER_PIDS.replace("ENGINE", repr(engine)),
        tmp_path,
    )
    _assert_ran_once_and_not_in_workers(out, tmp_path / "ran_top_level.txt")


@pytest.mark.slow
def test_the_sweep_command_forks_its_pool(tmp_path: Path) -> None:
    """The command's progress line drew from a thread of its own, so the pool never forked:
    each worker started by forkserver, a second or more, and the README's example on two
    workers was slower than serial."""
    spec = tmp_path / "spec.toml"
    spec.write_text(sweep_faults.SMALL_SPEC_TOML, encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("DASK_", "MALLOC_"))}
    env["PYTHONPATH"] = os.pathsep.join(sys.path)
    done = subprocess.run(
        [
            *(sys.executable, "-m", "racketdyn.cli", "sweep", str(spec)),
            *("--workers", "2", "--no-figures", "--out", str(tmp_path / "out")),
        ],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    record = json.loads((tmp_path / "out" / "run.json").read_text(encoding="utf-8"))
    assert record["worker_start_method"] == "fork"
    assert record["ran_in_main_process"] == 0


@pytest.mark.parametrize(("method", "loaded"), [("transient", True), ("approximate", False)])
@pytest.mark.slow
def test_local_dask_workers_of_a_transient_sweep_start_with_the_kernel_loaded(
    method: str, loaded: bool, tmp_path: Path
) -> None:
    """Each local Dask worker loaded numba's compiled kernel in its first task (0.3 s from the
    cache; the first result of a transient sweep came 0.3 s later than on a pool forked from a
    process that had it).  ``start_early`` has the forkserver load it once, for a transient
    sweep only."""
    pytest.importorskip("distributed")
    out = _python(
        f"""
        import logging

        def kernel_loaded():
            from racketdyn.impact import kernel
            return bool(kernel._integrate_batch.signatures)

        if __name__ == "__main__":
            from racketdyn.sweep import make_executor, start_early

            logging.getLogger("distributed").setLevel(logging.ERROR)
            start_early("dask-local", {method!r})
            with make_executor("dask-local", 1) as executor:
                print(executor.submit(kernel_loaded).result())
        """,
        tmp_path,
    )
    assert out.strip().splitlines()[-1] == str(loaded)


@pytest.mark.slow
def test_local_dask_workers_sample_for_the_dashboard_sparingly() -> None:
    """A local cluster's workers sampled their task thread every 10 ms for the dashboard's
    profile, and more: on two cores, time taken from the tasks (``LOCAL_DASK_QUIET``)."""
    pytest.importorskip("distributed")
    import dask

    from racketdyn.sweep import make_executor
    from racketdyn.sweep.executors import LOCAL_DASK_QUIET

    def settings() -> dict[str, object]:
        return {key: dask.config.get(key) for key in LOCAL_DASK_QUIET}

    with make_executor("dask-local", 1) as executor:
        seen = executor.submit(settings).result()
    assert seen == LOCAL_DASK_QUIET


@pytest.mark.parametrize("engine", ["process", "dask-local"])
@pytest.mark.slow
def test_the_forkserver_runs_the_main_script_as_a_worker_would(engine: str, tmp_path: Path) -> None:
    """The forkserver ran the main script's top level without the script's ``sys.argv`` and
    ``sys.path`` (Python gives them to each worker before it imports the script, never to the
    forkserver): a script that reads its arguments or imports a module beside it at its top
    level killed the forkserver — a traceback on stderr, then a dead pool (a design failed
    with ``EOFError``) or "Nanny failed to start".  Run from another folder, with arguments."""
    if engine == "dask-local":
        pytest.importorskip("distributed")
    project = tmp_path / "project"
    project.mkdir()
    (project / "helpers.py").write_text("LABEL = 'beside the script'\n", encoding="utf-8")
    script = project / "study.py"
    script.write_text(
        textwrap.dedent(
            """
            import os, sys, threading
            from helpers import LABEL   # a module beside the script
            OUT = sys.argv[1]           # the script's own argument, read at its top level
            with open(os.path.join(OUT, "ran_top_level.txt"), "a") as note:
                note.write(f"{os.getpid()}\\n")

            """
        )
        + _WORKER_PIDS.replace("ENGINE", repr(engine)),
        encoding="utf-8",
    )
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    env = {k: v for k, v in os.environ.items() if not k.startswith(("DASK_", "MALLOC_"))}
    env["PYTHONPATH"] = os.pathsep.join(sys.path)
    done = subprocess.run(
        [sys.executable, str(script), str(elsewhere)],
        capture_output=True,
        text=True,
        env=env,
        cwd=elsewhere,
        timeout=60,  # the pool hung for good when its forkserver had died
    )
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr, done.stderr
    _assert_ran_once_and_not_in_workers(done.stdout, elsewhere / "ran_top_level.txt")


@pytest.mark.parametrize("engine", ["process", "dask-local"])
@pytest.mark.slow
def test_workers_start_for_a_script_read_from_standard_input(engine: str, tmp_path: Path) -> None:
    """``python - < study.py`` (a notebook's cell piped to Python, a heredoc): the main
    module's ``__file__`` is ``<stdin>``, which every worker started by the forkserver tried to
    run as a file and died — 11 of 12 designs failed (``WorkerLostError``) on a pool started
    while a thread ran, and a local Dask cluster raised "Nanny failed to start".  Such a
    script has no file to import: its workers start as for ``python -c``."""
    if engine == "dask-local":
        pytest.importorskip("distributed")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("DASK_", "MALLOC_"))}
    env["PYTHONPATH"] = os.pathsep.join(sys.path)
    done = subprocess.run(
        [sys.executable, "-"],
        input="import os, threading\n" + _WORKER_PIDS.replace("ENGINE", repr(engine)),
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=60,  # the pool hung for good
    )
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr, done.stderr
    workers = {int(pid) for pid in done.stdout.strip().splitlines()[-1].split()}
    assert workers


def test_a_pool_never_forks_on_macos(monkeypatch: pytest.MonkeyPatch) -> None:
    """Forking was chosen wherever fork exists and one Python thread runs — macOS included,
    where Python itself defaults to spawn since 3.8 (its system libraries, NumPy's Accelerate
    among them, run threads Python cannot see, and a forked child may crash)."""
    from racketdyn.sweep.executors import _fork_context

    monkeypatch.setattr(sys, "platform", "darwin")
    assert _fork_context() is None


def test_ctrl_c_while_a_local_dask_cluster_starts_is_not_lost(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """This process ignored SIGINT while its LocalCluster started (so that spawned workers
    would inherit the ignore): a Ctrl-C in those 0.1–0.8 s was dropped and the sweep ran to
    its end (a new-user trial, 2026-11-26: SIGINT 2.2 s after the command started, exit 0
    after 4.3 s).  The workers come from a forkserver that ignores it already: the Ctrl-C is
    held back until the cluster runs, then stops it whole (interrupted inside its start, a
    half-started cluster printed tracebacks of its workers and its exit handler)."""
    pytest.importorskip("distributed")
    import signal

    import distributed
    from distributed.deploy.spec import SpecCluster

    from racketdyn.sweep import make_executor

    original = distributed.LocalCluster.__init__

    def pressed_while_starting(self: object, *args: object, **kwargs: object) -> None:
        os.kill(os.getpid(), signal.SIGINT)  # the terminal's Ctrl-C, as the cluster starts
        original(self, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(distributed.LocalCluster, "__init__", pressed_while_starting)
    ran = False
    with pytest.raises(KeyboardInterrupt), make_executor("dask-local", 1):
        ran = True
    assert not ran  # stopped before any task
    assert all(cluster.status.name == "closed" for cluster in SpecCluster._instances)


@pytest.mark.slow
def test_run_json_says_how_local_dask_started_its_workers(tmp_path: Path) -> None:
    """``worker_start_method`` was empty for a local Dask cluster, whose workers the nannies
    fork from this process's forkserver (a new-user trial, 2026-11-26)."""
    pytest.importorskip("distributed")
    import logging

    import racketdyn as rd
    from racketdyn.sweep import make_executor, run_sweep

    logging.getLogger("distributed").setLevel(logging.ERROR)
    spec = sweep_faults.small_spec(rd.default_racket(), rd.Ball(), "dask start")
    with make_executor("dask-local", 1) as executor:
        run_sweep(spec, tmp_path, executor, figures=None)
    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert record["worker_start_method"] == "forkserver"
