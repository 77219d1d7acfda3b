"""A beam frame held in a hand: the frame's displacement rows and the hand's matrices.

The one hand of every model (:class:`racketdyn.hand.Hand`) on the beam frame of the built-in
model and the virtual rig (Hermite cubics for ``w``, linear elements for ``θ``; the frame's DOFs
``w, w'`` at each node, then ``θ`` at each node): the rig's held racket
(:func:`racketdyn.rig.rig_model`) and the frame held by the hand that a held test's modes are
named against (:func:`racketdyn.racket_modal.beam.reference_shapes`) take their hand from
here.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from racketdyn.hand import Hand

__all__ = ["frame_rows", "hand_matrices"]

_GAUSS_LINE = np.polynomial.legendre.leggauss(4)


def frame_rows(
    x: NDArray[np.float64], xs: NDArray[np.float64], ys: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Rows giving ``w(x) + θ(x)·y`` from the frame DOFs (Hermite w, linear θ).

    Parameters
    ----------
    x : ndarray, shape (n_nodes,)
        The beam's nodes along the long axis, m.
    xs, ys : ndarray, shape (n,)
        Where the displacement is wanted, m (x from the butt, y across the face).

    Returns
    -------
    ndarray, shape (n, 3 n_nodes)
        Rows over the frame's DOFs (``w, w'`` at each node, then ``θ`` at each node).
    """
    n_nodes = x.size
    element = np.clip(np.searchsorted(x, xs, side="right") - 1, 0, n_nodes - 2)
    h = x[element + 1] - x[element]
    s = (xs - x[element]) / h
    rows = np.zeros((xs.size, 3 * n_nodes))
    point = np.arange(xs.size)
    hermite = (
        1 - 3 * s**2 + 2 * s**3,
        h * (s - 2 * s**2 + s**3),
        3 * s**2 - 2 * s**3,
        h * (-(s**2) + s**3),
    )
    for j, values in enumerate(hermite):
        rows[point, 2 * element + j] = values
    rows[point, 2 * n_nodes + element] = (1 - s) * ys
    rows[point, 2 * n_nodes + element + 1] = s * ys
    return rows


def _line_rows(
    x: NDArray[np.float64], start: float, end: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Gauss points' frame rows (``w`` and ``θ`` at y = 1) over [start, end], and weights."""
    gx, gw = _GAUSS_LINE
    edges = np.unique(np.concatenate([[start, end], x[(x > start) & (x < end)]]))
    xs = (0.5 * (edges[:-1, None] + edges[1:, None]) + 0.5 * np.diff(edges)[:, None] * gx).ravel()
    ws = (0.5 * np.diff(edges)[:, None] * gw).ravel()
    return frame_rows(x, xs, np.ones_like(xs)), ws


def _line_matrix(
    x: NDArray[np.float64], start: float, end: float, *, bending: bool
) -> NDArray[np.float64]:
    """``∫ NᵀN dx`` over [start, end] for the frame's w (bending) or θ (twist) field."""
    rows, ws = _line_rows(x, start, end)
    rows = rows[:, : 2 * x.size] if bending else rows[:, 2 * x.size :]
    return np.asarray(rows.T @ (ws[:, None] * rows))


def _line_mean(x: NDArray[np.float64], start: float, end: float) -> NDArray[np.float64]:
    """``∫ N dx`` over [start, end] for the frame's w field (bending DOFs)."""
    rows, ws = _line_rows(x, start, end)
    return np.asarray(ws @ rows[:, : 2 * x.size])


def hand_matrices(
    hand: Hand, x: NDArray[np.float64], n_dof: int
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Mass, stiffness and damping of the hand and arm, ``(n_dof + 1)`` square (the arm last).

    The hand's mass, and its roll inertia, spread evenly over the grip; springs and dashpots
    ``k/L ∫ (w(x) − a)² dx`` from the grip to the arm's displacement ``a``, and in roll to
    the non-rotating arm; the arm's mass, and the shoulder's spring on it.

    Parameters
    ----------
    hand : Hand
        The hand and arm holding the grip.
    x : ndarray, shape (n_nodes,)
        The beam's nodes along the long axis, m.
    n_dof : int
        The structure's DOFs, the frame's ``3 n_nodes`` first (:func:`frame_rows`'); the arm's
        is added after them.

    Returns
    -------
    mass, stiffness, damping : ndarray, shape (n_dof + 1, n_dof + 1)
        In kg (kg·m² in roll), N/m (N·m/rad) and N·s/m (N·m·s/rad).
    """
    n = x.size
    length = hand.grip_length_m
    w_line = _line_matrix(x, hand.grip_start_m, hand.grip_end_m, bending=True) / length
    t_line = _line_matrix(x, hand.grip_start_m, hand.grip_end_m, bending=False) / length
    w_mean = _line_mean(x, hand.grip_start_m, hand.grip_end_m) / length
    arm = n_dof
    out = []
    for translational, rolling, on_arm in (
        (hand.hand_mass_kg, hand.roll_inertia_kgm2, hand.arm_mass_kg),
        (hand.stiffness_n_per_m, hand.roll_stiffness_nm_per_rad, hand.shoulder_stiffness_n_per_m),
        (hand.damping_ns_per_m, hand.roll_damping_nms_per_rad, 0.0),
    ):
        matrix = np.zeros((n_dof + 1, n_dof + 1))
        matrix[: 2 * n, : 2 * n] = translational * w_line
        matrix[2 * n : 3 * n, 2 * n : 3 * n] = rolling * t_line
        matrix[arm, arm] = on_arm
        out.append(matrix)
    for matrix, value in ((out[1], hand.stiffness_n_per_m), (out[2], hand.damping_ns_per_m)):
        # the grip's springs and dashpots pull the handle towards the arm
        matrix[: 2 * n, arm] = -value * w_mean
        matrix[arm, : 2 * n] = -value * w_mean
        matrix[arm, arm] += value
    return out[0], out[1], out[2]
