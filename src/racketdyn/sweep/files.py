"""Sweep files: one netCDF part per finished task, combined into ``sweep.nc``.

:func:`~racketdyn.sweep.run.run_sweep` writes each :class:`~.task.TaskOutput` as
``parts/<task-id>.nc`` as it ends, skips the tasks whose part carries the spec's hash, and
combines the parts, always from the files, into the sweep dataset that
:mod:`~racketdyn.sweep.summary` reads.
"""

from __future__ import annotations

import json
import logging
import os
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.__about__ import __version__
from racketdyn.sweep.design import Design, build_design
from racketdyn.sweep.spec import SweepSpec
from racketdyn.sweep.task import _IMPACT_VARIABLES, STATUS_CODES, STATUS_FAILED, TaskOutput

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["PART_FORMAT", "SWEEP_FORMAT"]

# the package's logger, racketdyn.sweep: the sweep's messages keep one name
log = logging.getLogger(__package__)

PART_FORMAT = "racketdyn-sweep-part"
SWEEP_FORMAT = "racketdyn-sweep"

_DERIVED = {
    "racket_mass_kg": ("mass_kg", "kg", "racket mass with point masses"),
    "racket_balance_m": ("balance_m", "m", "balance point with point masses"),
    "racket_inertia_cg_kgm2": ("inertia_cg_kgm2", "kg m2", "inertia about the balance point"),
    "racket_swingweight_kgcm2": ("swingweight_kgcm2", "kg cm2", "swingweight"),
    "racket_twistweight_kgcm2": ("twistweight_kgcm2", "kg cm2", "twistweight"),
    "racket_centre_of_percussion_m": (
        "centre_of_percussion_m",
        "m",
        "centre of percussion for the grip pivot",
    ),
}
_IMPACT_DIMS = ("design", "point", "speed", "racket_speed", "support")


def _write_netcdf(dataset: xr.Dataset, path: Path) -> None:
    """Write netCDF 3 (xarray's scipy engine) atomically, see :func:`_atomic`."""
    with _atomic(path) as temporary:
        dataset.to_netcdf(temporary, engine="scipy")


@contextmanager
def _atomic(path: Path) -> Iterator[Path]:
    """A temporary name to write to, renamed to ``path`` on success: a reader never sees half a
    file, and an interrupted write leaves nothing behind."""
    temporary = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        yield temporary
        os.replace(temporary, path)
    finally:
        temporary.unlink(missing_ok=True)


def _read_netcdf(path: Path) -> xr.Dataset:
    import xarray as xr

    with xr.open_dataset(path, engine="scipy") as dataset:
        return dataset.load()


# Part files are plain netCDF 3 (xarray reads them), written and read with scipy's netCDF
# module directly: a few milliseconds less per part than through xarray, which is most of the
# coordinating process's work per task.  Numbers only; names and settings go in attributes.
def _write_part(
    sha256: str,
    task_id: str,
    settings: Sequence[tuple[str, float]],
    output: TaskOutput,
    parts_dir: Path,
) -> None:
    """Write one finished task as ``parts_dir/<task_id>.nc`` (in a worker or the main process)."""
    from scipy.io import netcdf_file

    dims = _IMPACT_DIMS[1:]
    with (
        _atomic(parts_dir / f"{task_id}.nc") as temporary,
        netcdf_file(temporary, "w", version=2) as part,
    ):
        shape = output.arrays["status"].shape
        for dim, size in zip(dims, shape, strict=True):
            part.createDimension(dim, size)
        for name, array in output.arrays.items():
            typecode = "b" if name == "status" else "d"
            variable = part.createVariable(name, typecode, dims)
            variable[:] = array
        variable = part.createVariable("reduced_mass_kg", "d", ("point", "support"))
        variable[:] = output.reduced_mass_kg
        if output.mode_names:
            part.createDimension("mode", len(output.mode_names))
            variable = part.createVariable("mode_frequency_hz", "d", ("mode",))
            variable[:] = output.mode_frequency_hz
        attributes = {
            "format": PART_FORMAT,
            "task_id": task_id,
            "spec_sha256": sha256,
            "design": json.dumps(dict(settings)),
            "mode_names": json.dumps(list(output.mode_names)),
            "attempt": output.attempt,
            "racketdyn_version": __version__,
        }
        for key, value in attributes.items():
            setattr(part, key, value)


def _remove_stale_temporaries(parts_dir: Path) -> None:
    """Remove half-written parts (``.<name>.<pid>.tmp``) of processes that are gone (a worker
    killed while writing); those of a live process are its business."""
    for stale in parts_dir.glob(".*.tmp"):
        pid = stale.name.rsplit(".", 2)[-2]
        if pid.isdigit() and _process_exists(int(pid)):
            continue
        stale.unlink(missing_ok=True)


def _process_exists(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _read_part(path: Path, spec: SweepSpec, data: bool) -> dict[str, Any] | None:
    """A part's arrays and attributes (``data=False``: attributes only) if it belongs to this
    spec, else None (missing, unreadable, or written for another spec or version)."""
    if not path.is_file():
        return None
    from scipy.io import netcdf_file

    try:
        with netcdf_file(path, "r", mmap=False) as part:
            attributes = {
                key: getattr(part, key).decode() if hasattr(part, key) else None
                for key in ("format", "task_id", "spec_sha256", "mode_names")
            }
            current = (
                attributes.get("format") == PART_FORMAT
                and attributes.get("spec_sha256") == spec.sha256
                and attributes.get("task_id") == path.stem
            )
            arrays = {
                name: np.asarray(variable.data).astype(variable.data.dtype.newbyteorder("="))
                for name, variable in part.variables.items()
                if data and current
            }
    except Exception as error:  # unreadable: compute it again
        log.warning("%s cannot be read (%s); the task runs again", path, error)
        return None
    if not current:
        log.info("%s belongs to another spec or version; the task runs again", path)
        return None
    return {**arrays, "attributes": attributes}


def _units(name: str) -> dict[str, Any]:
    if name == "status":
        return {
            "long_name": "impact status",
            "flag_values": np.array(list(STATUS_CODES.values()), dtype=np.int8),
            "flag_meanings": " ".join(s.replace(" ", "_") for s in STATUS_CODES),
        }
    _, units, long_name = _IMPACT_VARIABLES[name]
    return {"units": units, "long_name": long_name}


class _Assembly:
    """The sweep's arrays, filled design by design from the part files: while the workers
    compute, the coordinating process reads each part as it is recorded, so combining at the
    end reads only the resumed ones.  Mode names are ordered at the end, in design order, so
    the order parts arrive in does not show in ``sweep.nc``."""

    def __init__(self, spec: SweepSpec, parts_dir: Path) -> None:
        self.spec, self.parts_dir = spec, parts_dir
        n_d, n_p, n_s, n_r, n_u = (
            len(spec.designs),
            spec.locations.shape[0],
            spec.ball_speeds.size,
            spec.racket_speeds.size,
            len(spec.supports),
        )
        shape = (n_d, n_p, n_s, n_r, n_u)
        self.arrays: dict[str, NDArray[Any]] = {
            name: np.full(shape, np.nan) for name in _IMPACT_VARIABLES
        }
        self.arrays["status"] = np.full(shape, STATUS_CODES[STATUS_FAILED], dtype=np.int8)
        self.reduced = np.full((n_d, n_p, n_u), np.nan)
        self.modes: dict[int, list[tuple[str, float]]] = {}
        self.read: set[int] = set()
        self.missing: list[Design] = []
        """Designs whose part was not there, or of another spec, when read."""

    def add(self, design: Design) -> None:
        """Read one design's part, if it is there and of this spec."""
        part = _read_part(self.parts_dir / f"{design.task_id}.nc", self.spec, data=True)
        self.read.add(design.index)
        if part is None:
            self.missing.append(design)
            return
        for name, array in self.arrays.items():
            array[design.index] = part[name]
        self.reduced[design.index] = part["reduced_mass_kg"]
        names = json.loads(part["attributes"]["mode_names"])
        frequencies = part.get("mode_frequency_hz", [])
        self.modes[design.index] = [
            (mode, float(f)) for mode, f in zip(names, frequencies, strict=True)
        ]


def _combine(
    spec: SweepSpec,
    parts_dir: Path,
    failures: Sequence[dict[str, Any]],
    assembly: _Assembly | None = None,
) -> xr.Dataset:
    """The sweep dataset from the part files, in design order (NaN where a part is missing);
    the parts an ``assembly`` has read already are not read again."""
    import xarray as xr

    designs = spec.designs
    n_p = spec.locations.shape[0]
    if assembly is None:
        assembly = _Assembly(spec, parts_dir)
    for design in designs:
        if design.index not in assembly.read:
            assembly.add(design)
    arrays, reduced = assembly.arrays, assembly.reduced
    mode_names: list[str] = []
    frequencies: dict[tuple[int, str], float] = {}
    for design in designs:
        for mode, hz in assembly.modes.get(design.index, []):
            if mode not in mode_names:
                mode_names.append(mode)
            frequencies[design.index, mode] = hz
    data: dict[str, Any] = {
        name: (_IMPACT_DIMS, array, _units(name)) for name, array in arrays.items()
    }
    data["reduced_mass_kg"] = (
        ("design", "point", "support"),
        reduced,
        {"units": "kg", "long_name": "reduced mass of the racket at the impact point (eq 4)"},
    )
    coords: dict[str, Any] = {
        "design": ("design", np.arange(len(designs), dtype=np.int32)),
        "task_id": ("design", [d.task_id for d in designs]),
        "varied": ("design", [d.varied for d in designs]),
        "point": ("point", np.arange(n_p, dtype=np.int32)),
        "point_label": ("point", list(spec.labels)),
        "x_m": ("point", spec.locations[:, 0], {"units": "m", "long_name": "x from the butt"}),
        "y_m": ("point", spec.locations[:, 1], {"units": "m", "long_name": "y across the axis"}),
        "speed": ("speed", spec.ball_speeds, {"units": "m s-1", "long_name": "ball speed"}),
        "racket_speed": (
            "racket_speed",
            spec.racket_speeds,
            {"units": "m s-1", "long_name": "racket speed at the impact point"},
        ),
        "support": ("support", list(spec.supports)),
    }
    for variable in spec.variables:
        for coord in variable.coords:
            values = [dict(d.settings)[coord] for d in designs]
            coords[coord] = ("design", np.asarray(values, dtype=float), {"variable": variable.name})
    derived = []
    for design in designs:
        racket, _, _ = build_design(spec.racket, spec.ball, spec.variables, design.settings)
        derived.append(racket.derived_properties())
    for name, (key, units, long_name) in _DERIVED.items():
        coords[name] = (
            "design",
            np.array([d[key] for d in derived]),
            {"units": units, "long_name": long_name},
        )
    if mode_names:
        frequency = np.full((len(designs), len(mode_names)), np.nan)
        for (index, mode), value in frequencies.items():
            frequency[index, mode_names.index(mode)] = value
        data["mode_frequency_hz"] = (
            ("design", "mode"),
            frequency,
            {"units": "Hz", "long_name": "natural frequency of the modes charged"},
        )
        coords["mode"] = ("mode", mode_names)
    head = spec.racket.head
    attrs = {
        "format": SWEEP_FORMAT,
        "title": spec.name,
        "racketdyn_version": __version__,
        "spec_sha256": spec.sha256,
        "spec": json.dumps(spec.to_dict(), sort_keys=True),
        # not "variables" nor "mode": scipy's netCDF writer keeps its own state under those names
        "sweep_variables": json.dumps(
            [{**v.to_dict(), "base": list(spec.base_value(v))} for v in spec.variables]
        ),
        "sweep_mode": spec.mode,
        "method": spec.method,
        "engine": spec.transient_engine if spec.method == "transient" else "",
        "stiffness_reading": spec.stiffness_reading,
        "include_string_bed": int(spec.include_string_bed),
        "string_bed": spec.string_bed,
        "rigid": int(spec.rigid),
        "head_centre_x_m": head.centre_x_m,
        "head_centre_y_m": head.centre_y_m,
        "head_area_cm2": head.area_m2 * 1e4,
        "threshold_fraction": spec.threshold_fraction,
        "summary_ball_speed_mps": _summary_speed(spec.summary_ball_speed, spec.ball_speeds, True),
        "summary_racket_speed_mps": _summary_speed(
            spec.summary_racket_speed, spec.racket_speeds, False
        ),
        **_failure_attrs(failures),
    }
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _failure_attrs(failures: Sequence[dict[str, Any]]) -> dict[str, Any]:
    """The dataset's ``n_failed`` and ``failed_tasks`` attributes."""
    return {
        "n_failed": len(failures),
        "failed_tasks": json.dumps(
            [{k: f[k] for k in ("task_id", "design", "error")} for f in failures]
        ),
    }


def _summary_speed(value: float | None, listed: NDArray[np.float64], middle: bool) -> float:
    if value is not None:
        return float(listed[np.argmin(np.abs(listed - value))])
    return float(listed[listed.size // 2] if middle else listed[0])
