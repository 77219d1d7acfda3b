"""Writing a step's figures: built here, drawn here and in one helper process at once.

A step builds its figures (cheap: artists only) into a :class:`FigureBatch`, then
:meth:`FigureBatch.render` draws and writes them. Drawing is most of a figure's cost (layout,
Agg, PNG); with two or more figures in a batch and a helper process allowed, the helper takes
figures from the front of the batch (pickled through a pipe) while this process draws from the
back, so two cores draw at once. The helper is one ``python`` process
(:mod:`racketdyn.plotting.helper`) started on first use, or at a command's start by
:func:`start_helper`, and kept for the rest of the run (``racketdyn demo`` starts it once);
it imports matplotlib alone. If it cannot start or dies, this process draws everything. The
files are the same either way (same pixels, same bytes).

``RACKETDYN_FIGURE_WORKERS=0`` in the environment draws everything in this process; the
default is one helper on a machine with two or more cores, none on one core.
"""

from __future__ import annotations

import logging
import pickle
import threading
import warnings
from collections import deque
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from racketdyn.__about__ import __version__
from racketdyn.plotting import _png
from racketdyn.plotting.helper import WorkerGoneError, shared_worker, start_helper

__all__ = ["FigureBatch", "save_figure", "start_helper"]

log = logging.getLogger(__name__)

SOFTWARE = f"racketdyn {__version__}"


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


# --- batches -------------------------------------------------------------------------------------
_Outcome = tuple[_Job, str, str | None, list[tuple[type[Warning], str]]]


class FigureBatch:
    """The figures of one step: :meth:`add` them as they are built, then :meth:`render`.

    With a helper process, it takes figures from the front of the batch as soon as they are
    added (so it draws while this process builds the next ones or computes what they need);
    :meth:`render` draws the rest here, from the back, after any figure that does not pickle
    (the helper cannot take it: this process draws it first, while the helper draws).
    """

    def __init__(self) -> None:
        self._jobs: list[_Job] = []
        self._queue: deque[_Job] = deque()
        self._ready = threading.Condition()
        self._closed = False
        self._outcomes: list[_Outcome] = []
        self._left: list[_Job] = []
        self._here: list[_Job] = []  # figures that do not pickle: this process's from the start
        self._worker = shared_worker()  # starts it: it imports while the figures are built
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
            except Exception as error:  # an artist that does not pickle: drawn here, first
                log.info("%s is drawn here: its figure does not pickle (%s)", path, error)
                self._here.append(job)
                return Path(path)
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
            except WorkerGoneError as error:
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
                if self._here:
                    job = self._here.pop(0)
                elif self._queue:
                    job = self._queue.pop()
                else:
                    break
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
