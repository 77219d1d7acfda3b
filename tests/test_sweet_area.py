"""One "sweet area": the same definition and number in ``summary.csv`` and the summary figures.

Issue 27: ``summary.csv`` gave 0 cm² for 24 of 36 designs (the base design among them) while
the summary figure showed 55 cm² for the same design — the file compared each design with the
best point of every design in the sweep, the figure with the best of the designs it drew.
"""

from __future__ import annotations

import json
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest
import xarray as xr

import racketdyn as rd
from costly import costly
from racketdyn.plotting.primitives import SUPPORT_STYLE
from racketdyn.plotting.steps import sweep_figures
from racketdyn.plotting.sweep import plot_sweet_area
from racketdyn.sweep import (
    SWEET_AREA_DEFINITION,
    SerialExecutor,
    SweepSpec,
    Variable,
    run_sweep,
    summary_metrics,
    sweet_area_cm2,
)
from racketdyn.sweep.summary import summary_curves


@pytest.fixture(scope="module")
@costly
def swept(
    racket: rd.Racket, ball: rd.Ball, tmp_path_factory: pytest.TempPathFactory
) -> tuple[xr.Dataset, Path]:
    """e_BG and the frame's stiffness around the base, one at a time; grid 7, 20 m/s.

    A lively bed (e_BG 0.95) lifts the best point of the sweep far above the base design's.
    """
    spec = SweepSpec(
        racket=racket,
        ball=ball,
        locations=racket.head.grid(7),
        ball_speeds=[20.0],
        variables=(
            Variable.scalar("e_bg", [0.70, 0.95]),
            Variable.scalar("frame_stiffness_scale", [0.8, 1.2]),
        ),
        mode="one-at-a-time",
        name="sweet",
    )
    out = tmp_path_factory.mktemp("sweet")
    return run_sweep(spec, out, SerialExecutor(), figures=sweep_figures), out


def _csv_areas(out: Path) -> pd.DataFrame:
    return pd.read_csv(out / "summary.csv", index_col="design")


@pytest.mark.slow
def test_an_ordinary_racket_has_a_sweet_area(swept: tuple[xr.Dataset, Path]) -> None:
    ds, out = swept
    table = _csv_areas(out)
    for support in ds["support"].values:
        areas = table[f"sweet_area_cm2_{support}"].to_numpy()
        assert np.all(areas > 0.0), (support, areas)
        assert np.all(areas < ds.attrs["head_area_cm2"])
        assert np.all(table[f"best_rebound_ratio_{support}"] > 0.0)
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    assert any(SWEET_AREA_DEFINITION in note for note in record["notes"])


@pytest.mark.parametrize("variable", ["e_bg", "frame_stiffness_scale"])
def test_the_csv_and_the_figure_give_one_sweet_area(
    swept: tuple[xr.Dataset, Path], variable: str
) -> None:
    ds, out = swept
    table = _csv_areas(out)
    figure, ax = plt.subplots()
    try:
        plot_sweet_area(summary_curves(ds, variable), ax=ax)
        lines = {line.get_label(): line for line in ax.get_lines()}
        for support in ds["support"].values:
            line = lines[str(SUPPORT_STYLE[str(support)]["label"])]
            coord = "e_bg" if variable == "e_bg" else "frame_stiffness_scale"
            designs = [
                int(np.flatnonzero(np.isclose(ds[coord].values, x) & _shows(ds, variable))[0])
                for x in line.get_xdata()
            ]
            np.testing.assert_allclose(
                line.get_ydata(), table[f"sweet_area_cm2_{support}"].to_numpy()[designs]
            )
    finally:
        plt.close(figure)


def _shows(ds: xr.Dataset, variable: str) -> np.ndarray:
    varied = ds["varied"].values
    return np.asarray((varied == variable) | (varied == "base"))


def test_one_function_defines_it(swept: tuple[xr.Dataset, Path]) -> None:
    ds, _ = swept
    metrics = summary_metrics(ds)
    rebound = ds["rebound_ratio"].sel(speed=20.0, racket_speed=0.0)
    for design in range(ds.sizes["design"]):
        for support in ds["support"].values:
            values = rebound.isel(design=design).sel(support=support).values
            assert metrics["sweet_area_cm2"].isel(design=design).sel(
                support=support
            ).item() == pytest.approx(
                sweet_area_cm2(values, ds.attrs["head_area_cm2"], ds.attrs["threshold_fraction"])
            )


def test_the_definition() -> None:
    # 10 points over 100 cm²: the best 0.5, within 10 % of it (>= 0.45): 0.5, 0.47, 0.45
    face = np.array([0.5, 0.47, 0.45, 0.44, 0.3, 0.2, 0.1, 0.0, -0.1, np.nan])
    assert sweet_area_cm2(face, 100.0, 0.9) == pytest.approx(3 * 100.0 / 10)
    # a face rebounding backwards everywhere (a frame-dominated tip region) still has its best
    backwards = np.array([-0.10, -0.105, -0.2, -0.3])
    assert sweet_area_cm2(backwards, 40.0, 0.9) == pytest.approx(2 * 10.0)
    assert np.isnan(sweet_area_cm2(np.full(4, np.nan), 40.0, 0.9))
    # per design and support at once: the last axis is the points
    both = np.stack([face, face[::-1]])
    np.testing.assert_allclose(sweet_area_cm2(both, 100.0, 0.9), [30.0, 30.0])
