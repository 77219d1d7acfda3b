"""Issue 23: the library speaks Python, the CLI speaks flags.

Errors raised below the CLI name the Python parameter in backticks (`` `speeds` ``); the CLI
turns each into the command's option (``--speed``), in one place
(:func:`racketdyn.cli.options.in_flags`).  Before, a Python caller of
``run_predict(speeds=[-1])`` was told about ``--speed``.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import cast

import pytest

from racketdyn.cli import build_parser, main
from racketdyn.cli.options import in_flags
from racketdyn.errors import InputError
from racketdyn.workflows import PredictOptions, run_predict


@pytest.mark.parametrize(
    ("kwargs", "python", "flags"),
    [
        ({"speeds": [-1.0]}, "`speeds`", ["--speed", "-1"]),
        ({"racket_speed": [1.0, 2.0], "speeds": [10.0]}, "`racket_speed` takes one speed",
         ["--speed", "10", "--racket-speed", "1,2"]),
        ({"supports": ["hand"]}, "`supports` hand needs `model` transient",
         ["--support", "hand"]),
        ({"grid": 0}, "`grid` must be a whole number", ["--grid", "0"]),
        ({"model": "approx", "engine": "compiled"}, "`engine` is for the transient model",
         ["--engine", "compiled"]),
    ],
)  # fmt: skip
def test_python_hears_its_parameters_and_the_cli_its_flags(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    kwargs: dict[str, object],
    python: str,
    flags: list[str],
) -> None:
    with pytest.raises(InputError) as caught:
        run_predict(tmp_path / "py", options=PredictOptions(**kwargs))  # type: ignore[arg-type]
    message = str(caught.value)
    assert python in message
    assert "--" not in message
    assert main(["predict", *flags, "--no-figures", "--out", str(tmp_path / "cli")]) == 2
    said = capsys.readouterr().err
    assert "`" not in said
    option = flags[0]
    assert option in said


def command_parser(command: str) -> argparse.ArgumentParser:
    """The parser of one ``racketdyn`` command."""
    subparsers = next(
        a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)
    )
    return cast("argparse.ArgumentParser", subparsers.choices[command])


def test_in_flags_maps_names_and_leaves_unknown_ones_plain() -> None:
    parser = command_parser("predict")
    assert (
        in_flags("`speeds`: bad; `racket_speed` too", parser) == "--speed: bad; --racket-speed too"
    )
    assert in_flags("`supports` pinned", parser) == "--support pinned"
    assert in_flags("`not_an_option` here", parser) == "not_an_option here"
    assert in_flags("no names", parser) == "no names"


FLAGS_ALLOWED_BELOW_THE_CLI = {
    "report/sections/calibration.py": "the report's how-to-run line: a command by nature",
    "report/sections/contact.py": "the report's how-to-run line: a command by nature",
    "report/sections/stabilisation.py": "the report's how-to-run line: a command by nature",
    "plotting/registry.py": "a figure's caption in the report names the command that draws it",
    "workflows/calibrate.py": "calibration.json's `calibrated_files` says the options carrying "
    "the fitted values, on purpose (docs/develop.md, 'Errors name parameters')",
}
"""Files below the CLI that may write a flag, each with why (issue 23: none may elsewhere)."""


def test_no_flag_is_written_below_the_cli_but_where_said() -> None:
    """Issue 23's grep, ``grep -rn '"--' src/racketdyn | grep -v cli/``, as a test: a string
    starting with a flag (``"--speed``; matplotlib's dashed line ``"--"`` is none)."""
    import re

    source = Path(__file__).resolve().parents[1] / "src" / "racketdyn"
    found = {
        path.relative_to(source).as_posix()
        for path in source.rglob("*.py")
        if path.relative_to(source).parts[0] != "cli"
        and re.search(r"[\"']--[A-Za-z]", path.read_text(encoding="utf-8"))
    }
    assert found <= set(FLAGS_ALLOWED_BELOW_THE_CLI), sorted(
        found - set(FLAGS_ALLOWED_BELOW_THE_CLI)
    )


def test_an_unresolved_e_bg_names_the_parameter_and_the_cli_its_flag(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Issue 23, flags inside sentences: ``with_ball_string_cor`` said "give --e-bg" to a Python
    caller when the ball and string laws give no bounce at any speed; it names `e_bg`, and the
    CLI turns that into its option."""
    import numpy as np

    import racketdyn as rd
    from racketdyn import contact

    monkeypatch.setattr(contact, "ball_string_cor", lambda racket, ball, speeds: np.full(3, np.nan))
    ball = rd.Ball(mass_kg=0.0571)  # not one the cache of resolved balls holds
    with pytest.raises(InputError) as caught:
        contact.with_ball_string_cor(rd.default_racket(), ball)
    message = str(caught.value)
    assert "`e_bg`" in message
    assert "--" not in message
    parser = command_parser("predict")
    assert "give --e-bg" in in_flags(message, parser)


def test_the_modal_core_names_no_command_line_option() -> None:
    """The modal core is a library for any structure's FRFs: its messages name its Python
    parameters (`exclude_hz`, `geometry`), which the CLI turns into flags — the new-user trial
    of the Python API (2026-11-27, eighth session) was told "leave the mode out (--exclude)"."""
    import ast
    import re

    source = Path(__file__).resolve().parents[1] / "src" / "racketdyn" / "modal"
    found = []
    for path in source.rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        docstrings = {
            id(node.body[0].value)
            for node in ast.walk(tree)
            if isinstance(node, ast.Module | ast.FunctionDef | ast.ClassDef)
            and node.body
            and isinstance(node.body[0], ast.Expr)
        }
        found += [
            f"{path.name}:{node.lineno}"
            for node in ast.walk(tree)
            if isinstance(node, ast.Constant)
            and isinstance(node.value, str)
            and id(node) not in docstrings
            and re.search(r"(^|[ (])--[a-z]", node.value)
            # a modal model without coordinates is refused by the step that needs them
            # (predict): it points to the other command that makes them, by its option
            and not (path.name == "model.py" and "--geometry" in node.value)
        ]
    assert not found, found


def test_a_non_positive_driving_point_constant_names_exclude_hz_and_the_cli_its_flag() -> None:
    """``mass_normalised_shapes`` refused a mode with a non-positive driving-point constant
    naming ``--exclude`` to a Python caller (new-user trial of the Python API, 2026-11-27,
    eighth session): it names `exclude_hz`, which identify's parser turns into its option."""
    from dataclasses import replace

    import numpy as np

    from racketdyn.modal import fit_modal_constants, mass_normalised_shapes
    from racketdyn.testing import beam_frfs

    test = beam_frfs(np.linspace(0.0, 0.8, 5), reference_s=0.0)
    omega = 2 * np.pi * np.array([65.4, 180.3])
    fit = fit_modal_constants(test.frfs, -0.008 * omega + 1j * omega, (40.0, 250.0))
    constants = fit.constants.copy()
    constants[test.frfs.driving_point, 1] = -abs(constants[test.frfs.driving_point, 1])
    with pytest.raises(InputError) as caught:
        mass_normalised_shapes(test.frfs, replace(fit, constants=constants))
    message = str(caught.value)
    assert "`exclude_hz`" in message
    assert "--" not in message
    parser = command_parser("identify")
    assert "(--exclude)" in in_flags(message, parser)


def test_the_consoles_log_lines_name_the_commands_options() -> None:
    """Log records below the CLI name parameters in backticks (``shapes and maps will ask for
    `geometry` ``, io/uff.py, io/frf_layout.py): the console's log lines say the command's
    option, as its errors do (issue 23's leftover: flags inside sentences)."""
    import logging

    from racketdyn.cli import _InFlags

    record = logging.LogRecord(
        "racketdyn.io.uff", logging.INFO, __file__, 1, "%s: shapes will ask for `geometry`",
        ("frfs.uff",), None,
    )  # fmt: skip
    line = _InFlags(command_parser("identify")).format(record)
    assert line == "INFO racketdyn.io.uff: frfs.uff: shapes will ask for --geometry"


def test_the_frf_hint_names_the_parameter_and_the_cli_its_flag() -> None:
    parser = command_parser("frf")
    assert in_flags("give `force_window_s` 0.01 (s)", parser) == "give --force-window 0.01 (s)"
    assert in_flags("drop the ball's `e_bg_table`", command_parser("calibrate")) == (
        "drop the ball's --e-bg-table"
    )
    assert in_flags("choose one with `reference` (its node)", command_parser("identify")) == (
        "choose one with --reference (its node)"
    )


@pytest.mark.slow
def test_run_json_speaks_the_words_of_whoever_ran_the_step(tmp_path: Path) -> None:
    """New-user trial (2026-11-27, ninth session): frf's force-noise hint in run.json (shown
    in the report's provenance table) said "give `force_window_s` 0.01" to a user of the
    command, whose console said ``--force-window``.  A command's run.json says its flags (the
    console's translation, :func:`in_flags`); a Python call's keeps the parameter's name."""
    import json

    import racketdyn as rd
    from racketdyn.io import write_hammer_uff
    from racketdyn.rig import hammer_points, rig_model, simulate_hammer_test
    from racketdyn.workflows import run_frf

    rig = rig_model(rd.default_racket(), "free")
    locations, nodes = hammer_points(rig.racket, n_frame=2, n_strings=6)
    records = simulate_hammer_test(
        rig, locations, nodes, tuple(locations[0]), nodes[0], seed=2
    )  # the rig's default noise: 0.02 N rms on the force
    tests = write_hammer_uff(records, tmp_path / "hammer.uff")
    assert main(["frf", str(tests), "--out", str(tmp_path / "cli")]) == 0
    run_frf(tests, tmp_path / "py")
    hints = {
        how: json.loads((tmp_path / how / "run.json").read_text(encoding="utf-8"))["force_noise"][
            "hint"
        ]
        for how in ("cli", "py")
    }
    assert "give --force-window 0.01" in hints["cli"]
    assert "`" not in hints["cli"]
    assert "give `force_window_s` 0.01" in hints["py"]


def test_the_demos_steps_speak_their_commands_words(tmp_path: Path) -> None:
    """``racketdyn demo`` is a command: each step's run.json says its notes (frf's force-noise
    hint) in the words of the command it stands for (``--force-window``), as the step run on
    its own would, not the library's (`` `force_window_s` ``) — the report shows them."""
    from racketdyn.cli.demo import steps

    for label, command, call in steps(tmp_path, None):
        setup = call.keywords["setup"]  # type: ignore[attr-defined]
        assert setup.words is not None, label
        if command[1] == "frf":
            said = setup.words("give `force_window_s` 0.01")
            assert said == "give --force-window 0.01", label
