"""Numbers as the report's tables show them: significant digits, engineers' units, a dash for
a missing value."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["DERIVED_LABELS", "finite", "fmt", "quantity", "rounded"]

DERIVED_LABELS: dict[str, str] = {
    "mass": "mass",
    "balance": "balance point, from the butt",
    "inertia_cg": "pitch inertia about the balance point",
    "inertia_grip": "pitch inertia about the grip pivot",
    "swingweight": "swingweight (10 cm from the butt)",
    "twistweight": "twistweight (roll inertia)",
    "recoil_weight": "recoil weight (inertia about the balance point)",
    "centre_of_percussion": "centre of percussion, pivot at the grip",
    "head_area": "head (string-bed) area",
    "reduced_mass_centre_free": "reduced mass at the face centre, free (eq 4)",
    "reduced_mass_centre_pinned": "reduced mass at the face centre, pinned at the grip (eq 4)",
}
"""Labels of the racket's derived properties in the racket section, by key without its unit."""

UNITS: dict[str, tuple[str, float]] = {
    "kg": ("g", 1e3),
    "m": ("mm", 1e3),
    "kgm2": ("g·m²", 1e3),
    "kgcm2": ("kg·cm²", 1.0),
    "cm2": ("cm²", 1.0),
    "hz": ("Hz", 1.0),
    "n": ("N", 1.0),
    "pa": ("GPa", 1e-9),
    "s": ("ms", 1e3),
    "mps": ("m/s", 1.0),
}
"""Unit suffix of a key → (display unit, factor)."""


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


def quantity(key: str, value: Any) -> tuple[str, str, str]:
    """(label, value, unit) of a unit-suffixed key (``mass_kg``), in the units engineers quote."""
    name, _, suffix = key.rpartition("_")
    if not name or suffix not in UNITS:
        name, suffix = key, ""
    unit, factor = UNITS.get(suffix, ("", 1.0))
    if suffix == "pa" and "modulus" not in name:
        unit, factor = "Pa", 1.0
    if isinstance(value, int | float) and not isinstance(value, bool):
        text = fmt(float(value) * factor, ".4g") if suffix else fmt(value, "g")
    elif value is None:
        text, unit = "not set", ""
    else:
        text = str(value)
    return name.replace("_", " "), text, unit


def rounded(values: NDArray[np.float64], digits: int = 4) -> list[float | None]:
    """Values for JSON: ``digits`` significant digits kept, NaN as null."""
    return [float(f"{v:.{digits}g}") if math.isfinite(v) else None for v in values.tolist()]
