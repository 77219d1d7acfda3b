"""Counts in words: a noun in the number its count needs ("1 average", "3 averages").

Core layer, standard library only: the command line imports it before NumPy.
"""

from __future__ import annotations

__all__ = ["noun", "plural"]


def noun(count: int, singular: str, plural_form: str | None = None) -> str:
    """``singular`` for a count of one, else ``plural_form`` (default ``singular + "s"``)."""
    return singular if count == 1 else plural_form or singular + "s"


def plural(count: int, singular: str, plural_form: str | None = None) -> str:
    """A count with its noun in the number it takes: ``"1 average"``, ``"3 averages"``."""
    return f"{count} {noun(count, singular, plural_form)}"
