"""Public test helper: FRFs of a free–free Euler–Bernoulli beam, with noise, on any line in space.

The oracle of the general-structure identification tests (issue 12).  Everything is analytic:

- natural frequencies ``f_n = (β_n L)² / (2π L²) · √(EI / ρA)`` with ``β_n L`` the roots of
  ``cos βL · cosh βL = 1`` (4.7300, 7.8532, 10.9956, 14.1372, 17.2788; e.g. Blevins, *Formulas
  for natural frequency and mode shape*, table 8-1, "free–free");
- mode shapes ``φ_n(s) = cosh βs + cos βs − σ_n (sinh βs + sin βs)``,
  ``σ_n = (cosh βL − cos βL) / (sinh βL − sin βL)``, mass-normalised (``∫ ρA φ² ds = 1``);
- the two rigid-body modes (translation and rotation about the centre of mass), which a free
  structure adds to every FRF below the first flexible mode.

The beam lies along a unit ``direction`` in the lab's frame from ``origin``; it bends in a
plane that holds the direction, and a transducer measures along ``±`` the bending direction
(``sensor_sign = -1``: an accelerometer mounted against the hammer, e.g. in −z).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from racketdyn.measurement.records import FrfSet

# Aluminium bar 0.8 m × 30 mm × 8 mm (bending about its weak axis)
LENGTH_M = 0.8
EI_NM2 = 70e9 * 0.030 * 0.008**3 / 12
MASS_PER_LENGTH = 2700.0 * 0.030 * 0.008


def beta_l(n_modes: int) -> NDArray[np.float64]:
    """The first ``n_modes`` roots of ``cos x cosh x = 1`` above 0 (free–free beam)."""
    roots = []
    for n in range(1, n_modes + 1):
        guess = (n + 0.5) * np.pi
        roots.append(brentq(lambda x: np.cos(x) * np.cosh(x) - 1.0, guess - 0.5, guess + 0.5))
    return np.asarray(roots)


def natural_frequencies(n_modes: int) -> NDArray[np.float64]:
    """Analytic free–free natural frequencies of the bar, Hz."""
    return np.asarray(
        beta_l(n_modes) ** 2 / (2 * np.pi * LENGTH_M**2) * np.sqrt(EI_NM2 / MASS_PER_LENGTH)
    )


def mode_shapes(s: NDArray[np.float64], n_modes: int) -> NDArray[np.float64]:
    """Mass-normalised flexible shapes at distances ``s`` (m) along the bar, (n_s, n_modes)."""
    b = beta_l(n_modes) / LENGTH_M
    sigma = (np.cosh(b * LENGTH_M) - np.cos(b * LENGTH_M)) / (
        np.sinh(b * LENGTH_M) - np.sin(b * LENGTH_M)
    )

    def raw(x: NDArray[np.float64]) -> NDArray[np.float64]:
        bx = b * x[:, None]
        return np.asarray(np.cosh(bx) + np.cos(bx) - sigma * (np.sinh(bx) + np.sin(bx)))

    fine = np.linspace(0.0, LENGTH_M, 4001)
    norm = np.sqrt(MASS_PER_LENGTH * np.trapezoid(raw(fine) ** 2, fine, axis=0))
    return np.asarray(raw(np.asarray(s, float)) / norm)


def rigid_shapes(s: NDArray[np.float64]) -> NDArray[np.float64]:
    """Mass-normalised rigid-body shapes (translation, rotation about the centre), (n_s, 2)."""
    mass = MASS_PER_LENGTH * LENGTH_M
    inertia = mass * LENGTH_M**2 / 12
    s = np.asarray(s, float)
    return np.column_stack(
        [np.full_like(s, 1 / np.sqrt(mass)), (s - LENGTH_M / 2) / np.sqrt(inertia)]
    )


@dataclass(frozen=True)
class BeamTest:
    """A synthesised test and its truth."""

    frfs: FrfSet
    frequency_hz: NDArray[np.float64]
    damping_ratio: NDArray[np.float64]
    shapes: NDArray[np.float64]  # at the FRF points, mass-normalised, (n_points, n_modes)


# 13 parameters: a test's knobs, each set alone by keyword in the tests (the bar's line, its
# modes, the transducers, the noise, the axis); grouping them would only wrap the keywords
def beam_frfs(
    s: NDArray[np.float64] | list[float],
    reference_s: float,
    *,
    direction: tuple[float, float, float] = (1.0, 0.0, 0.0),
    origin: tuple[float, float, float] = (0.0, 0.0, 0.0),
    n_modes: int = 5,
    damping_ratio: float | NDArray[np.float64] = 0.008,
    sensor_sign: float = 1.0,
    noise: float = 0.01,
    floor: float = 2e-4,
    top_hz: float = 1250.0,
    lines: int = 5001,
    roving: str = "hammer",
    seed: int = 0,
) -> BeamTest:
    """Accelerances of the free bar at the points ``s`` against the reference at ``reference_s``.

    Parameters
    ----------
    s : array_like
        Distances of the points along the bar, m (the driving point is there when one equals
        ``reference_s``).
    reference_s : float
        The fixed transducer (roving hammer) or fixed hammer (``roving="accelerometer"``), m.
    direction, origin : tuple of float
        The bar's line in the lab frame (unit vector, and where s = 0 is), m.
    n_modes : int
        Flexible modes included (five reach 872 Hz).
    damping_ratio : float or array
        Modal damping, fraction of critical.
    sensor_sign : float
        +1, or −1 for a transducer measuring against the hammer's direction.
    noise : float
        Relative complex Gaussian noise on every line (0.01: 1 %).
    floor : float
        Additive noise, as a fraction of each FRF's largest magnitude.
    top_hz, lines : float, int
        The frequency axis 0…top_hz, Hz.
    roving : {"hammer", "accelerometer"}
        Which transducer moved (by reciprocity the same FRFs; recorded in metadata).
    seed : int
        Noise seed.
    """
    s = np.atleast_1d(np.asarray(s, float))
    rng = np.random.default_rng(seed)
    f_n = natural_frequencies(n_modes)
    zeta = np.broadcast_to(np.asarray(damping_ratio, float), f_n.shape).copy()
    phi = mode_shapes(s, n_modes)
    frequency = np.linspace(0.0, top_hz, lines)
    values = _accelerances(s, reference_s, phi, (f_n, zeta), frequency) * sensor_sign
    values = _with_noise(values, rng, noise, floor)
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    locations = np.asarray(origin, float) + s[:, None] * d
    nodes = tuple(range(1, s.size + 1))
    matches = np.flatnonzero(np.isclose(s, reference_s))
    reference_node = nodes[matches[0]] if matches.size else 100
    frfs = FrfSet(
        frequency=frequency,
        values=values,
        frf_type="accelerance",
        nodes=nodes,
        locations=locations,
        reference_node=reference_node,
        reference_location=tuple(np.asarray(origin, float) + reference_s * d),
        source=f"free beam along {tuple(direction)}, {s.size} points",
        metadata={"roving": roving},
    )
    return BeamTest(frfs, f_n, zeta, phi)


def _accelerances(
    s: NDArray[np.float64],
    reference_s: float,
    phi: NDArray[np.float64],
    modes: tuple[NDArray[np.float64], NDArray[np.float64]],
    frequency: NDArray[np.float64],
) -> NDArray[np.complex128]:
    """The exact accelerances at ``s`` against ``reference_s``: the flexible modes (shapes
    ``phi`` at ``s``, frequencies and damping ratios ``modes``) plus the rigid body."""
    f_n, zeta = modes
    n_modes = f_n.size
    phi_ref = mode_shapes(np.array([reference_s]), n_modes)[0]
    rigid = rigid_shapes(s) @ rigid_shapes(np.array([reference_s]))[0]
    w = 2 * np.pi * frequency
    wn = 2 * np.pi * f_n
    modal = (phi * phi_ref)[:, None, :] * (
        -(w[:, None] ** 2) / (wn**2 - w[:, None] ** 2 + 2j * zeta * wn * w[:, None])
    )[None]
    return np.asarray(modal.sum(-1) + rigid[:, None])  # rigid body: 1/m_eff at every line


def _with_noise(
    values: NDArray[np.complex128], rng: np.random.Generator, noise: float, floor: float
) -> NDArray[np.complex128]:
    """Relative complex Gaussian noise on every line, plus a floor relative to each FRF's
    largest magnitude."""
    scale = np.abs(values).max(axis=1, keepdims=True)
    return np.asarray(
        values
        * (
            1
            + noise
            * (rng.standard_normal(values.shape) + 1j * rng.standard_normal(values.shape))
            / np.sqrt(2)
        )
        + floor
        * scale
        * (rng.standard_normal(values.shape) + 1j * rng.standard_normal(values.shape))
        / np.sqrt(2)
    )
