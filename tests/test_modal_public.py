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
