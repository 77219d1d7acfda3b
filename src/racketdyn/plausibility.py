"""Plausible ranges of every number a person types: the one table, and the check that reads it.

A value in the wrong unit (grams for kilograms, millimetres for metres, km/h for m/s) is a
valid number to the physics and gives garbage marked "ok".  Each input therefore has two
ranges:

* the **plausible** range — what real rackets, strings, balls and strokes span (sources and
  reasoning in the comments of :data:`RANGES`).  A value outside is refused with one line naming
  the input, the value, the range and the likely slip ("did you give grams?"), unless the user
  says the object really is unusual (``allow_implausible``: ``--allow-implausible`` on the
  command line, ``[checks] allow_implausible = true`` in a racket file, ``allow_implausible=True``
  from Python);
* the **limits** — beyond them no object of the kind exists in that unit (a 5 kg point mass, a
  2 m ball flattening): the value is a slip and is refused even with ``allow_implausible``.

Objects built in Python (``Racket(...)``, ``Ball(...)``, sweep designs) are taken as given; the
readers of files and options call :func:`check`.  docs/racket-file.md says what the user sees.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Iterable
from dataclasses import dataclass

from racketdyn.errors import InputError

__all__ = [
    "OVERRIDE_FILE",
    "OVERRIDE_OPTION",
    "RANGES",
    "Range",
    "Slip",
    "check",
    "check_limits",
    "check_load_deflection",
    "check_speeds",
]

log = logging.getLogger(__name__)

OVERRIDE_OPTION = "if it is meant, set `allow_implausible`"
"""How to go on with an unusual value given as an option or a Python argument."""
OVERRIDE_FILE = "if the racket really is so, add [checks] allow_implausible = true to the file"
"""How to go on with an unusual value in a racket file."""


@dataclass(frozen=True)
class Slip:
    """A unit a value may have been given in by mistake.

    Parameters
    ----------
    name : str
        The unit's name in the message ("grams").
    symbol : str
        Its symbol ("g").
    si : float
        One of it in the SI unit of the quantity (1 g = 0.001 kg).
    least : float
        The smallest magnitude a person types in this unit (per cent: 1; 0.6 is no 0.6 %).
    """

    name: str
    symbol: str
    si: float
    least: float = 0.0


@dataclass(frozen=True)
class Range:
    """The plausible range and the limits of one input, in its SI unit.

    Parameters
    ----------
    says : str
        The start of the sentence that gives the range ("a strung racket weighs").
    low, high : float
        Plausible range: values outside are refused unless ``allow_implausible``.
    limit_low, limit_high : float
        Beyond these no such object exists: refused even with ``allow_implausible``.
    unit : str
        The SI unit of the input ("kg").
    slips : tuple of Slip
        Units a person might have used instead; a value that lands in the plausible range when
        read in one of them is named in the message.
    field_unit : Slip or None
        The unit the field quotes the range in, shown beside the SI one ("56–59.4 g").
    tail : str
        Words after the range ("from the butt").
    """

    says: str
    low: float
    high: float
    limit_low: float
    limit_high: float
    unit: str
    slips: tuple[Slip, ...] = ()
    field_unit: Slip | None = None
    tail: str = ""

    def __post_init__(self) -> None:
        if not self.limit_low <= self.low < self.high <= self.limit_high:
            raise ValueError(f"range {self.says!r}: limits must enclose the plausible range")

    def text(self) -> str:
        """The plausible range in words: "a strung racket weighs 0.23–0.4 kg (230–400 g)"."""

        def span(low: float, high: float, unit: str) -> str:
            words = f"up to {_g(high)}" if low == 0 else f"{_g(low)}–{_g(high)}"
            return f"{words} {unit}" if unit else words  # a dimensionless input: no unit

        words = f"{self.says} {span(self.low, self.high, self.unit)}"
        if self.field_unit is not None:
            shown = self.field_unit
            words += f" ({span(self.low / shown.si, self.high / shown.si, shown.symbol)})"
        return f"{words} {self.tail}" if self.tail else words

    def likely_slips(self, value: float) -> list[str]:
        """The slips that would make ``value`` plausible, as "grams (300 g = 0.3 kg)"; for a
        value beyond the limits with none, those that would bring it inside the limits."""

        def within(low: float, high: float) -> list[str]:
            return [
                f"{slip.name} ({_g(value)} {slip.symbol} = {_g(value * slip.si)} {self.unit})"
                for slip in self.slips
                if low <= value * slip.si <= high and abs(value) >= slip.least
            ]

        found = within(self.low, self.high)
        if not found and not self.limit_low <= value <= self.limit_high:
            found = within(self.limit_low, self.limit_high)
        return found


def _shown(number: float) -> float:
    """``number`` to the 3 significant figures the messages print it with."""
    return float(f"{number:.3g}")


def _g(number: float) -> str:
    """A number to 3 significant figures, without float noise (5000, not 5e+03)."""
    if 1e3 <= abs(number) < 1e6:
        return f"{float(f'{number:.3g}'):.0f}"
    return f"{number:.3g}"


# --- units a value may have slipped into -------------------------------------------------------
GRAM = Slip("grams", "g", 1e-3)
OUNCE = Slip("ounces", "oz", 0.028349523125)
POUND = Slip("pounds", "lb", 0.45359237)
MILLIMETRE = Slip("millimetres", "mm", 1e-3)
CENTIMETRE = Slip("centimetres", "cm", 1e-2)
INCH = Slip("inches", "in", 0.0254)
KM_PER_H = Slip("km/h", "km/h", 1.0 / 3.6)
MPH = Slip("mph", "mph", 0.44704)
POUND_FORCE = Slip("pounds", "lb", 4.4482216152605)
KILOGRAM_FORCE = Slip("kilograms (kgf)", "kg", 9.80665)
GRAM_FORCE = Slip("grams (gf)", "g", 9.80665e-3)
NEWTON_MILLIMETRE = Slip("N·mm", "N·mm", 1e-3)
KILONEWTON = Slip("kN", "kN", 1e3)
GIGAPASCAL = Slip("GPa", "GPa", 1e9)
MEGAPASCAL = Slip("MPa", "MPa", 1e6)
KILONEWTON_PER_M = Slip("kN/m", "kN/m", 1e3)
NEWTON_PER_MM = Slip("N/mm", "N/mm", 1e3)
KILONEWTON_S_PER_M = Slip("kN·s/m", "kN·s/m", 1e3)
NEWTON_S_PER_MM = Slip("N·s/mm", "N·s/mm", 1e3)
KG_CM2 = Slip("kg·cm²", "kg·cm²", 1e-4)
G_M2 = Slip("g·m²", "g·m²", 1e-3)
G_CM2 = Slip("g·cm²", "g·cm²", 1e-7)
KG_M2_AS_KG_CM2 = Slip("kg·m²", "kg·m²", 1e4)
G_CM2_AS_KG_CM2 = Slip("g·cm²", "g·cm²", 1e-3)
SQUARE_INCH = Slip("square inches", "sq in", 6.4516)  # as cm²
SQUARE_METRE_AS_CM2 = Slip("m²", "m²", 1e4)
RAD_PER_S = Slip("rad/s", "rad/s", 1.0 / (2.0 * math.pi))
KILOHERTZ = Slip("kHz", "kHz", 1e3)
DEG_PER_S = Slip("degrees per second", "°/s", math.pi / 180.0)
PER_CENT = Slip("per cent", "%", 0.01, least=1.0)
RPM = Slip("revolutions per minute", "rpm", 2.0 * math.pi / 60.0)
RADIAN = Slip("radians", "rad", 180.0 / math.pi)  # as degrees

_MASS = (GRAM, OUNCE, POUND)
_LENGTH = (MILLIMETRE, CENTIMETRE, INCH)
_SPEED = (KM_PER_H, MPH)

# --- the table ---------------------------------------------------------------------------------
RANGES: dict[str, Range] = {
    # The ball.  ITF Rules of Tennis, Appendix I: mass 56.0–59.4 g, diameter 6.54–6.86 cm (types
    # 1–3).  Stage (red/orange/green) balls weigh 36–51.5 g: unusual, allowed with the override.
    # Limits: a 5 g or 1 kg "ball" is a unit slip, not a ball.
    "ball_mass_kg": Range("a tennis ball weighs", 0.0560, 0.0594, 0.005, 1.0, "kg", _MASS, GRAM),
    "ball_diameter_m": Range(
        "a tennis ball measures", 0.0654, 0.0686, 0.01, 0.5, "m", _LENGTH, CENTIMETRE
    ),
    # Speeds of play: the fastest serves measured are ≈ 263 km/h (73 m/s): 75 m/s for the ball;
    # racket heads reach ≈ 45–50 m/s at the tip on a serve: 55 m/s for the racket at the impact
    # point (67 there is most likely 67 mph = 30 m/s, the new-user trial of issue 13).  Limit:
    # the speed of sound, where no contact model of a ball means anything.  The contact model
    # itself holds to 70 m/s of relative speed (ball + racket; docs/references.md, "High-speed
    # contact"); beyond its laws' range a row is NaN with its status, not refused here.
    "ball_speed_mps": Range("balls are played at", 0.0, 75.0, 0.0, 340.0, "m/s", _SPEED, KM_PER_H),
    "racket_speed_mps": Range(
        "rackets are swung at", 0.0, 55.0, 0.0, 340.0, "m/s", _SPEED, KM_PER_H
    ),
    # Ball and racket together: the contact laws hold to 70 m/s of relative speed (above); a
    # pair beyond it (60 + 40 m/s) gave rows marked ok from laws pushed past what they rest on
    # (the trial of 2026-11-27).
    "relative_speed_mps": Range(
        "the contact laws hold for ball + racket speeds of", 0.0, 70.0, 0.0, 680.0, "m/s"
    ),
    # The swing (impact.swing.Swing).  The shoulder lies ≈ 0.6 m behind the butt for a straight
    # arm (Dempster/Winter, 1.75 m adult); a wrist-led swing turns about ≈ 0.1 m: 0–1.2 m covers
    # every stroke.  Angular speeds at impact: ≈ 20–40 rad/s in groundstrokes, up to ≈ 60 rad/s
    # in serves (racket-head speeds of 30–50 m/s at ≈ 1.1 m from the shoulder); a blocked volley
    # turns at a few rad/s: 2–80 rad/s (0 is a racket at rest: predict's racket speed 0, not a
    # swing).  Limits: no arm turns a racket at 1000 rad/s or about an axis 3 m away.
    "axis_to_butt_m": Range(
        "the swing axis (shoulder) lies", 0.0, 1.2, 0.0, 3.0, "m", _LENGTH, None, "behind the butt"
    ),
    "angular_speed_radps": Range(
        "rackets turn at", 2.0, 80.0, 0.0, 1000.0, "rad/s", (DEG_PER_S, RPM), None, "at impact"
    ),
    # Spin of the incoming ball: topspin groundstrokes ≈ 2000–3500 rpm, the heaviest ≈ 5000 rpm
    # (≈ 520 rad/s); ±600 rad/s covers play, either sense.  Limits: ±10⁴ rad/s (≈ 95 000 rpm)
    # would tear a ball's cloth; typed in rpm it lands far above the plausible range.
    "spin_radps": Range(
        "balls arrive spinning at",
        -600.0,
        600.0,
        -1.0e4,
        1.0e4,
        "rad/s",
        (RPM,),
        RPM,
        "(either sense)",
    ),
    # The hammer's force channel (frf --force-range): a modal hammer's range runs from ≈ 200 N
    # (a small tip) to ≈ 20 kN (a sledge); 10 N–100 kN spans them.  Limits: 0.1 N–10 MN —
    # beyond, no hammer (1e9 N ran; the fifth session's scan of every option).
    "force_range_n": Range(
        "a hammer's force channel measures", 10.0, 1.0e5, 0.1, 1.0e7, "N", (), None, "at most"
    ),
    # The hammer's hits (frf: the median peak force of the accepted averages): a modal hammer on
    # a racket or a lab structure strikes with ≈ 10 N (a light tap with a small tip) to a few
    # kN; under 1 N a hit hardly stands above a hammer's noise.  Forces read in volts — the
    # channel before the hammer's sensitivity, ≈ 2.25 mV/N for a common modal hammer (1 V ≈
    # 444 N) — peak at 0.01–1: the wing's OpenModal records, 0.07–0.10 "N" (new-user trial,
    # eleventh session).  Limits: 1e-9 N (nothing measured) to 10 MN (no hammer).
    "hammer_peak_force_n": Range(
        "a modal hammer's hits peak at",
        1.0,
        1.0e5,
        1.0e-9,
        1.0e7,
        "N",
        (Slip("volts of a 2.25 mV/N hammer", "V", 1.0 / 2.25e-3),),
        None,
        "(the median hit)",
    ),
    # Ball–string friction (impact.oblique.TangentialContact): Cross measured μ ≈ 0.4 for a ball
    # sliding on strings (the default; docs/references.md); felt on nylon or polyester stays
    # below 1.  Limits: 10 — a thousand-fold μ (typed 1e9) ran the tangential model into its
    # 10 000 grip/slide phases (the fifth session's scan of every option).
    "friction_coefficient": Range(
        "the ball–string friction coefficient (μ) is", 0.0, 1.0, 0.0, 10.0, ""
    ),
    # Swing angle from rest to impact (torque model): a blocked volley turns ≈ 15–30°, a
    # groundstroke ≈ 90–180°, a serve up to a turn.  Below 15° the number is most likely radians
    # (1.57 for a quarter turn).  Limits: the model's (0, 360°].
    "swing_angle_deg": Range(
        "a racket turns", 15.0, 360.0, 0.0, 360.0, "°", (RADIAN,), None, "from rest to impact"
    ),
    # Shoulder torque: Kawazoe's forehand 56.9 N·m; elite serves model at ≈ 100–150 N·m.
    "torque_nm": Range(
        "a shoulder gives", 5.0, 250.0, 0.1, 5000.0, "N·m", (NEWTON_MILLIMETRE,), None, "of torque"
    ),
    # The arm behind the grip (impact.hand.Hand): Kawazoe's 1 kg at the handle; a whole adult
    # arm is ≈ 3.5 kg (Dempster).  0.2–6 kg spans children to heavy adults.
    "hand_arm_mass_kg": Range("an arm behind the grip weighs", 0.2, 6.0, 0.01, 100.0, "kg", _MASS),
    # A ball stuck on the strings (compound --preload): its weight (0.57 N) and the press that
    # sticks it; at 50 N the ball is already ≈ 2 mm into the bed, no longer a small amplitude.
    # Limits: the weight of a person on the ball (1 kN).  New-user trial of 2026-11-26: 5000 N
    # was taken and gave a 169 kN/m spring.
    "preload_n": Range(
        "a stuck ball presses on the strings with", 0.0, 50.0, 0.0, 1000.0, "N", (GRAM_FORCE,)
    ),
    # The palm and fingers between handle and arm (impact.hand.Hand): the hand–arm driving-point
    # stiffness normal to the palm is 10⁴–10⁵ N/m at 20–100 Hz (ISO 10068; Gurram, Rakheja and
    # Brammer 1995), a loose to a crushing grip; 2·10³–5·10⁵ N/m spans it with a margin each
    # way.  Its resistive part is 10–100 N·s/m: 1–500 N·s/m.  Limits: a spring of 1 N/m holds
    # nothing, one of 10⁸ N/m is steel; 10⁵ N·s/m would stop the handle dead.  A value in kN/m
    # or N/mm (20 for 2·10⁴ N/m) is the likely slip.
    "hand_stiffness_n_per_m": Range(
        "a hand holds the grip with",
        2.0e3,
        5.0e5,
        1.0,
        1.0e8,
        "N/m",
        (KILONEWTON_PER_M, NEWTON_PER_MM),
        KILONEWTON_PER_M,
        "between handle and arm",
    ),
    "hand_damping_ns_per_m": Range(
        "a hand damps the grip with",
        1.0,
        500.0,
        0.0,
        1.0e5,
        "N·s/m",
        (KILONEWTON_S_PER_M, NEWTON_S_PER_MM),
        None,
        "between handle and arm",
    ),
    # The racket.  Strung rackets on sale weigh 230–400 g (juniors' lighter: allow them);
    # ITF Rules, Appendix II: overall length at most 29.0 in (73.7 cm); adult rackets are
    # ≥ 26 in ≈ 0.66 m, juniors' from 19 in: 0.60 m keeps 25-in juniors' rackets implausible.
    "mass_kg": Range("a strung racket weighs", 0.230, 0.400, 0.05, 3.0, "kg", _MASS, GRAM),
    "length_m": Range("a racket is", 0.600, 0.7366, 0.2, 2.0, "m", _LENGTH, INCH, "long"),
    # Balance point: 31–36 cm from the butt on rackets on sale (head-light to head-heavy).
    "balance_m": Range(
        "a racket balances", 0.28, 0.40, 0.05, 2.0, "m", _LENGTH, None, "from the butt"
    ),
    # Pivot of the hand-held racket: in the handle, ≈ 70 mm (the paper); the handle is ≈ 20 cm.
    "grip_m": Range(
        "the grip pivot lies", 0.02, 0.20, 0.0, 1.0, "m", _LENGTH, None, "from the butt"
    ),
    # Inertia about the balance point: I_G = swingweight − M (x_G − 0.1 m)², which over the
    # ranges here gives ≈ 0.010–0.021 kg·m² (Kawazoe's racket 0.0131); widened a little.
    "inertia_cg_kgm2": Range(
        "a racket's inertia about its balance point is",
        0.008,
        0.025,
        5e-4,
        0.5,
        "kg·m²",
        (G_M2, KG_CM2, G_CM2),
    ),
    # Swingweight (axis 10 cm from the butt) of rackets on sale: 250–380 kg·cm².
    "swingweight_kgcm2": Range(
        "a racket's swingweight is",
        250.0,
        380.0,
        20.0,
        5000.0,
        "kg·cm²",
        (KG_M2_AS_KG_CM2, G_CM2_AS_KG_CM2),
    ),
    # Twistweight of rackets on sale: ≈ 12–17 kg·cm² (the hoop model gives 15.2 for Kawazoe's);
    # 8–30 leaves room for wide and weighted heads.
    "twistweight_kgcm2": Range(
        "a racket's twistweight is",
        8.0,
        30.0,
        0.5,
        500.0,
        "kg·cm²",
        (KG_M2_AS_KG_CM2, G_CM2_AS_KG_CM2),
    ),
    "roll_inertia_kgm2": Range(
        "a racket's roll inertia is",
        8e-4,
        3e-3,
        5e-5,
        0.05,
        "kg·m²",
        (G_M2, KG_CM2, G_CM2),
    ),
    # The head.  Heads on sale: 80–140 sq in (516–903 cm²); string beds 30–36 cm long and
    # 21–28 cm wide; the centre 0.45–0.55 m from the butt on a 27-in racket.
    "area_cm2": Range(
        "a string bed covers",
        80 * 6.4516,
        140 * 6.4516,
        150.0,
        5000.0,
        "cm²",
        (SQUARE_INCH, SQUARE_METRE_AS_CM2),
        SQUARE_INCH,
    ),
    "centre_x_m": Range(
        "a head's centre lies", 0.40, 0.60, 0.1, 2.0, "m", _LENGTH, None, "from the butt"
    ),
    "half_length_m": Range("a string bed's half-length is", 0.12, 0.22, 0.03, 1.0, "m", _LENGTH),
    "half_width_m": Range("a string bed's half-width is", 0.08, 0.16, 0.02, 1.0, "m", _LENGTH),
    "centre_y_m": Range("a head's centre is off the axis by", -0.02, 0.02, -0.3, 0.3, "m", _LENGTH),
    # Strings.  Tensions strung: 15–35 kg (33–77 lb) per string; gauges 15L–19 = 1.05–1.45 mm;
    # axial modulus: nylon and gut ≈ 2–6 GPa, polyester ≈ 4–10 GPa, aramid hybrids up to
    # tens of GPa; 16 × 19 and 18 × 20 patterns, 14–20 mains and 15–22 crosses on sale.
    # The strings of a racket weigh ≈ 12–20 g (4 % of the racket in the paper).
    "tension_n": Range(
        "a string is strung at",
        15 * 9.80665,
        35 * 9.80665,
        20.0,
        2000.0,
        "N",
        (POUND_FORCE, KILOGRAM_FORCE, KILONEWTON),
        KILOGRAM_FORCE,
    ),
    "string_diameter_m": Range(
        "a string's gauge is", 1.05e-3, 1.45e-3, 3e-4, 5e-3, "m", _LENGTH, MILLIMETRE
    ),
    "string_modulus_pa": Range(
        "a string's axial modulus is",
        1e9,
        5e10,
        5e7,
        1e12,
        "Pa",
        (GIGAPASCAL, MEGAPASCAL),
        GIGAPASCAL,
    ),
    # Tension lost by the played bed: ≈ 30 % just after stringing (Cross and Bower), a few
    # per cent more over days; 0 for a tension measured in the bed.  Given as 30 (per cent),
    # it is beyond the limit of a fraction.
    "tension_loss": Range(
        "a string bed loses",
        0.0,
        0.5,
        0.0,
        0.95,
        "× its pull tension",
        (PER_CENT,),
    ),
    "mains": Range("a racket has", 12, 22, 2, 60, "main strings"),
    "crosses": Range("a racket has", 14, 24, 2, 60, "cross strings"),
    "strings_mass_kg": Range(
        "a racket's strings weigh", 0.008, 0.025, 1e-3, 0.3, "kg", _MASS, GRAM
    ),
    # Scatter of a ball-cannon test (issue 24's uncertainty file): impact location ± 10 mm,
    # ball speed ± 1 m/s are usual (a lab's repeatability); up to 30 mm and 5 m/s plausible.
    # Limits: a 0.2 m scatter misses the head, a 50 m/s one is not a test.
    "location_scatter_m": Range(
        "a ball cannon scatters its impacts by", 0.0, 0.03, 0.0, 0.2, "m", _LENGTH, MILLIMETRE
    ),
    "ball_speed_scatter_mps": Range(
        "a ball cannon scatters its speed by", 0.0, 5.0, 0.0, 50.0, "m/s", _SPEED
    ),
    # Factors on a law or a damping (calibration's scales): 0.3–3 plausible; limits 0.01–100.
    "scale_factor": Range("a scale on a law is", 0.3, 3.0, 0.01, 100.0, "×"),
    # Free modes of rackets on sale: 2-node bending 110–180 Hz (wooden ≈ 100 Hz), 2-node
    # twisting 300–600 Hz (Kawazoe's 361 Hz).
    "first_bending_hz": Range(
        "a racket's first bending mode is at", 80.0, 250.0, 10.0, 2000.0, "Hz", (RAD_PER_S,)
    ),
    "twisting_hz": Range(
        "a racket's first twisting mode is at",
        250.0,
        700.0,
        30.0,
        5000.0,
        "Hz",
        (RAD_PER_S, KILOHERTZ),
    ),
    # Point masses: lead tape strips of 1–10 g, a few together ≤ ≈ 50 g; anywhere on a racket
    # (≤ 0.737 m, ITF) and across a head ≤ 14 cm from the axis.
    "point_mass_kg": Range("lead tape and the like weigh", 0.0, 0.050, 0.0, 1.0, "kg", _MASS, GRAM),
    "point_x_m": Range(
        "a point mass sits", 0.0, 0.7366, 0.0, 2.0, "m", _LENGTH, None, "from the butt"
    ),
    "point_y_m": Range("a point mass sits off the axis by", -0.15, 0.15, -0.5, 0.5, "m", _LENGTH),
    # Load–deflection data (ball and string bed, io.tables): a ball flattens by at most its
    # radius (34 mm), a string bed deflects ≈ 1–3 cm at play's speeds; 10 cm is beyond either.
    # Stiffness F/X at the largest deflection: balls ≈ 25–100 kN/m (one side), string beds
    # ≈ 20–40 kN/m static; foam balls a few kN/m.  Forces given in kN read ≈ 1000× too soft.
    "load_deflection_m": Range(
        "a ball or string bed deflects", 0.0, 0.05, 0.0, 0.1, "m", (MILLIMETRE, CENTIMETRE)
    ),
    "load_stiffness_n_per_m": Range(
        "load over deflection at the largest deflection of a ball or string bed is",
        2e3,
        1e6,
        500.0,
        1e9,
        "N/m",
    ),
}
"""Every plausible range, by input key (docs/racket-file.md lists them for the user)."""


GAUGE_MM = {15.0: 1.45, 16.0: 1.30, 17.0: 1.20, 18.0: 1.11, 19.0: 0.98}
"""Tennis string gauges (US) and the middles of their diameter ranges, mm (docs/references.md,
"Strings": 15 1.41–1.49, 16 1.26–1.34, 17 1.16–1.24, 18 1.06–1.16, 19 0.90–1.06 mm): a gauge
number typed as a diameter is named (new-user trial, 2026-11-26)."""


def check(
    key: str,
    value: float,
    name: str,
    *,
    allow_implausible: bool = False,
    override: str = OVERRIDE_OPTION,
) -> float:
    """Return ``value`` if it is plausible for ``key``, else raise InputError in one line.

    Parameters
    ----------
    key : str
        The input's entry in :data:`RANGES`.
    value : float
        The value, in the input's SI unit.
    name : str
        How the message names the input ("[racket].mass_kg", "`mass_kg`").
    allow_implausible : bool
        Take a value outside the plausible range but inside the limits (logged).
    override : str
        The sentence saying how to allow an unusual value, for the message.

    Returns
    -------
    float
        ``value``.  Values that are not finite numbers are returned unchecked: the type checks
        of the caller report them.
    """
    spec = RANGES[key]
    number = float(value)
    if not math.isfinite(number) or spec.low <= number <= spec.high:
        return value
    if _shown(spec.low) <= _shown(number) <= _shown(spec.high):
        return value  # at an end of the range as the message prints it (147 N for 15 kgf)
    given = f"{name} {_g(number)}" if name.startswith(("-", "`")) else f"{name} = {_g(number)}"
    message = f"{given}: {spec.text()}"
    slips = spec.likely_slips(number)
    if key == "string_diameter_m" and number in GAUGE_MM:  # a gauge number is no unit
        slips.append(f"a gauge number (gauge {number:g} ≈ {GAUGE_MM[number]:g} mm = "
                     f"{GAUGE_MM[number] / 1e3:g} m)")  # fmt: skip
    if slips:
        message += f"; did you give {' or '.join(slips)}?"
    if not spec.limit_low <= number <= spec.limit_high:
        raise InputError(
            f"{message} (outside {_g(spec.limit_low)}–{_g(spec.limit_high)} {spec.unit}: refused "
            "even with `allow_implausible`)"
        )
    if not allow_implausible:
        sep, advice = (" ", override[:1].upper() + override[1:]) if slips else ("; ", override)
        raise InputError(f"{message}{sep}{advice}")
    log.warning("%s (taken: allow_implausible)", message)
    return value


def check_degrees(name: str, values: Iterable[float], *, allow_implausible: bool = False) -> None:
    """Refuse angles that read as radians: every one within ±π/2 and one with a fraction.

    Incidence angles in degrees are written 0, 15, 30…; ``0, 0.5, 1.0`` is a quarter turn in
    radians (new-user trial, 2026-11-26: it ran as three angles within a degree of the normal).

    Parameters
    ----------
    name : str
        How the message names the input (``--angles``).
    values : iterable of float
        The angles, degrees.
    allow_implausible : bool
        Take them as degrees all the same.
    """
    angles = [float(v) for v in values]
    nonzero = [a for a in angles if a != 0.0 and math.isfinite(a)]
    if allow_implausible or not nonzero or max(abs(a) for a in nonzero) > math.pi / 2:
        return
    if all(a == round(a) for a in nonzero):
        return
    degrees = ",".join(f"{math.degrees(a):.3g}" for a in angles)
    raise InputError(
        f"{name} {','.join(f'{a:g}' for a in angles)}: every angle within ±1.57 with a fraction "
        f"— did you give radians ({name}={degrees} in degrees)? {OVERRIDE_OPTION[:1].upper()}"
        f"{OVERRIDE_OPTION[1:]}"
    )


def check_limits(key: str, value: float, name: str) -> float:
    """Return ``value`` unless it lies beyond the limits of ``key`` (a unit slip whatever the
    object): the check a core object makes on itself, silent inside the limits."""
    spec = RANGES[key]
    number = float(value)
    if math.isfinite(number) and not spec.limit_low <= number <= spec.limit_high:
        check(key, value, name)
    return value


def check_e_bg(name: str, value: float) -> None:
    """Refuse an e_BG outside 0–1 in one line, asking about per cent where it looks like one
    (83 → 0.83; the racket-free ratio has no plausible band narrower than its definition).

    Parameters
    ----------
    name : str
        How the message names the input (`` `e_bg` ``, ``[variables].e_bg``).
    value : float
        The value given.
    """
    number = float(value)
    if not math.isfinite(number) or 0.0 <= number <= 1.0:
        return
    slip = (
        f"; did you give a percentage ({_g(number)} % = {_g(number * PER_CENT.si)})?"
        if 10.0 <= number <= 100.0  # per cent is tens (83); 1.2 is no percentage of e_BG
        else ""
    )
    raise InputError(f"{name} {_g(number)}: e_BG is a ratio between 0 and 1 (Kawazoe's 0.83){slip}")


def check_speeds(
    name: str,
    speeds: Iterable[float],
    key: str = "ball_speed_mps",
    allow_implausible: bool = False,
    override: str = OVERRIDE_OPTION,
) -> None:
    """Check speeds (m/s) against the speeds of play (:func:`check`; negative ones are left to
    :func:`racketdyn.errors.require_speeds`)."""
    for speed in speeds:
        if float(speed) >= 0:
            check(key, speed, name, allow_implausible=allow_implausible, override=override)


def check_load_deflection(where: str, deflection: Iterable[float], force: Iterable[float]) -> None:
    """Refuse load–deflection data whose scale shows a unit slip: deflections in mm given as m
    (beyond 0.1 m), forces in kN given as N (load over deflection under 500 N/m).

    Only the limits are enforced (a slip, never an unusual object): the same data are read by
    the ball options and by a racket file's string bed.
    """
    points = [(float(x), float(f)) for x, f in zip(deflection, force, strict=True)]
    positive = [(x, f) for x, f in points if x > 0 and math.isfinite(x) and math.isfinite(f)]
    if not positive:
        return
    largest, force_there = max(positive)
    check("load_deflection_m", largest, f"{where}: largest deflection_m", allow_implausible=True)
    if force_there > 0:
        stiffness = force_there / largest
        spec = RANGES["load_stiffness_n_per_m"]
        if stiffness < spec.limit_low:
            kilo = " Did you give the forces in kN?" if spec.low <= stiffness * 1e3 else ""
            raise InputError(
                f"{where}: force_n {_g(force_there)} N at deflection_m {_g(largest)} m is "
                f"{_g(stiffness)} N/m; {spec.text()}.{kilo} (give forces in N)"
            )
