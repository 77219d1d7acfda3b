"""A lab's points on racketdyn's racket face: the face plane mapped onto (x, y), said how.

A lab measures a racket in its own frame: lying in the x–z plane, the head up or down, the
origin anywhere.  racketdyn's racket has x along the long axis from the butt (m) and y across
it.  :func:`face_mapping` finds the face plane of 3-D points (their two directions of largest
spread, by SVD), takes the long axis as the direction of largest spread pointing to the head
(the end where the points spread widest across), y across it, and places the origin:

- along x, at the lab origin's projection when every point then lies on the racket
  (0 ≤ x ≤ length: a lab that measured from the butt keeps its x), else so that the point
  furthest towards the head is at the racket's tip (the head's outer edge);
- along y, at the middle of the points' spread across (a racket is symmetric about its axis).

The sign of y is arbitrary (the lab's handedness); names and predictions do not depend on it.
:meth:`FaceMapping.describe` says all this for the run's record.  Points off the plane by more
than :data:`FACE_TOLERANCE` of the racket's length are not a face: :func:`face_mapping` returns
None for them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.numerics import as_points
from racketdyn.racket import Racket

__all__ = ["FACE_TOLERANCE", "FaceMapping", "face_mapping", "looks_like_racket"]

FACE_TOLERANCE = 0.05
"""Largest rms distance of the points from their plane, as a fraction of the racket's length
(a frame 25–30 mm thick measured on both faces stays well inside it)."""


@dataclass(frozen=True)
class FaceMapping:
    """Lab (x, y, z) → racketdyn face (x, y): ``x = (p − origin)·x_axis``, same for y.

    Attributes
    ----------
    origin : ndarray, shape (3,)
        The lab point that becomes the face's (0, 0), m.
    x_axis, y_axis : ndarray, shape (3,)
        Lab directions of racketdyn's x (butt → tip) and y (unit vectors).
    off_plane_m : float
        Rms distance of the points from the face plane, m.
    """

    origin: NDArray[np.float64]
    x_axis: NDArray[np.float64]
    y_axis: NDArray[np.float64]
    off_plane_m: float

    def apply(self, points: ArrayLike) -> NDArray[np.float64]:
        """Face coordinates (x, y), m, of lab points (x, y, z), m."""
        p = np.asarray(points, dtype=float) - self.origin
        return np.column_stack([p @ self.x_axis, p @ self.y_axis])

    def describe(self) -> str:
        """The mapping in words (for run.json and the console)."""

        def vector(v: NDArray[np.float64]) -> str:
            return "(" + ", ".join(f"{round(float(c), 3) + 0.0:+.3f}" for c in v) + ")"

        return (
            f"racket face from the lab's (x, y, z): x along lab {vector(self.x_axis)} from the "
            f"butt, y along lab {vector(self.y_axis)}, origin at lab {vector(self.origin)} m; "
            f"points within {1e3 * self.off_plane_m:.1f} mm (rms) of the face plane"
        )


def face_mapping(locations: ArrayLike, racket: Racket) -> FaceMapping | None:
    """The mapping of 3-D lab points onto the racket's face, or None if they are not a face.

    Parameters
    ----------
    locations : array_like, shape (n, 3)
        The points in the lab's frame, m.
    racket : Racket
        The racket (its length places the origin when the lab's does not fit).

    Returns
    -------
    FaceMapping or None
        None for fewer than three points, points on one line, or points off one plane.
    """
    points = as_points(locations, "points on the racket")
    if points.shape[1] != 3 or points.shape[0] < 3:
        return None
    centre = points.mean(axis=0)
    _, spread, directions = np.linalg.svd(points - centre, full_matrices=False)
    rms = spread / np.sqrt(points.shape[0])
    if rms[1] <= 1e-9 or rms[2] > FACE_TOLERANCE * racket.length_m:
        return None
    x_axis, y_axis = directions[0], directions[1]
    u = (points - centre) @ x_axis
    v = (points - centre) @ y_axis
    middle = 0.5 * (u.min() + u.max())
    upper, lower = v[u > middle], v[u <= middle]
    if (np.ptp(upper) if upper.size else 0.0) < (np.ptp(lower) if lower.size else 0.0):
        x_axis, y_axis = -x_axis, -y_axis  # the head (widest end) at larger x; stay right-handed
        u, v = -u, -v
    origin_u = -(centre @ x_axis)  # the lab origin's x
    if u.min() - origin_u >= 0 and u.max() - origin_u <= racket.length_m:
        start = origin_u
    else:
        start = float(u.max()) - racket.length_m
    across = 0.5 * (v.min() + v.max())
    origin = centre + start * x_axis + across * y_axis
    return FaceMapping(
        origin=np.asarray(origin),
        x_axis=np.asarray(x_axis),
        y_axis=np.asarray(y_axis),
        off_plane_m=float(rms[2]),
    )


def looks_like_racket(locations: ArrayLike, racket: Racket) -> bool:
    """True when face points (x, y) could be a racket's measured points: every point on the
    racket's outline box (2 cm margin), spread over at least a third of its length and half
    its head's width.  A beam, a plate or a line of points is not."""
    points = as_points(locations, "points on the racket")
    if points.shape[1] != 2 or points.shape[0] < 3:
        return False
    head = racket.head
    margin = 0.02
    inside = (
        (points[:, 0] >= -margin)
        & (points[:, 0] <= racket.length_m + margin)
        & (np.abs(points[:, 1] - head.centre_y_m) <= head.half_width_m + margin)
    )
    return bool(
        inside.all()
        and np.ptp(points[:, 0]) >= racket.length_m / 3
        and np.ptp(points[:, 1]) >= head.half_width_m
    )
