"""Where a modal fit misses its FRFs: the verdict on the fit error.

The fit error of an FRF, ‖H − Ĥ‖ / ‖H‖ over the band (:class:`~racketdyn.modal.residues.ModalFit`),
is a number without a verdict: a clean beam fits to 1 %, a measured wing to 39 %, a racket's
rig test to 17–50 %.  A threshold does not tell them apart, because the error the data's own
noise leaves is far smaller than any of them (a study over the realistic test files, recorded
in docs/develop.md: 0.07–1.4 % against medians of 7–79 %); what the misfit says lies in
*where* it is.  The residual ``H − Ĥ`` of every FRF, over its ‖H‖², is split by line into

* **at the kept modes** — within :data:`NEAR_WIDTHS` half-power widths (at least as many lines)
  of a mode's frequency: the poles or the constants miss the peaks themselves.  When modal
  constants that are complex (``R/(iω − λ) + R*/(iω − λ*)`` in place of the real
  ``A/((iω − λ)(iω − λ*))``, the same poles) leave at most :data:`COMPLEX_GAIN` of the error,
  the modes are complex — non-proportional damping, or the two channels differ in phase (a
  delay, a filter) — which real constants, the method's (mass-normalised shapes, eq 12), cannot
  follow.  Peaks narrower than one line (2ζf < Δf) are not resolved by the lines.
* **at the band's edges** — the outer :data:`EDGE_SHARE` of the band at each end: a mode at or
  beyond an edge that the residual terms cannot stand for.
* **elsewhere** — away from every kept mode: modes (or lines) the model lacks.

A median error under :data:`NEGLIGIBLE` is as close as a fit need be whatever the noise.

FRFs that measured noise alone (:func:`racketdyn.measurement.quality.noise_only_frfs`) are
read apart: a fit misses pure noise by ≈ 100 % whatever the model, so their errors would
make the median theirs (a cantilever with two of three FRFs noise read 99.4 %, "as good as the
noise allows", while its one measured FRF was missed by 35 %, mostly at its modes).  The
verdict is read over the FRFs that carry the structure, the noise ones named.

The noise's own share is the error white noise of the data's level would leave
(:func:`racketdyn.modal.poles.second_difference_noise`, per FRF, over all the band's lines):
a median error within :data:`NOISE_FACTOR` of it is as good as the data allow.

Written here rather than taken from a library: sdypy-EMA and pyFRF report the fit's error or
an FRF's coherence, not where a modal fit misses; the split uses only numpy.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn._grammar import plural
from racketdyn.measurement.records import FrfSet
from racketdyn.modal.poles import second_difference_noise
from racketdyn.modal.residues import ModalFit, design_columns, half_power_lines

__all__ = [
    "COMPLEX_GAIN",
    "DOMINANT",
    "EDGE_SHARE",
    "NEAR_WIDTHS",
    "NOISE_FACTOR",
    "Misfit",
    "misfit",
]

NEAR_WIDTHS = 3.0
"""Half-power widths (and at least as many lines) either side of a kept mode that count as at
the mode."""
EDGE_SHARE = 0.03
"""The fraction of the band's width at each end that counts as its edge."""
NOISE_FACTOR = 2.0
"""A median fit error within this factor of the noise's own is the noise's."""
NEGLIGIBLE = 0.005
"""A median fit error under this is as good as a fit need be, whatever the noise (noise-free
synthetic FRFs leave 0.0–0.1 %)."""
COMPLEX_GAIN = 0.6
"""Complex constants leaving at most this fraction of the median error: the modes are
complex."""
DOMINANT = 0.5
"""The share of the residual's energy that names where the misfit lies."""
WORST = 3
"""Frequencies named where the residual away from the modes is largest."""
NEAR_WORST = 0.03
"""A left-out mode within this fraction of a worst frequency is named with it."""

CAUSES = (
    "noise",
    "negligible",
    "missing modes",
    "band edges",
    "complex modes",
    "unresolved peaks",
    "poles",
    "spread",
)
"""The verdicts (``"spread"``: no place holds :data:`DOMINANT` of the misfit)."""


@dataclass(frozen=True)
class Misfit:
    """Where a modal fit misses its FRFs, and what that says.

    Attributes
    ----------
    median_error : float
        Median over the FRFs of ‖H − Ĥ‖ / ‖H‖ (the fit's).
    noise_error : float
        Median over the FRFs of the error white noise of each FRF's own level leaves.
    complex_error : float
        Median error of a fit with complex modal constants on the same poles.
    near_modes, edges, elsewhere : float
        Shares of the residual's energy (each FRF's over its ‖H‖², summed) at the kept modes,
        at the band's edges and elsewhere; they add up to 1.
    worst_hz : tuple of float
        Where, away from the kept modes and the edges, the residual is largest (up to
        :data:`WORST`, 2 % apart), Hz.
    edges_hz : tuple of float
        The band's edge ranges ``(low, low + w, high − w, high)``, Hz.
    unresolved_hz : tuple of float
        Kept modes whose half-power width is under one line, Hz.
    worst_modes_hz : tuple of float
        The kept modes at which the residual is largest (up to :data:`WORST`, the largest
        first), Hz.
    unresolved_share : float
        The share of the residual at the kept modes that lies at the unresolved ones.
    left_out_hz : tuple of float
        Modes left out (given by the caller) within :data:`NEAR_WORST` of a frequency in
        ``worst_hz``, Hz.
    worst_nodes : tuple of int
        The points whose FRFs the fit misses most (up to :data:`WORST`, the worst first).
    cause : str
        One of :data:`CAUSES`.
    noise_nodes : tuple of int
        The points whose FRFs measured noise alone, left out of everything above (none when
        every FRF is noise: then all are read).
    """

    median_error: float
    noise_error: float
    complex_error: float
    near_modes: float
    edges: float
    elsewhere: float
    worst_hz: tuple[float, ...]
    edges_hz: tuple[float, float, float, float]
    unresolved_hz: tuple[float, ...]
    worst_modes_hz: tuple[float, ...]
    unresolved_share: float
    left_out_hz: tuple[float, ...]
    worst_nodes: tuple[int, ...]
    cause: str
    noise_nodes: tuple[int, ...] = ()

    def sentence(self) -> str:
        """One line: the error, the noise's, and where the misfit lies (parameter names in
        backticks, for a caller to spell as its own options)."""
        head = (
            f"median fit error {self.median_error:.1%} against {self.noise_error:.2%} that the "
            f"data's noise leaves{self._apart()}"
        )
        if self.cause == "noise":
            return f"{head}: as good as the noise allows"
        if self.cause == "negligible":
            return f"{head}: under {NEGLIGIBLE:.1%}, as close as a fit need be"
        places = (
            f"{self.near_modes:.0%} of the misfit at the kept modes, {self.edges:.0%} at the "
            f"band's edges, {self.elsewhere:.0%} elsewhere"
        )
        nodes = ", ".join(map(str, self.worst_nodes))
        return f"{head}; {places}: {self._why()}; worst at nodes {nodes}"

    def _apart(self) -> str:
        """The FRFs of noise left out of the verdict, in words ("" if none; their nodes are
        the noise line's to name, :meth:`racketdyn.measurement.quality.NoiseOnly.sentence`)."""
        if not self.noise_nodes:
            return ""
        frfs = plural(len(self.noise_nodes), "FRF")
        return f" (over the FRFs that carry the structure, {frfs} of noise left out)"

    def _why(self) -> str:
        """What the dominant place says."""
        if self.cause == "missing modes":
            at = ", ".join(f"{f:.4g}" for f in self.worst_hz)
            if not self.left_out_hz:
                return f"modes or lines the model lacks, most at {at} Hz"
            there = ", ".join(f"{f:.5g}" for f in self.left_out_hz)
            return (
                f"modes or lines the model lacks, most at {at} Hz, where {there} Hz were left "
                "out (`pin_hz` keeps a mode)"
            )
        if self.cause == "band edges":
            lo0, lo1, hi0, hi1 = self.edges_hz
            return (
                f"at {lo0:.4g}–{lo1:.4g} and {hi0:.4g}–{hi1:.4g} Hz (the band's outer "
                f"{EDGE_SHARE:.0%} at each end), a mode at or beyond an edge that the residual "
                "terms cannot stand for (a `band_hz` whose edges lie between peaks, clear of "
                "the first and last modes by more than that)"
            )
        if self.cause == "complex modes":
            said = (
                f"complex modal constants would leave {self.complex_error:.1%}: the modes are "
                "complex (non-proportional damping), the channels differ in phase (a delay, a "
                "filter) or the record ends before the ringing does (leakage), which the real "
                "constants of mass-normalised shapes cannot follow"
            )
            if not self.unresolved_hz:
                return said
            at = ", ".join(f"{f:.4g}" for f in self.unresolved_hz)
            return (
                f"{said}; at {at} Hz the peaks are narrower than one line, their ringing "
                "outlasting the record: leakage there"
            )
        if self.cause == "unresolved peaks":
            at = ", ".join(f"{f:.4g}" for f in self.unresolved_hz)
            return (
                f"the poles miss peaks narrower than one line at {at} Hz, which the lines "
                "cannot pin down: their ringing outlasts the record (a longer record, finer "
                "lines)"
            )
        if self.cause == "poles":
            at = ", ".join(f"{f:.4g}" for f in self.worst_modes_hz)
            return (
                f"the peaks' shapes are not the kept poles', most at {at} Hz (two modes too "
                "close to part, a nonlinear, amplitude-dependent mode, or a peak the "
                "measurement distorted)"
            )
        return "no one place holds half of it: " + "; ".join(
            self._place(place) for place in self._places_by_share() if self._share(place) >= 0.25
        )

    def _share(self, place: str) -> float:
        return {"modes": self.near_modes, "edges": self.edges, "elsewhere": self.elsewhere}[place]

    def _places_by_share(self) -> list[str]:
        return sorted(("modes", "edges", "elsewhere"), key=self._share, reverse=True)

    def _place(self, place: str) -> str:
        """One place of a spread misfit with where in it (for the verdict of each alone, see
        the causes)."""
        if place == "modes":
            at = ", ".join(f"{f:.4g}" for f in self.worst_modes_hz)
            return f"at the kept modes most at {at} Hz (modes too close to part?)"
        if place == "edges":
            lo0, lo1, hi0, hi1 = self.edges_hz
            return (
                f"at the band's edges, {lo0:.4g}–{lo1:.4g} and {hi0:.4g}–{hi1:.4g} Hz (a mode at "
                "or beyond an edge?)"
            )
        at = ", ".join(f"{f:.4g}" for f in self.worst_hz)
        return f"away from the modes most at {at} Hz (modes the model lacks?)"

    def record(self) -> dict[str, Any]:
        """What run.json and modal_model.json keep of it."""
        return {
            "median_error": self.median_error,
            "noise_error": self.noise_error,
            "complex_error": self.complex_error,
            "share_near_modes": self.near_modes,
            "share_edges": self.edges,
            "share_elsewhere": self.elsewhere,
            "worst_hz": list(self.worst_hz),
            "unresolved_hz": list(self.unresolved_hz),
            "worst_modes_hz": list(self.worst_modes_hz),
            "left_out_hz": list(self.left_out_hz),
            "worst_nodes": list(self.worst_nodes),
            "cause": self.cause,
            "noise_nodes": list(self.noise_nodes),
            "sentence": self.sentence(),
        }


def misfit(
    frfs: FrfSet,
    fit: ModalFit,
    left_out_hz: Sequence[float] = (),
    noise_nodes: Sequence[int] = (),
) -> Misfit:
    """Where ``fit`` misses ``frfs`` (module docstring).

    Parameters
    ----------
    frfs : FrfSet
        The FRFs fitted (the lines of ``fit.frequency`` among theirs).
    fit : ModalFit
        The LSFD fit (:func:`racketdyn.modal.residues.fit_modal_constants`).
    left_out_hz : sequence of float
        Modes the identification left out although they stand in the data (clear peaks), Hz:
        those near where the misfit lies are named with it.
    noise_nodes : sequence of int
        Points whose FRFs measured noise alone
        (:attr:`racketdyn.measurement.quality.NoiseOnly.noise_nodes`): left out of the verdict
        and named in it, unless every FRF is noise.

    Returns
    -------
    Misfit
        The shares, the noise's and the complex constants' errors, and the verdict.
    """
    noise = set(noise_nodes)
    apart = tuple(n for n in frfs.nodes if n in noise)
    structure = [i for i, n in enumerate(frfs.nodes) if n not in apart]
    if apart and structure:
        frfs, fit = frfs.at_points(structure), fit.at_points(structure)
    else:
        apart = ()
    lines = np.isin(frfs.frequency, fit.frequency)
    data = frfs.values[:, lines]
    energy = np.sum(np.abs(data) ** 2, axis=1)
    energy = np.where(energy > 0, energy, np.inf)  # an FRF of zeros misses nothing
    residual = np.abs(data - fit.synthesised) ** 2 / energy[:, None]
    noise = np.sqrt(second_difference_noise(data) * data.shape[1] / energy)[np.isfinite(energy)]
    near, edge, edges_hz = _places(fit)
    total = float(residual.sum())
    places = (near, edge, ~near & ~edge)  # at the modes, at the edges, elsewhere
    shares = [float(residual[:, m].sum()) / total if total > 0 else 0.0 for m in places]
    unresolved = half_power_lines(fit.frequency_hz, fit.damping_ratio, fit.frequency) < 1.0
    per_mode = _per_mode(fit, residual.sum(axis=0), near)
    at_modes = float(per_mode.sum())
    worst = _worst(fit.frequency, residual.sum(axis=0), ~near & ~edge)
    found = Misfit(
        median_error=float(np.nanmedian(fit.error)) if np.isfinite(fit.error).any() else 0.0,
        noise_error=float(np.median(noise)) if noise.size else 0.0,
        complex_error=_complex_error(frfs, fit, data),
        near_modes=shares[0],
        edges=shares[1],
        elsewhere=shares[2],
        worst_hz=worst,
        edges_hz=edges_hz,
        unresolved_hz=tuple(float(f) for f in fit.frequency_hz[unresolved]),
        worst_modes_hz=tuple(
            float(fit.frequency_hz[k])
            for k in np.argsort(per_mode)[::-1][:WORST]
            if per_mode[k] > 0
        ),
        unresolved_share=float(per_mode[unresolved].sum()) / at_modes if at_modes > 0 else 0.0,
        left_out_hz=tuple(
            sorted(
                float(f) for f in left_out_hz if any(abs(f - w) <= NEAR_WORST * w for w in worst)
            )
        ),
        worst_nodes=tuple(
            int(frfs.nodes[i]) for i in np.argsort(-np.nan_to_num(fit.error))[:WORST]
        ),
        cause="",
        noise_nodes=apart,
    )
    return _judged(found)


def _places(
    fit: ModalFit,
) -> tuple[NDArray[np.bool_], NDArray[np.bool_], tuple[float, float, float, float]]:
    """Lines at the kept modes, lines at the band's edges (not at a mode), the edges' ranges."""
    f = fit.frequency
    spacing = float(np.median(np.diff(f)))
    near = np.zeros(f.size, dtype=bool)
    for fk, zk in zip(fit.frequency_hz, fit.damping_ratio, strict=True):
        near |= np.abs(f - fk) <= NEAR_WIDTHS * max(2 * zk * fk, spacing)
    width = EDGE_SHARE * float(f[-1] - f[0])
    low, high = float(f[0]), float(f[-1])
    edge = ((f <= low + width) | (f >= high - width)) & ~near
    return near, edge, (low, low + width, high - width, high)


def _per_mode(
    fit: ModalFit, residual: NDArray[np.float64], near: NDArray[np.bool_]
) -> NDArray[np.float64]:
    """The residual at each kept mode: its lines at the modes, each to the nearest mode."""
    nearest = np.argmin(np.abs(fit.frequency[:, None] - fit.frequency_hz[None, :]), axis=1)
    counted = np.bincount(nearest[near], weights=residual[near], minlength=fit.poles.size)
    return np.asarray(counted, dtype=float)


def _complex_error(frfs: FrfSet, fit: ModalFit, data: NDArray[np.complex128]) -> float:
    """Median error of the fit with complex constants on the same poles.

    ``R/(s − λ) + R*/(s − λ*)`` spans ``(a + b s)/((s − λ)(s − λ*))`` with real a, b: the real
    model's column and the same times s, each fitted with a real coefficient.
    """
    columns = design_columns(frfs, fit.poles, fit.frequency)
    n = fit.poles.size
    s = (2j * np.pi * fit.frequency)[:, None]
    extra = columns[:, :n] * s / np.abs(fit.poles)  # scaled like the rest (columns rescaled below)
    matrix = np.hstack([columns, extra])
    stacked = np.vstack([matrix.real, matrix.imag])
    scale = np.linalg.norm(stacked, axis=0)
    scale[scale == 0] = 1.0
    rhs = np.vstack([data.T.real, data.T.imag])
    solution, *_ = np.linalg.lstsq(stacked / scale, rhs, rcond=None)
    synthesised = (matrix @ (solution / scale[:, None])).T
    size = np.linalg.norm(data, axis=1)
    live = size > 0  # an FRF of zeros has no error to give
    errors = np.linalg.norm(data[live] - synthesised[live], axis=1) / size[live]
    return float(np.median(errors)) if errors.size else 0.0


def _worst(
    frequency: NDArray[np.float64], residual: NDArray[np.float64], away: NDArray[np.bool_]
) -> tuple[float, ...]:
    """The lines away from the modes with the largest residual, 2 % apart, largest first."""
    chosen: list[float] = []
    for i in np.argsort(np.where(away, residual, -1.0))[::-1]:
        if not away[i] or residual[i] <= 0 or len(chosen) == WORST:
            break
        if all(abs(frequency[i] - c) > 0.02 * frequency[i] for c in chosen):
            chosen.append(float(frequency[i]))
    return tuple(chosen)


def _judged(found: Misfit) -> Misfit:
    """The verdict: the noise's, else the place holding :data:`DOMINANT` of the misfit."""
    if found.median_error <= NOISE_FACTOR * found.noise_error:
        return replace(found, cause="noise")
    if found.median_error < NEGLIGIBLE:
        return replace(found, cause="negligible")
    if found.elsewhere >= DOMINANT:
        return replace(found, cause="missing modes")
    if found.edges >= DOMINANT:
        return replace(found, cause="band edges")
    if found.near_modes >= DOMINANT:
        if found.complex_error <= COMPLEX_GAIN * found.median_error:
            return replace(found, cause="complex modes")
        if found.unresolved_share >= DOMINANT:
            return replace(found, cause="unresolved peaks")
        return replace(found, cause="poles")
    return replace(found, cause="spread")
