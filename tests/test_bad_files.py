"""Issue 26, damaged measurement files: warnings off the console, non-finite and absurd values,
geometry faults, data sets lost silently (and issue 25, item 4: a real export's Nyquist NaN).

Every case was reproduced here before it was fixed.  Files are synthetic (racketdyn's writers,
edited as a damaged export would be); the real OpenModal wing runs where the shared data are.
"""

from __future__ import annotations

import os
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

from racketdyn.cli import main
from racketdyn.errors import InputError
from racketdyn.io import read_frf_uff, read_hammer_uff, write_frf_uff, write_hammer_uff
from test_uff import _frfs, _records

SRC = Path(__file__).resolve().parents[1] / "src"
FIXTURES = Path(__file__).parent / "fixtures"


def _lines(path: Path) -> list[str]:
    return path.read_text(encoding="ascii").splitlines()


def _write(path: Path, lines: list[str]) -> Path:
    path.write_text("\n".join(lines) + "\n", encoding="ascii")
    return path


def _data_sets(lines: list[str]) -> list[tuple[int, int]]:
    """(opening, closing) line indices of every data set."""
    delimiters = [i for i, line in enumerate(lines) if line.strip() == "-1"]
    return list(zip(delimiters[::2], delimiters[1::2], strict=True))


def _value_at(line: str, column: int, value: str) -> str:
    """``line`` (E20.12 values, 4 a line) with value ``column`` (from 0) set to ``value``."""
    return line[: 20 * column] + value.rjust(20) + line[20 * (column + 1) :]


def _one_line(capsys: pytest.CaptureFixture[str], *words: str) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    for word in words:
        assert word in err[0], err[0]
    return err[0]


def _run_cli(*argv: str) -> subprocess.CompletedProcess[str]:
    """The command in a fresh interpreter, as a user runs it: Python's own warning filters."""
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    env.pop("PYTHONWARNINGS", None)
    return subprocess.run(
        [sys.executable, "-m", "racketdyn.cli", *argv],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
        check=False,
    )


def _kilonewton_hammer_file(tmp_path: Path, sample: str) -> Path:
    """Hammer records whose first force record is labelled kN and holds ``sample`` once."""
    lines = _lines(write_hammer_uff(_records(), tmp_path / "hammer.uff"))
    opening, _ = next((o, c) for o, c in _data_sets(lines) if lines[o + 1].strip() == "58")
    label = opening + 10  # record 9: the ordinate's type and units label
    assert lines[label].split()[:2] == ["13", "0"]
    assert lines[label].split()[-1] == "N"
    lines[label] = lines[label].replace("Force                N ", "Force                kN")
    lines[opening + 15] = _value_at(lines[opening + 15], 3, sample)  # the pulse's rise
    return _write(tmp_path / "hammer_kn.uff", lines)


# --- item 1: numpy's and pyuff's warnings stay off the console ------------------------------
@pytest.mark.slow
def test_an_overflowing_sample_leaves_no_warning_on_the_console(tmp_path: Path) -> None:
    """A force of 1e307 kN overflowed when taken to N: numpy's RuntimeWarning (with the source
    line) reached the console."""
    path = _kilonewton_hammer_file(tmp_path, "9.99999999999e+307")
    run = _run_cli("frf", str(path), "--out", str(tmp_path / "out"))
    assert "Warning" not in run.stderr, run.stderr
    assert "Traceback" not in run.stderr, run.stderr


def test_pyuffs_warnings_go_to_the_log(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
    caplog: pytest.LogCaptureFixture,
) -> None:
    """pyuff's own warnings (and numpy's inside pyuff) while it reads a file are logged, not
    shown: the test session turns a warning into an error, so one escaping fails the command."""
    import numpy as np
    import pyuff

    real = pyuff.UFF.read_sets

    def warning(self: object, *args: object, **kwargs: object) -> object:
        warnings.warn("pyuff finds the file odd", UserWarning, stacklevel=1)
        np.float64(1e308) * np.float64(10.0)  # numpy: overflow encountered in scalar multiply
        return real(self, *args, **kwargs)

    monkeypatch.setattr(pyuff.UFF, "read_sets", warning)
    path = write_hammer_uff(_records(), tmp_path / "hammer.uff")
    caplog.set_level("DEBUG")
    assert main(["frf", str(path), "--out", str(tmp_path / "out")]) == 0
    assert "Warning" not in capsys.readouterr().err
    assert "pyuff finds the file odd" in caplog.text
    assert "overflow" in caplog.text
    # the library's readers too (a Python caller's console is kept as clean)
    frfs = write_frf_uff(_frfs(), tmp_path / "frfs.uff")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        read_frf_uff(frfs)
        read_hammer_uff(path)
    assert not caught, [str(w.message) for w in caught]


def test_a_warning_while_frfs_are_computed_goes_to_the_log(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    """The FRF-computing boundary (``estimate_frfs``) logs numpy's warnings too."""
    import numpy as np

    from racketdyn.measurement import frf

    real = frf.check_average

    def overflowing(*args: object, **kwargs: object) -> object:
        np.float64(1e308) * np.float64(10.0)
        return real(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(frf, "check_average", overflowing)
    caplog.set_level("DEBUG")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        frf.estimate_frfs(_records())
    assert not caught, [str(w.message) for w in caught]
    assert "overflow" in caplog.text


# --- item 2: non-finite and absurd samples name the data set --------------------------------
def test_a_sample_overflowing_in_si_units_names_the_data_set(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """1e307 kN is finite in the file and infinite in N: it was taken as data (the average
    rejected as "non-finite" later) instead of the data set being named."""
    path = _kilonewton_hammer_file(tmp_path, "9.99999999999e+307")
    assert main(["frf", str(path), "--out", str(tmp_path / "out")]) == 2
    _one_line(capsys, "hammer_kn.uff", "data set 2 (58", "response node 3", "load case 1", "kN")
    assert not (tmp_path / "out").exists()


def _frf_file(tmp_path: Path, value: str, line: int, column: int = 0) -> Path:
    """FRFs (racketdyn's writer) with ``value`` in data line ``line`` of the first FRF
    (data set 2; -1 its last line, the Nyquist line): columns 0 and 1 are the real and
    imaginary parts of the line's first frequency, 2 and 3 of its second."""
    lines = _lines(write_frf_uff(_frfs(), tmp_path / "frfs.uff"))
    opening, closing = _data_sets(lines)[1]
    assert lines[opening + 1].strip() == "58"
    index = closing - 1 if line == -1 else opening + 13 + line
    lines[index] = _value_at(lines[index], column, value)
    return _write(tmp_path / "damaged.uff", lines)


@pytest.mark.parametrize("value", ["nan", "inf", "9.99999999999e+299"])
def test_a_bad_frf_value_inside_the_band_names_the_data_set(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], value: str
) -> None:
    """A NaN, an infinity or 1e300 in the middle of an FRF: the NaN was refused, 1e300 was
    read as data (identify then overflowed: numpy's warnings and a traceback)."""
    path = _frf_file(tmp_path, value, 20)
    assert main(["identify", str(path), "--out", str(tmp_path / "out")]) == 2
    _one_line(capsys, "damaged.uff", "data set 2 (58", "response node 7", "reference node 3")


def test_a_nan_on_the_last_line_drops_that_line(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """Issue 25, item 4: an export with NaN on the last (Nyquist) line of one record: the line
    is dropped from every FRF and the log says so; the file is not refused."""
    truth = _frfs()
    path = _frf_file(tmp_path, "nan", -1, column=1)
    caplog.set_level("INFO")
    frfs = read_frf_uff(path)
    assert frfs.frequency.size == truth.frequency.size - 1
    assert frfs.frequency[-1] == truth.frequency[-2]
    assert frfs.coherence is not None
    assert frfs.coherence.shape == frfs.values.shape
    import numpy as np

    np.testing.assert_allclose(frfs.values, truth.values[:, :-1], rtol=1e-11)
    assert "data set 2 (58" in caplog.text
    assert "last line" in caplog.text
    assert "dropped" in caplog.text


def test_a_nan_on_the_last_line_of_a_time_record_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A time record has no Nyquist line: its last sample is data like any other."""
    lines = _lines(write_hammer_uff(_records(), tmp_path / "hammer.uff"))
    _, closing = next((o, c) for o, c in _data_sets(lines) if lines[o + 1].strip() == "58")
    lines[closing - 1] = _value_at(lines[closing - 1], 3, "nan")
    path = _write(tmp_path / "hammer_nan.uff", lines)
    assert main(["frf", str(path), "--out", str(tmp_path / "out")]) == 2
    _one_line(capsys, "hammer_nan.uff", "data set 2 (58", "NaN")


def test_the_openmodal_wing_is_read_without_its_nyquist_nan(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """The real OpenModal export (issue 25, item 4): 18 FRFs to 999.997 Hz, record 7's last
    line NaN as exported.  Read with that line dropped, the rest finite."""
    import lzma

    import numpy as np

    from realdata import realdata_dir

    folder = realdata_dir() / "wing_openmodal"
    path = tmp_path / "wing_openmodal_measurements.uff"  # unpacked into the test's folder
    path.write_bytes(lzma.decompress((folder / "wing_openmodal_measurements.uff.xz").read_bytes()))
    caplog.set_level("INFO")
    frfs = read_frf_uff(path, geometry=folder / "wing_openmodal_geometry_m.csv")
    assert frfs.n_points == 18
    assert frfs.frequency.size == 4096
    assert frfs.frequency[-1] == pytest.approx(4095 * 1000.0 / 4096, rel=1e-5)
    assert np.all(np.isfinite(frfs.values))
    assert "data set 7 (58" in caplog.text
    assert "dropped" in caplog.text


# --- item 3: geometry faults -----------------------------------------------------------------
_NODE_12 = "        12         0         0         0  6.00000E-01 -3.00000E-02  0.00000E+00"
_2411 = [
    "    -1",
    "  2411",
    "        12         0         0        11",
    "   6.0000000000000000D-01  -3.0000000000000000D-02   0.0000000000000000D+00",
    "    -1",
]


def _frfs_with_geometry(tmp_path: Path, extra: list[str], into_15: bool) -> Path:
    """racketdyn's FRF file (data set 15: nodes 7, 3, 12) with lines added to its data set 15
    (``into_15``) or a data set after it."""
    lines = _lines(write_frf_uff(_frfs(), tmp_path / "frfs.uff"))
    assert lines[1].strip() == "15"
    assert lines[4] == _NODE_12
    at = 5 if into_15 else 6
    return _write(tmp_path / "geometry.uff", lines[:at] + extra + lines[at:])


@pytest.mark.parametrize(
    ("extra", "into_15", "words"),
    [
        ([_NODE_12.replace("6.00000E-01", "6.50000E-01")], True, ["data set 1 (15"]),
        ([*_2411[:3], _2411[3].replace("6.0000", "6.5000"), *_2411[4:]], False, ["(2411"]),
    ],
)
def test_a_node_defined_twice_at_two_places_is_refused(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    extra: list[str],
    into_15: bool,
    words: list[str],
) -> None:
    """Node 12 at x = 0.60 and again at x = 0.65 m: the later one silently won."""
    path = _frfs_with_geometry(tmp_path, extra, into_15)
    assert main(["identify", str(path), "--out", str(tmp_path / "out")]) == 2
    _one_line(capsys, "geometry.uff", "node 12", "0.6, -0.03, 0", "0.65, -0.03, 0", *words)


@pytest.mark.parametrize(("extra", "into_15"), [([_NODE_12], True), (_2411, False)])
def test_a_node_defined_twice_at_one_place_is_read_and_logged(
    tmp_path: Path, caplog: pytest.LogCaptureFixture, extra: list[str], into_15: bool
) -> None:
    import numpy as np

    path = _frfs_with_geometry(tmp_path, extra, into_15)
    caplog.set_level("INFO")
    frfs = read_frf_uff(path)
    np.testing.assert_allclose(frfs.locations, _frfs().locations, rtol=1e-6)
    assert "node 12" in caplog.text
    assert "twice" in caplog.text


def test_a_geometry_in_mm_without_164_is_one_line_naming_the_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Issue 12 refused it; the line wrote ``--geometry FILE`` below the CLI (a parameter is
    named in backticks there) and said mm for the OpenModal wing's inches (60 in read as
    60 m): the span in either unit is said."""
    lines = _lines(write_frf_uff(_frfs(), tmp_path / "frfs.uff"))
    geometry = lines[:6]
    for k in (2, 3, 4):  # the nodes in mm
        node, x, y = geometry[k][:40], float(geometry[k][40:53]), float(geometry[k][53:66])
        geometry[k] = f"{node}{x * 1e3:13.5E}{y * 1e3:13.5E}{geometry[k][66:]}"
    nodes = _write(tmp_path / "nodes_mm.uff", geometry)
    frfs = _write(tmp_path / "frfs_only.uff", lines[6:])
    assert (
        main(["identify", str(frfs), "--geometry", str(nodes), "--out", str(tmp_path / "o")]) == 2
    )
    # the words of issue 25's unit guess (merged with this branch): "span 150 units",
    # "0.15 m if in mm", "3.81 m if in inches"
    _one_line(
        capsys,
        "nodes_mm.uff",
        "data set 1 (15",
        "150 units",
        "0.15 m if in mm",
        "3.81 m if in inches",
    )
    with pytest.raises(InputError, match="`geometry`"):
        read_frf_uff(frfs, geometry=nodes)


def test_a_csv_geometry_in_mm_is_one_line_naming_the_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A geometry CSV whose x_m, y_m are in mm (a racket's points at 90–680 "m") was read
    without a word by identify (a new user's trial: "modes numbered: no points on both the
    strings and the frame"; only predict, a step later, said "in mm?"). It is refused as a
    Universal File's nodes are, with the span in mm and in inches."""
    frfs = _frfs()
    lines = _lines(write_frf_uff(frfs, tmp_path / "frfs.uff"))
    only = _write(tmp_path / "frfs_only.uff", lines[6:])
    rows = ["node,x_m,y_m"]  # the reference is node 7, a hammer point (the driving point)
    rows += [
        f"{n},{1e3 * x},{1e3 * y}" for n, (x, y) in zip(frfs.nodes, frfs.locations, strict=True)
    ]
    geometry = tmp_path / "points_mm.csv"
    geometry.write_text("\n".join(rows) + "\n", encoding="utf-8")
    argv = ["identify", str(only), "--geometry", str(geometry), "--out", str(tmp_path / "o")]
    assert main(argv) == 2
    _one_line(capsys, "points_mm.csv", "m if in mm", "m if in inches", "give the coordinates in m")


# --- item 4: nothing lost silently ------------------------------------------------------------
@pytest.mark.parametrize("kind", ["frf", "hammer"])
def test_a_racketdyn_file_cut_between_data_sets_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], kind: str
) -> None:
    """Cut right after a complete data set, a file of FRFs read as fewer points (and one of
    time records as fewer averages): racketdyn's files say how many data sets they hold."""
    if kind == "frf":
        written = write_frf_uff(_frfs(), tmp_path / "whole.uff")
        command, keep = "identify", 5  # geometry, FRF + coherence of two points: 5 of 7
    else:
        written = write_hammer_uff(_records(), tmp_path / "whole.uff")
        command, keep = "frf", 9  # geometry, 4 averages of force + response: 9 of 13
    lines = _lines(written)
    _, closing = _data_sets(lines)[keep - 1]
    path = _write(tmp_path / "cut.uff", lines[: closing + 1])
    assert main([command, str(path), "--out", str(tmp_path / "out")]) == 2
    records = len(_data_sets(lines)) - 1  # the data sets 58 (after the geometry)
    _one_line(
        capsys, "cut.uff", f"{keep - 1} of the {records} data sets 58", f"after data set {keep}"
    )


def test_a_file_ending_inside_a_line_after_a_data_set_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Any exporter's file cut while the next data set's opening '    -1' was written: the
    spaces left after the last complete data set were taken as the file's end."""
    from racketdyn.errors import InputError

    lines = _lines(FIXTURES / "testlab_like_frf.uff")
    _, closing = _data_sets(lines)[3]  # the 164, the 15 and the first two FRFs
    path = tmp_path / "cut.uff"
    path.write_text("\n".join(lines[: closing + 1]) + "\n   ", encoding="ascii")
    with pytest.raises(InputError, match=r"cut\.uff: .*ends inside a line after data set 4"):
        read_frf_uff(path)


@pytest.mark.parametrize(
    ("columns", "junk", "words"),
    [
        ((51, 55), "   x", ["record 6", "field 7", "'x'", "response direction"]),  # -3
        ((0, 5), "   99", ["record 6", "field 1", "function type 99"]),
        ((41, 51), "        1x", ["record 6", "field 6", "'1x'", "response node"]),
        ((20, 30), "       2.5", ["record 6", "field 4", "load case"]),
    ],
)
def test_a_damaged_58_header_names_the_field(
    tmp_path: Path, columns: tuple[int, int], junk: str, words: list[str]
) -> None:
    """pyuff reads a damaged optional field of record 6 as 0 (a direction −3 became +, a node
    0) and racketdyn ignored a data set of an unknown function type: less or other data."""
    from racketdyn.errors import InputError

    lines = _lines(FIXTURES / "testlab_like_frf.uff")
    opening, _ = _data_sets(lines)[3]  # the second FRF
    record6 = opening + 7
    assert lines[record6].split()[0] == "4"
    start, end = columns
    lines[record6] = lines[record6][:start] + junk + lines[record6][end:]
    path = _write(tmp_path / "damaged.uff", lines)
    with pytest.raises(InputError) as error:
        read_frf_uff(path)
    message = str(error.value)
    assert "\n" not in message
    for word in ["damaged.uff", "data set 4 (58", f"line {record6 + 1}", *words]:
        assert word in message, message


@pytest.mark.slow
def test_a_data_set_not_used_is_said_on_the_console(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A header damaged into another valid number (function type 4 → 0, general) made an FRF
    vanish without a word on the console: identify now names the data sets it did not use."""
    lines = _lines(FIXTURES / "testlab_like_frf.uff")
    opening, _ = _data_sets(lines)[4]  # the third FRF
    record6 = opening + 7
    lines[record6] = "    0" + lines[record6][5:]
    path = _write(tmp_path / "general.uff", lines)
    assert main(["identify", str(path), "--out", str(tmp_path / "out")]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "not used from the file: data set 5 of another function type" in out, out


# --- found by the fuzz test (tests/test_fuzz_readers.py) ---------------------------------------
def _hammer_csv_lines(tmp_path: Path) -> tuple[list[str], Path]:
    from racketdyn.io import write_hammer_csv

    path, geometry = write_hammer_csv(_records(), tmp_path / "hammer.csv", tmp_path / "pts.csv")
    return _lines(path), geometry


def test_a_quote_left_open_in_a_hammer_csv_names_its_line(tmp_path: Path) -> None:
    """A flipped byte made a value ``"0.5``: the csv module read the rest of the file as one
    field and a ``ValueError: zip() argument 2 is shorter`` came out."""
    from racketdyn.io import read_hammer_csv

    lines, geometry = _hammer_csv_lines(tmp_path)
    assert lines[4].startswith("node,")
    lines[6] = lines[6].replace(",", ',"', 1)
    path = _write(tmp_path / "quoted.csv", lines)
    with pytest.raises(InputError, match=r"quoted\.csv: line 7: .*quote") as error:
        read_hammer_csv(path, geometry)
    assert "\n" not in str(error.value)


def test_a_node_too_large_in_a_hammer_csv_names_its_line(tmp_path: Path) -> None:
    """A node of 99999999999999999999 raised numpy's ``OverflowError: Python int too large to
    convert to C long``."""
    from racketdyn.io import read_hammer_csv

    lines, geometry = _hammer_csv_lines(tmp_path)
    lines[5] = "99999999999999999999" + lines[5][lines[5].index(",") :]
    path = _write(tmp_path / "huge_node.csv", lines)
    with pytest.raises(InputError, match=r"huge_node\.csv: line 6, column node: .*whole number"):
        read_hammer_csv(path, geometry)


@pytest.mark.parametrize(
    ("reader", "text"),
    [
        ("read_points", 'point,x_m,y_m\ncentre,0.5,0\n"throat,0.4,0.01\ntip,0.6,0\n'),
        ("read_load_deflection", 'deflection_m,force_n\n0.001,50\n0.002,"130\n0.004,330\n'),
        ("read_e_bg_table", 'speed_mps,e_bg\n10,0.86\n"20,0.82\n30,0.78\n'),
        (
            "read_measured",
            "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio\n"
            '0.5,0,20,0,free,0.39\n0.55,0.03,25,0,"pinned,0.30\n0.45,0,20,0,free,0.35\n',
        ),
    ],
)
def test_a_quote_left_open_in_a_table_names_its_line(
    tmp_path: Path, reader: str, text: str
) -> None:
    """The same open quote in the points, ball-law, e_BG and measured-rebound tables."""
    import racketdyn.io as io

    path = tmp_path / "table.csv"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(InputError, match=r"table\.csv: line 3: .*quote") as error:
        getattr(io, reader)(path)
    assert "\n" not in str(error.value)


# --- the last point with fewer averages (issue 26, "Silent loss") ------------------------------
def _last_point_short() -> object:
    """racketdyn's 3 points × 2 averages with the last point's second average gone, as a file
    cut between data sets leaves it (the count it held is not in another system's file)."""
    import dataclasses

    records = _records()
    return dataclasses.replace(
        records,
        force=(*records.force[:2], records.force[2][:1]),
        response=(*records.response[:2], records.response[2][:1]),
    )


def _said_fewer(message: object) -> None:
    assert isinstance(message, str), message
    for word in ["point 12", "last in the file", "1 average", "2 averages", "cut"]:
        assert word in message, message


def test_the_last_point_with_fewer_averages_is_said_uff(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """A file cut exactly between data sets dropped the last average (13 of 14 hits) without a
    word: the reader says that the last point has fewer averages than the others."""
    path = write_hammer_uff(_last_point_short(), tmp_path / "short.uff")  # type: ignore[arg-type]
    caplog.set_level("WARNING")
    records = read_hammer_uff(path)
    assert [len(f) for f in records.force] == [2, 2, 1]
    _said_fewer(records.metadata.get("fewer_averages"))
    assert "short.uff" in caplog.text
    assert "point 12" in caplog.text


def test_the_last_point_with_fewer_averages_is_said_csv(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """The same for another system's CSV cut at the end of a record (its last average's lines
    gone; racketdyn's own CSV says how many records it holds and is refused)."""
    from racketdyn.io import read_hammer_csv

    lines, geometry = _hammer_csv_lines(tmp_path)
    lines = [line for line in lines if not line.startswith("# records:")]
    last = [i for i, line in enumerate(lines) if line.startswith("12,2,")]
    assert last[-1] == len(lines) - 1
    path = _write(tmp_path / "short.csv", lines[: last[0]])
    caplog.set_level("WARNING")
    records = read_hammer_csv(path, geometry)
    assert [len(f) for f in records.force] == [2, 2, 1]
    _said_fewer(records.metadata.get("fewer_averages"))
    assert "short.csv" in caplog.text


def test_a_point_in_the_middle_with_fewer_averages_is_not_a_cut(tmp_path: Path) -> None:
    """A lab leaving out a bad hit at one point is no damaged file: only the last point's
    shortfall suggests a cut."""
    import dataclasses

    records = _records()
    fewer = dataclasses.replace(
        records,
        force=(records.force[0], records.force[1][:1], records.force[2]),
        response=(records.response[0], records.response[1][:1], records.response[2]),
    )
    read = read_hammer_uff(write_hammer_uff(fewer, tmp_path / "middle.uff"))
    assert "fewer_averages" not in read.metadata


@pytest.mark.slow
def test_frf_says_the_last_point_has_fewer_averages(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = write_hammer_uff(_last_point_short(), tmp_path / "short.uff")  # type: ignore[arg-type]
    assert main(["frf", str(path), "--out", str(tmp_path / "out")]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "point 12, the last in the file, has 1 average" in out, out
    import json

    record = json.loads((tmp_path / "out" / "run.json").read_text(encoding="utf-8"))
    _said_fewer(record["fewer_averages"])


def test_an_infinite_step_in_racketdyn_s_id_line_5_leaks_no_warning(tmp_path: Path) -> None:
    """Found by the fuzz test: ``step inf`` in ID line 5 ("racketdyn abscissa start … step …")
    made numpy warn "invalid value encountered in multiply" on the console (read_hammer_uff
    had lost its warnings wrapper to a helper added above it).  The header's step is the
    record's step when the exact one is no finite number, as when it is no number at all."""
    lines = _lines(write_hammer_uff(_records(), tmp_path / "hammer.uff"))
    exact = [i for i, line in enumerate(lines) if "racketdyn abscissa start" in line]
    assert exact
    for i in exact:
        lines[i] = lines[i].split(" step ")[0] + " step inf"
    path = _write(tmp_path / "inf_step.uff", lines)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        records = read_hammer_uff(path)
    assert records.sampling_interval_s == pytest.approx(_records().sampling_interval_s, rel=1e-5)


@pytest.mark.parametrize("cut", ["between records", "inside the first record"])
def test_a_racketdyn_hammer_csv_cut_short_is_refused(tmp_path: Path, cut: str) -> None:
    """Found by the fuzz test: racketdyn's hammer CSV cut between two records read as fewer
    records, and cut inside its first record as that one shorter record, without a word.  The
    writer says how many records it holds (``# records: 6``), as its UFFs do."""
    from racketdyn.io import read_hammer_csv

    lines, geometry = _hammer_csv_lines(tmp_path)
    assert "# records: 6" in lines
    header = next(i for i, line in enumerate(lines) if line.startswith("node,"))
    if cut == "between records":
        end = next(i for i, line in enumerate(lines) if line.startswith("7,1,"))
    else:
        end = header + 100
    path = _write(tmp_path / "cut.csv", lines[:end])
    with pytest.raises(InputError) as error:
        read_hammer_csv(path, geometry)
    message = str(error.value)
    assert "\n" not in message
    held = 2 if cut == "between records" else 1
    for word in ["cut.csv", f"{held} of its 6 records", f"after line {end}", "# records: 6"]:
        assert word in message, message


def test_a_records_line_that_is_no_count_is_refused(tmp_path: Path) -> None:
    from racketdyn.io import read_hammer_csv

    lines, geometry = _hammer_csv_lines(tmp_path)
    lines = [("# records: six" if line == "# records: 6" else line) for line in lines]
    path = _write(tmp_path / "words.csv", lines)
    with pytest.raises(InputError, match=r"words\.csv: .*# records: .*whole number"):
        read_hammer_csv(path, geometry)


def test_contact_says_the_last_point_has_fewer_averages(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``contact`` reads the same records as ``frf``: the last point's shortfall is said there
    too (its mean contact time is then over fewer hits)."""
    import json

    path = write_hammer_uff(_last_point_short(), tmp_path / "short.uff")  # type: ignore[arg-type]
    assert main(["contact", str(path), "--out", str(tmp_path / "out")]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "point 12, the last in the file, has 1 average" in out, out
    record = json.loads((tmp_path / "out" / "run.json").read_text(encoding="utf-8"))
    (said,) = record["fewer_averages"]
    _said_fewer(said)


def test_a_sweep_range_of_absurdly_many_values_is_one_line(tmp_path: Path) -> None:
    """Found by the fuzz test: ``num = 99999999999999999999`` in a sweep spec's range raised
    numpy's ``ValueError: Maximum allowed size exceeded`` (and 10⁹ would fill the memory)."""
    from racketdyn.sweep.spec_file import load_sweep_spec

    for num in ("99999999999999999999", "100001"):
        path = tmp_path / "sweep.toml"
        path.write_text(
            "[impacts]\ngrid = 3\nball_speeds_mps = [20.0]\n\n[variables]\n"
            f"tension_n = {{ start = 226.0, stop = 266.0, num = {num} }}\n",
            encoding="utf-8",
        )
        with pytest.raises(InputError, match=r"\[variables\]\.tension_n\.num.*1 to 100000"):
            load_sweep_spec(path)


def test_every_hit_rejected_names_no_file_the_failed_run_leaves_out(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """An unseen lab's NI DAQ record whose force channel wanders (a 35 N swell over 0.1 s on
    a drifting baseline, no impulse) was refused "... see quality.csv ..." while the failed
    run leaves its folder as it was, without a quality.csv: the message names what to check,
    not a file that is not there."""
    from dataclasses import replace

    import numpy as np

    records = _records()
    records = replace(records, force=tuple(f + np.roll(f, 40, axis=1) for f in records.force))
    path = write_hammer_uff(records, tmp_path / "double.uff")
    out = tmp_path / "frf"
    assert main(["frf", str(path), "--out", str(out)]) == 2
    message = " ".join(capsys.readouterr().err.split())
    assert "every average of every point was rejected: double hit 6" in message, message
    assert not (out / "quality.csv").exists()
    assert "quality.csv" not in message, message
