"""The ball's bounce on a rigid surface and on a head-clamped string bed (issue 22).

The check a lab runs on a new ball: drop or fire it at a rigid surface (the ITF rebound test,
a force plate) and at a racket clamped by its head, and compare flattening, COR, contact time
and peak force with what the ball law predicts.  Both bounces are the transient model's
hysteretic contact (:func:`racketdyn.impact.transient.simulate_contact`) on an immovable
target:

* ``rigid``: the ball's own law F_B(X) (``ball.restoring_force``), unloading to return the
  ball's rigid-surface COR (``ball.rigid_cor``);
* ``strings``: the ball and the string bed at the face centre in series (section 3.4's F_GB,
  :func:`racketdyn.contact.compound_law`), unloading to return e_BG (given, or from ball +
  strings: :func:`racketdyn.contact.with_ball_string_cor`); the ball's own flattening is the
  ball law's deflection under the contact force.

Units: SI (m, s, N); ``peak_compression_m`` is the ball's own flattening on both surfaces.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law, with_ball_string_cor
from racketdyn.errors import InputError, one_of, require_speeds
from racketdyn.impact.result import write_columns
from racketdyn.impact.transient import simulate_contact
from racketdyn.racket import Racket

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes

__all__ = ["BALL_COLUMNS", "SURFACES", "BallBounces", "Surface", "ball_bounces"]

Surface = Literal["rigid", "strings"]
SURFACES: tuple[str, ...] = get_args(Surface)
BALL_COLUMNS: tuple[str, ...] = (
    "speed_mps",
    "surface",
    "peak_compression_m",
    "cor",
    "contact_time_s",
    "peak_force_n",
    "bed_deflection_m",
)
"""Columns of ``ball.csv``, one row per surface × speed (``bed_deflection_m`` is 0 on the
rigid surface)."""


@dataclass(frozen=True, eq=False)
class BallBounces:
    """Bounces of one ball on each surface at each speed, with their force–compression loops.

    Attributes
    ----------
    speeds : ndarray (s,)
        Impact speeds, m/s.
    surfaces : tuple of str
        ``rigid`` and/or ``strings``.
    peak_compression, cor, contact_time, peak_force, bed_deflection : ndarray (n_surfaces, s)
        The ball's largest flattening (m), the COR (rebound / impact speed), the contact time
        (s), the largest force (N) and the bed's largest deflection (m, 0 on the rigid surface).
    loop_compression, loop_force : ndarray (n_surfaces, s, n_t)
        The compression (m) — the ball's flattening on the rigid surface, the ball's and the
        bed's together on the strings (their loop: the hysteresis is the pair's) — and the
        force (N) through each contact, resampled on ``n_t`` equal steps of time from first
        contact to separation.
    e_bg_record : dict
        How e_BG on the strings was set.
    """

    speeds: NDArray[np.float64]
    surfaces: tuple[str, ...]
    peak_compression: NDArray[np.float64]
    cor: NDArray[np.float64]
    contact_time: NDArray[np.float64]
    peak_force: NDArray[np.float64]
    bed_deflection: NDArray[np.float64]
    loop_compression: NDArray[np.float64]
    loop_force: NDArray[np.float64]
    e_bg_record: dict[str, Any]

    def rows(self) -> list[dict[str, Any]]:
        """One dict per surface × speed, keyed by :data:`BALL_COLUMNS`."""
        return [
            {
                "speed_mps": float(speed),
                "surface": surface,
                "peak_compression_m": float(self.peak_compression[i, j]),
                "cor": float(self.cor[i, j]),
                "contact_time_s": float(self.contact_time[i, j]),
                "peak_force_n": float(self.peak_force[i, j]),
                "bed_deflection_m": float(self.bed_deflection[i, j]),
            }
            for i, surface in enumerate(self.surfaces)
            for j, speed in enumerate(self.speeds)
        ]

    def write_csv(self, path: Path) -> Path:
        """Write ``ball.csv`` (:data:`BALL_COLUMNS`, SI units)."""
        rows = self.rows()
        write_columns(
            path, {name: np.asarray([row[name] for row in rows]) for name in BALL_COLUMNS}
        )
        return path

    def to_xarray(self) -> xr.Dataset:
        """The bounces and their loops as a labelled dataset (dims surface, speed, sample)."""
        import xarray as xr

        dims = ("surface", "speed")
        return xr.Dataset(
            {
                "peak_compression_m": (dims, self.peak_compression),
                "cor": (dims, self.cor),
                "contact_time_s": (dims, self.contact_time),
                "peak_force_n": (dims, self.peak_force),
                "bed_deflection_m": (dims, self.bed_deflection),
                "loop_compression_m": ((*dims, "sample"), self.loop_compression),
                "loop_force_n": ((*dims, "sample"), self.loop_force),
            },
            coords={"surface": list(self.surfaces), "speed": ("speed", self.speeds)},
            attrs={"speed_units": "m/s", "e_bg": str(self.e_bg_record)},
        )

    def plot(self, axes: Sequence[Axes] | None = None) -> list[Axes]:
        """Force against the ball's flattening (the hysteresis loop), one panel per surface.

        Draws only what this object holds: flattening in mm, force in N, one loop per speed.
        """
        from racketdyn.plotting.ball import draw_ball_loops

        return draw_ball_loops(self, axes)


def _one(
    surface: str, ball: Ball, law: RestoringForce, speed: float, samples: int
) -> tuple[list[float], NDArray[np.float64], NDArray[np.float64]]:
    """Numbers and loop of one bounce on ``law`` (the ball's, or ball + strings)."""
    e = ball.rigid_cor if surface == "rigid" else float(ball.e_bg_at(speed))
    run = simulate_contact(ball.mass_kg, e, law, math.inf, speed)
    if run.status != "ok":
        nan = np.full(samples, np.nan)
        return [math.nan] * 5, nan, nan
    t = np.linspace(0.0, run.contact_time_s, samples)
    force = np.interp(t, run.time_s, run.force_n)
    ball_law = ball.restoring_force
    compression = np.interp(t, run.time_s, run.deflection_m)
    peak_force = float(np.max(run.force_n))
    ball_peak = (
        run.peak_deflection_m if surface == "rigid" else float(ball_law.deflection(peak_force))
    )
    bed = 0.0 if surface == "rigid" else run.peak_deflection_m - ball_peak
    numbers = [ball_peak, run.rebound_speed_mps / speed, run.contact_time_s, peak_force, bed]
    return numbers, compression, force


def ball_bounces(
    ball: Ball,
    speeds: ArrayLike,
    surfaces: Sequence[str] = SURFACES,
    racket: Racket | None = None,
    samples: int = 200,
) -> BallBounces:
    """The ball's bounce on each surface at each speed (see the module docstring).

    Parameters
    ----------
    ball : Ball
        The ball (its law, rigid-surface COR and e_BG).
    speeds : array_like
        Impact speeds, m/s (positive).
    surfaces : sequence of {"rigid", "strings"}
        Which surfaces.
    racket : Racket, optional
        The racket whose head-clamped string bed (at the face centre) the ball meets; needed
        for ``strings``.
    samples : int
        Points of each force–compression loop.

    Returns
    -------
    BallBounces
    """
    v = require_speeds("speeds", speeds)
    if np.any(v <= 0):
        raise InputError("speeds: every impact speed must be above 0 m/s")
    names = tuple(dict.fromkeys(surfaces))
    if not names:
        raise InputError(f"surfaces: choose from {', '.join(SURFACES)}")
    for name in names:
        one_of("surfaces", name, SURFACES)
    if "strings" in names and racket is None:
        raise InputError("surface 'strings' needs the racket whose strings the ball meets")
    resolved = ball if racket is None else with_ball_string_cor(racket, ball)
    table = np.full((5, len(names), v.size), np.nan)
    loops = np.full((2, len(names), v.size, samples), np.nan)
    for i, surface in enumerate(names):
        # one law per surface (the compound law is a least-squares fit: not once per speed)
        law = ball.restoring_force
        if surface == "strings":
            assert racket is not None  # refused above
            law = compound_law(racket, ball)
        for j, speed in enumerate(v):
            numbers, compression, force = _one(surface, resolved, law, float(speed), samples)
            table[:, i, j] = numbers
            loops[0, i, j], loops[1, i, j] = compression, force
    return BallBounces(
        speeds=v,
        surfaces=names,
        peak_compression=table[0],
        cor=table[1],
        contact_time=table[2],
        peak_force=table[3],
        bed_deflection=table[4],
        loop_compression=loops[0],
        loop_force=loops[1],
        e_bg_record=resolved.e_bg_record(),
    )
