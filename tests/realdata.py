"""The real measured files of other labs (read-only, never copied into the repository).

They lie in ``<repository>/../shared/realdata`` (its README says what each folder holds and
where it comes from), or wherever the environment variable ``RACKETDYN_REALDATA`` points.  A
test that uses them skips when the folder is absent.
"""

from __future__ import annotations

import lzma
import os
import shutil
from pathlib import Path

import pytest

REPOSITORY = Path(__file__).resolve().parents[1]
ENVIRONMENT_VARIABLE = "RACKETDYN_REALDATA"


def folder() -> Path:
    """The real-data folder; skips the calling test when it is absent."""
    given = os.environ.get(ENVIRONMENT_VARIABLE)
    path = Path(given) if given else REPOSITORY.parent / "shared" / "realdata"
    if not path.is_dir():
        pytest.skip(f"real data not found at {path} (set {ENVIRONMENT_VARIABLE})")
    return path


def file(relative: str, tmp_path: Path) -> Path:
    """One real file, decompressed into ``tmp_path`` when it is ``.xz`` (else the file itself:
    the readers only read it).  Skips when the file is absent."""
    source = folder() / relative
    if not source.is_file():
        pytest.skip(f"real data file {relative} not found in {source.parent}")
    if source.suffix != ".xz":
        return source
    target = tmp_path / source.with_suffix("").name
    if not target.exists():
        with lzma.open(source) as packed, target.open("wb") as unpacked:
            shutil.copyfileobj(packed, unpacked)
    return target


def realdata_dir() -> Path:
    """The real-data folder, resolved (:func:`folder`; skips when absent)."""
    return folder().resolve()
