"""The one registry of figures: every PNG a step writes, once (issue 23).

Each :class:`FigureEntry` names a figure's id (its file stem), its file, the step that writes
it, the paper's figure, its caption, its place in the report (or why it has none), and — for a
figure drawn from the step's result data alone — its draw function and the result attributes
it reads.  The step's figure hook (:func:`write_figures`), ``result.plot(id)``, the report's
captions and placement (:mod:`racketdyn.report`) and the documentation's list of figures
(``docs/figures.md``, :func:`markdown`) all come from here, and ``tests/test_figure_registry.py``
walks it.  Adding a figure: its draw function in a plotting module, and its entry here.

Importing this module loads no matplotlib: a draw function is named ``"module:function"`` and
imported when a figure is drawn.
"""

from __future__ import annotations

import importlib
import logging
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = [
    "CAPTION_DEFAULTS",
    "FIGURES",
    "FigureEntry",
    "draw",
    "entry",
    "file_of",
    "for_step",
    "in_section",
    "labelled",
    "markdown",
    "of_file",
    "write_figures",
]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class FigureEntry:
    """One figure of the registry.

    Parameters
    ----------
    id : str
        The figure's name: its file stem (``"fig15_rebound_along_axis"``).
    step : str
        The command (step) that writes it.
    caption : str
        What it shows, a sentence without its final full stop; ``{field}`` are the run's
        settings in words (:func:`racketdyn.report.figures.run_words`).
    paper : str or None
        The figure of Kawazoe's paper it corresponds to (``"Fig. 15"``), or None.
    section : str or None
        The report section it is shown in (a key of :data:`racketdyn.report.SECTIONS`).
    not_in_report : str
        Why it is not in the report (then ``section`` is None).
    draw : str
        ``"module:function"`` of a function that only draws: ``function(*data) -> Figure``, its
        arguments the step result's attributes ``reads``; a one-panel figure's function may
        take ``ax`` after them and return it (``function(*data, ax=None) -> Axes``: a user
        draws it into a figure of their own; the registry saves the axes' figure).
    reads : tuple of str
        The attributes of the step's result (or the keys of the data read back from its folder,
        :func:`racketdyn.workflows.figure_data.read_step_data`) that ``draw`` takes; a dotted
        name reaches into one (``"inputs.effective_racket"``). Every one is in the step's run
        folder: the figure redraws from the folder alone (``tests/test_redraw_from_folder.py``).
    labelled : bool
        The step may write it once per model, ``<id>_<label>.png`` (``compare``: ``_free``,
        ``_hand``).
    ignore_float_errors : bool
        Drawn with NumPy's overflow and invalid-value errors ignored (mplot3d's projection
        overflows on the NaN outside the face of some surfaces; harmless).
    draw_first : bool
        Among the slowest of its step's figures to draw: built and queued before the others, so
        that the figure helper process draws it while this process builds the rest and writes
        the step's other files (:func:`write_figures`; the files and their order are the same).

    A read that is None gives no figure (Figs 4–5 of shapes without coordinates, Fig. 6 of a
    structure that is not a racket); nor does a draw function that returns None; the step then
    writes no file for it.
    """

    id: str
    step: str
    caption: str
    paper: str | None = None
    section: str | None = None
    not_in_report: str = ""
    draw: str = ""
    reads: tuple[str, ...] = ()
    labelled: bool = False
    ignore_float_errors: bool = False
    draw_first: bool = False

    @property
    def file(self) -> str:
        """Its file name."""
        return f"{self.id}.png"

    def file_for(self, label: str = "") -> str:
        """Its file name for one model's label (``fig4_mode_shapes_free.png``)."""
        return f"{self.id}_{label}.png" if label else self.file

    def drawer(self) -> Callable[..., Any]:
        """The draw function (imports its module, and matplotlib)."""
        if not self.draw:
            raise ValueError(f"figure {self.id!r} is drawn by its step's writer only")
        module, _, name = self.draw.partition(":")
        function: Callable[..., Any] = getattr(importlib.import_module(module), name)
        return function

    def data(self, source: object) -> tuple[Any, ...] | None:
        """The draw function's arguments from ``source`` (a step result, or a mapping of the data
        read back from a run folder); None when any is missing (the figure is not drawn)."""
        values = []
        for name in self.reads:
            value: Any = source
            for part in name.split("."):
                value = (
                    value.get(part) if isinstance(value, Mapping) else getattr(value, part, None)
                )
            if value is None:
                return None
            values.append(value)
        return tuple(values)


_FIGURES = "racketdyn.plotting.figures"
_COMPOUND = "racketdyn.plotting.compound"
_BALL = "racketdyn.plotting.ball"
_VALIDATE = "racketdyn.plotting.validate"
_SWEEP = "racketdyn.plotting.sweep"

FIGURES: dict[str, FigureEntry] = {
    e.id: e
    for e in (
        # --- frf --------------------------------------------------------------------------
        FigureEntry(
            "fig2_frf_frame",
            "frf",
            "FRF for an impact on the frame at the accelerometer (driving point): magnitude, "
            "phase and coherence",
            paper="Fig. 2",
            section="quality",
            draw=f"{_FIGURES}:figure_frf_frame",
            reads=("frf_points",),
        ),
        FigureEntry(
            "fig3_frf_string_centre",
            "frf",
            "FRF for an impact at the string-bed centre: magnitude, phase and coherence",
            paper="Fig. 3",
            section="quality",
            draw=f"{_FIGURES}:figure_frf_string_centre",
            reads=("frf_points",),
        ),
        # --- identify (compare: once per model, _free and _hand) --------------------------
        FigureEntry(
            "stabilisation",
            "identify",
            "LSCF stabilisation diagram: poles of every model order against frequency, with the "
            "selected modes",
            section="stabilisation",
            labelled=True,
            draw=f"{_FIGURES}:figure_stabilisation",
            reads=("fit_figures",),
        ),
        FigureEntry(
            "fig4_mode_shapes",
            "identify",
            "identified mode shapes in 3-D over the racket",
            paper="Fig. 4",
            section="modes",
            labelled=True,
            draw=f"{_FIGURES}:figure_mode_shapes",
            reads=("shape_figures.shapes",),
            ignore_float_errors=True,
        ),
        FigureEntry(
            "fig5_node_lines",
            "identify",
            "node lines of the identified modes on the string face",
            paper="Fig. 5",
            section="modes",
            labelled=True,
            draw=f"{_FIGURES}:figure_node_lines",
            reads=("shape_figures.shapes",),
        ),
        FigureEntry(
            "fig6_nodes",
            "identify",
            "node positions of the first mode along the long axis",
            paper="Fig. 6",
            section="modes",
            labelled=True,
            draw=f"{_FIGURES}:plot_axis_nodes",
            reads=("shape_figures.axis",),
        ),
        FigureEntry(
            "synthesised_frfs",
            "identify",
            "measured FRFs against those synthesised from the identified modal model "
            "(driving point and string-bed centre)",
            section="stabilisation",
            labelled=True,
            draw=f"{_FIGURES}:figure_synthesised_frfs",
            reads=("fit_figures",),
            draw_first=True,  # two log axes, 3,000-line FRFs: ≈ a quarter of identify's
        ),
        FigureEntry(
            "automac",
            "identify",
            "AutoMAC of the identified mode shapes: 1 on the diagonal; off it, how alike two "
            "modes look at the measured points (near 1: the points cannot tell them apart)",
            section="stabilisation",
            labelled=True,
            draw=f"{_FIGURES}:plot_automac",
            reads=("shape_figures.automac",),
        ),
        # --- compare ----------------------------------------------------------------------
        FigureEntry(
            "comparison",
            "compare",
            "frequency shift and damping ratio of each mode, hand-held ({hand_file}) against "
            "free ({free_file}), identified over {band} and paired by MAC",
            section="modes",
            draw=f"{_FIGURES}:figure_mode_comparison",
            reads=("comparison",),
        ),
        FigureEntry(
            "fig6_nodes_free_hand",
            "compare",
            "node positions of the first mode along the long axis, free (blue, {free_file}) "
            "against hand-held (black, {hand_file}), identified over {band}; the grey band is "
            "the hand",
            paper="Fig. 6",
            section="modes",
            draw=f"{_FIGURES}:plot_axis_nodes",
            reads=("nodes_free_hand",),
        ),
        FigureEntry(
            "fig15_identified",
            "compare",
            "rebound ratio along the long axis, ball at {check_speed}, racket at rest, predicted "
            "with the models identified from {free_file} and {hand_file}: pinned at the grip "
            "with the hand-held modes, pinned at the grip with the free modes, free with the "
            "free modes",
            paper="Fig. 15",
            section="rebound",
            draw=f"{_FIGURES}:plot_identified_rebound",
            reads=("rebound",),
        ),
        # --- contact ----------------------------------------------------------------------
        FigureEntry(
            "fig7_contact_time",
            "contact",
            "contact time of the hammer on the strings, per support",
            paper="Fig. 7",
            section="contact",
            draw=f"{_FIGURES}:figure_contact_time",
            reads=("tables", "labels", "racket"),
        ),
        # --- compound ---------------------------------------------------------------------
        FigureEntry(
            "compound_shape",
            "compound",
            "the ball mode: the frame's displacement along its long axis (line) against the "
            "ball's (marker), scaled so the ball's is 1, one colour, line style and marker per "
            "support; supports whose frames lie on one another are named on the figure",
            paper="Fig. 8a",
            section="compound",
            draw=f"{_COMPOUND}:figure_compound_shape",
            reads=("figure_data",),
        ),
        FigureEntry(
            "compound_response",
            "compound",
            "acceleration of the frame neck after a hammer blow on the strings near the ball "
            "fixed on them (a half-sine as long as the hammer's contact with the strings), per "
            "unit impulse, for the run's first support (linear compound model)",
            paper="Fig. 8c",
            section="compound",
            draw=f"{_COMPOUND}:figure_compound_response",
            reads=("figure_data",),
        ),
        FigureEntry(
            "compound_frf",
            "compound",
            "receptance from the hammer point on the strings to the frame neck, the racket alone "
            "(left) and with the ball fixed on the strings (right), with the ball mode marked",
            paper="Fig. 9",
            section="compound",
            draw=f"{_COMPOUND}:figure_compound_frf",
            reads=("figure_data",),
        ),
        # compare --ball-at, shown beside compound's Fig. 9
        FigureEntry(
            "fig9_frf_alone_and_ball",
            "compare --ball-at",
            "measured accelerance to the accelerometer from the hammer point nearest the ball "
            "whose FRF the ball mode dominates at its frequency (its node in the title), the "
            "racket alone (left) and with the ball fixed on the strings (right, the racket "
            "alone dashed), identified modes dotted, the ball's labelled (racketdyn compare "
            "--ball-at)",
            paper="Fig. 9",
            section="compound",
            draw=f"{_COMPOUND}:figure_ball_comparison",
            reads=("ball_frfs",),
        ),
        # --- predict: the paper's figures (approximate method) ----------------------------
        FigureEntry(
            "fig11_12_force_contact_time",
            "predict",
            "Fig. 11: equivalent (mean) impact force and Fig. 12: contact time against ball "
            "speed at the top, centre and throat of the face, for the run's supports, one row of "
            "panels per racket speed, titled with it ({racket_speed}); the run's speeds are "
            "marked on the row of their racket speed, its options are in the title; speeds where "
            "an impact is flagged (no valid value) are hatched, crosses at the foot mark each, "
            "and the legend counts them among the curves' own impacts (the three points × the "
            "curves' speeds × the supports: not the run's rows, which the console counts)",
            paper="Figs 11 and 12",
            section="impact",
            draw=f"{_FIGURES}:figure_force_and_contact_time",
            reads=("paper_figures",),
        ),
        FigureEntry(
            "fig13_pulse_spectrum",
            "predict",
            "eq 11's half sine of the impact's impulse at the face centre (peak π F_MEAN/2; the "
            "contact's own peak F_MAX is impact.csv's) and the magnitude of its spectrum for "
            "balls at {speeds}, {racket_speed} (support in the title), with the modes the "
            "prediction charges (dark, dotted) and the string bed's it does not charge (light, "
            "for reference): the faster the ball, the shorter the pulse and the higher its "
            "spectrum reaches",
            paper="Fig. 13",
            section="impact",
            draw=f"{_FIGURES}:figure_pulse_spectrum",
            reads=("paper_figures",),
        ),
        FigureEntry(
            "fig14_frame_vibration",
            "predict",
            "predicted first-mode displacement along the frame just after an impact at the tip, "
            "at the run's speeds, one panel per support; impacts the method flags have no valid "
            "vibration and are not drawn: the legend names them with their status and each "
            "panel says how many (hatched when none is valid)",
            paper="Fig. 14",
            section="vibration",
            draw=f"{_FIGURES}:figure_frame_vibration",
            reads=("paper_figures",),
        ),
        FigureEntry(
            "fig15_rebound_along_axis",
            "predict",
            "predicted rebound ratio along the long axis, ball at {shown_speed}, "
            "{shown_racket_speed}, {approximate_supports}, with the centre of percussion and the "
            "node of the first mode",
            paper="Fig. 15",
            section="rebound",
            draw=f"{_FIGURES}:figure_rebound_along_axis",
            reads=("paper_figures",),
        ),
        FigureEntry(
            "sensitivity",
            "predict",
            "which uncertain input dominates the rebound ratio at the face centre, tip, throat "
            "and 40 mm off the axis, ball at {shown_speed}: Sobol' total indices (light bars: "
            "the share of the variance an input takes part in) and first-order ones (dark: its "
            "own share), each with its 90 % interval; an interval reaching 0 is not told from no "
            "effect (with --uncertainty; sensitivity.csv holds the numbers)",
            section="rebound",
            draw=f"{_FIGURES}:figure_sensitivity",
            reads=("sensitivity",),
        ),
        FigureEntry(
            "face_maps",
            "predict",
            "maps over the face, ball at {shown_speed}, {shown_racket_speed}: rebound ratio for "
            "each support, contact time and vibration energy; red crosses mark impacts with no "
            "valid result, left out of every map; the paper shows the long axis only (Fig. 15)",
            section="rebound",
            draw=f"{_FIGURES}:figure_face_maps",
            reads=("paper_figures",),
            draw_first=True,  # four contour maps and their colour bars: ≈ 40 % of predict's
        ),
        # --- predict: the transient model (--model transient|both) ------------------------
        FigureEntry(
            "transient_comparison_face",
            "predict",
            "rebound ratio of the approximate method minus that of the transient simulation over "
            "the face, one panel per support, ball at {shown_speed}, {shown_racket_speed}; red "
            "where the approximate method predicts more; the paper checks its method against a "
            "freely suspended racket only",
            section="transient",
            draw=f"{_FIGURES}:figure_transient_comparison_face",
            reads=("comparison_map",),
        ),
        FigureEntry(
            "transient_comparison_speed",
            "predict",
            "rebound ratio and contact time against ball speed at the face centre, near the tip "
            "and near the throat, approximate method (dashed) against the transient simulation "
            "(solid), {racket_speed}; a curve breaks where its method flags the impact "
            "(vibration loss beyond e_BG, a second contact, …): the speeds are hatched at the "
            "foot, across the whole height where no curve is valid, and the legend counts them",
            section="transient",
            draw=f"{_FIGURES}:figure_transient_comparison_speed",
            reads=("transient_curves",),
        ),
        FigureEntry(
            "transient_histories",
            "predict",
            "time histories of the transient simulation at the face centre and near the tip: "
            "contact force (the approximate method assumes a half-sine, Fig. 13), ball and "
            "racket-face displacement, and the modal coordinates of the flexible modes (the "
            "largest named in the legend under the figure, the others grey and summed up in one "
            "entry; every mode's in transient_histories.csv)",
            section="transient",
            draw=f"{_FIGURES}:figure_transient_histories",
            reads=("transient_histories",),
        ),
        # --- swing, twist, oblique --------------------------------------------------------
        FigureEntry(
            "swing_map",
            "swing",
            "outgoing ball speed over the face of the swinging racket ({swing}), ball at "
            "{sweet_speed}, {support}, {impact_model} model, with the sweet spots: the centres "
            "of percussion about the swing axis and about the grip, the node of the first mode, "
            "the largest rebound ratio (racket at rest) and the largest outgoing speed for the "
            "swing; crosses mark impacts without a valid number",
            section="swing",
            draw=f"{_FIGURES}:figure_swing_map",
            reads=("swing_result", "racket", "spots", "shown_speed"),
        ),
        FigureEntry(
            "swing_along_axis",
            "swing",
            "outgoing ball speed along the long axis, ball at {sweet_speed}, {support}, "
            "{impact_model} model, for the racket at rest (the setting of the paper's Fig. 15) "
            "and for {axis_swings}, with the sweet spots of the run's swing ({swing}) as "
            "vertical lines",
            section="swing",
            draw=f"{_FIGURES}:figure_swing_along_axis",
            reads=("axis_curves", "spots"),
        ),
        FigureEntry(
            "twist",
            "twist",
            "off-axis impacts at one x: the racket's roll about its long axis at separation "
            "(left; positive turns the hit side away from the ball) and the outgoing ball speed "
            "(right) against the offset from the long axis, one line per support",
            section="oblique",
            draw=f"{_FIGURES}:figure_twist",
            reads=("curves",),
        ),
        FigureEntry(
            "oblique",
            "oblique",
            "oblique impacts at one point: outgoing angle to the face normal (left; dashed: the "
            "same impact without friction) and outgoing spin (right) against the incoming angle; "
            "filled markers where the ball gripped the strings, open where it slid throughout; "
            "the spin depends strongly on the tangential stiffness k_t",
            section="oblique",
            draw=f"{_FIGURES}:figure_oblique",
            reads=("curve", "point", "support", "contact"),
        ),
        # --- validate ---------------------------------------------------------------------
        FigureEntry(
            "validation_parity",
            "validate",
            "predicted against measured rebound ratio, approximate method and transient "
            "simulation, with the 1:1 line and the measured standard deviations as error bars; "
            "rows beyond ±3 standard deviations (standardised residual, validation.csv's z "
            "columns) are named; flagged rows are counted in the legend and not drawn",
            section="validation",
            draw=f"{_VALIDATE}:figure_validation_parity",
            reads=("measured", "predicted", "outlier_rank"),
        ),
        FigureEntry(
            "validation_along_axis",
            "validate",
            "measured rebound ratio (with one standard deviation where measured) and both "
            "models' predictions against the position along the long axis, every measured row",
            section="validation",
            draw=f"{_VALIDATE}:figure_validation_along_axis",
            reads=("measured", "predicted"),
        ),
        FigureEntry(
            "validation_residuals",
            "validate",
            "the transient simulation's residual (predicted − measured rebound ratio) over the "
            "face, one marker per support; flagged rows as crosses",
            section="validation",
            draw=f"{_VALIDATE}:figure_validation_residuals",
            reads=("measured", "predicted", "inputs.effective_racket"),
        ),
        # --- calibrate --------------------------------------------------------------------
        FigureEntry(
            "calibration_parity",
            "calibrate",
            "the rebound ratio before and after calibration against the measured, with the 1:1 "
            "line and the measured standard deviations as error bars; the rows held out of the "
            "fit ringed; rows beyond ±3 standard deviations after (calibration_rows.csv's "
            "z_after) are named; flagged rows are counted in the legend and not drawn",
            section="calibration",
            draw=f"{_VALIDATE}:figure_calibration_parity",
            reads=("measured", "parity_predicted", "parity_outliers", "held_out"),
        ),
        # --- ball, sweep: not in the report -----------------------------------------------
        FigureEntry(
            "ball_hysteresis",
            "ball",
            "force against compression, one loop per speed and surface: the ball's flattening "
            "on the rigid surface, ball and bed on the strings; the area of a loop is the energy "
            "the bounce loses",
            not_in_report="racketdyn ball is a check of the ball's law, not a step of the demo's "
            "pipeline; the report has no section for it",
            draw=f"{_BALL}:figure_ball_loops",
            reads=("bounces",),
        ),
        FigureEntry(
            "summary",
            "sweep",
            "rebound ratio at the face centre and face area above the threshold against one "
            "design variable, per support (one file per variable: summary_<variable>.png)",
            not_in_report="a sweep has its own folder (sweep.zarr, summary.csv); the report "
            "reads the demo's steps only",
            labelled=True,
            draw=f"{_SWEEP}:figure_summary",
            reads=("curves",),
        ),
    )
}
"""Figure id → :class:`FigureEntry`, in the order of the steps and of the report."""

CAPTION_DEFAULTS: dict[str, str] = {
    "free_file": "the free FRFs",
    "hand_file": "the hand-held FRFs",
    "band": "the band of the run",
    "check_speed": "20 m/s",  # what compare used before it took --speed
    "swing": "the run's swing",
    "sweet_speed": "the run's shown speed",
    "support": "the run's support",
    "impact_model": "the run's",
    "axis_swings": "half, the same and one and a half times the run's swing",
    "speeds": "the run's speeds",
    "shown_speed": "the run's shown speed (in the title)",
    "racket_speed": "the run's racket speed (in the title)",
    "shown_racket_speed": "the run's racket speed (in the title)",
    "approximate_supports": "for the run's supports",
}
"""The words of a caption's ``{field}`` when the run.json does not say (a run of an earlier
version), and in the documentation's list."""


def entry(figure: str) -> FigureEntry:
    """The entry of a figure id, or of a file name (``"face_maps.png"``)."""
    key = figure.removesuffix(".png")
    try:
        return FIGURES[key]
    except KeyError:
        raise KeyError(f"no figure {figure!r}; the registry has {', '.join(FIGURES)}") from None


def of_file(name: str) -> FigureEntry | None:
    """The entry of a file a step wrote (``fig4_mode_shapes_free.png``, ``summary_mass.png``),
    or None if the registry has none."""
    stem = name.removesuffix(".png")
    if stem in FIGURES:
        return FIGURES[stem]
    labelled = [e for e in FIGURES.values() if e.labelled and stem.startswith(f"{e.id}_")]
    return max(labelled, key=lambda e: len(e.id)) if labelled else None


def file_of(figure: str) -> str:
    """The file name of a figure id."""
    return entry(figure).file


def labelled(figure: str, suffix: str = "") -> str:
    """The file name of a figure id written for one model (``suffix`` ``"_free"`` or ``""``)."""
    return entry(figure).file_for(suffix.removeprefix("_"))


def for_step(step: str) -> Iterator[FigureEntry]:
    """The entries a step writes, in order."""
    return (e for e in FIGURES.values() if e.step == step)


def in_section(section: str) -> Iterator[FigureEntry]:
    """The entries a report section shows, in order."""
    return (e for e in FIGURES.values() if e.section == section)


def draw(figure: str, source: object, **options: Any) -> Any:
    """Draw one registered figure from a step's result or from a run folder's data.

    Parameters
    ----------
    figure : str
        Its id (or file name).
    source : object or mapping
        A step's result (``PredictResult``, …), or the mapping
        :func:`racketdyn.workflows.figure_data.read_step_data` reads from a run folder.
    **options
        The draw function's own keywords: ``axes=`` of the caller for a figure of several
        panels, ``ax=`` for one of a single panel (the draw function's documentation says
        which).

    Returns
    -------
    matplotlib.figure.Figure
    """
    if figure.removesuffix(".png") not in FIGURES:
        _unknown(figure, source)
    found = entry(figure)
    data = found.data(source)
    if data is None:
        raise ValueError(f"figure {found.id!r} needs {', '.join(found.reads)}: not all given")
    return _figure(found.drawer()(*data, **options))


def _unknown(figure: str, source: object) -> None:
    """Refuse an unknown figure id, naming the ids this source can draw and the closest."""
    import difflib

    here = [e.id for e in FIGURES.values() if e.draw and e.data(source) is not None]
    close = difflib.get_close_matches(figure, here or list(FIGURES), n=1, cutoff=0.3)
    close = close or [i for i in here if i.startswith(figure)][:1]
    hint = f"; did you mean {close[0]!r}?" if close else ""
    raise KeyError(f"no figure {figure!r}{hint} (this result draws {', '.join(here) or 'none'})")


def _figure(drawn: Any) -> Any:
    """The figure a draw function drew: itself, or the figure of the axes it returned."""
    from matplotlib.axes import Axes

    return drawn.get_figure(root=True) if isinstance(drawn, Axes) else drawn


def write_figures(
    step: str,
    result: object,
    out: Path,
    status: Callable[[str], None] | None = None,
    label: str = "",
) -> list[Path]:
    """Draw every registered figure of ``step`` whose data ``result`` holds into ``out``.

    Several figures are drawn as one batch (:class:`racketdyn.plotting.render.FigureBatch`:
    in a helper process while the next is built); one alone is saved here. With a batch, the
    step's deferred files (``result.pending``, :func:`racketdyn.workflows.run.defer_file`) are
    written once every figure is queued, while the helper draws. Entries marked
    ``draw_first`` are built first (the helper takes them), the others in the registry's order.

    Parameters
    ----------
    step : str
        The step (command).
    result : object or mapping
        Its result (the attributes each entry ``reads``), or a mapping of them.
    out : Path
        The run folder.
    status : callable, optional
        ``status(words)`` before each figure.
    label : str
        The model's label of a figure written once per model (``compare``: ``"free"``,
        ``"hand"``), in its file name.

    Returns
    -------
    list of Path
        The files written.
    """
    from contextlib import nullcontext

    import numpy as np

    from racketdyn.plotting import render
    from racketdyn.workflows.run import write_pending

    found = [(e, data) for e in for_step(step) if e.draw and (data := e.data(result)) is not None]
    found.sort(key=lambda entry_data: not entry_data[0].draw_first)  # stable: registry order
    batch = render.FigureBatch() if len(found) > 1 else None
    paths: list[Path] = []
    for k, (figure, data) in enumerate(found, 1):
        name = figure.file_for(label)
        if status is not None:
            status(f"drawing {name} ({k} of {len(found)} figures)")
        drawn = _figure(figure.drawer()(*data))
        if drawn is None:
            continue
        errors = np.errstate(over="ignore", invalid="ignore")
        with errors if figure.ignore_float_errors else nullcontext():  # the state it is drawn under
            if batch is None:
                paths.append(render.save_figure(drawn, Path(out) / name))
            else:
                batch.add(drawn, Path(out) / name)
    if batch is not None:
        try:  # the step's deferred files, while the helper process draws
            write_pending(result)
        except Exception:
            batch.render()  # every queued figure finished before the step's error goes up
            raise
        order = [e.file_for(label) for e in for_step(step)]
        paths = sorted(batch.render(), key=lambda path: order.index(path.name))
    for path in paths:
        log.info("wrote %s", path)
    return paths


def markdown(section_titles: Mapping[str, str] | None = None) -> str:
    """The documentation's list of figures, one table per step, from the registry (written by
    ``docs/conf.py`` into ``docs/_generated/figures.md`` at each build, included by
    ``docs/figures.md``); the run's settings in *italics*.

    Parameters
    ----------
    section_titles : mapping, optional
        Report section key → its title (:data:`racketdyn.report.SECTIONS`), for the "report"
        column; the key without.
    """
    lines: list[str] = []
    steps = list(dict.fromkeys(e.step for e in FIGURES.values()))
    words = {key: f"*{value}*" for key, value in CAPTION_DEFAULTS.items()}
    for step in steps:
        lines += [f"## {step}", "", "| file | paper | report | drawn from | what it shows |"]
        lines += ["|---|---|---|---|---|"]
        for e in for_step(step):
            name = f"`{e.id}_<label>.png`" if e.labelled else f"`{e.file}`"
            if e.labelled and e.step != "sweep":
                name = f"`{e.file}`, {name}"
            titles = section_titles or {}
            place = (
                titles.get(e.section, e.section) if e.section else f"not shown: {e.not_in_report}"
            )
            source = ", ".join(f"`{r}`" for r in e.reads) if e.draw else "the step's writer"
            text = e.caption.format_map(words).replace("|", "\\|")
            lines.append(f"| {name} | {e.paper or '–'} | {place} | {source} | {text} |")
        lines.append("")
    return "\n".join(lines)
