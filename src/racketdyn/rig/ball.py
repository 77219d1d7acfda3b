"""A ball fixed on the rig's strings: the paper's compound ball–racket test (section 3.2).

Kawazoe glued a ball to the centre of the string face and ran the modal test again (Figs 8–9).
:func:`ball_on_strings` adds that ball to a :class:`~racketdyn.rig.model.RigModel`: one more
degree of freedom, the ball's displacement normal to the face, joined to the string bed's
displacement at the ball's point (the rig's membrane, frame motion included) by the ball's own
one-sided spring and a dashpot.  The rig's membrane is the string bed here, so the spring is
the ball's law alone (not the compound F_GB of the approximate method): its tangent at a small
preload (a stuck ball presses on the strings), with the dashpot of
:func:`racketdyn.impact.compound.restitution_damping_ratio` for e_BG.

The modes are found as in :func:`racketdyn.rig.model.rig_model` (real modes of (K, M), modal
damping φᵀCφ/(2ω)), so the rig with the ball *is* its modal truth again: hammer records
simulated on it identify back to these modes.  The ball's dashpot is not proportional: the
modal damping of the ball mode is the classical diagonal approximation.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import eigh

from racketdyn.errors import InputError, require_positive
from racketdyn.racket import as_locations
from racketdyn.racket_modal.shapes import BALL_MODE_NAME
from racketdyn.rig.model import RigModel

__all__ = ["BALL_MODE_NAME", "ball_on_strings"]


def ball_on_strings(
    model: RigModel,
    location: ArrayLike,
    ball_mass_kg: float,
    stiffness_n_per_m: float,
    damping_ratio: float,
) -> RigModel:
    """The rig with a ball fixed on its strings at ``location``.

    Parameters
    ----------
    model : RigModel
        The racket on its support, without a ball.
    location : array_like (2,)
        The ball's point (x, y) on the string bed, m.
    ball_mass_kg : float
        m_B, kg.
    stiffness_n_per_m : float
        The ball's spring against the strings, N/m.
    damping_ratio : float
        ζ of the ball on a rigid bed: the dashpot is ``2 ζ √(k m_B)``, N·s/m.

    Returns
    -------
    RigModel
        One more DOF (``dofs["ball"]``), its modes re-solved; the ball mode is named
        :data:`BALL_MODE_NAME` (kind ``other``), the others keep the names of the modes they
        came from (by mass-weighted projection).
    """
    if model.dofs["ball"].stop > model.dofs["ball"].start:
        raise InputError("the rig already has a ball on its strings")
    xy = as_locations(location)
    if xy.shape[0] != 1 or not bool(model.on_string_bed(xy)[0]):
        raise InputError(
            f"`ball_at` {xy[0, 0]:g},{xy[0, 1]:g}: the ball must sit on the string bed"
        )
    m_b = require_positive("ball mass", ball_mass_kg)
    k = require_positive("ball stiffness", stiffness_n_per_m)
    c = 2.0 * damping_ratio * math.sqrt(k * m_b)
    n = model.n_dof
    link = np.concatenate([-model.displacement_rows(xy)[0], [1.0]])  # u_B − u_strings
    mass = np.zeros((n + 1, n + 1))
    mass[:n, :n] = model.mass
    mass[n, n] = m_b
    stiffness = np.pad(model.stiffness, (0, 1)) + k * np.outer(link, link)
    damping = np.pad(model.damping, (0, 1)) + c * np.outer(link, link)
    omega2, vectors = eigh(stiffness, mass)
    keep = omega2 <= (2 * np.pi * float(model.metadata["max_frequency_hz"])) ** 2
    omega2, vectors = omega2[keep], vectors[:, keep]
    omega = np.sqrt(omega2)
    zeta = np.einsum("ik,ij,jk->k", vectors, damping, vectors) / (2 * omega)
    # the same sign rule as the rig: the largest racket displacement positive
    largest = vectors[np.argmax(np.abs(vectors[:n]), axis=0), np.arange(omega.size)]
    vectors = vectors * np.where(largest < 0, -1.0, 1.0)
    ball_share = m_b * vectors[n] ** 2  # kinetic share of the ball (φᵀMφ = 1)
    projection = np.abs(model.modes.T @ model.mass @ vectors[:n])
    names = [model.names[int(j)] for j in np.argmax(projection, axis=0)]
    kinds = [model.kinds[int(j)] for j in np.argmax(projection, axis=0)]
    ball_mode = int(np.argmax(ball_share))
    names[ball_mode], kinds[ball_mode] = BALL_MODE_NAME, "other"
    plain = list(names)
    for i, name in enumerate(plain):  # one name per mode: number the repeats
        repeats = [j for j, other in enumerate(plain) if other == name]
        if len(repeats) > 1:
            names[i] = f"{name} ({repeats.index(i) + 1})"
    metadata = {
        **{key: v for key, v in model.metadata.items() if key != "strain_energy_shares"},
        "ball": {
            "location_m": [float(v) for v in xy[0]],
            "mass_kg": m_b,
            "stiffness_n_per_m": k,
            "damping_ns_per_m": c,
            "damping_ratio": damping_ratio,
        },
    }
    return replace(
        model,
        mass=mass,
        stiffness=stiffness,
        damping=damping,
        frequency=omega / (2 * np.pi),
        damping_ratio=zeta,
        modes=vectors,
        names=tuple(names),
        kinds=tuple(kinds),
        metadata=metadata,
    )
