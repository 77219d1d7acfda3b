"""The result of an impact prediction over impact points × speeds × supports."""

from __future__ import annotations

import csv
import json
import logging
import re
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.__about__ import __version__
from racketdyn._display import html_table, numbers, shorten, span, words
from racketdyn.modal.model import ModalModel

if TYPE_CHECKING:
    import pandas as pd
    import xarray as xr

__all__ = [
    "CSV_COLUMNS",
    "FROM_TRANSIENT_NOTE",
    "IMPACT_LOGGERS",
    "IMPACT_QUANTITIES",
    "INVALIDATED",
    "KEY_COLUMNS",
    "OUTCOMES",
    "SHOWN_BY_DEFAULT",
    "SHOWN_SPEED_MPS",
    "STATUS_BEYOND_LAW",
    "STATUS_DTYPE",
    "STATUS_FRAME_CONTACT",
    "STATUS_FROM_TRANSIENT",
    "STATUS_MEANING",
    "STATUS_NO_SEPARATION",
    "STATUS_OK",
    "STATUS_SECOND_CONTACT",
    "STATUS_VIBRATION_LOSS",
    "STATUS_VIBRATION_SHARE",
    "VALID_STATUSES",
    "ImpactResult",
    "Quantity",
    "extreme_row",
    "impact_columns",
    "impact_warnings_quiet",
    "invalidate_table",
    "invalidated_columns",
    "is_valid",
    "model_note",
    "shown_case_index",
    "shown_speed_index",
    "slug",
    "status_text",
    "summary_rows",
    "write_columns",
]

STATUS_OK = "ok"
STATUS_VIBRATION_LOSS = "vibration loss exceeds e_BG"
STATUS_BEYOND_LAW = "deflection beyond the restoring-force law"
STATUS_NO_SEPARATION = "ball did not leave the strings within the time allowed"
STATUS_SECOND_CONTACT = "second contact: the vibrating frame caught the ball again"
STATUS_FROM_TRANSIENT = "from the transient model: beyond the approximate method"
STATUS_VIBRATION_SHARE = (
    "frame vibration takes over 30 % of the approach energy: beyond the approximate method"
)
STATUS_FRAME_CONTACT = "the ball reaches the frame: a frame shot, not a string impact"


@dataclass(frozen=True)
class Quantity:
    """One impact quantity: its Python attribute and its name in files, datasets and tables.

    Attributes
    ----------
    attribute : str
        Attribute of :class:`ImpactResult`: the glossary's bare name, in SI units.
    name : str
        Column of ``impact.csv``, variable of :meth:`ImpactResult.to_xarray` and column of
        :meth:`ImpactResult.to_dataframe`: the attribute with its unit as a suffix.
    units : str
        Unit in UDUNITS spelling (the ``units`` attribute of the dataset's variable).
    long_name : str
        What it is, with the paper's equation (the ``long_name`` attribute).
    """

    attribute: str
    name: str
    units: str
    long_name: str


IMPACT_QUANTITIES: tuple[Quantity, ...] = (
    Quantity(
        "racket_speed",
        "racket_speed_mps",
        "m s-1",
        "racket speed at the impact point (towards ball)",
    ),
    Quantity(
        "reduced_mass",
        "reduced_mass_kg",
        "kg",
        "reduced mass of the racket at the impact point (eq 4)",
    ),
    Quantity(
        "stiffness", "stiffness_n_per_m", "N m-1", "compound ball+string stiffness K_GB (eqs 9-10)"
    ),
    Quantity("contact_time", "contact_time_s", "s", "contact time T_c (eq 7)"),
    Quantity("mean_force", "mean_force_n", "N", "equivalent force F_MEAN (eqs 8-10)"),
    Quantity("peak_force", "peak_force_n", "N", "peak force F_MAX (the spring's at the turn)"),
    Quantity(
        "vibration_energy", "vibration_energy_j", "J", "frame vibration energy after impact (eq 12)"
    ),
    Quantity("cor", "cor", "1", "ball-racket coefficient of restitution e_r"),
    Quantity("rebound_ratio", "rebound_ratio", "1", "rebound ratio e"),
    Quantity("rebound_speed", "rebound_speed_mps", "m s-1", "outgoing ball speed"),
    Quantity("peak_deflection", "peak_deflection_m", "m", "peak compound deflection X_p"),
)
"""The impact quantities in ``impact.csv``'s order: the one table that names them in files,
datasets and data frames (attribute ``contact_time`` ↔ column ``contact_time_s``)."""

KEY_COLUMNS = ("point", "x_m", "y_m", "support", "ball_speed_mps")
"""The columns that say which impact a row of ``impact.csv`` is."""

CSV_COLUMNS = (*KEY_COLUMNS, *(q.name for q in IMPACT_QUANTITIES), "status")
"""Columns of ``impact.csv`` (the first fifteen in the order the foundation issue fixes); one
``energy_<mode name>_j`` column per mode follows."""

OUTCOMES: tuple[str, ...] = (
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
    "energy_terms",
)
"""What an impact method computes (attributes of :class:`ImpactResult`); the rest of a row —
point, x, y, support, ball and racket speeds, reduced mass — is its input."""

INVALIDATED: dict[str, tuple[tuple[str, ...], str]] = {
    STATUS_VIBRATION_LOSS: (
        OUTCOMES,
        "the approximate method's half-sine pulse (eqs 7-11) assumes a racket that is rigid "
        "but for a small vibration loss; a loss larger than e_BG allows means the frame's "
        "flexibility shapes the contact, so its time, forces, deflection and stiffness are not "
        "the racket's either, and the vibration energy (eq 12) exceeds what the ball brings",
    ),
    STATUS_FROM_TRANSIENT: (
        (),
        "when both models run, a row the approximate method cannot give carries the transient "
        "model's numbers (valid, not the approximate method's): nothing is NaN",
    ),
    STATUS_VIBRATION_SHARE: (
        OUTCOMES,
        "the approximate method forces the frame with the pulse of a rigid racket; where the "
        "frame takes more than 30 % of the approach energy its motion changes the pulse and the "
        "method is no longer within 0.015 of the coupled (transient) solution (docs/"
        "validation.md): its numbers are not given; the transient model's are",
    ),
    STATUS_FRAME_CONTACT: (
        OUTCOMES,
        "both models let the ball touch the strings only; at its peak deflection X_p the ball's "
        "section in the plane of the strings, of radius sqrt(2 R X_p - X_p^2) for a ball of "
        "radius R, reaches the hoop, so part of the impulse goes straight into the frame, which "
        "neither model simulates (a lower bound: a real frame stands about 10 mm above the "
        "strings and is met sooner; docs/validation.md)",
    ),
    STATUS_BEYOND_LAW: (
        OUTCOMES,
        "the compression leaves the range where the ball+string law F_GB is known: nothing "
        "after that point (peak, time, forces, rebound, energies) is computed from a law",
    ),
    STATUS_NO_SEPARATION: (
        OUTCOMES,
        "the simulation stopped with the ball still on the strings: no end state",
    ),
    STATUS_SECOND_CONTACT: (
        OUTCOMES,
        "after the ball left, the vibrating frame caught it up again; that second contact is "
        "not simulated, so the end state (rebound, COR, energies) is not the impact's, the "
        "contact time and mean force miss the second pulse, and its peak is not known to be "
        "below the first",
    ),
}
"""Which results each failure status makes NaN, and why: ``status → (attributes, reason)``,
the one table every result applies (:class:`ImpactResult` on construction, the report on
reading ``impact.csv``).  A status not listed here other than ``ok`` invalidates
:data:`OUTCOMES` too."""

STATUS_MEANING = (
    "'ok', or why the impact's results are NaN: "
    + "; ".join(f"'{status}'" for status in INVALIDATED)
    + " (each makes every computed quantity NaN; inputs such as x, y, speeds and reduced mass "
    "stay)"
)
"""What the ``status`` column and variable hold."""


VALID_STATUSES: tuple[str, ...] = (STATUS_OK, STATUS_FROM_TRANSIENT)
"""Statuses of rows whose numbers are results: the method's own (``ok``) and, with both
models, the transient model's in a row the approximate method cannot give (valid, marked
so)."""

FROM_TRANSIENT_NOTE = "(transient model)"
"""What a number taken from a row filled from the transient model says after it."""

STATUS_DTYPE = np.dtype(f"<U{max(len(status) for status in (STATUS_OK, *INVALIDATED))}")
"""Text as wide as the longest status an impact model gives (85 characters)."""


def status_text(status: ArrayLike) -> NDArray[np.str_]:
    """Statuses as text at least :data:`STATUS_DTYPE` wide, so that a copy keeps any status
    written into it: numpy's text arrays are as wide as their longest element, and an
    all-``ok`` result's two-character copy cut "from the transient model: …" to "fr" without
    a word (the row, filled with valid numbers, then turned NaN)."""
    text = np.asarray(status, dtype=str)
    return text if text.itemsize >= STATUS_DTYPE.itemsize else text.astype(STATUS_DTYPE)


def is_valid(status: ArrayLike) -> NDArray[np.bool_]:
    """Which rows hold results (:data:`VALID_STATUSES`), element-wise.

    Parameters
    ----------
    status : array_like of str
        Rows' statuses.
    """
    return np.isin(np.asarray(status, dtype=str), VALID_STATUSES)


def model_note(status: str) -> str:
    """`` (transient model)`` for a number of a row filled from the transient model, else
    empty: the words after every number a headline or table picks from such a row."""
    return f" {FROM_TRANSIENT_NOTE}" if str(status) == STATUS_FROM_TRANSIENT else ""


def extreme_row(
    values: ArrayLike,
    status: ArrayLike,
    rows: ArrayLike | None = None,
    *,
    smallest: bool = False,
) -> int | None:
    """The row of the largest (or smallest) value among the valid rows: the one rule for
    every "highest", "best", "largest", "quietest" and sweet-spot number a headline, table or
    console gives (new-user trial, ninth session: rows filled from the transient model were
    passed over, and a lower number called the face's highest).

    Parameters
    ----------
    values, status : array_like
        One number and one status per row (flat, or the same shape: flattened alike).
    rows : array_like of int, optional
        The flat indices to choose among; by default all.
    smallest : bool
        The smallest value instead of the largest.

    Returns
    -------
    int or None
        The flat index of the row (the first of equal values), None when no row of ``rows``
        is valid (:data:`VALID_STATUSES`) with a finite value.
    """
    value = np.asarray(values, dtype=float).reshape(-1)
    among = np.arange(value.size) if rows is None else np.asarray(rows, dtype=np.intp)
    state = np.asarray(status, dtype=str).reshape(-1)[among]
    usable = among[is_valid(state) & np.isfinite(value[among])]
    if not usable.size:
        return None
    pick = np.argmin if smallest else np.argmax
    return int(usable[int(pick(value[usable]))])


def invalidated_columns(status: str) -> tuple[str, ...]:
    """The :class:`ImpactResult` attributes a row with this ``status`` holds as NaN.

    Parameters
    ----------
    status : str
        A row's status.

    Returns
    -------
    tuple of str
        Empty for ``ok``; :data:`INVALIDATED`'s entry, or :data:`OUTCOMES` for any other status.
    """
    if status == STATUS_OK:
        return ()
    return INVALIDATED.get(status, (OUTCOMES, ""))[0]


def invalidate_table(
    columns: dict[str, NDArray[np.float64]], status: NDArray[np.str_]
) -> dict[str, NDArray[np.float64]]:
    """``impact.csv``'s numeric columns with NaN wherever a row's status invalidates them.

    For a table read from a file (one written before this rule, or by hand): the same
    :data:`INVALIDATED` table as :class:`ImpactResult` applies on construction.

    Parameters
    ----------
    columns : dict of str to ndarray
        Numeric columns by ``impact.csv`` name (``contact_time_s``, ``energy_<mode>_j`` …).
    status : ndarray of str
        Each row's status.

    Returns
    -------
    dict of str to ndarray
        New arrays; columns no status touches are the ones given.
    """
    names = {q.attribute: q.name for q in IMPACT_QUANTITIES}
    status = np.asarray(status, dtype=str)
    out = dict(columns)
    for text in np.unique(status[status != STATUS_OK]):
        rows = status == text
        dead = invalidated_columns(str(text))
        for name in list(out):
            mode_column = name.startswith("energy_") and name.endswith("_j")
            if (mode_column and "mode_energy" in dead) or any(names.get(a) == name for a in dead):
                out[name] = np.where(rows, np.nan, np.asarray(out[name], dtype=float))
    return out


def _invalidate(result: Any) -> dict[str, Any]:
    """NaN in every array a row's status invalidates (:data:`INVALIDATED`): the new arrays."""
    status = np.asarray(result.status)
    changed: dict[str, Any] = {}
    if status.size == 0 or np.all(status == STATUS_OK):
        return changed
    for attribute in OUTCOMES:
        mask = np.zeros(status.shape, dtype=bool)
        for text in np.unique(status[status != STATUS_OK]):
            if attribute in invalidated_columns(str(text)):
                mask |= status == text
        if not mask.any():
            continue
        value = getattr(result, attribute, None)
        if value is None:
            continue
        if attribute == "energy_terms":
            changed[attribute] = {
                name: np.where(mask, np.nan, np.asarray(term, dtype=float))
                for name, term in value.items()
            }
            continue
        array = np.asarray(value, dtype=float)
        extra = (None,) * (array.ndim - mask.ndim)
        changed[attribute] = np.where(mask[(..., *extra)], np.nan, array)
    return changed


@dataclass(frozen=True, eq=False)
class ImpactResult:
    """Predicted impact quantities, arrays shaped ``(n_points, n_speeds, n_supports)``.

    Attributes carry the glossary's bare names in SI units (``contact_time``, s); the same
    quantities in ``impact.csv``, :meth:`to_xarray` and :meth:`to_dataframe` carry their unit
    as a suffix (``contact_time_s``), see :data:`IMPACT_QUANTITIES`.

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
        F_MEAN = impulse / T_c (eqs 8–10) and F_MAX, N: eq 11's π F_MEAN / 2 under the
        paper's charge; under the coupled charge (the approximate method's default) the
        spring's force at the turn, as the transient model's.
    mode_energy : ndarray (…, n_modes)
        Vibration energy per mode after the impact, J.
    vibration_energy : ndarray
        Sum over modes, J.
    cor : ndarray
        Ball–racket coefficient of restitution after the vibration loss, e_r (NaN where the
        status is not ``ok``).
    rebound_ratio : ndarray
        Rebound ratio e = (e_r − m_B/M_r)/(1 + m_B/M_r): the ratio of rebound to incident ball
        speed on a racket at rest (Kawazoe's "rebound capability", Fig. 15).
    rebound_speed : ndarray
        Outgoing ball speed e·v_ball + (1 + e)·v_racket, m/s.
    status : ndarray of str
        ``ok`` or why the numbers are missing: a row whose status is not ``ok`` holds NaN in
        every attribute :data:`INVALIDATED` lists for it (applied on construction).
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

    def __post_init__(self) -> None:
        # the one place a flagged row's results become NaN (issue 13): every producer and
        # every copy (concatenate, replace, swing) goes through here
        object.__setattr__(self, "status", status_text(self.status))
        for attribute, value in _invalidate(self).items():
            object.__setattr__(self, attribute, value)

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(n_points, n_speeds, n_supports)``."""
        return (self.locations.shape[0], self.ball_speed.size, len(self.supports))

    @property
    def impulse(self) -> NDArray[np.float64]:
        """Impulse F_MEAN · T_c, N·s: the ball's change of momentum — (1 + e_r) μ V with the
        coupled charge (eq 8 with the rebound's COR), (1 + e_BG) μ V with the paper's (eqs 6
        and 8)."""
        return np.asarray(self.mean_force * self.contact_time)

    def filled_from(self, transient: ImpactResult) -> ImpactResult:
        """This (approximate) result with the rows it cannot give taken from ``transient``.

        A row whose status is not ``ok`` here and ``ok`` in ``transient`` (same points, speeds
        and supports) takes every computed quantity from ``transient`` and the status
        :data:`STATUS_FROM_TRANSIENT`, so it is marked wherever it is shown.
        """
        if self.shape != transient.shape or self.supports != transient.supports:
            raise ValueError("results differ in points, speeds or supports")
        take = (self.status != STATUS_OK) & (transient.status == STATUS_OK)
        if not np.any(take):
            return self
        merged: dict[str, Any] = {}
        for name in (a for a in OUTCOMES if a != "energy_terms"):
            mine, theirs = getattr(self, name), getattr(transient, name)
            if mine.shape != theirs.shape:  # mode energies of a different modal model
                theirs = np.full(mine.shape, np.nan)
            mask = take.reshape(take.shape + (1,) * (mine.ndim - take.ndim))
            merged[name] = np.where(mask, theirs, mine)
        status = np.where(take, STATUS_FROM_TRANSIENT, self.status)
        return replace(self, status=status, **merged)

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
                *(a for a in OUTCOMES if a != "energy_terms"),
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
        mode k left by the pulse at impact point j, seen at response point i.  Taken from the
        energy the mode holds, ``E_jk = ½ φ_jk² |S_j(ω_k)|²``, as ``|φ_ik| sqrt(2 E_jk) / ω_k``:
        eq 12's half sine under the paper's charge, the contact's own pulse under the coupled
        one (:func:`racketdyn.impact.approximate.vibration_cor_squared`).

        Returns an array shaped ``(n_response, n_points, n_speeds, n_supports, n_modes)``.
        """
        if self.modal_model is None:
            raise ValueError("a rigid racket (no modal model) does not vibrate")
        model = self.modal_model
        shapes = np.abs(model.mode_shapes_at(response))
        velocity = np.sqrt(2.0 * self.mode_energy)  # |φ_jk S_j(ω_k)|, (n, s, p, m)
        return np.asarray(shapes[:, None, None, None, :] * velocity[None] / model.omega)

    @property
    def columns(self) -> dict[str, NDArray[Any]]:
        """The ``impact.csv`` table: column name → 1-D array, one row per point × speed ×
        support (``pandas.DataFrame(result.columns)`` is :meth:`to_dataframe`).

        Names carry their unit (``contact_time_s``, see :data:`IMPACT_QUANTITIES`); one
        ``energy_<mode name>_j`` column per mode follows the :data:`CSV_COLUMNS`.  Built anew
        at each access.
        """
        return impact_columns(self, self.racket_speed[None, :, None])

    def write_csv(self, path: Path) -> None:
        """Write ``impact.csv``: :attr:`columns`, SI units named in the header, NaN as ``nan``.

        Parameters
        ----------
        path : Path
            File to write.
        """
        write_columns(path, self.columns)

    def to_dataframe(self) -> pd.DataFrame:
        """The ``impact.csv`` table as a long :class:`pandas.DataFrame`.

        Same columns, order and values as the file :meth:`write_csv` writes (one row per
        point × speed × support, points slowest): ``pandas.read_csv("impact.csv")`` equals it
        to the file's nine significant digits.

        Returns
        -------
        pandas.DataFrame
            Columns named with their unit (``contact_time_s`` …), see :data:`IMPACT_QUANTITIES`.
        """
        import pandas as pd

        return pd.DataFrame(self.columns)

    def to_xarray(self) -> xr.Dataset:
        """The result as an :class:`xarray.Dataset`, with units and names for every variable.

        Dimensions ``point``, ``ball_speed``, ``support`` (and ``mode`` for the modal
        energies).  Coordinates: ``x_m``, ``y_m``, ``label`` on ``point`` (``label`` indexed:
        ``ds.sel(label="centre")``); ``ball_speed_mps`` (indexed) and ``racket_speed_mps`` on
        ``ball_speed``; ``support``; on ``mode``, the mode names with ``mode_frequency_hz``,
        ``mode_damping_ratio`` and ``mode_kind``.  Variables are named as ``impact.csv``'s
        columns (:data:`IMPACT_QUANTITIES`: ``contact_time_s`` holds :attr:`contact_time`) with
        ``units`` (UDUNITS) and ``long_name`` attributes, plus ``mode_energy_j`` (point,
        ball_speed, support, mode), ``status`` (its meaning in ``description``) and, for the
        transient model, ``energy_balance_j`` over an ``energy_term`` dimension.  Values are
        the result's arrays as they are: NaN where the status says the numbers are missing.
        Dataset attributes: ``method``, ``racket_speed_mps``, ``modal_model`` (its source),
        ``racketdyn_version`` and ``inputs`` (JSON of :attr:`inputs`).

        Returns
        -------
        xarray.Dataset
            Writable as netCDF (``ds.to_netcdf("impact.nc")``).
        """
        import xarray as xr

        cell = ("point", "ball_speed", "support")
        data: dict[str, Any] = {}
        # dims in the order (point, ball_speed, support): reduced mass, on (point, support),
        # after the impact quantities; the racket speed is a coordinate on ball_speed
        variables = [q for q in IMPACT_QUANTITIES if q.attribute != "racket_speed"]
        for quantity in sorted(variables, key=lambda q: q.attribute == "reduced_mass"):
            dims = ("point", "support") if quantity.attribute == "reduced_mass" else cell
            attrs = {"units": quantity.units, "long_name": quantity.long_name}
            data[quantity.name] = (dims, np.asarray(getattr(self, quantity.attribute)), attrs)
        coords: dict[str, Any] = {
            "x_m": ("point", self.locations[:, 0], {"units": "m", "long_name": _LONG_NAMES["x_m"]}),
            "y_m": ("point", self.locations[:, 1], {"units": "m", "long_name": _LONG_NAMES["y_m"]}),
            "label": ("point", list(self.labels), {"long_name": "point label"}),
            "ball_speed_mps": (
                "ball_speed",
                self.ball_speed,
                {"units": "m s-1", "long_name": _LONG_NAMES["ball_speed_mps"]},
            ),
            "racket_speed_mps": (
                "ball_speed",
                self.racket_speed,
                {"units": "m s-1", "long_name": _LONG_NAMES["racket_speed_mps"]},
            ),
            "support": ("support", list(self.supports), {"long_name": "support condition"}),
        }
        model = self.modal_model
        if model is not None:
            data["mode_energy_j"] = (
                (*cell, "mode"),
                self.mode_energy,
                {"units": "J", "long_name": "vibration energy per mode after impact (eq 12)"},
            )
            coords["mode"] = ("mode", list(model.names), {"long_name": "mode name"})
            coords["mode_frequency_hz"] = (
                "mode",
                model.frequency,
                {"units": "Hz", "long_name": "natural frequency"},
            )
            coords["mode_damping_ratio"] = (
                "mode",
                model.damping_ratio,
                {"units": "1", "long_name": "damping ratio"},
            )
            coords["mode_kind"] = ("mode", list(model.kinds), {"long_name": "mode kind"})
        if self.energy_terms is not None:
            terms = list(self.energy_terms)
            data["energy_balance_j"] = (
                (*cell, "energy_term"),
                np.stack([self.energy_terms[t] for t in terms], axis=-1),
                {"units": "J", "long_name": "where the ball's energy went (transient model)"},
            )
            coords["energy_term"] = ("energy_term", terms)
        data["status"] = (
            cell,
            np.asarray(self.status, dtype=str),
            {"long_name": "impact status", "description": STATUS_MEANING},
        )
        info: dict[str, Any] = {
            "title": "racketdyn impact prediction",
            "method": str(self.inputs.get("method", "")),
            "racket_speed_mps": np.asarray(self.racket_speed, dtype=float),
            "modal_model": "none (rigid racket)" if model is None else model.source,
            "racketdyn_version": str(self.inputs.get("racketdyn_version", __version__)),
            "inputs": json.dumps(self.inputs, default=str),
        }
        dataset = xr.Dataset(data, coords=coords, attrs=info)
        return dataset.set_xindex("label").set_xindex("ball_speed_mps")

    def __repr__(self) -> str:
        n, s, p = self.shape
        return (
            f"<ImpactResult {n} points × {s} ball speeds × {p} supports: "
            + "; ".join(f"{key} {value}" for key, value in summary_rows(self)[1:])
            + ">"
        )

    def _repr_html_(self) -> str:
        return html_table("ImpactResult", summary_rows(self))


def summary_rows(result: Any) -> list[tuple[str, str]]:
    """(what, value) lines that sum up a result with :class:`ImpactResult`'s arrays: the short
    ``repr`` and the notebook table.

    Parameters
    ----------
    result : ImpactResult or alike
        Has ``shape``, ``labels``, ``ball_speed``, ``racket_speed``, ``supports``,
        ``status``, ``rebound_ratio``, ``modal_model`` and ``inputs``.
    """
    n, s, p = result.shape
    flagged = int(np.count_nonzero(~is_valid(result.status)))
    filled = int(np.count_nonzero(result.status == STATUS_FROM_TRANSIENT))
    model = result.modal_model
    rows = [
        ("shape", f"{n} points × {s} ball speeds × {p} supports"),
        ("points", words(result.labels)),
        ("ball speed", f"{numbers(result.ball_speed)} m/s"),
        ("racket speed", f"{span(result.racket_speed)} m/s"),
        ("supports", words(result.supports)),
        ("method", shorten(str(result.inputs.get("method", "?")))),
        ("modes", "none (rigid)" if model is None else f"{model.frequency.size}"),
        ("rebound ratio", span(result.rebound_ratio[is_valid(result.status)])),
        ("flagged", f"{flagged} of {result.status.size} without numbers"),
    ]
    if filled:
        rows.insert(-1, ("from the transient model", f"{filled} of {result.status.size}"))
    return rows


_LONG_NAMES = {
    "x_m": "x along the long axis from the butt",
    "y_m": "y across the long axis (0 on it)",
    "ball_speed_mps": "incoming ball speed towards the strings",
    "racket_speed_mps": next(
        q.long_name for q in IMPACT_QUANTITIES if q.attribute == "racket_speed"
    ),
}


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
    shape = (n, s, p)
    table: dict[str, NDArray[Any]] = {
        "point": np.asarray(result.labels, dtype=object)[:, None, None],
        "x_m": result.locations[:, 0, None, None],
        "y_m": result.locations[:, 1, None, None],
        "support": np.asarray(result.supports, dtype=object),
        "ball_speed_mps": result.ball_speed[None, :, None],
    }
    for quantity in IMPACT_QUANTITIES:
        value = getattr(result, quantity.attribute)
        if quantity.attribute == "racket_speed":
            value = racket_speed
        elif quantity.attribute == "reduced_mass":
            value = value[:, None, :]
        table[quantity.name] = value
    table["status"] = result.status
    flat = {name: np.broadcast_to(table[name], shape).reshape(-1) for name in CSV_COLUMNS}
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


SHOWN_BY_DEFAULT = "default: 20 m/s if run, else the middle ball speed"
"""How run.json's ``shown_case`` says the case was chosen without ``show``."""


def shown_case_index(
    speeds: ArrayLike, racket_speeds: ArrayLike, show: float | Sequence[float] | None = None
) -> int:
    """Index of the case (ball speed and its racket speed) single-case summaries show.

    Parameters
    ----------
    speeds : array_like
        The run's ball speeds, m/s.
    racket_speeds : array_like
        Its racket speeds, m/s: one, or one per ball speed.
    show : float or sequence of float, optional
        ``ball speed``, ``(ball speed,)`` or ``(ball speed, racket speed)``, m/s, one of the
        run's cases; by default :func:`shown_speed_index`'s rule.

    Raises
    ------
    InputError
        ``show`` is not one of the run's cases (the cases named), or not one or two numbers.
    """
    from racketdyn._display import case_words
    from racketdyn.errors import InputError, require_numbers

    ball = np.asarray(speeds, dtype=float).reshape(-1)
    racket = np.broadcast_to(np.asarray(racket_speeds, dtype=float).reshape(-1), ball.shape)
    if show is None:
        return shown_speed_index(ball)
    wanted = require_numbers("`show`", show, "m/s")  # 20.0, (20.0,) or the command line's "20,5"
    if len(wanted) not in (1, 2):
        raise InputError(
            "`show` takes a ball speed and, optionally, its racket speed (m/s); got "
            + ", ".join(f"{v:g}" for v in wanted)
        )
    hit = np.isclose(ball, wanted[0], rtol=0.0, atol=1e-9)
    if len(wanted) == 2:
        hit &= np.isclose(racket, wanted[1], rtol=0.0, atol=1e-9)
    found = np.flatnonzero(hit)
    if found.size == 1:
        return int(found[0])
    cases = ", ".join(
        case_words(v, r).replace(", racket", " with racket")
        for v, r in zip(ball, racket, strict=True)
    )
    said = ", ".join(f"{v:g}" for v in wanted)
    why = (
        "not a case of the run"
        if not found.size
        else "two cases have that ball speed: add its racket speed"
    )
    raise InputError(f"`show` {said} m/s: {why} ({cases})")


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


IMPACT_LOGGERS = tuple(
    f"racketdyn.impact.{name}"
    for name in ("approximate", "grid", "swing", "transient", "uncertainty")
)
"""The impact models' loggers: each call warns of its impacts without numbers, by status."""


@contextmanager
def impact_warnings_quiet() -> Iterator[None]:
    """The impact models' warnings off for a while (errors pass).

    For impacts that are not the caller's own table: a sweep's designs (the sweep counts them
    from their status codes and warns once, and worker processes have no console) and a
    figure's curves (the figure marks its own; the console counts the run's impacts: the
    new-user trial of 2026-11-27 saw "76 of 276 impacts …" beside a run of 138).
    """

    def below_error(record: logging.LogRecord) -> bool:
        return record.levelno >= logging.ERROR

    loggers = [logging.getLogger(name) for name in IMPACT_LOGGERS]
    for logger in loggers:
        logger.addFilter(below_error)
    try:
        yield
    finally:
        for logger in loggers:
            logger.removeFilter(below_error)
