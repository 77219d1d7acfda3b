"""The virtual rig's truth behind FRFs, and the identification held against it (issue 23).

When FRFs were estimated (``racketdyn frf``) from a virtual rig's hammer test
(``racketdyn rig``), the rig's folder holds the modal truth of that test,
``modal_truth_<support>.json``: ``identify`` and ``compare`` find it by the run folders' own
records (the FRF folder's ``run.json`` names its ``tests_file``; the rig's ``run.json`` beside
that file lists the truth among its outputs and gives the accelerometer's location) and write
``truth_comparison<label>.csv`` (:data:`TRUTH_COLUMNS`, one row per flexible truth mode,
:func:`racketdyn.rig.truth.compare_with_truth`).  The report's section on the rig's truth reads
that file; it evaluates no model.
"""

from __future__ import annotations

import csv
import json
import logging
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from racketdyn.errors import InputError
from racketdyn.modal.identify import Identification
from racketdyn.modal.model import ModalModel
from racketdyn.rig.truth import TruthMode, compare_with_truth
from racketdyn.workflows.run import RUN_JSON, sha256

__all__ = [
    "TRUTH_COLUMNS",
    "TRUTH_COMPARISON",
    "TRUTH_FILES",
    "RigTruth",
    "rig_truth_of",
    "write_truth_comparisons",
]

logger = logging.getLogger(__name__)

TRUTH_COLUMNS = (
    "truth_mode",
    "truth_frequency_hz",
    "truth_damping_ratio",
    "identified_frequency_hz",
    "identified_damping_ratio",
    "frequency_error",
    "damping_ratio_error",
    "mac",
    "found",
    "why",
)
"""Columns of ``truth_comparison<label>.csv``: the truth mode's name, frequency (Hz) and
damping ratio; those of the identified mode paired with it (empty when none); the relative
errors (identified over truth, less one); the MAC of their shapes at the identified points;
whether it was found; and why not (empty when found)."""
TRUTH_COMPARISON = "truth_comparison{label}.csv"
"""The file's name; ``label`` is the model files' suffix (``_free``; empty for ``identify``)."""
TRUTH_FILES = "truth_files"
"""run.json's key: each ``truth_comparison<label>.csv`` written, with the truth it compares
against (``modal_truth_<support>.json``, absolute path)."""


@dataclass(frozen=True)
class RigTruth:
    """The virtual rig's modal truth of one hammer test.

    Attributes
    ----------
    path : Path
        Its ``modal_truth_<support>.json``.
    model : ModalModel
        The truth.
    reference_m : tuple of float or None
        The accelerometer's location (x, y), m (the rig's ``reference_location_m``).
    """

    path: Path
    model: ModalModel
    reference_m: tuple[float, ...] | None


def _record(folder: Path) -> dict[str, Any] | None:
    """A folder's run.json, or None when it has none or it is not a JSON object."""
    try:
        record = json.loads((folder / RUN_JSON).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return record if isinstance(record, dict) else None


def rig_truth_of(frfs: str | os.PathLike[str]) -> RigTruth | None:
    """The rig's truth behind a file of FRFs, found by the run folders' records; None when the
    FRFs do not come (through ``racketdyn frf``) from a virtual rig's test that is still where
    it was, unchanged.

    Parameters
    ----------
    frfs : path
        FRFs (``frfs.uff`` of :func:`~racketdyn.workflows.run_frf`).
    """
    frf_record = _record(Path(frfs).resolve().parent)
    if frf_record is None or not isinstance(frf_record.get("tests_file"), str):
        return None
    tests = Path(frf_record["tests_file"])
    rig_record = _record(tests.parent)
    if rig_record is None or tests.name not in rig_record.get("outputs", []):
        return None
    if not tests.is_file() or sha256(tests) != frf_record.get("tests_sha256"):
        return None  # the rig ran again since: its truth is not these FRFs'
    support = tests.stem.removeprefix("hammer_")
    path = tests.parent / f"modal_truth_{support}.json"
    if path.name not in rig_record.get("outputs", []) or not path.is_file():
        return None
    try:
        model = ModalModel.read_json(path)
    except InputError as error:
        logger.warning("the rig's truth %s is not read: %s", path, error)
        return None
    reference = rig_record.get("reference_location_m")
    return RigTruth(path, model, None if reference is None else tuple(map(float, reference)))


def write_truth_comparisons(
    out: Path,
    *identified: tuple[Identification, str | os.PathLike[str], str],
    words: Callable[[str], str] | None = None,
) -> tuple[list[Path], dict[str, str]]:
    """``truth_comparison<label>.csv`` of each identification whose FRFs come from a virtual
    rig (:func:`rig_truth_of`): every flexible truth mode against the identified model.

    Parameters
    ----------
    out : Path
        The step's folder.
    *identified : (Identification, path, str)
        Each identification, the FRFs it identified and its model files' suffix (``_free``,
        ``_hand``; empty for ``identify``).
    words : callable, optional
        The step's words for the library's texts (:attr:`Setup.words
        <racketdyn.workflows.setup.Setup.words>`): why a truth mode was not found, as the
        command that ran would say it (``--pin`` for `` `pin_hz` ``).

    Returns
    -------
    (list of Path, dict)
        The files written (none without a truth), and run.json's :data:`TRUTH_FILES` entry
        (each file's name → the truth's path).
    """
    written: list[Path] = []
    truths: dict[str, str] = {}
    for identification, frfs, label in identified:
        truth = rig_truth_of(frfs)
        if truth is None:
            continue
        said = words or str
        dropped = [(d.frequency_hz, said(d.reason)) for d in identification.dropped_modes]
        modes = compare_with_truth(identification.model, truth.model, truth.reference_m, dropped)
        path = out / TRUTH_COMPARISON.format(label=label)
        with path.open("w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(TRUTH_COLUMNS)
            writer.writerows(_row(mode) for mode in modes)
        written.append(path)
        truths[path.name] = str(truth.path)
    return written, truths


def _row(mode: TruthMode) -> list[str]:
    """A CSV row of :data:`TRUTH_COLUMNS` (numbers to the last bit; empty where not found)."""
    numbers = (
        mode.frequency_hz,
        mode.damping_ratio,
        mode.identified_frequency_hz,
        mode.identified_damping_ratio,
        mode.frequency_error,
        mode.damping_ratio_error,
        mode.mac,
    )
    cells = ["" if v != v else repr(float(v)) for v in numbers]  # NaN is an empty cell
    return [mode.name, *cells, str(mode.found).lower(), mode.why]
