"""Figures of a design sweep: the summary metrics against each variable, one line per support.

The metrics come from :mod:`racketdyn.sweep.summary`; this module only draws them.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.axes import Axes

from racketdyn.plotting.primitives import SUPPORT_STYLE
from racketdyn.plotting.registry import entry
from racketdyn.plotting.render import save_figure
from racketdyn.sweep.summary import _variables, axis_label, summary_metrics, variable_designs
from racketdyn.sweep.variables import POINT_MASS

__all__ = ["plot_centre_rebound", "plot_sweet_area", "write_summary_figures"]


def _plot_metric(
    dataset: xr.Dataset,
    variable: str,
    metric: str,
    ax: Axes | None,
    threshold_fraction: float | None,
    ball_speed: float | None,
    racket_speed: float | None,
) -> Axes:
    if ax is None:
        _, ax = plt.subplots(figsize=(5.0, 3.6), layout="constrained")
    keep = variable_designs(dataset, variable)
    # each design's own face sets its threshold: the numbers of summary.csv
    metrics = summary_metrics(
        dataset.isel(design=keep), threshold_fraction, ball_speed, racket_speed
    )
    coord, label, scale = axis_label(dataset, variable)
    x = dataset[coord].values[keep] * scale
    clock = coord.endswith("_clock")
    if clock:  # round the clock from 12 (shown as 0 on the axis, labelled 12)
        x = np.mod(x, 12.0)
    # a point mass placed by clock or x, y: its designs without the mass (the base of a
    # one-at-a-time sweep) have a position too, which is no position of a mass — drawn as a
    # level, not as a point at that position
    without = np.zeros(x.size, dtype=bool)
    if _variables(dataset)[variable]["kind"] == POINT_MASS and not coord.endswith("_mass_kg"):
        without = dataset[f"{variable}_mass_kg"].values[keep] == 0.0
    order = np.argsort(np.where(without, np.inf, x), kind="stable")
    with_mass = order[~without[order]]
    for support in metrics["support"].values.tolist():
        style = SUPPORT_STYLE.get(str(support), {})
        values = metrics[metric].sel(support=support).values
        color = str(style.get("color", "tab:gray"))
        ax.plot(
            x[with_mass],
            values[with_mass],
            color=color,
            marker=str(style.get("marker", "o")),
            label=str(style.get("label", support)),
            linestyle="-",
            markersize=4,
        )
        if f"{metric}_p05" in metrics:  # a sweep with an uncertainty: its 5-95 % band
            low = metrics[f"{metric}_p05"].sel(support=support).values
            high = metrics[f"{metric}_p95"].sel(support=support).values
            ax.fill_between(
                x[with_mass], low[with_mass], high[with_mass], color=color, alpha=0.2, lw=0
            )
        for level in np.unique(values[without]):
            ax.axhline(level, color=color, linestyle=":", linewidth=1.0)
    if f"{metric}_p05" in metrics:
        ax.fill_between([], [], [], color="0.4", alpha=0.2, lw=0, label="5-95 % band")
    if without.any():
        what = variable.replace("_", " ")
        ax.plot([], [], color="0.4", linestyle=":", linewidth=1.0, label=f"without the {what}")
    if clock:
        ticks = np.unique(x[with_mass])
        ax.set_xticks(ticks, [f"{12 if t == 0 else t:g}" for t in ticks])
    ax.set_xlabel(label)
    speeds = f"{metrics.attrs['ball_speed_mps']:g} m/s ball"
    if metrics.attrs["racket_speed_mps"]:
        speeds += f", {metrics.attrs['racket_speed_mps']:g} m/s racket"
    if metric == "centre_rebound_ratio":
        ax.set_ylabel("rebound ratio e at centre (–)")
        ax.set_title(f"face centre, {speeds}", fontsize=9)
    else:
        ax.set_ylabel("sweet area (cm²)")
        fraction = metrics.attrs["threshold_fraction"]
        ax.set_title(f"e ≥ {fraction:g} × the face's best, {speeds}", fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_centre_rebound(
    dataset: xr.Dataset,
    variable: str,
    ax: Axes | None = None,
    ball_speed: float | None = None,
    racket_speed: float | None = None,
) -> Axes:
    """Rebound ratio at the face centre against a variable, one line per support (with an
    uncertainty, its 5-95 % band shaded: ``centre_rebound_ratio_p05/_p95``).

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset.
    variable : str
        The variable (designs from :func:`variable_designs`).
    ax : matplotlib Axes, optional
        Where to draw (a new figure if None).
    ball_speed, racket_speed : float, optional
        Speeds, m/s (default the spec's summary speeds).
    """
    return _plot_metric(
        dataset, variable, "centre_rebound_ratio", ax, None, ball_speed, racket_speed
    )


def plot_sweet_area(
    dataset: xr.Dataset,
    variable: str,
    ax: Axes | None = None,
    threshold_fraction: float | None = None,
    ball_speed: float | None = None,
    racket_speed: float | None = None,
) -> Axes:
    """The sweet area against a variable, per support (with an uncertainty, its 5-95 % band
    shaded where given: ``sweet_area_cm2_p05/_p95``).

    The area of each design's face whose rebound ratio is near the best of that face
    (:func:`racketdyn.sweep.sweet_area_cm2`): the numbers of ``summary.csv``.

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset.
    variable : str
        The variable (designs from :func:`variable_designs`).
    ax : matplotlib Axes, optional
        Where to draw (a new figure if None).
    threshold_fraction : float, optional
        Fraction of each face's best rebound ratio (default the spec's).
    ball_speed, racket_speed : float, optional
        Speeds, m/s (default the spec's summary speeds).
    """
    return _plot_metric(
        dataset, variable, "sweet_area_cm2", ax, threshold_fraction, ball_speed, racket_speed
    )


def write_summary_figures(dataset: xr.Dataset, out_dir: Path | str) -> list[Path]:
    """Write ``summary_<variable>.png``: centre rebound and sweet area against each variable.

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset.
    out_dir : path-like
        Output folder.

    Returns
    -------
    list of Path
        The files written.
    """
    out = Path(out_dir)
    written = []
    for variable in _variables(dataset):
        figure, (left, right) = plt.subplots(1, 2, figsize=(9.0, 3.6), layout="constrained")
        plot_centre_rebound(dataset, variable, ax=left)
        plot_sweet_area(dataset, variable, ax=right)
        label = axis_label(dataset, variable)[1]  # "tension (N)", never the key "tension_n"
        figure.suptitle(f"{dataset.attrs['title']}: {label}", fontsize=10)
        path = out / entry("summary").file_for(variable)
        save_figure(figure, path)
        written.append(path)
    return written
