"""Helpers of the sweep tests: a small spec, bit-for-bit comparison, and faults — a worker
that dies or hangs, a slow method, a CLI runner.

Imported by ``tests/test_sweep_faults.py`` and by the pool's worker processes (the functions
below travel to them by name), and run as a script by the tests that signal a whole sweep
process: ``python tests/sweep_faults.py sweep SPEC ...`` is ``racketdyn sweep SPEC ...`` with
the ``slow`` method registered (here and, through the main module, in every worker).
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import xarray as xr

import racketdyn as rd
import racketdyn.sweep.task as sweep_task
from racketdyn.sweep import SweepSpec, Variable

SLOW_TASK_S = 0.4


def slow(*args: Any) -> Any:
    """The approximate method, SLOW_TASK_S later: a sweep that lasts long enough to signal."""
    time.sleep(SLOW_TASK_S)
    return sweep_task.METHODS["approximate"](*args)


if __name__ in ("__main__", "__mp_main__"):  # run as the script, or its pool's workers
    sweep_task.METHODS.setdefault("slow", slow)


SMALL_SPEC_TOML = """
name = "small"
racket = "builtin"
[impacts]
grid = 4
ball_speeds_mps = [10.0, 25.0]
[variables]
point_mass = { mass_kg = [0.0, 0.005, 0.010], clock = 12 }
e_bg = [0.80, 0.86]
"""
"""The spec of :func:`small_spec` as a file (variables in the same order)."""


def small_spec(racket: rd.Racket, ball: rd.Ball, name: str) -> SweepSpec:
    """2 variables × 3 and 2 values, grid 4 (12 points), 2 speeds, 2 supports: 6 designs."""
    return SweepSpec(
        racket=racket,
        ball=ball,
        locations=racket.head.grid(4),
        ball_speeds=[10.0, 25.0],
        variables=(
            Variable.point_mass([0.0, 0.005, 0.010], clock=12, head=racket.head),
            Variable.scalar("e_bg", [0.80, 0.86]),
        ),
        name=name,
    )


def assert_same_bits(expected: xr.Dataset, actual: xr.Dataset) -> None:
    """Identical datasets, numbers compared bit for bit (NaN included)."""
    xr.testing.assert_identical(expected, actual)
    for name in [*expected.data_vars, *expected.coords]:
        a, b = expected[name].values, actual[name].values
        if a.dtype.kind in "fiu":
            assert a.dtype == b.dtype, name
            assert a.tobytes() == b.tobytes(), f"{name} differs in its bits"
        else:
            assert a.tolist() == b.tolist(), name


def designs_done(out: Path) -> list[int]:
    """The designs recorded as done in the sweep store of ``out`` (none before it exists)."""
    import numpy as np
    import zarr

    try:
        records = zarr.open_group(out / "sweep.zarr", mode="r")["records"]["design"]
        texts = np.asarray(records[:]).tolist()  # type: ignore[index]
    except (FileNotFoundError, KeyError):
        return []
    return [i for i, text in enumerate(texts) if text]


def store_complete(out: Path) -> bool:
    """Whether the sweep store of ``out`` says its run finished."""
    import zarr

    return bool(zarr.open_group(out / "sweep.zarr", mode="r").attrs.get("sweep_complete"))


def chunk_file(out: Path, name: str, design: int, chunk_size: int = 1) -> Path:
    """The file of array ``name`` of the store in ``out`` holding ``design``."""
    ndim = 3 if name == "reduced_mass_kg" else 5
    return out / "sweep.zarr" / name / "c" / str(design // chunk_size) / "/".join("0" * (ndim - 1))


def task_ids(work: Any) -> list[str]:
    """Task ids in what a sweep submits: one task or a batch of them."""
    items = work if isinstance(work, list | tuple) else [work]
    return [str(getattr(item, "task_id", "")) for item in items]


def _first_time(marker: str) -> bool:
    """True once per marker file, across processes (an exclusive create)."""
    try:
        os.close(os.open(marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
    except FileExistsError:
        return False
    return True


def die_once(marker: str, victim: str, fn: Callable[..., Any], *args: Any) -> Any:
    """Run ``fn(*args)``, except that the first worker given task ``victim`` dies at once."""
    if victim in task_ids(args[0]) and _first_time(marker):
        os._exit(3)
    return fn(*args)


def die_always(victim: str, fn: Callable[..., Any], *args: Any) -> Any:
    """Run ``fn(*args)``; a worker given task ``victim`` dies every time."""
    if victim in task_ids(args[0]):
        os._exit(3)
    return fn(*args)


def hang_once(marker: str, victim: str, fn: Callable[..., Any], *args: Any) -> Any:
    """Run ``fn(*args)``, except that the first worker given task ``victim`` hangs."""
    if victim in task_ids(args[0]) and _first_time(marker):
        time.sleep(3600)
    return fn(*args)


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from racketdyn.cli import main

    sys.exit(main(sys.argv[1:]))
