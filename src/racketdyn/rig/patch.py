"""The string bed's deflection under a ball's patch: one more Ritz function of the rig's membrane.

The rig's membrane (:mod:`racketdyn.rig.model`) is ten smooth functions over the whole head.
Pressed at one point, or over any patch smaller than the ball, they bend as the string net
does under a patch as wide as the ball (≈ 48 kN/m with the frame held on the built-in
racket's played bed, against the net's 49 kN/m under a 33.5 mm patch and the string bed's
law's 21.4 kN/m): they cannot dip under a few strings.  A ball on the strings needs that dip,
the net's deflection falling off as the logarithm of the distance from the patch
(:func:`racketdyn.contact.membrane_patch_stiffness`), so the rig adds it as one Ritz function:

    ``g = ln|w| / ln ρ_a`` outside the patch, ``g = 1`` on it,
    ``w = (z − z₀) / (1 − z̄₀ z)``,  ``z = (x − x_c)/A + i (y − y_c)/B``

(A, B the head's half-axes): the head ellipse scaled onto the unit disc, the patch's centre z₀
moved to 0 (a Möbius map of the disc onto itself), so g vanishes on the head's edge and the
function is admissible; ``ρ_a = a / (√(A B) (1 − |z₀|²))`` gives the patch the area π a²
(|dz/dw| = 1 − |z₀|² at the patch).  Its level lines are the head's shape scaled about the
patch, not the net's own (nearly round near a small patch): a trial function, so the Ritz
bed is stiffer than the net's exact field, by 2.6–3 % for patches of 3–17 mm at the built-in
racket's centre.  No library builds this; the quadrature is Gauss–Legendre in ln|w| and
even in the angle, in the w-plane, where g depends on |w| alone.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.errors import InputError
from racketdyn.racket import HeadEllipse, as_locations

__all__ = ["BallPatch", "PatchQuadrature"]

_RADIAL = np.polynomial.legendre.leggauss(24)
_ANGLES = 64


@dataclass(frozen=True)
class PatchQuadrature:
    """Points over the head for integrals of the patch function: ``xy`` (m), area weights
    ``area`` (m²), and g with its x and y derivatives there (1, 1/m)."""

    xy: NDArray[np.float64]
    area: NDArray[np.float64]
    g: NDArray[np.float64]
    g_x: NDArray[np.float64]
    g_y: NDArray[np.float64]

    @property
    def on_patch(self) -> NDArray[np.bool_]:
        """The points on the patch (g = 1)."""
        return np.asarray(self.g >= 1.0)


@dataclass(frozen=True)
class BallPatch:
    """Where a ball presses the rig's membrane: the patch's centre (x, y) and radius, m."""

    centre_m: tuple[float, float]
    radius_m: float

    def _disc(self, head: HeadEllipse) -> tuple[complex, float]:
        """z₀ and ρ_a of the module docstring; InputError if the patch is not on the bed."""
        z0 = complex(
            (self.centre_m[0] - head.centre_x_m) / head.half_length_m,
            (self.centre_m[1] - head.centre_y_m) / head.half_width_m,
        )
        inside = 1.0 - abs(z0) ** 2
        size = math.sqrt(head.half_length_m * head.half_width_m)
        rho = self.radius_m / size / inside if inside > 0.0 else math.inf
        if not (self.radius_m > 0.0 and rho < 1.0):
            raise InputError(
                f"ball patch of radius {self.radius_m:g} m at x={self.centre_m[0]:g} m, "
                f"y={self.centre_m[1]:g} m: it must lie inside the string bed"
            )
        return z0, rho

    def values(self, head: HeadEllipse, locations: ArrayLike) -> NDArray[np.float64]:
        """g at the locations (1 on the patch, 0 on and beyond the head's edge)."""
        z0, rho = self._disc(head)
        xy = as_locations(locations)
        z = (xy[:, 0] - head.centre_x_m) / head.half_length_m + 1j * (
            (xy[:, 1] - head.centre_y_m) / head.half_width_m
        )
        size = np.abs((z - z0) / (1.0 - np.conj(z0) * z))
        with np.errstate(divide="ignore"):
            g = np.log(np.maximum(size, rho)) / math.log(rho)
        return np.asarray(np.where(np.abs(z) < 1.0, g, 0.0))

    def quadrature(self, head: HeadEllipse) -> PatchQuadrature:
        """Points and weights over the head: the patch (g = 1) and the ring out to the edge."""
        z0, rho = self._disc(head)
        x, weight = _RADIAL
        log_rho = math.log(rho)
        # ring: s = ln|w| from ln ρ_a to 0 (g linear in s); patch: |w| from 0 to ρ_a
        ring = np.exp(0.5 * log_rho * (1.0 - x))
        ring_w = -0.5 * log_rho * weight * ring**2  # d|w| |w| = |w|² ds
        patch = 0.5 * rho * (1.0 + x)
        patch_w = 0.5 * rho * weight * patch
        radius = np.concatenate([ring, patch])
        angle = 2.0 * np.pi * (np.arange(_ANGLES) + 0.5) / _ANGLES
        w = (radius[:, None] * np.exp(1j * angle)[None, :]).ravel()
        w_area = np.repeat(np.concatenate([ring_w, patch_w]) * 2.0 * np.pi / _ANGLES, _ANGLES)
        z = (w + z0) / (1.0 + np.conj(z0) * w)
        scale = 1.0 - abs(z0) ** 2
        dz_dw = scale / (1.0 + np.conj(z0) * w) ** 2
        a, b = head.half_length_m, head.half_width_m
        in_ring = np.repeat(np.arange(radius.size) < ring.size, _ANGLES)
        # ∂g/∂ξ − i ∂g/∂η = (d ln w / dz) / ln ρ_a in the ring, 0 on the patch
        slope = np.where(in_ring, 1.0 / (w * dz_dw) / log_rho, 0.0)
        return PatchQuadrature(
            xy=np.column_stack([head.centre_x_m + a * z.real, head.centre_y_m + b * z.imag]),
            area=np.asarray(w_area * np.abs(dz_dw) ** 2 * a * b),
            g=np.where(in_ring, np.log(np.abs(w)) / log_rho, 1.0),
            g_x=np.asarray(slope.real / a),
            g_y=np.asarray(-slope.imag / b),
        )
