"""Off-centre and oblique impacts (``racketdyn twist``, ``racketdyn oblique``)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from racketdyn._display import case_words
from racketdyn.plotting.registry import file_of
from racketdyn.report.folder import Row, RunFolder, number, read_csv, to_float
from racketdyn.report.formatting import fmt

HOW_TO_RUN = (
    "racketdyn twist --support free,hand --out DIR/twist; racketdyn oblique --out DIR/oblique"
)
HOW_TO_RUN_TWIST = "racketdyn twist --support free,hand --out DIR/twist"
HOW_TO_RUN_OBLIQUE = "racketdyn oblique --out DIR/oblique"


def gather(run: RunFolder) -> dict[str, Any] | None:
    """``twist.csv`` (roll against the offset, per support) and ``oblique.csv`` (outgoing angle
    and spin against the incoming angle) with their figures; either is enough."""
    twist = run.first("twist.csv")
    oblique = run.first("oblique.csv")
    if twist is None and oblique is None:
        return None
    glance: list[str] = []
    data: dict[str, Any] = {
        "twist": None if twist is None else _twist(run, twist, glance),
        "oblique": None if oblique is None else _oblique(run, oblique, glance),
        "run_twist": HOW_TO_RUN_TWIST,
        "run_oblique": HOW_TO_RUN_OBLIQUE,
        "glance": glance,
    }
    return data


def _twist(run: RunFolder, folder: Path, glance: list[str]) -> dict[str, Any]:
    rows = read_csv(folder / "twist.csv", ("support", "y_m", "roll_angle_rad"))
    body = []
    for support in dict.fromkeys(r.get("support", "") for r in rows):
        mine = [r for r in rows if r.get("support", "") == support]
        y = np.array([number(r, "y_m") for r in mine])
        roll = np.array([number(r, "roll_angle_rad") for r in mine])
        flexible = np.array([number(r, "flexible_twist_rad") for r in mine])
        speed = np.array([number(r, "rebound_speed_mps") for r in mine])
        if not mine or not np.any(np.isfinite(roll)):
            continue
        valid = [i for i in range(len(mine)) if math.isfinite(roll[i])]
        far = max(valid, key=lambda i: (abs(y[i]), y[i]))  # the +y side on a tie
        near = min(valid, key=lambda i: abs(y[i]))
        share = float(np.nanmax(np.abs(flexible)) / max(float(np.nanmax(np.abs(roll))), 1e-300))
        body.append(
            (
                support,
                fmt(y[far] * 1e3, ".0f"),
                fmt(math.degrees(roll[far]), ".2f"),
                fmt(speed[near], ".2f"),
                fmt(speed[far], ".2f"),
                fmt(100 * share, ".2g"),
            )
        )
        glance.append(
            f"off-axis impact, {support}, x = {number(mine[far], 'x_m') * 1e3:.0f} mm, "
            f"ball {fmt(number(mine[far], 'ball_speed_mps'), 'g')} m/s: "
            f"{y[far] * 1e3:.0f} mm off the axis the racket rolls "
            f"{math.degrees(roll[far]):.1f}° and the ball leaves at {speed[far]:.1f} m/s "
            f"({speed[near]:.1f} m/s on the axis)"
        )
    return {"figure": run.group([(folder / file_of("twist"), "")]), "rows": body}


def _oblique(run: RunFolder, folder: Path, glance: list[str]) -> dict[str, Any]:
    record = run.record(folder)
    contact = record.get("tangential_contact")
    settings = None
    if isinstance(contact, dict):
        settings = {
            "mu": fmt(contact.get("friction_coefficient"), "g"),
            "k_t": fmt(contact.get("stiffness_n_per_m"), ".3g"),
            "half_period": fmt(to_float(str(contact.get("grip_period_s"))) * 0.5e3, ".2f"),
            "speed": case_words(*_speeds(record)),
            "point": ", ".join(fmt(v * 1e3, ".0f") for v in record.get("point_m", [])),
            "support": str(record.get("support", "?")),
        }
    rows = read_csv(folder / "oblique.csv", ("incoming_angle_deg", "outgoing_angle_deg"))
    usable = [r for r in rows if r.get("status") == "ok"]
    if usable:
        shown = min(usable, key=lambda r: abs(abs(number(r, "incoming_angle_deg")) - 30))
        ball, racket = _speeds(record, shown)
        glance.append(
            f"oblique impact at {number(shown, 'incoming_angle_deg'):g}°, "
            f"{case_words(ball, racket, str(record.get('support', '?')))}: "
            f"leaves at {number(shown, 'outgoing_angle_deg'):.1f}° with "
            f"{number(shown, 'outgoing_spin_radps'):.0f} rad/s of spin (a lossless grip: "
            "the upper end of the model's range; the spin depends strongly on the tangential "
            "stiffness k_t)"
        )
    angle_rows = [
        (
            fmt(number(r, "incoming_angle_deg"), "g"),
            fmt(number(r, "incoming_spin_radps"), "g"),
            fmt(number(r, "outgoing_angle_deg"), ".1f"),
            fmt(number(r, "outgoing_spin_radps"), ".0f"),
            fmt(number(r, "normal_speed_mps"), ".2f"),
            fmt(number(r, "tangential_speed_mps"), ".2f"),
            "yes" if r.get("gripped") == "True" else "no",
            r.get("status", ""),
        )
        for r in rows
    ]
    return {
        "settings": settings,
        "figure": run.group([(folder / file_of("oblique"), "")]),
        "rows": angle_rows,
    }


def _speeds(record: dict[str, Any], row: Row | None = None) -> tuple[float, float]:
    """The ball's and the racket's speeds (m/s) of an oblique run: a row of oblique.csv's,
    else its run.json's (a racket at rest when neither says: a run of an earlier version)."""
    ball = number(row, "ball_speed_mps") if row is not None else math.nan
    racket = number(row, "racket_speed_mps") if row is not None else math.nan
    if not math.isfinite(ball):
        ball = to_float(str(record.get("ball_speed_mps", "")))
    if not math.isfinite(racket):
        racket = to_float(str(record.get("racket_speed_mps", "")))
    return ball, racket if math.isfinite(racket) else 0.0
