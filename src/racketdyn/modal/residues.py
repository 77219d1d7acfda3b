"""Modal constants by least-squares frequency-domain fitting (LSFD) and mass normalisation.

Given the poles, every FRF of the set is fitted at once (one design matrix, one right-hand side
per FRF) with **real modal constants** — the proportionally damped model the paper and
:class:`~racketdyn.modal.model.ModalModel` use —

``H_o(ω) = (iω)^p [ Σ_k A_ok / ((iω − λ_k)(iω − λ_k*)) − L_o/ω² + U_o ]``

with p = 0, 1, 2 for receptance, mobility and accelerance, a lower residual L (modes below the
band, rigid-body motion) and an upper residual U (modes above it).  Columns are scaled to unit
norm before the solve (the unscaled matrix spans many decades; scaled, its condition number is
that of the physics) and the real and imaginary parts are stacked so the unknowns stay real.

Exponential window: the FRFs of a windowed measurement have every pole moved left by 1/τ and
the same residues, so they are fitted with the moved poles and the constants hold for the
structure.

Mass normalisation (the paper's eq 12 needs it): ``A_ok = φ_o φ_ref``, so at the driving point
``A_ref,k = φ_ref²`` gives ``φ_ref = √A_ref,k`` and every ``φ_o = A_ok / φ_ref``.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.errors import InputError
from racketdyn.measurement.records import FrfSet
from racketdyn.modal.mac import mac

__all__ = [
    "ModalFit",
    "design_columns",
    "fit_modal_constants",
    "half_power_lines",
    "mac",
    "mass_normalised_shapes",
    "unscaled_shapes",
]

log = logging.getLogger(__name__)

_POWER = {"receptance": 0, "mobility": 1, "accelerance": 2}
WEAK_DRIVING_POINT = 0.05
"""Driving-point constant below this fraction of a mode's largest: normalisation flagged."""


@dataclass(frozen=True, eq=False)
class ModalFit:
    """Modal constants of every FRF and how well they reproduce it.

    Attributes
    ----------
    poles : ndarray, complex, shape (n_modes,)
        Poles of the structure λ = −σ + iω_d, rad/s (upper half plane).
    constants : ndarray, shape (n_points, n_modes)
        Real modal constants A_ok (1/kg, i.e. m/(N·s²) per unit of modal receptance).
    lower_residual, upper_residual : ndarray, shape (n_points,)
        Residual terms (receptance units: L in N⁻¹·s⁻², U in m/N).
    synthesised : ndarray, complex, shape (n_points, n_freq)
        The fitted FRFs on the data's band, in the data's frf_type.
    frequency : ndarray
        The band's lines, Hz.
    error : ndarray, shape (n_points,)
        Normalised fit error ‖H − Ĥ‖ / ‖H‖ of each FRF over the band.
    condition_number : float
        Of the column-scaled design matrix.
    """

    poles: NDArray[np.complex128]
    constants: NDArray[np.float64]
    lower_residual: NDArray[np.float64]
    upper_residual: NDArray[np.float64]
    synthesised: NDArray[np.complex128]
    frequency: NDArray[np.float64]
    error: NDArray[np.float64]
    condition_number: float

    def at_points(self, indices: Sequence[int]) -> ModalFit:
        """The fit of some FRFs only (by index, in the order given; the same poles)."""
        keep = np.asarray(indices, dtype=int)
        return replace(
            self,
            constants=self.constants[keep],
            lower_residual=self.lower_residual[keep],
            upper_residual=self.upper_residual[keep],
            synthesised=self.synthesised[keep],
            error=self.error[keep],
        )

    @property
    def frequency_hz(self) -> NDArray[np.float64]:
        """Undamped natural frequencies ``|λ|/2π``, Hz."""
        return np.asarray(np.abs(self.poles) / (2 * np.pi))

    @property
    def damping_ratio(self) -> NDArray[np.float64]:
        """Damping ratios ``−Re λ / |λ|``."""
        return np.asarray(-self.poles.real / np.abs(self.poles))


def half_power_lines(
    frequency_hz: NDArray[np.float64], damping_ratio: NDArray[np.float64], lines_hz: ArrayLike
) -> NDArray[np.float64]:
    """Each mode's half-power width 2ζf in lines (Δf the lines' median spacing): under one,
    the lines do not resolve its peak (its ringing outlasts the record, ζωT < π for T = 1/Δf).

    Parameters
    ----------
    frequency_hz, damping_ratio : ndarray
        The modes' frequencies, Hz, and damping ratios.
    lines_hz : array_like
        The FRFs' lines, Hz.
    """
    spacing = float(np.median(np.diff(np.asarray(lines_hz, dtype=float))))
    return np.asarray(2.0 * np.asarray(damping_ratio) * np.asarray(frequency_hz) / spacing)


def fit_modal_constants(
    frfs: FrfSet, poles: NDArray[np.complex128], band_hz: tuple[float, float] | None = None
) -> ModalFit:
    """Least-squares modal constants and residuals of every FRF for given poles.

    Parameters
    ----------
    frfs : FrfSet
        The FRFs (any frf_type; the exponential window, if recorded, is accounted for).
    poles : array_like, complex
        Poles of the structure λ = −σ + iω_d, rad/s (one per mode, upper half plane):
        :attr:`SelectedPoles.pole <racketdyn.modal.poles.SelectedPoles.pole>`, not its
        ``windowed_pole``.  With an exponential window τ recorded on ``frfs``, each is moved to
        λ − 1/τ here, as the windowed FRFs hold it (module docstring); the constants are the
        structure's.
    band_hz : tuple of float, optional
        Frequency band to fit, Hz (default: every line above 0 Hz).

    Returns
    -------
    ModalFit
        Constants, residuals, synthesised FRFs and the fit error per FRF.
    """
    lam = np.atleast_1d(np.asarray(poles, dtype=complex))
    if lam.size == 0:
        raise InputError(f"{frfs.source}: no poles to fit modal constants to")
    if np.any(lam.real >= 0) or np.any(lam.imag <= 0):
        raise InputError("poles must be stable (Re λ < 0) and in the upper half plane (Im λ > 0)")
    low, high = band_hz if band_hz is not None else (0.0, float(frfs.frequency[-1]))
    keep = (frfs.frequency > max(low, 0.0)) & (frfs.frequency <= high)
    if keep.sum() < 2 * lam.size + 2:
        raise InputError(
            f"{frfs.source}: {int(keep.sum())} lines in {low:g}–{high:g} Hz are too few to fit "
            f"{lam.size} modes and two residuals"
        )
    columns = design_columns(frfs, lam, frfs.frequency[keep])
    stacked = np.vstack([columns.real, columns.imag])
    scale = np.linalg.norm(stacked, axis=0)
    data = frfs.values[:, keep].T
    rhs = np.vstack([data.real, data.imag])
    solution, *_ = np.linalg.lstsq(stacked / scale, rhs, rcond=None)
    solution = solution / scale[:, None]
    singular = np.linalg.svd(stacked / scale, compute_uv=False)
    synthesised = (columns @ solution).T
    error = np.linalg.norm(frfs.values[:, keep] - synthesised, axis=1) / np.linalg.norm(
        frfs.values[:, keep], axis=1
    )
    n = lam.size
    return ModalFit(
        poles=lam,
        constants=np.asarray(solution[:n].T),
        lower_residual=np.asarray(solution[n]),
        upper_residual=np.asarray(solution[n + 1]),
        synthesised=np.asarray(synthesised),
        frequency=np.asarray(frfs.frequency[keep]),
        error=np.asarray(error),
        condition_number=float(singular[0] / singular[-1]),
    )


def design_columns(
    frfs: FrfSet, poles: NDArray[np.complex128], frequency: NDArray[np.float64]
) -> NDArray[np.complex128]:
    """The LSFD model's columns at some lines: one per mode (unit constant), L and U.

    Parameters
    ----------
    frfs : FrfSet
        Gives the FRF type and the exponential window.
    poles : ndarray, complex
        Poles of the structure, rad/s.
    frequency : ndarray
        Lines, Hz (above 0).

    Returns
    -------
    ndarray, complex, shape (n_freq, n_modes + 2)
        ``(iω)^p / ((iω − λ)(iω − λ*))`` per mode, then ``−(iω)^p / ω²`` and ``(iω)^p``: the
        FRF is these columns times ``[A_o, L_o, U_o]``.
    """
    omega = 2 * np.pi * np.asarray(frequency, dtype=float)
    s = 1j * omega
    windowed = poles - (1.0 / frfs.exponential_window_s if frfs.exponential_window_s else 0.0)
    power = (s ** _POWER[frfs.frf_type])[:, None]
    modal = 1.0 / ((s[:, None] - windowed) * (s[:, None] - np.conj(windowed)))
    return np.asarray(power * np.column_stack([modal, -1.0 / omega**2, np.ones_like(omega)]))


def mass_normalised_shapes(frfs: FrfSet, fit: ModalFit) -> NDArray[np.float64]:
    """Mass-normalised mode shapes at the FRF points from the driving-point constants, 1/√kg.

    ``φ_i = A_ir / sqrt(A_rr)`` for each mode, with r the driving point (eq 12's residues).

    Parameters
    ----------
    frfs : FrfSet
        The FRFs the constants were fitted to (their driving point, their source for errors).
    fit : ModalFit
        The modal constants (:func:`fit_modal_constants`).

    Returns
    -------
    ndarray (n_points, n_modes)
        The shapes, 1/√kg.

    Raises
    ------
    InputError
        If the set has no driving-point FRF (a hammer point at the reference node), or a mode's
        driving-point constant is not positive (the mode is not seen at the accelerometer, or
        the pole is not a real structural mode).
    """
    driving = frfs.driving_point
    if driving is None:
        raise InputError(
            f"{frfs.source}: mass-normalised shapes need a driving-point FRF — strike the "
            f"reference node {frfs.reference_node} (the accelerometer) too"
        )
    at_reference = fit.constants[driving]
    weak = np.flatnonzero(at_reference <= 0)
    if weak.size:
        listed = ", ".join(f"{f:.1f} Hz" for f in fit.frequency_hz[weak])
        raise InputError(
            f"{frfs.source}: the driving-point modal constant is not positive for {listed}; move "
            "the accelerometer off that mode's node, or leave the mode out (`exclude_hz`)"
        )
    weak = np.flatnonzero(at_reference < WEAK_DRIVING_POINT * np.abs(fit.constants).max(axis=0))
    for k in weak:
        log.warning(
            "%.1f Hz: the accelerometer sits near a node of this mode (driving-point constant "
            "%.2g of the largest); its mass normalisation is uncertain",
            fit.frequency_hz[k],
            at_reference[k] / np.abs(fit.constants[:, k]).max(),
        )
    return np.asarray(fit.constants / np.sqrt(at_reference))


def unscaled_shapes(fit: ModalFit) -> NDArray[np.float64]:
    """Shapes without a driving point: each mode's constants over its largest magnitude.

    ``A_ok = φ_o φ_ref`` is the shape times an unknown factor ``φ_ref`` per mode, so the
    constants are the shape up to that factor; each column is scaled so its largest magnitude
    is +1 (no unit).
    """
    constants = fit.constants
    largest = np.take_along_axis(constants, np.abs(constants).argmax(axis=0)[None], axis=0)[0]
    largest = np.where(largest == 0, 1.0, largest)
    return np.asarray(constants / largest)
