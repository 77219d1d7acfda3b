"""``racketdyn frf``: FRFs, quality table and plots from hammer-test records."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console


def add_geometry(parser: argparse.ArgumentParser) -> None:
    """``--geometry FILE``."""
    parser.add_argument(
        "--geometry",
        metavar="FILE",
        help="node coordinates (UFF 15/2411, or CSV node,x_m,y_m in m) (default: from the "
        "records file)",
    )


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "frf",
        "FRFs, quality table and plots from hammer-test records",
        "One FRF per hammer point from its accepted averages: quality.csv, frfs.uff, "
        "Figs 2-3, run.json",
    )
    p.add_argument("tests", help="hammer records: UFF 58 time records, or CSV (with --geometry)")
    add_geometry(p)
    opt.add_racket(p, " for the head outline")
    p.add_argument(
        "--estimator",
        choices=("H1", "H2"),
        default="H1",
        help="FRF estimator: H1 (noise on the response) or H2 (noise on the force) (default H1)",
    )
    p.add_argument(
        "--force-window",
        type=float,
        help="keep the force this long after the trigger, s (default: no force window)",
    )
    p.add_argument(
        "--exp-window",
        type=float,
        help="exponential window time constant τ on force and response, s (default: no "
        "window; identify takes 1/τ off the damping)",
    )
    p.add_argument(
        "--force-range",
        type=float,
        help="hammer channel range, N: reaching it is an overload (default: flat tops only)",
    )
    opt.add_allow_implausible(
        p, "a --force-range outside 10-100000 N, or hits whose median peak is under 1 N (volts)"
    )
    opt.add_out(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from racketdyn.plotting.steps import frf_figures
    from racketdyn.workflows.frf import run_frf

    with opt.progress_display(console) as progress:
        result = run_frf(
            args.tests,
            args.out,
            opt.setup_from_args(args, figures=frf_figures, progress=progress),
            geometry=args.geometry,
            estimator=args.estimator,
            force_window_s=args.force_window,
            exponential_window_s=args.exp_window,
            force_range_n=args.force_range,
        )
    estimate = result.estimate
    assert estimate is not None
    assert estimate.frfs is not None
    summary = estimate.summary()
    opt.say(
        console,
        f"{opt.plural(estimate.frfs.n_points, 'FRF')} from {summary['accepted']} of "
        f"{opt.plural(summary['averages'], 'average')} → {result.out}",
    )
    rejected = summary["averages"] - summary["accepted"]
    if 2 * rejected > summary["averages"]:
        opt.say(
            console,
            f"most averages rejected ({rejected} of {summary['averages']}), why: "
            f"{estimate.rejections()}; every verdict in quality.csv",
            "yellow",
        )
    else:
        for reason, count in summary.items():
            if reason not in ("averages", "accepted"):
                opt.say(console, f"{opt.plural(count, 'average')} rejected: {reason}", "yellow")
    if estimate.frfs.coherence is None:
        opt.say(
            console,
            "one average a point: no coherence (with one average it is 1 by definition); "
            "several hits a point measure it",
            "yellow",
        )
    noise = estimate.noise_only()
    if noise is not None and noise.noise_nodes:
        opt.say(console, noise.sentence(), "yellow")
    fewer = result.records_metadata.get("fewer_averages")
    if fewer:
        opt.say(console, fewer, "yellow")
    three_d = result.records_metadata.get("three_d_geometry")
    if three_d:
        opt.say(
            console,
            f"the points differ in z (3-D): frfs.uff carries no coordinates; give "
            f"--geometry {three_d} to identify for the (x, y, z) points",
            "yellow",
        )
    force = estimate.frfs.force_band_hz
    if force is not None and force < estimate.frfs.bandwidth_hz:
        from racketdyn.modal.identify import no_force_words

        opt.say(
            console,
            f"{no_force_words(force)} (its envelope, at the point whose force reaches "
            f"highest): identify's default band ends at {force:.6g} Hz",
        )
    hint = estimate.force_noise_hint()
    if hint:
        opt.say(console, opt.in_flags(hint, args.parser), "yellow")
    if estimate.rejected_points:
        nodes = ", ".join(str(n) for n in estimate.rejected_points)
        at = opt.noun(len(estimate.rejected_points), "node")
        opt.say(console, f"every average rejected at {at} {nodes}: no FRF there", "yellow")
    opt.print_written(console, result.written)
    return 0
