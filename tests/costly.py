"""Costly fixtures: a test that takes one is marked ``slow`` (``tests/conftest.py``).

The quick loop, ``python -m pytest -n auto --dist loadgroup -m "not slow"``, leaves out the
end-to-end runs (a rig and its FRFs, a chain of steps, a demo-like folder, a sweep) that CI runs
once with the rest.  A fixture that costs a few seconds or more to build is marked where it is
defined, so every test that takes it — today's and tomorrow's — is slow with it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

__all__ = ["COSTLY", "costly"]

COSTLY = "_racketdyn_costly_fixture"
"""The attribute :func:`costly` sets on a fixture's function."""

F = TypeVar("F", bound=Callable[..., Any])


def costly(function: F) -> F:
    """Mark a fixture's function as costly (put it under ``@pytest.fixture``)."""
    setattr(function, COSTLY, True)
    return function
