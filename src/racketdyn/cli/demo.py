"""``racketdyn demo``: the whole chain on the virtual rig, with the report.

The demo is a composition at the CLI level: it calls the workflows one after the other (rig
free and hand-held → FRFs → contact times → identification and comparison → prediction by
both impact models with the identified free modes → swing, twist, oblique → report), passes
the CLI's figure hooks, and records in each step's run.json the ``racketdyn`` command that
repeats that step.  Python users compose the same workflows the same way.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console

    from racketdyn.racket import Racket

DOUBLE_HITS, OVERLOADS = 0.03, 0.01  # probabilities per hit: a real test has a few bad hits
# mild measurement noise, each record's peak over its noise rms (issue 12): identification
# stays within 0.004 % in frequency and 0.3 % in damping (free, 40–850 Hz; docs/develop.md)
RESPONSE_SNR_DB, FORCE_SNR_DB = 50.0, 60.0
EXP_WINDOW_S = 0.1
FORCE_WINDOW_S = 0.01
FORCE_RANGE_N = 200.0
BAND_HZ = (40.0, 850.0)


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "demo",
        "the whole chain on a virtual rig, with a report",
        "Virtual hammer tests (free, hand-held) → FRFs → contact times → identification and "
        "comparison → prediction by both impact models → swing, twist, oblique → the ball on "
        "the strings → report.html, one folder per step",
    )
    opt.add_racket(p)
    opt.add_out(p)
    p.set_defaults(handler=run)


def steps(out: Path, racket: str | None) -> list[tuple[str, list[str], Callable[[], object]]]:
    """The demo's steps: label, the equivalent command, and the call."""
    from racketdyn.plotting import steps as fig
    from racketdyn.workflows.compound import run_compound
    from racketdyn.workflows.contact import run_contact
    from racketdyn.workflows.frf import run_frf
    from racketdyn.workflows.identify import IdentifyOptions, run_compare
    from racketdyn.workflows.oblique import run_oblique
    from racketdyn.workflows.predict import PredictOptions, run_predict
    from racketdyn.workflows.rig import RigOptions, run_rig
    from racketdyn.workflows.setup import Setup
    from racketdyn.workflows.swing import run_swing
    from racketdyn.workflows.twist import run_twist

    r = [] if racket is None else ["--racket", racket]
    rig, free, hand = out / "rig", out / "frf_free", out / "frf_hand"
    modal = out / "compare" / "modal_model_free.json"
    faults = ["--double-hits", "0.03", "--overloads", "0.01"]
    noise = ["--response-snr", "50", "--force-snr", "60"]
    frf_options = [
        *("--exp-window", f"{EXP_WINDOW_S:g}"),
        *("--force-window", f"{FORCE_WINDOW_S:g}"),
        *("--force-range", f"{FORCE_RANGE_N:g}"),
    ]
    identified = [*r, "--modal", str(modal)]
    result: list[tuple[str, list[str], Callable[[], object]]] = []

    from racketdyn.cli import compound as compound_command
    from racketdyn.cli import contact as contact_command
    from racketdyn.cli import frf as frf_command
    from racketdyn.cli import identify as identify_command
    from racketdyn.cli import oblique as oblique_command
    from racketdyn.cli import predict as predict_command
    from racketdyn.cli import rig as rig_command
    from racketdyn.cli import swing as swing_command
    from racketdyn.cli import twist as twist_command
    from racketdyn.cli.options import in_flags, parser_of

    modules = {
        "rig": rig_command,
        "frf": frf_command,
        "contact": contact_command,
        "compare": identify_command,
        "predict": predict_command,
        "swing": swing_command,
        "twist": twist_command,
        "oblique": oblique_command,
        "compound": compound_command,
    }

    def step(label: str, argv: list[str], call: Callable[..., object], setup: Setup) -> None:
        command = ["racketdyn", *argv]
        # run.json's notes in the words of the command the step stands for, as on its own
        words = partial(in_flags, parser=parser_of(modules[argv[0]], argv[0]))
        setup = setup.replace(command=command, words=words)
        result.append((label, command, partial(call, setup=setup)))

    step(
        "virtual hammer tests, free and hand-held",
        ["rig", *r, "--support", "free,hand", *faults, *noise, "--out", str(rig)],
        partial(
            run_rig,
            rig,
            options=RigOptions(
                support=("free", "hand"),
                double_hits=DOUBLE_HITS,
                overloads=OVERLOADS,
                response_snr_db=RESPONSE_SNR_DB,
                force_snr_db=FORCE_SNR_DB,
            ),
        ),
        Setup(racket=racket),
    )
    for support, folder, label in (("free", free, "free"), ("hand", hand, "hand-held")):
        tests = rig / f"hammer_{support}.uff"
        step(
            f"FRFs, {label}",
            ["frf", str(tests), *r, *frf_options, "--out", str(folder)],
            partial(
                run_frf,
                tests,
                folder,
                exponential_window_s=EXP_WINDOW_S,
                force_window_s=FORCE_WINDOW_S,
                force_range_n=FORCE_RANGE_N,
            ),
            Setup(racket=racket, figures=fig.frf_figures),
        )
    both = [rig / "hammer_free.uff", rig / "hammer_hand.uff"]
    step(
        "contact times",
        ["contact", *map(str, both), "--labels", "free,hand", *r, "--out", str(out / "contact")],
        partial(run_contact, both, out / "contact", labels=["free", "hand"]),
        Setup(racket=racket, figures=fig.contact_figures),
    )
    frfs = [free / "frfs.uff", hand / "frfs.uff"]
    step(
        "identification, free against hand-held",
        ["compare", *map(str, frfs), "--band", "40,850", *r, "--out", str(out / "compare")],
        partial(
            run_compare, frfs[0], frfs[1], out / "compare", options=IdentifyOptions(band_hz=BAND_HZ)
        ),
        Setup(racket=racket, figures=fig.compare_figures),
    )
    # --model both adds ≈ 2 s with the compiled transient engine, ≈ 10 s with the scipy
    # reference (measured on the 2-core development machine, default 9 × 9 grid)
    step(
        "prediction with the identified free modes, both models",
        ["predict", *identified, "--model", "both", "--out", str(out / "predict")],
        partial(run_predict, out / "predict", options=PredictOptions(model="both")),
        Setup(racket=racket, modal_model=modal, figures=fig.predict_figures()),
    )
    # the three below add ≈ 1.5 s together (measured on the 2-core development machine)
    swing = ["--model", "approx", "--support", "pinned", "--speed", "20", "--grid", "9"]
    step(
        "swinging racket: outgoing speed and sweet spots",
        ["swing", *identified, *swing, "--out", str(out / "swing")],
        partial(run_swing, out / "swing", model="approx", support="pinned", speeds=[20.0], grid=9),
        Setup(racket=racket, modal_model=modal, figures=fig.swing_figures),
    )
    step(
        "twist against offset, free and hand-held",
        ["twist", *identified, "--support", "free,hand", "--out", str(out / "twist")],
        partial(run_twist, out / "twist", supports=["free", "hand"]),
        Setup(racket=racket, modal_model=modal, figures=fig.twist_figures),
    )
    step(
        "oblique impacts: outgoing angle and spin",
        ["oblique", *identified, "--out", str(out / "oblique")],
        partial(run_oblique, out / "oblique"),
        Setup(racket=racket, modal_model=modal, figures=fig.oblique_figures),
    )
    # the racket's own model, as the section compares its ball mode with the paper's (≈ 3 s)
    step(
        "the ball on the strings",
        ["compound", *r, "--out", str(out / "compound")],
        partial(run_compound, out / "compound"),
        Setup(racket=racket, figures=fig.compound_figures),
    )
    return result


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from rich.progress import Progress

    from racketdyn.report import write_report
    from racketdyn.workflows.inputs import load_racket_input

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    racket, _ = load_racket_input(args.racket)
    chain = steps(out, args.racket)
    with Progress(console=console) as progress:
        task = progress.add_task("demo", total=len(chain) + 1)  # + the report
        for label, _, call in chain:
            progress.update(task, description=label)
            call()
            progress.advance(task)
        progress.update(task, description="report")
        report = write_report(out, racket)
        progress.advance(task)
    _say_unknown_modes(console, out / "compare" / "modal_model_free.json", racket)
    opt.say(console, f"demo complete → {report}")
    return 0


def _say_unknown_modes(console: Console, modal: Path, racket: Racket) -> None:
    """The line ``predict`` prints for the identified model's modes of unknown kind, which the
    demo's predict, swing, twist and oblique take as frame modes (issue 25 item 8: on the
    played bed the built-in racket's membrane veers with its 4-node bending and the shapes
    name neither; the demo said nothing)."""
    from racketdyn.cli.predict import unknown_modes_line
    from racketdyn.modal import ModalModel

    if not modal.is_file():
        return
    line = unknown_modes_line(ModalModel.read_json(modal), racket)
    if line:
        opt.say(
            console, f"the identified free model (predict, swing, twist, oblique): {line}", "yellow"
        )
