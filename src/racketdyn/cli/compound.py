"""``racketdyn compound``: the modes of a racket with a ball fixed on its strings (section 3.2)."""

from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console

    from racketdyn.ball import Ball
    from racketdyn.impact.compound_band import BedForFrequency
    from racketdyn.workflows.compound import CompoundResult


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "compound",
        "the modes of the racket with a ball fixed on its strings (paper, Figs 8-9)",
        "The linear modes of ball + ball-string spring + racket (rigid body and flexible "
        "modes) for a ball stuck at a point of the face: the ball mode whose half period is "
        "the contact time, the frame modes with and without the ball, and the ball mode of a "
        "racket with a 4x stiffer frame. compound.csv, figures, run.json",
    )
    opt.add_racket_and_ball(p)
    p.add_argument(
        "--ball-at",
        metavar="X,Y",
        help="where the ball sits, x,y in m (default: the centre of the string bed), "
        "e.g. --ball-at=0.5,-0.03 (as rig, identify and compare name a ball on the strings)",
    )
    # the old name (before the ninth session), read still, not shown: see `_ball_at`
    p.add_argument("--point", metavar="X,Y", help=argparse.SUPPRESS)
    opt.add_support(p, "free,hand", "free, pinned, hand, or several: free,hand")
    p.add_argument(
        "--preload",
        type=float,
        default=5.0,
        metavar="N",
        help="force pressing the stuck ball on the strings, N; the spring is the compound "
        "law's tangent there (default 5)",
    )
    p.add_argument(
        "--hammer",
        metavar="X,Y",
        # 12 mm: workflows.compound.HAMMER_OFFSET_M (not imported here: --help stays fast)
        help="where the hammer strikes the string face for Figs 8c and 9, x,y in m (default: "
        "12 mm from the ball towards the handle); with the ball and the blow near the 2-node "
        "mode's node line the neck shows the ball mode first, as in the paper's Fig. 8c",
    )
    opt.add_string_bed(p)
    opt.add_no_figures(p, "compound.csv")
    opt.add_out(p)
    p.set_defaults(handler=run)


def _ball_at(args: argparse.Namespace, console: Console) -> tuple[float, float] | None:
    """``--ball-at``, or ``--point``, its old name (said once, in yellow)."""
    from racketdyn.errors import InputError

    if args.point is None:
        return opt.parse_point("--ball-at", args.ball_at)
    if args.ball_at is not None:
        raise InputError("give --ball-at alone: --point is its old name")
    opt.say(
        console,
        "--point is now --ball-at, the name rig, identify and compare give a ball on the "
        "strings; --point will go in a later version",
        "yellow",
    )
    return opt.parse_point("--point", args.point)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from rich.table import Table

    from racketdyn.plausibility import check as plausible
    from racketdyn.plotting.steps import compound_figures
    from racketdyn.workflows.compound import NOT_THE_PAPERS_RACKET, run_compound

    ball_at = _ball_at(args, console)
    plausible("preload_n", args.preload, "--preload", allow_implausible=args.allow_implausible)
    supports = opt.parse_list("--support", args.support)
    with opt.progress_display(console) as progress:
        result = run_compound(
            args.out,
            opt.setup_from_args(args, supports, figures=compound_figures, progress=progress),
            ball_at=ball_at,
            supports=supports,
            preload_n=args.preload,
            hammer=opt.parse_point("--hammer", args.hammer),
        )
    spring, ball = result.spring, result.ball
    assert spring is not None
    assert ball is not None
    x, y = result.location
    opt.say(
        console,
        f"ball fixed at x = {x * 1e3:.0f} mm, y = {y * 1e3:.0f} mm on a bed preloaded with "
        f"{spring.preload_n:g} N: spring {spring.stiffness / 1e3:.2f} kN/m (tangent of F_GB), "
        f"ζ {spring.damping_ratio * 100:.2f} % (from e_BG) → {result.out}",
    )
    warnings = []
    if result.off_centre_m > _OFF_CENTRE_M and spring.location is None:
        warnings.append(
            f"the spring is the bed's law at the centre of the face, "
            f"{result.off_centre_m * 1e3:.0f} mm from the ball (the bed is stiffer towards the "
            "frame: --string-bed local takes the law at the ball)"
        )
    if result.overhangs:
        warnings.append(
            f"the ball ({ball.diameter_m * 500:.1f} mm in radius) reaches past the string bed's "
            "edge: it would rest on the frame"
        )
    if warnings:
        opt.say(console, "; ".join(warnings), "yellow")
    for support in result.supports:
        modes, alone = result.modes[support], result.alone[support]
        table = Table(title=opt.plain(f"{support}: modes with the ball (and the racket alone)"))
        for column in ("mode", "f (Hz)", "ζ", "ball / frame", "alone (Hz)", "shift"):
            table.add_column(column, justify="left" if column == "mode" else "right")
        for k, name in enumerate(modes.names):
            f_alone = alone.frequency_of(name)
            ratio = float(modes.ball_to_frame_ratio[k])
            table.add_row(
                opt.plain(name),
                f"{modes.frequency[k]:.2f}",
                f"{modes.damping_ratio[k]:.4f}",
                # a twisting mode has no frame motion under the ball on the axis: no ratio
                "–" if math.isnan(ratio) else f"{ratio:.3f}",
                "–" if f_alone != f_alone else f"{f_alone:.2f}",
                "new"
                if f_alone != f_alone
                else f"{100 * (modes.frequency[k] / f_alone - 1):+.2f} %",
            )
        console.print(table)
        times = ", ".join(f"{t * 1e3:.2f}" for t in result.contact_time[support])
        opt.say(
            console,
            f"{support}: ball mode {modes.ball_frequency:.2f} Hz, half period "
            f"{modes.half_period * 1e3:.2f} ms; approximate contact time on a rigid racket "
            f"at 5, 10, 20 m/s (predict's is the flexing frame's, a little longer): {times} ms",
        )
        band, bed = result.band[support], result.paper_bed.get(support)
        reach = " and ".join(f"{a:.0f}–{b:.0f}" for a, b in band.intervals_hz)
        gap = (
            " (a gap where the ball mode crosses a frame mode)"
            if len(band.intervals_hz) > 1
            else ""
        )
        spread = (
            f"{support}: the small-amplitude inputs' spread puts the ball mode at {reach} Hz{gap}"
        )
        if bed is None:
            opt.say(console, f"{spread} ({NOT_THE_PAPERS_RACKET})")
        else:
            opt.say(
                console,
                f"{spread} (the paper's {bed.frequency_hz:g} Hz "
                f"{'inside' if band.holds(bed.frequency_hz) else 'outside'}){_needs(bed, ball)}",
            )
        hand_over = _hand_over_line(result, support)
        if hand_over:
            opt.say(console, hand_over)
        check = result.checks.get(support)
        if check is not None:
            frames = ", ".join(
                f"{name} ×{check.stiffer_frame_hz[name] / f:.2f}"
                for name, f in check.frame_hz.items()
            )
            opt.say(
                console,
                f"{support}, frame {check.factor:g}× stiffer (same mass): ball mode "
                f"{check.ball_hz:.2f} → {check.stiffer_ball_hz:.2f} Hz "
                f"({100 * check.ball_change:+.2f} %); frame modes {frames}",
            )
    opt.print_written(console, result.written)
    return 0


_ON_THE_NODE_LINE_M = 0.005
"""A ball within this of the 2-node node line sits on it (the paper's racket: 3 mm), m."""

_OFF_CENTRE_M = 0.01
"""Beyond this distance of the ball from the bed's centre the console says the spring is the
centre's, m."""


def _needs(bed: BedForFrequency, ball: Ball) -> str:
    """What the paper's ball mode needs of the bed under the nominal ball, in words."""
    if bed.bed_stiffness_n_per_m != bed.bed_stiffness_n_per_m:
        return f"; {bed.note}" if bed.note else ""
    words = (
        f"; {bed.frequency_hz:g} Hz needs the bed at {bed.bed_stiffness_n_per_m / 1e3:.0f} kN/m "
        "under the nominal ball"
    )
    if bed.patch_radius_m == bed.patch_radius_m:
        words += (
            f" (the string net pushed over {bed.patch_radius_m * 1e3:.1f} mm in radius; the "
            f"ball's radius is {ball.diameter_m * 500:.1f} mm)"
        )
    return words


def _hand_over_line(result: CompoundResult, support: str) -> str:
    """Fig. 8c in words: which mode leads at the neck after the blow, and, when the 2-node mode
    does from the start, where its node line is (the ball mode leads near it)."""
    import math

    hand_over = result.hand_over.get(support, {})
    ratio = float(hand_over.get("ball_to_two_node", math.nan))
    cycles = float(hand_over.get("ball_cycles", math.nan))
    if not math.isfinite(ratio) or math.isnan(cycles):
        return ""
    away = math.dist(result.location, result.hammer) * 1e3
    said = f"{support}: at the neck after the blow {away:.0f} mm from the ball "
    if ratio > 1.0 and math.isinf(cycles):
        return (
            f"{said}the ball mode leads ({ratio:.1f}× the 2-node mode) throughout: it decays "
            "more slowly than the 2-node mode (the paper's Fig. 8c: the 2-node mode after about "
            "two cycles)"
        )
    if ratio > 1.0:
        return (
            f"{said}the ball mode leads ({ratio:.1f}× the 2-node mode) and the 2-node mode takes "
            f"over after {cycles:.1f} ball cycles (the paper's Fig. 8c: after about two)"
        )
    said += f"the 2-node mode leads from the start (the ball mode {ratio:.2f}× as large)"
    node = result.node_line.get(support, math.nan)
    if math.isfinite(node):
        off = abs(node - result.location[0])
        advice = (
            "the ball sits near it: strike nearer the ball (--hammer)"
            if off <= _ON_THE_NODE_LINE_M
            else f"with the ball and the blow near it the ball mode leads (--ball-at={node:.3f},0)"
        )
        said += (
            f"; the 2-node mode's node line crosses the axis at x = {node * 1e3:.0f} mm, "
            f"{off * 1e3:.0f} mm from the ball: {advice}, as in the paper's Fig. 8c"
        )
    return said
