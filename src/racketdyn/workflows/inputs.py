"""The inputs every step shares: the racket (with its modes), the ball and the hand.

Each builder returns the object together with the sentences ``run.json`` lists under
``defaults_used`` for whatever it filled in, so a run folder says which numbers nobody chose.
"""

from __future__ import annotations

import json
import logging
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from racketdyn.ball import Ball, RestoringForce
from racketdyn.errors import InputError, one_of, require_words
from racketdyn.impact.hand import Hand
from racketdyn.io import default_racket, load_racket, read_e_bg_table, read_load_deflection
from racketdyn.io.racket_file import DEFAULT_RACKET_NAME, check_racket, read_toml
from racketdyn.io.uff import holds_mode_shapes, mode_shapes_words, model_json_beside
from racketdyn.io.uncertainty_file import racket_spreads
from racketdyn.modal import ModalModel
from racketdyn.plausibility import check, check_e_bg
from racketdyn.racket import SUPPORT_NAMES, Racket
from racketdyn.racket_modal import modal_model_for
from racketdyn.workflows.run import RUN_JSON, sha256

if TYPE_CHECKING:
    from racketdyn.workflows.setup import Setup

__all__ = [
    "RacketInput",
    "RacketSetup",
    "ball_from",
    "ball_location",
    "hand_for",
    "load_racket_input",
    "setup",
    "single_support",
    "supports_named",
    "with_racket_of_run",
]

RacketInput = Racket | str | os.PathLike[str] | None
"""A racket as a step takes it: an object, a TOML file, or None for the built-in racket."""

log = logging.getLogger(__name__)

BUILT_IN_RACKET = f"racket: built-in {DEFAULT_RACKET_NAME} (Kawazoe's test racket)"
BUILT_IN_MODES = "modal model: built-in free-free beam model"


def load_racket_input(
    racket: RacketInput, *, allow_implausible: bool = False
) -> tuple[Racket, dict[str, Any]]:
    """The racket and its provenance (``racket_file`` and, for a file, its SHA-256).

    A :class:`Racket` given from Python meets the checks a racket file meets
    (:func:`racketdyn.io.racket_file.check_racket`; ``allow_implausible`` as the setup's)."""
    if racket is None:
        return default_racket(), {"racket_file": f"built-in {DEFAULT_RACKET_NAME}"}
    if isinstance(racket, Racket):
        check_racket(racket, allow_implausible=allow_implausible)
        return racket, {"racket_file": f"Racket object {racket.name!r} (given from Python)"}
    path = Path(racket)
    loaded = load_racket(path)
    racket_spreads(path)  # its [uncertainty] tables checked with the racket, used or not
    return loaded, {"racket_file": str(path.resolve()), "racket_file_sha256": sha256(path)}


def with_racket_of_run(
    setup: Setup, source: str | os.PathLike[str]
) -> tuple[Setup, dict[str, str]]:
    """``setup`` with the racket of the run that wrote ``source`` when it names none.

    A step reading another step's file (``frf`` a rig's records, ``identify`` an frf run's
    FRFs) takes the racket file that run's ``run.json`` names, when that file is still there
    with the same SHA-256: the lab's chain keeps its racket without ``--racket`` at every
    step (a chain of a rig run with its racket file and an ``frf`` run that took the built-in
    racket was refused by ``report`` as "2 rackets": new-user trial, eleventh session).

    Returns
    -------
    Setup, dict
        The setup (unchanged when it names a racket or the run names none) and, when the
        racket came from the run, ``{"racket_from_run": <its run.json>}`` for run.json.
    """
    if setup.racket is not None:
        return setup, {}
    record = Path(source).parent / RUN_JSON
    try:
        data = json.loads(record.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return setup, {}
    name = data.get("racket_file") if isinstance(data, dict) else None
    digest = data.get("racket_file_sha256") if isinstance(data, dict) else None
    if not isinstance(name, str) or not isinstance(digest, str) or not Path(name).is_file():
        return setup, {}
    if sha256(Path(name)) != digest:
        log.warning(
            "%s names the racket file %s, which has changed since: the built-in racket is "
            "used; give --racket to choose",
            record,
            name,
        )
        return setup, {}
    log.info("racket: %s, as %s names it", name, record)
    return setup.replace(racket=Path(name)), {"racket_from_run": str(record.resolve())}


@dataclass(frozen=True)
class RacketSetup:
    """A racket ready for a step.

    Attributes
    ----------
    racket : Racket
        The racket (its ``modal_model_file`` set when a modal model file was given).
    modal_model : ModalModel or None
        Its modes (built-in, its file or the one given); None for a rigid racket.
    provenance : dict
        Racket and modal-model files with their SHA-256, for run.json.
    defaults : list of str
        The defaults used (built-in racket, built-in modes).
    rigid : bool
        No vibration: no modes.
    """

    racket: Racket
    modal_model: ModalModel | None
    provenance: dict[str, Any]
    defaults: list[str]
    rigid: bool


def ball_location(ball_at: Sequence[float], racket: Racket) -> tuple[float, float]:
    """``ball_at``: where a ball is fixed on the strings (x, y), m, checked to lie on them.

    Parameters
    ----------
    ball_at : sequence of float
        x, y, m.
    racket : Racket
        The racket whose string bed must hold the point.
    """
    values = [float(v) for v in ball_at]
    if len(values) != 2 or not all(math.isfinite(v) for v in values):
        raise InputError("`ball_at`: give the ball's position as x, y in m, e.g. 0.505, 0")
    racket.head.check_inside(np.asarray([values]), "`ball_at`")
    return values[0], values[1]


def setup(
    racket: RacketInput = None,
    modal_model: ModalModel | str | os.PathLike[str] | None = None,
    rigid: bool = False,
    *,
    with_modes: bool = True,
    allow_implausible: bool = False,
) -> RacketSetup:
    """Load the racket, attach a modal model file if given, and build its modes.

    Parameters
    ----------
    racket, modal_model, rigid
        As :class:`racketdyn.workflows.setup.Setup`'s fields (:meth:`Setup.racket_setup
        <racketdyn.workflows.setup.Setup.racket_setup>` calls this).
    with_modes : bool
        Build the modal model (False: steps that only need the racket's geometry).
    allow_implausible : bool
        Take a racket given from Python with values outside the plausible ranges.
    """
    loaded, provenance = load_racket_input(racket, allow_implausible=allow_implausible)
    defaults = [BUILT_IN_RACKET] if racket is None else []
    modal = modal_model
    if modal is not None and rigid:
        raise InputError(
            "give a modal model file (`modal_model`) or a rigid racket (`rigid`), not both"
        )
    if isinstance(modal, ModalModel):
        provenance["modal_model_given"] = f"ModalModel object from Python: {modal.source}"
        if with_modes:
            modal.require_locations("a prediction")
            modal.require_mass_normalised("a prediction")
        return RacketSetup(loaded, modal if with_modes else None, provenance, defaults, rigid)
    if modal is not None:
        path = Path(modal)
        if not path.is_file():
            raise InputError(f"`modal_model` {modal}: no such modal model file")
        _refuse_mode_shapes(path)
        loaded = replace(loaded, modal_model_file=path)
        provenance["modal_model_file"] = str(path.resolve())
        provenance["modal_model_sha256"] = sha256(path)
    elif not rigid and loaded.modal_model_file is None and with_modes:
        defaults.append(BUILT_IN_MODES)
        if isinstance(racket, str | os.PathLike) and not _states_frequency(Path(racket)):
            # the trial of 2026-11-27: a racket file without it ran at the paper's 120 Hz
            # without a word, and the report showed 120 Hz as if it were given
            defaults.append(
                f"first bending frequency: {loaded.first_bending_hz:g} Hz, the paper's racket's "
                "(the racket file gives none; [modal] first_bending_hz, or --uncertainty "
                "literature for the range of rackets on sale)"
            )
            log.warning("%s gives no first bending frequency: %s", racket, defaults[-1])
    model = modal_model_for(loaded) if with_modes and not rigid else None
    if model is not None:
        model.require_locations("a prediction")
        model.require_mass_normalised("a prediction")
    return RacketSetup(loaded, model, provenance, defaults, rigid)


def _refuse_mode_shapes(path: Path) -> None:
    """A mode-shape UFF given as the modal model (identify's ``modes.uff`` for its
    ``modal_model.json``; the new-user trial of 2026-11-27 was told "Extra data: line 2
    column 5"): said what it is, and the JSON to give."""
    if not holds_mode_shapes(path):
        return
    beside = model_json_beside(path)
    give = f"give {beside}" if beside else "give the modal_model*.json written with it"
    raise InputError(
        f"`modal_model` {path}: {mode_shapes_words('a racketdyn modal model JSON file')}; {give}"
    )


def _states_frequency(path: Path) -> bool:
    """The racket file gives ``[modal] first_bending_hz`` (or a modal model file)."""
    modal = read_toml(path, "racket file").get("modal", {})
    return isinstance(modal, dict) and ("first_bending_hz" in modal or "file" in modal)


def ball_from(
    mass_kg: float | None = None,
    e_bg: float | None = None,
    law_file: str | os.PathLike[str] | None = None,
    *,
    allow_implausible: bool = False,
    e_bg_table: str | os.PathLike[str] | Sequence[tuple[float, float]] | None = None,
) -> tuple[Ball, list[str]]:
    """The ball, with the defaults used.

    Parameters
    ----------
    mass_kg : float, optional
        Ball mass, kg (default 0.0577, ITF middle).  Outside the ITF's 56.0–59.4 g it is
        refused (grams typed: always) unless ``allow_implausible``.
    e_bg : float, optional
        Ball–string COR on a head-clamped racket (default 0.83, Kawazoe).
    law_file : path, optional
        Load–deflection CSV (``deflection_m, force_n``), one side; a cubic is fitted.  Data in
        millimetres or kilonewtons are refused (:func:`racketdyn.io.read_load_deflection`).
    allow_implausible : bool
        Take a ball mass outside the plausible range but inside the limits
        (:mod:`racketdyn.plausibility`).
    e_bg_table : path or sequence of (float, float), optional
        e_BG against relative speed: a CSV (``speed_mps, e_bg``,
        :func:`racketdyn.io.read_e_bg_table`) or the pairs themselves (``Ball.e_bg_table``).
        Not together with ``e_bg``.
    """
    if e_bg_table is not None and e_bg is not None:
        raise InputError("give `e_bg` (one value) or `e_bg_table` (e_BG against speed), not both")
    if e_bg is not None:
        check_e_bg("`e_bg`", e_bg)
    if mass_kg is not None and _finite(mass_kg):
        check("ball_mass_kg", mass_kg, "`mass_kg`", allow_implausible=allow_implausible)
    defaults = []
    kwargs: dict[str, Any] = {}
    for value, key, label in (
        (mass_kg, "mass_kg", "ball mass 57.7 g (ITF middle)"),
        (e_bg, "e_bg", "e_BG from ball + strings"),
    ):
        if value is None:
            defaults.append(label)
        else:
            kwargs[key] = value
    if e_bg_table is not None:
        if isinstance(e_bg_table, (str, os.PathLike)):
            kwargs["e_bg_table"] = read_e_bg_table(Path(e_bg_table))
        else:
            kwargs["e_bg_table"] = tuple((float(v), float(e)) for v, e in e_bg_table)
        defaults.remove("e_BG from ball + strings")
    if law_file is not None:
        path = Path(law_file)
        deflection, force = read_load_deflection(path)
        kwargs["restoring_force"] = RestoringForce.fit(
            deflection, force, "polynomial", 3, f"ball, fitted to {path.name}"
        )
    else:
        defaults.append("ball law: its bounce (6 mm at 7.06 m/s, Cross) + adiabatic gas (one side)")
    return Ball(**kwargs), defaults


def hand_for(
    supports: Sequence[str],
    arm_mass_kg: float | None = None,
    *,
    allow_implausible: bool = False,
    stiffness_n_per_m: float | None = None,
    damping_ns_per_m: float | None = None,
) -> tuple[Hand | None, list[str]]:
    """The hand of the ``hand`` support (None without it), with the defaults used.

    Parameters
    ----------
    supports : sequence of str
        The supports of the step.
    arm_mass_kg : float, optional
        Mass of the arm holding the grip, kg (default 1.0, :class:`~racketdyn.impact.hand.Hand`);
        outside 0.2–6 kg refused unless ``allow_implausible``.
    allow_implausible : bool
        Take a value outside the plausible range but inside the limits.
    stiffness_n_per_m : float, optional
        Total stiffness between handle and arm, N/m (default :class:`Hand`'s 2·10⁴); outside
        2·10³–5·10⁵ N/m refused unless ``allow_implausible``.
    damping_ns_per_m : float, optional
        Total damping between handle and arm, N·s/m (default :class:`Hand`'s 12); outside
        1–500 N·s/m refused unless ``allow_implausible``.
    """
    if "hand" not in supports:
        return None, []
    given = {
        "arm_mass_kg": ("hand_arm_mass_kg", "`arm_mass_kg`", arm_mass_kg),
        "stiffness_n_per_m": ("hand_stiffness_n_per_m", "`stiffness_n_per_m`", stiffness_n_per_m),
        "damping_ns_per_m": ("hand_damping_ns_per_m", "`damping_ns_per_m`", damping_ns_per_m),
    }
    fields = {}
    for field, (key, option, value) in given.items():
        if value is None:
            continue
        if _finite(value):
            check(key, value, option, allow_implausible=allow_implausible)
        fields[field] = value
    hand = Hand(**fields)
    unset = [
        f"{words} {number}"
        for field, words, number in (
            ("arm_mass_kg", "arm", f"{hand.arm_mass_kg * 1e3:.0f} g (Kawazoe ACMD 2002)"),
            ("stiffness_n_per_m", "stiffness", f"{hand.stiffness_n_per_m:g} N/m"),
            ("damping_ns_per_m", "damping", f"{hand.damping_ns_per_m:g} N·s/m"),
        )
        if field not in fields
    ]
    if not unset:
        return hand, []
    return hand, [f"hand: the default {', '.join(unset)} (racketdyn.impact.hand.Hand)"]


def _finite(value: object) -> bool:
    """A finite number (others are left to the object's own checks): zero and negative values
    are checked against the range too, so the message names the parameter
    (``hand_for(damping_ns_per_m=0)`` passed unseen; -1 was refused as
    ``hand.damping_ns_per_m``)."""
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return False
    return math.isfinite(number)


def ball_or_default(ball: Ball | None) -> tuple[Ball, list[str]]:
    """``ball``, or the default ball with its defaults."""
    return ball_from() if ball is None else (ball, [])


def hand_or_default(supports: Sequence[str], hand: Hand | None) -> tuple[Hand | None, list[str]]:
    """``hand`` for the ``hand`` support (default :class:`Hand` if None); None without it."""
    if "hand" not in supports:
        return None, []
    return hand_for(supports) if hand is None else (hand, [])


def supports_named(supports: str | Sequence[str], allowed: Sequence[str]) -> list[str]:
    """A step's supports as Python or the command line gives them: a sequence of names, or
    one text of comma-separated names (``"free,hand"``, as the options objects take it), each
    of ``allowed``, each once; else InputError naming `supports`."""
    words = require_words("`supports`", supports)
    every = tuple(SUPPORT_NAMES)  # every support some step takes
    for word in words:
        if word not in every:  # a misspelt name: say every support, and which this step takes
            others = [s for s in every if s not in allowed]
            more = f" ({', '.join(others)} where the step takes it)" if others else ""
            raise InputError(f"`supports` must be one of {', '.join(allowed)}{more} (got {word!r})")
    checked = [one_of("`supports`", word, allowed) for word in words]
    if len(set(checked)) != len(checked):
        raise InputError(f"`supports`: name each support once (got {','.join(words)})")
    return checked


def single_support(step: str, support: str | Sequence[str], why: str) -> str:
    """The one support of a step that takes one, or why it takes one (issue 27: ``swing
    --support free,pinned`` said "must be one of free, pinned").

    Parameters
    ----------
    step : str
        The step, for the message (``swing``).
    support : str or sequence of str
        The support given; several (a sequence, or a comma-separated text) are refused.
    why : str
        Why the step takes one (what of it is one support's).
    """
    given = (
        [s.strip() for s in support.split(",")]
        if isinstance(support, str)
        else [str(s) for s in support]
    )
    if len(given) != 1:
        raise InputError(
            f"`support` {','.join(given)}: {step} takes one support ({why}); run it once per "
            "support, each into its own `out`"
        )
    return given[0]
