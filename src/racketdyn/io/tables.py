"""Plain CSV tables: impact points and load–deflection data.

Impact points: a header with ``x_m`` and ``y_m`` (metres; x from the butt along the long axis, y
across it) and optionally ``point`` (a label or number).  Load–deflection: a header with
``deflection_m`` and ``force_n``.  e_BG against speed: a header with ``speed_mps`` and
``e_bg``.  Lines starting with ``#`` are comments.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from racketdyn._grammar import noun
from racketdyn.errors import InputError
from racketdyn.plausibility import check_load_deflection

__all__ = ["read_e_bg_table", "read_load_deflection", "read_points", "split_csv_line"]


def split_csv_line(path: Path, number: int, line: str) -> list[str]:
    """The fields of one CSV line; InputError naming the line for a quote left open.

    Each line is split on its own: read as one stream, a quote opened on one line (a flipped
    byte, a typing slip) swallowed the rest of the file into one field (issue 26's fuzz test).
    """
    try:
        return next(csv.reader([line], skipinitialspace=True, strict=True), [])
    except csv.Error as error:
        raise InputError(
            f'{path}: line {number}: a quote (") opened and not closed on its line ({error}); '
            "remove the quote or close it"
        ) from None


def _read_columns(path: Path, required: tuple[str, ...]) -> dict[str, list[tuple[int, str]]]:
    """Columns of a CSV file as (file line number, text) pairs, comments and blank lines skipped."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise InputError(f"{path}: is a folder; give a CSV file") from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot be read as UTF-8 text ({error})") from None
    lines = [
        (number, line)
        for number, line in enumerate(text.splitlines(), start=1)
        if line.strip() and not line.lstrip().startswith("#")
    ]
    if not lines:
        raise InputError(f"{path}: empty; expected a header with columns {', '.join(required)}")
    rows = [split_csv_line(path, number, line) for number, line in lines]
    header = [name.strip() for name in rows[0]]
    missing = [name for name in required if name not in header]
    if missing:
        raise InputError(
            f"{path}: missing {noun(len(missing), 'column')} {', '.join(missing)}; "
            "the header must name "
            f"{', '.join(required)} (found {', '.join(header) or 'nothing'})"
        )
    columns: dict[str, list[tuple[int, str]]] = {name: [] for name in header}
    for (number, _), row in zip(lines[1:], rows[1:], strict=True):
        if len(row) != len(header):
            raise InputError(
                f"{path}: line {number} has {len(row)} values for {len(header)} columns "
                f"({', '.join(header)})"
            )
        for name, value in zip(header, row, strict=True):
            columns[name].append((number, value.strip()))
    return columns


def _numbers(
    path: Path, columns: dict[str, list[tuple[int, str]]], name: str
) -> NDArray[np.float64]:
    values = []
    for number, text in columns[name]:
        try:
            value = float(text)
        except ValueError:
            raise InputError(
                f"{path}: line {number}, column {name}: {text!r} is not a number"
            ) from None
        if not np.isfinite(value):
            raise InputError(
                f"{path}: line {number}, column {name}: {text!r} is not a finite number"
            )
        values.append(value)
    return np.asarray(values, dtype=float)


def read_points(path: Path) -> tuple[NDArray[np.float64], list[str]]:
    """Read impact points from a CSV file.

    Parameters
    ----------
    path : Path
        CSV with columns ``x_m``, ``y_m`` (m) and optionally ``point`` (labels).

    Returns
    -------
    locations : ndarray, shape (n, 2)
        Impact points (x, y), m.
    labels : list of str
        The ``point`` column, or 1, 2, … without one.
    """
    columns = _read_columns(path, ("x_m", "y_m"))
    x = _numbers(path, columns, "x_m")
    y = _numbers(path, columns, "y_m")
    if x.size == 0:
        raise InputError(f"{path}: no impact points listed")
    if "point" in columns:
        labels = [text for _, text in columns["point"]]
        blank = [number for number, text in columns["point"] if not text]
        if blank:
            raise InputError(
                f"{path}: line {blank[0]}: the point column is empty; label every point"
            )
    else:
        labels = [str(i) for i in range(1, x.size + 1)]
    return np.column_stack([x, y]), labels


def read_load_deflection(path: Path) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Read load–deflection data from a CSV file.

    Parameters
    ----------
    path : Path
        CSV with columns ``deflection_m`` (m) and ``force_n`` (N).

    Returns
    -------
    deflection, force : ndarray
        Deflection in m and force in N.

    Raises
    ------
    InputError
        Also when the data's scale shows a unit slip: deflections beyond 0.1 m (millimetres
        given as metres) or load over deflection under 500 N/m (kilonewtons given as newtons);
        see :func:`racketdyn.plausibility.check_load_deflection`.
    """
    columns = _read_columns(path, ("deflection_m", "force_n"))
    deflection = _numbers(path, columns, "deflection_m")
    force = _numbers(path, columns, "force_n")
    _rising(path, columns, "deflection_m", deflection, "a law's deflections")
    check_load_deflection(str(path), deflection, force)
    return deflection, force


def _rising(
    path: Path,
    columns: dict[str, list[tuple[int, str]]],
    name: str,
    values: NDArray[np.float64],
    what: str,
) -> None:
    """Refuse a column that does not rise strictly, naming the file's line (issue 26: unsorted
    or repeated rows were fitted as given)."""
    lines = [number for number, _ in columns[name]]
    for k in range(1, values.size):
        if values[k] <= values[k - 1]:
            how = "repeats" if values[k] == values[k - 1] else "comes after"
            raise InputError(
                f"{path}: line {lines[k]}: {name} {values[k]:g} {how} {values[k - 1]:g} (line "
                f"{lines[k - 1]}); {what} must rise from row to row: sort the rows and give "
                "each value once"
            )


def read_e_bg_table(path: Path) -> tuple[tuple[float, float], ...]:
    """Read e_BG against relative speed from a CSV file (``Ball.e_bg_table``).

    Parameters
    ----------
    path : Path
        CSV with columns ``speed_mps`` (relative ball–racket speed, m/s) and ``e_bg`` (COR of
        the ball on the head-clamped strings at that speed), speeds rising.

    Returns
    -------
    tuple of (float, float)
        ``(speed_mps, e_bg)`` pairs; :class:`~racketdyn.ball.Ball` checks their order and range.
    """
    columns = _read_columns(path, ("speed_mps", "e_bg"))
    speed = _numbers(path, columns, "speed_mps")
    e_bg = _numbers(path, columns, "e_bg")
    if speed.size < 2:
        raise InputError(f"{path}: an e_BG table needs at least two speeds (got {speed.size})")
    lines = [number for number, _ in columns["e_bg"]]
    for k, (v, e) in enumerate(zip(speed, e_bg, strict=True)):
        if v < 0:
            raise InputError(f"{path}: line {lines[k]}: speed_mps {v:g} is negative; give m/s ≥ 0")
        if not 0.0 < e <= 1.0:
            raise InputError(
                f"{path}: line {lines[k]}: e_bg {e:g}; the COR of a ball on strings lies above 0 "
                "(0 is no rebound at all) and at most 1"
                + (" (a fraction: 0.83, not 83)" if e > 1.0 else "")
            )
    _rising(path, columns, "speed_mps", speed, "an e_BG table's speeds")
    if np.any(speed > 340.0):
        raise InputError(
            f"{path}: speed_mps above 340 m/s; give speeds in m/s (km/h divided by 3.6)"
        )
    if np.any(e_bg > 1.0):
        raise InputError(f"{path}: e_bg above 1; give the COR as a fraction (0.83, not 83)")
    return tuple((float(v), float(e)) for v, e in zip(speed, e_bg, strict=True))
