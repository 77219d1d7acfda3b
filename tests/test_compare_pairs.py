"""Issue 25, item 8 (eleventh-session trial): ``compare`` and ``identify`` on a 300 g, 100 sq in
racket (145 Hz, 235 N: ``lab_rackets.TRIAL_RACKET_100``) from the virtual rig — ``rig``'s own
noise, 3 averages (the trial's 10 give the same modes and names), FRFs with ``frf
--force-window 0.01`` (estimated in memory, written as ``frf`` writes them), then
:func:`racketdyn.workflows.identify.run_compare` with the racket given, as ``compare
frf_free/frfs.uff frf_hand/frfs.uff --racket my_racket.toml`` runs it.

The trial found ``compare`` pairing the free 5-node bending (1435.4 Hz) with the hand's (2, 0)
membrane (1411.2 Hz, MAC 0.943 over every point) while the hand's own 5-node bending (1294.5
Hz) went unpaired; the free 375.4, 688.7 and 905.3 Hz modes, without a pair, were in neither
``comparison.csv`` nor the console nor the report; and ``identify --racket`` left five clean
frame modes ``unknown`` (``tests/test_shapes.py``: the rule, on the truth's shapes).  Each
test reproduced its failure before the fix.
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from costly import costly
from lab_rackets import TRIAL_RACKET_100
from racketdyn.io import load_racket
from racketdyn.io.uff import write_frf_uff
from racketdyn.modal.model import ModalModel
from racketdyn.rig import SensorNoise
from racketdyn.workflows.identify import CompareResult
from racketdyn.workflows.setup import Setup
from test_racket_data import measured_frfs

FORCE_WINDOW_S = 0.01


TRUTHS: dict[str, ModalModel] = {}
"""The rig's modal truth of each support, at the hammer points (filled by :func:`compared`)."""


@pytest.fixture(scope="module")
@costly
def compared(tmp_path_factory: pytest.TempPathFactory) -> CompareResult:
    """``compare`` of the trial racket's free and hand-held FRFs from the rig, its folder (the
    rig's truths in :data:`TRUTHS`)."""
    from racketdyn.workflows.identify import run_compare

    folder = tmp_path_factory.mktemp("trial11")
    racket_file = folder / "my_racket.toml"
    racket_file.write_text(TRIAL_RACKET_100)
    racket = load_racket(racket_file)
    files = {}
    for support in ("free", "hand"):
        frfs, TRUTHS[support] = measured_frfs(
            racket, support, SensorNoise(), 3, (FORCE_WINDOW_S, None)
        )
        files[support] = write_frf_uff(frfs, folder / f"frfs_{support}.uff")
    return run_compare(
        files["free"], files["hand"], folder / "compare", setup=Setup(racket=racket_file)
    )


def _rows(result: CompareResult) -> list[dict[str, str]]:
    with (result.out / "comparison.csv").open(encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def _at(rows: list[dict[str, str]], column: str, frequency_hz: float) -> dict[str, str]:
    found = [r for r in rows if r[column] and abs(float(r[column]) / frequency_hz - 1) < 0.005]
    assert len(found) == 1, (frequency_hz, [r["mode"] for r in found])
    return found[0]


@pytest.mark.slow
def test_compare_pairs_a_mode_only_with_a_mode_of_its_kind(compared: CompareResult) -> None:
    """The free 5-node bending veers with the bed's (2, 0) membrane (1383 Hz, 38 % of its
    strain energy in the strings); held, the two part (1294.5 Hz, 13 %; the membrane 1411.2
    Hz).  Over every point the free mode's shape is nearest the hand's membrane (MAC 0.94, its
    44 string points outweighing the frame's) and the greedy pairing took it: "−1.68 %".
    Kinds both named never pair across, and frame modes pair on the frame's points (the two
    5-node bendings: 0.95 there, 0.34 over every point): the rig's truth, free 1435.2 and held
    1294.5 Hz, says −9.8 %."""
    assert compared.free is not None
    assert compared.hand is not None
    free, hand = compared.free.model, compared.hand.model
    rows = _rows(compared)
    for row in rows:
        if not row["mac"]:
            continue
        a = int(np.argmin(np.abs(free.frequency - float(row["frequency_free_hz"]))))
        b = int(np.argmin(np.abs(hand.frequency - float(row["frequency_hand_hz"]))))
        if "unknown" not in (free.kinds[a], hand.kinds[b]):
            assert free.kinds[a] == hand.kinds[b], row
    bending = _at(rows, "frequency_free_hz", 1435.35)
    assert bending["mode"] == "5-node bending"
    assert float(bending["frequency_hand_hz"]) == pytest.approx(1294.5, rel=0.002)
    assert float(bending["frequency_shift_percent"]) == pytest.approx(
        100 * (1294.5 / 1435.24 - 1), abs=0.2
    )
    membrane = _at(rows, "frequency_hand_hz", 1411.2)
    assert membrane["mode"] == "string-bed membrane (2, 0)"


def test_compare_lists_every_mode_it_leaves_without_a_pair(compared: CompareResult) -> None:
    """Every free and every hand-held mode is one row of ``comparison.csv``: a pair, or a mode
    alone with its partner's columns empty and a ``note`` (the free 3-node bending, 3- and
    4-node twisting, which the hand damps out or changes, were left out without a word)."""
    assert compared.free is not None
    assert compared.hand is not None
    rows = _rows(compared)
    for column, model in (
        ("frequency_free_hz", compared.free.model),
        ("frequency_hand_hz", compared.hand.model),
    ):
        listed = sorted(float(r[column]) for r in rows if r[column])
        np.testing.assert_allclose(listed, sorted(model.frequency), rtol=1e-5)
    for row in rows:
        paired = bool(row["frequency_free_hz"]) and bool(row["frequency_hand_hz"])
        assert paired == bool(row["mac"]) == (not row["note"]), row
    alone = _at(rows, "frequency_free_hz", 688.66)
    assert not alone["frequency_hand_hz"]
    assert "no hand-held mode of its kind" in alone["note"]
    # the free 3-node bending and 4-node twisting were alone while their held partners were
    # lost (a mixed pole of the 3-node bending and the 2-node twisting 0.14 Hz apart; the 4-node
    # twisting a shoulder of the 4-node bending's peak); found since the thirteenth session,
    # they pair, each within 0.1 % of the rig's held truth of its name
    held = TRUTHS["hand"]
    for free_hz, name in ((375.35, "3-node bending"), (905.32, "4-node twisting")):
        pair = _at(rows, "frequency_free_hz", free_hz)
        assert pair["mode"] == name
        truth = float(held.frequency[held.names.index(name)])
        assert float(pair["frequency_hand_hz"]) == pytest.approx(
            truth, rel=1e-3
        )  # issue 25's 0.1 %
    # what the figure and the report read: the pairs' numbers, NaN where a mode is alone
    comparison = compared.comparison
    assert comparison is not None
    alone_rows = [r for r in comparison.rows if r["note"]]
    assert alone_rows
    assert all(math.isnan(r["mac"]) for r in alone_rows)


def test_identify_names_the_clean_frame_modes(compared: CompareResult) -> None:
    """The free 4-node bending (845.6 Hz), 5-node bending (1435.4), 6-node twisting (1484.7)
    and 7-node twisting (1835.1) were ``unknown`` with ``--racket``, each matching the truth
    at MAC 0.97-1.00, and the 6-node twisting's veering partner (1512.0 Hz) too, which the
    truth itself named "6-node twisting" a second time.  Now every identified mode, free and
    held, has its truth pair's name (:func:`racketdyn.rig.truth.compare_with_truth`, as
    ``truth_comparison_*.csv``: pairs by shape within a frequency window), and no mode is
    ``unknown``."""
    from racketdyn.rig.truth import compare_with_truth

    for suffix, found in (("free", compared.free), ("hand", compared.hand)):
        assert found is not None
        model = found.model
        truth = [t for t in compare_with_truth(model, TRUTHS[suffix], None, ()) if t.found]
        assert "unknown" not in model.kinds, (suffix, model.names)
        named = dict(zip(model.frequency, model.names, strict=True))
        agree = [named[t.identified_frequency_hz] == t.name for t in truth]
        # the hand's 3-node bending and 2-node twisting lie 0.1 Hz apart (354.0 and 354.1 Hz):
        # identified as two modes of mixed shapes, both named twisting (left, develop.md)
        assert sum(not a for a in agree) <= (1 if suffix == "hand" else 0), (suffix, truth)
    assert compared.free is not None
    model = compared.free.model
    for frequency_hz, name in (
        (845.65, "4-node bending"),
        (1435.35, "5-node bending"),
        (1484.72, "6-node twisting"),
        (1512.04, "string-bed membrane (1, 1)"),
        (1835.14, "7-node twisting"),
    ):
        k = int(np.argmin(np.abs(model.frequency - frequency_hz)))
        assert abs(model.frequency[k] - frequency_hz) < 1.0
        assert model.names[k] == name


def test_the_report_lists_the_modes_without_a_pair(compared: CompareResult) -> None:
    """The report's table of free against hand-held (section "modes") shows every row of
    ``comparison.csv``, a mode alone with a dash for its partner and its note; the "at a
    glance" line is the first pair's."""
    from racketdyn.report.folder import RunFolder
    from racketdyn.report.sections.modes import gather

    section = gather(RunFolder.scan(compared.out))
    assert section is not None
    rows = _rows(compared)
    assert len(section["pairs"]) == len(rows)
    alone = [p for p in section["pairs"] if p[-1]]
    assert alone
    assert all(p[2] == "–" or p[1] == "–" for p in alone)
    assert section["glance"][0].startswith("2-node bending: 145.0 Hz free")
