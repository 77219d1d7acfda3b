"""Short text and HTML summaries of the core objects, for ``repr`` and notebooks.

A dataclass ``repr`` prints every array in full (85 kB for a prediction over a face grid);
these helpers keep a summary to a line or a small table.  Core layer: imports nothing from
racketdyn.
"""

from __future__ import annotations

import html
from collections.abc import Iterable, Sequence

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["case_words", "html_table", "number", "numbers", "shorten", "span", "words"]

_MAX_TEXT = 60
_MAX_ITEMS = 6


def shorten(text: str, limit: int = _MAX_TEXT) -> str:
    """``text`` cut to ``limit`` characters, with ``…`` where it was cut."""
    return text if len(text) <= limit else text[: limit - 1] + "…"


def case_words(ball_speed: float, racket_speed: float, support: str | None = None) -> str:
    """One impact case in words, as every headline names it: ``"ball 25 m/s, racket 28 m/s,
    pinned"``, ``"ball 20 m/s, racket at rest"`` (m/s)."""
    racket = f"racket {racket_speed:g} m/s" if racket_speed else "racket at rest"
    return f"ball {ball_speed:g} m/s, {racket}" + (f", {support}" if support else "")


def number(value: float) -> str:
    """A float with four significant figures (``nan`` as such)."""
    return f"{float(value):.4g}"


def numbers(values: ArrayLike, limit: int = _MAX_ITEMS) -> str:
    """Up to ``limit`` numbers, comma-separated (``…, last`` beyond that)."""
    flat = np.asarray(values, dtype=float).reshape(-1)
    shown = [number(v) for v in flat]
    if len(shown) > limit:
        shown = [*shown[: limit - 1], "…", shown[-1]]
    return ", ".join(shown)


def span(values: ArrayLike) -> str:
    """``a–b`` (smallest to largest), or the one value."""
    flat = np.asarray(values, dtype=float).reshape(-1)
    if flat.size == 0:
        return "none"
    low, high = np.nanmin(flat), np.nanmax(flat)
    return number(low) if low == high else f"{number(low)}–{number(high)}"


def words(items: Sequence[str], limit: int = _MAX_ITEMS) -> str:
    """Up to ``limit`` names, comma-separated, each cut short (``… (n in all)`` beyond)."""
    shown = [shorten(str(item), 30) for item in items[:limit]]
    more = f", … ({len(items)} in all)" if len(items) > limit else ""
    return ", ".join(shown) + more


def html_table(title: str, rows: Iterable[tuple[str, str]]) -> str:
    """A small two-column HTML table (escaped), with ``title`` as its caption."""
    body = "".join(
        f"<tr><th style='text-align:left'>{html.escape(key)}</th>"
        f"<td style='text-align:left'>{html.escape(value)}</td></tr>"
        for key, value in rows
    )
    return f"<table><caption>{html.escape(title)}</caption><tbody>{body}</tbody></table>"
