"""An ``identify --ball-at`` run in a lab's folder (docs/commands/rig.md: ``rig --ball-at`` →
``frf`` → ``identify … --ball-at``) is the model of the racket with the ball on its strings,
not its support's racket model.  New-user trial, ninth session: ``report . --steps rig=lab``
printed "id_ball: left out (compare holds the free model)"; without a compare run beside it
the folder was refused as a second identify run of the free support.

The folders are run.json files and the CSVs the choice reads, written by hand (the choice reads
nothing else; the real chain is minutes of CPU)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from costly import costly
from racketdyn.report.folder import RunFolder
from racketdyn.report.sections import compound

BALL_AT = [0.51, 0.0]
BALL_HZ = 91.6306


def _step(folder: Path, command: list[str], files: dict[str, str], **record: object) -> None:
    folder.mkdir(parents=True)
    argv = ["racketdyn", *command, "--out", folder.name]
    (folder / "run.json").write_text(json.dumps({"command": argv, **record}), encoding="utf-8")
    for name, text in files.items():
        (folder / name).write_text(text, encoding="utf-8")


MODES = "mode,frequency_hz,damping_ratio,name,kind\n2,165,0.005,2-node bending,bending\n"
BALL_MODES = (
    f"mode,frequency_hz,damping_ratio,name,kind\n1,{BALL_HZ},0.057,ball on the strings,other\n"
)


@pytest.fixture
@costly
def lab(tmp_path: Path) -> Path:
    """id_free and id_ball: identify runs of the free racket, the second with the ball."""
    _step(
        tmp_path / "id_free",
        ["identify", "frfs.uff", "--support", "free"],
        {"modes.csv": MODES},
        support="free",
    )
    _step(
        tmp_path / "id_ball",
        ["identify", "frfs.uff", "--support", "free", "--ball-at", "0.51,0"],
        {"modes.csv": MODES + BALL_MODES.split("\n", 1)[1]},
        support="free",
        ball_at_m=BALL_AT,
    )
    return tmp_path


def test_beside_compare_runs_it_is_left_out_for_the_right_reason(lab: Path) -> None:
    _step(
        lab / "cmp",
        ["compare", "a.uff", "b.uff"],
        {"modes_free.csv": MODES, "modes_hand.csv": MODES},
    )
    _step(
        lab / "compare_ball",
        ["compare", "a.uff", "c.uff", "--ball-at", "0.51,0"],
        {"modes_alone.csv": MODES, "modes_ball.csv": BALL_MODES, "ball_comparison.csv": "mode\n"},
        ball_at_m=BALL_AT,
    )
    run = RunFolder.scan(lab)
    assert sorted((run.rel(f), why) for f, why in run.left_out) == [
        ("id_ball", "compare_ball holds the ball-on-strings model"),
        ("id_free", "cmp holds the free model"),
    ]


def test_alone_it_is_the_ball_model_and_its_ball_mode_is_shown(lab: Path) -> None:
    run = RunFolder.scan(lab)
    assert sorted((label, f.name) for label, f, _ in run.identifications) == [
        ("ball", "id_ball"),
        ("free", "id_free"),
    ]
    assert run.ball_identification == lab / "id_ball"
    header = "support,mode,frequency_hz,damping_ratio,ball_to_frame_ratio,half_period_s\n"
    _step(
        lab / "compound",
        ["compound"],
        {"compound.csv": header + "free,ball on the strings,95,0.05,0.9,0.00526\n"},
    )
    data = compound.gather(RunFolder.scan(lab))
    assert data is not None
    assert any(
        s.startswith(f"measured (identify --ball-at): a new mode at {BALL_HZ:.1f} Hz")
        for s in data["statements"]
    )
