"""From FRFs to a modal model of any structure: poles, selection, constants, mass normalisation.

:func:`identify` chains the steps — stabilisation diagram (:mod:`~racketdyn.modal.poles`),
automatic pole selection, LSFD modal constants (:mod:`~racketdyn.modal.residues`) and mass
normalisation from the driving point — and returns an :class:`Identification` holding every
intermediate result, so nothing is lost and every figure can be drawn from it.

The modes are named neutrally, ``"mode 1 (123.4 Hz)"``, of kind ``unknown``: what a mode is
depends on the structure, and a caller that knows it names them from their shapes (a racket:
:func:`racketdyn.racket_modal.identify.identify_racket`) with :meth:`Identification.renamed`.
"""

from __future__ import annotations

import csv
import logging
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from racketdyn.errors import InputError
from racketdyn.measurement.records import ANALYSER_BANDWIDTH_FACTOR, FrfSet
from racketdyn.modal.model import ModalModel
from racketdyn.modal.poles import SelectedPoles, Stabilisation, select_poles, stabilisation
from racketdyn.modal.residues import ModalFit, fit_modal_constants, mass_normalised_shapes

__all__ = ["DEFAULT_LOW_HZ", "Identification", "default_band", "identify"]

log = logging.getLogger(__name__)

DEFAULT_LOW_HZ = 40.0
"""Lower band edge by default, Hz: above the rigid-body modes of a light structure on soft
supports (≤ 15 Hz for a racket on a sponge or in a hand).  Pass ``band_hz`` for a structure
whose first flexible mode lies lower."""


def default_band(frfs: FrfSet) -> tuple[float, float]:
    """40 Hz to the analyser bandwidth, fs / 2.56 (the last line is fs / 2), Hz."""
    return (DEFAULT_LOW_HZ, 2.0 * float(frfs.frequency[-1]) / ANALYSER_BANDWIDTH_FACTOR)


@dataclass(frozen=True, eq=False)
class Identification:
    """Everything an identification produced.

    Attributes
    ----------
    model : ModalModel
        Frequencies, damping (window removed), mass-normalised shapes at the FRF points, names
        and kinds (neutral unless a caller named them: :meth:`renamed`).
    frfs : FrfSet
        The FRFs identified.
    stabilisation : Stabilisation
        Poles at every model order.
    selected : SelectedPoles
        The poles picked, with what was dropped and why.
    fit : ModalFit
        Modal constants, residuals, synthesised FRFs and the fit error of every FRF.
    band_hz : tuple of float
        Band used, Hz.
    """

    model: ModalModel
    frfs: FrfSet
    stabilisation: Stabilisation
    selected: SelectedPoles
    fit: ModalFit
    band_hz: tuple[float, float]

    def renamed(self, names: Sequence[str], kinds: Sequence[str]) -> Identification:
        """The same identification with its modes named (e.g. from their shapes).

        Parameters
        ----------
        names : sequence of str
            One name per mode.
        kinds : sequence of str
            One kind per mode (:data:`racketdyn.modal.model.MODE_KINDS`).

        Returns
        -------
        Identification
            A copy whose model carries the names and kinds; everything else is shared.
        """
        return replace(self, model=replace(self.model, names=tuple(names), kinds=tuple(kinds)))

    def write_modes_csv(self, path: Path) -> None:
        """``mode, frequency_hz, damping_ratio, name`` (+ kind, orders stable, fit spread)."""
        with Path(path).open("w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(
                [
                    "mode",
                    "frequency_hz",
                    "damping_ratio",
                    "name",
                    "kind",
                    "orders_stable",
                    "frequency_spread_hz",
                ]
            )
            model, selected = self.model, self.selected
            for k in range(model.n_modes):
                writer.writerow(
                    [
                        k + 1,
                        f"{model.frequency[k]:.6g}",
                        f"{model.damping_ratio[k]:.6g}",
                        model.names[k],
                        model.kinds[k],
                        int(selected.n_orders[k]),
                        f"{selected.frequency_spread_hz[k]:.3g}",
                    ]
                )


def identify(
    frfs: FrfSet,
    band_hz: tuple[float, float] | None = None,
    max_order: int = 60,
    pin_hz: Sequence[float] = (),
    exclude_hz: Sequence[float] = (),
    support: str = "free",
) -> Identification:
    """Identify a modal model of any structure from a set of FRFs against one reference.

    Parameters
    ----------
    frfs : FrfSet
        FRFs of the hammer points (with a driving point at the reference for mass-normalised
        shapes); an exponential window recorded on the set is taken off the damping.
    band_hz : tuple of float, optional
        Band to identify in, Hz (default :func:`default_band`).
    max_order : int
        Highest model order of the stabilisation diagram.
    pin_hz, exclude_hz : sequence of float
        Modes to force in or leave out, by approximate frequency, Hz.
    support : str
        Support the structure was tested on (``free``, ``hand`` …), recorded on the model.

    Returns
    -------
    Identification
        The model's modes are named ``"mode k (f Hz)"``, of kind ``unknown``.
    """
    band = band_hz or default_band(frfs)
    if not 0 <= band[0] < band[1] <= frfs.frequency[-1]:
        raise InputError(
            f"{frfs.source}: band {band[0]:g}–{band[1]:g} Hz must lie within the FRFs' "
            f"0–{frfs.frequency[-1]:g} Hz"
        )
    stab = stabilisation(frfs, band, max_order=max_order)
    selected = select_poles(stab, pin_hz=pin_hz, exclude_hz=exclude_hz)  # raises if none
    fit = fit_modal_constants(frfs, selected.pole, band)
    unseen: list[str] = []
    if frfs.driving_point is not None:
        # a mode the accelerometer does not see cannot be mass-normalised: leave it out, say so
        positive = fit.constants[frfs.driving_point] > 0
        for k in np.flatnonzero(~positive):
            unseen.append(
                f"{selected.frequency[k]:.2f} Hz: not seen at the accelerometer (driving-point "
                "constant not positive), so it cannot be mass-normalised; left out"
            )
            log.warning("%s", unseen[-1])
        if not positive.any():
            raise InputError(
                f"{frfs.source}: no mode is seen at the accelerometer (node "
                f"{frfs.reference_node}); move it off the nodes"
            )
        if not positive.all():
            selected = selected.select(positive)
            fit = fit_modal_constants(frfs, selected.pole, band)
    shapes = mass_normalised_shapes(frfs, fit)
    names = tuple(f"mode {k + 1} ({f:.1f} Hz)" for k, f in enumerate(selected.frequency))
    model = ModalModel(
        frequency=selected.frequency,
        damping_ratio=selected.damping_ratio,
        locations=frfs.locations,
        mode_shapes=shapes,
        names=names,
        kinds=("unknown",) * len(names),
        support=support,
        source=f"identified from {frfs.source}",
        metadata={
            "band_hz": list(band),
            "max_order": max_order,
            "exponential_window_s": frfs.exponential_window_s,
            "nodes": list(frfs.nodes),
            "reference_node": frfs.reference_node,
            "fit_error_median": float(np.median(fit.error)),
            "design_condition_number": fit.condition_number,
            "orders_stable": selected.n_orders.tolist(),
            "dropped": [*selected.dropped, *unseen],
        },
    )
    log.info("identified %d modes in %g–%g Hz", model.n_modes, *band)
    selected = replace(selected, dropped=(*selected.dropped, *unseen))
    return Identification(model, frfs, stab, selected, fit, band)
