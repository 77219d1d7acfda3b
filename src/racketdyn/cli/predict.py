"""``racketdyn predict``: impacts over the face (approximate method, transient model or both)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console
    from rich.table import Table

    from racketdyn.impact.comparison import ModelComparison
    from racketdyn.impact.result import ImpactResult
    from racketdyn.impact.uncertainty import Sensitivity, UncertainResult
    from racketdyn.modal import ModalModel
    from racketdyn.racket import Racket


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "predict",
        "predict impacts over the face; write CSV, figures, run.json",
        "Rebound ball speed, contact time, forces and vibration energy at every point x speed "
        "x support: impact.csv, figures, run.json",
    )
    opt.add_racket_and_ball(p)
    opt.add_speed(p, "10,20,30")
    opt.add_racket_speed(p)
    p.add_argument(
        "--model",
        choices=opt.MODELS,
        default="approx",
        help="approx: Kawazoe's approximate method (default); transient: the time-domain "
        "simulation of the contact; both: each, with comparison.csv and figures of the difference",
    )
    opt.add_support(
        p,
        "free,pinned",
        "free, pinned, or both as free,pinned; hand (the grip held by a hand and arm) with "
        "--model transient only",
    )
    p.add_argument(
        "--engine",
        choices=opt.ENGINES,
        help="transient model's integrator: auto (default: compiled where numba is installed), "
        "compiled (numba batch) or reference (scipy solve_ivp)",
    )
    p.add_argument(
        "--show",
        metavar="SPEED[,RACKET_SPEED]",
        help="the case the face maps, Fig. 15, the time histories, the models' comparison and "
        "the report's headline show: a ball speed of --speed and, where two share it, its "
        "racket speed, m/s (default: 20 m/s if run, else the middle ball speed)",
    )
    opt.add_grid(p, opt.DEFAULT_GRID)
    p.add_argument(
        "--points",
        metavar="CSV",
        help="CSV of impact points with columns x_m, y_m [, point], m (default: the --grid)",
    )
    p.add_argument(
        "--stiffness-reading",
        choices=("period", "tangent"),
        help="reading of the paper's eq 10 (approximate method): the exact elastic half period "
        "(default) or the tangent stiffness at peak deflection (the paper's shortcut)",
    )
    p.add_argument(
        "--vibration-charge",
        choices=("coupled", "paper"),
        default="coupled",
        help="how the approximate method charges the frame's vibration against e_BG: the "
        "contact's own pulse, charged as the coupled contact's energy and momentum balances "
        "give it (default), or eq 12's half sine as the paper's section 4.2 writes it (to "
        "reproduce the paper's figures; docs/validation.md)",
    )
    p.add_argument(
        "--include-string-bed",
        action="store_true",
        help="charge string-bed modes as vibration loss too (default: off)",
    )
    opt.add_string_bed(p)
    opt.add_uncertainty(p)
    opt.add_no_figures(p, "the CSV files, figures.nc (the figures' data)")
    opt.add_out(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    # five figures or more: the helper imports matplotlib while we import the library and compute
    opt.start_figure_helper(args)
    from rich.markup import escape

    from racketdyn._display import case_words
    from racketdyn.plotting.steps import predict_figures
    from racketdyn.workflows.predict import (
        PredictOptions,
        check_supports,
        run_predict,
        transient_csv_name,
    )

    speeds = opt.parse_speeds("--speed", args.speed)
    racket_speed = opt.parse_speeds("--racket-speed", args.racket_speed)
    supports = check_supports(opt.parse_list("--support", args.support), args.model)
    uncertainty = opt.uncertainty_from(args)
    show = None if args.show is None else opt.parse_numbers("--show", args.show, "m/s")
    with opt.progress_display(console) as progress:
        result = run_predict(
            args.out,
            opt.setup_from_args(
                args,
                supports,
                figures=predict_figures(lambda s: progress(s, 0, 0)),
                progress=progress,
            ),
            PredictOptions(
                speeds=speeds,
                racket_speed=racket_speed,
                supports=supports,
                model=args.model,
                engine=args.engine,
                points=args.points,
                grid=args.grid,
                stiffness_reading=args.stiffness_reading,
                vibration_charge=args.vibration_charge,
                include_string_bed=args.include_string_bed,
                uncertainty=uncertainty,
                workers=args.workers,
                show=show,
            ),
        )
    table = result.result
    console.print(
        f"[bold]{table.status.size}[/] {opt.noun(table.status.size, 'impact')} "
        f"({opt.plural(table.locations.shape[0], 'point')} × {opt.plural(len(speeds), 'speed')} "
        f"× {opt.plural(len(supports), 'support')}) "
        f"{'by each model ' if result.comparison is not None else ''}→ {escape(str(result.out))}"
    )
    assert result.racket is not None
    shown = result.shown_speed
    case = case_words(
        result.speeds[shown], result.racket_speed[shown if len(result.racket_speed) > 1 else 0]
    )
    opt.say(
        console,
        f"shown: {case} (face maps, Fig. 15, time histories, the models' comparison, the "
        "report's headline; choose with --show)",
    )
    for label, part, csv_name in (
        ("approximate method", result.approximate, "impact.csv"),
        ("transient model", result.transient, transient_csv_name(args.model)),
    ):
        if part is not None:
            band = result.bands.get("approx" if part is result.approximate else "transient")
            console.print(_headline(part, result.racket, label, band))
            flagged, style = _flagged(part.status, csv_name)
            opt.say(console, flagged, style)
    if result.sensitivity is not None:
        opt.say(console, _dominant_line(result.sensitivity), None)
    if result.comparison is not None:
        console.print(_comparison_table(result.comparison, result.shown_speed, result.racket))
        opt.say(console, *_differ_line(result.comparison))
    unknown = unknown_modes_line(result.modal_model, result.racket)
    if unknown:
        opt.say(console, unknown, "yellow")
    opt.print_written(console, result.written)
    return 0


def unknown_modes_line(model: ModalModel | None, racket: Racket) -> str:
    """A line naming the modal model's modes of unknown kind, which the prediction takes as
    frame modes (new-user trial of 2026-11-26: a string-bed mode identified as ``unknown``
    lengthened the transient contact by 8 %, the strings counted twice).  Where the model has
    hoop and string points the prediction takes the frame's motion under the bed (issue 22,
    seventh session), and a string-bed mode among them counts only through the frame it moves;
    without them the strings may count twice, and the line says how to avoid it."""
    from racketdyn.racket_modal.shapes import SHAPES_FRAME_UNDER_BED, frame_under_bed

    if model is None:
        return ""
    found = [
        name for name, kind in zip(model.names, model.kinds, strict=False) if kind == "unknown"
    ]
    if not found:
        return ""
    listed = ", ".join(found)
    verb = "is" if len(found) == 1 else "are"
    head = f"{listed} {verb} of unknown kind: taken as a frame mode"
    if frame_under_bed(model, racket.head).metadata["shapes_on_strings"] == (
        SHAPES_FRAME_UNDER_BED
    ):
        return (
            f"{head}, with the frame's motion under the bed at the strings (fitted to the "
            "hoop's points; the strings' own give is the ball-string law's), so a string-bed "
            "mode among them is charged only for the frame it moves"
        )
    return (
        f"{head} (vibration charged, and in the transient simulation moving the face under the "
        "ball); the model has no hoop and string points to take the frame's motion under the "
        "bed from, so if the strings make it, they count twice: identify with --racket so its "
        "shape names it, or leave it out (identify --exclude HZ)"
    )


def _headline(
    result: ImpactResult, racket: Racket, label: str, band: UncertainResult | None = None
) -> Table:
    """Contact time, rebound ratio, outgoing ball speed and peak force at the run's point
    nearest the face centre, per support and speed; a flagged row shows its status, not
    numbers; with an uncertainty the rebound ratio's 90 % band is the caption."""
    import numpy as np
    from rich.table import Table

    from racketdyn.impact.result import is_valid
    from racketdyn.racket import landmark_points

    centre = np.asarray(landmark_points(racket)["centre"])
    i = int(np.argmin(np.linalg.norm(result.locations - centre, axis=1)))
    x, y = result.locations[i] * 1e3
    off = float(np.linalg.norm(result.locations[i] - centre)) * 1e3
    table = Table(
        title=opt.plain(
            f"{label} at the face centre: point {result.labels[i]}, x = {x:.0f} mm, "
            f"y = {y:.0f} mm ({off:.0f} mm from the centre)"
        )
    )
    for heading in (
        "support",
        "ball in (m/s)",
        "racket (m/s)",
        "contact time (ms)",
        "rebound ratio",
        "ball out (m/s)",
        "peak force (N)",
        "status",
    ):
        table.add_column(heading)
    if band is not None:
        table.caption = opt.plain(
            f"rebound ratio's 90 % band ({band.uncertainty.samples} samples of "
            f"{', '.join(x.name for x in band.uncertainty.spreads)}): "
            + "; ".join(
                f"{support} {speed:g} m/s {_band(band, (i, s, p))}"
                for p, support in enumerate(result.supports)
                for s, speed in enumerate(result.ball_speed)
            )
        )
    for p, support in enumerate(result.supports):
        for s, speed in enumerate(result.ball_speed):
            status = str(result.status[i, s, p])
            valid = bool(is_valid(status))  # a row filled from the transient model holds numbers
            table.add_row(
                support,
                f"{speed:g}",
                f"{result.racket_speed[s]:g}",
                f"{result.contact_time[i, s, p] * 1e3:.2f}" if valid else "–",
                f"{result.rebound_ratio[i, s, p]:.3f}" if valid else "–",
                f"{result.rebound_speed[i, s, p]:.1f}" if valid else "–",
                f"{result.peak_force[i, s, p]:.0f}" if valid else "–",
                opt.plain(status),
            )
    return table


def _dominant_line(found: Sensitivity) -> str:
    """The input with the largest total Sobol' index of the rebound ratio at each point."""
    parts = [
        f"{label} {found.dominant(p) or f'not known ({found.why_none(p)})'}"
        + (f" (on {share:.0%} of the samples)" if found.dominant(p) and share < 1.0 else "")
        + (f", not told from {', '.join(found.rivals(p))}" if found.rivals(p) else "")
        for p, (label, share) in enumerate(zip(found.labels, found.valid_share, strict=True))
    ]
    return (
        f"dominant input of the rebound ratio at {found.ball_speed:g} m/s, {found.support} "
        f"(largest total Sobol' index; sensitivity.csv): {'; '.join(parts)}"
    )


def _band(band: UncertainResult, at: tuple[int, int, int]) -> str:
    """The rebound ratio's 90 % band, "0.353–0.406", or why there is none."""
    import numpy as np

    low, high = band.quantile("rebound_ratio", 0.05)[at], band.quantile("rebound_ratio", 0.95)[at]
    if not (np.isfinite(low) and np.isfinite(high)):
        return f"none: {band.band_note(*at) or 'no valid sample'}"
    return f"{low:.3f}–{high:.3f}"


def _flagged(status: Any, csv_name: str) -> tuple[str, str | None]:
    """How many rows are flagged (without numbers), by reason, and the line's style (yellow
    when any is); the rows filled from the transient model, which hold numbers, apart."""
    import numpy as np

    from racketdyn.impact.result import STATUS_FROM_TRANSIENT, is_valid

    filled = int(np.count_nonzero(status == STATUS_FROM_TRANSIENT))
    also = (
        f"; {filled} filled from the transient model (valid, marked so in its status column)"
        if filled
        else ""
    )
    bad = ~is_valid(status)
    if not np.any(bad):
        return f"flagged: none of {opt.plural(status.size, 'row')} in {csv_name}{also}", None
    reasons, counts = np.unique(status[bad], return_counts=True)
    why = "; ".join(f"{count} {reason}" for reason, count in zip(reasons, counts, strict=True))
    return (
        f"flagged: {int(bad.sum())} of {opt.plural(status.size, 'row')} in {csv_name} "
        f"(see its status column): {why}{also}",
        "yellow",
    )


def _differ_line(comparison: ModelComparison) -> tuple[str, str | None]:
    """How many rows the two models disagree on by more than MODELS_DIFFER (comparison.csv's
    ``models_differ``), and the line's style."""
    from racketdyn.impact.comparison import MODELS_DIFFER

    count = int(comparison.models_differ.sum())
    text = (
        f"models differ by more than {MODELS_DIFFER:g} in rebound ratio: "
        f"{count} of {opt.plural(comparison.models_differ.size, 'row')} (comparison.csv's "
        "models_differ; trust the transient model there)"
    )
    return text, "yellow" if count else None


def _comparison_table(comparison: ModelComparison, speed: int, racket: Racket) -> Table:
    """At the point nearest the face centre, and the largest difference over the face."""
    import numpy as np
    from rich.table import Table

    from racketdyn._display import case_words

    result = comparison.approximate
    centre = np.array([racket.head.centre_x_m, racket.head.centre_y_m])
    i = int(np.argmin(np.linalg.norm(result.locations - centre, axis=1)))
    x, y = result.locations[i] * 1e3
    case = case_words(float(result.ball_speed[speed]), float(result.racket_speed[speed]))
    table = Table(
        title=opt.plain(
            f"approximate against transient, {case} "
            f"(centre: point {result.labels[i]}, x = {x:.0f} mm, y = {y:.0f} mm)"
        )
    )
    for heading in (
        "support",
        "e approx",
        "e transient",
        "T_c (ms) approx / transient",
        "largest |Δe| on the face (at x, y mm)",
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
            largest = f"{column[worst]:.3f} ({where})"
        else:
            largest = "–"
        table.add_row(
            support,
            f"{e_a[i, speed, p]:.3f}",
            f"{e_t[i, speed, p]:.3f}",
            f"{t_a[i, speed, p] * 1e3:.2f} / {t_t[i, speed, p] * 1e3:.2f}",
            largest,
        )
    return table
