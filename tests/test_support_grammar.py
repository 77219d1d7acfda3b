"""One grammar for ``--support`` (issue 27).

The new-user trial found ``--support`` a list in ``predict`` and ``twist`` but one value in
``oblique`` and ``swing`` (``swing --support free,pinned``: "must be one of free, pinned (got
'free,pinned')"), ``--model both`` refusing ``hand`` with the approximate method's message,
the page calling ``pinned`` "hand-held (pinned at grip)" beside the rig's ``hand``, and
``twist`` defaulting to the paper racket's x = 0.52 m whatever racket was given.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from racketdyn.cli import main
from racketdyn.racket import SUPPORT_NAMES, landmark_points


def _error(capsys: pytest.CaptureFixture[str], argv: list[str]) -> str:
    capsys.readouterr()
    assert main(argv) == 2
    captured = capsys.readouterr()
    error = captured.err.strip()
    assert error.count("racketdyn: error:") == 1
    return " ".join(error.split())


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (
            ["swing", "--support", "free,pinned", "--grid", "3"],
            "--support free,pinned: swing takes one support",
        ),
        (
            ["oblique", "--support", "free,hand", "--angles", "0"],
            "--support free,hand: oblique takes one support",
        ),
    ],
)
def test_one_support_commands_say_why_given_several(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, argv: list[str], words: str
) -> None:
    error = _error(capsys, [*argv, "--no-figures", "--out", str(tmp_path / "out")])
    assert words in error
    assert "once per support" in error  # what to do instead
    assert "must be one of" not in error
    assert not (tmp_path / "out").exists()


def test_model_both_with_hand_says_why(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    argv = ["predict", "--model", "both", "--support", "free,hand", "--grid", "2"]
    error = _error(capsys, [*argv, "--out", str(tmp_path / "p")])
    assert "--support hand with --model both" in error
    assert "the approximate method has no hand" in error
    assert "--model transient" in error


def test_one_name_for_each_support() -> None:
    from racketdyn.plotting.primitives import SUPPORT_STYLE
    from racketdyn.report.figures import SUPPORT_WORDS, run_words

    assert SUPPORT_NAMES["pinned"] == "pinned at the grip"
    assert "hand-held" in SUPPORT_NAMES["hand"]
    assert "hand-held" not in SUPPORT_NAMES["pinned"]
    for support, style in SUPPORT_STYLE.items():
        assert style["label"] == SUPPORT_NAMES[support]
    for support, name in SUPPORT_WORDS.items():
        assert name == SUPPORT_NAMES[support]
    words = run_words({"speeds_mps": [20.0], "supports": ["free", "pinned"]})
    assert words["approximate_supports"] == "freely supported and pinned at the grip"


def test_twist_defaults_to_the_given_racket_s_face_centre(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from racketdyn.io import default_racket

    centre = landmark_points(default_racket())["centre"][0]
    assert abs(centre - 0.52) > 0.005  # the paper racket's x = 0.52 m is not its centre
    capsys.readouterr()
    argv = ["twist", "--offsets", "0", "--speed", "20", "--no-figures"]
    assert main([*argv, "--out", str(tmp_path / "t")]) == 0
    out = " ".join(capsys.readouterr().out.split())
    record = json.loads((tmp_path / "t" / "run.json").read_text(encoding="utf-8"))
    assert record["x_m"] == pytest.approx(centre)
    assert f"twist at x = {centre * 1e3:.0f} mm" in out
    assert any("face centre" in d for d in record["defaults_used"])
