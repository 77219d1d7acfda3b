"""Steps ``identify`` and ``compare``: modal models from FRFs, and free against hand-held.

``identify`` writes ``modes.csv``, ``modal_model.json`` (what ``predict --modal`` takes),
``modes.uff`` (UFF 55), ``fit_quality.csv`` and ``run.json``.  ``compare`` writes the same per
support (suffixes ``_free``, ``_hand``), ``comparison.csv`` (modes paired by MAC) and ``run.json``
(with the first mode's nodes along the axis, ``first_mode_nodes_m``).  When the FRFs come from
the virtual rig, each identification is held against the rig's truth in
``truth_comparison<label>.csv`` (:mod:`racketdyn.workflows.truth`).
Figures come from the caller's hook.
"""

from __future__ import annotations

import csv
import dataclasses
import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import NDArray

from racketdyn.ball import Ball
from racketdyn.errors import InputError, require_numbers, require_speeds
from racketdyn.hand import Hand
from racketdyn.impact.result import SHOWN_SPEED_MPS
from racketdyn.io.frf_layout import ReferenceChoice, read_frfs, reference_choice
from racketdyn.io.uff import write_modes_uff
from racketdyn.measurement.records import FrfReferences, FrfSet
from racketdyn.modal.identify import SELECTION, Identification, identify
from racketdyn.modal.model import ModalModel
from racketdyn.modal.poles import SelectionRules, require_rules
from racketdyn.modal.polyreference import DEFAULT_MAX_ORDER
from racketdyn.modal.shapes import pair_modes
from racketdyn.plausibility import check_speeds
from racketdyn.racket import HeadEllipse, Racket
from racketdyn.racket_modal.face import looks_like_racket
from racketdyn.racket_modal.identify import name_after, name_if_racket, pair_racket_modes
from racketdyn.racket_modal.shapes import BALL_MODE_NAME, axis_nodes
from racketdyn.workflows._figure_io import store
from racketdyn.workflows.figure_data import (
    FIGURES_FILE,
    IdentifiedRebound,
    defer_figure_data,
    identified_rebound,
    write_figure_data,
)
from racketdyn.workflows.frf_figures import BallFrfs, FitFigures, ball_frfs, fit_figures
from racketdyn.workflows.inputs import (
    ball_location,
    load_racket_input,
    with_racket_of_run,
)
from racketdyn.workflows.run import (
    StepResult,
    report,
    run_step,
    sha256,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup
from racketdyn.workflows.shape_figures import (
    AxisNodes,
    IdentifiedShapes,
    axis_node_curves,
    identified_shapes,
)
from racketdyn.workflows.truth import TRUTH_FILES, write_truth_comparisons

if TYPE_CHECKING:
    import xarray as xr

__all__ = [
    "BALL_COMPARISON_FILE",
    "BALL_MODE_SHOWN",
    "CHECK_SPEED_MPS",
    "DEFAULT_IDENTIFY",
    "NO_COORDINATES",
    "BallCompareResult",
    "CompareResult",
    "IdentifyOptions",
    "IdentifyResult",
    "ModeComparison",
    "ball_mode_share",
    "checked_band",
    "compare_modes",
    "compare_with_ball",
    "coordinates_note",
    "identify_file",
    "node_showing_ball_mode",
    "run_compare",
    "run_compare_ball",
    "run_identify",
    "write_mode_comparison",
    "write_model",
]

CHECK_SPEED_MPS = SHOWN_SPEED_MPS
"""Default incoming ball speed of ``compare``'s Fig. 15 check, m/s (the paper's 20 m/s)."""


def checked_band(band_hz: Sequence[float]) -> tuple[float, float]:
    """A band to identify over, checked: two frequencies, low before high, none negative.

    Parameters
    ----------
    band_hz : sequence of float
        (low, high), Hz.

    Returns
    -------
    tuple of float
        (low, high), Hz.

    Raises
    ------
    InputError
        Naming what is wrong with ``band_hz`` and the band that would do.
    """
    values = require_numbers("`band_hz`", band_hz, "Hz")
    given = ",".join(f"{v:g}" for v in values)
    if len(values) != 2:
        raise InputError(f"`band_hz` takes two frequencies low,high in Hz (got {given})")
    low, high = values
    if low < 0:
        raise InputError(f"`band_hz` {given}: {low:g} Hz is below 0 Hz; give 0 Hz or above")
    if low >= high:
        fix = f"give {high:g},{low:g}" if low > high else "give a high end above the low one"
        raise InputError(f"`band_hz` {given}: the low end is not below the high end; {fix}")
    return (low, high)


@dataclass(frozen=True)
class IdentifyOptions:
    """How FRFs are read and identified: what ``identify``, ``compare`` and ``compare
    --ball-at`` share (each of a step's identifications takes the same).

    Attributes
    ----------
    geometry : path, optional
        Node coordinates if not in the file (UFF 15/2411, or CSV node,x_m,y_m in m).
    band_hz : (low, high), optional
        Band, Hz (default from below the first clear peak, at most 40 Hz, to the FRFs'
        bandwidth: :func:`racketdyn.modal.identify.default_band`).
    max_order : int, optional
        Highest model order (default 60 against one reference, 30 against several:
        :func:`racketdyn.modal.identify.identify`).
    pin_hz, exclude_hz : sequence of float
        Modes forced in or left out, by approximate frequency, Hz (one number, or one text
        ``"600,700"`` as the command line spells them; ``band_hz`` too, ``"40,1000"``).
    reference : int, "all" or sequence of int, optional
        Reference node when the file has several; ``"all"`` or several nodes (``"201,203"``
        as the command line spells them) identify from those references together
        (:func:`racketdyn.io.frf_layout.read_frfs`, the poly-reference LSCF).
    rules : SelectionRules
        The rules of the automatic pole selection (default
        :data:`racketdyn.modal.identify.SELECTION`); Python only, the command line has no
        option for them.  Other rules are recorded in run.json (``selection_rules``).
    """

    geometry: str | os.PathLike[str] | None = None
    band_hz: Sequence[float] | None = None
    max_order: int | None = None
    pin_hz: Sequence[float] = ()
    exclude_hz: Sequence[float] = ()
    reference: ReferenceChoice | str | Sequence[int] = None
    rules: SelectionRules = SELECTION

    def __post_init__(self) -> None:
        require_rules("IdentifyOptions", self.rules)
        object.__setattr__(self, "reference", reference_choice(self.reference))
        if self.band_hz is not None:
            object.__setattr__(self, "band_hz", checked_band(self.band_hz))
        for name in ("pin_hz", "exclude_hz"):  # as the command line spells them too: "600,700"
            values = require_numbers(f"`{name}`", getattr(self, name), "Hz")
            object.__setattr__(self, name, tuple(values))

    def record(self) -> dict[str, Any]:
        """What run.json keeps of them (the band used is the identification's own)."""
        several = self.reference == "all" or isinstance(self.reference, tuple)
        default = DEFAULT_MAX_ORDER if several else 60
        recorded: dict[str, Any] = {
            "max_order": default if self.max_order is None else self.max_order,
            "pin_hz": list(self.pin_hz),
            "exclude_hz": list(self.exclude_hz),
        }
        if self.rules != SELECTION:  # the default's run.json as before
            rules = dataclasses.asdict(self.rules)
            recorded["selection_rules"] = {**rules, "stability": self.rules.stability.name}
        return recorded


DEFAULT_IDENTIFY = IdentifyOptions()
"""The options of an identification the user says nothing of."""


def identify_file(
    path: str | os.PathLike[str],
    racket: Racket,
    support: str,
    options: IdentifyOptions = DEFAULT_IDENTIFY,
    *,
    racket_given: bool = True,
    ball_at: Sequence[float] | None = None,
    names_from: str | os.PathLike[str] | ModalModel | None = None,
    hand: Hand | None = None,
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
    options : IdentifyOptions
        Geometry, band, model order, pins and exclusions, reference node.
    racket_given : bool
        True when the user named the racket (then its modes are named whatever the points).
    ball_at : sequence of float, optional
        Where a ball was fixed on the strings during the test (x, y), m (``--ball-at``, the
        paper's compound test): its mode is named ``"ball on the strings"``.
    names_from : path or ModalModel, optional
        A modal model of the same racket (or its JSON) whose names to give the modes by MAC
        pair (:func:`racketdyn.racket_modal.identify.name_after`): the free test's for a
        hand-held test, as ``compare`` names it (``--names-from``).
    hand : Hand, optional
        The hand that held the racket (``support`` ``hand`` only; None: the default
        :class:`~racketdyn.hand.Hand`): the node counts are read against the frame it holds
        (:func:`racketdyn.racket_modal.identify.name_if_racket`).
    """
    ball = None if ball_at is None else ball_location(ball_at, racket)
    reference_model = None
    if isinstance(names_from, ModalModel):
        reference_model, pairs_in = names_from, f"among the {names_from.support} modes"
    elif names_from is not None:
        reference_model = ModalModel.read_json(Path(names_from))
        pairs_in = f"in {Path(names_from).name}"
    if reference_model is not None and not reference_model.has_locations:
        raise InputError(
            f"`names_from` {names_from}: a model without node coordinates; its modes cannot "
            "be paired with these by shape"
        )
    frfs = read_frfs(
        Path(path),
        None if options.geometry is None else Path(options.geometry),
        cast(ReferenceChoice, options.reference),
        require_coordinates=False,  # none at all: a model without coordinates; some: refused
    )
    band = options.band_hz
    found = identify(
        frfs,
        None if band is None else (band[0], band[1]),
        max_order=options.max_order,
        pin_hz=list(options.pin_hz),
        exclude_hz=list(options.exclude_hz),
        support=support,
        rules=options.rules,
    )
    found, naming = name_if_racket(found, racket, racket_given, ball, hand)
    if ball is not None and naming.startswith("modes numbered"):
        naming += "; `ball_at` unused: the ball's mode is named only among a racket's modes"
    if reference_model is not None and naming.startswith("modes numbered"):
        naming += "; `names_from` unused: names are given only among a racket's modes"
    elif reference_model is not None:
        renamed = name_after(found.model, reference_model, racket.head)
        changed = sum(a != b for a, b in zip(renamed.names, found.model.names, strict=True))
        naming += (
            f"; {changed} named after their MAC pairs {pairs_in}"
            if changed
            else f"; named as their MAC pairs {pairs_in} are"
        )
        found = replace(found, model=renamed)
    elif support == "hand" and not naming.startswith("modes numbered"):
        naming += HAND_COUNTS
    layout = (frfs if isinstance(frfs, FrfSet) else frfs.sets[0]).metadata.get("layout")
    metadata = {**found.model.metadata, "naming": naming, "layout": layout}
    if isinstance(frfs, FrfReferences):  # the data sets no reference used
        found = replace(
            found,
            frfs=replace(found.frfs, metadata={**found.frfs.metadata, **_unused_by_all(frfs)}),
        )
    return replace(found, model=replace(found.model, metadata=metadata))


def _unused_by_all(frfs: FrfReferences) -> dict[str, Any]:
    """The data sets no reference used, by why (:func:`racketdyn.io.read_frfs`' metadata keys
    ``unused_data_sets``, ``not_against_reference``, ``other_direction``,
    ``reciprocal_second``): a data set against another of the references is used."""
    metas = [s.metadata for s in frfs.sets]
    unused = set.intersection(*(set(m.get("unused_data_sets", [])) for m in metas))
    out: dict[str, Any] = {"unused_data_sets": sorted(unused)}
    turned = [m["other_direction"] for m in metas if m.get("other_direction")]
    if turned:
        out["other_direction"] = {
            **turned[0],
            "nodes": sorted({n for t in turned for n in t["nodes"]}),
            "data_sets": sorted({d for t in turned for d in t["data_sets"]} & unused),
        }
    second = {d for m in metas for d in m.get("reciprocal_second", [])} & unused
    out["reciprocal_second"] = sorted(second)
    apart = set(out.get("other_direction", {}).get("data_sets", [])) | second
    out["not_against_reference"] = sorted(unused - apart)
    return out


HAND_COUNTS = (
    "; `names_from` the free test's modal_model.json names the modes after their free MAC "
    "pairs, as compare does"
)
"""What ``identify --support hand`` adds to its naming line without ``--names-from``."""


NO_COORDINATES = (
    "no node coordinates: frequencies, damping ratios and the shapes by node only; no shape "
    "figures, no node lines, no racket naming, and predict refuses the model; a file of "
    "coordinates as `geometry` (UFF data set 15 or 2411, or CSV node,x_m,y_m in m) adds them"
)
"""What an identification from FRFs without coordinates gives and lacks (console, run.json)."""


def coordinates_note(model: ModalModel) -> str:
    """:data:`NO_COORDINATES` for a model without node coordinates, else empty."""
    return "" if model.has_locations else NO_COORDINATES


def write_model(identification: Identification, out: Path, label: str = "") -> list[Path]:
    """``modes<label>.csv``, ``modal_model<label>.json``, ``modes<label>.uff``,
    ``fit_quality<label>.csv`` (x, y[, z] as the FRFs' points, empty without coordinates; each
    FRF's median coherence over the band and ``noise_only`` 1 where that says it measured noise
    alone, both empty without coherence) and
    ``dropped_modes<label>.csv`` of one identification; returns the paths."""
    model = identification.model
    # modes<label>.uff beside modal_model<label>.json: io.uff.MODES_FILE, model_json_beside
    paths = [out / f"modes{label}.csv", out / f"modal_model{label}.json", out / f"modes{label}.uff"]
    identification.write_modes_csv(paths[0])
    model.write_json(paths[1])
    write_modes_uff(model, paths[2], nodes=identification.frfs.nodes)
    quality = out / f"fit_quality{label}.csv"
    locations = identification.frfs.locations
    axes = "xyz"[: locations.shape[1]]
    n_points = identification.frfs.n_points
    noise = identification.noise_frfs  # empty cells without coherence
    coherence = [""] * n_points if noise is None else [f"{m:.4g}" for m in noise.median_coherence]
    noise_only = [""] * n_points if noise is None else [str(int(n)) for n in noise.noise_only]
    with quality.open("w", encoding="utf-8") as handle:
        handle.write(
            "node," + ",".join(f"{a}_m" for a in axes) + ",fit_error,median_coherence,noise_only\n"
        )
        for node, point, error, median, alone in zip(
            identification.frfs.nodes,
            locations,
            identification.fit.error,
            coherence,
            noise_only,
            strict=True,
        ):
            coordinates = ",".join("" if np.isnan(c) else f"{c:.6g}" for c in point)
            handle.write(f"{node},{coordinates},{error:.4g},{median},{alone}\n")
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
    shape_figures : IdentifiedShapes or None
        What Figs 4–6 and the AutoMAC draw, evaluated with the run's model and racket (in
        ``figures.nc``).
    fit_figures : FitFigures or None
        What the stabilisation diagram and the synthesised FRFs draw (in ``figures.nc``).
    """

    identification: Identification | None = None
    racket: Racket | None = None
    shape_figures: IdentifiedShapes | None = None
    fit_figures: FitFigures | None = None


@run_step
def run_identify(
    frfs: str | os.PathLike[str],
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    options: IdentifyOptions = DEFAULT_IDENTIFY,
    *,
    support: str = "free",
    ball_at: Sequence[float] | None = None,
    names_from: str | os.PathLike[str] | None = None,
) -> IdentifyResult:
    """Identify a modal model from FRFs and write the run folder.

    Parameters
    ----------
    frfs : path
        FRFs, UFF 58 function type 4 (e.g. ``frfs.uff`` of :func:`~racketdyn.workflows.run_frf`).
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, identify uses the racket: its head
        names the modes; with None, the built-in racket's, named only when the points lie on its
        outline; and the run (command, figures, progress).
    options : IdentifyOptions
        How the FRFs are read and identified.
    support : {"free", "hand"}
        Support of the test.
    ball_at, names_from
        As for :func:`identify_file`.
    """
    setup, from_run = with_racket_of_run(setup, frfs)
    the_racket, provenance = load_racket_input(setup.racket)
    provenance |= from_run
    out_dir = Path(out)
    report(setup.progress, f"identifying {Path(frfs).name}")
    found = identify_file(
        frfs,
        the_racket,
        support,
        options,
        racket_given=setup.racket is not None,
        ball_at=ball_at,
        names_from=names_from,
        hand=setup.hand,
    )
    shapes = identified_shapes(found.model, the_racket)
    written = write_model(found, out_dir)
    truth_written, truth_files = write_truth_comparisons(
        out_dir, (found, frfs, ""), words=setup.words
    )
    written += truth_written
    fits = fit_figures(found, the_racket)
    result = IdentifyResult(
        out_dir,
        written,
        identification=found,
        racket=the_racket,
        shape_figures=shapes,
        fit_figures=fits,
    )
    defer_figure_data(result, {"fit_figures": fits}, [shapes.to_xarray])
    inputs = {
        "frfs_file": str(Path(frfs).resolve()),
        "frfs_sha256": sha256(Path(frfs)),
        **provenance,
        "support": support,
        "band_hz": list(found.band_hz),
        **options.record(),
        "max_order": found.model.metadata["max_order"],
        "peaks_in_band": found.model.metadata.get("peaks_in_band"),
        "orders_note": found.model.metadata.get("orders_note"),
        "unexplained_peaks_hz": found.model.metadata.get("unexplained_peaks_hz"),
        "reference_node": found.frfs.reference_node,
        "references": list(found.references),
        "ball_at_m": None if ball_at is None else [float(v) for v in ball_at],
        "names_from": None if names_from is None else str(Path(names_from).resolve()),
        "layout": found.model.metadata.get("layout"),
        "naming": found.model.metadata.get("naming"),
        "face_mapping": found.model.metadata.get("face_mapping"),
        "scaling": found.model.scaling,
        "scaling_note": found.scaling_note,
        "conjugated": found.frfs.metadata.get("conjugated"),
        "coordinates": found.model.has_locations,
        "coordinates_note": coordinates_note(found.model),
        "modes": found.model.summary()["modes"],
        "kept": found.model.metadata.get("kept", []),
        "dropped": found.model.metadata["dropped"],
        "misfit": found.model.metadata.get("misfit"),
        "noise_frfs": found.model.metadata.get("noise_frfs"),
        TRUTH_FILES: truth_files,
    }
    return setup.finish(result, inputs, "identify")


@dataclass(frozen=True)
class ModeComparison:
    """Free and hand-held modes paired by MAC, and the first mode's nodes along the axis.

    Attributes
    ----------
    rows : list of dict
        One per pair: ``mode`` (the free mode's name), ``frequency_free_hz``,
        ``frequency_hand_hz``, ``frequency_shift_percent``, ``damping_free``, ``damping_hand``,
        ``damping_ratio_hand_over_free``, ``mac``, ``note`` (empty); and one per mode of
        either model left without a pair, its partner's columns NaN and ``note`` saying so
        (:data:`UNPAIRED_NOTE`); in order of frequency.
    nodes_free, nodes_hand : ndarray
        Nodes of the first mode along the long axis, m from the butt.
    """

    rows: list[dict[str, Any]]
    nodes_free: NDArray[np.float64]
    nodes_hand: NDArray[np.float64]


def name_after_pairs(
    free: ModalModel, hand: ModalModel, head: HeadEllipse | None = None
) -> ModalModel:
    """The hand-held model with each mode named after its MAC pair among the free modes
    (:func:`racketdyn.racket_modal.identify.name_after`, which ``identify --names-from`` uses
    too).

    Parameters
    ----------
    free, hand : ModalModel
        The freely supported and the hand-held models (names and kinds from their shapes).
    head : HeadEllipse, optional
        The string bed (frame modes pair on the frame's points).

    Returns
    -------
    ModalModel
        ``hand`` with new names (kinds, frequencies and shapes unchanged).
    """
    return name_after(hand, free, head)


UNPAIRED_NOTE = (
    "no {other} mode of its kind with a MAC of {minimum} or more: not in the {other} data, or "
    "its shape changed"
)
"""``comparison.csv``'s ``note`` of a mode left without a pair (``{other}``: the other
support)."""


def on_racket_face(free: ModalModel, hand: ModalModel, racket: Racket, racket_given: bool) -> str:
    """Why the identified models are not a racket's face ("" when they are): compare then
    leaves out what only a racket has (the nodes on its long axis, Figs 6 and 15).

    A model on a racket's face holds face (x, y) locations (3-D lab points on one plane are
    mapped onto the face when they are a racket's: :func:`racketdyn.racket_modal.identify.
    name_if_racket`), on the racket's outline or of a racket the user named."""
    for model in (free, hand):
        if model.n_dimensions != 2:
            return (
                "not a racket's face (points in space): no nodes on the long axis, Fig. 6 or "
                "Fig. 15"
            )
        if not (racket_given or looks_like_racket(model.locations, racket)):
            return (
                "not a racket's face (the points are off its outline; give `racket` for your "
                "racket's): no nodes on the long axis, Fig. 6 or Fig. 15"
            )
    return ""


def compare_modes(
    free: Identification, hand: Identification, racket: Racket | None
) -> ModeComparison:
    """Pair the free and hand-held modes by MAC and find the first mode's nodes on the axis.

    The pairs are :func:`racketdyn.racket_modal.identify.pair_racket_modes`' (a mode pairs
    only with a mode of its own kind where both kinds are known, a frame mode on the frame's
    points); every mode left without a pair is a row too.

    Parameters
    ----------
    free, hand : Identification
        The two identifications.
    racket : Racket or None
        The racket (its head tells frame from string points; its length bounds the axis
        searched for nodes); None for a structure that is not a racket's face
        (:func:`on_racket_face`): the modes are paired by MAC over every point and no nodes
        are sought.
    """
    pairing = pair_racket_modes(
        free.model, hand.model, None if racket is None else racket.head, MINIMUM_PAIR_MAC
    )
    nan = math.nan
    rows: list[dict[str, Any]] = []
    for a, b, value in zip(pairing.first, pairing.second, pairing.mac, strict=True):
        fa, fb = free.model.frequency[a], hand.model.frequency[b]
        za, zb = free.model.damping_ratio[a], hand.model.damping_ratio[b]
        rows.append(_comparison_row(free.model.names[a], (fa, fb), (za, zb), value, ""))
    for model, paired, other in (
        (free.model, pairing.first, "hand-held"),
        (hand.model, pairing.second, "free"),
    ):
        note = UNPAIRED_NOTE.format(other=other, minimum=MINIMUM_PAIR_MAC)
        for k in sorted(set(range(model.n_modes)) - set(paired)):
            f, z = float(model.frequency[k]), float(model.damping_ratio[k])
            frequencies, dampings = (
                ((f, nan), (z, nan)) if model is free.model else ((nan, f), (nan, z))
            )
            rows.append(_comparison_row(model.names[k], frequencies, dampings, nan, note))
    rows.sort(key=lambda r: np.nanmin([r["frequency_free_hz"], r["frequency_hand_hz"]]))
    if racket is None:
        return ModeComparison(rows, np.zeros(0), np.zeros(0))
    axis = (0.0, racket.length_m)
    return ModeComparison(rows, axis_nodes(free.model, 0, axis), axis_nodes(hand.model, 0, axis))


MINIMUM_PAIR_MAC = 0.6
"""Least MAC of a free and a hand-held mode for ``compare`` to pair them (–;
:func:`racketdyn.modal.shapes.pair_modes`' default)."""


def _comparison_row(
    mode: str,
    frequency_hz: tuple[float, float],
    damping: tuple[float, float],
    mac_value: float,
    note: str,
) -> dict[str, Any]:
    """One row of ``comparison.csv``: free and hand-held frequencies and damping ratios (NaN
    where a mode has no pair)."""
    (fa, fb), (za, zb) = frequency_hz, damping
    return {
        "mode": mode,
        "frequency_free_hz": fa,
        "frequency_hand_hz": fb,
        "frequency_shift_percent": 100 * (fb / fa - 1),
        "damping_free": za,
        "damping_hand": zb,
        "damping_ratio_hand_over_free": zb / za,
        "mac": mac_value,
        "note": note,
    }


def write_mode_comparison(comparison: ModeComparison, out: Path) -> Path:
    """``comparison.csv``: the pairs of :func:`compare_modes` and the modes left without one,
    one row each and nothing else (the first mode's nodes go into run.json as
    ``first_mode_nodes_m``); a number a mode without a pair has not is left empty."""
    table = out / "comparison.csv"
    rows = comparison.rows
    with table.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]) if rows else ["mode"])
        writer.writeheader()
        for row in rows:
            writer.writerow({k: _cell(v) for k, v in row.items()})
    return table


def _cell(value: Any) -> Any:
    """A value of ``comparison.csv``: floats to 6 significant digits, NaN empty."""
    if not isinstance(value, float):
        return value
    return "" if math.isnan(value) else f"{value:.6g}"


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
    ball : Ball or None
        The ball of the Fig. 15 check.
    rebound : IdentifiedRebound or None
        The Fig. 15 check: rebound ratio along the axis with the identified models and the
        run's ball (in ``figures.nc``).
    shapes_free, shapes_hand : IdentifiedShapes or None
        What each identification's Figs 4–6 and AutoMAC draw (in ``figures.nc``, ``_free``
        and ``_hand``).
    nodes_free_hand : AxisNodes or None
        Fig. 6 free against hand-held (in ``figures.nc``).
    fit_free, fit_hand : FitFigures or None
        What each identification's stabilisation diagram and synthesised FRFs draw (in
        ``figures.nc``, ``_free`` and ``_hand``).
    not_a_racket : str
        Why the models are not a racket's face and what was left out for it
        (:func:`on_racket_face`); "" for a racket's.
    """

    free: Identification | None = None
    hand: Identification | None = None
    racket: Racket | None = None
    comparison: ModeComparison | None = None
    speed: float = CHECK_SPEED_MPS
    ball: Ball | None = None
    rebound: IdentifiedRebound | None = None
    shapes_free: IdentifiedShapes | None = None
    shapes_hand: IdentifiedShapes | None = None
    nodes_free_hand: AxisNodes | None = None
    fit_free: FitFigures | None = None
    fit_hand: FitFigures | None = None
    not_a_racket: str = ""


@run_step
def run_compare(
    free: str | os.PathLike[str],
    hand: str | os.PathLike[str],
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    options: IdentifyOptions = DEFAULT_IDENTIFY,
    *,
    speed: float = CHECK_SPEED_MPS,
) -> CompareResult:
    """Identify free and hand-held FRFs, pair their modes by MAC, write the run folder.

    Parameters
    ----------
    free, hand : path
        FRFs of the freely supported and of the hand-held racket (UFF 58).
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, compare uses the racket, the ball of
        the Fig. 15 check and ``allow_implausible``; and the run (command, figures, progress).
    options : IdentifyOptions
        How both sets of FRFs are read and identified.
    speed : float
        Incoming ball speed of the paper's Fig. 15 check with the identified models, m/s
        (default 20, the paper's).
    """
    (check_speed,) = require_speeds("`speed`", [speed])
    check_speeds("`speed`", [check_speed], "ball_speed_mps", setup.allow_implausible)
    setup, from_run = with_racket_of_run(setup, free)
    the_racket, provenance = load_racket_input(setup.racket)
    provenance |= from_run
    out_dir = Path(out)
    given = setup.racket is not None
    report(setup.progress, f"identifying {Path(free).name}")
    found_free = identify_file(free, the_racket, "free", options, racket_given=given)
    found_free.model.require_locations("compare (modes paired by MAC, the first mode's nodes)")
    report(setup.progress, f"identifying {Path(hand).name}")
    # a hand damps some modes out: the hand's modes are named after their free pairs (issue
    # 13), as identify --names-from names them (issue 25 item 8: one name for one mode)
    found_hand = identify_file(
        hand,
        the_racket,
        "hand",
        options,
        racket_given=given,
        names_from=found_free.model,
        hand=setup.hand,
    )
    found_hand.model.require_locations("compare (modes paired by MAC, the first mode's nodes)")
    written = write_model(found_free, out_dir, "_free") + write_model(found_hand, out_dir, "_hand")
    truth_written, truth_files = write_truth_comparisons(
        out_dir, (found_free, free, "_free"), (found_hand, hand, "_hand"), words=setup.words
    )
    written += truth_written
    faces = on_racket_face(found_free.model, found_hand.model, the_racket, given)
    comparison = compare_modes(found_free, found_hand, the_racket if not faces else None)
    written.append(write_mode_comparison(comparison, out_dir))
    the_ball, ball_defaults = setup.ball_used()
    rebound, nodes_free_hand = None, None
    if not faces:
        report(setup.progress, "Fig. 15 with the identified models")
        rebound = identified_rebound(
            the_racket, the_ball, found_free.model, found_hand.model, float(check_speed)
        )
        nodes_free_hand = axis_node_curves([found_free.model, found_hand.model], the_racket)
    shapes_free = identified_shapes(found_free.model, the_racket)
    shapes_hand = identified_shapes(found_hand.model, the_racket)
    fit_free, fit_hand = fit_figures(found_free, the_racket), fit_figures(found_hand, the_racket)
    figure_data: list[Callable[[], xr.Dataset]] = [  # made while written (no dask import)
        partial(shapes_free.to_xarray, "free"),
        partial(shapes_hand.to_xarray, "hand"),
        *(
            []
            if nodes_free_hand is None
            else [partial(nodes_free_hand.to_xarray, "fig6_free_hand")]
        ),
        *([] if rebound is None else [rebound.to_xarray]),
        partial(store, {"comparison": comparison}),
        partial(store, {"fit_figures": fit_free}, "free"),
        partial(store, {"fit_figures": fit_hand}, "hand"),
    ]
    written.append(write_figure_data(out_dir / FIGURES_FILE, figure_data))
    result = CompareResult(
        out_dir,
        written,
        free=found_free,
        hand=found_hand,
        racket=the_racket,
        comparison=comparison,
        speed=float(check_speed),
        ball=the_ball,
        rebound=rebound,
        shapes_free=shapes_free,
        shapes_hand=shapes_hand,
        nodes_free_hand=nodes_free_hand,
        fit_free=fit_free,
        fit_hand=fit_hand,
        not_a_racket=faces,
    )
    inputs = {
        "free_file": str(Path(free).resolve()),
        "hand_file": str(Path(hand).resolve()),
        **provenance,
        "band_hz": list(found_free.band_hz),
        **options.record(),
        "modes_free": found_free.model.summary()["modes"],
        "modes_hand": found_hand.model.summary()["modes"],
        "misfit_free": found_free.model.metadata.get("misfit"),
        "misfit_hand": found_hand.model.metadata.get("misfit"),
        "noise_frfs_free": found_free.model.metadata.get("noise_frfs"),
        "noise_frfs_hand": found_hand.model.metadata.get("noise_frfs"),
        "first_mode_nodes_m": _first_mode_nodes(comparison),
        "racket_parts": faces
        or "the first mode's nodes on the long axis, Fig. 6 free against "
        "hand-held and Fig. 15 with the identified models",
        "fig15_ball_speed_mps": float(check_speed),
        "fig15_ball": {
            "mass_kg": the_ball.mass_kg,
            "diameter_m": the_ball.diameter_m,
            "e_bg": the_ball.e_bg,
        },
        "defaults_used": [*ball_defaults, *setup.defaults],
        TRUTH_FILES: truth_files,
    }
    return setup.finish(result, inputs, "compare")


BALL_COMPARISON_FILE = "ball_comparison.csv"
"""``compare --ball-at``'s table: the racket alone against the racket with a ball on its strings."""


@dataclass
class BallCompareResult(StepResult):
    """What :func:`run_compare_ball` identified and wrote.

    Attributes
    ----------
    alone, with_ball : Identification
        The racket alone and with the ball fixed on its strings (paper, Figs 9a and 9b).
    racket : Racket
        The racket.
    ball_at : tuple of float
        Where the ball sat (x, y), m.
    rows : list of dict
        :func:`compare_with_ball`'s rows (``ball_comparison.csv``).
    shown_node : int
        The hammer point whose FRFs Fig. 9 shows (:func:`node_showing_ball_mode`).
    ball_frfs : BallFrfs or None
        What Fig. 9 draws (in ``figures.nc``).
    """

    alone: Identification | None = None
    with_ball: Identification | None = None
    racket: Racket | None = None
    ball_at: tuple[float, float] = (math.nan, math.nan)
    rows: list[dict[str, Any]] = field(default_factory=list)
    shown_node: int = 0
    ball_frfs: BallFrfs | None = None


def compare_with_ball(alone: Identification, with_ball: Identification) -> list[dict[str, Any]]:
    """The modes of a racket with a ball on its strings against the racket alone.

    The ball's mode (named by :func:`racketdyn.racket_modal.identify.name_if_racket`) is new:
    its row has no partner (``frequency_alone_hz`` NaN).  The other modes are paired with the
    racket's by MAC (:func:`racketdyn.modal.shapes.pair_modes`, at the points both sets share:
    the hammer skips the strings under the ball) and their frequency shift is given (paper,
    section 3.2: "the natural frequencies of the frame do not change").

    Parameters
    ----------
    alone, with_ball : Identification
        The two identifications.

    Returns
    -------
    list of dict
        ``mode``, ``frequency_alone_hz``, ``frequency_ball_hz``, ``frequency_shift_percent``,
        ``damping_alone``, ``damping_ball``, ``mac`` — the ball's mode first, then the racket's
        modes in order of frequency (a racket mode with no partner has NaN in the ball columns).
    """
    model = with_ball.model
    ball = [k for k, name in enumerate(model.names) if name == BALL_MODE_NAME]
    rest = [k for k in range(model.n_modes) if k not in ball]
    nan = math.nan
    rows: list[dict[str, Any]] = [
        {
            "mode": BALL_MODE_NAME,
            "frequency_alone_hz": nan,
            "frequency_ball_hz": float(model.frequency[k]),
            "frequency_shift_percent": nan,
            "damping_alone": nan,
            "damping_ball": float(model.damping_ratio[k]),
            "mac": nan,
        }
        for k in ball
    ]
    pairing = pair_modes(model.select(rest), alone.model) if rest else None
    partner = (
        {}
        if pairing is None
        else dict(zip(pairing.second, zip(pairing.first, pairing.mac, strict=True), strict=True))
    )
    for a in range(alone.model.n_modes):
        fa, za = float(alone.model.frequency[a]), float(alone.model.damping_ratio[a])
        if a in partner:
            b, value = partner[a]
            fb, zb = float(model.frequency[rest[b]]), float(model.damping_ratio[rest[b]])
            rows.append(
                {
                    "mode": alone.model.names[a],
                    "frequency_alone_hz": fa,
                    "frequency_ball_hz": fb,
                    "frequency_shift_percent": 100 * (fb / fa - 1),
                    "damping_alone": za,
                    "damping_ball": zb,
                    "mac": value,
                }
            )
        else:
            rows.append(
                {
                    "mode": alone.model.names[a],
                    "frequency_alone_hz": fa,
                    "frequency_ball_hz": nan,
                    "frequency_shift_percent": nan,
                    "damping_alone": za,
                    "damping_ball": nan,
                    "mac": nan,
                }
            )
    return rows


BALL_MODE_SHOWN = 0.9
"""Fig. 9b strikes at the nearest point whose accelerance the ball mode carries at least this
share of at its own frequency (at 55 % the heavily damped mode made no visible peak on the
new-user trial's racket; at 90 % it does)."""


def ball_mode_share(model: ModalModel, reference: int) -> NDArray[np.float64]:
    """The ball mode's share of each point's accelerance at the ball mode's frequency.

    |term of the ball mode| over |sum of every mode's term|, the terms φ_k(j) φ_k(ref) (−ω²) /
    (ω_k² − ω² + 2iζ_k ω_k ω) of the model's modes at ω = the ball mode's; NaN without a ball
    mode.

    Parameters
    ----------
    model : ModalModel
        The racket with the ball (its modes at the test's points).
    reference : int
        Row of the accelerometer's point in the model.
    """
    if BALL_MODE_NAME not in model.names:
        return np.full(model.locations.shape[0], np.nan)
    k = model.names.index(BALL_MODE_NAME)
    omega = 2.0 * np.pi * model.frequency[k]
    omega_m = 2.0 * np.pi * model.frequency
    modal = -(omega**2) / (omega_m**2 - omega**2 + 2j * model.damping_ratio * omega_m * omega)
    terms = model.mode_shapes * model.mode_shapes[reference] * modal
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.asarray(np.abs(terms[:, k]) / np.abs(terms.sum(axis=1)), dtype=float)


def node_showing_ball_mode(
    model: ModalModel,
    nodes: Sequence[int],
    reference_node: int,
    candidates: Sequence[int],
    ball_at: tuple[float, float],
) -> int:
    """The hammer point of Fig. 9b: the candidate nearest the ball whose accelerance the ball
    mode carries at least :data:`BALL_MODE_SHOWN` of (:func:`ball_mode_share`), else the one
    it carries most of; the nearest candidate when the model has no ball mode or no reference.

    Parameters
    ----------
    model : ModalModel
        The racket with the ball, its rows the points ``nodes``.
    nodes : sequence of int
        The model's points.
    reference_node : int
        The accelerometer's point.
    candidates : sequence of int
        The points both tests hold.
    ball_at : tuple of float
        Where the ball sits (x, y), m.
    """
    rows = [list(nodes).index(n) for n in candidates]
    where = model.locations[rows, :2]
    order = np.argsort(np.hypot(*(where - np.asarray(ball_at)).T), kind="stable")
    if reference_node not in nodes:
        return int(candidates[int(order[0])])
    share = ball_mode_share(model, list(nodes).index(reference_node))[rows]
    if not np.any(np.isfinite(share)):
        return int(candidates[int(order[0])])
    shown = [i for i in order if share[i] >= BALL_MODE_SHOWN]
    return int(candidates[shown[0] if shown else int(np.nanargmax(share))])


@run_step
def run_compare_ball(
    alone: str | os.PathLike[str],
    with_ball: str | os.PathLike[str],
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    options: IdentifyOptions = DEFAULT_IDENTIFY,
    *,
    ball_at: Sequence[float],
    support: str = "free",
) -> BallCompareResult:
    """Identify a racket alone and with a ball fixed on its strings, and compare (Figs 9a, 9b).

    Writes ``modes_alone.*`` and ``modes_ball.*`` (as :func:`write_model`),
    ``ball_comparison.csv`` (:func:`compare_with_ball`) and ``run.json`` (the ball's mode, the
    largest frame-mode shift).

    Parameters
    ----------
    alone, with_ball : path
        FRFs of the racket alone and with the ball (UFF 58), both on ``support``.
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, compare_ball uses the racket; and the
        run (command, figures, progress).
    options : IdentifyOptions
        How both sets of FRFs are read and identified.
    ball_at : sequence of float
        Where the ball sat (x, y), m (``--ball-at``).
    support : {"free", "hand"}
        Support of both tests.
    """
    setup, from_run = with_racket_of_run(setup, alone)
    the_racket, provenance = load_racket_input(setup.racket)
    provenance |= from_run
    ball = ball_location(ball_at, the_racket)
    out_dir = Path(out)
    given = setup.racket is not None
    report(setup.progress, f"identifying {Path(alone).name}")
    found_alone = identify_file(
        alone, the_racket, support, options, racket_given=given, hand=setup.hand
    )
    found_alone.model.require_locations("compare --ball-at (modes paired by MAC)")
    report(setup.progress, f"identifying {Path(with_ball).name}")
    found_ball = identify_file(
        with_ball, the_racket, support, options, racket_given=given, ball_at=ball, hand=setup.hand
    )
    found_ball.model.require_locations("compare --ball-at (modes paired by MAC)")
    written = write_model(found_alone, out_dir, "_alone") + write_model(
        found_ball, out_dir, "_ball"
    )
    truth_written, truth_files = write_truth_comparisons(
        out_dir, (found_alone, alone, "_alone"), (found_ball, with_ball, "_ball"), words=setup.words
    )
    written += truth_written
    rows = compare_with_ball(found_alone, found_ball)
    table = out_dir / BALL_COMPARISON_FILE
    with table.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]) if rows else ["mode"])
        writer.writeheader()
        for row in rows:
            writer.writerow(
                {
                    k: ("" if isinstance(v, float) and math.isnan(v) else f"{v:.6g}")
                    if isinstance(v, float)
                    else v
                    for k, v in row.items()
                }
            )
    written.append(table)
    shared = [n for n in found_ball.frfs.nodes if n in found_alone.frfs.nodes]
    shown = node_showing_ball_mode(
        found_ball.model, found_ball.frfs.nodes, found_ball.frfs.reference_node, shared, ball
    )
    result = BallCompareResult(
        out_dir,
        written,
        alone=found_alone,
        with_ball=found_ball,
        racket=the_racket,
        ball_at=ball,
        rows=rows,
        shown_node=shown,
        ball_frfs=ball_frfs(found_alone, found_ball, shown, ball),
    )
    defer_figure_data(result, {"ball_frfs": result.ball_frfs})
    ball_rows = [r for r in rows if r["mode"] == BALL_MODE_NAME]
    shifts = [
        abs(r["frequency_shift_percent"])
        for r in rows
        if math.isfinite(r["frequency_shift_percent"])
    ]
    inputs = {
        "alone_file": str(Path(alone).resolve()),
        "with_ball_file": str(Path(with_ball).resolve()),
        **provenance,
        "support": support,
        "ball_at_m": list(ball),
        "band_hz": list(found_alone.band_hz),
        **options.record(),
        "naming_with_ball": found_ball.model.metadata.get("naming"),
        "ball_mode": (
            {
                "frequency_hz": ball_rows[0]["frequency_ball_hz"],
                "damping_ratio": ball_rows[0]["damping_ball"],
            }
            if ball_rows
            else None
        ),
        "largest_frame_mode_shift_percent": max(shifts) if shifts else None,
        "modes_alone": found_alone.model.summary()["modes"],
        "modes_ball": found_ball.model.summary()["modes"],
        TRUTH_FILES: truth_files,
    }
    return setup.finish(result, inputs, "compare_ball")
