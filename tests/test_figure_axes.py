"""Issue 23: a figure of several panels draws into the caller's axes when given them
(python-control's and scikit-rf's figure functions): ``axes=`` of the right count, checked with
a one-line error naming the parameter; without it, the figure is the one the step saves."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pytest

import racketdyn as rd
from figure_catch import default_paper_figures, same_3d_drawing, same_drawing
from racketdyn.errors import InputError
from racketdyn.plotting import figures
from racketdyn.plotting.primitives import axes_grid
from racketdyn.workflows.identify import ModeComparison
from racketdyn.workflows.shape_figures import mode_shapes


@pytest.fixture(scope="module")
def paper() -> Any:
    return default_paper_figures()


@pytest.fixture(autouse=True)
def _close() -> Any:
    yield
    plt.close("all")


def test_axes_grid_takes_the_callers_axes_in_the_shape_of_subplots() -> None:
    figure, made = plt.subplots(2, 3)
    got, grid = axes_grid(list(made.flat), 2, 3)
    assert got is figure
    assert grid.shape == (2, 3)
    assert all(a is b for a, b in zip(grid.flat, made.flat, strict=True))
    _, row = axes_grid(made[0], 1, 3)
    assert row.shape == (3,)  # squeezed, as plt.subplots(1, 3) is
    _, one = axes_grid([made[0, 0]], 1, 1)
    assert one is made[0, 0]
    _, kept = axes_grid(made[0], 1, 3, squeeze=False)
    assert kept.shape == (1, 3)


def test_axes_grid_refuses_a_wrong_count_or_kind_in_one_line() -> None:
    _, made = plt.subplots(1, 3)
    with pytest.raises(InputError, match=r"^`axes` takes 2 matplotlib Axes \(1 × 2\) for this "):
        axes_grid(list(made), 1, 2)
    with pytest.raises(InputError, match=r"^`axes` takes matplotlib Axes, got str$"):
        axes_grid([made[0], "right"], 1, 2)


def _comparison() -> ModeComparison:
    rows = [
        {
            "mode": name,
            "frequency_free_hz": f,
            "frequency_hand_hz": 0.97 * f,
            "frequency_shift_percent": -3.0,
            "damping_free": 0.005,
            "damping_hand": 0.02,
            "damping_ratio_hand_over_free": 4.0,
            "mac": 0.98,
        }
        for name, f in (("2-node bending", 120.0), ("3-node bending", 355.0))
    ]
    return ModeComparison(rows, np.array([0.16, 0.55]), np.array([0.2, 0.55]))


CASES: dict[str, tuple[Callable[..., Any], Callable[[Any], tuple[Any, tuple[int, int]]]]] = {
    "figs_11_12": (
        figures.figure_force_and_contact_time,
        lambda p: (p, (len(p.speed_curves.racket_speeds), 2)),
    ),
    "fig13": (figures.figure_pulse_spectrum, lambda p: (p, (1, 2))),
    "fig14": (figures.figure_frame_vibration, lambda p: (p, (1, len(p.frame.supports)))),
    "comparison": (figures.figure_mode_comparison, lambda p: (_comparison(), (1, 2))),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_a_figure_draws_into_the_callers_axes_what_it_draws_alone(paper: Any, case: str) -> None:
    draw, given = CASES[case]
    data, (rows, columns) = given(paper)
    alone = draw(data)
    mine, grid = plt.subplots(rows, columns, squeeze=False)
    drawn = draw(data, axes=list(grid.flat))
    assert drawn is mine
    same_drawing(alone, drawn)


def test_a_figure_given_axes_of_the_wrong_count_says_so(paper: Any) -> None:
    _, ax = plt.subplots()
    with pytest.raises(InputError, match=r"`axes` takes 2 matplotlib Axes \(1 × 2\)"):
        figures.figure_pulse_spectrum(paper, axes=[ax])


def test_the_registry_passes_the_callers_axes_on(paper: Any) -> None:
    """``draw(id, data, axes=…)`` and so ``result.plot(id, axes=…)``: a step's figure placed in
    a figure of the caller's, beside one of their own."""
    from racketdyn.plotting.registry import draw

    mine, (left, right, own) = plt.subplots(1, 3)
    drawn = draw("fig13_pulse_spectrum", {"paper_figures": paper}, axes=[left, right])
    assert drawn is mine
    assert not own.get_lines()
    own.remove()  # what is left: the step's two panels
    same_drawing(draw("fig13_pulse_spectrum", {"paper_figures": paper}), mine)


def test_fig4_draws_into_the_callers_3d_axes_what_it_draws_alone(
    racket: rd.Racket, model: rd.ModalModel
) -> None:
    """Fig. 4's panels are 3-D: the caller's axes must be too (one per mode), else a one-line
    error naming ``axes``."""
    shapes = mode_shapes(model, racket)
    n = shapes.n_modes
    alone = figures.figure_mode_shapes(shapes)
    mine = plt.figure()
    panels = [mine.add_subplot(1, n, k + 1, projection="3d") for k in range(n)]
    drawn = figures.figure_mode_shapes(shapes, axes=panels)
    assert drawn is mine
    assert drawn.get_suptitle() == alone.get_suptitle()
    same_3d_drawing(alone, drawn)
    with pytest.raises(InputError, match=rf"^`axes` takes {n} matplotlib Axes \(1 × {n}\)"):
        figures.figure_mode_shapes(shapes, axes=panels[:-1])
    _, flat = plt.subplots(1, n)
    with pytest.raises(InputError, match=r"^`axes` takes 3-D matplotlib Axes \(projection='3d'\)"):
        figures.figure_mode_shapes(shapes, axes=list(flat))


ONE_PANEL = "one panel: its primitive takes `ax` (the figure function adds the figure's title)"
NO_AXES = {
    "stabilisation": ONE_PANEL + ": plot_stabilisation",
    "compound_shape": ONE_PANEL + ": plot_ball_mode_shape",
    "compound_response": ONE_PANEL + ": plot_neck_response",
    "fig15_rebound_along_axis": ONE_PANEL + ": plot_along_axis",
    "swing_map": ONE_PANEL + ": plot_swing_map",
    "swing_along_axis": ONE_PANEL + ": plot_swing_along_axis",
    "validation_parity": ONE_PANEL + ": plot_parity",
    "calibration_parity": ONE_PANEL + ": plot_parity",
    "validation_along_axis": "one panel drawn in the figure function itself",
    "validation_residuals": "one panel drawn in the figure function itself",
}
"""Registered figures whose draw function takes neither ``ax`` nor ``axes``, and why."""


def test_every_figure_takes_the_callers_axes_or_says_why_not() -> None:
    import inspect

    from racketdyn.plotting.registry import FIGURES

    without = {
        e.id
        for e in FIGURES.values()
        if not {"ax", "axes"} & set(inspect.signature(e.drawer()).parameters)
    }
    assert without == set(NO_AXES)
