"""The grid of impacts both impact models work on: validated once, in one place.

:func:`impact_grid` checks the points, supports, speeds and labels a user gives, resolves the
modal model and the compound law, and computes the reduced masses — everything the
approximate method (:mod:`~racketdyn.impact.approximate`) and the transient simulation
(:mod:`~racketdyn.impact.transient`) share before they differ.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Any, Literal, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.__about__ import __version__
from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law, local_compound_law, with_ball_string_cor
from racketdyn.errors import InputError, one_of, require_speeds, require_words
from racketdyn.impact.hand import Hand
from racketdyn.modal import ModalModel
from racketdyn.racket import SUPPORTS, Racket, as_locations
from racketdyn.racket_modal import modal_model_for
from racketdyn.racket_modal.shapes import frame_under_bed

__all__ = [
    "STRING_BEDS",
    "ImpactGrid",
    "StringBed",
    "ball_reaches_frame",
    "check_string_bed",
    "check_supports",
    "impact_grid",
    "point_law",
    "predict_by_point_law",
    "resolve_modal_model",
    "status_warnings_held",
    "support_reduced_mass",
]

log = logging.getLogger(__name__)

StringBed = Literal["uniform", "local"]
STRING_BEDS: tuple[str, ...] = get_args(StringBed)
"""The string bed's law over the face: ``uniform``, the face centre's law at every point (the
paper's one law, :func:`racketdyn.contact.compound_law`), or ``local``, each point's own from
the lengths of its main and cross strings (:func:`racketdyn.contact.local_compound_law`)."""

LOCAL_LAW_RECORD = (
    "per point: ball + local string bed in series (racketdyn.contact.local_compound_law, "
    "Kawazoe's law per string with the lengths of the main and cross strings through the point)"
)
"""What ``inputs["compound_law"]`` says when every point has its own law."""


def check_supports(
    supports: Sequence[str] | str, allowed: Sequence[str] = SUPPORTS
) -> tuple[str, ...]:
    """Support names as a tuple: a sequence, or one text of one or several comma-separated
    names (``"free,pinned"``, the command line's spelling, as the options objects take it),
    each known, each once (InputError).

    ``allowed`` is the impact model's supports (the transient model adds ``hand``).
    """
    given = require_words("support", supports) if isinstance(supports, str) else supports
    names = tuple(given)
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
    the whole impulse (trial of 2026-11-23: every row flagged).  At points on the strings a
    measured model's shapes are the frame's motion under the bed
    (:func:`racketdyn.racket_modal.shapes.frame_under_bed`): the strings' own give is the
    ball-string law's.
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
        model.require_mass_normalised("an impact model")  # vibration energy needs 1/√kg
        model = frame_under_bed(
            model.flexible_modes if include_string_bed else model.frame_modes, racket.head
        )
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
    ball : Ball
        The ball, its e_BG resolved (:func:`racketdyn.contact.with_ball_string_cor`: given, or
        from ball + strings).
    """

    locations: NDArray[np.float64]
    labels: tuple[str, ...]
    supports: tuple[str, ...]
    ball_speed: NDArray[np.float64]
    racket_speed: NDArray[np.float64]
    reduced_mass: NDArray[np.float64]
    model: ModalModel | None
    law: RestoringForce
    ball: Ball
    edge_distance: NDArray[np.float64]

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(n_points, n_speeds, n_supports)``."""
        return (self.locations.shape[0], self.ball_speed.size, len(self.supports))

    def reaches_frame(self, peak_deflection: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Where the ball, pressed into the strings, reaches the hoop: a frame shot.

        A ball of radius R whose centre has come X_p towards the racket from first touch
        (the compound deflection: ball and strings) cuts the plane of the strings in a circle
        of radius ``sqrt(2 R X_p - X_p²)`` (R at most); where that passes the point's distance
        to the bed's edge the ball meets the frame.  The plane of the strings is the lowest a
        frame can stand, so this is a lower bound on frame shots.

        Parameters
        ----------
        peak_deflection : ndarray
            ``(n_points, n_speeds, n_supports)`` peak compound deflection X_p, m (NaN: not
            known, never marked).

        Returns
        -------
        ndarray of bool
            True where the ball reaches the frame.
        """
        return ball_reaches_frame(
            peak_deflection, 0.5 * self.ball.diameter_m, self.edge_distance[:, None, None]
        )

    def inputs(self, ball: Ball, method: str, **extra: Any) -> dict[str, Any]:
        """What produced a result, for ``ImpactResult.inputs`` and run records."""
        return {
            "racketdyn_version": __version__,
            "method": method,
            **extra,
            "string_bed": "uniform",
            "ball": {
                "mass_kg": ball.mass_kg,
                "diameter_m": ball.diameter_m,
                "e_bg": self.ball.e_bg,
                "e_bg_law": self.ball.e_bg_record(),
                "restoring_force": ball.restoring_force.as_dict(),
            },
            "compound_law": self.law.as_dict(),
            "modal_model": None if self.model is None else modal_record(self.model),
        }


def modal_record(model: ModalModel) -> dict[str, Any]:
    """A charged model's run record: its summary and what its shapes on the strings are
    (:func:`racketdyn.racket_modal.shapes.frame_under_bed`)."""
    record = model.summary()
    if "shapes_on_strings" in model.metadata:
        record["shapes_on_strings"] = model.metadata["shapes_on_strings"]
    return record


# 12 parameters: predict's inputs of an impact as it takes them, plus the model's allowed
# supports and its hand; no object of them reads better for its callers (predict, predict_transient)
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
        ball=with_ball_string_cor(racket, ball),
        edge_distance=racket.head.distance_to_edge(xy),
    )


def ball_reaches_frame(
    peak_deflection: NDArray[np.float64], radius: float, edge_distance: NDArray[np.float64]
) -> NDArray[np.bool_]:
    """Where a ball of ``radius`` (m) pressed ``peak_deflection`` (m, NaN: never marked) into
    the strings cuts their plane in a circle wider than the point's ``edge_distance`` (m,
    broadcast against the deflections): :meth:`ImpactGrid.reaches_frame` on any array."""
    x = np.clip(np.nan_to_num(peak_deflection, nan=0.0), 0.0, radius)
    section = np.sqrt(2.0 * radius * x - x * x)
    return np.asarray(section > edge_distance)


class _HoldWarnings(logging.Filter):
    """Drop WARNING records: the per-call status counts, summed once by the caller."""

    def filter(self, record: logging.LogRecord) -> bool:
        return record.levelno != logging.WARNING


@contextmanager
def status_warnings_held(name: str) -> Iterator[None]:
    """Hold the WARNING records of logger ``name`` (an impact model's per-call status counts)
    while a caller that calls it many times sums them itself."""
    logger = logging.getLogger(name)
    hold = _HoldWarnings()
    logger.addFilter(hold)
    try:
        yield
    finally:
        logger.removeFilter(hold)


@lru_cache(maxsize=8192)
def _cached_local_law(racket: Racket, ball: Ball, x: float, y: float) -> RestoringForce:
    return local_compound_law(racket, ball, (x, y))


def point_law(racket: Racket, ball: Ball, location: ArrayLike) -> RestoringForce:
    """The compound law at one point of the face (:func:`racketdyn.contact.local_compound_law`),
    cached per racket, ball and point.

    The head is symmetric about its long axis, so a point and its mirror image share one law
    (the same object): ±y give the same numbers to the last bit.

    Parameters
    ----------
    racket, ball : Racket, Ball
        The racket (head outline, strings) and the ball (diameter, restoring force).
    location : array_like (2,)
        Impact point (x, y), m.
    """
    x, y = (float(v) for v in np.asarray(location, dtype=float).reshape(2))
    centre = racket.head.centre_y_m
    return _cached_local_law(racket, ball, x, centre + abs(y - centre))


def predict_by_point_law(
    predictor: Callable[..., Any],
    racket: Racket,
    ball: Ball,
    locations: ArrayLike,
    labels: Sequence[str] | None,
    modal_model: ModalModel | Literal["racket"] | None,
    include_string_bed: bool,
    **options: Any,
) -> Any:
    """Run an impact model with each point's own string-bed law (``string_bed="local"``).

    The model runs once per run of consecutive points sharing a law (:func:`point_law`), with
    that law and the modal model resolved once, and the parts are joined in point order
    (:meth:`racketdyn.impact.result.ImpactResult.concatenate`).  ``inputs`` records
    ``string_bed = "local"``.

    Parameters
    ----------
    predictor : callable
        :func:`racketdyn.impact.predict` or
        :func:`racketdyn.impact.transient.predict_transient` (called with ``law`` and
        ``string_bed="uniform"``).
    racket, ball, locations, labels, modal_model, include_string_bed, **options
        As for the predictor (``options`` holds the speeds, supports and the rest).
    """
    from racketdyn.impact.result import ImpactResult

    xy = as_locations(locations, "impact points")
    if xy.shape[0] == 0:
        raise InputError("impact points: give at least one point")
    racket.head.check_inside(xy)
    names = tuple(labels) if labels is not None else tuple(str(i + 1) for i in range(len(xy)))
    if len(names) != len(xy):
        raise InputError(f"{len(names)} labels given for {len(xy)} impact points")
    model = resolve_modal_model(racket, modal_model, include_string_bed)
    laws = [point_law(racket, ball, point) for point in xy]
    parts = []
    start = 0
    with status_warnings_held(predictor.__module__):  # one count per status, below
        while start < len(xy):
            stop = start + 1
            while stop < len(xy) and laws[stop] is laws[start]:
                stop += 1
            parts.append(
                predictor(
                    racket,
                    ball,
                    xy[start:stop],
                    labels=names[start:stop],
                    modal_model=model,
                    include_string_bed=include_string_bed,
                    law=laws[start],
                    string_bed="uniform",
                    **options,
                )
            )
            start = stop
    joined = ImpactResult.concatenate(parts)
    status = np.asarray(joined.status)
    for message in np.unique(status[status != "ok"]):
        log.warning(
            "%d of %d impacts: %s (their results are NaN)",
            int(np.sum(status == message)), status.size, message,
        )  # fmt: skip
    inputs = {**joined.inputs, "string_bed": "local", "compound_law": LOCAL_LAW_RECORD}
    return replace(joined, inputs=inputs)


def check_string_bed(string_bed: str, law: RestoringForce | None, racket: Racket) -> None:
    """``string_bed`` is one of :data:`STRING_BEDS`; ``local`` takes no ``law`` and needs the
    strings' construction (InputError)."""
    one_of("string_bed", string_bed, STRING_BEDS)
    if string_bed == "local":
        if law is not None:
            raise InputError(
                "string_bed 'local' makes each point's law: give law or string_bed='local', "
                "not both"
            )
        file = racket.strings.load_deflection_file
        if file is not None:
            raise InputError(
                f"`string_bed` local needs the strings' construction; the racket's string bed is "
                f"a measured load-deflection file ({file.name}), a law at one point: use "
                "`string_bed` uniform"
            )
