"""The default band and its edges (issue 12, item 8).

FRFs another system exported end at its analyser bandwidth: their last line is the band's top
(not fs/2.56 of a record racketdyn never saw).  A band typed to the round number the file's
six-digit header rounds (999.997 Hz) is the file's band.  A clear mode in the band's edge
margin, where the fit puts its computational poles, is not dropped silently: one line names
it and the option that keeps it.  The oracle is the analytic free bar
(:mod:`racketdyn.testing.free_beam`: modes at 65.4, 180.3, 353.5, 584.4 and 873.0 Hz).
"""

from __future__ import annotations

import csv
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from lab_uff import write_lab_uff
from racketdyn.errors import InputError
from racketdyn.io.frf_layout import read_frfs
from racketdyn.modal.identify import default_band, identify
from racketdyn.testing.free_beam import beam_frfs

POINTS = np.linspace(0.0, 0.8, 9)
FIFTH_HZ = 873.0353  # the bar's fifth mode (racketdyn.testing.free_beam)


def _export(tmp_path: Path, top_hz: float, lines: int, name: str = "export.uff") -> Path:
    """A roving-hammer export by 'another system': no racketdyn ID lines, last line = top."""
    test = beam_frfs(POINTS, 0.0, top_hz=top_hz, lines=lines)
    nodes = {
        n: (float(p[0]), float(p[1]), float(p[2]))
        for n, p in zip(test.frfs.nodes, test.frfs.locations, strict=True)
    }
    records = [(1, 3, n, 3, v) for n, v in zip(test.frfs.nodes, test.frfs.values, strict=True)]
    return write_lab_uff(tmp_path / name, nodes, test.frfs.frequency, records)


def test_frfs_exported_to_1000_hz_are_not_cut_at_781_hz(tmp_path: Path) -> None:
    # fs = 2560 Hz, 2048-point records: 1.25 Hz lines, exported to the 1000 Hz bandwidth
    # (801 lines).  An fs/2 assumption put the top at 2 × 1000 / 2.56 = 781 Hz and lost the
    # 873 Hz mode.
    frfs = read_frfs(_export(tmp_path, 1000.0, 801))
    assert frfs.bandwidth_hz == 1000.0
    assert default_band(frfs) == (40.0, 1000.0)
    found = identify(frfs)
    assert found.band_hz[1] == 1000.0
    assert np.min(np.abs(found.model.frequency - FIFTH_HZ)) < 5e-4 * FIFTH_HZ


def test_racketdyns_own_estimates_keep_fs_over_2_56_through_the_reader(tmp_path: Path) -> None:
    from racketdyn.io.uff import write_frf_uff

    test = beam_frfs(POINTS, 0.0, top_hz=1280.0, lines=1025)
    estimated = replace(
        test.frfs,
        locations=test.frfs.locations[:, :2],
        reference_location=test.frfs.reference_location[:2],
        metadata={"bandwidth_hz": 1000.0},  # fs/2.56 of a 2560 Hz record: lines to 1280 Hz
    )
    back = read_frfs(write_frf_uff(estimated, tmp_path / "frfs.uff"))
    assert back.bandwidth_hz == pytest.approx(1000.0, rel=1e-6)
    assert default_band(back)[1] == pytest.approx(1000.0, rel=1e-6)


def test_a_band_to_1000_hz_is_the_file_whose_header_reads_999_997(tmp_path: Path) -> None:
    # a six-digit header step 1.95312 Hz: the 513th line reads 999.997 Hz
    frfs = read_frfs(_export(tmp_path, 512 * 1.953119, 513))
    assert frfs.frequency[-1] == pytest.approx(999.997, abs=5e-4)
    found = identify(frfs, (65.0, 1000.0))
    assert found.band_hz == (65.0, float(frfs.frequency[-1]))
    # a top a whole line beyond the last is still refused, naming the FRFs' end
    with pytest.raises(InputError, match=r"999\.99.* Hz"):
        identify(frfs, (65.0, 1005.0))


@pytest.mark.slow
def test_the_command_line_takes_band_65_1000(tmp_path: Path) -> None:
    from racketdyn.cli import main

    path = _export(tmp_path, 512 * 1.953119, 513)
    assert main(["identify", str(path), "--band", "65,1000", "--out", str(tmp_path / "o")]) == 0


def _edge_case(tmp_path: Path) -> Path:
    # the FRFs end at 880 Hz, 7 Hz above the 873 Hz mode: in the band's 2 % edge margin
    return _export(tmp_path, 880.0, 705)


def test_a_clear_mode_at_the_band_edge_is_named_with_the_option_that_keeps_it(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    frfs = read_frfs(_edge_case(tmp_path))
    found = identify(frfs)
    assert np.all(np.abs(found.model.frequency - FIFTH_HZ) > 5.0)  # left out ...
    edge = [d for d in found.dropped_modes if d.stage == "edge"]
    assert len(edge) == 1  # ... as one row, not the split clusters of one peak
    assert abs(edge[0].frequency_hz - FIFTH_HZ) < 5.0
    assert "`band_hz`" not in edge[0].reason  # the FRFs end at 880 Hz: no band keeps it ...
    assert "880 Hz" in edge[0].reason
    pin = float(edge[0].reason.split("`pin_hz` ")[1].split()[0])  # ... the pin it names does
    warned = [r.getMessage() for r in caplog.records if "`pin_hz`" in r.getMessage()]
    assert len(warned) == 1
    assert "\n" not in warned[0]
    kept = identify(frfs, pin_hz=[pin])
    assert np.min(np.abs(kept.model.frequency - FIFTH_HZ)) < 1e-3 * FIFTH_HZ


def test_a_band_set_below_a_clear_mode_names_the_wider_band(tmp_path: Path) -> None:
    frfs = read_frfs(_export(tmp_path, 1000.0, 801))
    found = identify(frfs, (40.0, 880.0))
    edge = [d for d in found.dropped_modes if d.stage == "edge"]
    assert len(edge) == 1
    band = edge[0].reason.split("`band_hz` ")[1].split()[0].rstrip(";,.")
    low, high = (float(v) for v in band.split(","))
    assert low == 40.0
    assert 880.0 < high <= 1000.0
    wider = identify(frfs, (low, high))  # the band it names keeps the mode
    assert np.min(np.abs(wider.model.frequency - FIFTH_HZ)) < 5e-4 * FIFTH_HZ


@pytest.mark.slow
def test_the_edge_row_reaches_dropped_modes_csv_and_the_console(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from racketdyn.cli import main

    out = tmp_path / "o"
    assert main(["identify", str(_edge_case(tmp_path)), "--out", str(out)]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    assert "--pin 873." in printed
    # why the band is what it is, said under the table (its bottom and its top)
    assert "band 40–" in printed
    assert "the FRFs' bandwidth (their last line)" in printed
    with (out / "dropped_modes.csv").open() as handle:
        rows = [r for r in csv.DictReader(handle) if r["stage"] == "edge"]
    assert len(rows) == 1
    assert "`pin_hz`" in rows[0]["reason"]  # the library's words in its file


def test_noise_at_the_edges_is_not_called_a_mode(tmp_path: Path) -> None:
    # the full 1000 Hz band holds no mode near its edges: no edge row
    found = identify(read_frfs(_export(tmp_path, 1000.0, 801)))
    assert not [d for d in found.dropped_modes if d.stage == "edge"]


def test_no_band_beyond_the_analyser_bandwidth_is_suggested() -> None:
    # racketdyn's own estimates run to fs/2, the lines above fs/2.56 being the anti-alias
    # filter's roll-off: a clear mode at that edge is kept with --pin, not a band above it
    test = beam_frfs(POINTS, 0.0, top_hz=1126.4, lines=902)
    frfs = replace(test.frfs, metadata={"bandwidth_hz": 880.0})  # fs = 2252.8 Hz
    edge = [d for d in identify(frfs).dropped_modes if d.stage == "edge"]
    assert len(edge) == 1
    assert "`band_hz`" not in edge[0].reason
    assert "`pin_hz` 87" in edge[0].reason
