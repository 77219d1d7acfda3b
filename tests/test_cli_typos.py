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
    with pytest.raises(SystemExit) as stop:
        main([*argv, "--out", str(tmp_path / "o")])
    assert stop.value.code == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert len(err.strip().splitlines()) == 1
    for word in words:
        assert word in err, err


def test_a_refused_value_prints_nothing_on_stdout(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``twist --speed 500`` wrote an empty line on stdout before its one-line error (the
    progress display's end, on a console that is no terminal)."""
    assert main(["twist", "--speed", "500", "--out", str(tmp_path / "o")]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert "--speed 500" in err
