"""The quick loop (``-m "not slow"``) leaves out every test that takes a costly fixture.

A fixture marked :func:`costly.costly` (a rig and its FRFs, a chain of steps, a sweep) makes
each test that takes it ``slow`` (``tests/conftest.py``), so the quick loop stays quick as tests
are added; CI runs every test once.
"""

from __future__ import annotations

import pytest

from costly import COSTLY


def _costly_fixtures(item: pytest.Item) -> set[str]:
    info = getattr(item, "_fixtureinfo", None)
    if info is None:
        return set()
    return {
        name
        for name, definitions in info.name2fixturedefs.items()
        if any(getattr(d.func, COSTLY, False) for d in definitions)
    }


def test_every_test_taking_a_costly_fixture_is_slow(request: pytest.FixtureRequest) -> None:
    items = request.session.items
    taking = [item for item in items if _costly_fixtures(item)]
    if not any(item.path.name == "test_report_steps.py" for item in items):
        pytest.skip("run with the whole suite: no test of a costly fixture collected")
    assert taking
    assert all(item.get_closest_marker("slow") for item in taking)
    # and this test, which takes none, is not
    assert request.node.get_closest_marker("slow") is None
