"""Test helper: catch the figures a step draws instead of rendering them (no test here)."""

from __future__ import annotations

from pathlib import Path

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
