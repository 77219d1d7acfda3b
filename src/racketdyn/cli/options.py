"""Options shared by the commands: one name, one meaning, one help text each.

Every command that takes a racket takes ``--racket FILE``; ball speeds are ``--speed`` (m/s),
supports ``--support``, the grid ``--grid``, the output folder ``--out``, verbosity ``-v``.
Help texts state the unit and the default.  Nothing here imports NumPy: ``racketdyn --help``
stays fast.  The copies of the library's constants below are checked against it by the tests.
"""

from __future__ import annotations

import argparse
import functools
import logging
import math
import re
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

# counts in words, re-exported for the commands (opt.plural, opt.noun)
from racketdyn._grammar import noun as noun
from racketdyn._grammar import plural as plural

if TYPE_CHECKING:
    from rich.console import Console

    from racketdyn.workflows.run import Progress

# Copies of library constants, kept here so that building the parser imports no NumPy
# (tests/test_cli_options.py checks each against the library).
SUPPORTS = ("free", "pinned")  # racketdyn.racket.SUPPORTS
TRANSIENT_SUPPORTS = ("free", "pinned", "hand")  # racketdyn.impact.transient.TRANSIENT_SUPPORTS
ENGINES = ("auto", "compiled", "reference")  # racketdyn.impact.transient.ENGINES
MODELS = ("approx", "transient", "both")  # racketdyn.workflows.predict.MODELS
IMPACT_MODELS = ("approx", "transient")  # racketdyn.workflows.swing.IMPACT_MODELS
STRING_BEDS = ("uniform", "local")  # racketdyn.impact.grid.STRING_BEDS
DEFAULT_GRID = 9  # racketdyn.workflows.predict.DEFAULT_GRID
SWING_GRID = 15  # racketdyn.workflows.swing.SWING_GRID
MAX_GRID = 400  # racketdyn.workflows.predict.MAX_GRID
UNITS = "SI units throughout: m/s, m, kg, N, Hz, s (degrees where named)."

Handler = Callable[[argparse.Namespace, "Console"], int]


def command(
    commands: Any, name: str, help_text: str, description: str | None = None
) -> argparse.ArgumentParser:
    """A subcommand with ``-v``; the description ends with the units note."""
    parser: argparse.ArgumentParser = commands.add_parser(
        name,
        allow_abbrev=False,  # one spelling per option: --angle is no --angles
        help=help_text,
        description=f"{description or help_text[0].upper() + help_text[1:]}. {UNITS}",
    )
    add_verbose(parser, subcommand=True)
    return parser


def parser_of(module: Any, name: str) -> argparse.ArgumentParser:
    """The parser of the command ``name`` that ``module`` (a command module: its ``add``)
    registers, built alone: a command's options without the whole ``racketdyn`` parser (the
    demo's steps name their notes in each command's words, :func:`in_flags`)."""
    commands = argparse.ArgumentParser(allow_abbrev=False).add_subparsers()
    module.add(commands)
    found: argparse.ArgumentParser = commands.choices[name]
    return found


def add_verbose(parser: argparse.ArgumentParser, subcommand: bool = False) -> None:
    """``-v/--verbose``: log each step's stages (before or after the command name)."""
    parser.add_argument(
        "-v",
        "--verbose",
        action="store_true",
        # a subcommand's default would overwrite ``racketdyn -v predict``: leave it unset
        default=argparse.SUPPRESS if subcommand else False,
        help="log each stage of the step (default: errors only)",
    )


def add_racket(parser: argparse.ArgumentParser, what: str = "") -> None:
    """``--racket FILE``."""
    parser.add_argument(
        "--racket",
        metavar="FILE",
        help=f"racket TOML file{what} (default: the built-in paper racket, kawazoe_2002.toml)",
    )


def add_modes(parser: argparse.ArgumentParser) -> None:
    """``--modal FILE`` and ``--rigid``."""
    parser.add_argument(
        "--modal",
        metavar="FILE",
        help="modal model (racketdyn JSON, e.g. from identify) to use (default: the racket's "
        "own, else the built-in beam model)",
    )
    parser.add_argument(
        "--rigid", action="store_true", help="no vibration: a rigid racket (default: off)"
    )


def add_ball(parser: argparse.ArgumentParser) -> None:
    """``--ball-mass``, ``--e-bg``, ``--e-bg-table``, ``--ball-law``."""
    parser.add_argument(
        "--ball-mass", type=float, metavar="KG", help="ball mass, kg (default 0.0577, ITF middle)"
    )
    parser.add_argument(
        "--e-bg",
        type=float,
        metavar="COR",
        help="ball-string COR on a head-clamped racket, dimensionless (default: from the ball "
        "and the strings at each speed, ≈ 0.84 to 0.82 over 4-40 m/s on the paper's racket; "
        "see racketdyn ball)",
    )
    parser.add_argument(
        "--e-bg-table",
        metavar="CSV",
        help="e_BG against relative speed: CSV with columns speed_mps, e_bg, interpolated "
        "linearly (default: from the ball and the strings)",
    )
    parser.add_argument(
        "--ball-law",
        metavar="CSV",
        help="ball load-deflection CSV (deflection_m, force_n), one side, measured in a bounce "
        "(default: the ball's bounce, 6 mm at 7.06 m/s on a rigid surface, + adiabatic gas)",
    )


HAND_OPTIONS = ("hand_arm_mass", "hand_stiffness", "hand_damping")
"""The hand's options (argparse names), for --support hand only."""


def add_hand(parser: argparse.ArgumentParser) -> None:
    """``--hand-arm-mass``, ``--hand-stiffness``, ``--hand-damping``."""
    parser.add_argument(
        "--hand-arm-mass",
        type=float,
        metavar="KG",
        help="mass of the arm holding the grip, kg, for --support hand (default 1.0)",
    )
    parser.add_argument(
        "--hand-stiffness",
        type=float,
        metavar="N/M",
        help="total stiffness of the palm and fingers between handle and arm, N/m, for --support "
        "hand (default 20000; hand-arm data 10000-100000 N/m)",
    )
    parser.add_argument(
        "--hand-damping",
        type=float,
        metavar="N·S/M",
        help="total damping of the palm and fingers between handle and arm, N·s/m, for "
        "--support hand (default 12; hand-arm data 10-100 N·s/m)",
    )


def add_string_bed(parser: argparse.ArgumentParser) -> None:
    """``--string-bed uniform|local``."""
    parser.add_argument(
        "--string-bed",
        choices=STRING_BEDS,
        default="uniform",
        help="the string bed's law over the face: uniform, the face centre's law at every point "
        "(the paper's method, default); local, each point's own from the lengths of the main and "
        "cross strings through it (stiffer towards the frame; a law fitted per point)",
    )


def add_uncertainty(
    parser: argparse.ArgumentParser,
    sampled: bool = True,
    workers: bool = True,
    tables: str = "the racket file",
) -> None:
    """``--uncertainty FILE``, ``--samples N``, ``--seed N``: inputs with their spread
    (``sampled`` False: the file alone, whose ranges bound a calibration; ``workers`` False:
    no ``--workers`` for the samples, a command whose ``--workers`` is its own; ``tables``:
    the file whose ``[uncertainty]`` tables are the default)."""
    if not sampled:
        parser.add_argument(
            "--uncertainty",
            metavar="TOML|literature|none",
            help="an uncertainty file (docs/uncertainty.md) or 'literature': the ranges (and the "
            "span of equally likely values) of the fitted parameters bound the fit; 'none': "
            "each parameter's own bounds (default: the racket file's [uncertainty] tables, else "
            "each parameter's own bounds)",
        )
        return
    parser.add_argument(
        "--uncertainty",
        metavar="TOML|literature|none",
        help="uncertain inputs, one table each (e_bg, first_bending_hz, ball_stiffness_scale, "
        "location_m, ball_speed_mps, ...: sd = x, range = [low, high] or values = [...]; "
        "docs/uncertainty.md), or 'literature' for the spreads the literature gives e_BG, the "
        "ball, the bed, the frame frequency and a ball cannon; each model runs once per sample "
        "and every number gets its mean, sd and 5-95 %% band; 'none' for no band, whatever "
        f"{tables} holds (default: {tables}'s [uncertainty] tables, else none)",
    )
    parser.add_argument(
        "--samples",
        type=int,
        default=256,
        help="quasi-Monte Carlo samples of --uncertainty, a count (scrambled Sobol'; default 256)",
    )
    parser.add_argument(
        "--seed",
        type=int,
        default=0,
        help="seed of the samples, a count (default 0: the same samples every run)",
    )
    if not workers:
        return
    parser.add_argument(
        "--workers",
        type=int,
        metavar="N",
        help="run the samples of --uncertainty that a model runs one by one (the transient "
        "model's, a swing's, measured rows') on a local pool of N processes, a count "
        "(default: this process)",
    )


def uncertainty_from(args: argparse.Namespace) -> Any:
    """The :class:`~racketdyn.impact.uncertainty.Uncertainty` of the options, or None."""
    from racketdyn.errors import InputError
    from racketdyn.impact.uncertainty import Spread, Uncertainty
    from racketdyn.io.uncertainty_file import (
        LITERATURE,
        NONE,
        literature_for_racket,
        racket_spreads,
        read_spreads,
    )

    spreads: tuple[Spread, ...] = ()  # --uncertainty none: no band, whatever the racket file
    if args.uncertainty == LITERATURE:
        spreads = literature_for_racket(args.racket, bool(getattr(args, "modal", None)))
    elif args.uncertainty not in (None, NONE):
        spreads = read_spreads(args.uncertainty)
    elif args.uncertainty is None:
        spreads = racket_spreads(args.racket) if getattr(args, "racket", None) else ()
        if spreads:
            logging.getLogger(__name__).info("uncertainty: the racket file's [uncertainty]")
    if not spreads:
        for name, default in (("samples", 256), ("seed", 0)):
            if getattr(args, name, default) != default:
                given = (
                    "with --uncertainty none nothing is sampled"
                    if args.uncertainty == NONE
                    else "give an uncertainty file (or a racket file with [uncertainty] tables)"
                )
                raise InputError(f"--{name} is for --uncertainty: {given}")
        return None
    return Uncertainty(
        spreads, samples=getattr(args, "samples", 256), seed=getattr(args, "seed", 0)
    )


def add_allow_implausible(parser: argparse.ArgumentParser, what: str | None = None) -> None:
    """``--allow-implausible``: go on with an unusual ball, speed or arm (see plausibility);
    ``what`` replaces the list of options it applies to (frf: the hammer's range)."""
    parser.add_argument(
        "--allow-implausible",
        action="store_true",
        help=(
            "take a --ball-mass, --speed, --racket-speed or --hand-arm-mass outside the ranges "
            "of play (ball 56.0-59.4 g, ITF; ball speeds up to 75 m/s, racket 55 m/s; arm "
            "0.2-6 kg)"
            if what is None
            else f"take {what}"
        )
        + " for an object meant to be unusual; a value in the wrong unit (57.7 for kg) is "
        "refused still; a racket file allows itself with [checks] allow_implausible = true "
        "(default: off)",
    )


def add_racket_and_ball(parser: argparse.ArgumentParser) -> None:
    """The racket, its modes, the ball and the hand: the same options for every impact step."""
    add_racket(parser)
    add_modes(parser)
    add_ball(parser)
    add_hand(parser)
    add_allow_implausible(parser)


def add_speed(parser: argparse.ArgumentParser, default: str, many: bool = True) -> None:
    """``--speed``: incoming ball speed(s), m/s."""
    if many:
        parser.add_argument(
            "--speed",
            default=default,
            metavar="M/S[,M/S...]",
            help=f"incoming ball speeds, m/s, comma-separated (default {default}; above 75 "
            "m/s only with --allow-implausible; the contact model holds to 70 m/s of ball + "
            "racket speed)",
        )
    else:  # one type for one option: text, read by `one_number` (issue 23)
        parser.add_argument(
            "--speed",
            default=default,
            metavar="M/S",
            help=f"incoming ball speed, m/s (default {default}; above 75 m/s only with "
            "--allow-implausible; the contact model holds to 70 m/s of ball + racket speed)",
        )


def add_racket_speed(parser: argparse.ArgumentParser, many: bool = True) -> None:
    """``--racket-speed``: the racket's speed towards the ball, m/s — one per ball speed
    (``many``) or one; text either way (read by :func:`parse_speeds` or :func:`one_number`)."""
    parser.add_argument(
        "--racket-speed",
        default="0",
        metavar="M/S[,M/S...]" if many else "M/S",
        help=(
            "racket speed at the impact point towards the ball, m/s: one, or one per speed"
            if many
            else "racket speed towards the ball, m/s"
        )
        + " (default 0; above 55 m/s only with --allow-implausible; the contact model holds "
        "to 70 m/s of ball + racket speed)",
    )


def add_support(parser: argparse.ArgumentParser, default: str, text: str, **kw: Any) -> None:
    """``--support``."""
    if "choices" not in kw:
        kw.setdefault("metavar", "SUPPORT")
    parser.add_argument("--support", default=default, help=f"{text} (default {default})", **kw)


def add_grid(parser: argparse.ArgumentParser, default: int) -> None:
    """``--grid N``."""
    parser.add_argument(
        "--grid",
        type=int,
        metavar="N",
        help=f"N x N grid of points over the head, a count from 1 to {MAX_GRID} "
        f"(default {default})",
    )


def add_out(parser: argparse.ArgumentParser, text: str = "") -> None:
    """``--out DIR`` (required)."""
    parser.add_argument(
        "--out",
        required=True,
        metavar="DIR",
        help=f"output folder (created if missing){text}; required",
    )


def add_no_figures(parser: argparse.ArgumentParser, what: str = "the CSV files") -> None:
    """``--no-figures``."""
    parser.add_argument(
        "--no-figures",
        action="store_true",
        help=f"write {what} and run.json only (default: draw the figures too)",
    )


def start_figure_helper(args: argparse.Namespace) -> None:
    """Start the figure helper process now, unless ``--no-figures``: for a command that draws
    several figures, so that the helper imports matplotlib while the step computes
    (:func:`racketdyn.plotting.helper.start_helper`; matplotlib is not imported here)."""
    if not getattr(args, "no_figures", False):
        from racketdyn.plotting.helper import start_helper

        start_helper()


# --- parsing ----------------------------------------------------------------------------------
PARAMETER_OPTIONS: dict[str, str] = {
    "modal_model": "modal",  # workflows.setup.Setup
    "speeds": "speed",
    "supports": "support",
    "mass_kg": "ball_mass",  # workflows.inputs.ball_from
    "arm_mass_kg": "hand_arm_mass",  # workflows.inputs.hand_for
    "stiffness_n_per_m": "hand_stiffness",
    "damping_ns_per_m": "hand_damping",
    "axis_to_butt_m": "axis_to_butt",  # workflows.swing.swing_from
    "angular_speed_radps": "angular_speed",
    "torque_nm": "torque",
    "x_m": "x",  # run_twist
    "offsets_m": "offsets",
    "angles_deg": "angles",  # run_oblique
    "spin_radps": "spin",
    "method": "model",  # run_calibrate
    "force_range_n": "force_range",  # run_frf
    "force_window_s": "force_window",
    "exponential_window_s": "exp_window",
    "band_hz": "band",  # run_identify, run_compare; modal.identify's dropped modes
    "pin_hz": "pin",
    "exclude_hz": "exclude",
    "force_snr_db": "force_snr",  # run_rig
    "response_snr_db": "response_snr",
    "pretrigger_s": "pretrigger",
    "response_direction": "accelerometer_direction",
}
"""The library's parameter names whose option has another name (``run_predict(speeds=)`` is
``--speed``); every other parameter is its option's ``dest`` (``racket_speed`` →
``--racket-speed``)."""


SAME_CONCEPT: tuple[tuple[str, ...], ...] = (
    # where on the face: oblique's impact point, predict's CSV of points, a ball fixed on the
    # strings (rig, identify, compare, compound), twist's point on the long axis
    ("--point", "--points", "--ball-at", "--x"),
    ("--speed", "--ball-speed"),  # the ball's speed; --ball-speed in swing, oblique, twist before
)
"""Options that name one concept in different commands, each group in the order to suggest:
an unknown option of a group is told the first other one the command has (the new-user
trial of 2026-11-27: ``compound --ball-at`` was told "did you mean --ball-law?")."""


def same_concept(name: str, options: Sequence[str]) -> list[str]:
    """The command's option (of ``options``) for the concept another command calls ``name``
    (:data:`SAME_CONCEPT`), as a list of one, or an empty list."""
    for group in SAME_CONCEPT:
        if name in group:
            return [other for other in group if other != name and other in options][:1]
    return []


LIBRARY_READERS: dict[str, str] = {
    "read it with `read_hammer_uff`": "run racketdyn frf on it first (it makes the FRFs from "
    "the time records)",
    "read it with `read_frf_uff`": "it holds FRFs already: give it to racketdyn identify",
    "as `write_modes_uff` writes it": "as racketdyn identify and compare write it (modes*.uff)",
}
"""The library's pointers to its readers (:func:`racketdyn.io.uff` names the function in
backticks), in the command line's words: the command that reads such a file."""


def in_flags(message: str, parser: argparse.ArgumentParser) -> str:
    """An error raised below the CLI, in the command's words: each parameter the library names
    in backticks (`` `speeds` ``, its convention: docs/develop.md, "Errors name parameters")
    becomes the command's option (``--speed``); a name no option has loses its backticks; a
    pointer to a Python reader becomes the command that reads the file
    (:data:`LIBRARY_READERS`).

    Parameters
    ----------
    message : str
        The library's message.
    parser : ArgumentParser
        The command's parser.
    """
    flags = {
        action.dest: action.option_strings[-1]
        for action in parser._actions
        if action.option_strings and action.option_strings[-1].startswith("--")
    }

    def flag(match: re.Match[str]) -> str:
        name = match.group(1)
        return flags.get(PARAMETER_OPTIONS.get(name, name), name)

    for words, command in LIBRARY_READERS.items():
        message = message.replace(words, command)
    return re.sub(r"`([A-Za-z_][A-Za-z0-9_]*)`", flag, message)


def parse_list(name: str, text: str) -> list[str]:
    """Items of a comma-separated list, none empty (:func:`racketdyn.errors.require_words`)."""
    from racketdyn.errors import require_words

    return require_words(name, text)


def parse_speeds(name: str, text: str) -> list[float]:
    """Speeds (m/s, ≥ 0) from a comma-separated list."""
    from racketdyn.errors import InputError, require_speeds

    speeds = []
    for item in parse_list(name, text):
        try:
            speeds.append(float(item))
        except ValueError:
            raise InputError(
                f"{name}: {item!r} is not a number; give speeds in m/s, e.g. 10,20,30"
            ) from None
    return [float(v) for v in require_speeds(name, speeds)]


def parse_frequencies(name: str, text: str) -> list[float]:
    """Frequencies (Hz, finite, ≥ 0) from a comma-separated list (``--band``, ``--pin``)."""
    from racketdyn.errors import InputError

    values = parse_numbers(name, text, "Hz")
    if any(v < 0 for v in values):
        given = ", ".join(f"{v:g}" for v in values)
        raise InputError(f"{name} must be frequencies of zero or more, Hz (got {given})")
    return values


def parse_numbers(name: str, text: str, unit: str) -> list[float]:
    """Finite numbers (any sign) from a comma-separated list
    (:func:`racketdyn.errors.require_numbers`)."""
    from racketdyn.errors import require_numbers

    return require_numbers(name, text, unit)


def one_number(name: str, text: str, unit: str = "m/s") -> float:
    """One finite number (any sign) from an option's text."""
    from racketdyn.errors import InputError

    values = parse_numbers(name, text, unit)
    if len(values) != 1:
        raise InputError(f"{name} takes one value in {unit} (got {text!r})")
    return values[0]


def parse_point(name: str, text: str | None) -> tuple[float, float] | None:
    """One point ``x,y`` in m (None stays None: the command's default point)."""
    from racketdyn.errors import InputError

    if text is None:
        return None
    values = parse_numbers(name, text, "x,y in m")
    if len(values) != 2:
        raise InputError(f"{name} takes x,y in m, e.g. 0.505,0 (got {text!r})")
    return values[0], values[1]


def ball_and_hand(args: argparse.Namespace, supports: Sequence[str]) -> tuple[Any, Any, list[str]]:
    """The ball and the hand from the options, with the defaults used."""
    from racketdyn.errors import InputError
    from racketdyn.workflows.inputs import ball_from, hand_for

    given = [name for name in HAND_OPTIONS if getattr(args, name, None) is not None]
    if "hand" not in supports and given:
        options = ", ".join("--" + name.replace("_", "-") for name in given)
        raise InputError(f"{options}: for --support hand (with --model transient) only")
    allow = bool(getattr(args, "allow_implausible", False))
    ball, ball_defaults = ball_from(
        args.ball_mass,
        args.e_bg,
        args.ball_law,
        allow_implausible=allow,
        e_bg_table=getattr(args, "e_bg_table", None),
    )
    hand, hand_defaults = hand_for(
        supports,
        getattr(args, "hand_arm_mass", None),
        allow_implausible=allow,
        stiffness_n_per_m=getattr(args, "hand_stiffness", None),
        damping_ns_per_m=getattr(args, "hand_damping", None),
    )
    return ball, hand, [*ball_defaults, *hand_defaults]


def setup_from_args(
    args: argparse.Namespace,
    supports: Sequence[str] = (),
    *,
    figures: Any = None,
    progress: Progress | None = None,
    defaults: Sequence[str] = (),
) -> Any:
    """The :class:`~racketdyn.workflows.setup.Setup` of a command's options: the one place
    where options become the set-up's fields (``--modal`` → ``modal_model``, ``--ball-mass``,
    ``--e-bg``, ``--e-bg-table``, ``--ball-law`` → ``ball``, the hand's options → ``hand``,
    ``--no-figures`` → no ``figures``; ``words``: the command's flags for the library's parameter
    names in run.json, :func:`in_flags`).  An option the command lacks leaves its field's default.

    Parameters
    ----------
    args : Namespace
        The parsed options.
    supports : sequence of str
        The command's supports (the hand is built for ``hand`` only).
    figures : callable, optional
        The command's figure hook, dropped with ``--no-figures``.
    progress : callable, optional
        The progress display.
    defaults : sequence of str
        Defaults the command filled in itself, said in run.json before the ball's and hand's.
    """
    from racketdyn.workflows.setup import Setup

    fields: dict[str, Any] = {"defaults": tuple(defaults)}
    if hasattr(args, "modal"):
        check_modes(args)
        fields.update(modal_model=args.modal, rigid=args.rigid)
    if hasattr(args, "ball_mass"):
        ball, hand, ball_defaults = ball_and_hand(args, supports)
        fields.update(ball=ball, hand=hand, defaults=(*defaults, *ball_defaults))
    for name in ("racket", "string_bed", "allow_implausible"):
        if hasattr(args, name):
            fields[name] = getattr(args, name)
    parser = getattr(args, "parser", None)  # set by `racketdyn.cli.parse`
    return Setup(
        **fields,
        command=tuple(command_line(args)),
        figures=None if getattr(args, "no_figures", False) else figures,
        progress=progress,
        words=None if parser is None else functools.partial(in_flags, parser=parser),
    )


def check_modes(args: argparse.Namespace) -> None:
    """``--modal`` and ``--rigid`` exclude each other."""
    from racketdyn.errors import InputError

    if args.modal is not None and args.rigid:
        raise InputError("give --modal or --rigid, not both")


def command_line(args: argparse.Namespace) -> list[str]:
    """The command as called, for run.json."""
    return ["racketdyn", *args.argv]


# --- output -----------------------------------------------------------------------------------
# rich reads "[word]" in a printed string as a style and drops it, and raises on "[/word]" with
# nothing open.  Paths, names and messages are data: they go through `say` (a whole line, no
# markup read), `plain` (a table title or cell) or `rich.markup.escape` (a line that also styles
# a part of itself on purpose).


def say(console: Console, line: str, style: str | None = None, **kwargs: Any) -> None:
    """Print ``line`` as it is, in ``style`` (a rich style name such as ``"yellow"``).

    No markup is read in it: a path, a racket name or a message quoting ``[impacts]`` is
    printed whole.  ``kwargs`` go to :meth:`rich.console.Console.print` (``soft_wrap``).
    """
    console.print(line, style=style, markup=False, **kwargs)


def plain(text: object) -> str:
    """``text`` for a table's title or cell, shown as it is: its markup escaped, so the table's
    own styles (the title's) still apply."""
    from rich.markup import escape

    return escape(str(text))


@contextmanager
def progress_display(
    console: Console, *, thread: bool = True, lines: bool = False
) -> Iterator[Progress]:
    """A ``progress(what, done, total)`` callback drawing one rich progress line (a spinner
    for ``total == 0``); the line goes when the step ends.

    ``thread=False``: no refresh thread — the line is drawn at each update only (the spinner
    does not turn between them).  For a step that forks worker processes, which is safe only
    while this process runs a single thread (``racketdyn.sweep.executors``).

    ``lines=True``: on a console that is not a terminal (a log, a pipe), where the line is
    never drawn, each stage is printed as a line, at most one every
    :data:`PROGRESS_LINE_S` seconds (a long step, issue 27: calibrate ran 29 s without one).
    """
    if not console.is_terminal:  # the line is never drawn; ending it printed an empty line
        yield _progress_lines(console) if lines else _no_progress
        return
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, SpinnerColumn, TextColumn

    with Progress(
        SpinnerColumn(),
        TextColumn("{task.description}", markup=False),
        BarColumn(),
        MofNCompleteColumn(),
        console=console,
        transient=True,
        auto_refresh=thread,
    ) as bar:
        task = bar.add_task("", total=None)

        def update(what: str, done: int, total: int) -> None:
            bar.update(
                task, description=what, completed=done, total=total or None, refresh=not thread
            )

        yield update


def _no_progress(what: str, done: int, total: int) -> None:
    """The progress of a step on a console that is not a terminal, without ``lines``."""


PROGRESS_LINE_S = 5.0
"""Seconds between progress lines on a console that is not a terminal."""


def _progress_lines(console: Console) -> Progress:
    """``progress(what, done, total)`` printing a line per stage (the first words of ``what``
    before a colon), and at most one every :data:`PROGRESS_LINE_S` seconds within one."""
    import time

    last_stage, last_at = "", -math.inf

    def update(what: str, done: int, total: int) -> None:
        nonlocal last_stage, last_at
        stage = what.split(":", 1)[0]
        now = time.monotonic()
        if stage == last_stage and now - last_at < PROGRESS_LINE_S:
            return
        last_stage, last_at = stage, now
        say(console, what)

    return update


def print_written(console: Console, paths: Sequence[Any]) -> None:
    """``wrote PATH`` per file, and a line when a report one folder up now tells an old run.

    A step re-run inside a report's folder (``predict --out demo/predict`` after ``demo``)
    leaves ``demo/report.html`` showing the step's previous run until the report is made
    again; the report is the user's, so it is named, not removed.
    """
    from pathlib import Path

    from racketdyn.workflows.run import REPORT_NAME

    for path in paths:
        say(console, f"  wrote {path}")
    if not paths:
        return
    step = Path(paths[0]).parent
    above = step.parent
    report = above / REPORT_NAME
    if report.is_file() and report.stat().st_mtime <= Path(paths[0]).stat().st_mtime:
        shown, given = _report_steps(report)
        if shown is not None and step.name not in shown:
            return  # a folder the page never showed
        again = f"racketdyn report {above}" + (f" --steps {given}" if given else "")
        say(
            console,
            f"{report} still shows this step's previous run: {again} makes it again",
            "yellow",
            soft_wrap=True,
        )


def _report_steps(report: Any) -> tuple[list[str] | None, str]:
    """The step folders a report page shows (None: a page that does not say, made before it
    did) and the ``--steps`` it was made with, from its ``racketdyn-steps`` meta lines."""
    import re

    with report.open(encoding="utf-8", errors="replace") as page:
        head = page.read(4000)  # the meta lines, not the ≈ 2 MB of figures
    shown = re.search(r'<meta name="racketdyn-steps" content="([^"]*)">', head)
    given = re.search(r'<meta name="racketdyn-steps-given" content="([^"]*)">', head)
    folders = None if shown is None else [s for s in shown.group(1).split(",") if s]
    return folders, "" if given is None else given.group(1)


def print_status(console: Console, status: Any, csv_name: str, label: str = "") -> None:
    """How many impacts failed, by reason (their rows are NaN)."""
    import numpy as np

    bad = status != "ok"
    if np.any(bad):
        reasons, counts = np.unique(status[bad], return_counts=True)
        for reason, count in zip(reasons, counts, strict=True):
            prefix = f"{label}: " if label else ""
            say(
                console, f"{prefix}{plural(count, 'impact')}: {reason}; NaN in {csv_name}", "yellow"
            )
