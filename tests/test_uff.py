"""Universal Files and CSV of hammer tests: round trips to file precision, lab files, bad files.

ASCII data sets 58 hold 12 significant digits (E20.12), binary ones the doubles themselves, the
CSV 17 digits; node coordinates in data set 15 hold 6 (E13.5), so the test geometry has 6.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import pyuff  # type: ignore[import-untyped]
from numpy.typing import NDArray

from racketdyn.errors import InputError
from racketdyn.io import (
    read_frf_uff,
    read_hammer_csv,
    read_hammer_uff,
    write_frf_uff,
    write_hammer_csv,
    write_hammer_uff,
)
from racketdyn.measurement.records import FrfSet, HammerRecords

DT = 1 / 51200  # 6 significant digits do not hold it: the exact step rides in ID line 5
N_SAMPLES = 256
PRETRIGGER = 10 * DT
NODES = (3, 7, 12)
REFERENCE = 7  # also a hammer point: the driving point
LOCATIONS = np.array([[0.45, 0.0], [0.55, 0.02], [0.6, -0.03]])
ASCII_RTOL = 1e-11  # E20.12 keeps 12 significant digits

# --------------------------------------------------------------------------------------------
# synthetic data
# --------------------------------------------------------------------------------------------


def _time() -> NDArray[np.float64]:
    return np.asarray(np.arange(N_SAMPLES) * DT - PRETRIGGER, dtype=np.float64)


def _records(response_type: str = "acceleration") -> HammerRecords:
    """3 points × 2 averages: half-sine hammer pulses, damped-sine responses."""
    t = _time()
    pulse_s = 4e-4
    forces, responses = [], []
    for i in range(len(NODES)):
        force = np.zeros((2, N_SAMPLES))
        response = np.zeros((2, N_SAMPLES))
        for k in range(2):
            on = (t >= 0) & (t <= pulse_s)
            force[k, on] = 100 * (1 + 0.1 * k + 0.2 * i) * np.sin(np.pi * t[on] / pulse_s)
            ringing = np.exp(-40 * t) * np.sin(2 * np.pi * (500 + 50 * i) * t + 0.3 * k)
            response[k] = np.where(t >= 0, 30 * (1 + 0.1 * k) * ringing, 0.0)
        forces.append(force)
        responses.append(response)
    return HammerRecords(
        sampling_interval_s=DT,
        force=tuple(forces),
        response=tuple(responses),
        response_type=response_type,  # type: ignore[arg-type]
        nodes=NODES,
        locations=LOCATIONS,
        reference_node=REFERENCE,
        reference_location=(0.55, 0.02),
        pretrigger_s=PRETRIGGER,
        source="synthetic",
    )


def _frfs(frf_type: str = "accelerance") -> FrfSet:
    """Receptance of two modes (finite at 0 Hz), converted up to ``frf_type``."""
    frequency = np.asarray(np.fft.rfftfreq(N_SAMPLES, DT), dtype=np.float64)
    s = 2j * np.pi * frequency
    constants = np.array([[0.5, -0.2], [0.8, 0.3], [1.2, -0.6]])
    omega = 2 * np.pi * np.array([120.0, 330.0])
    zeta = np.array([0.01, 0.02])
    poles = s[:, None] ** 2 + 2 * zeta * omega * s[:, None] + omega**2
    receptance = (constants[:, None, :] / poles[None]).sum(-1)
    return FrfSet(
        frequency=frequency,
        values=receptance,
        frf_type="receptance",
        nodes=NODES,
        locations=LOCATIONS,
        reference_node=REFERENCE,
        reference_location=(0.55, 0.02),
        coherence=np.clip(0.9 + 0.1 * np.cos(frequency / 1000)[None, :] * np.ones((3, 1)), 0, 1),
        n_averages=np.array([2, 2, 3]),
        exponential_window_s=0.0123,
        estimator="H1",
        source="synthetic",
    ).as_type(frf_type)


def _raises(path: Path, call: Callable[[], object], *fragments: str) -> str:
    """The call raises one InputError, on one line, naming the file and ``fragments``."""
    with pytest.raises(InputError) as info:
        call()
    message = str(info.value)
    assert str(path) in message
    assert "\n" not in message
    for fragment in fragments:
        assert fragment in message, message
    return message


# lab files written directly with pyuff, as other software would


def _geometry_set(nodes: tuple[int, ...] = (*NODES,), kind: int = 15) -> dict[str, Any]:
    coordinates = {3: (0.45, 0.0), 7: (0.55, 0.02), 12: (0.6, -0.03)}
    n = len(nodes)
    return {
        "type": kind,
        "node_nums": list(nodes),
        "def_cs": [0] * n,
        "disp_cs": [0] * n,
        "color": [0] * n,
        "x": [coordinates[m][0] for m in nodes],
        "y": [coordinates[m][1] for m in nodes],
        "z": [0.0] * n,
    }


def _time_set(
    rsp_node: int,
    ref_node: int,
    case: int,
    quantity: int,
    data: NDArray[np.float64],
    dt: float = DT,
    label: str = "NONE",
    rsp_dir: int = 3,
) -> dict[str, Any]:
    return {
        "type": 58,
        "func_type": 1,
        "load_case_id": case,
        "rsp_node": rsp_node,
        "rsp_dir": rsp_dir,
        "ref_node": ref_node,
        "ref_dir": 3,
        "abscissa_spacing": 1,
        "abscissa_spec_data_type": 17,
        "ordinate_spec_data_type": quantity,
        "ordinate_axis_units_lab": label,
        "orddenom_spec_data_type": 0,
        "x": np.arange(data.size) * dt,
        "data": np.array(data, dtype=float),
    }


def _lab_sets(records: HammerRecords, geometry: bool = True) -> list[dict[str, Any]]:
    sets = [_geometry_set()] if geometry else []
    for node, force, response in zip(records.nodes, records.force, records.response, strict=True):
        for k in range(force.shape[0]):
            sets.append(_time_set(node, node, k + 1, 13, force[k]))
            sets.append(_time_set(REFERENCE, node, k + 1, 12, response[k]))
    return sets


def _write_lab(path: Path, sets: list[dict[str, Any]]) -> Path:
    pyuff.UFF(str(path)).write_sets(sets, mode="add")
    return path


# --------------------------------------------------------------------------------------------
# round trips
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("binary", [False, True], ids=["ascii", "binary"])
def test_frf_round_trip(tmp_path: Path, binary: bool) -> None:
    frfs = _frfs()
    back = read_frf_uff(write_frf_uff(frfs, tmp_path / "frf.uff", binary=binary))
    np.testing.assert_array_equal(back.frequency, frfs.frequency)
    if binary:  # the doubles themselves
        np.testing.assert_array_equal(back.values, frfs.values)
    else:
        np.testing.assert_allclose(back.values, frfs.values, rtol=ASCII_RTOL, atol=0)
    assert back.coherence is not None
    assert frfs.coherence is not None
    np.testing.assert_allclose(back.coherence, frfs.coherence, rtol=ASCII_RTOL)
    assert back.frf_type == "accelerance"
    assert back.nodes == NODES
    np.testing.assert_array_equal(back.locations, LOCATIONS)
    assert (back.reference_node, back.reference_location) == (REFERENCE, (0.55, 0.02))
    assert (back.estimator, back.exponential_window_s) == ("H1", 0.0123)
    assert back.n_averages is not None
    np.testing.assert_array_equal(back.n_averages, [2, 2, 3])


def test_ascii_is_the_default_and_binary_header_is_58b(tmp_path: Path) -> None:
    ascii_path = write_frf_uff(_frfs(), tmp_path / "a.uff")
    binary_path = write_frf_uff(_frfs(), tmp_path / "b.uff", binary=True)
    assert b"  58b" not in ascii_path.read_bytes()
    assert binary_path.read_bytes().count(b"    58b") == 2 * len(NODES)  # FRF + coherence


@pytest.mark.parametrize("binary", [False, True], ids=["ascii", "binary"])
def test_hammer_round_trip(tmp_path: Path, binary: bool) -> None:
    records = _records()
    back = read_hammer_uff(write_hammer_uff(records, tmp_path / "h.uff", binary=binary))
    assert back.sampling_interval_s == DT
    assert back.pretrigger_s == PRETRIGGER
    assert (back.nodes, back.reference_node, back.response_type) == (
        NODES,
        REFERENCE,
        "acceleration",
    )
    np.testing.assert_array_equal(back.locations, LOCATIONS)
    assert back.metadata["averages"] == [[1, 2]] * 3
    for got, want in zip(
        (*back.force, *back.response), (*records.force, *records.response), strict=True
    ):
        if binary:
            np.testing.assert_array_equal(got, want)
        else:
            np.testing.assert_allclose(got, want, rtol=0, atol=ASCII_RTOL * np.max(np.abs(want)))


def test_csv_round_trip_is_exact(tmp_path: Path) -> None:
    records = _records("velocity")
    back = read_hammer_csv(*write_hammer_csv(records, tmp_path / "h.csv", tmp_path / "g.csv"))
    assert back.sampling_interval_s == pytest.approx(DT, rel=1e-14)
    assert back.pretrigger_s == PRETRIGGER
    assert (back.nodes, back.reference_node, back.response_type) == (
        NODES,
        REFERENCE,
        "velocity",
    )
    assert back.reference_location == (0.55, 0.02)
    np.testing.assert_array_equal(back.locations, LOCATIONS)
    for got, want in zip(
        (*back.force, *back.response), (*records.force, *records.response), strict=True
    ):
        np.testing.assert_array_equal(got, want)


def test_geometry_csv_is_pure_data(tmp_path: Path) -> None:
    """No comment line before the header: pandas reads the node table as it is (issue 13)."""
    import pandas as pd

    _, geometry = write_hammer_csv(_records(), tmp_path / "h.csv", tmp_path / "g.csv")
    table = pd.read_csv(geometry)
    assert list(table.columns) == ["node", "x_m", "y_m"]
    assert table["node"].tolist() == sorted({REFERENCE, *NODES})


@pytest.mark.parametrize(
    ("frf_type", "code"), [("receptance", 8), ("mobility", 11), ("accelerance", 12)]
)
def test_frf_type_follows_the_ordinate_type(tmp_path: Path, frf_type: str, code: int) -> None:
    path = write_frf_uff(_frfs(frf_type), tmp_path / "frf.uff")
    frf_sets = [s for s in pyuff.UFF(str(path)).read_sets() if s.get("func_type") == 4]
    assert {s["ordinate_spec_data_type"] for s in frf_sets} == {code}
    assert {s["orddenom_spec_data_type"] for s in frf_sets} == {13}
    assert read_frf_uff(path).frf_type == frf_type


@pytest.mark.parametrize(("response_type", "code"), [("displacement", 8), ("velocity", 11)])
def test_hammer_response_type_follows_the_ordinate_type(
    tmp_path: Path, response_type: str, code: int
) -> None:
    path = write_hammer_uff(_records(response_type), tmp_path / "h.uff")
    kinds = {s["ordinate_spec_data_type"] for s in pyuff.UFF(str(path)).read_sets()[1:]}
    assert kinds == {13, code}
    assert read_hammer_uff(path).response_type == response_type


def test_writing_replaces_the_file(tmp_path: Path) -> None:
    path = tmp_path / "frf.uff"
    write_frf_uff(_frfs(), path, binary=True)
    write_frf_uff(_frfs(), path, binary=True)
    assert pyuff.UFF(str(path)).get_n_sets() == 1 + 2 * len(NODES)


def test_uneven_frequencies_keep_six_digits(tmp_path: Path) -> None:
    frfs = _frfs()
    keep = np.r_[1:40, 60:129]
    uneven = FrfSet(
        frequency=frfs.frequency[keep],
        values=frfs.values[:, keep],
        frf_type=frfs.frf_type,
        nodes=NODES,
        locations=LOCATIONS,
        reference_node=REFERENCE,
        reference_location=(0.55, 0.02),
    )
    back = read_frf_uff(write_frf_uff(uneven, tmp_path / "frf.uff"))
    np.testing.assert_allclose(back.frequency, uneven.frequency, rtol=5e-6)
    np.testing.assert_allclose(back.values, uneven.values, rtol=ASCII_RTOL)
    assert (back.estimator, back.exponential_window_s, back.coherence) == ("file", None, None)


# --------------------------------------------------------------------------------------------
# lab files
# --------------------------------------------------------------------------------------------


def test_lab_file_with_geometry_in_a_separate_file(tmp_path: Path) -> None:
    records = _records()
    data = _write_lab(tmp_path / "data.uff", _lab_sets(records, geometry=False))
    geometry = _write_lab(tmp_path / "nodes.unv", [_geometry_set(kind=2411)])
    back = read_hammer_uff(data, geometry=geometry)
    np.testing.assert_array_equal(back.locations, LOCATIONS)
    assert back.reference_location == (0.55, 0.02)
    np.testing.assert_allclose(back.force[2], records.force[2], rtol=ASCII_RTOL)
    # issue 12, item 2: FRFs need no geometry; the records come without locations, and a step
    # that needs them names --geometry
    bare = read_hammer_uff(data)
    assert np.isnan(bare.locations).all()
    assert not bare.has_locations
    np.testing.assert_allclose(bare.force[2], records.force[2], rtol=ASCII_RTOL)
    _raises(data, lambda: bare.require_locations("the map"), "the map", "`geometry`")


def test_lab_file_with_geometry_in_a_csv_file(tmp_path: Path) -> None:
    """--geometry takes a CSV node,x_m,y_m for a Universal File too, as its help says."""
    records = _records()
    data = _write_lab(tmp_path / "data.uff", _lab_sets(records, geometry=False))
    nodes = [*records.nodes, records.reference_node]
    places = [*(tuple(row) for row in LOCATIONS), records.reference_location]
    lines = [
        "node,x_m,y_m",
        *(f"{n},{float(x)!r},{float(y)!r}" for n, (x, y) in zip(nodes, places, strict=True)),
    ]
    geometry = tmp_path / "nodes.csv"
    geometry.write_text("\n".join(lines) + "\n", encoding="utf-8")
    back = read_hammer_uff(data, geometry=geometry)
    np.testing.assert_array_equal(back.locations, LOCATIONS)
    assert back.reference_location == records.reference_location


def test_lab_file_units_labels_and_directions(tmp_path: Path) -> None:
    records = _records()
    sets = [_geometry_set()]
    for node, force, response in zip(records.nodes, records.force, records.response, strict=True):
        for k in range(2):
            sets.append(_time_set(node, node, k + 1, 13, force[k] / 1000, label="kN"))
            sets.append(_time_set(REFERENCE, node, k + 1, 12, response[k], label="g", rsp_dir=-3))
    back = read_hammer_uff(_write_lab(tmp_path / "lab.uff", sets))
    np.testing.assert_allclose(back.force[0], records.force[0], rtol=1e-10)
    np.testing.assert_allclose(back.response[0], -9.80665 * records.response[0], rtol=1e-10)


def test_lab_file_with_si_factors_of_data_set_164(tmp_path: Path) -> None:
    units = {"type": 164, "units_code": 5, "length": 1000.0, "force": 1000.0, "temp": 1.0}
    geometry = _geometry_set()
    geometry["x"] = [1000 * x for x in geometry["x"]]
    geometry["y"] = [1000 * y for y in geometry["y"]]
    records = _records()
    sets = [units | {"temp_offset": 0.0}, geometry, *_lab_sets(records, geometry=False)]
    back = read_hammer_uff(_write_lab(tmp_path / "mm.uff", sets))
    np.testing.assert_allclose(back.locations, LOCATIONS, rtol=1e-12)
    np.testing.assert_allclose(back.response[1], records.response[1] / 1000, rtol=1e-10)
    np.testing.assert_allclose(back.force[1], records.force[1] / 1000, rtol=1e-10)


# --------------------------------------------------------------------------------------------
# bad files
# --------------------------------------------------------------------------------------------


def test_missing_empty_and_foreign_files(tmp_path: Path) -> None:
    missing = tmp_path / "nothing.uff"
    _raises(missing, lambda: read_hammer_uff(missing), "no such file")
    _raises(missing, lambda: read_frf_uff(missing), "no such file")
    empty = tmp_path / "empty.uff"
    empty.write_text("")
    _raises(empty, lambda: read_frf_uff(empty), "empty")
    text = tmp_path / "points.csv"
    text.write_text("x_m,y_m\n0.5,0.0\n")
    _raises(text, lambda: read_hammer_uff(text), "not a Universal File")
    geometry = tmp_path / "nodes.uff"
    data = write_hammer_uff(_records(), tmp_path / "h.uff")
    _raises(missing, lambda: read_hammer_uff(data, geometry=missing), "no such file")
    _write_lab(geometry, [_time_set(3, 3, 1, 13, np.ones(16))])
    _raises(geometry, lambda: read_hammer_uff(data, geometry=geometry), "no node coordinates")


@pytest.mark.parametrize("binary", [False, True], ids=["ascii", "binary"])
def test_truncated_file(tmp_path: Path, binary: bool) -> None:
    path = write_hammer_uff(_records(), tmp_path / "h.uff", binary=binary)
    raw = path.read_bytes()
    path.write_bytes(raw[: len(raw) // 2])
    _raises(path, lambda: read_hammer_uff(path), "truncated")


def test_damaged_record_is_named(tmp_path: Path) -> None:
    path = write_frf_uff(_frfs(), tmp_path / "frf.uff")
    lines = path.read_text().splitlines(keepends=True)
    del lines[30]  # a data line of the second data set (the first FRF)
    path.write_text("".join(lines))
    _raises(path, lambda: read_frf_uff(path), "data set 2 ", "header says")


def test_wrong_kind_of_file(tmp_path: Path) -> None:
    frf = write_frf_uff(_frfs(), tmp_path / "frf.uff")
    hammer = write_hammer_uff(_records(), tmp_path / "h.uff")
    _raises(frf, lambda: read_hammer_uff(frf), "no time records", "read_frf_uff")
    _raises(hammer, lambda: read_frf_uff(hammer), "no FRFs", "read_hammer_uff")


@pytest.mark.parametrize(("drop", "missing"), [(2, "response"), (5, "force")])
def test_average_missing_a_record(tmp_path: Path, drop: int, missing: str) -> None:
    sets = _lab_sets(_records())
    kept = sets[:drop] + sets[drop + 1 :]
    path = _write_lab(tmp_path / "lab.uff", kept)
    _raises(path, lambda: read_hammer_uff(path), f"no {missing} record", "load case")


def test_records_of_different_length_or_sampling(tmp_path: Path) -> None:
    records = _records()
    sets = _lab_sets(records)
    sets[5] = _time_set(7, 7, 1, 13, records.force[1][0][:128])
    path = _write_lab(tmp_path / "short.uff", sets)
    _raises(path, lambda: read_hammer_uff(path), "data sets 2 and 6", "length and sampling")
    sets = _lab_sets(records)
    sets[6] = _time_set(REFERENCE, 7, 1, 12, records.response[1][0], dt=2 * DT)
    path = _write_lab(tmp_path / "slow.uff", sets)
    _raises(path, lambda: read_hammer_uff(path), "data sets 2 and 7")


def test_no_force_channel(tmp_path: Path) -> None:
    sets = [s for s in _lab_sets(_records()) if s.get("ordinate_spec_data_type") != 13]
    path = _write_lab(tmp_path / "lab.uff", sets)
    _raises(path, lambda: read_hammer_uff(path), "no force channel")


def test_nan_in_the_data(tmp_path: Path) -> None:
    records = _records()
    records.force[1][0, 3] = 1.2345e67  # a marker to replace by NaN in the text
    path = write_hammer_uff(records, tmp_path / "h.uff")
    text = path.read_text()
    assert text.count("1.23450000000e+67") == 1
    path.write_text(text.replace("1.23450000000e+67", "nan".rjust(17)))
    # samples counted from 1, as in the file (index 3 is its fourth)
    _raises(path, lambda: read_hammer_uff(path), "data set 6 ", "NaN", "sample 4 of 256")


def test_node_without_coordinates(tmp_path: Path) -> None:
    sets = _lab_sets(_records())
    sets[0] = _geometry_set((3, 7))
    path = _write_lab(tmp_path / "lab.uff", sets)
    records = read_hammer_uff(path)
    assert np.isnan(records.locations[2]).all()
    np.testing.assert_array_equal(records.locations[:2], LOCATIONS[:2])
    _raises(path, lambda: records.require_locations("the map"), "12", "`geometry`")
    # written again, the node without coordinates is left out of data set 15
    again = read_hammer_uff(write_hammer_uff(records, path.with_name("again.uff")))
    np.testing.assert_array_equal(again.locations, records.locations)


def test_frfs_on_different_frequency_axes(tmp_path: Path) -> None:
    path = write_frf_uff(_frfs(), tmp_path / "frf.uff")
    sets = pyuff.UFF(str(path)).read_sets()
    sets[3]["x"] = sets[3]["x"] * 2  # the second FRF (data set 3 is the first coherence)
    fresh = _write_lab(tmp_path / "mixed.uff", sets)
    _raises(fresh, lambda: read_frf_uff(fresh), "data sets 2 and 4", "frequency axis")


def test_unknown_units_label(tmp_path: Path) -> None:
    sets = _lab_sets(_records())
    sets[2]["ordinate_axis_units_lab"] = "furlong/s^2"
    path = _write_lab(tmp_path / "lab.uff", sets)
    _raises(path, lambda: read_hammer_uff(path), "data set 3 ", "'furlong/s^2'")


def test_writers_refuse_what_pyuff_would_spoil(tmp_path: Path) -> None:
    path = tmp_path / "frf.uff"
    with_nan = _frfs().as_type("receptance").as_type("mobility")  # 0 Hz line: NaN
    assert np.isnan(with_nan.values[:, 0]).all()
    _raises(path, lambda: write_frf_uff(with_nan, path), "node 3", "NaN")
    assert not path.exists()
    folder = tmp_path / "no-such-folder" / "frf.uff"
    _raises(folder, lambda: write_frf_uff(_frfs(), folder), "does not exist")


def test_bad_csv_files(tmp_path: Path) -> None:
    data, geometry = write_hammer_csv(_records(), tmp_path / "h.csv", tmp_path / "g.csv")
    text = data.read_text()
    no_reference = tmp_path / "no_reference.csv"
    no_reference.write_text(text.replace("# reference_node: 7\n", ""))
    _raises(no_reference, lambda: read_hammer_csv(no_reference, geometry), "# reference_node")
    lines = text.splitlines()
    lines[10] = ",".join([*lines[10].split(",")[:3], "nan", "0"])
    bad = tmp_path / "nan.csv"
    bad.write_text("\n".join(lines) + "\n")
    _raises(bad, lambda: read_hammer_csv(bad, geometry), "line 11", "force_n")
    short = tmp_path / "short.csv"
    short.write_text("\n".join(text.splitlines()[:-3]) + "\n")
    _raises(short, lambda: read_hammer_csv(short, geometry), "node 12, average 2")
    geometry.write_text("node,x_m,y_m\n3,0.45,0.0\n7,0.55,0.02\n")
    partial = read_hammer_csv(data, geometry)
    assert np.isnan(partial.locations[2]).all()
    _raises(data, lambda: partial.require_locations("the map"), "which node 12 lacks", "`geometry`")
    assert np.isnan(read_hammer_csv(data).locations).all()


def test_the_cli_names_the_command_for_the_wrong_kind_of_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``racketdyn identify`` on a time-record UFF said "read it with read_hammer_uff", a
    Python function the command-line user cannot call: the CLI says to run ``racketdyn frf``
    first (and ``frf`` on FRFs, to identify them); the library keeps the Python name."""
    from racketdyn.cli import main

    frf = write_frf_uff(_frfs(), tmp_path / "frf.uff")
    hammer = write_hammer_uff(_records(), tmp_path / "h.uff")
    assert main(["identify", str(hammer), "--out", str(tmp_path / "i")]) == 2
    said = " ".join(capsys.readouterr().err.split())
    assert "no FRFs" in said
    assert "read_hammer_uff" not in said
    assert "run racketdyn frf on it first" in said
    assert main(["frf", str(frf), "--out", str(tmp_path / "f")]) == 2
    said = " ".join(capsys.readouterr().err.split())
    assert "no time records" in said
    assert "read_frf_uff" not in said
    assert "racketdyn identify" in said


@pytest.fixture
def modes_uff(tmp_path: Path) -> Path:
    """What identify and compare write: ``modes_free.uff`` (UFF 55) beside
    ``modal_model_free.json``."""
    from racketdyn.io import write_modes_uff
    from racketdyn.modal import ModalModel

    model = ModalModel.read_json(Path(__file__).parent / "data" / "demo_modal_model_free.json")
    model.write_json(tmp_path / "modal_model_free.json")
    return write_modes_uff(model, tmp_path / "modes_free.uff")


def test_a_modal_model_uff_given_as_the_modal_model_names_the_json_beside(
    modes_uff: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """New-user trial (2026-11-27, ninth session): ``predict --modal compare/modes_free.uff``
    said "not a racketdyn modal model JSON file (Extra data: line 2 column 5 (char 11))": the
    error names what the file is (UFF 55 mode shapes, as identify and compare write) and the
    JSON beside it to give instead."""
    from racketdyn.cli import main
    from racketdyn.workflows import PredictOptions, run_predict
    from racketdyn.workflows.setup import Setup

    argv = ["predict", "--modal", str(modes_uff), "--no-figures", "--out", str(tmp_path / "p")]
    assert main(argv) == 2
    said = " ".join(capsys.readouterr().err.split())
    assert "Extra data" not in said
    assert "--modal" in said
    assert "mode shapes (UFF data set 55)" in said
    assert "racketdyn identify and compare write" in said
    assert f"give {tmp_path / 'modal_model_free.json'}" in said
    with pytest.raises(InputError) as caught:  # a Python caller hears its own words
        run_predict(tmp_path / "py", Setup(modal_model=modes_uff), PredictOptions(grid=3))
    assert "`modal_model`" in str(caught.value)
    assert "`write_modes_uff`" in str(caught.value)
    (tmp_path / "modal_model_free.json").unlink()
    assert main(argv) == 2
    said = " ".join(capsys.readouterr().err.split())
    assert "give the modal_model*.json" in said


def test_identify_on_a_modal_model_uff_says_it_holds_mode_shapes_not_frfs(
    modes_uff: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """New-user trial (2026-11-27, ninth session): ``identify compare/modes_free.uff`` (its own
    UFF 55 output) was told to "export FRFs … spectra and PSDs … are not read": it is told the
    file is a modal model (mode shapes), not FRFs, and where the model's JSON is."""
    from racketdyn.cli import main

    for command in ("identify", "frf"):
        assert main([command, str(modes_uff), "--out", str(tmp_path / command)]) == 2
        said = " ".join(capsys.readouterr().err.split())
        assert "spectra and PSDs" not in said, command
        assert "mode shapes (UFF data set 55)" in said, command
        assert "a modal model, as racketdyn identify and compare write" in said, command
        assert "modal_model_free.json" in said, command
