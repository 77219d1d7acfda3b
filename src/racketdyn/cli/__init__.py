"""The ``racketdyn`` command line (layer 5): parse, call a workflow, print with rich.

One short module per command (``predict``, ``racket``, ``rig``, ``frf``, ``contact``,
``identify``/``compare``, ``demo``, ``report``, ``sweep``, ``swing``, ``oblique``, ``twist``,
``compound``, ``validate``, ``calibrate``),
the shared options in :mod:`racketdyn.cli.options`, the figure hooks in
:mod:`racketdyn.plotting.steps`.  Building the parser imports neither NumPy nor the library: a
command imports what it needs when it runs, so ``racketdyn --help`` is instant.

Every user error (:class:`~racketdyn.errors.InputError`) becomes one line on stderr and exit
status 2; no traceback.  Ctrl-C becomes one line and exit status 130: a step writes into a
staging folder and moves its files in only when it has finished, so the folder it was writing
is as it was (``sweep`` says more: the designs it kept and the command that resumes).
"""

from __future__ import annotations

import argparse
import logging
import sys
from collections.abc import Sequence
from typing import NoReturn

from racketdyn.__about__ import __version__
from racketdyn.cli import (
    ball,
    calibrate,
    compound,
    contact,
    demo,
    frf,
    identify,
    oblique,
    predict,
    racket,
    report,
    rig,
    sweep,
    swing,
    twist,
    validate,
)
from racketdyn.cli import options as opt

__all__ = ["build_parser", "main"]

COMMANDS = (
    predict,
    frf,
    contact,
    rig,
    identify,
    demo,
    report,
    sweep,
    swing,
    oblique,
    twist,
    compound,
    validate,
    calibrate,
    racket,
    ball,
)
"""The command modules, in the order ``racketdyn --help`` lists them."""


class _Parser(argparse.ArgumentParser):
    """argparse's parser, its errors one line (argparse prints the whole usage block first):
    ``racketdyn predict: error: argument --grid: invalid int value: '2.5'`` and exit 2, as
    every other bad input (``--help`` still shows the usage)."""

    given: Sequence[str] = ()
    """The command line being parsed (for the hint of :func:`_dash_value_hint`)."""

    def error(self, message: str) -> NoReturn:
        if message.endswith("expected one argument"):
            message += _dash_value_hint(message, self.given)
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")

    def unrecognised(self, extras: Sequence[str]) -> NoReturn:
        """Refuse arguments this command does not take, with the option each is nearest to."""
        import difflib

        options = [
            s
            for a in self._actions
            if a.help != argparse.SUPPRESS  # an old name kept working is not suggested
            for s in a.option_strings
            if s.startswith("--")
        ]
        words = []
        for extra in extras:
            name = extra.split("=", 1)[0]
            near = opt.same_concept(name, options) or difflib.get_close_matches(
                name, options, n=1, cutoff=0.6
            )
            hint = f" (did you mean {near[0]}?)" if name.startswith("-") and near else ""
            words.append(f"{extra}{hint}")
        self.error(f"unrecognized arguments: {' '.join(words)}")


def _dash_value_hint(message: str, given: Sequence[str]) -> str:
    """For ``argument --offsets: expected one argument`` where the next word starts with '-'
    (a list of numbers whose first is negative, read as an option): it goes after '='."""
    option = message.removeprefix("argument ").split(":", 1)[0].split("/")[-1].strip()
    words = list(given)
    for i, word in enumerate(words[:-1]):
        if word == option and words[i + 1].startswith("-"):
            return f"; a value that starts with '-' goes after '=': {option}={words[i + 1]}"
    return ""


def build_parser() -> argparse.ArgumentParser:
    """The ``racketdyn`` parser with every subcommand."""
    parser = _Parser(
        prog="racketdyn",
        allow_abbrev=False,  # one spelling per option: a prefix is an unknown option
        description="Tennis racket impact dynamics: rebound ball speed over the string face "
        f"(Kawazoe's approximate method, and a transient simulation of the contact). {opt.UNITS}",
    )
    parser.add_argument("--version", action="version", version=f"racketdyn {__version__}")
    opt.add_verbose(parser)
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for module in COMMANDS:
        module.add(commands)
    return parser


def command_parser(parser: argparse.ArgumentParser, name: str) -> argparse.ArgumentParser:
    """The parser of the command ``name`` among ``parser``'s subcommands."""
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    found: argparse.ArgumentParser = commands.choices[name]
    return found


def parse(argv: Sequence[str] | None) -> argparse.Namespace:
    """Parsed arguments, with the command line as given (``argv``) kept for run records, and
    the command's parser (``args.parser``: its options name the library's parameters in
    errors, :func:`racketdyn.cli.options.in_flags`)."""
    parser = build_parser()
    _Parser.given = list(sys.argv[1:] if argv is None else argv)
    args, extras = parser.parse_known_args(argv)
    command = command_parser(parser, args.command)
    if extras:  # said by the command's parser: its options, its --help
        assert isinstance(command, _Parser)
        command.unrecognised(extras)
    args.argv = list(sys.argv[1:] if argv is None else argv)
    args.parser = command
    return args


class _InFlags(logging.Formatter):
    """The library's log records in the command's words: a parameter it names in backticks
    becomes the command's option (:func:`racketdyn.cli.options.in_flags`), as in its errors."""

    def __init__(self, parser: argparse.ArgumentParser) -> None:
        super().__init__("%(levelname)s %(name)s: %(message)s")
        self.parser = parser

    def format(self, record: logging.LogRecord) -> str:
        return opt.in_flags(super().format(record), self.parser)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``racketdyn`` command.

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments (default: the process's).

    Returns
    -------
    int
        Exit status: 0, 1 (a sweep with failed designs), 2 (bad input), 130 (Ctrl-C).
    """
    args = parse(argv)
    console_log = logging.StreamHandler()
    console_log.setFormatter(_InFlags(args.parser))
    logging.basicConfig(  # no handler added when logging is set up already (a test's)
        level=logging.INFO if args.verbose else logging.ERROR, handlers=[console_log]
    )
    from rich.console import Console

    from racketdyn.errors import InputError

    try:
        return int(args.handler(args, Console()))
    except InputError as error:
        Console(stderr=True, highlight=False, soft_wrap=True).print(
            f"racketdyn: error: {opt.in_flags(str(error), args.parser)}", markup=False
        )
        return 2
    except KeyboardInterrupt:
        out = getattr(args, "out", None)
        where = "" if out is None else f" to {out}"
        Console(stderr=True, highlight=False, soft_wrap=True).print(
            f"racketdyn: interrupted; nothing of the unfinished step was written{where} "
            "(a step's files move in only when it has finished)",
            markup=False,
        )
        return 130


if __name__ == "__main__":
    sys.exit(main())
