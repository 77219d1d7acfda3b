"""The report's scripts (``racketdyn/report/static/*.js``) on their own, in headless Chromium:
a page with the real markup of two interactive figures and hand-made data, driven by a probe
that hovers, zooms, pans and switches, and records what the scripts drew."""

from __future__ import annotations

import html
import json
import re
from typing import Any

import pytest

from browser import browse, find_chromium
from racketdyn.report.figures import interactive
from racketdyn.report.page import SCRIPTS, environment, static

pytestmark = pytest.mark.slow

# two or three points per panel, one without a value and one flagged with a value (both drawn
# hollow), a label that must stay text
MAP = {
    "id": "map-test",
    "frame": [-10.0, 110.0, -40.0, 60.0],
    "radius": 4.0,
    "font": 4.0,
    "head": [50.0, 0.0, 50.0, 30.0],
    "fields": [["x", "mm", 0], ["y", "mm", 0], ["rebound ratio", "", 3]],
    "colour": 2,
    "best": "max",
    "groups": [
        {
            "label": "10 m/s",
            "range": [0.1, 0.5],
            "panels": [
                {"label": "<i>free</i>", "rows": [[20, 0, 0.1, ""], [50, 0, 0.5, ""]]},
                {"label": "pinned", "rows": [[20, 0, 0.2, ""], [80, 0, None, "beyond the law"]]},
            ],
        },
        {
            "label": "20 m/s",
            "range": [0.2, 0.4],
            "panels": [
                {"label": "<i>free</i>", "rows": [[20, 0, 0.2, ""], [50, 0, 0.4, ""]]},
                {
                    "label": "pinned",
                    "rows": [
                        [20, 0, 0.3, ""],
                        [80, 0, 0.25, ""],
                        # flagged with a number (an impact.csv written before issue 13)
                        [50, 0, 0.45, "vibration loss exceeds e_BG"],
                    ],
                },
            ],
        },
    ],
    "initial": 1,
    "marks": [{"x": 40.0, "label": "CoP"}],
}

# 1 Hz lines to 1000 Hz, a resonance at 120 Hz, two views of two series
_F = [float(f) for f in range(1, 1001)]
_MAG = [float(f"{1e-4 / abs(1 - (f / 120) ** 2 + 0.02j * f / 120):.4g}") for f in _F]
FRF = {
    "id": "frf-test",
    "f": _F,
    "unit": "m/N",
    "views": [
        {
            "label": "driving point",
            "series": [
                {"label": "free, node 1", "colour": "#1f77b4", "mag": _MAG, "coh": [0.99] * 1000},
                {"label": "hand, node 1", "colour": "#222222", "mag": _MAG, "coh": None},
            ],
        },
        {
            "label": "centre",
            "series": [{"label": "free, node 9", "colour": "#1f77b4", "mag": _MAG, "coh": None}],
        },
    ],
    "modes": [{"f": 120.0, "label": "2-node bending (free)", "colour": "#1f77b4"}],
}

PROBE = r"""
(function () {
  var out = {}, rd = window.racketdyn, kit = rd.kit;
  function range() { return document.getElementById("frf-test").dataset.range; }
  try {
    out.esc = kit.esc('<a href="x">&');
    out.colours = [kit.colour(0), kit.colour(1), kit.colour(-1), kit.colour(2)];
    out.num = [kit.num(null, 2), kit.num(1.23456, 2), kit.num("text", 2)];
    out.niceStep = [kit.niceStep(1000, 8), kit.niceStep(7, 8)];
    var map = document.getElementById("map-test");
    out.mapDrawn = map.dataset.drawn;
    out.mapGroup = map.dataset.group;
    out.hollow = map.querySelectorAll("circle.bad").length;
    out.rings = map.querySelectorAll('circle[stroke="#d62728"]').length;
    out.ringX = Array.prototype.map.call(map.querySelectorAll('circle[stroke="#d62728"]'),
      function (c) { return c.getAttribute("cx"); });
    out.marks = map.querySelectorAll("line[stroke-dasharray]").length;
    out.panelLabels = Array.prototype.map.call(map.querySelectorAll("svg.face > text[font-weight]"),
      function (t) { return t.textContent; });
    map.querySelector('button[data-pick="0"]').click();
    out.switched = map.dataset.group;
    out.hollowAfter = map.querySelectorAll("circle.bad").length;
    var bad = map.querySelector("circle.bad"), r = bad.getBoundingClientRect();
    bad.dispatchEvent(new MouseEvent("mousemove",
      { bubbles: true, clientX: r.left + 1, clientY: r.top + 1 }));
    var tip = document.getElementById("tip");
    out.tipShown = !tip.hidden;
    out.tipText = tip.textContent;
    out.tipBold = tip.querySelector("b").textContent;
    out.tipItalic = tip.querySelectorAll("i").length;
    map.querySelector(".panels").dispatchEvent(new MouseEvent("mouseleave"));
    out.tipHidden = tip.hidden;

    var box = document.getElementById("frf-test"), svg = box.querySelector("svg");
    var b = svg.getBoundingClientRect();
    out.frfDrawn = box.dataset.drawn;
    out.full = range();
    out.lines = svg.querySelectorAll("polyline").length;
    out.modeLines = svg.querySelectorAll('g line[stroke-dasharray="4 3"]').length;
    var x120 = b.left + (78 + 822 * 119 / 999) * b.width / 900;  // 120 Hz on the full axis
    var at = { bubbles: true, cancelable: true, clientX: x120, clientY: b.top + 60 };
    svg.dispatchEvent(new MouseEvent("mousemove", at));
    out.readout = box.querySelector(".readout").textContent;
    at.deltaY = -100;
    svg.dispatchEvent(new WheelEvent("wheel", at));
    out.zoomed = range();
    for (var i = 0; i < 60; i++) { svg.dispatchEvent(new WheelEvent("wheel", at)); }
    out.deepest = range();
    box.querySelector('button[data-zoom="0"]').click();
    out.reset = range();
    box.querySelector('button[data-zoom="0.5"]').click();
    out.half = range();
    var down = { bubbles: true, clientX: b.left + b.width / 2, clientY: b.top + 60 };
    svg.dispatchEvent(new MouseEvent("mousedown", down));
    svg.dispatchEvent(new MouseEvent("mousemove",
      { bubbles: true, clientX: b.left + b.width / 2 + 100, clientY: b.top + 60 }));
    window.dispatchEvent(new MouseEvent("mouseup"));
    out.panned = range();
    svg.dispatchEvent(new MouseEvent("dblclick", { bubbles: true }));
    out.afterDouble = range();
    box.querySelector('button[data-pick="1"]').click();
    out.viewLines = svg.querySelectorAll("polyline").length;
  } catch (error) { out.error = String(error) + " " + error.stack; }
  document.body.setAttribute("data-probe", JSON.stringify(out));
})();
"""


def _harness() -> str:
    """A page with the report's markup for one map and one FRF plot, its styles and scripts,
    the hand-made data, and the probe."""
    env = environment()
    figures = env.from_string(
        '{% from "macros.html.j2" import figure %}{{ figure(a) }}{{ figure(b) }}'
    ).render(
        a=interactive("map-test", "map", None, "a test map", "test"),
        b=interactive("frf-test", "frf", "Figs 2–3", "a test FRF", "test"),
    )
    data = env.from_string("{{ d | tojson }}").render(d={"maps": [MAP], "frf": [FRF]})
    scripts = "".join(f"<script>{static(name)}</script>" for name in SCRIPTS)
    return (
        "<!DOCTYPE html><html><head><meta charset='utf-8'>"
        f"<style>{static('report.css')}</style><script>{static('error_trap.js')}</script>"
        f"</head><body style='width:1000px'>{figures}<div id='tip' hidden></div>"
        f"<script type='application/json' id='report-data'>{data}</script>{scripts}"
        f"<script>{PROBE}</script></body></html>"
    )


@pytest.fixture(scope="module")
def probe(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    chromium = find_chromium()
    folder = tmp_path_factory.mktemp("js")
    page = folder / "harness.html"
    page.write_text(_harness(), encoding="utf-8")
    done = browse(chromium, page, folder / "profile", "--window-size=1100,1600", "--dump-dom")
    assert done.returncode == 0, done.stderr[-2000:]
    dom = done.stdout
    assert "data-errors" not in dom[: dom.index("<head")], dom[:500]
    assert re.search(r'<body[^>]*data-ready="1"', dom)
    found = re.search(r'data-probe="([^"]*)"', dom)
    assert found is not None, dom[-2000:]
    result: dict[str, Any] = json.loads(html.unescape(found.group(1)))
    assert "error" not in result, result["error"]
    return result


def _span(text: str) -> float:
    low, high = (float(v) for v in text.split("-"))
    return high - low


def test_kit(probe: dict[str, Any]) -> None:
    assert probe["esc"] == "&lt;a href=&quot;x&quot;&gt;&amp;"
    # viridis ends, and values outside [0, 1] clipped to them
    assert probe["colours"] == ["rgb(68,1,84)", "rgb(253,231,37)"] * 2
    assert probe["num"] == ["–", "1.23", "text"]
    assert probe["niceStep"] == [100, 0.5]  # 1, 2 or 5 × 10^n


def test_face_map_draws_every_point(probe: dict[str, Any]) -> None:
    assert probe["mapDrawn"] == "5"
    assert probe["mapGroup"] == "20 m/s"  # the initial group
    assert probe["hollow"] == 1  # the flagged row: never coloured as a value (issue 13)
    assert probe["rings"] == 2  # the largest valid value of each panel
    # free: 0.4 at x = 50 mm; pinned: 0.3 at x = 20 mm, not the flagged 0.45 at 50 mm
    assert probe["ringX"] == ["60.0", "30.0"]
    assert probe["marks"] == 2  # the CoP line in each panel
    assert probe["panelLabels"] == ["<i>free</i>", "pinned"]  # shown as text, not markup


def test_face_map_buttons_and_hover(probe: dict[str, Any]) -> None:
    assert probe["switched"] == "10 m/s"
    assert probe["hollowAfter"] == 1  # the point without a value
    assert probe["tipShown"]
    assert probe["tipBold"] == "pinned, 10 m/s"
    assert "rebound ratio: –" in probe["tipText"]
    assert "beyond the law" in probe["tipText"]
    assert probe["tipItalic"] == 0
    assert probe["tipHidden"]


def test_frf_plot_draws_zooms_and_reads_out(probe: dict[str, Any]) -> None:
    assert probe["frfDrawn"] == "2000"  # two series of 1000 lines
    assert probe["full"] == "1.0-1000.0"
    assert probe["lines"] == 3  # two magnitudes and one coherence
    assert probe["modeLines"] == 1
    shown = re.match(r"f = ([\d.]+) Hz", probe["readout"])
    assert shown is not None
    assert float(shown.group(1)) == pytest.approx(120, abs=3)  # the line under the cursor
    assert "|H| = " in probe["readout"]
    assert "near 2-node bending (free) at 120.0 Hz" in probe["readout"]
    assert _span(probe["zoomed"]) == pytest.approx(0.8 * 999, abs=0.2)
    assert _span(probe["deepest"]) == pytest.approx(8.0)  # never below 8 lines
    assert probe["reset"] == probe["full"]
    assert _span(probe["half"]) == pytest.approx(999 / 2, abs=0.2)
    assert probe["panned"] != probe["half"]
    assert _span(probe["panned"]) == pytest.approx(_span(probe["half"]), abs=0.2)
    assert probe["afterDouble"] == probe["full"]
    assert probe["viewLines"] == 1  # the second view has one series, no coherence
