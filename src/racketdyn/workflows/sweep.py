"""Step ``sweep``: a design sweep (racket variants × points × speeds) on an executor.

:func:`racketdyn.sweep.run_sweep` writes the folder itself (``sweep.zarr``, ``summary.csv``,
its own ``run.json`` with the engine, counts and timing, and the figures the caller's hook
draws); this step chooses the executor and returns the record.
"""

from __future__ import annotations

import json
import os
import time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import Executor
from contextlib import AbstractContextManager, ExitStack, nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import xarray as xr

from racketdyn.sweep import (
    SweepSpec,
    TaskOptions,
    load_sweep_spec,
    make_executor,
    run_sweep,
    start_early,
)
from racketdyn.sweep.summary import SummaryCurves
from racketdyn.workflows.run import (
    Progress,
    StepResult,
    _lock,
    _refuse_other_step,
    command_record,
    make_out_folder,
    report,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

__all__ = ["SweepResult", "run_sweep_step"]

Engine = Literal["auto", "serial", "process", "dask-local", "dask"]


@dataclass
class SweepResult(StepResult):
    """What :func:`run_sweep_step` ran.

    Attributes
    ----------
    dataset : xarray.Dataset
        The results, read lazily from ``sweep.zarr`` (:func:`racketdyn.sweep.open_sweep`).
    spec : SweepSpec
        The sweep.
    failed : list of dict
        Tasks that failed for good (``task_id``, ``error``).
    """

    dataset: xr.Dataset | None = None
    spec: SweepSpec | None = None
    failed: list[dict[str, Any]] = field(default_factory=list)


def run_sweep_step(
    spec: SweepSpec | str | os.PathLike[str],
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    *,
    engine: Engine = "auto",
    workers: int | None = None,
    scheduler: str | None = None,
    task_timeout: float | None = None,
    shared_store: bool = False,
) -> SweepResult:
    """Run (or resume) a design sweep into ``out``.

    Parameters
    ----------
    spec : SweepSpec or path
        The sweep, or its TOML file (docs/sweep-file.md).
    out : path
        Output folder (created if missing); run again to resume.
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, sweep uses the run only (the racket
        and the rest come from the spec: ``figures(curves, out)`` draws the summary figures,
        :func:`racketdyn.plotting.steps.sweep_figures`);
        and the run (command, figures, progress).
    engine : {"auto", "serial", "process", "dask-local", "dask"}
        Where tasks run; ``auto``: this process for a small sweep, else two processes.
    workers : int, optional
        Worker processes for ``process`` and ``dask-local``.
    scheduler : str, optional
        Dask scheduler address for ``dask`` (``tcp://HOST:PORT``).
    task_timeout : float, optional
        Seconds before a task counts as hung and runs again elsewhere
        (:func:`racketdyn.sweep.run_sweep`; default: 10 × the longest task so far, at least
        60 s).
    shared_store : bool
        ``out`` is on a path every Dask worker can write, at the same absolute path: a
        ``dask`` cluster's workers write their own chunks of ``sweep.zarr`` (checked on each
        worker; default: this process writes them; :func:`racketdyn.sweep.run_sweep`).

    Raises
    ------
    InputError
        ``out`` holds another command's run (its run.json): its files are not replaced; with
        ``shared_store``, a Dask worker that does not see the store.
    racketdyn.sweep.SweepInterrupted
        On Ctrl-C: the workers are stopped and every finished design is kept; run again to
        resume.
    """
    the_spec = spec if isinstance(spec, SweepSpec) else load_sweep_spec(Path(spec))
    if Path(out).is_dir():  # before any engine starts
        _refuse_other_step(Path(out), "sweep")
    executor: AbstractContextManager[Executor | None]
    if engine == "auto":
        executor = nullcontext(None)
    elif engine in ("process", "dask-local") and workers is not None:
        executor = make_executor(engine, workers)
    else:
        executor = make_executor(engine, scheduler=scheduler)
    out_dir = make_out_folder(Path(out))
    # one sweep at a time in a folder (two overwrote each other's parts, silently)
    lock = _lock(out_dir)
    try:
        # a local Dask cluster's forkserver imports while the cluster's scheduler starts
        start_early(engine, the_spec.method)
        dataset = _run(
            the_spec,
            out_dir,
            executor,
            setup.progress,
            setup.figures,
            TaskOptions(task_timeout=task_timeout, shared_store=shared_store),
            setup.command,
        )
    finally:
        lock.unlink(missing_ok=True)
    record = json.loads((out_dir / "run.json").read_text(encoding="utf-8"))
    return SweepResult(
        out_dir,
        [out_dir / name for name in record["outputs"] if name != "run.json"],
        record,
        dataset=dataset,
        spec=the_spec,
        failed=json.loads(dataset.attrs["failed_tasks"]),
    )


def _run(
    the_spec: SweepSpec,
    out_dir: Path,
    executor: AbstractContextManager[Executor | None],
    progress: Progress | None,
    figures: Callable[[Mapping[str, SummaryCurves], Path], list[Path]] | None,
    options: TaskOptions,
    command: Sequence[str] | None,
) -> xr.Dataset:
    """The sweep in its locked folder, on the engine ``executor`` starts."""
    with ExitStack() as stack:
        report(progress, "starting the engine")
        clock = time.perf_counter()
        running = stack.enter_context(executor)
        started = time.perf_counter() - clock
        dataset = run_sweep(
            the_spec,
            out_dir,
            running,
            progress=None
            if progress is None
            else lambda done, total: progress("designs", done, total),
            options=options,
            figures=figures,
            times={"start": started} if running is not None else None,
            when_tasks_done=stack.close,
            command=command_record(command, "sweep"),
        )
    return dataset
