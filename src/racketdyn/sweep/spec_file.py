"""The sweep spec file: TOML (schema in docs/sweep-file.md) read into a :class:`SweepSpec`.

The input edge of :mod:`racketdyn.sweep`: :func:`load_sweep_spec` reads the file;
:func:`sweep_spec_from_dict` checks every key and builds the variables
(:class:`~racketdyn.sweep.variables.Variable`) and the :class:`~racketdyn.sweep.spec.SweepSpec`
that :func:`~racketdyn.sweep.run.run_sweep` runs.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.ball import Ball, RestoringForce
from racketdyn.errors import InputError, one_of, require_whole
from racketdyn.impact.approximate import STIFFNESS_READINGS
from racketdyn.impact.grid import STRING_BEDS
from racketdyn.impact.transient import ENGINES as TRANSIENT_ENGINES
from racketdyn.io.racket_file import DEFAULT_RACKET_NAME, default_racket, load_racket, read_toml
from racketdyn.io.tables import read_load_deflection, read_points
from racketdyn.plausibility import check, check_e_bg, check_speeds
from racketdyn.racket import SUPPORTS, Racket
from racketdyn.sweep.spec import (
    DEFAULT_THRESHOLD_FRACTION,
    MAX_DESIGNS,
    MODES,
    SPEC_SCHEMA_VERSION,
    SweepSpec,
)
from racketdyn.sweep.task import METHOD_SUPPORTS, _check_method, _check_supports
from racketdyn.sweep.variables import HAND_VARIABLES, POINT_MASS, SCALAR_VARIABLES, Variable

if TYPE_CHECKING:
    from racketdyn.impact.uncertainty import Uncertainty

__all__ = ["load_sweep_spec", "sweep_spec_from_dict"]

SUPPORT = "support"
POINT_MASS_KEYS = ("mass_kg", "x_m", "y_m", "clock", "label")
_TOP_KEYS = ("schema_version", "name", "description", "racket", "mode")
_TABLES = ("ball", "impacts", "variables", "summary", "checks", "uncertainty")
_PLAUSIBLE: dict[str, str] = {
    "mass_kg": "mass_kg",
    "balance_m": "balance_m",
    "inertia_cg_kgm2": "inertia_cg_kgm2",
    "swingweight_kgcm2": "swingweight_kgcm2",
    "roll_inertia_kgm2": "roll_inertia_kgm2",
    "twistweight_kgcm2": "twistweight_kgcm2",
    "grip_m": "grip_m",
    "tension_n": "tension_n",
    "hand.arm_mass_kg": "hand_arm_mass_kg",
    "hand.stiffness_n_per_m": "hand_stiffness_n_per_m",
    "hand.damping_ns_per_m": "hand_damping_ns_per_m",
}
"""The entry of :data:`racketdyn.plausibility.RANGES` each sweep variable's values pass (the
racket file's and the command options' table: a point mass of 5.0 — grams typed as kg — ran a
5.36 kg racket, issue 26); ``[checks] allow_implausible = true`` takes an unusual value, as in
a racket file."""
_BALL_KEYS = ("mass_kg", "diameter_m", "e_bg", "load_deflection_file")
_IMPACT_KEYS = (
    "grid",
    "points",
    "ball_speeds_mps",
    "racket_speeds_mps",
    "method",
    "engine",
    "stiffness_reading",
    "include_string_bed",
    "string_bed",
    "rigid",
)
_SUMMARY_KEYS = ("threshold_fraction", "ball_speed_mps", "racket_speed_mps")
MAX_GRID = 400
MAX_RANGE_VALUES = MAX_DESIGNS
"""Values a range ``{start, stop, num}`` may give: no more than a sweep's designs (a typo's
10⁹ filled the memory before the design count was checked)."""


def load_sweep_spec(path: Path | str) -> SweepSpec:
    """Read and validate a sweep spec (TOML; schema in docs/sweep-file.md).

    Parameters
    ----------
    path : path-like
        The spec file.  Relative file names inside it (racket, points, ball law) are taken
        relative to it.

    Returns
    -------
    SweepSpec
        The validated spec; every design is checked to be a valid racket.
    """
    path = Path(path)
    return sweep_spec_from_dict(read_toml(path, "sweep spec file"), path.parent, str(path))


def sweep_spec_from_dict(
    data: Mapping[str, Any], base_dir: Path | str = ".", source: str = "sweep spec"
) -> SweepSpec:
    """Build a sweep spec from parsed TOML (see :func:`load_sweep_spec`).

    Parameters
    ----------
    data : mapping
        The parsed TOML.
    base_dir : path-like
        Folder that relative file names are taken from.
    source : str
        Names the spec in error messages (the file name).
    """
    base = Path(base_dir)
    try:
        return _spec_from_dict(data, base, source)
    except InputError as error:
        message = str(error)
        raise InputError(
            message if message.startswith(source) else f"{source}: {message}"
        ) from None


def _spec_from_dict(data: Mapping[str, Any], base: Path, source: str) -> SweepSpec:
    """The spec from parsed TOML, table by table (:func:`sweep_spec_from_dict`)."""
    _check_top_level(data)
    name = _get(data, "name", str, "", "name")
    checks = _table(data, "checks", ("allow_implausible",))
    allow = _get(checks, "allow_implausible", bool, False, "[checks].allow_implausible")
    _get(data, "description", str, "", "description")
    mode = one_of("mode", data.get("mode", "full-factorial"), MODES)
    racket, racket_source = _racket_of(data, base)
    ball = _ball_of(_table(data, "ball", _BALL_KEYS), base)

    impacts = _table(data, "impacts", _IMPACT_KEYS)
    locations, labels = _impact_points(impacts, base, racket)
    ball_speeds, racket_speeds = _impact_speeds(impacts, allow)
    method = _check_method("[impacts].method", impacts.get("method", "approximate"))
    reading = one_of(
        "[impacts].stiffness_reading",
        impacts.get("stiffness_reading", "period"),
        STIFFNESS_READINGS,
    )
    include_string_bed = _get(
        impacts, "include_string_bed", bool, False, "[impacts].include_string_bed"
    )
    rigid = _get(impacts, "rigid", bool, False, "[impacts].rigid")
    string_bed = one_of("[impacts].string_bed", impacts.get("string_bed", "uniform"), STRING_BEDS)
    engine = one_of("[impacts].engine", impacts.get("engine", "auto"), TRANSIENT_ENGINES)

    variables, supports = _variables_of(data, method, racket, allow)
    fraction, summary_ball_speed, summary_racket_speed = _summary_of(data)
    uncertainty = _uncertainty_of(data, allow)
    return SweepSpec(
        racket=racket,
        ball=ball,
        locations=locations,
        labels=labels,
        ball_speeds=ball_speeds,
        racket_speeds=racket_speeds,
        supports=supports,
        variables=variables,
        mode=mode,  # type: ignore[arg-type]  # checked by one_of
        method=method,
        stiffness_reading=reading,  # type: ignore[arg-type]  # checked by one_of
        engine=engine,  # type: ignore[arg-type]  # checked by one_of
        include_string_bed=include_string_bed,
        string_bed=string_bed,  # type: ignore[arg-type]  # checked by one_of
        rigid=rigid,
        threshold_fraction=fraction,
        summary_ball_speed=summary_ball_speed,
        summary_racket_speed=summary_racket_speed,
        name=name or "sweep",
        racket_source=racket_source,
        uncertainty=uncertainty,
        uncertainty_source="" if uncertainty is None else "[uncertainty] of the sweep spec",
    )


def _check_top_level(data: Mapping[str, Any]) -> None:
    """Only known top-level keys and tables, and the schema version this racketdyn reads."""
    for key in data:
        if key not in _TOP_KEYS + _TABLES:
            raise InputError(
                f"unknown top-level key {key!r}; allowed: {', '.join(_TOP_KEYS + _TABLES)}"
            )
    version = data.get("schema_version", SPEC_SCHEMA_VERSION)
    if version != SPEC_SCHEMA_VERSION:
        raise InputError(f"schema_version {version!r} is not supported (this racketdyn reads 1)")


def _racket_of(data: Mapping[str, Any], base: Path) -> tuple[Racket, str]:
    """The racket (built-in or a racket file relative to ``base``) and where it came from."""
    racket_text = _get(data, "racket", str, "builtin", "racket")
    if racket_text in ("builtin", "built-in"):
        return default_racket(), f"built-in {DEFAULT_RACKET_NAME}"
    racket_path = base / racket_text
    return load_racket(racket_path), str(racket_path)


def _ball_of(ball_table: Mapping[str, Any], base: Path) -> Ball:
    """The ``[ball]`` table's ball, its load–deflection law fitted from its file if given."""
    ball_args: dict[str, Any] = {
        k: _number(f"[ball].{k}", ball_table[k])
        for k in ("mass_kg", "diameter_m", "e_bg")
        if k in ball_table
    }
    if "load_deflection_file" in ball_table:
        law_file = base / _get(
            ball_table, "load_deflection_file", str, "", "[ball].load_deflection_file"
        )
        deflection, force = read_load_deflection(law_file)
        ball_args["restoring_force"] = RestoringForce.fit(
            deflection, force, "polynomial", 3, f"ball, fitted to {law_file.name}"
        )
    try:
        return Ball(**ball_args)
    except InputError as error:
        raise InputError(f"[ball]: {error}") from None


def _impact_points(
    impacts: Mapping[str, Any], base: Path, racket: Racket
) -> tuple[NDArray[np.float64], tuple[str, ...]]:
    """The impact locations (``[impacts].points`` file or ``grid``) and their labels."""
    if "grid" in impacts and "points" in impacts:
        raise InputError("[impacts]: give grid or points, not both")
    if "points" in impacts:
        points_path = base / _get(impacts, "points", str, "", "[impacts].points")
        locations, point_labels = read_points(points_path)
        return locations, tuple(point_labels)
    grid = _get(impacts, "grid", int, 9, "[impacts].grid")
    if not 1 <= grid <= MAX_GRID:
        raise InputError(f"[impacts].grid must be a whole number from 1 to {MAX_GRID} (got {grid})")
    return racket.head.grid(grid), ()


def _impact_speeds(
    impacts: Mapping[str, Any], allow: bool
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The ball and racket speeds of ``[impacts]``, m/s, each checked to be plausible."""
    if "ball_speeds_mps" not in impacts:
        raise InputError("[impacts].ball_speeds_mps is missing; it is required")
    ball_speeds = _value_list("[impacts].ball_speeds_mps", impacts["ball_speeds_mps"])
    racket_speeds = _value_list(
        "[impacts].racket_speeds_mps", impacts.get("racket_speeds_mps", [0.0])
    )
    for speeds, key in ((ball_speeds, "ball_speed"), (racket_speeds, "racket_speed")):
        check_speeds(f"[impacts].{key}s_mps", speeds, f"{key}_mps", allow, _OVERRIDE)
    return ball_speeds, racket_speeds


def _variables_of(
    data: Mapping[str, Any], method: str, racket: Racket, allow: bool
) -> tuple[tuple[Variable, ...], tuple[str, ...]]:
    """The ``[variables]`` swept (hand parameters for the transient method only) and the
    supports (``support`` is a list of supports, not a variable)."""
    table = data.get("variables", {})
    if not isinstance(table, dict):
        raise InputError("[variables] must be a table of variables")
    variables: list[Variable] = []
    supports: tuple[str, ...] = SUPPORTS
    for key, value in _flat_hand_keys(table).items():
        where = f"[variables].{key}"
        if key in HAND_VARIABLES:
            if method != "transient":
                raise InputError(
                    f"{where}: hand parameters need [impacts].method = 'transient' and support "
                    "'hand'; the approximate method holds the racket pinned at the grip: sweep "
                    "grip_m or support instead"
                )
            variables.append(Variable.scalar(key, _plausible(where, key, value, allow)))
            continue
        if key.startswith(("hand", "wrist", "grip_force")):
            raise InputError(
                f"{where}: unknown hand parameter; the hand parameters are "
                f"{', '.join(HAND_VARIABLES)} (transient method, support 'hand')"
            )
        if key == SUPPORT:
            supports = _supports_of(where, value, method)
        elif key == POINT_MASS:
            tables = value if isinstance(value, list) else [value]
            for i, entry in enumerate(tables):
                variables.append(
                    _point_mass_from_table(
                        f"{where}[{i}]" if isinstance(value, list) else where,
                        entry,
                        racket,
                        allow,
                    )
                )
        elif key in SCALAR_VARIABLES:
            variables.append(Variable.scalar(key, _plausible(where, key, value, allow)))
        else:
            raise InputError(
                f"{where}: unknown variable; allowed: "
                f"{', '.join([POINT_MASS, SUPPORT, *SCALAR_VARIABLES, *HAND_VARIABLES])}"
            )
    return tuple(variables), supports


def _supports_of(where: str, value: object, method: str) -> tuple[str, ...]:
    """``[variables].support``: one support or a list, each one the method can run."""
    items = value if isinstance(value, list) else [value]
    allowed = METHOD_SUPPORTS[method]
    if not items or not all(isinstance(s, str) for s in items):
        raise InputError(f"{where} must be a list of {', '.join(allowed)}")
    _check_supports(where, items, method)
    return tuple(items)


def _summary_of(data: Mapping[str, Any]) -> tuple[float, float | None, float | None]:
    """``[summary]``: the threshold fraction and the ball and racket speeds summarised (None:
    the summary's default)."""
    summary = _table(data, "summary", _SUMMARY_KEYS)
    fraction = _number(
        "[summary].threshold_fraction",
        summary.get("threshold_fraction", DEFAULT_THRESHOLD_FRACTION),
    )
    ball_speed, racket_speed = (
        None if key not in summary else _number(f"[summary].{key}", summary[key])
        for key in ("ball_speed_mps", "racket_speed_mps")
    )
    return fraction, ball_speed, racket_speed


def _uncertainty_of(data: Mapping[str, Any], allow: bool) -> Uncertainty | None:
    """The ``[uncertainty]`` tables' spreads, or None without them."""
    if "uncertainty" not in data:
        return None
    from racketdyn.impact.uncertainty import Uncertainty
    from racketdyn.io.uncertainty_file import spreads_from_tables

    tables = data["uncertainty"]
    if not isinstance(tables, dict):
        raise InputError("[uncertainty] must be a table of tables ([uncertainty.e_bg] …)")
    return Uncertainty(spreads_from_tables(tables, "[uncertainty]", allow))


def _flat_hand_keys(table: Mapping[str, Any]) -> dict[str, Any]:
    """``[variables]`` with a ``hand`` table (TOML ``hand.arm_mass_kg = …`` or
    ``[variables.hand]``) flattened to ``hand.<key>`` keys, in the order given."""
    flat: dict[str, Any] = {}
    for key, value in table.items():
        if key == "hand" and isinstance(value, dict):
            for inner, inner_value in value.items():
                flat[f"hand.{inner}"] = inner_value
        else:
            flat[key] = value
    return flat


_OVERRIDE = "if it is meant, set [checks] allow_implausible = true in the sweep file"


def _check(key: str, number: float, where: str, allow: bool) -> None:
    check(key, number, where, allow_implausible=allow, override=_OVERRIDE)


def _plausible(where: str, key: str, value: object, allow: bool) -> NDArray[np.float64]:
    """The variable's values, each through the plausibility table (:data:`_PLAUSIBLE`)."""
    values = _value_list(where, value)
    if key in _PLAUSIBLE:
        for number in values:
            _check(_PLAUSIBLE[key], float(number), where, allow)
    elif key == "e_bg":
        for number in values:
            check_e_bg(f"{where} =", float(number))
    return values


def _point_mass_from_table(where: str, entry: object, racket: Racket, allow: bool) -> Variable:
    if not isinstance(entry, dict):
        raise InputError(f"{where} must be a table with mass_kg and x_m (or clock)")
    for key in entry:
        if key not in POINT_MASS_KEYS:
            raise InputError(
                f"{where}: unknown key {key!r}; allowed keys are {', '.join(POINT_MASS_KEYS)}"
            )
    if "mass_kg" not in entry:
        raise InputError(f"{where}.mass_kg is missing; it is required")
    label = _get(entry, "label", str, "", f"{where}.label")
    columns = {
        k: _value_list(f"{where}.{k}", entry[k])
        for k in ("mass_kg", "x_m", "y_m", "clock")
        if k in entry
    }
    for k, key in (("mass_kg", "point_mass_kg"), ("x_m", "point_x_m"), ("y_m", "point_y_m")):
        for number in columns.get(k, ()):
            _check(key, float(number), f"{where}.{k}", allow)
    clock = columns.get("clock")
    if clock is not None and np.any((clock <= 0.0) | (clock > 12.0)):
        raise InputError(
            f"{where}.clock: a clock position is an hour from 1 to 12 (12 the tip, 3 and 9 the "
            f"sides; got {', '.join(f'{c:g}' for c in clock)})"
        )
    return Variable.point_mass(
        columns["mass_kg"],
        columns.get("x_m"),
        columns.get("y_m"),
        columns.get("clock"),
        label=label,
        head=racket.head,
    )


def _table(data: Mapping[str, Any], name: str, allowed: Sequence[str]) -> dict[str, Any]:
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise InputError(f"[{name}] must be a table of keys")
    for key in table:
        if key not in allowed:
            raise InputError(
                f"[{name}]: unknown key {key!r}; allowed keys are {', '.join(allowed)}"
            )
    return dict(table)


def _get(table: Mapping[str, Any], key: str, kind: type, default: Any, where: str) -> Any:
    value = table.get(key, default)
    if kind is int:
        ok = isinstance(value, int) and not isinstance(value, bool)
        what = "a whole number"
    elif kind is bool:
        ok = isinstance(value, bool)
        what = "true or false"
    else:
        ok = isinstance(value, str)
        what = "a string"
    if not ok:
        raise InputError(f"{where} must be {what} (got {value!r})")
    return value


def _number(where: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise InputError(f"{where} must be a number (got {value!r})")
    return float(value)


def _value_list(where: str, value: object) -> NDArray[np.float64]:
    """Numbers from a number, a list of numbers or a table ``{start, stop, num}``."""
    if isinstance(value, dict):
        missing = [k for k in ("start", "stop", "num") if k not in value]
        unknown = [k for k in value if k not in ("start", "stop", "num")]
        if missing or unknown:
            raise InputError(
                f"{where}: a range is a table {{start, stop, num}}"
                + (f"; {', '.join(missing)} missing" if missing else "")
                + (f"; unknown key {', '.join(unknown)}" if unknown else "")
            )
        start = _number(f"{where}.start", value["start"])
        stop = _number(f"{where}.stop", value["stop"])
        num = require_whole(f"{where}.num", value["num"])
        if num > MAX_RANGE_VALUES:
            raise InputError(
                f"{where}.num must be a whole number from 1 to {MAX_RANGE_VALUES} (got {num})"
            )
        return np.linspace(start, stop, num)
    items = value if isinstance(value, list) else [value]
    if not items:
        raise InputError(f"{where}: give one or more values")
    return np.array(
        [
            _number(f"{where}[{i}]" if isinstance(value, list) else where, v)
            for i, v in enumerate(items)
        ]
    )
