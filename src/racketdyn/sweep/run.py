"""Running a sweep: :func:`run_sweep`, tasks of designs on an executor, parts, retries.

The top of the flow: takes a :class:`~.spec.SweepSpec` (or its file), submits the
:func:`~.task.run_task` of each design not yet on disk to an executor
(:mod:`~racketdyn.sweep.executors`), writes and combines the parts
(:mod:`~racketdyn.sweep.files`), and draws the summary (:mod:`~racketdyn.sweep.summary`).
"""

from __future__ import annotations

import json
import logging
import time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import (
    Executor,
    ProcessPoolExecutor,
)
from contextlib import ExitStack
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from racketdyn.__about__ import __version__
from racketdyn.errors import InputError, require_whole
from racketdyn.impact.result import STATUS_OK
from racketdyn.sweep.design import Design
from racketdyn.sweep.executors import (
    DEFAULT_WORKERS,
    EngineKind,
    ProcessPool,
    _in_flight_limit,
    _local_workers,
    make_executor,
)
from racketdyn.sweep.files import (
    _Assembly,
    _combine,
    _failure_attrs,
    _read_netcdf,
    _read_part,
    _remove_stale_temporaries,
    _write_netcdf,
)
from racketdyn.sweep.runner import (
    SweepInterrupted,
    TaskTimeoutError,
    WorkerLostError,
    _designs_per_task,
    _Job,
    _Runner,
    _Tally,
)
from racketdyn.sweep.spec import SweepSpec
from racketdyn.sweep.spec_file import load_sweep_spec
from racketdyn.sweep.summary import (
    SWEET_AREA_COARSE_FRACTION,
    sweet_area_resolution_cm2,
    write_summary_csv,
)
from racketdyn.sweep.task import STATUS_CODES, STATUS_FAILED

if TYPE_CHECKING:
    import xarray as xr

__all__ = [
    "SERIAL_IMPACT_LIMIT",
    "ProgressCallback",
    "SweepInterrupted",
    "TaskTimeoutError",
    "WorkerLostError",
    "run_sweep",
]

# the package's logger, racketdyn.sweep: the sweep's messages keep one name
log = logging.getLogger(__package__)

ProgressCallback = Callable[[int, int], None]
"""Called as ``progress(done, total)`` with the number of design tasks finished (run, resumed
or failed for good) and the number of tasks."""

SERIAL_IMPACT_LIMIT = 50_000
"""Below this many impacts to compute, ``run_sweep(executor=None)`` runs in this process;
above it, in a pool of two processes."""


def run_sweep(
    spec: SweepSpec | str | Path,
    out_dir: str | Path,
    executor: Executor | None = None,
    progress: ProgressCallback | None = None,
    *,
    retries: int = 1,
    figures: Callable[[xr.Dataset, Path], list[Path]] | None = None,
    max_in_flight: int | None = None,
    task_timeout: float | None = None,
    designs_per_task: int | None = None,
    times: Mapping[str, float] | None = None,
    when_tasks_done: Callable[[], None] | None = None,
    command: Sequence[str] | None = None,
) -> xr.Dataset:
    """Run a sweep: tasks of designs on an executor, parts on disk, one dataset at the end.

    Parameters
    ----------
    spec : SweepSpec or path
        The sweep, or its TOML file (:func:`load_sweep_spec`).
    out_dir : path
        Output folder (created): ``parts/<task-id>.nc`` per finished design, ``sweep.nc``,
        ``run.json``, ``failures.json`` when a task failed for good, ``summary.csv`` and the
        summary figures.
    executor : concurrent.futures.Executor, optional
        Where tasks run (:func:`make_executor`; a ``dask.distributed`` client's
        ``get_executor()``).  Default: this process for fewer than
        :data:`SERIAL_IMPACT_LIMIT` impacts to compute, else a pool of two processes.  An
        executor passed in is not shut down.  A process pool that loses a worker is replaced
        (a :class:`~concurrent.futures.ProcessPoolExecutor` passed in is taken over); the
        designs in flight run again, one at a time, and the one whose worker dies when alone
        has failed an attempt (:class:`WorkerLostError`).
    progress : callable, optional
        ``progress(done, total)`` (designs) after the resumed ones are counted and after each
        design ends.
    retries : int
        Times a failed design is submitted again before it is recorded as failed.
    figures : callable, optional
        ``figures(dataset, out_dir)`` draws the summary figures and returns their paths (the
        presentation layer's :func:`racketdyn.plotting.sweep.write_summary_figures`); none
        drawn if None.
    max_in_flight : int, optional
        Tasks submitted at once (default: twice the executor's workers; 1 for serial).
    task_timeout : float, optional
        Seconds a task may take from its submission before it counts as hung: its worker is
        stopped (a process pool is replaced; a Dask worker restarted through its nanny)
        and the task runs again elsewhere, as a failed attempt (:class:`TaskTimeoutError`).
        Default: 10 × the longest task finished so far, at least 60 s (600 s until one has
        finished); ``math.inf``: never.  Not for :class:`SerialExecutor`, which runs a task
        inside ``submit``.
    designs_per_task : int, optional
        Designs per task (default: :func:`designs_per_task` — one for serial, else enough for
        about :data:`TARGET_TASK_S` of work, with at least four tasks per worker).
    times : mapping of str to float, optional
        Seconds spent before this call to add to ``run.json``'s ``time_s`` (the engine's
        start, measured by the caller).
    when_tasks_done : callable, optional
        Called once every task has ended, before the parts are combined — to shut down an
        engine the caller owns (``ExitStack.close``): a local Dask cluster's scheduler runs in
        this process's event loop and slowed combining 2.3× while it lived (0.25 against
        0.11 s for 30 designs, a check of 2026-11-26).  Its time is ``time_s["shutdown"]``.
    command : sequence of str, optional
        The command as called, for ``run.json`` (default: this function's name).  The other
        steps read it: ``racketdyn predict --out`` refuses a folder whose ``run.json`` names
        ``racketdyn sweep`` or ``racketdyn.workflows.sweep``.

    Returns
    -------
    xarray.Dataset
        The combined results as read back from ``sweep.nc``: impact quantities over
        ``(design, point, speed, racket_speed, support)``; ``reduced_mass_kg`` over
        ``(design, point, support)``; ``mode_frequency_hz`` over ``(design, mode)``; design
        coordinates for every variable and the derived racket properties; attributes recording
        the spec (JSON), its hash, the racketdyn version and failed tasks.  A failed design
        has NaN and status code 3.

    Raises
    ------
    SweepInterrupted
        On Ctrl-C (a :class:`KeyboardInterrupt`): the workers are stopped, every finished
        design is on disk; run again to resume.
    """
    started = time.perf_counter()
    if not isinstance(spec, SweepSpec):
        spec = load_sweep_spec(Path(spec))
    require_whole("retries", retries, least=0)
    if task_timeout is not None and not task_timeout > 0:
        raise InputError(f"task_timeout must be a number of seconds above 0 (got {task_timeout})")
    out = Path(out_dir)
    previous_outputs = _listed_outputs(out / "run.json")
    parts_dir = out / "parts"
    try:  # before any work: a folder that cannot be written fails every design
        parts_dir.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise InputError(
            f"`out` {out}: cannot create the sweep's folder {parts_dir} ({error.strerror})"
        ) from None
    _remove_stale_temporaries(parts_dir)
    designs = spec.designs
    total = len(designs)
    todo = [d for d in designs if _read_part(parts_dir / f"{d.task_id}.nc", spec, False) is None]
    skipped = total - len(todo)
    log.info(
        "sweep %s: %d designs, %d impacts; %d resumed from %s, %d to run",
        spec.name,
        total,
        spec.n_impacts,
        skipped,
        parts_dir,
        len(todo),
    )
    time_s = {**(times or {}), "resume_check": time.perf_counter() - started}
    if progress is not None:
        progress(skipped, total)
    tally = _Tally(done=skipped, total=total)
    assembly = _Assembly(spec, parts_dir)
    engine = "none (all resumed)"
    worker_start = ""
    batch = 0
    if todo:
        with ExitStack() as stack:
            if executor is None:
                small = len(todo) * spec.impacts_per_design < SERIAL_IMPACT_LIMIT
                kind: EngineKind = "serial" if small else "process"
                clock = time.perf_counter()
                executor = stack.enter_context(make_executor(kind, DEFAULT_WORKERS))
                time_s["start"] = time_s.get("start", 0.0) + time.perf_counter() - clock
            elif isinstance(executor, ProcessPoolExecutor):
                adopted = ProcessPool.adopt(executor)
                stack.callback(adopted.shutdown_replacements)
                executor = adopted
            engine = type(executor).__name__
            worker_start = str(getattr(executor, "start_method", ""))
            limit = max_in_flight or _in_flight_limit(executor)
            batch = designs_per_task or _designs_per_task(spec, len(todo), executor)
            jobs = [_Job(tuple(todo[i : i + batch])) for i in range(0, len(todo), batch)]
            clock = time.perf_counter()
            runner = _Runner(
                spec,
                parts_dir,
                executor,
                limit,
                retries,
                task_timeout,
                progress,
                tally,
                write_in_worker=_local_workers(executor),
                assembly=assembly,
            )
            runner.run(jobs)
            time_s["tasks"] = time.perf_counter() - clock
    if when_tasks_done is not None:
        clock = time.perf_counter()
        when_tasks_done()
        if todo:  # an engine ran: its shutdown (nothing to say when every design was resumed)
            time_s["shutdown"] = time.perf_counter() - clock
    failures = tally.failures
    clock = time.perf_counter()
    dataset = _combine(spec, parts_dir, failures, assembly)
    if _lost_parts(assembly.missing, failures):
        dataset.attrs.update(_failure_attrs(failures))
    sweep_path = out / "sweep.nc"
    _write_netcdf(dataset, sweep_path)
    time_s["combining"] = time.perf_counter() - clock
    failures_path = out / "failures.json"
    if failures:
        failures_path.write_text(json.dumps(failures, indent=2), encoding="utf-8")
        log.error(
            "%d of %d designs failed; their results are NaN (status 3); see %s",
            len(failures),
            total,
            failures_path,
        )
    elif failures_path.exists():
        failures_path.unlink()
    codes, counts = np.unique(dataset["status"].values, return_counts=True)
    status_counts = {text: int(counts[codes == code].sum()) for text, code in STATUS_CODES.items()}
    for text in STATUS_CODES:
        if text not in (STATUS_OK, STATUS_FAILED) and status_counts[text]:
            log.warning(
                "%d of %d impacts: %s (their results are NaN)",
                status_counts[text],
                spec.n_impacts,
                text,
            )
    clock = time.perf_counter()
    result = _read_netcdf(sweep_path)
    written = [sweep_path]
    notes = []
    if spec.variables:
        written.append(write_summary_csv(result, out))
        step = sweet_area_resolution_cm2(result)
        if step > SWEET_AREA_COARSE_FRACTION * float(result.attrs["head_area_cm2"]):
            notes.append(
                f"the sweet area is counted in steps of {step:.1f} cm² (one of "
                f"{result.sizes['point']} impact points): designs closer than that look the "
                "same; give a finer [impacts] grid"
            )
            log.warning("%s", notes[-1])
        if figures is not None:
            written += figures(result, out)
    time_s["summary"] = time.perf_counter() - clock
    wall = time.perf_counter() - started + sum((times or {}).values())
    record = {
        "format": "racketdyn-sweep-run",
        "racketdyn_version": __version__,
        "command": [str(part) for part in command or ("python", "racketdyn.sweep.run_sweep")],
        "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
        "spec_sha256": spec.sha256,
        "engine": engine,
        # how a process pool started its workers: fork (this process was single-threaded) or
        # forkserver / spawn (it ran threads); a local Dask cluster: forkserver (spawn where
        # there is none); empty for this process and a running Dask cluster
        "worker_start_method": worker_start,
        "designs": total,
        "impacts": spec.n_impacts,
        "resumed": skipped,
        "ran": tally.ran,
        "retried": tally.retried,
        "timed_out": tally.timed_out,
        "pools_replaced": tally.pools_replaced,
        "ran_in_main_process": tally.ran_here,
        "designs_per_task": batch,
        "failed": [f["task_id"] for f in failures],
        "status_counts": status_counts,
        "wall_time_s": wall,
        "time_s": time_s,
        "task_time_s": tally.task_seconds,
        "part_write_time_s": tally.write_seconds,
        "part_read_time_s": tally.assemble_seconds,
        "first_result_s": tally.first_result_s,
        "outputs": [p.name for p in written] + ["run.json", "parts/"],
        "spec": spec.to_dict(),
        "notes": notes,
    }
    for name in previous_outputs - {p.name for p in written}:  # another spec's figures
        if (out / name).is_file():
            (out / name).unlink()
    (out / "run.json").write_text(json.dumps(record, indent=2), encoding="utf-8")
    return result


def _lost_parts(missing: Sequence[Design], failures: list[dict[str, Any]]) -> bool:
    """Record as failed the designs whose part was gone, or another spec's, when the parts
    were read (deleted during the run, or written over by another sweep in the folder:
    they were NaN with status 3 and counted nowhere); whether there were any."""
    failed = {failure["task_id"] for failure in failures}
    lost = [design for design in missing if design.task_id not in failed]
    for design in lost:
        error = (
            "PartLostError: its part was gone, or of another spec, when the parts were "
            "combined (deleted, or written by another sweep into this folder?)"
        )
        log.error("%s (%s) failed: %s", design.task_id, design.describe(), error)
        failures.append(
            {
                "task_id": design.task_id,
                "design": dict(design.settings),
                "attempts": 0,
                "error": error,
                "traceback": "",
            }
        )
    return bool(lost)


def _listed_outputs(run_json: Path) -> set[str]:
    """The files a previous sweep's ``run.json`` wrote into its folder (plain names only:
    never a path elsewhere, nor ``parts/``); none if there is no readable one, or it is
    another command's.  A run of another
    spec into the folder removes those it does not write again (a figure of a variable the
    new spec does not have), and leaves every other file alone."""
    try:
        record = json.loads(run_json.read_text(encoding="utf-8"))
        listed = record["outputs"] if record["format"] == "racketdyn-sweep-run" else []
    except (OSError, ValueError, KeyError, TypeError):
        return set()
    return {
        name
        for name in listed
        if isinstance(name, str)
        and Path(name).name == name
        and name not in ("", ".", "..", "run.json")
    }
