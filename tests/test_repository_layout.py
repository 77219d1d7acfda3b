"""The repository holds only its own tree: no run folder or output a command left behind and a
commit picked up (a stray ``o/`` with a run's oblique.png, run.json and figures.nc was
committed once)."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TOP_LEVEL = {
    ".ci",
    ".gitignore",
    "CHANGELOG.md",
    "LICENSE",
    "README.md",
    "benchmarks",
    "docs",
    "pyproject.toml",
    "src",
    "tests",
}
"""Every top-level entry a commit may hold."""


def _tracked() -> list[str]:
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("not a git checkout")
    done = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True)
    if done.returncode != 0:  # e.g. git refusing a checkout another user owns
        pytest.skip(f"git ls-files: {done.stderr.strip()}")
    return done.stdout.splitlines()


def test_the_repository_holds_only_its_own_tree() -> None:
    stray = sorted({name.split("/")[0] for name in _tracked()} - TOP_LEVEL)
    assert not stray, f"files outside the project's tree are tracked: {stray}"


def test_no_run_folder_is_tracked() -> None:
    runs = [name for name in _tracked() if name.endswith("/run.json")]
    runs = [name for name in runs if not name.startswith(("tests/data/", "docs/"))]
    assert not runs, f"run folders are tracked: {runs}"
