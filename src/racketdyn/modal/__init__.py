"""Modal analysis of any structure: models, poles, residues, shapes, MAC and identification.

Nothing here knows what a racket is; what modal results mean for a racket (the built-in beam
model, mode names from a racket's shapes) is :mod:`racketdyn.racket_modal`.

The chain, usable on any structure's FRFs (:class:`racketdyn.measurement.FrfSet`):

- :func:`identify` — band, poles, selection, residues, mass normalisation in one call,
  returning every intermediate result (:class:`Identification`);
- :func:`stabilisation` and :func:`select_poles` — LSCF poles of every model order and the
  automatic choice of the physical ones by :class:`SelectionRules` (:class:`Stabilisation`,
  :class:`SelectedPoles`); :func:`poly_stabilisation` — the poly-reference LSCF of FRFs
  against several references (:class:`racketdyn.measurement.records.FrfReferences`);
- :func:`fit_modal_constants` and :func:`mass_normalised_shapes` — LSFD modal constants with
  residuals, and mode shapes scaled from the driving point (:class:`ModalFit`);
- :func:`misfit` — where a fit misses its FRFs and what that says, the verdict on the fit
  error (:class:`Misfit`; :attr:`Identification.misfit`);
- :class:`ModalModel`, :func:`mac`, :func:`nodes_along`, :func:`pair_modes`.

The names ``racketdyn.modal.identify`` and ``racketdyn.modal.misfit`` are the functions; their
modules' other names import as before (``from racketdyn.modal.identify import default_band``).
:mod:`racketdyn.testing` has structures with known modes to try the chain on.
"""

from __future__ import annotations

from racketdyn.modal.identify import Identification, default_band, identify
from racketdyn.modal.mac import mac
from racketdyn.modal.misfit import Misfit, misfit
from racketdyn.modal.model import ModalModel
from racketdyn.modal.poles import (
    SelectedPoles,
    SelectionRules,
    Stabilisation,
    select_poles,
    stabilisation,
)
from racketdyn.modal.polyreference import poly_stabilisation
from racketdyn.modal.residues import ModalFit, fit_modal_constants, mass_normalised_shapes
from racketdyn.modal.shapes import ModePairing, nodes_along, pair_modes

__all__ = [
    "Identification",
    "Misfit",
    "ModalFit",
    "ModalModel",
    "ModePairing",
    "SelectedPoles",
    "SelectionRules",
    "Stabilisation",
    "default_band",
    "fit_modal_constants",
    "identify",
    "mac",
    "mass_normalised_shapes",
    "misfit",
    "nodes_along",
    "pair_modes",
    "poly_stabilisation",
    "select_poles",
    "stabilisation",
]
