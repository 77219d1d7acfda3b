"""The sweep spec: :class:`SweepSpec`, what a sweep computes, and the designs it lists.

Read from TOML by :mod:`~racketdyn.sweep.spec_file`; lists the design variants
(:class:`~racketdyn.sweep.design.Design`) and makes one :class:`~racketdyn.sweep.task.SweepTask`
per design for :mod:`~racketdyn.sweep.run`.  Its SHA-256 marks the part files of its sweep.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, get_args

import numpy as np
from numpy.typing import NDArray

from racketdyn.__about__ import __version__
from racketdyn.ball import Ball
from racketdyn.contact import with_ball_string_cor
from racketdyn.errors import InputError, one_of, require_positive, require_speeds, require_words
from racketdyn.impact.approximate import STIFFNESS_READINGS, StiffnessReading
from racketdyn.impact.grid import STRING_BEDS, StringBed
from racketdyn.impact.hand import Hand
from racketdyn.impact.kernel import NUMBA_AVAILABLE
from racketdyn.impact.transient import COMPILED_SCHEME, Engine
from racketdyn.impact.transient import ENGINES as TRANSIENT_ENGINES
from racketdyn.io.racket_file import DEFAULT_RACKET_NAME
from racketdyn.io.racket_file import racket_to_dict as _racket_to_dict
from racketdyn.racket import (
    KGM2_TO_KGCM2,
    SUPPORTS,
    SWINGWEIGHT_AXIS_M,
    Racket,
    as_locations,
)
from racketdyn.racket_modal.beam import beam_mass_per_length
from racketdyn.sweep.design import Design, build_design, build_hand
from racketdyn.sweep.task import SweepTask, _check_method, _check_supports, task_inputs
from racketdyn.sweep.variables import HAND_VARIABLES, POINT_MASS, Variable

if TYPE_CHECKING:  # imported when a sweep has an uncertainty: xarray and scipy.stats cost ≈ 1 s
    from racketdyn.impact.uncertainty import Uncertainty

__all__ = ["MODES", "SweepSpec"]

SweepMode = Literal["full-factorial", "one-at-a-time"]
MODES: tuple[str, ...] = get_args(SweepMode)
MAX_DESIGNS = 100_000
SAMPLE_COST = {"approximate": 0.25, "transient": 1.0}
"""A sample's cost in nominal impacts, by method: the approximate method's samples run at once
(≈ 0.25 of a nominal prediction a sample, docs/uncertainty.md "Speed"), the transient
model's once each."""
SPEC_SCHEMA_VERSION = 1
DEFAULT_THRESHOLD_FRACTION = 0.9
_EXCLUSIVE = (("inertia_cg_kgm2", "swingweight_kgcm2"), ("roll_inertia_kgm2", "twistweight_kgcm2"))
_SWEPT_INPUTS: dict[str, tuple[str, ...]] = {
    "e_bg": ("e_bg",),
    "first_bending_hz": ("frame_stiffness_scale",),
    "roll_inertia_kgm2": ("roll_inertia_kgm2", "twistweight_kgcm2"),
    "hand_stiffness_n_per_m": ("hand.stiffness_n_per_m",),
    "hand_damping_ns_per_m": ("hand.damping_ns_per_m",),
    "hand_arm_mass_kg": ("hand.arm_mass_kg",),
}
"""The sweep variables whose value each uncertain input's ``range`` or ``values`` would replace
(absolute values, the same in every design)."""


@dataclass(frozen=True, eq=False)
class SweepSpec:
    """What a sweep computes: base racket and ball, impacts, variables, how to combine them.

    Parameters
    ----------
    racket : Racket
        The base racket.
    ball : Ball
        The base ball.
    locations : array_like, shape (n, 2)
        Impact points (x, y) on the string bed, m.
    ball_speeds : array_like
        Incoming ball speeds, m/s.
    racket_speeds : array_like
        Racket speeds at the impact point towards the ball (swing), m/s; each is combined with
        each ball speed.
    supports : sequence of str
        Support conditions (``free``, ``pinned``; ``hand`` with the transient method); one
        text of comma-separated names too (``"free,pinned"``).
    variables : sequence of Variable
        The swept variables.
    mode : {"full-factorial", "one-at-a-time"}
        Every combination of values, or each variable on its own around the base.
    labels : sequence of str, optional
        Point labels (default 1, 2, …).
    method : str
        Impact method, a key of :data:`METHODS` (``approximate`` or ``transient``).
    stiffness_reading : {"period", "tangent"}
        Reading of eq (10) (see :func:`racketdyn.impact.predict`; approximate method only).
    engine : {"auto", "compiled", "reference"}
        Engine of the transient method (:func:`racketdyn.impact.transient.predict_transient`):
        ``auto`` is ``compiled`` where numba is installed, else ``reference``, decided when the
        spec is made (:attr:`transient_engine`), so the hash, and with it resuming, tells the
        two apart.  Only ``auto`` with the approximate method.
    include_string_bed : bool
        Charge string-bed modes as vibration loss too.
    string_bed : {"uniform", "local"}
        The string bed's law over the face: the centre's at every point (the paper's, default)
        or each point's own from its strings' lengths
        (:func:`racketdyn.impact.grid.predict_by_point_law`; each design's racket's own).
    rigid : bool
        No modal model: a rigid racket.
    threshold_fraction : float
        Summary: the sweet area counts where the rebound ratio reaches this fraction of the
        best of the same face (:func:`racketdyn.sweep.sweet_area_cm2`).
    summary_ball_speed, summary_racket_speed : float, optional
        Summary: the speeds the figures show, m/s (default the middle ball speed listed and the
        first racket speed).
    name : str
        Free text.
    racket_source : str
        Where the base racket came from, for the record.
    uncertainty : Uncertainty, optional
        Uncertain inputs: each design's impacts get their mean, sd and 5–95 % band over the
        samples (:func:`racketdyn.impact.uncertainty.propagate` inside the design's task), and
        its face its best rebound ratio's and sweet area's band (docs/uncertainty.md, "Sweeps
        with uncertainty").  A normal spread (``sd``) is about each design's own value; a
        ``range`` or ``values`` of an input the sweep varies is refused (it would replace the
        design's value).  None (default): the nominal numbers alone, as without.
    uncertainty_source : str
        Where the uncertainty came from (``[uncertainty]`` of the spec, ``--uncertainty FILE``),
        for the record.
    """

    racket: Racket
    ball: Ball
    locations: NDArray[np.float64]
    ball_speeds: NDArray[np.float64]
    racket_speeds: NDArray[np.float64] = field(default_factory=lambda: np.zeros(1))
    supports: tuple[str, ...] = SUPPORTS
    variables: tuple[Variable, ...] = ()
    mode: SweepMode = "full-factorial"
    labels: tuple[str, ...] = ()
    method: str = "approximate"
    stiffness_reading: StiffnessReading = "period"
    engine: Engine = "auto"
    include_string_bed: bool = False
    string_bed: StringBed = "uniform"
    rigid: bool = False
    threshold_fraction: float = DEFAULT_THRESHOLD_FRACTION
    summary_ball_speed: float | None = None
    summary_racket_speed: float | None = None
    name: str = "sweep"
    racket_source: str = f"built-in {DEFAULT_RACKET_NAME}"
    uncertainty: Uncertainty | None = None
    uncertainty_source: str = ""

    def __post_init__(self) -> None:
        locations = as_locations(self.locations, "[impacts].points")
        if locations.shape[0] == 0:
            raise InputError("[impacts].points: give at least one impact point")
        self.racket.head.check_inside(locations, "[impacts]: point")
        object.__setattr__(self, "locations", locations)
        labels = tuple(self.labels) or tuple(str(i + 1) for i in range(locations.shape[0]))
        if len(labels) != locations.shape[0]:
            raise InputError(f"{len(labels)} labels given for {locations.shape[0]} impact points")
        object.__setattr__(self, "labels", labels)
        ball_speeds = require_speeds("[impacts].ball_speeds_mps", self.ball_speeds)
        racket_speeds = require_speeds("[impacts].racket_speeds_mps", self.racket_speeds)
        for key, speeds in (("ball_speeds_mps", ball_speeds), ("racket_speeds_mps", racket_speeds)):
            if np.unique(speeds).size != speeds.size:
                raise InputError(f"[impacts].{key}: a speed is listed twice")
        if np.any(ball_speeds[:, None] + racket_speeds[None, :] <= 0):
            raise InputError(
                "[impacts]: every ball speed + racket speed must be positive (the ball must reach "
                "the strings); a ball speed of 0 needs racket speeds above 0"
            )
        object.__setattr__(self, "ball_speeds", ball_speeds)
        object.__setattr__(self, "racket_speeds", racket_speeds)
        _check_method("[impacts].method", self.method)
        given: object = self.supports  # a text of one or several comma-separated names too
        named = require_words("supports", given) if isinstance(given, str) else self.supports
        supports = tuple(named)
        _check_supports("[variables].support", supports, self.method)
        object.__setattr__(self, "supports", supports)
        object.__setattr__(self, "variables", tuple(self.variables))
        one_of("mode", self.mode, MODES)
        one_of("[impacts].engine", self.engine, TRANSIENT_ENGINES)
        if self.engine != "auto" and self.method != "transient":
            raise InputError(
                f"[impacts].engine = '{self.engine}' is for method = 'transient' only (the "
                f"{self.method} method has one way to compute); leave it out"
            )
        if self.engine == "compiled" and not NUMBA_AVAILABLE:
            raise InputError(
                "[impacts].engine = 'compiled' needs numba (pip install numba); use 'reference'"
            )
        one_of("[impacts].stiffness_reading", self.stiffness_reading, STIFFNESS_READINGS)
        one_of("[impacts].string_bed", self.string_bed, STRING_BEDS)
        if self.string_bed == "local" and self.racket.strings.load_deflection_file is not None:
            raise InputError(
                "[impacts].string_bed = 'local' needs the strings' construction; the racket's "
                "string bed is a measured load-deflection file (a law at one point): use "
                "'uniform'"
            )
        names = [v.name for v in self.variables]
        for name in names:
            if name in HAND_VARIABLES and "hand" not in supports:
                raise InputError(
                    f"[variables].{name}: hand parameters change the 'hand' support only; add "
                    "'hand' to [variables].support (with [impacts].method = 'transient')"
                )
        if len(set(names)) != len(names):
            raise InputError("[variables]: a variable is listed twice (label point masses)")
        for first, second in _EXCLUSIVE:
            if first in names and second in names:
                raise InputError(f"[variables]: give {first} or {second}, not both")
        fraction = require_positive("[summary].threshold_fraction", self.threshold_fraction)
        if fraction > 1.0:
            raise InputError(f"[summary].threshold_fraction must lie in (0, 1] (got {fraction})")
        for key, value, listed in (
            ("ball_speed_mps", self.summary_ball_speed, ball_speeds),
            ("racket_speed_mps", self.summary_racket_speed, racket_speeds),
        ):
            if value is not None and not np.any(np.isclose(listed, value, rtol=0, atol=1e-9)):
                raise InputError(
                    f"[summary].{key} ({value}) must be one of the listed speeds "
                    f"({', '.join(f'{s:g}' for s in listed)})"
                )
        sizes = [len(v.values) for v in self.variables]
        count = math.prod(sizes) if self.mode == "full-factorial" else 1 + sum(sizes)
        if count > MAX_DESIGNS:
            raise InputError(
                f"[variables]: {count:,} designs is more than {MAX_DESIGNS:,}; sweep fewer "
                "values or use mode = 'one-at-a-time'"
            )
        # every variant must be a valid racket before anything runs: each value on its own
        # (the message names the variable), then every design
        base = [self.base_value(v) for v in self.variables]
        for k, variable in enumerate(self.variables):
            for candidate in variable.values:
                combo = [*base[:k], candidate, *base[k + 1 :]]
                try:
                    self._check_design(_settings(self.variables, combo))
                except InputError as error:
                    shown = ", ".join(
                        f"{c} = {x:g}" for c, x in zip(variable.coords, candidate, strict=True)
                    )
                    raise InputError(f"[variables].{variable.name}: {shown}: {error}") from None
        for design in self.designs:
            try:
                self._check_design(design.settings)
            except InputError as error:
                raise InputError(f"[variables]: design {design.describe()}: {error}") from None
        if self.uncertainty is not None:
            self._check_uncertainty(self.uncertainty)

    def _check_uncertainty(self, uncertainty: Uncertainty) -> None:
        """Spreads the designs can take: none that replaces a swept value, each drawable on
        the base design (a rigid racket has no bending mode, a measured bed no scale); a
        message names the table where it came from (the spec's, or ``--uncertainty FILE``)."""
        from racketdyn.impact.calibration import PARAMETERS
        from racketdyn.impact.uncertainty import draw

        source = self.uncertainty_source
        from_spec = not source or source.startswith("[uncertainty]")

        def where(name: str) -> str:
            return f"[uncertainty.{name}]" if from_spec else f"{source.split(' (')[0]} [{name}]"

        swept = {v.kind for v in self.variables}
        for spread in uncertainty.spreads:
            clash = sorted(swept & set(_SWEPT_INPUTS.get(spread.name, ())))
            if clash and spread.sd is None:
                raise InputError(
                    f"{where(spread.name)}: a range or values replace the swept {clash[0]} in "
                    "every design; give sd = x (a spread about each design's value) or leave "
                    "it out"
                )
            if spread.name == "first_bending_hz" and self.rigid:
                raise InputError(
                    f"{where(spread.name)}: a rigid racket ([impacts] rigid = true) has no "
                    "bending mode; leave it out or drop rigid"
                )
        try:
            inputs = task_inputs(self.task(self.designs[0]))
            draw(uncertainty, inputs)
            if any(s.name == "string_stiffness_scale" for s in uncertainty.spreads):
                _ = PARAMETERS["string_stiffness_scale"].set(inputs, 1.01).effective_racket
        except InputError as error:
            table = "[uncertainty]" if from_spec else source.split(" (")[0]
            raise InputError(f"{table}: {error}") from None

    def _check_design(self, settings: tuple[tuple[str, float], ...]) -> None:
        racket, _, _ = build_design(self.racket, self.ball, self.variables, settings)
        if "hand" in self.supports:
            build_hand(self.variables, settings)
        if not self.rigid and racket.modal_model_file is None:
            beam_mass_per_length(
                racket.length_m, racket.mass_kg, racket.balance_m, racket.inertia_cg_kgm2
            )

    @property
    def transient_engine(self) -> Engine:
        """The transient method's engine as run here: ``compiled`` or ``reference``."""
        if self.engine == "auto":
            return "compiled" if NUMBA_AVAILABLE else "reference"
        return self.engine

    # --- designs ----------------------------------------------------------------------------
    def base_value(self, variable: Variable) -> tuple[float, ...]:
        """The base design's value of a variable (a point mass: mass 0 at its first position).

        Parameters
        ----------
        variable : Variable
            One of the spec's variables.
        """
        if variable.kind == POINT_MASS:
            return (0.0, *variable.values[0][1:])
        if variable.kind in HAND_VARIABLES:
            return (float(getattr(Hand(), variable.kind.removeprefix("hand."))),)
        racket = self.racket
        base = {
            "mass_kg": racket.mass_kg,
            "balance_m": racket.balance_m,
            "inertia_cg_kgm2": racket.inertia_cg_kgm2,
            "swingweight_kgcm2": (
                racket.inertia_cg_kgm2
                + racket.mass_kg * (racket.balance_m - SWINGWEIGHT_AXIS_M) ** 2
            )
            * KGM2_TO_KGCM2,
            "roll_inertia_kgm2": racket.roll_inertia_kgm2,
            "twistweight_kgcm2": racket.roll_inertia_kgm2 * KGM2_TO_KGCM2,
            "grip_m": racket.grip_m,
            "frame_stiffness_scale": 1.0,
            "tension_n": racket.strings.tension_n,
            "e_bg": float(with_ball_string_cor(racket, self.ball).e_bg_at(20.0)),
        }
        return (float(base[variable.kind]),)

    @cached_property
    def designs(self) -> tuple[Design, ...]:
        """The design variants, in the order of the ``design`` dimension.

        Full factorial: every combination, the first variable varying slowest.  One at a time:
        the base design first, then each variable's values other than its base value with the
        other variables at their base values.
        """
        if self.mode == "full-factorial":
            combos = itertools.product(*(v.values for v in self.variables))
            return tuple(
                Design(i, _settings(self.variables, combo), "factorial")
                for i, combo in enumerate(combos)
            )
        base = [self.base_value(v) for v in self.variables]
        designs = [Design(0, _settings(self.variables, base), "base")]
        for k, variable in enumerate(self.variables):
            for value in variable.values:
                if _same_value(variable, value, base[k]):
                    continue
                combo = [*base[:k], value, *base[k + 1 :]]
                designs.append(
                    Design(len(designs), _settings(self.variables, combo), variable.name)
                )
        return tuple(designs)

    @property
    def n_impacts(self) -> int:
        """Impacts in the sweep: designs × points × speeds × racket speeds × supports."""
        return len(self.designs) * self.impacts_per_design

    @property
    def impacts_per_design(self) -> int:
        """Impacts per design: points × speeds × racket speeds × supports."""
        return int(
            self.locations.shape[0]
            * self.ball_speeds.size
            * self.racket_speeds.size
            * len(self.supports)
        )

    @property
    def work_per_design(self) -> float:
        """A design's work in nominal impacts: :attr:`impacts_per_design`, and with an
        uncertainty its samples too (:data:`SAMPLE_COST` of a nominal impact each), to size
        the tasks and choose the engine."""
        if self.uncertainty is None:
            return float(self.impacts_per_design)
        cost = SAMPLE_COST.get(self.method, 1.0)
        return self.impacts_per_design * (1.0 + cost * self.uncertainty.samples)

    def task(self, design: Design) -> SweepTask:
        """The picklable task that computes one design.

        Parameters
        ----------
        design : Design
            One of :attr:`designs`.
        """
        return SweepTask(
            task_id=design.task_id,
            racket=self.racket,
            ball=self.ball,
            variables=self.variables,
            settings=design.settings,
            locations=self.locations,
            ball_speeds=self.ball_speeds,
            racket_speeds=self.racket_speeds,
            supports=self.supports,
            method=self.method,
            stiffness_reading=self.stiffness_reading,
            include_string_bed=self.include_string_bed,
            string_bed=self.string_bed,
            rigid=self.rigid,
            engine=self.transient_engine,
            uncertainty=self.uncertainty,
            threshold_fraction=self.threshold_fraction,
        )

    # --- record -----------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """Plain, JSON-ready data: everything the results depend on, plus the summary options.

        Files the racket refers to (modal model, load–deflection) appear by name and SHA-256,
        so the record does not depend on where the files sit.
        """
        return {
            **self._results_dict(),
            "name": self.name,
            "racket_source": self.racket_source,
            "summary": {
                "threshold_fraction": self.threshold_fraction,
                "ball_speed_mps": self.summary_ball_speed,
                "racket_speed_mps": self.summary_racket_speed,
            },
        }

    def _results_dict(self) -> dict[str, Any]:
        racket = _racket_to_dict(self.racket)
        racket.pop("derived")
        racket["modal_model_file"] = _file_record(self.racket.modal_model_file)
        racket["strings"]["load_deflection_file"] = _file_record(
            self.racket.strings.load_deflection_file
        )
        engine: dict[str, str] = {}
        if self.method == "transient":
            engine["engine"] = self.transient_engine
            if self.transient_engine == "compiled":  # its numerics changed in issue 16
                engine["compiled_scheme"] = COMPILED_SCHEME
        return {
            "format": "racketdyn-sweep-spec",
            "schema_version": SPEC_SCHEMA_VERSION,
            "racket": racket,
            "ball": {
                "mass_kg": self.ball.mass_kg,
                "diameter_m": self.ball.diameter_m,
                "e_bg": self.ball.e_bg,
                "restoring_force": self.ball.restoring_force.as_dict(),
            },
            "points": {"labels": list(self.labels), "locations_m": self.locations.tolist()},
            "ball_speeds_mps": self.ball_speeds.tolist(),
            "racket_speeds_mps": self.racket_speeds.tolist(),
            "supports": list(self.supports),
            "variables": [v.to_dict() for v in self.variables],
            "mode": self.mode,
            "method": self.method,
            **engine,
            "stiffness_reading": self.stiffness_reading,
            "include_string_bed": self.include_string_bed,
            "string_bed": self.string_bed,
            "rigid": self.rigid,
            **self._uncertainty_dict(),
        }

    def _uncertainty_dict(self) -> dict[str, Any]:
        """The uncertainty as the results depend on it (nothing without one: a sweep without
        keeps its hash); the sweet area's band depends on the threshold too."""
        if self.uncertainty is None:
            return {}
        u = self.uncertainty
        return {
            "uncertainty": {
                "samples": u.samples,
                "seed": u.seed,
                "sampler": u.sampler,
                "spreads": [
                    {
                        "name": s.name,
                        "sd": s.sd,
                        "range": None if s.bounds is None else list(s.bounds),
                        "values": list(s.values),
                    }
                    for s in u.spreads
                ],
                "threshold_fraction": self.threshold_fraction,
            }
        }

    def uncertainty_record(self) -> dict[str, Any] | None:
        """What was sampled and where it came from, for run.json (None: no uncertainty)."""
        if self.uncertainty is None:
            return None
        return {**self.uncertainty.record(), "source": self.uncertainty_source}

    @cached_property
    def sha256(self) -> str:
        """SHA-256 of what the results depend on (:meth:`to_dict` less name and summary) and
        the racketdyn version: a part file with this hash is a finished task of this sweep."""
        text = json.dumps(
            {"spec": self._results_dict(), "racketdyn_version": __version__},
            sort_keys=True,
            separators=(",", ":"),
        )
        return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _settings(
    variables: Sequence[Variable], combo: Sequence[tuple[float, ...]]
) -> tuple[tuple[str, float], ...]:
    return tuple(
        (coord, float(x))
        for variable, value in zip(variables, combo, strict=True)
        for coord, x in zip(variable.coords, value, strict=True)
    )


def _same_value(variable: Variable, value: tuple[float, ...], base: tuple[float, ...]) -> bool:
    if variable.kind == POINT_MASS:
        return value[0] == 0.0  # no mass is the base, wherever it would sit
    return value == base


def _file_record(path: Path | None) -> dict[str, str] | None:
    if path is None:
        return None
    try:
        digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError as error:
        raise InputError(f"{path}: cannot be read ({error})") from None
    return {"name": Path(path).name, "sha256": digest}
