"""One hand: the rig's hand-held test and the transient model's ``hand`` support agree.

Issue 27: ``rig --support hand`` and ``compound --support hand`` gave the same racket different
damping and frequencies (the built-in racket's 2-node twisting mode 3.25 % in the rig, 0.50 % in
the compound system): each had its own hand — the rig's springs to a fixed arm at 1000 N/m with
the hand's roll inertia and the fingers acting on the handle's twist, the impact model's springs
to a 1 kg arm at 2·10⁴ N/m with the fingers on the rigid roll alone, and the built-in modal
model knew no twist along the handle.  Both now build :class:`racketdyn.hand.Hand`.
"""

from __future__ import annotations

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.hand import Hand
from racketdyn.impact.compound import racket_modes
from racketdyn.impact.hand import Hand as ImpactHand
from racketdyn.racket_modal.beam import builtin_modal_model
from racketdyn.rig import HandModel, rig_model

# The two racket models differ a little on their own (free: the rig's string bed is coupled to
# the frame, the built-in model's is not: 3-node bending 325.4 against 328.5 Hz), and the rig's
# damping ratios are the classical real-mode approximation (its module docstring: twisting
# modes within 6 % of the complex modes), the impact model's the complex modes' own.
FREQUENCY_RTOL = {"2-node bending": 0.005, "3-node bending": 0.015, "2-node twisting": 0.005}
DAMPING_RTOL = {"2-node bending": 0.05, "3-node bending": 0.1, "2-node twisting": 0.25}


def test_one_class_one_place() -> None:
    assert HandModel is Hand
    assert ImpactHand is Hand


@pytest.fixture
def smooth_model(racket: rd.Racket, smooth_frame: None) -> rd.ModalModel:
    """The built-in modes on the frame the rig keeps (the smooth distribution: the frame's
    shape of issue 22's fourth session is the built-in model's alone so far), so that the two
    hands are compared on one frame."""
    return builtin_modal_model(racket)


@pytest.mark.slow
def test_the_rig_and_the_compound_system_hold_the_racket_alike(
    racket: rd.Racket, smooth_model: rd.ModalModel
) -> None:
    model = smooth_model
    rig = rig_model(racket, "hand")
    centre = [racket.head.centre_x_m, racket.head.centre_y_m]
    held = racket_modes(racket, model, "hand", centre, None)
    free = racket_modes(racket, model, "free", centre, None)
    for name in FREQUENCY_RTOL:
        k_rig = rig.names.index(name)
        k_held = held.names.index(name)
        k_free = free.names.index(name)
        assert held.frequency[k_held] == pytest.approx(
            rig.frequency[k_rig], rel=FREQUENCY_RTOL[name]
        ), name
        assert held.damping_ratio[k_held] == pytest.approx(
            rig.damping_ratio[k_rig], rel=DAMPING_RTOL[name]
        ), name
        # the hand damps every mode beyond the frame's own (the twisting mode 0.50 % before)
        assert held.damping_ratio[k_held] > 1.5 * free.damping_ratio[k_free], name
    # the hand–arm mode of the racket pitching on the palm against the arm: in both
    low = rig.frequency[(rig.frequency > 20.0) & (rig.frequency < 100.0)]
    pitch = held.frequency[(held.frequency > 20.0) & (held.frequency < 100.0)]
    assert held.names[int(np.flatnonzero(held.frequency > 20.0)[0])].startswith("hand–arm")
    np.testing.assert_allclose(low, pitch, rtol=0.01)


@pytest.mark.slow
def test_a_hand_changes_both_alike(racket: rd.Racket, smooth_model: rd.ModalModel) -> None:
    model = smooth_model
    firm = Hand(damping_ns_per_m=30.0, roll_damping_nms_per_rad=0.1)
    rig = rig_model(racket, "hand", firm)
    centre = [racket.head.centre_x_m, racket.head.centre_y_m]
    held = racket_modes(racket, model, "hand", centre, None, hand=firm)
    for name in ("2-node bending", "2-node twisting"):
        assert held.damping_ratio[held.names.index(name)] == pytest.approx(
            rig.damping_ratio[rig.names.index(name)], rel=DAMPING_RTOL[name]
        ), name
    assert rig.metadata["hand"]["damping_ns_per_m"] == 30.0
