"""Headless Chromium for the report's tests: find it, and load a page offline."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

CHROMIUM_FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--no-first-run",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",
)


def find_chromium() -> str:
    """Debian's headless Chromium: the test is skipped where it is missing, but fails under CI."""
    path = shutil.which("chromium")
    if path is None:
        message = (
            "headless Chromium is not installed (Debian: apt-get install chromium); "
            "the browser tests of the report need it"
        )
        if "CI" in os.environ:
            pytest.fail(f"{message}, and CI must run it")
        pytest.skip(message)
    return path


def browse(
    chromium: str, page: Path, profile: Path, *args: str
) -> subprocess.CompletedProcess[str]:
    """Load ``page`` (a file) in headless Chromium with a fresh profile and extra ``args``."""
    command = [
        chromium,
        *CHROMIUM_FLAGS,
        f"--user-data-dir={profile}",
        *args,
        page.resolve().as_uri(),
    ]
    return subprocess.run(command, capture_output=True, text=True, timeout=120, check=False)
