"""Issue 24, sweeps: ``racketdyn sweep --uncertainty`` and a spec's ``[uncertainty]``.

Each design's samples run inside its task (:func:`racketdyn.impact.uncertainty.propagate`,
the approximate method's all at once); the store gets per impact the mean, sd, 5 % and 95 %
quantiles and ``samples_valid``, per face the best rebound ratio's and the sweet area's band.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

import racketdyn as rd
import sweep_faults
from racketdyn.cli import main
from racketdyn.errors import InputError
from racketdyn.impact.measured import ModelInputs
from racketdyn.impact.uncertainty import Spread, Uncertainty, propagate
from racketdyn.numerics import one_blas_thread
from racketdyn.racket_modal import builtin_modal_model
from racketdyn.sweep import (
    SerialExecutor,
    SweepSpec,
    TaskOptions,
    build_design,
    make_executor,
    run_sweep,
)
from racketdyn.sweep.task import band_variables, run_task

assert_same_bits = sweep_faults.assert_same_bits

NOMINAL = ("contact_time_s", "peak_force_n", "vibration_energy_j", "rebound_ratio", "status")
SPREADS = (
    Spread("e_bg", sd=0.02),  # e_bg is swept: a spread about each design's value
    Spread("first_bending_hz", bounds=(110.0, 150.0)),
    Spread("location_m", sd=0.003),
    Spread("ball_speed_mps", sd=0.5),
)


@pytest.fixture(scope="module")
def spec(racket: rd.Racket) -> SweepSpec:
    """tests/sweep_faults.py's small sweep (6 designs: a point mass at 12 and e_BG) with
    four uncertain inputs, 16 samples."""
    small = sweep_faults.small_spec(racket, rd.Ball(), "small")
    return replace(small, uncertainty=Uncertainty(SPREADS, samples=16, seed=2))


@pytest.fixture(scope="module")
def banded(spec: SweepSpec, tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    return run_sweep(spec, tmp_path_factory.mktemp("banded"), SerialExecutor(), figures=None)


@pytest.mark.slow
def test_without_an_uncertainty_the_sweep_is_as_before_and_the_nominal_numbers_stay(
    spec: SweepSpec, banded: xr.Dataset, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    """No uncertainty: the same spec hash, the same store bit for bit, no band; with one, the
    nominal numbers are those bits still."""
    plain = replace(spec, uncertainty=None)
    assert plain.sha256 == sweep_faults.small_spec(spec.racket, spec.ball, "small").sha256
    assert spec.sha256 != plain.sha256
    assert_same_bits(serial_result, run_sweep(plain, tmp_path, SerialExecutor(), figures=None))
    assert "rebound_ratio_p05" not in serial_result
    assert json.loads((tmp_path / "run.json").read_text())["uncertainty"] is None
    for name in NOMINAL:
        assert banded[name].values.tobytes() == serial_result[name].values.tobytes(), name
    assert set(band_variables()) <= set(banded.data_vars)


@pytest.mark.slow
def test_pinned_spreads_collapse_the_band_onto_the_nominal(spec: SweepSpec, tmp_path: Path) -> None:
    pinned = Uncertainty(
        (Spread("e_bg", sd=0.0), Spread("first_bending_hz", sd=0.0), Spread("location_m", sd=0.0)),
        samples=8,
    )
    found = run_sweep(replace(spec, uncertainty=pinned), tmp_path, SerialExecutor(), figures=None)
    ok = found["status"].values == 0
    assert ok.sum() > 100
    np.testing.assert_array_equal(found["samples_valid"].values[ok], 1.0)
    for name in ("contact_time_s", "peak_force_n", "vibration_energy_j", "rebound_ratio"):
        nominal = found[name].values[ok]
        for stat in ("mean", "p05", "p95"):
            np.testing.assert_allclose(found[f"{name}_{stat}"].values[ok], nominal, rtol=1e-9)
        assert np.all(found[f"{name}_sd"].values[ok] <= 1e-9 * np.abs(nominal))
    metrics = rd.sweep.summary_metrics(found)
    for metric in ("centre_rebound_ratio", "best_rebound_ratio", "sweet_area_cm2"):
        np.testing.assert_allclose(metrics[f"{metric}_p05"], metrics[metric], rtol=1e-9)
        np.testing.assert_allclose(metrics[f"{metric}_p95"], metrics[metric], rtol=1e-9)


def test_a_design_s_band_is_propagate_on_that_design_alone(
    spec: SweepSpec, banded: xr.Dataset
) -> None:
    """The band of design 4 (5 g at 12 o'clock, e_BG 0.80) is what
    :func:`propagate` gives on its racket and ball, to round-off."""
    design = spec.designs[4]
    racket, ball, _ = build_design(spec.racket, spec.ball, spec.variables, design.settings)
    assert racket.derived_properties()["mass_kg"] > spec.racket.mass_kg
    assert spec.uncertainty is not None
    with one_blas_thread():  # as a task builds its model (threads round the beam's solve apart)
        alone = propagate(
            ModelInputs(racket, ball, modal_model=builtin_modal_model(racket)),
            spec.locations,
            spec.ball_speeds,
            spec.uncertainty,
            supports=spec.supports,
        )
    columns = alone.band_columns()
    assert np.isfinite(columns["rebound_ratio_p05"]).sum() > 10
    for name, values in columns.items():
        stored = banded[name].isel(design=4, racket_speed=0).values
        np.testing.assert_allclose(stored, values, rtol=1e-12, atol=0, equal_nan=True)
    # and the bands differ between designs: each design's own samples
    p95 = banded["rebound_ratio_p95"].values
    assert not np.allclose(p95[4], p95[1], equal_nan=True)


def test_a_transient_design_s_band_is_propagate_on_that_design_alone(
    racket: rd.Racket, tmp_path: Path
) -> None:
    """The transient model's samples run inside the task, as ``propagate`` runs them."""
    uncertainty = Uncertainty((Spread("e_bg", bounds=(0.80, 0.86)),), samples=4)
    spec = SweepSpec(
        racket,
        rd.Ball(),
        racket.head.grid(3),
        [20.0],
        supports=("free",),
        variables=(rd.sweep.Variable.scalar("tension_n", [200.0, 260.0]),),
        method="transient",
        uncertainty=uncertainty,
    )
    found = run_sweep(spec, tmp_path, SerialExecutor(), figures=None)
    racket_2, ball, _ = build_design(racket, spec.ball, spec.variables, spec.designs[1].settings)
    with one_blas_thread():
        model = builtin_modal_model(racket_2)
        alone = propagate(
            ModelInputs(racket_2, ball, modal_model=model, engine=spec.transient_engine),
            spec.locations,
            [20.0],
            uncertainty,
            method="transient",
            supports=("free",),
        )
    stored = found["rebound_ratio_p95"].isel(design=1, racket_speed=0).values
    assert np.isfinite(stored).sum() >= 3
    np.testing.assert_allclose(
        stored, alone.band_columns()["rebound_ratio_p95"], rtol=1e-12, equal_nan=True
    )


@pytest.mark.slow
def test_one_and_two_workers_give_the_same_bits(
    spec: SweepSpec, banded: xr.Dataset, tmp_path: Path
) -> None:
    for workers in (1, 2):
        with make_executor("process", workers) as executor:
            found = run_sweep(
                spec,
                tmp_path / str(workers),
                executor,
                options=TaskOptions(designs_per_task=2),
                figures=None,
            )
        assert_same_bits(banded, found.load())


def test_a_task_returns_the_bands_not_the_samples(spec: SweepSpec) -> None:
    """The main process receives (and the store holds) statistics, never a sample axis."""
    output = run_task(spec.task(spec.designs[0]))
    per_design = spec.impacts_per_design
    assert all(array.size <= per_design for array in output.arrays.values())
    assert set(band_variables()) <= set(output.arrays)


@pytest.mark.slow
def test_the_summary_gives_the_bands_or_says_why_not(
    spec: SweepSpec, banded: xr.Dataset, tmp_path: Path
) -> None:
    """Each headline metric with its band in summary.csv; where a wide location scatter puts
    edge points on the frame in most samples, the face's band is NaN with its reason (under
    90 % of the samples)."""
    rd.sweep.write_summary_csv(banded, tmp_path)
    table = pd.read_csv(tmp_path / "summary.csv")
    for metric in ("centre_rebound_ratio", "best_rebound_ratio"):
        low, value, high = (table[f"{metric}{s}_free"] for s in ("_p05", "", "_p95"))
        assert np.all((low < value) & (value < high)), metric
    assert np.all(table["face_samples_valid_free"] >= 0.9)
    assert table["band_note_free"].isna().all()  # "" read back
    wide = replace(
        spec.uncertainty, spreads=(Spread("e_bg", sd=0.02), Spread("location_m", sd=0.03))
    )
    found = run_sweep(
        replace(spec, uncertainty=wide), tmp_path / "wide", SerialExecutor(), figures=None
    )
    metrics = rd.sweep.summary_metrics(found).sel(support="free")
    assert np.all(metrics["face_samples_valid"] < 0.9)
    assert np.all(np.isnan(metrics["sweet_area_cm2_p05"]))
    assert np.all(np.isnan(metrics["best_rebound_ratio_p95"]))
    assert all("over the face" in note for note in metrics["band_note"].values.tolist())


SPEC = sweep_faults.SMALL_SPEC_TOML + "\n[uncertainty.e_bg]\nsd = 0.02\n"


def _argv(spec: Path, out: Path, *more: str) -> list[str]:
    return ["sweep", str(spec), "--out", str(out), "--serial", "--no-figures", *more]


@pytest.mark.slow
def test_the_spec_s_uncertainty_and_the_command_line_over_it(tmp_path: Path) -> None:
    spec = tmp_path / "spec.toml"
    spec.write_text(SPEC, encoding="utf-8")
    assert main(_argv(spec, tmp_path / "a", "--samples", "8")) == 0
    run = json.loads((tmp_path / "a" / "run.json").read_text())
    assert any("8 samples a design give a rough" in note for note in run["notes"])
    record = run["uncertainty"]
    assert record["source"] == "[uncertainty] of the sweep spec"
    assert record["inputs"] == {"e_bg": "normal, sd 0.02"}
    assert record["samples"] == 8
    other = tmp_path / "u.toml"
    other.write_text("[ball_speed_mps]\nsd = 1.0\n", encoding="utf-8")
    assert main(_argv(spec, tmp_path / "b", "--uncertainty", str(other), "--seed", "3")) == 0
    record = json.loads((tmp_path / "b" / "run.json").read_text())["uncertainty"]
    assert record["source"].startswith(f"--uncertainty {other}")
    assert record["inputs"] == {"ball_speed_mps": "normal, sd 1 m/s (offset)"}
    assert (record["samples"], record["seed"]) == (256, 3)
    with rd.sweep.open_sweep(tmp_path / "b") as found:
        assert json.loads(found.attrs["uncertainty"])["inputs"] == record["inputs"]
    # --uncertainty none: the sweep without, bit for bit as the spec without the table
    assert main(_argv(spec, tmp_path / "c", "--uncertainty", "none")) == 0
    plain = tmp_path / "plain.toml"
    plain.write_text(sweep_faults.SMALL_SPEC_TOML, encoding="utf-8")
    assert main(_argv(plain, tmp_path / "d")) == 0
    with rd.sweep.open_sweep(tmp_path / "c") as c, rd.sweep.open_sweep(tmp_path / "d") as d:
        assert_same_bits(d.load(), c.load())
    assert json.loads((tmp_path / "c" / "run.json").read_text())["uncertainty"] is None


@pytest.mark.parametrize(
    ("table", "options", "words"),
    [
        ("[uncertainty.e_bg]\nrange = [0.8, 0.88]\n", (), ("[uncertainty.e_bg]", "sd = x")),
        ("[uncertainty.e_bg]\nsd = -0.1\n", (), ("[e_bg] sd", "0 or more")),
        ("[uncertainty.e_bgg]\nsd = 0.1\n", (), ("[e_bgg]", "choose from")),
        ("[uncertainty.location_m]\nsd = 10\n", (), ("[location_m]", "millimetres")),
        ("[impacts.x]\n", (), ()),  # placeholder replaced below (rigid)
        ("", ("--samples", "16"), ("--samples", "sweep spec with [uncertainty]")),
        (
            "[uncertainty.e_bg]\nsd = 0.01\n",
            ("--uncertainty", "none", "--seed", "2"),
            ("--seed", "--uncertainty none"),
        ),
        ("[uncertainty.e_bg]\nsd = 0.01\n", ("--samples", "1"), ("--samples", "2 to")),
    ],
)
def test_bad_uncertainty_input_is_one_line_naming_it(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    table: str,
    options: tuple[str, ...],
    words: tuple[str, ...],
) -> None:
    text = sweep_faults.SMALL_SPEC_TOML + "\n" + table
    if table.startswith("[impacts.x]"):  # a rigid racket has no bending mode
        text = sweep_faults.SMALL_SPEC_TOML.replace("grid = 4", "grid = 4\nrigid = true")
        text += "\n[uncertainty.first_bending_hz]\nsd = 3.0\n"
        words = ("[uncertainty.first_bending_hz]", "rigid")
    spec = tmp_path / "spec.toml"
    spec.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(_argv(spec, out, *options)) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert "Traceback" not in err[0]
    for word in words:
        assert word in err[0], err[0]
    assert not out.exists()


def test_a_spread_the_designs_cannot_take_is_refused_in_python(spec: SweepSpec) -> None:
    with pytest.raises(InputError, match=r"\[uncertainty.e_bg\]: a range"):
        replace(spec, uncertainty=Uncertainty((Spread("e_bg", bounds=(0.8, 0.88)),)))


@pytest.mark.slow
def test_a_sweep_without_an_uncertainty_loads_no_more_modules() -> None:
    """Every worker process imports the sweep: the uncertainty's modules (xarray, scipy.stats:
    ≈ 1 s) are imported when a sweep has an uncertainty, not before (with them at the top,
    a local Dask cluster's Ctrl-C test failed 2 runs in 3 with a tornado traceback)."""
    import subprocess
    import sys

    heavy = ("xarray", "scipy.stats", "racketdyn.impact.uncertainty")
    imports = "racketdyn.sweep.runner, racketdyn.sweep.spec_file, racketdyn.cli.sweep"
    code = f"import sys, {imports}; print([m for m in {heavy!r} if m in sys.modules])"
    assert subprocess.check_output([sys.executable, "-c", code], text=True).strip() == "[]"
