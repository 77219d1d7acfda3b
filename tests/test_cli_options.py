"""The command line's shape: every option documented with its unit and default, one name per
shared option, the CLI's copies of library constants true, and a light import."""

from __future__ import annotations

import argparse
import re
import subprocess
import sys

import pytest

from racketdyn.cli import build_parser, main
from racketdyn.cli import options as opt

# Options whose value is text holding numbers (comma-separated lists, pairs)
NUMBER_LISTS = {"speed", "racket_speed", "offsets", "angles", "point", "band", "pin", "exclude"}
UNIT = re.compile(
    r"(?:^|[\s,(])(m/s|rad/s|m|kg|N·m|N·s/m|N/m|N|Hz|s|degrees|dB)(?=[\s,;:)]|$)"
    r"|dimensionless|a count"
)
# What every command taking these spells the same way
SHARED = {
    "racket": "--racket",
    "speed": "--speed",
    "support": "--support",
    "grid": "--grid",
    "out": "--out",
    "verbose": "-v",
}


def _subparsers() -> dict[str, argparse.ArgumentParser]:
    parser = build_parser()
    (commands,) = (a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(commands.choices)


def _options() -> list[tuple[str, argparse.Action]]:
    return [
        (name, action)
        for name, sub in _subparsers().items()
        for action in sub._actions
        if not isinstance(action, argparse._HelpAction)
    ]


@pytest.mark.parametrize(
    ("command", "action"),
    _options(),
    ids=[f"{c}:{a.dest}" for c, a in _options()],
)
def test_every_option_has_help_with_unit_and_default(command: str, action: argparse.Action) -> None:
    text = action.help or ""
    if text == argparse.SUPPRESS:  # an old name kept working, not shown (compound --point)
        return
    assert text.strip(), f"racketdyn {command} {action.dest}: no help text"
    numeric = action.type in (int, float) or action.dest in NUMBER_LISTS
    if numeric:
        assert UNIT.search(text), f"racketdyn {command} {action.dest}: no unit in {text!r}"
    if action.option_strings and not action.required and action.dest != "verbose":
        assert "default" in text, f"racketdyn {command} {action.dest}: no default in {text!r}"


def test_shared_options_have_one_spelling_everywhere() -> None:
    for command, sub in _subparsers().items():
        for action in sub._actions:
            if action.dest in SHARED:
                assert SHARED[action.dest] in action.option_strings, (command, action.dest)
        dests = {a.dest for a in sub._actions}
        assert "verbose" in dests, command
        assert "ball_speed" not in dests, command  # --speed everywhere


def test_help_says_the_units_are_si(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["--help"])
    assert "SI units" in " ".join(capsys.readouterr().out.split())
    for command in ("predict", "swing", "rig"):
        with pytest.raises(SystemExit):
            main([command, "--help"])
        assert "SI units" in " ".join(capsys.readouterr().out.split())


def test_verbose_before_or_after_the_command() -> None:
    parser = build_parser()
    assert parser.parse_args(["-v", "racket"]).verbose is True
    assert parser.parse_args(["racket", "-v"]).verbose is True
    assert parser.parse_args(["racket"]).verbose is False


def test_the_cli_copies_of_library_constants_are_true() -> None:
    from racketdyn.impact.grid import STRING_BEDS
    from racketdyn.impact.transient import ENGINES, TRANSIENT_SUPPORTS
    from racketdyn.racket import SUPPORTS
    from racketdyn.workflows import predict, swing

    assert tuple(SUPPORTS) == opt.SUPPORTS
    assert tuple(TRANSIENT_SUPPORTS) == opt.TRANSIENT_SUPPORTS
    assert tuple(ENGINES) == opt.ENGINES
    assert tuple(STRING_BEDS) == opt.STRING_BEDS
    assert predict.MODELS == opt.MODELS
    assert tuple(swing.IMPACT_MODELS) == opt.IMPACT_MODELS
    assert (predict.DEFAULT_GRID, predict.MAX_GRID) == (opt.DEFAULT_GRID, opt.MAX_GRID)
    assert swing.SWING_GRID == opt.SWING_GRID


def _loaded_after(statement: str) -> set[str]:
    code = f"import sys\n{statement}\nprint(' '.join(sorted(sys.modules)))"
    run = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    )
    return set(run.stdout.split())


HEAVY = {"numpy", "scipy", "matplotlib", "numba", "xarray", "rich"}


def test_importing_the_cli_loads_no_numerical_library() -> None:
    """``racketdyn --help`` must be instant: the parser imports no NumPy, SciPy, matplotlib."""
    assert not HEAVY & _loaded_after("import racketdyn.cli; racketdyn.cli.build_parser()")


@pytest.mark.slow
def test_the_approximate_method_and_the_figures_load_no_transient_model() -> None:
    """``predict``'s default run (the approximate method) and its figures need neither the
    transient model nor numba (≈ 0.2 s of the run): they are imported where the model runs."""
    modules = "racketdyn.workflows.predict, racketdyn.plotting.figures, racketdyn.plotting.steps"
    loaded = _loaded_after(f"import {modules}")
    assert not {"numba", "racketdyn.impact.transient", "racketdyn.impact.comparison"} & loaded


@pytest.mark.slow
def test_importing_racketdyn_is_light_and_names_load_on_use() -> None:
    assert not HEAVY & _loaded_after("import racketdyn")
    loaded = _loaded_after("import racketdyn as rd; rd.Ball")
    assert "racketdyn.ball" in loaded
    assert "matplotlib" not in loaded


def test_lazy_names_resolve() -> None:
    import racketdyn as rd

    for name in rd.__all__:
        assert getattr(rd, name) is not None, name
    assert set(rd.__all__) <= set(dir(rd))
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        rd.nothing  # noqa: B018


@pytest.mark.slow
def test_workflows_never_load_presentation() -> None:
    modules = ", ".join(
        f"racketdyn.workflows.{m}"
        for m in (
            "run",
            "inputs",
            "rig",
            "frf",
            "contact",
            "identify",
            "predict",
            "swing",
            "oblique",
            "twist",
            "sweep",
        )
    )
    loaded = _loaded_after(f"import {modules}")
    assert "matplotlib" not in loaded
    assert not {m for m in loaded if m.startswith(("racketdyn.plotting", "racketdyn.report"))}
    assert not {m for m in loaded if m.startswith("racketdyn.cli")}


def test_one_option_has_one_type_in_every_command() -> None:
    """Issue 23: ``--racket-speed`` was declared three times with two types (text in predict,
    a float in twist and oblique), ``--speed`` twice; each option is one declaration's type."""
    kinds: dict[str, set[tuple[object, str]]] = {}
    for sub in _subparsers().values():
        for action in sub._actions:
            if action.option_strings:
                kinds.setdefault(action.dest, set()).add((action.type, type(action).__name__))
    assert {dest: kind for dest, kind in kinds.items() if len(kind) > 1} == {}
