"""Issue 26, "Tracebacks": output folders and inputs that used to end in a traceback.

Each case is one line on stderr naming the input, exit status 2, and nothing written.  The
session runs as root, for whom a mode-0555 folder is writable; an unwritable place is made by
making the lock or the folder's creation fail as the operating system would (EACCES, EROFS).
"""

from __future__ import annotations

import errno
import json
import os
from pathlib import Path

import pytest

from costly import costly
from racketdyn.cli import main
from racketdyn.errors import InputError
from racketdyn.io import load_racket
from racketdyn.workflows import PredictOptions, run_predict
from racketdyn.workflows.setup import Setup


@pytest.fixture(scope="module")
def hammer_test(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """One rig's hammer records (one average a point), shared by the tests that only read them
    (each had run the rig itself: 3-4 s a case)."""
    from racketdyn.workflows import RigOptions, run_rig

    folder = tmp_path_factory.mktemp("rig")
    run_rig(folder, options=RigOptions(averages=1))
    return folder / "hammer_free.uff"


@pytest.fixture(scope="module")
@costly
def frfs(hammer_test: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The FRFs of :func:`hammer_test`'s records."""
    from racketdyn.workflows import run_frf

    folder = tmp_path_factory.mktemp("frf")
    run_frf(hammer_test, folder)
    return folder / "frfs.uff"


def _one_line(capsys: pytest.CaptureFixture[str], *words: str) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert "Traceback" not in err[0]
    for word in words:
        assert word in err[0], err[0]
    return err[0]


def test_an_empty_out_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``--out ''`` wrote the run into the current folder (Path('') is '.')."""
    os.chdir(tmp_path)
    assert main(["predict", "--grid", "2", "--no-figures", "--out", ""]) == 2
    _one_line(capsys, "--out")
    assert not list(tmp_path.iterdir())
    with pytest.raises(InputError, match="`out`"):
        run_predict("", options=PredictOptions(grid=2))


def test_an_over_long_out_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / ("a" * 300)
    assert main(["predict", "--grid", "2", "--no-figures", "--out", str(out)]) == 2
    _one_line(capsys, "--out", "too long")


@pytest.mark.parametrize("code", [errno.EACCES, errno.EROFS])
def test_a_folder_that_cannot_be_written_is_one_line(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
    code: int,
) -> None:
    real_open = os.open

    def refuse(path: object, flags: int, *args: object, **kwargs: object) -> int:
        if str(path).endswith(".racketdyn.lock"):
            raise OSError(code, os.strerror(code), str(path))
        return real_open(path, flags, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(os, "open", refuse)
    out = tmp_path / "ro"
    out.mkdir()
    assert main(["predict", "--grid", "2", "--no-figures", "--out", str(out)]) == 2
    _one_line(capsys, "--out", os.strerror(code))
    assert not list(out.iterdir())


def test_a_sweep_folder_that_cannot_be_created_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    # the sweep's results go to its store, sweep.zarr (issue 28; was parts/): its folder
    # cannot be made, as on a read-only disk
    real_mkdir = Path.mkdir

    def refuse(self: Path, *args: object, **kwargs: object) -> None:
        if "sweep.zarr" in self.parts:
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(self))
        real_mkdir(self, *args, **kwargs)  # type: ignore[arg-type]

    real_makedirs = os.makedirs

    def refuse_makedirs(name: str, *args: object, **kwargs: object) -> None:
        if "sweep.zarr" in Path(name).parts:
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(name))
        real_makedirs(name, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(Path, "mkdir", refuse)
    monkeypatch.setattr(os, "makedirs", refuse_makedirs)
    spec = tmp_path / "spec.toml"
    spec.write_text(
        'name = "s"\n[impacts]\nball_speeds_mps = [20.0]\ngrid = 2\n'
        "[variables]\nmass_kg = [0.30, 0.32]\n",
        encoding="utf-8",
    )
    assert main(["sweep", str(spec), "--out", str(tmp_path / "sw")]) == 2
    _one_line(capsys, "--out", "sweep.zarr", os.strerror(errno.EACCES))


@pytest.mark.parametrize("outputs", [5, "impact.csv", {"a": 1}, None])
def test_a_damaged_run_json_is_taken_as_damaged(tmp_path: Path, outputs: object) -> None:
    """A run.json whose ``outputs`` is not a list raised a TypeError after the computation."""
    out = tmp_path / "p"
    run_predict(out, options=PredictOptions(grid=2))
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    record["outputs"] = outputs
    (out / "run.json").write_text(json.dumps(record), encoding="utf-8")
    (out / "i").write_text("the user's", encoding="utf-8")  # a string's letters are no outputs
    run_predict(out, options=PredictOptions(grid=2))
    assert (out / "i").read_text(encoding="utf-8") == "the user's"
    assert json.loads((out / "run.json").read_text(encoding="utf-8"))["outputs"]


def test_a_negative_seed_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["rig", "--seed", "-1", "--averages", "1", "--out", str(tmp_path / "r")]) == 2
    _one_line(capsys, "--seed")


def test_a_deeply_nested_racket_file_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "deep.toml"
    path.write_text('name = "x"\na = ' + "[" * 3000 + "]" * 3000 + "\n", encoding="utf-8")
    with pytest.raises(InputError, match="nested"):
        load_racket(path)
    assert main(["racket", "--racket", str(path)]) == 2
    _one_line(capsys, "deep.toml", "nested")


# --- "Absurd numbers accepted as ok": every option gets a range ----------------------------
@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["oblique", "--spin", "1e9"], ["--spin", "refused even"]),
        (["oblique", "--spin", "3000"], ["--spin", "rpm"]),  # typed in rpm
        # fifth session's scan of every numeric option: μ 1e9 raised a RuntimeError after the
        # tangential model's 10 000 grip/slide phases; a face sliding at 1e9 m/s ran as ok
        (["oblique", "--friction", "1e9"], ["--friction", "refused even"]),
        (["oblique", "--friction", "3"], ["--friction", "up to 1;"]),
        (["oblique", "--racket-tangential-speed", "1e9"], ["--racket-tangential-speed"]),
        (["oblique", "--racket-tangential-speed=-1e9"], ["--racket-tangential-speed"]),
        (["swing", "--angular-speed", "0"], ["--angular-speed", "2–80 rad/s"]),
        (["predict", "--speed", "20,20", "--grid", "2"], ["--speed", "each ball speed once"]),
        (["swing", "--speed", "20,20"], ["--speed", "each ball speed once"]),
        (
            ["predict", "--model", "transient", "--support", "hand", "--hand-damping", "0",
             "--speed", "20", "--grid", "2"],
            ["--hand-damping", "1–500 N·s/m"],
        ),
    ],
)  # fmt: skip
def test_an_absurd_option_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], argv: list[str], words: list[str]
) -> None:
    assert main([*argv, "--no-figures", "--out", str(tmp_path / "o")]) == 2
    _one_line(capsys, *words)
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    ("value", "words"),
    [("nan", ["--force-range", "finite"]), ("inf", ["--force-range", "finite"]),
     ("1e9", ["--force-range", "refused even"]), ("2e6", ["--force-range", "N"])],
)  # fmt: skip
@pytest.mark.slow
def test_an_absurd_hammer_range_is_one_line(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    hammer_test: Path,
    value: str,
    words: list[str],
) -> None:
    """The fifth session's scan: ``frf --force-range`` took NaN (no overload ever found),
    inf and 1e9 N (a gigatonne-force hammer) without a word."""
    argv = ["frf", str(hammer_test), f"--force-range={value}"]
    assert main([*argv, "--out", str(tmp_path / "o")]) == 2
    _one_line(capsys, *words)
    if value == "2e6":  # a 2 MN channel: unusual, not impossible
        assert main([*argv, "--allow-implausible", "--out", str(tmp_path / "o")]) == 0


@pytest.mark.parametrize(
    ("option", "words"),
    [("--band=nan,500", ["--band", "finite", "Hz"]),
     ("--band=-5,500", ["--band", "frequencies", "Hz"]),
     ("--pin=nan", ["--pin", "finite", "Hz"]),
     ("--exclude=-5", ["--exclude", "frequencies", "Hz"]),
     ("--pin=1e9", ["--pin:", "outside the band"]),
     ("--max-order=0", ["--max-order", "at least 1"]),
     ("--band=1000,40", ["--band 1000,40", "low end is not below the high end", "give 40,1000"]),
     ("--band=40,40", ["--band 40,40", "not below the high end"]),
     ("--pin=1e4", ["--pin: 10000 Hz", "outside the band 40–", "give --band"]),
     ("--exclude=20", ["--exclude: 20 Hz", "outside the band 40–"]),
     ("--band=3000,4000", ["3000–4000 Hz", "(their last line; the default band is 40–"])],
)  # fmt: skip
def test_identifys_bad_numbers_name_their_option_and_unit(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    frfs: Path,
    option: str,
    words: list[str],
) -> None:
    """The fifth session's scan: ``--band nan,500`` was "finite speeds of zero or more, m/s"
    (frequencies read by the speeds' parser), and ``--max-order 0`` and ``--pin 1e9`` named
    the library's ``max_order`` and ``pin_hz`` instead of their options.  A new user's pass
    (thirteenth session): ``--band 1000,40`` said only "takes two frequencies low,high";
    ``--pin 5000`` quoted the band's first fitted line, 41.5039 Hz, as its bottom where the
    console says 40 Hz; a band beyond the FRFs quoted their 0–2500 Hz and not the default
    band the console shows."""
    assert main(["identify", str(frfs), option, "--out", str(tmp_path / "o")]) == 2
    line = _one_line(capsys, *words)
    assert "m/s" not in line
    assert "_hz" not in line
    assert "max_order" not in line
    assert "41.5" not in line


def test_more_worker_processes_than_the_machine_holds_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The fifth session's scan: ``predict --workers 100000`` with an uncertainty ran (a
    transient one would have forked a process a task)."""
    spread = tmp_path / "u.toml"
    spread.write_text("[e_bg]\nrange = [0.80, 0.88]\n", encoding="utf-8")
    argv = ["predict", "--grid", "2", "--no-figures", "--uncertainty", str(spread)]
    assert main([*argv, "--workers", "100000", "--out", str(tmp_path / "o")]) == 2
    _one_line(capsys, "--workers", "100000", "cores")
    assert not (tmp_path / "o").exists()


def test_a_ball_speed_twice_with_two_racket_speeds_is_two_cases(tmp_path: Path) -> None:
    result = run_predict(
        tmp_path / "p",
        options=PredictOptions(speeds=[20.0, 20.0], racket_speed=[0.0, 30.0], grid=2),
    )
    assert result.approximate is not None


def test_a_repeated_label_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], hammer_test: Path
) -> None:
    test = str(hammer_test)
    argv = ["contact", test, test, "--labels", "a,a", "--out", str(tmp_path / "c")]
    assert main(argv) == 2
    _one_line(capsys, "--labels", "each test once")


# --- the new-user trial of 2026-11-27 -------------------------------------------------------
@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["predict", "--grid", "2.5"], ["--grid", "2.5", "--help"]),  # argparse: usage block
        (["ball", "--tension", "abc"], ["--tension", "abc"]),
        (["predict", "--speed", "0"], ["--speed", "0 + 0"]),
        (["predict", "--speed", "-1"], ["--speed", "(got -1)"]),
        (
            ["predict", "--model", "transient", "--support", "hand", "--hand-damping", "-1",
             "--speed", "20"],
            ["--hand-damping -1", "refused even with --allow-implausible"],
        ),
    ],
)  # fmt: skip
def test_the_trials_bad_options_are_one_line_in_flags(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], argv: list[str], words: list[str]
) -> None:
    try:
        code = main([*argv, "--out", str(tmp_path / "o")])
    except SystemExit as raised:  # argparse's own errors exit from the parser
        code = raised.code
    assert code == 2
    line = _one_line(capsys, *words)
    assert "hand.damping" not in line
    assert "[" not in line  # no Python list


def test_a_fraction_below_one_is_not_called_per_cent(tmp_path: Path) -> None:
    text = (Path(__file__).parents[1] / "src/racketdyn/data/kawazoe_2002.toml").read_text()
    path = tmp_path / "r.toml"
    path.write_text(text.replace("tension_loss = 0.30", "tension_loss = 0.6"), "utf-8")
    with pytest.raises(InputError) as caught:
        load_racket(path)
    assert "per cent" not in str(caught.value)
    assert str(caught.value).count("pull tension") == 1


def test_compound_shows_no_nan_for_a_mode_without_a_ratio(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = ["compound", "--support", "free", "--no-figures", "--out", str(tmp_path / "c")]
    assert main(argv) == 0
    rows = [line for line in capsys.readouterr().out.splitlines() if "│" in line]
    assert any("2-node twisting" in row for row in rows)
    assert not any("nan" in row.lower() for row in rows)


def test_report_refuses_a_racket_the_runs_were_not_computed_on(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The trial of 2026-11-27: ``report --racket paper.toml`` over another racket's runs wrote
    a page titled with the paper's racket, its properties and outline, exit 0."""
    from dataclasses import replace

    import racketdyn as rd
    from racketdyn.io import write_racket_toml

    mine = replace(rd.default_racket(), name="mine", mass_kg=0.32)
    write_racket_toml(mine, tmp_path / "mine.toml")
    run_predict(
        tmp_path / "p", setup=Setup(racket=tmp_path / "mine.toml"), options=PredictOptions(grid=2)
    )
    paper = Path(rd.__file__).parent / "data" / "kawazoe_2002.toml"
    assert main(["report", str(tmp_path / "p"), "--racket", str(paper)]) == 2
    _one_line(capsys, "--racket", "mass_kg 0.32 against 0.36", "mine")
    assert main(["report", str(tmp_path / "p"), "--racket", str(tmp_path / "mine.toml")]) == 0


def test_a_relative_speed_beyond_the_laws_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The trial of 2026-11-27: ``--speed 60 --racket-speed 40`` (100 m/s relative) ran with rows
    marked ok from laws that hold to 70 m/s."""
    argv = ["predict", "--speed", "60", "--racket-speed", "40", "--no-figures"]
    assert main([*argv, "--out", str(tmp_path / "o")]) == 2
    _one_line(capsys, "--speed + --racket-speed", "= 100", "70 m/s", "--allow-implausible")
    assert main([*argv, "--grid", "2", "--allow-implausible", "--out", str(tmp_path / "o")]) == 0


def test_report_of_a_swinging_racket_does_not_say_at_rest(tmp_path: Path) -> None:
    """The trial of 2026-11-27: ``predict --speed 25 --racket-speed 28``'s page said the sweet
    spots were for a "racket at rest" and defined e on a racket at rest."""
    from racketdyn.report import write_report

    run_predict(tmp_path / "p", options=PredictOptions(speeds=[25.0], racket_speed=[28.0], grid=3))
    text = write_report(tmp_path / "p").read_text(encoding="utf-8")
    start = text.index('<section id="rebound">')
    section = text[start : text.index("</section>", start)]
    assert "racket at rest." not in section
    assert "racket moving at 28 m/s" in section
    assert "relative to the racket" in section


# --- sweep variables through the plausibility table (issue 26) -------------------------------
@pytest.mark.parametrize(
    ("variables", "impacts", "words"),
    [
        ("[variables.point_mass]\nmass_kg = [0.0, 5.0]\nclock = 12\n", "", ["mass_kg", "grams"]),
        ("[variables]\ntension_n = [50.0, 250.0]\n", "", ["tension_n", "pounds"]),
        ("[variables.point_mass]\nmass_kg = 0.005\nclock = 13\n", "", ["clock", "1 to 12"]),
        ("[variables]\nmass_kg = [0.30]\n", "", ["ball_speeds_mps", "km/h"]),
        ("[variables]\ne_bg = [83.0]\n", "", ["e_bg = 83", "a percentage (83 % = 0.83)"]),
    ],
)
def test_a_sweep_variable_of_another_unit_is_refused(
    tmp_path: Path, variables: str, impacts: str, words: list[str]
) -> None:
    from racketdyn.sweep import load_sweep_spec

    speeds = "[90.0]" if "ball_speeds_mps" in words else "[20.0]"
    spec = tmp_path / "spec.toml"
    spec.write_text(
        f'name = "s"\n[impacts]\nball_speeds_mps = {speeds}\ngrid = 2\n{impacts}{variables}',
        encoding="utf-8",
    )
    with pytest.raises(InputError) as caught:
        load_sweep_spec(spec)
    for word in words:
        assert word in str(caught.value)


def test_a_sweep_may_take_an_unusual_value_when_it_says_so(tmp_path: Path) -> None:
    from racketdyn.sweep import load_sweep_spec

    spec = tmp_path / "spec.toml"
    spec.write_text(
        'name = "s"\n[checks]\nallow_implausible = true\n[impacts]\nball_speeds_mps = [80.0]\n'
        "grid = 2\n[variables]\nmass_kg = [0.30, 0.45]\n",
        encoding="utf-8",
    )
    assert len(load_sweep_spec(spec).designs) == 2


# --- the modal-model JSON checked on read (issue 26) ---------------------------------------
def _modal_file(tmp_path: Path, change: object) -> Path:
    import racketdyn as rd
    from racketdyn.racket_modal import modal_model_for

    data = modal_model_for(rd.default_racket()).to_dict()
    change(data)  # type: ignore[operator]
    path = tmp_path / "modes.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


def _scale_frequencies(data: dict, factor: float) -> None:  # type: ignore[type-arg]
    for mode in data["modes"]:
        mode["frequency_hz"] *= factor


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (lambda d: d.update(format_version=99), ["format_version 99", "reads 1"]),
        (lambda d: d["units"].update(locations="mm"), ["units.locations", "'mm'"]),
        (lambda d: d["modes"][0].update(damping_ratio=2.5), ["damping_ratio 2.5", "per cent"]),
        (lambda d: _scale_frequencies(d, 2 * 3.141592653589793), ["rad/s", "120 Hz"]),
        (
            lambda d: d.update(locations_m=[[x * 1e3, y * 1e3] for x, y in d["locations_m"]]),
            ["off the racket", "in mm?"],
        ),
        (
            lambda d: d.update(mode_shapes=[[v * 1e4 for v in row] for row in d["mode_shapes"]]),
            ["1/√kg", "1–30"],
        ),
    ],
)
def test_a_modal_file_is_checked_like_a_racket_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], change: object, words: list[str]
) -> None:
    path = _modal_file(tmp_path, change)
    argv = ["predict", "--modal", str(path), "--grid", "2", "--no-figures"]
    assert main([*argv, "--out", str(tmp_path / "o")]) == 2
    _one_line(capsys, "modes.json", *words)


def test_a_sound_modal_file_is_read(tmp_path: Path) -> None:
    path = _modal_file(tmp_path, lambda d: None)
    assert main(["predict", "--modal", str(path), "--grid", "2", "--no-figures",
                 "--out", str(tmp_path / "o")]) == 0  # fmt: skip


# --- e_BG tables and load-deflection rows name the file and the line (issue 26) ------------
@pytest.mark.parametrize(
    ("option", "rows", "words"),
    [
        ("--e-bg-table", "speed_mps,e_bg\n10,0.84\n20,0\n", ["line 3", "e_bg 0"]),
        ("--e-bg-table", "speed_mps,e_bg\n10,0.84\n10,0.83\n", ["line 3", "repeats"]),
        ("--e-bg-table", "speed_mps,e_bg\n-5,0.84\n20,0.8\n", ["line 2", "negative"]),
        ("--ball-law", "deflection_m,force_n\n0.002,100\n0.001,50\n0.004,300\n",
         ["line 3", "comes after"]),
        ("--ball-law", "deflection_m,force_n\n0.001,50\n0.001,60\n0.004,300\n",
         ["line 3", "repeats"]),
    ],
)  # fmt: skip
def test_table_rows_out_of_order_name_the_line(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    option: str,
    rows: str,
    words: list[str],
) -> None:
    table = tmp_path / "table.csv"
    table.write_text(rows, encoding="utf-8")
    argv = ["predict", option, str(table), "--grid", "2", "--no-figures"]
    assert main([*argv, "--out", str(tmp_path / "o")]) == 2
    _one_line(capsys, "table.csv", *words)


# --- absurd samples (issue 26) -------------------------------------------------------------
def test_an_absurd_hammer_sample_names_the_data_set() -> None:
    """A sample of 1e300 in a mutated file was taken as data; numpy's overflow warnings leaked
    to the console."""
    import dataclasses

    import numpy as np

    from racketdyn.testing import Modes, records_for

    modes = Modes(np.array([150.0]), np.array([0.01]), np.array([[0.5], [0.2]]))
    good = records_for(modes, n_averages=2)
    force = [f.copy() for f in good.force]
    force[1][0, 40] = 1e300
    with pytest.raises(InputError, match=r"node .*: a force sample of 1e\+300 N"):
        dataclasses.replace(good, force=tuple(force))
    # every reader builds HammerRecords (UFF 58, the hammer CSV): the check holds for them all
    response = [r.copy() for r in good.response]
    response[0][1, 10] = 1e12
    with pytest.raises(InputError, match=r"a response sample of 1e\+12"):
        dataclasses.replace(good, response=tuple(response))


def test_a_folder_given_as_the_racket_file_says_so(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`--racket <folder>` printed "[Errno 21] Is a directory" with no fix (new-user trial,
    eleventh session)."""
    assert main(["racket", "--racket", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "is a folder; give a racket file (.toml)" in err
    assert "Errno" not in err


def test_a_compressed_universal_file_is_named_compressed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A ``.uff.xz`` (or gzip) file was "not a Universal File": say it is compressed and how
    to read it (new-user trial, eleventh session)."""
    import lzma

    packed = tmp_path / "test.uff.xz"
    packed.write_bytes(lzma.compress(b"    -1\n   151\n" + b"x\n" * 20 + b"    -1\n"))
    assert main(["identify", str(packed), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert "compressed (xz)" in err
    assert "decompress it first" in err


def test_a_misspelt_support_lists_every_support_some_command_takes(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`predict --support hnad` listed only free and pinned, though `hand` exists (with the
    transient model): the message says so (new-user trial, eleventh session)."""
    assert main(["predict", "--support", "hnad", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert "free, pinned" in err
    assert "hand" in err
