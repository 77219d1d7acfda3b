"""Shared fixtures: the built-in racket, the default ball and their modal model (built once)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

import racketdyn as rd

if TYPE_CHECKING:
    from collections.abc import Iterator

    import xarray as xr


@pytest.fixture(scope="session")
def racket() -> rd.Racket:
    return rd.default_racket()


@pytest.fixture(scope="session")
def ball() -> rd.Ball:
    # a given e_BG (Kawazoe's measured 0.83) for the tests of the methods' mechanics, which use
    # ball.e_bg as a number; the e_BG that follows from ball + strings (the default) is tested
    # in test_ball_bounce.py
    return rd.Ball(e_bg=0.83)


@pytest.fixture(scope="session")
def model(racket: rd.Racket) -> rd.ModalModel:
    return rd.modal_model_for(racket)


@pytest.fixture(scope="session")
def law(racket: rd.Racket, ball: rd.Ball) -> rd.RestoringForce:
    return rd.compound_law(racket, ball)


@pytest.fixture(scope="session")
def rig_frf_tree(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """The virtual rig's hammer tests, free and hand-held, and their FRFs
    (``figure_catch.rig_frfs``), built once for the whole run and shared by the modules that
    read them (``test_truth_comparison``, ``test_figure_data``, ``test_redraw_from_folder``:
    three builds of ≈ 10 s each before).  A test may add a folder of its own name beside them
    and change nothing else.  Under pytest-xdist the workers share the run's temporary folder;
    the first to come builds the tree under a lock, the others wait and read it (``filelock``
    is not a dependency, and one ``fcntl`` lock on one file is all this needs)."""
    from figure_catch import rig_frfs

    try:
        import fcntl
    except ImportError:  # not POSIX (Windows): each worker builds its own tree
        fcntl = None  # type: ignore[assignment]
    if os.environ.get("PYTEST_XDIST_WORKER") is None or fcntl is None:
        yield rig_frfs(tmp_path_factory.mktemp("rig_frfs"))
        return

    shared = tmp_path_factory.getbasetemp().parent  # the run's folder, above each worker's
    tree, done = shared / "rig_frfs", shared / "rig_frfs.done"
    with (shared / "rig_frfs.lock").open("w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            if not done.exists():
                rig_frfs(tree)
                done.touch()
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
    yield tree


@pytest.fixture(scope="module")
def small_spec(racket: rd.Racket) -> rd.sweep.SweepSpec:
    """A sweep of 6 designs (tests/sweep_faults.py), for the sweep tests."""
    import sweep_faults

    # the spec file's ball (sweep_faults.SMALL_SPEC_TOML gives none): e_BG from ball + strings
    return sweep_faults.small_spec(racket, rd.Ball(), "small")


@pytest.fixture(scope="module")
def serial_result(
    small_spec: rd.sweep.SweepSpec, tmp_path_factory: pytest.TempPathFactory
) -> xr.Dataset:
    """``small_spec`` run in this process."""
    from racketdyn.sweep import SerialExecutor, run_sweep

    return run_sweep(small_spec, tmp_path_factory.mktemp("serial"), SerialExecutor(), figures=None)


@pytest.fixture
def strings_only(monkeypatch: pytest.MonkeyPatch) -> None:
    """The ball meets the strings only, wherever it lands: no frame shots
    (``STATUS_FRAME_CONTACT``).  For tests of the contact's mechanics — analytic limits with
    laws far softer than a ball's, the integrator at points near the hoop, numbers fixed
    before frame shots were marked — where the geometry of the hoop is not what is tested."""
    import numpy as np

    from racketdyn.impact.grid import ImpactGrid

    monkeypatch.setattr(
        ImpactGrid, "reaches_frame", lambda self, deflection: np.zeros(np.shape(deflection), bool)
    )


@pytest.fixture
def smooth_frame(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """The built-in frame as it was before issue 22's fourth session: mass along the racket the
    smallest departure from a uniform beam, uniform EI (``mass_model`` "smooth").  For tests
    that hold machinery where an earlier frame put it — the flags of a tip that lost more than
    e_BG to vibration, a second contact — not the frame's physics."""
    from racketdyn.impact import measured
    from racketdyn.racket_modal import beam

    monkeypatch.setattr(beam, "frame_mass_per_length", lambda *args, **kwargs: None)
    measured._built_in_modes.cache_clear()
    yield
    measured._built_in_modes.cache_clear()


# Tests that start whole sweeps, clusters or commands in other processes and signal them
# (Ctrl-C, SIGKILL, a cluster's scheduler and workers) run one after another on one
# pytest-xdist worker (``--dist loadgroup``): two of them at once put a pool, a local Dask
# cluster and their deadlines on two cores together (three of them failed so once, none alone).
PROCESS_TESTS = {
    "test_sweep_faults.py",
    "test_sweep_cluster.py",
    "test_sweep_start.py",
    "test_cli_interrupt.py",
    # a pytest with two xdist workers of its own: 2 s alone, 10-49 s when it started last,
    # beside both workers of the suite, where it was the suite's tail (a one-test unit is sent
    # after the groups); in this group it runs early, on the group's worker
    "test_xdist_groups.py",
}


@pytest.hookimpl(tryfirst=True)  # before pytest-xdist reads the groups into the test ids
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if _takes_costly_fixture(item):
            item.add_marker(pytest.mark.slow)
        if item.path.name in PROCESS_TESTS:
            item.add_marker(pytest.mark.xdist_group("processes"))
        elif _has_module_fixture(item):
            item.add_marker(pytest.mark.xdist_group(item.path.name))


def _takes_costly_fixture(item: pytest.Item) -> bool:
    """Whether the test takes a fixture marked :func:`costly.costly` (then it is ``slow``)."""
    from costly import COSTLY

    info = getattr(item, "_fixtureinfo", None)
    if info is None:
        return False
    return any(
        getattr(definition.func, COSTLY, False)
        for definitions in info.name2fixturedefs.values()
        for definition in definitions
    )


def _has_module_fixture(item: pytest.Item) -> bool:
    """Whether the test uses a module-scoped fixture of its own module (a rig, FRFs, an
    identification, a demo-like folder): its module's tests then run on one pytest-xdist
    worker, so that the fixture is computed once, not once per worker (``--dist loadgroup``
    spread them: the report test's 39 s folder, the lab's 22 s chain and four more were
    computed twice each on two workers)."""
    info = getattr(item, "_fixtureinfo", None)
    if info is None:
        return False
    return any(
        definition.scope == "module" and definition.baseid.endswith(item.path.name)
        for definitions in info.name2fixturedefs.values()
        for definition in definitions
    )
