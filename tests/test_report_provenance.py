"""The report's words: the provenance section is a readable table, and the page names the racket
as a user knows it — no JSON escapes, no float noise, no internal function names (issue 13)."""

from __future__ import annotations

import dataclasses
import html
import json
import re
from pathlib import Path

import pytest

import racketdyn as rd
from racketdyn.cli import main
from racketdyn.errors import InputError
from racketdyn.report import write_report

NOISY = 0.1 + 0.2  # 0.30000000000000004
UNICODE = "grid 3 × 3 over the head … (Ω, ζ)"


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A prediction whose run.json holds a float with noise, in a list and in a nested table,
    and text beyond ASCII."""
    d = tmp_path_factory.mktemp("run")
    argv = ["predict", "--grid", "3", "--speed", "20", "--no-figures", "--out", f"{d}/predict"]
    assert main(argv) == 0
    path = d / "predict" / "run.json"
    record = json.loads(path.read_text(encoding="utf-8"))
    record["racket_speed_mps"] = [NOISY]
    record["ball"]["e_bg"] = NOISY
    record["points"] = UNICODE
    record["ball"] = {"source": UNICODE, **record["ball"]}  # was JSON with \u2026 escapes
    path.write_text(json.dumps(record, indent=2), encoding="utf-8")
    return d


def _section(page: str, key: str) -> str:
    start = page.index(f'<section id="{key}">')
    return page[start : page.index("</section>", start)]


def _rows(section: str) -> dict[str, tuple[str, ...]]:
    """The provenance inputs by label: (value, unit)."""
    rows = {}
    for cells in re.findall(r"<tr>(.*?)</tr>", section, re.S):
        texts = [
            html.unescape(re.sub(r"<[^>]+>", "", c)) for c in re.findall(r"<td.*?</td>", cells)
        ]
        if len(texts) == 3:
            rows[texts[0]] = (texts[1], texts[2])
    return rows


@pytest.fixture(scope="module")
def page(folder: Path) -> str:
    return write_report(folder).read_text(encoding="utf-8")


def test_the_page_has_no_json_escapes_nor_internal_names(page: str) -> None:
    assert not re.search(r"\\u[0-9a-fA-F]{4}", page)
    assert "write_report" not in page
    assert UNICODE in html.unescape(page)


def test_provenance_inputs_are_a_table_of_rounded_values_with_units(page: str) -> None:
    section = _section(page, "provenance")
    assert "0.30000000000000004" not in page
    assert "{" not in html.unescape(re.sub(r"<[^>]+>", "", section))  # no raw JSON left
    rows = _rows(section)
    assert rows["racket speed"] == ("0.3", "m/s")  # a list, unit from the key suffix
    assert rows["speeds"] == ("20", "m/s")
    assert rows["ball: e_BG"] == ("0.3", "")  # a nested table flattened to "table: key"
    assert rows["ball: mass"] == ("57.7", "g")  # the page's unit (run.json holds 0.0577 kg)
    assert rows["supports"] == ("free, pinned", "")
    assert rows["points"] == (UNICODE, "")
    assert rows["ball: source"] == (UNICODE, "")
    coefficients = rows["ball: restoring force: coefficients"][0].split(", ")
    assert len(coefficients) >= 2
    # significant digits: zeros leading or trailing a whole number are not (-469400 is 4)
    digits = [c.lstrip("-").replace(".", "").split("e")[0].strip("0") for c in coefficients]
    assert all(len(d) <= 5 for d in digits)


def test_the_racket_is_named_in_words(folder: Path, tmp_path: Path) -> None:
    racket = rd.default_racket()
    recorded = _section(write_report(folder).read_text(encoding="utf-8"), "racket")
    assert "the built-in racket, as recorded in predict/run.json" in recorded
    given = _section(write_report(folder, racket).read_text(encoding="utf-8"), "racket")
    assert "the built-in racket" in given
    assert "write_report" not in given
    # the same frame under another name is the racket the runs used: named as given
    renamed = dataclasses.replace(racket, name="Test frame, a copy")
    mine = _section(write_report(folder, renamed).read_text(encoding="utf-8"), "racket")
    assert "the racket given with --racket" in mine
    # another frame is refused (the trial of 2026-11-27: the page described it over runs
    # computed on the built-in racket)
    other = dataclasses.replace(racket, name="Test frame 300 g", mass_kg=0.300)
    with pytest.raises(InputError, match="computed on Kawazoe test racket"):
        write_report(folder, other)
