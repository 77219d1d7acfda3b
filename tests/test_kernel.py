"""The compiled engine of the transient model against the reference engine and closed forms.

The compiled engine (racketdyn.impact.kernel) integrates the racket's linear part exactly for a
contact force linear over each step, so its only error is that interpolation: second order in
the step.  Oracles: the reference engine (scipy DOP853 in physical coordinates, rtol 1e-10 —
itself tested against conservation laws in test_transient.py); the linear oscillator's half
period π sqrt(μ/k); e_BG on a clamped head; the observed order of convergence as the step
halves.  Tolerances are stated at the default 400 steps per contact, where the measured
differences are ≈ 4× smaller than the bounds (docs/develop.md, "Transient engines").
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.impact import kernel
from racketdyn.impact.result import STATUS_BEYOND_LAW, STATUS_OK
from racketdyn.impact.transient import ENERGY_TERMS, predict_transient

POINTS = np.array([[0.505, 0.0], [0.62, 0.0], [0.55, 0.06], [0.40, -0.04]])
SPEEDS = [8.0, 25.0, 40.0]
SUPPORTS = ("free", "pinned", "hand")

pytestmark = pytest.mark.skipif(not kernel.NUMBA_AVAILABLE, reason="numba is not installed")


@pytest.fixture(scope="module")
def both(racket, ball, model):
    kwargs = {"modal_model": model, "racket_speed": 3.0}
    compiled = predict_transient(
        racket, ball, POINTS, SPEEDS, SUPPORTS, engine="compiled", **kwargs
    )
    reference = predict_transient(
        racket, ball, POINTS, SPEEDS, SUPPORTS, engine="reference", **kwargs
    )
    return compiled, reference


def test_engines_agree(both) -> None:
    """Every support, point and speed: rebound speed within 5e-4 m/s (≈ 1e-5 of the approach
    speed), contact time within 3e-5 (a review measured 1.6e-5 at the tip, held), peak force
    within 1e-5, mode energy within 2e-4 J + 0.2 % (measured 1.1e-4 J)."""
    compiled, reference = both
    assert np.all(compiled.status == STATUS_OK)
    assert np.all(reference.status == STATUS_OK)
    np.testing.assert_allclose(compiled.rebound_speed, reference.rebound_speed, atol=5e-4)
    np.testing.assert_allclose(compiled.contact_time, reference.contact_time, rtol=3e-5)
    np.testing.assert_allclose(compiled.peak_force, reference.peak_force, rtol=1e-5)
    np.testing.assert_allclose(compiled.peak_deflection, reference.peak_deflection, rtol=1e-5)
    np.testing.assert_allclose(compiled.mode_energy, reference.mode_energy, rtol=2e-3, atol=5e-4)
    np.testing.assert_allclose(compiled.cor, reference.cor, atol=5e-5)


def _single(racket, ball, model, engine: str, **kwargs) -> rd.ImpactResult:
    return predict_transient(
        racket, ball, [(0.60, 0.02)], [30.0], "free", modal_model=model, engine=engine, **kwargs
    )


def test_second_order_convergence(racket, ball, model) -> None:
    """The scheme without extrapolation: halving the step divides the error by 4, observed
    order between 1.8 and 2.2 for the rebound speed and the contact time (reference at rtol
    1e-12 is ≥ 100× more accurate)."""
    exact = _single(racket, ball, model, "reference", rtol=1e-12)
    steps = [100, 200, 400, 800]
    runs = [
        _single(racket, ball, model, "compiled", steps_per_contact=n, extrapolate=False)
        for n in steps
    ]
    for name in ("rebound_speed", "contact_time"):
        errors = np.array(
            [abs(float(getattr(r, name)[0, 0, 0] - getattr(exact, name)[0, 0, 0])) for r in runs]
        )
        orders = np.log2(errors[:-1] / errors[1:])
        assert np.all((orders > 1.8) & (orders < 2.2)), (name, errors, orders)


def test_linear_spring_rigid_racket_half_period(racket) -> None:
    """Rigid racket, linear spring, e_BG = 1: T_c = π sqrt(μ/k) and the elastic two-body rebound
    (M_r − m_B)/(M_r + m_B), both to 2e-5 at 400 steps (the interpolation error, ≈ (π/400)²/3)."""
    ball = rd.Ball(e_bg=1.0)
    k = 2.0e4
    linear = rd.RestoringForce("polynomial", (k,), 0.2, 0.0, "linear test spring")
    result = predict_transient(
        racket, ball, POINTS, [5.0, 30.0], ("free", "pinned"), modal_model=None, law=linear,
        engine="compiled",
    )  # fmt: skip
    m_r = result.reduced_mass[:, None, :]
    mu = ball.mass_kg * m_r / (ball.mass_kg + m_r)
    expected_time = np.broadcast_to(np.pi * np.sqrt(mu / k), result.shape)
    np.testing.assert_allclose(result.contact_time, expected_time, rtol=2e-5)
    expected_ratio = np.broadcast_to((m_r - ball.mass_kg) / (m_r + ball.mass_kg), result.shape)
    np.testing.assert_allclose(result.rebound_ratio, expected_ratio, atol=2e-5)


@pytest.mark.parametrize("speed", [5.0, 20.0, 40.0])
def test_clamped_head_returns_e_bg(ball, law, speed) -> None:
    """No racket motion (zero compliance, no modes): the ball leaves at e_BG of its speed, to
    1e-5 (the hysteresis law is built for it; the residue is the second-order error)."""
    kind, coefficients = kernel.law_arrays(law.kind, law.coefficients)
    t_guess = 5e-3
    _, raw = kernel.integrate_impacts(
        np.array([0]), np.array([speed]), np.array([t_guess / 400]), np.zeros((1, 0), complex),
        np.zeros((1, 0), complex), np.zeros((1, 0)), np.zeros(1), ball.mass_kg, ball.e_bg, kind,
        coefficients, law.max_deflection_m, 20_000,
    )  # fmt: skip
    assert raw[0, 0] == kernel.STATUS_CODE_OK
    assert -raw[0, 4] / speed == pytest.approx(ball.e_bg, rel=1e-5)


def test_plain_python_path_is_the_same_arithmetic(racket, ball, model) -> None:
    """The kernel run as plain Python (its fallback without numba) gives the compiled numbers
    to 1e-11: the same operations, only compiled."""
    system_form = rd.impact.system.impact_system(racket, model, "free", POINTS[:2]).pole_residue()
    law = rd.compound_law(racket, ball)
    kind, coefficients = kernel.law_arrays(law.kind, law.coefficients)
    args = (
        np.array([0, 1]), np.array([20.0, 35.0]), np.array([1.3e-5, 1.2e-5]),
        np.repeat(system_form.poles[None, :], 2, axis=0), system_form.residues,
        np.repeat(system_form.weights[None, :], 2, axis=0), system_form.rigid_compliance,
        ball.mass_kg, np.full(2, ball.e_bg), kind, coefficients, law.max_deflection_m, 20_000,
        True,
    )  # fmt: skip
    modal_fast, raw_fast = kernel.integrate_impacts(*args)
    n = 2
    modal_slow = np.zeros((n, system_form.poles.size), complex)
    raw_slow = np.zeros((n, 8))
    kernel._integrate_batch.py_func(
        *(np.ascontiguousarray(a) if isinstance(a, np.ndarray) else a for a in args),
        modal_slow, raw_slow,
    )  # fmt: skip
    np.testing.assert_allclose(raw_slow, raw_fast, rtol=1e-11, atol=1e-15)
    np.testing.assert_allclose(modal_slow, modal_fast, rtol=1e-10, atol=1e-18)


def test_energy_terms_match_the_reference(both) -> None:
    """Where the energy goes (rest frame before impact): the reference engine's terms close to
    1e-6 of the energy in (its damping loss is integrated, so this can fail); the compiled
    engine's damping loss is what its balance leaves, and every one of its terms equals the
    reference's within 5e-4 J + 0.2 %."""
    compiled, reference = both
    assert compiled.energy_terms is not None
    assert reference.energy_terms is not None
    terms = reference.energy_terms
    parts = sum(terms[name] for name in ENERGY_TERMS[1:])
    np.testing.assert_allclose(parts, terms["energy_in_j"], rtol=1e-6)
    for name in ENERGY_TERMS:
        np.testing.assert_allclose(
            compiled.energy_terms[name], terms[name], rtol=2e-3, atol=5e-4, err_msg=name
        )
    assert np.all(compiled.energy_terms["damping_loss_j"] > -5e-4)
    hand = SUPPORTS.index("hand")
    assert np.all(terms["support_energy_j"][..., hand] > 0)
    np.testing.assert_allclose(terms["support_energy_j"][..., :hand], 0.0, atol=1e-9)


def test_beyond_the_law_is_flagged(racket, ball, model) -> None:
    """An approach past the law's range (here 160 m/s; the law covers ≈ 130 m/s on the free
    racket's centre since the high-speed laws, docs/references.md) is flagged, not
    extrapolated."""
    result = predict_transient(
        racket, ball, POINTS[:1], [160.0], "free", modal_model=model, engine="compiled"
    )
    assert result.status[0, 0, 0] == STATUS_BEYOND_LAW
    assert math.isnan(result.rebound_speed[0, 0, 0])


@pytest.mark.parametrize("exponent", [1.5, 0.8])
def test_power_law_branch(racket, ball, model, exponent) -> None:
    """A power law F = c Xⁿ (the kernel's other branch, closed-form unloading exponent): the
    engines agree within 1e-3 m/s at n = 1.5 and 0.8 (order 1 + n < 2 for n < 1: the force is
    not smooth at X = 0; a review measured 6e-5 and 4.5e-4 m/s)."""
    law = rd.RestoringForce("power", (4.0e4 * 0.01 ** (1 - exponent), exponent), 0.1, 0.0, "test")
    kwargs = {"modal_model": model, "law": law}
    fast = predict_transient(racket, ball, POINTS[:2], [20.0], "free", engine="compiled", **kwargs)
    slow = predict_transient(racket, ball, POINTS[:2], [20.0], "free", engine="reference", **kwargs)
    np.testing.assert_allclose(fast.rebound_speed, slow.rebound_speed, atol=1e-3)
    np.testing.assert_allclose(fast.contact_time, slow.contact_time, rtol=2e-4)


def test_overdamped_hand_gives_real_poles(racket, ball, model) -> None:
    """A grip damped past critical makes real poles (weight 1 in the kernel): the engines still
    agree within 5e-4 m/s."""
    from racketdyn.impact.hand import Hand
    from racketdyn.impact.system import impact_system

    hand = Hand(damping_ns_per_m=2000.0)
    form = impact_system(racket, model, "hand", POINTS[:1], hand).pole_residue()
    assert np.any(form.weights == 1.0)
    kwargs = {"modal_model": model, "hand": hand}
    fast = predict_transient(racket, ball, POINTS, [20.0], "hand", engine="compiled", **kwargs)
    slow = predict_transient(racket, ball, POINTS, [20.0], "hand", engine="reference", **kwargs)
    np.testing.assert_allclose(fast.rebound_speed, slow.rebound_speed, atol=5e-4)
