"""FRFs exported one text file per point, put together by a table of the test's points.

Some acquisition systems export each FRF to a text file of its own that names no point:
DataPhysics SignalCalc's text export, for instance, holds a short header (the channels as
``Ref Chan:Resp Chan``, the columns ``Frequency Real Imaginary`` and their units such as
``Hz (m/s²)(N)``) and one line per frequency. Which point each file measured is in the lab's
notes. The *FRF table* says it: a CSV file with one row per exported file and one for the
fixed sensor::

    file,node,x_m,y_m,z_m,direction
    Hxysv00001.txt,1,0,0,0.100,+x
    Hxysv00002.txt,2,0,0,0.250,+x
    reference,10,0,0,0.500,-x

``file`` is the export (a path relative to the table) of the FRF with the hammer at that row's
node, or ``reference`` for the fixed accelerometer (a roving-hammer test); ``x_m, y_m, z_m``
the point in the lab's frame, m (the reference's may be left empty); ``direction`` the
hammer's or the sensor's axis and sense (``+x`` … ``-z``). Lines starting with ``#`` are
comments, but for ``# units: m/N`` (response over force), the units of exports that hold
only numbers, three a line (frequency, real and imaginary part), as tap-test programs write
them. The FRFs are given in the lab's frame: an FRF whose hammer and sensor point opposite
ways along their axis is negated, as a Universal File's direction codes are.

The format is documented in docs/uff-and-csv.md ("FRFs exported one file per point"). The
columns are read with the standard library's :mod:`csv` and each export with
:func:`numpy.loadtxt`; no library reads SignalCalc's text export (pyuff reads Universal Files
only), hence this small parser of its header.
"""

from __future__ import annotations

import csv
import logging
import re
from dataclasses import dataclass
from pathlib import Path
from typing import cast

import numpy as np
from numpy.typing import NDArray

from racketdyn.errors import InputError
from racketdyn.io.uff import UNIT_SCALE, _locations, _normal_label
from racketdyn.measurement.records import (
    ABSURD_FRF,
    FRF_TYPE_OF_RESPONSE,
    FrfSet,
    FrfType,
    same_lines,
)

__all__ = ["COLUMNS", "is_frf_table", "read_frf_table", "read_text_frf"]

log = logging.getLogger(__name__)

COLUMNS = ("file", "node", "x_m", "y_m", "z_m", "direction")
"""The FRF table's columns, in this order."""
REFERENCE_ROW = "reference"
"""The ``file`` of the fixed sensor's row."""
_AXES = {"x": 0, "y": 1, "z": 2}
_UNITS = re.compile(r"\(([^()]+)\)\s*/?\s*\(([^()]+)\)")


@dataclass(frozen=True)
class TextFrf:
    """One FRF read from a text export: its lines (Hz), values (SI) and response type."""

    frequency: NDArray[np.float64]
    values: NDArray[np.complex128]
    response: str
    channels: str


def is_frf_table(path: Path) -> bool:
    """Whether ``path`` is an FRF table (a ``.csv`` file whose header starts ``file,node``)."""
    if path.suffix.lower() != ".csv" or not path.is_file():
        return False
    with path.open(encoding="utf-8", errors="replace") as handle:
        for line in handle:
            if line.strip() and not line.lstrip().startswith("#"):
                return line.replace(" ", "").lower().startswith("file,node")
    return False


def _unit(path: Path, label: str, quantities: tuple[str, ...]) -> tuple[str, float]:
    """The quantity and SI factor of a units label such as ``m/s²`` or ``g``."""
    key = _normal_label(label) or ""
    for quantity in quantities:
        if key in UNIT_SCALE[quantity]:
            return quantity, UNIT_SCALE[quantity][key]
    known = ", ".join(u for q in quantities for u in UNIT_SCALE[q])
    raise InputError(f"{path}: unit {label.strip()!r} is not one racketdyn reads ({known})")


def _bare(lines: list[str]) -> bool:
    """Whether an export starts with its data: three numbers a line and no header."""
    first = next((s for s in lines if s.strip()), "")
    try:
        return len([float(x) for x in first.replace(",", " ").split()]) == 3
    except ValueError:
        return False


def _units(path: Path, label: str) -> tuple[str, float]:
    """The response type and the SI factor of an FRF's units, ``(m/s²)(N)`` as SignalCalc writes
    them or ``m/s²/N`` (response over force) as an FRF table's ``# units:`` line says them."""
    found = _UNITS.search(label)
    parts = (found[1], found[2]) if found else tuple(label.strip().rsplit("/", 1))
    if len(parts) != 2:
        raise InputError(
            f"{path}: units {label.strip()!r} do not read as response over force, e.g. "
            "'(m/s²)(N)' or 'm/s²/N'"
        )
    response, response_scale = _unit(path, parts[0], ("acceleration", "velocity", "displacement"))
    _, force_scale = _unit(path, parts[1], ("force",))
    return response, response_scale / force_scale


def _header(path: Path, lines: list[str]) -> tuple[int, str, str]:
    """The first data line's index, the units line and the channels of a text export."""
    columns = next((i for i, s in enumerate(lines[:40]) if s.lower().startswith("frequency")), None)
    if columns is None:
        raise InputError(
            f"{path}: no 'Frequency Real Imaginary' header in its first 40 lines: not an FRF "
            "text export racketdyn reads (export the FRF as real and imaginary parts)"
        )
    names = lines[columns].lower().split()
    if names[1:3] != ["real", "imaginary"]:
        raise InputError(
            f"{path}: columns {' '.join(lines[columns].split())!r}; racketdyn reads FRFs as "
            "'Frequency Real Imaginary' (export real and imaginary parts, not magnitude and phase)"
        )
    units = next((i for i in range(columns + 1, len(lines)) if lines[i].startswith("Hz")), None)
    if units is None:
        raise InputError(f"{path}: no units line ('Hz  (m/s²)(N)') after the column names")
    channels = next((s.split(None, 3)[-1] for s in lines[:columns] if "Chan" in s), "")
    return units + 1, lines[units], channels.strip()


def read_text_frf(path: Path | str, units: str | None = None) -> TextFrf:
    """Read one FRF from a text export (DataPhysics SignalCalc's, columns Frequency Real
    Imaginary), in SI units.

    Parameters
    ----------
    path : Path or str
        The export.
    units : str, optional
        The FRF's units, response over force (``m/N``, ``g/N``, ``m/s²/N``), for an export
        without a header: three numbers a line from its first line (frequency, real and
        imaginary part), as tap-test programs write them. An export with a header must agree.

    Returns
    -------
    TextFrf
        Lines in Hz, values in SI units of their type (m/(N·s²) for an accelerance), the
        response (``"acceleration"``, ``"velocity"`` or ``"displacement"``) and the channels
        as the file names them. A last line that is not finite (the Nyquist line some
        exports write so) is dropped, with a log line.

    Raises
    ------
    InputError
        Not such an export, a unit racketdyn does not read, a non-finite or absurd value.
    """
    path = Path(path)
    raw = path.read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:  # SignalCalc writes its units' ² in Latin-1
        text = raw.decode("latin-1")
    lines = text.splitlines()
    if _bare(lines):
        if units is None:
            raise InputError(
                f"{path}: lines of numbers with no header naming their units: say them in the "
                "FRF table, a line '# units: m/N' (response over force: m/N, m/s²/N, g/N …)"
            )
        start, channels = 0, ""
        response, scale = _units(path, units)
    else:
        start, units_line, channels = _header(path, lines)
        if _UNITS.search(units_line) is None:
            raise InputError(
                f"{path}: units {units_line.strip()!r} do not read as '(response)(force)', "
                "e.g. '(m/s²)(N)'"
            )
        response, scale = _units(path, units_line)
        if units is not None and _units(path, units) != (response, scale):
            raise InputError(
                f"{path}: its header says units {units_line.strip()!r}, the FRF table "
                f"{units!r}; remove the table's '# units:' line or correct it"
            )
    try:
        data = np.loadtxt(lines[start:], ndmin=2)
    except ValueError as error:
        raise InputError(f"{path}: a data line is not three numbers ({error})") from None
    if data.shape[1] != 3 or data.shape[0] < 8:
        raise InputError(f"{path}: needs lines of three numbers (Hz, real, imaginary), 8 or more")
    if not np.all(np.isfinite(data[-1])):
        log.info("%s: the last line (%g Hz) is not finite: dropped", path, data[-1, 0])
        data = data[:-1]
    bad = np.flatnonzero(~np.all(np.isfinite(data), axis=1))
    if bad.size:
        raise InputError(f"{path}: line {start + int(bad[0]) + 1} is not finite")
    values = np.asarray((data[:, 1] + 1j * data[:, 2]) * scale, dtype=complex)
    if np.abs(values).max() > ABSURD_FRF:
        raise InputError(
            f"{path}: an FRF value of {np.abs(values).max():.3g} SI units: damage or a unit slip"
        )
    frequency = data[:, 0]
    if np.any(np.diff(frequency) <= 0):
        raise InputError(f"{path}: the frequencies do not rise line by line")
    return TextFrf(frequency, values, response, channels)


@dataclass(frozen=True)
class _Row:
    file: str
    node: int
    xyz: tuple[float, float, float]
    axis: int
    sign: float


def _number(table: Path, line: int, column: str, text: str, *, empty: bool) -> float:
    if not text.strip() and empty:
        return float("nan")
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{table}, line {line}: {column} {text!r} is not a number") from None
    if not np.isfinite(value):
        raise InputError(f"{table}, line {line}: {column} must be finite")
    return value


def _row(table: Path, line: int, cells: dict[str, str]) -> _Row:
    reference = cells["file"].strip().lower() == REFERENCE_ROW
    try:
        node = int(cells["node"])
    except ValueError:
        raise InputError(
            f"{table}, line {line}: node {cells['node']!r} is not a whole number"
        ) from None
    if node <= 0:
        raise InputError(f"{table}, line {line}: node {node} must be a positive number")
    xyz = tuple(_number(table, line, c, cells[c], empty=reference) for c in ("x_m", "y_m", "z_m"))
    direction = cells["direction"].strip().lower()
    if len(direction) != 2 or direction[0] not in "+-" or direction[1] not in _AXES:
        raise InputError(
            f"{table}, line {line}: direction {cells['direction']!r}; give +x, -x, +y, -y, +z or -z"
        )
    sign = 1.0 if direction[0] == "+" else -1.0
    return _Row(
        cells["file"].strip(),
        node,
        cast(tuple[float, float, float], xyz),
        _AXES[direction[1]],
        sign,
    )


def _table_units(table: Path) -> str | None:
    """The units of the table's exports from its ``# units: m/N`` line, if it has one."""
    with table.open(encoding="utf-8") as handle:
        for line in handle:
            key, _, value = line.lstrip().lstrip("#").partition(":")
            if line.lstrip().startswith("#") and key.strip().lower() == "units" and value.strip():
                return value.strip()
    return None


def _rows(table: Path) -> tuple[list[_Row], _Row]:
    """The table's point rows and its reference row."""
    with table.open(newline="", encoding="utf-8") as handle:
        numbered = [
            (i, s)
            for i, s in enumerate(handle, start=1)
            if s.strip() and not s.lstrip().startswith("#")
        ]
    if not numbered:
        raise InputError(f"{table}: empty; an FRF table has the columns {','.join(COLUMNS)}")
    header = [c.strip().lower() for c in next(csv.reader([numbered[0][1]]))]
    if tuple(header) != COLUMNS:
        raise InputError(
            f"{table}: columns {','.join(header)}; an FRF table has {','.join(COLUMNS)}"
        )
    rows = []
    for line, text in numbered[1:]:
        cells = next(csv.reader([text]))
        if len(cells) != len(COLUMNS):
            raise InputError(
                f"{table}, line {line}: {len(cells)} cells; a row has {len(COLUMNS)}: "
                f"{','.join(COLUMNS)}"
            )
        rows.append(_row(table, line, dict(zip(COLUMNS, cells, strict=True))))
    references = [r for r in rows if r.file.lower() == REFERENCE_ROW]
    points = [r for r in rows if r.file.lower() != REFERENCE_ROW]
    if len(references) != 1:
        raise InputError(
            f"{table}: {len(references)} rows with file 'reference'; give one, the fixed "
            "accelerometer's node, location and direction"
        )
    if not points:
        raise InputError(f"{table}: no FRF file listed")
    nodes = [r.node for r in points]
    twice = sorted({n for n in nodes if nodes.count(n) > 1})
    if twice:
        raise InputError(f"{table}: node {twice[0]} has two files; one FRF a point")
    if len({r.axis for r in rows}) > 1:
        raise InputError(
            f"{table}: hammer and sensor directions along different axes; racketdyn reads "
            "FRFs along one axis (give each file's direction along it)"
        )
    return points, references[0]


def read_frf_table(path: Path | str, reference: int | None = None) -> FrfSet:
    """Read the FRFs of a roving-hammer test exported one text file per point.

    Parameters
    ----------
    path : Path or str
        The FRF table (module docstring): each exported file with its node, location and
        direction, and the fixed accelerometer's row.
    reference : int, optional
        The reference node; must be the table's reference row's node when given.

    Returns
    -------
    FrfSet
        Points ordered by node number, locations (x, y, z) in m ((x, y) when every point and
        the reference share one z), values in SI units in the lab's frame, layout
        ``"roving hammer"``.

    Raises
    ------
    InputError
        A malformed table or export, files of different lines or response types.
    """
    table = Path(path)
    points, fixed = _rows(table)
    if reference is not None and reference != fixed.node:
        raise InputError(
            f"{table}: reference {reference} is not the table's reference row's node ({fixed.node})"
        )
    points = sorted(points, key=lambda r: r.node)
    units = _table_units(table)
    frfs = []
    for row in points:
        file = (table.parent / row.file).resolve()
        if not file.is_file():
            raise InputError(f"{table}: {row.file} (node {row.node}) is not a file")
        frfs.append(read_text_frf(file, units))
    first = frfs[0]
    for row, frf in zip(points, frfs, strict=True):
        if frf.response != first.response:
            raise InputError(
                f"{table}: {row.file} holds {frf.response} per force, {points[0].file} "
                f"{first.response}; one FRF type a test"
            )
        if not same_lines(frf.frequency, first.frequency):
            raise InputError(f"{table}: {row.file}'s lines are not {points[0].file}'s")
    # the reference at a point's node is that point (its row's coordinates may be empty)
    coordinates = {fixed.node: fixed.xyz, **{r.node: r.xyz for r in points}}
    locations, reference_location = _locations(coordinates, [r.node for r in points], fixed.node)
    return FrfSet(
        frequency=first.frequency,
        values=np.asarray(
            [f.values * r.sign * fixed.sign for f, r in zip(frfs, points, strict=True)]
        ),
        frf_type=cast(FrfType, FRF_TYPE_OF_RESPONSE[first.response]),
        nodes=tuple(r.node for r in points),
        locations=locations,
        reference_node=fixed.node,
        reference_location=reference_location,
        source=str(table),
        metadata={
            "layout": "roving hammer",
            "channels": first.channels,
            "directions": {r.node: r.axis + 1 for r in points},  # +x, +y, +z: the lab's frame
        },
    ).with_usual_phase()
