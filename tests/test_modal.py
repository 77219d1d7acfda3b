"""The built-in modal model against beam theory, and the ModalModel object."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.errors import InputError
from racketdyn.racket_modal.beam import N_ELEMENTS, beam_mass_per_length, mass_along


def test_targets_are_met(model: rd.ModalModel, racket: rd.Racket) -> None:
    # exact: the calibration solves the same eigenproblem
    names = dict(zip(model.names, model.frequency, strict=True))
    assert names["2-node bending"] == pytest.approx(racket.first_bending_hz, rel=1e-12)
    assert names["2-node twisting"] == pytest.approx(racket.twisting_hz, rel=1e-12)
    # the paper's order (section 2): 2-node, 3-node bending, twisting, string membrane
    assert model.names == (
        "2-node bending",
        "3-node bending",
        "2-node twisting",
        "string-bed membrane",
    )
    # Cross (docs/references.md): string-bed modes lie at 500–600 Hz with the frame taking
    # part; the uncoupled membrane of 4 % of the mass must sit above that.
    assert 500 < model.frequency[-1] < 1000


def test_rigid_body_properties_of_the_mass_distribution(racket: rd.Racket) -> None:
    density = beam_mass_per_length(
        racket.length_m, racket.mass_kg, racket.balance_m, racket.inertia_cg_kgm2
    )
    x = np.linspace(0, racket.length_m, N_ELEMENTS + 1)
    lo, hi = x[:-1], x[1:]
    assert density @ (hi - lo) == pytest.approx(0.360, rel=1e-12)
    assert density @ (hi**2 - lo**2) / 2 / 0.360 == pytest.approx(0.308, rel=1e-12)
    inertia_butt = density @ (hi**3 - lo**3) / 3
    assert inertia_butt - 0.360 * 0.308**2 == pytest.approx(0.0131, rel=1e-12)
    assert np.all(density > 0)


def test_flexible_modes_carry_no_momentum(model: rd.ModalModel, racket: rd.Racket) -> None:
    # Free–free flexible modes are orthogonal to the rigid-body modes (no linear or angular
    # momentum) and mass-normalised: ∫ m φ dx = ∫ m x φ dx = 0, ∫ m φ² dx = 1.  Integrated
    # here with the midpoint rule on the 68 elements: O(h²) ≈ 1e-3 relative error allowed.
    # The density is the model's own (the frame's shape, strings included: issue 22).
    targets = (racket.mass_kg, racket.balance_m, racket.inertia_cg_kgm2)
    density, _ = mass_along(racket.length_m, racket.head, targets, 0.04 * racket.mass_kg)
    x = np.linspace(0, racket.length_m, N_ELEMENTS + 1)
    mid, h = 0.5 * (x[:-1] + x[1:]), np.diff(x)
    shapes = model.select([0, 1]).mode_shapes_at(np.column_stack([mid, np.zeros_like(mid)]))
    weight = density * h
    scale = weight @ np.abs(shapes)
    np.testing.assert_allclose(weight @ shapes, 0.0, atol=2e-3 * scale.max())
    np.testing.assert_allclose(
        (weight * (mid - racket.balance_m)) @ shapes, 0.0, atol=2e-3 * scale.max() * racket.length_m
    )
    np.testing.assert_allclose(weight @ shapes**2, 1.0, rtol=2e-3)


def test_uniform_beam_limit() -> None:
    # A uniform free–free beam: f₂/f₁ = (7.8532/4.7300)² = 2.7565 and φ(end)² M = 4
    # (Euler–Bernoulli; 68 cubic elements converge to 1e-5, 1e-3 is allowed).
    length, mass = 0.68, 0.36
    head = rd.HeadEllipse(0.50, 0.15, 0.11)
    uniform = rd.Racket("uniform", mass, length, length / 2, mass * length**2 / 12, 1.5e-3, head)
    modes = rd.builtin_modal_model(uniform)
    bending = [k for k, n in enumerate(modes.names) if "bending" in n]
    f1, f2 = modes.frequency[bending]
    assert f2 / f1 == pytest.approx((7.853205 / 4.730041) ** 2, rel=1e-4)
    end = modes.select(bending[0]).mode_shapes_at([[0.0, 0.0], [length, 0.0]])[:, 0]
    np.testing.assert_allclose(end**2 * mass, 4.0, rtol=1e-4)
    # between the samples too: the analytic free–free shape, mass-normalised (∫ m φ² dx = 1
    # gives φ(end)² M = 4), against the interpolated one at 101 off-node points; the thin-plate
    # spline between 1 cm samples is good to 1e-3 of the peak.
    beta = 4.730041 / length
    sigma = (np.cosh(4.730041) - np.cos(4.730041)) / (np.sinh(4.730041) - np.sin(4.730041))
    x = np.linspace(0.0033, length - 0.0033, 101)

    def analytic(z: np.ndarray) -> np.ndarray:
        bz = beta * z
        return np.cosh(bz) + np.cos(bz) - sigma * (np.sinh(bz) + np.sin(bz))

    exact = analytic(x) * 2.0 / np.sqrt(mass) / abs(analytic(np.array([length]))[0])
    shape = modes.select(bending[0]).mode_shapes_at(np.column_stack([x, np.zeros_like(x)]))[:, 0]
    shape *= np.sign(shape[0]) * np.sign(exact[0])
    np.testing.assert_allclose(shape, exact, atol=1e-3 * np.abs(exact).max())


def test_lead_shifts_the_modes(racket: rd.Racket, model: rd.ModalModel) -> None:
    # Frequencies are targets for the racket as described; lead added to it must lower them
    # (Rayleigh: more mass, same stiffness).  5 g at the tip, off the axis so it twists too.
    leaded = rd.builtin_modal_model(racket.with_point_masses(rd.PointMass(0.005, 0.67, 0.03)))
    for k in range(3):  # bending 2-node, 3-node, twisting
        assert leaded.frequency[k] < model.frequency[k]
    # the 2-node mode's tip motion: the rough Rayleigh estimate f²/f₀² = 1/(1 + m φ_tip²)
    phi_tip = model.mode_shapes_at([[0.67, 0.0]])[0, 0]
    expected = model.frequency[0] / np.sqrt(1 + 0.005 * phi_tip**2)
    assert leaded.frequency[0] == pytest.approx(expected, rel=5e-3)


def test_membrane_vanishes_on_the_frame(model: rd.ModalModel, racket: rd.Racket) -> None:
    # The string-bed shape is zero on the frame; interpolation must not bulge past the bed's
    # edge or extrapolate onto the frame (allowed: 3 % of its peak).
    head = racket.head
    angle = np.linspace(0, 2 * np.pi, 37)
    outside = np.column_stack(
        [
            head.centre_x_m + 1.04 * head.half_length_m * np.cos(angle),
            head.centre_y_m + 1.04 * head.half_width_m * np.sin(angle),
        ]
    )
    membrane = model.select(model.kinds.index("string-bed"))
    peak = membrane.mode_shapes_at([[head.centre_x_m, head.centre_y_m]])[0, 0]
    assert np.abs(membrane.mode_shapes_at(outside)).max() < 0.03 * peak


def test_shapes_sampled_on_the_axis_only(model: rd.ModalModel) -> None:
    # an identified model may have points on the long axis only: interpolate along x
    on_axis = np.abs(model.locations[:, 1]) < 1e-12
    axis = rd.ModalModel(
        model.frequency,
        model.damping_ratio,
        model.locations[on_axis],
        model.mode_shapes[on_axis],
        model.names,
    )
    x = np.array([[0.3015, 0.0], [0.5555, 0.05]])
    np.testing.assert_allclose(
        axis.mode_shapes_at(x)[:, 0], model.mode_shapes_at(x[:, :1] * [1, 0])[:, 0], rtol=1e-3
    )


def test_interpolation_is_exact_at_samples(model: rd.ModalModel) -> None:
    np.testing.assert_allclose(model.mode_shapes_at(model.locations), model.mode_shapes, atol=1e-9)


def test_json_round_trip(model: rd.ModalModel, tmp_path: Path) -> None:
    path = tmp_path / "modes.json"
    model.write_json(path)
    again = rd.ModalModel.read_json(path)
    np.testing.assert_array_equal(again.frequency, model.frequency)
    np.testing.assert_array_equal(again.mode_shapes, model.mode_shapes)
    np.testing.assert_array_equal(again.locations, model.locations)
    assert again.names == model.names
    assert again.support == model.support


def test_racket_file_can_name_a_modal_model(model: rd.ModalModel, tmp_path: Path) -> None:
    stiffer = replace(model, frequency=model.frequency * 1.5, metadata={})
    stiffer.write_json(tmp_path / "stiff.json")
    text = (Path(rd.__file__).parent / "data" / "kawazoe_2002.toml").read_text()
    text = text.replace("[modal]\n", '[modal]\nfile = "stiff.json"\n')
    (tmp_path / "racket.toml").write_text(text)
    racket = rd.load_racket(tmp_path / "racket.toml")
    np.testing.assert_allclose(rd.modal_model_for(racket).frequency, model.frequency * 1.5)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"frequency": np.array([-1.0, 2.0, 3.0, 4.0])}, "frequencies must be positive"),
        ({"damping_ratio": np.array([0.1, 0.1, 0.1, 1.5])}, "damping ratios"),
        ({"mode_shapes": np.zeros((3, 4))}, "shaped"),
        ({"kinds": ("bending",)}, "one kind per mode"),
    ],
)
def test_bad_modal_model(model: rd.ModalModel, change: dict, message: str) -> None:
    with pytest.raises(InputError, match=message):
        replace(model, **change)


def test_repeated_location_is_rejected(model: rd.ModalModel) -> None:
    locations = model.locations.copy()
    locations[1] = locations[0]
    with pytest.raises(InputError, match=r"point 1 and point 2 at \(.*\) m"):
        replace(model, locations=locations)


def test_bad_modal_file(tmp_path: Path) -> None:
    (tmp_path / "bad.json").write_text("{not json")
    with pytest.raises(InputError, match=r"bad\.json"):
        rd.ModalModel.read_json(tmp_path / "bad.json")
    (tmp_path / "other.json").write_text('{"format": "something else"}')
    with pytest.raises(InputError, match="not a racketdyn modal model"):
        rd.ModalModel.read_json(tmp_path / "other.json")


def test_mode_shapes_as_uff55(model: rd.ModalModel, tmp_path: Path) -> None:
    # Other modal software reads data set 55: frequency, damping, shapes at numbered nodes,
    # with the node coordinates in data set 15 (to the file's 6 significant digits).
    import pyuff

    from racketdyn.io import write_modes_uff

    path = write_modes_uff(model, tmp_path / "modes.uff")
    sets = pyuff.UFF(str(path)).read_sets()
    assert [s["type"] for s in sets] == [15] + [55] * model.n_modes
    np.testing.assert_allclose(sets[0]["x"], model.locations[:, 0], rtol=1e-5, atol=1e-9)
    for k, record in enumerate(sets[1:]):
        assert record["freq"] == pytest.approx(model.frequency[k], rel=1e-5)
        assert record["modal_damp_vis"] == pytest.approx(model.damping_ratio[k], rel=1e-5)
        np.testing.assert_allclose(record["r3"], model.mode_shapes[:, k], rtol=1e-5, atol=1e-9)


@pytest.mark.parametrize("threads", [1, 2])
def test_builtin_model_whatever_the_blas_threads(racket: rd.Racket, threads: int) -> None:
    # The beam's eigenproblems are solved on one BLAS thread: the model is the same to the
    # last digit whatever threads the caller's BLAS has (a sweep's tasks run on one each, a
    # single run on all the machine's cores; OpenBLAS's answer depends on their number).
    from threadpoolctl import threadpool_limits  # type: ignore[import-untyped]

    reference = rd.builtin_modal_model(racket)
    with threadpool_limits(limits=threads, user_api="blas"):
        model = rd.builtin_modal_model(racket)
    np.testing.assert_array_equal(model.frequency, reference.frequency)
    np.testing.assert_array_equal(model.mode_shapes, reference.mode_shapes)
