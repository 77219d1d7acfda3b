"""Labels and legends of the figures stay off the data and off each other (issue 13: Fig. 6 node
labels, Fig. 13 mode labels, Fig. 15 labels and the swing legend overlapped the curves; the
stabilisation legend was too small; Fig. 4 had no scale; Fig. 5 did not say what black and white
mean).

Each figure is drawn with the Agg backend as the files are, then the window extents of its
texts and legends (``get_window_extent``) are checked against each other and against the
curves, the curves sampled densely along their segments in display coordinates.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import replace
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.backend_bases import RendererBase
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.text import Text
from matplotlib.transforms import Bbox
from numpy.typing import NDArray

import racketdyn as rd
from racketdyn.impact.swing import Swing, sweet_spots
from racketdyn.plotting import figures
from racketdyn.plotting.primitives import label_rows
from racketdyn.racket_modal.shapes import axis_nodes
from racketdyn.workflows.figure_data import paper_figures, swing_axis_curves
from racketdyn.workflows.shape_figures import axis_node_curves, mode_shapes


@pytest.fixture(autouse=True)
def _close() -> Iterable[None]:
    yield
    plt.close("all")


def _renderer(figure: Figure) -> RendererBase:
    canvas = FigureCanvasAgg(figure)
    canvas.draw()
    return canvas.get_renderer()


def _texts(figure: Figure, wanted: Sequence[str]) -> list[Text]:
    """The visible texts of the figure that read one of ``wanted``."""
    found = [
        t
        for t in figure.findobj(Text)
        if isinstance(t, Text) and t.get_visible() and t.get_text() in wanted
    ]
    return found


def _curves(figure: Figure) -> list[Line2D]:
    """The data curves: lines of more than two points (not axvline/axhline)."""
    return [
        line
        for ax in figure.axes
        for line in ax.get_lines()
        if np.asarray(line.get_xdata()).size > 2 and line.get_visible()
    ]


def _points(line: Line2D, per_segment: int = 25) -> NDArray[np.float64]:
    """The line in display coordinates, sampled along every segment."""
    xy = np.column_stack([line.get_xdata(), line.get_ydata()]).astype(float)
    xy = xy[np.all(np.isfinite(xy), axis=1)]
    shown = line.get_transform().transform(xy)
    if len(shown) < 2:
        return shown
    t = np.linspace(0.0, 1.0, per_segment, endpoint=False)[:, None, None]
    dense = shown[:-1] + t * (shown[1:] - shown[:-1])
    return np.vstack([dense.reshape(-1, 2), shown[-1:]])


def _crosses(box: Bbox, line: Line2D, margin: float = 0.5) -> bool:
    points = _points(line)
    inside = (
        (points[:, 0] > box.x0 + margin)
        & (points[:, 0] < box.x1 - margin)
        & (points[:, 1] > box.y0 + margin)
        & (points[:, 1] < box.y1 - margin)
    )
    return bool(np.any(inside))


def _apart(boxes: Sequence[Bbox], names: Sequence[str]) -> None:
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            overlap = Bbox.intersection(boxes[i], boxes[j])
            assert overlap is None or overlap.width * overlap.height < 1.0, (names[i], names[j])


def _off_the_curves(figure: Figure, renderer: RendererBase, boxes: dict[str, Bbox]) -> None:
    curves = _curves(figure)
    assert curves
    for name, box in boxes.items():
        for line in curves:
            assert not _crosses(box, line), f"{name!r} lies over the curve {line.get_label()!r}"


def _legends(figure: Figure) -> list[Legend]:
    found = list(figure.legends) + [ax.get_legend() for ax in figure.axes]
    return [legend for legend in found if legend is not None]


def test_label_rows_stack_only_labels_that_would_overlap() -> None:
    # widths 2: the labels at 0 and 1 overlap, 5 is clear of both, 5.5 overlaps 5 only
    assert label_rows([1.0, 0.0, 5.0, 5.5], [2.0, 2.0, 2.0, 2.0], space=0.5) == [1, 0, 0, 1]
    assert label_rows([0.0, 3.0], [2.0, 2.0], space=0.5) == [0, 0]  # 1 apart: room
    assert label_rows([0.0, 2.2], [2.0, 2.0], space=0.5) == [0, 1]  # 0.2 apart: too close
    assert label_rows([], [], space=1.0) == []


def test_fig6_node_labels_are_off_the_curves_and_apart(
    racket: rd.Racket, model: rd.ModalModel
) -> None:
    """Two models whose nodes lie 5 mm apart (the demo's 501 and 506 mm)."""
    other = replace(model, support="pinned")
    figure, ax = plt.subplots(figsize=(7, 4.2), layout="constrained")
    figures.plot_axis_nodes(axis_node_curves([model, other], racket), ax)
    renderer = _renderer(figure)
    nodes = axis_nodes(model, 0, (0.0, racket.length_m)) * 1e3
    names = [f"{node:.0f}" for node in nodes] + [f"{node:.0f} mm" for node in nodes]
    labels = _texts(figure, names)
    assert len(labels) == 2 * nodes.size  # both models' nodes are labelled
    boxes = [t.get_window_extent(renderer) for t in labels]
    _apart(boxes, [t.get_text() for t in labels])
    shown = {f"node {t.get_text()}": b for t, b in zip(labels, boxes, strict=True)}
    shown |= {
        f"legend {k}": leg.get_window_extent(renderer) for k, leg in enumerate(_legends(figure))
    }
    _off_the_curves(figure, renderer, shown)


@pytest.mark.slow
def test_fig13_mode_labels_are_off_the_spectra(
    racket: rd.Racket, ball: rd.Ball, model: rd.ModalModel
) -> None:
    figure = figures.figure_pulse_spectrum(paper_figures(racket, ball, modal_model=model))
    renderer = _renderer(figure)
    labels = _texts(figure, list(model.names))
    assert {t.get_text() for t in labels} == set(model.names)
    boxes = [t.get_window_extent(renderer) for t in labels]
    _apart(boxes, [t.get_text() for t in labels])
    _off_the_curves(figure, renderer, {t.get_text(): b for t, b in zip(labels, boxes, strict=True)})


@pytest.mark.slow
def test_fig15_labels_and_legend_are_off_the_curves(
    racket: rd.Racket, ball: rd.Ball, model: rd.ModalModel
) -> None:
    figure = figures.figure_rebound_along_axis(paper_figures(racket, ball, modal_model=model))
    renderer = _renderer(figure)
    names = ["centre of percussion (grip)", f"node of {model.names[0]}"]
    labels = _texts(figure, names)
    assert len(labels) == 2
    boxes = {t.get_text(): t.get_window_extent(renderer) for t in labels}
    _apart(list(boxes.values()), list(boxes))
    legends = _legends(figure)
    assert legends
    boxes |= {f"legend {k}": legend.get_window_extent(renderer) for k, legend in enumerate(legends)}
    _off_the_curves(figure, renderer, boxes)


def test_swing_legend_is_off_the_curves(racket: rd.Racket, ball: rd.Ball) -> None:
    swing = Swing()
    spots = sweet_spots(racket, ball, swing, 20.0, "pinned", n_axis=21)
    curves = swing_axis_curves(racket, ball, swing, 20.0, "pinned")
    figure = figures.figure_swing_along_axis(curves, spots)
    renderer = _renderer(figure)
    legends = _legends(figure)
    assert legends
    entries = [t.get_text() for legend in legends for t in legend.get_texts()]
    assert any("centre of percussion (grip)" in entry for entry in entries)
    boxes = {f"legend {k}": legend.get_window_extent(renderer) for k, legend in enumerate(legends)}
    _off_the_curves(figure, renderer, boxes)


def test_fig4_has_a_scale_and_fig5_says_what_black_and_white_mean(
    racket: rd.Racket, model: rd.ModalModel
) -> None:
    fig4 = figures.figure_mode_shapes(mode_shapes(model, racket))
    panels = [ax for ax in fig4.axes if ax.name == "3d"]
    assert len(panels) == model.n_modes
    for ax in panels:
        assert any(t.get_text() == "100 mm" for t in ax.texts), "no scale bar"
    assert "bar: 100 mm" in fig4.get_suptitle()
    fig5 = figures.figure_node_lines(mode_shapes(model, racket))
    words = " ".join(t.get_text() for legend in fig5.legends for t in legend.get_texts())
    for word in ("black", "white", "node line"):
        assert word in words
    renderer = _renderer(fig5)
    key = fig5.legends[0].get_window_extent(renderer)
    for ax in fig5.axes:  # the key is beside the panels, not over them
        overlap = Bbox.intersection(key, ax.get_window_extent(renderer))
        assert overlap is None or overlap.width * overlap.height < 1.0


@pytest.mark.slow
def test_the_compound_figures_keep_their_words_inside_and_every_support_visible(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """New-user trial (2026-11-26, second session): Fig. 8a's title ran past both edges of the
    figure and its y label was cut at the top; with ``--support free,pinned,hand`` the pinned
    curves (black) lay exactly on the free ones (blue) in Figs 8a and 9, which the legend
    listed but nobody could see.  Every text lies inside its figure, and curves that coincide
    are told apart by their line style."""
    from racketdyn.plotting import compound as drawing
    from racketdyn.workflows import run_compound

    drawn: list[Figure] = []

    def keep(figure: Figure, path: Path) -> Path:
        drawn.append(figure)
        return path

    monkeypatch.setattr(drawing, "save_figure", keep)
    result = run_compound(tmp_path / "c", supports=("free", "pinned", "hand"))
    drawing.write_compound_figures(result, tmp_path)
    assert len(drawn) == 3
    for figure in drawn:
        renderer = _renderer(figure)
        frame = figure.bbox
        words: list[Text] = [*figure.texts]
        if figure._suptitle is not None:
            words.append(figure._suptitle)
        for ax in figure.axes:
            words += [ax.title, ax.xaxis.label, ax.yaxis.label, *ax.texts]
        for legend in _legends(figure):
            words += legend.get_texts()
        for text in words:
            if not (text.get_visible() and text.get_text().strip()):
                continue
            box = text.get_window_extent(renderer)
            inside = Bbox.intersection(box, frame.expanded(1.0, 1.0).frozen())
            assert inside is not None, text.get_text()
            assert inside.width * inside.height >= 0.99 * box.width * box.height, text.get_text()
        for ax in figure.axes:
            lines = [ln for ln in ax.get_lines() if np.asarray(ln.get_xdata()).size > 2]
            for i, first in enumerate(lines):
                for second in lines[i + 1 :]:
                    a, b = np.asarray(first.get_ydata()), np.asarray(second.get_ydata())
                    if a.shape == b.shape and np.allclose(a, b, rtol=1e-3):
                        assert first.get_linestyle() != second.get_linestyle(), (
                            first.get_label(),
                            second.get_label(),
                        )
