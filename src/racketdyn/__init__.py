"""racketdyn: tennis racket impact dynamics, from modal models to rebound ball speed.

The core objects follow the data: a :class:`Racket` (mass properties, head, strings), a
:class:`Ball`, a :class:`ModalModel`, and the :class:`ImpactResult` that :func:`predict` returns
(Kawazoe's approximate method).  SI units throughout: attributes take the glossary's bare names
(``result.contact_time``, s); file columns, dataset variables and data-frame columns carry the
unit (``contact_time_s``), see :data:`racketdyn.impact.result.IMPACT_QUANTITIES`.

The names below are loaded when first used (Scientific Python SPEC 1: a module
``__getattr__`` and ``__dir__``).  ``import racketdyn`` therefore costs almost nothing, and the
command line (``racketdyn --help``) does not wait for SciPy, numba and NumPy to load;
``rd.predict``, ``rd.Ball``, ``rd.default_racket`` … work as before, importing their module on
first access.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from racketdyn.__about__ import __version__

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, imported eagerly
    from racketdyn.ball import Ball, RestoringForce
    from racketdyn.contact import compound_law, string_bed_law
    from racketdyn.errors import InputError
    from racketdyn.impact import ImpactResult, predict
    from racketdyn.io import default_racket, load_racket
    from racketdyn.modal import ModalModel
    from racketdyn.racket import HeadEllipse, MassProperties, PointMass, Racket, StringBed
    from racketdyn.racket_modal import builtin_modal_model, modal_model_for

_WHERE = {
    "Ball": "racketdyn.ball",
    "HeadEllipse": "racketdyn.racket",
    "ImpactResult": "racketdyn.impact",
    "InputError": "racketdyn.errors",
    "MassProperties": "racketdyn.racket",
    "ModalModel": "racketdyn.modal",
    "PointMass": "racketdyn.racket",
    "Racket": "racketdyn.racket",
    "RestoringForce": "racketdyn.ball",
    "StringBed": "racketdyn.racket",
    "builtin_modal_model": "racketdyn.racket_modal",
    "compound_law": "racketdyn.contact",
    "default_racket": "racketdyn.io",
    "load_racket": "racketdyn.io",
    "modal_model_for": "racketdyn.racket_modal",
    "predict": "racketdyn.impact",
    "string_bed_law": "racketdyn.contact",
}

__all__ = [
    "Ball",
    "HeadEllipse",
    "ImpactResult",
    "InputError",
    "MassProperties",
    "ModalModel",
    "PointMass",
    "Racket",
    "RestoringForce",
    "StringBed",
    "__version__",
    "builtin_modal_model",
    "compound_law",
    "default_racket",
    "load_racket",
    "modal_model_for",
    "predict",
    "string_bed_law",
]


def __getattr__(name: str) -> Any:
    """Import the module that defines ``name`` on first use (SPEC 1 lazy loading)."""
    if name in _WHERE:
        value = getattr(importlib.import_module(_WHERE[name]), name)
        globals()[name] = value  # later look-ups skip this function
        return value
    raise AttributeError(f"module 'racketdyn' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
