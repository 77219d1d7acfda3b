"""Helpers of the figure-data objects: several figures' datasets in one netCDF 3 file.

netCDF 3 has no groups: each figure's variables, dimensions and attributes are prefixed with
its key and ``__`` (``fig11_12__mean_force_n``) by :func:`_join`, and read back by
:func:`_part` (:mod:`racketdyn.workflows.figure_data`,
:mod:`racketdyn.workflows.shape_figures`).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from racketdyn._grammar import unit_of

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


# --- a step's result objects as they are: any dataclass of arrays and plain values ------------
_STORED = "stored"
"""The attribute (``<key>__stored``) holding a stored object's structure as JSON."""


def _class_name(value: object) -> str:
    """``module:QualifiedName`` of an object's class, imported again when it is read back."""
    return f"{type(value).__module__}:{type(value).__qualname__}"


class _Encoder:
    """Turns one object into JSON-able structure and the arrays of its variables."""

    def __init__(self, key: str) -> None:
        self.key = key
        self.variables: dict[str, tuple[tuple[str, ...], NDArray[Any], dict[str, str]]] = {}

    def node(self, value: Any, path: str) -> Any:
        import dataclasses
        import enum

        if value is None or isinstance(value, bool | str):
            return {"t": "v", "v": value}
        if isinstance(value, enum.Enum):
            return {"t": "enum", "cls": _class_name(value), "v": value.value}
        if isinstance(value, np.bool_):
            return {"t": "v", "v": bool(value)}
        if isinstance(value, int | np.integer):
            return {"t": "v", "v": int(value)}
        if isinstance(value, float | np.floating):
            return {"t": "v", "v": float(value)}
        if isinstance(value, complex | np.complexfloating):
            return {"t": "c", "v": [float(value.real), float(value.imag)]}
        if isinstance(value, Path):
            return {"t": "path", "v": str(value)}
        if isinstance(value, np.ndarray):
            return self.array(value, path)
        if dataclasses.is_dataclass(value) and not isinstance(value, type):
            found = {
                f.name: self.node(getattr(value, f.name), f"{path}__{f.name}")
                for f in dataclasses.fields(value)
                if f.init
            }
            return {"t": "dc", "cls": _class_name(value), "f": found}
        if isinstance(value, tuple | list):
            items = [self.node(v, f"{path}__{k}") for k, v in enumerate(value)]
            return {"t": type(value).__name__, "v": items}
        if isinstance(value, Mapping):
            keys = [self.node(k, "") for k in value]
            items = [self.node(v, f"{path}__{k}") for k, v in enumerate(value.values())]
            return {"t": "dict", "k": keys, "v": items}
        raise TypeError(f"cannot store {type(value).__name__} at {path!r} in figures.nc")

    def array(self, value: NDArray[Any], path: str) -> Any:
        kind = value.dtype.kind
        if kind in "USO" or value.size == 0:  # text inline; no zero-length netCDF 3 dimension
            return {
                "t": "a",
                "dtype": value.dtype.str if kind != "O" else "<U0",
                "shape": list(value.shape),
                "v": [str(v) for v in value.ravel()] if kind in "USO" else [],
            }
        stored = value
        if kind == "c":
            stored = np.stack([value.real, value.imag], axis=-1)
        elif kind in "biu":
            stored = value.astype(float)  # netCDF 3 has no 64-bit integers; exact below 2**53
        name = f"{self.key}{path}"
        dims = tuple(f"{name}{_SEP}d{k}" for k in range(stored.ndim))
        units = unit_of(path.rsplit(_SEP, 1)[-1])
        self.variables[name] = (dims, stored, {"units": units} if units else {})
        return {"t": "a", "dtype": value.dtype.str, "shape": list(value.shape), "var": name}


def store(objects: Mapping[str, Any], label: str = "") -> xr.Dataset:
    """A step result's objects as one dataset of ``figures.nc``, exactly as they are: the data
    of the figures drawn from them (:func:`stored` reads them back).

    Any frozen dataclass of arrays and plain values, nested, in tuples, lists and dicts, is
    written: each array a variable (complex as a last dimension of real and imaginary parts;
    units from the field's name, ``_m``, ``_s``, ``_hz``, …), the structure, the plain values and
    the text as JSON in one attribute.

    Parameters
    ----------
    objects : mapping of str to object
        Name (the step result's attribute a figure ``reads``) → object.
    label : str
        The model's label of a step that writes its figures once per model (``compare``).
    """
    import json

    import xarray as xr

    dataset = xr.Dataset()
    for name, value in objects.items():
        key = f"data_{name}_{label}" if label else f"data_{name}"
        encoder = _Encoder(key)
        tree = encoder.node(value, "")
        dataset = dataset.assign(encoder.variables)
        record = {"name": name, "label": label, "tree": tree}
        dataset.attrs[f"{key}{_SEP}{_STORED}"] = json.dumps(record, allow_nan=True)
    return dataset


def stored(dataset: xr.Dataset, label: str = "") -> dict[str, Any]:
    """The objects :func:`store` wrote into ``dataset``, by name, of one model's ``label``."""
    import json

    found: dict[str, Any] = {}
    for attribute, text in dataset.attrs.items():
        if not str(attribute).endswith(f"{_SEP}{_STORED}"):
            continue
        record = json.loads(text)
        if record["label"] == label:
            found[record["name"]] = _decode(record["tree"], dataset)
    return found


def _decode(node: Any, dataset: xr.Dataset) -> Any:
    import importlib

    def imported(name: str) -> Any:
        module, _, qualified = name.partition(":")
        value: Any = importlib.import_module(module)
        for part in qualified.split("."):
            value = getattr(value, part)
        return value

    kind = node["t"]
    if kind == "v":
        return node["v"]
    if kind == "c":
        return complex(*node["v"])
    if kind == "path":
        return Path(node["v"])
    if kind == "enum":
        return imported(node["cls"])(node["v"])
    if kind == "a":
        dtype = np.dtype(node["dtype"])
        if "var" not in node:
            return np.asarray(node["v"], dtype=dtype).reshape(node["shape"])
        values = np.asarray(dataset[node["var"]].values)
        if dtype.kind == "c":
            values = values[..., 0] + 1j * values[..., 1]
        return values.astype(dtype).reshape(node["shape"])
    if kind == "dc":
        fields = {name: _decode(value, dataset) for name, value in node["f"].items()}
        return imported(node["cls"])(**fields)
    items = [_decode(value, dataset) for value in node["v"]]
    if kind == "dict":
        return dict(zip([_decode(k, dataset) for k in node["k"]], items, strict=True))
    return tuple(items) if kind == "tuple" else items
