"""The racket layer on top of :mod:`racketdyn.modal`: what modal results mean for a racket.

The built-in beam-and-membrane modal model of a racket (:mod:`~racketdyn.racket_modal.beam`),
the beam held in a hand (:mod:`~racketdyn.racket_modal.grip`), mode names and kinds from a
racket's shapes and the nodes along its long axis (:mod:`~racketdyn.racket_modal.shapes`), and
the identification the racket workflows call
(:func:`racketdyn.racket_modal.identify.identify_racket`).
"""

from __future__ import annotations

import math

import numpy as np

from racketdyn.errors import InputError
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
        model = ModalModel.read_json(racket.modal_model_file)
        check_on_racket(model, racket, str(racket.modal_model_file))
        return model
    return builtin_modal_model(racket)


FIRST_MODE_HZ = (80.0, 250.0)
"""Where a racket's first bending mode lies (``plausibility.RANGES["first_bending_hz"]``)."""
SHAPE_LIMIT = 1.0e3
"""Largest mass-normalised shape value a racket's model may hold, 1/√kg: a racket's are
≈ 1–30 (a 0.1 kg modal mass gives 3.2); 10³ means grams or a shape in other units."""


def check_on_racket(model: ModalModel, racket: Racket, source: str) -> None:
    """A modal model read for a racket, checked like a racket file (issue 26): its points on
    the racket (not in mm), its first flexible mode where a racket's is (not in rad/s), its
    mass-normalised shapes of a racket's size.

    Parameters
    ----------
    model : ModalModel
        The model read.
    racket : Racket
        The racket it is for.
    source : str
        The file, for messages.
    """
    if model.has_locations:
        xy = np.asarray(model.locations, dtype=float)[:, :2]
        reach = max(racket.head.half_width_m, 0.05) * 1.2
        off = (xy[:, 0] < -0.05) | (xy[:, 0] > racket.length_m * 1.1) | (np.abs(xy[:, 1]) > reach)
        if np.any(off):
            i = int(np.flatnonzero(off)[0])
            mm = " (in mm? the file's locations are in m)" if np.abs(xy).max() > 5.0 else ""
            raise InputError(
                f"{source}: point {i + 1} at x = {xy[i, 0]:g}, y = {xy[i, 1]:g} m is off the "
                f"racket (0–{racket.length_m:g} m long, ±{racket.head.half_width_m:g} m at the "
                f"head){mm}"
            )
    flexible = model.frequency[model.frequency > 10.0]
    lowest = float(flexible.min()) if flexible.size else math.nan
    low, high = FIRST_MODE_HZ
    if lowest > high and low <= lowest / (2.0 * math.pi) <= high:
        raise InputError(
            f"{source}: its lowest flexible mode is at {lowest:g} Hz, where no racket's first "
            f"bending mode is ({low:g}–{high:g} Hz); did you give rad/s ({lowest:g} rad/s = "
            f"{lowest / (2.0 * math.pi):.4g} Hz)? racketdyn's modal models are in Hz"
        )
    if model.mass_normalised and model.n_modes:
        largest = float(np.nanmax(np.abs(model.mode_shapes)))
        if largest > SHAPE_LIMIT:
            raise InputError(
                f"{source}: a mass-normalised shape value of {largest:g} 1/√kg; a racket's are "
                f"≈ 1–30 (a shape in other units, or a modal mass in grams?)"
            )
