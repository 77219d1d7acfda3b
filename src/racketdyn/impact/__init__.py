"""Impact of ball and racket: the paper's approximate method, the transient simulation, the
swinging racket, oblique impacts with spin, the racket's twist off the axis, and the ball fixed
on the strings (the compound system of section 3.2)."""

from racketdyn.impact.approximate import elastic_contact_time, predict, tangent_peak_deflection
from racketdyn.impact.calibration import (
    PARAMETERS,
    Calibration,
    calibrate,
    simulate_measurements,
)
from racketdyn.impact.compound import (
    BallSpring,
    CompoundSystem,
    ball_spring,
    compound_modes,
    racket_modes,
    stiffer_frame,
)
from racketdyn.impact.hand import Hand
from racketdyn.impact.measured import ModelInputs, predict_rows
from racketdyn.impact.oblique import (
    ObliqueCurve,
    ObliqueImpact,
    TangentialContact,
    oblique_curve,
    simulate_oblique,
)
from racketdyn.impact.result import ImpactResult
from racketdyn.impact.spectrum import half_sine_force, half_sine_spectrum
from racketdyn.impact.swing import Swing, SwingResult, predict_swing, sweet_spots
from racketdyn.impact.system import TRANSIENT_SUPPORTS, ImpactSystem, impact_system
from racketdyn.impact.transient import (
    TransientImpact,
    predict_transient,
    simulate_impact,
)
from racketdyn.impact.twist import TwistCurve, twist_curve

__all__ = [
    "PARAMETERS",
    "TRANSIENT_SUPPORTS",
    "BallSpring",
    "Calibration",
    "CompoundSystem",
    "Hand",
    "ImpactResult",
    "ImpactSystem",
    "ModelInputs",
    "ObliqueCurve",
    "ObliqueImpact",
    "Swing",
    "SwingResult",
    "TangentialContact",
    "TransientImpact",
    "TwistCurve",
    "ball_spring",
    "calibrate",
    "compound_modes",
    "elastic_contact_time",
    "half_sine_force",
    "half_sine_spectrum",
    "impact_system",
    "oblique_curve",
    "predict",
    "predict_rows",
    "predict_swing",
    "predict_transient",
    "racket_modes",
    "simulate_impact",
    "simulate_measurements",
    "simulate_oblique",
    "stiffer_frame",
    "sweet_spots",
    "tangent_peak_deflection",
    "twist_curve",
]
