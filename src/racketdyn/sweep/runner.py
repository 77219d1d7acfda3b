"""The task loop of a sweep: submit, record, retry, and survive what goes wrong.

:func:`~racketdyn.sweep.run.run_sweep` hands the designs still to compute, grouped into tasks
(:func:`_designs_per_task`), to a :class:`_Runner`, which keeps a few tasks in flight on the
executor and writes (or has the workers write) each finished batch of designs as one chunk of
the sweep's store (:mod:`~racketdyn.sweep.store`; a task never spans two chunks, and two tasks
of one chunk are never in flight at once).  Faults it
handles: a task that raises (retried, then recorded as failed), a process pool that lost a
worker (replaced; the designs in flight run again, one at a time, until the one that kills its
worker is found: :class:`WorkerLostError`), a task past the timeout
(:class:`TaskTimeoutError`: its pool replaced, or on Dask its worker restarted, and run again),
and Ctrl-C (the workers stopped, every finished design kept: :class:`SweepInterrupted`).
"""

from __future__ import annotations

import logging
import math
import time
import traceback
from collections import deque
from collections.abc import Callable, Sequence
from concurrent.futures import (
    FIRST_COMPLETED,
    BrokenExecutor,
    CancelledError,
    Executor,
    Future,
    wait,
)
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from racketdyn.sweep.design import Design
from racketdyn.sweep.executors import (
    ProcessPool,
    SerialExecutor,
    _in_flight_limit,
    ctrl_c_as_flag,
    quiet_interrupted_cluster,
)
from racketdyn.sweep.spec import SweepSpec
from racketdyn.sweep.store import STORE_NAME, StoreNotSeenError, recorded, write_chunk
from racketdyn.sweep.task import SweepTask, TaskOutput, run_task

__all__ = [
    "FIRST_TASK_TIMEOUT_S",
    "SECONDS_PER_IMPACT",
    "TARGET_TASK_S",
    "TASK_TIMEOUT_FACTOR",
    "TASK_TIMEOUT_FLOOR_S",
    "SweepInterrupted",
    "TaskTimeoutError",
    "WorkerLostError",
]

# the package's logger, racketdyn.sweep: the sweep's messages keep one name
log = logging.getLogger(__package__)

ProgressCallback = Any  # Callable[[int, int], None]; see racketdyn.sweep.run.ProgressCallback

TASK_TIMEOUT_FACTOR = 10.0
TASK_TIMEOUT_FLOOR_S = 60.0
FIRST_TASK_TIMEOUT_S = 600.0
"""The default task timeout (``task_timeout=None``): ``TASK_TIMEOUT_FACTOR`` × the longest task
finished so far, at least ``TASK_TIMEOUT_FLOOR_S``; ``FIRST_TASK_TIMEOUT_S`` until one has
finished."""

SECONDS_PER_IMPACT = {"approximate": 5e-6, "transient": 2e-5}
"""Rough cost of one impact on one core, s, by method (the benchmarks' figures): used only to
size the tasks (:func:`_designs_per_task`).  Transient: 18 µs per impact in a 10,000-impact
sweep task of ``bench_sweep.py``'s study since issue 16's faster engine (was 70 µs)."""
TARGET_TASK_S = 0.5
"""A task should take about this long, s: long enough that submitting it, shipping it and
writing its part cost little beside it, short enough to share the designs out evenly."""


@dataclass
class _Tally:
    """What a run did so far: designs done (with resumed ones) of all, run, retried, failed,
    and where the time went."""

    done: int
    total: int
    ran: int = 0
    retried: int = 0
    timed_out: int = 0
    pools_replaced: int = 0
    task_seconds: float = 0.0
    write_seconds: float = 0.0
    ran_here: int = 0
    chunks_by_workers: int = 0
    chunks_by_main: int = 0
    longest_s: float = 0.0
    first_result_s: float | None = None
    failures: list[dict[str, Any]] = field(default_factory=list)


class WorkerLostError(RuntimeError):
    """A task's worker process died while it ran (killed, out of memory, ``os._exit``)."""


class TaskTimeoutError(RuntimeError):
    """A task ran past the task timeout; its worker was stopped (a pool replaced, a Dask worker
    restarted)."""


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during a sweep: the workers are stopped and every finished design is on disk.

    Parameters
    ----------
    done : int
        Designs finished (resumed, run or failed for good) and kept.
    total : int
        Designs in the sweep.
    parts_dir : Path
        Where the finished designs are: the sweep's store (``sweep.zarr``).
    """

    def __init__(
        self, done: int, total: int, parts_dir: Path, spec: SweepSpec | None = None
    ) -> None:
        super().__init__(f"{done} of {total} designs kept in {parts_dir}")
        self.done, self.total, self.parts_dir, self.spec = done, total, parts_dir, spec

    def count_kept(self) -> int:
        """Designs of this sweep in its store now: a Dask worker may finish a task and write
        its chunk after the interruption, until its cluster is closed."""
        if self.spec is None:
            return self.done
        self.done = sum(recorded(self.parts_dir.parent, self.spec.sha256))
        return self.done


@dataclass(frozen=True)
class _Job:
    """One submission: a batch of designs, its attempt, and whether it must run alone (a
    suspect after a pool lost a worker: alone, a second loss names it)."""

    designs: tuple[Design, ...]
    attempt: int = 1
    alone: bool = False

    def singles(self, alone: bool) -> list[_Job]:
        return [_Job((d,), self.attempt, alone) for d in self.designs]


def _designs_per_task(spec: SweepSpec, n_designs: int, executor: Executor) -> int:
    """Designs per task: one in this process; else enough for about :data:`TARGET_TASK_S` of
    work (:data:`SECONDS_PER_IMPACT`), but at least four tasks per worker so the last ones
    share out evenly."""
    if isinstance(executor, SerialExecutor):
        return 1
    workers = max(1, _in_flight_limit(executor) // 2)
    per_design = spec.work_per_design * SECONDS_PER_IMPACT.get(
        spec.method, SECONDS_PER_IMPACT["transient"]
    )
    by_time = math.ceil(TARGET_TASK_S / per_design)
    by_balance = max(1, n_designs // (4 * workers))
    return max(1, min(by_time, by_balance))


@dataclass(frozen=True)
class _DesignFailed:
    """A design of a batch that raised, where it ran (the rest of the batch is kept)."""

    error: BaseException
    trace: str


def _run_batch(
    tasks: Sequence[SweepTask],
    attempt: int,
    sha256: str,
    out_dir: str | None,
    indices: Sequence[int] = (),
    token: str | None = None,
) -> list[TaskOutput | _DesignFailed]:
    """Run tasks (designs of one chunk) one after another where the executor put them; a
    design that raises is returned as :class:`_DesignFailed` and the others kept.  With
    ``out_dir``, write the finished ones into the store's chunk there and return them without
    their arrays (the workers write, in parallel, and nothing large travels back) — unless
    this process does not see the store of the run ``token`` there (a Dask worker without
    the shared path, :class:`~.store.StoreNotSeenError`): then with their arrays, for the
    main process to write."""
    results: list[TaskOutput | _DesignFailed] = []
    for task in tasks:
        try:
            results.append(run_task(task, attempt))
        except Exception as error:
            results.append(_DesignFailed(error, "".join(traceback.format_exception(error))))
    if out_dir is None:
        return results
    done = [(i, r) for i, r in zip(indices, results, strict=True) if isinstance(r, TaskOutput)]
    started = time.perf_counter()
    try:
        write_chunk(Path(out_dir), sha256, [i for i, _ in done], [r for _, r in done], token)
    except StoreNotSeenError as error:
        log.warning("the main process writes these designs: %s", error)
        return results
    each = (time.perf_counter() - started) / max(1, len(done))
    return [
        replace(r, arrays={}, write_s=each) if isinstance(r, TaskOutput) else r for r in results
    ]


@dataclass(frozen=True)
class _Schedule:
    """How the runner submits its tasks: at most ``limit`` in flight, a failed design
    submitted again ``retries`` times, a task past ``task_timeout`` seconds from its submission
    stopped (None: never)."""

    limit: int
    retries: int
    task_timeout: float | None


class _Runner:
    """Submits the jobs (at most ``limit`` at once), records each design as it ends, retries
    failures, replaces a pool that lost a worker, stops tasks past the timeout."""

    def __init__(
        self,
        spec: SweepSpec,
        out_dir: Path,
        designs_per_chunk: int,
        executor: Executor,
        schedule: _Schedule,
        progress: ProgressCallback | None,
        tally: _Tally,
        write_in_worker: bool,
        token: str | None = None,
    ) -> None:
        self.spec, self.out_dir, self.executor = spec, out_dir, executor
        self.chunk_size = designs_per_chunk
        self.limit, self.retries = schedule.limit, schedule.retries
        self.task_timeout = schedule.task_timeout
        self.progress, self.tally = progress, tally
        # an absolute path: a remote worker's working folder is its own
        self.write_dir = str(out_dir.resolve()) if write_in_worker else None
        self.token = token
        self.in_main = isinstance(executor, SerialExecutor)  # its "worker" is this process
        self.busy: set[int] = set()  # chunks with a task in flight
        self.queue: deque[_Job] = deque()
        self.pending: dict[Future[list[TaskOutput | _DesignFailed]], tuple[_Job, float]] = {}
        self.started = time.monotonic()
        self.ready_at: float | None = None  # the current pool's first result

    # --- the loop -------------------------------------------------------------------------
    def run(self, jobs: Sequence[_Job]) -> None:
        """Run every job to an end: recorded, or failed for good."""
        self.queue.extend(jobs)
        try:
            with ctrl_c_as_flag(self.executor) as pressed:
                self._loop(pressed)
        except KeyboardInterrupt:
            quiet_interrupted_cluster()  # the tasks cancelled now are the sweep's to report
            lost = self._stop_all()
            # a worker writes its task's chunk when the task ends: count the designs of
            # unfinished tasks that made it to disk (the workers are stopped by now)
            ended = [d.index for job in lost for d in job.designs]
            kept = self.tally.done + sum(recorded(self.out_dir, self.spec.sha256, ended))
            store = self.out_dir / STORE_NAME
            log.warning(
                "sweep interrupted: %d of %d designs are done in %s; run again to resume",
                kept,
                self.tally.total,
                store,
            )
            raise SweepInterrupted(kept, self.tally.total, store, self.spec) from None
        except BaseException:
            self._stop_all()
            raise

    def _loop(self, pressed: Callable[[], bool]) -> None:
        """:meth:`run`'s loop: submit, wait a poll, settle; a Ctrl-C that ``pressed`` holds
        (:func:`~racketdyn.sweep.executors.ctrl_c_as_flag`) raised between polls."""
        while self.queue or self.pending:
            if pressed():
                raise KeyboardInterrupt
            self._submit()
            helped = self._help_while_starting()
            if not self.pending:
                continue
            finished, _ = wait(
                self.pending,
                timeout=0.0 if helped else self._poll_s(),
                return_when=FIRST_COMPLETED,
            )
            broken: list[_Job] = []
            for future in finished:
                job, _ = self._pop(future)
                self._settle(future, job, broken)
            if broken:
                self._pool_broke(broken)
            self._check_timeouts()

    def _starting(self) -> bool:
        """A fresh process pool (never replaced) that has given no result yet: its workers
        are still starting (forkserver, imports)."""
        return (
            isinstance(self.executor, ProcessPool)
            and not self.executor.started_at_once  # forked: its workers are up already
            and self.ready_at is None
            and self.tally.pools_replaced == 0
        )

    def _help_while_starting(self) -> bool:
        """While a fresh pool starts its workers, run one queued job in this process (the cores
        are otherwise idle then; a small sweep may be done before the workers are up).  Not
        after a pool was replaced: a job that kills its process must not kill this one."""
        if not self._starting() or not self.queue or self.queue[0].alone:
            return False
        job = self._next_job()
        if job is None:
            return False
        tasks = tuple(self.spec.task(d) for d in job.designs)
        outputs = _run_batch(tasks, job.attempt, self.spec.sha256, None)
        self.tally.ran_here += len(job.designs)
        self._record(job, outputs, here=True)
        return True

    def _chunk(self, job: _Job) -> int:
        return job.designs[0].index // self.chunk_size

    def _next_job(self) -> _Job | None:
        """The first queued job that may start now: none while a job that must run alone is
        in flight, a job that must run alone only when nothing is, and never a second task
        of a chunk (two would write it at once)."""
        if any(j.alone for j, _ in self.pending.values()):
            return None
        for k, job in enumerate(self.queue):
            if job.alone and self.pending:
                return None
            if self._chunk(job) not in self.busy:
                del self.queue[k]
                return job
        return None

    def _submit(self) -> None:
        # while a fresh pool starts, one task per worker: the rest may run here meanwhile
        limit = max(1, self.limit // 2) if self._starting() else self.limit
        while len(self.pending) < limit and (job := self._next_job()) is not None:
            tasks = tuple(self.spec.task(d) for d in job.designs)
            try:
                future = self.executor.submit(
                    _run_batch,
                    tasks,
                    job.attempt,
                    self.spec.sha256,
                    self.write_dir,
                    [d.index for d in job.designs],
                    self.token,
                )
            except BrokenExecutor:
                self._pool_broke([job])
                return
            except Exception as error:  # e.g. a task that cannot be pickled
                self._failed(job, error)
                continue
            self.pending[future] = (job, time.monotonic())
            self.busy.add(self._chunk(job))

    def _settle(
        self, future: Future[list[TaskOutput | _DesignFailed]], job: _Job, broken: list[_Job]
    ) -> None:
        if future.cancelled():  # not by us (we drop a future before cancelling it)
            self._failed(job, CancelledError("the executor cancelled the task"))
            return
        error = future.exception()
        if error is None:
            self._record(job, future.result())
        elif isinstance(error, BrokenExecutor):
            broken.append(job)
        else:
            self._failed(job, error)

    def _pop(self, future: Future[list[TaskOutput | _DesignFailed]]) -> tuple[_Job, float]:
        job, submitted = self.pending.pop(future)
        self.busy.discard(self._chunk(job))
        return job, submitted

    def _record(
        self, job: _Job, outputs: Sequence[TaskOutput | _DesignFailed], here: bool = False
    ) -> None:
        tally = self.tally
        if not here and tally.first_result_s is None:
            tally.first_result_s = time.monotonic() - self.started
        if not here and self.ready_at is None:
            self.ready_at = time.monotonic()
        finished = [
            (d, o) for d, o in zip(job.designs, outputs, strict=True) if isinstance(o, TaskOutput)
        ]
        if any(o.arrays for _, o in finished):  # the worker could not write them: here
            started = time.perf_counter()
            try:
                write_chunk(
                    self.out_dir,
                    self.spec.sha256,
                    [d.index for d, _ in finished],
                    [o for _, o in finished],
                )
            except Exception as error:
                self._failed(_Job(tuple(d for d, _ in finished), job.attempt, job.alone), error)
                finished = []
            else:
                tally.chunks_by_main += 1
            tally.write_seconds += time.perf_counter() - started
        elif finished and (here or self.in_main):
            tally.chunks_by_main += 1
        elif finished:
            tally.chunks_by_workers += 1
        batch_s = 0.0
        for design, output in zip(job.designs, outputs, strict=True):
            if isinstance(output, _DesignFailed):
                self._failed(_Job((design,), job.attempt, job.alone), output.error, output.trace)
                continue
            if (design, output) not in finished:
                continue
            tally.write_seconds += output.write_s
            tally.ran += 1
            tally.task_seconds += output.elapsed_s
            batch_s += output.elapsed_s + output.write_s
            self._finished_one()
        tally.longest_s = max(tally.longest_s, batch_s)

    def _on_disk(self, design: Design) -> bool:
        """Record a design whose chunk a worker wrote before its batch failed; whether it was."""
        if not recorded(self.out_dir, self.spec.sha256, [design.index])[0]:
            return False
        self.tally.ran += 1
        self._finished_one()
        return True

    def _finished_one(self) -> None:
        self.tally.done += 1
        if self.progress is not None:
            self.progress(self.tally.done, self.tally.total)

    def _failed(self, job: _Job, error: BaseException, trace: str | None = None) -> None:
        if len(job.designs) > 1:  # which design failed? each alone, the attempt unchanged
            # a worker on this machine may have written the batch's chunk before it failed:
            # the designs recorded there are done, only the others run again
            left = [d for d in job.designs if not (self.write_dir is not None and self._on_disk(d))]
            self.queue.extendleft(
                reversed(_Job(tuple(left), job.attempt, job.alone).singles(job.alone))
            )
            return
        (design,) = job.designs
        if job.attempt <= self.retries:
            self.tally.retried += 1
            log.warning(
                "%s (%s) failed on attempt %d (%s: %s); retrying",
                design.task_id,
                design.describe(),
                job.attempt,
                type(error).__name__,
                error,
            )
            self.queue.appendleft(_Job(job.designs, job.attempt + 1, job.alone))
            return
        log.error(
            "%s (%s) failed: %s: %s", design.task_id, design.describe(), type(error).__name__, error
        )
        self.tally.failures.append(
            {
                "task_id": design.task_id,
                "design": dict(design.settings),
                "attempts": job.attempt,
                "error": f"{type(error).__name__}: {error}",
                "traceback": trace or "".join(traceback.format_exception(error)),
            }
        )
        self._finished_one()

    # --- faults ---------------------------------------------------------------------------
    def _drain(self) -> list[_Job]:
        """Empty ``pending``: record what finished, return the jobs lost with the pool."""
        lost = []
        pending = list(self.pending.items())
        self.pending.clear()
        self.busy.clear()
        for future, (job, _) in pending:
            if future.done() and not future.cancelled() and future.exception() is None:
                self._record(job, future.result())
            else:
                future.cancel()
                lost.append(job)
        return lost

    def _pool_broke(self, broken: list[_Job]) -> None:
        """A worker died: every job in flight is lost with the pool.  Replace the pool; a job
        that was alone in flight killed it (a failed attempt); the others run again, each
        alone, without losing an attempt, until the one that kills a worker is found."""
        lost = broken + self._drain()
        renew = getattr(self.executor, "renew", None)
        if renew is None:  # an executor that cannot be replaced: each job has failed
            for job in lost:
                self._failed(job, WorkerLostError("the executor broke (a worker process died)"))
            return
        self._renew()
        if len(lost) == 1 and len(lost[0].designs) == 1:
            log.warning("%s: its worker process died", lost[0].designs[0].task_id)
            self._failed(
                replace(lost[0], alone=True),
                WorkerLostError("the worker process died running it (killed, out of memory, exit)"),
            )
            return
        log.warning(
            "a worker process died; the pool is replaced and the %d designs in flight run "
            "again, one at a time",
            sum(len(job.designs) for job in lost),
        )
        for job in reversed(lost):
            self.queue.extendleft(reversed(job.singles(alone=True)))

    def _timeout_s(self) -> float:
        """The task timeout now, s: counted from a task's submission or the pool's first
        result, whichever is later; until the pool's first result (a fresh pool starts its
        workers and imports racketdyn in them), at least :data:`FIRST_TASK_TIMEOUT_S`."""
        if self.ready_at is None:
            return max(self.task_timeout or 0.0, FIRST_TASK_TIMEOUT_S)
        if self.task_timeout is not None:
            return self.task_timeout
        return max(TASK_TIMEOUT_FLOOR_S, TASK_TIMEOUT_FACTOR * self.tally.longest_s)

    def _renew(self) -> None:
        self.executor.renew()  # type: ignore[attr-defined]
        self.tally.pools_replaced += 1
        self.ready_at = None

    def _poll_s(self) -> float:
        return min(1.0, self._timeout_s() / 4)

    def _check_timeouts(self) -> None:
        if isinstance(self.executor, SerialExecutor):
            return
        limit, now = self._timeout_s(), time.monotonic()
        ready = self.ready_at or 0.0
        late = [(f, job) for f, (job, t0) in self.pending.items() if now - max(t0, ready) > limit]
        if not late:
            return
        self.tally.timed_out += len(late)
        stop_task = getattr(self.executor, "stop_task", None)
        for future, _ in late:
            self._pop(future)
            if stop_task is not None:  # Dask: cancel it and restart its worker
                stop_task(future)
                self.ready_at = None  # a restarted worker starts again
            else:
                future.cancel()
        renew = getattr(self.executor, "renew", None)
        if renew is not None:
            # a worker cannot be told to stop a task: replace the pool; the other jobs in
            # flight run again without losing an attempt
            others = self._drain()
            self._renew()
            self.queue.extendleft(reversed(others))
        # else (Dask): the task is cancelled, its worker restarted where it has a nanny (else
        # the worker stays busy), and it runs again
        for _, job in late:
            log.warning(
                "%s still running after %.0f s (the task timeout); running it again",
                ", ".join(d.task_id for d in job.designs),
                limit,
            )
            self._failed(job, TaskTimeoutError(f"still running after {limit:.0f} s (task timeout)"))

    def _stop_all(self) -> list[_Job]:
        """Ctrl-C or an error: record what finished, cancel the rest, stop the workers; return
        the jobs that did not finish."""
        try:
            return self._drain()
        finally:
            stop = getattr(self.executor, "stop", None)
            if stop is not None:
                stop()
