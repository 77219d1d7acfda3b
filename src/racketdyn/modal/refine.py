"""Poles of modes narrower than one spectral line, refined by a local nonlinear fit.

When a mode's half-power width ``2ζf`` (in the data: an exponential window's share
included) is under one line spacing, one or two lines stand on its peak and the damping lies in
how high they stand over the skirts.  The LSCF of :mod:`~racketdyn.modal.poles` fits the
linearised error ``N − H d``, the FRFs' own error weighted by ``|d|²``, which is smallest at
the poles: the lines that hold the damping count least.  Where its poles then wander over the
orders its damping is not to be trusted (vtb_siglab's 34.05 Hz, 2ζf = 0.014 Hz under a
0.3125 Hz line: stable in 5 of 60 orders, ζ 0.033 % against sdypy-EMA's 0.021 %).  Here the
FRFs' own error is minimised instead, over :data:`REFINE_LINES` lines either side of the
mode, every FRF ``H_o ≈ Σ_k (r_ok/(iω − λ_k) + s_ok/(iω − λ_k*)) + c_o + d_o iω`` with the
modes in that window (the slope's ``iω`` scaled by the window's first line): complex constants
solved linearly for given poles (variable projection), the poles by nonlinear least squares
(``scipy.optimize.least_squares``).  The DFT of a ringing cut at the record's end is a pole
term at the same λ near its peak (leakage scales the constant, not the pole), so the local
model holds for unwindowed, truncated records too.

Only narrow modes whose LSCF poles do not settle over the orders are refined: where the peak
spans lines, or the poles settle, the LSCF's damping agrees with the independent references
(tests/test_realdata_must_hold.py), and a local fit's depends on the window fitted.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares

from racketdyn.measurement.records import FrfSet
from racketdyn.modal.poles import SelectedPoles, pole_of

__all__ = [
    "MOVE_LINES",
    "NARROW_LINES",
    "REFINE_LINES",
    "SETTLED_FRACTION",
    "fit_poles",
    "local_misfit",
    "refine_narrow_poles",
]

log = logging.getLogger(__name__)

NARROW_LINES = 1.0
"""A mode whose half-power width in the data is under this many line spacings is refined."""
REFINE_LINES = 10
"""Lines either side of a narrow mode fitted: its skirts, enough for the two background terms
(a constant and a slope for the modes outside) and every mode inside."""
SETTLED_FRACTION = 0.2
"""... and stable in fewer than this share of the orders (:class:`~racketdyn.modal.poles.
SelectionRules`' ``min_fraction``; kept as a clear peak or pinned): a narrow mode the LSCF settles
keeps its pole (on synthetic truncated ringing, 2ζf a twentieth of a line, with 5 %
multiplicative noise, it was within 5 % where the local fit was within 11 %; pyuff's six
narrow modes agree with sdypy-EMA's)."""
MOVE_LINES = 0.5
"""A refined frequency further than this many lines from the LSCF's is not taken (the fit
went to another feature): the LSCF pole is kept."""


def refine_narrow_poles(frfs: FrfSet, selected: SelectedPoles) -> tuple[SelectedPoles, list[str]]:
    """The selection with every unsettled narrow mode's pole refined (module docstring).

    Parameters
    ----------
    frfs : FrfSet
        The FRFs identified (an exponential window recorded on them is accounted for).
    selected : SelectedPoles
        The modes picked from the stabilisation diagram.

    Returns
    -------
    SelectedPoles, list of str
        The selection with the refined modes' ``frequency``, ``damping_ratio`` and ``pole``
        replaced, and one line per refined mode saying from what to what and why.
    """
    spacing = float(np.median(np.diff(frfs.frequency)))
    shift = 1.0 / frfs.exponential_window_s if frfs.exponential_window_s else 0.0
    frequency = selected.frequency.copy()
    zeta = selected.damping_ratio.copy()
    lines: list[str] = []
    for k in np.flatnonzero(_narrow(selected, spacing, shift)):
        refined = _local_fit(frfs, selected, int(k), spacing)
        if refined is None:
            continue
        frequency[k], zeta[k] = refined
        lines.append(
            f"{selected.frequency[k]:.2f} Hz: half-power width "
            f"{2 * selected.damping_ratio[k] * selected.frequency[k]:.3g} Hz under one "
            f"{spacing:.4g} Hz line; the local fit of its peak gives {frequency[k]:.3f} Hz, "
            f"ζ {100 * zeta[k]:.3g} % (the LSCF's {100 * selected.damping_ratio[k]:.3g} %)"
        )
    if not lines:
        return selected, []
    pole = pole_of(frequency, zeta)
    return replace(selected, frequency=frequency, damping_ratio=zeta, pole=pole), lines


def _narrow(selected: SelectedPoles, spacing: float, shift: float) -> NDArray[np.bool_]:
    """Unsettled modes whose half-power width in the data (the window's ``1/τ`` added) is
    under a line."""
    decay = selected.damping_ratio * 2 * np.pi * selected.frequency + shift
    unsettled = selected.n_orders < SETTLED_FRACTION * selected.n_orders_computed
    narrow = decay / np.pi < NARROW_LINES * spacing
    return np.asarray(narrow & unsettled & (selected.damping_ratio > 0))


def _local_fit(
    frfs: FrfSet, selected: SelectedPoles, k: int, spacing: float
) -> tuple[float, float] | None:
    """Frequency and damping of mode ``k`` from the FRFs' lines around it, or None (kept)."""
    centre = float(selected.frequency[k])
    inside = np.flatnonzero(np.abs(selected.frequency - centre) <= REFINE_LINES * spacing)
    found = fit_poles(
        frfs,
        selected.frequency[inside],
        selected.damping_ratio[inside],
        (centre - REFINE_LINES * spacing, centre + REFINE_LINES * spacing),
    )
    if found is None:
        return None
    frequency, zeta, _, improved = found
    j = int(np.flatnonzero(inside == k)[0])
    moved, z = (float(frequency[j]) - centre) / spacing, float(zeta[j])
    if abs(moved) > MOVE_LINES or not 0 < z < 1 or not improved:
        log.debug("narrow mode at %.2f Hz: the local fit not taken", centre)
        return None
    return float(frequency[j]), z


def fit_poles(
    frfs: FrfSet,
    frequency_hz: NDArray[np.float64],
    damping_ratio: NDArray[np.float64],
    window_hz: tuple[float, float],
    weights: NDArray[np.float64] | None = None,
    max_steps: int | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.complex128], bool] | None:
    """The poles of the FRFs' lines in ``window_hz`` by the local fit (module docstring),
    started from ``frequency_hz`` and ``damping_ratio``: frequencies (Hz), damping ratios, the
    constants ``r_ok`` of every FRF (one column a pole) and whether the fit improved on its
    start; None where the window holds too few lines or the fit fails.  ``weights`` (one a
    FRF, e.g. one over its noise) weight each FRF's error; the constants are the FRFs' own.
    ``max_steps`` bounds the nonlinear fit's steps (None: scipy's default); a fit that does not
    converge within them is None."""
    model = _LocalModel.of(frfs, frequency_hz, damping_ratio, window_hz, weights)
    if model is None:
        return None
    before = float(np.linalg.norm(model.residual(model.start)))
    try:
        found = least_squares(model.residual, model.start, max_nfev=max_steps)
    except (ValueError, np.linalg.LinAlgError):
        return None
    if not (found.success and np.all(np.isfinite(found.x))):
        return None
    improved = bool(np.linalg.norm(found.fun) < before)
    n = model.base.size
    frequency = model.base + found.x[:n] * model.spacing
    return frequency, np.exp(found.x[n:]), model.constants(found.x)[1], improved


def local_misfit(
    frfs: FrfSet,
    frequency_hz: NDArray[np.float64],
    damping_ratio: NDArray[np.float64],
    window_hz: tuple[float, float],
    weights: NDArray[np.float64] | None = None,
) -> float:
    """The local model's misfit (the norm of the weighted error) over ``window_hz`` with these
    poles as they are (no fit of the poles: their constants only); NaN where the window holds
    too few lines."""
    model = _LocalModel.of(frfs, frequency_hz, damping_ratio, window_hz, weights)
    if model is None:
        return float("nan")
    return float(np.linalg.norm(model.residual(model.start)))


@dataclass(frozen=True)
class _LocalModel:
    """The local model of :func:`fit_poles` over one window: its poles' parameters ``x``
    (offsets from ``base`` in lines, log damping ratios) to the weighted error and constants."""

    s: NDArray[np.complex128]
    data: NDArray[np.complex128]
    weight: NDArray[np.float64]
    base: NDArray[np.float64]
    start: NDArray[np.float64]
    spacing: float
    shift: float

    @classmethod
    def of(
        cls,
        frfs: FrfSet,
        frequency_hz: NDArray[np.float64],
        damping_ratio: NDArray[np.float64],
        window_hz: tuple[float, float],
        weights: NDArray[np.float64] | None,
    ) -> _LocalModel | None:
        near = (frfs.frequency >= window_hz[0]) & (frfs.frequency <= window_hz[1])
        n = len(frequency_hz)
        if np.count_nonzero(near) < 2 * (2 * n + 2):
            return None
        weight = np.ones(frfs.n_points) if weights is None else np.asarray(weights, dtype=float)
        return cls(
            s=(2j * np.pi * frfs.frequency[near]).astype(np.complex128),
            data=frfs.values[:, near].T * weight,
            weight=weight,
            base=np.asarray(frequency_hz, dtype=float),
            start=np.concatenate([np.zeros(n), np.log(np.maximum(damping_ratio, 1e-9))]),
            spacing=float(np.median(np.diff(frfs.frequency))),
            shift=1.0 / frfs.exponential_window_s if frfs.exponential_window_s else 0.0,
        )

    def constants(self, x: NDArray[np.float64]) -> tuple[NDArray[np.complex128], NDArray[Any]]:
        """The weighted error (lines × FRFs) and the FRFs' constants (FRFs × poles)."""
        n, s = self.base.size, self.s
        omega = 2 * np.pi * (self.base + x[:n] * self.spacing)
        z = np.exp(x[n:])
        pole = -z * omega + 1j * omega * np.sqrt(np.maximum(1 - z**2, 0.0)) - self.shift
        columns = np.column_stack(
            [1 / (s[:, None] - pole), 1 / (s[:, None] - pole.conj()), np.ones_like(s), s / s[0]]
        )
        scale = np.linalg.norm(columns, axis=0)
        solution, *_ = np.linalg.lstsq(columns / scale, self.data, rcond=None)
        amplitudes = (solution / scale[:, None])[:n].T / self.weight[:, None]
        return self.data - (columns / scale) @ solution, amplitudes

    def residual(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """The weighted error as real numbers."""
        error = self.constants(x)[0]
        return np.concatenate([error.real.ravel(), error.imag.ravel()])
