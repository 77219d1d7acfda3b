"""One design variant: :class:`Design`, and the racket, ball and hand its settings make.

Sits between the variables (:mod:`~racketdyn.sweep.variables`) and the task
(:mod:`~racketdyn.sweep.task`), which builds its design's racket with :func:`build_design`; the
spec (:mod:`~racketdyn.sweep.spec`) lists the designs and checks each with these functions.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

from racketdyn.ball import Ball
from racketdyn.errors import InputError
from racketdyn.impact.hand import Hand
from racketdyn.racket import KGM2_TO_KGCM2, SWINGWEIGHT_AXIS_M, PointMass, Racket
from racketdyn.sweep.variables import HAND_VARIABLES, POINT_MASS, Variable

__all__ = ["Design", "build_design", "build_hand"]

_RACKET_FIELDS = ("mass_kg", "balance_m", "inertia_cg_kgm2", "roll_inertia_kgm2", "grip_m")


@dataclass(frozen=True)
class Design:
    """One design variant: its index, task id, coordinate values and what it varies.

    Parameters
    ----------
    index : int
        Position along the ``design`` dimension.
    settings : tuple of (str, float)
        Every variable coordinate and its value in this design.
    varied : str
        One-at-a-time: the variable this design varies (``"base"`` for the base design);
        full factorial: ``"factorial"``.
    """

    index: int
    settings: tuple[tuple[str, float], ...]
    varied: str

    @property
    def task_id(self) -> str:
        """File-safe identifier of the design's task, ``design-00042``."""
        return f"design-{self.index:05d}"

    def describe(self) -> str:
        """The settings as ``name = value`` text."""
        return ", ".join(f"{k} = {v:g}" for k, v in self.settings) or "the base design"


def build_design(
    racket: Racket,
    ball: Ball,
    variables: Sequence[Variable],
    settings: Sequence[tuple[str, float]],
) -> tuple[Racket, Ball, float]:
    """The racket and ball of one design, and the frame-stiffness scale left to apply.

    Racket fields are replaced first (mass, balance, inertias, grip, tension); a swingweight
    gives the inertia about the balance point with the design's mass and balance,
    ``I_G = SW − M (x_G − 0.1 m)²``; point masses of positive mass are added to the racket's
    own.  A frame-stiffness scale s multiplies the built-in model's ``first_bending_hz`` and
    ``twisting_hz`` by √s (uniform stiffness scaling at fixed mass); for a racket with a modal
    model file it is returned for the task to scale the file's frame modes.

    Parameters
    ----------
    racket, ball : Racket, Ball
        The base racket and ball.
    variables : sequence of Variable
        The sweep's variables.
    settings : sequence of (str, float)
        The design's coordinate values (:attr:`Design.settings`).

    Returns
    -------
    racket : Racket
        The design's racket.
    ball : Ball
        The design's ball.
    file_model_scale : float
        Frame-stiffness scale still to apply to a modal model file (1 for the built-in model).
    """
    values = dict(settings)
    changes: dict[str, Any] = {}
    for name in _RACKET_FIELDS:
        if name in values:
            changes[name] = values[name]
    if "twistweight_kgcm2" in values:
        changes["roll_inertia_kgm2"] = values["twistweight_kgcm2"] / KGM2_TO_KGCM2
    if "swingweight_kgcm2" in values:
        mass = changes.get("mass_kg", racket.mass_kg)
        balance = changes.get("balance_m", racket.balance_m)
        swing = values["swingweight_kgcm2"]
        inertia = swing / KGM2_TO_KGCM2 - mass * (balance - SWINGWEIGHT_AXIS_M) ** 2
        if inertia <= 0:
            raise InputError(
                f"swingweight_kgcm2 ({swing:g}) must exceed M (x_G - 0.1 m)² = "
                f"{mass * (balance - SWINGWEIGHT_AXIS_M) ** 2 * KGM2_TO_KGCM2:.1f} kg·cm²"
            )
        changes["inertia_cg_kgm2"] = inertia
    if "tension_n" in values:
        changes["strings"] = replace(racket.strings, tension_n=values["tension_n"])
    added = []
    for variable in variables:
        if variable.kind == POINT_MASS:
            mass_kg, x_m, y_m = (values[c] for c in variable.coords[:3])
            if mass_kg > 0:
                added.append(PointMass(mass_kg, x_m, y_m, variable.name))
    if added:
        changes["point_masses"] = racket.point_masses + tuple(added)
    scale = values.get("frame_stiffness_scale", 1.0)
    if not (math.isfinite(scale) and scale > 0):
        raise InputError(f"frame_stiffness_scale must be a positive number (got {scale!r})")
    file_model_scale = 1.0
    if scale != 1.0:
        if racket.modal_model_file is None:
            changes["first_bending_hz"] = racket.first_bending_hz * math.sqrt(scale)
            changes["twisting_hz"] = racket.twisting_hz * math.sqrt(scale)
        else:
            file_model_scale = scale
    design_racket = replace(racket, **changes) if changes else racket
    design_ball = replace(ball, e_bg=values["e_bg"]) if "e_bg" in values else ball
    return design_racket, design_ball, file_model_scale


def build_hand(variables: Sequence[Variable], settings: Sequence[tuple[str, float]]) -> Hand:
    """The hand of one design (``hand`` support of the transient method).

    The design's hand variables (:data:`HAND_VARIABLES`) set their fields of
    :class:`~racketdyn.impact.hand.Hand`; the other fields keep the defaults.

    Parameters
    ----------
    variables : sequence of Variable
        The sweep's variables.
    settings : sequence of (str, float)
        The design's coordinate values (:attr:`Design.settings`).

    Returns
    -------
    Hand
        The design's hand (InputError if its values are not a valid hand).
    """
    values = dict(settings)
    fields = {
        variable.kind.removeprefix("hand."): values[variable.kind]
        for variable in variables
        if variable.kind in HAND_VARIABLES
    }
    return Hand(**fields)
