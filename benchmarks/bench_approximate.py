"""Throughput of the approximate impact method, ``racketdyn.impact.predict``, on one core.

Run with ``python benchmarks/bench_approximate.py``.  Times a whole face grid (68 points × 50
ball speeds × 2 supports) with the modal model and the compound ball+string law built once
outside the timed region, against the target of a whole grid in under 50 ms on one core; a
plain Python loop over single impacts gives the speed-up that vectorisation buys.  The setup
steps (modal model, compound law) are timed on their own.  Informational: the exit status is 0
whatever the timings.
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
):
    os.environ[_variable] = "1"

import logging  # noqa: E402
import platform  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402

import numpy as np  # noqa: E402

import racketdyn  # noqa: E402
from racketdyn.impact import predict  # noqa: E402

N_POINTS = 68
GRID_N = 10  # a 10 × 10 grid keeps 80 points on the ellipse; the first 68 are used
SPEEDS = np.linspace(5.0, 50.0, 50)
SUPPORTS = ("free", "pinned")
TARGET_S = 0.050
REPEATS = 20
BASELINE_IMPACTS = 200
BASELINE_REPEATS = 2
SETUP_REPEATS = 3


def best_of(function: Callable[[], object], repeats: int, warm_up: bool = True) -> float:
    """Best wall time of ``repeats`` calls, s (after one untimed warm-up call)."""
    if warm_up:
        function()
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def main() -> int:
    # predict logs a warning per call for impacts beyond the restoring-force law (the fastest
    # speeds); they are counted below instead of printed on every repeat.
    logging.getLogger("racketdyn").setLevel(logging.ERROR)
    racket = racketdyn.default_racket()
    ball = racketdyn.Ball()
    points = racket.head.grid(GRID_N)[:N_POINTS]
    if len(points) != N_POINTS:
        raise SystemExit(f"grid {GRID_N} gives only {len(points)} points; raise GRID_N")

    # Setup, outside the timed grid: cold first build, then best of a few.
    start = time.perf_counter()
    model = racketdyn.modal_model_for(racket)
    model_first = time.perf_counter() - start
    model_best = best_of(lambda: racketdyn.modal_model_for(racket), SETUP_REPEATS, warm_up=False)
    start = time.perf_counter()
    law = racketdyn.compound_law(racket, ball)
    law_first = time.perf_counter() - start
    law_best = best_of(lambda: racketdyn.compound_law(racket, ball), SETUP_REPEATS, warm_up=False)

    def whole_grid() -> racketdyn.ImpactResult:
        return predict(racket, ball, points, SPEEDS, SUPPORTS, modal_model=model, law=law)

    result = whole_grid()
    n_impacts = result.status.size
    assert n_impacts == N_POINTS * SPEEDS.size * len(SUPPORTS)
    n_ok = int(np.sum(result.status == "ok"))
    grid_s = best_of(whole_grid, REPEATS)

    # Diagnostic: predict keeps only the frame modes (model.frame_modes); when that drops a
    # string-bed mode it is a new ModalModel whose mode-shape interpolator is rebuilt per call.
    frame = model.frame_modes

    def whole_grid_frame_modes() -> racketdyn.ImpactResult:
        return predict(racket, ball, points, SPEEDS, SUPPORTS, modal_model=frame, law=law)

    frame_s = best_of(whole_grid_frame_modes, REPEATS)

    # Baseline: one predict call per single impact (point, speed, support), a plain loop.
    rng = np.random.default_rng(2002)
    cases = [
        (points[i], SPEEDS[j], SUPPORTS[k])
        for i, j, k in zip(
            rng.integers(N_POINTS, size=BASELINE_IMPACTS),
            rng.integers(SPEEDS.size, size=BASELINE_IMPACTS),
            rng.integers(len(SUPPORTS), size=BASELINE_IMPACTS),
            strict=True,
        )
    ]

    def loop() -> None:
        for location, speed, support in cases:
            predict(racket, ball, location, speed, (support,), modal_model=model, law=law)

    loop_s = best_of(loop, BASELINE_REPEATS)

    def loop_frame_modes() -> None:
        for location, speed, support in cases:
            predict(racket, ball, location, speed, (support,), modal_model=frame, law=law)

    loop_frame_s = best_of(loop_frame_modes, BASELINE_REPEATS)
    per_impact_loop = loop_s / BASELINE_IMPACTS
    per_impact_grid = grid_s / n_impacts

    verdict = "PASS" if grid_s < TARGET_S else "MISS"
    print(
        f"racketdyn {racketdyn.__version__}, numpy {np.__version__}, "
        f"Python {platform.python_version()}, one thread (OMP/OPENBLAS/MKL_NUM_THREADS=1)"
    )
    print(f"racket: {racket.name}; modal model: {model.source} ({model.n_modes} modes)")
    print()
    print("setup (outside the timed grid)")
    for label, first, best in (
        ("modal model build", model_first, model_best),
        ("compound law fit", law_first, law_best),
    ):
        print(f"  {label:<19} first {first * 1e3:8.2f} ms   best {best * 1e3:8.2f} ms")
    print()
    print(
        f"whole grid: {N_POINTS} points × {SPEEDS.size} speeds × {len(SUPPORTS)} supports "
        f"= {n_impacts} impacts ({n_ok} ok, {n_impacts - n_ok} beyond the law: NaN), "
        f"best of {REPEATS} after a warm-up"
    )
    print(f"  time                {grid_s * 1e3:8.2f} ms")
    print(f"  throughput          {n_impacts / grid_s:12,.0f} impacts/s")
    print(
        f"  diagnostic          {frame_s * 1e3:8.2f} ms with model.frame_modes passed in "
        f"({frame.n_modes} of {model.n_modes} modes; its interpolator stays cached)"
    )
    print(f"  target              whole grid < {TARGET_S * 1e3:.0f} ms on one core: {verdict}")
    print()
    print(f"baseline: Python loop, one predict call per impact, {BASELINE_IMPACTS} impacts")
    print(
        f"  time per impact     {per_impact_loop * 1e6:8.1f} µs   "
        f"(vectorised {per_impact_grid * 1e6:.2f} µs)"
    )
    print(f"  throughput          {1.0 / per_impact_loop:12,.0f} impacts/s")
    print(f"  vectorisation speed-up  {per_impact_loop / per_impact_grid:,.0f}×")
    per_impact_frame = loop_frame_s / BASELINE_IMPACTS
    print(
        f"  diagnostic          {per_impact_frame * 1e6:8.1f} µs per impact with model.frame_modes "
        f"passed in; speed-up {per_impact_frame / (frame_s / n_impacts):,.0f}× over its grid"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
