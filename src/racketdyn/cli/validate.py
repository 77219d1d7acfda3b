"""``racketdyn validate``: predicted against measured rebound, both models (issue 15)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console


def add_measured(p: argparse.ArgumentParser) -> None:
    """The measured file, the racket, its modes, the ball, the hand and the engine."""
    p.add_argument(
        "measured",
        metavar="MEASURED.csv",
        help="measured rebound: x_m, y_m, ball_speed_mps, racket_speed_mps, support, and "
        "rebound_ratio or outgoing_speed_mps (optional rebound_ratio_sd); docs/formats.md",
    )
    opt.add_racket_and_ball(p)
    p.add_argument(
        "--engine",
        choices=opt.ENGINES,
        default="auto",
        help="transient model's integrator: auto (default: compiled where numba is installed), "
        "compiled (numba batch) or reference (scipy solve_ivp)",
    )
    opt.add_string_bed(p)


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "validate",
        "predicted against measured rebound, approximate method and transient simulation",
        "Each measured row predicted by the approximate method and the transient simulation: "
        "validation.csv (measured, predicted, residual and status per model), the RMS error and "
        "bias per model (flagged rows left out and counted), figures, run.json",
    )
    add_measured(p)
    p.add_argument(
        "--calibration",
        metavar="FILE",
        help="calibration.json from racketdyn calibrate: its identifiable values applied "
        "(default: none, the inputs as given)",
    )
    opt.add_uncertainty(p)
    opt.add_no_figures(p, "validation.csv")
    opt.add_out(p)
    p.set_defaults(handler=run)


def hand_supports(args: argparse.Namespace) -> tuple[str, ...]:
    """``("hand",)`` with a hand option (--hand-arm-mass, --hand-stiffness, --hand-damping):
    the hand is built; else none (the measured file's supports choose)."""
    given = any(getattr(args, name) is not None for name in opt.HAND_OPTIONS)
    return ("hand",) if given else ()


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from rich.table import Table

    from racketdyn.impact.measured import OUTLIER_LIMIT
    from racketdyn.plotting.steps import validate_figures
    from racketdyn.workflows.validate import run_validate

    uncertainty = opt.uncertainty_from(args)
    with opt.progress_display(console) as progress:
        result = run_validate(
            args.out,
            args.measured,
            opt.setup_from_args(
                args, hand_supports(args), figures=validate_figures, progress=progress
            ),
            calibration=args.calibration,
            engine=args.engine,
            uncertainty=uncertainty,
            workers=args.workers,
        )
    table = Table(
        title=opt.plain(f"{opt.plural(len(result.measured or ()), 'measured row')} → {result.out}")
    )
    for column in (
        "model",
        "compared",
        "flagged",
        "RMS e",
        "bias e",
        "RMS v_out (m/s)",
        "RMS v_out (%)",
    ):
        table.add_column(column, justify="left" if column == "model" else "right")
    for summary in result.summary.values():
        table.add_row(
            opt.plain(summary.method),
            str(summary.n_compared),
            str(summary.n_flagged),
            f"{summary.rms:.4f}",
            f"{summary.bias:+.4f}",
            f"{summary.rms_speed_mps:.3f}",
            f"{summary.rms_speed_percent:.2f}",
        )
    console.print(table)
    for summary in result.summary.values() if result.bands else ():
        outside = ", ".join(summary.outside[:10]) + (" …" if len(summary.outside) > 10 else "")
        opt.say(
            console,
            f"{summary.method}: {summary.n_inside} of {summary.n_banded} measured rows inside "
            f"their predicted 90 % band (median width {summary.median_band_width:.3f})"
            + (f"; outside: {outside}" if summary.outside else ""),
            "yellow" if summary.outside else None,
        )
    for method in result.standardised:
        named = result.outliers(method)
        if named:
            shown = ", ".join(named[:10]) + (" …" if len(named) > 10 else "")
            opt.say(
                console,
                f"{method}: {opt.plural(len(named), 'row')} beyond ±{OUTLIER_LIMIT:g} standard "
                f"deviations: {shown} (z_{method} in validation.csv)",
                "yellow",
            )
    for method, status in result.status.items():
        opt.print_status(console, status, "validation.csv", method)
    opt.print_written(console, result.written)
    return 0
