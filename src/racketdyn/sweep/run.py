"""Running a sweep: :func:`run_sweep`, tasks of designs on an executor, parts, retries.

The top of the flow: takes a :class:`~.spec.SweepSpec` (or its file), creates or resumes the
sweep's store (:mod:`~racketdyn.sweep.store`), submits the :func:`~.task.run_task` of each
design not yet in it to an executor (:mod:`~racketdyn.sweep.executors`) in tasks of one chunk,
finishes the store (mode table, failures, ``sweep_complete`` last) and draws the summary from
it chunk by chunk (:mod:`~racketdyn.sweep.summary`).
"""

from __future__ import annotations

import json
import logging
import secrets
import time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import (
    Executor,
    ProcessPoolExecutor,
)
from contextlib import ExitStack
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

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
    on_each_worker,
)
from racketdyn.sweep.runner import (
    SweepInterrupted,
    TaskTimeoutError,
    WorkerLostError,
    _designs_per_task,
    _Job,
    _Runner,
    _Schedule,
    _Tally,
)
from racketdyn.sweep.spec import SweepSpec
from racketdyn.sweep.spec_file import load_sweep_spec
from racketdyn.sweep.store import (
    STORE_LAYOUT,
    STORE_NAME,
    StoreInfo,
    clear_rows,
    create_store,
    done_designs,
    failure_attrs,
    open_sweep,
    read_records,
    remove_stale_temporaries,
    set_complete,
    status_counts,
    store_info,
    store_seen,
    write_modes,
)
from racketdyn.sweep.summary import (
    SWEET_AREA_COARSE_FRACTION,
    SWEET_AREA_DEFINITION,
    SummaryCurves,
    summary_figures_data,
    sweet_area_resolution_cm2,
    write_summary_csv,
)
from racketdyn.sweep.task import STATUS_CODES, STATUS_FAILED

if TYPE_CHECKING:
    import xarray as xr

__all__ = [
    "DEFAULT_TASKS",
    "SERIAL_IMPACT_LIMIT",
    "ProgressCallback",
    "SweepInterrupted",
    "TaskOptions",
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
above it, in a pool of two processes (with an uncertainty its samples count too:
:attr:`SweepSpec.work_per_design`)."""


@dataclass(frozen=True)
class TaskOptions:
    """How :func:`run_sweep` runs its tasks and who writes their chunks (checked when the run
    starts).

    Attributes
    ----------
    retries : int
        Times a failed design is submitted again before it is recorded as failed.
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
        Designs per task and per chunk of a new store (default: one for serial, else enough
        for about :data:`~racketdyn.sweep.runner.TARGET_TASK_S` of work, with at least four
        tasks per worker).  A resumed store keeps its chunks: tasks are its chunks.
    shared_store : bool
        The sweep's folder is on a path every worker can write, mounted at the same absolute
        path on each (a cluster's shared file system): the workers of a remote Dask cluster
        write their own chunks, as workers on this machine always do.  Checked on each worker
        connected when the run starts; a worker that joins later and does not see the store
        sends its results back and this process writes them.  Default: this process writes
        the chunks of a remote cluster's workers from the results they send back.
        ``run.json`` records which (``store.chunk_writer``, ``store.chunk_writes``).
    """

    retries: int = 1
    max_in_flight: int | None = None
    task_timeout: float | None = None
    designs_per_task: int | None = None
    shared_store: bool = False


DEFAULT_TASKS = TaskOptions()
"""One retry, tasks in flight, timeout and designs per task chosen by the run, this process
writing a remote cluster's chunks."""


def run_sweep(
    spec: SweepSpec | str | Path,
    out_dir: str | Path,
    executor: Executor | None = None,
    progress: ProgressCallback | None = None,
    *,
    options: TaskOptions = DEFAULT_TASKS,
    figures: Callable[[Mapping[str, SummaryCurves], Path], list[Path]] | None = None,
    times: Mapping[str, float] | None = None,
    when_tasks_done: Callable[[], None] | None = None,
    command: Sequence[str] | None = None,
) -> xr.Dataset:
    """Run a sweep: tasks of designs on an executor, written into one chunked store.

    Parameters
    ----------
    spec : SweepSpec or path
        The sweep, or its TOML file (:func:`load_sweep_spec`).
    out_dir : path
        Output folder (created): ``sweep.zarr`` (the results, written as designs finish, one
        chunk per batch of designs; rerun to resume), ``run.json``, ``failures.json`` when a
        task failed for good, ``summary.csv`` and the summary figures.  A store of another
        spec in the folder is replaced.
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
    options : TaskOptions
        How the tasks run: retries, tasks in flight, timeout, designs per task, and who writes
        their chunks (:class:`TaskOptions`; default: :data:`DEFAULT_TASKS`).
    figures : callable, optional
        ``figures(curves, out_dir)`` draws the summary figures of the curves computed here
        (:func:`~racketdyn.sweep.summary.summary_figures_data`: by variable) and returns their
        paths (the presentation layer's :func:`racketdyn.plotting.steps.sweep_figures`); none
        drawn if None.
    times : mapping of str to float, optional
        Seconds spent before this call to add to ``run.json``'s ``time_s`` (the engine's
        start, measured by the caller).
    when_tasks_done : callable, optional
        Called once every task has ended, before the store is finished — to shut down an
        engine the caller owns (``ExitStack.close``): a local Dask cluster's scheduler runs in
        this process's event loop and slowed the old combining step 2.3× while it lived.  Its
        time is ``time_s["shutdown"]``.
    command : sequence of str, optional
        The command as called, for ``run.json`` (default: this function's name).  The other
        steps read it: ``racketdyn predict --out`` refuses a folder whose ``run.json`` names
        ``racketdyn sweep`` or ``racketdyn.workflows.sweep``.

    Returns
    -------
    xarray.Dataset
        The results, opened lazily from ``sweep.zarr`` (:func:`open_sweep`: nothing is read
        until indexed): impact quantities over
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
    InputError
        A negative or fractional ``options.retries``, an ``options.task_timeout`` not above 0;
        with ``options.shared_store``, a worker that does not see the store or cannot write
        there.
    """
    started = time.perf_counter()
    if not isinstance(spec, SweepSpec):
        spec = load_sweep_spec(Path(spec))
    _check_run_options(options)
    out = Path(out_dir)
    previous_outputs = _listed_outputs(out / "run.json")
    _make_folders(out)
    run = _SweepRun.open_or_resume(spec, out, started, times or {})
    if progress is not None:
        progress(run.skipped, run.total)
    if run.todo:
        run.run_tasks(executor, progress, options)
    run.shut_down(when_tasks_done)
    run.finish_store()
    _record_failures(out, run.failures, run.total)
    _warn_of_statuses(run.status_count, spec.n_impacts)
    result, written, notes = run.summarise(figures)
    run.write_record(command, options.shared_store, written, notes, previous_outputs)
    return result


def _check_run_options(options: TaskOptions) -> None:
    """Refuse a negative or fractional ``retries`` and a ``task_timeout`` not above 0."""
    require_whole("retries", options.retries, least=0)
    timeout = options.task_timeout
    if timeout is not None and not timeout > 0:
        raise InputError(f"task_timeout must be a number of seconds above 0 (got {timeout})")


def _make_folders(out: Path) -> None:
    """Create the sweep's folder and its store's, before any work: a folder that cannot be
    written fails every design."""
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise InputError(
            f"`out` {out}: cannot create the sweep's folder ({error.strerror})"
        ) from None
    try:  # and its store's folder, which every design is written into
        (out / STORE_NAME).mkdir(exist_ok=True)
    except OSError as error:
        raise InputError(
            f"`out` {out}: cannot create the sweep's store {STORE_NAME} ({error.strerror})"
        ) from None


@dataclass
class _SweepRun:
    """One call of :func:`run_sweep` in its folder, step by step: the store it resumed (None:
    made anew), the designs still to run, their tally, the engine, the designs per chunk and
    the seconds of each step (``run.json``'s ``time_s``)."""

    spec: SweepSpec
    out: Path
    started: float
    times: Mapping[str, float]
    info: StoreInfo | None
    todo: list[Design]
    time_s: dict[str, float]
    tally: _Tally
    chunk: int
    engine: str = "none (all resumed)"
    worker_start: str = ""
    status_count: dict[str, int] = field(default_factory=dict)

    @property
    def total(self) -> int:
        """The spec's designs."""
        return self.tally.total

    @property
    def skipped(self) -> int:
        """The designs resumed from the store."""
        return self.total - len(self.todo)

    @property
    def failures(self) -> list[dict[str, Any]]:
        """The designs failed for good (with those whose chunk was lost, once finished)."""
        return self.tally.failures

    @classmethod
    def open_or_resume(
        cls, spec: SweepSpec, out: Path, started: float, times: Mapping[str, float]
    ) -> _SweepRun:
        """The run of ``spec`` into ``out``: the designs already in its store are resumed (none
        if the store is another spec's), and the store is not complete until finished again."""
        remove_stale_temporaries(out)
        designs = spec.designs
        total = len(designs)
        info = store_info(out)
        if info is not None and (info.spec_sha256, info.n_designs) != (spec.sha256, total):
            log.info("%s belongs to another spec or version; it is made anew", out / STORE_NAME)
            info = None
        done = done_designs(out, spec)[0] if info is not None else set()
        todo = [d for d in designs if d.index not in done]
        skipped = total - len(todo)
        log.info(
            "sweep %s: %d designs, %d impacts; %d resumed from %s, %d to run",
            spec.name,
            total,
            spec.n_impacts,
            skipped,
            out / STORE_NAME,
            len(todo),
        )
        if info is not None:  # from now on the store is not complete until finished again
            set_complete(out, spec.sha256, False)
        time_s = {**times, "resume_check": time.perf_counter() - started}
        return cls(
            spec,
            out,
            started,
            times,
            info,
            todo,
            time_s,
            _Tally(done=skipped, total=total),
            chunk=info.designs_per_chunk if info is not None else 0,
        )

    def run_tasks(
        self, executor: Executor | None, progress: ProgressCallback | None, options: TaskOptions
    ) -> None:
        """Run the designs still to run, in tasks of one chunk, on ``executor`` (or an engine
        started here and shut down once they have ended)."""
        with ExitStack() as stack:
            executor = self._start_engine(stack, executor)
            limit = options.max_in_flight or _in_flight_limit(executor)
            self._create_or_keep_store(executor, options.designs_per_task)
            token = secrets.token_hex(8)  # the store this run's workers may write
            set_complete(self.out, self.spec.sha256, False, run_token=token)
            local = _local_workers(executor)
            if options.shared_store and not local:
                _check_shared(executor, self.out, self.spec.sha256, token)
            jobs = self._plan_tasks()
            clock = time.perf_counter()
            runner = _Runner(
                self.spec,
                self.out,
                self.chunk,
                executor,
                _Schedule(limit, options.retries, options.task_timeout),
                progress,
                self.tally,
                write_in_worker=local or options.shared_store,
                token=token,
            )
            runner.run(jobs)
            self.time_s["tasks"] = time.perf_counter() - clock

    def _start_engine(self, stack: ExitStack, executor: Executor | None) -> Executor:
        """``executor``, or this process or a pool of two (by the work to do) started on
        ``stack``; a process pool passed in is taken over (its replacements shut down on
        ``stack``)."""
        if executor is None:
            small = len(self.todo) * self.spec.work_per_design < SERIAL_IMPACT_LIMIT
            kind: EngineKind = "serial" if small else "process"
            clock = time.perf_counter()
            executor = stack.enter_context(make_executor(kind, DEFAULT_WORKERS))
            self.time_s["start"] = self.time_s.get("start", 0.0) + time.perf_counter() - clock
        elif isinstance(executor, ProcessPoolExecutor):
            adopted = ProcessPool.adopt(executor)
            stack.callback(adopted.shutdown_replacements)
            executor = adopted
        self.engine = type(executor).__name__
        self.worker_start = str(getattr(executor, "start_method", ""))
        return executor

    def _create_or_keep_store(self, executor: Executor, designs_per_task: int | None) -> None:
        """Create the store, its chunks this run's tasks; a resumed store keeps its chunks."""
        if self.info is None:  # a new store: its chunks are this run's batches
            self.chunk = designs_per_task or _designs_per_task(self.spec, len(self.todo), executor)
            clock = time.perf_counter()
            create_store(self.spec, self.out, self.chunk)
            self.time_s["store_creation"] = time.perf_counter() - clock
        elif designs_per_task not in (None, self.chunk):
            log.info(
                "the store's chunks hold %d designs each: tasks of %d designs, not %d",
                self.chunk,
                self.chunk,
                designs_per_task,
            )

    def _plan_tasks(self) -> list[_Job]:
        """The designs still to run, one task a chunk of the store."""
        by_chunk: dict[int, list[Design]] = {}
        for design in self.todo:
            by_chunk.setdefault(design.index // self.chunk, []).append(design)
        return [_Job(tuple(batch)) for batch in by_chunk.values()]

    def shut_down(self, when_tasks_done: Callable[[], None] | None) -> None:
        """Call the caller's ``when_tasks_done``, timed as ``shutdown`` when an engine ran."""
        if when_tasks_done is not None:
            clock = time.perf_counter()
            when_tasks_done()
            if self.todo:  # an engine ran: its shutdown (nothing to say when all were resumed)
                self.time_s["shutdown"] = time.perf_counter() - clock

    def finish_store(self) -> None:
        """Record the designs whose chunk was lost as failed, clear the rows of every design not
        done, write the mode table, count the statuses and mark the store complete (last)."""
        spec, out = self.spec, self.out
        clock = time.perf_counter()
        finished, _ = done_designs(out, spec)
        missing = [d for d in spec.designs if d.index not in finished]
        _lost_chunks(missing, self.failures)
        clear_rows(out, spec.sha256, sorted(d.index for d in missing))
        write_modes(out, spec, read_records(out, spec.sha256))
        self.status_count = status_counts(out, spec.sha256)
        set_complete(out, spec.sha256, True, run_token="", **failure_attrs(self.failures))  # last
        self.time_s["finishing"] = time.perf_counter() - clock

    def summarise(
        self, figures: Callable[[Mapping[str, SummaryCurves], Path], list[Path]] | None
    ) -> tuple[xr.Dataset, list[Path], list[str]]:
        """The results opened from the store, the files written (the store, ``summary.csv``,
        the figures) and the notes for ``run.json`` (each also logged as a warning but the
        sweet area's definition)."""
        spec, out = self.spec, self.out
        clock = time.perf_counter()
        result = open_sweep(out)
        written = [out / STORE_NAME]
        notes = _uncertainty_notes(spec)
        if spec.variables:
            written.append(write_summary_csv(result, out))
            notes += _sweet_area_notes(result)
            if figures is not None:
                written += figures(summary_figures_data(result), out)
        self.time_s["summary"] = time.perf_counter() - clock
        return result, written, notes

    def write_record(
        self,
        command: Sequence[str] | None,
        shared_store: bool,
        written: list[Path],
        notes: list[str],
        previous_outputs: set[str],
    ) -> None:
        """Write ``run.json``, after removing the files of a previous run's ``run.json`` that
        this run did not write again (another spec's figures)."""
        record = self._record(command, shared_store, written, notes)
        for name in previous_outputs - {p.name for p in written}:  # another spec's figures
            if (self.out / name).is_file():
                (self.out / name).unlink()
        (self.out / "run.json").write_text(json.dumps(record, indent=2), encoding="utf-8")

    def _record(
        self,
        command: Sequence[str] | None,
        shared_store: bool,
        written: list[Path],
        notes: list[str],
    ) -> dict[str, Any]:
        """``run.json``: the run, its engine, its tally and where its time went."""
        spec, tally = self.spec, self.tally
        wall = time.perf_counter() - self.started + sum(self.times.values())
        return {
            "format": "racketdyn-sweep-run",
            "racketdyn_version": __version__,
            "command": [str(part) for part in command or ("python", "racketdyn.sweep.run_sweep")],
            "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
            "spec_sha256": spec.sha256,
            "engine": self.engine,
            # how a process pool started its workers: fork (this process was single-threaded)
            # or forkserver / spawn (it ran threads); a local Dask cluster: forkserver (spawn
            # where there is none); empty for this process and a running Dask cluster
            "worker_start_method": self.worker_start,
            "designs": self.total,
            "impacts": spec.n_impacts,
            "resumed": self.skipped,
            "ran": tally.ran,
            "retried": tally.retried,
            "timed_out": tally.timed_out,
            "pools_replaced": tally.pools_replaced,
            "ran_in_main_process": tally.ran_here,
            "designs_per_task": self.chunk,
            "store": self._store_record(shared_store),
            "failed": [f["task_id"] for f in self.failures],
            "status_counts": self.status_count,
            "wall_time_s": wall,
            "time_s": self.time_s,
            "task_time_s": tally.task_seconds,
            "chunk_write_time_s": tally.write_seconds,
            "first_result_s": tally.first_result_s,
            "outputs": [p.name for p in written] + ["run.json"],
            "spec": spec.to_dict(),
            "uncertainty": spec.uncertainty_record(),
            "notes": notes,
        }

    def _store_record(self, shared_store: bool) -> dict[str, Any]:
        """``run.json``'s ``store``: its path, format, chunks, and who wrote them."""
        return {
            "path": STORE_NAME,
            "format": "zarr",
            "zarr_format": 3,
            "layout": STORE_LAYOUT,
            "designs_per_chunk": self.chunk,
            "chunks": -(-self.total // self.chunk),
            "shared_store": shared_store,
            # who wrote this run's chunks: the workers, this process, or both (a worker that
            # did not see the store; a pool's start, when this process computes too)
            "chunk_writer": _chunk_writer(self.tally),
            "chunk_writes": {
                "workers": self.tally.chunks_by_workers,
                "main_process": self.tally.chunks_by_main,
            },
        }


def _record_failures(out: Path, failures: list[dict[str, Any]], total: int) -> None:
    """Write ``failures.json`` when designs failed for good (and say so), else remove an old
    one."""
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


def _warn_of_statuses(status_count: Mapping[str, int], n_impacts: int) -> None:
    """Warn of the impacts of each status other than ok and failed (their results are NaN)."""
    for text in STATUS_CODES:
        if text not in (STATUS_OK, STATUS_FAILED) and status_count[text]:
            log.warning(
                "%d of %d impacts: %s (their results are NaN)",
                status_count[text],
                n_impacts,
                text,
            )


def _uncertainty_notes(spec: SweepSpec) -> list[str]:
    """A note (and a warning) when the spec's uncertainty has too few samples for its band."""
    if spec.uncertainty is None or spec.uncertainty.samples >= _rough_samples():
        return []
    # the tasks hold propagate's own warning back: said once here
    note = (
        f"{spec.uncertainty.samples} samples a design give a rough 90 % band (its 5 % and "
        f"95 % quantiles rest on a sample or two); {_rough_samples()} or more for numbers to "
        "quote"
    )
    log.warning("%s", note)
    return [note]


def _sweet_area_notes(result: xr.Dataset) -> list[str]:
    """The sweet area's definition, and a note (and a warning) when its steps are coarse."""
    notes = [
        f"sweet_area_cm2 (summary.csv and the summary figures): {SWEET_AREA_DEFINITION}; "
        f"threshold_fraction {float(result.attrs['threshold_fraction']):g}"
    ]
    step = sweet_area_resolution_cm2(result)
    if step > SWEET_AREA_COARSE_FRACTION * float(result.attrs["head_area_cm2"]):
        notes.append(
            f"the sweet area is counted in steps of {step:.1f} cm² (one of "
            f"{result.sizes['point']} impact points): designs closer than that look the "
            "same; give a finer [impacts] grid"
        )
        log.warning("%s", notes[-1])
    return notes


def _check_shared(executor: Executor, out: Path, sha256: str, token: str) -> None:
    """Refuse ``shared_store`` when a connected Dask worker does not see the store in ``out``
    or cannot write there."""
    path = str(out.resolve())
    unseen = {
        w: why
        for w, why in on_each_worker(executor, store_seen, path, sha256, token).items()
        if why
    }
    if unseen:
        worker, why = next(iter(unseen.items()))
        workers = "worker does" if len(unseen) == 1 else "workers do"
        raise InputError(
            f"`shared_store`: {len(unseen)} Dask {workers} "
            f"not see this run's store at {path} ({worker}, {why}); mount the output folder at "
            "the same path on every worker, or run without `shared_store` (this process then "
            "writes each chunk)"
        )
    log.info("shared store: the Dask workers write their own chunks of %s", path)


def _chunk_writer(tally: _Tally) -> str:
    """Who wrote this run's chunks: ``workers``, ``main process``, both, or ``none``."""
    who = [
        name
        for name, count in (
            ("workers", tally.chunks_by_workers),
            ("main process", tally.chunks_by_main),
        )
        if count
    ]
    return " and ".join(who) or "none"


def _rough_samples() -> int:
    """:data:`racketdyn.impact.uncertainty.ROUGH_SAMPLES`, imported when a sweep has an
    uncertainty (the module loads xarray and scipy.stats: ≈ 1 s a process)."""
    from racketdyn.impact.uncertainty import ROUGH_SAMPLES

    return ROUGH_SAMPLES


def _lost_chunks(missing: Sequence[Design], failures: list[dict[str, Any]]) -> bool:
    """Record as failed the designs not done when the sweep finished that did not fail (their
    chunk lost a file, or the store was written over by another sweep in the folder: they
    were NaN with status 3 and counted nowhere); whether there were any."""
    failed = {failure["task_id"] for failure in failures}
    lost = [design for design in missing if design.task_id not in failed]
    for design in lost:
        error = (
            "ChunkLostError: its chunk of the store was gone, or of another spec, when the "
            "sweep finished (deleted, or written by another sweep into this folder?)"
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
