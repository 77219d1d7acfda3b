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
    from racketdyn.workflows.inputs import load_racket_input

    racket, provenance = load_racket_input(args.racket)
    table = Table(title=f"{racket.name} ({provenance['racket_file']})")
    table.add_column("property")
    table.add_column("value", justify="right")
    table.add_column("unit")
    units = {"kg": "kg", "m": "m", "kgm2": "kg·m²", "kgcm2": "kg·cm²", "cm2": "cm²"}
    for key, value in racket.derived_properties().items():
        name, _, unit = key.rpartition("_")
        table.add_row(name.replace("_", " "), f"{value:.4g}", units.get(unit, unit))
    model = modal_model_for(racket)
    for name, frequency in zip(model.names, model.frequency, strict=True):
        table.add_row(f"mode: {name} ({model.support})", f"{frequency:.1f}", "Hz")
    console.print(table)
    return 0
