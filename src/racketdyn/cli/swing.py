"""``racketdyn swing``: a swinging racket — outgoing ball speed over the face, sweet spots."""

from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "swing",
        "a swinging racket: outgoing ball speed over the face and the sweet spots",
        "Outgoing ball speed over the face of a racket swung about the shoulder (constant "
        "shoulder torque, Kawazoe ACMD 2002, or a given angular speed), and where the sweet "
        "spots lie: swing.csv, sweet_spots.csv, figures, run.json",
    )
    opt.add_racket_and_ball(p)
    opt.add_speed(p, "20")
    p.add_argument(
        "--torque",
        type=float,
        help="constant shoulder torque, N·m (default 56.9, Kawazoe ACMD 2002)",
    )
    p.add_argument(
        "--swing-angle-deg",
        type=float,
        help="angle turned from rest to impact, degrees (default 90, an assumption)",
    )
    p.add_argument(
        "--angular-speed",
        type=float,
        help="angular speed at impact, rad/s, instead of the torque model (default: from the "
        "torque)",
    )
    p.add_argument(
        "--axis-to-butt",
        type=float,
        help="swing axis (shoulder) behind the butt, m (default 0.607: straight arm, 1.75 m adult)",
    )
    opt.add_support(
        p, "pinned", "pinned (the paper's hand-held racket), free, or hand (--model transient)"
    )
    p.add_argument(
        "--model",
        choices=opt.IMPACT_MODELS,
        default="approx",
        help="approx: Kawazoe's approximate method (default); transient: the time-domain model",
    )
    opt.add_grid(p, opt.SWING_GRID)
    opt.add_string_bed(p)
    opt.add_uncertainty(p)
    opt.add_no_figures(p, "the CSV files, figures.nc (the figures' data)")
    opt.add_out(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from rich.markup import escape
    from rich.table import Table

    from racketdyn.plotting.steps import swing_figures
    from racketdyn.workflows.swing import one_support, run_swing, swing_from

    speeds = opt.parse_speeds("--speed", args.speed)
    support = one_support(args.support, args.model == "transient")
    swing, swing_defaults = swing_from(
        args.torque,
        args.swing_angle_deg,
        args.angular_speed,
        args.axis_to_butt,
        allow_implausible=args.allow_implausible,
    )
    with opt.progress_display(console) as progress:
        result = run_swing(
            args.out,
            opt.setup_from_args(
                args,
                [support],
                figures=swing_figures,
                progress=progress,
                defaults=swing_defaults,
            ),
            swing=swing,
            speeds=speeds,
            support=support,
            model=args.model,
            grid=args.grid,
            uncertainty=opt.uncertainty_from(args),
            workers=args.workers,
        )
    assert result.swing_result is not None
    assert result.racket is not None
    chosen = result.shown_speed
    console.print(  # the count in bold; the description and the folder are data
        f"swing {escape(swing.describe(result.racket))} ({result.impact_model} model, {support}): "
        f"[bold]{result.swing_result.status.size}[/] "
        f"{opt.noun(result.swing_result.status.size, 'impact')} "
        f"({opt.plural(result.swing_result.locations.shape[0], 'point')} × "
        f"{opt.plural(len(speeds), 'speed')}) → "
        f"{escape(str(result.out))}"
    )
    opt.print_status(console, result.swing_result.status, "swing.csv")
    table = Table(title=opt.plain(f"sweet spots, ball {speeds[chosen]:g} m/s, {support}"))
    for heading in ("sweet spot", "x (mm)", "on the face", "racket (m/s)", "outgoing (m/s)"):
        table.add_column(heading, justify="left" if heading == "sweet spot" else "right")
    for row in result.spot_rows:
        table.add_row(
            opt.plain(row["name"]),
            f"{row['x_m'] * 1e3:.0f}",
            "yes" if row["on_face"] else "no",
            f"{row['racket_speed_mps']:.1f}",
            "–"
            if not math.isfinite(row["rebound_speed_mps"])
            else f"{row['rebound_speed_mps']:.1f}",
        )
    console.print(table)
    if result.band is not None:
        opt.say(console, _band_line(result), None)
    opt.print_written(console, result.written)
    return 0


def _band_line(result: Any) -> str:
    """The outgoing speed's 90 % band at the point nearest the face centre."""
    import numpy as np

    band, racket = result.band, result.racket
    centre = np.array([racket.head.centre_x_m, racket.head.centre_y_m])
    i = int(np.argmin(np.linalg.norm(band.nominal.locations - centre, axis=1)))
    s = result.shown_speed
    low = band.quantile("rebound_speed", 0.05)[i, s, 0]
    high = band.quantile("rebound_speed", 0.95)[i, s, 0]
    shown = (
        f"{low:.1f}–{high:.1f} m/s"
        if np.isfinite(low) and np.isfinite(high)
        else "none (under 90 % of samples valid)"
    )
    return (
        f"outgoing speed at the centre, ball {result.speeds[s]:g} m/s: "
        f"{band.nominal.rebound_speed[i, s, 0]:.1f} m/s, 90 % band {shown} "
        f"({band.uncertainty.samples} samples; swing.csv has every point's)"
    )
