"""Benchmark: FRF estimation for a roving-hammer test, and UFF read/write, in one run.

69 points × 10 averages × 2048 samples, two channels (the issue's target: FRFs in under 1 s).
Baseline in the same process: scipy.signal.csd/welch per point (one segment per average, the
same H1), so the ratio says what the vectorised estimator and its checks cost against it.
Run: ``python benchmarks/bench_frf.py``.
"""

from __future__ import annotations

import logging
import os
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import pyuff
from scipy.signal import csd, welch

import racketdyn as rd
from racketdyn.io import read_hammer_uff, write_hammer_uff
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.rig import accelerometer_index, hammer_points, rig_model, simulate_hammer_test


def best_of(function, repeats: int = 5) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def scipy_h1(records) -> list[np.ndarray]:
    fs = 1.0 / records.sampling_interval_s
    out = []
    for force, response in zip(records.force, records.response, strict=True):
        n = force.shape[1]
        s_fr = sum(
            csd(f, r, fs, nperseg=n, window="boxcar", detrend=False)[1]
            for f, r in zip(force, response, strict=True)
        )
        s_ff = sum(welch(f, fs, nperseg=n, window="boxcar", detrend=False)[1] for f in force)
        out.append(s_fr / s_ff)
    return out


def main() -> None:
    logging.disable(logging.WARNING)
    racket = rd.default_racket()
    locations, nodes = hammer_points(racket, n_frame=24, n_strings=45)  # 69 points
    start = time.perf_counter()
    model = rig_model(racket, "free")
    reference = accelerometer_index(racket, locations)
    records = simulate_hammer_test(
        model, locations, nodes, tuple(locations[reference]), nodes[reference], seed=1
    )
    simulate_s = time.perf_counter() - start
    print(
        f"racketdyn {rd.__version__}: {records.n_points} points × {records.force[0].shape[0]} "
        f"averages × {records.n_samples} samples, two channels"
    )
    print(f"  rig build + simulation        {simulate_s * 1e3:9.1f} ms")

    ours = best_of(lambda: estimate_frfs(records, exponential_window_s=0.1))
    baseline = best_of(lambda: scipy_h1(records), repeats=2)
    target = "PASS" if ours < 1.0 else "MISS"
    print(
        f"  FRFs, racketdyn (checks + windows + H1 + coherence)  {ours * 1e3:9.1f} ms  "
        f"target < 1000 ms: {target}"
    )
    print(f"  FRFs, scipy csd/welch per point (H1 only)           {baseline * 1e3:9.1f} ms")
    print(f"  ratio baseline / racketdyn                           {baseline / ours:9.2f}×")

    with tempfile.TemporaryDirectory() as folder:
        for binary in (False, True):
            path = Path(folder) / f"t{'b' if binary else 'a'}.uff"
            write_s = best_of(
                lambda p=path, b=binary: write_hammer_uff(records, p, binary=b), repeats=1
            )
            read_s = best_of(lambda p=path: read_hammer_uff(p), repeats=2)
            # baseline: pyuff's bare parse of the same file, without racketdyn's structure
            # check and record assembly (the check once cost 16× pyuff's parse: line numbers
            # counted from the file's start for every data set)
            bare_s = best_of(lambda p=path: pyuff.UFF(str(p)).read_sets(), repeats=2)
            kind = "binary" if binary else "ASCII "
            size = path.stat().st_size / 2**20
            verdict = "PASS" if read_s < 2.0 * bare_s else "MISS"
            print(
                f"  UFF {kind} write {write_s * 1e3:8.1f} ms, read {read_s * 1e3:8.1f} ms "
                f"({size:.1f} MiB; read / FRFs = {read_s / ours:.1f}×); pyuff alone "
                f"{bare_s * 1e3:8.1f} ms, read / pyuff = {read_s / bare_s:.2f}× "
                f"(target < 2×: {verdict})"
            )


if __name__ == "__main__":
    main()
