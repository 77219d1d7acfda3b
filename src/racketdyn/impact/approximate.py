"""Kawazoe's approximate impact method (paper, sections 3.3–4.2, eqs 1–12).

The ball (mass m_B) meets the racket's reduced mass M_r at the impact point through the
compound ball+string spring F_GB(X).  The contact lasts half a period of that two-body system
(eq 7) at the stiffness reached at the peak deflection; the impulse (1 + e_BG) μ V (eqs 6, 8) is
delivered as a half-sine pulse (eq 11) whose spectrum at each natural frequency sets the
vibration left in each mode (eq 12); that energy is charged against the ball–string COR e_BG to
give the ball–racket COR e_r and the rebound.

Reading of eq (10).  The paper writes ``F_MEAN = func(K_GB)`` from the measured restoring force
and points to its reference 11.  We take the reading the paper's own pulse implies: K_GB is the
tangent stiffness ``K(X_p) = dF_GB/dX`` at the peak deflection X_p, and the half-sine reaches the
restoring force there, ``F_MAX = F_GB(X_p)`` so ``F_MEAN = 2 F_GB(X_p)/π``.  With eq (9) this
gives one equation for X_p,

    F_GB(X_p) / sqrt(K(X_p)) = (1 + e_BG) V sqrt(μ) / 2,     μ = m_B M_r / (m_B + M_r),

whose left side rises monotonically for any stiffening law, so X_p is unique.  For a linear
spring every reading gives the same, exact, T_c = π sqrt(μ/k).
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.__about__ import __version__
from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law
from racketdyn.errors import InputError, one_of
from racketdyn.impact.result import (
    STATUS_BEYOND_LAW,
    STATUS_OK,
    STATUS_VIBRATION_LOSS,
    ImpactResult,
)
from racketdyn.impact.spectrum import half_sine_spectrum
from racketdyn.modal import ModalModel, modal_model_for
from racketdyn.racket import SUPPORTS, Racket, as_locations

__all__ = ["peak_deflection", "predict"]

log = logging.getLogger(__name__)

_TABLE_POINTS = 4097


def peak_deflection(law: RestoringForce, target: ArrayLike) -> NDArray[np.float64]:
    """Solve ``F(X)/sqrt(K(X)) = target`` for the peak deflection X, m (eqs 9–10).

    A monotone table gives the first guess and Newton steps (with the law's curvature) polish
    it.  NaN where the target lies beyond the law's valid range.

    Raises
    ------
    InputError
        If ``F/sqrt(K)`` does not rise with X over the law's range (a softening law for which
        the tangent reading of eq 10 has no unique solution).
    """
    goal = np.asarray(target, dtype=float)
    x_table = np.linspace(0.0, law.max_deflection_m, _TABLE_POINTS)
    g_table = law.force(x_table) / np.sqrt(law.stiffness(x_table))
    g_table[0] = 0.0
    if np.any(np.diff(g_table) <= 0):
        raise InputError(
            f"restoring force ({law.source}): F/sqrt(dF/dX) must rise with deflection for the "
            "paper's eq (10) to have one solution; the law softens too fast"
        )
    x = np.interp(goal, g_table, x_table)
    for _ in range(3):
        force, stiffness, curvature = law.force(x), law.stiffness(x), law.curvature(x)
        slope = np.sqrt(stiffness) - force * curvature / (2.0 * stiffness**1.5)
        residual = force / np.sqrt(stiffness) - goal
        step = np.divide(residual, slope, out=np.zeros_like(x), where=slope > 0)
        x = np.clip(x - step, 0.0, law.max_deflection_m)
    return np.asarray(np.where(goal > g_table[-1] * (1 + 1e-12), np.nan, x))


def _speeds(name: str, values: ArrayLike) -> NDArray[np.float64]:
    try:
        speeds = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"{name} must be numbers in m/s (got {values!r})") from None
    if speeds.ndim != 1 or not np.all(np.isfinite(speeds)) or np.any(speeds < 0):
        raise InputError(f"{name} must be finite speeds of zero or more, m/s (got {values!r})")
    return speeds


def predict(
    racket: Racket,
    ball: Ball,
    locations: ArrayLike,
    ball_speed: ArrayLike,
    supports: Sequence[str] = SUPPORTS,
    racket_speed: ArrayLike = 0.0,
    modal_model: ModalModel | Literal["racket"] | None = "racket",
    labels: Sequence[str] | None = None,
    law: RestoringForce | None = None,
    include_string_bed: bool = False,
) -> ImpactResult:
    """Predict contact time, forces, vibration and rebound by the approximate method.

    Vectorised over every impact point, speed and support.

    Parameters
    ----------
    racket : Racket
        Mass properties, head and strings.
    ball : Ball
        Ball mass, e_BG and restoring force.
    locations : array_like, shape (n, 2)
        Impact points (x, y) on the string bed, m.
    ball_speed : array_like, shape (s,)
        Incoming ball speed V_Bo towards the strings, m/s.
    supports : sequence of {"free", "pinned"}
        Support conditions (eq 4 for ``pinned``).
    racket_speed : float or array_like, shape (s,)
        Speed of the racket's impact point towards the ball before impact, m/s (the paper's
        V_Ro with the sign making it add to the ball's).
    modal_model : ModalModel, None or "racket"
        Modes for eq (12); ``"racket"`` takes the racket's own (:func:`modal_model_for`);
        ``None`` is a rigid racket (no vibration loss).
    labels : sequence of str, optional
        Point labels (default 1, 2, …).
    law : RestoringForce, optional
        Compound ball+string law F_GB; default :func:`racketdyn.contact.compound_law`.
    include_string_bed : bool
        Charge string-bed (membrane) modes as vibration loss too.  Off by default: the
        compound spring already carries the string bed's deflection (section 3.4), and with the
        ball on the strings the membrane mode becomes the ball–racket mode (103 Hz in the paper,
        section 3.2) whose half period *is* the contact time, so charging it again would count
        the strings twice.

    Returns
    -------
    ImpactResult
        Arrays shaped ``(n_points, n_speeds, n_supports)``.
    """
    xy = as_locations(locations, "impact points")
    racket.head.check_inside(xy)
    support_names = tuple(one_of("support", s, SUPPORTS) for s in supports)
    if not support_names:
        raise InputError(f"support: give at least one of {', '.join(SUPPORTS)}")
    v_ball = _speeds("ball speed", ball_speed)
    v_racket = np.broadcast_to(_speeds("racket speed", racket_speed), v_ball.shape).astype(float)
    approach = v_ball + v_racket
    if np.any(approach <= 0):
        raise InputError(
            "ball speed + racket speed must be positive: the ball must reach the strings"
        )
    point_labels = (
        tuple(labels) if labels is not None else tuple(str(i + 1) for i in range(len(xy)))
    )
    if len(point_labels) != len(xy):
        raise InputError(f"{len(point_labels)} labels given for {len(xy)} impact points")
    model = modal_model_for(racket) if isinstance(modal_model, str) else modal_model
    if model is not None and not include_string_bed:
        model = model.frame_modes
    law = law or compound_law(racket, ball)

    m_b, e_bg = ball.mass_kg, ball.e_bg
    reduced = np.column_stack([racket.reduced_mass(xy, s) for s in support_names])  # (n, p)
    mu = (m_b * reduced / (m_b + reduced))[:, None, :]  # (n, 1, p)
    speed = approach[None, :, None]  # (1, s, 1)

    deflection = peak_deflection(law, (1.0 + e_bg) * speed * np.sqrt(mu) / 2.0)  # (n, s, p)
    in_range = np.isfinite(deflection)
    safe = np.where(in_range, deflection, 0.0)
    stiffness = np.where(in_range, law.stiffness(safe), np.nan)
    peak_force = np.where(in_range, law.force(safe), np.nan)  # eq (11): F_MAX = F_GB(X_p)
    mean_force = 2.0 * peak_force / np.pi
    contact_time = np.pi * np.sqrt(mu / stiffness)  # eq (7)

    if model is None:
        mode_energy = np.zeros((*deflection.shape, 0))
    else:
        phi = model.mode_shapes_at(xy)  # (n, m)
        spectrum = half_sine_spectrum(
            model.frequency, contact_time[..., None], peak_force[..., None]
        )
        mode_energy = 0.5 * (phi[:, None, None, :] * spectrum) ** 2  # ½ A_jjk |S_j(ω_k)|²
    vibration_energy = mode_energy.sum(axis=-1)

    cor_squared = e_bg**2 - 2.0 * vibration_energy / (mu * speed**2)
    valid = in_range & (cor_squared >= 0.0)
    cor = np.sqrt(np.where(valid, cor_squared, np.nan))
    mass_ratio = (m_b / reduced)[:, None, :]
    rebound_ratio = (cor - mass_ratio) / (1.0 + mass_ratio)
    rebound_speed = (
        rebound_ratio * v_ball[None, :, None] + (1.0 + rebound_ratio) * v_racket[None, :, None]
    )
    status = np.full(deflection.shape, STATUS_OK, dtype=object)
    status[in_range & ~valid] = STATUS_VIBRATION_LOSS
    status[~in_range] = STATUS_BEYOND_LAW
    for message in (STATUS_VIBRATION_LOSS, STATUS_BEYOND_LAW):
        count = int(np.sum(status == message))
        if count:
            log.warning("%d of %d impacts: %s (their results are NaN)", count, status.size, message)

    inputs: dict[str, Any] = {
        "racketdyn_version": __version__,
        "method": "approximate (Kawazoe, eqs 1-12)",
        "eq10_reading": "tangent stiffness at the peak deflection, F_MAX = F_GB(X_p)",
        "ball": {
            "mass_kg": m_b,
            "diameter_m": ball.diameter_m,
            "e_bg": e_bg,
            "restoring_force": ball.restoring_force.as_dict(),
        },
        "compound_law": law.as_dict(),
        "modal_model": None
        if model is None
        else {
            "source": model.source,
            "support": model.support,
            "modes": [
                {"name": n, "frequency_hz": float(f), "damping_ratio": float(z)}
                for n, f, z in zip(model.names, model.frequency, model.damping_ratio, strict=True)
            ],
        },
    }
    return ImpactResult(
        locations=xy,
        labels=point_labels,
        ball_speed=v_ball,
        racket_speed=v_racket,
        supports=support_names,
        reduced_mass=reduced,
        stiffness=stiffness,
        peak_deflection=deflection,
        contact_time=contact_time,
        mean_force=mean_force,
        peak_force=peak_force,
        mode_energy=mode_energy,
        vibration_energy=vibration_energy,
        cor=cor,
        rebound_ratio=rebound_ratio,
        rebound_speed=rebound_speed,
        status=status.astype(str),
        modal_model=model,
        inputs=inputs,
    )
