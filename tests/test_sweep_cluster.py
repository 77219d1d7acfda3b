"""A sweep on a Dask cluster that was already running: ``racketdyn sweep --scheduler tcp://…``.

A ``dask scheduler`` and two ``dask worker`` processes (one single-threaded worker each, each
with its own memory limit, as on two nodes) are started on this machine as the documented
commands (docs/commands/sweep.md), on a random port, each in a session of its own, and torn
down after the tests.  The store is written by the main process from the workers' results, or
with ``--shared-store`` by the workers themselves (issue 28); a worker started in a mount
namespace of its own, where the output folder is an empty tmpfs, is a node that does not see
the shared path.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import pytest
import xarray as xr

import racketdyn as rd
import sweep_faults
from racketdyn.cli import main
from racketdyn.sweep import SweepSpec

DASK = Path(sys.executable).with_name("dask")
WORKER_MEMORY = 1 << 30
"""Each worker's memory limit, bytes (``dask worker --memory-limit``)."""
pytestmark = pytest.mark.skipif(
    not DASK.exists() and shutil.which("dask") is None, reason="needs the dask command"
)


def _stop(process: subprocess.Popen[bytes]) -> None:
    """End a process and every process of its session (the worker's nanny starts workers)."""
    for sig in (signal.SIGTERM, signal.SIGKILL):
        try:
            os.killpg(process.pid, sig)
        except ProcessLookupError:
            return
        try:
            process.wait(timeout=10)
            return
        except subprocess.TimeoutExpired:
            continue


def _worker(
    command: str, address: str, log: Any, env: dict[str, str], prefix: Sequence[str] = ()
) -> subprocess.Popen[bytes]:
    """``dask worker`` with one single-threaded worker and its own memory limit."""
    return subprocess.Popen(
        [
            *prefix,
            *(command, "worker", address, "--nworkers", "1", "--nthreads", "1"),
            *("--no-dashboard", "--memory-limit", str(WORKER_MEMORY)),
        ],
        stdout=log,
        stderr=log,
        env=env,
        start_new_session=True,
    )


@pytest.fixture(scope="module")
def scheduler(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """The address of a running scheduler with 2 single-threaded workers."""
    folder = tmp_path_factory.mktemp("cluster")
    command = str(DASK if DASK.exists() else shutil.which("dask"))
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    address_file = folder / "scheduler.json"
    started: list[subprocess.Popen[bytes]] = []
    with (folder / "log.txt").open("wb") as log:
        try:
            started.append(
                subprocess.Popen(
                    [
                        *(command, "scheduler", "--host", "127.0.0.1", "--port", "0"),
                        *("--no-dashboard", "--scheduler-file", str(address_file)),
                    ],
                    stdout=log,
                    stderr=log,
                    env=env,
                    start_new_session=True,
                )
            )
            deadline = time.monotonic() + 60
            while not address_file.exists() or not address_file.read_text():
                assert time.monotonic() < deadline, (folder / "log.txt").read_text()
                time.sleep(0.1)
            time.sleep(0.2)  # the file is written whole, but give it a moment
            address = json.loads(address_file.read_text())["address"]
            for _ in range(2):  # two worker processes, as on two nodes
                started.append(_worker(command, address, log, env))
            from distributed import Client

            with Client(address, timeout="30s") as client:
                client.wait_for_workers(2, timeout=120)
            yield address
        finally:
            for process in reversed(started):
                _stop(process)


@pytest.mark.slow
def test_a_sweep_on_a_running_cluster_equals_serial(
    scheduler: str, small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    assert scheduler.startswith("tcp://127.0.0.1:")
    spec = tmp_path / "spec.toml"
    spec.write_text(sweep_faults.SMALL_SPEC_TOML, encoding="utf-8")
    assert rd.sweep.load_sweep_spec(spec).sha256 == small_spec.sha256  # the same sweep
    out = tmp_path / "out"
    argv = ["sweep", str(spec), "--scheduler", scheduler, "--no-figures", "--out", str(out)]
    assert main(argv) == 0
    record = json.loads((out / "run.json").read_text())
    assert record["engine"] == "DaskExecutor"
    assert record["ran"] == 6
    # by default the main process writes a remote cluster's chunks from their results
    assert record["store"]["shared_store"] is False
    assert record["store"]["chunk_writer"] == "main process"
    assert record["store"]["chunk_writes"]["workers"] == 0
    with rd.sweep.open_sweep(out) as written:
        result = written.load()
    for name in serial_result.data_vars:
        assert result[name].values.tobytes() == serial_result[name].values.tobytes(), name
    assert result["task_id"].values.tolist() == serial_result["task_id"].values.tolist()


def _run_cli(scheduler: str, tmp_path: Path, *extra: str) -> tuple[int, Path]:
    spec = tmp_path / "spec.toml"
    spec.write_text(sweep_faults.SMALL_SPEC_TOML, encoding="utf-8")
    out = tmp_path / "out"
    argv = ["sweep", str(spec), "--scheduler", scheduler, "--no-figures", "--out", str(out)]
    return main([*argv, *extra]), out


def test_the_cluster_has_two_workers_each_with_its_own_memory_limit(scheduler: str) -> None:
    from distributed import Client

    with Client(scheduler, timeout="30s") as client:
        workers = client.scheduler_info()["workers"].values()
        pids = client.run(os.getpid)
    assert [w["memory_limit"] for w in workers] == [WORKER_MEMORY, WORKER_MEMORY]
    assert [w["nthreads"] for w in workers] == [1, 1]
    assert len(set(pids.values())) == 2


@pytest.mark.slow
def test_with_a_shared_store_the_remote_workers_write_their_own_chunks(
    scheduler: str, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    """Issue 28: ``--shared-store`` — the workers write the chunks, the main process none;
    the same bits as serial."""
    code, out = _run_cli(scheduler, tmp_path, "--shared-store")
    assert code == 0
    record = json.loads((out / "run.json").read_text())
    assert record["ran"] == 6
    store = record["store"]
    assert store["shared_store"] is True
    assert store["chunk_writer"] == "workers"
    assert store["chunk_writes"] == {"workers": store["chunks"], "main_process": 0}
    with rd.sweep.open_sweep(out) as written:
        assert written.attrs["run_token"] == ""  # the run has finished: no worker may write
        sweep_faults.assert_same_bits(serial_result, written.load())


def _private_mounts() -> bool:
    unshare = shutil.which("unshare")
    return unshare is not None and subprocess.run([unshare, "-rm", "true"]).returncode == 0


@pytest.mark.skipif(not _private_mounts(), reason="needs unshare -rm (user mount namespaces)")
@pytest.mark.slow
def test_a_worker_that_does_not_see_the_shared_store_is_named(
    scheduler: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A third worker on a "node" where the output folder is its own empty disk (a tmpfs
    mounted over it in a mount namespace of its own): ``--shared-store`` is refused in one
    line naming the option and the fix, exit 2."""
    from distributed import Client

    command = str(DASK if DASK.exists() else shutil.which("dask"))
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    mount = f'mount -t tmpfs tmpfs "{tmp_path}" && exec "$@"'
    with (tmp_path.parent / f"{tmp_path.name}-worker.txt").open("wb") as log:
        other = _worker(command, scheduler, log, env, ("unshare", "-rm", "sh", "-c", mount, "sh"))
        try:
            with Client(scheduler, timeout="30s") as client:
                client.wait_for_workers(3, timeout=120)
            code, _ = _run_cli(scheduler, tmp_path, "--shared-store")
        finally:
            _stop(other)
            with Client(scheduler, timeout="30s") as client:
                deadline = time.monotonic() + 60
                while len(client.scheduler_info()["workers"]) > 2:
                    assert time.monotonic() < deadline
                    time.sleep(0.2)
    assert code == 2
    said = capsys.readouterr().err
    assert said.count("\n") == 1
    assert said.startswith("racketdyn: error: --shared-store: 1 Dask worker does not see")
    assert "mount the output folder at the same path on every worker" in said
    assert "or run without --shared-store" in said
