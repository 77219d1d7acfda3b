"""A swinging racket: the racket speed at every impact point, the outgoing ball speed, sweet spots.

The swing
---------
Kawazoe (ACMD 2002) turns the arm and the racket, rigidly joined (wrist locked), about the
shoulder with a constant shoulder torque T (56.9 N·m in that paper, docs/references.md).  From
rest through the swing angle Δθ the work done is the kinetic energy,

    ``½ I Ω² = T Δθ``,  so  ``Ω = sqrt(2 T Δθ / I)``,

with ``I = I_arm + I_racket`` the inertia of arm and racket about the shoulder.  The racket's
part follows from its mass properties by the parallel-axis theorem,
``I_racket = I_G + M (x_G + d)²`` (:meth:`racketdyn.racket.Racket.inertia_about_axis` at
``x = −d``), ``d`` the distance of the shoulder behind the butt along the racket's long axis.  A
heavier swingweight therefore swings slower.  Alternatively :class:`Swing` takes the angular speed
Ω directly (rotation about an axis ``d`` behind the butt), without the torque model.

The swing axis is across the handle, in the plane of the face (parallel to y), so the point
(x, y) of the face moves normal to the face at ``V = Ω (x + d)``, whatever its y.  That is the
``racket_speed`` of the impact models (speed of the impact point towards the ball); each point has
its own, so :func:`predict_swing` calls the impact model once per group of points with the same x
and merges the results back into point order.

Rebound of a moving racket (Cross; docs/references.md): ``v_out = e v_in + (1 + e) V`` with
``e`` the rebound ratio (apparent COR) of the racket at that point — what
:func:`racketdyn.impact.predict` returns as ``rebound_speed``.

Defaults and their sources
--------------------------
* ``torque_nm`` = 56.9 N·m: Kawazoe, ACMD 2002 (docs/references.md).
* ``swing_angle_rad`` = π/2: *assumption* — a quarter turn of arm and racket about the shoulder,
  from the end of the backswing (racket pointing at the back fence) to contact (racket parallel
  to the baseline).  Ω grows as √Δθ.
* The arm, for a 70 kg, 1.75 m adult (*assumption*, :func:`arm_from_anthropometry`), from
  Dempster's segment parameters as tabulated by Winter (Biomechanics and Motor Control of Human
  Movement, Table 4.1; segment lengths from Drillis and Contini, Winter Fig. 4.1):
  the whole arm (upper arm, forearm and hand, shoulder to wrist) has 5.0 % of the body mass and
  a radius of gyration about the shoulder of 0.645 of the shoulder–wrist length; upper arm
  0.186 H and forearm 0.146 H long; the hand 0.108 H long with its centre of mass 0.506 of the
  way from the wrist.  So ``arm_mass_kg`` = 3.5 kg, ``arm_gyration_m`` = 0.375 m (I_arm =
  0.49 kg·m²).
* ``axis_to_butt_m``: the hand holds the grip 70 mm from the butt (the paper's grip axis) at its
  centre of mass, with the arm straight along the racket's axis: shoulder to grip = 0.332 H +
  0.506 × 0.108 H = 0.677 m, shoulder to butt 0.607 m (*assumption*: a straight arm in line with
  the racket, the longest lever the model allows).

Sweet spots
-----------
:func:`sweet_spots` names the points players and engineers call the sweet spot and says where
they lie: the centre of percussion about the swing axis and about the grip (an impact there
leaves that axis without reaction), the node of the first (2-node) bending mode on the face (no
vibration), the point of maximum rebound ratio (racket at rest) and the point of maximum outgoing
ball speed for the swing.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Literal, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import minimize_scalar

from racketdyn._display import html_table
from racketdyn.ball import Ball
from racketdyn.contact import compound_law
from racketdyn.errors import InputError, one_of, require_finite, require_positive, require_whole
from racketdyn.impact.approximate import predict
from racketdyn.impact.grid import resolve_modal_model, status_warnings_held
from racketdyn.impact.result import (
    STATUS_OK,
    ImpactResult,
    impact_columns,
    status_text,
    summary_rows,
    write_columns,
)
from racketdyn.modal import ModalModel
from racketdyn.racket import Racket, as_locations
from racketdyn.racket_modal.shapes import axis_nodes

__all__ = [
    "AXIS_SWING_FACTORS",
    "DEFAULT_ARM_GYRATION_M",
    "DEFAULT_ARM_MASS_KG",
    "DEFAULT_AXIS_TO_BUTT_M",
    "DEFAULT_SWING_ANGLE_RAD",
    "DEFAULT_TORQUE_NM",
    "IMPACT_MODELS",
    "ImpactModel",
    "SweetSpot",
    "Swing",
    "SwingResult",
    "arm_from_anthropometry",
    "axis_swings",
    "predict_swing",
    "sweet_spot_table",
    "sweet_spots",
]

log = logging.getLogger(__name__)

ImpactModel = Literal["approximate", "transient"]
IMPACT_MODELS: tuple[str, ...] = get_args(ImpactModel)

# Dempster's segment parameters as tabulated by Winter (Table 4.1, Fig. 4.1).
ARM_MASS_FRACTION = 0.050
"""Whole arm (upper arm + forearm + hand) mass / body mass."""
ARM_GYRATION_FRACTION = 0.645
"""Radius of gyration of the whole arm about the shoulder / shoulder–wrist length."""
UPPER_ARM_LENGTH_FRACTION = 0.186
"""Shoulder–elbow length / body height."""
FOREARM_LENGTH_FRACTION = 0.146
"""Elbow–wrist length / body height."""
HAND_LENGTH_FRACTION = 0.108
"""Wrist–fingertip length / body height."""
HAND_CENTRE_FRACTION = 0.506
"""Hand's centre of mass from the wrist / hand length."""
PAPER_GRIP_M = 0.070
"""Grip axis from the butt, where the hand holds the racket (paper, section 3.3)."""
DEFAULT_BODY_MASS_KG = 70.0
DEFAULT_HEIGHT_M = 1.75

DEFAULT_TORQUE_NM = 56.9
"""Constant shoulder torque of Kawazoe's forehand (ACMD 2002), N·m."""
DEFAULT_SWING_ANGLE_RAD = 0.5 * math.pi
"""Swing angle from rest to impact, rad (assumption: a quarter turn)."""


def arm_from_anthropometry(
    body_mass_kg: float = DEFAULT_BODY_MASS_KG,
    height_m: float = DEFAULT_HEIGHT_M,
    grip_m: float = PAPER_GRIP_M,
) -> tuple[float, float, float]:
    """The arm of a player from Dempster's segment parameters (Winter, Table 4.1, Fig. 4.1).

    Parameters
    ----------
    body_mass_kg : float
        Body mass, kg.
    height_m : float
        Body height, m.
    grip_m : float
        Where the hand holds the racket, m from the butt (the hand's centre of mass sits there).

    Returns
    -------
    arm_mass_kg : float
        Whole arm, hand included, kg (5.0 % of the body mass).
    arm_gyration_m : float
        Radius of gyration of the arm about the shoulder, m (0.645 of the shoulder–wrist
        length, 0.332 H).
    axis_to_butt_m : float
        Shoulder to butt along a straight arm in line with the racket, m: shoulder to wrist
        (0.332 H), wrist to the hand's centre of mass (0.506 × 0.108 H), less ``grip_m``.
    """
    mass = require_positive("body_mass_kg", body_mass_kg)
    height = require_positive("height_m", height_m)
    grip = require_positive("grip_m", grip_m, allow_zero=True)
    shoulder_to_wrist = (UPPER_ARM_LENGTH_FRACTION + FOREARM_LENGTH_FRACTION) * height
    shoulder_to_grip = shoulder_to_wrist + HAND_CENTRE_FRACTION * HAND_LENGTH_FRACTION * height
    if grip >= shoulder_to_grip:
        raise InputError(
            f"grip_m ({grip} m) must be shorter than the shoulder-to-grip distance "
            f"({shoulder_to_grip:.3f} m)"
        )
    return (
        ARM_MASS_FRACTION * mass,
        ARM_GYRATION_FRACTION * shoulder_to_wrist,
        shoulder_to_grip - grip,
    )


DEFAULT_ARM_MASS_KG, DEFAULT_ARM_GYRATION_M, DEFAULT_AXIS_TO_BUTT_M = arm_from_anthropometry()
"""The arm of a 70 kg, 1.75 m adult: 3.5 kg, 0.375 m about the shoulder, shoulder 0.607 m behind
the butt (:func:`arm_from_anthropometry`)."""


@dataclass(frozen=True)
class Swing:
    """A swing of arm and racket about an axis behind the butt (Kawazoe, ACMD 2002).

    Two forms.  The torque model (default): a constant shoulder torque turns arm and racket,
    rigidly joined, from rest through ``swing_angle_rad``, so ``½ I Ω² = T Δθ``.  The plain
    form: give ``angular_speed_radps`` and the torque, angle and arm are not used.

    Parameters
    ----------
    torque_nm : float
        Constant shoulder torque T, N·m (Kawazoe, ACMD 2002: 56.9).
    swing_angle_rad : float
        Angle turned from rest to impact Δθ, rad, in (0, 2π] (assumption: π/2).
    axis_to_butt_m : float
        Distance of the swing axis (the shoulder) behind the butt along the racket's long axis,
        m (arm + hand: 0.607 m, :func:`arm_from_anthropometry`).
    arm_mass_kg : float
        Mass of the arm, hand included, kg (3.5 kg: Dempster/Winter, 70 kg adult).  Zero: the
        racket alone.
    arm_gyration_m : float
        Radius of gyration of the arm about the shoulder, m (0.375 m: Dempster/Winter, 1.75 m
        adult); ``I_arm = arm_mass_kg · arm_gyration_m²``.
    angular_speed_radps : float or None
        If given, the angular speed Ω at impact, rad/s (zero or more), instead of the torque
        model.
    """

    torque_nm: float = DEFAULT_TORQUE_NM
    swing_angle_rad: float = DEFAULT_SWING_ANGLE_RAD
    axis_to_butt_m: float = DEFAULT_AXIS_TO_BUTT_M
    arm_mass_kg: float = DEFAULT_ARM_MASS_KG
    arm_gyration_m: float = DEFAULT_ARM_GYRATION_M
    angular_speed_radps: float | None = None

    def __post_init__(self) -> None:
        require_positive("swing torque_nm", self.torque_nm)
        angle = require_finite("swing swing_angle_rad", self.swing_angle_rad)
        if not 0.0 < angle <= 2.0 * math.pi:
            raise InputError(
                f"swing swing_angle_rad must be more than 0 and at most 2π rad, one turn "
                f"(got {self.swing_angle_rad!r})"
            )
        require_positive("swing axis_to_butt_m", self.axis_to_butt_m, allow_zero=True)
        require_positive("swing arm_mass_kg", self.arm_mass_kg, allow_zero=True)
        require_positive("swing arm_gyration_m", self.arm_gyration_m, allow_zero=True)
        if self.angular_speed_radps is not None:
            require_positive("swing angular_speed_radps", self.angular_speed_radps, allow_zero=True)

    @classmethod
    def for_player(
        cls,
        body_mass_kg: float = DEFAULT_BODY_MASS_KG,
        height_m: float = DEFAULT_HEIGHT_M,
        torque_nm: float = DEFAULT_TORQUE_NM,
        swing_angle_rad: float = DEFAULT_SWING_ANGLE_RAD,
        grip_m: float = PAPER_GRIP_M,
    ) -> Swing:
        """The torque-model swing of a player of a given build (:func:`arm_from_anthropometry`).

        Parameters
        ----------
        body_mass_kg, height_m : float
            Body mass (kg) and height (m).
        torque_nm : float
            Shoulder torque, N·m.
        swing_angle_rad : float
            Swing angle, rad.
        grip_m : float
            Where the hand holds the racket, m from the butt.
        """
        mass, gyration, axis = arm_from_anthropometry(body_mass_kg, height_m, grip_m)
        return cls(torque_nm, swing_angle_rad, axis, mass, gyration)

    @property
    def arm_inertia_kgm2(self) -> float:
        """Inertia of the arm about the shoulder, ``m k²``, kg·m²."""
        return self.arm_mass_kg * self.arm_gyration_m**2

    def racket_inertia_kgm2(self, racket: Racket) -> float:
        """Inertia of the racket about the swing axis, kg·m² (``I_G + M (x_G + d)²``)."""
        return racket.inertia_about_axis(-self.axis_to_butt_m)

    def inertia_kgm2(self, racket: Racket) -> float:
        """Inertia of arm and racket about the swing axis, kg·m²."""
        return self.arm_inertia_kgm2 + self.racket_inertia_kgm2(racket)

    def angular_speed(self, racket: Racket) -> float:
        """Angular speed Ω of arm and racket at impact, rad/s.

        Torque model: ``Ω = sqrt(2 T Δθ / I)`` from ``½ I Ω² = T Δθ``; else the given Ω.
        """
        if self.angular_speed_radps is not None:
            return float(self.angular_speed_radps)
        return math.sqrt(2.0 * self.torque_nm * self.swing_angle_rad / self.inertia_kgm2(racket))

    def impact_point_speed(self, racket: Racket, locations: ArrayLike) -> NDArray[np.float64]:
        """Speed of each point of the racket normal to the face, towards the ball, m/s.

        ``V = Ω (x + d)``: the distance from the swing axis (across the handle, ``d`` behind
        the butt) times the angular speed; the same for every y.

        Parameters
        ----------
        racket : Racket
            The racket swung.
        locations : array_like, shape (n, 2)
            Points (x, y) on the racket, m (0 ≤ x ≤ length).
        """
        xy = as_locations(locations, "impact points")
        off = np.flatnonzero((xy[:, 0] < 0.0) | (xy[:, 0] > racket.length_m))
        if off.size:
            i = int(off[0])
            raise InputError(
                f"impact point {i + 1} at x={xy[i, 0]:.4f} m is off the racket "
                f"(x from 0 to {racket.length_m} m)"
            )
        return np.asarray(self.angular_speed(racket) * (xy[:, 0] + self.axis_to_butt_m))

    def as_dict(self) -> dict[str, Any]:
        """The swing's parameters with unit-bearing keys (for run records)."""
        if self.angular_speed_radps is not None:
            return {
                "model": "angular speed",
                "angular_speed_radps": self.angular_speed_radps,
                "axis_to_butt_m": self.axis_to_butt_m,
            }
        return {
            "model": "constant shoulder torque (Kawazoe, ACMD 2002)",
            "torque_nm": self.torque_nm,
            "swing_angle_rad": self.swing_angle_rad,
            "axis_to_butt_m": self.axis_to_butt_m,
            "arm_mass_kg": self.arm_mass_kg,
            "arm_gyration_m": self.arm_gyration_m,
            "arm_inertia_kgm2": self.arm_inertia_kgm2,
        }

    def describe(self, racket: Racket) -> str:
        """One line for legends and tables."""
        omega = self.angular_speed(racket)
        if self.angular_speed_radps is not None:
            return f"Ω = {omega:.1f} rad/s"
        return (
            f"{self.torque_nm:g} N·m over {math.degrees(self.swing_angle_rad):.0f}°: "
            f"Ω = {omega:.1f} rad/s"
        )


_MERGED = (
    "stiffness",
    "peak_deflection",
    "contact_time",
    "mean_force",
    "peak_force",
    "vibration_energy",
    "cor",
    "rebound_ratio",
    "rebound_speed",
    "status",
    "mode_energy",
)


@dataclass(frozen=True, eq=False)
class SwingResult:
    """Impacts on a swinging racket: arrays shaped ``(n_points, n_speeds, n_supports)``.

    The fields of :class:`~racketdyn.impact.result.ImpactResult`, merged back into point order,
    with the racket speed given per point instead of per ball speed.

    Attributes
    ----------
    locations : ndarray (n_points, 2)
        Impact points (x, y), m.
    labels : tuple of str
        Point labels.
    ball_speed : ndarray (n_speeds,)
        Incoming ball speed towards the strings, m/s.
    racket_speed : ndarray (n_points,)
        Speed of each impact point towards the ball, ``Ω (x + d)``, m/s.
    supports : tuple of str
        Support conditions during the impact.
    swing : Swing
        The swing.
    angular_speed_radps : float
        Ω of the swing with this racket, rad/s.
    rebound_speed : ndarray
        Outgoing ball speed ``e v_ball + (1 + e) V_racket``, m/s, positive away from the
        strings.
    rebound_ratio, cor : ndarray
        Rebound ratio e and ball–racket COR e_r at the swing's approach speed.
    reduced_mass : ndarray (n_points, n_supports)
        Reduced mass at each point, kg (eq 4).
    stiffness, peak_deflection, contact_time, mean_force, peak_force, vibration_energy : ndarray
        As in :class:`~racketdyn.impact.result.ImpactResult` (N/m, m, s, N, N, J).
    mode_energy : ndarray (…, n_modes)
        Vibration energy per mode, J.
    status : ndarray of str
        ``ok`` or why the numbers are missing.
    modal_model : ModalModel or None
        Modes charged (None: rigid racket).
    inputs : dict
        What produced the result: the impact model's inputs plus ``swing`` (its parameters,
        Ω and the inertias).
    """

    locations: NDArray[np.float64]
    labels: tuple[str, ...]
    ball_speed: NDArray[np.float64]
    racket_speed: NDArray[np.float64]
    supports: tuple[str, ...]
    swing: Swing
    angular_speed_radps: float
    rebound_speed: NDArray[np.float64]
    rebound_ratio: NDArray[np.float64]
    cor: NDArray[np.float64]
    reduced_mass: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    peak_deflection: NDArray[np.float64]
    contact_time: NDArray[np.float64]
    mean_force: NDArray[np.float64]
    peak_force: NDArray[np.float64]
    vibration_energy: NDArray[np.float64]
    mode_energy: NDArray[np.float64]
    status: NDArray[np.str_]
    modal_model: ModalModel | None
    inputs: dict[str, Any]

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(n_points, n_speeds, n_supports)``."""
        return (self.locations.shape[0], self.ball_speed.size, len(self.supports))

    def support_index(self, support: str) -> int:
        """Index of a support on the last axis."""
        one_of("support", support, self.supports)
        return self.supports.index(support)

    @property
    def columns(self) -> dict[str, NDArray[Any]]:
        """The ``impact.csv`` table: column name → 1-D array, one row per point × speed ×
        support (``pandas.DataFrame(result.columns)`` works).

        ``racket_speed_mps`` is each point's own; ``energy_<mode>_j`` columns follow.
        """
        return impact_columns(self, self.racket_speed[:, None, None])

    def __repr__(self) -> str:
        n, s, p = self.shape
        rows = "; ".join(f"{key} {value}" for key, value in summary_rows(self)[1:])
        return f"<SwingResult {n} points × {s} ball speeds × {p} supports: {rows}>"

    def _repr_html_(self) -> str:
        return html_table("SwingResult", summary_rows(self))

    def write_csv(self, path: Path) -> None:
        """Write the ``impact.csv`` columns (racket speed per point), NaN where not ``ok``."""
        write_columns(path, self.columns)


Predictor = Callable[..., ImpactResult]


def _predict_transient(*args: Any, **kwargs: Any) -> ImpactResult:
    """:func:`racketdyn.impact.transient.predict_transient`, imported when a swing runs it: the
    transient model brings numba (≈ 0.2 s), which an approximate run never needs."""
    from racketdyn.impact.transient import predict_transient

    return predict_transient(*args, **kwargs)


PREDICTORS: dict[str, Predictor] = {"approximate": predict, "transient": _predict_transient}
"""The impact models a swing can use, by name."""


def _prepared(
    racket: Racket,
    ball: Ball,
    modal_model: ModalModel | Literal["racket"] | None,
    kwargs: dict[str, Any],
) -> tuple[ModalModel | None, dict[str, Any]]:
    """Resolve the racket's modal model and the compound law once, for many predictor calls."""
    # string-bed modes kept here: each predictor drops them itself (include_string_bed)
    model = resolve_modal_model(racket, modal_model, include_string_bed=True)
    options = dict(kwargs)
    if options.get("law") is None and options.get("string_bed", "uniform") == "uniform":
        options["law"] = compound_law(racket, ball)
    return model, options


def predict_swing(
    racket: Racket,
    ball: Ball,
    locations: ArrayLike,
    ball_speed: ArrayLike,
    swing: Swing,
    supports: Sequence[str] | str = "pinned",
    model: ImpactModel = "approximate",
    modal_model: ModalModel | Literal["racket"] | None = "racket",
    labels: Sequence[str] | None = None,
    **kwargs: Any,
) -> SwingResult:
    """Impacts on a swinging racket: outgoing ball speed at every point for every ball speed.

    Each point moves towards the ball at ``Ω (x + d)`` (:meth:`Swing.impact_point_speed`); the
    impact model runs once per group of points with the same racket speed, and the results are
    merged back into point order.

    Parameters
    ----------
    racket : Racket
        The racket swung.
    ball : Ball
        The ball.
    locations : array_like, shape (n, 2)
        Impact points (x, y) on the string bed, m.
    ball_speed : array_like, shape (s,)
        Incoming ball speed towards the strings, m/s.
    swing : Swing
        The swing (torque model or angular speed).
    supports : str or sequence of str
        Support conditions during the impact (default ``pinned``: the hand-held model); one
        text of comma-separated names too.
    model : {"approximate", "transient"}
        Impact model: :func:`racketdyn.impact.predict` or
        :func:`racketdyn.impact.transient.predict_transient`.
    modal_model : ModalModel, None or "racket"
        Flexible modes (``None``: rigid racket); ``"racket"`` is resolved once for all points.
    labels : sequence of str, optional
        Point labels (default 1, 2, …).
    **kwargs
        Passed to the impact model (``law``, ``string_bed``, ``include_string_bed``,
        ``stiffness_reading``,
        ``rtol`` …).

    Returns
    -------
    SwingResult
        Arrays shaped ``(n_points, n_speeds, n_supports)``.  Impacts without a valid number
        (status not ``ok``) are counted in one warning for the whole swing.
    """
    result = _predict_swing(
        racket, ball, locations, ball_speed, swing, supports, model, modal_model, labels, kwargs
    )
    for message in np.unique(result.status[result.status != STATUS_OK]):
        count = int(np.sum(result.status == message))
        log.warning(
            "%d of %d impacts: %s (their results are NaN)", count, result.status.size, message
        )
    return result


def _predict_swing(
    racket: Racket,
    ball: Ball,
    locations: ArrayLike,
    ball_speed: ArrayLike,
    swing: Swing,
    supports: Sequence[str] | str,
    model: str,
    modal_model: ModalModel | Literal["racket"] | None,
    labels: Sequence[str] | None,
    kwargs: dict[str, Any],
) -> SwingResult:
    """:func:`predict_swing` without the status warning."""
    if not isinstance(swing, Swing):
        raise InputError(f"swing must be a Swing (got {type(swing).__name__})")
    one_of("model", model, IMPACT_MODELS)
    xy = as_locations(locations, "impact points")
    if xy.shape[0] == 0:
        raise InputError("impact points: give at least one point")
    racket.head.check_inside(xy)
    point_labels = (
        tuple(labels) if labels is not None else tuple(str(i + 1) for i in range(len(xy)))
    )
    if len(point_labels) != len(xy):
        raise InputError(f"{len(point_labels)} labels given for {len(xy)} impact points")
    resolved, options = _prepared(racket, ball, modal_model, kwargs)
    omega = swing.angular_speed(racket)
    speeds = swing.impact_point_speed(racket, xy)
    predictor = PREDICTORS[model]

    groups, inverse = np.unique(speeds, return_inverse=True)
    log.info("swing Ω = %.3f rad/s: %d points in %d racket speeds", omega, len(xy), groups.size)
    merged: dict[str, NDArray[Any]] = {}
    reduced: NDArray[np.float64] | None = None
    first: ImpactResult | None = None
    for g, speed in enumerate(groups):
        index = np.flatnonzero(inverse == g)
        with status_warnings_held(predictor.__module__):
            part = predictor(
                racket,
                ball,
                xy[index],
                ball_speed,
                supports,
                racket_speed=float(speed),
                modal_model=resolved,
                labels=[point_labels[i] for i in index],
                **options,
            )
        if first is None:
            first = part
            reduced = np.full((len(xy), part.reduced_mass.shape[1]), np.nan)
            for name in _MERGED:
                value = np.asarray(getattr(part, name))
                dtype = object if name == "status" else value.dtype
                merged[name] = np.empty((len(xy), *value.shape[1:]), dtype=dtype)
        assert reduced is not None
        reduced[index] = part.reduced_mass
        for name in _MERGED:
            merged[name][index] = np.asarray(getattr(part, name))
    assert first is not None
    assert reduced is not None
    merged["status"] = status_text(merged["status"])

    inputs = dict(first.inputs)
    inputs["swing"] = {
        **swing.as_dict(),
        "angular_speed_radps": omega,
        "racket_inertia_about_axis_kgm2": swing.racket_inertia_kgm2(racket),
        "inertia_about_axis_kgm2": swing.inertia_kgm2(racket),
        "racket_speed": "Ω (x + axis_to_butt_m) at each point",
    }
    inputs["impact_model"] = model
    return SwingResult(
        locations=xy,
        labels=point_labels,
        ball_speed=first.ball_speed,
        racket_speed=speeds,
        supports=first.supports,
        swing=swing,
        angular_speed_radps=omega,
        reduced_mass=reduced,
        modal_model=first.modal_model,
        inputs=inputs,
        **merged,
    )


@dataclass(frozen=True)
class SweetSpot:
    """A named sweet spot of a racket and where it lies.

    Attributes
    ----------
    name : str
        Label for plots and tables.
    x_m, y_m : float
        Location, m (x from the butt, y across the long axis).
    on_face : bool
        True if the point lies on the string bed.
    value : float or None
        The quantity maximised (rebound ratio, or outgoing ball speed in m/s); None for the
        geometric points.
    definition : str
        What the point is.
    """

    name: str
    x_m: float
    y_m: float
    on_face: bool
    value: float | None
    definition: str

    @property
    def location(self) -> tuple[float, float]:
        """``(x, y)``, m."""
        return (self.x_m, self.y_m)


def _first_bending_mode(model: ModalModel) -> int | None:
    """The lowest bending mode (kind ``bending``; else the lowest ``other``, else ``unknown``)."""
    for kind in ("bending", "other", "unknown"):
        candidates = [k for k, name in enumerate(model.kinds) if name == kind]
        if candidates:
            return min(candidates, key=lambda k: float(model.frequency[k]))
    return None


def _axis_maximum(
    evaluate: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    x: NDArray[np.float64],
) -> tuple[float, float]:
    """Largest value of ``evaluate`` along x: the best sample, refined between its neighbours."""
    values = evaluate(x)
    if not np.any(np.isfinite(values)):
        raise InputError(
            "no valid rebound anywhere on the long axis at this ball speed (see the status of "
            "predict); lower the ball speed"
        )
    i = int(np.nanargmax(values))
    low, high = x[max(i - 1, 0)], x[min(i + 1, x.size - 1)]

    def negative(z: float) -> float:
        value = float(evaluate(np.array([z]))[0])
        return -value if math.isfinite(value) else math.inf

    found = minimize_scalar(negative, bounds=(low, high), method="bounded", options={"xatol": 1e-6})
    if found.success and -found.fun >= values[i]:
        return float(found.x), float(-found.fun)
    return float(x[i]), float(values[i])


def sweet_spots(
    racket: Racket,
    ball: Ball,
    swing: Swing,
    ball_speed: float = 20.0,
    support: str = "pinned",
    model: ImpactModel = "approximate",
    modal_model: ModalModel | Literal["racket"] | None = "racket",
    n_axis: int = 81,
    **kwargs: Any,
) -> dict[str, SweetSpot]:
    """The racket's named sweet spots and where they lie.

    Keys, each a :class:`SweetSpot`:

    ``centre_of_percussion_swing``
        Centre of percussion of the racket about the swing axis (d behind the butt),
        ``x = −d + I_axis / (M (x_G + d))``: an impact there gives the racket no reaction at
        the axis.  Of the racket alone; the arm is not included.
    ``centre_of_percussion_grip``
        The same about the grip (``racket.grip_m``, the paper's 70 mm).
    ``first_mode_node``
        Node of the first (2-node) bending mode on the face along the long axis (no vibration
        of that mode); absent for a rigid racket or if the node is off the face.
    ``max_rebound_ratio``
        Largest rebound ratio on the long axis, racket at rest, at ``ball_speed``.
    ``max_rebound_speed``
        Largest outgoing ball speed on the long axis for the swing, at ``ball_speed``.

    The maxima are searched on ``n_axis`` points along the long axis (y = the head's centre
    line; the maxima of a symmetric racket lie on it), inset half a step from the frame, then
    refined between the best sample's neighbours to 1 µm.  A maximum at the first or last
    sample is at the end of the string bed.

    Parameters
    ----------
    racket, ball : Racket, Ball
        Racket and ball.
    swing : Swing
        The swing.
    ball_speed : float
        Incoming ball speed, m/s.
    support : str
        Support during the impact (default ``pinned``).
    model : {"approximate", "transient"}
        Impact model.
    modal_model : ModalModel, None or "racket"
        Flexible modes (None: rigid racket: no node).
    n_axis : int
        Samples along the long axis for the maxima (at least 3).
    **kwargs
        Passed to the impact model.
    """
    require_whole("n_axis", n_axis, least=3)
    speed = require_positive("ball_speed", ball_speed)
    one_of("model", model, IMPACT_MODELS)
    if not isinstance(support, str):
        raise InputError(f"support must be one support name (got {support!r})")
    resolved, options = _prepared(racket, ball, modal_model, kwargs)
    head = racket.head
    y0 = head.centre_y_m
    spots: dict[str, SweetSpot] = {}

    def spot(name: str, x: float, value: float | None, definition: str) -> SweetSpot:
        on_face = bool(head.contains((x, y0))[0])
        return SweetSpot(name, float(x), float(y0), on_face, value, definition)

    def searched(definition: str, x_best: float) -> str:
        if x_best <= x[0] + 1e-6 or x_best >= x[-1] - 1e-6:
            definition += "; at the end of the axis searched: the maximum lies at the frame"
        return definition

    d = swing.axis_to_butt_m
    spots["centre_of_percussion_swing"] = spot(
        "centre of percussion (swing axis)",
        racket.centre_of_percussion_m(-d),
        None,
        f"racket about the swing axis {d * 1e3:.0f} mm behind the butt: no reaction at the axis",
    )
    spots["centre_of_percussion_grip"] = spot(
        "centre of percussion (grip)",
        racket.centre_of_percussion_m(),
        None,
        f"racket about the grip {racket.grip_m * 1e3:.0f} mm from the butt: no reaction at the "
        "grip",
    )
    mode = _first_bending_mode(resolved) if resolved is not None else None
    if resolved is not None and mode is not None:
        nodes = axis_nodes(resolved, mode, (head.throat_x_m, head.tip_x_m), y_m=y0)
        name = resolved.names[mode]
        if nodes.size:
            spots["first_mode_node"] = spot(
                "first-mode node",
                float(nodes[0]),
                None,
                f"node of the {name} mode ({resolved.frequency[mode]:.0f} Hz) on the long "
                "axis: no vibration of that mode",
            )
        else:
            log.info("the %s mode has no node on the face", name)

    step = 2.0 * head.half_length_m / n_axis
    x = np.asarray(head.throat_x_m + step * (np.arange(n_axis) + 0.5), dtype=np.float64)
    rest = Swing(angular_speed_radps=0.0, axis_to_butt_m=d)

    def profile(
        which: Swing, quantity: str
    ) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
        def evaluate(z: NDArray[np.float64]) -> NDArray[np.float64]:
            result = _predict_swing(
                racket,
                ball,
                np.column_stack([z, np.full_like(z, y0)]),
                [speed],
                which,
                support,
                model,
                resolved,
                None,
                options,
            )
            return np.asarray(getattr(result, quantity)[:, 0, 0], dtype=float)

        return evaluate

    x_ratio, best_ratio = _axis_maximum(profile(rest, "rebound_ratio"), x)
    spots["max_rebound_ratio"] = spot(
        "maximum rebound ratio",
        x_ratio,
        best_ratio,
        searched(
            f"largest rebound ratio on the long axis, racket at rest, ball at {speed:g} m/s "
            f"({support})",
            x_ratio,
        ),
    )
    x_speed, best_speed = _axis_maximum(profile(swing, "rebound_speed"), x)
    spots["max_rebound_speed"] = spot(
        "maximum outgoing speed",
        x_speed,
        best_speed,
        searched(
            f"largest outgoing ball speed on the long axis for the swing "
            f"({swing.describe(racket)}), ball at {speed:g} m/s ({support})",
            x_speed,
        ),
    )
    return spots


def sweet_spot_table(spots: Mapping[str, SweetSpot]) -> list[dict[str, Any]]:
    """Rows for a table or CSV: key, name, x_m, y_m, on_face, value, definition."""
    return [
        {
            "key": key,
            "name": s.name,
            "x_m": s.x_m,
            "y_m": s.y_m,
            "on_face": s.on_face,
            "value": s.value,
            "definition": s.definition,
        }
        for key, s in spots.items()
    ]


AXIS_SWING_FACTORS = (0.5, 1.0, 1.5)
"""Multiples of the run's swing (its angle, or Ω) that the along-axis figure compares."""


def axis_swings(swing: Swing) -> list[tuple[str, Swing]]:
    """The swings the along-axis figure compares, each with its legend name.

    The racket at rest (Ω = 0, the paper's Fig. 15), then half, the same and one and a half
    times the swing: the swing angle for the torque model (angles above one turn left out), Ω
    for a swing given by its angular speed.

    Parameters
    ----------
    swing : Swing
        The swing of the run.
    """
    swings = [
        ("racket at rest", Swing(angular_speed_radps=0.0, axis_to_butt_m=swing.axis_to_butt_m))
    ]
    for factor in AXIS_SWING_FACTORS:
        if swing.angular_speed_radps is not None:
            omega = factor * swing.angular_speed_radps
            swings.append((f"Ω = {omega:.1f} rad/s", replace(swing, angular_speed_radps=omega)))
        elif factor * swing.swing_angle_rad <= 2.0 * math.pi:
            angle = factor * swing.swing_angle_rad
            swings.append(
                (
                    f"{swing.torque_nm:g} N·m over {math.degrees(angle):.0f}°",
                    replace(swing, swing_angle_rad=angle),
                )
            )
    return swings
