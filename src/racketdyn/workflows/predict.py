"""Step ``predict``: impacts over the face by the approximate method, the transient model or
both, with the time histories and the comparison of the two models.

Writes ``impact.csv`` (``impact_transient.csv`` too with both models), ``transient_histories.csv``,
``comparison.csv``, ``figures.nc`` (what the figures draw, computed here with the run's inputs:
:mod:`racketdyn.workflows.figure_data`) and ``run.json``; figures come from the caller's hook.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import Ball
from racketdyn.contact import compound_law
from racketdyn.errors import InputError, one_of, require_speeds, require_words
from racketdyn.impact import ImpactResult, predict
from racketdyn.impact.grid import StringBed, check_string_bed
from racketdyn.impact.hand import Hand
from racketdyn.impact.measured import ModelInputs
from racketdyn.impact.result import (
    SHOWN_BY_DEFAULT,
    STATUS_FROM_TRANSIENT,
    shown_case_index,
    write_columns,
)
from racketdyn.impact.system import ENGINES, TRANSIENT_SUPPORTS, Engine
from racketdyn.impact.uncertainty import (
    Sensitivity,
    UncertainResult,
    Uncertainty,
    propagate,
    sensitivity,
)
from racketdyn.io import racket_to_dict, read_points
from racketdyn.modal import ModalModel
from racketdyn.plausibility import check, check_speeds
from racketdyn.racket import SUPPORTS, Racket, landmark_points
from racketdyn.workflows._figure_io import store
from racketdyn.workflows.figure_data import (
    FIGURES_FILE,
    AxisBand,
    ComparisonMap,
    ImpactCurves,
    PaperFigures,
    TransientCurves,
    TransientHistories,
    axis_points,
    joined_figure_data,
    paper_figures,
    transient_curves,
    write_figure_data,
)
from racketdyn.workflows.inputs import supports_named
from racketdyn.workflows.run import (
    Progress,
    StepResult,
    check_workers,
    defer_file,
    report,
    run_step,
    sample_pool,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

if TYPE_CHECKING:
    import xarray as xr

    from racketdyn.impact.comparison import History, ModelComparison

# The transient model (racketdyn.impact.transient, .comparison) is imported where it runs: with
# numba it costs ≈ 0.2 s, a tenth of `predict`'s default run, which is the approximate method's.

__all__ = [
    "DEFAULT_GRID",
    "DEFAULT_PREDICT",
    "MAX_GRID",
    "MODELS",
    "PredictOptions",
    "PredictResult",
    "impact_points",
    "run_predict",
]

Model = Literal["approx", "transient", "both"]
MODELS: tuple[Model, ...] = ("approx", "transient", "both")
DEFAULT_GRID = 9
MAX_GRID = 400  # 400 × 400 ≈ 126,000 points: a few seconds a speed
CHUNK_IMPACTS = 50_000  # above this, predict in chunks of points (progress reported)
TRANSIENT_FIRST_CHUNK = 32  # transient impacts in the first chunk, timed to size the others
TRANSIENT_CHUNK_S = 0.5  # then chunks of about this long: the progress moves smoothly
TRANSIENT_QUIET_IMPACTS = 64  # no progress reports up to this many transient impacts


@dataclass
class PredictResult(StepResult):
    """What :func:`run_predict` computed and wrote.

    Attributes
    ----------
    racket, ball : Racket, Ball
        The racket (with the modal model file used) and the ball.
    modal_model : ModalModel or None
        The racket's modes; None for a rigid racket.
    law : RestoringForce
        Compound ball + string-bed law.
    speeds, racket_speed : list of float
        Ball speeds and racket speeds, m/s.
    supports : list of str
        Supports.
    approximate, transient : ImpactResult or None
        Each model's impacts (None when not asked for).
    comparison : ModelComparison or None
        Both models on the same impacts (``model="both"``).
    histories : list of History
        Transient time histories at the centre and the tip, at the shown speed.
    mode_names : tuple of str
        Names of the transient model's modes.
    shown_speed : int
        Index of the speed single-speed figures and tables show (20 m/s if given).
    engine : str
        Transient engine asked for.
    include_string_bed : bool
        String-bed modes charged as vibration loss.
    string_bed : {"uniform", "local"}
        The string bed's law over the face (``law`` is the centre's, used with ``uniform``).
    stiffness_reading : {"period", "tangent"}
        Reading of eq 10 (approximate method).
    vibration_charge : {"coupled", "paper"}
        How the approximate method charges the vibration against e_BG
        (:func:`racketdyn.impact.approximate.vibration_cor_squared`).
    rigid : bool
        A rigid racket (no modes) was asked for.
    points : str
        What the impact points are (a grid, a file, points given).
    hand : Hand or None
        The hand of the ``hand`` support.
    paper_figures : PaperFigures or None
        What the paper's figures draw (Figs 11–15, face maps), with the run's inputs (None
        without the approximate method).
    transient_curves : TransientCurves or None
        Both models against speed (``model="both"``).
    comparison_map : ComparisonMap or None
        Approximate − transient rebound ratio over the face at the shown speed
        (``model="both"``).
    transient_histories : TransientHistories or None
        The time histories as the figure draws them (``model`` transient or both).
    bands : dict
        With an ``uncertainty``: each model's samples and bands (``approx``, ``transient``).
    sensitivity : Sensitivity or None
        With an ``uncertainty``: Sobol' indices at the centre, tip, throat and 40 mm off the
        axis, at the shown speed and the first support (``sensitivity.csv``).
    """

    racket: Racket | None = None
    ball: Ball | None = None
    modal_model: ModalModel | None = None
    law: Any = None
    speeds: list[float] = field(default_factory=list)
    racket_speed: list[float] = field(default_factory=list)
    supports: list[str] = field(default_factory=list)
    approximate: ImpactResult | None = None
    transient: ImpactResult | None = None
    comparison: ModelComparison | None = None
    histories: list[History] = field(default_factory=list)
    mode_names: tuple[str, ...] = ()
    shown_speed: int = 0
    engine: str = "auto"
    include_string_bed: bool = False
    string_bed: StringBed = "uniform"
    stiffness_reading: Literal["period", "tangent"] = "period"
    vibration_charge: Literal["coupled", "paper"] = "coupled"
    rigid: bool = False
    points: str = ""
    hand: Hand | None = None
    paper_figures: PaperFigures | None = None
    transient_curves: TransientCurves | None = None
    comparison_map: ComparisonMap | None = None
    transient_histories: TransientHistories | None = None
    bands: dict[str, UncertainResult] = field(default_factory=dict)
    sensitivity: Sensitivity | None = None

    @property
    def result(self) -> ImpactResult:
        """The main table: the approximate method's if run, else the transient model's."""
        result = self.approximate if self.approximate is not None else self.transient
        assert result is not None
        return result

    def to_xarray(self) -> xr.Dataset:
        """Everything the run computed as one :class:`xarray.Dataset`.

        Each model's impacts (:meth:`~racketdyn.impact.result.ImpactResult.to_xarray`: the
        dimensions ``point``, ``ball_speed``, ``support``, ``mode``), with an ``uncertainty``
        their bands and samples (:meth:`~racketdyn.impact.uncertainty.UncertainResult.
        to_xarray`'s variables beyond the impacts'), stacked on a ``model`` dimension
        (``approximate``, ``transient``: the models run), whose coordinates ``method`` and
        ``inputs`` hold each model's own attributes; a variable only one model has
        (``energy_balance_j``, the transient's) keeps its dimensions and names its ``model``
        in an attribute.  Beside them, the figures' data as ``figures.nc`` holds them (each
        figure's names prefixed with its key, ``fig11_12__…``: the paper's curves, the
        transient time histories, the comparison map, the sensitivity).  Values are the
        result's as they are (NaN where a status says why).

        Returns
        -------
        xarray.Dataset
            Writable as netCDF (``engine="scipy"``, as ``figures.nc``).
        """
        import xarray as xr

        runs = (("approximate", "approx"), ("transient", "transient"))
        parts = {
            name: _impacts_with_band(impacts, self.bands.get(key))
            for name, key in runs
            if (impacts := getattr(self, name)) is not None
        }
        if not parts:
            raise ValueError("no impacts in this result: run_predict makes them")
        names = (set(map(str, part.data_vars)) for part in parts.values())
        common = sorted(set.intersection(*names))
        stacked = xr.concat(
            [part[common] for part in parts.values()],
            dim="model",
            coords="minimal",
            compat="equals",
            join="exact",
            combine_attrs="drop_conflicts",
        ).assign_coords(
            model=("model", list(parts), {"long_name": "impact model"}),
            method=("model", [part.attrs.get("method", "") for part in parts.values()]),
            inputs=("model", [part.attrs.get("inputs", "") for part in parts.values()]),
        )
        for name, part in parts.items():
            for variable in set(part.data_vars) - set(common):
                stacked[variable] = part[variable].assign_attrs(model=name)
        figures = joined_figure_data([data() for data in self._figure_parts()])
        merged = xr.merge([stacked, figures], combine_attrs="override")
        merged.attrs = {**figures.attrs, **stacked.attrs}
        merged.attrs["title"] = "racketdyn predict: the impacts and the data of its figures"
        return merged

    def _figure_parts(self) -> list[Callable[[], xr.Dataset]]:
        """The ``to_xarray`` of each figure-data object the run computed (``figures.nc``'s
        parts, in its order), the sensitivity stored as it is."""
        objects = (
            self.paper_figures,
            self.transient_curves,
            self.comparison_map,
            self.transient_histories,
        )
        parts: list[Callable[[], xr.Dataset]] = [
            data.to_xarray for data in objects if data is not None
        ]
        if self.sensitivity is not None:
            parts.append(partial(store, {"sensitivity": self.sensitivity}))
        return parts


def _impacts_with_band(impacts: ImpactResult, band: UncertainResult | None) -> xr.Dataset:
    """A model's impacts as a dataset, with its band's variables the impacts have not (the
    bands, the samples, the draws) and the uncertainty's record."""
    dataset = impacts.to_xarray()
    if band is None:
        return dataset
    banded = band.to_xarray()
    extra = [name for name in banded.data_vars if name not in dataset]
    dataset = dataset.assign({str(name): banded[name].variable for name in extra})
    dataset.attrs["uncertainty"] = banded.attrs["uncertainty"]
    return dataset


def impact_points(
    racket: Racket,
    points: str | os.PathLike[str] | ArrayLike | None = None,
    grid: int | None = None,
    default_grid: int = DEFAULT_GRID,
) -> tuple[NDArray[np.float64], list[str], str]:
    """Impact points: a CSV file, an array of (x, y) in m, or an N × N grid over the head.

    Parameters
    ----------
    racket : Racket
        The racket (its head for the grid).
    points : path or array, optional
        CSV with columns ``x_m, y_m [, point]``, or locations ``(n, 2)`` in m.
    grid : int, optional
        N of the N × N grid (default ``default_grid``); excludes ``points``.
    default_grid : int
        N when neither is given.

    Returns
    -------
    locations : ndarray (n, 2)
        Points, m.
    labels : list of str
        Their labels.
    source : str
        What they are, for run.json.
    """
    if points is not None and grid is not None:
        raise InputError("give `grid` or `points`, not both")
    if isinstance(points, str | os.PathLike):
        locations, labels = read_points(Path(points))
        return locations, labels, f"points file {Path(points).resolve()}"
    if points is not None:
        array = np.asarray(points, dtype=float).reshape(-1, 2)
        return array, [str(i + 1) for i in range(len(array))], f"{len(array)} points given"
    n = default_grid if grid is None else grid
    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= MAX_GRID:
        raise InputError(f"`grid` must be a whole number from 1 to {MAX_GRID} (got {n})")
    locations = racket.head.grid(n)
    return locations, [str(i + 1) for i in range(len(locations))], f"grid {n} x {n} over the head"


def check_supports(supports: str | Sequence[str], model: str) -> list[str]:
    """The supports (a sequence, or one text of comma-separated names), each allowed by the
    model(s) asked for, each named once."""
    words = require_words("`supports`", supports)
    for support in words:
        if support == "hand" and model == "both":
            raise InputError(
                "`supports` hand with `model` both: the approximate method has no hand (it "
                "holds the racket pinned at the grip), so the two models cannot be compared "
                "there; run hand with `model` transient, or compare them on `supports` pinned"
            )
        if support == "hand" and model != "transient":
            raise InputError(
                "`supports` hand needs `model` transient: the approximate method has no hand "
                "(it holds the racket pinned at the grip: `supports` pinned)"
            )
    return supports_named(words, TRANSIENT_SUPPORTS if model == "transient" else SUPPORTS)


@dataclass(frozen=True)
class PredictOptions:
    """The impacts to predict and how: the cases (speeds, supports, points), the model and its
    choices, the uncertainty and the case shown.

    The fields are the words the library's errors name in backticks (``speeds``), which
    the CLI turns into its flags (:func:`racketdyn.cli.options.in_flags`); they are checked
    when :func:`run_predict` runs.

    Attributes
    ----------
    speeds : array_like
        Incoming ball speeds, m/s (or one text ``"10,20"``, as the command line spells them;
        the same for ``racket_speed``, ``supports`` and ``show``).
    racket_speed : array_like
        Racket speed at the impact point towards the ball, m/s: one, or one per speed.
    supports : str or sequence of str
        ``free``, ``pinned``; ``hand`` with ``model="transient"`` only (one as a string, or
        ``"free,pinned"``).
    model : {"approx", "transient", "both"}
        Kawazoe's approximate method, the transient simulation, or each with their comparison.
    engine : {"auto", "compiled", "reference"}, optional
        Transient integrator (default ``auto``); for ``model`` transient or both only.
    points : path or array, optional
        Impact points (CSV or ``(n, 2)`` in m); excludes ``grid``.
    grid : int, optional
        N × N grid over the head (default 9).
    stiffness_reading : {"period", "tangent"}, optional
        Reading of eq 10 (default ``period``); for ``model`` approx or both only.
    vibration_charge : {"coupled", "paper"}
        The approximate method's charge of the vibration against e_BG: the contact's own
        pulse, as the coupled contact's energy and momentum balances give it (default), or
        eq 12's half sine as the paper writes it.
    include_string_bed : bool
        Charge string-bed modes as vibration loss too.
    uncertainty : Uncertainty, optional
        Uncertain inputs: each model run once per sample (:func:`racketdyn.impact.
        uncertainty.propagate`), the bands written beside the numbers (``<column>_mean``,
        ``_sd``, ``_p05``, ``_p95``, ``samples_valid``, ``frame_shot_share``) and every sample in
        ``uncertainty.nc`` (``uncertainty_transient.nc`` for the transient with both).
    workers : int, optional
        Worker processes for the samples a model runs one by one (the transient model's): a
        local pool (:func:`racketdyn.sweep.executors.make_executor`); by default this process.
    show : sequence of float, optional
        The case the single-case summaries show (face maps, Fig. 15, the time histories, the
        models' comparison map and table, the report's headline): ``(ball speed,)`` or
        ``(ball speed, racket speed)``, m/s, one of the run's; by default 20 m/s if run,
        else the middle ball speed.  run.json's ``shown_case`` records it.
    """

    speeds: ArrayLike = (10.0, 20.0, 30.0)
    racket_speed: ArrayLike = (0.0,)
    supports: str | Sequence[str] = ("free", "pinned")
    model: Model = "approx"
    engine: str | None = None
    points: str | os.PathLike[str] | ArrayLike | None = None
    grid: int | None = None
    stiffness_reading: Literal["period", "tangent"] | None = None
    vibration_charge: Literal["coupled", "paper"] = "coupled"
    include_string_bed: bool = False
    uncertainty: Uncertainty | None = None
    workers: int | None = None
    show: float | Sequence[float] | None = None


DEFAULT_PREDICT = PredictOptions()
"""The approximate method at 10, 20 and 30 m/s on a racket at rest, free and pinned, over a
9 × 9 grid."""


@run_step
def run_predict(
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    options: PredictOptions = DEFAULT_PREDICT,
) -> PredictResult:
    """Predict impacts over the face and write the run folder.

    The steps: the options checked (:func:`_model_choices`, :func:`_impact_cases`,
    :func:`check_supports`), the points (:func:`impact_points`), each model's impacts
    (:func:`_run_models`), their bands (:func:`_bands`), the comparison and ``impact.csv``
    (:func:`_compare_and_write`), what the figures draw (:func:`_figure_data`) and run.json.

    Parameters
    ----------
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, predict uses the racket and its modes,
        the ball, the hand, the string bed (both models) and ``allow_implausible``; and the run
        (command, figures, progress).
    options : PredictOptions
        The speeds, supports and points, the model and its choices, the uncertainty and the
        case shown.

    Returns
    -------
    PredictResult
    """
    engine, stiffness_reading = _model_choices(options)
    speed_list, racket_speeds, paired = _impact_cases(
        options.speeds, options.racket_speed, setup.allow_implausible
    )
    shown = shown_case_index(speed_list, paired, options.show)
    # one as a string, as rd.predict takes it, or several as the command line spells them
    support_list = check_supports(options.supports, options.model)
    used = setup.racket_setup()
    the_ball, ball_defaults = setup.ball_used()
    the_hand, hand_defaults = setup.hand_used(support_list)
    defaults_used = [*used.defaults, *ball_defaults, *setup.defaults, *hand_defaults]
    locations, labels, points_source = impact_points(used.racket, options.points, options.grid)
    check_string_bed(setup.string_bed, None, used.racket)
    law = compound_law(used.racket, the_ball)
    result = PredictResult(
        Path(out), racket=used.racket, ball=the_ball, modal_model=used.modal_model, law=law,
        speeds=speed_list, racket_speed=racket_speeds, supports=support_list, shown_speed=shown,
        engine=engine, include_string_bed=options.include_string_bed,
        string_bed=setup.string_bed, stiffness_reading=stiffness_reading,
        vibration_charge=options.vibration_charge, rigid=setup.rigid, points=points_source,
        hand=the_hand,
    )  # fmt: skip
    run_options: dict[str, Any] = {
        "supports": support_list,
        "racket_speed": np.asarray(racket_speeds),
        "modal_model": used.modal_model,
        "law": None if setup.string_bed == "local" else law,
        "include_string_bed": options.include_string_bed,
        "string_bed": setup.string_bed,
    }
    _run_models(result, options.model, (locations, labels), run_options, setup.progress)
    band = None
    if options.uncertainty is not None:
        band = (_sample_inputs(result), options.uncertainty)
        extra = {
            "stiffness_reading": stiffness_reading,
            "vibration_charge": result.vibration_charge,
        }
        _bands(result, *band, (locations, labels), setup.progress, extra, options.workers)
    _compare_and_write(result)
    _figure_data(result, run_options, setup.progress, band)
    inputs = {
        **used.provenance,
        "racket": racket_to_dict(used.racket),
        "speeds_mps": speed_list,
        "racket_speed_mps": racket_speeds,
        "supports": support_list,
        "points": points_source,
        "n_points": len(locations),
        "rigid": setup.rigid,
        "defaults_used": defaults_used,
        **result.result.inputs,
        "model": options.model,
        **_transient_record(result.transient, result.approximate, engine),
        "uncertainty": None if options.uncertainty is None else options.uncertainty.record(),
        "shown_case": {
            "ball_speed_mps": speed_list[shown],
            "racket_speed_mps": paired[shown],
            "chosen_by": "show" if options.show is not None else SHOWN_BY_DEFAULT,
        },
    }
    return setup.finish(result, inputs, "predict")


def _model_choices(options: PredictOptions) -> tuple[str, Literal["period", "tangent"]]:
    """The model's choices checked against it: the transient engine and the reading of eq 10,
    defaults filled in (``auto``, ``period``); the workers against the uncertainty."""
    model, engine, stiffness_reading = options.model, options.engine, options.stiffness_reading
    one_of("`model`", model, MODELS)
    if engine is not None and model == "approx":
        raise InputError("`engine` is for the transient model: `model` transient or both")
    if stiffness_reading is not None and model == "transient":
        raise InputError(
            "`stiffness_reading` is a choice of the approximate method (eq 10); the transient "
            "model integrates the contact: drop it, or use `model` approx or both"
        )
    if options.uncertainty is not None and not isinstance(options.uncertainty, Uncertainty):
        raise TypeError(
            "run_predict: `uncertainty` must be an Uncertainty (got "
            f"{type(options.uncertainty).__name__}); build one from a file with "
            "racketdyn.impact.uncertainty.Uncertainty(racketdyn.io.uncertainty_file."
            "read_spreads(path), samples=256)"
        )
    check_workers(options.workers, options.uncertainty)
    engine = engine or "auto"
    stiffness_reading = stiffness_reading or "period"
    one_of("`engine`", engine, ENGINES)
    return engine, stiffness_reading


def _impact_cases(
    speeds: ArrayLike, racket_speed: ArrayLike, allow_implausible: bool
) -> tuple[list[float], list[float], list[float]]:
    """The ball speeds, the racket speeds as given (one, or one per ball speed) and the racket
    speed paired with each ball speed, m/s: each case once, the ball reaching the strings,
    within play (unless ``allow_implausible``)."""
    speed_list = [float(v) for v in require_speeds("`speeds`", speeds)]
    racket_speeds = [float(v) for v in require_speeds("`racket_speed`", racket_speed)]
    check_speeds("`speeds`", speed_list, "ball_speed_mps", allow_implausible)
    check_speeds("`racket_speed`", racket_speeds, "racket_speed_mps", allow_implausible)
    if len(racket_speeds) not in (1, len(speed_list)):
        raise InputError("`racket_speed` takes one speed, or one per `speeds` value")
    cases = list(
        zip(
            speed_list,
            racket_speeds * len(speed_list) if len(racket_speeds) == 1 else racket_speeds,
            strict=True,
        )
    )
    if any(v + r <= 0 for v, r in cases):
        raise InputError(
            "`speeds`: the ball must reach the strings: ball speed + racket speed above 0 m/s "
            f"(got {', '.join(f'{v:g} + {r:g}' for v, r in cases if v + r <= 0)})"
        )
    for v, r in cases:
        check(
            "relative_speed_mps",
            v + r,
            f"`speeds` + `racket_speed` ({v:g} + {r:g} m/s) =",
            allow_implausible=allow_implausible,
        )
    if len(set(cases)) != len(cases):
        raise InputError(
            f"`speeds`: each ball speed once (with its racket speed); got "
            f"{', '.join(f'{v:g}' for v in speed_list)}"
        )
    return speed_list, racket_speeds, [r for _, r in cases]


def _run_models(
    result: PredictResult,
    model: Model,
    points: tuple[NDArray[np.float64], list[str]],
    run_options: dict[str, Any],
    progress: Progress | None,
) -> None:
    """The approximate method's impacts at ``points`` (locations, labels) and the transient
    model's, as ``model`` asks, into ``result``."""
    assert result.racket is not None
    assert result.ball is not None
    locations, labels = points
    n_impacts = len(locations) * len(result.speeds) * len(result.supports)
    if model in ("approx", "both"):
        report(progress, f"approximate method: {n_impacts} impacts")
        result.approximate = _approximate(
            result.racket,
            result.ball,
            locations,
            result.speeds,
            labels,
            progress,
            stiffness_reading=result.stiffness_reading,
            vibration_charge=result.vibration_charge,
            **run_options,
        )
    if model in ("transient", "both"):
        report(progress, f"transient model ({result.engine} engine): {n_impacts} impacts")
        _transient_part(result, locations, labels, progress, run_options)


def _sample_inputs(result: PredictResult) -> ModelInputs:
    """The inputs each sample of an uncertainty varies: the result's racket, ball, hand,
    modes, string bed and engine."""
    assert result.racket is not None
    assert result.ball is not None
    return ModelInputs(
        result.racket,
        result.ball,
        hand=result.hand,
        modal_model=result.modal_model,
        include_string_bed=result.include_string_bed,
        engine=result.engine,
        string_bed=result.string_bed,
    )


def _compare_and_write(result: PredictResult) -> None:
    """With both models, their comparison (``comparison.csv``) and the approximate method's
    rows it cannot give filled from the transient's; then ``impact.csv``."""
    if result.approximate is not None and result.transient is not None:
        from racketdyn.impact.comparison import compare_models

        result.comparison = compare_models(result.approximate, result.transient)
        result.written.append(result.comparison.write_csv(result.out / "comparison.csv"))
        # rows the approximate method cannot give carry the transient's numbers, marked so
        result.approximate = result.approximate.filled_from(result.transient)
    if result.approximate is not None:
        _write_table(result, result.approximate, result.out / "impact.csv")


def _bands(
    result: PredictResult,
    inputs: ModelInputs,
    uncertainty: Uncertainty,
    points: tuple[NDArray[np.float64], list[str]],
    progress: Progress | None,
    approximate_options: dict[str, Any],
    workers: int | None,
) -> None:
    """Each model's samples and bands (the transient's on ``workers`` processes, if given);
    the transient's table rewritten with its bands."""
    locations, labels = points
    runs = [("approx", result.approximate), ("transient", result.transient)]
    for method, nominal in runs:
        if nominal is None:
            continue
        name = "approximate method" if method == "approx" else "transient model"
        report(progress, f"uncertainty: {uncertainty.samples} samples by the {name}")
        with sample_pool(workers) as executor:
            band = propagate(
                inputs,
                locations,
                result.speeds,
                uncertainty,
                method=method,  # type: ignore[arg-type]
                supports=result.supports,
                racket_speed=np.asarray(result.racket_speed),
                labels=labels,
                options=approximate_options if method == "approx" else None,
                progress=_sample_progress(progress, name),
                executor=executor,
            )
        result.bands[method] = band
        both = result.approximate is not None and result.transient is not None
        file = "uncertainty_transient.nc" if method == "transient" and both else "uncertainty.nc"
        band.to_xarray().to_netcdf(result.out / file)
        result.written.append(result.out / file)
    _sensitivity(result, inputs, uncertainty, progress, approximate_options, workers)
    if result.transient is not None and "transient" in result.bands:
        both = result.approximate is not None
        path = result.out / transient_csv_name("both" if both else "transient")
        write_columns(path, _with_bands(result.transient, result.bands["transient"]))


def _sample_progress(progress: Progress | None, name: str) -> Callable[[int, int], None] | None:
    if progress is None:
        return None
    shown = progress
    return lambda done, total: shown(name, done, total)


SENSITIVITY_SAMPLES = 64
"""Base samples of the Sobol' indices: n (d + 2) model runs for d inputs (448 for five)."""


def _sensitivity(
    result: PredictResult,
    inputs: ModelInputs,
    uncertainty: Uncertainty,
    progress: Progress | None,
    approximate_options: dict[str, Any],
    workers: int | None,
) -> None:
    """Which input dominates at the landmarks: ``sensitivity.csv`` (the transient model's runs
    on ``workers`` processes, if given)."""
    assert result.racket is not None
    marks = landmark_points(result.racket)
    centre = marks["centre"]
    points = {
        "centre": centre,
        "tip": marks["tip"],
        "throat": marks["throat"],
        "40 mm off the axis": (centre[0], centre[1] + 0.04),
    }
    method = "approx" if result.approximate is not None else "transient"
    shown = result.shown_speed
    report(progress, "uncertainty: which input dominates (Sobol' indices)")
    with sample_pool(workers if method == "transient" else None) as executor:
        result.sensitivity = sensitivity(
            inputs,
            points,
            result.speeds[shown],
            uncertainty,
            support=result.supports[0],
            racket_speed=result.racket_speed[shown if len(result.racket_speed) > 1 else 0],
            n=SENSITIVITY_SAMPLES,
            method=method,  # type: ignore[arg-type]
            options=approximate_options if method == "approx" else None,
            executor=executor,
        )
    path = result.out / "sensitivity.csv"
    rows = result.sensitivity.rows()
    write_columns(path, {k: np.asarray(v, dtype=object) for k, v in rows.items()})
    result.written.append(path)


def _with_bands(table: ImpactResult, band: UncertainResult | None) -> dict[str, Any]:
    columns: dict[str, Any] = dict(table.columns)
    if band is not None:
        columns.update({k: np.ravel(v) for k, v in band.band_columns().items()})
    return columns


_SHARES = ("samples_valid", "frame_shot_share")


def _write_table(result: PredictResult, table: ImpactResult, path: Path) -> None:
    """``impact.csv``: the approximate method's rows with their bands; a row filled from the
    transient model takes the transient's band."""
    columns = _with_bands(table, result.bands.get("approx"))
    other = result.bands.get("transient")
    if "approx" in result.bands and other is not None:
        filled = np.ravel(table.status) == STATUS_FROM_TRANSIENT
        for key, values in _with_bands(table, other).items():
            if key.endswith(("_mean", "_sd", "_p05", "_p95")) or key in _SHARES:
                columns[key] = np.where(filled, values, columns[key])
    write_columns(path, columns)
    result.written.append(path)


def _figure_data(
    result: PredictResult,
    options: dict[str, Any],
    progress: Progress | None,
    band: tuple[ModelInputs, Uncertainty] | None = None,
) -> None:
    """What the figures draw, with the run's inputs and options, into ``figures.nc`` (with an
    uncertainty, Fig. 15's band)."""
    assert result.racket is not None
    assert result.ball is not None
    grid: dict[str, Any] = {
        "speeds": result.speeds,
        "racket_speeds": result.racket_speed,
        "supports": tuple(s for s in result.supports if s != "hand"),
    }
    impact = {k: v for k, v in options.items() if k not in ("supports", "racket_speed")}
    if result.approximate is not None:
        report(progress, "computing the figures' curves")
        result.paper_figures = paper_figures(
            result.racket,
            result.ball,
            **grid,
            shown_speed=result.speeds[result.shown_speed],
            shown_racket_speed=result.racket_speed[
                result.shown_speed if len(result.racket_speed) > 1 else 0
            ],
            result=result.approximate,
            stiffness_reading=result.stiffness_reading,
            vibration_charge=result.vibration_charge,
            **impact,
        )
        if band is not None:
            result.paper_figures = replace(
                result.paper_figures,
                axis_band=_axis_band(result, *band),
                face=_face_band(result.paper_figures.face, result.bands["approx"], result),
            )
    if result.comparison is not None:
        report(progress, "both models against speed")
        result.transient_curves = transient_curves(
            result.racket,
            result.ball,
            **grid,
            engine=cast("Engine", result.engine),
            stiffness_reading=result.stiffness_reading,
            vibration_charge=result.vibration_charge,
            **impact,
        )
        result.comparison_map = ComparisonMap.of(
            result.comparison, result.shown_speed, result.racket.head
        )
    if result.transient is not None and result.histories:
        result.transient_histories = TransientHistories.of(result.histories, result.mode_names)
    datasets = result._figure_parts()
    if datasets:  # written while the figures are drawn (xarray's import is most of it)
        path = result.out / FIGURES_FILE
        defer_file(result, path, lambda: write_figure_data(path, datasets))


def _axis_band(
    result: PredictResult,
    inputs: ModelInputs,
    uncertainty: Uncertainty,
) -> AxisBand:
    """Fig. 15's band: the approximate method's samples along the axis at the shown speed."""
    assert result.racket is not None
    assert result.paper_figures is not None
    axis = result.paper_figures.axis
    extra = {
        "stiffness_reading": result.stiffness_reading,
        "vibration_charge": result.vibration_charge,
    }
    samples = propagate(
        inputs,
        axis_points(result.racket),
        axis.ball_speed,
        uncertainty,
        supports=axis.supports,
        racket_speed=axis.racket_speed,
        options=extra,
    )
    return AxisBand(
        samples.quantile("rebound_ratio", 0.05)[:, 0, :],
        samples.quantile("rebound_ratio", 0.95)[:, 0, :],
        uncertainty.samples,
        ", ".join(s.name for s in uncertainty.spreads),
    )


def _face_band(face: ImpactCurves, band: UncertainResult, result: PredictResult) -> ImpactCurves:
    """The face maps' impacts with the width of their band at the shown speed."""
    width = band.quantile("rebound_ratio", 0.95) - band.quantile("rebound_ratio", 0.05)
    shown = result.shown_speed
    return replace(face, rebound_ratio_band_width=width[:, shown : shown + 1, :])


def transient_csv_name(model: str) -> str:
    """The transient model's table: ``impact.csv`` alone, ``impact_transient.csv`` with both."""
    return "impact.csv" if model == "transient" else "impact_transient.csv"


def history_points(racket: Racket) -> dict[str, tuple[float, float]]:
    """Where the time histories are simulated: the face centre and the tip
    (:func:`racketdyn.racket.landmark_points`, the points of the paper's Figs 11–14)."""
    marks = landmark_points(racket)
    return {name: marks[name] for name in ("centre", "tip")}


def _transient_part(
    result: PredictResult,
    locations: NDArray[np.float64],
    labels: list[str],
    progress: Progress | None,
    options: dict[str, Any],
) -> None:
    from racketdyn.impact.comparison import simulate_histories, write_histories_csv

    assert result.racket is not None
    assert result.ball is not None
    hand = {} if result.hand is None else {"hand": result.hand}
    transient = _transient(
        result.racket,
        result.ball,
        locations,
        result.speeds,
        labels,
        progress,
        engine=result.engine,
        **options,
        **hand,
    )
    name = transient_csv_name("both" if result.approximate is not None else "transient")
    transient.write_csv(result.out / name)
    result.transient = transient
    result.written.append(result.out / name)
    chosen = result.shown_speed
    report(progress, "simulating the time histories")
    result.histories = simulate_histories(
        result.racket,
        result.ball,
        history_points(result.racket),
        result.speeds[chosen],
        result.supports,
        result.racket_speed[chosen if len(result.racket_speed) > 1 else 0],
        modal_model=options["modal_model"],
        law=options["law"],
        include_string_bed=result.include_string_bed,
        string_bed=options["string_bed"],
        hand=result.hand,
    )
    result.mode_names = () if transient.modal_model is None else tuple(transient.modal_model.names)
    result.written.append(
        write_histories_csv(
            result.histories, result.mode_names, result.out / "transient_histories.csv"
        )
    )


def _approximate(
    racket: Racket,
    ball: Ball,
    locations: NDArray[np.float64],
    speeds: list[float],
    labels: list[str],
    progress: Progress | None,
    **options: Any,
) -> ImpactResult:
    """The approximate method, in chunks of points (progress reported) when large."""
    per_point = len(speeds) * len(options["supports"])
    if len(locations) * per_point <= CHUNK_IMPACTS:
        return predict(racket, ball, locations, speeds, labels=labels, **options)
    step = max(CHUNK_IMPACTS // per_point, 1)
    parts = []
    report(progress, "predicting", 0, len(locations))
    for start in range(0, len(locations), step):
        stop = min(start + step, len(locations))
        parts.append(
            predict(
                racket, ball, locations[start:stop], speeds, labels=labels[start:stop], **options
            )
        )
        report(progress, "predicting", stop, len(locations))
    return ImpactResult.concatenate(parts)


def _transient(
    racket: Racket,
    ball: Ball,
    locations: NDArray[np.float64],
    speeds: list[float],
    labels: list[str],
    progress: Progress | None,
    **options: Any,
) -> ImpactResult:
    """The transient model, in chunks of points sized to about half a second with progress
    reported (the first chunk is timed to size the others: the engines differ a thousandfold)."""
    from racketdyn.impact.transient import predict_transient

    per_point = len(speeds) * len(options["supports"])
    total = len(locations) * per_point

    def chunk(start: int, stop: int) -> ImpactResult:
        return predict_transient(
            racket, ball, locations[start:stop], speeds, labels=labels[start:stop], **options
        )

    if total <= TRANSIENT_QUIET_IMPACTS:
        return chunk(0, len(locations))
    parts = []
    report(progress, "transient simulation", 0, total)
    start, step = 0, max(TRANSIENT_FIRST_CHUNK // per_point, 1)
    while start < len(locations):
        stop = min(start + step, len(locations))
        began = time.perf_counter()
        parts.append(chunk(start, stop))
        elapsed = max(time.perf_counter() - began, 1e-6)
        report(progress, "transient simulation", stop * per_point, total)
        step = max(int(TRANSIENT_CHUNK_S * (stop - start) / elapsed), 1)
        start = stop
    return ImpactResult.concatenate(parts)


def _transient_record(
    transient: ImpactResult | None, approximate: ImpactResult | None, engine: str
) -> dict[str, Any]:
    """What run.json says about the transient model: engine, integrator, its outputs."""
    if transient is None:
        return {}
    from racketdyn.impact.comparison import COMPARED, HISTORY_COLUMNS

    inputs = transient.inputs
    integrator = inputs.get("integrator")
    used = integrator.get("engine") if isinstance(integrator, dict) else None
    record: dict[str, Any] = {
        "engine": {"requested": engine, "used": used or "not recorded by predict_transient"},
        "integrator": integrator,
        "time_histories": "simulate_impact (the reference engine: scipy solve_ivp, DOP853, "
        "rtol 1e-10) at the centre and the tip, each support",
        "columns": {
            "transient_histories.csv": HISTORY_COLUMNS,
            **(
                {}
                if approximate is None
                else {
                    "comparison.csv": "per point x speed x support: approx_<q>, transient_<q>, "
                    "difference_<q> = approx - transient, relative_difference_<q> = "
                    "(approx - transient) / |transient| for q in "
                    + ", ".join(COMPARED.values())
                    + "; status_approx, status_transient"
                }
            ),
        },
    }
    if approximate is not None:  # the approximate method's inputs are at the top level
        record["transient"] = {
            key: value
            for key, value in inputs.items()
            if key not in approximate.inputs or approximate.inputs[key] != value
        }
    return record
