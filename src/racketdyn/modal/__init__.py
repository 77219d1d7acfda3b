"""Modal analysis of any structure: models, poles, residues, shapes, MAC and identification.

Nothing here knows what a racket is; what modal results mean for a racket (the built-in beam
model, mode names from a racket's shapes) is :mod:`racketdyn.racket_modal`.  The identification
chain is :func:`racketdyn.modal.identify.identify` (imported from its module: it loads the
pole estimator).
"""

from __future__ import annotations

from racketdyn.modal.mac import mac
from racketdyn.modal.model import ModalModel
from racketdyn.modal.shapes import ModePairing, nodes_along, pair_modes

__all__ = ["ModalModel", "ModePairing", "mac", "nodes_along", "pair_modes"]
