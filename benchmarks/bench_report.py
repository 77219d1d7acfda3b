"""Size of the HTML report and its time to interactive in headless Chromium.

Run with ``python benchmarks/bench_report.py [RUN_FOLDER]``.  Without a folder, ``racketdyn
demo`` runs first into a temporary folder (≈ 45 s).  Prints the time ``write_report`` takes, the
page's size (and how much of it is embedded PNGs, plot data, styles and scripts) against the
budget of 6 MB, and the time from navigation start until the page's scripts have drawn every
interactive plot (``<body data-ready="1">``), median of five loads in headless Chromium, against
the target of 2 s.  Informational: the exit status is 0 whatever the numbers.
"""

from __future__ import annotations

import html
import json
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from racketdyn.cli import main as racketdyn
from racketdyn.report import write_report

PAGE_BUDGET_BYTES = 6_000_000
INTERACTIVE_TARGET_S = 2.0
LOADS = 5
PROBE = (
    '<script>document.body.setAttribute("data-bench", JSON.stringify('
    '{ready: document.body.dataset.ready || "", ms: performance.now()}));</script>'
)
FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--no-first-run",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",
    "--window-size=1280,4000",
    "--dump-dom",
)


def time_to_interactive(chromium: str, page: Path, scratch: Path) -> list[float]:
    """Seconds from navigation start until the report's scripts have run, one per load."""
    probed = scratch / "probed.html"
    probed.write_text(
        page.read_text(encoding="utf-8").replace("</body>", PROBE + "</body>"), encoding="utf-8"
    )
    times = []
    for n in range(LOADS):
        done = subprocess.run(
            [chromium, *FLAGS, f"--user-data-dir={scratch / f'profile{n}'}", probed.as_uri()],
            capture_output=True,
            text=True,
            timeout=120,
            check=False,
        )
        found = re.search(r'data-bench="([^"]*)"', done.stdout)
        if found is None:
            raise RuntimeError(f"the probe did not run: {done.stderr[-500:]}")
        result = json.loads(html.unescape(found.group(1)))
        if result["ready"] != "1":
            raise RuntimeError("the page's scripts did not finish")
        times.append(result["ms"] / 1e3)
    return times


def main() -> int:
    scratch = Path(tempfile.mkdtemp(prefix="bench_report_"))
    if len(sys.argv) > 1:
        folder = Path(sys.argv[1])
    else:
        folder = scratch / "demo"
        print("running racketdyn demo …")
        racketdyn(["demo", "--out", str(folder)])
    start = time.perf_counter()
    page = write_report(folder)
    written = time.perf_counter() - start
    text = page.read_text(encoding="utf-8")
    size = page.stat().st_size
    images = sum(len(m) for m in re.findall(r'src="(data:image/png;base64,[^"]*)"', text))
    data = re.search(r'id="report-data">(.*?)</script>', text, re.S)
    scripts = sum(len(m) for m in re.findall(r"<script>(.*?)</script>", text, re.S))
    styles = sum(len(m) for m in re.findall(r"<style>(.*?)</style>", text, re.S))
    print(f"write_report: {written:.2f} s")
    print(
        f"page: {size / 1e6:.2f} MB (budget {PAGE_BUDGET_BYTES / 1e6:.0f} MB, "
        f"{'within' if size <= PAGE_BUDGET_BYTES else 'OVER'}): embedded PNGs "
        f"{images / 1e6:.2f} MB, plot data {len(data.group(1)) / 1e3 if data else 0:.0f} kB, "
        f"scripts {scripts / 1e3:.0f} kB, styles {styles / 1e3:.1f} kB"
    )
    chromium = shutil.which("chromium")
    if chromium is None:
        print("time to interactive: not measured (no chromium)")
    else:
        times = time_to_interactive(chromium, page, scratch)
        median = statistics.median(times)
        print(
            f"time to interactive (headless Chromium, median of {LOADS}): {median:.2f} s "
            f"(target {INTERACTIVE_TARGET_S:.0f} s, {median / INTERACTIVE_TARGET_S:.2f} of it); "
            f"loads: {', '.join(f'{t:.2f}' for t in times)} s"
        )
    shutil.rmtree(scratch, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
