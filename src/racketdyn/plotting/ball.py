"""Figure of ``racketdyn ball``: force against the ball's flattening in each bounce."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from racketdyn.plotting.primitives import axes_grid
from racketdyn.plotting.registry import file_of

if TYPE_CHECKING:
    from racketdyn.impact.bounce import BallBounces

__all__ = ["BALL_FIGURE", "draw_ball_loops", "figure_ball_loops"]

BALL_FIGURE = file_of("ball_hysteresis")
_TITLES = {
    "rigid": "rigid surface: the ball's flattening",
    "strings": "head-clamped strings: ball + bed compression",
}


def draw_ball_loops(bounces: BallBounces, axes: Sequence[Axes] | None = None) -> list[Axes]:
    """One panel per surface: force (N) against compression (mm), a loop per speed.

    Loading runs up the upper branch and unloading down the lower one; the area between is
    the energy the bounce loses.  Draws only the arrays ``bounces`` holds.

    Parameters
    ----------
    bounces : BallBounces
        The bounces the step computed.
    axes : sequence of Axes, optional
        One per surface to draw into; default a figure of its own
        (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that many).

    Returns
    -------
    list of Axes
    """
    _, made = axes_grid(
        axes, 1, len(bounces.surfaces), figsize=(4.6 * len(bounces.surfaces), 3.8), squeeze=False
    )
    axes = list(made[0])
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.85, max(bounces.speeds.size, 1)))
    for i, (ax, surface) in enumerate(zip(axes, bounces.surfaces, strict=True)):
        for j, speed in enumerate(bounces.speeds):
            x, f = bounces.loop_compression[i, j], bounces.loop_force[i, j]
            if not np.all(np.isfinite(f)):
                continue
            ax.plot(
                x * 1e3,
                f,
                color=colours[j],
                label=f"{speed:g} m/s: COR {bounces.cor[i, j]:.3f}",
            )
        ax.set_xlabel("compression (mm)")
        ax.set_ylabel("force (N)")
        ax.set_title(_TITLES.get(surface, surface), fontsize=10)
        ax.legend(fontsize=7, frameon=False)
        ax.grid(alpha=0.3)
    return list(axes)


def figure_ball_loops(bounces: BallBounces, axes: Sequence[Axes] | None = None) -> Figure:
    """:func:`draw_ball_loops` in a figure of its own (the registry's ``ball_hysteresis``), or
    in the caller's ``axes``.

    Parameters
    ----------
    bounces : BallBounces
        The bounces the step computed.
    axes : sequence of Axes, optional
        One per surface to draw into, their figure, size and layout the caller's (not tightened
        here); default a figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an
        error if not that many).
    """
    figure, made = axes_grid(
        axes, 1, len(bounces.surfaces), figsize=(4.6 * len(bounces.surfaces), 3.8), squeeze=False
    )
    draw_ball_loops(bounces, list(made[0]))
    if axes is None:
        figure.tight_layout()
    return figure
