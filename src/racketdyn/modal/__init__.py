"""Modal models: natural frequencies, damping and mass-normalised mode shapes of a racket."""

from __future__ import annotations

from racketdyn.modal.beam import builtin_modal_model
from racketdyn.modal.model import ModalModel
from racketdyn.racket import Racket

__all__ = ["ModalModel", "builtin_modal_model", "modal_model_for"]


def modal_model_for(racket: Racket) -> ModalModel:
    """The racket's modal model: its ``modal_model_file`` if set, else the built-in beam model."""
    if racket.modal_model_file is not None:
        return ModalModel.read_json(racket.modal_model_file)
    return builtin_modal_model(racket)
