"""What the pipeline commands wrote under a run folder, read once for every section.

:class:`RunFolder` scans the folder and its sub-folders, reads every ``run.json`` and answers the
questions the sections ask (where ``impact.csv`` is, which identifications exist, the racket's
head outline, …).  It is the only input of a section's ``gather`` function.
"""

from __future__ import annotations

import csv
import fnmatch
import io
import json
import logging
import math
import os
import re
import shlex
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.errors import InputError
from racketdyn.impact.result import invalidate_table, shown_speed_index
from racketdyn.plotting.registry import file_of, in_section, of_file
from racketdyn.racket import HeadEllipse, Racket
from racketdyn.report.figures import Figure, FigureGroup, Layout, embed_png
from racketdyn.workflows.run import REPORT_NAME

__all__ = [
    "REPORT_NAME",
    "Impacts",
    "Row",
    "RunFolder",
    "StepFolder",
    "damaged",
    "number",
    "read_csv",
    "read_json",
    "refuse_mixed_rackets",
    "shown_case",
    "to_float",
]

log = logging.getLogger(__name__)


REPAIR = "re-run the step that wrote it"
"""The fix a damaged file's message ends with (followed by the command, when known)."""

RECORD_TYPES: dict[str, type] = {
    "racketdyn_version": str,
    "created_utc": str,
    "command": list,
    "outputs": list,
    "defaults_used": list,
    "labels": list,
    "racket": dict,
    "ball": dict,
}
"""Keys of a run.json the report relies on, and the JSON type each must have (an object is a
dict, an array a list)."""


_JSON_WORDS: dict[type, str] = {
    dict: "an object",
    list: "an array",
    str: "a string",
    int: "a number",
    float: "a number",
    bool: "true or false",
    type(None): "null",
}


def damaged(path: Path, problem: str) -> InputError:
    """The error for a file of the run folder the report cannot read: the file, what is wrong
    with it, and the fix — the command that wrote it, from its folder's run.json if readable.

    Parameters
    ----------
    path : Path
        The damaged file.
    problem : str
        What is wrong with it (no trailing full stop).
    """
    return InputError(f"{path}: {problem}; {REPAIR}{_written_by(path)}")


WRITTEN_BY = {
    "impact.csv": "racketdyn predict",
    "comparison.csv": "racketdyn compare, or racketdyn predict --model both",
    "contact_*.csv": "racketdyn contact",
    "quality.csv": "racketdyn frf",
    "modes*.csv": "racketdyn identify or compare",
    "fit_quality*.csv": "racketdyn identify or compare",
    "sweet_spots.csv": "racketdyn swing",
    "twist.csv": "racketdyn twist",
    "oblique.csv": "racketdyn oblique",
}
"""The command that writes each file the report reads, for a folder without a readable
run.json."""


def _written_by(path: Path) -> str:
    """`` (racketdyn …)``: the command in the run.json beside ``path``, else the command that
    writes such a file; empty for run.json itself."""
    if path.name == "run.json":
        return ""
    try:
        record = json.loads((path.parent / "run.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        record = None
    command = record.get("command") if isinstance(record, dict) else None
    if isinstance(command, list) and command and all(isinstance(c, str) for c in command):
        return f" ({shlex.join(command)})"
    step = next((v for k, v in WRITTEN_BY.items() if fnmatch.fnmatchcase(path.name, k)), "")
    return f" ({step})" if step else ""


def read_json(path: Path) -> dict[str, Any]:
    """The JSON object of a run.json, its keys of :data:`RECORD_TYPES` checked.

    Raises
    ------
    InputError
        The file cannot be read, is not JSON, not an object, or a key has the wrong type.
    """
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except UnicodeDecodeError as error:
        raise damaged(path, f"not text (byte {error.start} is not UTF-8)") from None
    except json.JSONDecodeError as error:
        raise damaged(
            path, f"not valid JSON (line {error.lineno}, column {error.colno}: {error.msg})"
        ) from None
    except (OSError, ValueError) as error:
        raise damaged(path, f"not read ({error})") from None
    if not isinstance(data, dict):
        found = _JSON_WORDS.get(type(data), "?")
        raise damaged(path, f"{found} where a run.json holds an object of settings")
    for key, kind in RECORD_TYPES.items():
        if key in data and not isinstance(data[key], kind):
            found, wanted = _JSON_WORDS.get(type(data[key]), "?"), _JSON_WORDS[kind]
            raise damaged(path, f"'{key}' is {found} where {wanted} belongs")
    return data


class Row(dict[str, str]):
    """One row of a CSV of the run folder, by column; it knows its file and line.

    Attributes
    ----------
    path : Path
        The CSV file.
    line : int
        The row's line in the file, from 1.
    """

    def __init__(self, cells: Iterable[tuple[str, str]], path: Path, line: int) -> None:
        super().__init__(cells)
        self.path = path
        self.line = line


def read_csv(path: Path, required: Sequence[str] = ()) -> list[Row]:
    """The rows of a CSV the pipeline wrote, each as a :class:`Row`.

    Blank lines and lines starting with ``#`` are skipped (``comparison.csv`` of earlier
    versions ended with two).

    Parameters
    ----------
    path : Path
        The CSV file.
    required : sequence of str
        Columns its header must have.

    Raises
    ------
    InputError
        The file cannot be read, is not text, has no header or lacks a required column, or a
        row has more or fewer fields than the header (a file cut short).
    """
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError as error:
        raise damaged(path, f"not text: binary data (byte {error.start} is not UTF-8)") from None
    except OSError as error:
        raise damaged(path, f"cannot be read ({error.strerror or error})") from None
    if "\0" in text:
        raise damaged(path, "not text: binary data (NUL bytes)")
    records: list[tuple[int, list[str]]] = []
    reader = csv.reader(io.StringIO(text, newline=""))
    try:
        for cells in reader:
            if cells and "".join(cells).strip() and not cells[0].startswith("#"):
                records.append((reader.line_num, cells))
    except csv.Error as error:
        raise damaged(path, f"not a CSV (line {reader.line_num}: {error})") from None
    if not records:
        raise damaged(path, "empty: no header and no rows")
    (first, header), body = records[0], records[1:]
    missing = [name for name in required if name not in header]
    if missing:
        raise damaged(path, f"no column {', '.join(missing)} in its header (line {first})")
    rows = []
    for line, cells in body:
        if len(cells) != len(header):
            raise damaged(
                path,
                f"line {line} has {len(cells)} field{'' if len(cells) == 1 else 's'} where the "
                f"header has {len(header)} "
                "(the file is cut short or damaged)",
            )
        rows.append(Row(zip(header, cells, strict=True), path, line))
    return rows


def number(row: Mapping[str, str | None], column: str) -> float:
    """A CSV cell as a number; NaN when the column is missing or the cell empty.

    Raises
    ------
    InputError
        The cell of a :class:`Row` holds text that is not a number (NaN and inf are numbers).
    """
    text = row.get(column)
    if text is None or text == "":
        return math.nan
    try:
        return float(text)
    except ValueError:
        if isinstance(row, Row):
            raise damaged(
                row.path, f"line {row.line}, column {column}: {text!r} is not a number"
            ) from None
        return math.nan


def to_float(text: str | None) -> float:
    """A value of run.json given as text, as a number; NaN when empty or not a number."""
    try:
        return float(text) if text not in (None, "") else math.nan
    except ValueError:
        return math.nan


IMPACT_COLUMNS = ("x_m", "y_m", "support", "ball_speed_mps", "rebound_ratio")
"""Columns of ``impact.csv`` the report cannot do without."""
IMPACT_TEXT_COLUMNS = ("point", "support", "status")
"""Columns of ``impact.csv`` that hold text; every other one holds numbers."""


def _grid_size(record: Mapping[str, Any]) -> int | None:
    """Rows of predict's ``impact.csv`` by its run.json: points × speeds × supports."""
    points, speeds, supports = (record.get(k) for k in ("n_points", "speeds_mps", "supports"))
    if isinstance(points, int) and isinstance(speeds, list) and isinstance(supports, list):
        return points * len(speeds) * len(supports)
    return None


Case = tuple[float, float]
"""An impact case: (ball speed, racket speed), m/s."""


@dataclass(frozen=True)
class Impacts:
    """``impact.csv``: numeric columns as arrays, support and status as strings."""

    numbers: dict[str, NDArray[np.float64]]
    support: NDArray[np.str_]
    status: NDArray[np.str_]

    @classmethod
    def read(cls, path: Path, record: Mapping[str, Any] | None = None) -> Impacts:
        """The table of ``path``, checked against the run.json of its folder (``record``).

        Raises
        ------
        InputError
            The file is damaged: not a CSV, a column the report needs missing, a row cut
            short, text in a number column, or fewer or more rows than the points × speeds ×
            supports its run.json lists.
        """
        rows = read_csv(path, IMPACT_COLUMNS)
        if not rows:
            raise damaged(path, "no rows under its header")
        header = list(rows[0])
        table = np.array([list(row.values()) for row in rows], dtype=str)
        numbers = {}
        for i, name in enumerate(header):
            if name in IMPACT_TEXT_COLUMNS:
                continue
            try:
                numbers[name] = np.where(table[:, i] == "", "nan", table[:, i]).astype(float)
            except ValueError:
                numbers[name] = np.array([number(row, name) for row in rows])  # names the cell
        expected = _grid_size(record or {})
        if expected is not None and expected != len(rows):
            raise damaged(
                path,
                f"{len(rows)} rows where its run.json lists {expected} (points × speeds × "
                "supports): the file is cut short or damaged",
            )
        status = (
            table[:, header.index("status")] if "status" in header else np.full(len(table), "ok")
        )
        # a flagged row's numbers are never shown as valid, whoever wrote the file (issue 13)
        return cls(
            invalidate_table(numbers, status),
            table[:, header.index("support")] if "support" in header else np.full(len(table), ""),
            status,
        )

    def __getitem__(self, name: str) -> NDArray[np.float64]:
        return self.numbers.get(name, np.full(self.support.size, np.nan))

    @property
    def speeds(self) -> list[float]:
        """Ball speeds of the table, m/s, ascending."""
        return sorted({float(v) for v in self["ball_speed_mps"]})

    @property
    def supports(self) -> list[str]:
        """Supports in the order of the table."""
        return list(dict.fromkeys(self.support.tolist()))

    @property
    def racket_speeds(self) -> NDArray[np.float64]:
        """Each row's racket speed, m/s (0 without the column, or where it is empty)."""
        return np.nan_to_num(self["racket_speed_mps"], nan=0.0)

    @property
    def case_list(self) -> list[Case]:
        """The table's cases, (ball speed, racket speed) in m/s, ascending: a run may pair one
        ball speed with several racket speeds (``--speed 20,20 --racket-speed 0,30``)."""
        pairs = zip(self["ball_speed_mps"].tolist(), self.racket_speeds.tolist(), strict=True)
        return sorted({(float(b), float(r)) for b, r in pairs})

    @property
    def moving(self) -> bool:
        """Whether any row's racket moves (the cases are then named with their racket speed)."""
        return bool(np.any(self.racket_speeds != 0))

    def case_cell(self, case: Case) -> str:
        """A case in a table's "ball speed (m/s)" cell: ``20``, or — when the run's cases have
        several racket speeds — ``20, racket 30`` and ``20, racket at rest``."""
        ball, racket = case
        if len({r for _, r in self.case_list}) < 2:
            return f"{ball:g}"
        return f"{ball:g}, " + (f"racket {racket:g}" if racket else "racket at rest")

    def rows(self, case: Case, support: str) -> NDArray[np.intp]:
        """Row indices of one case (ball speed, racket speed; m/s) and support."""
        ball, racket = case
        return np.flatnonzero(
            (self["ball_speed_mps"] == ball)
            & (self.racket_speeds == racket)
            & (self.support == support)
        )

    def racket_speed_at(self, speed: float) -> float:
        """The racket speed paired with a ball speed (m/s) in the table; 0 without the
        column."""
        found = self["racket_speed_mps"][self["ball_speed_mps"] == speed]
        found = found[np.isfinite(found)]
        return float(found[0]) if found.size else 0.0

    def where(self, row: int) -> str:
        """``x, y`` of a row in mm, for tables."""
        return f"{self['x_m'][row] * 1e3:.0f}, {self['y_m'][row] * 1e3:.0f}"

    def nearest(self, rows: NDArray[np.intp], x: float, y: float) -> int:
        """The row among ``rows`` nearest the point (x, y), m."""
        distance = np.hypot(self["x_m"][rows] - x, self["y_m"][rows] - y)
        return int(rows[int(np.argmin(distance))])

    def cases(self, x: float, y: float) -> Iterator[tuple[str, Case, NDArray[np.intp], int]]:
        """Each support and case with rows: ``(support, case, rows, row nearest (x, y))`` (m),
        supports in the table's order, cases ascending (:attr:`case_list`)."""
        for support in self.supports:
            for case in self.case_list:
                selected = self.rows(case, support)
                if selected.size:
                    yield support, case, selected, self.nearest(selected, x, y)


STEP_NAMES = (
    "rig",
    "frf",
    "contact",
    "identify",
    "compare",
    "compare_ball",
    "predict",
    "swing",
    "twist",
    "oblique",
    "compound",
    "validate",
    "calibrate",
)
"""The steps the report reads, in the order of the page (``compare_ball`` is ``racketdyn
compare --ball-at``)."""
NOT_REPORTED = {
    "ball": "its ball.csv and figure stand alone",
    "sweep": "its summary.csv and figures stand alone",
}
"""Commands whose runs the report has no section for, and where their results are: such a
folder is listed as left out, not passed over in silence."""
LABELLED = ("frf", "identify")
"""Steps run once per support: several may be used, each known by its label (``free``,
``hand``, …: an FRF run's folder name after ``frf_`` or its tests file, an identification's
support)."""

StepsInput = Mapping[str, str | os.PathLike[str]] | Iterable[tuple[str, str | os.PathLike[str]]]
"""The folders a report is told to use: ``{"predict": "serve"}`` or ``[("identify", "id_free"),
("identify", "id_hand")]``; a name is a step of :data:`STEP_NAMES`, or the label of an FRF or
identify run (``free``); a folder is relative to the report's folder, or absolute."""


@dataclass(frozen=True)
class StepFolder:
    """A step's folder the report uses.

    Attributes
    ----------
    name : str
        The step's name as ``steps`` takes it: the label of an FRF run (``free``, ``hand``),
        else the step (``rig``, ``identify``, ``predict``, …).
    step : str
        The step that wrote the folder (one of :data:`STEP_NAMES`).
    label : str
        An FRF or identify run's label (its support); empty for the other steps.
    folder : Path
        The folder.
    given : bool
        Named by ``steps``; else found in the report's folder.
    """

    name: str
    step: str
    label: str
    folder: Path
    given: bool


def _frf_label(folder: Path, record: Mapping[str, Any]) -> str:
    if folder.name.startswith("frf_"):
        return folder.name[4:]
    tests = record.get("tests_file")
    return Path(str(tests)).stem.removeprefix("hammer_") if tests else folder.name


def _recorded_step(record: Mapping[str, Any]) -> str | None:
    """The step a run.json's command names (as ``workflows.run`` reads it to refuse another
    step's folder; the report, a presentation module, does not import it)."""
    command = record.get("command")
    if not isinstance(command, list) or len(command) < 2:
        return None
    first, second = str(command[0]), str(command[1])
    if Path(first).name == "racketdyn":
        return second
    if second.startswith("racketdyn.workflows."):
        return second.rsplit(".", 1)[-1]
    return None


def _step_of(folder: Path, record: Mapping[str, Any]) -> str | None:
    """The report's step of a folder by its run.json, None for one the report does not read."""
    step = _recorded_step(record)
    if step == "compare" and (folder / "ball_comparison.csv").is_file():
        return "compare_ball"
    return step if step in STEP_NAMES else None


BALL_LABEL = "ball"
"""The label of the model of the racket with the ball on its strings: an ``identify
--ball-at`` run's, and ``compare --ball-at``'s ``modes_ball.csv``."""


def _label_of(step: str, folder: Path, record: Mapping[str, Any]) -> str:
    if step == "frf":
        return _frf_label(folder, record)
    if step == "identify":
        # the ball on the strings (identify --ball-at): not its support's racket model
        if record.get("ball_at_m"):
            return BALL_LABEL
        return str(record.get("support") or folder.name)
    return ""


def _model_words(label: str) -> str:
    """A model's label in words: the ball-on-strings model, else the support's."""
    return "ball-on-strings" if label == BALL_LABEL else label


def _compared(folder: Path) -> set[str]:
    """The supports whose models a compare run's folder holds (``modes_<support>.csv``)."""
    return {p.stem.removeprefix("modes_") for p in folder.glob("modes_*.csv")}


def _rel(run_dir: Path, folder: Path) -> str:
    try:
        return folder.relative_to(run_dir).as_posix() or "."
    except ValueError:
        return Path(os.path.relpath(folder, run_dir)).as_posix()


def _given_steps(
    run_dir: Path, steps: StepsInput, records: dict[Path, dict[str, Any]]
) -> list[StepFolder]:
    """The folders ``steps`` names, each checked: a folder, holding the step named."""
    pairs = list(steps.items()) if isinstance(steps, Mapping) else list(steps)
    given: list[StepFolder] = []
    for pair in pairs:
        if not (isinstance(pair, tuple) and len(pair) == 2):
            raise InputError(f"`steps`: {pair!r} is not a pair NAME=FOLDER")
        name, where = str(pair[0]).strip(), pair[1]
        said = f"`steps` {name}={os.fspath(where)}"
        folder = Path(where) if Path(where).is_absolute() else run_dir / where
        if not folder.is_dir():
            raise InputError(
                f"{said}: no folder {folder} (a step's folder, relative to {run_dir} or absolute)"
            )
        if folder not in records and (folder / "run.json").is_file():
            records[folder] = read_json(folder / "run.json")
        record = records.get(folder)
        step = None if record is None else _step_of(folder, record)
        held = (
            "no run.json"
            if record is None
            else f"a {step} run"
            if step
            else "no run the report reads"
        )
        if name in STEP_NAMES:
            if record is not None and step != name:
                raise InputError(f"{said}: {os.fspath(where)} holds {held}, not a {name} run")
            label = _label_of(name, folder, record or {})
            given.append(StepFolder(label if name == "frf" else name, name, label, folder, True))
        elif step in LABELLED:
            given.append(StepFolder(name if step == "frf" else step, step, name, folder, True))
        else:
            known = ", ".join(STEP_NAMES)
            raise InputError(
                f"{said}: {os.fspath(where)} holds {held}, and {name} is no step ({known}; "
                "another word is the label of an FRF or identify run)"
                + (f"; give {step}={os.fspath(where)}" if step else "")
            )
    return given


def _choose(
    run_dir: Path,
    dirs: list[Path],
    records: dict[Path, dict[str, Any]],
    steps: StepsInput | None,
) -> tuple[list[StepFolder], list[tuple[Path, str]]]:
    """The step folders a report uses and those it leaves out (with why): the ones ``steps``
    names, and for every other step the one folder of the report's folder that holds it.

    Raises
    ------
    InputError
        A named folder is missing or holds another step, or a step not named has several
        folders (several predictions, two FRF runs of one label, …).
    """
    given = _given_steps(run_dir, steps or {}, records)
    keys = [(s.step, s.label) for s in given]
    for key in keys:
        if keys.count(key) > 1:
            twice = [_rel(run_dir, s.folder) for s in given if (s.step, s.label) == key]
            what = f"{key[0]} run labelled {key[1]}" if key[1] else f"{key[0]} run"
            raise InputError(f"`steps` names two folders of one {what}: {', '.join(twice)}")
    chosen = {s.folder for s in given}
    found: dict[tuple[str, str], list[Path]] = {}
    left_out: list[tuple[Path, str]] = []
    for folder in dirs:
        record = records.get(folder)
        step = None if record is None or folder in chosen else _step_of(folder, record)
        if step is None:
            other = None if record is None else _recorded_step(record)
            if other in NOT_REPORTED:
                why = f"the report has no section for `{other}` runs ({NOT_REPORTED[other]})"
                left_out.append((folder, why))
            continue
        key = (step, _label_of(step, folder, record or {}))
        if key in keys:
            named = next(s for s in given if (s.step, s.label) == key)
            left_out.append((folder, f"{named.name}={_rel(run_dir, named.folder)} given"))
        else:
            found.setdefault(key, []).append(folder)
    # one identified model per support: compare holds the free and hand models of its FRFs,
    # compare --ball-at the ball-on-strings model (with the racket alone's)
    compares = [
        *(s.folder for s in given if s.step in ("compare", "compare_ball")),
        *found.get(("compare", ""), []),
        *found.get(("compare_ball", ""), []),
    ]
    covered = {label: folder for folder in compares for label in _compared(folder)}
    for s in given:
        if s.step == "identify" and s.label in covered:
            where = covered[s.label]
            holder = _step_of(where, records.get(where, {})) or "compare"
            if where in chosen:
                raise InputError(
                    f"`steps` identify={_rel(run_dir, s.folder)} and "
                    f"{holder}={_rel(run_dir, where)} both give the "
                    f"{_model_words(s.label)} model; give one"
                )
            for folder in found.pop((holder, ""), []):
                left_out.append((folder, f"identify={_rel(run_dir, s.folder)} given"))
            covered = {k: v for k, v in covered.items() if v != where}
    for key in [k for k in found if k[0] == "identify" and k[1] in covered]:
        for folder in found.pop(key):
            holder = _rel(run_dir, covered[key[1]])
            left_out.append((folder, f"{holder} holds the {_model_words(key[1])} model"))
    for (step, label), folders in found.items():
        if len(folders) > 1:
            names = [_rel(run_dir, f) for f in folders]
            what = (
                f"{len(folders)} FRF runs labelled {label}"
                if step == "frf"
                else f"{len(folders)} {step} runs of {label}"
                if label
                else f"{len(folders)} {step} runs"
            )
            name = label if step == "frf" else step
            # runs of several rackets side by side: that is what to say first
            refuse_mixed_rackets(run_dir, {d: records[d] for d in dirs if d in records})
            raise InputError(
                f"{run_dir}: it holds {what} ({', '.join(names)}): a report tells one run; "
                f"choose one, e.g. `steps` {name}={names[-1]}"
            )
    used = given + [
        StepFolder(label if step == "frf" else step, step, label, folders[0], False)
        for (step, label), folders in found.items()
    ]
    order = {folder: n for n, folder in enumerate(dirs)}
    used.sort(key=lambda s: (STEP_NAMES.index(s.step), order.get(s.folder, len(order)), s.label))
    left_out.sort(key=lambda item: order.get(item[0], len(order)))
    return used, left_out


def refuse_mixed_rackets(run_dir: Path, records: Mapping[Path, Mapping[str, Any]]) -> None:
    """One page tells one racket: refuse runs whose run.json files name several rackets (the
    page would title one racket and mix the others' files in; the new-user trial of issue 13
    reported on a folder of two rackets' runs).

    Raises
    ------
    InputError
        The racket of each, by folder, and what to do.
    """
    rackets: dict[str, str] = {}
    folders: dict[str, list[str]] = {}
    for folder, record in records.items():
        name = record.get("racket_file")
        if not name:
            continue
        key = str(record.get("racket_file_sha256") or name)
        described = record.get("racket")
        title = described.get("name") if isinstance(described, dict) else None
        if title or key not in rackets:  # a record naming the racket wins over a file name
            rackets[key] = str(title or Path(str(name)).name)
        folders.setdefault(key, []).append(_rel(run_dir, folder))
    if len(rackets) > 1:
        by_default = sorted(
            f for key, names in folders.items() if key.startswith("built-in") for f in names
        )
        advice = (
            f"the steps in {', '.join(by_default)} took the built-in racket by default: run "
            "them again with --racket FILE, or give the folder of one racket's runs"
            if by_default
            else "give the folder of one racket's runs (a demo folder)"
        )
        raise InputError(
            f"{run_dir}: its runs used {len(rackets)} rackets ("
            + "; ".join(
                sorted(f"{rackets[key]} ({', '.join(sorted(folders[key]))})" for key in rackets)
            )
            + f"): a report tells one run; {advice}"
        )


def shown_case(record: Mapping[str, Any], impacts: Impacts | None = None) -> tuple[float, float]:
    """The case (ball speed, racket speed; m/s) a prediction's single-case summaries show:
    its run.json's ``shown_case`` (``predict --show``, or the rule's case), else — a run of an
    earlier version — the speed rule over the run's speeds.  NaN, NaN when neither says."""
    shown = record.get("shown_case")
    if isinstance(shown, Mapping):
        ball, racket = (to_float(str(shown.get(k, ""))) for k in SHOWN_KEYS)
        if math.isfinite(ball):
            return ball, racket if math.isfinite(racket) else 0.0
    speeds = impacts.speeds if impacts is not None else []
    listed = _floats(record.get("speeds_mps"))
    speeds = impacts.speeds if impacts is not None else listed
    if not speeds:
        return math.nan, math.nan
    ball = speeds[shown_speed_index(speeds)]
    if impacts is not None:
        return ball, impacts.racket_speed_at(ball)
    paired = _floats(record.get("racket_speed_mps"))
    if len(paired) == len(listed):
        return ball, paired[listed.index(ball)]
    return ball, paired[0] if paired else 0.0


def _floats(values: object) -> list[float]:
    """The numbers of a run.json list (none for anything else)."""
    if not isinstance(values, list):
        return []
    return [float(v) for v in values if isinstance(v, int | float) and not isinstance(v, bool)]


SHOWN_KEYS = ("ball_speed_mps", "racket_speed_mps")
"""Keys of run.json's ``shown_case``."""


def _scan(run_dir: Path) -> tuple[list[Path], dict[Path, dict[str, Any]]]:
    dirs = [
        run_dir,
        *sorted(
            p
            for p in run_dir.rglob("*")
            if p.is_dir() and not any(part.startswith(".") for part in p.relative_to(run_dir).parts)
        ),
    ]
    records = {}
    for folder in dirs:
        if (folder / "run.json").is_file():
            records[folder] = read_json(folder / "run.json")
    return dirs, records


@dataclass
class RunFolder:
    """What was found under a run folder: its folders, their run.json records, and the racket.

    Parameters
    ----------
    run_dir : Path
        The folder the report is written for.
    racket : Racket or None
        The racket given to :func:`~racketdyn.report.write_report`, if any.
    dirs : list of Path
        The folders the report reads: the step folders it uses and the folders without a
        run.json under it (hidden ones left out), the folder first.
    records : dict
        Each of those folders' ``run.json``, by folder.
    steps : list of StepFolder
        The step folders the report uses, in the order of the page.
    left_out : list of (Path, str)
        Step folders under the report's folder it does not use, each with why.
    """

    run_dir: Path
    racket: Racket | None
    dirs: list[Path]
    records: dict[Path, dict[str, Any]]
    steps: list[StepFolder] = field(default_factory=list)
    left_out: list[tuple[Path, str]] = field(default_factory=list)
    _cache: dict[str, Any] = field(default_factory=dict, repr=False)

    @classmethod
    def scan(
        cls, run_dir: Path, racket: Racket | None = None, steps: StepsInput | None = None
    ) -> RunFolder:
        """Read ``run_dir``: its sub-folders and every ``run.json``; the step folders to use.

        Parameters
        ----------
        run_dir : Path
            The report's folder.
        racket : Racket, optional
            The racket the runs used.
        steps : mapping or sequence of (name, folder), optional
            The folders to use for some steps (:data:`StepsInput`); every other step's
            folder is found under ``run_dir``.

        Raises
        ------
        InputError
            A folder of ``steps`` is missing or holds another step, or a step has several
            folders under ``run_dir`` and ``steps`` does not choose one.
        """
        run_dir = Path(run_dir)
        dirs, records = _scan(run_dir)
        used, left_out = _choose(run_dir, dirs, records, steps)
        folders = {s.folder for s in used}
        kept = [d for d in dirs if d in folders or d not in records]
        kept += [s.folder for s in used if s.folder not in kept]
        return cls(
            run_dir,
            racket,
            kept,
            {d: records[d] for d in kept if d in records},
            used,
            left_out,
        )

    def with_file(self, pattern: str) -> list[Path]:
        """Folders holding a file that matches ``pattern``, the run folder first."""
        return [d for d in self.dirs if any(d.glob(pattern))]

    def first(self, pattern: str) -> Path | None:
        """The first folder holding a file that matches ``pattern``."""
        found = self.with_file(pattern)
        return found[0] if found else None

    def rel(self, path: Path) -> str:
        """``path`` relative to the run folder, with forward slashes (``..`` for a step folder
        given outside it)."""
        try:
            return path.relative_to(self.run_dir).as_posix()
        except ValueError:
            return Path(os.path.relpath(path, self.run_dir)).as_posix()

    def label(self, folder: Path) -> str:
        """The label ``steps`` gave an FRF or identify run's folder, else the run's own."""
        for s in self.steps:
            if s.folder == folder and s.label:
                return s.label
        record = self.record(folder)
        return _frf_label(folder, record) if (folder / "quality.csv").is_file() else ""

    def record(self, folder: Path | None) -> dict[str, Any]:
        """The run.json of ``folder``; empty if it has none."""
        return self.records.get(folder, {}) if folder is not None else {}

    def unknown_modes(self, folder: Path | None) -> list[str]:
        """Names of the modes of unknown kind in the modal model a step used (its run.json's
        ``modal_model.modes``): a prediction takes them as frame modes (issue 25 item 8)."""
        used = self.record(folder).get("modal_model")
        modes = used.get("modes") if isinstance(used, dict) else None
        if not isinstance(modes, list):
            return []
        return [
            str(mode.get("name"))
            for mode in modes
            if isinstance(mode, dict) and mode.get("kind") == "unknown"
        ]

    def shapes_under_bed(self, folder: Path | None) -> bool:
        """Whether the modal model a step charged took the frame's motion under the bed at the
        string points (its run.json's ``modal_model.shapes_on_strings``; issue 22)."""
        from racketdyn.racket_modal.shapes import SHAPES_FRAME_UNDER_BED

        used = self.record(folder).get("modal_model")
        return isinstance(used, dict) and used.get("shapes_on_strings") == SHAPES_FRAME_UNDER_BED

    # -- what the pipeline wrote --------------------------------------------------------------
    @property
    def predict_dir(self) -> Path | None:
        """The folder of ``racketdyn predict``."""
        return self.first("impact.csv") or self.first(file_of("fig15_rebound_along_axis"))

    @property
    def ball_identification(self) -> Path | None:
        """The folder of the ``identify --ball-at`` run the report uses (the model of the racket
        with the ball on its strings), if any."""
        return next(
            (
                s.folder
                for s in self.steps
                if s.step == "identify" and self.record(s.folder).get("ball_at_m")
            ),
            None,
        )

    @property
    def frf_dirs(self) -> list[tuple[str, Path]]:
        """(label, folder) of every ``racketdyn frf`` run."""
        return [(self.label(folder), folder) for folder in self.with_file("quality.csv")]

    @property
    def identifications(self) -> list[tuple[str, Path, str]]:
        """(label, folder, file suffix) of every identified model."""
        found = []
        for folder in self.with_file("modes*.csv"):
            for path in sorted(folder.glob("modes*.csv")):
                match = re.fullmatch(r"modes(_[\w-]+)?\.csv", path.name)
                if match is None:
                    continue
                suffix = match.group(1) or ""
                given = next((s.label for s in self.steps if s.folder == folder), "")
                support = given or self.record(folder).get("support")
                label = suffix[1:] if suffix else str(support or folder.name)
                found.append((label, folder, suffix))
        return found

    def _comparison(self, of_models: bool) -> Path | None:
        for folder in self.with_file("comparison.csv"):
            if is_model_comparison(folder / "comparison.csv") == of_models:
                return folder
        return None

    @property
    def mode_comparison_dir(self) -> Path | None:
        """The folder of ``racketdyn compare``'s ``comparison.csv`` (modes paired by MAC)."""
        return self._comparison(of_models=False)

    @property
    def model_comparison_dir(self) -> Path | None:
        """The folder of ``racketdyn predict --model both``'s ``comparison.csv``."""
        return self._comparison(of_models=True)

    def head(self) -> HeadEllipse | None:
        """The string-bed outline: the given racket's, a run.json's, or the named racket's."""
        if self.racket is not None:
            return self.racket.head
        for record in self.records.values():
            head = record.get("racket", {}).get("head") if isinstance(record, dict) else None
            if isinstance(head, dict):
                try:
                    return HeadEllipse(
                        centre_x_m=float(head["centre_x_m"]),
                        half_length_m=float(head["half_length_m"]),
                        half_width_m=float(head["half_width_m"]),
                        centre_y_m=float(head.get("centre_y_m", 0.0)),
                    )
                except (KeyError, TypeError, ValueError, InputError):
                    continue
        racket = self.named_racket()
        return None if racket is None else racket.head

    def named_racket(self) -> Racket | None:
        """The racket a run.json names (built-in, or a TOML file still there), if any."""
        if "named_racket" not in self._cache:
            from racketdyn.io import default_racket, load_racket

            racket = None
            for record in self.records.values():
                name = str(record.get("racket_file", ""))
                try:
                    if name.startswith("built-in"):
                        racket = default_racket()
                    elif name and Path(name).is_file():
                        racket = load_racket(Path(name))
                except (InputError, OSError) as error:
                    log.warning("%s: not read (%s)", name, error)
                if racket is not None:
                    break
            self._cache["named_racket"] = racket
        named: Racket | None = self._cache["named_racket"]
        return named

    def derived(self) -> dict[str, Any]:
        """The racket's derived properties (unit-suffixed keys, SI units)."""
        if self.racket is not None:
            return dict(self.racket.derived_properties())
        for folder in filter(None, (self.predict_dir, self.first("hammer_*.uff"))):
            derived = self.record(folder).get("racket", {}).get("derived")
            if isinstance(derived, dict):
                return derived
        return {}

    def impacts(self) -> Impacts | None:
        """``impact.csv`` of ``racketdyn predict``, read once."""
        if "impacts" not in self._cache:
            folder = self.predict_dir
            path = folder / "impact.csv" if folder else None
            found = None
            if folder is not None and path is not None and path.is_file():
                found = Impacts.read(path, self.record(folder))
            self._cache["impacts"] = found
        impacts: Impacts | None = self._cache["impacts"]
        return impacts

    def centre(self, impacts: Impacts) -> tuple[float, float]:
        """The face centre, m: the head's, else the mean of the impact points."""
        head = self.head()
        if head is not None:
            return head.centre_x_m, head.centre_y_m
        return float(np.nanmean(impacts["x_m"])), float(np.nanmean(impacts["y_m"]))

    def first_mode_nodes(self) -> dict[str, list[float]]:
        """First-mode nodes along the axis (m from the butt), by support: the
        ``first_mode_nodes_m`` of ``racketdyn compare``'s run.json."""
        compare = self.mode_comparison_dir
        found = self.record(compare).get("first_mode_nodes_m")
        if not isinstance(found, dict):
            return {}
        return {
            str(support): [float(v) for v in values if isinstance(v, int | float)]
            for support, values in found.items()
            if isinstance(values, list)
        }

    # -- figures -------------------------------------------------------------------------------
    def figure(self, path: Path, label: str = "", wide: bool = False) -> Figure | None:
        """The PNG at ``path`` embedded with its caption; None if it is not a PNG."""
        where = f"{label}{' — ' if label else ''}{self.rel(path)}"
        self._cache.setdefault("embedded", set()).add(path)
        return embed_png(path, where, wide, self.record(path.parent))

    def unplaced(self, section: str) -> FigureGroup | None:
        """The registry's figures of ``section`` its ``gather`` did not place: each written in
        the folder of a step some figure of the page was embedded from (a figure added to the
        registry shows on the page with no section code; issue 23).  Call after every
        section's ``gather``."""
        embedded: set[Path] = self._cache.get("embedded", set())
        folders = {
            (found.step, path.parent)
            for path in embedded
            if (found := of_file(path.name)) is not None
        }
        missing = [
            (folder / figure.file, self.label(folder))
            for figure in in_section(section)
            for step, folder in sorted(folders, key=lambda pair: (pair[0], str(pair[1])))
            if step == figure.step and folder / figure.file not in embedded
        ]
        return self.group(missing)

    def group(
        self, found: list[tuple[Path, str]], layout: Layout | None = None, wide: bool = False
    ) -> FigureGroup | None:
        """The existing PNGs of (path, label) pairs; None if there are none.

        Parameters
        ----------
        found : list of (Path, str)
            Candidate PNG files, each with a label for its caption (empty for none).
        layout : {"pair", "stack", "plain"}, optional
            How they are shown; by default side by side when two or more, else stacked.
        wide : bool
            Figures that take the page's width.
        """
        figures = [
            f for path, label in found if path.is_file() and (f := self.figure(path, label, wide))
        ]
        if not figures:
            return None
        if layout is None:
            layout = "pair" if len(figures) > 1 else "stack"
        return FigureGroup(tuple(figures), layout)


def is_model_comparison(path: Path) -> bool:
    """Whether ``path`` is ``racketdyn predict --model both``'s ``comparison.csv``
    (approximate against transient), not the free-against-hand mode table of
    ``racketdyn compare``."""
    try:
        with path.open(encoding="utf-8") as handle:
            header = handle.readline()
    except UnicodeDecodeError as error:
        raise damaged(path, f"not text: binary data (byte {error.start} is not UTF-8)") from None
    except OSError as error:
        raise damaged(path, f"cannot be read ({error.strerror or error})") from None
    return "transient_rebound_ratio" in header.rstrip("\r\n").split(",")
