"""A step's result as one labelled dataset: ``PredictResult.to_xarray`` and
``ObliqueResult.to_xarray`` (new-user trial of the Python API, 2026-11-27, eighth session:
only their parts, ``ImpactResult.to_xarray``, had one).  The datasets hold the parts' own
values, written to netCDF and read back unchanged."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from racketdyn.workflows import ObliqueOptions, PredictOptions, Setup, run_oblique, run_predict


def _round_trip(dataset: xr.Dataset, path: Path) -> xr.Dataset:
    dataset.to_netcdf(path, engine="scipy")
    with xr.open_dataset(path, engine="scipy") as read:
        return read.load()


@pytest.fixture(scope="module")
def both(tmp_path_factory: pytest.TempPathFactory):  # type: ignore[no-untyped-def]
    from racketdyn.impact.uncertainty import Spread, Uncertainty

    out = tmp_path_factory.mktemp("predict") / "out"
    spread = Uncertainty((Spread("e_bg", bounds=(0.80, 0.88)),), samples=8)
    options = PredictOptions(speeds=[20.0, 30.0], model="both", grid=3, uncertainty=spread)
    return run_predict(out, Setup(), options)


@pytest.mark.slow
def test_a_predict_result_is_one_dataset_of_both_models(both, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    dataset = _round_trip(both.to_xarray(), tmp_path / "predict.nc")
    assert list(dataset["model"].values) == ["approximate", "transient"]
    for name, part in (("approximate", both.approximate), ("transient", both.transient)):
        one = dataset.sel(model=name)
        np.testing.assert_array_equal(one["rebound_ratio"].values, part.rebound_ratio)
        np.testing.assert_array_equal(one["contact_time_s"].values, part.contact_time)
        np.testing.assert_array_equal(one["status"].values, part.status)
    np.testing.assert_array_equal(dataset["ball_speed_mps"].values, [20.0, 30.0])
    for name in ("approximate", "transient"):  # each model's band, as its uncertainty.nc
        band = both.bands["approx" if name == "approximate" else name].to_xarray()
        one = dataset.sel(model=name)
        for variable in ("rebound_ratio_p05", "rebound_ratio_samples", "drawn_e_bg"):
            np.testing.assert_array_equal(one[variable].values, band[variable].values)
    assert list(dataset["support"].values) == list(both.supports)
    # the transient's own variable and the figures' data, as figures.nc holds them
    assert "energy_balance_j" in dataset
    assert "model" not in dataset["energy_balance_j"].dims
    figures = xr.open_dataset(both.out / "figures.nc", engine="scipy")
    for name in figures.data_vars:
        np.testing.assert_array_equal(dataset[name].values, figures[name].values)


def test_an_oblique_result_is_one_dataset_of_its_curve(tmp_path: Path) -> None:
    options = ObliqueOptions(angles_deg=(0.0, 20.0, 40.0), spin_radps=50.0, friction=0.3)
    result = run_oblique(tmp_path / "out", Setup(), options)
    curve = result.curve
    assert curve is not None
    dataset = _round_trip(result.to_xarray(), tmp_path / "oblique.nc")
    np.testing.assert_array_equal(dataset["incoming_angle_deg"].values, [0.0, 20.0, 40.0])
    np.testing.assert_array_equal(dataset["incoming_spin_radps"].values, [50.0] * 3)
    for name in ("outgoing_angle_deg", "outgoing_spin_radps", "friction_loss_j", "grip_time_s"):
        np.testing.assert_array_equal(dataset[name].values, getattr(curve, name))
        assert dataset[name].attrs["units"]
    np.testing.assert_array_equal(dataset["gripped"].values, curve.gripped)
    np.testing.assert_array_equal(dataset["status"].values, curve.status)
    assert float(dataset["x_m"]) == result.point[0]
    assert str(dataset["support"].values) == "free"
    assert dataset.attrs["friction_coefficient"] == 0.3
    assert dataset.attrs["ball_speed_mps"] == 20.0
