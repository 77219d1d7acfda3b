"""``compare`` on FRFs that are not a racket's: the pairs and shifts, not the racket's parts.

A lab compared two supports of an aeroplane-like frame (meca0062, 3-D points, three fixed
accelerometers): compare stopped with "shapes are sampled at 3-D locations; asked at 2-D ones"
— it sought the first mode's nodes along a racket's long axis.  On points that are not a
racket's face it now pairs the modes and gives their shifts, and leaves out, saying so, what
only a racket has (the nodes on the long axis, Fig. 6 free against hand-held, Fig. 15).
"""

from __future__ import annotations

import csv
import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from racketdyn.cli import main
from racketdyn.io.uff import write_frf_uff
from racketdyn.testing import beam_frfs

S = [0.05, 0.15, 0.25, 0.35, 0.45, 0.55]
"""Points along a free bar in space, m; the reference (driving point) at 0.15 m."""


def _bar(tmp_path: Path, name: str, damping: float) -> Path:
    """The bar's FRFs with its points on a slanted line in space (x and z): data set 15 holds
    z too (racketdyn writes a face's x, y; pyuff writes the z in)."""
    import pyuff

    frfs = beam_frfs(S, 0.15, damping_ratio=damping, n_modes=3).frfs
    flat = replace(
        frfs, locations=frfs.locations[:, :2], reference_location=frfs.reference_location[:2]
    )
    plain = write_frf_uff(flat, tmp_path / f"plain_{name}")
    sets = pyuff.UFF(str(plain)).read_sets()
    for data in sets:
        if data["type"] == 15:
            x = np.asarray(data["x"], dtype=float)
            data["x"], data["z"] = 0.6 * x, 0.8 * x
    path = tmp_path / name
    pyuff.UFF(str(path)).write_sets(sets, mode="overwrite")
    return path


def test_compare_pairs_the_modes_of_a_structure_in_space(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    free, held = _bar(tmp_path, "a.uff", 0.008), _bar(tmp_path, "b.uff", 0.02)
    out = tmp_path / "cmp"
    assert main(["compare", str(free), str(held), "--out", str(out)]) == 0
    said = " ".join(capsys.readouterr().out.split())
    assert "compare: not a racket's face (points in space): no nodes on the long axis" in said
    with (out / "comparison.csv").open(encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 3
    for row in rows:
        assert float(row["mac"]) > 0.99
        assert float(row["damping_ratio_hand_over_free"]) == pytest.approx(2.5, rel=0.1)
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    assert record["first_mode_nodes_m"] == {"free": [], "hand": []}
    assert "not a racket's face" in record["racket_parts"]
    assert not (out / "fig6_nodes_free_hand.png").exists()
    assert not (out / "fig15_identified.png").exists()


@pytest.mark.slow
def test_compare_takes_every_reference(tmp_path: Path) -> None:
    import realdata

    path = realdata.file("meca0062_aircraft/meca0062_aircraft_3acc.uff.xz", tmp_path)
    out = tmp_path / "cmp"
    assert main(["compare", str(path), str(path), "--reference", "all", "--out", str(out)]) == 0
    with (out / "comparison.csv").open(encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    paired = [r for r in rows if r["mac"]]
    assert len(paired) >= 11  # the same file twice: every mode with itself
    for row in paired:
        assert float(row["frequency_shift_percent"]) == pytest.approx(0.0, abs=1e-9)
