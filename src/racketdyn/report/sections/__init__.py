"""The sections of the report, in the order of the page.

A section is a function that gathers what it shows from the run folder and a template that shows
it: ``gather(run: RunFolder) -> dict | None`` in ``sections/<key>.py`` (None when its inputs are
missing: the section is then listed under "Not run" with its ``how_to_run``), and
``templates/sections/<key>.html.j2``, rendered with the dict's items as its variables.  Two keys
of the dict are read by the page, not the template: ``glance`` (lines for "At a glance") and
``plots`` (``{"frf": [...], "maps": [...]}``, data of the interactive plots, each with the
``id`` of its element).  A new section is a module with ``gather`` and ``HOW_TO_RUN``, a
template, and an entry in :data:`SECTIONS`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from racketdyn.report.folder import RunFolder
from racketdyn.report.sections import (
    calibration,
    compound,
    contact,
    impact,
    modes,
    oblique,
    provenance,
    quality,
    racket,
    rebound,
    stabilisation,
    swing,
    transient,
    truth,
    validation,
    vibration,
)

__all__ = ["SECTIONS", "Section"]


@dataclass(frozen=True)
class Section:
    """One section of the report.

    Parameters
    ----------
    title : str
        Its heading.
    gather : callable
        ``gather(run)``: the data its template shows, or None when its inputs are missing.
    how_to_run : str
        The commands that make its inputs, shown when it was not run.
    """

    title: str
    gather: Callable[[RunFolder], dict[str, Any] | None]
    how_to_run: str


SECTIONS: dict[str, Section] = {
    "racket": Section("The racket and its derived properties", racket.gather, racket.HOW_TO_RUN),
    "quality": Section("Measurement quality", quality.gather, quality.HOW_TO_RUN),
    "stabilisation": Section(
        "Stabilisation diagrams", stabilisation.gather, stabilisation.HOW_TO_RUN
    ),
    "modes": Section(
        "Mode shapes and node lines, free against hand-held", modes.gather, modes.HOW_TO_RUN
    ),
    "truth": Section(
        "Identified modes against the truth of the virtual rig", truth.gather, truth.HOW_TO_RUN
    ),
    "contact": Section("Contact time over the face", contact.gather, contact.HOW_TO_RUN),
    "compound": Section("The ball on the strings (Figs 8–9)", compound.gather, compound.HOW_TO_RUN),
    "impact": Section(
        "Impact force and contact time against speed", impact.gather, impact.HOW_TO_RUN
    ),
    "vibration": Section("Frame vibration", vibration.gather, vibration.HOW_TO_RUN),
    "rebound": Section("Rebound ratio and sweet spots", rebound.gather, rebound.HOW_TO_RUN),
    "transient": Section(
        "Approximate method against the transient simulation",
        transient.gather,
        transient.HOW_TO_RUN,
    ),
    "swing": Section("The swinging racket", swing.gather, swing.HOW_TO_RUN),
    "oblique": Section("Off-centre and oblique impacts", oblique.gather, oblique.HOW_TO_RUN),
    "validation": Section(
        "Predicted against measured rebound", validation.gather, validation.HOW_TO_RUN
    ),
    "calibration": Section(
        "Calibrated against measured rebound", calibration.gather, calibration.HOW_TO_RUN
    ),
    "provenance": Section(
        "Inputs, defaults and versions", provenance.gather, provenance.HOW_TO_RUN
    ),
}
"""Section id → :class:`Section`, in the order of the report; the template of a section is
``templates/sections/<id>.html.j2``."""
