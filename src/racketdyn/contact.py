"""Ball–string contact: the string-bed restoring force and the compound ball+string spring.

The compound spring F_GB(X) is the ball's one-sided law and the string bed's law in series
(paper, section 3.4), fitted by least squares; its fit residual is reported with it.
"""

from __future__ import annotations

import math
from dataclasses import replace
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import Ball, RestoringForce, series
from racketdyn.errors import InputError
from racketdyn.io.tables import read_load_deflection
from racketdyn.numerics import invert_increasing
from racketdyn.racket import Racket

__all__ = [
    "CROSS_DROP_E_BG",
    "CROSS_DROP_SPEED_MPS",
    "E_BG_SPEEDS_MPS",
    "ball_string_cor",
    "clamped_bounce",
    "compound_law",
    "local_compound_law",
    "local_string_bed_law",
    "membrane_patch_radius",
    "membrane_patch_stiffness",
    "net_share",
    "string_bed_cor",
    "string_bed_law",
    "string_tension",
    "with_ball_string_cor",
]

STRING_BED_MAX_DEFLECTION_M = 0.08
"""Range of the model string-bed law: 80 mm.  A 70 m/s impact at the centre of the paper's
racket deflects the bed ≈ 55 mm (the ball then carries ≈ 5 kN); 80 mm (≈ 14 kN) leaves the
compound law room beyond 70 m/s.  The law itself has no end of its own: it is a string
stretched by its own transverse deflection (Kawazoe), its stiffness rising as the string
elongates; its physical end is the string's strength (:func:`string_tension`)."""
COMPOUND_DEGREE = 9
"""Degree of the compound law's polynomial: the law spans ≈ 0.1 to 14 kN, so it is fitted on
the relative residual with the degree the ball law has."""


def string_bed_law(racket: Racket, ball: Ball) -> RestoringForce:
    """String-bed restoring force F_G(X) at the centre of the face, N for X in m.

    A measured load–deflection file on the racket (``strings.load_deflection_file``) is fitted
    by least squares (cubic polynomial).  Otherwise Kawazoe's law for a string of half-length L
    under tension S0 stretched by a transverse deflection X,
    ``F = 2 S0 X / L + A E X³ / L³`` (stiffness ``2 S0/L + 3 A E X²/L³``, docs/references.md,
    "Strings"), is summed over the strings the ball presses on: ball diameter / string spacing
    of the mains (half-length = head half-length) and of the crosses (half-length = head
    half-width).  The cubic term is the string's own elongation: a string deflected by X over a
    half-length L stretches by ≈ X²/(2L), its tension rising to ``S0 + A E X²/(2L²)``
    (:func:`string_tension`), so the law stays the physics of a stretched string to the 80 mm
    of its range; at 70 m/s the crosses of the paper's racket carry ≈ 0.9 kN each.
    """
    strings = racket.strings
    if strings.load_deflection_file is not None:
        deflection, force = read_load_deflection(strings.load_deflection_file)
        return RestoringForce.fit(
            deflection,
            force,
            "polynomial",
            3,
            f"string bed, fitted to {strings.load_deflection_file.name}",
        )
    spacing_mains, spacing_crosses = strings.spacing_m(racket.head)
    linear = 0.0
    cubic = 0.0
    for spacing, half_length in (
        (spacing_mains, racket.head.half_length_m),
        (spacing_crosses, racket.head.half_width_m),
    ):
        engaged = ball.diameter_m / spacing
        linear += engaged * 2.0 * strings.bed_tension_n / half_length
        cubic += engaged * strings.axial_stiffness_n / half_length**3
    return RestoringForce(
        "polynomial",
        (linear, 0.0, cubic),
        STRING_BED_MAX_DEFLECTION_M,
        0.0,
        f"string bed, Kawazoe law at {strings.bed_tension_n:g} N in the bed",
    )


def string_tension(
    racket: Racket, deflection: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Tension of a main and of a cross string at the centre deflected by X, N.

    ``S = S0 + A E X² / (2 L²)`` with S0 the tension in the bed
    (:attr:`~racketdyn.racket.StringBed.bed_tension_n`) and L the string's half-length (the
    elongation behind the cubic term of :func:`string_bed_law`).  Divide by the string's
    cross-section for the stress.

    Parameters
    ----------
    racket : Racket
        Strings (S0, A E) and head (half-lengths).
    deflection : array_like
        String-bed deflection X at the centre, m.

    Returns
    -------
    mains, crosses : ndarray
        Tension of a main string and of a cross string, N.
    """
    x = np.asarray(deflection, dtype=float)
    strings = racket.strings
    tensions = [
        strings.bed_tension_n + strings.axial_stiffness_n * x**2 / (2.0 * half**2)
        for half in (racket.head.half_length_m, racket.head.half_width_m)
    ]
    return np.asarray(tensions[0]), np.asarray(tensions[1])


def membrane_patch_stiffness(racket: Racket, patch_radius_m: float) -> float:
    """Small-deflection stiffness of the string bed as a net under a rigid round patch, N/m.

    :func:`string_bed_law` counts only the strings under the ball, each pushed on its own: the
    crosses beside the ball, lifted by the mains they cross, pull back on them too, and that
    law leaves it out.  Here the bed is the continuum of a string net (a cable net): tension
    per unit width ``T_x = S0 / s_mains`` along x and ``T_y = S0 / s_crosses`` along y, its
    deflection w obeying ``T_x w_xx + T_y w_yy = 0`` between the head ellipse (w = 0) and a
    rigid round patch of radius a at the centre (w = X).  Stretching x by ``√T_x`` and y by
    ``√T_y`` makes the net isotropic with tension ``√(T_x T_y)``; head and patch become
    ellipses, and for confocal ellipses the stiffness is exact:

        ``k = 2π √(T_x T_y) / ln(Λ / λ)``,  ``Λ = A/√T_x + B/√T_y``,
        ``λ = a (1/√T_x + 1/√T_y)``

    (the two ellipses' sums of half-axes; A, B the head's half-axes).  Ours are nearly
    confocal: a finite-difference solution of the same net agrees within 2 % for
    a = 5–34 mm (``tests/test_compound.py``).  The stiffness grows as the patch widens, and
    the linear stretching term of the net only (no elongation of the strings: small X).

    Parameters
    ----------
    racket : Racket
        Head half-axes, string tension S0 and spacings (:meth:`Strings.spacing_m`).
    patch_radius_m : float
        Radius of the patch that pushes the bed, m; smaller than the head's half-width.

    Returns
    -------
    float
        Stiffness dF/dX at small X, N/m.
    """
    tension, outer, inner_per_radius = _net(racket)
    _check_patch(racket, patch_radius_m)
    return 2.0 * math.pi * tension / math.log(outer / (patch_radius_m * inner_per_radius))


def membrane_patch_radius(racket: Racket, stiffness_n_per_m: float) -> float:
    """The patch radius whose :func:`membrane_patch_stiffness` is ``stiffness_n_per_m``, m.

    NaN when no patch inside the head's half-width has it.
    """
    tension, outer, inner_per_radius = _net(racket)
    if not stiffness_n_per_m > 0.0:
        return math.nan
    radius = outer / math.exp(2.0 * math.pi * tension / stiffness_n_per_m) / inner_per_radius
    return radius if 0.0 < radius < racket.head.half_width_m else math.nan


def net_share(racket: Racket, patch_radius_m: float, distance_m: float) -> float:
    """Share of a point force on the string net that a held patch takes, 0–1.

    By reciprocity (Betti) the force a held patch (radius a, at the head's centre) takes from a
    unit force at a point of the net equals the net's deflection there when the patch alone is
    displaced by a unit: in the net of :func:`membrane_patch_stiffness`,
    ``ln(Λ/(r κ)) / ln(Λ/(a κ))`` with κ = 1/√T_x + 1/√T_y, r the point's distance from the
    patch centre (the patch's own circles are the net's level lines in this approximation);
    1 on the patch, 0 at the head's edge.  The rest of the force goes to the frame through the
    strings.  The patch is taken at the centre wherever the ball sits: near the frame the
    share is over-estimated (an image-method estimate for a ball 35 mm from the rim: 0.82
    against 0.87; review, 2026-11-26).

    Parameters
    ----------
    racket : Racket
        Head and strings.
    patch_radius_m : float
        Radius of the held patch, m.
    distance_m : float
        Distance of the force from the patch centre, m.

    Returns
    -------
    float
    """
    _, outer, inner_per_radius = _net(racket)
    _check_patch(racket, patch_radius_m)
    if distance_m <= patch_radius_m:
        return 1.0
    share = math.log(outer / (distance_m * inner_per_radius)) / math.log(
        outer / (patch_radius_m * inner_per_radius)
    )
    return min(max(share, 0.0), 1.0)


def _check_patch(racket: Racket, patch_radius_m: float) -> None:
    if not 0.0 < patch_radius_m < racket.head.half_width_m:
        raise InputError(
            f"patch radius {patch_radius_m:g} m: must lie between 0 and the head's half-width "
            f"{racket.head.half_width_m:g} m"
        )


def _net(racket: Racket) -> tuple[float, float, float]:
    """√(T_x T_y), Λ and λ/a of :func:`membrane_patch_stiffness`."""
    head, strings = racket.head, racket.strings
    spacing_mains, spacing_crosses = strings.spacing_m(head)
    root_x = math.sqrt(strings.bed_tension_n / spacing_mains)
    root_y = math.sqrt(strings.bed_tension_n / spacing_crosses)
    outer = head.half_length_m / root_x + head.half_width_m / root_y
    return root_x * root_y, outer, 1.0 / root_x + 1.0 / root_y


def compound_law(racket: Racket, ball: Ball, degree: int = COMPOUND_DEGREE) -> RestoringForce:
    """Compound ball+string restoring force F_GB(X): the two laws in series, least-squares fit
    on the relative force residual (section 3.4).

    Parameters
    ----------
    racket, ball : Racket, Ball
        The string bed comes from the racket, the ball law from the ball.
    degree : int
        Degree of the fitted polynomial (no constant term).
    """
    return series(
        ball.restoring_force,
        string_bed_law(racket, ball),
        "polynomial",
        degree,
        "ball + string bed in series",
        relative=True,
    )


def _stretched_string(
    tension_n: float, axial_n: float, near: float, far: float
) -> tuple[float, float]:
    """Linear and cubic coefficients of one string of ends ``near`` and ``far`` (m) from the
    point it is pressed at: ``F = S0 k X + A E k² X³ / (2 (l1 + l2))`` with
    ``k = 1/l1 + 1/l2`` (Kawazoe's ``2 S0 X/L + A E X³/L³`` for l1 = l2 = L)."""
    k = 1.0 / near + 1.0 / far
    return tension_n * k, axial_n * k * k / (2.0 * (near + far))


def local_string_bed_law(
    racket: Racket, ball: Ball, location: ArrayLike, samples: int = 1
) -> RestoringForce:
    """String-bed restoring force F_G(X) at a point of the face, N for X in m.

    Kawazoe's stretched-string law (:func:`string_bed_law`) with each string's own geometry:
    a string of tension S0 pressed at distances l1 and l2 from its ends pushes back with
    ``S0 (1/l1 + 1/l2) X``; deflected by X it lengthens by ``X² (1/l1 + 1/l2)/2`` and its
    tension rises by A E times that over ``l1 + l2``, the cubic term
    ``A E (1/l1 + 1/l2)² X³ / (2 (l1 + l2))``.  The mains run along x between the head's
    outline at their y, the crosses along y between the outline at their x; as in
    :func:`string_bed_law` the ball presses ``diameter / spacing`` of each.  With
    ``samples = 1`` those strings are taken as the main and the cross through the point (at
    the centre of the face: :func:`string_bed_law` exactly); with more, at ``samples`` evenly
    spread positions across the ball's diameter, each with its own length (a string beyond
    the outline is not there).  Near the frame the shorter strings make the bed stiffer.
    A string end closer to the point than the ball's radius is taken at the ball's radius:
    the ball cannot bend a string over less than its own half-width.

    Parameters
    ----------
    racket : Racket
        Head outline and strings (tension, counts, gauge, modulus).
    ball : Ball
        Its diameter sets the strings pressed.
    location : array_like (2,)
        Impact point (x, y), m.
    samples : int
        Positions across the ball's diameter at which strings are taken.

    Returns
    -------
    RestoringForce
        Polynomial ``(linear, 0, cubic)`` over the 80 mm of :func:`string_bed_law`.
    """
    strings, head = racket.strings, racket.head
    if strings.load_deflection_file is not None:
        raise InputError(
            "local string-bed law: the racket's string bed is a measured load–deflection file "
            f"({strings.load_deflection_file.name}), a law at one point; a law at every point "
            "needs the strings' construction ([strings] tension_n, mains, crosses, gauge)"
        )
    x, y = (float(v) for v in np.asarray(location, dtype=float).reshape(2))
    if not bool(head.contains([(x, y)])[0]):
        raise InputError(f"local string-bed law: the point x={x:g} m, y={y:g} m is off the bed")
    spacing_mains, spacing_crosses = strings.spacing_m(head)
    radius = 0.5 * ball.diameter_m
    offsets = (
        ((np.arange(samples) + 0.5) / samples - 0.5) * ball.diameter_m if samples > 1 else [0.0]
    )
    linear = cubic = 0.0
    a, b = head.half_length_m, head.half_width_m
    for offset in offsets:
        # a main at y + offset, from x0 to x1; a cross at x + offset, from y0 to y1
        for along, across, half_axis, other_axis, centre, other_centre, spacing in (
            (x, y + offset, a, b, head.centre_x_m, head.centre_y_m, spacing_mains),
            (y, x + offset, b, a, head.centre_y_m, head.centre_x_m, spacing_crosses),
        ):
            ratio = (across - other_centre) / other_axis
            if abs(ratio) >= 1.0:
                continue
            half = half_axis * math.sqrt(1.0 - ratio**2)
            near = max(along - (centre - half), radius)
            far = max(centre + half - along, radius)
            lin, cub = _stretched_string(
                strings.bed_tension_n, strings.axial_stiffness_n, near, far
            )
            weight = ball.diameter_m / spacing / len(offsets)
            linear += weight * lin
            cubic += weight * cub
    return RestoringForce(
        "polynomial",
        (linear, 0.0, cubic),
        STRING_BED_MAX_DEFLECTION_M,
        0.0,
        f"string bed at x={x:.4f} m, y={y:.4f} m, Kawazoe law per string at "
        f"{strings.bed_tension_n:g} N in the bed",
    )


def local_compound_law(
    racket: Racket, ball: Ball, location: ArrayLike, samples: int = 1
) -> RestoringForce:
    """Compound ball + string law at a point: :func:`local_string_bed_law` in series with the
    ball, fitted as :func:`compound_law` does."""
    return series(
        ball.restoring_force,
        local_string_bed_law(racket, ball, location, samples),
        "polynomial",
        COMPOUND_DEGREE,
        "ball + local string bed in series",
        relative=True,
    )


# --- the ball's bounce on the strings: e_BG from the ball and the strings ------------------------
CROSS_DROP_SPEED_MPS = 4.43
"""A ball dropped 1 m onto a head-clamped string bed meets it at 4.43 m/s and bounces to
≈ 0.70 m: e_BG ≈ 0.84 (Cross, "The physics of tennis", University of Sydney; docs/references.md,
"The ball in a bounce")."""
CROSS_DROP_E_BG = 0.84
E_BG_SPEEDS_MPS = (0.5, 1.0, 2.0, 3.0, 4.43, 6.0, 8.0, 10.0, 12.5, 15.0, 20.0, 25.0, 30.0,
                   35.0, 40.0, 45.0, 50.0, 55.0, 60.0, 65.0, 70.0)  # fmt: skip
"""Relative speeds at which :func:`with_ball_string_cor` tabulates e_BG, m/s (linear between)."""


def clamped_bounce(racket: Racket, ball: Ball, speed: ArrayLike) -> dict[str, NDArray[np.float64]]:
    """The ball's bounce on the head-clamped string bed at the face centre, at its turn.

    The ball (mass m_B) stops with its kinetic energy ½ m_B V² held by the ball's law and the
    bed's law in series (section 3.4): the common force F solves
    ``E_B(X_B(F)) + E_G(X_G(F)) = ½ m_B V²``.

    Parameters
    ----------
    racket, ball : Racket, Ball
        The string bed (:func:`string_bed_law`) and the ball's law.
    speed : array_like
        Impact speed V, m/s.

    Returns
    -------
    dict
        ``force`` (N), ``ball_compression`` X_B and ``bed_deflection`` X_G (m), and the
        energies ``ball_energy`` E_B and ``bed_energy`` E_G (J), each shaped like ``speed``;
        NaN beyond the laws' range.
    """
    ball_law, bed = ball.restoring_force, string_bed_law(racket, ball)

    def stored(force: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(
            ball_law.energy(ball_law.deflection(force)) + bed.energy(bed.deflection(force))
        )

    def d_stored(force: NDArray[np.float64]) -> NDArray[np.float64]:
        # dE/dF = F dX/dF = F / K for each spring of the pair (dE/dX = F)
        x_b, x_g = ball_law.deflection(force), bed.deflection(force)
        return np.asarray(force / ball_law.stiffness(x_b) + force / bed.stiffness(x_g))

    kinetic = 0.5 * ball.mass_kg * np.asarray(speed, dtype=float) ** 2
    top = min(ball_law.max_force_n, bed.max_force_n)
    f = invert_increasing(stored, d_stored, kinetic, top)
    x_b, x_g = ball_law.deflection(f), bed.deflection(f)
    return {
        "force": f,
        "ball_compression": np.asarray(x_b),
        "bed_deflection": np.asarray(x_g),
        "ball_energy": np.asarray(ball_law.energy(x_b)),
        "bed_energy": np.asarray(bed.energy(x_g)),
    }


@lru_cache(maxsize=1)
def string_bed_cor() -> float:
    """The string bed's own energy return under a ball, as a COR e_S (its share e_S² of what
    it stores comes back), ≈ 0.865.

    Solved so that the built-in ball (its own COR 0.745 on a rigid surface, ITF) on the paper's
    racket bounces from Cross's 1 m drop with e_BG = 0.84 (:data:`CROSS_DROP_SPEED_MPS`,
    :data:`CROSS_DROP_E_BG`; :func:`ball_string_cor` solved for e_S): a measurement of a ball on
    clamped strings, not of a racket's rebound.  It then fixes e_BG at every other speed and
    tension.  Strings struck by a rigid impactor return ≈ 0.97 (docs/references.md,
    "Strings"); under a ball they also rub on one another and on the ball's cloth.
    """
    from racketdyn.io.racket_file import default_racket

    # The energies at the turn do not depend on e_S, so the defining equation of
    # :func:`ball_string_cor`, e_BG² (E_B + E_G) = e_B² E_B + e_S² E_G, gives e_S directly.
    ball = Ball()
    bounce = clamped_bounce(default_racket(), ball, CROSS_DROP_SPEED_MPS)
    e_b, e_g = float(bounce["ball_energy"]), float(bounce["bed_energy"])
    squared = (CROSS_DROP_E_BG**2 * (e_b + e_g) - ball.rigid_cor**2 * e_b) / e_g
    if not (e_g > 0.0 and ball.rigid_cor**2 <= squared <= 1.0):
        raise ValueError(f"no string-bed COR in [e_B, 1] bounces Cross's drop (e_S² {squared})")
    return math.sqrt(squared)


def ball_string_cor(
    racket: Racket, ball: Ball, speed: ArrayLike, string_cor: float | None = None
) -> NDArray[np.float64]:
    """e_BG of the ball on the head-clamped string bed at impact speeds, from ball + strings.

    At the turn the ball holds E_B and the bed E_G (:func:`clamped_bounce`).  Each gives back
    its own share: the ball ``e_B² E_B`` with e_B its COR on a rigid surface (``ball.rigid_cor``,
    ITF), the bed ``e_S² E_G`` (:func:`string_bed_cor`), so

        ``e_BG² = (e_B² E_B + e_S² E_G) / (E_B + E_G)``.

    A stiffer bed (higher tension, a faster impact on the stiffening bed) leaves more of the
    energy in the lossier ball, so e_BG falls slowly with speed and tension (Haake, Carré and
    Goodwill 2003; Vallatta, Casolo and Caffi), ≈ 0.84 → 0.82 from 4 to 40 m/s on the paper's
    racket: "almost independent of speed and tension", as Kawazoe measured.

    Parameters
    ----------
    racket, ball : Racket, Ball
    speed : array_like
        Impact (relative) speed, m/s.
    string_cor : float, optional
        e_S of the bed (default :func:`string_bed_cor`).

    Returns
    -------
    ndarray
        e_BG, shaped like ``speed``; NaN beyond the laws' range.
    """
    e_s = string_bed_cor() if string_cor is None else string_cor
    bounce = clamped_bounce(racket, ball, speed)
    e_b, e_g = bounce["ball_energy"], bounce["bed_energy"]
    with np.errstate(invalid="ignore", divide="ignore"):
        squared = (ball.rigid_cor**2 * e_b + e_s**2 * e_g) / (e_b + e_g)
    return np.asarray(np.sqrt(squared))


def with_ball_string_cor(racket: Racket, ball: Ball) -> Ball:
    """The ball with e_BG resolved: itself if e_BG was given, else a table from ball + strings.

    The table (:data:`E_BG_SPEEDS_MPS`, :func:`ball_string_cor` at the face centre's bed) is what
    both impact models read at each impact's relative speed (``Ball.e_bg_at``); ``e_bg`` is set
    to its value at 20 m/s for the few places that take one number.
    """
    if ball.e_bg_given:
        return ball
    return _resolved(racket, ball)


@lru_cache(maxsize=64)  # every impact call resolves its ball; racket and ball are frozen
def _resolved(racket: Racket, ball: Ball) -> Ball:
    speeds = np.asarray(E_BG_SPEEDS_MPS)
    cor = ball_string_cor(racket, ball, speeds)
    keep = np.isfinite(cor)
    if not np.any(keep):
        raise InputError(
            "e_BG from ball + strings: the laws hold no bounce; give `e_bg` (measured)"
        )
    table = tuple((float(v), float(e)) for v, e in zip(speeds[keep], cor[keep], strict=True))
    return replace(
        ball,
        e_bg=float(np.interp(20.0, speeds[keep], cor[keep])),
        e_bg_table=table,
        e_bg_source=(
            f"ball + strings: ball COR {ball.rigid_cor:g} on a rigid surface, string bed "
            f"{string_bed_cor():.4g} (e_BG² = (e_B² E_B + e_S² E_G)/(E_B + E_G)), at the face "
            "centre"
        ),
    )
