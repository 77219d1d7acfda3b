"""Layouts of other acquisition systems' UFF exports: read right, or refused in one line.

The fixtures (tests/fixtures, written by tests/fixtures/make_fixtures.py from racketdyn's own
two-mode model) reproduce what was studied on the public example files of pyuff's
repository: HBM catman's recorder channels, ARTeMIS's output-only records and geometry, and
an FRF export that names no point (Latin-1 units, ordinate type "general").  Issue 12,
"Tests and evidence": the corpus.
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

from racketdyn.cli import main
from racketdyn.io import read_frf_uff, read_hammer_uff
from racketdyn.io.frf_layout import read_frfs
from racketdyn.modal.identify import identify

FIXTURES = Path(__file__).parent / "fixtures"
sys.path.insert(0, str(FIXTURES))
import make_fixtures  # noqa: E402

from test_uff_lab import _one_line_error  # noqa: E402

E13_5_RTOL = 1e-5  # E13.5 and 12.5e keep 6 significant digits: half a unit in the 6th is 5e-6


def _with_record6(source: Path, target: Path, fields: list[tuple[int, int, int]]) -> Path:
    """``source`` with record 6 of its k-th data set 58 given (response node, direction,
    reference node) = ``fields[k]``: the one fix a user makes to such an export."""
    lines = source.read_bytes().decode("latin-1").split("\n")
    k = 0
    for i, line in enumerate(lines):
        if line.strip() == "58":
            rsp, rsp_dir, ref = fields[k]
            j = i + 6  # record 6 follows the five ID lines
            old = lines[j]
            lines[j] = f"{old[:41]}{rsp:10d}{rsp_dir:4d}{old[55:66]}{ref:10d}{3 if ref else 0:4d}"
            k += 1
    path = target / source.name
    path.write_bytes("\n".join(lines).encode("latin-1"))
    return path


def _cli_refuses(tmp_path: Path, capsys: pytest.CaptureFixture[str], *args: str) -> str:
    assert main([*args, "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert err[0].startswith("racketdyn: error:")
    return err[0]


# ---- HBM catman ----------------------------------------------------------------------------


def test_catman_channels_without_a_hammer_node_are_refused_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Reference node 0 and the channel number as response node: the file does not say where
    # the hammer struck, so no FRF can be put at a point.  The line names the record and field
    # to set and the CSV alternative.
    path = FIXTURES / "catman_like_time.uff"
    _one_line_error(
        lambda: read_hammer_uff(path), str(path), "data set 2", "record 6, field 9", "catman"
    )
    assert "CSV" in _cli_refuses(tmp_path, capsys, "frf", str(path))


def test_catman_channels_read_by_their_units_once_the_nodes_are_set(tmp_path: Path) -> None:
    # Ordinate type 1 (general) with "N" and the UTF-8 "m/s²" as the only clue to the
    # quantity; record 7 with three-digit exponents, a short last data line.  With record 6
    # naming hammer node 7 and sensor node 2 the samples are the model's to 6 digits.
    path = _with_record6(FIXTURES / "catman_like_time.uff", tmp_path, [(7, 0, 0), (2, 3, 7)])
    records = read_hammer_uff(path)
    force, acc = make_fixtures.catman_channels()
    assert records.nodes == (7,)
    assert records.reference_node == 2
    assert records.response_type == "acceleration"
    assert records.sampling_interval_s == pytest.approx(1 / make_fixtures.CATMAN_FS, rel=1e-12)
    assert records.force[0].shape == (1, make_fixtures.CATMAN_SAMPLES)  # 125 = 20 lines of 6 + 5
    np.testing.assert_allclose(records.force[0][0], force, rtol=E13_5_RTOL, atol=1e-9)
    np.testing.assert_allclose(records.response[0][0], acc, rtol=E13_5_RTOL, atol=1e-9)


# ---- ARTeMIS -------------------------------------------------------------------------------


def test_artemis_output_only_records_are_refused_naming_the_missing_force(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Ambient responses only (operational modal analysis): no hammer, no FRF possible.
    path = FIXTURES / "artemis_like_time.uff"
    _one_line_error(lambda: read_hammer_uff(path), str(path), "no force channel", "output-only")
    assert "no force channel" in _cli_refuses(tmp_path, capsys, "frf", str(path))


def test_artemis_geometry_with_nodes_out_of_order_traces_and_elements() -> None:
    # Data set 15 lists 16, 17, 3, 1, 2, ...; trace lines (82) and elements (2412) follow.
    # As --geometry it is read by node number, and its points take precedence over the
    # FRF file's own data set 15 (nodes 1-3 moved by 10 mm in it).
    frfs = read_frf_uff(
        FIXTURES / "testlab_like_frf.uff", geometry=FIXTURES / "artemis_like_geometry.uff"
    )
    expected = np.array([make_fixtures.ARTEMIS_NODES[n][:2] for n in frfs.nodes])
    np.testing.assert_allclose(frfs.locations, expected, atol=1e-12)
    assert tuple(frfs.reference_location) == pytest.approx(make_fixtures.ARTEMIS_NODES[2][:2])


# ---- an FRF export that names no point -----------------------------------------------------


def test_frf_naming_no_point_is_refused_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Response and reference node 0: a driving point cannot be told from a transfer point.
    path = FIXTURES / "h1_unlabelled_frf.uff"
    _one_line_error(lambda: read_frf_uff(path), str(path), "node 0", "record 6, fields 6 and 9")
    assert "node 0" in _cli_refuses(tmp_path, capsys, "identify", str(path))


def test_frf_of_general_type_read_by_its_latin1_label_and_identified(tmp_path: Path) -> None:
    # Ordinate type 1 with "(1/N)*(m/s²)" in one label, "²" the Latin-1 byte 0xB2 (pyuff
    # gives U+FFFD): read as accelerance in SI.  Set as the driving point (node 2 on both
    # sides) it gives the model's two modes: frequencies within 0.05 %, damping within 10 %
    # (the general-structure tolerances of issue 12), shapes mass-normalised.
    path = _with_record6(FIXTURES / "h1_unlabelled_frf.uff", tmp_path, [(2, 3, 2)])
    frfs = read_frf_uff(path, geometry=FIXTURES / "artemis_like_geometry.uff")
    truth = make_fixtures.frfs()
    assert frfs.frf_type == "accelerance"
    assert frfs.frequency[1] == 1000.0 / 512  # 1.95312e+00 in the header
    h = truth.values[truth.nodes.index(2)]
    np.testing.assert_allclose(frfs.values[0], h, rtol=E13_5_RTOL, atol=1e-6 * np.abs(h).max())
    model = identify(frfs).model
    np.testing.assert_allclose(model.frequency, make_fixtures.MODES_HZ, rtol=5e-4)
    np.testing.assert_allclose(model.damping_ratio, make_fixtures.ZETA, rtol=0.10)
    assert model.scaling == "mass"


def test_a_driving_point_without_coordinates_is_named_once(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # The driving point's node is both the point and the reference: it was listed twice
    # ("nodes 2, 2 have no coordinates").
    path = _with_record6(FIXTURES / "h1_unlabelled_frf.uff", tmp_path, [(2, 3, 2)])
    _one_line_error(
        lambda: read_frfs(path), "node 2 has no coordinates", "`geometry`"
    )  # where a step needs them: the parameter (the CLI says --geometry)
    # identify takes the lone driving point without coordinates (issue 12 item 6) and says so
    assert main(["identify", str(path), "--out", str(tmp_path / "out")]) == 0
    assert "a file of coordinates as --geometry" in " ".join(capsys.readouterr().out.split())


def test_spectra_and_psds_are_refused_naming_what_to_export(tmp_path: Path) -> None:
    # A power spectral density (function type 9, as ARTeMIS exports for output-only data):
    # no force, no phase; the line says which function types racketdyn reads.
    path = _with_record6(FIXTURES / "h1_unlabelled_frf.uff", tmp_path, [(2, 3, 2)])
    path.write_bytes(path.read_bytes().replace(b"\n    4         0", b"\n    9         0", 1))
    _one_line_error(
        lambda: read_frf_uff(path), "function type 9", "function type 4", "PSDs (2, 3, 9, 12)"
    )


# ---- LMS Test.Lab: a coordinate system per node ---------------------------------------------


def test_testlab_directions_in_each_nodes_own_system_are_made_global() -> None:
    # Every record says +3, but in its nodes' own systems (data sets 18, 15 field 3): at the
    # sensor's node 2 the system is turned over, +3 is global −Z.  Read in global axes the
    # FRFs are the model's, transfer points too; read as written (+3 everywhere) the
    # transfer FRFs would come out negated while the driving point looks right.
    frfs = read_frf_uff(FIXTURES / "testlab_like_local_systems.uff")
    truth = make_fixtures.frfs()
    assert frfs.nodes == truth.nodes
    np.testing.assert_allclose(frfs.values, truth.values, rtol=1e-11, atol=1e-15)
    assert "negated" not in frfs.metadata
    np.testing.assert_allclose(frfs.locations, make_fixtures.LOCATIONS, atol=1e-12)


def _edited(tmp_path: Path, old: str, new: str) -> Path:
    text = (FIXTURES / "testlab_like_local_systems.uff").read_text()
    assert text.count(old) == 1
    path = tmp_path / "edited.uff"
    path.write_text(text.replace(old, new))
    return path


def test_a_direction_oblique_to_the_global_axes_is_refused(tmp_path: Path) -> None:
    # Node 3's system turned 45° about z: its +1 would be half X, half Y.  Its +3 is still
    # global Z, so the records (all +3) read; a record in +1 at node 3 is refused.
    c, s = np.cos(np.pi / 4), np.sin(np.pi / 4)
    x_point = "".join(f"{v:13.5e}" for v in (0.55, 0.04, 0.0, 0.55 + c, 0.04 + s, 0.0))
    xz_point = "".join(f"{v:13.5e}" for v in (0.55 + c, 0.04 + s, 1.0))
    old_x = "".join(f"{v:13.5e}" for v in (0.55, 0.04, 0.0, 0.55, 1.04, 0.0))
    path = _edited(tmp_path, old_x, x_point)
    path.write_text(path.read_text().replace(f"{0.55:13.5e}{1.04:13.5e}{1.0:13.5e}", xz_point))
    assert read_frf_uff(path).nodes == (1, 2, 3)
    text = path.read_text().split("\n")
    at = next(i for i, line in enumerate(text) if "hammer node 3" in line) + 2  # record 6
    text[at] = text[at][:76] + f"{1:4d}"
    path.write_text("\n".join(text))
    _one_line_error(lambda: read_frf_uff(path), "node 3", "obliquely", "global directions")


def test_coordinates_given_in_a_nodes_system_are_taken_to_the_global_one(tmp_path: Path) -> None:
    # Node 3 defined in its own system (15, field 2 = 3), 10 mm along that system's x, which
    # is global +Y: at (0.55, 0.05) globally.
    old = f"{3:10d}{0:10d}{3:10d}{8:10d}" + "".join(f"{v:13.5e}" for v in (0.55, 0.04, 0.0))
    new = f"{3:10d}{3:10d}{3:10d}{8:10d}" + "".join(f"{v:13.5e}" for v in (0.01, 0.0, 0.0))
    frfs = read_frf_uff(_edited(tmp_path, old, new))
    np.testing.assert_allclose(frfs.locations[2], [0.55, 0.05], atol=1e-12)


def test_a_system_defined_in_another_is_refused_only_where_a_node_uses_it(tmp_path: Path) -> None:
    # System 3 given in system 1's frame (18, field 3 = 1): node 3 measures in it, refused
    # naming the node; the same system used by no node is left alone.
    old, new = f"{3:10d}{0:10d}{0:10d}{8:10d}{1:10d}", f"{3:10d}{0:10d}{1:10d}{8:10d}{1:10d}"
    path = _edited(tmp_path, old, new)
    _one_line_error(lambda: read_frf_uff(path), "node 3", "defined in another system")
    unused = f"{3:10d}{0:10d}{0:10d}{8:10d}"
    path.write_text(path.read_text().replace(f"{3:10d}{0:10d}{3:10d}{8:10d}", unused))
    assert read_frf_uff(path).nodes == (1, 2, 3)


def test_identify_with_some_coordinates_missing_names_geometry() -> None:
    # FRFs read without coordinates (NaN locations) gave "modal model locations must be
    # finite numbers" from deep inside; the line now names the nodes and --geometry.  FRFs
    # with no coordinates at all are identified without them (test_no_coordinates.py).
    frfs = read_frf_uff(FIXTURES / "testlab_like_frf.uff")
    locations = frfs.locations.copy()
    locations[0] = np.nan
    some = dataclasses.replace(frfs, locations=locations)
    _one_line_error(lambda: identify(some), "which node 1 lacks", "`geometry`")
    no_points = dataclasses.replace(
        frfs, locations=np.full_like(frfs.locations, np.nan), reference_location=(np.nan,) * 2
    )
    assert not identify(no_points).model.has_locations
