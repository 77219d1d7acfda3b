"""The virtual test rig: a racket model that stands in for a real one in a roving-hammer test.

:func:`rig_model` builds the structure (beam frame, coupled string bed, free or hand-held) and
its modal truth; :func:`simulate_hammer_test` makes the records a roving-hammer test would give.
"""

from racketdyn.rig.hammer import (
    accelerometer_index,
    anti_alias_filter,
    hammer_points,
    simulate_hammer_test,
    string_contact_time,
)
from racketdyn.rig.model import HandModel, RigModel, RigSupport, rig_model

__all__ = [
    "HandModel",
    "RigModel",
    "RigSupport",
    "accelerometer_index",
    "anti_alias_filter",
    "hammer_points",
    "rig_model",
    "simulate_hammer_test",
    "string_contact_time",
]
