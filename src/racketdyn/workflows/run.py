"""The run folder and its ``run.json``: one writer for every step.

Every step writes its data files into a fresh folder, lets the caller's figure hook draw into
it, then records what it did in ``run.json``: version, time, the command as called, Python and
NumPy versions, the step's inputs and the defaults it used, and every file written (figures
included, which is why the record is written after the hook).
"""

from __future__ import annotations

import csv
import dataclasses
import functools
import hashlib
import inspect
import json
import logging
import math
import os
import platform
import shutil
from collections.abc import Callable, Sequence
from concurrent.futures import Executor
from contextlib import AbstractContextManager, nullcontext
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any, ParamSpec, TypeVar

import numpy as np

from racketdyn.__about__ import __version__
from racketdyn.errors import InputError

__all__ = [
    "REPORT_NAME",
    "WRITES_PENDING",
    "FigureHook",
    "Progress",
    "StepResult",
    "defer_file",
    "finish_run",
    "make_out_folder",
    "run_step",
    "sha256",
    "write_pending",
    "write_rows",
    "write_run_json",
]

log = logging.getLogger(__name__)

RUN_JSON = "run.json"

REPORT_NAME = "report.html"
"""File name of ``racketdyn report``'s page inside a run folder: it tells the run the folder
held, so a new run into the folder removes it with that run's files (issue 13)."""


@dataclass
class StepResult:
    """What every step returns: its folder, the files it wrote and its run record.

    Attributes
    ----------
    out : Path
        The run folder.
    written : list of Path
        Data files and figures written, in order (``run.json`` not included).
    record : dict
        The content of ``run.json`` (empty until the step has finished).
    pending : list of callable
        Files listed in ``written`` but not yet written (:func:`defer_file`): each writes its
        file when called; :func:`finish_run` writes them, or the figure hook while its figures
        are drawn in the helper process (:func:`write_pending`).
    """

    out: Path
    written: list[Path] = field(default_factory=list)
    record: dict[str, Any] = field(default_factory=dict)
    pending: list[Callable[[], object]] = field(default_factory=list, repr=False, compare=False)

    @property
    def run_json(self) -> Path:
        """Path of the step's ``run.json``."""
        return self.out / RUN_JSON

    def plot(self, figure: str, **options: Any) -> Any:
        """Draw one of the step's figures from this result, as the step drew it.

        The figure is an id of the registry of figures (:mod:`racketdyn.plotting.registry`,
        ``"fig15_rebound_along_axis"``, ``"face_maps"``, …) whose data this result holds;
        matplotlib is imported now (python-control's ``response.plot()``).

        Parameters
        ----------
        figure : str
            The figure's id (or file name).
        **options
            The figure's draw function's keywords (``axes=`` of your own for a figure of
            several panels, ``ax=`` for one of a single panel).

        Returns
        -------
        matplotlib.figure.Figure
        """
        from racketdyn.plotting.registry import draw

        return draw(figure, self, **options)


R = TypeVar("R", bound=StepResult)

FigureHook = Callable[[R, Path], list[Path]]
"""A caller's figure drawer: ``hook(result, out)`` draws into ``out`` and returns the paths."""

WRITES_PENDING = "writes_pending"
"""The attribute (True) of a figure hook that calls :func:`write_pending` itself, once its
figures are on their way to the helper process: the step's deferred files are written while
they are drawn. Any other hook is called after them (it may read them)."""


def defer_file(result: StepResult, path: Path, write: Callable[[], object]) -> None:
    """List ``path`` in ``result.written`` now and write it later (``write()``, before
    ``run.json``; :func:`write_pending`): a file no figure reads from the folder, written while
    the figures are drawn.

    Parameters
    ----------
    result : StepResult
        The step's result.
    path : Path
        The file.
    write : callable
        Writes it.
    """
    result.written.append(Path(path))
    result.pending.append(write)


def write_pending(result: object) -> None:
    """Write the deferred files of ``result`` (:func:`defer_file`), if it has any; each once.

    Parameters
    ----------
    result : object
        A step's result (anything else: nothing to write).
    """
    pending = getattr(result, "pending", None)
    while isinstance(pending, list) and pending:
        pending.pop(0)()


Progress = Callable[[str, int, int], None]
"""A caller's progress display: ``progress(what, done, total)``; ``total == 0`` announces a
stage of unknown length.  Steps also log every stage with :mod:`logging`."""


LOCK_NAME = ".racketdyn.lock"
"""A run folder being written holds this file (the writing process's id) until the run ends."""

STAGING_PREFIX = ".racketdyn-staging-"
"""A run writes into ``<out>/.racketdyn-staging-<pid>/`` and moves its files out when it ends."""


def make_out_folder(out: str | os.PathLike[str]) -> Path:
    """Create the run folder ``out`` (and its parents) or say in one line why it cannot be.

    Parameters
    ----------
    out : Path
        The output folder (``--out``).

    Raises
    ------
    InputError
        ``out`` or one of its parents is a file, or the folder cannot be created.
    """
    if not str(out).strip():
        raise InputError(f"`out` {str(out)!r}: give the name of the output folder")
    out = Path(out)
    try:
        for place in (out, *out.parents):
            if place.exists() and not place.is_dir():
                raise InputError(f"`out` {out}: {place} is a file, not a folder; give a folder")
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:  # a name too long, a read-only file system, no permission
        raise InputError(f"`out` {out}: cannot create the folder ({error.strerror})") from None
    return out


def _absent(out: str | os.PathLike[str]) -> bool:
    """Whether the folder ``out`` is still to be made (a name the system refuses counts as
    absent: :func:`make_out_folder` then says why in one line)."""
    try:
        return not Path(out).exists()
    except OSError:
        return True


def _process_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # somebody else's process: alive
        return True
    return True


def _lock(folder: Path) -> Path:
    """Take ``folder``'s lock, or say which run holds it; a dead run's lock is taken over."""
    lock = folder / LOCK_NAME
    for _ in range(2):
        try:
            descriptor = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
        except FileExistsError:
            _take_over(folder, lock)
            continue
        except OSError as error:  # read-only, no permission: before any work, in one line
            raise InputError(
                f"`out` {folder}: cannot write into the folder ({error.strerror}); give a "
                "folder you can write to"
            ) from None
        with os.fdopen(descriptor, "w", encoding="utf-8") as handle:
            handle.write(str(os.getpid()))
        return lock
    raise InputError(f"`out` {folder}: cannot take the folder's lock {lock}")


def _take_over(folder: Path, lock: Path) -> None:
    """Refuse a lock a live run holds; remove a dead run's lock and staging folders."""
    text = lock.read_text(encoding="utf-8", errors="replace").strip()
    pid = int(text) if text.isdigit() else 0
    if pid and _process_alive(pid):
        raise InputError(
            f"`out` {folder}: another racketdyn run (process {pid}) is writing into it; "
            f"wait for it to end, or give another `out` (if no such run is going on, "
            f"delete {lock})"
        )
    log.warning("%s: taking over the lock of an ended run (process %s)", folder, pid)
    lock.unlink(missing_ok=True)
    for stale in folder.glob(f"{STAGING_PREFIX}*"):
        shutil.rmtree(stale, ignore_errors=True)


def _previous_outputs(folder: Path) -> list[str]:
    """The files an earlier run listed in ``folder/run.json`` (names inside ``folder``)."""
    try:
        record = json.loads((folder / RUN_JSON).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return []
    outputs = record.get("outputs", []) if isinstance(record, dict) else []
    if not isinstance(outputs, list):  # damaged: list nothing rather than a string's letters
        log.warning("%s: run.json's outputs is not a list (damaged); replacing none", folder)
        outputs = []
    names = [str(name).rstrip("/") for name in outputs if isinstance(name, str)]
    # only plain names inside the folder: a damaged record must not reach outside it
    return [name for name in names if name and Path(name).name == name and name != RUN_JSON]


_COMMAND_OF = {"compare_ball": "compare"}
"""Steps run by an option of another command (``compare --ball-at``): one folder family."""


def _previous_step(folder: Path) -> str | None:
    """The step (``rig``, ``predict``, …) whose run ``folder/run.json`` records, if any."""
    try:
        record = json.loads((folder / RUN_JSON).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if isinstance(record, dict) and record.get("format") == "racketdyn-sweep-run":
        return "sweep"  # run_sweep from Python, or an older sweep, names no command
    try:
        command = [str(part) for part in record["command"]]
    except (KeyError, TypeError):
        return None
    if len(command) >= 2 and Path(command[0]).name == "racketdyn":
        return _COMMAND_OF.get(command[1], command[1])
    if len(command) >= 2 and command[1].startswith("racketdyn.workflows."):
        step = command[1].rsplit(".", 1)[-1]
        return _COMMAND_OF.get(step, step)
    return None


def _refuse_other_step(folder: Path, step: str) -> None:
    """A folder holding another step's run is not replaced: its files are that run's data."""
    previous = _previous_step(folder)
    if previous is not None and previous != step:
        raise InputError(
            f"`out` {folder}: the folder holds a `racketdyn {previous}` run (its run.json), "
            f"which `{step}` would replace; give another `out` for {step}"
        )


def _commit(staging: Path, folder: Path) -> None:
    """Replace the previous run's files in ``folder`` by the staged ones."""
    new = {entry.name for entry in staging.iterdir()}
    previous = _previous_outputs(folder)
    if (folder / RUN_JSON).is_file():  # the earlier run's page tells that run, not this one
        previous.append(REPORT_NAME)
    for name in previous:
        if name not in new:
            old = folder / name
            if old.is_dir() and not old.is_symlink():
                shutil.rmtree(old)
            else:
                old.unlink(missing_ok=True)
    for entry in sorted(staging.iterdir(), key=lambda e: e.name == RUN_JSON):
        target = folder / entry.name
        if target.is_dir() and not target.is_symlink():
            shutil.rmtree(target)
        os.replace(entry, target)  # run.json last: a folder's record follows its files
    staging.rmdir()


def _moved(path: Path, staging: Path, folder: Path) -> Path:
    try:
        return folder / Path(path).relative_to(staging)
    except ValueError:
        return Path(path)


P = ParamSpec("P")
S = TypeVar("S", bound=StepResult)


def _object_parameters(signature: inspect.Signature) -> dict[str, type[Any]]:
    """The step's parameters whose default is a dataclass object (``setup``, ``options``), by
    name, with that default's type."""
    return {
        key: type(p.default)
        for key, p in signature.parameters.items()
        if dataclasses.is_dataclass(p.default) and not isinstance(p.default, type)
    }


def _bind(
    name: str,
    signature: inspect.Signature,
    objects: dict[str, type[Any]],
    args: Any,
    kwargs: dict[str, Any],
) -> inspect.BoundArguments:
    """The step's arguments bound, each of ``objects`` (:func:`_object_parameters`) checked
    against its default's type.

    A keyword the step does not take that is a field of one of its options objects (the
    keywords ``run_predict`` took before its options moved into ``PredictOptions``) is named
    with that object; an options object in another's place is named with both.

    Raises
    ------
    TypeError
        Naming the step, the parameter and the object to give.
    """
    try:
        bound = signature.bind(*args, **kwargs)
    except TypeError as error:
        hint = ""
        for key, kind in objects.items():
            fields = {f.name for f in dataclasses.fields(kind)}
            unknown = sorted((set(kwargs) - set(signature.parameters)) & fields)
            if unknown:
                hint = f"; give it as `{key}`={kind.__name__}({unknown[0]}=...)"
        raise TypeError(f"{name}: {error}{hint}") from None
    for key, kind in objects.items():
        value = bound.arguments.get(key)
        if value is not None and not isinstance(value, kind):
            raise TypeError(
                f"{name}: `{key}` must be a {kind.__name__} (got {type(value).__name__}); "
                f"call {name}(out, setup, options) with a Setup and its options object"
            )
    return bound


def run_step(step: Callable[P, S]) -> Callable[P, S]:
    """Run a step into a fresh copy of its folder, so the folder holds one whole run.

    The step writes into ``<out>/.racketdyn-staging-<pid>/``; when it has finished (figures
    and ``run.json`` included) the files the previous run's ``run.json`` listed are removed
    and the new ones moved in, ``run.json`` last.  A step that fails leaves ``out`` as it was
    (a folder it had to create is removed again).  While it runs, ``out/.racketdyn.lock``
    holds the process id: a second run into the same folder is refused with one line; the
    lock of a run that died is taken over.  Files of the user's in ``out`` are never touched.
    Paths in the result (``out``, ``written``) name the final folder.  The step names its
    folder ``out``.  A folder that holds another step's run (``rig`` data, say) is refused
    with one line, before any work: nothing of another step is ever replaced.
    """
    signature = inspect.signature(step)
    objects = _object_parameters(signature)
    step_name = step.__name__.removeprefix("run_")
    step_name = _COMMAND_OF.get(step_name, step_name)

    @functools.wraps(step)
    def run(*args: P.args, **kwargs: P.kwargs) -> S:
        bound = _bind(step.__name__, signature, objects, args, kwargs)
        raw = bound.arguments["out"]
        created = _absent(raw)
        folder = make_out_folder(raw)  # '' and unwritable places refused in one line
        _refuse_other_step(folder, step_name)
        try:
            lock = _lock(folder)
        except InputError:
            if created:
                folder.rmdir()
            raise
        staging = folder / f"{STAGING_PREFIX}{os.getpid()}"
        try:
            shutil.rmtree(staging, ignore_errors=True)
            staging.mkdir()
            try:
                bound.arguments["out"] = staging
                result: S = step(*bound.args, **bound.kwargs)
            except BaseException:
                shutil.rmtree(staging, ignore_errors=True)
                if created and not any(p.name != LOCK_NAME for p in folder.iterdir()):
                    lock.unlink(missing_ok=True)
                    folder.rmdir()
                raise
            _commit(staging, folder)
        finally:
            lock.unlink(missing_ok=True)
        result.out = folder
        result.written = [_moved(path, staging, folder) for path in result.written]
        return result

    return run


def report(progress: Progress | None, what: str, done: int = 0, total: int = 0) -> None:
    """Log a stage (at its start) and pass it to the caller's progress display, if any."""
    if done == 0:
        log.info("%s", what)
    if progress is not None:
        progress(what, done, total)


def command_record(command: Sequence[str] | None, step: str) -> list[str]:
    """The command as called, for run.json; a Python call is named by its step function."""
    if command is None:
        return ["python", f"racketdyn.workflows.{step}"]
    return [str(part) for part in command]


def write_run_json(
    out: Path, command: Sequence[str], inputs: dict[str, Any], outputs: Sequence[Path]
) -> dict[str, Any]:
    """Write ``out/run.json`` and return its content.

    Parameters
    ----------
    out : Path
        The run folder (exists).
    command : sequence of str
        The command as called (``["racketdyn", "predict", …]``).
    inputs : dict
        The step's inputs, provenance and defaults used (JSON-able; other objects as ``str``).
    outputs : sequence of Path
        Files the step wrote into ``out``; ``run.json`` is added.
    """
    record = {
        "racketdyn_version": __version__,
        "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
        "command": list(command),
        "python": platform.python_version(),
        "numpy": np.__version__,
        **inputs,
        "outputs": [Path(p).name for p in outputs] + [RUN_JSON],
    }
    path = Path(out) / RUN_JSON
    path.write_text(json.dumps(record, indent=2, default=str), encoding="utf-8")
    log.info("wrote %s", path)
    return record


def finish_run(
    result: R,
    inputs: dict[str, Any],
    command: Sequence[str],
    figures: Callable[[R, Path], list[Path]] | None,
) -> R:
    """Write the deferred files and draw the caller's figures (if any; a hook marked
    :data:`WRITES_PENDING` writes the files while its figures are drawn), then write run.json
    listing every file; returns ``result`` with ``written`` and ``record`` filled in."""
    if figures is None or not getattr(figures, WRITES_PENDING, False):
        write_pending(result)
    if figures is not None:
        drawn = figures(result, result.out)
        result.written += [path for path in drawn if path not in result.written]
    write_pending(result)  # a hook that drew nothing
    result.record = write_run_json(result.out, command, inputs, result.written)
    return result


def sha256(path: Path) -> str:
    """SHA-256 of a file's bytes, as hex."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def _format_cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool | np.bool_):
        return str(bool(value))
    if isinstance(value, float | np.floating):
        return "nan" if not math.isfinite(value) else f"{float(value):.9g}"
    return str(value)


def write_rows(path: Path, rows: Sequence[dict[str, Any]]) -> Path:
    """Rows of dicts (same keys) as CSV; None as an empty cell, floats to 9 digits."""
    with Path(path).open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(rows[0])
        for row in rows:
            writer.writerow(_format_cell(v) for v in row.values())
    return Path(path)


def check_workers(workers: int | None, uncertainty: object | None) -> None:
    """``workers`` (a step's worker processes for its uncertainty samples): a count, and only
    with an ``uncertainty`` (InputError naming them)."""
    if workers is None:
        return
    from racketdyn.sweep.executors import check_local_workers  # the pool's own limit

    check_local_workers("`workers`", workers)
    if uncertainty is None:
        raise InputError("`workers` is for the samples of an `uncertainty`: give one too")


def sample_pool(workers: int | None) -> AbstractContextManager[Executor | None]:
    """Where an uncertainty's samples run one by one: a local pool of ``workers`` processes
    (the sweeps', :func:`racketdyn.sweep.executors.make_executor`), or None, this process."""
    if not workers:
        return nullcontext(None)
    from racketdyn.sweep.executors import make_executor  # the pool, when asked for

    return make_executor("process", workers)
