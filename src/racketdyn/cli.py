"""The ``racketdyn`` command line: parse, call the library, print with rich.

Every user error becomes one line on stderr and exit status 2; no traceback.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import json
import logging
import math
import os
import platform
import sys
import time
from collections.abc import Sequence
from dataclasses import asdict, replace
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np
from rich.console import Console
from rich.progress import Progress
from rich.table import Table

from racketdyn.__about__ import __version__
from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law
from racketdyn.errors import (
    InputError,
    one_of,
    require_finite,
    require_positive,
    require_speeds,
)
from racketdyn.impact import ImpactResult, predict
from racketdyn.impact.comparison import (
    COMPARED,
    HISTORY_COLUMNS,
    History,
    ModelComparison,
    compare_models,
    simulate_histories,
    write_histories_csv,
)
from racketdyn.impact.hand import Hand
from racketdyn.impact.oblique import DEFAULT_TANGENTIAL_CONTACT, TangentialContact, oblique_curve
from racketdyn.impact.result import shown_speed_index
from racketdyn.impact.swing import (
    DEFAULT_ARM_GYRATION_M,
    DEFAULT_ARM_MASS_KG,
    DEFAULT_AXIS_TO_BUTT_M,
    DEFAULT_SWING_ANGLE_RAD,
    DEFAULT_TORQUE_NM,
    ImpactModel,
    SweetSpot,
    Swing,
    predict_swing,
    sweet_spot_table,
    sweet_spots,
)
from racketdyn.impact.transient import ENGINES, TRANSIENT_SUPPORTS, predict_transient
from racketdyn.impact.twist import twist_curve
from racketdyn.io import (
    default_racket,
    load_racket,
    racket_to_dict,
    read_frf_uff,
    read_hammer_csv,
    read_hammer_uff,
    read_load_deflection,
    read_points,
    write_frf_uff,
)
from racketdyn.io.racket_file import DEFAULT_RACKET_NAME
from racketdyn.measurement import HammerRecords
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.measurement.pulse import contact_times
from racketdyn.measurement.quality import QualitySettings
from racketdyn.modal import ModalModel
from racketdyn.modal.identify import Identification
from racketdyn.racket import SUPPORTS, Racket
from racketdyn.racket_modal import modal_model_for

__all__ = ["main"]

log = logging.getLogger("racketdyn")
DEFAULT_GRID = 9
MAX_GRID = 400  # 400 × 400 ≈ 126,000 points: a few seconds a speed
CHUNK_IMPACTS = 50_000  # above this, predict in chunks of points with a progress bar


def _parse_list(name: str, text: str) -> list[str]:
    items = [item.strip() for item in text.split(",")]
    if not all(items):
        raise InputError(
            f"{name} must be a comma-separated list without empty items (got {text!r})"
        )
    return items


def _parse_speeds(name: str, text: str) -> list[float]:
    speeds = []
    for item in _parse_list(name, text):
        try:
            speeds.append(float(item))
        except ValueError:
            raise InputError(
                f"{name}: {item!r} is not a number; give speeds in m/s, e.g. 10,20,30"
            ) from None
    return [float(v) for v in require_speeds(name, speeds)]


def _load(racket_file: str | None) -> tuple[Racket, dict[str, Any]]:
    if racket_file is None:
        return default_racket(), {"racket_file": f"built-in {DEFAULT_RACKET_NAME}"}
    path = Path(racket_file)
    racket = load_racket(path)
    return racket, {
        "racket_file": str(path.resolve()),
        "racket_file_sha256": hashlib.sha256(path.read_bytes()).hexdigest(),
    }


def _ball(args: argparse.Namespace) -> tuple[Ball, list[str]]:
    defaults = []
    kwargs: dict[str, Any] = {}
    for option, key, label in (
        ("ball_mass", "mass_kg", "ball mass 57.7 g (ITF middle)"),
        ("e_bg", "e_bg", "e_BG 0.83 (Kawazoe)"),
    ):
        value = getattr(args, option)
        if value is None:
            defaults.append(label)
        else:
            kwargs[key] = value
    if args.ball_law is not None:
        deflection, force = read_load_deflection(Path(args.ball_law))
        kwargs["restoring_force"] = RestoringForce.fit(
            deflection, force, "polynomial", 3, f"ball, fitted to {Path(args.ball_law).name}"
        )
    else:
        defaults.append("ball law: ITF forward deformation + adiabatic gas (one side)")
    return Ball(**kwargs), defaults


def _points(args: argparse.Namespace, racket: Racket) -> tuple[np.ndarray, list[str], str]:
    if args.points is not None and args.grid is not None:
        raise InputError("give --grid or --points, not both")
    if args.points is not None:
        locations, labels = read_points(Path(args.points))
        return locations, labels, f"points file {Path(args.points).resolve()}"
    n = DEFAULT_GRID if args.grid is None else args.grid
    if not 1 <= n <= MAX_GRID:
        raise InputError(f"--grid must be a whole number from 1 to {MAX_GRID} (got {n})")
    locations = racket.head.grid(n)
    return locations, [str(i + 1) for i in range(len(locations))], f"grid {n} x {n} over the head"


def _predict(args: argparse.Namespace, console: Console) -> int:
    racket, provenance = _load(args.racket)
    if args.modal is not None:
        if args.rigid:
            raise InputError("give --modal or --rigid, not both")
        if not Path(args.modal).is_file():
            raise InputError(f"--modal {args.modal}: no such modal model file")
        racket = replace(racket, modal_model_file=Path(args.modal))
        provenance["modal_model_sha256"] = _sha256(Path(args.modal))
    ball, defaults = _ball(args)
    speeds = _parse_speeds("--speed", args.speed)
    racket_speed = _parse_speeds("--racket-speed", args.racket_speed)
    if len(racket_speed) not in (1, len(speeds)):
        raise InputError("--racket-speed takes one speed, or one per --speed value")
    supports = _supports(args)
    hand = _hand(args, supports, defaults)
    transient_wanted = args.model in ("transient", "both")
    if not transient_wanted:
        if args.engine is not None:
            raise InputError("--engine is for the transient model: add --model transient or both")
    elif args.stiffness_reading is not None and args.model == "transient":
        raise InputError(
            "--stiffness-reading is a choice of the approximate method (eq 10); the transient "
            "model integrates the contact: drop it, or use --model approx or both"
        )
    engine = args.engine or "auto"
    stiffness_reading = args.stiffness_reading or "period"
    locations, labels, points_source = _points(args, racket)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.racket is None:
        defaults.append(f"racket: built-in {DEFAULT_RACKET_NAME} (Kawazoe's test racket)")
    if racket.modal_model_file is None and not args.rigid:
        defaults.append("modal model: built-in free-free beam model")
    model = None if args.rigid else modal_model_for(racket)
    law = compound_law(racket, ball)

    written: list[Path] = []
    approximate = transient = None
    if args.model in ("approx", "both"):
        approximate = _predict_approximate(
            racket,
            ball,
            locations,
            speeds,
            labels,
            console,
            supports=supports,
            racket_speed=np.asarray(racket_speed),
            modal_model=model,
            law=law,
            include_string_bed=args.include_string_bed,
            stiffness_reading=stiffness_reading,
        )
        approximate.write_csv(out / "impact.csv")
        written.append(out / "impact.csv")
    histories: list[History] = []
    mode_names: Sequence[str] = ()
    comparison = None
    chosen = shown_speed_index(speeds)
    transient_csv = "impact.csv" if args.model == "transient" else "impact_transient.csv"
    if transient_wanted:
        transient = _predict_transient(
            racket,
            ball,
            locations,
            speeds,
            labels,
            console,
            supports=supports,
            racket_speed=np.asarray(racket_speed),
            modal_model=model,
            law=law,
            include_string_bed=args.include_string_bed,
            engine=engine,
            hand=hand,
        )
        transient.write_csv(out / transient_csv)
        written.append(out / transient_csv)
        # the named points of the paper's figures
        from racketdyn.plotting.figures import landmark_points

        marks = landmark_points(racket)
        with console.status("simulating the time histories"):
            histories = simulate_histories(
                racket,
                ball,
                {"centre": marks["centre"], "tip": marks["tip"]},
                speeds[chosen],
                supports,
                racket_speed[chosen if len(racket_speed) > 1 else 0],
                modal_model=model,
                law=law,
                include_string_bed=args.include_string_bed,
                hand=hand,
            )
        mode_names = () if transient.modal_model is None else transient.modal_model.names
        written.append(write_histories_csv(histories, mode_names, out / "transient_histories.csv"))
    if approximate is not None and transient is not None:
        comparison = compare_models(approximate, transient)
        written.append(comparison.write_csv(out / "comparison.csv"))
    if not args.no_figures:
        from racketdyn.plotting.figures import FIGURES, write_paper_figures, write_transient_figures

        with console.status("drawing figures") as status:
            if approximate is not None:
                written += write_paper_figures(
                    racket,
                    ball,
                    model,
                    out,
                    progress=lambda name: status.update(f"drawing {name} ({len(FIGURES)} figures)"),
                )
            if transient is not None:
                status.update("drawing the transient model's figures")
                curves = {
                    "ball": ball,
                    "model": model,
                    "supports": supports,
                    "law": law,
                    "include_string_bed": args.include_string_bed,
                    "engine": engine,
                }
                written += write_transient_figures(
                    out,
                    racket,
                    histories,
                    mode_names,
                    comparison,
                    chosen,
                    curves if comparison is not None else None,
                )
    result = approximate if approximate is not None else transient
    assert result is not None  # argparse allows only the three models
    record = {
        "racketdyn_version": __version__,
        "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
        "command": ["racketdyn", *args.argv],
        "python": platform.python_version(),
        "numpy": np.__version__,
        **provenance,
        "racket": racket_to_dict(racket),
        "speeds_mps": speeds,
        "racket_speed_mps": racket_speed,
        "supports": supports,
        "points": points_source,
        "n_points": len(locations),
        "rigid": args.rigid,
        "defaults_used": defaults,
        **result.inputs,
        "model": args.model,
        **_transient_record(transient, approximate, engine),
        "outputs": [p.name for p in written] + ["run.json"],
    }
    (out / "run.json").write_text(json.dumps(record, indent=2, default=str), encoding="utf-8")
    console.print(
        f"[bold]{result.status.size}[/] impacts "
        f"({len(locations)} points × {len(speeds)} speeds × {len(supports)} supports) "
        f"{'by each model ' if comparison is not None else ''}→ {out}"
    )
    for label, part, csv_name in (
        ("approximate method", approximate, "impact.csv"),
        ("transient model", transient, transient_csv),
    ):
        if part is None:
            continue
        bad = part.status != "ok"
        if np.any(bad):
            reasons, counts = np.unique(part.status[bad], return_counts=True)
            for reason, count in zip(reasons, counts, strict=True):
                console.print(
                    f"[yellow]{label}: {count} impacts: {reason}; their results are NaN in "
                    f"{csv_name}[/]"
                )
    if comparison is not None:
        console.print(_comparison_table(comparison, chosen, racket))
    console.print(f"compound ball+string law: {law.describe()}")
    for path in written:
        console.print(f"  wrote {path}")
    return 0


MODELS = ("approx", "transient", "both")
TRANSIENT_FIRST_CHUNK = 32  # transient impacts in the first chunk, timed to size the others
TRANSIENT_CHUNK_S = 0.5  # then chunks of about this long: the progress bar moves smoothly
TRANSIENT_QUIET_IMPACTS = 64  # no progress bar up to this many transient impacts


def _supports(args: argparse.Namespace) -> list[str]:
    """The supports asked for, each allowed by the model(s) asked for."""
    allowed = TRANSIENT_SUPPORTS if args.model == "transient" else SUPPORTS
    supports = []
    for support in _parse_list("--support", args.support):
        if support == "hand" and args.model != "transient":
            raise InputError(
                "--support hand needs --model transient: the approximate method has no hand "
                "(its hand-held racket is pinned at the grip: --support pinned)"
            )
        supports.append(one_of("--support", support, allowed))
    if len(set(supports)) != len(supports):
        raise InputError(f"--support: name each support once (got {args.support})")
    return supports


def _hand(args: argparse.Namespace, supports: Sequence[str], defaults: list[str]) -> Hand | None:
    """The hand of the ``hand`` support (None without it)."""
    if "hand" not in supports:
        if args.hand_arm_mass is not None:
            raise InputError("--hand-arm-mass is for --support hand (with --model transient)")
        return None
    if args.hand_arm_mass is None:
        defaults.append("hand: racketdyn.impact.hand.Hand defaults (1 kg arm, Kawazoe ACMD 2002)")
        return Hand()
    return Hand(arm_mass_kg=args.hand_arm_mass)


def _predict_approximate(
    racket: Racket,
    ball: Ball,
    locations: np.ndarray,
    speeds: list[float],
    labels: list[str],
    console: Console,
    **options: Any,
) -> ImpactResult:
    """The approximate method, in chunks of points with a progress bar when large."""
    per_point = len(speeds) * len(options["supports"])
    if len(locations) * per_point <= CHUNK_IMPACTS:
        return predict(racket, ball, locations, speeds, labels=labels, **options)
    step = max(CHUNK_IMPACTS // per_point, 1)
    parts = []
    with Progress(console=console, transient=True) as progress:
        task = progress.add_task("predicting", total=len(locations))
        for start in range(0, len(locations), step):
            stop = min(start + step, len(locations))
            chunk_labels = labels[start:stop]
            parts.append(
                predict(racket, ball, locations[start:stop], speeds, labels=chunk_labels, **options)
            )
            progress.update(task, completed=stop)
    return ImpactResult.concatenate(parts)


def _predict_transient(
    racket: Racket,
    ball: Ball,
    locations: np.ndarray,
    speeds: list[float],
    labels: list[str],
    console: Console,
    **options: Any,
) -> ImpactResult:
    """The transient model, in chunks of points sized to about half a second, with a progress
    bar (the first chunk is timed to size the others: the engines differ a thousandfold)."""
    per_point = len(speeds) * len(options["supports"])
    total = len(locations) * per_point

    def chunk(start: int, stop: int) -> ImpactResult:
        return predict_transient(
            racket, ball, locations[start:stop], speeds, labels=labels[start:stop], **options
        )

    if total <= TRANSIENT_QUIET_IMPACTS:
        return chunk(0, len(locations))
    parts = []
    with Progress(console=console, transient=True) as progress:
        task = progress.add_task("transient simulation", total=total)
        start, step = 0, max(TRANSIENT_FIRST_CHUNK // per_point, 1)
        while start < len(locations):
            stop = min(start + step, len(locations))
            began = time.perf_counter()
            parts.append(chunk(start, stop))
            elapsed = max(time.perf_counter() - began, 1e-6)
            progress.update(task, completed=stop * per_point)
            step = max(int(TRANSIENT_CHUNK_S * (stop - start) / elapsed), 1)
            start = stop
    return ImpactResult.concatenate(parts)


def _transient_record(
    transient: ImpactResult | None, approximate: ImpactResult | None, engine: str
) -> dict[str, Any]:
    """What run.json says about the transient model: engine, integrator, its outputs."""
    if transient is None:
        return {}
    inputs = transient.inputs
    integrator = inputs.get("integrator")
    used = integrator.get("engine") if isinstance(integrator, dict) else None
    record: dict[str, Any] = {
        "engine": {"requested": engine, "used": used or "not recorded by predict_transient"},
        "integrator": integrator,
        "time_histories": "simulate_impact (the reference engine: scipy solve_ivp, DOP853, "
        "rtol 1e-10) at the centre and the tip, each support",
        "columns": {
            "transient_histories.csv": HISTORY_COLUMNS,
            **(
                {}
                if approximate is None
                else {
                    "comparison.csv": "per point x speed x support: approx_<q>, transient_<q>, "
                    "difference_<q> = approx - transient, relative_difference_<q> = "
                    "(approx - transient) / |transient| for q in "
                    + ", ".join(COMPARED.values())
                    + "; status_approx, status_transient"
                }
            ),
        },
    }
    if approximate is not None:  # the approximate method's inputs are at the top level
        record["transient"] = {
            key: value
            for key, value in inputs.items()
            if key not in approximate.inputs or approximate.inputs[key] != value
        }
    return record


def _comparison_table(comparison: ModelComparison, speed: int, racket: Racket) -> Table:
    """At the point nearest the face centre, and the largest difference over the face."""
    result = comparison.approximate
    centre = np.array([racket.head.centre_x_m, racket.head.centre_y_m])
    i = int(np.argmin(np.linalg.norm(result.locations - centre, axis=1)))
    x, y = result.locations[i] * 1e3
    table = Table(
        title=f"approximate against transient at {result.ball_speed[speed]:g} m/s "
        f"(centre: point {result.labels[i]}, x = {x:.0f} mm, y = {y:.0f} mm)"
    )
    for heading in (
        "support",
        "e approx",
        "e transient",
        "T_c approx (ms)",
        "T_c transient (ms)",
        "largest |Δe| on the face",
        "at x, y (mm)",
    ):
        table.add_column(heading)
    e_a, e_t = comparison.values("rebound_ratio")
    t_a, t_t = comparison.values("contact_time")
    difference = np.abs(comparison.difference("rebound_ratio"))
    for p, support in enumerate(result.supports):
        column = difference[:, speed, p]
        if np.any(np.isfinite(column)):
            worst = int(np.nanargmax(column))
            where = (
                f"{result.locations[worst, 0] * 1e3:.0f}, {result.locations[worst, 1] * 1e3:.0f}"
            )
            largest = f"{column[worst]:.3f}"
        else:
            largest, where = "–", "–"
        table.add_row(
            support,
            f"{e_a[i, speed, p]:.3f}",
            f"{e_t[i, speed, p]:.3f}",
            f"{t_a[i, speed, p] * 1e3:.2f}",
            f"{t_t[i, speed, p] * 1e3:.2f}",
            largest,
            where,
        )
    return table


def _racket(args: argparse.Namespace, console: Console) -> int:
    racket, provenance = _load(args.racket)
    table = Table(title=f"{racket.name} ({provenance['racket_file']})")
    table.add_column("property")
    table.add_column("value", justify="right")
    table.add_column("unit")
    units = {"kg": "kg", "m": "m", "kgm2": "kg·m²", "kgcm2": "kg·cm²", "cm2": "cm²"}
    for key, value in racket.derived_properties().items():
        name, _, unit = key.rpartition("_")
        table.add_row(name.replace("_", " "), f"{value:.4g}", units.get(unit, unit))
    model = modal_model_for(racket)
    for name, frequency in zip(model.names, model.frequency, strict=True):
        table.add_row(f"mode: {name} ({model.support})", f"{frequency:.1f}", "Hz")
    console.print(table)
    return 0


def _read_records(path_text: str, geometry: str | None) -> HammerRecords:
    path = Path(path_text)
    if path.suffix.lower() == ".csv":
        if geometry is None:
            raise InputError(f"{path}: a CSV of hammer records needs --geometry NODES.csv")
        return read_hammer_csv(path, geometry)
    return read_hammer_uff(path, geometry)


def _write_record(
    out: Path, args: argparse.Namespace, inputs: dict[str, Any], outputs: list[Path]
) -> None:
    record = {
        "racketdyn_version": __version__,
        "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
        "command": ["racketdyn", *args.argv],
        "python": platform.python_version(),
        "numpy": np.__version__,
        **inputs,
        "outputs": [p.name for p in outputs] + ["run.json"],
    }
    (out / "run.json").write_text(json.dumps(record, indent=2, default=str), encoding="utf-8")


def _sha256(path: Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def _frf(args: argparse.Namespace, console: Console) -> int:
    from racketdyn.plotting.figures import write_frf_figures

    records = _read_records(args.tests, args.geometry)
    racket, provenance = _load(args.racket)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with console.status("estimating FRFs"):
        estimate = estimate_frfs(
            records,
            estimator=args.estimator,
            force_window_s=args.force_window,
            exponential_window_s=args.exp_window,
            quality=QualitySettings(overload_level_n=args.force_range),
        )
    estimate.write_quality_csv(out / "quality.csv")
    written = [out / "quality.csv"]
    if estimate.frfs is None:
        raise InputError(
            f"{args.tests}: every average of every point was rejected; see {written[0]}"
        )
    written.append(write_frf_uff(estimate.frfs, out / "frfs.uff"))
    with console.status("drawing figures"):
        written += write_frf_figures(estimate.frfs, racket, out)
    summary = estimate.summary()
    _write_record(
        out,
        args,
        {
            "tests_file": str(Path(args.tests).resolve()),
            "tests_sha256": _sha256(Path(args.tests)),
            **provenance,
            "estimator": args.estimator,
            "force_window_s": args.force_window,
            "exponential_window_s": args.exp_window,
            "force_range_n": args.force_range,
            "quality": summary,
            "rejected_points": list(estimate.rejected_points),
        },
        written,
    )
    console.print(
        f"{estimate.frfs.n_points} FRFs from {summary['accepted']} of "
        f"{summary['averages']} averages → {out}"
    )
    for reason, count in summary.items():
        if reason not in ("averages", "accepted"):
            console.print(f"[yellow]{count} averages rejected: {reason}[/]")
    if estimate.rejected_points:
        nodes = ", ".join(str(n) for n in estimate.rejected_points)
        console.print(f"[yellow]every average rejected at node(s) {nodes}: no FRF there[/]")
    for path in written:
        console.print(f"  wrote {path}")
    return 0


def _contact(args: argparse.Namespace, console: Console) -> int:
    from racketdyn.plotting.figures import write_contact_figure

    labels = (
        _parse_list("--labels", args.labels) if args.labels else [Path(t).stem for t in args.tests]
    )
    if len(labels) != len(args.tests):
        raise InputError(f"--labels: give one label per test file ({len(args.tests)})")
    racket, provenance = _load(args.racket)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    tables = []
    written: list[Path] = []
    for label, test in zip(labels, args.tests, strict=True):
        records = _read_records(test, args.geometry)
        checks = estimate_frfs(records).checks
        times = contact_times(records, checks)
        slug = "".join(c if c.isalnum() or c in "-_" else "_" for c in label)
        path = out / f"contact_{slug}.csv"
        times.write_csv(path)
        written.append(path)
        tables.append(times)
    written.append(write_contact_figure(tables, labels, racket, out))
    _write_record(
        out,
        args,
        {
            "tests_files": [str(Path(t).resolve()) for t in args.tests],
            "labels": labels,
            **provenance,
            "method": "half-sine-equivalent duration: 1.5 x full width at half maximum",
        },
        written,
    )
    for label, times in zip(labels, tables, strict=True):
        on_bed = racket.head.contains(times.locations) & np.isfinite(times.mean_s)
        if np.any(on_bed):
            console.print(
                f"{label}: contact time on the strings {np.nanmin(times.mean_s[on_bed]) * 1e3:.2f}"
                f"–{np.nanmax(times.mean_s[on_bed]) * 1e3:.2f} ms over {int(on_bed.sum())} points"
            )
    for path in written:
        console.print(f"  wrote {path}")
    return 0


def _rig(args: argparse.Namespace, console: Console) -> int:
    from racketdyn.io import write_hammer_uff
    from racketdyn.rig import (
        accelerometer_index,
        hammer_points,
        rig_model,
        simulate_hammer_test,
        string_contact_time,
    )
    from racketdyn.rig.hammer import FRAME_PULSE_S

    racket, provenance = _load(args.racket)
    if args.averages < 1:
        raise InputError(f"--averages must be a whole number of at least 1 (got {args.averages})")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    locations, nodes = hammer_points(racket)
    reference = accelerometer_index(racket, locations)
    reference_location = (float(locations[reference, 0]), float(locations[reference, 1]))
    on_bed = racket.head.contains(locations)
    durations = np.full(len(nodes), FRAME_PULSE_S)
    support = "free" if args.support == "free" else "pinned"
    durations[on_bed] = string_contact_time(racket, locations[on_bed], support)
    with console.status(f"building the {args.support} rig and simulating the hammer test"):
        model = rig_model(racket, args.support)
        records = simulate_hammer_test(
            model,
            locations,
            nodes,
            reference_location,
            nodes[reference],
            n_averages=args.averages,
            double_hit_probability=args.double_hits,
            overload_probability=args.overloads,
            pulse_duration_s=durations,
            seed=args.seed,
        )
    tests = write_hammer_uff(records, out / f"hammer_{args.support}.uff", binary=args.binary)
    truth_locations = np.vstack([locations, [[0.0, 0.0], [racket.length_m, 0.0]]])
    truth = model.modal_truth(truth_locations, max_frequency_hz=0.5 / records.sampling_interval_s)
    truth_path = out / f"modal_truth_{args.support}.json"
    truth.write_json(truth_path)
    written = [tests, truth_path]
    faults = {
        "double_hits": int(sum(sum(row) for row in records.metadata.get("double_hit", []))),
        "overloads": int(sum(sum(row) for row in records.metadata.get("overload", []))),
    }
    _write_record(
        out,
        args,
        {
            **provenance,
            "racket": racket_to_dict(racket),
            "support": args.support,
            "reference_node": nodes[reference],
            "reference_location_m": reference_location,
            "n_points": len(nodes),
            "averages": args.averages,
            "seed": args.seed,
            **faults,
            "rig": records.metadata.get("rig"),
            "anti_alias": records.metadata.get("anti_alias"),
        },
        written,
    )
    console.print(
        f"{len(nodes)} points × {args.averages} averages on the {args.support} rig "
        f"(accelerometer at node {nodes[reference]}), {faults['double_hits']} double hits, "
        f"{faults['overloads']} overloads → {out}"
    )
    for name, frequency, damping in zip(
        truth.names, truth.frequency, truth.damping_ratio, strict=True
    ):
        if frequency > 15.0:
            console.print(f"  {name:24s} {frequency:8.1f} Hz  ζ = {damping * 100:.2f} %")
    for path in written:
        console.print(f"  wrote {path}")
    return 0


def _parse_band(text: str | None) -> tuple[float, float] | None:
    if text is None:
        return None
    values = _parse_speeds("--band", text)  # non-negative numbers, same rules
    if len(values) != 2 or values[0] >= values[1]:
        raise InputError(f"--band takes two frequencies low,high in Hz (got {text!r})")
    return (values[0], values[1])


def _frequencies(name: str, text: str | None) -> list[float]:
    return [] if text is None else _parse_speeds(name, text)


def _identify_file(
    path_text: str, args: argparse.Namespace, racket: Racket, support: str, console: Console
) -> Identification:
    from racketdyn.racket_modal.identify import identify_racket

    frfs = read_frf_uff(Path(path_text), args.geometry)
    with console.status(f"identifying {Path(path_text).name}"):
        return identify_racket(
            frfs,
            racket,
            band_hz=_parse_band(args.band),
            max_order=args.max_order,
            pin_hz=_frequencies("--pin", args.pin),
            exclude_hz=_frequencies("--exclude", args.exclude),
            support=support,
        )


def _write_model(identification: Identification, out: Path, label: str) -> list[Path]:
    from racketdyn.io.uff import write_modes_uff

    model = identification.model
    paths = [out / f"modes{label}.csv", out / f"modal_model{label}.json", out / f"modes{label}.uff"]
    identification.write_modes_csv(paths[0])
    model.write_json(paths[1])
    write_modes_uff(model, paths[2], nodes=identification.frfs.nodes)
    quality = out / f"fit_quality{label}.csv"
    with quality.open("w", encoding="utf-8") as handle:
        handle.write("node,x_m,y_m,fit_error\n")
        for node, (x, y), error in zip(
            identification.frfs.nodes,
            identification.frfs.locations,
            identification.fit.error,
            strict=True,
        ):
            handle.write(f"{node},{x:.6g},{y:.6g},{error:.4g}\n")
    return [*paths, quality]


def _print_modes(console: Console, identification: Identification) -> None:
    model = identification.model
    table = Table(
        title=f"{model.n_modes} modes ({model.support}), "
        f"{identification.band_hz[0]:g}–{identification.band_hz[1]:g} Hz"
    )
    for column in ("mode", "frequency (Hz)", "damping (%)", "name", "orders stable"):
        table.add_column(column)
    for k in range(model.n_modes):
        table.add_row(
            str(k + 1),
            f"{model.frequency[k]:.2f}",
            f"{100 * model.damping_ratio[k]:.3f}",
            model.names[k],
            str(int(identification.selected.n_orders[k])),
        )
    console.print(table)
    console.print(
        f"median fit error {np.median(identification.fit.error):.2%}, design matrix "
        f"condition {identification.fit.condition_number:.3g}"
    )
    for line in identification.selected.dropped:
        console.print(f"[dim]dropped: {line}[/]")


def _identify(args: argparse.Namespace, console: Console) -> int:
    from racketdyn.plotting.figures import write_identification

    racket, provenance = _load(args.racket)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    identification = _identify_file(args.frfs, args, racket, args.support, console)
    written = _write_model(identification, out, "")
    with console.status("drawing figures"):
        written += write_identification(identification, racket, out)
    _write_record(
        out,
        args,
        {
            "frfs_file": str(Path(args.frfs).resolve()),
            "frfs_sha256": _sha256(Path(args.frfs)),
            **provenance,
            "support": args.support,
            "band_hz": list(identification.band_hz),
            "max_order": args.max_order,
            "pin_hz": _frequencies("--pin", args.pin),
            "exclude_hz": _frequencies("--exclude", args.exclude),
            "modes": identification.model.summary()["modes"],
            "dropped": list(identification.selected.dropped),
        },
        written,
    )
    _print_modes(console, identification)
    for path in written:
        console.print(f"  wrote {path}")
    return 0


def _compare(args: argparse.Namespace, console: Console) -> int:
    from racketdyn.plotting.figures import write_comparison, write_identification

    racket, provenance = _load(args.racket)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    free = _identify_file(args.free, args, racket, "free", console)
    hand = _identify_file(args.hand, args, racket, "hand", console)
    written = _write_model(free, out, "_free") + _write_model(hand, out, "_hand")
    with console.status("drawing figures"):
        written += write_identification(free, racket, out, "free")
        written += write_identification(hand, racket, out, "hand")
        written += write_comparison(free, hand, racket, Ball(), out)
    _write_record(
        out,
        args,
        {
            "free_file": str(Path(args.free).resolve()),
            "hand_file": str(Path(args.hand).resolve()),
            **provenance,
            "band_hz": list(free.band_hz),
            "max_order": args.max_order,
            "modes_free": free.model.summary()["modes"],
            "modes_hand": hand.model.summary()["modes"],
        },
        written,
    )
    _print_modes(console, free)
    _print_modes(console, hand)
    for path in written:
        console.print(f"  wrote {path}")
    return 0


def _demo(args: argparse.Namespace, console: Console) -> int:
    """rig (free, hand) → FRFs → contact times → identification and comparison → prediction
    by both impact models → swing, twist, oblique impacts → report."""
    from racketdyn.report import write_report

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    racket_args = [] if args.racket is None else [args.racket]
    racket_option = [] if args.racket is None else ["--racket", args.racket]
    rig, free, hand = out / "rig", out / "frf_free", out / "frf_hand"
    faults = ["--double-hits", "0.03", "--overloads", "0.01"]  # a real test has a few bad hits
    racket, _ = _load(args.racket)
    steps: list[tuple[str, list[str]]] = [
        (
            "virtual hammer test, free",
            ["rig", *racket_args, "--support", "free", *faults, "--out", str(rig)],
        ),
        (
            "virtual hammer test, hand-held",
            ["rig", *racket_args, "--support", "hand", *faults, "--out", str(rig)],
        ),
        (
            "FRFs, free",
            [
                "frf",
                str(rig / "hammer_free.uff"),
                *racket_option,
                "--exp-window",
                "0.1",
                "--force-range",
                "200",
                "--out",
                str(free),
            ],
        ),
        (
            "FRFs, hand-held",
            [
                "frf",
                str(rig / "hammer_hand.uff"),
                *racket_option,
                "--exp-window",
                "0.1",
                "--force-range",
                "200",
                "--out",
                str(hand),
            ],
        ),
        (
            "contact times",
            [
                "contact",
                str(rig / "hammer_free.uff"),
                str(rig / "hammer_hand.uff"),
                "--labels",
                "free,hand",
                *racket_option,
                "--out",
                str(out / "contact"),
            ],
        ),
        (
            "identification, free against hand-held",
            [
                "compare",
                str(free / "frfs.uff"),
                str(hand / "frfs.uff"),
                "--band",
                "40,850",
                *racket_option,
                "--out",
                str(out / "compare"),
            ],
        ),
    ]
    identified = [*racket_args, "--modal", str(out / "compare" / "modal_model_free.json")]
    swing = ["--model", "approx", "--support", "pinned", "--ball-speed", "20", "--grid", "9"]
    steps += [
        # --model both adds ≈ 2 s with the compiled transient engine, ≈ 10 s with the scipy
        # reference (measured on the 2-core development machine, default 9 × 9 grid)
        (
            "prediction with the identified free modes, both models",
            ["predict", *identified, "--model", "both", "--out", str(out / "predict")],
        ),
        # the three below add ≈ 1.5 s together (measured on the 2-core development machine)
        (
            "swinging racket: outgoing speed and sweet spots",
            ["swing", *identified, *swing, "--out", str(out / "swing")],
        ),
        (
            "twist against offset, free and hand-held",
            ["twist", *identified, "--support", "free,hand", "--out", str(out / "twist")],
        ),
        (
            "oblique impacts: outgoing angle and spin",
            ["oblique", *identified, "--angles", OBLIQUE_ANGLES_DEG, "--out", str(out / "oblique")],
        ),
    ]
    quiet = Console(file=open(os.devnull, "w"), stderr=False)  # noqa: SIM115 - closed below
    try:
        with Progress(console=console) as progress:
            task = progress.add_task("demo", total=len(steps) + 1)  # + the report
            for label, argv in steps:
                progress.update(task, description=label)
                _run_step(argv, quiet)
                progress.advance(task)
            progress.update(task, description="report")
            report = write_report(out, racket)
            progress.advance(task)
    finally:
        quiet.file.close()
    console.print(f"demo complete → {report}")
    return 0


def _run_step(argv: list[str], console: Console) -> None:
    args = _parse(argv)
    args.handler(args, console)


def _parse(argv: Sequence[str] | None) -> argparse.Namespace:
    """Parsed arguments, with the command line as given (``argv``) kept for run records."""
    args = _parser().parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)
    return args


def _report(args: argparse.Namespace, console: Console) -> int:
    from racketdyn.report import write_report

    run_dir = Path(args.run_dir)
    if not run_dir.is_dir():
        raise InputError(f"{run_dir}: no such folder; give a folder written by racketdyn demo")
    racket, _ = _load(args.racket)
    console.print(f"wrote {write_report(run_dir, racket)}")
    return 0


def _sweep(args: argparse.Namespace, console: Console) -> int:
    from concurrent.futures import Executor
    from contextlib import AbstractContextManager, ExitStack, nullcontext

    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    from racketdyn.sweep import load_sweep_spec, make_executor, run_sweep

    spec = load_sweep_spec(Path(args.spec))
    engine: AbstractContextManager[Executor | None]
    if args.serial:
        engine = make_executor("serial")
    elif args.workers is not None:
        engine = make_executor("process", args.workers)
    elif args.dask_local is not None:
        engine = make_executor("dask-local", args.dask_local)
    elif args.scheduler is not None:
        engine = make_executor("dask", scheduler=args.scheduler)
    else:  # run_sweep chooses: this process for a small sweep, else two processes
        engine = nullcontext(None)
    out = Path(args.out)
    console.print(
        f"{spec.name}: {len(spec.designs)} designs × {spec.impacts_per_design:,} impacts "
        f"= {spec.n_impacts:,} impacts → {out}"
    )
    columns = (
        TextColumn("designs"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
    )
    if (args.dask_local is not None or args.scheduler is not None) and not args.verbose:
        import distributed  # noqa: F401  (importing it sets its loggers to INFO: quieten them)

        logging.getLogger("distributed").setLevel(logging.WARNING)
    with ExitStack() as stack:
        with console.status("starting the engine"):
            executor = stack.enter_context(engine)
        bar = stack.enter_context(Progress(*columns, console=console, transient=True))
        task = bar.add_task("sweep", total=len(spec.designs))
        result = run_sweep(
            spec,
            out,
            executor,
            progress=lambda done, total: bar.update(task, completed=done, total=total),
            figures=not args.no_figures,
        )
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    console.print(
        f"[bold]{record['impacts']:,}[/] impacts, {record['designs']} designs "
        f"({record['ran']} run, {record['resumed']} resumed) on {record['engine']} "
        f"in {record['wall_time_s']:.1f} s"
    )
    for text, count in record["status_counts"].items():
        if text not in ("ok", "task failed") and count:
            console.print(f"[yellow]{count:,} impacts: {text}; their results are NaN[/]")
    failed = json.loads(result.attrs["failed_tasks"])
    for failure in failed:
        console.print(f"[red]{failure['task_id']} failed: {failure['error']}[/]")
    for name in record["outputs"]:
        console.print(f"  wrote {out / name}")
    if failed:
        console.print(
            f"[red]{len(failed)} of {record['designs']} designs failed (NaN, status 3); "
            f"details in {out / 'failures.json'}; run the same command again to retry them[/]"
        )
        return 1
    return 0


# --- the swinging racket, twist and oblique impacts (issue 5) ------------------------------------
SWING_GRID = 15  # 177 points on the built-in head: a smooth map in ≈ 0.1 s (approximate model)
IMPACT_MODELS: dict[str, ImpactModel] = {"approx": "approximate", "transient": "transient"}
TWIST_OFFSETS_M = "-0.08,-0.06,-0.04,-0.02,0,0.02,0.04,0.06,0.08"
OBLIQUE_ANGLES_DEG = "0,10,20,30,40,50,60"
SPIN_CAVEAT = (
    "caveat: spin depends strongly on the tangential stiffness k_t (the grip is lossless); "
    "fit k_t to measured rebound spin before quoting it (racketdyn.impact.oblique)"
)


def _parse_numbers(name: str, text: str, unit: str) -> list[float]:
    """Finite numbers (any sign) from a comma-separated list."""
    numbers = []
    for item in _parse_list(name, text):
        try:
            number = float(item)
        except ValueError:
            raise InputError(f"{name}: {item!r} is not a number ({unit})") from None
        numbers.append(require_finite(name, number))
    return numbers


def _racket_setup(args: argparse.Namespace) -> tuple[Racket, dict[str, Any], list[str]]:
    """Racket (built-in or TOML, with ``--modal`` if given), provenance and the defaults used."""
    racket, provenance = _load(args.racket)
    defaults = []
    if args.racket is None:
        defaults.append(f"racket: built-in {DEFAULT_RACKET_NAME} (Kawazoe's test racket)")
    if args.modal is not None:
        if args.rigid:
            raise InputError("give --modal or --rigid, not both")
        if not Path(args.modal).is_file():
            raise InputError(f"--modal {args.modal}: no such modal model file")
        racket = replace(racket, modal_model_file=Path(args.modal))
        provenance["modal_model_file"] = str(Path(args.modal).resolve())
        provenance["modal_model_sha256"] = _sha256(Path(args.modal))
    elif not args.rigid and racket.modal_model_file is None:
        defaults.append("modal model: built-in free-free beam model")
    return racket, provenance, defaults


def _modes(args: argparse.Namespace, racket: Racket) -> ModalModel | None:
    """The racket's modes (built-in, its file or ``--modal``), None with ``--rigid``."""
    return None if args.rigid else modal_model_for(racket)


def _one_support(args: argparse.Namespace, transient: bool) -> str:
    """One support, allowed by the impact model."""
    if args.support == "hand" and not transient:
        raise InputError(
            "--support hand needs --model transient: the approximate method has no hand "
            "(its hand-held racket is pinned at the grip: --support pinned)"
        )
    return one_of("--support", args.support, TRANSIENT_SUPPORTS if transient else SUPPORTS)


def _swing_of(args: argparse.Namespace, defaults: list[str]) -> Swing:
    """The swing from the options: constant shoulder torque (default) or an angular speed."""
    if args.axis_to_butt is None:
        axis = DEFAULT_AXIS_TO_BUTT_M
        defaults.append(
            f"swing axis (shoulder) {axis:.3f} m behind the butt: a straight arm in line with "
            "the racket, 70 kg, 1.75 m adult (Dempster/Winter)"
        )
    else:
        axis = require_positive("--axis-to-butt", args.axis_to_butt, allow_zero=True)
    if args.angular_speed is not None:
        if args.torque is not None or args.swing_angle_deg is not None:
            raise InputError(
                "give --angular-speed, or --torque and --swing-angle-deg (the constant shoulder "
                "torque swing), not both"
            )
        omega = require_positive("--angular-speed", args.angular_speed, allow_zero=True)
        return Swing(axis_to_butt_m=axis, angular_speed_radps=omega)
    if args.torque is None:
        torque = DEFAULT_TORQUE_NM
        defaults.append(f"shoulder torque {torque:g} N·m (Kawazoe, ACMD 2002)")
    else:
        torque = require_positive("--torque", args.torque)
    if args.swing_angle_deg is None:
        angle = DEFAULT_SWING_ANGLE_RAD
        defaults.append("swing angle 90° from rest to impact (assumption: a quarter turn)")
    else:
        degrees = require_finite("--swing-angle-deg", args.swing_angle_deg)
        if not 0.0 < degrees <= 360.0:
            raise InputError(
                f"--swing-angle-deg must be more than 0 and at most 360 degrees (got {degrees:g})"
            )
        angle = math.radians(degrees)
    defaults.append(
        f"arm {DEFAULT_ARM_MASS_KG:g} kg, radius of gyration {DEFAULT_ARM_GYRATION_M:.3f} m "
        "about the shoulder (Dempster/Winter, 70 kg, 1.75 m adult)"
    )
    return Swing(torque_nm=torque, swing_angle_rad=angle, axis_to_butt_m=axis)


def _format_cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool | np.bool_):
        return str(bool(value))
    if isinstance(value, float | np.floating):
        return "nan" if not math.isfinite(value) else f"{float(value):.9g}"
    return str(value)


def _write_rows(path: Path, rows: Sequence[dict[str, Any]]) -> Path:
    """Rows of dicts (same keys) as CSV; None as an empty cell, floats to 9 digits."""
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(rows[0])
        for row in rows:
            writer.writerow(_format_cell(v) for v in row.values())
    return path


SWEET_SPOT_COLUMNS = (
    "key",
    "name",
    "x_m",
    "y_m",
    "on_face",
    "value",
    "definition",
    "racket_speed_mps",
    "rebound_speed_mps",
)
"""Columns of ``sweet_spots.csv``: :func:`~racketdyn.impact.swing.sweet_spot_table` (``value``:
the rebound ratio or outgoing speed maximised, empty for the geometric points), then the speed of
the racket and the outgoing ball speed at each spot for the swing (NaN off the face)."""


def _spot_rows(
    racket: Racket,
    ball: Ball,
    spots: dict[str, SweetSpot],
    swing: Swing,
    speed: float,
    support: str,
    impact_model: ImpactModel,
    model: ModalModel | None,
    options: dict[str, Any],
) -> list[dict[str, Any]]:
    """sweet_spot_table rows with the racket speed and the outgoing ball speed at each spot."""
    rows = sweet_spot_table(spots)
    on_face = [i for i, key in enumerate(spots) if spots[key].on_face]
    outgoing = np.full(len(rows), np.nan)
    if on_face:
        at = predict_swing(
            racket,
            ball,
            [spots[list(spots)[i]].location for i in on_face],
            [speed],
            swing,
            support,
            impact_model,
            model,
            **options,
        )
        outgoing[on_face] = at.rebound_speed[:, 0, 0]
    racket_speed = swing.angular_speed(racket) * (
        np.array([s.x_m for s in spots.values()]) + swing.axis_to_butt_m
    )
    for i, row in enumerate(rows):
        row["racket_speed_mps"] = float(racket_speed[i])
        row["rebound_speed_mps"] = float(outgoing[i])
    return rows


def _swing(args: argparse.Namespace, console: Console) -> int:
    from racketdyn.plotting.figures import write_swing_figures

    speeds = _parse_speeds("--ball-speed", args.ball_speed)
    transient = args.model == "transient"
    impact_model = IMPACT_MODELS[args.model]
    support = _one_support(args, transient)
    n = SWING_GRID if args.grid is None else args.grid
    if not 1 <= n <= MAX_GRID:
        raise InputError(f"--grid must be a whole number from 1 to {MAX_GRID} (got {n})")
    racket, provenance, defaults = _racket_setup(args)
    hand = _hand(args, [support], defaults)
    swing = _swing_of(args, defaults)
    ball, ball_defaults = _ball(args)
    defaults += ball_defaults
    model = _modes(args, racket)
    locations = racket.head.grid(n)
    labels = [str(i + 1) for i in range(len(locations))]
    law = compound_law(racket, ball)
    options: dict[str, Any] = {"law": law, **({"hand": hand} if hand is not None else {})}
    chosen = shown_speed_index(speeds)
    omega = swing.angular_speed(racket)
    with console.status(f"swing Ω = {omega:.2f} rad/s: {len(locations)} points") as status:
        result = predict_swing(
            racket,
            ball,
            locations,
            speeds,
            swing,
            support,
            impact_model,
            model,
            labels,
            **options,
        )
        status.update(f"sweet spots at {speeds[chosen]:g} m/s")
        spots = sweet_spots(
            racket, ball, swing, speeds[chosen], support, impact_model, model, **options
        )
        rows = _spot_rows(
            racket, ball, spots, swing, speeds[chosen], support, impact_model, model, options
        )
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    result.write_csv(out / "swing.csv")
    written = [out / "swing.csv", _write_rows(out / "sweet_spots.csv", rows)]
    if not args.no_figures:
        with console.status("drawing the swing's figures"):
            written += write_swing_figures(
                out, racket, ball, result, spots, chosen, impact_model, model, **options
            )
    _write_record(
        out,
        args,
        {
            **provenance,
            "racket": racket_to_dict(racket),
            "ball_speeds_mps": speeds,
            "support": support,
            "grid": n,
            "n_points": len(locations),
            "rigid": args.rigid,
            "defaults_used": defaults,
            **result.inputs,  # swing (parameters, Ω, inertias), impact model, ball, law, modes
            "angular_speed_radps": omega,
            "sweet_spots_at_mps": speeds[chosen],
            "columns": {
                "swing.csv": "impact.csv columns; racket_speed_mps = Ω (x + axis_to_butt_m) "
                "at each point",
                "sweet_spots.csv": list(SWEET_SPOT_COLUMNS),
            },
        },
        written,
    )
    console.print(
        f"swing {swing.describe(racket)} ({impact_model} model, {support}): "
        f"[bold]{result.status.size}[/] impacts ({len(locations)} points × {len(speeds)} "
        f"speeds) → {out}"
    )
    _print_status(console, result.status, "swing.csv")
    table = Table(title=f"sweet spots, ball {speeds[chosen]:g} m/s, {support}")
    for heading in ("sweet spot", "x (mm)", "on the face", "racket (m/s)", "outgoing (m/s)"):
        table.add_column(heading, justify="left" if heading == "sweet spot" else "right")
    for row in rows:
        table.add_row(
            str(row["name"]),
            f"{row['x_m'] * 1e3:.0f}",
            "yes" if row["on_face"] else "no",
            f"{row['racket_speed_mps']:.1f}",
            "–"
            if not math.isfinite(row["rebound_speed_mps"])
            else f"{row['rebound_speed_mps']:.1f}",
        )
    console.print(table)
    for path in written:
        console.print(f"  wrote {path}")
    return 0


def _print_status(console: Console, status: np.ndarray, csv_name: str) -> None:
    bad = status != "ok"
    if np.any(bad):
        reasons, counts = np.unique(status[bad], return_counts=True)
        for reason, count in zip(reasons, counts, strict=True):
            console.print(f"[yellow]{count} impacts: {reason}; NaN in {csv_name}[/]")


TWIST_COLUMNS = (
    "support",
    "x_m",
    "y_m",
    "ball_speed_mps",
    "racket_speed_mps",
    "roll_angle_rad",
    "roll_rate_radps",
    "flexible_twist_rad",
    "total_twist_rad",
    "rebound_speed_mps",
    "rebound_ratio",
    "contact_time_s",
    "status",
)
"""Columns of ``twist.csv``, one row per support × offset (``y_m``: the offset from the long
axis); the fields of :class:`~racketdyn.impact.twist.TwistCurve`."""


def _twist(args: argparse.Namespace, console: Console) -> int:
    from racketdyn.plotting.figures import write_twist_figure

    x = require_positive("--x", args.x)
    offsets = _parse_numbers("--offsets", args.offsets, "offsets from the long axis in m")
    speed = require_positive("--ball-speed", args.ball_speed)
    racket_speed = require_finite("--racket-speed", args.racket_speed)
    supports = [
        one_of("--support", s, TRANSIENT_SUPPORTS) for s in _parse_list("--support", args.support)
    ]
    if len(set(supports)) != len(supports):
        raise InputError(f"--support: name each support once (got {args.support})")
    racket, provenance, defaults = _racket_setup(args)
    racket.head.check_inside(np.column_stack([np.full(len(offsets), x), offsets]))
    hand = _hand(args, supports, defaults)
    ball, ball_defaults = _ball(args)
    defaults += ball_defaults
    model = _modes(args, racket)
    curves = []
    with console.status("") as status:
        for support in supports:
            status.update(f"twist against offset, {support} ({len(offsets)} impacts)")
            curves.append(
                twist_curve(racket, ball, x, offsets, speed, support, racket_speed, model, hand)
            )
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = [
        {
            "support": c.support,
            "x_m": c.x_m,
            "y_m": float(c.offsets_m[i]),
            "ball_speed_mps": c.ball_speed_mps,
            "racket_speed_mps": c.racket_speed_mps,
            **{name: float(getattr(c, name)[i]) for name in TWIST_COLUMNS[5:-1]},
            "status": str(c.status[i]),
        }
        for c in curves
        for i in range(c.offsets_m.size)
    ]
    written = [_write_rows(out / "twist.csv", rows)]
    if not args.no_figures:
        with console.status("drawing the twist figure"):
            written.append(write_twist_figure(out, curves))
    _write_record(
        out,
        args,
        {
            **provenance,
            "racket": racket_to_dict(racket),
            "x_m": x,
            "offsets_m": offsets,
            "ball_speed_mps": speed,
            "racket_speed_mps": racket_speed,
            "supports": supports,
            "rigid": args.rigid,
            "defaults_used": defaults,
            "method": "transient simulation, reference engine (racketdyn.impact.twist."
            "twist_curve): roll and section rotation of the modes at separation",
            "modal_model": None if model is None else model.summary(),
            "hand": None if hand is None else asdict(hand),
            "columns": {"twist.csv": list(TWIST_COLUMNS)},
        },
        written,
    )
    console.print(
        f"twist at x = {x * 1e3:.0f} mm, ball {speed:g} m/s: {len(offsets)} offsets × "
        f"{len(supports)} supports → {out}"
    )
    table = Table(title="roll angle at separation (°), + turns the +y side away from the ball")
    table.add_column("y (mm)", justify="right")
    for support in supports:
        table.add_column(f"{support}: roll (°)", justify="right")
        table.add_column(f"{support}: outgoing (m/s)", justify="right")
    order = np.argsort(offsets)
    for i in order:
        cells = [f"{offsets[i] * 1e3:.0f}"]
        for c in curves:
            cells += [f"{math.degrees(c.roll_angle_rad[i]):.2f}", f"{c.rebound_speed_mps[i]:.2f}"]
        table.add_row(*cells)
    console.print(table)
    for c in curves:
        _print_status(console, c.status, "twist.csv")
    for path in written:
        console.print(f"  wrote {path}")
    return 0


OBLIQUE_COLUMNS = (
    "ball_speed_mps",
    "incoming_angle_deg",
    "incoming_spin_radps",
    "outgoing_angle_deg",
    "outgoing_spin_radps",
    "normal_speed_mps",
    "tangential_speed_mps",
    "gripped",
    "grip_time_s",
    "tangential_impulse_ns",
    "friction_loss_j",
    "status",
)
"""Columns of ``oblique.csv``, one row per incoming angle; the fields of
:class:`~racketdyn.impact.oblique.ObliqueCurve` (angles from the face normal, spin about n̂ × t̂,
speeds away from the face and along it)."""


def _point(text: str | None, racket: Racket) -> tuple[float, float]:
    if text is None:
        return (racket.head.centre_x_m, racket.head.centre_y_m)
    values = _parse_numbers("--point", text, "x,y in m")
    if len(values) != 2:
        raise InputError(f"--point takes x,y in m, e.g. 0.505,0 (got {text!r})")
    return (values[0], values[1])


def _oblique(args: argparse.Namespace, console: Console) -> int:
    from racketdyn.plotting.figures import write_oblique_figure

    speed = require_positive("--ball-speed", args.ball_speed)
    angles = _parse_numbers("--angles", args.angles, "degrees from the face normal")
    for angle in angles:
        if not -90.0 < angle < 90.0:
            raise InputError(
                "--angles: each incoming angle must lie strictly between -90 and 90 degrees "
                f"from the face normal (got {angle:g})"
            )
    spin = require_finite("--spin", args.spin)
    support = one_of("--support", args.support, TRANSIENT_SUPPORTS)
    racket, provenance, defaults = _racket_setup(args)
    point = _point(args.point, racket)
    if args.point is None:
        defaults.append("impact point: the face centre")
    racket.head.check_inside([point])
    hand = _hand(args, [support], defaults)
    base = DEFAULT_TANGENTIAL_CONTACT
    if args.friction is None or args.tangential_stiffness is None:
        defaults.append(
            "tangential contact: μ 0.4 (Cross), k_t 1e4 N/m, ball inertia 0.55 m R² "
            "(racketdyn.impact.oblique)"
        )
    contact = TangentialContact(
        friction_coefficient=base.friction_coefficient if args.friction is None else args.friction,
        stiffness_n_per_m=(
            base.stiffness_n_per_m
            if args.tangential_stiffness is None
            else args.tangential_stiffness
        ),
        inertia_factor=base.inertia_factor,
    )
    racket_speed = require_finite("--racket-speed", args.racket_speed)
    face_speed = require_finite("--racket-tangential-speed", args.racket_tangential_speed)
    ball, ball_defaults = _ball(args)
    defaults += ball_defaults
    model = _modes(args, racket)
    with console.status(f"oblique impacts at {len(angles)} angles"):
        curve = oblique_curve(
            racket,
            ball,
            point,
            speed,
            angles,
            spin,
            support,
            racket_speed,
            contact,
            face_speed,
            modal_model=model,
            law=compound_law(racket, ball),
            hand=hand,
        )
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = [
        {
            "ball_speed_mps": curve.ball_speed_mps,
            **{name: getattr(curve, name)[i] for name in OBLIQUE_COLUMNS[1:]},
        }
        for i in range(curve.incoming_angle_deg.size)
    ]
    written = [_write_rows(out / "oblique.csv", rows)]
    if not args.no_figures:
        with console.status("drawing the oblique-impact figure"):
            written.append(write_oblique_figure(out, curve, point, support, contact))
    _write_record(
        out,
        args,
        {
            **provenance,
            "racket": racket_to_dict(racket),
            "point_m": list(point),
            "ball_speed_mps": speed,
            "angles_deg": angles,
            "spin_radps": spin,
            "support": support,
            "racket_speed_mps": racket_speed,
            "racket_tangential_speed_mps": face_speed,
            "tangential_contact": {
                **asdict(contact),
                "effective_mass_kg": contact.effective_mass(ball),
                "grip_period_s": contact.grip_period(ball),
            },
            "rigid": args.rigid,
            "defaults_used": defaults,
            "method": "normal impact by the transient simulation (reference engine), tangential "
            "elastic-Coulomb contact on its normal force history (racketdyn.impact.oblique)",
            "modal_model": None if model is None else model.summary(),
            "hand": None if hand is None else asdict(hand),
            "caveat": SPIN_CAVEAT,
            "columns": {"oblique.csv": list(OBLIQUE_COLUMNS)},
        },
        written,
    )
    console.print(
        f"oblique impacts at x = {point[0] * 1e3:.0f} mm, y = {point[1] * 1e3:.0f} mm, "
        f"ball {speed:g} m/s, spin {spin:g} rad/s, {support} → {out}"
    )
    table = Table(
        title=f"μ = {contact.friction_coefficient:g}, k_t = {contact.stiffness_n_per_m:.3g} N/m"
    )
    for heading in ("in (°)", "out (°)", "spin out (rad/s)", "along the face (m/s)", "gripped"):
        table.add_column(heading, justify="right")
    for i in np.argsort(curve.incoming_angle_deg, kind="stable"):
        table.add_row(
            f"{curve.incoming_angle_deg[i]:g}",
            f"{curve.outgoing_angle_deg[i]:.1f}",
            f"{curve.outgoing_spin_radps[i]:.0f}",
            f"{curve.tangential_speed_mps[i]:.2f}",
            "yes" if curve.gripped[i] else "no",
        )
    console.print(table)
    console.print(f"[yellow]{SPIN_CAVEAT}[/]")
    _print_status(console, curve.status, "oblique.csv")
    for path in written:
        console.print(f"  wrote {path}")
    return 0


def _add_racket_arguments(command: argparse.ArgumentParser) -> None:
    """The racket, its modes and the ball: the same options as predict."""
    command.add_argument(
        "racket", nargs="?", help="racket TOML file (default: the built-in paper racket)"
    )
    command.add_argument("--modal", help="modal model (racketdyn JSON, e.g. from identify) to use")
    command.add_argument("--rigid", action="store_true", help="no vibration: a rigid racket")
    command.add_argument("--ball-mass", type=float, help="ball mass, kg (default 0.0577)")
    command.add_argument(
        "--e-bg", type=float, help="ball-string COR on a head-clamped racket (default 0.83)"
    )
    command.add_argument(
        "--ball-law", help="ball load-deflection CSV (deflection_m, force_n), one side"
    )
    command.add_argument(
        "--hand-arm-mass",
        type=float,
        help="mass of the arm holding the grip, kg, for --support hand (default 1.0)",
    )
    command.add_argument(
        "--no-figures", action="store_true", help="write the CSV files and run.json only"
    )
    command.add_argument("--out", required=True, help="output folder (created if missing)")


def _add_swing_commands(commands: Any) -> None:
    swing = commands.add_parser(
        "swing",
        help="a swinging racket: outgoing ball speed over the face and the sweet spots",
        description="Outgoing ball speed over the face of a racket swung about the shoulder "
        "(constant shoulder torque, Kawazoe ACMD 2002, or a given angular speed), and where the "
        "sweet spots lie: swing.csv, sweet_spots.csv, figures, run.json.",
    )
    _add_racket_arguments(swing)
    swing.add_argument("--ball-speed", default="20", help="incoming ball speeds, m/s (default 20)")
    swing.add_argument(
        "--torque",
        type=float,
        help="constant shoulder torque, N·m (default 56.9, Kawazoe ACMD 2002)",
    )
    swing.add_argument(
        "--swing-angle-deg",
        type=float,
        help="angle turned from rest to impact, degrees (default 90, an assumption)",
    )
    swing.add_argument(
        "--angular-speed",
        type=float,
        help="angular speed at impact, rad/s, instead of the torque model",
    )
    swing.add_argument(
        "--axis-to-butt",
        type=float,
        help="swing axis (shoulder) behind the butt, m (default 0.607: straight arm, 1.75 m adult)",
    )
    swing.add_argument(
        "--support",
        default="pinned",
        help="pinned (default, the paper's hand-held racket), free, or hand (--model transient)",
    )
    swing.add_argument(
        "--model",
        choices=tuple(IMPACT_MODELS),
        default="approx",
        help="approx: Kawazoe's approximate method (default); transient: the time-domain model",
    )
    swing.add_argument(
        "--grid", type=int, help=f"N x N grid of points over the head (default {SWING_GRID})"
    )
    swing.set_defaults(handler=_swing)

    oblique = commands.add_parser(
        "oblique",
        help="oblique impacts with spin: outgoing angle and spin against incoming angle",
        description="A ball arriving at an angle (and with spin) at one point of the face: "
        "normal impact by the transient model, tangential elastic-Coulomb contact on its force "
        "history. oblique.csv, a figure, run.json.",
    )
    _add_racket_arguments(oblique)
    oblique.add_argument(
        "--ball-speed", type=float, default=20.0, help="incoming ball speed, m/s (default 20)"
    )
    oblique.add_argument(
        "--angles",
        default=OBLIQUE_ANGLES_DEG,
        help=f"incoming angles to the face normal, degrees, each in (-90, 90) (default "
        f"{OBLIQUE_ANGLES_DEG}); a list that starts with a minus sign needs --angles=-30,0,30",
    )
    oblique.add_argument(
        "--spin",
        type=float,
        default=0.0,
        help="incoming spin, rad/s, + = the sense of rolling along the face (default 0)",
    )
    oblique.add_argument(
        "--point", help="impact point x,y, m (default: the face centre), e.g. --point=0.5,-0.03"
    )
    oblique.add_argument("--support", default="free", help="free (default), pinned or hand")
    oblique.add_argument(
        "--friction", type=float, help="ball-string friction coefficient μ (default 0.4)"
    )
    oblique.add_argument(
        "--tangential-stiffness",
        type=float,
        help="tangential stiffness k_t of strings and ball, N/m (default 1e4; inf: rigid grip)",
    )
    oblique.add_argument(
        "--racket-speed", type=float, default=0.0, help="racket speed towards the ball, m/s"
    )
    oblique.add_argument(
        "--racket-tangential-speed",
        type=float,
        default=0.0,
        help="racket face speed along the face, m/s (brushing the ball)",
    )
    oblique.set_defaults(handler=_oblique)

    twist = commands.add_parser(
        "twist",
        help="off-axis impacts: the racket's roll (twist) and the outgoing speed against offset",
        description="Impacts across the face at one x: the racket's roll and twist at "
        "separation and the outgoing ball speed against the offset from the long axis (transient "
        "model). twist.csv, a figure, run.json.",
    )
    _add_racket_arguments(twist)
    twist.add_argument(
        "--x", type=float, default=0.52, help="impact position from the butt, m (default 0.52)"
    )
    twist.add_argument(
        "--offsets",
        default=TWIST_OFFSETS_M,
        help="offsets y from the long axis, m (default -0.08 to 0.08 in steps of 0.02); a list "
        "that starts with a minus sign needs the = form: --offsets=-0.05,0,0.05",
    )
    twist.add_argument(
        "--ball-speed", type=float, default=25.0, help="incoming ball speed, m/s (default 25)"
    )
    twist.add_argument(
        "--racket-speed", type=float, default=0.0, help="racket speed towards the ball, m/s"
    )
    twist.add_argument(
        "--support",
        default="free",
        help="free (default), hand, pinned, or several: free,hand (one line each)",
    )
    twist.set_defaults(handler=_twist)


def _add_identification_options(command: argparse.ArgumentParser) -> None:
    command.add_argument("--geometry", help="node coordinates (UFF 15/2411) if not in the file")
    command.add_argument("--racket", help="racket TOML for the head (default: built-in)")
    command.add_argument("--band", help="frequency band low,high in Hz (default 40 Hz to fs/2.56)")
    command.add_argument("--max-order", type=int, default=60, help="highest model order (60)")
    command.add_argument("--pin", help="force modes in, by approximate frequency: 120,330 (Hz)")
    command.add_argument("--exclude", help="leave modes out, by approximate frequency (Hz)")
    command.add_argument("--out", required=True, help="output folder (created if missing)")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="racketdyn",
        description="Tennis racket impact dynamics: rebound ball speed over the string face "
        "(Kawazoe's approximate method, and a transient simulation of the contact). SI units "
        "throughout.",
    )
    parser.add_argument("--version", action="version", version=f"racketdyn {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress")
    commands = parser.add_subparsers(dest="command", required=True)

    run = commands.add_parser(
        "predict", help="predict impacts over the face; write CSV, figures, run.json"
    )
    run.add_argument(
        "racket", nargs="?", help="racket TOML file (default: the built-in paper racket)"
    )
    run.add_argument(
        "--speed", default="10,20,30", help="incoming ball speeds, m/s (default 10,20,30)"
    )
    run.add_argument(
        "--racket-speed",
        default="0",
        help="racket speed at the impact point towards the ball, m/s: one, or one per speed",
    )
    run.add_argument(
        "--model",
        choices=MODELS,
        default="approx",
        help="approx: Kawazoe's approximate method (default); transient: the time-domain "
        "simulation of the contact; both: each, with comparison.csv and figures of the difference",
    )
    run.add_argument(
        "--support",
        default="free,pinned",
        help="free, pinned or both (default both); hand (the grip held by a hand and arm) with "
        "--model transient only",
    )
    run.add_argument(
        "--hand-arm-mass",
        type=float,
        help="mass of the arm holding the grip, kg, for --support hand (default 1.0)",
    )
    run.add_argument(
        "--engine",
        choices=ENGINES,
        help="transient model's integrator: auto (default: compiled where numba is installed), "
        "compiled (numba batch) or reference (scipy solve_ivp)",
    )
    run.add_argument(
        "--grid", type=int, help=f"N x N grid of points over the head (default {DEFAULT_GRID})"
    )
    run.add_argument("--points", help="CSV of impact points with columns x_m, y_m [, point]")
    run.add_argument("--ball-mass", type=float, help="ball mass, kg (default 0.0577)")
    run.add_argument(
        "--e-bg", type=float, help="ball-string COR on a head-clamped racket (default 0.83)"
    )
    run.add_argument(
        "--ball-law", help="ball load-deflection CSV (deflection_m, force_n), one side"
    )
    run.add_argument("--modal", help="modal model (racketdyn JSON, e.g. from identify) to use")
    run.add_argument("--rigid", action="store_true", help="no vibration: a rigid racket")
    run.add_argument(
        "--stiffness-reading",
        choices=("period", "tangent"),
        help="reading of the paper's eq 10 (approximate method): the exact elastic half period "
        "(default) or the tangent stiffness at peak deflection (the paper's shortcut)",
    )
    run.add_argument(
        "--include-string-bed",
        action="store_true",
        help="charge string-bed modes as vibration loss too",
    )
    run.add_argument(
        "--no-figures", action="store_true", help="write the CSV files and run.json only"
    )
    run.add_argument("--out", required=True, help="output folder (created if missing)")
    run.set_defaults(handler=_predict)

    frf = commands.add_parser("frf", help="FRFs, quality table and plots from hammer-test records")
    frf.add_argument("tests", help="hammer records: UFF 58 time records, or CSV (with --geometry)")
    frf.add_argument("--geometry", help="node coordinates (UFF 15/2411, or CSV node,x_m,y_m)")
    frf.add_argument("--racket", help="racket TOML for the head outline (default: built-in)")
    frf.add_argument("--estimator", choices=("H1", "H2"), default="H1")
    frf.add_argument(
        "--force-window", type=float, help="keep the force this long after the trigger, s"
    )
    frf.add_argument("--exp-window", type=float, help="exponential window time constant τ, s")
    frf.add_argument(
        "--force-range", type=float, help="hammer channel range, N: reaching it is an overload"
    )
    frf.add_argument("--out", required=True, help="output folder (created if missing)")
    frf.set_defaults(handler=_frf)

    contact = commands.add_parser(
        "contact", help="hammer contact time over the face (paper Fig. 7)"
    )
    contact.add_argument("tests", nargs="+", help="hammer records, one file per condition")
    contact.add_argument("--labels", help="a label per file, e.g. free,hand")
    contact.add_argument("--geometry", help="node coordinates (UFF 15/2411, or CSV node,x_m,y_m)")
    contact.add_argument("--racket", help="racket TOML for the head outline (default: built-in)")
    contact.add_argument("--out", required=True, help="output folder (created if missing)")
    contact.set_defaults(handler=_contact)

    rig = commands.add_parser("rig", help="virtual roving-hammer test of a racket model (UFF out)")
    rig.add_argument(
        "racket", nargs="?", help="racket TOML file (default: the built-in paper racket)"
    )
    rig.add_argument("--support", choices=("free", "hand"), default="free")
    rig.add_argument("--averages", type=int, default=10, help="hits per point (default 10)")
    rig.add_argument("--double-hits", type=float, default=0.0, help="probability of a double hit")
    rig.add_argument("--overloads", type=float, default=0.0, help="probability of an overload")
    rig.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    rig.add_argument("--binary", action="store_true", help="write binary UFF 58b (default ASCII)")
    rig.add_argument("--out", required=True, help="output folder (created if missing)")
    rig.set_defaults(handler=_rig)

    ident = commands.add_parser("identify", help="modal model from FRFs (modes.csv, UFF 55, JSON)")
    ident.add_argument("frfs", help="FRFs: UFF 58 (function type 4), e.g. racketdyn frf's frfs.uff")
    ident.add_argument("--support", choices=("free", "hand"), default="free")
    _add_identification_options(ident)
    ident.set_defaults(handler=_identify)

    compare = commands.add_parser("compare", help="identify free and hand-held FRFs and compare")
    compare.add_argument("free", help="FRFs of the freely supported racket (UFF 58)")
    compare.add_argument("hand", help="FRFs of the hand-held racket (UFF 58)")
    _add_identification_options(compare)
    compare.set_defaults(handler=_compare)

    demo = commands.add_parser("demo", help="the whole chain on a virtual rig, with a report")
    demo.add_argument("--racket", help="racket TOML file (default: the built-in paper racket)")
    demo.add_argument("--out", required=True, help="output folder (created if missing)")
    demo.set_defaults(handler=_demo)

    report = commands.add_parser("report", help="the HTML report of a demo folder")
    report.add_argument("run_dir", help="a folder written by racketdyn demo")
    report.add_argument("--racket", help="racket TOML file (default: the built-in paper racket)")
    report.set_defaults(handler=_report)

    sweep = commands.add_parser(
        "sweep", help="a design sweep: racket variants × points × speeds (sweep.nc, figures)"
    )
    sweep.add_argument("spec", help="sweep spec TOML (docs/sweep-file.md)")
    sweep.add_argument(
        "--out", required=True, help="output folder (created if missing); run again to resume"
    )
    engine = sweep.add_mutually_exclusive_group()
    engine.add_argument("--serial", action="store_true", help="run in this process")
    engine.add_argument("--workers", type=int, metavar="N", help="a local pool of N processes")
    engine.add_argument(
        "--dask-local", type=int, metavar="N", help="a local Dask cluster of N worker processes"
    )
    engine.add_argument(
        "--scheduler", metavar="tcp://HOST:PORT", help="a running Dask scheduler to use"
    )
    sweep.add_argument("--no-figures", action="store_true", help="write sweep.nc and run.json only")
    sweep.set_defaults(handler=_sweep)

    _add_swing_commands(commands)

    show = commands.add_parser("racket", help="print a racket's derived properties")
    show.add_argument(
        "racket", nargs="?", help="racket TOML file (default: the built-in paper racket)"
    )
    show.set_defaults(handler=_racket)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``racketdyn`` command."""
    args = _parse(argv)
    logging.basicConfig(
        level=logging.INFO if args.verbose else logging.ERROR,
        format="%(levelname)s %(name)s: %(message)s",
    )
    console = Console()
    try:
        return int(args.handler(args, console))
    except InputError as error:
        Console(stderr=True, highlight=False, soft_wrap=True).print(
            f"racketdyn: error: {error}", markup=False
        )
        return 2


if __name__ == "__main__":
    sys.exit(main())
