"""Sweep summary: per-design metrics, the designs that show one variable, ``summary.csv``.

The end of the flow: reads a sweep dataset (``sweep.zarr`` through
:func:`~racketdyn.sweep.open_sweep`, or any in memory) and nothing else — the rebound ratio at
the face centre and the sweet area (:func:`sweet_area_cm2`, the one definition) per design and
support, ``summary.csv``, and a full factorial's dimensions.  The metrics read the results a
block of designs at a time (the store's chunks): a study larger than memory is summarised in
the memory of a few chunks.
Their curves against each variable (:func:`summary_curves`) are computed here; drawing them is
presentation: :mod:`racketdyn.plotting.sweep`.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.errors import InputError
from racketdyn.sweep.variables import POINT_MASS

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes

__all__ = [
    "SWEET_AREA_DEFINITION",
    "SummaryCurves",
    "axis_label",
    "factorial_view",
    "summary_curves",
    "summary_figures_data",
    "summary_metrics",
    "sweet_area_cm2",
    "sweet_area_resolution_cm2",
    "variable_designs",
    "write_summary_csv",
]


def _variables(dataset: xr.Dataset) -> dict[str, dict[str, Any]]:
    return {v["name"]: v for v in json.loads(str(dataset.attrs["sweep_variables"]))}


def variable_designs(dataset: xr.Dataset, variable: str) -> NDArray[np.int_]:
    """Design indices that show one variable's effect, in order of its axis coordinate.

    One at a time: the designs varying it and the base design.  Full factorial: the designs
    with every other variable at its reference value — its base value if swept, else the swept
    value nearest the base.

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset (:func:`run_sweep`).
    variable : str
        A variable name (``e_bg``, ``point_mass`` …).
    """
    variables = _variables(dataset)
    if variable not in variables:
        raise InputError(f"no variable {variable!r} in the sweep; it has {', '.join(variables)}")
    info = variables[variable]
    axis = dataset[info["axis"]].values
    if dataset.attrs["sweep_mode"] == "one-at-a-time":
        varied = dataset["varied"].values
        keep = np.flatnonzero((varied == variable) | (varied == "base"))
    else:
        mask = np.ones(dataset.sizes["design"], dtype=bool)
        for name, other in variables.items():
            if name == variable:
                continue
            values = np.asarray(other["values"], dtype=float)
            base = np.asarray(other["base"], dtype=float)
            k = other["coords"].index(other["axis"])
            reference = values[np.argmin(np.abs(values[:, k] - base[k]))]
            if other["kind"] == POINT_MASS and base[0] == 0.0 and np.any(values[:, 0] == 0.0):
                reference = values[np.flatnonzero(values[:, 0] == 0.0)[0]]
            for coord, value in zip(other["coords"], reference, strict=True):
                mask &= dataset[coord].values == value
        keep = np.flatnonzero(mask)
    return np.asarray(keep[np.argsort(axis[keep], kind="stable")])


SWEET_AREA_DEFINITION = (
    "the face area whose rebound ratio is within (1 − threshold_fraction) × |best| of the "
    "best point of the same face (design, support and speeds): e ≥ threshold_fraction × best "
    "for a face that rebounds forwards"
)
"""What ``sweet_area_cm2`` means, in ``summary.csv``'s attributes, the figures and the docs."""


def sweet_area_cm2(
    rebound_ratio: NDArray[np.floating[Any]] | Sequence[float],
    head_area_cm2: float,
    threshold_fraction: float,
) -> NDArray[np.float64] | float:
    """The "sweet area" of a face: where its rebound ratio is near its own best, cm².

    The one definition (:data:`SWEET_AREA_DEFINITION`) that ``summary.csv``, the summary
    figures and :func:`summary_metrics` use: the points whose rebound ratio ``e`` reaches
    ``best − (1 − threshold_fraction) · |best|``, ``best`` the highest ``e`` of the same face
    (``threshold_fraction × best`` when the face rebounds forwards), each point standing for an
    equal share of the string-bed area (exact for a grid, approximate for a points file).  The
    threshold is the face's own, so the area does not depend on which other designs are
    compared, and it holds at least the best point: it is never 0 for a face with a number.
    Points without a number (NaN: a frame shot, a failed impact) count as outside.

    Parameters
    ----------
    rebound_ratio : array_like
        Rebound ratios ``e`` (–) of the face's impact points along the last axis (any leading
        axes, e.g. design and support, each its own face).
    head_area_cm2 : float
        The string-bed area the points cover, cm².
    threshold_fraction : float
        In (0, 1]: how near the best a point must be (0.9: within 10 % of the best).

    Returns
    -------
    float or numpy.ndarray
        The area, cm² (the leading axes' shape; NaN where a face has no number at all).
    """
    values = np.asarray(rebound_ratio, dtype=float)
    finite = np.isfinite(values)
    any_finite = finite.any(axis=-1)
    filled = np.where(finite, values, -np.inf)
    best = np.where(any_finite, filled.max(axis=-1, initial=-np.inf), np.nan)
    threshold = best - (1.0 - float(threshold_fraction)) * np.abs(best)
    with np.errstate(invalid="ignore"):
        inside = filled >= threshold[..., np.newaxis]
    area = np.where(any_finite, inside.mean(axis=-1) * float(head_area_cm2), np.nan)
    return float(area) if area.ndim == 0 else np.asarray(area, dtype=float)


def summary_metrics(
    dataset: xr.Dataset,
    threshold_fraction: float | None = None,
    ball_speed: float | None = None,
    racket_speed: float | None = None,
) -> xr.Dataset:
    """Per design and support: rebound ratio at the face centre, the best, the sweet area.

    The face centre is the impact point nearest the head's centre.  The sweet area is
    :func:`sweet_area_cm2` of each design's and support's face: a design's number is the same
    whichever designs are compared (``summary.csv`` and each variable's figure).

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset.
    threshold_fraction : float, optional
        Default: the spec's (``summary.threshold_fraction``, 0.9).
    ball_speed, racket_speed : float, optional
        The speeds to evaluate at, m/s (nearest listed; default the spec's summary speeds).

    Returns
    -------
    xarray.Dataset
        ``centre_rebound_ratio``, ``best_rebound_ratio`` and ``sweet_area_cm2`` over
        ``(design, support)``, with the centre point and the definition in the attributes.
        A sweep with an uncertainty adds each metric's ``_p05`` and ``_p95``,
        ``centre_samples_valid``, ``face_samples_valid`` and ``band_note`` (why a band is
        NaN: under 90 % of the samples valid).
    """
    import xarray as xr

    fraction = float(
        dataset.attrs["threshold_fraction"] if threshold_fraction is None else threshold_fraction
    )
    speed = float(dataset.attrs["summary_ball_speed_mps"] if ball_speed is None else ball_speed)
    swing = float(
        dataset.attrs["summary_racket_speed_mps"] if racket_speed is None else racket_speed
    )
    rebound = dataset["rebound_ratio"].sel(speed=speed, racket_speed=swing, method="nearest")
    rebound = rebound.transpose("design", "support", "point")
    x, y = dataset["x_m"].values, dataset["y_m"].values
    centre = int(
        np.argmin(
            (x - dataset.attrs["head_centre_x_m"]) ** 2
            + (y - dataset.attrs["head_centre_y_m"]) ** 2
        )
    )
    n_designs, n_supports = rebound.shape[0], rebound.shape[1]
    head_area = float(dataset.attrs["head_area_cm2"])
    centre_values = np.full((n_designs, n_supports), np.nan)
    best = np.full((n_designs, n_supports), np.nan)
    area = np.full((n_designs, n_supports), np.nan)
    step = _block(dataset)
    for start in range(0, n_designs, step):  # a block of designs at a time (the store's chunks)
        block = slice(start, min(start + step, n_designs))
        values = np.asarray(rebound[block].values, dtype=float)
        area[block] = sweet_area_cm2(values, head_area, fraction)
        finite = np.isfinite(values)
        best[block] = np.where(
            finite.any(axis=-1), np.where(finite, values, -np.inf).max(axis=-1), np.nan
        )
        centre_values[block] = values[:, :, centre]
    coords = {"design": dataset["design"].values, "support": dataset["support"].values}
    bands = {}
    if "rebound_ratio_p05" in dataset:
        bands = _bands(dataset, centre, speed, swing)
        if fraction != float(dataset.attrs["threshold_fraction"]):  # the tasks' threshold
            bands = {k: v for k, v in bands.items() if not k.startswith("sweet_area")}
    return xr.Dataset(
        {
            "centre_rebound_ratio": (
                ("design", "support"),
                centre_values,
                {"units": "1", "long_name": "rebound ratio at the face centre"},
            ),
            "best_rebound_ratio": (
                ("design", "support"),
                best,
                {"units": "1", "long_name": "highest rebound ratio over the face"},
            ),
            "sweet_area_cm2": (
                ("design", "support"),
                area,
                {
                    "units": "cm2",
                    "long_name": f"sweet area: rebound ratio ≥ {fraction:g} × the face's best",
                    "definition": SWEET_AREA_DEFINITION,
                },
            ),
            **bands,
        },
        coords=coords,
        attrs={
            "ball_speed_mps": speed,
            "racket_speed_mps": swing,
            "threshold_fraction": fraction,
            "centre_point_x_m": float(x[centre]),
            "centre_point_y_m": float(y[centre]),
        },
    )


BAND_NOTE = (
    "5-95 % quantiles over the samples of the sweep's uncertainty; NaN where fewer than 90 % "
    "of the samples are valid (band_note says how many)"
)
"""What the ``_p05``/``_p95`` metrics mean, in the metrics' attributes."""


def _bands(
    dataset: xr.Dataset, centre: int, speed: float, swing: float
) -> dict[str, tuple[tuple[str, str], NDArray[Any], dict[str, str]]]:
    """The bands of the metrics (a sweep with an uncertainty): the centre's rebound ratio
    (its impact's quantiles), the best rebound ratio and the sweet area (each sample's face's
    quantiles, computed in the tasks), their valid shares and a note where a band is NaN."""
    from racketdyn.impact.uncertainty import MIN_VALID_SHARE

    at = {"speed": speed, "racket_speed": swing}

    def read(name: str, **where: int) -> NDArray[np.float64]:
        values = dataset[name].sel(at, method="nearest").isel(where)
        return np.asarray(values.transpose("design", "support").values, dtype=float)

    out: dict[str, tuple[tuple[str, str], NDArray[Any], dict[str, str]]] = {}
    dims = ("design", "support")
    for q in ("p05", "p95"):
        out[f"centre_rebound_ratio_{q}"] = (
            dims,
            read(f"rebound_ratio_{q}", point=centre),
            {"units": "1", "band": BAND_NOTE},
        )
    centre_share = read("samples_valid", point=centre)
    face_share = read("face_samples_valid")
    for metric, units in (("best_rebound_ratio", "1"), ("sweet_area_cm2", "cm2")):
        for q in ("p05", "p95"):
            out[f"{metric}_{q}"] = (
                dims,
                read(f"{metric}_{q}"),
                {"units": units, "band": BAND_NOTE},
            )
    out["centre_samples_valid"] = (dims, centre_share, {"units": "1"})
    out["face_samples_valid"] = (dims, face_share, {"units": "1"})
    notes = np.full(centre_share.shape, "", dtype=object)
    for index in np.ndindex(notes.shape):
        missing = [
            f"{share[index]:.0%} of the samples valid {where}"
            for share, where in ((centre_share, "at the centre"), (face_share, "over the face"))
            if not share[index] >= MIN_VALID_SHARE
        ]
        if missing:
            notes[index] = "no band: " + ", ".join(missing) + " (a band needs 90 %)"
    out["band_note"] = (dims, notes, {})
    return out


BLOCK_BYTES = 8 * 2**20
"""About this many bytes of results are read at once by :func:`summary_metrics` (whole
chunks of the store: a block is a whole number of its chunks along ``design``)."""


def _block(dataset: xr.Dataset) -> int:
    """Designs per block: a whole number of the store's chunks along ``design`` (Dask's, or
    the Zarr chunk in the variable's encoding; one design in memory) within
    :data:`BLOCK_BYTES`, at least one chunk."""
    variable = dataset["rebound_ratio"]
    if variable.chunks is not None:
        chunk = int(variable.chunks[0][0])
    else:
        chunk = int(variable.encoding.get("preferred_chunks", {}).get("design", 1))
    per_design = max(1, variable.size // max(1, variable.sizes["design"])) * 8
    return max(1, chunk) * max(1, BLOCK_BYTES // (max(1, chunk) * per_design))


def sweet_area_resolution_cm2(dataset: xr.Dataset) -> float:
    """The face area one impact point stands for, cm²: the step of ``sweet_area_cm2``."""
    return float(dataset.attrs["head_area_cm2"]) / max(int(dataset.sizes["point"]), 1)


SWEET_AREA_COARSE_FRACTION = 0.02
"""A sweet area counted in steps of more than 2 % of the face (fewer than 50 points: a grid
below 8) is reported as coarse."""


def axis_label(dataset: xr.Dataset, variable: str) -> tuple[str, str, float]:
    """The coordinate a variable is plotted against, its axis label and display scale."""
    info = _variables(dataset)[variable]
    coord = str(info["axis"])
    if info["kind"] == POINT_MASS:
        what = variable.replace("_", " ")
        quantity = coord.removeprefix(variable + "_")
        labels = {
            "mass_kg": (f"{what} (g)", 1e3),
            "clock": (f"{what} position (o'clock)", 1.0),
            "x_m": (f"{what} x (m)", 1.0),
            "y_m": (f"{what} y (m)", 1.0),
        }
        label, scale = labels[quantity]
        return coord, label, scale
    hand_labels = {
        "hand.arm_mass_kg": "arm mass (kg)",
        "hand.stiffness_n_per_m": "hand stiffness (N/m)",
        "hand.damping_ns_per_m": "hand damping (N·s/m)",
    }
    if coord in hand_labels:
        return coord, hand_labels[coord], 1.0
    name, _, unit = coord.rpartition("_")
    units = {"kg": "kg", "m": "m", "kgm2": "kg·m²", "kgcm2": "kg·cm²", "n": "N"}
    if unit in units:
        return coord, f"{name.replace('_', ' ')} ({units[unit]})", 1.0
    return coord, f"{coord.replace('_', ' ')} (–)", 1.0


def write_summary_csv(dataset: xr.Dataset, out_dir: Path | str) -> Path:
    """Write ``summary.csv``: the summary metrics per design and support.

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset.
    out_dir : path-like
        Output folder.

    Returns
    -------
    Path
        The file written.
    """
    metrics = summary_metrics(dataset)
    table = metrics.to_dataframe().unstack("support")
    table.columns = [f"{name}_{support}" for name, support in table.columns]
    # the speeds the metrics are for, in every row (a table read alone must say so)
    table["ball_speed_mps"] = metrics.attrs["ball_speed_mps"]
    table["racket_speed_mps"] = metrics.attrs["racket_speed_mps"]
    design_coords = [c for c in dataset.coords if dataset[c].dims == ("design",) and c != "design"]
    for coord in design_coords:
        table[coord] = dataset[coord].values
    table = table[design_coords + [c for c in table.columns if c not in design_coords]]
    path = Path(out_dir) / "summary.csv"
    table.to_csv(path)
    return path


def factorial_view(dataset: xr.Dataset) -> xr.Dataset:
    """A full-factorial sweep with one dimension per variable instead of ``design``.

    Each variable's dimension is its axis coordinate (``e_bg``, ``point_mass_mass_kg`` …).
    For analysis in memory; netCDF cannot store the index this builds.

    Parameters
    ----------
    dataset : xarray.Dataset
        A full-factorial sweep dataset.
    """
    if dataset.attrs["sweep_mode"] != "full-factorial":
        raise InputError("factorial_view needs a full-factorial sweep (mode = 'full-factorial')")
    axes = [str(v["axis"]) for v in _variables(dataset).values()]
    if not axes:
        return dataset.squeeze("design", drop=False)
    others = [
        c
        for c in dataset.coords
        if dataset[c].dims == ("design",) and c not in axes and c != "design"
    ]
    stacked = dataset.drop_vars(others).set_index(design=axes)
    return stacked.unstack("design")


@dataclass(frozen=True)
class SummaryCurves:
    """What a variable's summary figure draws (``summary_<variable>.png``): the rebound ratio at
    the face centre and the sweet area against the variable, one line per support.

    Attributes
    ----------
    variable : str
        The variable.
    title : str
        The sweep's title.
    x_label : str
        The axis label of the variable ("tension (N)", never the key ``tension_n``).
    x : ndarray (n_designs,)
        The variable's value of each design that shows it, in the axis's unit, in order along
        the axis (a clock round from 12, shown as 0); a point mass's designs without the mass
        left out (their levels are ``*_without``).
    clock : bool
        The axis is a clock position (o'clock).
    supports : tuple of str
        The sweep's supports.
    centre_rebound_ratio, sweet_area_cm2 : ndarray (n_supports, n_designs)
        The metrics of :func:`summary_metrics` at ``x`` (dimensionless; cm²).
    centre_without, area_without : ndarray (n_supports, n_levels)
        Their values for the designs without the point mass, each distinct once (NaN-padded;
        no columns when every design has it).
    without : str
        What those designs are without ("point mass"), empty if none.
    ball_speed, racket_speed : float
        The speeds the metrics are read at, m/s.
    threshold_fraction : float
        The sweet area's fraction of each face's best rebound ratio.
    bands : dict of str to (ndarray, ndarray)
        With an uncertainty (issue 24), each metric's 5 and 95 % quantiles at ``x``,
        ``(n_supports, n_designs)`` each (NaN where fewer than 90 % of its samples are valid);
        empty without one.
    """

    variable: str
    title: str
    x_label: str
    x: NDArray[np.float64]
    clock: bool
    supports: tuple[str, ...]
    centre_rebound_ratio: NDArray[np.float64]
    sweet_area_cm2: NDArray[np.float64]
    centre_without: NDArray[np.float64]
    area_without: NDArray[np.float64]
    without: str
    ball_speed: float
    racket_speed: float
    threshold_fraction: float
    bands: dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]] = field(default_factory=dict)

    def plot(self, ax: Axes | None = None) -> Axes:
        """Draw the rebound ratio at the face centre (into ``ax``, or a new figure); returns the
        axes (:func:`racketdyn.plotting.sweep.plot_centre_rebound`; its ``plot_sweet_area``
        draws the other panel)."""
        from racketdyn.plotting.sweep import plot_centre_rebound

        return plot_centre_rebound(self, ax)


def _levels(values: NDArray[np.float64], rows: NDArray[np.bool_]) -> NDArray[np.float64]:
    """Each support's distinct values on ``rows``, NaN-padded: ``(n_supports, n_levels)``."""
    levels = [np.unique(v[rows]) for v in values]
    padded = np.full((len(levels), max((len(u) for u in levels), default=0)), np.nan)
    for k, found in enumerate(levels):
        padded[k, : len(found)] = found
    return padded


def summary_curves(
    dataset: xr.Dataset,
    variable: str,
    threshold_fraction: float | None = None,
    ball_speed: float | None = None,
    racket_speed: float | None = None,
) -> SummaryCurves:
    """The summary figure's curves of one variable: :func:`summary_metrics` of the designs that
    show it (:func:`variable_designs`), along its axis (:func:`axis_label`).

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep dataset.
    variable : str
        The variable.
    threshold_fraction, ball_speed, racket_speed : float, optional
        As for :func:`summary_metrics` (default the spec's).
    """
    keep = variable_designs(dataset, variable)
    # each design's own face sets its threshold: the numbers of summary.csv
    metrics = summary_metrics(
        dataset.isel(design=keep), threshold_fraction, ball_speed, racket_speed
    )
    coord, label, scale = axis_label(dataset, variable)
    x = dataset[coord].values[keep] * scale
    clock = coord.endswith("_clock")
    if clock:  # round the clock from 12 (shown as 0 on the axis, labelled 12)
        x = np.mod(x, 12.0)
    # a point mass placed by clock or x, y: its designs without the mass (the base of a
    # one-at-a-time sweep) have a position too, which is no position of a mass — drawn as a
    # level, not as a point at that position
    without = np.zeros(x.size, dtype=bool)
    if _variables(dataset)[variable]["kind"] == POINT_MASS and not coord.endswith("_mass_kg"):
        without = dataset[f"{variable}_mass_kg"].values[keep] == 0.0
    order = np.argsort(np.where(without, np.inf, x), kind="stable")
    with_mass = order[~without[order]]
    supports = tuple(str(s) for s in metrics["support"].values.tolist())
    centre = np.array([metrics["centre_rebound_ratio"].sel(support=s).values for s in supports])
    area = np.array([metrics["sweet_area_cm2"].sel(support=s).values for s in supports])
    bands = {
        metric: (
            np.array([metrics[f"{metric}_p05"].sel(support=s).values for s in supports])[
                :, with_mass
            ],
            np.array([metrics[f"{metric}_p95"].sel(support=s).values for s in supports])[
                :, with_mass
            ],
        )
        for metric in ("centre_rebound_ratio", "sweet_area_cm2")
        if f"{metric}_p05" in metrics
    }
    return SummaryCurves(
        variable=variable,
        title=str(dataset.attrs["title"]),
        x_label=label,
        x=np.asarray(x[with_mass], dtype=float),
        clock=clock,
        supports=supports,
        centre_rebound_ratio=centre[:, with_mass],
        sweet_area_cm2=area[:, with_mass],
        centre_without=_levels(centre, without),
        area_without=_levels(area, without),
        without=variable.replace("_", " ") if without.any() else "",
        ball_speed=float(metrics.attrs["ball_speed_mps"]),
        racket_speed=float(metrics.attrs["racket_speed_mps"]),
        threshold_fraction=float(metrics.attrs["threshold_fraction"]),
        bands=bands,
    )


def summary_figures_data(dataset: xr.Dataset) -> dict[str, SummaryCurves]:
    """Every variable's :func:`summary_curves` (the spec's speeds and fraction), by variable:
    what the summary figures draw (the hook of :func:`racketdyn.sweep.run_sweep`)."""
    return {variable: summary_curves(dataset, variable) for variable in _variables(dataset)}
