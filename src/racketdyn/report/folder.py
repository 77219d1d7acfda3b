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
import re
import shlex
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.errors import InputError
from racketdyn.impact.result import invalidate_table
from racketdyn.racket import HeadEllipse, Racket
from racketdyn.report.figures import Figure, FigureGroup, Layout, embed_png
from racketdyn.workflows.run import REPORT_NAME

__all__ = [
    "REPORT_NAME",
    "Impacts",
    "Row",
    "RunFolder",
    "damaged",
    "number",
    "read_csv",
    "read_json",
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

    def rows(self, speed: float, support: str) -> NDArray[np.intp]:
        """Row indices at one ball speed (m/s) and support."""
        return np.flatnonzero((self["ball_speed_mps"] == speed) & (self.support == support))

    def where(self, row: int) -> str:
        """``x, y`` of a row in mm, for tables."""
        return f"{self['x_m'][row] * 1e3:.0f}, {self['y_m'][row] * 1e3:.0f}"

    def nearest(self, rows: NDArray[np.intp], x: float, y: float) -> int:
        """The row among ``rows`` nearest the point (x, y), m."""
        distance = np.hypot(self["x_m"][rows] - x, self["y_m"][rows] - y)
        return int(rows[int(np.argmin(distance))])


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
        The folder and its sub-folders (hidden ones left out), the folder first.
    records : dict
        Each folder's ``run.json``, by folder.
    """

    run_dir: Path
    racket: Racket | None
    dirs: list[Path]
    records: dict[Path, dict[str, Any]]
    _cache: dict[str, Any] = field(default_factory=dict, repr=False)

    @classmethod
    def scan(cls, run_dir: Path, racket: Racket | None = None) -> RunFolder:
        """Read ``run_dir``: its sub-folders and every ``run.json``."""
        dirs, records = _scan(run_dir)
        return cls(run_dir, racket, dirs, records)

    def with_file(self, pattern: str) -> list[Path]:
        """Folders holding a file that matches ``pattern``, the run folder first."""
        return [d for d in self.dirs if any(d.glob(pattern))]

    def first(self, pattern: str) -> Path | None:
        """The first folder holding a file that matches ``pattern``."""
        found = self.with_file(pattern)
        return found[0] if found else None

    def rel(self, path: Path) -> str:
        """``path`` relative to the run folder, with forward slashes."""
        return path.relative_to(self.run_dir).as_posix()

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

    # -- what the pipeline wrote --------------------------------------------------------------
    @property
    def predict_dir(self) -> Path | None:
        """The folder of ``racketdyn predict``."""
        return self.first("impact.csv") or self.first("fig15_rebound_along_axis.png")

    @property
    def frf_dirs(self) -> list[tuple[str, Path]]:
        """(label, folder) of every ``racketdyn frf`` run."""
        found = []
        for folder in self.with_file("quality.csv"):
            if folder.name.startswith("frf_"):
                label = folder.name[4:]
            else:
                tests = self.record(folder).get("tests_file")
                label = Path(str(tests)).stem.removeprefix("hammer_") if tests else folder.name
            found.append((label, folder))
        return found

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
                support = self.record(folder).get("support")
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
        return embed_png(path, where, wide, self.record(path.parent))

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
