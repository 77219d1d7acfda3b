"""Step ``rig``: a virtual roving-hammer test of a racket model.

Writes ``hammer_<support>.uff`` (geometry + time records), ``modal_truth_<support>.json`` (the
rig's modes at the test points, butt and tip) and ``run.json``.  With ``ball_at`` a ball is
fixed on the strings (the paper's compound test, section 3.2: :mod:`racketdyn.rig.ball`); the
hammer then skips the points under the ball.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.ball import Ball
from racketdyn.contact import membrane_patch_radius
from racketdyn.errors import InputError, one_of, require_range, require_whole, require_words
from racketdyn.impact.compound import (
    PRELOAD_N,
    ball_spring,
    restitution_damping_ratio,
    small_amplitude_e_bg,
)
from racketdyn.io import racket_to_dict, write_hammer_uff
from racketdyn.measurement import HammerRecords
from racketdyn.modal import ModalModel
from racketdyn.racket import Racket
from racketdyn.rig import (
    Acquisition,
    HammerBlows,
    HammerFaults,
    SensorNoise,
    accelerometer_index,
    hammer_points,
    rig_model,
    simulate_hammer_test,
    string_contact_time,
)
from racketdyn.rig.ball import StuckBall, ball_on_strings
from racketdyn.rig.hammer import FRAME_PULSE_S
from racketdyn.workflows.inputs import ball_location, load_racket_input
from racketdyn.workflows.run import (
    Progress,
    StepResult,
    report,
    run_step,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

__all__ = ["DEFAULT_RIG", "RIG_SUPPORTS", "RigOptions", "RigResult", "run_rig", "support_stream"]

RIG_SUPPORTS = ("free", "hand")


@dataclass
class RigResult(StepResult):
    """What :func:`run_rig` simulated and wrote, by support.

    Attributes
    ----------
    supports : list of str
        The supports tested, in order (``free``, ``hand``).
    records : dict of str to HammerRecords
        The simulated hammer test of each support.
    truth : dict of str to ModalModel
        The rig's modes of each support (the truth identification should find).
    reference_node : int
        The accelerometer's node (the same for every support).
    faults : dict of str to dict
        Counts of ``double_hits`` and ``overloads`` of each support.
    ball : dict or None
        The ball fixed on the strings (``location_m``, ``mass_kg``, ``stiffness_n_per_m``,
        ``damping_ratio``, ``preload_n``), None without one.
    """

    supports: list[str] = field(default_factory=list)
    records: dict[str, HammerRecords] = field(default_factory=dict)
    truth: dict[str, ModalModel] = field(default_factory=dict)
    reference_node: int = 0
    faults: dict[str, dict[str, int]] = field(default_factory=dict)
    ball: dict[str, Any] | None = None


def support_stream(seed: int, support: str) -> np.random.SeedSequence:
    """The random stream of one support's hammer test: its own, reproducible from the seed.

    Each test draws its hits, faults and noise from its own stream, so one seed gives the free
    and the hand-held test different draws (they had the same: identical fault counts), and a
    support's records are the same whether it is tested alone or with the other.  ``free``
    keeps the seed's own stream (its records are those of earlier versions); each other
    support takes the child stream keyed by its place in :data:`RIG_SUPPORTS`
    (``SeedSequence(seed, spawn_key=(k,))``: the stream ``SeedSequence(seed).spawn`` would
    give as its ``k``-th child).

    Parameters
    ----------
    seed : int
        The run's seed (≥ 0).
    support : {"free", "hand"}
        The support tested.

    Returns
    -------
    numpy.random.SeedSequence
        Seed of the support's generator (``numpy.random.default_rng(stream)``).
    """
    one_of("`support`", support, RIG_SUPPORTS)
    key = RIG_SUPPORTS.index(support)
    if key == 0:
        return np.random.SeedSequence(seed)
    return np.random.SeedSequence(seed, spawn_key=(key,))


def _stream_words(seed: int, support: str) -> str:
    key = RIG_SUPPORTS.index(support)
    if key == 0:
        return f"numpy.random.default_rng(SeedSequence({seed}))"
    return f"numpy.random.default_rng(SeedSequence({seed}, spawn_key=({key},)))"


@dataclass(frozen=True)
class RigOptions:
    """How the virtual hammer test is run: supports, hits, faults, noise, and how the file is
    written.

    The fields are the words the library's errors name in backticks (``averages``), which
    the CLI turns into its flags (:func:`racketdyn.cli.options.in_flags`); they are checked
    when :func:`run_rig` runs.

    Attributes
    ----------
    support : {"free", "hand"} or sequence of them
        On a sponge, or held by a hand; both (``("free", "hand")``, or ``"free,hand"`` as the
        command line spells it) test the racket twice into the one folder, as the paper does
        (``hammer_<support>.uff`` each).
    averages : int
        Hits per point.
    double_hits, overloads : float
        Probability of a double hit and of an overload per hit (0 to 1).
    seed : int
        Random seed; each support draws from its own stream of it (:func:`support_stream`).
    binary : bool
        Write binary UFF 58b (default; the records' doubles themselves, ≈ 2.4 times smaller
        than the text form and faster to write); False writes ASCII data sets 58 (12
        significant digits).
    ball_at : sequence of float, optional
        Fix a ball on the strings at (x, y), m (the paper's section 3.2); its spring is the
        ball's one-sided law's tangent at :data:`~racketdyn.impact.compound.PRELOAD_N` (the
        rig's membrane is the string bed), its dashpot from e_BG, and it presses the patch
        of strings where the string net is as stiff as the string bed's law at that preload
        (:func:`~racketdyn.contact.membrane_patch_radius`).
    force_snr_db, response_snr_db : float, optional
        Hammer and accelerometer noise as a signal-to-noise ratio, dB (each record's peak over
        its noise rms); default: the fixed noise floors of 0.02 N and 0.05 m/s² rms
        (:func:`~racketdyn.rig.simulate_hammer_test`).
    pretrigger_s : float
        Time recorded before the pulse, s (default 0.01).
    time_zero : {"pulse", "record"}
        Where the file's time axis starts: ``pulse`` (t = 0 at the pulse, the pre-trigger
        negative) or ``record`` (t = 0 at the record's first sample, the pulse
        ``pretrigger_s`` into it, as many acquisition systems export).
    response_direction : {3, -3}
        The accelerometer's direction code: +z (along the hammer) or −z (mounted against it;
        the records hold what it measures and the code says so).
    driving_point : bool
        Strike the accelerometer's node too (default).  False leaves it out: identification
        then gives unscaled shapes, as from a lab that did not measure it.
    lab_plane : {"xy", "xz"}
        The lab plane the file's coordinates put the face in: ``xz`` writes (x, 0, y) with
        the normal along y (direction codes ±2), a racket measured standing; ``frf`` then
        reads the records without coordinates and ``identify --geometry hammer_<support>.uff``
        takes the (x, y, z) points and maps them onto the face.
    layout : {"roving hammer", "roving accelerometer"}
        ``roving accelerometer`` (or the command line's ``roving-accelerometer``): the hammer
        strikes the reference node (node 10, its pulse for every hit) and the accelerometer is
        moved over the points; by reciprocity the same FRFs (the file says it:
        :func:`~racketdyn.io.write_hammer_uff`'s ``layout``).
    """

    support: str | Sequence[str] = "free"
    averages: int = 10
    double_hits: float = 0.0
    overloads: float = 0.0
    seed: int = 1
    binary: bool = True
    ball_at: Sequence[float] | None = None
    force_snr_db: float | None = None
    response_snr_db: float | None = None
    pretrigger_s: float = 0.01
    time_zero: str = "pulse"
    response_direction: int = 3
    driving_point: bool = True
    lab_plane: str = "xy"
    layout: str = "roving hammer"


DEFAULT_RIG = RigOptions()
"""A free racket, 10 hits per point, no faults, the fixed noise floors, a binary file."""


@dataclass(frozen=True)
class _TestPoints:
    """Where the hammer strikes (``locations``, ``nodes``) and where the accelerometer sits."""

    locations: NDArray[np.float64]
    nodes: tuple[int, ...]
    reference_location: tuple[float, float]
    reference_node: int


@run_step
def run_rig(
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    options: RigOptions = DEFAULT_RIG,
) -> RigResult:
    """Simulate a roving-hammer test on the virtual rig and write the run folder.

    The options checked, the ball's spring and the struck points found, each support tested
    (:func:`_test_support`) and run.json written.

    Parameters
    ----------
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, rig uses the racket and the ball of
        ``ball_at``; and the run (command, figures, progress).
    options : RigOptions
        Supports, hits per point, faults, seed, noise, and how the file is written.
    """
    options = _checked(options)
    supports = list(options.support)
    the_racket, provenance = load_racket_input(setup.racket)
    spring, ball_record, under_ball = None, None, None
    if options.ball_at is not None:
        the_ball = setup.ball or Ball()
        spring, ball_record = _ball_spring(the_racket, the_ball, options.ball_at)
        under_ball = (spring.location, the_ball.diameter_m)
    points = _TestPoints(*_struck_points(the_racket, under_ball, options.driving_point))
    result = RigResult(
        Path(out), supports=supports, reference_node=points.reference_node, ball=ball_record
    )
    runs = {
        each: _test_support(result, the_racket, each, points, spring, options, setup.progress)
        for each in supports
    }
    inputs = {
        **provenance,
        "racket": racket_to_dict(the_racket),
        "supports": supports,
        "reference_node": points.reference_node,
        "reference_location_m": points.reference_location,
        "driving_point": options.driving_point,
        "accelerometer_direction": options.response_direction,
        "force_snr_db": options.force_snr_db,
        "response_snr_db": options.response_snr_db,
        "pretrigger_s": options.pretrigger_s,
        "time_zero": options.time_zero,
        "lab_plane": options.lab_plane,
        "layout": options.layout,
        "n_points": len(points.nodes),
        "averages": options.averages,
        "double_hit_probability": options.double_hits,
        "overload_probability": options.overloads,
        "seed": options.seed,
        "ball_on_strings": ball_record,
        "runs": runs,
    }
    return setup.finish(result, inputs, "rig")


def _checked(options: RigOptions) -> RigOptions:
    """Refuse options out of range (named by their field, as the CLI translates them); the
    options in one spelling: the supports a tuple, the layout in words (the command line's
    ``"free,hand"`` and ``roving-accelerometer`` taken from Python too)."""
    supports = require_words("`support`", options.support)
    if len(set(supports)) < len(supports):
        raise InputError(
            f"`support`: name each support once, free, hand or both (got {','.join(supports)})"
        )
    layout: object = options.layout
    if isinstance(layout, str):
        layout = layout.replace("-", " ")  # the command line's roving-accelerometer
    for each in supports:
        one_of("`support`", each, RIG_SUPPORTS)
    averages = options.averages
    if isinstance(averages, bool) or not isinstance(averages, int) or averages < 1:
        raise InputError(f"`averages` must be a whole number of at least 1 (got {averages})")
    require_whole("`seed`", options.seed, least=0)  # numpy's generators take no negative seed
    require_range("`double_hits`", options.double_hits, 0.0, 1.0)
    require_range("`overloads`", options.overloads, 0.0, 1.0)
    snrs = (
        ("`force_snr_db`", options.force_snr_db),
        ("`response_snr_db`", options.response_snr_db),
    )
    for name, snr in snrs:
        if snr is not None:
            require_range(name, snr, 0.0, 200.0)
    require_range("`pretrigger_s`", options.pretrigger_s, 0.0, 0.1)
    one_of("`time_zero`", options.time_zero, ("pulse", "record"))
    one_of("`lab_plane`", options.lab_plane, ("xy", "xz"))
    layout = one_of("`layout`", layout, ("roving hammer", "roving accelerometer"))
    if options.response_direction not in (3, -3):
        raise InputError(f"`response_direction`: give 3 or -3 (got {options.response_direction})")
    return replace(options, support=tuple(supports), layout=layout)


def _test_support(
    result: RigResult,
    the_racket: Racket,
    support: str,
    points: _TestPoints,
    spring: StuckBall | None,
    options: RigOptions,
    progress: Progress | None,
) -> dict[str, Any]:
    """One support's hammer test: simulated, its UFF and modal truth written into ``result``;
    its record for run.json's ``runs``."""
    durations = _pulse_lengths(
        the_racket, points.locations, support, options.layout, points.reference_location
    )
    report(progress, f"building the {support} rig and simulating the hammer test")
    model = rig_model(the_racket, "free" if support == "free" else "hand")
    if spring is not None:
        model = ball_on_strings(model, spring)
    records = simulate_hammer_test(
        model,
        points.locations,
        points.nodes,
        points.reference_location,
        points.reference_node,
        acquisition=Acquisition(n_averages=options.averages, pretrigger_s=options.pretrigger_s),
        blows=HammerBlows(pulse_duration_s=tuple(durations.tolist())),
        noise=SensorNoise(
            force_snr_db=options.force_snr_db, response_snr_db=options.response_snr_db
        ),
        faults=HammerFaults(
            double_hit_probability=options.double_hits, overload_probability=options.overloads
        ),
        seed=np.random.default_rng(support_stream(options.seed, support)),
    )
    if options.time_zero == "record":  # t = 0 at the first sample: the pulse pretrigger_s into it
        records = replace(
            records,
            pretrigger_s=0.0,
            metadata={**records.metadata, "pulse_at_s": records.pretrigger_s},
        )
    out_dir = result.out
    tests = write_hammer_uff(
        records,
        out_dir / f"hammer_{support}.uff",
        binary=options.binary,
        response_direction=options.response_direction,
        plane=options.lab_plane,
        layout=options.layout,
    )
    extra = [] if options.driving_point else [list(points.reference_location)]
    truth_locations = np.vstack([points.locations, *extra, [0.0, 0.0], [the_racket.length_m, 0.0]])
    truth = model.modal_truth(truth_locations, max_frequency_hz=0.5 / records.sampling_interval_s)
    truth_path = out_dir / f"modal_truth_{support}.json"
    truth.write_json(truth_path)
    faults = _fault_counts(records)
    result.written += [tests, truth_path]
    result.records[support] = records
    result.truth[support] = truth
    result.faults[support] = faults
    return {
        **faults,
        "random_stream": _stream_words(options.seed, support),
        "rig": records.metadata.get("rig"),
        "anti_alias": records.metadata.get("anti_alias"),
    }


def _ball_spring(
    the_racket: Racket, the_ball: Ball, ball_at: Sequence[float]
) -> tuple[StuckBall, dict[str, Any]]:
    """The ball fixed on the strings at ``ball_at``, and its record for run.json.

    Its patch: where the string net (:func:`~racketdyn.contact.membrane_patch_stiffness`) is
    as stiff as the string bed's law at the preload (the law ``compound`` puts under the
    ball), so that the rig and ``compound`` hold the ball on one bed.
    """
    ball_xy = np.asarray(ball_location(ball_at, the_racket))
    law = the_ball.restoring_force
    bed = ball_spring(the_racket, the_ball).bed_stiffness
    patch = membrane_patch_radius(the_racket, bed)
    if not np.isfinite(patch):
        raise InputError(
            f"`ball_at`: the string bed's law ({bed / 1e3:.1f} kN/m at the centre) is stiffer "
            "than the string net under any patch inside the head; check the racket's strings"
        )
    spring = StuckBall(
        (float(ball_xy[0]), float(ball_xy[1])),
        the_ball.mass_kg,
        float(law.stiffness(law.deflection(PRELOAD_N))),
        restitution_damping_ratio(small_amplitude_e_bg(the_racket, the_ball)),
        patch,
    )
    record = {
        "location_m": list(spring.location),
        "mass_kg": spring.mass_kg,
        "stiffness_n_per_m": spring.stiffness_n_per_m,
        "damping_ratio": spring.damping_ratio,
        "preload_n": PRELOAD_N,
        "patch_radius_m": patch,
        "bed_stiffness_n_per_m": bed,
        "spring": "the ball's own one-sided law, tangent at the preload, on the membrane's "
        "patch where the string net is as stiff as the string bed's law at the preload; "
        "dashpot from e_BG",
    }
    return spring, record


def _struck_points(
    the_racket: Racket,
    under_ball: tuple[tuple[float, float], float] | None,
    driving_point: bool,
) -> tuple[NDArray[np.float64], tuple[int, ...], tuple[float, float], int]:
    """The points the hammer strikes, their nodes, and the accelerometer's location and node.

    The rig's grid (:func:`~racketdyn.rig.hammer_points`) less the points under the ball
    (``under_ball``: its centre, m, and diameter, m) and, without ``driving_point``, the
    accelerometer's node.
    """
    locations, nodes = hammer_points(the_racket)
    if under_ball is not None:  # the hammer cannot strike the strings under the ball
        centre, diameter_m = under_ball
        free_of_ball = np.hypot(*(locations - np.asarray(centre)).T) > 0.5 * diameter_m
        locations = locations[free_of_ball]
        nodes = tuple(n for n, keep in zip(nodes, free_of_ball, strict=True) if keep)
    reference = accelerometer_index(the_racket, locations)
    reference_location = (float(locations[reference, 0]), float(locations[reference, 1]))
    reference_node = nodes[reference]
    if not driving_point:  # the hammer skips the accelerometer's node
        struck = np.arange(len(nodes)) != reference
        locations = locations[struck]
        nodes = tuple(n for n, keep in zip(nodes, struck, strict=True) if keep)
    return locations, nodes, reference_location, reference_node


def _pulse_lengths(
    the_racket: Racket,
    locations: NDArray[np.float64],
    support: str,
    layout: str,
    reference_location: tuple[float, float],
) -> NDArray[np.float64]:
    """Half-sine length of each hit, s: the plastic tip's on the frame, the string contact
    time on the bed (free, or pinned for the hand); every hit's at the reference node for a
    roving accelerometer."""
    on_bed = the_racket.head.contains(locations)
    durations = np.full(len(locations), FRAME_PULSE_S)
    contact_support = "free" if support == "free" else "pinned"
    durations[on_bed] = string_contact_time(the_racket, locations[on_bed], contact_support)
    if layout == "roving accelerometer":  # every hit on the reference node (the hoop)
        at_reference = np.asarray([reference_location])
        durations[:] = (
            string_contact_time(the_racket, at_reference, contact_support)[0]
            if the_racket.head.contains(at_reference)[0]
            else FRAME_PULSE_S
        )
    return durations


def _fault_counts(records: HammerRecords) -> dict[str, int]:
    """How many averages were double hits and overloads (from the records' truth)."""
    return {
        "double_hits": int(sum(sum(row) for row in records.metadata.get("double_hit", []))),
        "overloads": int(sum(sum(row) for row in records.metadata.get("overload", []))),
    }
