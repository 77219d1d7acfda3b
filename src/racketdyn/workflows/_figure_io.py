"""Helpers of the figure-data objects: several figures' datasets in one netCDF 3 file.

netCDF 3 has no groups: each figure's variables, dimensions and attributes are prefixed with
its key and ``__`` (``fig11_12__mean_force_n``) by :func:`_join`, and read back by
:func:`_part` (:mod:`racketdyn.workflows.figure_data`,
:mod:`racketdyn.workflows.shape_figures`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    import xarray as xr

_SEP = "__"


def _array(values: ArrayLike) -> NDArray[np.float64]:
    return np.asarray(values, dtype=float)


def _strings(values: Any) -> tuple[str, ...]:
    return tuple(str(v) for v in np.asarray(values).ravel())


def _prefixed(dataset: xr.Dataset, key: str) -> xr.Dataset:
    """Every name of ``dataset`` (variables, coordinates, dimensions, attributes) prefixed."""
    names = {name: f"{key}{_SEP}{name}" for name in [*dataset.variables, *dataset.dims]}
    renamed = dataset.rename(names)
    renamed.attrs = {f"{key}{_SEP}{name}": value for name, value in dataset.attrs.items()}
    return renamed


def _join(parts: Mapping[str, xr.Dataset]) -> xr.Dataset:
    """Datasets of several figures as one, each name prefixed with its figure's key."""
    import xarray as xr

    prefixed = [_prefixed(data, key) for key, data in parts.items()]
    # "override": each variable keeps its own attributes (units); the dataset's are set below
    joined = xr.merge(prefixed, combine_attrs="override") if prefixed else xr.Dataset()
    joined.attrs = {}
    for part in prefixed:
        joined.attrs.update(part.attrs)
    return joined


def _part(dataset: xr.Dataset, key: str) -> xr.Dataset:
    """The figure ``key``'s dataset, as :func:`_join` took it in."""
    start = f"{key}{_SEP}"
    names = [str(name) for name in dataset.variables if str(name).startswith(start)]
    if not names:
        raise KeyError(f"no data of the figure {key!r}")
    chosen = dataset[[n for n in names if n in dataset.data_vars]]
    chosen = chosen.assign_coords({n: dataset[n] for n in names if n in dataset.coords})
    renamed = chosen.rename(
        {
            name: str(name)[len(start) :]
            for name in [*chosen.variables, *chosen.dims]
            if str(name).startswith(start)
        }
    )
    renamed.attrs = {
        name[len(start) :]: value for name, value in dataset.attrs.items() if name.startswith(start)
    }
    return renamed


def _has(dataset: xr.Dataset, key: str) -> bool:
    return any(str(name).startswith(f"{key}{_SEP}") for name in dataset.variables)
