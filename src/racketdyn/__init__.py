"""racketdyn: tennis racket impact dynamics, from modal models to rebound ball speed.

The core objects follow the data: a :class:`Racket` (mass properties, head, strings), a
:class:`Ball`, a :class:`ModalModel`, and the :class:`ImpactResult` that :func:`predict` returns
(Kawazoe's approximate method).  SI units throughout: attributes take the glossary's bare names
(``result.contact_time``, s); file columns, dataset variables and data-frame columns carry the
unit (``contact_time_s``), see :data:`racketdyn.impact.result.IMPACT_QUANTITIES`.
"""

from racketdyn.__about__ import __version__
from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law, string_bed_law
from racketdyn.errors import InputError
from racketdyn.impact import ImpactResult, predict
from racketdyn.io import default_racket, load_racket
from racketdyn.modal import ModalModel
from racketdyn.racket import HeadEllipse, MassProperties, PointMass, Racket, StringBed
from racketdyn.racket_modal import builtin_modal_model, modal_model_for

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
