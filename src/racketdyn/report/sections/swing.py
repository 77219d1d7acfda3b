"""The swinging racket (``racketdyn swing``): outgoing ball speed and sweet spots."""

from __future__ import annotations

import math
from typing import Any

from racketdyn.plotting.registry import in_section
from racketdyn.report.folder import RunFolder, number, read_csv
from racketdyn.report.formatting import finite, fmt

HOW_TO_RUN = "racketdyn swing --out DIR/swing"


def _scaled(value: Any, factor: float, spec: str) -> str:
    """A run.json number in the page's unit (``factor`` times its SI value); a dash if none."""
    return fmt(value * factor if finite(value) else None, spec)


def gather(run: RunFolder) -> dict[str, Any] | None:
    """The swing's settings (run.json), its figures, and ``sweet_spots.csv``."""
    folder = run.first("swing.csv") or run.first("sweet_spots.csv")
    if folder is None:
        return None
    record = run.record(folder)
    swing = record.get("swing")
    if not isinstance(swing, dict):
        swing = {}
    omega = swing.get("angular_speed_radps", record.get("angular_speed_radps"))
    facts = []
    if "torque_nm" in swing:
        facts.append(f"shoulder torque {fmt(swing.get('torque_nm'), 'g')} N·m")
        angle = swing.get("swing_angle_rad")
        if isinstance(angle, int | float):
            facts.append(f"swing angle {math.degrees(angle):.0f}°")
        facts.append(
            f"arm {_scaled(swing.get('arm_mass_kg'), 1e3, '.0f')} g, "
            f"{_scaled(swing.get('arm_inertia_kgm2'), 1e4, '.0f')} kg·cm² about the shoulder"
        )
    if isinstance(swing.get("axis_to_butt_m"), int | float):
        facts.append(f"shoulder {swing['axis_to_butt_m'] * 1e3:.0f} mm behind the butt")
    if isinstance(swing.get("inertia_about_axis_kgm2"), int | float):
        facts.append(f"arm + racket {swing['inertia_about_axis_kgm2'] * 1e4:.0f} kg·cm² about it")
    if isinstance(omega, int | float):
        facts.append(f"Ω = {omega:.2f} rad/s")
    model = record.get("impact_model")
    support = record.get("support")
    if model or support:
        facts.append(f"{model or '?'} impact model, {support or '?'}")
    figures = run.group([(folder / figure.file, "") for figure in in_section("swing")], "stack")
    rows = (
        read_csv(folder / "sweet_spots.csv", ("key", "x_m", "value"))
        if (folder / "sweet_spots.csv").is_file()
        else []
    )
    speed = record.get("sweet_spots_at_mps")
    heading = "Sweet spots" + (
        f", ball {fmt(speed, 'g')} m/s" if isinstance(speed, int | float) else ""
    )
    body = []
    for row in rows:
        value = number(row, "value")
        key = row.get("key", "")
        shown = (
            "–"
            if not math.isfinite(value)
            else f"{value:.1f} m/s"
            if key == "max_rebound_speed"
            else f"{value:.3f}"
        )
        body.append(
            (
                row.get("name", key),
                fmt(number(row, "x_m") * 1e3, ".0f"),
                "yes" if row.get("on_face") == "True" else "no",
                fmt(number(row, "racket_speed_mps"), ".1f"),
                fmt(number(row, "rebound_speed_mps"), ".1f"),
                shown,
                row.get("definition", ""),
            )
        )
    glance = []
    spots = {row.get("key", ""): row for row in rows}
    best = spots.get("max_rebound_speed")
    if best is not None and math.isfinite(number(best, "value")):
        text = (
            f"swinging racket (Ω = {fmt(omega, '.1f')} rad/s"
            + (f", ball {fmt(speed, 'g')} m/s" if isinstance(speed, int | float) else "")
            + f", {support or '?'}): largest outgoing speed {number(best, 'value'):.1f}"
            f" m/s at x = {number(best, 'x_m') * 1e3:.0f} mm"
        )
        for key, label in (
            ("centre_of_percussion_grip", "centre of percussion (grip)"),
            ("first_mode_node", "first-mode node"),
        ):
            if key in spots:
                text += f"; {label} {number(spots[key], 'x_m') * 1e3:.0f} mm"
        glance.append(text)
    return {
        "facts": "; ".join(facts),
        "figures": figures,
        "heading": heading,
        "spots": body,
        "glance": glance,
    }
