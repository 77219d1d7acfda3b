"""The case a prediction's summaries show (issue 27).

With ``predict --speed 25,3 --racket-speed 28,42`` the single-case summaries — the face maps,
Fig. 15, the models' comparison table, the report's "At a glance" — showed the 3 m/s case chosen
by the speed rule and said "3 m/s, pinned" without the 42 m/s racket speed.  Every headline now
names the ball speed, the racket speed and the support; ``show`` (``--show SPEED[,RACKET]``)
chooses the case, and run.json records it so the report shows the same one.  Figs 11–12
interpolated the racket speed along the ball-speed axis (a kink at 25 m/s that is not
physics): they now draw one set of curves per racket speed, each panel titled with it.
"""

from __future__ import annotations

import csv
import json
import re
from pathlib import Path

import numpy as np
import pytest

from racketdyn.cli import main
from racketdyn.errors import InputError
from racketdyn.report import write_report
from racketdyn.workflows.figure_data import FIGURES_FILE, PaperFigures, read_figure_data
from racketdyn.workflows.predict import PredictOptions, run_predict

SERVE = {"speeds": [25.0, 3.0], "racket_speed": [28.0, 42.0], "grid": 3}


@pytest.fixture(scope="module")
def chosen(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("show") / "predict"
    run_predict(out, options=PredictOptions(**SERVE, show=(25.0, 28.0)))
    return out


def test_show_chooses_the_case_and_run_json_records_it(chosen: Path) -> None:
    record = json.loads((chosen / "run.json").read_text(encoding="utf-8"))
    assert record["shown_case"] == {
        "ball_speed_mps": 25.0,
        "racket_speed_mps": 28.0,
        "chosen_by": "show",
    }
    figures = PaperFigures.from_xarray(read_figure_data(chosen / FIGURES_FILE))
    assert figures.face.ball_speed.tolist() == [25.0]
    assert figures.face.racket_speed.tolist() == [28.0]
    assert figures.axis.ball_speed.tolist() == [25.0]
    assert figures.axis.racket_speed.tolist() == [28.0]


def test_without_show_the_rule_s_case_is_recorded(tmp_path: Path) -> None:
    result = run_predict(tmp_path / "p", options=PredictOptions(**SERVE))
    assert result.shown_speed == 1  # no 20 m/s: the middle speed, the lower of two
    record = json.loads((tmp_path / "p" / "run.json").read_text(encoding="utf-8"))
    assert record["shown_case"]["ball_speed_mps"] == 3.0
    assert record["shown_case"]["racket_speed_mps"] == 42.0
    assert record["shown_case"]["chosen_by"].startswith("default")


@pytest.mark.parametrize(
    ("show", "words"),
    [
        ((25.0, 42.0), "`show` 25, 42 m/s: not a case of the run"),
        ((7.0,), "`show` 7 m/s: not a case of the run"),
        ((1.0, 2.0, 3.0), "`show` takes a ball speed and, optionally, its racket speed"),
    ],
)
def test_a_show_not_run_is_one_line_naming_the_cases(
    tmp_path: Path, show: tuple[float, ...], words: str
) -> None:
    with pytest.raises(InputError) as error:
        run_predict(tmp_path / "p", options=PredictOptions(**SERVE, show=show))
    message = str(error.value)
    assert words in message
    assert "\n" not in message
    if len(show) < 3:
        assert "ball 25 m/s with racket 28 m/s, ball 3 m/s with racket 42 m/s" in message


def test_figs_11_12_draw_one_curve_per_racket_speed(chosen: Path) -> None:
    figures = PaperFigures.from_xarray(read_figure_data(chosen / FIGURES_FILE))
    curves = figures.speed_curves
    # the racket speeds are the run's own, never interpolated between them (no 35 m/s)
    assert sorted(set(curves.racket_speed.tolist())) == [28.0, 42.0]
    at_28 = curves.ball_speed[curves.racket_speed == 28.0]
    at_42 = curves.ball_speed[curves.racket_speed == 42.0]
    assert at_28.tolist() == at_42.tolist()  # each racket speed over the whole speed axis
    assert at_28.min() <= 3.0
    assert at_28.max() >= 25.0
    assert figures.run_racket_speeds.tolist() == [28.0, 42.0]
    # along one racket speed's curve the contact time falls smoothly with speed: no kink
    centre = curves.labels.index("centre")
    p = curves.support_index("free")
    rows = np.flatnonzero(curves.racket_speed == 28.0)
    tc = curves.contact_time[centre, rows, p]
    ok = np.isfinite(tc)
    slopes = np.diff(tc[ok]) / np.diff(curves.ball_speed[rows][ok])
    assert np.all(slopes < 0)
    assert np.ptp(np.diff(slopes)) < 1e-4  # no kink (the interpolated curve bent at 25 m/s)


def test_fig_11_12_panels_are_titled_with_their_racket_speed(chosen: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    from racketdyn.plotting.figures import figure_force_and_contact_time

    figures = PaperFigures.from_xarray(read_figure_data(chosen / FIGURES_FILE))
    figure = figure_force_and_contact_time(figures)
    titles = [ax.get_title() for ax in figure.axes if ax.get_title()]
    assert any("racket 28 m/s" in t for t in titles), titles
    assert any("racket 42 m/s" in t for t in titles), titles


def test_the_face_maps_name_ball_racket_and_support(chosen: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    from racketdyn.plotting.figures import figure_face_maps

    figures = PaperFigures.from_xarray(read_figure_data(chosen / FIGURES_FILE))
    figure = figure_face_maps(figures)
    titles = [ax.get_title() for ax in figure.axes if ax.get_title()]
    assert titles
    for title in titles:
        assert "ball 25 m/s" in title, title
        assert "racket 28 m/s" in title, title
        assert re.search(r"freely supported|pinned at the grip|hand-held", title), title


def test_the_cli_show_reaches_the_report(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "serve"
    argv = ["predict", "--speed", "25,3", "--racket-speed", "28,42", "--grid", "3"]
    capsys.readouterr()
    assert main([*argv, "--show", "25,28", "--no-figures", "--out", str(out)]) == 0
    console = " ".join(capsys.readouterr().out.split())
    assert "shown: ball 25 m/s, racket 28 m/s" in console
    page = write_report(out).read_text(encoding="utf-8")
    glance = page[page.index("At a glance") : page.index("</ul>", page.index("At a glance"))]
    assert "face centre, ball 25 m/s, racket 28 m/s, pinned:" in glance
    assert "ball 3 m/s" not in glance
    assert main([*argv, "--show", "25,42", "--no-figures", "--out", str(out)]) == 2
    error = " ".join(capsys.readouterr().err.split())
    assert "--show 25, 42 m/s: not a case of the run" in error


def test_the_models_table_names_its_case(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = ["predict", "--speed", "25,3", "--racket-speed", "28,42", "--grid", "2"]
    argv += ["--model", "both", "--support", "free", "--show", "3", "--no-figures"]
    capsys.readouterr()
    assert main([*argv, "--out", str(tmp_path / "both")]) == 0
    console = " ".join(capsys.readouterr().out.split())
    assert "approximate against transient, ball 3 m/s, racket 42 m/s" in console


def _page_tables(page: Path) -> list[str]:
    """The report's tables as text, one string each."""
    import html

    text = page.read_text(encoding="utf-8")
    tables = re.findall(r"<table.*?</table>", text, re.S)
    return [re.sub(r"\s+", " ", html.unescape(re.sub(r"<[^>]+>", " ", t))) for t in tables]


def test_two_cases_at_one_ball_speed_stay_apart_in_the_report(tmp_path: Path) -> None:
    """Two cases sharing a ball speed (``--speed 20,20 --racket-speed 0,30``) were merged into
    one row per support in the report's tables and maps: its rows were keyed by ball speed."""
    out = tmp_path / "predict"
    options = PredictOptions(speeds=[20.0, 20.0], racket_speed=[0.0, 30.0], grid=3)
    run_predict(out, options=options)
    tables = _page_tables(write_report(out))
    contact = next(t for t in tables if "contact time (ms)" in t and "support" in t)
    for support in ("free", "pinned"):
        assert f"{support} 20, racket at rest " in contact
        assert f"{support} 20, racket 30 " in contact
    sweet = next(t for t in tables if "highest rebound ratio" in t)
    # the centre's rebound ratio of each case, as impact.csv has it (the centre at 505, 0 mm)
    with (out / "impact.csv").open(encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    centre = {
        (row["support"], float(row["racket_speed_mps"])): float(row["rebound_ratio"])
        for row in rows
        if abs(float(row["x_m"]) - 0.505) < 1e-9 and abs(float(row["y_m"])) < 1e-9
    }
    assert len(centre) == 4
    assert len(set(centre.values())) == 4  # the cases differ
    for (support, racket_speed), value in centre.items():
        words = "racket at rest" if racket_speed == 0 else f"racket {racket_speed:g}"
        assert re.search(rf"{support} 20, {words} \S+ \S+, \S+ {value:.3f}", sweet), sweet


def test_the_models_curves_against_speed_take_each_racket_speed_whole() -> None:
    """The approximate-against-transient curves against speed interpolated the racket speed
    between the run's (ball, racket) pairs, as Figs 11–12 did: one set per racket speed now."""
    import matplotlib

    matplotlib.use("Agg")
    from racketdyn.ball import Ball
    from racketdyn.io.racket_file import default_racket
    from racketdyn.plotting.figures import figure_transient_comparison_speed
    from racketdyn.workflows.figure_data import TransientCurves, transient_curves

    curves = transient_curves(
        default_racket(),
        Ball(),
        speeds=SERVE["speeds"],
        racket_speeds=SERVE["racket_speed"],
        supports=("free",),
        engine="compiled",
    )
    for part in (curves.approximate, curves.transient):
        assert sorted(set(part.racket_speed.tolist())) == [28.0, 42.0]
        at_28 = part.ball_speed[part.racket_speed == 28.0]
        at_42 = part.ball_speed[part.racket_speed == 42.0]
        assert at_28.tolist() == at_42.tolist()
        assert at_28.min() <= 3.0
        assert at_28.max() >= 25.0
    assert curves.run_racket_speeds.tolist() == [28.0, 42.0]
    back = TransientCurves.from_xarray(curves.to_xarray())
    assert back.run_racket_speeds.tolist() == [28.0, 42.0]
    np.testing.assert_array_equal(back.transient.racket_speed, curves.transient.racket_speed)
    figure = figure_transient_comparison_speed(back)
    titles = [ax.get_title() for ax in figure.axes if ax.get_title()]
    assert any("racket 28 m/s" in t for t in titles), titles
    assert any("racket 42 m/s" in t for t in titles), titles
