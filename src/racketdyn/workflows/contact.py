"""Step ``contact``: hammer contact time over the face from one or more hammer tests (paper
Fig. 7).

Writes ``contact_<label>.csv`` per test and ``run.json``; the figure comes from the caller's hook.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from racketdyn.errors import InputError
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.measurement.pulse import ContactTimes, contact_times
from racketdyn.racket import Racket
from racketdyn.workflows.figure_data import defer_figure_data
from racketdyn.workflows.frf import read_records
from racketdyn.workflows.inputs import load_racket_input
from racketdyn.workflows.run import (
    StepResult,
    report,
    run_step,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

__all__ = ["CONTACT_METHOD", "ContactResult", "run_contact"]

CONTACT_METHOD = "half-sine-equivalent duration: 1.5 x full width at half maximum"


@dataclass
class ContactResult(StepResult):
    """What :func:`run_contact` measured and wrote.

    Attributes
    ----------
    tables : list of ContactTimes
        Contact times per point, one table per test.
    labels : list of str
        A label per test.
    racket : Racket
        The racket (head outline).
    fewer_averages : list of str
        What the readers said of a test whose last point holds fewer averages than the
        others (``HammerRecords.metadata["fewer_averages"]``: a file perhaps cut short).
    """

    tables: list[ContactTimes] = field(default_factory=list)
    labels: list[str] = field(default_factory=list)
    racket: Racket | None = None
    fewer_averages: list[str] = field(default_factory=list)


def _slug(label: str) -> str:
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in label)


@run_step
def run_contact(
    tests: Sequence[str | os.PathLike[str]],
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    *,
    labels: Sequence[str] | None = None,
    geometry: str | os.PathLike[str] | None = None,
) -> ContactResult:
    """Contact time of every hammer hit, per point, for each test; write the run folder.

    Parameters
    ----------
    tests : sequence of path
        Hammer records, one file per condition (UFF 58 or CSV with ``geometry``).
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, contact uses the racket (its head
        outline); and the run (command, figures, progress).
    labels : sequence of str, optional
        A label per file (default: the file names' stems).
    geometry : path, optional
        Node coordinates if not in the files.
    """
    names = [Path(t).stem for t in tests] if labels is None else list(labels)
    if len(names) != len(tests):
        raise InputError(f"`labels`: give one label per test file ({len(tests)})")
    if len(set(names)) != len(names):
        raise InputError(
            f"`labels`: name each test once (got {', '.join(names)}); their tables would "
            "overwrite one another"
        )
    the_racket, provenance = load_racket_input(setup.racket)
    out_dir = Path(out)
    result = ContactResult(out_dir, labels=names, racket=the_racket)
    for i, (label, test) in enumerate(zip(names, tests, strict=True)):
        report(setup.progress, "contact times", i, len(names))
        records = read_records(test, geometry)
        records.require_locations("the contact-time map")
        if records.metadata.get("fewer_averages"):
            result.fewer_averages.append(str(records.metadata["fewer_averages"]))
        times = contact_times(records, estimate_frfs(records).checks)
        path = out_dir / f"contact_{_slug(label)}.csv"
        times.write_csv(path)
        result.written.append(path)
        result.tables.append(times)
    defer_figure_data(
        result, {"tables": result.tables, "labels": result.labels, "racket": the_racket}
    )
    inputs = {
        "tests_files": [str(Path(t).resolve()) for t in tests],
        "labels": names,
        **provenance,
        "method": CONTACT_METHOD,
        "fewer_averages": result.fewer_averages,
    }
    return setup.finish(result, inputs, "contact")
