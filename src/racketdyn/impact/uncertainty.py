"""Uncertainty: what the inputs do not pin down, carried to every impact's numbers.

An :class:`Uncertainty` names the uncertain inputs (:data:`UNCERTAIN_INPUTS`: the calibration
parameters of :data:`racketdyn.impact.calibration.PARAMETERS` plus the impact's own location
and ball speed) with a distribution each (:class:`Spread`: normal about the nominal value,
uniform over a range, or equally likely values).  :func:`propagate` draws quasi-random samples
of them (:mod:`scipy.stats.qmc`, Sobol' or Latin hypercube, seeded), runs a model at every
sample over the whole grid (the approximate method on all samples at once,
:mod:`racketdyn.impact.samples`; the transient model once per sample, on an executor if
given), and returns an :class:`UncertainResult`: every sample's numbers,
the nominal result, and per impact the mean, standard deviation and the 5 % and 95 %
quantiles of :data:`BAND_QUANTITIES`.

Location and ball speed are offsets from each impact's nominal value (a ball cannon's scatter),
the same offset for every point and speed of one sample; the model parameters are absolute
values (``range = [0.80, 0.88]`` for e_BG).  A sample whose location the scatter puts onto
the frame (:data:`~racketdyn.impact.result.STATUS_FRAME_CONTACT`) is a frame shot: an outcome,
not a failure of the method — a lab keeps only the string impacts and says how many hit the
frame — so the band is over the samples that hit the strings and
:attr:`UncertainResult.frame_shot_share` says how many did not; where more than
:data:`MAX_FRAME_SHOT_SHARE` of them hit the frame the band is NaN (it would describe another
point).  A string impact the model cannot give (any other status than ``ok``) is left out of
that impact's statistics; where fewer than :data:`MIN_VALID_SHARE` of the string impacts are
valid the band is NaN (the method cannot give it) and :attr:`UncertainResult.valid_share` says
so.
"""

from __future__ import annotations

import logging
import math
import warnings
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import Executor, as_completed
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, replace
from functools import partial
from typing import TYPE_CHECKING, Any, Literal, TypeVar, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn._grammar import unit_of
from racketdyn.errors import InputError, one_of, require_words
from racketdyn.impact.approximate import STATUSES, predict
from racketdyn.impact.calibration import PARAMETERS
from racketdyn.impact.grid import status_warnings_held
from racketdyn.impact.hand import Hand
from racketdyn.impact.measured import Method, ModelInputs, predict_rows
from racketdyn.impact.result import (
    IMPACT_QUANTITIES,
    STATUS_FRAME_CONTACT,
    STATUS_OK,
    ImpactResult,
)
from racketdyn.impact.samples import predict_samples
from racketdyn.impact.swing import SwingResult, predict_swing
from racketdyn.io.measured import MeasuredRebound
from racketdyn.racket import as_locations

if TYPE_CHECKING:  # imported where used: scipy.stats and xarray cost ≈ 0.5 s a run without them
    import xarray as xr
    from scipy.stats import qmc

__all__ = [
    "BAND_QUANTITIES",
    "IMPACT_INPUTS",
    "MAX_FRAME_SHOT_SHARE",
    "MAX_SAMPLES",
    "MIN_VALID_SHARE",
    "QUANTILES",
    "SAMPLERS",
    "SENSITIVITY_OUTPUTS",
    "UNCERTAIN_INPUTS",
    "RowBands",
    "Sensitivity",
    "Spread",
    "UncertainResult",
    "Uncertainty",
    "propagate",
    "propagate_rows",
    "sensitivity",
]

log = logging.getLogger(__name__)
_approximate_log = "racketdyn.impact.approximate"
_transient_log = "racketdyn.impact.transient"

Sampler = Literal["sobol", "lhs"]
SAMPLERS: tuple[str, ...] = get_args(Sampler)
"""Quasi-Monte Carlo designs: ``sobol`` (scrambled Sobol', best in powers of two) or ``lhs``
(Latin hypercube)."""

IMPACT_INPUTS: dict[str, str] = {
    "location_m": "impact-location scatter, m, each direction (x and y apart): an offset",
    "ball_speed_mps": "ball-speed scatter, m/s: an offset on every nominal speed",
}
"""Uncertain inputs of the impact itself (offsets from the nominal impact)."""

UNCERTAIN_INPUTS: tuple[str, ...] = (*PARAMETERS, *IMPACT_INPUTS)
"""Every name an uncertainty file may hold."""

BAND_QUANTITIES: tuple[str, ...] = (
    "contact_time",
    "peak_force",
    "vibration_energy",
    "rebound_ratio",
    "rebound_speed",
)
"""The :class:`~racketdyn.impact.result.ImpactResult` attributes given with their bands."""

QUANTILES: tuple[float, ...] = (0.05, 0.95)
"""The band: 5 % and 95 % quantiles (a 90 % band)."""

MAX_SAMPLES = 65_536
"""Most samples an uncertainty takes: every sample's numbers are kept (for ``uncertainty.nc``),
5 quantities × 8 bytes per impact and sample."""

ROUGH_SAMPLES = 64
"""Fewer samples than this give 5 % and 95 % quantiles too rough to quote: said in the log."""

MIN_VALID_SHARE = 0.9
"""Share of an impact's string impacts (samples not on the frame) that must be valid for its
band to be given: fewer, and the band would describe only the samples that happened to stay
within the method."""

MAX_FRAME_SHOT_SHARE = 0.5
"""Largest share of an impact's samples that may hit the frame for its band to be given: where
most shots aimed at a point hit the frame, the few string impacts describe another point."""


@dataclass(frozen=True)
class Spread:
    """One uncertain input and its distribution: exactly one of ``sd``, ``bounds``, ``values``.

    Parameters
    ----------
    name : str
        One of :data:`UNCERTAIN_INPUTS`.
    sd : float, optional
        Standard deviation of a normal distribution about the nominal value (≥ 0).
    bounds : (float, float), optional
        ``(low, high)`` of a uniform distribution (``range`` in the file).
    values : tuple of float
        Equally likely values.
    """

    name: str
    sd: float | None = None
    bounds: tuple[float, float] | None = None
    values: tuple[float, ...] = ()

    def __post_init__(self) -> None:
        if self.name not in UNCERTAIN_INPUTS:
            raise InputError(
                f"uncertainty [{self.name}]: not an uncertain input; choose from "
                f"{', '.join(UNCERTAIN_INPUTS)}"
            )
        given = [self.sd is not None, self.bounds is not None, bool(self.values)]
        if sum(given) != 1:
            raise InputError(
                f"uncertainty [{self.name}]: give exactly one of sd = x, range = [low, high] "
                "or values = [...]"
            )
        if self.sd is not None and not (math.isfinite(self.sd) and self.sd >= 0.0):
            raise InputError(f"uncertainty [{self.name}]: sd must be 0 or more, not {self.sd}")
        if self.bounds is not None:
            low, high = self.bounds
            if not (math.isfinite(low) and math.isfinite(high) and low <= high):
                raise InputError(
                    f"uncertainty [{self.name}]: range must be [low, high] with low ≤ high, "
                    f"not [{low}, {high}]"
                )
        if self.values and not all(math.isfinite(v) for v in self.values):
            raise InputError(f"uncertainty [{self.name}]: values must be finite")

    @property
    def is_offset(self) -> bool:
        """True for the impact's own inputs, drawn as offsets from the nominal impact."""
        return self.name in IMPACT_INPUTS

    @property
    def dimensions(self) -> int:
        """Sample dimensions it takes: two for the location (x and y), else one."""
        return 2 if self.name == "location_m" else 1

    @property
    def pinned(self) -> bool:
        """True when the distribution is one value."""
        if self.sd is not None:
            return self.sd == 0.0
        if self.bounds is not None:
            return self.bounds[0] == self.bounds[1]
        return len(set(self.values)) == 1

    def draw(self, unit: NDArray[np.float64], nominal: float) -> NDArray[np.float64]:
        """Values from uniform ``unit`` samples in [0, 1) (inverse distribution function).

        A normal spread is centred on ``nominal`` (0 for an offset); a range and values are
        taken as given.
        """
        centre = 0.0 if self.is_offset else nominal
        if self.sd is not None:
            from scipy.stats import norm

            u = np.clip(unit, 1e-12, 1.0 - 1e-12)
            return np.asarray(centre + self.sd * norm.ppf(u))
        if self.bounds is not None:
            low, high = self.bounds
            return np.asarray(low + (high - low) * unit)
        table = np.asarray(self.values, dtype=float)
        index = np.minimum((unit * table.size).astype(int), table.size - 1)
        return np.asarray(table[index])

    def describe(self) -> str:
        """The distribution in words, for run records and the report."""
        unit = unit_of(self.name)
        units = f" {unit}" if unit else ""  # e_bg and the scales are dimensionless
        offset = " (offset)" if self.is_offset else ""
        if self.sd is not None:
            return f"normal, sd {self.sd:g}{units}{offset}"
        if self.bounds is not None:
            return f"uniform {self.bounds[0]:g} to {self.bounds[1]:g}{units}{offset}"
        return "equally likely " + ", ".join(f"{v:g}" for v in self.values) + units


@dataclass(frozen=True)
class Uncertainty:
    """The uncertain inputs and how they are sampled.

    Parameters
    ----------
    spreads : tuple of Spread
        One per uncertain input, each name once.
    samples : int
        Number of samples (default 256; Sobol' is balanced at powers of two).
    seed : int
        Seed of the scrambled design: the same seed, the same samples.
    sampler : {"sobol", "lhs"}
        Quasi-Monte Carlo design.
    """

    spreads: tuple[Spread, ...]
    samples: int = 256
    seed: int = 0
    sampler: Sampler = "sobol"

    def __post_init__(self) -> None:
        names = [s.name for s in self.spreads]
        if len(set(names)) != len(names):
            raise InputError("uncertainty: name each input once")
        if not self.spreads:
            raise InputError("uncertainty: give at least one uncertain input")
        if isinstance(self.samples, bool) or not isinstance(self.samples, int):
            raise InputError(f"`samples` must be a whole number, not {self.samples!r}")
        if not 2 <= self.samples <= MAX_SAMPLES:
            raise InputError(
                f"`samples` must be 2 to {MAX_SAMPLES:,}, not {self.samples} (every sample's "
                "numbers are kept: 65,536 samples of the default grid take ≈ 1 GB)"
            )
        if isinstance(self.seed, bool) or not isinstance(self.seed, int) or self.seed < 0:
            raise InputError(f"`seed` must be a whole number ≥ 0, not {self.seed!r}")
        one_of("sampler", self.sampler, SAMPLERS)

    def unit_samples(self) -> NDArray[np.float64]:
        """``(samples, dimensions)`` quasi-random points in the unit cube, seeded."""
        from scipy.stats import qmc

        d = sum(s.dimensions for s in self.spreads)
        engine: qmc.QMCEngine = (
            qmc.Sobol(d, scramble=True, seed=self.seed)
            if self.sampler == "sobol"
            else qmc.LatinHypercube(d, seed=self.seed)
        )
        with warnings.catch_warnings():
            # Sobol' points lose their balance off powers of two: said in the docs, not on
            # every call
            warnings.filterwarnings("ignore", "The balance properties", UserWarning)
            return np.asarray(engine.random(self.samples))

    def record(self) -> dict[str, Any]:
        """What was sampled, for run.json."""
        return {
            "samples": self.samples,
            "seed": self.seed,
            "sampler": self.sampler,
            "inputs": {s.name: s.describe() for s in self.spreads},
            "band": f"{QUANTILES[0]:.0%}–{QUANTILES[1]:.0%} quantiles",
            "min_valid_share": MIN_VALID_SHARE,
        }


@dataclass(frozen=True)
class Draws:
    """The drawn values: model parameters (absolute) and impact offsets, one row a sample."""

    parameters: dict[str, NDArray[np.float64]]
    location_offset: NDArray[np.float64]
    speed_offset: NDArray[np.float64]

    def part(self, index: NDArray[np.intp]) -> Draws:
        """The draws of the samples at ``index``."""
        return Draws(
            {name: values[index] for name, values in self.parameters.items()},
            self.location_offset[index],
            self.speed_offset[index],
        )

    def inputs_table(self) -> dict[str, NDArray[np.float64]]:
        """Every drawn column by name (location as x and y)."""
        table = dict(self.parameters)
        table["location_x_offset_m"] = self.location_offset[:, 0]
        table["location_y_offset_m"] = self.location_offset[:, 1]
        table["ball_speed_offset_mps"] = self.speed_offset
        return table


def draw(uncertainty: Uncertainty, inputs: ModelInputs) -> Draws:
    """The samples of every uncertain input (model parameters about ``inputs``' values)."""
    unit = uncertainty.unit_samples()
    n = unit.shape[0]
    parameters: dict[str, NDArray[np.float64]] = {}
    location = np.zeros((n, 2))
    speed = np.zeros(n)
    column = 0
    for spread in uncertainty.spreads:
        block = unit[:, column : column + spread.dimensions]
        column += spread.dimensions
        if spread.name == "location_m":
            location = np.column_stack([spread.draw(block[:, k], 0.0) for k in range(2)])
        elif spread.name == "ball_speed_mps":
            speed = spread.draw(block[:, 0], 0.0)
        else:
            nominal = PARAMETERS[spread.name].get(inputs)
            parameters[spread.name] = spread.draw(block[:, 0], nominal)
    return Draws(parameters, location, speed)


@dataclass(frozen=True)
class UncertainResult:
    """Every sample's impacts, the nominal impact and the bands.

    Attributes
    ----------
    nominal : ImpactResult or SwingResult
        The impacts at the nominal inputs (a swing's with a ``swing`` option).
    samples : dict
        :data:`BAND_QUANTITIES` attribute → ``(n_samples, n_points, n_speeds, n_supports)``
        (NaN where that sample's impact is not valid).
    valid : ndarray of bool
        ``(n_samples, n_points, n_speeds, n_supports)``: the sample's status is ``ok``.
    frame_shot : ndarray of bool
        The same shape: the sample's location is on the frame (a frame shot: an outcome, left
        out of the band, counted by :attr:`frame_shot_share`).
    draws : Draws
        The drawn inputs.
    uncertainty : Uncertainty
        What was sampled.
    method : str
        ``approx`` or ``transient``.
    """

    nominal: ImpactResult | SwingResult
    samples: dict[str, NDArray[np.float64]]
    valid: NDArray[np.bool_]
    frame_shot: NDArray[np.bool_]
    draws: Draws
    uncertainty: Uncertainty
    method: str

    @property
    def frame_shot_share(self) -> NDArray[np.float64]:
        """``(n_points, n_speeds, n_supports)`` share of samples that hit the frame."""
        return np.asarray(self.frame_shot.mean(axis=0))

    @property
    def valid_share(self) -> NDArray[np.float64]:
        """``(n_points, n_speeds, n_supports)`` share of the string impacts (samples not on
        the frame) the method could give; 0 where every sample hit the frame."""
        strings = np.sum(~self.frame_shot, axis=0)
        return np.asarray(np.sum(self.valid, axis=0) / np.maximum(strings, 1))

    def _given(self) -> NDArray[np.bool_]:
        return np.asarray(
            (self.valid_share >= MIN_VALID_SHARE) & (self.frame_shot_share <= MAX_FRAME_SHOT_SHARE)
        )

    def band_note(self, *at: int) -> str:
        """Why the impact at ``at`` (point, speed, support) has no band; "" where it has."""
        if self.frame_shot_share[at] > MAX_FRAME_SHOT_SHARE:
            return f"{self.frame_shot_share[at]:.0%} of the shots aimed here hit the frame"
        if self.valid_share[at] < MIN_VALID_SHARE:
            return (
                f"{self.valid_share[at]:.0%} of the string impacts within the method "
                f"(under {MIN_VALID_SHARE:.0%})"
            )
        return ""

    def quantile(self, attribute: str, q: float) -> NDArray[np.float64]:
        """``q`` quantile of a quantity over the valid samples, per impact (NaN where the band
        is not given)."""
        values = self.samples[attribute]
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", "All-NaN slice", RuntimeWarning)
            out = np.nanquantile(values, q, axis=0)
        return np.asarray(np.where(self._given(), out, np.nan))

    def mean(self, attribute: str) -> NDArray[np.float64]:
        """Mean over the valid samples, per impact (NaN where the band is not given)."""
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", "Mean of empty slice", RuntimeWarning)
            out = np.nanmean(self.samples[attribute], axis=0)
        return np.asarray(np.where(self._given(), out, np.nan))

    def sd(self, attribute: str) -> NDArray[np.float64]:
        """Standard deviation over the valid samples (n − 1), per impact."""
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", "Degrees of freedom", RuntimeWarning)
            out = np.nanstd(self.samples[attribute], axis=0, ddof=1)
        return np.asarray(np.where(self._given(), out, np.nan))

    def band_columns(self) -> dict[str, NDArray[np.float64]]:
        """Per impact, ``<column>_mean``, ``_sd``, ``_p05``, ``_p95`` for every band quantity
        (columns named after :data:`~racketdyn.impact.result.IMPACT_QUANTITIES`), plus
        ``samples_valid`` (:attr:`valid_share`) and ``frame_shot_share``; each
        ``(n_points, n_speeds, n_supports)``."""
        names = {q.attribute: q.name for q in IMPACT_QUANTITIES}
        columns: dict[str, NDArray[np.float64]] = {}
        for attribute in BAND_QUANTITIES:
            name = names[attribute]
            columns[f"{name}_mean"] = self.mean(attribute)
            columns[f"{name}_sd"] = self.sd(attribute)
            for q in QUANTILES:
                columns[f"{name}_p{round(100 * q):02d}"] = self.quantile(attribute, q)
        columns["samples_valid"] = self.valid_share
        columns["frame_shot_share"] = self.frame_shot_share
        return columns

    def to_xarray(self) -> xr.Dataset:
        """The nominal dataset with the bands as ``<name>_mean/_sd/_p05/_p95`` variables and
        every sample's value on a ``sample`` dimension (``<name>_samples``)."""
        import xarray as xr

        dims = ("point", "ball_speed", "support")
        nominal = self.nominal
        if isinstance(nominal, ImpactResult):
            data = nominal.to_xarray()
        else:  # a swing's: its columns on the same dimensions
            data = xr.Dataset(
                {
                    q.name: (dims, getattr(nominal, q.attribute), {"units": q.units})
                    for q in IMPACT_QUANTITIES
                    if np.ndim(getattr(nominal, q.attribute)) == 3
                },
                coords={
                    "x_m": ("point", nominal.locations[:, 0]),
                    "y_m": ("point", nominal.locations[:, 1]),
                    "ball_speed_mps": ("ball_speed", nominal.ball_speed),
                    "support": ("support", list(nominal.supports)),
                },
            )
        units = {q.attribute: (q.name, q.units) for q in IMPACT_QUANTITIES}
        for name, values in self.band_columns().items():
            base = name.rsplit("_", 1)[0]
            unit = next((u for n, u in units.values() if n == base), "1")
            data[name] = (dims, values, {"units": unit})  # "1" for the shares
        for attribute in BAND_QUANTITIES:
            name, unit = units[attribute]
            data[f"{name}_samples"] = (("sample", *dims), self.samples[attribute], {"units": unit})
        for column, values in self.draws.inputs_table().items():
            data[f"drawn_{column}"] = (("sample",), values)
        data.attrs["uncertainty"] = str(self.uncertainty.record())
        data.attrs["uncertainty_method"] = self.method
        return data


def _inside(racket_head: Any, xy: NDArray[np.float64]) -> NDArray[np.float64]:
    """Points scattered off the bed put back on its edge (where they are frame shots)."""
    rho = racket_head.normalised_radius(xy)
    scale = np.where(rho > 1.0 - 1e-9, (1.0 - 1e-9) / np.maximum(rho, 1e-300), 1.0)
    centre = np.array([racket_head.centre_x_m, racket_head.centre_y_m])
    return np.asarray(centre + (xy - centre) * scale[:, None])


def _sample_inputs(inputs: ModelInputs, draws: Draws, k: int) -> ModelInputs:
    for name, values in draws.parameters.items():
        inputs = PARAMETERS[name].set(inputs, float(values[k]))
    return inputs


def _run(
    method: Method,
    inputs: ModelInputs,
    locations: NDArray[np.float64],
    speeds: NDArray[np.float64],
    options: dict[str, Any],
) -> ImpactResult | SwingResult:
    common = {
        "modal_model": inputs.modes(),
        "law": None if inputs.string_bed == "local" else inputs.law(),
        "string_bed": inputs.string_bed,
        "include_string_bed": inputs.include_string_bed,
        **options,
    }
    swing = common.pop("swing", None)
    if swing is not None:  # each point at its own racket speed, Ω (x + d)
        common.pop("racket_speed", None)
        if method == "transient":
            common["engine"] = inputs.engine
            if "hand" in common["supports"]:
                common["hand"] = inputs.hand or Hand()
        return predict_swing(
            inputs.effective_racket,
            inputs.effective_ball,
            locations,
            speeds,
            swing,
            model="approximate" if method == "approx" else "transient",
            **common,
        )
    if method == "approx":
        return predict(inputs.effective_racket, inputs.effective_ball, locations, speeds, **common)
    from racketdyn.impact.transient import predict_transient  # numba: only where it runs

    hand = (inputs.hand or Hand()) if "hand" in common["supports"] else None
    return predict_transient(
        inputs.effective_racket,
        inputs.effective_ball,
        locations,
        speeds,
        engine=inputs.engine,  # type: ignore[arg-type]
        hand=hand,
        **common,
    )


# 13 parameters: the grid of impacts as predict takes it, and how the samples run; each a
# keyword the workflows and the sweep's tasks pass by name, none of them a group of its own
def propagate(
    inputs: ModelInputs,
    locations: ArrayLike,
    ball_speed: ArrayLike,
    uncertainty: Uncertainty,
    *,
    method: Method = "approx",
    supports: str | Sequence[str] = ("free",),
    racket_speed: ArrayLike = 0.0,
    labels: Sequence[str] | None = None,
    options: dict[str, Any] | None = None,
    progress: Callable[[int, int], None] | None = None,
    vectorised: bool = True,
    executor: Executor | None = None,
    nominal: ImpactResult | SwingResult | None = None,
) -> UncertainResult:
    """Carry the uncertain inputs through a model to every impact of a grid.

    Parameters
    ----------
    inputs : ModelInputs
        The nominal racket, ball, hand, modes and scales.
    locations : array_like, shape (n, 2)
        Nominal impact points (x, y), m.
    ball_speed : array_like
        Nominal ball speeds, m/s.
    uncertainty : Uncertainty
        The uncertain inputs and the sampling.
    method : {"approx", "transient"}
        The approximate method (eqs 1–12) or the transient simulation.
    supports : str or sequence of str
        Supports, as the model takes them (one text of comma-separated names too).
    racket_speed : array_like
        Racket speed at the impact point, one or one per ball speed, m/s.
    labels : sequence of str, optional
        Point labels.
    options : dict, optional
        More keyword arguments of the model (e.g. the approximate method's
        ``stiffness_reading``); ``swing`` (a :class:`~racketdyn.impact.swing.Swing`) runs
        :func:`~racketdyn.impact.swing.predict_swing`, each point at its own racket speed.
    progress : callable, optional
        ``progress(done, total)`` after each sample (the approximate method: after each chunk
        of samples).
    vectorised : bool
        Run the approximate method on every sample at once
        (:func:`racketdyn.impact.samples.predict_samples`: the same numbers to round-off,
        ≈ 30 times faster) where it can (a ``uniform`` string bed, no ``swing``); False runs
        it once per sample, as the transient model always is.
    executor : concurrent.futures.Executor, optional
        Where the samples run when the model runs once per sample (the transient model): in
        tasks of :data:`SAMPLES_PER_TASK` (a sweep's process pool,
        :func:`racketdyn.sweep.executors.make_executor`); by default this process.
    nominal : ImpactResult or SwingResult, optional
        The impacts at the nominal inputs when the caller has them already (a sweep's task
        computes them as it would without an uncertainty): not run again.

    Returns
    -------
    UncertainResult
    """
    xy = as_locations(locations, "impact points")
    speeds = np.atleast_1d(np.asarray(ball_speed, dtype=float))
    _warn_if_rough(uncertainty.samples)
    model_options: dict[str, Any] = {
        "supports": require_words("supports", supports),
        "racket_speed": racket_speed,
        "labels": labels,
        **(options or {}),
    }
    if nominal is None:
        nominal = _run(method, inputs, xy, speeds, model_options)
    draws = draw(uncertainty, inputs)
    runs = _Runs(method, inputs, draws, xy, speeds, model_options)
    with _statuses_held():
        samples, valid, frame = _sampler(runs, vectorised, executor)(runs, progress)
    log.info("uncertainty: %d samples by the %s model", uncertainty.samples, method)
    _log_left_out(valid, frame, method)
    return UncertainResult(
        nominal=nominal,
        samples=samples,
        valid=valid,
        frame_shot=frame,
        draws=draws,
        uncertainty=uncertainty,
        method=method,
    )


def _warn_if_rough(samples: int) -> None:
    """Warn that fewer than :data:`ROUGH_SAMPLES` samples give a rough band."""
    if samples < ROUGH_SAMPLES:
        log.warning(
            "uncertainty: %d samples give a rough 90 %% band (its 5 %% and 95 %% quantiles "
            "rest on a sample or two); %d or more for numbers to quote",
            samples, ROUGH_SAMPLES,
        )  # fmt: skip


def _sampler(
    runs: _Runs, vectorised: bool, executor: Executor | None
) -> Callable[[_Runs, Callable[[int, int], None] | None], Samples]:
    """How :func:`propagate` runs the samples: all at once (the approximate method where it
    batches), on the executor, or one by one here."""
    if vectorised and runs.method == "approx" and _batches(runs.inputs, runs.options):
        return _all_samples
    if executor is not None:
        return partial(_on_executor, executor)
    return _each_sample


def _log_left_out(valid: NDArray[np.bool_], frame: NDArray[np.bool_], method: str) -> None:
    """Say how many sampled impacts hit the frame and how many are beyond the model."""
    shots = int(np.count_nonzero(frame))
    beyond = int(np.count_nonzero(~valid & ~frame))
    if shots:
        log.info(
            "uncertainty: %d of %d sampled impacts hit the frame (frame shots: left out of "
            "their bands and counted in frame_shot_share; a band with over %.0f %% of them is "
            "NaN)",
            shots, valid.size, 100 * MAX_FRAME_SHOT_SHARE,
        )  # fmt: skip
    if beyond:
        log.warning(
            "uncertainty: %d of %d sampled string impacts are beyond the %s model (left out "
            "of their bands; a band with under %.0f %% of its string impacts valid is NaN)",
            beyond, valid.size - shots, method, 100 * MIN_VALID_SHARE,
        )  # fmt: skip


@contextmanager
def _statuses_held() -> Iterator[None]:
    """The impact models' per-call status warnings held (the caller sums them)."""
    with ExitStack() as stack:
        for name in (_approximate_log, _transient_log):
            stack.enter_context(status_warnings_held(name))
        yield


T = TypeVar("T")

SAMPLES_PER_TASK = 4
"""Samples in one task of an executor (:func:`propagate`'s ``executor``)."""

Samples = tuple[dict[str, NDArray[np.float64]], NDArray[np.bool_], NDArray[np.bool_]]
"""Every sample's band quantities (NaN where not valid), where each is valid and where each is
a frame shot."""

_BATCHED_OPTIONS = {"supports", "racket_speed", "labels", "stiffness_reading", "vibration_charge"}


def _batches(inputs: ModelInputs, options: dict[str, Any]) -> bool:
    """Whether :func:`racketdyn.impact.samples.predict_samples` takes these runs: one law over
    the face and no option beyond the grid's, eq (10)'s reading and the vibration charge."""
    return inputs.string_bed == "uniform" and set(options) <= _BATCHED_OPTIONS


@dataclass(frozen=True)
class _Runs:
    """What the samples run: the model, the nominal inputs, the draws and the grid."""

    method: Method
    inputs: ModelInputs
    draws: Draws
    xy: NDArray[np.float64]
    speeds: NDArray[np.float64]
    options: dict[str, Any]

    @property
    def n(self) -> int:
        """Samples."""
        return int(self.draws.speed_offset.size)

    def part(self, index: NDArray[np.intp]) -> _Runs:
        """The runs of the samples at ``index``."""
        return replace(self, draws=self.draws.part(index))

    def empty(self) -> Samples:
        """NaN band quantities, no valid sample and no frame shot,
        ``(n, n_points, n_speeds, n_supports)``."""
        shape = (self.n, self.xy.shape[0], self.speeds.size, len(self.options["supports"]))
        nothing = np.zeros(shape, dtype=bool)
        return {a: np.full(shape, np.nan) for a in BAND_QUANTITIES}, nothing, nothing.copy()


def _each_sample(runs: _Runs, progress: Callable[[int, int], None] | None) -> Samples:
    """The model once per sample."""
    method, inputs, draws, xy, speeds, options = (
        runs.method, runs.inputs, runs.draws, runs.xy, runs.speeds, runs.options,
    )  # fmt: skip
    n = runs.n
    samples, valid, frame = runs.empty()
    for k in range(n):
        sample = _sample_inputs(inputs, draws, k)
        where = _inside(inputs.racket.head, xy + draws.location_offset[k])
        v = speeds + draws.speed_offset[k]
        result = _run(method, sample, where, np.maximum(v, 0.1), options)
        ok = np.asarray(result.status) == STATUS_OK
        ok[:, v + _racket_speeds(options, speeds) <= 0.0, :] = False  # no impact
        valid[k] = ok
        frame[k] = np.asarray(result.status) == STATUS_FRAME_CONTACT
        for attribute in BAND_QUANTITIES:
            samples[attribute][k] = np.where(ok, getattr(result, attribute), np.nan)
        if progress is not None:
            progress(k + 1, n)
    return samples, valid, frame


def _samples_task(runs: _Runs, draws: Draws) -> Samples:
    """Some samples (``draws``) once each, in a worker process (status warnings held)."""
    with _statuses_held():
        return _each_sample(replace(runs, draws=draws), None)


def _on_executor(
    executor: Executor, runs: _Runs, progress: Callable[[int, int], None] | None
) -> Samples:
    """:func:`_each_sample` in tasks of :data:`SAMPLES_PER_TASK` samples on an executor."""
    samples, valid, frame = runs.empty()
    task = partial(_samples_task, runs)
    for part, (found, valid[part], frame[part]) in _in_tasks(executor, task, runs.draws, progress):
        for attribute in BAND_QUANTITIES:
            samples[attribute][part] = found[attribute]
    return samples, valid, frame


def _in_tasks(
    executor: Executor,
    task: Callable[[Draws], T],
    draws: Draws,
    progress: Callable[[int, int], None] | None,
) -> Iterator[tuple[NDArray[np.intp], T]]:
    """``task(draws of some samples)`` for every :data:`SAMPLES_PER_TASK` samples on an
    executor: each part's sample indices and result, as they finish."""
    n = draws.speed_offset.size
    parts = np.array_split(np.arange(n), -(-n // SAMPLES_PER_TASK))
    futures = {executor.submit(task, draws.part(part)): part for part in parts}
    done = 0
    for future in as_completed(futures):
        part = futures[future]
        yield part, future.result()
        done += part.size
        if progress is not None:
            progress(done, n)


def _all_samples(runs: _Runs, progress: Callable[[int, int], None] | None) -> Samples:
    """The approximate method on every sample at once (:func:`predict_samples`), the same
    numbers as :func:`_each_sample` to round-off."""
    inputs, draws, xy, speeds, options = (
        runs.inputs, runs.draws, runs.xy, runs.speeds, runs.options,
    )  # fmt: skip
    n = runs.n
    scattered = (xy[None, :, :] + draws.location_offset[:, None, :]).reshape(-1, 2)
    v = speeds[None, :] + draws.speed_offset[:, None]
    impacts = predict_samples(
        inputs,
        draws.parameters,
        _inside(inputs.racket.head, scattered).reshape(n, xy.shape[0], 2),
        np.maximum(v, 0.1),
        supports=options["supports"],
        racket_speed=options["racket_speed"],
        stiffness_reading=options.get("stiffness_reading", "period"),
        vibration_charge=options.get("vibration_charge", "coupled"),
        progress=progress,
    )
    ok = impacts.status_code == 0  # STATUSES[0]: ok
    ok &= (v + _racket_speeds(options, speeds)[None, :] > 0.0)[:, None, :, None]  # an impact
    samples = {a: np.where(ok, getattr(impacts, a), np.nan) for a in BAND_QUANTITIES}
    return samples, ok, impacts.status_code == STATUSES.index(STATUS_FRAME_CONTACT)


def _racket_speeds(options: dict[str, Any], speeds: NDArray[np.float64]) -> NDArray[np.float64]:
    """The racket speed at each ball speed (0 for a swing's, whose racket moves forward)."""
    if "swing" in options:
        return np.zeros(speeds.shape)
    return np.broadcast_to(np.asarray(options.get("racket_speed", 0.0), dtype=float), speeds.shape)


def widened(uncertainty: Uncertainty, name: str, factor: float) -> Uncertainty:
    """The same uncertainty with one input's spread scaled by ``factor`` about its centre."""
    spreads = []
    for s in uncertainty.spreads:
        if s.name == name:
            if s.sd is not None:
                s = replace(s, sd=s.sd * factor)
            elif s.bounds is not None:
                mid, half = 0.5 * (s.bounds[0] + s.bounds[1]), 0.5 * (s.bounds[1] - s.bounds[0])
                s = replace(s, bounds=(mid - factor * half, mid + factor * half))
        spreads.append(s)
    return replace(uncertainty, spreads=tuple(spreads))


SENSITIVITY_OUTPUTS: tuple[str, ...] = ("rebound_ratio", "contact_time", "vibration_energy")
"""The quantities whose Sobol' indices :func:`sensitivity` gives."""


@dataclass(frozen=True)
class _Marginal:
    """One input's distribution as :func:`scipy.stats.sobol_indices` takes it (a ``ppf``)."""

    spread: Spread
    nominal: float

    def ppf(self, unit: NDArray[np.float64]) -> NDArray[np.float64]:
        return self.spread.draw(np.asarray(unit, dtype=float), self.nominal)


@dataclass(frozen=True)
class Sensitivity:
    """Sobol' first-order and total indices of each output to each uncertain input.

    Attributes
    ----------
    labels : tuple of str
        The points (``centre``, ``tip``, …).
    locations : ndarray
        ``(n_points, 2)`` the points, m.
    inputs : tuple of str
        The uncertain inputs (the location as ``location_m x`` and ``location_m y``).
    first_order, total_order : ndarray
        ``(n_outputs, n_points, n_inputs)``, on the base samples whose every evaluation is
        valid; NaN at a point where fewer than :data:`MIN_VALID_SHARE` of them are.
    ball_speed : float
        Ball speed, m/s.
    support : str
        The support.
    evaluations : int
        Model runs it took (``n (d + 2)``).
    valid_share : ndarray
        ``(n_points,)`` share of the base samples the indices at each point rest on.
    first_order_ci, total_order_ci : ndarray, optional
        ``(2, n_outputs, n_points, n_inputs)``: each index's 90 % confidence interval (low,
        high) from its base samples (:data:`SENSITIVITY_BOOTSTRAP`); an index whose interval
        holds 0 is not told from none, one whose intervals overlap another's not told from
        it.
    frame_share : ndarray, optional
        ``(n_points,)`` share of the base samples with a frame shot among their runs.
    outputs : tuple of str
        The outputs along the indices' first axis (:data:`SENSITIVITY_OUTPUTS`).
    """

    labels: tuple[str, ...]
    locations: NDArray[np.float64]
    inputs: tuple[str, ...]
    first_order: NDArray[np.float64]
    total_order: NDArray[np.float64]
    ball_speed: float
    support: str
    evaluations: int
    valid_share: NDArray[np.float64]
    first_order_ci: NDArray[np.float64] | None = None
    total_order_ci: NDArray[np.float64] | None = None
    frame_share: NDArray[np.float64] | None = None
    outputs: tuple[str, ...] = SENSITIVITY_OUTPUTS

    def why_none(self, point: int) -> str:
        """Why a point has no indices: its base samples' frame shots, or runs beyond the
        method ("" where it has them)."""
        if self.valid_share[point] >= MIN_VALID_SHARE:
            return ""
        shots = 0.0 if self.frame_share is None else float(self.frame_share[point])
        if shots > 1.0 - MIN_VALID_SHARE:
            return f"{shots:.0%} of its base samples scatter a shot onto the frame"
        return "samples beyond the method"

    def dominant(self, point: int, output: str = "rebound_ratio") -> str:
        """The input with the largest total index at a point ("" when not known)."""
        total = self.total_order[self.outputs.index(output), point]
        if not np.all(np.isfinite(total)):
            return ""
        return self.inputs[int(np.argmax(total))]

    def rivals(self, point: int, output: str = "rebound_ratio") -> tuple[str, ...]:
        """The inputs :meth:`dominant`'s total index is not told from: their 90 % intervals
        reach into its interval (none without intervals)."""
        if self.total_order_ci is None or not self.dominant(point, output):
            return ()
        o = self.outputs.index(output)
        top = int(np.argmax(self.total_order[o, point]))
        low = self.total_order_ci[0, o, point, top]
        high = self.total_order_ci[1, o, point]
        return tuple(name for i, name in enumerate(self.inputs) if i != top and high[i] >= low)

    def rows(self) -> dict[str, list[Any]]:
        """``sensitivity.csv``: one row per point × output × input."""
        table: dict[str, list[Any]] = {
            key: []
            for key in (
                "point", "x_m", "y_m", "ball_speed_mps", "support", "output", "input",
                "first_order", "first_order_p05", "first_order_p95",
                "total_order", "total_order_p05", "total_order_p95", "samples_valid",
                "samples_frame_shot", "dominant", "not_told_from_dominant", "note",
            )
        }  # fmt: skip
        blank = np.full((2, *self.first_order.shape), np.nan)
        first_ci = blank if self.first_order_ci is None else self.first_order_ci
        total_ci = blank if self.total_order_ci is None else self.total_order_ci
        for o, output in enumerate(self.outputs):
            for p, label in enumerate(self.labels):
                top, rivals = self.dominant(p, output), self.rivals(p, output)
                for i, name in enumerate(self.inputs):
                    at = (o, p, i)
                    values = (
                        label, self.locations[p, 0], self.locations[p, 1], self.ball_speed,
                        self.support, output, name,
                        self.first_order[at], first_ci[(0, *at)], first_ci[(1, *at)],
                        self.total_order[at], total_ci[(0, *at)], total_ci[(1, *at)],
                        self.valid_share[p],
                        np.nan if self.frame_share is None else self.frame_share[p],
                        name == top, name in rivals, self.why_none(p),
                    )  # fmt: skip
                    for key, value in zip(table, values, strict=True):
                        table[key].append(value)
        return table


def sensitivity(
    inputs: ModelInputs,
    points: dict[str, tuple[float, float]],
    ball_speed: float,
    uncertainty: Uncertainty,
    *,
    support: str = "free",
    racket_speed: float = 0.0,
    n: int = 64,
    method: Method = "approx",
    options: dict[str, Any] | None = None,
    executor: Executor | None = None,
) -> Sensitivity:
    """Which input dominates: Sobol' first-order and total indices at named points.

    Saltelli 2010's estimators on a scrambled Sobol' design, seeded with the uncertainty's
    seed, as :func:`scipy.stats.sobol_indices` draws and computes them; ``n (d + 2)`` model
    runs for ``d`` inputs (the location counts twice: x and y), the approximate method's all
    at once (:func:`racketdyn.impact.samples.predict_samples`).  A base sample with any run
    beyond the method (a frame shot, say) is left out of that point's indices; where fewer
    than :data:`MIN_VALID_SHARE` of them are left the point has none (NaN), and
    :attr:`Sensitivity.valid_share` says on how many they rest.

    Parameters
    ----------
    inputs : ModelInputs
        The nominal inputs.
    points : dict
        Label → (x, y), m.
    ball_speed : float
        Ball speed, m/s.
    uncertainty : Uncertainty
        The uncertain inputs.
    support : str
        One support.
    racket_speed : float
        Racket speed at the impact point, m/s.
    n : int
        Base samples, a power of two.
    method : {"approx", "transient"}
        The model.
    options : dict, optional
        More keyword arguments of the model.
    executor : concurrent.futures.Executor, optional
        Where the runs go when the model runs them one by one (the transient model), as for
        :func:`propagate`; by default this process.

    Returns
    -------
    Sensitivity
    """
    if n < 8 or n & (n - 1):
        raise InputError(f"`n` for Sobol' indices must be a power of two ≥ 8, not {n}")
    labels = tuple(points)
    xy = as_locations(list(points.values()), "sensitivity points")
    marginals, names = _marginals(uncertainty, inputs)
    d = len(names)
    # Saltelli's design as scipy.stats.sobol_indices draws it: A, B and A with column i of B
    a, b = _design(n, marginals, np.random.default_rng(uncertainty.seed))
    ab = np.repeat(a[None, :, :], d, axis=0)
    ab[np.arange(d), np.arange(d)] = b
    x = np.concatenate([a, b, *ab], axis=1)  # (d, (d + 2) n)
    model_options = {"supports": [support], "racket_speed": racket_speed, **(options or {})}
    with _statuses_held():
        runs = _Runs(
            method, inputs, _columns_as_draws(names, x), xy, np.array([ball_speed]), model_options
        )
        out, frame = _sensitivity_outputs(runs, executor)
    f = out.reshape(*out.shape[:2], d + 2, n)  # (outputs, points, d + 2, n)
    # a base sample with a frame shot among its d + 2 runs
    frame_share = frame.reshape(frame.shape[0], d + 2, n).any(axis=1).mean(axis=-1)
    first, total, share = _saltelli_2010(f[:, :, 0], f[:, :, 1], np.moveaxis(f[:, :, 2:], 2, 0))
    first_ci, total_ci = _bootstrap_indices(f, uncertainty.seed)
    for label, given in zip(labels, share, strict=True):
        if given < 1.0:
            log.info(
                "sensitivity at %s: %.0f %% of the base samples valid (%s)",
                label, 100 * given,
                "indices on those" if given >= MIN_VALID_SHARE else "no indices",
            )  # fmt: skip
    return Sensitivity(
        labels=labels,
        locations=xy,
        inputs=tuple(names),
        first_order=first,
        total_order=total,
        ball_speed=float(ball_speed),
        support=support,
        evaluations=n * (d + 2),
        valid_share=share,
        frame_share=frame_share,
        first_order_ci=np.where(np.isnan(first)[None], np.nan, first_ci),
        total_order_ci=np.where(np.isnan(total)[None], np.nan, total_ci),
    )


SENSITIVITY_BOOTSTRAP = 499
"""Resamples of the base samples for the indices' 90 % confidence intervals (percentile
bootstrap, :func:`scipy.stats.bootstrap`)."""


def _bootstrap_indices(
    f: NDArray[np.float64], seed: int | None
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """90 % intervals ``(2, n_outputs, n_points, d)`` of the first-order and total indices,
    resampling the base samples j of ``f`` ``(n_outputs, n_points, d + 2, n)`` (A, B and every
    A_B^i of one j together)."""
    from scipy.stats import bootstrap

    columns = tuple(f[:, :, k] for k in range(f.shape[2]))

    def statistic(*arrays: NDArray[np.float64], axis: int = -1) -> NDArray[np.float64]:
        # (n_outputs, n_points, [resamples,] n) each; the indices with the resamples last
        first, total, _ = _saltelli_2010(arrays[0], arrays[1], np.stack(arrays[2:]))
        both = np.stack([first, total])  # (2, n_outputs, n_points, [resamples,] d)
        return both if arrays[0].ndim == 3 else np.moveaxis(both, -2, -1)

    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")  # NaN where a point has no indices; degenerate ones
        found = bootstrap(
            columns,
            statistic,
            paired=True,
            vectorized=True,
            n_resamples=SENSITIVITY_BOOTSTRAP,
            confidence_level=0.9,
            method="percentile",
            random_state=np.random.default_rng(seed),
            axis=-1,
        )
    low, high = found.confidence_interval  # (2, n_outputs, n_points, d) each
    return np.stack([low[0], high[0]]), np.stack([low[1], high[1]])


def _marginals(uncertainty: Uncertainty, inputs: ModelInputs) -> tuple[list[_Marginal], list[str]]:
    """Each sampled dimension's distribution and name (the location as x and y)."""
    marginals: list[_Marginal] = []
    names: list[str] = []
    for spread in uncertainty.spreads:
        if spread.name == "location_m":
            marginals += [_Marginal(spread, 0.0), _Marginal(spread, 0.0)]
            names += ["location_m x", "location_m y"]
        else:
            nominal = 0.0 if spread.is_offset else PARAMETERS[spread.name].get(inputs)
            marginals.append(_Marginal(spread, nominal))
            names.append(spread.name)
    return marginals, names


def _design(
    n: int, marginals: Sequence[_Marginal], rng: np.random.Generator
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Saltelli's matrices A and B, each ``(d, n)``: a scrambled Sobol' design of 2d
    dimensions split in two, through each input's inverse distribution function (as
    :func:`scipy.stats.sobol_indices` draws them)."""
    from scipy.stats import qmc

    d = len(marginals)
    unit = qmc.Sobol(d=2 * d, seed=rng, bits=64).random(n).T.reshape(2, d, -1)
    for i, marginal in enumerate(marginals):
        unit[:, i] = marginal.ppf(unit[:, i])
    return unit[0], unit[1]


def _columns_as_draws(names: Sequence[str], x: NDArray[np.float64]) -> Draws:
    """The columns of ``x`` (one row per name) as the samples of :func:`propagate`."""
    columns = dict(zip(names, x, strict=True))
    zeros = np.zeros(x.shape[1])
    return Draws(
        parameters={k: v for k, v in columns.items() if k in PARAMETERS},
        location_offset=np.column_stack(
            [columns.get("location_m x", zeros), columns.get("location_m y", zeros)]
        ),
        speed_offset=columns.get("ball_speed_mps", zeros),
    )


def _sensitivity_outputs(
    runs: _Runs, executor: Executor | None
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """``(n_outputs, n_points, n_runs)`` the outputs of every run at one speed and support,
    NaN where not valid, and ``(n_points, n_runs)`` where a run is a frame shot."""
    if runs.method == "approx" and _batches(runs.inputs, runs.options):
        samples, _, frame = _all_samples(runs, None)
    elif executor is not None:
        samples, _, frame = _on_executor(executor, runs, None)
    else:
        samples, _, frame = _each_sample(runs, None)
    outputs = np.stack([samples[a][:, :, 0, 0].T for a in SENSITIVITY_OUTPUTS])
    return outputs, np.asarray(frame[:, :, 0, 0].T)


def _saltelli_2010(
    f_a: NDArray[np.float64], f_b: NDArray[np.float64], f_ab: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """First-order and total indices ``(n_outputs, n_points, d)`` and each point's share of
    valid base samples ``(n_points,)``.

    Saltelli et al. 2010's estimators (Table 2 (b) and (f)), as
    :func:`scipy.stats.sobol_indices` computes them, on the base samples j whose ``f_a``,
    ``f_b`` and every ``f_ab[i]`` are valid (finite); NaN where fewer than
    :data:`MIN_VALID_SHARE` are.  ``f_a``, ``f_b``: ``(n_outputs, n_points, …, n)``; ``f_ab``:
    ``(d, n_outputs, n_points, …, n)`` (``…``: the bootstrap's resamples, or nothing).
    """
    ok = np.isfinite(f_a) & np.isfinite(f_b) & np.all(np.isfinite(f_ab), axis=0)
    share = ok.all(axis=0).mean(axis=-1)
    use = ok & (share >= MIN_VALID_SHARE)[None, ..., None]
    count = use.sum(axis=-1)

    def mean(values: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(np.where(use, values, 0.0).sum(axis=-1) / count)

    with np.errstate(divide="ignore", invalid="ignore"):
        centre = (0.5 * (mean(f_a) + mean(f_b)))[..., None]
        a, b, ab = f_a - centre, f_b - centre, f_ab - centre
        variance = 0.5 * (mean(a**2) + mean(b**2))
        first = mean(b * (ab - a)) / variance
        total = 0.5 * mean((a - ab) ** 2) / variance
    given = share >= MIN_VALID_SHARE
    # a null variance means null indices (as scipy's); no indices where too few are valid
    first = np.where(given, np.nan_to_num(first, nan=0.0, posinf=0.0, neginf=0.0), np.nan)
    total = np.where(given, np.nan_to_num(total, nan=0.0, posinf=0.0, neginf=0.0), np.nan)
    return np.moveaxis(first, 0, -1), np.moveaxis(total, 0, -1), share


@dataclass(frozen=True)
class RowBands:
    """The 90 % band of the predicted rebound ratio at each measured row, by one model.

    Attributes
    ----------
    p05, p95 : ndarray
        ``(n_rows,)`` 5 % and 95 % quantiles over the valid samples (NaN where fewer than
        :data:`MIN_VALID_SHARE` of the samples are valid).
    valid_share : ndarray
        ``(n_rows,)`` share of samples the model could give.
    method : str
        ``approx`` or ``transient``.
    """

    p05: NDArray[np.float64]
    p95: NDArray[np.float64]
    valid_share: NDArray[np.float64]
    method: str

    def inside(self, measured: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Rows whose measured value lies in the band (False where there is no band)."""
        with np.errstate(invalid="ignore"):
            return np.asarray((measured >= self.p05) & (measured <= self.p95))

    @property
    def given(self) -> NDArray[np.bool_]:
        """Rows with a band."""
        return np.asarray(np.isfinite(self.p05) & np.isfinite(self.p95))


def propagate_rows(
    inputs: ModelInputs,
    measured: MeasuredRebound,
    uncertainty: Uncertainty,
    method: Method,
    progress: Callable[[int, int], None] | None = None,
    executor: Executor | None = None,
) -> RowBands:
    """The predicted rebound ratio's band at every measured row (``validate``).

    Each sample moves the model parameters, and offsets every row's location and ball speed
    as :func:`propagate` does; :func:`racketdyn.impact.measured.predict_rows` predicts the
    rows.  Where the rows give their measurement's standard deviation
    (``rebound_ratio_sd``), each sample gets a normal draw of it (seeded), so the band is that
    of what is measured, not only of the model's number.

    Parameters
    ----------
    inputs : ModelInputs
        The nominal inputs.
    measured : MeasuredRebound
        The rows.
    uncertainty : Uncertainty
        The uncertain inputs.
    method : {"approx", "transient"}
        The model.
    progress : callable, optional
        ``progress(done, total)`` after each sample.
    executor : concurrent.futures.Executor, optional
        Where the samples run, :data:`SAMPLES_PER_TASK` to a task (a sweep's process pool);
        by default this process.

    Returns
    -------
    RowBands
    """
    draws = draw(uncertainty, inputs)
    n = uncertainty.samples
    task = partial(_rows_task, inputs, measured, method)
    if executor is None:
        values = task(draws, progress)
    else:
        values = np.full((n, len(measured)), np.nan)
        for part, found in _in_tasks(executor, task, draws, progress):
            values[part] = found
    valid = np.isfinite(values)
    share = valid.mean(axis=0)
    if measured.rebound_ratio_sd is not None:
        # the band of what is measured: each sample with the row's own measurement noise
        noise = np.random.default_rng(uncertainty.seed).standard_normal(values.shape)
        values = values + noise * np.nan_to_num(measured.rebound_ratio_sd)[None, :]
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "All-NaN slice", RuntimeWarning)
        low, high = np.nanquantile(values, QUANTILES, axis=0)
    given = share >= MIN_VALID_SHARE
    return RowBands(np.where(given, low, np.nan), np.where(given, high, np.nan), share, str(method))


def _rows_task(
    inputs: ModelInputs,
    measured: MeasuredRebound,
    method: Method,
    draws: Draws,
    progress: Callable[[int, int], None] | None = None,
) -> NDArray[np.float64]:
    """``(n_samples, n_rows)`` every sample's rebound ratio at the rows (NaN where not valid),
    here or in a worker process (status warnings held)."""
    n = draws.speed_offset.size
    values = np.full((n, len(measured)), np.nan)
    head = inputs.racket.head
    with _statuses_held():
        for k in range(n):
            rows = replace(
                measured,
                locations=_inside(head, measured.locations + draws.location_offset[k]),
                ball_speed=np.maximum(measured.ball_speed + draws.speed_offset[k], 0.1),
            )
            values[k], _ = predict_rows(_sample_inputs(inputs, draws, k), rows, method)
            if progress is not None:
                progress(k + 1, n)
    return values
