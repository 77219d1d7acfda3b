"""Test helper: catch the figures a step draws instead of rendering them (no test here)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

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


def catch_figures(patch: Any, drawn: Drawn) -> None:
    """Catch every figure a step's hook draws in a batch into ``drawn``; ``patch`` is a
    ``pytest.MonkeyPatch``."""
    from racketdyn.plotting import render

    patch.setattr(render, "FigureBatch", lambda: Catch(drawn))


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
