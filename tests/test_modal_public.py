"""The modal core is public and works on any structure (issue 23): docs/modal.md's example."""

from __future__ import annotations

import numpy as np
import pytest

import racketdyn.modal as modal
from racketdyn.modal import ModalModel, identify
from racketdyn.testing import assert_modes_match, beam_frfs, natural_frequencies


def test_the_chain_is_exported() -> None:
    chain = ("identify", "stabilisation", "select_poles", "fit_modal_constants")
    for name in (*chain, "mass_normalised_shapes", "Identification", "Stabilisation", "ModalFit"):
        assert name in modal.__all__
        assert getattr(modal, name).__module__.startswith("racketdyn.modal.")


def test_docs_example_identifies_the_free_bar() -> None:
    """docs/modal.md: nine points, 1 % noise, the driving point at s = 0."""
    test = beam_frfs(np.linspace(0.0, 0.8, 9), reference_s=0.0, noise=0.01, seed=1)
    found = identify(test.frfs, band_hz=(40.0, 1000.0)).model
    np.testing.assert_allclose(found.frequency, [65.4, 180.3, 353.5, 584.4, 873.0], atol=0.1)
    assert found.scaling == "mass"  # mass-normalised: the driving point at s = 0
    assert_modes_match(
        found, natural_frequencies(5), frequency_rtol=2e-3, shapes=test.shapes, mac_min=0.98
    )


def test_assert_modes_match_says_what_is_wrong() -> None:
    shapes = np.eye(3)[:, :2]
    model = ModalModel(
        frequency=np.array([100.0, 250.0]),
        damping_ratio=np.array([0.01, 0.01]),
        mode_shapes=shapes,
        locations=np.column_stack([np.arange(3.0), np.zeros(3)]),
        names=("a", "b"),
    )
    assert_modes_match(model, [100.0, 250.0], shapes=shapes)
    with pytest.raises(AssertionError, match="true mode 2 at 260 Hz not found"):
        assert_modes_match(model, [100.0, 260.0])
    with pytest.raises(AssertionError, match="not in the truth: 250 Hz"):
        assert_modes_match(model, [100.0])
    with pytest.raises(AssertionError, match=r"MAC 0\.000"):
        assert_modes_match(model, [100.0, 250.0], shapes=shapes[:, ::-1])


def test_identify_takes_selection_rules() -> None:
    """A lab's own :class:`SelectionRules` reach :func:`identify` (new-user trial of the Python
    API, 2026-11-27, eighth session: only ``stabilisation`` → ``select_poles`` →
    ``fit_modal_constants`` by hand took them).  With an edge margin of a quarter of the band
    (40–1000 Hz: no mode within 240 Hz of either edge) the free bar keeps exactly its analytic
    modes in 280–760 Hz, the 3rd and 4th (Blevins: 353.5 and 584.4 Hz)."""
    test = beam_frfs(np.linspace(0.0, 0.8, 9), reference_s=0.0, noise=0.01, seed=1)
    rules = modal.SelectionRules(edge_margin=0.25)
    found = identify(test.frfs, band_hz=(40.0, 1000.0), rules=rules).model
    truth = natural_frequencies(5)
    inside = truth[(truth > 280.0) & (truth < 760.0)]
    assert inside.size == 2
    assert_modes_match(found, inside, frequency_rtol=2e-3)
    assert found.scaling == "mass"


def test_docs_chain_by_hand_makes_a_model_of_the_bar() -> None:
    """docs/modal.md, "From FRFs to a model the impact models use": the chain step by step
    with the structure's poles gives a mass-normalised ModalModel of the bar's analytic modes
    (the same tolerances as the one-call example)."""
    from racketdyn.modal import (
        SelectionRules,
        fit_modal_constants,
        mass_normalised_shapes,
        select_poles,
        stabilisation,
    )

    test = beam_frfs(np.linspace(0.0, 0.8, 9), reference_s=0.0, noise=0.01, seed=1)
    band = (40.0, 1000.0)
    selected = select_poles(stabilisation(test.frfs, band), rules=SelectionRules(min_fraction=0.5))
    fit = fit_modal_constants(test.frfs, selected.pole, band)
    model = ModalModel(
        frequency=selected.frequency,
        damping_ratio=selected.damping_ratio,
        locations=test.frfs.locations,
        mode_shapes=mass_normalised_shapes(test.frfs, fit),
        names=tuple(f"mode {k + 1}" for k in range(selected.n_modes)),
    )
    assert_modes_match(
        model, natural_frequencies(5), frequency_rtol=2e-3, shapes=test.shapes, mac_min=0.98
    )
