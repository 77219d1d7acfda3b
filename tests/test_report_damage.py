"""`racketdyn report` on a damaged run folder: one line naming the file and the fix, exit 2.

A run folder lives on disks, in mail and in zip files: a copy stops half-way, a file is saved
over by a spreadsheet, a JSON file is cut short.  The report must say which file is damaged and
what to do, never show a traceback nor quietly leave the numbers out (issue 13).
"""

from __future__ import annotations

import json
import shutil
from collections.abc import Callable
from pathlib import Path

import pytest

from racketdyn.cli import main

BINARY = bytes(range(256)) * 8  # not UTF-8 from byte 128 on
CONTACT = """node,x_m,y_m,contact_time_mean_s,contact_time_std_s,n_averages
1,0.09,0,0.000375,2.3e-07,10
7,0.45,0.02,0.00412,3.1e-05,10
8,0.505,0,0.00405,2.8e-05,10
9,0.56,-0.03,0.00398,3.0e-05,9
"""
"""A small contact table in the layout `racketdyn contact` writes (`contact_<label>.csv`)."""


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A run folder with a prediction (impact.csv, run.json) and a contact table."""
    d = tmp_path_factory.mktemp("run")
    argv = ["predict", "--grid", "3", "--speed", "20", "--no-figures", "--out", f"{d}/predict"]
    assert main(argv) == 0
    (d / "contact").mkdir()
    (d / "contact" / "contact_free.csv").write_text(CONTACT, encoding="utf-8")
    return d


def _lines(path: Path) -> list[str]:
    return path.read_text(encoding="utf-8").splitlines(keepends=True)


def _cut_mid_row(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    path.write_text(text[: len(text) - len(_lines(path)[-1]) // 2], encoding="utf-8")


def _drop_rows(path: Path) -> None:
    path.write_text("".join(_lines(path)[:-3]), encoding="utf-8")


def _text_in(column: str) -> Callable[[Path], None]:
    def damage(path: Path) -> None:
        lines = _lines(path)
        header = lines[0].rstrip("\n").split(",")
        cells = lines[2].rstrip("\n").split(",")
        cells[header.index(column)] = "fast"
        lines[2] = ",".join(cells) + "\n"
        path.write_text("".join(lines), encoding="utf-8")

    return damage


def _cut_json(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    path.write_text(text[: len(text) // 2], encoding="utf-8")


def _racket_as_text(path: Path) -> None:
    record = json.loads(path.read_text(encoding="utf-8"))
    record["racket"] = "built-in"
    path.write_text(json.dumps(record), encoding="utf-8")


def _binary_frfs(path: Path) -> None:
    """An FRF folder (quality.csv as `racketdyn frf` writes it) whose frfs.uff is garbage."""
    path.parent.mkdir()
    (path.parent / "quality.csv").write_text(
        "node,average,accepted,reasons,peak_force_n\n1,1,1,,38.1\n", encoding="utf-8"
    )
    path.write_bytes(BINARY)


DAMAGE: dict[str, tuple[str, Callable[[Path], None]]] = {
    "impact.csv cut mid-row": ("predict/impact.csv", _cut_mid_row),
    "impact.csv rows missing": ("predict/impact.csv", _drop_rows),
    "impact.csv text in a number column": ("predict/impact.csv", _text_in("contact_time_s")),
    "impact.csv text in the speed column": ("predict/impact.csv", _text_in("ball_speed_mps")),
    "impact.csv empty": ("predict/impact.csv", lambda p: p.write_bytes(b"")),
    "impact.csv binary": ("predict/impact.csv", lambda p: p.write_bytes(BINARY)),
    "contact CSV binary": ("contact/contact_free.csv", lambda p: p.write_bytes(BINARY)),
    "contact CSV NUL bytes": ("contact/contact_free.csv", lambda p: p.write_bytes(b"\0" * 64)),
    "contact CSV text in a number column": (
        "contact/contact_free.csv",
        _text_in("contact_time_mean_s"),
    ),
    "contact CSV cut mid-row": ("contact/contact_free.csv", _cut_mid_row),
    "comparison.csv binary": ("predict/comparison.csv", lambda p: p.write_bytes(BINARY)),
    "frfs.uff binary": ("frf_free/frfs.uff", _binary_frfs),
    "run.json cut short": ("predict/run.json", _cut_json),
    "run.json binary": ("predict/run.json", lambda p: p.write_bytes(BINARY)),
    "run.json not an object": ("predict/run.json", lambda p: p.write_text("[1, 2]\n")),
    "run.json racket not a table": ("predict/run.json", _racket_as_text),
}


def test_the_undamaged_folder_reports(
    folder: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    shutil.copytree(folder, tmp_path / "run")
    assert main(["report", str(tmp_path / "run")]) == 0
    assert capsys.readouterr().err == ""
    page = (tmp_path / "run" / "report.html").read_text(encoding="utf-8")
    for section in ("impact", "contact", "rebound"):
        assert f'<section id="{section}">' in page


@pytest.mark.parametrize("kind", list(DAMAGE))
def test_a_damaged_file_is_one_line_naming_it(
    kind: str, folder: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    run = tmp_path / "run"
    shutil.copytree(folder, run)
    name, damage = DAMAGE[kind]
    damage(run / name)
    assert main(["report", str(run)]) == 2
    captured = capsys.readouterr()
    err = captured.err.strip().splitlines()
    assert len(err) == 1, captured.err
    assert err[0].startswith("racketdyn: error: ")
    assert str(run / name) in err[0]
    assert "re-run the step that wrote it" in err[0]
    assert "Traceback" not in captured.out + captured.err
    if name == "predict/impact.csv":  # the command that wrote it, from its run.json
        assert "racketdyn predict --grid 3" in err[0]
    assert not (run / "report.html").exists()


def test_an_interrupted_page_write_leaves_the_previous_page_whole(
    folder: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """report.html was written in place: a write cut off (Ctrl-C, a full disk) left half a
    page where the previous one had been.  It is now written beside and moved in whole."""
    from racketdyn.report import write_report

    run = tmp_path / "run"
    shutil.copytree(folder, run)
    previous = write_report(run).read_text(encoding="utf-8")
    write_text = Path.write_text

    def cut_off(self: Path, data: str, *args: object, **kwargs: object) -> int:
        write_text(self, data[: len(data) // 2], encoding="utf-8")
        raise KeyboardInterrupt

    monkeypatch.setattr(Path, "write_text", cut_off)
    with pytest.raises(KeyboardInterrupt):
        write_report(run)
    monkeypatch.undo()
    assert (run / "report.html").read_text(encoding="utf-8") == previous
    assert sorted(p.name for p in run.iterdir() if p.name.startswith(".")) == []
