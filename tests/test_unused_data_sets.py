"""What a file holds that an identification leaves out is said by kind and by point.

meca0062's aeroplane frame was struck along z at 68 points and along x at the tail's 6: the
tail's 18 FRFs (6 points × 3 accelerometers) were listed as "data sets 206, 207 … not against
references 201, 202, 203, in another direction or a reciprocal pair's second", three reasons in
one, the points not named and the tail's missing shape not said.  Each reason is now said on
its own, the points of another direction named with their direction.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from racketdyn.cli import main
from racketdyn.io import read_frfs
from racketdyn.io.uff import write_frf_uff
from racketdyn.testing import beam_frfs

S = [0.05, 0.15, 0.25, 0.35, 0.45, 0.55]
"""Points along a free bar, m; the reference at 0.15 m."""


def _two_directions(tmp_path: Path) -> Path:
    """A roving-hammer file: the bar's points struck along +Z, the last two also along +X."""
    import pyuff

    path = tmp_path / "one.uff"
    frfs = beam_frfs(S, 0.15).frfs  # along x: its locations in the plane z = 0
    flat = replace(
        frfs, locations=frfs.locations[:, :2], reference_location=frfs.reference_location[:2]
    )
    write_frf_uff(flat, path)
    sets = pyuff.UFF(str(path)).read_sets()
    frfs = [s for s in sets if s["type"] == 58]
    extra = []
    for s in frfs[-2:]:
        twin = dict(s)
        twin["ref_dir"] = 1  # the same point struck along +X
        extra.append(twin)
    out = tmp_path / "two_directions.uff"
    writer = pyuff.UFF(str(out))
    writer.write_sets([*sets, *extra], mode="overwrite")
    return out


def test_the_points_of_another_direction_are_named_with_it(tmp_path: Path) -> None:
    path = _two_directions(tmp_path)
    frfs = read_frfs(path)
    assert len(frfs.nodes) == len(S)  # every point once, along z
    other = frfs.metadata["other_direction"]
    assert other["direction"] == "x"
    assert other["usual"] == "z"
    assert len(other["nodes"]) == 2
    assert len(other["data_sets"]) == 2


def test_identify_says_each_reason_apart(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = _two_directions(tmp_path)
    frfs = read_frfs(path)
    nodes = frfs.metadata["other_direction"]["nodes"]
    assert main(["identify", str(path), "--out", str(tmp_path / "out")]) == 0
    said = " ".join(capsys.readouterr().out.split())
    assert (
        f"2 points struck along x (nodes {nodes[0]}, {nodes[1]}) while the others are along z: "
        "left out, a mode shape here has one direction (data sets" in said
    ), said
    assert "reciprocal" not in said
    assert np.isfinite(frfs.values).all()


def test_meca0062s_tail_is_said_by_all_three_references(tmp_path: Path) -> None:
    """The real file: 18 FRFs of the tail's 6 points (x), 3 accelerometers each."""
    import realdata
    from racketdyn.measurement.records import FrfReferences
    from racketdyn.workflows.identify import _unused_by_all

    path = realdata.file("meca0062_aircraft/meca0062_aircraft_3acc.uff.xz", tmp_path)
    frfs = read_frfs(path, reference="all")
    assert isinstance(frfs, FrfReferences)
    unused = _unused_by_all(frfs)
    assert unused["other_direction"]["direction"] == "x"
    assert unused["other_direction"]["usual"] == "z"
    assert len(unused["other_direction"]["nodes"]) == 6
    assert len(unused["other_direction"]["data_sets"]) == 18
    assert unused["not_against_reference"] == []  # every other set is some reference's
    assert unused["reciprocal_second"] == []
