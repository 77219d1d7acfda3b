"""Writing a step's figures: built here, drawn here and in one helper process at once.

A step builds its figures (cheap: artists only) into a :class:`FigureBatch`, then
:meth:`FigureBatch.render` draws and writes them. Drawing is most of a figure's cost (layout,
Agg, PNG); with two or more figures in a batch and a helper process allowed, the helper takes
figures from the front of the batch (pickled through a pipe) while this process draws from the
back, so two cores draw at once. The helper is one ``python`` process started on first use and
kept for the rest of the run (``racketdyn demo`` starts it once); it imports matplotlib alone.
If it cannot start or dies, this process draws everything. The files are the same either way
(same pixels, same bytes).

``RACKETDYN_FIGURE_WORKERS=0`` in the environment draws everything in this process; the
default is one helper on a machine with two or more cores, none on one core.
"""

from __future__ import annotations

import atexit
import logging
import os
import pickle
import struct
import subprocess
import sys
import threading
import warnings
from collections import deque
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from racketdyn.__about__ import __version__
from racketdyn.plotting import _png

__all__ = ["FigureBatch", "save_figure", "start_helper"]

log = logging.getLogger(__name__)

SOFTWARE = f"racketdyn {__version__}"
_ENV = "RACKETDYN_FIGURE_WORKERS"
_HEADER = struct.Struct("<Q")


def _rc_changes() -> dict[str, Any]:
    """The rcParams that differ from matplotlib's defaults (sent with each figure)."""
    defaults = matplotlib.rcParamsDefault
    return {
        key: value
        for key, value in dict.items(matplotlib.rcParams)
        if key != "backend" and value != dict.__getitem__(defaults, key)
    }


@dataclass
class _Job:
    figure: Figure
    path: Path
    errstate: dict[str, Any]
    rc: dict[str, Any]
    payload: bytes = b""

    def here(self) -> dict[str, Any]:
        return {"figure": self.figure, **self._common()}

    def there(self) -> dict[str, Any]:
        return {"payload": self.payload, **self._common()}

    def _common(self) -> dict[str, Any]:
        return {
            "path": str(self.path),
            "errstate": self.errstate,
            "rc": self.rc,
            "software": SOFTWARE,
        }


def save_figure(figure: Figure, path: Path) -> Path:
    """Draw one figure and write it as a PNG in this process (closes the figure).

    Parameters
    ----------
    figure : Figure
        The figure.
    path : Path
        The file to write.

    Returns
    -------
    Path
        ``path``.
    """
    plt.close(figure)
    return _png.write_png(figure, Path(path), SOFTWARE)


# --- the helper process ----------------------------------------------------------------------
_WORKER_CODE = """
import importlib.util, pickle, struct, sys, traceback, warnings
spec = importlib.util.spec_from_file_location("_racketdyn_png", sys.argv[1])
png = importlib.util.module_from_spec(spec)
spec.loader.exec_module(png)
header = struct.Struct("<Q")
source, sink = sys.stdin.buffer, sys.stdout.buffer
def send(message):
    data = pickle.dumps(message)
    sink.write(header.pack(len(data)) + data)
    sink.flush()
send(("ready", None, []))
while True:
    head = source.read(header.size)
    if len(head) < header.size:
        break
    job = pickle.loads(source.read(header.unpack(head)[0]))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            png.render_job(job)
            status, detail = "ok", None
        except Exception:
            status, detail = "error", traceback.format_exc()
    send((status, detail, [(w.category, str(w.message)) for w in caught]))
"""


class _WorkerGoneError(Exception):
    """The helper process could not take a figure."""


class _Worker:
    """One helper process and its pipes; used by one thread at a time."""

    def __init__(self) -> None:
        env = {**os.environ, "MPLBACKEND": "Agg", "OPENBLAS_NUM_THREADS": "1"}
        env["OMP_NUM_THREADS"] = "1"
        self.process = subprocess.Popen(
            [sys.executable, "-c", _WORKER_CODE, str(Path(_png.__file__))],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            env=env,
        )
        self.ready = False
        self.broken = False

    def _receive(self) -> tuple[str, str | None, list[tuple[type[Warning], str]]]:
        stdout: IO[bytes] | None = self.process.stdout
        assert stdout is not None
        head = stdout.read(_HEADER.size)
        if len(head) < _HEADER.size:
            raise _WorkerGoneError("the figure helper process ended")
        message: tuple[str, str | None, list[tuple[type[Warning], str]]] = pickle.loads(
            stdout.read(_HEADER.unpack(head)[0])
        )
        return message

    def render(
        self, job: dict[str, Any]
    ) -> tuple[str, str | None, list[tuple[type[Warning], str]]]:
        """Send one job and wait for its outcome (status, traceback, warnings)."""
        if self.broken:
            raise _WorkerGoneError("the figure helper process failed before")
        try:
            if not self.ready:
                self._receive()  # "ready": matplotlib imported
                self.ready = True
            stdin = self.process.stdin
            assert stdin is not None
            data = pickle.dumps(job)
            stdin.write(_HEADER.pack(len(data)) + data)
            stdin.flush()
            return self._receive()
        except (OSError, EOFError, pickle.PickleError, _WorkerGoneError) as error:
            self.broken = True
            raise _WorkerGoneError(str(error)) from error

    def close(self) -> None:
        try:
            if self.process.stdin is not None:
                self.process.stdin.close()
            self.process.wait(timeout=5)
        except (OSError, subprocess.TimeoutExpired):
            self.process.kill()
            self.process.wait()
        finally:
            if self.process.stdout is not None:
                self.process.stdout.close()


_worker: _Worker | None = None
_worker_lock = threading.Lock()


def _workers_allowed() -> int:
    text = os.environ.get(_ENV)
    if text is not None:
        try:
            return max(0, min(1, int(text)))
        except ValueError:
            log.warning("%s=%r is not a whole number: no figure helper process", _ENV, text)
            return 0
    return 1 if (os.cpu_count() or 1) >= 2 else 0


def _shared_worker() -> _Worker | None:
    """The run's helper process, started on first use (None if not allowed or not startable)."""
    global _worker
    if not _workers_allowed():
        return None
    with _worker_lock:
        if _worker is not None and (_worker.broken or _worker.process.poll() is not None):
            _worker.close()
            _worker = None
        if _worker is None:
            try:
                _worker = _Worker()
            except OSError as error:
                log.info("no figure helper process (%s): drawing here", error)
                return None
        return _worker


def start_helper() -> bool:
    """Start the helper process now, so that it has imported matplotlib by the first figure.

    A command that will draw several figures calls this before its computation; the first
    :class:`FigureBatch` starts it otherwise. Returns whether a helper process runs.
    """
    return _shared_worker() is not None


@atexit.register
def _close_worker() -> None:
    global _worker
    with _worker_lock:
        if _worker is not None:
            _worker.close()
            _worker = None


# --- batches -------------------------------------------------------------------------------------
_Outcome = tuple[_Job, str, str | None, list[tuple[type[Warning], str]]]


class FigureBatch:
    """The figures of one step: :meth:`add` them as they are built, then :meth:`render`.

    With a helper process, it takes figures from the front of the batch as soon as they are
    added (so it draws while this process builds the next ones or computes what they need);
    :meth:`render` draws the rest here, from the back.
    """

    def __init__(self) -> None:
        self._jobs: list[_Job] = []
        self._queue: deque[_Job] = deque()
        self._ready = threading.Condition()
        self._closed = False
        self._outcomes: list[_Outcome] = []
        self._left: list[_Job] = []
        self._worker = _shared_worker()  # starts it: it imports while the figures are built
        self._feeder: threading.Thread | None = None

    def add(self, figure: Figure, path: Path) -> Path:
        """Queue ``figure`` for ``path`` (closed in pyplot now, drawn by :meth:`render`).

        The NumPy error state and rcParams in force now are the ones it is drawn under.

        Parameters
        ----------
        figure : Figure
            The built figure.
        path : Path
            Its file.

        Returns
        -------
        Path
            ``path``.
        """
        plt.close(figure)
        job = _Job(figure, Path(path), dict(np.geterr()), _rc_changes())
        self._jobs.append(job)
        if self._worker is not None and not self._worker.broken:
            try:
                job.payload = pickle.dumps(figure)
            except Exception as error:  # an artist that does not pickle: drawn here
                log.info("%s is drawn here: its figure does not pickle (%s)", path, error)
            if self._feeder is None:
                self._feeder = threading.Thread(target=self._feed, daemon=True)
                self._feeder.start()
        with self._ready:
            self._queue.append(job)
            self._ready.notify()
        return Path(path)

    def _feed(self) -> None:
        """Hand the helper process figures from the front of the queue until render() ends."""
        worker = self._worker
        assert worker is not None
        while True:
            with self._ready:
                while not self._queue and not self._closed:
                    self._ready.wait()
                if not self._queue:
                    return
                job = self._queue.popleft()
            if not job.payload:
                self._left.append(job)
                continue
            try:
                status, detail, caught = worker.render(job.there())
            except _WorkerGoneError as error:
                log.info("figure helper process: %s; drawing here", error)
                self._left.append(job)
                return
            self._outcomes.append((job, status, detail, caught))

    def render(self) -> list[Path]:
        """Draw and write every queued figure; returns their paths in the order added.

        Warnings raised while drawing are raised again here; the first error is raised after
        every other figure has been written.
        """
        with self._ready:
            self._closed = True
            self._ready.notify()
        errors: list[BaseException] = []
        while True:
            with self._ready:
                if not self._queue:
                    break
                job = self._queue.pop()
            try:
                _png.render_job(job.here())
            except Exception as error:  # raised below, after the other figures
                errors.append(error)
        if self._feeder is not None:
            self._feeder.join()
        for job in self._left:  # the helper failed: draw its share here
            _png.render_job(job.here())
        for job, status, detail, caught in self._outcomes:
            for category, message in caught:
                warnings.warn(message, category, stacklevel=2)
            if status != "ok":
                errors.append(RuntimeError(f"drawing {job.path.name} failed:\n{detail}"))
        if errors:
            raise errors[0]
        return [job.path for job in self._jobs]
