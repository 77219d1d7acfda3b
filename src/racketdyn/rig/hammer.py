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
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.signal import firwin, kaiserord, oaconvolve

from racketdyn.errors import InputError, require_positive, require_range, require_whole
from racketdyn.measurement.records import ANALYSER_BANDWIDTH_FACTOR, HammerRecords
from racketdyn.racket import Racket, as_locations
from racketdyn.rig.model import RigModel

__all__ = [
    "ANALYSER_BANDWIDTH_FACTOR",
    "FRAME_PULSE_S",
    "STRING_PULSE_S",
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


def simulate_hammer_test(
    model: RigModel,
    points: ArrayLike,
    nodes: Sequence[int],
    reference_location: tuple[float, float],
    reference_node: int,
    *,
    n_averages: int = 10,
    sampling_interval_s: float = 2.0e-4,
    n_samples: int = 2048,
    pretrigger_s: float = 0.01,
    frame_pulse_s: float = FRAME_PULSE_S,
    string_pulse_s: float = STRING_PULSE_S,
    pulse_duration_s: ArrayLike | None = None,
    peak_force_n: tuple[float, float] = (20.0, 60.0),
    force_noise_n: float = 0.02,
    acceleration_noise_ms2: float = 0.05,
    force_snr_db: float | None = None,
    response_snr_db: float | None = None,
    double_hit_probability: float = 0.0,
    double_hit_gap_s: tuple[float, float] = (0.5e-3, 3.0e-3),
    double_hit_ratio: tuple[float, float] = (0.2, 0.6),
    overload_probability: float = 0.0,
    overload_level_n: float = 200.0,
    overload_factor: tuple[float, float] = (1.2, 2.0),
    oversampling: int = 8,
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
    n_averages : int
        Hits per point.
    sampling_interval_s : float
        Sampling period, s (the paper: 200 µs).
    n_samples : int
        Samples per record.
    pretrigger_s : float
        Time recorded before the pulse starts, s (rounded to whole samples).
    frame_pulse_s, string_pulse_s : float
        Half-sine length on the frame and inside the string bed, s.
    pulse_duration_s : array_like or None
        One half-sine length per point, s, instead of the frame/string rule.
    peak_force_n : tuple of float
        Range of the peak force of a normal hit, N (uniform per average).
    force_noise_n : float
        Force sensor noise, N rms (white, after the anti-alias filter).
    acceleration_noise_ms2 : float
        Accelerometer noise, m/s² rms.
    force_snr_db, response_snr_db : float, optional
        Noise of the force and response channels as a signal-to-noise ratio, dB: each record's
        noise rms is its noiseless peak × 10^(−SNR/20) (so a weak response far from the
        accelerometer is noisier relative to its modes, as on a real test).  Given, it replaces
        ``force_noise_n`` / ``acceleration_noise_ms2``.
    double_hit_probability : float
        Chance that an average gets a second pulse.
    double_hit_gap_s : tuple of float
        Range of the gap from the end of the first pulse to the start of the second, s.
    double_hit_ratio : tuple of float
        Range of the second pulse's peak as a fraction of the first's.
    overload_probability : float
        Chance that an average is struck too hard.
    overload_level_n : float
        Force channel range, N: the recorded force clips at ± this.
    overload_factor : tuple of float
        Range of the peak of an overloading hit, as a multiple of ``overload_level_n``.
    oversampling : int
        Fine-grid factor for the anti-alias filtering and decimation (at least 2).
    seed : int, numpy Generator or None
        Random seed or generator (None: fresh entropy).

    Returns
    -------
    HammerRecords
        ``response_type="acceleration"`` (m/s²), force in N, with the truth in ``metadata``.
    """
    xy = as_locations(points, "hammer points")
    n_points = xy.shape[0]
    node_list = [int(n) for n in nodes]
    if len(node_list) != n_points or len(set(node_list)) != n_points:
        raise InputError(
            f"hammer test: give one different node number per point ({n_points} points, "
            f"{len(node_list)} nodes)"
        )
    reference = as_locations(reference_location, "reference location")
    settings = _check_settings(
        n_averages, n_samples, oversampling, peak_force_n, overload_level_n, overload_factor
    )
    dt = require_positive("sampling_interval_s", sampling_interval_s)
    for name, value in (
        ("double_hit_probability", double_hit_probability),
        ("overload_probability", overload_probability),
    ):
        require_range(name, value, 0.0, 1.0)
    require_positive("force_noise_n", force_noise_n, allow_zero=True)
    require_positive("acceleration_noise_ms2", acceleration_noise_ms2, allow_zero=True)
    for name, snr in (("force_snr_db", force_snr_db), ("response_snr_db", response_snr_db)):
        if snr is not None:
            require_range(name, snr, 0.0, 200.0)
    _check_range("double_hit_gap_s", double_hit_gap_s, allow_zero=True)
    _check_range("double_hit_ratio", double_hit_ratio)
    n_pre = round(require_positive("pretrigger_s", pretrigger_s, allow_zero=True) / dt)

    on_bed = model.on_string_bed(xy)
    if pulse_duration_s is None:
        require_positive("frame_pulse_s", frame_pulse_s)
        require_positive("string_pulse_s", string_pulse_s)
        durations = np.where(on_bed, string_pulse_s, frame_pulse_s)
    else:
        durations = np.broadcast_to(np.asarray(pulse_duration_s, dtype=float), (n_points,))
        if not np.all(np.isfinite(durations) & (durations > 0)):
            raise InputError("pulse_duration_s must be positive lengths in s, one per point")
    q = settings["oversampling"]
    fine_dt = dt / q
    if np.min(durations) < 4 * fine_dt:
        raise InputError(
            f"hammer pulses of {np.min(durations) * 1e3:.3g} ms are shorter than 4 fine samples "
            f"({4 * fine_dt * 1e3:.3g} ms); raise oversampling or the pulse length"
        )
    longest = np.max(durations) * (2 if double_hit_probability > 0 else 1) + (
        double_hit_gap_s[1] if double_hit_probability > 0 else 0.0
    )
    if (settings["n_samples"] - n_pre) * dt <= longest:
        raise InputError(
            f"hammer test: {(settings['n_samples'] - n_pre) * dt:.4g} s recorded after the "
            f"trigger is too short for pulses of up to {longest * 1e3:.3g} ms"
        )

    rng = np.random.default_rng(seed)
    taps = anti_alias_filter(dt, q)
    margin = (taps.size // 2) // q + 2  # output samples computed beyond each end
    n_out = settings["n_samples"]
    n_fine = (n_out + 2 * margin) * q
    hit = (margin + n_pre) * q  # fine index of t = 0
    pick = (margin + np.arange(n_out)) * q

    phi_ref = model.mode_shapes_at(reference)[0]
    coefficients = model.mode_shapes_at(xy) * phi_ref  # φ_p φ_ref, (n_points, n_modes)
    unit_response = np.zeros((n_points, n_fine - hit))
    for duration in np.unique(durations):
        group = np.flatnonzero(durations == duration)
        unit_response[group] = _half_sine_acceleration(
            model, float(duration), fine_dt, n_fine - hit, coefficients[group]
        )

    n_avg = settings["n_averages"]
    forces, responses = [], []
    truth: dict[str, list[list[Any]]] = {
        "peak_force_n": [],
        "double_hit": [],
        "double_hit_gap_s": [],
        "double_hit_ratio": [],
        "overload": [],
    }
    for p in range(n_points):
        duration = float(durations[p])
        pulse = _half_sine(duration, fine_dt, n_fine - hit)
        peaks = rng.uniform(*peak_force_n, n_avg)
        overloaded = rng.random(n_avg) < overload_probability
        peaks[overloaded] = overload_level_n * rng.uniform(*overload_factor, overloaded.sum())
        doubled = rng.random(n_avg) < double_hit_probability
        gaps = np.where(doubled, rng.uniform(*double_hit_gap_s, n_avg), np.nan)
        ratios = np.where(doubled, rng.uniform(*double_hit_ratio, n_avg), np.nan)
        force_fine = np.zeros((n_avg, n_fine))
        response_fine = np.zeros((n_avg, n_fine))
        force_fine[:, hit:] = peaks[:, None] * pulse
        response_fine[:, hit:] = peaks[:, None] * unit_response[p]
        for a in np.flatnonzero(doubled):
            shift = round((duration + gaps[a]) / fine_dt)
            gaps[a] = shift * fine_dt - duration  # on the fine grid
            second = ratios[a] * peaks[a]
            force_fine[a, hit + shift :] += second * pulse[: pulse.size - shift]
            response_fine[a, hit + shift :] += second * unit_response[p, : pulse.size - shift]
        both = oaconvolve(np.vstack([force_fine, response_fine]), taps[None, :], "same", axes=1)
        force_clean, response_clean = both[:n_avg, pick], both[n_avg:, pick]
        force = force_clean + _noise_rms(force_clean, force_snr_db, force_noise_n)[
            :, None
        ] * rng.standard_normal((n_avg, n_out))
        response = response_clean + _noise_rms(
            response_clean, response_snr_db, acceleration_noise_ms2
        )[:, None] * rng.standard_normal((n_avg, n_out))
        clipped = np.any(np.abs(force) >= overload_level_n, axis=1)
        force = np.clip(force, -overload_level_n, overload_level_n)
        forces.append(force)
        responses.append(response)
        truth["peak_force_n"].append(peaks.tolist())
        truth["double_hit"].append(doubled.tolist())
        truth["double_hit_gap_s"].append(
            [float(g) if d else None for g, d in zip(gaps, doubled, strict=True)]
        )
        truth["double_hit_ratio"].append(
            [float(r) if d else None for r, d in zip(ratios, doubled, strict=True)]
        )
        truth["overload"].append(clipped.tolist())

    fs = 1.0 / dt
    truth_points = xy
    if not np.any(np.all(np.isclose(xy, reference), axis=1)):
        truth_points = np.vstack([xy, reference])
    if truth_points.shape[0] < 3:  # a ModalModel needs three: add the butt and the tip
        ends = np.array([[0.0, 0.0], [model.racket.length_m, 0.0]])
        fresh = [e for e in ends if not np.any(np.all(np.isclose(truth_points, e), axis=1))]
        truth_points = np.vstack([truth_points, *fresh])
    modal_truth = model.modal_truth(truth_points, max_frequency_hz=fs / 2)
    metadata: dict[str, Any] = {
        "rig": {
            "support": model.support,
            "racket": model.racket.name,
            "n_averages": n_avg,
            "oversampling": q,
            "frame_pulse_s": frame_pulse_s,
            "string_pulse_s": string_pulse_s,
            "peak_force_n": list(peak_force_n),
            "force_noise_n": force_noise_n,
            "acceleration_noise_ms2": acceleration_noise_ms2,
            "force_snr_db": force_snr_db,
            "response_snr_db": response_snr_db,
            "double_hit_probability": double_hit_probability,
            "overload_probability": overload_probability,
            "overload_level_n": overload_level_n,
            "seed": seed if isinstance(seed, int) else None,
        },
        "anti_alias": {
            "passband_hz": fs / ANALYSER_BANDWIDTH_FACTOR,
            "stopband_hz": fs - fs / ANALYSER_BANDWIDTH_FACTOR,
            "attenuation_db": FILTER_ATTENUATION_DB,
            "taps": int(taps.size),
        },
        "pulse_duration_s": durations.tolist(),
        "on_string_bed": on_bed.tolist(),
        **truth,
        "modal_truth": modal_truth.to_dict(),
    }
    logger.info(
        "rig: %d points × %d averages × %d samples simulated (%s support)",
        n_points,
        n_avg,
        n_out,
        model.support,
    )
    return HammerRecords(
        sampling_interval_s=dt,
        force=tuple(forces),
        response=tuple(responses),
        response_type="acceleration",
        nodes=tuple(node_list),
        locations=xy,
        reference_node=int(reference_node),
        reference_location=(float(reference[0, 0]), float(reference[0, 1])),
        pretrigger_s=n_pre * dt,
        source=f"racketdyn virtual rig: {model.racket.name}, {model.support} support",
        metadata=metadata,
    )


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
    duration: float,
    dt: float,
    n: int,
    coefficients: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Acceleration for a unit half-sine, ``Σ_k c_k a_k(t)``, at ``n`` samples from t = 0.

    Each mode ``q̈ + 2ζωq̇ + ω²q = sin(Ωt)`` from rest has the displacement whose Laplace
    transform is ``1 / ((s − iΩ)(s − s₁)(s − s₂))`` (imaginary part); its residues give
    ``q(t) = Im[P e^{iΩt} + B₁ e^{s₁t} + B₂ e^{s₂t}]``.  The half-sine is this from 0 plus the
    same from T; after T the forced terms cancel exactly and are left out.  The samples are the
    acceleration averaged over a triangle of half-width dt (the second difference of the exact
    displacement over dt²), the same weighting :func:`_half_sine` gives the force: a first
    anti-alias stage (``sinc²``) that the fine grid needs, as an analogue filter would be.

    Returns an array ``(n_sets, n)`` for ``coefficients`` shaped ``(n_sets, n_modes)``.
    """
    omega, zeta = model.omega, model.damping_ratio
    big = np.pi / duration
    s1 = omega * (-zeta + 1j * np.sqrt(1 - zeta**2))
    s2 = np.conj(s1)
    iw = 1j * big
    forced = 1 / ((iw - s1) * (iw - s2))
    b1 = 1 / ((s1 - iw) * (s1 - s2))
    b2 = 1 / ((s2 - iw) * (s2 - s1))
    after1, after2 = b1 * (1 + np.exp(-s1 * duration)), b2 * (1 + np.exp(-s2 * duration))
    displacement = np.zeros((coefficients.shape[0], n + 2))  # from t = -dt to n dt
    for start in range(0, n + 1, _CHUNK):
        t = (start + np.arange(min(_CHUNK, n + 1 - start))) * dt
        e1 = np.exp(np.outer(t, s1))
        e2 = np.conj(e1)
        during = t[:, None] <= duration
        terms = np.where(
            during,
            forced * np.exp(iw * t)[:, None] + b1 * e1 + b2 * e2,
            after1 * e1 + after2 * e2,
        ).imag
        displacement[:, 1 + start : 1 + start + t.size] = coefficients @ terms.T
    return np.asarray(
        (displacement[:, 2:] - 2 * displacement[:, 1:-1] + displacement[:, :-2]) / dt**2
    )


def _check_range(name: str, bounds: tuple[float, float], *, allow_zero: bool = False) -> None:
    low, high = (float(b) for b in bounds)
    require_positive(f"{name} (low)", low, allow_zero=allow_zero)
    require_positive(f"{name} (high)", high)
    if high < low:
        raise InputError(f"{name} must be (low, high) with low ≤ high (got {bounds!r})")


def _check_settings(
    n_averages: int,
    n_samples: int,
    oversampling: int,
    peak_force_n: tuple[float, float],
    overload_level_n: float,
    overload_factor: tuple[float, float],
) -> dict[str, int]:
    for name, value, least in (
        ("n_averages", n_averages, 1),
        ("n_samples", n_samples, 8),
        ("oversampling", oversampling, 2),
    ):
        require_whole(name, value, least)
    _check_range("peak_force_n", peak_force_n)
    require_positive("overload_level_n", overload_level_n)
    if peak_force_n[1] >= overload_level_n:
        raise InputError(
            f"peak_force_n (up to {peak_force_n[1]} N) must stay below overload_level_n "
            f"({overload_level_n} N): normal hits would clip"
        )
    _check_range("overload_factor", overload_factor)
    if overload_factor[0] <= 1.0:
        raise InputError(f"overload_factor must exceed 1 (got {overload_factor!r})")
    return {
        "n_averages": int(n_averages),
        "n_samples": int(n_samples),
        "oversampling": int(oversampling),
    }
