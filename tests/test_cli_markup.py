"""The console prints data as it is: rich markup is never read in a path, a name or a message.

rich takes ``[word]`` for a style and drops it, and ``[/word]`` with nothing open for an error:
``rig --out 'rg[x]'`` printed ``wrote rg/hammer_free.uff``, a racket named
``Pro [prototype]`` was titled ``Pro``, and ``twist --out 'o[/b]'`` ended in a ``MarkupError``
traceback after its files were written (the closing notes of issues 14-15).
"""

from __future__ import annotations

import dataclasses
import io
from pathlib import Path

import numpy as np
import pytest
from rich.console import Console

import racketdyn
from racketdyn.cli import main
from racketdyn.cli import options as opt
from racketdyn.testing.records import Modes, records_for

DEFAULT_TOML = Path(racketdyn.__file__).parent / "data" / "kawazoe_2002.toml"
MODES = Modes(np.array([120.0, 330.0]), np.array([0.03, 0.02]), np.array([[6.0, 4.0], [-3.0, 2.5]]))


@pytest.fixture(autouse=True)
def _wide(monkeypatch: pytest.MonkeyPatch) -> None:
    """A console wide enough that no path is folded over two lines."""
    monkeypatch.setenv("COLUMNS", "400")


def _printed(capsys: pytest.CaptureFixture[str]) -> str:
    captured = capsys.readouterr()
    return captured.out + captured.err


def _racket_named(tmp_path: Path, name: str, file_name: str) -> Path:
    text = DEFAULT_TOML.read_text(encoding="utf-8")
    lines = [f'name = "{name}"' if line.startswith("name =") else line for line in text.split("\n")]
    assert lines != text.split("\n"), "no name line in the built-in racket file; update the test"
    path = tmp_path / file_name
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


@pytest.mark.parametrize("name", ["Pro [prototype]", "Pro [/b]"])
def test_a_racket_name_and_file_with_brackets_are_printed_whole(
    name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = _racket_named(tmp_path, name, "my[file].toml")
    assert main(["racket", "--racket", str(path)]) == 0
    printed = _printed(capsys)
    assert name in printed
    assert "my[file].toml" in printed


def test_an_input_error_quoting_brackets_is_one_whole_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    missing = tmp_path / "nope[file].toml"
    assert main(["racket", "--racket", str(missing)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert str(missing) in err[0]


@pytest.mark.parametrize(
    "argv",
    [
        ["predict", "--grid", "3", "--no-figures"],
        ["twist", "--no-figures"],
        ["oblique", "--no-figures"],
        ["swing", "--grid", "3", "--no-figures"],
        ["compound", "--no-figures"],
    ],
    ids=lambda argv: argv[0],
)
@pytest.mark.parametrize("folder", ["out[draft]", "o[/b]"])
@pytest.mark.slow
def test_an_output_folder_with_brackets_is_printed_whole(
    argv: list[str], folder: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``[draft]`` was dropped; ``[/b]`` (a closing tag with nothing open) raised."""
    out = tmp_path / folder
    assert main([*argv, "--out", str(out)]) == 0
    printed = _printed(capsys)
    assert f"→ {out}" in printed
    assert f"wrote {out}{'/'}" in printed


@pytest.mark.slow
def test_frf_prints_its_input_and_output_paths_whole(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from racketdyn.io import write_hammer_csv

    records = records_for(MODES, n_averages=3)
    records = dataclasses.replace(records, force=tuple(f.copy() for f in records.force))
    records.force[1][0] = 0.0  # one average without a pulse: a note naming the reason
    data, _ = write_hammer_csv(records, tmp_path / "h.csv", tmp_path / "g.csv")
    out = tmp_path / "frf[run]"
    assert main(["frf", str(data), "--out", str(out)]) == 0
    printed = " ".join(_printed(capsys).split())
    assert f"→ {out}" in printed
    assert f"wrote {out / 'frfs.uff'}" in printed


def _console() -> tuple[Console, io.StringIO]:
    sink = io.StringIO()
    return Console(file=sink, width=400, color_system=None), sink


def test_status_reasons_and_labels_keep_their_brackets() -> None:
    console, sink = _console()
    status = np.array(["ok", "beyond the [ball] law", "beyond the [ball] law"])
    opt.print_status(console, status, "a[/b].csv", "approx [v2]")
    assert "approx [v2]: 2 impacts: beyond the [ball] law; NaN in a[/b].csv" in sink.getvalue()


def test_the_stale_report_line_names_bracketed_folders_whole(tmp_path: Path) -> None:
    from racketdyn.workflows.run import REPORT_NAME

    above = tmp_path / "demo[/x]"
    (above / "step").mkdir(parents=True)
    (above / REPORT_NAME).write_text("old", encoding="utf-8")
    written = above / "step" / "impact.csv"
    written.write_text("new", encoding="utf-8")
    console, sink = _console()
    opt.print_written(console, [written])
    printed = sink.getvalue()
    assert f"wrote {written}" in printed
    assert f"{above / REPORT_NAME} still shows" in printed
    assert f"racketdyn report {above} makes it again" in printed


def test_a_progress_line_describing_a_bracketed_name_does_not_raise() -> None:
    console, _ = _console()
    with opt.progress_display(console, thread=False) as progress:
        progress("figure [/b].png", 0, 0)


def test_a_long_racket_path_is_printed_whole(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """The file's path sat in the table's title, folded at 80 columns mid-name ("my[fil" /
    "e].toml"): under pytest-xdist's longer temporary folders the test above failed."""
    monkeypatch.setenv("COLUMNS", "80")
    deep = tmp_path / ("a_folder_with_a_rather_long_name_" * 2) / "and_another_one"
    deep.mkdir(parents=True)
    path = _racket_named(deep, "Pro", "my[file].toml")
    assert main(["racket", "--racket", str(path)]) == 0
    assert str(path) in _printed(capsys)
