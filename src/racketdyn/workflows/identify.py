"""Steps ``identify`` and ``compare``: modal models from FRFs, and free against hand-held.

``identify`` writes ``modes.csv``, ``modal_model.json`` (what ``predict --modal`` takes),
``modes.uff`` (UFF 55), ``fit_quality.csv`` and ``run.json``.  ``compare`` writes the same per
support (suffixes ``_free``, ``_hand``), ``comparison.csv`` (modes paired by MAC) and ``run.json``
(with the first mode's nodes along the axis, ``first_mode_nodes_m``).
Figures come from the caller's hook.
"""

from __future__ import annotations

import csv
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.errors import InputError, require_speeds
from racketdyn.impact.result import SHOWN_SPEED_MPS
from racketdyn.io.frf_layout import read_frfs
from racketdyn.io.uff import write_modes_uff
from racketdyn.modal.identify import Identification, identify
from racketdyn.modal.shapes import pair_modes
from racketdyn.plausibility import check_speeds
from racketdyn.racket import Racket
from racketdyn.racket_modal.identify import name_if_racket
from racketdyn.racket_modal.shapes import axis_nodes
from racketdyn.workflows.inputs import RacketInput, load_racket_input
from racketdyn.workflows.run import (
    Progress,
    StepResult,
    command_record,
    finish_run,
    report,
    run_step,
    sha256,
)

__all__ = [
    "CHECK_SPEED_MPS",
    "CompareResult",
    "IdentifyResult",
    "ModeComparison",
    "compare_modes",
    "identify_file",
    "run_compare",
    "run_identify",
    "write_mode_comparison",
    "write_model",
]

CHECK_SPEED_MPS = SHOWN_SPEED_MPS
"""Default incoming ball speed of ``compare``'s Fig. 15 check, m/s (the paper's 20 m/s)."""


def _band(band_hz: Sequence[float] | None) -> tuple[float, float] | None:
    if band_hz is None:
        return None
    values = [float(v) for v in band_hz]
    if len(values) != 2 or not 0.0 <= values[0] < values[1]:
        raise InputError(f"--band takes two frequencies low,high in Hz (got {band_hz!r})")
    return (values[0], values[1])


def identify_file(
    path: str | os.PathLike[str],
    racket: Racket,
    support: str,
    *,
    geometry: str | os.PathLike[str] | None = None,
    band_hz: Sequence[float] | None = None,
    max_order: int = 60,
    pin_hz: Sequence[float] = (),
    exclude_hz: Sequence[float] = (),
    reference: int | None = None,
    racket_given: bool = True,
) -> Identification:
    """Read FRFs (UFF 58, any layout) and identify their modal model.

    The FRFs are read against one reference (:func:`racketdyn.io.frf_layout.read_frfs`:
    roving hammer, roving accelerometer or several references), identified on any structure
    (:func:`racketdyn.modal.identify.identify`), and their modes named the racket way only
    when the points are a racket's (:func:`racketdyn.racket_modal.identify.name_if_racket`);
    how they were named is ``model.metadata["naming"]``.

    Parameters
    ----------
    path : path
        FRFs, UFF 58 function type 4 with geometry (or ``geometry``).
    racket : Racket
        The racket the points may belong to (its head names the modes).
    support : str
        ``free`` or ``hand``, recorded on the model.
    geometry : path, optional
        Node coordinates if not in the file.
    band_hz : (low, high), optional
        Band, Hz (default 40 Hz to the FRFs' bandwidth:
        :func:`racketdyn.modal.identify.default_band`).
    max_order : int
        Highest model order.
    pin_hz, exclude_hz : sequence of float
        Modes forced in or left out, by approximate frequency, Hz.
    reference : int, optional
        Reference node when the file has several (``--reference``).
    racket_given : bool
        True when the user named the racket (then its modes are named whatever the points).
    """
    frfs = read_frfs(Path(path), None if geometry is None else Path(geometry), reference)
    found = identify(
        frfs,
        _band(band_hz),
        max_order=max_order,
        pin_hz=list(pin_hz),
        exclude_hz=list(exclude_hz),
        support=support,
    )
    found, naming = name_if_racket(found, racket, racket_given)
    metadata = {**found.model.metadata, "naming": naming, "layout": frfs.metadata.get("layout")}
    return replace(found, model=replace(found.model, metadata=metadata))


def write_model(identification: Identification, out: Path, label: str = "") -> list[Path]:
    """``modes<label>.csv``, ``modal_model<label>.json``, ``modes<label>.uff``,
    ``fit_quality<label>.csv`` (x, y[, z] as the FRFs' points) and ``dropped_modes<label>.csv``
    of one identification; returns the paths."""
    model = identification.model
    paths = [out / f"modes{label}.csv", out / f"modal_model{label}.json", out / f"modes{label}.uff"]
    identification.write_modes_csv(paths[0])
    model.write_json(paths[1])
    write_modes_uff(model, paths[2], nodes=identification.frfs.nodes)
    quality = out / f"fit_quality{label}.csv"
    locations = identification.frfs.locations
    axes = "xyz"[: locations.shape[1]]
    with quality.open("w", encoding="utf-8") as handle:
        handle.write("node," + ",".join(f"{a}_m" for a in axes) + ",fit_error\n")
        for node, point, error in zip(
            identification.frfs.nodes, locations, identification.fit.error, strict=True
        ):
            coordinates = ",".join(f"{c:.6g}" for c in point)
            handle.write(f"{node},{coordinates},{error:.4g}\n")
    dropped = out / f"dropped_modes{label}.csv"
    identification.write_dropped_csv(dropped)
    return [*paths, quality, dropped]


@dataclass
class IdentifyResult(StepResult):
    """What :func:`run_identify` identified and wrote.

    Attributes
    ----------
    identification : Identification
        Every intermediate result; ``identification.model`` is the modal model.
    racket : Racket
        The racket (head for the figures).
    """

    identification: Identification | None = None
    racket: Racket | None = None


@run_step
def run_identify(
    frfs: str | os.PathLike[str],
    out: str | os.PathLike[str],
    *,
    support: str = "free",
    racket: RacketInput = None,
    geometry: str | os.PathLike[str] | None = None,
    band_hz: Sequence[float] | None = None,
    max_order: int = 60,
    pin_hz: Sequence[float] = (),
    exclude_hz: Sequence[float] = (),
    reference: int | None = None,
    command: Sequence[str] | None = None,
    figures: Callable[[IdentifyResult, Path], list[Path]] | None = None,
    progress: Progress | None = None,
) -> IdentifyResult:
    """Identify a modal model from FRFs and write the run folder.

    Parameters
    ----------
    frfs : path
        FRFs, UFF 58 function type 4 (e.g. ``frfs.uff`` of :func:`~racketdyn.workflows.run_frf`).
    out : path
        Output folder (created if missing).
    support : {"free", "hand"}
        Support of the test.
    racket : Racket, path or None
        Racket (its head names the modes); None for the built-in racket, whose modes are
        named only when the points lie on its outline.
    geometry, band_hz, max_order, pin_hz, exclude_hz, reference
        As for :func:`identify_file`.
    command : sequence of str, optional
        The command as called, for run.json.
    figures : callable, optional
        ``figures(result, out) -> paths`` (none without it).
    progress : callable, optional
        ``progress(what, done, total)`` for a progress display.
    """
    the_racket, provenance = load_racket_input(racket)
    out_dir = Path(out)
    report(progress, f"identifying {Path(frfs).name}")
    found = identify_file(
        frfs,
        the_racket,
        support,
        geometry=geometry,
        band_hz=band_hz,
        max_order=max_order,
        pin_hz=pin_hz,
        exclude_hz=exclude_hz,
        reference=reference,
        racket_given=racket is not None,
    )
    result = IdentifyResult(
        out_dir, write_model(found, out_dir), identification=found, racket=the_racket
    )
    inputs = {
        "frfs_file": str(Path(frfs).resolve()),
        "frfs_sha256": sha256(Path(frfs)),
        **provenance,
        "support": support,
        "band_hz": list(found.band_hz),
        "max_order": max_order,
        "pin_hz": list(pin_hz),
        "exclude_hz": list(exclude_hz),
        "reference_node": found.frfs.reference_node,
        "layout": found.model.metadata.get("layout"),
        "naming": found.model.metadata.get("naming"),
        "face_mapping": found.model.metadata.get("face_mapping"),
        "scaling": found.model.scaling,
        "scaling_note": found.scaling_note,
        "modes": found.model.summary()["modes"],
        "dropped": found.model.metadata["dropped"],
    }
    return finish_run(result, inputs, command_record(command, "identify"), figures)


@dataclass(frozen=True)
class ModeComparison:
    """Free and hand-held modes paired by MAC, and the first mode's nodes along the axis.

    Attributes
    ----------
    rows : list of dict
        One per pair: ``mode`` (the free mode's name), ``frequency_free_hz``,
        ``frequency_hand_hz``, ``frequency_shift_percent``, ``damping_free``, ``damping_hand``,
        ``damping_ratio_hand_over_free``, ``mac``.
    nodes_free, nodes_hand : ndarray
        Nodes of the first mode along the long axis, m from the butt.
    """

    rows: list[dict[str, Any]]
    nodes_free: NDArray[np.float64]
    nodes_hand: NDArray[np.float64]


def compare_modes(free: Identification, hand: Identification, racket: Racket) -> ModeComparison:
    """Pair the free and hand-held modes by MAC and find the first mode's nodes on the axis.

    Parameters
    ----------
    free, hand : Identification
        The two identifications.
    racket : Racket
        The racket (its length bounds the axis searched for nodes).
    """
    pairing = pair_modes(free.model, hand.model)
    rows: list[dict[str, Any]] = []
    for a, b, value in zip(pairing.first, pairing.second, pairing.mac, strict=True):
        fa, fb = free.model.frequency[a], hand.model.frequency[b]
        za, zb = free.model.damping_ratio[a], hand.model.damping_ratio[b]
        rows.append(
            {
                "mode": free.model.names[a],
                "frequency_free_hz": fa,
                "frequency_hand_hz": fb,
                "frequency_shift_percent": 100 * (fb / fa - 1),
                "damping_free": za,
                "damping_hand": zb,
                "damping_ratio_hand_over_free": zb / za,
                "mac": value,
            }
        )
    axis = (0.0, racket.length_m)
    return ModeComparison(rows, axis_nodes(free.model, 0, axis), axis_nodes(hand.model, 0, axis))


def write_mode_comparison(comparison: ModeComparison, out: Path) -> Path:
    """``comparison.csv``: the pairs of :func:`compare_modes`, one row per pair and nothing
    else (the first mode's nodes go into run.json as ``first_mode_nodes_m``)."""
    table = out / "comparison.csv"
    rows = comparison.rows
    with table.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]) if rows else ["mode"])
        writer.writeheader()
        for row in rows:
            writer.writerow(
                {k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()}
            )
    return table


def _first_mode_nodes(comparison: ModeComparison) -> dict[str, list[float]]:
    """The first mode's nodes along the long axis by support, m from the butt to 0.1 mm: the
    ``first_mode_nodes_m`` of compare's run.json."""
    return {
        "free": [round(float(v), 4) for v in comparison.nodes_free],
        "hand": [round(float(v), 4) for v in comparison.nodes_hand],
    }


@dataclass
class CompareResult(StepResult):
    """What :func:`run_compare` identified and wrote.

    Attributes
    ----------
    free, hand : Identification
        The two identifications.
    racket : Racket
        The racket.
    comparison : ModeComparison
        The modes paired by MAC and the first mode's nodes (``comparison.csv``).
    speed : float
        Incoming ball speed of the Fig. 15 check, m/s.
    """

    free: Identification | None = None
    hand: Identification | None = None
    racket: Racket | None = None
    comparison: ModeComparison | None = None
    speed: float = CHECK_SPEED_MPS


@run_step
def run_compare(
    free: str | os.PathLike[str],
    hand: str | os.PathLike[str],
    out: str | os.PathLike[str],
    *,
    racket: RacketInput = None,
    geometry: str | os.PathLike[str] | None = None,
    band_hz: Sequence[float] | None = None,
    max_order: int = 60,
    pin_hz: Sequence[float] = (),
    exclude_hz: Sequence[float] = (),
    speed: float = CHECK_SPEED_MPS,
    allow_implausible: bool = False,
    reference: int | None = None,
    command: Sequence[str] | None = None,
    figures: Callable[[CompareResult, Path], list[Path]] | None = None,
    progress: Progress | None = None,
) -> CompareResult:
    """Identify free and hand-held FRFs, pair their modes by MAC, write the run folder.

    Parameters
    ----------
    free, hand : path
        FRFs of the freely supported and of the hand-held racket (UFF 58).
    out : path
        Output folder (created if missing).
    racket : Racket, path or None
        Racket; None for the built-in racket.
    geometry, band_hz, max_order, pin_hz, exclude_hz, reference
        As for :func:`identify_file`, for both.
    speed : float
        Incoming ball speed of the paper's Fig. 15 check with the identified models, m/s
        (default 20, the paper's).
    allow_implausible : bool
        Let a speed beyond those of play (75 m/s) through (:mod:`racketdyn.plausibility`).
    command : sequence of str, optional
        The command as called, for run.json.
    figures : callable, optional
        ``figures(result, out) -> paths`` (none without it).
    progress : callable, optional
        ``progress(what, done, total)`` for a progress display.
    """
    (check_speed,) = require_speeds("--speed", [speed])
    check_speeds("--speed", [check_speed], "ball_speed_mps", allow_implausible)
    the_racket, provenance = load_racket_input(racket)
    out_dir = Path(out)
    options: dict[str, Any] = {
        "geometry": geometry,
        "band_hz": band_hz,
        "max_order": max_order,
        "pin_hz": pin_hz,
        "exclude_hz": exclude_hz,
        "reference": reference,
        "racket_given": racket is not None,
    }
    report(progress, f"identifying {Path(free).name}")
    found_free = identify_file(free, the_racket, "free", **options)
    report(progress, f"identifying {Path(hand).name}")
    found_hand = identify_file(hand, the_racket, "hand", **options)
    written = write_model(found_free, out_dir, "_free") + write_model(found_hand, out_dir, "_hand")
    comparison = compare_modes(found_free, found_hand, the_racket)
    written.append(write_mode_comparison(comparison, out_dir))
    result = CompareResult(
        out_dir,
        written,
        free=found_free,
        hand=found_hand,
        racket=the_racket,
        comparison=comparison,
        speed=float(check_speed),
    )
    inputs = {
        "free_file": str(Path(free).resolve()),
        "hand_file": str(Path(hand).resolve()),
        **provenance,
        "band_hz": list(found_free.band_hz),
        "max_order": max_order,
        "modes_free": found_free.model.summary()["modes"],
        "modes_hand": found_hand.model.summary()["modes"],
        "first_mode_nodes_m": _first_mode_nodes(comparison),
        "fig15_ball_speed_mps": float(check_speed),
    }
    return finish_run(result, inputs, command_record(command, "compare"), figures)
