"""Racket description files (TOML): schema, validation and the built-in default racket.

The schema is documented in docs/racket-file.md.  Every table and key is checked: an unknown
key, a missing key or a value of the wrong type raises :class:`~racketdyn.errors.InputError`
naming the file, the key and what is allowed.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import replace
from importlib import resources
from pathlib import Path
from typing import Any

from racketdyn.errors import InputError
from racketdyn.plausibility import OVERRIDE_FILE, check
from racketdyn.racket import (
    KGM2_TO_KGCM2,
    M2_TO_CM2,
    SWINGWEIGHT_AXIS_M,
    HeadEllipse,
    PointMass,
    Racket,
    StringBed,
)

__all__ = [
    "DEFAULT_RACKET_NAME",
    "check_racket",
    "default_racket",
    "load_racket",
    "racket_to_dict",
    "read_toml",
    "write_racket_toml",
]

DEFAULT_RACKET_NAME = "kawazoe_2002.toml"

_SCHEMA: dict[str, dict[str, type | tuple[type, ...]]] = {
    "racket": {
        "mass_kg": float,
        "length_m": float,
        "balance_m": float,
        "inertia_cg_kgm2": float,
        "swingweight_kgcm2": float,
        "roll_inertia_kgm2": float,
        "twistweight_kgcm2": float,
        "grip_m": float,
    },
    "head": {
        "centre_x_m": float,
        "half_length_m": float,
        "half_width_m": float,
        "area_cm2": float,
        "centre_y_m": float,
    },
    "strings": {
        "tension_n": float,
        "tension_loss": float,
        "mains": int,
        "crosses": int,
        "string_diameter_m": float,
        "string_modulus_pa": float,
        "mass_kg": float,
        "load_deflection_file": str,
    },
    "modal": {"file": str, "first_bending_hz": float, "twisting_hz": float},
    "point_masses": {"mass_kg": float, "x_m": float, "y_m": float, "label": str},
    "checks": {"allow_implausible": bool},
}
_TOP = {"schema_version", "name", "description", "uncertainty", *_SCHEMA}
_REQUIRED = {
    "racket": ("mass_kg", "length_m", "balance_m"),
    "head": ("centre_x_m", "half_length_m"),
    "point_masses": ("mass_kg", "x_m"),
}
# the entry of racketdyn.plausibility.RANGES each key is checked against, by table
_PLAUSIBLE: dict[str, dict[str, str]] = {
    "racket": {key: key for key in _SCHEMA["racket"]},
    "head": {key: key for key in _SCHEMA["head"]},
    "strings": {
        "tension_n": "tension_n",
        "tension_loss": "tension_loss",
        "mains": "mains",
        "crosses": "crosses",
        "string_diameter_m": "string_diameter_m",
        "string_modulus_pa": "string_modulus_pa",
        "mass_kg": "strings_mass_kg",
    },
    "modal": {"first_bending_hz": "first_bending_hz", "twisting_hz": "twisting_hz"},
    "point_masses": {"mass_kg": "point_mass_kg", "x_m": "point_x_m", "y_m": "point_y_m"},
}


def _check_table(where: str, table: object, kind: str) -> dict[str, Any]:
    if not isinstance(table, dict):
        raise InputError(f"{where} must be a table of keys")
    allowed = _SCHEMA[kind]
    for key, value in table.items():
        if key not in allowed:
            raise InputError(f"{where}: unknown key {key!r}; allowed keys are {', '.join(allowed)}")
        wanted = allowed[key]
        if wanted is float:
            ok = (
                isinstance(value, int | float)
                and not isinstance(value, bool)
                and math.isfinite(value)
            )
            what = "a number"
        elif wanted is int:
            ok = isinstance(value, int) and not isinstance(value, bool)
            what = "a whole number"
        elif wanted is bool:
            ok = isinstance(value, bool)
            what = "true or false"
        else:
            ok = isinstance(value, str)
            what = "a string"
        if not ok:
            raise InputError(f"{where}.{key} must be {what} (got {value!r})")
    for key in _REQUIRED.get(kind, ()):
        if key not in table:
            raise InputError(f"{where}.{key} is missing; it is required")
    return dict(table)


def _one_of_pair(where: str, table: dict[str, Any], first: str, second: str) -> None:
    if first in table and second in table:
        raise InputError(f"{where}: give {first} or {second}, not both")


def read_toml(path: Path, what: str) -> dict[str, Any]:
    """Parse a TOML file; a missing, unreadable or malformed file is an InputError naming it.

    Parameters
    ----------
    path : Path
        The file.
    what : str
        What it should be, for the message ("racket file", "sweep spec file").
    """
    if Path(path).is_dir():
        raise InputError(f"{path}: is a folder; give a {what} (.toml)")
    try:
        return tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(f"{path}: no such {what}") from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot be read ({error})") from None
    except tomllib.TOMLDecodeError as error:
        raise InputError(f"{path}: malformed TOML ({error})") from None
    except RecursionError:
        raise InputError(
            f"{path}: nested too deeply to be a {what} (arrays or tables within one another "
            "hundreds of levels down); see docs/racket-file.md for its tables"
        ) from None


def load_racket(path: Path | str, *, allow_implausible: bool = False) -> Racket:
    """Read and validate a racket description file.

    Parameters
    ----------
    path : path-like
        TOML file (schema: docs/racket-file.md).  Relative file names inside it are taken
        relative to the file.
    allow_implausible : bool
        Take values outside the plausible ranges of rackets on sale (but inside the limits of
        :data:`racketdyn.plausibility.RANGES`), as the file's ``[checks] allow_implausible``.

    Returns
    -------
    Racket
        The validated racket.  A missing roll inertia is derived from the hoop model
        (:func:`racketdyn.racket_modal.beam.hoop_roll_inertia`).
    """
    path = Path(path)
    return racket_from_dict(
        read_toml(path, "racket file"), path, allow_implausible=allow_implausible
    )


def _check_plausible(
    path: Path, tables: dict[str, list[dict[str, Any]]], allow_implausible: bool
) -> None:
    """Every number against its plausible range (racketdyn.plausibility), table by table."""
    for kind, keys in _PLAUSIBLE.items():
        for i, table in enumerate(tables[kind]):
            where = f"[[point_masses]] {i + 1}" if kind == "point_masses" else f"[{kind}]"
            for key, value in table.items():
                if key in keys:
                    check(
                        keys[key],
                        value,
                        f"{path}: {where}.{key}",
                        allow_implausible=allow_implausible,
                        override=OVERRIDE_FILE,
                    )


def check_racket(racket: Racket, *, allow_implausible: bool = False) -> None:
    """A racket built in Python against the plausible ranges a racket file meets.

    A racket file is checked as it is read (:func:`load_racket`); a :class:`Racket` made in
    Python is checked here against the same table of keys (``_PLAUSIBLE``), read from the
    racket's objects instead of the file's tables: a tension typed in lbf, a mass in grams or a
    length in mm is refused in one line naming the field and the likely slip.

    Parameters
    ----------
    racket : Racket
        The racket.
    allow_implausible : bool
        Take values outside the plausible ranges (but inside the limits), logged.

    Raises
    ------
    InputError
        The first field outside its range, named as ``racket.<field>``.
    """
    objects: dict[str, list[tuple[str, object]]] = {
        "racket": [("", racket)],
        "head": [("head.", racket.head)],
        "strings": [("strings.", racket.strings)],
        "modal": [("", racket)],
        "point_masses": [("point_masses.", mass) for mass in racket.point_masses],
    }
    for kind, keys in _PLAUSIBLE.items():
        for prefix, owner in objects[kind]:
            for key, ranged in keys.items():
                value = getattr(owner, key, None)  # the file's derived keys are no fields
                if value is not None:
                    check(
                        ranged,
                        value,
                        f"`racket.{prefix}{key}`",
                        allow_implausible=allow_implausible,
                    )


def racket_from_dict(
    data: dict[str, Any], path: Path, *, allow_implausible: bool = False
) -> Racket:
    """Build a racket from parsed TOML (see :func:`load_racket`)."""
    from racketdyn.racket_modal.beam import hoop_roll_inertia  # the hoop model lives with the beam

    for key in data:
        if key not in _TOP:
            raise InputError(
                f"{path}: unknown top-level key {key!r}; allowed: {', '.join(sorted(_TOP))}"
            )
    version = data.get("schema_version", 1)
    if version != 1:
        raise InputError(
            f"{path}: schema_version {version!r} is not supported (this racketdyn reads 1)"
        )
    for kind in ("racket", "head"):
        if kind not in data:
            raise InputError(f"{path}: the [{kind}] table is missing; it is required")
    body = _check_table(f"{path}: [racket]", data["racket"], "racket")
    head_table = _check_table(f"{path}: [head]", data["head"], "head")
    strings_table = _check_table(f"{path}: [strings]", data.get("strings", {}), "strings")
    modal_table = _check_table(f"{path}: [modal]", data.get("modal", {}), "modal")
    raw_masses = data.get("point_masses", [])
    if not isinstance(raw_masses, list):
        raise InputError(f"{path}: point_masses must be an array of tables ([[point_masses]])")
    masses = [
        _check_table(f"{path}: [[point_masses]] {i + 1}", t, "point_masses")
        for i, t in enumerate(raw_masses)
    ]
    checks_table = _check_table(f"{path}: [checks]", data.get("checks", {}), "checks")
    allow_implausible = allow_implausible or bool(checks_table.get("allow_implausible", False))
    if "uncertainty" in data and not isinstance(data["uncertainty"], dict):
        # its tables are checked where they are read (io.uncertainty_file.racket_spreads, on
        # every racket file a step loads: workflows.inputs.load_racket_input)
        raise InputError(f"{path}: [uncertainty] must be a table of tables ([uncertainty.e_bg])")
    _check_plausible(
        path,
        {
            "racket": [body],
            "head": [head_table],
            "strings": [strings_table],
            "modal": [modal_table],
            "point_masses": masses,
        },
        allow_implausible,
    )

    where = f"{path}: [racket]"
    _one_of_pair(where, body, "inertia_cg_kgm2", "swingweight_kgcm2")
    _one_of_pair(where, body, "roll_inertia_kgm2", "twistweight_kgcm2")
    _one_of_pair(f"{path}: [head]", head_table, "half_width_m", "area_cm2")
    if "inertia_cg_kgm2" not in body and "swingweight_kgcm2" not in body:
        raise InputError(
            f"{where}: give inertia_cg_kgm2 (about the balance point) or swingweight_kgcm2"
        )
    if "half_width_m" not in head_table and "area_cm2" not in head_table:
        raise InputError(f"{path}: [head]: give half_width_m or area_cm2")

    def guarded(build: Any, *args: Any, **kwargs: Any) -> Any:
        try:
            return build(*args, **kwargs)
        except InputError as error:
            raise InputError(f"{path}: {error}") from None

    mass, balance = float(body["mass_kg"]), float(body["balance_m"])
    head_args = {k: float(v) for k, v in head_table.items() if k != "area_cm2"}
    if "area_cm2" in head_table:
        if head_table["area_cm2"] <= 0 or head_table["half_length_m"] <= 0:
            raise InputError(f"{path}: [head] area_cm2 and half_length_m must be positive")
        head_args["half_width_m"] = (
            head_table["area_cm2"] / M2_TO_CM2 / (math.pi * head_args["half_length_m"])
        )
    head = guarded(HeadEllipse, **head_args)
    if "area_cm2" not in head_table:
        check(
            "area_cm2",
            head.area_m2 * M2_TO_CM2,
            f"{path}: [head] area π half_length_m half_width_m (cm²)",
            allow_implausible=allow_implausible,
            override=OVERRIDE_FILE,
        )

    strings_args = dict(strings_table)
    if "load_deflection_file" in strings_args:
        strings_args["load_deflection_file"] = path.parent / strings_args["load_deflection_file"]
    strings = guarded(StringBed, **strings_args)

    length = float(body["length_m"])
    roll: float | None = None
    if "roll_inertia_kgm2" in body:
        roll = float(body["roll_inertia_kgm2"])
    elif "twistweight_kgcm2" in body:
        roll = float(body["twistweight_kgcm2"]) / KGM2_TO_KGCM2
    modal_file = modal_table.get("file")
    racket: Racket = guarded(
        Racket,
        name=str(data.get("name", path.stem)),
        mass_kg=mass,
        length_m=length,
        balance_m=balance,
        # derived values get placeholders: the racket's own checks run first, on what was given
        inertia_cg_kgm2=float(body.get("inertia_cg_kgm2", 1.0)),
        roll_inertia_kgm2=1.0 if roll is None else roll,
        head=head,
        strings=strings,
        grip_m=float(body.get("grip_m", 0.070)),
        point_masses=tuple(guarded(PointMass, **m) for m in masses),
        modal_model_file=None if modal_file is None else path.parent / modal_file,
        first_bending_hz=float(modal_table.get("first_bending_hz", 120.0)),
        twisting_hz=float(modal_table.get("twisting_hz", 361.0)),
    )
    if "swingweight_kgcm2" in body:
        swing_axis = SWINGWEIGHT_AXIS_M
        inertia_cg = body["swingweight_kgcm2"] / KGM2_TO_KGCM2 - mass * (balance - swing_axis) ** 2
        if inertia_cg <= 0:
            raise InputError(
                f"{where}.swingweight_kgcm2 ({body['swingweight_kgcm2']}) must exceed "
                f"M (x_G - 0.1 m)² = {mass * (balance - swing_axis) ** 2 * KGM2_TO_KGCM2:.1f} "
                "kg·cm² for this mass and balance"
            )
        racket = guarded(replace, racket, inertia_cg_kgm2=inertia_cg)
    else:
        swingweight = (
            racket.inertia_cg_kgm2 + mass * (balance - SWINGWEIGHT_AXIS_M) ** 2
        ) * KGM2_TO_KGCM2
        check(
            "swingweight_kgcm2",
            swingweight,
            f"{path}: [racket] swingweight from mass_kg, balance_m and inertia_cg_kgm2 (kg·cm²)",
            allow_implausible=allow_implausible,
            override=OVERRIDE_FILE,
        )
    if roll is None:
        derived = guarded(
            hoop_roll_inertia, length, mass, balance, racket.inertia_cg_kgm2, racket.head
        )
        racket = replace(racket, roll_inertia_kgm2=derived)
    return racket


def default_racket() -> Racket:
    """The built-in racket: Kawazoe's test racket (paper, section 2)."""
    resource = resources.files("racketdyn.data").joinpath(DEFAULT_RACKET_NAME)
    with resources.as_file(resource) as path:
        return load_racket(path)


def racket_to_dict(racket: Racket) -> dict[str, Any]:
    """The racket as plain data (for run records), with its derived properties."""
    return {
        "name": racket.name,
        "mass_kg": racket.mass_kg,
        "length_m": racket.length_m,
        "balance_m": racket.balance_m,
        "inertia_cg_kgm2": racket.inertia_cg_kgm2,
        "roll_inertia_kgm2": racket.roll_inertia_kgm2,
        "grip_m": racket.grip_m,
        "head": vars(racket.head).copy(),
        "strings": {
            k: (str(v) if isinstance(v, Path) else v) for k, v in vars(racket.strings).items()
        },
        "point_masses": [vars(p).copy() for p in racket.point_masses],
        "modal_model_file": None
        if racket.modal_model_file is None
        else str(racket.modal_model_file),
        "first_bending_hz": racket.first_bending_hz,
        "twisting_hz": racket.twisting_hz,
        "derived": racket.derived_properties(),
    }


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)
    text = str(value).replace("\\", "\\\\").replace('"', '\\"')
    return f'"{text}"'


def write_racket_toml(racket: Racket, path: Path, comment: str = "") -> Path:
    """Write a racket as a racket file :func:`load_racket` reads back to the same racket.

    Inertias are written as such (``inertia_cg_kgm2``, ``roll_inertia_kgm2``), the head by its
    half-axes, files (string-bed load–deflection, modal model) by absolute path unless they lie
    beside ``path``.

    Parameters
    ----------
    racket : Racket
        The racket.
    path : Path
        The TOML file to write.
    comment : str
        Lines put at the top as ``#`` comments (what made the file).
    """
    path = Path(path)

    def file_name(file: Path) -> str:
        file = Path(file).resolve()
        return file.name if file.parent == path.parent.resolve() else str(file)

    strings = {
        k: v
        for k, v in vars(racket.strings).items()
        if v is not None and k != "load_deflection_file"
    }
    if racket.strings.load_deflection_file is not None:
        strings["load_deflection_file"] = file_name(racket.strings.load_deflection_file)
    modal: dict[str, Any] = {
        "first_bending_hz": racket.first_bending_hz,
        "twisting_hz": racket.twisting_hz,
    }
    if racket.modal_model_file is not None:
        modal["file"] = file_name(racket.modal_model_file)
    tables: list[tuple[str, dict[str, Any]]] = [
        (
            "racket",
            {
                "mass_kg": racket.mass_kg,
                "length_m": racket.length_m,
                "balance_m": racket.balance_m,
                "inertia_cg_kgm2": racket.inertia_cg_kgm2,
                "roll_inertia_kgm2": racket.roll_inertia_kgm2,
                "grip_m": racket.grip_m,
            },
        ),
        ("head", dict(vars(racket.head))),
        ("strings", strings),
        ("modal", modal),
    ]
    lines = [f"# {line}" for line in comment.splitlines()]
    lines += ["schema_version = 1", f"name = {_toml_value(racket.name)}", ""]
    for name, table in tables:
        lines.append(f"[{name}]")
        lines += [f"{key} = {_toml_value(value)}" for key, value in table.items()]
        lines.append("")
    for mass in racket.point_masses:
        lines.append("[[point_masses]]")
        lines += [f"{key} = {_toml_value(value)}" for key, value in vars(mass).items()]
        lines.append("")
    path.write_text("\n".join(lines), encoding="utf-8")
    return path
