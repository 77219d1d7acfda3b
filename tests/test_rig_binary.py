"""The rig writes binary UFF 58b by default (issue 27: the demo's ``results/`` was 126 MB,
111 MB of it two ASCII UFF files); ``--ascii`` keeps the text form.  Both read back: the
binary file gives the doubles themselves, the text file 12 significant digits."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from racketdyn.cli import main
from racketdyn.io import read_hammer_uff
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.workflows.rig import RigOptions, run_rig


@pytest.mark.slow
def test_the_rig_writes_binary_uff_by_default(tmp_path: Path) -> None:
    result = run_rig(tmp_path, options=RigOptions(averages=1, support="hand", seed=3))
    path = tmp_path / "hammer_hand.uff"
    text = path.read_bytes()
    assert b"    58b" in text
    back = read_hammer_uff(path)
    written = result.records["hand"]
    assert back.nodes == written.nodes
    for before, after in zip(written.force, back.force, strict=True):
        np.testing.assert_array_equal(after, before)
    for before, after in zip(written.response, back.response, strict=True):
        np.testing.assert_array_equal(after, before)
    # and the next step reads it as before: FRFs from every point
    assert estimate_frfs(back, exponential_window_s=0.1).frfs.n_points == len(written.nodes)


@pytest.mark.slow
def test_ascii_keeps_the_text_form(tmp_path: Path) -> None:
    assert main(["rig", "--averages", "1", "--ascii", "--out", str(tmp_path)]) == 0
    path = tmp_path / "hammer_free.uff"
    assert b"    58b" not in path.read_bytes()
    back = read_hammer_uff(path)
    assert len(back.nodes) == 68
