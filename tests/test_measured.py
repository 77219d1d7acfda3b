"""Measured rebound files (issue 15): the layout, the ratio of a moving racket, unit slips."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from racketdyn.errors import InputError
from racketdyn.io import read_measured
from racketdyn.io.measured import outgoing_to_ratio

HEADER = "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio,rebound_ratio_sd"


def write(tmp_path: Path, *lines: str, header: str = HEADER) -> Path:
    path = tmp_path / "measured.csv"
    path.write_text("\n".join(["# a ball-cannon test", header, *lines]) + "\n", encoding="utf-8")
    return path


def test_a_file_reads_with_its_lines_labels_and_sd(tmp_path: Path) -> None:
    path = write(
        tmp_path,
        "0.50,0.0,20,0,free,0.39,0.01",
        "0.55,0.03,25,0,pinned,0.30,0.02",
        "0.45,-0.02,20,3,hand,0.35,0.01",
    )
    rows = read_measured(path)
    assert len(rows) == 3
    assert rows.support == ("free", "pinned", "hand")
    assert rows.lines == (3, 4, 5)
    assert rows.labels == ("1", "2", "3")
    np.testing.assert_allclose(rows.locations[1], [0.55, 0.03])
    assert rows.rebound_ratio_sd is not None
    np.testing.assert_allclose(rows.rebound_ratio_sd, [0.01, 0.02, 0.01])
    sub = rows.subset([2, 0])
    assert sub.support == ("hand", "free")
    assert sub.lines == (5, 3)


def test_outgoing_speed_of_a_moving_racket_is_the_glossary_ratio(tmp_path: Path) -> None:
    """v_out = e v_ball + (1 + e) v_racket (glossary rebound_speed) read back as e."""
    e, v_b, v_r = 0.42, 20.0, 5.0
    v_out = e * v_b + (1 + e) * v_r
    path = write(
        tmp_path,
        f"0.5,0,{v_b},{v_r},free,{v_out},0.1",
        header="x_m,y_m,ball_speed_mps,racket_speed_mps,support,outgoing_speed_mps,"
        "outgoing_speed_sd_mps",
    )
    rows = read_measured(path)
    assert rows.given == "outgoing_speed_mps"
    np.testing.assert_allclose(rows.rebound_ratio, [e], rtol=1e-12)
    np.testing.assert_allclose(rows.outgoing_speed, [v_out], rtol=1e-12)
    assert rows.rebound_ratio_sd is not None
    np.testing.assert_allclose(rows.rebound_ratio_sd, [0.1 / (v_b + v_r)])
    # a racket at rest: the ratio of the speeds, the literature's "apparent COR"
    assert outgoing_to_ratio(8.0, 20.0, 0.0) == pytest.approx(0.4)


@pytest.mark.parametrize(
    ("line", "words"),
    [
        ("500,0,20,0,free,0.4,0.01", "did you give millimetres"),
        ("0.5,30,20,0,free,0.4,0.01", "did you give millimetres"),
        ("0.5,0,90,0,free,0.4,0.01", "km/h"),  # 90 km/h = 25 m/s given as m/s
        ("0.5,0,20,0,free,40,0.01", "did you give percent"),
        ("0.5,0,20,0,free,1.4,0.01", "outside -0.2 to 1"),
        ("0.5,0,20,0,clamped,0.4,0.01", "pinned (handle clamped on a pivot)"),
        ("0.5,0,20,0,free,0.4,0", "must be above 0"),
        ("0.5,0,20,0,free,0.4,2", "did you give percent"),
        ("0.5,0,0,0,free,0.4,0.01", "must be above 0"),
        ("0.5,0,20,-1,free,0.4,0.01", "0 or above"),
        ("0.5,0,20,0,free,,0.01", "is not a number"),
    ],
)
def test_bad_rows_are_one_line_naming_the_line_and_column(
    tmp_path: Path, line: str, words: str
) -> None:
    path = write(tmp_path, "0.5,0,20,0,free,0.4,0.01", line)
    with pytest.raises(InputError) as error:
        read_measured(path)
    message = str(error.value)
    assert "\n" not in message
    assert words in message
    assert "line 4" in message


def test_outgoing_speed_in_km_per_h_is_named(tmp_path: Path) -> None:
    path = write(
        tmp_path, "0.5,0,20,0,free,28.8", header="x_m,y_m,ball_speed_mps,racket_speed_mps,"
        "support,outgoing_speed_mps"
    )  # fmt: skip
    with pytest.raises(InputError, match="did you give km/h"):
        read_measured(path)


@pytest.mark.parametrize(
    ("header", "words"),
    [
        ("x_m,y_m,ball_speed_mps,racket_speed_mps,support", "neither found"),
        (
            "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio,outgoing_speed_mps",
            "both found",
        ),
        ("x_m,y_m,ball_speed_mps,support,rebound_ratio", "missing column racket_speed_mps"),
        (
            "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio,outgoing_speed_sd_mps",
            "with rebound_ratio give rebound_ratio_sd",
        ),
    ],
)
def test_bad_headers(tmp_path: Path, header: str, words: str) -> None:
    n = header.count(",") + 1
    path = write(tmp_path, ",".join(["0.5", "0", "20", "0", "free", "0.4", "8"][:n]), header=header)
    with pytest.raises(InputError) as error:
        read_measured(path)
    assert words in str(error.value)


def test_no_rows_and_no_file(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="no measured rows"):
        read_measured(write(tmp_path))
    with pytest.raises(InputError, match="no such file"):
        read_measured(tmp_path / "nothing.csv")
    (tmp_path / "folder.csv").mkdir()
    with pytest.raises(InputError, match=r"folder\.csv: is a folder; give a CSV file$"):
        read_measured(tmp_path / "folder.csv")


def test_a_fast_measured_ball_goes_on_with_allow_implausible(tmp_path: Path) -> None:
    """80 m/s is beyond the speeds of play (75 m/s) but a real cannon can fire it."""
    path = write(tmp_path, "0.5,0,80,0,free,0.4,0.01")
    with pytest.raises(InputError, match="allow_implausible"):
        read_measured(path)
    assert read_measured(path, allow_implausible=True).ball_speed[0] == 80.0
