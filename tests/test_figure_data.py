"""Results carry the data their figures show (issue 23): each step computes what its figures
draw with the run's own inputs and writes it to ``figures.nc``; a figure redrawn from that file
alone draws the same lines as the figure the run drew."""

from __future__ import annotations

import logging
from collections.abc import Iterator
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.figure import Figure

import racketdyn as rd
from racketdyn.cli import main
from racketdyn.plotting import figures as figures_module
from racketdyn.plotting.steps import compare_figures

Drawn = dict[str, Figure]


class _Catch:
    """Stands in for FigureBatch: keeps each figure by file name, writes an empty file."""

    def __init__(self, drawn: Drawn) -> None:
        self.drawn = drawn
        self.paths: list[Path] = []

    def add(self, figure: Figure, path: Path) -> Path:
        self.drawn[Path(path).name] = figure
        Path(path).write_bytes(b"")
        self.paths.append(Path(path))
        return Path(path)

    def render(self) -> list[Path]:
        return list(self.paths)


@pytest.fixture
def caught(monkeypatch: pytest.MonkeyPatch) -> Iterator[Drawn]:
    """The figures the step draws, by file name, as matplotlib objects."""
    drawn: Drawn = {}
    monkeypatch.setattr(figures_module, "FigureBatch", lambda: _Catch(drawn))
    yield drawn
    for figure in drawn.values():
        plt.close(figure)


@pytest.fixture(scope="module")
def frfs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """FRFs of the virtual rig, free and hand-held (few averages, no faults)."""
    d = tmp_path_factory.mktemp("frfs")
    commands = [
        ["rig", "--support", "free,hand", "--averages", "2", "--out", f"{d}/rig"],
        ["frf", f"{d}/rig/hammer_free.uff", "--out", f"{d}/frf_free"],
        ["frf", f"{d}/rig/hammer_hand.uff", "--out", f"{d}/frf_hand"],
    ]
    logging.disable(logging.WARNING)
    try:
        for argv in commands:
            assert main(argv) == 0, argv
    finally:
        logging.disable(logging.NOTSET)
    return d / "frf_free" / "frfs.uff", d / "frf_hand" / "frfs.uff"


def _lines(figure: Figure) -> dict[str, np.ndarray]:
    """The drawn lines of a one-axes figure by legend label: their y data."""
    (ax,) = [a for a in figure.axes if a.get_lines()]
    return {
        str(line.get_label()): np.asarray(line.get_ydata(), dtype=float) for line in ax.get_lines()
    }


def test_compare_fig15_uses_the_runs_ball(
    frfs: tuple[Path, Path], tmp_path: Path, caught: Drawn
) -> None:
    """The compare step's Fig. 15 predicted with a default ``Ball()`` whatever ball the run
    used (issue 23): a heavier ball must change the curves, and they must be that ball's."""
    from racketdyn.workflows.identify import run_compare

    heavy = rd.Ball(mass_kg=0.0594, e_bg=0.78)
    logging.disable(logging.WARNING)
    try:
        result = run_compare(
            frfs[0], frfs[1], tmp_path / "compare", ball=heavy, figures=compare_figures
        )
    finally:
        logging.disable(logging.NOTSET)
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
        "hand-held, hand-held modes": ("pinned", result.hand.model),
        "hand-held, free modes": ("pinned", result.free.model),
        "freely supported, free modes": ("free", result.free.model),
    }
    for label, (support, model) in cases.items():
        expected = rd.predict(racket, heavy, points, [20.0], (support,), modal_model=model)
        default = rd.predict(racket, rd.Ball(), points, [20.0], (support,), modal_model=model)
        np.testing.assert_allclose(drawn[label], expected.rebound_ratio[:, 0, 0], rtol=1e-12)
        assert not np.allclose(drawn[label], default.rebound_ratio[:, 0, 0], equal_nan=True)
