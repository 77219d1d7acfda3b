"""Throughput of the transient impact simulation on one core: compiled engine against scipy.

Run with ``python benchmarks/bench_transient.py``.  The issue's case: a 68-point × 30-speed ×
2-support face map (free and pinned) with 8 flexible modes (the built-in beam model with seven
bending modes and the twisting mode), against the target of 10,000 impacts per second on one
core after compilation.  The same impacts through the reference engine (one
``scipy.integrate.solve_ivp`` per impact, DOP853, rtol 1e-10) are timed on a sample, and the
speed-up and the largest differences between the engines are printed in the same run.  The
compile time (first call, or numba's on-disk cache) is printed on its own.  Informational:
the exit status is 0 whatever the timings.
"""

from __future__ import annotations

import os

# One core: pin the BLAS/OpenMP thread pools before numpy is imported.
for _variable in (
    "OMP_NUM_THREADS",
    "OPENBLAS_NUM_THREADS",
    "MKL_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS",
    "NUMEXPR_NUM_THREADS",
    "NUMBA_NUM_THREADS",
):
    os.environ[_variable] = "1"

import platform  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

import racketdyn  # noqa: E402
from racketdyn.impact.transient import predict_transient  # noqa: E402
from racketdyn.io.racket_file import default_racket  # noqa: E402
from racketdyn.racket_modal.beam import builtin_modal_model  # noqa: E402

N_POINTS = 68
GRID_N = 10
SPEEDS = np.linspace(5.0, 40.0, 30)
SUPPORTS = ("free", "pinned")
N_MODES = 8
TARGET_PER_S = 10_000
REPEATS = 3
SAMPLE = 120  # impacts through the reference engine


def main() -> int:
    import numba

    racket = default_racket()
    ball = racketdyn.Ball()
    model = builtin_modal_model(racket, n_bending=N_MODES - 1).frame_modes
    points = racket.head.grid(GRID_N)[:N_POINTS]
    n_impacts = len(points) * SPEEDS.size * len(SUPPORTS)
    print(f"racketdyn {racketdyn.__version__}, numba {numba.__version__}, numpy {np.__version__}")
    print(f"python {platform.python_version()} on {platform.machine()}, one core")
    print(
        f"case: {len(points)} points × {SPEEDS.size} speeds × {len(SUPPORTS)} supports = "
        f"{n_impacts} impacts, {model.n_modes} flexible modes "
        f"({model.frequency.min():.0f}–{model.frequency.max():.0f} Hz)"
    )

    def compiled() -> racketdyn.ImpactResult:
        return predict_transient(
            racket, ball, points, SPEEDS, SUPPORTS, modal_model=model, engine="compiled"
        )

    start = time.perf_counter()
    fast = compiled()
    first = time.perf_counter() - start
    best = float("inf")
    for _ in range(REPEATS):
        start = time.perf_counter()
        fast = compiled()
        best = min(best, time.perf_counter() - start)
    rate = n_impacts / best
    print(f"compiled engine, first call (compile or load cache): {first:8.2f} s")
    print(
        f"compiled engine, whole map: {best * 1e3:8.1f} ms = {rate:,.0f} impacts/s "
        f"(target {TARGET_PER_S:,}: {'met' if rate >= TARGET_PER_S else 'NOT met'})"
    )

    rng = np.random.default_rng(1)
    picks = rng.choice(len(points), size=SAMPLE // (2 * len(SUPPORTS)), replace=False)
    speeds = SPEEDS[[0, -1]]
    start = time.perf_counter()
    reference = predict_transient(
        racket, ball, points[picks], speeds, SUPPORTS, modal_model=model, engine="reference"
    )
    per_reference = (time.perf_counter() - start) / reference.rebound_ratio.size
    print(
        f"reference engine (solve_ivp DOP853, rtol 1e-10): {per_reference * 1e3:6.2f} ms per "
        f"impact = {1 / per_reference:,.0f} impacts/s"
    )
    print(f"speed-up of the compiled engine: {per_reference * rate:,.0f}×")
    sample = predict_transient(
        racket, ball, points[picks], speeds, SUPPORTS, modal_model=model, engine="compiled"
    )
    ok = (sample.status == "ok") & (reference.status == "ok")
    for name, unit in (("rebound_speed", "m/s"), ("contact_time", "s"), ("vibration_energy", "J")):
        difference = np.abs(getattr(sample, name) - getattr(reference, name))[ok]
        print(f"  max |compiled − reference| {name}: {difference.max():.2e} {unit}")
    print(f"  impacts with no valid number (beyond the law): {int(np.sum(fast.status != 'ok'))}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
