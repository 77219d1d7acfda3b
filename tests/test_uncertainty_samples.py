"""Issue 24's speed: the approximate method over every sample at once
(:func:`racketdyn.impact.samples.predict_samples`) gives the numbers of one ``predict`` call
per sample, to round-off, with every uncertain input varied and invalid samples among them."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
import pytest

import racketdyn.impact.uncertainty as uncertainty_module
from racketdyn.ball import Ball
from racketdyn.impact.measured import ModelInputs
from racketdyn.impact.uncertainty import (
    BAND_QUANTITIES,
    UNCERTAIN_INPUTS,
    Spread,
    UncertainResult,
    Uncertainty,
    propagate,
)
from racketdyn.io.racket_file import default_racket

RACKET = default_racket()
ROLL = RACKET.roll_inertia_kgm2

# every registry input: the ones that change the law, the racket or the shapes as a few
# values (the samples fall into groups), the rest continuous; location and speed wide enough
# for frame shots, impacts beyond the vibration share and a ball speed offset to below zero
EVERY_INPUT = (
    Spread("e_bg", bounds=(0.78, 0.90)),
    Spread("first_bending_hz", bounds=(100.0, 190.0)),
    Spread("ball_stiffness_scale", values=(0.85, 1.15)),
    Spread("string_stiffness_scale", values=(0.9, 1.0, 1.1)),
    Spread("frame_damping_scale", bounds=(0.5, 2.0)),
    Spread("roll_inertia_kgm2", values=(0.9 * ROLL, 1.1 * ROLL)),
    Spread("hand_stiffness_n_per_m", bounds=(1e4, 3e4)),
    Spread("hand_damping_ns_per_m", bounds=(20.0, 60.0)),
    Spread("hand_arm_mass_kg", bounds=(1.0, 2.0)),
    Spread("location_m", sd=0.02),
    Spread("ball_speed_mps", sd=3.0),
)
SPEEDS = (2.0, 20.0, 45.0)


def _both(inputs: ModelInputs, **options: Any) -> tuple[UncertainResult, UncertainResult]:
    uncertainty = Uncertainty(EVERY_INPUT, samples=32, seed=5)
    points = RACKET.head.grid(7)
    run = {"supports": ("free", "pinned"), **options}
    at_once = propagate(inputs, points, SPEEDS, uncertainty, **run)
    each = propagate(inputs, points, SPEEDS, uncertainty, vectorised=False, **run)
    return at_once, each


def test_every_input_is_varied() -> None:
    assert {s.name for s in EVERY_INPUT} == set(UNCERTAIN_INPUTS)


@pytest.mark.parametrize(
    ("ball", "options"),
    [
        (Ball(), {}),  # e_BG from ball + strings: a table shifted per sample
        (
            Ball(e_bg=0.84),  # a constant e_BG, replaced per sample
            {"options": {"stiffness_reading": "tangent", "vibration_charge": "paper"}},
        ),
    ],
    ids=["derived-e_bg", "constant-e_bg-tangent-paper"],
)
def test_every_sample_at_once_gives_the_numbers_of_one_predict_per_sample(
    ball: Ball, options: dict[str, Any]
) -> None:
    at_once, each = _both(ModelInputs(RACKET, ball), **options)
    assert np.array_equal(at_once.valid, each.valid)
    assert at_once.valid.any()
    assert not at_once.valid.all()
    for name in BAND_QUANTITIES:
        np.testing.assert_allclose(
            at_once.samples[name], each.samples[name], rtol=1e-10, atol=1e-12, err_msg=name
        )
    np.testing.assert_allclose(
        at_once.quantile("rebound_ratio", 0.95), each.quantile("rebound_ratio", 0.95), atol=1e-12
    )


def test_a_rigid_racket_and_a_given_first_bending_frequency_too() -> None:
    rigid = ModelInputs(RACKET, Ball(), modal_model=None)
    spreads = tuple(s for s in EVERY_INPUT if s.name != "first_bending_hz")
    for inputs, chosen in (
        (rigid, spreads),
        (replace(ModelInputs(RACKET, Ball()), first_bending_hz=150.0), spreads),
    ):
        uncertainty = Uncertainty(chosen, samples=16, seed=2)
        at_once = propagate(inputs, RACKET.head.grid(5), [20.0], uncertainty)
        each = propagate(inputs, RACKET.head.grid(5), [20.0], uncertainty, vectorised=False)
        assert np.array_equal(at_once.valid, each.valid)
        np.testing.assert_allclose(
            at_once.samples["rebound_ratio"], each.samples["rebound_ratio"], atol=1e-12
        )


def test_the_approximate_method_is_not_run_once_per_sample(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Before: ``predict`` once per sample (≈ 5 ms each on the built-in grid); now once, for
    the nominal impacts, and the samples in arrays."""
    calls = []
    original = uncertainty_module.predict

    def counted(*args: Any, **kwargs: Any) -> Any:
        calls.append(1)
        return original(*args, **kwargs)

    monkeypatch.setattr(uncertainty_module, "predict", counted)
    spreads = (Spread("e_bg", bounds=(0.8, 0.88)), Spread("location_m", sd=0.01))
    propagate(ModelInputs(RACKET, Ball()), RACKET.head.grid(5), [20.0], Uncertainty(spreads, 64))
    assert len(calls) == 1


def test_the_transient_model_s_samples_run_on_a_process_pool() -> None:
    """The transient model runs once per sample: on the sweeps' process pool the samples are
    the same, and the numbers."""
    from racketdyn.sweep.executors import make_executor

    spreads = (Spread("e_bg", bounds=(0.8, 0.88)), Spread("location_m", sd=0.01))
    uncertainty = Uncertainty(spreads, samples=8, seed=1)
    inputs = ModelInputs(RACKET, Ball())
    points = RACKET.head.grid(3)
    here = propagate(inputs, points, [20.0], uncertainty, method="transient")
    done: list[int] = []
    with make_executor("process", 2) as pool:
        pooled = propagate(
            inputs,
            points,
            [20.0],
            uncertainty,
            method="transient",
            executor=pool,
            progress=lambda k, n: done.append(k),
        )
    assert done[-1] == 8
    assert np.array_equal(here.valid, pooled.valid)
    for name in BAND_QUANTITIES:
        # 1e-6, the compiled kernel's own accuracy (tests/test_kernel.py: 1e-6 of the rebound
        # speed against the reference engine): alone the two agree to the bit, but after the
        # full suite has run in this process they differed by up to 8e-8 (CI) — a state some
        # earlier test leaves in this process, not found yet (docs/develop.md, issue 24)
        np.testing.assert_allclose(pooled.samples[name], here.samples[name], rtol=1e-6)


def test_the_transient_model_s_sobol_runs_on_a_process_pool() -> None:
    from racketdyn.impact.uncertainty import sensitivity
    from racketdyn.sweep.executors import make_executor

    uncertainty = Uncertainty((Spread("e_bg", bounds=(0.8, 0.88)),), seed=2)
    inputs = ModelInputs(RACKET, Ball())
    points = {"centre": (RACKET.head.centre_x_m, RACKET.head.centre_y_m)}
    here = sensitivity(inputs, points, 20.0, uncertainty, n=8, method="transient")
    with make_executor("process", 2) as pool:
        pooled = sensitivity(
            inputs, points, 20.0, uncertainty, n=8, method="transient", executor=pool
        )
    np.testing.assert_allclose(pooled.total_order, here.total_order, rtol=1e-6)  # as above
