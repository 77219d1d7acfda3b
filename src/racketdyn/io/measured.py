"""Measured rebound over the face: the CSV a ball-cannon test writes (issue 15).

One row per measured impact: where the ball struck the strings, how fast it came and how fast
the racket moved, how the racket was held, and what came back.  Columns (SI; lines starting
with ``#`` are comments; docs/formats.md, "Measured rebound"):

=====================  ========  ==========================================================
column                 unit      meaning
=====================  ========  ==========================================================
``x_m``, ``y_m``       m         impact point: x from the butt along the long axis, y across
``ball_speed_mps``     m/s       incoming ball speed towards the strings (> 0)
``racket_speed_mps``   m/s       speed of the impact point towards the ball (0: at rest)
``support``            –         ``free``, ``pinned`` (a handle clamped on a pivot) or ``hand``
``rebound_ratio``      –         e = (v_out − v_racket) / (v_ball + v_racket)
``outgoing_speed_mps`` m/s       the ball's speed away from the strings, instead of the ratio
``rebound_ratio_sd``   –         optional: one standard deviation of the ratio
``outgoing_speed_sd_mps`` m/s    optional, with ``outgoing_speed_mps``: its standard deviation
``point``              –         optional label
=====================  ========  ==========================================================

The rebound ratio of a moving racket is the one of :mod:`racketdyn.impact`: the outgoing speed
is ``e·v_ball + (1 + e)·v_racket`` (the glossary's ``rebound_speed``), so
``e = (v_out − v_racket) / (v_ball + v_racket)``; for a racket at rest it is the ratio of
outgoing to incoming ball speed (the "apparent COR" of the literature).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.errors import InputError
from racketdyn.io.tables import _numbers, _read_columns
from racketdyn.plausibility import check

__all__ = [
    "MEASURED_SUPPORTS",
    "RATIO_RANGE",
    "MeasuredRebound",
    "outgoing_to_ratio",
    "read_measured",
]

MEASURED_SUPPORTS = ("free", "pinned", "hand")
"""How a measured racket is held: suspended, handle clamped on a pivot, or in a hand."""

RATIO_RANGE = (-0.2, 1.0)
"""Rebound ratios a measurement can hold.  Above 1 the ball would leave faster than an elastic
impact on an immovable racket returns it.  Below 0 the ball goes on towards the racket after the
impact, slower: possible only where the racket is very light under the ball (a free racket's
tip), and measured ratios there are ≈ 0.1 (docs/validation.md); −0.2 leaves room for that
(the approximate method predicts ≈ −0.3 at the tip of the built-in free racket at 15 m/s, the
model's own weakness there, not a measurement)."""

MAX_SD = 0.5
"""Largest standard deviation of a rebound ratio taken (half the whole range)."""

REQUIRED = ("x_m", "y_m", "ball_speed_mps", "racket_speed_mps", "support")


def outgoing_to_ratio(
    outgoing_speed: ArrayLike, ball_speed: ArrayLike, racket_speed: ArrayLike
) -> NDArray[np.float64]:
    """Rebound ratio from the measured outgoing ball speed (glossary ``rebound_ratio``).

    Parameters
    ----------
    outgoing_speed : array_like
        Ball speed away from the strings after impact, m/s.
    ball_speed : array_like
        Incoming ball speed towards the strings, m/s.
    racket_speed : array_like
        Speed of the impact point towards the ball before impact, m/s.

    Returns
    -------
    ndarray
        ``(v_out − v_racket) / (v_ball + v_racket)``: the inverse of
        ``v_out = e·v_ball + (1 + e)·v_racket``.
    """
    v_out = np.asarray(outgoing_speed, dtype=float)
    v_b = np.asarray(ball_speed, dtype=float)
    v_r = np.asarray(racket_speed, dtype=float)
    return np.asarray((v_out - v_r) / (v_b + v_r))


@dataclass(frozen=True, eq=False)
class MeasuredRebound:
    """Measured rebound ratios, one per row of the file.

    Attributes
    ----------
    locations : ndarray (n, 2)
        Impact points (x, y), m.
    ball_speed, racket_speed : ndarray (n,)
        Incoming ball speed and racket speed towards the ball, m/s.
    support : tuple of str
        Each row's support.
    rebound_ratio : ndarray (n,)
        Measured rebound ratio (from the outgoing speed when that was given).
    rebound_ratio_sd : ndarray (n,) or None
        One standard deviation of each ratio; None when the file gives none.
    labels : tuple of str
        Point labels (the ``point`` column, else the row number 1, 2, …).
    lines : tuple of int
        Line of the file each row came from (for messages).
    source : str
        The file, or what the rows are.
    given : str
        ``rebound_ratio`` or ``outgoing_speed_mps``: what the file measured.
    """

    locations: NDArray[np.float64]
    ball_speed: NDArray[np.float64]
    racket_speed: NDArray[np.float64]
    support: tuple[str, ...]
    rebound_ratio: NDArray[np.float64]
    rebound_ratio_sd: NDArray[np.float64] | None
    labels: tuple[str, ...]
    lines: tuple[int, ...]
    source: str = ""
    given: str = "rebound_ratio"

    def __len__(self) -> int:
        return int(self.rebound_ratio.size)

    def row_label(self, i: int) -> str:
        """Row ``i``'s (0-based) name: its point's label, with its row number (1 = the first
        data row) when the point is measured more than once: ``C (row 7)``."""
        label = self.labels[i]
        return label if self.labels.count(label) == 1 else f"{label} (row {i + 1})"

    def __repr__(self) -> str:
        supports = ",".join(sorted(set(self.support)))
        sd = "with" if self.rebound_ratio_sd is not None else "without"
        return f"<MeasuredRebound {len(self)} rows ({supports}) {sd} sd from {self.source!r}>"

    @property
    def outgoing_speed(self) -> NDArray[np.float64]:
        """Outgoing ball speed of each row, m/s: e·v_ball + (1 + e)·v_racket."""
        e = self.rebound_ratio
        return np.asarray(e * self.ball_speed + (1.0 + e) * self.racket_speed)

    def subset(self, rows: Sequence[int] | NDArray[np.int_]) -> MeasuredRebound:
        """The rows at these indices (0-based), in that order."""
        index = np.asarray(rows, dtype=int)
        return MeasuredRebound(
            self.locations[index],
            self.ball_speed[index],
            self.racket_speed[index],
            tuple(self.support[i] for i in index),
            self.rebound_ratio[index],
            None if self.rebound_ratio_sd is None else self.rebound_ratio_sd[index],
            tuple(self.labels[i] for i in index),
            tuple(self.lines[i] for i in index),
            self.source,
            self.given,
        )


def _where(path: Path, line: int, column: str) -> str:
    return f"{path}: line {line}, column {column}"


def _check_ratio(path: Path, line: int, column: str, value: float, hint: str) -> None:
    low, high = RATIO_RANGE
    if low <= value <= high:
        return
    slip = ""
    if column == "rebound_ratio" and 1.0 < value <= 100.0:
        slip = f"; did you give percent ({value:g} % = {value / 100:g})? Give a fraction"
    raise InputError(
        f"{_where(path, line, column)}: rebound ratio {value:.4g} lies outside "
        f"{low:g} to {high:g}{slip}{hint}"
    )


def read_measured(path: Path | str, *, allow_implausible: bool = False) -> MeasuredRebound:
    """Read measured rebound from a CSV file (layout in the module docstring).

    Parameters
    ----------
    path : path
        The CSV file.
    allow_implausible : bool
        Take speeds beyond those of play (75 m/s) that are inside the limits
        (:mod:`racketdyn.plausibility`; ``--allow-implausible``).

    Returns
    -------
    MeasuredRebound

    Raises
    ------
    InputError
        In one line naming the file, the line and the column: a missing column, both or
        neither of ``rebound_ratio`` and ``outgoing_speed_mps``, a value that is not a number,
        a support not in free/pinned/hand, and unit slips: points beyond 1 m (millimetres),
        speeds beyond those of play (km/h), ratios above 1 (percent), a standard deviation of
        zero or above 0.5.
    """
    path = Path(path)
    columns = _read_columns(path, REQUIRED)
    has_ratio, has_out = "rebound_ratio" in columns, "outgoing_speed_mps" in columns
    if has_ratio == has_out:
        raise InputError(
            f"{path}: give one of the columns rebound_ratio and outgoing_speed_mps "
            f"({'both' if has_ratio else 'neither'} found)"
        )
    lines = tuple(number for number, _ in columns["x_m"])
    if not lines:
        raise InputError(f"{path}: no measured rows below the header")
    x = _numbers(path, columns, "x_m")
    y = _numbers(path, columns, "y_m")
    for name, values, limit in (("x_m", x, 1.0), ("y_m", y, 0.5)):
        for line, value in zip(lines, values, strict=True):
            if abs(value) > limit:
                raise InputError(
                    f"{_where(path, line, name)}: {value:g} m is off any racket (|{name}| ≤ "
                    f"{limit:g} m); did you give millimetres ({value:g} mm = {value / 1e3:g} m)? "
                    "Give metres"
                )
    v_b = _numbers(path, columns, "ball_speed_mps")
    v_r = _numbers(path, columns, "racket_speed_mps")
    for name, values, key in (
        ("ball_speed_mps", v_b, "ball_speed_mps"),
        ("racket_speed_mps", v_r, "racket_speed_mps"),
    ):
        for line, value in zip(lines, values, strict=True):
            if value < 0 or (name == "ball_speed_mps" and value == 0):
                need = "above 0" if name == "ball_speed_mps" else "0 or above"
                raise InputError(
                    f"{_where(path, line, name)}: {value:g} m/s; a speed towards the other body "
                    f"must be {need}"
                )
            check(key, value, _where(path, line, name), allow_implausible=allow_implausible)
    supports = []
    for line, text in columns["support"]:
        if text not in MEASURED_SUPPORTS:
            raise InputError(
                f"{_where(path, line, 'support')}: {text!r} is not a support; give free "
                "(suspended), pinned (handle clamped on a pivot) or hand"
            )
        supports.append(text)
    given = "rebound_ratio" if has_ratio else "outgoing_speed_mps"
    measured = _numbers(path, columns, given)
    if has_ratio:
        ratio = measured
        for line, value in zip(lines, ratio, strict=True):
            _check_ratio(path, line, "rebound_ratio", value, "")
    else:
        ratio = outgoing_to_ratio(measured, v_b, v_r)
        for line, value, out, vb, vr in zip(lines, ratio, measured, v_b, v_r, strict=True):
            hint = ""
            if value > 1.0 and RATIO_RANGE[0] <= outgoing_to_ratio(out / 3.6, vb, vr) <= 1.0:
                hint = "; did you give km/h? Give m/s"
            _check_ratio(
                path,
                line,
                "outgoing_speed_mps",
                float(value),
                f" (outgoing {out:g} m/s: e = (v_out − v_racket)/(v_ball + v_racket)){hint}",
            )
    sd = _read_sd(path, columns, lines, has_ratio, v_b + v_r)
    if "point" in columns:
        labels = tuple(text for _, text in columns["point"])
        blank = [line for line, text in columns["point"] if not text]
        if blank:
            raise InputError(f"{path}: line {blank[0]}: the point column is empty; label it")
    else:
        labels = tuple(str(i) for i in range(1, len(lines) + 1))
    return MeasuredRebound(
        np.column_stack([x, y]),
        v_b,
        v_r,
        tuple(supports),
        np.asarray(ratio, dtype=float),
        sd,
        labels,
        lines,
        str(path),
        given,
    )


def _read_sd(
    path: Path,
    columns: dict[str, list[tuple[int, str]]],
    lines: tuple[int, ...],
    has_ratio: bool,
    approach: NDArray[np.float64],
) -> NDArray[np.float64] | None:
    """The standard deviation of each ratio, from ``rebound_ratio_sd`` or
    ``outgoing_speed_sd_mps`` (divided by the approach speed); None without either."""
    own, other = (
        ("rebound_ratio_sd", "outgoing_speed_sd_mps")
        if has_ratio
        else ("outgoing_speed_sd_mps", "rebound_ratio_sd")
    )
    if other in columns:
        measured = "rebound_ratio" if has_ratio else "outgoing_speed_mps"
        raise InputError(
            f"{path}: column {other} goes with the other measured column; with {measured} give "
            f"{own}"
        )
    if own not in columns:
        return None
    values = _numbers(path, columns, own)
    sd = values if has_ratio else values / approach
    for line, value, ratio_sd in zip(lines, values, sd, strict=True):
        if value <= 0:
            raise InputError(
                f"{_where(path, line, own)}: {value:g}; a standard deviation must be above 0 "
                "(leave the column out if the spread was not measured)"
            )
        if ratio_sd > MAX_SD:
            slip = "; did you give percent? Give a fraction" if has_ratio else ""
            raise InputError(
                f"{_where(path, line, own)}: {value:g} is a standard deviation of the ratio of "
                f"{ratio_sd:.3g}, above {MAX_SD:g}{slip}"
            )
    return np.asarray(sd, dtype=float)
