"""Figures of ``racketdyn validate``: predicted against measured rebound (issue 15).

The predictions come from :mod:`racketdyn.workflows.validate`; this module only draws them.
Flagged rows (NaN) are left out of every figure and counted in its title.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from numpy.typing import ArrayLike, NDArray

from racketdyn.impact.measured import OUTLIER_LIMIT
from racketdyn.plotting.primitives import plot_outline
from racketdyn.plotting.registry import draw, file_of, for_step
from racketdyn.plotting.render import save_figure

if TYPE_CHECKING:
    from racketdyn.io.measured import MeasuredRebound
    from racketdyn.racket import Racket
    from racketdyn.workflows.calibrate import CalibrateResult
    from racketdyn.workflows.validate import ValidateResult

__all__ = [
    "CALIBRATION_PARITY_FIGURE",
    "MAX_LABELLED",
    "VALIDATION_ALONG_FIGURE",
    "VALIDATION_PARITY_FIGURE",
    "VALIDATION_RESIDUAL_FIGURE",
    "figure_calibration_parity",
    "figure_validation_along_axis",
    "figure_validation_parity",
    "figure_validation_residuals",
    "plot_parity",
    "write_calibrate_figures",
    "write_validate_figures",
]

VALIDATION_PARITY_FIGURE = file_of("validation_parity")
"""Predicted against measured rebound ratio, both models, with the 1:1 line."""
CALIBRATION_PARITY_FIGURE = file_of("calibration_parity")
"""The rebound ratio before and after a calibration against the measured."""
VALIDATION_ALONG_FIGURE = file_of("validation_along_axis")
"""Measured and predicted rebound ratio against the position along the long axis."""
VALIDATION_RESIDUAL_FIGURE = file_of("validation_residuals")
"""The transient model's residual (predicted − measured) over the face."""

METHOD_STYLE = {
    "approx": {"color": "tab:blue", "marker": "o", "label": "approximate method"},
    "transient": {"color": "tab:red", "marker": "s", "label": "transient simulation"},
    "before": {"color": "0.55", "marker": "o", "label": "before calibration"},
    "after": {"color": "tab:red", "marker": "s", "label": "after calibration"},
}

Predicted = Mapping[str, ArrayLike]
"""Each model's rebound ratio at the measured rows."""

SUPPORT_MARKER = {"free": "o", "pinned": "s", "hand": "^"}
"""Marker of each support in the residual map (rows at one point overlap otherwise)."""


def _flagged(predicted: ArrayLike) -> int:
    return int(np.count_nonzero(~np.isfinite(np.asarray(predicted, dtype=float))))


MAX_LABELLED = 8
"""Outliers named on a parity figure per model, the worst first (the rest are counted)."""


def plot_parity(
    measured: MeasuredRebound,
    predicted: Predicted,
    outlier_rank: Predicted | None = None,
    ax: Axes | None = None,
) -> Axes:
    """Predicted against measured rebound ratio with the 1:1 line, the measured standard
    deviations as horizontal error bars and the outliers named.

    Parameters
    ----------
    measured : MeasuredRebound
        The measured rows (ratio, standard deviation where measured, labels).
    predicted : mapping of str to array_like
        Per model or role (``approx``, ``transient``; ``before``, ``fitted``, ``held out``): the
        predicted ratio at every row (NaN: flagged or not this role's row, not drawn).
    outlier_rank : mapping of str to array_like, optional
        Per model or role: each row's rank among the outliers, rows whose residual is beyond
        ± :data:`racketdyn.impact.measured.OUTLIER_LIMIT` standard deviations (1 the worst; 0
        not one; :func:`racketdyn.impact.measured.outlier_rank`); they are named, at most
        :data:`MAX_LABELLED` per model.
    ax : Axes, optional
        Where to draw.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(4.8, 4.4))
    e = measured.rebound_ratio
    sd = measured.rebound_ratio_sd
    finite = [e]
    for method, values in predicted.items():
        p = np.asarray(values, dtype=float)
        style: dict[str, Any] = dict(METHOD_STYLE.get(method, {"label": method}))
        rank = None if outlier_rank is None else outlier_rank.get(method)
        rank = None if rank is None else np.asarray(rank).astype(int)
        words = _legend_words(p, rank)
        style["label"] = f"{style['label']} ({words})" if words else style["label"]
        drawn = np.isfinite(p)
        if sd is not None and np.any(drawn):
            ax.errorbar(e[drawn], p[drawn], xerr=sd[drawn], fmt="none", lw=0.8, alpha=0.6,
                        ecolor=style.get("color", "0.3"))  # fmt: skip
        ax.scatter(e, p, s=22, alpha=0.8, **style)
        if rank is not None:
            _name_outliers(ax, measured, p, rank, style.get("color", "k"))
        finite.append(p[drawn])
    values = np.concatenate(finite)
    low, high = float(np.min(values)), float(np.max(values))
    pad = 0.05 * max(high - low, 0.01)
    ax.plot([low - pad, high + pad], [low - pad, high + pad], color="0.4", lw=1, label="1:1")
    ax.set_xlabel("measured rebound ratio" + ("" if sd is None else " (± 1 standard deviation)"))
    ax.set_ylabel("predicted rebound ratio")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(fontsize=7)
    return ax


def _legend_words(p: NDArray[np.float64], rank: NDArray[np.int_] | None) -> str:
    """The legend's count of flagged rows and of outliers, e.g. "2 flagged, 3 beyond ±3σ"."""
    words = []
    if _flagged(p):
        words.append(f"{_flagged(p)} flagged")
    n = 0 if rank is None else int(np.count_nonzero(rank))
    if n:
        shown = "" if n <= MAX_LABELLED else f", {MAX_LABELLED} worst named"
        words.append(f"{n} beyond ±{OUTLIER_LIMIT:g}σ{shown}")
    return ", ".join(words)


def _name_outliers(
    ax: Axes, measured: MeasuredRebound, p: NDArray[np.float64], rank: NDArray[np.int_], color: str
) -> None:
    """Write each outlier's name beside its marker, the worst :data:`MAX_LABELLED`."""
    for i in np.flatnonzero((rank > 0) & (rank <= MAX_LABELLED)):
        ax.annotate(measured.row_label(int(i)), (measured.rebound_ratio[i], p[i]), xytext=(4, 3),
                    textcoords="offset points", fontsize=7, color=color)  # fmt: skip


def figure_validation_parity(
    measured: MeasuredRebound, predicted: Predicted, outlier_rank: Predicted
) -> Figure:
    """Predicted against measured rebound ratio, both models, with the 1:1 line.

    Parameters
    ----------
    measured : MeasuredRebound
        The measured rows.
    predicted : mapping of str to array
        Each model's rebound ratio at the rows.
    outlier_rank : mapping of str to array
        Each model's outliers' ranks (:func:`plot_parity`; they are named).
    """
    ax = plot_parity(measured, predicted, outlier_rank)
    return _titled(ax, "Predicted against measured rebound ratio")


def figure_calibration_parity(
    measured: MeasuredRebound, predicted: Predicted, outlier_rank: Predicted, held_out: ArrayLike
) -> Figure:
    """The rebound ratio before and after a calibration against the measured.

    Parameters
    ----------
    measured : MeasuredRebound
        The measured rows.
    predicted : mapping of str to array
        ``before`` and ``after``: the rebound ratio at every row.
    outlier_rank : mapping of str to array
        ``after``: the outliers' ranks after the fit (:func:`plot_parity`; they are named).
    held_out : array_like of bool
        The rows held out of the fit (ringed).
    """
    ax = plot_parity(measured, predicted, outlier_rank)
    held = np.asarray(held_out, dtype=bool)
    after = np.asarray(predicted["after"], dtype=float)
    if np.any(held & np.isfinite(after)):
        ax.scatter(measured.rebound_ratio[held], after[held], s=90, facecolors="none",
                   edgecolors="k", linewidths=0.8, label="held out of the fit")  # fmt: skip
        ax.legend(fontsize=7)
    return _titled(ax, "Rebound ratio before and after calibration")


def _titled(ax: Axes, title: str) -> Figure:
    """The figure of a one-panel parity plot, titled."""
    ax.set_title(title, fontsize=10)
    figure = ax.get_figure()
    assert isinstance(figure, Figure)
    return figure


def figure_validation_along_axis(measured: MeasuredRebound, predicted: Predicted) -> Figure:
    """Measured (± 1 sd) and predicted rebound ratio against x along the long axis.

    Parameters
    ----------
    measured, predicted
        As for :func:`figure_validation_parity`.
    """
    rows = measured
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    x_mm = rows.locations[:, 0] * 1e3
    ax.errorbar(
        x_mm,
        rows.rebound_ratio,
        yerr=None if rows.rebound_ratio_sd is None else rows.rebound_ratio_sd,
        fmt="k^",
        ms=5,
        label="measured",
    )
    for method, values in predicted.items():
        style = METHOD_STYLE[method]
        ax.scatter(x_mm, values, s=18, facecolors="none", edgecolors=style["color"],
                   marker=style["marker"], label=style["label"])  # fmt: skip
    ax.set_xlabel("x along the long axis from the butt (mm)")
    ax.set_ylabel("rebound ratio")
    ax.set_title("Measured and predicted along the axis (all rows)", fontsize=10)
    ax.legend(fontsize=8)
    return fig


def figure_validation_residuals(
    measured: MeasuredRebound, predicted: Predicted, racket: Racket
) -> Figure:
    """The transient simulation's residual over the face; flagged rows as crosses.

    Parameters
    ----------
    measured, predicted
        As for :func:`figure_validation_parity` (``predicted["transient"]`` drawn).
    racket : Racket
        The racket of the predictions (its outline; ``ModelInputs.effective_racket``).
    """
    rows = measured
    fig, ax = plt.subplots(figsize=(6.0, 3.8))
    plot_outline(racket, ax=ax)
    residual = np.asarray(predicted["transient"]) - rows.rebound_ratio
    ok = np.isfinite(residual)
    limit = float(np.max(np.abs(residual[ok]))) if np.any(ok) else 1.0
    support = np.asarray(rows.support)
    points = None
    for name, marker in SUPPORT_MARKER.items():
        here = ok & (support == name)
        if not np.any(here):
            continue
        points = ax.scatter(
            rows.locations[here, 0] * 1e3,
            rows.locations[here, 1] * 1e3,
            c=residual[here],
            cmap="coolwarm",
            vmin=-limit,
            vmax=limit,
            s=60 if marker == "o" else 40,
            marker=marker,
            edgecolors="k",
            linewidths=0.5,
            label=name,
        )
    if not np.all(ok):
        ax.scatter(rows.locations[~ok, 0] * 1e3, rows.locations[~ok, 1] * 1e3, marker="x",
                   c="k", label=f"flagged ({int((~ok).sum())})")  # fmt: skip
    if points is not None:
        fig.colorbar(points, ax=ax, label="predicted − measured rebound ratio")
    ax.legend(fontsize=8, loc="upper left")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title("Residual of the transient simulation", fontsize=10)
    return fig


def write_validate_figures(result: ValidateResult, out: Path) -> list[Path]:
    """The registry's figures of a validate run (parity, along the axis, residuals), drawn one
    after another in this process."""
    paths = [
        save_figure(draw(figure.id, result), Path(out) / figure.file)
        for figure in for_step("validate")
    ]
    return paths


def write_calibrate_figures(result: CalibrateResult, out: Path) -> list[Path]:
    """The registry's figure of a calibrate run (before and after against measured)."""
    return [
        save_figure(draw(figure.id, result), Path(out) / figure.file)
        for figure in for_step("calibrate")
    ]
