"""The numbers ``predict`` writes are those of the code before issue 23's refactor (figures
computed by the workflows, not the plotting): every CSV cell and run.json number of two small
runs against the files that code wrote (``tests/data/predict_before_issue23``, its README says
how they were made and when to write them anew).

Written anew since: by the commit giving the built-in frame its shape (issue 22, fourth
session, "frame's shape" in CHANGELOG.md) and by the merge of issue 27's one hand (the built-in
model sampling the handle's sides: ≈ 1e-6), and by the commit adding the frame's head's top
(issue 22, fifth session: the paper's racket carries nothing there, but its amounts are solved
another way, 2e-8 in its frequencies), and by the commit solving the built-in model's
eigenproblems on one BLAS thread (issue 27: 1e-8 in its 3-node frequency, the files' numbers
in their ninth digit; before, they were two threads' on the machine that wrote them) — changes
of physics or of round-off, not of the refactor."""

from __future__ import annotations

import csv
import json
import logging
import math
from pathlib import Path
from typing import Any

import pytest

from racketdyn.workflows import PredictOptions, run_predict

RTOL = 1e-5
"""Round-off of one build of the numerical libraries against another, not of the files' nine
digits: a fresh install (numpy 2.4.6, scipy 1.17.1 and their BLAS, 2026-11-28) moved the
built-in model's eigenproblem in the eighth digit and a mode's energy near its node by up to
1.6e-6 against the files the session before wrote; a change of the physics or a slip of a
refactor moves a number by 1e-3 or more."""
FLOOR = 1e-6
"""Absolute tolerance as a share of a column's largest magnitude: a mode's energy near its node
line goes with the square of a small shape value and moves more (the same install: a 3-node
bending energy of 5.4e-6 J by 2e-5 relative; a twisting mode on
the long axis, 1e-31 J on one build, 2e-29 J on another)."""
UNRECORDED = {"created_utc", "racketdyn_version", "outputs", "command"}
"""run.json keys that differ from run to run or by this change's new files (figures.nc)."""

RUNS = {
    "approx": {"speeds": [10.0, 20.0, 35.0], "racket_speed": [0.0, 2.0, 4.0], "grid": 3},
    "both": {
        "model": "both",
        "speeds": [20.0],
        "supports": ["free", "pinned"],
        "grid": 3,
        "engine": "reference",
    },
}


REFERENCE = Path(__file__).parent / "data" / "predict_before_issue23"

# the reference files were written before frame shots were marked (issue 22, third session):
# the refactor's numbers are what is held, at every point of the 3 × 3 grid
pytestmark = pytest.mark.usefixtures("strings_only")


def _number(text: str) -> float | None:
    try:
        return float(text)
    except ValueError:
        return None


def _same(before: Any, after: Any, where: str) -> list[str]:
    if isinstance(before, dict):
        missing = [f"{where}.{k}: missing" for k in before if k not in after]
        return missing + [
            problem
            for key, value in before.items()
            if key not in UNRECORDED and key in after
            for problem in _same(value, after[key], f"{where}.{key}")
        ]
    if isinstance(before, list):
        if not isinstance(after, list) or len(before) != len(after):
            return [f"{where}: {before!r} -> {after!r}"]
        return [
            p
            for k, (u, v) in enumerate(zip(before, after, strict=True))
            for p in _same(u, v, f"{where}[{k}]")
        ]
    if isinstance(before, bool) or not isinstance(before, int | float):
        return [] if isinstance(before, str) else ([] if before == after else [f"{where}"])
    if isinstance(after, int | float) and (
        math.isclose(before, after, rel_tol=RTOL, abs_tol=1e-300)
        or (math.isnan(before) and math.isnan(after))
    ):
        return []
    return [f"{where}: {before!r} -> {after!r}"]


@pytest.mark.parametrize("run", sorted(RUNS))
@pytest.mark.slow
def test_predict_numbers_are_those_before_the_refactor(run: str, tmp_path: Path) -> None:
    reference = REFERENCE / run
    logging.disable(logging.WARNING)
    try:
        run_predict(tmp_path, options=PredictOptions(**RUNS[run]))  # type: ignore[arg-type]
    finally:
        logging.disable(logging.NOTSET)
    problems: list[str] = []
    for table in sorted(reference.glob("*.csv")):
        with table.open(encoding="utf-8") as f:
            before = list(csv.reader(f))
        with (tmp_path / table.name).open(encoding="utf-8") as f:
            after = list(csv.reader(f))
        assert before[0] == after[0], f"{table.name}: columns changed"
        assert len(before) == len(after), f"{table.name}: rows changed"
        scale = [
            max((abs(x) for row in before[1:] if (x := _number(row[c])) is not None), default=0)
            for c in range(len(before[0]))
        ]
        for r, (old, new) in enumerate(zip(before[1:], after[1:], strict=True), 1):
            for c, (column, u, v) in enumerate(zip(before[0], old, new, strict=True)):
                x, y = _number(u), _number(v)
                if x is None or y is None:
                    ok = u == v
                else:
                    floor = max(FLOOR * scale[c], 1e-300) if math.isfinite(scale[c]) else 1e-300
                    ok = math.isclose(x, y, rel_tol=RTOL, abs_tol=floor) or (
                        math.isnan(x) and math.isnan(y)
                    )
                if not ok:
                    problems.append(f"{table.name} row {r} {column}: {u} -> {v}")
    record = json.loads((reference / "run.json").read_text(encoding="utf-8"))
    problems += _same(
        record, json.loads((tmp_path / "run.json").read_text(encoding="utf-8")), "run.json"
    )
    assert not problems, "\n".join(problems[:40])
