"""``racketdyn ball``: the ball's bounce on a rigid surface and on head-clamped strings."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console

BALL_SPEEDS = "4.43,7.06,10,20,30,40"


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "ball",
        "the ball's bounce on a rigid surface and on head-clamped strings",
        "The check a lab runs on a new ball: the ball model's bounce on a rigid surface and on "
        "the racket's string bed clamped by its head, at each speed: the ball's flattening, "
        "the COR, the contact time and the peak force (ball.csv, ball.nc), the hysteresis "
        "loops (ball_hysteresis.png) and the slow ITF plate test on the static law as a "
        "separate check",
    )
    opt.add_racket(p, " whose strings the ball meets")
    opt.add_ball(p)
    opt.add_allow_implausible(p)
    opt.add_speed(p, BALL_SPEEDS)
    p.add_argument(
        "--surface",
        default="rigid,strings",
        metavar="NAME[,NAME]",
        help="rigid, strings, or both (default rigid,strings)",
    )
    p.add_argument(
        "--tension",
        type=float,
        metavar="N",
        help="string (pull) tension of the clamped bed, N (default: the racket's); the bed "
        "plays at it less the racket file's tension_loss (default 30 %%)",
    )
    opt.add_no_figures(p, "ball.csv, ball.nc")
    opt.add_out(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from rich.table import Table

    from racketdyn.errors import InputError
    from racketdyn.plausibility import check, check_speeds
    from racketdyn.plotting.steps import ball_figures
    from racketdyn.workflows.ball import run_ball

    speeds = opt.parse_speeds("--speed", args.speed)
    if any(v <= 0 for v in speeds):
        raise InputError("--speed: every impact speed must be above 0 m/s")
    check_speeds("--speed", speeds, "ball_speed_mps", args.allow_implausible)
    if args.tension is not None:
        check("tension_n", args.tension, "--tension", allow_implausible=args.allow_implausible)
    surfaces = opt.parse_list("--surface", args.surface)
    for name in surfaces:
        if name not in ("rigid", "strings"):
            raise InputError(f"--surface {name!r}: choose rigid, strings or rigid,strings")
    with opt.progress_display(console) as progress:
        result = run_ball(
            args.out,
            opt.setup_from_args(args, figures=ball_figures, progress=progress),
            speeds=speeds,
            surfaces=surfaces,
            tension_n=args.tension,
        )
    assert result.bounces is not None
    table = Table(
        title=opt.plain(
            f"the ball's bounce (strings at {result.tension_n:g} N, "
            f"{result.bed_tension_n:.4g} N in the played bed)"
        )
    )
    for name, justify in (
        ("surface", "left"),
        ("speed (m/s)", "right"),
        ("ball flattening (mm)", "right"),
        ("COR", "right"),
        ("contact time (ms)", "right"),
        ("peak force (N)", "right"),
    ):
        table.add_column(name, justify=justify)  # type: ignore[arg-type]
    for row in result.bounces.rows():
        table.add_row(
            row["surface"],
            f"{row['speed_mps']:g}",
            f"{row['peak_compression_m'] * 1e3:.2f}",
            f"{row['cor']:.3f}",
            f"{row['contact_time_s'] * 1e3:.2f}",
            f"{row['peak_force_n']:.0f}",
        )
    console.print(table)
    opt.say(
        console,
        f"ITF plate test (slow, 80.1 N between two plates) on the static ball law: "
        f"{result.static_deformation_m * 1e3:.2f} mm (ITF limits 5.6-7.4 mm): a different "
        "test from a bounce",
    )
    rigid = [row for row in result.bounces.rows() if row["surface"] == "rigid"]
    if rigid and max(row["speed_mps"] for row in rigid) > _ITF_DROP_MPS:
        opt.say(
            console,
            f"the ball's own COR on a rigid surface is one number, {rigid[0]['cor']:.3f} (the "
            f"ITF rebound test at {_ITF_DROP_MPS:g} m/s), at every speed: measured balls lose "
            "more at higher speeds (docs/references.md, 'Ball and strings'), so above it the "
            "rigid COR here is an upper bound",
        )
    opt.print_written(console, result.written)
    return 0


_ITF_DROP_MPS = 7.06
"""The ITF rebound test's impact speed (a drop from 100 in), where the ball's COR is set."""
