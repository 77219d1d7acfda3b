"""``racketdyn predict --model transient|both``: the transient model's files, the comparison
table against an independent recomputation, the time histories against Newton's second law,
and the approximate method against the transient simulation at the face centre.

Small grids (a few points, two speeds) keep these fast with either engine.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

import racketdyn as rd
import racketdyn.workflows.predict as predict_step
from racketdyn.cli import main
from racketdyn.impact.comparison import COMPARED, COMPARISON_COLUMNS, HISTORY_COLUMNS
from racketdyn.impact.result import CSV_COLUMNS, STATUS_FROM_TRANSIENT

CENTRE = (0.505, 0.0)  # face centre of the built-in racket, m
OFF_AXIS = (0.45, 0.06)
POINTS = "point,x_m,y_m\ncentre,0.505,0.0\ntip,0.62,0.0\noff,0.45,0.06\n"

# Approximate against transient rebound ratio at the face centre, 20 m/s, built-in racket and
# modes: measured 0.374 (approximate, period reading) against 0.378 (transient), free; 0.379
# against 0.384 pinned (docs/develop.md, "Transient vs approximate"): about 1 %.  The documented
# tolerance of the approximate method at the centre is 5 %: the half-sine and the charge of the
# vibration energy hold where the vibration is small (0.01 J of 11.5 J at the centre).
CENTRE_TOLERANCE = 0.05


def _read(path: Path) -> list[dict[str, str]]:
    with path.open(newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def _header(path: Path) -> list[str]:
    with path.open(newline="", encoding="utf-8") as handle:
        return next(csv.reader(handle))


def _number(text: str) -> float:
    return float(text)  # "nan" reads as NaN


@pytest.fixture(scope="module")
def points(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("points") / "points.csv"
    path.write_text(POINTS, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def both(points: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """``--model both`` at three points, 10 and 20 m/s, free and pinned, no figures."""
    out = tmp_path_factory.mktemp("both")
    argv = ["predict", "--model", "both", "--points", str(points), "--speed", "10,20"]
    assert main([*argv, "--no-figures", "--out", str(out)]) == 0
    return out


def test_transient_writes_the_impact_columns(points: Path, tmp_path: Path) -> None:
    argv = ["predict", "--model", "transient", "--points", str(points), "--speed", "10,20"]
    assert main([*argv, "--support", "free", "--no-figures", "--out", str(tmp_path)]) == 0
    header = _header(tmp_path / "impact.csv")
    assert header[: len(CSV_COLUMNS)] == list(CSV_COLUMNS)
    assert header[len(CSV_COLUMNS) :] == [
        "energy_2_node_bending_j",
        "energy_3_node_bending_j",
        "energy_2_node_twisting_j",
    ]
    rows = _read(tmp_path / "impact.csv")
    assert len(rows) == 3 * 2
    assert all(row["status"] == "ok" for row in rows)
    # a racket at rest: rebound speed = rebound ratio × ball speed (the CSV's own definition)
    for row in rows:
        assert _number(row["rebound_speed_mps"]) == pytest.approx(
            _number(row["rebound_ratio"]) * _number(row["ball_speed_mps"]), rel=1e-8
        )
    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert record["model"] == "transient"
    assert record["method"] == "transient"
    assert record["engine"]["requested"] == "auto"
    assert record["engine"]["used"] in ("compiled", "reference")
    assert record["integrator"]["engine"] == record["engine"]["used"]
    assert set(record["outputs"]) == {
        "impact.csv",
        "transient_histories.csv",
        "figures.nc",
        "run.json",
    }


def test_chunks_give_the_same_table(
    points: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The progress-bar path (chunks of points, here one point each) writes the same table."""
    argv = ["predict", "--model", "transient", "--points", str(points), "--speed", "10,20"]
    assert main([*argv, "--no-figures", "--out", str(tmp_path / "one")]) == 0
    monkeypatch.setattr(predict_step, "TRANSIENT_QUIET_IMPACTS", 0)
    monkeypatch.setattr(predict_step, "TRANSIENT_FIRST_CHUNK", 1)
    monkeypatch.setattr(predict_step, "TRANSIENT_CHUNK_S", 1e-9)
    assert main([*argv, "--no-figures", "--out", str(tmp_path / "chunks")]) == 0
    one, chunks = (_read(tmp_path / name / "impact.csv") for name in ("one", "chunks"))
    assert [(r["point"], r["support"], r["status"]) for r in chunks] == [
        (r["point"], r["support"], r["status"]) for r in one
    ]
    for column in one[0]:
        if column in ("point", "support", "status"):
            continue
        # the batch integrator rounds differently with the batch only where a value is
        # numerically zero (twisting energy of an impact on the axis, ~1e-30 J)
        np.testing.assert_allclose(
            [_number(r[column]) for r in chunks],
            [_number(r[column]) for r in one],
            rtol=1e-12,
            atol=1e-20,
            err_msg=column,
        )


def test_both_writes_a_comparison_equal_to_the_two_tables(both: Path) -> None:
    assert _header(both / "comparison.csv") == list(COMPARISON_COLUMNS)
    approximate = {
        (r["point"], r["support"], r["ball_speed_mps"]): r for r in _read(both / "impact.csv")
    }
    transient = {
        (r["point"], r["support"], r["ball_speed_mps"]): r
        for r in _read(both / "impact_transient.csv")
    }
    rows = _read(both / "comparison.csv")
    assert len(rows) == len(approximate) == len(transient) == 3 * 2 * 2
    for row in rows:
        key = (row["point"], row["support"], row["ball_speed_mps"])
        a_row, t_row = approximate[key], transient[key]
        assert row["status_transient"] == t_row["status"]
        filled = a_row["status"] == STATUS_FROM_TRANSIENT  # issue 22: impact.csv takes the
        # transient's numbers where the approximate method gives none; comparison.csv keeps
        # the approximate method's own status and NaN
        if filled:
            assert row["status_approx"] != "ok"
        else:
            assert row["status_approx"] == a_row["status"]
        for quantity, column in COMPARED.items():
            a, t = _number(a_row[column]), _number(t_row[column])
            if filled:
                assert a == pytest.approx(t, rel=1e-8, nan_ok=True)
                a = math.nan
            assert _number(row[f"approx_{column}"]) == pytest.approx(a, rel=1e-8, nan_ok=True)
            assert _number(row[f"transient_{column}"]) == pytest.approx(t, rel=1e-8, nan_ok=True)
            difference = _number(row[f"difference_{column}"])
            relative = _number(row[f"relative_difference_{quantity}"])
            if math.isnan(a) or math.isnan(t):
                assert math.isnan(difference)
                assert math.isnan(relative)
                continue
            # the CSVs hold 9 significant digits: the difference of the rounded values agrees
            # to 1e-8 of the larger value
            scale = max(abs(a), abs(t))
            assert difference == pytest.approx(a - t, abs=1e-8 * scale), (key, column)
            assert relative == pytest.approx((a - t) / abs(t), abs=1e-8 * scale / abs(t))


def test_the_approximate_method_holds_at_the_face_centre(both: Path) -> None:
    rows = [
        r
        for r in _read(both / "comparison.csv")
        if r["point"] == "centre" and _number(r["ball_speed_mps"]) == 20.0
    ]
    assert {r["support"] for r in rows} == {"free", "pinned"}
    for row in rows:
        approximate = _number(row["approx_rebound_ratio"])
        transient = _number(row["transient_rebound_ratio"])
        assert approximate == pytest.approx(transient, rel=CENTRE_TOLERANCE)
    record = json.loads((both / "run.json").read_text(encoding="utf-8"))
    assert record["model"] == "both"
    assert record["method"].startswith("approximate")  # impact.csv is the approximate method
    assert record["transient"]["method"] == "transient"
    assert record["integrator"]["engine"] == record["engine"]["used"]
    assert "comparison.csv" in record["columns"]


@pytest.mark.parametrize("engine", ["reference", "compiled"])
@pytest.mark.slow
def test_on_a_rigid_racket_both_models_agree(engine: str, points: Path, tmp_path: Path) -> None:
    """No modes: a two-body impact with COR e_BG, which the approximate method has exactly and
    the transient hysteresis returns by construction; the rebound ratios agree to the
    integrator's accuracy (measured: 5e-7 with the reference, COR within 6e-6 with the
    compiled engine, which its author states as ≈ 1e-5)."""
    if engine == "compiled":
        pytest.importorskip("numba")
    argv = ["predict", "--model", "both", "--rigid", "--points", str(points), "--speed", "10,30"]
    assert main([*argv, "--engine", engine, "--no-figures", "--out", str(tmp_path)]) == 0
    rows = _read(tmp_path / "comparison.csv")
    assert len(rows) == 3 * 2 * 2
    for row in rows:
        assert row["status_approx"] == row["status_transient"] == "ok"
        assert abs(_number(row["difference_rebound_ratio"])) < 1e-5
        assert _number(row["transient_vibration_energy_j"]) == 0.0
    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert record["engine"] == {"requested": engine, "used": engine}


def test_histories_obey_newtons_second_law_for_the_ball(both: Path) -> None:
    """x_B(t) = V t − ∫∫ F/m_B: the CSV's force and ball displacement agree (trapezoids)."""
    header = _header(both / "transient_histories.csv")
    fixed = [name for name in HISTORY_COLUMNS if not name.startswith("q_")]
    assert header[: len(fixed)] == fixed
    assert header[len(fixed) :] == [
        "q_2_node_bending_m_sqrtkg",
        "q_3_node_bending_m_sqrtkg",
        "q_2_node_twisting_m_sqrtkg",
    ]
    rows = _read(both / "transient_histories.csv")
    groups = {(r["point"], r["support"]) for r in rows}
    assert groups == {(p, s) for p in ("centre", "tip") for s in ("free", "pinned")}
    mass = rd.Ball().mass_kg
    for point, support in groups:
        table = [r for r in rows if r["point"] == point and r["support"] == support]
        t = np.array([_number(r["time_s"]) for r in table])
        force = np.array([_number(r["force_n"]) for r in table])
        ball = np.array([_number(r["ball_displacement_m"]) for r in table])
        face = np.array([_number(r["face_displacement_m"]) for r in table])
        compression = np.array([_number(r["compression_m"]) for r in table])
        speed = _number(table[0]["ball_speed_mps"])
        assert speed == 20.0  # the history speed: 20 m/s when listed
        assert t[0] == 0.0
        assert np.all(np.diff(t) >= 0)
        assert force[0] == pytest.approx(0.0, abs=1e-9)
        np.testing.assert_allclose(ball - face, compression, atol=1e-9)
        dt = np.diff(t)
        impulse = np.concatenate([[0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * dt)])
        velocity = speed - impulse / mass
        position = np.concatenate([[0.0], np.cumsum(0.5 * (velocity[1:] + velocity[:-1]) * dt)])
        # ≈ 400 samples a contact: the trapezoid error is ~1e-5 of the peak displacement
        np.testing.assert_allclose(position, ball, atol=1e-3 * np.max(np.abs(ball)))


@pytest.mark.slow
def test_both_draws_the_comparison_figures(points: Path, tmp_path: Path) -> None:
    argv = ["predict", "--model", "both", "--points", str(points), "--speed", "20"]
    assert main([*argv, "--support", "free", "--out", str(tmp_path)]) == 0
    for name in (
        "transient_comparison_face.png",
        "transient_comparison_speed.png",
        "transient_histories.png",
        "fig15_rebound_along_axis.png",
    ):
        assert (tmp_path / name).stat().st_size > 10_000, name


def test_hand_support_with_the_transient_model(points: Path, tmp_path: Path) -> None:
    argv = ["predict", "--model", "transient", "--points", str(points), "--speed", "20"]
    argv += ["--support", "free,hand", "--hand-arm-mass", "0.8", "--no-figures"]
    assert main([*argv, "--out", str(tmp_path)]) == 0
    rows = _read(tmp_path / "impact.csv")
    assert {r["support"] for r in rows} == {"free", "hand"}
    assert all(r["status"] == "ok" for r in rows)
    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert record["hand"]["arm_mass_kg"] == 0.8
    # Grip firmness hardly changes the rebound (Grabiner et al. 1983; docs/references.md) and
    # an arm barely changes the reduced mass near the centre (Kawazoe 2002): within 2 % of free
    centre = {r["support"]: _number(r["rebound_ratio"]) for r in rows if r["point"] == "centre"}
    assert centre["hand"] == pytest.approx(centre["free"], rel=0.02)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--support", "hand"], "--support hand needs --model transient"),
        (["--model", "both", "--support", "free,hand"], "--support hand with --model both"),
        (["--model", "transient", "--hand-arm-mass", "1"], "--hand-arm-mass: for --support hand"),
        (
            ["--model", "transient", "--hand-stiffness", "3e4", "--hand-damping", "20"],
            "--hand-stiffness, --hand-damping: for --support hand",
        ),
        (["--engine", "reference"], "--engine is for the transient model"),
        (
            ["--model", "transient", "--stiffness-reading", "tangent"],
            "--stiffness-reading is a choice of the approximate method",
        ),
        (
            ["--model", "transient", "--support", "hand", "--hand-arm-mass", "-1"],
            "--hand-arm-mass -1: an arm",
        ),
    ],
)
def test_bad_combinations_are_one_line_errors(
    extra: list[str], message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = ["predict", "--grid", "3", "--speed", "20", "--no-figures", *extra]
    assert main([*argv, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert message in err[0]
    assert not (tmp_path / "impact.csv").exists()


def test_compare_models_needs_the_same_impacts_of_the_two_models(
    racket: rd.Racket, ball: rd.Ball
) -> None:
    from racketdyn.errors import InputError
    from racketdyn.impact.comparison import compare_models
    from racketdyn.impact.transient import predict_transient

    approximate = rd.predict(racket, ball, [CENTRE, OFF_AXIS], [20.0], ("free",))
    transient = predict_transient(racket, ball, [CENTRE, OFF_AXIS], [20.0], ("free",))
    comparison = compare_models(approximate, transient)
    np.testing.assert_array_equal(
        comparison.difference("contact_time"), approximate.contact_time - transient.contact_time
    )
    with pytest.raises(InputError, match="an approximate-method result and a transient one"):
        compare_models(transient, approximate)
    other = predict_transient(racket, ball, [CENTRE, OFF_AXIS], [20.0], ("pinned",))
    with pytest.raises(InputError, match="same points, speeds and supports"):
        compare_models(approximate, other)
    with pytest.raises(InputError, match="quantity must be one of"):
        comparison.difference("stiffness")


def test_predict_says_when_the_modal_model_holds_modes_of_unknown_kind(
    points: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """New-user trial (2026-11-26, second session): the junior's identified model named its
    string-bed membrane mode (793.6 Hz, 8.7 Hz from a twisting mode) ``mode 4``, kind
    ``unknown``; ``predict`` took it as a frame mode without a word, and the transient contact
    at the centre grew from 5.80 to 6.26 ms (the strings' own motion on top of their spring).
    The console names such modes and what to do."""
    from dataclasses import replace

    from racketdyn.racket_modal import modal_model_for

    model = modal_model_for(rd.default_racket())
    kinds = list(model.kinds)
    k = kinds.index("string-bed")
    kinds[k] = "unknown"
    names = list(model.names)
    names[k] = f"mode {k + 1} ({model.frequency[k]:.1f} Hz)"
    path = tmp_path / "model.json"
    replace(model, kinds=tuple(kinds), names=tuple(names)).write_json(path)
    argv = ["predict", "--modal", str(path), "--points", str(points), "--speed", "20"]
    capsys.readouterr()
    assert main([*argv, "--no-figures", "--out", str(tmp_path / "out")]) == 0
    said = " ".join(capsys.readouterr().out.split())
    assert f"{names[k]} is of unknown kind: taken as a frame mode" in said
    assert "--exclude" in said
    capsys.readouterr()
    assert main(["predict", "--points", str(points), "--speed", "20", "--no-figures",
                 "--out", str(tmp_path / "builtin")]) == 0  # fmt: skip
    assert "unknown kind" not in capsys.readouterr().out


def test_predicts_comparison_table_cuts_no_word_at_80_columns(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """``predict --model both`` at 80 columns printed the heading "T_c transient (ms)" as
    "T_c transie…" (issue 27, "console wrapping")."""
    monkeypatch.setenv("COLUMNS", "80")
    argv = ["predict", "--model", "both", "--grid", "3", "--speed", "20", "--no-figures"]
    assert main([*argv, "--out", str(tmp_path / "p")]) == 0
    out = capsys.readouterr().out
    assert "…" not in out
    assert "transient" in out
    for line in out.splitlines():  # a table cropped at 80 columns loses its right border
        if line.startswith(("│", "┃", "┏", "┡", "└")):
            assert line[-1] in "│┃┓┩┘", line
