"""Inputs, defaults and versions: every run.json, and the files of every folder with hashes."""

from __future__ import annotations

import platform
import shlex
from datetime import UTC, datetime
from typing import Any

import numpy as np

from racketdyn.__about__ import __version__
from racketdyn.report.folder import REPORT_NAME, RunFolder
from racketdyn.report.formatting import quantity
from racketdyn.workflows.run import sha256

HOW_TO_RUN = "any racketdyn command with --out (each writes run.json)"

RUN_KEYS = ("racketdyn_version", "created_utc", "command", "python", "numpy", "outputs")
"""Keys of a run.json shown in a run's header line, not among its inputs."""
MAX_ITEMS = 24
"""Items of a list shown in one cell; the rest are counted."""
MAX_TEXT = 400
"""Characters of one cell; longer text is cut with an ellipsis."""

Input = tuple[str, str, str, str, bool]
"""A row of a run's inputs: label, value, unit, the key in run.json, whether it is a hash."""


def inputs(record: dict[str, Any]) -> list[Input]:
    """A run.json's inputs as table rows: nested tables flattened to "table: key" rows (a list
    of tables to a row per item), numbers to 4 significant figures in the page's unit of the
    quantity their key's suffix names (g, mm, ms, kg·cm², °, damping in %), lists joined, text
    as it is. Keys under a file name (the ``columns`` of a
    CSV) are column names and stay as they are."""
    rows: list[Input] = []
    for key, value in record.items():
        if key not in RUN_KEYS and key not in ("racket", "defaults_used"):
            _add(rows, key, value, "", "", verbatim=False)
    return rows


def _add(rows: list[Input], key: str, value: Any, label: str, path: str, verbatim: bool) -> None:
    verbatim = verbatim or "." in key  # a file name, and the column names under it
    name = key if verbatim else quantity(key, None)[0]
    label = f"{label}: {name}" if label else name
    path = f"{path}.{key}" if path else key
    if isinstance(value, dict) and value:
        for sub, subvalue in value.items():
            _add(rows, str(sub), subvalue, label, path, verbatim)
        return
    if isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
        for i, item in enumerate(value[:MAX_ITEMS], start=1):
            rows.append((f"{label} {i}", _clip(_text(key, item)[0]), "", f"{path}[{i - 1}]", False))
        if len(value) > MAX_ITEMS:
            rows.append((label, f"… ({len(value)} in all)", "", path, False))
        return
    text, unit = _text(key, value)
    rows.append((label, _clip(text), unit, path, key.endswith("sha256")))


def _clip(text: str) -> str:
    return text if len(text) <= MAX_TEXT else text[:MAX_TEXT].rstrip() + " …"


def _text(key: str, value: Any) -> tuple[str, str]:
    """(text, unit) of one value of ``key``: a list item by item, a table inline (text as it
    is, numbers with their name and unit)."""
    if isinstance(value, dict):
        parts = []
        for sub, subvalue in value.items():
            label, (text, unit) = quantity(str(sub), None)[0], _text(str(sub), subvalue)
            numeric = not isinstance(subvalue, str | dict)
            parts.append(f"{label} {text}{' ' + unit if unit else ''}" if numeric else text)
        return (", ".join(parts) or "none"), ""
    if isinstance(value, list):
        _, shown, unit = quantity(key, value[:MAX_ITEMS])
        if not value:
            return "none", ""
        if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in value):
            items = [_text(key, item) for item in value[:MAX_ITEMS]]
            nested = any(isinstance(item, dict | list) for item in value)
            shown = ("; " if nested else ", ").join(
                f"({text})" if isinstance(item, list) else text
                for (text, _), item in zip(items, value, strict=False)
            )
            units = {u for _, u in items}
            unit = (
                units.pop() if len(units) == 1 and all(isinstance(v, list) for v in value) else ""
            )
        if len(value) > MAX_ITEMS:
            shown += f", … ({len(value)} in all)"
        return shown, unit
    _, text, unit = quantity(key, value)
    return text, unit


def gather(run: RunFolder) -> dict[str, Any] | None:
    """One block per run.json, in the order the runs were made: the command, versions, inputs,
    defaults used, and the folder's files with their size and SHA-256."""
    if not run.records:
        return None
    versions = {str(r.get("racketdyn_version")) for r in run.records.values()}
    # in the order they were run (created_utc is ISO 8601), then by folder
    ordered = sorted(
        run.records.items(), key=lambda item: (str(item[1].get("created_utc")), item[0])
    )
    runs = []
    for folder, record in ordered:
        command = record.get("command")
        outputs = {str(o) for o in record.get("outputs", [])}
        files = [
            (
                path.name,
                f"{path.stat().st_size:,}",
                "yes" if path.name in outputs else "no",
                sha256(path),
            )
            for path in sorted(p for p in folder.iterdir() if p.is_file())
            if path.name != REPORT_NAME
        ]
        runs.append(
            {
                "name": run.rel(folder) if folder != run.run_dir else run.run_dir.name,
                "command": shlex.join(str(c) for c in command) if isinstance(command, list) else "",
                "meta": (
                    f"racketdyn {record.get('racketdyn_version', '?')}, "
                    f"created {record.get('created_utc', '?')}, "
                    f"Python {record.get('python', '?')}, NumPy {record.get('numpy', '?')}"
                ),
                "defaults": [str(d) for d in record.get("defaults_used") or []],
                "inputs": inputs(record),
                "files": files,
                "unlisted": any(f[2] == "no" for f in files),
            }
        )
    steps = [
        (
            s.name,
            run.rel(s.folder) or ".",
            s.label if s.label != s.name else "",
            "given with --steps" if s.given else "found",
        )
        for s in run.steps
    ]
    return {
        "steps": steps,
        "left_out": [(run.rel(folder), why) for folder, why in run.left_out],
        "written": datetime.now(UTC).isoformat(timespec="seconds"),
        "version": __version__,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "folder": str(run.run_dir.resolve()),
        "other_versions": sorted(versions) if versions - {__version__} else [],
        "runs": runs,
    }
