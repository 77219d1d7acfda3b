"""Step ``oblique``: a ball arriving at an angle (and with spin) at one point of the face —
outgoing angle and spin against incoming angle.

Writes ``oblique.csv`` (:data:`OBLIQUE_COLUMNS`) and ``run.json``; the figure comes from the
caller's hook.
"""

from __future__ import annotations

import os
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from numpy.typing import ArrayLike

from racketdyn.contact import compound_law
from racketdyn.errors import (
    InputError,
    one_of,
    require_finite,
    require_numbers,
    require_positive,
)
from racketdyn.impact.grid import check_string_bed, point_law
from racketdyn.impact.oblique import (
    DEFAULT_TANGENTIAL_CONTACT,
    ObliqueCurve,
    TangentialContact,
    oblique_curve,
    require_friction,
    require_tangential_stiffness,
)
from racketdyn.impact.transient import TRANSIENT_SUPPORTS
from racketdyn.io import racket_to_dict
from racketdyn.plausibility import check, check_speeds
from racketdyn.racket import Racket
from racketdyn.workflows.figure_data import defer_figure_data
from racketdyn.workflows.inputs import (
    single_support,
)
from racketdyn.workflows.run import (
    StepResult,
    report,
    run_step,
    write_rows,
)
from racketdyn.workflows.setup import DEFAULT_SETUP, Setup

if TYPE_CHECKING:
    import xarray as xr

__all__ = [
    "DEFAULT_OBLIQUE",
    "OBLIQUE_ANGLES_DEG",
    "OBLIQUE_COLUMNS",
    "SPIN_CAVEAT",
    "ObliqueOptions",
    "ObliqueResult",
    "run_oblique",
]

OBLIQUE_ANGLES_DEG = (0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0)
"""Default incoming angles to the face normal, degrees."""

SPIN_CAVEAT = (
    "caveat: spin depends strongly on the tangential stiffness k_t (the grip is lossless); "
    "fit k_t to measured rebound spin before quoting it (racketdyn.impact.oblique)"
)

OBLIQUE_COLUMNS = (
    "ball_speed_mps",
    "racket_speed_mps",
    "incoming_angle_deg",
    "incoming_spin_radps",
    "outgoing_angle_deg",
    "outgoing_spin_radps",
    "normal_speed_mps",
    "tangential_speed_mps",
    "gripped",
    "grip_time_s",
    "tangential_impulse_ns",
    "friction_loss_j",
    "status",
)
"""Columns of ``oblique.csv``, one row per incoming angle; the fields of
:class:`~racketdyn.impact.oblique.ObliqueCurve` (angles from the face normal, spin about n̂ × t̂,
speeds away from the face and along it)."""


@dataclass
class ObliqueResult(StepResult):
    """What :func:`run_oblique` computed and wrote.

    Attributes
    ----------
    curve : ObliqueCurve
        Outgoing angle and spin against incoming angle.
    point : tuple of float
        The impact point (x, y), m.
    support : str
        The support.
    contact : TangentialContact
        The tangential contact used.
    racket : Racket
        The racket.
    """

    curve: ObliqueCurve | None = None
    point: tuple[float, float] = (0.0, 0.0)
    support: str = "free"
    contact: TangentialContact = field(default_factory=lambda: DEFAULT_TANGENTIAL_CONTACT)
    racket: Racket | None = None

    def to_xarray(self) -> xr.Dataset:
        """The run's oblique impacts as one :class:`xarray.Dataset`.

        The curve's dataset (:meth:`~racketdyn.impact.oblique.ObliqueCurve.to_xarray`: one
        ``impact`` per incoming angle, outgoing angles, spins, speeds, grip, friction loss,
        status) with the run's own coordinates — the point ``x_m``, ``y_m`` and the
        ``support`` — and the tangential contact used as attributes
        (``friction_coefficient``, ``tangential_stiffness_n_per_m``, ``inertia_factor``).

        Returns
        -------
        xarray.Dataset
            Writable as netCDF.
        """
        if self.curve is None:
            raise ValueError("no oblique impacts in this result: run_oblique makes them")
        dataset = self.curve.to_xarray().assign_coords(
            x_m=((), self.point[0], {"units": "m", "long_name": "impact point along the axis"}),
            y_m=((), self.point[1], {"units": "m", "long_name": "impact point across it"}),
            support=((), self.support, {"long_name": "support condition"}),
        )
        dataset.attrs |= {
            "friction_coefficient": float(self.contact.friction_coefficient),
            "tangential_stiffness_n_per_m": float(self.contact.stiffness_n_per_m),
            "inertia_factor": float(self.contact.inertia_factor),
        }
        return dataset


@dataclass(frozen=True)
class ObliqueOptions:
    """The oblique impacts: the ball's arrival, the point and support, the tangential contact
    and the racket's motion.

    The fields are the words the library's errors name in backticks (``speed``), which
    the CLI turns into its flags (:func:`racketdyn.cli.options.in_flags`); they are checked
    when :func:`run_oblique` runs.

    Attributes
    ----------
    speed : float
        Incoming ball speed, m/s.
    angles_deg : array_like
        Incoming angles to the face normal, degrees, each in (-90, 90) (or one text
        ``"0,30"``, as the command line spells them; ``point`` too, ``"0.505,0"``).
    spin_radps : float
        Incoming spin, rad/s (+ = the sense of rolling along the face).
    point : (x, y), optional
        Impact point, m (default: the face centre).
    support : {"free", "pinned", "hand"}
        Support.
    friction : float, optional
        Ball–string friction coefficient μ (default 0.4).
    tangential_stiffness : float, optional
        Tangential stiffness k_t, N/m (default 1e4; inf: a rigid grip).
    racket_speed : float
        Racket speed towards the ball, m/s.
    racket_tangential_speed : float
        Racket face speed along the face, m/s.
    """

    speed: float = 20.0
    angles_deg: ArrayLike = OBLIQUE_ANGLES_DEG
    spin_radps: float = 0.0
    point: tuple[float, float] | None = None
    support: str = "free"
    friction: float | None = None
    tangential_stiffness: float | None = None
    racket_speed: float = 0.0
    racket_tangential_speed: float = 0.0


DEFAULT_OBLIQUE = ObliqueOptions()
"""20 m/s at 0–60° without spin, at the face centre of a free racket at rest, μ 0.4, k_t 1e4."""


@run_step
def run_oblique(
    out: str | os.PathLike[str],
    setup: Setup = DEFAULT_SETUP,
    options: ObliqueOptions = DEFAULT_OBLIQUE,
) -> ObliqueResult:
    """Oblique impacts at one point, one per incoming angle; write the run folder.

    The steps: the options checked (:func:`_incoming`, :func:`_racket_motion`), the point
    and the tangential contact (:func:`_impact_point`, :func:`_tangential_contact`), the
    impacts (:func:`~racketdyn.impact.oblique.oblique_curve`), ``oblique.csv``
    (:func:`_oblique_rows`) and run.json.

    Parameters
    ----------
    out : path
        Output folder (created if missing).
    setup : Setup
        Of the :class:`~racketdyn.workflows.setup.Setup`, oblique uses the racket and its modes,
        the ball, the hand, the string bed (the face centre's law or the impact point's own) and
        ``allow_implausible``; and the run (command, figures, progress).
    options : ObliqueOptions
        The ball's speed, angles and spin, the point, support, tangential contact and the
        racket's motion.
    """
    allow = setup.allow_implausible
    speed, angles, spin = _incoming(options, allow)
    the_support = one_of(
        "`support`",
        single_support(
            "oblique",
            options.support,
            "its outgoing angles and spins, oblique.csv and figure are one support's",
        ),
        TRANSIENT_SUPPORTS,
    )
    used = setup.racket_setup()
    extra: list[str] = []
    where = _impact_point(used.racket, options.point, extra)
    check_string_bed(setup.string_bed, None, used.racket)
    the_hand, hand_defaults = setup.hand_used([the_support])
    contact = _tangential_contact(options, allow, extra)
    racket_speed, face_speed = _racket_motion(options, allow)
    the_ball, ball_defaults = setup.ball_used()
    defaults_used = [*used.defaults, *extra, *hand_defaults, *ball_defaults, *setup.defaults]
    model = used.modal_model
    report(setup.progress, f"oblique impacts at {len(angles)} angles")
    curve = oblique_curve(
        used.racket,
        the_ball,
        where,
        speed,
        angles,
        spin,
        the_support,
        racket_speed,
        contact,
        face_speed,
        modal_model=model,
        law=(
            point_law(used.racket, the_ball, where)
            if setup.string_bed == "local"
            else compound_law(used.racket, the_ball)
        ),
        hand=the_hand,
    )
    out_dir = Path(out)
    result = ObliqueResult(
        out_dir,
        [write_rows(out_dir / "oblique.csv", _oblique_rows(curve))],
        curve=curve,
        point=where,
        support=the_support,
        contact=contact,
        racket=used.racket,
    )
    defer_figure_data(
        result, {"curve": curve, "point": where, "support": the_support, "contact": contact}
    )
    inputs = {
        **used.provenance,
        "racket": racket_to_dict(used.racket),
        "point_m": list(where),
        "ball_speed_mps": speed,
        "angles_deg": angles,
        "spin_radps": spin,
        "support": the_support,
        "racket_speed_mps": racket_speed,
        "racket_tangential_speed_mps": face_speed,
        "tangential_contact": {
            **asdict(contact),
            "effective_mass_kg": contact.effective_mass(the_ball),
            "grip_period_s": contact.grip_period(the_ball),
        },
        "rigid": setup.rigid,
        "string_bed": setup.string_bed,
        "defaults_used": defaults_used,
        "method": "normal impact by the transient simulation (reference engine), tangential "
        "elastic-Coulomb contact on its normal force history (racketdyn.impact.oblique)",
        "modal_model": None if model is None else model.summary(),
        "hand": None if the_hand is None else asdict(the_hand),
        "caveat": SPIN_CAVEAT,
        "columns": {"oblique.csv": list(OBLIQUE_COLUMNS)},
    }
    return setup.finish(result, inputs, "oblique")


def _incoming(options: ObliqueOptions, allow_implausible: bool) -> tuple[float, list[float], float]:
    """The incoming ball speed (m/s), angles (degrees, each in (-90, 90)) and spin (rad/s),
    checked, the racket's speed towards the ball too (each within play unless
    ``allow_implausible``)."""
    speed = require_positive("`speed`", options.speed)
    check_speeds("`speed`", [speed], "ball_speed_mps", allow_implausible)
    check_speeds("`racket_speed`", [options.racket_speed], "racket_speed_mps", allow_implausible)
    # a sequence, one angle, or the command line's "0,30"
    angles = require_numbers("`angles_deg`", options.angles_deg, "degrees from the face normal")
    for angle in angles:
        if not -90.0 < angle < 90.0:
            raise InputError(
                "`angles_deg`: each incoming angle must lie strictly between -90 and 90 degrees "
                f"from the face normal (got {angle:g})"
            )
    spin = require_finite("`spin_radps`", options.spin_radps)
    check("spin_radps", spin, "`spin_radps`", allow_implausible=allow_implausible)
    return speed, angles, spin


def _impact_point(
    the_racket: Racket, point: tuple[float, float] | None, defaults_used: list[str]
) -> tuple[float, float]:
    """The impact point (x, y), m: ``point``, or the face centre (said in ``defaults_used``);
    refused outside the head."""
    if point is None:
        where = (the_racket.head.centre_x_m, the_racket.head.centre_y_m)
        defaults_used.append("impact point: the face centre")
    else:
        flat = require_numbers("`point`", point, "x,y in m")  # or the command line's "0.505,0"
        if len(flat) != 2:
            raise InputError(f"`point` is the impact point (x, y), m: two numbers (got {point!r})")
        where = (flat[0], flat[1])
    the_racket.head.check_inside([where])
    return where


def _tangential_contact(
    options: ObliqueOptions, allow_implausible: bool, defaults_used: list[str]
) -> TangentialContact:
    """The tangential contact: μ and k_t as given, checked and named as the options name them
    (μ within play unless ``allow_implausible``), else the defaults' (said in
    ``defaults_used``)."""
    friction, tangential_stiffness = options.friction, options.tangential_stiffness
    if friction is not None:
        friction = require_friction("`friction`", friction)
        check("friction_coefficient", friction, "`friction`", allow_implausible=allow_implausible)
    if tangential_stiffness is not None:
        tangential_stiffness = require_tangential_stiffness(
            "`tangential_stiffness`", tangential_stiffness
        )
    base = DEFAULT_TANGENTIAL_CONTACT
    if friction is None or tangential_stiffness is None:
        defaults_used.append(
            "tangential contact: μ 0.4 (Cross), k_t 1e4 N/m, ball inertia 0.55 m_B R² "
            "(racketdyn.impact.oblique)"
        )
    return TangentialContact(
        friction_coefficient=base.friction_coefficient if friction is None else friction,
        stiffness_n_per_m=(
            base.stiffness_n_per_m if tangential_stiffness is None else tangential_stiffness
        ),
        inertia_factor=base.inertia_factor,
    )


def _racket_motion(options: ObliqueOptions, allow_implausible: bool) -> tuple[float, float]:
    """The racket's speed towards the ball and along the face, m/s, checked (within play
    unless ``allow_implausible``)."""
    racket_speed = require_finite("`racket_speed`", options.racket_speed)
    face_speed = require_finite("`racket_tangential_speed`", options.racket_tangential_speed)
    # either sense along the face: its size against the speeds rackets are swung at
    check_speeds(
        "`racket_tangential_speed`", [abs(face_speed)], "racket_speed_mps", allow_implausible
    )
    return racket_speed, face_speed


def _oblique_rows(curve: ObliqueCurve) -> list[dict[str, Any]]:
    """``oblique.csv``'s rows (:data:`OBLIQUE_COLUMNS`), one per incoming angle."""
    return [
        {
            "ball_speed_mps": curve.ball_speed_mps,
            "racket_speed_mps": curve.racket_speed_mps,
            **{name: getattr(curve, name)[i] for name in OBLIQUE_COLUMNS[2:]},
        }
        for i in range(curve.incoming_angle_deg.size)
    ]
