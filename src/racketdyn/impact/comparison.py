"""The approximate method against the transient simulation, impact by impact (issue 5).

:func:`compare_models` sets an :class:`~racketdyn.impact.result.ImpactResult` of the
approximate method (:func:`racketdyn.impact.predict`) beside one of the transient simulation
(:func:`racketdyn.impact.transient.predict_transient`) on the same points × speeds × supports,
and :class:`ModelComparison` gives, for the contact time, the peak force, the vibration energy,
the rebound ratio and the rebound speed, both values, their difference and the relative
difference.  The transient simulation is the reference: the difference is the approximate
method's error,

    ``difference = approximate − transient``,
    ``relative difference = (approximate − transient) / |transient|``,

NaN where either has no valid number (its status is not ``ok``) and, for the relative
difference, where the transient value is 0.  ``racketdyn predict --model both`` writes the
table as ``comparison.csv`` (:meth:`ModelComparison.write_csv`, columns in
:data:`COMPARISON_COLUMNS`).

The time histories of a few named impacts (:func:`simulate_histories`) go with it:
``racketdyn predict --model transient|both`` writes them as ``transient_histories.csv``
(:func:`write_histories_csv`, columns in :data:`HISTORY_COLUMNS`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import Ball, RestoringForce
from racketdyn.errors import InputError, one_of
from racketdyn.impact.grid import StringBed, check_string_bed, check_supports, point_law
from racketdyn.impact.result import ImpactResult, slug, write_columns
from racketdyn.impact.transient import TRANSIENT_SUPPORTS, TransientImpact, simulate_impact
from racketdyn.modal.model import ModalModel
from racketdyn.racket import Racket

__all__ = [
    "COMPARED",
    "COMPARISON_COLUMNS",
    "HISTORY_COLUMNS",
    "MODELS_DIFFER",
    "History",
    "ModelComparison",
    "compare_models",
    "simulate_histories",
    "write_histories_csv",
]

MODELS_DIFFER = 0.05
"""|approximate − transient| rebound ratio beyond which a row is flagged ``models_differ``."""

COMPARED: dict[str, str] = {
    "contact_time": "contact_time_s",
    "peak_force": "peak_force_n",
    "vibration_energy": "vibration_energy_j",
    "rebound_ratio": "rebound_ratio",
    "rebound_speed": "rebound_speed_mps",
}
"""Quantities compared: :class:`ImpactResult` attribute → ``impact.csv`` column (with unit)."""

_KEYS = ("point", "x_m", "y_m", "support", "ball_speed_mps", "racket_speed_mps")
COMPARISON_COLUMNS: tuple[str, ...] = (
    *_KEYS,
    *(
        column
        for quantity, name in COMPARED.items()
        for column in (
            f"approx_{name}",
            f"transient_{name}",
            f"difference_{name}",
            f"relative_difference_{quantity}",
        )
    ),
    "status_approx",
    "status_transient",
    "models_differ",
)
"""Columns of ``comparison.csv``, one row per point × speed × support (the order of
``impact.csv``): the impact's keys, then per quantity of :data:`COMPARED` the approximate
value, the transient value, ``difference_…`` = approximate − transient (same unit) and
``relative_difference_…`` = (approximate − transient) / |transient| (–), then both statuses."""

HISTORY_COLUMNS: dict[str, str] = {
    "point": "name of the impact point (centre, tip, …)",
    "x_m": "impact point, m from the butt",
    "y_m": "impact point, m across the long axis",
    "support": "support condition",
    "ball_speed_mps": "incoming ball speed, m/s",
    "racket_speed_mps": "speed of the impact point towards the ball, m/s",
    "time_s": "time from first contact, s",
    "force_n": "contact force, N",
    "ball_displacement_m": "ball displacement into the strings from first contact, m",
    "face_displacement_m": "displacement of the racket face at the impact point (rigid body + "
    "modes), same direction, m",
    "compression_m": "compression of the ball+string spring X = ball − face displacement, m",
    "q_<mode>_m_sqrtkg": "modal coordinate of each mode, m·√kg (mass-normalised shapes)",
}
"""Columns of ``transient_histories.csv`` (long format: one row per time sample)."""


# --- the difference table -----------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class ModelComparison:
    """The approximate method and the transient simulation on the same impacts.

    Build one with :func:`compare_models`.

    Attributes
    ----------
    approximate, transient : ImpactResult
        The two results, arrays shaped ``(n_points, n_speeds, n_supports)``.
    """

    approximate: ImpactResult
    transient: ImpactResult

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(n_points, n_speeds, n_supports)``."""
        return self.approximate.shape

    def values(self, quantity: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(approximate, transient) values of a quantity of :data:`COMPARED`, NaN where not ok.

        Parameters
        ----------
        quantity : str
            A key of :data:`COMPARED` (``rebound_ratio`` …), in the units of ``impact.csv``.
        """
        one_of("quantity", quantity, COMPARED)
        pair = []
        for result in (self.approximate, self.transient):
            value = np.asarray(getattr(result, quantity), dtype=float)
            pair.append(np.where(result.status == "ok", value, np.nan))
        return pair[0], pair[1]

    def difference(self, quantity: str) -> NDArray[np.float64]:
        """Approximate − transient, in the quantity's unit (NaN where either is not ok).

        Parameters
        ----------
        quantity : str
            A key of :data:`COMPARED`.
        """
        approximate, transient = self.values(quantity)
        return np.asarray(approximate - transient)

    def relative_difference(self, quantity: str) -> NDArray[np.float64]:
        """(Approximate − transient) / |transient| (NaN where either is not ok, or transient 0).

        Parameters
        ----------
        quantity : str
            A key of :data:`COMPARED`.
        """
        approximate, transient = self.values(quantity)
        scale = np.where(transient == 0.0, np.nan, np.abs(transient))
        return np.asarray((approximate - transient) / scale)

    @property
    def models_differ(self) -> NDArray[np.bool_]:
        """Rows where the two models' rebound ratios differ by more than :data:`MODELS_DIFFER`
        (both valid): the approximate method's number is not to be trusted there."""
        with np.errstate(invalid="ignore"):
            return np.asarray(np.abs(self.difference("rebound_ratio")) > MODELS_DIFFER)

    @property
    def columns(self) -> dict[str, NDArray[Any]]:
        """The ``comparison.csv`` table: column name → 1-D array (:data:`COMPARISON_COLUMNS`)."""
        keys = self.approximate.columns
        table: dict[str, NDArray[Any]] = {name: keys[name] for name in _KEYS}
        for quantity, name in COMPARED.items():
            approximate, transient = self.values(quantity)
            table[f"approx_{name}"] = approximate.reshape(-1)
            table[f"transient_{name}"] = transient.reshape(-1)
            table[f"difference_{name}"] = self.difference(quantity).reshape(-1)
            table[f"relative_difference_{quantity}"] = self.relative_difference(quantity).reshape(
                -1
            )
        table["status_approx"] = self.approximate.status.reshape(-1)
        table["status_transient"] = self.transient.status.reshape(-1)
        table["models_differ"] = self.models_differ.reshape(-1)
        return {name: table[name] for name in COMPARISON_COLUMNS}

    def write_csv(self, path: Path) -> Path:
        """Write ``comparison.csv`` (SI units named in the header, NaN where not ok).

        Parameters
        ----------
        path : Path
            File to write.

        Returns
        -------
        Path
            ``path``.
        """
        write_columns(Path(path), self.columns)
        return Path(path)


def compare_models(approximate: ImpactResult, transient: ImpactResult) -> ModelComparison:
    """Set an approximate-method result beside a transient one on the same impacts.

    Parameters
    ----------
    approximate : ImpactResult
        From :func:`racketdyn.impact.predict`.
    transient : ImpactResult
        From :func:`racketdyn.impact.transient.predict_transient`, on the same points, ball
        speeds, racket speeds and supports, in the same order.

    Returns
    -------
    ModelComparison

    Raises
    ------
    InputError
        The two results are not on the same impacts, or not of the two models.
    """
    method_a = str(approximate.inputs.get("method", ""))
    method_t = str(transient.inputs.get("method", ""))
    if not method_a.startswith("approximate") or method_t != "transient":
        raise InputError(
            "compare_models: give an approximate-method result and a transient one "
            f"(got methods {method_a!r} and {method_t!r})"
        )
    same = (
        approximate.locations.shape == transient.locations.shape
        and np.array_equal(approximate.locations, transient.locations)
        and approximate.labels == transient.labels
        and np.array_equal(approximate.ball_speed, transient.ball_speed)
        and np.array_equal(approximate.racket_speed, transient.racket_speed)
        and approximate.supports == transient.supports
    )
    if not same:
        raise InputError(
            "compare_models: the two results must be on the same points, speeds and supports, "
            "in the same order"
        )
    return ModelComparison(approximate, transient)


# --- time histories -----------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class History:
    """One simulated impact with its time histories, and where it was.

    Attributes
    ----------
    point : str
        Name of the impact point.
    location : tuple of float
        (x, y), m.
    support : str
        Support condition.
    impact : TransientImpact
        The simulation (``time_s``, ``force_n``, ``ball_displacement_m``, ``deflection_m``,
        ``modal_coordinates`` …).
    """

    point: str
    location: tuple[float, float]
    support: str
    impact: TransientImpact

    @property
    def face_displacement_m(self) -> NDArray[np.float64]:
        """Displacement of the racket face at the impact point, ball − compression, m."""
        return np.asarray(self.impact.ball_displacement_m - self.impact.deflection_m)


# 10 parameters and **options: simulate_impact's, taken by name, for named points
def simulate_histories(
    racket: Racket,
    ball: Ball,
    points: Mapping[str, ArrayLike],
    ball_speed: float,
    supports: str | Sequence[str],
    racket_speed: float = 0.0,
    modal_model: ModalModel | Literal["racket"] | None = "racket",
    law: RestoringForce | None = None,
    include_string_bed: bool = False,
    string_bed: StringBed = "uniform",
    **options: Any,
) -> list[History]:
    """Simulate the impacts at named points, for their time histories.

    Parameters
    ----------
    racket, ball : Racket, Ball
        As for :func:`~racketdyn.impact.transient.simulate_impact`.
    points : mapping of str to (x, y)
        Named impact points, m.
    ball_speed : float
        Incoming ball speed, m/s.
    supports : str or sequence of str
        Support conditions, each simulated (one text of comma-separated names too).
    racket_speed : float
        Speed of the impact point towards the ball, m/s.
    modal_model : ModalModel, None or "racket"
        Flexible modes: ``"racket"`` the racket's own, None a rigid racket.
    law : RestoringForce, optional
        Compound ball+string law.
    include_string_bed : bool
        Keep string-bed modes.
    string_bed : {"uniform", "local"}
        ``local``: each point's own string-bed law (:func:`racketdyn.impact.grid.point_law`)
        instead of ``law``.
    **options
        Further keywords of :func:`simulate_impact` (``hand``, ``rtol``, ``method``).

    Returns
    -------
    list of History
        Points slowest, then supports.
    """
    check_string_bed(string_bed, law, racket)
    support_names = check_supports(supports, TRANSIENT_SUPPORTS)
    histories = []
    for name, location in points.items():
        xy = np.asarray(location, dtype=float).reshape(2)
        if string_bed == "local":
            law = point_law(racket, ball, xy)
        for support in support_names:
            impact = simulate_impact(
                racket,
                ball,
                xy,
                ball_speed,
                support,
                racket_speed,
                modal_model=modal_model,
                law=law,
                include_string_bed=include_string_bed,
                **options,
            )
            histories.append(History(name, (float(xy[0]), float(xy[1])), support, impact))
    return histories


def write_histories_csv(
    histories: Sequence[History], mode_names: Sequence[str], path: Path
) -> Path:
    """Write the time histories in long format, one row per sample (:data:`HISTORY_COLUMNS`).

    Parameters
    ----------
    histories : sequence of History
        From :func:`simulate_histories`.
    mode_names : sequence of str
        Names of the modes, in the order of ``modal_coordinates`` (one ``q_<name>_m_sqrtkg``
        column each).
    path : Path
        File to write.

    Returns
    -------
    Path
        ``path``.
    """
    fixed = [name for name in HISTORY_COLUMNS if not name.startswith("q_")]
    modes = [f"q_{slug(name)}_m_sqrtkg" for name in mode_names]
    columns: dict[str, list[NDArray[Any]]] = {name: [] for name in [*fixed, *modes]}
    for history in histories:
        impact = history.impact
        n = impact.time_s.size
        if impact.modal_coordinates.shape != (n, len(modes)):
            raise ValueError(
                f"{history.point}: {impact.modal_coordinates.shape[1]} modal coordinates for "
                f"{len(modes)} mode names"
            )
        rows: dict[str, NDArray[Any]] = {
            "point": np.full(n, history.point, dtype=object),
            "x_m": np.full(n, history.location[0]),
            "y_m": np.full(n, history.location[1]),
            "support": np.full(n, history.support, dtype=object),
            "ball_speed_mps": np.full(n, impact.ball_speed_mps),
            "racket_speed_mps": np.full(n, impact.racket_speed_mps),
            "time_s": impact.time_s,
            "force_n": impact.force_n,
            "ball_displacement_m": impact.ball_displacement_m,
            "face_displacement_m": history.face_displacement_m,
            "compression_m": impact.deflection_m,
        }
        for k, name in enumerate(modes):
            rows[name] = impact.modal_coordinates[:, k]
        for name, values in rows.items():
            columns[name].append(np.asarray(values))
    write_columns(
        Path(path),
        {name: np.concatenate(parts) if parts else np.zeros(0) for name, parts in columns.items()},
    )
    return Path(path)
