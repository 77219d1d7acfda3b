"""The uncertainty file: one TOML table per uncertain input (issue 24).

```toml
[e_bg]
range = [0.80, 0.88]      # uniform
[first_bending_hz]
range = [140.0, 200.0]
[location_m]              # impact-location scatter, each direction: an offset
sd = 0.010                # normal
[ball_speed_mps]
sd = 1.0
[frame_damping_scale]
values = [0.5, 1.0, 2.0]  # equally likely
```

A racket file may hold the same tables under ``[uncertainty]`` (``[uncertainty.e_bg]`` …):
:func:`racket_spreads` reads them.

Names are those of :data:`racketdyn.impact.uncertainty.UNCERTAIN_INPUTS`; each table holds
exactly one of ``sd``, ``range`` or ``values``.  Every number passes the plausibility table
(:mod:`racketdyn.plausibility`) like a racket file's, and a bad entry is refused in one line
naming the file and the table.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

from racketdyn import plausibility
from racketdyn.errors import InputError
from racketdyn.impact.uncertainty import UNCERTAIN_INPUTS, Spread
from racketdyn.io.racket_file import read_toml

__all__ = [
    "LITERATURE",
    "NONE",
    "literature_spreads",
    "racket_spreads",
    "read_spreads",
    "spreads_from_tables",
]

_PLAUSIBLE: dict[str, str] = {
    "first_bending_hz": "first_bending_hz",
    "hand_stiffness_n_per_m": "hand_stiffness_n_per_m",
    "hand_damping_ns_per_m": "hand_damping_ns_per_m",
    "hand_arm_mass_kg": "hand_arm_mass_kg",
    "string_stiffness_scale": "scale_factor",
    "ball_stiffness_scale": "scale_factor",
    "frame_damping_scale": "scale_factor",
}
"""Plausibility key of each model parameter's values (e_bg: :func:`plausibility.check_e_bg`)."""

_SCATTER: dict[str, str] = {
    "location_m": "location_scatter_m",
    "ball_speed_mps": "ball_speed_scatter_mps",
}
"""Plausibility key of each offset's size (its sd, or the half-width of its range)."""


def _number(where: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise InputError(f"{where}: give a finite number, not {value!r}")
    return float(value)


def _check_value(name: str, where: str, value: float, allow_implausible: bool) -> None:
    if name == "e_bg":
        plausibility.check_e_bg(where, value)
        if value <= 0.0:
            raise InputError(f"{where}: e_BG must be above 0")
    elif name == "roll_inertia_kgm2":
        if value <= 0.0:
            raise InputError(f"{where}: an inertia must be above 0")
    elif name in _PLAUSIBLE:
        if value <= 0.0:
            raise InputError(f"{where}: must be above 0")
        plausibility.check(
            _PLAUSIBLE[name], value, where, allow_implausible=allow_implausible,
            override="if it is meant, set [checks] allow_implausible = true in the file",
        )  # fmt: skip


def _spread(name: str, table: Any, source: str, allow_implausible: bool) -> Spread:
    where = f"{source} [{name}]"
    if name not in UNCERTAIN_INPUTS:
        raise InputError(
            f"{where}: not an uncertain input; choose from {', '.join(UNCERTAIN_INPUTS)}"
        )
    if not isinstance(table, dict):
        raise InputError(f"{where}: give a table with sd, range or values")
    unknown = sorted(set(table) - {"sd", "range", "values"})
    if unknown:
        raise InputError(f"{where}: unknown key {unknown[0]!r}; give sd, range or values")
    if len(table) != 1:
        raise InputError(
            f"{where}: give exactly one of sd = x, range = [low, high], values = [...]"
        )
    key, raw = next(iter(table.items()))
    if key == "sd":
        sd = _number(f"{where} sd", raw)
        if sd < 0:
            raise InputError(f"{where} sd: must be 0 or more, not {sd:g}")
        numbers, spread = [sd], Spread(name, sd=sd)
    else:
        if not isinstance(raw, list) or not raw:
            raise InputError(f"{where} {key}: give a list of numbers")
        numbers = [_number(f"{where} {key}", v) for v in raw]
        if key == "range":
            if len(numbers) != 2 or numbers[0] > numbers[1]:
                raise InputError(f"{where} range: give [low, high] with low ≤ high")
            spread = Spread(name, bounds=(numbers[0], numbers[1]))
        else:
            spread = Spread(name, values=tuple(numbers))
    if name in _SCATTER:
        size = numbers[0] if key == "sd" else max(abs(v) for v in numbers)
        plausibility.check(
            _SCATTER[name], size, f"{where} {key}", allow_implausible=allow_implausible,
            override="if it is meant, set [checks] allow_implausible = true in the file",
        )  # fmt: skip
    elif key != "sd":
        for value in numbers:
            _check_value(name, f"{where} {key}", value, allow_implausible)
    return spread


def spreads_from_tables(
    tables: dict[str, Any], source: str, allow_implausible: bool = False
) -> tuple[Spread, ...]:
    """The spreads of an uncertainty file's tables (or a racket file's ``[uncertainty]``).

    Parameters
    ----------
    tables : dict
        Name → ``{"sd": x}``, ``{"range": [low, high]}`` or ``{"values": [...]}``.
    source : str
        How messages name the file.
    allow_implausible : bool
        Take values outside the plausible ranges (within the limits).

    Returns
    -------
    tuple of Spread
    """
    spreads = tuple(
        _spread(name, table, source, allow_implausible)
        for name, table in tables.items()
        if name != "checks"
    )
    if not spreads:
        raise InputError(f"{source}: no uncertain input; give at least one table, e.g. [e_bg]")
    return spreads


def read_spreads(path: str | os.PathLike[str]) -> tuple[Spread, ...]:
    """Read an uncertainty file (InputError in one line naming the file and table).

    Parameters
    ----------
    path : path
        The TOML file.

    Returns
    -------
    tuple of Spread
    """
    file = Path(path)
    tables = read_toml(file, "uncertainty file")
    checks = tables.get("checks", {})
    allow = bool(checks.get("allow_implausible", False)) if isinstance(checks, dict) else False
    return spreads_from_tables(tables, f"uncertainty file {file.name}", allow)


def racket_spreads(path: str | os.PathLike[str]) -> tuple[Spread, ...]:
    """The ``[uncertainty]`` tables of a racket file (``[uncertainty.e_bg]`` …), empty without.

    Parameters
    ----------
    path : path
        The racket's TOML file.

    Returns
    -------
    tuple of Spread
    """
    file = Path(path)
    data = read_toml(file, "racket file")
    tables = data.get("uncertainty")
    if tables is None:
        return ()
    if not isinstance(tables, dict):
        raise InputError(f"{file}: [uncertainty] must be a table of tables ([uncertainty.e_bg])")
    checks = data.get("checks", {})
    allow = bool(checks.get("allow_implausible", False)) if isinstance(checks, dict) else False
    return spreads_from_tables(tables, f"{file}: [uncertainty]", allow)


LITERATURE = "literature"
"""The name (``--uncertainty literature``) of :func:`literature_spreads`."""

NONE = "none"
"""The name (``--uncertainty none``) of no uncertain input: a racket file's ``[uncertainty]``
tables left out for one run."""


def literature_spreads(frequency_measured: bool, measured_bed: bool = False) -> tuple[Spread, ...]:
    """What the literature leaves uncertain about any racket, ball and test (docs/references.md).

    - ``e_bg``: uniform 0.80–0.88, the spread of e_BG on head-clamped strings in the
      literature (Kawazoe's ≈ 0.83 "almost independent" of speed and tension; Cross's 1 m drop
      ≈ 0.84; Haake, Carré and Goodwill falling with speed).
    - ``ball_stiffness_scale``: uniform 0.87–1.14, ball to ball: the ITF forward deformation
      0.56–0.74 cm under 80.1 N about its middle (0.65 cm), stiffness ∝ 1 / deformation.
    - ``string_stiffness_scale``: uniform 0.86–1.14, the bed's tension 20–40 % below the pull
      tension (Cross and Bower's ≈ 30 % taken as the nominal: 0.6/0.7 to 0.8/0.7).
    - ``first_bending_hz``: normal, sd 3 Hz about a measured frequency ("measured ± a few Hz");
      uniform 110–180 Hz (the free 2-node modes of rackets on sale) when the racket file gives
      none.
    - ``location_m``: normal, sd 10 mm each way (a ball cannon's scatter).
    - ``ball_speed_mps``: normal, sd 0.5 m/s (a ball cannon's repeatability).

    Parameters
    ----------
    frequency_measured : bool
        The racket file states its first bending frequency.
    measured_bed : bool
        The string bed is a measured load–deflection file (then no string-stiffness spread:
        the file is the bed as played).

    Returns
    -------
    tuple of Spread
    """
    bed = () if measured_bed else (Spread("string_stiffness_scale", bounds=(0.86, 1.14)),)
    return (
        Spread("e_bg", bounds=(0.80, 0.88)),
        Spread("ball_stiffness_scale", bounds=(0.87, 1.14)),
        *bed,
        Spread("first_bending_hz", sd=3.0)
        if frequency_measured
        else Spread("first_bending_hz", bounds=(110.0, 180.0)),
        Spread("location_m", sd=0.010),
        Spread("ball_speed_mps", sd=0.5),
    )


def literature_for_racket(
    racket: str | os.PathLike[str] | None, modal_file: bool = False
) -> tuple[Spread, ...]:
    """:func:`literature_spreads` for a racket file (None: the built-in racket, whose 120 Hz
    the paper measured), its frequency taken as measured where the file states it or a modal
    model file is given."""
    if racket is None:
        return literature_spreads(True)
    data = read_toml(Path(racket), "racket file")
    modal = data.get("modal", {}) if isinstance(data.get("modal"), dict) else {}
    strings = data.get("strings", {}) if isinstance(data.get("strings"), dict) else {}
    stated = modal_file or "first_bending_hz" in modal or "file" in modal
    return literature_spreads(stated, "load_deflection_file" in strings)
