"""What the figures of measured FRFs draw, chosen by the step (issue 23): the points of Figs 2–3
(``frf``), the stabilisation diagram and the synthesised FRFs (``identify``, ``compare``), and
the FRFs alone and with the ball of Fig. 9 (``compare --ball-at``).

Each is a frozen dataclass of the step's own arrays, the drawn points only, written to the
run's ``figures.nc`` as it is (:func:`racketdyn.workflows._figure_io.store`) and read back by
:func:`racketdyn.workflows.figure_data.read_step_data`: the figures redraw from the folder
alone.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from racketdyn.measurement.records import FrfSet, SummedFrf
from racketdyn.modal.identify import Identification
from racketdyn.modal.poles import SelectedPoles, Stabilisation
from racketdyn.racket import Racket
from racketdyn.workflows.shape_figures import is_racket_model

__all__ = [
    "BallFrfs",
    "FitFigures",
    "FrfPoints",
    "SynthesisedFrfs",
    "ball_frfs",
    "fit_figures",
    "frf_points",
]


def _nearest_centre(frfs: FrfSet, racket: Racket, dimensions: int | None = 2) -> int:
    """The index of the point nearest the string-bed centre (in x–y, or over every
    coordinate when ``dimensions`` is None)."""
    centre = np.array([racket.head.centre_x_m, racket.head.centre_y_m])
    return int(np.argmin(np.linalg.norm(frfs.locations[:, :dimensions] - centre, axis=1)))


@dataclass(frozen=True)
class FrfPoints:
    """The FRFs of paper Figs 2–3: the frame's driving point and the point nearest the
    string-bed centre (one point when they are one).

    Attributes
    ----------
    frfs : FrfSet
        The estimated FRFs of those points only.
    frame : int
        Index in ``frfs`` of Fig. 2's point: the driving point (without one, the first point).
    centre : int
        Index in ``frfs`` of Fig. 3's point, nearest the string-bed centre.
    """

    frfs: FrfSet
    frame: int
    centre: int


def frf_points(frfs: FrfSet, racket: Racket) -> FrfPoints:
    """The points Figs 2–3 draw of a step's FRFs.

    Parameters
    ----------
    frfs : FrfSet
        Every estimated FRF.
    racket : Racket
        The racket (its string-bed centre).
    """
    frame = frfs.driving_point if frfs.driving_point is not None else 0
    centre = _nearest_centre(frfs, racket)
    picks = sorted({frame, centre})
    return FrfPoints(frfs.at_points(picks), picks.index(frame), picks.index(centre))


@dataclass(frozen=True)
class SynthesisedFrfs:
    """Measured FRFs against those synthesised from the identified model, at the points drawn:
    the driving point and the point nearest the string-bed centre (a racket's modes) or the
    worst-fitted point.

    Attributes
    ----------
    frfs : FrfSet
        The measured FRFs of the points drawn.
    frequency : ndarray (n_fit,)
        The fit's frequency lines, Hz.
    synthesised : ndarray (n_points, n_fit)
        The synthesised FRFs of those points, in the units of ``frfs``.
    error : ndarray (n_points,)
        Each point's fit error (relative).
    """

    frfs: FrfSet
    frequency: NDArray[np.float64]
    synthesised: NDArray[np.complex128]
    error: NDArray[np.float64]


@dataclass(frozen=True)
class FitFigures:
    """What an identification's stabilisation diagram and synthesised FRFs draw.

    Attributes
    ----------
    stabilisation : Stabilisation
        The poles of every order (their residues, not drawn, left out: an empty array).
    selected : SelectedPoles
        The selected modes.
    summed : SummedFrf
        Σ|H| of the FRFs over the band.
    synthesised : SynthesisedFrfs
        The synthesised FRFs' figure.
    """

    stabilisation: Stabilisation
    selected: SelectedPoles
    summed: SummedFrf
    synthesised: SynthesisedFrfs


def fit_figures(identification: Identification, racket: Racket) -> FitFigures:
    """The data of an identification's stabilisation and synthesised-FRF figures.

    Parameters
    ----------
    identification : Identification
        The step's identification.
    racket : Racket
        The racket of the run (its string-bed centre).
    """
    model, frfs, fit = identification.model, identification.frfs, identification.fit
    if is_racket_model(model):
        second = _nearest_centre(frfs, racket, None)
    else:
        second = int(np.argmax(fit.error))  # the worst-fitted point
    picks = sorted({frfs.driving_point or 0, second})
    stab = identification.stabilisation
    return FitFigures(
        replace(stab, residues=np.zeros((stab.residues.shape[0], 0), dtype=complex)),
        identification.selected,
        frfs.summed(*stab.band_hz),
        SynthesisedFrfs(
            frfs.at_points(picks), fit.frequency, fit.synthesised[picks], fit.error[picks]
        ),
    )


@dataclass(frozen=True)
class BallFrfs:
    """What ``compare --ball-at``'s Fig. 9 draws: one hammer point's measured FRF of the racket
    alone and with the ball, as accelerance, and the modes identified from each.

    Attributes
    ----------
    alone, with_ball : FrfSet
        The shown point's FRF (one point: the step's ``shown_node``), accelerance.
    alone_hz, with_ball_hz : ndarray
        The identified modes' frequencies, Hz.
    alone_names, with_ball_names : tuple of str
        Their names (the ball's is :data:`racketdyn.racket_modal.shapes.BALL_MODE_NAME`).
    ball_at : tuple of float
        Where the ball sits (x, y), m.
    support : str
        The racket's support.
    """

    alone: FrfSet
    with_ball: FrfSet
    alone_hz: NDArray[np.float64]
    with_ball_hz: NDArray[np.float64]
    alone_names: tuple[str, ...]
    with_ball_names: tuple[str, ...]
    ball_at: tuple[float, float]
    support: str


def ball_frfs(
    alone: Identification, with_ball: Identification, node: int, ball_at: tuple[float, float]
) -> BallFrfs:
    """Fig. 9's data of ``compare --ball-at``.

    Parameters
    ----------
    alone, with_ball : Identification
        The identifications of the racket alone and with the ball.
    node : int
        The hammer point shown (in both sets).
    ball_at : tuple of float
        Where the ball sits (x, y), m.
    """
    first = alone.frfs.as_type("accelerance")
    second = with_ball.frfs.as_type("accelerance")
    return BallFrfs(
        first.at_points([first.nodes.index(node)]),
        second.at_points([second.nodes.index(node)]),
        alone.model.frequency,
        with_ball.model.frequency,
        alone.model.names,
        with_ball.model.names,
        ball_at,
        alone.model.support,
    )
