"""General tools on mode shapes of any structure: nodes along a line, pairing two models by MAC.

Nothing here knows what the structure is: a caller that does (a racket, a beam, a plate) names
the modes from their shapes itself (for a racket, :mod:`racketdyn.racket_modal.shapes`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.modal.mac import mac
from racketdyn.modal.model import ModalModel
from racketdyn.numerics import as_points

__all__ = ["UNNAMED_KINDS", "ModePairing", "nodes_along", "pair_modes"]

UNNAMED_KINDS = ("unknown", "other")
"""Kinds that say nothing of a mode's shape (:data:`racketdyn.modal.model.MODE_KINDS`): a mode
of one of these may pair with a mode of any kind (:func:`pair_modes`)."""


def nodes_along(model: ModalModel, points: ArrayLike, mode: int) -> NDArray[np.float64]:
    """Where a mode's shape changes sign along a line or curve given by points, m.

    The shape is interpolated (:meth:`ModalModel.mode_shapes_at`) at the points, taken in
    order as a polyline; each sign change between two neighbours gives a node, placed by
    linear interpolation of the shape between them.

    Parameters
    ----------
    model : ModalModel
        The mode shapes.
    points : array_like, shape (n, 2) or (n, 3)
        The line or curve, ``(x, y)`` or ``(x, y, z)`` as the model's locations, m, in order
        along it (densely enough sampled that a mode has at most one node between two
        neighbours).
    mode : int
        Index of the mode (0-based).

    Returns
    -------
    ndarray, shape (n_nodes, 2) or (n_nodes, 3)
        The nodes, m, in order along the line.
    """
    line = as_points(points, "points along the line")
    shape = model.mode_shapes_at(line)[:, mode]
    crossing = np.flatnonzero(np.sign(shape[:-1]) * np.sign(shape[1:]) < 0)
    return np.asarray(
        line[crossing]
        - shape[crossing, None]
        * (line[crossing + 1] - line[crossing])
        / (shape[crossing + 1] - shape[crossing])[:, None]
    )


@dataclass(frozen=True)
class ModePairing:
    """Modes of two models paired by MAC (e.g. free against hand-held).

    Attributes
    ----------
    first, second : tuple of int
        Paired mode indices in each model.
    mac : tuple of float
        MAC of each pair.
    """

    first: tuple[int, ...]
    second: tuple[int, ...]
    mac: tuple[float, ...]


def pair_modes(
    first: ModalModel,
    second: ModalModel,
    minimum_mac: float = 0.6,
    matrix: NDArray[np.float64] | None = None,
) -> ModePairing:
    """Pair the modes of two models measured on the same points by their MAC.

    Greedy on the MAC matrix (largest first), each mode used once; pairs under ``minimum_mac``
    are left unpaired, and so are two modes whose kinds both say what they are and differ (a
    bending mode never pairs with a string-bed mode, whatever their MAC: a mode veering with
    another shares much of its shape at the points; only :data:`UNNAMED_KINDS` pair with any
    kind).  So a mode pairs with the mode of its own kind that its shape matches best, however
    far the support moved its frequency.  Shapes are compared at the first model's locations
    (the second model is interpolated there).

    Parameters
    ----------
    first, second : ModalModel
        The two models (e.g. one structure on two supports).
    minimum_mac : float
        Smallest MAC that makes a pair (–).
    matrix : ndarray, shape (first.n_modes, second.n_modes), optional
        The MAC of each two modes, where the caller compares them otherwise (e.g. on some
        of the points only); default the MAC over every point.

    Returns
    -------
    ModePairing
        The pairs, in order of the first model's modes.
    """
    if matrix is None:
        matrix = mac(first.mode_shapes, second.mode_shapes_at(first.locations))
    pairs: list[tuple[int, int, float]] = []
    used_a: set[int] = set()
    used_b: set[int] = set()
    for flat in np.argsort(matrix, axis=None)[::-1]:
        a, b = np.unravel_index(flat, matrix.shape)
        if matrix[a, b] < minimum_mac:
            break
        if a in used_a or b in used_b or not _same_kind(first.kinds[a], second.kinds[b]):
            continue
        pairs.append((int(a), int(b), float(matrix[a, b])))
        used_a.add(int(a))
        used_b.add(int(b))
    pairs.sort()
    return ModePairing(
        tuple(p[0] for p in pairs), tuple(p[1] for p in pairs), tuple(p[2] for p in pairs)
    )


def _same_kind(first: str, second: str) -> bool:
    """Whether two modes' kinds allow a pair: equal, or one of them says nothing."""
    return first == second or first in UNNAMED_KINDS or second in UNNAMED_KINDS
