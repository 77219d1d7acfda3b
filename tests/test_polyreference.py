"""The poly-reference LSCF against a modal model it must recover (racketdyn.modal.polyreference).

Two modes 0.3 % apart (100.0 and 100.3 Hz, ζ 0.4 %: half-power width 0.8 Hz, so one peak)
whose shapes over the hammer points nearly agree (MAC 0.90) while two accelerometers off the
points see them differently (participations (1, 0.2) and (0.2, 1)), plus a third mode at
160 Hz; analytic accelerances of mass-normalised real modes, ``A_ojk = ψ_ok φ_jk``.  Each
single-reference identification reads the pair as one peak (the "one peak" rule of
``select_poles``: neighbours within their half-power width whose shapes agree); the pLSCF, whose
residues carry the participations too, keeps both.
"""

from __future__ import annotations

import numpy as np
import pytest

import racketdyn as rd
from costly import costly
from racketdyn.errors import InputError
from racketdyn.measurement.records import FrfReferences, FrfSet
from racketdyn.modal.identify import Identification, identify
from racketdyn.modal.mac import mac
from racketdyn.modal.model import ModalModel
from racketdyn.modal.poles import select_poles, stabilisation
from racketdyn.modal.polyreference import poly_stabilisation
from racketdyn.modal.residues import fit_modal_constants
from racketdyn.rig import hammer_points, rig_model

FREQUENCY_HZ = np.array([100.0, 100.3, 160.0])
DAMPING = np.array([0.004, 0.004, 0.004])
X = np.linspace(0.0, 1.0, 12)
SHAPES = np.stack(
    [np.sin(np.pi * X), np.sin(np.pi * X) + 0.3 * np.cos(np.pi * X), np.sin(2 * np.pi * X + 0.4)],
    axis=1,
)  # (points, modes)
SEEN = np.array([[1.0, 0.2, 0.5], [0.2, 1.0, -0.5]])  # (reference, mode)
LINES = np.arange(60.0, 200.0 + 1e-9, 0.05)
BAND = (70.0, 190.0)


def _references(noise: float = 0.0, seed: int = 0) -> FrfReferences:
    """The model's accelerances against each reference, with complex noise of ``noise`` × each
    FRF's rms per line."""
    rng = np.random.default_rng(seed)
    omega, omega_n = 2 * np.pi * LINES, 2 * np.pi * FREQUENCY_HZ
    sets = []
    for j, seen in enumerate(SEEN):
        modal = 1 / (omega_n[:, None] ** 2 - omega**2 + 2j * (DAMPING * omega_n)[:, None] * omega)
        values = -(omega**2) * ((SHAPES * seen) @ modal)
        rms = np.sqrt(np.mean(np.abs(values) ** 2, axis=1, keepdims=True))
        values = values + noise * rms * (
            rng.standard_normal(values.shape) + 1j * rng.standard_normal(values.shape)
        ) / np.sqrt(2)
        sets.append(
            FrfSet(
                LINES,
                values,
                "accelerance",
                tuple(range(1, X.size + 1)),
                np.c_[X, np.zeros_like(X)],
                101 + j,
                (np.nan, np.nan),
                source=f"model against {101 + j}",
            )
        )
    return FrfReferences(tuple(sets))


def test_each_single_reference_reads_the_close_pair_as_one_mode() -> None:
    """The failure the pLSCF mends: one reference, one mode where the model has two."""
    for frfs in _references().sets:
        found = select_poles(stabilisation(frfs, BAND, 60)).frequency
        near = np.abs(found[:, None] - FREQUENCY_HZ[:2]).min(axis=1) < 1.0
        assert near.sum() == 1, f"against {frfs.reference_node}: {found}"


def test_plscf_recovers_both_poles_of_the_pair_noise_free() -> None:
    selected = select_poles(poly_stabilisation(_references(), BAND, 30))
    assert selected.n_modes == 3
    np.testing.assert_allclose(selected.frequency, FREQUENCY_HZ, rtol=1e-6)
    np.testing.assert_allclose(selected.damping_ratio, DAMPING, rtol=1e-3)


def test_plscf_residues_per_reference_are_the_models_shapes_and_participations() -> None:
    """LSFD per reference with the shared poles gives ``ψ_k φ_jk``: shapes (MAC > 0.999) and the
    ratio of the references' participations."""
    frfs = _references()
    selected = select_poles(poly_stabilisation(frfs, BAND, 30))
    constants = [fit_modal_constants(s, selected.pole, BAND).constants for s in frfs.sets]
    for j, c in enumerate(constants):
        for k in range(3):
            assert mac(c[:, k : k + 1], SHAPES[:, k : k + 1]).item() > 0.999, (j, k)
    ratio = np.linalg.norm(constants[1], axis=0) / np.linalg.norm(constants[0], axis=0)
    np.testing.assert_allclose(ratio, np.abs(SEEN[1] / SEEN[0]), rtol=1e-3)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_plscf_holds_the_pair_under_two_percent_noise(seed: int) -> None:
    """2 % complex noise per line (about 2,400 lines in the band): measured errors ≤ 8.5e-6 in
    frequency and ≤ 0.43 % in damping over seeds 0–9; held at a tenth of the real-data must-hold's
    tolerances (0.1 % and 20 %): 1e-4 and 2 %."""
    selected = select_poles(poly_stabilisation(_references(0.02, seed), BAND, 30))
    assert selected.n_modes == 3, selected.frequency
    np.testing.assert_allclose(selected.frequency, FREQUENCY_HZ, rtol=1e-4)
    np.testing.assert_allclose(selected.damping_ratio, DAMPING, rtol=0.02)


def test_one_reference_gives_the_scalar_lscf_poles() -> None:
    """n_r = 1 is the scalar LSCF: the same poles at every order (round-off)."""
    frfs = _references(0.01).sets[0]
    poly = poly_stabilisation([frfs], BAND, 30)
    scalar = stabilisation(frfs, BAND, 30)
    np.testing.assert_array_equal(poly.order, scalar.order)
    np.testing.assert_allclose(poly.pole, scalar.pole, rtol=1e-9)


def test_sets_on_other_points_are_refused_naming_the_fix() -> None:
    sets = _references().sets
    with pytest.raises(InputError, match=r"other points.*at_points"):
        FrfReferences((sets[0], sets[1].at_points(range(5))))


# --- the virtual rig's wide band against three references ------------------------------------
#
# The rig's free racket, its 69 hammer points against points 9, 0 and 40 (as
# benchmarks/bench_poles.py's third part), accelerance, complex noise of 1 % of each set's
# largest FRF value per line, 60 Hz to the analyser band's top (1,953 Hz at 200 µs sampling,
# 4,096 samples: 1.22 Hz lines).

RIG_REFERENCES = (9, 0, 40)
RIG_SAMPLING_S = 2.0e-4
RIG_SAMPLES = 4096
RIG_NOISE = 0.01
WIDE_BAND = (60.0, 1.0 / RIG_SAMPLING_S / 2.56)


@pytest.fixture(scope="module")
@costly
def rig_references() -> tuple[FrfReferences, ModalModel]:
    """The rig's FRFs against the three references, and its modal truth at the points."""
    racket = rd.default_racket()
    model = rig_model(racket, "free")
    locations, nodes = hammer_points(racket, n_frame=24, n_strings=45)
    lines = np.arange(RIG_SAMPLES // 2 + 1) / (RIG_SAMPLES * RIG_SAMPLING_S)
    lines = lines[lines <= WIDE_BAND[1]]
    sets = []
    for k, reference in enumerate(RIG_REFERENCES):
        values = model.frf(locations[reference : reference + 1], locations, lines)[0]
        rng = np.random.default_rng(1 + k)
        sigma = RIG_NOISE * float(np.abs(values).max())
        noise = (rng.normal(size=values.shape) + 1j * rng.normal(size=values.shape)) / np.sqrt(2)
        sets.append(
            FrfSet(
                lines,
                values + sigma * noise,
                "accelerance",
                nodes,
                locations,
                nodes[reference],
                tuple(locations[reference]),
                source=f"virtual rig, free, against point {reference}",
            )
        )
    return FrfReferences(tuple(sets)), model.modal_truth(locations)


@pytest.fixture(scope="module")
def rig_identified(rig_references: tuple[FrfReferences, ModalModel]) -> Identification:
    """identify over the wide band with the three references together (the pLSCF)."""
    return identify(rig_references[0], WIDE_BAND)


def test_identify_of_the_rigs_wide_band_against_three_references_runs(
    rig_references: tuple[FrfReferences, ModalModel], rig_identified: Identification
) -> None:
    """It stopped with a ValueError: a close pair's local fit (896.0/898.9 Hz) put one
    reference's constants (69 rows) among the pLSCF's residues, which stack every reference's
    (207 rows)."""
    frfs, _ = rig_references
    found = rig_identified
    assert found.stabilisation.residues.shape[0] == 3 * len(frfs.nodes)
    assert found.selected.residues.shape[0] == found.stabilisation.residues.shape[0]
    assert found.model.n_modes >= 12


def test_the_rigs_first_bending_is_kept_or_named_with_the_band_that_keeps_it(
    rig_references: tuple[FrfReferences, ModalModel], rig_identified: Identification
) -> None:
    """The rig's 120.0 Hz first bending (ζ 0.5 %; its peak 41, 17 and 1.2 × the noise against
    points 9, 0 and 40) over 60–1,953 Hz: the pLSCF's poles there wander from order to order
    (their errors, about one size in the zoomed z-plane for every mode, grow with the band's
    width in rad/s, and this mode decays the slowest of the band: docs/develop.md, issue 25),
    so no stable pole holds it.  It must be kept or named with the band that keeps it, and
    that band's fit must hold the rig's truth within issue 25's must-hold tolerances: 0.1 % in
    frequency, 20 % in damping."""
    frfs, truth = rig_references
    k = int(np.argmin(np.abs(truth.frequency - 120.0)))
    f_true, zeta_true = float(truth.frequency[k]), float(truth.damping_ratio[k])
    found = rig_identified
    near = np.abs(found.model.frequency / f_true - 1) < 0.01
    if not near.any():
        named = [
            d
            for d in found.dropped_modes
            if d.stage != "selection" and abs(d.frequency_hz / f_true - 1) < 0.01
        ]
        assert [d.stage for d in named] == ["edge"], named
        # why, not "too near the edge": the band's bottom at 5 Hz instead of 60 loses it too
        assert "slow decay (ζω 3.7 rad/s" in named[0].reason, named[0].reason
        band = named[0].reason.split("`band_hz` ")[1].split()[0]
        found = identify(frfs, tuple(float(v) for v in band.split(",")))  # type: ignore[arg-type]
        near = np.abs(found.model.frequency / f_true - 1) < 0.01
    (j,) = np.flatnonzero(near)
    assert found.model.frequency[j] == pytest.approx(f_true, rel=1e-3)
    assert found.model.damping_ratio[j] == pytest.approx(zeta_true, rel=0.2)
