"""The sweep's store: one Zarr group, ``sweep.zarr``, written chunk by chunk as designs finish.

:func:`~racketdyn.sweep.run.run_sweep` creates the store before the first task (every array's
shape, coordinates and attributes; no data), and each finished batch of designs is written
into its own chunk along ``design`` — by the worker that computed it when the worker sees
the store (a worker on this machine; a remote Dask worker when the store is on a path every
worker can write, ``TaskOptions(shared_store=True)``), else by the main process — so no process
ever holds more than a chunk of results.  Readers open it lazily (:func:`open_sweep`,
``xr.open_zarr``): the summary and the figures read it chunk by chunk.

What makes it safe to resume and to read:

- a chunk file is written whole or not at all (Zarr's local store writes a temporary file and
  renames it);
- each chunk's designs are recorded as done in the ``records`` sub-group (one JSON text per
  design: its attempt and modes) *after* their data: a design is done when its record is there
  and its chunk's data files are present (a chunk file lost since is a design to compute
  again);
- a batch that completes a chunk already partly done reads the chunk first and keeps the done
  designs (only one task per chunk is in flight at a time);
- a worker writes only into the store of the run that sent it its task: the group attribute
  ``run_token`` (a random text set when a run starts, cleared when it finishes) must equal the
  task's, so a worker that sees another folder at the same path (a node's own disk), or a
  task left over from an earlier run, never writes there (:class:`StoreNotSeenError`);
- the group attribute ``sweep_complete`` is 0 from the moment a run starts writing and becomes
  1 last, once every design has ended and the mode table and failures are written: a store of
  an interrupted run is never read as complete (:func:`open_sweep` refuses it).
"""

from __future__ import annotations

import json
import logging
import os
import shutil
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.__about__ import __version__
from racketdyn.errors import InputError
from racketdyn.sweep.design import build_design
from racketdyn.sweep.spec import SweepSpec
from racketdyn.sweep.task import (
    _FACE_DIMS,
    _IMPACT_VARIABLES,
    STATUS_CODES,
    STATUS_FAILED,
    TaskOutput,
    band_variables,
)

if TYPE_CHECKING:
    import xarray as xr
    import zarr

__all__ = ["STORE_LAYOUT", "STORE_NAME", "SWEEP_FORMAT", "StoreNotSeenError", "open_sweep"]

# the package's logger, racketdyn.sweep: the sweep's messages keep one name
log = logging.getLogger(__package__)

SWEEP_FORMAT = "racketdyn-sweep"
STORE_NAME = "sweep.zarr"
"""The store's folder in a sweep's output folder."""
STORE_LAYOUT = "zarr-3, one chunk per design batch, records/design written last"
"""What ``run.json`` records as the store's layout (``store.layout``)."""
RUN_TOKEN = "run_token"
"""The group attribute naming the run that writes the store ("" once it has finished)."""
RECORDS = "records"
"""The sub-group holding ``design``: per design, "" until it is done, then a JSON text."""

_FAILED = STATUS_CODES[STATUS_FAILED]
_IMPACT_DIMS = ("design", "point", "speed", "racket_speed", "support")
_REDUCED_DIMS = ("design", "point", "support")
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


def _chunked_variables(
    bands: bool = False,
) -> dict[str, tuple[tuple[str, ...], str, Any, dict[str, Any]]]:
    """Every array written chunk by chunk: name → (dims, dtype, fill value, attributes); with
    ``bands`` (a sweep with an uncertainty) the bands too (:func:`~.task.band_variables`)."""
    variables: dict[str, tuple[tuple[str, ...], str, Any, dict[str, Any]]] = {}
    for name, (_, units, long_name) in _IMPACT_VARIABLES.items():
        variables[name] = (
            _IMPACT_DIMS,
            "float64",
            np.nan,
            {"units": units, "long_name": long_name},
        )
    variables["status"] = (
        _IMPACT_DIMS,
        "int8",
        _FAILED,  # a chunk never written reads as "task failed"
        {
            "long_name": "impact status",
            "flag_values": list(STATUS_CODES.values()),
            "flag_meanings": " ".join(s.replace(" ", "_") for s in STATUS_CODES),
        },
    )
    variables["reduced_mass_kg"] = (
        _REDUCED_DIMS,
        "float64",
        np.nan,
        {"units": "kg", "long_name": "reduced mass of the racket at the impact point (eq 4)"},
    )
    if bands:
        for name, (per_impact, units, long_name) in band_variables().items():
            variables[name] = (
                _IMPACT_DIMS if per_impact else _FACE_DIMS,
                "float64",
                np.nan,
                {"units": units, "long_name": long_name},
            )
    return variables


CHUNKED = tuple(_chunked_variables())
"""The arrays written chunk by chunk (the impact quantities, ``status``, ``reduced_mass_kg``;
with an uncertainty, the bands of :func:`~racketdyn.sweep.task.band_variables` too)."""


def _chunked_names(group: zarr.Group) -> tuple[str, ...]:
    """The arrays of this store written chunk by chunk (the bands where the group attribute
    ``bands`` is 1)."""
    return CHUNKED + (tuple(band_variables()) if group.attrs.get("bands") else ())


# --- creating ---------------------------------------------------------------------------------
def store_path(out: Path) -> Path:
    return out / STORE_NAME


def _coordinates(spec: SweepSpec) -> dict[str, Any]:
    """The store's coordinates: designs (with every variable and derived racket property),
    points, speeds, supports; strings as Python objects (Zarr's variable-length UTF-8)."""
    designs = spec.designs
    n_p = spec.locations.shape[0]

    def text(values: Sequence[str]) -> NDArray[np.object_]:
        return np.array(list(values), dtype=object)

    coords: dict[str, Any] = {
        "design": ("design", np.arange(len(designs), dtype=np.int32)),
        "task_id": ("design", text([d.task_id for d in designs])),
        "varied": ("design", text([d.varied for d in designs])),
        "point": ("point", np.arange(n_p, dtype=np.int32)),
        "point_label": ("point", text(spec.labels)),
        "x_m": ("point", spec.locations[:, 0], {"units": "m", "long_name": "x from the butt"}),
        "y_m": ("point", spec.locations[:, 1], {"units": "m", "long_name": "y across the axis"}),
        "speed": ("speed", spec.ball_speeds, {"units": "m s-1", "long_name": "ball speed"}),
        "racket_speed": (
            "racket_speed",
            spec.racket_speeds,
            {"units": "m s-1", "long_name": "racket speed at the impact point"},
        ),
        "support": ("support", text(spec.supports)),
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
    return coords


def _attributes(spec: SweepSpec) -> dict[str, Any]:
    head = spec.racket.head
    return {
        "format": SWEEP_FORMAT,
        "title": spec.name,
        "racketdyn_version": __version__,
        "spec_sha256": spec.sha256,
        "spec": json.dumps(spec.to_dict(), sort_keys=True),
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
        "n_failed": 0,
        "failed_tasks": "[]",
        "sweep_complete": 0,
        "bands": int(spec.uncertainty is not None),
        **(
            {}
            if spec.uncertainty is None
            else {"uncertainty": json.dumps(spec.uncertainty_record())}
        ),
    }


def _summary_speed(value: float | None, listed: NDArray[np.float64], middle: bool) -> float:
    if value is not None:
        return float(listed[np.argmin(np.abs(listed - value))])
    return float(listed[listed.size // 2] if middle else listed[0])


def create_store(spec: SweepSpec, out: Path, designs_per_chunk: int) -> None:
    """Create ``out/sweep.zarr`` for ``spec`` (replacing a store of another spec): every array
    with its shape and chunks along ``design``, the coordinates and attributes, no results.
    Built under a temporary name and renamed: a store is there whole or not at all."""
    import xarray as xr
    import zarr

    path = store_path(out)
    temporary = out / f".{STORE_NAME}.{os.getpid()}.tmp"
    shutil.rmtree(temporary, ignore_errors=True)
    xr.Dataset(coords=_coordinates(spec), attrs=_attributes(spec)).to_zarr(
        temporary, mode="w", zarr_format=3, consolidated=False
    )
    group = zarr.open_group(temporary, mode="r+")
    sizes = {
        "design": len(spec.designs),
        "point": spec.locations.shape[0],
        "speed": spec.ball_speeds.size,
        "racket_speed": spec.racket_speeds.size,
        "support": len(spec.supports),
    }
    coordinates = " ".join(_coordinate_names(spec))
    for name, (dims, dtype, fill, attrs) in _chunked_variables(
        spec.uncertainty is not None
    ).items():
        shape = tuple(sizes[d] for d in dims)
        group.create_array(
            name,
            shape=shape,
            chunks=(designs_per_chunk, *shape[1:]),
            dtype=dtype,
            fill_value=fill,
            dimension_names=dims,
            attributes={**attrs, "coordinates": coordinates},
        )
    records = group.create_group(RECORDS)
    records.create_array(
        "design",
        shape=(sizes["design"],),
        chunks=(designs_per_chunk,),
        dtype=str,
        fill_value="",
        dimension_names=("design",),
    )
    if path.exists():
        old = out / f".{STORE_NAME}.{os.getpid()}.old"
        os.replace(path, old)
        shutil.rmtree(old, ignore_errors=True)
    os.replace(temporary, path)


def _coordinate_names(spec: SweepSpec) -> list[str]:
    """The non-dimension coordinates of the chunked arrays."""
    names = ["task_id", "varied", "point_label", "x_m", "y_m"]
    names += [coord for variable in spec.variables for coord in variable.coords]
    return names + list(_DERIVED)


def remove_stale_temporaries(out: Path) -> None:
    """Remove what killed processes left half-made: a store being created (``.sweep.zarr.<pid>
    .tmp`` of a process that is gone) and Zarr's half-written chunk files (``*.partial``,
    called only before this run's workers start)."""
    for stale in out.glob(f".{STORE_NAME}.*"):
        pid = stale.name.split(".")[-2]
        if pid.isdigit() and int(pid) != os.getpid() and _process_exists(int(pid)):
            continue
        shutil.rmtree(stale, ignore_errors=True)
    path = store_path(out)
    if path.is_dir():
        for partial in path.rglob("*.partial"):
            partial.unlink(missing_ok=True)


def _process_exists(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


# --- opening ----------------------------------------------------------------------------------
@dataclass(frozen=True)
class StoreInfo:
    """An existing store: its spec hash, designs per chunk and designs."""

    spec_sha256: str
    designs_per_chunk: int
    n_designs: int
    complete: bool


def store_info(out: Path) -> StoreInfo | None:
    """The store in ``out``, or None when there is none or it cannot be read."""
    import zarr

    path = store_path(out)
    if not (path / "zarr.json").is_file():
        return None
    try:
        group = zarr.open_group(path, mode="r")
        status = _array(group, "status")
        return StoreInfo(
            str(group.attrs["spec_sha256"]),
            int(status.chunks[0]),
            int(status.shape[0]),
            bool(group.attrs.get("sweep_complete", 0)),
        )
    except Exception as error:  # damaged: made again
        log.warning("%s cannot be read (%s); it is made again", path, error)
        return None


def _open_group(path: Path, sha256: str, mode: str = "r+") -> zarr.Group:
    import zarr

    group = zarr.open_group(path, mode=mode)  # type: ignore[arg-type]
    if group.attrs.get("spec_sha256") != sha256:
        raise RuntimeError(f"{path} now belongs to another sweep (spec hash changed)")
    return group


def _array(group: zarr.Group, name: str) -> zarr.Array[Any]:
    """The array ``name`` (a path: ``records/design``) of the group."""
    import zarr

    array = group[name]
    if not isinstance(array, zarr.Array):
        raise TypeError(f"{name} is not an array of the sweep store")
    return array


def _writable(group: zarr.Group, name: str) -> zarr.Array[Any]:
    # a chunk equal to its fill value is written too: a chunk file missing means a chunk lost
    return _array(group, name).with_config({"write_empty_chunks": True})


class StoreNotSeenError(RuntimeError):
    """A worker does not see this run's store at the path it was given (no store there,
    another sweep's, or another run's): the main process writes the chunk instead."""


def _group_for_run(path: Path, sha256: str, token: str) -> zarr.Group:
    """The store at ``path`` opened for writing, if it is the one of the run ``token``.

    Raises
    ------
    StoreNotSeenError
        No store there, another spec's, or another run's (a node's own disk mounted at the
        same path; a task left over from an earlier run).
    """
    try:
        group = _open_group(path, sha256)
    except (OSError, RuntimeError, KeyError, ValueError) as error:  # zarr: not found, …
        raise StoreNotSeenError(f"{path}: {type(error).__name__}: {error}") from None
    if group.attrs.get(RUN_TOKEN) != token:
        raise StoreNotSeenError(f"{path} is not the store of this run (another run's token)")
    return group


def store_seen(out: str, sha256: str, token: str) -> str:
    """Whether this process sees the store of run ``token`` in ``out`` and can write into its
    folder: "" if so, else why not.  Run on each Dask worker before a run whose workers are
    to write the store (``shared_store``).

    Parameters
    ----------
    out : str
        The sweep's folder, an absolute path.
    sha256 : str
        The spec's hash.
    token : str
        The run's token (the store's ``run_token`` attribute).
    """
    import socket
    import tempfile

    try:
        _group_for_run(store_path(Path(out)), sha256, token)
        with tempfile.NamedTemporaryFile(dir=store_path(Path(out)), prefix=".probe."):
            pass
    except StoreNotSeenError as error:
        return f"{socket.gethostname()}: {error}"
    except OSError as error:
        return f"{socket.gethostname()}: cannot write in {store_path(Path(out))} ({error})"
    return ""


def set_complete(out: Path, sha256: str, complete: bool, **attrs: Any) -> None:
    """Set ``sweep_complete`` (and other attributes, written with it)."""
    group = _open_group(store_path(out), sha256)
    group.attrs.update({**attrs, "sweep_complete": int(complete)})


def read_records(out: Path, sha256: str) -> list[dict[str, Any] | None]:
    """Each design's record (attempt, modes) if done, else None."""
    group = _open_group(store_path(out), sha256, "r")
    texts = _array(group, f"{RECORDS}/design")[:]
    return [json.loads(str(t)) if t else None for t in np.asarray(texts).tolist()]


def recorded(out: Path, sha256: str, indices: Sequence[int] | None = None) -> list[bool]:
    """Whether each design (all, or ``indices``) is recorded as done in the store in ``out``
    (all False when there is no store of this spec)."""
    try:
        group = _open_group(store_path(out), sha256, "r")
        texts = _array(group, f"{RECORDS}/design")
        if indices is None:
            values = np.asarray(texts[:])
        elif len(indices) == 0:
            return []
        else:
            values = np.asarray(texts.get_coordinate_selection(np.asarray(indices, np.int64)))
    except Exception:  # no store, or another spec's
        return [False] * (0 if indices is None else len(indices))
    return [bool(t) for t in values.tolist()]


def _chunk_keys(group: zarr.Group, path: Path, chunk: int) -> list[Path]:
    """The files of one chunk of every chunked array of the store at ``path``."""
    files = []
    for name in _chunked_names(group):
        array = _array(group, name)
        key = array.metadata.encode_chunk_key((chunk,) + (0,) * (array.ndim - 1))
        files.append(path / name / key)
    return files


def done_designs(out: Path, spec: SweepSpec) -> tuple[set[int], list[int]]:
    """The designs done in the store (recorded, their chunk's files present), and those
    recorded whose chunk lost a file (their records are cleared: they run again)."""
    import zarr

    path = store_path(out)
    records = read_records(out, spec.sha256)
    group = zarr.open_group(path, mode="r+")
    size = int(_array(group, "status").chunks[0])
    done: set[int] = set()
    lost: list[int] = []
    for chunk in range(-(-len(records) // size)):
        rows = range(chunk * size, min((chunk + 1) * size, len(records)))
        recorded = [i for i in rows if records[i] is not None]
        if not recorded:
            continue
        if all(f.is_file() for f in _chunk_keys(group, path, chunk)):
            done.update(recorded)
            continue
        log.warning(
            "%s: chunk %d lost a file; its %d designs run again", path, chunk, len(recorded)
        )
        lost += recorded
        block = _writable(group, f"{RECORDS}/design")
        block[rows.start : rows.stop] = np.full(len(rows), "", dtype=object)
    return done, lost


# --- writing ----------------------------------------------------------------------------------
def write_chunk(
    out: Path | str,
    sha256: str,
    indices: Sequence[int],
    outputs: Sequence[TaskOutput],
    token: str | None = None,
) -> None:
    """Write finished designs (all in one chunk) into the store, then their records.

    The chunk's designs done before and not among these are read first and kept; the rows
    of designs not done are the fill values (NaN, status 3).  Called where the designs ran
    when that process sees the store, else in the main process; one call per chunk at a
    time (the runner never has two tasks of one chunk in flight).  With ``token`` (a
    worker's call), only into the store of that run, else :class:`StoreNotSeenError`."""
    if not outputs:
        return
    path = store_path(Path(out))
    group = _open_group(path, sha256) if token is None else _group_for_run(path, sha256, token)
    size = int(_array(group, "status").chunks[0])
    n_designs = int(_array(group, "status").shape[0])
    chunk = indices[0] // size
    lo, hi = chunk * size, min((chunk + 1) * size, n_designs)
    if any(i // size != chunk for i in indices):
        raise ValueError(f"designs {list(indices)} span more than one chunk of {size}")
    records = _writable(group, f"{RECORDS}/design")
    texts = np.asarray(records[lo:hi], dtype=object)
    rows = [i - lo for i in indices]
    kept = [r for r in range(hi - lo) if texts[r] and r not in rows]
    for name in _chunked_names(group):
        array = _writable(group, name)
        if kept:
            block = np.asarray(array[lo:hi])
            mask = np.ones(hi - lo, dtype=bool)
            mask[kept] = False
            block[mask] = array.fill_value
        else:
            block = np.full((hi - lo, *array.shape[1:]), array.fill_value, dtype=array.dtype)
        for row, output in zip(rows, outputs, strict=True):
            block[row] = (
                output.reduced_mass_kg if name == "reduced_mass_kg" else output.arrays[name]
            )
        array[lo:hi] = block
    for row, output in zip(rows, outputs, strict=True):
        texts[row] = json.dumps(
            {
                "attempt": output.attempt,
                "modes": [
                    [mode, float(hz)]
                    for mode, hz in zip(output.mode_names, output.mode_frequency_hz, strict=True)
                ],
            }
        )
    records[lo:hi] = texts  # last: the designs are done from here on


def clear_rows(out: Path, sha256: str, indices: Sequence[int]) -> None:
    """Set designs' rows to the fill values (NaN, status 3) and clear their records: a design
    that failed for good never shows numbers left by an earlier attempt."""
    if not indices:
        return
    group = _open_group(store_path(out), sha256)
    size = int(_array(group, "status").chunks[0])
    by_chunk: dict[int, list[int]] = {}
    for index in indices:
        by_chunk.setdefault(index // size, []).append(index)
    files_of = {c: _chunk_keys(group, store_path(out), c) for c in by_chunk}
    records = _writable(group, f"{RECORDS}/design")
    for chunk, rows in by_chunk.items():
        if not any(f.is_file() for f in files_of[chunk]):
            continue  # never written: fill values already
        for name in (RECORDS, *_chunked_names(group)):
            array = records if name == RECORDS else _writable(group, name)
            lo, hi = chunk * size, min((chunk + 1) * size, array.shape[0])
            block = np.asarray(array[lo:hi], dtype=object if name == RECORDS else array.dtype)
            block[[r - lo for r in rows]] = array.fill_value
            array[lo:hi] = block


# --- finishing --------------------------------------------------------------------------------
def write_modes(out: Path, spec: SweepSpec, records: Sequence[dict[str, Any] | None]) -> None:
    """``mode_frequency_hz`` over ``(design, mode)`` and the ``mode`` coordinate, from the
    designs' records (modes named in design order; NaN where a design lacks a mode)."""
    group = _open_group(store_path(out), spec.sha256)
    for name in ("mode_frequency_hz", "mode"):
        if name in group:
            del group[name]
    names: list[str] = []
    for record in records:
        for mode, _ in (record or {}).get("modes", []):
            if mode not in names:
                names.append(mode)
    if not names:
        return
    frequency = np.full((len(records), len(names)), np.nan)
    for index, record in enumerate(records):
        for mode, hz in (record or {}).get("modes", []):
            frequency[index, names.index(mode)] = hz
    modes = group.create_array(
        "mode", shape=(len(names),), dtype=str, fill_value="", dimension_names=("mode",)
    )
    modes[:] = np.array(names, dtype=object)
    group.create_array(
        "mode_frequency_hz",
        data=frequency,
        dimension_names=("design", "mode"),
        attributes={"units": "Hz", "long_name": "natural frequency of the modes charged"},
    )


def design_blocks(n_designs: int, size: int) -> Iterator[slice]:
    for start in range(0, n_designs, max(1, size)):
        yield slice(start, min(start + size, n_designs))


def status_counts(out: Path, sha256: str) -> dict[str, int]:
    """Impacts per status text, counted chunk by chunk."""
    group = _open_group(store_path(out), sha256, "r")
    status = _array(group, "status")
    counts = np.zeros(256, dtype=np.int64)
    for block in design_blocks(int(status.shape[0]), int(status.chunks[0])):
        values = np.asarray(status[block]).astype(np.int64).ravel()
        counts += np.bincount(values % 256, minlength=256)
    return {text: int(counts[code]) for text, code in STATUS_CODES.items()}


def failure_attrs(failures: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """The dataset's ``n_failed`` and ``failed_tasks`` attributes."""
    return {
        "n_failed": len(failures),
        "failed_tasks": json.dumps(
            [{k: f[k] for k in ("task_id", "design", "error")} for f in failures]
        ),
    }


# --- reading ----------------------------------------------------------------------------------
def open_sweep(path: str | Path, chunks: Mapping[str, int] | None = None) -> xr.Dataset:
    """A sweep's results, read lazily from its store.

    Parameters
    ----------
    path : path
        The sweep's output folder or its ``sweep.zarr``.
    chunks : mapping, optional
        Dask chunks (``{}``: the store's, one per design batch; needs Dask); default: xarray's
        lazy arrays without Dask — nothing is read until indexed, and only the chunks needed.

    Returns
    -------
    xarray.Dataset
        Impact quantities over ``(design, point, speed, racket_speed, support)``,
        ``reduced_mass_kg``, ``mode_frequency_hz``, design coordinates and the spec in the
        attributes (docs/sweep-file.md).

    Raises
    ------
    InputError
        No sweep store there, or one whose run has not finished (interrupted, still running):
        its results are incomplete; run the sweep again to finish it.
    """
    import xarray as xr

    store = Path(path)
    if store.name != STORE_NAME and (store / STORE_NAME).is_dir():
        store = store / STORE_NAME
    if not (store / "zarr.json").is_file():
        raise InputError(f"`path` {path}: no sweep store ({STORE_NAME}) there")
    dataset = xr.open_dataset(
        store,
        engine="zarr",
        chunks=chunks,
        consolidated=False,
        cache=False,
        zarr_format=3,
    )
    if dataset.attrs.get("format") != SWEEP_FORMAT or not dataset.attrs.get("sweep_complete"):
        dataset.close()
        raise InputError(
            f"`path` {store}: the sweep's run has not finished (interrupted, or still running); "
            "run the same sweep again to finish it"
        )
    return dataset
