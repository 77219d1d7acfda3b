"""Identify a racket: the general identification, then the modes named the racket way.

:func:`identify_racket` is what the racket workflows call: :func:`racketdyn.modal.identify.identify`
on the FRFs, then :func:`name_racket_modes` (bending, twisting, string bed from the shapes and
the head: :func:`racketdyn.racket_modal.shapes.classify_modes`).
"""

from __future__ import annotations

from collections.abc import Sequence

from racketdyn.measurement.records import FrfSet
from racketdyn.modal.identify import Identification, identify
from racketdyn.racket import HeadEllipse, Racket
from racketdyn.racket_modal.shapes import classify_modes

__all__ = ["identify_racket", "name_racket_modes"]


def _head(racket: Racket | HeadEllipse) -> HeadEllipse:
    return racket.head if isinstance(racket, Racket) else racket


def name_racket_modes(
    identification: Identification, racket: Racket | HeadEllipse
) -> Identification:
    """The identification with its modes named from their shapes on the racket.

    Parameters
    ----------
    identification : Identification
        From :func:`racketdyn.modal.identify.identify` on a racket's FRFs.
    racket : Racket or HeadEllipse
        The racket (or its string bed), to tell string points from frame points.

    Returns
    -------
    Identification
        Names ``"2-node bending"``, ``"2-node twisting"``, ``"string-bed membrane"`` … and
        kinds ``bending``, ``twisting``, ``string-bed``.
    """
    names, kinds = classify_modes(identification.model, _head(racket))
    return identification.renamed(names, kinds)


def identify_racket(
    frfs: FrfSet,
    racket: Racket | HeadEllipse,
    band_hz: tuple[float, float] | None = None,
    max_order: int = 60,
    pin_hz: Sequence[float] = (),
    exclude_hz: Sequence[float] = (),
    support: str = "free",
) -> Identification:
    """Identify a racket's modal model from its FRFs and name the modes the racket way.

    Parameters
    ----------
    frfs : FrfSet
        FRFs of the hammer points (with a driving point at the reference for mass-normalised
        shapes); an exponential window recorded on the set is taken off the damping.
    racket : Racket or HeadEllipse
        The racket (or its string bed), to name modes (string-bed against frame).
    band_hz : tuple of float, optional
        Band to identify in, Hz (default :func:`racketdyn.modal.identify.default_band`: 40 Hz,
        above the rigid-body modes of a racket on a sponge or in a hand (≤ 15 Hz) and below
        its first bending mode (≥ 100 Hz), to the analyser bandwidth).
    max_order : int
        Highest model order of the stabilisation diagram.
    pin_hz, exclude_hz : sequence of float
        Modes to force in or leave out, by approximate frequency, Hz.
    support : str
        Support the racket was tested on (``free``, ``hand``), recorded on the model.

    Returns
    -------
    Identification
    """
    identification = identify(
        frfs,
        band_hz,
        max_order=max_order,
        pin_hz=pin_hz,
        exclude_hz=exclude_hz,
        support=support,
    )
    return name_racket_modes(identification, racket)
