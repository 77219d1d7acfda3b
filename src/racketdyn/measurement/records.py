"""Roving-hammer test records and the FRF set estimated from them: the measurement nouns.

A roving-hammer test strikes each point of a grid several times (averages) and records the
hammer force and the response of a fixed accelerometer (the reference).  ``HammerRecords``
holds the time records as measured; ``FrfSet`` holds one FRF per hammer point against the
reference, with coherence and what was done to get it.  Frequencies in Hz, time in s, SI units.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any, Literal, get_args

import numpy as np
from numpy.typing import NDArray

from racketdyn._display import html_table, number, shorten, span, words
from racketdyn._grammar import noun
from racketdyn.errors import InputError, require_positive
from racketdyn.numerics import as_locations, as_points

log = logging.getLogger(__name__)

__all__ = [
    "ANALYSER_BANDWIDTH_FACTOR",
    "CONJUGATE_LEVEL",
    "FORCE_DROP_DB",
    "FRF_TYPES",
    "FRF_TYPE_OF_RESPONSE",
    "FRF_UNITS",
    "PHASE_COHERENCE",
    "RESPONSE_TYPES",
    "FrfReferences",
    "FrfSet",
    "FrfType",
    "HammerRecords",
    "ResponseType",
    "SummedFrf",
    "check_fit_together",
    "same_lines",
]

ANALYSER_BANDWIDTH_FACTOR = 2.56
"""Sampling rate / usable bandwidth of an analyser's anti-alias filter (the FFT analysers'
convention): lines above fs/2.56 are filter roll-off."""

FORCE_DROP_DB = 40.0
"""How far the hammer's force spectrum may fall below its low-frequency level within the
default band, dB (:func:`racketdyn.measurement.frf.force_band_top`).

Why 40 dB.  A hammer pulse of length T is flat to about 1/(4T) and then falls; the envelope
of a half sine's side lobes falls as (2fT)⁻² (−40 dB a decade).  H1 divides the response's
noise by the force, so the FRF's floor rises as the force falls: 20 dB down it is 10 ×
higher, 40 dB down 100 ×.  The usual rule for choosing a tip, 10–20 dB, lies at fT ≈ 1.6
for 20 dB, on the main lobe's first null (1.5/T): modes that laboratories read on the side
lobes would be cut (a tool tip's 1961 and 2617 Hz modes, 30 and 37 dB down under its hammer's
pulse, which the lab itself reads).  40 dB (fT ≈ 5, about three times the first null) keeps
them and leaves a mode whose peak stood 60 dB over the response's noise at the plateau (a
good hammer test's) 20 dB over it at the top; beyond, the peaks are the response's noise
over almost no force (the same tool tip's 3.9–14.6 kHz "clear peaks", where the force's envelope is
53–105 dB down)."""

CONJUGATE_LEVEL = 0.05
"""The phase direction (:meth:`FrfSet.phase_direction`) above which a set is taken to be
written with the conjugate convention.  Measured sets of the usual convention read −0.12 to
−0.57 (the real exports of tests/realdata.py, racketdyn's estimates), vtb_siglab's conjugate
case 2 +0.23; a set of noise reads about 0 and is left as it is.  Each FRF counts once (the
mean of their directions): the same exports then read −0.23 to −0.57 (meca0062 −0.27, the wing
−0.23, pyuff's showcase −0.33, vtb_siglab's case 1 −0.57)."""

PHASE_COHERENCE = 0.95
"""Where a set carries its coherence, the phase's turn is read on the steps between lines whose
coherence is at least this (:meth:`FrfSet.phase_direction`).  Elsewhere the response is not
the force's: at the nulls of a hammer pulse's spectrum ((k + ½)/T for a half sine of length
T, inside the force's band from T ≈ 1 ms) |H| is the response's noise over almost no force, the
largest of the band with random phase steps, and turned healthy sets without an exponential
window to +0.6.  H1's phase error is √((1 − γ²)/(2 n_d γ²)) rad (Bendat and Piersol ch. 9),
under 0.1 rad from 3 averages at 0.95; noise reaches it with probability 0.05^(n_d − 1), 0.25 %
at 3 averages."""

ResponseType = Literal["acceleration", "velocity", "displacement"]
RESPONSE_TYPES: tuple[str, ...] = get_args(ResponseType)
FrfType = Literal["accelerance", "mobility", "receptance"]
FRF_TYPES: tuple[str, ...] = get_args(FrfType)
FRF_UNITS = {"receptance": "m/N", "mobility": "m/(N·s)", "accelerance": "m/(N·s²)"}
"""Units of each FRF type, for labels (values are stored in SI)."""
FRF_TYPE_OF_RESPONSE: dict[str, str] = {
    "acceleration": "accelerance",
    "velocity": "mobility",
    "displacement": "receptance",
}


def _locations_or_missing(locations: Any, check: Any, name: str) -> NDArray[np.float64]:
    """Locations checked by ``check``, rows entirely NaN allowed (a point without coordinates)."""
    array = np.asarray(locations, dtype=float)
    if array.ndim == 2 and array.size:
        missing = np.all(np.isnan(array), axis=1)
        if np.any(missing):
            known = check(np.where(missing[:, None], 0.0, array), name)
            return np.asarray(np.where(missing[:, None], np.nan, known))
    return np.asarray(check(array, name))


class _PointsAndReference:
    """What hammer records and FRF sets share: points (nodes, locations) and a reference."""

    nodes: tuple[int, ...]
    locations: NDArray[np.float64]
    reference_node: int
    reference_location: tuple[float, ...]
    source: str

    @property
    def driving_point(self) -> int | None:
        """Index of the point at the reference node (the driving point), if any."""
        return self.nodes.index(self.reference_node) if self.reference_node in self.nodes else None

    @property
    def has_locations(self) -> bool:
        """Every point and the reference have coordinates."""
        return not (
            np.isnan(self.locations).any()
            or np.isnan(np.asarray(self.reference_location, dtype=float)).any()
        )

    def require_locations(self, what: str) -> None:
        """InputError naming ``geometry`` (the CLI's ``--geometry``) unless every point has
        coordinates.

        The reference transducer's own position is not needed (shapes, maps and predictions
        are at the points), and a fixed accelerometer is often not in a lab's geometry.

        Parameters
        ----------
        what : str
            The step that needs them (e.g. ``"the contact-time map"``).
        """
        missing = [
            n
            for n, row in zip(self.nodes, np.asarray(self.locations), strict=True)
            if np.isnan(row).any()
        ]
        if missing:
            named = ", ".join(str(n) for n in missing[:8]) + (", …" if len(missing) > 8 else "")
            raise InputError(
                f"{self.source}: {what} needs node coordinates, which "
                f"{noun(len(missing), 'node')} {named} {noun(len(missing), 'lacks', 'lack')}; give "
                "the file of coordinates as `geometry` (UFF data set 15 or 2411, or CSV "
                "node,x_m,y_m in m)"
            )


ABSURD_FORCE_N = 1.0e6
"""A hammer's force sample beyond this (N) is damage or a unit slip: impact hammers are rated to
≈ 20–50 kN; 1e300 (a mutated file) was taken as data and overflowed the FRFs (issue 26)."""
ABSURD_RESPONSE = 1.0e9
"""A response sample beyond this (m/s², m/s or m) is damage: accelerometers for structures
read up to ≈ 10⁵ m/s²."""
ABSURD_FRF = 1.0e9
"""An FRF value read from a file beyond this (SI units of its type) is damage or a unit slip:
a 1 g structure's accelerance at a resonance with Q = 1000 is ≈ 10⁶ m/(N·s²), its mobility and
receptance smaller; a mutated file's 1e300 was taken as data and overflowed identification
(issue 26).  FRFs racketdyn estimates are not held to it (a force spectrum's null)."""


def _check_scale(
    source: str, node: object, what: str, records: NDArray[np.float64], limit: float, unit: str
) -> None:
    """Refuse finite samples no transducer gives, naming the data set (non-finite ones are the
    quality check's: one average is rejected with its reason)."""
    finite = records[np.isfinite(records)]
    if finite.size and float(np.max(np.abs(finite))) > limit:
        worst = float(np.max(np.abs(finite)))
        raise InputError(
            f"{source}: node {node}: a {what} sample of {worst:.3g} {unit} (beyond {limit:g}): "
            "the data set is damaged or not in SI units"
        )


@dataclass(frozen=True, eq=False)
class HammerRecords(_PointsAndReference):
    """Force and response time records of a roving-hammer test.

    Parameters
    ----------
    sampling_interval_s : float
        Sampling period, s (the paper: 200 µs).
    force : tuple of ndarray
        One array per hammer point, shaped ``(n_averages, n_samples)``: hammer force, N.
    response : tuple of ndarray
        Same shapes: response at the reference, in SI units of ``response_type``
        (m/s², m/s or m).
    response_type : {"acceleration", "velocity", "displacement"}
        What the response transducer measures.
    nodes : tuple of int
        Node number of each hammer point.
    locations : ndarray, shape (n_points, 2)
        Hammer point locations (x, y), m; a row of NaN where a point has no coordinates (a
        file without geometry: FRFs need none, :meth:`require_locations` asks for them).
    reference_node : int
        Node of the response transducer.
    reference_location : tuple of float
        Its location (x, y), m (NaN when unknown).
    pretrigger_s : float
        Time recorded before the trigger, s.
    source : str
        Where the records came from (file name, rig settings).
    """

    sampling_interval_s: float
    force: tuple[NDArray[np.float64], ...]
    response: tuple[NDArray[np.float64], ...]
    response_type: ResponseType
    nodes: tuple[int, ...]
    locations: NDArray[np.float64]
    reference_node: int
    reference_location: tuple[float, float]
    pretrigger_s: float = 0.0
    source: str = ""
    metadata: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        require_positive(f"{self.source}: sampling interval", self.sampling_interval_s)
        if self.response_type not in RESPONSE_TYPES:
            raise InputError(
                f"{self.source}: response type must be one of {', '.join(RESPONSE_TYPES)} "
                f"(got {self.response_type!r})"
            )
        locations = _locations_or_missing(
            self.locations, as_locations, f"{self.source}: hammer point locations"
        )
        n = len(self.nodes)
        if not (len(self.force) == len(self.response) == n == locations.shape[0]):
            raise InputError(
                f"{self.source}: one force record set, response set and location per node"
            )
        forces, responses = [], []
        for node, f, r in zip(self.nodes, self.force, self.response, strict=True):
            f2, r2 = np.atleast_2d(np.asarray(f, float)), np.atleast_2d(np.asarray(r, float))
            if f2.shape != r2.shape or f2.ndim != 2 or f2.shape[1] < 8:
                raise InputError(
                    f"{self.source}: node {node}: force {f2.shape} and response {r2.shape} must "
                    "have the same (n_averages, n_samples) shape with 8 samples or more"
                )
            _check_scale(self.source, node, "force", f2, ABSURD_FORCE_N, "N")
            _check_scale(self.source, node, "response", r2, ABSURD_RESPONSE, "SI units")
            forces.append(f2)
            responses.append(r2)
        lengths = {f.shape[1] for f in forces}
        if len(lengths) > 1:
            raise InputError(f"{self.source}: records differ in length ({sorted(lengths)} samples)")
        object.__setattr__(self, "force", tuple(forces))
        object.__setattr__(self, "response", tuple(responses))
        object.__setattr__(self, "locations", locations)
        object.__setattr__(self, "nodes", tuple(int(n) for n in self.nodes))

    @property
    def n_points(self) -> int:
        """Number of hammer points."""
        return len(self.nodes)

    def _summary(self) -> list[tuple[str, str]]:
        averages = sorted({f.shape[0] for f in self.force})
        return [
            ("hammer points", f"{self.n_points} (nodes {words([str(n) for n in self.nodes])})"),
            ("averages", span(averages)),
            ("samples", f"{self.n_samples} at {number(self.sampling_interval_s)} s"),
            ("response", f"{self.response_type} at node {self.reference_node}"),
            ("source", shorten(self.source)),
        ]

    def __repr__(self) -> str:
        rows = "; ".join(f"{key} {value}" for key, value in self._summary())
        return f"<HammerRecords {rows}>"

    def _repr_html_(self) -> str:
        return html_table("HammerRecords", self._summary())

    @property
    def n_samples(self) -> int:
        """Samples per record."""
        return int(self.force[0].shape[1])

    @property
    def pretrigger_samples(self) -> int:
        """Samples recorded before the trigger."""
        return round(self.pretrigger_s / self.sampling_interval_s)

    @property
    def time(self) -> NDArray[np.float64]:
        """Sample times from the trigger, s (negative in the pre-trigger)."""
        return np.asarray(np.arange(self.n_samples) * self.sampling_interval_s - self.pretrigger_s)


@dataclass(frozen=True)
class SummedFrf:
    """The magnitudes of a set of FRFs summed over its points, Σ|H|, over a band (the curve
    beside the stabilisation diagram; :meth:`FrfSet.summed`).

    Attributes
    ----------
    frequency : ndarray (n_freq,)
        Frequency lines, Hz.
    magnitude : ndarray (n_freq,)
        Σ|H| over the points, in the units of ``frf_type`` (:data:`FRF_UNITS`).
    frf_type : str
        The FRFs' type.
    """

    frequency: NDArray[np.float64]
    magnitude: NDArray[np.float64]
    frf_type: FrfType


@dataclass(frozen=True, eq=False)
class FrfSet(_PointsAndReference):
    """Frequency response functions of hammer points against one reference.

    Parameters
    ----------
    frequency : ndarray, shape (n_freq,)
        Frequency lines, Hz.
    values : ndarray, complex, shape (n_points, n_freq)
        FRF of the response at the reference to a force at each point, SI units of
        ``frf_type`` (receptance m/N, mobility m/(N·s), accelerance m/(N·s²)).
    frf_type : {"accelerance", "mobility", "receptance"}
        What the FRF relates.
    nodes : tuple of int
        Node number of each hammer point.
    locations : ndarray, shape (n_points, 2) or (n_points, 3)
        Hammer point locations (x, y) or (x, y, z), m (a racket's are (x, y): the racket
        workflows use 2-D locations); a row of NaN where a point has no coordinates
        (:meth:`require_locations` asks for them where a step needs them).
    reference_node : int
        Node of the response transducer.
    reference_location : tuple of float
        Its location, m.
    coherence : ndarray, shape (n_points, n_freq), optional
        Ordinary coherence (0–1); None where unknown (e.g. FRFs read from a file).
    n_averages : ndarray of int, shape (n_points,), optional
        Averages used at each point.
    exponential_window_s : float or None
        Time constant τ of the exponential window applied to the response, s.  It adds
        ``1/(τ ω)`` to the damping ratio of a mode at ω; identification removes it.
    estimator : str
        ``H1``, ``H2`` or ``file``.
    source : str
        Where the FRFs came from.
    """

    frequency: NDArray[np.float64]
    values: NDArray[np.complex128]
    frf_type: FrfType
    nodes: tuple[int, ...]
    locations: NDArray[np.float64]
    reference_node: int
    reference_location: tuple[float, ...]
    coherence: NDArray[np.float64] | None = None
    n_averages: NDArray[np.int_] | None = None
    exponential_window_s: float | None = None
    estimator: str = "file"
    source: str = ""
    metadata: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        frequency = np.asarray(self.frequency, dtype=float)
        values = np.atleast_2d(np.asarray(self.values, dtype=complex))
        locations = _locations_or_missing(
            self.locations, as_points, f"{self.source}: FRF point locations"
        )
        if frequency.ndim != 1 or values.shape != (len(self.nodes), frequency.size):
            raise InputError(
                f"{self.source}: FRF values must be shaped (n_points, n_freq) = "
                f"({len(self.nodes)}, {frequency.size}), got {values.shape}"
            )
        if locations.shape[0] != len(self.nodes):
            raise InputError(f"{self.source}: one location per FRF node")
        if np.any(np.diff(frequency) <= 0):
            raise InputError(f"{self.source}: frequencies must rise strictly")
        if self.frf_type not in FRF_TYPES:
            raise InputError(
                f"{self.source}: frf_type must be one of {', '.join(FRF_TYPES)} "
                f"(got {self.frf_type!r})"
            )
        if self.coherence is not None and np.shape(self.coherence) != values.shape:
            raise InputError(f"{self.source}: coherence must have the shape of the FRF values")
        object.__setattr__(self, "frequency", frequency)
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "locations", locations)
        object.__setattr__(self, "nodes", tuple(int(n) for n in self.nodes))

    @property
    def n_points(self) -> int:
        """Number of FRFs."""
        return len(self.nodes)

    def _summary(self) -> list[tuple[str, str]]:
        return [
            (
                "FRFs",
                f"{self.n_points} {self.frf_type} (nodes {words([str(n) for n in self.nodes])})",
            ),
            ("frequency", f"{self.frequency.size} lines, {span(self.frequency)} Hz"),
            ("reference node", str(self.reference_node)),
            ("estimator", self.estimator),
            ("coherence", "none" if self.coherence is None else "yes"),
            ("source", shorten(self.source)),
        ]

    def __repr__(self) -> str:
        rows = "; ".join(f"{key} {value}" for key, value in self._summary())
        return f"<FrfSet {rows}>"

    def _repr_html_(self) -> str:
        return html_table("FrfSet", self._summary())

    @property
    def omega(self) -> NDArray[np.float64]:
        """Angular frequency of each line, rad/s."""
        return np.asarray(2 * np.pi * self.frequency)

    @property
    def bandwidth_hz(self) -> float:
        """Top of the usable band, Hz: the analyser bandwidth where known, else the last line.

        FRFs estimated by racketdyn from time records end at fs/2, of which the lines above
        fs/2.56 are the anti-alias filter's roll-off (``metadata["bandwidth_hz"]``); FRFs read
        from another system's file are exported to their bandwidth, so their last line is it.
        """
        value = self.metadata.get("bandwidth_hz")
        try:
            top = float(value) if value is not None else math.nan
        except (TypeError, ValueError):
            top = math.nan
        last = float(self.frequency[-1])
        return top if 0 < top <= last else last

    @property
    def force_band_hz(self) -> float | None:
        """Where the hammer's force spectrum has fallen too far to excite the structure, Hz.

        Above it the hammer gave no force: the FRF there is the response's noise over almost
        none (:func:`racketdyn.measurement.frf.force_band_top`, ``metadata["force_band_hz"]``).
        Known for FRFs estimated from time records (and written with them by racketdyn); None
        for another system's export, which carries no force, and never above
        :attr:`bandwidth_hz`.
        """
        value = self.metadata.get("force_band_hz")
        try:
            top = float(value) if value is not None else math.nan
        except (TypeError, ValueError):
            return None
        return min(top, self.bandwidth_hz) if top > 0 else None

    def driving_point_sign(self) -> int | None:
        """+1 or −1: the sign the driving-point FRF's modal constants read with; None without one.

        At the driving point every modal constant is positive, so the receptance's imaginary
        part is ≤ 0 at every frequency (the mobility's real part, the accelerance's imaginary
        part ≥ 0).  A driving-point FRF that reads the other way (summed over the lines,
        weighted by magnitude) was measured with the sensor against the hammer or with opposite
        sign conventions of the two channels that the file's direction codes do not say.
        """
        i = self.driving_point
        if i is None:
            return None
        h = self.values[i]
        usable = np.isfinite(h)
        indicator = {"receptance": -h.imag, "mobility": h.real, "accelerance": h.imag}[
            self.frf_type
        ]
        total = float(np.sum(indicator[usable]))
        return None if total == 0 else (1 if total > 0 else -1)

    def phase_direction(self) -> float:
        """Which way the phase turns as the frequency rises: < 0 falls (e^{iωt}), > 0 rises.

        The mean over the FRFs of each one's mean sin Δφ between neighbouring lines, weighted by
        ``|H_k| |H_k+1|`` within the FRF (between −1 and 1; 0 without a usable line).  Each FRF
        counts once whatever its scale: the convention is the analyser's, one for the file,
        and a weakly struck point's FRF, large and its phase steps mostly noise, outweighed the
        others when every line of the set was weighted by its magnitude (an unseen lab's 50 Hz
        frame: its driving point +0.12 against −0.07 and −0.28, the set +0.10, conjugated).
        With the usual convention (a response ``H e^{iωt}``) a mode's phase falls by 180°
        through its resonance and a delay's phase falls too; only anti-resonances, where
        ``|H|`` is small, rise.  An analyser
        writing ``H e^{−iωt}`` (SigLab, vtb_siglab's case 2) gives the conjugate FRF, whose
        phase rises through its resonances.  The sign does not depend on the FRF's type nor on
        its sign (a negated FRF turns the same way).  Only lines up to :attr:`bandwidth_hz`
        count: above it (racketdyn's own estimates to fs/2) the anti-alias filter has taken the
        force away and ``|H|`` is the response's noise over nothing, large enough to outweigh the
        resonances; nor above :attr:`force_band_hz`, where the hammer's own spectrum has (1 ms
        hits at 51.2 kHz, their force 40 dB down at 4.4 kHz, read +0.08 over the 20 kHz
        bandwidth and were conjugated; −0.06 up to 4.4 kHz).  Where the set carries its
        coherence only the steps between lines of coherence :data:`PHASE_COHERENCE` or more
        count, each FRF by the share of its steps that do: the nulls of the hammer's spectrum
        within its band leave the others noise over almost no force.
        """
        top = self.force_band_hz or self.bandwidth_hz
        band = (self.frequency > 0) & (self.frequency <= top)
        band[band] = np.all(np.isfinite(self.values[:, band]), axis=0)
        h = self.values[:, band]
        turns = np.conj(h[:, :-1]) * h[:, 1:]
        read = self._coherent_steps(band)
        if read is not None:
            turns = turns * read
        weight = np.sum(np.abs(turns), axis=1)
        usable = weight > 0
        if not np.any(usable):
            return 0.0
        share = np.ones(h.shape[0]) if read is None else np.mean(read, axis=1)
        ratio = np.sum(turns.imag, axis=1)[usable] / weight[usable]
        return float(np.sum(share[usable] * ratio) / np.sum(share[usable]))

    def _coherent_steps(self, band: NDArray[np.bool_]) -> NDArray[np.bool_] | None:
        """The steps between lines of ``band`` whose coherence is at least
        :data:`PHASE_COHERENCE` (n_points, n_lines − 1); None without a coherence, with one
        that is not (a value over 1), or where no step has it."""
        if self.coherence is None:
            return None
        coherence = np.asarray(self.coherence[:, band], dtype=float)
        if not np.all(np.isfinite(coherence)) or np.any(coherence > 1.0 + 1e-9):
            return None
        high = coherence >= PHASE_COHERENCE
        steps = high[:, :-1] & high[:, 1:]
        return steps if steps.any() else None

    def with_usual_phase(self) -> FrfSet:
        """The set conjugated when its phase rises through the resonances (the conjugate
        convention e^{−iωt}, :meth:`phase_direction` > :data:`CONJUGATE_LEVEL`).

        Modal identification assumes e^{iωt}: fitted to a conjugate FRF the poles turn the
        wrong way and no mode is stable.  ``metadata["conjugated"]`` records that it was
        undone, and a warning is logged.
        """
        direction = self.phase_direction()
        if direction <= CONJUGATE_LEVEL:
            return self
        log.warning(
            "%s: the phase rises through the resonances (mean sin of its step between lines "
            "%+.2f): the conjugate convention e^(-iwt) of some analysers; every FRF conjugated",
            self.source,
            direction,
        )
        return replace(
            self,
            values=np.conj(self.values),
            metadata={
                **self.metadata,
                "conjugated": f"phase rose through the resonances ({direction:+.2f})",
            },
        )

    def with_positive_driving_point(self) -> FrfSet:
        """The set negated when its driving point reads with negative modal constants.

        The reference sensor is common to every FRF of a roving-hammer set, so a sign
        convention the file does not state flips them all; ``metadata["negated"]`` records
        that it was undone (and a warning is logged).
        """
        if self.driving_point_sign() != -1:
            return self
        log.warning(
            "%s: the driving-point FRF (node %d) reads with negative modal constants: the "
            "sensor or the hammer measured against the other's direction; every FRF negated",
            self.source,
            self.reference_node,
        )
        return replace(
            self,
            values=-self.values,
            metadata={**self.metadata, "negated": "driving point read with negative constants"},
        )

    def band(self, low_hz: float, high_hz: float) -> FrfSet:
        """The FRFs between two frequencies (inclusive), Hz."""
        keep = (self.frequency >= low_hz) & (self.frequency <= high_hz)
        if not np.any(keep):
            raise InputError(f"{self.source}: no frequency line between {low_hz} and {high_hz} Hz")
        return replace(
            self,
            frequency=self.frequency[keep],
            values=self.values[:, keep],
            coherence=None if self.coherence is None else self.coherence[:, keep],
        )

    def summed(self, low_hz: float, high_hz: float) -> SummedFrf:
        """Σ|H| over the points between two frequencies (inclusive), Hz."""
        band = self.band(low_hz, high_hz)
        return SummedFrf(band.frequency, np.abs(band.values).sum(axis=0), band.frf_type)

    def at_points(self, indices: Sequence[int]) -> FrfSet:
        """The FRFs of some points only (by index, in the order given)."""
        keep = np.asarray(indices, dtype=int)
        return replace(
            self,
            values=self.values[keep],
            nodes=tuple(self.nodes[k] for k in keep),
            locations=self.locations[keep],
            coherence=None if self.coherence is None else self.coherence[keep],
            n_averages=None if self.n_averages is None else self.n_averages[keep],
        )

    def as_type(self, frf_type: str) -> FrfSet:
        """The same FRFs converted to another type (× (iω)ⁿ); the zero line becomes 0 or NaN."""
        order = {"receptance": 0, "mobility": 1, "accelerance": 2}
        if frf_type not in order:
            raise InputError(f"frf_type must be one of {', '.join(FRF_TYPES)} (got {frf_type!r})")
        power = order[frf_type] - order[self.frf_type]
        factor = np.full(self.omega.shape, np.nan + 0j)
        usable = self.omega > 0 if power < 0 else np.ones(self.omega.shape, bool)
        factor[usable] = (1j * self.omega[usable]) ** float(power)
        return FrfSet(
            frequency=self.frequency,
            values=self.values * factor,
            frf_type=frf_type,  # type: ignore[arg-type]
            nodes=self.nodes,
            locations=self.locations,
            reference_node=self.reference_node,
            reference_location=self.reference_location,
            coherence=self.coherence,
            n_averages=self.n_averages,
            exponential_window_s=self.exponential_window_s,
            estimator=self.estimator,
            source=self.source,
            metadata=dict(self.metadata),
        )


def same_lines(a: NDArray[np.float64], b: NDArray[np.float64]) -> bool:
    """Whether two frequency axes are the same lines (to 1e-9 relative)."""
    return a.shape == b.shape and bool(np.allclose(a, b, rtol=1e-9, atol=0.0))


def check_fit_together(first: FrfSet, other: FrfSet, what: str, against: str) -> None:
    """InputError unless ``other`` has ``first``'s frequency lines, FRF type and exponential
    window: FRFs that one fit takes together (their poles are one set only then).

    Parameters
    ----------
    first, other : FrfSet
        The sets.
    what, against : str
        How the message names ``other`` and ``first``.
    """
    if not same_lines(other.frequency, first.frequency):
        raise InputError(
            f"{what} ({other.source or 'no source'}: {other.frequency.size} lines, "
            f"{other.frequency[0]:g}–{other.frequency[-1]:g} Hz) is on a different frequency "
            f"axis from {against} ({first.frequency.size} lines, {first.frequency[0]:g}–"
            f"{first.frequency[-1]:g} Hz); resample them onto one axis"
        )
    if other.frf_type != first.frf_type:
        raise InputError(
            f"{what} is {other.frf_type}, {against} {first.frf_type}; convert with "
            "FrfSet.as_type first"
        )
    if other.exponential_window_s != first.exponential_window_s:
        raise InputError(
            f"{what} has exponential window τ = {other.exponential_window_s} s, {against} "
            f"τ = {first.exponential_window_s} s; their poles differ, fit them apart"
        )


@dataclass(frozen=True, eq=False)
class FrfReferences:
    """FRFs of the same points against several references (a poly-reference test).

    A roving-hammer test with several fixed accelerometers, or a roving accelerometer with
    several hammer nodes, measures one FRF set per reference on the same points and lines;
    this holds them together so that an identification can use them all at once
    (:func:`racketdyn.modal.polyreference.poly_stabilisation`).

    Parameters
    ----------
    sets : tuple of FrfSet
        One set per reference, each against its own ``reference_node``: the same nodes in
        the same order, the same frequency lines, FRF type and exponential window.

    Raises
    ------
    InputError
        No set; two sets against one reference; sets on other points, lines, types or
        windows than the first.
    """

    sets: tuple[FrfSet, ...]

    def __post_init__(self) -> None:
        sets = tuple(self.sets)
        if not sets or not all(isinstance(s, FrfSet) for s in sets):
            raise InputError("FrfReferences needs one FrfSet per reference (got none)")
        first = sets[0]
        references = [s.reference_node for s in sets]
        if len(set(references)) != len(references):
            raise InputError(f"FrfReferences: a reference given twice ({references})")
        for other in sets[1:]:
            what = f"the set against reference {other.reference_node}"
            if other.nodes != first.nodes:
                raise InputError(
                    f"{what} is on other points than the set against {first.reference_node}; "
                    "keep the points they share (FrfSet.at_points)"
                )
            check_fit_together(first, other, what, f"the set against {first.reference_node}")
        object.__setattr__(self, "sets", sets)

    @property
    def references(self) -> tuple[int, ...]:
        """The reference node of each set."""
        return tuple(s.reference_node for s in self.sets)

    @property
    def nodes(self) -> tuple[int, ...]:
        """The points' nodes (shared by every set)."""
        return self.sets[0].nodes

    @property
    def frequency(self) -> NDArray[np.float64]:
        """The frequency lines, Hz."""
        return self.sets[0].frequency

    @property
    def values(self) -> NDArray[np.complex128]:
        """Every FRF, shaped (n_references, n_points, n_freq)."""
        return np.stack([s.values for s in self.sets])

    @property
    def source(self) -> str:
        """Where the FRFs came from."""
        return self.sets[0].source

    @property
    def shape_reference(self) -> FrfSet:
        """The set a model's shapes are taken from: the first with a driving point (an FRF at
        its own reference node, so the shapes can be mass-normalised), else the first."""
        return next((s for s in self.sets if s.driving_point is not None), self.sets[0])

    def against(self, reference: int) -> FrfSet:
        """The set against one reference node."""
        if reference not in self.references:
            raise InputError(
                f"`reference` {reference}: no set against it (references {list(self.references)})"
            )
        return self.sets[self.references.index(reference)]

    def band(self, low_hz: float, high_hz: float) -> FrfReferences:
        """Every set between two frequencies (inclusive), Hz."""
        return FrfReferences(tuple(s.band(low_hz, high_hz) for s in self.sets))

    def __repr__(self) -> str:
        return (
            f"FrfReferences({len(self.sets)} references {list(self.references)}, "
            f"{len(self.nodes)} points, {self.frequency.size} lines, {self.sets[0].frf_type})"
        )
