"""The run folder and its ``run.json``: one writer for every step.

Every step writes its data files into a fresh folder, lets the caller's figure hook draw into
it, then records what it did in ``run.json``: version, time, the command as called, Python and
NumPy versions, the step's inputs and the defaults it used, and every file written (figures
included, which is why the record is written after the hook).
"""

from __future__ import annotations

import csv
import hashlib
import json
import logging
import math
import platform
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any, TypeVar

import numpy as np

from racketdyn.__about__ import __version__
from racketdyn.errors import InputError

__all__ = [
    "FigureHook",
    "Progress",
    "StepResult",
    "finish_run",
    "make_out_folder",
    "sha256",
    "write_rows",
    "write_run_json",
]

log = logging.getLogger(__name__)

RUN_JSON = "run.json"


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
    """

    out: Path
    written: list[Path] = field(default_factory=list)
    record: dict[str, Any] = field(default_factory=dict)

    @property
    def run_json(self) -> Path:
        """Path of the step's ``run.json``."""
        return self.out / RUN_JSON


R = TypeVar("R", bound=StepResult)

FigureHook = Callable[[R, Path], list[Path]]
"""A caller's figure drawer: ``hook(result, out)`` draws into ``out`` and returns the paths."""

Progress = Callable[[str, int, int], None]
"""A caller's progress display: ``progress(what, done, total)``; ``total == 0`` announces a
stage of unknown length.  Steps also log every stage with :mod:`logging`."""


def make_out_folder(out: Path) -> Path:
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
    out = Path(out)
    for place in (out, *out.parents):
        if place.exists() and not place.is_dir():
            raise InputError(f"--out {out}: {place} is a file, not a folder; give a folder")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise InputError(f"--out {out}: cannot create the folder ({error.strerror})") from None
    return out


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
    """Draw the caller's figures (if any), then write run.json listing every file; returns
    ``result`` with ``written`` and ``record`` filled in."""
    if figures is not None:
        drawn = figures(result, result.out)
        result.written += [path for path in drawn if path not in result.written]
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
