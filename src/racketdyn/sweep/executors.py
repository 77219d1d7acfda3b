"""Executors: where sweep tasks run — this process, a process pool, or Dask.

:func:`make_executor` builds a :class:`concurrent.futures.Executor` for
:func:`~racketdyn.sweep.run.run_sweep` (the ``racketdyn sweep`` command line calls it); it
knows nothing of sweeps beyond how many tasks to keep submitted at once.
"""

from __future__ import annotations

import ast
import logging
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from contextlib import contextmanager
from types import FrameType
from typing import Any, Literal, ParamSpec, TypeVar, get_args

from racketdyn.errors import InputError, one_of, require_whole

__all__ = [
    "ENGINES",
    "EngineKind",
    "ProcessPool",
    "SerialExecutor",
    "make_executor",
    "start_early",
]

# the package's logger, racketdyn.sweep: the sweep's messages keep one name
log = logging.getLogger(__package__)

P = ParamSpec("P")
T = TypeVar("T")

EngineKind = Literal["serial", "process", "dask-local", "dask"]
"""Where sweep tasks run (:func:`make_executor`): this process, a local process pool, a local
Dask cluster, or a running Dask scheduler."""
ENGINES: tuple[str, ...] = get_args(EngineKind)
DEFAULT_WORKERS = 2
PROCESSES_PER_CORE = 4
"""Local worker processes allowed per core: more only thrash the machine (a transient sample
or a sweep's task each take a core while they run)."""


def check_local_workers(name: str, count: int) -> int:
    """``count`` worker processes on this machine: a whole number from 1 to
    :data:`PROCESSES_PER_CORE` a core (InputError naming ``name`` otherwise)."""
    count = require_whole(name, count)
    cores = os.cpu_count() or 1
    limit = PROCESSES_PER_CORE * cores
    if count > limit:
        raise InputError(
            f"{name} {count}: more worker processes than this machine runs side by side "
            f"({cores} cores, at most {limit}); give at most {cores}, one a core"
        )
    return count


DASK_MISSING = "the Dask engines need dask.distributed: pip install 'racketdyn[dask]'"
"""What to say when dask.distributed is not installed (the command line says it first)."""


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


WORKER_PRELOAD = ("racketdyn.sweep.runner",)
"""Modules the forkserver imports once, before it forks the pool's workers: each worker then
starts with NumPy, SciPy, numba and racketdyn's impact models loaded, instead of importing
them itself (seconds per worker on a loaded machine, paid again by a replaced pool)."""


def _fork_context() -> Any | None:
    """The fork start method while it is safe, else None.

    Forking copies this process as it is — racketdyn and its libraries already imported, so a
    worker is ready in milliseconds instead of the second a forkserver takes to import them
    (most of a 5 s sweep's serial part, ``benchmarks/bench_sweep.py``).  But a fork copies only
    the thread that forks: a lock another thread holds at that moment (a console, logging, an
    allocator) stays locked in the child for good.  So fork only while this process runs a
    single thread; the pool's workers are then started at once (:meth:`ProcessPool._new`),
    before the pool's own manager thread exists.

    Never on macOS, whatever the threads: its system libraries (Accelerate, which NumPy's
    wheels use there, the Objective-C runtime) start threads of their own and a forked child
    can crash or hang, which is why Python's default there is spawn since 3.8.
    """
    import multiprocessing

    if sys.platform == "darwin" or threading.active_count() > 1:
        return None
    if "fork" not in multiprocessing.get_all_start_methods():
        return None
    return multiprocessing.get_context("fork")


def _release_zarr_threads() -> None:
    """Stop Zarr's I/O thread in this process (idle between calls; Zarr starts it again on its
    next call), so that a pool made after this process read or wrote a sweep's store still
    forks its workers.  Called only between store calls: the main process makes them one at a
    time, in its one thread."""
    sync = sys.modules.get("zarr.core.sync")
    if sync is not None and getattr(sync, "iothread", [None])[0] is not None:
        sync.cleanup_resources()
    # its executor's threads ("asyncio_N") end a moment after it is shut down: on a loaded
    # machine they were still alive when the pool chose fork or forkserver (a forkserver
    # pool, and the main process running designs while it started)
    for thread in threading.enumerate():
        if thread.name.startswith(("asyncio_", "zarr_io")):
            thread.join(timeout=2.0)


def _start_context() -> Any:
    """forkserver where available, else spawn: for a process that runs threads (see
    :func:`_fork_context`).

    The forkserver preloads the main module and :data:`WORKER_PRELOAD`
    (:func:`_start_forkserver`).  It is started once per process: the preload applies if no
    forkserver runs yet.
    """
    import multiprocessing

    if "forkserver" not in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("spawn")
    context = multiprocessing.get_context("forkserver")
    _start_forkserver(context, list(WORKER_PRELOAD))
    return context


def _start_forkserver(context: Any, preload: list[str]) -> None:
    """Start this process's forkserver (if none runs yet) preloading the main script, then
    the modules ``preload``.

    Python before 3.13.8 never preloads ``__main__`` in the forkserver, whatever the preload
    list says (CPython gh-126631, gh-137996: ``forkserver.ensure_running`` looks for a
    ``main_path`` that ``spawn.get_preparation_data`` has named ``init_main_from_path`` since
    2013), so each child ran the main script's top level again: the imports of a script that
    imports xarray cost every local Dask worker 0.3 s more to start (0.39 against 0.08 s, a
    scratch check of 2026-11-26).  Python's own preload, where it works, runs the script
    without its ``sys.argv`` and ``sys.path``, which each worker gets before it imports the
    script: a script reading its arguments, or importing a module beside it, at its top level
    killed the forkserver.  So instead of ``"__main__"`` the forkserver preloads
    :mod:`racketdyn.sweep._main_preload`, which sets both from what this process passes it
    and imports the script as a worker would (a script that raises there is left to the
    workers; one read from standard input, ``<stdin>``, is no file to import: no worker tries).
    Running the script's top level once in the forkserver is what spawn does in every child
    anyway.
    """
    import json
    import multiprocessing.forkserver
    from multiprocessing import spawn

    from racketdyn.sweep import _main_preload

    data = spawn.get_preparation_data("forkserver")
    path = data.get("init_main_from_path")
    main = isinstance(path, str)  # None when run with -m, or with no script (python -c)
    context.set_forkserver_preload([_main_preload.__name__, *preload] if main else preload)
    if main:
        os.environ[_main_preload.ENVIRONMENT] = json.dumps(
            {"main_path": path, "sys_argv": data["sys_argv"], "sys_path": data["sys_path"]}
        )
    try:
        multiprocessing.forkserver.ensure_running()
    finally:
        os.environ.pop(_main_preload.ENVIRONMENT, None)


def _dask_forkserver(extra: tuple[str, ...] = ()) -> bool:
    """Start this process's forkserver, if none runs yet, preloading distributed besides
    :data:`WORKER_PRELOAD` and ``extra`` (then a local Dask cluster forks its workers from it
    instead of starting an interpreter that imports them for each); whether there is a
    forkserver."""
    import multiprocessing

    if "forkserver" not in multiprocessing.get_all_start_methods():
        return False
    context = multiprocessing.get_context("forkserver")
    with _workers_ignore_ctrl_c():  # its children start with Ctrl-C ignored
        _start_forkserver(context, [*WORKER_PRELOAD, "distributed", *extra])
    return True


def start_early(kind: str, method: str | None = None) -> None:
    """Start in the background what an engine will need, while this process goes on (checks
    the parts on disk, starts the cluster's scheduler).

    For ``dask-local``: the forkserver that imports distributed and racketdyn once and forks
    the cluster's workers (:func:`_dask_forkserver`; a second or more of imports, on another
    core meanwhile) and, for the ``transient`` method, loads numba's compiled kernel
    (:mod:`racketdyn.sweep._transient_preload`).  Nothing for the others: a process pool
    forks its workers in milliseconds (:func:`_fork_context`), a remote cluster is running
    already.  Without this call, :func:`make_executor` starts the forkserver itself, without
    the kernel.

    Parameters
    ----------
    kind : str
        The engine (:data:`EngineKind`); any other value starts nothing.
    method : str, optional
        The sweep's impact method.
    """
    if kind == "dask-local":
        _dask_forkserver(("racketdyn.sweep._transient_preload",) if method == "transient" else ())


def _method_of(context: Any) -> str:
    """A multiprocessing context's start method ("" for none)."""
    return "" if context is None else str(context.get_start_method())


def _worker_setup(parent_pid: int) -> None:
    """Run in each pool worker as it starts: leave Ctrl-C to the main process, and exit when
    the main process is gone.

    A terminal sends SIGINT to the whole process group: the main process stops the workers and
    keeps what finished, so the workers ignore it (else each prints a traceback).  Nothing tells
    a worker when the main process is killed (SIGKILL; a forkserver's worker is not even its
    child): a daemon thread waits on the main process (a pidfd where Linux has them, else
    polling its pid every second) and ends the worker with it; the forkserver and the
    resource tracker end once no worker holds their pipes.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(
        target=_exit_with, args=(parent_pid,), name="racketdyn-parent-watch", daemon=True
    ).start()


def _exit_with(parent_pid: int) -> None:
    """Return never: ``os._exit`` this process once ``parent_pid`` has ended."""
    import select

    try:
        descriptor = os.pidfd_open(parent_pid)
    except (AttributeError, OSError):  # not Linux ≥ 5.3: poll
        while _alive(parent_pid):
            time.sleep(1.0)
    else:
        select.select([descriptor], [], [])  # readable once the process has ended
    os._exit(1)


def _alive(pid: int) -> bool:
    if os.getppid() == 1:  # re-parented: whoever started us is gone
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # it exists, owned by someone else (pid reused)
        return False
    return True


class ProcessPool(Executor):
    """A local process pool that survives a dead worker and stops at once when asked.

    A :class:`~concurrent.futures.ProcessPoolExecutor` whose worker dies (killed, out of
    memory, ``os._exit`` in a task) is broken for good: every pending future fails with
    :class:`~concurrent.futures.process.BrokenProcessPool` and it takes no more tasks.
    :meth:`renew` replaces it with a fresh pool of the same size, so
    :func:`~racketdyn.sweep.run.run_sweep` can rerun the lost tasks; :meth:`stop` kills the
    workers (a task that hangs, Ctrl-C) instead of waiting for them.  Workers ignore SIGINT
    and exit when the process that made the pool ends (:func:`_worker_setup`).

    Parameters
    ----------
    workers : int
        Worker processes.
    pool : ProcessPoolExecutor, optional
        A pool to take over (its size and start method are kept for the replacements); by
        default a new one.
    """

    def __init__(self, workers: int, pool: ProcessPoolExecutor | None = None) -> None:
        self.workers = workers
        self._context = None if pool is None else pool._mp_context
        self._pool = self._new() if pool is None else pool
        self.renewals = 0

    @classmethod
    def adopt(cls, pool: ProcessPoolExecutor) -> ProcessPool:
        """A :class:`ProcessPool` that takes over a pool made elsewhere (not shut down here
        unless replaced).

        Parameters
        ----------
        pool : ProcessPoolExecutor
            The pool.
        """
        return cls(int(getattr(pool, "_max_workers", DEFAULT_WORKERS)), pool)

    @property
    def start_method(self) -> str:
        """How the current pool started its workers: ``fork``, ``forkserver`` or ``spawn``."""
        return _method_of(self._pool._mp_context)

    @property
    def started_at_once(self) -> bool:
        """Whether the current pool's workers were forked, all at once, when it was made."""
        return self.start_method == "fork"

    @property
    def _max_workers(self) -> int:  # read by _in_flight_limit, as for a ProcessPoolExecutor
        return self.workers

    def _new(self) -> ProcessPoolExecutor:
        """A fresh pool: forked now while this process runs one thread (its workers ready at
        once, :attr:`started_at_once`), else started by forkserver with its first task."""
        if self._context is None:
            _release_zarr_threads()
        forked = _fork_context() if self._context is None else None
        context = forked or self._context or _start_context()
        pool = ProcessPoolExecutor(
            max_workers=self.workers,
            mp_context=context,
            initializer=_worker_setup,
            initargs=(os.getpid(),),
        )
        if forked is not None:
            # a fork pool forks all its workers on its first submission, before it starts its
            # manager thread: do it now, while this process still runs one thread
            pool.submit(os.getpid)
        return pool

    def submit(self, fn: Callable[P, T], /, *args: P.args, **kwargs: P.kwargs) -> Future[T]:
        """Submit ``fn(*args, **kwargs)`` to the current pool.

        Parameters
        ----------
        fn : callable
            The task (picklable, as its arguments).
        *args, **kwargs
            Its arguments.
        """
        return self._pool.submit(fn, *args, **kwargs)

    def stop(self) -> None:
        """Kill the workers now; every pending future ends (cancelled or broken)."""
        processes = list((getattr(self._pool, "_processes", None) or {}).values())
        for process in processes:
            if process.is_alive():
                process.kill()
        self._pool.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            process.join(timeout=5.0)

    def renew(self) -> None:
        """Replace the pool (broken, or with a worker that hangs) by a fresh one."""
        self.stop()
        self._pool = self._new()
        self.renewals += 1
        log.info("process pool replaced (%d so far)", self.renewals)

    def shutdown_replacements(self) -> None:
        """Shut down the current pool if it replaced the one taken over (:meth:`adopt`): that
        one belongs to whoever made it."""
        if self.renewals:
            self.shutdown(wait=True)

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        """Shut the current pool down (see :meth:`ProcessPoolExecutor.shutdown`).

        Parameters
        ----------
        wait : bool
            Wait for the running tasks.
        cancel_futures : bool
            Cancel the tasks not yet started.
        """
        self._pool.shutdown(wait=wait, cancel_futures=cancel_futures)


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
        :class:`ProcessPool` of ``workers`` processes (forked at once while this process runs
        a single thread, else started by forkserver where available, else spawn — fork is
        unsafe in a process with threads; replaced when a worker dies, killed on an error or
        Ctrl-C rather than waited for).  ``dask-local``: a
        ``dask.distributed.LocalCluster`` of ``workers`` single-threaded worker processes and
        a client to it.  ``dask``: a client to a running
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
    if kind in ("process", "dask-local"):
        check_local_workers("`workers`", workers)
    else:
        require_whole("`workers`", workers)
    if kind == "dask":
        if not scheduler:
            raise InputError("the dask engine needs a scheduler address, e.g. tcp://HOST:8786")
    elif scheduler is not None:
        raise InputError(f"a scheduler address is for the dask engine only (not {kind})")
    if kind == "serial":
        yield SerialExecutor()
        return
    if kind in ("process", "dask-local"):
        _check_main_guard()
    if kind == "process":
        pool = ProcessPool(workers)
        try:
            yield pool
        except BaseException:
            pool.stop()
            raise
        pool.shutdown(wait=True)
        return
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise InputError(DASK_MISSING) from None
    if kind == "dask-local":
        import dask

        forkserver = _dask_forkserver()
        held = _HeldCtrlC()
        levels = _LoggerLevels(INTERRUPT_LOGGERS)
        # Dask's nannies set MALLOC_TRIM_THRESHOLD_ on their workers, which switches off glibc's
        # adaptive mmap threshold: every large temporary array is then mapped and unmapped
        # afresh, and a sweep task runs ≈ 1.7 times slower.  Leave the allocator alone.
        with (
            levels,  # set back after the cluster closed (quiet_interrupted_cluster)
            dask.config.set(
                {
                    "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None,
                    # where this process shows no info of distributed (the command line
                    # without -v), its workers log errors only: each would warn of every task
                    # cancelled by Ctrl-C or a timeout
                    "distributed.nanny.pre-spawn-environ.DASK_LOGGING__DISTRIBUTED": (
                        "error"
                        if logging.getLogger("distributed").getEffectiveLevel() >= logging.WARNING
                        else "info"
                    ),
                    # workers forked from a forkserver that has imported distributed and
                    # racketdyn (_dask_forkserver): no interpreter start and imports per worker
                    **(
                        {"distributed.worker.multiprocessing-method": "forkserver"}
                        if forkserver
                        else {}
                    ),
                    "distributed.worker.preload": ["racketdyn.sweep._dask_worker"],
                    **LOCAL_DASK_QUIET,
                }
            ),
            # spawned workers inherit an ignored SIGINT, so this process ignores it while
            # they start; workers forked from the forkserver ignore it already, and a Ctrl-C
            # while the cluster starts is held back until it runs (then it closes cleanly)
            held if forkserver else _workers_ignore_ctrl_c(),
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
            _restore_ctrl_c()
            held.release()  # a Ctrl-C pressed while the cluster started acts now
            log.info("local Dask cluster: %d workers, dashboard %s", workers, client.dashboard_link)
            # how the nannies start their workers (the "process" engine's start_method)
            yield _dask_executor(client, "forkserver" if forkserver else "spawn")
        return
    try:
        client = Client(scheduler, timeout="20s")  # type: ignore[no-untyped-call]
    except (OSError, TimeoutError, ValueError) as error:
        raise InputError(f"scheduler {scheduler}: cannot connect ({error})") from None
    with _LoggerLevels(INTERRUPT_LOGGERS), client:
        yield _dask_executor(client)


INTERRUPT_LOGGERS = (
    "distributed.scheduler",
    "distributed.client",
    "distributed.core",
    "distributed.batched",
    "distributed.nanny",
    "distributed.worker",
)
"""The loggers of distributed's parts in this process (a local cluster's scheduler, the
client) that report the tasks a Ctrl-C cancelled while it closes."""


def quiet_interrupted_cluster() -> None:
    """After a Ctrl-C, before the sweep's Dask tasks are cancelled: the scheduler and the client
    in this process would report each task they could no longer gather ("Couldn't gather keys
    … forgotten", "rescheduling") — the sweep says itself what it kept.  Unless this process
    shows distributed's info (``-v``), their loggers are set to critical until the cluster or
    the client has closed (:class:`_LoggerLevels`)."""
    if logging.getLogger("distributed").getEffectiveLevel() < logging.WARNING:
        return
    for name in INTERRUPT_LOGGERS:
        logging.getLogger(name).setLevel(logging.CRITICAL)


class _LoggerLevels:
    """A context that sets the named loggers' levels back to what they were on entry."""

    def __init__(self, names: Sequence[str]) -> None:
        self._names = tuple(names)
        self._levels: dict[str, int] = {}

    def __enter__(self) -> None:
        self._levels = {name: logging.getLogger(name).level for name in self._names}

    def __exit__(self, *_: object) -> None:
        for name, level in self._levels.items():
            logging.getLogger(name).setLevel(level)


LOCAL_DASK_QUIET: dict[str, Any] = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.scheduler.work-stealing-interval": "1s",
}
"""Dask settings of a local cluster: its dashboard's sampling slowed or off.  By default each
worker samples its task thread's stack every 10 ms for the dashboard's profile, checks its
event loop every 20 ms and its memory every 100 ms, and the scheduler — in this process —
looks for work to steal every 100 ms: on two cores all of it competes with the two workers'
tasks.  ``bench_sweep``-like A/B, 4 pairs each, 10⁶ approximate impacts (2026-11-26): the
2-worker tasks' summed time 4.83–5.00 s instead of 5.23–5.56 s, the run 2.87–2.99 s instead
of 3.05–3.46 s, 1-to-2-worker speed-up 1.80–1.93× instead of 1.65–1.82×.  The dashboard still
works; its profile page stays empty."""


def _check_main_guard() -> None:
    """Refuse local worker processes started from a script's top level.

    Worker processes started by forkserver or spawn import the main script (Python's
    multiprocessing rule; the forkserver imports it once, :mod:`._main_preload`): a script that
    runs a sweep at its top level, outside ``if __name__ == "__main__":``, runs it again in
    each import — sweeps whose designs all fail, writing into the same folder as the real one
    (seen on 2026-11-26: three runs, two of them all NaN, one ``sweep.nc``).  The script's
    source shows whether the call sits under the guard: no ``<module>`` frame of a file-based
    ``__main__`` on the stack (the command line, pytest, a notebook) or a call inside the
    guard is fine.  Our own check because Python's own comes only in the workers, too late.

    Raises
    ------
    InputError
        The call is at the top level of the main script, outside the guard.
    """
    main = sys.modules.get("__main__")
    path = getattr(main, "__file__", None)
    if not isinstance(path, str) or not os.path.isfile(path):
        return
    if str(getattr(getattr(main, "__spec__", None), "name", "")).endswith(".__main__"):
        return  # python -m package: multiprocessing never imports a package's __main__ again
    frame: FrameType | None = sys._getframe(1)
    while frame is not None and not (
        frame.f_code.co_name == "<module>" and frame.f_globals.get("__name__") == "__main__"
    ):
        frame = frame.f_back
    if frame is None or not _same_file(frame.f_code.co_filename, path):
        return  # e.g. python -m cProfile script.py: the workers import cProfile, not the script
    line = frame.f_lineno
    try:
        with open(path, encoding="utf-8") as handle:
            tree = ast.parse(handle.read())
    except (OSError, SyntaxError, UnicodeDecodeError):
        return
    for node in ast.walk(tree):  # the guarded branch only: the other is what workers run
        branch = _main_branch(node) if isinstance(node, ast.If) else []
        if branch and branch[0].lineno <= line <= (branch[-1].end_lineno or branch[-1].lineno):
            return
    raise InputError(
        f"{path}, line {line}: a sweep on worker processes is started at the top level of the "
        "script; each worker imports the script and would run it again: put the code that runs "
        'the sweep under if __name__ == "__main__":'
    )


def _same_file(one: str, other: str) -> bool:
    try:
        return os.path.samefile(one, other)
    except OSError:
        return False


def _main_branch(node: ast.If) -> list[ast.stmt]:
    """The branch of an ``if`` that runs only as the main script: the body under
    ``__name__ == "__main__"`` (alone or in an ``and``), the ``else`` under
    ``__name__ != "__main__"``; none for any other test."""
    test = node.test
    if _compares_main(test, ast.Eq) or (
        isinstance(test, ast.BoolOp)
        and isinstance(test.op, ast.And)
        and any(_compares_main(value, ast.Eq) for value in test.values)
    ):
        return node.body
    if _compares_main(test, ast.NotEq):
        return node.orelse
    return []


def _compares_main(test: ast.expr, op: type[ast.cmpop]) -> bool:
    """Whether ``test`` is ``__name__ <op> "__main__"`` (either way round)."""
    if not (isinstance(test, ast.Compare) and len(test.ops) == 1):
        return False
    if not isinstance(test.ops[0], op):
        return False
    sides = [test.left, test.comparators[0]]
    return any(isinstance(x, ast.Name) and x.id == "__name__" for x in sides) and any(
        isinstance(x, ast.Constant) and x.value == "__main__" for x in sides
    )


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


_SAVED_SIGINT: list[Any] = []


@contextmanager
def _workers_ignore_ctrl_c() -> Iterator[None]:
    """Start processes with SIGINT ignored (the disposition survives their exec), so a
    terminal's Ctrl-C to the process group reaches only this process, which stops the sweep;
    each Dask worker would otherwise print a KeyboardInterrupt traceback.  Restored by
    :func:`_restore_ctrl_c` once the workers run, or on leaving."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _SAVED_SIGINT.append(signal.signal(signal.SIGINT, signal.SIG_IGN))
    try:
        yield
    finally:
        _restore_ctrl_c()


class _HeldCtrlC:
    """A context that holds a Ctrl-C back while something starts that must not be stopped
    half-way (a local Dask cluster: interrupted inside its start, it stayed half up, its
    forked workers and its exit handler printed tracebacks), until :meth:`release`.

    This process ignored SIGINT instead while the cluster started, and a Ctrl-C in those
    0.1-0.8 s was lost: the sweep ran to its end (a new-user trial, 2026-11-26).  Only in the
    main thread, where Python runs signal handlers.
    """

    def __init__(self) -> None:
        self.pressed = False
        self._held = False  # not _previous is None: signal.signal gives None for a C handler
        self._previous: Any = None

    def _note(self, signum: int, frame: FrameType | None) -> None:
        self.pressed = True

    def __enter__(self) -> _HeldCtrlC:
        if threading.current_thread() is threading.main_thread():
            self._previous = signal.signal(signal.SIGINT, self._note)
            self._held = True
        return self

    def __exit__(self, *exc: object) -> None:
        self._restore()

    def _restore(self) -> bool:
        if not self._held:
            return False
        signal.signal(signal.SIGINT, self._previous or signal.SIG_DFL)
        self._held = False
        return True

    def release(self) -> None:
        """Give Ctrl-C back; raise KeyboardInterrupt if it was pressed meanwhile."""
        if self._restore() and self.pressed:
            raise KeyboardInterrupt


@contextmanager
def ctrl_c_as_flag(executor: object) -> Iterator[Callable[[], bool]]:
    """While a sweep waits on ``executor``: a function saying whether Ctrl-C was pressed.

    On a Dask executor a Ctrl-C is noted, not raised, and the caller raises it between its
    polls: raised where it lands, in the event loop's wake-up (``_write_to_self``, called as
    this process hands the loop a task), asyncio logged it and swallowed it, and the sweep ran
    to its end with exit status 0 (a CI run under load).  Other executors keep Python's own
    KeyboardInterrupt (a process pool's start may run a task here, which a flag would wait
    out).  Only in the main thread, where Python runs signal handlers.
    """
    if not getattr(executor, "ctrl_c_at_polls", False):
        yield lambda: False
        return
    with _HeldCtrlC() as held:
        yield lambda: held.pressed


def _restore_ctrl_c() -> None:
    while _SAVED_SIGINT:
        signal.signal(signal.SIGINT, _SAVED_SIGINT.pop())


async def _cascade_future(task: Any, future: Future[Any]) -> None:
    """Pass a Dask task's outcome to its concurrent future, as ``distributed.cfexecutor``'s
    ``_cascade_future`` does, and a task cancelled between finishing and the gathering of its
    result (the client closed by a Ctrl-C or a timeout) as cancelled.

    There distributed's cascade raises ``FutureCancelledError`` into the event loop, which
    tornado logs with its traceback on the console (an interrupted local Dask sweep under load:
    seen in CI, 2026-11-27).  Written here because distributed's cannot be told so.
    """
    from distributed.cfexecutor import _cascade_future as cascade
    from distributed.client import FutureCancelledError

    try:
        await cascade(task, future)
    except FutureCancelledError:
        if future.cancel():
            future.set_running_or_notify_cancel()  # wakes wait() and as_completed()


def _dask_executor(client: Any, start_method: str = "") -> Executor:
    """``client.get_executor(pure=False)`` that can also stop a hung task's worker, and says
    how its workers were started (``start_method``: "" for a cluster not started here)."""
    from distributed.cfexecutor import ClientExecutor

    class DaskExecutor(ClientExecutor):
        """A Dask client's executor that knows the Dask task behind each future, so
        :meth:`stop_task` can restart the worker running it (a thread cannot be stopped)."""

        ctrl_c_at_polls = True  # ctrl_c_as_flag: a Ctrl-C in the event loop is swallowed

        def __init__(self, client: Any, start_method: str) -> None:
            super().__init__(client, pure=False)  # type: ignore[no-untyped-call]
            self._keys: dict[Future[Any], str] = {}
            self.start_method = start_method

        def submit(self, fn: Any, *args: Any, **kwargs: Any) -> Any:  # type: ignore[override]
            task = self._client.submit(fn, *args, pure=False, **kwargs)
            self._futures.add(task)
            future: Future[Any] = self._wrap_future(task)
            self._keys[future] = task.key
            future.add_done_callback(lambda done: self._keys.pop(done, None))
            return future

        def _wrap_future(self, task: Any) -> Future[Any]:
            """``ClientExecutor._wrap_future`` with :func:`_cascade_future`: cancelling the
            concurrent future cancels the task, the task's outcome ends the future."""
            future: Future[Any] = Future()

            def cancel_task(done: Future[Any]) -> None:
                if done.cancelled() and task.status != "cancelled":
                    task.cancel()

            future.add_done_callback(cancel_task)
            self._client.loop.add_callback(_cascade_future, task, future)
            return future

        def stop_task(self, future: Future[Any]) -> None:
            """Cancel a task and restart the worker that runs it (through its nanny), so the
            scheduler does not queue the retry behind the hung thread; where the worker cannot
            be restarted, the task is only abandoned."""
            key = self._keys.get(future)
            try:
                processing = self._client.processing()
            except Exception:  # the scheduler cannot say: abandon it
                processing = {}
            hung = [worker for worker, keys in processing.items() if key in keys]
            future.cancel()
            if hung:
                try:
                    self._client.restart_workers(hung, timeout=60, raise_for_error=False)
                except Exception as error:  # no nanny, an older scheduler: abandon it
                    log.warning("could not restart the Dask worker %s: %s", hung, error)

    return DaskExecutor(client, start_method)


def on_each_worker(executor: Executor, fn: Callable[..., T], *args: Any) -> dict[str, T]:
    """``fn(*args)`` run on each worker of a Dask executor now connected, by worker address
    (``Client.run``); nothing for any other executor.

    Parameters
    ----------
    executor : Executor
        The executor (:func:`make_executor`).
    fn : callable
        A function importable on the workers (not a lambda), which should not raise.
    *args
        Its arguments.
    """
    client = getattr(executor, "_client", None)
    if client is None:
        return {}
    return dict(client.run(fn, *args))


def _local_workers(executor: Executor) -> bool:
    """Whether the executor's workers run on this machine (and see its files): then each
    worker writes its own part files, in parallel, and only small records travel back."""
    if isinstance(executor, SerialExecutor | ProcessPool | ProcessPoolExecutor):
        return True
    client = getattr(executor, "_client", None)
    cluster = getattr(client, "cluster", None)
    return type(cluster).__name__ == "LocalCluster"
