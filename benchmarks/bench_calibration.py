"""Synthetic truth for ``calibrate`` (issue 15): 50 seeded trials.

Rebound ratios simulated by the transient model (compiled engine) at known parameter values
(e_BG 0.80, roll inertia 1.3 × the built-in racket's) at eight points of the face, 20 m/s,
free racket, plus Gaussian noise of 0.005 on the ratio; ``calibrate`` fits e_bg and
roll_inertia_kgm2 from the built-in starting values.  Printed: how often the truth lies within
one and within two standard errors of the fitted value (the issue asks for ≥ 90 % "within
their standard errors": we read that as the two-standard-error interval, whose nominal coverage
is 95 %; one standard error covers 68 % by definition), the median relative standard error,
and the time per calibration.  Then the same fit from points on the long axis only, where the
roll inertia has no effect: it must come out "not identifiable" in every trial.
Run with ``python benchmarks/bench_calibration.py [TRIALS]``; informational, exit 0.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from racketdyn.ball import Ball
from racketdyn.impact.calibration import apply, calibrate, simulate_measurements
from racketdyn.impact.measured import ModelInputs
from racketdyn.io.racket_file import default_racket

FACE = [
    (0.45, 0.0),
    (0.50, 0.0),
    (0.55, 0.0),
    (0.60, 0.0),
    (0.50, 0.06),
    (0.55, -0.06),
    (0.45, 0.05),
    (0.60, 0.04),
]
AXIS = [(0.42, 0.0), (0.47, 0.0), (0.52, 0.0), (0.57, 0.0), (0.62, 0.0)]
SD = 0.005
FIT = ("e_bg", "roll_inertia_kgm2")


def truth_and_start() -> tuple[ModelInputs, ModelInputs, dict[str, float]]:
    """The starting inputs (built-in racket and ball), the true ones, and the true values."""
    racket = default_racket()
    start = ModelInputs(racket, Ball())
    values = {"e_bg": 0.80, "roll_inertia_kgm2": 1.3 * racket.roll_inertia_kgm2}
    return start, apply(start, values), values


def main(trials: int) -> None:
    start, truth, values = truth_and_start()
    within1 = np.zeros(len(FIT))
    within2 = np.zeros(len(FIT))
    relative = []
    began = time.perf_counter()
    for seed in range(trials):
        measured = simulate_measurements(truth, FACE, 20.0, sd=SD, rng=seed)
        result, _ = calibrate(start, measured, FIT)
        error = np.abs(result.value - [values[n] for n in FIT])
        within1 += error <= result.standard_error
        within2 += error <= 2 * result.standard_error
        relative.append(result.standard_error / result.value)
    elapsed = (time.perf_counter() - began) / trials
    print(f"{trials} trials, {len(FACE)} points, sd {SD}: {elapsed:.2f} s per calibration")
    for k, name in enumerate(FIT):
        print(
            f"  {name}: within 1 SE {100 * within1[k] / trials:.0f} %, within 2 SE "
            f"{100 * within2[k] / trials:.0f} %, median relative SE "
            f"{100 * float(np.median([r[k] for r in relative])):.2f} %"
        )
    refused = 0
    for seed in range(min(trials, 10)):
        measured = simulate_measurements(truth, AXIS, 20.0, sd=SD, rng=seed)
        result, _ = calibrate(start, measured, FIT)
        refused += not result.identifiable[1]
    print(f"points on the axis only: roll inertia not identifiable in {refused} of "
          f"{min(trials, 10)} trials")  # fmt: skip


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 50)
