"""``racketdyn contact``: hammer contact time over the face (paper Fig. 7)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt
from racketdyn.cli.frf import add_geometry

if TYPE_CHECKING:
    from rich.console import Console


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "contact",
        "hammer contact time over the face (paper Fig. 7)",
        "Contact time of every hammer hit (1.5 x the pulse's FWHM), per point and test: "
        "contact_<label>.csv, Fig. 7, run.json",
    )
    p.add_argument("tests", nargs="+", help="hammer records, one file per condition")
    p.add_argument("--labels", help="a label per file, e.g. free,hand (default: the file names)")
    add_geometry(p)
    opt.add_racket(p, " for the head outline")
    opt.add_out(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    import numpy as np

    from racketdyn.plotting.steps import contact_figures
    from racketdyn.workflows.contact import run_contact

    labels = opt.parse_list("--labels", args.labels) if args.labels else None
    with opt.progress_display(console) as progress:
        result = run_contact(
            args.tests,
            args.out,
            opt.setup_from_args(args, figures=contact_figures, progress=progress),
            labels=labels,
            geometry=args.geometry,
        )
    assert result.racket is not None
    for said in result.fewer_averages:
        opt.say(console, said, "yellow")
    for label, times in zip(result.labels, result.tables, strict=True):
        on_bed = result.racket.head.contains(times.locations) & np.isfinite(times.mean_s)
        if np.any(on_bed):
            opt.say(
                console,
                f"{label}: contact time on the strings {np.nanmin(times.mean_s[on_bed]) * 1e3:.2f}"
                f"–{np.nanmax(times.mean_s[on_bed]) * 1e3:.2f} ms over "
                f"{opt.plural(int(on_bed.sum()), 'point')}",
            )
    opt.print_written(console, result.written)
    return 0
