"""Inputs, defaults and versions: every run.json, and the files of every folder with hashes."""

from __future__ import annotations

import json
import platform
import shlex
from datetime import UTC, datetime
from typing import Any

import numpy as np

from racketdyn.__about__ import __version__
from racketdyn.report.folder import REPORT_NAME, RunFolder
from racketdyn.report.formatting import fmt
from racketdyn.workflows.run import sha256

HOW_TO_RUN = "any racketdyn command with --out (each writes run.json)"

RUN_KEYS = ("racketdyn_version", "created_utc", "command", "python", "numpy", "outputs")
"""Keys of a run.json shown in a run's header line, not among its inputs."""


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
        inputs = []
        for key, value in record.items():
            if key in RUN_KEYS or key in ("racket", "defaults_used"):
                continue
            if isinstance(value, dict | list):
                text = json.dumps(value, default=str, separators=(", ", ": "))
                text = text if len(text) <= 300 else text[:300] + " …"
            else:
                text = "not set" if value is None else fmt(value, "g")
            inputs.append((key, text, key.endswith("sha256")))
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
                "inputs": inputs,
                "files": files,
                "unlisted": any(f[2] == "no" for f in files),
            }
        )
    return {
        "written": datetime.now(UTC).isoformat(timespec="seconds"),
        "version": __version__,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "folder": str(run.run_dir.resolve()),
        "other_versions": sorted(versions) if versions - {__version__} else [],
        "runs": runs,
    }
