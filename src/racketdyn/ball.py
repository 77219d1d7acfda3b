"""The ball and the restoring-force laws of the ball, the strings and the two in series.

Kawazoe's one-degree-of-freedom contact model (paper, section 3.4): the ball's mass sits at its
centre and only the side touching the strings deforms.  The ball restoring force F_B(X), the
string-bed force F_G(X) and the compound F_GB(X) of the two in series are smooth laws fitted by
least squares to load–deflection data; their derivatives are the stiffnesses K(X) = dF/dX.

Units: deflection X in m, force F in N, stiffness K in N/m.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Literal, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import least_squares

from racketdyn.errors import InputError, one_of, require_positive, require_range
from racketdyn.numerics import invert_increasing
from racketdyn.plausibility import check_limits

__all__ = [
    "BALL_LAW_RANGE_RADII",
    "BOUNCE_COMPRESSION_M",
    "BOUNCE_SPEED_MPS",
    "ITF_FORWARD_DEFORMATION_M",
    "ITF_FORWARD_LOAD_N",
    "ITF_REBOUND_COR",
    "STATIC_WALL_STIFFNESS_N_PER_M",
    "Ball",
    "LawKind",
    "RestoringForce",
    "ball_physical_force",
    "default_ball_law",
    "dynamic_wall_stiffness",
    "series",
]

log = logging.getLogger(__name__)

LawKind = Literal["polynomial", "power"]
LAW_KINDS: tuple[str, ...] = get_args(LawKind)

# ITF Rules of Tennis, Appendix I (docs/references.md, "Ball"): forward deformation 0.56–0.74 cm
# between two plates under 80.1 N.  The middle of the range is used.
ITF_FORWARD_LOAD_N = 80.1
ITF_FORWARD_DEFORMATION_M = 0.5 * (0.56e-2 + 0.74e-2)

# The ball in a bounce (docs/references.md, "The ball in a bounce"): dropped from 100 in
# (2.54 m, 7.06 m/s at impact) onto concrete a ball flattens by about 6 mm (Cross, "The physics
# of tennis", University of Sydney) and rebounds 135–147 cm (ITF Rules, Appendix I): a COR of
# 0.729–0.761, 0.745 in the middle.  These two numbers set the built-in ball's dynamic law.
BOUNCE_SPEED_MPS = 7.06
BOUNCE_COMPRESSION_M = 6.0e-3
ITF_REBOUND_COR = 0.745


@dataclass(frozen=True)
class RestoringForce:
    """A monotone restoring-force law F(X) with F(0) = 0.

    Parameters
    ----------
    kind : {"polynomial", "power"}
        ``polynomial``: ``F = Σ_k c_k X^k`` for k = 1..n (``coefficients = (c_1, …, c_n)``).
        ``power``: ``F = c X^n`` (``coefficients = (c, n)``).
    coefficients : tuple of float
        SI units: c_k in N/m^k; for the power law c in N/m^n and n dimensionless.
    max_deflection_m : float
        Largest deflection the law is valid for (the range of the data it was fitted to), m.
    rms_residual_n : float
        Root-mean-square force residual of the least-squares fit, N (0 for a model law).
    source : str
        Where the law came from, recorded in run files.
    """

    kind: LawKind
    coefficients: tuple[float, ...]
    max_deflection_m: float
    rms_residual_n: float = 0.0
    source: str = ""

    def __post_init__(self) -> None:
        one_of("restoring force kind", self.kind, LAW_KINDS)
        require_positive("restoring force max_deflection_m", self.max_deflection_m)
        if self.kind == "power" and len(self.coefficients) != 2:
            raise InputError("a power law takes two coefficients (c, n) for F = c X^n")
        if not self.coefficients:
            raise InputError("a polynomial restoring force needs at least one coefficient")
        if not all(np.isfinite(self.coefficients)):
            raise InputError(f"restoring force ({self.source}): coefficients must be finite")
        x = np.linspace(0.0, self.max_deflection_m, 257)[1:]
        if np.any(self.stiffness(x) <= 0.0):
            raise InputError(
                f"restoring force ({self.source or self.kind}) is not monotone over 0–"
                f"{self.max_deflection_m * 1e3:.1f} mm: its stiffness dF/dX turns negative; fit a "
                "lower-degree polynomial or a power law"
            )

    def scaled(self, factor: float) -> RestoringForce:
        """This law with every force multiplied by ``factor`` (> 0), same range."""
        require_positive("restoring force scale", factor)
        coefficients = (
            (self.coefficients[0] * factor, self.coefficients[1])
            if self.kind == "power"
            else tuple(c * factor for c in self.coefficients)
        )
        return replace(
            self,
            coefficients=coefficients,
            rms_residual_n=self.rms_residual_n * factor,
            source=f"{self.source} ×{factor:g}",
        )

    # --- evaluation -------------------------------------------------------------------------
    def force(self, deflection: ArrayLike) -> NDArray[np.float64]:
        """Restoring force F(X), N, for deflection X in m."""
        x = np.asarray(deflection, dtype=float)
        if self.kind == "power":
            c, n = self.coefficients
            return np.asarray(c * np.abs(x) ** n * np.sign(x))
        return np.asarray(np.polynomial.polynomial.polyval(x, (0.0, *self.coefficients)))

    def stiffness(self, deflection: ArrayLike) -> NDArray[np.float64]:
        """Tangent stiffness K(X) = dF/dX, N/m."""
        x = np.asarray(deflection, dtype=float)
        if self.kind == "power":
            c, n = self.coefficients
            with np.errstate(divide="ignore"):
                return np.asarray(c * n * np.abs(x) ** (n - 1.0))
        k = np.arange(1, len(self.coefficients) + 1) * np.asarray(self.coefficients)
        return np.asarray(np.polynomial.polynomial.polyval(x, k))

    def curvature(self, deflection: ArrayLike) -> NDArray[np.float64]:
        """Second derivative d²F/dX², N/m²."""
        x = np.asarray(deflection, dtype=float)
        if self.kind == "power":
            c, n = self.coefficients
            with np.errstate(divide="ignore", invalid="ignore"):
                return np.asarray(c * n * (n - 1.0) * np.abs(x) ** (n - 2.0))
        orders = np.arange(1, len(self.coefficients) + 1)
        k2 = (orders * (orders - 1.0) * np.asarray(self.coefficients))[1:]
        return np.asarray(np.polynomial.polynomial.polyval(x, k2)) if k2.size else np.zeros_like(x)

    def energy(self, deflection: ArrayLike) -> NDArray[np.float64]:
        """Stored energy ∫₀ˣ F dX, J."""
        x = np.asarray(deflection, dtype=float)
        if self.kind == "power":
            c, n = self.coefficients
            return np.asarray(c * np.abs(x) ** (n + 1.0) / (n + 1.0))
        orders = np.arange(1, len(self.coefficients) + 1)
        integral = np.asarray(self.coefficients) / (orders + 1.0)
        return np.asarray(np.polynomial.polynomial.polyval(x, (0.0, 0.0, *integral)))

    def unloading_energy(
        self, deflection: ArrayLike, peak: ArrayLike, exponent: ArrayLike
    ) -> NDArray[np.float64]:
        """Energy ∫₀ˣ F(s) (s/X_p)^p ds under the unloading curve from a peak X_p, J.

        The hysteresis of the transient model (:func:`racketdyn.impact.transient.
        unloading_exponent`): the spring unloads along ``F(X) (X/X_p)^p``.  Closed form for both
        kinds; the three arguments broadcast.
        """
        x, x_p, p = (np.asarray(a, dtype=float) for a in (deflection, peak, exponent))
        scale = np.abs(x / x_p) ** p  # one power a point; the orders by multiplication
        if self.kind == "power":
            c, n = self.coefficients
            return np.asarray(scale * c * np.abs(x) ** (n + 1.0) / (n + 1.0 + p))
        # Σ c_k X^(k+1) / (k + 1 + p) = X² Σ c_k X^(k−1) / (k + 1 + p), by Horner
        total = np.zeros(np.broadcast_shapes(x.shape, x_p.shape, p.shape))
        for order in range(len(self.coefficients), 0, -1):
            total = total * x + self.coefficients[order - 1] / (order + 1.0 + p)
        return np.asarray(scale * x**2 * total)

    def unloading_exponent(self, peak: ArrayLike, cor: ArrayLike) -> NDArray[np.float64]:
        """Exponent p of the unloading curve ``F(X) (X/X_p)^p`` that gives back cor² of the
        energy stored at the peak X_p: ``∫₀^{X_p} F (X/X_p)^p dX = cor² E(X_p)``.

        The transient model's hysteresis (:func:`racketdyn.impact.transient.unloading_exponent`
        solves it per impact inside its compiled kernel, which cannot call this method); here
        on arrays.  Closed form for a power law; for a polynomial, Newton from p = 0, which
        rises monotonically to the root (the left side is convex and falling in p).

        Parameters
        ----------
        peak : array_like
            X_p > 0, m.
        cor : array_like
            The spring's COR, 0 < cor ≤ 1 (1: p = 0), broadcast against ``peak``.
        """
        x_p, e = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (peak, cor)))
        if self.kind == "power":
            return np.asarray((self.coefficients[1] + 1.0) * (1.0 / e**2 - 1.0))
        orders = np.arange(2.0, len(self.coefficients) + 2.0)
        terms = np.asarray(self.coefficients) * x_p[..., None] ** orders  # c_i X_p^(i+2)
        target = e**2 * np.sum(terms / orders, axis=-1)
        p = np.zeros(x_p.shape)
        for _ in range(100):
            share = terms / (orders + p[..., None])
            step = (np.sum(share, axis=-1) - target) / -np.sum(share / (orders + p[..., None]), -1)
            p = p - step
            if not np.any(np.abs(step) > 1e-15 * (1.0 + p)):
                break
        return np.asarray(np.where(e >= 1.0, 0.0, p))

    @property
    def max_force_n(self) -> float:
        """Force at the end of the valid range, N."""
        return float(self.force(self.max_deflection_m))

    def deflection(self, force: ArrayLike) -> NDArray[np.float64]:
        """Inverse law X(F), m; NaN beyond the valid range."""
        return invert_increasing(self.force, self.stiffness, force, self.max_deflection_m)

    def deflection_at_energy(self, energy: ArrayLike) -> NDArray[np.float64]:
        """Deflection at which the stored energy ∫F dX reaches ``energy`` (J), m; NaN beyond."""
        return invert_increasing(self.energy, self.force, energy, self.max_deflection_m)

    def describe(self) -> str:
        """One line: the law, its range and fit residual."""
        if self.kind == "power":
            c, n = self.coefficients
            law = f"F = {c:.4g}·X^{n:.4g}"
        else:
            law = "F = " + " + ".join(f"{c:.4g}·X^{k}" for k, c in enumerate(self.coefficients, 1))
        return (
            f"{law} (N, m) for X ≤ {self.max_deflection_m * 1e3:.1f} mm, "
            f"rms residual {self.rms_residual_n:.3g} N [{self.source}]"
        )

    def as_dict(self) -> dict[str, object]:
        """Plain dict for run records."""
        return {
            "kind": self.kind,
            "coefficients": list(self.coefficients),
            "max_deflection_m": self.max_deflection_m,
            "rms_residual_n": self.rms_residual_n,
            "source": self.source,
        }

    # --- fitting ----------------------------------------------------------------------------
    @classmethod
    def fit(
        cls,
        deflection: ArrayLike,
        force: ArrayLike,
        kind: LawKind = "polynomial",
        degree: int = 3,
        source: str = "least-squares fit",
        *,
        relative: bool = False,
    ) -> RestoringForce:
        """Fit a law to load–deflection data by least squares (paper, section 3.4).

        Parameters
        ----------
        deflection : array_like
            Deflections X, m (non-negative).
        force : array_like
            Forces F, N, one per deflection.
        kind : {"polynomial", "power"}
            Law to fit.  The polynomial has no constant term (F(0) = 0); its columns are scaled
            by the largest deflection so the normal equations stay well conditioned.  The power
            law is fitted on the force residual (not in log space) with a log–log start.
        degree : int
            Highest power of the polynomial.
        source : str
            Recorded with the law.
        relative : bool
            Polynomial only: minimise the *relative* force residual (each point weighted by
            1/F), so a law spanning 0.1 kN to 10 kN stays accurate at the low forces too.

        Returns
        -------
        RestoringForce
            The law, with the rms force residual and the data's deflection range.
        """
        one_of("restoring force kind", kind, LAW_KINDS)
        x = np.asarray(deflection, dtype=float).ravel()
        f = np.asarray(force, dtype=float).ravel()
        if x.shape != f.shape:
            raise InputError(f"{source}: deflection and force columns differ in length")
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(f))):
            raise InputError(f"{source}: load–deflection data must be finite numbers (no NaN)")
        if np.any(x < 0) or np.any(f < 0):
            raise InputError(f"{source}: deflections (m) and forces (N) must not be negative")
        keep = x > 0
        x, f = x[keep], f[keep]
        needed = degree if kind == "polynomial" else 2
        if x.size < max(needed, 2) + 1:
            raise InputError(
                f"{source}: need at least {max(needed, 2) + 1} points with positive deflection "
                f"to fit a {kind} law (got {x.size})"
            )
        scale = float(x.max())
        if kind == "polynomial":
            if not 1 <= degree <= 9:
                raise InputError(f"polynomial degree must be 1 to 9 (got {degree})")
            columns = (x[:, None] / scale) ** np.arange(1, degree + 1)
            weight = 1.0 / np.maximum(f, 1e-9 * f.max()) if relative else np.ones_like(f)
            scaled, *_ = np.linalg.lstsq(columns * weight[:, None], f * weight, rcond=None)
            coefficients = tuple(float(c) for c in scaled / scale ** np.arange(1, degree + 1))
        else:
            positive = f > 0
            if positive.sum() < 2:
                raise InputError(f"{source}: a power law needs at least two positive forces")
            slope, intercept = np.polyfit(np.log(x[positive] / scale), np.log(f[positive]), 1)

            def residual(p: NDArray[np.float64]) -> NDArray[np.float64]:
                return np.asarray(p[0] * (x / scale) ** p[1] - f)

            solution = least_squares(
                residual, x0=[np.exp(intercept), slope], bounds=([0.0, 0.05], [np.inf, 10.0])
            )
            c_scaled, n = solution.x
            coefficients = (float(c_scaled / scale**n), float(n))
        trial = cls(kind, coefficients, scale, 0.0, source)
        rms = float(np.sqrt(np.mean((trial.force(x) - f) ** 2)))
        return cls(kind, coefficients, scale, rms, source)


def series(
    first: RestoringForce,
    second: RestoringForce,
    kind: LawKind = "polynomial",
    degree: int = 5,
    source: str = "",
    *,
    relative: bool = False,
) -> RestoringForce:
    """The law of two springs in series, fitted by least squares (the paper's F_GB).

    For a force F both springs carry F, so ``X_GB(F) = X_1(F) + X_2(F)``.  The compound curve is
    sampled up to the smaller of the two laws' largest forces and fitted with
    :meth:`RestoringForce.fit` (``relative``: on the relative force residual); the fit residual
    is recorded on the result.
    """
    top = min(first.max_force_n, second.max_force_n)
    # samples even in force, plus a geometric run so the low forces of slow impacts are dense
    force = np.unique(
        np.concatenate([np.linspace(0.0, top, 400), np.geomspace(top * 1e-3, top, 200)])
    )
    deflection = first.deflection(force) + second.deflection(force)
    return RestoringForce.fit(
        deflection,
        force,
        kind,
        degree,
        source or f"series of ({first.source}) and ({second.source})",
        relative=relative,
    )


BALL_GAUGE_PRESSURE_PA = 83.0e3
"""Internal gauge pressure of a pressurised ball, Pa (≈ 12 psi, the usual figure; assumption)."""
ATMOSPHERE_PA = 101.325e3
AIR_HEAT_CAPACITY_RATIO = 1.4


BALL_LAW_RANGE_RADII = 1.65
"""Range of the default ball law in ball radii (1.65 R ≈ 55 mm, ≈ 22 kN): a ball on a rigid
plate stores ½ m V² at 70 m/s (141 J) at ≈ 53 mm, so the law covers relative speeds to
≈ 75 m/s even on a rigid plate, and far beyond on a string bed (docs/references.md,
"High-speed contact")."""
BALL_LAW_DEGREE = 9


def ball_physical_force(
    deflection: ArrayLike,
    diameter_m: float = 0.067,
    gauge_pressure_pa: float = BALL_GAUGE_PRESSURE_PA,
    wall_stiffness_n_per_m: float | None = None,
) -> NDArray[np.float64]:
    """The one-sided ball force the default law is fitted to, N for a flattening X in m.

    ``F = k₁ X + (p(X) − p₀) A(X)``:

    * ``k₁ X`` — the wall and the initial pressure: ``wall_stiffness_n_per_m``, by default the
      ITF forward deformation's (80.1 N over half of 6.5 mm: the test flattens both sides, the
      model one), the *static* ball of a slow plate test.  The built-in ball law passes the
      dynamic wall of a bounce (:func:`dynamic_wall_stiffness`).
    * ``p(X) = p₀ (V₀ / (V₀ − V_cap))^γ`` — the gas compressed adiabatically (γ = 1.4, p₀
      absolute) by the cap of height X cut off the sphere, ``V_cap = π X² (3R − X)/3``.
    * ``A(X)`` — the flat the extra pressure acts on: the cap's base ``π (2RX − X²)`` up to one
      radius, then the ball's cross-section ``π R²`` (beyond one radius the wall folds inwards;
      the flat cannot outgrow the ball).  A is continuous with its slope at X = R.

    For small X this is the earlier cubic ``k₁ X + (3π/2) γ p₀ X³/R``; near one radius the exact
    geometry is ≈ 10 % softer; beyond it the shrinking gas volume makes the law stiffen without
    bound (V → 0 as X → 2R), which is what keeps a ball at serve speeds from flattening through.
    """
    x = np.asarray(deflection, dtype=float)
    radius = 0.5 * diameter_m
    absolute = gauge_pressure_pa + ATMOSPHERE_PA
    volume = 4.0 / 3.0 * np.pi * radius**3
    cap = np.pi * x**2 * (3.0 * radius - x) / 3.0
    pressure = absolute * (volume / (volume - cap)) ** AIR_HEAT_CAPACITY_RATIO
    area = np.where(x < radius, np.pi * (2.0 * radius * x - x**2), np.pi * radius**2)
    linear = (
        STATIC_WALL_STIFFNESS_N_PER_M if wall_stiffness_n_per_m is None else wall_stiffness_n_per_m
    )
    return np.asarray(linear * x + (pressure - absolute) * area)


STATIC_WALL_STIFFNESS_N_PER_M = ITF_FORWARD_LOAD_N / (0.5 * ITF_FORWARD_DEFORMATION_M)
"""One-sided secant stiffness of the ITF plate test (80.1 N over half of 6.5 mm), ≈ 24.6 kN/m:
the ball pressed slowly, not in a bounce."""


@lru_cache(maxsize=16)
def dynamic_wall_stiffness(
    mass_kg: float = 0.0577,
    diameter_m: float = 0.067,
    gauge_pressure_pa: float = BALL_GAUGE_PRESSURE_PA,
    compression_m: float = BOUNCE_COMPRESSION_M,
    speed_mps: float = BOUNCE_SPEED_MPS,
) -> float:
    """Wall stiffness k₁ of a ball that flattens by ``compression_m`` on a rigid surface at
    ``speed_mps``, N/m (the ball's own bounce, measured: docs/references.md).

    Solves ``∫₀^{X} F(x) dx = ½ m V²`` for k₁ with F of :func:`ball_physical_force`: the ball's
    kinetic energy is held in its flattening when it stops.  For the built-in ball (6 mm at
    7.06 m/s) k₁ ≈ 79 kN/m, 3.2 times the slow ITF plate test's 24.6 kN/m — the dynamic
    stiffness of a bounce that Haake, Carré and Goodwill (2003) measured above the static one.
    """
    x = np.linspace(0.0, compression_m, 401)
    gas = ball_physical_force(x, diameter_m, gauge_pressure_pa, 0.0)
    gas_energy = float(np.trapezoid(gas, x))
    kinetic = 0.5 * mass_kg * speed_mps**2
    if kinetic <= gas_energy:
        raise InputError(
            f"ball bounce: {compression_m * 1e3:g} mm at {speed_mps:g} m/s is softer than the gas "
            "alone; check the compression (m) and speed (m/s)"
        )
    return 2.0 * (kinetic - gas_energy) / compression_m**2


@lru_cache(maxsize=16)  # a frozen law; every Ball() would otherwise refit it
def default_ball_law(
    diameter_m: float = 0.067,
    gauge_pressure_pa: float = BALL_GAUGE_PRESSURE_PA,
    wall_stiffness_n_per_m: float | None = None,
) -> RestoringForce:
    """The ball's one-sided restoring force F_B(X) in a bounce, N for X in m (section 3.4).

    A degree-9 polynomial fitted, on the relative residual, to :func:`ball_physical_force` over
    0 to 1.65 ball radii (docs/develop.md, "Ball and string laws"; its rms force residual is
    recorded).  The wall is the *dynamic* wall of a bounce, ``wall_stiffness_n_per_m`` or by
    default :func:`dynamic_wall_stiffness` (the built-in ball flattens 6 mm at 7.06 m/s on a
    rigid surface, Cross; ≈ 79 kN/m); the adiabatic gas sets the law at large flattening, where
    it stiffens steeply.  The slow ITF plate test (24.6 kN/m one-sided) is a different test:
    ``wall_stiffness_n_per_m=STATIC_WALL_STIFFNESS_N_PER_M`` gives the static ball, which
    ``racketdyn ball`` sets beside the ITF limits as a separate check.

    Cross (Sports Eng. 1999) shows the wall buckling within the first 200 µs; one smooth
    loading law is the model's approximation (docs/references.md).
    """
    wall = dynamic_wall_stiffness() if wall_stiffness_n_per_m is None else wall_stiffness_n_per_m
    radius = 0.5 * diameter_m
    top = BALL_LAW_RANGE_RADII * radius
    x = np.linspace(0.0, top, 801)
    which = "static ITF" if wall == STATIC_WALL_STIFFNESS_N_PER_M else "bounce"
    law = RestoringForce.fit(
        x,
        ball_physical_force(x, diameter_m, gauge_pressure_pa, wall),
        "polynomial",
        BALL_LAW_DEGREE,
        f"ball, {which} wall {wall / 1e3:.1f} kN/m + adiabatic gas, one side",
        relative=True,
    )
    return law


@dataclass(frozen=True)
class Ball:
    """A tennis ball.

    Parameters
    ----------
    mass_kg : float
        Mass, kg (ITF: 56.0–59.4 g; default the middle, 57.7 g).
    diameter_m : float
        Diameter, m (ITF type 1 and 2: 6.54–6.86 cm; default the middle, 6.70 cm).
    e_bg : float or None
        Coefficient of restitution of this ball on a head-clamped string bed, used at every
        speed unless ``e_bg_table`` is given.  ``None`` (the default): e_BG follows from the
        ball and the strings at each speed (:func:`racketdyn.contact.ball_string_cor`; the
        impact models resolve it with :func:`racketdyn.contact.with_ball_string_cor`), ≈ 0.84
        at 4.4 m/s falling to ≈ 0.82 at 40 m/s on the paper's racket — Kawazoe measured it
        "almost independent" of speed and tension (≈ 0.83), Haake, Carré and Goodwill (2003)
        falling with speed.
    restoring_force : RestoringForce
        One-sided ball law F_B(X) in a bounce (default: :func:`default_ball_law`).
    e_bg_table : tuple of (float, float)
        Optional e_BG against the relative (approach) speed: ``((speed_mps, e_bg), …)``,
        speeds rising, interpolated linearly and held at the end values outside the table.
        Given, it overrides ``e_bg``.
    rigid_cor : float
        The ball's own COR on a rigid surface (ITF rebound test from 100 in: 0.729–0.761; the
        middle, 0.745), its share of the loss on the strings (:func:`racketdyn.contact.
        ball_string_cor`).
    e_bg_source : str
        How e_BG was set (recorded with results): empty for a given value or table.
    """

    mass_kg: float = 0.0577
    diameter_m: float = 0.0670
    e_bg: float | None = None
    restoring_force: RestoringForce = field(default_factory=default_ball_law)
    e_bg_table: tuple[tuple[float, float], ...] = ()
    rigid_cor: float = ITF_REBOUND_COR
    e_bg_source: str = ""

    def __post_init__(self) -> None:
        require_positive("ball mass_kg", self.mass_kg)
        require_positive("ball diameter_m", self.diameter_m)
        # a 57.7 kg or 67 m ball is a unit slip, whatever the ball (racketdyn.plausibility);
        # the ITF ranges themselves are checked where a person types them (workflows.inputs)
        check_limits("ball_mass_kg", self.mass_kg, "ball mass_kg")
        check_limits("ball_diameter_m", self.diameter_m, "ball diameter_m")
        require_range("ball rigid_cor", self.rigid_cor, 0.0, 1.0)
        if self.e_bg is not None:
            require_range("ball e_bg", self.e_bg, 0.0, 1.0)
            if self.e_bg == 0:
                raise InputError(
                    "ball e_bg must be above 0: a ball that does not rebound has no rebound"
                )
        if self.e_bg_table:
            table = np.asarray(self.e_bg_table, dtype=float)
            if table.ndim != 2 or table.shape[1] != 2:
                raise InputError("ball e_bg_table: give (speed_mps, e_bg) pairs")
            if not np.all(np.isfinite(table)):
                raise InputError("ball e_bg_table: speeds and e_bg must be finite numbers")
            if np.any(table[:, 0] < 0) or np.any(np.diff(table[:, 0]) <= 0):
                raise InputError("ball e_bg_table: speeds (m/s) must be ≥ 0 and strictly rising")
            if np.any(table[:, 1] <= 0) or np.any(table[:, 1] > 1):
                raise InputError("ball e_bg_table: every e_bg must be above 0 and at most 1")

    @property
    def e_bg_given(self) -> bool:
        """Whether e_BG was given (a value or a table) rather than left to ball + strings."""
        return self.e_bg is not None or bool(self.e_bg_table)

    @property
    def speed_dependent(self) -> bool:
        """Whether e_BG depends on speed (a table, given or derived from ball + strings)."""
        return bool(self.e_bg_table) or self.e_bg is None

    def e_bg_at(self, speed: ArrayLike) -> NDArray[np.float64]:
        """e_BG at relative (approach) speeds, m/s: the table's linear interpolation, held at
        its end values outside it; the constant ``e_bg`` without a table.

        Raises
        ------
        InputError
            If e_BG is neither given nor resolved from ball + strings
            (:func:`racketdyn.contact.with_ball_string_cor`).
        """
        v = np.asarray(speed, dtype=float)
        if self.e_bg_table:
            table = np.asarray(self.e_bg_table, dtype=float)
            return np.asarray(np.interp(v, table[:, 0], table[:, 1]))
        if self.e_bg is None:
            raise InputError(
                "ball e_bg: not given and not yet derived from the ball and the strings; "
                "resolve it with racketdyn.contact.with_ball_string_cor(racket, ball) or give "
                "e_bg"
            )
        return np.full(v.shape, self.e_bg)

    def e_bg_record(self) -> dict[str, object]:
        """How e_BG was set, for run records."""
        if self.e_bg_source:
            return {
                "kind": self.e_bg_source,
                "table": [list(map(float, row)) for row in self.e_bg_table],
            }
        if not self.e_bg_table:
            return {
                "kind": "constant" if self.e_bg is not None else "ball + strings (unresolved)",
                "e_bg": self.e_bg,
            }
        return {
            "kind": "table (relative speed m/s, e_BG), linear, held beyond the ends",
            "table": [list(map(float, row)) for row in self.e_bg_table],
        }
