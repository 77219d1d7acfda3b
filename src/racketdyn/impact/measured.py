"""Predictions at measured impacts: each row of a measured-rebound file by either model.

A measured file lists impacts one by one (point, ball speed, racket speed, support), not as a
grid.  :func:`predict_rows` groups the rows by support, ball speed and racket speed and runs the
approximate method (:func:`racketdyn.impact.predict`) or the transient simulation
(:func:`racketdyn.impact.transient.predict_transient`) once per group, so a whole file costs a
few vectorised calls.  :class:`ModelInputs` holds what a prediction depends on and what a
calibration may change (:mod:`racketdyn.impact.calibration`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from racketdyn.ball import Ball, RestoringForce
from racketdyn.contact import compound_law
from racketdyn.errors import InputError, one_of
from racketdyn.impact.approximate import predict
from racketdyn.impact.grid import StringBed, check_string_bed, point_law
from racketdyn.impact.hand import Hand
from racketdyn.impact.result import STATUS_OK
from racketdyn.io.measured import MeasuredRebound
from racketdyn.modal import ModalModel
from racketdyn.racket import Racket
from racketdyn.racket_modal import modal_model_for

__all__ = [
    "METHODS",
    "NO_HAND_STATUS",
    "OUTLIER_LIMIT",
    "ModelInputs",
    "first_bending_index",
    "outlier_labels",
    "outlier_rank",
    "outliers",
    "predict_rows",
    "standardised_residuals",
]

Method = Literal["approx", "transient"]
METHODS: tuple[Method, ...] = ("approx", "transient")

NO_HAND_STATUS = "hand support: the approximate method has no hand"
"""Status of a ``hand`` row under the approximate method (its held racket is ``pinned``)."""

OUTLIER_LIMIT = 3.0
"""A row is an outlier when its standardised residual (:func:`standardised_residuals`) is
beyond ± this: three standard deviations, the usual rule (a normal residual passes it once in
370 rows)."""

ROBUST_SD_PER_MAD = 1.4826
"""Standard deviation of a normal sample per its median absolute deviation."""

MAX_DAMPING_RATIO = 0.5
"""Largest modal damping ratio a scaled damping reaches (the modal model takes < 1)."""


@lru_cache(maxsize=32)
def _built_in_modes(racket: Racket) -> ModalModel:
    """The racket's own modal model, kept for the racket (calibration rebuilds it often)."""
    return modal_model_for(racket)


@dataclass(frozen=True, eq=False)
class ModelInputs:
    """What a prediction at measured rows depends on.

    Parameters
    ----------
    racket : Racket
        The racket as described (its strings unscaled).
    ball : Ball
        The ball.
    hand : Hand or None
        The hand of ``hand`` rows (default :class:`Hand` when a row needs one).
    modal_model : ModalModel, None or "racket"
        The modes: ``"racket"`` builds the racket's own (its file, else the built-in beam
        model, rebuilt when the racket changes); None is a rigid racket.
    string_stiffness_scale : float
        Factor on the string bed's restoring force (its tension and axial stiffness both
        scaled: Kawazoe's law F = 2 S0 X / L + A E X³ / L³ scales as a whole).
    frame_damping_scale : float
        Factor on every mode's damping ratio (capped at :data:`MAX_DAMPING_RATIO`).
    include_string_bed : bool
        Charge string-bed modes as vibration loss too.
    engine : {"auto", "compiled", "reference"}
        Transient engine.
    string_bed : {"uniform", "local"}
        ``uniform``: the face centre's string-bed law at every point (the paper's); ``local``:
        each point's own from the lengths of its main and cross strings
        (:func:`racketdyn.contact.local_compound_law`).
    first_bending_hz : float, optional
        The frame's first bending frequency in place of the modal model's (its shape and the
        other modes kept): the input a racket file often does not pin down.
    ball_stiffness_scale : float
        Factor on the ball's restoring force F_B (ball-to-ball scatter, temperature).
    """

    racket: Racket
    ball: Ball
    hand: Hand | None = None
    modal_model: ModalModel | Literal["racket"] | None = "racket"
    string_stiffness_scale: float = 1.0
    frame_damping_scale: float = 1.0
    include_string_bed: bool = False
    engine: str = "auto"
    string_bed: StringBed = "uniform"
    first_bending_hz: float | None = None
    ball_stiffness_scale: float = 1.0

    def __post_init__(self) -> None:
        check_string_bed(self.string_bed, None, self.racket)

    @property
    def effective_ball(self) -> Ball:
        """The ball with its restoring force scaled by :attr:`ball_stiffness_scale`."""
        if self.ball_stiffness_scale == 1.0:
            return self.ball
        law = self.ball.restoring_force.scaled(self.ball_stiffness_scale)
        return replace(self.ball, restoring_force=law)

    @property
    def effective_racket(self) -> Racket:
        """The racket with its string bed scaled by :attr:`string_stiffness_scale`."""
        scale = self.string_stiffness_scale
        if scale == 1.0:
            return self.racket
        strings = self.racket.strings
        if strings.load_deflection_file is not None:
            raise InputError(
                "string_stiffness_scale: the racket's string bed is a measured load–deflection "
                f"file ({strings.load_deflection_file.name}); fit its scale there, not here"
            )
        return replace(
            self.racket,
            strings=replace(
                strings,
                tension_n=strings.tension_n * scale,
                string_modulus_pa=strings.string_modulus_pa * scale,
            ),
        )

    def modes(self) -> ModalModel | None:
        """The modal model used, its damping scaled."""
        if self.modal_model is None:
            return None
        model = _built_in_modes(self.racket) if self.modal_model == "racket" else self.modal_model
        if self.first_bending_hz is not None:
            frequency = model.frequency.copy()
            frequency[first_bending_index(model)] = self.first_bending_hz
            model = model.with_dynamics(frequency=frequency)
        if self.frame_damping_scale == 1.0:
            return model
        damping = np.minimum(model.damping_ratio * self.frame_damping_scale, MAX_DAMPING_RATIO)
        return model.with_dynamics(damping_ratio=damping)

    def law(self, location: tuple[float, float] | None = None) -> RestoringForce:
        """Compound ball + string-bed law of :attr:`effective_racket`: the face centre's, or
        with :attr:`string_bed` ``local`` the one at ``location`` (x, y in m)."""
        if self.string_bed == "local" and location is not None:
            return point_law(self.effective_racket, self.effective_ball, location)
        return compound_law(self.effective_racket, self.effective_ball)


def first_bending_index(model: ModalModel) -> int:
    """Index of the frame's first bending mode: the lowest ``bending`` mode, else the lowest
    frame mode (InputError without one)."""
    order = np.argsort(model.frequency)
    for kinds in (("bending",), ("bending", "twisting", "other", "unknown")):
        found = [int(k) for k in order if model.kinds[k] in kinds]
        if found:
            return found[0]
    raise InputError("`first_bending_hz`: the modal model has no frame mode to set")


def predict_rows(
    inputs: ModelInputs, measured: MeasuredRebound, method: Method
) -> tuple[NDArray[np.float64], NDArray[np.str_]]:
    """Predicted rebound ratio at every measured row.

    Parameters
    ----------
    inputs : ModelInputs
        Racket, ball, hand, modes and the scales.
    measured : MeasuredRebound
        The rows (points, speeds, supports).
    method : {"approx", "transient"}
        Kawazoe's approximate method (eqs 1–12) or the transient simulation.

    Returns
    -------
    rebound_ratio : ndarray (n,)
        Predicted rebound ratio (glossary ``rebound_ratio``); NaN where the status is not ok.
    status : ndarray of str (n,)
        ``ok`` or why the method gives no number (:data:`racketdyn.impact.result.INVALIDATED`,
        :data:`NO_HAND_STATUS`).
    """
    one_of("method", method, METHODS)
    n = len(measured)
    ratio = np.full(n, np.nan)
    status = np.full(n, STATUS_OK, dtype=object)
    racket = inputs.effective_racket
    local = inputs.string_bed == "local"
    model, law = inputs.modes(), None if local else inputs.law()
    keys = list(
        zip(
            measured.support,
            measured.ball_speed.tolist(),
            measured.racket_speed.tolist(),
            strict=True,
        )
    )
    for key in dict.fromkeys(keys):
        support, v_ball, v_racket = key
        rows = np.array([i for i, k in enumerate(keys) if k == key])
        if method == "approx" and support == "hand":
            status[rows] = NO_HAND_STATUS
            continue
        options = {
            "supports": [support],
            "racket_speed": v_racket,
            "modal_model": model,
            "law": law,
            "string_bed": inputs.string_bed,
            "include_string_bed": inputs.include_string_bed,
            "labels": [measured.labels[i] for i in rows],
        }
        if method == "approx":
            result = predict(
                racket, inputs.effective_ball, measured.locations[rows], [v_ball], **options
            )
        else:
            from racketdyn.impact.transient import predict_transient  # numba: only if it runs

            hand = (inputs.hand or Hand()) if support == "hand" else None
            result = predict_transient(
                racket,
                inputs.effective_ball,
                measured.locations[rows],
                [v_ball],
                engine=inputs.engine,  # type: ignore[arg-type]
                hand=hand,
                **options,
            )
        ratio[rows] = result.rebound_ratio[:, 0, 0]
        status[rows] = np.asarray(result.status)[:, 0, 0]
    ratio[status != STATUS_OK] = np.nan
    return ratio, status.astype(str)


def standardised_residuals(
    measured: MeasuredRebound, predicted: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Each row's residual (predicted − measured rebound ratio) in standard deviations.

    With the rows' measured standard deviations, z = (e_pred − e_meas) / sd: how far the model
    misses in the measurement's own scatter, so a model biased by more than that scatter puts
    every row beyond :data:`OUTLIER_LIMIT` (it is the model that misses, and the figure says
    so).  Without them (or at a row whose sd is not positive), z = (r − median r) / (1.4826 ×
    MAD), the median absolute deviation of the residuals about their median: a row off the
    others' pattern.

    Parameters
    ----------
    measured : MeasuredRebound
        The rows (their ``rebound_ratio`` and ``rebound_ratio_sd``).
    predicted : ndarray (n,)
        The model's rebound ratio at each row (NaN where it gives none).

    Returns
    -------
    ndarray (n,)
        z per row; NaN where the prediction is NaN, or where no spread is known (fewer than
        three finite residuals, or all equal, without the rows' sd).
    """
    residual = np.asarray(predicted, dtype=float) - measured.rebound_ratio
    z = np.full(residual.shape, np.nan)
    finite = np.isfinite(residual)
    sd = measured.rebound_ratio_sd
    has_sd = np.zeros(residual.shape, bool) if sd is None else np.isfinite(sd) & (sd > 0)
    mine = finite & has_sd
    if sd is not None:
        z[mine] = residual[mine] / sd[mine]
    rest = finite & ~has_sd
    if np.count_nonzero(finite) >= 3 and np.any(rest):
        centre = float(np.median(residual[finite]))
        spread = ROBUST_SD_PER_MAD * float(np.median(np.abs(residual[finite] - centre)))
        if spread > 0:
            z[rest] = (residual[rest] - centre) / spread
    return z


def outliers(z: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Rows whose standardised residual is beyond ± :data:`OUTLIER_LIMIT` (NaN: not one)."""
    with np.errstate(invalid="ignore"):
        return np.asarray(np.abs(z) > OUTLIER_LIMIT)


def outlier_rank(z: NDArray[np.float64]) -> NDArray[np.int64]:
    """Each row's rank among the outliers: 1 the worst (largest absolute z), 2 the next, …; 0
    for a row that is not one."""
    rows = np.flatnonzero(outliers(z))
    rows = rows[np.argsort(-np.abs(z[rows]), kind="stable")]
    rank = np.zeros(np.shape(z), dtype=np.int64)
    rank[rows] = np.arange(1, rows.size + 1)
    return rank


def outlier_labels(measured: MeasuredRebound, z: NDArray[np.float64]) -> tuple[str, ...]:
    """Labels of the rows beyond ± :data:`OUTLIER_LIMIT`, the worst first
    (:meth:`~racketdyn.io.measured.MeasuredRebound.row_label`)."""
    rank = outlier_rank(z)
    rows = np.flatnonzero(rank)
    return tuple(measured.row_label(int(i)) for i in rows[np.argsort(rank[rows])])
