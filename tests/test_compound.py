"""The compound ball–racket system (paper, section 3.2, Figs 8–9): analytic limits, the paper's
statements and measurement, and ``racketdyn compound``'s files."""

from __future__ import annotations

import csv
import json
import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from racketdyn.ball import Ball
from racketdyn.cli import main
from racketdyn.impact.approximate import predict
from racketdyn.impact.compound import (
    BALL_MODE_NAME,
    BallSpring,
    ball_spring,
    compound_modes,
    racket_modes,
    restitution_damping_ratio,
    stiffer_frame,
)
from racketdyn.impact.system import point_system
from racketdyn.io import default_racket
from racketdyn.racket_modal import modal_model_for
from racketdyn.workflows.compound import COMPOUND_COLUMNS

CENTRE = (0.505, 0.0)  # centre of the built-in racket's string bed, m
PAPER_BALL_MODE_HZ = 103.0  # Kawazoe, section 3.2 and Fig. 9b


@pytest.fixture(scope="module")
def racket():  # type: ignore[no-untyped-def]
    return default_racket()


@pytest.fixture(scope="module")
def spring(racket):  # type: ignore[no-untyped-def]
    return ball_spring(racket, Ball())


def _hz(stiffness: float, mass: float) -> float:
    return math.sqrt(stiffness / mass) / (2.0 * math.pi)


# --- analytic limits ------------------------------------------------------------------------
def test_infinitely_heavy_rigid_racket_gives_the_ball_on_its_spring(spring: BallSpring) -> None:
    m_b = Ball().mass_kg
    modes = compound_modes(point_system(math.inf), spring, m_b)
    assert modes.names == (BALL_MODE_NAME,)
    assert modes.ball_frequency == pytest.approx(_hz(spring.stiffness, m_b), rel=1e-10)
    assert modes.damping_ratio[0] == pytest.approx(spring.damping_ratio, rel=1e-10)


@pytest.mark.parametrize("support", ["free", "pinned"])
def test_rigid_racket_gives_the_two_body_frequency(racket, spring, support) -> None:  # type: ignore[no-untyped-def]
    """f = √(k (1/m_B + 1/M_r))/2π with M_r of eq 4 (computed by the approximate method)."""
    ball = Ball()
    m_r = float(
        predict(racket, ball, [CENTRE], [10.0], support, modal_model=None).reduced_mass[0, 0]
    )
    modes = racket_modes(racket, None, support, CENTRE, spring, ball)
    expected = math.sqrt(spring.stiffness * (1 / ball.mass_kg + 1 / m_r)) / (2 * math.pi)
    assert modes.ball_frequency == pytest.approx(expected, rel=1e-9)
    # the rigid body moves against the ball with momentum balance: u_B/w = −M_r/m_B
    assert modes.ball_to_frame_ratio[modes.ball_mode] == pytest.approx(
        -m_r / ball.mass_kg, rel=1e-9
    )


def test_a_flexible_mode_far_above_leaves_the_ball_mode(spring: BallSpring) -> None:
    """A mode at 20 kHz (200× the ball mode) moves it by about (f/f_k)² × its share: < 1e-4."""
    m_b, m_r = Ball().mass_kg, 0.174
    rigid = compound_modes(point_system(m_r), spring, m_b).ball_frequency
    flexible = compound_modes(point_system(m_r, [3.0], [2 * math.pi * 2e4], [0.005]), spring, m_b)
    assert flexible.ball_frequency == pytest.approx(rigid, rel=1e-4)
    assert flexible.frequency[-1] == pytest.approx(2e4, rel=1e-3)


def test_restitution_damping_ratio_gives_back_the_cor() -> None:
    for cor in (0.3, 0.83, 0.99):
        zeta = restitution_damping_ratio(cor)
        assert math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2)) == pytest.approx(cor, rel=1e-12)


def test_the_spring_is_ball_and_bed_in_series_at_small_amplitude(racket, spring) -> None:  # type: ignore[no-untyped-def]
    """Two springs in series: 1/k = 1/k_B + 1/k_G of the laws' linear terms (docs/develop.md:
    24.6 and 30.5 kN/m); the degree-5 fit and the 5 N preload stay within 1 %."""
    from racketdyn.contact import string_bed_law

    ball = Ball()
    k_b = float(ball.restoring_force.stiffness(0.0))
    k_g = float(string_bed_law(racket, ball).stiffness(0.0))
    assert spring.stiffness == pytest.approx(1 / (1 / k_b + 1 / k_g), rel=0.01)
    assert spring.preload_n == 5.0


def test_slow_contact_lasts_the_rigid_half_period(racket, spring) -> None:  # type: ignore[no-untyped-def]
    """Section 3.2's premise as a limit: the approximate method's contact time at a small
    speed tends to the undamped half period of the rigid compound system, π√(μ/k(0))."""
    ball = Ball()
    rigid = racket_modes(racket, None, "free", CENTRE, spring, ball)
    contact = float(
        predict(racket, ball, [CENTRE], [0.2], "free", modal_model=None).contact_time[0, 0, 0]
    )
    # the spring is taken at 5 N, the slow contact's at ≈ 0 N: 0.1 % apart (run.json records it)
    assert contact == pytest.approx(0.5 / rigid.ball_frequency, rel=3e-3)


# --- the paper's statements -----------------------------------------------------------------
@pytest.fixture(scope="module")
def built_in(racket, spring):  # type: ignore[no-untyped-def]
    model = modal_model_for(racket)
    return model, {
        s: racket_modes(racket, model, s, CENTRE, spring, Ball(), None) for s in ("free", "hand")
    }


def test_ball_mode_lies_below_the_two_node_mode_ball_against_frame(built_in) -> None:  # type: ignore[no-untyped-def]
    """Fig. 8a and 9b: a new mode below the 2-node bending mode, ball and frame in opposition."""
    _, modes = built_in
    for compound in modes.values():
        k = compound.ball_mode
        assert compound.names[k] == BALL_MODE_NAME
        assert compound.ball_frequency < compound.frequency_of("2-node bending")
        assert compound.ball_to_frame_ratio[k] < -1.0
        assert compound.ball_energy_share[k] > 0.5


def test_frame_modes_do_not_change_when_the_ball_is_added(racket, spring, built_in) -> None:  # type: ignore[no-untyped-def]
    """Paper: "the natural frequencies of the frame do not change even when the ball is
    attached" — within 1 % here for every flexible mode (the ball, 16 % of the racket's reduced
    mass at the centre, sits near the 2-node mode's node)."""
    model, modes = built_in
    for support, compound in modes.items():
        alone = racket_modes(racket, model, support, CENTRE, None, Ball(), None)
        for name in model.frame_modes.names:
            assert compound.frequency_of(name) == pytest.approx(alone.frequency_of(name), rel=0.01)


def test_four_times_stiffer_frame_moves_the_ball_mode_a_little(racket, spring, built_in) -> None:  # type: ignore[no-untyped-def]
    """Paper, section 3.2: with a frame about 4× as stiff (same mass) the ball's motion was the
    same.  Here the frame modes double (within 3 % held, the hand's springs stay) and the ball
    mode moves by under 2 % (measured +0.5 %)."""
    model, modes = built_in
    stiff = stiffer_frame(model, 4.0)
    for support, compound in modes.items():
        harder = racket_modes(racket, stiff, support, CENTRE, spring, Ball(), None)
        assert harder.ball_frequency == pytest.approx(compound.ball_frequency, rel=0.02)
        for name in model.frame_modes.names:
            ratio = harder.frequency_of(name) / compound.frequency_of(name)
            assert ratio == pytest.approx(2.0, rel=0.03)


# Inputs of the ball mode and their published spread (docs/references.md, docs/develop.md):
# the ball's one-sided stiffness from the ITF forward deformation 5.6–7.4 mm at 80.1 N (halved),
# the string bed's static stiffness 20–40 kN/m, the ball's mass 56.0–59.4 g (ITF).
BALL_STIFFNESS_N_PER_M = (80.1 / 3.7e-3, 80.1 / 2.8e-3)
BED_STIFFNESS_N_PER_M = (20e3, 40e3)
BALL_MASS_KG = (0.0560, 0.0594)


def _band(racket, model, spring) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    corners = []
    for k_b in BALL_STIFFNESS_N_PER_M:
        for k_g in BED_STIFFNESS_N_PER_M:
            for m_b in BALL_MASS_KG:
                trial = replace(spring, stiffness=1 / (1 / k_b + 1 / k_g))
                ball = replace(Ball(), mass_kg=m_b)
                corners.append(
                    racket_modes(racket, model, "free", CENTRE, trial, ball).ball_frequency
                )
    return min(corners), max(corners)


def test_ball_mode_band_from_the_inputs_spread(racket, spring, built_in) -> None:  # type: ignore[no-untyped-def]
    """The inputs' spread puts the ball mode within about ±12 % of the nominal 88.7 Hz."""
    model, modes = built_in
    low, high = _band(racket, model, spring)
    nominal = modes["free"].ball_frequency
    assert low < nominal < high
    assert 0.08 < (high - low) / (2 * nominal) < 0.16


@pytest.mark.xfail(
    strict=True,
    reason="the model's ball mode is 88.7 Hz, 14 % below the paper's 103 Hz; the inputs' spread "
    "(ball and bed stiffness at small amplitude, ball mass) reaches 77-99 Hz, so 103 Hz lies "
    "outside it: the small-amplitude compound stiffness would have to be ≈ 18.5 kN/m against "
    "13.5 kN/m from the built-in laws (docs/develop.md, 'The ball on the strings')",
)
def test_built_in_ball_mode_near_the_papers_103_hz(racket, spring, built_in) -> None:  # type: ignore[no-untyped-def]
    """Within the inputs' spread (the tolerance): the band of
    :func:`test_ball_mode_band_from_the_inputs_spread` must hold 103 Hz."""
    model, _ = built_in
    low, high = _band(racket, model, spring)
    assert low <= PAPER_BALL_MODE_HZ <= high


def test_receptance_is_reciprocal(racket, spring) -> None:  # type: ignore[no-untyped-def]
    model = modal_model_for(racket)
    for support in ("free", "hand"):
        system = racket_modes(
            racket, model, support, CENTRE, spring, Ball(), None, [(0.465, 0.0), (0.31, 0.0)]
        )
        f = np.array([50.0, 88.0, 130.0, 400.0])
        assert np.allclose(system.receptance(f, 1, 2), system.receptance(f, 2, 1), rtol=1e-9)


def test_impulse_response_rings_at_the_modes(racket, spring) -> None:  # type: ignore[no-untyped-def]
    """The neck's response to a hammer impulse, Fourier-transformed, peaks at the ball mode or
    the 2-node mode (the two below 300 Hz), and starts with the impulse's acceleration
    r_nᵀ M⁻¹ (−C M⁻¹ r_h) — zero displacement, so no spring force at t = 0."""
    system = racket_modes(
        racket, modal_model_for(racket), "free", CENTRE, spring, Ball(), None,
        [(0.465, 0.0), (0.31, 0.0)],
    )  # fmt: skip
    times = np.arange(0.0, 1.0, 2e-4)
    response = system.impulse_acceleration(times, 1, 2)
    spectrum = np.abs(np.fft.rfft(response * np.hanning(times.size)))
    freq = np.fft.rfftfreq(times.size, 2e-4)
    band = (freq > 60) & (freq < 300)
    peak = freq[band][np.argmax(spectrum[band])]
    targets = [system.ball_frequency, system.frequency_of("2-node bending")]
    assert min(abs(peak - t) for t in targets) < 2.0
    m_inv = np.linalg.inv(system.mass)
    start = -system.rows[2] @ m_inv @ system.damping @ m_inv @ system.rows[1]
    assert response[0] == pytest.approx(start, rel=1e-9)


# --- the command ----------------------------------------------------------------------------
def test_compound_command_writes_its_files(tmp_path: Path) -> None:
    out = tmp_path / "compound"
    assert main(["compound", "--out", str(out)]) == 0
    with (out / "compound.csv").open(newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert tuple(rows[0]) == COMPOUND_COLUMNS
    assert {r["support"] for r in rows} == {"free", "hand"}
    ball_rows = [r for r in rows if r["mode"] == BALL_MODE_NAME]
    assert len(ball_rows) == 2
    for row in ball_rows:
        half = float(row["half_period_s"])
        assert half == pytest.approx(0.5 / float(row["frequency_hz"]), rel=0.01)
        times = [float(row[c]) for c in COMPOUND_COLUMNS[-3:]]
        assert times == sorted(times, reverse=True)  # contact time falls with speed
        # half period against contact time: within 15 % at 5–20 m/s (measured 2–12 %)
        assert all(t == pytest.approx(half, rel=0.15) for t in times)
    others = [r for r in rows if r["mode"] != BALL_MODE_NAME]
    assert all(r["half_period_s"] == "" for r in others)
    record = json.loads((out / "run.json").read_text(encoding="utf-8"))
    assert record["ball_spring"]["preload_n"] == 5.0
    assert {c["support"] for c in record["frame_stiffness_check"]} == {"free", "hand"}
    assert all(abs(c["ball_mode_change_percent"]) < 2 for c in record["frame_stiffness_check"])
    assert set(record["frame_mode_shifts"]) == {"free", "hand"}
    for name in ("compound.csv", "compound_response.png", "compound_frf.png", "run.json"):
        assert name in record["outputs"]
        assert (out / name).is_file()


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--point=0.9,0"], "--point"),
        (["--point", "0.5"], "--point"),
        (["--support", "moon"], "--support"),
        (["--preload", "-1"], "preload"),
    ],
)
def test_compound_bad_input_is_one_line(tmp_path: Path, capsys, argv, words) -> None:  # type: ignore[no-untyped-def]
    assert main(["compound", *argv, "--no-figures", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert words in err
    assert "\n" not in err


# --- the virtual rig with the ball (racketdyn rig --ball-at) --------------------------------
def test_rig_ball_adds_one_mode_and_keeps_the_frame_modes() -> None:
    """The rig's ball: one new mode below the 2-node mode with the ball against the strings;
    the free racket's frame modes stay within 3 % (ball near the 2-node mode's node; the
    3-node and 4-node modes rise a little, the ball acting above its own resonance)."""
    from racketdyn.rig import rig_model
    from racketdyn.rig.ball import BALL_MODE_NAME as RIG_BALL
    from racketdyn.rig.ball import ball_on_strings

    racket = default_racket()
    bare = rig_model(racket, "free")
    ball = Ball()
    with_ball = ball_on_strings(bare, CENTRE, ball.mass_kg, 24.65e3, 0.059)
    assert with_ball.n_modes == bare.n_modes + 1
    k = with_ball.names.index(RIG_BALL)
    assert with_ball.frequency[k] < with_ball.frequency[with_ball.names.index("2-node bending")]
    # Fig. 8a: ball and frame move against each other (the frame's w + θy under the ball)
    row = with_ball.displacement_rows([CENTRE])[0]
    row[with_ball.dofs["membrane"]] = 0.0
    assert with_ball.modes[-1, k] * (row @ with_ball.modes[:, k]) < 0
    for name in ("2-node bending", "3-node bending", "2-node twisting"):
        f0 = bare.frequency[bare.names.index(name)]
        assert with_ball.frequency[with_ball.names.index(name)] == pytest.approx(f0, rel=0.03)
    # mass-normalised with the ball's mass in M
    assert np.allclose(
        with_ball.modes.T @ with_ball.mass @ with_ball.modes, np.eye(with_ball.n_modes), atol=1e-8
    )


def test_rig_with_ball_round_trip_identifies_the_ball_mode(tmp_path: Path) -> None:
    """rig --ball-at → frf → identify: the ball mode within 0.5 % of the rig's truth (measured
    0.04 %: the records are the truth's modes plus noise; 0.5 % is the issue's bound)."""
    from racketdyn.modal import ModalModel
    from racketdyn.rig.ball import BALL_MODE_NAME as RIG_BALL
    from racketdyn.workflows import run_frf, run_identify, run_rig

    rig = run_rig(tmp_path / "rig", ball_at=CENTRE, averages=3, support="free")
    assert rig.ball is not None
    truth = ModalModel.read_json(tmp_path / "rig" / "modal_truth_free.json")
    f_true = float(truth.frequency[truth.names.index(RIG_BALL)])
    record = json.loads((tmp_path / "rig" / "run.json").read_text(encoding="utf-8"))
    assert record["ball_on_strings"]["location_m"] == list(CENTRE)
    run_frf(tmp_path / "rig" / "hammer_free.uff", tmp_path / "frf", exponential_window_s=0.1)
    found = run_identify(tmp_path / "frf" / "frfs.uff", tmp_path / "id", band_hz=(40.0, 850.0))
    assert found.identification is not None
    frequencies = np.asarray(found.identification.model.frequency)
    nearest = float(frequencies[np.argmin(np.abs(frequencies - f_true))])
    assert nearest == pytest.approx(f_true, rel=0.005)


def test_rig_ball_off_the_strings_is_one_line(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    assert main(["rig", "--ball-at", "0.2,0", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert "--ball-at" in err
    assert "\n" not in err


def test_report_section_states_the_papers_claims_in_words(tmp_path: Path) -> None:
    from racketdyn.report.folder import RunFolder
    from racketdyn.report.page import render_section
    from racketdyn.report.sections import compound as section

    assert main(["compound", "--out", str(tmp_path / "compound")]) == 0
    data = section.gather(RunFolder.scan(tmp_path))
    assert data is not None
    text = " ".join(data["statements"])
    with (tmp_path / "compound" / "compound.csv").open(encoding="utf-8") as file:
        rows = list(csv.DictReader(file))
    ball = next(r for r in rows if r["support"] == "free" and r["mode"] == "ball on the strings")
    frequency = float(ball["frequency_hz"])
    miss = round(100 * (frequency / 103.0 - 1))
    assert f"at {frequency:.1f} Hz ({miss:+d} %)" in text  # the miss against the paper, stated
    assert -20 < miss < -5  # docs/develop.md "The ball on the strings": 14 % below, not tuned
    times = [float(ball[f"contact_time_{v}_s"]) for v in (5, 10, 20)]
    worst = max(abs(t / float(ball["half_period_s"]) - 1.0) for t in times)
    assert f"within {100 * worst:.0f} %" in text  # half period against the contact time, 5–20 m/s
    assert worst < 0.15  # the paper: half the ball mode's period is the contact time
    assert "ball mode moves by 0.5 %" in text
    assert [row[0] for row in data["times"]] == ["free", "hand"]
    html = render_section("compound", data)
    assert "Half period against contact time" in html
    assert "A frame four times as stiff" in html
    words = re.sub(r"data:image/png;base64,[A-Za-z0-9+/=]+", "", str(html))
    assert not re.search(r"\bnan\b", words, re.IGNORECASE)
    assert section.gather(RunFolder.scan(tmp_path / "compound" / "nothing")) is None


def test_ball_mode_shape_is_the_ratio_at_the_ball(tmp_path: Path) -> None:
    """Fig. 8a's data: the frame's displacement under the ball (ball = 1) is 1 / (ball to frame
    ratio) of compound.csv, and the frame moves against the ball."""
    from racketdyn.workflows import run_compound

    result = run_compound(tmp_path / "c", supports=("free",))
    frame, ball = result.ball_shape["free"]
    modes = result.modes["free"]
    under = float(np.interp(result.location[0], result.axis_x, frame))
    assert ball == 1.0
    assert under == pytest.approx(1.0 / modes.ball_to_frame_ratio[modes.ball_mode], rel=0.02)
    assert under < 0
