"""Throughput of the transient impact simulation on one core, side by side with its accuracy.

Run with ``python benchmarks/bench_transient.py``.  The case of issues 5 and 16: a 68-point ×
30-speed × 2-support face map (free and pinned) with 8 flexible modes (the built-in beam model
with seven bending modes and the twisting mode).  Each scheme of the compiled engine is timed
on the whole map (the least CPU time of this process over 7 runs, the schemes taken in turn,
after compilation: CPU time rather than wall time, as the machine is often shared) and its
largest differences to the reference engine (one ``scipy.integrate.solve_ivp`` per impact,
DOP853, rtol 1e-10, also timed in CPU time) are taken on a sample of the map (the same 30
points at 5 and 40 m/s, both supports, as before issue 16):

* ``before issue 16`` — the baseline: the kernel as it was before issue 16's engine work
  (``src/racketdyn/impact/kernel.py`` at commit ``BEFORE``, read with ``git show`` and compiled
  here; skipped when git or that commit is not at hand), at its default 400 steps per contact;
* ``400 steps, order 2`` — the same scheme through today's kernel (``extrapolate=False``):
  what the per-step work (predictor, one Newton correction, arrays, free flight) gained;
* ``128 steps, extrapolated`` — the default since issue 16 (runs at h and 2h, Richardson);
* ``96 steps, extrapolated`` — one step further down, to show the margin.

The ratio of each scheme's throughput to the baseline's is printed in the same run, the
kernel's share of the time (the rest is NumPy: step sizes, energies), the issue's target
(30,000 impacts/s) and whether the differences stayed within the baseline's (to 1e-6 of
them: the Newton iteration's tolerance moves the last digits).  The compile time (first
call, or numba's on-disk cache) is printed on its own.  Informational: the exit status is 0
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
    "NUMBA_NUM_THREADS",
):
    os.environ[_variable] = "1"

import platform  # noqa: E402
import subprocess  # noqa: E402
import time  # noqa: E402
import types  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

import racketdyn  # noqa: E402
from racketdyn.impact import transient  # noqa: E402
from racketdyn.impact.transient import predict_transient  # noqa: E402
from racketdyn.io.racket_file import default_racket  # noqa: E402
from racketdyn.racket_modal.beam import builtin_modal_model  # noqa: E402

N_POINTS = 68
GRID_N = 10
SPEEDS = np.linspace(5.0, 40.0, 30)
SUPPORTS = ("free", "pinned")
N_MODES = 8
TARGET_PER_S = 30_000
REPEATS = 7
SAMPLE = 120  # impacts through the reference engine
BEFORE = "77cbbd4"  # main before issue 16's engine work
SCHEMES = (  # label, steps per contact, extrapolate
    ("before issue 16 (400 steps, order 2)", 400, False),
    ("400 steps, order 2, today's kernel", 400, False),
    ("128 steps, extrapolated (default)", 128, True),
    ("96 steps, extrapolated", 96, True),
)
FIELDS = (("rebound_speed", "m/s"), ("contact_time", "s"), ("vibration_energy", "J"))


def _kernel_before() -> Any:
    """``integrate_impacts`` of the kernel at commit ``BEFORE`` (None without git or it)."""
    try:
        text = subprocess.run(
            ["git", "show", f"{BEFORE}:src/racketdyn/impact/kernel.py"],
            cwd=Path(__file__).parent, capture_output=True, text=True, check=True,
        ).stdout  # fmt: skip
    except (OSError, subprocess.CalledProcessError):
        return None
    module = types.ModuleType("kernel_before")
    # no on-disk cache for code that has no file
    exec(compile(text.replace("cache=True, ", ""), "kernel_before", "exec"), module.__dict__)

    def integrate(*args: Any) -> Any:
        return module.integrate_impacts(*args[:13])  # it had no ``extrapolate``

    return integrate


class _KernelClock:
    """Sums the time spent in the compiled kernel (``integrate_impacts``) while installed."""

    def __init__(self) -> None:
        self.seconds = 0.0
        self.original = transient.__dict__["integrate_impacts"]
        self.inner = self.original

    def __call__(self, *args: Any) -> Any:
        start = time.process_time()
        try:
            return self.inner(*args)
        finally:
            self.seconds += time.process_time() - start


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

    def compiled(where: Any, speeds: Any, steps: int, extrapolate: bool) -> Any:
        return predict_transient(
            racket, ball, where, speeds, SUPPORTS, modal_model=model, engine="compiled",
            steps_per_contact=steps, extrapolate=extrapolate,
        )  # fmt: skip

    start = time.perf_counter()
    compiled(points, SPEEDS, SCHEMES[1][1], SCHEMES[1][2])
    first = time.perf_counter() - start
    print(f"compiled engine, first call (compile or load cache): {first:.2f} s")
    before = _kernel_before()
    if before is None:
        print(f"(git or commit {BEFORE} not at hand: the kernel before issue 16 is skipped)")

    rng = np.random.default_rng(1)
    picks = rng.choice(len(points), size=SAMPLE // (2 * len(SUPPORTS)), replace=False)
    sample_speeds = SPEEDS[[0, -1]]
    start = time.process_time()
    reference = predict_transient(
        racket, ball, points[picks], sample_speeds, SUPPORTS, modal_model=model,
        engine="reference",
    )  # fmt: skip
    per_reference = (time.process_time() - start) / reference.rebound_ratio.size
    print(
        f"reference engine (solve_ivp DOP853, rtol 1e-10): {per_reference * 1e3:.1f} ms per "
        f"impact = {1 / per_reference:,.0f} impacts/s ({reference.rebound_ratio.size} impacts)"
    )

    clock = _KernelClock()
    transient.__dict__["integrate_impacts"] = clock
    schemes = [s for s in SCHEMES if before is not None or s is not SCHEMES[0]]
    least = {label: (float("inf"), 0.0) for label, _, _ in schemes}
    results: dict[str, Any] = {}
    try:
        if before is not None:
            clock.inner = before
            compiled(points[:1], SPEEDS[:1], 400, False)  # compile it
        # round robin, so that the other processes' load falls on every scheme alike
        for _ in range(REPEATS):
            for label, steps, extrapolate in schemes:
                clock.inner = before if label == SCHEMES[0][0] else clock.original
                clock.seconds = 0.0
                start = time.process_time()
                results[label] = compiled(points, SPEEDS, steps, extrapolate)
                elapsed = time.process_time() - start
                if elapsed < least[label][0]:
                    least[label] = (elapsed, clock.seconds)
        rows = []
        for label, steps, extrapolate in schemes:
            clock.inner = before if label == SCHEMES[0][0] else clock.original
            sample = compiled(points[picks], sample_speeds, steps, extrapolate)
            ok = (sample.status == "ok") & (reference.status == "ok")
            worst = [
                float(np.abs(getattr(sample, name) - getattr(reference, name))[ok].max())
                for name, _ in FIELDS
            ]
            bad = int(np.sum(results[label].status != "ok"))
            seconds, kernel = least[label]
            rows.append((label, n_impacts / seconds, seconds, kernel, worst, bad))
    finally:
        transient.__dict__["integrate_impacts"] = clock.original

    base_rate, base_worst = rows[0][1], rows[0][4]
    print()
    header = "max |compiled − reference|: " + ", ".join(f"{n} ({u})" for n, u in FIELDS)
    print(f"{'scheme':<40} {'impacts/s':>10} {'× base':>7} {'kernel':>7}   {header}")
    for label, rate, best, kernel, worst, bad in rows:
        within = all(w <= b * (1 + 1e-6) for w, b in zip(worst, base_worst, strict=True))
        print(
            f"{label:<40} {rate:>10,.0f} {rate / base_rate:>6.2f}× {kernel / best:>6.0%}   "
            + "  ".join(f"{w:.2e}" for w in worst)
            + ("" if label == rows[0][0] else ("  (within baseline)" if within else "  (WORSE)"))
            + (f"  [{bad} impacts with no valid number]" if bad else "")
        )
    default_rate = next(row[1] for row in rows if "default" in row[0])
    print(
        f"\ndefault scheme: {default_rate:,.0f} impacts/s, target {TARGET_PER_S:,}: "
        f"{'met' if default_rate >= TARGET_PER_S else 'NOT met'}; "
        f"{per_reference * default_rate:,.0f}× the reference engine"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
