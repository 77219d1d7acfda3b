"""Design sweeps: many racket variants × impact points × speeds × swing, on any executor.

A sweep answers a racket maker's "what if" — 5 g of lead at 12 o'clock, a 10 % softer frame,
20 N less tension — with a full map of predictions per variant.  A :class:`SweepSpec` (read from
TOML by :func:`load_sweep_spec`, schema in docs/sweep-file.md) names a base racket and ball, the
impact points and speeds, and the variables with their values; :meth:`SweepSpec.designs` lists
the design variants, as a full factorial or one variable at a time around the base.

:func:`run_sweep` makes one task per design — :func:`run_task`, a pure function of plain
picklable inputs (:class:`SweepTask`) that builds the variant's racket, ball, modal model and
contact law and calls :func:`racketdyn.impact.predict` — and submits the tasks to any
:class:`concurrent.futures.Executor`: :class:`SerialExecutor` in this process, a
:class:`~concurrent.futures.ProcessPoolExecutor`, or Dask through
``dask.distributed.Client.get_executor()``.  :func:`make_executor` builds each of these (the
``racketdyn sweep`` command line calls it).  Each finished task is written at once to
``out_dir/parts/<task-id>.nc``; a rerun skips the tasks whose part carries the same spec hash,
so an interrupted sweep resumes.  A failed task is retried once, then recorded (dataset
attributes and ``failures.json``) while the other results are kept.  The parts are combined,
always from the files, into ``out_dir/sweep.nc``: an :mod:`xarray` dataset with dimensions
``(design, point, speed, racket_speed, support)``, so every engine gives the same file.

Summary figures (:func:`write_summary_figures`) plot, for each variable, the rebound ratio at the
face centre and the area of the face with a rebound ratio above a threshold against the variable,
per support.

The impact method is a parameter (``SweepSpec.method``, :data:`METHODS`): ``approximate``
(:func:`racketdyn.impact.predict`) or ``transient``
(:func:`racketdyn.impact.transient.predict_transient`).  The transient method also takes the
``hand`` support, a grip held by a hand and arm (:class:`racketdyn.impact.hand.Hand`), whose
parameters are sweepable (:data:`HAND_VARIABLES`).
"""

from __future__ import annotations

import hashlib
import itertools
import json
import logging
import math
import os
import time
import traceback
from collections import deque
from collections.abc import Callable, Iterator, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, Executor, Future, wait
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, field, replace
from datetime import UTC, datetime
from functools import cached_property, lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, ParamSpec, TypeVar, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray
from threadpoolctl import ThreadpoolController  # type: ignore[import-untyped]

from racketdyn.__about__ import __version__
from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law
from racketdyn.errors import InputError, one_of, require_positive, require_speeds
from racketdyn.impact.approximate import STIFFNESS_READINGS, StiffnessReading, predict
from racketdyn.impact.hand import Hand
from racketdyn.impact.result import (
    STATUS_BEYOND_LAW,
    STATUS_OK,
    STATUS_VIBRATION_LOSS,
    ImpactResult,
)
from racketdyn.impact.transient import (
    STATUS_NO_SEPARATION,
    TRANSIENT_SUPPORTS,
    predict_transient,
)
from racketdyn.io.racket_file import DEFAULT_RACKET_NAME, default_racket, load_racket, read_toml
from racketdyn.io.racket_file import racket_to_dict as _racket_to_dict
from racketdyn.io.tables import read_load_deflection, read_points
from racketdyn.modal import ModalModel, builtin_modal_model
from racketdyn.modal.beam import beam_mass_per_length
from racketdyn.racket import (
    KGM2_TO_KGCM2,
    SUPPORTS,
    SWINGWEIGHT_AXIS_M,
    HeadEllipse,
    PointMass,
    Racket,
    as_locations,
)

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes

__all__ = [
    "ENGINES",
    "HAND_VARIABLES",
    "METHODS",
    "METHOD_SUPPORTS",
    "MODES",
    "SCALAR_VARIABLES",
    "SERIAL_IMPACT_LIMIT",
    "STATUS_CODES",
    "Design",
    "EngineKind",
    "SerialExecutor",
    "SweepSpec",
    "SweepTask",
    "TaskOutput",
    "Variable",
    "build_design",
    "build_hand",
    "factorial_view",
    "load_sweep_spec",
    "make_executor",
    "plot_centre_rebound",
    "plot_sweet_area",
    "run_sweep",
    "run_task",
    "summary_metrics",
    "sweep_spec_from_dict",
    "variable_designs",
    "write_summary_figures",
]

log = logging.getLogger(__name__)

P = ParamSpec("P")
T = TypeVar("T")

EngineKind = Literal["serial", "process", "dask-local", "dask"]
"""Where sweep tasks run (:func:`make_executor`): this process, a local process pool, a local
Dask cluster, or a running Dask scheduler."""
ENGINES: tuple[str, ...] = get_args(EngineKind)
SweepMode = Literal["full-factorial", "one-at-a-time"]
MODES: tuple[str, ...] = get_args(SweepMode)
ProgressCallback = Callable[[int, int], None]
"""Called as ``progress(done, total)`` with the number of design tasks finished (run, resumed
or failed for good) and the number of tasks."""

SERIAL_IMPACT_LIMIT = 50_000
"""Below this many impacts to compute, ``run_sweep(executor=None)`` runs in this process;
above it, in a pool of two processes."""
DEFAULT_WORKERS = 2
MAX_DESIGNS = 100_000
SPEC_SCHEMA_VERSION = 1
PART_FORMAT = "racketdyn-sweep-part"
SWEEP_FORMAT = "racketdyn-sweep"
DEFAULT_THRESHOLD_FRACTION = 0.9

SCALAR_VARIABLES: dict[str, str] = {
    "mass_kg": "strung mass without the point masses, kg (balance and inertia held)",
    "balance_m": "balance point from the butt, m (inertia about it held)",
    "inertia_cg_kgm2": "inertia about the balance point, across the handle, kg·m²",
    "swingweight_kgcm2": "swingweight (axis 100 mm from the butt) without point masses, kg·cm²",
    "roll_inertia_kgm2": "inertia about the long axis, kg·m²",
    "twistweight_kgcm2": "twistweight without point masses, kg·cm²",
    "grip_m": "the hand: pivot of the pinned support from the butt, m",
    "frame_stiffness_scale": "frame stiffness factor s: frame-mode frequencies × √s",
    "tension_n": "string tension, N",
    "e_bg": "ball–string COR on a head-clamped racket",
}
"""Variables that take one number per value, and what each changes."""
HAND_VARIABLES: dict[str, str] = {
    "hand.arm_mass_kg": "mass of the arm holding the grip, kg (racketdyn.impact.hand.Hand)",
    "hand.stiffness_n_per_m": "total stiffness between handle and arm, N/m",
    "hand.damping_ns_per_m": "total damping between handle and arm, N·s/m",
}
"""Hand parameters: one number per value, for the ``hand`` support of the transient method;
the other fields of :class:`~racketdyn.impact.hand.Hand` keep their defaults."""
METHOD_SUPPORTS: dict[str, tuple[str, ...]] = {
    "approximate": SUPPORTS,
    "transient": TRANSIENT_SUPPORTS,
}
"""Supports each impact method takes."""
POINT_MASS = "point_mass"
SUPPORT = "support"
POINT_MASS_KEYS = ("mass_kg", "x_m", "y_m", "clock", "label")
_RACKET_FIELDS = ("mass_kg", "balance_m", "inertia_cg_kgm2", "roll_inertia_kgm2", "grip_m")
_EXCLUSIVE = (("inertia_cg_kgm2", "swingweight_kgcm2"), ("roll_inertia_kgm2", "twistweight_kgcm2"))

STATUS_FAILED = "task failed"
STATUS_CODES: dict[str, int] = {
    STATUS_OK: 0,
    STATUS_VIBRATION_LOSS: 1,
    STATUS_BEYOND_LAW: 2,
    STATUS_FAILED: 3,
    STATUS_NO_SEPARATION: 4,
}
"""Integer codes of the ``status`` variable of a sweep dataset (CF ``flag_values``)."""

_IMPACT_VARIABLES: dict[str, tuple[str, str, str]] = {
    # dataset name: (ImpactResult attribute, units, long name)
    "stiffness_n_per_m": ("stiffness", "N m-1", "compound ball+string stiffness K_GB (eqs 9-10)"),
    "contact_time_s": ("contact_time", "s", "contact time T_c (eq 7)"),
    "mean_force_n": ("mean_force", "N", "equivalent force F_MEAN (eqs 8-10)"),
    "peak_force_n": ("peak_force", "N", "peak force F_MAX (eq 11)"),
    "vibration_energy_j": ("vibration_energy", "J", "frame vibration energy after impact (eq 12)"),
    "cor": ("cor", "1", "ball-racket coefficient of restitution e_r"),
    "rebound_ratio": ("rebound_ratio", "1", "rebound power coefficient e"),
    "rebound_speed_mps": ("rebound_speed", "m s-1", "outgoing ball speed"),
    "peak_deflection_m": ("peak_deflection", "m", "peak compound deflection X_p"),
}
_DERIVED = {
    "racket_mass_kg": ("mass_kg", "kg", "racket mass with point masses"),
    "racket_balance_m": ("balance_m", "m", "balance point with point masses"),
    "racket_inertia_cg_kgm2": ("inertia_cg_kgm2", "kg m2", "inertia about the balance point"),
    "racket_swingweight_kgcm2": ("swingweight_kgcm2", "kg cm2", "swingweight"),
    "racket_twistweight_kgcm2": ("twistweight_kgcm2", "kg cm2", "twistweight"),
    "racket_centre_of_percussion_m": (
        "centre_of_percussion_m",
        "m",
        "centre of percussion for the grip pivot",
    ),
}
_IMPACT_DIMS = ("design", "point", "speed", "racket_speed", "support")


# --- variables and the spec -----------------------------------------------------------------
@dataclass(frozen=True)
class Variable:
    """One swept quantity and its values.

    Build one with :meth:`scalar` or :meth:`point_mass` rather than directly.

    Parameters
    ----------
    name : str
        The variable's name: a key of :data:`SCALAR_VARIABLES` or :data:`HAND_VARIABLES`,
        ``"point_mass"`` or ``"point_mass_<label>"``.
    kind : str
        A key of :data:`SCALAR_VARIABLES` or :data:`HAND_VARIABLES`, or ``"point_mass"``.
    coords : tuple of str
        Names of the design coordinates this variable sets (one for a scalar; for a point mass
        ``<name>_mass_kg``, ``<name>_x_m``, ``<name>_y_m`` and ``<name>_clock`` if placed by
        clock hour).
    values : tuple of tuple of float
        Each value, one number per coordinate (SI units as the coordinate names say).
    axis : str
        The coordinate the summary figures plot against.
    """

    name: str
    kind: str
    coords: tuple[str, ...]
    values: tuple[tuple[float, ...], ...]
    axis: str

    def __post_init__(self) -> None:
        if not self.values:
            raise InputError(f"[variables].{self.name}: give at least one value")
        if any(len(v) != len(self.coords) for v in self.values):
            raise InputError(f"[variables].{self.name}: one number per coordinate in each value")
        if len(set(self.values)) != len(self.values):
            raise InputError(f"[variables].{self.name}: a value is listed twice")
        if self.axis not in self.coords:
            raise InputError(f"[variables].{self.name}: axis {self.axis!r} is not a coordinate")

    @classmethod
    def scalar(cls, name: str, values: ArrayLike) -> Variable:
        """A variable of one number per value.

        Parameters
        ----------
        name : str
            A key of :data:`SCALAR_VARIABLES` or :data:`HAND_VARIABLES`.
        values : array_like
            Its values, in the unit its name carries.
        """
        one_of("variable", name, {**SCALAR_VARIABLES, **HAND_VARIABLES})
        numbers = _finite_values(f"[variables].{name}", values)
        return cls(name, name, (name,), tuple((v,) for v in numbers), name)

    @classmethod
    def point_mass(
        cls,
        mass_kg: ArrayLike,
        x_m: ArrayLike | None = None,
        y_m: ArrayLike | None = None,
        clock: ArrayLike | None = None,
        label: str = "",
        head: HeadEllipse | None = None,
    ) -> Variable:
        """A point mass (lead tape) whose mass and/or position is swept.

        Each of ``mass_kg``, ``x_m``, ``y_m`` and ``clock`` is one number or a list; lists are
        taken together, element by element, and must have one length.  A mass of 0 means no
        mass (the base racket).

        Parameters
        ----------
        mass_kg : float or array_like
            Mass, kg (0 or more).
        x_m, y_m : float or array_like, optional
            Position, m (x from the butt, y across the long axis).  Give these or ``clock``.
        clock : float or array_like, optional
            Position as a clock hour on the string-bed ellipse seen from the hitting face, tip
            up: 12 the tip, 3 the right-hand side (y < 0), 6 the throat, 9 the left (y > 0).
        label : str
            Names the variable ``point_mass_<label>`` (several point masses need labels).
        head : HeadEllipse
            The head, needed to place by ``clock``.
        """
        name = f"{POINT_MASS}_{label}" if label else POINT_MASS
        where = f"[variables].{name}"
        if label and not label.replace("_", "").isalnum():
            raise InputError(f"{where}.label must be letters, digits and _ (got {label!r})")
        if clock is not None and (x_m is not None or y_m is not None):
            raise InputError(f"{where}: give clock or x_m (and y_m), not both")
        if clock is None and x_m is None:
            raise InputError(f"{where}: give the position as x_m (and y_m) or clock")
        columns: dict[str, NDArray[np.float64]] = {
            "mass_kg": _finite_values(f"{where}.mass_kg", mass_kg)
        }
        if clock is not None:
            columns["clock"] = _finite_values(f"{where}.clock", clock)
        else:
            columns["x_m"] = _finite_values(f"{where}.x_m", x_m)
            columns["y_m"] = _finite_values(f"{where}.y_m", 0.0 if y_m is None else y_m)
        lengths = {len(c) for c in columns.values()} - {1}
        if len(lengths) > 1:
            sizes = ", ".join(f"{k}: {len(c)}" for k, c in columns.items())
            raise InputError(f"{where}: lists must have one length ({sizes})")
        n = lengths.pop() if lengths else 1
        full = {k: np.broadcast_to(c, (n,)) for k, c in columns.items()}
        if np.any(full["mass_kg"] < 0):
            raise InputError(f"{where}.mass_kg must be 0 or more, kg (got {mass_kg!r})")
        if "clock" in full:
            if head is None:
                raise InputError(f"{where}.clock needs the racket's head to place the mass")
            angle = np.deg2rad(np.mod(full["clock"], 12.0) * 30.0)
            cos, sin = (np.where(np.abs(f) < 1e-12, 0.0, f) for f in (np.cos(angle), np.sin(angle)))
            full["x_m"] = head.centre_x_m + head.half_length_m * cos
            full["y_m"] = head.centre_y_m - head.half_width_m * sin
        order = ["mass_kg", "x_m", "y_m"] + (["clock"] if "clock" in full else [])
        coords = tuple(f"{name}_{k}" for k in order)
        values = tuple(tuple(float(full[k][i]) for k in order) for i in range(n))
        # plot against the first of mass, clock, x, y whose values are all different
        axis = next(
            (
                f"{name}_{k}"
                for k in ("mass_kg", "clock", "x_m", "y_m")
                if k in full and np.unique(full[k]).size == n
            ),
            None,
        )
        if axis is None:
            raise InputError(
                f"{where}: the values of one of mass_kg, clock, x_m or y_m must all differ"
            )
        return cls(name, POINT_MASS, coords, values, axis)

    def to_dict(self) -> dict[str, Any]:
        """Plain data for the spec record."""
        return {
            "name": self.name,
            "kind": self.kind,
            "coords": list(self.coords),
            "values": [list(v) for v in self.values],
            "axis": self.axis,
        }


@dataclass(frozen=True)
class Design:
    """One design variant: its index, task id, coordinate values and what it varies.

    Parameters
    ----------
    index : int
        Position along the ``design`` dimension.
    settings : tuple of (str, float)
        Every variable coordinate and its value in this design.
    varied : str
        One-at-a-time: the variable this design varies (``"base"`` for the base design);
        full factorial: ``"factorial"``.
    """

    index: int
    settings: tuple[tuple[str, float], ...]
    varied: str

    @property
    def task_id(self) -> str:
        """File-safe identifier of the design's task, ``design-00042``."""
        return f"design-{self.index:05d}"

    def describe(self) -> str:
        """The settings as ``name = value`` text."""
        return ", ".join(f"{k} = {v:g}" for k, v in self.settings) or "the base design"


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
        Support conditions (``free``, ``pinned``; ``hand`` with the transient method).
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
    include_string_bed : bool
        Charge string-bed modes as vibration loss too.
    rigid : bool
        No modal model: a rigid racket.
    threshold_fraction : float
        Summary: the face area counts where the rebound ratio reaches this fraction of the
        best of the sweep.
    summary_ball_speed, summary_racket_speed : float, optional
        Summary: the speeds the figures show, m/s (default the middle ball speed listed and the
        first racket speed).
    name : str
        Free text.
    racket_source : str
        Where the base racket came from, for the record.
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
    include_string_bed: bool = False
    rigid: bool = False
    threshold_fraction: float = DEFAULT_THRESHOLD_FRACTION
    summary_ball_speed: float | None = None
    summary_racket_speed: float | None = None
    name: str = "sweep"
    racket_source: str = f"built-in {DEFAULT_RACKET_NAME}"

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
        given: object = self.supports  # a lone name is accepted too
        supports = (given,) if isinstance(given, str) else tuple(self.supports)
        _check_supports("[variables].support", supports, self.method)
        object.__setattr__(self, "supports", supports)
        object.__setattr__(self, "variables", tuple(self.variables))
        one_of("mode", self.mode, MODES)
        one_of("[impacts].stiffness_reading", self.stiffness_reading, STIFFNESS_READINGS)
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

    def _check_design(self, settings: tuple[tuple[str, float], ...]) -> None:
        racket, _, _ = build_design(self.racket, self.ball, self.variables, settings)
        if "hand" in self.supports:
            build_hand(self.variables, settings)
        if not self.rigid and racket.modal_model_file is None:
            beam_mass_per_length(
                racket.length_m, racket.mass_kg, racket.balance_m, racket.inertia_cg_kgm2
            )

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
            "e_bg": self.ball.e_bg,
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
            rigid=self.rigid,
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
            "stiffness_reading": self.stiffness_reading,
            "include_string_bed": self.include_string_bed,
            "rigid": self.rigid,
        }

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


def _finite_values(where: str, values: ArrayLike | None) -> NDArray[np.float64]:
    try:
        array = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"{where} must be numbers (got {values!r})") from None
    if array.ndim != 1 or array.size == 0:
        raise InputError(f"{where}: give one or more numbers (got {values!r})")
    if not np.all(np.isfinite(array)):
        raise InputError(f"{where} must be finite numbers (got {values!r})")
    return array


# --- building a design ----------------------------------------------------------------------
def build_design(
    racket: Racket,
    ball: Ball,
    variables: Sequence[Variable],
    settings: Sequence[tuple[str, float]],
) -> tuple[Racket, Ball, float]:
    """The racket and ball of one design, and the frame-stiffness scale left to apply.

    Racket fields are replaced first (mass, balance, inertias, grip, tension); a swingweight
    gives the inertia about the balance point with the design's mass and balance,
    ``I_G = SW − M (x_G − 0.1 m)²``; point masses of positive mass are added to the racket's
    own.  A frame-stiffness scale s multiplies the built-in model's ``first_bending_hz`` and
    ``twisting_hz`` by √s (uniform stiffness scaling at fixed mass); for a racket with a modal
    model file it is returned for the task to scale the file's frame modes.

    Parameters
    ----------
    racket, ball : Racket, Ball
        The base racket and ball.
    variables : sequence of Variable
        The sweep's variables.
    settings : sequence of (str, float)
        The design's coordinate values (:attr:`Design.settings`).

    Returns
    -------
    racket : Racket
        The design's racket.
    ball : Ball
        The design's ball.
    file_model_scale : float
        Frame-stiffness scale still to apply to a modal model file (1 for the built-in model).
    """
    values = dict(settings)
    changes: dict[str, Any] = {}
    for name in _RACKET_FIELDS:
        if name in values:
            changes[name] = values[name]
    if "twistweight_kgcm2" in values:
        changes["roll_inertia_kgm2"] = values["twistweight_kgcm2"] / KGM2_TO_KGCM2
    if "swingweight_kgcm2" in values:
        mass = changes.get("mass_kg", racket.mass_kg)
        balance = changes.get("balance_m", racket.balance_m)
        swing = values["swingweight_kgcm2"]
        inertia = swing / KGM2_TO_KGCM2 - mass * (balance - SWINGWEIGHT_AXIS_M) ** 2
        if inertia <= 0:
            raise InputError(
                f"swingweight_kgcm2 ({swing:g}) must exceed M (x_G - 0.1 m)² = "
                f"{mass * (balance - SWINGWEIGHT_AXIS_M) ** 2 * KGM2_TO_KGCM2:.1f} kg·cm²"
            )
        changes["inertia_cg_kgm2"] = inertia
    if "tension_n" in values:
        changes["strings"] = replace(racket.strings, tension_n=values["tension_n"])
    added = []
    for variable in variables:
        if variable.kind == POINT_MASS:
            mass_kg, x_m, y_m = (values[c] for c in variable.coords[:3])
            if mass_kg > 0:
                added.append(PointMass(mass_kg, x_m, y_m, variable.name))
    if added:
        changes["point_masses"] = racket.point_masses + tuple(added)
    scale = values.get("frame_stiffness_scale", 1.0)
    if not (math.isfinite(scale) and scale > 0):
        raise InputError(f"frame_stiffness_scale must be a positive number (got {scale!r})")
    file_model_scale = 1.0
    if scale != 1.0:
        if racket.modal_model_file is None:
            changes["first_bending_hz"] = racket.first_bending_hz * math.sqrt(scale)
            changes["twisting_hz"] = racket.twisting_hz * math.sqrt(scale)
        else:
            file_model_scale = scale
    design_racket = replace(racket, **changes) if changes else racket
    design_ball = replace(ball, e_bg=values["e_bg"]) if "e_bg" in values else ball
    return design_racket, design_ball, file_model_scale


def build_hand(variables: Sequence[Variable], settings: Sequence[tuple[str, float]]) -> Hand:
    """The hand of one design (``hand`` support of the transient method).

    The design's hand variables (:data:`HAND_VARIABLES`) set their fields of
    :class:`~racketdyn.impact.hand.Hand`; the other fields keep the defaults.

    Parameters
    ----------
    variables : sequence of Variable
        The sweep's variables.
    settings : sequence of (str, float)
        The design's coordinate values (:attr:`Design.settings`).

    Returns
    -------
    Hand
        The design's hand (InputError if its values are not a valid hand).
    """
    values = dict(settings)
    fields = {
        variable.kind.removeprefix("hand."): values[variable.kind]
        for variable in variables
        if variable.kind in HAND_VARIABLES
    }
    return Hand(**fields)


# --- the task -------------------------------------------------------------------------------
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
    rigid : bool
        No modal model.
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
    """

    task_id: str
    arrays: dict[str, NDArray[Any]]
    reduced_mass_kg: NDArray[np.float64]
    mode_names: tuple[str, ...]
    mode_frequency_hz: NDArray[np.float64]
    attempt: int = 1
    elapsed_s: float = 0.0


def _approximate(
    racket: Racket,
    ball: Ball,
    model: ModalModel | None,
    law: RestoringForce,
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
    )


def _transient(
    racket: Racket,
    ball: Ball,
    model: ModalModel | None,
    law: RestoringForce,
    task: SweepTask,
) -> ImpactResult:
    """The transient simulation over points × (ball speed, racket speed) pairs × supports.

    The ``hand`` support holds the grip with the design's hand (:func:`build_hand`); the
    engine is ``auto`` (compiled where numba is installed).
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
    )


ImpactMethod = Callable[[Racket, Ball, ModalModel | None, RestoringForce, SweepTask], ImpactResult]
METHODS: dict[str, ImpactMethod] = {"approximate": _approximate, "transient": _transient}
"""Impact methods a sweep can run, by name.  Each takes the design's racket, ball, modal model
(None: rigid), compound law and the task, and returns an :class:`ImpactResult` over points ×
(ball speed, racket speed) pairs (ball speed slowest) × supports.  The supports each takes are
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
    with _blas_controller().limit(limits=1, user_api="blas"), _quiet(*_PREDICT_LOGS):
        racket, ball, file_model_scale = build_design(
            task.racket, task.ball, task.variables, task.settings
        )
        model = None if task.rigid else _modal_model(racket, file_model_scale)
        law = _compound_law(racket, ball)
        result = METHODS[task.method](racket, ball, model, law, task)
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


_PREDICT_LOGS = ("racketdyn.impact.approximate", "racketdyn.impact.transient")


@contextmanager
def _quiet(*logger_names: str) -> Iterator[None]:
    """Drop loggers' warnings for a while: predict warns once per call (predict_transient once
    per impact) about impacts whose results are NaN; a sweep counts them from the status codes
    and warns once instead (and not from worker processes whose logging nobody configured)."""

    def below_error(record: logging.LogRecord) -> bool:
        return record.levelno >= logging.ERROR

    loggers = [logging.getLogger(name) for name in logger_names]
    for logger in loggers:
        logger.addFilter(below_error)
    try:
        yield
    finally:
        for logger in loggers:
            logger.removeFilter(below_error)


# --- executors ------------------------------------------------------------------------------
class SerialExecutor(Executor):
    """An executor that runs each task in this process, at once, when it is submitted."""

    def submit(self, fn: Callable[P, T], /, *args: P.args, **kwargs: P.kwargs) -> Future[T]:
        """Run ``fn(*args, **kwargs)`` now; return a finished future with its result or error.

        Parameters
        ----------
        fn : callable
            The task.
        *args, **kwargs
            Its arguments.
        """
        future: Future[T] = Future()
        try:
            result = fn(*args, **kwargs)
        except Exception as error:  # the future carries it, as a pool's would
            future.set_exception(error)
        else:
            future.set_result(result)
        return future


@contextmanager
def make_executor(
    kind: EngineKind, workers: int = DEFAULT_WORKERS, scheduler: str | None = None
) -> Iterator[Executor]:
    """An executor for :func:`run_sweep`, as a context manager that shuts it down on exit.

    The ``racketdyn sweep`` command line calls this: ``--serial`` → ``serial``, ``--workers N``
    → ``process``, ``--dask-local N`` → ``dask-local``, ``--scheduler tcp://HOST:PORT`` →
    ``dask``.

    Parameters
    ----------
    kind : {"serial", "process", "dask-local", "dask"}
        ``serial``: this process (:class:`SerialExecutor`).  ``process``: a local
        :class:`~concurrent.futures.ProcessPoolExecutor` of ``workers`` processes (started by
        forkserver where available, else spawn: never fork, which is unsafe in a process with
        threads).  ``dask-local``: a ``dask.distributed.LocalCluster`` of ``workers``
        single-threaded worker processes and a client to it.  ``dask``: a client to a running
        Dask scheduler at ``scheduler``.  Dask engines use ``Client.get_executor()``; their
        workers need racketdyn installed.
    workers : int
        Worker processes for ``process`` and ``dask-local``.
    scheduler : str, optional
        Scheduler address for ``dask``, e.g. ``tcp://10.0.0.5:8786``.

    Yields
    ------
    concurrent.futures.Executor
        The executor.  The Dask client and a local cluster are closed on exit.
    """
    one_of("engine", kind, ENGINES)
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InputError(f"workers must be a whole number of at least 1 (got {workers!r})")
    if kind == "dask":
        if not scheduler:
            raise InputError("the dask engine needs a scheduler address, e.g. tcp://HOST:8786")
    elif scheduler is not None:
        raise InputError(f"a scheduler address is for the dask engine only (not {kind})")
    if kind == "serial":
        yield SerialExecutor()
        return
    if kind == "process":
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        methods = multiprocessing.get_all_start_methods()
        context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
        with ProcessPoolExecutor(max_workers=workers, mp_context=context) as pool:
            yield pool
        return
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise InputError(
            "the Dask engines need dask.distributed: pip install 'racketdyn[dask]'"
        ) from None
    if kind == "dask-local":
        import dask

        # Dask's nannies set MALLOC_TRIM_THRESHOLD_ on their workers, which switches off glibc's
        # adaptive mmap threshold: every large temporary array is then mapped and unmapped
        # afresh, and a sweep task runs ≈ 1.7 times slower.  Leave the allocator alone.
        with (
            dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}),
            LocalCluster(  # type: ignore[no-untyped-call]
                # the scheduler's HTTP server (dashboard if bokeh is installed) on a free port:
                # with None it still takes 8787, and warns and leaks a socket where that is taken
                n_workers=workers,
                threads_per_worker=1,
                processes=True,
                dashboard_address=":0",
            ) as cluster,
            Client(cluster) as client,  # type: ignore[no-untyped-call]
        ):
            log.info("local Dask cluster: %d workers, dashboard %s", workers, client.dashboard_link)
            yield client.get_executor(pure=False)
        return
    try:
        client = Client(scheduler, timeout="20s")  # type: ignore[no-untyped-call]
    except (OSError, TimeoutError, ValueError) as error:
        raise InputError(f"scheduler {scheduler}: cannot connect ({error})") from None
    with client:
        yield client.get_executor(pure=False)  # type: ignore[no-untyped-call]


def _in_flight_limit(executor: Executor) -> int:
    """How many tasks to keep submitted at once: enough to keep every worker busy."""
    if isinstance(executor, SerialExecutor):
        return 1
    workers = getattr(executor, "_max_workers", None)  # ProcessPool/ThreadPoolExecutor
    if isinstance(workers, int) and workers > 0:
        return 2 * workers
    client = getattr(executor, "_client", None)  # dask.distributed ClientExecutor
    if client is not None:
        try:
            threads = int(sum(client.nthreads().values()))
        except Exception:  # a client that cannot say: fall back to the default
            threads = 0
        if threads > 0:
            return 2 * threads
    return 64


# --- running --------------------------------------------------------------------------------
def run_sweep(
    spec: SweepSpec | str | Path,
    out_dir: str | Path,
    executor: Executor | None = None,
    progress: ProgressCallback | None = None,
    *,
    retries: int = 1,
    figures: bool = True,
    max_in_flight: int | None = None,
) -> xr.Dataset:
    """Run a sweep: one task per design on an executor, parts on disk, one dataset at the end.

    Parameters
    ----------
    spec : SweepSpec or path
        The sweep, or its TOML file (:func:`load_sweep_spec`).
    out_dir : path
        Output folder (created): ``parts/<task-id>.nc`` per finished design, ``sweep.nc``,
        ``run.json``, ``failures.json`` when a task failed for good, ``summary.csv`` and the
        summary figures.
    executor : concurrent.futures.Executor, optional
        Where tasks run (:func:`make_executor`; a ``dask.distributed`` client's
        ``get_executor()``).  Default: this process for fewer than
        :data:`SERIAL_IMPACT_LIMIT` impacts to compute, else a pool of two processes.  An
        executor passed in is not shut down.
    progress : callable, optional
        ``progress(done, total)`` after the resumed tasks are counted and after each task ends.
    retries : int
        Times a failed task is submitted again before it is recorded as failed.
    figures : bool
        Draw the summary figures.
    max_in_flight : int, optional
        Tasks submitted at once (default: twice the executor's workers; 1 for serial).

    Returns
    -------
    xarray.Dataset
        The combined results as read back from ``sweep.nc``: impact quantities over
        ``(design, point, speed, racket_speed, support)``; ``reduced_mass_kg`` over
        ``(design, point, support)``; ``mode_frequency_hz`` over ``(design, mode)``; design
        coordinates for every variable and the derived racket properties; attributes recording
        the spec (JSON), its hash, the racketdyn version and failed tasks.  A failed design
        has NaN and status code 3.
    """
    started = time.perf_counter()
    if not isinstance(spec, SweepSpec):
        spec = load_sweep_spec(Path(spec))
    if isinstance(retries, bool) or not isinstance(retries, int) or retries < 0:
        raise InputError(f"retries must be a whole number of 0 or more (got {retries!r})")
    out = Path(out_dir)
    parts_dir = out / "parts"
    parts_dir.mkdir(parents=True, exist_ok=True)
    designs = spec.designs
    total = len(designs)
    todo = [d for d in designs if _read_part(parts_dir / f"{d.task_id}.nc", spec, False) is None]
    skipped = total - len(todo)
    log.info(
        "sweep %s: %d designs, %d impacts; %d resumed from %s, %d to run",
        spec.name,
        total,
        spec.n_impacts,
        skipped,
        parts_dir,
        len(todo),
    )
    if progress is not None:
        progress(skipped, total)
    tally = _Tally(done=skipped, total=total)
    engine = "none (all resumed)"
    if todo:
        with ExitStack() as stack:
            if executor is None:
                small = len(todo) * spec.impacts_per_design < SERIAL_IMPACT_LIMIT
                kind: EngineKind = "serial" if small else "process"
                executor = stack.enter_context(make_executor(kind, DEFAULT_WORKERS))
            engine = type(executor).__name__
            limit = max_in_flight or _in_flight_limit(executor)
            _run_tasks(spec, todo, parts_dir, executor, limit, retries, progress, tally)
    failures = tally.failures
    dataset = _combine(spec, parts_dir, failures)
    sweep_path = out / "sweep.nc"
    _write_netcdf(dataset, sweep_path)
    failures_path = out / "failures.json"
    if failures:
        failures_path.write_text(json.dumps(failures, indent=2), encoding="utf-8")
        log.error(
            "%d of %d designs failed; their results are NaN (status 3); see %s",
            len(failures),
            total,
            failures_path,
        )
    elif failures_path.exists():
        failures_path.unlink()
    codes, counts = np.unique(dataset["status"].values, return_counts=True)
    status_counts = {text: int(counts[codes == code].sum()) for text, code in STATUS_CODES.items()}
    for text in STATUS_CODES:
        if text not in (STATUS_OK, STATUS_FAILED) and status_counts[text]:
            log.warning(
                "%d of %d impacts: %s (their results are NaN)",
                status_counts[text],
                spec.n_impacts,
                text,
            )
    result = _read_netcdf(sweep_path)
    written = [sweep_path]
    if figures and spec.variables:
        written += write_summary_figures(result, out)
    record = {
        "format": "racketdyn-sweep-run",
        "racketdyn_version": __version__,
        "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
        "spec_sha256": spec.sha256,
        "engine": engine,
        "designs": total,
        "impacts": spec.n_impacts,
        "resumed": skipped,
        "ran": tally.ran,
        "retried": tally.retried,
        "failed": [f["task_id"] for f in failures],
        "status_counts": status_counts,
        "wall_time_s": time.perf_counter() - started,
        "task_time_s": tally.task_seconds,
        "outputs": [p.name for p in written] + ["run.json", "parts/"],
        "spec": spec.to_dict(),
    }
    (out / "run.json").write_text(json.dumps(record, indent=2), encoding="utf-8")
    return result


@dataclass
class _Tally:
    """What a run did so far: tasks done (with resumed ones) of all, run, retried, failed."""

    done: int
    total: int
    ran: int = 0
    retried: int = 0
    task_seconds: float = 0.0
    failures: list[dict[str, Any]] = field(default_factory=list)


def _run_tasks(
    spec: SweepSpec,
    todo: Sequence[Design],
    parts_dir: Path,
    executor: Executor,
    limit: int,
    retries: int,
    progress: ProgressCallback | None,
    tally: _Tally,
) -> None:
    """Submit the tasks (at most ``limit`` at once), write each part as it ends, retry."""
    queue: deque[tuple[Design, int]] = deque((d, 1) for d in todo)
    pending: dict[Future[TaskOutput], tuple[Design, int]] = {}

    def finished_one() -> None:
        tally.done += 1
        if progress is not None:
            progress(tally.done, tally.total)

    def failed(design: Design, attempt: int, error: BaseException) -> None:
        if attempt <= retries:
            tally.retried += 1
            log.warning(
                "%s (%s) failed on attempt %d (%s: %s); retrying",
                design.task_id,
                design.describe(),
                attempt,
                type(error).__name__,
                error,
            )
            queue.appendleft((design, attempt + 1))
            return
        log.error(
            "%s (%s) failed: %s: %s", design.task_id, design.describe(), type(error).__name__, error
        )
        tally.failures.append(
            {
                "task_id": design.task_id,
                "design": dict(design.settings),
                "attempts": attempt,
                "error": f"{type(error).__name__}: {error}",
                "traceback": "".join(traceback.format_exception(error)),
            }
        )
        finished_one()

    try:
        while queue or pending:
            while queue and len(pending) < limit:
                design, attempt = queue.popleft()
                try:
                    future = executor.submit(run_task, spec.task(design), attempt)
                except Exception as error:  # e.g. a broken process pool
                    failed(design, attempt, error)
                    continue
                pending[future] = (design, attempt)
            if not pending:
                continue
            finished, _ = wait(pending, return_when=FIRST_COMPLETED)
            for future in finished:
                design, attempt = pending.pop(future)
                try:
                    output = future.result()
                    _write_part(spec, design, output, parts_dir)
                except Exception as error:
                    failed(design, attempt, error)
                    continue
                tally.ran += 1
                tally.task_seconds += output.elapsed_s
                finished_one()
    except BaseException:
        for future in pending:
            future.cancel()
        log.warning(
            "sweep interrupted: %d designs are done in %s; run again to resume",
            tally.done,
            parts_dir,
        )
        raise


# --- files ----------------------------------------------------------------------------------
def _write_netcdf(dataset: xr.Dataset, path: Path) -> None:
    """Write netCDF 3 (xarray's scipy engine) atomically, see :func:`_atomic`."""
    with _atomic(path) as temporary:
        dataset.to_netcdf(temporary, engine="scipy")


@contextmanager
def _atomic(path: Path) -> Iterator[Path]:
    """A temporary name to write to, renamed to ``path`` on success: a reader never sees half a
    file, and an interrupted write leaves nothing behind."""
    temporary = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        yield temporary
        os.replace(temporary, path)
    finally:
        temporary.unlink(missing_ok=True)


def _read_netcdf(path: Path) -> xr.Dataset:
    import xarray as xr

    with xr.open_dataset(path, engine="scipy") as dataset:
        return dataset.load()


# Part files are plain netCDF 3 (xarray reads them), written and read with scipy's netCDF
# module directly: a few milliseconds less per part than through xarray, which is most of the
# coordinating process's work per task.  Numbers only; names and settings go in attributes.
def _write_part(spec: SweepSpec, design: Design, output: TaskOutput, parts_dir: Path) -> None:
    from scipy.io import netcdf_file

    dims = _IMPACT_DIMS[1:]
    with (
        _atomic(parts_dir / f"{design.task_id}.nc") as temporary,
        netcdf_file(temporary, "w", version=2) as part,
    ):
        shape = output.arrays["status"].shape
        for dim, size in zip(dims, shape, strict=True):
            part.createDimension(dim, size)
        for name, array in output.arrays.items():
            typecode = "b" if name == "status" else "d"
            variable = part.createVariable(name, typecode, dims)
            variable[:] = array
        variable = part.createVariable("reduced_mass_kg", "d", ("point", "support"))
        variable[:] = output.reduced_mass_kg
        if output.mode_names:
            part.createDimension("mode", len(output.mode_names))
            variable = part.createVariable("mode_frequency_hz", "d", ("mode",))
            variable[:] = output.mode_frequency_hz
        attributes = {
            "format": PART_FORMAT,
            "task_id": design.task_id,
            "spec_sha256": spec.sha256,
            "design": json.dumps(dict(design.settings)),
            "mode_names": json.dumps(list(output.mode_names)),
            "attempt": output.attempt,
            "racketdyn_version": __version__,
        }
        for key, value in attributes.items():
            setattr(part, key, value)


def _read_part(path: Path, spec: SweepSpec, data: bool) -> dict[str, Any] | None:
    """A part's arrays and attributes (``data=False``: attributes only) if it belongs to this
    spec, else None (missing, unreadable, or written for another spec or version)."""
    if not path.is_file():
        return None
    from scipy.io import netcdf_file

    try:
        with netcdf_file(path, "r", mmap=False) as part:
            attributes = {
                key: getattr(part, key).decode() if hasattr(part, key) else None
                for key in ("format", "task_id", "spec_sha256", "mode_names")
            }
            current = (
                attributes.get("format") == PART_FORMAT
                and attributes.get("spec_sha256") == spec.sha256
                and attributes.get("task_id") == path.stem
            )
            arrays = {
                name: np.asarray(variable.data).astype(variable.data.dtype.newbyteorder("="))
                for name, variable in part.variables.items()
                if data and current
            }
    except Exception as error:  # unreadable: compute it again
        log.warning("%s cannot be read (%s); the task runs again", path, error)
        return None
    if not current:
        log.info("%s belongs to another spec or version; the task runs again", path)
        return None
    return {**arrays, "attributes": attributes}


def _units(name: str) -> dict[str, Any]:
    if name == "status":
        return {
            "long_name": "impact status",
            "flag_values": np.array(list(STATUS_CODES.values()), dtype=np.int8),
            "flag_meanings": " ".join(s.replace(" ", "_") for s in STATUS_CODES),
        }
    _, units, long_name = _IMPACT_VARIABLES[name]
    return {"units": units, "long_name": long_name}


def _combine(spec: SweepSpec, parts_dir: Path, failures: Sequence[dict[str, Any]]) -> xr.Dataset:
    """The sweep dataset from the part files, in design order (NaN where a part is missing)."""
    import xarray as xr

    designs = spec.designs
    n_p, n_s, n_r, n_u = (
        spec.locations.shape[0],
        spec.ball_speeds.size,
        spec.racket_speeds.size,
        len(spec.supports),
    )
    shape = (len(designs), n_p, n_s, n_r, n_u)
    arrays: dict[str, NDArray[Any]] = {name: np.full(shape, np.nan) for name in _IMPACT_VARIABLES}
    arrays["status"] = np.full(shape, STATUS_CODES[STATUS_FAILED], dtype=np.int8)
    reduced = np.full((len(designs), n_p, n_u), np.nan)
    mode_names: list[str] = []
    frequencies: dict[tuple[int, str], float] = {}
    for design in designs:
        part = _read_part(parts_dir / f"{design.task_id}.nc", spec, data=True)
        if part is None:
            continue
        for name in arrays:
            arrays[name][design.index] = part[name]
        reduced[design.index] = part["reduced_mass_kg"]
        names = json.loads(part["attributes"]["mode_names"])
        for mode, frequency in zip(names, part.get("mode_frequency_hz", []), strict=True):
            if mode not in mode_names:
                mode_names.append(mode)
            frequencies[design.index, mode] = float(frequency)
    data: dict[str, Any] = {
        name: (_IMPACT_DIMS, array, _units(name)) for name, array in arrays.items()
    }
    data["reduced_mass_kg"] = (
        ("design", "point", "support"),
        reduced,
        {"units": "kg", "long_name": "reduced mass of the racket at the impact point (eq 4)"},
    )
    coords: dict[str, Any] = {
        "design": ("design", np.arange(len(designs), dtype=np.int32)),
        "task_id": ("design", [d.task_id for d in designs]),
        "varied": ("design", [d.varied for d in designs]),
        "point": ("point", np.arange(n_p, dtype=np.int32)),
        "point_label": ("point", list(spec.labels)),
        "x_m": ("point", spec.locations[:, 0], {"units": "m", "long_name": "x from the butt"}),
        "y_m": ("point", spec.locations[:, 1], {"units": "m", "long_name": "y across the axis"}),
        "speed": ("speed", spec.ball_speeds, {"units": "m s-1", "long_name": "ball speed"}),
        "racket_speed": (
            "racket_speed",
            spec.racket_speeds,
            {"units": "m s-1", "long_name": "racket speed at the impact point"},
        ),
        "support": ("support", list(spec.supports)),
    }
    for variable in spec.variables:
        for coord in variable.coords:
            values = [dict(d.settings)[coord] for d in designs]
            coords[coord] = ("design", np.asarray(values, dtype=float), {"variable": variable.name})
    derived = []
    for design in designs:
        racket, _, _ = build_design(spec.racket, spec.ball, spec.variables, design.settings)
        derived.append(racket.derived_properties())
    for name, (key, units, long_name) in _DERIVED.items():
        coords[name] = (
            "design",
            np.array([d[key] for d in derived]),
            {"units": units, "long_name": long_name},
        )
    if mode_names:
        frequency = np.full((len(designs), len(mode_names)), np.nan)
        for (index, mode), value in frequencies.items():
            frequency[index, mode_names.index(mode)] = value
        data["mode_frequency_hz"] = (
            ("design", "mode"),
            frequency,
            {"units": "Hz", "long_name": "natural frequency of the modes charged"},
        )
        coords["mode"] = ("mode", mode_names)
    head = spec.racket.head
    attrs = {
        "format": SWEEP_FORMAT,
        "title": spec.name,
        "racketdyn_version": __version__,
        "spec_sha256": spec.sha256,
        "spec": json.dumps(spec.to_dict(), sort_keys=True),
        # not "variables" nor "mode": scipy's netCDF writer keeps its own state under those names
        "sweep_variables": json.dumps(
            [{**v.to_dict(), "base": list(spec.base_value(v))} for v in spec.variables]
        ),
        "sweep_mode": spec.mode,
        "method": spec.method,
        "stiffness_reading": spec.stiffness_reading,
        "include_string_bed": int(spec.include_string_bed),
        "rigid": int(spec.rigid),
        "head_centre_x_m": head.centre_x_m,
        "head_centre_y_m": head.centre_y_m,
        "head_area_cm2": head.area_m2 * 1e4,
        "threshold_fraction": spec.threshold_fraction,
        "summary_ball_speed_mps": _summary_speed(spec.summary_ball_speed, spec.ball_speeds, True),
        "summary_racket_speed_mps": _summary_speed(
            spec.summary_racket_speed, spec.racket_speeds, False
        ),
        "n_failed": len(failures),
        "failed_tasks": json.dumps(
            [{k: f[k] for k in ("task_id", "design", "error")} for f in failures]
        ),
    }
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _summary_speed(value: float | None, listed: NDArray[np.float64], middle: bool) -> float:
    if value is not None:
        return float(listed[np.argmin(np.abs(listed - value))])
    return float(listed[listed.size // 2] if middle else listed[0])


# --- the spec file --------------------------------------------------------------------------
_TOP_KEYS = ("schema_version", "name", "description", "racket", "mode")
_TABLES = ("ball", "impacts", "variables", "summary")
_BALL_KEYS = ("mass_kg", "diameter_m", "e_bg", "load_deflection_file")
_IMPACT_KEYS = (
    "grid",
    "points",
    "ball_speeds_mps",
    "racket_speeds_mps",
    "method",
    "stiffness_reading",
    "include_string_bed",
    "rigid",
)
_SUMMARY_KEYS = ("threshold_fraction", "ball_speed_mps", "racket_speed_mps")
MAX_GRID = 400


def load_sweep_spec(path: Path | str) -> SweepSpec:
    """Read and validate a sweep spec (TOML; schema in docs/sweep-file.md).

    Parameters
    ----------
    path : path-like
        The spec file.  Relative file names inside it (racket, points, ball law) are taken
        relative to it.

    Returns
    -------
    SweepSpec
        The validated spec; every design is checked to be a valid racket.
    """
    path = Path(path)
    return sweep_spec_from_dict(read_toml(path, "sweep spec file"), path.parent, str(path))


def sweep_spec_from_dict(
    data: Mapping[str, Any], base_dir: Path | str = ".", source: str = "sweep spec"
) -> SweepSpec:
    """Build a sweep spec from parsed TOML (see :func:`load_sweep_spec`).

    Parameters
    ----------
    data : mapping
        The parsed TOML.
    base_dir : path-like
        Folder that relative file names are taken from.
    source : str
        Names the spec in error messages (the file name).
    """
    base = Path(base_dir)
    try:
        return _spec_from_dict(data, base, source)
    except InputError as error:
        message = str(error)
        raise InputError(
            message if message.startswith(source) else f"{source}: {message}"
        ) from None


def _spec_from_dict(data: Mapping[str, Any], base: Path, source: str) -> SweepSpec:
    for key in data:
        if key not in _TOP_KEYS + _TABLES:
            raise InputError(
                f"unknown top-level key {key!r}; allowed: {', '.join(_TOP_KEYS + _TABLES)}"
            )
    version = data.get("schema_version", SPEC_SCHEMA_VERSION)
    if version != SPEC_SCHEMA_VERSION:
        raise InputError(f"schema_version {version!r} is not supported (this racketdyn reads 1)")
    name = _get(data, "name", str, "", "name")
    _get(data, "description", str, "", "description")
    mode = one_of("mode", data.get("mode", "full-factorial"), MODES)
    racket_text = _get(data, "racket", str, "builtin", "racket")
    if racket_text in ("builtin", "built-in"):
        racket, racket_source = default_racket(), f"built-in {DEFAULT_RACKET_NAME}"
    else:
        racket_path = base / racket_text
        racket, racket_source = load_racket(racket_path), str(racket_path)

    ball_table = _table(data, "ball", _BALL_KEYS)
    ball_args: dict[str, Any] = {
        k: _number(f"[ball].{k}", ball_table[k])
        for k in ("mass_kg", "diameter_m", "e_bg")
        if k in ball_table
    }
    if "load_deflection_file" in ball_table:
        law_file = base / _get(
            ball_table, "load_deflection_file", str, "", "[ball].load_deflection_file"
        )
        deflection, force = read_load_deflection(law_file)
        ball_args["restoring_force"] = RestoringForce.fit(
            deflection, force, "polynomial", 3, f"ball, fitted to {law_file.name}"
        )
    try:
        ball = Ball(**ball_args)
    except InputError as error:
        raise InputError(f"[ball]: {error}") from None

    impacts = _table(data, "impacts", _IMPACT_KEYS)
    if "grid" in impacts and "points" in impacts:
        raise InputError("[impacts]: give grid or points, not both")
    labels: tuple[str, ...] = ()
    if "points" in impacts:
        points_path = base / _get(impacts, "points", str, "", "[impacts].points")
        locations, point_labels = read_points(points_path)
        labels = tuple(point_labels)
    else:
        grid = _get(impacts, "grid", int, 9, "[impacts].grid")
        if not 1 <= grid <= MAX_GRID:
            raise InputError(
                f"[impacts].grid must be a whole number from 1 to {MAX_GRID} (got {grid})"
            )
        locations = racket.head.grid(grid)
    if "ball_speeds_mps" not in impacts:
        raise InputError("[impacts].ball_speeds_mps is missing; it is required")
    ball_speeds = _value_list("[impacts].ball_speeds_mps", impacts["ball_speeds_mps"])
    racket_speeds = _value_list(
        "[impacts].racket_speeds_mps", impacts.get("racket_speeds_mps", [0.0])
    )
    method = _check_method("[impacts].method", impacts.get("method", "approximate"))
    reading = one_of(
        "[impacts].stiffness_reading",
        impacts.get("stiffness_reading", "period"),
        STIFFNESS_READINGS,
    )
    include_string_bed = _get(
        impacts, "include_string_bed", bool, False, "[impacts].include_string_bed"
    )
    rigid = _get(impacts, "rigid", bool, False, "[impacts].rigid")

    table = data.get("variables", {})
    if not isinstance(table, dict):
        raise InputError("[variables] must be a table of variables")
    variables: list[Variable] = []
    supports: tuple[str, ...] = SUPPORTS
    for key, value in _flat_hand_keys(table).items():
        where = f"[variables].{key}"
        if key in HAND_VARIABLES:
            if method != "transient":
                raise InputError(
                    f"{where}: hand parameters need [impacts].method = 'transient' and support "
                    "'hand'; the approximate method holds the racket pinned at the grip: sweep "
                    "grip_m or support instead"
                )
            variables.append(Variable.scalar(key, _value_list(where, value)))
            continue
        if key.startswith(("hand", "wrist", "grip_force")):
            raise InputError(
                f"{where}: unknown hand parameter; the hand parameters are "
                f"{', '.join(HAND_VARIABLES)} (transient method, support 'hand')"
            )
        if key == SUPPORT:
            items = value if isinstance(value, list) else [value]
            allowed = METHOD_SUPPORTS[method]
            if not items or not all(isinstance(s, str) for s in items):
                raise InputError(f"{where} must be a list of {', '.join(allowed)}")
            _check_supports(where, items, method)
            supports = tuple(items)
        elif key == POINT_MASS:
            tables = value if isinstance(value, list) else [value]
            for i, entry in enumerate(tables):
                variables.append(
                    _point_mass_from_table(
                        f"{where}[{i}]" if isinstance(value, list) else where, entry, racket
                    )
                )
        elif key in SCALAR_VARIABLES:
            variables.append(Variable.scalar(key, _value_list(where, value)))
        else:
            raise InputError(
                f"{where}: unknown variable; allowed: "
                f"{', '.join([POINT_MASS, SUPPORT, *SCALAR_VARIABLES, *HAND_VARIABLES])}"
            )

    summary = _table(data, "summary", _SUMMARY_KEYS)
    fraction = _number(
        "[summary].threshold_fraction",
        summary.get("threshold_fraction", DEFAULT_THRESHOLD_FRACTION),
    )
    summary_speeds = [
        None if key not in summary else _number(f"[summary].{key}", summary[key])
        for key in ("ball_speed_mps", "racket_speed_mps")
    ]
    return SweepSpec(
        racket=racket,
        ball=ball,
        locations=locations,
        labels=labels,
        ball_speeds=ball_speeds,
        racket_speeds=racket_speeds,
        supports=supports,
        variables=tuple(variables),
        mode=mode,  # type: ignore[arg-type]  # checked by one_of
        method=method,
        stiffness_reading=reading,  # type: ignore[arg-type]  # checked by one_of
        include_string_bed=include_string_bed,
        rigid=rigid,
        threshold_fraction=fraction,
        summary_ball_speed=summary_speeds[0],
        summary_racket_speed=summary_speeds[1],
        name=name or "sweep",
        racket_source=racket_source,
    )


def _flat_hand_keys(table: Mapping[str, Any]) -> dict[str, Any]:
    """``[variables]`` with a ``hand`` table (TOML ``hand.arm_mass_kg = …`` or
    ``[variables.hand]``) flattened to ``hand.<key>`` keys, in the order given."""
    flat: dict[str, Any] = {}
    for key, value in table.items():
        if key == "hand" and isinstance(value, dict):
            for inner, inner_value in value.items():
                flat[f"hand.{inner}"] = inner_value
        else:
            flat[key] = value
    return flat


def _point_mass_from_table(where: str, entry: object, racket: Racket) -> Variable:
    if not isinstance(entry, dict):
        raise InputError(f"{where} must be a table with mass_kg and x_m (or clock)")
    for key in entry:
        if key not in POINT_MASS_KEYS:
            raise InputError(
                f"{where}: unknown key {key!r}; allowed keys are {', '.join(POINT_MASS_KEYS)}"
            )
    if "mass_kg" not in entry:
        raise InputError(f"{where}.mass_kg is missing; it is required")
    label = _get(entry, "label", str, "", f"{where}.label")
    columns = {
        k: _value_list(f"{where}.{k}", entry[k])
        for k in ("mass_kg", "x_m", "y_m", "clock")
        if k in entry
    }
    return Variable.point_mass(
        columns["mass_kg"],
        columns.get("x_m"),
        columns.get("y_m"),
        columns.get("clock"),
        label=label,
        head=racket.head,
    )


def _table(data: Mapping[str, Any], name: str, allowed: Sequence[str]) -> dict[str, Any]:
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise InputError(f"[{name}] must be a table of keys")
    for key in table:
        if key not in allowed:
            raise InputError(
                f"[{name}]: unknown key {key!r}; allowed keys are {', '.join(allowed)}"
            )
    return dict(table)


def _get(table: Mapping[str, Any], key: str, kind: type, default: Any, where: str) -> Any:
    value = table.get(key, default)
    if kind is int:
        ok = isinstance(value, int) and not isinstance(value, bool)
        what = "a whole number"
    elif kind is bool:
        ok = isinstance(value, bool)
        what = "true or false"
    else:
        ok = isinstance(value, str)
        what = "a string"
    if not ok:
        raise InputError(f"{where} must be {what} (got {value!r})")
    return value


def _number(where: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise InputError(f"{where} must be a number (got {value!r})")
    return float(value)


def _value_list(where: str, value: object) -> NDArray[np.float64]:
    """Numbers from a number, a list of numbers or a table ``{start, stop, num}``."""
    if isinstance(value, dict):
        missing = [k for k in ("start", "stop", "num") if k not in value]
        unknown = [k for k in value if k not in ("start", "stop", "num")]
        if missing or unknown:
            raise InputError(
                f"{where}: a range is a table {{start, stop, num}}"
                + (f"; {', '.join(missing)} missing" if missing else "")
                + (f"; unknown key {', '.join(unknown)}" if unknown else "")
            )
        start = _number(f"{where}.start", value["start"])
        stop = _number(f"{where}.stop", value["stop"])
        num = value["num"]
        if isinstance(num, bool) or not isinstance(num, int) or num < 1:
            raise InputError(f"{where}.num must be a whole number of at least 1 (got {num!r})")
        return np.linspace(start, stop, num)
    items = value if isinstance(value, list) else [value]
    if not items:
        raise InputError(f"{where}: give one or more values")
    return np.array(
        [
            _number(f"{where}[{i}]" if isinstance(value, list) else where, v)
            for i, v in enumerate(items)
        ]
    )


# --- summary --------------------------------------------------------------------------------
def _variables(dataset: xr.Dataset) -> dict[str, dict[str, Any]]:
    return {v["name"]: v for v in json.loads(str(dataset.attrs["sweep_variables"]))}


def variable_designs(dataset: xr.Dataset, variable: str) -> NDArray[np.int_]:
    """Design indices that show one variable's effect, in order of its axis coordinate.

    One at a time: the designs varying it and the base design.  Full factorial: the designs
    with every other variable at its reference value — its base value if swept, else the swept
    value nearest the base.

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset (:func:`run_sweep`).
    variable : str
        A variable name (``e_bg``, ``point_mass`` …).
    """
    variables = _variables(dataset)
    if variable not in variables:
        raise InputError(f"no variable {variable!r} in the sweep; it has {', '.join(variables)}")
    info = variables[variable]
    axis = dataset[info["axis"]].values
    if dataset.attrs["sweep_mode"] == "one-at-a-time":
        varied = dataset["varied"].values
        keep = np.flatnonzero((varied == variable) | (varied == "base"))
    else:
        mask = np.ones(dataset.sizes["design"], dtype=bool)
        for name, other in variables.items():
            if name == variable:
                continue
            values = np.asarray(other["values"], dtype=float)
            base = np.asarray(other["base"], dtype=float)
            k = other["coords"].index(other["axis"])
            reference = values[np.argmin(np.abs(values[:, k] - base[k]))]
            if other["kind"] == POINT_MASS and base[0] == 0.0 and np.any(values[:, 0] == 0.0):
                reference = values[np.flatnonzero(values[:, 0] == 0.0)[0]]
            for coord, value in zip(other["coords"], reference, strict=True):
                mask &= dataset[coord].values == value
        keep = np.flatnonzero(mask)
    return np.asarray(keep[np.argsort(axis[keep], kind="stable")])


def summary_metrics(
    dataset: xr.Dataset,
    threshold_fraction: float | None = None,
    ball_speed: float | None = None,
    racket_speed: float | None = None,
) -> xr.Dataset:
    """Per design and support: rebound ratio at the face centre and the "sweet" face area.

    The face centre is the impact point nearest the head's centre.  The area counts the
    points whose rebound ratio reaches ``threshold_fraction`` × the best rebound ratio of the
    designs in ``dataset`` (all their points, per support: one threshold for the designs
    compared), each point standing for an equal share of the string-bed area (exact for a
    grid, approximate for a points file).  The figures compare the designs of one variable
    (:func:`variable_designs`) and pass only those; ``summary.csv`` compares all.

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset.
    threshold_fraction : float, optional
        Default: the spec's (``summary.threshold_fraction``, 0.9).
    ball_speed, racket_speed : float, optional
        The speeds to evaluate at, m/s (nearest listed; default the spec's summary speeds).

    Returns
    -------
    xarray.Dataset
        ``centre_rebound_ratio`` and ``sweet_area_cm2`` over ``(design, support)``, with the
        threshold per support and the centre point in the attributes.
    """
    import xarray as xr

    fraction = float(
        dataset.attrs["threshold_fraction"] if threshold_fraction is None else threshold_fraction
    )
    speed = float(dataset.attrs["summary_ball_speed_mps"] if ball_speed is None else ball_speed)
    swing = float(
        dataset.attrs["summary_racket_speed_mps"] if racket_speed is None else racket_speed
    )
    rebound = dataset["rebound_ratio"].sel(speed=speed, racket_speed=swing, method="nearest")
    x, y = dataset["x_m"].values, dataset["y_m"].values
    centre = int(
        np.argmin(
            (x - dataset.attrs["head_centre_x_m"]) ** 2
            + (y - dataset.attrs["head_centre_y_m"]) ** 2
        )
    )
    values = rebound.transpose("design", "point", "support").values
    with np.errstate(invalid="ignore"):
        finite = np.where(np.isfinite(values), values, -np.inf)
        best = finite.max(axis=(0, 1))  # per support
        threshold = np.where(np.isfinite(best), fraction * best, np.nan)
        share = np.mean(finite >= threshold, axis=1)  # (design, support)
    area = share * float(dataset.attrs["head_area_cm2"])
    failed = np.all(~np.isfinite(values), axis=1)
    area = np.where(failed, np.nan, area)
    coords = {"design": dataset["design"].values, "support": dataset["support"].values}
    return xr.Dataset(
        {
            "centre_rebound_ratio": (
                ("design", "support"),
                values[:, centre, :],
                {"units": "1", "long_name": "rebound ratio at the face centre"},
            ),
            "sweet_area_cm2": (
                ("design", "support"),
                area,
                {
                    "units": "cm2",
                    "long_name": f"face area with rebound ratio ≥ {fraction:g} × best",
                },
            ),
        },
        coords=coords,
        attrs={
            "ball_speed_mps": speed,
            "racket_speed_mps": swing,
            "threshold_fraction": fraction,
            "threshold_rebound_ratio": threshold.tolist(),
            "centre_point_x_m": float(x[centre]),
            "centre_point_y_m": float(y[centre]),
        },
    )


def _axis_label(dataset: xr.Dataset, variable: str) -> tuple[str, str, float]:
    """The coordinate a variable is plotted against, its axis label and display scale."""
    info = _variables(dataset)[variable]
    coord = str(info["axis"])
    if info["kind"] == POINT_MASS:
        what = variable.replace("_", " ")
        quantity = coord.removeprefix(variable + "_")
        labels = {
            "mass_kg": (f"{what} (g)", 1e3),
            "clock": (f"{what} position (o'clock)", 1.0),
            "x_m": (f"{what} x (m)", 1.0),
            "y_m": (f"{what} y (m)", 1.0),
        }
        label, scale = labels[quantity]
        return coord, label, scale
    hand_labels = {
        "hand.arm_mass_kg": "arm mass (kg)",
        "hand.stiffness_n_per_m": "hand stiffness (N/m)",
        "hand.damping_ns_per_m": "hand damping (N·s/m)",
    }
    if coord in hand_labels:
        return coord, hand_labels[coord], 1.0
    name, _, unit = coord.rpartition("_")
    units = {"kg": "kg", "m": "m", "kgm2": "kg·m²", "kgcm2": "kg·cm²", "n": "N"}
    if unit in units:
        return coord, f"{name.replace('_', ' ')} ({units[unit]})", 1.0
    return coord, f"{coord.replace('_', ' ')} (–)", 1.0


def _plot_metric(
    dataset: xr.Dataset,
    variable: str,
    metric: str,
    ax: Axes | None,
    threshold_fraction: float | None,
    ball_speed: float | None,
    racket_speed: float | None,
) -> Axes:
    import matplotlib.pyplot as plt

    from racketdyn.plotting import SUPPORT_STYLE  # sets the Agg backend: files, not windows

    if ax is None:
        _, ax = plt.subplots(figsize=(5.0, 3.6), layout="constrained")
    keep = variable_designs(dataset, variable)
    # the designs compared share one threshold: a fraction of the best among them
    metrics = summary_metrics(
        dataset.isel(design=keep), threshold_fraction, ball_speed, racket_speed
    )
    coord, label, scale = _axis_label(dataset, variable)
    x = dataset[coord].values[keep] * scale
    for support in metrics["support"].values.tolist():
        style = SUPPORT_STYLE.get(str(support), {})
        ax.plot(
            x,
            metrics[metric].sel(support=support).values,
            color=str(style.get("color", "tab:gray")),
            marker=str(style.get("marker", "o")),
            label=str(style.get("label", support)),
            linestyle="-",
            markersize=4,
        )
    ax.set_xlabel(label)
    speeds = f"{metrics.attrs['ball_speed_mps']:g} m/s ball"
    if metrics.attrs["racket_speed_mps"]:
        speeds += f", {metrics.attrs['racket_speed_mps']:g} m/s racket"
    if metric == "centre_rebound_ratio":
        ax.set_ylabel("rebound ratio e at centre (–)")
        ax.set_title(f"face centre, {speeds}", fontsize=9)
    else:
        ax.set_ylabel("face area above threshold (cm²)")
        ax.set_title(f"e ≥ {metrics.attrs['threshold_fraction']:g} × best, {speeds}", fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_centre_rebound(
    dataset: xr.Dataset,
    variable: str,
    ax: Axes | None = None,
    ball_speed: float | None = None,
    racket_speed: float | None = None,
) -> Axes:
    """Rebound ratio at the face centre against a variable, one line per support.

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset.
    variable : str
        The variable (designs from :func:`variable_designs`).
    ax : matplotlib Axes, optional
        Where to draw (a new figure if None).
    ball_speed, racket_speed : float, optional
        Speeds, m/s (default the spec's summary speeds).
    """
    return _plot_metric(
        dataset, variable, "centre_rebound_ratio", ax, None, ball_speed, racket_speed
    )


def plot_sweet_area(
    dataset: xr.Dataset,
    variable: str,
    ax: Axes | None = None,
    threshold_fraction: float | None = None,
    ball_speed: float | None = None,
    racket_speed: float | None = None,
) -> Axes:
    """Face area with a rebound ratio above the threshold against a variable, per support.

    The threshold is a fraction of the best rebound ratio among the designs plotted (see
    :func:`summary_metrics`).

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset.
    variable : str
        The variable (designs from :func:`variable_designs`).
    ax : matplotlib Axes, optional
        Where to draw (a new figure if None).
    threshold_fraction : float, optional
        Fraction of the sweep's best rebound ratio (default the spec's).
    ball_speed, racket_speed : float, optional
        Speeds, m/s (default the spec's summary speeds).
    """
    return _plot_metric(
        dataset, variable, "sweet_area_cm2", ax, threshold_fraction, ball_speed, racket_speed
    )


def write_summary_figures(dataset: xr.Dataset, out_dir: Path | str) -> list[Path]:
    """Write ``summary_<variable>.png`` (centre rebound and sweet area) and ``summary.csv``.

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset.
    out_dir : path-like
        Output folder.

    Returns
    -------
    list of Path
        The files written.
    """
    import matplotlib.pyplot as plt

    import racketdyn.plotting  # noqa: F401  (sets the Agg backend: files, not windows)

    out = Path(out_dir)
    written = []
    for variable in _variables(dataset):
        figure, (left, right) = plt.subplots(1, 2, figsize=(9.0, 3.6), layout="constrained")
        plot_centre_rebound(dataset, variable, ax=left)
        plot_sweet_area(dataset, variable, ax=right)
        figure.suptitle(f"{dataset.attrs['title']}: {variable.replace('_', ' ')}", fontsize=10)
        path = out / f"summary_{variable}.png"
        figure.savefig(path, dpi=120, metadata={"Software": f"racketdyn {__version__}"})
        plt.close(figure)
        written.append(path)
    metrics = summary_metrics(dataset)
    table = metrics.to_dataframe().unstack("support")
    table.columns = [f"{name}_{support}" for name, support in table.columns]
    design_coords = [c for c in dataset.coords if dataset[c].dims == ("design",) and c != "design"]
    for coord in design_coords:
        table[coord] = dataset[coord].values
    table = table[design_coords + [c for c in table.columns if c not in design_coords]]
    path = out / "summary.csv"
    table.to_csv(path)
    written.append(path)
    return written


def factorial_view(dataset: xr.Dataset) -> xr.Dataset:
    """A full-factorial sweep with one dimension per variable instead of ``design``.

    Each variable's dimension is its axis coordinate (``e_bg``, ``point_mass_mass_kg`` …).
    For analysis in memory; netCDF cannot store the index this builds.

    Parameters
    ----------
    dataset : xarray.Dataset
        A full-factorial sweep dataset.
    """
    if dataset.attrs["sweep_mode"] != "full-factorial":
        raise InputError("factorial_view needs a full-factorial sweep (mode = 'full-factorial')")
    axes = [str(v["axis"]) for v in _variables(dataset).values()]
    if not axes:
        return dataset.squeeze("design", drop=False)
    others = [
        c
        for c in dataset.coords
        if dataset[c].dims == ("design",) and c not in axes and c != "design"
    ]
    stacked = dataset.drop_vars(others).set_index(design=axes)
    return stacked.unstack("design")
