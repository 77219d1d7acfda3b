"""Poles from FRFs against several references: the poly-reference LSCF (pLSCF, PolyMAX-type).

A single-reference LSCF (:func:`racketdyn.modal.poles.stabilisation`) fits one common scalar
denominator to every FRF: two modes closer than their half-power width that one reference
sees alike read as one pole.  Several references see two such modes differently (their
participation factors differ), and a right matrix-fraction model of all of them at once tells
them apart (Guillaume, Verboven, Vanlanduit, Van der Auweraer and Peeters, "A poly-reference
implementation of the least-squares complex frequency-domain estimator", IMAC XXI, 2003;
Peeters, Van der Auweraer, Guillaume and Leuridan, "The PolyMAX frequency-domain method",
Shock and Vibration 11, 2004)::

    H_o(ω_f) ≈ N_o(Ω_f) D(Ω_f)⁻¹,   N_o(Ω) = Σ_r Ω^r β_or (1 × n_r),
    D(Ω) = Σ_r Ω^r α_r (n_r × n_r),   r = 0 … m,

``H_o`` the row of output (point) o against the n_r references.  A matrix order m has
``m · n_r`` poles.  Everything else is the scalar LSCF's (its module docstring): the band zoomed
onto the unit circle with complex coefficients (each pole one mode), the Toeplitz normal
equations from FFTs, the numerators eliminated once for every order, the noise bias removed
(``σ² (1 − (m+1)/F) R ⊗ diag(Σ_o σ²_oj)``), ``α_m = I``.  The poles are the eigenvalues of the
block companion matrix of ``D``; at a root z_k, ``D(z_k)`` has a right null vector ``v`` (the
participation of the references) and a left one ``u``, and the residue of point o against
reference j is ``(N_o(z_k) v)(u_j^* / u^H D'(z_k) v) / (z_k Δt)`` (s-domain): a mode shape
times a participation factor.

The result is a :class:`~racketdyn.modal.poles.Stabilisation` like the scalar one, whose
``residues`` stack the references (row ``j · n_points + p``: point p against reference j), so
the stability classes and :func:`~racketdyn.modal.poles.select_poles` compare shapes and
participations together.

Orders and fragments
    ``max_order`` is the matrix polynomial's degree m, as PolyMAX counts its model order and
    as the scalar LSCF's ``max_order`` is its polynomial's degree; order m has ``m · n_r``
    poles.  Pushed too high, the fit splits a mode into fragments that take over from it
    order after order: on meca0062's aircraft (68 points, 3 accelerometers, 9.4–200 Hz,
    1,601 lines) matrix orders 1–25, 1–30, 1–35 and 1–40 all give the lab's 13 poles with its
    125.21/125.58 Hz pair apart, while from order 38 on a 125.65 Hz fragment with the
    125.60 Hz mode's participations (stacked MAC 0.885) follows it, and at 1–60 it is kept.
    :data:`DEFAULT_MAX_ORDER` (30) sits in the middle of that range; the scalar LSCF's 60
    would keep fragments.

Why not a library's: sdypy-EMA (0.31) has the single-reference LSCF only; pyOMA2's pLSCF works
on output spectra (operational modal analysis) over the whole 0 … fs/2 band; strid's
``PolyReferenceLSCF`` (0.4.3, 2022) fits the whole 0 … fs/2 band with real coefficients and
no noise compensation.  None fits a chosen band of FRFs with the scalar LSCF's noise
compensation and stabilisation, which this shares.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from racketdyn.errors import require_whole
from racketdyn.measurement.records import FrfReferences, FrfSet
from racketdyn.modal.poles import (
    Stabilisation,
    _band,
    _check_stabilisation_options,
    _uneven_r,
    _ZDomain,
    diagram_fields,
    noise_bound,
    second_difference_noise,
)
from racketdyn.numerics import one_blas_thread

__all__ = ["DEFAULT_MAX_ORDER", "poly_stabilisation"]

logger = logging.getLogger(__name__)

DEFAULT_MAX_ORDER = 30
"""The highest matrix order by default (module docstring, "Orders and fragments")."""


def poly_stabilisation(
    frfs: FrfReferences | Sequence[FrfSet],
    band_hz: tuple[float, float],
    max_order: int = DEFAULT_MAX_ORDER,
    *,
    frequency_tolerance: float = 0.01,
    damping_tolerance: float = 0.05,
    min_mac: float = 0.98,
    noise_compensation: bool = True,
) -> Stabilisation:
    """pLSCF poles at every matrix order over a band, classed by stability (module docstring).

    Parameters
    ----------
    frfs : FrfReferences or sequence of FrfSet
        The FRFs of the same points against each reference.
    band_hz : tuple of float
        Lowest and highest frequency to fit, Hz (the lines between them, inclusive).
    max_order : int
        Highest matrix order (the degree of ``D``; ``n_references`` poles an order): orders
        ``1 … max_order`` are computed.  The band must hold more than
        ``2 · max_order · n_references`` lines.
    frequency_tolerance, damping_tolerance, min_mac : float
        Stability tolerances between consecutive orders, as
        :func:`~racketdyn.modal.poles.stabilisation`'s (the MAC is of the stacked residues:
        shape and participation).
    noise_compensation : bool
        Remove the bias that noise on the FRFs puts on the damping.

    Returns
    -------
    Stabilisation
        ``orders`` and ``order`` are matrix orders; ``residues`` are
        shaped (n_references · n_points, n_poles), reference by reference; ``nodes`` and
        ``noise_rms`` follow the same rows; ``metadata`` holds ``method`` ("pLSCF"),
        ``references`` and ``matrix_orders``.

    Raises
    ------
    InputError
        Sets on other points or lines (:class:`~racketdyn.measurement.records.FrfReferences`),
        a band outside the FRFs or with too few lines, tolerances out of range.
    """
    references = frfs if isinstance(frfs, FrfReferences) else FrfReferences(tuple(frfs))
    max_order = require_whole("`max_order`", max_order)
    n_refs = len(references.sets)
    top = max_order
    tolerances = (frequency_tolerance, damping_tolerance, min_mac)
    first = references.sets[0]
    _check_stabilisation_options(tolerances, "uniform", first)
    bands = [_band(s, band_hz, top * n_refs) for s in references.sets]
    values = np.stack([b.values for b in bands], axis=1)  # (n_o, n_r, F)
    domain = _ZDomain.of(bands[0].frequency, first.exponential_window_s)
    matrix_orders = np.arange(1, top + 1)
    logger.debug(
        "pLSCF: %d points × %d references × %d lines, %.1f–%.1f Hz, matrix orders 1–%d",
        values.shape[0],
        n_refs,
        domain.n_lines,
        domain.low_hz,
        domain.high_hz,
        top,
    )
    with one_blas_thread():
        equations = _normal_equations(values, domain.theta, top, even=domain.even)
        fits = [
            _poles_at(equations, m, domain, compensate=noise_compensation)
            for m in matrix_orders.tolist()
        ]
    orders = matrix_orders
    order_flat = np.concatenate(
        [np.full(p.size, o) for o, (p, _) in zip(orders, fits, strict=True)]
    )
    pole_flat = np.concatenate([p for p, _ in fits]).astype(complex)
    residues = np.concatenate([r for _, r in fits], axis=1)
    noise = np.sqrt(equations.noise_variance).T.reshape(-1)  # (n_r · n_o,), reference-major
    return Stabilisation(
        **diagram_fields(domain, orders, order_flat, pole_flat, residues, tolerances),
        noise_rms=noise,
        frf_type=first.frf_type,
        exponential_window_s=first.exponential_window_s,
        nodes=tuple(n for _ in range(n_refs) for n in references.nodes),
        source=references.source,
        metadata={
            "method": "pLSCF",
            "references": list(references.references),
            "matrix_orders": [1, top],
            "lines": domain.n_lines,
            "weighting": "uniform",
            "noise_compensation": bool(noise_compensation),
            "evenly_spaced": domain.even,
        },
    )


@dataclass(frozen=True)
class _MatrixEquations:
    """The pLSCF normal equations at the highest matrix order, reduced for every order."""

    reduced: list[NDArray[np.complex128]]  # order m: ((m+1) n_r, (m+1) n_r)
    rows: NDArray[np.complex128]  # rows[k, o, :] = X_o[k, :], X_o = L⁻¹ S_o
    inverse_h: NDArray[np.complex128] | None  # L⁻ᴴ (None: R = F·I)
    r_matrix: NDArray[np.complex128]  # R ((n+1) × (n+1))
    noise_variance: NDArray[np.float64]  # (n_o, n_r), per line
    n_lines: int
    n_refs: int


def _normal_equations(
    values: NDArray[np.complex128], theta: NDArray[np.float64], n: int, *, even: bool
) -> _MatrixEquations:
    """``T``, ``X_o = L⁻¹ S_o`` at matrix order n (column index ``s · n_r + j``), and the noise.

    ``S_o[r, (s, j)] = −Σ_f H_oj Ω_f^(s−r)`` and ``T[(r, i), (s, j)] = Σ_o Σ_f H_oi^* H_oj
    Ω_f^(s−r)`` are block Toeplitz: their generators are FFTs of the FRFs (even lines) or sums.
    """
    n_o, n_r, n_lines = values.shape
    lags = np.arange(-n, n + 1)
    cross = np.einsum("oif,ojf->ijf", values.conj(), values)  # (n_r, n_r, F)
    if even:
        gen_s = -np.fft.ifft(values, axis=2)[:, :, lags % n_lines] * n_lines
        gen_t = np.fft.ifft(cross, axis=2)[:, :, lags % n_lines] * n_lines
    else:
        powers = np.exp(1j * np.outer(theta, lags))
        gen_s = -(values @ powers)
        gen_t = cross @ powers
    lag = np.arange(n + 1)[None, :] - np.arange(n + 1)[:, None] + n  # s − r + n, [r, s]
    size = (n + 1) * n_r
    # T[(r, i), (s, j)] = gen_t[i, j, lag[r, s]]
    t_matrix = gen_t[:, :, lag].transpose(2, 0, 3, 1).reshape(size, size)
    # S_o[r, (s, j)] = gen_s[o, j, lag[r, s]] -> s_stack[r, o, (s, j)]
    s_stack = gen_s[:, :, lag].transpose(2, 0, 3, 1).reshape(n + 1, n_o, size)
    inverse_h: NDArray[np.complex128] | None = None
    r_matrix: NDArray[np.complex128]
    if even:
        r_matrix = np.asarray(n_lines * np.eye(n + 1, dtype=complex))
        rows = s_stack / np.sqrt(n_lines)
    else:
        r_matrix, inverse_h = _uneven_r(theta, lags, lag)
        rows = (inverse_h.conj().T @ s_stack.reshape(n + 1, -1)).reshape(n + 1, n_o, size)
    rows = np.ascontiguousarray(rows)
    reduced: list[NDArray[np.complex128]] = []
    accumulated = np.zeros((size, size), dtype=complex)
    for m in range(n + 1):
        accumulated += rows[m].conj().T @ rows[m]
        c = (m + 1) * n_r
        reduced.append(t_matrix[:c, :c] - accumulated[:c, :c])
    # Noise per FRF (the scalar LSCF's estimate), capped by the smallest eigenvalue of the
    # whitened reduced matrix at the highest order (every reference's total at once).
    per_frf = second_difference_noise(values)  # (n_o, n_r)
    totals = per_frf.sum(axis=0)
    if totals.min() > 0:
        if inverse_h is None:
            whitened = reduced[n] / n_lines
        else:
            big = np.kron(inverse_h, np.eye(n_r))
            whitened = big.conj().T @ reduced[n] @ big
        bound = noise_bound(whitened, n_lines, n, n_o)
        if bound < totals.min():
            per_frf = per_frf * (bound / totals.min())
    return _MatrixEquations(
        reduced=reduced,
        rows=rows,
        inverse_h=inverse_h,
        r_matrix=r_matrix,
        noise_variance=np.asarray(per_frf, dtype=float),
        n_lines=n_lines,
        n_refs=n_r,
    )


def _poles_at(
    equations: _MatrixEquations, m: int, domain: _ZDomain, *, compensate: bool
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """The poles of matrix order m kept by the band (ascending |λ|) and their residues,
    shaped (n_r · n_o, n_kept), reference-major."""
    n_r, n_lines = equations.n_refs, equations.n_lines
    n_o = equations.rows.shape[1]
    c = (m + 1) * n_r
    reduced = equations.reduced[m]
    if compensate:
        share = equations.noise_variance.sum(axis=0) * (1 - (m + 1) / n_lines)
        reduced = reduced - np.kron(equations.r_matrix[: m + 1, : m + 1], np.diag(share))
    alpha = np.zeros((c, n_r), dtype=complex)
    alpha[m * n_r :] = np.eye(n_r)
    head = reduced[: m * n_r, : m * n_r]
    try:
        alpha[: m * n_r] = np.linalg.solve(head, -reduced[: m * n_r, m * n_r :])
    except np.linalg.LinAlgError:
        alpha[: m * n_r] = np.linalg.lstsq(head, -reduced[: m * n_r, m * n_r :], rcond=None)[0]
    blocks = alpha.reshape(m + 1, n_r, n_r)  # D(z) = Σ_r blocks[r] z^r, blocks[m] = I
    companion = np.zeros((m * n_r, m * n_r), dtype=complex)
    for r in range(m):  # first block row: −α_(m−1) … −α_0
        companion[:n_r, r * n_r : (r + 1) * n_r] = -blocks[m - 1 - r]
    companion[n_r:, : (m - 1) * n_r] += np.eye((m - 1) * n_r)
    z = np.asarray(np.linalg.eigvals(companion), dtype=complex)
    z = z[domain.accept(z)]
    pole = domain.to_pole(z)
    index = np.argsort(np.abs(pole))
    z, pole = z[index], pole[index]
    # numerators β_o = −R⁻¹ S_o α = −L⁻ᴴ (X_o α): (m + 1, n_o, n_r)
    y = np.einsum("kop,pj->koj", equations.rows[: m + 1, :, :c], alpha)
    if equations.inverse_h is None:
        beta = -y / np.sqrt(n_lines)
    else:
        beta = -np.einsum("rk,koj->roj", equations.inverse_h[: m + 1, : m + 1], y)
    # at every root at once: D(z_k), D'(z_k), their null vectors, N_o(z_k) v
    powers = np.arange(m + 1)
    zr = z[:, None] ** powers  # (K, m + 1)
    d_value = np.einsum("kr,rij->kij", zr, blocks)
    d_slope = np.einsum("kr,rij->kij", powers[1:] * zr[:, :-1], blocks[1:])
    left, _, right_h = np.linalg.svd(d_value)
    u, v = left[:, :, -1], right_h[:, -1, :].conj()  # (K, n_r): left and right null vectors
    denominator = np.einsum("ki,kij,kj->k", u.conj(), d_slope, v)
    denominator = np.where(denominator == 0, np.finfo(float).tiny, denominator)
    shape = np.einsum("kr,roj,kj->ko", zr, beta, v)  # N_o(z_k) v
    participation = u.conj() / (denominator * z * domain.time_step)[:, None]
    residues = (participation[:, :, None] * shape[:, None, :]).reshape(z.size, n_r * n_o).T
    return pole, residues
