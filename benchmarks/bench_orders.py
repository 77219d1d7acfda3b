"""Benchmark: identify's run time against the model order its band's peaks ask for.

``identify`` raises its default ``max_order`` (60) to ``ORDERS_PER_PEAK`` times the band's clear
peaks, up to ``MAX_RAISED_ORDER`` (racketdyn.modal.identify).  This times it on 45 well-
separated modes in one band (200–2,000 Hz, ζ 0.4 %, 4 FRFs, 0.1 % noise; 1 Hz lines, and
0.25 Hz lines: four times the lines), at order 60 (the old default: the baseline), at the
default (raised) and at ``MAX_RAISED_ORDER``, with the modes found within 0.1 % of the truth.
Wall and CPU time of the whole ``identify`` (stabilisation, selection, constants, shapes), the
best of ``REPEATS``.  One BLAS thread.  Run: ``python benchmarks/bench_orders.py``.
Informational: the exit status is 0 whatever the timings.
"""

from __future__ import annotations

import os

for _variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import logging  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from numpy.typing import NDArray  # noqa: E402

from racketdyn.measurement.records import FrfSet  # noqa: E402
from racketdyn.modal.identify import MAX_RAISED_ORDER, Identification, identify  # noqa: E402

N_MODES = 45
ZETA = 0.004
BAND = (40.0, 2400.0)
REPEATS = 2


def many_modes(spacing_hz: float) -> tuple[FrfSet, NDArray[np.float64]]:
    """The FRFs of the 45 modes on lines ``spacing_hz`` apart, and their frequencies, Hz."""
    rng = np.random.default_rng(3)
    f_n = np.linspace(200.0, 2000.0, N_MODES) + rng.uniform(-5.0, 5.0, N_MODES)
    x = np.linspace(0.0, 1.0, 4)
    shapes = np.cos(np.outer(x, np.arange(N_MODES) % 5 + 1) * np.pi)  # (points, modes)
    f = np.arange(0.0, 2500.0, spacing_hz)
    w, wn = 2 * np.pi * f[:, None], 2 * np.pi * f_n[None, :]
    modal = -(w**2) / (wn**2 - w**2 + 2j * ZETA * wn * w)  # (lines, modes)
    values = (shapes * shapes[0]) @ modal.T
    scale = 1e-3 * np.abs(values).max(axis=1, keepdims=True) / np.sqrt(2)
    values = values + scale * (
        rng.standard_normal(values.shape) + 1j * rng.standard_normal(values.shape)
    )
    frfs = FrfSet(
        frequency=f,
        values=values,
        nodes=(1, 2, 3, 4),
        locations=np.column_stack([x, np.zeros_like(x)]),
        frf_type="accelerance",
        reference_node=1,
        reference_location=(0.0, 0.0),
        source="benchmark: 45 modes",
    )
    return frfs, f_n


def timed(frfs: FrfSet, order: int | None) -> tuple[float, float, Identification]:
    """Best wall and CPU time of ``identify`` at ``order``, s, and its identification."""
    wall, cpu, found = float("inf"), float("inf"), None
    for _ in range(REPEATS):
        start, start_cpu = time.perf_counter(), time.process_time()
        found = identify(frfs, BAND, max_order=order)
        wall = min(wall, time.perf_counter() - start)
        cpu = min(cpu, time.process_time() - start_cpu)
    assert found is not None
    return wall, cpu, found


def main() -> int:
    logging.disable(logging.WARNING)
    print(f"identify on {N_MODES} modes in {BAND[0]:g}–{BAND[1]:g} Hz, best of {REPEATS}")
    for spacing in (1.0, 0.25):
        frfs, truth = many_modes(spacing)
        lines = int(np.count_nonzero((frfs.frequency >= BAND[0]) & (frfs.frequency <= BAND[1])))
        print(f"\n{spacing:g} Hz lines ({lines} in the band)")
        base = None
        for label, order in (
            ("60 (old default)", 60),
            ("default", None),
            ("cap", MAX_RAISED_ORDER),
        ):
            wall, cpu, found = timed(frfs, order)
            got = found.model.frequency
            within = sum(bool(np.min(np.abs(got - f) / f) < 1e-3) for f in truth)
            used = found.model.metadata["max_order"]
            base = base or wall
            print(
                f"  order {used:>3} ({label:>16}): {wall:6.2f} s wall, {cpu:6.2f} s CPU, "
                f"×{wall / base:4.1f} the baseline; {found.model.n_modes} modes, {within} of "
                f"{N_MODES} within 0.1 %"
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
