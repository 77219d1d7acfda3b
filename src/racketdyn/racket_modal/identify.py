"""Identify a racket: the general identification, then the modes named the racket way.

:func:`identify_racket` is what the racket workflows call: :func:`racketdyn.modal.identify.identify`
on the FRFs, then :func:`name_racket_modes` (bending, twisting, string bed from the shapes and
the head: :func:`racketdyn.racket_modal.shapes.classify_modes`).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from racketdyn.hand import Hand
from racketdyn.measurement.records import FrfSet
from racketdyn.modal import ModalModel
from racketdyn.modal.identify import SELECTION, Identification, identify
from racketdyn.modal.mac import mac
from racketdyn.modal.poles import SelectionRules
from racketdyn.modal.shapes import ModePairing, pair_modes
from racketdyn.racket import HeadEllipse, Racket
from racketdyn.racket_modal.beam import reference_shapes
from racketdyn.racket_modal.face import face_mapping, looks_like_racket
from racketdyn.racket_modal.shapes import (
    BALL_MODE_NAME,
    BALL_RIGID_SHARE,
    ON_STRINGS,
    ReferenceShapes,
    classify_modes,
    naming_evidence,
    naming_words,
    outline_rigid_share,
    rigid_share,
)

__all__ = [
    "FRAME_KINDS",
    "PAIRED_KINDS",
    "holding",
    "identify_racket",
    "name_after",
    "name_if_racket",
    "name_racket_modes",
    "pair_racket_modes",
]


def _head(racket: Racket | HeadEllipse) -> HeadEllipse:
    return racket.head if isinstance(racket, Racket) else racket


def name_racket_modes(
    identification: Identification,
    racket: Racket | HeadEllipse,
    ball_at: tuple[float, float] | None = None,
    hand: Hand | None = None,
) -> Identification:
    """The identification with its modes named from their shapes on the racket.

    Parameters
    ----------
    identification : Identification
        From :func:`racketdyn.modal.identify.identify` on a racket's FRFs.
    racket : Racket or HeadEllipse
        The racket (or its string bed), to tell string points from frame points; a racket
        also gives its frame's own modes and its bed's tensions, which the modes' node counts
        and nodal lines are read against
        (:func:`racketdyn.racket_modal.beam.reference_shapes`).
    ball_at : tuple of float, optional
        Where a ball was fixed on the strings (x, y), m (the paper's compound test): its mode
        is named ``"ball on the strings"`` (:func:`~racketdyn.racket_modal.shapes.classify_modes`).
    hand : Hand, optional
        The hand that held the racket, for a model whose ``support`` is ``hand``: the node
        counts are read against the frame held by it
        (:func:`racketdyn.racket_modal.beam.reference_shapes`; None: the default
        :class:`~racketdyn.hand.Hand`, the rig's and the impact model's).  Any other support:
        against the frame free (:func:`holding`).

    Returns
    -------
    Identification
        Names ``"2-node bending"``, ``"2-node twisting"``, ``"string-bed membrane"`` … and
        kinds ``bending``, ``twisting``, ``string-bed``.
    """
    reference = (
        reference_shapes(racket, holding(identification.model, hand))
        if isinstance(racket, Racket)
        else None
    )
    return _named(identification, _head(racket), ball_at, reference)


def _named(
    identification: Identification,
    head: HeadEllipse,
    ball_at: tuple[float, float] | None,
    reference: ReferenceShapes | None,
) -> Identification:
    """:func:`name_racket_modes` against ``reference`` (the shapes the names are read
    against)."""
    names, kinds = classify_modes(identification.model, head, ball_at, reference)
    return identification.renamed(names, kinds)


def holding(model: ModalModel, hand: Hand | None = None) -> Hand | None:
    """The hand a model's node counts are read against: for a model whose ``support`` is
    ``hand``, ``hand`` or, if None, the default :class:`~racketdyn.hand.Hand` (the rig's and
    the impact model's); None for any other support (the frame free).

    Parameters
    ----------
    model : ModalModel
        The identified model (its ``support``).
    hand : Hand, optional
        The hand that held the racket in the test.
    """
    if model.support != "hand":
        return None
    return Hand() if hand is None else hand


def identify_racket(
    frfs: FrfSet,
    racket: Racket | HeadEllipse,
    band_hz: tuple[float, float] | None = None,
    max_order: int = 60,
    pin_hz: Sequence[float] = (),
    exclude_hz: Sequence[float] = (),
    support: str = "free",
    *,
    rules: SelectionRules = SELECTION,
) -> Identification:
    """Identify a racket's modal model from its FRFs and name the modes the racket way.

    Parameters
    ----------
    frfs : FrfSet
        FRFs of the hammer points (with a driving point at the reference for mass-normalised
        shapes); an exponential window recorded on the set is taken off the damping.
    racket : Racket or HeadEllipse
        The racket (or its string bed), to name modes (string-bed against frame).
    band_hz : tuple of float, optional
        Band to identify in, Hz (default :func:`racketdyn.modal.identify.default_band`: 40 Hz,
        above the rigid-body modes of a racket on a sponge or in a hand (≤ 15 Hz) and below
        its first bending mode (≥ 100 Hz), to the analyser bandwidth).
    max_order : int
        Highest model order of the stabilisation diagram.
    pin_hz, exclude_hz : sequence of float
        Modes to force in or leave out, by approximate frequency, Hz.
    support : str
        Support the racket was tested on (``free``, ``hand``), recorded on the model.
    rules : SelectionRules
        The rules of the automatic pole selection
        (:func:`racketdyn.modal.identify.identify`'s).

    Returns
    -------
    Identification
        Its ``model`` is what the impact models take (``modal_model=``): mass-normalised
        shapes at the points of the racket's face, named the racket way.
    """
    identification = identify(
        frfs,
        band_hz,
        max_order=max_order,
        pin_hz=pin_hz,
        exclude_hz=exclude_hz,
        support=support,
        rules=rules,
    )
    return name_racket_modes(identification, racket)


def name_if_racket(
    identification: Identification,
    racket: Racket,
    racket_given: bool,
    ball_at: tuple[float, float] | None = None,
    hand: Hand | None = None,
) -> tuple[Identification, str]:
    """Name the modes the racket way only when the structure is a racket and the shapes show it.

    3-D lab points on one plane are first mapped onto the racket's face
    (:func:`racketdyn.racket_modal.face.face_mapping`); the model then holds face (x, y)
    locations, its metadata the lab's (``lab_locations_m``) and the mapping in words
    (``face_mapping``).  The modes are named from their shapes when the points are a racket's —
    ``racket_given`` (the user gave ``--racket``) or they lie on the racket's outline
    (:func:`~racketdyn.racket_modal.face.looks_like_racket`) — and the shapes can tell the
    kinds apart (:func:`~racketdyn.racket_modal.shapes.naming_evidence`); otherwise they stay
    ``mode 1 … n`` of kind ``unknown``.

    Parameters
    ----------
    identification : Identification
        From :func:`racketdyn.modal.identify.identify`.
    racket : Racket
        The racket the points may belong to.
    racket_given : bool
        True when the user named the racket (``--racket``).
    ball_at : tuple of float, optional
        Where a ball was fixed on the strings (x, y), m (``--ball-at``): one mode is named
        ``"ball on the strings"`` if its frame shape shows it, and the sentence says which.
    hand : Hand, optional
        The hand that held the racket, for a model whose ``support`` is ``hand``
        (:func:`name_racket_modes`; None: the default hand); the sentence then says the node
        counts were read against the frame it holds.

    Returns
    -------
    Identification, str
        The identification (renamed, or as it was) and a sentence saying how the modes were
        named and why.
    """
    model = identification.model
    if not model.has_locations:
        return identification, (
            "modes numbered: the points have no coordinates (give `geometry` to name a "
            "racket's modes)"
        )
    face = model.locations
    if model.n_dimensions == 3:
        mapping = face_mapping(model.locations, racket)
        if mapping is None:
            return (
                identification,
                "modes numbered: the points are not a racket's face (on a line, or off one plane)",
            )
        face = mapping.apply(model.locations)
        if racket_given or looks_like_racket(face, racket):
            metadata = {
                **model.metadata,
                "lab_locations_m": model.locations.tolist(),
                "face_mapping": mapping.describe(),
            }
            identification = replace(
                identification, model=replace(model, locations=face, metadata=metadata)
            )
    if not (racket_given or looks_like_racket(face, racket)):
        return identification, (
            "modes numbered: the points are not on a racket's outline (give `racket` to name "
            "a racket's modes)"
        )
    reason = naming_evidence(identification.model, racket.head)
    if reason:
        return identification, f"modes numbered: {reason}"
    held = holding(identification.model, hand)
    reference = reference_shapes(racket, held)
    named = _named(identification, racket.head, ball_at, reference)
    sentence = "modes named from their shapes on the head of " + (
        racket.name if racket_given else f"the built-in {racket.name}, whose outline the points fit"
    )
    if held is not None:
        sentence += (
            ", their node counts read against its frame held in the hand (the grip "
            f"{1e3 * held.grip_start_m:.0f}–{1e3 * held.grip_end_m:.0f} mm from the butt)"
        )
    if not racket_given:  # the default racket: a user's own may merely lie near its outline
        sentence += "; give `racket` to name them on your racket's head"
    sentence += _unknown_modes(named.model, racket, ball_at, reference)
    if ball_at is None:
        return named, sentence + _looks_like_a_ball(named.model, racket, racket_given)
    names = named.model.names
    if BALL_MODE_NAME in names:
        k = names.index(BALL_MODE_NAME)
        return named, (
            f"{sentence}; the ball on the strings at x = {1e3 * ball_at[0]:.0f} mm, "
            f"y = {1e3 * ball_at[1]:.0f} mm: {named.model.frequency[k]:.1f} Hz, the mode whose "
            "frame moves most nearly as a rigid body"
        )
    share = rigid_share(named.model, racket.head)
    best = float(np.nanmax(share)) if np.any(np.isfinite(share)) else float("nan")
    return named, (
        f"{sentence}; no mode of the ball on the strings found: no mode's frame shape is more "
        f"than {BALL_RIGID_SHARE:.0%} a rigid-body motion (largest {best:.0%}; "
        + ("" if racket_given else "give `racket` (a racket file) for your racket's head, ")
        + "widen `band_hz` or measure more frame points)"
    )


def _unknown_modes(
    model: ModalModel,
    racket: Racket,
    ball_at: tuple[float, float] | None,
    reference: ReferenceShapes,
) -> str:
    """A clause naming each mode the shapes leave ``unknown`` and why, and each whose name
    they support only in part and what makes it uncertain
    (:func:`~racketdyn.racket_modal.shapes.naming_words`, against ``reference``, the shapes
    the names were read against); "" when none is."""
    reasons, notes = naming_words(model, racket.head, ball_at, reference)  # one classification
    clauses = []
    for word, said in (
        ("unknown", [(k, r) for k, r in enumerate(reasons) if r and model.kinds[k] == "unknown"]),
        ("uncertain", [(k, n) for k, n in enumerate(notes) if n]),
    ):
        if said:
            clauses.append(
                f"; {word}: " + "; ".join(f"{model.frequency[k]:.1f} Hz ({why})" for k, why in said)
            )
    return "".join(clauses)


_SWING_ON_HAND_HZ = 40.0
"""Below this a nearly rigid frame motion is the racket swinging on the hand and arm (a held
racket's pitch and heave modes lie at ≈ 3–30 Hz), not a ball on the strings (≈ 80–110 Hz)."""


def _looks_like_a_ball(model: ModalModel, racket: Racket, racket_given: bool = True) -> str:
    """A clause for a mode whose frame moves nearly as a rigid body when no ball was declared.

    No elastic mode of a bare racket can (mass orthogonality to the rigid-body modes); a ball
    or a mass on the strings makes one (section 3.2).  Named as the racket's mode all the same,
    it pushes every bending mode above it one node too far, so the user is told.  Without
    ``--racket`` the head is the built-in racket's, which the points may fit only loosely
    (a junior's racket: string points near the throat taken for frame points), so the points'
    outline is read too (:func:`~racketdyn.racket_modal.shapes.outline_rigid_share`).
    """
    share = rigid_share(model, racket.head)
    if not racket_given:
        share = np.fmax(share, outline_rigid_share(model))
    share = np.where(model.frequency >= _SWING_ON_HAND_HZ, share, np.nan)
    if not np.any(np.isfinite(share)) or float(np.nanmax(share)) <= BALL_RIGID_SHARE:
        return ""
    k = int(np.nanargmax(share))
    give = "`ball_at` x,y" if racket_given else "`ball_at` x,y and `racket` (a racket file)"
    return (
        f"; but the mode at {model.frequency[k]:.1f} Hz moves the frame almost as a rigid body "
        f"({share[k]:.0%}), as a ball or a mass on the strings makes: if one was on, give "
        f"{give} to name it (its name here and the bending modes' above it are then off)"
    )


PAIRED_KINDS = ("bending", "twisting", "string-bed")
"""Kinds whose names a mode takes from its MAC pair in another model of the racket
(:func:`name_after`; not ``unknown`` or the ball's ``other``)."""
_OWN_FREQUENCY = re.compile(r"\(\d+(?:\.\d+)? Hz\)$")
"""A name ending in its mode's own frequency: "bending mode (838.4 Hz)"."""


FRAME_KINDS = ("bending", "twisting")
"""Kinds of the frame's own modes, paired on the frame's points (:func:`pair_racket_modes`)."""


def pair_racket_modes(
    first: ModalModel, second: ModalModel, head: HeadEllipse | None, minimum_mac: float = 0.6
) -> ModePairing:
    """Pair two models' racket modes by MAC (:func:`racketdyn.modal.shapes.pair_modes`: a
    mode only with a mode of its own kind where both kinds are known), a bending or twisting
    mode with another on the frame's points alone.

    A frame mode veering with a string-bed mode shares its strings' motion with it, and a
    support that moves the one moves the share: the trial racket's free 5-node bending
    (1435 Hz, 38 % of its strain energy in the strings, veering with the (2, 0) membrane at
    1383 Hz) and its hand-held one (1294 Hz, 13 %) score a MAC of 0.34 over every point, the
    strings' 44 points outweighing the frame's, and 0.95 on the frame's points; over every
    point the free mode's best match was the hand's (2, 0) membrane (0.94).

    Parameters
    ----------
    first, second : ModalModel
        The two models (e.g. free and hand-held), shapes at face points (x, y), m.
    head : HeadEllipse or None
        The string bed, to tell frame points (elliptic radius ≥ 0.95) from string points;
        None: every point counts for every mode.
    minimum_mac : float
        Smallest MAC that makes a pair (–).

    Returns
    -------
    ModePairing
    """
    second_shapes = second.mode_shapes_at(first.locations)
    matrix = mac(first.mode_shapes, second_shapes)
    if head is not None and first.n_dimensions == 2:
        frame = head.normalised_radius(first.locations) >= ON_STRINGS
        if 0 < np.count_nonzero(frame) < frame.size:
            on_frame = mac(first.mode_shapes[frame], second_shapes[frame])
            for a, kind in enumerate(first.kinds):
                for b, other in enumerate(second.kinds):
                    if kind in FRAME_KINDS and kind == other:
                        matrix[a, b] = on_frame[a, b]
    return pair_modes(first, second, minimum_mac, matrix)


def name_after(model: ModalModel, named: ModalModel, head: HeadEllipse | None = None) -> ModalModel:
    """``model`` with each mode named after its MAC pair of the same kind in ``named``.

    Twisting and bending modes are numbered in order of frequency
    (:func:`~racketdyn.racket_modal.shapes.classify_modes`); a hand damps some of them out
    of the identification (the trial of issue 13 lost the 3- and 4-node twisting modes, ζ
    10 % and 6 %; issue 25 item 8's 305 g racket the same two, ζ 10 % and 5 %), and the
    hand's later modes were then named a node or two short.  A pair of the same kind
    (:func:`racketdyn.modal.shapes.pair_modes`, MAC ≥ 0.6) in a model whose names are
    trusted — the same racket freely supported — gives the mode its pair's name; a name
    that holds its pair's frequency (``bending mode (838.4 Hz)``: the order unknown) is given
    with the mode's own.  The others keep theirs, made unique with their frequency.
    ``compare`` and ``identify --names-from`` both name the hand-held modes so: one name for
    one mode in every command.

    Parameters
    ----------
    model : ModalModel
        The model to name (e.g. the hand-held racket's; names and kinds from its shapes).
    named : ModalModel
        The model whose names it takes (e.g. the freely supported racket's).
    head : HeadEllipse, optional
        The string bed: frame modes pair on the frame's points (:func:`pair_racket_modes`).

    Returns
    -------
    ModalModel
        ``model`` with new names (kinds, frequencies and shapes unchanged).
    """
    if not model.kinds or not named.kinds or not (model.has_locations and named.has_locations):
        return model
    names = list(model.names)
    pairing = pair_racket_modes(named, model, head)
    renamed = set()
    for a, b in zip(pairing.first, pairing.second, strict=True):
        kind = model.kinds[b]
        if kind in PAIRED_KINDS and named.kinds[a] == kind:
            names[b] = _OWN_FREQUENCY.sub(f"({model.frequency[b]:.1f} Hz)", named.names[a])
            renamed.add(int(b))
    taken = {names[b] for b in renamed}
    for b, name in enumerate(names):
        if b not in renamed and name in taken:
            names[b] = f"{name} ({model.frequency[b]:.1f} Hz)"
    return replace(model, names=tuple(names))
