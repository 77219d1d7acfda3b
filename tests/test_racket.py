"""Mass properties and reduced mass against the paper and the rigid-body laws."""

from __future__ import annotations

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.errors import InputError
from racketdyn.racket import MassProperties, PointMass
from racketdyn.racket_modal.beam import hoop_roll_inertia


def test_grip_inertia_matches_paper(racket: rd.Racket) -> None:
    # Paper, section 2 (docs/references.md): 33.5 g·m² about the grip 70 mm from the butt,
    # from 13.1 g·m² about the CG by the parallel-axis theorem; ±0.1 g·m² is the paper's rounding.
    assert racket.inertia_about_axis(0.070) * 1e3 == pytest.approx(33.5, abs=0.1)


def test_swingweight_and_recoil_weight(racket: rd.Racket) -> None:
    # Parallel axis to 100 mm from the butt, in kg·cm²; recoil weight is I about the CG.
    expected = (0.0131 + 0.360 * (0.308 - 0.100) ** 2) * 1e4
    assert racket.swingweight_kgcm2 == pytest.approx(expected, rel=1e-12)
    assert racket.recoil_weight_kgcm2 == pytest.approx(131.0, rel=1e-12)


def test_default_roll_inertia_is_the_hoop_model(racket: rd.Racket) -> None:
    # The paper gives no roll inertia: the built-in file leaves it out and the loader derives it.
    derived = hoop_roll_inertia(0.680, 0.360, 0.308, 0.0131, racket.head)
    assert racket.roll_inertia_kgm2 == pytest.approx(derived, rel=1e-12)
    assert 10.0 < racket.twistweight_kgcm2 < 20.0  # the range of strung rackets on sale


def test_head_area_is_the_papers(racket: rd.Racket) -> None:
    assert racket.head.area_m2 * 1e4 == pytest.approx(628.0, rel=1e-12)


def test_free_reduced_mass_closed_form(racket: rd.Racket) -> None:
    # 1/M_r = 1/M + b²/I_G + y²/I_roll for a symmetric racket.
    x, y = 0.55, 0.04
    expected = 1.0 / (1 / 0.360 + (x - 0.308) ** 2 / 0.0131 + y**2 / racket.roll_inertia_kgm2)
    assert racket.reduced_mass([x, y], "free")[0] == pytest.approx(expected, rel=1e-12)
    assert racket.reduced_mass([0.308, 0.0], "free")[0] == pytest.approx(0.360, rel=1e-12)


def test_pinned_reduced_mass_is_eq4(racket: rd.Racket) -> None:
    # Paper eq (4): M_r = I_A / L_A² on the long axis; the roll term adds y²/I_roll off it.
    i_a = racket.inertia_about_axis(0.070)
    x = 0.60
    assert racket.reduced_mass([x, 0.0], "pinned")[0] == pytest.approx(
        i_a / (x - 0.070) ** 2, rel=1e-12
    )
    y = 0.05
    expected = 1.0 / ((x - 0.070) ** 2 / i_a + y**2 / racket.roll_inertia_kgm2)
    assert racket.reduced_mass([x, y], "pinned")[0] == pytest.approx(expected, rel=1e-12)


def test_free_equals_pinned_at_centre_of_percussion(racket: rd.Racket) -> None:
    cop = racket.centre_of_percussion_m()
    free = racket.reduced_mass([cop, 0.0], "free")[0]
    pinned = racket.reduced_mass([cop, 0.0], "pinned")[0]
    assert free == pytest.approx(pinned, rel=1e-12)
    # and only there: beyond the COP the pinned racket is heavier (paper, section 4.2)
    tip = racket.head.tip_x_m - 0.01
    assert racket.reduced_mass([tip, 0.0], "pinned")[0] > racket.reduced_mass([tip, 0.0], "free")[0]


def test_reduced_mass_symmetric_across_the_axis(racket: rd.Racket) -> None:
    for support in ("free", "pinned"):
        left, right = racket.reduced_mass([[0.5, 0.06], [0.5, -0.06]], support)
        assert left == pytest.approx(right, rel=1e-14)


def _cloud_properties(m: np.ndarray, xy: np.ndarray) -> MassProperties:
    total = m.sum()
    centre = m @ xy / total
    d = xy - centre
    inertia = np.array(
        [
            [m @ d[:, 1] ** 2, -(m @ (d[:, 0] * d[:, 1]))],
            [-(m @ (d[:, 0] * d[:, 1])), m @ d[:, 0] ** 2],
        ]
    )
    return MassProperties(float(total), (float(centre[0]), float(centre[1])), inertia)


def test_point_masses_fold_in_like_a_particle_cloud() -> None:
    # A racket made of particles, then lead tape added: with_point_masses must give what
    # recomputing the whole cloud from scratch gives (parallel axis + product of inertia).
    rng = np.random.default_rng(1)
    m = rng.uniform(0.001, 0.01, 50)
    xy = np.column_stack([rng.uniform(0, 0.68, 50), rng.uniform(-0.1, 0.1, 50)])
    lead = (PointMass(0.005, 0.66, 0.03), PointMass(0.003, 0.45, -0.11))
    folded = _cloud_properties(m, xy).with_point_masses(lead)
    direct = _cloud_properties(
        np.append(m, [p.mass_kg for p in lead]), np.vstack([xy, [[p.x_m, p.y_m] for p in lead]])
    )
    assert folded.mass_kg == pytest.approx(direct.mass_kg, rel=1e-14)
    np.testing.assert_allclose(folded.centre_m, direct.centre_m, rtol=1e-13)
    np.testing.assert_allclose(folded.inertia_kgm2, direct.inertia_kgm2, rtol=1e-12)


def test_reduced_mass_is_the_rigid_body_impulse_response() -> None:
    # An impulse J at a point changes that point's normal velocity by J / M_r: check against
    # the Newton–Euler equations solved directly for an asymmetric body.
    props = _cloud_properties(
        np.array([0.2, 0.1, 0.05]), np.array([[0.1, 0.0], [0.5, 0.08], [0.6, -0.1]])
    )
    point = np.array([0.55, 0.05])
    r = point - np.asarray(props.centre_m)
    angular_impulse = np.array([r[1], -r[0]])  # r × ẑ J with J = 1
    omega = np.linalg.solve(props.inertia_kgm2, angular_impulse)
    velocity = 1.0 / props.mass_kg + omega[0] * r[1] - omega[1] * r[0]
    assert props.reduced_mass(point)[0] == pytest.approx(1.0 / velocity, rel=1e-12)


def test_lead_at_the_tip_raises_tip_reduced_mass(racket: rd.Racket) -> None:
    tip = [racket.head.tip_x_m - 0.02, 0.0]
    leaded = racket.with_point_masses(PointMass(0.005, racket.length_m - 0.01, 0.0, "12 o'clock"))
    assert leaded.mass_properties.mass_kg == pytest.approx(0.365)
    assert leaded.reduced_mass(tip, "free")[0] > racket.reduced_mass(tip, "free")[0]
    assert leaded.swingweight_kgcm2 > racket.swingweight_kgcm2


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("mass_kg", 0.0, "racket.mass_kg"),
        ("mass_kg", -0.36, "racket.mass_kg"),
        ("balance_m", 0.70, "racket.balance_m"),
        ("inertia_cg_kgm2", float("nan"), "racket.inertia_cg_kgm2"),
    ],
)
def test_bad_racket_values_are_named(
    racket: rd.Racket, field: str, value: float, message: str
) -> None:
    from dataclasses import replace

    with pytest.raises(InputError, match=message):
        replace(racket, **{field: value})


def test_point_outside_string_bed_is_named(racket: rd.Racket) -> None:
    with pytest.raises(InputError, match="outside the string bed"):
        racket.head.check_inside([[0.5, 0.0], [0.2, 0.0]])


def test_unknown_support_is_named(racket: rd.Racket) -> None:
    with pytest.raises(InputError, match="support must be one of free, pinned"):
        racket.reduced_mass([0.5, 0.0], "clamped")
