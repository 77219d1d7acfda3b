"""The paper's figures for a racket, and the other figures of the steps.

Each figure is listed once, with its file name, caption and report section, in
:mod:`racketdyn.plotting.registry`, which draws the figures of a step from its result
(:func:`racketdyn.plotting.registry.write_figures`).  Every figure only draws: what it shows
was computed by the step's workflow with the run's own inputs
(:mod:`racketdyn.workflows.figure_data`: :class:`PaperFigures`, :class:`TransientCurves`,
:class:`SwingAxisCurves`, :class:`IdentifiedRebound`, written to the run's ``figures.nc``).
"""

from __future__ import annotations

import logging
import math
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from numpy.typing import NDArray

from racketdyn._display import case_words
from racketdyn.errors import InputError
from racketdyn.measurement.records import FRF_UNITS
from racketdyn.plotting.primitives import (
    SCALE_BAR_M,
    SUPPORT_STYLE,
    axes_grid,
    label_lines,
    mark_flagged_spans,
    plot_along_axis,
    plot_contact_map,
    plot_face_map,
    plot_frame_amplitude,
    plot_frf,
    plot_mac,
    plot_mode_3d,
    plot_node_lines,
    plot_oblique_curve,
    plot_outline,
    plot_speed_curves,
    plot_stabilisation,
    plot_swing_along_axis,
    plot_swing_map,
    plot_twist_curve,
)
from racketdyn.plotting.registry import file_of
from racketdyn.plotting.render import save_figure
from racketdyn.racket import SUPPORT_NAMES, Racket
from racketdyn.workflows.figure_data import (
    SWING_AXIS_POINTS,
    TRANSIENT_CURVE_SPEEDS_MPS,
    ComparisonMap,
    IdentifiedRebound,
    ImpactCurves,
    PaperFigures,
    SwingAxisCurves,
    TransientCurves,
    TransientHistories,
)

if TYPE_CHECKING:  # what the figures draw is given to them: its modules are the callers'
    # (racketdyn.impact.oblique imports the transient model and numba, ≈ 0.2 s of a `predict`)
    from racketdyn.impact.oblique import ObliqueCurve, TangentialContact
    from racketdyn.impact.swing import SweetSpot, SwingResult
    from racketdyn.impact.twist import TwistCurve
    from racketdyn.measurement.pulse import ContactTimes
    from racketdyn.measurement.records import FrfSet
    from racketdyn.workflows.frf_figures import FitFigures, FrfPoints
    from racketdyn.workflows.identify import ModeComparison
    from racketdyn.workflows.shape_figures import AutoMac, AxisNodes, ModeShapes

__all__ = [
    "IDENTIFIED_STYLES",
    "SWING_AXIS_POINTS",
    "TRANSIENT_CURVE_SPEEDS_MPS",
    "figure_contact_time",
    "figure_face_maps",
    "figure_force_and_contact_time",
    "figure_frame_vibration",
    "figure_frf_frame",
    "figure_frf_string_centre",
    "figure_mode_comparison",
    "figure_mode_shapes",
    "figure_node_lines",
    "figure_oblique",
    "figure_pulse_spectrum",
    "figure_rebound_along_axis",
    "figure_sensitivity",
    "figure_stabilisation",
    "figure_swing_along_axis",
    "figure_swing_map",
    "figure_synthesised_frfs",
    "figure_transient_comparison_face",
    "figure_transient_comparison_speed",
    "figure_transient_histories",
    "figure_twist",
    "plot_automac",
    "plot_axis_nodes",
    "plot_identified_rebound",
    "write_contact_figure",
]

log = logging.getLogger(__name__)


def _save(figure: Figure, path: Path) -> Path:
    """Draw one figure into ``path`` now (a step with one figure)."""
    return save_figure(figure, path)


def _mark_run_speeds(
    ax: Axes,
    speeds: NDArray[np.float64],
    values: NDArray[np.float64],
    run_speeds: NDArray[np.float64],
) -> None:
    """The run's speeds on a curve against speed: markers on the curve's values there."""
    if not run_speeds.size:
        return
    at = np.isin(speeds, run_speeds)
    ax.plot(speeds[at], values[at], "o", color="tab:red", markersize=4, label="the run's speeds")


def figure_force_and_contact_time(data: PaperFigures, axes: Sequence[Axes] | None = None) -> Figure:
    """Paper Figs 11 and 12: F_MEAN and T_c against speed at the top, centre and throat.

    Parameters
    ----------
    data : PaperFigures
        The run's figure data (:func:`racketdyn.workflows.figure_data.paper_figures`): its
        ``speed_curves``, with the run's speeds marked.
    axes : sequence of Axes, optional
        Two per racket speed of the curves (a row each: force, contact time) to draw into, their
        figure, size and layout the caller's; default a figure of its own
        (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that many).
    """
    every = data.speed_curves
    names = list(every.labels)
    racket_speeds = every.racket_speeds
    figure, grid = axes_grid(
        axes,
        len(racket_speeds),
        2,
        figsize=(10, 4 * len(racket_speeds)),
        layout="constrained",
        squeeze=False,
    )
    for pair, racket_speed in zip(grid, racket_speeds, strict=True):
        # one row per racket speed, its curves over the whole speed axis (issue 27)
        curves = every.at_racket_speed(racket_speed)
        run_speeds = data.run_speeds
        if data.run_racket_speeds.size == run_speeds.size:
            run_speeds = run_speeds[data.run_racket_speeds == racket_speed]
        racket = f"racket {racket_speed:g} m/s" if racket_speed else "racket at rest"
        for ax, quantity in zip(pair, ("mean_force", "contact_time"), strict=True):
            plot_speed_curves(curves, quantity, names, ax=ax)
            scale = 1e3 if quantity == "contact_time" else 1.0
            values = np.asarray(getattr(curves, quantity), dtype=float) * scale
            for i in range(len(names)):
                for p in range(len(curves.supports)):
                    _mark_run_speeds(ax, curves.ball_speed, values[i, :, p], run_speeds)
            _dedupe_legend(ax)
        pair[0].set_title(f"Fig. 11: equivalent impact force, {racket}", fontsize=9)
        pair[1].set_title(f"Fig. 12: contact time, {racket}", fontsize=9)
    figure.suptitle(f"{data.racket_name}: {data.description}", fontsize=10)
    return figure


def _legend_below(ax: Axes | Sequence[Axes], fontsize: float = 7, columns: int = 2) -> None:
    """The axes' legend moved under the figure, out of the data's way (constrained layout
    makes room for it).  Several axes share one legend, each label once; a panel's own count of
    flagged rows is then prefixed by its title."""
    panels = [ax] if isinstance(ax, Axes) else list(ax)
    unique: dict[str, Any] = {}
    for panel in panels:
        for handle, label in zip(*panel.get_legend_handles_labels(), strict=True):
            if len(panels) > 1 and label.startswith("flagged"):
                label = f"{panel.get_title()}: {label}"
            unique.setdefault(label, handle)
        legend = panel.get_legend()
        if legend is not None:
            legend.remove()
    handles, labels = list(unique.values()), list(unique)
    figure = panels[0].get_figure() if panels else None
    if handles and isinstance(figure, Figure):
        # as many columns as the widest entry lets fit across the figure (≈ 0.55 em a character)
        entry_pt = 0.55 * fontsize * max(len(label) for label in labels) + 3.0 * fontsize
        fit = int(0.95 * figure.get_figwidth() * 72.0 // entry_pt)
        columns = max(1, min(columns, fit, len(labels)))
        figure.legend(handles, labels, loc="outside lower center", ncols=columns, fontsize=fontsize)


def _dedupe_legend(ax: Axes, fontsize: float = 7) -> None:
    """One legend entry per label."""
    handles, labels = ax.get_legend_handles_labels()
    unique = dict(zip(labels, handles, strict=True))
    ax.legend(list(unique.values()), list(unique.keys()), fontsize=fontsize)


def figure_frame_vibration(data: PaperFigures, axes: Sequence[Axes] | None = None) -> Figure:
    """Paper Fig. 14: first-mode displacement along the frame for an impact at the tip.

    One panel per support of the run; flagged impacts are not drawn and are labelled.

    Parameters
    ----------
    data : PaperFigures
        The run's figure data: its ``frame`` (None: a rigid racket, a figure that says there
        is no vibration).
    axes : sequence of Axes, optional
        One per support of the run (one for a rigid racket) to draw into, their figure, size and
        layout the caller's; default a figure of its own
        (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that many).
    """
    frame = data.frame
    if frame is None:
        figure, ax = axes_grid(axes, 1, 1, figsize=(6, 2.5), layout="constrained")
        ax.set_axis_off()
        ax.text(
            0.5,
            0.5,
            "rigid racket: no vibration (no modes)",
            ha="center",
            va="center",
            transform=ax.transAxes,
        )
        figure.suptitle("Fig. 14: frame vibration", fontsize=10)
        return figure
    supports = frame.supports
    figure, grid = axes_grid(
        axes,
        1,
        len(supports),
        figsize=(5 * len(supports), 4),
        layout="constrained",
        sharey=True,
        squeeze=False,
    )
    for ax, support in zip(grid[0], supports, strict=True):
        plot_frame_amplitude(frame, support=support, ax=ax)
    figure.suptitle(
        "Fig. 14: predicted frame vibration just after an impact at the tip (first mode only); "
        + frame.description,
        fontsize=10,
    )
    return figure


def figure_rebound_along_axis(data: PaperFigures) -> Figure:
    """Paper Fig. 15: rebound ratio along the long axis at the shown speed, per support.

    Parameters
    ----------
    data : PaperFigures
        The run's figure data: its ``axis`` curves and ``axis_marks``.
    """
    axis = data.axis
    figure, ax = plt.subplots(figsize=(6.5, 5.6), layout="constrained")
    plot_along_axis(axis, "rebound_ratio", 0, ax=ax, marks=data.axis_marks, band=data.axis_band)
    _legend_below(ax)
    uncertain = "" if data.axis_band is None else f"\nshaded: 90 % band of {data.axis_band.inputs}"
    ax.set_title(
        f"Fig. 15: predicted rebound ratio, ball at {axis.ball_speed[0]:g} m/s\n"
        + data.axis_description
        + uncertain,
        fontsize=9,
    )
    return figure


def figure_sensitivity(data: Any, axes: Sequence[Axes] | None = None) -> Figure:
    """Which input dominates the rebound ratio at the run's named points: Sobol' total indices
    (bars) and first-order ones (dark), with their 90 % intervals.

    Parameters
    ----------
    data : racketdyn.impact.uncertainty.Sensitivity
        The run's indices (``sensitivity.csv``'s numbers).
    axes : sequence of Axes, optional
        One per named point, two to a row (a last odd one hidden) to draw into, their figure, size
        and layout the caller's; default a figure of its own
        (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that many).
    """
    o = data.outputs.index("rebound_ratio")
    n = len(data.labels)
    columns = 2 if n > 1 else 1
    rows = int(np.ceil(n / columns))
    figure, grid = axes_grid(
        axes, rows, columns, figsize=(5.2 * columns, 0.9 + 0.38 * len(data.inputs) * rows + 0.6),
        layout="constrained", squeeze=False,
    )  # fmt: skip
    for p, label in enumerate(data.labels):
        ax = grid.flat[p]
        ax.set_title(f"{label} ({data.locations[p, 0] * 1e3:.0f}, "
                     f"{data.locations[p, 1] * 1e3:.0f} mm)", fontsize=8)  # fmt: skip
        total, first = data.total_order[o, p], data.first_order[o, p]
        ax.set_xlim(0.0, 1.05)
        ax.tick_params(axis="x", labelsize=7)
        if not np.all(np.isfinite(total)):
            why = f"no indices:\n{data.why_none(p)}"
            ax.text(0.5, 0.5, why, ha="center", va="center", fontsize=7,
                    transform=ax.transAxes, wrap=True)  # fmt: skip
            ax.set_yticks([])
            continue
        order = np.argsort(total)
        y = np.arange(order.size)
        ax.barh(y, total[order], color="0.75", label="total")
        ax.barh(y, first[order], height=0.4, color="0.25", label="first order")
        for ci, colour in ((data.total_order_ci, "0.45"), (data.first_order_ci, "0.1")):
            if ci is not None:
                low, high = ci[0, o, p][order], ci[1, o, p][order]
                ax.errorbar(
                    (low + high) / 2, y, xerr=(high - low) / 2, fmt="none", ecolor=colour,
                    elinewidth=0.8, capsize=2,
                )  # fmt: skip
        ax.set_yticks(y, [data.inputs[i] for i in order], fontsize=7)
    for ax in grid.flat[n:]:
        ax.set_visible(False)
    for ax in grid[-1]:
        ax.set_xlabel("Sobol' index of the rebound ratio", fontsize=8)
    grid.flat[0].legend(fontsize=7, loc="lower right")
    figure.suptitle(
        f"which input dominates the rebound ratio: ball at {data.ball_speed:g} m/s, "
        f"{data.support}; Sobol' total (light) and first-order (dark) indices, 90 % intervals "
        f"({data.evaluations} model runs)",
        fontsize=8,
    )
    return figure


def figure_face_maps(data: PaperFigures, axes: Sequence[Axes] | None = None) -> Figure:
    """Face maps at one speed: rebound ratio (each support), contact time and vibration energy.

    The run's impacts at the shown speed (points, not a contour, where they span no surface).

    Parameters
    ----------
    data : PaperFigures
        The run's figure data: its ``face`` impacts and ``main_support``.
    axes : sequence of Axes, optional
        One per map (rebound ratio per support, contact time, vibration energy, and the band's width
        per support with an uncertainty), two or three to a row to draw into, their figure, size and
        layout the caller's; default a figure of its own
        (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that many).
    """
    face = data.face
    panels = [("rebound_ratio", support) for support in face.supports]
    panels += [("contact_time", data.main_support), ("vibration_energy", data.main_support)]
    if face.rebound_ratio_band_width.size:
        panels += [("rebound_ratio_band_width", support) for support in face.supports]
    columns = 2 if len(panels) in (4, 6) else min(len(panels), 3)
    rows = int(np.ceil(len(panels) / columns))
    figure, grid = axes_grid(
        axes, rows, columns, figsize=(5 * columns, 3.75 * rows), layout="constrained", squeeze=False
    )
    for ax, (quantity, support) in zip(grid.flat, panels, strict=True):
        plot_face_map(face, data.head, quantity, 0, support, ax=ax)
    figure.suptitle(
        f"{data.racket_name}: ball at {face.ball_speed[0]:g} m/s, {len(face.locations)} points; "
        + data.face_description
        + "\napproximate method (eqs 1–12); with both models run, impact.csv holds the "
        "transient model's numbers where this map has none",
        fontsize=10,
    )
    return figure


_CHARGED, _NOT_CHARGED = "0.3", "0.7"
"""Fig. 13's dotted lines: a mode the prediction charges, and a string-bed mode it does not."""

_CHARGED_WORDS = "modes the prediction charges"
_NOT_CHARGED_WORDS = "the string bed's modes: for reference, not charged"


def figure_pulse_spectrum(data: PaperFigures, axes: Sequence[Axes] | None = None) -> Figure:
    """Paper Fig. 13: the half-sine pulse at the face centre and its spectrum, against speed.

    Parameters
    ----------
    data : PaperFigures
        The run's figure data: its ``pulse`` (the modes the prediction charges dotted, the
        string bed's it does not charge dotted in a lighter grey, for reference).
    axes : sequence of Axes, optional
        Two (the pulse, its spectrum) to draw into, their figure, size and layout the caller's;
        default a figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an error if
        not that many).
    """
    pulse = data.pulse
    figure, grid = axes_grid(axes, 1, 2, figsize=(10, 4.6), layout="constrained")
    frequency = pulse.frequency
    for s in np.flatnonzero(pulse.drawn()):
        speed, contact = pulse.ball_speed[s], pulse.contact_time[s]
        grid[0].plot(
            pulse.time * 1e3,
            pulse.force[s],
            label=f"{speed:g} m/s: peak {pulse.half_sine_peak[s]:.0f} N",
        )
        grid[1].plot(
            frequency, pulse.spectrum[s], label=f"{speed:g} m/s: T_c = {contact * 1e3:.2f} ms"
        )
    if pulse.modal:
        modes = [
            (float(f), name, _CHARGED if charged else _NOT_CHARGED)
            for name, f, charged in zip(
                pulse.mode_names, pulse.mode_frequency, pulse.mode_charged, strict=True
            )
        ]
        grid[1].set_xlim(frequency[0] - 30.0, frequency[-1] + 30.0)
        label_lines(grid[1], modes)
        for colour, words in ((_CHARGED, _CHARGED_WORDS), (_NOT_CHARGED, _NOT_CHARGED_WORDS)):
            if any(mark[2] == colour for mark in modes):
                grid[1].plot([], [], color=colour, linestyle=":", linewidth=1.0, label=words)
    grid[0].set_xlabel("time from first contact (ms)")
    grid[0].set_ylabel("half-sine force F(t), eq 11 (N)")
    grid[1].set_xlabel("frequency (Hz)")
    grid[1].set_ylabel("|S(f)| (N·s)")
    for ax in grid:
        ax.grid(alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    figure.suptitle(
        "Fig. 13: eq 11's half sine of the impact's impulse at the face centre "
        f"({SUPPORT_STYLE[pulse.support]['label']}) and its spectrum; the racket's modes dotted"
        f"\n{pulse.description}; the contact's own peak F_MAX is impact.csv's peak_force_n",
        fontsize=10,
    )
    return figure


def _point_label(frfs: FrfSet, index: int, centre_index: int) -> str:
    """One label per point, the same in every figure: its node, where it is and what it is."""
    where = ", ".join(f"{1e3 * c:.0f}" for c in frfs.locations[index])
    roles = []
    if index == frfs.driving_point:
        roles.append("driving point (at the accelerometer)")
    if index == centre_index:
        roles.append("nearest the string-bed centre")
    return f"node {frfs.nodes[index]} ({where}) mm" + (": " + ", ".join(roles) if roles else "")


def _frf_figure(points: FrfPoints, frame_point: bool, axes: Sequence[Axes] | None) -> Figure:
    """Fig. 2 (``frame_point``) or Fig. 3: one point's FRF, magnitude, phase and coherence."""
    frfs = points.frfs
    index = points.frame if frame_point else points.centre
    figure, grid = axes_grid(
        axes,
        3,
        1,
        figsize=(6.5, 6),
        sharex=True,
        layout="constrained",
        gridspec_kw={"height_ratios": [2, 1, 1]},
    )
    plot_frf(frfs, index, axes=list(grid), label=_point_label(frfs, index, points.centre))
    averages = "" if frfs.n_averages is None else f", {int(frfs.n_averages[index])} averages"
    figure.suptitle(f"{frfs.frf_type} FRF, {frfs.estimator}{averages} ({frfs.source})", fontsize=9)
    return figure


def figure_frf_frame(points: FrfPoints, axes: Sequence[Axes] | None = None) -> Figure:
    """Paper Fig. 2: the frame's driving-point FRF (without a driving point, the first point's,
    and its label says so).

    Parameters
    ----------
    points : FrfPoints
        The FRFs of the points drawn (:func:`racketdyn.workflows.frf_figures.frf_points`).
    axes : sequence of Axes, optional
        Three (magnitude, phase, coherence) to draw into, their figure, size and layout the
        caller's; default a figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an
        error if not that many).
    """
    return _frf_figure(points, True, axes)


def figure_frf_string_centre(points: FrfPoints, axes: Sequence[Axes] | None = None) -> Figure:
    """Paper Fig. 3: the FRF at the point nearest the string-bed centre.

    Each point is labelled the same way in Figs 2 and 3 (:func:`_point_label`): when the
    driving point is also the point nearest the centre both figures say both.

    Parameters
    ----------
    points : FrfPoints
        The FRFs of the points drawn (:func:`racketdyn.workflows.frf_figures.frf_points`).
    axes : sequence of Axes, optional
        Three (magnitude, phase, coherence) to draw into, their figure, size and layout the
        caller's; default a figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an
        error if not that many).
    """
    return _frf_figure(points, False, axes)


def figure_contact_time(
    tables: Sequence[ContactTimes],
    labels: Sequence[str],
    racket: Racket,
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Paper Fig. 7: hammer contact time over the string face, one panel per condition.

    Parameters
    ----------
    tables : sequence of ContactTimes
        Contact times per test (condition).
    labels : sequence of str
        A label per table.
    racket : Racket
        The racket (its face).
    axes : sequence of Axes, optional
        One per table to draw into, their figure, size and layout the caller's; default a figure of
        its own (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that many).
    """
    figure, grid = axes_grid(
        axes, 1, len(tables), figsize=(4.6 * len(tables), 3.8), layout="constrained", squeeze=False
    )
    finite = (
        np.concatenate(
            [t.mean_s[racket.head.contains(t.locations) & np.isfinite(t.mean_s)] for t in tables]
        )
        * 1e3
    )
    levels = (
        np.linspace(finite.min(), finite.max(), 11) if finite.size and np.ptp(finite) > 0 else 10
    )
    for ax, table, label in zip(grid[0], tables, labels, strict=True):
        plot_contact_map(table, racket, ax=ax, title=label, levels=levels)
    figure.suptitle("Fig. 7: contact time of the hammer on the strings", fontsize=10)
    return figure


def write_contact_figure(
    tables: Sequence[ContactTimes], labels: Sequence[str], racket: Racket, out_dir: Path
) -> Path:
    """Draw :func:`figure_contact_time` into ``out_dir``; returns the path."""
    return _save(
        figure_contact_time(tables, labels, racket), Path(out_dir) / file_of("fig7_contact_time")
    )


def _mode_grid(n: int) -> tuple[int, int]:
    """(rows, columns) of a grid of ``n`` mode panels, three to a row."""
    columns = max(min(n, 3), 1)
    return int(np.ceil(n / columns)), columns


def figure_mode_shapes(shapes: ModeShapes, axes: Sequence[Axes] | None = None) -> Figure:
    """Paper Fig. 4: each mode shape in 3-D over the racket, with a 100 mm scale bar (over its
    own points for a structure that is not a racket).

    Parameters
    ----------
    shapes : ModeShapes
        The modes evaluated where they are drawn
        (:func:`racketdyn.workflows.shape_figures.mode_shapes`).
    axes : sequence of 3-D Axes, optional
        One per mode, each made with ``projection="3d"`` (:mod:`mpl_toolkits.mplot3d`), to draw
        into, their figure, size and layout the caller's; default a figure of its own, three
        panels to a row (an error if not one 3-D Axes per mode).
    """
    figure, panels = _mode_panels_3d(shapes.n_modes, axes)
    for k, ax3d in enumerate(panels):
        plot_mode_3d(shapes, k, ax=ax3d)
    scaled = "" if shapes.mass_normalised else ", unscaled"
    bar = f"; bar: {SCALE_BAR_M * 1e3:.0f} mm" if shapes.layout_3d == "racket" else ""
    figure.suptitle(
        f"Fig. 4: mode shapes ({shapes.support}{scaled}), each scaled to the same largest "
        f"amplitude{bar}",
        fontsize=10,
    )
    return figure


def _mode_panels_3d(n: int, axes: Sequence[Axes] | None) -> tuple[Figure, Iterable[Axes]]:
    """Fig. 4's figure and its ``n`` 3-D panels: the caller's (checked: one per mode, each 3-D),
    or a new figure's, three to a row, each made as it is drawn."""
    if axes is None:
        rows, columns = _mode_grid(n)
        figure = plt.figure(figsize=(4.2 * columns, 3.2 * rows), layout="constrained")
        made = (figure.add_subplot(rows, columns, k + 1, projection="3d") for k in range(n))
        return figure, made
    figure, grid = axes_grid(axes, 1, n, squeeze=False)
    flat = [ax for ax in grid.flat if isinstance(ax, Axes)]
    plain = [k + 1 for k, ax in enumerate(flat) if ax.name != "3d"]
    if plain:
        raise InputError(
            "`axes` takes 3-D matplotlib Axes (projection='3d') for this figure; not 3-D: "
            f"panel {', '.join(map(str, plain))}"
        )
    return figure, flat


def figure_node_lines(shapes: ModeShapes, axes: Sequence[Axes] | None = None) -> Figure:
    """Paper Fig. 5: node lines of each mode on the string face, with a key to black and white.

    Parameters
    ----------
    shapes : ModeShapes
        The modes evaluated where they are drawn: over the face and outline of a racket, over
        its own points for any other structure.
    axes : sequence of Axes, optional
        One per mode, three to a row (the last row's spare ones turned off) to draw into, their
        figure, size and layout the caller's; default a figure of its own
        (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that many).
    """
    rows, columns = _mode_grid(shapes.n_modes)
    figure, grid = axes_grid(
        axes,
        rows,
        columns,
        figsize=(3.2 * columns, 2.6 * rows),
        layout="constrained",
        squeeze=False,
    )
    for k, ax in enumerate(grid.flat):
        if k >= shapes.n_modes:
            ax.set_axis_off()
        else:
            plot_node_lines(shapes, k, ax=ax)
    where = "on the string face" if shapes.layout_nodes == "racket" else "over the measured points"
    figure.suptitle(f"Fig. 5: node lines {where} ({shapes.support})", fontsize=10)
    figure.legend(
        handles=[
            Patch(facecolor="k", edgecolor="k", label="black: the face moves one way"),
            Patch(facecolor="w", edgecolor="k", label="white: it moves the other way"),
            Line2D([], [], color="tab:red", label="node line: it does not move"),
        ],
        loc="outside lower center",
        ncols=3,
        fontsize=8,
        title="at each instant of the mode's vibration (which way is which is arbitrary)",
        title_fontsize=8,
    )
    return figure


def figure_stabilisation(data: FitFigures) -> Figure:
    """The stabilisation diagram of an identification, with the selected modes.

    Parameters
    ----------
    data : FitFigures
        What the step's identification draws (:func:`racketdyn.workflows.frf_figures.fit_figures`).
    """
    figure, ax = plt.subplots(figsize=(8, 5), layout="constrained")
    plot_stabilisation(data.stabilisation, data.selected, ax=ax, frfs=data.summed)
    return figure


def figure_synthesised_frfs(data: FitFigures, axes: Sequence[Axes] | None = None) -> Figure:
    """Measured FRFs against those synthesised from the identified model: the driving point and
    the point nearest the string-bed centre (a racket's modes) or the worst-fitted point.

    Parameters
    ----------
    data : FitFigures
        What the step's identification draws (:func:`racketdyn.workflows.frf_figures.fit_figures`).
    axes : sequence of Axes, optional
        One per drawn point to draw into, their figure, size and layout the caller's; default a
        figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that
        many).
    """
    drawn = data.synthesised
    frfs, frequency = drawn.frfs, drawn.frequency
    figure, grid = axes_grid(
        axes,
        1,
        frfs.n_points,
        figsize=(5.5 * frfs.n_points, 4),
        layout="constrained",
        squeeze=False,
    )
    band = (frfs.frequency >= frequency[0]) & (frfs.frequency <= frequency[-1])
    for ax, index in zip(grid[0], range(frfs.n_points), strict=True):
        ax.semilogy(frfs.frequency, np.abs(frfs.values[index]), color="0.6", label="measured")
        ax.semilogy(
            frequency,
            np.abs(drawn.synthesised[index]),
            "--",
            color="tab:red",
            label=f"synthesised (error {drawn.error[index]:.1%})",
        )
        ax.set_xlim(0, float(frequency[-1]) * 1.05)
        ax.set_ylim(
            np.abs(frfs.values[index, band]).min() / 3, np.abs(frfs.values[index]).max() * 3
        )
        ax.set_xlabel("frequency (Hz)")
        ax.set_ylabel(f"|H| ({FRF_UNITS[frfs.frf_type]})")
        ax.set_title(f"node {frfs.nodes[index]}", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    return figure


def plot_automac(automac: AutoMac, ax: Axes | None = None) -> Axes:
    """The AutoMAC of identified mode shapes, with its values.

    Parameters
    ----------
    automac : AutoMac
        The matrix (:meth:`racketdyn.workflows.shape_figures.AutoMac.of`).
    ax : matplotlib Axes, optional
        Where to draw (in the caller's figure); a new figure if None.

    Returns
    -------
    Axes
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(5.5, 4.5), layout="constrained")
    plot_mac(automac.matrix, automac.names, automac.names, ax=ax)
    ax.set_title("AutoMAC", fontsize=9)
    return ax


def plot_axis_nodes(axis: AxisNodes, ax: Axes | None = None) -> Axes:
    """Paper Fig. 6: the first mode along the long axis with its nodes, one line per model
    (identify's; compare's free against hand-held).

    Parameters
    ----------
    axis : AxisNodes
        The curves and nodes (:func:`racketdyn.workflows.shape_figures.axis_node_curves`).
    ax : matplotlib Axes, optional
        Where to draw; a new figure if None.

    Returns
    -------
    Axes
    """
    if ax is None:
        height = 3.8 if len(axis.supports) == 1 else 4.2  # room for the legend's second row
        _, ax = plt.subplots(figsize=(7, height), layout="constrained")
    marks = []
    for k, colour in zip(range(len(axis.supports)), ("tab:blue", "k"), strict=False):
        nodes = axis.nodes_of(k) * 1e3
        ax.plot(
            axis.x * 1e3,
            axis.shapes[k],
            color=colour,
            label=f"{axis.supports[k]}: {axis.names[k]}, {axis.frequency[k]:.1f} Hz; nodes at "
            + ", ".join(f"{node:.0f}" for node in nodes)
            + " mm",
        )
        marks += [(float(node), f"{node:.0f}", colour) for node in nodes]
    ax.axvspan(0, axis.grip_m * 2e3, color="0.9", label="hand")
    ax.axhline(0, color="0.5", linewidth=0.8)
    label_lines(ax, marks)
    ax.set_xlabel("x from the butt (mm)")
    ax.set_ylabel("mass-normalised shape (1/√kg)")
    ax.set_title("Fig. 6: node positions of the first mode (mm from the butt)", fontsize=9)
    ax.grid(alpha=0.3)
    _legend_below(ax, columns=len(axis.supports) + 1)
    return ax


IDENTIFIED_STYLES: tuple[tuple[str, str, str], ...] = (
    ("k", "s", "-"),
    ("k", "s", "--"),
    ("tab:blue", "D", "-"),
)
"""(colour, marker, line style) of each curve of
:data:`~racketdyn.workflows.figure_data.IDENTIFIED_CASES` in the compare step's Fig. 15."""


def plot_identified_rebound(data: IdentifiedRebound, ax: Axes | None = None) -> Axes:
    """Paper Fig. 15 with the identified models: rebound ratio along the long axis.

    Parameters
    ----------
    data : IdentifiedRebound
        The compare step's curves (:func:`racketdyn.workflows.figure_data.identified_rebound`,
        with the run's ball).
    ax : matplotlib Axes, optional
        Where to draw (in the caller's figure); a new figure if None.

    Returns
    -------
    Axes
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 4.2), layout="constrained")
    for k, label in enumerate(data.cases):
        colour, marker, style = IDENTIFIED_STYLES[k % len(IDENTIFIED_STYLES)]
        ax.plot(
            data.x * 1e3,
            data.rebound_ratio[k],
            color=colour,
            marker=marker,
            markersize=3,
            linestyle=style,
            markerfacecolor="none" if style == "--" else colour,
            label=label,
        )
    ax.set_xlabel("impact point, x from the butt (mm)")
    ax.set_ylabel("rebound ratio e (–)")
    ax.set_title(f"Fig. 15: identified models, ball at {data.ball_speed:g} m/s", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return ax


def figure_mode_comparison(
    comparison: ModeComparison, axes: Sequence[Axes] | None = None
) -> Figure:
    """Frequency shift and damping ratio of each mode, hand-held against free (paired by MAC).

    Parameters
    ----------
    comparison : ModeComparison
        The compare step's pairing (``comparison.csv``).
    axes : sequence of Axes, optional
        Two (frequency shift, damping ratio) to draw into, their figure, size and layout the
        caller's; default a figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an
        error if not that many).
    """
    rows = [row for row in comparison.rows if np.isfinite(row["mac"])]  # the pairs
    figure, grid = axes_grid(axes, 1, 2, figsize=(11, 4), layout="constrained")
    names = [row["mode"] for row in rows]
    index = np.arange(len(rows))
    grid[0].bar(index, [row["frequency_shift_percent"] for row in rows], color="tab:blue")
    grid[0].set_ylabel("frequency shift, hand-held vs free (%)")
    grid[1].bar(index - 0.2, [100 * row["damping_free"] for row in rows], 0.4, label="free")
    grid[1].bar(
        index + 0.2, [100 * row["damping_hand"] for row in rows], 0.4, label="hand-held", color="k"
    )
    grid[1].set_ylabel("damping ratio (%)")
    grid[1].legend(fontsize=8)
    for ax in grid:
        ax.set_xticks(index, names, rotation=30, ha="right", fontsize=8)
        ax.grid(alpha=0.3, axis="y")
    figure.suptitle("Free against hand-held (paired by MAC)", fontsize=10)
    return figure


# --- the approximate method against the transient simulation (issue 5) --------------------------
_EXTRA_SUPPORT_STYLE = {"color": "tab:red", "marker": "o"}
_SUPPORT_LINES = {"free": "-", "pinned": "--", "hand": ":"}


def _support_style(support: str) -> dict[str, str]:
    style = SUPPORT_STYLE.get(support)
    if style is None:  # the transient model's hand support has no paper style
        return {**_EXTRA_SUPPORT_STYLE, "label": SUPPORT_NAMES.get(support, support)}
    return {key: str(value) for key, value in style.items()}


def _difference_map(data: ComparisonMap, support: str, limit: float, ax: Axes) -> Axes:
    """Approximate − transient rebound ratio over the face, diverging colours around 0."""
    values = data.difference[:, data.supports.index(support)]
    x_mm, y_mm = data.locations[:, 0] * 1e3, data.locations[:, 1] * 1e3
    finite = np.isfinite(values)
    scale = limit if limit > 0 else 1.0
    if finite.sum() >= 3 and np.ptp(x_mm[finite]) > 0 and np.ptp(y_mm[finite]) > 0:
        filled = ax.tricontourf(
            x_mm[finite],
            y_mm[finite],
            values[finite],
            levels=np.linspace(-scale, scale, 13),
            cmap="RdBu_r",
            extend="both",
        )
        ax.figure.colorbar(filled, ax=ax, label="Δ rebound ratio, approx − transient (–)")
    ax.scatter(
        x_mm[finite],
        y_mm[finite],
        c=values[finite],
        cmap="RdBu_r",
        vmin=-scale,
        vmax=scale,
        s=12,
        edgecolors="k",
        linewidths=0.3,
    )
    if np.any(~finite):
        ax.plot(
            x_mm[~finite],
            y_mm[~finite],
            "x",
            color="k",
            markersize=4,
            label="no valid result in one model (see status)",
        )
        ax.legend(fontsize=7, loc="lower left")
    if finite.any():
        worst = int(np.flatnonzero(finite)[np.argmax(np.abs(values[finite]))])
        ax.annotate(
            f"{values[worst]:+.3f}",
            (x_mm[worst], y_mm[worst]),
            xytext=(4, 4),
            textcoords="offset points",
            fontsize=7,
        )
    plot_outline(data.head, ax)
    ax.set_xlabel("x from the butt (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"{_support_style(support)['label']}, {data.ball_speed:g} m/s", fontsize=9)
    return ax


def figure_transient_comparison_face(
    data: ComparisonMap, axes: Sequence[Axes] | None = None
) -> Figure:
    """Rebound ratio, approximate − transient, over the face at one speed, one panel a support.

    Parameters
    ----------
    data : ComparisonMap
        The difference at the run's impacts
        (:meth:`racketdyn.workflows.figure_data.ComparisonMap.of`).
    axes : sequence of Axes, optional
        One per support to draw into, their figure, size and layout the caller's; default a figure
        of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that many).
    """
    supports = data.supports
    difference = data.difference
    limit = float(np.nanmax(np.abs(difference))) if np.any(np.isfinite(difference)) else 0.0
    figure, grid = axes_grid(
        axes,
        1,
        len(supports),
        figsize=(4.8 * len(supports), 3.9),
        layout="constrained",
        squeeze=False,
    )
    for ax, support in zip(grid[0], supports, strict=True):
        _difference_map(data, support, limit, ax)
    figure.suptitle(
        "Rebound ratio: approximate method − transient simulation "
        f"(largest |Δ| {limit:.3f}; red: the approximate method higher)",
        fontsize=10,
    )
    return figure


def figure_transient_comparison_speed(
    curves: TransientCurves, axes: Sequence[Axes] | None = None
) -> Figure:
    """Rebound ratio and contact time against speed, approximate against transient.

    At the face centre, near the tip and near the throat, one column per support and two rows
    (rebound ratio, contact time) per racket speed of the curves; the run's speeds marked.

    Parameters
    ----------
    curves : TransientCurves
        Both models' curves (:func:`racketdyn.workflows.figure_data.transient_curves`).
    axes : sequence of Axes, optional
        Two rows (rebound ratio, contact time) per racket speed of one per support to draw
        into, their figure, size and layout the caller's; default a figure of its own
        (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that many).
    """
    supports = curves.approximate.supports
    racket_speeds = curves.approximate.racket_speeds
    figure, grid = axes_grid(
        axes,
        2 * len(racket_speeds),
        len(supports),
        figsize=(5.0 * len(supports), 7.0 * len(racket_speeds)),
        layout="constrained",
        squeeze=False,
        sharex=True,
    )
    for k, racket_speed in enumerate(racket_speeds):
        run_speeds = curves.run_speeds
        if curves.run_racket_speeds.size == run_speeds.size:
            run_speeds = run_speeds[curves.run_racket_speeds == racket_speed]
        racket = f"racket {racket_speed:g} m/s" if racket_speed else "racket at rest"
        block = grid[2 * k : 2 * k + 2, :]
        _comparison_against_speed(
            block,
            curves.approximate.at_racket_speed(racket_speed),
            curves.transient.at_racket_speed(racket_speed),
            run_speeds,
        )
        for p, support in enumerate(supports):
            title = _support_style(support)["label"]
            block[0, p].set_title(title if len(racket_speeds) == 1 else f"{title}, {racket}",
                                  fontsize=9)  # fmt: skip
    _legend_below(list(grid[0, :]), columns=3)
    figure.suptitle(
        "Approximate method (dashed) against the transient simulation (solid); "
        + curves.description,
        fontsize=10,
    )
    return figure


def _comparison_against_speed(
    grid: Any, approximate: ImpactCurves, transient: ImpactCurves, run_speeds: NDArray[np.float64]
) -> None:
    """One racket speed's two rows (rebound ratio, contact time) × supports of
    :func:`figure_transient_comparison_speed`."""
    supports = approximate.supports
    names = list(approximate.labels)
    speeds = approximate.ball_speed
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.85, len(names)))
    for p in range(len(supports)):
        for row, (quantity, label, scale) in enumerate(
            (("rebound_ratio", "rebound ratio e (–)", 1.0), ("contact_time", "T_c (ms)", 1e3))
        ):
            ax = grid[row, p]
            for i, (name, colour) in enumerate(zip(names, colours, strict=True)):
                x = approximate.locations[i, 0]
                for result, style, model_name in (
                    (approximate, "--", "approximate"),
                    (transient, "-", "transient"),
                ):
                    values = np.where(
                        result.status[i, :, p] == "ok",
                        np.asarray(getattr(result, quantity))[i, :, p],
                        np.nan,
                    )
                    ax.plot(
                        speeds,
                        values * scale,
                        style,
                        color=colour,
                        marker="o" if style == "-" else None,
                        markersize=3,
                        label=f"{name} ({x * 1e3:.0f} mm), {model_name}",
                    )
                    if style == "-":
                        _mark_run_speeds(ax, speeds, values * scale, run_speeds)
            # rows either method flags (vibration loss, second contact …): hatched, counted
            flagged = np.stack(
                [r.status[: len(names), :, p] != "ok" for r in (approximate, transient)]
            )  # (method, point, speed)
            mark_flagged_spans(
                ax,
                np.asarray(speeds, dtype=float),
                flagged.transpose(2, 0, 1).reshape(len(speeds), -1),
                "impacts of the two methods",
                flagged.size,
            )
            ax.set_ylabel(label)
            ax.grid(alpha=0.3)
            if row == 1:
                ax.set_xlabel("incoming ball speed (m/s)")


_NAMED_MODES = 4
"""The modal coordinates' legend names at most this many modes, the largest."""

_NAMED_SHARE = 0.05
"""… each peaking at this share of the largest peak or more; the rest are drawn grey and
summed up in one entry (the trial racket's 8 modes × 2 supports made 16 entries over the
curves; every number is in transient_histories.csv)."""

_SMALL_MODES = "0.7"
"""The colour of the modes the legend does not name."""


def _largest_modes(peaks: NDArray[np.float64]) -> list[int]:
    """The modes the legend names, largest first, from each mode's largest |q|
    (:data:`_NAMED_MODES`, :data:`_NAMED_SHARE`)."""
    order = [int(k) for k in np.argsort(-peaks, kind="stable")]
    return [k for k in order[:_NAMED_MODES] if peaks[k] >= _NAMED_SHARE * peaks[order[0]]]


def _modal_legend(
    ax: Axes, histories: TransientHistories, peaks: NDArray[np.float64], colours: Any
) -> list[int]:
    """The modal coordinates' legend entries, as empty lines in ``ax``: the largest modes in
    their colours, the others in one grey entry with their largest peak (``peaks``: each
    mode's, m·√kg), and each support's line style.  Returns the modes named."""
    named = _largest_modes(peaks)
    for k in named:
        ax.plot([], [], color=colours[k], label=histories.mode_names[k])
    rest = [k for k in range(peaks.size) if k not in named]
    if rest:
        largest = float(np.max(peaks[rest])) * 1e3
        label = f"{len(rest)} more modes (largest peak {largest:.2g} mm·√kg)"
        ax.plot([], [], color=_SMALL_MODES, label=label)
    for support in dict.fromkeys(histories.supports):
        ax.plot([], [], color="0.2", linestyle=_SUPPORT_LINES.get(support, "-."), label=support)
    return named


def figure_transient_histories(
    histories: TransientHistories, axes: Sequence[Axes] | None = None
) -> Figure:
    """Time histories of simulated impacts: force, displacements, modal coordinates.

    One column per impact point, one line per support (modal coordinates: one colour per mode,
    one line style per support; their legend, under the figure, names the largest modes and
    sums up the rest, drawn grey: :func:`_modal_legend`).

    Parameters
    ----------
    histories : TransientHistories
        The run's simulated impacts (:meth:`racketdyn.workflows.figure_data.
        TransientHistories.of`).
    axes : sequence of Axes, optional
        Three rows (force, displacements, modal coordinates) of one per impact point to draw into,
        their figure, size and layout the caller's; default a figure of its own
        (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that many).
    """
    mode_names = histories.mode_names
    points = list(dict.fromkeys(histories.points))
    figure, grid = axes_grid(
        axes, 3, len(points), figsize=(5.0 * len(points), 8.0), layout="constrained", squeeze=False
    )
    mode_colours = plt.get_cmap("tab10")(np.arange(max(len(mode_names), 1)) % 10)
    named: list[int] = []
    if mode_names:  # each mode's largest |q| over every impact drawn, m·√kg
        peaks = np.nanmax(np.abs(histories.modal_coordinates), axis=(0, 1))
        named = _modal_legend(grid[2, 0], histories, peaks, mode_colours)
    for column, point in enumerate(points):
        force_ax, move_ax, modal_ax = grid[:, column]
        rows = [k for k, name in enumerate(histories.points) if name == point]
        for row in rows:
            support = histories.supports[row]
            style = _support_style(support)
            line = _SUPPORT_LINES.get(support, "-.")
            at = histories.samples(row)
            time_ms = histories.time[row, at] * 1e3
            force_ax.plot(
                time_ms, histories.force[row, at], color=style["color"], label=style["label"]
            )
            move_ax.plot(
                time_ms,
                histories.ball_displacement[row, at] * 1e3,
                color=style["color"],
                label=f"ball, {support}",
            )
            move_ax.plot(
                time_ms,
                histories.face_displacement[row, at] * 1e3,
                color=style["color"],
                linestyle=":",
                label=f"racket face, {support}",
            )
            for k, name in enumerate(mode_names):
                modal_ax.plot(
                    time_ms,
                    histories.modal_coordinates[row, at, k] * 1e3,
                    color=mode_colours[k] if k in named else _SMALL_MODES,
                    linestyle=line,
                    label=f"_{name}, {support}",  # the legend is _modal_legend's
                )
        first = rows[0]
        x, y = histories.locations[first]
        racket_speed = histories.racket_speed[first]
        force_ax.set_title(
            f"{point}: x = {x * 1e3:.0f} mm, y = {y * 1e3:.0f} mm, "
            f"{histories.ball_speed[first]:g} m/s"
            + (f", racket {racket_speed:g} m/s" if racket_speed else ", racket at rest"),
            fontsize=9,
        )
        force_ax.set_ylabel("contact force (N)")
        move_ax.set_ylabel("displacement into the strings (mm)")
        modal_ax.set_ylabel("modal coordinate q (mm·√kg)")
        modal_ax.set_xlabel("time from first contact (ms)")
        if not mode_names:
            modal_ax.text(
                0.5, 0.5, "rigid racket: no modes", ha="center", transform=modal_ax.transAxes
            )
        modal_ax.grid(alpha=0.3)
        for ax in (force_ax, move_ax):
            ax.grid(alpha=0.3)
            ax.legend(fontsize=6)
    if mode_names:  # under the figure: beside or on the panels it covered the curves
        _legend_below(grid[2, 0], fontsize=7, columns=4)
    figure.suptitle(
        "Transient simulation: contact force, ball and racket-face displacement (dotted) and "
        "modal coordinates",
        fontsize=10,
    )
    return figure


# --- the swinging racket, twist and oblique impacts (issue 5) ------------------------------------
def figure_swing_map(
    result: SwingResult,
    racket: Racket,
    spots: Mapping[str, SweetSpot] | None = None,
    speed_index: int = 0,
) -> Figure:
    """Outgoing ball speed over the face of the swinging racket, with the sweet spots.

    Parameters
    ----------
    result : SwingResult
        Impacts over the face (:func:`racketdyn.impact.swing.predict_swing`).
    racket : Racket
        The racket (outline, swing description).
    spots : mapping of str to SweetSpot, optional
        Sweet spots to mark (:func:`racketdyn.impact.swing.sweet_spots`).
    speed_index : int
        Which incoming ball speed of the result.
    """
    figure, ax = plt.subplots(figsize=(6.8, 5.0), layout="constrained")
    plot_swing_map(result, racket, spots, speed_index, ax=ax)
    swing = result.swing
    how = (
        "given angular speed"
        if swing.angular_speed_radps is not None
        else f"{swing.torque_nm:g} N·m over {math.degrees(swing.swing_angle_rad):.0f}°"
    )
    figure.suptitle(
        f"Swinging racket ({how}), {result.inputs.get('impact_model', 'approximate')} model",
        fontsize=10,
    )
    return figure


def figure_swing_along_axis(
    curves: SwingAxisCurves, spots: Mapping[str, SweetSpot] | None = None
) -> Figure:
    """Outgoing ball speed along the long axis for the racket at rest and a few swings.

    Parameters
    ----------
    curves : SwingAxisCurves
        The curves (:func:`racketdyn.workflows.figure_data.swing_axis_curves`).
    spots : mapping of str to SweetSpot, optional
        Sweet spots to mark as vertical lines.
    """
    figure, ax = plt.subplots(figsize=(7.5, 6.0), layout="constrained")
    plot_swing_along_axis(list(curves.curves), spots, curves.support, ax=ax, names=curves.names)
    _legend_below(ax)
    figure.suptitle(
        f"Outgoing ball speed along the long axis, ball {curves.ball_speed:g} m/s, "
        f"{curves.model} model\nsweet spots for the swing {curves.swing_description}",
        fontsize=10,
    )
    return figure


def figure_twist(curves: Sequence[TwistCurve], axes: Sequence[Axes] | None = None) -> Figure:
    """Roll angle and outgoing ball speed against the offset from the long axis, per support.

    Parameters
    ----------
    curves : sequence of TwistCurve
        One per support, at the same x and ball speed
        (:func:`racketdyn.impact.twist.twist_curve`).
    axes : sequence of Axes, optional
        Two (roll angle, outgoing speed) to draw into, their figure, size and layout the caller's;
        default a figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an error if
        not that many).
    """
    figure, grid = axes_grid(axes, 1, 2, figsize=(10.0, 4.0), layout="constrained")
    for curve in curves:
        plot_twist_curve(curve, "roll_angle_rad", ax=grid[0])
        plot_twist_curve(curve, "rebound_speed_mps", ax=grid[1])
    first = curves[0]
    figure.suptitle(
        f"Off-axis impacts at x = {first.x_m * 1e3:.0f} mm, ball {first.ball_speed_mps:g} m/s"
        + (f", racket {first.racket_speed_mps:g} m/s" if first.racket_speed_mps else "")
        + ": the racket's roll at separation and the outgoing ball speed",
        fontsize=10,
    )
    return figure


def figure_oblique(
    curve: ObliqueCurve,
    location: tuple[float, float],
    support: str,
    contact: TangentialContact,
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Outgoing angle and spin against the incoming angle (oblique impacts at one point).

    Parameters
    ----------
    curve : ObliqueCurve
        From :func:`racketdyn.impact.oblique.oblique_curve`.
    location : tuple of float
        Impact point (x, y), m.
    support : str
        Support condition of the normal impact.
    contact : TangentialContact
        The tangential contact used (μ, k_t), for the title.
    axes : sequence of Axes, optional
        Two (outgoing angle, spin) to draw into, their figure, size and layout the caller's; default
        a figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an error if not that
        many).
    """
    figure, grid = axes_grid(axes, 1, 2, figsize=(10.0, 4.0), layout="constrained")
    plot_oblique_curve(curve, "outgoing_angle_deg", ax=grid[0])
    plot_oblique_curve(curve, "outgoing_spin_radps", ax=grid[1])
    stiffness = "rigid grip" if contact.rigid else f"k_t = {contact.stiffness_n_per_m:.3g} N/m"
    figure.suptitle(
        f"Oblique impacts at x = {location[0] * 1e3:.0f} mm, y = {location[1] * 1e3:.0f} mm, "
        f"{case_words(curve.ball_speed_mps, curve.racket_speed_mps, support)}: "
        f"μ = {contact.friction_coefficient:g}, "
        f"{stiffness} (spin depends strongly on k_t)",
        fontsize=10,
    )
    return figure
