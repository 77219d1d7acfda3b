"""Test helper: catch the figures a step draws instead of rendering them, and compare two
drawings (no test here)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

Drawn = dict[str, Figure]


class Catch:
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


def catch_figures(patch: Any, drawn: Drawn, modules: tuple[Any, ...] = ()) -> None:
    """Catch every figure a step's hook draws in a batch into ``drawn``; ``patch`` is a
    ``pytest.MonkeyPatch``. With ``modules``, a figure saved alone is caught too: ``render``'s
    and each module's own ``save_figure`` (the writers that import it by name)."""
    from racketdyn.plotting import render

    patch.setattr(render, "FigureBatch", lambda: Catch(drawn))
    for module in (render, *modules) if modules else ():
        patch.setattr(module, "save_figure", lambda figure, path: Catch(drawn).add(figure, path))


def rig_frfs(folder: Path) -> Path:
    """The virtual rig's hammer tests, free and hand-held (few averages, no faults), and their
    FRFs in ``folder``: ``rig/hammer_<support>.uff``, ``frf_<support>/frfs.uff``."""
    import logging

    from racketdyn.cli import main

    commands = [
        ["rig", "--support", "free,hand", "--averages", "2", "--out", f"{folder}/rig"],
        ["frf", f"{folder}/rig/hammer_free.uff", "--out", f"{folder}/frf_free"],
        ["frf", f"{folder}/rig/hammer_hand.uff", "--out", f"{folder}/frf_hand"],
    ]
    logging.disable(logging.WARNING)
    try:
        for argv in commands:
            assert main(argv) == 0, argv
    finally:
        logging.disable(logging.NOTSET)
    return folder


def default_paper_figures() -> Any:
    """The paper figures' data of the built-in racket and ball (``predict``'s defaults), its
    warnings about flagged impacts silenced."""
    import logging

    import racketdyn as rd
    from racketdyn.workflows.figure_data import paper_figures

    logging.disable(logging.WARNING)
    try:
        racket = rd.default_racket()
        return paper_figures(racket, rd.Ball(), modal_model=rd.modal_model_for(racket))
    finally:
        logging.disable(logging.NOTSET)


# --- two drawings the same ---------------------------------------------------------------------
def _artists(figure: Figure) -> list[list[np.ndarray]]:
    """What each axes of a figure draws: its lines' x and y, its collections' points and
    values (NaN kept), in drawing order."""
    drawn = []
    for ax in figure.axes:
        arrays: list[np.ndarray] = []
        for line in ax.get_lines():
            arrays += [np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)]
        for collection in ax.collections:
            arrays.append(np.asarray(collection.get_offsets(), float))
            values = collection.get_array()
            if values is not None:
                arrays.append(np.asarray(values, float))
        drawn.append(arrays)
    return drawn


def _texts(figure: Figure) -> list[list[str]]:
    """Every text of a figure by axes: title, axis labels, texts and annotations, legend."""
    found = [[figure.get_suptitle()]]
    for ax in figure.axes:
        legend = ax.get_legend()
        found.append(
            [ax.get_title(), ax.get_xlabel(), ax.get_ylabel()]
            + [t.get_text() for t in ax.texts]
            + ([t.get_text() for t in legend.get_texts()] if legend is not None else [])
        )
    return found


def same_drawing(first: Figure, second: Figure) -> None:
    """Two figures draw the same: each axes' lines and collections (bit for bit) and texts."""
    a, b = _artists(first), _artists(second)
    assert [len(x) for x in a] == [len(x) for x in b]
    for left, right in zip(a, b, strict=True):
        for u, v in zip(left, right, strict=True):
            np.testing.assert_array_equal(u, v)
    assert _texts(first) == _texts(second)


def same_3d_drawing(first: Figure, second: Figure) -> None:
    """Fig. 4's panels: the same surfaces (their 3-D vertices), lines and points."""

    def drawn(figure: Figure) -> list[np.ndarray]:
        arrays = []
        for ax in figure.axes:
            for line in ax.get_lines():
                arrays.append(np.asarray(line.get_data_3d(), float))  # type: ignore[attr-defined]
            for collection in ax.collections:  # a surface's faces, or a scatter's points
                faces = getattr(collection, "_faces", None)
                if faces is None:
                    points = getattr(collection, "_offsets3d", collection.get_offsets())
                    arrays.append(np.asarray(points, float))
                    continue
                invalid = np.asarray(getattr(collection, "_invalid_vertices", False))
                padding = np.broadcast_to(invalid, np.shape(faces)[:2])[..., None]
                arrays.append(np.where(padding, 0.0, np.asarray(faces, float)))
        return arrays

    a, b = drawn(first), drawn(second)
    assert len(a) == len(b) > 0
    for u, v in zip(a, b, strict=True):
        np.testing.assert_array_equal(u, v)
    assert _texts(first) == _texts(second)
