"""LSFD modal constants and mass normalisation against the rig's modal truth."""

from __future__ import annotations

import numpy as np
import pytest

import racketdyn as rd
from pull_tension import pull_tension_racket
from racketdyn.errors import InputError
from racketdyn.measurement import FrfSet
from racketdyn.modal.residues import fit_modal_constants, mac, mass_normalised_shapes
from racketdyn.rig import accelerometer_index, hammer_points, rig_model

BAND = (60.0, 735.0)
"""The rig's modes from the 2-node bending to the 3-node twisting (663 Hz), the band's top midway
to the membrane (806.8 Hz on the frame's shape, issue 22's sixth session).  On the smooth frame
the band ran to 800 Hz and held the membrane (772 Hz); now a top of 800 Hz leaves the membrane
7 Hz above it, where the two residual terms cannot stand in for it (constants off by up to
0.9 % of the largest, 0.5 % allowed), and a top of 850 Hz puts the 4-node twisting (897 Hz) 47 Hz
above (median fit error 1.5 %) and the membrane in, which the accelerometer sees at 6 % of its
largest amplitude: its mass-normalised shape comes back 5.4 % off with 1 % noise (the
identification tests exempt such a mode from the 5 %: ``tests/test_identify.py``)."""


@pytest.fixture(scope="module")
def rig() -> rd.rig.RigModel:
    return rig_model(pull_tension_racket(), "free")


def _frfs(
    rig, tau: float | None = None, noise: float = 0.0, seed: int = 0
) -> tuple[FrfSet, np.ndarray]:
    # the CLI's layout: the accelerometer on the hoop 22.5° from the tip, where every mode of the
    # band moves it (a reference near a node makes that mode's mass normalisation ill-posed)
    locations, nodes = hammer_points(rig.racket, n_frame=24, n_strings=12)
    reference = accelerometer_index(rig.racket, locations)
    frequency = np.arange(1, 1025) * 2.44140625  # 5 kHz / 2048 lines
    s_shift = 0.0 if tau is None else 1.0 / tau
    # H(iω + 1/τ): the windowed structure (accelerance), by modal superposition
    phi_ref = rig.mode_shapes_at(locations[reference : reference + 1])[0]
    phi = rig.mode_shapes_at(locations)
    s = 2j * np.pi * frequency + s_shift
    wk, zk = rig.omega, rig.damping_ratio
    modal = s**2 / (s[None, :] ** 2 + 2 * (zk * wk)[:, None] * s + (wk**2)[:, None])
    values = np.einsum("k,jk,kf->jf", phi_ref, phi, modal)
    rng = np.random.default_rng(seed)
    scale = np.abs(values).max(axis=1, keepdims=True)
    values = values + noise * scale * (
        rng.standard_normal(values.shape) + 1j * rng.standard_normal(values.shape)
    ) / np.sqrt(2)
    frfs = FrfSet(
        frequency,
        values,
        "accelerance",
        nodes,
        locations,
        nodes[reference],
        tuple(locations[reference]),
        exponential_window_s=tau,
        source="rig FRFs",
    )
    return frfs, phi


def _truth_poles(rig, band: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    inside = (rig.frequency > band[0]) & (rig.frequency < band[1])
    w, z = rig.omega[inside], rig.damping_ratio[inside]
    return -z * w + 1j * w * np.sqrt(1 - z**2), inside


@pytest.mark.parametrize("tau", [None, 0.1])
def test_shapes_are_mass_normalised_truth(rig, tau) -> None:
    # True poles, 1 % noise (complex Gaussian, 1 % of each FRF's peak at every line): mass-
    # normalised shapes within 5 % (‖φ − φ_true‖ / ‖φ_true‖, issue 4), MAC ≥ 0.99; with an
    # exponential window (τ recorded) the same.
    frfs, phi_true = _frfs(rig, tau=tau, noise=0.01)
    poles, inside = _truth_poles(rig, BAND)
    fit = fit_modal_constants(frfs, poles, BAND)
    shapes = mass_normalised_shapes(frfs, fit)
    truth = phi_true[:, inside]
    sign = np.sign(np.sum(shapes * truth, axis=0))
    error = np.linalg.norm(shapes * sign - truth, axis=0) / np.linalg.norm(truth, axis=0)
    assert np.all(error < 0.05)
    assert np.all(np.diag(mac(shapes, truth)) > 0.99)
    assert fit.condition_number < 1e3  # column scaling (unscaled it is ~1e8)


def test_noise_free_fit_is_exact(rig) -> None:
    # All modes of the rig in the model and no noise: constants exact up to the residuals' share
    # of modes outside the band (< 0.5 %).
    frfs, phi_true = _frfs(rig)
    poles, inside = _truth_poles(rig, BAND)
    fit = fit_modal_constants(frfs, poles, BAND)
    expected = phi_true[:, inside] * phi_true[frfs.driving_point, inside]
    np.testing.assert_allclose(fit.constants, expected, atol=5e-3 * np.abs(expected).max())
    assert np.median(fit.error) < 0.01  # what is left: modes outside the band, two residual terms
    assert np.all(fit.error < 0.05)


def test_no_driving_point_is_a_clear_error(rig) -> None:
    frfs, _ = _frfs(rig)
    moved = FrfSet(
        frfs.frequency,
        frfs.values,
        frfs.frf_type,
        frfs.nodes,
        frfs.locations,
        999,
        (0.1, 0.0),
        source="no driving point",
    )
    poles, _ = _truth_poles(rig, BAND)
    fit = fit_modal_constants(moved, poles, BAND)
    with pytest.raises(InputError, match="strike the reference node 999"):
        mass_normalised_shapes(moved, fit)


def test_bad_poles(rig) -> None:
    frfs, _ = _frfs(rig)
    with pytest.raises(InputError, match="stable"):
        fit_modal_constants(frfs, np.array([1.0 + 700j]))
    with pytest.raises(InputError, match="no poles"):
        fit_modal_constants(frfs, np.array([]))


def test_the_structures_poles_fit_windowed_frfs_and_the_windowed_ones_do_not(rig) -> None:
    """What ``fit_modal_constants`` and ``SelectedPoles.windowed_pole`` say of the window (their
    docstrings disagreed: new-user trial of the Python API, 2026-11-27, eighth session): FRFs
    windowed with τ = 0.1 s and τ recorded are fitted with the structure's poles as well as
    without a window (what is left: the modes outside the band); given the windowed poles λ − 1/τ
    the window is taken twice and the fit is an order of magnitude worse (1.2 % against
    15 % measured)."""
    frfs, _ = _frfs(rig, tau=0.1)
    poles, _ = _truth_poles(rig, BAND)
    structure = fit_modal_constants(frfs, poles, BAND)
    twice = fit_modal_constants(frfs, poles - 1.0 / 0.1, BAND)
    # the windowed peaks are wider: the modes outside the band reach further in (1 % → 1.2 %)
    assert np.median(structure.error) < 0.02
    assert np.median(twice.error) > 5 * np.median(structure.error)
