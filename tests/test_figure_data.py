"""Results carry the data their figures show (issue 23): each step computes what its figures
draw with the run's own inputs and writes it to ``figures.nc``; a figure redrawn from that file
alone draws the same lines as the figure the run drew."""

from __future__ import annotations

import functools
import logging
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.figure import Figure

import racketdyn as rd
from costly import costly
from figure_catch import Drawn, catch_figures, same_3d_drawing, same_drawing
from racketdyn.plotting import figures as figures_module
from racketdyn.plotting.primitives import SUPPORT_STYLE
from racketdyn.plotting.steps import compare_figures
from racketdyn.workflows.setup import Setup


@pytest.fixture
def caught(monkeypatch: pytest.MonkeyPatch) -> Iterator[Drawn]:
    """The figures the step draws, by file name, as matplotlib objects."""
    drawn: Drawn = {}
    catch_figures(monkeypatch, drawn)
    yield drawn
    for figure in drawn.values():
        plt.close(figure)


@pytest.fixture(scope="module")
@costly
def frfs(rig_frf_tree: Path) -> tuple[Path, Path]:
    """FRFs of the virtual rig, free and hand-held (few averages, no faults; the run's shared
    tree)."""
    d = rig_frf_tree
    return d / "frf_free" / "frfs.uff", d / "frf_hand" / "frfs.uff"


@functools.cache
def heavy_ball() -> rd.Ball:
    """A ball heavier than the default, for the compare run (its Fig. 15 must be this ball's)."""
    return rd.Ball(mass_kg=0.0594, e_bg=0.78)


def _lines(figure: Figure) -> dict[str, np.ndarray]:
    """The drawn lines of a one-axes figure by legend label: their y data."""
    (ax,) = [a for a in figure.axes if a.get_lines()]
    return {
        str(line.get_label()): np.asarray(line.get_ydata(), dtype=float) for line in ax.get_lines()
    }


@pytest.mark.slow
def test_swing_along_axis_redrawn_from_figures_nc(tmp_path: Path, caught: Drawn) -> None:
    """The swing step's along-axis curves are computed by the step (with the run's ball) and
    drawn the same from its figures.nc."""
    from racketdyn.plotting.steps import swing_figures
    from racketdyn.workflows import run_swing
    from racketdyn.workflows.figure_data import FIGURES_FILE, SwingAxisCurves, read_figure_data

    ball = rd.Ball(mass_kg=0.0594)
    logging.disable(logging.WARNING)
    try:
        result = run_swing(tmp_path, grid=3, setup=Setup(ball=ball, figures=swing_figures))
    finally:
        logging.disable(logging.NOTSET)
    curves = SwingAxisCurves.from_xarray(read_figure_data(tmp_path / FIGURES_FILE))
    assert result.axis_curves is not None
    assert curves.names == result.axis_curves.names
    for read, computed in zip(curves.curves, result.axis_curves.curves, strict=True):
        np.testing.assert_array_equal(read.rebound_speed, computed.rebound_speed)
    redrawn = figures_module.figure_swing_along_axis(curves, result.spots)
    try:
        same_drawing(caught["swing_along_axis.png"], redrawn)
    finally:
        plt.close(redrawn)


# --- predict: every figure redrawn from figures.nc alone -------------------------------------
def _by_label(figure: Figure, ax_index: int = 0) -> dict[str, np.ndarray]:
    ax = figure.axes[ax_index]
    return {str(line.get_label()): np.asarray(line.get_ydata(), float) for line in ax.get_lines()}


def _run_caught(run: Callable[[], Any]) -> tuple[Any, Drawn]:
    """A step run with the figures its hook draws caught open, by file name (pyplot's warning
    beyond 20 open figures off: a module's runs keep theirs open side by side)."""
    drawn: Drawn = {}
    patch = pytest.MonkeyPatch()
    catch_figures(patch, drawn)
    logging.disable(logging.WARNING)
    try:
        with plt.rc_context({"figure.max_open_warning": 0}):
            result = run()
    finally:
        logging.disable(logging.NOTSET)
        patch.undo()
    return result, drawn


@pytest.fixture(scope="module")
@costly
def predicted(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Any, Drawn, Path]]:
    """A small ``predict --model both`` run with its figures caught, and its folder."""
    from racketdyn.plotting.steps import predict_figures
    from racketdyn.workflows import PredictOptions, run_predict

    out = tmp_path_factory.mktemp("predict")
    result, drawn = _run_caught(
        lambda: run_predict(
            out,
            setup=Setup(figures=predict_figures()),
            options=PredictOptions(
                model="both",
                speeds=[10.0, 20.0, 35.0],
                racket_speed=[0.0, 2.0, 4.0],
                grid=3,
                engine="compiled",
            ),
        )
    )
    yield result, drawn, out
    for figure in drawn.values():
        plt.close(figure)


@pytest.mark.slow
def test_figures_nc_is_listed_and_holds_si_units(predicted: tuple[Any, Drawn, Path]) -> None:
    import json

    from racketdyn.workflows.figure_data import FIGURES_FILE, read_figure_data

    _, _, out = predicted
    assert FIGURES_FILE in json.loads((out / "run.json").read_text())["outputs"]
    data = read_figure_data(out / FIGURES_FILE)
    assert data["fig11_12__mean_force_n"].attrs["units"] == "N"
    assert data["fig11_12__contact_time_s"].attrs["units"] == "s"
    assert data["fig13__spectrum_n_s"].attrs["units"] == "N s"
    assert data["fig14__amplitude_m"].attrs["units"] == "m"
    assert data["fig15__rebound_ratio"].attrs["units"] == "1"


def test_figure_data_round_trips_through_figures_nc(predicted: tuple[Any, Drawn, Path]) -> None:
    from dataclasses import fields

    from racketdyn.workflows.figure_data import (
        FIGURES_FILE,
        ComparisonMap,
        PaperFigures,
        TransientCurves,
        TransientHistories,
        read_figure_data,
    )

    result, _, out = predicted
    dataset = read_figure_data(out / FIGURES_FILE)

    def same(a: Any, b: Any, where: str) -> None:
        if hasattr(a, "__dataclass_fields__") and not isinstance(a, rd.racket.HeadEllipse):
            for f in fields(a):
                same(getattr(a, f.name), getattr(b, f.name), f"{where}.{f.name}")
        elif isinstance(a, np.ndarray):
            assert a.shape == b.shape, where
            if a.dtype.kind in "US":
                assert np.array_equal(a, b), where
            else:
                np.testing.assert_array_equal(a, b, err_msg=where)
        else:
            assert a == b, where

    same(result.paper_figures, PaperFigures.from_xarray(dataset), "paper")
    same(result.transient_curves, TransientCurves.from_xarray(dataset), "transient")
    same(result.comparison_map, ComparisonMap.from_xarray(dataset), "comparison map")
    same(result.transient_histories, TransientHistories.from_xarray(dataset), "histories")


@pytest.mark.slow
def test_each_predict_figure_redrawn_from_figures_nc_alone(
    predicted: tuple[Any, Drawn, Path],
) -> None:
    """Issue 23: every figure of predict in the registry, drawn from the folder's figures.nc
    alone, draws the same as the figure the step drew, and its lines are the computed arrays."""
    from racketdyn.plotting.registry import draw, for_step
    from racketdyn.workflows.figure_data import read_step_data

    result, drawn, out = predicted
    data = read_step_data(out)  # the folder's file alone
    curves, comparison = data["transient_curves"], data["comparison_map"]
    # every figure of the step but the uncertainty's (tests/test_redraw_from_folder.py runs it)
    with_data = [f for f in for_step("predict") if f.data(data) is not None]
    assert {f.id for f in for_step("predict")} - {f.id for f in with_data} == {"sensitivity"}
    redrawn = {figure.file: draw(figure.id, data) for figure in with_data}
    assert set(redrawn) == set(drawn)
    try:
        for name, figure in redrawn.items():
            same_drawing(drawn[name], figure)
        computed = result.paper_figures
        # Figs 11-12: F_MEAN and T_c per point and support, a row of panels per racket speed
        assert computed.speed_curves.racket_speeds == [0.0, 2.0, 4.0]
        for row, racket_speed in enumerate(computed.speed_curves.racket_speeds):
            speed_curves = computed.speed_curves.at_racket_speed(racket_speed)
            for k, quantity in enumerate(("mean_force", "contact_time")):
                lines = _by_label(redrawn["fig11_12_force_contact_time.png"], 2 * row + k)
                scale = 1e3 if quantity == "contact_time" else 1.0
                for i, name in enumerate(speed_curves.labels):
                    for p, support in enumerate(speed_curves.supports):
                        label = f"{name}, {SUPPORT_STYLE[support]['label']}"
                        expected = np.where(
                            speed_curves.status[i, :, p] == "ok",
                            getattr(speed_curves, quantity)[i, :, p] * scale,
                            np.nan,
                        )
                        np.testing.assert_array_equal(lines[label], expected)
        # Fig. 13: each drawn pulse and spectrum
        pulse = computed.pulse
        force_lines = list(_by_label(redrawn["fig13_pulse_spectrum.png"], 0).values())
        spectrum_lines = [
            line
            for label, line in _by_label(redrawn["fig13_pulse_spectrum.png"], 1).items()
            if "T_c" in label
        ]
        shown = np.flatnonzero(pulse.drawn())
        assert len(force_lines) == shown.size
        for line, s in zip(force_lines, shown, strict=True):
            np.testing.assert_array_equal(line, pulse.force[s])
        for line, s in zip(spectrum_lines, shown, strict=True):
            np.testing.assert_array_equal(line, pulse.spectrum[s])
        # Fig. 14: amplitude along the frame, mm, each support's panel
        frame = computed.frame
        assert frame is not None
        for p, _support in enumerate(frame.supports):
            lines = _by_label(redrawn["fig14_frame_vibration.png"], p)
            for s, speed in enumerate(frame.ball_speed):
                if frame.status[s, p] == "ok":
                    np.testing.assert_array_equal(
                        lines[f"{speed:g} m/s"], frame.amplitude[:, s, p] * 1e3
                    )
        # Fig. 15: rebound ratio along the axis, per support
        axis = computed.axis
        lines = _by_label(redrawn["fig15_rebound_along_axis.png"])
        for p, support in enumerate(axis.supports):
            np.testing.assert_array_equal(
                lines[SUPPORT_STYLE[support]["label"]],
                np.where(axis.status[:, 0, p] == "ok", axis.rebound_ratio[:, 0, p], np.nan),
            )
        # both models against speed: the transient model's rebound ratio at the centre, two
        # rows of panels (rebound ratio, contact time) per racket speed, each over every speed
        assert curves.transient.racket_speeds == [0.0, 2.0, 4.0]
        n_supports = len(curves.transient.supports)
        for k, racket_speed in enumerate(curves.transient.racket_speeds):
            transient = curves.transient.at_racket_speed(racket_speed)
            lines = _by_label(redrawn["transient_comparison_speed.png"], 2 * k * n_supports)
            label = next(key for key in lines if key.startswith("centre") and "transient" in key)
            np.testing.assert_array_equal(
                lines[label],
                np.where(
                    transient.status[0, :, 0] == "ok", transient.rebound_ratio[0, :, 0], np.nan
                ),
            )
        # the face comparison: approximate - transient at the run's points, first support
        face_ax = redrawn["transient_comparison_face.png"].axes[0]
        points = face_ax.collections[-1]  # the dots, coloured by the difference
        finite = np.isfinite(comparison.difference[:, 0])
        np.testing.assert_array_equal(
            np.asarray(points.get_array(), float), comparison.difference[finite, 0]
        )
        np.testing.assert_array_equal(
            np.asarray(result.comparison.difference("rebound_ratio"))[:, result.shown_speed, 0],
            comparison.difference[:, 0],
        )
        # the time histories: the contact force of each simulated impact, N
        force_ax = redrawn["transient_histories.png"].axes[0]
        first = result.histories[0]
        np.testing.assert_array_equal(force_ax.get_lines()[0].get_ydata(), first.impact.force_n)
    finally:
        for figure in redrawn.values():
            plt.close(figure)


# --- identify and compare: Figs 4-6 and the AutoMAC drawn from what the step evaluated ----------
@pytest.fixture(scope="module")
@costly
def compared(
    frfs: tuple[Path, Path], tmp_path_factory: pytest.TempPathFactory
) -> Iterator[tuple[Any, Drawn, Path]]:
    """A compare run (free against hand-held) with a heavier ball than the default (Fig. 15
    must be that ball's) and its figures caught, and its folder: one run for the shapes'
    tests and Fig. 15's (each had run compare, ≈ 10 s a run on a quiet machine)."""
    from racketdyn.workflows.identify import run_compare

    out = tmp_path_factory.mktemp("compare")
    setup = Setup(ball=heavy_ball(), figures=compare_figures)
    result, drawn = _run_caught(lambda: run_compare(frfs[0], frfs[1], out, setup=setup))
    kept = (*SHAPE_FIGURES, "fig15_identified")
    for name in [n for n in drawn if not n.startswith(kept)]:
        plt.close(drawn.pop(name))  # the figures the tests read kept only (pyplot warns beyond 20)
    yield result, drawn, out
    for figure in drawn.values():
        plt.close(figure)


SHAPE_FIGURES = ("fig4_mode_shapes", "fig5_node_lines", "fig6_nodes", "automac")
"""The identified shapes' figures (compare writes them once per model)."""


@pytest.mark.slow
def test_compare_fig15_uses_the_runs_ball(compared: tuple[Any, Drawn, Path]) -> None:
    """The compare step's Fig. 15 predicted with a default ``Ball()`` whatever ball the run
    used (issue 23): a heavier ball must change the curves, and they must be that ball's (the
    module's compare run, ``compared``, is made with that ball)."""
    result, caught, out = compared
    heavy = heavy_ball()
    assert result.free is not None
    assert result.hand is not None
    racket = rd.default_racket()
    head = racket.head
    x = np.linspace(
        head.throat_x_m + 0.05 * head.half_length_m, head.tip_x_m - 0.05 * head.half_length_m, 31
    )
    points = np.column_stack([x, np.full_like(x, head.centre_y_m)])
    drawn = _lines(caught["fig15_identified.png"])
    cases = {
        "pinned at the grip, hand-held modes": ("pinned", result.hand.model),
        "pinned at the grip, free modes": ("pinned", result.free.model),
        "freely supported, free modes": ("free", result.free.model),
    }
    for label, (support, model) in cases.items():
        expected = rd.predict(racket, heavy, points, [20.0], (support,), modal_model=model)
        default = rd.predict(racket, rd.Ball(), points, [20.0], (support,), modal_model=model)
        np.testing.assert_allclose(drawn[label], expected.rebound_ratio[:, 0, 0], rtol=1e-12)
        assert not np.allclose(drawn[label], default.rebound_ratio[:, 0, 0], equal_nan=True)
    # redrawn from the folder's figures.nc alone: the same lines
    from racketdyn.workflows.figure_data import FIGURES_FILE, IdentifiedRebound, read_figure_data

    data = IdentifiedRebound.from_xarray(read_figure_data(out / FIGURES_FILE))
    redrawn = data.plot().get_figure()
    try:
        same_drawing(caught["fig15_identified.png"], redrawn)
    finally:
        plt.close(redrawn)
        plt.close(caught.pop("fig15_identified.png"))


@pytest.mark.slow
def test_identified_shapes_redrawn_from_figures_nc_alone(
    compared: tuple[Any, Drawn, Path],
) -> None:
    """Issue 23: Figs 4-6 and the AutoMAC of each model, and Fig. 6 free against hand-held,
    drawn from the compare folder's figures.nc alone, draw what the step drew; the shapes are
    the model evaluated by the step (its MAC, its nodes on the axis)."""
    from racketdyn.modal.residues import mac
    from racketdyn.plotting.registry import draw
    from racketdyn.racket_modal.shapes import axis_nodes
    from racketdyn.workflows.figure_data import read_step_data

    result, drawn, out = compared
    racket = rd.default_racket()

    def same(name: str, redrawn: Figure) -> None:
        try:
            if name.startswith("fig4"):
                same_3d_drawing(drawn[name], redrawn)
            else:
                same_drawing(drawn[name], redrawn)
        finally:
            plt.close(redrawn)  # one at a time: the step's figures are open
            plt.close(drawn.pop(name))

    for label, identification in (("free", result.free), ("hand", result.hand)):
        data = read_step_data(out, label)  # the folder's file alone
        for figure in SHAPE_FIGURES:
            same(f"{figure}_{label}.png", draw(figure, data))
        model = identification.model
        shapes = data["shape_figures"]
        np.testing.assert_array_equal(
            shapes.automac.matrix, mac(model.mode_shapes, model.mode_shapes)
        )
        np.testing.assert_array_equal(
            shapes.axis.nodes_of(0), axis_nodes(model, 0, (0.0, racket.length_m))
        )
    same("fig6_nodes_free_hand.png", draw("fig6_nodes_free_hand", read_step_data(out)))


@pytest.mark.slow
def test_identify_writes_its_shapes_to_figures_nc(frfs: tuple[Path, Path], tmp_path: Path) -> None:
    """identify lists figures.nc in run.json; the shapes read back equal those it evaluated."""
    import json
    from dataclasses import fields

    from racketdyn.workflows import run_identify
    from racketdyn.workflows.figure_data import FIGURES_FILE, read_step_data

    logging.disable(logging.WARNING)
    try:
        result = run_identify(frfs[0], tmp_path, setup=Setup(figures=None))
    finally:
        logging.disable(logging.NOTSET)
    assert FIGURES_FILE in json.loads((tmp_path / "run.json").read_text())["outputs"]
    computed, read = result.shape_figures, read_step_data(tmp_path)["shape_figures"]
    assert computed.shapes is not None
    assert computed.shapes.layout_3d == "racket"
    for part in ("automac", "shapes", "axis"):
        a, b = getattr(computed, part), getattr(read, part)
        for f in fields(a):
            u, v = getattr(a, f.name), getattr(b, f.name)
            if isinstance(u, np.ndarray):
                np.testing.assert_array_equal(u, v, err_msg=f"{part}.{f.name}")
            else:
                assert u == v, f"{part}.{f.name}"


def test_a_shape_figure_goes_into_a_users_figure(compared: tuple[Any, Drawn, Path]) -> None:
    """python-control style: the figure-data objects draw into the caller's axes."""
    result, _, _ = compared
    before = set(plt.get_fignums())
    figure, (left, middle, right) = plt.subplots(1, 3)
    try:
        assert result.shapes_free.automac.plot(ax=left) is left
        assert result.nodes_free_hand.plot(ax=middle) is middle
        assert result.rebound.plot(ax=right) is right
        assert left.get_title() == "AutoMAC"
        assert len(middle.get_lines()) >= 2  # free and hand-held
        assert right.get_title().startswith("Fig. 15")
        assert set(plt.get_fignums()) - before == {figure.number}  # no figure of their own
    finally:
        plt.close(figure)


def test_general_shapes_round_trip_through_xarray() -> None:
    """A structure that is not a racket (a beam: a line; points in space) keeps its layout."""
    from racketdyn.modal.model import ModalModel
    from racketdyn.workflows.shape_figures import ModeShapes, mode_shapes

    t = np.linspace(0, 1, 11)
    beam = ModalModel(
        [10.0, 30.0], [0.01, 0.02], np.column_stack([t, 0.5 * t]),
        np.column_stack([np.sin(np.pi * t), np.sin(2 * np.pi * t)]), ("a", "b"),
    )  # fmt: skip
    shapes = mode_shapes(beam, None)
    assert (shapes.layout_3d, shapes.layout_nodes) == ("line", "line")
    back = ModeShapes.from_xarray(shapes.to_xarray())
    np.testing.assert_array_equal(back.nodes_line_shapes, shapes.nodes_line_shapes)
    np.testing.assert_array_equal(back.line, shapes.line)
    assert back.head is None
    assert back.names == shapes.names
    # one mode of each figure in the user's own figure
    figure = plt.figure()
    try:
        flat, solid = figure.add_subplot(1, 2, 1), figure.add_subplot(1, 2, 2, projection="3d")
        assert back.plot(1, ax=flat) is flat
        assert back.plot(1, ax=solid, kind="3d") is solid
        assert flat.get_title() == "b, 30 Hz"
        np.testing.assert_array_equal(flat.get_lines()[0].get_ydata(), shapes.nodes_line_shapes[1])
    finally:
        plt.close(figure)


def test_read_step_data_is_a_name_of_the_workflows_package() -> None:
    """New-user trial (2026-11-27, ninth session): ``racketdyn.workflows.read_step_data`` was
    an AttributeError beside ``read_figure_data``; both are the package's names."""
    import racketdyn.workflows as workflows
    from racketdyn.workflows import figure_data

    assert workflows.read_step_data is figure_data.read_step_data
    assert "read_step_data" in workflows.__all__
