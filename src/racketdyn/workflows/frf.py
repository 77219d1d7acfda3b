"""Step ``frf``: FRFs and the per-average quality table from hammer-test records.

Writes ``quality.csv``, ``frfs.uff`` (UFF 58, with geometry) and ``run.json`` (with the FRFs whose
coherence says they measured noise alone, ``noise_frfs``); figures come from the caller's hook.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np

from racketdyn.errors import InputError, one_of, require_positive
from racketdyn.io import read_hammer_csv, read_hammer_uff, write_frf_uff
from racketdyn.measurement import HammerRecords
from racketdyn.measurement.frf import FrfEstimate, estimate_frfs
from racketdyn.measurement.quality import QualitySettings
from racketdyn.plausibility import check
from racketdyn.racket import Racket
from racketdyn.workflows.figure_data import defer_figure_data
from racketdyn.workflows.frf_figures import FrfPoints, frf_points
from racketdyn.workflows.inputs import load_racket_input, with_racket_of_run
from racketdyn.workflows.run import (
    StepResult,
    report,
    run_step,
    sha256,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

__all__ = ["ESTIMATORS", "FrfResult", "read_records", "run_frf"]

ESTIMATORS = ("H1", "H2")


def read_records(
    path: str | os.PathLike[str], geometry: str | os.PathLike[str] | None = None
) -> HammerRecords:
    """Hammer records from UFF 58 or CSV; node coordinates from the file or ``geometry``.

    FRFs need no coordinates: without them the locations are NaN and the steps that need them
    ask for ``--geometry``.

    Parameters
    ----------
    path : path
        UFF or CSV records.
    geometry : path, optional
        Node coordinates (UFF 15/2411, or CSV ``node, x_m, y_m``).
    """
    path = Path(path)
    if path.suffix.lower() == ".csv":
        return read_hammer_csv(path, None if geometry is None else Path(geometry))
    return read_hammer_uff(path, None if geometry is None else Path(geometry))


@dataclass
class FrfResult(StepResult):
    """What :func:`run_frf` estimated and wrote.

    Attributes
    ----------
    estimate : FrfEstimate
        FRFs (``estimate.frfs``), per-average checks and rejected points.
    racket : Racket
        The racket (head outline for the figures).
    records_metadata : dict
        What the reader said of the records (``three_d_geometry``: the file whose points
        differ in z, read without coordinates).
    frf_points : FrfPoints or None
        The FRFs Figs 2–3 draw (in ``figures.nc``).
    """

    estimate: FrfEstimate | None = None
    racket: Racket | None = None
    records_metadata: dict[str, Any] = field(default_factory=dict)
    frf_points: FrfPoints | None = None


def _check_hits(tests: object, estimate: FrfEstimate, allow_implausible: bool) -> None:
    """Refuse forces whose accepted hits peak where no modal hammer's do (forces in volts):
    the FRFs and the shapes' scale would be in the wrong unit, with nothing saying so."""
    peaks = [c.peak_force_n for c in estimate.checks if c.accepted]
    if peaks:
        check(
            "hammer_peak_force_n",
            float(np.median(peaks)),
            f"{tests}: the accepted hits' median peak force",
            allow_implausible=allow_implausible,
            override="scale the force channel to newtons (by the hammer's sensitivity), or "
            "take the forces as they are with `allow_implausible` (frequencies and damping do "
            "not depend on the force's unit; the FRFs' and the shapes' scale do)",
        )


@run_step
def run_frf(
    tests: str | os.PathLike[str],
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    *,
    geometry: str | os.PathLike[str] | None = None,
    estimator: Literal["H1", "H2"] = "H1",
    force_window_s: float | None = None,
    exponential_window_s: float | None = None,
    force_range_n: float | None = None,
) -> FrfResult:
    """Estimate FRFs from hammer records and write the run folder.

    Parameters
    ----------
    tests : path
        Hammer records: UFF 58 time records, or CSV (with ``geometry``).
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, frf uses the racket (its head outline,
        for the figures) and ``allow_implausible`` (the hammer's range); and the run (command,
        figures, progress).
    geometry : path, optional
        Node coordinates if not in ``tests``.
    estimator : {"H1", "H2"}
        FRF estimator.
    force_window_s : float, optional
        Keep the force this long after the trigger, s (default: the whole record).
    exponential_window_s : float, optional
        Exponential window time constant τ, s (default: none).
    force_range_n : float, optional
        Hammer channel range, N: reaching it is an overload (finite, positive; 10–100 000 N
        unless ``setup.allow_implausible``).
    """
    one_of("`estimator`", estimator, ESTIMATORS)
    if force_range_n is not None:
        force_range_n = require_positive("`force_range_n`", force_range_n)
        check(
            "force_range_n",
            force_range_n,
            "`force_range_n`",
            allow_implausible=setup.allow_implausible,
        )
    records = read_records(tests, geometry)
    setup, from_run = with_racket_of_run(setup, tests)
    the_racket, provenance = load_racket_input(setup.racket)
    provenance |= from_run
    out_dir = Path(out)
    report(setup.progress, "estimating FRFs")
    estimate = estimate_frfs(
        records,
        estimator=estimator,
        force_window_s=force_window_s,
        exponential_window_s=exponential_window_s,
        quality=QualitySettings(overload_level_n=force_range_n),
    )
    estimate.write_quality_csv(out_dir / "quality.csv")
    _check_hits(tests, estimate, setup.allow_implausible)
    result = FrfResult(
        out_dir,
        [out_dir / "quality.csv"],
        estimate=estimate,
        racket=the_racket,
        records_metadata=dict(records.metadata),
    )
    if estimate.frfs is None:
        # the run folder is left as it was: the reasons go into the message
        raise InputError(
            f"{tests}: every average of every point was rejected: {estimate.rejections()}; "
            "check the hammer channel (a clean impulse a hit) and the force range and window "
            "(`force_range_n`, `force_window_s`)"
        )
    result.written.append(write_frf_uff(estimate.frfs, out_dir / "frfs.uff"))
    noise = estimate.noise_only()
    result.frf_points = frf_points(estimate.frfs, the_racket)
    defer_figure_data(result, {"frf_points": result.frf_points})
    inputs = {
        "tests_file": str(Path(tests).resolve()),
        "tests_sha256": sha256(Path(tests)),
        **provenance,
        "estimator": estimator,
        "force_window_s": force_window_s,
        "exponential_window_s": exponential_window_s,
        "force_range_n": force_range_n,
        "quality": estimate.summary(),
        "rejected_points": list(estimate.rejected_points),
        "three_d_geometry": records.metadata.get("three_d_geometry"),
        "fewer_averages": records.metadata.get("fewer_averages"),
        "force_band_hz": estimate.frfs.force_band_hz,
        "noise_frfs": None if noise is None else noise.record(),
        "force_noise": {
            "share_of_band_median": _median(estimate.force_noise_share),
            "share_with_force_window_median": _median(estimate.force_noise_share_windowed),
            "hint": estimate.force_noise_hint(),
            "why": "the share of the lines up to the bandwidth where the force's noise (its "
            "pre-trigger rms over the windowed record) is over a tenth of the force's "
            "autospectrum (H1 low by 9 % or more there), and with a 10 ms force window "
            "(racketdyn.measurement.frf.FrfEstimate)",
        },
    }
    return setup.finish(result, inputs, "frf")


def _median(values: tuple[float, ...]) -> float | None:
    return float(np.median(values)) if values else None
