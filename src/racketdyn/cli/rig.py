"""``racketdyn rig``: a virtual roving-hammer test of a racket model (UFF out)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console

BALL_BAND_HZ = (40.0, 850.0)
"""The band the hint after ``rig --ball-at`` gives ``identify``: the frame's modes up to the
played bed's membrane.  Over the records' whole band (to 1953 Hz on the built-in racket) the
fit near the heavily damped ball mode (ζ ≈ 6 %, as ``compound``'s) is too poor for identify
to keep it (1.46 × better with it, where it keeps 1.5 ×); in this band it finds it within
0.02 % (issue 22)."""


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "rig",
        "virtual roving-hammer test of a racket model (UFF out)",
        "A roving-hammer test simulated on the virtual rig: hammer_<support>.uff (geometry + "
        "time records), modal_truth_<support>.json, run.json",
    )
    opt.add_racket(p)
    opt.add_support(
        p,
        "free",
        "free (on a sponge), hand (held by a hand), or free,hand: both tests into the one folder",
    )
    p.add_argument("--averages", type=int, default=10, help="hits per point, a count (default 10)")
    p.add_argument(
        "--double-hits",
        type=float,
        default=0.0,
        help="probability of a double hit per hit, 0 to 1, dimensionless (default 0)",
    )
    p.add_argument(
        "--overloads",
        type=float,
        default=0.0,
        help="probability of an overload per hit, 0 to 1, dimensionless (default 0)",
    )
    p.add_argument("--seed", type=int, default=1, help="random seed, a count (default 1)")
    p.add_argument(
        "--ascii",
        action="store_true",
        help="write the hammer records as ASCII UFF 58 text, 12 significant digits (default: "
        "binary UFF 58b, the doubles themselves, about 2.4 times smaller)",
    )
    p.add_argument(
        "--ball-at",
        metavar="X,Y",
        help="fix a ball on the strings at x,y, m, as in the paper's compound test (Figs 8-9); "
        "the hammer skips the points under it (default: no ball)",
    )
    p.add_argument(
        "--force-snr",
        type=float,
        metavar="DB",
        help="hammer noise as a signal-to-noise ratio, dB: each record's peak over its noise rms "
        "(default: a fixed 0.02 N rms noise floor)",
    )
    p.add_argument(
        "--response-snr",
        type=float,
        metavar="DB",
        help="accelerometer noise as a signal-to-noise ratio, dB: each record's peak over its "
        "noise rms; 40 gives coherence ≈ 0.95 and damping within a few %% (default: a fixed "
        "0.05 m/s² rms noise floor)",
    )
    p.add_argument(
        "--pretrigger",
        type=float,
        default=0.01,
        metavar="S",
        help="time recorded before the pulse, s (default 0.01)",
    )
    p.add_argument(
        "--time-zero",
        choices=("pulse", "record"),
        default="pulse",
        help="where the file's time axis starts: pulse (t = 0 at the pulse, the pre-trigger "
        "negative) or record (t = 0 at the first sample, the pulse --pretrigger into it, as "
        "many acquisition systems export) (default pulse)",
    )
    p.add_argument(
        "--accelerometer-direction",
        type=int,
        choices=(3, -3),
        default=3,
        help="the accelerometer's UFF direction code: 3 (+z, along the hammer) or -3 (mounted "
        "against it), dimensionless (default 3)",
    )
    p.add_argument(
        "--no-driving-point",
        action="store_true",
        help="the hammer skips the accelerometer's node: identify then gives unscaled shapes "
        "(default: the node is struck too)",
    )
    p.add_argument(
        "--lab-plane",
        choices=("xy", "xz"),
        default="xy",
        help="the lab plane the file's coordinates put the face in: xy, or xz (the racket "
        "standing: points (x, 0, y), normal along y, direction codes ±2; identify then needs "
        "--geometry hammer_<support>.uff), dimensionless (default xy)",
    )
    p.add_argument(
        "--layout",
        choices=("roving-hammer", "roving-accelerometer"),
        default="roving-hammer",
        help="roving-hammer, or roving-accelerometer: the hammer on the reference node, the "
        "accelerometer moved over the points (by reciprocity the same FRFs), dimensionless "
        "(default roving-hammer)",
    )
    opt.add_out(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from racketdyn.workflows.rig import RigOptions, run_rig

    with opt.progress_display(console) as progress:
        setup = opt.setup_from_args(args, progress=progress)
        options = RigOptions(
            support=opt.parse_list("--support", args.support),
            averages=args.averages,
            double_hits=args.double_hits,
            overloads=args.overloads,
            seed=args.seed,
            binary=not args.ascii,
            ball_at=opt.parse_point("--ball-at", args.ball_at),
            force_snr_db=args.force_snr,
            response_snr_db=args.response_snr,
            pretrigger_s=args.pretrigger,
            time_zero=args.time_zero,
            response_direction=args.accelerometer_direction,
            driving_point=not args.no_driving_point,
            lab_plane=args.lab_plane,
            layout=args.layout,
        )
        result = run_rig(args.out, setup, options)
    for support in result.supports:
        records, truth, faults = (
            result.records[support],
            result.truth[support],
            result.faults[support],
        )
        ball = "" if result.ball is None else " with a ball on the strings"
        opt.say(
            console,
            f"{opt.plural(records.n_points, 'point')} × {opt.plural(args.averages, 'average')} "
            f"on the {support} rig{ball} "
            f"(accelerometer at node {result.reference_node}), "
            f"{opt.plural(faults['double_hits'], 'double hit')}, "
            f"{opt.plural(faults['overloads'], 'overload')} → {result.out}",
        )
        for name, frequency, damping in zip(
            truth.names, truth.frequency, truth.damping_ratio, strict=True
        ):
            if frequency > 15.0:
                opt.say(console, f"  {name:24s} {frequency:8.1f} Hz  ζ = {damping * 100:.2f} %")
    opt.print_written(console, result.written)
    if result.ball is not None:
        x, y = result.ball["location_m"]
        opt.say(
            console,
            f"the ball's mode is heavily damped: frf --exp-window 0.1, then identify "
            f"--ball-at {x:g},{y:g} --band {BALL_BAND_HZ[0]:g},{BALL_BAND_HZ[1]:g} to name it",
            "dim",
        )
    return 0
