"""Plain CSV tables: impact points and load–deflection data.

Impact points: a header with ``x_m`` and ``y_m`` (metres; x from the butt along the long axis, y
across it) and optionally ``point`` (a label or number).  Load–deflection: a header with
``deflection_m`` and ``force_n``.  Lines starting with ``#`` are comments.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from racketdyn.errors import InputError

__all__ = ["read_load_deflection", "read_points"]


def _read_columns(path: Path, required: tuple[str, ...]) -> dict[str, list[str]]:
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot be read as UTF-8 text ({error})") from None
    lines = [
        line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")
    ]
    if not lines:
        raise InputError(f"{path}: empty; expected a header with columns {', '.join(required)}")
    reader = csv.DictReader(lines, skipinitialspace=True)
    header = [name.strip() for name in (reader.fieldnames or [])]
    missing = [name for name in required if name not in header]
    if missing:
        raise InputError(
            f"{path}: missing column(s) {', '.join(missing)}; the header must name "
            f"{', '.join(required)} (found {', '.join(header) or 'nothing'})"
        )
    columns: dict[str, list[str]] = {name: [] for name in header}
    for row in reader:
        for name in header:
            columns[name].append((row.get(name) or "").strip())
    return columns


def _numbers(path: Path, columns: dict[str, list[str]], name: str) -> NDArray[np.float64]:
    values = []
    for line, text in enumerate(columns[name], start=2):
        try:
            value = float(text)
        except ValueError:
            raise InputError(
                f"{path}: row {line}, column {name}: {text!r} is not a number"
            ) from None
        if not np.isfinite(value):
            raise InputError(f"{path}: row {line}, column {name}: {text!r} is not a finite number")
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
    labels = columns.get("point") or [str(i) for i in range(1, x.size + 1)]
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
    """
    columns = _read_columns(path, ("deflection_m", "force_n"))
    return _numbers(path, columns, "deflection_m"), _numbers(path, columns, "force_n")
