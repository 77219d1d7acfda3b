"""Impact of ball and racket: the paper's approximate method and its result."""

from racketdyn.impact.approximate import elastic_contact_time, predict, tangent_peak_deflection
from racketdyn.impact.result import ImpactResult
from racketdyn.impact.spectrum import half_sine_force, half_sine_spectrum

__all__ = [
    "ImpactResult",
    "elastic_contact_time",
    "half_sine_force",
    "half_sine_spectrum",
    "predict",
    "tangent_peak_deflection",
]
