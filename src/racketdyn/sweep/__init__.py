"""Design sweeps: many racket variants × impact points × speeds × swing, on any executor.

A sweep answers a racket maker's "what if" — 5 g of lead at 12 o'clock, a 10 % softer frame,
20 N less tension — with a full map of predictions per variant.  A :class:`SweepSpec` (read from
TOML by :func:`load_sweep_spec`, schema in docs/sweep-file.md) names a base racket and ball, the
impact points and speeds, and the variables with their values; :meth:`SweepSpec.designs` lists
the design variants, as a full factorial or one variable at a time around the base.

:func:`run_sweep` computes each design with :func:`run_task`, a pure function of plain
picklable inputs (:class:`SweepTask`) that builds the variant's racket, ball, modal model and
contact law and calls :func:`racketdyn.impact.predict`, and submits them, a few designs to a
task when designs are small, to any :class:`concurrent.futures.Executor`:
:class:`SerialExecutor` in this process, a :class:`ProcessPool` (replaced when a worker dies),
or Dask through ``dask.distributed.Client.get_executor()``.  :func:`make_executor` builds
each of these (the ``racketdyn sweep`` command line calls it).  Results go, as each task
ends, into one chunked Zarr store, ``out_dir/sweep.zarr`` (one chunk per batch of designs,
written by the worker that computed it): no process holds the whole study.  A rerun skips the
designs recorded there, so an interrupted sweep (Ctrl-C: :class:`SweepInterrupted`) resumes.
A failed design is retried once, then recorded (dataset attributes and ``failures.json``)
while the other results are kept; a worker that dies or hangs costs only its own designs
(:class:`WorkerLostError`, :class:`TaskTimeoutError`).  :func:`open_sweep` reads the store
lazily as an :mod:`xarray` dataset with dimensions ``(design, point, speed, racket_speed,
support)`` — every engine gives the same numbers — and refuses a store whose run has not
finished.

``summary.csv`` (:func:`write_summary_csv`) and the summary figures
(the curves of :func:`~racketdyn.sweep.summary.summary_curves`, drawn by the hook
:func:`racketdyn.plotting.steps.sweep_figures` through the registry of figures) give, for each
variable, the rebound ratio at the face centre and the sweet area (:func:`sweet_area_cm2`:
the face area whose rebound ratio is near the best of the same face) against the variable,
per support.

The impact method is a parameter (``SweepSpec.method``, :data:`METHODS`): ``approximate``
(:func:`racketdyn.impact.predict`) or ``transient``
(:func:`racketdyn.impact.transient.predict_transient`).  The transient method also takes the
``hand`` support, a grip held by a hand and arm (:class:`racketdyn.impact.hand.Hand`), whose
parameters are sweepable (:data:`HAND_VARIABLES`).

The modules follow the data, each importing only those above it:

- :mod:`~racketdyn.sweep.variables`: what a sweep can change, :class:`Variable`;
- :mod:`~racketdyn.sweep.design`: :class:`Design`, :func:`build_design`, :func:`build_hand`;
- :mod:`~racketdyn.sweep.task`: :class:`SweepTask`, :func:`run_task`, :data:`METHODS`, status
  codes, the per-process caches;
- :mod:`~racketdyn.sweep.spec`: :class:`SweepSpec`, its designs, tasks and hash;
- :mod:`~racketdyn.sweep.spec_file`: the TOML reader, :func:`load_sweep_spec`;
- :mod:`~racketdyn.sweep.executors`: :class:`SerialExecutor`, :func:`make_executor`;
- :mod:`~racketdyn.sweep.store`: the chunked store ``sweep.zarr``, :func:`open_sweep`;
- :mod:`~racketdyn.sweep.summary`: metrics and figures from a sweep dataset, chunk by chunk;
- :mod:`~racketdyn.sweep.runner`: the task loop (retries, a lost worker, timeouts, Ctrl-C);
- :mod:`~racketdyn.sweep.run`: :func:`run_sweep`, its :class:`TaskOptions`.

Everything public is importable from :mod:`racketdyn.sweep` itself.
"""

from racketdyn.sweep.design import Design, build_design, build_hand
from racketdyn.sweep.executors import (
    ENGINES,
    EngineKind,
    ProcessPool,
    SerialExecutor,
    make_executor,
    start_early,
)
from racketdyn.sweep.run import DEFAULT_TASKS, SERIAL_IMPACT_LIMIT, TaskOptions, run_sweep
from racketdyn.sweep.runner import SweepInterrupted, TaskTimeoutError, WorkerLostError
from racketdyn.sweep.spec import MODES, SweepSpec
from racketdyn.sweep.spec_file import load_sweep_spec, sweep_spec_from_dict
from racketdyn.sweep.store import open_sweep
from racketdyn.sweep.summary import (
    SWEET_AREA_DEFINITION,
    factorial_view,
    summary_metrics,
    sweet_area_cm2,
    sweet_area_resolution_cm2,
    variable_designs,
    write_summary_csv,
)
from racketdyn.sweep.task import (
    METHOD_SUPPORTS,
    METHODS,
    STATUS_CODES,
    SweepTask,
    TaskOutput,
    run_task,
)
from racketdyn.sweep.variables import HAND_VARIABLES, SCALAR_VARIABLES, Variable

__all__ = [
    "DEFAULT_TASKS",
    "ENGINES",
    "HAND_VARIABLES",
    "METHODS",
    "METHOD_SUPPORTS",
    "MODES",
    "SCALAR_VARIABLES",
    "SERIAL_IMPACT_LIMIT",
    "STATUS_CODES",
    "SWEET_AREA_DEFINITION",
    "Design",
    "EngineKind",
    "ProcessPool",
    "SerialExecutor",
    "SweepInterrupted",
    "SweepSpec",
    "SweepTask",
    "TaskOptions",
    "TaskOutput",
    "TaskTimeoutError",
    "Variable",
    "WorkerLostError",
    "build_design",
    "build_hand",
    "factorial_view",
    "load_sweep_spec",
    "make_executor",
    "open_sweep",
    "run_sweep",
    "run_task",
    "start_early",
    "summary_metrics",
    "sweep_spec_from_dict",
    "sweet_area_cm2",
    "sweet_area_resolution_cm2",
    "variable_designs",
    "write_summary_csv",
]
