"""A ball fixed on the rig's strings: the paper's compound ball–racket test (section 3.2).

Kawazoe glued a ball to the centre of the string face and ran the modal test again (Figs 8–9).
:func:`ball_on_strings` adds that ball to a :class:`~racketdyn.rig.model.RigModel`: two more
degrees of freedom, the membrane's dip under the ball's patch (:mod:`racketdyn.rig.patch`: the
string net's deflection under a patch, one more Ritz function) and the ball's displacement
normal to the face.  The ball is rigid against the strings it presses: its own one-sided
spring and a dashpot join it to the patch's mean displacement (the frame's motion carried
under the bed, the membrane's ten functions and the dip, which is 1 on the patch).  The rig's
membrane is the string bed here, so the spring is the ball's law alone (not the compound
F_GB of the approximate method): its tangent at a small preload (a stuck ball presses on the
strings).  e_BG is the bounce of the ball on head-clamped strings, its loss the ball's and the
strings' together, so the dashpot (:func:`racketdyn.impact.compound.restitution_damping_ratio`
for e_BG) spans both, from the ball to the frame's motion under the patch, ``2 ζ √(k_s m_B)``
with k_s the ball's spring in series with the rig's bed under the patch (frame held):
``compound``'s dashpot on its ball–string spring.  Without the dip the ten smooth functions,
pressed anywhere under the ball, are as stiff as the net pushed over the ball's whole width
(the ball mode of the built-in racket 129.6 Hz against ``compound``'s 98.6 Hz: issue 22).

The dip's Ritz terms: its stiffness against itself and the membrane's functions
``∫ (T_x g_x ψ_x + T_y g_y ψ_y) dA`` (none against the frame's carried motion: for a linear
carried field it vanishes, integrating by parts as the rig's other membrane terms do), and its
mass against every racket DOF ``∫ σ g u dA`` with the membrane's areal density σ.

The modes are found as in :func:`racketdyn.rig.model.rig_model` (real modes of (K, M), modal
damping φᵀCφ/(2ω)), so the rig with the ball *is* its modal truth again: hammer records
simulated on it identify back to these modes.  The ball's dashpot is not proportional: the
modal damping of the ball mode is the classical diagonal approximation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh

from racketdyn.errors import InputError, require_positive
from racketdyn.racket import as_locations
from racketdyn.racket_modal.shapes import BALL_MODE_NAME
from racketdyn.rig.model import RigModel, _membrane_functions
from racketdyn.rig.patch import BallPatch

__all__ = ["BALL_MODE_NAME", "DIP_MODE_NAME", "StuckBall", "ball_on_strings"]

DIP_MODE_NAME = "strings under the ball"
"""The mode of the membrane's dip under the ball (kind ``string-bed``)."""


@dataclass(frozen=True)
class StuckBall:
    """A ball fixed on the strings, as :func:`ball_on_strings` takes it.

    Attributes
    ----------
    location : tuple of float
        The ball's point (x, y) on the string bed, m.
    mass_kg : float
        m_B, kg.
    stiffness_n_per_m : float
        The ball's own spring against the strings, N/m.
    damping_ratio : float
        ζ of the ball on head-clamped strings (from e_BG): the dashpot is ``2 ζ √(k_s m_B)``,
        N·s/m, k_s the ball's spring in series with the bed under the patch.
    patch_radius_m : float
        Radius of the patch of strings the ball presses, m.
    """

    location: tuple[float, float]
    mass_kg: float
    stiffness_n_per_m: float
    damping_ratio: float
    patch_radius_m: float


def ball_on_strings(model: RigModel, ball: StuckBall) -> RigModel:
    """The rig with a ball fixed on its strings.

    Parameters
    ----------
    model : RigModel
        The racket on its support, without a ball.
    ball : StuckBall
        Where the ball sits, its mass, spring, damping and patch.

    Returns
    -------
    RigModel
        Two more DOFs (``dofs["patch"]``, ``dofs["ball"]``), its modes re-solved; the ball mode
        is named :data:`BALL_MODE_NAME` (kind ``other``), the dip's own (the strings under the
        ball against their tension, kHz) :data:`DIP_MODE_NAME`; the others are named as the
        rig names its modes, by where their strain energy is (strings or the rest), after the
        bare racket's mode of that kind they project on most (mass-weighted): the ball moves
        the played bed's veering pair, the membrane and the 4-node bending, past each other.
    """
    if model.patch is not None:
        raise InputError("the rig already has a ball on its strings")
    xy = as_locations(ball.location)
    if xy.shape[0] != 1 or not bool(model.on_string_bed(xy)[0]):
        raise InputError(
            f"`ball_at` {xy[0, 0]:g},{xy[0, 1]:g}: the ball must sit on the string bed"
        )
    m_b = require_positive("ball mass", ball.mass_kg)
    k = require_positive("ball stiffness", ball.stiffness_n_per_m)
    patch = BallPatch((float(xy[0, 0]), float(xy[0, 1])), ball.patch_radius_m)
    mass, stiffness, link = _with_patch(model, patch, m_b)
    n = model.n_dof
    bed = np.r_[np.arange(model.dofs["membrane"].start, model.dofs["membrane"].stop), n]
    dashpot, k_bed = _dashpot(ball, stiffness, link, bed)
    damping = np.pad(model.damping, (0, 2)) + dashpot
    omega2, vectors = eigh(stiffness + k * np.outer(link, link), mass)
    keep = omega2 <= (2 * np.pi * float(model.metadata["max_frequency_hz"])) ** 2
    omega2, vectors = omega2[keep], vectors[:, keep]
    omega = np.sqrt(omega2)
    zeta = np.einsum("ik,ij,jk->k", vectors, damping, vectors) / (2 * omega)
    # the same sign rule as the rig: the largest racket displacement positive
    largest = vectors[np.argmax(np.abs(vectors[:n]), axis=0), np.arange(omega.size)]
    vectors = vectors * np.where(largest < 0, -1.0, 1.0)
    names, kinds = _named(model, vectors, (mass, stiffness), bed)
    metadata = {
        **{key: v for key, v in model.metadata.items() if key != "strain_energy_shares"},
        "ball": {
            "location_m": [float(v) for v in xy[0]],
            "mass_kg": m_b,
            "stiffness_n_per_m": k,
            "damping_ns_per_m": float(dashpot[-1, -1]),
            "damping_ratio": ball.damping_ratio,
            "patch_radius_m": ball.patch_radius_m,
            "bed_stiffness_n_per_m": float(k_bed),
        },
    }
    return replace(
        model,
        mass=mass,
        stiffness=stiffness + k * np.outer(link, link),
        damping=damping,
        frequency=omega / (2 * np.pi),
        damping_ratio=zeta,
        modes=vectors,
        names=tuple(names),
        kinds=tuple(kinds),
        metadata=metadata,
        patch=patch,
    )


def _with_patch(
    model: RigModel, patch: BallPatch, ball_mass: float
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """M and K with the patch's dip and the ball's DOFs (the ball's spring not yet in), and the
    link ``u_B − (the patch's mean displacement)``."""
    racket, head, n = model.racket, model.racket.head, model.n_dof
    points = patch.quadrature(head)
    rows = model.displacement_rows(points.xy)
    sigma = model.metadata["string_mass_kg"] / (math.pi * head.half_length_m * head.half_width_m)
    weight = sigma * points.area
    mass = np.zeros((n + 2, n + 2))
    mass[:n, :n] = model.mass
    mass[n, :n] = mass[:n, n] = (weight * points.g) @ rows
    mass[n, n] = weight @ points.g**2
    mass[-1, -1] = ball_mass
    tension_x, tension_y = model.metadata["string_tension_per_width_n_per_m"]
    _, psi_x, psi_y = _membrane_functions(racket, model.membrane_powers, points.xy)
    membrane = model.dofs["membrane"]
    stiffness = np.zeros((n + 2, n + 2))
    stiffness[:n, :n] = model.stiffness
    stiffness[n, membrane] = stiffness[membrane, n] = (
        points.area * tension_x * points.g_x
    ) @ psi_x + (points.area * tension_y * points.g_y) @ psi_y
    stiffness[n, n] = points.area @ (tension_x * points.g_x**2 + tension_y * points.g_y**2)
    on = points.on_patch
    mean = points.area[on] @ rows[on] / points.area[on].sum()
    link = np.concatenate([-mean, [-1.0, 1.0]])  # u_B − (mean of the smooth field + the dip)
    return mass, stiffness, link


def _dashpot(
    ball: StuckBall,
    stiffness: NDArray[np.float64],
    link: NDArray[np.float64],
    bed: NDArray[np.intp],
) -> tuple[NDArray[np.float64], float]:
    """The dashpot of e_BG from the ball to the frame under the patch (module docstring), and
    the rig's bed under the patch with the frame held, k_G (N/m)."""
    bed_link = link[bed]  # the dip and the membrane under the patch, the frame held
    k_bed = 1.0 / float(bed_link @ np.linalg.solve(stiffness[np.ix_(bed, bed)], bed_link))
    series = 1.0 / (1.0 / ball.stiffness_n_per_m + 1.0 / k_bed)
    c = 2.0 * ball.damping_ratio * math.sqrt(series * ball.mass_kg)
    across = link.copy()  # u_B − the frame's motion under the patch
    across[bed] = 0.0
    return c * np.outer(across, across), k_bed


def _named(
    model: RigModel,
    vectors: NDArray[np.float64],
    matrices: tuple[NDArray[np.float64], NDArray[np.float64]],
    bed: NDArray[np.intp],
) -> tuple[list[str], list[str]]:
    """Names and kinds of the modes of the rig with the ball (``ball_on_strings``'s Returns).

    ``matrices`` are M and K without the ball's spring, ``bed`` the membrane's DOFs and the
    dip's.  The dip's own mode is the one whose dip alone holds more kinetic energy than the
    whole mode (m_gg φ_g² > 1: the dip moving against the membrane's smooth field, ≈ 17 at
    4.8 kHz on the built-in racket, ≤ 0.23 in every other mode); none if it lies above the
    rig's ``max_frequency_hz``.
    """
    mass, stiffness = matrices
    n = model.n_dof
    ball_mode = int(np.argmax(mass[-1, -1] * vectors[-1] ** 2))  # the ball's kinetic share
    dip = mass[n, n] * vectors[n] ** 2
    dip[ball_mode] = 0.0
    strings = np.einsum("ik,ij,jk->k", vectors[bed], stiffness[np.ix_(bed, bed)], vectors[bed])
    rest = np.einsum("ik,ij,jk->k", vectors, stiffness, vectors) - strings
    projection = np.abs(model.modes.T @ model.mass @ vectors[:n])
    of_bed = np.array([kind == "string-bed" for kind in model.kinds])
    mine = np.where((strings > rest)[None, :] == of_bed[:, None], projection, -1.0)
    nearest = np.argmax(mine, axis=0)
    names = [model.names[int(j)] for j in nearest]
    kinds = [model.kinds[int(j)] for j in nearest]
    names[ball_mode], kinds[ball_mode] = BALL_MODE_NAME, "other"
    if dip.max(initial=0.0) > 1.0:  # the dip against the smooth field: kept below max_frequency
        names[int(np.argmax(dip))], kinds[int(np.argmax(dip))] = DIP_MODE_NAME, "string-bed"
    plain = list(names)
    for i, name in enumerate(plain):  # one name per mode: number the repeats
        repeats = [j for j, other in enumerate(plain) if other == name]
        if len(repeats) > 1:
            names[i] = f"{name} ({repeats.index(i) + 1})"
    return names, kinds
