"""The modal package on a structure that is not a racket: a free–free uniform beam along y.

FRFs in closed form from the beam's modes (Euler–Bernoulli, free–free: β_n L = 4.7300, 7.8532,
10.9956, 14.1372, 17.2788; Blevins, *Formulas for Natural Frequency and Mode Shape*, 1979,
table 8-1), a little noise; the identification must give the modes back, named neutrally, and
the general figures must draw without a racket.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pytest
from numpy.typing import NDArray

from racketdyn.errors import InputError
from racketdyn.measurement.records import FrfSet
from racketdyn.modal import ModalModel, mac, nodes_along, pair_modes
from racketdyn.modal.identify import identify

BETA_L = np.array([4.73004074, 7.85320462, 10.99560784, 14.13716549, 17.27875966])
LENGTH_M = 1.0
MASS_PER_LENGTH = 2.0  # kg/m
FIRST_HZ = 100.0
FREQUENCY = FIRST_HZ * (BETA_L / BETA_L[0]) ** 2  # 100, 275.6, 540.4, 893.3, 1334.4 Hz
DAMPING = np.array([0.010, 0.006, 0.008, 0.005, 0.007])
X_M = 0.2  # the beam lies along y, at x = 0.2 m
N_POINTS = 21
FIRST_NODES = np.array([0.2242, 0.7758]) * LENGTH_M  # Blevins, table 8-1
RACKET_WORDS = ("bending", "twisting", "string", "membrane")


def beam_shapes(y: NDArray[np.float64]) -> NDArray[np.float64]:
    """Mass-normalised free–free shapes at y, (n, n_modes), 1/√kg (∫ m φ² dy = 1)."""
    b = BETA_L / LENGTH_M
    sigma = (np.cosh(BETA_L) - np.cos(BETA_L)) / (np.sinh(BETA_L) - np.sin(BETA_L))
    by = np.outer(y, b)
    raw = np.cosh(by) + np.cos(by) - sigma * (np.sinh(by) + np.sin(by))
    return np.asarray(raw / np.sqrt(MASS_PER_LENGTH * LENGTH_M))  # ∫₀ᴸ raw² dy = L


def beam_frfs(locations: NDArray[np.float64], along: NDArray[np.float64]) -> FrfSet:
    """Accelerances of the beam (0.5 % noise), accelerometer at the first point (an end)."""
    phi = beam_shapes(along)
    frequency = np.arange(0.0, 1280.0 + 1e-9, 0.5)  # default band: 40 Hz to 1000 Hz
    omega, omega_k = 2 * np.pi * frequency, 2 * np.pi * FREQUENCY
    denominator = omega_k**2 - omega[:, None] ** 2 + 2j * DAMPING * omega_k * omega[:, None]
    values = -(omega**2) * ((phi * phi[0]) @ (1 / denominator).T)
    rng = np.random.default_rng(7)
    scale = 0.005 * np.abs(values).mean(axis=1, keepdims=True)
    values = values + scale * (rng.normal(size=values.shape) + 1j * rng.normal(size=values.shape))
    return FrfSet(
        frequency=frequency,
        values=values,
        frf_type="accelerance",
        nodes=tuple(range(1, len(along) + 1)),
        locations=locations,
        reference_node=1,
        reference_location=tuple(locations[0]),
        source="free-free beam (closed form)",
    )


@pytest.fixture(scope="module")
def beam() -> dict:
    y = np.linspace(0.0, LENGTH_M, N_POINTS)
    frfs = beam_frfs(np.column_stack([np.full_like(y, X_M), y]), y)
    return {"frfs": frfs, "phi": beam_shapes(y), "result": identify(frfs)}


def test_the_beam_modes_come_back(beam) -> None:
    # frequencies within 0.05 %, damping within 2 %, MAC ≥ 0.999, mass-normalised shapes within
    # 2 % (0.5 % noise on every line); the band 40–1000 Hz holds the first four modes
    model = beam["result"].model
    assert model.n_modes == 4
    np.testing.assert_allclose(model.frequency, FREQUENCY[:4], rtol=5e-4)
    np.testing.assert_allclose(model.damping_ratio, DAMPING[:4], rtol=0.02)
    phi = beam["phi"][:, :4]
    assert np.all(mac(model.mode_shapes, phi, pairwise=True) > 0.999)
    for k in range(4):
        sign = np.sign(model.mode_shapes[:, k] @ phi[:, k])
        error = np.linalg.norm(sign * model.mode_shapes[:, k] - phi[:, k])
        assert error / np.linalg.norm(phi[:, k]) < 0.02


def test_modes_are_named_neutrally(beam) -> None:
    model = beam["result"].model
    assert model.kinds == ("unknown",) * model.n_modes
    for k, name in enumerate(model.names):
        assert name == f"mode {k + 1} ({model.frequency[k]:.1f} Hz)"
        assert not any(word in name.lower() for word in RACKET_WORDS)
    assert model.frame_modes is model  # nothing is taken for a string bed


def test_shapes_interpolate_along_a_line_in_y(beam) -> None:
    # issue 12, item 5: points on a line along y crashed the interpolator (LinAlgError)
    model = beam["result"].model
    y = np.linspace(0.0, LENGTH_M, 201)
    line = np.column_stack([np.full_like(y, X_M), y])
    nodes = nodes_along(model, line, 0)
    np.testing.assert_allclose(nodes[:, 0], X_M)
    np.testing.assert_allclose(nodes[:, 1], FIRST_NODES, atol=0.005)
    off_line = model.mode_shapes_at([[X_M + 0.05, 0.5]])
    np.testing.assert_allclose(off_line, model.mode_shapes_at([[X_M, 0.5]]))


def test_a_slanted_line_interpolates_along_itself() -> None:
    t = np.linspace(0.0, 1.0, 11)
    direction = np.array([0.6, 0.8])
    model = ModalModel([10.0], [0.01], t[:, None] * direction, np.sin(np.pi * t)[:, None], ("a",))
    np.testing.assert_allclose(model.mode_shapes_at([0.3 * direction]), [[np.sin(0.3 * np.pi)]])


def test_pairing_a_model_with_itself(beam) -> None:
    model = beam["result"].model
    pairing = pair_modes(model, model)
    assert pairing.first == pairing.second == tuple(range(model.n_modes))
    np.testing.assert_allclose(pairing.mac, 1.0)


def test_general_figures_need_no_racket(beam) -> None:
    from racketdyn.plotting.primitives import plot_mac, plot_mode_3d, plot_node_lines
    from racketdyn.workflows.shape_figures import mode_shapes

    result = beam["result"]
    model = result.model
    shapes = mode_shapes(model, None)
    ax = plot_node_lines(shapes, 0)
    assert ax.get_title().startswith("mode 1 (")
    assert len(ax.lines[-1].get_xdata()) == 2  # the first mode's two nodes
    plt.close(ax.figure)
    ax = plot_mode_3d(shapes, 1)
    plt.close(ax.figure)
    ax = result.stabilisation.plot(result.selected, frfs=result.frfs)
    plt.close(ax.figure)
    ax = plot_mac(mac(model.mode_shapes, model.mode_shapes), model.names, model.names)
    plt.close(ax.figure)


@pytest.mark.slow
def test_general_figures_on_a_surface() -> None:
    # a simply supported 0.4 m × 0.3 m plate sampled on a grid: node lines over its points
    from racketdyn.plotting.primitives import plot_mode_3d, plot_node_lines
    from racketdyn.workflows.shape_figures import mode_shapes

    x, y = np.meshgrid(np.linspace(0, 0.4, 9), np.linspace(0, 0.3, 7), indexing="ij")
    points = np.column_stack([x.ravel(), y.ravel()])
    shapes = np.column_stack(
        [
            np.sin(np.pi * points[:, 0] / 0.4) * np.sin(np.pi * points[:, 1] / 0.3),
            np.sin(2 * np.pi * points[:, 0] / 0.4) * np.sin(np.pi * points[:, 1] / 0.3),
        ]
    )
    model = ModalModel([50.0, 120.0], [0.01, 0.01], points, shapes, ("mode 1", "mode 2"))
    ax = plot_node_lines(mode_shapes(model, None), 1)
    assert ax.get_title() == "mode 2, 120 Hz"
    plt.close(ax.figure)
    ax = plot_mode_3d(mode_shapes(model, None), 1)
    plt.close(ax.figure)


def test_a_beam_in_space_along_z() -> None:
    # (x, y, z) coordinates: the same beam along z, off the origin
    z = np.linspace(0.0, LENGTH_M, N_POINTS)
    locations = np.column_stack([np.full_like(z, 0.1), np.full_like(z, -0.3), z])
    result = identify(beam_frfs(locations, z))
    model = result.model
    assert model.n_dimensions == 3
    np.testing.assert_allclose(model.frequency, FREQUENCY[:4], rtol=5e-4)
    np.testing.assert_allclose(model.damping_ratio, DAMPING[:4], rtol=0.02)
    assert np.all(mac(model.mode_shapes, beam_shapes(z)[:, :4], pairwise=True) > 0.999)
    line = np.column_stack([np.full(201, 0.1), np.full(201, -0.3), np.linspace(0, LENGTH_M, 201)])
    nodes = nodes_along(model, line, 0)
    np.testing.assert_allclose(nodes[:, 2], FIRST_NODES, atol=0.005)
    with pytest.raises(InputError, match="3-D"):
        model.mode_shapes_at([[0.1, 0.5]])


def test_figures_of_points_in_space() -> None:
    # points on two faces of a box (not one plane): drawn where they are, coloured by shape
    from racketdyn.plotting.primitives import plot_mode_3d, plot_node_lines
    from racketdyn.workflows.shape_figures import mode_shapes

    u, v = np.meshgrid(np.linspace(0, 0.3, 5), np.linspace(0, 0.2, 4), indexing="ij")
    top = np.column_stack([u.ravel(), v.ravel(), np.zeros(u.size)])
    side = np.column_stack([u.ravel(), np.zeros(u.size), -0.05 - 0.1 * v.ravel() / 0.2])
    points = np.vstack([top, side])
    shapes = np.sin(np.pi * points[:, :1] / 0.3) * np.array([[1.0, -1.0]]) + points[:, 1:2]
    model = ModalModel([80.0, 200.0], [0.01, 0.02], points, shapes, ("mode 1", "mode 2"))
    assert model.mode_shapes_at(points[:3]).shape == (3, 2)
    ax = plot_mode_3d(mode_shapes(model, None), 0)
    assert ax.get_title().startswith("mode 1, 80.0 Hz")
    plt.close(ax.figure)
    ax = plot_node_lines(mode_shapes(model, None), 1)
    plt.close(ax.figure)
