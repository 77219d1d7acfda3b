"""Universal Files (UFF) and plain CSV files of roving-hammer tests: time records and FRFs.

A roving-hammer test strikes each point of a grid several times and records the hammer force
and the response of one fixed transducer (the reference).  This module reads and writes those
records as :class:`~racketdyn.measurement.records.HammerRecords` and the FRFs estimated from
them as :class:`~racketdyn.measurement.records.FrfSet`, through pyuff.

What is read and written (see ``docs/uff-and-csv.md`` for the full description):

- data set 15 or 2411: node coordinates (x along the racket from the butt, y across, m; z is
  ignored); data set 164: the file's units, applied when it says non-SI;
- data set 58 (ASCII) or 58b (binary), function type 1: time records, a force record
  (ordinate type 13 at the hammer node) and a response record (ordinate type 8, 11 or 12 at the
  reference node, its reference node the hammer node) per average, the load case being the
  average number;
- data set 58, function type 4: one FRF per hammer point, response node = the reference
  transducer, reference (excitation) node = the hammer point; function type 6: coherence.

Data sets are counted from 1 in the order of the file in every message.
"""

from __future__ import annotations

import contextlib
import dataclasses
import datetime
import io
import logging
import math
import os
import re
import tempfile
import warnings
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, cast

import numpy as np
import pyuff  # type: ignore[import-untyped]
from numpy.typing import NDArray

from racketdyn.__about__ import __version__
from racketdyn._grammar import noun, plural
from racketdyn.errors import InputError, logs_warnings, warnings_logged
from racketdyn.io.tables import split_csv_line
from racketdyn.io.uff_structure import check_structure
from racketdyn.measurement.records import (
    ABSURD_FORCE_N,
    ABSURD_RESPONSE,
    FRF_TYPE_OF_RESPONSE,
    RESPONSE_TYPES,
    FrfSet,
    HammerRecords,
    ResponseType,
)
from racketdyn.modal.model import ModalModel

__all__ = [
    "read_hammer_csv",
    "read_hammer_uff",
    "write_frf_uff",
    "write_hammer_csv",
    "write_hammer_uff",
]

logger = logging.getLogger(__name__)

#: Function types of data set 58 (record 6, field 1).
TIME_RESPONSE, FREQUENCY_RESPONSE, COHERENCE = 1, 4, 6
#: Specific data types of data set 58 (records 8–11, field 1).
QUANTITY_CODE: dict[str, int] = {
    "displacement": 8,
    "velocity": 11,
    "acceleration": 12,
    "force": 13,
    "time": 17,
    "frequency": 18,
}
RESPONSE_OF_CODE: dict[int, ResponseType] = {8: "displacement", 11: "velocity", 12: "acceleration"}
#: Direction written for every record: +Z, normal to the string bed.
DIRECTION = 3
SI_LABEL: dict[str, str] = {
    "displacement": "m",
    "velocity": "m/s",
    "acceleration": "m/s^2",
    "force": "N",
    "time": "s",
    "frequency": "Hz",
}
#: Units labels understood in records 8–10 (lower case, spaces removed), as factors to SI.
UNIT_SCALE: dict[str, dict[str, float]] = {
    "displacement": {"m": 1.0, "mm": 1e-3, "um": 1e-6, "in": 0.0254},
    "velocity": {"m/s": 1.0, "mm/s": 1e-3, "in/s": 0.0254},
    "acceleration": {"m/s^2": 1.0, "mm/s^2": 1e-3, "g": 9.80665, "in/s^2": 0.0254},
    "force": {"n": 1.0, "kn": 1e3, "mn": 1e-3, "lbf": 4.4482216152605},
    "time": {"s": 1.0, "sec": 1.0, "ms": 1e-3},
    "frequency": {"hz": 1.0, "1/s": 1.0},
}
_ABSCISSA_LINE = re.compile(r"racketdyn abscissa start (\S+) step (\S+)")
_FRF_LINE = re.compile(r"estimator (\S+); exponential window tau (\S+) s; averages (\S+)")
_BANDWIDTH = re.compile(r"; bandwidth (\S+) Hz")
_FORCE_BAND = re.compile(r"; force band (\S+) Hz")


# --------------------------------------------------------------------------------------------
# Reading: data sets → checked records
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Units:
    """Factors of data set 164: file value / factor = SI value (1 when absent or SI)."""

    length: float = 1.0
    force: float = 1.0


@dataclass(frozen=True)
class _Record:
    """One data set 58, checked and with its abscissa rebuilt (exactly if racketdyn wrote it)."""

    index: int
    func_type: int
    rsp_node: int
    rsp_dir: int
    ref_node: int
    ref_dir: int
    load_case: int
    quantity: int
    denominator: int
    labels: tuple[str, str, str]
    x: NDArray[np.float64]
    step: float
    even: bool
    data: NDArray[Any]
    ids: tuple[str, ...]
    nyquist_nan: bool = False  # a spectrum whose last line alone is NaN or infinite

    def where(self, path: Path) -> str:
        """The start of a message about this record."""
        return (
            f"{path}: data set {self.index} (58, function type {self.func_type}, "
            f"response node {self.rsp_node}, reference node {self.ref_node}, "
            f"load case {self.load_case})"
        )


@dataclass(frozen=True)
class _Contents:
    records: list[_Record]
    nodes: dict[int, tuple[float, float]]
    units: _Units
    types: list[int]
    depth: dict[int, float] = dataclasses.field(default_factory=dict)  # z of each node, m


def _as_int(value: Any, default: int = 0) -> int:
    try:
        return int(value)
    except (TypeError, ValueError):
        return default


@contextlib.contextmanager
def _quiet_pyuff() -> Iterator[None]:
    """Keep pyuff's prints (it prints the layouts of some data sets) and warnings (its own and
    numpy's while it parses a damaged file) off the console; logged."""
    captured = io.StringIO()
    with contextlib.redirect_stdout(captured), warnings_logged(logger, "pyuff"):
        yield
    if captured.getvalue():
        logger.debug("pyuff printed: %s", captured.getvalue())


_COMPRESSED = (
    (b"\xfd7zXZ\x00", "xz", "unxz"),
    (b"\x1f\x8b", "gzip", "gunzip"),
    (b"BZh", "bzip2", "bunzip2"),
    (b"PK\x03\x04", "zip", "unzip"),
)
"""Magic numbers of compressed files a lab may hand over, their names and a tool that opens them."""


def _read_sets(path: Path) -> list[dict[str, Any]]:
    """All data sets of a Universal File as pyuff dictionaries; InputError on anything wrong."""
    if not path.exists():
        raise InputError(f"{path}: no such file")
    if path.is_dir():
        raise InputError(f"{path}: is a folder; give a Universal File (.uff or .unv)")
    try:
        raw = path.read_bytes()
    except OSError as error:
        raise InputError(f"{path}: cannot be read ({error.strerror})") from None
    if not raw.strip():
        raise InputError(f"{path}: empty; expected a Universal File of data sets 15 and 58")
    for magic, kind, tool in _COMPRESSED:
        if raw.startswith(magic):
            raise InputError(
                f"{path}: compressed ({kind}), not a Universal File; decompress it first "
                f"({tool} {path.name})"
            )
    blocks = check_structure(path, raw)
    if not blocks:
        raise InputError(
            f"{path}: not a Universal File (no data sets between '    -1' lines); export the "
            "test as UFF data sets 15 and 58"
        )
    sets = []
    with _quiet_pyuff():
        try:  # pyuff raises bare Exception for every failure
            uff = pyuff.UFF(str(path))
            n_sets = int(uff.get_n_sets())
        except Exception:
            raise InputError(f"{path}: cannot be read as a Universal File") from None
        if n_sets != len(blocks):  # the structure check follows pyuff's rule: never expected
            raise InputError(
                f"{path}: pyuff finds {n_sets} data sets where the file holds {len(blocks)}; "
                "export the file again"
            )
        for block in blocks:
            i = block.number - 1
            try:  # read one set at a time: pyuff's read_sets() names no set when one fails
                dset = uff.read_sets(i)
            except Exception:
                raise InputError(
                    f"{path}: data set {block.number} of {n_sets} ({block.type}, line "
                    f"{block.line}) cannot be read (damaged); export the file again"
                ) from None
            sets.append(cast(dict[str, Any], dset))
    _check_complete(path, sets)
    return sets


#: Largest plausible extent of a hammer-tested structure's nodes, m (a racket is 0.7 m; a
#: car body or a machine frame a few metres).  Coordinates beyond it were written in another
#: unit without a data set 164 (680 mm read as 680 m, a 60 in wing as 60 m) and are refused
#: with what they would be in mm and in inches (:func:`_unit_guess`).
MAX_EXTENT_M = 20.0
#: Smallest extent of a structure a roving-hammer test covers with its points, m (a blade, a
#: racket's throat).  A span that would be smaller in one length unit is not called likely in it.
MIN_EXTENT_M = 0.1
#: Length units a geometry written without data set 164 is likely in: name → metres per unit.
LIKELY_UNITS = {"mm": 1.0e-3, "inches": 0.0254}


def _unit_guess(extent: float) -> str:
    """What a span of ``extent`` units (too large for metres) would be in mm and in inches,
    and the likely one where only one of them gives a structure's size
    (:data:`MIN_EXTENT_M`–:data:`MAX_EXTENT_M`): ``"0.06 m if in mm, 1.52 m if in inches
    (likely inches: …)"``."""
    sizes = {unit: extent * factor for unit, factor in LIKELY_UNITS.items()}
    readings = ", ".join(f"{size:.3g} m if in {unit}" for unit, size in sizes.items())
    fits = [unit for unit, size in sizes.items() if MIN_EXTENT_M <= size <= MAX_EXTENT_M]
    if len(fits) != 1:
        return readings
    others = ", ".join(
        f"{size:.3g} m {'smaller' if size < MIN_EXTENT_M else 'larger'} than a hammer test's "
        "structures"
        for unit, size in sizes.items()
        if unit != fits[0]
    )
    return f"{readings} (likely {fits[0]}: {others})"


def _units_of(path: Path, sets: Sequence[dict[str, Any]]) -> _Units:
    """Units of the first data set 164, if it says non-SI; SI otherwise."""
    for i, dset in enumerate(sets, start=1):
        if dset.get("type") != 164:
            continue
        if _as_int(dset.get("units_code"), 1) == 1:
            return _Units()
        length, force = dset.get("length"), dset.get("force")
        if not all(isinstance(v, float) and math.isfinite(v) and v > 0 for v in (length, force)):
            raise InputError(
                f"{path}: data set {i} (164, units): the length and force factors must be "
                f"positive numbers (got {length!r}, {force!r})"
            )
        return _Units(length=cast(float, length), force=cast(float, force))
    return _Units()


#: ``_System.kind`` of a system defined in another one or by points on one line.
_UNUSABLE_SYSTEM = -1
_SYSTEM_KIND = {_UNUSABLE_SYSTEM: "defined in another system or by points on one line"}


def _system_problem(kind: int) -> str:
    """Why a coordinate system cannot be used (its kind is not cartesian)."""
    return _SYSTEM_KIND.get(kind, "not cartesian")


@dataclass(frozen=True)
class _System:
    """A coordinate system of data set 18: origin (m) and axes (columns x, y, z), global."""

    kind: int  # 0 cartesian, 1 cylindrical, 2 spherical, _UNUSABLE_SYSTEM
    origin: NDArray[np.float64]
    axes: NDArray[np.float64]


def _systems_of(path: Path, sets: Sequence[dict[str, Any]], units: _Units) -> dict[int, _System]:
    """Coordinate systems of data sets 18, defined in the global system (reference 0).

    Record 3 gives the origin and a point on the +x axis, record 4 a point in the x–z plane
    (on the +z side): x = (x point − origin), y = (x–z point − origin) × x, z = x × y.
    """
    systems: dict[int, _System] = {}
    for i, dset in enumerate(sets, start=1):
        if dset.get("type") != 18:
            continue
        numbers = np.atleast_1d(np.asarray(dset.get("cs_num", []), dtype=float))
        kinds = np.atleast_1d(np.asarray(dset.get("cs_type", []), dtype=float))
        references = np.atleast_1d(np.asarray(dset.get("ref_cs_num", []), dtype=float))
        points = [
            np.asarray(dset.get(key, []), dtype=float).reshape(-1, 3) / units.length
            for key in ("ref_o", "x_point", "xz_point")
        ]
        for k, number in enumerate(numbers):
            origin, on_x, in_xz = (p[k] for p in points)
            x = on_x - origin
            y = np.cross(in_xz - origin, x)
            if references[k] != 0 or not (
                np.linalg.norm(x) > 0 and np.linalg.norm(y) > 1e-12 * np.linalg.norm(x) ** 2
            ):  # unusable: refused only where a node uses it
                logger.info(
                    "%s: data set %d (18): system %d is defined in another system or by points "
                    "on one line",
                    path,
                    i,
                    int(number),
                )
                systems[int(number)] = _System(_UNUSABLE_SYSTEM, origin, np.eye(3))
                continue
            x, y = x / np.linalg.norm(x), y / np.linalg.norm(y)
            axes = np.column_stack([x, y, np.cross(x, y)])
            systems[int(number)] = _System(int(kinds[k]), origin, axes)
    return systems


def _nodes_xyz_of(
    path: Path, sets: Sequence[dict[str, Any]], units: _Units
) -> tuple[dict[int, tuple[float, float, float]], dict[int, _System]]:
    """Node coordinates (x, y, z) in m from data sets 15 and 2411, their extent checked, and
    the coordinate system of data set 18 that each node's measurement directions are in.

    Coordinates given in a system of data set 18 (field 2, definition system) are taken to the
    global system; a system number no data set 18 defines is taken as the global system.
    """
    nodes: dict[int, tuple[float, float, float]] = {}
    where: dict[int, str] = {}  # the data set defining each node
    frames: dict[int, _System] = {}
    systems = _systems_of(path, sets, units)
    for i, dset in enumerate(sets, start=1):
        if dset.get("type") not in (15, 2411):
            continue
        numbers = np.asarray(dset.get("node_nums", []), dtype=float)
        x = np.asarray(dset.get("x", []), dtype=float) / units.length
        y = np.asarray(dset.get("y", []), dtype=float) / units.length
        z = np.asarray(dset.get("z", np.zeros_like(x)), dtype=float) / units.length
        if not (numbers.size == x.size == y.size == z.size) or not np.all(
            np.isfinite(np.r_[numbers, x, y, z])
        ):
            raise InputError(
                f"{path}: data set {i} ({dset['type']}, nodes): every node needs a finite node "
                "number and finite x, y, z coordinates"
            )
        defined = np.asarray(dset.get("def_cs", np.zeros_like(x)), dtype=float).ravel()
        displaced = np.asarray(dset.get("disp_cs", np.zeros_like(x)), dtype=float).ravel()
        for k in range(x.size):
            system = systems.get(int(defined[k])) if defined.size == x.size else None
            if system is None:
                continue
            if system.kind != 0:
                raise InputError(
                    f"{path}: data set {i} ({dset['type']}, nodes): node {int(numbers[k])} is "
                    f"given in system {int(defined[k])}, which is "
                    f"{_system_problem(system.kind)} (data set 18); give the coordinates in a "
                    "cartesian system defined in the global one"
                )
            x[k], y[k], z[k] = system.origin + system.axes @ np.array([x[k], y[k], z[k]])
        if displaced.size == x.size:
            for number, code in zip(numbers, displaced, strict=True):
                if int(code) in systems:
                    frames[int(number)] = systems[int(code)]
        extent = float(np.max(np.ptp(np.c_[x, y, z], axis=0))) if x.size else 0.0
        if extent > MAX_EXTENT_M and units.length != 1.0:
            raise InputError(
                f"{path}: data set {i} ({dset['type']}, nodes): the nodes span {extent:.3g} m "
                f"in data set 164's length unit, more than the {MAX_EXTENT_M:g} m of any "
                "structure tested with a hammer; check data set 164, or give the coordinates "
                "in m in a file given as `geometry`"
            )
        if extent > MAX_EXTENT_M:
            raise InputError(
                f"{path}: data set {i} ({dset['type']}, nodes): the nodes span {extent:.4g} "
                f"units, more than the {MAX_EXTENT_M:g} m of any structure tested with a "
                f"hammer if they were m: {_unit_guess(extent)}; add a data set 164 giving the "
                "length unit, or give the coordinates in m with `geometry`"
            )
        for number, xi, yi, zi in zip(numbers, x, y, z, strict=True):
            _define(path, nodes, where, int(number), (float(xi), float(yi), float(zi)), i, dset)
    return nodes, frames


def _define(
    path: Path,
    nodes: dict[int, tuple[float, float, float]],
    where: dict[int, str],
    number: int,
    xyz: tuple[float, float, float],
    index: int,
    dset: dict[str, Any],
) -> None:
    """Node ``number`` at ``xyz`` (m) in ``nodes``: a node defined again at the same place is
    read once (logged), at another place refused naming both (the later one silently won)."""
    here = f"data set {index} ({dset['type']})"
    if number in nodes:
        before = nodes[number]
        if not np.allclose(xyz, before, rtol=1e-6, atol=1e-9):
            raise InputError(
                f"{path}: node {number} is defined twice: at ({_xyz(before)}) m in "
                f"{where[number]} and at ({_xyz(xyz)}) m in {here}; keep one definition per "
                "node and export the geometry again"
            )
        logger.info(
            "%s: node %d is defined twice at the same place (%s and %s); read once",
            path,
            number,
            where[number],
            here,
        )
        return
    nodes[number] = xyz
    where[number] = here


def _xyz(xyz: tuple[float, float, float]) -> str:
    return ", ".join(f"{v:.6g}" for v in xyz)


def _global_direction(path: Path, record: _Record, node: int, code: int, frame: _System) -> int:
    """The global direction code (±1, ±2, ±3) of ``code`` measured in a node's own system."""
    if code == 0 or abs(code) > 3:
        return code  # scalar; rotations are refused by _sign
    if frame.kind != 0:
        raise InputError(
            f"{record.where(path)}: node {node} measures in a coordinate system that is "
            f"{_system_problem(frame.kind)} (data set 18); give its directions in a cartesian "
            "system defined in the global one"
        )
    vector = np.sign(code) * frame.axes[:, abs(code) - 1]
    axis = int(np.argmax(np.abs(vector)))
    if abs(vector[axis]) < 1 - 1e-6:
        raise InputError(
            f"{record.where(path)}: direction {code} at node {node} is in the node's own "
            "coordinate system (data set 18), which points it obliquely to the global axes; "
            "racketdyn reads directions along the global axes: export in global directions"
        )
    return (axis + 1) * (1 if vector[axis] > 0 else -1)


def _in_global_axes(
    path: Path, records: list[_Record], frames: dict[int, _System]
) -> list[_Record]:
    """Records whose direction codes are those of their nodes' own systems, made global.

    LMS Test.Lab gives every node a displacement coordinate system (data set 15, field 3;
    data set 18): direction +3 at a node whose system is turned over is global −Z.
    """
    out = []
    changed = 0
    for record in records:
        rsp_dir, ref_dir = record.rsp_dir, record.ref_dir
        if record.rsp_node in frames:
            rsp_dir = _global_direction(
                path, record, record.rsp_node, rsp_dir, frames[record.rsp_node]
            )
        if record.ref_node in frames:
            ref_dir = _global_direction(
                path, record, record.ref_node, ref_dir, frames[record.ref_node]
            )
        if (rsp_dir, ref_dir) != (record.rsp_dir, record.ref_dir):
            changed += 1
            record = dataclasses.replace(record, rsp_dir=rsp_dir, ref_dir=ref_dir)
        out.append(record)
    if changed:
        logger.info(
            "%s: the directions of %d records taken from their nodes' coordinate systems "
            "(data set 18) to the global axes",
            path,
            changed,
        )
    return out


def _locations(
    coordinates: dict[int, tuple[float, float, float]], nodes: list[int], ref: int
) -> tuple[NDArray[np.float64], tuple[float, ...]]:
    """The points' and the reference's locations: (x, y, z), or (x, y) when all share one z."""
    xyz = np.asarray([coordinates[n] for n in nodes], dtype=float)
    reference_xyz = np.asarray(coordinates.get(ref, (np.nan,) * 3), dtype=float)
    z = np.r_[xyz[:, 2], reference_xyz[2]]
    three_d = bool(np.nanmax(z) > np.nanmin(z)) if np.isfinite(z).any() else False
    locations = xyz if three_d else xyz[:, :2]
    reference = tuple(float(v) for v in (reference_xyz if three_d else reference_xyz[:2]))
    return locations, reference


def _normal_label(label: Any) -> str | None:
    """A units label in lower case without spaces, or None where the record gives none."""
    text = str(label or "").strip().lower().replace(" ", "")
    text = text.replace("²", "^2").replace("**", "^").replace("µ", "u").replace("μ", "u")
    # a Latin-1 "²" (byte 0xB2) that pyuff decodes as U+FFFD: after "/s" it can be nothing else
    text = text.replace("/s\ufffd", "/s^2")
    if text.endswith("s2") and not text.endswith("^2") and "/" in text:
        text = text[:-1] + "^2"
    return None if text in ("", "none") else text


def _scale(path: Path, record: _Record, quantity: str, label: str | None, units: _Units) -> float:
    """Factor taking a value of ``quantity`` with units ``label`` to SI."""
    if label is None:
        length = {"displacement": 1, "velocity": 1, "acceleration": 1}.get(quantity, 0)
        force = 1 if quantity == "force" else 0
        return 1.0 / (units.length**length * units.force**force)
    known = UNIT_SCALE[quantity]
    if label in known:
        return known[label]
    raise InputError(
        f"{record.where(path)}: units label {label!r} of the {quantity} is not one racketdyn "
        f"knows ({', '.join(known)}); export in SI ({SI_LABEL[quantity]}) or with one of these"
    )


def _frf_scale(path: Path, record: _Record, response: str, units: _Units) -> float:
    """Factor taking an FRF (response per force, or per the same response) to SI, from the
    labels of records 9 and 10."""
    numerator, denominator = _normal_label(record.labels[1]), _normal_label(record.labels[2])
    if numerator is not None and numerator not in UNIT_SCALE[response] and "/" in numerator:
        top, bottom = numerator.rsplit("/", 1)
        top = top.strip("()")
        if top in UNIT_SCALE[response] and bottom in UNIT_SCALE["force"]:
            return UNIT_SCALE[response][top] / UNIT_SCALE["force"][bottom]
    # a transmissibility's denominator is the same response's (io.frf_layout._transmissibility)
    per = response if record.denominator == record.quantity else "force"
    return _scale(path, record, response, numerator, units) / _scale(
        path, record, per, denominator, units
    )


def _sign(path: Path, record: _Record, direction: int) -> float:
    """+1 or −1 for a translational direction code (0, scalar, counts as +)."""
    if abs(direction) > 3:
        raise InputError(
            f"{record.where(path)}: direction {direction} is a rotation; racketdyn reads "
            "translations (±1, ±2, ±3) only"
        )
    return -1.0 if direction < 0 else 1.0


def _in_si(
    path: Path,
    record: _Record,
    scale: float,
    what: str,
    limit: float,
    unit: str,
    top: float | None = None,
) -> NDArray[Any]:
    """A record's values times ``scale`` (to SI units, with its direction's sign), refused
    naming the data set where one overflows or lies beyond ``limit``: a damaged number
    (1e300 for 1.2) or a wrong units label.  Lines above ``top`` (the analyser's roll-off
    above the bandwidth racketdyn's own FRFs record) and a spectrum's NaN Nyquist line (which
    the FRF reader drops) are left as they are."""
    with np.errstate(over="ignore", invalid="ignore"):
        values = np.asarray(record.data * scale)
    checked = values.copy()
    if record.nyquist_nan:
        checked[-1] = 0.0
    if top is not None:
        checked[record.x > top] = 0.0
    magnitude = np.abs(checked)
    bad = ~np.isfinite(magnitude) | (magnitude > limit)
    if np.any(bad):
        k = int(np.argmax(bad))
        labels = [text.strip() for text in record.labels[1:]]
        labelled = "/".join(text for text in labels if text and text.upper() != "NONE")
        found = f"{abs(record.data[k]):.3g}{' ' + labelled if labelled else ''}"
        in_si = f" {unit}" if unit else ""
        sample = "sample" if record.func_type == TIME_RESPONSE else "line"
        value = (
            f"{magnitude[k]:.3g}{in_si}, beyond the {limit:g}{in_si} of any measurement"
            if np.isfinite(magnitude[k])
            else f"beyond the largest floating-point number in{in_si or ' SI units'}"
        )
        raise InputError(
            f"{record.where(path)}: {what} {sample} {k + 1} reads {found}, which is {value}: "
            "the data set is damaged or its units label wrong; export it again"
        )
    return values


def _abscissa(dset: dict[str, Any]) -> tuple[NDArray[np.float64], float, bool]:
    """Abscissa, its step and whether it is even, exact where racketdyn's ID line 5 holds them.

    The header holds the start and step with 6 significant digits (E13.5, as the format
    prescribes); racketdyn writes both exactly in ID line 5 and takes them back when they agree
    with the header.
    """
    x = np.asarray(dset.get("x"), dtype=float)
    even = _as_int(dset.get("abscissa_spacing")) == 1
    step = float((x[-1] - x[0]) / (x.size - 1)) if x.size > 1 else math.nan
    if not even:
        return x, step, even
    header_start = float(dset.get("abscissa_min", math.nan))
    header_step = float(dset.get("abscissa_inc", math.nan))
    match = _ABSCISSA_LINE.search(str(dset.get("id5", "")))
    if match and x.size:
        try:
            start, exact = float(match.group(1)), float(match.group(2))
        except ValueError:
            return x, header_step, even
        if not (math.isfinite(start) and math.isfinite(exact)):  # damaged: the header's step
            return x, header_step, even
        if abs(exact - header_step) <= 1e-5 * abs(exact) and abs(start - header_start) <= 1e-5 * (
            abs(start) + abs(exact)
        ):
            return np.asarray(start + np.arange(x.size) * exact), exact, even
    snapped = _round_step(
        header_start, header_step, x.size, _as_int(dset.get("abscissa_spec_data_type"))
    )
    if snapped is not None:
        return np.asarray(header_start + np.arange(x.size) * snapped), snapped, even
    return x, header_step, even


#: Significant digits of a "round" band top or sampling rate (1000 Hz, 51 200 Hz, 12.8 kHz).
ROUND_DIGITS = 4


def _round_step(start: float, step: float, n: int, kind: int) -> float | None:
    """The exact step behind a 6-digit header step, where the axis ends on a round number.

    The header holds the step with 6 significant digits (E13.5): 1.953125 Hz is written
    1.95312, and 512 of them end at 999.997 Hz instead of 1000.  A frequency axis from 0 whose
    top, within the header's rounding (±5e-6 of the step per line), is a number of at most
    :data:`ROUND_DIGITS` significant digits gets the step that ends exactly there; a time axis
    gets the step of a round sampling rate.  None where no such number lies within reach.
    """
    if not (math.isfinite(step) and step > 0 and n > 1):
        return None
    if kind == QUANTITY_CODE["time"]:
        rate = 1.0 / step
        for digits in range(1, ROUND_DIGITS + 1):
            candidate = float(f"{rate:.{digits - 1}e}")
            if abs(candidate - rate) <= 5e-6 * rate and f"{1 / candidate:.5e}" == f"{step:.5e}":
                return 1.0 / candidate
        return None
    if start != 0.0:
        return None
    top = (n - 1) * step
    for digits in range(1, ROUND_DIGITS + 1):
        candidate = float(f"{top:.{digits - 1}e}")
        if abs(candidate - top) <= 5e-6 * top:
            exact = candidate / (n - 1)
            return exact if f"{exact:.5e}" == f"{step:.5e}" else None
    return None


#: Ordinate types that say nothing of the quantity (0 unknown, 1 general): the units label
#: then tells it (HBM catman's time records, FRFs labelled "(1/N)*(m/s²)").
_GENERAL_QUANTITY = (0, 1)


def _quantity_of_label(label: str | None) -> int | None:
    """The ordinate type a units label names unambiguously (force or a response), else None."""
    if label is None:
        return None
    found = [
        QUANTITY_CODE[quantity]
        for quantity in ("force", *RESPONSE_OF_CODE.values())
        if label in UNIT_SCALE[quantity]
    ]
    return found[0] if len(found) == 1 else None


def _split_frf_label(label: str | None) -> tuple[str, str] | None:
    """(response, force) labels of an FRF's one label: "m/s^2/n", "(m/s^2)/(n)", "(1/n)*(m/s^2)"."""
    if label is None:
        return None
    text = label.replace(" ", "")
    for prefix in ("(1/", "1/"):
        if text.startswith(prefix) and "*" in text:
            force, response = text[len(prefix) :].split("*", 1)
            return response.strip("()"), force.strip("()")
    if "/" in text:
        response, force = text.rsplit("/", 1)
        return response.strip("()"), force.strip("()")
    return None


def _with_quantity_from_label(record: _Record) -> _Record:
    """A record of ordinate type 0/1 given the quantity its units label names, if it names one.

    Time records: the label itself ("N", "m/s^2").  FRFs: a response label over a force label
    in records 9 and 10, or both in record 9 ("(1/N)*(m/s^2)", "m/s^2/N"), which become the
    two labels.  Anything else is left as it is (and refused where a quantity is needed).
    """
    if record.quantity not in _GENERAL_QUANTITY:
        return record
    numerator = _normal_label(record.labels[1])
    denominator = _normal_label(record.labels[2])
    if record.func_type == TIME_RESPONSE:
        code = _quantity_of_label(numerator)
        return record if code is None else dataclasses.replace(record, quantity=code)
    if denominator is None:
        split = _split_frf_label(numerator)
        if split is None:
            return record
        numerator, denominator = split
    code = _quantity_of_label(numerator)
    if code is None or code == QUANTITY_CODE["force"]:
        return record
    if _quantity_of_label(denominator) != QUANTITY_CODE["force"]:
        return record
    labels = (record.labels[0], numerator or "", denominator or "")
    return dataclasses.replace(
        record, quantity=code, denominator=QUANTITY_CODE["force"], labels=labels
    )


def _record_of(path: Path, index: int, dset: dict[str, Any]) -> _Record:
    data = np.asarray(dset.get("data"))
    x, step, even = _abscissa(dset)
    record = _Record(
        index=index,
        func_type=_as_int(dset.get("func_type")),
        rsp_node=_as_int(dset.get("rsp_node")),
        rsp_dir=_as_int(dset.get("rsp_dir")),
        ref_node=_as_int(dset.get("ref_node")),
        ref_dir=_as_int(dset.get("ref_dir")),
        load_case=_as_int(dset.get("load_case_id")),
        quantity=_as_int(dset.get("ordinate_spec_data_type")),
        denominator=_as_int(dset.get("orddenom_spec_data_type")),
        labels=(
            str(dset.get("abscissa_axis_units_lab", "")),
            str(dset.get("ordinate_axis_units_lab", "")),
            str(dset.get("orddenom_axis_units_lab", "")),
        ),
        x=x,
        step=step,
        even=even,
        data=data,
        ids=tuple(str(dset.get(f"id{k}", "")) for k in range(1, 6)),
    )
    labelled = _with_quantity_from_label(record)
    if labelled is not record:
        logger.info(
            "%s: ordinate type %d (general) read as %d from the units label %r",
            record.where(path),
            record.quantity,
            labelled.quantity,
            record.labels[1],
        )
        record = labelled
    n_header = _as_int(dset.get("num_pts"), -1)
    if data.ndim != 1 or data.size != n_header or x.size != data.size:
        raise InputError(
            f"{record.where(path)}: holds {data.size} values but its header says {n_header} "
            "(truncated or damaged file); export the file again"
        )
    if data.size < 2:
        raise InputError(f"{record.where(path)}: a record needs two values or more")
    if not np.all(np.isfinite(x)) or (x.size > 1 and np.any(np.diff(x) <= 0)):
        raise InputError(f"{record.where(path)}: the abscissa must rise strictly")
    bad = ~np.isfinite(data)
    if np.any(bad):
        if record.func_type != TIME_RESPONSE and bad[-1] and not np.any(bad[:-1]):
            # a spectrum's last line is its Nyquist line, which some exports (OpenModal)
            # write as NaN: the readers of spectra drop it (and say so)
            return dataclasses.replace(record, nyquist_nan=True)
        first, count = int(np.argmax(bad)), int(bad.sum())
        what = "sample" if record.func_type == TIME_RESPONSE else "line"
        raise InputError(
            f"{record.where(path)}: {plural(count, 'value')} {noun(count, 'is', 'are')} NaN or "
            f"infinite (the first at {what} {first + 1} of {data.size}, abscissa "
            f"{x[first]:g}); re-export the record or leave it out"
        )
    return record


def _coordinates(
    path: Path, sets: Sequence[dict[str, Any]], units: _Units, geometry: Path | str | None
) -> tuple[dict[int, tuple[float, float, float]], dict[int, _System]]:
    """Node coordinates (x, y, z), m, of a file and of a separate geometry file (which wins):
    a Universal File (data set 15 or 2411) or a CSV ``node,x_m,y_m``; and the coordinate
    system each node's directions are measured in (a CSV gives positions only: the file's
    systems stay)."""
    nodes, frames = _nodes_xyz_of(path, sets, units)
    if geometry is not None:
        geometry = Path(geometry)
        found_frames: dict[int, _System] | None = None
        if geometry.suffix.lower() == ".csv":  # node,x_m,y_m: face coordinates, m
            found = {n: (x, y, 0.0) for n, (x, y) in _read_geometry_csv(geometry).items()}
        else:
            geometry_sets = _read_sets(geometry)
            found, found_frames = _nodes_xyz_of(
                geometry, geometry_sets, _units_of(geometry, geometry_sets)
            )
        if not found:
            raise InputError(
                f"{geometry}: no node coordinates (data set 15 or 2411); give a geometry file "
                "that lists the nodes"
            )
        nodes.update(found)
        if found_frames is not None:
            frames = {n: f for n, f in frames.items() if n not in found} | found_frames
    return nodes, frames


def _load(path: Path, geometry: Path | str | None) -> _Contents:
    """Records 58 and node coordinates (x, y) of a file (and of a separate geometry file)."""
    sets = _read_sets(path)
    units = _units_of(path, sets)
    xyz, frames = _coordinates(path, sets, units, geometry)
    nodes = {n: (x, y) for n, (x, y, _) in xyz.items()}
    records = [
        _record_of(path, i, dset) for i, dset in enumerate(sets, start=1) if dset.get("type") == 58
    ]
    records = _in_global_axes(path, records, frames)
    types = [_as_int(dset.get("type")) for dset in sets]
    depth = {n: z for n, (_, _, z) in xyz.items()}
    return _Contents(records=records, nodes=nodes, units=units, types=types, depth=depth)


def _location(nodes: dict[int, tuple[float, float]], node: int) -> tuple[float, float]:
    """A node's (x, y), m; NaN without coordinates (FRFs need none; a step that does asks)."""
    return nodes.get(node, (math.nan, math.nan))


def _note_missing(path: Path, nodes: dict[int, tuple[float, float]], wanted: list[int]) -> None:
    missing = [n for n in wanted if n not in nodes]
    if missing:
        logger.info(
            "%s: %s %s no coordinates (FRFs need none; shapes and maps will ask for `geometry`)",
            path,
            noun(len(missing), "node") + " " + ", ".join(map(str, missing[:8])),
            noun(len(missing), "has", "have"),
        )


def _check_same_abscissa(path: Path, first: _Record, record: _Record, what: str) -> None:
    """InputError naming both records unless they share one abscissa."""
    same = first.x.size == record.x.size
    if same:
        scale = float(np.max(np.abs(first.x))) + float(np.ptp(first.x)) / max(first.x.size, 1)
        same = bool(np.allclose(record.x, first.x, rtol=1e-9, atol=1e-9 * scale))
    if not same:

        def axis(r: _Record) -> str:
            step = float(np.mean(np.diff(r.x))) if r.x.size > 1 else math.nan
            return f"{r.x.size} values from {r.x[0]:g} by {step:g}"

        raise InputError(
            f"{path}: data sets {first.index} and {record.index} differ in {what} "
            f"({axis(first)} against {axis(record)}); every record must share one {what}"
        )


def _describe_types(contents: _Contents) -> str:
    functions = sorted({r.func_type for r in contents.records})
    others = sorted(set(contents.types) - {58})
    parts = []
    if functions:
        parts.append("data set 58 of function type " + ", ".join(map(str, functions)))
    if others:
        parts.append(f"data set{'s' if len(others) > 1 else ''} " + ", ".join(map(str, others)))
    return " and ".join(parts) or "nothing usable"


# --------------------------------------------------------------------------------------------
# Public readers
# --------------------------------------------------------------------------------------------


def _records_of(path: Path, contents: _Contents, func_type: int) -> list[_Record]:
    """The file's records of one function type; an error naming what it holds instead."""
    records = [r for r in contents.records if r.func_type == func_type]
    if records:
        return records
    other = FREQUENCY_RESPONSE if func_type == TIME_RESPONSE else TIME_RESPONSE
    what = {
        TIME_RESPONSE: ("time records", "read_hammer_uff"),
        FREQUENCY_RESPONSE: ("FRFs", "read_frf_uff"),
    }
    if any(r.func_type == other for r in contents.records):
        hint = f"; read it with `{what[other][1]}`"
    elif MODE_SHAPES in contents.types:
        beside = model_json_beside(path)
        hint = f"; {mode_shapes_words(what[func_type][0])}" + (
            f"; its modal model's JSON is {beside}" if beside else ""
        )
    else:
        hint = (
            "; export FRFs (function type 4) or the time records of the hammer and the sensor "
            "(1): spectra and PSDs (2, 3, 9, 12) are not read"
        )
    raise InputError(
        f"{path}: no {what[func_type][0]} (data set 58, function type {func_type}): the file "
        f"holds {_describe_types(contents)}{hint}"
    )


def _fewer_averages(path: Path, counts: dict[int, int], last: int) -> str | None:
    """What to say when the point recorded last holds fewer averages than every other point.

    Issue 26: another system's file cut exactly between two data sets is a smaller valid file,
    and the hits it lost were the last point's; nothing else betrays the cut.  A point in the
    middle with fewer averages is a lab's choice (a bad hit left out) and is not said.
    ``counts`` maps each point to its averages; returns the message (also logged), or None.
    """
    others = [n for node, n in counts.items() if node != last]
    if not others or counts[last] >= min(others):
        return None
    low, high = min(others), max(others)
    usual = f"{low}" if low == high else f"{low}–{high}"
    message = (
        f"{path}: hammer point {last}, the last in the file, has "
        f"{plural(counts[last], 'average')}, the others {usual} {noun(high, 'average')}: the "
        "file may have been cut after its last complete data set; check that it holds every hit"
    )
    logger.warning("%s", message)
    return message


@logs_warnings(logger)
def read_hammer_uff(path: Path | str, geometry: Path | str | None = None) -> HammerRecords:
    """Read the time records of a roving-hammer test from a Universal File.

    Parameters
    ----------
    path : Path or str
        Universal File with data sets 58 (ASCII) or 58b (binary) of function type 1: per hammer
        point and average a force record (ordinate type 13 excitation force, response node =
        the hammer node) and a response record (ordinate type 12 acceleration, 11 velocity or
        8 displacement, response node = the fixed transducer, reference node = the hammer
        node), paired by hammer node and load case (the average number).  Node coordinates
        (data set 15 or 2411, m) may be in the same file.
    geometry : Path or str, optional
        A second Universal File with node coordinates (data set 15 or 2411, m); its nodes take
        precedence over those of ``path``.

    Returns
    -------
    HammerRecords
        Points ordered by node number, averages in load-case order, SI units (converted where
        the units labels or a data set 164 say otherwise; SI assumed where the file is silent).
        ``metadata["averages"]`` lists the load cases of each point.

    Raises
    ------
    InputError
        Missing, damaged or truncated file; FRFs instead of time records; an average missing
        its force or response record; records of different length or sampling; no force
        channel; NaN in the data; a node without coordinates.
    """
    path = Path(path)
    contents = _load(path, geometry)
    records = _records_of(path, contents, TIME_RESPONSE)
    ignored = len(contents.records) - len(records)
    if ignored:
        logger.info("%s: %d data sets 58 that are not time records ignored", path, ignored)
    forces, responses = _channels(path, records)
    layout = _hammer_layout(path, forces, responses)
    x, step = _time_axis(path, records)
    time_scale = _scale(
        path, records[0], "time", _normal_label(records[0].labels[0]), contents.units
    )
    nodes = sorted(set(layout.point_of.values()))
    averages = [layout.cases_at(node) for node in nodes]
    rows = [_point_in_si(path, (forces, responses), layout, n, contents.units) for n in nodes]
    _note_missing(path, contents.nodes, [*nodes, layout.reference_node])
    metadata: dict[str, Any] = {"averages": averages}
    last = max(forces, key=lambda key: max(forces[key].index, responses[key].index))
    counts = dict(zip(nodes, map(len, averages), strict=True))
    fewer = _fewer_averages(path, counts, layout.point_of[last])
    if fewer:
        metadata["fewer_averages"] = fewer
    if layout.roving_accelerometer:
        metadata["layout"] = "roving accelerometer"
    if _three_d(path, contents, [*nodes, layout.reference_node]):
        metadata["three_d_geometry"] = str(path)
        contents = dataclasses.replace(contents, nodes={})
    locations = [_location(contents.nodes, n) for n in nodes]
    reference_location = _location(contents.nodes, layout.reference_node)
    return HammerRecords(
        sampling_interval_s=float(step * time_scale),
        force=tuple(f for f, _ in rows),
        response=tuple(r for _, r in rows),
        response_type=layout.response_type,
        nodes=tuple(nodes),
        locations=np.asarray(locations, dtype=float),
        reference_node=layout.reference_node,
        reference_location=reference_location,
        pretrigger_s=float(-x[0] * time_scale),
        source=str(path),
        metadata=metadata,
    )


_Key = tuple[int, int]
"""An average of a hammer test: (hammer node, load case)."""


def _channels(
    path: Path, records: list[_Record]
) -> tuple[dict[_Key, _Record], dict[_Key, _Record]]:
    """The force and the response record of every average, by (hammer node, load case).

    Raises an InputError for a complex record, an ordinate that is neither, two records of one
    channel and average, no force or no response channel, a response naming no hammer node,
    and an average missing one of its two records.
    """
    forces: dict[_Key, _Record] = {}
    responses: dict[_Key, _Record] = {}
    unreferenced: list[_Record] = []  # responses naming no hammer node (reference node 0)
    for record in records:
        if np.iscomplexobj(record.data):
            raise InputError(f"{record.where(path)}: a time record must be real, not complex")
        if record.quantity == QUANTITY_CODE["force"]:
            table, key = forces, (record.rsp_node, record.load_case)
        elif record.quantity in RESPONSE_OF_CODE:
            if record.ref_node == 0:
                unreferenced.append(record)
                continue
            table, key = responses, (record.ref_node, record.load_case)
        else:
            raise InputError(
                f"{record.where(path)}: ordinate type {record.quantity} is neither a force (13) "
                "nor a response (8 displacement, 11 velocity, 12 acceleration); set record 9, "
                "field 1 to one of these"
            )
        if key in table:
            raise InputError(
                f"{path}: data sets {table[key].index} and {record.index} are both the "
                f"{'force' if table is forces else 'response'} of hammer node {key[0]}, load "
                f"case {key[1]}; give each average its own load case number"
            )
        table[key] = record
    _check_channels(path, forces, responses, unreferenced)
    return forces, responses


def _check_channels(
    path: Path,
    forces: dict[_Key, _Record],
    responses: dict[_Key, _Record],
    unreferenced: list[_Record],
) -> None:
    """A force and a response channel, every response naming its hammer node, every average
    with both records."""
    if not forces:
        raise InputError(
            f"{path}: no force channel: no time record has ordinate type 13 (excitation force) "
            "or units of force; export the hammer channel with the responses (an output-only "
            "export, as ARTeMIS writes for operational modal analysis, has none: racketdyn "
            "needs the hammer's force)"
        )
    if unreferenced:
        raise InputError(
            f"{unreferenced[0].where(path)}: a response record must name the hammer node as its "
            "reference node (record 6, field 9; 0 means none, as general-purpose recorders such "
            "as HBM catman write); set it for every average, or write the test as racketdyn CSV "
            "(docs/uff-and-csv.md)"
        )
    if not responses:
        raise InputError(
            f"{path}: no response channel: no time record has ordinate type 8, 11 or 12; export "
            "the transducer channel with the forces"
        )
    for key in sorted(forces.keys() ^ responses.keys()):
        present = forces.get(key) or responses[key]
        missing = "response" if key in forces else "force"
        raise InputError(
            f"{present.where(path)}: hammer node {key[0]}, average (load case) {key[1]} has no "
            f"{missing} record; export both channels of every average or leave the average out"
        )


@dataclass(frozen=True)
class _HammerLayout:
    """Who moved in a hammer test: the reference node, the point of each average and the
    response type measured."""

    reference_node: int
    point_of: dict[_Key, int]
    """The point of each average: the hammer node (roving hammer), or, with one hammer node
    and the accelerometer moved, the response node (by reciprocity H_ij = H_ji the same data;
    the hammer node is then the reference)."""
    roving_accelerometer: bool
    response_type: ResponseType

    def keys_at(self, node: int) -> list[_Key]:
        """The averages of one point, in load-case order."""
        return sorted(
            (key for key in self.point_of if self.point_of[key] == node), key=lambda k: k[1]
        )

    def cases_at(self, node: int) -> list[int]:
        """The load cases of one point's averages, ascending."""
        return [case for _, case in self.keys_at(node)]


def _hammer_layout(
    path: Path, forces: dict[_Key, _Record], responses: dict[_Key, _Record]
) -> _HammerLayout:
    """Roving hammer or roving accelerometer; one response node and one response type."""
    first_response = next(iter(responses.values()))
    response_type = RESPONSE_OF_CODE[first_response.quantity]
    reference_node = first_response.rsp_node
    hammer_nodes = {node for node, _ in forces}
    roving_accelerometer = (
        len({r.rsp_node for r in responses.values()}) > 1 and len(hammer_nodes) == 1
    )
    point_of = {key: key[0] for key in forces}
    if roving_accelerometer:
        reference_node = next(iter(hammer_nodes))
        point_of = {key: responses[key].rsp_node for key in forces}
    for record in responses.values():
        if record.rsp_node != reference_node and not roving_accelerometer:
            raise InputError(
                f"{path}: data sets {first_response.index} and {record.index} were measured at "
                f"different response nodes ({reference_node} and {record.rsp_node}); racketdyn "
                "reads one reference transducer at a time"
            )
        if record.quantity != first_response.quantity:
            raise InputError(
                f"{path}: data sets {first_response.index} and {record.index} hold different "
                f"responses ({response_type} and {RESPONSE_OF_CODE[record.quantity]}); give one "
                "response type"
            )
    return _HammerLayout(reference_node, point_of, roving_accelerometer, response_type)


def _time_axis(path: Path, records: list[_Record]) -> tuple[NDArray[np.float64], float]:
    """The records' common time axis and step, in the file's unit: two samples or more, evenly
    spaced."""
    first = records[0]
    for record in records[1:]:
        _check_same_abscissa(path, first, record, "length and sampling")
    x, step = first.x, first.step
    if x.size < 2:
        raise InputError(f"{first.where(path)}: a time record needs two samples or more")
    if (
        not first.even
        and np.max(np.abs(np.diff(x) - step)) > 1e-5 * np.max(np.abs(x)) + 1e-9 * step
    ):
        raise InputError(f"{first.where(path)}: the samples must be evenly spaced in time")
    return x, step


def _point_in_si(
    path: Path,
    channels: tuple[dict[_Key, _Record], dict[_Key, _Record]],
    layout: _HammerLayout,
    node: int,
    units: _Units,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """One point's force (N) and response records (SI units of the response type), one row
    per average, each average's force then its response checked."""
    forces, responses = channels
    kind = layout.response_type
    rows_f, rows_r = [], []
    for key in layout.keys_at(node):
        f, r = forces[key], responses[key]
        f_scale = _scale(path, f, "force", _normal_label(f.labels[1]), units)
        r_scale = _scale(path, r, kind, _normal_label(r.labels[1]), units)
        rows_f.append(
            _in_si(path, f, f_scale * _sign(path, f, f.rsp_dir), "force", ABSURD_FORCE_N, "N")
        )
        rows_r.append(
            _in_si(
                path, r, r_scale * _sign(path, r, r.rsp_dir), kind, ABSURD_RESPONSE, SI_LABEL[kind]
            )
        )
    return np.asarray(rows_f, dtype=float), np.asarray(rows_r, dtype=float)


def _three_d(path: Path, contents: _Contents, nodes: list[int]) -> bool:
    """Whether the nodes differ in z (logged): then the records are read without coordinates.

    (x, y, z) points: time records and FRFs are (x, y); rather no coordinates than points
    squashed onto x–y.  identify reads the lab's (x, y, z) from this file.
    """
    depths = [contents.depth[n] for n in nodes if n in contents.depth]
    if not (depths and max(depths) > min(depths)):
        return False
    logger.warning(
        "%s: the points differ in z (3-D geometry): the records are read without "
        "coordinates; give this file to identify as --geometry for the (x, y, z) points",
        path,
    )
    return True


def _coherence(
    path: Path, records: Iterable[_Record], reference: int, nodes: list[int], first: _Record
) -> NDArray[np.float64] | None:
    """Coherences (function type 6) of every point against the reference, or None."""
    found: dict[int, _Record] = {}
    for record in records:
        if record.func_type == COHERENCE and record.rsp_node == reference:
            found[record.ref_node] = record
    if not found:
        return None
    if set(found) != set(nodes):
        logger.warning(
            "%s: coherence given for nodes %s only; coherence left out", path, sorted(found)
        )
        return None
    for record in found.values():
        _check_same_abscissa(path, first, record, "frequency axis")
        if np.iscomplexobj(record.data):
            raise InputError(f"{record.where(path)}: a coherence must be real")
    return np.asarray(
        [_in_si(path, found[n], 1.0, "the coherence's", ABSURD_COHERENCE, "") for n in nodes],
        dtype=float,
    )


#: A coherence read from a file beyond this is damage (it lies between 0 and 1; a per-cent
#: coherence, 0–100, passes and only draws wrong).
ABSURD_COHERENCE = 1.0e3


def _id_number(records: Sequence[_Record], pattern: re.Pattern[str], line: int) -> float | None:
    """The number racketdyn wrote in ID line ``line`` (from 1) of every record, if all agree."""
    found = set()
    for record in records:
        written = record.ids[0].startswith("racketdyn")
        match = pattern.search(record.ids[line - 1]) if written else None
        if match is None:
            return None
        found.add(match.group(1))
    try:
        return float(found.pop()) if len(found) == 1 else None
    except ValueError:
        return None


def _bandwidth_of(records: Sequence[_Record]) -> float | None:
    """The analyser bandwidth racketdyn wrote in ID line 2 (Hz), if every record agrees."""
    return _id_number(records, _BANDWIDTH, 2)


def _force_band_of(records: Sequence[_Record]) -> float | None:
    """Where the hammer's force was 40 dB down (Hz), as racketdyn wrote it in ID line 3 of
    every record (:attr:`~racketdyn.measurement.records.FrfSet.force_band_hz`)."""
    return _id_number(records, _FORCE_BAND, 3)


def _frf_id_fields(
    records: Sequence[_Record],
) -> tuple[str, float | None, NDArray[np.int_] | None]:
    """Estimator, exponential window τ (s) and averages from racketdyn's ID line 2, if all agree."""
    fields = []
    for record in records:
        match = _FRF_LINE.search(record.ids[1]) if record.ids[0].startswith("racketdyn") else None
        if match is None:
            return "file", None, None
        fields.append(match.groups())
    estimators = {f[0] for f in fields}
    taus = {f[1] for f in fields}
    if len(estimators) != 1 or len(taus) != 1:
        return "file", None, None
    tau_text = taus.pop()
    try:
        tau = None if tau_text == "none" else float(tau_text)
    except ValueError:
        tau = None
    try:
        averages = np.asarray([int(f[2]) for f in fields], dtype=int)
    except ValueError:
        averages = None
    return estimators.pop(), tau, averages


# --------------------------------------------------------------------------------------------
# Writing
# --------------------------------------------------------------------------------------------


def _ascii_line(text: str) -> str:
    """An ID line: ASCII, one line, at most 80 characters, never blank."""
    line = " ".join(text.encode("ascii", "replace").decode("ascii").split())
    return line[:80] or "NONE"


def _abscissa_line(x: NDArray[np.float64]) -> str:
    start, step = float(x[0]), float((x[-1] - x[0]) / (x.size - 1))
    return _ascii_line(f"racketdyn abscissa start {start!r} step {step!r}")


def _is_even(x: NDArray[np.float64]) -> bool:
    step = (x[-1] - x[0]) / (x.size - 1)
    return bool(np.allclose(np.diff(x), step, rtol=1e-9, atol=0.0))


def _geometry_set(
    target: Path,
    reference_node: int,
    reference_location: tuple[float, float],
    nodes: Sequence[int],
    locations: NDArray[np.float64],
    plane: str = "xy",
) -> dict[str, Any] | None:
    """Data set 15 with the reference node first, then the hammer nodes (those with coordinates).

    None when no node has coordinates (the records came without geometry).  ``plane="xz"``
    writes the points (x, y) in the lab's x–z plane: (x, 0, y).
    """
    numbers, xs, ys = [reference_node], [reference_location[0]], [reference_location[1]]
    if any(math.isnan(v) for v in reference_location):
        numbers, xs, ys = [], [], []
    seen: set[int] = set()
    for node, (x, y) in zip(nodes, locations, strict=True):
        if node <= 0:
            raise InputError(f"{target}: node {node}: UFF node numbers must be positive")
        if node in seen:
            raise InputError(f"{target}: node {node} is listed twice; give each point its own node")
        seen.add(node)
        if math.isnan(x) or math.isnan(y):
            continue
        if node == reference_node and numbers and numbers[0] == reference_node:
            if not np.allclose((x, y), reference_location, rtol=0.0, atol=1e-9):
                raise InputError(
                    f"{target}: node {node} is the reference and a hammer point at different "
                    f"locations ({reference_location} and {(float(x), float(y))}); make them agree"
                )
            continue
        numbers.append(node)
        xs.append(float(x))
        ys.append(float(y))
    if reference_node <= 0:
        raise InputError(
            f"{target}: reference node {reference_node}: UFF node numbers must be positive"
        )
    n = len(numbers)
    if n == 0:
        return None
    in_plane = {"x": xs, "y": ys, "z": [0.0] * n}
    if plane == "xz":
        in_plane = {"x": xs, "y": [0.0] * n, "z": ys}
    return {
        "type": 15,
        "node_nums": numbers,
        "def_cs": [0] * n,
        "disp_cs": [0] * n,
        "color": [0] * n,
        **in_plane,
    }


@dataclass(frozen=True)
class _Ends:
    """The nodes a data set 58 joins (records 6's response and reference nodes) and its load
    case (the average number of a time record, 0 for an FRF)."""

    rsp_node: int
    ref_node: int
    load_case: int = 0


@dataclass(frozen=True)
class _Axes:
    """What a data set 58's axes hold: the abscissa's quantity (``frequency``, ``time``), the
    ordinate's (None: a coherence, no unit) and the ordinate's denominator (``force`` for an
    FRF; None: none)."""

    abscissa: str
    ordinate: str | None
    denominator: str | None = None


def _record_set(
    func_type: int,
    ends: _Ends,
    axes: _Axes,
    x: NDArray[np.float64],
    data: NDArray[Any],
    ids: Sequence[str],
    *,
    binary: bool,
    number: int,
) -> dict[str, Any]:
    """A pyuff dictionary for one data set 58, SI units labelled."""
    even = _is_even(x)
    ordinate, denominator = axes.ordinate, axes.denominator
    dset: dict[str, Any] = {
        "type": 58,
        "binary": int(binary),
        "func_type": func_type,
        "func_id": number,
        "ver_num": 0,
        "load_case_id": ends.load_case,
        "rsp_ent_name": "NONE",
        "rsp_node": ends.rsp_node,
        "rsp_dir": DIRECTION,
        "ref_ent_name": "NONE",
        "ref_node": ends.ref_node,
        "ref_dir": DIRECTION,
        "abscissa_spacing": int(even),
        "abscissa_spec_data_type": QUANTITY_CODE[axes.abscissa],
        "abscissa_axis_lab": axes.abscissa.capitalize(),
        "abscissa_axis_units_lab": SI_LABEL[axes.abscissa],
        "ordinate_spec_data_type": QUANTITY_CODE[ordinate] if ordinate else 0,
        "ordinate_axis_lab": (ordinate or "coherence").capitalize(),
        "ordinate_axis_units_lab": SI_LABEL[ordinate] if ordinate else "NONE",
        # pyuff requires this key although it documents it as optional
        "orddenom_spec_data_type": QUANTITY_CODE[denominator] if denominator else 0,
        "orddenom_axis_lab": denominator.capitalize() if denominator else "NONE",
        "orddenom_axis_units_lab": SI_LABEL[denominator] if denominator else "NONE",
        "z_axis_spec_data_type": 0,
        "x": np.asarray(x, dtype=float),
        "data": np.array(data),
    }
    for k, text in enumerate(ids, start=1):
        dset[f"id{k}"] = _ascii_line(text)
    dset["id5"] = _abscissa_line(x) if even else "racketdyn abscissa uneven"
    return dset


_RECORD_COUNT = re.compile(r"; record (\d+) of (\d+)$")


def _numbered(sets: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The data sets 58 with "; record k of n" after the date in ID line 3: a file cut
    between two data sets is otherwise a smaller valid file (:func:`_check_complete`)."""
    records = [dset for dset in sets if dset["type"] == 58]
    for k, dset in enumerate(records, start=1):
        dset["id3"] = _ascii_line(f"{dset['id3']}; record {k} of {len(records)}")
    return sets


def _check_complete(path: Path, sets: Sequence[dict[str, Any]]) -> None:
    """Refuse a file racketdyn wrote that holds fewer of its data sets 58 than it wrote.

    Only racketdyn's own files say how many records they hold (ID line 3); another system's
    file cut exactly between two data sets cannot be told from a smaller file.
    """
    counts: list[tuple[int, int]] = []
    for dset in sets:
        if dset.get("type") != 58 or not str(dset.get("id1", "")).startswith("racketdyn"):
            continue
        match = _RECORD_COUNT.search(str(dset.get("id3", "")).strip())
        if match:
            counts.append((int(match.group(1)), int(match.group(2))))
    totals = {total for _, total in counts}
    if len(totals) != 1:
        return  # none, or records of several files put together: nothing to hold them to
    total = totals.pop()
    if len(counts) < total:
        raise InputError(
            f"{path}: the file holds {len(counts)} of the {total} data sets 58 racketdyn wrote "
            f"into it: it was cut after data set {len(sets)}; copy or write it again"
        )


def _write_sets(path: Path, sets: Sequence[dict[str, Any]]) -> Path:
    """Write data sets to a fresh file with pyuff.

    Each data set goes with mode 'add' into a fresh scratch file whose bytes are appended to the
    output, which then replaces ``path`` in one step: pyuff re-reads the whole file after every
    data set it writes (quadratic time), and its mode 'overwrite' truncates the file again when
    the first data set is binary, destroying that set's header.
    """
    if path.is_dir():
        raise InputError(f"{path}: is a folder; give a file name to write")
    if not path.parent.is_dir():
        raise InputError(f"{path}: the folder {path.parent} does not exist; create it first")
    with tempfile.TemporaryDirectory(prefix="racketdyn-uff-") as scratch:
        out = Path(scratch) / "out.uff"
        try:
            with out.open("wb") as target:
                for k, dset in enumerate(sets):
                    part = Path(scratch) / f"{k}.uff"
                    # pyuff leaves a file handle open after a binary data set 58 (CPython closes
                    # it at once; the ResourceWarning would reach the user as noise)
                    with warnings.catch_warnings(), _quiet_pyuff():
                        warnings.simplefilter("ignore", ResourceWarning)
                        pyuff.UFF(str(part)).write_sets([dset], mode="add")
                    target.write(part.read_bytes())
                    part.unlink()
        except Exception as error:  # pyuff raises bare Exception
            raise InputError(f"{path}: cannot be written ({error})") from None
        try:
            os.replace(out, path)
        except OSError as error:
            raise InputError(f"{path}: cannot be written ({error.strerror})") from None
    return path


def _finite(target: Path, what: str, node: int, values: NDArray[Any]) -> None:
    bad = ~np.isfinite(values)
    if np.any(bad):
        raise InputError(
            f"{target}: {what} of node {node} has "
            f"{plural(int(bad.sum()), 'NaN or infinite value')}; "
            "pyuff would write them as 0 or huge numbers — drop those lines before writing"
        )


def write_frf_uff(frfs: FrfSet, path: Path | str, binary: bool = False) -> Path:
    """Write FRFs to a fresh Universal File.

    The file holds a data set 15 (the reference node, then the hammer nodes, x and y in m, z 0)
    and per point a data set 58 of function type 4 (complex, double precision; response node =
    the reference, reference node = the hammer point, both +Z; ordinate type 8, 11 or 12 per
    ``frf_type`` over force 13; frequency in Hz) followed, when the set has coherence, by its
    coherence (function type 6).  ID line 1 names racketdyn and its version, line 2 the
    estimator, exponential window τ and averages, line 3 the date, line 4 the nodes, line 5 the
    exact frequency start and step.

    Parameters
    ----------
    frfs : FrfSet
        The FRFs; every value must be finite.
    path : Path or str
        File to write; an existing file is replaced.
    binary : bool
        Write binary data sets 58b instead of ASCII 58 (default False).  pyuff writes the byte
        count of a complex binary record as half the true count in the 58b header (8 bytes per
        value instead of 16), which readers that trust it choke on; hence ASCII by default.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    InputError
        NaN or infinite values (pyuff would write them as 0), node numbers that are not
        positive or repeat, fewer than two frequency lines, or a file that cannot be written.
    """
    path = Path(path)
    frequency = np.asarray(frfs.frequency, dtype=float)
    if frequency.size < 2:
        raise InputError(f"{path}: an FRF needs two frequency lines or more to be written")
    if frfs.locations.shape[1] != 2:
        raise InputError(f"{path}: racketdyn writes UFF geometry for (x, y) locations only")
    reference = (float(frfs.reference_location[0]), float(frfs.reference_location[1]))
    geometry = _geometry_set(path, frfs.reference_node, reference, frfs.nodes, frfs.locations)
    sets: list[dict[str, Any]] = [] if geometry is None else [geometry]
    response = {v: k for k, v in FRF_TYPE_OF_RESPONSE.items()}[frfs.frf_type]
    tau = "none" if frfs.exponential_window_s is None else repr(float(frfs.exponential_window_s))
    estimator = "_".join(str(frfs.estimator).split()) or "file"
    date = datetime.datetime.now().strftime("%d-%b-%y %H:%M:%S")
    top = frfs.bandwidth_hz
    bandwidth = "" if top == frequency[-1] else f"; bandwidth {top:.7g} Hz"
    # ID line 2 is full: the force's band goes after the date (ID line 3)
    force = frfs.force_band_hz
    dated = date if force is None else f"{date}; force band {force:.7g} Hz"
    for i, node in enumerate(frfs.nodes):
        _finite(path, "the FRF", node, frfs.values[i])
        averages = "?" if frfs.n_averages is None else str(int(frfs.n_averages[i]))
        ids = [
            f"racketdyn {__version__} FRF {frfs.frf_type}",
            f"estimator {estimator}; exponential window tau {tau} s; averages {averages}"
            + bandwidth,
            dated,
            f"hammer node {node} to reference node {frfs.reference_node}; {frfs.source}",
        ]
        ends = _Ends(frfs.reference_node, node)
        sets.append(
            _record_set(
                FREQUENCY_RESPONSE,
                ends,
                _Axes("frequency", response, "force"),
                frequency,
                np.asarray(frfs.values[i], dtype=complex),
                ids,
                binary=binary,
                number=len(sets),
            )
        )
        if frfs.coherence is not None:
            _finite(path, "the coherence", node, frfs.coherence[i])
            sets.append(
                _record_set(
                    COHERENCE,
                    ends,
                    _Axes("frequency", None),
                    frequency,
                    np.asarray(frfs.coherence[i], dtype=float),
                    [f"racketdyn {__version__} coherence", ids[1], dated, ids[3]],
                    binary=binary,
                    number=len(sets),
                )
            )
    return _write_sets(path, _numbered(sets))


def write_hammer_uff(
    records: HammerRecords,
    path: Path | str,
    binary: bool = False,
    response_direction: int = 3,
    plane: str = "xy",
    layout: str = "roving hammer",
) -> Path:
    """Write roving-hammer time records to a fresh Universal File, as a lab would.

    The file holds a data set 15 (the reference node, then the hammer nodes, x and y in m, z 0)
    and, per point and average, a force record and a response record: data sets 58 of function
    type 1, real, double precision, time in s from ``-pretrigger_s``.  The force record has
    ordinate type 13 (N) and the hammer node as response and reference node; the response record
    has ordinate type 12, 11 or 8 per ``response_type`` (SI), the reference transducer as
    response node and the hammer node as reference node.  The load case is the average number,
    from 1.  :func:`read_hammer_uff` reads the file back.

    Parameters
    ----------
    records : HammerRecords
        The records; every value must be finite.
    path : Path or str
        File to write; an existing file is replaced.
    binary : bool
        Write binary data sets 58b instead of ASCII 58 (default False).
    response_direction : int
        Direction code of the response records (record 6): ``3`` (+z, along the hammer) or
        ``-3`` (an accelerometer mounted against the hammer, in −z: the records hold what it
        measures, the response negated, and the code says so, as a lab's export does).
    plane : {"xy", "xz"}
        The lab plane the face lies in: ``xy`` (coordinates (x, y, 0), the normal z: codes
        ±3) or ``xz`` (the racket in the lab's x–z plane, as a lab measures it standing:
        coordinates (x, 0, y), the normal y: codes ±2).
    layout : {"roving hammer", "roving accelerometer"}
        ``roving accelerometer`` writes the same data (by reciprocity, H_ij = H_ji) as a test
        with the hammer at the reference node and the accelerometer moved over the points:
        every force record at the reference node, each response record at its point, the load
        case a running number over the file (each point's averages its own cases).
        :func:`read_hammer_uff` reads either.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    InputError
        NaN or infinite values, node numbers that are not positive or repeat, a direction code
        other than ±3, or a file that cannot be written.
    """
    path = Path(path)
    if response_direction not in (DIRECTION, -DIRECTION):
        raise InputError(
            f"{path}: response direction {response_direction!r}: racketdyn writes +3 or -3"
        )
    if plane not in ("xy", "xz"):
        raise InputError(f"{path}: plane {plane!r}: give xy or xz")
    if layout not in ("roving hammer", "roving accelerometer"):
        raise InputError(f"{path}: layout {layout!r}: give roving hammer or roving accelerometer")
    moving = layout == "roving accelerometer"
    mounted = 1.0 if response_direction > 0 else -1.0
    normal = DIRECTION if plane == "xy" else 2
    geometry = _geometry_set(
        path,
        records.reference_node,
        records.reference_location,
        records.nodes,
        records.locations,
        plane,
    )
    sets: list[dict[str, Any]] = [] if geometry is None else [geometry]
    time = records.time
    date = datetime.datetime.now().strftime("%d-%b-%y %H:%M:%S")
    kind = records.response_type
    for node, force, response in zip(records.nodes, records.force, records.response, strict=True):
        _finite(path, "the force", node, force)
        _finite(path, "the response", node, response)
        for k in range(force.shape[0]):
            where = f"hammer node {node}, average {k + 1}, reference node {records.reference_node}"
            hammer, sensor, case = node, records.reference_node, k + 1
            if moving:
                hammer, sensor = records.reference_node, node
                where = f"accelerometer node {node}, average {k + 1}, hammer node {hammer}"
                case = sum(1 for s in sets if s.get("func_type") == TIME_RESPONSE) // 2 + 1
            for channel, data, rsp_node, direction in (
                ("force", force[k], hammer, normal),
                (kind, mounted * response[k], sensor, int(mounted) * normal),
            ):
                sets.append(
                    _record_set(
                        TIME_RESPONSE,
                        _Ends(rsp_node, hammer, load_case=case),
                        _Axes("time", channel),
                        time,
                        np.asarray(data, dtype=float),
                        [
                            f"racketdyn {__version__} hammer test, {channel}",
                            records.source or "NONE",
                            date,
                            where,
                        ],
                        binary=binary,
                        number=len(sets),
                    )
                )
                sets[-1]["rsp_dir"], sets[-1]["ref_dir"] = direction, normal
    return _write_sets(path, _numbered(sets))


# --------------------------------------------------------------------------------------------
# CSV
# --------------------------------------------------------------------------------------------

CSV_COLUMNS = ("node", "average", "time_s", "force_n", "response")
_LARGEST_WHOLE = int(np.iinfo(np.int64).max)
"""A whole-number column beyond this (numpy's int64) is refused naming its line."""
GEOMETRY_COLUMNS = ("node", "x_m", "y_m")


def _csv_rows(
    path: Path, required: tuple[str, ...]
) -> tuple[dict[str, str], list[str], list[int], list[list[str]]]:
    """Settings (``# key: value`` lines), header, line numbers and rows of a CSV file."""
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot be read as UTF-8 text ({error})") from None
    settings: dict[str, str] = {}
    numbers, lines = [], []
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if stripped.startswith("#"):
            key, colon, value = stripped[1:].partition(":")
            if colon:
                settings[key.strip().lower()] = value.strip()
        elif stripped:
            numbers.append(number)
            lines.append(line)
    if not lines:
        raise InputError(f"{path}: empty; expected a header with columns {', '.join(required)}")
    rows = [split_csv_line(path, n, line) for n, line in zip(numbers, lines, strict=True)]
    header = [name.strip() for name in rows[0]]
    missing = [name for name in required if name not in header]
    if missing:
        raise InputError(
            f"{path}: missing {noun(len(missing), 'column')} {', '.join(missing)}; "
            "the header must name "
            f"{', '.join(required)} (found {', '.join(header) or 'nothing'})"
        )
    for number, row in zip(numbers[1:], rows[1:], strict=True):
        if len(row) != len(header):
            raise InputError(
                f"{path}: line {number} has {len(row)} values for {len(header)} columns "
                f"({', '.join(header)})"
            )
    return settings, header, numbers[1:], rows[1:]


def _csv_column(
    path: Path,
    header: list[str],
    numbers: list[int],
    rows: list[list[str]],
    name: str,
    integer: bool,
) -> NDArray[Any]:
    """One column as numbers; InputError naming the line of the first bad value."""
    j = header.index(name)
    texts = [row[j].strip() for row in rows]
    kind = "a whole number" if integer else "a finite number"
    try:
        values = np.asarray(texts, dtype=int if integer else float)
    except (TypeError, ValueError, OverflowError):  # OverflowError: an integer beyond int64
        values = None
    if values is not None and (values.size == 0 or bool(np.all(np.isfinite(values)))):
        return values
    for number, text in zip(numbers, texts, strict=True):
        try:
            value = int(text) if integer else float(text)
        except ValueError:
            value = math.nan
        if not math.isfinite(value) or (integer and abs(value) > _LARGEST_WHOLE):
            raise InputError(f"{path}: line {number}, column {name}: {text!r} is not {kind}")
    raise InputError(f"{path}: column {name} must hold {kind} on every line")


def _csv_setting(path: Path, settings: dict[str, str], key: str, example: str) -> str:
    if key not in settings or not settings[key]:
        raise InputError(
            f"{path}: no '# {key}: …' line; add one before the header (e.g. '# {key}: {example}')"
        )
    return settings[key]


@logs_warnings(logger)
def read_hammer_csv(path: Path | str, geometry_path: Path | str | None = None) -> HammerRecords:
    """Read roving-hammer time records from a CSV file and its geometry CSV.

    Parameters
    ----------
    path : Path or str
        CSV in long form: comment lines ``# reference_node: N`` and ``# response_type:
        acceleration`` (or velocity, displacement) before the header ``node,average,time_s,
        force_n,response``; one row per sample: hammer node, average number, time from the
        trigger (s, the same evenly spaced times for every average), hammer force (N), response
        at the reference node (SI units of the response type).
    geometry_path : Path or str, optional
        CSV with header ``node,x_m,y_m``: coordinates (m) of the reference node and the hammer
        nodes.  Without it (or for a node it does not list) the locations are NaN: FRFs need
        none, the steps that do ask for ``--geometry``.

    Returns
    -------
    HammerRecords
        Points ordered by node number, averages by their number (listed in
        ``metadata["averages"]``).

    Raises
    ------
    InputError
        Missing file or column, a value that is not a number (NaN included), a missing
        setting, averages of different length or timing.
    """
    path = Path(path)
    settings, header, numbers, rows = _csv_rows(path, CSV_COLUMNS)
    if not rows:
        raise InputError(f"{path}: no samples listed under the header")
    reference_text = _csv_setting(path, settings, "reference_node", "3")
    try:
        reference_node = int(reference_text)
    except ValueError:
        raise InputError(
            f"{path}: reference_node must be a whole number (got {reference_text!r})"
        ) from None
    response_type = _csv_setting(path, settings, "response_type", "acceleration")
    if response_type not in RESPONSE_TYPES:
        raise InputError(
            f"{path}: response_type must be one of {', '.join(RESPONSE_TYPES)} "
            f"(got {response_type!r})"
        )
    node = _csv_column(path, header, numbers, rows, "node", True)
    average = _csv_column(path, header, numbers, rows, "average", True)
    time = _csv_column(path, header, numbers, rows, "time_s", False)
    force = _csv_column(path, header, numbers, rows, "force_n", False)
    response = _csv_column(path, header, numbers, rows, "response", False)
    line = np.asarray(numbers)
    order = np.lexsort((average, node))  # stable: samples keep their file order
    keys = np.column_stack([node, average])[order]
    starts = np.flatnonzero(np.r_[True, np.any(keys[1:] != keys[:-1], axis=1)])
    groups = np.split(order, starts[1:])
    _check_record_count(path, settings, len(groups), int(line[-1]))
    axis = time[groups[0]]
    if axis.size < 2:
        raise InputError(f"{path}: line {line[groups[0][0]]}: an average needs two samples or more")
    step = (axis[-1] - axis[0]) / (axis.size - 1)
    if not step > 0 or np.max(np.abs(np.diff(axis) - step)) > 1e-3 * step:
        raise InputError(
            f"{path}: lines {line[groups[0][0]]}–{line[groups[0][-1]]}: time_s must rise in even "
            "steps; write the times with enough digits"
        )
    for group in groups[1:]:
        if group.size != axis.size or not np.allclose(time[group], axis, rtol=0, atol=1e-3 * step):
            raise InputError(
                f"{path}: line {line[group[0]]}: node {node[group[0]]}, average "
                f"{average[group[0]]} has {group.size} samples from {time[group[0]]:g} s, the "
                f"first average {axis.size} from {axis[0]:g} s; every average must share one "
                "time axis"
            )
    nodes = sorted({int(n) for n in node})
    forces, responses, averages = [], [], []
    for n in nodes:
        mine = [g for g in groups if node[g[0]] == n]
        averages.append([int(average[g[0]]) for g in mine])
        forces.append(np.asarray([force[g] for g in mine]))
        responses.append(np.asarray([response[g] for g in mine]))
    coordinates = {} if geometry_path is None else _read_geometry_csv(Path(geometry_path))
    _note_missing(path, coordinates, [*nodes, reference_node])
    metadata: dict[str, Any] = {"averages": averages}
    fewer = _fewer_averages(path, dict(zip(nodes, map(len, averages), strict=True)), int(node[-1]))
    if fewer:
        metadata["fewer_averages"] = fewer
    return HammerRecords(
        sampling_interval_s=float(step),
        force=tuple(forces),
        response=tuple(responses),
        response_type=cast(ResponseType, response_type),
        nodes=tuple(nodes),
        locations=np.asarray([_location(coordinates, n) for n in nodes], dtype=float),
        reference_node=reference_node,
        reference_location=_location(coordinates, reference_node),
        pretrigger_s=float(-axis[0]),
        source=str(path),
        metadata=metadata,
    )


def _check_record_count(path: Path, settings: dict[str, str], held: int, last_line: int) -> None:
    """Refuse a hammer CSV holding another number of records than its ``# records: N`` line.

    racketdyn's CSVs say how many (node, average) records they hold, as its UFFs do (ID line
    3): a file cut between two records, or inside its first, is otherwise a smaller valid
    file (issue 26's fuzz test).  Another system's CSV without the line is read as it is.
    """
    if "records" not in settings:
        return
    text = settings["records"]
    try:
        written = int(text)
    except ValueError:
        raise InputError(
            f"{path}: '# records: {text}': the count of records must be a whole number; "
            "correct it or remove the line"
        ) from None
    if held < written:
        raise InputError(
            f"{path}: holds {held} of its {written} records (node, average): it was cut after "
            f"line {last_line} ('# records: {written}' says how many were written); copy or "
            "export it again, or remove that line if records were left out on purpose"
        )
    if held > written:
        raise InputError(
            f"{path}: holds {held} records (node, average) but its '# records: {written}' line "
            "says how many were written; correct the line or remove it"
        )


def _read_geometry_csv(path: Path) -> dict[int, tuple[float, float]]:
    _, header, numbers, rows = _csv_rows(path, GEOMETRY_COLUMNS)
    node = _csv_column(path, header, numbers, rows, "node", True)
    x = _csv_column(path, header, numbers, rows, "x_m", False)
    y = _csv_column(path, header, numbers, rows, "y_m", False)
    coordinates: dict[int, tuple[float, float]] = {}
    for number, n, xi, yi in zip(numbers, node, x, y, strict=True):
        if int(n) in coordinates and coordinates[int(n)] != (float(xi), float(yi)):
            raise InputError(f"{path}: line {number}: node {n} is listed twice, at two places")
        coordinates[int(n)] = (float(xi), float(yi))
    extent = float(max(np.ptp(x), np.ptp(y))) if len(coordinates) > 1 else 0.0
    if extent > MAX_EXTENT_M:  # as a Universal File's nodes (_nodes_xyz_of): another unit
        raise InputError(
            f"{path}: the points span {extent:.4g} m in x_m, y_m, more than the "
            f"{MAX_EXTENT_M:g} m of any structure tested with a hammer: {_unit_guess(extent)}; "
            "give the coordinates in m"
        )
    return coordinates


def write_hammer_csv(
    records: HammerRecords, path: Path | str, geometry_path: Path | str
) -> tuple[Path, Path]:
    """Write roving-hammer time records to a CSV file and a geometry CSV.

    The layout is the one :func:`read_hammer_csv` reads; numbers are written with 17
    significant digits, so the round trip is exact.

    Parameters
    ----------
    records : HammerRecords
        The records.
    path : Path or str
        CSV of the samples (``node,average,time_s,force_n,response``); replaced if it exists.
    geometry_path : Path or str
        CSV of the coordinates (``node,x_m,y_m``) of the reference node and the hammer nodes;
        replaced if it exists.

    Returns
    -------
    tuple of Path
        ``(path, geometry_path)``, ready for :func:`read_hammer_csv`.
    """
    path, geometry_path = Path(path), Path(geometry_path)
    time = records.time
    buffer = io.StringIO()
    buffer.write(
        f"# racketdyn {__version__} hammer records\n"
        f"# reference_node: {records.reference_node}\n"
        f"# response_type: {records.response_type}\n"
        f"# records: {sum(force.shape[0] for force in records.force)}\n"
        f"{','.join(CSV_COLUMNS)}\n"
    )
    for node, force, response in zip(records.nodes, records.force, records.response, strict=True):
        for k in range(force.shape[0]):
            table = np.column_stack(
                [np.full(time.size, node), np.full(time.size, k + 1), time, force[k], response[k]]
            )
            np.savetxt(buffer, table, fmt=["%d", "%d", "%.17g", "%.17g", "%.17g"], delimiter=",")
    geometry = io.StringIO()
    geometry.write(f"{','.join(GEOMETRY_COLUMNS)}\n")  # pure data: pandas reads it as it is
    written = {
        records.reference_node: (
            float(records.reference_location[0]),
            float(records.reference_location[1]),
        )
    }
    written.update(
        {
            n: (float(x), float(y))
            for n, (x, y) in zip(records.nodes, records.locations, strict=True)
        }
    )
    for n in sorted(written):
        if math.isnan(written[n][0]) or math.isnan(written[n][1]):
            continue  # no coordinates: left out, as read
        geometry.write(f"{n},{written[n][0]!r},{written[n][1]!r}\n")
    for target, text in ((path, buffer.getvalue()), (geometry_path, geometry.getvalue())):
        try:
            target.write_text(text, encoding="utf-8")
        except OSError as error:
            raise InputError(f"{target}: cannot be written ({error.strerror})") from None
    return path, geometry_path


MODE_SHAPES = 55
"""Data set of a normal mode's shape (:func:`write_modes_uff`)."""
MODES_FILE = re.compile(r"modes(?P<label>[\w-]*)\.uff")
"""Name of the mode-shape UFF an identification writes (``workflows.identify.write_model``)
beside its model's JSON, ``modal_model<label>.json``."""


def model_json_beside(path: Path) -> Path | None:
    """The racketdyn modal-model JSON written beside a mode-shape UFF (``modes_free.uff`` →
    ``modal_model_free.json``, as :data:`MODES_FILE` says), if it is there."""
    match = MODES_FILE.fullmatch(Path(path).name)
    beside = None if match is None else Path(path).with_name(f"modal_model{match['label']}.json")
    return beside if beside is not None and beside.is_file() else None


def mode_shapes_words(instead: str) -> str:
    """What a file of mode shapes is, given where ``instead`` was wanted (FRFs, a model's
    JSON): its data set, and who writes such files (`write_modes_uff`, in backticks: the CLI
    names its commands, ``cli.options.LIBRARY_READERS``)."""
    return (
        f"it holds mode shapes (UFF data set {MODE_SHAPES}): a modal model, as "
        f"`write_modes_uff` writes it, not {instead}"
    )


def holds_mode_shapes(path: Path) -> bool:
    """A Universal File whose data sets are mode shapes (55) and no functions (58): a modal
    model exported for other programs, never a racketdyn model's JSON (read by its structure
    alone, :func:`racketdyn.io.uff_structure.check_structure`; a damaged file is not one)."""
    try:
        blocks = check_structure(Path(path), Path(path).read_bytes())
    except (InputError, OSError):
        return False
    types = {block.type for block in blocks}
    return MODE_SHAPES in types and 58 not in types


def write_modes_uff(
    model: ModalModel, path: Path | str, nodes: Sequence[int] | None = None
) -> Path:
    """Write mode shapes as UFF 55 (normal modes) with UFF 15 geometry.

    One data set 55 per mode (analysis type 2, normal mode), frequency in Hz, viscous damping
    ratio; readable by other modal software.  The geometry keeps z of a 3-D model (the lab's
    frame; 0 for (x, y) locations).  The displacement is written along the direction the FRFs
    were measured in (``model.metadata["directions"]``: the one translation code every point
    shares; z, normal to a racket's face, when none is recorded), the other two zero.  A
    mass-normalised model (``model.scaling == "mass"``) has modal mass 1 and says
    "mass-normalised, 1/sqrt(kg)" in ID line 3; an unscaled one (no driving point) has modal
    mass 0 (unknown) and says "unscaled (largest 1), modal mass unknown".  A model without
    node coordinates (:attr:`~racketdyn.modal.model.ModalModel.has_locations` False) gets no
    data set 15: its shapes by node number only.

    Parameters
    ----------
    model : ModalModel
        Shapes at its locations (1/√kg, or unscaled).
    path : Path or str
        File to write (replaced).
    nodes : sequence of int, optional
        Node number of each location (default 1, 2, …).
    """
    target = Path(path)
    numbers = (
        list(range(1, model.locations.shape[0] + 1)) if nodes is None else [int(n) for n in nodes]
    )
    if len(numbers) != model.locations.shape[0] or len(set(numbers)) != len(numbers):
        raise InputError(f"{target}: one distinct node number per mode-shape location")
    geometry = {
        "type": 15,
        "node_nums": numbers,
        "def_cs": [0] * len(numbers),
        "disp_cs": [0] * len(numbers),
        "color": [0] * len(numbers),
        "x": model.locations[:, 0].tolist(),
        "y": model.locations[:, 1].tolist(),
        "z": (
            model.locations[:, 2].tolist()
            if model.locations.shape[1] == 3
            else [0.0] * len(numbers)
        ),
    }
    sets: list[dict[str, Any]] = [geometry] if model.has_locations else []
    zeros = np.zeros(len(numbers))
    recorded = model.metadata.get("directions") or {}
    codes = {abs(int(c)) for c in recorded.values()} if isinstance(recorded, dict) else set()
    axis = codes.pop() if len(codes) == 1 and codes <= {1, 2, 3} else 3
    letter = "xyz"[axis - 1]
    scaled = model.scaling == "mass"
    scaling = (
        "mass-normalised shapes, 1/sqrt(kg)"
        if scaled
        else "unscaled shapes (largest 1), modal mass unknown"
    )
    where = "normal to the face (z)" if recorded == {} else f"along {letter} as measured"
    for k in range(model.n_modes):
        shape = model.mode_shapes[:, k]
        _finite(target, f"mode {k + 1} shape", k + 1, shape)
        sets.append(
            {
                "type": MODE_SHAPES,
                "id1": _ascii_line(f"racketdyn {__version__} {model.names[k]}"),
                "id2": _ascii_line(f"{model.support} support; {model.source}"),
                "id3": _ascii_line(f"{scaling}, {where}"),
                "id4": "NONE",
                "id5": "NONE",
                "model_type": 1,
                "analysis_type": 2,
                "data_ch": 2,
                "spec_data_type": 8,
                "data_type": 2,
                "n_data_per_node": 3,
                **{f"r{i}": shape.astype(float) if i == axis else zeros for i in (1, 2, 3)},
                "load_case": 1,
                "mode_n": k + 1,
                "freq": float(model.frequency[k]),
                "modal_m": 1.0 if scaled else 0.0,
                "modal_damp_vis": float(model.damping_ratio[k]),
                "modal_damp_his": 0.0,
                "node_nums": np.asarray(numbers, dtype=float),
            }
        )
    return _write_sets(target, sets)
