"""Impact of ball and racket: the paper's approximate method and its result."""

from racketdyn.impact.approximate import peak_deflection, predict
from racketdyn.impact.result import ImpactResult
from racketdyn.impact.spectrum import half_sine_force, half_sine_spectrum

__all__ = ["ImpactResult", "half_sine_force", "half_sine_spectrum", "peak_deflection", "predict"]
