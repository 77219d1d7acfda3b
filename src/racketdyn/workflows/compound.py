"""Step ``compound``: the modes of a racket with a ball fixed on its strings (section 3.2).

Writes ``compound.csv`` (:data:`COMPOUND_COLUMNS`) and ``run.json`` (the ball–string spring
and why, the frame modes' shifts when the ball is added, and the frame-stiffness check); the
figures come from the caller's hook.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import Ball
from racketdyn.contact import net_share
from racketdyn.errors import InputError, one_of
from racketdyn.impact.approximate import predict
from racketdyn.impact.compound import (
    BALL_MODE_NAME,
    PRELOAD_N,
    BallSpring,
    CompoundSystem,
    ball_spring,
    racket_modes,
    resting_patch_radius,
    small_amplitude_e_bg,
    spring_split,
    stiffer_frame,
)
from racketdyn.impact.compound_band import (
    PAPER_BALL_MODE_HZ,
    BallModeBand,
    BedForFrequency,
    ball_mode_band,
    bed_for_frequency,
)
from racketdyn.impact.grid import STRING_BEDS
from racketdyn.impact.hand import Hand
from racketdyn.impact.system import TRANSIENT_SUPPORTS
from racketdyn.io import default_racket, racket_to_dict
from racketdyn.modal import ModalModel
from racketdyn.racket import Racket
from racketdyn.rig.hammer import string_contact_time
from racketdyn.workflows.figure_data import defer_figure_data
from racketdyn.workflows.inputs import supports_named
from racketdyn.workflows.run import (
    StepResult,
    report,
    run_step,
    write_rows,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

__all__ = [
    "COMPOUND_COLUMNS",
    "CONTACT_SPEEDS_MPS",
    "FRAME_STIFFNESS_FACTOR",
    "HAMMER_OFFSET_M",
    "NOT_THE_PAPERS_RACKET",
    "CompoundResult",
    "FrameCheck",
    "is_papers_racket",
    "run_compound",
]

CONTACT_SPEEDS_MPS = (5.0, 10.0, 20.0)
"""Ball speeds of the approximate method's contact times beside the half period, m/s."""

FRAME_STIFFNESS_FACTOR = 4.0
"""The paper's stiffer racket: "approximately 4 times the frame rigidity", same mass."""

COMPOUND_COLUMNS = (
    "support",
    "mode",
    "frequency_hz",
    "damping_ratio",
    "ball_to_frame_ratio",
    "half_period_s",
    "contact_time_5_s",
    "contact_time_10_s",
    "contact_time_20_s",
)
"""Columns of ``compound.csv``: one row per support × elastic mode of the racket with the ball;
the last four only on the ball mode (empty elsewhere)."""

HAMMER_OFFSET_M = 0.012
"""By default the hammer strikes the strings this far from the ball, towards the handle, m
(the paper: "a point, slightly away from the contact point of the ball"; struck from behind
the face, where the ball does not cover the strings).  How long the ball mode leads at the
neck (Fig. 8c) depends steeply on it: on the built-in frame's shape (issue 22, fourth
session) the free racket's 2-node mode takes over after ≈ 9.4 ball cycles at 12 mm, 4.1 at
20 mm, 2.3 at 25 mm, 0.7 at 30 mm; from 40 mm on it leads from the start (the smooth frame:
2.7 at 12 mm, from 18 mm on; docs/develop.md, "The ball on the strings").  Give ``--hammer``
where you struck."""

NOT_THE_PAPERS_RACKET = (
    "the paper's 103 Hz was measured on its own racket and strings, 360 g and 97 sq in, not on "
    "this one: no check of it"
)
"""Why another racket's ball mode is not held against the paper's 103 Hz (run.json, console,
report)."""

NECK_BELOW_BED_M = 0.03
"""The accelerometer on the frame neck: on the long axis, this far below the string bed, m."""

RESPONSE_TIME_S = 0.04
"""Length of the neck's time response (Fig. 8c), s; sampled at :data:`RESPONSE_STEP_S`."""
RESPONSE_STEP_S = 1.0e-4

AXIS_POINTS = 69
"""Points along the long axis for the ball mode's shape (Fig. 8a)."""

FRF_FREQUENCY_HZ = (20.0, 500.0, 2000)
"""Band and count of the FRFs without and with the ball (Fig. 9), Hz."""

# the approximate method's support for each support of the compound system: it has no hand,
# and the paper's model of a held racket is the pin at the grip (section 3.3)
_APPROXIMATE_SUPPORT = {"free": "free", "pinned": "pinned", "hand": "pinned"}


@dataclass(frozen=True)
class FrameCheck:
    """The ball mode and the frame modes of the racket and of one with a stiffer frame.

    Attributes
    ----------
    support : str
        Support.
    factor : float
        Frame stiffness factor (4: the paper's stiffer racket).
    ball_hz, stiffer_ball_hz : float
        Ball mode of the racket and of the stiffer racket, Hz.
    frame_hz, stiffer_frame_hz : dict of str to float
        Frame modes (with the ball) by name, Hz.
    """

    support: str
    factor: float
    ball_hz: float
    stiffer_ball_hz: float
    frame_hz: dict[str, float]
    stiffer_frame_hz: dict[str, float]

    @property
    def ball_change(self) -> float:
        """Relative change of the ball mode, stiffer / original − 1."""
        return self.stiffer_ball_hz / self.ball_hz - 1.0

    def as_dict(self) -> dict[str, Any]:
        """For run.json."""
        return {
            "support": self.support,
            "frame_stiffness_factor": self.factor,
            "ball_mode_hz": self.ball_hz,
            "stiffer_ball_mode_hz": self.stiffer_ball_hz,
            "ball_mode_change_percent": 100.0 * self.ball_change,
            "frame_modes": [
                {
                    "mode": name,
                    "frequency_hz": f,
                    "stiffer_frequency_hz": self.stiffer_frame_hz.get(name, math.nan),
                    "ratio": self.stiffer_frame_hz.get(name, math.nan) / f,
                }
                for name, f in self.frame_hz.items()
            ],
        }


@dataclass
class CompoundResult(StepResult):
    """What :func:`run_compound` computed and wrote.

    Attributes
    ----------
    racket : Racket
        The racket.
    ball : Ball
        The ball.
    spring : BallSpring
        The ball–string spring.
    location : tuple of float
        Where the ball sits (x, y), m.
    supports : list of str
        Supports, in order.
    modes, alone : dict of str to CompoundSystem
        Per support: the racket with the ball, and alone.
    checks : dict of str to FrameCheck
        Per support: the frame-stiffness check.
    blow_share : dict of str to float
        The hammer's blow shared through the strings: ``net_share`` (the strings under the
        ball) and ``to_ball``.
    neck_parts : dict of str to dict of str to ndarray
        Per support: the ball mode's and the 2-node mode's parts of the neck's response after
        the blow (``ball``, ``2-node bending``), m/s² per N·s.
    hand_over : dict of str to dict of str to float
        Per support: ``ball_to_two_node`` (their amplitudes after the blow) and
        ``ball_cycles`` (after how many ball-mode cycles the 2-node mode is the larger; 0 if
        from the start, inf if never — the ball mode decays more slowly —, NaN without a
        2-node mode): Fig. 8c's reading.
    band : dict of str to BallModeBand
        Per support: the ball mode over the small-amplitude inputs' spread
        (:mod:`racketdyn.impact.compound_band`).
    paper_bed : dict of str to BedForFrequency
        Per support: the bed under the nominal ball that would give the paper's 103 Hz (only
        for the paper's racket: empty for another).
    paper_racket : bool
        Whether the racket is the paper's (:func:`is_papers_racket`): only then is the ball
        mode held against the paper's measured 103 Hz.
    overhangs : bool
        Whether the ball's edge reaches past the string bed's (it would rest on the frame).
    off_centre_m : float
        The ball's distance from the bed's centre, m (the spring is the centre's law).
    node_line : dict of str to float
        Per support: where the racket's 2-node mode (without the ball) crosses the long axis
        nearest the ball, x in m (NaN without a 2-node mode): a blow or a ball near it hardly
        rings the 2-node mode (Fig. 8c).
    contact_time : dict of str to list of float
        Per support: the approximate method's contact time at :data:`CONTACT_SPEEDS_MPS`, s.
    model : ModalModel or None
        The racket's modes (None: rigid).
    hand : Hand or None
        The hand of ``hand``.
    hammer, neck : tuple of float
        Where the hammer strikes and the accelerometer sits (x, y), m.
    times : ndarray
        Times of the neck responses, s.
    neck_acceleration : dict of str to ndarray
        Per support: the neck's acceleration after the hammer's blow of unit impulse (a
        half-sine ``blow_s`` long), m/s² per N·s.
    blow_s : dict of str to float
        Per support: length of the hammer's half-sine blow on the strings, s.
    frequency : ndarray
        Frequencies of the FRFs, Hz.
    frf_alone, frf_with_ball : dict of str to ndarray
        Per support: receptance hammer → neck without and with the ball, m/N (complex).
    axis_x : ndarray
        Points along the long axis (y = 0) where the ball mode's shape is given, m.
    ball_shape : dict of str to tuple of (ndarray, float)
        Per support: the ball mode's frame displacement along the axis and the ball's, scaled
        so the ball's is 1 (real parts after removing the ball's phase; Fig. 8a).
    figure_data : CompoundFigures or None
        What the figures draw (in ``figures.nc``).
    """

    racket: Racket | None = None
    ball: Ball | None = None
    spring: BallSpring | None = None
    location: tuple[float, float] = (math.nan, math.nan)
    supports: list[str] = field(default_factory=list)
    modes: dict[str, CompoundSystem] = field(default_factory=dict)
    alone: dict[str, CompoundSystem] = field(default_factory=dict)
    checks: dict[str, FrameCheck] = field(default_factory=dict)
    blow_share: dict[str, float] = field(default_factory=dict)
    neck_parts: dict[str, dict[str, NDArray[np.float64]]] = field(default_factory=dict)
    hand_over: dict[str, dict[str, float]] = field(default_factory=dict)
    band: dict[str, BallModeBand] = field(default_factory=dict)
    paper_bed: dict[str, BedForFrequency] = field(default_factory=dict)
    paper_racket: bool = False
    node_line: dict[str, float] = field(default_factory=dict)
    overhangs: bool = False
    off_centre_m: float = 0.0
    contact_time: dict[str, list[float]] = field(default_factory=dict)
    model: ModalModel | None = None
    hand: Hand | None = None
    hammer: tuple[float, float] = (math.nan, math.nan)
    neck: tuple[float, float] = (math.nan, math.nan)
    times: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    neck_acceleration: dict[str, NDArray[np.float64]] = field(default_factory=dict)
    blow_s: dict[str, float] = field(default_factory=dict)
    frequency: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    frf_alone: dict[str, NDArray[np.complex128]] = field(default_factory=dict)
    frf_with_ball: dict[str, NDArray[np.complex128]] = field(default_factory=dict)
    axis_x: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    ball_shape: dict[str, tuple[NDArray[np.float64], float]] = field(default_factory=dict)
    figure_data: CompoundFigures | None = None


@dataclass(frozen=True)
class CompoundFigures:
    """What the compound step's figures (Figs 8a, 8c, 9) draw: the step's computed responses and
    the modes' frequencies they mark (in ``figures.nc``).

    Attributes
    ----------
    supports : tuple of str
        Supports, in order.
    location, hammer : tuple of float
        Where the ball sits and the hammer strikes (x, y), m.
    times : ndarray
        Times of the neck responses, s.
    neck_acceleration, neck_parts, blow_s, hand_over
        As :class:`CompoundResult`'s, per support.
    frequency : ndarray
        Frequencies of the FRFs, Hz.
    frf_alone, frf_with_ball : dict of str to ndarray
        Per support: receptance hammer → neck without and with the ball, m/N (complex).
    axis_x : ndarray
        Points along the long axis of the ball mode's shape, m.
    ball_shape : dict of str to tuple of (ndarray, float)
        Per support: the ball mode's frame displacement along the axis and the ball's.
    ball_frequency_hz, two_node_frequency_hz : dict of str to float
        Per support: the ball mode's and the 2-node bending mode's frequencies with the ball,
        Hz (NaN without a 2-node mode).
    """

    supports: tuple[str, ...]
    location: tuple[float, float]
    hammer: tuple[float, float]
    times: NDArray[np.float64]
    neck_acceleration: dict[str, NDArray[np.float64]]
    neck_parts: dict[str, dict[str, NDArray[np.float64]]]
    blow_s: dict[str, float]
    hand_over: dict[str, dict[str, float]]
    frequency: NDArray[np.float64]
    frf_alone: dict[str, NDArray[np.complex128]]
    frf_with_ball: dict[str, NDArray[np.complex128]]
    axis_x: NDArray[np.float64]
    ball_shape: dict[str, tuple[NDArray[np.float64], float]]
    ball_frequency_hz: dict[str, float]
    two_node_frequency_hz: dict[str, float]

    @classmethod
    def of(cls, result: CompoundResult) -> CompoundFigures:
        """The figures' data of a compound result."""
        return cls(
            tuple(result.supports),
            result.location,
            result.hammer,
            result.times,
            result.neck_acceleration,
            result.neck_parts,
            result.blow_s,
            result.hand_over,
            result.frequency,
            result.frf_alone,
            result.frf_with_ball,
            result.axis_x,
            result.ball_shape,
            {s: float(m.ball_frequency) for s, m in result.modes.items()},
            {s: m.frequency_of("2-node bending") for s, m in result.modes.items()},
        )


def frame_shifts(with_ball: CompoundSystem, alone: CompoundSystem) -> list[dict[str, Any]]:
    """The racket's own modes with and without the ball, matched by name."""
    rows = []
    for name, f_alone in zip(alone.names, alone.frequency, strict=True):
        f_with = with_ball.frequency_of(name)
        rows.append(
            {
                "mode": name,
                "alone_hz": float(f_alone),
                "with_ball_hz": f_with,
                "shift_percent": 100.0 * (f_with / float(f_alone) - 1.0),
            }
        )
    return rows


@run_step
def run_compound(
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    *,
    ball_at: ArrayLike | None = None,
    supports: str | Sequence[str] = ("free", "hand"),
    preload_n: float = PRELOAD_N,
    hammer: ArrayLike | None = None,
) -> CompoundResult:
    """The linear modes of ball + ball–string spring + racket; write the run folder.

    The steps: the ball's and the hammer's points (:func:`_ball_point`, :func:`_hammer_point`),
    the ball's spring, where the responses are taken (:func:`_place`), the approximate
    method's contact times, each support's modes and responses (:func:`_support_modes`),
    then ``compound.csv`` (:func:`_compound_rows`) and run.json (:func:`_blow_record`,
    :func:`_modes_record`).

    Parameters
    ----------
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, compound uses the racket and its
        modes, the ball, the hand and the string bed; and the run (command, figures, progress).
    ball_at : array_like (2,), optional
        Where the ball sits (x, y), m (default the centre of the string bed); the name
        :class:`~racketdyn.workflows.RigOptions` and :func:`run_compare_ball
        <racketdyn.workflows.identify.run_compare_ball>` give a ball on the strings.
    supports : sequence of str
        ``free``, ``pinned``, ``hand`` (the modes of each).
    preload_n : float
        Preload of the stuck ball on the strings, N (the spring is F_GB's tangent there).
    hammer : array_like (2,), optional
        Where the hammer strikes the string face for Figs 8c and 9 (x, y), m (default
        :data:`HAMMER_OFFSET_M` from the ball towards the handle).  Its blow is a half-sine as
        long as the hammer's contact with the strings there
        (:func:`racketdyn.rig.hammer.string_contact_time`, as the virtual rig's).
    """
    checked = supports_named(supports, TRANSIENT_SUPPORTS)
    used = setup.racket_setup()
    the_racket = used.racket
    defaults_used = [*used.defaults, *setup.defaults]
    xy = _ball_point(the_racket, ball_at, defaults_used)
    the_hand, hand_defaults = setup.hand_used(checked)
    the_ball, ball_defaults = setup.ball_used()
    defaults_used += [*hand_defaults, *ball_defaults]
    one_of("string_bed", setup.string_bed, STRING_BEDS)
    spring = ball_spring(
        the_racket, the_ball, preload_n, None if setup.string_bed == "uniform" else xy
    )
    model = used.modal_model
    stiffer = None if model is None else stiffer_frame(model, FRAME_STIFFNESS_FACTOR)
    strike = _hammer_point(the_racket, xy, hammer, defaults_used)
    head = the_racket.head
    result = _place(
        CompoundResult(
            Path(out), racket=the_racket, ball=the_ball, spring=spring, location=xy,
            supports=checked, model=model, hand=the_hand, hammer=strike,
            neck=(head.centre_x_m - head.half_length_m - NECK_BELOW_BED_M, 0.0),
        )
    )  # fmt: skip
    approximate = predict(
        the_racket,
        the_ball,
        [xy],
        CONTACT_SPEEDS_MPS,
        sorted({_APPROXIMATE_SUPPORT[s] for s in checked}),
        modal_model=None,
        string_bed=setup.string_bed,  # the contact time with the law the spring was taken from
    )
    k_ball, k_bed = spring_split(spring)
    ball_fraction = k_ball / (k_ball + k_bed)
    patch = resting_patch_radius(the_racket)
    share = net_share(the_racket, patch, math.dist(strike, xy))  # the same for every support
    result.blow_share = {"net_share": share, "to_ball": share * ball_fraction}
    for i, support in enumerate(checked):
        report(setup.progress, f"modes with the ball, {support}", i, len(checked))
        _support_modes(result, support, ball_fraction, stiffer)
        k = approximate.supports.index(_APPROXIMATE_SUPPORT[support])
        result.contact_time[support] = [float(t) for t in approximate.contact_time[0, :, k]]
    result.written.append(write_rows(result.out / "compound.csv", _compound_rows(result)))
    result.figure_data = CompoundFigures.of(result)
    defer_figure_data(result, {"figure_data": result.figure_data})
    inputs = {
        **used.provenance,
        "racket": racket_to_dict(the_racket),
        **_blow_record(result, patch, setup.string_bed),
        "supports": checked,
        "rigid": setup.rigid,
        "ball_mass_kg": the_ball.mass_kg,
        "defaults_used": defaults_used,
        **_modes_record(result, the_racket, the_ball),
    }
    return setup.finish(result, inputs, "compound")


def _ball_point(the_racket: Racket, ball_at: ArrayLike | None, defaults_used: list[str]) -> tuple[
    float, float
]:  # fmt: skip
    """Where the ball sits (x, y), m: ``ball_at``, or the bed's centre (said in
    ``defaults_used``); refused outside the head."""
    if ball_at is None:
        xy = (the_racket.head.centre_x_m, the_racket.head.centre_y_m)
        defaults_used.append("ball_at: the centre of the string bed")
    else:
        values = np.asarray(ball_at, dtype=float).ravel()
        if values.size != 2 or not np.all(np.isfinite(values)):
            raise InputError("`ball_at`: give the ball's position as x,y in m, e.g. 0.505,0")
        xy = (float(values[0]), float(values[1]))
    the_racket.head.check_inside(np.array([xy]), "`ball_at`")
    return xy


def _hammer_point(
    the_racket: Racket,
    xy: tuple[float, float],
    hammer: ArrayLike | None,
    defaults_used: list[str],
) -> tuple[float, float]:
    """Where the hammer strikes (x, y), m: ``hammer``, or :data:`HAMMER_OFFSET_M` from the
    ball at ``xy`` towards the handle (said in ``defaults_used``); refused outside the head."""
    head = the_racket.head
    if hammer is None:
        strike = (xy[0] - HAMMER_OFFSET_M, xy[1])
        defaults_used.append(
            f"hammer: {1e3 * HAMMER_OFFSET_M:.0f} mm from the ball, to the handle, behind the face"
        )
        head.check_inside(
            np.array([strike]),
            f"the hammer point (`ball_at` minus {1e3 * HAMMER_OFFSET_M:.0f} mm; `hammer`)",
        )
    else:
        values = np.asarray(hammer, dtype=float).ravel()
        if values.size != 2 or not np.all(np.isfinite(values)):
            raise InputError("`hammer`: give the hammer's point as x,y in m, e.g. 0.495,0")
        strike = (float(values[0]), float(values[1]))
        head.check_inside(np.array([strike]), "`hammer`")
    return strike


def _place(result: CompoundResult) -> CompoundResult:
    """``result`` with the times, frequencies and axis points of its responses, whether its
    racket is the paper's, and where its ball sits on the bed (off the centre, overhanging)."""
    the_racket, the_ball = _racket_and_ball(result)
    head, xy = the_racket.head, result.location
    result.times = np.arange(0.0, RESPONSE_TIME_S, RESPONSE_STEP_S)
    result.frequency = np.linspace(*FRF_FREQUENCY_HZ[:2], FRF_FREQUENCY_HZ[2])
    result.axis_x = np.linspace(0.0, the_racket.length_m, AXIS_POINTS)
    result.paper_racket = is_papers_racket(the_racket)
    result.off_centre_m = math.dist(xy, (head.centre_x_m, head.centre_y_m))
    angles = np.linspace(0.0, 2.0 * math.pi, 72, endpoint=False)
    rim = np.column_stack([np.cos(angles), np.sin(angles)]) * the_ball.diameter_m / 2 + xy
    result.overhangs = not bool(np.all(head.contains(rim)))
    return result


def _racket_and_ball(result: CompoundResult) -> tuple[Racket, Ball]:
    """The result's racket and ball (set by :func:`run_compound` before any step uses them)."""
    assert result.racket is not None
    assert result.ball is not None
    return result.racket, result.ball


def _support_modes(
    result: CompoundResult, support: str, ball_fraction: float, stiffer: ModalModel | None
) -> None:
    """One support's modes with the ball and without, the neck's response and the FRFs after
    the hammer's blow (``ball_fraction`` of the strings' share to the ball), the ball mode's
    shape, its band and the bed for the paper's frequency, the 2-node node line and, with
    ``stiffer`` (the racket with a stiffer frame), the frame check: into ``result``."""
    the_racket, the_ball = _racket_and_ball(result)
    model, xy, spring, the_hand = result.model, result.location, result.spring, result.hand
    assert spring is not None
    extra = np.vstack(
        [[result.hammer, result.neck], np.column_stack([result.axis_x, np.zeros(AXIS_POINTS)])]
    )
    with_ball = racket_modes(the_racket, model, support, xy, spring, the_ball, the_hand, extra)
    alone = racket_modes(the_racket, model, support, xy, None, the_ball, the_hand, extra)
    result.modes[support], result.alone[support] = with_ball, alone
    blow = float(string_contact_time(the_racket, [result.hammer], _APPROXIMATE_SUPPORT[support])[0])
    result.blow_s[support] = blow
    load = with_ball.string_blow(1, result.blow_share["net_share"], ball_fraction)
    result.neck_acceleration[support] = with_ball.blow_acceleration(result.times, load, 2, blow)
    result.neck_parts[support], result.hand_over[support] = _hand_over(
        with_ball, result.times, result.neck_acceleration[support], blow
    )
    result.frf_with_ball[support] = with_ball.receptance(result.frequency, load, 2)
    result.frf_alone[support] = alone.receptance(result.frequency, 1, 2)
    if with_ball.ball_mode >= 0:
        shape = with_ball.shapes[:, with_ball.ball_mode] / with_ball.shapes[-1, with_ball.ball_mode]
        result.ball_shape[support] = (np.real(with_ball.rows[3:] @ shape), 1.0)
    result.band[support] = ball_mode_band(
        the_racket, model, support, xy, spring, the_ball, the_hand
    )
    if result.paper_racket:
        result.paper_bed[support] = bed_for_frequency(
            the_racket, model, support, xy, spring, PAPER_BALL_MODE_HZ, the_ball, the_hand
        )
    result.node_line[support] = _node_line(alone, result.axis_x, xy[0])
    if stiffer is not None:
        harder = racket_modes(the_racket, stiffer, support, xy, spring, the_ball, the_hand)
        result.checks[support] = FrameCheck(
            support,
            FRAME_STIFFNESS_FACTOR,
            with_ball.ball_frequency,
            harder.ball_frequency,
            _frame_frequencies(with_ball, model),
            _frame_frequencies(harder, model),
        )


def _compound_rows(result: CompoundResult) -> list[dict[str, Any]]:
    """``compound.csv``'s rows (:data:`COMPOUND_COLUMNS`): each support's elastic modes with
    the ball, the contact times on the ball mode."""
    rows = []
    for support in result.supports:
        modes = result.modes[support]
        for k, name in enumerate(modes.names):
            ball_mode = k == modes.ball_mode
            times = result.contact_time[support] if ball_mode else [None] * 3
            rows.append(
                {
                    "support": support,
                    "mode": name,
                    "frequency_hz": float(modes.frequency[k]),
                    "damping_ratio": float(modes.damping_ratio[k]),
                    "ball_to_frame_ratio": float(modes.ball_to_frame_ratio[k]),
                    "half_period_s": modes.half_period if ball_mode else None,
                    **dict(zip(COMPOUND_COLUMNS[-3:], times, strict=True)),
                }
            )
    return rows


def _blow_record(result: CompoundResult, patch: float, string_bed: str) -> dict[str, Any]:
    """run.json's points, the hammer's blow and how it is shared (``patch``: the resting
    patch's radius, m), the spring's law and the neck's readings."""
    return {
        "point_m": list(result.location),
        "hammer_point_m": list(result.hammer),
        "hammer_blow_s": result.blow_s,
        "hammer_blow": "a half-sine of unit impulse as long as the hammer's contact with the "
        "strings there (racketdyn.rig.hammer.string_contact_time), shared through the strings "
        "between the ball, the frame under it and the frame at the hammer's point as "
        "hammer_share says",
        "hammer_share": {
            **result.blow_share,
            "patch_radius_m": patch,
            "why": "the strings are folded into the ball's spring, so a blow on them is shared "
            "by hand: the strings under the ball take the share of the string net "
            "(racketdyn.contact.net_share, a patch of half the larger string spacing: the ball "
            "rests on the nearest two mains and two crosses; the patch taken at the head's "
            "centre, so near the frame the share is somewhat high), which splits "
            "k_B/(k_B + k_G) to the ball and the rest to the frame under it; the remainder acts "
            "on the frame at "
            "the hammer's point",
        },
        "neck_point_m": list(result.neck),
        "ball_overhangs_bed": result.overhangs,
        "string_bed": string_bed,
        "spring_law_at": (
            "the centre of the face (contact.compound_law) wherever the ball sits"
            if string_bed == "uniform"
            else "the ball's point (contact.local_compound_law)"
        ),
        "neck_hand_over": result.hand_over,
        "two_node_node_line_m": result.node_line,
    }


def _modes_record(result: CompoundResult, the_racket: Racket, the_ball: Ball) -> dict[str, Any]:
    """run.json's method, the ball's spring, the modes and their checks, the racket's modal
    model and hand, and the columns."""
    spring, model, checked = result.spring, result.model, result.supports
    assert spring is not None
    return {
        "method": "linear modes of ball + ball–string spring + racket (racketdyn.impact."
        "compound): the racket's rigid body and flexible modes (string-bed modes left out: the "
        "spring carries the strings), complex eigenvalues of the damped system",
        "ball_spring": {
            **asdict(spring),
            "why": "a ball stuck on the strings sits on a slightly preloaded bed: the small-"
            "amplitude spring is the tangent dF_GB/dX of the compound ball + string-bed law "
            f"at the preload; its dashpot gives a linear contact the ball's e_BG = "
            f"{small_amplitude_e_bg(the_racket, the_ball):.3g}",
            "stiffness_n_per_m_at": {
                f"{f:g} N": ball_spring(the_racket, the_ball, f, spring.location).stiffness
                for f in (0.0, 20.0)
            },
        },
        "contact_speeds_mps": list(CONTACT_SPEEDS_MPS),
        "contact_time_support": {s: _APPROXIMATE_SUPPORT[s] for s in checked},
        "ball_mode_hz": {s: result.modes[s].ball_frequency for s in checked},
        "frame_mode_shifts": {s: frame_shifts(result.modes[s], result.alone[s]) for s in checked},
        "frame_stiffness_check": [c.as_dict() for c in result.checks.values()],
        "ball_mode_band": {s: _band_record(result, s) for s in checked},
        "modal_model": None if model is None else model.summary(),
        "hand": None if result.hand is None else asdict(result.hand),
        "columns": {"compound.csv": list(COMPOUND_COLUMNS)},
    }


def _band_record(result: CompoundResult, support: str) -> dict[str, Any]:
    """run.json's ball-mode band of one support, held against the paper's 103 Hz only on the
    paper's racket."""
    band = result.band[support]
    return {
        **band.as_dict(),
        "why": "the ball mode at the corners of the small-amplitude inputs' spread: "
        "ball one-sided stiffness (ITF forward deformation, halved), the bed under the "
        "ball (published static stiffness and the per-string law, to the string net "
        "pushed over the ball's width), ball mass (ITF); racketdyn.impact.compound_band",
        "paper_hz": PAPER_BALL_MODE_HZ,
        "paper_racket": result.paper_racket,
        **(
            {
                "paper_inside": band.holds(PAPER_BALL_MODE_HZ),
                "bed_for_paper": result.paper_bed[support].as_dict(),
            }
            if result.paper_racket
            else {
                "paper_inside": None,
                "bed_for_paper": None,
                "paper_note": NOT_THE_PAPERS_RACKET,
            }
        ),
    }


def is_papers_racket(racket: Racket) -> bool:
    """Whether ``racket`` is the paper's (the built-in racket, whatever its name): the only one
    whose ball mode the paper's measured 103 Hz can check (section 3.2)."""
    built_in = default_racket()
    return replace(racket, name=built_in.name) == built_in


def _node_line(alone: CompoundSystem, axis_x: NDArray[np.float64], ball_x: float) -> float:
    """Where the racket's 2-node mode crosses the long axis nearest the ball, m (NaN: none).

    The mode's shape at the axis points (``alone.rows[3:]``: after the ball's point, the
    hammer's and the neck's), its phase taken off, zero crossings interpolated linearly."""
    if "2-node bending" not in alone.names:
        return math.nan
    shape = alone.rows[3:] @ alone.shapes[:, alone.names.index("2-node bending")]
    shape = np.real(shape * np.exp(-1j * np.angle(shape[np.argmax(np.abs(shape))])))
    left, right = shape[:-1], shape[1:]
    at = np.flatnonzero(np.sign(left) * np.sign(right) < 0)
    if at.size == 0:
        return math.nan
    crossings = axis_x[at] + (axis_x[at + 1] - axis_x[at]) * left[at] / (left[at] - right[at])
    return float(crossings[np.argmin(np.abs(crossings - ball_x))])


def _hand_over(
    system: CompoundSystem, times: NDArray[np.float64], response: NDArray[np.float64], blow: float
) -> tuple[dict[str, NDArray[np.float64]], dict[str, float]]:
    """The ball mode's and 2-node mode's parts of the neck's response, and when the second
    overtakes the first (their envelopes after the blow), in ball-mode cycles."""
    f_ball, f_bend = system.ball_frequency, system.frequency_of("2-node bending")
    if not (math.isfinite(f_ball) and math.isfinite(f_bend)):
        return {}, {"ball_to_two_node": math.nan, "ball_cycles": math.nan}
    frequency, amplitude, parts, decay = system.modal_parts(times, response, blow)
    k_ball = int(np.argmin(np.abs(frequency - f_ball)))
    k_bend = int(np.argmin(np.abs(frequency - f_bend)))
    ratio = float(amplitude[k_ball] / amplitude[k_bend])
    gap = float(decay[k_ball] - decay[k_bend])  # envelopes a·e^(−σ t) cross at ln(ratio)/gap
    cycles = 0.0 if ratio <= 1.0 else (math.log(ratio) / gap * f_ball if gap > 0 else math.inf)
    named = {"ball": parts[k_ball], "2-node bending": parts[k_bend]}
    return named, {"ball_to_two_node": ratio, "ball_cycles": cycles}


def _frame_frequencies(modes: CompoundSystem, model: ModalModel | None) -> dict[str, float]:
    """The compound system's modes that carry a name of the racket's flexible modes, Hz."""
    names = set() if model is None else set(model.frame_modes.names)
    return {
        n: float(f)
        for n, f in zip(modes.names, modes.frequency, strict=True)
        if n in names and n != BALL_MODE_NAME
    }
