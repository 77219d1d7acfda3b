"""The report's section of a ``calibrate`` run (issue 15): fitted values with standard errors in
the page's units, a parameter the rows cannot identify shown without a number and with why,
the correlations, and the fit, held-out and leave-one-out errors as calibration.json has them."""

from __future__ import annotations

import json
import re
from html import unescape
from pathlib import Path

import pytest

from costly import costly
from racketdyn.cli import main
from racketdyn.report import SECTIONS, write_report

# a ball-cannon test of the built-in racket (made up): on and off the axis, free
MEASURED = (
    "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio,rebound_ratio_sd\n"
    "0.50,0,20,0,free,0.385,0.01\n0.58,0,20,0,free,0.16,0.01\n0.50,0.05,20,0,free,0.29,0.01\n"
    "0.45,-0.04,20,0,free,0.36,0.01\n0.55,0.04,20,0,free,0.25,0.01\n0.42,0,20,0,free,0.42,0.01\n"
)


@pytest.fixture(scope="module")
@costly
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A calibrate run by the approximate method on a rigid racket (fast: no beam model to
    rebuild per roll inertia): e_BG and the roll inertia identifiable, the frame damping not
    (a rigid racket has no modes to damp)."""
    d = tmp_path_factory.mktemp("calibration")
    (d / "measured.csv").write_text(MEASURED, encoding="utf-8")
    argv = ["calibrate", str(d / "measured.csv"), "--model", "approx", "--rigid", "--holdout", "6"]
    argv += ["--fit", "e_bg,roll_inertia_kgm2,frame_damping_scale", "--out", str(d / "cal")]
    assert main(argv) == 0
    return d


@pytest.fixture(scope="module")
def section(folder: Path) -> str:
    page = write_report(folder).read_text(encoding="utf-8")
    start = page.index('<section id="calibration">')
    html = page[start : page.index("</section>", start)]
    return html


def _rows(html: str, table: int) -> list[list[str]]:
    """The body rows of the section's ``table``-th table (0: parameters, 1: correlation, 2:
    errors), each a list of cell texts."""
    part = html.split("<table")[table + 1].split("</table>")[0]
    cell = r"<td[^>]*>(.*?)</td>"
    return [
        [unescape(re.sub(r"<[^>]+>", "", c)).strip() for c in re.findall(cell, row)]
        for row in re.findall(r"<tr>(.*?)</tr>", part, re.S)
        if "<td" in row
    ]


def test_the_section_is_listed() -> None:
    assert "calibration" in SECTIONS
    assert list(SECTIONS).index("calibration") == list(SECTIONS).index("validation") + 1


@pytest.mark.slow
def test_identified_values_with_their_errors_in_the_page_units(folder: Path, section: str) -> None:
    data = json.loads((folder / "cal" / "calibration.json").read_text(encoding="utf-8"))
    by_name = {p["name"]: p for p in data["parameters"]}
    rows = {r[0]: r for r in _rows(section, 0)}
    e_bg, roll = by_name["e_bg"], by_name["roll_inertia_kgm2"]
    assert e_bg["identifiable"]
    assert roll["identifiable"]
    assert rows["e_BG"][4] == f"{e_bg['value']:.4g} ± {e_bg['standard_error']:.4g}"
    # the roll inertia as the field quotes it (twistweight, kg·cm²)
    assert rows["roll inertia"][1] == "kg·cm²"
    assert rows["roll inertia"][4] == (
        f"{roll['value'] * 1e4:.4g} ± {roll['standard_error'] * 1e4:.4g}"
    )
    assert rows["roll inertia"][5] == f"{100 * roll['standard_error'] / roll['value']:.1f} %"


def test_a_parameter_the_rows_cannot_identify_has_no_number(folder: Path, section: str) -> None:
    data = json.loads((folder / "cal" / "calibration.json").read_text(encoding="utf-8"))
    damping = next(p for p in data["parameters"] if p["name"] == "frame_damping_scale")
    assert not damping["identifiable"]
    row = next(r for r in _rows(section, 0) if r[0] == "frame damping scale")
    assert row[4] == "not identifiable"
    assert "±" not in " ".join(row)
    assert f"{damping['best_fit_value']:.4g}" not in row[4:6]
    assert row[6] == damping["status"].removeprefix("not identifiable: ")
    # nor does it enter the correlation table
    assert all("frame damping scale" not in row for row in _rows(section, 1))


def test_the_errors_are_calibration_json_s(folder: Path, section: str) -> None:
    data = json.loads((folder / "cal" / "calibration.json").read_text(encoding="utf-8"))
    rows = {r[0]: r for r in _rows(section, 2)}
    assert rows["fit (rows fitted)"][1:] == [f"{data['fit_rms']:.4f}", "5"]
    assert rows["held out"][1:] == [f"{data['holdout_rms']:.4f}", "1"]
    assert rows["leave-one-out"][1] == f"{data['leave_one_out_rms']:.4f}"
    assert "weighted by its measured standard deviation" in section
    # the correlation of the two identified estimates, symmetric with ones on the diagonal
    matrix = data["correlation"]
    assert [r[1:] for r in _rows(section, 1)] == [
        ["+1.00", f"{matrix[0][1]:+.2f}"],
        [f"{matrix[1][0]:+.2f}", "+1.00"],
    ]


def test_not_run_without_a_calibration(tmp_path: Path) -> None:
    from racketdyn.report.folder import RunFolder
    from racketdyn.report.sections import calibration

    argv = ["predict", "--grid", "3", "--speed", "20", "--no-figures", "--out", str(tmp_path)]
    assert main(argv) == 0
    assert calibration.gather(RunFolder.scan(tmp_path)) is None
