"""Kawazoe's approximate impact method (paper, sections 3.3–4.2, eqs 1–12).

The ball (mass m_B) meets the racket's reduced mass M_r at the impact point through the
compound ball+string spring F_GB(X).  The contact lasts half a period of that two-body system
(eq 7) at the stiffness reached at the peak deflection; the impulse (1 + e_BG) μ V (eqs 6, 8) is
delivered as a half-sine pulse (eq 11) whose spectrum at each natural frequency sets the
vibration left in each mode (eq 12); that energy is charged against the ball–string COR e_BG to
give the ball–racket COR e_r and the rebound.

Reading of eq (10).  The paper writes ``F_MEAN = func(K_GB)`` from the measured restoring force
and points to its reference 11; eqs (7)–(9) then follow from one stiffness K_GB per impact.
Two readings are offered (``stiffness_reading``):

``"period"`` (default)
    K_GB is the stiffness of the linear spring with the same half period as the nonlinear
    contact: T_c is the exact elastic contact time of the ball on F_GB against M_r,
    ``T_c = 2 ∫₀^{X_p} dX / sqrt(V² − 2 E_GB(X)/μ)`` with ``E_GB(X_p) = ½ μ V²``, and
    ``K_GB = π² μ / T_c²`` (eq 7).  This is the paper's own premise — "the contact duration is
    determined by the natural period of the entire system" with the nonlinear stiffness —
    taken literally, and it matches a time-domain solution of the contact by construction.
``"tangent"``
    The paper's shortcut: K_GB is the tangent stiffness ``dF_GB/dX`` at the peak deflection and
    the half-sine reaches the restoring force there, ``F_MAX = F_GB(X_p)``.  With eq (9) this is
    ``F_GB(X_p)/sqrt(K(X_p)) = (1 + e_BG) V sqrt(μ)/2``.  The tangent stiffness is the stiffest
    the contact ever gets, so for a stiffening spring T_c comes out short (for the built-in
    laws at the face centre: 9 % at 10 m/s, 24 % at 20 m/s, 34 % at 30 m/s against the exact
    elastic contact time) and F_MAX high; kept to reproduce the paper's figures.

For a linear spring both give T_c = π sqrt(μ/k) exactly.  The tangent reading, and the
period reading under the paper's charge, take the impulse (1 + e_BG) μ V (eqs 6, 8) and
F_MAX = π F_MEAN / 2 (eq 11).  The period reading under the coupled charge (the default) takes
the contact from the charge's own balances (:func:`_coupled_contact`): the spring, holding
the approach energy less the frame's at the turn, is pressed to X_p and pushes
F_MAX = F_GB(X_p); it loads along F_GB and unloads along its hysteresis, which sets T_c
(:func:`hysteretic_contact_time`, longer than eq 7's elastic half period); the impulse is the
rebound's, (1 + e_r) μ V, so F_MEAN = (1 + e_r) μ V / T_c.  On a rigid racket this is the
transient model's contact to round-off; over issue 22's protocol its peak force within
2.3 % and its T_c within −8.8 … +0.4 %, where eq 11's half sine was up to 22 % low and eq 7's
T_c up to 14 % short (docs/validation.md, "The contact: time and forces").  K_GB = π² μ / T_c²
either way.

The vibration charge (``vibration_charge``).  ``"paper"`` is eq 12 as written: the half sine's
spectrum, its energy taken from e_BG².  ``"coupled"`` (default) takes, for the spectrum, the
contact's own pulse — the mass μ on F_GB, the elastic contact whose half period is eq 7's T_c
in the period reading (:func:`contact_spectra`; for a linear law, eq 11's half sine) — and
charges it by the coupled contact's balances of energy and momentum
(:func:`vibration_cor_squared`).  Against the transient model over issue 22's protocol (frames
of 120, 130 and 190 Hz, along the axis and 40 mm off it, 10–40 m/s, free and pinned) the worst
row is 0.0033 / 0.0041 / 0.0042 (the half sine with the energy balance alone: 0.010 / 0.006 /
0.017, under-charging a stiff frame's throat, where f₁ T_c ≈ 0.9 and the mode takes what the
stiffening law's peaked pulse gives; docs/validation.md).
"""

from __future__ import annotations

import functools
import logging
from collections.abc import Callable, Sequence
from dataclasses import dataclass, fields
from typing import Any, Literal, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import Ball, RestoringForce
from racketdyn.errors import InputError, one_of
from racketdyn.impact.grid import (
    ImpactGrid,
    StringBed,
    check_string_bed,
    impact_grid,
    predict_by_point_law,
)
from racketdyn.impact.result import (
    STATUS_BEYOND_LAW,
    STATUS_FRAME_CONTACT,
    STATUS_OK,
    STATUS_VIBRATION_LOSS,
    STATUS_VIBRATION_SHARE,
    ImpactResult,
)
from racketdyn.impact.spectrum import half_sine_spectrum
from racketdyn.modal import ModalModel
from racketdyn.numerics import invert_increasing
from racketdyn.racket import SUPPORTS, Racket

__all__ = [
    "STATUSES",
    "STIFFNESS_READINGS",
    "VIBRATION_CHARGES",
    "VIBRATION_SHARE_LIMIT",
    "ApproximateImpacts",
    "Shapes",
    "StiffnessReading",
    "VibrationCharge",
    "approach_energy",
    "approximate_impacts",
    "contact_spectra",
    "elastic_contact_time",
    "predict",
    "shapes_where",
    "tangent_peak_deflection",
    "vibration_cor_squared",
]

log = logging.getLogger(__name__)

StiffnessReading = Literal["period", "tangent"]
STIFFNESS_READINGS: tuple[str, ...] = get_args(StiffnessReading)
VIBRATION_SHARE_LIMIT = 0.30
"""Largest share of the approach energy ``½ μ V²`` the frame's vibration (eq 12) may take for
the approximate method to give a number.  Measured (2026-11-26, docs/validation.md): over the
built-in racket at 120, 130, 160 and 190 Hz, along the long axis and 40 mm off it, 10–40 m/s,
free and pinned, every one of the 430 rows (of 551) at or below 30 % was within 0.013 of the
transient model's rebound ratio with the half-sine coupled charge, and rows above it up to 0.28
off.  With the contact's own pulse and the momentum balance (2026-11-27, the axis ending at the
tip landmark): the 496 rows at or below 30 % within 0.0042 and the 16 from 30 to 40 % within
0.0042 as well; kept at 30 % (the paper's charge, and rows the transient does not give, are
not measured above it).  The coupled charge holds the frame's energy at the contact's turn to
the same share (2026-11-27, review): single modes of 600–2000 Hz and 0.3–10 g and the
membrane mode charged (``include_string_bed``), 10–40 m/s, free and pinned, within 0.0113 of
the transient model up to 30 % at the turn, 0.024 from 30 to 50 %, 0.058 from 80 to 100 %;
beyond 100 % e_r passed 1 (energy from nowhere, rebound ratios up to 0.96 off)."""


def approach_energy(
    ball_mass: float, reduced_mass: ArrayLike, speed: ArrayLike
) -> NDArray[np.float64]:
    """The approach energy ``½ μ V²`` of ball and racket, J: the energy of their motion
    towards each other, which the impact may turn into rebound, losses and vibration; the
    energy :data:`VIBRATION_SHARE_LIMIT` and the report's vibration share are shares of.

    Parameters
    ----------
    ball_mass : float
        m_B, kg.
    reduced_mass : array_like
        The racket's reduced mass M_r at the impact point, kg (eq 4).
    speed : array_like
        The relative speed V = V_Bo + V_Ro (ball and racket towards each other), m/s.

    Returns
    -------
    ndarray
        ``½ μ V²`` with ``μ = m_B M_r / (m_B + M_r)`` (the pair's reduced mass, whose
        natural period is eq 7's contact time).
    """
    reduced = np.asarray(reduced_mass, dtype=float)
    mu = ball_mass * reduced / (ball_mass + reduced)
    return np.asarray(0.5 * mu * np.asarray(speed, dtype=float) ** 2)


VibrationCharge = Literal["coupled", "paper"]
VIBRATION_CHARGES: tuple[str, ...] = get_args(VibrationCharge)

_CONTACT_NODES = 48
"""Gauss–Legendre nodes for the contact-time integral in θ (X = X_p sin θ): the integrand is
smooth in θ, so 48 nodes give the half period to round-off for polynomial laws."""


@functools.cache
def _legendre_nodes(
    count: int,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """θ nodes on [0, π/2], their weights, and the ``(count, count)`` matrix taking dt/dθ at
    the nodes to t(θ) = ∫₀^θ (dt/dθ') dθ' at each node: the Legendre series through the nodes
    integrated (numpy's legint).  Own code because scipy's cumulative rules need sampled end
    points, where dt/dθ is 0/0."""
    legendre = np.polynomial.legendre
    nodes, weights = legendre.leggauss(count)
    # the series' coefficients by the nodes' discrete orthogonality: (2k + 1)/2 Σ w P_k g
    vander = legendre.legvander(nodes, count - 1)
    series = (np.arange(count) + 0.5)[:, None] * vander.T * weights
    cumulative = legendre.legvander(nodes, count) @ legendre.legint(series, lbnd=-1, axis=0)
    return 0.25 * np.pi * (nodes + 1.0), 0.25 * np.pi * weights, 0.25 * np.pi * cumulative


def _contact_rate(
    law: RestoringForce, mu: ArrayLike, peak: ArrayLike, theta: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Deflection X = X_p sin θ and dt/dθ of the elastic contact at the nodes θ, ``(..., n)``."""
    mu_, x_p = (np.asarray(a, dtype=float)[..., None] for a in (mu, peak))
    x = x_p * np.sin(theta)
    return x, x_p * np.cos(theta) / np.sqrt(2.0 * (law.energy(x_p) - law.energy(x)) / mu_)


def elastic_contact_time(
    law: RestoringForce, mu: ArrayLike, peak: ArrayLike
) -> NDArray[np.float64]:
    """Exact duration of an elastic contact of mass μ on the law ``F(X)``, s.

    ``T_c = 2 ∫₀^{X_p} dX / sqrt(2 (E(X_p) − E(X)) / μ)`` — the approach speed V enters through
    ``E(X_p) = ½ μ V²`` — computed with the substitution ``X = X_p sin θ``, which removes the
    inverse-square-root end point, and Gauss–Legendre quadrature.  For a linear spring the
    integrand is constant and the result is π sqrt(μ/k) exactly.

    Parameters
    ----------
    law : RestoringForce
        Loading curve F(X).
    mu : array_like
        Two-body mass μ = m_B M_r / (m_B + M_r), kg.
    peak : array_like
        Peak deflection X_p > 0, m.
    """
    theta, weights, _ = _legendre_nodes(_CONTACT_NODES)
    _, rate = _contact_rate(law, mu, peak, theta)
    return np.asarray(2.0 * np.sum(rate * weights, axis=-1))


def hysteretic_contact_time(
    law: RestoringForce, mu: ArrayLike, peak: ArrayLike, e_bg: ArrayLike
) -> NDArray[np.float64]:
    """Duration of a contact of mass μ that loads along F_GB to X_p and unloads along the
    transient model's hysteresis ``F_GB(X) (X/X_p)^p``, which gives back e_BG² of E_GB(X_p), s.

    ``T_c = ∫₀^{X_p} dX / sqrt(2 (E(X_p) − E(X)) / μ) + ∫₀^{X_p} dX / sqrt(2 (E_un(X_p) −
    E_un(X)) / μ)``: the loading half of :func:`elastic_contact_time` and the unloading on the
    softer curve (:meth:`~racketdyn.ball.RestoringForce.unloading_energy`), both in
    ``X = X_p sin θ`` with Gauss–Legendre quadrature.  On a rigid racket it is the transient
    model's contact time; for e_BG = 1, the elastic one.

    Parameters
    ----------
    law : RestoringForce
        Loading curve F_GB(X).
    mu : array_like
        Two-body mass, kg.
    peak : array_like
        Peak deflection X_p > 0, m.
    e_bg : array_like
        COR of the spring's hysteresis (e_BG), broadcast against ``peak``.
    """
    theta, weights, _ = _legendre_nodes(_CONTACT_NODES)
    mu_, x_p = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (mu, peak)))
    x, loading = _contact_rate(law, mu_, x_p, theta)
    e = np.broadcast_to(np.asarray(e_bg, dtype=float), x_p.shape)
    p = law.unloading_exponent(x_p, e)[..., None]
    held = law.unloading_energy(x_p[..., None], x_p[..., None], p)
    left = np.maximum(held - law.unloading_energy(x, x_p[..., None], p), 0.0)
    unloading = x_p[..., None] * np.cos(theta) / np.sqrt(2.0 * left / mu_[..., None])
    return np.asarray(np.sum((loading + unloading) * weights, axis=-1))


def elastic_contact(
    law: RestoringForce, mu: ArrayLike, speed: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """Peak deflection and duration of an elastic contact of mass μ at an approach speed.

    ``E(X_p) = ½ μ V²`` solved for X_p, then :func:`elastic_contact_time`.  Where X_p lies
    beyond the law's range, the law's end stands in (``in_range`` is False there).

    Parameters
    ----------
    law : RestoringForce
        Loading curve F(X).
    mu : array_like
        Two-body mass, kg.
    speed : array_like
        Approach speed V, m/s.

    Returns
    -------
    peak, contact_time, in_range : ndarray
        X_p (m), T_c (s) and whether X_p is within the law.
    """
    mu_ = np.asarray(mu, dtype=float)
    deflection = np.asarray(law.deflection_at_energy(0.5 * mu_ * np.asarray(speed) ** 2))
    in_range = np.isfinite(deflection)
    peak = np.where(in_range, deflection, law.max_deflection_m)
    return peak, np.asarray(elastic_contact_time(law, mu_, peak)), in_range


def tangent_peak_deflection(law: RestoringForce, target: ArrayLike) -> NDArray[np.float64]:
    """Solve ``F(X)/sqrt(K(X)) = target`` for the peak deflection X, m (tangent reading).

    NaN where the target lies beyond the law's range.

    Raises
    ------
    InputError
        If ``F/sqrt(K)`` does not rise with X (a law softening so fast that the tangent reading
        of eq 10 has no unique solution).
    """

    def ratio(x: NDArray[np.float64]) -> NDArray[np.float64]:
        with np.errstate(invalid="ignore", divide="ignore"):
            value = law.force(x) / np.sqrt(law.stiffness(x))
        return np.asarray(np.where(x > 0, value, 0.0))

    def slope(x: NDArray[np.float64]) -> NDArray[np.float64]:
        force, stiffness, curvature = law.force(x), law.stiffness(x), law.curvature(x)
        with np.errstate(invalid="ignore", divide="ignore"):
            value = np.sqrt(stiffness) - force * curvature / (2.0 * stiffness**1.5)
        return np.asarray(np.nan_to_num(value, nan=0.0, posinf=0.0, neginf=0.0))

    try:
        return invert_increasing(ratio, slope, target, law.max_deflection_m)
    except ValueError:
        raise InputError(
            f"restoring force ({law.source}): F/sqrt(dF/dX) must rise with deflection for the "
            "tangent reading of eq (10); use the period reading"
        ) from None


_CYCLES_RESOLVED = 32.0
"""Cycles of a mode over the contact (f T_c) that :data:`_CONTACT_NODES` resolve in
:func:`contact_spectra`; beyond, more nodes.  Measured against 512 nodes on the built-in law
at 40 m/s: 48 nodes to 3e-7 (relative) up to f T_c = 40 and 75 % off at 50, 64 nodes to 2e-5 at
60, 96 nodes to 1e-9 at 80 (a 100 × stiffer frame's 2-node mode sits at f T_c ≈ 54)."""


def contact_spectra(
    law: RestoringForce, mu: ArrayLike, peak: ArrayLike, omega: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The elastic contact's own pulse at each mode, per unit impulse: whole and to the turn.

    The mass μ on the law F(X) from first touch to the peak deflection X_p and back (the
    contact whose duration is eq 7's T_c in the period reading): ``dt/dθ`` as in
    :func:`elastic_contact_time` and the force ``F(X_p sin θ)``; the pulse is symmetric about
    its turn T_c/2.  For a linear law it is eq 11's half sine.

    Parameters
    ----------
    law : RestoringForce
        Loading curve F(X).
    mu, peak : array_like (...)
        Two-body mass μ (kg) and peak deflection X_p (m).
    omega : array_like (..., m)
        Natural angular frequencies, rad/s.

    Returns
    -------
    whole, to_turn : ndarray (..., m)
        ``|S(ω)| / J`` over the pulse and ``|∫₀^{T_c/2} F e^{−iωt} dt| / J`` to its turn,
        J the pulse's impulse (both 1 at ω = 0, ½ for the turn).
    """
    w = np.asarray(omega, dtype=float)[..., None]
    count = _nodes_for(np.max(w, initial=0.0) * elastic_contact_time(law, mu, peak) / (2 * np.pi))
    theta, weights, cumulative = _legendre_nodes(count)
    x, rate = _contact_rate(law, mu, peak, theta)
    time = rate @ cumulative.T  # (..., nodes)
    turn = np.sum(rate * weights, axis=-1, keepdims=True)  # T_c / 2
    weight = (rate * law.force(x) * weights)[..., None, :]  # F dt at each node
    impulse = 2.0 * np.sum(weight, axis=-1)
    whole = 2.0 * np.sum(weight * np.cos(w * (turn[..., None] - time[..., None, :])), axis=-1)
    to_turn = np.sum(weight * np.exp(-1j * w * time[..., None, :]), axis=-1)
    return np.abs(whole) / impulse, np.abs(to_turn) / impulse


def _nodes_for(cycles: ArrayLike) -> int:
    """Nodes resolving a mode of ``cycles`` (f T_c, the most of an array) in the contact's
    pulse: :data:`_CONTACT_NODES` up to :data:`_CYCLES_RESOLVED`, then 1.5 per cycle, by 16."""
    most = float(np.max(np.nan_to_num(np.asarray(cycles, dtype=float)), initial=0.0))
    if most <= _CYCLES_RESOLVED:
        return _CONTACT_NODES
    return int(16 * np.ceil(1.5 * most / 16))


def vibration_cor_squared(
    e_bg: ArrayLike,
    vibration_energy: ArrayLike,
    turn_energy: ArrayLike,
    relative_energy: ArrayLike,
    charge: VibrationCharge = "coupled",
) -> NDArray[np.float64]:
    """The ball–racket COR squared, e_r², after the frame's vibration is charged (section 4.2).

    The energies are those of a pulse of eq 8's impulse ``(1 + e_BG) μ V``.

    ``paper``: ``e_r² = e_BG² − E_vib / E_rel`` — the whole approach energy
    ``E_rel = ½ μ V²`` passes through the ball–string spring and loses its share 1 − e_BG², and
    the vibration is taken on top.

    ``coupled`` (default): the coupled contact's two balances.  Energy: the ball–string loss is
    a hysteresis of the spring, 1 − e_BG² of what it holds at its turn, and at the turn the
    frame holds ``E_turn`` that never passed through it (the transient model's
    ``½ μ V² e_r² = E_rel − (1 − e_BG²) E_spring(turn) − E_vib`` with
    ``E_spring(turn) = E_rel − E_turn``).  Momentum: the pulse's impulse is the ball's change of
    momentum, ``(1 + e_r) μ V`` (the modes carry none), not ``(1 + e_BG) μ V``, and the modes'
    energies go with its square.  With ``k = (E_vib − (1 − e_BG²) E_turn) / (E_rel (1 + e_BG)²)``
    the two give ``e_r² + k (1 + e_r)² = e_BG²``, whose root is

        ``e_r = (sqrt(e_BG² (1 + k) − k) − k) / (1 + k)``.

    Parameters
    ----------
    e_bg, vibration_energy, turn_energy, relative_energy : array_like
        e_BG, E_vib at separation (J), E_turn (J) and E_rel (J), broadcast together.
    charge : {"coupled", "paper"}

    Returns
    -------
    ndarray
        e_r², negative where no e_r ≥ 0 balances the charge (``coupled``: e_r's sign times
        e_r²).
    """
    one_of("vibration_charge", charge, VIBRATION_CHARGES)
    e = np.asarray(e_bg, dtype=float)
    vibration, relative = (np.asarray(a, dtype=float) for a in (vibration_energy, relative_energy))
    if charge == "paper":
        return np.asarray(e**2 - vibration / relative)
    charged = vibration - (1.0 - e**2) * np.asarray(turn_energy, dtype=float)
    k = charged / (relative * (1.0 + e) ** 2)
    cor = (np.sqrt(np.maximum(e**2 * (1.0 + k) - k, 0.0)) - k) / (1.0 + k)
    return np.asarray(np.sign(cor) * cor**2)


# 13 parameters: the paper's inputs of an impact and the method's readings, each documented
# once here and taken by name by the CLI, the workflows and predict_by_point_law; no object
# of them reads better for callers
def predict(
    racket: Racket,
    ball: Ball,
    locations: ArrayLike,
    ball_speed: ArrayLike,
    supports: Sequence[str] | str = SUPPORTS,
    racket_speed: ArrayLike = 0.0,
    modal_model: ModalModel | Literal["racket"] | None = "racket",
    labels: Sequence[str] | None = None,
    law: RestoringForce | None = None,
    include_string_bed: bool = False,
    stiffness_reading: StiffnessReading = "period",
    string_bed: StringBed = "uniform",
    vibration_charge: VibrationCharge = "coupled",
) -> ImpactResult:
    """Predict contact time, forces, vibration and rebound by the approximate method.

    Vectorised over every impact point, speed and support.

    Parameters
    ----------
    racket : Racket
        Mass properties, head and strings, taken as given: a library function trusts its
        caller, as numpy does (sweeps, uncertainty samples and tests build unusual rackets on
        purpose).  The workflow steps check a racket against the racket file's plausible
        ranges; check one built in Python with :func:`racketdyn.io.check_racket`.
    ball : Ball
        Ball mass, e_BG and restoring force.
    locations : array_like, shape (n, 2)
        Impact points (x, y) on the string bed, m.
    ball_speed : array_like, shape (s,)
        Incoming ball speed V_Bo towards the strings, m/s.
    supports : str or sequence of {"free", "pinned"}
        Support conditions (eq 4 for ``pinned``); one text of one or several comma-separated
        names too (``"free,pinned"``, as the command line and the options objects take them).
    racket_speed : float or array_like, shape (s,)
        Speed of the racket's impact point towards the ball before impact, m/s (the paper's
        V_Ro with the sign making it add to the ball's).
    modal_model : ModalModel, None or "racket"
        Modes for eq (12); ``"racket"`` takes the racket's own
        (:func:`racketdyn.racket_modal.modal_model_for`); ``None`` is a rigid racket (no
        vibration loss).
    labels : sequence of str, optional
        Point labels (default 1, 2, …).
    law : RestoringForce, optional
        Compound ball+string law F_GB at every point; default
        :func:`racketdyn.contact.compound_law` (with ``string_bed="uniform"``).
    include_string_bed : bool
        Charge string-bed (membrane) modes as vibration loss too.  Off by default: the
        compound spring already carries the string bed's deflection (section 3.4), and with the
        ball on the strings the membrane mode becomes the ball–racket mode (103 Hz in the paper,
        section 3.2) whose half period *is* the contact time, so charging it again would count
        the strings twice.
    stiffness_reading : {"period", "tangent"}
        Reading of eq (10), see the module docstring.
    string_bed : {"uniform", "local"}
        ``uniform``: one law for the whole face, the centre's (the paper's method);
        ``local``: each point's own law from the lengths of its main and cross strings
        (:func:`racketdyn.impact.grid.predict_by_point_law`, stiffer towards the frame).
    vibration_charge : {"coupled", "paper"}
        How the vibration is charged against e_BG (:func:`vibration_cor_squared`): ``coupled``
        (default) the contact's own pulse (:func:`contact_spectra`) charged as the coupled
        contact's energy and momentum balances give it, ``paper`` eq 12's half sine as
        section 4.2 writes it (to reproduce the paper's figures).

    Returns
    -------
    ImpactResult
        Arrays shaped ``(n_points, n_speeds, n_supports)``.
    """
    one_of("stiffness_reading", stiffness_reading, STIFFNESS_READINGS)
    one_of("vibration_charge", vibration_charge, VIBRATION_CHARGES)
    check_string_bed(string_bed, law, racket)
    if string_bed == "local":
        grid_options = {
            "ball_speed": ball_speed,
            "supports": supports,
            "vibration_charge": vibration_charge,
        }
        return predict_by_point_law(  # type: ignore[no-any-return]
            predict, racket, ball, locations, labels, modal_model, include_string_bed,
            racket_speed=racket_speed, stiffness_reading=stiffness_reading, **grid_options,
        )  # fmt: skip
    grid = impact_grid(
        racket,
        ball,
        locations,
        ball_speed,
        supports,
        racket_speed,
        modal_model,
        labels,
        law,
        include_string_bed,
    )
    return _predict_on(grid, ball, stiffness_reading, include_string_bed, vibration_charge)


def _predict_on(
    grid: ImpactGrid,
    ball: Ball,
    stiffness_reading: StiffnessReading,
    include_string_bed: bool,
    vibration_charge: VibrationCharge,
) -> ImpactResult:
    """:func:`predict` on its checked grid: eqs 1–12 at every point, speed and support."""
    xy, model, v_ball, v_racket = grid.locations, grid.model, grid.ball_speed, grid.racket_speed
    speed = (v_ball + v_racket)[None, :, None]  # (1, s, 1)
    impacts = approximate_impacts(
        grid.law,
        ball,
        grid.reduced_mass[:, None, :],
        v_ball[None, :, None],
        v_racket[None, :, None],
        grid.ball.e_bg_at(speed),  # e_BG at the relative speed (given, or ball + strings)
        None if model is None else (model.frequency, _shapes_at(model, xy)),
        grid.reaches_frame,
        stiffness_reading=stiffness_reading,
        vibration_charge=vibration_charge,
    )
    _log_statuses(impacts.status)
    inputs = grid.inputs(
        ball,
        "approximate (Kawazoe, eqs 1-12)",
        stiffness_reading=stiffness_reading,
        include_string_bed=include_string_bed,
        vibration_charge=vibration_charge,
    )
    return ImpactResult(
        locations=xy,
        labels=grid.labels,
        ball_speed=v_ball,
        racket_speed=v_racket,
        supports=grid.supports,
        reduced_mass=grid.reduced_mass,
        **impacts.arrays(),
        modal_model=model,
        inputs=inputs,
    )


STATUSES: tuple[str, ...] = (
    STATUS_OK,
    STATUS_VIBRATION_SHARE,
    STATUS_VIBRATION_LOSS,
    STATUS_FRAME_CONTACT,
    STATUS_BEYOND_LAW,
)
"""The approximate method's statuses, by :attr:`ApproximateImpacts.status_code`."""


def _log_statuses(status: NDArray[np.str_]) -> None:
    """One warning per status that left impacts without numbers."""
    for message in STATUSES[1:]:
        count = int(np.sum(status == message))
        if count:
            log.warning("%d of %d impacts: %s (their results are NaN)", count, status.size, message)


Shapes = Callable[[NDArray[np.bool_]], NDArray[np.float64]]
"""``shapes(needed)``: the mode shapes (1/√kg) at the points of impacts shaped ``(...)``, as
``(..., n_modes)`` with the speed and support axes 1; a point none of whose impacts is
``needed`` (frame shots, beyond the law) may be left 0."""


def shapes_where(
    model: ModalModel, points: NDArray[np.float64], wanted: NDArray[np.bool_]
) -> NDArray[np.float64]:
    """``(n, n_modes)`` mode shapes at the ``wanted`` of ``(n, 2)`` points, 0 elsewhere, 1/√kg
    (a spline evaluation costs ≈ 20 µs a point on the built-in racket's 797 samples)."""
    phi = np.zeros((points.shape[0], model.n_modes))
    if np.any(wanted):
        phi[wanted] = model.mode_shapes_at(points[wanted])
    return phi


def _shapes_at(model: ModalModel, xy: NDArray[np.float64]) -> Shapes:
    """:data:`Shapes` at the grid's ``(n_points, 2)`` points."""
    return lambda needed: shapes_where(model, xy, np.asarray(needed.any(axis=(1, 2))))[
        :, None, None, :
    ]


@dataclass(frozen=True)
class ApproximateImpacts:
    """The approximate method's numbers for impacts of any shape ``(...)`` (eqs 6–12).

    Attributes
    ----------
    stiffness : ndarray
        K_GB, N/m (eq 7).
    peak_deflection : ndarray
        X_p, m.
    contact_time : ndarray
        T_c, s.
    mean_force, peak_force : ndarray
        F_MEAN and F_MAX, N (eqs 8–11; with the coupled charge in the period reading, the
        rebound's impulse over T_c and the spring's force at the turn).
    mode_energy : ndarray
        ``(..., n_modes)`` vibration energy left in each mode, J (eq 12).
    vibration_energy : ndarray
        Their sum, J.
    cor : ndarray
        Ball–racket COR e_r.
    rebound_ratio, rebound_speed : ndarray
        e_A and the ball's outgoing speed, m/s.
    status_code : ndarray of int8
        Index in :data:`STATUSES`: 0 (``ok``) or why the method gives no number
        (:attr:`status` in words).
    """

    stiffness: NDArray[np.float64]
    peak_deflection: NDArray[np.float64]
    contact_time: NDArray[np.float64]
    mean_force: NDArray[np.float64]
    peak_force: NDArray[np.float64]
    mode_energy: NDArray[np.float64]
    vibration_energy: NDArray[np.float64]
    cor: NDArray[np.float64]
    rebound_ratio: NDArray[np.float64]
    rebound_speed: NDArray[np.float64]
    status_code: NDArray[np.int8]

    @property
    def status(self) -> NDArray[np.str_]:
        """``ok`` or why the method gives no number, per impact."""
        # as wide as the longest status present (all ok: two characters an impact)
        return np.asarray(np.asarray(STATUSES, dtype=object)[self.status_code].astype(str))

    def arrays(self) -> dict[str, Any]:
        """The :class:`ImpactResult` fields they fill, by name (the status in words)."""
        out = {f.name: getattr(self, f.name) for f in fields(self) if f.name != "status_code"}
        return {**out, "status": self.status}


def approximate_impacts(
    law: RestoringForce,
    ball: Ball,
    reduced_mass: NDArray[np.float64],
    ball_speed: NDArray[np.float64],
    racket_speed: NDArray[np.float64],
    e_bg: NDArray[np.float64],
    modes: tuple[NDArray[np.float64], Shapes] | None,
    reaches_frame: Callable[[NDArray[np.float64]], NDArray[np.bool_]],
    *,
    stiffness_reading: StiffnessReading = "period",
    vibration_charge: VibrationCharge = "coupled",
) -> ApproximateImpacts:
    """The approximate method (eqs 1–12) on arrays that broadcast to the impacts' shape.

    :func:`predict` calls it on ``(n_points, n_speeds, n_supports)``; a stack of samples
    (:func:`racketdyn.impact.samples.predict_samples`) adds a leading sample axis.

    Parameters
    ----------
    law : RestoringForce
        Compound ball+string law F_GB.
    ball : Ball
        The ball (its mass, kg).
    reduced_mass : ndarray
        Racket's reduced mass M_r at each impact, kg (eq 4).
    ball_speed, racket_speed : ndarray
        V_Bo and V_Ro towards each other, m/s.
    e_bg : ndarray
        e_BG at each impact's relative speed.
    modes : (ndarray, callable) or None
        Natural frequencies (Hz) with a last mode axis broadcasting against
        ``(..., n_modes)``, and :data:`Shapes`, the mass-normalised shapes at the impact
        points; None: a rigid racket.
    reaches_frame : callable
        ``reaches_frame(peak_deflection)``: where the ball reaches the frame (a frame shot,
        :meth:`racketdyn.impact.grid.ImpactGrid.reaches_frame`).
    stiffness_reading, vibration_charge : str
        As for :func:`predict`.

    Returns
    -------
    ApproximateImpacts
    """
    speed = ball_speed + racket_speed
    shape = np.broadcast_shapes(reduced_mass.shape, speed.shape, np.shape(e_bg))
    m_b = ball.mass_kg
    mu = np.broadcast_to(m_b * reduced_mass / (m_b + reduced_mass), shape)
    impulse = (1.0 + e_bg) * mu * speed  # eqs (6), (8)
    # the coupled charge's period reading times its own contact (_coupled_contact)
    elastic = vibration_charge == "paper" or stiffness_reading == "tangent"
    deflection, contact_time, stiffness, in_range, frame = _contact(
        law, (mu, speed, impulse), stiffness_reading, reaches_frame, elastic
    )
    mean_force = impulse / contact_time  # eqs (8)-(10)
    peak_force = np.pi * mean_force / 2.0  # eq (11)
    # the contact's own pulse reaches E(X_p) = ½ μ V², the period reading's peak deflection
    peak = (
        deflection
        if stiffness_reading == "period"
        else np.asarray(law.deflection_at_energy(0.5 * mu * speed**2))
    )
    pulse = _Pulse(law, mu, peak, impulse, in_range & ~frame, contact_time, peak_force)
    mode_energy, turn_energy = _vibration(modes, pulse, vibration_charge)
    cor_squared = vibration_cor_squared(
        e_bg, mode_energy.sum(axis=-1), turn_energy, 0.5 * mu * speed**2, vibration_charge
    )
    valid = in_range & (cor_squared >= 0.0)
    cor = np.sqrt(np.where(valid, cor_squared, np.nan))
    if vibration_charge == "coupled":  # the pulse's impulse is (1 + e_r) μ V
        scale = np.where(valid, ((1.0 + cor) / (1.0 + e_bg)) ** 2, 1.0)
        mode_energy, turn_energy = mode_energy * scale[..., None], turn_energy * scale
        if stiffness_reading == "period":  # the tangent reading is the paper's shortcut
            coupled = _coupled_contact(law, mu, speed, turn_energy, (e_bg, cor, valid))
            deflection, contact_time, mean_force, peak_force = (
                np.where(valid, new, old)
                for new, old in zip(
                    coupled, (pulse.peak, contact_time, mean_force, peak_force), strict=True
                )
            )
            stiffness = np.pi**2 * mu / contact_time**2  # eq (7) solved for K_GB
    vibration_energy = mode_energy.sum(axis=-1)
    mass_ratio = m_b / reduced_mass
    rebound_ratio = (cor - mass_ratio) / (1.0 + mass_ratio)
    status = np.zeros(deflection.shape, dtype=np.int8)  # STATUSES[0]: ok
    # the frame's share at separation and at the turn (coupled charge): a frame holding more
    # than the approach energy at the turn would give e_r > 1, energy from nowhere
    frame_energy = np.maximum(vibration_energy, turn_energy)
    with np.errstate(invalid="ignore"):
        over = frame_energy > VIBRATION_SHARE_LIMIT * approach_energy(m_b, reduced_mass, speed)
    status[in_range & valid & over] = STATUSES.index(STATUS_VIBRATION_SHARE)
    # no e_r ≥ 0 closes the balances: the paper's charge's vibration beyond e_BG²; under the
    # coupled charge the frame holding over the share limit, which says why
    beyond = STATUS_VIBRATION_LOSS if vibration_charge == "paper" else STATUS_VIBRATION_SHARE
    status[in_range & ~valid] = STATUSES.index(beyond)
    status[frame] = STATUSES.index(STATUS_FRAME_CONTACT)
    status[~in_range] = STATUSES.index(STATUS_BEYOND_LAW)
    return ApproximateImpacts(
        stiffness=stiffness,
        peak_deflection=deflection,
        contact_time=contact_time,
        mean_force=mean_force,
        peak_force=peak_force,
        mode_energy=mode_energy,
        vibration_energy=vibration_energy,
        cor=cor,
        rebound_ratio=rebound_ratio,
        rebound_speed=rebound_ratio * ball_speed + (1.0 + rebound_ratio) * racket_speed,
        status_code=status,
    )


def _coupled_contact(
    law: RestoringForce,
    mu: NDArray[np.float64],
    speed: NDArray[np.float64],
    turn_energy: NDArray[np.float64],
    balance: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]],
) -> tuple[NDArray[np.float64], ...]:
    """X_p, T_c, F_MEAN and F_MAX of the coupled charge's contact, where valid (else NaN).

    The balances that charge the vibration also say what the ball–string spring does: at the
    turn it holds the approach energy less the frame's, ``½ μ V² − E_turn``, so it is pressed
    to ``X_p = E_GB⁻¹(½ μ V² − E_turn)`` and pushes ``F_MAX = F_GB(X_p)``; it loads along F_GB
    and unloads along its hysteresis (:func:`hysteretic_contact_time`, with e_BG), which sets
    T_c; the ball's impulse is the rebound's, ``(1 + e_r) μ V`` (eq 8 with e_r for e_BG), so
    ``F_MEAN = (1 + e_r) μ V / T_c``.  On a rigid racket (``E_turn = 0``, e_r = e_BG) the
    transient model's contact.  Measured against the transient model over issue 22's protocol
    (370 rows; docs/validation.md, "The contact: time and forces"): F_MAX 0.05–2.3 % high (eq 11's
    ``π F_MEAN / 2`` was 3–22 % low: the stiffening spring's pulse is peaked), X_p within
    1.8 % (was up to 8.5 % high), the impulse within 0.4 % (was up to 11 % high), T_c
    −8.8 … +0.4 % (median −1.3 %; eq 7's elastic half period was 4–14 % short).

    Parameters
    ----------
    law : RestoringForce
        F_GB.
    mu, speed : ndarray
        μ, kg, and V, m/s.
    turn_energy : ndarray
        E_turn, the frame's energy at the turn, J.
    balance : (ndarray, ndarray, ndarray of bool)
        e_BG, e_r and where e_r is given.
    """
    e_bg, cor, valid = balance
    held = np.where(valid, 0.5 * mu * speed**2 - turn_energy, np.nan)
    deflection = np.asarray(law.deflection_at_energy(np.where(held > 0.0, held, np.nan)))
    at = np.isfinite(deflection)
    contact_time, peak_force = (np.full(deflection.shape, np.nan) for _ in range(2))
    e = np.broadcast_to(e_bg, deflection.shape)
    contact_time[at] = hysteretic_contact_time(law, mu[at], deflection[at], e[at])
    peak_force[at] = law.force(deflection[at])
    return deflection, contact_time, (1.0 + cor) * mu * speed / contact_time, peak_force


def _contact(
    law: RestoringForce,
    impact: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
    stiffness_reading: StiffnessReading,
    reaches_frame: Callable[[NDArray[np.float64]], NDArray[np.bool_]],
    elastic: bool = True,
) -> tuple[
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.bool_],
    NDArray[np.bool_],
]:
    """Peak deflection, contact time, K_GB, whether the law reaches and whether the ball
    reaches the frame, by eq (10)'s reading, for the impacts' ``(μ, V, impulse)``.  A frame
    shot's numbers are not given (NaN): its contact-time quadrature is skipped, as is every
    row's in the period reading unless ``elastic`` (eq 7's half period wanted)."""
    mu, speed, impulse = impact
    if stiffness_reading == "period":
        deflection = np.asarray(law.deflection_at_energy(0.5 * mu * speed**2))  # NaN beyond
        in_range = np.isfinite(deflection)
        frame = in_range & reaches_frame(deflection)
        needed = in_range & ~frame
        contact_time = np.full(deflection.shape, np.nan)
        if elastic:
            contact_time[needed] = elastic_contact_time(law, mu[needed], deflection[needed])
        stiffness = np.pi**2 * mu / contact_time**2  # eq (7) solved for K_GB
    else:
        deflection = tangent_peak_deflection(law, impulse / (2.0 * np.sqrt(mu)))
        in_range = np.isfinite(deflection)
        frame = in_range & reaches_frame(deflection)
        safe = np.where(in_range, deflection, 0.0)
        stiffness = np.where(in_range, law.stiffness(safe), np.nan)
        contact_time = np.pi * np.sqrt(mu / stiffness)  # eq (7)
    return deflection, contact_time, stiffness, in_range, frame


@dataclass(frozen=True)
class _Pulse:
    """Impacts' pulses, shaped ``(...)``: the contact (law, μ, peak deflection X_p) with eq 8's
    impulse, given where ``needed``, and eq 11's half sine of the same impulse (T_c, F_MAX)."""

    law: RestoringForce
    mu: NDArray[np.float64]
    peak: NDArray[np.float64]
    impulse: NDArray[np.float64]
    needed: NDArray[np.bool_]
    contact_time: NDArray[np.float64]
    peak_force: NDArray[np.float64]


def _vibration(
    modes: tuple[NDArray[np.float64], Shapes] | None,
    pulse: _Pulse,
    vibration_charge: VibrationCharge,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Each mode's energy after a pulse of eq 8's impulse and the frame's energy at the turn, J,
    where the pulse is ``needed`` (elsewhere NaN or 0): eq 12's half sine for the paper's
    charge, the contact's own pulse (:func:`contact_spectra`) for the coupled one."""
    shape = pulse.contact_time.shape
    if modes is None:
        return np.zeros((*shape, 0)), np.zeros(shape)
    frequency, shapes = modes
    phi = shapes(pulse.needed)
    if vibration_charge == "paper":  # eq 12; the paper's charge does not use the turn
        spectrum = half_sine_spectrum(
            frequency, pulse.contact_time[..., None], pulse.peak_force[..., None]
        )
        return 0.5 * (phi * spectrum) ** 2, np.zeros(shape)
    omega = np.broadcast_to(2.0 * np.pi * np.asarray(frequency), (*shape, phi.shape[-1]))
    whole, to_turn = (np.full(omega.shape, np.nan) for _ in range(2))
    at = pulse.needed & np.isfinite(pulse.peak)  # tangent reading: E(X_p) within the law
    whole[at], to_turn[at] = contact_spectra(pulse.law, pulse.mu[at], pulse.peak[at], omega[at])
    impulse = pulse.impulse[..., None]
    mode_energy = 0.5 * (phi * impulse * whole) ** 2
    return mode_energy, np.sum(0.5 * (phi * impulse * to_turn) ** 2, axis=-1)
