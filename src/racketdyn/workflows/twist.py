"""Step ``twist``: the racket's roll and twist at separation and the outgoing ball speed
against the offset from the long axis (transient model).

Writes ``twist.csv`` (:data:`TWIST_COLUMNS`) and ``run.json``; the figure comes from the
caller's hook.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from racketdyn.errors import InputError, require_finite, require_positive
from racketdyn.impact.grid import check_string_bed
from racketdyn.impact.transient import TRANSIENT_SUPPORTS
from racketdyn.impact.twist import TwistCurve, twist_curve
from racketdyn.io import racket_to_dict
from racketdyn.plausibility import check_speeds
from racketdyn.racket import Racket, landmark_points
from racketdyn.workflows.figure_data import defer_figure_data
from racketdyn.workflows.inputs import supports_named
from racketdyn.workflows.run import (
    StepResult,
    report,
    run_step,
    write_rows,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

__all__ = ["TWIST_COLUMNS", "TWIST_OFFSETS_M", "TwistResult", "run_twist"]

TWIST_OFFSETS_M = (-0.08, -0.06, -0.04, -0.02, 0.0, 0.02, 0.04, 0.06, 0.08)
"""Default offsets from the long axis, m."""

TWIST_COLUMNS = (
    "support",
    "x_m",
    "y_m",
    "ball_speed_mps",
    "racket_speed_mps",
    "roll_angle_rad",
    "roll_rate_radps",
    "flexible_twist_rad",
    "total_twist_rad",
    "rebound_speed_mps",
    "rebound_ratio",
    "contact_time_s",
    "status",
)
"""Columns of ``twist.csv``, one row per support × offset (``y_m``: the offset from the long
axis); the fields of :class:`~racketdyn.impact.twist.TwistCurve`."""


@dataclass
class TwistResult(StepResult):
    """What :func:`run_twist` computed and wrote.

    Attributes
    ----------
    curves : list of TwistCurve
        One curve per support.
    racket : Racket
        The racket.
    offsets : list of float
        Offsets from the long axis, m.
    """

    curves: list[TwistCurve] = field(default_factory=list)
    racket: Racket | None = None
    offsets: list[float] = field(default_factory=list)


@run_step
def run_twist(
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    *,
    x_m: float | None = None,
    offsets_m: ArrayLike = TWIST_OFFSETS_M,
    speed: float = 25.0,
    racket_speed: float = 0.0,
    supports: str | Sequence[str] = ("free",),
) -> TwistResult:
    """Impacts across the face at one x, one curve per support; write the run folder.

    Parameters
    ----------
    out : path
        Output folder (created if missing).
    setup : Setup
        Racket, modes, ball, hand, string bed (the face centre's law or each offset's own),
        checks and the run (:class:`~racketdyn.workflows.setup.Setup`).
    x_m : float, optional
        Impact position from the butt, m (default: the racket's face centre,
        :func:`racketdyn.racket.landmark_points`).
    offsets_m : array_like
        Offsets y from the long axis, m.
    speed : float
        Incoming ball speed, m/s.
    racket_speed : float
        Racket speed towards the ball, m/s.
    supports : sequence of str
        ``free``, ``pinned``, ``hand`` (one curve each).
    """
    x = None if x_m is None else require_positive("`x_m`", x_m)
    offsets = [require_finite("`offsets_m`", v) for v in np.atleast_1d(offsets_m)]
    speed = require_positive("`speed`", speed)
    racket_speed = require_finite("`racket_speed`", racket_speed)
    check_speeds("`speed`", [speed], "ball_speed_mps", setup.allow_implausible)
    check_speeds("`racket_speed`", [racket_speed], "racket_speed_mps", setup.allow_implausible)
    checked = supports_named(supports, TRANSIENT_SUPPORTS)
    used = setup.racket_setup()
    head = used.racket.head
    centre: list[str] = []
    if x is None:  # the given racket's face centre (issue 27: it was the paper racket's 0.52 m)
        x = float(landmark_points(used.racket)["centre"][0])
        centre = [f"impact point x: the face centre, {x * 1e3:.0f} mm from the butt"]
    wide = [y for y in offsets if abs(y - head.centre_y_m) > head.half_width_m]
    if wide and all(abs(y) >= 1.0 and abs(y * 1e-3) <= head.half_width_m for y in wide):
        raise InputError(
            f"`offsets_m`: y={wide[0]:g} m is wider than the string bed (half-width "
            f"{head.half_width_m:.4f} m); did you give millimetres? (give metres)"
        )
    head.check_inside(
        np.column_stack([np.full(len(offsets), x), offsets]), "impact point (`x_m`, `offsets_m`)"
    )
    check_string_bed(setup.string_bed, None, used.racket)
    the_hand, hand_defaults = setup.hand_used(checked)
    the_ball, ball_defaults = setup.ball_used()
    defaults_used = [*used.defaults, *centre, *hand_defaults, *ball_defaults, *setup.defaults]
    curves = []
    for i, support in enumerate(checked):
        report(
            setup.progress,
            f"twist against offset, {support} ({len(offsets)} impacts)",
            i,
            len(checked),
        )
        curves.append(
            twist_curve(
                used.racket,
                the_ball,
                x,
                offsets,
                speed,
                support,
                racket_speed,
                used.modal_model,
                the_hand,
                setup.string_bed,
            )
        )
    out_dir = Path(out)
    rows = [
        {
            "support": c.support,
            "x_m": c.x_m,
            "y_m": float(c.offsets_m[i]),
            "ball_speed_mps": c.ball_speed_mps,
            "racket_speed_mps": c.racket_speed_mps,
            **{name: float(getattr(c, name)[i]) for name in TWIST_COLUMNS[5:-1]},
            "status": str(c.status[i]),
        }
        for c in curves
        for i in range(c.offsets_m.size)
    ]
    result = TwistResult(
        out_dir,
        [write_rows(out_dir / "twist.csv", rows)],
        curves=curves,
        racket=used.racket,
        offsets=offsets,
    )
    defer_figure_data(result, {"curves": curves})
    model = used.modal_model
    inputs = {
        **used.provenance,
        "racket": racket_to_dict(used.racket),
        "x_m": x,
        "offsets_m": offsets,
        "ball_speed_mps": speed,
        "racket_speed_mps": racket_speed,
        "supports": checked,
        "rigid": setup.rigid,
        "string_bed": setup.string_bed,
        "defaults_used": defaults_used,
        "method": "transient simulation, reference engine (racketdyn.impact.twist."
        "twist_curve): roll and section rotation of the modes at separation",
        "modal_model": None if model is None else model.summary(),
        "hand": None if the_hand is None else asdict(the_hand),
        "columns": {"twist.csv": list(TWIST_COLUMNS)},
    }
    return setup.finish(result, inputs, "twist")
