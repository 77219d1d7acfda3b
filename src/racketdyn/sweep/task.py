"""The task: one design's computation, a pure function of plain picklable data.

:class:`SweepTask` is what an executor ships to a worker; :func:`run_task` builds the design
(:mod:`~racketdyn.sweep.design`), runs an impact method (:data:`METHODS`) and returns a
:class:`TaskOutput`, which :mod:`~racketdyn.sweep.store` writes into a chunk.  The
per-process caches of modal models and contact laws live here.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray
from threadpoolctl import ThreadpoolController  # type: ignore[import-untyped]

from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law
from racketdyn.errors import InputError, one_of
from racketdyn.impact.approximate import StiffnessReading, predict
from racketdyn.impact.grid import StringBed
from racketdyn.impact.result import (
    IMPACT_QUANTITIES,
    STATUS_BEYOND_LAW,
    STATUS_FRAME_CONTACT,
    STATUS_NO_SEPARATION,
    STATUS_OK,
    STATUS_SECOND_CONTACT,
    STATUS_VIBRATION_LOSS,
    STATUS_VIBRATION_SHARE,
    ImpactResult,
    impact_warnings_quiet,
)
from racketdyn.impact.transient import (
    TRANSIENT_SUPPORTS,
    Engine,
    predict_transient,
)
from racketdyn.modal import ModalModel
from racketdyn.racket import SUPPORTS, Racket
from racketdyn.racket_modal import builtin_modal_model
from racketdyn.sweep.design import build_design, build_hand
from racketdyn.sweep.variables import Variable

if TYPE_CHECKING:  # imported when a sweep has an uncertainty: xarray and scipy.stats cost ≈ 1 s
    from racketdyn.impact.measured import ModelInputs
    from racketdyn.impact.uncertainty import UncertainResult, Uncertainty

__all__ = [
    "METHODS",
    "METHOD_SUPPORTS",
    "STATUS_CODES",
    "STATUS_FAILED",
    "SweepTask",
    "TaskOutput",
    "band_variables",
    "run_task",
    "task_inputs",
]

METHOD_SUPPORTS: dict[str, tuple[str, ...]] = {
    "approximate": SUPPORTS,
    "transient": TRANSIENT_SUPPORTS,
}
"""Supports each impact method takes."""

STATUS_FAILED = "task failed"
STATUS_CODES: dict[str, int] = {
    STATUS_OK: 0,
    STATUS_VIBRATION_LOSS: 1,
    STATUS_BEYOND_LAW: 2,
    STATUS_FAILED: 3,
    STATUS_NO_SEPARATION: 4,
    STATUS_SECOND_CONTACT: 5,
    STATUS_VIBRATION_SHARE: 6,
    STATUS_FRAME_CONTACT: 7,
}
"""Integer codes of the ``status`` variable of a sweep dataset (CF ``flag_values``)."""

_IMPACT_VARIABLES: dict[str, tuple[str, str, str]] = {
    # dataset name: (ImpactResult attribute, units, long name)
    "stiffness_n_per_m": ("stiffness", "N m-1", "compound ball+string stiffness K_GB (eqs 9-10)"),
    "contact_time_s": ("contact_time", "s", "contact time T_c (eq 7)"),
    "mean_force_n": ("mean_force", "N", "equivalent force F_MEAN (eqs 8-10)"),
    "peak_force_n": ("peak_force", "N", "peak force F_MAX (the spring's at the turn)"),
    "vibration_energy_j": ("vibration_energy", "J", "frame vibration energy after impact (eq 12)"),
    "cor": ("cor", "1", "ball-racket coefficient of restitution e_r"),
    "rebound_ratio": ("rebound_ratio", "1", "rebound ratio e"),
    "rebound_speed_mps": ("rebound_speed", "m s-1", "outgoing ball speed"),
    "peak_deflection_m": ("peak_deflection", "m", "peak compound deflection X_p"),
}


@dataclass(frozen=True, eq=False)
class SweepTask:
    """Everything one design's computation needs: plain, picklable data.

    Parameters
    ----------
    task_id : str
        The design's task id (part file name).
    racket, ball : Racket, Ball
        The base racket and ball.
    variables : tuple of Variable
        The sweep's variables.
    settings : tuple of (str, float)
        The design's coordinate values.
    locations : ndarray, shape (n, 2)
        Impact points, m.
    ball_speeds, racket_speeds : ndarray
        Speeds, m/s.
    supports : tuple of str
        Support conditions.
    method : str
        Impact method (a key of :data:`METHODS`).
    stiffness_reading : {"period", "tangent"}
        Reading of eq (10).
    include_string_bed : bool
        Charge string-bed modes too.
    string_bed : {"uniform", "local"}
        One law for the face (the centre's) or each point's own.
    rigid : bool
        No modal model.
    engine : {"compiled", "reference"}
        Engine of the transient method (resolved: never ``auto``).
    uncertainty : Uncertainty, optional
        Uncertain inputs: the design's samples run in the task and its bands are returned
        beside the nominal numbers (:func:`band_variables`).
    threshold_fraction : float
        The sweet area's threshold, for its band (with an uncertainty).
    """

    task_id: str
    racket: Racket
    ball: Ball
    variables: tuple[Variable, ...]
    settings: tuple[tuple[str, float], ...]
    locations: NDArray[np.float64]
    ball_speeds: NDArray[np.float64]
    racket_speeds: NDArray[np.float64]
    supports: tuple[str, ...]
    method: str
    stiffness_reading: StiffnessReading
    include_string_bed: bool
    rigid: bool
    engine: Engine = "compiled"
    string_bed: StringBed = "uniform"
    uncertainty: Uncertainty | None = None
    threshold_fraction: float = 0.9


@dataclass(frozen=True, eq=False)
class TaskOutput:
    """The arrays one task returns, shaped ``(n_points, n_speeds, n_racket_speeds, n_supports)``.

    Parameters
    ----------
    task_id : str
        The design's task id.
    arrays : dict of str to ndarray
        The impact quantities named as in the dataset (``contact_time_s`` …) and ``status``
        (int8 codes, :data:`STATUS_CODES`).
    reduced_mass_kg : ndarray, shape (n_points, n_supports)
        Reduced mass at each point, kg.
    mode_names : tuple of str
        Modes charged with vibration (empty for a rigid racket).
    mode_frequency_hz : ndarray
        Their natural frequencies, Hz.
    attempt : int
        Which attempt produced it (1 first, 2 the retry).
    elapsed_s : float
        Time the task took where it ran, s (for the run record).
    write_s : float
        Time its worker took to write it as a part file, s; 0 with ``arrays`` set: the
        coordinating process writes it.
    """

    task_id: str
    arrays: dict[str, NDArray[Any]]
    reduced_mass_kg: NDArray[np.float64]
    mode_names: tuple[str, ...]
    mode_frequency_hz: NDArray[np.float64]
    attempt: int = 1
    elapsed_s: float = 0.0
    write_s: float = 0.0


def _approximate(
    racket: Racket,
    ball: Ball,
    model: ModalModel | None,
    law: RestoringForce | None,
    task: SweepTask,
) -> ImpactResult:
    """Kawazoe's approximate method over points × (ball speed, racket speed) pairs × supports."""
    n_r = task.racket_speeds.size
    return predict(
        racket,
        ball,
        task.locations,
        np.repeat(task.ball_speeds, n_r),
        task.supports,
        np.tile(task.racket_speeds, task.ball_speeds.size),
        modal_model=model,
        law=law,
        include_string_bed=task.include_string_bed,
        stiffness_reading=task.stiffness_reading,
        string_bed=task.string_bed,
    )


def _transient(
    racket: Racket,
    ball: Ball,
    model: ModalModel | None,
    law: RestoringForce | None,
    task: SweepTask,
) -> ImpactResult:
    """The transient simulation over points × (ball speed, racket speed) pairs × supports.

    The ``hand`` support holds the grip with the design's hand (:func:`build_hand`); the
    engine is the spec's (``[impacts].engine``, resolved where the spec was read).
    """
    n_r = task.racket_speeds.size
    hand = build_hand(task.variables, task.settings) if "hand" in task.supports else None
    return predict_transient(
        racket,
        ball,
        task.locations,
        np.repeat(task.ball_speeds, n_r),
        task.supports,
        np.tile(task.racket_speeds, task.ball_speeds.size),
        modal_model=model,
        law=law,
        include_string_bed=task.include_string_bed,
        hand=hand,
        engine=task.engine,
        string_bed=task.string_bed,
    )


ImpactMethod = Callable[
    [Racket, Ball, ModalModel | None, RestoringForce | None, SweepTask], ImpactResult
]
METHODS: dict[str, ImpactMethod] = {"approximate": _approximate, "transient": _transient}
"""Impact methods a sweep can run, by name.  Each takes the design's racket, ball, modal model
(None: rigid), compound law (None with ``string_bed = "local"``: each point's own) and the
task, and returns an :class:`ImpactResult` over points × (ball speed, racket speed) pairs (ball
speed slowest) × supports.  The supports each takes are
in :data:`METHOD_SUPPORTS`."""


def _check_method(where: str, method: object) -> str:
    return one_of(where, method, METHODS)


def _check_supports(where: str, supports: Sequence[object], method: str) -> None:
    """Each support known to the method, each once (InputError naming the key)."""
    allowed = METHOD_SUPPORTS.get(method, SUPPORTS)
    if not supports:
        raise InputError(f"{where}: give one or more of {', '.join(allowed)}")
    for support in supports:
        if support == "hand" and "hand" not in allowed:
            raise InputError(
                f"{where}: 'hand' needs [impacts].method = 'transient'; the {method} method has "
                "no hand (its hand-held racket is pinned at the grip: support 'pinned')"
            )
        one_of(where, support, allowed)
    if len(set(supports)) != len(supports):
        raise InputError(f"{where}: name each support once")


def _modal_model(racket: Racket, file_model_scale: float) -> ModalModel:
    """The design's modal model (a file's frame modes scaled by √scale), cached per process."""
    return _cached_modal_model(racket, file_model_scale, _file_stamps(racket))


def _compound_law(racket: Racket, ball: Ball) -> RestoringForce:
    """The design's compound ball+string law, cached per process."""
    return _cached_compound_law(racket, ball, _file_stamps(racket))


def _file_stamps(racket: Racket) -> tuple[tuple[int, int], ...]:
    """Modification time and size of the files a racket reads: part of the cache keys, so a
    changed file is read again (the racket itself holds only their names)."""
    paths = (racket.modal_model_file, racket.strings.load_deflection_file)
    return tuple(
        (stat.st_mtime_ns, stat.st_size)
        for stat in (Path(p).stat() for p in paths if p is not None)
    )


# A design often shares its racket (an e_BG sweep) or its strings with others.
@lru_cache(maxsize=8)
def _cached_modal_model(
    racket: Racket, file_model_scale: float, stamps: tuple[tuple[int, int], ...]
) -> ModalModel:
    if racket.modal_model_file is None:
        return builtin_modal_model(racket)
    model = ModalModel.read_json(racket.modal_model_file)
    model.require_locations("a sweep")
    model.require_mass_normalised("a sweep")
    if file_model_scale == 1.0:
        return model
    frame = np.array([kind != "string-bed" for kind in model.kinds])
    return replace(
        model,
        frequency=np.where(frame, model.frequency * math.sqrt(file_model_scale), model.frequency),
        source=f"{model.source}, frame stiffness × {file_model_scale:g}",
    )


@lru_cache(maxsize=8)
def _cached_compound_law(
    racket: Racket, ball: Ball, stamps: tuple[tuple[int, int], ...]
) -> RestoringForce:
    return compound_law(racket, ball)


@lru_cache(maxsize=1)
def _blas_controller() -> ThreadpoolController:
    return ThreadpoolController()


def run_task(task: SweepTask, attempt: int = 1) -> TaskOutput:
    """Compute one design: build its racket, ball, modal model and law, then predict.

    A pure function of its inputs (per-process caches of modal models and laws only save
    time), so any executor gives the same numbers.

    Parameters
    ----------
    task : SweepTask
        The design.
    attempt : int
        Attempt number, recorded on the output (it also makes a retry a new task for executors
        that reuse the result of an identical call, such as Dask's pure tasks).

    Returns
    -------
    TaskOutput
        Arrays shaped ``(n_points, n_speeds, n_racket_speeds, n_supports)``.
    """
    # One BLAS thread: a dense solve (the mode-shape interpolator) split over threads rounds
    # differently with their number, and a Dask worker runs one thread where this process may
    # run several; pinned, every engine gives the same bits.  Parallelism is across tasks.
    started = time.perf_counter()
    with _blas_controller().limit(limits=1, user_api="blas"), impact_warnings_quiet():
        racket, ball, file_model_scale = build_design(
            task.racket, task.ball, task.variables, task.settings
        )
        model = None if task.rigid else _modal_model(racket, file_model_scale)
        law = _compound_law(racket, ball) if task.string_bed == "uniform" else None
        result = METHODS[task.method](racket, ball, model, law, task)
        bands = (
            {}
            if task.uncertainty is None
            else _bands(task, _inputs(task, racket, ball, model), result)
        )
    shape = (
        task.locations.shape[0],
        task.ball_speeds.size,
        task.racket_speeds.size,
        len(task.supports),
    )
    arrays: dict[str, NDArray[Any]] = {
        name: np.asarray(getattr(result, attribute), dtype=float).reshape(shape)
        for name, (attribute, _, _) in _IMPACT_VARIABLES.items()
    }
    status = np.full(result.status.shape, -1, dtype=np.int8)
    for text, code in STATUS_CODES.items():
        status[result.status == text] = code
    if np.any(status < 0):
        unknown = sorted(set(result.status[status < 0].tolist()))
        raise RuntimeError(f"{task.task_id}: unknown impact status {unknown}")
    arrays["status"] = status.reshape(shape)
    arrays.update(bands)
    used = result.modal_model
    return TaskOutput(
        task_id=task.task_id,
        arrays=arrays,
        reduced_mass_kg=np.asarray(result.reduced_mass, dtype=float),
        mode_names=() if used is None else tuple(used.names),
        mode_frequency_hz=np.zeros(0) if used is None else np.asarray(used.frequency, dtype=float),
        attempt=attempt,
        elapsed_s=time.perf_counter() - started,
    )


def _inputs(task: SweepTask, racket: Racket, ball: Ball, model: ModalModel | None) -> ModelInputs:
    """The design's inputs as :func:`racketdyn.impact.uncertainty.propagate` takes them."""
    from racketdyn.impact.measured import ModelInputs

    hand = build_hand(task.variables, task.settings) if "hand" in task.supports else None
    return ModelInputs(
        racket=racket,
        ball=ball,
        hand=hand,
        modal_model=model,
        include_string_bed=task.include_string_bed,
        engine=task.engine,
        string_bed=task.string_bed,
    )


def task_inputs(task: SweepTask) -> ModelInputs:
    """The nominal inputs of a task's design (racket, ball, modes, hand), as
    :func:`racketdyn.impact.uncertainty.propagate` takes them.

    Parameters
    ----------
    task : SweepTask
        The design's task.

    Returns
    -------
    ModelInputs
    """
    racket, ball, file_model_scale = build_design(
        task.racket, task.ball, task.variables, task.settings
    )
    # one BLAS thread, as in run_task: the cached model is built the same here (several
    # threads round the beam's solve apart, and a serial sweep reuses this process's cache)
    with _blas_controller().limit(limits=1, user_api="blas"):
        model = None if task.rigid else _modal_model(racket, file_model_scale)
    return _inputs(task, racket, ball, model)


_FACE_DIMS = ("design", "speed", "racket_speed", "support")
_FACE_METRICS = {
    "best_rebound_ratio": ("1", "highest rebound ratio over the face"),
    "sweet_area_cm2": ("cm2", "sweet area (racketdyn.sweep.sweet_area_cm2)"),
}


def band_variables() -> dict[str, tuple[bool, str, str]]:
    """The arrays a task adds with an uncertainty: name → (per impact, units, long name).

    Per impact (over ``(design, point, speed, racket_speed, support)``), as
    :meth:`racketdyn.impact.uncertainty.UncertainResult.band_columns` names them:
    ``<quantity>_mean``, ``_sd``, ``_p05``, ``_p95`` of contact time, peak force, vibration
    energy, rebound ratio and outgoing speed, ``samples_valid`` and ``frame_shot_share``.
    Per face (over
    ``(design, speed, racket_speed, support)``): ``best_rebound_ratio_p05/_p95`` and
    ``sweet_area_cm2_p05/_p95``, each sample's face metric's quantiles, and
    ``face_samples_valid``, the share of samples whose face counts (valid at 90 % of the
    points the nominal face gives).
    """
    from racketdyn.impact.uncertainty import BAND_QUANTITIES, QUANTILES

    names = {q.attribute: q.name for q in IMPACT_QUANTITIES}  # as band_columns names them
    out: dict[str, tuple[bool, str, str]] = {}
    for name in (names[attribute] for attribute in BAND_QUANTITIES):
        units, long_name = _IMPACT_VARIABLES[name][1:]
        for stat, what in (("mean", "mean"), ("sd", "standard deviation")):
            out[f"{name}_{stat}"] = (True, units, f"{what} over the samples: {long_name}")
        for q in QUANTILES:
            out[f"{name}_p{round(100 * q):02d}"] = (True, units, f"{q:.0%} quantile: {long_name}")
    out["samples_valid"] = (True, "1", "share of the string impacts the method could give")
    out["frame_shot_share"] = (True, "1", "share of the samples that hit the frame")
    for metric, (units, long_name) in _FACE_METRICS.items():
        for q in QUANTILES:
            out[f"{metric}_p{round(100 * q):02d}"] = (
                False,
                units,
                f"{q:.0%} quantile: {long_name}",
            )
    out["face_samples_valid"] = (
        False,
        "1",
        "share of the samples valid at 90 % of the points the nominal face gives",
    )
    return out


def _bands(task: SweepTask, inputs: ModelInputs, nominal: ImpactResult) -> dict[str, NDArray[Any]]:
    """The design's bands (:func:`band_variables`): its samples by
    :func:`~racketdyn.impact.uncertainty.propagate` (the approximate method's all at once),
    here in the task."""
    from racketdyn.impact.uncertainty import propagate

    assert task.uncertainty is not None
    n_b, n_r = task.ball_speeds.size, task.racket_speeds.size
    found = propagate(
        inputs,
        task.locations,
        np.repeat(task.ball_speeds, n_r),
        task.uncertainty,
        method="approx" if task.method == "approximate" else "transient",
        supports=task.supports,
        racket_speed=np.tile(task.racket_speeds, n_b),
        options={"stiffness_reading": task.stiffness_reading}
        if task.method == "approximate"
        else None,
        nominal=nominal,
    )
    shape = (task.locations.shape[0], n_b, n_r, len(task.supports))
    arrays = {k: v.reshape(shape) for k, v in found.band_columns().items()}
    arrays.update(_face_bands(task, found, nominal))
    return arrays


def _face_bands(
    task: SweepTask, found: UncertainResult, nominal: ImpactResult
) -> dict[str, NDArray[np.float64]]:
    """Each sample's best rebound ratio and sweet area over the face (points it cannot give
    count as outside, as :func:`~racketdyn.sweep.sweet_area_cm2` counts them), their 5 % and
    95 % quantiles over the samples whose face counts — valid at :data:`MIN_VALID_SHARE` of
    the points the nominal face gives — NaN where fewer than :data:`MIN_VALID_SHARE` of the
    samples count; shaped ``(n_speeds, n_racket_speeds, n_supports)``."""
    from racketdyn.impact.uncertainty import MIN_VALID_SHARE, QUANTILES
    from racketdyn.sweep.summary import sweet_area_cm2  # the one definition

    rebound = found.samples["rebound_ratio"]  # (samples, points, pairs, supports)
    nominal_ok = np.asarray(nominal.status) == STATUS_OK
    # a sample's face counts where it gives 90 % of the points the nominal face gives (a
    # location offset moves edge points onto the frame: those count as outside)
    given_points = np.sum(found.valid & nominal_ok[None], axis=1)
    face_ok = given_points >= MIN_VALID_SHARE * np.sum(nominal_ok, axis=0)[None]
    share = face_ok.mean(axis=0)
    faces = np.moveaxis(rebound, 1, -1)  # (samples, pairs, supports, points)
    finite = np.isfinite(faces)
    metrics = {
        "best_rebound_ratio": np.where(
            finite.any(axis=-1), np.where(finite, faces, -np.inf).max(axis=-1), np.nan
        ),
        "sweet_area_cm2": np.asarray(
            sweet_area_cm2(faces, task.racket.head.area_m2 * 1e4, task.threshold_fraction)
        ),
    }
    shape = (task.ball_speeds.size, task.racket_speeds.size, len(task.supports))
    given = share >= MIN_VALID_SHARE
    out: dict[str, NDArray[np.float64]] = {}
    for metric, values in metrics.items():
        kept = np.where(face_ok, values, np.nan)
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", "All-NaN slice", RuntimeWarning)
            quantiles = np.nanquantile(kept, QUANTILES, axis=0)
        for q, value in zip(QUANTILES, quantiles, strict=True):
            out[f"{metric}_p{round(100 * q):02d}"] = np.where(given, value, np.nan).reshape(shape)
    out["face_samples_valid"] = share.reshape(shape)
    return out
