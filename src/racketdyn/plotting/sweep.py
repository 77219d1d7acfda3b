"""Figures of a design sweep: the summary metrics against each variable, one line per support.

The curves come from :func:`racketdyn.sweep.summary.summary_curves` (computed by the sweep with
the spec's speeds and fraction); this module only draws them.  The figure is the registry's
``summary`` entry (:mod:`racketdyn.plotting.registry`), written once per variable by
:func:`racketdyn.plotting.steps.sweep_figures`.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from racketdyn.plotting.primitives import SUPPORT_STYLE, axes_grid
from racketdyn.sweep.summary import SummaryCurves

__all__ = ["figure_summary", "plot_centre_rebound", "plot_sweet_area"]


def _plot_metric(curves: SummaryCurves, metric: str, ax: Axes | None) -> Axes:
    if ax is None:
        _, ax = plt.subplots(figsize=(5.0, 3.6), layout="constrained")
    centre = metric == "centre_rebound_ratio"
    values = curves.centre_rebound_ratio if centre else curves.sweet_area_cm2
    levels = curves.centre_without if centre else curves.area_without
    for k, support in enumerate(curves.supports):
        style = SUPPORT_STYLE.get(support, {})
        color = str(style.get("color", "tab:gray"))
        ax.plot(
            curves.x,
            values[k],
            color=color,
            marker=str(style.get("marker", "o")),
            label=str(style.get("label", support)),
            linestyle="-",
            markersize=4,
        )
        if metric in curves.bands:  # a sweep with an uncertainty: its 5-95 % band
            low, high = curves.bands[metric]
            ax.fill_between(curves.x, low[k], high[k], color=color, alpha=0.2, lw=0)
        for level in levels[k][np.isfinite(levels[k])]:
            ax.axhline(level, color=color, linestyle=":", linewidth=1.0)
    if metric in curves.bands:
        ax.fill_between([], [], [], color="0.4", alpha=0.2, lw=0, label="5-95 % band")
    if curves.without:
        ax.plot(
            [], [], color="0.4", linestyle=":", linewidth=1.0, label=f"without the {curves.without}"
        )
    if curves.clock:
        ticks = np.unique(curves.x)
        ax.set_xticks(ticks, [f"{12 if t == 0 else t:g}" for t in ticks])
    ax.set_xlabel(curves.x_label)
    speeds = f"{curves.ball_speed:g} m/s ball"
    if curves.racket_speed:
        speeds += f", {curves.racket_speed:g} m/s racket"
    if centre:
        ax.set_ylabel("rebound ratio e at centre (–)")
        ax.set_title(f"face centre, {speeds}", fontsize=9)
    else:
        ax.set_ylabel("sweet area (cm²)")
        ax.set_title(f"e ≥ {curves.threshold_fraction:g} × the face's best, {speeds}", fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_centre_rebound(curves: SummaryCurves, ax: Axes | None = None) -> Axes:
    """Rebound ratio at the face centre against a variable, one line per support (with an
    uncertainty, its 5-95 % band shaded: ``curves.bands``).

    Parameters
    ----------
    curves : SummaryCurves
        The variable's curves (:func:`racketdyn.sweep.summary.summary_curves`).
    ax : matplotlib Axes, optional
        Where to draw (a new figure if None).

    Returns
    -------
    Axes
    """
    return _plot_metric(curves, "centre_rebound_ratio", ax)


def plot_sweet_area(curves: SummaryCurves, ax: Axes | None = None) -> Axes:
    """The sweet area against a variable, per support (with an uncertainty, its 5-95 % band
    shaded where given).

    The area of each design's face whose rebound ratio is near the best of that face
    (:func:`racketdyn.sweep.sweet_area_cm2`): the numbers of ``summary.csv``.

    Parameters
    ----------
    curves, ax
        As for :func:`plot_centre_rebound`.

    Returns
    -------
    Axes
    """
    return _plot_metric(curves, "sweet_area_cm2", ax)


def figure_summary(curves: SummaryCurves, axes: Sequence[Axes] | None = None) -> Figure:
    """``summary_<variable>.png``: the centre rebound (left) and the sweet area (right) against
    the variable.

    Parameters
    ----------
    curves : SummaryCurves
        The variable's curves.
    axes : sequence of Axes, optional
        Two (centre rebound, sweet area) to draw into, their figure, size and layout the caller's;
        default a figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an error if
        not that many).
    """
    figure, (left, right) = axes_grid(axes, 1, 2, figsize=(9.0, 3.6), layout="constrained")
    plot_centre_rebound(curves, ax=left)
    plot_sweet_area(curves, ax=right)
    figure.suptitle(f"{curves.title}: {curves.x_label}", fontsize=10)
    return figure
