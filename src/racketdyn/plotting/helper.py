"""The figure helper process: one ``python`` process that draws figures beside this one.

It is started by the first :class:`racketdyn.plotting.render.FigureBatch`, or earlier by
:func:`start_helper` (a command that will draw calls it at its start, so that the helper
imports matplotlib while this process imports the library and computes), and kept for the
rest of the run. It loads :mod:`racketdyn.plotting._png` by its file path: it starts with
matplotlib alone. This module imports neither matplotlib nor NumPy, so starting the helper
costs this process nothing it would not pay anyway.

``RACKETDYN_FIGURE_WORKERS=0`` in the environment: no helper; the default is one helper on a
machine with two or more cores, none on one core. A helper that was started but never given a
figure (the step failed first, or drew one figure alone) is stopped at exit without waiting
for its imports.
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
from pathlib import Path
from typing import IO, Any

__all__ = ["Worker", "WorkerGoneError", "shared_worker", "start_helper"]

log = logging.getLogger(__name__)

_ENV = "RACKETDYN_FIGURE_WORKERS"
_HEADER = struct.Struct("<Q")
_PNG_MODULE = Path(__file__).with_name("_png.py")
"""The module the helper loads by its path (:mod:`racketdyn.plotting._png`)."""

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


class WorkerGoneError(Exception):
    """The helper process could not take a figure."""


class Worker:
    """One helper process and its pipes; used by one thread at a time."""

    def __init__(self) -> None:
        env = {**os.environ, "MPLBACKEND": "Agg", "OPENBLAS_NUM_THREADS": "1"}
        env["OMP_NUM_THREADS"] = "1"
        self.process = subprocess.Popen(
            [sys.executable, "-c", _WORKER_CODE, str(_PNG_MODULE)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            env=env,
        )
        self.ready = False
        self.broken = False
        self.used = False

    def _receive(self) -> tuple[str, str | None, list[tuple[type[Warning], str]]]:
        stdout: IO[bytes] | None = self.process.stdout
        assert stdout is not None
        head = stdout.read(_HEADER.size)
        if len(head) < _HEADER.size:
            raise WorkerGoneError("the figure helper process ended")
        message: tuple[str, str | None, list[tuple[type[Warning], str]]] = pickle.loads(
            stdout.read(_HEADER.unpack(head)[0])
        )
        return message

    def render(
        self, job: dict[str, Any]
    ) -> tuple[str, str | None, list[tuple[type[Warning], str]]]:
        """Send one job and wait for its outcome (status, traceback, warnings)."""
        if self.broken:
            raise WorkerGoneError("the figure helper process failed before")
        try:
            if not self.ready:
                self._receive()  # "ready": matplotlib imported
                self.ready = True
            stdin = self.process.stdin
            assert stdin is not None
            self.used = True
            data = pickle.dumps(job)
            stdin.write(_HEADER.pack(len(data)) + data)
            stdin.flush()
            return self._receive()
        except (OSError, EOFError, pickle.PickleError, WorkerGoneError) as error:
            self.broken = True
            raise WorkerGoneError(str(error)) from error

    def close(self) -> None:
        """End the process: let it finish its figure (at most 5 s); one never given a figure
        is stopped at once (it may still be importing matplotlib)."""
        if not self.used:
            self.process.kill()
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


_worker: Worker | None = None
_worker_lock = threading.Lock()


def _workers_allowed() -> int:
    """Helper processes allowed: ``RACKETDYN_FIGURE_WORKERS`` (0 or 1), else 1 on two cores."""
    text = os.environ.get(_ENV)
    if text is not None:
        try:
            return max(0, min(1, int(text)))
        except ValueError:
            log.warning("%s=%r is not a whole number: no figure helper process", _ENV, text)
            return 0
    return 1 if (os.cpu_count() or 1) >= 2 else 0


def shared_worker() -> Worker | None:
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
                _worker = Worker()
            except OSError as error:
                log.info("no figure helper process (%s): drawing here", error)
                return None
        return _worker


def start_helper() -> bool:
    """Start the helper process now, so that it has imported matplotlib by the first figure.

    A command that will draw several figures calls this before its computation; the first
    :class:`~racketdyn.plotting.render.FigureBatch` starts it otherwise.

    Returns
    -------
    bool
        Whether a helper process runs.
    """
    return shared_worker() is not None


@atexit.register
def _close_worker() -> None:
    global _worker
    with _worker_lock:
        if _worker is not None:
            _worker.close()
            _worker = None
