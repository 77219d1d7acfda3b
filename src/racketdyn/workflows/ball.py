"""Step ``ball``: the ball's bounce on a rigid surface and on head-clamped strings (issue 22).

Writes ``ball.csv`` (:data:`racketdyn.impact.bounce.BALL_COLUMNS`), ``ball.nc`` (the bounces
and their force–compression loops, the data the figure draws) and ``run.json``; the figure
comes from the caller's hook.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from racketdyn.ball import (
    BOUNCE_COMPRESSION_M,
    BOUNCE_SPEED_MPS,
    ITF_FORWARD_DEFORMATION_M,
    ITF_FORWARD_LOAD_N,
    STATIC_WALL_STIFFNESS_N_PER_M,
    default_ball_law,
)
from racketdyn.contact import string_bed_cor
from racketdyn.impact.bounce import SURFACES, BallBounces, ball_bounces
from racketdyn.plausibility import check, check_speeds
from racketdyn.workflows.figure_data import defer_figure_data
from racketdyn.workflows.inputs import load_racket_input
from racketdyn.workflows.run import (
    StepResult,
    report,
    run_step,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

__all__ = ["BALL_SPEEDS_MPS", "BallResult", "run_ball"]

BALL_SPEEDS_MPS = (4.43, 7.06, 10.0, 20.0, 30.0, 40.0)
"""Default speeds: Cross's 1 m drop onto clamped strings, the ITF 100 in drop, then play."""


@dataclass
class BallResult(StepResult):
    """What :func:`run_ball` computed and wrote.

    Attributes
    ----------
    bounces : BallBounces or None
        The bounces (numbers and loops).
    static_deformation_m : float
        The ITF plate test (two plates, 80.1 N) on the static ball law, m: the separate check.
    tension_n : float
        String (pull) tension of the clamped bed, N.
    bed_tension_n : float
        The tension in the played bed, N (``tension_n`` less the strings' tension loss).
    """

    bounces: BallBounces | None = None
    static_deformation_m: float = float("nan")
    tension_n: float = float("nan")
    bed_tension_n: float = float("nan")


@run_step
def run_ball(
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    *,
    speeds: ArrayLike = BALL_SPEEDS_MPS,
    surfaces: Sequence[str] = SURFACES,
    tension_n: float | None = None,
) -> BallResult:
    """The ball's bounce on each surface at each speed; write the run folder.

    Parameters
    ----------
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, ball uses the racket (its strings),
        the ball and ``allow_implausible``; and the run (command, figures, progress).
    speeds : array_like
        Impact speeds, m/s.
    surfaces : sequence of {"rigid", "strings"}
        Which surfaces.
    tension_n : float, optional
        String tension of the clamped bed, N (default: the racket's).
    """
    speed_list = [float(v) for v in np.atleast_1d(np.asarray(speeds, dtype=float))]
    check_speeds("speeds", speed_list, "ball_speed_mps", setup.allow_implausible)
    the_racket, provenance = load_racket_input(setup.racket)
    if tension_n is not None:
        check("tension_n", tension_n, "tension_n", allow_implausible=setup.allow_implausible)
        the_racket = replace(the_racket, strings=replace(the_racket.strings, tension_n=tension_n))
    the_ball, ball_defaults = setup.ball_used()
    report(setup.progress, "bounces", 0, 1)
    bounces = ball_bounces(the_ball, speed_list, surfaces, the_racket)
    report(setup.progress, "bounces", 1, 1)
    static = default_ball_law(
        the_ball.diameter_m, wall_stiffness_n_per_m=STATIC_WALL_STIFFNESS_N_PER_M
    )
    out_dir = Path(out)
    result = BallResult(
        out_dir,
        bounces=bounces,
        static_deformation_m=2.0 * float(static.deflection(ITF_FORWARD_LOAD_N)),
        tension_n=the_racket.strings.tension_n,
        bed_tension_n=the_racket.strings.bed_tension_n,
    )
    result.written.append(bounces.write_csv(out_dir / "ball.csv"))
    bounces.to_xarray().to_netcdf(out_dir / "ball.nc")
    result.written.append(out_dir / "ball.nc")
    defer_figure_data(result, {"bounces": bounces})
    inputs: dict[str, Any] = {
        **provenance,
        "speeds_mps": speed_list,
        "surfaces": list(bounces.surfaces),
        "string_tension_n": the_racket.strings.tension_n,
        "bed_tension_n": the_racket.strings.bed_tension_n,
        "ball": {
            "mass_kg": the_ball.mass_kg,
            "diameter_m": the_ball.diameter_m,
            "rigid_cor": the_ball.rigid_cor,
            "restoring_force": the_ball.restoring_force.as_dict(),
            "e_bg_law": bounces.e_bg_record,
        },
        "string_bed_cor": string_bed_cor(),
        "bounce_the_law_came_from": {
            "speed_mps": BOUNCE_SPEED_MPS,
            "compression_m": BOUNCE_COMPRESSION_M,
        },
        "itf_plate_test": {
            "load_n": ITF_FORWARD_LOAD_N,
            "deformation_m_static_law": result.static_deformation_m,
            "deformation_m_itf_middle": ITF_FORWARD_DEFORMATION_M,
            "why": "a slow plate test, not a bounce: the static law (ITF wall + gas) against "
            "the ITF limits 5.6-7.4 mm, a separate check",
        },
        "defaults_used": [*ball_defaults, *setup.defaults],
    }
    return setup.finish(result, inputs, "ball")
