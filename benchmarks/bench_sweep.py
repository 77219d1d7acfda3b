"""Throughput of a design sweep, ``racketdyn.sweep.run_sweep``, on each engine, in one run.

Run with ``python benchmarks/bench_sweep.py``.  A sweep of 1,000,000 impacts — 100 designs
(lead tape 0–9 g at 12 o'clock × ten frame stiffnesses, so every design builds its own modal
model) × 100 impact points × 50 ball speeds × 2 supports — by the approximate method, run on
this process (serial), a local process pool of 1 and 2 workers, and a local Dask cluster of 1
and 2 single-threaded workers.  Each run starts from an empty folder and includes starting the
engine, writing every part file and combining them into ``sweep.nc`` (no figures).  Prints
impacts per second and the ratio against serial, checks that every engine wrote the same
numbers, and splits one serial task into its steps.

``python benchmarks/bench_sweep.py --method transient --designs 10`` times the transient
model (compiled engine) the same way on 100,000 impacts (measured: ≈ 16,000 impacts/s serial,
1.35× with a process pool of 2).  Informational: the exit status is 0 whatever the timings.
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import platform
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr

import racketdyn
from racketdyn.sweep import (
    METHODS,
    SweepSpec,
    Variable,
    make_executor,
    run_sweep,
    run_task,
)

N_POINTS = 100
GRID_N = 12  # a 12 × 12 grid keeps 112 points on the ellipse; the first 100 are used
SPEEDS = np.linspace(5.0, 50.0, 50)
SUPPORTS = ("free", "pinned")
LEAD_KG = np.arange(10) * 1e-3  # 0–9 g
STIFFNESS = np.linspace(0.8, 1.25, 10)
ENGINES = (
    ("serial", "serial", 1),
    ("process pool, 1 worker", "process", 1),
    ("process pool, 2 workers", "process", 2),
    ("local Dask, 1 worker", "dask-local", 1),
    ("local Dask, 2 workers", "dask-local", 2),
)


def build_spec(n_designs: int, method: str) -> SweepSpec:
    """The benchmark sweep: ``n_designs`` designs (at most 100) × 100 points × 50 × 2."""
    racket = racketdyn.default_racket()
    points = racket.head.grid(GRID_N)[:N_POINTS]
    if len(points) != N_POINTS:
        raise SystemExit(f"grid {GRID_N} gives only {len(points)} points; raise GRID_N")
    n_lead = max(1, min(len(LEAD_KG), n_designs // len(STIFFNESS)))
    n_stiff = max(1, min(len(STIFFNESS), -(-n_designs // n_lead)))
    return SweepSpec(
        racket=racket,
        ball=racketdyn.Ball(),
        locations=points,
        ball_speeds=SPEEDS,
        supports=SUPPORTS,
        variables=(
            Variable.point_mass(LEAD_KG[:n_lead], clock=12, head=racket.head),
            Variable.scalar("frame_stiffness_scale", STIFFNESS[:n_stiff]),
        ),
        method=method,
        name="bench_sweep",
    )


def time_engine(spec: SweepSpec, kind: str, workers: int, out: Path) -> tuple[float, float, float]:
    """Wall time of the whole sweep, of starting the engine, and the tasks' own time summed, s."""
    start = time.perf_counter()
    with make_executor(kind, workers) as executor:  # type: ignore[arg-type]
        started = time.perf_counter()
        run_sweep(spec, out, executor, figures=None)
    wall = time.perf_counter() - start
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    return wall, started - start, float(record["task_time_s"])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=100, help="designs (default 100)")
    parser.add_argument(
        "--method", default="approximate", help=f"impact method: {', '.join(METHODS)}"
    )
    args = parser.parse_args()
    # predict logs a warning per task for impacts beyond the restoring-force law (the fastest
    # speeds); distributed logs its start-up; neither is timed output.
    logging.getLogger("racketdyn").setLevel(logging.ERROR)
    logging.getLogger("distributed").setLevel(logging.ERROR)
    spec = build_spec(args.designs, args.method)
    n_impacts = spec.n_impacts
    print(
        f"racketdyn {racketdyn.__version__}, numpy {np.__version__}, xarray {xr.__version__}, "
        f"Python {platform.python_version()}, {os.cpu_count()} CPUs"
    )
    print(
        f"sweep: {len(spec.designs)} designs × {N_POINTS} points × {SPEEDS.size} speeds × "
        f"{len(SUPPORTS)} supports = {n_impacts:,} impacts, method {spec.method!r}; "
        "one task per design, one BLAS thread per task"
    )
    print()

    # One serial task, step by step (the first builds nothing cached).
    task = spec.task(spec.designs[-1])
    start = time.perf_counter()
    output = run_task(task)
    first = time.perf_counter() - start
    start = time.perf_counter()
    run_task(task)
    cached = time.perf_counter() - start
    per_task = spec.impacts_per_design
    print(f"one task ({per_task:,} impacts), in this process")
    print(f"  first call          {first * 1e3:8.1f} ms  (modal model, law, predict)")
    print(f"  same design again   {cached * 1e3:8.1f} ms  (modal model and law cached)")
    ok = int(np.sum(output.arrays["status"] == 0))
    print(f"  impacts ok          {ok:,} of {per_task:,} (the rest NaN with a status code)")
    print()

    results: dict[str, tuple[float, float, float]] = {}
    datasets: dict[str, xr.Dataset] = {}
    with tempfile.TemporaryDirectory(prefix="bench_sweep_") as scratch:
        for label, kind, workers in ENGINES:
            out = Path(scratch) / f"{kind}-{workers}"
            results[label] = time_engine(spec, kind, workers, out)
            with xr.open_dataset(out / "sweep.nc", engine="scipy") as written:
                datasets[label] = written[["rebound_ratio", "vibration_energy_j"]].load()
    serial_s = results["serial"][0]
    print(
        f"{'engine':<26}{'wall s':>8}{'start s':>9}{'tasks s':>9}{'impacts/s':>12}{'vs serial':>11}"
    )
    for label, (wall, startup, tasks) in results.items():
        print(
            f"{label:<26}{wall:8.2f}{startup:9.2f}{tasks:9.2f}{n_impacts / wall:12,.0f}"
            f"{serial_s / wall:10.2f}×"
        )
    print("wall: engine start, all tasks, part files and sweep.nc.  start: the engine alone (a")
    print("process pool starts its workers with the first task, inside the wall).  tasks: the")
    print("tasks' own time summed over workers, as measured where they ran.")
    reference = datasets["serial"]
    same = all(
        reference[name].values.tobytes() == other[name].values.tobytes()
        for other in datasets.values()
        for name in reference.data_vars
    )
    print()
    print(f"identical results on every engine: {'yes' if same else 'NO'}")
    if "transient" not in METHODS:
        print(
            "transient method: not available yet (issue 5); once it registers in "
            "racketdyn.sweep.METHODS, rerun with --method transient"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
