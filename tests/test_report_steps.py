"""``racketdyn report`` over a lab's own step folders (issue 27).

A lab works step by step: its folder holds ``rig/``, ``frf_free/``, ``frf_hand/``, an
``identify`` run per support, a ``compare`` run, and two predictions.  The report refused such a
folder ("it holds 2 predict runs … give the folder of one of them, or a demo folder"), and with
both ``identify`` and ``compare`` in it showed every identified model twice (mode tables, the
rig's truth tables, Figs 4–5).  ``report DIR --steps NAME=FOLDER,…`` names the folders to use;
without it they are found when that is unambiguous; either way the console and the page's
provenance say which folder each step came from.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from costly import costly
from racketdyn.cli import main
from racketdyn.errors import InputError
from racketdyn.report import write_report
from racketdyn.report.folder import RunFolder

BAND = (40.0, 850.0)


@pytest.fixture(scope="module")
@costly
def lab(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A lab's folder of step folders, run one by one (small settings, no figures where a
    step allows it)."""
    from racketdyn.workflows.frf import run_frf
    from racketdyn.workflows.identify import IdentifyOptions, run_compare, run_identify
    from racketdyn.workflows.rig import RigOptions, run_rig

    d = tmp_path_factory.mktemp("lab")
    run_rig(d / "rig", options=RigOptions(support=("free", "hand"), averages=2, binary=True))
    for support in ("free", "hand"):
        run_frf(d / "rig" / f"hammer_{support}.uff", d / f"frf_{support}")
        run_identify(
            d / f"frf_{support}" / "frfs.uff",
            d / f"id_{support}",
            options=IdentifyOptions(band_hz=BAND),
            support=support,
        )
    run_compare(
        d / "frf_free" / "frfs.uff",
        d / "frf_hand" / "frfs.uff",
        d / "cmp",
        options=IdentifyOptions(band_hz=BAND),
    )
    common = ["--grid", "3", "--support", "free", "--no-figures"]
    assert main(["predict", *common, "--speed", "20", "--out", str(d / "predict")]) == 0
    argv = ["predict", *common, "--speed", "25,3", "--racket-speed", "28,42"]
    assert main([*argv, "--out", str(d / "serve")]) == 0
    return d


def _text(html: str) -> list[str]:
    """The page's visible lines (scripts, styles and images left out)."""
    html = re.sub(r"<(script|style)\b.*?</\1>", "", html, flags=re.S)
    html = re.sub(r"data:image/png;base64,[A-Za-z0-9+/=]+", "", html)
    return [line.strip() for line in re.sub(r"<[^>]+>", "", html).splitlines() if line.strip()]


@pytest.mark.slow
def test_two_predictions_are_refused_naming_steps(
    lab: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    capsys.readouterr()
    assert main(["report", str(lab)]) == 2
    error = " ".join(capsys.readouterr().err.split())
    assert "2 predict runs (predict, serve)" in error
    assert "--steps predict=serve" in error  # the way to choose, in the command's words
    assert "`" not in error
    assert not (lab / "report.html").exists()


def test_steps_choose_the_folders_and_the_report_says_which(
    lab: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    capsys.readouterr()
    assert main(["report", str(lab), "--steps", "predict=serve"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    for step, folder in (
        ("rig", "rig"),
        ("free", "frf_free"),
        ("hand", "frf_hand"),
        ("compare", "cmp"),
        ("predict", "serve"),
    ):
        assert f"{step}: {folder}" in out, (step, out)
    # compare holds both supports' models: the identify runs of the same supports are left out
    assert "id_free: left out" in out
    assert "id_hand: left out" in out
    page = (lab / "report.html").read_text(encoding="utf-8")
    lines = _text(page)
    # the provenance says which folder each step came from
    assert "<h3>Step folders</h3>" in page
    assert "<tr><td>predict</td><td>serve</td><td></td><td>given with --steps</td></tr>" in page
    assert "<tr><td>free</td><td>frf_free</td><td></td><td>found</td></tr>" in page
    assert "id_free (cmp holds the free model)" in page
    assert "<h3>predict</h3>" not in page  # the other prediction's provenance is not shown
    run = RunFolder.scan(lab, steps={"predict": "serve"})
    assert [label for label, _, _ in run.identifications] == ["free", "hand"]
    assert {folder.name for _, folder, _ in run.identifications} == {"cmp"}
    impacts = run.impacts()
    assert impacts is not None
    assert impacts.speeds == [3.0, 25.0]
    # no table shown twice: each support's identified modes once
    modes = [line for line in lines if line.startswith("2-node bending")]
    assert len(modes) == len(set(modes)), modes


def test_identify_runs_alone_are_labelled_by_their_support(lab: Path) -> None:
    steps = [
        ("rig", "rig"),
        ("free", "frf_free"),
        ("hand", "frf_hand"),
        ("identify", "id_free"),
        ("identify", "id_hand"),
        ("predict", "predict"),
    ]
    run = RunFolder.scan(lab, steps=steps)
    assert [(label, f.name) for label, f, _ in run.identifications] == [
        ("free", "id_free"),
        ("hand", "id_hand"),
    ]
    assert [(s.name, run.rel(s.folder)) for s in run.steps] == [
        ("rig", "rig"),
        ("free", "frf_free"),
        ("hand", "frf_hand"),
        ("identify", "id_free"),
        ("identify", "id_hand"),
        ("predict", "predict"),
    ]
    # the compare run found beside them holds the same supports' models: left out, said
    assert [(run.rel(f), why) for f, why in run.left_out] == [
        ("cmp", "identify=id_free given"),
        ("serve", "predict=predict given"),
    ]
    assert write_report(lab, steps=steps) == lab / "report.html"


@pytest.mark.parametrize(
    ("steps", "words"),
    [
        ({"predict": "rig"}, "`steps` predict=rig: rig holds a rig run"),
        ({"predict": "nowhere"}, "`steps` predict=nowhere: no folder"),
        ({"predikt": "serve"}, "`steps` predikt=serve: serve holds a predict run, and predikt"),
        ({"free": "serve"}, "`steps` free=serve: serve holds a predict run"),
    ],
)
def test_a_wrong_step_is_one_line(lab: Path, steps: dict[str, str], words: str) -> None:
    with pytest.raises(InputError) as error:
        RunFolder.scan(lab, steps=steps)
    assert words in str(error.value)
    assert "\n" not in str(error.value)


def test_steps_from_the_command_line_name_the_option(
    lab: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    capsys.readouterr()
    assert main(["report", str(lab), "--steps", "predict=rig"]) == 2
    error = " ".join(capsys.readouterr().err.split())
    assert "--steps predict=rig: rig holds a rig run" in error
    assert main(["report", str(lab), "--steps", "predict"]) == 2
    error = " ".join(capsys.readouterr().err.split())
    assert "--steps" in error
    assert "NAME=FOLDER" in error


@pytest.mark.slow
def test_a_step_the_report_has_no_section_for_is_said_left_out(tmp_path: Path) -> None:
    """A new user's ``ball`` run beside their steps was neither shown nor listed as left out:
    the page kept silent about a folder of theirs."""
    assert main(["ball", "--speed", "10", "--out", str(tmp_path / "ball")]) == 0
    argv = ["predict", "--grid", "3", "--speed", "20", "--no-figures"]
    assert main([*argv, "--out", str(tmp_path / "predict")]) == 0
    run = RunFolder.scan(tmp_path)
    assert [run.rel(s.folder) for s in run.steps] == ["predict"]
    assert [(run.rel(f), why) for f, why in run.left_out] == [
        ("ball", "the report has no section for `ball` runs (its ball.csv and figure stand alone)")
    ]
