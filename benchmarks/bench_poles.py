"""Benchmark: LSCF stabilisation diagram + automatic pole selection, against sdypy-EMA.

69 FRFs (the rig's free racket, accelerance, 1 % noise) × 1,551 lines between 60 Hz and the
analyser band's top (1,953 Hz at 200 µs sampling, 4,096 samples), every model order from 1 to
100.  Target: stabilisation + selection well under 0.5 s (the residue fit that follows needs
the rest of a second).  Baseline in the same run: sdypy-EMA's LSCF (``Model.get_poles``,
``pol_order_high=100``: the same number of poles per order) on the same FRFs and band; it has
no automatic selection, so its ``select_closest_poles`` is timed apart with the rig's true
frequencies given (the best it can do).  Accuracy of both against the rig's modal truth is
printed, the modes whose peak is under 5 × the noise apart.  sdypy-EMA is a benchmark-only
dependency (``pip install sdypy-EMA``); without it the comparison is skipped with a note.

Second part (issue 12): a real export's size — 9 FRFs × 51,201 lines (0–3,200 Hz, a free
aluminium bar's five modes, 1 % noise) in a Universal File (binary 58b, and ASCII) — timed from
the file to the modal model (``read_frfs`` + ``identify``: stabilisation, selection, constants,
shapes) in the 40–1,000 Hz band, against sdypy-EMA's ``get_poles`` + ``select_closest_poles``
(true frequencies given) + ``get_constants`` on the same arrays (its reading not counted).
Target: racketdyn ≥ 5× faster.

Third part (issue 25): the poly-reference LSCF against the scalar one on the same data — the
rig's 69 FRFs against three references (points 9, 0 and 40, 1 % noise each) — at
``identify``'s default orders (pLSCF matrix orders 1–30, the scalar LSCF 1–60): one reference,
the three fitted with one scalar denominator, the three with the pLSCF; times and accuracy
against the truth.  The single-reference path is the first part's, unchanged.

BLAS threads: one by default (``OPENBLAS_NUM_THREADS`` etc. set before numpy is imported,
unless already set): the work is many small matrices, for which extra BLAS threads cost more
than they give.  Run: ``python benchmarks/bench_poles.py``.  Informational: the exit status is
0 whatever the timings.
"""

from __future__ import annotations

import os

for _variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import contextlib  # noqa: E402
import io  # noqa: E402
import logging  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from collections.abc import Callable  # noqa: E402
from dataclasses import dataclass  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402
from numpy.typing import NDArray  # noqa: E402

import racketdyn as rd  # noqa: E402
from racketdyn.measurement.records import FrfSet  # noqa: E402
from racketdyn.modal.poles import select_poles, stabilisation  # noqa: E402
from racketdyn.modal.residues import fit_modal_constants  # noqa: E402
from racketdyn.rig import hammer_points, rig_model  # noqa: E402

MAX_ORDER = 100
BAND_LOW_HZ = 60.0
SAMPLING_S = 2.0e-4
N_SAMPLES = 4096
NOISE = 0.01
REFERENCE = 9  # a hoop point off the long axis: bending, twisting and membrane modes show
TARGET_S = 0.5


@dataclass(frozen=True)
class Truth:
    """The rig's modes inside the band (edges excluded) and their peaks over the noise."""

    frequency: NDArray[np.float64]
    damping_ratio: NDArray[np.float64]
    peak_to_noise: NDArray[np.float64]


def best_of(function: Callable[[], Any], repeats: int) -> tuple[float, Any]:
    """Shortest wall time over ``repeats`` calls, s, and the last result."""
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return min(times), result


def rig_frfs(reference: int = REFERENCE, seed: int = 1) -> tuple[FrfSet, Truth]:
    """69 accelerance FRFs of the free rig against hammer point ``reference`` with 1 % complex
    noise, and the truth (modes with their peaks against ``reference``)."""
    racket = rd.default_racket()
    model = rig_model(racket, "free")
    locations, nodes = hammer_points(racket, n_frame=24, n_strings=45)
    band_top = 1.0 / SAMPLING_S / 2.56
    lines = np.arange(N_SAMPLES // 2 + 1) / (N_SAMPLES * SAMPLING_S)
    lines = lines[lines <= band_top]
    values = model.frf(locations[reference : reference + 1], locations, lines)[0]
    rng = np.random.default_rng(seed)
    sigma = NOISE * float(np.abs(values).max())
    noise = rng.normal(size=values.shape) + 1j * rng.normal(size=values.shape)
    frfs = FrfSet(
        frequency=lines,
        values=values + sigma * noise / np.sqrt(2),
        frf_type="accelerance",
        nodes=nodes,
        locations=locations,
        reference_node=nodes[reference],
        reference_location=tuple(locations[reference]),
        source="virtual rig, free, 69 points",
    )
    modes = model.modal_truth(locations)
    inside = (modes.frequency > BAND_LOW_HZ * 1.05) & (modes.frequency < 0.98 * lines[-1])
    shapes = modes.mode_shapes[:, inside]
    peaks = np.abs(shapes * shapes[reference]).max(axis=0) / (2 * modes.damping_ratio[inside])
    truth = Truth(modes.frequency[inside], modes.damping_ratio[inside], peaks / sigma)
    return frfs, truth


def errors(frequency: NDArray[np.float64], damping: NDArray[np.float64], truth: Truth) -> str:
    """Modes found / expected and the errors against the truth, the weak peaks apart."""
    found = [int(np.argmin(np.abs(frequency - f))) for f in truth.frequency]
    df = np.abs(frequency[found] / truth.frequency - 1)
    dz = np.abs(damping[found] / truth.damping_ratio - 1)
    hit = df < 0.005
    strong = hit & (truth.peak_to_noise >= 5)
    text = (
        f"{hit.sum()}/{hit.size} modes; peaks ≥ 5 × noise: frequency within "
        f"{100 * df[strong].max():.3f} %, damping within {100 * dz[strong].max():.1f} %"
    )
    for k in np.flatnonzero(~strong):
        outcome = f"{100 * df[k]:.3f} %, {100 * dz[k]:.1f} %" if hit[k] else "missed"
        text += (
            f"; {truth.frequency[k]:.1f} Hz (peak {truth.peak_to_noise[k]:.1f} × noise) {outcome}"
        )
    return text


def main() -> None:
    logging.disable(logging.WARNING)
    frfs, truth = rig_frfs()
    band = (BAND_LOW_HZ, float(frfs.frequency[-1]))
    n_lines = int(np.count_nonzero(frfs.frequency >= BAND_LOW_HZ))
    print(
        f"racketdyn {rd.__version__}: {frfs.n_points} FRFs × {n_lines} lines "
        f"({band[0]:.0f}–{band[1]:.0f} Hz), orders 1–{MAX_ORDER}, "
        f"OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS')}"
    )
    stab_s, stab = best_of(lambda: stabilisation(frfs, band, max_order=MAX_ORDER), repeats=5)
    select_s, selected = best_of(lambda: select_poles(stab), repeats=5)
    residues_s, _ = best_of(lambda: fit_modal_constants(frfs, selected.pole, band), repeats=5)
    total = stab_s + select_s + residues_s
    verdict = "PASS" if total < TARGET_S else "MISS"
    print(f"  stabilisation, every order 1–{MAX_ORDER}         {stab_s * 1e3:8.1f} ms")
    print(f"  automatic selection                       {select_s * 1e3:8.1f} ms")
    print(f"  residues (LSFD, real modes, residuals)    {residues_s * 1e3:8.1f} ms")
    print(
        f"  racketdyn total                           {total * 1e3:8.1f} ms  "
        f"target < {TARGET_S * 1e3:.0f} ms: {verdict}"
    )
    print(f"    {errors(selected.frequency, selected.damping_ratio, truth)}")

    try:
        from sdypy import EMA  # type: ignore[import-not-found]
    except ImportError:
        print("  sdypy-EMA not importable: comparison skipped (pip install sdypy-EMA)")
        return

    def sdypy_poles() -> Any:
        model = EMA.Model(
            frf=frfs.values.copy(),
            freq=frfs.frequency.copy(),
            lower=BAND_LOW_HZ,
            upper=float(frfs.frequency[-1]),
            pol_order_high=MAX_ORDER,
            frf_form="accelerance",
        )
        with warnings.catch_warnings(), contextlib.redirect_stdout(io.StringIO()):
            warnings.simplefilter("ignore")
            model.get_poles(method="lscf", show_progress=False)
        return model

    sdypy_s, model = best_of(sdypy_poles, repeats=2)
    pick_start = time.perf_counter()
    with (
        warnings.catch_warnings(),
        contextlib.redirect_stdout(io.StringIO()),
        contextlib.redirect_stderr(io.StringIO()),  # its progress bar
    ):
        warnings.simplefilter("ignore")
        model.select_closest_poles(list(truth.frequency), f_window=5)
    pick_s = time.perf_counter() - pick_start
    print(
        f"  sdypy-EMA {EMA.__version__} get_poles, lscf, order {MAX_ORDER}  {sdypy_s * 1e3:8.1f} ms"
    )
    print(f"  sdypy-EMA select_closest_poles, answers given {pick_s * 1e3:8.1f} ms")
    nat_freq, nat_xi = np.asarray(model.nat_freq), np.asarray(model.nat_xi)
    print(f"    {errors(nat_freq, nat_xi, truth)}")
    print(f"  ratio sdypy-EMA get_poles / racketdyn stabilisation     {sdypy_s / stab_s:6.1f}×")
    print(
        "  ratio sdypy-EMA get_poles + select / racketdyn total    "
        f"{(sdypy_s + pick_s) / total:6.1f}×"
    )


EXPORT_LINES = 51_201
EXPORT_TOP_HZ = 3_200.0
EXPORT_BAND_HZ = (40.0, 1_000.0)
EXPORT_TARGET = 5.0


def bar_frfs() -> tuple[FrfSet, NDArray[np.float64]]:
    """9 accelerances of a free–free bar (0.8 m aluminium, 30 × 8 mm), 1 % noise; truth, Hz."""
    from scipy.optimize import brentq

    length, ei, rho_a = 0.8, 70e9 * 0.030 * 0.008**3 / 12, 2700 * 0.030 * 0.008
    beta = np.array(
        [
            brentq(
                lambda x: np.cos(x) * np.cosh(x) - 1,
                (n + 0.5) * np.pi - 0.5,
                (n + 0.5) * np.pi + 0.5,
            )
            for n in range(1, 6)
        ]
    )
    f_n = beta**2 / (2 * np.pi * length**2) * np.sqrt(ei / rho_a)
    s = np.linspace(0.0, length, 9)
    b = beta / length
    sigma = (np.cosh(beta) - np.cos(beta)) / (np.sinh(beta) - np.sin(beta))
    phi = (
        np.cosh(b * s[:, None])
        + np.cos(b * s[:, None])
        - sigma * (np.sinh(b * s[:, None]) + np.sin(b * s[:, None]))
    ) / np.sqrt(rho_a * length)
    frequency = np.linspace(0.0, EXPORT_TOP_HZ, EXPORT_LINES)
    w, wn = 2 * np.pi * frequency, 2 * np.pi * f_n
    h = (
        (phi * phi[0])[:, None, :]
        * (-(w[:, None] ** 2) / (wn**2 - w[:, None] ** 2 + 2j * 0.008 * wn * w[:, None]))[None]
    ).sum(-1)
    rng = np.random.default_rng(1)
    h = h * (1 + 0.01 * (rng.standard_normal(h.shape) + 1j * rng.standard_normal(h.shape)))
    frfs = FrfSet(
        frequency=frequency,
        values=h,
        frf_type="accelerance",
        nodes=tuple(range(1, 10)),
        locations=np.column_stack([s, np.zeros_like(s)]),
        reference_node=1,
        reference_location=(0.0, 0.0),
        source="free bar, 9 points",
    )
    return frfs, f_n


def main_export() -> None:
    """Read + identify a real export's size against sdypy-EMA (issue 12)."""
    import tempfile
    from pathlib import Path

    from racketdyn.io.frf_layout import read_frfs
    from racketdyn.io.uff import write_frf_uff
    from racketdyn.modal.identify import identify

    logging.disable(logging.WARNING)
    frfs, truth = bar_frfs()
    print(
        f"\nreal export's size: {frfs.n_points} FRFs × {EXPORT_LINES} lines "
        f"(0–{EXPORT_TOP_HZ:g} Hz), band {EXPORT_BAND_HZ[0]:g}–{EXPORT_BAND_HZ[1]:g} Hz"
    )
    with tempfile.TemporaryDirectory() as folder:
        paths = {}
        for kind, binary in (("binary 58b", True), ("ASCII 58", False)):
            paths[kind] = write_frf_uff(frfs, Path(folder) / f"{kind[:5]}.uff", binary=binary)
        timings = {}
        for kind, path in paths.items():
            read_s, read = best_of(lambda p=path: read_frfs(p), repeats=2)
            ident_s, found = best_of(lambda r=read: identify(r, EXPORT_BAND_HZ), repeats=2)
            timings[kind] = read_s + ident_s
            errors_pct = 100 * (found.model.frequency / truth[: found.model.n_modes] - 1)
            print(
                f"  racketdyn read ({kind}) {read_s * 1e3:8.1f} ms + identify "
                f"{ident_s * 1e3:8.1f} ms = {(read_s + ident_s) * 1e3:8.1f} ms; "
                f"{found.model.n_modes} modes, frequency error ≤ {np.abs(errors_pct).max():.4f} %"
            )
    try:
        from sdypy import EMA
    except ImportError:
        print("  sdypy-EMA not importable: comparison skipped (pip install sdypy-EMA)")
        return

    def sdypy_all() -> Any:
        model = EMA.Model(
            frf=frfs.values.copy(),
            freq=frfs.frequency.copy(),
            lower=EXPORT_BAND_HZ[0],
            upper=EXPORT_BAND_HZ[1],
            pol_order_high=MAX_ORDER,
            frf_form="accelerance",
        )
        with (
            warnings.catch_warnings(),
            contextlib.redirect_stdout(io.StringIO()),
            contextlib.redirect_stderr(io.StringIO()),
        ):
            warnings.simplefilter("ignore")
            model.get_poles(method="lscf", show_progress=False)
            model.select_closest_poles(list(truth), f_window=5)
            model.get_constants(whose_poles="own", FRF_ind="all")
        return model

    sdypy_s, model = best_of(sdypy_all, repeats=1)
    errors_pct = 100 * (np.asarray(model.nat_freq) / truth - 1)
    print(
        f"  sdypy-EMA {EMA.__version__} get_poles (order {MAX_ORDER}) + select_closest_poles + "
        f"get_constants {sdypy_s * 1e3:8.1f} ms; frequency error ≤ {np.abs(errors_pct).max():.4f} %"
    )
    for kind, total in timings.items():
        ratio = sdypy_s / total
        verdict = "PASS" if ratio >= EXPORT_TARGET else "MISS"
        print(
            f"  ratio sdypy-EMA / racketdyn ({kind} read + identify) {ratio:6.1f}×  target ≥ "
            f"{EXPORT_TARGET:g}×: {verdict}"
        )


POLY_REFERENCES = (REFERENCE, 0, 40)
POLY_MAX_ORDER = 30  # racketdyn.modal.polyreference.DEFAULT_MAX_ORDER, identify's default
SCALAR_MAX_ORDER = 60  # identify's default against one reference


def main_poly() -> None:
    """The pLSCF of three references against the scalar LSCF on the same FRFs (issue 25)."""
    from racketdyn.measurement.records import FrfReferences
    from racketdyn.modal.polyreference import poly_stabilisation

    logging.disable(logging.WARNING)
    made = [rig_frfs(r, seed=1 + k) for k, r in enumerate(POLY_REFERENCES)]
    sets = FrfReferences(tuple(frfs for frfs, _ in made))
    truth = made[0][1]
    # a mode counts as strong if some reference sees it 5 × above the noise
    strongest = np.max([t.peak_to_noise for _, t in made], axis=0)
    truth = Truth(truth.frequency, truth.damping_ratio, strongest)
    band = (BAND_LOW_HZ, float(sets.frequency[-1]))
    print(
        f"\npoly-reference: {len(sets.nodes)} points × {len(sets.sets)} references "
        f"{list(POLY_REFERENCES)} (hammer points), {band[0]:.0f}–{band[1]:.0f} Hz"
    )
    runs = (
        (
            f"scalar LSCF, one reference, orders 1–{SCALAR_MAX_ORDER}",
            lambda: stabilisation(sets.sets[0], band, max_order=SCALAR_MAX_ORDER),
        ),
        (
            f"scalar LSCF, three references, orders 1–{SCALAR_MAX_ORDER}",
            lambda: stabilisation(list(sets.sets), band, max_order=SCALAR_MAX_ORDER),
        ),
        (
            f"pLSCF, three references, matrix orders 1–{POLY_MAX_ORDER}",
            lambda: poly_stabilisation(sets, band, POLY_MAX_ORDER),
        ),
    )
    first = 0.0
    for label, run in runs:
        stab_s, stab = best_of(run, repeats=3)
        select_s, selected = best_of(lambda st=stab: select_poles(st), repeats=3)
        first = first or stab_s + select_s
        print(
            f"  {label:48s} {stab_s * 1e3:8.1f} ms + selection {select_s * 1e3:6.1f} ms "
            f"({(stab_s + select_s) / first:4.1f}× the first)"
        )
        print(f"    {errors(selected.frequency, selected.damping_ratio, truth)}")


if __name__ == "__main__":
    main()
    main_export()
    main_poly()
