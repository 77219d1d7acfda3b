"""Workflows (layer 3): one function per step, called by the CLI, the demo and Python users.

Each step takes plain inputs (objects and paths), runs the step, writes its data files into a
run folder with a ``run.json`` (:mod:`racketdyn.workflows.run`) and returns a result object
(the paths written and the computed objects).  Workflows draw no figures and print nothing:
figures come from a hook the caller passes (``figures(result, out) -> paths``), progress from a
``progress(what, done, total)`` callback, and they log with :mod:`logging`.

==========================  =========================================================
:func:`run_ball`            the ball's bounce on a rigid surface and clamped strings
:func:`run_rig`             virtual roving-hammer test (UFF)
:func:`run_frf`             FRFs and quality table from hammer records
:func:`run_contact`         hammer contact time over the face
:func:`run_identify`        modal model from FRFs
:func:`run_compare`         free against hand-held identification
:func:`run_compare_ball`    the racket alone against the racket with a ball (Fig. 9)
:func:`run_predict`         impacts over the face: approximate, transient or both
:func:`run_swing`           a swinging racket and its sweet spots
:func:`run_oblique`         oblique impacts with spin
:func:`run_twist`           off-axis impacts: roll and twist
:func:`run_compound`        a ball fixed on the strings: the compound modes (Figs 8–9)
:func:`run_validate`        predicted against measured rebound, both models
:func:`run_calibrate`       uncertain inputs fitted to measured rebound
:func:`run_sweep_step`      a design sweep
==========================  =========================================================

What each step's figures draw is computed by the step (:mod:`racketdyn.workflows.figure_data`:
:class:`PaperFigures`, :class:`TransientCurves`, :class:`ComparisonMap`,
:class:`TransientHistories`, :class:`SwingAxisCurves`, :class:`IdentifiedRebound`, each with
``to_xarray``/``from_xarray``) and written to its folder's ``figures.nc``
(:func:`read_figure_data` reads it back; :func:`read_step_data` gives a folder's figure data,
which :func:`racketdyn.plotting.registry.draw` redraws).

What every step shares — the racket and its modes, the ball, the hand, the string bed, the
plausibility override, the command, the figure hook and the progress display — travels in one
frozen :class:`Setup` (:mod:`racketdyn.workflows.setup`), documented there once.

Example
-------
>>> from racketdyn.workflows import PredictOptions, Setup, run_predict
>>> options = PredictOptions(speeds=[20.0], grid=3)
>>> result = run_predict("out", Setup(rigid=True), options)  # doctest: +SKIP
>>> result.written  # doctest: +SKIP
[PosixPath('out/impact.csv')]

Submodules are imported when first used (SPEC 1), so ``import racketdyn.workflows`` is cheap.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from racketdyn.workflows.ball import BallResult, run_ball
    from racketdyn.workflows.calibrate import CalibrateResult, run_calibrate
    from racketdyn.workflows.compound import CompoundResult, run_compound
    from racketdyn.workflows.contact import ContactResult, run_contact
    from racketdyn.workflows.figure_data import (
        ComparisonMap,
        FrameVibration,
        IdentifiedRebound,
        ImpactCurves,
        PaperFigures,
        PulseSpectra,
        SwingAxisCurves,
        TransientCurves,
        TransientHistories,
        read_figure_data,
        read_step_data,
    )
    from racketdyn.workflows.frf import FrfResult, run_frf
    from racketdyn.workflows.identify import (
        BallCompareResult,
        CompareResult,
        IdentifyOptions,
        IdentifyResult,
        run_compare,
        run_compare_ball,
        run_identify,
    )
    from racketdyn.workflows.oblique import ObliqueOptions, ObliqueResult, run_oblique
    from racketdyn.workflows.predict import PredictOptions, PredictResult, run_predict
    from racketdyn.workflows.rig import RigOptions, RigResult, run_rig
    from racketdyn.workflows.run import StepResult
    from racketdyn.workflows.setup import Setup
    from racketdyn.workflows.sweep import SweepResult, run_sweep_step
    from racketdyn.workflows.swing import SwingStepResult, run_swing
    from racketdyn.workflows.twist import TwistResult, run_twist
    from racketdyn.workflows.validate import ValidateResult, run_validate

_WHERE = {
    "ComparisonMap": "figure_data",
    "FrameVibration": "figure_data",
    "IdentifiedRebound": "figure_data",
    "ImpactCurves": "figure_data",
    "PaperFigures": "figure_data",
    "PulseSpectra": "figure_data",
    "SwingAxisCurves": "figure_data",
    "TransientCurves": "figure_data",
    "TransientHistories": "figure_data",
    "read_figure_data": "figure_data",
    "read_step_data": "figure_data",
    "BallCompareResult": "identify",
    "BallResult": "ball",
    "run_ball": "ball",
    "CalibrateResult": "calibrate",
    "ValidateResult": "validate",
    "run_calibrate": "calibrate",
    "run_validate": "validate",
    "CompareResult": "identify",
    "CompoundResult": "compound",
    "ContactResult": "contact",
    "FrfResult": "frf",
    "IdentifyOptions": "identify",
    "IdentifyResult": "identify",
    "ObliqueOptions": "oblique",
    "ObliqueResult": "oblique",
    "PredictOptions": "predict",
    "PredictResult": "predict",
    "RigOptions": "rig",
    "RigResult": "rig",
    "StepResult": "run",
    "Setup": "setup",
    "SweepResult": "sweep",
    "SwingStepResult": "swing",
    "TwistResult": "twist",
    "run_compare": "identify",
    "run_compare_ball": "identify",
    "run_compound": "compound",
    "run_contact": "contact",
    "run_frf": "frf",
    "run_identify": "identify",
    "run_oblique": "oblique",
    "run_predict": "predict",
    "run_rig": "rig",
    "run_sweep_step": "sweep",
    "run_swing": "swing",
    "run_twist": "twist",
}

__all__ = [
    "BallCompareResult",
    "BallResult",
    "CalibrateResult",
    "CompareResult",
    "ComparisonMap",
    "CompoundResult",
    "ContactResult",
    "FrameVibration",
    "FrfResult",
    "IdentifiedRebound",
    "IdentifyOptions",
    "IdentifyResult",
    "ImpactCurves",
    "ObliqueOptions",
    "ObliqueResult",
    "PaperFigures",
    "PredictOptions",
    "PredictResult",
    "PulseSpectra",
    "RigOptions",
    "RigResult",
    "Setup",
    "StepResult",
    "SweepResult",
    "SwingAxisCurves",
    "SwingStepResult",
    "TransientCurves",
    "TransientHistories",
    "TwistResult",
    "ValidateResult",
    "read_figure_data",
    "read_step_data",
    "run_ball",
    "run_calibrate",
    "run_compare",
    "run_compare_ball",
    "run_compound",
    "run_contact",
    "run_frf",
    "run_identify",
    "run_oblique",
    "run_predict",
    "run_rig",
    "run_sweep_step",
    "run_swing",
    "run_twist",
    "run_validate",
]


def __getattr__(name: str) -> Any:
    if name in _WHERE:
        return getattr(importlib.import_module(f"racketdyn.workflows.{_WHERE[name]}"), name)
    raise AttributeError(f"module 'racketdyn.workflows' has no attribute {name!r}")


def __dir__() -> list[str]:
    return __all__
