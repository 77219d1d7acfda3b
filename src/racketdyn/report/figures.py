"""Figures of the report: PNGs embedded as data URIs, each with a caption naming the figure of
Kawazoe's paper it corresponds to (or saying it has none); captions and places come from the
registry of figures (:mod:`racketdyn.plotting.registry`)."""

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
from racketdyn.plotting.registry import CAPTION_DEFAULTS, FIGURES
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

CAPTIONS: dict[str, tuple[str | None, str]] = {e.id: (e.paper, e.caption) for e in FIGURES.values()}
"""Caption of every PNG the commands write, by file stem (or its start), from the registry of
figures (:data:`racketdyn.plotting.registry.FIGURES`): (the figure of Kawazoe's paper it
corresponds to, or None; what it shows, its ``{field}`` the settings its run used, from the
run.json of its folder: :func:`run_words`)."""


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

UNKNOWN_WORDS: dict[str, str] = CAPTION_DEFAULTS
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

    The registry's entry (:data:`racketdyn.plotting.registry.FIGURES`) whose id is the longest
    start of ``stem`` wins; its ``{field}`` are filled in with :func:`run_words` of ``record``.

    Parameters
    ----------
    stem : str
        The file name without ``.png``.
    record : mapping, optional
        The run.json of the folder the figure is in.
    """
    key = next((k for k in sorted(FIGURES, key=len, reverse=True) if stem.startswith(k)), None)
    if key is None:
        return None, stem.replace("_", " ")
    figure = FIGURES[key]
    return figure.paper, figure.caption.format_map(run_words(record or {}))


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
