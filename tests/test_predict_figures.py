"""``predict``'s figures follow what was asked and what was run (issue 13), and its printed
headline: the figures are caught as matplotlib objects on their way to the files (no pixels
read), then their axes, titles, line labels and data are checked against the run."""

from __future__ import annotations

import csv
import json
import logging
import re
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.axes import Axes
from matplotlib.figure import Figure

import racketdyn as rd
from figure_catch import Drawn, catch_figures
from racketdyn.cli import main
from racketdyn.plotting.steps import predict_figures
from racketdyn.racket import landmark_points
from racketdyn.workflows import PredictOptions, PredictResult, PulseSpectra, run_predict
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup


@pytest.fixture
def draw(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> Iterator[Callable[..., tuple[PredictResult, Drawn]]]:
    """``draw(setup=Setup(...), **PredictOptions fields)`` → (result, figures by file name)."""
    caught: list[Drawn] = []

    def run(setup: Setup = DEFAULT_SETUP, **options: Any) -> tuple[PredictResult, Drawn]:
        drawn: Drawn = {}
        catch_figures(monkeypatch, drawn)
        out = tmp_path / f"run{len(caught)}"
        caught.append(drawn)
        logging.disable(logging.WARNING)  # flagged rows log warnings; not the subject here
        try:
            result = run_predict(
                out, setup.replace(figures=predict_figures()), PredictOptions(**options)
            )
        finally:
            logging.disable(logging.NOTSET)
        return result, drawn

    yield run
    for drawn in caught:
        for figure in drawn.values():
            plt.close(figure)


def _titles(figure: Figure) -> list[str]:
    return [ax.get_title() for ax in figure.axes if ax.get_title()]


def _maps(figure: Figure) -> list[Axes]:
    """The map panels of face_maps.png (colour bars have no title)."""
    return [ax for ax in figure.axes if ax.get_title()]


def _line_labels(figure: Figure) -> list[str]:
    return [line.get_label() for ax in figure.axes for line in ax.get_lines()]


def _line_data(figure: Figure) -> list[np.ndarray]:
    """The curves' data (the crosses that mark flagged rows aside: their number varies)."""
    return [
        np.asarray(line.get_ydata(), dtype=float)
        for ax in figure.axes
        for line in ax.lines
        if not line.get_label().startswith("_flagged")
    ]


# --- face maps -----------------------------------------------------------------------------------


def test_face_maps_show_the_run_speed_and_only_its_supports(draw: Any) -> None:
    result, drawn = draw(speeds=[25.0, 35.0], supports=["free"], grid=5)
    face = drawn["face_maps.png"]
    shown = result.speeds[result.shown_speed]
    assert shown == 25.0  # the CLI's rule: 20 m/s if given, else the middle speed
    maps = _maps(face)
    assert len(maps) == 3  # rebound ratio, contact time, vibration energy: free only
    for title in _titles(face):
        assert "freely supported" in title
        assert "pinned" not in title
        assert f"{shown:g} m/s" in title
    assert "20 m/s" not in face.get_suptitle()
    # the trial of 2026-11-27: with --model both the maps showed the approximate method only
    # and did not say so
    assert "approximate method" in face.get_suptitle()


def test_face_maps_draw_the_runs_points(draw: Any) -> None:
    points = np.array([[0.505, 0.0], [0.45, 0.02], [0.56, -0.03], [0.52, 0.05]])
    _, drawn = draw(speeds=[20.0], supports=["pinned", "free"], points=points)
    maps = _maps(drawn["face_maps.png"])
    assert len(maps) == 4
    for ax in maps:
        offsets = [np.asarray(c.get_offsets()) for c in ax.collections if len(c.get_offsets())]
        drawn_points = {tuple(np.round(p, 3)) for o in offsets for p in o}
        assert {tuple(np.round(p * 1e3, 3)) for p in points} <= drawn_points


@pytest.mark.slow
def test_face_maps_of_points_on_a_line_are_points_not_a_contour(draw: Any) -> None:
    points = np.array([[0.45, 0.0], [0.505, 0.0], [0.56, 0.0]])  # collinear: no triangles
    _, drawn = draw(speeds=[20.0], supports=["free"], points=points)
    for ax in _maps(drawn["face_maps.png"]):
        sizes = [len(c.get_offsets()) for c in ax.collections]
        assert 3 in sizes


def test_face_maps_say_the_options(draw: Any) -> None:
    _, drawn = draw(
        speeds=[20.0],
        supports=["free"],
        grid=4,
        racket_speed=[15.0],
        stiffness_reading="tangent",
        include_string_bed=True,
    )
    title = drawn["face_maps.png"].get_suptitle()
    assert "racket 15 m/s" in title
    assert "tangent" in title
    assert "string-bed modes charged" in title
    assert "string-bed law" not in title  # the paper's one law: nothing to say


@pytest.mark.slow
def test_face_maps_say_each_points_law(draw: Any) -> None:
    _, drawn = draw(speeds=[20.0], supports=["free"], grid=4, setup=Setup(string_bed="local"))
    assert "each point's string-bed law" in drawn["face_maps.png"].get_suptitle()


# --- curves against speed, Figs 11-13 and 15 -----------------------------------------------------


@pytest.mark.slow
def test_force_and_contact_time_follow_the_stiffness_reading(draw: Any) -> None:
    _, period = draw(speeds=[20.0], supports=["free"], grid=3)
    _, tangent = draw(speeds=[20.0], supports=["free"], grid=3, stiffness_reading="tangent")
    name = "fig11_12_force_contact_time.png"
    a, b = _line_data(period[name]), _line_data(tangent[name])
    assert len(a) == len(b)
    assert any(
        x.shape == y.shape and not np.allclose(x, y, equal_nan=True)
        for x, y in zip(a, b, strict=True)
    )
    assert "tangent" in tangent[name].get_suptitle()


def test_force_and_contact_time_show_the_run_supports_and_speeds(draw: Any) -> None:
    _, drawn = draw(speeds=[25.0, 35.0], supports=["free"], grid=3, racket_speed=[10.0])
    figure = drawn["fig11_12_force_contact_time.png"]
    labels = _line_labels(figure)
    assert not any("pinned" in label for label in labels)
    assert any("freely supported" in label for label in labels)
    marked = [
        line
        for ax in figure.axes
        for line in ax.get_lines()
        if line.get_label().startswith("the run's speeds")
    ]
    assert marked
    for line in marked:
        assert set(np.asarray(line.get_xdata(), dtype=float)) == {25.0, 35.0}
    assert "racket 10 m/s" in figure.get_suptitle()


@pytest.mark.slow
def test_force_curves_use_the_run_racket_speed(draw: Any) -> None:
    _, rest = draw(speeds=[20.0], supports=["free"], grid=3)
    _, moving = draw(speeds=[20.0], supports=["free"], grid=3, racket_speed=[15.0])
    name = "fig11_12_force_contact_time.png"
    # every curve together: the top's is NaN since issue 22 (the frame takes over 30 % there)
    at_rest, on_the_move = (np.concatenate(_line_data(d[name])) for d in (rest, moving))
    assert np.isfinite(at_rest).any()
    assert not np.allclose(at_rest, on_the_move, equal_nan=True)


@pytest.mark.slow
def test_pulse_spectrum_is_at_the_run_speeds_and_support(draw: Any) -> None:
    _, drawn = draw(speeds=[15.0, 25.0], supports=["free"], grid=3)
    figure = drawn["fig13_pulse_spectrum.png"]
    labels = [line.get_label().split(":")[0] for line in figure.axes[0].get_lines()]
    assert labels == ["15 m/s", "25 m/s"]
    assert "freely supported" in figure.get_suptitle()


@pytest.mark.slow
def test_the_pulse_of_fig_13_carries_the_impacts_impulse(draw: Any) -> None:
    """Fig. 13 draws eq 11's half sine of the row's impulse F_MEAN T_c (the rebound's with the
    coupled charge), not of its F_MAX: the coupled charge's F_MAX is the spring's force at the
    turn, above a half sine's of one impulse (a stiffening spring's pulse is peaked)."""
    result, _ = draw(speeds=[15.0, 25.0], supports=["free"], grid=3)
    pulse, impacts = result.paper_figures.pulse, result.approximate
    assert impacts is not None
    at = int(np.argmin(np.hypot(*(impacts.locations - np.asarray(pulse.location)).T)))
    assert np.allclose(impacts.locations[at], pulse.location)
    impulse = impacts.impulse[at, :, 0]
    drawn = pulse.drawn()
    assert drawn.any()
    area = np.trapezoid(pulse.force, pulse.time, axis=-1)
    np.testing.assert_allclose(area[drawn], impulse[drawn], rtol=1e-3)
    np.testing.assert_allclose(pulse.spectrum[:, 0][drawn], impulse[drawn], rtol=1e-3)
    assert np.all(impacts.peak_force[at, :, 0][drawn] > 1.05 * pulse.half_sine_peak[drawn])


def test_fig_13_names_its_half_sines_peak_apart_from_the_impacts_peak_force(
    draw: Any, tmp_path: Path
) -> None:
    """Fig. 13's half sine peaks at π F_MEAN / 2 (eq 11), below the impact's own F_MAX with
    the coupled charge.  Before, figures.nc stored it as ``fig13__peak_force_n`` (812 N)
    beside impact.csv's ``peak_force_n`` (1050 N) for the same impact, and the figure did not
    say which it drew (new-user trial, eleventh session)."""
    import xarray as xr

    result, drawn = draw(speeds=[30.0], supports=["pinned"], grid=3)
    stored = xr.open_dataset(tmp_path / "run0" / "figures.nc")
    try:
        assert "fig13__peak_force_n" not in stored
        half_sine = stored["fig13__half_sine_peak_force_n"].values
    finally:
        stored.close()
    pulse, impacts = result.paper_figures.pulse, result.approximate
    assert impacts is not None
    at = int(np.argmin(np.hypot(*(impacts.locations - np.asarray(pulse.location)).T)))
    np.testing.assert_allclose(half_sine, np.pi * impacts.mean_force[at, :, 0] / 2, rtol=1e-12)
    figure = drawn["fig13_pulse_spectrum.png"]
    words = " ".join([figure.get_suptitle(), *_line_labels(figure)])
    assert "eq 11" in words
    assert "F_MAX" in words


def test_rebound_along_axis_at_the_shown_speed_and_run_supports(draw: Any) -> None:
    _, drawn = draw(speeds=[30.0, 40.0, 50.0], supports=["pinned"], grid=3, racket_speed=[5.0])
    figure = drawn["fig15_rebound_along_axis.png"]
    labels = _line_labels(figure)
    assert not any("freely" in label for label in labels)
    title = " ".join(_titles(figure))
    assert "40 m/s" in title
    assert "racket 5 m/s" in title


@pytest.mark.slow
def test_rebound_along_axis_follows_the_string_bed_option(draw: Any) -> None:
    _, off = draw(speeds=[20.0], supports=["free"], grid=3)
    _, on = draw(speeds=[20.0], supports=["free"], grid=3, include_string_bed=True)
    name = "fig15_rebound_along_axis.png"
    assert not np.allclose(_line_data(off[name])[0], _line_data(on[name])[0], equal_nan=True)


# --- Fig. 14 -------------------------------------------------------------------------------------


def test_frame_vibration_at_the_run_speeds_and_supports(draw: Any) -> None:
    _, drawn = draw(speeds=[25.0, 35.0], supports=["free"], grid=3)
    figure = drawn["fig14_frame_vibration.png"]
    assert len(figure.axes) == 1
    labels = _line_labels(figure)
    assert any(label.startswith("25 m/s") for label in labels)
    assert any(label.startswith("35 m/s") for label in labels)
    assert not any(label.startswith("10 m/s") for label in labels)


def test_frame_vibration_marks_flagged_impacts(draw: Any) -> None:
    result, drawn = draw(speeds=[10.0, 30.0], supports=["pinned"], grid=3)
    tip = rd.predict(
        result.racket, result.ball, [landmark_points(result.racket)["tip"]], [30.0], "pinned"
    )
    assert tip.status[0, 0, 0] != "ok"  # the premise: 30 m/s at the tip is flagged
    labels = _line_labels(drawn["fig14_frame_vibration.png"])
    assert any(label.startswith("30 m/s") and "flagged" in label for label in labels)


def test_rigid_racket_draws_no_vibration(draw: Any) -> None:
    _, drawn = draw(speeds=[20.0], supports=["free"], grid=3, setup=Setup(rigid=True))
    figure = drawn.get("fig14_frame_vibration.png")
    if figure is not None:
        assert not any(ax.get_lines() for ax in figure.axes)
        texts = [t.get_text() for ax in figure.axes for t in ax.texts]
        assert any("rigid" in text for text in texts)


def _spectrum_modes(figure: Figure) -> dict[str, Any]:
    """Fig. 13's modes: each label over the spectrum → its dotted line's colour."""
    spectrum = figure.axes[1]
    (top,) = spectrum.child_axes  # label_lines' secondary axis
    names = [t.get_text() for t in top.get_xticklabels()]
    lines = [
        line
        for line in spectrum.get_lines()
        if line.get_linestyle() == ":" and len(line.get_xdata())
    ]
    return {name: line.get_color() for name, line in zip(names, lines, strict=True)}


@pytest.mark.slow
def test_pulse_spectrum_says_which_modes_the_prediction_charges(draw: Any) -> None:
    """New-user trial (2026-11-27, ninth session): Fig. 13 drew the string bed's membranes as
    "modes of the model" while the report's "Modes the prediction used" listed only the
    frame's.  The charged modes and the string bed's (for reference, not charged) are drawn
    apart, and the legend says which is which."""
    result, drawn = draw(speeds=[20.0], supports=["free"], grid=2)
    figure = drawn["fig13_pulse_spectrum.png"]
    pulse = result.paper_figures.pulse
    used = json.loads((result.out / "run.json").read_text(encoding="utf-8"))["modal_model"]
    charged = {name for name, c in zip(pulse.mode_names, pulse.mode_charged, strict=True) if c}
    assert charged == {m["name"] for m in used["modes"]}  # the report's list, the same modes
    assert set(pulse.mode_names) - charged == {"string-bed membrane"}
    colours = _spectrum_modes(figure)
    assert colours["string-bed membrane"] != colours["2-node bending"]
    assert len({colours[name] for name in charged}) == 1
    legend = [t.get_text() for t in figure.axes[1].get_legend().get_texts()]
    assert "modes the prediction charges" in legend
    assert "the string bed's modes: for reference, not charged" in legend
    assert "modes of the model" not in figure.get_suptitle()
    # a figures.nc written before: read as a run charges them by default
    older = pulse.to_xarray().drop_vars("mode_charged")
    assert list(PulseSpectra.from_xarray(older).mode_charged) == list(pulse.mode_charged)
    # with the string bed's modes charged, every mode is drawn as charged
    result, drawn = draw(speeds=[20.0], supports=["free"], grid=2, include_string_bed=True)
    assert all(result.paper_figures.pulse.mode_charged)
    legend = [
        t.get_text() for t in drawn["fig13_pulse_spectrum.png"].axes[1].get_legend().get_texts()
    ]
    assert not any("not charged" in text for text in legend)


# --- the transient model's figures ---------------------------------------------------------------


def test_transient_curves_follow_the_run(draw: Any) -> None:
    _, drawn = draw(
        model="both",
        speeds=[22.0],
        supports=["free"],
        points=[[0.505, 0.0], [0.45, 0.02], [0.56, -0.03]],
        racket_speed=[5.0],
        stiffness_reading="tangent",
    )
    figure = drawn["transient_comparison_speed.png"]
    assert len(figure.axes) == 2  # one support: one column
    x = {float(v) for ax in figure.axes for line in ax.get_lines() for v in line.get_xdata()}
    assert 22.0 in x
    title = figure.get_suptitle()
    assert "racket 5 m/s" in title
    assert "tangent" in title
    histories = drawn["transient_histories.png"]
    assert any("racket 5 m/s" in t for t in _titles(histories))
    # the legend sits under the panels, not on the curves (it covered the tip's once)
    assert all(ax.get_legend() is None for ax in figure.axes)
    (legend,) = figure.legends
    labels = [t.get_text() for t in legend.get_texts()]
    assert len(labels) == len(set(labels))
    assert any(label.endswith("transient") for label in labels)


@pytest.mark.slow
def test_transient_histories_legend_leaves_the_curves_clear(draw: Any) -> None:
    """New-user trial (2026-11-27, ninth session): with eight modes the modal coordinates'
    legends held 16 entries each (each mode with each support) and covered the curves.  One
    legend under the figure names the largest modes and the supports' line styles and sums up
    the rest (every curve stays drawn, every number in transient_histories.csv)."""
    racket = rd.default_racket()
    setup = Setup(modal_model=rd.builtin_modal_model(racket, n_bending=7))
    result, drawn = draw(setup, model="both", speeds=[25.0], supports=["free", "pinned"], grid=2)
    histories = result.transient_histories
    n_modes = len(histories.mode_names)
    assert n_modes >= 8
    figure = drawn["transient_histories.png"]
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()  # type: ignore[attr-defined]
    modal = [ax for ax in figure.axes if ax.get_ylabel().startswith("modal coordinate")]
    assert len(modal) == 2
    (legend,) = figure.legends
    texts = [t.get_text() for t in legend.get_texts()]
    assert len(texts) <= 7
    assert texts[-2:] == ["free", "pinned"]
    for ax in modal:
        curves = [line for line in ax.get_lines() if len(line.get_xdata())]
        assert len(curves) == 2 * n_modes  # every mode of every support still drawn
        assert ax.get_legend() is None
        assert not legend.get_window_extent(renderer).overlaps(ax.get_window_extent(renderer))
    # the modes named are the largest; the others summed up with the largest of their peaks
    peaks = np.nanmax(np.abs(histories.modal_coordinates), axis=(0, 1))
    named = [k for k, name in enumerate(histories.mode_names) if name in texts]
    rest = [k for k in range(n_modes) if k not in named]
    assert named
    assert min(peaks[named]) >= max(peaks[rest])
    largest = 1e3 * max(peaks[rest])
    assert f"{len(rest)} more modes (largest peak {largest:.2g} mm·√kg)" in texts


# --- the printed headline ------------------------------------------------------------------------


def _centre_row(out: Path, support: str, speed: float) -> dict[str, float]:
    racket = rd.default_racket()
    centre = np.array(landmark_points(racket)["centre"])
    with (out / "impact.csv").open(newline="", encoding="utf-8") as handle:
        rows = [
            r
            for r in csv.DictReader(handle)
            if r["support"] == support and float(r["ball_speed_mps"]) == speed
        ]
    distance = [np.hypot(float(r["x_m"]) - centre[0], float(r["y_m"]) - centre[1]) for r in rows]
    row = rows[int(np.argmin(distance))]
    return {key: float(row[key]) for key in ("contact_time_s", "rebound_ratio", "peak_force_n")}


def test_predict_prints_headline_numbers_at_the_centre(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = ["predict", "--speed", "10,20", "--support", "free,pinned", "--grid", "5"]
    assert main([*argv, "--no-figures", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "compound ball+string law" not in out  # no fitted polynomial
    assert "face centre" in out
    for support in ("free", "pinned"):
        for speed in (10.0, 20.0):
            row = _centre_row(tmp_path, support, speed)
            assert f"{row['contact_time_s'] * 1e3:.2f}" in out
            assert f"{row['rebound_ratio']:.3f}" in out
            assert f"{row['peak_force_n']:.0f}" in out
    assert "flagged: " in out  # the count (none at the centre; the rim's rows since issue 22)


def test_predict_headline_counts_flagged_rows(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = ["predict", "--speed", "30", "--support", "pinned", "--grid", "9", "--no-figures"]
    logging.disable(logging.WARNING)
    try:
        assert main([*argv, "--out", str(tmp_path)]) == 0
    finally:
        logging.disable(logging.NOTSET)
    out = " ".join(capsys.readouterr().out.split())
    with (tmp_path / "impact.csv").open(newline="", encoding="utf-8") as handle:
        statuses = [r["status"] for r in csv.DictReader(handle)]
    flagged = sum(s != "ok" for s in statuses)
    assert flagged > 0
    assert f"flagged: {flagged} of {len(statuses)} rows" in out
    for reason in set(statuses) - {"ok"}:
        assert reason in out


def test_face_maps_leave_flagged_rows_out_of_every_quantity() -> None:
    """Issue 13: the vibration-energy map contoured the tip's flagged rows (≈ 5 J where the
    rebound ratio is 'no valid result'); every panel now leaves them out and counts them."""
    from racketdyn.plotting.primitives import plot_face_map

    racket = rd.default_racket()
    result = rd.predict(racket, rd.Ball(), racket.head.grid(9), [40.0], ["free"])
    flagged = result.status[:, 0, 0] != "ok"
    assert flagged.any(), "the test needs flagged rows"
    energy = result.vibration_energy[:, 0, 0]
    assert np.all(np.isnan(energy[flagged]))  # the result holds none (INVALIDATED)
    # a result with the flagged energies still filled (as before that rule): the map must
    # leave them out all the same, on its status
    from dataclasses import replace

    filled_in = rd.predict(racket, rd.Ball(), racket.head.grid(9), [20.0], ["free"])
    stale = replace(filled_in, status=result.status)
    object.__setattr__(stale, "vibration_energy", filled_in.vibration_energy * 100.0)
    figure, ax = plt.subplots()
    plot_face_map(stale, racket, "vibration_energy", 0, "free", ax=ax)
    labels = [line.get_label() for line in ax.get_lines()]
    assert f"no valid result at {int(flagged.sum())} points (see status)" in labels
    (filled,) = [c for c in ax.collections if hasattr(c, "levels")][:1]
    assert max(filled.levels) <= 1.2 * np.nanmax(stale.vibration_energy[~flagged, 0, 0])
    plt.close(figure)


def test_predict_headline_gives_the_outgoing_speed_of_a_serve(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """New-user trial (issue 13): a serve (ball nearly at rest, racket at 40 m/s) printed the
    rebound ratio only; what a serve is about, the speed the ball leaves at, was in impact.csv
    alone.  It is e v_ball + (1 + e) V (Cross), so about 1.3 × 40 m/s at the centre."""
    argv = ["predict", "--speed", "0", "--racket-speed", "40", "--support", "pinned"]
    assert main([*argv, "--grid", "5", "--no-figures", "--out", str(tmp_path)]) == 0
    out = " ".join(capsys.readouterr().out.split())
    row = _centre_row(tmp_path, "pinned", 0.0)
    outgoing = (1.0 + row["rebound_ratio"]) * 40.0
    assert 40.0 < outgoing < 80.0
    assert f"{outgoing:.1f}" in out


@pytest.mark.slow
def test_force_and_contact_time_count_their_own_curves_impacts(draw: Any) -> None:
    """New-user trial (2026-11-27, ninth session): Figs 11–12's legend said "86 of 276 impacts"
    flagged while the console said 142 of 276 rows of impact.csv: the figure counts its own
    sweep over ball speed (three points × its speeds × the supports), the same denominator by
    coincidence.  The legend says whose impacts it counts, with the curves' own count."""
    result, drawn = draw(speeds=[30.0], supports=["free", "pinned"], grid=5)
    figure = drawn["fig11_12_force_contact_time.png"]
    assert result.paper_figures is not None
    curves = result.paper_figures.speed_curves
    hatched = {
        patch.get_label()
        for ax in figure.axes
        for patch in ax.patches
        if patch.get_hatch() and not patch.get_label().startswith("_")
    }
    assert hatched, "the top's impacts are flagged (the frame takes over 30 %)"
    (label,) = hatched
    match = re.fullmatch(r"flagged, no valid value: (\d+) of these curves' (\d+) impacts.*", label)
    assert match, label
    flagged = np.asarray(curves.status)[: len(curves.labels)] != "ok"  # the three points
    assert (int(match[1]), int(match[2])) == (int(flagged.sum()), flagged.size)
    assert result.approximate is not None
    assert flagged.size != np.asarray(result.approximate.status).size  # not the run's rows
