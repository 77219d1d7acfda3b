"""Poles from FRFs (LSCF stabilisation + automatic selection) against known modal truth.

Oracles and their tolerances:
- FRFs synthesised from a known modal model, 1 % complex Gaussian noise (standard deviation 1 %
  of the largest FRF magnitude of the set, the same on every line and FRF, as one
  accelerometer's noise floor gives): every mode whose peak stands 10 × above the noise is
  found, frequency within 0.2 %, damping ratio within 10 %, nothing else in the band (the
  issue's requirement; measured: frequency within 0.05 %, damping within 5 %);
- the virtual rig's modal truth (``RigModel.modal_truth``) the same way;
- the exponential window: FRFs of the windowed structure, H(iω + 1/τ), with τ recorded give
  back the true damping within 5 % (docs/develop.md, measurement conventions);
- the LSCF algebra: every order of one build equals a fresh build at that order, and a dense
  least-squares solve of the same linearised problem (numpy ``lstsq`` and ``roots``), to
  round-off;
- noise-free FRFs: poles exact to 1e-6.
"""

from __future__ import annotations

import logging
from dataclasses import replace

import matplotlib
import numpy as np
import pytest
from numpy.typing import NDArray

from costly import costly

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from pull_tension import pull_tension_racket
from racketdyn.errors import InputError
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.measurement.records import FrfSet
from racketdyn.modal.poles import (
    PoleStability,
    SelectedPoles,
    SelectionRules,
    Stabilisation,
    mac,
    select_poles,
    stabilisation,
)
from racketdyn.plotting.primitives import plot_stabilisation
from racketdyn.rig import Acquisition, RigModel, hammer_points, rig_model, simulate_hammer_test

# A five-mode structure with a close pair: 520 and 530 Hz are one half-power bandwidth apart
# at ζ = 1 % and two at 0.5 %.
FREQUENCY = np.array([105.0, 240.0, 385.0, 520.0, 530.0, 690.0])
DAMPING = np.array([0.008, 0.006, 0.010, 0.005, 0.007, 0.009])
BAND = (50.0, 800.0)
N_POINTS = 20
FREQUENCY_TOLERANCE = 0.002  # the issue: 0.2 %
DAMPING_TOLERANCE = 0.10  # the issue: 10 %


def _shapes(seed: int) -> NDArray[np.float64]:
    """Random shapes at N_POINTS points, the reference (row 0) on no node of any mode."""
    rng = np.random.default_rng(seed)
    shapes = rng.normal(size=(N_POINTS, FREQUENCY.size))
    shapes[0] = np.sign(shapes[0]) * np.maximum(np.abs(shapes[0]), 0.8)
    return shapes


def _mdof(
    seed: int = 0,
    noise: float = 0.01,
    shift: float = 0.0,
    frequency: NDArray[np.float64] | None = None,
    frf_type: str = "accelerance",
    modes: tuple[NDArray[np.float64], NDArray[np.float64]] = (FREQUENCY, DAMPING),
) -> tuple[FrfSet, float]:
    """Analytic FRFs H(s) = Σ φ_i φ_ref s^p / (s² + 2ζωs + ω²) at s = iω + shift, plus noise.

    ``modes``: six frequencies (Hz) and damping ratios.  Returns the set and the noise
    standard deviation (``noise`` of the set's largest magnitude).
    """
    lines = np.arange(0.0, 1000.0 + 0.25, 0.5) if frequency is None else frequency
    shapes = _shapes(seed)
    constants = shapes * shapes[0]
    omega = 2 * np.pi * modes[0]
    zeta = modes[1]
    s = 2j * np.pi * lines + shift
    power = {"receptance": 0, "mobility": 1, "accelerance": 2}[frf_type]
    modal = s[:, None] ** power / (s[:, None] ** 2 + 2 * zeta * omega * s[:, None] + omega**2)
    values = constants @ modal.T
    sigma = noise * float(np.abs(values).max())
    values = values + _complex_noise(sigma, values.shape, seed=100 + seed)
    frfs = FrfSet(
        frequency=lines,
        values=values,
        frf_type=frf_type,  # type: ignore[arg-type]
        nodes=tuple(range(1, N_POINTS + 1)),
        locations=np.column_stack([np.linspace(0.1, 0.6, N_POINTS), np.zeros(N_POINTS)]),
        reference_node=1,
        reference_location=(0.1, 0.0),
        source=f"analytic 6-mode structure, seed {seed}",
    )
    return frfs, sigma


def _complex_noise(sigma: float, shape: tuple[int, ...], seed: int) -> NDArray[np.complex128]:
    """Complex Gaussian noise of standard deviation σ (σ/√2 on each part)."""
    rng = np.random.default_rng(seed)
    return np.asarray(sigma * (rng.normal(size=shape) + 1j * rng.normal(size=shape)) / np.sqrt(2))


def _peaks(seed: int, sigma: float) -> NDArray[np.float64]:
    """Each mode's accelerance peak |A|/(2ζ) at its best point, over the noise σ."""
    shapes = _shapes(seed)
    return np.asarray(np.abs(shapes * shapes[0]).max(axis=0) / (2 * DAMPING) / sigma)


def _match(
    selected: SelectedPoles, frequency: NDArray[np.float64], damping: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], list[float]]:
    """Relative frequency and damping errors of the selected mode nearest each true mode, and
    the selected modes near no true mode (spurious)."""
    nearest = np.array([np.argmin(np.abs(selected.frequency - f)) for f in frequency])
    df = selected.frequency[nearest] / frequency - 1
    dz = selected.damping_ratio[nearest] / damping - 1
    spurious = [
        float(f) for k, f in enumerate(selected.frequency) if k not in set(nearest.tolist())
    ]
    return df, dz, spurious


@pytest.fixture(scope="module")
def noisy() -> tuple[FrfSet, float]:
    return _mdof(seed=0)


@pytest.fixture(scope="module")
def noisy_stab(noisy: tuple[FrfSet, float]) -> Stabilisation:
    return stabilisation(noisy[0], BAND, max_order=60)


# --- accuracy --------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_close_pair_and_every_mode_above_the_noise_are_found(seed: int) -> None:
    frfs, sigma = _mdof(seed=seed)
    assert np.all(_peaks(seed, sigma) > 10)  # every peak stands out of the noise
    selected = select_poles(stabilisation(frfs, BAND, max_order=60))
    assert selected.n_modes == FREQUENCY.size
    df, dz, spurious = _match(selected, FREQUENCY, DAMPING)
    assert not spurious
    np.testing.assert_array_less(np.abs(df), FREQUENCY_TOLERANCE)
    np.testing.assert_array_less(np.abs(dz), DAMPING_TOLERANCE)
    # the pair stays two modes, with their own shapes
    pair = np.flatnonzero((selected.frequency > 510) & (selected.frequency < 540))
    assert pair.size == 2
    assert mac(selected.residues[:, pair[:1]], selected.residues[:, pair[1:]])[0, 0] < 0.9


def test_a_pair_inside_its_half_power_width_with_other_shapes_stays_two() -> None:
    # 520 and 524 Hz at ζ = 0.5 %: 4 Hz apart, inside their half-power width 5.2 Hz, with
    # unlike shapes (random): two modes, not one peak merged (issue 25, item A)
    frequency = np.array([105.0, 240.0, 385.0, 520.0, 524.0, 690.0])
    damping = np.array([0.008, 0.006, 0.010, 0.005, 0.005, 0.009])
    frfs, _ = _mdof(seed=0, noise=0.001, modes=(frequency, damping))
    selected = select_poles(stabilisation(frfs, BAND, max_order=60))
    np.testing.assert_allclose(selected.frequency, frequency, rtol=FREQUENCY_TOLERANCE)
    assert not [d for d in selected.dropped_modes if d.stage == "merged"]


def test_noise_estimate_is_the_noise(noisy: tuple[FrfSet, float], noisy_stab) -> None:
    # the standard deviation of the complex noise on each line, within 10 %
    np.testing.assert_allclose(noisy_stab.noise_rms, noisy[1], rtol=0.1)


def test_noise_free_poles_are_exact() -> None:
    frfs, _ = _mdof(noise=0.0)
    selected = select_poles(stabilisation(frfs, BAND, max_order=40))
    np.testing.assert_allclose(selected.frequency, FREQUENCY, rtol=1e-6)
    np.testing.assert_allclose(selected.damping_ratio, DAMPING, rtol=1e-6)


def test_unevenly_spaced_lines_take_the_general_path() -> None:
    lines = np.arange(0.0, 1000.25, 0.5)
    lines = np.delete(lines, np.arange(3, lines.size, 7))  # every seventh line missing
    frfs, _ = _mdof(noise=0.0, frequency=lines)
    stab = stabilisation(frfs, BAND, max_order=40)
    assert stab.metadata["evenly_spaced"] is False
    selected = select_poles(stab)
    np.testing.assert_allclose(selected.frequency, FREQUENCY, rtol=1e-6)
    np.testing.assert_allclose(selected.damping_ratio, DAMPING, rtol=1e-6)


@pytest.mark.parametrize("frf_type", ["mobility", "receptance"])
def test_other_frf_types(frf_type: str) -> None:
    frfs, _ = _mdof(seed=1, frf_type=frf_type, noise=0.002)
    selected = select_poles(stabilisation(frfs, BAND, max_order=60))
    df, dz, spurious = _match(selected, FREQUENCY, DAMPING)
    assert not spurious
    np.testing.assert_array_less(np.abs(df), FREQUENCY_TOLERANCE)
    np.testing.assert_array_less(np.abs(dz), DAMPING_TOLERANCE)


def test_without_noise_compensation_the_damping_is_biased_high(noisy) -> None:
    # The plain LSCF estimate (module docstring, "Noise"): at order 15 the 105 Hz mode's
    # damping is a third too high (measured +36 %); the compensated one is right (−0.2 %).
    def damping_at_order_15(compensate: bool) -> float:
        stab = stabilisation(noisy[0], BAND, max_order=15, noise_compensation=compensate)
        at = stab.at_order(15)
        return float(stab.damping_ratio[at[np.argmin(np.abs(stab.frequency[at] - 105.0))]])

    assert damping_at_order_15(False) > 1.25 * DAMPING[0]
    assert damping_at_order_15(True) == pytest.approx(DAMPING[0], rel=DAMPING_TOLERANCE)


@pytest.fixture(scope="module")
@costly
def free_rig() -> RigModel:
    return rig_model(pull_tension_racket(), "free")


def test_rig_modes_are_its_modal_truth(free_rig: RigModel) -> None:
    # 26 points (12 on the frame, 14 on the strings), reference on the hoop off the long axis
    # so bending, twisting and membrane modes all show; accelerance, 0.5 Hz lines, 1 % noise.
    # On the frame's shape (issue 22, sixth session) the 10-point frame's hoop points each sit
    # near a node of one mode (the 4-node bending at 0.5 σ at the old reference); 12 frame
    # points put one at (0.381, −0.091) m where the weakest of the six peaks is 37 σ, and the
    # band reaches 850 Hz for the membrane, now 806.8 Hz (772 on the smooth frame).
    locations, nodes = hammer_points(free_rig.racket, n_frame=12, n_strings=14)
    reference = 9
    lines = np.arange(40.0, 900.25, 0.5)
    values = free_rig.frf(locations[reference : reference + 1], locations, lines)[0]
    sigma = 0.01 * float(np.abs(values).max())
    values = values + _complex_noise(sigma, values.shape, seed=7)
    frfs = FrfSet(
        frequency=lines,
        values=values,
        frf_type="accelerance",
        nodes=nodes,
        locations=locations,
        reference_node=nodes[reference],
        reference_location=tuple(locations[reference]),
    )
    band = (60.0, 850.0)
    truth = free_rig.modal_truth(locations)
    inside = (truth.frequency > band[0]) & (truth.frequency < band[1])
    frequency, damping = truth.frequency[inside], truth.damping_ratio[inside]
    peaks = np.abs(truth.mode_shapes * truth.mode_shapes[reference]).max(axis=0) / (
        2 * truth.damping_ratio
    )
    assert np.all(peaks[inside] > 10 * sigma)  # all six flexible modes stand out
    selected = select_poles(stabilisation(frfs, band, max_order=60))
    df, dz, spurious = _match(selected, frequency, damping)
    assert selected.n_modes == frequency.size == 6
    assert not spurious
    np.testing.assert_array_less(np.abs(df), FREQUENCY_TOLERANCE)
    np.testing.assert_array_less(np.abs(dz), DAMPING_TOLERANCE)


# --- the exponential window ------------------------------------------------------------------


def test_window_shift_is_removed_analytic() -> None:
    # FRFs of the windowed structure are H(iω + 1/τ) exactly (docs/develop.md); with τ on the
    # set the damping comes back within 5 %, without it every mode carries 1/(τω) more.
    tau = 0.2
    frfs, _ = _mdof(seed=1, shift=1.0 / tau)
    windowed = replace(frfs, exponential_window_s=tau)
    selected = select_poles(stabilisation(windowed, BAND, max_order=60))
    _, dz, spurious = _match(selected, FREQUENCY, DAMPING)
    assert not spurious
    np.testing.assert_array_less(np.abs(dz), 0.05)
    naive = select_poles(stabilisation(frfs, BAND, max_order=60))
    _, dz_naive, _ = _match(naive, FREQUENCY, DAMPING + 1 / (tau * 2 * np.pi * FREQUENCY))
    np.testing.assert_array_less(np.abs(dz_naive), 0.05)
    np.testing.assert_allclose(selected.windowed_pole, selected.pole - 1 / tau)


def test_window_shift_is_removed_through_the_measurement_chain(free_rig: RigModel) -> None:
    # Hammer records of twelve frame points on the rig, estimated with an exponential window of
    # τ = 0.1 s (it adds 1/(τω) = 1.3 % to the 2-node mode's 0.5 %): the damping comes back
    # within 5 % of the rig's truth, every flexible mode in 60–800 Hz found, nothing else.
    # Twelve, with the reference at (0.381, −0.091) m: on the frame's shape (issue 22, sixth
    # session) the ten-point layout's reference sat on a node of the 4-node bending (624 Hz),
    # whose damping then came back 8 % off (the previous test).
    locations, nodes = hammer_points(free_rig.racket, n_frame=12, n_strings=5)
    frame, reference = slice(0, 12), 9
    records = simulate_hammer_test(
        free_rig,
        locations[frame],
        nodes[frame],
        tuple(locations[reference]),
        nodes[reference],
        acquisition=Acquisition(n_averages=4, n_samples=4096),
        seed=3,
    )
    frfs = estimate_frfs(records, exponential_window_s=0.1).frfs
    assert frfs is not None
    truth = free_rig.modal_truth(locations[frame], max_frequency_hz=800.0)
    flexible = truth.frequency > 60.0
    selected = select_poles(stabilisation(frfs, (60.0, 800.0), max_order=60))
    df, dz, spurious = _match(selected, truth.frequency[flexible], truth.damping_ratio[flexible])
    assert not spurious
    np.testing.assert_array_less(np.abs(df), FREQUENCY_TOLERANCE)
    np.testing.assert_array_less(np.abs(dz), 0.05)


# --- the algebra -----------------------------------------------------------------------------


def _dense_lscf_poles(stab: Stabilisation, frfs: FrfSet, order: int) -> NDArray[np.complex128]:
    """The same linearised least squares at one order, solved densely: an independent oracle.

    Minimise Σ_o ‖N_o(Ω) − H_o d(Ω)‖² over the numerators and d with α_m = 1: the numerators
    are projected out (QR of the basis), the rest is one ``lstsq``; poles from ``np.roots``.
    """
    band = frfs.band(*stab.band_hz)
    theta = 2 * np.pi * (band.frequency - band.frequency[0]) * stab.time_step_s
    basis = np.exp(1j * np.outer(theta, np.arange(order + 1)))
    q, _ = np.linalg.qr(basis)
    blocks = []
    for h in band.values:
        weighted = h[:, None] * basis
        blocks.append(weighted - q @ (q.conj().T @ weighted))
    stacked = np.vstack(blocks)
    alpha = np.linalg.lstsq(stacked[:, :order], -stacked[:, order], rcond=None)[0]
    z = np.roots(np.append(alpha, 1.0)[::-1])
    pole = np.log(z) / stab.time_step_s
    pole = pole.real + 1j * (np.mod(pole.imag * stab.time_step_s, 2 * np.pi) / stab.time_step_s)
    pole = pole + 2j * np.pi * band.frequency[0]
    keep = (np.abs(z) < 1) & (np.abs(z) > np.exp(-2 * np.pi))
    f = np.abs(pole) / (2 * np.pi)
    keep &= (f >= stab.band_hz[0]) & (f <= stab.band_hz[1])
    return np.sort_complex(pole[keep])


@pytest.mark.slow
def test_every_order_equals_a_fresh_solve(noisy) -> None:
    frfs = noisy[0]
    full = stabilisation(frfs, BAND, max_order=50, noise_compensation=False)
    for order in (8, 23, 40):
        fresh = stabilisation(frfs, BAND, max_order=order, noise_compensation=False)
        a = np.sort_complex(full.pole[full.at_order(order)])
        b = np.sort_complex(fresh.pole[fresh.at_order(order)])
        np.testing.assert_allclose(a, b, rtol=1e-9)
        dense = _dense_lscf_poles(full, frfs, order)
        np.testing.assert_allclose(a, dense, rtol=1e-7)


def test_sets_on_one_axis_are_fitted_together(noisy) -> None:
    frfs = noisy[0]
    halves = [
        FrfSet(
            frequency=frfs.frequency,
            values=frfs.values[part],
            frf_type=frfs.frf_type,
            nodes=frfs.nodes[part],
            locations=frfs.locations[part],
            reference_node=frfs.reference_node,
            reference_location=frfs.reference_location,
        )
        for part in (slice(0, 8), slice(8, None))
    ]
    one = stabilisation(frfs, BAND, max_order=30)
    two = stabilisation(halves, BAND, max_order=30)
    np.testing.assert_allclose(two.pole, one.pole, rtol=1e-10)
    assert two.nodes == one.nodes


def test_stability_classes_nest(noisy_stab: Stabilisation) -> None:
    # a fully stable pole agrees with its match below in frequency, damping and shape
    stable = noisy_stab.stability == PoleStability.SHAPE
    assert stable.sum() > 100
    assert np.all(noisy_stab.stability[noisy_stab.order == noisy_stab.orders[0]] == 0)
    assert set(np.unique(noisy_stab.stability)) <= {0, 1, 2, 3}


def test_mac() -> None:
    rng = np.random.default_rng(3)
    a = rng.normal(size=(12, 3)) + 1j * rng.normal(size=(12, 3))
    np.testing.assert_allclose(np.diag(mac(a, a)), 1.0)
    np.testing.assert_allclose(mac(a, (2 - 3j) * a, pairwise=True), 1.0)
    e = np.eye(4)
    np.testing.assert_allclose(mac(e, e), e)
    assert mac(np.zeros(4), e[:, 0])[0, 0] == 0.0


# --- selection controls ----------------------------------------------------------------------


def test_exclude_and_pin(noisy_stab: Stabilisation, caplog: pytest.LogCaptureFixture) -> None:
    without = select_poles(noisy_stab, exclude_hz=[521.0])
    assert without.n_modes == 5
    assert np.min(np.abs(without.frequency - 520.0)) > 5
    assert any("excluded by the user" in d for d in without.dropped)
    # a rule strict enough to drop every mode: the pinned ones come back, flagged, logged
    with caplog.at_level(logging.INFO, logger="racketdyn.modal.poles"):
        strict = select_poles(
            noisy_stab, pin_hz=[530.0, 105.0], rules=SelectionRules(min_fraction=1.0)
        )
    np.testing.assert_allclose(strict.frequency, [105.0, 530.0], rtol=FREQUENCY_TOLERANCE)
    assert strict.pinned.all()
    assert "though the selection left it out" in caplog.text


def test_selection_subset(noisy_stab: Stabilisation) -> None:
    selected = select_poles(noisy_stab)
    keep = selected.frequency > 300
    part = selected.select(keep)
    np.testing.assert_array_equal(part.frequency, selected.frequency[keep])
    np.testing.assert_array_equal(part.residues, selected.residues[:, keep])
    assert part.peak_to_noise.size == part.n_modes == int(keep.sum())
    np.testing.assert_array_equal(selected.select([0, 2]).pole, selected.pole[[0, 2]])


def test_pins_that_find_nothing_or_clash_are_errors(noisy_stab: Stabilisation) -> None:
    with pytest.raises(InputError, match="no stable pole within"):
        select_poles(noisy_stab, pin_hz=[300.0])
    with pytest.raises(InputError, match="both pinned and excluded"):
        select_poles(noisy_stab, pin_hz=[240.0], exclude_hz=[240.0])
    with pytest.raises(InputError, match="same mode"):
        select_poles(noisy_stab, pin_hz=[240.0, 241.0])
    with pytest.raises(InputError, match="outside the band"):
        select_poles(noisy_stab, pin_hz=[900.0])


# --- bad input -------------------------------------------------------------------------------


def test_pure_noise_finds_no_mode() -> None:
    # Decision: no mode is an InputError that says so (the issue: a clear message, never an
    # invented mode); the diagram itself is returned for inspection.
    frfs, _ = _mdof(noise=0.0)
    noise = replace(frfs, values=_complex_noise(1.0, frfs.values.shape, seed=5))
    stab = stabilisation(noise, BAND, max_order=60)
    with pytest.raises(InputError, match=r"no mode found between 50\.0 and 800\.0 Hz"):
        select_poles(stab)


@pytest.mark.parametrize("band", [(800.0, 1000.0), (560.0, 660.0)])
def test_band_without_modes_finds_no_mode(noisy, band: tuple[float, float]) -> None:
    with pytest.raises(InputError, match="no mode found"):
        select_poles(stabilisation(noisy[0], band, max_order=40))


def test_bad_inputs_are_input_errors(noisy) -> None:
    frfs = noisy[0]
    other_axis = replace(frfs, frequency=frfs.frequency * 1.001)
    with pytest.raises(InputError, match="different frequency axis"):
        stabilisation([frfs, other_axis], BAND)
    with pytest.raises(InputError, match="convert with"):
        stabilisation([frfs, frfs.as_type("mobility")], BAND)
    with pytest.raises(InputError, match="their poles differ"):
        stabilisation([frfs, replace(frfs, exponential_window_s=0.1)], BAND)
    with pytest.raises(InputError, match="outside"):
        stabilisation(frfs, (1100.0, 1200.0))
    with pytest.raises(InputError, match="low < high"):
        stabilisation(frfs, (800.0, 50.0))
    with pytest.raises(InputError, match="lines"):
        stabilisation(frfs, (100.0, 120.0), max_order=60)
    with pytest.raises(InputError, match="max_order"):
        stabilisation(frfs, BAND, max_order=0)
    with pytest.raises(InputError, match="min_mac"):
        stabilisation(frfs, BAND, min_mac=1.5)
    with pytest.raises(InputError, match="weighting"):
        stabilisation(frfs, BAND, weighting="loud")  # type: ignore[arg-type]
    with pytest.raises(InputError, match="FrfSet"):
        stabilisation([], BAND)
    broken = frfs.values.copy()
    broken[3, 500] = np.nan
    with pytest.raises(InputError, match="NaN"):
        stabilisation(replace(frfs, values=broken), BAND)
    with pytest.raises(InputError, match="every FRF is zero"):
        stabilisation(replace(frfs, values=np.zeros_like(frfs.values)), BAND)
    with pytest.raises(InputError, match="min_fraction"):
        select_poles(
            stabilisation(frfs, BAND, max_order=10), rules=SelectionRules(min_fraction=2.0)
        )


def test_band_past_the_lines_is_cut_and_logged(noisy, caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.WARNING, logger="racketdyn.modal.poles"):
        stab = stabilisation(noisy[0], (50.0, 1500.0), max_order=10)
    assert stab.band_hz == (50.0, 1000.0)
    assert "cut to the measured" in caplog.text


def test_inputs_are_not_mutated(noisy) -> None:
    frfs = noisy[0]
    values, frequency = frfs.values.copy(), frfs.frequency.copy()
    stab = stabilisation(frfs, BAND, max_order=30, weighting="rms")
    arrays = {name: getattr(stab, name).copy() for name in ("pole", "residues", "stability")}
    select_poles(stab, pin_hz=(105.0,), exclude_hz=[240.0])
    ax = plot_stabilisation(stab, frfs=frfs)
    plt.close(ax.figure)
    np.testing.assert_array_equal(frfs.values, values)
    np.testing.assert_array_equal(frfs.frequency, frequency)
    for name, before in arrays.items():
        np.testing.assert_array_equal(getattr(stab, name), before)


def test_rms_weighting_gives_the_same_modes(noisy) -> None:
    selected = select_poles(stabilisation(noisy[0], BAND, max_order=60, weighting="rms"))
    df, dz, spurious = _match(selected, FREQUENCY, DAMPING)
    assert not spurious
    np.testing.assert_array_less(np.abs(df), FREQUENCY_TOLERANCE)
    np.testing.assert_array_less(np.abs(dz), DAMPING_TOLERANCE)


# --- the figure ------------------------------------------------------------------------------


def test_plot_stabilisation(noisy, noisy_stab: Stabilisation) -> None:
    selected = select_poles(noisy_stab, pin_hz=[530.0])
    fig, ax = plt.subplots()
    out = plot_stabilisation(noisy_stab, selected, ax=ax, frfs=noisy[0])
    assert out is ax
    assert ax.get_xlim() == noisy_stab.band_hz
    assert ax.get_ylabel() == "model order (–)"
    labels = {t.get_text() for t in ax.get_legend().get_texts()}
    assert "+ shape (stable)" in labels
    assert len(fig.axes) == 2  # the summed |FRF| on its twin axis
    plt.close(fig)
    own = noisy_stab.plot(selected)
    plt.close(own.figure)


def test_stabilisation_legend_is_readable_and_off_the_poles(
    noisy, noisy_stab: Stabilisation
) -> None:
    """Issue 13: the legend was 6 pt and sat on the poles in the lower right corner."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig, ax = plt.subplots(figsize=(8, 5), layout="constrained")
    plot_stabilisation(noisy_stab, select_poles(noisy_stab), ax=ax, frfs=noisy[0])
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    legend = ax.get_legend()
    assert legend is not None
    assert min(t.get_fontsize() for t in legend.get_texts()) >= 8
    box = legend.get_window_extent(canvas.get_renderer())
    for line in ax.get_lines():
        xy = np.column_stack([line.get_xdata(), line.get_ydata()]).astype(float)
        shown = line.get_transform().transform(xy)
        covered = (
            (shown[:, 0] > box.x0) & (shown[:, 0] < box.x1)
            & (shown[:, 1] > box.y0) & (shown[:, 1] < box.y1)
        )  # fmt: skip
        assert not np.any(covered), f"the legend covers {line.get_label()!r}"
    plt.close(fig)


def test_public_objects_are_documented() -> None:
    import inspect

    from racketdyn.modal import poles

    for name in poles.__all__:
        obj = getattr(poles, name)
        doc = inspect.getdoc(obj)
        assert doc, f"poles.{name} has no docstring"
        if inspect.isfunction(obj):
            for parameter in inspect.signature(obj).parameters:
                assert parameter in doc, f"poles.{name}: {parameter!r} is not described"
