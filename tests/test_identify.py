"""Identification end to end on the virtual rig: records → FRFs → modal model → prediction."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import racketdyn as rd
from costly import costly
from pull_tension import pull_tension_racket
from racketdyn.cli import main
from racketdyn.io import write_frf_uff
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.modal.identify import identify
from racketdyn.modal.residues import mac
from racketdyn.racket_modal.identify import identify_racket, name_racket_modes
from racketdyn.rig import (
    Acquisition,
    accelerometer_index,
    hammer_points,
    rig_model,
    simulate_hammer_test,
)

BAND = (40.0, 850.0)


@pytest.fixture(scope="module", params=["free", "hand"])
@costly
def case(request: pytest.FixtureRequest) -> dict:
    racket = pull_tension_racket()
    rig = rig_model(racket, request.param)
    locations, nodes = hammer_points(racket)
    reference = accelerometer_index(racket, locations)  # the CLI's, on the hoop
    records = simulate_hammer_test(
        rig, locations, nodes, tuple(locations[reference]), nodes[reference], seed=2
    )
    frfs = estimate_frfs(records, exponential_window_s=0.1).frfs
    truth = rig.modal_truth(locations, max_frequency_hz=BAND[1])
    truth = truth.select([k for k, f in enumerate(truth.frequency) if f > BAND[0]])
    return {
        "racket": racket,
        "frfs": frfs,
        "truth": truth,
        "result": identify_racket(frfs, racket, BAND, support=request.param),
    }


@pytest.mark.slow
def test_modes_match_the_truth(case) -> None:
    # Issue 4: frequency within 0.2 %, damping within 10 % (the 0.1 s exponential window taken
    # off), MAC ≥ 0.98, mass-normalised shapes within 5 %, names as the rig's.  Every truth mode
    # whose peak stands out is found; the hand's 3- and 4-node twisting (ζ ≈ 6–8 %) may be
    # missed — they are buried between their neighbours — and the hand's 2-node twisting
    # (ζ 3.3 %) then carries some of the missed mode: 10 % on its shape.  The scale of a mode
    # the accelerometer barely sees (the string bed: 3–5 % of its largest amplitude at the
    # driving point, flagged by a warning) is not held to the 5 %.
    model, truth = case["result"].model, case["truth"]
    found = 0
    for k in range(truth.n_modes):
        j = int(np.argmin(np.abs(model.frequency - truth.frequency[k])))
        if abs(model.frequency[j] / truth.frequency[k] - 1) > 0.002:
            assert truth.damping_ratio[k] > 0.05, f"{truth.names[k]} not found"
            continue
        found += 1
        assert model.damping_ratio[j] == pytest.approx(truth.damping_ratio[k], rel=0.1)
        shape, expected = model.mode_shapes[:, j], truth.mode_shapes[:, k]
        assert mac(shape[:, None], expected[:, None])[0, 0] > 0.98
        sign = np.sign(shape @ expected)
        error = np.linalg.norm(sign * shape - expected) / np.linalg.norm(expected)
        seen = abs(expected[case["frfs"].driving_point]) > 0.1 * np.abs(expected).max()
        if seen:
            assert error < (0.10 if truth.damping_ratio[k] > 0.02 else 0.05), truth.names[k]
        assert model.names[j] == truth.names[k]
    assert found == model.n_modes  # no spurious mode


@pytest.mark.usefixtures("strings_only")  # numbers at points by the hoop
def test_identified_model_drives_the_prediction(case) -> None:
    # The identified model in eq 12 gives the rebound the rig's own modes give (within 0.01).
    racket = case["racket"]
    points = racket.head.grid(5)
    identified = rd.predict(racket, rd.Ball(), points, [20.0], modal_model=case["result"].model)
    true = rd.predict(racket, rd.Ball(), points, [20.0], modal_model=case["truth"])
    ok = (identified.status == "ok") & (true.status == "ok")
    assert ok.mean() > 0.6  # the rim beyond the approximate method since issue 22 (over 30 %)
    np.testing.assert_allclose(identified.rebound_ratio[ok], true.rebound_ratio[ok], atol=0.01)


def test_racket_names_are_a_step_on_the_general_identification(case) -> None:
    # identify() names modes neutrally; naming them the racket way changes nothing else
    general = identify(case["frfs"], BAND, support=case["result"].model.support)
    assert all(kind == "unknown" for kind in general.model.kinds)
    assert general.model.names[0] == f"mode 1 ({general.model.frequency[0]:.1f} Hz)"
    named = name_racket_modes(general, case["racket"])
    assert named.model.names == case["result"].model.names
    assert named.model.kinds == case["result"].model.kinds
    np.testing.assert_array_equal(named.model.frequency, case["result"].model.frequency)
    np.testing.assert_array_equal(named.model.mode_shapes, case["result"].model.mode_shapes)
    assert named.stabilisation is general.stabilisation


def test_band_without_modes_is_a_clear_error(case) -> None:
    # below the first bending mode, above the hand's pitch on the palm against the arm (53.8 Hz,
    # ζ 9.5 %: a mode of the held racket since the rig holds it with racketdyn.hand.Hand), only
    # the tails of the sponge's or hand's modes: nothing stable
    with pytest.raises(rd.InputError, match="no mode found"):
        identify(case["frfs"], (62.0, 105.0), max_order=8)
    with pytest.raises(rd.InputError, match="band"):
        identify_racket(case["frfs"], case["racket"].head, (1500.0, 1510.0))


@pytest.mark.slow
def test_identify_and_compare_commands(tmp_path: Path, racket: rd.Racket) -> None:
    racket = rd.default_racket()
    locations, nodes = hammer_points(racket, n_frame=12, n_strings=20)
    files = []
    four = Acquisition(n_averages=4)
    for support in ("free", "hand"):
        rig = rig_model(racket, support)
        records = simulate_hammer_test(
            rig, locations, nodes, tuple(locations[5]), nodes[5], acquisition=four, seed=3
        )
        path = tmp_path / f"{support}.uff"
        write_frf_uff(estimate_frfs(records, exponential_window_s=0.1).frfs, path)
        files.append(str(path))
    out = tmp_path / "identify"
    assert main(["identify", files[0], "--band", "40,850", "--out", str(out)]) == 0
    lines = (out / "modes.csv").read_text().splitlines()
    assert lines[0].startswith("mode,frequency_hz,damping_ratio,name")
    assert "2-node bending" in lines[1]
    model = rd.ModalModel.read_json(out / "modal_model.json")
    assert model.frequency[0] == pytest.approx(racket.first_bending_hz, rel=2e-3)
    for name in (
        "stabilisation.png",
        "fig4_mode_shapes.png",
        "fig5_node_lines.png",
        "fig6_nodes.png",
        "modes.uff",
        "run.json",
    ):
        assert (out / name).stat().st_size > 1000
    compared = tmp_path / "compare"
    assert main(["compare", *files, "--band", "40,850", "--out", str(compared)]) == 0
    table = (compared / "comparison.csv").read_text().splitlines()
    assert table[1].startswith("2-node bending")
    shift = float(table[1].split(",")[3])
    assert -10 < shift < 0  # slightly lower when held
    # pure data: pandas reads one row per mode pair and one per mode left without a pair
    # (its partner's columns empty, a note), the nodes are in run.json (issue 13)
    record = json.loads((compared / "run.json").read_text())
    pairs = pd.read_csv(compared / "comparison.csv")
    paired = pairs["mac"].notna()
    assert len(pairs) == len(table) - 1
    assert len(pairs) + paired.sum() == len(record["modes_free"]) + len(record["modes_hand"])
    assert pairs["mode"].iloc[0] == "2-node bending"
    assert pairs["frequency_free_hz"].dtype == float
    assert (pairs["note"].isna() == paired).all()
    assert not any(line.startswith("#") for line in table)
    nodes = record["first_mode_nodes_m"]
    assert set(nodes) == {"free", "hand"}
    for support in ("free", "hand"):  # a 2-node bending mode: one node near the throat,
        assert len(nodes[support]) == 2  # one near the face centre (m from the butt)
        assert 0.05 < nodes[support][0] < 0.25 < 0.4 < nodes[support][1] < 0.6
    assert (compared / "fig15_identified.png").stat().st_size > 10_000
    # every file listed once in run.json (the table is the workflow's, the figures the hook's)
    outputs = json.loads((compared / "run.json").read_text())["outputs"]
    assert len(outputs) == len(set(outputs))
    assert "comparison.csv" in outputs


def test_compare_names_hand_modes_after_their_free_pairs() -> None:
    """New-user trial (issue 13): the hand-held rig of a 270 g racket damps its 3- and 4-node
    twisting modes (ζ 10 % and 6 %) out of the identification, so the hand's twisting modes,
    numbered in order of frequency, were named two nodes short: its 1065 Hz mode "3-node
    twisting" in modes_hand.csv beside the free racket's 658 Hz "3-node twisting" (MAC pair:
    the free 1107 Hz "5-node twisting").  compare now names a hand mode after its MAC pair."""
    from racketdyn.modal.model import ModalModel
    from racketdyn.workflows.identify import name_after_pairs

    rng = np.random.default_rng(4)
    points = np.column_stack([np.linspace(0.1, 0.65, 12), np.tile([-0.05, 0.05], 6)])
    shapes, _ = np.linalg.qr(rng.normal(size=(12, 5)))
    free = ModalModel(
        np.array([135.0, 361.0, 363.0, 658.0, 1107.0]),
        np.full(5, 0.005),
        points,
        shapes,
        (
            "2-node bending",
            "2-node twisting",
            "3-node bending",
            "3-node twisting",
            "4-node twisting",
        ),
        ("bending", "twisting", "bending", "twisting", "twisting"),
    )
    keep = [0, 1, 2, 4]  # the hand lost the 658 Hz twisting mode
    hand = ModalModel(
        np.array([130.0, 352.0, 346.0, 1065.0]),
        np.array([0.013, 0.05, 0.009, 0.013]),
        points,
        shapes[:, keep] * 1.1,
        ("2-node bending", "2-node twisting", "3-node bending", "3-node twisting"),
        ("bending", "twisting", "bending", "twisting"),
    )
    named = name_after_pairs(free, hand)
    assert named.names == ("2-node bending", "2-node twisting", "3-node bending", "4-node twisting")
    assert named.kinds == hand.kinds
    np.testing.assert_array_equal(named.frequency, hand.frequency)
