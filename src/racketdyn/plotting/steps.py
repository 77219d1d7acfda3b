"""Figure hooks: what each workflow step draws (the CLI, the demo and Python users pass them).

Each hook has the shape the workflows take, ``hook(result, out) -> paths``: a step whose
figures are all drawn from its result's data draws the registry's entries of the step
(:func:`racketdyn.plotting.registry.write_figures`); the others call their writers in
:mod:`racketdyn.plotting.figures` (imported when a hook runs: matplotlib is loaded only when
figures are drawn).  ``status`` shows what is being drawn.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, TypeVar

if TYPE_CHECKING:
    from racketdyn.sweep.summary import SummaryCurves
    from racketdyn.workflows.ball import BallResult
    from racketdyn.workflows.calibrate import CalibrateResult
    from racketdyn.workflows.compound import CompoundResult
    from racketdyn.workflows.contact import ContactResult
    from racketdyn.workflows.frf import FrfResult
    from racketdyn.workflows.identify import BallCompareResult, CompareResult, IdentifyResult
    from racketdyn.workflows.oblique import ObliqueResult
    from racketdyn.workflows.predict import PredictResult
    from racketdyn.workflows.swing import SwingStepResult
    from racketdyn.workflows.twist import TwistResult
    from racketdyn.workflows.validate import ValidateResult

__all__ = [
    "ball_figures",
    "calibrate_figures",
    "compare_ball_figures",
    "compare_figures",
    "compound_figures",
    "contact_figures",
    "frf_figures",
    "identify_figures",
    "oblique_figures",
    "predict_figures",
    "sweep_figures",
    "swing_figures",
    "twist_figures",
    "validate_figures",
]

Status = Callable[[str], None]
Hook = TypeVar("Hook", bound=Callable[..., list[Path]])


def _quiet(_: str) -> None:
    return None


def _writes_pending(hook: Hook) -> Hook:
    """Mark a hook that writes the step's deferred files itself, while its figures are drawn
    (:data:`racketdyn.workflows.run.WRITES_PENDING`: ``write_figures`` does)."""
    from racketdyn.workflows.run import WRITES_PENDING

    setattr(hook, WRITES_PENDING, True)
    return hook


def predict_figures(status: Status = _quiet) -> Callable[[PredictResult, Path], list[Path]]:
    """The paper's figures (approximate method) and the transient model's figures, drawn from
    what the run computed (its ``paper_figures``, ``transient_curves``, ``comparison_map`` and
    ``transient_histories``: the data of ``figures.nc``), as the registry lists them."""

    def draw(result: PredictResult, out: Path) -> list[Path]:
        from racketdyn.plotting.registry import write_figures

        return write_figures("predict", result, out, status)

    return _writes_pending(draw)


def frf_figures(result: FrfResult, out: Path) -> list[Path]:
    """Paper Figs 2–3."""
    from racketdyn.plotting.registry import write_figures

    return write_figures("frf", result, out)


def contact_figures(result: ContactResult, out: Path) -> list[Path]:
    """Paper Fig. 7."""
    from racketdyn.plotting.registry import write_figures

    return write_figures("contact", result, out)


def identify_figures(result: IdentifyResult, out: Path) -> list[Path]:
    """Stabilisation diagram, Figs 4–6, synthesised FRFs, AutoMAC."""
    from racketdyn.plotting.registry import write_figures

    return write_figures("identify", result, out)


_writes_pending(identify_figures)


def compare_figures(result: CompareResult, out: Path) -> list[Path]:
    """Both identifications' figures (``_free``, ``_hand``), the comparison figures and the
    Fig. 15 check (with the run's ball)."""
    from racketdyn.plotting.registry import write_figures

    written = []
    for label, fits, shapes in (
        ("free", result.fit_free, result.shapes_free),
        ("hand", result.fit_hand, result.shapes_hand),
    ):
        data = {"fit_figures": fits, "shape_figures": shapes}
        written += write_figures("identify", data, out, label=label)
    return written + write_figures("compare", result, out)


def compare_ball_figures(result: BallCompareResult, out: Path) -> list[Path]:
    """The FRFs of the racket alone and with the ball (the paper's Figs 9a and 9b)."""
    from racketdyn.plotting.registry import write_figures

    return write_figures("compare --ball-at", result, out)


def swing_figures(result: SwingStepResult, out: Path) -> list[Path]:
    """The swing map and the outgoing speed along the axis."""
    from racketdyn.plotting.registry import write_figures

    return write_figures("swing", result, out)


def ball_figures(result: BallResult, out: Path) -> list[Path]:
    """Force against the ball's flattening, one loop per speed and surface."""
    from racketdyn.plotting.registry import write_figures

    return write_figures("ball", result, out)


def twist_figures(result: TwistResult, out: Path) -> list[Path]:
    """Roll and outgoing speed against offset."""
    from racketdyn.plotting.registry import write_figures

    return write_figures("twist", result, out)


def oblique_figures(result: ObliqueResult, out: Path) -> list[Path]:
    """Outgoing angle and spin against incoming angle."""
    from racketdyn.plotting.registry import write_figures

    return write_figures("oblique", result, out)


def compound_figures(result: CompoundResult, out: Path) -> list[Path]:
    """The neck's response (Fig. 8c) and the FRFs without and with the ball (Fig. 9)."""
    from racketdyn.plotting.compound import write_compound_figures

    return write_compound_figures(result, out)


def calibrate_figures(result: CalibrateResult, out: Path) -> list[Path]:
    """Before and after calibration against measured (1:1 line, error bars, outliers named)."""
    from racketdyn.plotting.validate import write_calibrate_figures

    return write_calibrate_figures(result, out)


def validate_figures(result: ValidateResult, out: Path) -> list[Path]:
    """Predicted against measured (1:1 line), along the axis, and the residual map."""
    from racketdyn.plotting.validate import write_validate_figures

    return write_validate_figures(result, out)


def sweep_figures(curves: Mapping[str, SummaryCurves], out: Path) -> list[Path]:
    """``summary_<variable>.png`` of each variable: the centre rebound and the sweet area
    against it (the curves :func:`racketdyn.sweep.run_sweep` computed, by variable)."""
    from racketdyn.plotting.registry import write_figures

    written = []
    for variable, data in curves.items():
        written += write_figures("sweep", {"curves": data}, out, label=variable)
    return written
