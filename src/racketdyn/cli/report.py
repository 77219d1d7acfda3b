"""``racketdyn report``: the HTML report of a demo folder, or of a lab's own step folders."""

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
        "the HTML report of a demo folder or of a lab's step folders",
        "Rebuild report.html from the step folders of a run (racketdyn demo's layout, or the "
        "folders a lab ran step by step); it says which folder it used for each step",
    )
    p.add_argument(
        "run_dir",
        help="a folder written by racketdyn demo, or holding a lab's step folders (the page "
        "is written there)",
    )
    p.add_argument(
        "--steps",
        metavar="NAME=FOLDER,...",
        help="the folder to use for a step, for those the folder holds several runs of: NAME "
        "a step (rig, frf, contact, identify, compare, compare_ball, predict, swing, twist, "
        "oblique, compound, validate, calibrate; frf and identify may repeat) or the label "
        "of an FRF or identify run (free, hand); FOLDER relative to RUN_DIR or absolute, e.g. "
        "rig=lab/rig,free=frf_free,predict=serve; dimensionless (default: every step's one "
        "folder found under RUN_DIR)",
    )
    opt.add_racket(p)
    p.set_defaults(handler=run)


def parse_steps(text: str | None) -> list[tuple[str, str]] | None:
    """``NAME=FOLDER,…`` as pairs (None stays None)."""
    from racketdyn.errors import InputError

    if text is None:
        return None
    pairs = []
    for item in opt.parse_list("--steps", text):
        name, equals, folder = item.partition("=")
        if not (equals and name.strip() and folder.strip()):
            raise InputError(
                f"--steps: {item!r} is not NAME=FOLDER (e.g. rig=lab/rig,free=frf_free)"
            )
        pairs.append((name.strip(), folder.strip()))
    return pairs


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from pathlib import Path

    from racketdyn.errors import InputError
    from racketdyn.report import write_report
    from racketdyn.report.folder import RunFolder
    from racketdyn.workflows.inputs import load_racket_input

    run_dir = Path(args.run_dir)
    if not run_dir.is_dir():
        raise InputError(f"{run_dir}: no such folder; give a folder written by racketdyn demo")
    steps = parse_steps(args.steps)
    # without --racket the report takes the racket the runs recorded in their run.json
    racket = None if args.racket is None else load_racket_input(args.racket)[0]
    found = RunFolder.scan(run_dir, racket, steps)
    for step in found.steps:
        label = f" ({step.label})" if step.label and step.label != step.name else ""
        how = ", given with --steps" if step.given else ""
        opt.say(console, f"{step.name}: {found.rel(step.folder) or '.'}{label}{how}")
    for folder, why in found.left_out:
        opt.say(console, f"{found.rel(folder)}: left out ({why})")
    opt.say(console, f"wrote {write_report(run_dir, racket, steps=steps)}")
    return 0
