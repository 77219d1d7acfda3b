"""A Python caller's slips name the function, the parameter and the object to use (new-user
trial of the Python API, 2026-11-27, eighth session: each reproduced first)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.errors import InputError
from racketdyn.io.racket_file import default_racket
from racketdyn.workflows import (
    PredictOptions,
    RigOptions,
    Setup,
    run_oblique,
    run_predict,
    run_rig,
)


@pytest.mark.parametrize(
    ("step", "keyword", "options"),
    [
        (run_predict, {"speeds": [20.0]}, "PredictOptions"),
        (run_rig, {"averages": 4}, "RigOptions"),
        (run_oblique, {"spin_radps": 100.0}, "ObliqueOptions"),
    ],
)
def test_an_old_keyword_names_the_step_and_its_options_object(
    tmp_path: Path, step: object, keyword: dict[str, object], options: str
) -> None:
    with pytest.raises(TypeError) as caught:
        step(tmp_path / "out", Setup(), **keyword)  # type: ignore[operator]
    name = next(iter(keyword))
    message = str(caught.value)
    assert step.__name__ in message  # type: ignore[attr-defined]
    assert f"{options}({name}=" in message
    assert not (tmp_path / "out").exists()


def test_options_in_the_setups_place_are_named(tmp_path: Path) -> None:
    with pytest.raises(TypeError) as caught:
        run_predict(tmp_path / "out", PredictOptions(speeds=[20.0]))  # type: ignore[arg-type]
    message = str(caught.value)
    for word in ("run_predict", "`setup`", "Setup", "PredictOptions"):
        assert word in message
    with pytest.raises(TypeError, match=r"`options`.*PredictOptions.*RigOptions"):
        run_predict(tmp_path / "out", Setup(), RigOptions())  # type: ignore[arg-type]
    assert not (tmp_path / "out").exists()


def test_an_uncertainty_given_as_a_file_name_says_what_to_build(tmp_path: Path) -> None:
    options = PredictOptions(speeds=[20.0], uncertainty="unc.toml")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"`uncertainty`.*Uncertainty.*read_spreads"):
        run_predict(tmp_path / "out", Setup(), options)


def test_selection_rules_of_the_wrong_type_are_named() -> None:
    from racketdyn.modal import select_poles

    with pytest.raises(TypeError, match=r"`rules`.*SelectionRules"):
        select_poles(None, rules={"min_fraction": 0.5})  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (lambda r: replace(r, strings=replace(r.strings, tension_n=52.0)), "tension_n"),
        (lambda r: replace(r, mass_kg=300.0), "mass_kg"),
    ],
)
def test_a_racket_built_in_python_meets_the_file_checks(
    tmp_path: Path, change: object, words: str
) -> None:
    """A tension in lbf or a mass in grams is refused from Python as from a racket file."""
    racket = change(default_racket())  # type: ignore[operator]
    with pytest.raises(InputError, match=words):
        run_predict(tmp_path / "out", Setup(racket=racket), PredictOptions(speeds=[20.0]))
    allowed = Setup(racket=change(default_racket()), allow_implausible=True)  # type: ignore[operator]
    if words == "tension_n":  # plausible limits hold it; the override takes it
        result = run_predict(tmp_path / "ok", allowed, PredictOptions(speeds=[20.0]))
        assert np.isfinite(result.approximate.rebound_ratio).any()


def test_the_built_in_racket_from_python_passes() -> None:
    rd.workflows.inputs.setup(default_racket(), allow_implausible=False)


def test_only_the_runs_own_impacts_are_counted_on_the_console(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """The figures' own impacts (the paper's curves, the axis) were counted too: "76 of 276
    impacts …" beside the run's 138."""
    import logging

    with caplog.at_level(logging.WARNING):
        run_predict(tmp_path / "out", Setup(), PredictOptions(speeds=[20.0]))
    counts = [r.getMessage() for r in caplog.records if "(their results are NaN)" in r.getMessage()]
    assert counts
    assert all(" of 138 impacts: " in message for message in counts), counts


def test_one_support_as_a_string_and_one_shown_speed_as_a_number(tmp_path: Path) -> None:
    """As ``rd.predict`` takes them: ``supports="free"`` was read letter by letter ("got 'f'")
    and ``show=20.0`` was a TypeError in ``impact/result.py``."""
    result = run_predict(
        tmp_path / "out", Setup(), PredictOptions(speeds=[10.0, 20.0], supports="free", show=20.0)
    )
    assert list(result.approximate.supports) == ["free"]
    assert result.shown_speed == 1


def test_an_oblique_point_of_one_number_is_one_line(tmp_path: Path) -> None:
    from racketdyn.workflows import ObliqueOptions, run_oblique

    with pytest.raises(InputError, match="`point`"):
        run_oblique(tmp_path / "out", Setup(), ObliqueOptions(point=(0.505,)))  # type: ignore[arg-type]


def test_selection_rules_name_their_field_and_refuse_a_zero_damping_limit() -> None:
    from racketdyn.modal import SelectionRules

    with pytest.raises(InputError, match="`max_damping_ratio`"):
        SelectionRules(max_damping_ratio=0.0)
    with pytest.raises(InputError, match="`min_fraction` must be a number"):
        SelectionRules(min_fraction="0.5")  # type: ignore[arg-type]


def test_a_run_folder_that_is_not_there_is_named(tmp_path: Path) -> None:
    """``read_step_data("predcit")`` returned {} and the draw then said "not all given"."""
    from racketdyn.workflows.figure_data import read_step_data

    with pytest.raises(InputError, match="predcit"):
        read_step_data(tmp_path / "predcit")
    assert read_step_data(tmp_path) == {}  # a folder without figures.nc: nothing to draw


def test_an_unknown_figure_id_names_the_results_own(tmp_path: Path) -> None:
    """``result.plot("fig15")`` listed all 34 ids of every step."""
    result = run_predict(tmp_path / "out", Setup(), PredictOptions(speeds=[20.0]))
    with pytest.raises(KeyError) as caught:
        result.plot("fig15")
    message = str(caught.value)
    assert "fig15_rebound_along_axis" in message
    assert "stabilisation" not in message  # identify's, not this result's


def test_identify_names_rules_of_the_wrong_type_before_computing() -> None:
    from racketdyn.modal import identify
    from racketdyn.testing import beam_frfs

    test = beam_frfs(np.linspace(0.0, 0.8, 3), reference_s=0.0)
    with pytest.raises(TypeError, match=r"identify: `rules`.*SelectionRules"):
        identify(test.frfs, rules={"min_fraction": 0.5})  # type: ignore[arg-type]


@pytest.mark.slow
def test_rig_options_take_the_command_lines_spelling(tmp_path: Path) -> None:
    """``RigOptions(support="free,hand")`` and ``layout="roving-accelerometer"``, as the
    command line spells them, were refused from Python (``support must be one of free, hand
    (got 'free,hand')``); both are taken, and written in one spelling."""
    import json

    options = RigOptions(support="free,hand", averages=1, layout="roving-accelerometer")
    result = run_rig(tmp_path / "rig", Setup(), options)
    assert result.supports == ["free", "hand"]
    record = json.loads((tmp_path / "rig" / "run.json").read_text(encoding="utf-8"))
    assert record["layout"] == "roving accelerometer"
    with pytest.raises(InputError, match=r"`support`.*once"):
        run_rig(tmp_path / "twice", Setup(), RigOptions(support=("free", "free")))


@pytest.mark.parametrize(
    ("options", "field", "given"),
    [
        ({"pin_hz": "600"}, "pin_hz", (600.0,)),
        ({"pin_hz": 600.0}, "pin_hz", (600.0,)),
        ({"exclude_hz": "600,700.5"}, "exclude_hz", (600.0, 700.5)),
        ({"band_hz": "40,1000"}, "band_hz", (40.0, 1000.0)),
    ],
)
def test_identify_options_take_the_command_lines_spelling(
    options: dict[str, object], field: str, given: tuple[float, ...]
) -> None:
    """``IdentifyOptions(pin_hz="600")`` pinned 6, 0 and 0 Hz (the text read letter by
    letter); ``pin_hz=600.0`` and ``band_hz="40,1000"`` were bare TypeError/ValueError."""
    from racketdyn.workflows.identify import IdentifyOptions

    assert getattr(IdentifyOptions(**options), field) == given  # type: ignore[arg-type]


def test_identify_options_name_what_is_not_a_frequency() -> None:
    from racketdyn.workflows.identify import IdentifyOptions

    with pytest.raises(InputError, match=r"`pin_hz`: 'x' is not a number"):
        IdentifyOptions(pin_hz="600,x")


def test_predict_options_take_the_command_lines_spelling(tmp_path: Path) -> None:
    """``PredictOptions(supports="free,pinned", speeds="10,20")``: the command line's
    spelling, refused before (``supports must be one of …``)."""
    options = PredictOptions(speeds="10,20", supports="free,pinned", grid=3)  # type: ignore[arg-type]
    result = run_predict(tmp_path / "out", Setup(figures=None), options)
    assert list(result.approximate.supports) == ["free", "pinned"]
    assert list(result.speeds) == [10.0, 20.0]


def test_oblique_options_take_the_command_lines_spelling(tmp_path: Path) -> None:
    """``ObliqueOptions(angles_deg="0,30", point="0.505,0")``, the command line's spelling,
    was read as one angle ``'0,30'`` ("must be a number") and refused as a point."""
    from racketdyn.workflows import ObliqueOptions

    options = ObliqueOptions(angles_deg="0,30", point="0.505,0")  # type: ignore[arg-type]
    result = run_oblique(tmp_path / "out", Setup(figures=None), options)
    assert result.curve is not None
    np.testing.assert_array_equal(result.curve.incoming_angle_deg, [0.0, 30.0])
    assert result.point == (0.505, 0.0)


@pytest.mark.parametrize(
    ("options", "command_line"),
    [
        ({"friction": -0.4}, "--friction=-0.4"),
        ({"friction": "x"}, "--friction=nan"),
        ({"tangential_stiffness": -1e4}, "--tangential-stiffness=-1e4"),
    ],
)
def test_oblique_contact_errors_name_the_parameter_and_the_cli_its_flag(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    options: dict[str, object],
    command_line: str,
) -> None:
    """``ObliqueOptions(friction=-0.4)`` said "friction coefficient must be …", which names
    neither the parameter nor the option (new-user trial, 2026-11-27, eighth session)."""
    from racketdyn.cli import main
    from racketdyn.workflows import ObliqueOptions

    with pytest.raises(InputError) as caught:
        run_oblique(tmp_path / "py", Setup(), ObliqueOptions(**options))  # type: ignore[arg-type]
    message = str(caught.value)
    assert f"`{next(iter(options))}`" in message
    assert "--" not in message
    assert main(["oblique", command_line, "--no-figures", "--out", str(tmp_path / "cli")]) == 2
    said = capsys.readouterr().err
    assert command_line.split("=")[0] in said
    assert "`" not in said


@pytest.mark.parametrize(
    ("field", "value"),
    [("friction_coefficient", -0.4), ("stiffness_n_per_m", -1e4), ("inertia_factor", 0.0)],
)
def test_a_tangential_contact_names_its_field(field: str, value: float) -> None:
    from racketdyn.impact.oblique import TangentialContact

    with pytest.raises(InputError, match=f"`{field}`"):
        TangentialContact(**{field: value})


def test_a_racket_built_in_python_is_checked_by_the_public_check() -> None:
    """``rd.predict`` trusts its caller (as numpy does: sweeps, uncertainty samples and tests
    build unusual rackets on purpose); the check the steps run is public and says so, a
    300 kg racket named by its field."""
    import racketdyn.io as rio

    with pytest.raises(InputError, match="mass_kg"):
        rio.check_racket(replace(default_racket(), mass_kg=300.0))
    rio.check_racket(default_racket())
    assert "check_racket" in (rd.predict.__doc__ or "")
