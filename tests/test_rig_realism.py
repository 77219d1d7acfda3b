"""The virtual rig as real as a lab (issue 12, "The virtual rig must be realistic enough").

Noise given as a signal-to-noise ratio, a pre-trigger with t = 0 at the record's start, the
accelerometer in −z (UFF direction −3), no driving point: each round-trips through
``frf`` → ``identify`` against the rig's modal truth.

Tolerances, from what the noise allows (measured on this seed, loaded machine irrelevant):
with 40 dB on the response and 50 dB on the force the coherence's median in the band falls to
≈ 0.96 (1.000 without noise); the LSCF frequencies stay within 0.03 % of the truth (tests:
0.05 %, the issue's figure for noisy data) and the damping ratios within 6 % (tests: 10 %),
where the noise-free rig gives ≤ 0.5 %.  That holds for the modes the accelerometer sees (at
10 % of their largest amplitude or more, the rule of ``tests/test_identify.py``).  The
string-bed mode, which it barely sees (9 % at the tip of the few-point layout), comes back
0.12 % off in frequency and 14 % in damping on this seed on the rig's frame shape (issue 22,
sixth session; 0.06–0.12 % and 4–16 % on seeds 3–5; within 0.03 % and 6 % at 772 Hz on the
smooth frame): it is held to 0.2 % and 20 %.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import racketdyn as rd
from pull_tension import pull_tension_racket
from racketdyn.io import read_hammer_uff
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.modal.identify import identify
from racketdyn.modal.mac import mac
from racketdyn.modal.model import ModalModel
from racketdyn.rig import (
    RigModel,
    SensorNoise,
    accelerometer_index,
    hammer_points,
    rig_model,
    simulate_hammer_test,
)
from racketdyn.workflows.setup import Setup

BAND = (40.0, 850.0)
SNR = {"force_snr_db": 50.0, "response_snr_db": 40.0}


@pytest.fixture(scope="module")
def free_rig() -> RigModel:
    return rig_model(pull_tension_racket(), "free")


def _few_points(rig: RigModel) -> tuple[np.ndarray, tuple[int, ...], int]:
    locations, nodes = hammer_points(rig.racket, n_frame=10, n_strings=8)
    return locations, nodes, accelerometer_index(rig.racket, locations)


def _errors(
    model: ModalModel, truth: ModalModel, kinds: tuple[str, ...] | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Relative frequency and damping errors of the truth's flexible modes in the band found
    (of the given kinds only, if given)."""
    f_true = truth.frequency
    wanted = np.flatnonzero(
        (f_true > BAND[0])
        & (f_true < BAND[1])
        & np.array([kinds is None or kind in kinds for kind in truth.kinds], dtype=bool)
    )
    df, dz = [], []
    for k in wanted:
        j = int(np.argmin(np.abs(model.frequency - f_true[k])))
        if abs(model.frequency[j] / f_true[k] - 1) < 0.01:  # found (twisting: not excited)
            df.append(model.frequency[j] / f_true[k] - 1)
            dz.append(model.damping_ratio[j] / truth.damping_ratio[k] - 1)
    return np.abs(df), np.abs(dz)


def test_noise_given_as_snr_is_that_snr(free_rig: RigModel) -> None:
    locations, nodes, ref = _few_points(free_rig)
    records = simulate_hammer_test(
        free_rig,
        locations[:3],
        nodes[:3],
        tuple(locations[ref]),
        nodes[ref],
        seed=2,
        noise=SensorNoise(**SNR),
    )
    before = records.pretrigger_samples - 5  # the pre-trigger holds noise only
    for channel, snr in ((records.force, 50.0), (records.response, 40.0)):
        data = np.concatenate(channel)
        noise = np.sqrt(np.mean(data[:, :before] ** 2, axis=1))
        measured = 20 * np.log10(np.max(np.abs(data), axis=1) / noise)
        assert np.median(measured) == pytest.approx(snr, abs=1.0)


@pytest.mark.slow
def test_snr_noise_lowers_coherence_and_damping_is_found_within_its_tolerance(
    free_rig: RigModel,
) -> None:
    locations, nodes, ref = _few_points(free_rig)
    truth = free_rig.modal_truth(locations, max_frequency_hz=BAND[1])
    found = {}
    for label, noise in (("floor", SensorNoise()), ("snr", SensorNoise(**SNR))):
        records = simulate_hammer_test(
            free_rig, locations, nodes, tuple(locations[ref]), nodes[ref], seed=3, noise=noise
        )
        estimate = estimate_frfs(records, exponential_window_s=0.1)
        frfs = estimate.frfs
        assert frfs is not None
        assert frfs.coherence is not None
        band = (frfs.frequency > BAND[0]) & (frfs.frequency < BAND[1])
        found[label] = (np.median(frfs.coherence[:, band]), identify(frfs, BAND).model)
    assert found["floor"][0] > 0.999  # the old rig: coherence 1.000
    assert 0.8 < found["snr"][0] < 0.99
    _df_floor, dz_floor = _errors(found["floor"][1], truth)
    df, dz = _errors(found["snr"][1], truth)
    assert df.size >= 4
    # the accelerometer (the tip) sees the frame's modes; the string bed at 9 % of its largest
    ref_share = np.abs(truth.mode_shapes[ref]) / np.abs(truth.mode_shapes).max(axis=0)
    assert np.all(ref_share[np.array(truth.kinds) == "string-bed"] < 0.1)
    df_frame, dz_frame = _errors(found["snr"][1], truth, ("bending", "twisting"))
    assert df_frame.size >= 3
    assert np.all(df_frame < 5e-4)
    assert np.all(dz_frame < 0.10)
    df_bed, dz_bed = _errors(found["snr"][1], truth, ("string-bed",))
    assert df_bed.size == 1
    assert np.all(df_bed < 2e-3)
    assert np.all(dz_bed < 0.20)
    assert dz.max() > 2 * dz_floor.max()  # the damping is no longer recovered exactly


@pytest.mark.slow
def test_realistic_rig_round_trips_through_frf_and_identify(tmp_path: Path) -> None:
    # −z accelerometer, t = 0 at the record's start (pulse 10 ms in), no driving point, noise
    from racketdyn.workflows.frf import run_frf
    from racketdyn.workflows.rig import RigOptions, run_rig

    rig = run_rig(
        tmp_path / "rig",
        Setup(racket=pull_tension_racket()),
        RigOptions(
            averages=4,
            time_zero="record",
            response_direction=-3,
            driving_point=False,
            binary=False,  # the text form, read below for its direction codes (binary by default)
            **SNR,
        ),
    )
    path = tmp_path / "rig" / "hammer_free.uff"
    text = path.read_text()
    assert "  -3" in text  # the response records carry direction −3
    back = read_hammer_uff(path)
    assert back.pretrigger_s == 0.0  # t = 0 at the first sample ...
    assert back.reference_node not in back.nodes  # ... and no driving point
    # the −3 code is honoured: what is read is the response along +z, as simulated
    np.testing.assert_allclose(back.response[0], rig.records["free"].response[0], rtol=1e-9)
    inputs = json.loads((tmp_path / "rig" / "run.json").read_text())
    assert inputs["accelerometer_direction"] == -3
    assert inputs["driving_point"] is False

    frf = run_frf(path, tmp_path / "frf", exponential_window_s=0.1)
    assert frf.estimate is not None
    assert frf.estimate.frfs is not None
    assert not frf.estimate.rejected_points  # the pulse 10 ms in is found, no trigger rejects
    found = identify(frf.estimate.frfs, BAND).model
    truth = ModalModel.read_json(tmp_path / "rig" / "modal_truth_free.json")
    df, dz = _errors(found, truth)
    assert df.size >= 5
    assert np.all(df < 5e-4)
    assert np.all(dz < 0.10)
    assert found.scaling == "unscaled"  # no driving point: shapes unscaled, said so
    strong = [k for k in range(found.n_modes) if found.frequency[k] < 700]
    shapes_truth = truth.mode_shapes_at(frf.estimate.frfs.locations)
    for k in strong:
        j = int(np.argmin(np.abs(truth.frequency - found.frequency[k])))
        assert mac(found.mode_shapes[:, [k]], shapes_truth[:, [j]])[0, 0] > 0.95


@pytest.mark.slow
def test_a_racket_measured_in_the_lab_x_z_plane_round_trips(tmp_path: Path) -> None:
    # --lab-plane xz: points (x, 0, y), normal along y (codes ±2).  frf reads the records
    # without coordinates (rather none than points squashed onto x–y: z dropped silently
    # put every point on the axis); identify takes the (x, y, z) points from the rig's file
    # with --geometry and maps them onto the face.
    import pyuff

    from racketdyn.workflows.frf import run_frf
    from racketdyn.workflows.identify import IdentifyOptions, identify_file
    from racketdyn.workflows.rig import RigOptions, run_rig

    rig = run_rig(tmp_path / "rig", options=RigOptions(averages=3, lab_plane="xz"))
    path = tmp_path / "rig" / "hammer_free.uff"
    geometry = pyuff.UFF(str(path)).read_sets(0)  # data set 15 comes first
    assert np.ptp(geometry["z"]) > 0.2
    assert np.all(np.asarray(geometry["y"]) == 0.0)
    codes = {(s["rsp_dir"], s["ref_dir"]) for s in pyuff.UFF(str(path)).read_sets([1, 2])}
    assert codes == {(2, 2)}  # force and response both along the lab's y, the face normal
    frf = run_frf(path, tmp_path / "frf", exponential_window_s=0.1)
    assert frf.records_metadata["three_d_geometry"] == str(path)
    assert frf.estimate is not None
    assert frf.estimate.frfs is not None
    assert not frf.estimate.frfs.has_locations
    found = identify_file(
        tmp_path / "frf" / "frfs.uff",
        rd.default_racket(),
        "free",
        IdentifyOptions(geometry=path, band_hz=(40.0, 850.0)),
        racket_given=False,
    )
    model = found.model
    assert found.frfs.locations.shape[1] == 3  # the lab's (x, y, z) read ...
    assert model.locations.shape[1] == 2  # ... and mapped onto the face
    assert "2-node bending" in model.names  # named: the points are a racket's
    truth = ModalModel.read_json(tmp_path / "rig" / "modal_truth_free.json")
    df, _ = _errors(model, truth)
    assert df.size >= 5
    assert np.all(df < 5e-4)
    points = rig.records["free"].locations
    np.testing.assert_allclose(np.sort(model.locations[:, 0]), np.sort(points[:, 0]), atol=1e-3)


@pytest.mark.slow
def test_a_roving_accelerometer_test_round_trips(tmp_path: Path) -> None:
    # --layout roving-accelerometer: the hammer on the reference node (its 0.4 ms frame pulse
    # for every hit), the accelerometer moved over the points; the file says so (force records
    # all at one node, response records at the points, a running load case).  By reciprocity
    # frf gives the FRFs of the roving-hammer test, and identify the same modes.
    import pyuff

    from racketdyn.workflows.frf import run_frf
    from racketdyn.workflows.rig import RigOptions, run_rig

    rig = run_rig(tmp_path / "rig", options=RigOptions(averages=2, layout="roving accelerometer"))
    records = rig.records["free"]
    assert set(records.metadata["pulse_duration_s"]) == {0.4e-3}  # every hit on the hoop
    path = tmp_path / "rig" / "hammer_free.uff"
    sets = pyuff.UFF(str(path)).read_sets()[1:]
    forces = [s for s in sets if s["ordinate_spec_data_type"] == 13]
    responses = [s for s in sets if s["ordinate_spec_data_type"] != 13]
    assert {s["rsp_node"] for s in forces} == {rig.reference_node}
    assert {s["rsp_node"] for s in responses} == set(records.nodes)
    assert len({s["load_case_id"] for s in forces}) == len(forces)
    back = read_hammer_uff(path)
    assert back.metadata["layout"] == "roving accelerometer"
    assert back.reference_node == rig.reference_node
    assert back.nodes == tuple(sorted(records.nodes))
    frf = run_frf(path, tmp_path / "frf", exponential_window_s=0.1)
    assert frf.estimate is not None
    assert frf.estimate.frfs is not None
    found = identify(frf.estimate.frfs, BAND).model
    assert found.scaling == "mass"  # the hammer node is struck with the sensor on it too
    truth = ModalModel.read_json(tmp_path / "rig" / "modal_truth_free.json")
    df, dz = _errors(found, truth)
    assert df.size >= 5
    assert np.all(df < 5e-4)
    assert np.all(dz < 0.10)
