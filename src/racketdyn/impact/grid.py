"""The grid of impacts both impact models work on: validated once, in one place.

:func:`impact_grid` checks the points, supports, speeds and labels a user gives, resolves the
modal model and the compound law, and computes the reduced masses — everything the
approximate method (:mod:`~racketdyn.impact.approximate`) and the transient simulation
(:mod:`~racketdyn.impact.transient`) share before they differ.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.__about__ import __version__
from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law
from racketdyn.errors import InputError, one_of, require_speeds
from racketdyn.impact.hand import Hand
from racketdyn.modal import ModalModel
from racketdyn.racket import SUPPORTS, Racket, as_locations
from racketdyn.racket_modal import modal_model_for

__all__ = [
    "ImpactGrid",
    "check_supports",
    "impact_grid",
    "resolve_modal_model",
    "support_reduced_mass",
]


def check_supports(
    supports: Sequence[str] | str, allowed: Sequence[str] = SUPPORTS
) -> tuple[str, ...]:
    """Support names as a tuple: one string or a sequence, each known, each once (InputError).

    ``allowed`` is the impact model's supports (the transient model adds ``hand``).
    """
    names = (supports,) if isinstance(supports, str) else tuple(supports)
    if not names:
        raise InputError(f"support: give at least one of {', '.join(allowed)}")
    for name in names:
        if name == "hand" and "hand" not in allowed:
            raise InputError(
                "support 'hand' needs the transient impact model (the approximate method "
                "holds the grip as a pin: use 'pinned')"
            )
        one_of("support", name, allowed)
    if len(set(names)) != len(names):
        raise InputError(f"support: each support once (got {', '.join(names)})")
    return names


def resolve_modal_model(
    racket: Racket,
    modal_model: ModalModel | Literal["racket"] | None,
    include_string_bed: bool,
) -> ModalModel | None:
    """The modes an impact model charges: ``"racket"`` → the racket's own, ``None`` → rigid.

    String-bed modes are dropped unless ``include_string_bed`` (see
    :func:`racketdyn.impact.approximate.predict` for why).  Rigid-body modes (a sponge's or a
    hand's, in the rig's modal truth) are always dropped: the reduced mass of the support
    already carries the rigid-body motion, and a 2 Hz mode charged as vibration would take
    the whole impulse (trial of 2026-11-23: every row flagged).
    """
    if isinstance(modal_model, str):
        if modal_model != "racket":
            raise InputError(
                f"modal_model must be a ModalModel, None or 'racket' (got {modal_model!r})"
            )
        model: ModalModel | None = modal_model_for(racket)
    else:
        model = modal_model
    if model is not None:
        model = model.flexible_modes if include_string_bed else model.frame_modes
    return model


def support_reduced_mass(
    racket: Racket, locations: ArrayLike, support: str, hand: Hand | None = None
) -> NDArray[np.float64]:
    """Reduced mass at each point for a support, kg: eq 4 for ``free`` and ``pinned``; for
    ``hand``, Kawazoe's arm at the handle (:meth:`racketdyn.impact.hand.Hand.reduced_mass`)."""
    if support == "hand":
        return (hand or Hand()).reduced_mass(racket, locations)
    return racket.reduced_mass(locations, support)


@dataclass(frozen=True, eq=False)
class ImpactGrid:
    """Validated inputs of an impact prediction over points × speeds × supports.

    Attributes
    ----------
    locations : ndarray (n_points, 2)
        Impact points on the string bed, m.
    labels : tuple of str
        Point labels.
    supports : tuple of str
        Support conditions.
    ball_speed, racket_speed : ndarray (n_speeds,)
        Speeds towards each other, m/s (racket speed broadcast to one per ball speed).
    reduced_mass : ndarray (n_points, n_supports)
        Reduced mass at each point for each support, kg (eq 4).
    model : ModalModel or None
        Modes charged (None: rigid racket).
    law : RestoringForce
        Compound ball+string law F_GB.
    """

    locations: NDArray[np.float64]
    labels: tuple[str, ...]
    supports: tuple[str, ...]
    ball_speed: NDArray[np.float64]
    racket_speed: NDArray[np.float64]
    reduced_mass: NDArray[np.float64]
    model: ModalModel | None
    law: RestoringForce

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(n_points, n_speeds, n_supports)``."""
        return (self.locations.shape[0], self.ball_speed.size, len(self.supports))

    def inputs(self, ball: Ball, method: str, **extra: Any) -> dict[str, Any]:
        """What produced a result, for ``ImpactResult.inputs`` and run records."""
        return {
            "racketdyn_version": __version__,
            "method": method,
            **extra,
            "ball": {
                "mass_kg": ball.mass_kg,
                "diameter_m": ball.diameter_m,
                "e_bg": ball.e_bg,
                "e_bg_law": ball.e_bg_record(),
                "restoring_force": ball.restoring_force.as_dict(),
            },
            "compound_law": self.law.as_dict(),
            "modal_model": None if self.model is None else self.model.summary(),
        }


def impact_grid(
    racket: Racket,
    ball: Ball,
    locations: ArrayLike,
    ball_speed: ArrayLike,
    supports: Sequence[str] | str = SUPPORTS,
    racket_speed: ArrayLike = 0.0,
    modal_model: ModalModel | Literal["racket"] | None = "racket",
    labels: Sequence[str] | None = None,
    law: RestoringForce | None = None,
    include_string_bed: bool = False,
    allowed_supports: Sequence[str] = SUPPORTS,
    hand: Hand | None = None,
) -> ImpactGrid:
    """Validate an impact prediction's inputs (InputError naming the input) and prepare them.

    Parameters are those of :func:`racketdyn.impact.approximate.predict`, plus the model's
    ``allowed_supports`` and the ``hand`` of a ``hand`` support (its reduced mass:
    :meth:`racketdyn.impact.hand.Hand.reduced_mass`).
    """
    xy = as_locations(locations, "impact points")
    if xy.shape[0] == 0:
        raise InputError("impact points: give at least one point")
    racket.head.check_inside(xy)
    support_names = check_supports(supports, allowed_supports)
    v_ball = require_speeds("ball speed", ball_speed)
    v_racket = require_speeds("racket speed", racket_speed)
    if v_racket.size == 1:
        v_racket = np.full(v_ball.shape, float(v_racket[0]))
    elif v_racket.shape != v_ball.shape:
        raise InputError(
            f"racket speed: give one speed or one per ball speed ({v_ball.size}), "
            f"not {v_racket.size}"
        )
    if np.any(v_ball + v_racket <= 0):
        raise InputError(
            "ball speed + racket speed must be positive: the ball must reach the strings"
        )
    point_labels = (
        tuple(labels) if labels is not None else tuple(str(i + 1) for i in range(len(xy)))
    )
    if len(point_labels) != len(xy):
        raise InputError(f"{len(point_labels)} labels given for {len(xy)} impact points")
    return ImpactGrid(
        locations=xy,
        labels=point_labels,
        supports=support_names,
        ball_speed=v_ball,
        racket_speed=v_racket,
        reduced_mass=np.column_stack(
            [support_reduced_mass(racket, xy, s, hand) for s in support_names]
        ),
        model=resolve_modal_model(racket, modal_model, include_string_bed),
        law=law or compound_law(racket, ball),
    )
