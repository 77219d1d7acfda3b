"""Numbers as the report's tables show them: significant digits, engineers' units, a dash for
a missing value."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "DERIVED_LABELS",
    "LABELS",
    "PERCENT_NAMES",
    "SI_UNITS",
    "UNITS",
    "finite",
    "fmt",
    "quantity",
    "rounded",
    "split_unit",
    "unit_symbol",
]

DERIVED_LABELS: dict[str, str] = {
    "mass": "mass",
    "balance": "balance point, from the butt",
    "inertia_cg": "pitch inertia about the balance point",
    "inertia_grip": "pitch inertia about the grip pivot",
    "swingweight": "swingweight (100 mm from the butt)",
    "twistweight": "twistweight (roll inertia)",
    "recoil_weight": "recoil weight (inertia about the balance point)",
    "centre_of_percussion": "centre of percussion, pivot at the grip",
    "head_area": "head (string-bed) area",
    "bed_tension": "string tension in the played bed (pull tension less its loss)",
    "reduced_mass_centre_free": "reduced mass at the face centre, free: 1/(1/M + b²/I_G)",
    "reduced_mass_centre_pinned": "reduced mass at the face centre, pinned at the grip (eq 4)",
}
"""Labels of the racket's derived properties in the racket section, by key without its unit."""

UNITS: dict[str, tuple[str, float]] = {
    "kg": ("g", 1e3),
    "m": ("mm", 1e3),
    "kgm2": ("kg·cm²", 1e4),  # inertias as players and makers quote them: one unit for all
    "kgcm2": ("kg·cm²", 1.0),
    "cm2": ("cm²", 1.0),
    "hz": ("Hz", 1.0),
    "n": ("N", 1.0),
    "pa": ("GPa", 1e-9),
    "m2": ("cm²", 1e4),
    "s": ("ms", 1e3),
    "mps": ("m/s", 1.0),
    "rad": ("°", 180.0 / math.pi),
}
"""Unit suffix of a key → (display unit, factor) on the page (docs/develop.md, "Units on the
page"); other suffixes of :data:`SI_UNITS` are shown as they are."""

PERCENT_NAMES = frozenset({"damping_ratio", "damping_free", "damping_hand"})
"""Keys without a unit suffix that hold a ratio the page shows in %: damping ratios."""

SI_UNITS: dict[str, str] = {
    "kg": "kg",
    "m": "m",
    "m2": "m²",
    "s": "s",
    "hz": "Hz",
    "n": "N",
    "j": "J",
    "pa": "Pa",
    "mps": "m/s",
    "ms2": "m/s²",
    "rad": "rad",
    "radps": "rad/s",
    "deg": "°",
    "kgm2": "kg·m²",
    "kgcm2": "kg·cm²",
    "cm2": "cm²",
    "nm": "N·m",
    "ns": "N·s",
    "nms": "N·m·s",
    "db": "dB",
    "percent": "%",
}
"""Unit suffix of a key (the glossary's naming rule) → its symbol; ``a_per_b`` is a/b."""

LABELS: dict[str, str] = {"e_bg": "e_BG", "cor": "COR", "mac": "MAC"}
"""Keys shown as the field writes them rather than as words."""


def split_unit(key: str) -> tuple[str, str]:
    """(name, unit suffix) of a unit-suffixed key: ``mass_kg`` → (``mass``, ``kg``),
    ``stiffness_n_per_m`` → (``stiffness``, ``n_per_m``); no suffix → (``key``, "")."""
    head, per, denominator = key.partition("_per_")
    if per and denominator in SI_UNITS:
        name, _, numerator = head.rpartition("_")
        if name and numerator in SI_UNITS:
            return name, f"{numerator}_per_{denominator}"
    name, _, suffix = key.rpartition("_")
    if name and suffix in SI_UNITS:
        return name, suffix
    return key, ""


def unit_symbol(suffix: str) -> str:
    """The symbol of a unit suffix of :func:`split_unit` (``n_per_m`` → ``N/m``)."""
    numerator, per, denominator = suffix.partition("_per_")
    symbol = SI_UNITS.get(numerator, "")
    return f"{symbol}/{SI_UNITS[denominator]}" if per and symbol else symbol


def finite(value: object) -> bool:
    """Whether ``value`` is a finite number."""
    return isinstance(value, int | float) and math.isfinite(value)


def fmt(value: Any, spec: str = ".4g") -> str:
    """A number for a table (format ``spec``); a dash for None or NaN, yes/no for a bool."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int | float | np.floating | np.integer):
        number = float(value)
        return format(number, spec) if math.isfinite(number) else "–"
    return str(value)


def quantity(key: str, value: Any, si: bool = False) -> tuple[str, str, str]:
    """(label, value, unit) of a unit-suffixed key (``mass_kg``): numbers to 4 significant
    figures (whole numbers as they are), a list of numbers joined with commas.

    Parameters
    ----------
    key : str
        The key, its unit as a suffix (docs/develop.md, naming rule).
    value : object
        Its value.
    si : bool
        Show SI units as the key names them; by default the units of the page, those the field
        quotes (:data:`UNITS`: g, mm, ms, kg·cm², cm², °, GPa; damping ratios in %).
    """
    name, suffix = split_unit(key)
    unit, factor = unit_symbol(suffix), 1.0
    if not si and suffix in UNITS:
        unit, factor = UNITS[suffix]
        if suffix == "pa" and "modulus" not in name:
            unit, factor = "Pa", 1.0
    elif not si and not suffix and name in PERCENT_NAMES:
        unit, factor = "%", 100.0
    label = LABELS.get(name, name.replace("_", " "))
    if value is None:
        return label, "not set", ""
    if isinstance(value, list | tuple) and all(_is_number(v) for v in value):
        return label, ", ".join(_number(v, factor) for v in value) if value else "none", unit
    if _is_number(value):
        return label, _number(value, factor), unit
    return label, fmt(value), ""


def _is_number(value: object) -> bool:
    return isinstance(value, int | float | np.integer | np.floating) and not isinstance(value, bool)


def _number(value: Any, factor: float) -> str:
    """A number for a table: a whole number as it is, else 4 significant figures, without an
    exponent from 0.0001 to a million."""
    if isinstance(value, int | np.integer) and factor == 1.0:
        return str(int(value))
    number = float(value) * factor
    text = fmt(number, ".4g")
    if "e" in text and 1e-4 <= abs(number) < 1e6:
        text = f"{float(text):f}".rstrip("0").rstrip(".")
    return text


def rounded(values: NDArray[np.float64], digits: int = 4) -> list[float | None]:
    """Values for JSON: ``digits`` significant digits kept, NaN as null."""
    return [float(f"{v:.{digits}g}") if math.isfinite(v) else None for v in values.tolist()]
