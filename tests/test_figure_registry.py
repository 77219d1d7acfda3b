"""The one registry of figures (issue 23): every figure a step writes is one entry, with a
caption and a place in the report (or a reason for none); hooks, ``result.plot(id)``, the
report's captions and the documentation's list come from it.

Redrawing predict's figures from a run folder alone: ``tests/test_figure_data.py``; every PNG of
a demo-like folder placed in its registered section of the page: ``tests/test_html_report.py``.
"""

from __future__ import annotations

import inspect
import logging
import re
import subprocess
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest

from racketdyn.plotting import registry
from racketdyn.plotting.registry import CAPTION_DEFAULTS, FIGURES, of_file
from racketdyn.report import CAPTIONS, SECTIONS
from racketdyn.workflows.setup import Setup

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "racketdyn"
DOCS = ROOT / "docs"


@pytest.mark.parametrize("figure", list(FIGURES.values()), ids=list(FIGURES))
def test_every_figure_has_a_caption_and_a_report_place(figure: registry.FigureEntry) -> None:
    assert figure.caption.strip(), f"{figure.id}: no caption"
    assert not figure.caption.endswith("."), f"{figure.id}: the page adds the full stop"
    figure.caption.format_map(CAPTION_DEFAULTS)  # every {field} has words
    assert (figure.section is None) != (not figure.not_in_report), (
        f"{figure.id}: a report section, or a reason it has none (not both)"
    )
    if figure.section is not None:
        assert figure.section in SECTIONS, f"{figure.id}: no report section {figure.section!r}"
    assert figure.paper is None or figure.paper.startswith("Fig")
    assert CAPTIONS[figure.id] == (figure.paper, figure.caption)  # the report's, from here


@pytest.mark.parametrize(
    "figure", [f for f in FIGURES.values() if f.draw], ids=[k for k, f in FIGURES.items() if f.draw]
)
def test_every_draw_function_is_a_plotting_function_taking_what_the_entry_reads(
    figure: registry.FigureEntry,
) -> None:
    assert figure.draw.startswith("racketdyn.plotting."), figure.draw
    assert figure.reads, f"{figure.id}: a draw function reads the step's data"
    parameters = inspect.signature(figure.drawer()).parameters.values()
    positional = [p for p in parameters if p.kind is p.POSITIONAL_OR_KEYWORD]
    required = [p for p in positional if p.default is p.empty]
    assert len(required) <= len(figure.reads) <= len(positional), figure.id


def test_every_figure_is_drawn_by_its_entry() -> None:
    """Issue 23: ``write_figures`` is the one door; sweep's summaries were drawn by their own
    writer, outside the registry (an entry without a draw function)."""
    assert [f.id for f in FIGURES.values() if not f.draw] == []


def test_ids_and_files_are_unique_and_found_back_from_a_file_name() -> None:
    files = [f.file for f in FIGURES.values()]
    assert len(set(files)) == len(files)
    for figure in FIGURES.values():
        assert figure.file == f"{figure.id}.png"
        assert of_file(figure.file) is figure
        if figure.labelled:
            assert of_file(figure.file_for("free")) is figure
    assert of_file("fig6_nodes_hand.png") is FIGURES["fig6_nodes"]
    assert of_file("fig6_nodes_free_hand.png") is FIGURES["fig6_nodes_free_hand"]
    assert of_file("summary_tension_n.png") is FIGURES["summary"]
    assert of_file("no_such_figure.png") is None
    with pytest.raises(KeyError, match="no figure 'no_such_figure'"):
        registry.entry("no_such_figure")


def test_no_figure_file_is_named_outside_the_registry() -> None:
    """A figure's file name is written once: in its entry."""
    literal = re.compile(r"""["']([\w{}<>-]+\.png)["']""")
    found = [
        f"{path.relative_to(SRC)}: {name}"
        for path in sorted(SRC.rglob("*.py"))
        if path.name != "registry.py"
        for name in literal.findall(path.read_text(encoding="utf-8"))
    ]
    assert not found, found


def test_the_docs_name_only_registered_figures_and_list_the_registry() -> None:
    named = {
        name
        for page in sorted((DOCS / "commands").glob("*.md"))
        for name in re.findall(r"`([\w<>-]+\.png)`", page.read_text(encoding="utf-8"))
    }
    assert named, "the command pages list their figures"
    assert not [name for name in named if of_file(name) is None]
    # docs/figures.md includes the tables docs/conf.py writes from the registry at each build
    assert "{include} _generated/figures.md" in (DOCS / "figures.md").read_text(encoding="utf-8")
    assert 'registry").markdown(' in (DOCS / "conf.py").read_text(encoding="utf-8")
    tables = registry.markdown({key: section.title for key, section in SECTIONS.items()})
    assert "| Rebound ratio and sweet spots |" in tables
    for figure in FIGURES.values():
        name = f"{figure.id}_<label>.png" if figure.labelled else figure.file
        assert f"`{name}`" in tables, figure.id
    assert "{" not in tables  # every run's setting in words


@pytest.mark.slow
def test_importing_the_registry_loads_no_matplotlib() -> None:
    code = (
        "import sys, racketdyn.plotting.registry, racketdyn.report.figures; "
        "print('matplotlib' in sys.modules)"
    )
    loaded = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.strip()
    assert loaded == "False"


def _lines(figure: plt.Figure) -> list[np.ndarray]:
    return [np.asarray(line.get_ydata(), float) for ax in figure.axes for line in ax.get_lines()]


def test_a_result_plots_its_registered_figures(tmp_path: Path) -> None:
    """``result.plot(id)`` (python-control style) draws the registry's figure from the result;
    the same figure drawn from the folder's data alone draws the same lines."""
    from racketdyn.plotting.registry import draw
    from racketdyn.workflows import PredictOptions, run_predict
    from racketdyn.workflows.figure_data import read_step_data

    logging.disable(logging.WARNING)
    try:
        result = run_predict(
            tmp_path, setup=Setup(figures=None), options=PredictOptions(speeds=[20.0], grid=3)
        )
    finally:
        logging.disable(logging.NOTSET)
    assert not list(tmp_path.glob("*.png"))
    from_result = result.plot("fig15_rebound_along_axis")
    from_folder = draw("fig15_rebound_along_axis.png", read_step_data(tmp_path))
    try:
        assert from_result.get_suptitle() == from_folder.get_suptitle()
        first, second = _lines(from_result), _lines(from_folder)
        assert len(first) == len(second) > 0
        for a, b in zip(first, second, strict=True):
            np.testing.assert_array_equal(a, b)
    finally:
        plt.close(from_result)
        plt.close(from_folder)
    with pytest.raises(ValueError, match="needs transient_histories"):
        result.plot("transient_histories")  # the approximate method alone: no histories
    with pytest.raises(KeyError, match="no figure"):
        result.plot("fig99")


@pytest.mark.slow
def test_every_file_a_step_writes_is_its_registered_figure(tmp_path: Path) -> None:
    """The hooks of the steps drawn from their data write exactly the registry's files."""
    from racketdyn.plotting.steps import oblique_figures, twist_figures
    from racketdyn.workflows import run_oblique, run_twist

    logging.disable(logging.WARNING)
    try:
        twist = run_twist(
            tmp_path / "twist", offsets_m=[-0.03, 0.0, 0.03], setup=Setup(figures=twist_figures)
        )
        oblique = run_oblique(tmp_path / "oblique", setup=Setup(figures=oblique_figures))
    finally:
        logging.disable(logging.NOTSET)
    for step, result in (("twist", twist), ("oblique", oblique)):
        written = {p.name for p in result.written if p.suffix == ".png"}
        assert written == {f.file for f in registry.for_step(step)}
        assert all(of_file(name) is not None for name in written)


@pytest.mark.slow
def test_a_new_figure_is_its_draw_function_and_one_entry(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Issue 23's goal: adding a figure touches two files, its draw function and its entry.
    Entries added here (drawing with a function that exists) are written by predict's hook,
    captioned and shown in their report sections — one that lists its figures from the
    registry, one whose template names its figures (the new one goes at its end) — and listed
    in the docs, nothing else changed."""
    from racketdyn.plotting.steps import predict_figures
    from racketdyn.report.folder import RunFolder
    from racketdyn.report.sections import impact
    from racketdyn.workflows import PredictOptions, run_predict

    new = registry.FigureEntry(
        "fig99_new_figure",
        "predict",
        "a new figure of the pulse, {speeds}",
        section="impact",
        draw="racketdyn.plotting.figures:figure_pulse_spectrum",
        reads=("paper_figures",),
    )
    monkeypatch.setitem(FIGURES, new.id, new)
    # and one in a section whose template names its figures one by one: placed at its end
    slotted = registry.FigureEntry(
        "fig98_new_map", "predict", "a new map", section="rebound", draw=new.draw, reads=new.reads
    )
    monkeypatch.setitem(FIGURES, slotted.id, slotted)
    logging.disable(logging.WARNING)
    try:
        result = run_predict(
            tmp_path / "p",
            setup=Setup(figures=predict_figures()),
            options=PredictOptions(speeds=[20.0], grid=3),
        )
    finally:
        logging.disable(logging.NOTSET)
    assert "fig99_new_figure.png" in {path.name for path in result.written}
    data = impact.gather(RunFolder.scan(tmp_path))
    assert data is not None
    shown = [figure for group in data["figures"] for figure in group.figures]
    assert [f.text for f in shown if f.where.endswith("fig99_new_figure.png")] == [
        "A new figure of the pulse, 20 m/s."
    ]
    assert "`fig99_new_figure.png`" in registry.markdown()
    from racketdyn.report import write_report

    page = write_report(tmp_path).read_text(encoding="utf-8")
    sections = dict(re.findall(r'<section id="([\w-]+)">(.*?)</section>', page, re.S))
    assert "p/fig99_new_figure.png" in sections["impact"]
    assert "p/fig98_new_map.png" in sections["rebound"]
    assert "A new map." in sections["rebound"]
    assert page.count("p/fig98_new_map.png") == 1
