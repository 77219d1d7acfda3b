"""The sweep's store (issue 28): results written chunk by chunk into ``sweep.zarr`` as tasks
end, read lazily, resumable, never read as complete before its run has finished."""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable
from concurrent.futures import Executor, Future, ThreadPoolExecutor
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr

import racketdyn as rd
import racketdyn.sweep.summary as summary
import sweep_faults
from racketdyn.sweep import (
    SerialExecutor,
    SweepSpec,
    TaskOptions,
    make_executor,
    open_sweep,
    run_sweep,
    summary_metrics,
)
from racketdyn.sweep.store import STORE_LAYOUT

assert_same_bits = sweep_faults.assert_same_bits


def _serial_sweep(spec: SweepSpec, out: Path, designs_per_task: int) -> xr.Dataset:
    """``spec`` run in this process into ``out``, in tasks (chunks) of ``designs_per_task``."""
    options = TaskOptions(designs_per_task=designs_per_task)
    return run_sweep(spec, out, SerialExecutor(), options=options, figures=None)


class CountingExecutor(SerialExecutor):
    """Runs tasks in this process and records the task ids submitted."""

    def __init__(self) -> None:
        self.submitted: list[str] = []

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Future[Any]:
        self.submitted.extend(task.task_id for task in args[0])
        return super().submit(fn, *args, **kwargs)


@pytest.mark.slow
def test_the_store_has_one_chunk_per_batch_and_is_read_lazily(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    result = _serial_sweep(small_spec, tmp_path, designs_per_task=4)
    assert not (tmp_path / "sweep.nc").exists()
    # what run_sweep returns is read from the store when indexed, not held in memory
    assert not result["rebound_ratio"].variable._in_memory
    with xr.open_zarr(tmp_path / "sweep.zarr", consolidated=False) as lazy:
        assert lazy["rebound_ratio"].chunks[0] == (4, 2)  # one chunk per batch of designs
        assert lazy["rebound_ratio"].data.__module__.startswith("dask")
        assert lazy.attrs["sweep_complete"] == 1
        assert_same_bits(serial_result, lazy.load())
    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert record["store"] == {
        "path": "sweep.zarr",
        "format": "zarr",
        "zarr_format": 3,
        "layout": STORE_LAYOUT,
        "designs_per_chunk": 4,
        "chunks": 2,
        "shared_store": False,
        "chunk_writer": "main process",  # serial: this process is the worker
        "chunk_writes": {"workers": 0, "main_process": 2},
    }
    assert "sweep.zarr" in record["outputs"]


@pytest.mark.slow
def test_one_two_workers_and_dask_write_the_same_store(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    """The store's contents to the bit: a pool of one and of two workers (chunks of another
    size: the tasks are sized by the workers) and a local Dask cluster."""
    for name, kind, workers in (
        ("one", "process", 1),
        ("two", "process", 2),
        ("dask", "dask-local", 2),
    ):
        with make_executor(kind, workers) as executor:  # type: ignore[arg-type]
            run_sweep(small_spec, tmp_path / name, executor, figures=None)
        with open_sweep(tmp_path / name) as written:
            assert_same_bits(serial_result, written.load())


def test_a_store_is_not_complete_while_its_run_is_not(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    """A finished store run again (here for a lost chunk) reads as incomplete from the moment
    the run starts writing until it has finished; readers refuse it meanwhile."""
    run_sweep(small_spec, tmp_path, SerialExecutor(), figures=None)
    sweep_faults.chunk_file(tmp_path, "rebound_ratio", 4).unlink()
    seen: list[bool] = []

    def look(done: int, total: int) -> None:
        seen.append(sweep_faults.store_complete(tmp_path))
        with pytest.raises(rd.InputError, match="has not finished"):
            open_sweep(tmp_path)

    result = run_sweep(small_spec, tmp_path, SerialExecutor(), look, figures=None)
    assert seen == [False, False]
    assert sweep_faults.store_complete(tmp_path)
    assert_same_bits(serial_result, result)


def test_a_lost_chunk_costs_only_its_designs(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    _serial_sweep(small_spec, tmp_path, designs_per_task=2)
    sweep_faults.chunk_file(tmp_path, "reduced_mass_kg", 2, chunk_size=2).unlink()
    counting = CountingExecutor()
    result = run_sweep(small_spec, tmp_path, counting, figures=None)
    assert counting.submitted == ["design-00002", "design-00003"]  # chunk 1's designs
    assert result.attrs["n_failed"] == 0
    assert_same_bits(serial_result, result)


def test_another_spec_replaces_the_store(small_spec: SweepSpec, tmp_path: Path) -> None:
    _serial_sweep(small_spec, tmp_path, designs_per_task=4)
    changed = replace(small_spec, ball_speeds=np.array([10.0, 26.0]))
    counting = CountingExecutor()
    result = run_sweep(changed, tmp_path, counting, figures=None)
    assert len(counting.submitted) == 6
    assert result.attrs["spec_sha256"] == changed.sha256
    assert result["speed"].values.tolist() == [10.0, 26.0]
    assert result["rebound_ratio"].encoding["chunks"][0] == 1  # its own chunks (serial: one)


def test_the_summary_is_read_chunk_by_chunk(
    small_spec: SweepSpec, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The summary metrics of a store read one chunk at a time equal those read at once."""
    result = _serial_sweep(small_spec, tmp_path, designs_per_task=2)
    at_once = summary_metrics(result)
    monkeypatch.setattr(summary, "BLOCK_BYTES", 1)  # a block is one chunk
    assert summary._block(result) == 2
    reads: list[int] = []
    real = xr.DataArray.values.fget  # type: ignore[attr-defined]

    def counted(self: xr.DataArray) -> Any:
        values = real(self)
        if self.name == "rebound_ratio":
            reads.append(self.sizes["design"])
        return values

    monkeypatch.setattr(xr.DataArray, "values", property(counted))
    chunked = summary_metrics(result)
    # one pass over three chunks, none whole (each face's sweet area needs only its own best:
    # the second pass over the store that a sweep-wide best needed is gone)
    assert reads == [2, 2, 2]
    xr.testing.assert_identical(at_once, chunked)


class Overlaps(Executor):
    """A thread pool whose tasks record how many tasks of one chunk run at once; the first
    task of each chunk fails as a whole (before it runs: its batch is split)."""

    def __init__(self, chunk_size: int) -> None:
        self.inner = ThreadPoolExecutor(2)
        self.lock = threading.Lock()
        self.running: dict[int, int] = {}
        self.most = 0
        self.failed: set[int] = set()
        self.chunk_size = chunk_size

    def _run(self, fn: Callable[..., Any], *args: Any) -> Any:
        chunk = int(args[0][0].task_id.split("-")[1]) // self.chunk_size
        with self.lock:
            if chunk not in self.failed:
                self.failed.add(chunk)
                raise RuntimeError("the batch failed as a whole")
            self.running[chunk] = self.running.get(chunk, 0) + 1
            self.most = max(self.most, self.running[chunk])
        try:
            time.sleep(0.05)
            return fn(*args)
        finally:
            with self.lock:
                self.running[chunk] -= 1

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Future[Any]:
        return self.inner.submit(self._run, fn, *args)

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        self.inner.shutdown(wait, cancel_futures=cancel_futures)


def test_two_tasks_of_one_chunk_never_run_at_once(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    """A batch split after it failed runs its designs one by one: two tasks writing one chunk
    at once would each keep only their own designs."""
    with Overlaps(chunk_size=3) as executor:
        result = run_sweep(
            small_spec,
            tmp_path,
            executor,
            options=TaskOptions(max_in_flight=4, designs_per_task=3),
            figures=None,
        )
    assert executor.most == 1
    assert result.attrs["n_failed"] == 0
    assert_same_bits(serial_result, result)


class ElsewhereFirst(Executor):
    """Threads standing for remote Dask workers; the first chunk's task runs on a "node"
    that does not see this run's store (it is handed another run's token)."""

    def __init__(self) -> None:
        self.inner = ThreadPoolExecutor(2)
        self.first = True

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Future[Any]:
        if self.first:
            self.first = False
            args = (*args[:-1], "another run")
        return self.inner.submit(fn, *args, **kwargs)

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        self.inner.shutdown(wait, cancel_futures=cancel_futures)


def test_a_worker_that_does_not_see_the_store_sends_its_results_to_be_written(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    """``shared_store``: a worker that does not see this run's store (one that joined the
    cluster later, without the shared path; a task of an earlier run) writes nothing there and
    sends its results back; the main process writes them.  run.json says who wrote."""
    with ElsewhereFirst() as executor:
        result = run_sweep(
            small_spec,
            tmp_path,
            executor,
            options=TaskOptions(designs_per_task=2, shared_store=True),
            figures=None,
        )
    assert_same_bits(serial_result, result)
    store = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))["store"]
    assert store["chunk_writer"] == "workers and main process"
    assert store["chunk_writes"] == {"workers": 2, "main_process": 1}


def test_without_a_shared_store_remote_workers_write_nothing(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    with ThreadPoolExecutor(2) as executor:  # not this machine's pool: "remote" workers
        result = run_sweep(
            small_spec, tmp_path, executor, options=TaskOptions(designs_per_task=2), figures=None
        )
    assert_same_bits(serial_result, result)
    store = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))["store"]
    assert (store["shared_store"], store["chunk_writer"]) == (False, "main process")
