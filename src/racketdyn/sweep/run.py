"""Running a sweep: :func:`run_sweep`, one task per design on an executor, parts, retries.

The top of the flow: takes a :class:`~.spec.SweepSpec` (or its file), submits the
:func:`~.task.run_task` of each design not yet on disk to an executor
(:mod:`~racketdyn.sweep.executors`), writes and combines the parts
(:mod:`~racketdyn.sweep.files`), and draws the summary (:mod:`~racketdyn.sweep.summary`).
"""

from __future__ import annotations

import json
import logging
import time
import traceback
from collections import deque
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Executor, Future, wait
from contextlib import ExitStack
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from racketdyn.__about__ import __version__
from racketdyn.errors import require_whole
from racketdyn.impact.result import STATUS_OK
from racketdyn.sweep.design import Design
from racketdyn.sweep.executors import DEFAULT_WORKERS, EngineKind, _in_flight_limit, make_executor
from racketdyn.sweep.files import _combine, _read_netcdf, _read_part, _write_netcdf, _write_part
from racketdyn.sweep.spec import SweepSpec
from racketdyn.sweep.spec_file import load_sweep_spec
from racketdyn.sweep.summary import (
    SWEET_AREA_COARSE_FRACTION,
    sweet_area_resolution_cm2,
    write_summary_csv,
)
from racketdyn.sweep.task import STATUS_CODES, STATUS_FAILED, TaskOutput, run_task

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["SERIAL_IMPACT_LIMIT", "ProgressCallback", "run_sweep"]

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
) -> xr.Dataset:
    """Run a sweep: one task per design on an executor, parts on disk, one dataset at the end.

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
        executor passed in is not shut down.
    progress : callable, optional
        ``progress(done, total)`` after the resumed tasks are counted and after each task ends.
    retries : int
        Times a failed task is submitted again before it is recorded as failed.
    figures : callable, optional
        ``figures(dataset, out_dir)`` draws the summary figures and returns their paths (the
        presentation layer's :func:`racketdyn.plotting.sweep.write_summary_figures`); none
        drawn if None.
    max_in_flight : int, optional
        Tasks submitted at once (default: twice the executor's workers; 1 for serial).

    Returns
    -------
    xarray.Dataset
        The combined results as read back from ``sweep.nc``: impact quantities over
        ``(design, point, speed, racket_speed, support)``; ``reduced_mass_kg`` over
        ``(design, point, support)``; ``mode_frequency_hz`` over ``(design, mode)``; design
        coordinates for every variable and the derived racket properties; attributes recording
        the spec (JSON), its hash, the racketdyn version and failed tasks.  A failed design
        has NaN and status code 3.
    """
    started = time.perf_counter()
    if not isinstance(spec, SweepSpec):
        spec = load_sweep_spec(Path(spec))
    require_whole("retries", retries, least=0)
    out = Path(out_dir)
    parts_dir = out / "parts"
    parts_dir.mkdir(parents=True, exist_ok=True)
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
    if progress is not None:
        progress(skipped, total)
    tally = _Tally(done=skipped, total=total)
    engine = "none (all resumed)"
    if todo:
        with ExitStack() as stack:
            if executor is None:
                small = len(todo) * spec.impacts_per_design < SERIAL_IMPACT_LIMIT
                kind: EngineKind = "serial" if small else "process"
                executor = stack.enter_context(make_executor(kind, DEFAULT_WORKERS))
            engine = type(executor).__name__
            limit = max_in_flight or _in_flight_limit(executor)
            _run_tasks(spec, todo, parts_dir, executor, limit, retries, progress, tally)
    failures = tally.failures
    dataset = _combine(spec, parts_dir, failures)
    sweep_path = out / "sweep.nc"
    _write_netcdf(dataset, sweep_path)
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
    record = {
        "format": "racketdyn-sweep-run",
        "racketdyn_version": __version__,
        "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
        "spec_sha256": spec.sha256,
        "engine": engine,
        "designs": total,
        "impacts": spec.n_impacts,
        "resumed": skipped,
        "ran": tally.ran,
        "retried": tally.retried,
        "failed": [f["task_id"] for f in failures],
        "status_counts": status_counts,
        "wall_time_s": time.perf_counter() - started,
        "task_time_s": tally.task_seconds,
        "outputs": [p.name for p in written] + ["run.json", "parts/"],
        "spec": spec.to_dict(),
        "notes": notes,
    }
    (out / "run.json").write_text(json.dumps(record, indent=2), encoding="utf-8")
    return result


@dataclass
class _Tally:
    """What a run did so far: tasks done (with resumed ones) of all, run, retried, failed."""

    done: int
    total: int
    ran: int = 0
    retried: int = 0
    task_seconds: float = 0.0
    failures: list[dict[str, Any]] = field(default_factory=list)


def _run_tasks(
    spec: SweepSpec,
    todo: Sequence[Design],
    parts_dir: Path,
    executor: Executor,
    limit: int,
    retries: int,
    progress: ProgressCallback | None,
    tally: _Tally,
) -> None:
    """Submit the tasks (at most ``limit`` at once), write each part as it ends, retry."""
    queue: deque[tuple[Design, int]] = deque((d, 1) for d in todo)
    pending: dict[Future[TaskOutput], tuple[Design, int]] = {}

    def finished_one() -> None:
        tally.done += 1
        if progress is not None:
            progress(tally.done, tally.total)

    def failed(design: Design, attempt: int, error: BaseException) -> None:
        if attempt <= retries:
            tally.retried += 1
            log.warning(
                "%s (%s) failed on attempt %d (%s: %s); retrying",
                design.task_id,
                design.describe(),
                attempt,
                type(error).__name__,
                error,
            )
            queue.appendleft((design, attempt + 1))
            return
        log.error(
            "%s (%s) failed: %s: %s", design.task_id, design.describe(), type(error).__name__, error
        )
        tally.failures.append(
            {
                "task_id": design.task_id,
                "design": dict(design.settings),
                "attempts": attempt,
                "error": f"{type(error).__name__}: {error}",
                "traceback": "".join(traceback.format_exception(error)),
            }
        )
        finished_one()

    try:
        while queue or pending:
            while queue and len(pending) < limit:
                design, attempt = queue.popleft()
                try:
                    future = executor.submit(run_task, spec.task(design), attempt)
                except Exception as error:  # e.g. a broken process pool
                    failed(design, attempt, error)
                    continue
                pending[future] = (design, attempt)
            if not pending:
                continue
            finished, _ = wait(pending, return_when=FIRST_COMPLETED)
            for future in finished:
                design, attempt = pending.pop(future)
                try:
                    output = future.result()
                    _write_part(spec, design, output, parts_dir)
                except Exception as error:
                    failed(design, attempt, error)
                    continue
                tally.ran += 1
                tally.task_seconds += output.elapsed_s
                finished_one()
    except BaseException:
        for future in pending:
            future.cancel()
        log.warning(
            "sweep interrupted: %d designs are done in %s; run again to resume",
            tally.done,
            parts_dir,
        )
        raise
