"""The hand and arm holding the grip: one definition for every model of the ``hand`` support.

The virtual rig's hand-held test (:func:`racketdyn.rig.rig_model`, ``support="hand"``) and the
transient impact model's ``hand`` support (:func:`racketdyn.impact.system.impact_system`,
used by ``predict``, ``compound``, ``swing``, sweeps) build their equations from this one
:class:`Hand`, so the same racket held by the same hand has the same modes in both (the rig's
2-node twisting mode had 3.3 % damping, the compound system's 0.50 %, when each had its own
hand).

Model:

* the palm and fingers, ``hand_mass_kg``, move with the handle, spread evenly over the grip
  from ``grip_start_m`` to ``grip_end_m``, with the radius of gyration ``roll_radius_m`` about
  the long axis (they turn with the handle);
* the arm is a rigid mass ``arm_mass_kg`` that translates normal to the face (its rotation is
  not modelled: over a 5 ms contact it turns far less than the racket in the hand);
* the palm and fingers join the handle to the arm with springs and dashpots spread evenly over
  the grip, acting on the racket's whole displacement there, flexible modes included;
* the fingers resist the handle turning about its long axis, flexible twist included, with a
  torsional spring and dashpot to the (non-rotating) arm, spread over the grip;
* the shoulder holds the arm with a soft spring, ``shoulder_stiffness_n_per_m``: periods of a
  good fraction of a second, far longer than a contact or a hammer's blow.  The rig, whose
  records and truth cover whole seconds, includes it; the transient impact model leaves it out
  (over a contact of a few milliseconds it stores nothing: the arm is free beyond the grip).

Defaults, with how sure they are:

* ``arm_mass_kg = 1.0``: Kawazoe's arm at the handle (ACMD 2002, model).
* ``hand_mass_kg = 0.06``: the part of the hand that moves with the handle at 100–400 Hz.  The
  whole hand is ≈ 0.6 % of body mass (≈ 0.45 kg; Dempster's segment tables as given by Winter,
  *Biomechanics and Motor Control of Human Movement*, 2009); the apparent mass of a gripping
  hand–arm falls well below that above ≈ 100 Hz (the ISO 10068 hand–arm impedance data).  The
  value is chosen within that range so that the bending frequencies drop by a few per cent, as
  Kawazoe (section 2) and Chadefaux et al. (J. Sports Sci. 2017) report for a held racket; the
  number itself is an assumption.
* ``roll_radius_m = 0.015``: radius of gyration of that mass about the long axis, just outside
  the handle's own (:data:`racketdyn.racket_modal.beam.HANDLE_RADIUS_M`, 12.5 mm): the skin and
  palm against the handle.  Assumption; a larger radius pulls the higher twisting modes down
  strongly (the handle's own roll inertia is small).
* ``grip_start_m = 0.010``, ``grip_end_m = 0.130``: a hand about 85 mm across the palm plus
  the wrap of thumb and index finger, centred on the paper's 70 mm grip axis (section 3.3).
  Assumption.
* ``stiffness_n_per_m = 2.0e4``: total palm-and-finger stiffness.  The hand–arm system's
  driving-point stiffness normal to the palm is of order 10⁴–10⁵ N/m in the 20–100 Hz band
  (ISO 10068 hand–arm impedance; Gurram, Rakheja and Brammer, J. Sound Vib. 1995); the low end
  is taken because only soft tissue acts between handle and arm.  Assumption within a
  published range.
* ``damping_ns_per_m = 12``: total palm-and-finger damping, at the low end of the 10–100 N·s/m
  resistive part of the same impedance data.  With the built-in racket the 2-node mode moves
  from 120 Hz, ζ 0.5 % (free) to ≈ 117 Hz, ζ ≈ 2 %: a few per cent lower and more than twice
  as damped, as Kawazoe measured (section 2; docs/references.md).  Assumption within a
  published range.
* ``roll_stiffness_nm_per_rad = 3.0``, ``roll_damping_nms_per_rad = 0.05``: the fingers'
  resistance to the handle turning in the hand.  No published value known to us; chosen so
  the roll mode is a heavily damped few-hertz mode and the twisting modes' damping rises like
  the bending modes'.  Assumption.
* ``shoulder_stiffness_n_per_m = 1000``: arm stiffnesses at the hand measured in
  posture-holding tasks are a few hundred to a few thousand N/m (Mussa-Ivaldi, Hogan and
  Bizzi, J. Neurosci. 1985).  Only roughly sure; it hardly matters above a few hertz.

Grip firmness hardly changes the rebound (Grabiner et al., 1983, measured at 10.6 m/s;
docs/references.md): ``tests/test_system.py`` checks that the model agrees.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.errors import InputError, require_finite, require_positive
from racketdyn.racket import PointMass, Racket

__all__ = ["GRIP_POINTS", "Hand"]

GRIP_POINTS = 5
"""Points the impact model lumps the grip's springs, dashpots and mass at, evenly over the grip
(the rig spreads them continuously)."""


@dataclass(frozen=True)
class Hand:
    """A hand and arm holding the grip (the ``hand`` support of the rig and the impact model).

    Parameters
    ----------
    arm_mass_kg : float
        Mass of the arm behind the grip's springs, kg (Kawazoe, ACMD 2002: ≈ 1 kg).
    hand_mass_kg : float
        Mass of the palm and fingers moving with the handle, kg (spread over the grip).
    roll_radius_m : float
        Radius of gyration of the hand's mass about the long axis, m.
    grip_start_m, grip_end_m : float
        Where the hand covers the handle, m from the butt.
    stiffness_n_per_m : float
        Total translational stiffness between handle and arm, N/m.
    damping_ns_per_m : float
        Total translational damping between handle and arm, N·s/m.
    roll_stiffness_nm_per_rad : float
        Total stiffness against the handle turning in the hand about the long axis, N·m/rad.
    roll_damping_nms_per_rad : float
        Total damping against the handle turning in the hand, N·m·s/rad.
    shoulder_stiffness_n_per_m : float
        Stiffness holding the arm in place, N/m.
    """

    arm_mass_kg: float = 1.0
    hand_mass_kg: float = 0.06
    roll_radius_m: float = 0.015
    grip_start_m: float = 0.010
    grip_end_m: float = 0.130
    stiffness_n_per_m: float = 2.0e4
    damping_ns_per_m: float = 12.0
    roll_stiffness_nm_per_rad: float = 3.0
    roll_damping_nms_per_rad: float = 0.05
    shoulder_stiffness_n_per_m: float = 1000.0

    def __post_init__(self) -> None:
        require_positive("hand.arm_mass_kg", self.arm_mass_kg)
        require_positive("hand.stiffness_n_per_m", self.stiffness_n_per_m)
        for name in (
            "hand_mass_kg",
            "roll_radius_m",
            "damping_ns_per_m",
            "roll_stiffness_nm_per_rad",
            "roll_damping_nms_per_rad",
            "shoulder_stiffness_n_per_m",
        ):
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
    def grip_length_m(self) -> float:
        """Length of handle the hand covers, m."""
        return self.grip_end_m - self.grip_start_m

    @property
    def roll_inertia_kgm2(self) -> float:
        """The hand's moment of inertia about the long axis, kg·m²."""
        return self.hand_mass_kg * self.roll_radius_m**2

    @property
    def grip_points_m(self) -> tuple[float, ...]:
        """Where the impact model lumps the grip (:data:`GRIP_POINTS`, equal shares), m."""
        step = self.grip_length_m / GRIP_POINTS
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
