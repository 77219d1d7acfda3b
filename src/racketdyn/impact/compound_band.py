"""How far the ball mode of a ball fixed on the strings can lie from its nominal value.

The ball mode (:mod:`racketdyn.impact.compound`) rests on three inputs at small amplitude, none
of them measured on the racket at hand: the ball's one-sided stiffness, the string bed's
stiffness under the ball and the ball's mass.  Their spread:

- **ball**, one-sided: the wall of the ball's bounce (:func:`racketdyn.ball.
  dynamic_wall_stiffness`) over the spread of its measurement, 5–7 mm of flattening at
  7.06 m/s on a rigid surface (Cross's "about 6 mm"; docs/references.md, "The ball in a
  bounce"): ≈ 58–115 kN/m.  Nothing readable gave the stiffness of a ball stuck on strings and
  shaken by a hammer (before issue 22 the slow ITF plate test's 21.6–28.6 kN/m stood here).
- **bed**, under the ball: from the smaller of the published static stiffness of strung beds
  (20 kN/m) and the per-string law the impact model uses (:func:`racketdyn.contact.
  string_bed_law`, only the strings under the ball), to the larger of the published 40 kN/m
  and the string net pushed over the ball's whole width
  (:func:`racketdyn.contact.membrane_patch_stiffness` at the ball's radius: the crosses beside
  the ball pull on the mains too).  How much of the bed a stuck ball pushes depends on how it
  was stuck, which the paper does not say.
- **ball mass**: 56.0–59.4 g (ITF).

:func:`ball_mode_band` takes the ball mode along the bed's range at every corner of ball
stiffness and mass (where the ball mode crosses a frame mode it jumps, and the box leaves a
gap);
:func:`bed_for_frequency` turns a measured ball mode (the paper's 103 Hz) back into the bed
stiffness, and the net's patch radius, it needs with the nominal ball.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from itertools import pairwise, product

import numpy as np
import scipy.optimize
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import BOUNCE_COMPRESSION_M, Ball, dynamic_wall_stiffness
from racketdyn.contact import membrane_patch_radius, membrane_patch_stiffness
from racketdyn.impact.compound import BallSpring, racket_modes, spring_split
from racketdyn.impact.hand import Hand
from racketdyn.modal import ModalModel
from racketdyn.racket import Racket

__all__ = [
    "BALL_MASS_KG",
    "BALL_STIFFNESS_N_PER_M",
    "BED_STATIC_STIFFNESS_N_PER_M",
    "PAPER_BALL_MODE_HZ",
    "BallModeBand",
    "BedForFrequency",
    "ball_mode_band",
    "bed_for_frequency",
]

PAPER_BALL_MODE_HZ = 103.0
"""The paper's ball mode (section 3.2, Fig. 9b), Hz."""
BALL_STIFFNESS_N_PER_M = (
    dynamic_wall_stiffness(compression_m=BOUNCE_COMPRESSION_M + 1e-3),
    dynamic_wall_stiffness(compression_m=BOUNCE_COMPRESSION_M - 1e-3),
)
"""One-sided small-amplitude ball stiffness, N/m: the bounce's wall at 7 and 5 mm of flattening
at 7.06 m/s (the gas adds nothing at small flattening)."""
BED_STATIC_STIFFNESS_N_PER_M = (20e3, 40e3)
"""Published static stiffness of strung beds, N/m (docs/references.md, "Ball fixed on the
strings")."""
BALL_MASS_KG = (0.0560, 0.0594)
"""ITF ball mass range, kg."""
BED_SAMPLES = 13
JUMP_BISECTIONS = 12
"""Halvings locating a jump of the ball mode between two sampled beds (to 1/4096 of the step)."""
"""Bed stiffnesses sampled (geometrically) along the box's bed range at each corner."""
JUMP_FACTOR = 5.0
"""A step of the ball mode this many times the median step along the bed's range is a jump."""


@dataclass(frozen=True)
class BallModeBand:
    """The ball mode's range over the small-amplitude inputs' spread.

    Attributes
    ----------
    nominal_hz : float
        The ball mode with the built-in spring, Hz.
    low_hz, high_hz : float
        Smallest and largest ball mode over the inputs' box, Hz.
    ball_stiffness_n_per_m, bed_stiffness_n_per_m : tuple of float
        The box's ball and bed stiffness ranges, N/m.
    ball_mass_kg : tuple of float
        The box's ball mass range, kg.
    intervals_hz : tuple of (float, float)
        The frequencies the box reaches, Hz: one interval, or several where the ball mode
        jumps as it crosses a frame mode (the mode with the ball's largest energy share
        changes) and leaves a gap no input gives.
    """

    nominal_hz: float
    low_hz: float
    high_hz: float
    ball_stiffness_n_per_m: tuple[float, float]
    bed_stiffness_n_per_m: tuple[float, float]
    ball_mass_kg: tuple[float, float]
    intervals_hz: tuple[tuple[float, float], ...] = ()

    def holds(self, frequency_hz: float) -> bool:
        """Whether a frequency lies within the band (ends included) and not in a gap."""
        if not self.low_hz <= frequency_hz <= self.high_hz:
            return False
        return not self.intervals_hz or any(a <= frequency_hz <= b for a, b in self.intervals_hz)

    def as_dict(self) -> dict[str, object]:
        """Plain numbers for run.json (SI)."""
        return {
            "nominal_hz": self.nominal_hz,
            "band_hz": [self.low_hz, self.high_hz],
            "intervals_hz": [list(pair) for pair in self.intervals_hz],
            "ball_stiffness_n_per_m": list(self.ball_stiffness_n_per_m),
            "bed_stiffness_n_per_m": list(self.bed_stiffness_n_per_m),
            "ball_mass_kg": list(self.ball_mass_kg),
        }


@dataclass(frozen=True)
class BedForFrequency:
    """The bed under the nominal ball that puts the ball mode at a given frequency.

    Attributes
    ----------
    frequency_hz : float
        The frequency asked for, Hz.
    bed_stiffness_n_per_m : float
        Small-amplitude bed stiffness that gives it, N/m; NaN if no bed stiffness does (the
        nominal ball alone is too soft or too stiff for it).
    patch_radius_m : float
        Radius of the patch of the string net (:func:`membrane_patch_stiffness`) with that
        stiffness, m; NaN when the bed stiffness is NaN or beyond the head.
    note : str
        Why the bed stiffness is NaN ("" when it is found).
    """

    frequency_hz: float
    bed_stiffness_n_per_m: float
    patch_radius_m: float
    note: str = ""

    def as_dict(self) -> dict[str, object]:
        """Plain numbers for run.json (SI; NaN as is) and why there is none."""
        return dataclasses.asdict(self)


def ball_mode_band(
    racket: Racket,
    model: ModalModel | None,
    support: str,
    location: ArrayLike,
    spring: BallSpring,
    ball: Ball | None = None,
    hand: Hand | None = None,
) -> BallModeBand:
    """The ball mode over the corners of the small-amplitude inputs' spread (module docstring).

    Parameters
    ----------
    racket, model, support, location, ball, hand
        As :func:`racketdyn.impact.compound.racket_modes`.
    spring : BallSpring
        The built-in spring (its ζ and preload are kept; the stiffness is varied).

    Returns
    -------
    BallModeBand
    """
    the_ball = ball or Ball()
    k_law = spring.bed_stiffness  # the per-string law's tangent where the spring was taken
    net = membrane_patch_stiffness(racket, the_ball.diameter_m / 2.0)
    bed = (  # the spring's own bed inside too (a local law near the frame may pass the net's)
        min(BED_STATIC_STIFFNESS_N_PER_M[0], k_law),
        max(BED_STATIC_STIFFNESS_N_PER_M[1], net, k_law),
    )
    # the ball mode along the bed's range at each corner of ball stiffness and mass: monotone
    # unless the ball mode jumps across a frame mode, which leaves a gap (review, 2026-11-26)
    beds = np.geomspace(bed[0], bed[1], BED_SAMPLES)
    intervals = []
    for k_b, m_b in product(BALL_STIFFNESS_N_PER_M, BALL_MASS_KG):

        def ball_hz(k_g: float, k_b: float = k_b, m_b: float = m_b) -> float:
            return racket_modes(
                racket, model, support, location,
                replace(spring, stiffness=1.0 / (1.0 / k_b + 1.0 / k_g)),
                replace(the_ball, mass_kg=m_b), hand,
            ).ball_frequency  # fmt: skip

        intervals += _pieces(np.array([ball_hz(k_g) for k_g in beds]), beds, ball_hz)
    nominal = racket_modes(racket, model, support, location, spring, the_ball, hand)
    merged = _merge(intervals)
    return BallModeBand(
        nominal.ball_frequency,
        merged[0][0],
        merged[-1][1],
        BALL_STIFFNESS_N_PER_M,
        bed,
        BALL_MASS_KG,
        tuple(merged),
    )


def _pieces(
    curve: NDArray[np.float64],
    beds: NDArray[np.float64],
    ball_hz: Callable[[float], float],
) -> list[tuple[float, float]]:
    """The curve's stretches between jumps: a step more than :data:`JUMP_FACTOR` times the
    median step (and over 2 % of the frequency) is a jump of the ball mode's identity.

    Each jump is located by bisection on the bed's stiffness (:data:`JUMP_BISECTIONS` halvings
    of its logarithm), and the stretches on either side reach the values found there: the
    sampled ends alone left a nominal ball mode 0.05 Hz past its stretch's end in a gap
    (issue 22, the frame's shape: the throat's ball mode veering with the 2-node mode)."""
    steps = np.abs(np.diff(curve))
    typical = float(np.median(steps)) if steps.size else 0.0
    jumps = np.flatnonzero((steps > JUMP_FACTOR * typical) & (steps > 0.02 * curve[:-1]))
    bounds = [0, *(jumps + 1).tolist(), curve.size]
    ends = {int(j): _jump_ends(float(beds[j]), float(beds[j + 1]), curve[j : j + 2], ball_hz)
            for j in jumps}  # fmt: skip
    pieces = []
    for a, b in pairwise(bounds):
        values = [*curve[a:b], *(ends[a - 1][1:] if a - 1 in ends else ()),
                  *(ends[b - 1][:1] if b - 1 in ends else ())]  # fmt: skip
        pieces.append((float(min(values)), float(max(values))))
    return pieces


def _jump_ends(
    low: float, high: float, values: NDArray[np.float64], ball_hz: Callable[[float], float]
) -> tuple[float, float]:
    """The ball mode just before and just after a jump between beds ``low`` and ``high``."""
    before, after = float(values[0]), float(values[1])
    for _ in range(JUMP_BISECTIONS):
        middle = float(np.sqrt(low * high))
        value = ball_hz(middle)
        if abs(value - before) <= abs(value - after):
            low, before = middle, value
        else:
            high, after = middle, value
    return before, after


def _merge(intervals: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Overlapping intervals joined, in order."""
    merged: list[tuple[float, float]] = []
    for low, high in sorted(intervals):
        if merged and low <= merged[-1][1]:
            merged[-1] = (merged[-1][0], max(merged[-1][1], high))
        else:
            merged.append((low, high))
    return merged


def bed_for_frequency(
    racket: Racket,
    model: ModalModel | None,
    support: str,
    location: ArrayLike,
    spring: BallSpring,
    frequency_hz: float,
    ball: Ball | None = None,
    hand: Hand | None = None,
) -> BedForFrequency:
    """The bed stiffness under the nominal ball that puts the ball mode at ``frequency_hz``.

    The ball's part of the spring is kept (its tangent at the preload); the bed's is solved for
    with Brent's method between 1 kN/m and 10 MN/m; the patch radius is
    :func:`racketdyn.contact.membrane_patch_radius` of it.

    Parameters
    ----------
    racket, model, support, location, spring, ball, hand
        As :func:`ball_mode_band`.
    frequency_hz : float
        The ball mode wanted (e.g. the paper's 103 Hz), Hz.

    Returns
    -------
    BedForFrequency
    """
    the_ball = ball or Ball()
    k_ball, _ = spring_split(spring)

    def miss(log_bed: float) -> float:
        k = 1.0 / (1.0 / k_ball + 1.0 / math.exp(log_bed))
        trial = replace(spring, stiffness=k)
        modes = racket_modes(racket, model, support, location, trial, the_ball, hand)
        return modes.ball_frequency - frequency_hz

    low, high = math.log(1e3), math.log(1e7)
    if miss(low) * miss(high) > 0:
        return BedForFrequency(
            frequency_hz, math.nan, math.nan, "no bed stiffness from 1 kN/m to 10 MN/m gives it"
        )
    log_bed = scipy.optimize.brentq(miss, low, high, xtol=1e-10)
    if abs(miss(log_bed)) > 1e-6 * frequency_hz:  # a sign change across a jump, no root
        return BedForFrequency(
            frequency_hz, math.nan, math.nan,
            "no bed stiffness gives it: the ball mode jumps past it as it crosses a frame mode",
        )  # fmt: skip
    bed = math.exp(log_bed)
    return BedForFrequency(frequency_hz, bed, membrane_patch_radius(racket, bed))
