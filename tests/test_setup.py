"""Issue 23: one set-up object.

The racket and its modes, the ball, the hand, the string bed, the plausibility override, the
defaults, the command, the figure hook and the progress display travel in one frozen
:class:`~racketdyn.workflows.setup.Setup`, documented there once; every step takes it, and
none repeats its fields in its own signature or docstring.  The CLI builds it in one place,
:func:`racketdyn.cli.options.setup_from_args`.
"""

from __future__ import annotations

import dataclasses
import inspect
import re
from collections.abc import Callable
from typing import Any

import pytest

from racketdyn import workflows
from racketdyn.cli import options as opt
from racketdyn.cli import parse
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

FIELDS = {f.name for f in dataclasses.fields(Setup)}
OLD_NAMES = {"modal"}  # the modal model's name before the set-up object
OWN = {("run_compare", "hand")}
"""A step's own parameter that shares a field's name: compare's hand-held FRF file."""

STEPS: list[Callable[..., Any]] = [
    getattr(workflows, name) for name in workflows.__all__ if name.startswith("run_")
]


def _documented(function: Callable[..., Any]) -> list[str]:
    """The names a numpydoc "Parameters" section documents (``a, b : type`` gives both)."""
    doc = inspect.getdoc(function) or ""
    section = doc.split("Parameters\n----------\n", 1)[-1]
    section = re.split(r"\n\n[A-Z][a-z]+\n-+\n", section, maxsplit=1)[0]
    names = []
    for line in section.splitlines():
        match = re.match(r"^([A-Za-z_][\w, ]*?)(?: : .*)?$", line)
        if match and not line.startswith(" "):
            names += [name.strip() for name in match.group(1).split(",")]
    return names


def test_the_setup_documents_each_field_once() -> None:
    assert dataclasses.is_dataclass(Setup)
    assert Setup.__dataclass_params__.frozen  # type: ignore[attr-defined]
    assert sorted(_documented(Setup)) == sorted(FIELDS)
    with pytest.raises(dataclasses.FrozenInstanceError):
        DEFAULT_SETUP.rigid = True  # type: ignore[misc]


@pytest.mark.parametrize("step", STEPS, ids=lambda step: step.__name__)
def test_every_step_takes_the_setup_and_repeats_none_of_its_fields(
    step: Callable[..., Any],
) -> None:
    parameters = inspect.signature(step).parameters
    assert parameters["setup"].default is DEFAULT_SETUP
    assert parameters["setup"].kind is inspect.Parameter.POSITIONAL_OR_KEYWORD
    own = {name for s, name in OWN if s == step.__name__}
    repeated = (set(parameters) & (FIELDS | OLD_NAMES)) - own
    assert not repeated, f"{step.__name__} takes {sorted(repeated)}: they are Setup's"
    documented = set(_documented(step))
    assert "setup" in documented
    assert not (documented & (FIELDS | OLD_NAMES)) - own, step.__name__


def test_the_cli_builds_the_setup_from_its_options_in_one_place(tmp_path: Any) -> None:
    args = parse(
        [
            "predict",
            "--rigid",
            "--string-bed",
            "local",
            "--allow-implausible",
            "--ball-mass",
            "0.058",
            "--support",
            "hand",
            "--hand-arm-mass",
            "1.5",
            "--no-figures",
            "--out",
            str(tmp_path),
        ]
    )
    setup = opt.setup_from_args(args, ["hand"], figures=print)
    assert setup.rigid
    assert setup.modal_model is None
    assert setup.racket is None
    assert setup.string_bed == "local"
    assert setup.allow_implausible
    assert setup.ball is not None
    assert setup.ball.mass_kg == pytest.approx(0.058)
    assert setup.hand is not None
    assert setup.hand.arm_mass_kg == pytest.approx(1.5)
    assert setup.figures is None  # --no-figures
    assert setup.command is not None
    assert list(setup.command)[:2] == ["racketdyn", "predict"]
    bare = opt.setup_from_args(parse(["frf", "x.uff", "--out", str(tmp_path)]), figures=print)
    assert bare.figures is print
    assert (bare.ball, bare.hand, bare.rigid) == (None, None, False)
