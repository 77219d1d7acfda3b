"""Ball–string contact: the string-bed restoring force and the compound ball+string spring.

The compound spring F_GB(X) is the ball's one-sided law and the string bed's law in series
(paper, section 3.4), fitted by least squares; its fit residual is reported with it.
"""

from __future__ import annotations

from racketdyn.ball import Ball, RestoringForce, series
from racketdyn.io.tables import read_load_deflection
from racketdyn.racket import Racket

__all__ = ["compound_law", "string_bed_law"]

STRING_BED_MAX_DEFLECTION_M = 0.05
"""Range of the model string-bed law: 50 mm, beyond the deepest string-bed deflection of play."""


def string_bed_law(racket: Racket, ball: Ball) -> RestoringForce:
    """String-bed restoring force F_G(X) at the centre of the face, N for X in m.

    A measured load–deflection file on the racket (``strings.load_deflection_file``) is fitted
    by least squares (cubic polynomial).  Otherwise Kawazoe's law for a string of half-length L
    under tension S0 stretched by a transverse deflection X,
    ``F = 2 S0 X / L + A E X³ / L³`` (stiffness ``2 S0/L + 3 A E X²/L³``, REFERENCE_VALUES.md),
    is summed over the strings the ball presses on: ball diameter / string spacing of the mains
    (half-length = head half-length) and of the crosses (half-length = head half-width).
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
        linear += engaged * 2.0 * strings.tension_n / half_length
        cubic += engaged * strings.axial_stiffness_n / half_length**3
    return RestoringForce(
        "polynomial",
        (linear, 0.0, cubic),
        STRING_BED_MAX_DEFLECTION_M,
        0.0,
        f"string bed, Kawazoe law at {strings.tension_n:g} N",
    )


def compound_law(racket: Racket, ball: Ball, degree: int = 5) -> RestoringForce:
    """Compound ball+string restoring force F_GB(X): the two laws in series, least-squares fit.

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
    )
