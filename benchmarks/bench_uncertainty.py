"""Cost of carrying uncertain inputs through the approximate method (issue 24), on one core.

Run with ``python benchmarks/bench_uncertainty.py``.  Times
:func:`racketdyn.impact.uncertainty.propagate` over the built-in racket's 69-point grid at
three ball speeds, one support, with four uncertain inputs (e_BG, the first bending frequency,
the impact location, the ball speed), for 256 and 1,000 samples, both ways: every sample at
once (``vectorised``, :func:`racketdyn.impact.samples.predict_samples`, the default) and the
model once per sample (``vectorised=False``, the path before).  The baseline is one nominal
prediction of the same grid in the same process, so the ratios say what a sample costs
against a plain prediction, and the speed-up is the per-sample path's time over the
vectorised one's.  Wall time and CPU time (this process's: what the wall time is on an idle
core) are printed; on a machine shared with other work the wall time is the larger.  The
issue's target: 1,000 samples in under 2 s.  Informational: the exit status is 0 whatever the
timings.

A design sweep with the same uncertainty (``racketdyn sweep --uncertainty``) is timed last: six
tension designs, the same grid and speeds, in this process (``SerialExecutor``), without and
with 256 samples a design, against :func:`propagate` on one design alone: what the sweep's
store and tasks add to the samples' cost.
"""

from __future__ import annotations

import os

for _variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_variable] = "1"

import logging  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from dataclasses import replace  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
from numpy.typing import NDArray  # noqa: E402

from racketdyn.ball import Ball  # noqa: E402
from racketdyn.impact.approximate import predict  # noqa: E402
from racketdyn.impact.measured import ModelInputs  # noqa: E402
from racketdyn.impact.uncertainty import Spread, Uncertainty, propagate  # noqa: E402
from racketdyn.io.racket_file import default_racket  # noqa: E402
from racketdyn.racket import Racket  # noqa: E402
from racketdyn.sweep import SerialExecutor, SweepSpec, Variable, run_sweep  # noqa: E402

TARGET_S = 2.0
SPEEDS = (10.0, 20.0, 30.0)
SPREADS = (
    Spread("e_bg", bounds=(0.80, 0.88)),
    Spread("first_bending_hz", bounds=(100.0, 160.0)),
    Spread("location_m", sd=0.01),
    Spread("ball_speed_mps", sd=1.0),
)


def _best(run: Callable[[], object], repeats: int) -> tuple[float, float]:
    """The shortest wall time and the shortest CPU time of ``repeats`` runs, s."""
    wall, cpu = [], []
    for _ in range(repeats):
        start, start_cpu = time.perf_counter(), time.process_time()
        run()
        wall.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
    return min(wall), min(cpu)


def main() -> None:
    logging.disable(logging.WARNING)
    racket = default_racket()
    inputs = ModelInputs(racket, Ball())
    points = racket.head.grid(9)
    law, model = inputs.law(), inputs.modes()
    propagate(inputs, points, SPEEDS, Uncertainty(SPREADS, samples=2))  # warm the caches
    nominal, _ = _best(
        lambda: predict(racket, Ball(), points, SPEEDS, "free", modal_model=model, law=law), 20
    )
    print(f"{len(points)} points × {len(SPEEDS)} speeds × 1 support, 4 uncertain inputs")
    print(f"  one nominal prediction (baseline): {nominal * 1e3:8.2f} ms")
    spent: dict[tuple[int, bool], tuple[float, float]] = {}
    for samples, vectorised, repeats in ((256, True, 3), (1000, True, 3), (1000, False, 1)):
        uncertainty = Uncertainty(SPREADS, samples=samples)
        spent[samples, vectorised] = wall, cpu = _best(
            lambda u=uncertainty, v=vectorised: propagate(inputs, points, SPEEDS, u, vectorised=v),
            repeats,
        )
        how = "every sample at once" if vectorised else "once per sample    "
        print(
            f"  {samples:5d} samples, {how} (best of {repeats}): {wall:6.2f} s wall "
            f"({cpu:5.2f} s CPU) = "
            f"{wall / samples * 1e3:5.2f} ms a sample = {wall / samples / nominal:4.2f} × a "
            "nominal prediction"
        )
    ratio = spent[1000, False][0] / spent[1000, True][0]
    print(f"  speed-up at 1000 samples: {ratio:4.1f} × (wall)")
    wall, cpu = spent[1000, True]
    verdict = "met" if wall <= TARGET_S else ("met in CPU time" if cpu <= TARGET_S else "not met")
    print(f"  target: 1000 samples in {TARGET_S:g} s ({verdict})")
    _sweep(racket, points, spent[256, True][0])


def _sweep(racket: Racket, points: NDArray[np.float64], alone_s: float) -> None:
    """Six designs without and with 256 samples each, serial, against ``alone_s`` (propagate
    on one design, 256 samples)."""
    tensions = np.linspace(200.0, 260.0, 6)
    spec = SweepSpec(
        racket,
        Ball(),
        points,
        SPEEDS,
        supports=("free",),
        variables=(Variable.scalar("tension_n", tensions),),
    )
    banded = replace(spec, uncertainty=Uncertainty(SPREADS, samples=256))
    spent = {}
    with tempfile.TemporaryDirectory() as folder:
        for name, study in (("nominal", spec), ("256 samples", banded)):
            spent[name] = _best(
                lambda s=study, n=name: run_sweep(
                    s, Path(folder) / n.replace(" ", "_"), SerialExecutor(), figures=None
                ),
                1,
            )[0]
    n = tensions.size
    print(f"sweep of {n} designs (tension), serial, store and summary included")
    print(f"  without an uncertainty (baseline): {spent['nominal']:6.2f} s")
    print(
        f"  with 256 samples a design:         {spent['256 samples']:6.2f} s = "
        f"{spent['256 samples'] / spent['nominal']:5.1f} × the baseline, "
        f"{spent['256 samples'] / n:5.2f} s a design against {alone_s:5.2f} s for propagate "
        f"alone ({spent['256 samples'] / n / alone_s:4.2f} ×)"
    )
    added = (spent["256 samples"] - spent["nominal"]) / n
    print(
        f"  the samples' share: {added:5.2f} s a design = {added / alone_s:4.2f} × propagate "
        "alone (the rest: the nominal sweep's own cost)"
    )


if __name__ == "__main__":
    main()
