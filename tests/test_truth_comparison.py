"""Issue 23: the identification held against the virtual rig's truth is computed by the step
that has both models (``identify``, ``compare``) into ``truth_comparison<label>.csv``; the
report's section only reads that file (it evaluated the rig's model while writing the page)."""

from __future__ import annotations

import csv
import json
import logging
import shutil
from pathlib import Path

import numpy as np
import pytest

from costly import costly
from racketdyn.modal.model import ModalModel
from racketdyn.report import render_section
from racketdyn.report.folder import RunFolder
from racketdyn.report.formatting import fmt
from racketdyn.report.sections.truth import gather
from racketdyn.rig.truth import compare_with_truth
from racketdyn.workflows.truth import TRUTH_COLUMNS, TRUTH_FILES, rig_truth_of


@pytest.fixture(scope="module")
@costly
def tree(rig_frf_tree: Path) -> Path:
    """rig, frf_free, frf_hand (few averages; the run's shared tree) and ``identify`` of the
    free FRFs, no figures."""
    from racketdyn.workflows import run_identify

    folder = rig_frf_tree
    logging.disable(logging.WARNING)
    try:
        run_identify(folder / "frf_free" / "frfs.uff", folder / "identify")
    finally:
        logging.disable(logging.NOTSET)
    return folder


def _table(path: Path) -> list[dict[str, str]]:
    with path.open(encoding="utf-8", newline="") as handle:
        return list(csv.DictReader(handle))


@pytest.mark.slow
def test_identify_writes_the_comparison_with_the_rigs_truth(tree: Path) -> None:
    table = tree / "identify" / "truth_comparison.csv"
    record = json.loads((tree / "identify" / "run.json").read_text(encoding="utf-8"))
    assert "truth_comparison.csv" in record["outputs"]
    assert record[TRUTH_FILES] == {
        "truth_comparison.csv": str((tree / "rig" / "modal_truth_free.json").resolve())
    }
    rows = _table(table)
    assert tuple(rows[0]) == TRUTH_COLUMNS
    first = next(r for r in rows if r["truth_mode"] == "2-node bending")
    assert first["found"] == "true"
    assert first["why"] == ""
    assert abs(float(first["frequency_error"])) < 5e-4
    assert float(first["mac"]) > 0.99
    assert all(r["why"] for r in rows if r["found"] == "false")


def test_the_sections_numbers_are_the_files(tree: Path) -> None:
    """The page shows the file's numbers, and the same rows the page showed when it evaluated
    the rig's model itself (the models read back from their JSON, as the report did)."""
    data = gather(RunFolder.scan(tree))
    assert data is not None
    assert data["notes"] == []
    (block,) = data["blocks"]
    assert block["truth"] == "rig/modal_truth_free.json"
    assert block["identified"] == "identify/modal_model.json"
    rows = _table(tree / "identify" / "truth_comparison.csv")
    found = [r for r in rows if r["found"] == "true"]
    assert [r[0] for r in block["rows"]] == [r["truth_mode"] for r in found]
    for shown, row in zip(block["rows"], found, strict=True):
        numbers = [float(v) for v in shown[1:]]
        stored = [
            float(row[c]) * scale
            for c, scale in (
                ("truth_frequency_hz", 1),
                ("identified_frequency_hz", 1),
                ("frequency_error", 100),
                ("truth_damping_ratio", 100),
                ("identified_damping_ratio", 100),
                ("damping_ratio_error", 100),
                ("mac", 1),
            )
        ]
        # to the page's digits: .2f, .2f, .3f, .3f, .3f, .1f, .3f
        np.testing.assert_allclose(numbers, stored, rtol=0, atol=0.051)
        assert shown[1:] == (
            fmt(stored[0], ".2f"),
            fmt(stored[1], ".2f"),
            fmt(stored[2], "+.3f"),
            fmt(stored[3], ".3f"),
            fmt(stored[4], ".3f"),
            fmt(stored[5], "+.1f"),
            fmt(stored[6], ".3f"),
        )
    missed = [(r["truth_mode"], fmt(float(r["truth_frequency_hz"]), ".1f"), r["why"]) for r in rows]
    assert block["missed"] == [m for m, r in zip(missed, rows, strict=True) if r["found"] != "true"]
    # the rows the page showed before issue 23 moved the evaluation into the step
    found_model = ModalModel.read_json(tree / "identify" / "modal_model.json")
    truth = ModalModel.read_json(tree / "rig" / "modal_truth_free.json")
    reference = json.loads((tree / "rig" / "run.json").read_text(encoding="utf-8"))[
        "reference_location_m"
    ]
    dropped = [
        (float(r["frequency_hz"]), r["reason"])
        for r in _table(tree / "identify" / "dropped_modes.csv")
    ]
    before = compare_with_truth(found_model, truth, reference, dropped)
    assert [m.name for m in before if m.found] == [r[0] for r in block["rows"]]
    assert [(m.name, f"{m.frequency_hz:.1f}", m.why) for m in before if not m.found] == block[
        "missed"
    ]
    for mode, shown in zip([m for m in before if m.found], block["rows"], strict=True):
        assert shown[2] == f"{mode.identified_frequency_hz:.2f}"
        assert shown[3] == f"{100 * mode.frequency_error:+.3f}"
        assert shown[7] == f"{mode.mac:.3f}"


def test_a_folder_of_an_older_racketdyn_gets_one_line(tree: Path, tmp_path: Path) -> None:
    """Written before the step computed it (no ``truth_comparison.csv``): the section says so in
    one line, not a traceback, and shows no table it would have to evaluate the model for."""
    old = tmp_path / "old"
    for name in ("rig", "identify"):
        shutil.copytree(tree / name, old / name)
    (old / "identify" / "truth_comparison.csv").unlink()
    data = gather(RunFolder.scan(old))
    assert data is not None
    assert data["blocks"] == []
    assert data["glance"] == []
    (note,) = data["notes"]
    assert note.startswith("free: no identify/truth_comparison.csv beside identify/modal_model")
    assert note.endswith("the rig's truth rig/modal_truth_free.json")
    html = render_section("truth", data)
    assert html.count("<p>") == 1
    assert "<table" not in html


def test_frfs_whose_rig_ran_again_have_no_truth(tree: Path, tmp_path: Path) -> None:
    """The FRF folder's record names the hammer file and its hash: after the rig ran again (the
    hash differs) its truth is not these FRFs'; FRFs of no ``racketdyn frf`` run have none."""
    assert rig_truth_of(tree / "frf_free" / "frfs.uff") is not None
    moved = tmp_path / "frf"
    shutil.copytree(tree / "frf_free", moved)
    record = json.loads((moved / "run.json").read_text(encoding="utf-8"))
    (moved / "run.json").write_text(
        json.dumps({**record, "tests_sha256": "0" * 64}), encoding="utf-8"
    )
    assert rig_truth_of(moved / "frfs.uff") is None
    (moved / "run.json").unlink()
    assert rig_truth_of(moved / "frfs.uff") is None
