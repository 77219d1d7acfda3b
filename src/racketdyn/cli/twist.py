"""``racketdyn twist``: off-axis impacts — the racket's roll (twist) and the outgoing speed
against the offset from the long axis."""

from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console

TWIST_OFFSETS_M = "-0.08,-0.06,-0.04,-0.02,0,0.02,0.04,0.06,0.08"


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "twist",
        "off-axis impacts: the racket's roll (twist) and the outgoing speed against offset",
        "Impacts across the face at one x: the racket's roll and twist at separation and the "
        "outgoing ball speed against the offset from the long axis (transient model). "
        "twist.csv, a figure, run.json",
    )
    opt.add_racket_and_ball(p)
    p.add_argument(
        "--x",
        type=float,
        help="impact position from the butt, m (default: the racket's face centre)",
    )
    p.add_argument(
        "--offsets",
        default=TWIST_OFFSETS_M,
        help="offsets y from the long axis, m (default -0.08 to 0.08 in steps of 0.02); a list "
        "that starts with a minus sign needs the = form: --offsets=-0.05,0,0.05",
    )
    opt.add_speed(p, "25", many=False)
    opt.add_racket_speed(p, many=False)
    opt.add_support(p, "free", "free, hand, pinned, or several: free,hand (one line each)")
    opt.add_string_bed(p)
    opt.add_no_figures(p, "twist.csv")
    opt.add_out(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    import numpy as np
    from rich.table import Table

    from racketdyn.plotting.steps import twist_figures
    from racketdyn.workflows.twist import run_twist

    offsets = opt.parse_numbers("--offsets", args.offsets, "offsets from the long axis in m")
    supports = opt.parse_list("--support", args.support)
    speed = opt.one_number("--speed", args.speed)
    with opt.progress_display(console) as progress:
        result = run_twist(
            args.out,
            setup=opt.setup_from_args(args, supports, figures=twist_figures, progress=progress),
            x_m=args.x,
            offsets_m=offsets,
            speed=speed,
            racket_speed=opt.one_number("--racket-speed", args.racket_speed),
            supports=supports,
        )
    opt.say(
        console,
        f"twist at x = {result.curves[0].x_m * 1e3:.0f} mm, ball {speed:g} m/s: "
        f"{opt.plural(len(offsets), 'offset')} × "
        f"{opt.plural(len(supports), 'support')} → {result.out}",
    )
    table = Table(title="roll angle at separation (°), + turns the +y side away from the ball")
    table.add_column("y (mm)", justify="right")
    for support in supports:
        table.add_column(f"{support}: roll (°)", justify="right")
        table.add_column(f"{support}: outgoing (m/s)", justify="right")
    for i in np.argsort(offsets):
        cells = [f"{offsets[i] * 1e3:.0f}"]
        for c in result.curves:
            cells += [f"{math.degrees(c.roll_angle_rad[i]):.2f}", f"{c.rebound_speed_mps[i]:.2f}"]
        table.add_row(*cells)
    console.print(table)
    for c in result.curves:
        opt.print_status(console, c.status, "twist.csv")
    opt.print_written(console, result.written)
    return 0
