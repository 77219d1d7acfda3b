"""The page: Jinja2 templates (``templates/``) filled by the sections, with the styles and
scripts of ``static/`` inline, so the file works offline on its own."""

from __future__ import annotations

import logging
import math
import os
from dataclasses import dataclass
from datetime import UTC, datetime
from functools import cache
from importlib.resources import files
from pathlib import Path
from typing import Any

from jinja2 import Environment, PackageLoader, StrictUndefined
from markupsafe import Markup

from racketdyn.__about__ import __version__
from racketdyn.errors import InputError
from racketdyn.racket import Racket
from racketdyn.report.figures import FigureGroup
from racketdyn.report.folder import REPORT_NAME, RunFolder, StepsInput, refuse_mixed_rackets
from racketdyn.report.sections import SECTIONS

__all__ = ["render_section", "write_report"]

log = logging.getLogger(__name__)

SCRIPTS = ("plot_kit.js", "face_map.js", "frf_plot.js", "boot.js")
"""Scripts of ``static/`` at the end of the page, in this order (``error_trap.js`` goes in the
head, before them)."""


@cache
def environment() -> Environment:
    """The Jinja2 environment of the report: templates from the package, autoescaping on."""
    env = Environment(
        loader=PackageLoader("racketdyn.report", "templates"),
        autoescape=True,
        undefined=StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
    )
    # compact JSON for the plots' data; NaN is never written (the sections give None)
    # (Unicode as it is: the page is UTF-8; tojson still escapes <, >, & and ')
    env.policies["json.dumps_kwargs"] = {
        "separators": (",", ":"),
        "allow_nan": False,
        "ensure_ascii": False,
    }
    return env


@cache
def static(name: str) -> Markup:
    """A style sheet or script of ``static/``, trusted as it is (it ships with the package)."""
    text = (files("racketdyn.report") / "static" / name).read_text(encoding="utf-8")
    if "</script" in text.lower() or "</style" in text.lower():
        raise ValueError(f"static/{name} would close its element early")
    return Markup(text)


def render_section(key: str, data: dict[str, Any]) -> Markup:
    """The HTML of section ``key`` from the data its ``gather`` function returned."""
    template = environment().get_template(f"sections/{key}.html.j2")
    return Markup(template.render(**data))


def render_group(group: FigureGroup) -> Markup:
    """The HTML of a group of figures (the macros' ``group``)."""
    template = environment().from_string(
        '{% from "macros.html.j2" import group as g %}{{ g(figures) }}'
    )
    return Markup(template.render(figures=group))


@dataclass(frozen=True)
class _Shown:
    key: str
    title: str
    body: Markup


_SAME_RACKET = ("mass_kg", "balance_m", "inertia_cg_kgm2", "head_area_cm2")
"""Derived properties a given racket must share with the one the runs recorded."""


def _refuse_another_racket(run: RunFolder, racket: Racket) -> None:
    """The racket given for the page must be the one the runs were computed on (the trial of
    2026-11-27: ``report --racket paper.toml`` over a 305 g racket's runs titled the page with
    the 360 g racket, its properties and outline, and said nothing)."""
    given = racket.derived_properties()
    for folder, record in run.records.items():
        described = record.get("racket")
        derived = described.get("derived") if isinstance(described, dict) else None
        if not isinstance(derived, dict):
            continue
        for key in _SAME_RACKET:
            value = derived.get(key)
            if isinstance(value, int | float) and not math.isclose(
                float(value), float(given[key]), rel_tol=1e-6, abs_tol=1e-12
            ):
                name = described.get("name", "another racket") if described else "?"
                where = run.rel(folder)
                raise InputError(
                    f"`racket` {racket.name}: the runs in "
                    f"{run.run_dir if where in ('', '.') else where} were "
                    f"computed on {name} ({key} {float(value):g} against {float(given[key]):g}); "
                    "give that racket, or leave `racket` out: the page takes the runs' own"
                )


def _refuse_mixed_runs(run: RunFolder) -> None:
    """One page tells one run: refuse a folder whose run.json files name several rackets, or
    that holds several predictions (the page would title one racket and mix the others' files
    in; the new-user trial of issue 13 reported on a folder of two rackets' runs)."""
    refuse_mixed_rackets(run.run_dir, run.records)
    predictions = run.with_file("impact.csv")
    if len(predictions) > 1:  # a folder without run.json holding an impact.csv
        names = [run.rel(folder) or "." for folder in predictions]
        raise InputError(
            f"{run.run_dir}: it holds {len(predictions)} predict runs ({', '.join(names)}): a "
            f"report tells one run; choose one, e.g. `steps` predict={names[-1]}"
        )


def write_report(
    run_dir: Path, racket: Racket | None = None, *, steps: StepsInput | None = None
) -> Path:
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
    steps : mapping or sequence of (name, folder), optional
        The folders to use for some steps, e.g. ``{"predict": "serve", "free": "frf_free"}``
        (a name is a step — ``rig``, ``frf``, ``contact``, ``identify``, ``compare``,
        ``compare_ball``, ``predict``, ``swing``, ``twist``, ``oblique``, ``compound``,
        ``validate``, ``calibrate`` — or the label of an FRF or identify run; a folder is
        relative to ``run_dir``, or absolute).  Every other step's folder is found under
        ``run_dir`` when it holds one; with both ``identify`` and ``compare`` runs there,
        compare's models are shown.  :attr:`RunFolder.steps` says which folder each step
        came from, and the page's provenance too.

    Returns
    -------
    Path
        The report written, ``run_dir/report.html``.  PNG figures are embedded as data URIs and
        the scripts and styles are inline, so the file works offline on its own.

    Raises
    ------
    InputError
        ``run_dir`` is not a folder, holds nothing a racketdyn command wrote, holds a damaged
        file (named, with the command that wrote it), holds the runs of several rackets, or
        several runs of one step that ``steps`` does not choose between (one page tells one
        run), or a folder of ``steps`` is missing or holds another step; nothing is written
        then.
    """
    run_dir = Path(run_dir)
    if not run_dir.is_dir():
        raise InputError(f"{run_dir}: not a folder; give the output folder of racketdyn commands")
    run = RunFolder.scan(run_dir, racket, steps)
    _refuse_mixed_runs(run)
    if racket is not None:
        _refuse_another_racket(run, racket)
    shown: list[_Shown] = []
    missing = []
    glance: list[str] = []
    plots: dict[str, list[dict[str, Any]]] = {"maps": [], "frf": []}
    gathered = {key: section.gather(run) for key, section in SECTIONS.items()}
    for key, section in SECTIONS.items():
        data = gathered[key]
        if data is None:
            missing.append(section)
            continue
        body = render_section(key, data)
        unplaced = run.unplaced(key)  # registered figures its template does not name
        if unplaced is not None:
            body += render_group(unplaced)
        shown.append(_Shown(key, section.title, Markup(body)))
        glance += data.get("glance", [])
        for kind, specs in data.get("plots", {}).items():
            plots[kind] += specs
    if not shown:
        raise InputError(
            f"{run_dir}: nothing to report; give a folder written by racketdyn commands "
            "(run.json, impact.csv, quality.csv, modes*.csv, …)"
        )
    name = _racket_name(run)
    template = environment().get_template("page.html.j2")
    page = template.render(
        title=f"racketdyn report — {name}" if name else "racketdyn report",
        version=__version__,
        created=datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
        folder=run_dir.name or run_dir.resolve().name,
        step_folders=",".join(_relative(s.folder, run_dir) for s in run.steps),
        steps_given=",".join(
            f"{s.name}={_relative(s.folder, run_dir)}" for s in run.steps if s.given
        ),
        glance=glance,
        sections=shown,
        missing=missing,
        data=plots,
        css=static("report.css"),
        error_trap=static("error_trap.js"),
        scripts=[static(script) for script in SCRIPTS],
    )
    path = run_dir / REPORT_NAME
    # written beside and moved in whole: an interrupted write never leaves half a page
    partial = path.with_name(f".{REPORT_NAME}.{os.getpid()}.partial")
    try:
        partial.write_text(page, encoding="utf-8")
        os.replace(partial, path)
    finally:
        partial.unlink(missing_ok=True)
    log.info("wrote %s (%d sections)", path, len(shown))
    return path


def _relative(folder: Path, run_dir: Path) -> str:
    """A step folder as the page records it (``racketdyn-steps``): relative to the report's
    folder, ``.`` for the folder itself."""
    try:
        return folder.resolve().relative_to(run_dir.resolve()).as_posix() or "."
    except ValueError:
        return folder.resolve().as_posix()


def _racket_name(run: RunFolder) -> str:
    if run.racket is not None:
        return run.racket.name
    for record in run.records.values():
        racket = record.get("racket")
        if isinstance(racket, dict) and racket.get("name"):
            return str(racket["name"])
    return ""
