"""Cost of carrying uncertain inputs through the approximate method (issue 24), on one core.

Run with ``python benchmarks/bench_uncertainty.py``.  Times
:func:`racketdyn.impact.uncertainty.propagate` over the built-in racket's 69-point grid at
three ball speeds, one support, with four uncertain inputs (e_BG, the first bending frequency,
the impact location, the ball speed), for 256 and 1,000 samples; the baseline is one nominal
prediction of the same grid in the same process, so the ratio says what a sample costs
against a plain prediction.  The issue's target: 1,000 samples in under 2 s.  Informational:
the exit status is 0 whatever the timings.
"""

from __future__ import annotations

import os

for _variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_variable] = "1"

import logging  # noqa: E402
import time  # noqa: E402

from racketdyn.ball import Ball  # noqa: E402
from racketdyn.impact.approximate import predict  # noqa: E402
from racketdyn.impact.measured import ModelInputs  # noqa: E402
from racketdyn.impact.uncertainty import Spread, Uncertainty, propagate  # noqa: E402
from racketdyn.io.racket_file import default_racket  # noqa: E402

TARGET_S = 2.0
SPEEDS = (10.0, 20.0, 30.0)
SPREADS = (
    Spread("e_bg", bounds=(0.80, 0.88)),
    Spread("first_bending_hz", bounds=(100.0, 160.0)),
    Spread("location_m", sd=0.01),
    Spread("ball_speed_mps", sd=1.0),
)


def _best(run: object, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()  # type: ignore[operator]
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    logging.disable(logging.WARNING)
    racket = default_racket()
    inputs = ModelInputs(racket, Ball())
    points = racket.head.grid(9)
    law, model = inputs.law(), inputs.modes()
    propagate(inputs, points, SPEEDS, Uncertainty(SPREADS, samples=2))  # warm the caches
    nominal = _best(
        lambda: predict(racket, Ball(), points, SPEEDS, "free", modal_model=model, law=law), 20
    )
    print(f"{len(points)} points × {len(SPEEDS)} speeds × 1 support, 4 uncertain inputs")
    print(f"  one nominal prediction (baseline): {nominal * 1e3:8.2f} ms")
    for samples in (256, 1000):
        spent = _best(
            lambda n=samples: propagate(inputs, points, SPEEDS, Uncertainty(SPREADS, samples=n)),
            1,
        )
        print(
            f"  {samples:5d} samples: {spent:6.2f} s = {spent / samples * 1e3:5.2f} ms a sample "
            f"= {spent / samples / nominal:4.2f} × a nominal prediction"
        )
    print(f"  target: 1000 samples in {TARGET_S:g} s ({'met' if spent <= TARGET_S else 'not met'})")


if __name__ == "__main__":
    main()
