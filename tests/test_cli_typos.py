"""A mistyped option, a value starting with '-', and a refused value (a new user's trial): one
line on stderr naming the command's own help, a suggestion where one is near, nothing on
stdout."""

from __future__ import annotations

from pathlib import Path

import pytest

from racketdyn.cli import main


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (
            ["predict", "--speeds", "20"],
            ["--speeds", "did you mean --speed?", "racketdyn predict --help"],
        ),
        (["predict", "--suport", "free"], ["--suport", "did you mean --support?"]),
        (["sweep", "spec.toml", "--workrs", "2"], ["--workrs", "did you mean --workers?"]),
        (["twist", "--offsets", "-0.05,0,0.05"], ["--offsets=-0.05,0,0.05"]),
    ],
)
def test_a_typo_names_the_option_it_was_near_and_the_commands_help(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], argv: list[str], words: list[str]
) -> None:
    err = _refused([*argv, "--out", str(tmp_path / "o")], capsys)
    for word in words:
        assert word in err, err


def _refused(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    """The one line on stderr of a command line argparse refuses (exit 2, nothing on stdout)."""
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert len(err.strip().splitlines()) == 1
    return err


def test_a_refused_value_prints_nothing_on_stdout(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``twist --speed 500`` wrote an empty line on stdout before its one-line error (the
    progress display's end, on a console that is no terminal)."""
    assert main(["twist", "--speed", "500", "--out", str(tmp_path / "o")]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert "--speed 500" in err


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        # predict took oblique's --point as a prefix of --points (a CSV): "0.51,0: no such file"
        (["predict", "--point=0.51,0", "--out", "o"], ["--point=0.51,0", "did you mean --points?"]),
        (["oblique", "--angle", "30", "--out", "o"], ["--angle", "did you mean --angles?"]),
        (["contact", "t.uff", "--label", "free", "--out", "o"], ["did you mean --labels?"]),
        (["report", "r", "--step", "predict"], ["--step", "did you mean --steps?"]),
    ],
)
def test_an_option_is_taken_by_its_whole_name_only(
    capsys: pytest.CaptureFixture[str], argv: list[str], words: list[str]
) -> None:
    """New-user trial (2026-11-27, ninth session): argparse's prefix matching took ``--angle``
    for ``--angles`` without a word, and ``predict --point=0.51,0`` for ``--points``; one
    spelling per option, so a prefix is an unknown option with its "did you mean"."""
    err = _refused(argv, capsys)
    for word in words:
        assert word in err, err


def test_every_parser_refuses_prefixes() -> None:
    import argparse

    from racketdyn.cli import build_parser

    parser = build_parser()
    (commands,) = (a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    assert not parser.allow_abbrev
    assert [name for name, sub in commands.choices.items() if sub.allow_abbrev] == []


@pytest.mark.parametrize(
    ("argv", "dest", "value"),
    [
        (["twist", "--offsets=-0.05,0,0.05"], "offsets", "-0.05,0,0.05"),
        (["oblique", "--angles=-30,0,30"], "angles", "-30,0,30"),
        (["oblique", "--point=0.5,-0.03"], "point", "0.5,-0.03"),
        (["predict", "--racket-speed", "-5"], "racket_speed", "-5"),
        (["predict", "--speed=20"], "speed", "20"),
        (["compound", "--ball-at=0.5,-0.03"], "ball_at", "0.5,-0.03"),
    ],
)
def test_values_after_equals_and_negative_numbers_still_parse(
    argv: list[str], dest: str, value: str
) -> None:
    from racketdyn.cli import parse

    assert getattr(parse([*argv, "--out", "o"]), dest) == value


@pytest.mark.parametrize(
    ("argv", "hint"),
    [
        # rig's, identify's and compare's spelling of a ball on the strings
        (["rig", "--point", "0.51,0"], "did you mean --ball-at?"),
        (["identify", "f.uff", "--point", "0.51,0"], "did you mean --ball-at?"),
        # swing, oblique and twist called the ball's speed --ball-speed before --speed
        (["twist", "--ball-speed", "20"], "did you mean --speed?"),
        (["oblique", "--ball-speed", "20"], "did you mean --speed?"),
        (["twist", "--point", "0.5,0"], "did you mean --x?"),
    ],
)
def test_another_commands_word_for_a_concept_names_this_commands_option(
    capsys: pytest.CaptureFixture[str], argv: list[str], hint: str
) -> None:
    """New-user trial (2026-11-27, ninth session): ``compound --ball-at`` (rig's word for the
    ball's place) was told "did you mean --ball-law?"; a word another command uses for the
    same thing names this command's option for it."""
    assert hint in _refused([*argv, "--out", "o"], capsys)
