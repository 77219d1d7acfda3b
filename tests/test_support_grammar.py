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


def test_library_functions_take_the_command_lines_comma_separated_supports(
    tmp_path: Path,
) -> None:
    """New-user trial (2026-11-27, ninth session): ``PredictOptions(supports="free,pinned")``
    took the command line's spelling while ``rd.predict(..., supports="free,pinned")`` read one
    support named "free,pinned" ("must be one of free, pinned"), ``run_compound`` and
    ``run_twist`` read a text letter by letter, ``simulate_histories``, ``propagate`` and
    ``SweepSpec`` likewise."""
    import racketdyn as rd
    from racketdyn.impact.comparison import simulate_histories
    from racketdyn.impact.samples import ModelInputs
    from racketdyn.impact.swing import Swing, predict_swing
    from racketdyn.impact.transient import predict_transient
    from racketdyn.impact.uncertainty import Spread, Uncertainty, propagate
    from racketdyn.sweep.spec import SweepSpec
    from racketdyn.workflows import Setup, run_compound, run_twist

    racket, ball = rd.default_racket(), rd.Ball()
    point = [(racket.head.centre_x_m, 0.0)]
    both = ("free", "pinned")
    assert rd.predict(racket, ball, point, [20.0], "free, pinned").supports == both
    transient = predict_transient(racket, ball, point, [20.0], "free,pinned", engine="reference")
    assert transient.supports == both
    swung = predict_swing(racket, ball, point, [20.0], Swing(), supports="free,pinned")
    assert swung.supports == both
    history = simulate_histories(racket, ball, {"centre": point[0]}, 20.0, "free,hand")
    assert [h.support for h in history] == ["free", "hand"]
    spread = Uncertainty((Spread("e_bg", bounds=(0.82, 0.86)),), samples=8)
    banded = propagate(ModelInputs(racket, ball), point, [20.0], spread, supports="free,pinned")
    assert banded.nominal.supports == both
    sweep = SweepSpec(racket=racket, ball=ball, locations=point, ball_speeds=[20.0],
                      supports="free,pinned")  # type: ignore[arg-type]  # fmt: skip
    assert sweep.supports == both
    quiet = Setup()  # no figures
    compound = run_compound(tmp_path / "c", quiet, supports="free,hand")
    assert compound.supports == ["free", "hand"]
    twist = run_twist(tmp_path / "t", quiet, offsets_m=[0.0], supports="free,hand")
    assert [curve.support for curve in twist.curves] == ["free", "hand"]
