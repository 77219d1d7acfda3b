"""The virtual test rig: a racket model that stands in for a real one in a roving-hammer test.

:func:`rig_model` builds the structure (beam frame, coupled string bed, free or hand-held) and
its modal truth; :func:`simulate_hammer_test` makes the records a roving-hammer test would give,
set by :class:`Acquisition`, :class:`HammerBlows`, :class:`SensorNoise` and :class:`HammerFaults`.

Submodules are imported when first used (SPEC 1): importing one of them, or this package,
does not load the others.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from racketdyn.rig.hammer import (
        Acquisition,
        HammerBlows,
        HammerFaults,
        SensorNoise,
        accelerometer_index,
        anti_alias_filter,
        hammer_points,
        simulate_hammer_test,
        string_contact_time,
    )
    from racketdyn.rig.model import HandModel, RigModel, RigSupport, rig_model

_WHERE = {
    "Acquisition": "hammer",
    "HammerBlows": "hammer",
    "HammerFaults": "hammer",
    "SensorNoise": "hammer",
    "HandModel": "model",
    "RigModel": "model",
    "RigSupport": "model",
    "accelerometer_index": "hammer",
    "anti_alias_filter": "hammer",
    "hammer_points": "hammer",
    "rig_model": "model",
    "simulate_hammer_test": "hammer",
    "string_contact_time": "hammer",
}

__all__ = [
    "Acquisition",
    "HammerBlows",
    "HammerFaults",
    "HandModel",
    "RigModel",
    "RigSupport",
    "SensorNoise",
    "accelerometer_index",
    "anti_alias_filter",
    "hammer_points",
    "rig_model",
    "simulate_hammer_test",
    "string_contact_time",
]


def __getattr__(name: str) -> Any:
    if name in _WHERE:
        return getattr(importlib.import_module(f"racketdyn.rig.{_WHERE[name]}"), name)
    raise AttributeError(f"module 'racketdyn.rig' has no attribute {name!r}")


def __dir__() -> list[str]:
    return __all__
