"""How much an off-axis hit twists the racket: its stability against the offset.

A ball that lands a distance y off the long axis turns the racket about that axis: the rigid
roll (twistweight, ``roll_inertia_kgm2``) and the twisting modes.  :func:`twist_curve` runs the
transient simulation (reference engine, :func:`racketdyn.impact.transient.simulate_impact`) at
a row of offsets across the face and reads, at separation:

* the rigid roll angle and roll rate of the racket about its long axis (rad, rad/s);
* the section rotation of the flexible modes at the impact point, ∂w/∂y (central difference
  over ±``TWIST_DIFFERENCE_M`` of the mode shapes), and the total;
* the outgoing ball speed and the rebound ratio, which fall as the offset grows.

For a rigid free racket with no product of inertia (y_G = 0, a symmetric racket) the roll rate
after a normal impulse J at offset y is exactly ``J y / I_roll`` (``tests/test_twist.py``): the
twist grows with the offset and falls with the twistweight, as players feel it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import Ball
from racketdyn.errors import InputError, require_positive, require_speeds
from racketdyn.impact.grid import StringBed, check_string_bed, point_law, resolve_modal_model
from racketdyn.impact.hand import Hand
from racketdyn.impact.result import STATUS_OK
from racketdyn.impact.transient import simulate_impact
from racketdyn.modal import ModalModel
from racketdyn.racket import Racket

__all__ = ["TWIST_DIFFERENCE_M", "TwistCurve", "twist_curve"]

TWIST_DIFFERENCE_M = 0.005
"""Half-step of the central difference ∂φ/∂y for the modes' section rotation, m."""


@dataclass(frozen=True, eq=False)
class TwistCurve:
    """The racket's twist against the offset of the impact from its long axis.

    Attributes
    ----------
    x_m : float
        Impact position along the racket, m from the butt.
    offsets_m : ndarray (n,)
        Impact offsets y from the long axis, m.
    ball_speed_mps, racket_speed_mps : float
        Incoming speeds, m/s.
    support : str
        Support condition.
    roll_angle_rad, roll_rate_radps : ndarray (n,)
        Rigid roll of the racket about its long axis at separation, rad and rad/s; positive
        turns the +y side away from the ball (so a hit at y > 0 gives a positive roll).
    flexible_twist_rad : ndarray (n,)
        Section rotation ∂w/∂y of the flexible modes at the impact point at separation, rad
        (same sense).
    total_twist_rad : ndarray (n,)
        ``roll_angle_rad + flexible_twist_rad``, rad.
    rebound_speed_mps, rebound_ratio : ndarray (n,)
        Outgoing ball speed (m/s) and rebound ratio.
    contact_time_s : ndarray (n,)
        Contact time, s.
    status : ndarray of str (n,)
        ``ok`` or why the numbers are NaN.
    """

    x_m: float
    offsets_m: NDArray[np.float64]
    ball_speed_mps: float
    racket_speed_mps: float
    support: str
    roll_angle_rad: NDArray[np.float64]
    roll_rate_radps: NDArray[np.float64]
    flexible_twist_rad: NDArray[np.float64]
    total_twist_rad: NDArray[np.float64]
    rebound_speed_mps: NDArray[np.float64]
    rebound_ratio: NDArray[np.float64]
    contact_time_s: NDArray[np.float64]
    status: NDArray[np.str_]


def twist_curve(
    racket: Racket,
    ball: Ball,
    x_m: float,
    offsets_m: ArrayLike,
    ball_speed: float,
    support: str = "free",
    racket_speed: float = 0.0,
    modal_model: ModalModel | Literal["racket"] | None = "racket",
    hand: Hand | None = None,
    string_bed: StringBed = "uniform",
) -> TwistCurve:
    """Simulate impacts across the face at one x and read the racket's twist at separation.

    Parameters
    ----------
    racket, ball : Racket, Ball
        The racket and ball.
    x_m : float
        Position along the racket, m from the butt (on the string bed).
    offsets_m : array_like (n,)
        Offsets y from the long axis, m (each point must lie on the string bed).
    ball_speed : float
        Incoming ball speed, m/s.
    support : {"free", "pinned", "hand"}
        Support condition.
    racket_speed : float
        Speed of the impact point towards the ball, m/s.
    modal_model : ModalModel, None or "racket"
        Flexible modes (None: rigid racket).
    hand : Hand, optional
        The hand and arm of the ``hand`` support.
    string_bed : {"uniform", "local"}
        The face centre's string-bed law at every offset (the paper's) or each point's own
        (:func:`racketdyn.impact.grid.point_law`).

    Returns
    -------
    TwistCurve
    """
    require_positive("x_m", x_m)
    offsets = np.atleast_1d(np.asarray(offsets_m, dtype=float))
    if offsets.ndim != 1 or offsets.size == 0 or not np.all(np.isfinite(offsets)):
        raise InputError("offsets_m: give a row of finite offsets from the long axis, m")
    speed = float(require_speeds("ball speed", ball_speed)[0])
    check_string_bed(string_bed, None, racket)
    model = resolve_modal_model(racket, modal_model, include_string_bed=False)
    racket.head.check_inside(np.column_stack([np.full(offsets.size, x_m), offsets]))
    n = offsets.size
    values = {
        name: np.full(n, np.nan) for name in ("roll", "rate", "flex", "speed", "ratio", "time")
    }
    status = np.full(n, STATUS_OK, dtype=object)
    for i, y in enumerate(offsets):
        impact = simulate_impact(
            racket, ball, (x_m, y), speed, support, racket_speed, model,
            law=point_law(racket, ball, (x_m, y)) if string_bed == "local" else None,
            hand=hand if support == "hand" else None,
        )  # fmt: skip
        status[i] = impact.status
        if impact.status != STATUS_OK:
            continue
        names = impact.coordinate_names
        roll = names.index("roll")
        values["roll"][i] = impact.final_displacement[roll]
        values["rate"][i] = impact.final_velocity[roll]
        if model is not None:
            probe = np.array([[x_m, y + TWIST_DIFFERENCE_M], [x_m, y - TWIST_DIFFERENCE_M]])
            shapes = model.mode_shapes_at(probe)
            slope = (shapes[0] - shapes[1]) / (2.0 * TWIST_DIFFERENCE_M)
            modes = [names.index(name) for name in model.names]
            values["flex"][i] = float(slope @ impact.final_displacement[modes])
        else:
            values["flex"][i] = 0.0
        values["speed"][i] = impact.rebound_speed_mps
        values["ratio"][i] = impact.rebound_ratio
        values["time"][i] = impact.contact_time_s
    return TwistCurve(
        x_m=float(x_m),
        offsets_m=offsets,
        ball_speed_mps=speed,
        racket_speed_mps=float(racket_speed),
        support=support,
        roll_angle_rad=values["roll"],
        roll_rate_radps=values["rate"],
        flexible_twist_rad=values["flex"],
        total_twist_rad=values["roll"] + values["flex"],
        rebound_speed_mps=values["speed"],
        rebound_ratio=values["ratio"],
        contact_time_s=values["time"],
        status=status.astype(str),
    )
