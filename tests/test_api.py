"""The Python API in notebooks and the data ecosystem: names, tables, datasets and reprs.

One naming rule (docs/develop.md, glossary): attributes are the glossary's bare names in SI
units (``contact_time``); files, dataset variables and data-frame columns carry the unit
(``contact_time_s``).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr
from hypothesis import given, settings
from hypothesis import strategies as st

import racketdyn as rd
from racketdyn.impact.comparison import compare_models
from racketdyn.impact.result import (
    CSV_COLUMNS,
    IMPACT_QUANTITIES,
    STATUS_BEYOND_LAW,
    STATUS_OK,
    STATUS_VIBRATION_LOSS,
    ImpactResult,
)
from racketdyn.impact.swing import Swing, predict_swing
from racketdyn.impact.transient import predict_transient, simulate_impact
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.testing.records import Modes, records_for

# the impact quantities that are dataset variables (the racket speed is a coordinate)
VARIABLES = [q for q in IMPACT_QUANTITIES if q.attribute != "racket_speed"]
# those on (point, ball_speed, support)
CELL_VARIABLES = [q for q in VARIABLES if q.attribute != "reduced_mass"]
LOCATIONS = np.array([[0.505, 0.0], [0.60, 0.0], [0.45, 0.05]])
LABELS = ("centre", "tip", "side")
# 200 m/s compresses the ball and strings beyond the restoring-force law: flagged rows
SPEEDS = np.array([10.0, 20.0, 40.0, 200.0])
MAX_REPR = 500


@pytest.fixture(scope="module")
def result(racket: rd.Racket, ball: rd.Ball, model: rd.ModalModel) -> ImpactResult:
    return rd.predict(
        racket, ball, LOCATIONS, SPEEDS, modal_model=model, labels=LABELS, racket_speed=1.5
    )


def _same(a: object, b: object) -> bool:
    """Equal arrays, NaN equal to NaN (exact, no tolerance)."""
    x, y = np.asarray(a), np.asarray(b)
    if x.dtype.kind in "fc":
        return bool(np.array_equal(x, y, equal_nan=True))
    return bool(np.array_equal(x.astype(str), y.astype(str)))


# --- one table of names -------------------------------------------------------------------------
def test_each_attribute_is_the_bare_name_and_each_column_carries_the_unit() -> None:
    units = {"m s-1": "_mps", "kg": "_kg", "N m-1": "_n_per_m", "s": "_s", "N": "_n", "J": "_j"}
    units |= {"m": "_m", "1": ""}
    for quantity in IMPACT_QUANTITIES:
        assert quantity.attribute in ImpactResult.__dataclass_fields__
        assert quantity.name == quantity.attribute + units[quantity.units]
        assert quantity.name in CSV_COLUMNS


# --- columns, data frame, CSV -------------------------------------------------------------------
def test_columns_is_a_mapping_pandas_takes(result: ImpactResult) -> None:
    columns = result.columns
    n_rows = int(np.prod(result.shape))
    assert list(columns)[: len(CSV_COLUMNS)] == list(CSV_COLUMNS)
    assert all(np.ndim(v) == 1 and len(v) == n_rows for v in columns.values())
    frame = pd.DataFrame(result.columns)
    assert frame.shape == (n_rows, len(CSV_COLUMNS) + len(result.modal_model.names))


def test_to_dataframe_is_impact_csv(result: ImpactResult, tmp_path: Path) -> None:
    path = tmp_path / "impact.csv"
    result.write_csv(path)
    read = pd.read_csv(path, keep_default_na=False, na_values=["nan"])
    frame = result.to_dataframe()
    assert list(read.columns) == list(frame.columns)
    # the file holds nine significant digits
    pd.testing.assert_frame_equal(read, frame, check_dtype=False, rtol=1e-8, atol=0.0)
    assert (frame["status"] != STATUS_OK).any()


def test_comparison_and_swing_columns_are_properties(
    racket: rd.Racket, ball: rd.Ball, model: rd.ModalModel, result: ImpactResult
) -> None:
    transient = predict_transient(
        racket, ball, LOCATIONS[:1], [20.0], modal_model=model, labels=LABELS[:1]
    )
    approximate = rd.predict(
        racket, ball, LOCATIONS[:1], [20.0], modal_model=model, labels=LABELS[:1]
    )
    comparison = compare_models(approximate, transient)
    assert pd.DataFrame(comparison.columns).shape[0] == 2
    swing = predict_swing(racket, ball, LOCATIONS[:2], [20.0], Swing(), modal_model=model)
    assert pd.DataFrame(swing.columns).shape[0] == 2
    assert len(repr(swing)) < MAX_REPR


# --- the dataset --------------------------------------------------------------------------------
def test_dataset_dims_coords_and_units(result: ImpactResult) -> None:
    ds = result.to_xarray()
    assert tuple(ds.sizes) == ("point", "ball_speed", "support", "mode")
    assert ds.sizes["point"] == 3
    assert ds.sizes["ball_speed"] == 4
    assert ds.sizes["mode"] == 3
    for name, dim in [
        ("x_m", "point"),
        ("y_m", "point"),
        ("label", "point"),
        ("ball_speed_mps", "ball_speed"),
        ("racket_speed_mps", "ball_speed"),
        ("support", "support"),
        ("mode", "mode"),
        ("mode_frequency_hz", "mode"),
    ]:
        assert ds[name].dims == (dim,), name
    assert list(ds["support"].values) == list(result.supports)
    assert list(ds["mode"].values) == list(result.modal_model.names)
    for quantity in VARIABLES:
        variable = ds[quantity.name]
        assert variable.attrs["units"] == quantity.units
        assert variable.attrs["long_name"]
    assert ds["mode_energy_j"].dims == ("point", "ball_speed", "support", "mode")
    assert ds["reduced_mass_kg"].dims == ("point", "support")
    assert STATUS_OK in ds["status"].attrs["description"]
    assert ds.attrs["method"].startswith("approximate")
    assert _same(ds.attrs["racket_speed_mps"], result.racket_speed)
    # labelled selection
    chosen = ds.sel(label="side", ball_speed_mps=20.0, support="free")  # the tip: NaN (issue 22)
    p, s, u = LABELS.index("side"), 1, result.support_index("free")
    assert float(chosen["contact_time_s"]) == result.contact_time[p, s, u]


def test_dataset_round_trips_the_values_exactly(result: ImpactResult) -> None:
    ds = result.to_xarray()
    for quantity in VARIABLES:
        assert _same(ds[quantity.name].values, getattr(result, quantity.attribute))
    assert _same(ds["racket_speed_mps"].values, result.racket_speed)
    assert _same(ds["x_m"].values, result.locations[:, 0])
    assert _same(ds["y_m"].values, result.locations[:, 1])
    assert tuple(ds["label"].values) == result.labels
    assert _same(ds["ball_speed_mps"].values, result.ball_speed)
    assert _same(ds["mode_energy_j"].values, result.mode_energy)
    assert _same(ds["status"].values, result.status)
    # and the dataset's long table is the CSV's, row for row
    frame = result.to_dataframe()
    stacked = ds["contact_time_s"].values.reshape(-1)
    assert _same(frame["contact_time_s"].to_numpy(), stacked)


def test_flagged_rows_are_nan_in_the_dataset(result: ImpactResult) -> None:
    ds = result.to_xarray()
    status = ds["status"].values
    beyond = status == STATUS_BEYOND_LAW
    assert beyond.any(), "200 m/s goes beyond the restoring-force law"
    for quantity in CELL_VARIABLES:
        assert np.isnan(ds[quantity.name].values[beyond]).all(), quantity.name
    for name in ("cor", "rebound_ratio", "rebound_speed_mps"):
        values = ds[name].values
        assert np.isnan(values[status == STATUS_VIBRATION_LOSS]).all()
        assert np.isnan(values[status != STATUS_OK]).all()
        assert np.isfinite(values[status == STATUS_OK]).all()


def test_dataset_writes_and_reads_netcdf(result: ImpactResult, tmp_path: Path) -> None:
    path = tmp_path / "impact.nc"
    result.to_xarray().to_netcdf(path, engine="scipy")
    with xr.open_dataset(path, engine="scipy") as read:
        assert _same(read["contact_time_s"].values, result.contact_time)
        assert _same(read["status"].values, result.status)
        assert read["contact_time_s"].attrs["units"] == "s"


def test_transient_dataset_holds_the_energy_balance(
    racket: rd.Racket, ball: rd.Ball, model: rd.ModalModel
) -> None:
    transient = predict_transient(racket, ball, LOCATIONS[:2], [20.0], modal_model=model)
    ds = transient.to_xarray()
    balance = ds["energy_balance_j"]
    assert balance.dims == ("point", "ball_speed", "support", "energy_term")
    assert list(ds["energy_term"].values) == list(transient.energy_terms)
    assert _same(balance.sel(energy_term="energy_in_j"), transient.energy_terms["energy_in_j"])
    assert ds.attrs["method"] == "transient"


def test_rigid_racket_has_no_mode_dimension(racket: rd.Racket, ball: rd.Ball) -> None:
    rigid = rd.predict(racket, ball, LOCATIONS[:1], [20.0], modal_model=None)
    ds = rigid.to_xarray()
    assert "mode" not in ds.sizes
    assert "rigid" in ds.attrs["modal_model"]
    assert "modes none" in repr(rigid)


@settings(max_examples=15, deadline=None)
@given(
    speeds=st.lists(st.floats(1.0, 60.0), min_size=1, max_size=3, unique=True),
    racket_speed=st.floats(0.0, 30.0),
)
def test_dataset_values_are_the_attributes_for_any_speeds(
    racket: rd.Racket, ball: rd.Ball, speeds: list[float], racket_speed: float
) -> None:
    result = rd.predict(
        racket, ball, LOCATIONS[:2], speeds, modal_model=None, racket_speed=racket_speed
    )
    ds = result.to_xarray()
    for quantity in VARIABLES:
        assert _same(ds[quantity.name].values, getattr(result, quantity.attribute))
    frame = result.to_dataframe()
    assert _same(frame["rebound_speed_mps"].to_numpy(), ds["rebound_speed_mps"].values.ravel())


# --- reprs --------------------------------------------------------------------------------------
def _looks_like_html(text: str) -> bool:
    tags = re.findall(r"<(/?)(table|caption|tbody|tr|th|td)\b", text)
    opened = [t for slash, t in tags if not slash]
    closed = [t for slash, t in tags if slash]
    return text.startswith("<table") and sorted(opened) == sorted(closed)


def test_impact_result_repr_is_short_and_says_what_it_is(result: ImpactResult) -> None:
    text = repr(result)
    assert len(text) < MAX_REPR
    assert "3 points × 4 ball speeds × 2 supports" in text
    flagged = int(np.count_nonzero(result.status != STATUS_OK))
    assert f"flagged {flagged} of 24" in text
    assert "approximate" in text
    assert "free, pinned" in text
    page = result._repr_html_()
    assert _looks_like_html(page)
    assert "200" in page
    assert f"{flagged} of 24" in page
    assert "centre" in page


def test_core_objects_have_short_reprs(
    racket: rd.Racket, ball: rd.Ball, model: rd.ModalModel
) -> None:
    modes = Modes(
        frequency=np.array([120.0, 330.0]),
        damping_ratio=np.array([0.03, 0.02]),
        constants=np.array([[6.0, 4.0], [-3.0, 2.5]]),
    )
    records = records_for(modes, n_averages=2)
    frfs = estimate_frfs(records).frfs
    impact = simulate_impact(racket, ball, LOCATIONS[0], 20.0, modal_model=model)
    for thing in (racket, ball, model, records, frfs, impact, racket.head, racket.strings):
        text = repr(thing)
        assert len(text) < MAX_REPR, (type(thing).__name__, len(text))
        assert type(thing).__name__ in text
    assert "0.36" in repr(racket)
    assert "120" in repr(model)
    assert "accelerance" in repr(frfs)
    for thing in (racket, model, records, frfs):
        page = thing._repr_html_()
        assert _looks_like_html(page), type(thing).__name__
    assert "120 Hz" in model._repr_html_()
    assert "0.36 kg" in racket._repr_html_()
    assert f"{records.n_samples}" in records._repr_html_()


def test_a_copy_of_the_status_array_keeps_any_status_written_into_it(
    racket: rd.Racket, ball: rd.Ball
) -> None:
    """New-user trial (2026-11-27, ninth session): ``np.asarray(result.status).copy()`` of an
    all-``ok`` result was two characters wide (``<U2``), so a longer status written into it was
    cut short without a word ("from the transient model: …" became "fr") and the row, filled
    with valid numbers, turned NaN.  Every impact result's statuses are as wide as the longest
    status any model gives."""
    from dataclasses import replace

    from racketdyn.impact.result import INVALIDATED, STATUS_FROM_TRANSIENT

    centre = [(racket.head.centre_x_m, 0.0)]
    longest = max((STATUS_OK, *INVALIDATED), key=len)
    swing = Swing(angular_speed_radps=20.0)
    for made in (
        rd.predict(racket, ball, centre, [20.0], "free"),
        predict_transient(racket, ball, centre, [20.0], "free", engine="reference"),
        predict_swing(racket, ball, centre, [20.0], swing, "free"),
    ):
        assert np.all(made.status == STATUS_OK)
        status = np.asarray(made.status).copy()
        status[0, 0, 0] = longest
        assert status[0, 0, 0] == longest
        status[0, 0, 0] = STATUS_FROM_TRANSIENT
        if isinstance(made, ImpactResult):  # a filled row keeps its numbers, marked
            filled = replace(made, status=status)
            assert filled.status[0, 0, 0] == STATUS_FROM_TRANSIENT
            assert np.isfinite(filled.rebound_ratio[0, 0, 0])
