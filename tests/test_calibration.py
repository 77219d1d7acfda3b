"""Validation and calibration against measured rebound (issue 15): predictions at measured
rows agree with the grid predictions, a calibration recovers a known truth within its standard
errors, and a parameter the points cannot tell is reported so."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from racketdyn.ball import Ball
from racketdyn.cli import main
from racketdyn.cli.calibrate import PARAMETER_NAMES
from racketdyn.errors import InputError
from racketdyn.impact import predict
from racketdyn.impact.calibration import PARAMETERS, apply, calibrate, simulate_measurements
from racketdyn.impact.measured import NO_HAND_STATUS, ModelInputs, predict_rows
from racketdyn.impact.transient import predict_transient
from racketdyn.io import load_racket, read_measured
from racketdyn.io.racket_file import default_racket
from racketdyn.racket_modal import modal_model_for

FACE = [
    (0.45, 0.0),
    (0.50, 0.0),
    (0.55, 0.0),
    (0.60, 0.0),
    (0.50, 0.06),
    (0.55, -0.06),
    (0.45, 0.05),
    (0.60, 0.04),
]
AXIS = [(0.42, 0.0), (0.47, 0.0), (0.52, 0.0), (0.57, 0.0), (0.62, 0.0)]
FIT = ("e_bg", "roll_inertia_kgm2")


@pytest.fixture(scope="module")
def start() -> ModelInputs:
    return ModelInputs(default_racket(), Ball())


@pytest.fixture(scope="module")
def truth(start: ModelInputs) -> tuple[ModelInputs, dict[str, float]]:
    values = {"e_bg": 0.80, "roll_inertia_kgm2": 1.3 * start.racket.roll_inertia_kgm2}
    return apply(start, values), values


def test_the_cli_lists_every_parameter() -> None:
    assert tuple(PARAMETERS) == PARAMETER_NAMES


def test_rows_are_the_grid_predictions_of_both_models(start: ModelInputs) -> None:
    """Each row's prediction is the one predict/predict_transient give at that impact."""
    # (0.60, 0) is beyond the approximate method since issue 22 (the frame takes > 30 %)
    points = [FACE[0], FACE[1], FACE[2], FACE[4]]
    measured = simulate_measurements(start, points, [20.0, 20.0, 30.0, 20.0], sd=0.0)
    racket, model = start.racket, modal_model_for(start.racket)
    for method, function in (("approx", predict), ("transient", predict_transient)):
        rows, status = predict_rows(start, measured, method)  # type: ignore[arg-type]
        assert np.all(status == "ok")
        for i in range(len(measured)):
            grid = function(
                racket, start.ball, measured.locations[i : i + 1], [measured.ball_speed[i]],
                ["free"], modal_model=model,
            )  # fmt: skip
            assert rows[i] == pytest.approx(grid.rebound_ratio[0, 0, 0], rel=1e-9)


def test_a_moving_racket_measured_by_outgoing_speed_validates_to_zero(
    tmp_path: Path, start: ModelInputs
) -> None:
    """A file of the model's own outgoing speeds (racket moving at 5 m/s) reads back as its
    rebound ratios: the mapping v_out ↔ e is the glossary's both ways."""
    xy = np.array(FACE[:3])
    result = predict(start.racket, start.ball, xy, [20.0], ["free"], racket_speed=5.0)
    lines = ["x_m,y_m,ball_speed_mps,racket_speed_mps,support,outgoing_speed_mps"]
    lines += [
        f"{x},{y},20,5,free,{float(v)!r}"
        for (x, y), v in zip(xy, result.rebound_speed[:, 0, 0], strict=True)
    ]
    (tmp_path / "m.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    rows, _ = predict_rows(start, read_measured(tmp_path / "m.csv"), "approx")
    np.testing.assert_allclose(rows, result.rebound_ratio[:, 0, 0], rtol=1e-9)
    np.testing.assert_allclose(read_measured(tmp_path / "m.csv").rebound_ratio, rows, rtol=1e-9)


def test_hand_rows_are_flagged_for_the_approximate_method(start: ModelInputs) -> None:
    measured = simulate_measurements(start, FACE[:2], 20.0, ["free", "hand"], sd=0.0)
    ratio, status = predict_rows(start, measured, "approx")
    assert status.tolist() == ["ok", NO_HAND_STATUS]
    assert math.isfinite(ratio[0])
    assert math.isnan(ratio[1])


def test_exact_data_give_back_the_truth(
    start: ModelInputs, truth: tuple[ModelInputs, dict[str, float]]
) -> None:
    """Without noise the fit lands on the values that made the data."""
    inputs, values = truth
    measured = simulate_measurements(inputs, FACE, 20.0, sd=0.0)
    result, fitted = calibrate(start, measured, FIT)
    assert all(result.identifiable)
    for k, name in enumerate(FIT):
        assert result.value[k] == pytest.approx(values[name], rel=2e-4)
    assert result.fit_rms < 1e-5
    assert fitted.ball.e_bg == pytest.approx(0.80, rel=2e-4)


@pytest.mark.slow
def test_synthetic_truth_within_two_standard_errors(
    start: ModelInputs, truth: tuple[ModelInputs, dict[str, float]]
) -> None:
    """10 seeded trials (the 50-trial run: benchmarks/bench_calibration.py).  The truth lies
    within two standard errors (nominal 95 %) in ≥ 9 of 10 for each parameter, and the
    standard errors are tight enough to mean something (< 10 % of the value; ≈ 0.4 % for
    e_BG, ≈ 5 % for the roll inertia)."""
    inputs, values = truth
    hits = np.zeros(len(FIT))
    for seed in range(10):
        measured = simulate_measurements(inputs, FACE, 20.0, sd=0.005, rng=seed)
        result, _ = calibrate(start, measured, FIT)
        assert all(result.identifiable)
        assert np.all(result.standard_error < 0.1 * result.value)
        hits += np.abs(result.value - [values[n] for n in FIT]) <= 2 * result.standard_error
    assert np.all(hits >= 9), hits


def test_roll_inertia_from_points_on_the_axis_is_not_identifiable(
    start: ModelInputs, truth: tuple[ModelInputs, dict[str, float]]
) -> None:
    """On the long axis the racket does not roll: its roll inertia changes nothing there."""
    inputs, _ = truth
    measured = simulate_measurements(inputs, AXIS, 20.0, sd=0.005, rng=1)
    result, fitted = calibrate(start, measured, FIT)
    assert result.identifiable == [True, False]
    assert "do not change" in result.why[1] or "cannot tell" in result.why[1]
    assert math.isnan(result.values["roll_inertia_kgm2"])
    assert fitted.racket.roll_inertia_kgm2 == start.racket.roll_inertia_kgm2
    assert result.as_dict()["parameters"][1]["value"] is None
    assert result.as_dict()["parameters"][1]["status"].startswith("not identifiable")
    assert result.value[0] == pytest.approx(0.80, abs=0.02)


def test_hand_parameters_without_hand_rows_are_not_identifiable(start: ModelInputs) -> None:
    measured = simulate_measurements(start, FACE[:4], 20.0, sd=0.005, rng=2)
    result, _ = calibrate(start, measured, ["e_bg", "hand_stiffness_n_per_m"])
    assert result.identifiable == [True, False]
    assert result.why[1] == "the data do not change with it"


def test_two_parameters_the_data_trade_off_exactly(start: ModelInputs) -> None:
    """One point at one speed: e_BG and the string-bed scale both move the one ratio."""
    measured = simulate_measurements(start, [(0.5, 0.0)] * 3, 20.0, sd=0.005, rng=3)
    result, _ = calibrate(start, measured, ["e_bg", "string_stiffness_scale"])
    assert not all(result.identifiable)


def test_bad_fits_are_one_line(start: ModelInputs) -> None:
    measured = simulate_measurements(start, FACE[:3], 20.0, sd=0.005, rng=4)
    with pytest.raises(InputError, match="not a parameter"):
        calibrate(start, measured, ["stiffness"])
    with pytest.raises(InputError, match="name each parameter once"):
        calibrate(start, measured, ["e_bg", "e_bg"])
    with pytest.raises(InputError, match="rows are numbered"):
        calibrate(start, measured, ["e_bg"], holdout=[7])
    with pytest.raises(InputError, match=r"0 rows left to fit \(3 held out, 0 without"):
        calibrate(start, measured, ["e_bg"], holdout=[0, 1, 2])
    table = replace(start, ball=Ball(e_bg_table=((10.0, 0.85), (40.0, 0.78))))
    with pytest.raises(InputError, match="table against speed"):
        calibrate(table, measured, ["e_bg"])


@pytest.mark.slow
def test_validate_and_calibrate_commands(tmp_path: Path, start: ModelInputs) -> None:
    """calibrate writes calibration.json and a racket.toml predict reads; validate with the
    calibration fits the data it was fitted on better than without."""
    truth = apply(start, {"e_bg": 0.78, "roll_inertia_kgm2": 0.0018})
    measured = simulate_measurements(truth, FACE, 20.0, sd=0.004, rng=5)
    lines = ["point,x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio,rebound_ratio_sd"]
    for i in range(len(measured)):
        x, y = measured.locations[i]
        lines.append(f"p{i},{x},{y},20,0,free,{float(measured.rebound_ratio[i])!r},0.004")
    csv = tmp_path / "measured.csv"
    csv.write_text("\n".join(lines) + "\n", encoding="utf-8")
    assert main(["validate", str(csv), "--out", str(tmp_path / "before"), "--no-figures"]) == 0
    status = main(
        ["calibrate", str(csv), "--fit", "e_bg,roll_inertia_kgm2,hand_arm_mass_kg",
         "--holdout", "2,5", "--no-loo", "--out", str(tmp_path / "cal")]
    )  # fmt: skip
    assert status == 0
    record = json.loads((tmp_path / "cal" / "calibration.json").read_text())
    by_name = {p["name"]: p for p in record["parameters"]}
    assert by_name["hand_arm_mass_kg"]["value"] is None
    assert by_name["e_bg"]["value"] == pytest.approx(0.78, abs=0.01)
    assert record["rows"] == {"fitted": 6, "held_out": 2, "flagged_left_out": 0}
    assert math.isfinite(record["holdout_rms"])
    racket = load_racket(tmp_path / "cal" / "racket.toml")
    assert racket.roll_inertia_kgm2 == pytest.approx(by_name["roll_inertia_kgm2"]["value"])
    calibrated = str(tmp_path / "cal" / "calibration.json")
    after_out = str(tmp_path / "after")
    status = main(["validate", str(csv), "--calibration", calibrated, "--out", after_out])
    assert status == 0
    assert (tmp_path / "after" / "validation_parity.png").is_file()
    before = json.loads((tmp_path / "before" / "run.json").read_text())["summary"]
    after = json.loads((tmp_path / "after" / "run.json").read_text())["summary"]
    assert after["transient"]["rms"] < 0.5 * before["transient"]["rms"]
    assert after["transient"]["rms"] < 0.01


def test_validate_refuses_points_off_the_strings(tmp_path: Path) -> None:
    csv = tmp_path / "m.csv"
    csv.write_text(
        "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio\n0.2,0,20,0,free,0.3\n",
        encoding="utf-8",
    )
    assert main(["validate", str(csv), "--out", str(tmp_path / "o")]) == 2


def test_a_racket_written_as_toml_reads_back_the_same(tmp_path: Path) -> None:
    """write_racket_toml → load_racket: the same racket (point masses and files included)."""
    from racketdyn.io import write_racket_toml
    from racketdyn.racket import PointMass

    table = tmp_path / "bed.csv"
    table.write_text("deflection_m,force_n\n0,0\n0.005,150\n0.01,320\n0.02,700\n", "utf-8")
    racket = default_racket().with_point_masses(PointMass(0.004, 0.66, 0.02, "12 o'clock"))
    racket = replace(
        racket,
        roll_inertia_kgm2=0.00171,
        strings=replace(racket.strings, load_deflection_file=table),
    )
    back = load_racket(write_racket_toml(racket, tmp_path / "r.toml", "a test\nof two lines"))
    assert back == racket


def test_the_report_shows_a_validate_run(tmp_path: Path) -> None:
    """The report's section: the summary per model from run.json and the three figures."""
    from racketdyn.report import SECTIONS, write_report

    csv = tmp_path / "m.csv"
    csv.write_text(
        "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio\n"
        "0.50,0,20,0,free,0.39\n0.55,0.04,20,0,hand,0.30\n",
        encoding="utf-8",
    )
    assert main(["validate", str(csv), "--out", str(tmp_path / "run" / "validate")]) == 0
    page = write_report(tmp_path / "run").read_text(encoding="utf-8")
    start = page.index('<section id="validation">')
    section = page[start : page.index("</section>", start)]
    assert SECTIONS["validation"].title in section
    summary = json.loads((tmp_path / "run" / "validate" / "run.json").read_text())["summary"]
    assert f"{summary['transient']['rms']:.4f}" in section
    assert '<td>approximate method</td><td class="num">1</td><td class="num">1</td>' in section
    assert section.count("<figure") == 3


# --- the string bed's law at each point (issue 15, "physics that matters off-centre") ----------


def _string_force_exact(s0: float, axial: float, near: float, far: float, x: float) -> float:
    """One string pressed by x at distances near, far from its ends: exact geometry (the two
    straight segments' tension S0 + A E ΔL / L0 times the sines of their angles)."""
    one, two = math.hypot(near, x), math.hypot(far, x)
    tension = s0 + axial * (one + two - near - far) / (near + far)
    return tension * (x / one + x / two)


def test_the_local_law_of_one_string_is_its_geometry() -> None:
    """The per-string law (linear + cubic) against the exact force of a string pressed off its
    middle.  Kawazoe's form keeps the stretching (A E) and drops the tilt of the initial
    tension, −S0 X³ (1/l1³ + 1/l2³)/2 (S0/AE ≈ 4 %): the difference is that term to 10 %, and
    the law is within 0.1 % of the geometry at 1 mm and 2 % at 5 mm from the frame's 33 mm."""
    from racketdyn.contact import _stretched_string

    s0, axial = 246.0, default_racket().strings.axial_stiffness_n
    for near, far in ((0.165, 0.165), (0.05, 0.28), (0.0335, 0.2)):
        linear, cubic = _stretched_string(s0, axial, near, far)
        for x, tolerance in ((0.001, 1e-3), (0.005, 2e-2)):
            exact = _string_force_exact(s0, axial, near, far, x)
            law = linear * x + cubic * x**3
            assert law == pytest.approx(exact, rel=tolerance)
            dropped = -s0 * x**3 * (1 / near**3 + 1 / far**3) / 2
            assert exact - law == pytest.approx(dropped, rel=0.1)


def test_the_local_law_is_the_face_law_at_the_centre_and_stiffer_towards_the_frame() -> None:
    from racketdyn.contact import local_string_bed_law, string_bed_law

    racket, ball = default_racket(), Ball()
    head = racket.head
    centre = (head.centre_x_m, head.centre_y_m)
    assert local_string_bed_law(racket, ball, centre).coefficients == pytest.approx(
        string_bed_law(racket, ball).coefficients, rel=1e-12
    )

    def stiffness(x: float, y: float) -> float:
        return float(local_string_bed_law(racket, ball, (x, y)).stiffness(0.0))

    along = [stiffness(head.centre_x_m + d, 0.0) for d in (0.0, 0.04, 0.08, 0.12, 0.14)]
    assert np.all(np.diff(along) > 0)
    across = [stiffness(head.centre_x_m, d) for d in (0.0, 0.03, 0.06, 0.09)]
    assert np.all(np.diff(across) > 0)
    assert stiffness(0.55, 0.05) == pytest.approx(stiffness(0.55, -0.05), rel=1e-12)
    # spread over the ball's width, the centre's law is 1 % stiffer: the mains under the ball's
    # edge are shorter
    spread = local_string_bed_law(racket, ball, centre, samples=5).stiffness(0.0)
    assert float(spread) / along[0] == pytest.approx(1.01, abs=0.01)
    with pytest.raises(InputError, match="off the bed"):
        local_string_bed_law(racket, ball, (0.2, 0.0))


def test_the_local_law_changes_the_rebound_near_the_frame_only(start: ModelInputs) -> None:
    """Both models: at the centre nothing changes; within 50 mm of it under 0.003 of ratio (0.0022
    at 55 mm towards the throat, approximate, since issue 22's stiffer ball); at
    630 mm on the axis the stiffer bed lowers the rebound ratio (transient, free: ≈ −0.02)."""
    points = [(0.505, 0.0), (0.45, 0.0), (0.55, 0.0), (0.505, 0.04), (0.63, 0.0)]
    measured = simulate_measurements(start, points, 20.0, sd=0.0)
    local = replace(start, string_bed="local")
    for method in ("approx", "transient"):
        face, _ = predict_rows(start, measured, method)  # type: ignore[arg-type]
        each, _ = predict_rows(local, measured, method)  # type: ignore[arg-type]
        assert each[0] == pytest.approx(face[0], abs=1e-12)
        assert np.all(np.abs(each[1:4] - face[1:4]) < 3e-3)
        if method == "transient":
            assert each[4] < face[4] - 0.01
        else:  # 630 mm is beyond the approximate method since issue 22 (the frame takes > 30 %)
            assert np.isnan(each[4])
            assert np.isnan(face[4])


def test_the_hand_is_not_identifiable_from_rebound_at_20_mps() -> None:
    """The ball leaves the strings before the hand's springs act (≈ 4 ms against the hand's
    period): rebound ratios of a held racket, even with the truth's hand 3× as stiff and a
    2 kg arm, cannot give the hand's stiffness or the arm's mass; e_BG they give."""
    from racketdyn.impact.hand import Hand

    start = ModelInputs(default_racket(), Ball(), Hand())
    truth = apply(start, {"hand_stiffness_n_per_m": 6e4, "hand_arm_mass_kg": 2.0})
    measured = simulate_measurements(truth, FACE, 20.0, "hand", sd=0.005, rng=0)
    result, _ = calibrate(start, measured, ["e_bg", "hand_stiffness_n_per_m", "hand_arm_mass_kg"])
    assert result.identifiable == [True, False, False]
    assert result.value[0] == pytest.approx(0.83, abs=0.01)


def test_calibrate_predicts_every_row_once_before_and_once_after(
    tmp_path: Path, start: ModelInputs, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The workflow takes the before/after predictions the fit made, not a second run of the
    model over every row (a transient model over every row costs as much as the fit's step)."""
    import racketdyn.impact.calibration as calibration_module
    from racketdyn.workflows.calibrate import run_calibrate

    measured = simulate_measurements(start, FACE, 20.0, method="approx", rng=3)
    whole: list[int] = []

    def counted(inputs: ModelInputs, rows: object, method: str) -> object:
        if len(rows) == len(measured):  # type: ignore[arg-type]
            whole.append(1)
        return predict_rows(inputs, rows, method)  # type: ignore[arg-type]

    monkeypatch.setattr(calibration_module, "predict_rows", counted)
    import racketdyn.workflows.calibrate as workflow_module

    if hasattr(workflow_module, "predict_rows"):
        monkeypatch.setattr(workflow_module, "predict_rows", counted)
    result = run_calibrate(
        tmp_path / "cal", measured, ["e_bg"], holdout=[1], method="approx", leave_one_out=False
    )
    assert len(whole) == 2  # the start and the fitted inputs, over every row
    np.testing.assert_allclose(
        result.after - measured.rebound_ratio, result.calibration.residual_fit
    )


def test_the_record_names_only_the_fitted_values_racket_toml_holds(
    tmp_path: Path, start: ModelInputs
) -> None:
    """calibration.json says which fitted values racket.toml carries: none for e_bg alone."""
    from racketdyn.workflows.calibrate import run_calibrate

    measured = simulate_measurements(start, FACE, 20.0, method="approx", rng=4)
    only_e = run_calibrate(tmp_path / "e", measured, ["e_bg"], method="approx", leave_one_out=False)
    said = json.loads((only_e.out / "calibration.json").read_text())["calibrated_files"]
    assert "roll inertia" not in said["racket.toml"]
    assert "string" not in said["racket.toml"]
    both = run_calibrate(
        tmp_path / "r", measured, ["e_bg", "roll_inertia_kgm2"], method="approx",
        leave_one_out=False,
    )  # fmt: skip
    said = json.loads((both.out / "calibration.json").read_text())["calibrated_files"]
    assert "roll inertia" in said["racket.toml"]
    assert "string" not in said["racket.toml"]


def test_a_calibration_value_the_model_refuses_names_the_calibration_file(tmp_path: Path) -> None:
    from racketdyn.workflows.validate import run_validate

    measured = tmp_path / "measured.csv"
    measured.write_text(
        "x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio\n0.5,0,20,0,free,0.4\n",
        encoding="utf-8",
    )
    damaged = tmp_path / "calibration.json"
    damaged.write_text(json.dumps({"parameters": [{"name": "e_bg", "value": -3.0}]}))
    with pytest.raises(InputError, match=r"^`calibration` .*calibration\.json: .*e_bg"):
        run_validate(tmp_path / "out", measured, calibration=damaged)


def test_a_normal_prior_weighs_the_start_against_the_data(start: ModelInputs) -> None:
    """Issue 24: an uncertainty file's normal spread as a prior about the start.  One e_BG
    from rows whose truth is 0.80, the start 0.83 (the built-in ball's): a prior far wider than
    the data's standard error changes nothing; one far narrower keeps the start; one equal to
    it lands halfway (the linear limit: the precision-weighted mean) with a standard error
    1/√2 of the data's alone."""
    truth = apply(start, {"e_bg": 0.80})
    measured = simulate_measurements(truth, FACE, 20.0, sd=0.005, rng=11)
    alone, _ = calibrate(start, measured, ["e_bg"])
    e0, se = PARAMETERS["e_bg"].get(start), float(alone.standard_error[0])
    wide, _ = calibrate(start, measured, ["e_bg"], priors={"e_bg": 100 * se})
    assert wide.value[0] == pytest.approx(alone.value[0], abs=0.01 * se)
    narrow, _ = calibrate(start, measured, ["e_bg"], priors={"e_bg": se / 100})
    assert narrow.value[0] == pytest.approx(e0, abs=0.01 * abs(e0 - alone.value[0]))
    equal, _ = calibrate(start, measured, ["e_bg"], priors={"e_bg": se})
    halfway = 0.5 * (e0 + alone.value[0])
    assert equal.value[0] == pytest.approx(halfway, abs=0.05 * abs(e0 - alone.value[0]))
    assert equal.standard_error[0] == pytest.approx(se / math.sqrt(2), rel=0.05)
    assert equal.as_dict()["parameters"][0]["prior_sd"] == se
    assert alone.as_dict()["parameters"][0]["prior_sd"] is None


def test_a_prior_does_not_make_a_parameter_identifiable(start: ModelInputs) -> None:
    """The roll inertia from points on the axis: the data cannot tell it, with or without a
    prior; it stays at its start (the prior's mean), and e_BG is fitted as without."""
    measured = simulate_measurements(start, AXIS, 20.0, sd=0.005, rng=1)
    sd = 0.1 * start.racket.roll_inertia_kgm2
    result, fitted = calibrate(start, measured, FIT, priors={"roll_inertia_kgm2": sd})
    assert result.identifiable == [True, False]
    assert fitted.racket.roll_inertia_kgm2 == start.racket.roll_inertia_kgm2


def test_priors_need_the_rows_standard_deviations(start: ModelInputs) -> None:
    measured = simulate_measurements(start, FACE[:3], 20.0, sd=0.0)
    with pytest.raises(InputError, match="rebound_ratio_sd"):
        calibrate(start, measured, ["e_bg"], priors={"e_bg": 0.01})
    with pytest.raises(InputError, match="sd above 0"):
        calibrate(start, measured, ["e_bg"], priors={"e_bg": -1.0})


def test_calibrate_takes_an_uncertainty_files_normal_spread_as_a_prior(
    tmp_path: Path, start: ModelInputs
) -> None:
    """``calibrate --uncertainty``: a normal spread is the fitted parameter's prior (recorded
    in calibration.json), a range its bounds; rows without a standard deviation leave the
    prior out and say so."""
    truth = apply(start, {"e_bg": 0.80})
    measured = simulate_measurements(truth, FACE[:4], 20.0, sd=0.005, rng=7)
    header = "point,x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio"
    rows = [(f"p{i},{x},{y},20,0,free,{float(e)!r}") for i, ((x, y), e) in
            enumerate(zip(measured.locations, measured.rebound_ratio, strict=True))]  # fmt: skip
    with_sd = tmp_path / "with_sd.csv"
    with_sd.write_text(
        "\n".join([header + ",rebound_ratio_sd", *(r + ",0.005" for r in rows)]) + "\n", "utf-8"
    )
    spreads = tmp_path / "u.toml"
    spreads.write_text("[e_bg]\nsd = 0.01\n", encoding="utf-8")
    argv = ["calibrate", "--fit", "e_bg", "--no-loo", "--uncertainty", str(spreads)]
    assert main([*argv[:1], str(with_sd), *argv[1:], "--out", str(tmp_path / "a")]) == 0
    record = json.loads((tmp_path / "a" / "calibration.json").read_text())
    assert record["parameters"][0]["prior_sd"] == 0.01
    bare = tmp_path / "bare.csv"
    bare.write_text("\n".join([header, *rows]) + "\n", "utf-8")
    assert main([*argv[:1], str(bare), *argv[1:], "--out", str(tmp_path / "b")]) == 0
    record = json.loads((tmp_path / "b" / "calibration.json").read_text())
    assert record["parameters"][0]["prior_sd"] is None
