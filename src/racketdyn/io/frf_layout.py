"""FRFs as real labs lay them out: roving hammer, roving accelerometer, several references, 3-D.

:func:`read_frfs` reads the FRFs (UFF 58, function type 4) of a file whatever moved during the
test and returns them as one :class:`~racketdyn.measurement.records.FrfSet` against one
reference node, with the points' coordinates in the lab's own frame:

- **roving hammer** (every FRF has one response node): the reference is that node;
- **roving accelerometer** (every FRF has one excitation node, the hammer): by reciprocity
  (H_ij = H_ji) the same data; the reference is the hammer node and the points are the
  response nodes;
- **several references** (MIMO, several sensors or hammer nodes): the FRFs against one node are
  used; the node that reaches the most points is chosen when it is the only one, else the
  caller names it (``reference=``, the CLI's ``--reference NODE``).  FRFs of the other
  references are left out and counted in the metadata.

Coordinates keep z: a beam along z, a racket measured in the x–z plane, and nodes that share x
and y but differ in z are read as they are ((x, y, z) locations); a set whose points all share
one z gets (x, y) locations.  Units and direction signs are read as :mod:`racketdyn.io.uff`
reads them (its helpers; this module adds the layouts and z).  Where one node is measured in
several directions, the direction most FRFs share is used and the others are counted as left out.
"""

from __future__ import annotations

import logging
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal, cast, overload

import numpy as np
from numpy.typing import NDArray

from racketdyn._grammar import noun, plural
from racketdyn.errors import InputError, logs_warnings
from racketdyn.io.frf_table import is_frf_table, read_frf_table
from racketdyn.io.uff import (
    COHERENCE,
    FREQUENCY_RESPONSE,
    QUANTITY_CODE,
    RESPONSE_OF_CODE,
    _bandwidth_of,
    _check_same_abscissa,
    _coherence,
    _Contents,
    _coordinates,
    _force_band_of,
    _frf_id_fields,
    _frf_scale,
    _in_global_axes,
    _in_si,
    _locations,
    _normal_label,
    _read_sets,
    _Record,
    _record_of,
    _records_of,
    _scale,
    _sign,
    _Units,
    _units_of,
)
from racketdyn.measurement.records import (
    ABSURD_FRF,
    FRF_TYPE_OF_RESPONSE,
    FRF_UNITS,
    FrfReferences,
    FrfSet,
    FrfType,
)

__all__ = ["LAYOUTS", "ReferenceChoice", "read_frf_uff", "read_frfs", "reference_choice"]

log = logging.getLogger(__name__)

LAYOUTS = ("roving hammer", "roving accelerometer", "several references")
"""How a file's FRFs were measured (``FrfSet.metadata["layout"]``)."""


def _check(path: Path, record: _Record) -> None:
    if not np.iscomplexobj(record.data):
        raise InputError(
            f"{record.where(path)}: an FRF must be complex (ordinate data type 5 or 6)"
        )
    if record.quantity not in RESPONSE_OF_CODE:
        raise InputError(
            f"{record.where(path)}: ordinate type {record.quantity} is not a response "
            "(8 displacement, 11 velocity, 12 acceleration) and its units label "
            f"{record.labels[1].strip()!r} names none; set record 9, field 1"
        )
    if record.rsp_node <= 0 or record.ref_node <= 0:
        raise InputError(
            f"{record.where(path)}: names no point (node 0 means none): racketdyn cannot tell "
            "the points apart nor find the driving point; set record 6, fields 6 and 9 to the "
            "sensor's and the hammer's node numbers (the same at the driving point)"
        )
    if record.denominator in RESPONSE_OF_CODE and record.denominator != record.quantity:
        over = f"{RESPONSE_OF_CODE[record.quantity]} over {RESPONSE_OF_CODE[record.denominator]}"
        raise InputError(
            f"{record.where(path)}: holds {over} (record 10, field 1 = {record.denominator}), "
            "neither a response per force nor a transmissibility (a response over the same "
            "response at the base): racketdyn identifies FRFs per newton or like over like; "
            "export the FRF against the force (an impact hammer, or a force cell at the "
            "shaker's stinger)"
        )
    if record.denominator == record.quantity:
        return  # a transmissibility: its poles are the structure's (_transmissibility)
    if record.denominator not in (0, QUANTITY_CODE["force"]):
        raise InputError(
            f"{record.where(path)}: the FRF must be per force (record 10, field 1 = 13), "
            f"not per quantity {record.denominator}"
        )


def _choose_reference(path: Path, records: list[_Record], reference: int | None) -> tuple[int, str]:
    """The reference node and the layout's name."""
    responses = {r.rsp_node for r in records}
    hammers = {r.ref_node for r in records}
    reach: dict[int, set[int]] = {}
    for r in records:
        reach.setdefault(r.rsp_node, set()).add(r.ref_node)
        reach.setdefault(r.ref_node, set()).add(r.rsp_node)
    if len(responses) == 1:
        layout = "roving hammer"
    elif len(hammers) == 1:
        layout = "roving accelerometer"
    else:
        layout = "several references"
    if reference is not None:
        if reference not in reach:
            raise InputError(
                f"{path}: `reference` {reference}: no FRF has node {reference} as its response "
                f"or excitation node (references found: {_listed(sorted(responses))} respond, "
                f"{_listed(sorted(hammers))} excite)"
            )
        return reference, layout
    if layout == "roving hammer":
        return next(iter(responses)), layout
    if layout == "roving accelerometer":
        return next(iter(hammers)), layout
    most = max(len(v) for v in reach.values())
    best = sorted(n for n, v in reach.items() if len(v) == most)
    if len(best) > 1:
        raise InputError(
            f"{path}: the FRFs have several references (nodes {_listed(best)} each reach "
            f"{most} points); choose one with `reference` (its node), or 'all' to use them "
            "together"
        )
    return best[0], layout


def _listed(nodes: list[int]) -> str:
    return ", ".join(map(str, nodes[:8])) + (" …" if len(nodes) > 8 else "")


ReferenceChoice = int | Literal["all"] | tuple[int, ...] | None
"""What ``reference`` may be: a node, every reference (``"all"``), some nodes, or the default."""


def reference_choice(value: object) -> ReferenceChoice:
    """``reference`` as :func:`read_frfs` takes it, from a node, ``"all"``, a sequence of nodes
    or their text as the command line spells it (``"201"``, ``"201,203"``, ``"all"``).

    Raises
    ------
    InputError
        Anything else, or a node listed twice (one line naming ``reference``).
    """
    if value is None or value == "all":
        return cast(ReferenceChoice, value)
    if isinstance(value, int | np.integer) and not isinstance(value, bool):
        return int(value)
    parts: list[object]
    if isinstance(value, str):
        parts = [p.strip() for p in value.split(",")]
    elif isinstance(value, Sequence | np.ndarray):
        parts = list(value)
    else:
        parts = [value]
    try:
        nodes = tuple(int(str(p)) for p in parts)
    except ValueError:
        nodes = ()
    if not nodes or any(isinstance(p, bool | float) for p in parts):
        raise InputError(
            f"`reference` must be a node number, node numbers separated by commas or 'all' "
            f"(got {value!r})"
        )
    if len(set(nodes)) != len(nodes):
        raise InputError(f"`reference` lists a node twice (got {value!r}); give each once")
    return nodes[0] if len(nodes) == 1 and isinstance(value, str) else nodes


@overload
def read_frfs(
    path: Path | str,
    geometry: Path | str | None = None,
    reference: int | None = None,
    *,
    require_coordinates: bool = True,
) -> FrfSet: ...


@overload
def read_frfs(
    path: Path | str,
    geometry: Path | str | None = None,
    reference: Literal["all"] | Sequence[int] = ...,
    *,
    require_coordinates: bool = True,
) -> FrfReferences: ...


@overload
def read_frfs(
    path: Path | str,
    geometry: Path | str | None = None,
    reference: int | Literal["all"] | Sequence[int] | None = None,
    *,
    require_coordinates: bool = True,
) -> FrfSet | FrfReferences: ...


@logs_warnings(log)
def read_frfs(
    path: Path | str,
    geometry: Path | str | None = None,
    reference: int | Literal["all"] | Sequence[int] | None = None,
    *,
    require_coordinates: bool = True,
) -> FrfSet | FrfReferences:
    """Read the FRFs of a file against one reference node, or against several together.

    Parameters
    ----------
    path : Path or str
        Universal File with data sets 58/58b of function type 4 (complex FRFs) and node
        coordinates (data set 15 or 2411, with data set 164's length unit); or an FRF table,
        a CSV file listing FRFs exported one text file per point
        (:func:`racketdyn.io.frf_table.read_frf_table`).
    geometry : Path or str, optional
        A second Universal File with node coordinates; its nodes take precedence.
    reference : int, "all" or sequence of int, optional
        The reference node (a node every FRF used has at one end).  Default: the only
        response node (roving hammer), the only excitation node (roving accelerometer), or
        the node reaching the most points when one node does.  ``"all"``: every reference of
        a file of several (the response nodes when fewer than the excitation nodes, else the
        excitation nodes), or a sequence of reference nodes: an
        :class:`~racketdyn.measurement.records.FrfReferences` of the points every reference
        reaches (the others left out, logged), for a poly-reference identification.
    require_coordinates : bool
        A point without coordinates is an error naming ``--geometry`` (default: shapes need
        them); False gives it NaN coordinates (FRFs need none;
        :func:`read_frf_uff`).  The reference node may lack them either way (its location
        NaN): shapes are at the points, and a fixed accelerometer is often not in a lab's
        geometry.

    Returns
    -------
    FrfSet or FrfReferences
        Points ordered by node number; ``reference_node`` the reference; locations (x, y, z)
        in the lab's frame, m ((x, y) when every point has the same z); metadata
        ``layout`` (:data:`LAYOUTS`), ``left_out`` (FRFs not against the reference),
        ``unused_data_sets`` (their data sets' numbers, and those of a reciprocal pair's
        other FRF), ``ignored_data_sets`` (data sets 58 of other function types than FRF and
        coherence), ``directions`` (node → direction code used) and, for FRFs racketdyn
        estimated,
        ``bandwidth_hz`` (fs/2.56; another system's export ends at its bandwidth:
        :attr:`~racketdyn.measurement.records.FrfSet.bandwidth_hz`).  With several
        references, one such set per reference, in the order given (``"all"``: ascending).

    Raises
    ------
    InputError
        As :func:`read_frf_uff`, and: several references with none chosen; a
        reference that is in no FRF; a point without coordinates (naming ``--geometry``);
        references that share no point.
    """
    path = Path(path)
    if is_frf_table(path):
        if geometry is not None:
            raise InputError(
                f"{path}: an FRF table holds the points' coordinates; give no `geometry`"
            )
        if reference is not None and not isinstance(reference, int):
            raise InputError(
                f"{path}: an FRF table has one reference (its 'reference' row); give no "
                f"`reference` or its node, not {reference!r}"
            )
        return read_frf_table(path, reference)
    sets = _read_sets(path)
    units = _units_of(path, sets)
    coordinates, frames = _coordinates(path, sets, units, geometry)
    every = [
        _record_of(path, i, dset) for i, dset in enumerate(sets, start=1) if dset.get("type") == 58
    ]
    every = _in_global_axes(path, every, frames)
    contents = _Contents(
        records=every, nodes={}, units=units, types=[int(d.get("type") or 0) for d in sets]
    )
    records = _records_of(path, contents, FREQUENCY_RESPONSE)  # an error naming what it holds
    for record in records:
        _check(path, record)
    file = _File(path, every, records, units, coordinates, geometry, require_coordinates)
    if reference is None or isinstance(reference, int | np.integer):
        ref, layout = _choose_reference(
            path, records, None if reference is None else int(reference)
        )
        return _against(file, ref, layout)
    refs = _references(path, records, reference)
    layout = _choose_reference(path, records, refs[0])[1]
    against = [_against(file, ref, layout) for ref in refs]
    shared = sorted(set.intersection(*(set(s.nodes) for s in against)))
    if not shared:
        raise InputError(
            f"{path}: references {_listed(refs)} reach no point in common; read them one at a "
            "time (`reference` a node)"
        )
    for one in against:
        if len(shared) < one.n_points:
            log.info(
                "%s: %s reached by reference %d but not by every reference left out",
                path,
                plural(one.n_points - len(shared), "point"),
                one.reference_node,
            )
    return FrfReferences(tuple(s.at_points([s.nodes.index(n) for n in shared]) for s in against))


@dataclass(frozen=True)
class _File:
    """What one reading of a file gives every reference's set."""

    path: Path
    every: list[_Record]
    records: list[_Record]
    units: _Units
    coordinates: dict[int, tuple[float, float, float]]
    geometry: Path | str | None
    require_coordinates: bool


def _references(path: Path, records: list[_Record], reference: str | Sequence[int]) -> list[int]:
    """The reference nodes of ``"all"`` or of a sequence of nodes (each checked)."""
    if isinstance(reference, str):
        if reference != "all":
            raise InputError(
                f"{path}: `reference` must be a node, a list of nodes or 'all' (got {reference!r})"
            )
        responses = sorted({r.rsp_node for r in records})
        hammers = sorted({r.ref_node for r in records})
        return responses if len(responses) <= len(hammers) else hammers
    try:
        refs = [int(r) for r in reference]
    except (TypeError, ValueError):
        raise InputError(
            f"{path}: `reference` must be a node, a list of nodes or 'all' (got {reference!r})"
        ) from None
    if not refs or len(set(refs)) != len(refs):
        raise InputError(f"{path}: `reference` lists no node, or one twice (got {refs})")
    for ref in refs:
        _choose_reference(path, records, ref)  # an error naming the file's references
    return refs


def _against(file: _File, ref: int, layout: str) -> FrfSet:
    """The FRF set of a file's points against one reference node."""
    path, every, records, units = file.path, file.every, file.records, file.units
    ignored = _ignored(path, every)
    points = _one_per_point(path, records, ref)
    nodes = sorted(points.by_node)
    chosen = [points.by_node[n] for n in nodes]
    response_type = _check_alike(path, chosen)
    coordinates = _with_point_coordinates(
        path,
        file.coordinates,
        ref,
        nodes,
        file.geometry,
        require_coordinates=file.require_coordinates,
    )
    locations, reference_location = _locations(coordinates, nodes, ref)
    transmissibility = _transmissibility(chosen[0])
    # a transmissibility has an accelerance's form in any like-over-like quantity (module
    # _transmissibility): 1 − ω² Σ …
    frf_type = cast(
        FrfType, "accelerance" if transmissibility else FRF_TYPE_OF_RESPONSE[response_type]
    )
    frequency, values = _values_in_si(path, chosen, frf_type, units)
    first = chosen[0]
    coherence = _coherence(path, every, ref, nodes, first) if layout == "roving hammer" else None
    frequency, values, coherence = _without_nyquist(path, chosen, frequency, values, coherence)
    estimator, tau, averages = _frf_id_fields(chosen)
    bandwidth = _bandwidth_of(chosen)
    force_band = _force_band_of(chosen)
    frfs = FrfSet(
        frequency=frequency,
        values=values,
        frf_type=frf_type,
        nodes=tuple(nodes),
        locations=locations,
        reference_node=ref,
        reference_location=reference_location,
        coherence=coherence,
        n_averages=averages,
        exponential_window_s=tau,
        estimator=estimator,
        source=str(path),
        metadata={
            "layout": layout,
            "left_out": points.left_out,
            "unused_data_sets": sorted(points.unused),
            **points.unused_by_kind(ref),
            "ignored_data_sets": ignored,
            "directions": {int(n): int(_point_of(points.by_node[n], ref)[1]) for n in nodes},
            **({} if bandwidth is None else {"bandwidth_hz": bandwidth}),
            **({} if force_band is None else {"force_band_hz": force_band}),
            **({} if transmissibility is None else {"transmissibility": transmissibility}),
        },
    )
    return frfs.with_usual_phase()  # an analyser's e^(-iωt) undone (vtb_siglab's case 2)


def _ignored(path: Path, every: list[_Record]) -> list[int]:
    """The data sets 58 of other function types than FRF and coherence (logged)."""
    ignored = [r.index for r in every if r.func_type not in (FREQUENCY_RESPONSE, COHERENCE)]
    if ignored:
        log.info(
            "%s: %s of other function types than FRF (4) and coherence (6) ignored",
            path,
            plural(len(ignored), "data set"),
        )
    return ignored


def _point_of(record: _Record, ref: int) -> tuple[int, int]:
    """The point an FRF against the reference node measures: its other node and direction."""
    if record.rsp_node == ref:
        return record.ref_node, record.ref_dir
    return record.rsp_node, record.rsp_dir


@dataclass(frozen=True)
class _Points:
    """The FRF of each point against the reference, and what was left out."""

    by_node: dict[int, _Record]
    left_out: int
    """FRFs not against the reference, in another direction, or a reciprocal pair's other."""
    unused: list[int]
    """Their data sets' numbers."""
    usual: int = 3
    """The direction most points share (1, 2, 3: x, y, z), the one kept."""
    other_direction: tuple[_Record, ...] = ()
    """The FRFs against the reference in another direction (left out: a shape has one)."""
    reciprocal: tuple[int, ...] = ()
    """The data sets left out as a reciprocal pair's second."""

    def unused_by_kind(self, ref: int) -> dict[str, Any]:
        """What was left out, by why (``run.json`` and identify's console line): the data sets
        not against the reference, the points of another direction (named with it) and the
        reciprocal pairs' seconds."""
        other = set(self.unused) - set(self.reciprocal)
        other -= {r.index for r in self.other_direction}
        out: dict[str, Any] = {
            "not_against_reference": sorted(other),
            "reciprocal_second": sorted(self.reciprocal),
        }
        if self.other_direction:
            directions = sorted({abs(_point_of(r, ref)[1]) for r in self.other_direction})
            out["other_direction"] = {
                "usual": AXIS_NAMES.get(self.usual, str(self.usual)),
                "direction": ", ".join(AXIS_NAMES.get(d, str(d)) for d in directions),
                "nodes": sorted({_point_of(r, ref)[0] for r in self.other_direction}),
                "data_sets": sorted(r.index for r in self.other_direction),
            }
        return out


AXIS_NAMES = {1: "x", 2: "y", 3: "z"}
"""UFF's direction codes (their magnitude) by name."""


def _one_per_point(path: Path, records: list[_Record], ref: int) -> _Points:
    """The FRFs against the reference, one per point, in the direction most of them share.

    Of a reciprocal pair (both H_ij and H_ji) the one with the sensor at the reference is kept;
    the same FRF twice is an InputError.  What is left out is logged.
    """
    mine = [r for r in records if ref in (r.rsp_node, r.ref_node)]
    left_out = len(records) - len(mine)
    unused = [r.index for r in records if ref not in (r.rsp_node, r.ref_node)]
    usual = Counter(abs(_point_of(r, ref)[1]) for r in mine).most_common(1)[0][0]
    by_node: dict[int, _Record] = {}
    other_direction: list[_Record] = []
    reciprocal: list[int] = []
    for r in mine:
        node, direction = _point_of(r, ref)
        if abs(direction) != usual:
            left_out += 1
            unused.append(r.index)
            other_direction.append(r)
            continue
        kept = by_node.get(node)
        if kept is None:
            by_node[node] = r
            continue
        if (kept.rsp_node, kept.ref_node) == (r.rsp_node, r.ref_node):
            raise InputError(
                f"{path}: data sets {kept.index} and {r.index} are both the FRF between "
                f"nodes {r.rsp_node} and {r.ref_node}; keep one"
            )
        left_out += 1  # both H_ij and H_ji: keep the one with the sensor at the reference
        if r.rsp_node == ref and kept.rsp_node != ref:
            by_node[node] = r
        unused.append(r.index if by_node[node] is not r else kept.index)
        reciprocal.append(unused[-1])
    if left_out:
        log.info(
            "%s: %d FRFs not against reference node %d (or in another direction) left out",
            path,
            left_out,
            ref,
        )
    return _Points(by_node, left_out, unused, usual, tuple(other_direction), tuple(reciprocal))


def _transmissibility(record: _Record) -> str | None:
    """``"acceleration over acceleration"`` (or velocity, displacement) for a response over the
    same response (record 10, field 1 = record 9's), else None (a response per force).

    A base-excited shaker test's response over the base's (or two sensors'): with the base's
    motion y, the relative motion z = x − y obeys M z̈ + C ż + K z = −M r ÿ, so
    ẍ/ÿ = 1 − ω² Σ_r ψ_r/(ω_r² − ω² + 2iζ_rω_rω), an accelerance's form whose force is the
    base's inertia load: its poles are the structure's (base fixed), its constants the shapes
    times each mode's participation, with no force to mass-normalise them.
    """
    if record.denominator != record.quantity or record.quantity not in RESPONSE_OF_CODE:
        return None
    response = RESPONSE_OF_CODE[record.quantity]
    return f"{response} over {response}"


def _check_alike(path: Path, chosen: list[_Record]) -> str:
    """The response type the chosen FRFs share; they must share it and the frequency axis."""
    first = chosen[0]
    for record in chosen[1:]:
        if record.quantity != first.quantity:
            raise InputError(
                f"{path}: data sets {first.index} and {record.index} are FRFs of different types "
                f"({record.quantity} against {first.quantity} in record 9); give one type"
            )
        if _transmissibility(record) != _transmissibility(first):
            raise InputError(
                f"{path}: data sets {first.index} and {record.index} are one per force and one "
                "a transmissibility (record 10, field 1); give one kind"
            )
        _check_same_abscissa(path, first, record, "frequency axis")
    return RESPONSE_OF_CODE[first.quantity]


def _with_point_coordinates(
    path: Path,
    coordinates: dict[int, tuple[float, float, float]],
    ref: int,
    nodes: list[int],
    geometry: Path | str | None,
    *,
    require_coordinates: bool,
) -> dict[int, tuple[float, float, float]]:
    """The coordinates, every point's there: NaN for those without (logged) when none are
    required, else an InputError naming ``--geometry``.  The reference may lack them."""
    if ref not in coordinates and ref not in nodes and any(n in coordinates for n in nodes):
        # a fixed accelerometer is often not in the geometry: NaN below
        log.info(
            "%s: reference node %d has no coordinates (none needed: shapes are at the points)",
            path,
            ref,
        )
    missing = [n for n in nodes if n not in coordinates]
    if missing and not require_coordinates:
        log.info(
            "%s: %s %s %s no coordinates (FRFs need none; shapes and maps will ask for `geometry`)",
            path,
            noun(len(missing), "node"),
            _listed(missing),
            noun(len(missing), "has", "have"),
        )
        return {**coordinates, **{n: (np.nan, np.nan, np.nan) for n in missing}}
    if missing:
        where = "" if geometry is None else f" or {geometry}"
        raise InputError(
            f"{path}: node{'s' if len(missing) > 1 else ''} {_listed(missing)} ha"
            f"{'ve' if len(missing) > 1 else 's'} no coordinates in {path}{where}; shapes need "
            "them: add data set 15 or give the file of coordinates as `geometry`"
        )
    return coordinates


def _values_in_si(
    path: Path, chosen: list[_Record], frf_type: FrfType, units: _Units
) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
    """The frequency axis (Hz) and the FRFs in SI units, their direction signs applied."""
    first = chosen[0]
    response_type = RESPONSE_OF_CODE[first.quantity]
    frequency_scale = _scale(path, first, "frequency", _normal_label(first.labels[0]), units)
    bandwidth = _bandwidth_of(chosen)
    top = None if bandwidth is None else bandwidth / frequency_scale  # in the file's unit
    values = np.asarray(
        [
            _in_si(
                path,
                record,
                _frf_scale(path, record, response_type, units)
                * _sign(path, record, record.rsp_dir)
                * _sign(path, record, record.ref_dir),
                "the FRF's",
                ABSURD_FRF,
                FRF_UNITS[frf_type],
                top,
            )
            for record in chosen
        ],
        dtype=complex,
    )
    return first.x * frequency_scale, values


def _without_nyquist(
    path: Path,
    chosen: list[_Record],
    frequency: NDArray[np.float64],
    values: NDArray[np.complex128],
    coherence: NDArray[np.float64] | None,
) -> tuple[NDArray[np.float64], NDArray[np.complex128], NDArray[np.float64] | None]:
    """Frequency, FRFs and coherence without the last line if some record has NaN or inf
    there (issue 25, item 4: OpenModal writes NaN on one record's Nyquist line; logged)."""
    nyquist = [r for r in chosen if r.nyquist_nan]
    if coherence is not None and not np.all(np.isfinite(coherence[:, -1])):
        nyquist.append(chosen[int(np.argmin(np.isfinite(coherence[:, -1])))])
    if not nyquist:
        return frequency, values, coherence
    log.info(
        "%s%s: NaN or infinite on the last line, %g Hz (the Nyquist line; some exports write "
        "it so): that line dropped from every FRF",
        nyquist[0].where(path),
        "" if len(nyquist) == 1 else f" and {noun(len(nyquist) - 1, 'another')} ",
        frequency[-1],
    )
    return frequency[:-1], values[:, :-1], None if coherence is None else coherence[:, :-1]


def read_frf_uff(
    path: Path | str, geometry: Path | str | None = None, reference: int | None = None
) -> FrfSet:
    """Read the FRFs of a Universal File against one reference node.

    The one FRF reader: :func:`read_frfs` (any layout — roving
    hammer, roving accelerometer, several references —, z kept), with points allowed to lack
    coordinates (FRFs need none: they get NaN, and a step that needs them asks for
    ``--geometry``) and the set negated back where its driving point reads with negative
    modal constants (:meth:`~racketdyn.measurement.records.FrfSet.with_positive_driving_point`).

    Parameters
    ----------
    path : Path or str
        Universal File with data sets 58 or 58b of function type 4 (FRF), complex.  The FRF
        type follows the ordinate (numerator) type of record 9: 8 displacement → receptance,
        11 velocity → mobility, 12 acceleration → accelerance; the denominator (record 10)
        must be a force (13) or left unknown (0).  Coherences (function type 6) of the same
        node pairs are read when every point has one.  Node coordinates (data set 15 or 2411,
        m, or in data set 164's unit) may be in the same file.
    geometry : Path or str, optional
        A second Universal File with node coordinates; its nodes take precedence.
    reference : int, optional
        The reference node when the file has FRFs against several (``--reference``).

    Returns
    -------
    FrfSet
        Points ordered by node number, frequencies in Hz, values in SI units of the FRF type.
        Files written by :func:`racketdyn.io.uff.write_frf_uff` give back their estimator,
        exponential window, averages and bandwidth; other files get ``estimator="file"``.

    Raises
    ------
    InputError
        Missing, damaged or truncated file; time records instead of FRFs; records on different
        frequency axes; two FRFs of one point; NaN in the data; several references and none
        chosen.
    """
    frfs = read_frfs(path, geometry, reference, require_coordinates=False)
    return frfs.with_positive_driving_point()
