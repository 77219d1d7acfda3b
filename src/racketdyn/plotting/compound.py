"""Figures of ``racketdyn compound``: the ball on the strings (paper, Figs 8–9).

The responses come from :mod:`racketdyn.workflows.compound` (computed by
:class:`racketdyn.impact.compound.CompoundSystem`); this module only draws them.
"""

from __future__ import annotations

import logging
from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from numpy.typing import ArrayLike

from racketdyn.plotting.primitives import SUPPORT_STYLE
from racketdyn.plotting.render import save_figure

if TYPE_CHECKING:
    from racketdyn.workflows.compound import CompoundResult

__all__ = [
    "COMPOUND_FRF_FIGURE",
    "COMPOUND_RESPONSE_FIGURE",
    "COMPOUND_SHAPE_FIGURE",
    "plot_ball_mode_shape",
    "plot_compound_frf",
    "plot_neck_response",
    "write_compound_figures",
]

log = logging.getLogger(__name__)

COMPOUND_RESPONSE_FIGURE = "compound_response.png"
"""The neck's acceleration after the hammer blow, ball on the strings (Fig. 8c)."""
COMPOUND_FRF_FIGURE = "compound_frf.png"
"""Receptance hammer → neck without and with the ball (Fig. 9a, 9b)."""
COMPOUND_SHAPE_FIGURE = "compound_shape.png"
"""The ball mode: the frame along its axis against the ball (Fig. 8a)."""


def plot_ball_mode_shape(
    axis_x: ArrayLike,
    frame: ArrayLike,
    ball_x: float,
    ball: float,
    support: str = "free",
    ax: Axes | None = None,
) -> Axes:
    """The ball mode's shape: the frame's displacement along its long axis and the ball's.

    Parameters
    ----------
    axis_x : array_like
        Points along the axis, m from the butt.
    frame : array_like
        The frame's displacement there (ball = 1), dimensionless.
    ball_x : float
        Where the ball sits, m from the butt.
    ball : float
        The ball's displacement (1).
    support : str
        Support (line colour and label).
    ax : Axes, optional
        Where to draw.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 3.6), layout="constrained")
    colour = SUPPORT_STYLE.get(support, {}).get("color", "tab:orange")
    x_mm = np.asarray(axis_x) * 1e3
    ax.plot(x_mm, np.asarray(frame), color=colour, lw=1.2, label=f"frame, {support}")
    ax.plot([ball_x * 1e3], [ball], "o", color=colour, ms=9, mfc="none", label=f"ball, {support}")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("x from the butt (mm)")
    ax.set_ylabel("displacement in the ball mode (ball = 1)")
    ax.legend(fontsize=8)
    return ax


def plot_neck_response(
    times: ArrayLike,
    acceleration: ArrayLike,
    ball_hz: float,
    bending_hz: float,
    label: str = "",
    ax: Axes | None = None,
) -> Axes:
    """The neck's acceleration against time, with the ball mode's and 2-node mode's periods.

    Parameters
    ----------
    times : array_like
        Times, s.
    acceleration : array_like
        Acceleration per unit hammer impulse, m/s² per N·s.
    ball_hz, bending_hz : float
        Frequencies of the ball mode and of the 2-node bending mode, Hz (for the label).
    label : str
        Legend label.
    ax : Axes, optional
        Where to draw.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 3.6), layout="constrained")
    t_ms = np.asarray(times) * 1e3
    ax.plot(t_ms, np.asarray(acceleration), lw=0.9, label=label or None)
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("neck acceleration (m/s² per N·s of impulse)")
    ax.set_title(f"ball mode {ball_hz:.1f} Hz and 2-node bending {bending_hz:.1f} Hz", fontsize=9)
    if label:
        ax.legend(fontsize=8)
    return ax


def plot_compound_frf(
    frequency: ArrayLike,
    receptance: ArrayLike,
    label: str,
    support: str = "free",
    dashed: bool = False,
    ax: Axes | None = None,
) -> Axes:
    """|receptance| against frequency (log scale).

    Parameters
    ----------
    frequency : array_like
        Frequencies, Hz.
    receptance : array_like
        Complex receptance, m/N.
    label : str
        Legend label.
    support : str
        Support (line colour).
    dashed : bool
        Dashed line (the racket alone).
    ax : Axes, optional
        Where to draw.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 3.6), layout="constrained")
    colour = SUPPORT_STYLE.get(support, {}).get("color", "tab:orange")
    style = {"color": colour, "linestyle": "--" if dashed else "-"}
    ax.semilogy(np.asarray(frequency), np.abs(np.asarray(receptance)), label=label, lw=1.0, **style)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("|receptance| hammer → neck (m/N)")
    ax.legend(fontsize=8)
    return ax


def write_compound_figures(result: CompoundResult, out: Path) -> list[Path]:
    """Draw Fig. 8c and Fig. 9 of the run into ``out``; returns the paths.

    Parameters
    ----------
    result : CompoundResult
        The step's result.
    out : Path
        Output folder.
    """
    # one panel, the first support's (the page is near its size budget; the CSV and run.json
    # hold every support)
    support = result.supports[0]
    modes = result.modes[support]
    figure, ax = plt.subplots(figsize=(4.8, 2.8), layout="constrained")
    plot_neck_response(
        result.times,
        result.neck_acceleration[support],
        modes.ball_frequency,
        modes.frequency_of("2-node bending"),
        support,
        ax=ax,
    )
    away_mm = abs(result.location[0] - result.hammer[0]) * 1e3
    figure.suptitle(
        f"Fig. 8c: the neck after a hammer blow {away_mm:.0f} mm from the ball, {support}",
        fontsize=9,
    )
    paths = [save_figure(figure, Path(out) / COMPOUND_RESPONSE_FIGURE)]
    figure, axes = plt.subplots(1, 2, figsize=(8.0, 2.7), layout="constrained", sharey=True)
    for support in result.supports:
        plot_compound_frf(result.frequency, result.frf_alone[support], support, support, ax=axes[0])
        plot_compound_frf(
            result.frequency, result.frf_with_ball[support], support, support, ax=axes[1]
        )
    axes[0].set_title("(a) the racket alone", fontsize=9)
    axes[1].set_title("(b) the racket with the ball on the strings", fontsize=9)
    for support in result.supports[:1]:
        f_ball = result.modes[support].ball_frequency
        axes[1].axvline(f_ball, color="0.5", lw=0.6, ls=":")
        axes[1].annotate(
            f"ball mode {f_ball:.1f} Hz",
            (f_ball, 0.98),
            xycoords=("data", "axes fraction"),
            fontsize=8,
            ha="right",
            va="top",
            rotation=90,
        )
    figure.suptitle("Fig. 9: receptance hammer → neck without and with the ball", fontsize=10)
    paths.append(save_figure(figure, Path(out) / COMPOUND_FRF_FIGURE))
    figure, ax = plt.subplots(figsize=(4.8, 2.6), layout="constrained")
    for support, (frame, ball) in result.ball_shape.items():
        plot_ball_mode_shape(result.axis_x, frame, result.location[0], ball, support, ax=ax)
    ax.set_title(
        "Fig. 8a: the ball mode, ball and frame moving against each other through the strings",
        fontsize=9,
    )
    paths.append(save_figure(figure, Path(out) / COMPOUND_SHAPE_FIGURE))
    for path in paths:
        log.info("wrote %s", path)
    return paths
