"""Poles from FRFs: LSCF (PolyMAX-type) stabilisation diagram and automatic pole selection.

:func:`stabilisation` fits a common-denominator rational model to every FRF of a set over a
chosen band, at every model order up to ``max_order``, and classes each pole by how it agrees
with the poles of the order below (frequency, damping, shape).  :func:`select_poles` picks the
physical modes from the stable poles with no clicking: it clusters them across orders, keeps
close modes apart and lets the user pin or exclude modes by approximate frequency.
:meth:`Stabilisation.plot` draws the diagram (with
:func:`racketdyn.plotting.primitives.plot_stabilisation`).

The estimator
    Least-squares complex-frequency (LSCF) common-denominator model in the z-domain
    (Guillaume, Verboven, Vanlanduit, Van der Auweraer and Peeters, "A poly-reference
    implementation of the least-squares complex frequency-domain estimator", IMAC XXI, 2003;
    Peeters, Van der Auweraer, Guillaume and Leuridan, "The PolyMAX frequency-domain method",
    Shock and Vibration 11, 2004)::

        H_o(ω_f) ≈ N_o(Ω_f) / d(Ω_f),   N_o(Ω) = Σ_r β_or Ω^r,   d(Ω) = Σ_r α_r Ω^r,
        Ω_f = exp(i θ_f),   θ_f = (ω_f − ω_0) Δt,   r = 0 … n,

    with complex coefficients (each pole is one mode: no conjugate twins) and the band
    ``f_0 … f_{F−1}`` (F lines) spread over the whole unit circle, ``Δt = 1 / (F δf)`` with δf
    the mean line spacing.  For evenly spaced lines the numerator block of the normal equations
    is then exactly ``F·I`` (perfectly conditioned at any order); the price is a jump between
    the band's two ends, which the model meets with poles at the band's edges, and
    :func:`select_poles` keeps away from them.  Poles are ``λ = ln(z)/Δt + iω_0``.
Normal equations at every order from one build
    Minimising ``Σ_o Σ_f |N_o − H_o d|²`` gives for each FRF the blocks ``R = ΓᴴΓ``,
    ``S_o = −ΓᴴD_oΓ`` and ``T_o = ΓᴴD_oᴴD_oΓ`` (Γ the basis ``Ω_f^r``, D_o = diag H_o), all
    Toeplitz in ``r − s`` (built from FFTs of the FRFs); the numerators are eliminated
    (``β_o = −R⁻¹S_o α``), leaving ``M α ≈ 0`` with ``M = Σ_o (T_o − S_oᴴ R⁻¹ S_o)``, solved
    with ``α_m = 1``.  The blocks of a lower order are the leading sub-blocks of the highest
    order's, and so is the Cholesky factor of R: with ``R = LLᴴ`` and ``X_o = L⁻¹ S_o`` built
    once at the highest order, the reduced matrix of order m is
    ``T[:m+1, :m+1] − Σ_o Σ_{k≤m} X_o[k, :m+1]ᴴ X_o[k, :m+1]``: one rank-n_o update per order
    instead of sdypy-EMA's inverse and n_o products per order.
Noise
    Noise on the FRFs biases the plain least-squares denominator: in expectation it adds
    ``σ² (1 − (m+1)/F) R`` to the reduced matrix (σ² summed over the FRFs, white over the band),
    which pulls the damping ratios up (at 1 % noise by 20 % and more at the orders a
    stabilisation diagram uses, converging slowly with the order).  The noise variance of each
    FRF is estimated from its second differences (a robust median; capped by the smallest
    eigenvalue of the reduced matrix at the highest order, which it cannot exceed) and the
    term is subtracted before solving (bias-compensated least squares; ``noise_compensation``).
    The estimate is kept as ``Stabilisation.noise_rms`` and :func:`select_poles` uses it to
    tell a peak from the noise.
Poles
    The roots of ``d`` at each order, found by Aberth–Ehrlich iteration from the roots of the
    order below (most poles move little from one order to the next; the companion matrix's
    eigenvalues when that fails), which is three to four times cheaper than an eigenvalue
    solve at order 100 and gives the same roots to round-off.  Kept: poles inside the unit
    circle (stable) whose natural frequency lies in the band.
Shapes
    Each pole gets the residues of the fitted model, ``A_ok = N_o(z_k) / (d'(z_k) z_k Δt)``
    (FRF units × rad/s; ``H_o ≈ A_ok / (iω − λ_k)`` near the pole): rough, but good enough to
    compare shapes by MAC across orders, to keep close modes apart, to tell a peak from the
    noise and as starting values.
Exponential window
    An exponential window ``exp(−t/τ)`` moves every pole left by ``1/τ``.  When the FRF set
    carries τ (``FrfSet.exponential_window_s``), ``1/τ`` is added back to the real part of
    each pole, so the frequencies and damping ratios reported are the structure's.  The
    residues are not changed by the window.
Speed
    69 FRFs × 1,551 lines, every order from 1 to 100: about 0.13 s on one core (benchmarks/
    bench_poles.py, against sdypy-EMA on the same data).  The loop over orders calls numpy's
    linear algebra only: mixing in scipy's (a second OpenBLAS with its own thread pool) in a
    loop of small problems makes the two pools fight over the cores.  Small problems run best
    with one BLAS thread (``OPENBLAS_NUM_THREADS=1``); the benchmarks set it.

The algebra follows sdypy-EMA's LSCF (``Model._get_poles_lscf``, after OpenModal's
``lscf.py``; sdypy-EMA is MIT-licensed, © Janko Slavič, Klemen Zaletelj and contributors):
the Toeplitz normal equations from FFTs and the reduced matrix ``Σ (T − Sᴴ R⁻¹ S)``.  Unlike
it, the band is zoomed onto the whole unit circle with complex coefficients, the reduction is
done once for all orders, the noise bias is removed, nothing is printed and no input is
changed.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from enum import IntEnum
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.cluster.hierarchy import fcluster, linkage

from racketdyn.errors import InputError, require_whole
from racketdyn.measurement.records import FrfSet, check_fit_together
from racketdyn.modal.mac import mac
from racketdyn.numerics import one_blas_thread

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = [
    "DEFAULT_SELECTION",
    "DroppedMode",
    "NoModeError",
    "PoleStability",
    "SelectedPoles",
    "SelectionRules",
    "Stabilisation",
    "edge_margin",
    "mac",
    "modal_peak",
    "pole_of",
    "require_rules",
    "select_poles",
    "stabilisation",
]

logger = logging.getLogger(__name__)

Weighting = Literal["uniform", "rms"]


class PoleStability(IntEnum):
    """How a pole agrees with the nearest pole (in frequency) of the order below.

    Each class includes the ones before it: ``DAMPING`` is stable in frequency and damping,
    ``SHAPE`` (fully stable) in frequency, damping and shape.
    """

    NEW = 0
    """No pole of the order below within the frequency tolerance (or the lowest order)."""
    FREQUENCY = 1
    """Frequency within the tolerance."""
    DAMPING = 2
    """Frequency and damping ratio within their tolerances."""
    SHAPE = 3
    """Frequency, damping ratio and shape (MAC) within their tolerances: fully stable."""


@dataclass(frozen=True, eq=False)
class Stabilisation:
    """Poles of an LSCF fit at every model order, with their stability classes.

    Build it with :func:`stabilisation`.  Poles of all orders are stored flat, one entry per
    pole, in order of model order then frequency; ``order`` says which order each came from.

    Parameters
    ----------
    band_hz : tuple of float
        Lowest and highest frequency line of the band fitted, Hz.
    orders : ndarray of int, shape (n_orders,)
        Model orders computed (number of poles of the common denominator), ascending.
    order : ndarray of int, shape (n_poles,)
        Model order of each pole.
    pole : ndarray, complex, shape (n_poles,)
        Poles λ (rad/s, upper half plane), the exponential window's shift removed.
    frequency : ndarray, shape (n_poles,)
        Natural frequency ``|λ| / 2π``, Hz.
    damping_ratio : ndarray, shape (n_poles,)
        Damping ratio ``−Re λ / |λ|`` (can be zero or negative for computational poles once the
        window's shift is removed).
    residues : ndarray, complex, shape (n_points, n_poles)
        Residues of the fitted model at each pole, FRF units × rad/s (see the module
        docstring): the per-pole shape used for MAC.
    stability : ndarray of int8, shape (n_poles,)
        :class:`PoleStability` of each pole.
    frequency_tolerance : float
        Relative frequency change allowed between orders for a stable pole.
    damping_tolerance : float
        Relative damping-ratio change allowed between orders.
    min_mac : float
        Smallest MAC between the shapes at two orders for a stable pole.
    noise_rms : ndarray, shape (n_points,)
        Estimated noise of each FRF, standard deviation per line, FRF units (module
        docstring, "Noise").
    line_spacing_hz : float
        Mean spacing of the FRF lines in the band, Hz.
    time_step_s : float
        Δt of the z-domain mapping ``θ_f = 2π (f − f_0) Δt``, s.
    frf_type : str
        Type of the FRFs fitted (the residues' units follow it).
    exponential_window_s : float or None
        τ of the FRFs' exponential window, s (None: none); ``1/τ`` has been removed.
    nodes : tuple of int
        Node of each FRF (rows of ``residues``).
    source : str
        Where the FRFs came from.
    metadata : dict
        Lines in the band, weighting, noise compensation, whether the lines are evenly spaced.
    """

    band_hz: tuple[float, float]
    orders: NDArray[np.int_]
    order: NDArray[np.int_]
    pole: NDArray[np.complex128]
    frequency: NDArray[np.float64]
    damping_ratio: NDArray[np.float64]
    residues: NDArray[np.complex128]
    stability: NDArray[np.int8]
    frequency_tolerance: float
    damping_tolerance: float
    min_mac: float
    noise_rms: NDArray[np.float64]
    line_spacing_hz: float
    time_step_s: float
    frf_type: str
    exponential_window_s: float | None
    nodes: tuple[int, ...]
    source: str = ""
    metadata: dict[str, Any] = field(default_factory=dict)

    @property
    def n_poles(self) -> int:
        """Number of poles over all orders."""
        return int(self.pole.size)

    @property
    def n_points(self) -> int:
        """Number of FRFs (rows of ``residues``)."""
        return len(self.nodes)

    def at_order(self, order: int) -> NDArray[np.intp]:
        """Indices of the poles of one model order (ascending frequency)."""
        if int(order) not in set(self.orders.tolist()):
            raise InputError(
                f"order {order} was not computed (orders {self.orders[0]}–{self.orders[-1]})"
            )
        return np.flatnonzero(self.order == int(order))

    def plot(
        self,
        selected: SelectedPoles | None = None,
        ax: Axes | None = None,
        frfs: FrfSet | None = None,
    ) -> Axes:
        """The stabilisation diagram (:func:`racketdyn.plotting.primitives.plot_stabilisation`).

        Imports the presentation layer (matplotlib) when called, not before.

        Parameters
        ----------
        selected : SelectedPoles, optional
            Modes to mark with vertical lines (pinned ones solid).
        ax : matplotlib Axes, optional
            Where to draw; a new figure if None.
        frfs : FrfSet, optional
            FRFs whose summed magnitude to draw on a twin log axis (over the band).

        Returns
        -------
        Axes
        """
        from racketdyn.plotting.primitives import plot_stabilisation

        return plot_stabilisation(self, selected=selected, ax=ax, frfs=frfs)


@dataclass(frozen=True)
class DroppedMode:
    """A candidate mode left out, with the evidence (one row of ``dropped_modes.csv``).

    Attributes
    ----------
    frequency_hz : float
        Its frequency, Hz.
    damping_ratio : float
        Its damping ratio.
    orders_stable : int
        Model orders it was stable in.
    stage : str
        ``selection`` (the stabilisation diagram's rules), ``merged`` (one peak with a kept
        mode of the same shape; the reason names it), ``line`` (an electrical line: a mains
        harmonic with ζ ≈ 0), ``unsettled`` (a clear peak stable in too few orders; the reason
        names the pin that keeps it), ``edge`` (a clear mode in the band's edge margin; the
        reason names the option that keeps it), ``no force`` (a clear peak above the band
        the hammer's force fills: the response's noise over none) or ``constants`` (what
        the modal constants showed: no peak in the data, not normalisable at the driving
        point).
    reason : str
        Why, in words.
    peak_to_noise : float
        Its peak over the FRF's noise (NaN where not computed).
    fit_gain : float
        How much worse the fit is near its frequency without it (NaN where not computed);
        about 1 for a pole with no peak in the data.
    driving_point_ratio : float
        Its driving-point constant over its largest constant, signed (NaN where not computed).
    merged_into_hz : float
        For a ``merged`` row, the frequency of the mode it was merged into, Hz (NaN
        otherwise): :func:`racketdyn.modal.identify.identify` tries the row in that mode's
        place when the modal constants find no peak for the mode.
    """

    frequency_hz: float
    damping_ratio: float
    orders_stable: int
    stage: str
    reason: str
    peak_to_noise: float = math.nan
    fit_gain: float = math.nan
    driving_point_ratio: float = math.nan
    merged_into_hz: float = math.nan

    COLUMNS: ClassVar[tuple[str, ...]] = (
        "frequency_hz",
        "damping_ratio",
        "orders_stable",
        "stage",
        "reason",
        "peak_to_noise",
        "fit_gain",
        "driving_point_ratio",
    )

    def row(self) -> list[str]:
        """The CSV row: numbers to 6 significant figures, NaN left empty."""

        def text(value: float) -> str:
            return "" if math.isnan(value) else f"{value:.6g}"

        return [
            text(self.frequency_hz),
            text(self.damping_ratio),
            str(self.orders_stable),
            self.stage,
            self.reason,
            text(self.peak_to_noise),
            text(self.fit_gain),
            text(self.driving_point_ratio),
        ]


@dataclass(frozen=True, eq=False)
class SelectedPoles:
    """The physical poles picked from a stabilisation diagram, one per mode.

    Parameters
    ----------
    frequency : ndarray, shape (n_modes,)
        Natural frequencies (median over the orders the mode was stable in), Hz.
    damping_ratio : ndarray, shape (n_modes,)
        Damping ratios (median), the exponential window's share removed.
    pole : ndarray, complex, shape (n_modes,)
        ``λ = −ζω + iω√(1 − ζ²)``, rad/s, from the two above: the structure's poles, the
        window's share removed — what :func:`~racketdyn.modal.residues.fit_modal_constants`
        takes.
    n_orders : ndarray of int, shape (n_modes,)
        Number of model orders in which each mode was fully stable.
    frequency_spread_hz : ndarray, shape (n_modes,)
        Standard deviation of the frequency over those orders, Hz.
    damping_spread : ndarray, shape (n_modes,)
        Standard deviation of the damping ratio over those orders.
    peak_to_noise : ndarray, shape (n_modes,)
        Each mode's peak ``|A| / σ`` in the FRF where it is largest, over that FRF's noise.
    residues : ndarray, complex, shape (n_points, n_modes)
        The LSCF model's residues at the pole nearest each mode's median (FRF units × rad/s):
        starting values, not a residue fit.
    pinned : ndarray of bool, shape (n_modes,)
        True for modes the user pinned.
    band_hz : tuple of float
        The band of the stabilisation, Hz.
    exponential_window_s : float or None
        τ of the FRFs' exponential window, s.  The windowed FRFs show the poles moved by
        −1/τ (:attr:`windowed_pole`); :func:`~racketdyn.modal.residues.fit_modal_constants`
        takes the structure's :attr:`pole` and moves them itself.
    n_orders_computed : int
        Number of orders in the stabilisation diagram.
    nodes : tuple of int
        Node of each FRF (rows of ``residues``).
    dropped : tuple of str
        What was left out and why (one line per cluster of stable poles), also logged.
    dropped_modes : tuple of DroppedMode
        The same as a table, plus what identification left out later.
    pair_fitted : ndarray of bool, shape (n_modes,), optional
        True for the second mode of a close pair fitted on the FRFs' own lines
        (:func:`racketdyn.modal.identify.identify`): no cluster of the band's orders is its own,
        so its ``n_orders`` is its pair's (the first mode's) and its spreads are NaN; what a
        user reads (:meth:`orders_stable`) has no count for it.  None: no such mode.
    at_peak : ndarray of bool, shape (n_modes,), optional
        True for a mode pinned at the data's peak where no cluster of the fit stands
        (:func:`racketdyn.modal.identify.identify`: its pole from the poles that agree with
        the peak in frequency, or a local fit of the peak's lines): no cluster is its own, so
        its ``n_orders`` (the orders whose pole there is stable in damping too) is no count
        of a cluster's, and :meth:`orders_stable` has none for it.  None: no such mode.
    """

    frequency: NDArray[np.float64]
    damping_ratio: NDArray[np.float64]
    pole: NDArray[np.complex128]
    n_orders: NDArray[np.int_]
    frequency_spread_hz: NDArray[np.float64]
    damping_spread: NDArray[np.float64]
    peak_to_noise: NDArray[np.float64]
    residues: NDArray[np.complex128]
    pinned: NDArray[np.bool_]
    band_hz: tuple[float, float]
    exponential_window_s: float | None
    n_orders_computed: int
    nodes: tuple[int, ...]
    dropped: tuple[str, ...] = ()
    dropped_modes: tuple[DroppedMode, ...] = ()
    pair_fitted: NDArray[np.bool_] | None = None
    at_peak: NDArray[np.bool_] | None = None

    @property
    def n_modes(self) -> int:
        """Number of modes selected."""
        return int(self.frequency.size)

    @property
    def omega(self) -> NDArray[np.float64]:
        """Natural angular frequencies, rad/s."""
        return np.asarray(2 * np.pi * self.frequency)

    def select(self, modes: Sequence[int] | NDArray[np.intp] | NDArray[np.bool_]) -> SelectedPoles:
        """The selection restricted to some modes (indices or a boolean mask); ``dropped`` kept."""
        index = np.arange(self.n_modes)[np.asarray(modes)]
        return replace(
            self,
            frequency=self.frequency[index],
            damping_ratio=self.damping_ratio[index],
            pole=self.pole[index],
            n_orders=self.n_orders[index],
            frequency_spread_hz=self.frequency_spread_hz[index],
            damping_spread=self.damping_spread[index],
            peak_to_noise=self.peak_to_noise[index],
            residues=self.residues[:, index],
            pinned=self.pinned[index],
            pair_fitted=None if self.pair_fitted is None else self.pair_fitted[index],
            at_peak=None if self.at_peak is None else self.at_peak[index],
        )

    def flags(self, name: Literal["pair_fitted", "at_peak"]) -> NDArray[np.bool_]:
        """:attr:`pair_fitted` or :attr:`at_peak` as an array, all False where None."""
        given: NDArray[np.bool_] | None = getattr(self, name)
        return np.zeros(self.n_modes, bool) if given is None else given

    def orders_stable(self) -> list[int | None]:
        """Each mode's orders stable as a user reads it (``modes.csv``, run.json): None for a
        close pair's second mode, fitted on the FRFs' own lines (:attr:`pair_fitted`), and for
        a mode pinned at the data's peak (:attr:`at_peak`): no cluster is theirs."""
        none = self.flags("pair_fitted") | self.flags("at_peak")
        return [None if f else int(n) for n, f in zip(self.n_orders, none, strict=True)]

    @property
    def windowed_pole(self) -> NDArray[np.complex128]:
        """The poles as the exponentially windowed FRFs show them (``λ − 1/τ``), rad/s.

        What a fit of the windowed data sees (the LSCF's :attr:`residues` are at these poles).
        Not for :func:`~racketdyn.modal.residues.fit_modal_constants`: it takes the
        structure's :attr:`pole` and moves them by the window the FRFs record, so these would
        be moved twice.  Without a window, :attr:`pole`.
        """
        if self.exponential_window_s is None:
            return self.pole
        return np.asarray(self.pole - 1.0 / self.exponential_window_s)


# --- the stabilisation diagram ---------------------------------------------------------------


def stabilisation(
    frfs: FrfSet | Sequence[FrfSet],
    band_hz: tuple[float, float],
    max_order: int = 60,
    *,
    order_step: int = 1,
    frequency_tolerance: float = 0.01,
    damping_tolerance: float = 0.05,
    min_mac: float = 0.98,
    weighting: Weighting = "uniform",
    noise_compensation: bool = True,
) -> Stabilisation:
    """LSCF poles at every model order over a band, classed by stability (module docstring).

    Parameters
    ----------
    frfs : FrfSet or sequence of FrfSet
        The FRFs (one reference, many hammer points).  Several sets are fitted together; they
        must share the frequency axis, the FRF type and the exponential window.
    band_hz : tuple of float
        Lowest and highest frequency to fit, Hz; the FRF lines between them (inclusive) are
        used.  A band reaching past the measured lines is cut to them (logged).
    max_order : int
        Highest model order: the number of poles of the common denominator (each pole is one
        mode candidate; sdypy-EMA's ``pol_order_high`` counts the same).  The band must hold
        more than ``2 · max_order`` lines.
    order_step : int
        Orders computed: ``max_order, max_order − order_step, …`` down to 1 or more.
    frequency_tolerance : float
        Relative frequency change between consecutive computed orders for a pole to count as
        stable in frequency (default 1 %).
    damping_tolerance : float
        Relative damping-ratio change for stable in damping (default 5 %).
    min_mac : float
        Smallest MAC of the pole's residues with the matched pole's for stable in shape.
    weighting : {"uniform", "rms"}
        ``uniform`` weighs every line of every FRF alike (right when the noise floor is the
        same everywhere, as for one accelerometer); ``rms`` scales each FRF to unit rms over
        the band first, so weak FRFs count as much as strong ones.
    noise_compensation : bool
        Remove the bias that noise on the FRFs puts on the damping (module docstring,
        "Noise").  False gives the plain LSCF estimate, whose damping ratios come out high at
        low orders (at 1 % noise, +20 % and more) and converge slowly with the order.

    Returns
    -------
    Stabilisation
        Poles, frequencies (Hz), damping ratios and residues at every order, and their
        stability classes.  With ``frfs.exponential_window_s`` = τ set, ``1/τ`` is added to the
        real part of every pole: the damping reported is the structure's, not the window's.

    Raises
    ------
    InputError
        FRF sets on different frequency axes or of different types, a band outside the
        measurements or with too few lines for ``max_order``, non-finite or all-zero FRFs,
        tolerances out of range.
    """
    data = _combine(frfs)
    max_order = require_whole("`max_order`", max_order)
    order_step = require_whole("order_step", order_step)
    tolerances = (frequency_tolerance, damping_tolerance, min_mac)
    _check_stabilisation_options(tolerances, weighting, data)
    band = _band(data, band_hz, max_order)
    values, scale = _weighted(band.values, weighting)
    domain = _ZDomain.of(band.frequency, data.exponential_window_s)
    orders = np.arange(max_order, 0, -order_step)[::-1]
    logger.debug(
        "LSCF: %d FRFs × %d lines, %.1f–%.1f Hz, orders %d–%d",
        band.n_points,
        domain.n_lines,
        domain.low_hz,
        domain.high_hz,
        orders[0],
        orders[-1],
    )
    # One BLAS thread: a few hundred small products and solves, which OpenBLAS splits over
    # its threads for nothing but their hand-offs (the demo's 69 FRFs: 0.06 s on one thread,
    # 1–3 s on two threads of a busy two-core machine; the same numbers).
    with one_blas_thread():
        equations = _normal_equations(values, domain.theta, int(orders[-1]), even=domain.even)
        order_flat, pole_flat, residues = _poles_of_orders(
            equations, orders, domain, compensate=noise_compensation
        )
    unscale = np.where(scale > 0, scale, 1.0)
    if weighting == "rms":
        residues = residues / unscale[:, None]
    return Stabilisation(
        **diagram_fields(domain, orders, order_flat, pole_flat, residues, tolerances),
        noise_rms=np.sqrt(equations.noise_variance) / unscale,
        frf_type=data.frf_type,
        exponential_window_s=data.exponential_window_s,
        nodes=data.nodes,
        source=data.source,
        metadata={
            "lines": domain.n_lines,
            "weighting": weighting,
            "noise_compensation": bool(noise_compensation),
            "evenly_spaced": domain.even,
        },
    )


def pole_of(frequency_hz: ArrayLike, damping_ratio: ArrayLike) -> NDArray[np.complex128]:
    """The continuous-time poles of modes of (undamped) natural frequency ``frequency_hz`` (Hz)
    and damping ratio ``damping_ratio``: −ζω + iω√(1 − ζ²), ω = 2πf (rad/s)."""
    zeta = np.asarray(damping_ratio, dtype=float)
    omega = 2 * np.pi * np.asarray(frequency_hz, dtype=float)
    return np.asarray(-zeta * omega + 1j * omega * np.sqrt(1 - zeta**2))


def diagram_fields(
    domain: _ZDomain,
    orders: NDArray[np.int_],
    order: NDArray[np.int_],
    pole: NDArray[np.complex128],
    residues: NDArray[np.complex128],
    tolerances: tuple[float, float, float],
) -> dict[str, Any]:
    """The fields of a :class:`Stabilisation` that its poles and settings give (frequency,
    damping ratio, each pole's stability among its neighbours), whatever fitted the poles:
    the scalar LSCF here and the poly-reference one (:mod:`racketdyn.modal.polyreference`)."""
    magnitude = np.abs(pole)
    frequency = magnitude / (2 * np.pi)
    damping = -pole.real / np.where(magnitude > 0, magnitude, 1.0)  # a pole at 0 Hz: ζ 0
    return {
        "band_hz": (domain.low_hz, domain.high_hz),
        "orders": orders,
        "order": order.astype(int),
        "pole": pole,
        "frequency": frequency,
        "damping_ratio": damping,
        "residues": residues,
        "stability": _classify(order, orders, frequency, damping, residues, *tolerances),
        "frequency_tolerance": float(tolerances[0]),
        "damping_tolerance": float(tolerances[1]),
        "min_mac": float(tolerances[2]),
        "line_spacing_hz": domain.line_spacing_hz,
        "time_step_s": domain.time_step,
    }


def _check_stabilisation_options(
    tolerances: tuple[float, float, float], weighting: str, data: FrfSet
) -> None:
    """Tolerances strictly between 0 and 1, a known weighting, a positive window τ."""
    names = ("frequency_tolerance", "damping_tolerance", "min_mac")
    for name, value in zip(names, tolerances, strict=True):
        if not (isinstance(value, int | float) and 0.0 < value < 1.0):
            raise InputError(f"{name} must lie strictly between 0 and 1 (got {value!r})")
    if weighting not in ("uniform", "rms"):
        raise InputError(f"weighting must be 'uniform' or 'rms' (got {weighting!r})")
    tau = data.exponential_window_s
    if tau is not None and not (math.isfinite(tau) and tau > 0):
        raise InputError(f"{data.source}: exponential window τ must be positive (got {tau!r})")


def _weighted(
    values: NDArray[np.complex128], weighting: str
) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
    """The FRFs as fitted and the scale of each (``rms``: unit rms over the band; else 1)."""
    scale = np.ones(values.shape[0])
    if weighting == "rms":
        rms = np.sqrt(np.mean(np.abs(values) ** 2, axis=1))
        scale = np.where(rms > 0, 1.0 / np.where(rms > 0, rms, 1.0), 0.0)
        values = values * scale[:, None]
    return values, scale


@dataclass(frozen=True)
class _ZDomain:
    """The band zoomed onto the unit circle (module docstring, "The estimator")."""

    low_hz: float
    high_hz: float
    omega_0: float
    """2π f_0, rad/s."""
    n_lines: int
    time_step: float
    """Δt = 1 / (F δf), s."""
    line_spacing_hz: float
    even: bool
    """The lines are evenly spaced (then ``θ_f = 2πf/F`` exactly)."""
    theta: NDArray[np.float64]
    """θ_f = 2π (f − f_0) Δt of each line."""
    shift: float
    """1/τ of the exponential window, added back to every pole (0 without a window)."""

    @classmethod
    def of(cls, frequency: NDArray[np.float64], tau: float | None) -> _ZDomain:
        """The mapping of the band's lines ``frequency`` (Hz), for a window τ (s) or none."""
        n_lines = frequency.size
        span = frequency[-1] - frequency[0]
        time_step = 1.0 / (span * n_lines / (n_lines - 1))
        spacing = np.diff(frequency)
        return cls(
            low_hz=float(frequency[0]),
            high_hz=float(frequency[-1]),
            omega_0=float(2 * np.pi * frequency[0]),
            n_lines=int(n_lines),
            time_step=float(time_step),
            line_spacing_hz=float(span / (n_lines - 1)),
            even=bool(np.allclose(spacing, span / (n_lines - 1), rtol=1e-6, atol=0.0)),
            theta=2 * np.pi * (frequency - frequency[0]) * time_step,
            shift=0.0 if tau is None else 1.0 / tau,
        )

    def to_pole(self, z: NDArray[np.complex128]) -> NDArray[np.complex128]:
        """The poles λ = ln(z)/Δt + iω_0 (rad/s) of roots z, the window's shift removed."""
        angle = np.mod(np.angle(z), 2 * np.pi)
        measured = (np.log(np.maximum(np.abs(z), 1e-300)) + 1j * angle) / self.time_step
        measured += 1j * self.omega_0
        return np.asarray(measured + self.shift)

    def accept(self, z: NDArray[np.complex128]) -> NDArray[np.bool_]:
        """Roots kept: stable, not too wide, with their natural frequency in the band."""
        f_n = np.abs(self.to_pole(z)) / (2 * np.pi)
        # |z| > e^−2π: half-power bandwidth under twice the band (wider cannot be fitted)
        inside = (np.abs(z) < 1.0) & (np.abs(z) > np.exp(-2 * np.pi))
        return np.asarray(inside & (f_n >= self.low_hz) & (f_n <= self.high_hz))


def _poles_of_orders(
    equations: _NormalEquations,
    orders: NDArray[np.int_],
    domain: _ZDomain,
    *,
    compensate: bool,
) -> tuple[NDArray[np.int_], NDArray[np.complex128], NDArray[np.complex128]]:
    """The poles of every order, flat (order, then ascending |λ|), with their residues."""
    order_list, pole_list, residue_list = [], [], []
    fits = _poles_by_order(equations, orders, domain.accept, compensate=compensate)
    for order, (z, residues_z) in zip(orders, fits, strict=True):
        pole = domain.to_pole(z)
        index = np.argsort(np.abs(pole))
        order_list.append(np.full(z.size, order))
        pole_list.append(pole[index])
        residue_list.append(residues_z[:, index] / (z[index] * domain.time_step))
    order_flat = np.concatenate(order_list).astype(int)
    pole_flat = np.concatenate(pole_list).astype(complex)
    return order_flat, pole_flat, np.concatenate(residue_list, axis=1)


@dataclass(frozen=True)
class _NormalEquations:
    """The LSCF normal equations at the highest order, reduced to what every order needs."""

    reduced: list[NDArray[np.complex128]]  # M of order m: (m + 1, m + 1), m = 0 … n
    rows: NDArray[np.complex128]  # rows[k, o, :] = X_o[k, :], X_o = L⁻¹ S_o
    inverse_h: NDArray[np.complex128] | None  # L⁻ᴴ (None: R = F·I)
    r_matrix: NDArray[np.complex128] | None  # R (None: F·I)
    noise_variance: NDArray[np.float64]  # per FRF, per line (units of the values fitted)
    n_lines: int


def _normal_equations(
    values: NDArray[np.complex128], theta: NDArray[np.float64], n: int, *, even: bool
) -> _NormalEquations:
    """Build ``Σ T_o``, ``X_o = L⁻¹ S_o`` (R = LLᴴ) at order n, and estimate the noise.

    ``values`` (n_o, F) on the unit-circle angles ``theta``; ``even``: the lines are evenly
    spaced, so ``θ_f = 2πf/F`` exactly, the generators come from FFTs and ``R = F·I``.
    """
    n_o, n_lines = values.shape
    lags = np.arange(-n, n + 1)
    # Toeplitz generators Σ_f x_f exp(iθ_f k), k = −n … n (sdypy-EMA builds them with FFTs too)
    if even:
        gen_s = -np.fft.ifft(values, axis=1)[:, lags % n_lines] * n_lines
        gen_t = np.fft.ifft((np.abs(values) ** 2).sum(axis=0))[lags % n_lines] * n_lines
    else:
        powers = np.exp(1j * np.outer(theta, lags))
        gen_s = -(values @ powers)
        gen_t = (np.abs(values) ** 2).sum(axis=0) @ powers
    lag = np.arange(n + 1)[None, :] - np.arange(n + 1)[:, None] + n  # s − r + n
    t_matrix = gen_t[lag]
    s_stack = gen_s[:, lag].transpose(1, 0, 2)  # s_stack[r, o, s] = S_o[r, s]
    inverse_h: NDArray[np.complex128] | None = None
    r_matrix: NDArray[np.complex128] | None = None
    if even:
        rows = s_stack / np.sqrt(n_lines)
    else:
        r_matrix, inverse_h = _uneven_r(theta, lags, lag)
        rows = (inverse_h.conj().T @ s_stack.reshape(n + 1, -1)).reshape(n + 1, n_o, n + 1)
    rows = np.ascontiguousarray(rows)

    # The reduced matrix of every order (module docstring): one rank-n_o update per order.
    reduced: list[NDArray[np.complex128]] = []
    accumulated = np.zeros((n + 1, n + 1), dtype=complex)
    for m in range(n + 1):
        accumulated += rows[m].conj().T @ rows[m]
        reduced.append(t_matrix[: m + 1, : m + 1] - accumulated[: m + 1, : m + 1])

    # Noise.  Per FRF from second differences (robust median: |Δ²e|² of complex white noise
    # is exponential with mean 6σ², median 6σ² ln 2); the total is capped by the smallest
    # eigenvalue of the whitened reduced matrix at the highest order, which is the noise
    # variance times (1 − (n+1)/F) up to the Marchenko–Pastur lower edge of its fluctuation.
    per_frf = second_difference_noise(values)
    total = float(per_frf.sum())
    if total > 0:
        top = reduced[n]
        whitened = top / n_lines if inverse_h is None else inverse_h.conj().T @ top @ inverse_h
        bound = noise_bound(whitened, n_lines, n, n_o)
        if bound < total:
            per_frf = per_frf * (bound / total)
    return _NormalEquations(
        reduced=reduced,
        rows=rows,
        inverse_h=inverse_h,
        r_matrix=r_matrix,
        noise_variance=np.asarray(per_frf, dtype=float),
        n_lines=n_lines,
    )


def _uneven_r(
    theta: NDArray[np.float64], lags: NDArray[np.int_], lag: NDArray[np.int_]
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """``R = ΓᴴΓ`` of unevenly spaced lines and ``L⁻ᴴ`` of its Cholesky factor ``R = LLᴴ``."""
    r_matrix = np.exp(1j * np.outer(theta, lags)).sum(axis=0)[lag]
    try:
        inverse = np.tril(np.linalg.inv(np.linalg.cholesky(r_matrix)))
    except np.linalg.LinAlgError:
        raise InputError(
            "the FRF lines are too unevenly spaced for this model order; resample them "
            "onto an even grid or lower max_order"
        ) from None
    return np.asarray(r_matrix), np.asarray(inverse.conj().T)


def second_difference_noise(values: NDArray[np.complex128]) -> NDArray[np.float64]:
    """Noise variance per line of each FRF (along the last axis) from its second differences:
    a robust median (``|Δ²e|²`` of complex white noise is exponential with mean 6σ², median
    6σ² ln 2)."""
    second = values[..., 2:] - 2 * values[..., 1:-1] + values[..., :-2]
    return np.asarray(np.median(np.abs(second) ** 2, axis=-1) / (6 * np.log(2)))


def noise_bound(whitened: NDArray[np.complex128], n_lines: int, n: int, n_outputs: int) -> float:
    """The largest total noise variance the whitened reduced matrix at order n allows (inf when
    too few lines per unknown to tell): its smallest eigenvalue is the noise variance times
    (1 − (n+1)/F) up to the Marchenko–Pastur lower edge of its fluctuation."""
    dof = n_lines - n - 1
    ratio = (n + 1) / (n_outputs * dof)
    if ratio >= 0.25:
        return math.inf
    smallest = float(np.linalg.eigvalsh(whitened)[0])
    return max(smallest, 0.0) / (dof / n_lines) / (1 - math.sqrt(ratio)) ** 2


def _poles_by_order(
    equations: _NormalEquations,
    orders: NDArray[np.int_],
    accept: Callable[[NDArray[np.complex128]], NDArray[np.bool_]],
    *,
    compensate: bool,
) -> Iterator[tuple[NDArray[np.complex128], NDArray[np.complex128]]]:
    """Roots z_k of the common denominator and ``N_o(z_k)/d'(z_k)``, order by order.

    Yields, per order m, the roots that ``accept`` keeps and an (n_o, n_kept) array.  Only
    numpy's linear algebra is called here: alternating with scipy's (a second BLAS library
    with its own threads) in a loop of small problems makes the two thread pools fight over
    the cores (measured: ten times slower on two cores).
    """
    rows, inverse_h = equations.rows, equations.inverse_h
    n_lines = equations.n_lines
    n = rows.shape[0] - 1
    n_o = rows.shape[1]
    flat = rows.reshape((n + 1) * n_o, n + 1)
    noise = float(equations.noise_variance.sum()) if compensate else 0.0
    roots: NDArray[np.complex128] | None = None
    for m in orders.tolist():
        reduced = equations.reduced[m]
        if noise > 0:
            # bias-compensated least squares: noise on H adds σ²(1 − (m+1)/F)·R to the
            # reduced matrix (exactly, in expectation, for white noise)
            share = noise * (1 - (m + 1) / n_lines)
            if equations.r_matrix is None:
                reduced = reduced - share * n_lines * np.eye(m + 1)
            else:
                reduced = reduced - share * equations.r_matrix[: m + 1, : m + 1]
        alpha = np.ones(m + 1, dtype=complex)
        try:
            alpha[:m] = np.linalg.solve(reduced[:m, :m], -reduced[:m, m])
        except np.linalg.LinAlgError:
            alpha[:m] = np.linalg.lstsq(reduced[:m, :m], -reduced[:m, m], rcond=None)[0]
        roots = _roots(alpha, roots)
        z = roots[accept(roots)]
        # numerators β_o = −R⁻¹ S_o α = −L⁻ᴴ (X_o α), evaluated at the kept roots only
        y = (flat[: (m + 1) * n_o, : m + 1] @ alpha).reshape(m + 1, n_o)
        beta = -(y / np.sqrt(n_lines) if inverse_h is None else inverse_h[: m + 1, : m + 1] @ y)
        vander = np.vander(z, m + 1, increasing=True)  # e^−2π < |z| < 1: no subnormals
        derivative = vander[:, :m] @ (np.arange(1, m + 1) * alpha[1:])
        derivative = np.where(derivative == 0, np.finfo(float).tiny, derivative)
        yield z, np.asarray((vander @ beta).T / derivative)


_ABERTH_FROM_ORDER = 16
"""Below this order the companion matrix's eigenvalues are as cheap as the iteration."""
_ABERTH_ITERATIONS = 40


def _roots(
    alpha: NDArray[np.complex128], guess: NDArray[np.complex128] | None
) -> NDArray[np.complex128]:
    """Roots of the monic polynomial ``Σ_r α_r z^r`` (``α_m = 1``).

    From the roots of the order below (``guess``; most poles move little from one order to
    the next) by Aberth–Ehrlich iteration, converged to round-off (cubic convergence: six
    sweeps on average at orders 50–100), three times faster than the eigenvalues of the
    companion matrix at order 100.  The companion matrix's eigenvalues are used with no
    guess, at low orders, and whenever the iteration fails to converge or to account for
    every root (their sum must be ``−α_{m−1}``).
    """
    m = alpha.size - 1
    if guess is not None and m >= _ABERTH_FROM_ORDER and guess.size < m:
        found = _aberth(alpha, guess)
        if found is not None:
            return found
    companion = np.zeros((m, m), dtype=complex)
    companion[0, :] = -alpha[m - 1 :: -1]
    companion[np.arange(1, m), np.arange(m - 1)] = 1.0
    return np.asarray(np.linalg.eigvals(companion))


def _aberth(
    alpha: NDArray[np.complex128], guess: NDArray[np.complex128]
) -> NDArray[np.complex128] | None:
    """Aberth–Ehrlich iteration for the roots of ``Σ α_r z^r`` from ``guess``; None if it fails."""
    m = alpha.size - 1
    extra = m - guess.size
    if extra == 1:
        new = np.array([-alpha[m - 1] - guess.sum()])
    else:
        radius = float(np.median(np.abs(guess))) if guess.size else 1.0
        new = radius * np.exp(2j * np.pi * (np.arange(extra) + 0.5) / extra)
    z = np.concatenate([guess, new]).astype(complex)
    active = np.arange(m)
    with np.errstate(all="ignore"):
        for _ in range(_ABERTH_ITERATIONS):
            za = z[active]
            ratio = _newton_step(alpha, za)
            gaps = za[:, None] - z[None, :]
            gaps[np.arange(za.size), active] = np.inf
            step = ratio / (1 - ratio * (1 / gaps).sum(axis=1))
            if not np.all(np.isfinite(step)):
                return None
            z[active] = za - step
            active = active[np.abs(step) > 1e-12 * np.maximum(np.abs(z[active]), 1.0)]
            if active.size == 0:
                break
        else:
            return None
    if abs(z.sum() + alpha[m - 1]) > 1e-9 * max(1.0, float(np.abs(z).sum())):
        return None
    return z


def _newton_step(alpha: NDArray[np.complex128], z: NDArray[np.complex128]) -> NDArray[Any]:
    """``p(z) / p'(z)`` for ``p = Σ α_r z^r``; outside the unit circle from ``w = 1/z`` (no
    overflow): ``p/p' = z q(w) / (m q(w) − w q'(w))`` with ``q(w) = Σ α_r w^(m−r)``."""
    m = alpha.size - 1
    out = np.empty(z.size, dtype=complex)
    inside = np.abs(z) <= 1.0
    weights = np.arange(1, m + 1)
    for part, coefficients in ((inside, alpha), (~inside, alpha[::-1])):
        if not np.any(part):
            continue
        x = z[part] if coefficients is alpha else 1.0 / z[part]
        powers = np.vander(x, m + 1, increasing=True)
        value = np.einsum("ij,j->i", powers, coefficients)  # einsum: no BLAS threads woken
        slope = np.einsum("ij,j->i", powers[:, :m], weights * coefficients[1:])
        if coefficients is alpha:
            out[part] = value / slope
        else:
            out[part] = z[part] * value / (m * value - x * slope)
    return out


def _classify(
    order: NDArray[np.int_],
    orders: NDArray[np.int_],
    frequency: NDArray[np.float64],
    damping: NDArray[np.float64],
    residues: NDArray[np.complex128],
    frequency_tolerance: float,
    damping_tolerance: float,
    min_mac: float,
) -> NDArray[np.int8]:
    """Stability class of every pole against the nearest pole of the order computed below."""
    stability = np.zeros(order.size, dtype=np.int8)
    previous: NDArray[np.intp] | None = None
    for m in orders:
        current = np.flatnonzero(order == m)
        if previous is not None and previous.size and current.size:
            f_prev = frequency[previous]  # ascending
            slot = np.clip(np.searchsorted(f_prev, frequency[current]), 1, f_prev.size - 1)
            if f_prev.size == 1:
                match = np.zeros(current.size, dtype=int)
            else:
                left = np.abs(frequency[current] - f_prev[slot - 1])
                right = np.abs(frequency[current] - f_prev[slot])
                match = np.where(left <= right, slot - 1, slot)
            other = previous[match]
            df = np.abs(frequency[current] - frequency[other]) / frequency[other]
            zeta_prev = damping[other]
            dz = np.abs(damping[current] - zeta_prev) / np.where(zeta_prev > 0, zeta_prev, np.inf)
            shape = mac(residues[:, current], residues[:, other], pairwise=True)
            ok_f = df <= frequency_tolerance
            ok_z = ok_f & (zeta_prev > 0) & (dz <= damping_tolerance)
            ok_s = ok_z & (shape >= min_mac)
            stability[current] = ok_f.astype(np.int8) + ok_z + ok_s
        previous = current
    return stability


# --- automatic selection ---------------------------------------------------------------------


@dataclass(frozen=True)
class _Cluster:
    members: NDArray[np.intp]
    frequency: float
    damping_ratio: float
    n_orders: int
    representative: int
    peak: float
    peak_to_noise: float


@dataclass(frozen=True)
class SelectionRules:
    """The rules by which :func:`select_poles` tells the physical modes (its steps 1–3).

    Every rule is checked when the rules are made (InputError naming it).

    Attributes
    ----------
    min_fraction : float
        Smallest share of the computed orders a mode must be stable in (0–1).
    min_peak_to_noise : float
        Smallest ratio of a mode's peak (largest over the FRFs) to that FRF's noise rms.
    dynamic_range_db : float
        Largest distance of a mode's peak below the strongest mode's, dB.
    max_damping_ratio : float
        Largest damping ratio of a physical mode.
    edge_margin : float
        Part of the band's width added to each mode's edge margin (0–0.25; 0 by default: the
        margin follows the data, not the band's width).
    edge_lines : float
        Line spacings in each mode's edge margin (0–1000).
    edge_widths : float
        Of the mode's own half-power width ``2ζf`` in its edge margin (0–100).
    bandwidth_tolerance : float
        Frequency tolerance of the clustering, in half-power bandwidths.
    damping_tolerance : float
        Relative damping tolerance of the clustering.
    cluster_mac : float
        Smallest MAC between two poles of one cluster, and between the mean shapes of two
        modes merged as one peak.
    pin_tolerance : float
        Relative distance within which a pin or an exclusion finds its mode.
    stability : PoleStability
        Least stability class of the poles clustered.
    """

    min_fraction: float = 0.2
    min_peak_to_noise: float = 2.0
    dynamic_range_db: float = 60.0
    max_damping_ratio: float = 0.2
    edge_margin: float = 0.0
    edge_lines: float = 3.0
    edge_widths: float = 1.0
    bandwidth_tolerance: float = 0.5
    damping_tolerance: float = 0.3
    cluster_mac: float = 0.9
    pin_tolerance: float = 0.05
    stability: PoleStability = PoleStability.DAMPING

    _RANGES: ClassVar[tuple[tuple[str, float, float], ...]] = (
        ("min_fraction", 0.0, 1.0),
        ("min_peak_to_noise", 0.0, 1e6),
        ("dynamic_range_db", 0.0, 400.0),
        ("max_damping_ratio", 0.0, 1.0),
        ("edge_margin", 0.0, 0.25),
        ("edge_lines", 0.0, 1000.0),
        ("edge_widths", 0.0, 100.0),
        ("bandwidth_tolerance", 0.0, 10.0),
        ("damping_tolerance", 0.0, 10.0),
        ("cluster_mac", 0.0, 1.0),
        ("pin_tolerance", 0.0, 1.0),
    )

    def __post_init__(self) -> None:
        for name, low, high in self._RANGES:
            value = getattr(self, name)
            if not isinstance(value, int | float) or isinstance(value, bool):
                raise InputError(f"`{name}` must be a number (got {value!r})")
            if not (math.isfinite(value) and low <= value <= high):
                raise InputError(f"`{name}` must lie between {low:g} and {high:g} (got {value!r})")
        if self.max_damping_ratio == 0:
            raise InputError("`max_damping_ratio` must be above 0: 0 keeps no mode")
        if self.stability not in tuple(PoleStability):
            raise InputError(f"stability must be a PoleStability (got {self.stability!r})")

    @property
    def tolerances(self) -> tuple[float, float, float]:
        """The clustering's: bandwidth, damping and shape (MAC) tolerances."""
        return (self.bandwidth_tolerance, self.damping_tolerance, self.cluster_mac)


DEFAULT_SELECTION = SelectionRules()
"""The rules :func:`select_poles` follows unless given others."""


def require_rules(caller: str, rules: object) -> SelectionRules:
    """``rules`` if it is a :class:`SelectionRules`, else a TypeError naming ``caller``'s
    parameter and what to build (a dict of rules is the likely slip)."""
    if not isinstance(rules, SelectionRules):
        raise TypeError(
            f"{caller}: `rules` must be a SelectionRules (got {type(rules).__name__}); "
            "give SelectionRules(min_fraction=..., ...)"
        )
    return rules


def select_poles(
    stab: Stabilisation,
    pin_hz: Sequence[float] = (),
    exclude_hz: Sequence[float] = (),
    *,
    rules: SelectionRules = DEFAULT_SELECTION,
    log: bool = True,
) -> SelectedPoles:
    """Pick the physical modes from a stabilisation diagram, automatically.

    The names below are the fields of ``rules`` (:class:`SelectionRules`).

    1. The poles of class ``stability`` or better (default: stable in frequency and damping
       from one order to the next; the shape is checked here, over all the orders) are
       clustered by complete linkage: every two poles of a cluster agree.  Two poles agree if
       their frequencies differ by less than ``bandwidth_tolerance`` half-power bandwidths
       (``2ζf``, kept between a tenth of and the whole stabilisation frequency tolerance),
       their damping ratios by less than ``damping_tolerance`` (relative) and their shapes
       have a MAC of ``cluster_mac`` or more.  Close modes are kept apart by bandwidth and by
       shape, and a cluster holding two poles of one order in many orders is split again.
       Clusters of one mode broken up over the orders (neighbours within the tolerance, in
       different orders, with agreeing shapes) are joined.
    2. A cluster is a mode if it is stable in at least ``min_fraction`` of the orders
       computed, its median damping ratio lies in ``(0, max_damping_ratio)``, its median
       frequency lies inside the band by more than its edge margin — ``edge_lines`` line
       spacings and ``edge_widths`` of its own half-power width ``2ζf`` (plus ``edge_margin``
       of the band's width, none by default): the fit puts computational poles at the edges,
       and a mode whose peak is cut by the edge is not fitted whole — and its peak stands
       above the noise: the
       residue over the decay rate, ``|A| / σ``, is at least ``min_peak_to_noise`` times the
       noise of that FRF (``Stabilisation.noise_rms``) in some FRF (σ taken no smaller than
       π × the line spacing: a narrower peak falls between lines), and no more than
       ``dynamic_range_db`` below the strongest mode's (a hammer test resolves 40–60 dB; a
       "mode" further down is the fit's model of a systematic error, e.g. leakage or the
       window, whose "noise" the white-noise estimate does not see).  Two such modes closer
       than their half-power width (the mean of their ``2ζf``) whose shapes agree (MAC of
       the clusters' mean shapes ``cluster_mac`` or more, or closer than one line with
       dampings within ``damping_tolerance``: no line between them) are one peak the fit
       split in two: the one stable in more orders is kept, the other is dropped as
       ``merged`` (its reason names the mode kept).
    3. ``exclude_hz`` drops the selected mode nearest each frequency; ``pin_hz`` forces in the
       cluster nearest each frequency even if step 2 left it out (within ``pin_tolerance``,
       relative).  Everything left out is logged with the reason and listed in ``dropped``.

    Frequency and damping of a mode are the medians over its cluster (with the noise
    compensation of :func:`stabilisation` the low orders are not biased, so every order
    counts).

    Parameters
    ----------
    stab : Stabilisation
        The stabilisation diagram (:func:`stabilisation`).
    pin_hz : sequence of float
        Approximate frequencies of modes to keep whatever the automatic rules say, Hz.
    exclude_hz : sequence of float
        Approximate frequencies of modes to leave out, Hz.
    rules : SelectionRules
        The rules of steps 1–3 (default :data:`DEFAULT_SELECTION`).
    log : bool
        Log what was kept, pinned, excluded and dropped (default).  False for a trial
        selection whose outcome its caller says in its own words: a pin is said once.

    Returns
    -------
    SelectedPoles
        The modes, ascending in frequency.

    Raises
    ------
    InputError
        No mode found — a band with no mode above the noise, or pure noise: the message says
        what was dropped and why — a pin with no stable pole near it, a pin and an exclusion
        on the same mode, or pins or exclusions outside the band.
    """
    require_rules("select_poles", rules)
    if not isinstance(stab, Stabilisation):
        raise InputError("select_poles needs the Stabilisation that stabilisation() returns")
    pins = _frequencies("`pin_hz`", pin_hz, stab.band_hz)
    excludes = _frequencies("`exclude_hz`", exclude_hz, stab.band_hz)
    # step 1: clusters of stable poles
    candidates = np.flatnonzero(stab.stability >= int(rules.stability))
    clusters = _cluster(stab, candidates, *rules.tolerances)
    # step 2: the rules, the dynamic range, one peak
    reasons = _reasons(stab, clusters, rules)
    merged = _merge_one_peak(
        stab, clusters, reasons, rules.cluster_mac, rules.damping_tolerance, log
    )
    # step 3: the user's exclusions and pins
    accepted = [not r for r in reasons]
    _exclude(clusters, excludes, accepted, reasons, rules.pin_tolerance, log)
    pinned = _pin(clusters, pins, accepted, reasons, rules.pin_tolerance, log)
    dropped, dropped_modes = _dropped(clusters, reasons, accepted, merged, log)
    kept = sorted(
        (k for k in range(len(clusters)) if accepted[k]), key=lambda k: clusters[k].frequency
    )
    if not kept:
        left_out = (tuple(dropped), tuple(dropped_modes))
        raise _no_mode(stab, clusters, dropped, _selected(stab, [], np.zeros(0, bool), left_out))
    (logger.info if log else logger.debug)(
        "selected %d modes (%s Hz); %d clusters of stable poles dropped",
        len(kept),
        ", ".join(f"{clusters[k].frequency:.1f}" for k in kept),
        len(dropped),
    )
    chosen = [clusters[k] for k in kept]
    pinned_kept = np.array([pinned[k] for k in kept], dtype=bool)
    return _selected(stab, chosen, pinned_kept, (tuple(dropped), tuple(dropped_modes)))


def edge_margin(
    rules: SelectionRules,
    band_hz: tuple[float, float],
    line_spacing_hz: float,
    frequency_hz: float,
    damping_ratio: float,
) -> float:
    """A mode's edge margin by ``rules``, Hz: ``edge_margin`` of the band's width,
    ``edge_lines`` line spacings and ``edge_widths`` of its own half-power width ``2ζf``; no
    mode is taken nearer the band's edge (its peak is not in the band whole).

    Parameters
    ----------
    rules : SelectionRules
        The selection's rules (``edge_margin``, ``edge_lines``, ``edge_widths``).
    band_hz : tuple of float
        The band, Hz.
    line_spacing_hz : float
        The FRFs' line spacing, Hz.
    frequency_hz, damping_ratio : float
        The mode's frequency, Hz, and damping ratio.

    Returns
    -------
    float
        The margin, Hz.
    """
    return (
        rules.edge_margin * (band_hz[1] - band_hz[0])
        + rules.edge_lines * line_spacing_hz
        + rules.edge_widths * 2 * max(damping_ratio, 0.0) * frequency_hz
    )


def _reasons(stab: Stabilisation, clusters: list[_Cluster], rules: SelectionRules) -> list[str]:
    """Why each cluster is not a mode by the rules of step 2 (empty: it is one)."""
    low_hz, high_hz = stab.band_hz
    n_orders_total = int(stab.orders.size)
    need = max(1, math.ceil(rules.min_fraction * n_orders_total))
    reasons: list[str] = []
    for c in clusters:
        margin = edge_margin(
            rules, stab.band_hz, stab.line_spacing_hz, c.frequency, c.damping_ratio
        )
        if not 0.0 < c.damping_ratio < rules.max_damping_ratio:
            reasons.append(
                f"damping ratio {c.damping_ratio:.3g} outside (0, {rules.max_damping_ratio:g})"
            )
        elif not low_hz + margin <= c.frequency <= high_hz - margin:
            reasons.append(f"within {margin:.3g} Hz of the band's edge")
        elif c.n_orders < need:
            reasons.append(f"stable in {c.n_orders} of {n_orders_total} orders (< {need})")
        elif c.peak_to_noise < rules.min_peak_to_noise:
            reasons.append(
                f"peak {c.peak_to_noise:.2g} × the noise (< {rules.min_peak_to_noise:g})"
            )
        else:
            reasons.append("")
    strongest = max((c.peak for c, r in zip(clusters, reasons, strict=True) if not r), default=0.0)
    floor = strongest * 10 ** (-rules.dynamic_range_db / 20)
    for k, c in enumerate(clusters):
        if not reasons[k] and c.peak < floor:
            below = 20 * math.log10(strongest / max(c.peak, 1e-300))
            reasons[k] = f"peak {below:.0f} dB below the strongest mode's"
    return reasons


def _exclude(
    clusters: list[_Cluster],
    excludes: NDArray[np.float64],
    accepted: list[bool],
    reasons: list[str],
    tolerance: float,
    log: bool = True,
) -> None:
    """Drop the accepted mode nearest each exclusion (within ``tolerance``, relative); one
    with none near it is logged when ``log``."""
    centres = np.array([c.frequency for c in clusters])
    for f in excludes:
        near = [k for k in range(len(centres)) if accepted[k] and _near(centres[k], f, tolerance)]
        if not near:
            if log:
                logger.warning("exclude %g Hz: no selected mode within %g %%", f, 100 * tolerance)
            continue
        k = min(near, key=lambda j: abs(centres[j] - f))
        accepted[k] = False
        reasons[k] = f"excluded by the user ({f:g} Hz)"


def _pin(
    clusters: list[_Cluster],
    pins: NDArray[np.float64],
    accepted: list[bool],
    reasons: list[str],
    tolerance: float,
    log: bool = True,
) -> list[bool]:
    """Force in the cluster nearest each pin (within ``tolerance``); which ones are pinned.
    One the selection had left out is logged when ``log``."""
    centres = np.array([c.frequency for c in clusters])
    pinned = [False] * len(clusters)
    for f in pins:
        near = [
            k
            for k in range(len(clusters))
            if _near(centres[k], f, tolerance) and 0.0 < clusters[k].damping_ratio < 1.0
        ]
        if not near:
            nearest = (
                f"; the nearest stable poles are at {centres[np.argmin(np.abs(centres - f))]:.1f}"
                " Hz"
                if centres.size
                else ""
            )
            raise InputError(
                f"pinned {f:g} Hz: no stable pole within {100 * tolerance:g} % of it"
                f"{nearest}; raise `max_order` or widen `band_hz`"
            )
        k = min(near, key=lambda j: abs(centres[j] - f))
        if reasons[k].startswith("excluded"):
            raise InputError(f"{f:g} Hz is both pinned and excluded")
        if pinned[k]:
            raise InputError(f"two pins point at the same mode ({centres[k]:.1f} Hz)")
        if log and not accepted[k]:  # the user's word against the diagram's: said, not hidden
            logger.warning(
                "pinned %g Hz: kept the mode at %.2f Hz (ζ %.3g %%) though the selection "
                "left it out: %s; its damping is that of the orders it has, not a settled one",
                f,
                centres[k],
                100 * clusters[k].damping_ratio,
                reasons[k],
            )
        pinned[k] = True
        accepted[k] = True
    return pinned


def _dropped(
    clusters: list[_Cluster],
    reasons: list[str],
    accepted: list[bool],
    merged: dict[int, int],
    log: bool = True,
) -> tuple[list[str], list[DroppedMode]]:
    """What was left out, as lines and as rows (logged when ``log``; clusters of ≤ 3 poles
    at DEBUG)."""
    dropped = []
    dropped_modes = []
    for k, (c, reason, keep) in enumerate(zip(clusters, reasons, accepted, strict=True)):
        if keep:
            continue
        line = f"{c.frequency:.2f} Hz, ζ = {c.damping_ratio:.4f}, {c.n_orders} orders: {reason}"
        dropped.append(line)
        dropped_modes.append(
            DroppedMode(
                float(c.frequency),
                float(c.damping_ratio),
                int(c.n_orders),
                "merged" if k in merged else "selection",
                reason,
                peak_to_noise=float(c.peak_to_noise),
                merged_into_hz=float(clusters[merged[k]].frequency) if k in merged else math.nan,
            )
        )
        # clusters of one to three poles are the noise's: logged at DEBUG only
        (logger.info if log and c.n_orders > 3 else logger.debug)("dropped %s", line)
    return dropped, dropped_modes


class NoModeError(InputError):
    """No mode is left in the band (:func:`select_poles`): ``head`` says where and what was
    dropped; a caller that knows the data's peaks may name the cause in its place, and may
    go on from ``selected`` (no mode, every cluster's row) with rules of its own."""

    def __init__(self, head: str, advice: str, selected: SelectedPoles | None = None) -> None:
        super().__init__(f"{head}. {advice}")
        self.head = head
        self.selected = selected


def _no_mode(
    stab: Stabilisation, clusters: list[_Cluster], dropped: list[str], selected: SelectedPoles
) -> InputError:
    """The error when no mode is left: the first substantial clusters dropped, and why, with
    the empty ``selected``.

    ``dropped`` lines up with ``clusters`` here: every cluster was dropped.
    """
    low_hz, high_hz = stab.band_hz
    substantial = [d for d, c in zip(dropped, clusters, strict=True) if c.n_orders > 3]
    detail = "; ".join(substantial[:4]) if substantial else "no pole is stable over orders"
    return NoModeError(
        f"no mode found between {low_hz:.1f} and {high_hz:.1f} Hz ({detail})",
        "The band may hold no mode above the noise; widen the band, raise max_order or pin a mode",
        selected,
    )


def _selected(
    stab: Stabilisation,
    chosen: list[_Cluster],
    pinned: NDArray[np.bool_],
    left_out: tuple[tuple[str, ...], tuple[DroppedMode, ...]],
) -> SelectedPoles:
    """The modes of the chosen clusters (medians, spreads, the representative's residues) and
    what was left out (``dropped``, ``dropped_modes``)."""
    frequency = np.array([c.frequency for c in chosen])
    zeta = np.array([c.damping_ratio for c in chosen])
    return SelectedPoles(
        frequency=frequency,
        damping_ratio=zeta,
        pole=pole_of(frequency, zeta),
        n_orders=np.array([c.n_orders for c in chosen], dtype=int),
        frequency_spread_hz=np.array([np.std(stab.frequency[c.members]) for c in chosen]),
        damping_spread=np.array([np.std(stab.damping_ratio[c.members]) for c in chosen]),
        peak_to_noise=np.array([c.peak_to_noise for c in chosen]),
        residues=stab.residues[:, [c.representative for c in chosen]],
        pinned=pinned,
        band_hz=stab.band_hz,
        exponential_window_s=stab.exponential_window_s,
        n_orders_computed=int(stab.orders.size),
        nodes=stab.nodes,
        dropped=left_out[0],
        dropped_modes=left_out[1],
    )


def _merge_one_peak(
    stab: Stabilisation,
    clusters: list[_Cluster],
    reasons: list[str],
    cluster_mac: float,
    damping_tolerance: float,
    log: bool = True,
) -> dict[int, int]:
    """Merge accepted neighbours that are one peak; their reasons set, each merged index
    returned with the index of the cluster it was merged into (the one its reason names).

    Two accepted modes closer than their half-power width (the mean of their ``2 ζ f``) whose
    shapes agree (MAC of the clusters' mean shapes at least ``cluster_mac``) are one peak that
    the fit's higher orders split in two: no single-reference test can tell two modes of one
    shape under one peak apart.  The one stable in more orders is kept (the larger peak on a
    tie).  So are two closer than one line with dampings alike whose shapes are more alike
    than not (MAC :data:`SPLIT_MAC` or more; :func:`_within_a_line`: the lines cannot part
    them; a narrow band's high orders split a peak whose frequency moves a little from FRF to
    FRF into such poles, each with a share of its constants: MAC 0.75–0.89 on the wing).
    Close modes of other shapes (a symmetric structure's pairs, MAC near 0) or a line or more
    apart, or of unlike damping, stay apart.
    """
    order = sorted((k for k, r in enumerate(reasons) if not r), key=lambda k: clusters[k].frequency)
    merged: dict[int, int] = {}
    if len(order) < 2:
        return merged
    kept = order[0]
    for other in order[1:]:
        a, b = clusters[kept], clusters[other]
        apart = abs(b.frequency - a.frequency)
        width = max(a.damping_ratio, 0.0) * a.frequency + max(b.damping_ratio, 0.0) * b.frequency
        if apart >= width:
            kept = other
            continue
        shapes = mac(_mean_shape(stab, a.members)[:, None], _mean_shape(stab, b.members)[:, None])
        alike = float(shapes[0, 0])
        unparted = alike >= SPLIT_MAC and _within_a_line(
            stab.line_spacing_hz,
            (a.frequency, b.frequency),
            (a.damping_ratio, b.damping_ratio),
            damping_tolerance,
        )
        if alike < cluster_mac and not unparted:
            kept = other
            continue
        if (b.n_orders, b.peak) > (a.n_orders, a.peak):
            kept, gone = other, kept
        else:
            gone = other
        stay = clusters[kept]
        if alike >= cluster_mac:
            why = f"shapes alike (MAC {alike:.2f} ≥ {cluster_mac:g})"
        else:
            why = (
                f"closer than a line ({stab.line_spacing_hz:.2g} Hz) with dampings alike: the "
                f"lines cannot part them (MAC {alike:.2f})"
            )
        reasons[gone] = (
            f"one peak with the mode at {stay.frequency:.2f} Hz, merged into it: {apart:.2g} "
            f"Hz apart, within their half-power width {width:.2g} Hz (2ζf), {why}; kept the "
            f"one stable in more orders ({stay.n_orders} against {clusters[gone].n_orders})"
        )
        merged[gone] = kept
        (logger.info if log else logger.debug)(
            "%.2f Hz: %s", clusters[gone].frequency, reasons[gone]
        )
    return merged


SPLIT_MAC = 0.5
"""The MAC at or above which two poles closer than a line with dampings alike are one mode
split in two (:func:`_merge_one_peak`): shares of one shape are more alike than not, while a
symmetric structure's two modes under a line apart are near orthogonal (0.00 in
``tests/test_close_modes.py``)."""


def _within_a_line(
    spacing_hz: float,
    frequency_hz: tuple[float, float],
    damping_ratio: tuple[float, float],
    damping_tolerance: float,
) -> bool:
    """Whether two poles are closer than one line with dampings alike: modes the FRF's lines
    cannot part.

    Two sinusoids closer than ``1/T`` (one line of a record of length ``T``) are not resolved
    by its spectrum; a parametric fit parts them only by what else differs — their decay
    (dampings further apart than ``damping_tolerance``, relative) or their shapes.  Under one
    peak the shapes of two such poles are those of one mode split in two (each with a share
    of its constants: a cantilevered wing's 167.18 Hz, ζ 0.063 % on 0.245 Hz lines, split by
    a narrow band's high orders into 167.16 and 167.24 Hz of MAC 0.88), so they do not tell.

    Parameters
    ----------
    spacing_hz : float
        The FRFs' line spacing, Hz.
    frequency_hz : tuple of float
        The two poles' frequencies, Hz.
    damping_ratio : tuple of float
        Their damping ratios.
    damping_tolerance : float
        Relative difference of the dampings within which they are alike.

    Returns
    -------
    bool
    """
    zeta = np.maximum(np.asarray(damping_ratio, dtype=float), 0.0)
    alike = abs(zeta[1] - zeta[0]) <= damping_tolerance * max(float(zeta.mean()), 1e-12)
    return bool(abs(frequency_hz[1] - frequency_hz[0]) < spacing_hz and alike)


def _near(centre: float, target: float, tolerance: float) -> bool:
    return abs(centre - target) <= tolerance * target


def _cluster(
    stab: Stabilisation,
    candidates: NDArray[np.intp],
    bandwidth_tolerance: float,
    damping_tolerance: float,
    cluster_mac: float,
) -> list[_Cluster]:
    """Clusters of the candidate poles, one per mode (see :func:`select_poles`, step 1)."""
    if candidates.size == 0:
        return []
    f = stab.frequency[candidates]
    order = np.argsort(f, kind="stable")
    candidates, f = candidates[order], f[order]
    # islands: runs of poles no further apart than the stabilisation's frequency tolerance;
    # no cluster can reach across a gap wider than that
    gaps = np.flatnonzero(np.diff(f) > stab.frequency_tolerance * f[:-1])
    groups: list[NDArray[np.intp]] = []
    for island in np.split(candidates, gaps + 1):
        if island.size == 1:
            groups.append(island)
            continue
        distance = _distance(stab, island, bandwidth_tolerance, damping_tolerance, cluster_mac)
        labels = _complete_linkage(distance, 1.0)
        found = [island[labels == label] for label in np.unique(labels)]
        found = [g for members in found for g in _split_by_order(stab, members, island, distance)]
        groups.extend(_join_fragments(stab, found, bandwidth_tolerance, cluster_mac))
    return [_summarise(stab, g) for g in groups]


def _complete_linkage(distance: NDArray[np.float64], threshold: float) -> NDArray[np.intc]:
    """Flat clusters of complete linkage cut at ``threshold`` (labels from 1)."""
    condensed = distance[np.triu_indices(distance.shape[0], 1)]
    return np.asarray(fcluster(linkage(condensed, method="complete"), threshold, "distance"))


def _distance(
    stab: Stabilisation,
    poles: NDArray[np.intp],
    bandwidth_tolerance: float,
    damping_tolerance: float,
    cluster_mac: float,
) -> NDArray[np.float64]:
    """Pairwise distances: the largest of the three, each 1 at the edge of its tolerance."""
    f = stab.frequency[poles]
    zeta = stab.damping_ratio[poles]
    f_bar = 0.5 * (f[:, None] + f[None, :])
    zeta_bar = np.maximum(0.5 * (zeta[:, None] + zeta[None, :]), 1e-6)
    d_f = np.abs(f[:, None] - f[None, :]) / _frequency_tolerance(
        stab, f_bar, zeta_bar, bandwidth_tolerance
    )
    d_z = np.abs(zeta[:, None] - zeta[None, :]) / (damping_tolerance * zeta_bar + 1e-12)
    shapes = stab.residues[:, poles]
    d_s = (1.0 - mac(shapes, shapes)) / max(1.0 - cluster_mac, 1e-12)
    distance = np.maximum(np.maximum(d_f, d_z), d_s)
    np.fill_diagonal(distance, 0.0)
    return np.asarray(distance)


def _frequency_tolerance(
    stab: Stabilisation,
    frequency: NDArray[np.float64] | float,
    damping_ratio: NDArray[np.float64] | float,
    bandwidth_tolerance: float,
) -> NDArray[np.float64]:
    """``bandwidth_tolerance`` half-power bandwidths, within [0.1, 1] × the frequency tolerance."""
    eps = stab.frequency_tolerance
    bandwidth = 2 * np.maximum(damping_ratio, 0.0) * frequency
    return np.asarray(
        np.clip(bandwidth_tolerance * bandwidth, 0.1 * eps * frequency, eps * frequency)
    )


def _split_by_order(
    stab: Stabilisation,
    members: NDArray[np.intp],
    island: NDArray[np.intp],
    distance: NDArray[np.float64],
) -> list[NDArray[np.intp]]:
    """Split a cluster holding two poles of one order in many orders; else one pole per order."""
    orders = stab.order[members]
    n_distinct = np.unique(orders).size
    if members.size - n_distinct > 0.25 * n_distinct and members.size >= 4:
        position = np.array([int(np.flatnonzero(island == m)[0]) for m in members])
        sub = distance[np.ix_(position, position)]
        condensed = sub[np.triu_indices(members.size, 1)]
        labels = fcluster(linkage(condensed, method="complete"), 2, "maxclust")
        if np.unique(labels).size == 2:
            return [
                part
                for label in (1, 2)
                for part in _split_by_order(stab, members[labels == label], island, distance)
            ]
    return [_one_per_order(stab, members)]


def _one_per_order(stab: Stabilisation, members: NDArray[np.intp]) -> NDArray[np.intp]:
    """The members, keeping in each order only the pole nearest the median frequency."""
    orders = stab.order[members]
    if np.unique(orders).size == members.size:
        return members
    median = _median(stab.frequency[members])
    keep = []
    for m in np.unique(orders):
        same = members[orders == m]
        keep.append(same[np.argmin(np.abs(stab.frequency[same] - median))])
    return np.array(keep, dtype=np.intp)


def _join_fragments(
    stab: Stabilisation,
    groups: list[NDArray[np.intp]],
    bandwidth_tolerance: float,
    cluster_mac: float,
) -> list[NDArray[np.intp]]:
    """Join clusters of one mode broken up over the orders.

    Two neighbouring clusters are one mode if their median frequencies agree within the
    clustering tolerance, they share almost no order (two modes close together both appear
    at the same orders; one mode's fragments take turns) and their shapes agree.
    """

    def stats(g: NDArray[np.intp]) -> tuple[float, float, NDArray[np.complex128]]:
        return (
            _median(stab.frequency[g]),
            _median(stab.damping_ratio[g]),
            _mean_shape(stab, g),
        )

    groups = sorted(groups, key=lambda g: _median(stab.frequency[g]))
    summary = [stats(g) for g in groups]
    i = 0
    while i < len(groups) - 1:
        (f_a, z_a, shape_a), (f_b, z_b, shape_b) = summary[i], summary[i + 1]
        a, b = groups[i], groups[i + 1]
        tol = _frequency_tolerance(
            stab, 0.5 * (f_a + f_b), max(0.5 * (z_a + z_b), 0.0), bandwidth_tolerance
        )
        shared = np.intersect1d(stab.order[a], stab.order[b]).size
        if (
            abs(f_a - f_b) <= tol
            and shared <= 0.1 * min(a.size, b.size)
            and float(mac(shape_a[:, None], shape_b[:, None])[0, 0]) >= cluster_mac
        ):
            groups[i] = _one_per_order(stab, np.concatenate([a, b]))
            summary[i] = stats(groups[i])
            del groups[i + 1], summary[i + 1]
            i = max(i - 1, 0)  # the joined median moved: look back once more
        else:
            i += 1
    return groups


def _mean_shape(stab: Stabilisation, members: NDArray[np.intp]) -> NDArray[np.complex128]:
    """Shapes of the members rotated onto the first one's phase and averaged (unit norm)."""
    shapes = stab.residues[:, members]
    if members.size == 1:
        return np.asarray(shapes[:, 0])
    shapes = shapes / np.maximum(np.linalg.norm(shapes, axis=0), 1e-300)
    phase = shapes[:, :1].conj().T @ shapes
    phase = phase / np.maximum(np.abs(phase), 1e-300)
    return np.asarray((shapes * phase.conj()).mean(axis=1))


def _median(values: NDArray[np.float64]) -> float:
    """Median of a small array (np.median's overhead is ten times the work here)."""
    ordered = np.sort(values)
    n = ordered.size
    return float(0.5 * (ordered[(n - 1) // 2] + ordered[n // 2]))


def _summarise(stab: Stabilisation, members: NDArray[np.intp]) -> _Cluster:
    f = stab.frequency[members]
    zeta = stab.damping_ratio[members]
    f_med, z_med = _median(f), _median(zeta)
    spread = np.abs(f - f_med) / max(f_med, 1e-12) + np.abs(zeta - z_med) / max(abs(z_med), 1e-6)
    representative = int(members[np.argmin(spread)])
    peak, peak_to_noise = modal_peak(
        stab, stab.residues[:, representative], -stab.pole[representative].real
    )
    return _Cluster(
        members=members,
        frequency=f_med,
        damping_ratio=z_med,
        n_orders=int(np.unique(stab.order[members]).size),
        representative=representative,
        peak=peak,
        peak_to_noise=peak_to_noise,
    )


def modal_peak(
    stab: Stabilisation, residues: NDArray[np.complex128], decay: float
) -> tuple[float, float]:
    """A mode's largest modal peak ``|A| / σ`` over the FRFs and its largest ratio to that
    FRF's noise; a peak narrower than the line spacing is not seen at full height.

    Parameters
    ----------
    stab : Stabilisation
        The diagram whose ``noise_rms`` (one an FRF) and ``line_spacing_hz`` are used.
    residues : ndarray, complex, shape (n_points,)
        The mode's residues ``A``, FRF units × rad/s.
    decay : float
        Its decay rate σ = ζω, rad/s (taken no smaller than π × the line spacing).

    Returns
    -------
    tuple of float
        The largest peak (FRF units) and the largest peak over its FRF's noise.
    """
    peaks = np.abs(residues) / max(decay, np.pi * stab.line_spacing_hz)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(peaks > 0, peaks / stab.noise_rms, 0.0)
    largest = float(np.max(peaks))
    return (
        largest if math.isfinite(largest) else 0.0,
        float(np.nan_to_num(np.max(ratio), nan=0.0, posinf=np.inf)),
    )


# --- input checks ----------------------------------------------------------------------------


def _combine(frfs: FrfSet | Sequence[FrfSet]) -> FrfSet:
    """One FRF set from one or several on a common frequency axis."""
    sets = [frfs] if isinstance(frfs, FrfSet) else list(frfs)
    if not sets or not all(isinstance(s, FrfSet) for s in sets):
        raise InputError("stabilisation needs an FrfSet or a sequence of FrfSets")
    first = sets[0]
    for k, other in enumerate(sets[1:], start=2):
        check_fit_together(first, other, f"FRF set {k}", "set 1")
    if len(sets) == 1:
        return first
    return FrfSet(
        frequency=first.frequency,
        values=np.vstack([s.values for s in sets]),
        frf_type=first.frf_type,
        nodes=tuple(n for s in sets for n in s.nodes),
        locations=np.vstack([s.locations for s in sets]),
        reference_node=first.reference_node,
        reference_location=first.reference_location,
        exponential_window_s=first.exponential_window_s,
        source=" + ".join(s.source for s in sets if s.source),
    )


def _band(data: FrfSet, band_hz: tuple[float, float], max_order: int) -> FrfSet:
    """The FRFs over the band, checked for the fit."""
    try:
        low, high = (float(v) for v in band_hz)
    except (TypeError, ValueError):
        raise InputError(f"band_hz must be two frequencies in Hz (got {band_hz!r})") from None
    if not (math.isfinite(low) and math.isfinite(high) and 0 <= low < high):
        raise InputError(
            f"band_hz must be two finite frequencies, low < high, Hz (got {band_hz!r})"
        )
    f_min, f_max = float(data.frequency[0]), float(data.frequency[-1])
    if high <= f_min or low >= f_max:
        raise InputError(f"band {low:g}–{high:g} Hz lies outside the FRFs' {f_min:g}–{f_max:g} Hz")
    if low < f_min or high > f_max:
        logger.warning(
            "band %g–%g Hz cut to the measured %g–%g Hz",
            low,
            high,
            max(low, f_min),
            min(high, f_max),
        )
    band = data.band(max(low, f_min), min(high, f_max))
    n_lines = band.frequency.size
    if n_lines <= 2 * max_order:
        wider = "" if low <= f_min and high >= f_max else ", or widen the band"
        raise InputError(
            f"band {low:g}–{high:g} Hz holds {n_lines} lines; max_order {max_order} needs more "
            f"than {2 * max_order}: give `max_order` {(n_lines - 1) // 2} or lower{wider}"
        )
    finite = np.all(np.isfinite(band.values), axis=1)
    if not np.all(finite):
        bad = [band.nodes[k] for k in np.flatnonzero(~finite)[:5]]
        raise InputError(
            f"{data.source}: FRFs of nodes {bad} hold NaN or inf in the band; leave those "
            "points out"
        )
    if not np.any(np.abs(band.values) > 0):
        raise InputError(f"{data.source}: every FRF is zero between {low:g} and {high:g} Hz")
    return band


def _frequencies(
    name: str, values: Sequence[float], band_hz: tuple[float, float]
) -> NDArray[np.float64]:
    try:
        out = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"{name} must be frequencies in Hz (got {values!r})") from None
    if out.ndim != 1 or not np.all(np.isfinite(out)):
        raise InputError(f"{name} must be finite frequencies in Hz (got {values!r})")
    outside = out[(out < band_hz[0]) | (out > band_hz[1])]
    if outside.size:
        raise InputError(
            f"{name}: {outside[0]:g} Hz lies outside the band {band_hz[0]:g}–{band_hz[1]:g} Hz"
        )
    return out
