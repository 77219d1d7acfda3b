"""FRFs exported one text file per point (DataPhysics SignalCalc's text export) and the FRF
table that puts them together (:mod:`racketdyn.io.frf_table`).

The exports here are written from a known two-mode model in SignalCalc's layout (its header,
tab-separated columns, the units' ² in Latin-1, as ``../shared/realdata/ModeLAB`` has them);
the real files are read in ``tests/test_realdata_must_hold.py``.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from racketdyn.cli import main
from racketdyn.errors import InputError
from racketdyn.io.frf_layout import read_frfs
from racketdyn.io.frf_table import read_text_frf
from racketdyn.modal.identify import identify

FREQUENCY = np.arange(0.0, 1000.0 + 0.25, 0.25)
MODES_HZ = np.array([180.0, 520.0])
DAMPING = np.array([0.004, 0.006])
Z_M = np.array([0.05, 0.2, 0.35, 0.5, 0.65])


def _shapes(z: np.ndarray) -> np.ndarray:
    """Mass-normalised shapes of the two modes at ``z`` (1/√kg)."""
    return np.stack([np.cos(np.pi * z / 0.7), np.cos(2 * np.pi * z / 0.7)], axis=-1) / 0.5


def _accelerance(z_point: float, z_sensor: float) -> np.ndarray:
    w = 2 * np.pi * FREQUENCY
    wk = 2 * np.pi * MODES_HZ
    residues = _shapes(np.array([z_point]))[0] * _shapes(np.array([z_sensor]))[0]
    return np.asarray(
        -(w**2)[:, None] * residues / (wk**2 - (w**2)[:, None] + 2j * DAMPING * wk * w[:, None])
    ).sum(axis=1)


def _export(path: Path, values: np.ndarray, units: str = "(m/s\u00b2)(N)") -> None:
    head = [
        "Units: Ratio",
        "Ref Chan:Resp Chan\t0-Z:0-Z",
        "Channel Name\t : ",
        "Channel Comment\t : ",
        "",
        "Frequency\t Real\t Imaginary",
        "",
        "Units:",
        f"Hz\t{units}\t ",
    ]
    rows = [
        f"{f:.13e}\t{v.real:16.7g}\t{v.imag:16.7g}" for f, v in zip(FREQUENCY, values, strict=True)
    ]
    path.write_bytes("\r\n".join(head + rows).encode("latin-1"))


def _table(folder: Path, sensor_sign: str = "-x") -> Path:
    """Five exports (hammer +x along z) and a sensor at z = 0.2 m (point 2) pointing
    ``sensor_sign``: the analyser stored the lab-frame accelerance times the sensor's sign."""
    sign = -1.0 if sensor_sign.startswith("-") else 1.0
    lines = ["# a free beam, roving hammer", "file,node,x_m,y_m,z_m,direction"]
    for k, z in enumerate(Z_M, start=1):
        _export(folder / f"Hxy{k}.txt", sign * _accelerance(z, 0.2))
        lines.append(f"Hxy{k}.txt,{k},0,0,{z},+x")
    lines.append(f"reference,2,,,,{sensor_sign}")
    table = folder / "frfs.csv"
    table.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return table


def test_the_table_gives_the_lab_frame_frfs_in_si(tmp_path: Path) -> None:
    frfs = read_frfs(_table(tmp_path))
    assert frfs.nodes == (1, 2, 3, 4, 5)
    assert frfs.reference_node == 2
    assert frfs.frf_type == "accelerance"
    assert frfs.metadata["layout"] == "roving hammer"
    np.testing.assert_allclose(frfs.locations[:, 2], Z_M)
    # the reference row names point 2 with no coordinates: it is that point
    np.testing.assert_allclose(frfs.reference_location, frfs.locations[1])
    expected = np.array([_accelerance(z, 0.2) for z in Z_M])
    scale = np.abs(expected).max()
    # the sensor pointed -x: the stored values were negated, the table's signs undo it (to the
    # seven digits the export writes)
    assert np.abs(frfs.values - expected).max() < 1e-6 * scale


def test_a_beam_exported_one_file_a_point_is_identified(tmp_path: Path) -> None:
    found = identify(read_frfs(_table(tmp_path, "+x")))
    np.testing.assert_allclose(np.sort(found.model.frequency), MODES_HZ, rtol=1e-4)
    np.testing.assert_allclose(
        found.model.damping_ratio[np.argsort(found.model.frequency)], DAMPING, rtol=0.05
    )
    # mass-normalised at the driving point (node 2): the shapes' own amplitudes back
    model = found.model
    truth = _shapes(Z_M)[:, np.argsort(np.argsort(model.frequency))]
    for k in range(2):
        sign = np.sign(model.mode_shapes[:, k] @ truth[:, k])
        np.testing.assert_allclose(sign * model.mode_shapes[:, k], truth[:, k], atol=0.02)


def test_grams_per_newton_and_the_nyquist_line(tmp_path: Path) -> None:
    values = _accelerance(0.5, 0.2)
    _export(tmp_path / "g.txt", values / 9.80665, "(g)(N)")
    frf = read_text_frf(tmp_path / "g.txt")
    assert np.abs(frf.values - values).max() < 1e-6 * np.abs(values).max()
    text = (tmp_path / "g.txt").read_bytes().decode("latin-1").splitlines()
    text[-1] = text[-1].split("\t")[0] + "\tnan\tnan"
    (tmp_path / "g.txt").write_bytes("\n".join(text).encode("latin-1"))
    assert read_text_frf(tmp_path / "g.txt").frequency.size == FREQUENCY.size - 1


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (lambda s: s.replace("reference,2,,,,-x\n", ""), "0 rows with file 'reference'"),
        (lambda s: s.replace("z_m,direction", "z,direction"), "an FRF table has"),
        (lambda s: s.replace("Hxy2.txt,2,0,0,0.2,+x", "Hxy2.txt,2,0,0,0.2,up"), "give +x, -x"),
        (lambda s: s.replace("Hxy2.txt,2,", "Hxy9.txt,2,"), "Hxy9.txt (node 2) is not a file"),
        (lambda s: s.replace("Hxy2.txt,2,", "Hxy2.txt,1,"), "node 1 has two files"),
        (lambda s: s.replace("Hxy2.txt,2,0,0,0.2", "Hxy2.txt,2,0,0,0.2m"), "z_m '0.2m'"),
        (lambda s: s.replace("Hxy2.txt,2,0,0,0.2,+x", "Hxy2.txt,2,0,0,0.2,+z"), "one axis"),
    ],
)
def test_a_bad_table_is_one_line_naming_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], change: object, words: str
) -> None:
    table = _table(tmp_path)
    table.write_text(change(table.read_text()), encoding="utf-8")  # type: ignore[operator]
    with pytest.raises(InputError, match=re.escape(words)):
        read_frfs(table)
    assert main(["identify", str(table), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert str(table) in err[0]


@pytest.mark.parametrize(
    ("edit", "words"),
    [
        (lambda s: s.replace("Real\t Imaginary", "Magnitude\t Phase"), "not magnitude and phase"),
        (lambda s: s.replace("(m/s\u00b2)(N)", "(furlong)(N)"), "unit 'furlong'"),
        (lambda s: s.replace("Frequency\t Real", "Freq\t Real"), "no 'Frequency Real Imaginary'"),
    ],
)
def test_a_bad_export_is_one_line_naming_it(tmp_path: Path, edit: object, words: str) -> None:
    table = _table(tmp_path)
    export = tmp_path / "Hxy4.txt"
    export.write_bytes(edit(export.read_bytes().decode("latin-1")).encode("latin-1"))  # type: ignore[operator]
    with pytest.raises(InputError, match=re.escape(words)) as caught:
        read_frfs(table)
    assert "Hxy4.txt" in str(caught.value)


def test_exports_of_other_lines_are_refused(tmp_path: Path) -> None:
    table = _table(tmp_path)
    export = tmp_path / "Hxy5.txt"
    lines = export.read_bytes().decode("latin-1").splitlines()
    export.write_bytes("\n".join(lines[:-10]).encode("latin-1"))
    with pytest.raises(InputError, match=re.escape("Hxy5.txt's lines are not Hxy1.txt's")):
        read_frfs(table)


def test_an_frf_table_takes_no_geometry(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="give no `geometry`"):
        read_frfs(_table(tmp_path), geometry=tmp_path / "g.uff")


@pytest.mark.slow
def test_a_structure_not_a_racket_is_not_said_to_be_free(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """identify headed a cantilevered wing's table "(free)", the racket test's default
    support (new-user trial, eleventh session): a structure that is not a racket's face gets
    no support word."""
    assert main(["identify", str(_table(tmp_path, "+x")), "--out", str(tmp_path / "o")]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "2 modes, " in out
    assert "(free)" not in out
