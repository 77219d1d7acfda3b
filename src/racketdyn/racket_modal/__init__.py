"""The racket layer on top of :mod:`racketdyn.modal`: what modal results mean for a racket.

The built-in beam-and-membrane modal model of a racket (:mod:`~racketdyn.racket_modal.beam`),
mode names and kinds from a racket's shapes and the nodes along its long axis
(:mod:`~racketdyn.racket_modal.shapes`), and the identification the racket workflows call
(:func:`racketdyn.racket_modal.identify.identify_racket`).
"""

from __future__ import annotations

from racketdyn.modal.model import ModalModel
from racketdyn.racket import Racket
from racketdyn.racket_modal.beam import builtin_modal_model, hoop_roll_inertia
from racketdyn.racket_modal.identify import identify_racket, name_racket_modes
from racketdyn.racket_modal.shapes import axis_nodes, classify_modes

__all__ = [
    "axis_nodes",
    "builtin_modal_model",
    "classify_modes",
    "hoop_roll_inertia",
    "identify_racket",
    "modal_model_for",
    "name_racket_modes",
]


def modal_model_for(racket: Racket) -> ModalModel:
    """The racket's modal model: its ``modal_model_file`` if set, else the built-in beam model.

    Parameters
    ----------
    racket : Racket
        The racket.

    Returns
    -------
    ModalModel
    """
    if racket.modal_model_file is not None:
        return ModalModel.read_json(racket.modal_model_file)
    return builtin_modal_model(racket)
