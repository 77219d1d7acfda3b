"""Impact of ball and racket: the paper's approximate method, the transient simulation, the
swinging racket, oblique impacts with spin, the racket's twist off the axis, and the ball fixed
on the strings (the compound system of section 3.2).

Submodules are imported when first used (SPEC 1): importing one of them, or this package,
does not load the others.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from racketdyn.impact.approximate import elastic_contact_time, predict, tangent_peak_deflection
    from racketdyn.impact.bounce import BallBounces, ball_bounces
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
    from racketdyn.impact.compound_band import (
        BallModeBand,
        BedForFrequency,
        ball_mode_band,
        bed_for_frequency,
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

_WHERE = {
    "BallBounces": "bounce",
    "ball_bounces": "bounce",
    "BallModeBand": "compound_band",
    "BedForFrequency": "compound_band",
    "ball_mode_band": "compound_band",
    "bed_for_frequency": "compound_band",
    "BallSpring": "compound",
    "Calibration": "calibration",
    "CompoundSystem": "compound",
    "Hand": "hand",
    "ImpactResult": "result",
    "ImpactSystem": "system",
    "ModelInputs": "measured",
    "ObliqueCurve": "oblique",
    "ObliqueImpact": "oblique",
    "PARAMETERS": "calibration",
    "Swing": "swing",
    "SwingResult": "swing",
    "TRANSIENT_SUPPORTS": "system",
    "TangentialContact": "oblique",
    "TransientImpact": "transient",
    "TwistCurve": "twist",
    "ball_spring": "compound",
    "calibrate": "calibration",
    "compound_modes": "compound",
    "elastic_contact_time": "approximate",
    "half_sine_force": "spectrum",
    "half_sine_spectrum": "spectrum",
    "impact_system": "system",
    "oblique_curve": "oblique",
    "predict": "approximate",
    "predict_rows": "measured",
    "predict_swing": "swing",
    "predict_transient": "transient",
    "racket_modes": "compound",
    "simulate_impact": "transient",
    "simulate_measurements": "calibration",
    "simulate_oblique": "oblique",
    "stiffer_frame": "compound",
    "sweet_spots": "swing",
    "tangent_peak_deflection": "approximate",
    "twist_curve": "twist",
}

__all__ = [
    "PARAMETERS",
    "TRANSIENT_SUPPORTS",
    "BallBounces",
    "BallModeBand",
    "BallSpring",
    "BedForFrequency",
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
    "ball_bounces",
    "ball_mode_band",
    "ball_spring",
    "bed_for_frequency",
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


def __getattr__(name: str) -> Any:
    if name in _WHERE:
        return getattr(importlib.import_module(f"racketdyn.impact.{_WHERE[name]}"), name)
    raise AttributeError(f"module 'racketdyn.impact' has no attribute {name!r}")


def __dir__() -> list[str]:
    return __all__
