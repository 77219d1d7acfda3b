"""Where the shared real measurements are (read-only; never copied into the repository).

``<repository root>/../shared/realdata`` or the folder the environment variable
``RACKETDYN_REALDATA`` names; a test that needs them is skipped where they are absent.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

REPOSITORY = Path(__file__).resolve().parents[1]


def realdata_dir() -> Path:
    """The folder of the shared real measurements, or :func:`pytest.skip` when there is none."""
    given = os.environ.get("RACKETDYN_REALDATA")
    folder = Path(given) if given else REPOSITORY.parent / "shared" / "realdata"
    if not folder.is_dir():
        pytest.skip(f"no real measurements at {folder} (set RACKETDYN_REALDATA)")
    return folder.resolve()
