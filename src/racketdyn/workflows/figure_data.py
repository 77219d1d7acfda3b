"""What the steps' figures draw, computed with the run's own inputs (issue 23).

A figure only draws: every number it shows is computed here, by the step's workflow, with the
run's racket, ball, modes and impact options, into a frozen result object that converts to
xarray (:meth:`to_xarray`) and back (:meth:`from_xarray`).  The step writes them together to
``figures.nc`` in its run folder (:data:`FIGURES_FILE`, netCDF 3 through xarray's scipy engine,
SI units in the variable names and ``units`` attributes), so each figure can be redrawn from
the folder alone (:func:`read_figure_data`).

============================  ==================================================================
object                        figures
============================  ==================================================================
:class:`PaperFigures`         predict: the paper's Figs 11–12 (:class:`ImpactCurves` against
                              speed), 13 (:class:`PulseSpectra`), 14 (:class:`FrameVibration`),
                              15 (rebound along the axis) and the face maps
:class:`TransientCurves`      predict ``--model both``: both models against speed
:class:`ComparisonMap`        predict ``--model both``: approximate − transient over the face
:class:`TransientHistories`   predict ``--model transient|both``: the simulated time histories
:class:`SwingAxisCurves`      swing: outgoing speed along the axis for a few swings
:class:`IdentifiedRebound`    compare: Fig. 15 with the identified free and hand-held modes
``shape_figures``             identify, compare: Figs 4–6 and the AutoMAC
                              (:mod:`racketdyn.workflows.shape_figures`)
============================  ==================================================================

Each figure's variables are a group of ``figures.nc``, their names prefixed with the figure's
key and ``__`` (netCDF 3 has no groups): ``fig11_12__mean_force_n``.  Every other step's
figures read objects it computed, stored in its ``figures.nc`` as they are
(:func:`defer_figure_data`, :func:`racketdyn.workflows._figure_io.store`: the FRFs of Figs 2–3
and the fits of :mod:`racketdyn.workflows.frf_figures`, compound's ``CompoundFigures``, the
swing map's impacts, twist's and oblique's curves, validate's rows, the ball's bounces);
:func:`read_step_data` reads every one back, so each figure redraws from its folder alone.
"""

from __future__ import annotations

import functools
import sys
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, ParamSpec, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import Ball
from racketdyn.errors import InputError
from racketdyn.impact import half_sine_force, half_sine_spectrum, predict
from racketdyn.impact.result import (
    IMPACT_QUANTITIES,
    SHOWN_SPEED_MPS,
    STATUS_OK,
    ImpactResult,
    impact_warnings_quiet,
)
from racketdyn.impact.swing import ImpactModel, Swing, SwingResult, axis_swings, predict_swing
from racketdyn.impact.system import Engine
from racketdyn.modal.model import ModalModel, kind_from_name
from racketdyn.racket import HeadEllipse, Racket, landmark_points
from racketdyn.racket_modal.shapes import axis_nodes
from racketdyn.workflows._figure_io import _array, _has, _join, _part, _strings, store, stored
from racketdyn.workflows.run import StepResult, defer_file

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes

    from racketdyn.impact.comparison import History, ModelComparison

# the transient model (with numba, ≈ 0.2 s) is imported where its curves are computed: a run
# of the approximate method alone never needs it

__all__ = [
    "APPROXIMATE_ONLY",
    "AXIS_POINTS",
    "CURVE_SPEEDS_MPS",
    "FIGURES_FILE",
    "FRAME_POINTS",
    "IDENTIFIED_CASES",
    "PULSE_FREQUENCY_HZ",
    "PULSE_SPEEDS_MPS",
    "PULSE_TIME_S",
    "SWING_AXIS_POINTS",
    "TRANSIENT_CURVE_SPEEDS_MPS",
    "VIBRATION_SPEEDS_MPS",
    "AxisBand",
    "ComparisonMap",
    "FigureData",
    "FrameVibration",
    "IdentifiedRebound",
    "ImpactCurves",
    "PaperFigures",
    "PulseSpectra",
    "SwingAxisCurves",
    "TransientCurves",
    "TransientHistories",
    "axis_points",
    "defer_figure_data",
    "describe_options",
    "identified_rebound",
    "joined_figure_data",
    "paper_figures",
    "racket_speed_at",
    "read_figure_data",
    "read_step_data",
    "swing_axis_curves",
    "transient_curves",
    "write_figure_data",
]

FIGURES_FILE = "figures.nc"
BAND_WIDTH = "rebound_ratio_band_width"
"""The face maps' variable of the band's width (``predict --uncertainty``)."""
"""The file of a run folder holding what its figures draw."""
CURVE_SPEEDS_MPS = np.linspace(5.0, 50.0, 46)
"""Ball speeds of Figs 11–12 (stretched to the run's fastest, the run's speeds added), m/s."""
VIBRATION_SPEEDS_MPS = (10.0, 20.0, 30.0)
"""Ball speeds of Fig. 14 when the run gives none, m/s."""
PULSE_SPEEDS_MPS = (10.0, 20.0, 30.0, 40.0)
"""Ball speeds of Fig. 13 when the run gives none, m/s."""
PULSE_TIME_S = np.linspace(-0.5e-3, 7e-3, 751)
"""Times of Fig. 13's pulses, s from first contact."""
PULSE_FREQUENCY_HZ = np.linspace(0.0, 1500.0, 1501)
"""Frequencies of Fig. 13's spectra, Hz."""
FRAME_POINTS = 121
"""Points along the frame (butt to tip) of Fig. 14."""
AXIS_POINTS = 31
"""Impact points along the long axis of Fig. 15 (5 % of the half-length in from the frame)."""
TRANSIENT_CURVE_SPEEDS_MPS = np.linspace(5.0, 40.0, 15)
"""Ball speeds of the approximate-against-transient curves (15 speeds: 3 points × 15 × 2
supports ≈ 0.7 s with the scipy reference path of the transient model)."""
SWING_AXIS_POINTS = 41
"""Points along the long axis of the along-axis swing figure (inset half a step from the frame,
as :func:`racketdyn.impact.swing.sweet_spots` samples it)."""

APPROXIMATE_ONLY = ("stiffness_reading", "vibration_charge")
"""Keywords of :func:`racketdyn.impact.predict` the transient model does not take: the run's
options less these go to :func:`~racketdyn.impact.transient.predict_transient`."""
_CURVE_QUANTITIES = ("contact_time", "mean_force", "rebound_ratio", "rebound_speed")
_FACE_QUANTITIES = ("contact_time", "rebound_ratio", "vibration_energy")
_QUANTITY = {q.attribute: q for q in IMPACT_QUANTITIES}
_EMPTY = np.zeros((0, 0, 0))
_HEAD = ("centre_x_m", "half_length_m", "half_width_m", "centre_y_m")


# --- impacts on the points and speeds of a figure ---------------------------------------------
@dataclass(frozen=True)
class ImpactCurves:
    """Impact quantities on a figure's own points × speeds × supports (a slice of an
    :class:`~racketdyn.impact.result.ImpactResult` holding what curves and maps draw).

    Attributes carry the :class:`ImpactResult` names in SI units; a quantity the figure does not
    draw is an empty array.  Rows whose ``status`` is not ``ok`` hold NaN, as in the result.

    Attributes
    ----------
    locations : ndarray (n_points, 2)
        Impact points (x, y), m.
    labels : tuple of str
        Point labels.
    ball_speed, racket_speed : ndarray (n_speeds,)
        Incoming ball speed and racket speed, m/s.
    supports : tuple of str
        Supports.
    status : ndarray of str (n_points, n_speeds, n_supports)
        ``ok`` or why the numbers are missing.
    contact_time : ndarray
        T_c, s.
    mean_force : ndarray
        F_MEAN, N.
    rebound_ratio : ndarray
        Rebound ratio e, dimensionless.
    rebound_speed : ndarray
        Outgoing ball speed, m/s.
    vibration_energy : ndarray
        Frame vibration energy after the impact, J.
    rebound_ratio_band_width : ndarray
        With an uncertainty: the width of the rebound ratio's 90 % band (p95 − p05), NaN where
        the band is not given.
    """

    locations: NDArray[np.float64]
    labels: tuple[str, ...]
    ball_speed: NDArray[np.float64]
    racket_speed: NDArray[np.float64]
    supports: tuple[str, ...]
    status: NDArray[np.str_]
    contact_time: NDArray[np.float64] = field(default_factory=lambda: _EMPTY)
    mean_force: NDArray[np.float64] = field(default_factory=lambda: _EMPTY)
    rebound_ratio: NDArray[np.float64] = field(default_factory=lambda: _EMPTY)
    rebound_speed: NDArray[np.float64] = field(default_factory=lambda: _EMPTY)
    vibration_energy: NDArray[np.float64] = field(default_factory=lambda: _EMPTY)
    rebound_ratio_band_width: NDArray[np.float64] = field(default_factory=lambda: _EMPTY)

    @classmethod
    def of(
        cls,
        result: ImpactResult | SwingResult,
        quantities: Sequence[str] = _CURVE_QUANTITIES,
        speeds: Sequence[int] | None = None,
    ) -> ImpactCurves:
        """The quantities a figure draws, taken from an impact result.

        Parameters
        ----------
        result : ImpactResult or SwingResult
            The impacts.
        quantities : sequence of str
            Attributes to keep (the others empty).
        speeds : sequence of int, optional
            Indices of the ball speeds to keep (default all).
        """
        s = list(range(result.ball_speed.size)) if speeds is None else list(speeds)
        return cls(
            locations=_array(result.locations),
            labels=tuple(result.labels),
            ball_speed=_array(result.ball_speed)[s],
            racket_speed=_array(result.racket_speed)[s],
            supports=tuple(result.supports),
            status=np.asarray(result.status, dtype=str)[:, s, :],
            **{q: _array(getattr(result, q))[:, s, :] for q in quantities},
        )

    @classmethod
    def concatenate(cls, parts: Sequence[ImpactCurves]) -> ImpactCurves:
        """Curves of the same points and supports one after the other along the speed axis
        (Figs 11–12: one run of speeds per racket speed)."""
        first = parts[0]
        if len(parts) == 1:
            return first

        def joined(name: str) -> NDArray[Any]:
            values = [getattr(part, name) for part in parts]
            return values[0] if not values[0].size else np.concatenate(values, axis=1)

        return replace(
            first,
            ball_speed=np.concatenate([part.ball_speed for part in parts]),
            racket_speed=np.concatenate([part.racket_speed for part in parts]),
            status=joined("status"),
            contact_time=joined("contact_time"),
            mean_force=joined("mean_force"),
            rebound_ratio=joined("rebound_ratio"),
            rebound_speed=joined("rebound_speed"),
            vibration_energy=joined("vibration_energy"),
            rebound_ratio_band_width=joined("rebound_ratio_band_width"),
        )

    @property
    def racket_speeds(self) -> list[float]:
        """The racket speeds of the curves, m/s, in their order."""
        return list(dict.fromkeys(float(v) for v in self.racket_speed))

    def at_racket_speed(self, racket_speed: float) -> ImpactCurves:
        """The curves of one racket speed (m/s): a single racket speed's run of ball speeds."""
        keep = np.flatnonzero(self.racket_speed == racket_speed)

        def cut(values: NDArray[Any]) -> NDArray[Any]:
            return values if not values.size else values[:, keep, :]

        return replace(
            self,
            ball_speed=self.ball_speed[keep],
            racket_speed=self.racket_speed[keep],
            status=cut(self.status),
            contact_time=cut(self.contact_time),
            mean_force=cut(self.mean_force),
            rebound_ratio=cut(self.rebound_ratio),
            rebound_speed=cut(self.rebound_speed),
            vibration_energy=cut(self.vibration_energy),
            rebound_ratio_band_width=cut(self.rebound_ratio_band_width),
        )

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(n_points, n_speeds, n_supports)``."""
        return (self.locations.shape[0], self.ball_speed.size, len(self.supports))

    def support_index(self, support: str) -> int:
        """Index of a support on the last axis."""
        return self.supports.index(support)

    def to_xarray(self) -> xr.Dataset:
        """The curves as a dataset: dims ``point``, ``ball_speed``, ``support``; variables named
        as ``impact.csv``'s columns (``contact_time_s`` …) with ``units``, and ``status``."""
        import xarray as xr

        cell = ("point", "ball_speed", "support")
        data: dict[str, Any] = {}
        for attribute in (*_CURVE_QUANTITIES, "vibration_energy"):
            values = getattr(self, attribute)
            if values.size:
                quantity = _QUANTITY[attribute]
                attrs = {"units": quantity.units, "long_name": quantity.long_name}
                data[quantity.name] = (cell, values, attrs)
        if self.rebound_ratio_band_width.size:
            data[BAND_WIDTH] = (
                cell,
                self.rebound_ratio_band_width,
                {"units": "1", "long_name": "width of the rebound ratio's 90 % band (p95 - p05)"},
            )
        data["status"] = (cell, np.asarray(self.status, dtype=str), {"long_name": "impact status"})
        coords = {
            "x_m": ("point", self.locations[:, 0], {"units": "m"}),
            "y_m": ("point", self.locations[:, 1], {"units": "m"}),
            "label": ("point", list(self.labels)),
            "ball_speed_mps": ("ball_speed", self.ball_speed, {"units": "m s-1"}),
            "racket_speed_mps": ("ball_speed", self.racket_speed, {"units": "m s-1"}),
            "support_name": ("support", list(self.supports)),
        }
        return xr.Dataset(data, coords=coords)

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> ImpactCurves:
        """The curves back from :meth:`to_xarray`'s dataset (read from ``figures.nc``)."""
        n, s, p = (dataset.sizes.get(d, 0) for d in ("point", "ball_speed", "support"))
        values = {
            attribute: _array(dataset[_QUANTITY[attribute].name].values)
            if _QUANTITY[attribute].name in dataset
            else _EMPTY
            for attribute in (*_CURVE_QUANTITIES, "vibration_energy")
        }
        status = np.asarray(dataset["status"].values, dtype=str).reshape(n, s, p)
        if BAND_WIDTH in dataset:
            values["rebound_ratio_band_width"] = _array(dataset[BAND_WIDTH].values)
        return cls(
            locations=np.column_stack([_array(dataset["x_m"].values), dataset["y_m"].values]),
            labels=_strings(dataset["label"].values),
            ball_speed=_array(dataset["ball_speed_mps"].values),
            racket_speed=_array(dataset["racket_speed_mps"].values),
            supports=_strings(dataset["support_name"].values),
            status=status,
            **values,
        )


# --- Fig. 13 and Fig. 14 --------------------------------------------------------------------
@dataclass(frozen=True)
class PulseSpectra:
    """Paper Fig. 13: the half-sine force at one point and its spectrum, per ball speed.

    Attributes
    ----------
    support : str
        Support of the impacts.
    location : tuple of float
        Impact point (x, y), m.
    ball_speed : ndarray (n_speeds,)
        Incoming ball speeds, m/s.
    contact_time, half_sine_peak : ndarray (n_speeds,)
        T_c, s, and the half sine's peak π F_MEAN / 2, N (eq 11; NaN where flagged) — the
        impact's own F_MAX with the paper's charge, below it with the coupled charge, whose
        F_MAX (impact.csv's ``peak_force_n``) is the spring's force at the turn.
    status : ndarray of str (n_speeds,)
        Impact status.
    time : ndarray (n_times,)
        Time from first contact, s.
    force : ndarray (n_speeds, n_times)
        Half-sine force F(t), N (eq 11; NaN for a flagged speed).
    frequency : ndarray (n_frequencies,)
        Frequency, Hz.
    spectrum : ndarray (n_speeds, n_frequencies)
        ``|S(f)|``, N·s (NaN for a flagged speed).
    mode_names : tuple of str
        The flexible modes of the run's model within the frequency range.
    mode_frequency : ndarray (n_modes,)
        Their natural frequencies, Hz.
    mode_charged : ndarray of bool (n_modes,)
        Which of them the prediction charges (run.json's ``modal_model``, the report's "Modes
        the prediction used"); the others are the string bed's, left out unless
        ``include_string_bed`` (their vibration is in the ball–string law), drawn for
        reference.
    modal : bool
        The racket has a modal model (False: rigid).
    description : str
        The run's options in words, for the title.
    """

    support: str
    location: tuple[float, float]
    ball_speed: NDArray[np.float64]
    contact_time: NDArray[np.float64]
    half_sine_peak: NDArray[np.float64]
    status: NDArray[np.str_]
    time: NDArray[np.float64]
    force: NDArray[np.float64]
    frequency: NDArray[np.float64]
    spectrum: NDArray[np.float64]
    mode_names: tuple[str, ...]
    mode_frequency: NDArray[np.float64]
    mode_charged: NDArray[np.bool_]
    modal: bool
    description: str

    def drawn(self) -> NDArray[np.bool_]:
        """Which speeds have a pulse to draw (a finite contact time and status ``ok``)."""
        return np.asarray(np.isfinite(self.contact_time) & (self.status == STATUS_OK))

    def to_xarray(self) -> xr.Dataset:
        """Dims ``ball_speed``, ``time``, ``frequency``, ``mode``; ``force_n`` and
        ``spectrum_n_s``, the pulse's ``contact_time_s``, ``half_sine_peak_force_n`` and
        ``status``."""
        import xarray as xr

        return xr.Dataset(
            {
                "contact_time_s": ("ball_speed", self.contact_time, {"units": "s"}),
                "half_sine_peak_force_n": ("ball_speed", self.half_sine_peak, {"units": "N"}),
                "status": ("ball_speed", np.asarray(self.status, dtype=str)),
                "force_n": (("ball_speed", "time"), self.force, {"units": "N"}),
                "spectrum_n_s": (("ball_speed", "frequency"), self.spectrum, {"units": "N s"}),
            },
            coords={
                "ball_speed_mps": ("ball_speed", self.ball_speed, {"units": "m s-1"}),
                "time_s": ("time", self.time, {"units": "s"}),
                "frequency_hz": ("frequency", self.frequency, {"units": "Hz"}),
                **(
                    {
                        "mode_name": ("mode", list(self.mode_names)),
                        "mode_frequency_hz": ("mode", self.mode_frequency, {"units": "Hz"}),
                        # netCDF 3 has no boolean
                        "mode_charged": ("mode", self.mode_charged.astype(np.int8)),
                    }
                    if self.mode_names
                    else {}
                ),
            },
            attrs={
                "support": self.support,
                "x_m": self.location[0],
                "y_m": self.location[1],
                "modal": int(self.modal),
                "description": self.description,
            },
        )

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> PulseSpectra:
        """Back from :meth:`to_xarray`'s dataset."""
        attrs = dataset.attrs
        return cls(
            support=str(attrs["support"]),
            location=(float(attrs["x_m"]), float(attrs["y_m"])),
            ball_speed=_array(dataset["ball_speed_mps"].values),
            contact_time=_array(dataset["contact_time_s"].values),
            half_sine_peak=_array(dataset["half_sine_peak_force_n"].values),
            status=np.asarray(dataset["status"].values, dtype=str),
            time=_array(dataset["time_s"].values),
            force=_array(dataset["force_n"].values),
            frequency=_array(dataset["frequency_hz"].values),
            spectrum=_array(dataset["spectrum_n_s"].values),
            mode_names=_strings(dataset["mode_name"].values) if "mode_name" in dataset else (),
            mode_frequency=_array(dataset["mode_frequency_hz"].values)
            if "mode_name" in dataset
            else _array([]),
            mode_charged=_charged(dataset),
            modal=bool(int(attrs["modal"])),
            description=str(attrs["description"]),
        )


def _charged(dataset: xr.Dataset) -> NDArray[np.bool_]:
    """Fig. 13's ``mode_charged`` back; from a figures.nc written before it, as a run charges
    them by default (``include_string_bed`` False): all but the modes named the string bed's."""
    if "mode_charged" in dataset:
        return np.asarray(dataset["mode_charged"].values, dtype=bool)
    names = _strings(dataset["mode_name"].values) if "mode_name" in dataset else ()
    return np.array([kind_from_name(name) != "string-bed" for name in names], dtype=bool)


@dataclass(frozen=True)
class FrameVibration:
    """Paper Fig. 14: one mode's displacement amplitude along the frame after an impact.

    Attributes
    ----------
    response_x : ndarray (n_response,)
        Points along the long axis, x from the butt, m.
    location : tuple of float
        Impact point (x, y), m.
    ball_speed : ndarray (n_speeds,)
        Incoming ball speeds, m/s.
    supports : tuple of str
        Supports.
    amplitude : ndarray (n_response, n_speeds, n_supports)
        Displacement amplitude X (eq 12) signed by the mode's shape, m (NaN where flagged).
    status : ndarray of str (n_speeds, n_supports)
        Impact status.
    mode_name : str
        The mode drawn.
    description : str
        The run's options in words, for the title.
    """

    response_x: NDArray[np.float64]
    location: tuple[float, float]
    ball_speed: NDArray[np.float64]
    supports: tuple[str, ...]
    amplitude: NDArray[np.float64]
    status: NDArray[np.str_]
    mode_name: str
    description: str = ""

    @classmethod
    def of(
        cls, result: ImpactResult, response_x: ArrayLike, mode: int = 0, point: int = 0
    ) -> FrameVibration:
        """The amplitude of mode ``mode`` along the axis after the impacts at ``point`` (eq 12).

        Parameters
        ----------
        result : ImpactResult
            Impacts of a flexible racket (with a modal model).
        response_x : array_like
            Points along the long axis, m from the butt.
        mode : int
            Which mode.
        point : int
            Which impact point of the result.
        """
        model = result.modal_model
        if model is None:
            raise ValueError("a rigid racket (no modal model) does not vibrate")
        x = _array(response_x)
        response = np.column_stack([x, np.zeros_like(x)])
        sign = np.sign(model.mode_shapes_at(response)[:, mode])
        amplitude = result.displacement_amplitude(response)[:, point, :, :, mode]
        return cls(
            response_x=x,
            location=(float(result.locations[point, 0]), float(result.locations[point, 1])),
            ball_speed=_array(result.ball_speed),
            supports=tuple(result.supports),
            amplitude=np.asarray(sign[:, None, None] * amplitude),
            status=np.asarray(result.status, dtype=str)[point],
            mode_name=model.names[mode],
        )

    def to_xarray(self) -> xr.Dataset:
        """Dims ``x``, ``ball_speed``, ``support``: ``amplitude_m`` and ``status``."""
        import xarray as xr

        return xr.Dataset(
            {
                "amplitude_m": (
                    ("x", "ball_speed", "support"),
                    self.amplitude,
                    {"units": "m", "long_name": "displacement amplitude (eq 12), signed by shape"},
                ),
                "status": (("ball_speed", "support"), np.asarray(self.status, dtype=str)),
            },
            coords={
                "x_m": ("x", self.response_x, {"units": "m"}),
                "ball_speed_mps": ("ball_speed", self.ball_speed, {"units": "m s-1"}),
                "support_name": ("support", list(self.supports)),
            },
            attrs={
                "impact_x_m": self.location[0],
                "impact_y_m": self.location[1],
                "mode_name": self.mode_name,
                "description": self.description,
            },
        )

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> FrameVibration:
        """Back from :meth:`to_xarray`'s dataset."""
        attrs = dataset.attrs
        return cls(
            response_x=_array(dataset["x_m"].values),
            location=(float(attrs["impact_x_m"]), float(attrs["impact_y_m"])),
            ball_speed=_array(dataset["ball_speed_mps"].values),
            supports=_strings(dataset["support_name"].values),
            amplitude=_array(dataset["amplitude_m"].values),
            status=np.asarray(dataset["status"].values, dtype=str),
            mode_name=str(attrs["mode_name"]),
            description=str(attrs["description"]),
        )


# --- datasets of several figures in one file ------------------------------------------------
def write_figure_data(
    path: Path, datasets: Sequence[xr.Dataset | Callable[[], xr.Dataset]]
) -> Path:
    """Write the figures' data of a step into one netCDF file (``figures.nc``).

    Parameters
    ----------
    path : Path
        The file (netCDF 3, xarray's scipy engine).
    datasets : sequence of xarray.Dataset or callable
        The ``to_xarray()`` of each figure-data object of the step (their names do not clash:
        each is prefixed with its figures' keys), or the ``to_xarray`` itself (a callable
        without arguments): made here, where xarray is spared importing dask (≈ 0.4 s, see
        :func:`_no_dask_arrays`).

    Returns
    -------
    Path
        ``path``.
    """
    with _no_dask_arrays():
        made = [data() if callable(data) else data for data in datasets]
        _write_netcdf3(joined_figure_data(made), Path(path))
    return Path(path)


@contextmanager
def _no_dask_arrays() -> Iterator[None]:
    """Tell xarray, while this runs, that no array is dask's, when none can be: ``dask`` (or
    ``dask.array``) is not imported in this process.

    xarray asks of every array it wraps whether it is a dask array, and to ask it imports
    ``dask.array`` (at its first Variable) and ``dask`` (to encode text): ≈ 0.5 s CPU of
    ``predict`` and ``identify``, for nothing, with no switch. Its answers come from its cache
    of duck-array modules and from ``is_dask_collection``, which give here the answers xarray
    gives where dask is not installed; both are put back after, so a dask array made later is
    known as one. Another thread making dask arrays for xarray while a figures.nc is written
    would have them taken as plain arrays; no racketdyn step does.
    """
    try:
        from packaging.version import Version
        from xarray.namedarray import pycompat
        from xarray.namedarray import utils as named_utils

        cache = pycompat._cached_duck_array_modules
        absent = object.__new__(pycompat.DuckArrayModule)
        absent.module, absent.type, absent.available = None, (), False
        absent.version = Version("0.0.0")
        collection = named_utils.is_dask_collection
    except (ImportError, AttributeError):  # another xarray: it imports dask as it likes
        yield
        return
    arrays = "dask.array" not in sys.modules and "dask" not in cache
    collections = "dask" not in sys.modules
    if arrays:
        cache["dask"] = absent
    if collections:
        named_utils.is_dask_collection = _no_dask_collection  # type: ignore[assignment]
    try:
        yield
    finally:
        if arrays and cache.get("dask") is absent:
            del cache["dask"]
        if collections and named_utils.is_dask_collection is _no_dask_collection:
            named_utils.is_dask_collection = collection


def _no_dask_collection(value: object) -> bool:
    """xarray's ``is_dask_collection`` where dask is not imported (:func:`_no_dask_arrays`)."""
    return False


def joined_figure_data(datasets: Sequence[xr.Dataset]) -> xr.Dataset:
    """The figures' data of a step as one dataset, as ``figures.nc`` holds it
    (:func:`write_figure_data`).

    Parameters
    ----------
    datasets : sequence of xarray.Dataset
        The ``to_xarray()`` of each figure-data object of the step.
    """
    import xarray as xr

    joined = xr.merge(list(datasets), combine_attrs="override")
    joined.attrs = {}
    for dataset in datasets:
        joined.attrs.update(dataset.attrs)
    joined.attrs["title"] = "racketdyn: the data each figure of the run draws"
    return joined


def _write_netcdf3(dataset: xr.Dataset, path: Path) -> None:
    """``dataset.to_netcdf(path, engine="scipy")``, the same bytes, without asking dask for its
    scheduler: ``to_netcdf`` and the store's default write lock import ``dask.distributed`` to
    learn that none runs (≈ 0.2 s of a 3 s ``predict``). The file is written by this thread
    alone, so it takes no lock (``tests/test_figure_data_file.py`` compares the bytes)."""
    from xarray.backends import ScipyDataStore

    store = ScipyDataStore(str(path), mode="w", lock=False)
    try:
        dataset.dump_to_store(store)
    finally:
        store.close()


def read_figure_data(path: Path) -> xr.Dataset:
    """The dataset of a ``figures.nc`` (:func:`write_figure_data`), loaded.

    Each figure-data class reads its part back with ``from_xarray`` (``PaperFigures.from_xarray(
    read_figure_data(folder / FIGURES_FILE))``).

    Parameters
    ----------
    path : Path
        The file.
    """
    import xarray as xr

    with xr.open_dataset(path, engine="scipy") as dataset:
        return dataset.load()


def read_step_data(folder: Path, label: str = "") -> dict[str, Any]:
    """What a run folder holds for its figures, as the figure-data objects of its step, by the
    name of the step result's attribute that holds each (``paper_figures``,
    ``transient_curves``, ``comparison_map``, ``transient_histories``, ``axis_curves``,
    ``rebound``, ``shape_figures``, ``nodes_free_hand``, and the objects a step stores as they
    are, :func:`defer_figure_data`): the ``source`` of :func:`racketdyn.plotting.registry.draw`,
    which redraws every figure of the folder from it alone (``tests/test_redraw_from_folder.py``).

    Parameters
    ----------
    folder : Path
        A run folder of any step; without ``figures.nc`` (nor a sweep's store): empty.
    label : str
        Of a figure written once per model (compare's ``"free"``, ``"hand"``): that model's
        data; of a sweep's summary (``summary_<variable>.png``): the variable, whose curves are
        read from the folder's store (:func:`racketdyn.sweep.summary.summary_curves`).

    Raises
    ------
    InputError
        ``folder`` is not a folder.
    """
    from racketdyn.sweep.store import STORE_NAME, open_sweep
    from racketdyn.sweep.summary import summary_curves
    from racketdyn.workflows.shape_figures import AxisNodes, IdentifiedShapes

    if not Path(folder).is_dir():
        raise InputError(f"{folder}: no such run folder")
    if label and (Path(folder) / STORE_NAME).is_dir():  # a sweep: its store holds the curves
        return {"curves": summary_curves(open_sweep(Path(folder)), label)}
    path = Path(folder) / FIGURES_FILE
    if not path.is_file():
        return {}
    dataset = read_figure_data(path)
    found: dict[str, Any] = {}
    if IdentifiedShapes.in_dataset(dataset, label):
        found["shape_figures"] = IdentifiedShapes.from_xarray(dataset, label)
    if _has(dataset, "fig6_free_hand"):
        found["nodes_free_hand"] = AxisNodes.from_xarray(dataset, "fig6_free_hand")
    if _has(dataset, "fig11_12"):
        found["paper_figures"] = PaperFigures.from_xarray(dataset)
    if TransientCurves.in_dataset(dataset):
        found["transient_curves"] = TransientCurves.from_xarray(dataset)
    if ComparisonMap.in_dataset(dataset):
        found["comparison_map"] = ComparisonMap.from_xarray(dataset)
    if TransientHistories.in_dataset(dataset):
        found["transient_histories"] = TransientHistories.from_xarray(dataset)
    if _has(dataset, "swing_axis_0"):
        found["axis_curves"] = SwingAxisCurves.from_xarray(dataset)
    if _has(dataset, "fig15_identified"):
        found["rebound"] = IdentifiedRebound.from_xarray(dataset)
    return {**stored(dataset, label), **found}


def defer_figure_data(
    result: StepResult,
    objects: Mapping[str, Any],
    datasets: Sequence[Callable[[], xr.Dataset]] = (),
) -> None:
    """List the step's ``figures.nc`` and write it while the figures are drawn
    (:func:`racketdyn.workflows.run.defer_file`): the objects its figures read, stored as they
    are (:func:`racketdyn.workflows._figure_io.store`), beside the figure-data objects'.

    Parameters
    ----------
    result : StepResult
        The step's result (its ``out`` is the run folder).
    objects : mapping of str to object
        Name (the attribute of the step's result a figure ``reads``) → object.
    datasets : sequence of callable
        The ``to_xarray`` of the step's figure-data objects.
    """
    path = result.out / FIGURES_FILE

    def write() -> Path:
        return write_figure_data(path, [functools.partial(store, objects), *datasets])

    defer_file(result, path, write)


# --- the figures' own impacts are not the run's ------------------------------------------
_P = ParamSpec("_P")
_R = TypeVar("_R")


def _figure_impacts(function: Callable[_P, _R]) -> Callable[_P, _R]:
    """Compute a figure's data with its impacts' warnings off the console (the figure marks
    its own; :func:`racketdyn.impact.result.impact_warnings_quiet`)."""

    @functools.wraps(function)
    def computed(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        with impact_warnings_quiet():
            return function(*args, **kwargs)

    return computed


# --- the options in words, and the racket speed at any ball speed --------------------------
def describe_options(
    options: Mapping[str, Any], racket_speeds: Sequence[float], racket_speed: float | None = None
) -> str:
    """A run's impact options in words, for figure titles.

    Parameters
    ----------
    options : mapping
        Keywords of :func:`racketdyn.impact.predict` (``modal_model``, ``stiffness_reading``,
        ``include_string_bed``, ``string_bed``).
    racket_speeds : sequence of float
        The run's racket speeds, m/s.
    racket_speed : float, optional
        The racket speed of a single-speed figure, m/s (default: the run's).
    """
    if racket_speed is None:
        distinct = sorted(set(racket_speeds))
        moving = len(distinct) > 1 or (distinct and distinct[0] != 0.0)
        racket = (
            "racket " + ", ".join(f"{v:g}" for v in racket_speeds) + " m/s"
            if moving
            else "racket at rest"
        )
    else:
        racket = f"racket {racket_speed:g} m/s" if racket_speed else "racket at rest"
    parts = [racket, f"eq 10 {options.get('stiffness_reading') or 'period'} reading"]
    if options.get("vibration_charge") == "paper":
        parts.append("the paper's vibration charge")
    if options.get("include_string_bed"):
        parts.append("string-bed modes charged")
    if options.get("string_bed") == "local":
        parts.append("each point's string-bed law")
    if options.get("modal_model") is None:
        parts.append("rigid racket")
    return "; ".join(parts)


def racket_speed_at(
    speeds: ArrayLike, run_speeds: Sequence[float], racket_speeds: Sequence[float]
) -> NDArray[np.float64]:
    """Racket speed at each ball speed, m/s: the run's one racket speed, or the run's (ball
    speed, racket speed) pairs interpolated linearly (held beyond their ends).

    Parameters
    ----------
    speeds : array_like
        Ball speeds, m/s.
    run_speeds, racket_speeds : sequence of float
        The run's ball speeds and racket speeds (one, or one per ball speed), m/s.
    """
    v = _array(speeds)
    if len(set(racket_speeds)) <= 1 or len(racket_speeds) != len(run_speeds):
        return np.full(v.shape, racket_speeds[0] if racket_speeds else 0.0)
    order = np.argsort(run_speeds)
    return _array(np.interp(v, _array(run_speeds)[order], _array(racket_speeds)[order]))


def _curve_speeds(
    run_speeds: Sequence[float], low: float, high: float, n: int
) -> NDArray[np.float64]:
    """A fixed sweep of ball speeds, stretched to the run's fastest, with the run's speeds in."""
    top = max(high, *run_speeds) if run_speeds else high
    return np.union1d(np.linspace(low, top, n), _array(run_speeds))


def _main_support(supports: Sequence[str]) -> str:
    """The support of single-support panels: pinned (the paper's hand-held) if run."""
    return "pinned" if "pinned" in supports else supports[0]


def _axis_points(racket: Racket, n: int, inset: float) -> NDArray[np.float64]:
    head = racket.head
    x = np.linspace(
        head.throat_x_m + inset * head.half_length_m, head.tip_x_m - inset * head.half_length_m, n
    )
    return np.column_stack([x, np.full_like(x, head.centre_y_m)])


# --- predict: the paper's figures ----------------------------------------------------------
@dataclass(frozen=True)
class PaperFigures:
    """What the paper's figures of a ``predict`` run draw (Figs 11–15 and the face maps).

    Attributes
    ----------
    racket_name : str
        The racket's name, for titles.
    head : HeadEllipse
        The racket's string bed (the face maps' outline).
    speed_curves : ImpactCurves
        Figs 11–12: F_MEAN and T_c at the top, centre and throat against ball speed, over the
        curve speeds once per racket speed of the run (its ``racket_speed`` constant along
        each: :meth:`ImpactCurves.at_racket_speed`).
    run_speeds : ndarray
        The run's ball speeds, m/s (marked on the curves against speed).
    pulse : PulseSpectra
        Fig. 13.
    frame : FrameVibration or None
        Fig. 14 (None: a rigid racket, no vibration).
    axis : ImpactCurves
        Fig. 15: rebound ratio along the long axis at the shown speed.
    axis_marks : dict of str to float
        Fig. 15's marks on the axis (centre of percussion, the first mode's nodes), x in m.
    face : ImpactCurves
        The face maps: the run's impacts at the shown speed (rebound ratio, contact time,
        vibration energy).
    main_support : str
        Support of the single-support panels.
    description, axis_description, face_description : str
        The run's options in words, for the titles (the latter two with their racket speed).
    axis_band : AxisBand or None
        With an uncertainty: Fig. 15's 90 % band of the rebound ratio.
    run_racket_speeds : ndarray
        The racket speed of each of ``run_speeds``, m/s (empty: a figures.nc of an earlier
        version, racket speeds not recorded).
    """

    racket_name: str
    head: HeadEllipse
    speed_curves: ImpactCurves
    run_speeds: NDArray[np.float64]
    pulse: PulseSpectra
    frame: FrameVibration | None
    axis: ImpactCurves
    axis_marks: dict[str, float]
    face: ImpactCurves
    main_support: str
    description: str
    axis_description: str
    face_description: str
    axis_band: AxisBand | None = None
    run_racket_speeds: NDArray[np.float64] = field(default_factory=lambda: _EMPTY)

    def to_xarray(self) -> xr.Dataset:
        """One dataset, each figure's names prefixed with its key and ``__``: ``fig11_12``,
        ``fig13``, ``fig14`` (absent for a rigid racket), ``fig15``, ``face_maps``."""
        curves = self.speed_curves.to_xarray().assign_coords(
            run_speed_mps=("run_speed", self.run_speeds, {"units": "m s-1"})
        )
        if self.run_racket_speeds.size == self.run_speeds.size:
            curves = curves.assign_coords(
                run_racket_speed_mps=("run_speed", self.run_racket_speeds, {"units": "m s-1"})
            )
        curves.attrs = {
            "racket_name": self.racket_name,
            "description": self.description,
            **{f"head_{key}": float(getattr(self.head, key)) for key in _HEAD},
        }
        axis = self.axis.to_xarray().assign_coords(
            mark_name=("mark", list(self.axis_marks)),
            mark_x_m=("mark", _array(list(self.axis_marks.values())), {"units": "m"}),
        )
        axis.attrs = {"description": self.axis_description}
        if self.axis_band is not None:
            axis = axis.assign(self.axis_band.variables())
        face = self.face.to_xarray()
        face.attrs = {"main_support": self.main_support, "description": self.face_description}
        parts = {"fig11_12": curves, "fig13": self.pulse.to_xarray()}
        if self.frame is not None:
            parts["fig14"] = self.frame.to_xarray()
        parts |= {"fig15": axis, "face_maps": face}
        return _join(parts)

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> PaperFigures:
        """Back from :meth:`to_xarray`'s dataset (or a ``figures.nc`` holding it)."""
        curves, axis, face = (_part(dataset, k) for k in ("fig11_12", "fig15", "face_maps"))
        return cls(
            racket_name=str(curves.attrs["racket_name"]),
            head=HeadEllipse(**{key: float(curves.attrs[f"head_{key}"]) for key in _HEAD}),
            speed_curves=ImpactCurves.from_xarray(curves),
            run_speeds=_array(curves["run_speed_mps"].values),
            pulse=PulseSpectra.from_xarray(_part(dataset, "fig13")),
            frame=FrameVibration.from_xarray(_part(dataset, "fig14"))
            if _has(dataset, "fig14")
            else None,
            axis=ImpactCurves.from_xarray(axis),
            axis_marks={
                str(name): float(x)
                for name, x in zip(axis["mark_name"].values, axis["mark_x_m"].values, strict=True)
            },
            face=ImpactCurves.from_xarray(face),
            main_support=str(face.attrs["main_support"]),
            description=str(curves.attrs["description"]),
            axis_description=str(axis.attrs["description"]),
            face_description=str(face.attrs["description"]),
            axis_band=AxisBand.from_xarray(axis) if "rebound_ratio_p05" in axis else None,
            run_racket_speeds=_array(curves["run_racket_speed_mps"].values)
            if "run_racket_speed_mps" in curves.coords
            else _EMPTY,
        )


@dataclass(frozen=True)
class AxisBand:
    """The 90 % band of the rebound ratio along Fig. 15's axis (``predict --uncertainty``).

    Attributes
    ----------
    p05, p95 : ndarray (n_points, n_supports)
        5 % and 95 % quantiles over the valid samples; NaN where the band is not given.
    samples : int
        Samples drawn.
    inputs : str
        The uncertain inputs, for the legend.
    """

    p05: NDArray[np.float64]
    p95: NDArray[np.float64]
    samples: int
    inputs: str

    def variables(self) -> dict[str, Any]:
        """Fig. 15's band as dataset variables on ``point`` × ``support``."""
        attrs = {"units": "1", "samples": self.samples, "inputs": self.inputs}
        return {
            "rebound_ratio_p05": (("point", "support"), self.p05, attrs),
            "rebound_ratio_p95": (("point", "support"), self.p95, attrs),
        }

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> AxisBand:
        """Back from :meth:`variables` in a dataset."""
        low = dataset["rebound_ratio_p05"]
        return cls(
            _array(low.values),
            _array(dataset["rebound_ratio_p95"].values),
            int(low.attrs["samples"]),
            str(low.attrs["inputs"]),
        )


def axis_points(racket: Racket) -> NDArray[np.float64]:
    """Fig. 15's points along the long axis."""
    return _axis_points(racket, AXIS_POINTS, 0.05)


@_figure_impacts
def paper_figures(
    racket: Racket,
    ball: Ball,
    *,
    speeds: Sequence[float] = (),
    racket_speeds: Sequence[float] = (0.0,),
    supports: Sequence[str] = ("pinned", "free"),
    shown_speed: float = SHOWN_SPEED_MPS,
    shown_racket_speed: float | None = None,
    result: ImpactResult | None = None,
    **options: Any,
) -> PaperFigures:
    """Compute what the paper's figures draw, with the run's racket, ball and options.

    The figures that need a grid of their own (curves against speed, the long axis, the tip)
    get it here, by :func:`racketdyn.impact.predict` with the run's options; the face maps
    take the run's own impacts.

    Parameters
    ----------
    racket, ball : Racket, Ball
        The run's racket and ball.
    speeds : sequence of float
        The run's ball speeds, m/s (none: the figures' own); marked on the curves against
        speed, the speeds of Figs 13 and 14.
    racket_speeds : sequence of float
        The run's racket speeds, m/s: one, or one per speed of ``speeds``.
    supports : sequence of str
        Supports to draw (``free``, ``pinned``).
    shown_speed : float
        Ball speed of the single-speed figures (face maps, Fig. 15), m/s.
    shown_racket_speed : float, optional
        Its racket speed, m/s (default: the run's racket speed at ``shown_speed``); with it
        the face maps take the run's case of both speeds.
    result : ImpactResult, optional
        The run's impacts (approximate method), drawn by the face maps; None: a 25 × 25 grid
        at ``shown_speed``.
    **options
        The run's further keywords of :func:`racketdyn.impact.predict` (``modal_model``,
        ``law``, ``stiffness_reading``, ``include_string_bed``, ``string_bed`` …), used as
        they are.

    Returns
    -------
    PaperFigures
    """
    supports = tuple(supports)
    model: ModalModel | None = options.get("modal_model")

    def run(
        points: ArrayLike,
        at: ArrayLike,
        on: Sequence[str] = supports,
        labels: Sequence[str] | None = None,
    ) -> ImpactResult:
        racket_speed = racket_speed_at(at, speeds, racket_speeds)
        return predict(
            racket, ball, points, at, on, racket_speed=racket_speed, labels=labels, **options
        )

    marks = landmark_points(racket)
    names = ["top", "centre", "throat"]
    curve_speeds = _curve_speeds(
        speeds, CURVE_SPEEDS_MPS[0], CURVE_SPEEDS_MPS[-1], CURVE_SPEEDS_MPS.size
    )
    # one set of curves per racket speed, each over the whole speed axis: interpolating the
    # racket speed between the run's (ball, racket) pairs bent the curves at each (issue 27)
    racket_list = list(racket_speeds) or [0.0]
    speed_curves = ImpactCurves.concatenate(
        [
            ImpactCurves.of(
                predict(
                    racket,
                    ball,
                    [marks[n] for n in names],
                    curve_speeds,
                    supports,
                    racket_speed=np.full(curve_speeds.shape, r),
                    labels=names,
                    **options,
                ),
                ("mean_force", "contact_time"),
            )
            for r in dict.fromkeys(racket_list)
        ]
    )
    description = describe_options(options, racket_speeds)
    main = _main_support(supports)
    pulse = _pulse_spectra(
        run([marks["centre"]], _array(speeds or PULSE_SPEEDS_MPS), (main,), ["centre"]),
        model,
        description,
    )
    frame = None
    if model is not None and model.n_modes:
        tip = run([marks["tip"]], _array(speeds or VIBRATION_SPEEDS_MPS), labels=["tip"])
        along = np.linspace(0.0, racket.length_m, FRAME_POINTS)
        frame = replace(FrameVibration.of(tip, along), description=description)
    axis_marks = {"centre of percussion (grip)": racket.centre_of_percussion_m()}
    if model is not None and model.n_modes:
        head = racket.head
        nodes = axis_nodes(model, 0, (head.throat_x_m, head.tip_x_m))
        for k, node in enumerate(nodes, 1):
            name = model.names[0]
            axis_marks[f"node of {name}" if nodes.size == 1 else f"node {k} of {name}"] = float(
                node
            )
    axis_racket_speed = (
        float(racket_speed_at([shown_speed], speeds, racket_speeds)[0])
        if shown_racket_speed is None
        else float(shown_racket_speed)
    )

    def at_shown(points: ArrayLike) -> ImpactResult:
        return predict(
            racket,
            ball,
            points,
            [shown_speed],
            supports,
            racket_speed=[axis_racket_speed],
            **options,
        )

    if result is None:
        result = at_shown(racket.head.grid(25))
    hits = np.isclose(result.ball_speed, shown_speed)
    if shown_racket_speed is not None:
        hits &= np.isclose(_array(result.racket_speed), axis_racket_speed)
    found = np.flatnonzero(hits)
    face = ImpactCurves.of(result, _FACE_QUANTITIES, [int(found[0]) if found.size else 0])
    return PaperFigures(
        racket_name=racket.name,
        head=racket.head,
        speed_curves=speed_curves,
        run_speeds=_array(speeds),
        pulse=pulse,
        frame=frame,
        axis=ImpactCurves.of(at_shown(axis_points(racket))),
        axis_marks=axis_marks,
        face=face,
        main_support=main if main in face.supports else face.supports[0],
        description=description,
        axis_description=describe_options(options, racket_speeds, axis_racket_speed),
        face_description=describe_options(options, racket_speeds, float(face.racket_speed[0])),
        run_racket_speeds=_array(racket_speeds)
        if len(racket_speeds) == len(speeds)
        else np.full(len(speeds), racket_list[0]),
    )


def _pulse_spectra(
    result: ImpactResult, model: ModalModel | None, description: str
) -> PulseSpectra:
    """Fig. 13's pulses and spectra from the impacts at one point on one support (eq 11)."""
    time, frequency = PULSE_TIME_S, PULSE_FREQUENCY_HZ
    # eq 11's half sine of the row's impulse F_MEAN T_c (the coupled charge's F_MAX is the
    # spring's force at the turn, above the half sine's: the stiffening spring's pulse peaks)
    contact, peak = result.contact_time[0, :, 0], np.pi * result.mean_force[0, :, 0] / 2.0
    status = np.asarray(result.status, dtype=str)[0, :, 0]
    force = np.full((contact.size, time.size), np.nan)
    spectrum = np.full((contact.size, frequency.size), np.nan)
    for s in range(contact.size):
        if np.isfinite(contact[s]) and status[s] == STATUS_OK:
            force[s] = half_sine_force(time, contact[s], peak[s])
            spectrum[s] = half_sine_spectrum(frequency, contact[s], peak[s])
    # the run's flexible modes: those charged (the result's own) and the string bed's
    shown = None if model is None else model.flexible_modes
    within = (
        [] if shown is None else [k for k, f in enumerate(shown.frequency) if f <= frequency[-1]]
    )
    charged = () if result.modal_model is None else result.modal_model.names
    return PulseSpectra(
        support=result.supports[0],
        location=(float(result.locations[0, 0]), float(result.locations[0, 1])),
        ball_speed=_array(result.ball_speed),
        contact_time=_array(contact),
        half_sine_peak=_array(peak),
        status=status,
        time=time,
        force=force,
        frequency=frequency,
        spectrum=spectrum,
        mode_names=tuple(shown.names[k] for k in within) if shown is not None else (),
        mode_frequency=_array([shown.frequency[k] for k in within])
        if shown is not None
        else _array([]),
        mode_charged=np.array([shown.names[k] in charged for k in within], dtype=bool)
        if shown is not None
        else np.zeros(0, dtype=bool),
        modal=model is not None,
        description=description,
    )


# --- predict --model both: the two models against speed ---------------------------------------
@dataclass(frozen=True)
class TransientCurves:
    """Rebound ratio and contact time against speed at the centre, tip and throat, by the
    approximate method and the transient simulation on the same impacts.

    Attributes
    ----------
    approximate, transient : ImpactCurves
        Each model's impacts (``rebound_ratio``, ``contact_time``).
    run_speeds : ndarray
        The run's ball speeds, m/s (marked).
    description : str
        The run's options in words, for the title.
    run_racket_speeds : ndarray
        The racket speed paired with each of ``run_speeds``, m/s (empty: one racket speed for
        all); the curves hold one run of ball speeds per racket speed
        (:meth:`ImpactCurves.at_racket_speed`).
    """

    approximate: ImpactCurves
    transient: ImpactCurves
    run_speeds: NDArray[np.float64]
    description: str
    run_racket_speeds: NDArray[np.float64] = field(default_factory=lambda: _EMPTY)

    def to_xarray(self) -> xr.Dataset:
        """One dataset: ``transient_speed_approximate__…`` and ``transient_speed_transient__…``."""
        approximate = self.approximate.to_xarray().assign_coords(
            run_speed_mps=("run_speed", self.run_speeds, {"units": "m s-1"})
        )
        if self.run_racket_speeds.size == self.run_speeds.size:
            approximate = approximate.assign_coords(
                run_racket_speed_mps=("run_speed", self.run_racket_speeds, {"units": "m s-1"})
            )
        approximate.attrs = {"description": self.description}
        return _join(
            {
                "transient_speed_approximate": approximate,
                "transient_speed_transient": self.transient.to_xarray(),
            }
        )

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> TransientCurves:
        """Back from :meth:`to_xarray`'s dataset (or a ``figures.nc`` holding it)."""
        approximate = _part(dataset, "transient_speed_approximate")
        paired = approximate.coords.get("run_racket_speed_mps")
        return cls(
            approximate=ImpactCurves.from_xarray(approximate),
            transient=ImpactCurves.from_xarray(_part(dataset, "transient_speed_transient")),
            run_speeds=_array(approximate["run_speed_mps"].values),
            description=str(approximate.attrs["description"]),
            run_racket_speeds=_EMPTY if paired is None else _array(paired.values),
        )

    @staticmethod
    def in_dataset(dataset: xr.Dataset) -> bool:
        """Whether a ``figures.nc`` holds these curves."""
        return _has(dataset, "transient_speed_approximate")


@_figure_impacts
def transient_curves(
    racket: Racket,
    ball: Ball,
    *,
    speeds: Sequence[float] = (),
    racket_speeds: Sequence[float] = (0.0,),
    supports: Sequence[str] = ("free", "pinned"),
    engine: Engine = "auto",
    **options: Any,
) -> TransientCurves:
    """Both impact models at the centre, tip and throat against speed, with the run's options.

    At :data:`TRANSIENT_CURVE_SPEEDS_MPS` (stretched to the run's fastest) and the run's
    speeds; supports those the approximate method takes (free, pinned).

    Parameters
    ----------
    racket, ball : Racket, Ball
        The run's racket and ball.
    speeds, racket_speeds : sequence of float
        The run's ball speeds and racket speeds (one, or one per speed), m/s.
    supports : sequence of str
        Supports.
    engine : str
        Transient engine.
    **options
        The run's keywords of :func:`racketdyn.impact.predict` (``modal_model``, ``law``,
        ``include_string_bed``, ``string_bed``, ``stiffness_reading`` …); all but
        :data:`APPROXIMATE_ONLY` go to :func:`~racketdyn.impact.transient.predict_transient`.
    """
    marks = landmark_points(racket)
    names = ["centre", "tip", "throat"]
    points = [marks[n] for n in names]
    at = _curve_speeds(
        speeds,
        TRANSIENT_CURVE_SPEEDS_MPS[0],
        TRANSIENT_CURVE_SPEEDS_MPS[-1],
        TRANSIENT_CURVE_SPEEDS_MPS.size,
    )
    # one run of ball speeds per racket speed, each over the whole axis (as Figs 11–12):
    # interpolating the racket speed between the run's (ball, racket) pairs bent the curves
    racket_list = list(dict.fromkeys(float(r) for r in racket_speeds)) or [0.0]
    common: dict[str, Any] = {
        "labels": names,
        "racket_speed": np.repeat(racket_list, at.size),
    }
    every = np.tile(at, len(racket_list))
    from racketdyn.impact.transient import predict_transient

    approximate = predict(racket, ball, points, every, supports, **common, **options)
    transient = predict_transient(
        racket,
        ball,
        points,
        every,
        supports,
        engine=engine,
        **common,
        **{k: v for k, v in options.items() if k not in APPROXIMATE_ONLY},
    )
    kept = ("rebound_ratio", "contact_time")
    paired = _array(racket_speeds) if len(racket_speeds) == len(speeds) else _EMPTY
    return TransientCurves(
        approximate=ImpactCurves.of(approximate, kept),
        transient=ImpactCurves.of(transient, kept),
        run_speeds=_array(speeds),
        description=describe_options(options, racket_speeds),
        run_racket_speeds=paired,
    )


# --- predict --model transient|both: the face comparison and the time histories ---------------
@dataclass(frozen=True)
class ComparisonMap:
    """Rebound ratio, approximate method − transient simulation, over the face at one speed.

    Attributes
    ----------
    locations : ndarray (n_points, 2)
        The run's impact points (x, y), m.
    supports : tuple of str
        Supports (one panel each).
    ball_speed : float
        Incoming ball speed, m/s.
    difference : ndarray (n_points, n_supports)
        Approximate − transient rebound ratio, dimensionless (NaN where either is flagged).
    head : HeadEllipse
        The racket's string bed (the maps' outline).
    """

    locations: NDArray[np.float64]
    supports: tuple[str, ...]
    ball_speed: float
    difference: NDArray[np.float64]
    head: HeadEllipse

    @classmethod
    def of(cls, comparison: ModelComparison, speed_index: int, head: HeadEllipse) -> ComparisonMap:
        """The map at one speed of a comparison of the two models on the run's impacts.

        Parameters
        ----------
        comparison : ModelComparison
            Both models on the same impacts.
        speed_index : int
            Which ball speed.
        head : HeadEllipse
            The racket's string bed.
        """
        result = comparison.approximate
        return cls(
            locations=_array(result.locations),
            supports=tuple(result.supports),
            ball_speed=float(result.ball_speed[speed_index]),
            difference=_array(comparison.difference("rebound_ratio")[:, speed_index, :]),
            head=head,
        )

    def to_xarray(self) -> xr.Dataset:
        """One dataset, names prefixed ``transient_comparison_face__``: ``difference_rebound_ratio``
        on (``point``, ``support``)."""
        import xarray as xr

        data = xr.Dataset(
            {
                "difference_rebound_ratio": (
                    ("point", "support"),
                    self.difference,
                    {"units": "1", "long_name": "rebound ratio, approximate - transient"},
                )
            },
            coords={
                "x_m": ("point", self.locations[:, 0], {"units": "m"}),
                "y_m": ("point", self.locations[:, 1], {"units": "m"}),
                "support_name": ("support", list(self.supports)),
            },
            attrs={
                "ball_speed_mps": self.ball_speed,
                **{f"head_{key}": float(getattr(self.head, key)) for key in _HEAD},
            },
        )
        return _join({"transient_comparison_face": data})

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> ComparisonMap:
        """Back from :meth:`to_xarray`'s dataset (or a ``figures.nc`` holding it)."""
        data = _part(dataset, "transient_comparison_face")
        return cls(
            locations=np.column_stack([_array(data["x_m"].values), data["y_m"].values]),
            supports=_strings(data["support_name"].values),
            ball_speed=float(data.attrs["ball_speed_mps"]),
            difference=_array(data["difference_rebound_ratio"].values),
            head=HeadEllipse(**{key: float(data.attrs[f"head_{key}"]) for key in _HEAD}),
        )

    @staticmethod
    def in_dataset(dataset: xr.Dataset) -> bool:
        """Whether a ``figures.nc`` holds the map."""
        return _has(dataset, "transient_comparison_face")


@dataclass(frozen=True)
class TransientHistories:
    """Time histories of simulated impacts: force, displacements, modal coordinates.

    One row per impact (point × support); the samples of each row are the first
    ``n_samples[row]`` (the rest NaN).

    Attributes
    ----------
    points : tuple of str
        Each impact's point name.
    locations : ndarray (n_impacts, 2)
        Impact points (x, y), m.
    supports : tuple of str
        Each impact's support.
    ball_speed, racket_speed : ndarray (n_impacts,)
        Incoming ball speed and racket speed, m/s.
    n_samples : ndarray of int (n_impacts,)
        Samples of each impact.
    time : ndarray (n_impacts, n_samples)
        Time from first contact, s.
    force : ndarray (n_impacts, n_samples)
        Contact force, N.
    ball_displacement, face_displacement : ndarray (n_impacts, n_samples)
        Ball and racket-face displacement into the strings, m.
    modal_coordinates : ndarray (n_impacts, n_samples, n_modes)
        Modal coordinates, m·√kg.
    mode_names : tuple of str
        Names of the modes.
    """

    points: tuple[str, ...]
    locations: NDArray[np.float64]
    supports: tuple[str, ...]
    ball_speed: NDArray[np.float64]
    racket_speed: NDArray[np.float64]
    n_samples: NDArray[np.int64]
    time: NDArray[np.float64]
    force: NDArray[np.float64]
    ball_displacement: NDArray[np.float64]
    face_displacement: NDArray[np.float64]
    modal_coordinates: NDArray[np.float64]
    mode_names: tuple[str, ...]

    @classmethod
    def of(cls, histories: Sequence[History], mode_names: Sequence[str]) -> TransientHistories:
        """The histories of :func:`racketdyn.impact.comparison.simulate_histories`, padded.

        Parameters
        ----------
        histories : sequence of History
            The simulated impacts.
        mode_names : sequence of str
            Names of their modes.
        """
        lengths = np.array([h.impact.time_s.size for h in histories], dtype=np.int64)
        width = int(lengths.max()) if lengths.size else 0
        n_modes = len(mode_names)

        def padded(rows: list[NDArray[np.float64]], *tail: int) -> NDArray[np.float64]:
            out = np.full((len(rows), width, *tail), np.nan)
            for k, row in enumerate(rows):
                out[k, : row.shape[0]] = row
            return out

        return cls(
            points=tuple(h.point for h in histories),
            locations=_array([h.location for h in histories]).reshape(-1, 2),
            supports=tuple(h.support for h in histories),
            ball_speed=_array([h.impact.ball_speed_mps for h in histories]),
            racket_speed=_array([h.impact.racket_speed_mps for h in histories]),
            n_samples=lengths,
            time=padded([_array(h.impact.time_s) for h in histories]),
            force=padded([_array(h.impact.force_n) for h in histories]),
            ball_displacement=padded([_array(h.impact.ball_displacement_m) for h in histories]),
            face_displacement=padded([_array(h.face_displacement_m) for h in histories]),
            modal_coordinates=padded(
                [
                    _array(h.impact.modal_coordinates).reshape(h.impact.time_s.size, n_modes)
                    for h in histories
                ],
                n_modes,
            ),
            mode_names=tuple(mode_names),
        )

    def samples(self, row: int) -> slice:
        """The samples of impact ``row``."""
        return slice(0, int(self.n_samples[row]))

    def to_xarray(self) -> xr.Dataset:
        """One dataset, names prefixed ``transient_histories__``: dims ``impact``, ``sample``,
        ``mode``; ``time_s``, ``force_n``, ``ball_displacement_m``, ``face_displacement_m``,
        ``modal_coordinate_m_sqrt_kg``."""
        import xarray as xr

        cell = ("impact", "sample")
        data = xr.Dataset(
            {
                "time_s": (cell, self.time, {"units": "s"}),
                "force_n": (cell, self.force, {"units": "N"}),
                "ball_displacement_m": (cell, self.ball_displacement, {"units": "m"}),
                "face_displacement_m": (cell, self.face_displacement, {"units": "m"}),
                **(
                    {
                        "modal_coordinate_m_sqrt_kg": (
                            (*cell, "mode"),
                            self.modal_coordinates,
                            {"units": "m kg0.5"},
                        )
                    }
                    if self.mode_names
                    else {}
                ),
            },
            coords={
                "point": ("impact", list(self.points)),
                "x_m": ("impact", self.locations[:, 0], {"units": "m"}),
                "y_m": ("impact", self.locations[:, 1], {"units": "m"}),
                "support_name": ("impact", list(self.supports)),
                "ball_speed_mps": ("impact", self.ball_speed, {"units": "m s-1"}),
                "racket_speed_mps": ("impact", self.racket_speed, {"units": "m s-1"}),
                "n_samples": ("impact", self.n_samples.astype(np.int32)),
                **({"mode_name": ("mode", list(self.mode_names))} if self.mode_names else {}),
            },
        )
        return _join({"transient_histories": data})

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> TransientHistories:
        """Back from :meth:`to_xarray`'s dataset (or a ``figures.nc`` holding it)."""
        data = _part(dataset, "transient_histories")
        return cls(
            points=_strings(data["point"].values),
            locations=np.column_stack([_array(data["x_m"].values), data["y_m"].values]),
            supports=_strings(data["support_name"].values),
            ball_speed=_array(data["ball_speed_mps"].values),
            racket_speed=_array(data["racket_speed_mps"].values),
            n_samples=np.asarray(data["n_samples"].values, dtype=np.int64),
            time=_array(data["time_s"].values),
            force=_array(data["force_n"].values),
            ball_displacement=_array(data["ball_displacement_m"].values),
            face_displacement=_array(data["face_displacement_m"].values),
            modal_coordinates=_array(data["modal_coordinate_m_sqrt_kg"].values)
            if "mode_name" in data
            else np.zeros((*data["time_s"].shape, 0)),
            mode_names=_strings(data["mode_name"].values) if "mode_name" in data else (),
        )

    @staticmethod
    def in_dataset(dataset: xr.Dataset) -> bool:
        """Whether a ``figures.nc`` holds the histories."""
        return _has(dataset, "transient_histories")


# --- swing: outgoing speed along the axis ------------------------------------------------------
@dataclass(frozen=True)
class SwingAxisCurves:
    """Outgoing ball speed along the long axis for the racket at rest and a few swings.

    Attributes
    ----------
    names : tuple of str
        Each swing's legend name (:func:`racketdyn.impact.swing.axis_swings`).
    curves : tuple of ImpactCurves
        One per swing: points along the axis × the ball speed × the support (``rebound_speed``).
    ball_speed : float
        Incoming ball speed, m/s.
    support : str
        Support during the impact.
    model : str
        Impact model.
    swing_description : str
        The run's swing in words.
    """

    names: tuple[str, ...]
    curves: tuple[ImpactCurves, ...]
    ball_speed: float
    support: str
    model: str
    swing_description: str

    def to_xarray(self) -> xr.Dataset:
        """One dataset: ``swing_axis_<k>__…`` for the k-th swing (its name in attribute
        ``swing_axis_<k>__name``)."""
        parts = {}
        for k, (name, curves) in enumerate(zip(self.names, self.curves, strict=True)):
            data = curves.to_xarray()
            data.attrs = {
                "name": name,
                "ball_speed_mps": self.ball_speed,
                "support": self.support,
                "model": self.model,
                "swing": self.swing_description,
            }
            parts[f"swing_axis_{k}"] = data
        return _join(parts)

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> SwingAxisCurves:
        """Back from :meth:`to_xarray`'s dataset (or a ``figures.nc`` holding it)."""
        parts: list[xr.Dataset] = []
        while _has(dataset, f"swing_axis_{len(parts)}"):
            parts.append(_part(dataset, f"swing_axis_{len(parts)}"))
        first = parts[0].attrs
        return cls(
            names=tuple(str(p.attrs["name"]) for p in parts),
            curves=tuple(ImpactCurves.from_xarray(p) for p in parts),
            ball_speed=float(first["ball_speed_mps"]),
            support=str(first["support"]),
            model=str(first["model"]),
            swing_description=str(first["swing"]),
        )


@_figure_impacts
def swing_axis_curves(
    racket: Racket,
    ball: Ball,
    swing: Swing,
    ball_speed: float,
    support: str,
    model: ImpactModel = "approximate",
    modal_model: ModalModel | None = None,
    **options: Any,
) -> SwingAxisCurves:
    """Outgoing ball speed at :data:`SWING_AXIS_POINTS` points on the long axis for the swings
    of :func:`~racketdyn.impact.swing.axis_swings`, with the run's ball, modes and options.

    Parameters
    ----------
    racket, ball : Racket, Ball
        The run's racket and ball.
    swing : Swing
        The run's swing.
    ball_speed : float
        Incoming ball speed, m/s.
    support : str
        Support during the impact.
    model : {"approximate", "transient"}
        Impact model.
    modal_model : ModalModel or None
        Flexible modes (None: rigid racket).
    **options
        The run's further keywords of the impact model (``law``, ``hand`` …).
    """
    head = racket.head
    step = 2.0 * head.half_length_m / SWING_AXIS_POINTS
    x = head.throat_x_m + step * (np.arange(SWING_AXIS_POINTS) + 0.5)
    points = np.column_stack([x, np.full_like(x, head.centre_y_m)])
    names, curves = [], []
    for name, each in axis_swings(swing):
        names.append(name)
        result = predict_swing(
            racket, ball, points, [ball_speed], each, support, model, modal_model, **options
        )
        curves.append(ImpactCurves.of(result, ("rebound_speed",)))
    return SwingAxisCurves(
        names=tuple(names),
        curves=tuple(curves),
        ball_speed=float(ball_speed),
        support=support,
        model=str(model),
        swing_description=swing.describe(racket),
    )


# --- compare: Fig. 15 with the identified models -----------------------------------------------
IDENTIFIED_CASES: tuple[tuple[str, str, str], ...] = (
    ("pinned", "hand", "pinned at the grip, hand-held modes"),
    ("pinned", "free", "pinned at the grip, free modes"),
    ("free", "free", "freely supported, free modes"),
)
"""Fig. 15's curves with the identified models: (support, which modes, legend)."""


@dataclass(frozen=True)
class IdentifiedRebound:
    """Paper Fig. 15 with the identified models: rebound ratio along the long axis.

    Attributes
    ----------
    x : ndarray (n_points,)
        Impact points along the long axis, m from the butt.
    ball_speed : float
        Incoming ball speed, m/s.
    cases : tuple of str
        Each curve's legend (:data:`IDENTIFIED_CASES`).
    supports : tuple of str
        Each curve's support.
    rebound_ratio : ndarray (n_cases, n_points)
        Rebound ratio e, dimensionless (NaN where flagged).
    """

    x: NDArray[np.float64]
    ball_speed: float
    cases: tuple[str, ...]
    supports: tuple[str, ...]
    rebound_ratio: NDArray[np.float64]

    def plot(self, ax: Axes | None = None) -> Axes:
        """Draw the curves (into ``ax``, or a new figure); returns the axes
        (:func:`racketdyn.plotting.figures.plot_identified_rebound`)."""
        from racketdyn.plotting.figures import plot_identified_rebound

        return plot_identified_rebound(self, ax)

    def to_xarray(self) -> xr.Dataset:
        """One dataset, names prefixed ``fig15_identified__``: ``rebound_ratio`` on
        (``case``, ``x``)."""
        import xarray as xr

        data = xr.Dataset(
            {"rebound_ratio": (("case", "x"), self.rebound_ratio, {"units": "1"})},
            coords={
                "x_m": ("x", self.x, {"units": "m"}),
                "case_name": ("case", list(self.cases)),
                "support_name": ("case", list(self.supports)),
            },
            attrs={"ball_speed_mps": self.ball_speed},
        )
        return _join({"fig15_identified": data})

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset) -> IdentifiedRebound:
        """Back from :meth:`to_xarray`'s dataset (or a ``figures.nc`` holding it)."""
        data = _part(dataset, "fig15_identified")
        return cls(
            x=_array(data["x_m"].values),
            ball_speed=float(data.attrs["ball_speed_mps"]),
            cases=_strings(data["case_name"].values),
            supports=_strings(data["support_name"].values),
            rebound_ratio=_array(data["rebound_ratio"].values),
        )


@_figure_impacts
def identified_rebound(
    racket: Racket, ball: Ball, free: ModalModel, hand: ModalModel, speed: float
) -> IdentifiedRebound:
    """Fig. 15 with the identified free and hand-held modes, with the run's ball.

    Parameters
    ----------
    racket, ball : Racket, Ball
        The racket and the run's ball.
    free, hand : ModalModel
        The identified modes of the freely supported and of the hand-held racket.
    speed : float
        Incoming ball speed, m/s.
    """
    points = _axis_points(racket, AXIS_POINTS, 0.05)
    models = {"free": free, "hand": hand}
    # a model whose shapes lost their scaling (no usable driving point) charges the frame in
    # no unit: its curves are NaN and their legends say why, not drawn as a rigid racket's
    rows = [
        predict(racket, ball, points, [speed], (support,), modal_model=models[modes]).rebound_ratio[
            :, 0, 0
        ]
        if models[modes].mass_normalised
        else np.full(len(points), np.nan)
        for support, modes, _ in IDENTIFIED_CASES
    ]
    return IdentifiedRebound(
        x=points[:, 0].copy(),
        ball_speed=float(speed),
        cases=tuple(
            label if models[modes].mass_normalised else f"{label}: unscaled shapes, not drawn"
            for _, modes, label in IDENTIFIED_CASES
        ),
        supports=tuple(support for support, _, _ in IDENTIFIED_CASES),
        rebound_ratio=np.stack(rows),
    )


FigureData = (
    PaperFigures
    | TransientCurves
    | ComparisonMap
    | TransientHistories
    | SwingAxisCurves
    | IdentifiedRebound
)
"""Any figure-data object a step writes to ``figures.nc``."""
