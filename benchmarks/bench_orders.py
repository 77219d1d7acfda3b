"""Benchmark: identify's run time against the model order its band's peaks ask for.

``identify`` raises its default ``max_order`` (60) to ``ORDERS_PER_PEAK`` times the band's clear
peaks, up to ``MAX_RAISED_ORDER`` (racketdyn.modal.identify).  This times it on 45 well-
separated modes in one band (200–2,000 Hz, ζ 0.4 %, 4 FRFs, 0.1 % noise; 1 Hz lines, and
0.25 Hz lines: four times the lines), at order 60 (the old default: the baseline), at the
default (raised) and at ``MAX_RAISED_ORDER``, with the modes found within 0.1 % of the truth.
Wall and CPU time of the whole ``identify`` (stabilisation, selection, constants, shapes), the
best of ``REPEATS``.  One BLAS thread.  Run: ``python benchmarks/bench_orders.py``.

``--real``: every case of ``tests/test_realdata_must_hold.py`` (read as that file reads them;
the real data beside the repository) and the racket rig's FRFs of ``tests/test_racket_data.py``
(free, held, and the held trial racket two ways): the band's clear peaks, the order used, the
CPU time (``time.process_time``, one run) at the default against order 60 (the baseline, run
first in the same process; several references: their default 30 against the single
reference's rule, 5 orders a peak), the modes at the default that order 60 keeps within 0.1 %
(and damping within 20 %), and the unexplained peaks with what a pin at each keeps and what
the band between its neighbouring counted peaks keeps.
Informational: the exit status is 0 whatever the timings.
"""

from __future__ import annotations

import os

for _variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import logging  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from functools import partial  # noqa: E402
from pathlib import Path  # noqa: E402
from tempfile import TemporaryDirectory  # noqa: E402

import numpy as np  # noqa: E402
from numpy.typing import NDArray  # noqa: E402

from racketdyn.measurement.records import FrfReferences, FrfSet  # noqa: E402
from racketdyn.modal.identify import (  # noqa: E402
    MAX_RAISED_ORDER,
    ORDERS_PER_PEAK,
    Identification,
    identify,
)
from racketdyn.modal.peaks import resolved_peaks  # noqa: E402

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


def cpu_identify(
    frfs: FrfSet | FrfReferences, **options: object
) -> tuple[float, Identification | str]:
    """CPU time of one ``identify``, s, and its identification (or its error's words)."""
    start = time.process_time()
    try:
        found: Identification | str = identify(frfs, **options)  # type: ignore[arg-type]
    except Exception as error:
        found = f"{type(error).__name__}: {str(error)[:60]}"
    return time.process_time() - start, found


def compared(base: Identification, other: Identification) -> str:
    """The modes of ``base`` that ``other`` loses (none within 0.1 %) or changes (damping
    beyond 20 %), in words."""
    lost, changed = [], []
    for f, z in zip(base.model.frequency, base.model.damping_ratio, strict=True):
        k = int(np.argmin(np.abs(other.model.frequency - f))) if other.model.n_modes else -1
        if k < 0 or abs(other.model.frequency[k] - f) > 1e-3 * f:
            lost.append(f"{f:.2f}")
        elif abs(other.model.damping_ratio[k] / z - 1) > 0.2:
            changed.append(f"{f:.2f} ζ {z:.3%}→{other.model.damping_ratio[k]:.3%}")
    return f"lost [{', '.join(lost)}] changed [{'; '.join(changed)}]"


def near(found: Identification | str, peak: float) -> str:
    """The modes of ``found`` within 0.3 % of ``peak``, in words (or its error's)."""
    if isinstance(found, str):
        return found
    model = found.model
    return ", ".join(
        f"{f:.2f} Hz ζ {z:.3%}"
        for f, z in zip(model.frequency, model.damping_ratio, strict=True)
        if abs(f - peak) <= 3e-3 * peak
    )


def tried(frfs: FrfSet | FrfReferences, found: Identification, label: str) -> None:
    """Each unexplained peak of ``found``: what a pin at it keeps (the same order), and what
    the band between its neighbouring counted peaks keeps (its default order), with the CPU
    time each costs."""
    band = found.model.metadata["band_hz"]
    peaks = resolved_peaks(found.frfs, (band[0], band[1]))
    for peak in found.model.metadata["unexplained_peaks_hz"]:
        pin_cpu, pinned = cpu_identify(
            frfs, max_order=found.model.metadata["max_order"], pin_hz=[peak]
        )
        low = max([band[0], *(p for p in peaks if p < peak - 1e-9)])
        high = min([band[1], *(p for p in peaks if p > peak + 1e-9)])
        band_cpu, banded = cpu_identify(frfs, band_hz=(low, high))
        print(
            f"{'':>26}  unexplained {peak:.1f} Hz at {label}: a pin keeps [{near(pinned, peak)}]"
            f" ({pin_cpu:.1f} s CPU); the band {low:.0f}-{high:.0f} Hz keeps "
            f"[{near(banded, peak)}] ({band_cpu:.1f} s CPU)"
        )


def real_cases(folder: Path) -> dict[str, Callable[[], FrfSet | FrfReferences]]:
    """The cases, each a reader of its FRFs (the tests' own readers)."""
    tests = Path(__file__).resolve().parents[1] / "tests"
    sys.path.insert(0, str(tests))  # the tests' readers: a benchmark, not a test
    import test_racket_data as rig
    from lab_rackets import TRIAL_RACKET_100
    from racketdyn.io import load_racket
    from racketdyn.workflows.rig import support_stream
    from test_realdata_must_hold import READ

    cases: dict[str, Callable[[], FrfSet | FrfReferences]] = {
        case: partial(read, folder / case) for case, read in READ.items()
    }
    racket = load_racket(rig.trial_racket_file(folder))

    def rig_frfs(racket: object, support: str, *options: object, **seed: object) -> FrfSet:
        return rig.measured_frfs(racket, support, *options, **seed)[0]  # type: ignore[no-any-return]

    for support in ("free", "hand"):
        cases[f"rig_{support}"] = partial(rig_frfs, racket, support)
    (folder / "trial.toml").write_text(TRIAL_RACKET_100, encoding="utf-8")
    trial = load_racket(folder / "trial.toml")
    for name, (noise, windows) in rig.HELD_TRIAL_CASES.items():
        stream = np.random.default_rng(support_stream(1, "hand"))
        cases[f"held_{name}"] = partial(rig_frfs, trial, "hand", noise, 10, windows, seed=stream)
    return cases


def real(only: list[str]) -> int:
    """The ``--real`` table (module docstring)."""
    logging.disable(logging.WARNING)
    with TemporaryDirectory() as scratch:
        folder = Path(scratch)
        for case, read in real_cases(folder).items():
            if only and case not in only:
                continue
            (folder / case).mkdir(exist_ok=True)
            frfs = read()
            several = isinstance(frfs, FrfReferences)
            base_order = 30 if several else 60
            base_cpu, base = cpu_identify(frfs, max_order=base_order)
            cpu, found = cpu_identify(frfs)
            if isinstance(found, str) or isinstance(base, str):
                print(f"{case}: {base if isinstance(base, str) else found}")
                continue
            peaks = found.model.metadata["peaks_in_band"]
            used = found.model.metadata["max_order"]
            band = found.model.metadata["band_hz"]
            print(
                f"{case:>26}: band {band[0]:.1f}-{band[1]:.0f} Hz, {peaks} peaks; order "
                f"{base_order} {base_cpu:6.1f} s CPU, {base.model.n_modes} modes | order {used} "
                f"{cpu:6.1f} s CPU (×{cpu / base_cpu:4.1f}), {found.model.n_modes} modes; "
                f"{compared(base, found)}; gained against {base_order}: {compared(found, base)}"
            )
            if several:
                order = min(ORDERS_PER_PEAK * peaks, MAX_RAISED_ORDER)
                more_cpu, more = cpu_identify(frfs, max_order=order)
                if not isinstance(more, str):
                    print(
                        f"{'':>26}  several references at {order}: {more_cpu:6.1f} s CPU, "
                        f"{more.model.n_modes} modes; {compared(base, more)}"
                    )
            tried(frfs, found, "default")
            tried(frfs, base, str(base_order))
    return 0


def main() -> int:
    if "--real" in sys.argv:
        return real([a for a in sys.argv[1:] if a != "--real"])
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
