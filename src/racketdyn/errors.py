"""Errors that carry a message a user can act on.

Every check of user input raises :class:`InputError`; the command line prints its message on
one line and exits with status 2.  Library users can catch it as a :class:`ValueError`.
"""

from __future__ import annotations

import contextlib
import functools
import logging
import math
import warnings
from collections.abc import Callable, Iterable, Iterator
from typing import ParamSpec, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn._display import shorten

__all__ = [
    "InputError",
    "logs_warnings",
    "one_of",
    "require_finite",
    "require_numbers",
    "require_positive",
    "require_range",
    "require_speeds",
    "require_words",
    "warnings_logged",
]

P = ParamSpec("P")
R = TypeVar("R")


class InputError(ValueError):
    """Bad user input: the message names the input and says what is allowed."""


def require_positive(name: str, value: float, *, allow_zero: bool = False) -> float:
    """Return ``value`` as a float if it is a finite positive number, else raise InputError."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number (got {value!r})") from None
    if not math.isfinite(number) or number < 0 or (number == 0 and not allow_zero):
        what = "zero or positive" if allow_zero else "positive"
        raise InputError(f"{name} must be a finite {what} number (got {value!r})")
    return number


def require_finite(name: str, value: float) -> float:
    """Return ``value`` as a float if it is a finite number, else raise InputError."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number (got {value!r})") from None
    if not math.isfinite(number):
        raise InputError(f"{name} must be a finite number (got {value!r})")
    return number


def require_range(name: str, value: float, low: float, high: float) -> float:
    """Return ``value`` as a float if ``low <= value <= high``, else raise InputError."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number (got {value!r})") from None
    if not (math.isfinite(number) and low <= number <= high):
        raise InputError(f"{name} must lie between {low:g} and {high:g} (got {value!r})")
    return number


def require_whole(name: str, value: object, least: int = 1) -> int:
    """Return ``value`` as an int if it is a whole number (not a bool) ≥ ``least``, else raise
    InputError."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < least:
        raise InputError(f"{name} must be a whole number of at least {least} (got {value!r})")
    return int(value)


def require_words(name: str, value: str | Iterable[str]) -> list[str]:
    """The words of a list option as Python or the command line gives them: a sequence of
    words, or one text of comma-separated words (``"free,hand"``, the command line's spelling),
    none empty; else InputError naming ``name``."""
    items = value.split(",") if isinstance(value, str) else list(value)
    words = [item.strip() if isinstance(item, str) else item for item in items]
    if not words or not all(isinstance(word, str) and word for word in words):
        raise InputError(
            f"{name} must be words, a sequence of them or one text of comma-separated words, "
            f"none empty (got {value!r})"
        )
    return words


def require_numbers(name: str, value: object, unit: str) -> list[float]:
    """Finite numbers (any sign) of a list option as Python or the command line gives them:
    one number, a sequence of them or one text of comma-separated numbers (``"40,1000"``);
    else InputError naming ``name`` and the ``unit``."""
    if isinstance(value, str):
        items: list[object] = list(require_words(name, value))
    elif isinstance(value, int | float | np.integer | np.floating):
        items = [value]
    else:
        items = list(np.ravel(np.asarray(value, dtype=object)))
    numbers = []
    for item in items:
        try:
            if isinstance(item, bool):
                raise TypeError
            number = float(item)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            raise InputError(f"{name}: {item!r} is not a number ({unit})") from None
        if not math.isfinite(number):
            raise InputError(f"{name} must be a finite number, {unit} (got {item!r})")
        numbers.append(number)
    return numbers


def require_speeds(name: str, values: ArrayLike) -> NDArray[np.float64]:
    """Return speeds (m/s) as a non-empty 1-D float array of finite values ≥ 0, else InputError;
    one text of comma-separated speeds (``"10,20"``, the command line's spelling) is read."""
    if isinstance(values, str):
        values = require_numbers(name, values, "m/s")
    try:
        speeds = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"{name} must be numbers in m/s (got {values!r})") from None
    if speeds.ndim != 1 or speeds.size == 0:
        raise InputError(f"{name}: give one or more speeds in m/s (got {values!r})")
    if not np.all(np.isfinite(speeds)) or np.any(speeds < 0):
        given = ", ".join(f"{v:g}" for v in speeds)
        raise InputError(f"{name} must be finite speeds of zero or more, m/s (got {given})")
    return speeds


def one_of(name: str, value: object, allowed: Iterable[str]) -> str:
    """Return ``value`` if it is one of ``allowed``, else raise InputError listing them."""
    options = tuple(allowed)
    if not isinstance(value, str) or value not in options:
        raise InputError(f"{name} must be one of {', '.join(options)} (got {value!r})")
    return value


@contextlib.contextmanager
def warnings_logged(log: logging.Logger, where: str) -> Iterator[None]:
    """Warnings raised inside go to ``log`` (info level), not to the console.

    For the boundaries where a user's file meets numpy and pyuff (reading a file, computing
    FRFs): a damaged file makes numpy warn (``overflow encountered in multiply``) and pyuff
    warn, which the console showed with a source line, while the input's own check says what
    is wrong in one line.  Only the warnings raised inside the block are taken (no global
    filter); each distinct one is logged once, naming ``where``.
    """
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            yield
        finally:
            seen: set[tuple[str, str]] = set()
            for warning in caught:
                key = (warning.category.__name__, str(warning.message))
                if key not in seen:
                    seen.add(key)
                    log.info("%s: %s: %s (%s:%d)", where, *key, warning.filename, warning.lineno)


def logs_warnings(log: logging.Logger) -> Callable[[Callable[P, R]], Callable[P, R]]:
    """Decorator: the function runs under :func:`warnings_logged`, named with its first
    argument (the file it reads, the records it computes from)."""

    def decorate(func: Callable[P, R]) -> Callable[P, R]:
        @functools.wraps(func)
        def logged(*args: P.args, **kwargs: P.kwargs) -> R:
            where = f"{func.__name__}({shorten(str(args[0])) if args else ''})"
            with warnings_logged(log, where):
                return func(*args, **kwargs)

        return logged

    return decorate
