"""Stabilisation diagrams and the identified modes of each model."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from racketdyn._grammar import plural
from racketdyn.plotting.registry import labelled
from racketdyn.report.figures import FigureGroup
from racketdyn.report.folder import RunFolder, number, read_csv, read_json
from racketdyn.report.formatting import fmt

HOW_TO_RUN = (
    "racketdyn compare DIR/frf_free/frfs.uff DIR/frf_hand/frfs.uff "
    "--out DIR/compare (or racketdyn identify)"
)


def _sentence(record: dict[str, Any], folder: Path, suffix: str, key: str) -> str:
    """The sentence of an identification's record ``key`` — ``misfit``, the verdict on the fit
    error (:mod:`racketdyn.modal.misfit`), or ``noise_frfs``, the FRFs that measured noise alone
    (:func:`racketdyn.measurement.quality.noise_only_frfs`): run.json's, in the words of the
    command that ran (``KEY`` of identify, ``KEY_free``/``_hand`` of compare), else the model
    file's with its parameter names as plain words; empty without one."""
    kept = record.get(f"{key}{suffix}")
    if not isinstance(kept, dict):
        path = folder / f"modal_model{suffix}.json"
        if not path.is_file():
            return ""
        kept = read_json(path).get("metadata", {}).get(key) or {}
    return str(kept.get("sentence", "")).replace("`", "")


def fit_error_line(path: Path) -> str:
    """The median and largest fit error of an identification's ``fit_quality*.csv`` over the
    FRFs that carry the structure (rows not ``noise_only``; every row where all are, or where
    the file does not say), as the verdict reads them (:func:`racketdyn.modal.misfit.misfit`);
    empty without a finite error."""
    rows = read_csv(path, ("fit_error",))
    noise = np.array([r.get("noise_only", "") == "1" for r in rows], dtype=bool)
    if noise.all():
        noise[:] = False
    errors = np.array(
        [number(r, "fit_error") for r, alone in zip(rows, noise, strict=True) if not alone]
    )
    if not (errors.size and np.isfinite(errors).any()):
        return ""
    line = f"median {np.nanmedian(errors):.1%}, largest {np.nanmax(errors):.1%}"
    n = int(noise.sum())
    return f"{line} ({plural(n, 'FRF')} of noise left out)" if n else line


def gather(run: RunFolder) -> dict[str, Any] | None:
    """For every identification: its figures, its ``modes*.csv`` and ``fit_quality*.csv``, and
    the orders it dropped (run.json)."""
    idents = run.identifications
    if not idents:
        return None

    def figures(stem: str) -> FigureGroup | None:
        return run.group([(f / labelled(stem, s), label) for label, f, s in idents])

    models = []
    for label, folder, suffix in idents:
        rows = read_csv(folder / f"modes{suffix}.csv", ("frequency_hz", "damping_ratio"))
        body = [
            (
                r.get("name", ""),
                fmt(number(r, "frequency_hz"), ".2f"),
                fmt(100 * number(r, "damping_ratio"), ".3f"),
                r.get("orders_stable", ""),
                fmt(number(r, "frequency_spread_hz"), ".3g"),
            )
            for r in rows
        ]
        fit = folder / f"fit_quality{suffix}.csv"
        fit_error = fit_error_line(fit) if fit.is_file() else ""
        dropped = [str(d) for d in run.record(folder).get("dropped") or []]
        models.append(
            {
                "label": label,
                "modes": body,
                "fit_error": fit_error,
                "misfit": _sentence(run.record(folder), folder, suffix, "misfit"),
                "noise": _sentence(run.record(folder), folder, suffix, "noise_frfs"),
                "dropped": dropped,
            }
        )
    return {
        "diagrams": figures("stabilisation"),
        "models": models,
        "synthesised": figures("synthesised_frfs"),
        "automac": figures("automac"),
    }
