"""Executors: where sweep tasks run — this process, a process pool, or Dask.

:func:`make_executor` builds a :class:`concurrent.futures.Executor` for
:func:`~racketdyn.sweep.run.run_sweep` (the ``racketdyn sweep`` command line calls it); it
knows nothing of sweeps beyond how many tasks to keep submitted at once.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterator
from concurrent.futures import Executor, Future
from contextlib import contextmanager
from typing import Literal, ParamSpec, TypeVar, get_args

from racketdyn.errors import InputError, one_of, require_whole

__all__ = ["ENGINES", "EngineKind", "SerialExecutor", "make_executor"]

# the package's logger, racketdyn.sweep: the sweep's messages keep one name
log = logging.getLogger(__package__)

P = ParamSpec("P")
T = TypeVar("T")

EngineKind = Literal["serial", "process", "dask-local", "dask"]
"""Where sweep tasks run (:func:`make_executor`): this process, a local process pool, a local
Dask cluster, or a running Dask scheduler."""
ENGINES: tuple[str, ...] = get_args(EngineKind)
DEFAULT_WORKERS = 2


class SerialExecutor(Executor):
    """An executor that runs each task in this process, at once, when it is submitted."""

    def submit(self, fn: Callable[P, T], /, *args: P.args, **kwargs: P.kwargs) -> Future[T]:
        """Run ``fn(*args, **kwargs)`` now; return a finished future with its result or error.

        Parameters
        ----------
        fn : callable
            The task.
        *args, **kwargs
            Its arguments.
        """
        future: Future[T] = Future()
        try:
            result = fn(*args, **kwargs)
        except Exception as error:  # the future carries it, as a pool's would
            future.set_exception(error)
        else:
            future.set_result(result)
        return future


@contextmanager
def make_executor(
    kind: EngineKind, workers: int = DEFAULT_WORKERS, scheduler: str | None = None
) -> Iterator[Executor]:
    """An executor for :func:`run_sweep`, as a context manager that shuts it down on exit.

    The ``racketdyn sweep`` command line calls this: ``--serial`` → ``serial``, ``--workers N``
    → ``process``, ``--dask-local N`` → ``dask-local``, ``--scheduler tcp://HOST:PORT`` →
    ``dask``.

    Parameters
    ----------
    kind : {"serial", "process", "dask-local", "dask"}
        ``serial``: this process (:class:`SerialExecutor`).  ``process``: a local
        :class:`~concurrent.futures.ProcessPoolExecutor` of ``workers`` processes (started by
        forkserver where available, else spawn: never fork, which is unsafe in a process with
        threads).  ``dask-local``: a ``dask.distributed.LocalCluster`` of ``workers``
        single-threaded worker processes and a client to it.  ``dask``: a client to a running
        Dask scheduler at ``scheduler``.  Dask engines use ``Client.get_executor()``; their
        workers need racketdyn installed.
    workers : int
        Worker processes for ``process`` and ``dask-local``.
    scheduler : str, optional
        Scheduler address for ``dask``, e.g. ``tcp://10.0.0.5:8786``.

    Yields
    ------
    concurrent.futures.Executor
        The executor.  The Dask client and a local cluster are closed on exit.
    """
    one_of("engine", kind, ENGINES)
    require_whole("workers", workers)
    if kind == "dask":
        if not scheduler:
            raise InputError("the dask engine needs a scheduler address, e.g. tcp://HOST:8786")
    elif scheduler is not None:
        raise InputError(f"a scheduler address is for the dask engine only (not {kind})")
    if kind == "serial":
        yield SerialExecutor()
        return
    if kind == "process":
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        methods = multiprocessing.get_all_start_methods()
        context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
        with ProcessPoolExecutor(max_workers=workers, mp_context=context) as pool:
            yield pool
        return
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise InputError(
            "the Dask engines need dask.distributed: pip install 'racketdyn[dask]'"
        ) from None
    if kind == "dask-local":
        import dask

        # Dask's nannies set MALLOC_TRIM_THRESHOLD_ on their workers, which switches off glibc's
        # adaptive mmap threshold: every large temporary array is then mapped and unmapped
        # afresh, and a sweep task runs ≈ 1.7 times slower.  Leave the allocator alone.
        with (
            dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}),
            LocalCluster(  # type: ignore[no-untyped-call]
                # the scheduler's HTTP server (dashboard if bokeh is installed) on a free port:
                # with None it still takes 8787, and warns and leaks a socket where that is taken
                n_workers=workers,
                threads_per_worker=1,
                processes=True,
                dashboard_address=":0",
            ) as cluster,
            Client(cluster) as client,  # type: ignore[no-untyped-call]
        ):
            log.info("local Dask cluster: %d workers, dashboard %s", workers, client.dashboard_link)
            yield client.get_executor(pure=False)
        return
    try:
        client = Client(scheduler, timeout="20s")  # type: ignore[no-untyped-call]
    except (OSError, TimeoutError, ValueError) as error:
        raise InputError(f"scheduler {scheduler}: cannot connect ({error})") from None
    with client:
        yield client.get_executor(pure=False)  # type: ignore[no-untyped-call]


def _in_flight_limit(executor: Executor) -> int:
    """How many tasks to keep submitted at once: enough to keep every worker busy."""
    if isinstance(executor, SerialExecutor):
        return 1
    workers = getattr(executor, "_max_workers", None)  # ProcessPool/ThreadPoolExecutor
    if isinstance(workers, int) and workers > 0:
        return 2 * workers
    client = getattr(executor, "_client", None)  # dask.distributed ClientExecutor
    if client is not None:
        try:
            threads = int(sum(client.nthreads().values()))
        except Exception:  # a client that cannot say: fall back to the default
            threads = 0
        if threads > 0:
            return 2 * threads
    return 64
