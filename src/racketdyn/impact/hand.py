"""The hand and arm holding the grip: the ``hand`` support of the transient impact model.

The approximate method models a hand-held racket as pinned at the grip (paper, section 3.3).
The transient model can instead hold the grip with a hand and an arm that have mass, stiffness
and damping: a lumped version of the virtual rig's distributed hand
(:class:`racketdyn.rig.model.HandModel`) with the arm given a mass, as in Kawazoe's model of
an arm of ≈ 1 kg at the handle (ACMD 2002; docs/references.md, "Racket dynamics").

Model (built into the equations of motion by :mod:`racketdyn.impact.system`):

* the palm and fingers, ``hand_mass_kg``, move with the handle, spread over the grip;
* the arm is a rigid mass ``arm_mass_kg`` that translates normal to the face (its rotation is
  not modelled: over a 5 ms contact it turns far less than the racket in the hand);
* the palm and fingers join the handle to the arm with springs and dashpots spread evenly over
  the grip, from ``grip_start_m`` to ``grip_end_m`` (lumped at ``GRIP_POINTS`` points, equal
  shares), acting on the racket's whole displacement there, flexible modes included;
* the fingers resist the handle turning about its long axis with a torsional spring and
  dashpot to the (non-rotating) arm;
* the arm is free beyond that: the shoulder's stiffness (a few hundred to a few thousand N/m,
  Mussa-Ivaldi, Hogan and Bizzi, J. Neurosci. 1985) sets periods of a second, far longer than
  the contact.

Defaults, with how sure they are:

* ``arm_mass_kg = 1.0``: Kawazoe's arm at the handle (ACMD 2002, model).
* ``hand_mass_kg = 0.06``: the part of the hand that moves with the handle at 100–400 Hz, as
  the rig's hand (:class:`racketdyn.rig.model.HandModel`, where its sources are given).  It
  lowers the bending frequencies by a few per cent, as Kawazoe measured (section 2).
* ``grip_start_m = 0.010``, ``grip_end_m = 0.130``: an adult's hand centred on the paper's
  70 mm grip axis (as the rig's hand).  Assumption.
* ``stiffness_n_per_m = 2.0e4``: total palm-and-finger stiffness.  The hand–arm system's
  driving-point stiffness normal to the palm is of order 10⁴–10⁵ N/m in the 20–100 Hz band
  (ISO 10068 hand–arm impedance; Gurram, Rakheja and Brammer, J. Sound Vib. 1995); the low end
  is taken because only soft tissue acts between handle and arm.  Assumption within a
  published range.
* ``damping_ns_per_m = 12``: total palm-and-finger damping, the rig's value, at the low end of
  the 10–100 N·s/m resistive part of the same impedance data.  With the built-in racket the
  2-node mode moves from 120 Hz, ζ 0.5 % (free) to 116.6 Hz, ζ 2.2 %: a few per cent lower and
  more than twice as damped, as Kawazoe measured (section 2; docs/references.md).  The
  hand–arm mode sits at 54 Hz, ζ 9 %.  Assumption within a published range.
* ``roll_stiffness_nm_per_rad = 3.0``, ``roll_damping_nms_per_rad = 0.05``: as the rig's hand
  (no published value known to us).  Assumption.

Grip firmness hardly changes the rebound (Grabiner et al., 1983, measured at 10.6 m/s;
docs/references.md): ``tests/test_system.py`` checks that the model agrees.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.errors import InputError, require_finite, require_positive
from racketdyn.racket import PointMass, Racket
from racketdyn.rig.model import (
    HAND_DAMPING_NS_PER_M,
    HAND_GRIP_END_M,
    HAND_GRIP_START_M,
    HAND_MASS_KG,
    HAND_ROLL_DAMPING_NMS_PER_RAD,
    HAND_ROLL_STIFFNESS_NM_PER_RAD,
)

__all__ = ["GRIP_POINTS", "Hand"]

GRIP_POINTS = 5
"""Points the grip's springs and dashpots are lumped at, evenly over the grip."""


@dataclass(frozen=True)
class Hand:
    """A hand and arm holding the grip (``support="hand"`` of the transient model).

    Parameters
    ----------
    arm_mass_kg : float
        Mass of the arm behind the grip's springs, kg (Kawazoe, ACMD 2002: ≈ 1 kg).
    hand_mass_kg : float
        Mass of the palm and fingers moving with the handle, kg (spread over the grip).
    grip_start_m, grip_end_m : float
        Where the hand covers the handle, m from the butt.
    stiffness_n_per_m : float
        Total translational stiffness between handle and arm, N/m.
    damping_ns_per_m : float
        Total translational damping between handle and arm, N·s/m.
    roll_stiffness_nm_per_rad : float
        Stiffness against the handle turning in the hand about the long axis, N·m/rad.
    roll_damping_nms_per_rad : float
        Damping against the handle turning in the hand, N·m·s/rad.
    """

    arm_mass_kg: float = 1.0
    hand_mass_kg: float = HAND_MASS_KG
    grip_start_m: float = HAND_GRIP_START_M
    grip_end_m: float = HAND_GRIP_END_M
    stiffness_n_per_m: float = 2.0e4
    damping_ns_per_m: float = HAND_DAMPING_NS_PER_M
    roll_stiffness_nm_per_rad: float = HAND_ROLL_STIFFNESS_NM_PER_RAD
    roll_damping_nms_per_rad: float = HAND_ROLL_DAMPING_NMS_PER_RAD

    def __post_init__(self) -> None:
        require_positive("hand.arm_mass_kg", self.arm_mass_kg)
        require_positive("hand.hand_mass_kg", self.hand_mass_kg, allow_zero=True)
        require_positive("hand.stiffness_n_per_m", self.stiffness_n_per_m)
        for name in ("damping_ns_per_m", "roll_stiffness_nm_per_rad", "roll_damping_nms_per_rad"):
            require_positive(f"hand.{name}", getattr(self, name), allow_zero=True)
        if self.roll_stiffness_nm_per_rad == 0 and self.roll_damping_nms_per_rad > 0:
            raise InputError(
                "hand: a roll damper needs a roll spring (roll_stiffness_nm_per_rad > 0): the "
                "arm does not turn, so a damper alone would hold no motion the model can split"
            )
        require_finite("hand.grip_start_m", self.grip_start_m)
        require_finite("hand.grip_end_m", self.grip_end_m)
        if not 0.0 <= self.grip_start_m < self.grip_end_m:
            raise InputError(
                "hand: the grip must run from grip_start_m ≥ 0 to a larger grip_end_m "
                f"(got {self.grip_start_m:g} to {self.grip_end_m:g} m)"
            )

    @property
    def grip_points_m(self) -> tuple[float, ...]:
        """Where the grip's springs and dashpots act, m from the butt (equal shares)."""
        step = (self.grip_end_m - self.grip_start_m) / GRIP_POINTS
        return tuple(self.grip_start_m + (i + 0.5) * step for i in range(GRIP_POINTS))

    def reduced_mass(self, racket: Racket, locations: ArrayLike) -> NDArray[np.float64]:
        """Reduced mass with the arm's and hand's mass fixed at the grip centre, kg.

        Kawazoe's arm at the handle (ACMD 2002): the ``hand`` support's number for the
        ``reduced_mass`` and ``cor`` columns.  The simulation itself keeps the grip's springs
        and dashpots; its rebound ratio is simulated, and ``cor`` is the e_r that gives it
        with this reduced mass.

        Parameters
        ----------
        racket : Racket
            The racket.
        locations : array_like (n, 2)
            Impact points (x, y), m.
        """
        centre = 0.5 * (self.grip_start_m + self.grip_end_m)
        held = racket.with_point_masses(
            PointMass(self.arm_mass_kg + self.hand_mass_kg, centre, 0.0, "hand and arm")
        )
        return held.reduced_mass(locations, "free")
