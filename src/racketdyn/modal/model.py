"""The modal model: natural frequencies, damping and mass-normalised mode shapes of a structure.

Mode shapes are mass-normalised (``φᵀ M φ = 1``, units 1/√kg) and stored at sample locations
over the structure; shapes anywhere else come from a thin-plate-spline interpolation through the
samples.  The modal constant of mode k between points i and j is
``A_ijk = φ_ik φ_jk`` (1/kg): the paper's ``r_i0k r_0jk / r_00k`` of eq (12) once residues
measured against a reference point 0 are scaled by the driving-point residue ``r_00k``.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, replace
from functools import cached_property, lru_cache
from pathlib import Path
from typing import Any, NoReturn

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import RBFInterpolator

from racketdyn.__about__ import __version__
from racketdyn._display import html_table, number, numbers, shorten, words
from racketdyn._grammar import plural
from racketdyn.errors import InputError
from racketdyn.numerics import as_points

__all__ = ["ModalModel", "kind_from_name"]

FORMAT = "racketdyn-modal-model"
MODE_KINDS = ("bending", "twisting", "string-bed", "rigid-body", "other", "unknown")
"""What a mode can be: a racket's kinds, ``rigid-body`` (the structure moving as a whole on its
support: a sponge, a hand), ``other``, and ``unknown`` (not classified)."""
FLAT = 0.01
"""Sample points whose spread in a direction is under this fraction of their largest spread lie
on a line or plane: shapes are interpolated along it (a beam's or a face's points measured off
it by a millimetre)."""
SCALINGS = ("mass", "unscaled")
"""How the shapes are scaled: mass-normalised (1/√kg), or unscaled (largest |φ| of each mode
1, no unit: the test had no usable driving point)."""


def kind_from_name(name: str) -> str:
    """A mode's kind as its name says it, where no kind is given: ``string-bed`` (a name with
    "string" or "membrane"), ``rigid-body``, else ``other``."""
    lower = name.lower()
    if "string" in lower or "membrane" in lower:
        return "string-bed"
    return "rigid-body" if "rigid-body" in lower else "other"


@dataclass(frozen=True, eq=False)
class ModalModel:
    """Natural frequencies, damping ratios and mass-normalised mode shapes.

    Parameters
    ----------
    frequency : ndarray, shape (n_modes,)
        Natural frequencies, Hz.
    damping_ratio : ndarray, shape (n_modes,)
        Viscous damping ratios (fraction of critical).
    locations : ndarray, shape (n_points, 2) or (n_points, 3)
        Where the shapes are sampled, ``(x, y)`` (a racket's face) or ``(x, y, z)``, m; all NaN
        when the points have no coordinates (FRFs identified without geometry:
        :attr:`has_locations` False; the shapes are known per point only, and a step needing
        locations refuses the model, :meth:`require_locations`).
    mode_shapes : ndarray, shape (n_points, n_modes)
        Mass-normalised mode shapes (displacement normal to the face), 1/√kg; unscaled shapes
        (``scaling="unscaled"``) have their largest magnitude 1 and no unit.
    names : tuple of str
        Mode names (``"2-node bending"``, …).
    kinds : tuple of str
        What each mode is: ``bending``, ``twisting``, ``string-bed``, ``rigid-body``, ``other``
        or ``unknown`` (not classified: :func:`racketdyn.modal.identify.identify` leaves it to
        the caller).  String-bed modes are left out of the vibration loss by default; rigid-body
        modes always (an impact model carries the rigid-body motion in its reduced mass).
        Empty: read from the names (``string-bed`` where a name mentions a string bed or
        membrane, ``rigid-body`` where it says rigid-body, else ``other``).
    support : str
        The support the modes belong to (``free``, ``hand`` …).
    source : str
        Where the model came from.
    metadata : dict
        Anything else (an identified model: band, nodes, reference, what was dropped).
    scaling : {"mass", "unscaled"}
        ``mass`` (the default) or ``unscaled``: frequencies and damping ratios hold, but the
        shapes are known up to a factor per mode, so no prediction can use them
        (:meth:`require_mass_normalised`).
    """

    frequency: NDArray[np.float64]
    damping_ratio: NDArray[np.float64]
    locations: NDArray[np.float64]
    mode_shapes: NDArray[np.float64]
    names: tuple[str, ...]
    kinds: tuple[str, ...] = ()
    support: str = "free"
    source: str = ""
    metadata: dict[str, Any] = field(default_factory=dict)
    scaling: str = "mass"

    def __post_init__(self) -> None:
        frequency = np.asarray(self.frequency, dtype=float)
        damping = np.asarray(self.damping_ratio, dtype=float)
        shapes = np.asarray(self.mode_shapes, dtype=float)
        locations = _locations(self.locations, self.source)
        if shapes.ndim != 2 or shapes.shape != (locations.shape[0], frequency.size):
            raise InputError(
                f"modal model ({self.source}): mode_shapes must be shaped (n_points, n_modes) = "
                f"({locations.shape[0]}, {frequency.size}), got {shapes.shape}"
            )
        if damping.shape != frequency.shape or len(self.names) != frequency.size:
            raise InputError(f"modal model ({self.source}): one damping ratio and name per mode")
        if not (np.all(np.isfinite(frequency)) and np.all(frequency > 0)):
            raise InputError(f"modal model ({self.source}): frequencies must be positive (Hz)")
        if not (np.all(np.isfinite(damping)) and np.all((damping >= 0) & (damping < 1))):
            raise InputError(f"modal model ({self.source}): damping ratios must lie in [0, 1)")
        if not np.all(np.isfinite(shapes)):
            raise InputError(f"modal model ({self.source}): mode shapes contain NaN or inf")
        object.__setattr__(self, "frequency", frequency)
        object.__setattr__(self, "damping_ratio", damping)
        object.__setattr__(self, "mode_shapes", shapes)
        object.__setattr__(self, "locations", locations)
        object.__setattr__(self, "names", tuple(self.names))
        kinds = tuple(self.kinds) or tuple(kind_from_name(n) for n in self.names)
        if len(kinds) != frequency.size or not set(kinds) <= set(MODE_KINDS):
            raise InputError(
                f"modal model ({self.source}): one kind per mode, each one of "
                f"{', '.join(MODE_KINDS)}"
            )
        object.__setattr__(self, "kinds", kinds)
        if self.scaling not in SCALINGS:
            raise InputError(
                f"modal model ({self.source}): scaling must be one of {', '.join(SCALINGS)} "
                f"(got {self.scaling!r})"
            )
        if locations.shape[0] < 1:
            raise InputError(f"modal model ({self.source}): needs shapes at one point or more")
        if self.has_locations:
            _check_distinct(locations, self.source, self.metadata.get("nodes"))

    @property
    def has_locations(self) -> bool:
        """True when the points have coordinates (False: FRFs identified without geometry)."""
        return not bool(np.isnan(self.locations).any())

    def require_locations(self, what: str) -> None:
        """InputError naming ``--geometry`` unless the points have coordinates.

        Parameters
        ----------
        what : str
            The step that needs them, for the message (e.g. ``"a prediction"``).
        """
        if not self.has_locations:
            self._refuse(
                what,
                "it has no node coordinates (FRFs identified without geometry)",
                "identify again with --geometry FILE (UFF data set 15 or 2411, or CSV "
                "node,x_m,y_m in m)",
            )

    @property
    def mass_normalised(self) -> bool:
        """True when the shapes are mass-normalised (1/√kg)."""
        return self.scaling == "mass"

    def require_mass_normalised(self, what: str) -> None:
        """InputError unless the shapes are mass-normalised: ``what`` needs them.

        Parameters
        ----------
        what : str
            The step that needs them, for the message (e.g. ``"predict"``).
        """
        if not self.mass_normalised:
            self._refuse(
                what,
                "its shapes are unscaled (the test had no usable driving point)",
                "measure a driving point (strike the accelerometer's node) and identify again",
            )

    def _refuse(self, what: str, reason: str, fix: str) -> NoReturn:
        raise InputError(f"modal model ({self.source}): {reason}, so {what} cannot use it; {fix}")

    @property
    def n_modes(self) -> int:
        """Number of modes."""
        return int(self.frequency.size)

    @property
    def omega(self) -> NDArray[np.float64]:
        """Natural angular frequencies, rad/s."""
        return np.asarray(2 * np.pi * self.frequency)

    def __repr__(self) -> str:
        return (
            f"<ModalModel {self.n_modes} modes at {numbers(self.frequency)} Hz "
            f"({words(self.names)}), shapes at {self.locations.shape[0]} points"
            f"{'' if self.has_locations else ' without coordinates'}, "
            f"support {self.support!r}, source {shorten(self.source)!r}>"
        )

    def _repr_html_(self) -> str:
        rows = [
            (name, f"{number(f)} Hz, ζ = {number(z)}, {kind}")
            for name, f, z, kind in zip(
                self.names, self.frequency, self.damping_ratio, self.kinds, strict=True
            )
        ]
        rows += [
            (
                "shapes at",
                f"{self.locations.shape[0]} points"
                + ("" if self.has_locations else " (no coordinates)"),
            ),
            ("support", self.support),
            ("source", shorten(self.source)),
        ]
        return html_table(f"ModalModel: {self.n_modes} modes", rows)

    @property
    def n_dimensions(self) -> int:
        """Coordinates of each location: 2 for ``(x, y)``, 3 for ``(x, y, z)``."""
        return int(self.locations.shape[1])

    @cached_property
    def _basis(self) -> NDArray[np.float64] | None:
        """Orthonormal directions (rows) of the line or plane holding every sample, if any.

        None when the samples fill their coordinates (a face in (x, y), a solid in (x, y, z)).
        """
        centred = self.locations - self.locations.mean(axis=0)
        # a direction spread less than FLAT of the largest is no dimension: coordinates
        # rounded to a file's 6 digits, or a tape's millimetre, off a line or plane made the
        # thin-plate spline ill-conditioned (shapes × 10⁴ between the points, issue 12)
        spread = np.linalg.svd(centred, compute_uv=False)
        rank = int(np.count_nonzero(spread > max(FLAT * spread.max(), 1e-12)))
        if rank >= self.n_dimensions:
            return None
        if self.n_dimensions == 2 and np.ptp(self.locations[:, 1]) == 0:
            return np.array([[1.0, 0.0]])  # along x (a racket's long axis)
        return np.asarray(np.linalg.svd(centred, full_matrices=False)[2][:rank])

    def _coordinates(self, points: NDArray[np.float64]) -> NDArray[np.float64]:
        """What the interpolator sees: the points, or their coordinates in the samples' line
        or plane."""
        basis = self._basis
        if basis is None:
            return points
        if basis.shape[0] == 0:
            raise InputError(
                f"modal model ({self.source}): the shapes are known at one point only; they "
                "cannot be interpolated elsewhere"
            )
        if basis.shape == (1, 2) and basis[0, 1] == 0:
            return points[:, :1]  # along x: x itself
        return np.asarray((points - self.locations[0]) @ basis.T)

    @cached_property
    def _interpolator(self) -> RBFInterpolator:
        # Thin-plate spline: smooth, exact at the samples, and it extends past the last sample
        # linearly rather than wildly.  Shapes sampled on one straight line only (a racket's
        # long axis, a beam along any direction) are interpolated along that line, shapes on
        # one plane of (x, y, z) in that plane; a point off them gets the shape of its
        # projection onto them.
        coordinates = self._coordinates(self.locations)
        # points that share their place on the line or plane (two faces of a beam, nodes that
        # differ off it only) are one sample: their mean shape (the spline needs distinct points)
        scale = float(np.abs(coordinates).max()) or 1.0
        keys = np.round(coordinates / (1e-6 * scale)).astype(np.int64)
        _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
        inverse = np.ravel(inverse)
        needed = coordinates.shape[1] + 1  # the spline's plane (or line) through the samples
        if first.size < needed:
            raise InputError(
                f"modal model ({self.source}): shapes sampled at {plural(first.size, 'point')}; "
                f"shapes between the points need {needed} or more (FRFs at more points)"
            )
        shapes = np.zeros((first.size, self.n_modes))
        np.add.at(shapes, inverse, self.mode_shapes)
        shapes /= np.bincount(inverse)[:, None]
        return _spline(coordinates[first].tobytes(), shapes.tobytes(), shapes.shape)

    def with_dynamics(
        self,
        frequency: ArrayLike | None = None,
        damping_ratio: ArrayLike | None = None,
    ) -> ModalModel:
        """This model with other frequencies or damping ratios, its shapes unchanged (their
        spline is the same: built once for any model of these shapes, :func:`_spline`)."""
        changes: dict[str, Any] = {}
        if frequency is not None:
            changes["frequency"] = np.asarray(frequency, dtype=float)
        if damping_ratio is not None:
            changes["damping_ratio"] = np.asarray(damping_ratio, dtype=float)
        return replace(self, **changes)

    def mode_shapes_at(self, locations: ArrayLike) -> NDArray[np.float64]:
        """Mass-normalised mode shapes at any locations, shaped ``(n, n_modes)``, 1/√kg.

        Parameters
        ----------
        locations : array_like, shape (n, 2) or (n, 3)
            Where, ``(x, y)`` or ``(x, y, z)`` in m, as the model's own locations.

        Returns
        -------
        ndarray, shape (n, n_modes)
            Interpolated (thin-plate spline) from the sampled shapes, 1/√kg.
        """
        self.require_locations("shapes between the points")
        points = as_points(locations, f"modal model ({self.source}): locations")
        if points.shape[1] != self.n_dimensions:
            raise InputError(
                f"modal model ({self.source}): shapes are sampled at {self.n_dimensions}-D "
                f"locations; asked at {points.shape[1]}-D ones"
            )
        return np.asarray(self._interpolator(self._coordinates(points)))

    def modal_constants(self, response: ArrayLike, excitation: ArrayLike) -> NDArray[np.float64]:
        """Modal constants ``A_ijk = φ_ik φ_jk`` (1/kg) for every response i and excitation j.

        Returns an array shaped ``(n_response, n_excitation, n_modes)``: the paper's
        ``r_i0k r_0jk / r_00k`` of eq (12).
        """
        phi_i = self.mode_shapes_at(response)
        phi_j = self.mode_shapes_at(excitation)
        return np.asarray(phi_i[:, None, :] * phi_j[None, :, :])

    def select(self, modes: ArrayLike) -> ModalModel:
        """A model keeping only the listed mode indices (0-based)."""
        index = np.atleast_1d(np.asarray(modes, dtype=int))
        return ModalModel(
            frequency=self.frequency[index],
            damping_ratio=self.damping_ratio[index],
            locations=self.locations,
            mode_shapes=self.mode_shapes[:, index],
            names=tuple(self.names[i] for i in index),
            kinds=tuple(self.kinds[i] for i in index),
            support=self.support,
            source=self.source,
            metadata=dict(self.metadata),
            scaling=self.scaling,
        )

    def summary(self) -> dict[str, Any]:
        """Source, support and the modes (for run records)."""
        return {
            "source": self.source,
            "support": self.support,
            "scaling": self.scaling,
            "modes": self.to_dict()["modes"],
        }

    @cached_property
    def frame_modes(self) -> ModalModel:
        """The model without its string-bed and rigid-body modes."""
        keep = [k for k, kind in enumerate(self.kinds) if kind not in ("string-bed", "rigid-body")]
        return self if len(keep) == self.n_modes else self.select(keep)

    @cached_property
    def flexible_modes(self) -> ModalModel:
        """The model without its rigid-body modes (string-bed modes kept)."""
        keep = [k for k, kind in enumerate(self.kinds) if kind != "rigid-body"]
        return self if len(keep) == self.n_modes else self.select(keep)

    # --- files --------------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict (the racketdyn modal-model format)."""
        return {
            "format": FORMAT,
            "format_version": 1,
            "racketdyn_version": __version__,
            "support": self.support,
            "source": self.source,
            "scaling": self.scaling,
            "units": {
                "frequency": "Hz",
                "locations": "m",
                "mode_shapes": "1/sqrt(kg)" if self.mass_normalised else "1 (unscaled)",
            },
            "modes": [
                {"name": n, "kind": k, "frequency_hz": float(f), "damping_ratio": float(z)}
                for n, k, f, z in zip(
                    self.names, self.kinds, self.frequency, self.damping_ratio, strict=True
                )
            ],
            "locations_m": self.locations.tolist() if self.has_locations else None,
            "mode_shapes": self.mode_shapes.tolist(),
            "metadata": self.metadata,
        }

    def write_json(self, path: Path) -> None:
        """Write the model as racketdyn modal-model JSON."""
        Path(path).write_text(json.dumps(self.to_dict(), indent=1), encoding="utf-8")

    @classmethod
    def read_json(cls, path: Path) -> ModalModel:
        """Read a racketdyn modal-model JSON file."""
        path = Path(path)
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except FileNotFoundError:
            raise InputError(f"{path}: no such modal model file") from None
        except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
            raise InputError(f"{path}: not a racketdyn modal model JSON file ({error})") from None
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise InputError(f"{path}: not a racketdyn modal model (format must be {FORMAT!r})")
        _check_header(path, data)
        try:
            modes = data["modes"]
            shapes = np.array(data["mode_shapes"], dtype=float).reshape(-1, len(modes))
            located = data["locations_m"]
            return cls(
                frequency=np.array([m["frequency_hz"] for m in modes], dtype=float),
                damping_ratio=np.array([m["damping_ratio"] for m in modes], dtype=float),
                locations=(
                    np.full((shapes.shape[0], 3), np.nan)
                    if located is None
                    else np.array(located, dtype=float)
                ),
                mode_shapes=shapes,
                names=tuple(str(m["name"]) for m in modes),
                kinds=tuple(str(m.get("kind", "other")) for m in modes),
                support=str(data.get("support", "free")),
                source=str(data.get("source", path.name)),
                metadata=dict(data.get("metadata", {})),
                scaling=str(data.get("scaling", "mass")),
            )
        except (KeyError, TypeError, ValueError) as error:
            raise InputError(
                f"{path}: modal model is missing or has a bad field ({error})"
            ) from None


FORMAT_VERSION = 1
"""The modal-model JSON's version this racketdyn writes and reads."""
_UNITS = {"frequency": "Hz", "locations": "m"}


@lru_cache(maxsize=64)
def _spline(points: bytes, values: bytes, shape: tuple[int, int]) -> RBFInterpolator:
    """The thin-plate spline through ``values`` (``shape``: samples × modes) at ``points``,
    kept for the same arrays: a model with other frequencies or damping, or the same modes
    selected again (an uncertainty's samples, a calibration's steps), costs no new spline."""
    samples = np.frombuffer(values).reshape(shape)
    return RBFInterpolator(
        np.frombuffer(points).reshape(shape[0], -1), samples, kernel="thin_plate_spline"
    )


def _check_header(path: Path, data: dict[str, Any]) -> None:
    """The file's version, declared units and modes, checked before any number is used
    (issue 26: rad/s, damping in per cent, mm and version 99 were taken on trust)."""
    version = data.get("format_version", FORMAT_VERSION)
    if version != FORMAT_VERSION:
        raise InputError(
            f"{path}: format_version {version!r}; this racketdyn reads {FORMAT_VERSION} (write "
            "the file again with this version, or update racketdyn)"
        )
    units = data.get("units", {})
    if not isinstance(units, dict):
        raise InputError(f"{path}: units must be a table of unit names (got {units!r})")
    for key, unit in _UNITS.items():
        if key in units and units[key] != unit:
            raise InputError(
                f"{path}: units.{key} is {units[key]!r}; racketdyn's modal models are in {unit} "
                "(convert the file's numbers)"
            )
    modes = data.get("modes")
    if not isinstance(modes, list):
        return  # the read below names the missing field
    for k, mode in enumerate(modes, 1):
        if not isinstance(mode, dict):
            continue
        f, zeta = mode.get("frequency_hz"), mode.get("damping_ratio")
        if isinstance(f, int | float) and not (math.isfinite(f) and f > 0):
            raise InputError(f"{path}: mode {k}: frequency_hz {f!r} must be a positive number")
        if isinstance(zeta, int | float) and not (math.isfinite(zeta) and 0 <= zeta < 1):
            slip = f"; did you give per cent ({zeta:g} % = {zeta / 100:g})?" if zeta >= 1 else ""
            raise InputError(
                f"{path}: mode {k}: damping_ratio {zeta!r} must be a fraction of critical from "
                f"0 to 1{slip}"
            )


def _locations(raw: ArrayLike, source: str) -> NDArray[np.float64]:
    """The model's locations, m: finite, or all NaN (no coordinates); InputError for some of
    each."""
    array = np.asarray(raw, dtype=float)
    missing = np.isnan(array)
    if not missing.any():
        return as_points(array, "modal model locations")
    if not missing.all():
        raise InputError(
            f"modal model ({source}): some points have coordinates and some not; give every "
            "point's (--geometry FILE) or none"
        )
    return np.full(as_points(np.zeros_like(array), "modal model locations").shape, np.nan)


def _check_distinct(locations: NDArray[np.float64], source: str, nodes: Any) -> None:
    """InputError naming the source and the node numbers (when known) of two points at one
    location."""
    _, first, inverse = np.unique(locations, axis=0, return_index=True, return_inverse=True)
    if first.size == locations.shape[0]:
        return
    inverse = np.ravel(inverse)
    clashes = []
    for group in np.unique(inverse[np.bincount(inverse)[inverse] > 1]):
        members = np.flatnonzero(inverse == group)
        if isinstance(nodes, list | tuple) and len(nodes) == locations.shape[0]:
            names = " and ".join(f"node {nodes[i]}" for i in members)
        else:
            names = " and ".join(f"point {i + 1}" for i in members)
        where = ", ".join(f"{v:.4g}" for v in locations[members[0]])
        clashes.append(f"{names} at ({where}) m")
    raise InputError(
        f"modal model ({source}): two points share one location: {'; '.join(clashes[:4])}; "
        "give each its own coordinates (keep z for points that differ only in z)"
    )
