"""The racket and its derived properties; the modes the prediction used."""

from __future__ import annotations

import math
from typing import Any

from racketdyn.report.folder import RunFolder
from racketdyn.report.formatting import DERIVED_LABELS, fmt, quantity

HOW_TO_RUN = "racketdyn predict --out DIR/predict (or racketdyn rig --out DIR/rig)"


def _racket_file(name: object) -> str:
    """The racket file a run.json records, in words."""
    text = str(name or "")
    if not text:
        return "the racket file"
    return "the built-in racket" if text.startswith("built-in") else text


def gather(run: RunFolder) -> dict[str, Any] | None:
    """The racket's inputs and derived properties: from the racket given to the report
    (``--racket``, the demo's racket), else from the run.json of ``predict`` (or the rig)."""
    racket_record: dict[str, Any] | None = None
    source = ""
    if run.racket is not None:
        from racketdyn.io import default_racket, racket_to_dict

        racket_record = racket_to_dict(run.racket)
        builtin = run.racket == default_racket()
        source = "the built-in racket" if builtin else "the racket given with --racket"
    else:
        for folder in filter(None, (run.predict_dir, run.first("hammer_*.uff"))):
            record = run.record(folder)
            if isinstance(record.get("racket"), dict):
                racket_record = record["racket"]
                source = (
                    f"{_racket_file(record.get('racket_file'))}, as recorded in "
                    f"{run.rel(folder / 'run.json')}"
                )
                break
    if racket_record is None:
        return None
    derived = run.derived()
    inputs = []
    for key, value in racket_record.items():
        if key in ("name", "derived"):
            continue
        if isinstance(value, dict):
            for sub, subvalue in value.items():
                label, text, unit = quantity(sub, subvalue)
                inputs.append((f"{key}: {label}", text, unit))
        elif isinstance(value, list):
            inputs.append((key.replace("_", " "), str(len(value)) if value else "none", ""))
        else:
            inputs.append(quantity(key, value))
    rows = []
    for key, value in derived.items():
        if key == "inertia_cg_kgm2" and "recoil_weight_kgcm2" in derived:
            continue  # the same quantity as the recoil weight: one row, one unit
        name, text, unit = quantity(key, value)
        rows.append((DERIVED_LABELS.get(key.rpartition("_")[0], name), text, unit))
    name = str(racket_record.get("name", "racket"))
    glance = []
    if derived:
        glance.append(
            f"{racket_record.get('name', 'racket')}: "
            f"{fmt(derived.get('mass_kg', math.nan) * 1e3, '.0f')} g, balance "
            f"{fmt(derived.get('balance_m', math.nan) * 1e3, '.0f')} mm, swingweight "
            f"{fmt(derived.get('swingweight_kgcm2'), '.0f')} kg·cm²"
        )
    model = run.record(run.predict_dir).get("modal_model")
    modes = []
    if isinstance(model, dict) and model.get("modes"):
        modes = [
            (
                str(m.get("name", "")),
                str(m.get("kind", "")),
                fmt(m.get("frequency_hz"), ".1f"),
                fmt(100 * float(m.get("damping_ratio", math.nan)), ".2f"),
            )
            for m in model["modes"]
        ]
    else:
        model = {}
    return {
        "name": name,
        "source": source,
        "derived": rows,
        "inputs": inputs,
        "modes": modes,
        "model_source": str(model.get("source", "")),
        "model_support": str(model.get("support", "")),
        "glance": glance,
    }
