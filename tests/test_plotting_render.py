"""Figure files: one drawing pass gives savefig's pixels; the helper process writes the same
bytes as this one; errors and warnings come back; the paper's figures keep their content."""

from __future__ import annotations

import argparse
import logging
import os
import pickle
import signal
import subprocess
import sys
import threading
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest
from PIL import Image

import racketdyn as rd
from racketdyn.cli import options as opt
from racketdyn.plotting import helper, primitives, registry, render
from racketdyn.plotting.registry import for_step
from racketdyn.workflows.figure_data import paper_figures


def _figure(title: str = "a figure") -> plt.Figure:
    figure, axes = plt.subplots(1, 2, figsize=(5, 2.5), layout="constrained")
    x = np.linspace(0.0, 1.0, 200)
    axes[0].plot(x, np.sin(8 * x), label="sin")
    axes[0].set_xlabel("x (m)")
    axes[0].legend()
    contours = axes[1].contourf(np.outer(x[:40], x[:40]), levels=8)
    figure.colorbar(contours, ax=axes[1], label="product (–)")
    figure.suptitle(title)
    return figure


def _pixels(path: Path) -> np.ndarray:
    with Image.open(path) as image:
        return np.asarray(image.convert("RGB"))


@pytest.mark.slow
def test_one_drawing_pass_gives_the_pixels_of_savefig(tmp_path: Path) -> None:
    _figure().savefig(tmp_path / "savefig.png", dpi=render._png.DPI)
    render.save_figure(_figure(), tmp_path / "fast.png")  # a twin: drawing changes a figure
    np.testing.assert_array_equal(_pixels(tmp_path / "fast.png"), _pixels(tmp_path / "savefig.png"))
    with Image.open(tmp_path / "fast.png") as image:
        assert image.info["Software"] == render.SOFTWARE
        assert image.mode == "RGB"  # opaque: no alpha channel written


@pytest.mark.slow
def test_the_helper_process_writes_the_same_bytes(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("RACKETDYN_FIGURE_WORKERS", "1")
    here = [render.save_figure(_figure(f"figure {k}"), tmp_path / f"here{k}.png") for k in range(4)]
    batch = render.FigureBatch()
    for k in range(4):
        batch.add(_figure(f"figure {k}"), tmp_path / f"batch{k}.png")
    written = batch.render()
    assert written == [tmp_path / f"batch{k}.png" for k in range(4)]
    for k, path in enumerate(here):
        assert (tmp_path / f"batch{k}.png").read_bytes() == path.read_bytes()


@pytest.mark.parametrize("workers", ["0", "1"])
def test_an_error_is_raised_after_the_other_figures(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, workers: str
) -> None:
    monkeypatch.setenv("RACKETDYN_FIGURE_WORKERS", workers)
    batch = render.FigureBatch()
    for k in range(3):
        figure = _figure()
        if k == 0:  # a mathtext error appears only when the figure is drawn
            figure.axes[0].set_title(r"$\frac{1$")
        batch.add(figure, tmp_path / f"{k}.png")
    with pytest.raises(ValueError if workers == "0" else RuntimeError):
        batch.render()
    assert (tmp_path / "1.png").is_file()
    assert (tmp_path / "2.png").is_file()


def test_a_warning_while_drawing_in_the_helper_comes_back(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("RACKETDYN_FIGURE_WORKERS", "1")
    batch = render.FigureBatch()
    for k in range(3):  # too small for its labels: constrained layout warns when drawn
        figure, ax = plt.subplots(figsize=(0.4, 0.4), layout="constrained")
        ax.set_xlabel("a long label " * 5)
        batch.add(figure, tmp_path / f"{k}.png")
    with pytest.warns(UserWarning, match="constrained_layout not applied") as caught:
        batch.render()
    assert len({str(w.message) for w in caught}) == 1
    assert len(caught) >= 3  # one or more from each figure, wherever it was drawn
    assert all((tmp_path / f"{k}.png").is_file() for k in range(3))


def test_paper_figures_keep_their_content() -> None:
    logging.disable(logging.WARNING)
    try:
        racket = rd.default_racket()
        model = rd.modal_model_for(racket)
        data = paper_figures(racket, rd.Ball(), modal_model=model)
        built = {
            e.file: e.drawer()(data) for e in for_step("predict") if e.reads == ("paper_figures",)
        }
    finally:
        logging.disable(logging.NOTSET)
    try:
        face = built["face_maps.png"]
        assert len(face.axes) == 8  # four maps and their colour bars
        assert {ax.get_xlabel() for ax in face.axes[:4]} == {"x from the butt (mm)"}
        curves = built["fig11_12_force_contact_time.png"]
        assert [ax.get_ylabel() for ax in curves.axes] == [
            "equivalent force F_MEAN (N)",
            "contact time T_c (ms)",
        ]
        curve_lines = [
            line for line in curves.axes[0].lines if not line.get_label().startswith("_flagged")
        ]
        assert len(curve_lines) == 6  # three points × two supports (crosses at flagged rows)
        assert len(built["fig14_frame_vibration.png"].axes) == 2
        assert built["fig15_rebound_along_axis.png"].legends  # under the axes (issue 13)
    finally:
        for figure in built.values():
            plt.close(figure)


def test_no_helper_when_told(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("RACKETDYN_FIGURE_WORKERS", "0")
    assert render.start_helper() is False
    monkeypatch.setenv("RACKETDYN_FIGURE_WORKERS", "1")
    assert render.start_helper() is True


def test_starting_the_helper_loads_no_matplotlib_here() -> None:
    code = (
        "import sys; from racketdyn.plotting.helper import start_helper; start_helper(); "
        "print('matplotlib' in sys.modules)"
    )
    env = {**os.environ, "RACKETDYN_FIGURE_WORKERS": "1"}
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env
    )
    assert out.stdout.split() == ["False"]


def test_a_helper_never_given_a_figure_is_stopped_at_once() -> None:
    worker = helper.Worker()  # a step that failed before its figures: no wait for its imports
    worker.close()
    assert worker.process.returncode == -signal.SIGKILL


@pytest.mark.parametrize("no_figures", [False, True])
def test_a_command_starts_the_helper_unless_no_figures(
    monkeypatch: pytest.MonkeyPatch, no_figures: bool
) -> None:
    started: list[bool] = []
    monkeypatch.setattr(helper, "start_helper", lambda: started.append(True) or True)
    opt.start_figure_helper(argparse.Namespace(no_figures=no_figures))
    assert started == ([] if no_figures else [True])


def test_the_figures_of_predict_and_identify_pickle_for_the_helper() -> None:
    """Figs 13 and 15 (predict) and Fig. 6 (identify) did not pickle — their line labels'
    secondary axis held matplotlib's own lambdas — so the helper process could not take them:
    this process drew them after the helper had drawn the rest, one after the other."""
    logging.disable(logging.WARNING)
    try:
        racket = rd.default_racket()
        data = paper_figures(racket, rd.Ball(), modal_model=rd.modal_model_for(racket))
        built = {
            e.file: e.drawer()(data) for e in for_step("predict") if e.reads == ("paper_figures",)
        }
    finally:
        logging.disable(logging.NOTSET)
    figure, ax = plt.subplots(layout="constrained")
    ax.plot([0.0, 1.0], [0.0, 1.0])
    primitives.label_lines(ax, [(0.3, "node", "0.3"), (0.35, "centre of percussion", "k")])
    built["label_lines"] = figure
    try:
        for name, figure in built.items():
            assert pickle.loads(pickle.dumps(figure)) is not None, name
    finally:
        for figure in built.values():
            plt.close(figure)


def test_a_figure_that_does_not_pickle_is_drawn_here_while_the_helper_draws(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A figure the helper cannot take was queued with the others; when the helper's feeder
    took it, this process drew it only after the helper had finished every other figure.  It
    is now this process's from the start: drawn while the helper draws."""
    monkeypatch.setenv("RACKETDYN_FIGURE_WORKERS", "1")
    drawn_here = threading.Event()
    helper_saw_it: list[bool] = []
    render_job = render._png.render_job

    def here(job: dict[str, object]) -> Path:
        path = render_job(job)
        if path.name == "0.png":
            drawn_here.set()
        return path

    worker_render = helper.Worker.render

    def there(self: helper.Worker, job: dict[str, object]) -> object:
        helper_saw_it.append(drawn_here.wait(timeout=20))  # the helper's first figure waits
        return worker_render(self, job)

    monkeypatch.setattr(render._png, "render_job", here)
    monkeypatch.setattr(helper.Worker, "render", there)
    batch = render.FigureBatch()
    for k in range(3):
        figure = _figure(f"figure {k}")
        if k == 0:
            figure.not_picklable = lambda: None  # type: ignore[attr-defined]
        batch.add(figure, tmp_path / f"{k}.png")
    assert batch.render() == [tmp_path / f"{k}.png" for k in range(3)]
    assert helper_saw_it  # the helper drew one or both of the others
    assert all(helper_saw_it)  # each after this process had drawn the one that does not pickle


def _draw_titled(title: str) -> plt.Figure:
    """A registry draw function for the test below."""
    return _figure(title)


def test_a_figure_marked_slow_to_draw_is_built_first_and_listed_in_order(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """predict built its face maps (the slowest of its figures to draw) last, so this process
    drew them after figures.nc while the helper process, done with the others, waited.  An
    entry marked ``draw_first`` is built and queued first (the helper takes it); the files are
    returned in the registry's order."""
    assert registry.entry("face_maps").draw_first  # predict's: four contour maps and bars
    entries = {
        name: registry.FigureEntry(
            name,
            "a step",
            name,
            draw=f"{__name__}:_draw_titled",
            reads=(name,),
            draw_first=name == "slow",
        )
        for name in ("quick", "other", "slow")
    }
    monkeypatch.setattr(registry, "FIGURES", entries)
    monkeypatch.setenv("RACKETDYN_FIGURE_WORKERS", "1")
    added: list[str] = []
    add = render.FigureBatch.add

    def queued(self: render.FigureBatch, figure: plt.Figure, path: Path) -> Path:
        added.append(path.stem)
        return add(self, figure, path)

    monkeypatch.setattr(render.FigureBatch, "add", queued)
    paths = registry.write_figures("a step", {name: name for name in entries}, tmp_path)
    assert added == ["slow", "quick", "other"]
    assert paths == [tmp_path / f"{name}.png" for name in ("quick", "other", "slow")]
