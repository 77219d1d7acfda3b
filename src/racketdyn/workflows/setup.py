"""The set-up every step shares: the racket and its modes, the ball, the hand, the string bed,
the plausibility override, and how the caller runs the step (command, figures, progress).

One frozen object, documented once, with the glossary's names (docs/develop.md): a step
function takes ``setup: Setup`` and its own parameters only; the CLI builds the object from
its options in one place (:func:`racketdyn.cli.options.setup_from_args`).

Examples
--------
>>> from racketdyn.workflows.setup import Setup
>>> Setup(rigid=True, string_bed="local").rigid
True
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, TypeVar

from racketdyn.ball import Ball
from racketdyn.impact.grid import StringBed
from racketdyn.impact.hand import Hand
from racketdyn.modal import ModalModel
from racketdyn.workflows.inputs import (
    RacketInput,
    RacketSetup,
    ball_or_default,
    hand_or_default,
    setup,
)
from racketdyn.workflows.run import Progress, StepResult, command_record, finish_run

__all__ = ["DEFAULT_SETUP", "FigureHook", "Setup"]

R = TypeVar("R", bound=StepResult)

FigureHook = Callable[[Any, Path], list[Path]]
"""``figures(result, out) -> paths``: draws a step's figures into its run folder."""


@dataclass(frozen=True)
class Setup:
    """What every step shares: racket, modes, ball, hand, string bed, checks, and the run.

    Every field has its default; a step uses the fields it needs and ignores the others (a
    ``hand`` without the ``hand`` support, a ``ball`` in ``frf``).

    Parameters
    ----------
    racket : Racket, path or None
        Racket object, TOML file, or None for the built-in racket.
    modal_model : ModalModel or path, optional
        Modal model, or its JSON file (e.g. from identify), replacing the racket's modes.
    rigid : bool
        No vibration: a rigid racket (no modes); excludes ``modal_model``.
    ball : Ball, optional
        The ball (default :class:`~racketdyn.ball.Ball`, its defaults said in run.json).
    hand : Hand, optional
        The hand of the ``hand`` support (default :class:`~racketdyn.impact.hand.Hand`);
        unused without that support.
    string_bed : {"uniform", "local"}
        The string bed's law over the face: the face centre's at every point (the paper's,
        default) or each point's own from its strings' lengths
        (:func:`racketdyn.impact.grid.predict_by_point_law`).
    allow_implausible : bool
        Let values beyond those of play through (speeds, ball mass, arm:
        :mod:`racketdyn.plausibility`); a value in the wrong unit is refused still.
    defaults : sequence of str
        Defaults the caller filled in (the ball's, the hand's), added to run.json's
        ``defaults_used``.
    command : sequence of str, optional
        The command as called, for run.json (default: the step function's name).
    figures : callable, optional
        ``figures(result, out) -> paths`` (none without it).
    progress : callable, optional
        ``progress(what, done, total)`` for a progress display.
    words : callable, optional
        ``words(text) -> text``: run.json's texts (a hint, a note) in the caller's words.  The
        library names its parameters in backticks (`` `force_window_s` ``); the command line
        gives its own translation (:func:`racketdyn.cli.options.in_flags` with the command's
        parser: ``--force-window``), as it does for the errors and log lines it prints, so the
        report shows the command's words (default: the library's).
    """

    racket: RacketInput = None
    modal_model: ModalModel | str | os.PathLike[str] | None = None
    rigid: bool = False
    ball: Ball | None = None
    hand: Hand | None = None
    string_bed: StringBed = "uniform"
    allow_implausible: bool = False
    defaults: Sequence[str] = ()
    command: Sequence[str] | None = None
    figures: FigureHook | None = None
    progress: Progress | None = None
    words: Callable[[str], str] | None = None

    def replace(self, **changes: Any) -> Setup:
        """A copy with ``changes`` (field names as keywords)."""
        return replace(self, **changes)

    def racket_setup(self, *, with_modes: bool = True) -> RacketSetup:
        """The racket loaded, with its modes (:func:`racketdyn.workflows.inputs.setup`).

        Parameters
        ----------
        with_modes : bool
            Build the modal model (False: steps that only need the racket's geometry).
        """
        return setup(
            self.racket,
            self.modal_model,
            self.rigid,
            with_modes=with_modes,
            allow_implausible=self.allow_implausible,
        )

    def ball_used(self) -> tuple[Ball, list[str]]:
        """``ball``, or the default ball with the defaults it fills in."""
        return ball_or_default(self.ball)

    def hand_used(self, supports: Sequence[str]) -> tuple[Hand | None, list[str]]:
        """``hand`` for the ``hand`` support (default :class:`Hand`), None without it, with
        the defaults it fills in.

        Parameters
        ----------
        supports : sequence of str
            The supports of the step.
        """
        return hand_or_default(supports, self.hand)

    def finish(self, result: R, inputs: dict[str, Any], step: str) -> R:
        """Draw the figures and write run.json (:func:`racketdyn.workflows.run.finish_run`).

        Parameters
        ----------
        result : StepResult
            The step's result.
        inputs : dict
            run.json's inputs.
        step : str
            The step's name, for a Python call's command record.
        """
        if self.words is not None:
            inputs = _in_words(inputs, self.words)
        return finish_run(result, inputs, command_record(self.command, step), self.figures)


def _in_words(value: Any, words: Callable[[str], str]) -> Any:
    """``value`` (run.json's inputs: tables, lists, texts) with every text that names a
    parameter in backticks put in ``words``."""
    if isinstance(value, dict):
        return {key: _in_words(item, words) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_in_words(item, words) for item in value]
    return words(value) if isinstance(value, str) and "`" in value else value


DEFAULT_SETUP = Setup()
"""The built-in racket and its modes, the default ball and hand, nothing allowed beyond play."""
