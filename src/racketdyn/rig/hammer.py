"""The roving-hammer test on the virtual rig: force and acceleration records as a test gives them.

What is simulated, and how:

* **Hammer pulses.**  Half-sine force pulses (paper, eq 11 and section 3.1), their length set by
  the tip on the surface struck: ``frame_pulse_s`` (0.4 ms: a plastic tip on the frame, the
  paper's tip) on the frame, ``string_pulse_s`` (3 ms: the strings are soft, Kawazoe's Fig. 7
  contact times) inside the string bed; or one length per point.  The peak force of each
  average is drawn uniformly from ``peak_force_n``.
* **Response.**  Exact modal superposition over the rig's modes (:class:`RigModel`): each mode
  is a damped single-DOF system whose displacement for a half-sine is written in closed form
  (partial fractions of ``1 / ((s − iΩ)(s − s₁)(s − s₂))``; the pulse is ``sin Ωt`` from 0 plus
  the same started at T, which cancels it after T).  No time stepping.
* **Acquisition.**  Both channels are computed on a grid ``oversampling`` times finer than the
  record.  Each fine sample is the exact signal averaged over a triangle two fine steps wide
  (the second difference of the exact displacement, or of the force's double integral): a
  ``sinc²`` first stage, as an analogue filter would be, that keeps the fine grid free of
  aliases.  Then a low-pass filter (linear-phase Kaiser FIR, applied with zero phase: passband
  to ``fs / 2.56``, the usual analyser bandwidth, flat to 3e-5; ≥ 90 dB down from
  ``fs − fs / 2.56``, so nothing aliases into the passband) and decimation.  White sensor noise
  is added to each channel last (``force_noise_n``, ``acceleration_noise_ms2``, rms; or as a
  signal-to-noise ratio of each record's peak, ``force_snr_db``, ``response_snr_db``).  A pulse
  much shorter than the sampling interval rings after the filter (the frame's 0.4 ms pulse
  spans two samples at 200 µs), as it does on a real analyser.
* **Faults.**  With ``double_hit_probability`` an average gets a second, smaller pulse
  (``double_hit_ratio`` of the first) starting ``double_hit_gap_s`` after the first ends.  With
  ``overload_probability`` it is struck too hard (``overload_factor`` × the range) and the force
  channel clips at ± ``overload_level_n`` (the structure still feels the whole force).
* **Truth.**  ``HammerRecords.metadata`` holds, per point and average, the peak force, whether
  it was double-hit (and the gap and ratio) and whether the force channel clipped; and the
  rig's modal truth at the points and the reference (``modal_truth``: ModalModel JSON dict,
  every mode up to the Nyquist frequency; with fewer than three such locations the butt and
  tip are added) so identification can be checked against it.

The record's time origin is the start of the (first) pulse; ``pretrigger_s`` (rounded to whole
samples) is recorded before it.

The settings named above are fields of four frozen objects that :func:`simulate_hammer_test`
takes: :class:`Acquisition`, :class:`HammerBlows`, :class:`SensorNoise` and :class:`HammerFaults`.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.signal import firwin, kaiserord, oaconvolve

from racketdyn.errors import InputError, require_positive, require_range, require_whole
from racketdyn.measurement.records import ANALYSER_BANDWIDTH_FACTOR, HammerRecords
from racketdyn.racket import Racket, as_locations
from racketdyn.rig.model import RigModel

if TYPE_CHECKING:
    from racketdyn.modal.model import ModalModel

__all__ = [
    "ANALYSER_BANDWIDTH_FACTOR",
    "FRAME_PULSE_S",
    "STRING_PULSE_S",
    "Acquisition",
    "HammerBlows",
    "HammerFaults",
    "SensorNoise",
    "accelerometer_index",
    "anti_alias_filter",
    "hammer_points",
    "simulate_hammer_test",
    "string_contact_time",
]

logger = logging.getLogger(__name__)

FRAME_PULSE_S = 0.4e-3
"""Half-sine length of a plastic-tipped hammer on the frame, s (assumed, 0.3–0.5 ms typical)."""
STRING_PULSE_S = 3.0e-3
"""Half-sine length of the hammer on the strings, s (assumed; the soft bed lengthens contact)."""
FILTER_ATTENUATION_DB = 90.0
_CHUNK = 8192


ACCELEROMETER_ANGLE_DEG = 22.5
"""Where the rig's accelerometer sits: on the hoop, this far round from the tip.  There the
bending modes (off the face's nodes) and the twisting modes (off the long axis) all move it, so
every mode can be mass-normalised from the driving point."""


def accelerometer_index(racket: Racket, locations: ArrayLike) -> int:
    """Index of the hammer point nearest the accelerometer position on the hoop.

    Parameters
    ----------
    racket : Racket
        Its head gives the hoop.
    locations : array_like, shape (n, 2)
        Hammer points (x, y), m (e.g. from :func:`hammer_points`).
    """
    head = racket.head
    angle = np.deg2rad(ACCELEROMETER_ANGLE_DEG)
    target = np.array(
        [
            head.centre_x_m + 1.06 * head.half_length_m * np.cos(angle),
            head.centre_y_m + 1.06 * head.half_width_m * np.sin(angle),
        ]
    )
    return int(np.argmin(np.linalg.norm(as_locations(locations) - target, axis=1)))


HAMMER_MASS_KG = 0.010
"""Head mass of a miniature impact hammer, kg (assumption: the 5–20 g class used on rackets)."""


def string_contact_time(
    racket: Racket,
    locations: ArrayLike,
    support: str = "free",
    hammer_mass_kg: float = HAMMER_MASS_KG,
) -> NDArray[np.float64]:
    """Hammer–string contact time at points on the string bed, s (for the rig's pulses).

    Half the period of the hammer head on the local string stiffness against the racket's
    reduced mass there: ``T = π sqrt(μ/k)``, ``μ = m_h M_r/(m_h + M_r)``.  The hammer tip meets
    one main and one cross string; each pulls back with ``2 S₀ / L`` for its local half-length
    L — the half-chord of the head ellipse through the point (Kawazoe's linear string term; the
    hammer's few tens of newtons stay in the linear range).  Shorter strings near the frame
    make the contact shorter there, as in the paper's Fig. 7.

    Parameters
    ----------
    racket : Racket
        Head, strings and mass properties.
    locations : array_like, shape (n, 2)
        Points on the string bed, m.
    support : {"free", "pinned"}
        Support for the reduced mass (the hand is close to ``pinned``).
    hammer_mass_kg : float
        Hammer head mass, kg.
    """
    require_positive("hammer_mass_kg", hammer_mass_kg)
    xy = as_locations(locations)
    head = racket.head
    xi = (xy[:, 0] - head.centre_x_m) / head.half_length_m
    eta = (xy[:, 1] - head.centre_y_m) / head.half_width_m
    inside = np.clip(1.0 - xi**2 - eta**2, 0.0, None) + 1e-4  # 1 % of a half-axis at the edge
    main_half = head.half_length_m * np.sqrt(inside + xi**2)  # half-chord along x through y
    cross_half = head.half_width_m * np.sqrt(inside + eta**2)  # half-chord along y through x
    stiffness = 2.0 * racket.strings.bed_tension_n * (1.0 / main_half + 1.0 / cross_half)
    reduced = racket.reduced_mass(xy, support)
    mu = hammer_mass_kg * reduced / (hammer_mass_kg + reduced)
    return np.asarray(np.pi * np.sqrt(mu / stiffness))


def anti_alias_filter(sampling_interval_s: float, oversampling: int) -> NDArray[np.float64]:
    """Taps of the rig's anti-alias FIR filter, at the fine (oversampled) rate.

    Linear-phase Kaiser design: passband to ``fs / 2.56``, stopband from ``fs − fs / 2.56``
    with :data:`FILTER_ATTENUATION_DB` attenuation (``fs = 1 / sampling_interval_s``), so the
    decimated record is free of aliases below ``fs / 2.56``.

    Parameters
    ----------
    sampling_interval_s : float
        Sampling period of the record, s.
    oversampling : int
        Ratio of the fine rate to the record's rate.
    """
    fs = 1.0 / sampling_interval_s
    fine = fs * oversampling
    passband = fs / ANALYSER_BANDWIDTH_FACTOR
    width = (fs - 2 * passband) / (fine / 2)
    numtaps, beta = kaiserord(FILTER_ATTENUATION_DB, width)
    numtaps |= 1  # odd: a whole-sample delay, removed exactly
    return np.asarray(firwin(numtaps, fs / 2, window=("kaiser", beta), fs=fine))


MIN_FRAME_M = 0.002
"""The least frame beyond the string bed's tip the rig's hammer points need, m."""


def hammer_points(
    racket: Racket, n_frame: int = 24, n_strings: int = 44
) -> tuple[NDArray[np.float64], tuple[int, ...]]:
    """A roving-hammer grid like the paper's Fig. 1: frame points, then string points.

    A third of the frame points (at least one) lie on the long axis between the grip and the
    throat; the rest on the hoop 6 % outside the string bed's edge (where that would pass the
    racket's tip, half way from the bed's tip to the racket's), evenly in angle from the tip.
    The string points lie on four elliptic rings (ρ = 0.2, 0.45, 0.68, 0.88) and the centre.
    Nodes are numbered from 1, frame first (the paper: 1–24 frame, 25–68 strings).

    Parameters
    ----------
    racket : Racket
        Its head gives the string bed.
    n_frame : int
        Number of frame points (at least 2).
    n_strings : int
        Number of string points (at least 5).

    Returns
    -------
    locations : ndarray, shape (n_frame + n_strings, 2)
        Point locations (x, y), m.
    nodes : tuple of int
        Node numbers 1, 2, ….
    """
    if n_frame < 2 or n_strings < 5:
        raise InputError(
            f"hammer points: need at least 2 frame and 5 string points (got {n_frame}, {n_strings})"
        )
    head = racket.head
    n_axis = max(n_frame // 3, 1)
    n_hoop = n_frame - n_axis
    axis_x = np.linspace(racket.grip_m + 0.02, head.throat_x_m - 0.02, n_axis)
    angle = 2 * np.pi * np.arange(n_hoop) / n_hoop
    # the hoop 6 % outside the bed where that lies on the racket; a bed that ends closer to the
    # tip than that has its frame points half-way between the bed's tip and the racket's
    gap = racket.length_m - head.tip_x_m
    if gap < MIN_FRAME_M:
        raise InputError(
            f"racket {racket.name!r}: the string bed ends {gap * 1e3:.1f} mm from the tip; the "
            f"virtual rig strikes the frame around it and needs at least {MIN_FRAME_M * 1e3:g} mm "
            "there (check [head] centre_x_m and half_length_m against [racket] length_m)"
        )
    reach_x = 0.06 * head.half_length_m if 0.06 * head.half_length_m <= gap else 0.5 * gap
    hoop = np.column_stack(
        [
            head.centre_x_m + (head.half_length_m + reach_x) * np.cos(angle),
            head.centre_y_m + 1.06 * head.half_width_m * np.sin(angle),
        ]
    )
    radii = np.array([0.2, 0.45, 0.68, 0.88])
    counts = np.round((n_strings - 1) * radii / radii.sum()).astype(int)
    counts[-1] = n_strings - 1 - counts[:-1].sum()
    rings = [np.array([[head.centre_x_m, head.centre_y_m]])]
    for radius, count in zip(radii, counts, strict=True):
        theta = 2 * np.pi * (np.arange(count) + 0.5) / count
        rings.append(
            np.column_stack(
                [
                    head.centre_x_m + radius * head.half_length_m * np.cos(theta),
                    head.centre_y_m + radius * head.half_width_m * np.sin(theta),
                ]
            )
        )
    locations = np.vstack([np.column_stack([axis_x, np.zeros(n_axis)]), hoop, *rings])
    return locations, tuple(range(1, locations.shape[0] + 1))


def _check_range(name: str, bounds: tuple[float, float], *, allow_zero: bool = False) -> None:
    low, high = (float(b) for b in bounds)
    require_positive(f"{name} (low)", low, allow_zero=allow_zero)
    require_positive(f"{name} (high)", high)
    if high < low:
        raise InputError(f"{name} must be (low, high) with low ≤ high (got {bounds!r})")


@dataclass(frozen=True)
class Acquisition:
    """How the analyser records each hit: averages, sampling and the pre-trigger.

    Parameters
    ----------
    n_averages : int
        Hits per point, a count (at least 1).
    sampling_interval_s : float
        Sampling period, s (the paper: 200 µs).
    n_samples : int
        Samples per record, a count (at least 8).
    pretrigger_s : float
        Time recorded before the pulse starts, s (rounded to whole samples).
    oversampling : int
        Fine-grid factor for the anti-alias filtering and decimation, a count (at least 2).
    """

    n_averages: int = 10
    sampling_interval_s: float = 2.0e-4
    n_samples: int = 2048
    pretrigger_s: float = 0.01
    oversampling: int = 8

    def __post_init__(self) -> None:
        for name, least in (("n_averages", 1), ("n_samples", 8), ("oversampling", 2)):
            object.__setattr__(self, name, require_whole(name, getattr(self, name), least))
        dt = require_positive("sampling_interval_s", self.sampling_interval_s)
        object.__setattr__(self, "sampling_interval_s", dt)
        pretrigger = require_positive("pretrigger_s", self.pretrigger_s, allow_zero=True)
        object.__setattr__(self, "pretrigger_s", pretrigger)

    @property
    def pretrigger_samples(self) -> int:
        """Samples recorded before the pulse (``pretrigger_s`` rounded to whole samples)."""
        return round(self.pretrigger_s / self.sampling_interval_s)


@dataclass(frozen=True)
class HammerBlows:
    """The hammer's normal hits: the half-sine pulse lengths and the range of peak forces.

    Parameters
    ----------
    frame_pulse_s, string_pulse_s : float
        Half-sine length on the frame and inside the string bed, s.
    pulse_duration_s : float, sequence of float or None
        One half-sine length per point (or one for all), s, instead of the frame/string rule.
    peak_force_n : tuple of float
        Range (low, high) of the peak force of a normal hit, N (uniform per average).
    """

    frame_pulse_s: float = FRAME_PULSE_S
    string_pulse_s: float = STRING_PULSE_S
    pulse_duration_s: float | tuple[float, ...] | None = None
    peak_force_n: tuple[float, float] = (20.0, 60.0)

    def __post_init__(self) -> None:
        if self.pulse_duration_s is None:
            require_positive("frame_pulse_s", self.frame_pulse_s)
            require_positive("string_pulse_s", self.string_pulse_s)
        else:
            lengths = np.asarray(self.pulse_duration_s, dtype=float)
            if lengths.ndim > 1 or not np.all(np.isfinite(lengths) & (lengths > 0)):
                raise InputError("pulse_duration_s must be positive lengths in s, one per point")
            held = float(lengths) if lengths.ndim == 0 else tuple(lengths.tolist())
            object.__setattr__(self, "pulse_duration_s", held)
        _check_range("peak_force_n", self.peak_force_n)
        object.__setattr__(self, "peak_force_n", tuple(self.peak_force_n))


@dataclass(frozen=True)
class SensorNoise:
    """White noise of the force and acceleration channels, added after the anti-alias filter.

    Parameters
    ----------
    force_noise_n : float
        Force sensor noise, N rms.
    acceleration_noise_ms2 : float
        Accelerometer noise, m/s² rms.
    force_snr_db, response_snr_db : float, optional
        Noise of the force and response channels as a signal-to-noise ratio, dB (0 to 200):
        each record's noise rms is its noiseless peak × 10^(−SNR/20) (so a weak response far
        from the accelerometer is noisier relative to its modes, as on a real test).  Given,
        it replaces ``force_noise_n`` / ``acceleration_noise_ms2``.
    """

    force_noise_n: float = 0.02
    acceleration_noise_ms2: float = 0.05
    force_snr_db: float | None = None
    response_snr_db: float | None = None

    def __post_init__(self) -> None:
        require_positive("force_noise_n", self.force_noise_n, allow_zero=True)
        require_positive("acceleration_noise_ms2", self.acceleration_noise_ms2, allow_zero=True)
        for name in ("force_snr_db", "response_snr_db"):
            if getattr(self, name) is not None:
                require_range(name, getattr(self, name), 0.0, 200.0)


@dataclass(frozen=True)
class HammerFaults:
    """The hits a careless hand gives: double hits and overloads, and the force channel's range.

    Parameters
    ----------
    double_hit_probability : float
        Chance that an average gets a second pulse, 0 to 1.
    double_hit_gap_s : tuple of float
        Range of the gap from the end of the first pulse to the start of the second, s.
    double_hit_ratio : tuple of float
        Range of the second pulse's peak as a fraction of the first's, dimensionless.
    overload_probability : float
        Chance that an average is struck too hard, 0 to 1.
    overload_level_n : float
        Force channel range, N: the recorded force clips at ± this.
    overload_factor : tuple of float
        Range of the peak of an overloading hit, as a multiple of ``overload_level_n`` (above 1).
    """

    double_hit_probability: float = 0.0
    double_hit_gap_s: tuple[float, float] = (0.5e-3, 3.0e-3)
    double_hit_ratio: tuple[float, float] = (0.2, 0.6)
    overload_probability: float = 0.0
    overload_level_n: float = 200.0
    overload_factor: tuple[float, float] = (1.2, 2.0)

    def __post_init__(self) -> None:
        require_positive("overload_level_n", self.overload_level_n)
        _check_range("overload_factor", self.overload_factor)
        if self.overload_factor[0] <= 1.0:
            raise InputError(f"overload_factor must exceed 1 (got {self.overload_factor!r})")
        for name in ("double_hit_probability", "overload_probability"):
            require_range(name, getattr(self, name), 0.0, 1.0)
        _check_range("double_hit_gap_s", self.double_hit_gap_s, allow_zero=True)
        _check_range("double_hit_ratio", self.double_hit_ratio)
        for name in ("double_hit_gap_s", "double_hit_ratio", "overload_factor"):
            object.__setattr__(self, name, tuple(getattr(self, name)))

    @property
    def longest_extra_s(self) -> float:
        """How much a double hit can add after the first pulse's end, s (0 without them)."""
        return float(self.double_hit_gap_s[1]) if self.double_hit_probability > 0 else 0.0


def simulate_hammer_test(
    model: RigModel,
    points: ArrayLike,
    nodes: Sequence[int],
    reference_location: tuple[float, float],
    reference_node: int,
    *,
    acquisition: Acquisition = Acquisition(),
    blows: HammerBlows = HammerBlows(),
    noise: SensorNoise = SensorNoise(),
    faults: HammerFaults = HammerFaults(),
    seed: int | np.random.Generator | None = None,
) -> HammerRecords:
    """Simulate a roving-hammer test on the rig (see the module docstring for the physics).

    Parameters
    ----------
    model : RigModel
        The racket on its support (:func:`racketdyn.rig.rig_model`).
    points : array_like, shape (n_points, 2)
        Hammer points (x, y), m.
    nodes : sequence of int
        Node number of each hammer point (all different).
    reference_location : tuple of float
        Accelerometer location (x, y), m.
    reference_node : int
        Its node number.
    acquisition : Acquisition
        Averages, sampling interval (s), samples, pre-trigger (s) and oversampling.
    blows : HammerBlows
        Pulse lengths (s) and the range of peak forces (N) of the normal hits.
    noise : SensorNoise
        Noise of the force (N rms) and acceleration (m/s² rms) channels, or their SNRs (dB).
    faults : HammerFaults
        Double hits and overloads, and the force channel's range (N).
    seed : int, numpy Generator or None
        Random seed or generator (None: fresh entropy).

    Returns
    -------
    HammerRecords
        ``response_type="acceleration"`` (m/s²), force in N, with the truth in ``metadata``.
    """
    xy, node_list, reference = _check_points(points, nodes, reference_location)
    on_bed = model.on_string_bed(xy)
    durations = _pulse_durations(blows, on_bed)
    _check_together(acquisition, blows, faults, durations)
    rng = np.random.default_rng(seed)
    grid = _FineGrid.of(acquisition)
    unit_response = _unit_responses(model, xy, reference, durations, grid)
    truth: dict[str, list[list[Any]]] = {key: [] for key in _TRUTH_KEYS}
    forces, responses = [], []
    for duration, unit in zip(durations, unit_response, strict=True):  # point by point
        force, response = _strike(rng, float(duration), unit, grid, (blows, noise, faults), truth)
        forces.append(force)
        responses.append(response)
    metadata = _metadata(model, acquisition, blows, noise, faults, seed, grid, durations, on_bed)
    metadata.update(truth)
    metadata["modal_truth"] = _modal_truth(model, xy, reference, acquisition).to_dict()
    logger.info(
        "rig: %d points × %d averages × %d samples simulated (%s support)",
        xy.shape[0],
        acquisition.n_averages,
        acquisition.n_samples,
        model.support,
    )
    dt = acquisition.sampling_interval_s
    return HammerRecords(
        sampling_interval_s=dt,
        force=tuple(forces),
        response=tuple(responses),
        response_type="acceleration",
        nodes=tuple(node_list),
        locations=xy,
        reference_node=int(reference_node),
        reference_location=(float(reference[0, 0]), float(reference[0, 1])),
        pretrigger_s=acquisition.pretrigger_samples * dt,
        source=f"racketdyn virtual rig: {model.racket.name}, {model.support} support",
        metadata=metadata,
    )


_TRUTH_KEYS = ("peak_force_n", "double_hit", "double_hit_gap_s", "double_hit_ratio", "overload")


def _check_points(
    points: ArrayLike, nodes: Sequence[int], reference_location: tuple[float, float]
) -> tuple[NDArray[np.float64], list[int], NDArray[np.float64]]:
    """The hammer points, their node numbers (one different each) and the reference, checked."""
    xy = as_locations(points, "hammer points")
    n_points = xy.shape[0]
    node_list = [int(n) for n in nodes]
    if len(node_list) != n_points or len(set(node_list)) != n_points:
        raise InputError(
            f"hammer test: give one different node number per point ({n_points} points, "
            f"{len(node_list)} nodes)"
        )
    return xy, node_list, as_locations(reference_location, "reference location")


def _pulse_durations(blows: HammerBlows, on_bed: NDArray[np.bool_]) -> NDArray[np.float64]:
    """Half-sine length at each point, s: the frame/string rule, or the lengths given."""
    if blows.pulse_duration_s is None:
        return np.where(on_bed, blows.string_pulse_s, blows.frame_pulse_s)
    return np.broadcast_to(np.asarray(blows.pulse_duration_s, dtype=float), on_bed.shape)


def _check_together(
    acquisition: Acquisition,
    blows: HammerBlows,
    faults: HammerFaults,
    durations: NDArray[np.float64],
) -> None:
    """Refuse normal hits that would clip, and pulses the fine grid or the record cannot hold."""
    if blows.peak_force_n[1] >= faults.overload_level_n:
        raise InputError(
            f"peak_force_n (up to {blows.peak_force_n[1]} N) must stay below overload_level_n "
            f"({faults.overload_level_n} N): normal hits would clip"
        )
    dt = acquisition.sampling_interval_s
    fine_dt = dt / acquisition.oversampling
    if np.min(durations) < 4 * fine_dt:
        raise InputError(
            f"hammer pulses of {np.min(durations) * 1e3:.3g} ms are shorter than 4 fine samples "
            f"({4 * fine_dt * 1e3:.3g} ms); raise oversampling or the pulse length"
        )
    doubled = faults.double_hit_probability > 0
    longest = np.max(durations) * (2 if doubled else 1) + faults.longest_extra_s
    after = (acquisition.n_samples - acquisition.pretrigger_samples) * dt
    if after <= longest:
        raise InputError(
            f"hammer test: {after:.4g} s recorded after the trigger is too short for pulses of "
            f"up to {longest * 1e3:.3g} ms"
        )


@dataclass(frozen=True)
class _FineGrid:
    """The oversampled grid a point's averages are computed on, and the filter that decimates it."""

    taps: NDArray[np.float64]
    fine_dt: float
    n_averages: int
    n_out: int
    n_fine: int
    hit: int  # fine index of t = 0
    pick: NDArray[np.intp]  # fine indices of the record's samples

    @classmethod
    def of(cls, acquisition: Acquisition) -> _FineGrid:
        q = acquisition.oversampling
        taps = anti_alias_filter(acquisition.sampling_interval_s, q)
        margin = (taps.size // 2) // q + 2  # output samples computed beyond each end
        n_out = acquisition.n_samples
        return cls(
            taps=taps,
            fine_dt=acquisition.sampling_interval_s / q,
            n_averages=acquisition.n_averages,
            n_out=n_out,
            n_fine=(n_out + 2 * margin) * q,
            hit=(margin + acquisition.pretrigger_samples) * q,
            pick=(margin + np.arange(n_out)) * q,
        )

    @property
    def n_after(self) -> int:
        """Fine samples from t = 0 to the grid's end."""
        return self.n_fine - self.hit


def _unit_responses(
    model: RigModel,
    xy: NDArray[np.float64],
    reference: NDArray[np.float64],
    durations: NDArray[np.float64],
    grid: _FineGrid,
) -> NDArray[np.float64]:
    """Acceleration at the reference for a unit half-sine at each point, on the fine grid."""
    phi_ref = model.mode_shapes_at(reference)[0]
    coefficients = model.mode_shapes_at(xy) * phi_ref  # φ_p φ_ref, (n_points, n_modes)
    return _half_sine_acceleration(model, durations, grid.fine_dt, grid.n_after, coefficients)


@dataclass
class _Hits:
    """One point's averages as drawn: peak forces, overloads and double hits."""

    peaks: NDArray[np.float64]
    doubled: NDArray[np.bool_]
    gaps: NDArray[np.float64]  # s, NaN where single
    ratios: NDArray[np.float64]  # NaN where single

    def record(self, truth: dict[str, list[list[Any]]], clipped: NDArray[np.bool_]) -> None:
        """Append this point's row to each list of the metadata's truth."""
        truth["peak_force_n"].append(self.peaks.tolist())
        truth["double_hit"].append(self.doubled.tolist())
        truth["double_hit_gap_s"].append(
            [float(g) if d else None for g, d in zip(self.gaps, self.doubled, strict=True)]
        )
        truth["double_hit_ratio"].append(
            [float(r) if d else None for r, d in zip(self.ratios, self.doubled, strict=True)]
        )
        truth["overload"].append(clipped.tolist())


def _strike(
    rng: np.random.Generator,
    duration: float,
    unit_response: NDArray[np.float64],
    grid: _FineGrid,
    settings: tuple[HammerBlows, SensorNoise, HammerFaults],
    truth: dict[str, list[list[Any]]],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """One point's averages: draw the hits, record them, and append their truth to ``truth``.

    Returns the force (N) and acceleration (m/s²) records, shaped ``(n_averages, n_samples)``.
    """
    blows, noise, faults = settings
    pulse = _half_sine(duration, grid.fine_dt, grid.n_after)
    hits = _draw_hits(rng, grid.n_averages, blows, faults)
    force_fine, response_fine = _fine_records(hits, duration, pulse, unit_response, grid)
    force, response, clipped = _acquire(rng, force_fine, response_fine, grid, noise, faults)
    hits.record(truth, clipped)
    return force, response


def _draw_hits(
    rng: np.random.Generator, n_avg: int, blows: HammerBlows, faults: HammerFaults
) -> _Hits:
    """Draw one point's peaks, overloads and double hits (in this order: the seed's stream)."""
    peaks = rng.uniform(*blows.peak_force_n, n_avg)
    overloaded = rng.random(n_avg) < faults.overload_probability
    peaks[overloaded] = faults.overload_level_n * rng.uniform(
        *faults.overload_factor, overloaded.sum()
    )
    doubled = rng.random(n_avg) < faults.double_hit_probability
    gaps = np.where(doubled, rng.uniform(*faults.double_hit_gap_s, n_avg), np.nan)
    ratios = np.where(doubled, rng.uniform(*faults.double_hit_ratio, n_avg), np.nan)
    return _Hits(peaks, doubled, gaps, ratios)


def _fine_records(
    hits: _Hits,
    duration: float,
    pulse: NDArray[np.float64],
    unit_response: NDArray[np.float64],
    grid: _FineGrid,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Force and acceleration of each average on the fine grid, second pulses added.

    A double hit's gap is moved onto the fine grid (``hits.gaps`` is updated to it).
    """
    n_avg, hit = hits.peaks.size, grid.hit
    force_fine = np.zeros((n_avg, grid.n_fine))
    response_fine = np.zeros((n_avg, grid.n_fine))
    force_fine[:, hit:] = hits.peaks[:, None] * pulse
    response_fine[:, hit:] = hits.peaks[:, None] * unit_response
    for a in np.flatnonzero(hits.doubled):
        shift = round((duration + hits.gaps[a]) / grid.fine_dt)
        hits.gaps[a] = shift * grid.fine_dt - duration  # on the fine grid
        second = hits.ratios[a] * hits.peaks[a]
        force_fine[a, hit + shift :] += second * pulse[: pulse.size - shift]
        response_fine[a, hit + shift :] += second * unit_response[: pulse.size - shift]
    return force_fine, response_fine


def _acquire(
    rng: np.random.Generator,
    force_fine: NDArray[np.float64],
    response_fine: NDArray[np.float64],
    grid: _FineGrid,
    noise: SensorNoise,
    faults: HammerFaults,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """Filter, decimate, add the sensors' noise (force first) and clip the force channel.

    Returns the force and acceleration records and which averages clipped.
    """
    n_avg = force_fine.shape[0]
    both = oaconvolve(np.vstack([force_fine, response_fine]), grid.taps[None, :], "same", axes=1)
    force_clean, response_clean = both[:n_avg, grid.pick], both[n_avg:, grid.pick]
    shape = (n_avg, grid.n_out)
    force = force_clean + _noise_rms(force_clean, noise.force_snr_db, noise.force_noise_n)[
        :, None
    ] * rng.standard_normal(shape)
    response = response_clean + _noise_rms(
        response_clean, noise.response_snr_db, noise.acceleration_noise_ms2
    )[:, None] * rng.standard_normal(shape)
    level = faults.overload_level_n
    clipped = np.any(np.abs(force) >= level, axis=1)
    return np.clip(force, -level, level), response, clipped


def _modal_truth(
    model: RigModel,
    xy: NDArray[np.float64],
    reference: NDArray[np.float64],
    acquisition: Acquisition,
) -> ModalModel:
    """The rig's modes to the Nyquist frequency at the points, the reference (and the ends)."""
    truth_points = xy
    if not np.any(np.all(np.isclose(xy, reference), axis=1)):
        truth_points = np.vstack([xy, reference])
    if truth_points.shape[0] < 3:  # a ModalModel needs three: add the butt and the tip
        ends = np.array([[0.0, 0.0], [model.racket.length_m, 0.0]])
        fresh = [e for e in ends if not np.any(np.all(np.isclose(truth_points, e), axis=1))]
        truth_points = np.vstack([truth_points, *fresh])
    fs = 1.0 / acquisition.sampling_interval_s
    return model.modal_truth(truth_points, max_frequency_hz=fs / 2)


def _metadata(
    model: RigModel,
    acquisition: Acquisition,
    blows: HammerBlows,
    noise: SensorNoise,
    faults: HammerFaults,
    seed: int | np.random.Generator | None,
    grid: _FineGrid,
    durations: NDArray[np.float64],
    on_bed: NDArray[np.bool_],
) -> dict[str, Any]:
    """The records' metadata before the truth of the hits: the rig's settings and filter."""
    fs = 1.0 / acquisition.sampling_interval_s
    return {
        "rig": {
            "support": model.support,
            "racket": model.racket.name,
            "n_averages": acquisition.n_averages,
            "oversampling": acquisition.oversampling,
            "frame_pulse_s": blows.frame_pulse_s,
            "string_pulse_s": blows.string_pulse_s,
            "peak_force_n": list(blows.peak_force_n),
            "force_noise_n": noise.force_noise_n,
            "acceleration_noise_ms2": noise.acceleration_noise_ms2,
            "force_snr_db": noise.force_snr_db,
            "response_snr_db": noise.response_snr_db,
            "double_hit_probability": faults.double_hit_probability,
            "overload_probability": faults.overload_probability,
            "overload_level_n": faults.overload_level_n,
            "seed": seed if isinstance(seed, int) else None,
        },
        "anti_alias": {
            "passband_hz": fs / ANALYSER_BANDWIDTH_FACTOR,
            "stopband_hz": fs - fs / ANALYSER_BANDWIDTH_FACTOR,
            "attenuation_db": FILTER_ATTENUATION_DB,
            "taps": int(grid.taps.size),
        },
        "pulse_duration_s": durations.tolist(),
        "on_string_bed": on_bed.tolist(),
    }


def _noise_rms(
    clean: NDArray[np.float64], snr_db: float | None, absolute: float
) -> NDArray[np.float64]:
    """Noise rms of each record: its peak × 10^(−SNR/20), or the absolute level."""
    if snr_db is None:
        return np.full(clean.shape[0], absolute)
    return np.asarray(np.max(np.abs(clean), axis=1) * 10.0 ** (-snr_db / 20.0))


def _half_sine(duration: float, dt: float, n: int) -> NDArray[np.float64]:
    """Unit half-sine ``sin(π t / T)``, 0 ≤ t ≤ T, averaged over a triangle of half-width dt.

    The triangle average of f is the second difference of its double integral F₂ divided by
    dt²; for the half-sine F₂ = t/Ω − sin(Ωt)/Ω² up to T and T/Ω + 2(t − T)/Ω after.
    """
    big = np.pi / duration
    m = min(n, int(np.ceil(duration / dt)) + 2)
    t = np.arange(-1, m + 1) * dt
    inside = t / big - np.sin(big * np.clip(t, 0.0, duration)) / big**2
    double = np.where(t < 0, 0.0, np.where(t <= duration, inside, (2 * t - duration) / big))
    out = np.zeros(n)
    out[:m] = (double[2:] - 2 * double[1:-1] + double[:-2]) / dt**2
    return out


def _half_sine_acceleration(
    model: RigModel,
    durations: NDArray[np.float64],
    dt: float,
    n: int,
    coefficients: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Acceleration for a unit half-sine of each set's duration, ``Σ_k c_k a_k(t)``, at ``n``
    samples from t = 0.

    Each mode ``q̈ + 2ζωq̇ + ω²q = sin(Ωt)`` from rest has the displacement whose Laplace
    transform is ``1 / ((s − iΩ)(s − s₁)(s − s₂))`` (imaginary part); its residues give
    ``q(t) = Im[P e^{iΩt} + B₁ e^{s₁t} + B₂ e^{s₂t}]``.  The half-sine is this from 0 plus the
    same from T; after T the forced terms cancel exactly and are left out.  The samples are the
    acceleration averaged over a triangle of half-width dt (the second difference of the exact
    displacement over dt²), the same weighting :func:`_half_sine` gives the force: a first
    anti-alias stage (``sinc²``) that the fine grid needs, as an analogue filter would be.
    The modes' ``e^{s₁t}`` do not depend on T and are computed once for every duration (they
    were most of a rig's run when computed again for each of its ≈ 30 durations).

    Returns an array ``(n_sets, n)`` for ``durations`` shaped ``(n_sets,)`` and
    ``coefficients`` shaped ``(n_sets, n_modes)``.
    """
    omega, zeta = model.omega, model.damping_ratio
    s1 = omega * (-zeta + 1j * np.sqrt(1 - zeta**2))
    groups = [(float(d), np.flatnonzero(durations == d)) for d in np.unique(durations)]
    displacement = np.zeros((coefficients.shape[0], n + 2))  # from t = -dt to n dt
    for start in range(0, n + 1, _CHUNK):
        t = (start + np.arange(min(_CHUNK, n + 1 - start))) * dt
        e1 = np.exp(np.outer(t, s1))
        for duration, group in groups:
            terms = _half_sine_terms(s1, duration, t, e1)
            displacement[group, 1 + start : 1 + start + t.size] = coefficients[group] @ terms.T
    return np.asarray(
        (displacement[:, 2:] - 2 * displacement[:, 1:-1] + displacement[:, :-2]) / dt**2
    )


def _half_sine_terms(
    s1: NDArray[np.complex128],
    duration: float,
    t: NDArray[np.floating[Any]],
    e1: NDArray[np.complex128],
) -> NDArray[np.float64]:
    """Each mode's displacement ``q(t)`` for a unit half-sine of ``duration`` (the residues of
    :func:`_half_sine_acceleration`), shaped ``(t.size, n_modes)``; ``e1`` is ``e^{s₁t}``."""
    s2 = np.conj(s1)
    big = np.pi / duration
    iw = 1j * big
    forced = 1 / ((iw - s1) * (iw - s2))
    b1 = 1 / ((s1 - iw) * (s1 - s2))
    b2 = 1 / ((s2 - iw) * (s2 - s1))
    after1, after2 = b1 * (1 + np.exp(-s1 * duration)), b2 * (1 + np.exp(-s2 * duration))
    e2 = np.conj(e1)
    during = t[:, None] <= duration
    return np.asarray(
        np.where(
            during,
            forced * np.exp(iw * t)[:, None] + b1 * e1 + b2 * e2,
            after1 * e1 + after2 * e2,
        ).imag
    )
