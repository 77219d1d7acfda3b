"""The result of an impact prediction over impact points × speeds × supports."""

from __future__ import annotations

import csv
import re
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.impact.spectrum import half_sine_spectrum
from racketdyn.modal.model import ModalModel

__all__ = [
    "CSV_COLUMNS",
    "SHOWN_SPEED_MPS",
    "STATUS_BEYOND_LAW",
    "STATUS_OK",
    "STATUS_VIBRATION_LOSS",
    "ImpactResult",
    "impact_columns",
    "shown_speed_index",
    "slug",
    "write_columns",
]

STATUS_OK = "ok"
STATUS_VIBRATION_LOSS = "vibration loss exceeds e_BG"
STATUS_BEYOND_LAW = "deflection beyond the restoring-force law"

CSV_COLUMNS = (
    "point",
    "x_m",
    "y_m",
    "support",
    "ball_speed_mps",
    "racket_speed_mps",
    "reduced_mass_kg",
    "stiffness_n_per_m",
    "contact_time_s",
    "mean_force_n",
    "peak_force_n",
    "vibration_energy_j",
    "cor",
    "rebound_ratio",
    "rebound_speed_mps",
    "peak_deflection_m",
    "status",
)
"""Columns of ``impact.csv`` (the first fifteen in the order the foundation issue fixes); one
``energy_<mode name>_j`` column per mode follows."""


@dataclass(frozen=True, eq=False)
class ImpactResult:
    """Predicted impact quantities, arrays shaped ``(n_points, n_speeds, n_supports)``.

    Attributes
    ----------
    locations : ndarray (n_points, 2)
        Impact points (x, y), m.
    labels : tuple of str
        Point labels.
    ball_speed, racket_speed : ndarray (n_speeds,)
        Incoming ball speed and racket speed at the impact point (towards each other), m/s.
    supports : tuple of str
        Support conditions.
    reduced_mass : ndarray (n_points, n_supports)
        Reduced mass of the racket at the impact point, kg (eq 4).
    stiffness : ndarray
        Compound ball+string stiffness K_GB reached at the peak deflection, N/m (eqs 9–10).
    peak_deflection : ndarray
        Peak compound deflection, m.
    contact_time : ndarray
        T_c, s (eq 7).
    mean_force, peak_force : ndarray
        F_MEAN (eqs 8–10) and F_MAX = π F_MEAN / 2 (eq 11), N.
    mode_energy : ndarray (…, n_modes)
        Vibration energy per mode after the impact, J.
    vibration_energy : ndarray
        Sum over modes, J.
    cor : ndarray
        Ball–racket coefficient of restitution after the vibration loss, e_r (NaN where the
        status is not ``ok``).
    rebound_ratio : ndarray
        Rebound power coefficient e = (e_r − m_B/M_r)/(1 + m_B/M_r): the ratio of rebound to
        incident ball speed on a racket at rest.
    rebound_speed : ndarray
        Outgoing ball speed e·v_ball + (1 + e)·v_racket, m/s.
    status : ndarray of str
        ``ok`` or why the numbers are missing.
    modal_model : ModalModel or None
        The modes used (None: rigid racket).
    inputs : dict
        What produced the result (racket, ball, laws, version) for run records.
    energy_terms : dict of str to ndarray, optional
        Transient model only: where the ball's energy went, J, in the frame where the racket is
        at rest before the impact (``energy_in_j`` = ``ball_energy_out_j`` +
        ``racket_energy_j`` (rigid body) + ``vibration_energy_j`` + ``support_energy_j`` (hand
        and arm) + ``hysteresis_loss_j`` + ``damping_loss_j``; see
        :data:`racketdyn.impact.transient.ENERGY_TERMS`).
    """

    locations: NDArray[np.float64]
    labels: tuple[str, ...]
    ball_speed: NDArray[np.float64]
    racket_speed: NDArray[np.float64]
    supports: tuple[str, ...]
    reduced_mass: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    peak_deflection: NDArray[np.float64]
    contact_time: NDArray[np.float64]
    mean_force: NDArray[np.float64]
    peak_force: NDArray[np.float64]
    mode_energy: NDArray[np.float64]
    vibration_energy: NDArray[np.float64]
    cor: NDArray[np.float64]
    rebound_ratio: NDArray[np.float64]
    rebound_speed: NDArray[np.float64]
    status: NDArray[np.str_]
    modal_model: ModalModel | None
    inputs: dict[str, Any]
    energy_terms: dict[str, NDArray[np.float64]] | None = None

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(n_points, n_speeds, n_supports)``."""
        return (self.locations.shape[0], self.ball_speed.size, len(self.supports))

    @property
    def impulse(self) -> NDArray[np.float64]:
        """Impulse F_MEAN · T_c = (1 + e_BG) μ V, N·s (eqs 6 and 8)."""
        return np.asarray(self.mean_force * self.contact_time)

    @classmethod
    def concatenate(cls, parts: Sequence[ImpactResult]) -> ImpactResult:
        """Join results computed on consecutive chunks of points (same speeds, supports, model)."""
        if not parts:
            raise ValueError("nothing to concatenate")
        first = parts[0]
        for part in parts[1:]:
            same = (
                np.array_equal(part.ball_speed, first.ball_speed)
                and np.array_equal(part.racket_speed, first.racket_speed)
                and part.supports == first.supports
                and part.modal_model is first.modal_model
            )
            if not same:
                raise ValueError("results differ in speeds, supports or modal model")
        joined: dict[str, Any] = {
            name: np.concatenate([getattr(p, name) for p in parts], axis=0)
            for name in (
                "locations",
                "reduced_mass",
                "stiffness",
                "peak_deflection",
                "contact_time",
                "mean_force",
                "peak_force",
                "mode_energy",
                "vibration_energy",
                "cor",
                "rebound_ratio",
                "rebound_speed",
                "status",
            )
        }
        labels = tuple(label for p in parts for label in p.labels)
        terms = None
        if all(p.energy_terms is not None for p in parts) and first.energy_terms is not None:
            terms = {
                name: np.concatenate([p.energy_terms[name] for p in parts], axis=0)  # type: ignore[index]
                for name in first.energy_terms
            }
        return replace(first, labels=labels, energy_terms=terms, **joined)

    def support_index(self, support: str) -> int:
        """Index of a support on the last axis."""
        return self.supports.index(support)

    def displacement_amplitude(self, response: ArrayLike) -> NDArray[np.float64]:
        """Vibration displacement amplitude per mode just after the impact (eq 12), m.

        ``X_ijk = |A_ijk| |S_j(ω_k)| / ω_k`` with ``A_ijk = φ_ik φ_jk``: the free vibration of
        mode k left by the half-sine pulse at impact point j, seen at response point i.

        Returns an array shaped ``(n_response, n_points, n_speeds, n_supports, n_modes)``.
        """
        if self.modal_model is None:
            raise ValueError("a rigid racket (no modal model) does not vibrate")
        model = self.modal_model
        constants = np.abs(model.modal_constants(response, self.locations))  # (r, n, m)
        spectrum = half_sine_spectrum(
            model.frequency, self.contact_time[..., None], self.peak_force[..., None]
        )  # (n, s, p, m)
        return np.asarray(constants[:, :, None, None, :] * spectrum[None] / model.omega)

    def columns(self) -> dict[str, NDArray[Any]]:
        """The ``impact.csv`` table as flat columns, one row per point × speed × support."""
        return impact_columns(self, self.racket_speed[None, :, None])

    def write_csv(self, path: Path) -> None:
        """Write ``impact.csv``: SI units named in the header, NaN where status is not ``ok``."""
        write_columns(path, self.columns())


def impact_columns(result: Any, racket_speed: NDArray[np.float64]) -> dict[str, NDArray[Any]]:
    """The ``impact.csv`` columns of any result with :class:`ImpactResult`'s arrays.

    Parameters
    ----------
    result : ImpactResult or alike
        Has ``shape``, ``labels``, ``locations``, ``supports``, ``ball_speed``,
        ``reduced_mass``, the impact arrays, ``status``, ``modal_model`` and ``mode_energy``.
    racket_speed : ndarray
        Racket speed broadcastable to ``(n_points, n_speeds, n_supports)``, m/s (one per speed
        for :class:`ImpactResult`, one per point for a swing).
    """
    n, s, p = result.shape
    point = np.broadcast_to(np.asarray(result.labels, dtype=object)[:, None, None], (n, s, p))
    table: dict[str, NDArray[Any]] = {
        "point": point,
        "x_m": np.broadcast_to(result.locations[:, 0, None, None], (n, s, p)),
        "y_m": np.broadcast_to(result.locations[:, 1, None, None], (n, s, p)),
        "support": np.broadcast_to(np.asarray(result.supports, dtype=object), (n, s, p)),
        "ball_speed_mps": np.broadcast_to(result.ball_speed[None, :, None], (n, s, p)),
        "racket_speed_mps": np.broadcast_to(racket_speed, (n, s, p)),
        "reduced_mass_kg": np.broadcast_to(result.reduced_mass[:, None, :], (n, s, p)),
        "stiffness_n_per_m": result.stiffness,
        "contact_time_s": result.contact_time,
        "mean_force_n": result.mean_force,
        "peak_force_n": result.peak_force,
        "vibration_energy_j": result.vibration_energy,
        "cor": result.cor,
        "rebound_ratio": result.rebound_ratio,
        "rebound_speed_mps": result.rebound_speed,
        "peak_deflection_m": result.peak_deflection,
        "status": result.status,
    }
    flat = {name: np.asarray(table[name]).reshape(-1) for name in CSV_COLUMNS}
    if result.modal_model is not None:
        for k, name in enumerate(result.modal_model.names):
            flat[f"energy_{slug(name)}_j"] = result.mode_energy[..., k].reshape(-1)
    return flat


SHOWN_SPEED_MPS = 20.0
"""Ball speed that single-speed figures and summaries show when it is among the speeds (the
paper's Fig. 15 speed), m/s."""


def shown_speed_index(speeds: ArrayLike) -> int:
    """Index of the ball speed single-speed figures and summaries show: 20 m/s if given, else
    the middle of the speeds in increasing order (the same rule for the CLI and the report)."""
    values = np.asarray(speeds, dtype=float)
    hit = np.flatnonzero(values == SHOWN_SPEED_MPS)
    if hit.size:
        return int(hit[0])
    return int(np.argsort(values, kind="stable")[(values.size - 1) // 2])


def slug(name: str) -> str:
    """A mode's name as a column-name part: lower case, runs of other characters as ``_``."""
    return re.sub(r"[^a-z0-9]+", "_", name.lower()).strip("_")


def write_columns(path: Path, columns: dict[str, NDArray[Any]]) -> None:
    """Write flat columns as CSV (header = column names), NaN as ``nan``, 9 digits."""
    with Path(path).open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(columns)
        for row in zip(*columns.values(), strict=True):
            writer.writerow(_format(value) for value in row)


def _format(value: Any) -> str:
    if isinstance(value, float | np.floating):
        return "nan" if not np.isfinite(value) else f"{float(value):.9g}"
    return str(value)
