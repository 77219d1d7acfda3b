"""One self-contained HTML report of a run folder: the whole story, from the racket to the rebound.

:func:`write_report` looks for what the pipeline commands wrote under a folder (the folder itself
and its sub-folders: ``racketdyn rig``, ``frf``, ``contact``, ``identify`` / ``compare``,
``predict``, ``swing``, ``twist`` and ``oblique``) and writes ``report.html`` into it.  The
page works offline and can be mailed as it is: the PNG figures are embedded as base64 data URIs,
the CSS and small dependency-free scripts are inline, and the data of the interactive plots
(FRF magnitude with zoom and hover readout, face maps with hover values) sit in the page as
JSON.  The PNGs stay for print.

The package is the presentation layer of the report: :mod:`~racketdyn.report.folder` reads the
run folder, each module of :mod:`~racketdyn.report.sections` gathers one section's data, and the
Jinja2 templates (``templates/``, autoescaping on) show them with the styles and scripts of
``static/``, all package data.

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
paper it corresponds to, or says it has none (:data:`CAPTIONS`).
"""

from racketdyn.report.figures import CAPTIONS
from racketdyn.report.folder import REPORT_NAME
from racketdyn.report.page import render_section, write_report
from racketdyn.report.sections import SECTIONS, Section

__all__ = ["CAPTIONS", "REPORT_NAME", "SECTIONS", "Section", "render_section", "write_report"]
