"""One self-contained HTML report of a run folder: the whole story, from the racket to the rebound.

:func:`write_report` looks for what the pipeline commands wrote under a folder (the folder itself
and its sub-folders: ``racketdyn rig``, ``frf``, ``contact``, ``identify`` / ``compare``,
``predict``, ``swing``, ``twist`` and ``oblique``) and writes ``report.html`` into it.  The
page works offline and can be mailed as it is: the PNG figures are embedded as base64 data URIs,
the CSS and a small dependency-free script are inline, and the data of the interactive plots
(FRF magnitude with zoom and hover readout, face maps with hover values) sit in the page as
JSON.  The PNGs stay for print.

Sections, in order, each present only if its inputs exist: the racket and its derived
properties; measurement quality; stabilisation diagrams; mode shapes and node lines, free
against hand-held; contact time over the face; impact force and contact time against speed;
frame vibration; rebound ratio and sweet spots; the approximate method against the transient
simulation (``racketdyn predict --model both``: ``comparison.csv`` with approximate and transient
columns, told apart from ``racketdyn compare``'s ``comparison.csv`` of paired modes by its
header); the swinging racket (``racketdyn swing``: ``swing.csv``, ``sweet_spots.csv``);
off-centre and oblique impacts (``racketdyn twist``: ``twist.csv``; ``racketdyn oblique``:
``oblique.csv``; either is enough); inputs, defaults and versions.  Sections whose inputs are
missing are listed at the end as not run.  Every figure's caption names the figure of Kawazoe's
paper it corresponds to, or says it has none.
"""

from __future__ import annotations

import base64
import csv
import hashlib
import html
import json
import logging
import math
import platform
import re
import shlex
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.__about__ import __version__
from racketdyn.errors import InputError
from racketdyn.impact.result import shown_speed_index
from racketdyn.racket import Racket

__all__ = ["REPORT_NAME", "SECTIONS", "write_report"]

log = logging.getLogger(__name__)

REPORT_NAME = "report.html"
"""File name of the report inside the run folder."""

SECTIONS: dict[str, str] = {
    "racket": "The racket and its derived properties",
    "quality": "Measurement quality",
    "stabilisation": "Stabilisation diagrams",
    "modes": "Mode shapes and node lines, free against hand-held",
    "contact": "Contact time over the face",
    "impact": "Impact force and contact time against speed",
    "vibration": "Frame vibration",
    "rebound": "Rebound ratio and sweet spots",
    "transient": "Approximate method against the transient simulation",
    "swing": "The swinging racket",
    "oblique": "Off-centre and oblique impacts",
    "provenance": "Inputs, defaults and versions",
}
"""Section id → heading, in the order of the report."""

_HOW_TO_RUN: dict[str, str] = {
    "racket": "racketdyn predict --out DIR/predict (or racketdyn rig --out DIR/rig)",
    "quality": "racketdyn frf DIR/rig/hammer_free.uff --exp-window 0.1 --out DIR/frf_free",
    "stabilisation": "racketdyn compare DIR/frf_free/frfs.uff DIR/frf_hand/frfs.uff "
    "--out DIR/compare (or racketdyn identify)",
    "modes": "racketdyn compare DIR/frf_free/frfs.uff DIR/frf_hand/frfs.uff --out DIR/compare",
    "contact": "racketdyn contact DIR/rig/hammer_free.uff DIR/rig/hammer_hand.uff "
    "--labels free,hand --out DIR/contact",
    "impact": "racketdyn predict --out DIR/predict",
    "vibration": "racketdyn predict --out DIR/predict",
    "rebound": "racketdyn predict --out DIR/predict",
    "transient": "racketdyn predict --model both --out DIR/predict",
    "swing": "racketdyn swing --out DIR/swing",
    "oblique": "racketdyn twist --support free,hand --out DIR/twist; "
    "racketdyn oblique --out DIR/oblique",
    "provenance": "any racketdyn command with --out (each writes run.json)",
}

_MAX_MAP_POINTS = 2500  # per speed and support in the interactive map; more are thinned
_MAX_MAP_SPEEDS = 7
_MAX_FRF_LINES = 4000
_SERIES_COLOURS = ("#1f77b4", "#222222", "#d62728", "#2ca02c", "#9467bd", "#8c564b")
_SUPPORT_COLOURS = {"free": "#1f77b4", "hand": "#222222", "pinned": "#222222"}
_PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"

# caption of every PNG the commands write: (paper figure or None, what it shows)
_CAPTIONS: dict[str, tuple[str | None, str]] = {
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
    "automac": (None, "AutoMAC of the identified mode shapes: near-zero off the diagonal"),
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
        "at the top, centre and throat of the face, free and pinned at the grip",
    ),
    "fig13_pulse_spectrum": (
        "Fig. 13",
        "the half-sine impact force at the face centre (pinned) and the magnitude of its "
        "spectrum at 10–40 m/s, with the modes of the model: the faster the ball, the shorter "
        "the pulse and the higher its spectrum reaches",
    ),
    "fig14_frame_vibration": (
        "Fig. 14",
        "predicted first-mode displacement along the frame just after an impact at the tip, "
        "free and pinned",
    ),
    "fig15_rebound_along_axis": (
        "Fig. 15",
        "predicted rebound ratio along the long axis at 20 m/s, free against pinned at the "
        "grip, with the centre of percussion and the node of the first mode",
    ),
    "face_maps": (
        None,
        "maps over the face at 20 m/s: rebound ratio (pinned, free), contact time and "
        "vibration energy (pinned); the paper shows the long axis only (Fig. 15)",
    ),
    "transient_comparison_face": (
        None,
        "rebound ratio of the approximate method minus that of the transient simulation over "
        "the face, one panel per support, at 20 m/s (or the middle speed of the run); red where "
        "the approximate method predicts more; the paper checks its method against a freely "
        "suspended racket only",
    ),
    "transient_comparison_speed": (
        None,
        "rebound ratio and contact time against ball speed at the face centre, near the tip and "
        "near the throat, approximate method (dashed) against the transient simulation (solid), "
        "racket at rest; missing dashes are impacts the approximate method flags (vibration "
        "loss beyond e_BG)",
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
}

_DERIVED_LABELS: dict[str, str] = {
    "mass": "mass",
    "balance": "balance point, from the butt",
    "inertia_cg": "pitch inertia about the balance point",
    "inertia_grip": "pitch inertia about the grip pivot",
    "swingweight": "swingweight (10 cm from the butt)",
    "twistweight": "twistweight (roll inertia)",
    "recoil_weight": "recoil weight (inertia about the balance point)",
    "centre_of_percussion": "centre of percussion, pivot at the grip",
    "head_area": "head (string-bed) area",
    "reduced_mass_centre_free": "reduced mass at the face centre, free (eq 4)",
    "reduced_mass_centre_pinned": "reduced mass at the face centre, pinned at the grip (eq 4)",
}

# unit suffix → (display unit, factor)
_UNITS: dict[str, tuple[str, float]] = {
    "kg": ("g", 1e3),
    "m": ("mm", 1e3),
    "kgm2": ("g·m²", 1e3),
    "kgcm2": ("kg·cm²", 1.0),
    "cm2": ("cm²", 1.0),
    "hz": ("Hz", 1.0),
    "n": ("N", 1.0),
    "pa": ("GPa", 1e-9),
    "s": ("ms", 1e3),
    "mps": ("m/s", 1.0),
}

_RUN_KEYS = ("racketdyn_version", "created_utc", "command", "python", "numpy", "outputs")


class _Html(str):
    """Text that is already HTML: table cells of this type are not escaped."""

    __slots__ = ()


def _e(text: object) -> str:
    return html.escape(str(text), quote=True)


def _finite(value: float) -> bool:
    return isinstance(value, int | float) and math.isfinite(value)


def _fmt(value: Any, spec: str = ".4g") -> str:
    """A number for a table; a dash for None or NaN."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int | float | np.floating | np.integer):
        number = float(value)
        return format(number, spec) if math.isfinite(number) else "–"
    return str(value)


def _table(
    header: Sequence[str], rows: Iterable[Sequence[str]], cls: str = "", numeric_from: int = 1
) -> str:
    """An HTML table; cells are escaped unless they are :class:`_Html`."""

    def cell(tag: str, value: str, index: int) -> str:
        text = value if isinstance(value, _Html) else _e(value)
        align = ' class="num"' if index >= numeric_from else ""
        return f"<{tag}{align}>{text}</{tag}>"

    head = "".join(cell("th", h, i) for i, h in enumerate(header))
    body = "\n".join(
        "<tr>" + "".join(cell("td", v, i) for i, v in enumerate(row)) + "</tr>" for row in rows
    )
    klass = f' class="{cls}"' if cls else ""
    return f"<table{klass}><thead><tr>{head}</tr></thead><tbody>\n{body}\n</tbody></table>"


def _quantity(key: str, value: Any) -> tuple[str, str, str]:
    """(label, value, unit) of a unit-suffixed key, in the units engineers quote."""
    name, _, suffix = key.rpartition("_")
    if not name or suffix not in _UNITS:
        name, suffix = key, ""
    unit, factor = _UNITS.get(suffix, ("", 1.0))
    if suffix == "pa" and "modulus" not in name:
        unit, factor = "Pa", 1.0
    if isinstance(value, int | float) and not isinstance(value, bool):
        text = _fmt(float(value) * factor, ".4g") if suffix else _fmt(value, "g")
    elif value is None:
        text, unit = "not set", ""
    else:
        text = str(value)
    return name.replace("_", " "), text, unit


def _read_json(path: Path) -> dict[str, Any] | None:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as error:
        log.warning("%s: not read (%s)", path, error)
        return None
    return data if isinstance(data, dict) else None


def _read_csv(path: Path) -> tuple[list[dict[str, str]], list[str]]:
    """Rows of a CSV as dicts, and its comment lines (starting with ``#``) without the ``#``."""
    lines = path.read_text(encoding="utf-8").splitlines()
    comments = [line[1:].strip() for line in lines if line.startswith("#")]
    rows = list(csv.DictReader(line for line in lines if line and not line.startswith("#")))
    return rows, comments


def _float(text: str | None) -> float:
    try:
        return float(text) if text not in (None, "") else math.nan
    except ValueError:
        return math.nan


def _sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _round(values: NDArray[np.float64], digits: int = 4) -> list[float | None]:
    """Values for JSON: significant digits kept, NaN as null."""
    return [float(f"{v:.{digits}g}") if math.isfinite(v) else None for v in values.tolist()]


@dataclass(frozen=True)
class _Head:
    """The string-bed ellipse, m."""

    centre_x: float
    centre_y: float
    half_length: float
    half_width: float

    def contains(self, x: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.bool_]:
        return np.asarray(
            ((x - self.centre_x) / self.half_length) ** 2
            + ((y - self.centre_y) / self.half_width) ** 2
            <= 1.0
        )


@dataclass(frozen=True)
class _Impacts:
    """``impact.csv``: numeric columns as arrays, support and status as strings."""

    numbers: dict[str, NDArray[np.float64]]
    support: NDArray[np.str_]
    status: NDArray[np.str_]

    @classmethod
    def read(cls, path: Path) -> _Impacts | None:
        with path.open(encoding="utf-8", newline="") as handle:
            rows = list(csv.reader(handle))
        if len(rows) < 2:
            return None
        header, table = rows[0], np.array(rows[1:], dtype=str)
        numbers = {}
        for i, name in enumerate(header):
            if name in ("point", "support", "status"):
                continue
            column = np.where(table[:, i] == "", "nan", table[:, i])
            try:
                numbers[name] = column.astype(float)
            except ValueError:
                continue
        if not {"x_m", "y_m", "ball_speed_mps", "rebound_ratio"} <= set(numbers):
            return None
        return cls(
            numbers,
            table[:, header.index("support")] if "support" in header else np.full(len(table), ""),
            table[:, header.index("status")] if "status" in header else np.full(len(table), "ok"),
        )

    def __getitem__(self, name: str) -> NDArray[np.float64]:
        return self.numbers.get(name, np.full(self.support.size, np.nan))

    @property
    def speeds(self) -> list[float]:
        return sorted({float(v) for v in self["ball_speed_mps"]})

    @property
    def supports(self) -> list[str]:
        return list(dict.fromkeys(self.support.tolist()))

    def rows(self, speed: float, support: str) -> NDArray[np.intp]:
        return np.flatnonzero((self["ball_speed_mps"] == speed) & (self.support == support))

    def where(self, row: int) -> str:
        """``x, y`` of a row in mm, for tables."""
        return f"{self['x_m'][row] * 1e3:.0f}, {self['y_m'][row] * 1e3:.0f}"

    def nearest(self, rows: NDArray[np.intp], x: float, y: float) -> int:
        distance = np.hypot(self["x_m"][rows] - x, self["y_m"][rows] - y)
        return int(rows[int(np.argmin(distance))])


@dataclass
class _Context:
    """What was found under the run folder, and the state the sections share."""

    run_dir: Path
    racket: Racket | None
    dirs: list[Path]
    records: dict[Path, dict[str, Any]]
    data: dict[str, list[Any]] = field(default_factory=lambda: {"maps": [], "frf": []})
    glance: list[str] = field(default_factory=list)
    figures: int = 0
    impacts_read: list[_Impacts | None] = field(default_factory=list)
    loaded: list[Racket | None] = field(default_factory=list)

    def with_file(self, pattern: str) -> list[Path]:
        """Folders holding a file that matches ``pattern``, the run folder first."""
        return [d for d in self.dirs if any(d.glob(pattern))]

    def first(self, pattern: str) -> Path | None:
        found = self.with_file(pattern)
        return found[0] if found else None

    def rel(self, path: Path) -> str:
        return path.relative_to(self.run_dir).as_posix()

    # -- what the pipeline wrote --------------------------------------------------------------
    @property
    def predict_dir(self) -> Path | None:
        return self.first("impact.csv") or self.first("fig15_rebound_along_axis.png")

    @property
    def frf_dirs(self) -> list[tuple[str, Path]]:
        found = []
        for folder in self.with_file("quality.csv"):
            if folder.name.startswith("frf_"):
                label = folder.name[4:]
            else:
                tests = self.records.get(folder, {}).get("tests_file")
                label = Path(str(tests)).stem.removeprefix("hammer_") if tests else folder.name
            found.append((label, folder))
        return found

    @property
    def identifications(self) -> list[tuple[str, Path, str]]:
        """(label, folder, file suffix) of every identified model."""
        found = []
        for folder in self.with_file("modes*.csv"):
            for path in sorted(folder.glob("modes*.csv")):
                match = re.fullmatch(r"modes(_[\w-]+)?\.csv", path.name)
                if match is None:
                    continue
                suffix = match.group(1) or ""
                support = self.records.get(folder, {}).get("support")
                label = suffix[1:] if suffix else str(support or folder.name)
                found.append((label, folder, suffix))
        return found

    def head(self) -> _Head | None:
        if self.racket is not None:
            h = self.racket.head
            return _Head(h.centre_x_m, h.centre_y_m, h.half_length_m, h.half_width_m)
        for record in self.records.values():
            head = record.get("racket", {}).get("head") if isinstance(record, dict) else None
            if isinstance(head, dict):
                try:
                    return _Head(
                        float(head["centre_x_m"]),
                        float(head.get("centre_y_m", 0.0)),
                        float(head["half_length_m"]),
                        float(head["half_width_m"]),
                    )
                except (KeyError, TypeError, ValueError):
                    continue
        racket = self.named_racket()
        if racket is None:
            return None
        h = racket.head
        return _Head(h.centre_x_m, h.centre_y_m, h.half_length_m, h.half_width_m)

    def named_racket(self) -> Racket | None:
        """The racket a run.json names (built-in, or a TOML file still there), if any."""
        if not self.loaded:
            from racketdyn.io import default_racket, load_racket

            racket = None
            for record in self.records.values():
                name = str(record.get("racket_file", ""))
                try:
                    if name.startswith("built-in"):
                        racket = default_racket()
                    elif name and Path(name).is_file():
                        racket = load_racket(Path(name))
                except (InputError, OSError) as error:
                    log.warning("%s: not read (%s)", name, error)
                if racket is not None:
                    break
            self.loaded.append(racket)
        return self.loaded[0]

    def derived(self) -> dict[str, Any]:
        if self.racket is not None:
            return dict(self.racket.derived_properties())
        for folder in filter(None, (self.predict_dir, self.first("hammer_*.uff"))):
            derived = self.records.get(folder, {}).get("racket", {}).get("derived")
            if isinstance(derived, dict):
                return derived
        return {}

    # -- figures -------------------------------------------------------------------------------
    def figure(self, path: Path, label: str = "", wide: bool = False) -> str:
        """An embedded PNG with its caption (paper figure or none); empty if not a PNG."""
        try:
            data = path.read_bytes()
        except OSError:
            return ""
        if not data.startswith(_PNG_SIGNATURE):
            log.warning("%s: not a PNG; left out of the report", path)
            return ""
        stem = path.stem
        key = next(
            (k for k in sorted(_CAPTIONS, key=len, reverse=True) if stem.startswith(k)), None
        )
        paper, what = _CAPTIONS[key] if key else (None, stem.replace("_", " "))
        self.figures += 1
        return _figure_html(
            f'<img alt="{_e(what)}" src="data:image/png;base64,'
            f'{base64.b64encode(data).decode("ascii")}">',
            paper,
            what,
            f"{label}{' — ' if label else ''}{self.rel(path)}",
            "wide" if wide else "",
        )

    def figures_of(
        self, items: Sequence[tuple[str, Path]], pattern: str, wide: bool = False
    ) -> str:
        """One figure per (label, folder) found with ``pattern``, side by side when two."""
        parts = []
        for label, folder in items:
            path = folder / pattern.format(label=label)
            if path.is_file():
                parts.append(self.figure(path, label, wide))
        if not parts:
            return ""
        klass = "pair" if len(parts) > 1 and not wide else "stack"
        return f'<div class="{klass}">{"".join(parts)}</div>'


def _figure_html(body: str, paper: str | None, what: str, where: str, cls: str = "") -> str:
    lead = f"Kawazoe {paper}." if paper else "No figure in the paper."
    caption = f"<b>{_e(lead)}</b> {_e(what[0].upper() + what[1:])}."
    if where:
        caption += f' <span class="src">{_e(where)}</span>'
    klass = f' class="{cls}"' if cls else ""
    return f"<figure{klass}>{body}<figcaption>{caption}</figcaption></figure>"


# --- sections ---------------------------------------------------------------------------------


def _section_racket(ctx: _Context) -> str | None:
    racket_record: dict[str, Any] | None = None
    source = ""
    if ctx.racket is not None:
        from racketdyn.io import racket_to_dict

        racket_record, source = racket_to_dict(ctx.racket), "given to write_report"
    else:
        for folder in filter(None, (ctx.predict_dir, ctx.first("hammer_*.uff"))):
            record = ctx.records.get(folder, {})
            if isinstance(record.get("racket"), dict):
                racket_record = record["racket"]
                source = f"{record.get('racket_file', 'racket file')} ({ctx.rel(folder)}/run.json)"
                break
    if racket_record is None:
        return None
    derived = ctx.derived()
    parts = [f"<p><b>{_e(racket_record.get('name', 'racket'))}</b> — {_e(source)}.</p>"]
    inputs = []
    for key, value in racket_record.items():
        if key in ("name", "derived"):
            continue
        if isinstance(value, dict):
            for sub, subvalue in value.items():
                label, text, unit = _quantity(sub, subvalue)
                inputs.append((f"{key}: {label}", text, unit))
        elif isinstance(value, list):
            inputs.append((key.replace("_", " "), str(len(value)) if value else "none", ""))
        else:
            inputs.append(_quantity(key, value))
    rows = []
    for key, value in derived.items():
        name, text, unit = _quantity(key, value)
        rows.append((_DERIVED_LABELS.get(key.rpartition("_")[0], name), text, unit))
    parts.append('<div class="cols">')
    parts.append(
        "<div><h3>Derived properties</h3>" + _table(("property", "value", "unit"), rows) + "</div>"
    )
    parts.append(
        "<div><h3>Inputs</h3>" + _table(("input", "value", "unit"), inputs, "small") + "</div>"
    )
    parts.append("</div>")
    if derived:
        ctx.glance.append(
            f"{racket_record.get('name', 'racket')}: "
            f"{_fmt(derived.get('mass_kg', math.nan) * 1e3, '.0f')} g, balance "
            f"{_fmt(derived.get('balance_m', math.nan) * 1e3, '.0f')} mm, swingweight "
            f"{_fmt(derived.get('swingweight_kgcm2'), '.0f')} kg·cm²"
        )
    model = ctx.records.get(ctx.predict_dir, {}).get("modal_model") if ctx.predict_dir else None
    if isinstance(model, dict) and model.get("modes"):
        modes = [
            (
                str(m.get("name", "")),
                str(m.get("kind", "")),
                _fmt(m.get("frequency_hz"), ".1f"),
                _fmt(100 * float(m.get("damping_ratio", math.nan)), ".2f"),
            )
            for m in model["modes"]
        ]
        parts.append(
            f"<h3>Modes the prediction used</h3><p>{_e(model.get('source', ''))} "
            f"({_e(model.get('support', ''))} support).</p>"
            + _table(("mode", "kind", "frequency (Hz)", "damping (%)"), modes, numeric_from=2)
        )
    return "\n".join(parts)


def _quality_counts(path: Path) -> dict[str, Any]:
    rows, _ = _read_csv(path)
    reasons: dict[str, int] = {}
    nodes: dict[str, list[int]] = {}
    forces = []
    for row in rows:
        accepted = row.get("accepted") == "1"
        nodes.setdefault(row.get("node", ""), []).append(int(accepted))
        if accepted:
            forces.append(_float(row.get("peak_force_n")))
        for reason in filter(None, (row.get("reasons") or "").split(";")):
            reasons[reason] = reasons.get(reason, 0) + 1
    return {
        "averages": len(rows),
        "accepted": sum(int(r.get("accepted") == "1") for r in rows),
        "reasons": reasons,
        "points": len(nodes),
        "dead_points": [n for n, v in nodes.items() if not any(v)],
        "forces": np.array(forces, dtype=float),
    }


def _section_quality(ctx: _Context) -> str | None:
    folders = ctx.frf_dirs
    if not folders:
        return None
    labels = [label for label, _ in folders]
    counts = {label: _quality_counts(folder / "quality.csv") for label, folder in folders}
    reasons = sorted({r for c in counts.values() for r in c["reasons"]})
    rows: list[list[str]] = [
        ["hammer points", *(str(counts[k]["points"]) for k in labels)],
        ["averages", *(str(counts[k]["averages"]) for k in labels)],
        ["accepted", *(str(counts[k]["accepted"]) for k in labels)],
    ]
    rows += [
        [f"rejected: {reason}", *(str(counts[k]["reasons"].get(reason, 0)) for k in labels)]
        for reason in reasons
    ]
    if not reasons:
        rows.append(["rejected (any reason)", *("0" for _ in labels)])
    rows.append(
        [
            "points with every average rejected",
            *(", ".join(counts[k]["dead_points"]) or "none" for k in labels),
        ]
    )
    rows.append(
        [
            "peak hammer force, accepted (N)",
            *(
                f"{np.nanmin(f):.0f}–{np.nanmax(f):.0f}" if (f := counts[k]["forces"]).size else "–"
                for k in labels
            ),
        ]
    )
    settings = []
    for name, key, spec in (
        ("estimator", "estimator", ""),
        ("exponential window τ (s)", "exponential_window_s", "g"),
        ("force window (s)", "force_window_s", "g"),
        ("hammer range (N)", "force_range_n", "g"),
    ):
        values = []
        for _, folder in folders:
            value = ctx.records.get(folder, {}).get(key)
            values.append("not set" if value is None else _fmt(value, spec) if spec else value)
        settings.append([name, *map(str, values)])
    parts = [
        "<p>Every average of every hammer point is checked (non-finite, empty, force or response "
        "overload, double hit, trigger) and rejected with its reasons (<code>quality.csv</code>)."
        "</p>",
        '<div class="cols"><div><h3>Averages by verdict</h3>',
        _table(("", *labels), rows),
        "</div><div><h3>Settings</h3>",
        _table(("", *labels), settings),
        "</div></div>",
    ]
    for label in labels:
        c = counts[label]
        ctx.glance.append(
            f"hammer test ({label}): {c['accepted']} of {c['averages']} averages accepted "
            f"at {c['points']} points"
        )
    frf_plot = _frf_plot(ctx, folders)
    if frf_plot:
        parts.append(frf_plot)
    parts.append(ctx.figures_of(folders, "fig2_frf_frame.png"))
    parts.append(ctx.figures_of(folders, "fig3_frf_string_centre.png"))
    return "\n".join(parts)


def _frf_plot(ctx: _Context, folders: Sequence[tuple[str, Path]]) -> str:
    """Coherence table and the interactive FRF plot (driving point and string-bed centre)."""
    from racketdyn.io import read_frf_uff

    head = ctx.head()
    idents = {label: (folder, suffix) for label, folder, suffix in ctx.identifications}
    band = None
    for _, folder, _ in ctx.identifications:
        value = ctx.records.get(folder, {}).get("band_hz")
        if isinstance(value, list) and len(value) == 2:
            band = (float(value[0]), float(value[1]))
            break
    views: dict[str, list[dict[str, Any]]] = {"frame": [], "centre": []}
    modes: list[dict[str, Any]] = []
    coherence_rows = []
    frequency: NDArray[np.float64] | None = None
    unit = ""
    for n, (label, folder) in enumerate(folders):
        path = folder / "frfs.uff"
        if not path.is_file():
            continue
        try:
            frfs = read_frf_uff(path)
        except (InputError, OSError, ValueError) as error:
            log.warning("%s: not read (%s)", path, error)
            continue
        keep = frfs.frequency > 0
        if frequency is None:
            frequency = frfs.frequency[keep]
            unit = {"receptance": "m/N", "mobility": "m/(N·s)", "accelerance": "m/(N·s²)"}[
                frfs.frf_type
            ]
        elif frfs.frequency[keep].shape != frequency.shape or not np.allclose(
            frfs.frequency[keep], frequency
        ):
            log.warning("%s: frequency lines differ from the first FRF set; left out", path)
            continue
        colour = _SUPPORT_COLOURS.get(label, _SERIES_COLOURS[n % len(_SERIES_COLOURS)])
        frame = frfs.driving_point if frfs.driving_point is not None else 0
        centre_xy = (
            np.array([head.centre_x, head.centre_y])
            if head is not None
            else frfs.locations.mean(axis=0)
        )
        centre = int(np.argmin(np.linalg.norm(frfs.locations - centre_xy, axis=1)))
        for view, index in (("frame", frame), ("centre", centre)):
            coherence = None if frfs.coherence is None else frfs.coherence[index, keep]
            views[view].append(
                {
                    "label": f"{label}, node {frfs.nodes[index]}",
                    "colour": colour,
                    "mag": _round(np.abs(frfs.values[index, keep])),
                    "coh": None if coherence is None else _round(coherence, 3),
                }
            )
        if frfs.coherence is not None:
            lines = frequency >= (band[0] if band else 0.0)
            lines &= frequency <= (band[1] if band else np.inf)
            per_point = np.median(frfs.coherence[:, keep][:, lines], axis=1)
            worst = int(np.argmin(per_point))
            coherence_rows.append(
                [
                    label,
                    f"{np.median(per_point):.3f}",
                    f"{per_point[frame]:.3f}",
                    f"{per_point[worst]:.3f} (node {frfs.nodes[worst]})",
                ]
            )
        if label in idents:
            ident_folder, suffix = idents[label]
            rows, _ = _read_csv(ident_folder / f"modes{suffix}.csv")
            modes += [
                {
                    "f": _float(r.get("frequency_hz")),
                    "label": f"{r.get('name', '')} ({label})",
                    "colour": colour,
                }
                for r in rows
                if _finite(_float(r.get("frequency_hz")))
            ]
    if frequency is None or not views["frame"]:
        return ""
    step = max(1, math.ceil(frequency.size / _MAX_FRF_LINES))
    if step > 1:
        for series in views["frame"] + views["centre"]:
            series["mag"] = series["mag"][::step]
            series["coh"] = None if series["coh"] is None else series["coh"][::step]
    ctx.data["frf"].append(
        {
            "id": "frf-plot",
            "f": _round(frequency[::step], 6),
            "unit": unit,
            "views": [
                {"label": "driving point on the frame (Fig. 2)", "series": views["frame"]},
                {"label": "string-bed centre (Fig. 3)", "series": views["centre"]},
            ],
            "modes": modes,
        }
    )
    parts = []
    if coherence_rows:
        where = f"{band[0]:g}–{band[1]:g} Hz" if band else "all lines above 0 Hz"
        parts.append(
            f"<h3>Coherence</h3><p>Median of the ordinary coherence over {_e(where)}, "
            "per point; the table gives the median over the points, the driving point and the "
            "worst point.</p>"
            + _table(("", "median over points", "driving point", "worst point"), coherence_rows)
        )
    body = (
        '<div class="controls"></div><svg class="frf" viewBox="0 0 900 440" role="img" '
        'aria-label="FRF magnitude and coherence"></svg><div class="readout">'
        "Hover for values; mouse wheel or the buttons zoom the frequency axis, drag pans, "
        "double-click resets.</div>"
    )
    parts.append(
        _figure_html(
            f'<div class="interactive-body" id="frf-plot">{body}</div>',
            "Figs 2–3",
            "interactive FRF magnitude |H| (log scale) and coherence, free against hand-held, at "
            "the driving point (Fig. 2) or the string-bed centre (Fig. 3); dashed lines mark the "
            "identified natural frequencies",
            "frfs.uff",
            "interactive",
        )
    )
    return "\n".join(parts)


def _section_stabilisation(ctx: _Context) -> str | None:
    idents = ctx.identifications
    if not idents:
        return None
    pairs = [(label, folder, suffix) for label, folder, suffix in idents]
    parts = [
        "<p>Poles of the LSCF estimator for every model order; stable poles line up at "
        "the natural frequencies and the automatic selection keeps those clusters.</p>"
    ]

    def figures(stem: str) -> str:
        found = []
        for label, folder, suffix in pairs:
            path = folder / f"{stem}{suffix}.png"
            if path.is_file():
                found.append(ctx.figure(path, label))
        klass = "pair" if len(found) > 1 else "stack"
        return f'<div class="{klass}">{"".join(found)}</div>' if found else ""

    parts.append(figures("stabilisation"))
    tables = []
    for label, folder, suffix in pairs:
        rows, _ = _read_csv(folder / f"modes{suffix}.csv")
        body = [
            (
                r.get("name", ""),
                _fmt(_float(r.get("frequency_hz")), ".2f"),
                _fmt(100 * _float(r.get("damping_ratio")), ".3f"),
                r.get("orders_stable", ""),
                _fmt(_float(r.get("frequency_spread_hz")), ".3g"),
            )
            for r in rows
        ]
        fit = folder / f"fit_quality{suffix}.csv"
        note = ""
        if fit.is_file():
            errors = np.array([_float(r.get("fit_error")) for r in _read_csv(fit)[0]])
            if errors.size and np.isfinite(errors).any():
                note = (
                    f"<p>FRF fit error: median {np.nanmedian(errors):.1%}, "
                    f"largest {np.nanmax(errors):.1%}.</p>"
                )
        dropped = ctx.records.get(folder, {}).get("dropped") or []
        if dropped:
            note += "<p>Dropped: " + "; ".join(_e(d) for d in dropped) + ".</p>"
        tables.append(
            f"<div><h3>Identified modes, {_e(label)}</h3>"
            + _table(
                ("mode", "frequency (Hz)", "damping (%)", "orders stable", "spread (Hz)"), body
            )
            + note
            + "</div>"
        )
    parts.append(f'<div class="cols">{"".join(tables)}</div>')
    parts.append(figures("synthesised_frfs"))
    parts.append(figures("automac"))
    return "\n".join(parts)


def _section_modes(ctx: _Context) -> str | None:
    idents = ctx.identifications
    if not idents:
        return None
    parts = []
    for label, folder, suffix in idents:
        path = folder / f"fig4_mode_shapes{suffix}.png"
        if path.is_file():
            parts.append(ctx.figure(path, label, wide=True))
    node_lines = [
        ctx.figure(folder / f"fig5_node_lines{suffix}.png", label)
        for label, folder, suffix in idents
        if (folder / f"fig5_node_lines{suffix}.png").is_file()
    ]
    if node_lines:
        parts.append(
            f'<div class="{"pair" if len(node_lines) > 1 else "stack"}">'
            + "".join(node_lines)
            + "</div>"
        )
    compare = _mode_comparison_dir(ctx)
    overlay = compare / "fig6_nodes_free_hand.png" if compare else None
    if overlay is not None and overlay.is_file():
        parts.append(f'<div class="stack">{ctx.figure(overlay)}</div>')
    else:
        nodes = [
            ctx.figure(folder / f"fig6_nodes{suffix}.png", label)
            for label, folder, suffix in idents
            if (folder / f"fig6_nodes{suffix}.png").is_file()
        ]
        if nodes:
            parts.append(f'<div class="pair">{"".join(nodes)}</div>')
    if compare is not None:
        rows, _ = _read_csv(compare / "comparison.csv")
        body = [
            (
                r.get("mode", ""),
                _fmt(_float(r.get("frequency_free_hz")), ".2f"),
                _fmt(_float(r.get("frequency_hand_hz")), ".2f"),
                _fmt(_float(r.get("frequency_shift_percent")), "+.2f"),
                _fmt(100 * _float(r.get("damping_free")), ".3f"),
                _fmt(100 * _float(r.get("damping_hand")), ".3f"),
                _fmt(_float(r.get("damping_ratio_hand_over_free")), ".2f"),
                _fmt(_float(r.get("mac")), ".3f"),
            )
            for r in rows
        ]
        parts.append(
            "<h3>Free against hand-held (modes paired by MAC)</h3>"
            + _table(
                (
                    "mode",
                    "free (Hz)",
                    "hand-held (Hz)",
                    "shift (%)",
                    "ζ free (%)",
                    "ζ hand (%)",
                    "ζ hand / free",
                    "MAC",
                ),
                body,
            )
        )
        first_nodes = _first_mode_nodes(ctx)
        if first_nodes:
            parts.append(
                "<p>Nodes of the first mode along the long axis: "
                + "; ".join(
                    f"{_e(support)} " + ", ".join(f"{v * 1e3:.0f}" for v in values) + " mm"
                    for support, values in first_nodes.items()
                )
                + " from the butt.</p>"
            )
        if rows:
            first = rows[0]
            ctx.glance.append(
                f"{first.get('mode', 'first mode')}: "
                f"{_fmt(_float(first.get('frequency_free_hz')), '.1f')} Hz "
                f"free, {_fmt(_float(first.get('frequency_hand_hz')), '.1f')} Hz hand-held "
                f"({_fmt(_float(first.get('frequency_shift_percent')), '+.1f')} %), damping "
                f"×{_fmt(_float(first.get('damping_ratio_hand_over_free')), '.1f')} in the hand"
            )
        comparison_png = compare / "comparison.png"
        if comparison_png.is_file():
            parts.append(f'<div class="stack">{ctx.figure(comparison_png)}</div>')
    return "\n".join(p for p in parts if p)


def _is_model_comparison(path: Path) -> bool:
    """``comparison.csv`` of ``racketdyn predict --model both`` (approximate against
    transient), not the free-against-hand mode table of ``racketdyn compare``."""
    try:
        with path.open(encoding="utf-8") as handle:
            header = handle.readline()
    except OSError:
        return False
    return "transient_rebound_ratio" in header.split(",") or "transient_rebound_ratio\n" in header


def _mode_comparison_dir(ctx: _Context) -> Path | None:
    """The folder of ``racketdyn compare``'s ``comparison.csv`` (modes paired by MAC)."""
    for folder in ctx.with_file("comparison.csv"):
        if not _is_model_comparison(folder / "comparison.csv"):
            return folder
    return None


def _model_comparison_dir(ctx: _Context) -> Path | None:
    """The folder of ``racketdyn predict --model both``'s ``comparison.csv``."""
    for folder in ctx.with_file("comparison.csv"):
        if _is_model_comparison(folder / "comparison.csv"):
            return folder
    return None


def _first_mode_nodes(ctx: _Context) -> dict[str, list[float]]:
    """First-mode nodes along the axis (m) from ``comparison.csv``, by support."""
    compare = _mode_comparison_dir(ctx)
    if compare is None:
        return {}
    _, comments = _read_csv(compare / "comparison.csv")
    nodes = {}
    for comment in comments:
        match = re.search(r"axis, (\w+) \(m\): \[(.*)\]", comment)
        if match:
            nodes[match.group(1)] = [_float(v) for v in match.group(2).split(",") if v.strip()]
    return nodes


def _map_spec(
    ctx: _Context,
    map_id: str,
    groups: list[dict[str, Any]],
    fields: list[tuple[str, str, int]],
    colour: int,
    initial: int,
    xy: NDArray[np.float64],
    marks: list[dict[str, Any]],
    best: str,
) -> dict[str, Any]:
    """Data of an interactive face map: one panel per support, one group per speed (mm)."""
    head = ctx.head()
    xs, ys = xy[:, 0] * 1e3, xy[:, 1] * 1e3
    if head is not None:
        xs = np.append(
            xs, [1e3 * (head.centre_x - head.half_length), 1e3 * (head.centre_x + head.half_length)]
        )
        ys = np.append(
            ys, [1e3 * (head.centre_y - head.half_width), 1e3 * (head.centre_y + head.half_width)]
        )
    span = max(float(np.ptp(xs)), float(np.ptp(ys)), 1.0)
    pad = 0.06 * span
    font = 0.035 * (float(xs.max() - xs.min()) + 2 * pad)
    frame = [
        round(float(xs.min()) - pad, 1),
        round(float(xs.max()) + pad, 1),
        round(float(ys.min()) - pad, 1),
        round(float(ys.max()) + pad + (0.9 * len(marks) + 0.6) * font, 1),
    ]
    # dots of 0.42 of the median distance to the nearest neighbour: a grid reads as a heat map
    unique = np.unique(np.round(xy * 1e3, 1), axis=0)
    if len(unique) > 1:
        from scipy.spatial import cKDTree

        distance, _ = cKDTree(unique).query(unique, k=2)
        radius = 0.42 * float(np.median(np.asarray(distance)[:, 1]))
    else:
        radius = 0.02 * span
    radius = float(np.clip(radius, 0.006 * span, 0.04 * span))
    return {
        "id": map_id,
        "frame": frame,
        "radius": round(radius, 2),
        "font": round(font, 1),
        "head": None
        if head is None
        else [
            round(head.centre_x * 1e3, 2),
            round(head.centre_y * 1e3, 2),
            round(head.half_length * 1e3, 2),
            round(head.half_width * 1e3, 2),
        ],
        "fields": [list(f) for f in fields],
        "colour": colour,
        "best": best,
        "groups": groups,
        "initial": initial,
        "marks": marks,
    }


def _interactive_map(map_id: str, paper: str | None, what: str, where: str) -> str:
    body = (
        f'<div class="interactive-body" id="{map_id}"><div class="controls"></div>'
        '<div class="panels"></div></div>'
    )
    return _figure_html(body, paper, what, where, "interactive")


def _section_contact(ctx: _Context) -> str | None:
    folder = ctx.first("contact_*.csv") or ctx.first("fig7_contact_time.png")
    if folder is None:
        return None
    parts = []
    figure = folder / "fig7_contact_time.png"
    if figure.is_file():
        parts.append(f'<div class="stack">{ctx.figure(figure)}</div>')
    head = ctx.head()
    record = ctx.records.get(folder, {})
    labels = [str(v) for v in record.get("labels", [])]
    tables = []
    for path in sorted(folder.glob("contact_*.csv")):
        label = path.stem.removeprefix("contact_")
        rows, _ = _read_csv(path)
        xy = np.array([[_float(r.get("x_m")), _float(r.get("y_m"))] for r in rows], dtype=float)
        mean = np.array([_float(r.get("contact_time_mean_s")) for r in rows], dtype=float)
        spread = np.array([_float(r.get("contact_time_std_s")) for r in rows], dtype=float)
        n = np.array([_float(r.get("n_averages")) for r in rows], dtype=float)
        node = np.array([_float(r.get("node")) for r in rows], dtype=float)
        if not rows:
            continue
        tables.append((label, xy, mean, spread, n, node))
    if labels and len(labels) == len(tables):
        order = {name: i for i, name in enumerate(labels)}
        tables.sort(key=lambda t: order.get(t[0], len(order)))
    summary = []
    panels: list[dict[str, Any]] = []
    for label, xy, mean, spread, n, node in tables:
        on_bed = head.contains(xy[:, 0], xy[:, 1]) if head is not None else np.ones(len(xy), bool)
        for where, mask in (("strings", on_bed), ("frame", ~on_bed)):
            values = mean[mask & np.isfinite(mean)] * 1e3
            if values.size:
                summary.append(
                    (
                        label,
                        where,
                        str(values.size),
                        f"{values.min():.2f}",
                        f"{np.median(values):.2f}",
                        f"{values.max():.2f}",
                    )
                )
        keep = np.flatnonzero(on_bed)
        rows_json = [
            [
                round(float(xy[i, 0]) * 1e3, 1),
                round(float(xy[i, 1]) * 1e3, 1),
                round(float(mean[i]) * 1e3, 4) if math.isfinite(mean[i]) else None,
                round(float(spread[i]) * 1e3, 4) if math.isfinite(spread[i]) else None,
                int(n[i]) if math.isfinite(n[i]) else None,
                int(node[i]) if math.isfinite(node[i]) else None,
                "" if math.isfinite(mean[i]) else "no contact time",
            ]
            for i in keep
        ]
        panels.append({"label": label, "rows": rows_json, "xy": xy[keep]})
    if summary:
        parts.append(
            "<h3>Hammer contact time (ms)</h3>"
            + _table(
                ("support", "where", "points", "shortest", "median", "longest"),
                summary,
                numeric_from=2,
            )
        )
    if panels and any(p["rows"] for p in panels):
        values = [r[2] for p in panels for r in p["rows"] if r[2] is not None]
        group = {
            "label": "hammer",
            "range": [min(values), max(values)] if values else [0.0, 1.0],
            "panels": [{"label": p["label"], "rows": p["rows"]} for p in panels],
        }
        spec = _map_spec(
            ctx,
            "map-contact",
            [group],
            [
                ("x", "mm", 0),
                ("y", "mm", 0),
                ("contact time", "ms", 2),
                ("spread (std)", "ms", 3),
                ("averages", "", 0),
                ("node", "", 0),
            ],
            2,
            0,
            np.vstack([p["xy"] for p in panels]),
            [],
            "",
        )
        ctx.data["maps"].append(spec)
        parts.append(
            _interactive_map(
                "map-contact",
                "Fig. 7",
                "hammer contact time at each hammer point on the strings; hover for the values",
                "contact_*.csv",
            )
        )
    return "\n".join(parts) if parts else None


def _impacts(ctx: _Context) -> _Impacts | None:
    folder = ctx.predict_dir
    path = folder / "impact.csv" if folder else None
    if path is None or not path.is_file():
        return None
    if not ctx.impacts_read:
        ctx.impacts_read.append(_Impacts.read(path))
    return ctx.impacts_read[0]


def _centre(ctx: _Context, impacts: _Impacts) -> tuple[float, float]:
    head = ctx.head()
    if head is not None:
        return head.centre_x, head.centre_y
    return float(np.nanmean(impacts["x_m"])), float(np.nanmean(impacts["y_m"]))


def _chosen_speed(speeds: Sequence[float]) -> float:
    return speeds[shown_speed_index(speeds)]


def _section_impact(ctx: _Context) -> str | None:
    folder = ctx.predict_dir
    if folder is None:
        return None
    parts = []
    for name in ("fig11_12_force_contact_time.png", "fig13_pulse_spectrum.png"):
        figure = folder / name
        if figure.is_file():
            parts.append(f'<div class="stack">{ctx.figure(figure)}</div>')
    impacts = _impacts(ctx)
    if impacts is not None:
        x, y = _centre(ctx, impacts)
        rows = []
        for support in impacts.supports:
            for speed in impacts.speeds:
                selected = impacts.rows(speed, support)
                if not selected.size:
                    continue
                i = impacts.nearest(selected, x, y)
                rows.append(
                    (
                        support,
                        f"{speed:g}",
                        _fmt(impacts["contact_time_s"][i] * 1e3, ".2f"),
                        _fmt(impacts["mean_force_n"][i], ".0f"),
                        _fmt(impacts["peak_force_n"][i], ".0f"),
                        _fmt(impacts["peak_deflection_m"][i] * 1e3, ".1f"),
                        _fmt(impacts["stiffness_n_per_m"][i] / 1e3, ".1f"),
                    )
                )
        i0 = impacts.nearest(np.arange(impacts.support.size), x, y)
        parts.append(
            f"<h3>At the point nearest the face centre (x = {impacts['x_m'][i0] * 1e3:.0f} mm, "
            f"y = {impacts['y_m'][i0] * 1e3:.0f} mm), from impact.csv</h3>"
            + _table(
                (
                    "support",
                    "ball speed (m/s)",
                    "contact time (ms)",
                    "mean force (N)",
                    "peak force (N)",
                    "peak deflection (mm)",
                    "stiffness K_GB (kN/m)",
                ),
                rows,
            )
        )
        speed = _chosen_speed(impacts.speeds)
        for support in ("pinned", "free"):
            selected = impacts.rows(speed, support)
            if selected.size:
                i = impacts.nearest(selected, x, y)
                ctx.glance.append(
                    f"face centre, {speed:g} m/s, {support}: contact time "
                    f"{_fmt(impacts['contact_time_s'][i] * 1e3, '.2f')} ms, mean force "
                    f"{_fmt(impacts['mean_force_n'][i], '.0f')} N, rebound ratio "
                    f"{_fmt(impacts['rebound_ratio'][i], '.3f')}"
                )
                break
    return "\n".join(parts) if parts else None


def _section_vibration(ctx: _Context) -> str | None:
    folder = ctx.predict_dir
    if folder is None:
        return None
    parts = []
    figure = folder / "fig14_frame_vibration.png"
    if figure.is_file():
        parts.append(f'<div class="stack">{ctx.figure(figure)}</div>')
    impacts = _impacts(ctx)
    record = ctx.records.get(folder, {})
    ball_mass = _float(str(record.get("ball", {}).get("mass_kg", "")))
    if impacts is not None and "vibration_energy_j" in impacts.numbers:
        x, y = _centre(ctx, impacts)
        energy = impacts["vibration_energy_j"]
        rows = []
        for support in impacts.supports:
            for speed in impacts.speeds:
                selected = impacts.rows(speed, support)
                if not selected.size:
                    continue
                i = impacts.nearest(selected, x, y)
                finite = selected[np.isfinite(energy[selected])]
                largest = int(finite[np.argmax(energy[finite])]) if finite.size else None
                smallest = int(finite[np.argmin(energy[finite])]) if finite.size else None
                incoming = 0.5 * ball_mass * speed**2
                flagged = int(np.sum(impacts.status[selected] != "ok"))
                rows.append(
                    (
                        support,
                        f"{speed:g}",
                        _fmt(energy[i], ".3g"),
                        _fmt(100 * energy[i] / incoming, ".2g"),
                        "–" if largest is None else f"{energy[largest]:.3g}",
                        "–" if largest is None else impacts.where(largest),
                        "–" if smallest is None else f"{energy[smallest]:.3g}",
                        "–" if smallest is None else impacts.where(smallest),
                        str(flagged),
                    )
                )
        parts.append(
            "<h3>Vibration energy left in the frame (eq 12), from impact.csv</h3>"
            + _table(
                (
                    "support",
                    "ball speed (m/s)",
                    "at the centre (J)",
                    "of the ball's energy (%)",
                    "largest on the face (J)",
                    "at x, y (mm)",
                    "smallest on the face (J)",
                    "at x, y (mm)",
                    "rows flagged",
                ),
                rows,
            )
        )
        bad = impacts.status != "ok"
        if np.any(bad):
            reasons, counts = np.unique(impacts.status[bad], return_counts=True)
            parts.append(
                "<p>Flagged rows (NaN in impact.csv, drawn hollow in the maps): "
                + "; ".join(f"{c} × {_e(r)}" for r, c in zip(reasons, counts, strict=True))
                + ".</p>"
            )
    return "\n".join(parts) if parts else None


def _section_rebound(ctx: _Context) -> str | None:
    folder = ctx.predict_dir
    compare = ctx.first("fig15_identified.png")
    if folder is None and compare is None:
        return None
    parts = []
    for path in (
        folder / "fig15_rebound_along_axis.png" if folder else None,
        compare / "fig15_identified.png" if compare else None,
    ):
        if path is not None and path.is_file():
            parts.append(ctx.figure(path))
    if parts:
        parts = [f'<div class="{"pair" if len(parts) > 1 else "stack"}">{"".join(parts)}</div>']
    if folder is not None and (folder / "face_maps.png").is_file():
        parts.append(f'<div class="stack">{ctx.figure(folder / "face_maps.png")}</div>')
    impacts = _impacts(ctx)
    if impacts is None:
        return "\n".join(parts) if parts else None
    derived = ctx.derived()
    nodes = _first_mode_nodes(ctx)
    head = ctx.head()
    marks = []
    cop = derived.get("centre_of_percussion_m")
    if isinstance(cop, int | float):
        marks.append({"x": round(cop * 1e3, 1), "label": "CoP"})
    for support, values in nodes.items():
        for node in values:
            if head is None or abs(node - head.centre_x) < head.half_length:
                marks.append({"x": round(node * 1e3, 1), "label": f"node ({support})"})
    speeds = impacts.speeds
    chosen = _chosen_speed(speeds)
    if len(speeds) > _MAX_MAP_SPEEDS:
        picks = np.unique(np.linspace(0, len(speeds) - 1, _MAX_MAP_SPEEDS).round().astype(int))
        speeds = sorted({speeds[i] for i in picks} | {chosen})
    groups = []
    fields = [
        ("x", "mm", 0),
        ("y", "mm", 0),
        ("rebound ratio", "", 3),
        ("contact time", "ms", 2),
        ("rebound speed", "m/s", 1),
        ("vibration energy", "J", 3),
        ("reduced mass", "g", 0),
    ]
    thinned = False
    all_xy = []
    sweet = []
    for speed in speeds:
        panels: list[dict[str, Any]] = []
        for support in impacts.supports:
            selected = impacts.rows(speed, support)
            if selected.size > _MAX_MAP_POINTS:
                selected = selected[:: math.ceil(selected.size / _MAX_MAP_POINTS)]
                thinned = True
            e = impacts["rebound_ratio"]
            rows = [
                [
                    round(float(impacts["x_m"][i]) * 1e3, 1),
                    round(float(impacts["y_m"][i]) * 1e3, 1),
                    *(
                        None if not math.isfinite(v) else float(f"{v:.5g}")
                        for v in (
                            e[i],
                            impacts["contact_time_s"][i] * 1e3,
                            impacts["rebound_speed_mps"][i],
                            impacts["vibration_energy_j"][i],
                            impacts["reduced_mass_kg"][i] * 1e3,
                        )
                    ),
                    "" if impacts.status[i] == "ok" else str(impacts.status[i]),
                ]
                for i in selected
            ]
            panels.append({"label": support, "rows": rows})
            all_xy.append(np.column_stack([impacts["x_m"][selected], impacts["y_m"][selected]]))
            finite = selected[np.isfinite(e[selected])]
            if finite.size:
                best = int(finite[np.argmax(e[finite])])
                x, y = _centre(ctx, impacts)
                centre = impacts.nearest(selected, x, y)
                calm = impacts["vibration_energy_j"]
                calm_rows = finite[np.isfinite(calm[finite])]
                quiet = int(calm_rows[np.argmin(calm[calm_rows])]) if calm_rows.size else None
                sweet.append(
                    (
                        support,
                        f"{speed:g}",
                        f"{e[best]:.3f}",
                        impacts.where(best),
                        _fmt(e[centre], ".3f"),
                        "–" if quiet is None else impacts.where(quiet),
                    )
                )
                if speed == chosen and support == "pinned":
                    ctx.glance.append(
                        f"highest rebound ratio at {speed:g} m/s, pinned: {e[best]:.3f} at "
                        f"x = {impacts['x_m'][best] * 1e3:.0f} mm, "
                        f"y = {impacts['y_m'][best] * 1e3:.0f} mm"
                    )
        values = [r[2] for p in panels for r in p["rows"] if r[2] is not None]
        groups.append(
            {
                "label": f"{speed:g} m/s",
                "range": [min(values), max(values)] if values else [0.0, 1.0],
                "panels": panels,
            }
        )
    spec = _map_spec(
        ctx,
        "map-rebound",
        groups,
        fields,
        2,
        speeds.index(chosen),
        np.vstack(all_xy),
        marks,
        "max",
    )
    ctx.data["maps"].append(spec)
    notes = " (points thinned for the page)" if thinned else ""
    parts.append(
        _interactive_map(
            "map-rebound",
            None,
            f"rebound ratio over the face from impact.csv{notes}, one panel per support, "
            "one shared colour scale per speed; hover a point for x, y, rebound ratio, contact "
            "time and more; the ringed point is the highest rebound ratio, dashed lines the "
            "centre of percussion (CoP) and the first-mode nodes; the paper shows the long axis "
            "only (Fig. 15)",
            "impact.csv",
        )
    )
    order = {support: n for n, support in enumerate(impacts.supports)}
    sweet.sort(key=lambda row: (order[row[0]], float(row[1])))
    parts.append(
        "<h3>Sweet spots</h3><p>Over the impact points of impact.csv, racket at rest.</p>"
        + _table(
            (
                "support",
                "ball speed (m/s)",
                "highest rebound ratio",
                "at x, y (mm)",
                "rebound ratio at the centre",
                "least vibration energy at x, y (mm)",
            ),
            sweet,
        )
    )
    spots = []
    if isinstance(cop, int | float):
        spots.append(
            f"centre of percussion (pivot at the grip): x = {cop * 1e3:.0f} mm — the least "
            "shock to the hand"
        )
    for support, values in nodes.items():
        spots.append(
            f"first-mode nodes on the axis, {support}: "
            + ", ".join(f"x = {v * 1e3:.0f} mm" for v in values)
            + " — the least vibration"
        )
    if spots:
        parts.append("<ul>" + "".join(f"<li>{_e(s)}</li>" for s in spots) + "</ul>")
    return "\n".join(parts)


def _section_transient(ctx: _Context) -> str | None:
    folder = _model_comparison_dir(ctx)
    if folder is None:
        return None
    parts = [
        "<p>The same impacts by Kawazoe's approximate method (half-sine pulse, vibration "
        "charged by eq 12) and by the transient simulation of the contact (ball on the "
        "hysteretic ball+string spring, the racket's rigid-body reduced mass and its flexible "
        "modes, integrated to separation), from <code>comparison.csv</code>. Δ = approximate "
        "− transient: the transient simulation is the reference.</p>"
    ]
    record = ctx.records.get(folder, {})
    engine = record.get("engine")
    integrator = record.get("integrator")
    if isinstance(engine, dict) or isinstance(integrator, dict):
        used = engine.get("used", "–") if isinstance(engine, dict) else "–"
        settings = (
            ", ".join(f"{k} {v}" for k, v in integrator.items())
            if isinstance(integrator, dict)
            else "–"
        )
        parts.append(f"<p>Transient engine: {_e(used)}; integrator: {_e(settings)}.</p>")
    for name in (
        "transient_comparison_face.png",
        "transient_comparison_speed.png",
        "transient_histories.png",
    ):
        if (folder / name).is_file():
            parts.append(f'<div class="stack">{ctx.figure(folder / name)}</div>')
    rows, _ = _read_csv(folder / "comparison.csv")
    if not rows:
        return "\n".join(parts)
    x = np.array([_float(r.get("x_m")) for r in rows])
    y = np.array([_float(r.get("y_m")) for r in rows])
    speed = np.array([_float(r.get("ball_speed_mps")) for r in rows])
    support = np.array([r.get("support", "") for r in rows])
    delta = np.array([_float(r.get("difference_rebound_ratio")) for r in rows])
    e_approx = np.array([_float(r.get("approx_rebound_ratio")) for r in rows])
    e_transient = np.array([_float(r.get("transient_rebound_ratio")) for r in rows])
    contact = np.array([_float(r.get("relative_difference_contact_time")) for r in rows])
    head = ctx.head()
    centre_x, centre_y = (
        (head.centre_x, head.centre_y) if head else (float(np.nanmean(x)), float(np.nanmean(y)))
    )
    body = []
    speeds = sorted({float(v) for v in speed if math.isfinite(v)})
    chosen = _chosen_speed(speeds) if speeds else math.nan
    for name in dict.fromkeys(support.tolist()):
        for value in speeds:
            selected = np.flatnonzero((support == name) & (speed == value))
            if not selected.size:
                continue
            centre = int(
                selected[np.argmin(np.hypot(x[selected] - centre_x, y[selected] - centre_y))]
            )
            finite = selected[np.isfinite(delta[selected])]
            if finite.size:
                worst = int(finite[np.argmax(np.abs(delta[finite]))])
                largest = f"{abs(delta[worst]):.3f}"
                where = f"{x[worst] * 1e3:.0f}, {y[worst] * 1e3:.0f}"
                median = _fmt(float(np.median(delta[finite])), "+.3f")
                median_contact = _fmt(100 * float(np.nanmedian(contact[finite])), "+.1f")
            else:
                largest, where, median, median_contact = "–", "–", "–", "–"
            body.append(
                (
                    name,
                    f"{value:g}",
                    largest,
                    where,
                    median,
                    _fmt(e_approx[centre], ".3f"),
                    _fmt(e_transient[centre], ".3f"),
                    median_contact,
                    str(int(selected.size - finite.size)),
                )
            )
            if value == chosen and name == support[0] and finite.size:
                ctx.glance.append(
                    f"approximate against transient, {value:g} m/s, {name}: rebound ratio at "
                    f"the centre {_fmt(e_approx[centre], '.3f')} against "
                    f"{_fmt(e_transient[centre], '.3f')}; largest |Δ| {largest} at "
                    f"x, y = {where} mm"
                )
    parts.append(
        "<h3>Rebound ratio, approximate − transient, over the impact points of "
        "comparison.csv</h3>"
        + _table(
            (
                "support",
                "ball speed (m/s)",
                "largest |Δ rebound ratio|",
                "at x, y (mm)",
                "median Δ over the face",
                "at the centre: approximate",
                "at the centre: transient",
                "median Δ contact time (%)",
                "points without a number in one model",
            ),
            body,
        )
    )
    return "\n".join(parts)


def _rows_of(path: Path) -> list[dict[str, str]]:
    try:
        rows, _ = _read_csv(path)
    except (OSError, UnicodeDecodeError, csv.Error) as error:
        log.warning("%s: not read (%s)", path, error)
        return []
    return rows


def _section_swing(ctx: _Context) -> str | None:
    folder = ctx.first("swing.csv") or ctx.first("sweet_spots.csv")
    if folder is None:
        return None
    record = ctx.records.get(folder, {})
    swing = record.get("swing")
    if not isinstance(swing, dict):
        swing = {}
    parts = [
        "<p>Kawazoe closes his discussion of the rebound (section 4.2, last paragraph): "
        "<q>In an actual swing, the racket velocity differs according to the impact location"
        "</q>, and physical body movements must be considered. Here arm and racket, rigidly "
        "joined, turn about the shoulder under a constant shoulder torque, the forehand model "
        "of Kawazoe (ACMD 2002, 56.9 N·m): ½ I Ω² = T Δθ. A point x from the butt meets the "
        "ball at V = Ω (x + d), d the shoulder's distance behind the butt, and sends it back "
        "at e v<sub>ball</sub> + (1 + e) V, e the rebound ratio there (Cross).</p>"
    ]
    omega = swing.get("angular_speed_radps", record.get("angular_speed_radps"))
    facts = []
    if "torque_nm" in swing:
        facts.append(f"shoulder torque {_fmt(swing.get('torque_nm'), 'g')} N·m")
        angle = swing.get("swing_angle_rad")
        if isinstance(angle, int | float):
            facts.append(f"swing angle {math.degrees(angle):.0f}°")
        facts.append(
            f"arm {_fmt(swing.get('arm_mass_kg'), '.3g')} kg, "
            f"{_fmt(swing.get('arm_inertia_kgm2'), '.3g')} kg·m² about the shoulder"
        )
    if isinstance(swing.get("axis_to_butt_m"), int | float):
        facts.append(f"shoulder {swing['axis_to_butt_m'] * 1e3:.0f} mm behind the butt")
    if isinstance(swing.get("inertia_about_axis_kgm2"), int | float):
        facts.append(f"arm + racket {swing['inertia_about_axis_kgm2']:.3g} kg·m² about it")
    if isinstance(omega, int | float):
        facts.append(f"Ω = {omega:.2f} rad/s")
    model = record.get("impact_model")
    support = record.get("support")
    if model or support:
        facts.append(f"{model or '?'} impact model, {support or '?'}")
    if facts:
        parts.append(f"<p>Swing: {_e('; '.join(facts))}.</p>")
    figures = [
        ctx.figure(folder / name)
        for name in ("swing_map.png", "swing_along_axis.png")
        if (folder / name).is_file()
    ]
    if figures:
        parts.append(f'<div class="stack">{"".join(figures)}</div>')
    rows = _rows_of(folder / "sweet_spots.csv") if (folder / "sweet_spots.csv").is_file() else []
    if rows:
        speed = record.get("sweet_spots_at_mps")
        heading = "Sweet spots" + (
            f", ball {_fmt(speed, 'g')} m/s" if isinstance(speed, int | float) else ""
        )
        body = []
        for row in rows:
            value = _float(row.get("value"))
            key = row.get("key", "")
            shown = (
                "–"
                if not math.isfinite(value)
                else f"{value:.1f} m/s"
                if key == "max_rebound_speed"
                else f"{value:.3f}"
            )
            body.append(
                (
                    row.get("name", key),
                    _fmt(_float(row.get("x_m")) * 1e3, ".0f"),
                    "yes" if row.get("on_face") == "True" else "no",
                    _fmt(_float(row.get("racket_speed_mps")), ".1f"),
                    _fmt(_float(row.get("rebound_speed_mps")), ".1f"),
                    shown,
                    row.get("definition", ""),
                )
            )
        parts.append(
            f"<h3>{_e(heading)}</h3>"
            + _table(
                (
                    "sweet spot",
                    "x from the butt (mm)",
                    "on the face",
                    "racket speed there (m/s)",
                    "outgoing ball speed (m/s)",
                    "largest value",
                    "what it is",
                ),
                body,
                "small",
            )
        )
        spots = {row.get("key", ""): row for row in rows}
        best = spots.get("max_rebound_speed")
        if best is not None and math.isfinite(_float(best.get("value"))):
            text = (
                f"swinging racket (Ω = {_fmt(omega, '.1f')} rad/s"
                + (f", ball {_fmt(speed, 'g')} m/s" if isinstance(speed, int | float) else "")
                + f", {support or '?'}): largest outgoing speed {_float(best.get('value')):.1f}"
                f" m/s at x = {_float(best.get('x_m')) * 1e3:.0f} mm"
            )
            for key, label in (
                ("centre_of_percussion_grip", "centre of percussion (grip)"),
                ("first_mode_node", "first-mode node"),
            ):
                if key in spots:
                    text += f"; {label} {_float(spots[key].get('x_m')) * 1e3:.0f} mm"
            ctx.glance.append(text)
    return "\n".join(parts)


def _section_oblique(ctx: _Context) -> str | None:
    twist = ctx.first("twist.csv")
    oblique = ctx.first("oblique.csv")
    if twist is None and oblique is None:
        return None
    parts = []
    if twist is not None:
        parts.append(
            "<h3>Twist against the offset from the long axis</h3><p>A ball that lands off the "
            "long axis turns the racket about it. The transient simulation gives the racket's "
            "rigid roll at separation and the section rotation of its flexible modes at the "
            "impact point; for a rigid racket the roll rate is J y / I<sub>roll</sub>, so the "
            "twist grows with the offset and falls with the twistweight. A positive roll turns "
            "the hit side away from the ball.</p>"
        )
        if (twist / "twist.png").is_file():
            parts.append(f'<div class="stack">{ctx.figure(twist / "twist.png")}</div>')
        rows = _rows_of(twist / "twist.csv")
        body = []
        for support in dict.fromkeys(r.get("support", "") for r in rows):
            mine = [r for r in rows if r.get("support", "") == support]
            y = np.array([_float(r.get("y_m")) for r in mine])
            roll = np.array([_float(r.get("roll_angle_rad")) for r in mine])
            flexible = np.array([_float(r.get("flexible_twist_rad")) for r in mine])
            speed = np.array([_float(r.get("rebound_speed_mps")) for r in mine])
            if not mine or not np.any(np.isfinite(roll)):
                continue
            valid = [i for i in range(len(mine)) if math.isfinite(roll[i])]
            far = max(valid, key=lambda i: (abs(y[i]), y[i]))  # the +y side on a tie
            near = min(valid, key=lambda i: abs(y[i]))
            share = float(np.nanmax(np.abs(flexible)) / max(float(np.nanmax(np.abs(roll))), 1e-300))
            body.append(
                (
                    support,
                    _fmt(y[far] * 1e3, ".0f"),
                    _fmt(math.degrees(roll[far]), ".2f"),
                    _fmt(speed[near], ".2f"),
                    _fmt(speed[far], ".2f"),
                    _fmt(100 * share, ".2g"),
                )
            )
            ctx.glance.append(
                f"off-axis impact, {support}, x = {_float(mine[far].get('x_m')) * 1e3:.0f} mm, "
                f"ball {_fmt(_float(mine[far].get('ball_speed_mps')), 'g')} m/s: "
                f"{y[far] * 1e3:.0f} mm off the axis the racket rolls "
                f"{math.degrees(roll[far]):.1f}° and the ball leaves at {speed[far]:.1f} m/s "
                f"({speed[near]:.1f} m/s on the axis)"
            )
        if body:
            parts.append(
                _table(
                    (
                        "support",
                        "largest offset (mm)",
                        "roll there (°)",
                        "outgoing speed on the axis (m/s)",
                        "outgoing speed there (m/s)",
                        "modes' section rotation / roll, largest (%)",
                    ),
                    body,
                    "small",
                )
            )
    else:
        parts.append(
            f'<p class="note">Twist against offset not run: <code>'
            f"{_e('racketdyn twist --support free,hand --out DIR/twist')}</code></p>"
        )
    if oblique is not None:
        record = ctx.records.get(oblique, {})
        contact = record.get("tangential_contact")
        parts.append(
            "<h3>Oblique impacts and spin</h3><p>The ball arrives at an angle to the face "
            "normal. The normal part is the transient simulation; along the face the ball's "
            "contact point meets the strings through an elastic–Coulomb contact (a tangential "
            "spring k<sub>t</sub> that slides at μ F<sub>n</sub>) driven by the simulated normal "
            "force. Angles are measured from the face normal; spin is positive in the sense of "
            "rolling along the face in the direction the ball travels.</p>"
        )
        if isinstance(contact, dict):
            parts.append(
                f"<p>μ = {_e(_fmt(contact.get('friction_coefficient'), 'g'))}, k<sub>t</sub> = "
                f"{_e(_fmt(contact.get('stiffness_n_per_m'), '.3g'))} N/m (half period of the "
                "grip oscillation "
                f"{_e(_fmt(_float(str(contact.get('grip_period_s'))) * 0.5e3, '.2f'))} ms); ball "
                f"{_e(_fmt(record.get('ball_speed_mps'), 'g'))} m/s at x, y = "
                f"{_e(', '.join(_fmt(v * 1e3, '.0f') for v in record.get('point_m', [])))} mm, "
                f"{_e(record.get('support', '?'))}.</p>"
            )
        parts.append(
            '<p class="warn">Caveat: the tangential contact has no damping, so a ball that '
            "grips gives back what the spring stored, and the outgoing spin depends strongly on "
            "k<sub>t</sub>: treat it as the upper end of the model's range until k<sub>t</sub> "
            "and a tangential loss are fitted to measured rebound spin.</p>"
        )
        if (oblique / "oblique.png").is_file():
            parts.append(f'<div class="stack">{ctx.figure(oblique / "oblique.png")}</div>')
        rows = _rows_of(oblique / "oblique.csv")
        usable = [r for r in rows if r.get("status") == "ok"]
        if usable:
            shown = min(usable, key=lambda r: abs(abs(_float(r.get("incoming_angle_deg"))) - 30))
            ctx.glance.append(
                f"oblique impact at {_float(shown.get('incoming_angle_deg')):g}°, ball "
                f"{_float(shown.get('ball_speed_mps')):g} m/s, {record.get('support', '?')}: "
                f"leaves at {_float(shown.get('outgoing_angle_deg')):.1f}° with "
                f"{_float(shown.get('outgoing_spin_radps')):.0f} rad/s of spin (the spin "
                "depends strongly on the tangential stiffness k_t)"
            )
        angle_rows = [
            (
                _fmt(_float(r.get("incoming_angle_deg")), "g"),
                _fmt(_float(r.get("incoming_spin_radps")), "g"),
                _fmt(_float(r.get("outgoing_angle_deg")), ".1f"),
                _fmt(_float(r.get("outgoing_spin_radps")), ".0f"),
                _fmt(_float(r.get("normal_speed_mps")), ".2f"),
                _fmt(_float(r.get("tangential_speed_mps")), ".2f"),
                "yes" if r.get("gripped") == "True" else "no",
                r.get("status", ""),
            )
            for r in rows
        ]
        if angle_rows:
            parts.append(
                _table(
                    (
                        "incoming angle (°)",
                        "incoming spin (rad/s)",
                        "outgoing angle (°)",
                        "outgoing spin (rad/s)",
                        "normal speed out (m/s)",
                        "speed along the face out (m/s)",
                        "gripped",
                        "status",
                    ),
                    angle_rows,
                    "small",
                    numeric_from=0,
                )
            )
    else:
        parts.append(
            f'<p class="note">Oblique impacts not run: <code>'
            f"{_e('racketdyn oblique --out DIR/oblique')}</code></p>"
        )
    return "\n".join(parts)


def _section_provenance(ctx: _Context) -> str | None:
    if not ctx.records:
        return None
    parts = [
        f"<p>Report written {_e(datetime.now(UTC).isoformat(timespec='seconds'))} by racketdyn "
        f"{_e(__version__)} (Python {_e(platform.python_version())}, NumPy {_e(np.__version__)}"
        f") from <code>{_e(ctx.run_dir.resolve())}</code>.</p>"
    ]
    versions = {str(r.get("racketdyn_version")) for r in ctx.records.values()}
    if versions - {__version__}:
        parts.append(
            '<p class="warn">Runs made with racketdyn '
            + ", ".join(sorted(_e(v) for v in versions))
            + f"; this report is {_e(__version__)}.</p>"
        )
    # in the order they were run (created_utc is ISO 8601), then by folder
    runs = sorted(ctx.records.items(), key=lambda item: (str(item[1].get("created_utc")), item[0]))
    for folder, record in runs:
        command = record.get("command")
        command_text = shlex.join(str(c) for c in command) if isinstance(command, list) else ""
        meta = (
            f"racketdyn {record.get('racketdyn_version', '?')}, "
            f"created {record.get('created_utc', '?')}, Python {record.get('python', '?')}, "
            f"NumPy {record.get('numpy', '?')}"
        )
        inputs = []
        for key, value in record.items():
            if key in _RUN_KEYS or key in ("racket", "defaults_used"):
                continue
            if isinstance(value, dict | list):
                text = json.dumps(value, default=str, separators=(", ", ": "))
                text = text if len(text) <= 300 else text[:300] + " …"
            else:
                text = "not set" if value is None else _fmt(value, "g")
            klass = "hash" if key.endswith("sha256") else ""
            inputs.append((key, _Html(f'<span class="{klass}">{_e(text)}</span>')))
        defaults = record.get("defaults_used") or []
        outputs = {str(o) for o in record.get("outputs", [])}
        files = []
        for path in sorted(p for p in folder.iterdir() if p.is_file()):
            if path.name == REPORT_NAME:
                continue
            recorded = "yes" if path.name in outputs else "no"
            files.append(
                (
                    path.name,
                    f"{path.stat().st_size:,}",
                    recorded,
                    _Html(f'<span class="hash">{_sha256(path)}</span>'),
                )
            )
        block = [
            f"<h3>{_e(ctx.rel(folder) if folder != ctx.run_dir else ctx.run_dir.name)}</h3>",
            f"<p><code>{_e(command_text)}</code><br>{_e(meta)}</p>",
        ]
        if defaults:
            block.append("<p>Defaults used: " + "; ".join(_e(d) for d in defaults) + ".</p>")
        if inputs:
            block.append(_table(("input", "value"), inputs, "small inputs", numeric_from=9))
        block.append(_table(("file", "bytes", "in run.json", "SHA-256"), files, "small files", 1))
        if any(f[2] == "no" for f in files):
            block.append(
                '<p class="note">Files not listed in run.json were written by an earlier run '
                "into the same folder (its run.json was overwritten).</p>"
            )
        parts.append('<div class="run">' + "\n".join(block) + "</div>")
    return "\n".join(parts)


_BUILDERS: dict[str, Callable[[_Context], str | None]] = {
    "racket": _section_racket,
    "quality": _section_quality,
    "stabilisation": _section_stabilisation,
    "modes": _section_modes,
    "contact": _section_contact,
    "impact": _section_impact,
    "vibration": _section_vibration,
    "rebound": _section_rebound,
    "transient": _section_transient,
    "swing": _section_swing,
    "oblique": _section_oblique,
    "provenance": _section_provenance,
}


def _scan(run_dir: Path) -> tuple[list[Path], dict[Path, dict[str, Any]]]:
    dirs = [
        run_dir,
        *sorted(
            p
            for p in run_dir.rglob("*")
            if p.is_dir() and not any(part.startswith(".") for part in p.relative_to(run_dir).parts)
        ),
    ]
    records = {}
    for folder in dirs:
        if (folder / "run.json").is_file():
            record = _read_json(folder / "run.json")
            if record is not None:
                records[folder] = record
    return dirs, records


def write_report(run_dir: Path, racket: Racket | None = None) -> Path:
    """Write ``run_dir/report.html``: one self-contained HTML page telling the whole story.

    Parameters
    ----------
    run_dir : Path
        Folder written by the pipeline commands, or the folder of one command: the report
        looks in it and in its sub-folders (``racketdyn demo`` writes ``rig/``, ``frf_free/``,
        ``frf_hand/``, ``contact/``, ``compare/``, ``predict/``, ``swing/``, ``twist/`` and
        ``oblique/``, each with its run.json).
    racket : Racket, optional
        The racket the runs used, for its derived properties and head outline; by default
        read from ``predict/run.json`` (or the rig's run.json).

    Returns
    -------
    Path
        The report written, ``run_dir/report.html``.  PNG figures are embedded as data URIs and
        the script and styles are inline, so the file works offline on its own.

    Raises
    ------
    InputError
        ``run_dir`` is not a folder, or holds nothing a racketdyn command wrote.
    """
    run_dir = Path(run_dir)
    if not run_dir.is_dir():
        raise InputError(f"{run_dir}: not a folder; give the output folder of racketdyn commands")
    dirs, records = _scan(run_dir)
    ctx = _Context(run_dir, racket, dirs, records)
    sections: list[tuple[str, str, str]] = []
    missing = []
    for key, title in SECTIONS.items():
        body = _BUILDERS[key](ctx)
        if body:
            sections.append((key, title, body))
        else:
            missing.append(key)
    if not sections:
        raise InputError(
            f"{run_dir}: nothing to report; give a folder written by racketdyn commands "
            "(run.json, impact.csv, quality.csv, modes*.csv, …)"
        )
    page = _page(ctx, sections, missing)
    path = run_dir / REPORT_NAME
    path.write_text(page, encoding="utf-8")
    log.info("wrote %s (%d figures, %d sections)", path, ctx.figures, len(sections))
    return path


def _page(ctx: _Context, sections: list[tuple[str, str, str]], missing: list[str]) -> str:
    name = ""
    for record in ctx.records.values():
        racket = record.get("racket")
        if isinstance(racket, dict) and racket.get("name"):
            name = str(racket["name"])
            break
    if ctx.racket is not None:
        name = ctx.racket.name
    title = f"racketdyn report — {name}" if name else "racketdyn report"
    toc = "".join(f'<li><a href="#{key}">{_e(heading)}</a></li>' for key, heading, _ in sections)
    if missing:
        toc += '<li><a href="#not-run">Not run</a></li>'
    body = []
    for n, (key, heading, content) in enumerate(sections, start=1):
        body.append(
            f'<section id="{key}"><h2><span class="n">{n}</span> {_e(heading)}</h2>\n'
            f"{content}\n</section>"
        )
    if missing:
        items = "".join(
            f"<li><b>{_e(SECTIONS[key])}</b>: <code>{_e(_HOW_TO_RUN[key])}</code></li>"
            for key in missing
        )
        body.append(
            '<section id="not-run"><h2>Not run</h2><p>These sections have no inputs in this '
            f"folder; the commands that make them:</p><ul>{items}</ul></section>"
        )
    glance = "".join(f"<li>{_e(item)}</li>" for item in ctx.glance)
    created = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    data = json.dumps(ctx.data, allow_nan=False, separators=(",", ":")).replace("</", "<\\/")
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="racketdyn {_e(__version__)}">
<title>{_e(title)}</title>
<style>{_CSS}</style>
<script>{_ERROR_TRAP}</script>
</head>
<body>
<header>
<h1>{_e(title)}</h1>
<p class="sub">Impact dynamics of a tennis racket by Kawazoe's approximate method, from the
hammer test to the rebound ball speed. racketdyn {_e(__version__)}, {_e(created)}.
Folder <code>{_e(ctx.run_dir.name or ctx.run_dir.resolve().name)}</code>.</p>
{f'<div class="glance"><h2>At a glance</h2><ul>{glance}</ul></div>' if glance else ""}
<nav><ol>{toc}</ol></nav>
</header>
<main>
{"".join(body)}
</main>
<div id="tip" role="tooltip" hidden></div>
<script type="application/json" id="report-data">{data}</script>
<script>{_SCRIPT}</script>
</body>
</html>
"""


_CSS = """
:root { --ink: #1d232b; --muted: #5b6672; --rule: #d8dde3; --accent: #1f5f99; --bg: #fff; }
* { box-sizing: border-box; }
body { margin: 0 auto; max-width: 1180px; padding: 1.5rem 2rem 4rem; color: var(--ink);
  background: var(--bg); font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto,
  "Helvetica Neue", Arial, sans-serif; }
h1 { font-size: 1.7rem; margin: 0 0 .3rem; }
h2 { font-size: 1.3rem; margin: 2.2rem 0 .8rem; padding-bottom: .3rem;
  border-bottom: 2px solid var(--accent); }
h2 .n { color: var(--accent); margin-right: .3rem; }
h3 { font-size: 1.02rem; margin: 1.3rem 0 .5rem; }
p { margin: .4rem 0 .8rem; }
code { font: 12.5px/1.4 ui-monospace, "SFMono-Regular", Menlo, Consolas, monospace;
  background: #f2f4f7; padding: 0 .25rem; border-radius: 3px; overflow-wrap: anywhere; }
.sub { color: var(--muted); margin-top: 0; }
.glance { background: #f4f8fc; border-left: 4px solid var(--accent); padding: .4rem 1rem;
  margin: 1rem 0; }
.glance h2 { border: 0; margin: .4rem 0 .2rem; font-size: 1.05rem; }
.glance ul { margin: .2rem 0 .5rem; padding-left: 1.2rem; }
nav ol { columns: 2; margin: .5rem 0 0; padding-left: 1.4rem; }
nav a, nav a:visited { color: var(--accent); text-decoration: none; }
nav a:hover { text-decoration: underline; }
table { border-collapse: collapse; margin: .4rem 0 1rem; font-size: 13.5px; }
th, td { padding: .22rem .6rem; border-bottom: 1px solid var(--rule); text-align: left;
  vertical-align: top; }
th { background: #f2f4f7; font-weight: 600; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
table.small { font-size: 12.5px; }
table.inputs td:first-child { white-space: nowrap; }
table.files td.num:nth-child(2) { white-space: nowrap; }
.hash { font: 11px/1.3 ui-monospace, Menlo, Consolas, monospace; word-break: break-all; }
.cols { display: grid; grid-template-columns: repeat(auto-fit, minmax(360px, 1fr));
  gap: 0 2rem; align-items: start; }
.pair { display: grid; grid-template-columns: 1fr 1fr; gap: 1.2rem; align-items: start; }
.stack { display: block; }
figure { margin: .8rem 0 1.4rem; }
figure img { display: block; max-width: 100%; height: auto; margin: 0 auto;
  border: 1px solid var(--rule); }
.stack figure img { max-width: min(100%, 980px); }
figcaption { font-size: 13px; color: var(--muted); margin-top: .35rem; }
figcaption b { color: var(--ink); }
figcaption .src { font-family: ui-monospace, Menlo, Consolas, monospace; font-size: 11.5px;
  color: #8a949e; margin-left: .3rem; }
figure.interactive { border: 1px solid var(--rule); border-radius: 6px; padding: .7rem;
  background: #fbfcfd; }
.controls { display: flex; flex-wrap: wrap; gap: .3rem; margin-bottom: .4rem; }
.controls button { font: inherit; font-size: 13px; padding: .15rem .6rem; cursor: pointer;
  border: 1px solid #b7c0ca; background: #fff; border-radius: 4px; }
.controls button.on { background: var(--accent); color: #fff; border-color: var(--accent); }
.controls .gap { width: 1rem; }
.maps { display: grid; grid-template-columns: repeat(auto-fit, minmax(300px, 1fr)); gap: .6rem; }
svg.face, svg.frf { width: 100%; height: auto; display: block; background: #fff;
  border: 1px solid var(--rule); }
svg.frf { cursor: crosshair; user-select: none; }
svg.bar { width: 100%; max-width: 520px; height: auto; display: block; margin: .3rem auto 0; }
circle.pt { stroke: rgba(0, 0, 0, .25); stroke-width: .4; }
circle.pt:hover { stroke: #d62728; stroke-width: 2; }
circle.bad { fill: #fff; stroke: #d62728; stroke-dasharray: 2 1.5; }
.readout { font: 12.5px/1.4 ui-monospace, Menlo, Consolas, monospace; min-height: 2.8em;
  margin-top: .35rem; color: var(--ink); }
#tip { position: fixed; z-index: 10; pointer-events: none; background: rgba(29, 35, 43, .94);
  color: #fff; font-size: 12.5px; line-height: 1.35; padding: .35rem .55rem; border-radius: 4px;
  max-width: 320px; }
#tip .warn, .warn { color: #d62728; }
#tip .warn { color: #ffb4b4; }
.note { color: var(--muted); font-size: 13px; }
.run { margin-bottom: 1.2rem; }
ul { padding-left: 1.3rem; }
@media (max-width: 800px) { .pair { grid-template-columns: 1fr; } nav ol { columns: 1; } }
@media print {
  @page { size: A4; margin: 14mm 12mm; }
  body { max-width: none; padding: 0; font-size: 10.5pt; }
  nav, .controls, .readout, #tip, figure.interactive { display: none !important; }
  h2 { break-after: avoid; page-break-after: avoid; }
  section { break-before: page; page-break-before: always; }
  section:first-of-type { break-before: auto; page-break-before: auto; }
  figure, table, .glance { break-inside: avoid; page-break-inside: avoid; }
  figure img { border: 0; }
  .pair { grid-template-columns: 1fr 1fr; }
  a { color: inherit; text-decoration: none; }
}
"""

_ERROR_TRAP = """
window.onerror = function (message) {
  var root = document.documentElement;
  root.setAttribute("data-errors", (root.getAttribute("data-errors") || "") + message + "; ");
};
"""

_SCRIPT = r"""
(function () {
  "use strict";
  var D = JSON.parse(document.getElementById("report-data").textContent);
  var tip = document.getElementById("tip");
  var VIR = [[68, 1, 84], [72, 40, 120], [62, 73, 137], [49, 104, 142], [38, 130, 142],
    [31, 158, 137], [53, 183, 121], [110, 206, 88], [181, 222, 43], [253, 231, 37]];
  function colour(t) {
    t = Math.max(0, Math.min(1, t)) * (VIR.length - 1);
    var i = Math.min(Math.floor(t), VIR.length - 2), u = t - i, a = VIR[i], b = VIR[i + 1];
    return "rgb(" + [0, 1, 2].map(function (k) {
      return Math.round(a[k] + u * (b[k] - a[k]));
    }).join(",") + ")";
  }
  function num(v, d) {
    return v === null || v === undefined ? "–" : (typeof v === "number" ? v.toFixed(d) : v);
  }
  function esc(s) {
    return String(s).replace(/[&<>"]/g, function (c) {
      return { "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[c];
    });
  }
  function sci(v) { return v === null ? "–" : v.toExponential(3); }
  function showTip(ev, content) {
    tip.innerHTML = content;
    tip.hidden = false;
    var x = ev.clientX + 14, y = ev.clientY + 14;
    if (x + tip.offsetWidth > window.innerWidth) { x = ev.clientX - tip.offsetWidth - 14; }
    if (y + tip.offsetHeight > window.innerHeight) { y = ev.clientY - tip.offsetHeight - 14; }
    tip.style.left = x + "px";
    tip.style.top = y + "px";
  }
  function hideTip() { tip.hidden = true; }
  function buttons(holder, labels, active, onPick) {
    holder.insertAdjacentHTML("beforeend", labels.map(function (l, i) {
      return '<button type="button" data-pick="' + i + '"' + (i === active ? ' class="on"' : "") +
        ">" + esc(l) + "</button>";
    }).join(""));
    holder.addEventListener("click", function (ev) {
      var b = ev.target.closest("button[data-pick]");
      if (!b) { return; }
      holder.querySelectorAll("button[data-pick]").forEach(function (x) {
        x.classList.toggle("on", x === b);
      });
      onPick(Number(b.dataset.pick));
    });
  }

  function drawMap(spec) {
    var box = document.getElementById(spec.id), holder = box.querySelector(".panels");
    var fr = spec.frame, W = fr[1] - fr[0], H = fr[3] - fr[2], f = spec.font;
    var current = spec.initial;
    function X(x) { return (x - fr[0]).toFixed(1); }
    function Y(y) { return (fr[3] - y).toFixed(1); }
    function panel(g, p, pi) {
      var lo = g.range[0], span = (g.range[1] - g.range[0]) || 1, c = spec.colour, best = -1;
      var s = '<svg class="face" viewBox="0 0 ' + W + " " + H + '" role="img">';
      s += '<text x="' + f * 0.4 + '" y="' + f * 1.2 + '" font-size="' + f +
        '" font-weight="600">' + esc(p.label) + "</text>";
      if (spec.head) {
        var h = spec.head;
        s += '<ellipse cx="' + X(h[0]) + '" cy="' + Y(h[1]) + '" rx="' + h[2] + '" ry="' + h[3] +
          '" fill="#f3f5f7" stroke="#555" stroke-width="' + f * 0.12 + '"/>';
      }
      spec.marks.forEach(function (m, k) {
        var top = spec.head ? spec.head[1] + spec.head[3] : fr[3];
        var bottom = spec.head ? spec.head[1] - spec.head[3] : fr[2];
        s += '<line x1="' + X(m.x) + '" x2="' + X(m.x) + '" y1="' + Y(top) + '" y2="' + Y(bottom) +
          '" stroke="#444" stroke-dasharray="' + f * 0.3 + " " + f * 0.2 + '" stroke-width="' +
          f * 0.08 + '"/><text x="' + X(m.x) + '" y="' +
          (Number(Y(top)) - f * (0.3 + 0.9 * k)) + '" font-size="' + f * 0.7 +
          '" text-anchor="middle" fill="#444">' + esc(m.label) + "</text>";
      });
      p.rows.forEach(function (r, i) {
        var v = r[c];
        if (spec.best && v !== null && (best < 0 || v > p.rows[best][c])) { best = i; }
        s += '<circle class="pt' + (v === null ? " bad" : "") + '" data-p="' + pi +
          '" data-i="' + i + '" cx="' + X(r[0]) + '" cy="' + Y(r[1]) + '" r="' + spec.radius +
          '" fill="' + (v === null ? "#fff" : colour((v - lo) / span)) + '"/>';
      });
      if (best >= 0) {
        s += '<circle cx="' + X(p.rows[best][0]) + '" cy="' + Y(p.rows[best][1]) + '" r="' +
          spec.radius * 1.7 + '" fill="none" stroke="#d62728" stroke-width="' + f * 0.15 +
          '" pointer-events="none"/>';
      }
      return s + "</svg>";
    }
    function bar(g) {
      var field = spec.fields[spec.colour], stops = "", id = spec.id + "-grad";
      for (var k = 0; k <= 10; k++) {
        stops += '<stop offset="' + k * 10 + '%" stop-color="' + colour(k / 10) + '"/>';
      }
      var unit = field[1] ? " (" + field[1] + ")" : "";
      return '<svg class="bar" viewBox="0 0 520 44"><defs><linearGradient id="' + id + '">' +
        stops + '</linearGradient></defs><rect x="60" y="4" width="400" height="14" fill="url(#' +
        id + ')" stroke="#999" stroke-width=".5"/><text x="55" y="16" font-size="12" ' +
        'text-anchor="end">' + num(g.range[0], field[2]) + '</text><text x="465" y="16" ' +
        'font-size="12">' + num(g.range[1], field[2]) + '</text><text x="260" y="36" ' +
        'font-size="12" text-anchor="middle">' + esc(field[0] + unit + ", " + g.label) +
        "</text></svg>";
    }
    function render() {
      var g = spec.groups[current];
      holder.innerHTML = '<div class="maps">' + g.panels.map(function (p, pi) {
        return panel(g, p, pi);
      }).join("") + "</div>" + bar(g);
      box.dataset.drawn = String(holder.querySelectorAll("circle.pt").length);
      box.dataset.group = g.label;
    }
    if (spec.groups.length > 1) {
      buttons(box.querySelector(".controls"), spec.groups.map(function (g) { return g.label; }),
        current, function (i) { current = i; render(); });
    }
    holder.addEventListener("mousemove", function (ev) {
      var t = ev.target;
      if (!t.classList || !t.classList.contains("pt")) { hideTip(); return; }
      var p = spec.groups[current].panels[Number(t.dataset.p)], r = p.rows[Number(t.dataset.i)];
      var out = "<b>" + esc(p.label) + ", " + esc(spec.groups[current].label) + "</b>";
      spec.fields.forEach(function (fd, k) {
        out += "<br>" + esc(fd[0]) + ": " + num(r[k], fd[2]) + (fd[1] ? " " + esc(fd[1]) : "");
      });
      if (r[spec.fields.length]) {
        out += '<br><span class="warn">' + esc(r[spec.fields.length]) + "</span>";
      }
      showTip(ev, out);
    });
    holder.addEventListener("mouseleave", hideTip);
    render();
  }

  function niceStep(span, n) {
    var step = Math.pow(10, Math.floor(Math.log10(span / n))), m = span / n / step;
    return step * (m < 2 ? 1 : m < 5 ? 2 : 5);
  }

  function drawFrf(spec) {
    var box = document.getElementById(spec.id), svg = box.querySelector("svg");
    var readout = box.querySelector(".readout"), controls = box.querySelector(".controls");
    var W = 900, L = 78, R = 14, PW = W - L - R, MT = 30, MH = 252, CT = 300, CH = 90;
    var f = spec.f, lo = f[0], hi = f[f.length - 1], x0 = lo, x1 = hi, view = 0, drag = null;
    var minSpan = 8 * (f[1] - f[0]);
    function X(v) { return L + (v - x0) / (x1 - x0) * PW; }
    function svgX(ev) {
      var r = svg.getBoundingClientRect();
      return (ev.clientX - r.left) * W / r.width;
    }
    function fAt(ev) { return x0 + (svgX(ev) - L) / PW * (x1 - x0); }
    function nearest(v) {
      var a = 0, b = f.length - 1;
      while (b - a > 1) { var m = (a + b) >> 1; if (f[m] < v) { a = m; } else { b = m; } }
      return v - f[a] < f[b] - v ? a : b;
    }
    function render() {
      var series = spec.views[view].series, i0 = Math.max(nearest(x0) - 1, 0);
      var i1 = Math.min(nearest(x1) + 1, f.length - 1), ymin = Infinity, ymax = -Infinity, s = "";
      series.forEach(function (sr) {
        for (var i = i0; i <= i1; i++) {
          var m = sr.mag[i];
          if (m > 0) { var l = Math.log10(m); ymin = Math.min(ymin, l); ymax = Math.max(ymax, l); }
        }
      });
      if (!isFinite(ymin)) { ymin = -3; ymax = 0; }
      ymin = Math.floor(ymin); ymax = Math.ceil(ymax);
      if (ymax === ymin) { ymax += 1; }
      function Y(m) { return MT + (ymax - Math.log10(m)) / (ymax - ymin) * MH; }
      function C(c) { return CT + (1 - c) * CH; }
      s += '<defs><clipPath id="' + spec.id + '-clip"><rect x="' + L + '" y="0" width="' + PW +
        '" height="440"/></clipPath></defs>';
      var step = niceStep(x1 - x0, 8);
      for (var t = Math.ceil(x0 / step) * step; t <= x1; t += step) {
        s += '<line x1="' + X(t) + '" x2="' + X(t) + '" y1="' + MT + '" y2="' + (CT + CH) +
          '" stroke="#e3e7eb"/><text x="' + X(t) + '" y="' + (CT + CH + 16) +
          '" font-size="12" text-anchor="middle">' + Number(t.toPrecision(6)) + "</text>";
      }
      for (var d = ymin; d <= ymax; d++) {
        s += '<line x1="' + L + '" x2="' + (L + PW) + '" y1="' + Y(Math.pow(10, d)) + '" y2="' +
          Y(Math.pow(10, d)) + '" stroke="#e3e7eb"/><text x="' + (L - 6) + '" y="' +
          (Y(Math.pow(10, d)) + 4) + '" font-size="12" text-anchor="end">1e' + d + "</text>";
      }
      [0, 0.5, 1].forEach(function (c) {
        s += '<line x1="' + L + '" x2="' + (L + PW) + '" y1="' + C(c) + '" y2="' + C(c) +
          '" stroke="#e3e7eb"/><text x="' + (L - 6) + '" y="' + (C(c) + 4) +
          '" font-size="12" text-anchor="end">' + c + "</text>";
      });
      s += '<g clip-path="url(#' + spec.id + '-clip)">';
      spec.modes.forEach(function (m) {
        if (m.f < x0 || m.f > x1) { return; }
        s += '<line x1="' + X(m.f) + '" x2="' + X(m.f) + '" y1="' + MT + '" y2="' + (MT + MH) +
          '" stroke="' + m.colour + '" stroke-opacity=".45" stroke-dasharray="4 3"/>';
      });
      var drawn = 0;
      series.forEach(function (sr) {
        var pm = [], pc = [];
        for (var i = i0; i <= i1; i++) {
          if (sr.mag[i] > 0) { pm.push(X(f[i]).toFixed(1) + "," + Y(sr.mag[i]).toFixed(1)); }
          if (sr.coh && sr.coh[i] !== null) {
            pc.push(X(f[i]).toFixed(1) + "," + C(sr.coh[i]).toFixed(1));
          }
        }
        drawn += pm.length;
        s += '<polyline class="mag" fill="none" stroke="' + sr.colour +
          '" stroke-width="1.3" points="' + pm.join(" ") + '"/>';
        if (pc.length) {
          s += '<polyline fill="none" stroke="' + sr.colour + '" stroke-width="1" points="' +
            pc.join(" ") + '"/>';
        }
      });
      s += "</g>";
      s += '<rect x="' + L + '" y="' + MT + '" width="' + PW + '" height="' + MH +
        '" fill="none" stroke="#888"/><rect x="' + L + '" y="' + CT + '" width="' + PW +
        '" height="' + CH + '" fill="none" stroke="#888"/>';
      s += '<text x="16" y="' + (MT + MH / 2) + '" font-size="12" text-anchor="middle" ' +
        'transform="rotate(-90 16 ' + (MT + MH / 2) + ')">|H| (' + esc(spec.unit) + ")</text>" +
        '<text x="16" y="' + (CT + CH / 2) + '" font-size="12" text-anchor="middle" ' +
        'transform="rotate(-90 16 ' + (CT + CH / 2) + ')">coherence</text>' +
        '<text x="' + (L + PW / 2) + '" y="432" font-size="12" text-anchor="middle">' +
        "frequency (Hz)</text>";
      series.forEach(function (sr, k) {
        var x = L + 200 * k;
        s += '<line x1="' + x + '" x2="' + (x + 22) + '" y1="14" y2="14" stroke="' + sr.colour +
          '" stroke-width="2"/><text x="' + (x + 28) + '" y="18" font-size="12">' +
          esc(sr.label) + "</text>";
      });
      if (spec.modes.length) {
        s += '<line x1="' + (L + 200 * series.length) + '" x2="' + (L + 200 * series.length + 22) +
          '" y1="14" y2="14" stroke="#888" stroke-dasharray="4 3"/><text x="' +
          (L + 200 * series.length + 28) + '" y="18" font-size="12">identified modes</text>';
      }
      s += '<line class="cursor" x1="0" x2="0" y1="' + MT + '" y2="' + (CT + CH) +
        '" stroke="#d62728" visibility="hidden"/>';
      svg.innerHTML = s;
      box.dataset.drawn = String(drawn);
      box.dataset.range = x0.toFixed(1) + "-" + x1.toFixed(1);
    }
    function zoom(centre, k) {
      var span = Math.min(Math.max((x1 - x0) * k, minSpan), hi - lo);
      centre = Math.max(x0, Math.min(x1, centre));
      var a = centre - (centre - x0) / (x1 - x0) * span;
      x0 = Math.max(lo, Math.min(a, hi - span));
      x1 = x0 + span;
      render();
    }
    function hover(ev) {
      if (drag) {
        var shift = (svgX(ev) - drag.x) / PW * (drag.b - drag.a);
        var a = Math.max(lo, Math.min(drag.a - shift, hi - (drag.b - drag.a)));
        x0 = a; x1 = a + (drag.b - drag.a); render();
      }
      var v = fAt(ev), line = svg.querySelector("line.cursor");
      if (v < x0 || v > x1) { line.setAttribute("visibility", "hidden"); return; }
      var i = nearest(v), out = "f = " + f[i].toFixed(1) + " Hz";
      spec.views[view].series.forEach(function (sr) {
        out += "\n" + sr.label + ": |H| = " + sci(sr.mag[i]) + " " + spec.unit +
          (sr.coh ? ", coherence " + num(sr.coh[i], 3) : "");
      });
      var near = null;
      spec.modes.forEach(function (m) {
        var gap = Math.abs(m.f - f[i]);
        if (gap <= Math.max(0.02 * f[i], 3 * (f[1] - f[0])) && (!near || gap < near.gap)) {
          near = { gap: gap, m: m };
        }
      });
      if (near) { out += "\nnear " + near.m.label + " at " + near.m.f.toFixed(1) + " Hz"; }
      readout.textContent = out;
      readout.style.whiteSpace = "pre";
      line.setAttribute("x1", X(f[i]));
      line.setAttribute("x2", X(f[i]));
      line.setAttribute("visibility", "visible");
    }
    buttons(controls, spec.views.map(function (v) { return v.label; }), 0, function (i) {
      view = i; render();
    });
    controls.insertAdjacentHTML("beforeend", '<span class="gap"></span>' +
      '<button type="button" data-zoom="0.5">zoom in</button>' +
      '<button type="button" data-zoom="2">zoom out</button>' +
      '<button type="button" data-zoom="0">reset</button>');
    controls.addEventListener("click", function (ev) {
      var b = ev.target.closest("button[data-zoom]");
      if (!b) { return; }
      var k = Number(b.dataset.zoom);
      if (k === 0) { x0 = lo; x1 = hi; render(); } else { zoom((x0 + x1) / 2, k); }
    });
    svg.addEventListener("wheel", function (ev) {
      ev.preventDefault();
      zoom(fAt(ev), ev.deltaY < 0 ? 0.8 : 1.25);
    }, { passive: false });
    svg.addEventListener("mousedown", function (ev) {
      drag = { x: svgX(ev), a: x0, b: x1 };
      ev.preventDefault();
    });
    window.addEventListener("mouseup", function () { drag = null; });
    svg.addEventListener("mousemove", hover);
    svg.addEventListener("mouseleave", function () {
      var line = svg.querySelector("line.cursor");
      if (line) { line.setAttribute("visibility", "hidden"); }
    });
    svg.addEventListener("dblclick", function () { x0 = lo; x1 = hi; render(); });
    render();
  }

  D.maps.forEach(drawMap);
  D.frf.forEach(drawFrf);
  document.body.dataset.ready = "1";
})();
"""
