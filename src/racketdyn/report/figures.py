"""Figures of the report: PNGs embedded as data URIs, each with a caption naming the figure of
Kawazoe's paper it corresponds to (or saying it has none)."""

from __future__ import annotations

import base64
import io
import logging
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path, PurePath
from typing import Any, Literal

from racketdyn.impact.result import shown_speed_index
from racketdyn.racket import SUPPORT_NAMES

__all__ = [
    "CAPTIONS",
    "Figure",
    "FigureGroup",
    "Layout",
    "caption_of",
    "embed_png",
    "interactive",
    "page_png",
    "run_words",
]

log = logging.getLogger(__name__)

_PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
PAGE_PNG_COLOURS = 256
"""Colours of the palette a figure is embedded with (PNG's largest palette)."""

CAPTIONS: dict[str, tuple[str | None, str]] = {
    "fig2_frf_frame": (
        "Fig. 2",
        "FRF for an impact on the frame at the accelerometer (driving point): magnitude, "
        "phase and coherence",
    ),
    "fig3_frf_string_centre": (
        "Fig. 3",
        "FRF for an impact at the string-bed centre: magnitude, phase and coherence",
    ),
    "stabilisation": (
        None,
        "LSCF stabilisation diagram: poles of every model order against frequency, with the "
        "selected modes",
    ),
    "synthesised_frfs": (
        None,
        "measured FRFs against those synthesised from the identified modal model "
        "(driving point and string-bed centre)",
    ),
    "automac": (
        None,
        "AutoMAC of the identified mode shapes: 1 on the diagonal; off it, how alike two modes "
        "look at the measured points (near 1: the points cannot tell them apart)",
    ),
    "fig4_mode_shapes": ("Fig. 4", "identified mode shapes in 3-D over the racket"),
    "fig5_node_lines": ("Fig. 5", "node lines of the identified modes on the string face"),
    "fig6_nodes_free_hand": (
        "Fig. 6",
        "node positions of the first mode along the long axis, free (blue, {free_file}) "
        "against hand-held (black, {hand_file}), identified over {band}; the grey band is the "
        "hand",
    ),
    "fig6_nodes": ("Fig. 6", "node positions of the first mode along the long axis"),
    "comparison": (
        None,
        "frequency shift and damping ratio of each mode, hand-held ({hand_file}) against free "
        "({free_file}), identified over {band} and paired by MAC",
    ),
    "fig15_identified": (
        "Fig. 15",
        "rebound ratio along the long axis, ball at {check_speed}, racket at rest, predicted "
        "with the models identified from {free_file} and {hand_file}: pinned at the grip with "
        "the hand-held modes, pinned at the grip with the free modes, free with the free modes",
    ),
    "fig7_contact_time": ("Fig. 7", "contact time of the hammer on the strings, per support"),
    "fig11_12_force_contact_time": (
        "Figs 11 and 12",
        "Fig. 11: equivalent (mean) impact force and Fig. 12: contact time against ball speed "
        "at the top, centre and throat of the face, for the run's supports, one row of panels "
        "per racket speed, titled with it ({racket_speed}); the run's speeds are marked on the "
        "row of their racket speed, its options are in the title; speeds where an impact is "
        "flagged (no valid value) are hatched, crosses at the foot mark each, and the legend "
        "counts them",
    ),
    "fig13_pulse_spectrum": (
        "Fig. 13",
        "the half-sine impact force at the face centre and the magnitude of its spectrum for "
        "balls at {speeds}, {racket_speed} (support in the title), with the modes of the "
        "model: the faster the ball, the shorter the pulse and the higher its spectrum reaches",
    ),
    "fig14_frame_vibration": (
        "Fig. 14",
        "predicted first-mode displacement along the frame just after an impact at the tip, "
        "at the run's speeds, one panel per support; impacts the method flags have no valid "
        "vibration and are not drawn: the legend names them with their status and each panel "
        "says how many (hatched when none is valid)",
    ),
    "fig15_rebound_along_axis": (
        "Fig. 15",
        "predicted rebound ratio along the long axis, ball at {shown_speed}, "
        "{shown_racket_speed}, {approximate_supports}, with the centre of percussion and the "
        "node of the first mode",
    ),
    "face_maps": (
        None,
        "maps over the face, ball at {shown_speed}, {shown_racket_speed}: rebound ratio for each "
        "support, contact time and vibration energy; red crosses mark impacts with no valid "
        "result, left out of every map; the paper shows the long axis only (Fig. 15)",
    ),
    "transient_comparison_face": (
        None,
        "rebound ratio of the approximate method minus that of the transient simulation over "
        "the face, one panel per support, ball at {shown_speed}, {shown_racket_speed}; red where "
        "the approximate method predicts more; the paper checks its method against a freely "
        "suspended racket only",
    ),
    "transient_comparison_speed": (
        None,
        "rebound ratio and contact time against ball speed at the face centre, near the tip and "
        "near the throat, approximate method (dashed) against the transient simulation (solid), "
        "{racket_speed}; a curve breaks where its method flags the impact (vibration loss "
        "beyond e_BG, a second contact, …): the speeds are hatched at the foot, across the "
        "whole height where no curve is valid, and the legend counts them",
    ),
    "transient_histories": (
        None,
        "time histories of the transient simulation at the face centre and near the tip: "
        "contact force (the approximate method assumes a half-sine, Fig. 13), ball and "
        "racket-face displacement, and the modal coordinates of the flexible modes",
    ),
    "swing_map": (
        None,
        "outgoing ball speed over the face of the swinging racket ({swing}), ball at "
        "{sweet_speed}, {support}, {impact_model} model, with the sweet spots: the centres of "
        "percussion about the swing axis and about the grip, the node of the first mode, the "
        "largest rebound ratio (racket at rest) and the largest outgoing speed for the swing; "
        "crosses mark impacts without a valid number",
    ),
    "swing_along_axis": (
        None,
        "outgoing ball speed along the long axis, ball at {sweet_speed}, {support}, "
        "{impact_model} model, for the racket at rest (the setting of the paper's Fig. 15) and "
        "for {axis_swings}, with the sweet spots of the run's swing ({swing}) as vertical lines",
    ),
    "twist": (
        None,
        "off-axis impacts at one x: the racket's roll about its long axis at separation (left; "
        "positive turns the hit side away from the ball) and the outgoing ball speed (right) "
        "against the offset from the long axis, one line per support",
    ),
    "oblique": (
        None,
        "oblique impacts at one point: outgoing angle to the face normal (left; dashed: the "
        "same impact without friction) and outgoing spin (right) against the incoming angle; "
        "filled markers where the ball gripped the strings, open where it slid throughout; the "
        "spin depends strongly on the tangential stiffness k_t",
    ),
    "compound_response": (
        "Fig. 8c",
        "acceleration of the frame neck after a hammer blow on the strings near the ball fixed "
        "on them (a half-sine as long as the hammer's contact with the strings), per unit "
        "impulse, for the run's first support (linear compound model)",
    ),
    "compound_shape": (
        "Fig. 8a",
        "the ball mode: the frame's displacement along its long axis (line) against the ball's "
        "(marker), scaled so the ball's is 1, one colour, line style and marker per support; "
        "supports whose frames lie on one another are named on the figure",
    ),
    "validation_parity": (
        None,
        "predicted against measured rebound ratio, approximate method and transient simulation, "
        "with the 1:1 line; flagged rows are counted in the legend and not drawn",
    ),
    "validation_along_axis": (
        None,
        "measured rebound ratio (with one standard deviation where measured) and both models' "
        "predictions against the position along the long axis, every measured row",
    ),
    "validation_residuals": (
        None,
        "the transient simulation's residual (predicted − measured rebound ratio) over the face, "
        "one marker per support; flagged rows as crosses",
    ),
    "compound_frf": (
        "Fig. 9",
        "receptance from the hammer point on the strings to the frame neck, the racket alone "
        "(left) and with the ball fixed on the strings (right), with the ball mode marked",
    ),
    "fig9_frf_alone_and_ball": (
        "Fig. 9",
        "measured accelerance to the accelerometer from the hammer point nearest the ball "
        "whose FRF the ball mode dominates at its frequency (its node in the title), the "
        "racket alone (left) and with the ball fixed on the strings (right, the racket alone "
        "dashed), identified modes dotted, the ball's labelled (racketdyn compare --ball-at)",
    ),
}
"""Caption of every PNG the commands write, by file stem (or its start): (the figure of
Kawazoe's paper it corresponds to, or None; what it shows, its ``{field}`` the settings its run
used, from the run.json of its folder: :func:`run_words`)."""


@dataclass(frozen=True)
class Figure:
    """One figure of the page: an embedded PNG, or an interactive plot drawn by the script.

    Parameters
    ----------
    paper : str or None
        The figure of the paper it corresponds to (``"Fig. 7"``), or None.
    what : str
        What it shows, a sentence without the final full stop.
    where : str
        Where its data came from (file, relative to the run folder).
    src : str
        ``data:image/png;base64,…`` of an image; empty for an interactive plot.
    plot_id : str
        For an interactive plot, the id of its element (its data in the page's JSON carry the
        same id); empty for an image.
    plot_kind : {"", "frf", "map"}
        Which script draws the interactive plot.
    css_class : str
        ``"wide"``, ``"interactive"`` or empty.
    """

    paper: str | None
    what: str
    where: str
    src: str = ""
    plot_id: str = ""
    plot_kind: Literal["", "frf", "map"] = ""
    css_class: str = ""

    @property
    def lead(self) -> str:
        """The caption's bold start: the paper's figure, or that it has none."""
        return f"Kawazoe {self.paper}." if self.paper else "No figure in the paper."

    @property
    def text(self) -> str:
        """The caption's sentence."""
        return f"{self.what[0].upper()}{self.what[1:]}."


Layout = Literal["pair", "stack", "plain"]
"""How a group of figures is shown: side by side, one under another, or without a wrapper."""


@dataclass(frozen=True)
class FigureGroup:
    """Figures shown together: side by side (``"pair"``), one under another (``"stack"``), or
    without a wrapper (``"plain"``)."""

    figures: tuple[Figure, ...]
    layout: Layout = "stack"


SUPPORT_WORDS = dict(SUPPORT_NAMES)
"""A support as the captions name it."""

UNKNOWN_WORDS: dict[str, str] = {
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
version)."""


def _file_words(path: object) -> str | None:
    """A run's input file as the caption names it: its folder and name."""
    if not isinstance(path, str) or not path:
        return None
    found = PurePath(path)
    return f"{found.parent.name}/{found.name}" if found.parent.name else found.name


def _number(value: object) -> float | None:
    return float(value) if isinstance(value, int | float) and not isinstance(value, bool) else None


def _swing_words(swing: object, omega: float | None) -> str | None:
    """A swing of run.json's ``swing`` table in words (its torque model, or its Ω)."""
    if not isinstance(swing, Mapping):
        return None
    speed = f"Ω = {omega:.1f} rad/s" if omega is not None else ""
    torque, angle = _number(swing.get("torque_nm")), _number(swing.get("swing_angle_rad"))
    if torque is not None and angle is not None:
        words = f"shoulder torque {torque:g} N·m over {math.degrees(angle):.0f}°"
        return f"{words}: {speed}" if speed else words
    given = _number(swing.get("angular_speed_radps"))
    return f"given angular speed Ω = {given:.1f} rad/s" if given is not None else speed or None


def _list_words(items: Sequence[str]) -> str:
    """``a``, ``a and b``, ``a, b and c``."""
    return ", ".join(items[:-1]) + " and " + items[-1] if len(items) > 1 else "".join(items)


def _speeds_words(speeds: Sequence[float]) -> str:
    """``10, 20 and 30 m/s``."""
    return _list_words([f"{v:g}" for v in speeds]) + " m/s"


def _racket_words(speeds: Sequence[float]) -> str:
    """The racket's speed(s) towards the ball in words."""
    if not any(speeds):
        return "racket at rest"
    if len(set(speeds)) == 1:
        return f"racket at {speeds[0]:g} m/s"
    return f"racket at {_speeds_words(speeds)} (one per ball speed)"


def _predict_words(record: Mapping[str, Any]) -> dict[str, str | None]:
    """predict's speeds, racket speeds and supports in words (its run.json)."""
    speeds = [v for v in _numbers(record.get("speeds_mps")) if v is not None]
    racket = [v for v in _numbers(record.get("racket_speed_mps")) if v is not None]
    if not speeds:
        return {}
    shown = shown_speed_index(speeds)
    ball, at_shown = speeds[shown], None
    case = record.get("shown_case")  # predict --show, or the rule's case (issue 27)
    if isinstance(case, Mapping):
        given = _number(case.get("ball_speed_mps"))
        ball = ball if given is None else given
        at_shown = _number(case.get("racket_speed_mps"))
    words: dict[str, str | None] = {
        "speeds": _speeds_words(sorted(speeds)),
        "shown_speed": f"{ball:g} m/s",
    }
    if racket:
        words["racket_speed"] = _racket_words(racket)
        if at_shown is None:
            at_shown = racket[shown] if len(racket) == len(speeds) else racket[0]
        words["shown_racket_speed"] = _racket_words([at_shown])
    supports = record.get("supports")
    if isinstance(supports, list):
        # the approximate method's supports: the hand model is the transient simulation's
        named = [SUPPORT_WORDS.get(str(s), str(s)) for s in supports if s != "hand"]
        words["approximate_supports"] = _list_words(named) if named else None
    return words


def _numbers(values: object) -> list[float | None]:
    return [_number(v) for v in values] if isinstance(values, list) else []


def run_words(record: Mapping[str, Any]) -> dict[str, str]:
    """The settings a run used, in the words of the captions' ``{field}``, from its run.json;
    :data:`UNKNOWN_WORDS` where it does not say.

    Parameters
    ----------
    record : mapping
        The run.json of the folder the figure is in.
    """
    words: dict[str, str | None] = {
        "free_file": _file_words(record.get("free_file")),
        "hand_file": _file_words(record.get("hand_file")),
        "support": SUPPORT_WORDS.get(str(record.get("support"))),
        "impact_model": str(record["impact_model"]) if record.get("impact_model") else None,
        "swing": _swing_words(record.get("swing"), _number(record.get("angular_speed_radps"))),
    }
    band = record.get("band_hz")
    if isinstance(band, list) and len(band) == 2 and all(_number(b) is not None for b in band):
        words["band"] = f"{band[0]:g}–{band[1]:g} Hz"
    for key, field in (
        ("check_speed", "fig15_ball_speed_mps"),
        ("sweet_speed", "sweet_spots_at_mps"),
    ):
        speed = _number(record.get(field))
        words[key] = f"{speed:g} m/s" if speed is not None else None
    words |= _predict_words(record)
    swings = record.get("along_axis_swings")
    if isinstance(swings, list) and all(isinstance(s, str) for s in swings):
        moving = [s for s in swings if s != "racket at rest"]
        words["axis_swings"] = f"the swings {_list_words(moving)}" if moving else None
    return {key: words.get(key) or unknown for key, unknown in UNKNOWN_WORDS.items()}


def caption_of(stem: str, record: Mapping[str, Any] | None = None) -> tuple[str | None, str]:
    """(paper figure, what it shows) of a PNG by its file stem, worded from its run's settings.

    The longest matching key of :data:`CAPTIONS` wins; its ``{field}`` are filled in with
    :func:`run_words` of ``record``.

    Parameters
    ----------
    stem : str
        The file name without ``.png``.
    record : mapping, optional
        The run.json of the folder the figure is in.
    """
    key = next((k for k in sorted(CAPTIONS, key=len, reverse=True) if stem.startswith(k)), None)
    if key is None:
        return None, stem.replace("_", " ")
    paper, what = CAPTIONS[key]
    return paper, what.format_map(run_words(record or {}))


def embed_png(
    path: Path, where: str, wide: bool = False, record: Mapping[str, Any] | None = None
) -> Figure | None:
    """The PNG at ``path`` as a :class:`Figure` with its caption; None (logged) if not a PNG.

    Parameters
    ----------
    path : Path
        The PNG file.
    where : str
        Shown at the end of the caption: the file, relative to the run folder.
    wide : bool
        A figure that takes the page's width.
    record : mapping, optional
        The run.json of its folder, for the caption's words (:func:`caption_of`).
    """
    try:
        data = path.read_bytes()
    except OSError:
        return None
    if not data.startswith(_PNG_SIGNATURE):
        log.warning("%s: not a PNG; left out of the report", path)
        return None
    paper, what = caption_of(path.stem, record)
    encoded = base64.b64encode(page_png(data, path)).decode("ascii")
    return Figure(
        paper, what, where, src=f"data:image/png;base64,{encoded}", css_class="wide" if wide else ""
    )


def page_png(data: bytes, path: Path | None = None) -> bytes:
    """The PNG ``data`` as embedded in the page: the same picture with a palette of
    :data:`PAGE_PNG_COLOURS` colours, or ``data`` itself when that is not smaller.

    A figure of the commands is drawn in RGB(A) with antialiased lines and text, thousands of
    colours; on the page a palette of 256 (Pillow's fast octree, no dithering) gives the same
    picture to the eye in about a third of the bytes (the demo's 35 figures: mean channel error
    1.1 of 255, 99.9 % of the values within 13, a few antialiased pixels of shaded surfaces and
    marker edges up to 46; 0.32 of the bytes).  The files the commands wrote are not changed.

    Parameters
    ----------
    data : bytes
        A PNG file's bytes.
    path : Path, optional
        Its file, named in the warning when Pillow cannot read it (then ``data`` is kept).

    Returns
    -------
    bytes
        A PNG file's bytes.
    """
    from PIL import Image

    try:
        with Image.open(io.BytesIO(data)) as opened:
            opened.load()
            image: Image.Image = opened
            if image.mode not in ("RGB", "RGBA"):
                image = image.convert("RGBA" if "A" in image.getbands() else "RGB")
            palette = image.quantize(
                colors=PAGE_PNG_COLOURS,
                method=Image.Quantize.FASTOCTREE,
                dither=Image.Dither.NONE,
            )
    except (OSError, ValueError) as error:
        log.warning("%s: embedded as it is (%s)", path or "PNG", error)
        return data
    buffer = io.BytesIO()
    palette.save(buffer, format="png", compress_level=6)
    smaller = buffer.getvalue()
    return smaller if len(smaller) < len(data) else data


def interactive(
    plot_id: str, kind: Literal["frf", "map"], paper: str | None, what: str, where: str
) -> Figure:
    """An interactive plot drawn by the page's scripts from the data with id ``plot_id``.

    Parameters
    ----------
    plot_id : str
        Id of its element, and of its entry in the page's JSON data.
    kind : {"frf", "map"}
        ``"frf"``: FRF magnitude and coherence (``static/frf_plot.js``); ``"map"``: values over
        the face (``static/face_map.js``).
    paper : str or None
        The figure of the paper it corresponds to.
    what : str
        What it shows, for the caption.
    where : str
        Where its data came from.
    """
    return Figure(paper, what, where, plot_id=plot_id, plot_kind=kind, css_class="interactive")
