"""The workflows called from Python: each writes its run folder (data files + run.json) and
returns the computed objects; figures only through the caller's hook."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.io import read_frf_uff, write_hammer_uff
from racketdyn.testing.records import Modes, records_for
from racketdyn.workflows import (
    FrfResult,
    ObliqueOptions,
    PredictOptions,
    PredictResult,
    run_frf,
    run_oblique,
    run_predict,
    run_twist,
)
from racketdyn.workflows.run import StepResult
from racketdyn.workflows.setup import Setup


def _record(out: Path) -> dict[str, object]:
    record: dict[str, object] = json.loads((out / "run.json").read_text(encoding="utf-8"))
    return record


def test_predict_writes_its_folder_and_returns_the_result(tmp_path: Path) -> None:
    racket = rd.default_racket()
    result = run_predict(
        tmp_path,
        setup=Setup(racket=racket),
        options=PredictOptions(speeds=[20.0], supports=["free"], grid=3),
    )

    assert isinstance(result, PredictResult)
    assert result.written == [tmp_path / "impact.csv", tmp_path / "figures.nc"]
    assert result.approximate is not None
    assert result.transient is None
    n = len(racket.head.grid(3))
    assert result.approximate.rebound_ratio.shape == (n, 1, 1)
    record = _record(tmp_path)
    assert record == result.record
    assert record["outputs"] == ["impact.csv", "figures.nc", "run.json"]
    assert record["command"] == ["python", "racketdyn.workflows.predict"]
    assert record["speeds_mps"] == [20.0]
    assert (
        record["racket_file"]
        == "Racket object 'Kawazoe test racket (360 g, 97 sq in)' (given from Python)"
    )
    assert "modal model: built-in free-free beam model" in record["defaults_used"]  # type: ignore[operator]
    # the same numbers as the library function
    direct = rd.predict(racket, rd.Ball(), racket.head.grid(3), [20.0], ["free"])
    np.testing.assert_array_equal(result.approximate.rebound_ratio, direct.rebound_ratio)


def test_predict_figures_come_from_the_hook_and_are_recorded(tmp_path: Path) -> None:
    seen: list[StepResult] = []

    def hook(result: PredictResult, out: Path) -> list[Path]:
        assert not (out / "run.json").exists()  # run.json is written after the figures
        seen.append(result)
        path = out / "figure.png"
        path.write_bytes(b"png")
        return [path]

    result = run_predict(
        tmp_path,
        setup=Setup(figures=hook),
        options=PredictOptions(
            model="both", speeds=[20.0], supports=["free"], points=[[0.505, 0.0]]
        ),
    )
    assert seen == [result]
    assert result.comparison is not None
    assert [p.name for p in result.written] == [
        "impact_transient.csv",
        "transient_histories.csv",
        "comparison.csv",
        "impact.csv",  # after the comparison: rows beyond the approximate method filled (issue 22)
        "figures.nc",
        "figure.png",
    ]
    assert _record(tmp_path)["outputs"] == [p.name for p in result.written] + ["run.json"]


def test_predict_refuses_bad_input_before_writing(tmp_path: Path) -> None:
    with pytest.raises(rd.InputError, match="`supports` hand needs `model` transient"):
        run_predict(tmp_path / "out", options=PredictOptions(supports=["hand"]))
    with pytest.raises(rd.InputError, match="grid"):
        run_predict(tmp_path / "out", options=PredictOptions(grid=0))
    # review of issue 11: these were checked by the CLI only, and ignored from Python
    with pytest.raises(rd.InputError, match="engine"):
        run_predict(tmp_path / "out", options=PredictOptions(model="approx", engine="reference"))
    with pytest.raises(rd.InputError, match="`stiffness_reading`"):
        run_predict(
            tmp_path / "out", options=PredictOptions(model="transient", stiffness_reading="tangent")
        )
    assert not (tmp_path / "out").exists()


@pytest.fixture(scope="module")
def tests_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    modes = Modes(
        np.array([120.0, 330.0]), np.array([0.03, 0.02]), np.array([[6.0, 4.0], [-3.0, 2.5]])
    )
    records = records_for(modes, pulse_s=3e-3, n_averages=2, second_hit=None)
    records = dataclasses.replace(
        records,
        locations=np.array([[0.505, 0.0], [0.55, 0.03]]),
        reference_location=(0.505, 0.0),
    )
    path = tmp_path_factory.mktemp("tests") / "free.uff"
    write_hammer_uff(records, path)
    return path


def test_frf_writes_its_folder_and_returns_the_estimate(tests_file: Path, tmp_path: Path) -> None:
    result = run_frf(
        tests_file, tmp_path, exponential_window_s=0.1, setup=Setup(command=["racketdyn", "frf"])
    )

    assert isinstance(result, FrfResult)
    assert [p.name for p in result.written] == ["quality.csv", "frfs.uff", "figures.nc"]
    assert result.estimate is not None
    assert result.estimate.frfs is not None
    assert read_frf_uff(tmp_path / "frfs.uff").nodes == result.estimate.frfs.nodes == (1, 2)
    record = _record(tmp_path)
    assert record["command"] == ["racketdyn", "frf"]
    assert record["exponential_window_s"] == 0.1
    assert record["outputs"] == ["quality.csv", "frfs.uff", "figures.nc", "run.json"]
    assert not list(tmp_path.glob("*.png"))  # no hook, no figures


def test_twist_and_oblique_from_python(tmp_path: Path) -> None:
    twist = run_twist(
        tmp_path / "twist", offsets_m=[0.0, 0.04], supports=["free"], setup=Setup(rigid=True)
    )
    assert [p.name for p in twist.written] == ["twist.csv", "figures.nc"]
    assert twist.curves[0].roll_angle_rad[0] == pytest.approx(0.0, abs=1e-12)
    assert twist.curves[0].roll_angle_rad[1] > 0.0
    oblique = run_oblique(
        tmp_path / "oblique", Setup(rigid=True), ObliqueOptions(angles_deg=[0.0, 30.0])
    )
    assert oblique.curve is not None
    assert oblique.curve.outgoing_spin_radps.shape == (2,)
    assert _record(tmp_path / "oblique")["outputs"] == ["oblique.csv", "figures.nc", "run.json"]


def test_every_workflow_parameter_is_described() -> None:
    import inspect

    import racketdyn.workflows as workflows

    for name in workflows.__all__:
        obj = getattr(workflows, name)
        doc = inspect.getdoc(obj)
        assert doc, name
        if inspect.isfunction(obj):
            for parameter in inspect.signature(obj).parameters:
                assert parameter in doc, f"{name}: parameter {parameter!r} is not described"


def test_predict_takes_a_modal_model_object(tmp_path: Path) -> None:
    """Review of issue 11: `modal=` took a file only (a ModalModel raised a raw TypeError)."""
    racket = rd.default_racket()
    model = rd.modal_model_for(racket)
    by_object = run_predict(
        tmp_path / "a",
        setup=Setup(modal_model=model),
        options=PredictOptions(speeds=[20.0], grid=3),
    )
    by_default = run_predict(tmp_path / "b", options=PredictOptions(speeds=[20.0], grid=3))
    assert by_object.modal_model is model
    np.testing.assert_array_equal(by_object.result.rebound_ratio, by_default.result.rebound_ratio)
    record = json.loads((tmp_path / "a" / "run.json").read_text(encoding="utf-8"))
    assert "ModalModel object" in json.dumps(record)


def test_predict_from_python_refuses_a_speed_in_kmh(tmp_path: Path) -> None:
    """Issue 13: `run_predict(speeds=[90])` (km/h typed) ran with every row NaN; the CLI
    refused it, Python did not."""
    with pytest.raises(rd.InputError, match="did you give"):
        run_predict(tmp_path / "out", options=PredictOptions(speeds=[90.0], grid=3))
    assert not (tmp_path / "out").exists()
    unusual = run_predict(
        tmp_path / "out",
        setup=Setup(allow_implausible=True),
        options=PredictOptions(speeds=[80.0], grid=3),
    )
    assert unusual.result.status.size == 2 * len(unusual.result.locations)
