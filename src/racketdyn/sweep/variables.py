"""Sweep variables: what a sweep can change, and :class:`Variable`, one swept quantity.

The lowest module of :mod:`racketdyn.sweep`: a spec (:mod:`~racketdyn.sweep.spec`) lists its
variables; a design (:mod:`~racketdyn.sweep.design`) sets each to one of its values.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.errors import InputError, one_of
from racketdyn.racket import HeadEllipse

__all__ = ["HAND_VARIABLES", "POINT_MASS", "SCALAR_VARIABLES", "Variable"]

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
POINT_MASS = "point_mass"


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
