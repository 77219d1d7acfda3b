"""Figures of ``racketdyn compound``: the ball on the strings (paper, Figs 8–9).

The responses come from :mod:`racketdyn.workflows.compound` (computed by
:class:`racketdyn.impact.compound.CompoundSystem`); this module only draws them.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from racketdyn.plotting.primitives import SUPPORT_STYLE, axes_grid, label_lines
from racketdyn.plotting.registry import draw, file_of, for_step
from racketdyn.plotting.render import save_figure
from racketdyn.racket_modal.shapes import BALL_MODE_NAME

if TYPE_CHECKING:
    from racketdyn.workflows.compound import CompoundFigures, CompoundResult
    from racketdyn.workflows.frf_figures import BallFrfs

__all__ = [
    "BALL_COMPARISON_FIGURE",
    "COINCIDE",
    "COMPOUND_FRF_FIGURE",
    "COMPOUND_RESPONSE_FIGURE",
    "COMPOUND_SHAPE_FIGURE",
    "coinciding_supports",
    "figure_ball_comparison",
    "figure_compound_frf",
    "figure_compound_response",
    "figure_compound_shape",
    "neck_reading",
    "plot_ball_mode_shape",
    "plot_compound_frf",
    "plot_neck_response",
    "write_compound_figures",
]

log = logging.getLogger(__name__)

COMPOUND_RESPONSE_FIGURE = file_of("compound_response")
"""The neck's acceleration after the hammer blow, ball on the strings (Fig. 8c)."""
COMPOUND_FRF_FIGURE = file_of("compound_frf")
"""Receptance hammer → neck without and with the ball (Fig. 9a, 9b)."""
COMPOUND_SHAPE_FIGURE = file_of("compound_shape")
"""The ball mode: the frame along its axis against the ball (Fig. 8a)."""
BALL_COMPARISON_FIGURE = file_of("fig9_frf_alone_and_ball")
"""``compare --ball-at``: measured FRFs of the racket alone and with the ball (Fig. 9a, 9b)."""

# each support its own line and ball marker, so curves lying on each other all show: the pinned
# racket's rigid-body motion differs from the free one's only far from the ball (new-user trial,
# 2026-11-26), and the hand hardly acts on the ball mode (free and hand frames within 0.4 %)
_LINESTYLE = {"free": "-", "pinned": (0, (4, 2)), "hand": "-."}
_BALL_MARKER = {"free": ("o", 8.0), "pinned": ("s", 11.0), "hand": ("^", 14.0)}
COINCIDE = 0.01
"""Frames of two supports whose ball-mode shapes differ by less than this share of the ball's
displacement lie on one another in Fig. 8a (about a pixel); the figure says so."""


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
    ax.plot(
        x_mm, np.asarray(frame), color=colour, lw=1.2, label=f"frame, {support}",
        linestyle=_LINESTYLE.get(support, "-"),
    )  # fmt: skip
    marker, size = _BALL_MARKER.get(support, ("o", 8.0))
    ax.plot(
        [ball_x * 1e3], [ball], marker, color=colour, ms=size, mfc="none", label=f"ball, {support}"
    )
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("x from the butt (mm)")
    ax.set_ylabel("displacement (ball = 1)")
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5))
    return ax


def coinciding_supports(result: CompoundFigures) -> str:
    """Words for Fig. 8a naming the supports whose ball-mode frames lie on one another
    (within :data:`COINCIDE` of the ball's displacement), with the largest difference and
    their ball-mode frequencies; empty when every frame stands apart."""
    supports = list(result.ball_shape)
    words = []
    for i, first in enumerate(supports):
        for second in supports[i + 1 :]:
            (a, ball_a), (b, ball_b) = result.ball_shape[first], result.ball_shape[second]
            difference = float(np.max(np.abs(np.asarray(a) / ball_a - np.asarray(b) / ball_b)))
            if difference < COINCIDE:
                words.append(
                    f"{first} and {second} coincide: frames within {100 * difference:.1f} %\n"
                    "of the ball's displacement (ball mode "
                    f"{result.ball_frequency_hz[first]:.2f} and "
                    f"{result.ball_frequency_hz[second]:.2f} Hz)"
                )
    return "\n".join(words)


def plot_neck_response(
    times: ArrayLike,
    acceleration: ArrayLike,
    ball_hz: float,
    bending_hz: float,
    label: str = "",
    ax: Axes | None = None,
    parts: Mapping[str, ArrayLike] | None = None,
    hand_over_s: float = math.nan,
) -> Axes:
    """The neck's acceleration against time, with the ball mode's and 2-node mode's parts.

    Parameters
    ----------
    times : array_like
        Times, s.
    acceleration : array_like
        Acceleration per unit impulse of the hammer's blow, m/s² per N·s.
    ball_hz, bending_hz : float
        Frequencies of the ball mode and of the 2-node bending mode, Hz (for the labels).
    label : str
        Legend label of the whole response.
    ax : Axes, optional
        Where to draw.
    parts : mapping of str to array_like, optional
        The ``ball`` and ``2-node bending`` parts of the response (drawn thin, so the reader
        sees which leads).
    hand_over_s : float
        When the 2-node mode becomes the larger, s (a dotted line; NaN: none).
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 3.6), layout="constrained")
    t_ms = np.asarray(times) * 1e3
    ax.plot(
        t_ms, np.asarray(acceleration), lw=1.1, color="0.55",
        label=f"neck, {label}" if label else "neck",
    )  # fmt: skip
    for name, colour, hz in (("ball", "C0", ball_hz), ("2-node bending", "C1", bending_hz)):
        if parts is not None and name in parts:
            part = np.asarray(parts[name], dtype=float)
            start = int(np.argmax(part != 0.0))  # the parts begin after the blow: no step
            ax.plot(
                t_ms[start:], part[start:], lw=0.8, color=colour,
                label=f"{'ball mode' if name == 'ball' else name} {hz:.1f} Hz",
            )  # fmt: skip
    if math.isfinite(hand_over_s):
        ax.axvline(hand_over_s * 1e3, color="0.3", lw=0.7, ls=":")
        ax.text(  # left of the line: to its right it ran past the axes near the record's end
            hand_over_s * 1e3, 0.03, "2-node takes over ", transform=ax.get_xaxis_transform(),
            fontsize=7, color="0.3", ha="right",
        )  # fmt: skip
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("neck acceleration\n(m/s² per N·s)")
    ax.legend(fontsize=7, loc="upper right")
    return ax


def neck_reading(hand_over: Mapping[str, float]) -> str:
    """Fig. 8c in words: which mode leads at the neck after the blow, and whether and when the
    2-node mode takes over; empty without a reading.

    Parameters
    ----------
    hand_over : mapping of str to float
        One support's ``ball_to_two_node`` (the modes' amplitudes after the blow, their ratio)
        and ``ball_cycles`` (when the 2-node mode becomes the larger, in ball-mode cycles: 0
        from the start, inf never), as :attr:`racketdyn.workflows.CompoundResult.hand_over`.
    """
    ratio = float(hand_over.get("ball_to_two_node", math.nan))
    cycles = float(hand_over.get("ball_cycles", math.nan))
    if not math.isfinite(ratio) or math.isnan(cycles):
        return ""
    if ratio <= 1.0:
        return f"the 2-node mode leads from the start (the ball mode {ratio:.2f}× as large)"
    if math.isinf(cycles):
        return f"the ball mode leads ({ratio:.1f}×) throughout: it decays more slowly"
    return (
        f"the ball mode leads ({ratio:.1f}×); the 2-node mode takes over after {cycles:.1f} "
        "ball cycles"
    )


def plot_compound_frf(
    frequency: ArrayLike,
    receptance: ArrayLike,
    label: str,
    support: str = "free",
    dashed: bool = False,
    ax: Axes | None = None,
) -> Axes:
    """The receptance's magnitude against frequency (log scale).

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
        Dashed line (the racket alone); else the support's line style (the pinned racket's
        curves, which often coincide with the free one's, dashed).
    ax : Axes, optional
        Where to draw.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 3.6), layout="constrained")
    colour = SUPPORT_STYLE.get(support, {}).get("color", "tab:orange")
    style = {"color": colour, "linestyle": "--" if dashed else _LINESTYLE.get(support, "-")}
    ax.semilogy(np.asarray(frequency), np.abs(np.asarray(receptance)), label=label, lw=1.0, **style)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("|receptance| hammer → neck (m/N)")
    ax.legend(fontsize=8)
    return ax


def _mark_mode(ax: Axes, frequency_hz: float, label: str, colour: str) -> None:
    """A dotted vertical line at a mode's frequency, ``label`` (if any) above the axes over it:
    written along the line it crossed the receptance curves (Fig. 9b)."""
    if label:
        label_lines(ax, [(frequency_hz, label, colour)], fontsize=7, linewidth=0.6)
    else:
        ax.axvline(frequency_hz, color=colour, lw=0.6, ls=":")


def figure_compound_response(result: CompoundFigures) -> Figure:
    """Fig. 8c: the neck's acceleration after a blow on the strings, the first support's (one
    panel: the page is near its size budget; the CSV and run.json hold every support).

    Parameters
    ----------
    result : CompoundFigures
        What the step computed for its figures (its responses).
    """
    support = result.supports[0]
    ball_hz = result.ball_frequency_hz[support]
    figure, ax = plt.subplots(figsize=(6.2, 3.0), layout="constrained")
    hand_over = result.hand_over.get(support, {})
    cycles = float(hand_over.get("ball_cycles", math.nan))
    blow = result.blow_s.get(support, 0.0)
    plot_neck_response(
        result.times,
        result.neck_acceleration[support],
        ball_hz,
        result.two_node_frequency_hz[support],
        support,
        ax=ax,
        parts=result.neck_parts.get(support),
        hand_over_s=blow + cycles / ball_hz if 0 < cycles < math.inf else math.nan,
    )
    away_mm = math.dist(result.location, result.hammer) * 1e3
    reading = neck_reading(hand_over)
    ax.set_title(
        f"Fig. 8c: the neck after a blow on the strings {away_mm:.0f} mm from the ball ({support})"
        + (f"\n{reading}" if reading else ""),
        fontsize=9,
    )
    return figure


def figure_compound_frf(result: CompoundFigures, axes: Sequence[Axes] | None = None) -> Figure:
    """Fig. 9: receptance hammer → neck without and with the ball, every support.

    Parameters
    ----------
    result : CompoundFigures
        What the step computed for its figures.
    axes : sequence of Axes, optional
        Two ((a) alone, (b) with the ball) to draw into, their figure, size and layout the caller's;
        default a figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an error if
        not that many).
    """
    figure, grid = axes_grid(axes, 1, 2, figsize=(8.0, 2.7), layout="constrained", sharey=True)
    for support in result.supports:
        plot_compound_frf(result.frequency, result.frf_alone[support], support, support, ax=grid[0])
        plot_compound_frf(
            result.frequency, result.frf_with_ball[support], support, support, ax=grid[1]
        )
    grid[0].set_title("(a) the racket alone", fontsize=9)
    grid[1].set_title("(b) the racket with the ball on the strings", fontsize=9)
    grid[1].set_ylabel("")  # shared with (a)
    for support in result.supports[:1]:
        f_ball = result.ball_frequency_hz[support]
        _mark_mode(grid[1], f_ball, f"ball mode {f_ball:.1f} Hz", "0.5")
    figure.suptitle("Fig. 9: receptance hammer → neck without and with the ball", fontsize=10)
    return figure


def figure_compound_shape(result: CompoundFigures) -> Figure:
    """Fig. 8a: the ball mode, the frame along its axis against the ball, per support.

    Parameters
    ----------
    result : CompoundFigures
        What the step computed for its figures.
    """
    figure, ax = plt.subplots(figsize=(6.0, 3.0), layout="constrained")
    for support, (frame, ball) in result.ball_shape.items():
        plot_ball_mode_shape(result.axis_x, frame, result.location[0], ball, support, ax=ax)
    together = coinciding_supports(result)
    if together:  # where the curves lie on one another, in words: the reader sees one line
        ax.text(0.02, 0.04, together, transform=ax.transAxes, fontsize=6.5, va="bottom")
    ax.set_title("Fig. 8a: the ball mode, ball and frame against\neach other through the strings",
                 fontsize=9)  # fmt: skip
    return figure


def write_compound_figures(result: CompoundResult, out: Path) -> list[Path]:
    """Draw the registry's figures of ``compound`` (Figs 8a, 8c and 9) into ``out``, one after
    another in this process; returns the paths.

    Parameters
    ----------
    result : CompoundResult
        The step's result.
    out : Path
        Output folder.
    """
    paths = [
        save_figure(draw(figure.id, result), Path(out) / figure.file)
        for figure in for_step("compound")
    ]
    for path in paths:
        log.info("wrote %s", path)
    return paths


def figure_ball_comparison(data: BallFrfs, axes: Sequence[Axes] | None = None) -> Figure:
    """The measured FRFs of the racket alone and with the ball (paper, Figs 9a and 9b).

    One FRF from each set: the hammer point nearest the ball that both sets hold and whose FRF
    shows the ball mode (the step's ``shown_node``,
    :func:`racketdyn.workflows.identify.node_showing_ball_mode`; the paper struck the strings
    slightly away from the ball), against the accelerometer; the identified
    modes marked, the ball's labelled.  Drawn as accelerance, whose rigid-body part is flat
    (the paper's compliance falls as 1/f² there and hides the ball's heavily damped peak).

    Parameters
    ----------
    data : BallFrfs
        What ``compare --ball-at`` chose to draw
        (:func:`racketdyn.workflows.frf_figures.ball_frfs`).
    axes : sequence of Axes, optional
        Two ((a) alone, (b) with the ball) to draw into, their figure, size and layout the caller's;
        default a figure of its own (:func:`racketdyn.plotting.primitives.axes_grid`: an error if
        not that many).
    """
    alone, ball = data.alone, data.with_ball
    node = alone.nodes[0]
    x, y = ball.locations[0, 0], ball.locations[0, 1]
    top = 3.0 * max([*data.with_ball_hz[:2], *data.alone_hz[:1], 100.0])
    figure, grid = axes_grid(axes, 1, 2, figsize=(8.0, 2.8), layout="constrained", sharey=True)
    for ax, frfs in ((grid[0], alone), (grid[1], ball)):
        keep = (frfs.frequency > 0) & (frfs.frequency <= top)
        ax.semilogy(frfs.frequency[keep], np.abs(frfs.values[0, keep]), lw=0.9, color="tab:blue")
        ax.set_xlabel("frequency (Hz)")
    keep = (alone.frequency > 0) & (alone.frequency <= top)
    grid[1].semilogy(
        alone.frequency[keep], np.abs(alone.values[0, keep]), lw=0.7, color="0.6", ls="--",
        label="racket alone",
    )  # fmt: skip
    grid[0].set_ylabel("|accelerance| (m/(N·s²))", fontsize=8)
    for ax, frequency, names in (
        (grid[0], data.alone_hz, data.alone_names),
        (grid[1], data.with_ball_hz, data.with_ball_names),
    ):
        for f, name in zip(frequency, names, strict=True):
            if f > top:
                continue
            if name == BALL_MODE_NAME:
                _mark_mode(ax, f, f"{name} {f:.1f} Hz", "tab:red")
            else:
                _mark_mode(ax, f, "", "0.7")
    grid[0].set_title("(a) the racket alone", fontsize=9)
    grid[1].set_title("(b) with the ball on the strings", fontsize=9)
    grid[1].legend(fontsize=8, loc="lower right")
    figure.suptitle(
        f"Fig. 9: hammer at node {node} (x = {1e3 * x:.0f} mm, y = {1e3 * y:.0f} mm) → "
        f"accelerometer, ball at "
        f"x = {1e3 * data.ball_at[0]:.0f} mm, y = {1e3 * data.ball_at[1]:.0f} mm "
        f"({data.support})",
        fontsize=9,
    )
    return figure
