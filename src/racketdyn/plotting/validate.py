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
from numpy.typing import ArrayLike

from racketdyn.plotting.primitives import plot_outline
from racketdyn.plotting.registry import draw, file_of, for_step
from racketdyn.plotting.render import save_figure

if TYPE_CHECKING:
    from racketdyn.io.measured import MeasuredRebound
    from racketdyn.racket import Racket
    from racketdyn.workflows.validate import ValidateResult

__all__ = [
    "VALIDATION_ALONG_FIGURE",
    "VALIDATION_PARITY_FIGURE",
    "VALIDATION_RESIDUAL_FIGURE",
    "figure_validation_along_axis",
    "figure_validation_parity",
    "figure_validation_residuals",
    "plot_parity",
    "write_validate_figures",
]

VALIDATION_PARITY_FIGURE = file_of("validation_parity")
"""Predicted against measured rebound ratio, both models, with the 1:1 line."""
VALIDATION_ALONG_FIGURE = file_of("validation_along_axis")
"""Measured and predicted rebound ratio against the position along the long axis."""
VALIDATION_RESIDUAL_FIGURE = file_of("validation_residuals")
"""The transient model's residual (predicted − measured) over the face."""

METHOD_STYLE = {
    "approx": {"color": "tab:blue", "marker": "o", "label": "approximate method"},
    "transient": {"color": "tab:red", "marker": "s", "label": "transient simulation"},
}

Predicted = Mapping[str, ArrayLike]
"""Each model's rebound ratio at the measured rows."""

SUPPORT_MARKER = {"free": "o", "pinned": "s", "hand": "^"}
"""Marker of each support in the residual map (rows at one point overlap otherwise)."""


def _flagged(predicted: ArrayLike) -> int:
    return int(np.count_nonzero(~np.isfinite(np.asarray(predicted, dtype=float))))


def plot_parity(
    measured: ArrayLike,
    predicted: dict[str, ArrayLike],
    ax: Axes | None = None,
) -> Axes:
    """Predicted against measured rebound ratio with the 1:1 line.

    Parameters
    ----------
    measured : array_like
        Measured rebound ratios, dimensionless.
    predicted : dict of str to array_like
        Per model (``approx``, ``transient``): predicted ratios (NaN: flagged, not drawn).
    ax : Axes, optional
        Where to draw.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(4.6, 4.2))
    e = np.asarray(measured, dtype=float)
    finite = [e]
    for method, values in predicted.items():
        p = np.asarray(values, dtype=float)
        style: dict[str, Any] = dict(METHOD_STYLE.get(method, {"label": method}))
        style["label"] = (
            f"{style['label']} ({_flagged(p)} flagged)" if _flagged(p) else style["label"]
        )
        ax.scatter(e, p, s=22, alpha=0.8, **style)
        finite.append(p[np.isfinite(p)])
    values = np.concatenate(finite)
    low, high = float(np.min(values)), float(np.max(values))
    pad = 0.05 * max(high - low, 0.01)
    ax.plot([low - pad, high + pad], [low - pad, high + pad], color="0.4", lw=1, label="1:1")
    ax.set_xlabel("measured rebound ratio")
    ax.set_ylabel("predicted rebound ratio")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(fontsize=8)
    return ax


def figure_validation_parity(measured: MeasuredRebound, predicted: Predicted) -> Figure:
    """Predicted against measured rebound ratio, both models, with the 1:1 line.

    Parameters
    ----------
    measured : MeasuredRebound
        The measured rows.
    predicted : mapping of str to array
        Each model's rebound ratio at the rows.
    """
    ax = plot_parity(measured.rebound_ratio, dict(predicted))
    ax.set_title("Predicted against measured rebound ratio", fontsize=10)
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
