"""The ball on the strings (``racketdyn compound``; paper, section 3.2, Figs 8–9)."""

from __future__ import annotations

import math
from typing import Any

from racketdyn.impact.compound_band import PAPER_BALL_MODE_HZ
from racketdyn.plotting.registry import file_of, in_section
from racketdyn.racket_modal.shapes import BALL_MODE_NAME
from racketdyn.report.folder import Row, RunFolder, number, read_csv
from racketdyn.report.formatting import fmt

HOW_TO_RUN = "racketdyn compound --support free,hand --out DIR/compound"

_SPEEDS = (("contact_time_5_s", 5), ("contact_time_10_s", 10), ("contact_time_20_s", 20))


def gather(run: RunFolder) -> dict[str, Any] | None:
    """``compound.csv`` (the modes with the ball, the half period beside the contact times),
    its run.json (frame-mode shifts, the frame-stiffness check, the spring) and its figures."""
    folder = run.first("compound.csv")
    if folder is None:
        return None
    rows = read_csv(folder / "compound.csv", ("support", "mode", "frequency_hz"))
    record = run.record(folder)
    shifts = record.get("frame_mode_shifts")
    shifts = shifts if isinstance(shifts, dict) else {}
    paper = _papers_racket(record)
    modes, times, statements, glance = [], [], [], []
    for support in dict.fromkeys(r.get("support", "") for r in rows):
        mine = [r for r in rows if r.get("support", "") == support]
        alone = {
            str(s.get("mode")): s
            for s in shifts.get(support, [])
            if isinstance(s, dict) and "mode" in s
        }
        for r in mine:
            shift = alone.get(r.get("mode", ""), {})
            modes.append(
                (
                    support,
                    r.get("mode", ""),
                    fmt(number(r, "frequency_hz"), ".2f"),
                    fmt(100 * number(r, "damping_ratio"), ".2f"),
                    fmt(number(r, "ball_to_frame_ratio"), ".3f"),
                    fmt(shift.get("alone_hz"), ".2f") if shift else "new",
                    fmt(shift.get("shift_percent"), "+.2f") if shift else "–",
                )
            )
        ball = next((r for r in mine if math.isfinite(number(r, "half_period_s"))), None)
        if ball is None:
            continue
        half = number(ball, "half_period_s")
        cells = [support, fmt(number(ball, "frequency_hz"), ".1f"), fmt(half * 1e3, ".2f")]
        contacts = [number(ball, column) for column, _ in _SPEEDS]
        cells += [fmt(contact * 1e3, ".2f") for contact in contacts]
        times.append(tuple(cells))
        f_ball = number(ball, "frequency_hz")
        where = (
            f"the paper's new mode at {PAPER_BALL_MODE_HZ:g} Hz is here at {f_ball:.1f} Hz "
            f"({100 * (f_ball / PAPER_BALL_MODE_HZ - 1):+.0f} %)"
            if paper
            else f"the new mode, the ball's, is at {f_ball:.1f} Hz"
        )
        statements.append(f"{support}: {where}{_half_period_words(half, contacts)}.")
        statements.extend(_band_statement(support, record.get("ball_mode_band")))
        statements.extend(_hand_over_statement(support, record))
        frame = [
            abs(float(s["shift_percent"]))
            for s in alone.values()
            if isinstance(s.get("shift_percent"), int | float)
            and not str(s.get("mode", "")).startswith(("hand–arm", "rigid body"))
        ]
        if frame:
            statements.append(
                f"{support}: \u201cthe natural frequencies of the frame do not change\u201d "
                f"— the flexible modes move by {max(frame):.1f} % at most when the ball is "
                "added."
            )
        glance.append(
            f"ball on the strings, {support}: ball mode {f_ball:.1f} Hz"
            + (f" (paper {PAPER_BALL_MODE_HZ:g} Hz)" if paper else "")
            + f", half period {half * 1e3:.2f} ms against a contact time of "
            f"{number(ball, 'contact_time_10_s') * 1e3:.2f} ms at 10 m/s"
        )
    checks = []
    for check in record.get("frame_stiffness_check", []) or []:
        if not isinstance(check, dict):
            continue
        stiffer = [m for m in check.get("frame_modes", []) if isinstance(m, dict)]
        ratios = [f"{m.get('mode')} ×{fmt(m.get('ratio'), '.2f')}" for m in stiffer]
        change = check.get("ball_mode_change_percent")
        factor = fmt(check.get("frame_stiffness_factor"), "g")
        checks.append(
            (
                str(check.get("support", "")),
                factor,
                fmt(check.get("ball_mode_hz"), ".2f"),
                fmt(check.get("stiffer_ball_mode_hz"), ".2f"),
                fmt(change, "+.2f"),
                ", ".join(ratios),
            )
        )
        values = [float(m["ratio"]) for m in stiffer if isinstance(m.get("ratio"), int | float)]
        if isinstance(change, int | float) and values:
            # "not affected": the ball mode moves by under a tenth of the frame modes' rise
            holds = abs(change) < 10.0 * (min(values) - 1.0)
            statements.append(
                f"{check.get('support')}: with the frame {factor}× as stiff (same mass) the "
                f"frame modes rise ×{min(values):.2f}–×{max(values):.2f} while the ball mode "
                f"moves by {abs(change):.1f} %: the paper's “not affected by frame "
                f"rigidity” {'holds' if holds else 'does not hold here'}."
            )
    shown = [figure for figure in in_section("compound") if figure.step == "compound"]
    figures = [(folder / figure.file, "") for figure in shown]
    measured = run.first("ball_comparison.csv")
    identified = run.ball_identification
    if measured is not None:
        figures.append((measured / file_of("fig9_frf_alone_and_ball"), ""))
        statements += _measured(
            read_csv(measured / "ball_comparison.csv", ("mode",)), run.record(measured), record
        )
    elif identified is not None:
        statements += _identified(
            read_csv(identified / "modes.csv", ("frequency_hz", "name")),
            run.record(identified),
            record,
        )
    return {
        "spring": _spring(record),
        "point": ", ".join(fmt(v * 1e3, ".0f") for v in record.get("point_m", []) or []),
        "modes": modes,
        "times": times,
        "checks": checks,
        "statements": statements,
        "figures": run.group(figures),
        "glance": glance,
    }


def _measured(rows: list[Row], test: dict[str, Any], model: dict[str, Any]) -> list[str]:
    """Statements from ``compare --ball-at``'s ``ball_comparison.csv`` (measured Fig. 9): the
    new mode against the model's band of the small-amplitude inputs when the ball sat at the
    same point in the test (``test``: its run.json) and in the model (``model``: compound's)."""
    ball = [r for r in rows if not r.get("frequency_alone_hz") and r.get("frequency_ball_hz")]
    shifts = [
        abs(number(r, "frequency_shift_percent"))
        for r in rows
        if math.isfinite(number(r, "frequency_shift_percent"))
    ]
    if not ball:
        return ["measured (compare --ball-at): no mode of the ball on the strings identified."]
    words = _against_band(number(ball[0], "frequency_ball_hz"), "compare --ball-at", test, model)
    if shifts:
        words += (
            f"; the {len(shifts)} racket modes paired by MAC move by {max(shifts):.1f} % at most"
        )
    return [words + "."]


def _identified(rows: list[Row], test: dict[str, Any], model: dict[str, Any]) -> list[str]:
    """The statement from an ``identify --ball-at`` run's ``modes.csv`` (no ``compare
    --ball-at``): its mode named the ball on the strings against the model's band."""
    ball = [r for r in rows if r.get("name") == BALL_MODE_NAME]
    if not ball:
        return [
            f"measured (identify --ball-at): no mode named “{BALL_MODE_NAME}” among the modes "
            "identified."
        ]
    return [_against_band(number(ball[0], "frequency_hz"), "identify --ball-at", test, model) + "."]


def _against_band(
    f_measured: float, command: str, test: dict[str, Any], model: dict[str, Any]
) -> str:
    """The measured ball mode (Hz) of a ``command`` run, held against the model's band of the
    small-amplitude inputs when the ball sat at the same point in the test (``test``: its
    run.json) and in the model (``model``: compound's)."""
    words = f"measured ({command}): a new mode at {f_measured:.1f} Hz with the ball"
    support = str(test.get("support") or "free")
    band = (model.get("ball_mode_band") or {}).get(support)
    at, point = test.get("ball_at_m"), model.get("point_m")
    if isinstance(band, dict) and isinstance(at, list) and isinstance(point, list):
        low, high = (band.get("band_hz") or [math.nan, math.nan])[:2]
        nominal = number(band, "nominal_hz")
        if math.dist(at, point) <= _SAME_POINT_M:
            inside = "inside" if low <= f_measured <= high else "outside"
            words += (
                f", {inside} the band of the small-amplitude inputs ({fmt(low, '.0f')}–"
                f"{fmt(high, '.0f')} Hz, {support}) and "
                f"{100 * (f_measured / nominal - 1):+.0f} % from the model's {nominal:.1f} Hz"
            )
        else:
            words += (
                f" (not held against the model's band: the ball was at x, y = "
                f"{at[0] * 1e3:.0f}, {at[1] * 1e3:.0f} mm in the test and "
                f"{point[0] * 1e3:.0f}, {point[1] * 1e3:.0f} mm in the model)"
            )
    return words


_SAME_POINT_M = 0.005
"""A measured ball mode is held against the model's band when the test's ball sat within this
distance of the model's, m."""


def _half_period_words(half: float, contacts: list[float]) -> str:
    """The ball mode's half period (s) against the approximate method's contact times at
    5–20 m/s (s; eq 7): the differences themselves, at one decimal (the trial's page said
    "within 15 %" for 15.2 %)."""
    gaps = [100 * abs(t / half - 1.0) for t in contacts if math.isfinite(t)]
    if not gaps:
        return ""
    spread = f"{min(gaps):.1f}–{max(gaps):.1f}" if len(gaps) > 1 else f"{gaps[0]:.1f}"
    return (
        "; the approximate method's contact time at 5–20 m/s differs from its half period "
        f"({half * 1e3:.2f} ms) by {spread} %"
    )


def _papers_racket(record: dict[str, Any]) -> bool:
    """Whether the run's racket is the paper's (run.json ``ball_mode_band``'s
    ``paper_racket``; a run written before it was recorded is taken as the paper's, the only
    racket those runs compared with 103 Hz)."""
    bands = record.get("ball_mode_band")
    if not isinstance(bands, dict):
        return True
    return all(
        not isinstance(band, dict) or band.get("paper_racket", True) is not False
        for band in bands.values()
    )


def _spring(record: dict[str, Any]) -> dict[str, str] | None:
    spring = record.get("ball_spring")
    if not isinstance(spring, dict):
        return None
    return {
        "stiffness": fmt(_kilo(spring.get("stiffness")), ".2f"),
        "preload": fmt(spring.get("preload_n"), "g"),
        "damping": fmt(100 * float(spring.get("damping_ratio", math.nan)), ".1f"),
        "why": str(spring.get("why", "")),
    }


def _kilo(value: Any) -> float:
    return float(value) / 1e3 if isinstance(value, int | float) else math.nan


__all__ = ["HOW_TO_RUN", "gather"]


def _band_statement(support: str, bands: object) -> list[str]:
    """What the small-amplitude inputs' spread allows, and what the paper's mode would need."""
    band = bands.get(support) if isinstance(bands, dict) else None
    if not isinstance(band, dict):
        return []
    low, high = (band.get("band_hz") or [math.nan, math.nan])[:2]
    pieces = [p for p in band.get("intervals_hz") or [] if isinstance(p, list) and len(p) == 2]
    reach = (
        f"between {fmt(low, '.0f')} and {fmt(high, '.0f')} Hz"
        if len(pieces) < 2
        else " and ".join(f"{fmt(a, '.0f')}–{fmt(b, '.0f')}" for a, b in pieces)
        + " Hz, with a gap where the ball mode crosses a frame mode"
    )
    text = (
        f"{support}: the spread of the small-amplitude inputs (the ball's stiffness, the bed "
        f"under the ball, the ball's mass) puts the ball mode {reach}"
    )
    if band.get("paper_racket") is False:
        return [f"{text} ({band.get('paper_note') or 'the paper measured another racket'})."]
    inside = "holds" if band.get("paper_inside") else "does not hold"
    text += f", which {inside} the paper's {PAPER_BALL_MODE_HZ:g} Hz"
    bed = band.get("bed_for_paper")
    if isinstance(bed, dict) and bed.get("note"):
        text += f"; {bed['note']}"
    elif isinstance(bed, dict) and math.isfinite(number(bed, "bed_stiffness_n_per_m")):
        radius = number(bed, "patch_radius_m")
        text += (
            f"; with the nominal ball it needs the bed at "
            f"{number(bed, 'bed_stiffness_n_per_m') / 1e3:.0f} kN/m under it"
            + (
                f", the string net pushed over a patch {radius * 1e3:.0f} mm in radius"
                if math.isfinite(radius)
                else ""
            )
        )
    return [text + "."]


def _hand_over_statement(support: str, record: dict[str, Any]) -> list[str]:
    """Fig. 8c in words: which mode leads at the neck after the blow, and for how long."""
    hand_over = (record.get("neck_hand_over") or {}).get(support)
    if not isinstance(hand_over, dict):
        return []
    ratio, cycles = number(hand_over, "ball_to_two_node"), number(hand_over, "ball_cycles")
    if not math.isfinite(ratio) or math.isnan(cycles):
        return []
    hammer, point = record.get("hammer_point_m"), record.get("point_m")
    away = (
        f" {math.dist(hammer, point) * 1e3:.0f} mm from the ball"
        if isinstance(hammer, list) and isinstance(point, list)
        else ""
    )
    if ratio <= 1.0:
        lead = f"the 2-node mode leads from the start ({ratio:.2f}× as large a ball mode)"
    elif math.isinf(cycles):
        lead = (
            f"the ball mode leads ({ratio:.1f}× the 2-node mode's amplitude) throughout: it "
            "decays more slowly"
        )
    else:
        lead = (
            f"the ball mode leads ({ratio:.1f}× the 2-node mode's amplitude) and the 2-node "
            f"mode takes over after {cycles:.1f} ball cycles"
        )
    node = number(record.get("two_node_node_line_m") or {}, support)
    if ratio <= 1.0 and math.isfinite(node) and isinstance(point, list):
        lead += (
            f"; the 2-node mode's node line crosses the axis at x = {node * 1e3:.0f} mm, "
            f"{abs(node - point[0]) * 1e3:.0f} mm from the ball, and the ball mode leads with "
            "the ball and the blow near it"
        )
    return [
        f"{support}: at the neck, after a blow on the strings{away}, {lead} (the paper, "
        "Fig. 8c: the ball mode first, the 2-node mode after about two cycles)."
    ]
