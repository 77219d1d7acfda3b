"""The racket: mass properties, string-bed geometry and reduced mass at an impact point.

Coordinates (used everywhere in racketdyn): ``x`` in metres from the butt along the long axis,
``y`` in metres across it (positive to the left seen from the hitting face), ``z`` normal to the
string face.  A ``location`` is an ``(x, y)`` pair; arrays of locations are shaped ``(n, 2)``.

All inertias are in kg·m² unless a name says otherwise (players quote swingweight and twistweight
in kg·cm²; the properties named so return those units).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Literal, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn._display import html_table, number, shorten
from racketdyn.errors import InputError, one_of, require_finite, require_positive, require_whole
from racketdyn.numerics import as_locations

__all__ = [
    "SUPPORTS",
    "SUPPORT_NAMES",
    "SWINGWEIGHT_AXIS_M",
    "TIP_INSET_M",
    "HeadEllipse",
    "MassProperties",
    "PointMass",
    "Racket",
    "StringBed",
    "Support",
    "as_locations",
    "landmark_points",
]

Support = Literal["free", "pinned"]
"""Support condition of the racket during an impact.

``free``: a freely supported (suspended) racket, translating and rotating about its centre of
mass.  ``pinned``: the hand-held model of the paper (section 3.3), the racket turning about a
point on the long axis at the grip (default 70 mm from the butt), free to roll about the long axis.
"""

SUPPORTS: tuple[str, ...] = get_args(Support)
SUPPORT_NAMES: dict[str, str] = {
    "free": "freely supported",
    "pinned": "pinned at the grip",
    "hand": "hand-held (hand and arm)",
}
"""Each support in words, one name each wherever a page, a figure or a table names it:
``pinned`` is the approximate method's model of a held racket (the paper's "hand-held"),
``hand`` the transient model's hand and arm and the rig's hand-held test (issue 27: the page
had called ``pinned`` "hand-held (pinned at grip)" beside the rig's ``hand``)."""
SWINGWEIGHT_AXIS_M = 0.100
"""Swingweight axis, 100 mm from the butt, as racket makers and players quote it."""
TENSION_LOSS = 0.30
"""Fraction of the pull tension a string bed has lost when it is played: ≈ 30 % just after
stringing, measured from the bed's frequency on strung rackets (Cross and Bower,
docs/references.md, "Strings"); the bed's membrane mode then falls in the 500–700 Hz that
string-bed meters read."""

KGM2_TO_KGCM2 = 1.0e4
M2_TO_CM2 = 1.0e4


@dataclass(frozen=True)
class PointMass:
    """A concentrated mass fixed to the racket, such as lead tape.

    Parameters
    ----------
    mass_kg : float
        Mass in kg (positive).
    x_m, y_m : float
        Location in metres (x from the butt, y across the long axis).
    label : str
        Free text shown in tables, e.g. ``"12 o'clock"``.
    """

    mass_kg: float
    x_m: float
    y_m: float = 0.0
    label: str = ""

    def __post_init__(self) -> None:
        name = f"point mass {self.label}".strip()
        require_positive(f"{name} mass_kg", self.mass_kg)
        require_finite(f"{name} x_m", self.x_m)
        require_finite(f"{name} y_m", self.y_m)


@dataclass(frozen=True)
class HeadEllipse:
    """The string bed, taken as an ellipse in the plane of the face.

    Parameters
    ----------
    centre_x_m : float
        x of the ellipse centre, metres from the butt.
    half_length_m : float
        Half-axis along the racket, metres (the main strings are twice this long).
    half_width_m : float
        Half-axis across the racket, metres (the cross strings are twice this long).
    centre_y_m : float
        y of the centre, metres (0 for a symmetric racket).
    """

    centre_x_m: float
    half_length_m: float
    half_width_m: float
    centre_y_m: float = 0.0

    def __post_init__(self) -> None:
        require_positive("head.centre_x_m", self.centre_x_m)
        require_positive("head.half_length_m", self.half_length_m)
        require_positive("head.half_width_m", self.half_width_m)
        require_finite("head.centre_y_m", self.centre_y_m)

    @property
    def area_m2(self) -> float:
        """String-bed area, m² (π a b)."""
        return float(np.pi * self.half_length_m * self.half_width_m)

    @property
    def tip_x_m(self) -> float:
        """x of the top of the string bed, m."""
        return self.centre_x_m + self.half_length_m

    @property
    def throat_x_m(self) -> float:
        """x of the bottom (throat end) of the string bed, m."""
        return self.centre_x_m - self.half_length_m

    def normalised_radius(self, locations: ArrayLike) -> NDArray[np.float64]:
        """Elliptic radius ρ (0 at the centre, 1 on the edge) of each location."""
        xy = as_locations(locations)
        xi = (xy[:, 0] - self.centre_x_m) / self.half_length_m
        eta = (xy[:, 1] - self.centre_y_m) / self.half_width_m
        return np.asarray(np.sqrt(xi**2 + eta**2))

    def contains(self, locations: ArrayLike) -> NDArray[np.bool_]:
        """True where a location lies on the string bed (edge included, to 1e-9 relative)."""
        return self.normalised_radius(locations) <= 1.0 + 1e-9

    def distance_to_edge(self, locations: ArrayLike) -> NDArray[np.float64]:
        """Distance in the plane of the face from each location to the bed's edge (the hoop), m.

        Parameters
        ----------
        locations : array_like
            ``(n, 2)`` points ``(x, y)``, m, on the bed.

        Returns
        -------
        ndarray
            ``(n,)`` shortest distance to the ellipse, m (0 on the edge).

        Notes
        -----
        numpy and scipy have no point-to-ellipse distance, hence our own: the nearest of 64
        parametric angles of the quarter ellipse (by symmetry), refined by Newton steps on the
        angle ``t`` where ``(a² − b²) sin t cos t − a u sin t + b v cos t = 0`` (the foot of
        the normal), kept within one sample spacing so that a second root inside the ellipse
        is never taken.
        """
        xy = as_locations(locations)
        a, b = self.half_length_m, self.half_width_m
        u = np.abs(xy[:, 0] - self.centre_x_m)[:, None]
        v = np.abs(xy[:, 1] - self.centre_y_m)[:, None]
        step = 0.5 * np.pi / 63
        t = np.linspace(0.0, 0.5 * np.pi, 64)[None, :]
        squared = (a * np.cos(t) - u) ** 2 + (b * np.sin(t) - v) ** 2
        nearest = np.argmin(squared, axis=1)
        t0 = t[0, nearest][:, None]
        tt = t0.copy()
        for _ in range(8):
            s, c = np.sin(tt), np.cos(tt)
            f = (a * a - b * b) * s * c - a * u * s + b * v * c
            df = (a * a - b * b) * (c * c - s * s) - a * u * c - b * v * s
            with np.errstate(divide="ignore", invalid="ignore"):
                tt = np.where(df != 0.0, tt - f / df, tt)
            tt = np.clip(tt, np.maximum(t0 - step, 0.0), np.minimum(t0 + step, 0.5 * np.pi))
        d = np.hypot(a * np.cos(tt) - u, b * np.sin(tt) - v)[:, 0]
        coarse = np.sqrt(squared[np.arange(squared.shape[0]), nearest])
        return np.asarray(np.minimum(d, coarse))

    def half_width_at(self, x_m: ArrayLike) -> NDArray[np.float64]:
        """Half-width of the string bed at each x (0 outside the head), m."""
        xi = (np.asarray(x_m, dtype=float) - self.centre_x_m) / self.half_length_m
        return np.asarray(self.half_width_m * np.sqrt(np.clip(1.0 - xi**2, 0.0, None)))

    def grid(self, n: int) -> NDArray[np.float64]:
        """Impact locations on an ``n × n`` grid over the ellipse's bounding box, kept if inside.

        The grid is inset by half a cell so that no point sits on the frame.
        """
        n = require_whole("grid size", n)
        u = (np.arange(n) + 0.5) / n * 2.0 - 1.0
        xi, eta = np.meshgrid(u, u, indexing="ij")
        inside = xi**2 + eta**2 <= 1.0
        x = self.centre_x_m + self.half_length_m * xi[inside]
        y = self.centre_y_m + self.half_width_m * eta[inside]
        return np.column_stack([x, y])

    def check_inside(self, locations: ArrayLike, name: str = "impact point") -> None:
        """Raise InputError naming the first location outside the string bed."""
        xy = as_locations(locations)
        outside = np.flatnonzero(~self.contains(xy))
        if outside.size:
            i = int(outside[0])
            # points in millimetres (520 for 0.52 m) or centimetres (52) land on the bed read
            # so: say which
            slip = next(
                (
                    f"; did you give {unit}? (give metres)"
                    for unit, scale in (("millimetres", 1e-3), ("centimetres", 1e-2))
                    if bool(np.all(self.contains(xy[outside] * scale)))
                ),
                "; give points on the strings",
            )
            which = f"{name} {i + 1}" if xy.shape[0] > 1 else name
            raise InputError(
                f"{which} at x={_g4(xy[i, 0])} m, y={_g4(xy[i, 1])} m lies outside the string "
                f"bed (ellipse centre x={self.centre_x_m:.4f} m, half-axes "
                f"{self.half_length_m:.4f} × {self.half_width_m:.4f} m){slip}"
            )


def _g4(value: float) -> str:
    """A coordinate for a message: 4 decimals in metres, as typed when larger (510, not
    510.0000)."""
    return f"{value:.4f}" if abs(value) < 10 else f"{value:g}"


@dataclass(frozen=True)
class MassProperties:
    """Rigid-body mass properties for motion normal to the string face.

    Parameters
    ----------
    mass_kg : float
        Total mass, kg.
    centre_m : tuple of float
        Centre of mass ``(x, y)``, m.
    inertia_kgm2 : ndarray, shape (2, 2)
        Inertia tensor about the centre of mass for rotation about the in-plane axes, kg·m²:
        ``[[I_roll, I_xy], [I_xy, I_pitch]]`` with ``I_roll = Σ m y²`` (about the long axis),
        ``I_pitch = Σ m x²`` (about an axis across the handle) and ``I_xy = -Σ m x y``.
    """

    mass_kg: float
    centre_m: tuple[float, float]
    inertia_kgm2: NDArray[np.float64]

    def inertia_about(self, point: tuple[float, float]) -> NDArray[np.float64]:
        """Inertia tensor about a point in the plane of the face (parallel-axis theorem), kg·m²."""
        dx = self.centre_m[0] - point[0]
        dy = self.centre_m[1] - point[1]
        shift = self.mass_kg * np.array([[dy * dy, -dx * dy], [-dx * dy, dx * dx]])
        return np.asarray(self.inertia_kgm2 + shift)

    def with_point_masses(self, point_masses: tuple[PointMass, ...]) -> MassProperties:
        """Mass properties with point masses added (a new object; this one is unchanged)."""
        if not point_masses:
            return self
        masses = np.array([self.mass_kg] + [p.mass_kg for p in point_masses])
        xs = np.array([self.centre_m[0]] + [p.x_m for p in point_masses])
        ys = np.array([self.centre_m[1]] + [p.y_m for p in point_masses])
        total = float(masses.sum())
        centre = (float(masses @ xs / total), float(masses @ ys / total))
        inertia = self.inertia_about(centre)
        for p in point_masses:
            dx, dy = p.x_m - centre[0], p.y_m - centre[1]
            inertia = inertia + p.mass_kg * np.array([[dy * dy, -dx * dy], [-dx * dy, dx * dx]])
        return MassProperties(total, centre, inertia)

    def reduced_mass(
        self, locations: ArrayLike, pivot: tuple[float, float] | None = None
    ) -> NDArray[np.float64]:
        """Reduced (effective) mass at each impact location for a force normal to the face, kg.

        Free body (``pivot=None``): ``1/M_r = 1/M + uᵀ I_G⁻¹ u`` with ``u = (y - y_G, -(x - x_G))``,
        which for a symmetric racket is ``1/M + b²/I_G + y²/I_roll`` (b the distance from the
        centre of mass along the long axis).  Pinned at ``pivot``: ``1/M_r = uᵀ I_A⁻¹ u`` with
        ``u`` and ``I_A`` taken about the pivot, i.e. the paper's eq (4) ``M_r = I_A / L_A²`` plus
        the roll term.
        """
        xy = as_locations(locations)
        if pivot is None:
            origin, inertia, translation = self.centre_m, self.inertia_kgm2, 1.0 / self.mass_kg
        else:
            origin, inertia, translation = pivot, self.inertia_about(pivot), 0.0
        lever = np.column_stack([xy[:, 1] - origin[1], -(xy[:, 0] - origin[0])])
        compliance = np.einsum("ni,ij,nj->n", lever, np.linalg.inv(inertia), lever)
        with np.errstate(divide="ignore"):
            return np.asarray(1.0 / (translation + compliance))


@dataclass(frozen=True)
class StringBed:
    """String-bed construction, for the default string restoring force and membrane mode.

    Parameters
    ----------
    tension_n : float
        Reference (pull) tension of each string on the stringing machine, N (the paper's
        racket: 246 N, 55 lb).
    tension_loss : float
        Fraction of the reference tension the bed has lost by the time the racket is played
        (stringing losses, frame distortion, stress relaxation): :data:`TENSION_LOSS`, ≈ 30 %
        just after stringing (Cross and Bower, docs/references.md, "Strings").  0 when
        ``tension_n`` was measured in the bed (from its frequency, say).  Every law of the bed
        (its restoring force, its membrane mode) uses :attr:`bed_tension_n`.
    mains, crosses : int
        Number of main strings (running along the racket) and cross strings.
    string_diameter_m : float
        Gauge of the string, m.
    string_modulus_pa : float
        Axial (Young's) modulus of the string, Pa, for the stretching term of Kawazoe's law.
    mass_kg : float or None
        Mass of the strings, kg; ``None`` means 4 % of the racket mass (the paper, section 2).
    load_deflection_file : Path or None
        Measured string-bed load–deflection CSV; if given it replaces the Kawazoe law.
    """

    tension_n: float = 246.0
    tension_loss: float = TENSION_LOSS
    mains: int = 16
    crosses: int = 19
    string_diameter_m: float = 1.30e-3
    string_modulus_pa: float = 5.0e9
    mass_kg: float | None = None
    load_deflection_file: Path | None = None

    def __post_init__(self) -> None:
        require_positive("strings.tension_n", self.tension_n)
        if not 0.0 <= self.tension_loss < 1.0:
            raise InputError(
                f"strings.tension_loss = {self.tension_loss:g}: a fraction of the reference "
                "tension in [0, 1) is needed (0.3 for 30 %; 0 if the tension was measured in "
                "the bed)"
            )
        require_positive("strings.string_diameter_m", self.string_diameter_m)
        require_positive("strings.string_modulus_pa", self.string_modulus_pa)
        for name in ("mains", "crosses"):
            require_whole(f"strings.{name}", getattr(self, name))
        if self.mass_kg is not None:
            require_positive("strings.mass_kg", self.mass_kg)

    @property
    def bed_tension_n(self) -> float:
        """Tension of each string in the played bed, N: ``tension_n (1 − tension_loss)``."""
        return self.tension_n * (1.0 - self.tension_loss)

    @property
    def axial_stiffness_n(self) -> float:
        """Axial stiffness A·E of one string, N."""
        return float(np.pi / 4 * self.string_diameter_m**2 * self.string_modulus_pa)

    def spacing_m(self, head: HeadEllipse) -> tuple[float, float]:
        """Mean spacing of the mains (across) and of the crosses (along), m."""
        return (
            2 * head.half_width_m / (self.mains + 1),
            2 * head.half_length_m / (self.crosses + 1),
        )


@dataclass(frozen=True)
class Racket:
    """A tennis racket as racketdyn sees it: mass properties, head, strings, optional modes.

    The mass, balance and inertias describe the racket as strung, without ``point_masses``;
    the derived properties (:attr:`mass_properties` and everything built on it) fold the point
    masses in.

    Parameters
    ----------
    name : str
        Free text for tables and reports.
    mass_kg : float
        Strung mass, kg.
    length_m : float
        Overall length, m.
    balance_m : float
        Centre of mass (balance point) from the butt, m.
    inertia_cg_kgm2 : float
        Moment of inertia about an axis across the handle through the centre of mass, kg·m².
    roll_inertia_kgm2 : float
        Moment of inertia about the long axis (twistweight ×1e-4), kg·m².
    head : HeadEllipse
        String-bed ellipse.
    strings : StringBed
        String-bed construction.
    grip_m : float
        Grip (pivot) axis from the butt, m: the paper's 70 mm, the middle of a hand.
    point_masses : tuple of PointMass
        Added masses (lead tape).
    modal_model_file : Path or None
        A modal model (racketdyn JSON) to use instead of the built-in beam model.
    first_bending_hz, twisting_hz : float
        Targets for the built-in modal model's free 2-node bending and 2-node twisting modes, Hz.
    """

    name: str
    mass_kg: float
    length_m: float
    balance_m: float
    inertia_cg_kgm2: float
    roll_inertia_kgm2: float
    head: HeadEllipse
    strings: StringBed = field(default_factory=StringBed)
    grip_m: float = 0.070
    point_masses: tuple[PointMass, ...] = ()
    modal_model_file: Path | None = None
    first_bending_hz: float = 120.0
    twisting_hz: float = 361.0

    def __repr__(self) -> str:
        return (
            f"<Racket {shorten(self.name)!r}: mass_kg={number(self.mass_kg)}, "
            f"length_m={number(self.length_m)}, balance_m={number(self.balance_m)}, "
            f"inertia_cg_kgm2={number(self.inertia_cg_kgm2)}, grip_m={number(self.grip_m)}, "
            f"head {number(self.head.area_m2 * 1e4)} cm², strings {self.strings.mains}×"
            f"{self.strings.crosses} at {number(self.strings.tension_n)} N "
            f"({number(self.strings.bed_tension_n)} N in the bed), "
            f"{len(self.point_masses)} point masses>"
        )

    def _repr_html_(self) -> str:
        rows = [
            ("mass", f"{number(self.mass_kg)} kg"),
            ("length", f"{number(self.length_m)} m"),
            ("balance", f"{number(self.balance_m)} m from the butt"),
            ("inertia about the balance point", f"{number(self.inertia_cg_kgm2)} kg·m²"),
            ("roll inertia", f"{number(self.roll_inertia_kgm2)} kg·m²"),
            ("grip", f"{number(self.grip_m)} m from the butt"),
            ("head", f"{number(self.head.area_m2 * 1e4)} cm²"),
            (
                "strings",
                f"{self.strings.mains}×{self.strings.crosses} at "
                f"{number(self.strings.tension_n)} N "
                f"({number(self.strings.bed_tension_n)} N in the bed)",
            ),
            ("point masses", str(len(self.point_masses))),
        ]
        return html_table(f"Racket: {self.name}", rows)

    def __post_init__(self) -> None:
        require_positive("racket.mass_kg", self.mass_kg)
        require_positive("racket.length_m", self.length_m)
        require_positive("racket.inertia_cg_kgm2", self.inertia_cg_kgm2)
        require_positive("racket.roll_inertia_kgm2", self.roll_inertia_kgm2)
        require_positive("modal.first_bending_hz", self.first_bending_hz)
        require_positive("modal.twisting_hz", self.twisting_hz)
        require_positive("racket.balance_m", self.balance_m)
        if self.balance_m >= self.length_m:
            raise InputError(
                f"racket.balance_m ({self.balance_m} m) must lie between the butt and the tip "
                f"(0 < balance_m < length_m = {self.length_m} m)"
            )
        require_positive("racket.grip_m", self.grip_m, allow_zero=True)
        if self.grip_m >= self.balance_m:
            raise InputError(
                f"racket.grip_m ({self.grip_m} m) must lie between the butt and the balance point "
                f"({self.balance_m} m)"
            )
        if self.head.tip_x_m > self.length_m + 1e-9 or self.head.throat_x_m <= self.grip_m:
            raise InputError(
                f"head ellipse (x from {self.head.throat_x_m:.3f} to {self.head.tip_x_m:.3f} m) "
                f"must lie between the grip ({self.grip_m} m) and the tip "
                f"(length_m = {self.length_m} m)"
            )
        for i, p in enumerate(self.point_masses):
            if not 0.0 <= p.x_m <= self.length_m:
                raise InputError(
                    f"point_masses[{i}].x_m ({p.x_m} m) must lie on the racket "
                    f"(0 to {self.length_m} m)"
                )

    # --- mass properties -------------------------------------------------------------------
    @property
    def base_mass_properties(self) -> MassProperties:
        """Mass properties of the racket without point masses."""
        inertia = np.diag([self.roll_inertia_kgm2, self.inertia_cg_kgm2])
        return MassProperties(self.mass_kg, (self.balance_m, 0.0), inertia)

    @property
    def mass_properties(self) -> MassProperties:
        """Mass properties with the point masses folded in."""
        return self.base_mass_properties.with_point_masses(self.point_masses)

    @property
    def pivot_m(self) -> tuple[float, float]:
        """The grip pivot ``(grip_m, 0)`` used by the ``pinned`` support, m."""
        return (self.grip_m, 0.0)

    def inertia_about_axis(self, x_m: float) -> float:
        """Moment of inertia about an axis across the handle at ``x_m`` from the butt, kg·m².

        Parallel-axis theorem: ``I = I_G + M (x_G - x)²`` (point masses included).
        """
        return float(self.mass_properties.inertia_about((x_m, 0.0))[1, 1])

    @property
    def swingweight_kgcm2(self) -> float:
        """Swingweight: inertia about the axis 100 mm from the butt, kg·cm²."""
        return self.inertia_about_axis(SWINGWEIGHT_AXIS_M) * KGM2_TO_KGCM2

    @property
    def twistweight_kgcm2(self) -> float:
        """Twistweight: inertia about the long axis, kg·cm²."""
        return float(self.mass_properties.inertia_about((0.0, 0.0))[0, 0]) * KGM2_TO_KGCM2

    @property
    def recoil_weight_kgcm2(self) -> float:
        """Recoil weight: inertia about the balance point (``SW − M (x_G − 0.1 m)²``), kg·cm²."""
        return float(self.mass_properties.inertia_kgm2[1, 1]) * KGM2_TO_KGCM2

    def centre_of_percussion_m(self, pivot_x_m: float | None = None) -> float:
        """Centre of percussion for a pivot on the long axis, m from the butt.

        ``x_cop = x_p + I_p / (M (x_G − x_p))``: an impact there leaves the pivot at rest.
        ``pivot_x_m`` defaults to the grip.
        """
        props = self.mass_properties
        pivot = self.grip_m if pivot_x_m is None else pivot_x_m
        arm = props.centre_m[0] - pivot
        if arm <= 0:
            raise InputError(f"pivot ({pivot} m) must lie between the butt and the balance point")
        return pivot + self.inertia_about_axis(pivot) / (props.mass_kg * arm)

    def reduced_mass(self, locations: ArrayLike, support: str) -> NDArray[np.float64]:
        """Reduced mass at each impact location for a support condition, kg.

        ``free``: ``1/M_r = 1/M + b²/I_G + y²/I_roll`` (with point masses, the full in-plane
        inertia tensor).  ``pinned``: the paper's eq (4), ``M_r = I_A / L_A²``, about the grip,
        with the roll term ``y²/I_roll`` added.
        """
        one_of("support", support, SUPPORTS)
        pivot = None if support == "free" else self.pivot_m
        return self.mass_properties.reduced_mass(locations, pivot)

    def with_point_masses(self, *point_masses: PointMass) -> Racket:
        """A copy with more point masses."""
        return replace(self, point_masses=self.point_masses + tuple(point_masses))

    def derived_properties(self) -> dict[str, float]:
        """The derived properties, keyed with unit-bearing names (for tables and run records)."""
        props = self.mass_properties
        centre = self.head.centre_x_m, self.head.centre_y_m
        return {
            "mass_kg": props.mass_kg,
            "balance_m": props.centre_m[0],
            "inertia_cg_kgm2": float(props.inertia_kgm2[1, 1]),
            "inertia_grip_kgm2": self.inertia_about_axis(self.grip_m),
            "swingweight_kgcm2": self.swingweight_kgcm2,
            "twistweight_kgcm2": self.twistweight_kgcm2,
            "recoil_weight_kgcm2": self.recoil_weight_kgcm2,
            "centre_of_percussion_m": self.centre_of_percussion_m(),
            "head_area_cm2": self.head.area_m2 * 1e4,
            "bed_tension_n": self.strings.bed_tension_n,
            "reduced_mass_centre_free_kg": float(self.reduced_mass(centre, "free")[0]),
            "reduced_mass_centre_pinned_kg": float(self.reduced_mass(centre, "pinned")[0]),
        }


TIP_INSET_M = 0.035
"""How far inside the bed's edge the tip landmark lies, m: a tennis ball's radius (33.5 mm,
ITF) and 1.5 mm, so that no deflection brings the ball's section in the plane of the strings
to the hoop there (a ball's section is at most its radius)."""


def landmark_points(racket: Racket) -> dict[str, tuple[float, float]]:
    """Named impact points on the long axis: top, centre and throat (Figs 11–12), tip (Fig. 14).

    Top and throat lie three quarters of the half-length from the centre; the tip
    :data:`TIP_INSET_M` inside the bed's edge, the farthest point on the axis where a ball
    pressed into the strings cannot reach the hoop (the paper's "very end of the string
    surface"; nearer the hoop an impact is a frame shot, ``STATUS_FRAME_CONTACT``).

    Parameters
    ----------
    racket : Racket
        The racket (its head).

    Returns
    -------
    dict
        Name -> (x, y), m.
    """
    head = racket.head
    a, xc, yc = head.half_length_m, head.centre_x_m, head.centre_y_m
    return {
        "top": (xc + 0.75 * a, yc),
        "centre": (xc, yc),
        "throat": (xc - 0.75 * a, yc),
        "tip": (xc + max(a - TIP_INSET_M, 0.75 * a), yc),
    }
