"""Counts in words: a noun in the number its count needs ("1 average", "3 averages"); the
unit a name's ending gives (``contact_time_s`` → s).

Core layer, standard library only: the command line imports it before NumPy.
"""

from __future__ import annotations

__all__ = ["UNITS_BY_ENDING", "noun", "plural", "unit_of"]


def noun(count: int, singular: str, plural_form: str | None = None) -> str:
    """``singular`` for a count of one, else ``plural_form`` (default ``singular + "s"``)."""
    return singular if count == 1 else plural_form or singular + "s"


def plural(count: int, singular: str, plural_form: str | None = None) -> str:
    """A count with its noun in the number it takes: ``"1 average"``, ``"3 averages"``."""
    return f"{count} {noun(count, singular, plural_form)}"


UNITS_BY_ENDING = {
    "_m": "m",
    "_s": "s",
    "_hz": "Hz",
    "_mps": "m/s",
    "_rad": "rad",
    "_radps": "rad/s",
    "_deg": "degree",
    "_n": "N",
    "_ns": "N s",
    "_j": "J",
    "_kg": "kg",
    "_kgm2": "kg m2",
    "_n_per_m": "N/m",
    "_s_per_m": "s/m",
}
"""Units by the ending of a field's name (the glossary's ``x_m``, ``contact_time_s``), SI; the
longest ending that matches wins."""


def unit_of(name: str) -> str | None:
    """The SI unit a name's ending gives (:data:`UNITS_BY_ENDING`), or None."""
    endings = [end for end in UNITS_BY_ENDING if name.endswith(end)]
    return UNITS_BY_ENDING[max(endings, key=len)] if endings else None
