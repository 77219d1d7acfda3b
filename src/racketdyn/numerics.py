"""Small numerical building blocks shared by the laws and the impact method."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from threadpoolctl import ThreadpoolController  # type: ignore[import-untyped]

from racketdyn.errors import InputError

__all__ = [
    "as_locations",
    "as_points",
    "find_peaks",
    "invert_increasing",
    "one_blas_thread",
    "spans_a_surface",
]

Function = Callable[[NDArray[np.float64]], NDArray[np.float64]]

TABLE_POINTS = 4097


def invert_increasing(
    function: Function,
    derivative: Function,
    target: ArrayLike,
    upper: float,
    newton_steps: int = 3,
) -> NDArray[np.float64]:
    """Solve ``function(x) = target`` for x in [0, upper], vectorised; NaN beyond the range.

    ``function`` must rise strictly on [0, upper].  A table of 4097 points gives the first guess
    (linear interpolation), Newton steps with ``derivative`` polish it to round-off.

    Parameters
    ----------
    function, derivative : callable
        f(x) and f'(x) on arrays.
    target : array_like
        Values to invert.
    upper : float
        Upper end of the range (the lower end is 0).
    newton_steps : int
        Newton iterations after the table.

    Raises
    ------
    ValueError
        If ``function`` does not rise strictly over the table.
    """
    goal = np.asarray(target, dtype=float)
    table_x = np.linspace(0.0, upper, TABLE_POINTS)
    table_f = function(table_x)
    if np.any(np.diff(table_f) <= 0):
        raise ValueError("function does not rise strictly over the range")
    x = np.interp(goal, table_f, table_x)
    for _ in range(newton_steps):
        slope = derivative(x)
        step = np.divide(function(x) - goal, slope, out=np.zeros_like(x), where=slope > 0)
        x = np.clip(x - step, 0.0, upper)
    outside = (goal < table_f[0]) | (goal > table_f[-1] * (1 + 1e-12))
    return np.asarray(np.where(outside, np.nan, x))


def as_locations(locations: ArrayLike, name: str = "locations") -> NDArray[np.float64]:
    """Return point locations as a finite float array shaped ``(n, 2)``, ``(x, y)`` in metres."""
    try:
        array = np.asarray(locations, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be (x, y) pairs in metres (got {locations!r})") from None
    if array.ndim == 1 and array.size == 2:
        array = array[None, :]
    if array.ndim != 2 or array.shape[1] != 2:
        raise InputError(
            f"{name} must be (x, y) pairs in metres, shaped (n, 2) (got {array.shape})"
        )
    if not np.all(np.isfinite(array)):
        raise InputError(f"{name} must be finite numbers, without NaN or inf")
    return array


def spans_a_surface(locations: NDArray[np.float64]) -> bool:
    """True if the points do not all lie on one straight line.

    Parameters
    ----------
    locations : ndarray (n_points, n_dimensions)
        The points, m.
    """
    centred = locations - locations.mean(axis=0)
    return bool(np.linalg.matrix_rank(centred, tol=1e-9) >= 2)


def as_points(points: ArrayLike, name: str = "points") -> NDArray[np.float64]:
    """Return point coordinates as a finite float array shaped ``(n, 2)`` or ``(n, 3)``, m.

    Parameters
    ----------
    points : array_like
        ``(x, y)`` or ``(x, y, z)`` of each point, m; one point may be given flat.
    name : str
        What the points are, for error messages.

    Returns
    -------
    ndarray, shape (n, 2) or (n, 3)
    """
    try:
        array = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be (x, y[, z]) in metres (got {points!r})") from None
    if array.ndim == 1 and array.size in (2, 3):
        array = array[None, :]
    if array.ndim != 2 or array.shape[1] not in (2, 3):
        raise InputError(
            f"{name} must be (x, y) or (x, y, z) in metres, shaped (n, 2) or (n, 3) "
            f"(got {array.shape})"
        )
    if not np.all(np.isfinite(array)):
        raise InputError(f"{name} must be finite numbers, without NaN or inf")
    return array


@lru_cache(maxsize=1)
def _blas() -> ThreadpoolController:
    return ThreadpoolController()


@contextmanager
def one_blas_thread() -> Iterator[None]:
    """BLAS on one thread inside the block: many small products (the mode shapes' spline at a
    thousand points, 800 × 3 each) cost twice the CPU time split over threads."""
    with _blas().limit(limits=1, user_api="blas"):
        yield


def find_peaks(
    values: ArrayLike, *, height: float | None = None, prominence: float | None = None
) -> tuple[NDArray[np.intp], dict[str, NDArray[Any]]]:
    """``scipy.signal.find_peaks(values, height=, prominence=)`` with scalar conditions: the
    same peaks and properties, without importing :mod:`scipy.signal` (which brings
    :mod:`scipy.stats`: ≈ 0.35 s of CPU, a tenth of ``racketdyn identify``).

    A peak is a sample (the middle of a flat top, rounded down) higher than its neighbours;
    its prominence is its height above the higher of the lowest points either side before a
    higher sample (or NaN, or the end). ``tests/test_numerics.py`` holds it to SciPy's.

    Parameters
    ----------
    values : array_like, 1-D
        The signal.
    height : float, optional
        Keep peaks at least this high (property ``peak_heights``).
    prominence : float, optional
        Keep peaks at least this prominent (properties ``prominences``, ``left_bases``,
        ``right_bases``).

    Returns
    -------
    peaks : ndarray of int
        Indices of the peaks kept, rising.
    properties : dict
        The properties of the conditions given, of the peaks kept.
    """
    x = np.asarray(values, dtype=np.float64)
    if x.ndim != 1:
        raise ValueError("`values` must be a 1-D array")
    # runs of equal samples (each NaN a run of its own); a peak is a run above both neighbours
    peaks = np.zeros(0, dtype=np.intp)
    if x.size >= 3:
        starts = np.flatnonzero(np.r_[True, x[1:] != x[:-1]])
        ends = np.r_[starts[1:] - 1, x.size - 1]
        top = x[starts]
        inner = np.arange(1, max(top.size - 1, 1))
        rising = (top[inner - 1] < top[inner]) & (top[inner + 1] < top[inner])
        peaks = ((starts[inner] + ends[inner]) // 2)[rising].astype(np.intp)
    properties: dict[str, NDArray[Any]] = {}
    if height is not None:
        heights = x[peaks]
        keep = height <= heights
        peaks, properties = peaks[keep], {"peak_heights": heights[keep]}
    if prominence is not None:
        found = np.empty(peaks.size)
        left_bases = np.empty(peaks.size, dtype=np.intp)
        right_bases = np.empty(peaks.size, dtype=np.intp)
        for k, peak in enumerate(peaks):
            higher = np.flatnonzero(~(x <= x[peak]))  # a higher sample or NaN ends a side
            after = int(np.searchsorted(higher, peak))
            first = int(higher[after - 1]) + 1 if after > 0 else 0
            stop = int(higher[after]) if after < higher.size else x.size
            left, right = x[first : peak + 1], x[peak:stop]
            # the lowest point nearest the peak each side (SciPy's walks away from the peak)
            left_bases[k] = first + left.size - 1 - int(np.argmin(left[::-1]))
            right_bases[k] = peak + int(np.argmin(right))
            found[k] = x[peak] - max(float(left.min()), float(right.min()))
        keep = prominence <= found
        peaks = peaks[keep]
        properties = {name: value[keep] for name, value in properties.items()}
        properties |= {
            "prominences": found[keep],
            "left_bases": left_bases[keep],
            "right_bases": right_bases[keep],
        }
    return peaks, properties
