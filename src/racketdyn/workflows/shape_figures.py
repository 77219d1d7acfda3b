"""What the identified modes' figures draw, evaluated by the step (issue 23).

The paper's Figs 4 (mode shapes in 3-D), 5 (node lines), 6 (the first mode's nodes along the
long axis) and the AutoMAC show the modal model *evaluated*: its shapes interpolated over the
string face, along the long axis or over the measured points' hull, the nodes found on the axis,
the MAC of the shapes.  ``identify`` and ``compare`` evaluate them here, with the run's model
and racket, into frozen objects that convert to xarray (:meth:`to_xarray`) and back
(:meth:`from_xarray`) and are written to the step's ``figures.nc``; the figures
(:mod:`racketdyn.plotting.figures`) only draw them, and redraw them from the folder alone.

=============================  =================================================================
object                         figures
=============================  =================================================================
:class:`ModeShapes`            Fig. 4 (shapes in 3-D) and Fig. 5 (node lines), one panel a mode
:class:`AutoMac`               the AutoMAC of the identified shapes
:class:`AxisNodes`             Fig. 6: the first mode along the long axis, one line per model
:class:`IdentifiedShapes`      the three of one identification (``figures.nc`` of identify,
                               once per model in compare's)
=============================  =================================================================
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import NDArray

from racketdyn.modal.model import ModalModel
from racketdyn.modal.residues import mac
from racketdyn.numerics import spans_a_surface
from racketdyn.racket import HeadEllipse, Racket
from racketdyn.racket_modal.shapes import axis_nodes
from racketdyn.workflows._figure_io import _array, _has, _join, _part, _strings

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes

__all__ = [
    "AXIS_SAMPLES",
    "GRID_3D",
    "GRID_NODE_LINES",
    "AutoMac",
    "AxisNodes",
    "IdentifiedShapes",
    "Layout",
    "ModeShapes",
    "Panel",
    "axis_node_curves",
    "identified_shapes",
    "is_racket_model",
    "mode_shapes",
]

GRID_3D = 31
"""Grid nodes along each side of Fig. 4's surfaces (over the face or the points' hull)."""
GRID_NODE_LINES = 41
"""Grid nodes along each side of Fig. 5's maps."""
LINE_3D = 101
"""Points of Fig. 4's line (the racket's long axis, or through points on one line)."""
LINE_NODE_LINES = 341
"""Points of Fig. 5's line through points on one line (a beam)."""
AXIS_SAMPLES = 341
"""Points of Fig. 6's curves along the long axis."""

Layout = Literal["racket", "surface", "line", "space"]
"""How a figure shows the shapes: over a racket's face and long axis; over the convex hull of
points in a plane; along points on one straight line (a beam); at points in space."""

Panel = Literal["node_lines", "3d"]
"""Which figure's panel :meth:`ModeShapes.plot` draws: Fig. 5's node lines or Fig. 4's shape."""
_HEAD = ("centre_x_m", "half_length_m", "half_width_m", "centre_y_m")


def is_racket_model(model: ModalModel) -> bool:
    """Whether the modes are a racket's (named from their shapes, over the face)."""
    return any(kind != "unknown" for kind in model.kinds) and model.n_dimensions == 2


def _face_grid(racket: Racket, n: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    head = racket.head
    u = np.linspace(-1.0, 1.0, n)
    xi, eta = np.meshgrid(u, u, indexing="ij")
    return head.centre_x_m + head.half_length_m * xi, head.centre_y_m + head.half_width_m * eta


def _grid_over(
    locations: NDArray[np.float64], n: int
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """An n × n grid over the points' bounding box, and which nodes lie in their convex hull."""
    from scipy.spatial import Delaunay

    low, high = locations.min(axis=0), locations.max(axis=0)
    x, y = np.meshgrid(
        np.linspace(low[0], high[0], n), np.linspace(low[1], high[1], n), indexing="ij"
    )
    hull = Delaunay(locations)
    inside = hull.find_simplex(np.column_stack([x.ravel(), y.ravel()]), tol=1e-9) >= 0
    return x, y, inside.reshape(x.shape)


def _line_through(locations: NDArray[np.float64], n: int) -> NDArray[np.float64]:
    """n points from one end of collinear points to the other, m."""
    centred = locations - locations.mean(axis=0)
    direction = np.linalg.svd(centred, full_matrices=False)[2][0]
    along = centred @ direction
    t = np.linspace(along.min(), along.max(), n)
    return np.asarray(locations.mean(axis=0) + t[:, None] * direction[None, :])


def _on_grid(
    model: ModalModel,
    x: NDArray[np.float64],
    y: NDArray[np.float64],
    inside: NDArray[np.bool_],
) -> NDArray[np.float64]:
    """Every mode's shape on a grid, ``(n_modes, *x.shape)``, NaN outside."""
    shapes = model.mode_shapes_at(np.column_stack([x.ravel(), y.ravel()]))
    on_grid = shapes.T.reshape((model.n_modes, *x.shape))
    return np.where(inside[None], on_grid, np.nan)


@dataclass(frozen=True)
class ModeShapes:
    """The paper's Figs 4 and 5 of one modal model: its shapes evaluated where they are drawn.

    Attributes
    ----------
    names : tuple of str
        Each mode's name.
    frequency : ndarray (n_modes,)
        Natural frequencies, Hz.
    damping_ratio : ndarray (n_modes,)
        Damping ratios, dimensionless.
    support : str
        Support of the test.
    mass_normalised : bool
        Whether the shapes are mass-normalised (1/√kg).
    layout_3d, layout_nodes : Layout
        How Fig. 4 and Fig. 5 show the shapes (:data:`Layout`).
    locations : ndarray (n_points, n_dimensions)
        The measured points, m.
    at_points : ndarray (n_points, n_modes)
        The shapes at the measured points.
    surface_x, surface_y : ndarray (n, n)
        Fig. 4's grid (layouts ``racket`` and ``surface``), m; empty otherwise.
    surface : ndarray (n_modes, n, n)
        The shapes on it, NaN off the face (outside the points' hull).
    line : ndarray (n_line, 2 or 3)
        Fig. 4's line (the long axis; through points on one line), m; empty otherwise.
    line_shapes : ndarray (n_modes, n_line)
        The shapes along it.
    nodes_x, nodes_y : ndarray (n, n)
        Fig. 5's grid (layouts ``racket`` and ``surface``), m; empty otherwise.
    nodes_surface : ndarray (n_modes, n, n)
        The shapes on it, NaN outside.
    nodes_along : ndarray (n_line,)
        Fig. 5's distance along the line through points on one line (layout ``line``), m.
    nodes_line_shapes : ndarray (n_modes, n_line)
        The shapes along that line.
    plane : ndarray (n_points, 2)
        The points in their best-fit plane (layout ``space``), m; empty otherwise.
    head : HeadEllipse or None
        The racket's string bed (layout ``racket``).
    length_m : float
        The racket's length (layout ``racket``), m; NaN otherwise.
    """

    names: tuple[str, ...]
    frequency: NDArray[np.float64]
    damping_ratio: NDArray[np.float64]
    support: str
    mass_normalised: bool
    layout_3d: Layout
    layout_nodes: Layout
    locations: NDArray[np.float64]
    at_points: NDArray[np.float64]
    surface_x: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    surface_y: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    surface: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0, 0)))
    line: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    line_shapes: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    nodes_x: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    nodes_y: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    nodes_surface: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0, 0)))
    nodes_along: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    nodes_line_shapes: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    plane: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    head: HeadEllipse | None = None
    length_m: float = float("nan")

    @property
    def n_modes(self) -> int:
        """Number of modes."""
        return len(self.names)

    def title(self, mode: int, decimals: int = 0) -> str:
        """A mode's name, with its frequency unless the name holds it ("mode 1, 100 Hz")."""
        name = self.names[mode]
        return name if name.endswith(" Hz)") else f"{name}, {self.frequency[mode]:.{decimals}f} Hz"

    def plot(self, mode: int = 0, ax: Axes | None = None, *, kind: Panel = "node_lines") -> Axes:
        """Draw one mode: its node lines (Fig. 5, ``kind="node_lines"``) or its shape in 3-D
        (Fig. 4, ``kind="3d"``, ``ax`` a 3-D axes); matplotlib is imported now.

        Parameters
        ----------
        mode : int
            Index of the mode (0-based).
        ax : matplotlib Axes, optional
            Where to draw; a new figure if None.
        kind : {"node_lines", "3d"}
            Which figure's panel.

        Returns
        -------
        Axes
        """
        from racketdyn.plotting.primitives import plot_mode_3d, plot_node_lines

        if kind == "3d":
            return plot_mode_3d(self, mode, ax)
        return plot_node_lines(self, mode, ax)

    def to_xarray(self, key: str = "fig4_5") -> xr.Dataset:
        """One dataset, names prefixed ``<key>__``: the grids, lines and shapes in SI units (those
        of the layouts only: netCDF 3 takes a dimension of length 0 for its unlimited one)."""
        import xarray as xr

        variables = {
            name: (dims, getattr(self, name), {"units": units})
            for name, (dims, units) in _SHAPE_VARIABLES.items()
            if getattr(self, name).size
        }
        variables["at_points"] = (("point", "mode"), self.at_points, {"units": _units(self)})
        variables["locations"] = (("point", "dimension"), self.locations, {"units": "m"})
        head = {} if self.head is None else {f"head_{k}": getattr(self.head, k) for k in _HEAD}
        data = xr.Dataset(
            variables,
            coords={
                "mode_name": ("mode", list(self.names)),
                "frequency_hz": ("mode", self.frequency, {"units": "Hz"}),
                "damping_ratio": ("mode", self.damping_ratio, {"units": "1"}),
            },
            attrs={
                "support": self.support,
                "mass_normalised": int(self.mass_normalised),
                "layout_3d": self.layout_3d,
                "layout_nodes": self.layout_nodes,
                "length_m": self.length_m,
                **{name: float(value) for name, value in head.items()},
            },
        )
        return _join({key: data})

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset, key: str = "fig4_5") -> ModeShapes:
        """Back from :meth:`to_xarray`'s dataset (or a ``figures.nc`` holding it)."""
        data = _part(dataset, key)
        attrs = data.attrs
        head = (
            HeadEllipse(**{k: float(attrs[f"head_{k}"]) for k in _HEAD})
            if "head_centre_x_m" in attrs
            else None
        )
        arrays = {name: _array(data[name].values) for name in _SHAPE_VARIABLES if name in data}
        return cls(
            names=_strings(data["mode_name"].values),
            frequency=_array(data["frequency_hz"].values),
            damping_ratio=_array(data["damping_ratio"].values),
            support=str(attrs["support"]),
            mass_normalised=bool(attrs["mass_normalised"]),
            layout_3d=attrs["layout_3d"],
            layout_nodes=attrs["layout_nodes"],
            locations=_array(data["locations"].values),
            at_points=_array(data["at_points"].values),
            head=head,
            length_m=float(attrs["length_m"]),
            **arrays,
        )


_SHAPE_VARIABLES: dict[str, tuple[tuple[str, ...], str]] = {
    "surface_x": (("sx", "sy"), "m"),
    "surface_y": (("sx", "sy"), "m"),
    "surface": (("mode", "sx", "sy"), "1"),
    "line": (("line", "line_dimension"), "m"),
    "line_shapes": (("mode", "line"), "1"),
    "nodes_x": (("nx", "ny"), "m"),
    "nodes_y": (("nx", "ny"), "m"),
    "nodes_surface": (("mode", "nx", "ny"), "1"),
    "nodes_along": (("along",), "m"),
    "nodes_line_shapes": (("mode", "along"), "1"),
    "plane": (("point", "plane_dimension"), "m"),
}
""":class:`ModeShapes`' arrays of a layout: dimensions and units (a shape's ``1``: as
``at_points``'s, which says whether mass-normalised)."""


def _units(shapes: ModeShapes) -> str:
    return "1/sqrt(kg)" if shapes.mass_normalised else "1"


def mode_shapes(model: ModalModel, racket: Racket | None) -> ModeShapes:
    """Evaluate a modal model where Figs 4 and 5 draw it.

    Over a racket's face (and along its long axis, Fig. 4) when ``racket`` is given; else over
    the convex hull of the model's points, along the line through points on one line (a beam),
    or at points in space ``(x, y, z)`` (coloured by shape, Fig. 4; over their best-fit plane,
    Fig. 5).

    Parameters
    ----------
    model : ModalModel
        The modes, with their points' coordinates.
    racket : Racket or None
        The racket whose face the shapes are drawn over; None for any other structure.

    Returns
    -------
    ModeShapes
    """
    locations = np.asarray(model.locations, dtype=float)
    common: dict[str, Any] = {
        "names": tuple(model.names),
        "frequency": np.asarray(model.frequency, dtype=float),
        "damping_ratio": np.asarray(model.damping_ratio, dtype=float),
        "support": model.support,
        "mass_normalised": model.mass_normalised,
        "locations": locations,
        "at_points": np.asarray(model.mode_shapes, dtype=float),
    }
    if racket is not None:
        x, y = _face_grid(racket, GRID_3D)
        inside = racket.head.contains(np.column_stack([x.ravel(), y.ravel()])).reshape(x.shape)
        axis_x = np.linspace(0.0, racket.length_m, LINE_3D)
        axis = np.column_stack([axis_x, np.zeros_like(axis_x)])
        nx, ny = _face_grid(racket, GRID_NODE_LINES)
        inside_nodes = racket.head.contains(np.column_stack([nx.ravel(), ny.ravel()]))
        return ModeShapes(
            **common,
            layout_3d="racket",
            layout_nodes="racket",
            surface_x=x,
            surface_y=y,
            surface=_on_grid(model, x, y, inside),
            line=axis,
            line_shapes=model.mode_shapes_at(axis).T,
            nodes_x=nx,
            nodes_y=ny,
            nodes_surface=_on_grid(model, nx, ny, inside_nodes.reshape(nx.shape)),
            head=racket.head,
            length_m=float(racket.length_m),
        )
    fields: dict[str, Any] = {}
    surface = spans_a_surface(locations)
    # Fig. 4: points in space where they are; a surface over the hull; a line through a beam
    if model.n_dimensions == 3:
        layout_3d: Layout = "space"
    elif surface:
        layout_3d = "surface"
        x, y, hull = _grid_over(locations, GRID_3D)
        fields |= {"surface_x": x, "surface_y": y, "surface": _on_grid(model, x, y, hull)}
    else:
        layout_3d = "line"
        line = _line_through(locations, LINE_3D)
        fields |= {"line": line, "line_shapes": model.mode_shapes_at(line).T}
    # Fig. 5: a beam's shape along it; points in space over their plane; else node lines
    if not surface:
        layout_nodes: Layout = "line"
        line = _line_through(locations, LINE_NODE_LINES)
        fields |= {
            "nodes_along": np.linalg.norm(line - line[0], axis=1),
            "nodes_line_shapes": model.mode_shapes_at(line).T,
        }
    elif model.n_dimensions == 3:
        layout_nodes = "space"
        centred = locations - locations.mean(axis=0)
        fields["plane"] = centred @ np.linalg.svd(centred, full_matrices=False)[2][:2].T
    else:
        layout_nodes = "surface"
        nx, ny, hull = _grid_over(locations, GRID_NODE_LINES)
        fields |= {"nodes_x": nx, "nodes_y": ny, "nodes_surface": _on_grid(model, nx, ny, hull)}
    return ModeShapes(**common, layout_3d=layout_3d, layout_nodes=layout_nodes, **fields)


@dataclass(frozen=True)
class AutoMac:
    """The AutoMAC of a model's shapes: how alike two modes look at the measured points.

    Attributes
    ----------
    names : tuple of str
        Each mode's name.
    matrix : ndarray (n_modes, n_modes)
        The MAC of each pair, dimensionless (1 on the diagonal).
    """

    names: tuple[str, ...]
    matrix: NDArray[np.float64]

    @classmethod
    def of(cls, model: ModalModel) -> AutoMac:
        """The AutoMAC of ``model``'s shapes (:func:`racketdyn.modal.residues.mac`)."""
        return cls(tuple(model.names), mac(model.mode_shapes, model.mode_shapes))

    def plot(self, ax: Axes | None = None) -> Axes:
        """Draw the matrix with its values (into ``ax``, or a new figure); returns the axes."""
        from racketdyn.plotting.figures import plot_automac

        return plot_automac(self, ax)

    def to_xarray(self, key: str = "automac") -> xr.Dataset:
        """One dataset, names prefixed ``<key>__``: ``mac`` on (``mode``, ``other_mode``)."""
        import xarray as xr

        data = xr.Dataset(
            {"mac": (("mode", "other_mode"), self.matrix, {"units": "1"})},
            coords={"mode_name": ("mode", list(self.names))},
        )
        return _join({key: data})

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset, key: str = "automac") -> AutoMac:
        """Back from :meth:`to_xarray`'s dataset (or a ``figures.nc`` holding it)."""
        data = _part(dataset, key)
        return cls(_strings(data["mode_name"].values), _array(data["mac"].values))


@dataclass(frozen=True)
class AxisNodes:
    """Paper Fig. 6: the first mode along the long axis with its nodes, one line per model.

    Attributes
    ----------
    x : ndarray (n_samples,)
        Points along the long axis, m from the butt.
    shapes : ndarray (n_models, n_samples)
        Each model's first mode there, its sign such that it starts positive.
    nodes : ndarray (n_models, n_nodes)
        Each model's nodes on the axis, m from the butt (NaN-padded).
    supports, names : tuple of str
        Each model's support and first mode's name.
    frequency : ndarray (n_models,)
        Each model's first natural frequency, Hz.
    grip_m : float
        The racket's grip length, m (the hand covers twice it).
    """

    x: NDArray[np.float64]
    shapes: NDArray[np.float64]
    nodes: NDArray[np.float64]
    supports: tuple[str, ...]
    names: tuple[str, ...]
    frequency: NDArray[np.float64]
    grip_m: float

    def nodes_of(self, k: int) -> NDArray[np.float64]:
        """Model ``k``'s nodes, m."""
        row = self.nodes[k]
        return np.asarray(row[np.isfinite(row)], dtype=float)

    def plot(self, ax: Axes | None = None) -> Axes:
        """Draw the curves with their nodes (into ``ax``, or a new figure); returns the axes."""
        from racketdyn.plotting.figures import plot_axis_nodes

        return plot_axis_nodes(self, ax)

    def to_xarray(self, key: str = "fig6") -> xr.Dataset:
        """One dataset, names prefixed ``<key>__``: ``shape`` on (``model``, ``x``), ``node_m``
        on (``model``, ``node``)."""
        import xarray as xr

        data = xr.Dataset(
            {
                "shape": (("model", "x"), self.shapes),
                "node_m": (("model", "node"), self.nodes, {"units": "m"}),
            },
            coords={
                "x_m": ("x", self.x, {"units": "m"}),
                "support_name": ("model", list(self.supports)),
                "mode_name": ("model", list(self.names)),
                "frequency_hz": ("model", self.frequency, {"units": "Hz"}),
            },
            attrs={"grip_m": self.grip_m},
        )
        return _join({key: data})

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset, key: str = "fig6") -> AxisNodes:
        """Back from :meth:`to_xarray`'s dataset (or a ``figures.nc`` holding it)."""
        data = _part(dataset, key)
        return cls(
            x=_array(data["x_m"].values),
            shapes=_array(data["shape"].values),
            nodes=_array(data["node_m"].values),
            supports=_strings(data["support_name"].values),
            names=_strings(data["mode_name"].values),
            frequency=_array(data["frequency_hz"].values),
            grip_m=float(data.attrs["grip_m"]),
        )


def axis_node_curves(models: Sequence[ModalModel], racket: Racket) -> AxisNodes:
    """Fig. 6 of one or more models: the first mode along the long axis and its nodes
    (:func:`racketdyn.racket_modal.shapes.axis_nodes`).

    Parameters
    ----------
    models : sequence of ModalModel
        A racket's modes (free, then hand-held: one line each).
    racket : Racket
        The racket (its length and grip).
    """
    x = np.linspace(0.0, racket.length_m, AXIS_SAMPLES)
    shapes, nodes = [], []
    for model in models:
        shape = model.mode_shapes_at(np.column_stack([x, np.zeros_like(x)]))[:, 0]
        shapes.append(shape * np.sign(shape[0]))
        nodes.append(axis_nodes(model, 0, (0.0, racket.length_m)))
    width = max((len(n) for n in nodes), default=0)
    padded = np.full((len(nodes), width), np.nan)
    for k, found in enumerate(nodes):
        padded[k, : len(found)] = found
    return AxisNodes(
        x=x,
        shapes=np.array(shapes),
        nodes=padded,
        supports=tuple(m.support for m in models),
        names=tuple(m.names[0] for m in models),
        frequency=np.array([m.frequency[0] for m in models], dtype=float),
        grip_m=float(racket.grip_m),
    )


@dataclass(frozen=True)
class IdentifiedShapes:
    """What an identification's figures of its shapes draw (Figs 4–6 and the AutoMAC).

    Attributes
    ----------
    automac : AutoMac
        The AutoMAC.
    shapes : ModeShapes or None
        Figs 4 and 5; None for shapes known at one point only, or at points without coordinates.
    axis : AxisNodes or None
        Fig. 6; None for a structure that is not a racket.
    """

    automac: AutoMac
    shapes: ModeShapes | None = None
    axis: AxisNodes | None = None

    def to_xarray(self, label: str = "") -> xr.Dataset:
        """The datasets of the three, names prefixed ``automac__``, ``fig4_5__``, ``fig6__``
        (with ``_<label>``: ``automac_free__``)."""
        import xarray as xr

        suffix = f"_{label}" if label else ""
        parts = [self.automac.to_xarray(f"automac{suffix}")]
        if self.shapes is not None:
            parts.append(self.shapes.to_xarray(f"fig4_5{suffix}"))
        if self.axis is not None:
            parts.append(self.axis.to_xarray(f"fig6{suffix}"))
        merged = xr.merge(parts, combine_attrs="override")
        merged.attrs = {}
        for part in parts:
            merged.attrs.update(part.attrs)
        return merged

    @classmethod
    def from_xarray(cls, dataset: xr.Dataset, label: str = "") -> IdentifiedShapes:
        """Back from :meth:`to_xarray`'s dataset (or a ``figures.nc`` holding it)."""
        suffix = f"_{label}" if label else ""
        return cls(
            automac=AutoMac.from_xarray(dataset, f"automac{suffix}"),
            shapes=(
                ModeShapes.from_xarray(dataset, f"fig4_5{suffix}")
                if _has(dataset, f"fig4_5{suffix}")
                else None
            ),
            axis=(
                AxisNodes.from_xarray(dataset, f"fig6{suffix}")
                if _has(dataset, f"fig6{suffix}")
                else None
            ),
        )

    @staticmethod
    def in_dataset(dataset: xr.Dataset, label: str = "") -> bool:
        """Whether ``dataset`` holds an identification's shapes (of ``label``)."""
        return _has(dataset, f"automac_{label}" if label else "automac")


def identified_shapes(model: ModalModel, racket: Racket) -> IdentifiedShapes:
    """Evaluate an identified model for its figures: Figs 4–5 over the racket for a racket's
    modes (over its own points for any other structure), Fig. 6 for a racket's, the AutoMAC.

    Parameters
    ----------
    model : ModalModel
        The identified modes.
    racket : Racket
        The racket of the run.
    """
    racket_modes = is_racket_model(model)
    drawable = model.locations.shape[0] >= 2 and model.has_locations
    return IdentifiedShapes(
        automac=AutoMac.of(model),
        shapes=mode_shapes(model, racket if racket_modes else None) if drawable else None,
        axis=axis_node_curves([model], racket) if racket_modes else None,
    )
