"""A sweep on a Dask cluster that was already running: ``racketdyn sweep --scheduler tcp://…``.

A ``dask scheduler`` and a ``dask worker`` (two single-threaded worker processes) are started
on this machine as the documented commands (docs/commands/sweep.md), on a random port, each in
a session of its own, and torn down after the test.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import xarray as xr

import racketdyn as rd
import sweep_faults
from racketdyn.cli import main
from racketdyn.sweep import SweepSpec

DASK = Path(sys.executable).with_name("dask")
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
            started.append(
                subprocess.Popen(
                    [
                        *(command, "worker", address, "--nworkers", "2", "--nthreads", "1"),
                        *("--no-dashboard", "--memory-limit", "0"),
                    ],
                    stdout=log,
                    stderr=log,
                    env=env,
                    start_new_session=True,
                )
            )
            from distributed import Client

            with Client(address, timeout="30s") as client:
                client.wait_for_workers(2, timeout=120)
            yield address
        finally:
            for process in reversed(started):
                _stop(process)


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
    with rd.sweep.open_sweep(out) as written:
        result = written.load()
    for name in serial_result.data_vars:
        assert result[name].values.tobytes() == serial_result[name].values.tobytes(), name
    assert result["task_id"].values.tolist() == serial_result["task_id"].values.tolist()
