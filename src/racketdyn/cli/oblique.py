"""``racketdyn oblique``: oblique impacts with spin — outgoing angle and spin against incoming
angle."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console

OBLIQUE_ANGLES_DEG = "0,10,20,30,40,50,60"


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "oblique",
        "oblique impacts with spin: outgoing angle and spin against incoming angle",
        "A ball arriving at an angle (and with spin) at one point of the face: normal impact "
        "by the transient model, tangential elastic-Coulomb contact on its force history. "
        "oblique.csv, a figure, run.json",
    )
    opt.add_racket_and_ball(p)
    opt.add_speed(p, "20", many=False)
    p.add_argument(
        "--angles",
        default=OBLIQUE_ANGLES_DEG,
        help=f"incoming angles to the face normal, degrees, each in (-90, 90) (default "
        f"{OBLIQUE_ANGLES_DEG}); a list that starts with a minus sign needs --angles=-30,0,30",
    )
    p.add_argument(
        "--spin",
        type=float,
        default=0.0,
        help="incoming spin, rad/s, + = the sense of rolling along the face (default 0)",
    )
    p.add_argument(
        "--point",
        metavar="X,Y",
        help="impact point x,y, m (default: the face centre), e.g. --point=0.5,-0.03",
    )
    opt.add_support(p, "free", "free, pinned or hand")
    p.add_argument(
        "--friction",
        type=float,
        help="ball-string friction coefficient μ, dimensionless (default 0.4)",
    )
    p.add_argument(
        "--tangential-stiffness",
        type=float,
        help="tangential stiffness k_t of strings and ball, N/m (default 1e4; inf: rigid grip)",
    )
    opt.add_racket_speed(p, many=False)
    p.add_argument(
        "--racket-tangential-speed",
        type=float,
        default=0.0,
        help="racket face speed along the face, m/s, brushing the ball (default 0)",
    )
    opt.add_string_bed(p)
    opt.add_no_figures(p, "oblique.csv")
    opt.add_out(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    import numpy as np
    from rich.table import Table

    from racketdyn.plotting.steps import oblique_figures
    from racketdyn.workflows.oblique import SPIN_CAVEAT, ObliqueOptions, run_oblique

    angles = opt.parse_numbers("--angles", args.angles, "degrees from the face normal")
    from racketdyn.plausibility import check_degrees

    check_degrees("--angles", angles, allow_implausible=args.allow_implausible)
    point = opt.parse_point("--point", args.point)
    speed = opt.one_number("--speed", args.speed)
    racket_speed = opt.one_number("--racket-speed", args.racket_speed)
    with opt.progress_display(console) as progress:
        result = run_oblique(
            args.out,
            opt.setup_from_args(args, [args.support], figures=oblique_figures, progress=progress),
            ObliqueOptions(
                speed=speed,
                angles_deg=angles,
                spin_radps=args.spin,
                point=point,
                support=args.support,
                friction=args.friction,
                tangential_stiffness=args.tangential_stiffness,
                racket_speed=racket_speed,
                racket_tangential_speed=args.racket_tangential_speed,
            ),
        )
    curve, contact, where = result.curve, result.contact, result.point
    assert curve is not None
    moving = ""  # the racket's motion is in every number: say it (issue 13)
    if racket_speed or args.racket_tangential_speed:
        moving = f", racket {racket_speed:g} m/s towards it"
        if args.racket_tangential_speed:
            moving += f" and {args.racket_tangential_speed:g} m/s along the face"
    opt.say(
        console,
        f"oblique impacts at x = {where[0] * 1e3:.0f} mm, y = {where[1] * 1e3:.0f} mm, "
        f"ball {speed:g} m/s{moving}, spin {args.spin:g} rad/s, {result.support} → "
        f"{result.out}",
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
    opt.say(console, SPIN_CAVEAT, "yellow")
    opt.print_status(console, curve.status, "oblique.csv")
    opt.print_written(console, result.written)
    return 0
