"""A step's deferred files (``figures.nc``): written while its figures are drawn in the helper
process, before ``run.json``; a hook that does not write them finds them written; an error in
one is raised after every queued figure is written."""

from __future__ import annotations

from pathlib import Path

import pytest

from figure_catch import default_paper_figures
from racketdyn.plotting.registry import write_figures
from racketdyn.plotting.steps import identify_figures, predict_figures
from racketdyn.workflows.run import (
    WRITES_PENDING,
    StepResult,
    defer_file,
    finish_run,
)


def _deferred(tmp_path: Path, content: str = "data") -> StepResult:
    result = StepResult(tmp_path)
    path = tmp_path / "later.txt"
    defer_file(result, path, lambda: path.write_text(content))
    return result


def test_a_hook_that_does_not_write_them_finds_them_written(tmp_path: Path) -> None:
    result = _deferred(tmp_path)
    seen: list[bool] = []

    def hook(step: StepResult, out: Path) -> list[Path]:
        seen.append((out / "later.txt").is_file())
        return []

    finish_run(result, {}, ["step"], hook)
    assert seen == [True]
    assert result.record["outputs"] == ["later.txt", "run.json"]
    assert result.pending == []


def test_without_figures_they_are_written(tmp_path: Path) -> None:
    result = _deferred(tmp_path)
    finish_run(result, {}, ["step"], None)
    assert (tmp_path / "later.txt").read_text() == "data"


def test_the_registrys_hooks_write_them_while_drawing() -> None:
    assert getattr(predict_figures(), WRITES_PENDING) is True
    assert getattr(identify_figures, WRITES_PENDING) is True


class _Predicted(StepResult):
    paper_figures: object = None


@pytest.mark.parametrize("workers", ["0", "1"])
@pytest.mark.slow
def test_an_error_in_a_deferred_file_comes_after_the_figures(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, workers: str
) -> None:
    monkeypatch.setenv("RACKETDYN_FIGURE_WORKERS", workers)
    result = _Predicted(tmp_path)
    result.paper_figures = default_paper_figures()

    def fails() -> None:
        raise OSError("disk full")

    defer_file(result, tmp_path / "figures.nc", fails)
    with pytest.raises(OSError, match="disk full"):
        write_figures("predict", result, tmp_path)
    written = sorted(p.name for p in tmp_path.iterdir())
    assert written == [
        "face_maps.png",
        "fig11_12_force_contact_time.png",
        "fig13_pulse_spectrum.png",
        "fig14_frame_vibration.png",
        "fig15_rebound_along_axis.png",
    ]
