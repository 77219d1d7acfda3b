"""The approximate method over many samples of its inputs at once (issue 24's speed).

:func:`racketdyn.impact.uncertainty.propagate` draws hundreds of samples of the uncertain
inputs; running :func:`racketdyn.impact.approximate.predict` once per sample rebuilds the
compound law, the modal model and the grid every time (≈ 5 ms a sample on the built-in
racket's grid).  :func:`predict_samples` groups the samples by what changes the compound law,
the racket's mass or the mode shapes (:data:`ARRAY_PARAMETERS` do not) and evaluates each
group in one set of arrays with a leading sample axis: each sample's own impact points
(location offsets), ball speeds (speed offsets), e_BG and first bending frequency.  The
numbers are those of one :func:`~racketdyn.impact.approximate.predict` call per sample, to
round-off: both run :func:`~racketdyn.impact.approximate.approximate_impacts`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, fields, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn.ball import RestoringForce
from racketdyn.contact import with_ball_string_cor
from racketdyn.errors import one_of
from racketdyn.impact.approximate import (
    STIFFNESS_READINGS,
    VIBRATION_CHARGES,
    ApproximateImpacts,
    Shapes,
    StiffnessReading,
    VibrationCharge,
    approximate_impacts,
    shapes_where,
)
from racketdyn.impact.calibration import PARAMETERS, shifted_e_bg
from racketdyn.impact.grid import (
    ball_reaches_frame,
    check_supports,
    resolve_modal_model,
    support_reduced_mass,
)
from racketdyn.impact.measured import ModelInputs, first_bending_index
from racketdyn.modal import ModalModel
from racketdyn.numerics import one_blas_thread
from racketdyn.racket import Racket

__all__ = ["ARRAY_PARAMETERS", "SAMPLE_CHUNK", "predict_samples"]

ARRAY_PARAMETERS: frozenset[str] = frozenset(
    {
        "e_bg",
        "first_bending_hz",
        "frame_damping_scale",
        "hand_stiffness_n_per_m",
        "hand_damping_ns_per_m",
        "hand_arm_mass_kg",
    }
)
"""Parameters whose samples share one compound law, racket and set of mode shapes: e_BG and
the first bending frequency are carried as arrays; the damping and the hand are not read by
the approximate method.  Samples that differ in any other parameter are evaluated apart."""

SAMPLE_CHUNK = 32
"""Most samples evaluated in one set of arrays: of 16, 32, 64 and 128 on the built-in grid at
three speeds, 32 was the fastest (a few MB of temporaries a chunk; larger ones leave the
cache)."""


def predict_samples(
    inputs: ModelInputs,
    parameters: dict[str, NDArray[np.float64]],
    locations: ArrayLike,
    ball_speed: ArrayLike,
    *,
    supports: str | Sequence[str] = ("free",),
    racket_speed: ArrayLike = 0.0,
    stiffness_reading: StiffnessReading = "period",
    vibration_charge: VibrationCharge = "coupled",
    progress: Callable[[int, int], None] | None = None,
) -> ApproximateImpacts:
    """The approximate method at every sample's impacts, as one ``predict`` call per sample.

    Sample k runs ``inputs`` with each parameter set to ``parameters[name][k]``
    (:data:`racketdyn.impact.calibration.PARAMETERS`) at its own points and ball speeds.

    Parameters
    ----------
    inputs : ModelInputs
        The nominal inputs (``string_bed`` ``uniform``: one compound law over the face).
    parameters : dict
        Parameter name → ``(n_samples,)`` values.
    locations : array_like
        ``(n_samples, n_points, 2)`` each sample's impact points on the bed (x, y), m.
    ball_speed : array_like
        ``(n_samples, n_speeds)`` each sample's ball speeds, m/s (> 0).
    supports : str or sequence of {"free", "pinned"}
        Supports (one text of comma-separated names too).
    racket_speed : array_like
        Racket speed at the impact point, one or one per ball speed, m/s.
    stiffness_reading, vibration_charge : str
        As for :func:`racketdyn.impact.approximate.predict`.
    progress : callable, optional
        ``progress(done, total)`` after each chunk of samples.

    Returns
    -------
    ApproximateImpacts
        Arrays shaped ``(n_samples, n_points, n_speeds, n_supports)`` (``mode_energy`` with a
        last mode axis); where ``status_code`` is not 0 (``ok``) the numbers are not given (a
        frame shot's are NaN).
    """
    one_of("stiffness_reading", stiffness_reading, STIFFNESS_READINGS)
    one_of("vibration_charge", vibration_charge, VIBRATION_CHARGES)
    xy = np.asarray(locations, dtype=float)
    speeds = np.asarray(ball_speed, dtype=float)
    total = xy.shape[0]
    options = {
        "supports": check_supports(supports),
        "racket_speed": np.broadcast_to(np.asarray(racket_speed, dtype=float), speeds.shape[1:]),
        "stiffness_reading": stiffness_reading,
        "vibration_charge": vibration_charge,
    }
    parts: list[tuple[NDArray[np.intp], ApproximateImpacts]] = []
    done = 0
    with one_blas_thread():
        for members, group in _groups(inputs, parameters, total):
            for chunk in np.array_split(members, -(-members.size // SAMPLE_CHUNK)):
                values = {name: v[chunk] for name, v in parameters.items()}
                parts.append((chunk, group.impacts(values, xy[chunk], speeds[chunk], options)))
                done += chunk.size
                if progress is not None:
                    progress(done, total)
    return _joined(parts, total)


def _groups(
    inputs: ModelInputs, parameters: dict[str, NDArray[np.float64]], total: int
) -> Iterator[tuple[NDArray[np.intp], _Group]]:
    """Sample indices of each group sharing the values of every grouping parameter, and
    what they share."""
    keys = [np.asarray(v) for name, v in parameters.items() if name not in ARRAY_PARAMETERS]
    if not keys:
        yield np.arange(total), _Group.of(inputs)
        return
    _, inverse = np.unique(np.column_stack(keys), axis=0, return_inverse=True)
    inverse = np.ravel(inverse)
    for g in range(int(inverse.max()) + 1):
        members = np.flatnonzero(inverse == g)
        yield members, _Group.of(_group_inputs(inputs, parameters, int(members[0])))


def _group_inputs(
    inputs: ModelInputs, parameters: dict[str, NDArray[np.float64]], k: int
) -> ModelInputs:
    """The inputs with sample k's grouping parameters (the array ones left nominal)."""
    for name, values in parameters.items():
        if name not in ARRAY_PARAMETERS:
            inputs = PARAMETERS[name].set(inputs, float(values[k]))
    return inputs


@dataclass(frozen=True)
class _Group:
    """What a group's samples share: the inputs, the racket, the law and the modes charged
    (with the first bending frequency the inputs give, before a sample's own)."""

    inputs: ModelInputs
    racket: Racket
    law: RestoringForce
    model: ModalModel | None

    @classmethod
    def of(cls, inputs: ModelInputs) -> _Group:
        bare = replace(inputs, first_bending_hz=None, frame_damping_scale=1.0)
        model = resolve_modal_model(inputs.racket, bare.modes(), inputs.include_string_bed)
        return cls(inputs, inputs.effective_racket, inputs.law(), model)

    def impacts(
        self,
        parameters: dict[str, NDArray[np.float64]],
        locations: NDArray[np.float64],
        ball_speed: NDArray[np.float64],
        options: dict[str, Any],
    ) -> ApproximateImpacts:
        """``k`` samples in arrays ``(k, n_points, n_speeds, n_supports)``."""
        k, n = locations.shape[:2]
        flat = locations.reshape(-1, 2)
        supports = options["supports"]
        reduced = np.column_stack([support_reduced_mass(self.racket, flat, s) for s in supports])
        v_racket = np.broadcast_to(options["racket_speed"], ball_speed.shape)
        e_bg = _e_bg(self.inputs, parameters.get("e_bg"), ball_speed + v_racket)
        radius = 0.5 * self.inputs.ball.diameter_m
        edge = self.racket.head.distance_to_edge(flat).reshape(k, n)[:, :, None, None]
        return approximate_impacts(
            self.law,
            self.inputs.effective_ball,
            reduced.reshape(k, n, 1, len(supports)),
            ball_speed[:, None, :, None],
            v_racket[:, None, :, None],
            e_bg[:, None, :, None],
            self._modes(parameters.get("first_bending_hz"), flat, k),
            lambda deflection: ball_reaches_frame(deflection, radius, edge),
            stiffness_reading=options["stiffness_reading"],
            vibration_charge=options["vibration_charge"],
        )

    def _modes(
        self, first_bending: NDArray[np.float64] | None, flat: NDArray[np.float64], k: int
    ) -> tuple[NDArray[np.float64], Shapes] | None:
        """``(k, 1, 1, 1, n_modes)`` each sample's frequencies (Hz), and the shapes at its
        points (``flat``: ``(k n_points, 2)``), evaluated only where an impact needs them."""
        model = self.model
        if model is None:
            return None
        frequency = np.tile(model.frequency, (k, 1))
        if first_bending is None and self.inputs.first_bending_hz is not None:
            first_bending = np.full(k, self.inputs.first_bending_hz)
        if first_bending is not None:
            frequency[:, first_bending_index(model)] = first_bending
        n = flat.shape[0] // k

        def shapes(needed: NDArray[np.bool_]) -> NDArray[np.float64]:
            wanted = needed.any(axis=(2, 3)).ravel()
            return shapes_where(model, flat, wanted).reshape(k, n, 1, 1, -1)

        return frequency[:, None, None, None, :], shapes


def _e_bg(
    group: ModelInputs, values: NDArray[np.float64] | None, approach: NDArray[np.float64]
) -> NDArray[np.float64]:
    """``(k, n_speeds)`` e_BG at each sample's relative speeds (its own e_BG, if drawn)."""
    if values is None:
        ball = with_ball_string_cor(group.effective_racket, group.effective_ball)
        return ball.e_bg_at(approach)
    tables = shifted_e_bg(group, values)
    if tables is None:  # a constant e_BG: each sample's own
        return np.repeat(np.asarray(values, dtype=float)[:, None], approach.shape[1], axis=1)
    speeds, table = tables
    return np.stack([np.interp(v, speeds, row) for v, row in zip(approach, table, strict=True)])


def _joined(
    parts: list[tuple[NDArray[np.intp], ApproximateImpacts]], total: int
) -> ApproximateImpacts:
    """The chunks' arrays put back in sample order."""
    joined: dict[str, Any] = {}
    for name in (f.name for f in fields(ApproximateImpacts)):
        first = getattr(parts[0][1], name)
        out = np.empty((total, *first.shape[1:]), dtype=first.dtype)
        for members, part in parts:
            out[members] = getattr(part, name)
        joined[name] = out
    return ApproximateImpacts(**joined)
