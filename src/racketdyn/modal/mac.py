"""The modal assurance criterion (MAC): how alike two sets of mode shapes are.

Allemang and Brown, "A correlation coefficient for modal vector analysis", IMAC I, 1982.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["mac"]


def mac(
    a: NDArray[np.complexfloating[Any, Any]] | NDArray[np.floating[Any]],
    b: NDArray[np.complexfloating[Any, Any]] | NDArray[np.floating[Any]],
    *,
    pairwise: bool = False,
) -> NDArray[np.float64]:
    """Modal assurance criterion ``|aᴴb|² / ((aᴴa)(bᴴb))`` between shapes (columns).

    Parameters
    ----------
    a, b : ndarray, shape (n_points, n_a) and (n_points, n_b)
        Shapes as columns (real or complex).
    pairwise : bool
        False: the (n_a, n_b) matrix of every pair.  True: column k of ``a`` with column k of
        ``b`` only (n_a = n_b), shape (n_a,).

    Returns
    -------
    ndarray
        MAC values in [0, 1] (0 where a shape is zero).
    """
    a2 = np.atleast_2d(np.asarray(a).T).T
    b2 = np.atleast_2d(np.asarray(b).T).T
    norm_a = np.sum(np.abs(a2) ** 2, axis=0)
    norm_b = np.sum(np.abs(b2) ** 2, axis=0)
    if pairwise:
        cross = np.abs(np.sum(a2.conj() * b2, axis=0)) ** 2
        denominator = norm_a * norm_b
    else:
        cross = np.abs(a2.conj().T @ b2) ** 2
        denominator = np.outer(norm_a, norm_b)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = np.where(denominator > 0, cross / np.where(denominator > 0, denominator, 1), 0.0)
    return np.asarray(np.clip(out, 0.0, 1.0), dtype=float)
