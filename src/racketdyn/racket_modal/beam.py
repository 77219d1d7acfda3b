"""The built-in modal model: a free–free beam racket with a twisting head and a string membrane.

Derivation (documented in docs/develop.md, "Built-in modal model"):

* **Mass along the racket.**  Euler–Bernoulli beam elements of equal length along the long axis.
  The mass per unit length of each element is the smallest departure from a uniform racket
  (least squares) whose mass, balance point and moment of inertia about the balance point equal
  the racket's.  The cubic (Hermite) element reproduces rigid-body motion exactly, so the FE
  model has exactly those rigid-body properties.  Point masses are lumped on the nearest node
  after the stiffnesses are calibrated, so lead tape shifts the frequencies.
* **Bending.**  Uniform bending stiffness EI, scaled so that the first flexible (2-node bending)
  mode of the free beam sits at ``racket.first_bending_hz`` (paper, section 3.2: ≈ 120 Hz).
  With one free parameter, uniform EI is the least-assumption choice.
* **Twisting.**  Linear torsion elements; the roll inertia per unit length puts each section's
  mass on the frame hoop, at the string bed's half-width (at least a handle radius of 12.5 mm),
  scaled so the total equals the racket's roll inertia; uniform GJ is scaled so the first
  flexible twisting mode sits at ``racket.twisting_hz`` (docs/references.md: 361 Hz measured).
* **String bed.**  The fundamental mode of an elliptic membrane of the strings' mass (4 % of the
  racket, paper section 2) under the played bed's tension per unit width of the mains and
  crosses (``bed tension / spacing``, :attr:`racketdyn.racket.StringBed.bed_tension_n`), with
  the trial shape ``ψ = 1 − ρ²`` (ρ the elliptic radius); its Rayleigh quotient
  ``ω² = 3 (T_x/a² + T_y/b²) / σ`` gives the frequency.  The membrane is not coupled to the
  frame.
* **Damping.**  The identified damping of a freely supported racket is ≈ 0.5 % of critical;
  the approximate method does not use it (eq 12 gives the amplitude just after the impact).

The shape normal to the face at ``(x, y)`` is ``w(x)`` for bending, ``θ(x)·y`` for twisting and
``φ_m(x, y)`` for the membrane, each mass-normalised.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh

from racketdyn.errors import InputError
from racketdyn.modal.model import ModalModel
from racketdyn.racket import HeadEllipse, Racket

__all__ = [
    "HANDLE_RADIUS_M",
    "STRING_MASS_FRACTION",
    "beam_mass_per_length",
    "builtin_modal_model",
    "hoop_roll_inertia",
]

STRING_MASS_FRACTION = 0.04
"""Strings ≈ 4 % of the strung racket's mass (paper, section 2)."""
HANDLE_RADIUS_M = 0.0125
"""Radius of gyration of a handle section about the long axis (a 25 mm grip), m."""
DEFAULT_DAMPING_RATIO = 0.005
N_ELEMENTS = 68


def _nodes(length_m: float, n_elements: int) -> NDArray[np.float64]:
    return np.linspace(0.0, length_m, n_elements + 1)


def beam_mass_per_length(
    length_m: float,
    mass_kg: float,
    balance_m: float,
    inertia_cg_kgm2: float,
    n_elements: int = N_ELEMENTS,
) -> NDArray[np.float64]:
    """Mass per unit length of each element, kg/m, matching M, balance and I_G exactly.

    Minimum-norm departure from a uniform beam under the three moment constraints
    ``∫m dx = M``, ``∫m x dx = M x_G``, ``∫m x² dx = I_G + M x_G²`` (exact for piecewise-constant
    m).  Raises InputError if the racket's inertia cannot be met by a positive distribution.
    """
    x = _nodes(length_m, n_elements)
    lo, hi = x[:-1], x[1:]
    moments = np.vstack([hi - lo, (hi**2 - lo**2) / 2, (hi**3 - lo**3) / 3])
    target = np.array([mass_kg, mass_kg * balance_m, inertia_cg_kgm2 + mass_kg * balance_m**2])
    uniform = np.full(n_elements, mass_kg / length_m)
    correction = moments.T @ np.linalg.solve(moments @ moments.T, target - moments @ uniform)
    density = uniform + correction
    if np.any(density <= 0):
        raise InputError(
            f"racket: no positive mass distribution along {length_m} m has mass {mass_kg} kg, "
            f"balance {balance_m} m and inertia {inertia_cg_kgm2} kg·m² about it; check inertia_cg"
        )
    return np.asarray(density)


def _section_radius(head: HeadEllipse, x_mid: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.asarray(np.maximum(head.half_width_at(x_mid), HANDLE_RADIUS_M))


def hoop_roll_inertia(
    length_m: float, mass_kg: float, balance_m: float, inertia_cg_kgm2: float, head: HeadEllipse
) -> float:
    """Roll inertia (about the long axis) with each section's mass on the frame hoop, kg·m².

    ``I_roll = ∫ m(x) r(x)² dx`` with m(x) from :func:`beam_mass_per_length` and r(x) the string
    bed's half-width (at least :data:`HANDLE_RADIUS_M`).  Used when a racket file gives no
    roll inertia or twistweight.
    """
    density = beam_mass_per_length(length_m, mass_kg, balance_m, inertia_cg_kgm2)
    x = _nodes(length_m, density.size)
    mid, step = 0.5 * (x[:-1] + x[1:]), np.diff(x)
    return float(np.sum(density * _section_radius(head, mid) ** 2 * step))


def _bending_matrices(
    x: NDArray[np.float64], density: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Unit-EI stiffness and consistent mass matrices for Hermite beam elements (w, θ at nodes)."""
    n = x.size
    stiffness = np.zeros((2 * n, 2 * n))
    mass = np.zeros((2 * n, 2 * n))
    for e, (h, rho) in enumerate(zip(np.diff(x), density, strict=True)):
        k = (
            np.array(
                [
                    [12, 6 * h, -12, 6 * h],
                    [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                    [-12, -6 * h, 12, -6 * h],
                    [6 * h, 2 * h * h, -6 * h, 4 * h * h],
                ]
            )
            / h**3
        )
        m = (
            rho
            * h
            / 420
            * np.array(
                [
                    [156, 22 * h, 54, -13 * h],
                    [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                    [54, 13 * h, 156, -22 * h],
                    [-13 * h, -3 * h * h, -22 * h, 4 * h * h],
                ]
            )
        )
        dofs = slice(2 * e, 2 * e + 4)
        stiffness[dofs, dofs] += k
        mass[dofs, dofs] += m
    return stiffness, mass


def _torsion_matrices(
    x: NDArray[np.float64], roll_density: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Unit-GJ stiffness and consistent inertia matrices for linear torsion elements."""
    n = x.size
    stiffness = np.zeros((n, n))
    inertia = np.zeros((n, n))
    for e, (h, j) in enumerate(zip(np.diff(x), roll_density, strict=True)):
        stiffness[e : e + 2, e : e + 2] += np.array([[1, -1], [-1, 1]]) / h
        inertia[e : e + 2, e : e + 2] += j * h / 6 * np.array([[2, 1], [1, 2]])
    return stiffness, inertia


def _flexible_modes(
    stiffness: NDArray[np.float64], mass: NDArray[np.float64], n_rigid: int, n_modes: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Lowest flexible eigenpairs (ω², mass-normalised vectors) of a free structure."""
    values, vectors = eigh(stiffness, mass, subset_by_index=[0, n_rigid + n_modes - 1])
    return values[n_rigid:], vectors[:, n_rigid:]


def builtin_modal_model(racket: Racket, n_bending: int = 2) -> ModalModel:
    """The built-in free–free modal model of a racket (see the module docstring).

    Parameters
    ----------
    racket : Racket
        Mass properties, head, strings, point masses and the two frequency targets.
    n_bending : int
        Number of flexible bending modes (2: the 2- and 3-node modes).

    Returns
    -------
    ModalModel
        ``n_bending`` bending modes, one twisting mode and the string-bed mode, sampled on the
        beam's nodes along the axis and across the head.
    """
    x = _nodes(racket.length_m, N_ELEMENTS)
    density = beam_mass_per_length(
        racket.length_m, racket.mass_kg, racket.balance_m, racket.inertia_cg_kgm2, N_ELEMENTS
    )
    mid, step = 0.5 * (x[:-1] + x[1:]), np.diff(x)
    nearest = [int(np.argmin(np.abs(x - p.x_m))) for p in racket.point_masses]

    # Stiffnesses are calibrated on the racket as described (without point masses): the targets
    # are its measured frequencies; lead tape then shifts the modes, as it would on the racket.
    stiffness, mass = _bending_matrices(x, density)
    bare_omega2, _ = _flexible_modes(stiffness, mass, 2, n_bending)
    bending_stiffness = (2 * np.pi * racket.first_bending_hz) ** 2 / bare_omega2[0]
    for node, p in zip(nearest, racket.point_masses, strict=True):
        mass[2 * node, 2 * node] += p.mass_kg
    omega2, vectors = _flexible_modes(stiffness, mass, 2, n_bending)
    bending_omega = np.sqrt(omega2 * bending_stiffness)
    bending_shapes = vectors[0::2, :]  # displacement DOFs, mass-normalised

    roll_density = density * _section_radius(racket.head, mid) ** 2
    roll_density *= racket.roll_inertia_kgm2 / np.sum(roll_density * step)
    t_stiffness, t_inertia = _torsion_matrices(x, roll_density)
    bare_t_omega2, _ = _flexible_modes(t_stiffness, t_inertia, 1, 1)
    torsional_stiffness = (2 * np.pi * racket.twisting_hz) ** 2 / bare_t_omega2[0]
    for node, p in zip(nearest, racket.point_masses, strict=True):
        t_inertia[node, node] += p.mass_kg * p.y_m**2
    t_omega2, t_vectors = _flexible_modes(t_stiffness, t_inertia, 1, 1)
    twist_omega = np.sqrt(t_omega2[0] * torsional_stiffness)
    twist_shape = t_vectors[:, 0]

    head, strings = racket.head, racket.strings
    string_mass = strings.mass_kg or STRING_MASS_FRACTION * racket.mass_kg
    spacing_mains, spacing_crosses = strings.spacing_m(head)
    areal_density = string_mass / head.area_m2
    membrane_omega = np.sqrt(
        3.0
        * (
            strings.bed_tension_n / spacing_mains / head.half_length_m**2
            + strings.bed_tension_n / spacing_crosses / head.half_width_m**2
        )
        / areal_density
    )
    membrane_scale = np.sqrt(3.0 / string_mass)  # ∫σψ² dA = m_s / 3 for ψ = 1 − ρ²

    locations = _sample_locations(x, head)
    along = np.interp(locations[:, 0], x, np.arange(x.size))  # fractional node index
    lower = np.clip(np.floor(along).astype(int), 0, x.size - 2)
    frac = along - lower

    def on_nodes(values: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(values[lower] * (1 - frac) + values[lower + 1] * frac)

    rho = head.normalised_radius(locations)
    columns = [on_nodes(bending_shapes[:, k]) for k in range(n_bending)]
    columns.append(on_nodes(twist_shape) * locations[:, 1])  # roll about the long axis
    columns.append(np.where(rho < 1.0, membrane_scale * (1.0 - rho**2), 0.0))
    frequency = np.concatenate([bending_omega, [twist_omega, membrane_omega]]) / (2 * np.pi)
    names = (
        *(f"{k + 2}-node bending" for k in range(n_bending)),
        "2-node twisting",
        "string-bed membrane",
    )
    kinds = (*("bending",) * n_bending, "twisting", "string-bed")
    order = np.argsort(frequency)
    return ModalModel(
        frequency=frequency[order],
        damping_ratio=np.full(frequency.size, DEFAULT_DAMPING_RATIO),
        locations=locations,
        mode_shapes=np.column_stack(columns)[:, order],
        names=tuple(names[i] for i in order),
        kinds=tuple(kinds[i] for i in order),
        support="free",
        source=f"built-in beam model of {racket.name}",
        metadata={
            "bending_stiffness_nm2": float(bending_stiffness),
            "torsional_stiffness_nm2_per_rad": float(torsional_stiffness),
            "string_mass_kg": float(string_mass),
            "elements": N_ELEMENTS,
        },
    )


def _sample_locations(x: NDArray[np.float64], head: HeadEllipse) -> NDArray[np.float64]:
    """Beam nodes on the axis and on the handle's sides, a 1 cm lattice across the head, and
    two rings on the frame.

    The handle's sides (y = ±:data:`HANDLE_RADIUS_M`, nodes up to the throat) give the twist
    along the handle, where a hand reads the handle's turn (:class:`racketdyn.hand.Hand`):
    without them the interpolation took it from the head, half the beam's.

    The rings (on the bed's edge and 8 % outside it, every 5°) pin the membrane shape to zero
    on the frame, so the interpolation neither bulges past the edge nor extrapolates onto it.
    """
    points = [np.column_stack([x, np.zeros_like(x)])]
    # the handle's sides (the hand's grip reads the handle's turn there: racketdyn.hand)
    handle = x[x <= head.throat_x_m]
    for side in (-HANDLE_RADIUS_M, HANDLE_RADIUS_M):
        points.append(np.column_stack([handle, np.full(handle.size, side)]))
    in_head = x[(x > head.throat_x_m) & (x < head.tip_x_m)]
    for xi in in_head:
        half = float(head.half_width_at(xi))
        count = max(int(np.ceil(half / 0.01)), 1)
        offsets = np.linspace(-half, half, 2 * count + 1)[1:-1]
        offsets = offsets[np.abs(offsets) > 1e-12]
        points.append(np.column_stack([np.full(offsets.size, xi), head.centre_y_m + offsets]))
    angle = np.deg2rad(np.arange(0.0, 360.0, 5.0))
    for scale in (1.0, 1.08):
        ring = np.column_stack(
            [
                head.centre_x_m + scale * head.half_length_m * np.cos(angle),
                head.centre_y_m + scale * head.half_width_m * np.sin(angle),
            ]
        )
        points.append(ring[(ring[:, 0] > 0) & (np.abs(ring[:, 1]) > 1e-12)])
    return np.vstack(points)
