"""What a racket's mode is: naming (bending, twisting, string bed) and nodes along the long axis.

Naming, from the shape at the measured points and the racket's head:

* **string-bed** when the mean square of the shape on the strings (points inside 95 % of the
  bed's elliptic radius) is more than :data:`CLEAR_STRING_BED_RATIO` (40) times that on the
  frame; between four and 40 times the shape does not say (the rig's 5- and 6-node bending
  modes above 1 kHz, coupled with the bed, score 12 and 17, its second and fourth membrane
  modes 17 and 19): the mode keeps its neutral name ``mode k (f Hz)``, kind ``unknown`` (so
  a prediction charges its vibration energy rather than silently leaving it out), and the
  bending modes above it lose their node count (``bending mode (f Hz)``);
* **string-bed** also, whatever that ratio, when the mode's symmetric part (even in y) has
  every string point in phase (:data:`IN_PHASE_SHARE`) and the frame nearly still (the
  symmetric part's ratio above :data:`CLEAR_STRING_BED_RATIO`): the all-in-phase membrane
  mode, whose measured shape a twisting mode close by leaks into — odd in y and largest on
  the hoop (issue 25 item 8: a 305 g racket's membrane at 679 Hz, 14 Hz above its 3-node
  twisting, scored 12.8 on its whole shape and 101 on its symmetric part); a membrane mode
  veering with a bending mode shares its frame motion and stays ``unknown``;
* in between (4–40), the bed's own motion decides where it is clear: the frame's motion under
  the bed, ``w(x) + θ(x)·y``, is fitted to the hoop's points (cubics in x, :func:`bed_own_motion`)
  and taken off the string points' shape.  A mode whose strings follow the frame in phase,
  their own motion less than :data:`BED_OWN_RATIO` (18) times the carried motion in mean
  square, is the frame's: the bed, driven below its own frequency, amplifies the frame's
  motion (the rig's pull-tension 4-node bending on the frame's shape: 7.3 free, 4.1 held,
  20 % and 15 % of its strain energy in the strings).  A mode whose frame moves against its
  strings (it recoils), their own motion more than 18 times the carried, is the bed's (the
  rig's pull-tension membrane: 24 and 28, 78 % and 82 % in the strings).  The played bed's
  veering pairs, their strain energy shared 44–56 % either way, score 10 and 13 against and
  39 and 104 in phase: they stay ``unknown``.  The recoil must be clear, the correlation below
  −:data:`RECOIL_CORRELATION`: the built-in racket's 6-node bending at 1796 Hz moves its strings
  21.5 times the carried but hardly against it (−0.14), and the lab racket's veering pair at
  917.7/993.0 Hz (the 4-node bending and the (1, 0) membrane, 51 and 55 % of their strain
  energy in the strings) scores 14.4 at −0.02 (``unknown``: the shapes cannot say) and 22.6
  at −0.57 (the membrane).  The recoil names only a mode mostly even in y:
  a twisting mode veering with an odd membrane mode (a 285 g racket's above 1.4 kHz, strain
  energy twist/strings 56/44 and 61/39, their partners 45/55 and 41/59) moves its strings
  15-26 times its frame in mean square, their own motion 200-750 times the hoop's carried
  twist, whichever part holds more energy: the recoil does not name them;
* in between too, a mode neither following nor recoiling is the frame's when its frame's shape
  matches one of the frame's own modes (:data:`FRAME_MAC`) better than its strings' own motion
  matches one of the bed's (:func:`membrane_names`; eleventh session): above the bed's own
  frequency a frame mode's bed moves against its frame without recoiling (the 300 g, 100 sq in
  trial racket's 4- and 5-node bending at 845.6 and 1435.2 Hz, 75 and 62 % of their strain
  energy in the frame: strings 4.8 and 13 times the frame in mean square, their own motion 5
  and 24 times the carried at −0.5, frames 0.955 and 0.949 against beds 0.78 and 0.80; its
  6- and 7-node twisting likewise), and they were ``unknown``.  Of the modes then given one
  frame name, the one whose strings move least against its frame in mean square keeps it and
  the others take the bed's name their strings match (``unknown`` where none does): the
  members of a veering pair share both shapes, and the one moving its strings less holds more
  of its energy in the frame (the trial racket's 1484.7/1512.1 Hz, 6-node twisting and (1, 1)
  membrane, 16.4 against 16.9; its 1835.2/1879.9 Hz, 7-node twisting and (2, 1), 12 against
  22; the 285 g racket's 1469.3/1493.7 Hz, 26 and 15, the (1, 1) and the 6-node twisting).  A
  mode whose strings match the bed at least as well stays ``unknown``, and
  :func:`naming_reasons` says what both shapes matched (the built-in racket's played-bed pair
  at 586 and 721 Hz: beds 1.00 and 0.99, frames 0.82 and 0.91).  A veering pair's member
  identified without its partner carries some of the partner's shape: the 305 g racket's
  1522.1 Hz (the truth's (2, 0) membrane, 52 % strings, its partner at 1422.3 Hz not found)
  matches the 5-node bending at 0.96 and the bed at 0.73 and takes the bending's name, with a
  note (:func:`naming_words`) naming the bed mode its strings match that no other mode is
  named after: the points cannot tell whether the frame or the strings hold more of its
  energy;
* **twisting** when more than half of the shape's energy is odd in y: points are paired with
  their mirror images across the long axis (within 1 cm) and the odd part (φ(x,y) − φ(x,−y))/2
  compared with the whole;
* **bending** otherwise;
* a bending (twisting) mode whose shape holds :data:`MIXED_SHARE` or more of its energy at the
  mirrored points odd (even) in y is two modes of opposite symmetry under one peak, fitted as
  one pole: named ``"3-node twisting mixed with string-bed membrane"`` (the other part's bed
  mode, or frame mode, where it matches one), kind ``unknown`` (charged for the frame it moves),
  and :func:`naming_reasons` says so.

A name says the mode's shape, not its rank among the modes found, so a mode missed does not
shift the names above it (issue 25 item 8, tenth session):

* a bending (twisting) mode takes the node count of the racket's own frame mode its frame shape
  matches best, MAC ≥ :data:`FRAME_MAC` — the symmetric part at the frame points against the
  frame's ``w(x)``, the twist ``(φ(x, y) − φ(x, −y)) / 2y`` at mirrored frame points against its
  ``θ(x)`` (:class:`ReferenceShapes`, from :func:`racketdyn.racket_modal.beam.reference_shapes`:
  an n-node bending has n sign changes of ``w`` from butt to tip, an n-node twisting n − 1 of
  ``θ``).  The points do not reach the butt, where the outer node of the higher modes sits, so
  the count is read against whole shapes rather than counted; where another count's frame
  mode matches nearly as well (:data:`COUNT_CONTRAST`) the name gives both ("3- or 4-node
  twisting") and :func:`naming_words` says why.  Without a frame model or a
  match, the n-th bending mode in frequency is "(n+1)-node bending" (a free or hand-held racket
  has its bending modes in the order of their nodes) and the twisting modes likewise;
  :func:`axis_nodes` gives the node positions for the figures (paper, Figs 6 and 15);
* a string-bed mode is named by the nodal lines of the bed's own mode (on a still frame,
  :func:`bed_modes`) that its strings' own motion matches best, MAC ≥ :data:`MEMBRANE_MAC`
  (:func:`membrane_names`, :func:`membrane_name`): "string-bed membrane" (all in phase),
  "string-bed membrane (1, 0)" (one nodal line across the bed), "(0, 1)" (one along it), …;
  "string-bed membrane (f Hz)" where none matches.

The virtual rig names its truth the same way (:mod:`racketdyn.rig.model`).

A ball fixed on the strings (the paper's compound test, section 3.2, ``ball_at``) adds one mode
in which ball and frame push against each other through the strings (:data:`BALL_MODE_NAME`).
Its shape on the frame is the frame's recoil, nearly a rigid-body motion of the head and handle,
whereas an elastic mode of a bare racket is orthogonal (through the mass matrix) to every
rigid-body motion and cannot look like one (:func:`rigid_share`).  With ``ball_at`` the mode
whose frame shape is most nearly a plane ``a + b x + c y`` is the ball mode when more than
:data:`BALL_RIGID_SHARE` of its frame shape is that plane (the rig's ball mode: 0.98; its
2-node bending mode: 0.45); the bending modes are then counted without it.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache
from weakref import WeakKeyDictionary

import numpy as np
from numpy.typing import NDArray

from racketdyn.modal.model import ModalModel
from racketdyn.modal.shapes import nodes_along
from racketdyn.racket import HeadEllipse

__all__ = [
    "BALL_MODE_NAME",
    "BALL_RIGID_SHARE",
    "BED_DEGREE",
    "BED_OWN_RATIO",
    "CLEAR_STRING_BED_RATIO",
    "COUNT_CONTRAST",
    "FRAME_MAC",
    "HOOP_DEGREE",
    "HOOP_REACH",
    "IN_PHASE_SHARE",
    "MEMBRANE_MAC",
    "MIRROR_TOLERANCE_M",
    "MIXED_SHARE",
    "RECOIL_CORRELATION",
    "SHAPES_AS_MEASURED",
    "SHAPES_FRAME_MODEL",
    "SHAPES_FRAME_UNDER_BED",
    "SHAPES_ON_STRINGS",
    "STRING_BED_RATIO",
    "ReferenceShapes",
    "axis_nodes",
    "ball_mode_index",
    "bed_modes",
    "bed_own_motion",
    "classify_modes",
    "frame_under_bed",
    "membrane_name",
    "membrane_names",
    "naming_evidence",
    "naming_reasons",
    "naming_words",
    "outline_rigid_share",
    "rigid_share",
    "sign_changes",
]

BALL_MODE_NAME = "ball on the strings"
"""Name of the compound mode in which a ball fixed on the strings moves against the frame (the
paper's 103 Hz, section 3.2)."""
BALL_RIGID_SHARE = 0.8
"""Least share of a mode's frame shape (sum of squares) that a plane a + b x + c y must explain
for the mode to be a ball's on the strings (–): the rig's ball mode scores 0.98, its bending and
twisting modes at most 0.45 (``tests/test_compound.py``)."""

STRING_BED_RATIO = 4.0
"""Below this ratio of mean squares on the strings and on the frame a mode is the frame's
(bending or twisting) (–)."""
CLEAR_STRING_BED_RATIO = 40.0
"""Above this ratio a mode is clearly a string-bed mode; between the two the shape does not say
(–)."""
IN_PHASE_SHARE = 0.9
"""Least ``|Σ φ| / Σ |φ|`` over the string points of a mode's symmetric part for its strings to
move in phase, as in the first membrane mode (–): the rig's membrane modes score 0.99–1.00
(identified with noise 0.97–1.00), its bending modes 0.1–0.9, its other membrane modes
≤ 0.5."""
MIRROR_TOLERANCE_M = 0.01
"""Largest distance between a point and the mirror image of another across y = 0, m."""
BED_OWN_RATIO = 18.0
"""Mean square of the strings' own motion (their shape less the frame's carried under them)
over the carried motion's that parts a frame mode the bed follows in phase (below) from a bed
mode its frame recoils against (above) (–): the rig's pull-tension 4-node bending scores 7.3
and 4.1, its membrane 24 and 28; the played bed's veering pairs 10–13 (frame against) and
39–104 (in phase), left unnamed (module docstring)."""
ON_STRINGS = 0.95
"""Elliptic radius (the bed's edge at 1) below which a point is on the strings, at or above
which it is on the frame (–)."""
HOOP_DEGREE = 3
"""Degree in x of the polynomials ``w(x)`` and ``θ(x)`` fitted to the hoop's points (–)."""
SHAPES_FRAME_UNDER_BED = "the frame's motion under the bed, fitted to the hoop's points"
"""``metadata["shapes_on_strings"]`` of a model whose string points carry the frame's motion
(:func:`frame_under_bed`)."""
SHAPES_FRAME_MODEL = "the frame's motion (a model of the frame, the bed's own give not in it)"
"""``metadata["shapes_on_strings"]`` of the built-in beam model, whose shapes are the frame's
everywhere: :func:`frame_under_bed` keeps them."""
SHAPES_AS_MEASURED = "as measured (no hoop and string points to fit the frame's motion)"
"""``metadata["shapes_on_strings"]`` of a model taken as it is (:func:`frame_under_bed`)."""
SHAPES_ON_STRINGS = (SHAPES_FRAME_MODEL, SHAPES_FRAME_UNDER_BED, SHAPES_AS_MEASURED)
"""What ``metadata["shapes_on_strings"]`` may say: a model saying one is kept as it is."""
HOOP_REACH = 1.5
"""Frame points within this elliptic radius of the bed (–, the bed's edge at 1) are the hoop's,
those further out the throat's and the handle's."""
RECOIL_CORRELATION = 0.5
"""Least negative correlation of the strings' own motion with the frame's carried under them
for a frame to recoil against its strings (–, :func:`bed_own_motion`): the rig's pull-tension
membrane scores below −0.5 free and held; the built-in racket's 6-node bending at 1796 Hz,
71 % of its strain energy in the frame, −0.14 (its strings' own motion 21.5 times the
carried), and was named a membrane by the recoil rule without it."""
BED_DEGREE = 6
"""Highest degree of the polynomials multiplying ``1 − ρ²`` in the string bed's own modes on a
still frame (:func:`bed_modes`; 28 functions: the first twelve modes' shapes settled)."""
BED_MODES = 12
"""How many of the bed's own modes a measured membrane mode is matched against (–): the
hammer grid's 44 string points tell them apart; higher ones would alias."""
MEMBRANE_MAC = 0.7
"""Least MAC of a string-bed mode's own motion (its strings' shape less the frame's carried
under them) with one of the bed's own modes for the mode to take that mode's nodal lines as
its name (–): the rig's membrane modes to 2.1 kHz score 0.83–1.00 at the hammer points, its
5-node bending's strings 0.51."""
FRAME_MAC = 0.8
"""Least MAC of a bending (twisting) mode's frame shape with one of the frame's own bending
(twisting) modes for the mode to take that mode's node count (–; :class:`ReferenceShapes`)."""
MIXED_SHARE = 0.2
"""Least share of a bending (twisting) mode's shape at the points (sum of squares over the
mirrored pairs) odd (even) in y for the mode to be named a mix of two (–): two modes of opposite
symmetry under one peak give one pole of both shapes (a 276 g racket's 3-node twisting and
membrane 1.4 Hz apart, ζ 0.5 %: 38 % even, MAC 0.58 and 0.42 with the two; its 6-node twisting
and (2, 0) membrane 5 Hz apart: 26 %, 0.66 and 0.29); the rig's modes identified alone score
at most 10 % (a 305 g racket's 5-node bending veering with the bed)."""
COUNT_CONTRAST = 2.0
"""Least ratio of the misfit ``1 − MAC`` of a frame mode's shape with the frame's own mode of
the best other node count to its misfit with the best for the count to be named alone (–):
otherwise the name gives both ("3- or 4-node twisting").  The hoop's points sample the twist
over 0.34–0.67 m only, where a held racket's 4-node twisting matched the free frame's 3-node at
0.82 and its 4-node at 0.69 (ratio 1.7; the rig's truth: the 4-node), while a free 5-node
twisting matched its own at 1.00 and the 7-node at 0.85 (ratio > 100)."""
NODE_LEVEL = 0.05
"""Samples smaller than this share of a shape's largest magnitude are taken as on a node when
counting sign changes (–): a node sampled exactly would otherwise count twice or not at all."""


def sign_changes(values: NDArray[np.float64], level: float = NODE_LEVEL) -> int:
    """How often a sampled shape changes sign along its samples, the ones smaller than
    ``level`` times the largest magnitude left out (on a node).

    Parameters
    ----------
    values : ndarray
        The shape at points in order along a line.
    level : float
        Share of the largest magnitude below which a sample is taken as on a node (–).
    """
    values = np.asarray(values, dtype=float)
    scale = float(np.max(np.abs(values))) if values.size else 0.0
    if scale == 0.0:
        return 0
    kept = values[np.abs(values) > level * scale]
    return int(np.count_nonzero(np.diff(np.sign(kept)) != 0))


def membrane_name(across: int, along: int) -> str:
    """A string-bed mode's name from its nodal lines: ``"string-bed membrane"`` for the mode
    whose strings all move in phase, else ``"string-bed membrane (m, n)"`` with m the nodal
    lines met walking along the long axis (lines across the bed) and n those met walking
    across it (lines along the bed)."""
    if (across, along) == (0, 0):
        return "string-bed membrane"
    return f"string-bed membrane ({across}, {along})"


def _bed_powers(degree: int) -> tuple[tuple[int, int], ...]:
    return tuple((a, d - a) for d in range(degree + 1) for a in range(d, -1, -1))


def _bed_basis(
    powers: tuple[tuple[int, int], ...], xi: NDArray[np.float64], eta: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Ritz functions ``(1 − ξ² − η²) ξ^p η^q`` and their ξ and η derivatives, ``(n, n_psi)``."""
    bubble = 1.0 - xi**2 - eta**2
    psi, d_xi, d_eta = [], [], []
    for p, q in powers:
        mono = xi**p * eta**q
        psi.append(bubble * mono)
        d_xi.append(bubble * p * xi ** max(p - 1, 0) * eta**q - 2.0 * xi * mono)
        d_eta.append(bubble * q * xi**p * eta ** max(q - 1, 0) - 2.0 * eta * mono)
    return np.column_stack(psi), np.column_stack(d_xi), np.column_stack(d_eta)


@lru_cache(maxsize=32)
def _bed_reference(
    stiffness_ratio: float,
) -> tuple[NDArray[np.float64], tuple[tuple[int, int], ...]]:
    """The bed's own modes on a still frame: Ritz coefficients ``(n_psi, BED_MODES)`` and each
    mode's nodal lines (across, along)."""
    from scipy.linalg import eigh

    radius, weight = np.polynomial.legendre.leggauss(2 * BED_DEGREE)
    radius, weight = 0.5 * (radius + 1.0), 0.5 * weight
    n_angles = 4 * (BED_DEGREE + 3)
    angle = np.arange(n_angles) * 2.0 * np.pi / n_angles
    r, t = np.meshgrid(radius, angle)
    area = (np.outer(np.full(n_angles, 2.0 * np.pi / n_angles), weight) * r).ravel()
    xi, eta = (r * np.cos(t)).ravel(), (r * np.sin(t)).ravel()
    powers = _bed_powers(BED_DEGREE)
    psi, d_xi, d_eta = _bed_basis(powers, xi, eta)
    mass = psi.T @ (area[:, None] * psi)
    stiffness = d_xi.T @ (area[:, None] * d_xi) + stiffness_ratio * d_eta.T @ (
        area[:, None] * d_eta
    )
    _, vectors = eigh(stiffness, mass, subset_by_index=[0, BED_MODES - 1])
    return vectors, tuple(_nodal_lines(powers, vectors[:, k]) for k in range(BED_MODES))


def _nodal_lines(
    powers: tuple[tuple[int, int], ...], coefficients: NDArray[np.float64]
) -> tuple[int, int]:
    """Sign changes of a bed shape walking along the long axis and across it (through the
    centre, or 0.4 of the half-width (half-length) off it where the shape is odd across it)."""
    grid = np.linspace(-1.0, 1.0, 41)
    gx, gy = np.meshgrid(grid, grid)
    inside = gx**2 + gy**2 < 0.98
    gx, gy = gx[inside], gy[inside]

    def shape(xi: NDArray[np.float64], eta: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(_bed_basis(powers, xi, eta)[0] @ coefficients)

    values = shape(gx, gy)
    scale = float(np.max(np.abs(values)))
    odd_across = float(np.max(np.abs(values + shape(gx, -gy)))) < 1e-6 * scale
    odd_along = float(np.max(np.abs(values + shape(-gx, gy)))) < 1e-6 * scale
    walk = np.linspace(-0.99, 0.99, 397)
    off = 0.4 if odd_across else 0.0
    reach = np.sqrt(1.0 - off**2)
    across = sign_changes(shape(reach * walk, np.full_like(walk, off)))
    off = 0.4 if odd_along else 0.0
    reach = np.sqrt(1.0 - off**2)
    along = sign_changes(shape(np.full_like(walk, off), reach * walk))
    return across, along


def bed_modes(
    head: HeadEllipse, locations: NDArray[np.float64], stiffness_ratio: float | None = None
) -> tuple[NDArray[np.float64], tuple[tuple[int, int], ...]]:
    """The string bed's own modes on a still frame at points on the strings, and their nodal
    lines.

    A membrane on the head's ellipse, fixed at its edge, of even areal density and tension per
    unit width ``T_x`` (mains) and ``T_y`` (crosses): Ritz functions ``(1 − ξ² − η²) ξ^p η^q``
    of degree up to :data:`BED_DEGREE` in the coordinates scaled by the half-axes.  Its shapes
    depend on the tensions only through ``(T_y/b²) / (T_x/a²)``.

    Parameters
    ----------
    head : HeadEllipse
        The string bed.
    locations : ndarray, shape (n, 2)
        Points on the strings, m.
    stiffness_ratio : float, optional
        ``(T_y/b²) / (T_x/a²)`` (–); None for an even tension, ``(a/b)²``.

    Returns
    -------
    shapes : ndarray, shape (n, BED_MODES)
        The first :data:`BED_MODES` modes at the points (unscaled).
    lines : tuple of (int, int)
        Each mode's nodal lines (across the bed, along it): :func:`membrane_name`.
    """
    ratio = (
        (head.half_length_m / head.half_width_m) ** 2
        if stiffness_ratio is None
        else stiffness_ratio
    )
    coefficients, lines = _bed_reference(round(float(ratio), 6))
    xy = np.asarray(locations, dtype=float)
    xi = (xy[:, 0] - head.centre_x_m) / head.half_length_m
    eta = (xy[:, 1] - head.centre_y_m) / head.half_width_m
    return _bed_basis(_bed_powers(BED_DEGREE), xi, eta)[0] @ coefficients, lines


def membrane_names(
    own: NDArray[np.float64],
    locations: NDArray[np.float64],
    head: HeadEllipse,
    stiffness_ratio: float | None = None,
) -> tuple[list[str | None], NDArray[np.float64]]:
    """Each mode's name from the bed's own mode its strings' own motion matches.

    Parameters
    ----------
    own : ndarray, shape (n_points, n_modes)
        The strings' own motion at points on the strings (a mode's shape there less the
        frame's carried under them).
    locations : ndarray, shape (n_points, 2)
        The points, m.
    head : HeadEllipse
        The string bed.
    stiffness_ratio : float, optional
        :func:`bed_modes`'.

    Returns
    -------
    names : list of str or None
        :func:`membrane_name` of the best match, None where no MAC reaches
        :data:`MEMBRANE_MAC`.
    mac : ndarray, shape (n_modes,)
        The best MAC.
    """
    reference, lines = bed_modes(head, locations, stiffness_ratio)
    own = np.asarray(own, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        mac = (reference.T @ own) ** 2 / (
            np.sum(reference**2, axis=0)[:, None] * np.sum(own**2, axis=0)[None, :]
        )
    mac = np.nan_to_num(mac)
    best = np.argmax(mac, axis=0)
    score = mac[best, np.arange(own.shape[1])]
    names: list[str | None] = [
        membrane_name(*lines[b]) if m >= MEMBRANE_MAC else None
        for b, m in zip(best, score, strict=True)
    ]
    return names, score


@dataclass(frozen=True, eq=False)
class ReferenceShapes:
    """What a racket's measured modes are named against: its bed's tensions and its frame's own
    bending and twisting modes (:func:`racketdyn.racket_modal.beam.reference_shapes`).

    Parameters
    ----------
    bed_stiffness_ratio : float or None
        ``(T_y/b²) / (T_x/a²)`` of the bed (:func:`bed_modes`); None for an even tension.
    frame_x : ndarray or None
        Nodes along the long axis, m (None: no frame model; bending and twisting are then
        numbered in order of frequency).
    bending, twisting : ndarray, shape (n_nodes, k)
        The frame's bending ``w(x)`` and twisting ``θ(x)`` shapes on the nodes.
    bending_nodes, twisting_nodes : tuple of int
        Each one's node count as its name says it ("n-node bending").
    """

    bed_stiffness_ratio: float | None = None
    frame_x: NDArray[np.float64] | None = None
    bending: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    twisting: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    bending_nodes: tuple[int, ...] = ()
    twisting_nodes: tuple[int, ...] = ()


_Counts = list[tuple[int | None, float, int | None, float]]
"""Per mode: the node count of the frame's own mode its frame shape matches best (None below
:data:`FRAME_MAC`), that MAC, and the count and MAC of the best match of another count."""


def _frame_counts(
    model: ModalModel, head: HeadEllipse, reference: ReferenceShapes, pairs: NDArray[np.int_]
) -> tuple[_Counts, _Counts]:
    """Each mode's bending and twisting node counts from its frame shape's best MAC with the
    frame's own modes (None below :data:`FRAME_MAC` or without a frame model), with that MAC
    (NaN without a frame model)."""
    n = model.n_modes
    none: _Counts = [(None, float("nan"), None, float("nan"))] * n
    if reference.frame_x is None or model.n_dimensions != 2:
        return none, list(none)
    frame = head.normalised_radius(model.locations) >= ON_STRINGS
    x, y = model.locations[:, 0], model.locations[:, 1]
    shapes = model.mode_shapes
    # the even part at the frame points (a point and its mirror image averaged)
    even = shapes.copy()
    if pairs.size:
        mean = 0.5 * (shapes[pairs[:, 0]] + shapes[pairs[:, 1]])
        even[pairs[:, 0]], even[pairs[:, 1]] = mean, mean
    rows = np.flatnonzero(frame)
    bending = _best_counts(
        even[rows],
        _on_nodes(reference.frame_x, reference.bending, x[rows]),
        reference.bending_nodes,
    )
    twisting = list(none)
    twisted = pairs[frame[pairs[:, 0]]] if pairs.size else pairs
    if twisted.shape[0] >= 2:
        odd = 0.5 * (shapes[twisted[:, 0]] - shapes[twisted[:, 1]]) / y[twisted[:, 0], None]
        twisting = _best_counts(
            odd,
            _on_nodes(reference.frame_x, reference.twisting, x[twisted[:, 0]]),
            reference.twisting_nodes,
        )
    return bending, twisting


def _on_nodes(
    nodes: NDArray[np.float64], shapes: NDArray[np.float64], x: NDArray[np.float64]
) -> NDArray[np.float64]:
    return np.column_stack([np.interp(x, nodes, shapes[:, k]) for k in range(shapes.shape[1])])


def _best_counts(
    measured: NDArray[np.float64], reference: NDArray[np.float64], counts: tuple[int, ...]
) -> _Counts:
    if reference.size == 0:
        return [(None, float("nan"), None, float("nan"))] * measured.shape[1]
    with np.errstate(invalid="ignore", divide="ignore"):
        mac = (reference.T @ measured) ** 2 / (
            np.sum(reference**2, axis=0)[:, None] * np.sum(measured**2, axis=0)[None, :]
        )
    mac = np.nan_to_num(mac)
    best = np.argmax(mac, axis=0)
    found: _Counts = []
    for k, b in enumerate(best):
        other = [j for j in range(len(counts)) if counts[j] != counts[b]]
        rival = max(other, key=lambda j: mac[j, k]) if other else None
        found.append(
            (
                counts[b] if mac[b, k] >= FRAME_MAC else None,
                float(mac[b, k]),
                None if rival is None else counts[rival],
                float("nan") if rival is None else float(mac[rival, k]),
            )
        )
    return found


def _mirror_pairs(locations: NDArray[np.float64]) -> NDArray[np.int_]:
    """Index pairs (i, j) with point j the mirror image of point i across y = 0 (y_i > 1 cm)."""
    pairs = []
    for i, (x, y) in enumerate(locations):
        if y <= MIRROR_TOLERANCE_M:
            continue
        distance = np.hypot(locations[:, 0] - x, locations[:, 1] + y)
        j = int(np.argmin(distance))
        if distance[j] <= MIRROR_TOLERANCE_M:
            pairs.append((i, j))
    return np.asarray(pairs, dtype=int).reshape(-1, 2)


def naming_evidence(model: ModalModel, head: HeadEllipse) -> str:
    """Why the shapes cannot tell a racket's modes apart, or "" when they can.

    Twisting needs points mirrored across the long axis (two pairs or more); string-bed needs
    points on the strings and on the frame; unscaled shapes are compared as they are (the
    tests are ratios, so scaling does not matter).

    Parameters
    ----------
    model : ModalModel
        Shapes at face points (x, y), m.
    head : HeadEllipse
        The string bed.
    """
    if model.n_dimensions != 2:
        return "the points are not on the racket's face (x, y)"
    on_strings = head.normalised_radius(model.locations) < ON_STRINGS
    missing = []
    if _mirror_pairs(model.locations).shape[0] < 2:
        missing.append("points mirrored across the long axis (for twisting)")
    if not on_strings.any() or on_strings.all():
        missing.append("points on both the strings and the frame (for string-bed modes)")
    return "no " + " nor ".join(missing) if missing else ""


def bed_own_motion(
    model: ModalModel, head: HeadEllipse
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """How much each mode's strings move on their own, and whether with their frame or against.

    The frame's motion under the bed, ``w(x) + θ(x)·y`` with ``w`` and ``θ`` polynomials of
    degree :data:`HOOP_DEGREE` in x, is fitted (least squares) to the shape at the hoop's points
    (elliptic radius from :data:`ON_STRINGS` to :data:`HOOP_REACH`) and carried to the string
    points (radius below it); the strings' own motion is their shape less that.

    Parameters
    ----------
    model : ModalModel
        Shapes at face points (x, y), m.
    head : HeadEllipse
        The string bed.

    Returns
    -------
    ratio, correlation : ndarray, shape (n_modes,)
        Mean square of the strings' own motion over the carried motion's (–), and the
        correlation of the two over the string points (−1 … 1: positive when the strings move
        with the frame).  NaN for every mode when the hoop's points cannot fix the fit (too few,
        or not on both sides of the long axis) or no point is on the strings.
    """
    nan = np.full(model.n_modes, np.nan)
    fitted = _carried_under_bed(model, head)
    if fitted is None:
        return nan, nan.copy()
    on_strings, carried = fitted
    own = model.mode_shapes[on_strings] - carried
    square_own, square_carried = np.sum(own**2, axis=0), np.sum(carried**2, axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = square_own / square_carried
        correlation = np.sum(own * carried, axis=0) / np.sqrt(square_own * square_carried)
    return np.asarray(ratio, dtype=float), np.asarray(correlation, dtype=float)


def _carried_under_bed(
    model: ModalModel, head: HeadEllipse
) -> tuple[NDArray[np.bool_], NDArray[np.float64]] | None:
    """The string points, and the frame's motion carried under them: ``w(x) + θ(x)·y`` fitted
    (least squares) to the shapes at the hoop's points (:func:`bed_own_motion`); None when
    the hoop's points cannot fix the fit or no point is on the strings."""
    if model.n_dimensions != 2 or model.n_modes == 0:
        return None
    rho = head.normalised_radius(model.locations)
    on_strings = rho < ON_STRINGS
    hoop = (rho >= ON_STRINGS) & (rho < HOOP_REACH)

    def basis(xy: NDArray[np.float64]) -> NDArray[np.float64]:
        t = (xy[:, 0] - head.centre_x_m) / head.half_length_m
        powers = np.column_stack([t**p for p in range(HOOP_DEGREE + 1)])
        across = (xy[:, 1] - head.centre_y_m) / head.half_width_m
        return np.column_stack([powers, powers * across[:, None]])

    fit = basis(model.locations[hoop])
    if (
        not on_strings.any()
        or fit.shape[0] <= fit.shape[1]
        or (np.linalg.matrix_rank(fit) < fit.shape[1])
    ):
        return None
    coefficients = np.linalg.lstsq(fit, model.mode_shapes[hoop], rcond=None)[0]
    return on_strings, basis(model.locations[on_strings]) @ coefficients


def frame_under_bed(model: ModalModel, head: HeadEllipse) -> ModalModel:
    """The model an impact model charges: at the string points, the frame's motion under the bed.

    A mode's measured shape at a point on the strings is the frame's motion carried under the
    bed plus the strings' own motion (:func:`bed_own_motion`).  The impact models put the
    strings' own give in the ball–string law (eqs 6-9), so a shape that carries it too counts
    the strings twice: on the built-in racket's played bed the rig's model, taken as measured,
    rebounds at 0.395 at the centre (20 m/s, free) against 0.377 from the same frame's beam
    model, and the identified model, whose membrane and 4-node bending are named neither,
    at 0.413; with the frame's motion under the bed all three give 0.377 (docs/develop.md,
    issue 22, seventh session).  The string points' shapes are replaced by the fit of
    ``w(x) + θ(x)·y`` to the hoop's points; the rest are kept.  A model whose points cannot
    fix the fit (no hoop or no string points, shapes along a line) is returned as it is; so
    is a model of the frame (the built-in beam model, :data:`SHAPES_FRAME_MODEL`) or one this
    function has returned already (:data:`SHAPES_ON_STRINGS`).

    Parameters
    ----------
    model : ModalModel
        Shapes at face points (x, y), m.
    head : HeadEllipse
        The string bed.

    Returns
    -------
    ModalModel
        With ``metadata["shapes_on_strings"]`` saying which was used
        (:data:`SHAPES_FRAME_UNDER_BED` or :data:`SHAPES_AS_MEASURED`).
    """
    if model.metadata.get("shapes_on_strings") in SHAPES_ON_STRINGS:
        return model
    # one object per model and head: results computed by chunks of points are joined only
    # when their models are one object (ImpactResult.concatenate), and each new model would
    # build its shapes' interpolator again
    known = _UNDER_BED.setdefault(model, {})
    if head not in known:
        known[head] = _under_bed(model, head)
    return known[head]


_UNDER_BED: WeakKeyDictionary[ModalModel, dict[HeadEllipse, ModalModel]] = WeakKeyDictionary()


def _under_bed(model: ModalModel, head: HeadEllipse) -> ModalModel:
    """:func:`frame_under_bed` computed."""
    fitted = _carried_under_bed(model, head)
    if fitted is None:
        return replace(model, metadata={**model.metadata, "shapes_on_strings": SHAPES_AS_MEASURED})
    on_strings, carried = fitted
    shapes = model.mode_shapes.copy()
    shapes[on_strings] = carried
    return replace(
        model,
        mode_shapes=shapes,
        metadata={**model.metadata, "shapes_on_strings": SHAPES_FRAME_UNDER_BED},
    )


def rigid_share(model: ModalModel, head: HeadEllipse) -> NDArray[np.float64]:
    """Share of each mode's frame shape that a rigid-body motion of the face explains (–).

    The least-squares plane ``a + b x + c y`` through the shape at the frame points (outside
    95 % of the bed's elliptic radius), its sum of squares over the shape's; NaN when the frame
    points cannot fix a plane (fewer than four, or all on one line).

    Parameters
    ----------
    model : ModalModel
        Shapes at face points (x, y), m.
    head : HeadEllipse
        The string bed, to tell string points from frame points.
    """
    frame = head.normalised_radius(model.locations) >= ON_STRINGS
    return _plane_share(model, np.flatnonzero(frame))


def _plane_share(model: ModalModel, rows: NDArray[np.intp]) -> NDArray[np.float64]:
    """Share of each mode's shape at the points ``rows`` that a plane a + b x + c y explains;
    NaN when those points cannot fix a plane (fewer than four, or all on one line)."""
    plane = np.column_stack([np.ones(rows.size), model.locations[rows, :2]])
    if plane.shape[0] < 4 or np.linalg.matrix_rank(plane) < 3:
        return np.full(model.n_modes, np.nan)
    phi = model.mode_shapes[rows]
    fitted = plane @ np.linalg.lstsq(plane, phi, rcond=None)[0]
    total = np.sum(phi**2, axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.asarray(np.sum(fitted**2, axis=0) / total, dtype=float)


def outline_rigid_share(model: ModalModel) -> NDArray[np.float64]:
    """Share of each mode's shape on the points' outline that a plane ``a + b x + c y`` explains.

    :func:`rigid_share` without a head: the frame points are the vertices of the convex hull
    of the face points (x, y) — the hoop and the handle's end, never a string point, whatever
    the racket — so a racket measured without its head outline (``identify`` without
    ``--racket``) can still show the nearly rigid frame of a ball on the strings.  NaN when
    the hull has fewer than four vertices.

    Parameters
    ----------
    model : ModalModel
        Shapes at face points (x, y), m.
    """
    from scipy.spatial import ConvexHull, QhullError

    points = np.asarray(model.locations, dtype=float)[:, :2]
    try:
        vertices = ConvexHull(points).vertices
    except (QhullError, ValueError):  # fewer than three points, or all on a line
        return np.full(model.n_modes, np.nan)
    return _plane_share(model, np.asarray(vertices, dtype=np.intp))


def ball_mode_index(model: ModalModel, head: HeadEllipse) -> int:
    """Index of the ball mode of a racket with a ball on its strings, or −1 if no mode's frame
    shape is rigid enough (:data:`BALL_RIGID_SHARE`).

    Parameters
    ----------
    model : ModalModel
        Shapes at face points (x, y), m.
    head : HeadEllipse
        The string bed.
    """
    share = rigid_share(model, head)
    if model.n_modes == 0 or not np.any(np.isfinite(share)):
        return -1
    k = int(np.nanargmax(share))
    return k if share[k] > BALL_RIGID_SHARE else -1


def classify_modes(
    model: ModalModel,
    head: HeadEllipse,
    ball_at: tuple[float, float] | None = None,
    reference: ReferenceShapes | None = None,
) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Names and kinds of a racket's modes from their shapes (see the module docstring).

    Parameters
    ----------
    model : ModalModel
        Shapes at measured points (frame and strings).
    head : HeadEllipse
        The string bed, to tell string points from frame points.
    ball_at : tuple of float, optional
        Where a ball was fixed on the strings during the test (x, y), m: one mode is then
        named :data:`BALL_MODE_NAME` (kind ``other``) if its frame shape shows it
        (:func:`ball_mode_index`).
    reference : ReferenceShapes, optional
        The racket's bed tensions and frame modes
        (:func:`racketdyn.racket_modal.beam.reference_shapes`): bending and twisting modes take
        their node counts from them; without it (or below :data:`FRAME_MAC`) they are
        numbered in order of frequency, and the bed's own modes are those of an even tension.

    Returns
    -------
    names, kinds : tuple of str
        Names (``"2-node bending"`` …) and kinds (``bending``, ``twisting``, ``string-bed``,
        ``other`` for the ball, ``unknown`` where the shape does not say).
    """
    names, kinds, _, _ = _classify(model, head, ball_at, reference)
    return names, kinds


def naming_reasons(
    model: ModalModel,
    head: HeadEllipse,
    ball_at: tuple[float, float] | None = None,
    reference: ReferenceShapes | None = None,
) -> tuple[str, ...]:
    """Why each mode :func:`classify_modes` leaves ``unknown`` is so ("" for a named mode).

    Parameters
    ----------
    model, head, ball_at, reference
        As :func:`classify_modes`.

    Returns
    -------
    tuple of str
        One clause per mode, e.g. "its strings move 16 times its frame in mean square, their
        own motion matches the bed's (1, 1) mode (MAC 0.90) as well as its frame the 6-node
        twisting (0.86)".
    """
    return _classify(model, head, ball_at, reference)[2]


def naming_words(
    model: ModalModel,
    head: HeadEllipse,
    ball_at: tuple[float, float] | None = None,
    reference: ReferenceShapes | None = None,
) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Why each mode is ``unknown`` (:func:`naming_reasons`) and what makes a named mode's
    name uncertain ("" for a name the shape supports), from one classification.

    Two cases (module docstring): a node count the frame's shape does not tell from another
    (:data:`COUNT_CONTRAST`: the name gives both), and a frame mode named in the unclear band
    (strings 4–40 times the frame in mean square) whose strings match a bed mode no other mode
    of the model is named after — a member of a veering pair whose partner is not found,
    which carries some of the partner's shape and may hold as much of its energy in the
    strings as in the frame.

    Parameters
    ----------
    model, head, ball_at, reference
        As :func:`classify_modes`.

    Returns
    -------
    reasons, notes : tuple of str
        One clause per mode each.
    """
    _, _, reasons, notes = _classify(model, head, ball_at, reference)
    return reasons, notes


def _classify(
    model: ModalModel,
    head: HeadEllipse,
    ball_at: tuple[float, float] | None,
    reference: ReferenceShapes | None,
) -> tuple[tuple[str, ...], tuple[str, ...], tuple[str, ...], tuple[str, ...]]:
    """Names, kinds, the reasons for each ``unknown`` and the notes on uncertain names
    (:func:`classify_modes`, :func:`naming_reasons`, :func:`naming_words`)."""
    locations, shapes = model.locations, model.mode_shapes
    on_strings = head.normalised_radius(locations) < ON_STRINGS
    pairs = _mirror_pairs(locations)
    names, kinds, reasons = [], [], []
    counts = {"bending": 0, "twisting": 0, "string-bed": 0}
    unclear = False
    ball = -1 if ball_at is None else ball_mode_index(model, head)
    # the strings' own motion from the symmetric part (even in y) of a mode mostly even: a
    # twisting neighbour's leak, odd and carried by the frame, would read as the frame's
    even = model.mode_shapes.copy()
    if pairs.size:
        mean = 0.5 * (shapes[pairs[:, 0]] + shapes[pairs[:, 1]])
        even[pairs[:, 0]], even[pairs[:, 1]] = mean, mean
    own_ratio, own_correlation = bed_own_motion(model, head)
    even_ratio, even_correlation = bed_own_motion(replace(model, mode_shapes=even), head)
    reference = reference or ReferenceShapes()
    membrane, membrane_mac = _membrane_names(model, head, reference)
    # each part's bed mode, for a mode that mixes a frame mode with one of the other symmetry
    parts = {
        "even": replace(model, mode_shapes=even),
        "odd": replace(model, mode_shapes=model.mode_shapes - even),
    }
    part_beds = {part: _membrane_names(m, head, reference)[0] for part, m in parts.items()}
    bed_lines = [
        "the bed's own mode" if name is None else f"the bed's {name.removeprefix('string-bed ')}"
        for name in membrane
    ]
    bending_nodes, twisting_nodes = _frame_counts(model, head, reference, pairs)
    square_ratio = np.full(model.n_modes, np.inf)
    from_band: list[int] = []  # frame modes named in the unclear band by their frame shape
    notes: list[str] = []
    frame_macs = np.full(model.n_modes, np.nan)
    for k in range(model.n_modes):
        reasons.append("")
        notes.append("")
        if k == ball:
            names.append(BALL_MODE_NAME)
            kinds.append("other")
            continue
        phi = shapes[:, k]
        strings = np.mean(phi[on_strings] ** 2) if on_strings.any() else 0.0
        frame = np.mean(phi[~on_strings] ** 2) if (~on_strings).any() else np.inf
        if frame > 0:
            square_ratio[k] = strings / frame
        odd_fraction = 0.0
        if pairs.size:
            odd = 0.5 * (phi[pairs[:, 0]] - phi[pairs[:, 1]])
            even = 0.5 * (phi[pairs[:, 0]] + phi[pairs[:, 1]])
            total = np.sum(odd**2 + even**2)
            odd_fraction = float(np.sum(odd**2) / total) if total > 0 else 0.0
        unclear_ratio = STRING_BED_RATIO * frame < strings <= CLEAR_STRING_BED_RATIO * frame
        # in the unclear band, the strings' own motion against the frame's (module docstring)
        ratio, correlation = (
            (even_ratio[k], even_correlation[k])
            if odd_fraction <= 0.5
            else (own_ratio[k], own_correlation[k])
        )
        bed_follows = correlation > 0 and ratio < BED_OWN_RATIO
        # drawn from even modes: an odd mode's carried motion is the hoop's twist θ(x)·y, which
        # both members of an odd veering pair leave small beside their strings (module docstring)
        frame_recoils = (
            odd_fraction <= 0.5 and correlation < -RECOIL_CORRELATION and ratio > BED_OWN_RATIO
        )
        kind = "twisting" if odd_fraction > 0.5 else "bending"
        nodes, frame_mac, rival, rival_mac = (
            twisting_nodes if kind == "twisting" else bending_nodes
        )[k]
        frame_macs[k] = frame_mac
        # the frame's shape says more than the strings': the frame matches one of its own modes
        # better than the strings' own motion matches one of the bed's (module docstring)
        frame_says = nodes is not None and frame_mac > np.nan_to_num(membrane_mac[k])
        if (
            (odd_fraction <= 0.5 and _in_phase_membrane(phi, pairs, on_strings))
            or (unclear_ratio and frame_recoils)
            or (strings > STRING_BED_RATIO * frame and not unclear_ratio)
        ):
            names.append(membrane[k] or f"string-bed membrane ({model.frequency[k]:.1f} Hz)")
            kinds.append("string-bed")
            continue
        if unclear_ratio and not bed_follows and not frame_says:
            unclear = True
            names.append(f"mode {k + 1} ({model.frequency[k]:.1f} Hz)")
            kinds.append("unknown")
            reasons[k] = _unknown_reason(
                float(strings / frame),
                ratio,
                correlation,
                (bed_lines[k], membrane_mac[k]),
                (nodes, kind, frame_mac),
            )
            continue
        if unclear_ratio and not bed_follows:
            from_band.append(k)
        counts[kind] += 1
        count = f"{nodes}"
        if (
            nodes is not None
            and rival is not None
            and 1 - rival_mac < COUNT_CONTRAST * (1 - frame_mac)
        ):
            low, high = sorted((nodes, rival))
            count = f"{low}- or {high}"
            notes[k] = (
                f"its frame matches the {nodes}-node {kind} (MAC {frame_mac:.2f}) and the "
                f"{rival}-node (MAC {rival_mac:.2f}) nearly as well: the points cannot tell the "
                "count"
            )
        if kind == "twisting":
            names.append(f"{counts['twisting'] + 1 if nodes is None else count}-node twisting")
        # after a mode the shape could not name, the bending order is no longer known
        elif nodes is not None:
            names.append(f"{count}-node bending")
        elif unclear:
            names.append(f"bending mode ({model.frequency[k]:.1f} Hz)")
        else:
            names.append(f"{counts['bending'] + 1}-node bending")
        kinds.append(kind)
        mixed = (1.0 - odd_fraction) if kind == "twisting" else odd_fraction
        if pairs.size and mixed >= MIXED_SHARE:
            part = "even" if kind == "twisting" else "odd"
            other = _other_part(parts[part], part_beds[part][k], k, on_strings)
            if other is None:
                other = (
                    _other_count(bending_nodes, k, "bending")
                    if kind == "twisting"
                    else _other_count(twisting_nodes, k, "twisting")
                )
            name = f"{names[-1]} mixed with {other or f'a mode {part} in y'}"
            names[-1], kinds[-1], notes[k] = name, "unknown", ""
            reasons[k] = (
                f"{mixed:.0%} of its shape at the points is {part} in y, the rest the "
                f"{kind}'s: two modes of opposite symmetry under one peak, fitted as one"
            )
    _one_mode_a_frame_name(names, kinds, reasons, from_band, square_ratio, membrane, model)
    for k in from_band:
        bed = membrane[k]
        if kinds[k] in ("bending", "twisting") and bed is not None and bed not in names:
            notes[k] = (
                f"its frame matches the {names[k]} (MAC {frame_macs[k]:.2f}) and its strings' "
                f"own motion the bed's {bed.removeprefix('string-bed ')} mode (MAC "
                f"{membrane_mac[k]:.2f}), which no other mode here is named after: a frame "
                "mode veering with the bed, its "
                "partner not found; the points cannot tell whether the frame or the strings "
                "hold more of its energy"
            )
    return _unique(names), tuple(kinds), tuple(reasons), tuple(notes)


def _other_part(
    part: ModalModel, bed: str | None, k: int, on_strings: NDArray[np.bool_]
) -> str | None:
    """The bed mode a part of mode ``k``'s shape (even or odd in y) is, when its strings move
    more than :data:`STRING_BED_RATIO` times its frame in mean square and match one."""
    phi = part.mode_shapes[:, k]
    if bed is None or on_strings.all() or not on_strings.any():
        return None
    strings, frame = np.mean(phi[on_strings] ** 2), np.mean(phi[~on_strings] ** 2)
    return bed if strings > STRING_BED_RATIO * frame else None


def _other_count(counts: _Counts, k: int, kind: str) -> str | None:
    """The frame mode of the other symmetry (``kind``) that mode ``k``'s frame matches, if
    any."""
    nodes = counts[k][0]
    return None if nodes is None else f"{nodes}-node {kind}"


def _unknown_reason(
    square_ratio: float,
    own_ratio: float,
    correlation: float,
    bed: tuple[str, float],
    frame: tuple[int | None, str, float],
) -> str:
    """Why a mode in the unclear band (strings 4-40 times the frame) stays ``unknown``."""
    head = f"its strings move {square_ratio:.0f} times its frame in mean square"
    if not np.isfinite(own_ratio):
        return head + " and the hoop's points cannot fix the frame's motion under the bed"
    nodes, kind, frame_mac = frame
    said = (
        f"its frame matches the {nodes}-node {kind} ({frame_mac:.2f})"
        if nodes is not None
        else (
            f"its frame matches none of the frame's own {kind} modes"
            + ("" if np.isnan(frame_mac) else f" (best MAC {frame_mac:.2f})")
        )
    )
    return (
        f"{head}, their own motion {own_ratio:.0f} times the carried at correlation "
        f"{correlation:+.2f} (neither a bed following its frame, in phase and under "
        f"{BED_OWN_RATIO:.0f} times, nor a frame recoiling, over {BED_OWN_RATIO:.0f} times at "
        f"{-RECOIL_CORRELATION:+.1f} or below), their own motion matches {bed[0]} (MAC "
        f"{np.nan_to_num(bed[1]):.2f}) at least as well as {said}: a veering pair the shapes "
        "at the points cannot part"
    )


def _one_mode_a_frame_name(
    names: list[str],
    kinds: list[str],
    reasons: list[str],
    from_band: list[int],
    square_ratio: NDArray[np.float64],
    membrane: list[str | None],
    model: ModalModel,
) -> None:
    """Of modes given one frame name where one of them was named in the unclear band by its
    frame's shape, the one moving its strings least against its frame (mean square) keeps it:
    the two members of a veering pair share the frame's and the bed's shapes, and the one
    whose strings move less holds more of its energy in the frame.  The others (of the band)
    take the bed's name their strings' own motion matches, or stay ``unknown``."""
    for name in {names[k] for k in from_band}:
        sharing = [k for k, n in enumerate(names) if n == name]
        if len(sharing) < 2:
            continue
        kept = min(sharing, key=lambda k: square_ratio[k])
        for k in sharing:
            if k == kept or k not in from_band:
                continue
            bed = membrane[k]
            if bed is not None:
                names[k], kinds[k] = bed, "string-bed"
                continue
            names[k], kinds[k] = f"mode {k + 1} ({model.frequency[k]:.1f} Hz)", "unknown"
            reasons[k] = (
                f"its frame matches the {name} as the mode at {model.frequency[kept]:.1f} Hz "
                "does, which moves its strings less, and its strings match none of the bed's "
                "own modes"
            )


def _membrane_names(
    model: ModalModel, head: HeadEllipse, reference: ReferenceShapes
) -> tuple[list[str | None], NDArray[np.float64]]:
    """Each mode's name from the bed's own mode its strings' own motion matches
    (:func:`membrane_names`; the shape at the string points as it is where the hoop's points
    cannot fix the frame's motion under the bed)."""
    fitted = _carried_under_bed(model, head)
    if fitted is None:
        if model.n_dimensions != 2:
            return [None] * model.n_modes, np.full(model.n_modes, np.nan)
        on_strings = head.normalised_radius(model.locations) < ON_STRINGS
        if not on_strings.any():
            return [None] * model.n_modes, np.full(model.n_modes, np.nan)
        own = model.mode_shapes[on_strings]
    else:
        on_strings, carried = fitted
        own = model.mode_shapes[on_strings] - carried
    return membrane_names(own, model.locations[on_strings], head, reference.bed_stiffness_ratio)


def _in_phase_membrane(
    phi: NDArray[np.float64], pairs: NDArray[np.int_], on_strings: NDArray[np.bool_]
) -> bool:
    """Whether a mode's symmetric part moves every string point in phase with the frame nearly
    still (:data:`IN_PHASE_SHARE`, :data:`CLEAR_STRING_BED_RATIO`): the first membrane mode,
    whatever a twisting neighbour (odd in y) added to its measured shape."""
    if not on_strings.any() or on_strings.all():
        return False
    even = np.array(phi, dtype=float)
    if pairs.size:
        even[pairs[:, 0]] = even[pairs[:, 1]] = 0.5 * (phi[pairs[:, 0]] + phi[pairs[:, 1]])
    strings = even[on_strings]
    spread = float(np.sum(np.abs(strings)))
    if spread == 0.0 or abs(float(np.sum(strings))) < IN_PHASE_SHARE * spread:
        return False
    frame = float(np.mean(even[~on_strings] ** 2))
    return bool(np.mean(strings**2) > CLEAR_STRING_BED_RATIO * frame)


def _unique(names: list[str]) -> tuple[str, ...]:
    seen: dict[str, int] = {}
    out = []
    for name in names:
        seen[name] = seen.get(name, 0) + 1
        out.append(name if seen[name] == 1 else f"{name} ({seen[name]})")
    return tuple(out)


def axis_nodes(
    model: ModalModel, mode: int, x_range: tuple[float, float], y_m: float = 0.0, samples: int = 681
) -> NDArray[np.float64]:
    """Positions of a mode's nodes along a line parallel to the long axis (paper, Fig. 6), m.

    Zero crossings of the interpolated shape on ``samples`` points between ``x_range``, refined
    by linear interpolation between the two samples either side
    (:func:`racketdyn.modal.shapes.nodes_along` on that line).

    Parameters
    ----------
    model : ModalModel
        The racket's mode shapes.
    mode : int
        Index of the mode (0-based).
    x_range : tuple of float
        Ends of the line, x from the butt, m.
    y_m : float
        Offset of the line from the long axis, m.
    samples : int
        Points along the line (681: 1 mm apart over a 680 mm racket).

    Returns
    -------
    ndarray
        x of each node, m, from the butt towards the tip.
    """
    x = np.linspace(x_range[0], x_range[1], samples)
    return np.asarray(nodes_along(model, np.column_stack([x, np.full_like(x, y_m)]), mode)[:, 0])
