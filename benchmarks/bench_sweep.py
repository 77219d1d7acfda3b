"""Throughput and memory of a design sweep, ``racketdyn.sweep.run_sweep``, in one run.

Run with ``python benchmarks/bench_sweep.py``.  A sweep of 1,000,000 impacts — 100 designs
(lead tape 0–9 g at 12 o'clock × ten frame stiffnesses, so every design builds its own modal
model) × 100 impact points × 50 ball speeds × 2 supports — by the approximate method, run on
this process (serial), a local process pool of 1 and 2 workers, and a local Dask cluster of 1
and 2 single-threaded workers.  Each run starts from an empty folder and includes starting the
engine, writing every chunk of the store ``sweep.zarr`` and finishing it (no figures).  Prints
impacts per second and the ratio against serial, checks that every engine wrote the same
numbers (the store's contents to the bit), and splits one serial task into its steps.

Memory (issue 28): the peak resident memory of the main process and of each worker over a
whole sweep on two workers (a process pool, or ``--memory-engine dask-local``), summary
included, at 10⁶ and 10⁷ impacts (100 and 1,000 designs of 10⁴ impacts; ten values of e_BG
multiply the designs), against baselines measured in the same run just before each sweep;
the slope between the two projects 10⁸ impacts.  Then reading from the 10⁷-impact store: one
design's map and one point across all designs, opened afresh each time (median of 5).  Linux
only (``/proc/PID/status``'s VmHWM, reset through ``/proc/PID/clear_refs``).  ``--part
speed`` or ``--part memory`` runs one half.

``--scheduler ADDRESS`` adds two runs on a running Dask cluster to the speed part (its chunks
written by the main process, then with ``shared_store``, the workers writing them) and to the
check of the bits.

``python benchmarks/bench_sweep.py --method transient --designs 10`` times the transient
model (compiled engine) the same way on 100,000 impacts.  Prints, per engine, where the wall
time went (start, tasks, part writing, combining), the speed-up from 1 to 2 workers for the
process pool and local Dask, and whether every engine wrote the same bits (the results do
not depend on the engine nor on the number of workers).  Informational: the exit status is 0
whatever the timings.
"""

from __future__ import annotations

import argparse
import gc
import json
import logging
import os
import platform
import shutil
import tempfile
import time
from contextlib import ExitStack
from pathlib import Path

import numpy as np
import xarray as xr

import racketdyn
from racketdyn.sweep import (
    METHODS,
    SweepSpec,
    TaskOptions,
    Variable,
    make_executor,
    open_sweep,
    run_sweep,
    run_task,
    start_early,
)

N_POINTS = 100
GRID_N = 12  # a 12 × 12 grid keeps 112 points on the ellipse; the first 100 are used
SPEEDS = np.linspace(5.0, 50.0, 50)
SUPPORTS = ("free", "pinned")
LEAD_KG = np.arange(10) * 1e-3  # 0–9 g
STIFFNESS = np.linspace(0.8, 1.25, 10)
E_BG = np.linspace(0.80, 0.89, 10)
OLD_BYTES_PER_IMPACT = 245
"""The main process's peak over its baseline per impact before the store (parts combined
into sweep.nc in memory): 233 MB over 187 MB at 10⁶ impacts on a pool of two workers,
measured 2026-11-28 with this benchmark's study; issue 28 quotes 330 B at 2.2 × 10⁶."""


CLUSTER_MAIN, CLUSTER_SHARED = "cluster, main writes", "cluster, shared store"
"""The labels of the runs on a running cluster (``--scheduler``): workers 0 and 1."""


def engines_in_order(repeat: int, cluster: bool = False) -> list[tuple[str, str, int, int]]:
    """(label, engine, workers, repeat) in the order run: serial once, then each engine's
    1- and 2-worker runs alternately, ``repeat`` pairs; with ``cluster``, runs on a running
    cluster with the main process writing the chunks (workers 0) and the workers (1),
    alternately."""
    order = [("serial", "serial", 1, 0)]
    for name, kind in (("process pool", "process"), ("local Dask", "dask-local")):
        for r in range(repeat):
            order += [
                (f"{name}, 1 worker", kind, 1, r),
                (f"{name}, 2 workers", kind, 2, r),
            ]
    for r in range(repeat if cluster else 0):
        order += [(CLUSTER_MAIN, "dask", 0, r), (CLUSTER_SHARED, "dask", 1, r)]
    return order


def build_spec(n_designs: int, method: str) -> SweepSpec:
    """The benchmark sweep: ``n_designs`` designs (at most 100; 1,000 with e_BG's ten values
    as a third variable) × 100 points × 50 × 2."""
    racket = racketdyn.default_racket()
    points = racket.head.grid(GRID_N)[:N_POINTS]
    if len(points) != N_POINTS:
        raise SystemExit(f"grid {GRID_N} gives only {len(points)} points; raise GRID_N")
    n_e = max(1, min(len(E_BG), n_designs // (len(LEAD_KG) * len(STIFFNESS))))
    per_e = -(-n_designs // n_e)
    n_lead = max(1, min(len(LEAD_KG), per_e // len(STIFFNESS)))
    n_stiff = max(1, min(len(STIFFNESS), -(-per_e // n_lead)))
    variables = (
        Variable.point_mass(LEAD_KG[:n_lead], clock=12, head=racket.head),
        Variable.scalar("frame_stiffness_scale", STIFFNESS[:n_stiff]),
    )
    if n_e > 1:
        variables += (Variable.scalar("e_bg", E_BG[:n_e]),)
    return SweepSpec(
        racket=racket,
        ball=racketdyn.Ball(),
        locations=points,
        ball_speeds=SPEEDS,
        supports=SUPPORTS,
        variables=variables,
        method=method,
        name="bench_sweep",
    )


def _status_mb(field: str, pid: int | str = "self") -> float:
    with open(f"/proc/{pid}/status", encoding="ascii") as status:
        for line in status:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024
    raise RuntimeError(f"no {field} in /proc/self/status")


def _worker_pids(executor: object) -> list[int]:
    """The worker processes of a process pool or a Dask client's executor."""
    pool = getattr(executor, "_pool", None)
    if pool is not None:
        return sorted(pool._processes)
    client = getattr(executor, "_client", None)
    return sorted(client.run(os.getpid).values()) if client is not None else []


def _reset_peak(pid: int | str) -> float:
    """Reset a process's peak resident memory to its current one (VmHWM := VmRSS); MB."""
    Path(f"/proc/{pid}/clear_refs").write_text("5", encoding="ascii")
    return _status_mb("VmRSS", pid)


def peak_memory(spec: SweepSpec, out: Path, kind: str) -> tuple[float, ...]:
    """(baseline, peak, wall, worker baselines…, worker peaks…): the main process's resident
    memory just before the sweep and its peak during it (summary included, no figures), MB,
    then each worker's, on two workers of the engine ``kind``."""
    with make_executor(kind, 2) as executor:  # type: ignore[arg-type]
        pids = _worker_pids(executor)
        gc.collect()
        worker_base = [_reset_peak(pid) for pid in pids]
        baseline = _reset_peak("self")
        start = time.perf_counter()
        run_sweep(spec, out, executor, figures=None)
        wall = time.perf_counter() - start
        peak = _status_mb("VmHWM")
        worker_peak = [_status_mb("VmHWM", pid) for pid in pids]
    return (baseline, peak, wall, *worker_base, *worker_peak)


def read_times(out: Path, repeat: int = 5) -> dict[str, float]:
    """Seconds to read from a finished store, each opened afresh (median of ``repeat``): one
    design's map of the rebound ratio (one chunk), every quantity of that design, and one
    point's rebound ratio across all designs (a slice of every chunk)."""
    with open_sweep(out) as probe:
        design, point = probe.sizes["design"] // 2 + 1, probe.sizes["point"] // 2
    reads = {
        "one design's map (rebound_ratio)": lambda d: d["rebound_ratio"].isel(design=design),
        "one design, every quantity": lambda d: d.isel(design=design),
        "one point across all designs (rebound_ratio)": lambda d: d["rebound_ratio"].isel(
            point=point
        ),
    }
    times: dict[str, float] = {}
    for name, read in reads.items():
        runs = []
        for _ in range(repeat):
            start = time.perf_counter()
            with open_sweep(out) as dataset:
                read(dataset).load()
            runs.append(time.perf_counter() - start)
        times[name] = sorted(runs)[repeat // 2]
    return times


def memory_part(method: str, kind: str = "process") -> None:
    """Peak memory of the main process and each worker at 10⁶ and 10⁷ impacts; 10⁸
    projected from the slope; then reads from the 10⁷-impact store."""
    if not Path("/proc/self/clear_refs").exists():
        print("memory: needs Linux's /proc/self/clear_refs; skipped")
        return
    rows = []
    workers = []
    reads: dict[str, float] = {}
    with tempfile.TemporaryDirectory(prefix="bench_sweep_memory_") as scratch:
        for n_designs in (100, 1000):
            spec = build_spec(n_designs, method)
            out = Path(scratch) / f"d{n_designs}"
            baseline, peak, wall, *each = peak_memory(spec, out, kind)
            rows.append((spec.n_impacts, baseline, peak, wall))
            half = len(each) // 2
            workers.append((spec.n_impacts, each[:half], each[half:]))
            if n_designs == 1000:
                reads = read_times(out)
            shutil.rmtree(out)
    engine = "pool" if kind == "process" else kind
    print(f"peak resident memory of the main process ({engine} of 2 workers, summary included)")
    print(
        f"{'impacts':>12}{'baseline MB':>13}{'peak MB':>9}{'over MB':>9}{'peak/base':>10}"
        f"{'B/impact':>9}{'wall s':>8}"
    )
    for n, baseline, peak, wall in rows:
        over = peak - baseline
        print(
            f"{n:>12,}{baseline:13.0f}{peak:9.0f}{over:9.1f}{peak / baseline:9.2f}×"
            f"{over * 2**20 / n:9.1f}{wall:8.1f}"
        )
    (n1, b1, p1, _), (n2, b2, p2, _) = rows
    slope = ((p2 - b2) - (p1 - b1)) * 2**20 / (n2 - n1)  # bytes per impact
    # a slope within the noise of a few MB (or below zero) is no growth: 10⁸ as 10⁷
    projected = (p2 - b2) + max(slope, 0.0) * (1e8 - n2) / 2**20
    print(
        f"over the baseline, 10⁷ against 10⁶ impacts: {(p2 - b2) / max(p1 - b1, 1e-9):.2f}× "
        f"for 10× the impacts; slope {slope:.2f} B/impact"
        + (" (none: the peak does not grow with the designs)" if slope <= 0 else "")
    )
    print(
        f"projected at 10⁸ impacts: {projected:.0f} MB over the baseline "
        f"({b2 + projected:.0f} MB in all); with sweep.nc combined in memory "
        f"({OLD_BYTES_PER_IMPACT} B/impact): {OLD_BYTES_PER_IMPACT * 1e8 / 2**30:.1f} GB"
    )
    print(
        f"main process within 1 GB at 10⁷ impacts: {'yes' if p2 < 1024 else 'NO'} "
        f"({p2:.0f} MB in all)"
    )
    print()
    print(f"peak resident memory of each worker ({engine} of 2), over its own baseline")
    print(f"{'impacts':>12}  " + "  ".join(f"{'worker ' + str(k + 1):>24}" for k in range(2)))
    for n, base, peaks in workers:
        cells = [
            f"{b:5.0f} → {p:5.0f} MB (+{p - b:5.1f})" for b, p in zip(base, peaks, strict=True)
        ]
        print(f"{n:>12,}  " + "  ".join(f"{c:>24}" for c in cells))
    (_, b1s, p1s), (_, b2s, p2s) = workers
    over1 = max(p - b for b, p in zip(b1s, p1s, strict=True))
    over2 = max(p - b for b, p in zip(b2s, p2s, strict=True))
    w_slope = (over2 - over1) * 2**20 / (n2 - n1)
    print(
        f"largest worker growth, 10⁷ against 10⁶ impacts: {over2:.1f} against {over1:.1f} MB; "
        f"slope {w_slope:.2f} B/impact → 10⁸ projected "
        f"{over2 + max(w_slope, 0.0) * (1e8 - n2) / 2**20:.0f} MB over a worker's baseline"
    )
    print()
    print(f"reading from the {n2:,}-impact store (opened afresh each time, median of 5)")
    for name, seconds in reads.items():
        print(f"  {name:<46}{seconds:7.3f} s")
    quick = all(v < 1.0 for k, v in reads.items() if "every quantity" not in k)
    print(
        "one design's map and one point across all designs under a second: "
        + ("yes" if quick else "NO")
    )


def start_dask_forkserver(method: str) -> float:
    """Start the forkserver local Dask forks its workers from, as the command does, and wait
    until it has imported what it preloads (a first child started and ended); seconds."""
    import multiprocessing

    clock = time.perf_counter()
    start_early("dask-local", method)
    child = multiprocessing.get_context("forkserver").Process(target=os.getpid)
    child.start()
    child.join()
    return time.perf_counter() - clock


def time_engine(
    spec: SweepSpec, kind: str, workers: int, out: Path, scheduler: str | None = None
) -> dict[str, float]:
    """Wall time of the whole sweep (engine start and shutdown included) and where it went, s:
    ``start`` (the engine), ``first`` (first result after the first submission: a pool starts
    its workers then), ``tasks`` (submission to last result), ``write`` (chunks of the store,
    summed over workers), ``finish`` (finishing the store), ``busy`` (the tasks' own time
    summed).  ``kind`` "dask": the cluster at ``scheduler``, the workers writing the chunks
    (``shared_store``) if ``workers`` is 1, else the main process."""
    start = time.perf_counter()
    with ExitStack() as stack:  # as the command: the engine closes before finishing
        engine = (
            make_executor("dask", scheduler=scheduler)
            if kind == "dask"
            else make_executor(kind, workers)  # type: ignore[arg-type]
        )
        executor = stack.enter_context(engine)
        started = time.perf_counter() - start
        run_sweep(
            spec,
            out,
            executor,
            options=TaskOptions(shared_store=kind == "dask" and workers == 1),
            figures=None,
            times={"start": started},
            when_tasks_done=stack.close,
        )
    wall = time.perf_counter() - start
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    spent = record["time_s"]
    return {
        "wall": wall,
        "start": started,
        "first": float(record["first_result_s"]),
        "tasks": float(spent["tasks"]),
        "write": float(record["chunk_write_time_s"]),
        "finish": float(spent["finishing"]),
        "shutdown": float(spent.get("shutdown", 0.0)),
        "busy": float(record["task_time_s"]),
        "per_task": float(record["designs_per_task"]),
        "fork": float(record["worker_start_method"] == "fork"),
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=100, help="designs (default 100)")
    parser.add_argument(
        "--repeat",
        type=int,
        default=3,
        help="pairs of 1- and 2-worker runs per engine (default 3): a run varies by ±5 %%",
    )
    parser.add_argument(
        "--method", default="approximate", help=f"impact method: {', '.join(METHODS)}"
    )
    parser.add_argument(
        "--memory-engine",
        choices=("process", "dask-local"),
        default="process",
        help="the two workers of the memory part (default: a process pool)",
    )
    parser.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="also run the speed part's study on this running Dask cluster, its chunks "
        "written by the main process and then by the workers (shared_store)",
    )
    parser.add_argument(
        "--part",
        choices=("both", "speed", "memory"),
        default="both",
        help="the engines' speed, the main process's memory, or both (default)",
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
        "designs grouped into tasks by size, one BLAS thread per task"
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
    if args.part in ("both", "memory"):  # before any Dask client leaves threads here
        memory_part(args.method, args.memory_engine)
        print()
    if args.part == "memory":
        return 0

    # A local Dask cluster forks its workers from a forkserver that imports distributed and
    # racketdyn once per process (the command starts it while it reads the spec): started
    # here, before any clock, so that 1 and 2 Dask workers start alike; its time is printed
    # apart.  A process pool forks its workers from this process (single-threaded here).
    print(
        f"forkserver for local Dask (once per process, not in the table): "
        f"{start_dask_forkserver(args.method):.2f} s"
    )
    # Serial once, then each engine's 1- and 2-worker runs alternately, ``--repeat`` pairs:
    # one run on this shared machine varies by ±5 %, as much as the gap to be measured.  The
    # pools run before Dask: a Dask client leaves a thread in this process, after which a
    # pool may not fork (it takes the forkserver, as the command would).
    runs: dict[str, list[dict[str, float]]] = {}
    same = True
    reference: xr.Dataset | None = None
    with tempfile.TemporaryDirectory(prefix="bench_sweep_") as scratch:
        for label, kind, workers, repeat in engines_in_order(args.repeat, bool(args.scheduler)):
            out = Path(scratch) / f"{kind}-{workers}-{repeat}"
            timed = time_engine(spec, kind, workers, out, args.scheduler)
            runs.setdefault(label, []).append(timed)
            with open_sweep(out) as written:  # the store's contents, to the bit
                if reference is None:
                    reference = written.load()
                else:
                    same &= all(
                        reference[name].values.tobytes() == written[name].values.tobytes()
                        for name in [*reference.data_vars, *reference.coords]
                        if reference[name].dtype.kind in "fiu"
                    )
            shutil.rmtree(out)
    serial_s = runs["serial"][0]["wall"]
    print(
        f"{'engine (median run)':<26}{'wall s':>7}{'start':>7}{'first':>7}{'tasks':>7}"
        f"{'write':>7}{'stop':>6}{'finish':>8}{'busy':>7}{'per task':>9}{'impacts/s':>11}"
        f"{'vs serial':>10}"
    )
    for label, timed in runs.items():
        t = sorted(timed, key=lambda run: run["wall"])[len(timed) // 2]
        print(
            f"{label:<26}{t['wall']:7.2f}{t['start']:7.2f}{t['first']:7.2f}{t['tasks']:7.2f}"
            f"{t['write']:7.2f}{t['shutdown']:6.2f}{t['finish']:8.2f}{t['busy']:7.2f}"
            f"{t['per_task']:9.0f}{n_impacts / t['wall']:11,.0f}{serial_s / t['wall']:9.2f}×"
        )
    print("wall: the whole sweep, engine start and shutdown included.  start: the engine alone")
    print("(a pool starts its workers with the first task: see first, the first result after")
    print("the first submission).  tasks: first submission to last result.  write: chunks of")
    print("the store, summed over the workers that wrote them.  stop: the engine's shutdown,")
    print("before finishing (a local Dask scheduler in this process slows it).  finish: the")
    print("store's mode table, status counts and completion mark.  busy: the tasks' own time")
    print("summed over workers.  per task: designs per task (= per chunk of the store).")
    forked = all(t["fork"] for label, timed in runs.items() if "pool" in label for t in timed)
    print(
        "process pool workers forked from this process: "
        f"{'yes' if forked else 'NO (it ran threads: forkserver)'}"
    )
    print()
    for kind in ("process pool", "local Dask"):
        one, two = runs[f"{kind}, 1 worker"], runs[f"{kind}, 2 workers"]
        ratios = sorted(a["wall"] / b["wall"] for a, b in zip(one, two, strict=True))
        print(
            f"{kind}: 2 workers vs 1: {ratios[len(ratios) // 2]:.2f}× median of {len(ratios)} "
            f"pairs (each pair run back to back; {ratios[0]:.2f}–{ratios[-1]:.2f}×)"
        )
    if args.scheduler:
        ratios = sorted(
            a["wall"] / b["wall"]
            for a, b in zip(runs[CLUSTER_MAIN], runs[CLUSTER_SHARED], strict=True)
        )
        print(
            f"running cluster: the workers writing their chunks (shared store) vs the main "
            f"process writing them: {ratios[len(ratios) // 2]:.2f}× median of {len(ratios)} "
            f"pairs ({ratios[0]:.2f}–{ratios[-1]:.2f}×)"
        )
    print()
    print(
        "identical results on every engine and number of workers (bit for bit): "
        f"{'yes' if same else 'NO'}"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
