"""Plot primitives: each takes ``ax=`` (a new figure if None), draws, and returns the axes.

Styles are applied inside the functions, never at import.  Units on every axis label.
"""

from __future__ import annotations

import textwrap
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import matplotlib

matplotlib.use("Agg")  # files only: racketdyn draws figures for reports, not windows
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Ellipse
from matplotlib.tri import Triangulation
from numpy.typing import ArrayLike, NDArray

from racketdyn._display import case_words
from racketdyn.errors import InputError
from racketdyn.impact.result import STATUS_OK, ImpactResult
from racketdyn.impact.swing import SweetSpot, SwingResult
from racketdyn.measurement.pulse import ContactTimes
from racketdyn.measurement.records import FRF_UNITS, FrfSet, SummedFrf
from racketdyn.modal.poles import PoleStability, SelectedPoles, Stabilisation
from racketdyn.numerics import spans_a_surface
from racketdyn.racket import SUPPORT_NAMES, HeadEllipse, Racket
from racketdyn.workflows.figure_data import AxisBand, FrameVibration, ImpactCurves
from racketdyn.workflows.shape_figures import ModeShapes

if TYPE_CHECKING:  # drawn, not made here; their modules import the transient model and numba
    from racketdyn.impact.oblique import ObliqueCurve
    from racketdyn.impact.twist import TwistCurve

__all__ = [
    "FLAGGED_STYLE",
    "OBLIQUE_QUANTITIES",
    "QUANTITIES",
    "SWEET_SPOT_STYLE",
    "TWIST_QUANTITIES",
    "axes_grid",
    "label_contours_in_head",
    "label_lines",
    "label_rows",
    "mark_flagged_spans",
    "plot_along_axis",
    "plot_contact_map",
    "plot_face_map",
    "plot_frame_amplitude",
    "plot_frf",
    "plot_mac",
    "plot_mode_3d",
    "plot_node_lines",
    "plot_oblique_curve",
    "plot_outline",
    "plot_speed_curves",
    "plot_stabilisation",
    "plot_swing_along_axis",
    "plot_swing_map",
    "plot_twist_curve",
]

QUANTITIES: dict[str, tuple[str, float]] = {
    "mean_force": ("equivalent force F_MEAN (N)", 1.0),
    "peak_force": ("peak force F_MAX (N)", 1.0),
    "contact_time": ("contact time T_c (ms)", 1e3),
    "rebound_ratio": ("rebound ratio e (–)", 1.0),
    "cor": ("ball–racket COR e_r (–)", 1.0),
    "vibration_energy": ("vibration energy (J)", 1.0),
    "rebound_speed": ("rebound ball speed (m/s)", 1.0),
    "reduced_mass": ("reduced mass M_r (g)", 1e3),
    "rebound_ratio_band_width": ("width of the rebound ratio's 90 % band (–)", 1.0),
}
SUPPORT_STYLE = {
    "pinned": {"color": "k", "marker": "s", "label": SUPPORT_NAMES["pinned"]},
    "free": {"color": "tab:blue", "marker": "D", "label": SUPPORT_NAMES["free"]},
}


def _axes(ax: Axes | None, size: tuple[float, float] = (5.0, 3.6)) -> Axes:
    if ax is None:
        _, ax = plt.subplots(figsize=size, layout="constrained")
    return ax


def axes_grid(
    axes: Sequence[Axes] | None, rows: int, columns: int, **subplots: Any
) -> tuple[Figure, Any]:
    """The figure and axes a figure of several panels draws into: new ones, or the caller's.

    Parameters
    ----------
    axes : sequence of Axes or None
        The caller's axes, ``rows × columns`` of them in row order (a grid from
        :func:`matplotlib.pyplot.subplots` too): their figure, size, layout and shared axes are
        the caller's.  None: a new figure, ``plt.subplots(rows, columns, **subplots)``.
    rows, columns : int
        The panels.
    **subplots
        :func:`matplotlib.pyplot.subplots`'s options of a new figure (``figsize``, ``layout``,
        ``sharey``, ``squeeze``, …).

    Returns
    -------
    (Figure, Axes or ndarray of Axes)
        The figure (the caller's axes' own) and the axes shaped as ``plt.subplots`` shapes them
        (``squeeze``).

    Raises
    ------
    InputError
        ``axes`` is not ``rows × columns`` matplotlib Axes.
    """
    if axes is None:
        return plt.subplots(rows, columns, **subplots)
    given = list(np.ravel(np.asarray(axes, dtype=object)))
    if len(given) != rows * columns:
        raise InputError(
            f"`axes` takes {rows * columns} matplotlib Axes ({rows} × {columns}) for this "
            f"figure, got {len(given)}"
        )
    if not all(isinstance(a, Axes) for a in given):
        kinds = sorted({type(a).__name__ for a in given if not isinstance(a, Axes)})
        raise InputError(f"`axes` takes matplotlib Axes, got {', '.join(kinds)}")
    figure = given[0].get_figure(root=True)
    if not isinstance(figure, Figure):
        raise InputError("`axes` must belong to a matplotlib figure")
    grid = np.empty((rows, columns), dtype=object)
    grid.flat[:] = given
    if not subplots.get("squeeze", True):
        return figure, grid
    return figure, grid.item() if grid.size == 1 else grid.squeeze()


def _values(result: ImpactResult | ImpactCurves, quantity: str) -> NDArray[np.float64]:
    scale = QUANTITIES[quantity][1]
    values = np.asarray(getattr(result, quantity), dtype=float)
    if values.ndim == 2:  # reduced mass: (n, p) -> (n, s, p)
        values = np.broadcast_to(values[:, None, :], result.shape)
    return values * scale


FLAGGED_STYLE: dict[str, Any] = {
    "facecolor": "0.85",
    "edgecolor": "0.55",
    "hatch": "///",
    "linewidth": 0.0,
}
"""How figures mark where rows are flagged (their status not ``ok``): grey, hatched."""


def _runs(mask: NDArray[np.bool_]) -> list[tuple[int, int]]:
    """(first, last) index of each run of True in a 1-D mask."""
    edges = np.diff(np.concatenate([[0], mask.astype(int), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1, strict=True))


def mark_flagged_spans(
    ax: Axes, x: NDArray[np.float64], flagged: NDArray[np.bool_], what: str, total: int
) -> None:
    """Hatch the stretches of the x axis where rows are flagged and say how many.

    Where every curve is flagged the hatching fills the axes' height (nothing valid there);
    where only some are, it is a strip along the foot, so the valid curves stay in the clear.

    Parameters
    ----------
    ax : Axes
        Axes with x in the same units as ``x``.
    x : ndarray (n,)
        Sorted x values of the rows (speeds, positions).
    flagged : ndarray of bool, shape (n, k)
        Which of the ``k`` curves' rows are flagged at each x.
    what : str
        What a row is, in the legend ("impacts").
    total : int
        Rows of the curves in all, for "N of these curves' M" (the figure's own rows, which
        a sweep over speed makes other than the run's).
    """
    flagged = np.asarray(flagged, dtype=bool).reshape(len(x), -1)
    anywhere = np.asarray(flagged.any(axis=1), dtype=bool)
    if not anywhere.any():
        return
    everywhere = np.asarray(flagged.all(axis=1), dtype=bool)
    edges = np.concatenate([[x[0]], 0.5 * (x[1:] + x[:-1]), [x[-1]]])
    width = 0.01 * float(np.ptp(x) or 1.0)
    # the curves' own rows (a figure's sweep over speed is not the run's impacts: the trial of
    # 2026-11-27 read "86 of 276" against the console's 142 of the run's 276)
    count = f"{int(flagged.sum())} of these curves' {total} {what}"
    label = f"flagged, no valid value: {count} (hatched)"
    for mask, top in ((anywhere & ~everywhere, 0.06), (everywhere, 1.0)):
        for first, last in _runs(mask):
            low, high = float(edges[first]), float(edges[last + 1])
            if high - low < 2 * width:  # a single row at an end: give it a visible width
                low, high = low - width, high + width
            ax.axvspan(low, high, ymin=0.0, ymax=top, zorder=0, label=label, **FLAGGED_STYLE)
            label = "_flagged"


def plot_speed_curves(
    result: ImpactResult | ImpactCurves,
    quantity: str,
    point_names: Sequence[str],
    ax: Axes | None = None,
) -> Axes:
    """A quantity against incoming ball speed for each impact point and support (Figs 11–12).

    Rows whose status is not ``ok`` have no value: their curve breaks there, a cross in its
    colour at the foot of the axes marks each, the speeds are hatched and the legend says how
    many (issue 13)."""
    ax = _axes(ax)
    values = _values(result, quantity)
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.85, len(point_names)))
    foot = ax.get_xaxis_transform()
    flagged = np.asarray(result.status) != STATUS_OK  # (n, s, p)
    for i, (name, colour) in enumerate(zip(point_names, colours, strict=True)):
        for p, support in enumerate(result.supports):
            style = "-" if support == "pinned" else "--"
            ax.plot(
                result.ball_speed,
                np.where(flagged[i, :, p], np.nan, values[i, :, p]),
                color=colour,
                linestyle=style,
                label=f"{name}, {SUPPORT_STYLE[support]['label']}",
            )
            if flagged[i, :, p].any():
                ax.plot(
                    result.ball_speed[flagged[i, :, p]],
                    np.full(int(flagged[i, :, p].sum()), 0.03),
                    "x",
                    color=colour,
                    transform=foot,
                    clip_on=False,
                    label="_flagged rows",
                )
    order = np.argsort(result.ball_speed)
    mark_flagged_spans(
        ax,
        result.ball_speed[order],
        flagged[: len(point_names)][:, order, :].transpose(1, 0, 2),
        "impacts",
        len(point_names) * result.ball_speed.size * len(result.supports),
    )
    ax.set_xlabel("incoming ball speed (m/s)")
    ax.set_ylabel(QUANTITIES[quantity][0])
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return ax


def plot_frame_amplitude(
    vibration: FrameVibration,
    support: str = "pinned",
    ax: Axes | None = None,
) -> Axes:
    """Displacement amplitude of one mode along the frame after an impact (Fig. 14), mm.

    Impacts without a valid result (their ``status``) are not drawn: the legend names each
    with its reason, the panel says how many and is hatched when none is valid (issue 13).

    Parameters
    ----------
    vibration : FrameVibration
        The amplitudes along the frame
        (:meth:`racketdyn.workflows.figure_data.FrameVibration.of`).
    support : str
        Which support's impacts.
    ax : Axes, optional
        Where to draw (a new figure if None).
    """
    ax = _axes(ax)
    response_x_m = vibration.response_x
    p = vibration.supports.index(support)
    flagged = []
    for s, speed in enumerate(vibration.ball_speed):
        status = str(vibration.status[s, p])
        if status == STATUS_OK:
            ax.plot(response_x_m * 1e3, vibration.amplitude[:, s, p] * 1e3, label=f"{speed:g} m/s")
        else:  # no curve: the method gives no pulse here (issue 13); the legend says why
            flagged.append(s)
            ax.plot([], [], " ", label=f"{speed:g} m/s: flagged, not drawn ({status})")
    if flagged:
        count = len(flagged)
        if count == vibration.ball_speed.size:  # nothing valid in the panel: grey it all
            ax.axvspan(response_x_m[0] * 1e3, response_x_m[-1] * 1e3, zorder=0, **FLAGGED_STYLE)
    ax.axhline(0.0, color="0.5", linewidth=0.8)
    ax.axvline(vibration.location[0] * 1e3, color="r", linestyle=":", label="impact point")
    note = (
        f"\n{len(flagged)} of {vibration.ball_speed.size} speeds flagged: no valid vibration"
        if flagged
        else ""
    )
    ax.set_title(f"{SUPPORT_STYLE[support]['label']}: {vibration.mode_name}{note}", fontsize=9)
    ax.set_xlabel("x from the butt (mm)")
    ax.set_ylabel("displacement amplitude (mm)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return ax


def label_lines(
    ax: Axes,
    marks: Sequence[tuple[float, str, str]],
    fontsize: float = 7,
    **style: Any,
) -> Axes:
    """Vertical lines at ``x`` with their labels above the axes, out of the data's way.

    The labels are the tick labels of a secondary x axis on top (matplotlib places the title
    above them and the constrained layout makes room), written across, each centred over its
    line and in its colour.  A label that would overlap the one before it goes up a row (a
    larger tick pad): rows of text, not the tall strip that upright labels made (Fig. 15: a
    quarter of the figure for two labels).

    Parameters
    ----------
    ax : Axes
        The axes, its data drawn (its x limits set).
    marks : sequence of (float, str, str)
        ``(x, label, colour)`` of each line, x in data units.
    fontsize : float
        Of the labels, points.
    **style
        Of the lines (default dotted, 1 pt).

    Returns
    -------
    Axes
        The secondary axis that holds the labels.
    """
    line = {"linestyle": ":", "linewidth": 1.0, **style}
    for x, _, colour in marks:
        ax.axvline(x, color=colour, **line)
    low, high = ax.get_xlim()
    figure = ax.get_figure(root=True)
    assert isinstance(figure, Figure)
    # the axes' width once laid out (the layout engine run now, so the rows are judged on the
    # width the figure will have, not the width before layout: issue 22's membrane at 619 Hz
    # went a fourth row up on the narrower estimate), with a margin for what comes after
    engine = figure.get_layout_engine()
    if engine is not None:
        engine.execute(figure)
    width_pt = 0.95 * ax.get_position().width * figure.get_figwidth() * 72.0
    per_pt = abs(high - low) / width_pt
    # the identity as NumPy's own function: matplotlib's default is a lambda, which does not
    # pickle, and a figure that does not pickle cannot go to the figure helper process
    top: Any = ax.secondary_xaxis("top", functions=(np.asanyarray, np.asanyarray))
    top.set_xticks([x for x, _, _ in marks], [label for _, label, _ in marks], fontsize=fontsize)
    top.tick_params(length=0, pad=2)
    texts = top.get_xticklabels()
    points_per_px = 72.0 / figure.dpi
    rows = label_rows(
        [x for x, _, _ in marks],
        [t.get_window_extent().width * points_per_px * per_pt for t in texts],
        LABEL_SPACE * fontsize * per_pt,
    )
    for tick, text, row, (_, _, colour) in zip(
        top.xaxis.get_major_ticks(), texts, rows, marks, strict=True
    ):
        text.set_color(colour)
        tick.set_pad(2 + row * LABEL_ROW * fontsize)
    axes: Axes = top
    return axes


LABEL_SPACE = 1.0
"""Least space between two labels on one row, in font sizes."""
LABEL_ROW = 1.25
"""Height of a row of labels, in font sizes."""


def label_rows(centres: ArrayLike, widths: ArrayLike, space: float) -> list[int]:
    """The row (0 lowest) of each label centred at ``centres``, ``widths`` wide: the lowest
    row where it keeps ``space`` from the labels already there, taken from left to right.

    Parameters
    ----------
    centres, widths : array_like
        Each label's centre and width (any one unit).
    space : float
        Least gap between two labels on a row, same unit.
    """
    centre, width = np.asarray(centres, dtype=float), np.asarray(widths, dtype=float)
    ends: list[float] = []  # the right end of each row so far
    rows = [0] * centre.size
    for k in np.argsort(centre, kind="stable"):
        left = centre[k] - width[k] / 2
        row = next((r for r, end in enumerate(ends) if left >= end + space), len(ends))
        if row == len(ends):
            ends.append(0.0)
        ends[row] = centre[k] + width[k] / 2
        rows[k] = row
    return rows


def plot_along_axis(
    result: ImpactResult | ImpactCurves,
    quantity: str,
    speed_index: int = 0,
    ax: Axes | None = None,
    marks: dict[str, float] | None = None,
    band: AxisBand | None = None,
) -> Axes:
    """A quantity along the long axis of the face, one line per support (Fig. 15), with its
    90 % band shaded where an uncertainty gave one."""
    ax = _axes(ax)
    values = _values(result, quantity)
    x_mm = result.locations[:, 0] * 1e3
    flagged = np.asarray(result.status)[:, speed_index, :] != STATUS_OK  # (n, p)
    foot = ax.get_xaxis_transform()
    for p, support in enumerate(result.supports):
        style = SUPPORT_STYLE[support]
        if band is not None:
            ax.fill_between(
                x_mm,
                band.p05[:, p],
                band.p95[:, p],
                color=style["color"],
                alpha=0.18,
                linewidth=0,
                label=f"{style['label']}: 90 % band ({band.samples} samples)",
            )
        ax.plot(
            x_mm,
            np.where(flagged[:, p], np.nan, values[:, speed_index, p]),
            color=style["color"],
            marker=style["marker"],
            markersize=3,
            label=style["label"],
        )
        missing = flagged[:, p]
        if np.any(missing):  # at the foot of the axes: a cross at 0 would read as a value
            reasons = ", ".join(np.unique(result.status[missing, speed_index, p]))
            ax.plot(
                x_mm[missing],
                np.full(int(missing.sum()), 0.03),
                "x",
                color=style["color"],
                transform=foot,
                clip_on=False,
                # wrapped: the statuses' reasons run wider than the figure (issue 22's)
                label=textwrap.fill(f"{style['label']}: no valid value ({reasons})", 70),
            )
    order = np.argsort(x_mm)
    mark_flagged_spans(ax, x_mm[order], flagged[order], "points", flagged.size)
    if marks:
        label_lines(ax, [(x * 1e3, name, "0.3") for name, x in marks.items()])
    ax.set_xlabel("impact point, x from the butt (mm)")
    ax.set_ylabel(QUANTITIES[quantity][0])
    racket_speed = float(result.racket_speed[speed_index])
    moving = f"racket {racket_speed:g} m/s" if racket_speed else "racket at rest"
    ax.set_title(f"incoming ball {result.ball_speed[speed_index]:g} m/s, {moving}", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return ax


def _head(racket: Racket | HeadEllipse) -> HeadEllipse:
    return racket if isinstance(racket, HeadEllipse) else racket.head


def plot_outline(racket: Racket | HeadEllipse, ax: Axes | None = None, **style: Any) -> Axes:
    """The string-bed ellipse and the long axis (x, y in mm) of a racket or its head."""
    ax = _axes(ax)
    head = _head(racket)
    ax.add_patch(
        Ellipse(
            (head.centre_x_m * 1e3, head.centre_y_m * 1e3),
            2e3 * head.half_length_m,
            2e3 * head.half_width_m,
            fill=False,
            color=style.get("color", "k"),
            linewidth=style.get("linewidth", 1.5),
        )
    )
    ax.set_aspect("equal")
    return ax


def _contour_face(
    ax: Axes, racket: Racket | HeadEllipse, locations: NDArray[np.float64],
    values: NDArray[np.float64], *, label: str, levels: int,
) -> bool:  # fmt: skip
    """Filled, labelled contours of values at face points (mm), a colour bar and the head's
    outline, the points themselves as dots; where the valid points span no surface (fewer than
    three, on a line, or one value everywhere) the points coloured by value instead.  Points
    with no valid value marked with red crosses.  The contour labels one per level, inside the
    head and apart (:func:`label_contours_in_head`).  Returns whether any were marked."""
    x_mm, y_mm = locations[:, 0] * 1e3, locations[:, 1] * 1e3
    finite = np.isfinite(values)
    lines = None
    surface = (
        finite.sum() >= 3 and spans_a_surface(locations[finite]) and np.ptp(values[finite]) > 0
    )
    if surface:
        triangles = Triangulation(x_mm[finite], y_mm[finite])
        filled = ax.tricontourf(triangles, values[finite], levels=levels, cmap="viridis")
        lines = ax.tricontour(
            triangles, values[finite], levels=np.asarray(filled.levels), colors="k", linewidths=0.4
        )
        ax.figure.colorbar(filled, ax=ax, label=label, shrink=0.85)
        if finite.sum() <= 2000:
            ax.scatter(x_mm[finite], y_mm[finite], s=2, color="k", linewidths=0)
    elif finite.any():
        dots = ax.scatter(
            x_mm[finite], y_mm[finite], c=values[finite], cmap="viridis", s=30,
            edgecolors="k", linewidths=0.4,
        )  # fmt: skip
        ax.figure.colorbar(dots, ax=ax, label=label, shrink=0.85)
        if finite.sum() <= 30:
            for x, y, value in zip(x_mm[finite], y_mm[finite], values[finite], strict=True):
                ax.annotate(
                    f"{value:.3g}", (x, y), xytext=(3, 3), textcoords="offset points", fontsize=6
                )
    plot_outline(racket, ax)
    if lines is not None:
        label_contours_in_head(ax, lines, racket, "%.3g")
    if np.all(finite):
        return False
    count = int((~finite).sum())
    ax.plot(
        x_mm[~finite], y_mm[~finite], "x", color="r", markersize=4,
        label=f"no valid result at {count} point{'s' if count > 1 else ''} (see status)",
    )  # fmt: skip
    return True


def plot_face_map(
    result: ImpactResult | ImpactCurves,
    racket: Racket | HeadEllipse,
    quantity: str,
    speed_index: int = 0,
    support: str = "pinned",
    ax: Axes | None = None,
    levels: int = 12,
) -> Axes:
    """Contour map of a quantity over the string face (x along, y across, mm).

    Rows whose status is not ``ok`` are left out of the map in every quantity and marked with
    red crosses, their number in the legend (issue 13: no flagged row drawn as if valid).
    """
    ax = _axes(ax, (4.2, 3.6))
    column = result.support_index(support)
    values = _values(result, quantity)[:, speed_index, column]
    valid = np.asarray(result.status)[:, speed_index, column] == STATUS_OK
    values = np.where(valid, values, np.nan)
    if _contour_face(
        ax, racket, result.locations, values, label=QUANTITIES[quantity][0], levels=levels
    ):
        ax.legend(fontsize=7, loc="lower left")
    ax.set_xlabel("x from the butt (mm)")
    ax.set_ylabel("y (mm)")
    racket_speed = float(np.asarray(result.racket_speed, dtype=float)[speed_index])
    ax.set_title(
        f"{SUPPORT_STYLE[support]['label']}: "
        + case_words(float(result.ball_speed[speed_index]), racket_speed),
        fontsize=9,
    )
    return ax


def plot_frf(
    frfs: FrfSet, index: int, axes: Sequence[Axes] | None = None, label: str = ""
) -> Sequence[Axes]:
    """Magnitude (log), phase and coherence of one FRF on three stacked axes (paper, Figs 2–3)."""
    if axes is None:
        _, created = plt.subplots(
            3,
            1,
            figsize=(6, 6),
            sharex=True,
            layout="constrained",
            gridspec_kw={"height_ratios": [2, 1, 1]},
        )
        axes = list(created)
    magnitude, phase, coherence = axes
    values = frfs.values[index]
    magnitude.semilogy(frfs.frequency, np.abs(values), label=label or f"node {frfs.nodes[index]}")
    phase.plot(frfs.frequency, np.degrees(np.angle(values)))
    if frfs.coherence is not None:
        coherence.plot(frfs.frequency, frfs.coherence[index])
    magnitude.set_ylabel(f"|H| ({FRF_UNITS[frfs.frf_type]})")
    phase.set_ylabel("phase (°)")
    phase.set_yticks([-180, -90, 0, 90, 180])
    coherence.set_ylabel("coherence")
    coherence.set_ylim(0, 1.05)
    coherence.set_xlabel("frequency (Hz)")
    for ax in axes:
        ax.grid(alpha=0.3)
    magnitude.legend(fontsize=7)
    return axes


def plot_contact_map(
    times: ContactTimes,
    racket: Racket,
    ax: Axes | None = None,
    title: str = "",
    levels: NDArray[np.float64] | int = 10,
) -> Axes:
    """Contour map of the hammer contact time over the string face, ms (paper, Fig. 7)."""
    ax = _axes(ax, (4.2, 3.6))
    on_bed = racket.head.contains(times.locations) & np.isfinite(times.mean_s)
    x_mm, y_mm = times.locations[on_bed, 0] * 1e3, times.locations[on_bed, 1] * 1e3
    values = times.mean_s[on_bed] * 1e3
    lines = None
    if on_bed.sum() >= 3:
        triangles = Triangulation(x_mm, y_mm)
        filled = ax.tricontourf(triangles, values, levels=levels, cmap="magma")
        lines = ax.tricontour(
            triangles, values, levels=np.asarray(filled.levels), colors="k", linewidths=0.4
        )
        ax.figure.colorbar(filled, ax=ax, label="contact time (ms)", shrink=0.85, format="%.2f")
    ax.plot(x_mm, y_mm, ".", color="w", markersize=3)
    plot_outline(racket, ax)
    if lines is not None:
        label_contours_in_head(ax, lines, racket, "%.2f")
    ax.set_xlabel("x from the butt (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(title, fontsize=9)
    return ax


CONTOUR_LABEL_POINTS = 6.0
"""Font size of contour labels, points."""
_LABEL_ROOM = 1.4
"""Room kept around a contour label's estimated box: the constrained layout may shrink the axes
after the labels are placed (a colour bar, tick labels), which makes the labels larger in data
units."""


def label_contours_in_head(
    ax: Axes, lines: Any, racket: Racket | HeadEllipse, fmt: str
) -> list[float]:
    """Label each contour level once, inside the string bed and apart from the other labels.

    matplotlib's own placement put several labels on the same spot where the levels crowd
    (Fig. 7: at the ends of the head, where the contact time falls steeply) and some past the
    head's outline.  Here each level's label goes at the point of its contour nearest the
    head's upper-right diagonal whose label box (estimated from the font size, as wide as
    it is long in every direction, since an inline label turns with its line) lies inside the
    head and clear of the labels already placed; levels are taken from the innermost out.
    A level with no such point stays unlabelled (the colour bar still gives it).

    Parameters
    ----------
    ax : Axes
        The map, its outline drawn (limits set, aspect equal), x and y in mm.
    lines : matplotlib ContourSet
        The contour lines.
    racket : Racket or HeadEllipse
        Its head bounds the labels.
    fmt : str
        Format of a label's value (``"%.2f"``).

    Returns
    -------
    list of float
        The levels labelled.
    """
    head = _head(racket)
    centre = np.array([head.centre_x_m, head.centre_y_m]) * 1e3
    half = np.array([head.half_length_m, head.half_width_m]) * 1e3
    figure = ax.get_figure(root=True)
    assert isinstance(figure, Figure)
    box = ax.get_position()
    width_pt = box.width * figure.get_figwidth() * 72.0
    height_pt = box.height * figure.get_figheight() * 72.0
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    mm_per_pt = _LABEL_ROOM * max(abs(x1 - x0) / width_pt, abs(y1 - y0) / height_pt)
    placed: list[tuple[NDArray[np.float64], float]] = []  # (centre, half size), mm
    chosen: list[tuple[float, float]] = []
    levels: list[float] = []
    values = np.asarray(lines.levels, dtype=float)
    segments = [
        [np.asarray(seg, dtype=float) for seg in segs if len(seg)] for segs in lines.allsegs
    ]
    # innermost first: by the mean distance of the level's contour from the head's centre
    depth = np.array(
        [
            float(np.mean(np.hypot(*((np.vstack(level) - centre) / half).T))) if level else np.inf
            for level in segments
        ]
    )
    for k in np.argsort(depth, kind="stable"):
        half_size = 0.5 * mm_per_pt * CONTOUR_LABEL_POINTS * 0.62 * len(fmt % values[k])
        # only on a line longer than its label (the extreme levels' contours are mere dots)
        long = [seg for seg in segments[k] if np.ptp(seg, axis=0).max() > 2.0 * half_size]
        if not long:
            continue
        points = np.vstack(long)
        # the label's square box inside the head: its corners within the ellipse
        corners = points[:, None, :] + half_size * np.array(
            [[-1.0, -1.0], [-1.0, 1.0], [1.0, -1.0], [1.0, 1.0]]
        )
        rho = np.hypot(*((corners - centre) / half).transpose(2, 0, 1)).max(axis=1)
        fits = rho < 0.98
        for where, size in placed:
            fits &= np.max(np.abs(points - where), axis=1) > size + half_size
        if not np.any(fits):
            continue
        angle = np.arctan2(
            (points[:, 1] - centre[1]) / half[1], (points[:, 0] - centre[0]) / half[0]
        )
        preference = np.abs(np.angle(np.exp(1j * (angle - np.pi / 4))))
        best = int(np.argmin(np.where(fits, preference, np.inf)))
        placed.append((points[best], half_size))
        chosen.append((float(points[best, 0]), float(points[best, 1])))
        levels.append(float(values[k]))
    if chosen:
        ax.clabel(
            lines, levels=levels, manual=chosen, fontsize=CONTOUR_LABEL_POINTS, fmt=fmt,
            inline=True,
        )  # fmt: skip
    return levels


def _mode_title(shapes: ModeShapes, mode: int, decimals: int = 0) -> str:
    """The mode's name, with its frequency unless the name holds it ("mode 1 (100.0 Hz)")."""
    return shapes.title(mode, decimals)


def plot_node_lines(shapes: ModeShapes, mode: int, ax: Axes | None = None) -> Axes:
    """Sign of a mode shape over a surface, black and white, node lines between (paper, Fig. 5).

    Works for any structure, as :func:`racketdyn.workflows.shape_figures.mode_shapes` evaluated
    it: over a racket's string face with its outline, or over the convex hull of the model's
    points.  Points on one straight line (a beam) give the shape along the line with its nodes
    marked instead; points in space ``(x, y, z)``, the measured shape over their best-fit plane.

    Parameters
    ----------
    shapes : ModeShapes
        The modes evaluated where they are drawn.
    mode : int
        Index of the mode (0-based).
    ax : matplotlib Axes, optional
        Where to draw; a new figure if None.

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (3.2, 2.6))
    if shapes.layout_nodes == "line":
        along = shapes.nodes_along
        shape = shapes.nodes_line_shapes[mode]
        ax.plot(along * 1e3, shape, color="k")
        ax.axhline(0.0, color="0.5", linewidth=0.8)
        crossing = np.flatnonzero(np.sign(shape[:-1]) * np.sign(shape[1:]) < 0)
        nodes = along[crossing] - shape[crossing] * (along[crossing + 1] - along[crossing]) / (
            shape[crossing + 1] - shape[crossing]
        )
        ax.plot(nodes * 1e3, np.zeros_like(nodes), "o", color="tab:red", markersize=4)
        ax.set_xlabel("distance along the line (mm)")
        ax.set_title(_mode_title(shapes, mode), fontsize=8)
        return ax
    if shapes.layout_nodes == "space":
        # points in space: the measured shape over the points' best-fit plane
        plane = shapes.plane
        triangles = Triangulation(plane[:, 0] * 1e3, plane[:, 1] * 1e3)
        values = shapes.at_points[:, mode]
        span = float(np.abs(values).max()) + 1.0
        ax.tricontourf(triangles, values, levels=[-span, 0.0, span], colors=["k", "w"])
        ax.tricontour(triangles, values, levels=[0.0], colors="tab:red", linewidths=1.2)
        ax.plot(plane[:, 0] * 1e3, plane[:, 1] * 1e3, ".", color="0.5", markersize=2)
        ax.set_aspect("equal")
        ax.set_title(_mode_title(shapes, mode), fontsize=8)
        ax.set_xticks([])
        ax.set_yticks([])
        return ax
    x, y = shapes.nodes_x, shapes.nodes_y
    shape = shapes.nodes_surface[mode]
    ax.contourf(x * 1e3, y * 1e3, np.sign(shape), levels=[-1.5, 0.0, 1.5], colors=["k", "w"])
    ax.contour(x * 1e3, y * 1e3, shape, levels=[0.0], colors="tab:red", linewidths=1.2)
    ax.set_aspect("equal")
    ax.set_title(_mode_title(shapes, mode), fontsize=8)
    ax.set_xticks([])
    ax.set_yticks([])
    if shapes.head is not None:
        plot_outline(shapes.head, ax)
    return ax


def plot_mode_3d(shapes: ModeShapes, mode: int, ax: Axes | None = None) -> Axes:
    """A mode shape in 3-D (paper, Fig. 4): a surface, a line through it and the measured points.

    Works for any structure, as :func:`racketdyn.workflows.shape_figures.mode_shapes` evaluated
    it: a racket's shape over its string face and along its long axis, with a 100 mm scale bar;
    a surface over the convex hull of the model's points; points on one straight line (a beam),
    the shape along that line; points in space ``(x, y, z)`` where they are, coloured by shape.

    Parameters
    ----------
    shapes : ModeShapes
        The modes evaluated where they are drawn.
    mode : int
        Index of the mode (0-based).
    ax : 3-D matplotlib Axes, optional
        Where to draw; a new figure if None.

    Returns
    -------
    Axes
    """
    if ax is None:
        figure = plt.figure(figsize=(4.5, 3.2), layout="constrained")
        ax = figure.add_subplot(projection="3d")
    locations = shapes.locations
    ax3d: Any = ax  # a 3-D axes: matplotlib's stubs type it as plain Axes
    title = f"{_mode_title(shapes, mode, 1)}, ζ = {100 * shapes.damping_ratio[mode]:.2f} %"
    if shapes.layout_3d == "space":
        # points in space: each point coloured by its shape value (the measured direction's)
        values = shapes.at_points[:, mode]
        limit = max(float(np.abs(values).max()), 1e-12)
        ax3d.scatter(*locations.T, c=values, cmap="coolwarm", vmin=-limit, vmax=limit, s=12)
        ax.set_title(title, fontsize=8)
        extent = np.maximum(np.ptp(locations, axis=0), 1e-3 * np.ptp(locations, axis=0).max())
        ax3d.set_box_aspect(tuple(float(e) for e in extent))
        ax.set_axis_off()
        return ax
    scale = 0.08 / max(float(np.abs(shapes.at_points[:, mode]).max()), 1e-12)
    if shapes.layout_3d in ("racket", "surface"):
        shape = shapes.surface[mode] * scale
        ax3d.plot_surface(shapes.surface_x, shapes.surface_y, shape, cmap="coolwarm", linewidth=0)
    if shapes.line.size:
        line = shapes.line
        along = shapes.line_shapes[mode]
        ax3d.plot(line[:, 0], line[:, 1], along * scale, color="k")
        ax3d.plot(line[:, 0], line[:, 1], np.zeros(len(line)), color="0.6", linewidth=0.8)
    ax3d.scatter(
        locations[:, 0],
        locations[:, 1],
        shapes.at_points[:, mode] * scale,
        s=4,
        color="k",
    )
    ax.set_title(title, fontsize=8)
    extent = np.maximum(np.ptp(locations, axis=0), 1e-3 * np.ptp(locations, axis=0).max())
    ax3d.set_box_aspect((float(extent[0]), float(extent[1]), 0.2))
    ax3d.view_init(elev=25, azim=-60)
    ax.set_axis_off()
    if shapes.layout_3d == "racket" and shapes.head is not None:
        half_width = shapes.head.half_width_m
        ax3d.set_box_aspect((shapes.length_m, 2.4 * half_width, 0.2))
        # a scale: 100 mm along the long axis from the butt, beside the handle
        y_bar = -1.1 * half_width
        ax3d.plot([0.0, SCALE_BAR_M], [y_bar, y_bar], [0.0, 0.0], color="k", linewidth=2.5)
        ax3d.text(0.0, 1.6 * y_bar, 0.0, f"{SCALE_BAR_M * 1e3:.0f} mm", fontsize=7)
    return ax


SCALE_BAR_M = 0.1
"""Length of the scale bar of a racket's 3-D mode shapes, m."""


def plot_mac(
    matrix: NDArray[np.float64], rows: Sequence[str], columns: Sequence[str], ax: Axes | None = None
) -> Axes:
    """A MAC (or AutoMAC) matrix with its values."""
    ax = _axes(ax, (4.5, 3.8))
    image = ax.imshow(matrix, vmin=0.0, vmax=1.0, cmap="Greys")
    for (i, j), value in np.ndenumerate(matrix):
        ax.text(
            j,
            i,
            f"{value:.2f}",
            ha="center",
            va="center",
            fontsize=6,
            color="w" if value > 0.5 else "k",
        )
    ax.set_xticks(range(len(columns)), columns, rotation=60, ha="right", fontsize=7)
    ax.set_yticks(range(len(rows)), rows, fontsize=7)
    ax.figure.colorbar(image, ax=ax, label="MAC", shrink=0.8)
    return ax


SWEET_SPOT_STYLE: dict[str, dict[str, Any]] = {
    "centre_of_percussion_swing": {"marker": "o", "color": "tab:orange"},
    "centre_of_percussion_grip": {"marker": "s", "color": "tab:red"},
    "first_mode_node": {"marker": "^", "color": "w"},
    "max_rebound_ratio": {"marker": "D", "color": "tab:cyan"},
    "max_rebound_speed": {"marker": "*", "color": "magenta"},
}
"""Marker and colour of each sweet spot (keys of :func:`~racketdyn.impact.swing.sweet_spots`)."""


def _support_label(support: str) -> str:
    return str(SUPPORT_STYLE.get(support, {}).get("label", support))


def _mark_sweet_spots(ax: Axes, spots: Mapping[str, SweetSpot], in_plane: bool) -> None:
    """Sweet spots as markers on a face map (``in_plane``) or vertical lines on an x plot."""
    for key, spot in spots.items():
        style = SWEET_SPOT_STYLE.get(key, {"marker": "P", "color": "k"})
        text = f"{spot.name}: x = {spot.x_m * 1e3:.0f} mm"
        if not spot.on_face:
            text += " (off the face)"
        if in_plane:
            if spot.on_face:
                ax.plot(
                    spot.x_m * 1e3,
                    spot.y_m * 1e3,
                    linestyle="none",
                    marker=style["marker"],
                    markersize=9 if style["marker"] == "*" else 6,
                    markerfacecolor=style["color"],
                    markeredgecolor="k",
                    label=text,
                )
            else:
                ax.plot([], [], linestyle="none", marker="", label=text)
        else:
            ax.axvline(
                spot.x_m * 1e3,
                color="k" if style["color"] == "w" else style["color"],
                linestyle=":",
                linewidth=1.2,
                label=text,
            )


def plot_swing_map(
    result: SwingResult,
    racket: Racket,
    spots: Mapping[str, SweetSpot] | None = None,
    speed_index: int = 0,
    support: str | None = None,
    ax: Axes | None = None,
    levels: int = 12,
) -> Axes:
    """Contour map of the outgoing ball speed over the string face of a swinging racket.

    The look of :func:`plot_face_map` (x along, y across, mm), with the sweet spots of
    :func:`racketdyn.impact.swing.sweet_spots` marked and named (those off the face listed).

    Parameters
    ----------
    result : SwingResult
        Impacts over the face (:func:`racketdyn.impact.swing.predict_swing`).
    racket : Racket
        The racket, for its outline.
    spots : mapping of str to SweetSpot, optional
        Sweet spots to mark.
    speed_index : int
        Which incoming ball speed.
    support : str, optional
        Which support (default the result's first).
    ax : Axes, optional
        Where to draw (a new figure if None).
    levels : int
        Number of contour levels.
    """
    ax = _axes(ax, (5.2, 3.8))
    support = support or result.supports[0]
    column = result.support_index(support)
    flagged = np.asarray(result.status)[:, speed_index, column] != STATUS_OK
    values = np.where(flagged, np.nan, result.rebound_speed[:, speed_index, column])
    _contour_face(
        ax, racket, result.locations, values, label="outgoing ball speed (m/s)", levels=levels
    )
    if spots:
        _mark_sweet_spots(ax, spots, in_plane=True)
    entries = len(ax.get_legend_handles_labels()[1])
    if entries:
        # room below the face for the legend, inside the axes (so any layout keeps it)
        head = racket.head
        rows = (entries + 1) // 2
        bottom = (head.centre_y_m - head.half_width_m) * 1e3 - 14.0 * rows - 8.0
        ax.set_ylim(bottom, (head.centre_y_m + head.half_width_m) * 1e3 + 8.0)
        ax.legend(fontsize=6, loc="lower center", ncol=2, frameon=False, handletextpad=0.3)
    ax.set_xlabel("x from the butt (mm)")
    ax.set_ylabel("y (mm)")
    note = (
        f"\n{int(flagged.sum())} of {flagged.size} impacts flagged (crosses)"
        if flagged.any()
        else ""
    )
    ax.set_title(
        f"{_support_label(support)}, ball {result.ball_speed[speed_index]:g} m/s, "
        f"swing Ω = {result.angular_speed_radps:.1f} rad/s{note}",
        fontsize=9,
    )
    return ax


def plot_swing_along_axis(
    results: Sequence[SwingResult | ImpactCurves],
    spots: Mapping[str, SweetSpot] | None = None,
    support: str | None = None,
    ax: Axes | None = None,
    names: Sequence[str] | None = None,
) -> Axes:
    """Outgoing ball speed along the long axis (x) for a few swings and ball speeds.

    One line per result × incoming ball speed; the sweet spots as vertical lines.

    Parameters
    ----------
    results : sequence of SwingResult or of ImpactCurves
        Impacts on points along the long axis, one result per swing
        (:class:`racketdyn.workflows.figure_data.SwingAxisCurves`' curves).
    spots : mapping of str to SweetSpot, optional
        Sweet spots to mark.
    support : str, optional
        Which support (default each result's first).
    ax : Axes, optional
        Where to draw (a new figure if None).
    names : sequence of str, optional
        A name per result for the legend (default its Ω).
    """
    ax = _axes(ax, (6.5, 4.2))
    if names is not None and len(names) != len(results):
        raise ValueError(f"{len(names)} names given for {len(results)} results")
    styles = ("-", "--", "-.", ":")
    foot = ax.get_xaxis_transform()
    spans: dict[bytes, tuple[NDArray[np.float64], list[NDArray[np.bool_]]]] = {}
    for k, result in enumerate(results):
        chosen = support or result.supports[0]
        p = result.support_index(chosen)
        order = np.argsort(result.locations[:, 0])
        x_mm = result.locations[order, 0] * 1e3
        if names is not None:
            name = names[k]
        elif isinstance(result, SwingResult):
            name = f"Ω = {result.angular_speed_radps:.1f} rad/s"
        else:
            name = f"swing {k + 1}"
        colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.85, result.ball_speed.size))
        flagged = np.asarray(result.status)[order, :, p] != STATUS_OK  # (n, s)
        for s, (speed, colour) in enumerate(zip(result.ball_speed, colours, strict=True)):
            ax.plot(
                x_mm,
                np.where(flagged[:, s], np.nan, result.rebound_speed[order, s, p]),
                color=colour,
                linestyle=styles[k % len(styles)],
                label=f"{name}, ball {speed:g} m/s",
            )
            if flagged[:, s].any():  # at the foot of the axes: a cross at 0 would read as a value
                ax.plot(
                    x_mm[flagged[:, s]],
                    np.full(int(flagged[:, s].sum()), 0.03),
                    "x",
                    color=colour,
                    transform=foot,
                    clip_on=False,
                    label="_flagged rows",
                )
        # curves on the same points share one hatching and one count (issue 13)
        spans.setdefault(x_mm.tobytes(), (x_mm, []))[1].append(flagged)
    for x_mm, flags in spans.values():
        flagged_all = np.concatenate(flags, axis=1)
        mark_flagged_spans(ax, x_mm, flagged_all, "impacts", flagged_all.size)
    if spots:
        _mark_sweet_spots(ax, spots, in_plane=False)
    ax.set_xlabel("impact point, x from the butt (mm)")
    ax.set_ylabel("outgoing ball speed (m/s)")
    chosen = support or (results[0].supports[0] if results else "")
    ax.set_title(f"swinging racket, {_support_label(chosen)}", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=6)
    return ax


# --- oblique impacts and twist (issue 5) ---------------------------------------------------------
OBLIQUE_QUANTITIES: dict[str, tuple[str, float]] = {
    "outgoing_angle_deg": ("outgoing angle to the face normal (°)", 1.0),
    "outgoing_spin_radps": ("outgoing spin (rad/s)", 1.0),
    "normal_speed_mps": ("outgoing speed along the normal (m/s)", 1.0),
    "tangential_speed_mps": ("outgoing speed along the face (m/s)", 1.0),
    "tangential_impulse_ns": ("tangential impulse (N·s)", 1.0),
    "friction_loss_j": ("friction loss (J)", 1.0),
}
"""Quantities :func:`plot_oblique_curve` draws: field of ObliqueCurve → (axis label, scale)."""


def plot_oblique_curve(
    curve: ObliqueCurve,
    quantity: str = "outgoing_angle_deg",
    ax: Axes | None = None,
    label: str | None = None,
    frictionless: bool = True,
) -> Axes:
    """Outgoing angle, spin or another quantity of oblique impacts against the incoming angle.

    One line per incoming spin; filled markers where the ball gripped the strings during the
    contact, open where it slid throughout.  For the outgoing angle, the angle without friction
    (μ = 0: the tangential velocity unchanged, ``atan2(v sin θ, v_n,out)`` with the curve's own
    normal rebound speed) is drawn dashed, so the friction's part shows.

    Parameters
    ----------
    curve : ObliqueCurve
        From :func:`racketdyn.impact.oblique.oblique_curve`.
    quantity : str
        A key of :data:`OBLIQUE_QUANTITIES`.
    ax : Axes, optional
        Where to draw (a new figure if None).
    label : str, optional
        Legend label (default: the incoming spin).
    frictionless : bool
        Draw the outgoing angle without friction (``quantity`` ``outgoing_angle_deg`` only).
    """
    if quantity not in OBLIQUE_QUANTITIES:
        raise ValueError(f"quantity must be one of {', '.join(OBLIQUE_QUANTITIES)}")
    ax = _axes(ax)
    axis_label, scale = OBLIQUE_QUANTITIES[quantity]
    angles = np.ravel(curve.incoming_angle_deg)
    spins = np.ravel(curve.incoming_spin_radps)
    values = np.ravel(np.asarray(getattr(curve, quantity), dtype=float)) * scale
    gripped = np.ravel(curve.gripped)
    normal = np.ravel(curve.normal_speed_mps)
    spin_values = np.unique(spins)
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.85, spin_values.size))
    for spin, colour in zip(spin_values, colours, strict=True):
        chosen = np.flatnonzero(spins == spin)
        chosen = chosen[np.argsort(angles[chosen])]
        name = label if label is not None else f"incoming spin {spin:g} rad/s"
        ax.plot(angles[chosen], values[chosen], "-", color=colour, label=name)
        held, slid = chosen[gripped[chosen]], chosen[~gripped[chosen]]
        ax.plot(angles[held], values[held], "o", color=colour, markersize=5)
        ax.plot(angles[slid], values[slid], "o", mfc="w", mec=colour, markersize=5)
        if quantity == "outgoing_angle_deg" and frictionless:
            tangential = curve.ball_speed_mps * np.sin(np.radians(angles[chosen]))
            ax.plot(
                angles[chosen],
                np.degrees(np.arctan2(tangential, normal[chosen])),
                "--",
                color=colour,
                linewidth=0.9,
                label=f"{name}, without friction",
            )
    ax.plot([], [], "o", color="0.4", markersize=5, label="gripped")
    ax.plot([], [], "o", mfc="w", mec="0.4", markersize=5, label="slid throughout")
    ax.set_xlabel("incoming angle to the face normal (°)")
    ax.set_ylabel(axis_label)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return ax


TWIST_QUANTITIES: dict[str, tuple[str, float]] = {
    "roll_angle_rad": ("roll angle at separation (°)", 180.0 / np.pi),
    "total_twist_rad": ("roll + section rotation at separation (°)", 180.0 / np.pi),
    "flexible_twist_rad": ("section rotation of the modes (°)", 180.0 / np.pi),
    "roll_rate_radps": ("roll rate at separation (rad/s)", 1.0),
    "rebound_speed_mps": ("outgoing ball speed (m/s)", 1.0),
    "rebound_ratio": ("rebound ratio e (–)", 1.0),
    "contact_time_s": ("contact time T_c (ms)", 1e3),
}
"""Quantities :func:`plot_twist_curve` draws: field of TwistCurve → (axis label, scale); angles
are drawn in degrees."""

_EXTRA_STYLE = {"color": "tab:red", "marker": "o", "label": "hand-held (hand and arm model)"}


def plot_twist_curve(
    curve: TwistCurve,
    quantity: str = "roll_angle_rad",
    ax: Axes | None = None,
    label: str | None = None,
) -> Axes:
    """A quantity of :func:`racketdyn.impact.twist.twist_curve` against the offset from the axis.

    Parameters
    ----------
    curve : TwistCurve
        The racket's twist against the offset y, at one x, speed and support.
    quantity : str
        A key of :data:`TWIST_QUANTITIES` (angles drawn in degrees).
    ax : Axes, optional
        Where to draw (a new figure if None); call once per support to compare supports.
    label : str, optional
        Legend label (default: the support's).
    """
    if quantity not in TWIST_QUANTITIES:
        raise ValueError(f"quantity must be one of {', '.join(TWIST_QUANTITIES)}")
    ax = _axes(ax)
    axis_label, scale = TWIST_QUANTITIES[quantity]
    style = SUPPORT_STYLE.get(curve.support, _EXTRA_STYLE)
    order = np.argsort(curve.offsets_m)
    values = np.asarray(getattr(curve, quantity), dtype=float)[order] * scale
    ax.plot(
        curve.offsets_m[order] * 1e3,
        values,
        color=style["color"],
        marker=style["marker"],
        markersize=4,
        label=label if label is not None else str(style["label"]),
    )
    ax.set_xlabel("offset from the long axis, y (mm)")
    ax.set_ylabel(axis_label)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return ax


# --- the stabilisation diagram (of racketdyn.modal.poles) ----------------------------------

_POLE_STYLE: dict[PoleStability, dict[str, Any]] = {
    PoleStability.NEW: {"marker": "o", "mfc": "none", "color": "0.75", "ms": 2.5, "mew": 0.5},
    PoleStability.FREQUENCY: {"marker": "x", "color": "tab:orange", "ms": 3.0, "mew": 0.7},
    PoleStability.DAMPING: {"marker": "^", "mfc": "none", "color": "tab:green", "ms": 3.0},
    PoleStability.SHAPE: {"marker": "o", "color": "tab:blue", "ms": 3.0, "mew": 0.0},
}
_POLE_LABEL = {
    PoleStability.NEW: "new",
    PoleStability.FREQUENCY: "stable frequency",
    PoleStability.DAMPING: "+ damping",
    PoleStability.SHAPE: "+ shape (stable)",
}


def plot_stabilisation(
    stab: Stabilisation,
    selected: SelectedPoles | None = None,
    ax: Axes | None = None,
    frfs: FrfSet | SummedFrf | None = None,
) -> Axes:
    """The stabilisation diagram: model order against pole frequency, marker by stability.

    Parameters
    ----------
    stab : Stabilisation
        The poles (:func:`racketdyn.modal.poles.stabilisation`).
    selected : SelectedPoles, optional
        Modes to mark with vertical lines (pinned ones solid).
    ax : matplotlib Axes, optional
        Where to draw; a new figure if None.
    frfs : FrfSet or SummedFrf, optional
        FRFs whose summed magnitude ``Σ|H|`` to draw on a twin log axis (over the band), or
        that sum (:meth:`FrfSet.summed`).

    Returns
    -------
    Axes
        The diagram's axes (the summed FRF's twin axis, if drawn, is the other axes of
        ``ax.figure`` sharing its x axis).
    """
    ax = _axes(ax, (7.0, 4.5))
    if frfs is not None:
        summed = frfs if isinstance(frfs, SummedFrf) else frfs.summed(*stab.band_hz)
        twin = ax.twinx()
        twin.semilogy(summed.frequency, summed.magnitude, color="0.4", lw=0.7)
        twin.set_ylabel(f"Σ|H| ({FRF_UNITS[summed.frf_type]})", color="0.4")
        twin.tick_params(axis="y", colors="0.4")
        ax.set_zorder(twin.get_zorder() + 1)
        ax.patch.set_visible(False)
    for kind in PoleStability:
        mask = stab.stability == int(kind)
        if np.any(mask):
            ax.plot(
                stab.frequency[mask],
                stab.order[mask],
                linestyle="none",
                label=_POLE_LABEL[kind],
                **_POLE_STYLE[kind],
            )
    if selected is not None:
        for k, f in enumerate(selected.frequency):
            ax.axvline(f, color="tab:red", lw=0.8, ls="-" if selected.pinned[k] else "--", zorder=0)
            ax.annotate(
                f"{f:.1f}",
                (f, 1.0),
                xycoords=("data", "axes fraction"),
                xytext=(2, -2),
                textcoords="offset points",
                rotation=90,
                va="top",
                fontsize=6,
                color="tab:red",
            )
    ax.set_xlim(*stab.band_hz)
    ax.set_ylim(0, int(stab.orders[-1]) + 1)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("model order (–)")
    # above the diagram, out of the poles' way, in a readable size
    ax.legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.01), ncols=4, frameon=False)
    return ax
