"""The report's and the console's headline numbers come from every valid row of impact.csv:
the approximate method's own and those filled from the transient model (``predict --model
both``), which carry the transient model's numbers, valid, marked so (docs/formats.md).

New-user trial of the ninth session: "highest rebound ratio, ball 25 m/s, racket 10 m/s,
pinned: 0.365 at x = 472 mm" passed over a filled row with 0.3742 at x = 397 mm, and the
sweet-spot table said 0.393 where impact.csv held 0.4146; the frame-vibration table gave the
vibration as a share of the ball's lab-frame energy with the racket moving at 10 m/s.
"""

from __future__ import annotations

import csv
import shutil
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.cli import main
from racketdyn.impact.result import STATUS_FROM_TRANSIENT, STATUS_OK, summary_rows
from racketdyn.report.folder import RunFolder
from racketdyn.report.sections import impact, rebound, vibration

SPEEDS = (15.0, 25.0)
RACKET_SPEED = 10.0


@pytest.fixture(scope="module")
def predicted(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A small approximate run, racket at 10 m/s (a few seconds)."""
    out = tmp_path_factory.mktemp("headline") / "run"
    argv = ["predict", "--speed", "15,25", "--racket-speed", str(RACKET_SPEED)]
    argv += ["--support", "pinned", "--grid", "7", "--no-figures"]
    assert main([*argv, "--out", str(out / "predict")]) == 0
    return out


def _rows(path: Path) -> list[dict[str, str]]:
    with path.open(encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def _write(path: Path, rows: list[dict[str, str]]) -> None:
    with path.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def _with_filled_best(predicted: Path, tmp_path: Path) -> tuple[Path, dict[float, dict[str, str]]]:
    """The run with, at each speed, one ok row turned into a row filled from the transient
    model whose rebound ratio and vibration energy are the face's highest: the row each
    "highest" must name."""
    out = tmp_path / "run"
    shutil.copytree(predicted, out)
    path = out / "predict" / "impact.csv"
    rows = _rows(path)
    filled: dict[float, dict[str, str]] = {}
    for speed in SPEEDS:
        at = [r for r in rows if float(r["ball_speed_mps"]) == speed and r["status"] == STATUS_OK]
        assert len(at) > 2, "the test needs valid rows"
        top = max(float(r["rebound_ratio"]) for r in at)
        most = max(float(r["vibration_energy_j"]) for r in at)
        row = min(at, key=lambda r: float(r["rebound_ratio"]))  # not already the best
        row["status"] = STATUS_FROM_TRANSIENT
        row["rebound_ratio"] = f"{top + 0.0123:.9g}"
        row["vibration_energy_j"] = f"{most * 1.5:.9g}"
        filled[speed] = row
    _write(path, rows)
    return out, filled


def _gathered(
    section: Any, predicted: Path, tmp_path: Path
) -> tuple[dict[str, Any], dict[float, dict[str, str]]]:
    """A section's data of the run with a filled best row at each speed, and those rows."""
    out, filled = _with_filled_best(predicted, tmp_path)
    data = section.gather(RunFolder.scan(out))
    assert data is not None
    return data, filled


def _where(row: dict[str, str]) -> str:
    return f"{float(row['x_m']) * 1e3:.0f}, {float(row['y_m']) * 1e3:.0f}"


def test_the_highest_rebound_ratio_counts_rows_filled_from_the_transient(
    predicted: Path, tmp_path: Path
) -> None:
    data, filled = _gathered(rebound, predicted, tmp_path)
    (line,) = [g for g in data["glance"] if g.startswith("highest rebound ratio")]
    shown = next(row for speed, row in filled.items() if f"ball {speed:g} m/s" in line)
    value = float(shown["rebound_ratio"])
    assert f": {value:.3f} at x = {float(shown['x_m']) * 1e3:.0f} mm" in line
    assert line.endswith("(transient model)")
    for speed, row in filled.items():
        (sweet,) = [s for s in data["sweet"] if s[1] == f"{speed:g}"]
        assert sweet[2] == f"{float(row['rebound_ratio']):.3f} (transient model)"
        assert sweet[3] == _where(row)


def test_the_largest_vibration_counts_rows_filled_from_the_transient(
    predicted: Path, tmp_path: Path
) -> None:
    data, filled = _gathered(vibration, predicted, tmp_path)
    for speed, row in filled.items():
        (line,) = [r for r in data["rows"] if r[1] == f"{speed:g}"]
        assert line[4] == f"{float(row['vibration_energy_j']):.3g} (transient model)"
        assert line[5] == _where(row)


def test_the_centre_s_headline_names_the_model_of_a_filled_row(
    predicted: Path, tmp_path: Path
) -> None:
    """The face centre's contact time and rebound ratio "At a glance" from a filled row say
    which model gave them."""
    out = tmp_path / "run"
    shutil.copytree(predicted, out)
    run = RunFolder.scan(out)
    impacts = run.impacts()
    assert impacts is not None
    x, y = run.centre(impacts)
    path = out / "predict" / "impact.csv"
    rows = _rows(path)
    for case in impacts.case_list:
        rows[impacts.nearest(impacts.rows(case, "pinned"), x, y)]["status"] = STATUS_FROM_TRANSIENT
    _write(path, rows)
    data = impact.gather(RunFolder.scan(out))
    assert data is not None
    (line,) = data["glance"]
    assert line.startswith("face centre")
    assert line.endswith("(transient model)")


def test_the_vibration_share_is_of_the_approach_energy(predicted: Path) -> None:
    """The share the 30 % validity rule uses: ½ μ V², μ = m_B M_r/(m_B + M_r), V the ball's
    and the racket's speeds added; not ½ m_B v_ball² in the lab frame."""
    run = RunFolder.scan(predicted)
    data = vibration.gather(run)
    assert data is not None
    impacts = run.impacts()
    assert impacts is not None
    m_b = float(run.record(run.predict_dir)["ball"]["mass_kg"])
    x, y = run.centre(impacts)
    for speed in SPEEDS:
        i = impacts.nearest(impacts.rows((speed, RACKET_SPEED), "pinned"), x, y)
        assert impacts.status[i] == STATUS_OK
        reduced = impacts["reduced_mass_kg"][i]
        mu = m_b * reduced / (m_b + reduced)
        approach = 0.5 * mu * (speed + RACKET_SPEED) ** 2
        share = 100 * impacts["vibration_energy_j"][i] / approach
        (line,) = [r for r in data["rows"] if r[1] == f"{speed:g}"]
        assert line[3] == f"{share:.2g}"
    assert data["share_of"] == "of the approach energy"


def test_summaries_of_a_result_count_rows_filled_from_the_transient() -> None:
    """``repr`` and the notebook table give the rebound ratios of every valid row."""
    racket = rd.default_racket()
    result = rd.predict(racket, rd.Ball(), [(0.45, 0.0), (0.50, 0.0)], [20.0], ["pinned"])
    status = np.asarray(result.status).copy()
    e = np.asarray(result.rebound_ratio).copy()
    status[0, 0, 0] = STATUS_FROM_TRANSIENT
    e[0, 0, 0] = float(np.nanmax(e)) + 0.1
    filled = replace(result, status=status, rebound_ratio=e)
    rows = dict(summary_rows(filled))
    assert f"{e[0, 0, 0]:.4g}" in rows["rebound ratio"]


def test_the_console_headline_shows_a_row_filled_from_the_transient() -> None:
    """``predict``'s table at the face centre gave dashes for a row filled from the transient
    model, as if it had no numbers; its status column names the model."""
    from rich.console import Console

    from racketdyn.cli.predict import _headline

    racket = rd.default_racket()
    result = rd.predict(racket, rd.Ball(), [(racket.head.centre_x_m, 0.0)], [20.0], ["pinned"])
    status = np.asarray(result.status).copy()
    status[0, 0, 0] = STATUS_FROM_TRANSIENT
    console = Console(width=300, record=True)
    console.print(_headline(replace(result, status=status), racket, "approximate method"))
    text = console.export_text()
    assert f"{float(result.rebound_ratio[0, 0, 0]):.3f}" in text
    assert "from the transient model" in text


def test_the_console_does_not_call_filled_rows_flagged() -> None:
    """``predict --model both`` printed "flagged: 96 of … rows (see its status column): … 64
    from the transient model: beyond the approximate method", rows that hold numbers."""
    from racketdyn.cli.predict import _flagged

    status = np.array([STATUS_OK, STATUS_FROM_TRANSIENT, STATUS_FROM_TRANSIENT])
    line, style = _flagged(status, "impact.csv")
    assert line.startswith("flagged: none of 3 rows in impact.csv")
    assert "2 filled from the transient model" in line
    assert style is None
