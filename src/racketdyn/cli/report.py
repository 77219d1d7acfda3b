"""``racketdyn report``: the HTML report of a demo folder."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "report",
        "the HTML report of a demo folder",
        "Rebuild report.html from the step folders of a run (racketdyn demo's layout)",
    )
    p.add_argument("run_dir", help="a folder written by racketdyn demo")
    opt.add_racket(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from pathlib import Path

    from racketdyn.errors import InputError
    from racketdyn.report import write_report
    from racketdyn.workflows.inputs import load_racket_input

    run_dir = Path(args.run_dir)
    if not run_dir.is_dir():
        raise InputError(f"{run_dir}: no such folder; give a folder written by racketdyn demo")
    # without --racket the report takes the racket the runs recorded in their run.json
    racket = None if args.racket is None else load_racket_input(args.racket)[0]
    opt.say(console, f"wrote {write_report(run_dir, racket)}")
    return 0
