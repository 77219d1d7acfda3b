"""The HTML report: built from a small run of every pipeline command, checked as a file and in
a real browser (headless Chromium), which must load it offline without a script error."""

from __future__ import annotations

import base64
import csv
import io
import json
import math
import re
import shutil
from html import unescape
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
from markupsafe import escape
from PIL import Image

import racketdyn as rd
from browser import browse, find_chromium
from racketdyn.cli import main
from racketdyn.errors import InputError
from racketdyn.report import REPORT_NAME, SECTIONS, write_report
from racketdyn.report.figures import caption_of

pytestmark = pytest.mark.slow

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
# the paper's figures the captions must name, and the marker of figures it does not have
PAPER_LEADS = (
    "Kawazoe Fig. 2.",
    "Kawazoe Fig. 3.",
    "Kawazoe Figs 2–3.",
    "Kawazoe Fig. 4.",
    "Kawazoe Fig. 5.",
    "Kawazoe Fig. 6.",
    "Kawazoe Fig. 7.",
    "Kawazoe Figs 11 and 12.",
    "Kawazoe Fig. 14.",
    "Kawazoe Fig. 15.",
    "No figure in the paper.",
)


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """What ``racketdyn demo`` writes, with small settings: rig, FRFs, contact, compare, predict
    (both impact models, as the demo does), swing, twist and oblique impacts, the ball on the
    strings; and a validation and a calibration against measured rebounds, which the demo does
    not run.

    The rig double-hits and overloads now and then, so the quality table has reasons to show.
    """
    d = tmp_path_factory.mktemp("demo")
    rig = ["--averages", "3", "--double-hits", "0.05", "--overloads", "0.05"]
    rig += ["--response-snr", "50", "--force-snr", "60"]  # the demo's mild noise
    frf = ["--exp-window", "0.1", "--force-window", "0.01", "--force-range", "200"]
    tests = [f"{d}/rig/hammer_free.uff", f"{d}/rig/hammer_hand.uff"]
    frfs = [f"{d}/frf_free/frfs.uff", f"{d}/frf_hand/frfs.uff"]
    measured = d / "measured.csv"  # a ball-cannon test of the built-in racket (made up)
    measured.write_text(
        "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio\n"
        "0.50,0,20,0,free,0.39\n0.58,0,20,0,free,0.17\n0.50,0.05,20,0,pinned,0.30\n",
        encoding="utf-8",
    )
    commands = [
        ["rig", "--support", "free,hand", *rig, "--out", f"{d}/rig"],
        ["frf", f"{d}/rig/hammer_free.uff", *frf, "--out", f"{d}/frf_free"],
        ["frf", f"{d}/rig/hammer_hand.uff", *frf, "--out", f"{d}/frf_hand"],
        ["contact", *tests, "--labels", "free,hand", "--out", f"{d}/contact"],
        ["compare", *frfs, "--band", "40,850", "--out", f"{d}/compare"],
        [
            "predict",
            "--grid",
            "5",
            "--speed",
            "10,20,30",
            "--model",
            "both",
            "--out",
            f"{d}/predict",
        ],
        ["swing", "--grid", "5", "--out", f"{d}/swing"],
        ["twist", "--support", "free,hand", "--offsets=-0.05,0,0.05", "--out", f"{d}/twist"],
        ["oblique", "--angles", "0,30", "--out", f"{d}/oblique"],
        ["compound", "--out", f"{d}/compound"],
        ["validate", str(measured), "--out", f"{d}/validate"],
        [
            "calibrate", str(measured), "--model", "approx", "--fit", "e_bg,frame_damping_scale",
            "--no-loo", "--out", f"{d}/calibrate",
        ],
    ]  # fmt: skip
    for argv in commands:
        assert main(argv) == 0, argv
    return d


@pytest.fixture(scope="module")
def report(run_dir: Path) -> Path:
    return write_report(run_dir)


@pytest.fixture(scope="module")
def page(report: Path) -> str:
    return report.read_text(encoding="utf-8")


class _Tags(HTMLParser):
    """Every start tag with its attributes."""

    def __init__(self) -> None:
        super().__init__()
        self.tags: list[tuple[str, dict[str, str]]] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags.append((tag, {k: v or "" for k, v in attrs}))


def _tags(text: str) -> list[tuple[str, dict[str, str]]]:
    parser = _Tags()
    parser.feed(text)
    return parser.tags


def test_report_is_written_in_the_run_folder(run_dir: Path, report: Path) -> None:
    assert report == run_dir / REPORT_NAME
    assert 100_000 < report.stat().st_size <= 6_000_000  # the page budget of issue 11


def test_nothing_is_loaded_from_outside_the_file(page: str) -> None:
    tags = _tags(page)
    for tag, attrs in tags:
        for name in ("src", "href", "srcset", "poster", "data", "action"):
            value = attrs.get(name, "").strip()
            assert not re.match(r"(https?:)?//", value, re.I), (tag, name, value[:80])
        if "href" in attrs:
            assert attrs["href"].startswith("#"), attrs["href"]  # in-page links only
        if tag == "script":
            assert "src" not in attrs
    assert not any(tag in ("link", "iframe", "object", "embed") for tag, _ in tags)
    assert "@import" not in page
    assert all(ref.startswith("#") for ref in re.findall(r"url\(\s*([^)]*)\)", page))
    assert page.count("<style>") == 1
    assert page.count('<script type="application/json"') == 1


def test_every_image_is_an_embedded_png(run_dir: Path, page: str) -> None:
    sources = [attrs["src"] for tag, attrs in _tags(page) if tag == "img"]
    # every PNG the commands wrote, but the single Fig. 6s the free/hand overlay replaces
    written = sorted(run_dir.rglob("*.png"))
    shown = [p for p in written if not re.fullmatch(r"fig6_nodes_(free|hand)\.png", p.name)]
    assert len(sources) == len(shown) == len(written) - 2
    for path in shown:
        assert path.relative_to(run_dir).as_posix() in page
    for src in sources:
        assert src.startswith("data:image/png;base64,")
        data = base64.b64decode(src.split(",", 1)[1], validate=True)
        assert data.startswith(PNG_SIGNATURE)
        with Image.open(io.BytesIO(data)) as image:
            assert image.width > 100
            assert image.height > 100


def test_every_png_is_a_registered_figure_shown_in_its_section(run_dir: Path, page: str) -> None:
    """Issue 23: every PNG a step wrote is in the registry of figures, and the page shows it in
    the section its entry names (the single Fig. 6s: replaced by the free/hand overlay)."""
    from racketdyn.plotting.registry import of_file

    sections = dict(re.findall(r'<section id="([\w-]+)">(.*?)</section>', page, re.S))
    for path in sorted(run_dir.rglob("*.png")):
        figure = of_file(path.name)
        assert figure is not None, f"{path.name}: not in the registry of figures"
        if re.fullmatch(r"fig6_nodes_(free|hand)\.png", path.name):
            continue
        assert figure.section is not None, f"{path.name}: {figure.not_in_report}"
        where = path.relative_to(run_dir).as_posix()
        assert where in sections[figure.section], f"{where} not in section {figure.section}"


def test_sections_in_order_and_captions_name_the_paper_figures(page: str) -> None:
    headings = re.findall(r"<h2>(?:<span[^>]*>\d+</span> )?(.*?)</h2>", page)
    expected = [s.title for s in SECTIONS.values()]
    assert [h for h in headings if h in expected] == expected
    assert "Not run" not in headings  # every section had its inputs
    captions = " ".join(re.findall(r"<figcaption>(.*?)</figcaption>", page, re.S))
    for caption in PAPER_LEADS:
        assert caption in captions
    assert page.count("<figure") == page.count("<figcaption>")
    for name in ("fig2_frf_frame.png", "fig7_contact_time.png", "fig15_identified.png"):
        assert name in captions


def test_tables_carry_the_results(run_dir: Path, page: str) -> None:
    # rejected averages by reason, free and hand, as quality.csv has them
    for support in ("free", "hand"):
        quality = (run_dir / f"frf_{support}" / "quality.csv").read_text()
        assert "double hit" in quality
        assert "force overload" in quality  # the rig's faults, seed 1
    rows = re.findall(r"<tr><td>rejected: ([^<]*)</td>((?:<td[^>]*>\d+</td>){2})</tr>", page)
    assert {reason for reason, _ in rows} >= {"double hit", "force overload"}
    assert all(int(n) > 0 for _, cells in rows for n in re.findall(r">(\d+)<", cells))
    assert "2-node bending" in page  # modes and the free/hand comparison
    assert "centre of percussion" in page
    assert "Sweet spots" in page
    run = json.loads((run_dir / "predict" / "run.json").read_text())
    assert f"{run['racket']['derived']['swingweight_kgcm2']:.4g}" in page
    for folder in (
        "rig",
        "frf_free",
        "frf_hand",
        "contact",
        "compare",
        "predict",
        "swing",
        "twist",
        "oblique",
    ):
        assert f"<h3>{folder}</h3>" in page  # provenance of every run
    assert re.search(r"[0-9a-f]{64}", page)  # file hashes


def test_interactive_data_are_embedded(page: str) -> None:
    block = re.search(
        r'<script type="application/json" id="report-data">(.*?)</script>', page, re.S
    )
    assert block is not None
    data = json.loads(block.group(1))
    (frf,) = data["frf"]
    assert len(frf["f"]) > 100
    assert [len(v["series"]) for v in frf["views"]] == [2, 2]  # free and hand
    assert all(len(s["mag"]) == len(frf["f"]) for v in frf["views"] for s in v["series"])
    maps = {m["id"]: m for m in data["maps"]}
    rebound = maps["map-rebound"]
    assert [g["label"] for g in rebound["groups"]] == ["10 m/s", "20 m/s", "30 m/s"]
    assert rebound["groups"][rebound["initial"]]["label"] == "20 m/s"
    assert [p["label"] for p in rebound["groups"][1]["panels"]] == ["free", "pinned"]
    assert [p["label"] for p in maps["map-contact"]["groups"][0]["panels"]] == ["free", "hand"]


def test_missing_sections_are_listed_as_not_run(run_dir: Path, tmp_path: Path) -> None:
    shutil.copytree(run_dir / "predict", tmp_path / "predict")
    path = write_report(tmp_path, racket=rd.default_racket())
    text = path.read_text(encoding="utf-8")
    not_run = text[text.index('<section id="not-run">') :]
    for key in ("quality", "stabilisation", "modes", "contact", "swing", "oblique"):
        assert SECTIONS[key].title in not_run
        assert f'<section id="{key}">' not in text
    for key in ("racket", "impact", "vibration", "rebound", "provenance"):
        assert f'<section id="{key}">' in text
        assert SECTIONS[key].title not in not_run
    assert rd.default_racket().name in text


def _section(page: str, key: str) -> str:
    start = page.index(f'<section id="{key}">')
    return page[start : page.index("</section>", start)]


def test_the_transient_section_shows_the_comparison(run_dir: Path, page: str) -> None:
    section = _section(page, "transient")
    assert SECTIONS["transient"].title in section
    captions = " ".join(re.findall(r"<figcaption>(.*?)</figcaption>", section, re.S))
    record = json.loads((run_dir / "predict" / "run.json").read_text())
    for key in ("transient_comparison_face", "transient_comparison_speed", "transient_histories"):
        _, what = caption_of(key, record)
        assert escape(what[0].upper() + what[1:]) in captions, key
        assert f"predict/{key}.png" in captions
    # one row per support and speed of comparison.csv, the largest |Δ| where comparison.csv has it
    body = section[section.index("<tbody>") : section.index("</tbody>")]
    rows = re.findall(r"<tr>(.*?)</tr>", body, re.S)
    assert len(rows) == 2 * 3
    with (run_dir / "predict" / "comparison.csv").open(encoding="utf-8") as handle:
        table = list(csv.DictReader(handle))
    free_20 = [r for r in table if r["support"] == "free" and float(r["ball_speed_mps"]) == 20]
    largest = float(np.nanmax([abs(float(r["difference_rebound_ratio"])) for r in free_20]))
    cells = re.findall(r"<td[^>]*>(.*?)</td>", rows[1])
    assert cells[:3] == ["free", "20", f"{largest:.3f}"]
    # at a glance, the case named by its ball speed, racket speed and support (issue 27)
    assert "approximate against transient, ball 20 m/s, racket at rest, free" in page


def test_the_transient_section_counts_the_rows_where_the_models_differ(
    run_dir: Path, tmp_path: Path
) -> None:
    """Issue 22: comparison.csv flags rows whose rebound ratios differ by more than 0.05
    (``models_differ``); the console counted them, the report did not.  Two rows of the free
    racket at 20 m/s are marked here: the table counts them on their row, at a glance says so."""
    shutil.copytree(run_dir / "predict", tmp_path / "predict")
    path = tmp_path / "predict" / "comparison.csv"
    with path.open(encoding="utf-8") as handle:
        table = list(csv.DictReader(handle))
    marked = [
        i
        for i, r in enumerate(table)
        if r["support"] == "free" and float(r["ball_speed_mps"]) == 20
    ][:2]
    for i, row in enumerate(table):
        row["models_differ"] = "True" if i in marked else "False"
    with path.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(table[0]))
        writer.writeheader()
        writer.writerows(table)
    text = write_report(tmp_path, racket=rd.default_racket()).read_text(encoding="utf-8")
    section = _section(text, "transient")
    assert "points where the models differ by &gt; 0.05 (models_differ)" in section
    body = section[section.index("<tbody>") : section.index("</tbody>")]
    counts = {
        tuple(cells[:2]): cells[-1]
        for cells in (
            re.findall(r"<td[^>]*>(.*?)</td>", r) for r in re.findall(r"<tr>(.*?)</tr>", body, re.S)
        )
    }
    assert counts[("free", "20")] == "2"
    assert sum(int(v) for v in counts.values()) == 2
    assert f"2 of {len(table)} rows of comparison.csv differ by more than 0.05" in text


def test_rows_filled_from_the_transient_are_not_called_nan(run_dir: Path, tmp_path: Path) -> None:
    """The demo's page said "Flagged rows (NaN in impact.csv …): 91 × from the transient model":
    those rows carry the transient model's numbers (``--model both``), not NaN.  They are
    counted apart, in words that say what they hold."""
    from racketdyn.impact.result import STATUS_FROM_TRANSIENT

    shutil.copytree(run_dir / "predict", tmp_path / "predict")
    path = tmp_path / "predict" / "impact.csv"
    with path.open(encoding="utf-8") as handle:
        table = list(csv.DictReader(handle))
    for row in table[:3]:
        row["status"] = STATUS_FROM_TRANSIENT
    with path.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(table[0]))
        writer.writeheader()
        writer.writerows(table)
    text = write_report(tmp_path, racket=rd.default_racket()).read_text(encoding="utf-8")
    section = _section(text, "vibration")
    flagged = re.search(r"Flagged rows \(NaN in impact\.csv[^<]*", section)
    assert flagged is None or STATUS_FROM_TRANSIENT not in flagged.group(0)
    filled = sum(r["status"] == STATUS_FROM_TRANSIENT for r in table)
    assert f"{filled} rows the approximate method cannot give carry the transient" in section


def test_the_swing_and_oblique_sections_show_their_runs(run_dir: Path, page: str) -> None:
    swing = _section(page, "swing")
    captions = " ".join(re.findall(r"<figcaption>(.*?)</figcaption>", swing, re.S))
    record = json.loads((run_dir / "swing" / "run.json").read_text())
    for key in ("swing_map", "swing_along_axis"):
        _, what = caption_of(key, record)
        assert escape(what[0].upper() + what[1:]) in captions, key
        assert f"swing/{key}.png" in captions
    # one row per sweet spot of sweet_spots.csv, at its x
    with (run_dir / "swing" / "sweet_spots.csv").open(encoding="utf-8") as handle:
        spots = list(csv.DictReader(handle))
    body = swing[swing.index("<tbody>") : swing.index("</tbody>")]
    rows = re.findall(r"<tr>(.*?)</tr>", body, re.S)
    assert len(rows) == len(spots)
    for row, spot in zip(rows, spots, strict=True):
        cells = re.findall(r"<td[^>]*>(.*?)</td>", row)
        assert cells[:2] == [escape(spot["name"]), f"{float(spot['x_m']) * 1e3:.0f}"]
    assert "section 4.2" in swing
    assert "ACMD 2002" in swing
    oblique = _section(page, "oblique")
    for key in ("twist", "oblique"):
        assert f"{key}/{key}.png" in oblique
    assert "Caveat" in oblique
    assert "swinging racket" in page[: page.index("<main>")]  # at a glance


def test_the_mode_table_still_reads_the_identification(page: str) -> None:
    """compare's comparison.csv (modes paired by MAC) is not predict's (the two models)."""
    section = _section(page, "modes")
    table = section[section.index("Free against hand-held") :]
    first = re.search(r"<tbody>\s*<tr>(.*?)</tr>", table, re.S)
    assert first is not None
    cells = re.findall(r"<td[^>]*>(.*?)</td>", first.group(1))
    assert cells[0] == "2-node bending"
    assert 110 < float(cells[1]) < 130  # free 2-node bending, Hz (the rig's 120 Hz)
    assert "Nodes of the first mode along the long axis" in section


def test_the_identified_models_say_where_their_fit_misses(page: str) -> None:
    """Each identification's verdict on its fit error (racketdyn.modal.misfit), from its
    modal_model*.json, under its mode table: the shares and what they say."""
    section = _section(page, "stabilisation")
    verdicts = re.findall(r"Where the fit misses: (median fit error [^<]*)\.</p>", section)
    assert len(verdicts) == 2  # free and hand-held
    for verdict in map(unescape, verdicts):
        assert "the data's noise leaves" in verdict
        assert "`" not in verdict


def test_the_whole_page_has_no_json_escapes_nor_internal_names(page: str) -> None:
    """Run data with Unicode (…, Ω, Xⁿ, m/(N·s²)) as it is, in the tables and the plots' data."""
    assert not re.search(r"\\u[0-9a-fA-F]{4}", page)
    assert "write_report" not in page
    assert "Xⁿ" in page  # the transient integrator's order, from predict/run.json
    assert "steps per contact 128" in _section(page, "transient")  # words, not run.json keys
    # the library's parameter names are the command's options on a page of command runs (the
    # misfit verdict and the truth table's reasons said `pin_hz`)
    words = _page_text(page)
    for name in ("pin_hz", "band_hz", "exclude_hz", "max_order"):
        assert name not in words, name


PERSON = "70 kg, 1.75 m adult"
"""The one place the page quotes kg and m: the body the default arm is scaled from (a person's
mass and height, as anthropometry quotes them; docs/develop.md, "Units on the page")."""

OTHER_SPELLINGS = {
    "an inertia not in kg·cm²": r"kg·m²|(?<!k)g·m²|g·cm²(?<!kg·cm²)",
    "a mass not in g": r"\d\s*kg\b(?!·)",
    "a length in m": r"\d\s*m\b(?![/²·_])",
    "a length in cm": r"\d\s*cm\b(?!²)",
    "a time in s": r"\d\s*s\b|\(s\)",
    "a unit the page does not use": r"\d\s*(?:kN(?!/m)|mJ|kHz|km/h|mph|μm|µm)\b",
    "an angle in rad": r"\d\s*rad\b(?!/)",
    "a column in SI where the page has its own unit": r"\((?:kg|m|kg·m²)\)",
    "a damping ratio not in %": r"damping(?: ratio)? \d+(?:\.\d+)?(?![\d.]|\s*(?:%|N))",
}
"""What the page must not show (issue 13: one unit per quantity, the field's)."""


def _page_text(page: str) -> str:
    """The words of the page: no scripts, styles, images' data or tags."""
    text = re.sub(r"<(script|style)\b.*?</\1>", " ", page, flags=re.S)
    text = re.sub(r"<[^>]+>", " ", text)
    return re.sub(r"\s+", " ", unescape(text))


def test_one_unit_per_quantity_and_one_term_for_the_rebound(page: str) -> None:
    """Issue 13: inertias were 13.1 g·m² and 131 kg·cm², lengths m and mm, damping a fraction
    and a percentage, the rebound a "ratio" and a "power coefficient"."""
    text = _page_text(page)
    assert PERSON in text
    scanned = text.replace(PERSON, "")
    for what, pattern in OTHER_SPELLINGS.items():
        found = [
            scanned[max(0, m.start() - 50) : m.end() + 10] for m in re.finditer(pattern, scanned)
        ]
        assert not found, f"{what}: {found[:3]}"
    for unit in ("kg·cm²", " g", " mm", " Hz", " %", " ms", " N", " m/s", " J"):
        assert unit in text, unit  # the page's units are there
    # one term, defined once
    assert len(re.findall(r"rebound power coefficient|apparent coefficient", text, re.I)) == 1
    definition = _section(page, "rebound")
    assert 'id="rebound-ratio"' in definition
    assert "rebound power coefficient" in _page_text(definition)
    assert text.count("rebound ratio") > 10


def test_first_mode_nodes_come_from_compare_run_json(run_dir: Path, page: str) -> None:
    """comparison.csv is pure data (issue 13); the nodes the page shows are run.json's."""
    nodes = json.loads((run_dir / "compare" / "run.json").read_text())["first_mode_nodes_m"]
    modes, rebound = _section(page, "modes"), _section(page, "rebound")
    for support in ("free", "hand"):
        shown = ", ".join(f"{v * 1e3:.0f}" for v in nodes[support])
        assert f"{support} {shown} mm" in modes
        assert f"first-mode nodes on the axis, {support}: x = {nodes[support][0] * 1e3:.0f}" in (
            rebound
        )


def _captions(page: str, key: str) -> str:
    return " ".join(re.findall(r"<figcaption>(.*?)</figcaption>", _section(page, key), re.S))


def test_swing_captions_state_the_run_s_settings(run_dir: Path, tmp_path: Path) -> None:
    """Issue 13: the swing captions named the default swing (constant torque, half/same/1.5
    times the angle) whatever the run used; they now say what swing/run.json records."""
    out = tmp_path / "swing"
    argv = ["swing", "--grid", "3", "--speed", "15,35", "--angular-speed", "30"]
    assert main([*argv, "--support", "free", "--out", str(out)]) == 0
    page = write_report(tmp_path).read_text(encoding="utf-8")
    captions = _captions(page, "swing")
    record = json.loads((out / "run.json").read_text())
    assert record["along_axis_swings"] == [
        "racket at rest",
        "Ω = 15.0 rad/s",
        "Ω = 30.0 rad/s",
        "Ω = 45.0 rad/s",
    ]
    assert captions.count("given angular speed Ω = 30.0 rad/s") == 2
    shown = record["sweet_spots_at_mps"]
    assert shown in (15.0, 35.0)
    assert captions.count(f"ball at {shown:g} m/s, freely supported, approximate model") == 2
    assert "the swings Ω = 15.0 rad/s, Ω = 30.0 rad/s and Ω = 45.0 rad/s" in captions
    for default in ("56.9", "torque", "20 m/s", "hand-held", "pinned"):
        assert default not in captions, default


def _caption_of(page: str, png: str) -> str:
    """The caption text of the figure whose file is ``png`` (relative to the run folder)."""
    for caption in re.findall(r"<figcaption>(.*?)</figcaption>", page, re.S):
        if png in caption:
            return unescape(re.sub(r"<[^>]+>", "", caption))
    raise AssertionError(f"no figure {png} on the page")


def test_predict_captions_state_the_run_s_speeds_and_supports(tmp_path: Path) -> None:
    """Issue 13: predict's captions named "the run's speeds (in the title)"; they now say them."""
    out = tmp_path / "predict"
    argv = ["predict", "--grid", "3", "--speed", "35,25", "--racket-speed", "5"]
    assert main([*argv, "--support", "free", "--model", "both", "--out", str(out)]) == 0
    page = write_report(tmp_path).read_text(encoding="utf-8")
    expected = {
        "fig13_pulse_spectrum": "balls at 25 and 35 m/s, racket at 5 m/s (support in the title)",
        "fig15_rebound_along_axis": "ball at 25 m/s, racket at 5 m/s, freely supported, with",
        "transient_comparison_face": "one panel per support, ball at 25 m/s, racket at 5 m/s;",
        "transient_comparison_speed": "(solid), racket at 5 m/s; a curve breaks where",
    }
    for name, words in expected.items():
        caption = _caption_of(page, f"predict/{name}.png")
        assert words in caption, name
        for default in ("20 m/s", "pinned", "racket at rest", "the run's"):
            assert default not in caption, (name, default)


def test_compare_captions_state_the_files_band_and_speed(run_dir: Path, tmp_path: Path) -> None:
    """Issue 13: compare's captions said 20 m/s and free/hand-held whatever was compared; a
    compare of another pair at another speed is described as what it was."""
    pair = tmp_path / "pair"
    pair.mkdir()
    shutil.copy(run_dir / "frf_hand" / "frfs.uff", pair / "first.uff")
    shutil.copy(run_dir / "frf_free" / "frfs.uff", pair / "second.uff")
    out = tmp_path / "compare"
    argv = ["compare", str(pair / "first.uff"), str(pair / "second.uff"), "--band", "60,800"]
    assert main([*argv, "--speed", "32.5", "--out", str(out)]) == 0
    assert json.loads((out / "run.json").read_text())["fig15_ball_speed_mps"] == 32.5
    page = write_report(tmp_path).read_text(encoding="utf-8")
    modes, rebound = _captions(page, "modes"), _captions(page, "rebound")
    assert "free (blue, pair/first.uff) against hand-held (black, pair/second.uff)" in modes
    assert "identified over 60–800 Hz" in modes
    assert "hand-held (pair/second.uff) against free (pair/first.uff)" in modes
    assert "ball at 32.5 m/s" in rebound
    assert "identified from pair/first.uff and pair/second.uff" in rebound
    assert "20 m/s" not in rebound


def test_no_transient_section_without_a_comparison(run_dir: Path, tmp_path: Path) -> None:
    shutil.copytree(run_dir / "predict", tmp_path / "predict")
    (tmp_path / "predict" / "comparison.csv").unlink()
    text = write_report(tmp_path, racket=rd.default_racket()).read_text(encoding="utf-8")
    assert '<section id="transient">' not in text
    not_run = text[text.index('<section id="not-run">') :]
    assert SECTIONS["transient"].title in not_run
    assert "--model both" in not_run
    for key in ("impact", "vibration", "rebound"):
        assert f'<section id="{key}">' in text


def test_an_empty_folder_is_an_input_error(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="nothing to report"):
        write_report(tmp_path)
    with pytest.raises(InputError, match="not a folder"):
        write_report(tmp_path / "missing")


# --- a real browser -----------------------------------------------------------------------------

# dispatched after the report's own script: hover a map point and the FRF, zoom, switch views
PROBE = """<script>
(function () {
  var out = { ms: performance.now() };  // the report's scripts have run: interactive
  try {
    var dot = document.querySelector("#map-rebound circle.pt"), r = dot.getBoundingClientRect();
    dot.dispatchEvent(new MouseEvent("mousemove",
      { bubbles: true, clientX: r.left + 1, clientY: r.top + 1 }));
    out.tip = document.getElementById("tip").textContent;
    out.tipShown = !document.getElementById("tip").hidden;
    var svg = document.querySelector("#frf-plot svg"), b = svg.getBoundingClientRect();
    var at = { bubbles: true, cancelable: true, clientX: b.left + 0.3 * b.width,
      clientY: b.top + 60 };
    svg.dispatchEvent(new MouseEvent("mousemove", at));
    out.readout = document.querySelector("#frf-plot .readout").textContent;
    out.before = document.getElementById("frf-plot").dataset.range;
    at.deltaY = -100;
    svg.dispatchEvent(new WheelEvent("wheel", at));
    out.after = document.getElementById("frf-plot").dataset.range;
    document.querySelector('#map-rebound button[data-pick="0"]').click();
    out.group = document.getElementById("map-rebound").dataset.group;
  } catch (error) { out.error = String(error); }
  document.body.setAttribute("data-probe", JSON.stringify(out));
})();
</script>"""


@pytest.fixture(scope="module")
def chromium() -> str:
    return find_chromium()


def test_browser_screenshot_is_not_blank(chromium: str, report: Path, tmp_path: Path) -> None:
    shot = tmp_path / "report.png"
    done = browse(
        chromium, report, tmp_path / "profile", f"--screenshot={shot}", "--window-size=1280,4000"
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert shot.is_file()
    assert shot.stat().st_size > 10_000
    with Image.open(shot) as image:
        assert image.size == (1280, 4000)
        colours = image.convert("RGB").getcolors(maxcolors=1 << 20)
    assert colours is not None
    assert len(colours) > 200  # text, tables and figures, not a blank or error page


def test_browser_runs_the_script_without_errors(
    chromium: str, report: Path, tmp_path: Path
) -> None:
    probed = tmp_path / "probed.html"
    probed.write_text(report.read_text(encoding="utf-8").replace("</body>", PROBE + "</body>"))
    done = browse(
        chromium,
        probed,
        tmp_path / "profile",
        "--window-size=1280,4000",
        "--enable-logging=stderr",
        "--v=0",
        "--dump-dom",
    )
    assert done.returncode == 0, done.stderr[-2000:]
    dom = done.stdout
    assert not re.search(r"Uncaught|CONSOLE.*error", done.stderr, re.I), done.stderr[-2000:]
    body = re.search(r"<body[^>]*>", dom)
    assert body is not None
    assert 'data-ready="1"' in body.group(0)
    assert "data-errors" not in dom[: dom.index("<head")]
    figures = re.findall(r"<figure\b.*?</figure>", dom, re.S)
    assert len(figures) == report.read_text(encoding="utf-8").count("<figure")
    for figure in figures:
        drawn = re.search(r'data-drawn="(\d+)"', figure)
        embedded = 'src="data:image/png;base64,' in figure
        assert embedded or (drawn is not None and int(drawn.group(1)) > 0), figure[:300]
    for element in ("frf-plot", "map-rebound", "map-contact"):
        assert re.search(rf'id="{element}"[^>]*data-drawn="[1-9]', dom), element
    probe_attribute = re.search(r'data-probe="([^"]*)"', dom)
    assert probe_attribute is not None
    probe = json.loads(probe_attribute.group(1).replace("&quot;", '"').replace("&amp;", "&"))
    assert "error" not in probe, probe
    assert probe["tipShown"]
    assert "rebound ratio" in probe["tip"]
    assert "contact time" in probe["tip"]
    assert "Hz" in probe["readout"]
    assert "|H|" in probe["readout"]
    low, high = (float(v) for v in probe["before"].split("-"))
    zoomed_low, zoomed_high = (float(v) for v in probe["after"].split("-"))
    assert zoomed_high - zoomed_low < high - low  # the wheel zoomed in
    assert probe["group"] == "10 m/s"
    # the probe ran once the page was interactive; how soon (≤ 2 s, issue 11) is a benchmark's,
    # benchmarks/bench_report.py (median of five loads): timed here it failed at 2.2 s on a
    # machine at load 10 (tenth session) and passed alone
    assert 0 < probe["ms"] < 60_000


def test_every_file_of_the_demo_layout_is_its_runs_own(page: str) -> None:
    """Issue 13: the report called the demo's own rig files "written by an earlier run" (two
    rig runs shared one folder); the rig now tests both supports in one run."""
    assert "not this run" not in page
    assert "earlier run" not in page


def test_the_largest_vibration_is_never_a_flagged_row(tmp_path: Path) -> None:
    """Issue 13: §7's "largest on the face" (11.7 J) came from rows flagged as beyond what e_BG
    allows near the tip; only valid rows may give it."""
    from racketdyn.report.folder import RunFolder
    from racketdyn.report.sections import vibration

    out = tmp_path / "run"
    argv = ["predict", "--speed", "40", "--support", "free", "--grid", "9", "--no-figures"]
    assert main([*argv, "--out", str(out / "predict")]) == 0
    with (out / "predict" / "impact.csv").open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    energy: dict[bool, list[float]] = {}
    for r in rows:
        energy.setdefault(r["status"] == "ok", []).append(float(r["vibration_energy_j"]))
    assert energy.get(False), "the test needs flagged rows: raise the speed"
    assert all(math.isnan(e) for e in energy[False])  # flagged: NaN in the file
    # a file written before that rule, flagged rows holding 100 J: still never the largest
    with (out / "predict" / "impact.csv").open(encoding="utf-8") as handle:
        text = handle.read().splitlines()
    header = text[0].split(",")
    at, state = header.index("vibration_energy_j"), header.index("status")
    lines = [text[0]]
    for line in text[1:]:
        cells = line.split(",")
        if cells[state] != "ok":
            cells[at] = "100"
        lines.append(",".join(cells))
    (out / "predict" / "impact.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    data = vibration.gather(RunFolder.scan(out))
    assert data is not None
    (row,) = data["rows"]
    # the page gives 3 significant figures: within half a unit of the third (13.0 for 13.02)
    assert float(row[4]) == pytest.approx(max(energy[True]), rel=5e-3)


def test_the_ball_section_says_what_the_papers_103_hz_asks_of_the_inputs(
    run_dir: Path, page: str
) -> None:
    """Issue 14: the page states the band of the small-amplitude inputs from the run's own
    run.json, whether it holds the paper's 103 Hz, and the bed that 103 Hz needs."""
    record = json.loads((run_dir / "compound" / "run.json").read_text(encoding="utf-8"))
    band = record["ball_mode_band"]["free"]
    low, high = band["band_hz"]
    bed = band["bed_for_paper"]["bed_stiffness_n_per_m"]
    text = unescape(" ".join(re.sub(r"<[^>]+>", " ", page).split()))
    assert (
        f"free: the spread of the small-amplitude inputs (the ball's stiffness, the bed under "
        f"the ball, the ball's mass) puts the ball mode between {low:.0f} and {high:.0f} Hz, "
        f"which holds the paper's 103 Hz; with the nominal ball it needs the bed at "
        f"{bed / 1e3:.0f} kN/m under it" in text
    )
    cycles = record["neck_hand_over"]["free"]["ball_cycles"]
    assert f"the 2-node mode takes over after {cycles:.1f} ball cycles" in text


def test_compare_prints_what_the_hand_changes(
    run_dir: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """New-user trial (2026-11-26, second session): ``compare`` printed the two mode tables and
    nothing of the comparison it is named for (its page quotes "the 2-node bending mode drops
    from 120.0 Hz to 113.2 Hz"); it now prints each MAC pair's shift, damping ratio and MAC,
    and the first mode's nodes, as comparison.csv and run.json hold them."""
    frfs = [str(run_dir / "frf_free" / "frfs.uff"), str(run_dir / "frf_hand" / "frfs.uff")]
    out = tmp_path / "compare"
    capsys.readouterr()
    assert main(["compare", *frfs, "--band", "40,850", "--out", str(out)]) == 0
    printed = " ".join(capsys.readouterr().out.split())
    with (out / "comparison.csv").open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    first = next(r for r in rows if r["mode"] == "2-node bending")
    line = re.search(
        r"2-node bending: ([\d.]+) → ([\d.]+) Hz \(([-+\d.]+) %\), damping ×([\d.]+), "
        r"MAC ([\d.]+)",
        printed,
    )
    assert line is not None, printed
    # the console rounds the numbers in memory, the CSV holds 9 digits: half a printed digit
    # apart at most (116.85 Hz printed 116.9, read back from the CSV as 116.8499… → 116.8)
    columns = (
        "frequency_free_hz",
        "frequency_hand_hz",
        "frequency_shift_percent",
        "damping_ratio_hand_over_free",
        "mac",
    )
    for column, shown in zip(columns, line.groups(), strict=True):
        half_digit = 0.5 * 10.0 ** -len(shown.partition(".")[2])
        assert abs(float(shown) - float(first[column])) <= half_digit + 1e-9, column
    nodes = json.loads((out / "run.json").read_text(encoding="utf-8"))["first_mode_nodes_m"]
    free = ", ".join(f"{x * 1e3:.0f}" for x in nodes["free"])
    assert f"first mode's nodes on the axis: free {free} mm" in printed
