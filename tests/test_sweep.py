"""Design sweeps: the same bits on every engine, the physics, resuming, retries, spec errors."""

from __future__ import annotations

import json
import os
import re
from collections.abc import Callable, Iterator
from concurrent.futures import Future
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr
from distributed import LocalCluster

import racketdyn as rd
import racketdyn.sweep as sweep
import racketdyn.sweep.task as sweep_task
import sweep_faults
from costly import costly
from racketdyn.impact.hand import Hand
from racketdyn.impact.transient import predict_transient
from racketdyn.plotting.steps import sweep_figures
from racketdyn.plotting.sweep import plot_centre_rebound, plot_sweet_area
from racketdyn.sweep import (
    SerialExecutor,
    SweepSpec,
    TaskOptions,
    Variable,
    build_design,
    build_hand,
    factorial_view,
    load_sweep_spec,
    make_executor,
    run_sweep,
    summary_metrics,
    sweet_area_resolution_cm2,
    variable_designs,
)
from racketdyn.sweep.summary import summary_curves
from racketdyn.workflows.setup import Setup

assert_same_bits = sweep_faults.assert_same_bits

DOCS = Path(__file__).resolve().parents[1] / "docs" / "sweep-file.md"


class CountingExecutor(SerialExecutor):
    """Runs tasks in this process and records the task ids submitted."""

    def __init__(self) -> None:
        self.submitted: list[str] = []

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Future[Any]:
        self.submitted.extend(task.task_id for task in args[0])
        return super().submit(fn, *args, **kwargs)


# --- fixtures ---------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def cluster() -> Iterator[LocalCluster]:
    """One real local Dask cluster for the module (starting one is the slow part).

    Its HTTP server on a free port (``":0"``): with ``None`` the scheduler still serves HTTP on
    8787, and where that port is taken it warns and leaks a socket (ResourceWarning).
    """
    with LocalCluster(
        n_workers=2, processes=True, threads_per_worker=1, dashboard_address=":0"
    ) as local:
        yield local


@pytest.fixture(scope="module")
@costly
def one_at_a_time(
    racket: rd.Racket, ball: rd.Ball, tmp_path_factory: pytest.TempPathFactory
) -> tuple[xr.Dataset, Path]:
    """Lead at the tip, e_BG and a very stiff frame, each around the base; grid 5, 10 m/s."""
    spec = SweepSpec(
        racket=racket,
        ball=ball,
        locations=racket.head.grid(5),
        ball_speeds=[10.0],
        variables=(
            Variable.point_mass([0.0, 0.010], clock=12, head=racket.head),
            Variable.scalar("e_bg", [0.83, 0.88]),
            Variable.scalar("frame_stiffness_scale", [1.0, 1.0e4]),
        ),
        mode="one-at-a-time",
        name="physics",
    )
    out = tmp_path_factory.mktemp("physics")
    return run_sweep(spec, out, SerialExecutor(), figures=sweep_figures), out


def design(dataset: xr.Dataset, varied: str) -> xr.Dataset:
    index = np.flatnonzero(dataset["varied"].values == varied)
    assert index.size == 1, varied
    return dataset.isel(design=int(index[0]))


# --- engines ----------------------------------------------------------------------------------
@pytest.mark.parametrize("engine", ["process", "dask"])
@pytest.mark.slow
def test_every_engine_gives_the_same_bits(
    engine: str,
    small_spec: SweepSpec,
    serial_result: xr.Dataset,
    cluster: LocalCluster,
    tmp_path: Path,
) -> None:
    scheduler = cluster.scheduler_address if engine == "dask" else None
    progress: list[tuple[int, int]] = []
    with make_executor(engine, workers=2, scheduler=scheduler) as executor:  # type: ignore[arg-type]
        result = run_sweep(
            small_spec,
            tmp_path,
            executor,
            progress=lambda done, total: progress.append((done, total)),
            figures=None,
        )
    assert_same_bits(serial_result, result)
    assert progress[0] == (0, 6)
    assert progress[-1] == (6, 6)
    with sweep.open_sweep(tmp_path) as written:
        assert_same_bits(serial_result, written.load())


@pytest.mark.slow
def test_a_local_dask_cluster_from_make_executor(
    small_spec: SweepSpec,
    serial_result: xr.Dataset,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # A nanny writes its worker variables into this process's environment before it spawns
    # (distributed's doing): the module's cluster left MALLOC_TRIM_THRESHOLD_ here.
    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    with make_executor("dask-local", workers=1) as executor:
        # make_executor leaves it out (with it, glibc maps every large array anew: ≈ 1.7 ×
        # slower tasks)
        assert executor.submit(os.environ.get, "MALLOC_TRIM_THRESHOLD_").result() is None
        result = run_sweep(small_spec, tmp_path, executor, figures=None)
    assert_same_bits(serial_result, result)


@pytest.mark.slow
def test_the_engine_closes_before_the_store_is_finished(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    """A local Dask scheduler runs in this process and slowed combining 2.3× while it lived:
    the command closes its engine when the tasks are done (``when_tasks_done``), before
    the store is finished — every design is in it then and it is not complete yet; run.json
    times it."""
    seen: list[tuple[int, bool]] = []

    def closing() -> None:
        seen.append(
            (len(sweep_faults.designs_done(tmp_path)), sweep_faults.store_complete(tmp_path))
        )

    result = run_sweep(
        small_spec, tmp_path, SerialExecutor(), figures=None, when_tasks_done=closing
    )
    assert seen == [(len(small_spec.designs), False)]
    assert_same_bits(serial_result, result)
    record = json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))
    assert record["time_s"]["shutdown"] >= 0.0
    # the workflow the command calls passes its own engine's close
    from racketdyn.workflows import run_sweep_step

    out = tmp_path / "step"
    run_sweep_step(small_spec, out, engine="dask-local", workers=1, setup=Setup(figures=None))
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    assert "shutdown" in record["time_s"]


def test_dataset_layout(small_spec: SweepSpec, serial_result: xr.Dataset) -> None:
    ds = serial_result
    assert ds["rebound_ratio"].dims == ("design", "point", "speed", "racket_speed", "support")
    assert dict(ds.sizes) == {
        "design": 6,
        "point": 12,
        "speed": 2,
        "racket_speed": 1,
        "support": 2,
        "mode": 3,
    }
    assert ds["contact_time_s"].attrs["units"] == "s"
    assert ds["status"].dtype == np.int8
    assert ds.attrs["spec_sha256"] == small_spec.sha256
    assert ds.attrs["racketdyn_version"] == rd.__version__
    assert json.loads(ds.attrs["spec"])["variables"][1]["name"] == "e_bg"
    # full factorial, the first variable slowest; point masses add to the racket's mass
    np.testing.assert_array_equal(ds["e_bg"].values, [0.80, 0.86] * 3)
    np.testing.assert_allclose(
        ds["racket_mass_kg"].values - ds["point_mass_mass_kg"].values, small_spec.racket.mass_kg
    )
    # each design equals a direct prediction of its racket and ball
    racket, ball, _ = build_design(
        small_spec.racket, small_spec.ball, small_spec.variables, small_spec.designs[3].settings
    )
    direct = rd.predict(racket, ball, small_spec.locations, small_spec.ball_speeds)
    # to the rounding of the mode-shape interpolator's dense solve, which the sweep does on one
    # BLAS thread and this process may split over several (seen: 6e-9 on a ratio of 0.0045, so an
    # absolute floor as well)
    np.testing.assert_allclose(
        ds["rebound_ratio"].isel(design=3, racket_speed=0).values,
        direct.rebound_ratio,
        rtol=1e-6,
        atol=1e-7,
    )
    view = factorial_view(ds)
    assert view["rebound_ratio"].sizes["point_mass_mass_kg"] == 3
    assert view["rebound_ratio"].sizes["e_bg"] == 2


def test_default_engine_is_serial_for_small_sweeps(small_spec: SweepSpec, tmp_path: Path) -> None:
    run_sweep(small_spec, tmp_path, figures=None)
    assert json.loads((tmp_path / "run.json").read_text())["engine"] == "SerialExecutor"


# --- physics ----------------------------------------------------------------------------------
@pytest.mark.slow
def test_lead_at_the_tip_raises_rebound_near_the_tip_when_pinned(
    one_at_a_time: tuple[xr.Dataset, Path],
) -> None:
    ds, _ = one_at_a_time
    base, lead = design(ds, "base"), design(ds, "point_mass")
    # the farthest point on the axis the approximate method gives a number for (issue 22: the
    # last one, near the frame, takes over 30 % of the approach energy)
    given = (
        base["rebound_ratio"].isel(speed=0, racket_speed=0).sel(support="pinned").notnull().values
    )
    on_axis = (np.abs(ds["y_m"].values) < 1e-9) & given
    tip = int(np.argmax(np.where(on_axis, ds["x_m"].values, -np.inf)))
    before = float(
        base["rebound_ratio"].isel(point=tip, speed=0, racket_speed=0).sel(support="pinned")
    )
    after = float(
        lead["rebound_ratio"].isel(point=tip, speed=0, racket_speed=0).sel(support="pinned")
    )
    assert np.isfinite(before)
    assert after > before + 0.01
    assert float(lead["racket_swingweight_kgcm2"]) > float(base["racket_swingweight_kgcm2"])


def test_higher_e_bg_raises_rebound_everywhere(one_at_a_time: tuple[xr.Dataset, Path]) -> None:
    ds, _ = one_at_a_time
    base, livelier = design(ds, "base"), design(ds, "e_bg")
    ok = (base["status"] == 0) & (livelier["status"] == 0)
    # the rim: frame shots and rows beyond the approximate method (issue 22)
    assert int(ok.sum()) > 0.4 * ok.size
    assert bool((livelier["rebound_ratio"] > base["rebound_ratio"]).where(ok, True).all())


def test_a_very_stiff_frame_hardly_vibrates(one_at_a_time: tuple[xr.Dataset, Path]) -> None:
    ds, _ = one_at_a_time
    base, stiff = design(ds, "base"), design(ds, "frame_stiffness_scale")
    np.testing.assert_allclose(
        stiff["mode_frequency_hz"].values, 100.0 * base["mode_frequency_hz"].values, rtol=1e-9
    )
    energy, reference = stiff["vibration_energy_j"].values, base["vibration_energy_j"].values
    both = np.isfinite(energy) & np.isfinite(reference)  # the base's rim: over 30 % (issue 22)
    assert np.all(energy[both] <= reference[both])
    assert np.nanmax(energy) < 1e-3 * np.nanmax(reference)


def test_frame_stiffness_scales_a_modal_model_file(
    racket: rd.Racket, ball: rd.Ball, model: rd.ModalModel, tmp_path: Path
) -> None:
    model.write_json(tmp_path / "modes.json")
    spec = SweepSpec(
        racket=replace(racket, modal_model_file=tmp_path / "modes.json"),
        ball=ball,
        locations=[(0.5, 0.0), (0.6, 0.02)],
        ball_speeds=[15.0],
        variables=(Variable.scalar("frame_stiffness_scale", [1.0, 4.0]),),
    )
    ds = run_sweep(spec, tmp_path / "out", SerialExecutor(), figures=None)
    frequency = ds["mode_frequency_hz"].values
    np.testing.assert_allclose(frequency[1], 2.0 * frequency[0], rtol=1e-12)


def test_swingweight_variable_sets_the_swingweight(racket: rd.Racket, ball: rd.Ball) -> None:
    spec = SweepSpec(
        racket=racket,
        ball=ball,
        locations=racket.head.grid(3),
        ball_speeds=[20.0],
        variables=(Variable.scalar("swingweight_kgcm2", [280.0, 320.0]),),
    )
    for d, wanted in zip(spec.designs, (280.0, 320.0), strict=True):
        built, _, _ = build_design(spec.racket, spec.ball, spec.variables, d.settings)
        assert built.swingweight_kgcm2 == pytest.approx(wanted, rel=1e-12)
        assert built.balance_m == racket.balance_m


# --- the transient method ---------------------------------------------------------------------
CENTRE, NEAR_TIP, OFF_AXIS = (0.505, 0.0), (0.62, 0.0), (0.45, 0.06)


def test_transient_sweep_equals_direct_calls(
    racket: rd.Racket, ball: rd.Ball, tmp_path: Path
) -> None:
    """Each design's numbers are those of predict_transient on its racket and ball, for each
    (ball speed, racket speed) pair the sweep combines."""
    spec = SweepSpec(
        racket=racket,
        ball=ball,
        locations=[CENTRE, NEAR_TIP, OFF_AXIS],
        ball_speeds=[10.0, 25.0],
        racket_speeds=[0.0, 10.0],
        variables=(Variable.scalar("e_bg", [0.80, 0.86]),),
        method="transient",
        name="transient",
    )
    ds = run_sweep(spec, tmp_path, SerialExecutor(), figures=None)
    assert ds.attrs["method"] == "transient"
    assert np.all(ds["status"].values == 0)
    for design in spec.designs:
        racket_d, ball_d, _ = build_design(racket, ball, spec.variables, design.settings)
        for k, swing in enumerate(spec.racket_speeds):
            direct = predict_transient(
                racket_d, ball_d, spec.locations, spec.ball_speeds, spec.supports, swing
            )
            for name, attribute in (
                ("rebound_ratio", "rebound_ratio"),
                ("rebound_speed_mps", "rebound_speed"),
                ("contact_time_s", "contact_time"),
                ("peak_force_n", "peak_force"),
                ("vibration_energy_j", "vibration_energy"),
            ):
                # to the rounding of the mode-shape interpolator (one BLAS thread in the sweep)
                np.testing.assert_allclose(
                    ds[name].isel(design=design.index, racket_speed=k).values,
                    getattr(direct, attribute),
                    rtol=1e-6,
                    err_msg=name,
                )
    # the livelier ball rebounds faster at every impact (the hysteresis returns e_BG² of the
    # stored energy)
    slow, lively = (ds["rebound_speed_mps"].isel(design=i).values for i in (0, 1))
    assert np.all(lively > slow)


ENGINE_SPEC = """
[impacts]
points = "points.csv"
ball_speeds_mps = [25.0]
method = "transient"
engine = "ENGINE"

[variables]
e_bg = [0.80, 0.86]
"""


def _engine_spec(tmp_path: Path, engine: str) -> SweepSpec:
    (tmp_path / "points.csv").write_text("x_m,y_m\n0.505,0.0\n0.62,0.0\n0.45,0.06\n")
    path = tmp_path / f"{engine}.toml"
    path.write_text(ENGINE_SPEC.replace("ENGINE", engine), encoding="utf-8")
    return load_sweep_spec(path)


@pytest.mark.slow
def test_the_engine_key_chooses_the_transient_engine(
    racket: rd.Racket, ball: rd.Ball, tmp_path: Path
) -> None:
    """``[impacts].engine`` reaches predict_transient: the reference engine's numbers are
    predict_transient's with engine="reference" and differ from the compiled engine's by its
    documented accuracy (≈ 3e-5 m/s, 128 steps per contact extrapolated), no more."""
    specs = {engine: _engine_spec(tmp_path, engine) for engine in ("reference", "compiled")}
    results = {
        engine: run_sweep(spec, tmp_path / engine, SerialExecutor(), figures=None)
        for engine, spec in specs.items()
    }
    reference, compiled = results["reference"], results["compiled"]
    assert reference.attrs["engine"] == "reference"
    assert compiled.attrs["engine"] == "compiled"
    spec = specs["reference"]
    for design in spec.designs:
        racket_d, ball_d, _ = build_design(racket, ball, spec.variables, design.settings)
        direct = predict_transient(
            racket_d, ball_d, spec.locations, spec.ball_speeds, spec.supports, engine="reference"
        )
        np.testing.assert_allclose(
            reference["rebound_speed_mps"].isel(design=design.index, racket_speed=0).values,
            direct.rebound_speed,
            rtol=1e-6,
        )
    gap = np.abs(reference["rebound_speed_mps"] - compiled["rebound_speed_mps"]).values
    assert 0 < gap.max() < 1e-3  # two engines, one answer to their accuracy
    # the engine is part of what the results depend on: parts of one are not resumed by the
    # other; auto is the engine numba allows here, decided when the spec is read
    assert specs["reference"].sha256 != specs["compiled"].sha256
    auto = _engine_spec(tmp_path, "auto")
    assert auto.transient_engine == "compiled"  # numba is a dependency
    assert auto.sha256 == specs["compiled"].sha256
    counting = CountingExecutor()
    run_sweep(auto, tmp_path / "compiled", counting, figures=None)
    assert counting.submitted == []  # all resumed


def test_the_compiled_scheme_is_in_the_hash(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The compiled engine's numerics (steps, extrapolation: issue 16 changed them) are part
    of what a transient sweep's numbers depend on, so parts made with another scheme are
    recomputed, not resumed; the reference engine's hash does not depend on them."""
    before = {engine: _engine_spec(tmp_path, engine).sha256 for engine in ("compiled", "reference")}
    monkeypatch.setattr("racketdyn.sweep.spec.COMPILED_SCHEME", "400 steps per contact")
    after = {engine: _engine_spec(tmp_path, engine).sha256 for engine in ("compiled", "reference")}
    assert after["compiled"] != before["compiled"]
    assert after["reference"] == before["reference"]


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (('"transient"', '"approximate"'), r"\[impacts\]\.engine = 'reference' is for method"),
        (('"reference"', '"fast"'), r"\[impacts\]\.engine must be one of auto, compiled"),
    ],
)
def test_a_bad_engine_key_is_one_line(edit: tuple[str, str], message: str, tmp_path: Path) -> None:
    (tmp_path / "points.csv").write_text("x_m,y_m\n0.505,0.0\n")
    path = tmp_path / "spec.toml"
    text = ENGINE_SPEC.replace("ENGINE", "reference")
    path.write_text(text.replace(*edit), encoding="utf-8")
    with pytest.raises(rd.InputError, match=message):
        load_sweep_spec(path)


def test_hand_variables_change_the_hand_support_only(
    racket: rd.Racket, ball: rd.Ball, tmp_path: Path
) -> None:
    spec = SweepSpec(
        racket=racket,
        ball=ball,
        locations=[CENTRE, NEAR_TIP],
        ball_speeds=[20.0],
        supports=("free", "hand"),
        variables=(Variable.scalar("hand.arm_mass_kg", [0.5, 2.0]),),
        method="transient",
        name="arm",
    )
    ds = run_sweep(spec, tmp_path, SerialExecutor(), figures=sweep_figures)
    np.testing.assert_array_equal(ds["hand.arm_mass_kg"].values, [0.5, 2.0])
    free = ds["rebound_ratio"].sel(support="free").values
    np.testing.assert_allclose(free[0], free[1], rtol=1e-12)
    for design in spec.designs:
        hand = build_hand(spec.variables, design.settings)
        assert hand.arm_mass_kg == dict(design.settings)["hand.arm_mass_kg"]
        assert hand.stiffness_n_per_m == Hand().stiffness_n_per_m  # not swept
        direct = predict_transient(racket, ball, spec.locations, [20.0], ("hand",), hand=hand)
        np.testing.assert_allclose(
            ds["rebound_ratio"].isel(design=design.index, racket_speed=0).sel(support="hand"),
            direct.rebound_ratio[:, :, 0],
            rtol=1e-6,
        )
    assert (tmp_path / "summary_hand.arm_mass_kg.png").stat().st_size > 10_000
    import matplotlib.pyplot as plt

    figure, ax = plt.subplots()
    assert (
        plot_centre_rebound(summary_curves(ds, "hand.arm_mass_kg"), ax=ax).get_xlabel()
        == "arm mass (kg)"
    )
    plt.close(figure)


def test_hand_variables_as_dotted_keys_or_a_table(tmp_path: Path) -> None:
    head = TRANSIENT + "support = ['hand']\n"
    dotted = head + "hand.arm_mass_kg = [0.5, 1.5]\nhand.damping_ns_per_m = 20.0\n"
    table = head + "[variables.hand]\narm_mass_kg = [0.5, 1.5]\ndamping_ns_per_m = 20.0\n"
    specs = []
    for name, text in (("dotted", dotted), ("table", table)):
        (tmp_path / f"{name}.toml").write_text(text, encoding="utf-8")
        specs.append(load_sweep_spec(tmp_path / f"{name}.toml"))
    assert specs[0].sha256 == specs[1].sha256
    assert [v.name for v in specs[0].variables] == ["hand.arm_mass_kg", "hand.damping_ns_per_m"]
    hands = [build_hand(specs[0].variables, d.settings) for d in specs[0].designs]
    assert [(h.arm_mass_kg, h.damping_ns_per_m) for h in hands] == [(0.5, 20.0), (1.5, 20.0)]


def test_every_transient_status_has_a_code() -> None:
    import racketdyn.impact.transient as transient

    statuses = {
        value
        for name, value in vars(transient).items()
        if name.startswith("STATUS_") and isinstance(value, str)
    }
    assert transient.STATUS_NO_SEPARATION in statuses
    assert statuses <= set(sweep.STATUS_CODES)
    assert len(set(sweep.STATUS_CODES.values())) == len(sweep.STATUS_CODES)


# --- summary ----------------------------------------------------------------------------------
def test_summary_figures_and_table(one_at_a_time: tuple[xr.Dataset, Path]) -> None:
    ds, out = one_at_a_time
    for name in ("point_mass", "e_bg", "frame_stiffness_scale"):
        assert (out / f"summary_{name}.png").stat().st_size > 10_000
    table = (out / "summary.csv").read_text().splitlines()
    assert len(table) == 1 + ds.sizes["design"]
    assert "centre_rebound_ratio_pinned" in table[0]
    np.testing.assert_array_equal(variable_designs(ds, "e_bg"), [0, 2])
    metrics = summary_metrics(ds)
    assert metrics.attrs["centre_point_x_m"] == pytest.approx(ds.attrs["head_centre_x_m"])
    assert np.all(metrics["sweet_area_cm2"].values <= ds.attrs["head_area_cm2"])
    # trial of 2026-11-23: the table did not say its speed, the titles showed the key
    # "tension n", and a grid-5 sweet area (14 points, 45 cm² a step) came with no word
    header = table[0].split(",")
    assert {"ball_speed_mps", "racket_speed_mps"} <= set(header)
    speed = float(table[1].split(",")[header.index("ball_speed_mps")])
    assert speed == metrics.attrs["ball_speed_mps"]
    step = sweet_area_resolution_cm2(ds)
    assert step == pytest.approx(ds.attrs["head_area_cm2"] / ds.sizes["point"])
    areas = metrics["sweet_area_cm2"].values
    np.testing.assert_allclose(areas / step, np.round(areas / step), atol=1e-9)
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    assert any("steps of" in note and "finer" in note for note in record["notes"])
    import matplotlib.pyplot as plt

    figure, (left, right) = plt.subplots(1, 2)
    assert plot_centre_rebound(summary_curves(ds, "point_mass"), ax=left) is left
    assert plot_sweet_area(summary_curves(ds, "e_bg"), ax=right) is right
    assert left.get_xlabel() == "point mass (g)"
    plt.close(figure)


def test_summary_figure_drawn_through_the_registry_from_the_store(
    one_at_a_time: tuple[xr.Dataset, Path], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Issue 23: the summary figures are the registry's ``summary`` entry, drawn from the
    curves the sweep computes; the folder's store alone redraws them the same."""
    import matplotlib.pyplot as plt

    from racketdyn.plotting import registry, render
    from racketdyn.sweep import open_sweep
    from racketdyn.sweep.summary import summary_figures_data

    ds, out = one_at_a_time
    saved: dict[str, Any] = {}
    monkeypatch.setattr(
        render, "save_figure", lambda figure, path: saved.setdefault(path.name, figure) and path
    )
    written = sweep_figures(summary_figures_data(ds), out)
    assert {p.name for p in written} == {
        f"summary_{v}.png" for v in ("point_mass", "e_bg", "frame_stiffness_scale")
    }
    assert all(registry.of_file(p.name) is registry.FIGURES["summary"] for p in written)
    curves = summary_curves(open_sweep(out), "e_bg")  # the folder alone
    redrawn = registry.draw("summary", {"curves": curves})
    try:
        for drawn_ax, redrawn_ax in zip(saved["summary_e_bg.png"].axes, redrawn.axes, strict=True):
            for a, b in zip(drawn_ax.get_lines(), redrawn_ax.get_lines(), strict=True):
                np.testing.assert_array_equal(a.get_xydata(), b.get_xydata())
        assert saved["summary_e_bg.png"].get_suptitle() == redrawn.get_suptitle()
    finally:
        plt.close(redrawn)
        for figure in saved.values():
            plt.close(figure)


# --- resuming and failures --------------------------------------------------------------------
@pytest.mark.slow
def test_a_rerun_computes_only_missing_designs(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    run_sweep(small_spec, tmp_path, SerialExecutor(), figures=None)
    sweep_faults.chunk_file(tmp_path, "cor", 3).unlink()  # design 3's chunk (one design each)
    counting, progress = CountingExecutor(), []
    result = run_sweep(
        small_spec,
        tmp_path,
        counting,
        progress=lambda done, total: progress.append((done, total)),
        figures=None,
    )
    assert counting.submitted == ["design-00003"]
    assert progress == [(5, 6), (6, 6)]
    assert_same_bits(serial_result, result)


@pytest.mark.slow
def test_an_interrupted_sweep_resumes(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    def interrupt(done: int, total: int) -> None:
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(small_spec, tmp_path, SerialExecutor(), progress=interrupt, figures=None)
    assert sweep_faults.designs_done(tmp_path) == [0, 1]
    with pytest.raises(rd.InputError, match="has not finished"):
        sweep.open_sweep(tmp_path)
    counting = CountingExecutor()
    result = run_sweep(small_spec, tmp_path, counting, figures=None)
    assert counting.submitted == [f"design-{i:05d}" for i in range(2, 6)]
    assert_same_bits(serial_result, result)


def test_chunks_written_in_any_order_give_the_same_store(
    small_spec: SweepSpec, serial_result: xr.Dataset, tmp_path: Path
) -> None:
    """Chunks arrive in any order, a chunk's designs in several writes: the same numbers."""
    from racketdyn.sweep import store

    store.create_store(small_spec, tmp_path, designs_per_chunk=4)
    outputs = {d.index: rd.sweep.run_task(small_spec.task(d)) for d in small_spec.designs}
    for indices in ([5], [4], [2, 0], [3], [1]):
        store.write_chunk(tmp_path, small_spec.sha256, indices, [outputs[i] for i in indices])
    records = store.read_records(tmp_path, small_spec.sha256)
    store.write_modes(tmp_path, small_spec, records)
    store.set_complete(tmp_path, small_spec.sha256, True)
    written = sweep.open_sweep(tmp_path)
    for name in serial_result.data_vars:
        assert written[name].values.tobytes() == serial_result[name].values.tobytes(), name


@pytest.mark.slow
def test_parts_of_another_spec_are_recomputed(small_spec: SweepSpec, tmp_path: Path) -> None:
    run_sweep(small_spec, tmp_path, SerialExecutor(), figures=None)
    changed = replace(small_spec, ball_speeds=np.array([10.0, 26.0]))
    counting = CountingExecutor()
    result = run_sweep(changed, tmp_path, counting, figures=None)
    assert len(counting.submitted) == 6
    assert result.attrs["spec_sha256"] == changed.sha256 != small_spec.sha256


def _fail_design_3(times: int) -> Callable[..., rd.ImpactResult]:
    """predict that fails ``times`` times for design 3 (5 g of lead, e_BG 0.86)."""
    real, calls = rd.predict, []

    def flaky(racket: rd.Racket, ball: rd.Ball, *args: Any, **kwargs: Any) -> rd.ImpactResult:
        lead = [p.mass_kg for p in racket.point_masses]
        if lead == [0.005] and ball.e_bg == 0.86 and len(calls) < times:
            calls.append(1)
            raise RuntimeError("worker lost")
        return real(racket, ball, *args, **kwargs)

    return flaky


@pytest.mark.slow
def test_a_failed_task_is_retried(
    small_spec: SweepSpec,
    serial_result: xr.Dataset,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
) -> None:
    monkeypatch.setattr(sweep_task, "predict", _fail_design_3(times=1))
    counting = CountingExecutor()
    result = run_sweep(small_spec, tmp_path, counting, figures=None)
    assert counting.submitted.count("design-00003") == 2
    assert len(counting.submitted) == 7
    assert "retrying" in caplog.text
    assert result.attrs["n_failed"] == 0
    assert not (tmp_path / "failures.json").exists()
    assert_same_bits(serial_result, result)


def test_a_failed_batch_reruns_only_its_unfinished_designs(
    small_spec: SweepSpec,
    serial_result: xr.Dataset,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Batches of two: design 2 ends (its part written where it ran), then design 3 fails;
    the batch was split and both ran again, design 2 for nothing.  Now design 2 is taken
    from its file and only design 3 is retried."""
    monkeypatch.setattr(sweep_task, "predict", _fail_design_3(times=1))
    counting = CountingExecutor()
    result = run_sweep(
        small_spec, tmp_path, counting, options=TaskOptions(designs_per_task=2), figures=None
    )
    assert counting.submitted.count("design-00002") == 1
    assert counting.submitted.count("design-00003") == 2
    assert len(counting.submitted) == 7
    assert result.attrs["n_failed"] == 0
    assert_same_bits(serial_result, result)


def test_a_task_that_always_fails_is_reported_and_the_rest_kept(
    small_spec: SweepSpec,
    serial_result: xr.Dataset,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(sweep_task, "predict", _fail_design_3(times=99))
    result = run_sweep(small_spec, tmp_path, SerialExecutor(), figures=None)
    failures = json.loads((tmp_path / "failures.json").read_text())
    assert [f["task_id"] for f in failures] == ["design-00003"]
    assert failures[0]["attempts"] == 2
    assert "RuntimeError: worker lost" in failures[0]["error"]
    assert result.attrs["n_failed"] == 1
    assert json.loads(result.attrs["failed_tasks"])[0]["design"]["e_bg"] == 0.86
    assert np.all(result["status"].isel(design=3).values == sweep.STATUS_CODES["task failed"])
    assert np.all(np.isnan(result["rebound_ratio"].isel(design=3).values))
    others = [0, 1, 2, 4, 5]
    for name in ("rebound_ratio", "vibration_energy_j", "status"):
        np.testing.assert_array_equal(
            result[name].isel(design=others).values,
            serial_result[name].isel(design=others).values,
        )
    # fixed, a rerun computes the failed design only and clears the failure record
    monkeypatch.undo()
    counting = CountingExecutor()
    rerun = run_sweep(small_spec, tmp_path, counting, figures=None)
    assert counting.submitted == ["design-00003"]
    assert not (tmp_path / "failures.json").exists()
    assert_same_bits(serial_result, rerun)


# --- the spec file ----------------------------------------------------------------------------
BASE = """
[impacts]
grid = 4
ball_speeds_mps = [20.0]

[variables]
e_bg = [0.80, 0.86]
"""


TRANSIENT = """
[impacts]
grid = 3
ball_speeds_mps = [20.0]
method = "transient"

[variables]
"""


def test_the_documented_example_is_valid(tmp_path: Path) -> None:
    block = re.search(r"```toml\n(.*?)```", DOCS.read_text(encoding="utf-8"), re.DOTALL)
    assert block is not None
    (tmp_path / "sweep.toml").write_text(block.group(1), encoding="utf-8")
    spec = load_sweep_spec(tmp_path / "sweep.toml")
    assert len(spec.designs) == 27
    assert spec.n_impacts == 22_356  # the count the documentation gives
    lead = spec.variables[2]
    assert lead.values[-1] == pytest.approx((0.010, spec.racket.head.tip_x_m, 0.0, 12.0))


def test_one_at_a_time_from_a_file(tmp_path: Path) -> None:
    text = (
        'mode = "one-at-a-time"\n'
        + BASE
        + (
            "tension_n = { start = 206.0, stop = 286.0, num = 3 }\n"
            "[[variables.point_mass]]\nlabel = 'tip'\nmass_kg = [0.0, 0.005]\nx_m = 0.66\n"
            "[[variables.point_mass]]\nlabel = 'side'\nmass_kg = 0.003\nclock = [3, 9]\n"
        )
    )
    (tmp_path / "spec.toml").write_text(text, encoding="utf-8")
    spec = load_sweep_spec(tmp_path / "spec.toml")
    # base + e_bg 2 + tension 2 (246 N is the base) + tip 1 (0 g is the base) + side 2
    assert [d.varied for d in spec.designs] == [
        "base",
        "e_bg",
        "e_bg",
        "tension_n",
        "tension_n",
        "point_mass_tip",
        "point_mass_side",
        "point_mass_side",
    ]
    side = dict(spec.designs[-1].settings)
    assert side["point_mass_side_y_m"] == pytest.approx(spec.racket.head.half_width_m)  # 9: left


ALLOW = "[checks]\nallow_implausible = true\n"
"""Past the plausibility table (issue 26): the design-level checks behind it."""

BAD_SPECS = [
    ("foo = [1.0]\n", r"\[variables\]\.foo: unknown variable; allowed: point_mass"),
    (
        "hand_stiffness_n_per_m = [1e4]\n",
        r"\[variables\]\.hand_stiffness_n_per_m: unknown hand parameter; the hand parameters are "
        r"hand\.arm_mass_kg, hand\.stiffness_n_per_m, hand\.damping_ns_per_m",
    ),
    (
        "hand.arm_mass_kg = [0.5, 1.0]\n",  # the approximate method has no hand
        r"\[variables\]\.hand\.arm_mass_kg: hand parameters need \[impacts\]\.method = "
        r"'transient' and support 'hand'",
    ),
    ('tension_n = "high"\n', r"\[variables\]\.tension_n must be a number \(got 'high'\)"),
    (
        "tension_n = {start = 200.0, stop = 260.0}\n",
        r"\[variables\]\.tension_n: a range is a "
        r"table \{start, stop, num\}; num missing",
    ),
    ("e_bg_x = 1\n", r"\[variables\]\.e_bg_x: unknown variable"),
    (
        "balance_m = [0.30, 0.70]\n" + ALLOW,  # past the plausibility table: the design's
        r"\[variables\]\.balance_m: balance_m = 0\.7: racket\.balance_m \(0\.7 m\) must lie "
        r"between the butt and the tip",
    ),
    (
        "mass_kg = [0.15]\n" + ALLOW,
        r"\[variables\]\.mass_kg: mass_kg = 0\.15: racket: no positive mass distribution",
    ),
    (
        "mass_kg = [0.2]\ninertia_cg_kgm2 = [0.016]\n" + ALLOW,  # each fine alone, not together
        r"\[variables\]: design e_bg = 0\.8, mass_kg = 0\.2, inertia_cg_kgm2 = 0\.016: racket: no "
        r"positive mass distribution",
    ),
    ("frame_stiffness_scale = [0.0]\n", r"frame_stiffness_scale must be a positive number"),
    (
        "support = ['free', 'hand']\n",
        r"\[variables\]\.support: 'hand' needs \[impacts\]\.method = 'transient'; the approximate "
        r"method has no hand",
    ),
    (
        "inertia_cg_kgm2 = [0.013]\nswingweight_kgcm2 = [300.0]\n",
        r"give inertia_cg_kgm2 or "
        r"swingweight_kgcm2, not both",
    ),
    ("swingweight_kgcm2 = [100.0]\n" + ALLOW, r"swingweight_kgcm2 \(100\) must exceed"),
    ("swingweight_kgcm2 = [100.0]\n", r"swingweight_kgcm2 = 100: a racket's swingweight is"),
    (
        "[variables.point_mass]\nmass_kg = [0.005]\n",
        r"\[variables\]\.point_mass: give the "
        r"position as x_m \(and y_m\) or clock",
    ),
    (
        "[variables.point_mass]\nmass_kg = [-0.005]\nclock = 12\n",
        r"\[variables\]\.point_mass\."
        r"mass_kg = -0\.005: lead tape",
    ),
    (
        "[variables.point_mass]\nmass_kg = [0.005]\nx_m = 0.7\n",
        r"point_masses\[0\]\.x_m \(0\.7 m\) "
        r"must lie on the racket",
    ),
    (
        "[variables.point_mass]\nmass_kg = 0.005\nx_m = 0.6\nz_m = 0\n",
        r"\[variables\]\."
        r"point_mass: unknown key 'z_m'",
    ),
]
BAD_FILES = [
    ('mode = "random"\n' + BASE, r"mode must be one of full-factorial, one-at-a-time"),
    ("colour = 'red'\n" + BASE, r"unknown top-level key 'colour'"),
    ('racket = "missing.toml"\n' + BASE, r"missing\.toml: no such racket file"),
    (BASE.replace("grid = 4", "grid = 4\npoints = 'p.csv'"), r"\[impacts\]: give grid or points"),
    (BASE.replace("grid = 4", "grid = 4.5"), r"\[impacts\]\.grid must be a whole number"),
    (BASE.replace("grid = 4", "speed = 3"), r"\[impacts\]: unknown key 'speed'"),
    (BASE.replace("ball_speeds_mps = [20.0]", ""), r"\[impacts\]\.ball_speeds_mps is missing"),
    (
        BASE.replace("grid = 4", 'grid = 4\nmethod = "implicit"'),
        r"\[impacts\]\.method must be one of approximate, transient \(got 'implicit'\)",
    ),
    (
        TRANSIENT + "hand.arm_mass_kg = [0.5, 1.0]\n",  # no hand support to change
        r"\[variables\]\.hand\.arm_mass_kg: hand parameters change the 'hand' support only",
    ),
    (
        TRANSIENT + "support = ['hand']\n[variables.hand]\nstiffness_n_per_m = [2e4, 0.0]\n",
        r"\[variables\]\.hand\.stiffness_n_per_m = 0: a hand holds the grip",
    ),
    (
        TRANSIENT + "support = ['free', 'hand', 'free']\n",
        r"\[variables\]\.support: name each support once",
    ),
    (BASE.replace("[0.80, 0.86]", "[0.80, 0.80]"), r"\[variables\]\.e_bg: a value is listed twice"),
    (
        BASE.replace("[0.80, 0.86]", "[0.80, 1.2]"),
        r"\[variables\]\.e_bg = 1\.2: e_BG is a ratio between 0 and 1",
    ),
    (
        BASE + "[summary]\nball_speed_mps = 25.0\n",
        r"\[summary\]\.ball_speed_mps \(25\.0\) must be "
        r"one of the listed speeds \(20\)",
    ),
    ("[ball]\ne_bg = true\n" + BASE, r"\[ball\]\.e_bg must be a number \(got True\)"),
    (BASE + "tension_n = [\n", r"malformed TOML"),
]


@pytest.mark.parametrize(
    ("text", "message"),
    [(BASE + extra, message) for extra, message in BAD_SPECS] + BAD_FILES,
    ids=[f"spec-{i}" for i in range(len(BAD_SPECS))] + [f"file-{i}" for i in range(len(BAD_FILES))],
)
def test_bad_specs_name_the_key(text: str, message: str, tmp_path: Path) -> None:
    path = tmp_path / "spec.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(rd.InputError, match=message) as error:
        load_sweep_spec(path)
    assert str(error.value).startswith(str(path))


def test_engine_choices_are_checked() -> None:
    checks = [
        ({"kind": "threads"}, "engine must be one of serial, process"),
        ({"kind": "dask"}, "needs a scheduler address"),
        ({"kind": "process", "workers": 0}, "`workers` must be a whole number"),
        ({"kind": "process", "scheduler": "tcp://127.0.0.1:8786"}, "for the dask engine only"),
    ]
    for arguments, message in checks:
        with pytest.raises(rd.InputError, match=message), make_executor(**arguments):
            pass


_SCRIPT = """
import sys
import racketdyn as rd
from racketdyn.sweep import SweepSpec, Variable, make_executor, run_sweep

def main(out):
    racket = rd.default_racket()
    spec = SweepSpec(racket=racket, ball=rd.Ball(), locations=racket.head.grid(3),
                     ball_speeds=[10.0], variables=(Variable.scalar("e_bg", [0.80, 0.86]),),
                     name="guard")
    with make_executor("process", 1) as executor:
        data = run_sweep(spec, out, executor, figures=None)
    print("failed", data.attrs["n_failed"])
"""


@pytest.mark.parametrize(
    ("body", "runs"),
    [
        ("main(sys.argv[1])\n", False),
        ('if __name__ == "__main__":\n    main(sys.argv[1])\n', True),
        ('if __name__ == "__main__" and len(sys.argv) > 1:\n    main(sys.argv[1])\n', True),
        ('if __name__ != "__main__":\n    pass\nelse:\n    main(sys.argv[1])\n', True),
        ('if __name__ != "__main__":\n    main(sys.argv[1])\n', None),
        ("if len(sys.argv) > 1:\n    main(sys.argv[1])\n", False),
    ],
    ids=["top level", "guarded", "guard and more", "else of !=", "body of !=", "other if"],
)
@pytest.mark.slow
def test_a_script_without_the_main_guard_is_refused(
    tmp_path: Path, body: str, runs: bool | None
) -> None:
    """A script that starts a process sweep at its top level ran it again in every import by
    a worker process: three sweeps into one folder, two of them all NaN.  Refused before any
    process starts, naming the line; under ``if __name__ == "__main__":`` (alone or in an
    ``and``, or the ``else`` of ``!=``) it runs once; a sweep only a worker would run never
    runs here (``runs`` None); another ``if`` is no guard (review, 2026-11-26)."""
    import subprocess
    import sys

    script = tmp_path / "study.py"
    script.write_text(_SCRIPT + body, encoding="utf-8")
    run = subprocess.run(
        [sys.executable, str(script), str(tmp_path / "out")],
        capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    assert "bootstrapping" not in run.stderr
    if runs is None:
        assert run.returncode == 0, run.stderr
        assert run.stdout == ""
    elif runs:
        assert run.returncode == 0, run.stderr
        assert run.stdout.split() == ["failed", "0"]
    else:
        assert run.returncode == 1
        line = len((_SCRIPT + body).splitlines())  # the call is the script's last line
        assert f"{script}, line {line}:" in run.stderr
        assert "a sweep on worker processes is started at the top level" in run.stderr
        assert 'if __name__ == "__main__":' in run.stderr
        assert not (tmp_path / "out" / "sweep.zarr").exists()


@pytest.mark.slow
def test_a_package_run_with_dash_m_needs_no_guard(tmp_path: Path) -> None:
    """``python -m package`` runs ``package/__main__.py``, which multiprocessing never imports
    again in a worker; the check refused it all the same — ``python -m racketdyn.cli sweep
    --workers 2`` among others (found 2026-11-26, third session)."""
    import subprocess
    import sys

    package = tmp_path / "study_package"
    package.mkdir()
    (package / "__init__.py").write_text("", encoding="utf-8")
    (package / "__main__.py").write_text(_SCRIPT + "main(sys.argv[1])\n", encoding="utf-8")
    run = subprocess.run(
        [sys.executable, "-m", "study_package", str(tmp_path / "out")],
        capture_output=True, text=True, timeout=300, check=False, cwd=tmp_path,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == ["failed", "0"]


def test_summary_lines_follow_the_axis_and_the_clock_reads_from_twelve(tmp_path: Path) -> None:
    """Values listed out of order in the spec drew a zig-zag (a line from 266 N back to 226
    N), and lead at 12, 2, 3 and 10 o'clock put 12 o'clock after 10 on the axis (a new-user
    trial, 2026-11-26): lines run along the axis, and the clock axis starts at 12."""
    import matplotlib.pyplot as plt

    racket = rd.default_racket()
    spec = SweepSpec(
        racket=racket,
        ball=rd.Ball(),
        locations=racket.head.grid(3),
        ball_speeds=[20.0],
        variables=(
            Variable.point_mass(0.005, clock=[12, 2, 3, 10], head=racket.head),
            Variable.scalar("tension_n", [266.0, 226.0, 246.0]),
        ),
        mode="one-at-a-time",
        name="order",
    )
    ds = run_sweep(spec, tmp_path, SerialExecutor(), figures=None)
    _, (left, right) = plt.subplots(1, 2)
    plot_centre_rebound(summary_curves(ds, "point_mass"), ax=left)
    plot_centre_rebound(summary_curves(ds, "tension_n"), ax=right)
    for ax in (left, right):
        for line in ax.get_lines():
            x = np.asarray(line.get_xdata(), float)
            assert np.all(np.diff(x) > 0), x
    clock = np.asarray(left.get_lines()[0].get_xdata(), float)
    assert clock.tolist() == [0.0, 2.0, 3.0, 10.0]
    labels = {t.get_text() for t in left.get_xticklabels()}
    assert {"12", "2", "3", "10"} <= labels
    # the base design carries no lead: a dotted level per support, not a point at 12 o'clock
    base = int(np.flatnonzero(ds["varied"].values == "base")[0])
    assert ds["point_mass_mass_kg"].values[base] == 0.0
    levels = [line for line in left.get_lines() if line.get_linestyle() == ":"]
    assert len([line for line in levels if len(line.get_xdata())]) == ds.sizes["support"]
    assert "without the point mass" in [t.get_text() for t in left.get_legend().get_texts()]
    plt.close("all")
