"""Step ``swing``: outgoing ball speed over the face of a swinging racket, and the sweet spots.

Writes ``swing.csv`` (the impact.csv columns; the racket speed is Ω (x + d) at each point),
``sweet_spots.csv`` (:data:`SWEET_SPOT_COLUMNS`) and ``run.json``; figures come from the
caller's hook.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import Ball
from racketdyn.contact import compound_law
from racketdyn.errors import InputError, one_of, require_finite, require_positive, require_speeds
from racketdyn.impact.grid import StringBed, check_string_bed
from racketdyn.impact.hand import Hand
from racketdyn.impact.measured import ModelInputs
from racketdyn.impact.result import shown_speed_index, write_columns
from racketdyn.impact.swing import (
    DEFAULT_ARM_GYRATION_M,
    DEFAULT_ARM_MASS_KG,
    DEFAULT_AXIS_TO_BUTT_M,
    DEFAULT_SWING_ANGLE_RAD,
    DEFAULT_TORQUE_NM,
    ImpactModel,
    SweetSpot,
    Swing,
    SwingResult,
    axis_swings,
    predict_swing,
    sweet_spot_table,
    sweet_spots,
)
from racketdyn.impact.transient import TRANSIENT_SUPPORTS
from racketdyn.impact.uncertainty import UncertainResult, Uncertainty, propagate
from racketdyn.io import racket_to_dict
from racketdyn.modal import ModalModel
from racketdyn.plausibility import check, check_speeds
from racketdyn.racket import SUPPORTS, Racket
from racketdyn.workflows._figure_io import store
from racketdyn.workflows.figure_data import (
    FIGURES_FILE,
    SwingAxisCurves,
    swing_axis_curves,
    write_figure_data,
)
from racketdyn.workflows.inputs import (
    single_support,
)
from racketdyn.workflows.predict import MAX_GRID
from racketdyn.workflows.run import (
    Progress,
    StepResult,
    check_workers,
    report,
    run_step,
    sample_pool,
    write_rows,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

__all__ = [
    "IMPACT_MODELS",
    "SWEET_SPOT_COLUMNS",
    "SWING_GRID",
    "SwingStepResult",
    "run_swing",
    "swing_from",
]

SWING_GRID = 15  # 177 points on the built-in head: a smooth map in ≈ 0.1 s (approximate model)
IMPACT_MODELS: dict[str, ImpactModel] = {"approx": "approximate", "transient": "transient"}

SWEET_SPOT_COLUMNS = (
    "key",
    "name",
    "x_m",
    "y_m",
    "on_face",
    "value",
    "definition",
    "racket_speed_mps",
    "rebound_speed_mps",
)
"""Columns of ``sweet_spots.csv``: :func:`~racketdyn.impact.swing.sweet_spot_table` (``value``:
the rebound ratio or outgoing speed maximised, empty for the geometric points), then the speed of
the racket and the outgoing ball speed at each spot for the swing (NaN off the face)."""


def swing_from(
    torque_nm: float | None = None,
    swing_angle_deg: float | None = None,
    angular_speed_radps: float | None = None,
    axis_to_butt_m: float | None = None,
    allow_implausible: bool = False,
) -> tuple[Swing, list[str]]:
    """The swing: constant shoulder torque (default) or a given angular speed; with the
    defaults used.

    Parameters
    ----------
    torque_nm : float, optional
        Constant shoulder torque, N·m (default 56.9, Kawazoe ACMD 2002).
    swing_angle_deg : float, optional
        Angle turned from rest to impact, degrees, in (0, 360] (default 90, an assumption).
    angular_speed_radps : float, optional
        Angular speed at impact, rad/s, instead of the torque model.
    axis_to_butt_m : float, optional
        Swing axis (shoulder) behind the butt, m (default 0.607: straight arm, 1.75 m adult).
    allow_implausible : bool
        Take values outside the plausible ranges of :mod:`racketdyn.plausibility` (a unit slip
        such as 607 for 0.607 m or 900 °/s for rad/s is refused otherwise).
    """
    defaults = []
    if axis_to_butt_m is None:
        axis = DEFAULT_AXIS_TO_BUTT_M
        defaults.append(
            f"swing axis (shoulder) {axis * 1e3:.0f} mm behind the butt: a straight arm in line "
            "with the racket, 70 kg, 1.75 m adult (Dempster/Winter)"
        )
    else:
        axis = require_positive("`axis_to_butt_m`", axis_to_butt_m, allow_zero=True)
        check("axis_to_butt_m", axis, "`axis_to_butt_m`", allow_implausible=allow_implausible)
    if angular_speed_radps is not None:
        if torque_nm is not None or swing_angle_deg is not None:
            raise InputError(
                "give `angular_speed_radps`, or `torque_nm` and `swing_angle_deg` (the constant "
                "shoulder torque swing), not both"
            )
        omega = require_positive("`angular_speed_radps`", angular_speed_radps, allow_zero=True)
        check(
            "angular_speed_radps",
            omega,
            "`angular_speed_radps`",
            allow_implausible=allow_implausible,
        )
        return Swing(axis_to_butt_m=axis, angular_speed_radps=omega), defaults
    if torque_nm is None:
        torque = DEFAULT_TORQUE_NM
        defaults.append(f"shoulder torque {torque:g} N·m (Kawazoe, ACMD 2002)")
    else:
        torque = require_positive("`torque_nm`", torque_nm)
        check("torque_nm", torque, "`torque_nm`", allow_implausible=allow_implausible)
    if swing_angle_deg is None:
        angle = DEFAULT_SWING_ANGLE_RAD
        defaults.append("swing angle 90° from rest to impact (assumption: a quarter turn)")
    else:
        degrees = require_finite("`swing_angle_deg`", swing_angle_deg)
        if not 0.0 < degrees <= 360.0:
            raise InputError(
                f"`swing_angle_deg` must be more than 0 and at most 360 degrees (got {degrees:g})"
            )
        check("swing_angle_deg", degrees, "`swing_angle_deg`", allow_implausible=allow_implausible)
        angle = math.radians(degrees)
    defaults.append(
        f"arm {DEFAULT_ARM_MASS_KG * 1e3:.0f} g, radius of gyration "
        f"{DEFAULT_ARM_GYRATION_M * 1e3:.0f} mm about the shoulder (Dempster/Winter, 70 kg, "
        "1.75 m adult)"
    )
    return Swing(torque_nm=torque, swing_angle_rad=angle, axis_to_butt_m=axis), defaults


def one_support(support: str, transient: bool) -> str:
    """One support, allowed by the impact model."""
    support = single_support(
        "swing", support, "its sweet spots, swing.csv and figures are one support's"
    )
    if support == "hand" and not transient:
        raise InputError(
            "`support` hand needs `model` transient: the approximate method has no hand "
            "(it holds the racket pinned at the grip: `support` pinned)"
        )
    return one_of("`support`", support, TRANSIENT_SUPPORTS if transient else SUPPORTS)


@dataclass
class SwingStepResult(StepResult):
    """What :func:`run_swing` computed and wrote.

    Attributes
    ----------
    swing_result : SwingResult
        Impacts over the face on the swinging racket.
    spots : dict of SweetSpot
        The named sweet spots at the shown speed.
    spot_rows : list of dict
        ``sweet_spots.csv`` rows (:data:`SWEET_SPOT_COLUMNS`).
    band : UncertainResult or None
        With an uncertainty: every sample of the swing and the bands.
    racket, ball, swing : Racket, Ball, Swing
        The inputs used.
    modal_model : ModalModel or None
        The racket's modes (None: rigid).
    impact_model : str
        ``approximate`` or ``transient``.
    support : str
        The support.
    speeds : list of float
        Ball speeds, m/s.
    shown_speed : int
        Index of the speed of the sweet spots and figures.
    options : dict
        Keywords passed to the impact model (law, hand).
    axis_curves : SwingAxisCurves or None
        The outgoing speed along the axis for the racket at rest and a few swings, at the
        shown speed (the along-axis figure; in ``figures.nc``).
    """

    swing_result: SwingResult | None = None
    spots: dict[str, SweetSpot] = field(default_factory=dict)
    spot_rows: list[dict[str, Any]] = field(default_factory=list)
    band: UncertainResult | None = None
    racket: Racket | None = None
    ball: Ball | None = None
    swing: Swing | None = None
    modal_model: ModalModel | None = None
    impact_model: ImpactModel = "approximate"
    support: str = "pinned"
    speeds: list[float] = field(default_factory=list)
    shown_speed: int = 0
    options: dict[str, Any] = field(default_factory=dict)
    axis_curves: SwingAxisCurves | None = None


def _spot_rows(
    result: SwingStepResult, speed: float, model: ModalModel | None
) -> list[dict[str, Any]]:
    """sweet_spot_table rows with the racket speed and the outgoing ball speed at each spot."""
    assert result.racket is not None
    assert result.ball is not None
    assert result.swing is not None
    spots = result.spots
    rows = sweet_spot_table(spots)
    on_face = [i for i, key in enumerate(spots) if spots[key].on_face]
    outgoing = np.full(len(rows), np.nan)
    if on_face:
        at = predict_swing(
            result.racket,
            result.ball,
            [spots[list(spots)[i]].location for i in on_face],
            [speed],
            result.swing,
            result.support,
            result.impact_model,
            model,
            **result.options,
        )
        outgoing[on_face] = at.rebound_speed[:, 0, 0]
    racket_speed = result.swing.angular_speed(result.racket) * (
        np.array([s.x_m for s in spots.values()]) + result.swing.axis_to_butt_m
    )
    for i, row in enumerate(rows):
        row["racket_speed_mps"] = float(racket_speed[i])
        row["rebound_speed_mps"] = float(outgoing[i])
    return rows


@run_step
def run_swing(
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    *,
    swing: Swing | None = None,
    speeds: ArrayLike = (20.0,),
    support: str = "pinned",
    model: Literal["approx", "transient"] = "approx",
    grid: int | None = None,
    uncertainty: Uncertainty | None = None,
    workers: int | None = None,
) -> SwingStepResult:
    """Impacts over the face of a swinging racket and its sweet spots; write the run folder.

    The steps: the options checked (:func:`_ball_speeds`, :func:`_grid_size`), the impacts
    over the face, the sweet spots and the along-axis curves (:func:`_swing_curves`), the
    bands of an uncertainty (:func:`_write_bands`), the tables and ``figures.nc``
    (:func:`_write_tables`), run.json.

    Parameters
    ----------
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, swing uses the racket and its modes,
        the ball, the hand, the string bed and ``allow_implausible``; and the run (command,
        figures, progress).
    swing : Swing, optional
        The swing (default: :func:`swing_from` with no arguments, 56.9 N·m over 90°).
    speeds : array_like
        Incoming ball speeds, m/s.
    support : {"pinned", "free", "hand"}
        Support (``hand`` with ``model="transient"``).
    model : {"approx", "transient"}
        Impact model.
    grid : int, optional
        N × N grid over the head (default 15).
    uncertainty : Uncertainty, optional
        Uncertain inputs: the swing run once per sample; ``swing.csv`` gets each number's
        mean, sd and 90 % band (:func:`racketdyn.impact.uncertainty.propagate`), every sample
        goes to ``uncertainty.nc``.
    workers : int, optional
        Worker processes for those samples (a local pool,
        :func:`racketdyn.sweep.executors.make_executor`); by default this process.
    """
    check_workers(workers, uncertainty)
    speed_list = _ball_speeds(speeds, setup.allow_implausible)
    impact_model = IMPACT_MODELS[one_of("`model`", model, tuple(IMPACT_MODELS))]
    the_support = one_support(support, model == "transient")
    n = _grid_size(grid)
    used = setup.racket_setup()
    the_hand, hand_defaults = setup.hand_used([the_support])
    the_swing, swing_defaults = swing_from() if swing is None else (swing, [])
    the_ball, ball_defaults = setup.ball_used()
    defaults_used = [*used.defaults, *hand_defaults, *swing_defaults, *ball_defaults]
    defaults_used += setup.defaults
    locations = used.racket.head.grid(n)
    labels = [str(i + 1) for i in range(len(locations))]
    options = _impact_options(setup.string_bed, used.racket, the_ball, the_hand)
    result = SwingStepResult(
        Path(out),
        racket=used.racket,
        ball=the_ball,
        swing=the_swing,
        modal_model=used.modal_model,
        impact_model=impact_model,
        support=the_support,
        speeds=speed_list,
        shown_speed=shown_speed_index(speed_list),
        options=options,
    )
    omega = the_swing.angular_speed(used.racket)
    report(setup.progress, f"swing Ω = {omega:.2f} rad/s: {len(locations)} points")
    computed = _swing_curves(result, locations, labels, setup.progress)
    if uncertainty is None:
        computed.write_csv(result.out / "swing.csv")
    else:
        report(setup.progress, f"uncertainty: {uncertainty.samples} samples of the swing")
        result.band = _sample_band(result, (locations, labels), uncertainty, model, workers)
        _write_bands(result, computed, result.band)
    _write_tables(result, computed)
    chosen = result.shown_speed
    inputs = {
        **used.provenance,
        "racket": racket_to_dict(used.racket),
        "ball_speeds_mps": speed_list,
        "support": the_support,
        "grid": n,
        "n_points": len(locations),
        "rigid": setup.rigid,
        "defaults_used": defaults_used,
        **computed.inputs,  # swing (parameters, Ω, inertias), impact model, ball, law, modes
        "angular_speed_radps": omega,
        "uncertainty": None if uncertainty is None else uncertainty.record(),
        "sweet_spots_at_mps": speed_list[chosen],
        "along_axis_swings": [name for name, _ in axis_swings(the_swing)],
        "columns": {
            "swing.csv": "impact.csv columns; racket_speed_mps = Ω (x + axis_to_butt_m) "
            "at each point",
            "sweet_spots.csv": list(SWEET_SPOT_COLUMNS),
        },
    }
    return setup.finish(result, inputs, "swing")


def _ball_speeds(speeds: ArrayLike, allow_implausible: bool) -> list[float]:
    """The incoming ball speeds, m/s: each once, within play (unless ``allow_implausible``)."""
    speed_list = [float(v) for v in require_speeds("`speeds`", speeds)]
    check_speeds("`speeds`", speed_list, "ball_speed_mps", allow_implausible)
    if len(set(speed_list)) != len(speed_list):
        raise InputError(
            f"`speeds`: each ball speed once (got {', '.join(f'{v:g}' for v in speed_list)})"
        )
    return speed_list


def _grid_size(grid: int | None) -> int:
    """N of the N × N grid over the head (default :data:`SWING_GRID`)."""
    n = SWING_GRID if grid is None else grid
    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= MAX_GRID:
        raise InputError(f"`grid` must be a whole number from 1 to {MAX_GRID} (got {n})")
    return n


def _impact_options(
    string_bed: StringBed, the_racket: Racket, the_ball: Ball, the_hand: Hand | None
) -> dict[str, Any]:
    """The impact model's keywords: the face centre's law (a uniform bed), the bed, the hand
    (if any); the bed's law checked for the racket."""
    check_string_bed(string_bed, None, the_racket)
    law = {"law": compound_law(the_racket, the_ball)} if string_bed == "uniform" else {}
    return {
        **law,
        "string_bed": string_bed,
        **({"hand": the_hand} if the_hand is not None else {}),
    }


def _swing_curves(
    result: SwingStepResult,
    locations: NDArray[np.float64],
    labels: list[str],
    progress: Progress | None,
) -> SwingResult:
    """The impacts at ``locations`` on the swinging racket (returned and kept in ``result``),
    then at the shown speed the sweet spots, their table and the outgoing speed along the
    axis for a few swings."""
    assert result.racket is not None
    assert result.ball is not None
    assert result.swing is not None
    speed = result.speeds[result.shown_speed]
    how = (result.support, result.impact_model, result.modal_model)
    the_racket, the_ball, the_swing = result.racket, result.ball, result.swing
    computed = predict_swing(
        the_racket, the_ball, locations, result.speeds, the_swing, *how, labels, **result.options
    )
    result.swing_result = computed
    report(progress, f"sweet spots at {speed:g} m/s")
    result.spots = sweet_spots(the_racket, the_ball, the_swing, speed, *how, **result.options)
    result.spot_rows = _spot_rows(result, speed, result.modal_model)
    report(progress, "outgoing speed along the axis for a few swings")
    result.axis_curves = swing_axis_curves(
        the_racket, the_ball, the_swing, speed, *how, **result.options
    )
    return computed


def _sample_band(
    result: SwingStepResult,
    points: tuple[NDArray[np.float64], list[str]],
    uncertainty: Uncertainty,
    method: Literal["approx", "transient"],
    workers: int | None,
) -> UncertainResult:
    """The swing at ``points`` (locations, labels) once per sample of ``uncertainty``, on
    ``workers`` processes: every sample and the bands."""
    assert result.racket is not None
    assert result.ball is not None
    locations, labels = points
    inputs_of_samples = ModelInputs(
        result.racket,
        result.ball,
        hand=result.options.get("hand"),
        modal_model=result.modal_model,
        string_bed=result.options["string_bed"],
    )
    with sample_pool(workers) as executor:
        return propagate(
            inputs_of_samples,
            locations,
            result.speeds,
            uncertainty,
            method=method,
            supports=[result.support],
            labels=labels,
            options={"swing": result.swing},
            executor=executor,
        )


def _write_bands(result: SwingStepResult, computed: SwingResult, band: UncertainResult) -> None:
    """``swing.csv`` with each number's band beside it, and every sample in
    ``uncertainty.nc``."""
    out_dir = result.out
    bands = {k: np.ravel(v) for k, v in band.band_columns().items()}
    write_columns(out_dir / "swing.csv", {**computed.columns, **bands})
    band.to_xarray().to_netcdf(out_dir / "uncertainty.nc")
    result.written.append(out_dir / "uncertainty.nc")


def _write_tables(result: SwingStepResult, computed: SwingResult) -> None:
    """Write ``sweet_spots.csv`` and ``figures.nc``; list them in ``result.written`` after
    ``swing.csv`` (written already, with or without bands)."""
    out_dir = result.out
    result.written += [
        out_dir / "swing.csv",
        write_rows(out_dir / "sweet_spots.csv", result.spot_rows),
        write_figure_data(
            out_dir / FIGURES_FILE,
            [
                _axis_curves(result).to_xarray(),
                store(
                    {
                        "swing_result": computed,
                        "racket": result.racket,
                        "spots": result.spots,
                        "shown_speed": result.shown_speed,
                    }
                ),
            ],
        ),
    ]


def _axis_curves(result: SwingStepResult) -> SwingAxisCurves:
    """The result's along-axis curves (computed by :func:`_swing_curves`)."""
    assert result.axis_curves is not None
    return result.axis_curves
