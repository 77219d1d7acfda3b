"""`racketdyn frf` and `racketdyn contact` end to end on synthetic UFF records."""

from __future__ import annotations

import csv
import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from racketdyn.cli import main
from racketdyn.io import read_frf_uff, write_hammer_uff
from racketdyn.testing.records import Modes, records_for

MODES = Modes(np.array([120.0, 330.0]), np.array([0.03, 0.02]), np.array([[6.0, 4.0], [-3.0, 2.5]]))


@pytest.fixture(scope="module")
def tests_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    records = records_for(MODES, pulse_s=3e-3, n_averages=3, second_hit=None)
    records = dataclasses.replace(
        records,
        locations=np.array([[0.505, 0.0], [0.55, 0.03]]),
        reference_location=(0.505, 0.0),
    )
    path = tmp_path_factory.mktemp("tests") / "free.uff"
    write_hammer_uff(records, path)
    return path


@pytest.mark.slow
def test_frf_command(tests_file: Path, tmp_path: Path) -> None:
    assert main(["frf", str(tests_file), "--exp-window", "0.1", "--out", str(tmp_path)]) == 0
    frfs = read_frf_uff(tmp_path / "frfs.uff")
    assert frfs.nodes == (1, 2)
    assert frfs.exponential_window_s == pytest.approx(0.1)
    rows = list(csv.DictReader((tmp_path / "quality.csv").read_text().splitlines()))
    assert len(rows) == 6
    assert all(r["accepted"] == "1" for r in rows)
    run = json.loads((tmp_path / "run.json").read_text())
    assert run["exponential_window_s"] == 0.1
    assert len(run["tests_sha256"]) == 64
    for name in ("fig2_frf_frame.png", "fig3_frf_string_centre.png"):
        assert (tmp_path / name).stat().st_size > 10_000


@pytest.mark.slow
def test_contact_command(tests_file: Path, tmp_path: Path) -> None:
    argv = [
        "contact",
        str(tests_file),
        str(tests_file),
        "--labels",
        "free,hand",
        "--out",
        str(tmp_path),
    ]
    assert main(argv) == 0
    rows = list(csv.DictReader((tmp_path / "contact_hand.csv").read_text().splitlines()))
    assert [float(r["contact_time_mean_s"]) for r in rows] == pytest.approx([3e-3, 3e-3], rel=0.02)
    assert (tmp_path / "fig7_contact_time.png").stat().st_size > 10_000


def test_bad_tests_file_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "junk.uff").write_text("this is not a universal file\n")
    assert main(["frf", str(tmp_path / "junk.uff"), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert err[0].startswith("racketdyn: error:")
    assert "junk.uff" in err[0]
    assert main(["contact", str(tmp_path / "x.csv"), "--out", str(tmp_path / "o")]) == 2
    assert "no such file" in capsys.readouterr().err


@pytest.mark.slow
def test_frf_needs_no_geometry_and_says_why_most_averages_were_rejected(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Issue 12, items 1 and 2: time records without node coordinates (CSV without --geometry)
    # give FRFs; a contact map, which needs coordinates, names --geometry.  When most averages
    # are rejected, the console says why in words.
    from racketdyn.io import write_hammer_csv

    records = records_for(MODES, n_averages=3)
    force = records.force[0].copy()
    force[:] = 0.0  # node 1: no pulse at all; node 2 is fine
    records = dataclasses.replace(records, force=(force, records.force[1].copy()))
    records.force[1][0] = 0.0
    data, _ = write_hammer_csv(records, tmp_path / "h.csv", tmp_path / "g.csv")
    assert main(["frf", str(data), "--out", str(tmp_path / "o")]) == 0
    out = capsys.readouterr().out
    assert "most averages rejected (4 of 6)" in " ".join(out.split())
    assert "no force pulse above the noise" in " ".join(out.split())
    assert read_frf_uff(tmp_path / "o" / "frfs.uff").nodes == (2,)
    assert main(["contact", str(data), "--out", str(tmp_path / "c")]) == 2
    assert "--geometry" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("option", "value", "words"),
    [
        ("--exp-window", "100", "did you give milliseconds (100 ms = 0.1 s)"),
        ("--force-window", "5", "did you give milliseconds (5 ms = 0.005 s)"),
    ],
)
def test_a_window_in_milliseconds_is_one_line(
    tests_file: Path,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    option: str,
    value: str,
    words: str,
) -> None:
    """New-user trial (2026-11-26, second session): ``frf --exp-window 100`` (meant 100 ms)
    ran: a 100 s window on a record of a fraction of a second does nothing, and the heavily
    damped mode of a ball on the strings is then lost.  A window over ten times the record is
    refused, naming the option and the slip."""
    assert main(["frf", str(tests_file), option, value, "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1
    assert f"{option} {value}" in err
    assert words in err


@pytest.mark.slow
def test_forces_in_volts_are_one_line_naming_the_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Hits whose median peak is under a newton are a force channel in volts (the wing's
    OpenModal records: 0.07–0.10 "N", quality.csv and the FRFs in the wrong unit with nothing
    saying so; new-user trial, eleventh session): refused in one line naming the file and
    the likely unit; `--allow-implausible` takes them as they are."""
    from racketdyn.io import write_hammer_csv

    records = records_for(MODES, n_averages=2)
    peak = max(float(np.abs(f).max()) for f in records.force)
    volts = dataclasses.replace(
        records,
        force=tuple(f * (0.08 / peak) for f in records.force),
        response=tuple(r * (0.08 / peak) for r in records.response),
    )
    data, _ = write_hammer_csv(volts, tmp_path / "h.csv", tmp_path / "g.csv")
    assert main(["frf", str(data), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert str(data) in err[0]
    assert "volts" in err[0]
    assert "--allow-implausible" in err[0]
    assert not (tmp_path / "o" / "frfs.uff").exists()
    args = ["frf", str(data), "--out", str(tmp_path / "o"), "--allow-implausible"]
    assert main(args) == 0
    assert (tmp_path / "o" / "frfs.uff").exists()
    # the FRFs of the same test in newtons are accepted as they are
    data, _ = write_hammer_csv(records, tmp_path / "n.csv", tmp_path / "gn.csv")
    assert main(["frf", str(data), "--out", str(tmp_path / "n")]) == 0


def test_one_hit_a_point_gives_no_coherence_and_says_so(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """With one average a point the coherence is 1 by definition: it was written as measured
    (the wing's time records, one hit a point: 1.000 everywhere; new-user trial, eleventh
    session).  Now no coherence, and the console says why."""
    records = records_for(MODES, pulse_s=3e-3, n_averages=1, second_hit=None)
    records = dataclasses.replace(
        records,
        locations=np.array([[0.505, 0.0], [0.55, 0.03]]),
        reference_location=(0.505, 0.0),
    )
    path = tmp_path / "one.uff"
    write_hammer_uff(records, path)
    assert main(["frf", str(path), "--exp-window", "0.1", "--out", str(tmp_path / "o")]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "one average a point: no coherence" in out
    assert read_frf_uff(tmp_path / "o" / "frfs.uff").coherence is None
