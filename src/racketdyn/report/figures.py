"""Figures of the report: PNGs embedded as data URIs, each with a caption naming the figure of
Kawazoe's paper it corresponds to (or saying it has none)."""

from __future__ import annotations

import base64
import logging
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

__all__ = ["CAPTIONS", "Figure", "FigureGroup", "Layout", "embed_png", "interactive"]

log = logging.getLogger(__name__)

_PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"

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
        "node positions of the first mode along the long axis, free (blue) against "
        "hand-held (black); the grey band is the hand",
    ),
    "fig6_nodes": ("Fig. 6", "node positions of the first mode along the long axis"),
    "comparison": (
        None,
        "frequency shift and damping ratio of each mode, hand-held against free (paired by MAC)",
    ),
    "fig15_identified": (
        "Fig. 15",
        "rebound ratio along the long axis at 20 m/s predicted with the identified models: "
        "hand-held with hand-held modes, hand-held with free modes, free with free modes",
    ),
    "fig7_contact_time": ("Fig. 7", "contact time of the hammer on the strings, per support"),
    "fig11_12_force_contact_time": (
        "Figs 11 and 12",
        "Fig. 11: equivalent (mean) impact force and Fig. 12: contact time against ball speed "
        "at the top, centre and throat of the face, for the run's supports; the run's speeds "
        "are marked, its racket speed and options are in the title",
    ),
    "fig13_pulse_spectrum": (
        "Fig. 13",
        "the half-sine impact force at the face centre and the magnitude of its spectrum at "
        "the run's speeds (support in the title), with the modes of the model: the faster the "
        "ball, the shorter the pulse and the higher its spectrum reaches",
    ),
    "fig14_frame_vibration": (
        "Fig. 14",
        "predicted first-mode displacement along the frame just after an impact at the tip, "
        "at the run's speeds, one panel per support; impacts the method flags are faint and "
        "dashed, with their status",
    ),
    "fig15_rebound_along_axis": (
        "Fig. 15",
        "predicted rebound ratio along the long axis at the run's shown speed (in the title), "
        "for its supports, with the centre of percussion and the node of the first mode",
    ),
    "face_maps": (
        None,
        "maps over the face at the run's shown speed (in the title): rebound ratio for each "
        "support, contact time and vibration energy; red crosses mark impacts with no valid "
        "result, left out of every map; the paper shows the long axis only (Fig. 15)",
    ),
    "transient_comparison_face": (
        None,
        "rebound ratio of the approximate method minus that of the transient simulation over "
        "the face, one panel per support, at the run's shown speed (in the title); red where "
        "the approximate method predicts more; the paper checks its method against a freely "
        "suspended racket only",
    ),
    "transient_comparison_speed": (
        None,
        "rebound ratio and contact time against ball speed at the face centre, near the tip and "
        "near the throat, approximate method (dashed) against the transient simulation (solid), "
        "at the run's racket speed (in the title); missing dashes are impacts the approximate "
        "method flags (vibration loss beyond e_BG)",
    ),
    "transient_histories": (
        None,
        "time histories of the transient simulation at the face centre and near the tip: "
        "contact force (the approximate method assumes a half-sine, Fig. 13), ball and "
        "racket-face displacement, and the modal coordinates of the flexible modes",
    ),
    "swing_map": (
        None,
        "outgoing ball speed over the face of the swinging racket (constant shoulder torque, "
        "Kawazoe ACMD 2002), with the sweet spots: the centres of percussion about the swing "
        "axis and about the grip, the node of the first mode, the largest rebound ratio "
        "(racket at rest) and the largest outgoing speed for the swing; crosses mark impacts "
        "without a valid number",
    ),
    "swing_along_axis": (
        None,
        "outgoing ball speed along the long axis for the racket at rest (the setting of the "
        "paper's Fig. 15) and for swings of half, the same and one and a half times the swing "
        "angle (or angular speed), with the sweet spots of the run's swing as vertical lines",
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
        "on them, per unit impulse, for the run's first support (linear compound model)",
    ),
    "compound_shape": (
        "Fig. 8a",
        "the ball mode: the frame's displacement along its long axis (line) against the ball's "
        "(circle), scaled so the ball's is 1, one colour per support",
    ),
    "compound_frf": (
        "Fig. 9",
        "receptance from the hammer point on the strings to the frame neck, the racket alone "
        "(left) and with the ball fixed on the strings (right), with the ball mode marked",
    ),
}
"""Caption of every PNG the commands write, by file stem (or its start): (the figure of
Kawazoe's paper it corresponds to, or None; what it shows)."""


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


def caption_of(stem: str) -> tuple[str | None, str]:
    """(paper figure, what it shows) of a PNG by its file stem; the longest matching key wins."""
    key = next((k for k in sorted(CAPTIONS, key=len, reverse=True) if stem.startswith(k)), None)
    return CAPTIONS[key] if key else (None, stem.replace("_", " "))


def embed_png(path: Path, where: str, wide: bool = False) -> Figure | None:
    """The PNG at ``path`` as a :class:`Figure` with its caption; None (logged) if not a PNG.

    Parameters
    ----------
    path : Path
        The PNG file.
    where : str
        Shown at the end of the caption: the file, relative to the run folder.
    wide : bool
        A figure that takes the page's width.
    """
    try:
        data = path.read_bytes()
    except OSError:
        return None
    if not data.startswith(_PNG_SIGNATURE):
        log.warning("%s: not a PNG; left out of the report", path)
        return None
    paper, what = caption_of(path.stem)
    encoded = base64.b64encode(data).decode("ascii")
    return Figure(
        paper, what, where, src=f"data:image/png;base64,{encoded}", css_class="wide" if wide else ""
    )


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
