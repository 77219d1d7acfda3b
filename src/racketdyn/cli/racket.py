"""``racketdyn racket``: print a racket's derived properties and its modes."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(commands, "racket", "print a racket's derived properties and its modes")
    opt.add_racket(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from rich.table import Table

    from racketdyn.racket_modal import modal_model_for
    from racketdyn.report.formatting import DERIVED_LABELS, quantity
    from racketdyn.workflows.inputs import load_racket_input

    racket, provenance = load_racket_input(args.racket)
    # the file on a line of its own, never folded (a long path in the title was, mid-name)
    opt.say(console, f"racket file: {provenance['racket_file']}", soft_wrap=True)
    table = Table(title=opt.plain(racket.name))
    table.add_column("property")
    table.add_column("value", justify="right")
    table.add_column("unit")
    derived = racket.derived_properties()
    for key, value in derived.items():
        if key == "inertia_cg_kgm2" and "recoil_weight_kgcm2" in derived:
            continue  # the recoil weight is this inertia: one row, one unit (issue 13)
        name, text, unit = quantity(key, value)  # the units the field quotes, as the report
        table.add_row(DERIVED_LABELS.get(key.rpartition("_")[0], name), text, unit)
    model = modal_model_for(racket)
    for name, frequency in zip(model.names, model.frequency, strict=True):
        table.add_row(opt.plain(f"mode: {name} ({model.support})"), f"{frequency:.1f}", "Hz")
    console.print(table)
    mass_model = model.metadata.get("mass_model")
    if mass_model is not None:
        opt.say(console, MASS_MODELS[str(mass_model)])
    for line in _defaults(args.racket, racket):
        opt.say(console, line)
    return 0


MASS_MODELS = {
    "frame": "built-in modes: mass along the racket from the frame's shape (shaft, throat arms, "
    "hoop, handle and the head's top, meeting its mass, balance and inertia)",
    "smooth": "built-in modes: mass along the racket smooth (the frame's shaft, arms, hoop, "
    "handle and head's top cannot meet this racket's mass, balance and inertia with none "
    "negative: more mass at its ends than they hold)",
}
"""The built-in model's mass distribution in words (``metadata["mass_model"]``, issue 22)."""


def _defaults(path: Any, racket: Any) -> list[str]:
    """The built-in modal model's targets a racket file leaves to their defaults (the paper's
    racket's frequencies), in words (the new-user trial of issue 13)."""
    import tomllib
    from pathlib import Path

    if path is None or racket.modal_model_file is not None:
        return []
    with Path(path).open("rb") as handle:
        modal = tomllib.load(handle).get("modal", {})
    given = modal if isinstance(modal, dict) else {}
    return [
        f"[modal] {key} not in the file: the built-in modes are tuned to the default "
        f"{value:g} Hz (the paper's racket's); give {key} for this racket's own"
        for key, value in (
            ("first_bending_hz", racket.first_bending_hz),
            ("twisting_hz", racket.twisting_hz),
        )
        if key not in given
    ]
