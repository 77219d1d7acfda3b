"""``racketdyn identify`` and ``racketdyn compare``: modal models from FRFs."""

from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt
from racketdyn.cli.frf import add_geometry

if TYPE_CHECKING:
    from rich.console import Console

    from racketdyn.measurement.records import FrfSet
    from racketdyn.modal.identify import Identification
    from racketdyn.workflows.identify import IdentifyOptions


def _add_options(p: argparse.ArgumentParser) -> None:
    add_geometry(p)
    opt.add_racket(
        p,
        " for the head (names the modes; without it the modes are named only when the points "
        "lie on the built-in racket's outline)",
    )
    p.add_argument(
        "--band",
        metavar="LOW,HIGH",
        help="frequency band low,high, Hz (default from 40 Hz, or an octave below the data's "
        "first clear peak where that lies below 40 Hz, to the FRFs' bandwidth: the last "
        "line of an exported file, fs/2.56 of FRFs racketdyn estimated)",
    )
    p.add_argument(
        "--max-order",
        type=int,
        help="highest model order of the stabilisation diagram, a count (default 60; 30 with "
        "several references)",
    )
    p.add_argument(
        "--pin", help="force modes in, by approximate frequency, Hz: 120,330 (default: none)"
    )
    p.add_argument(
        "--exclude", help="leave modes out, by approximate frequency, Hz (default: none)"
    )
    p.add_argument(
        "--reference",
        metavar="NODE",
        help="reference node, a node number (dimensionless), when the file has FRFs against "
        "several; 'all' or nodes separated by commas (201,203) identify from those "
        "references together, a poly-reference LSCF that tells apart close modes the "
        "references see differently (default: the one node every FRF shares, else the one "
        "reaching the most points)",
    )
    p.add_argument(
        "--ball-at",
        metavar="X,Y",
        help="a ball was fixed on the strings at x,y, m, during the test (the paper's compound "
        "test, Figs 8-9, racketdyn rig --ball-at): its mode is named 'ball on the strings' "
        "(default: no ball)",
    )
    opt.add_out(p)


def add(commands: Any) -> None:
    """Register both commands."""
    p = opt.command(
        commands,
        "identify",
        "modal model from FRFs (modes.csv, UFF 55, JSON)",
        "LSCF poles, automatic selection, LSFD mass-normalised shapes: modes.csv, "
        "modal_model.json (what predict --modal takes), modes.uff, fit_quality.csv, figures, "
        "run.json",
    )
    p.add_argument(
        "frfs",
        help="FRFs: UFF 58 (function type 4), e.g. racketdyn frf's frfs.uff, or an FRF table "
        "(CSV: file,node,x_m,y_m,z_m,direction) of FRFs exported one text file per point",
    )
    opt.add_support(p, "free", "support of the test: free or hand", choices=("free", "hand"))
    _add_options(p)
    p.add_argument(
        "--names-from",
        metavar="FILE",
        help="a modal-model JSON of the same racket (the free test's modal_model.json for a "
        "hand-held test): each mode takes the name of its MAC pair of the same kind there, as "
        "compare names the hand-held modes (default: names from the shapes alone)",
    )
    p.set_defaults(handler=run_identify)

    p = opt.command(
        commands,
        "compare",
        "identify free and hand-held FRFs (or alone and with a ball) and compare",
        "Both identifications, modes paired by MAC (comparison.csv) and the paper's Fig. 15 "
        "check with the identified models at the ball speed --speed.  With --ball-at: the "
        "racket alone against the racket with a ball fixed on its strings (paper, Figs 9a and "
        "9b): ball_comparison.csv with the ball's new mode and the frame modes' shifts, and "
        "the two FRFs (fig9_frf_alone_and_ball.png)",
    )
    p.add_argument(
        "free",
        help="FRFs of the freely supported racket (UFF 58); with --ball-at, of the racket alone",
    )
    p.add_argument(
        "hand",
        help="FRFs of the hand-held racket (UFF 58); with --ball-at, of the racket with the ball",
    )
    _add_options(p)
    p.add_argument(
        "--support",
        choices=("free", "hand"),
        help="with --ball-at: support of both tests, free or hand (default free)",
    )
    opt.add_speed(p, "20", many=False)
    opt.add_ball(p)
    opt.add_allow_implausible(p)
    p.set_defaults(handler=run_compare)


_LOWEST_BAND_TOP_HZ = 10.0
"""A band ending below this holds no mode of any racket or its hand (new-user trial of
2026-11-26, second session: ``--band 0.04,0.85`` in kHz said only "no frequency line")."""


def _options(args: argparse.Namespace) -> tuple[IdentifyOptions, tuple[float, float] | None]:
    """The identification's options from the command line (one place), and ``--ball-at``."""
    from racketdyn.workflows.identify import IdentifyOptions, checked_band

    # checked_band's words name `band_hz`, which the CLI says as --band
    band = None if args.band is None else checked_band(opt.parse_frequencies("--band", args.band))
    if band is not None and band[1] < _LOWEST_BAND_TOP_HZ:
        from racketdyn.errors import InputError

        raise InputError(
            f"--band {args.band}: a racket's modes lie at 80 Hz and above, and the band ends "
            f"at {band[1]:g} Hz; did you give kHz ({band[0]:g}–{band[1]:g} kHz = "
            f"{band[0] * 1e3:g}–{band[1] * 1e3:g} Hz)? (give Hz)"
        )
    options = IdentifyOptions(
        geometry=args.geometry,
        band_hz=band,
        max_order=args.max_order,
        pin_hz=() if args.pin is None else opt.parse_frequencies("--pin", args.pin),
        exclude_hz=() if args.exclude is None else opt.parse_frequencies("--exclude", args.exclude),
        reference=args.reference,
    )
    return options, opt.parse_point("--ball-at", args.ball_at)


def references_note(console: Console, identification: Identification) -> None:
    """One line saying which references the poles came from, when there were several."""
    references = identification.references
    if len(references) > 1:
        opt.say(
            console,
            f"references {', '.join(map(str, references))} together (poly-reference LSCF); "
            f"shapes from reference {references[0]}",
        )


def unused_note(console: Console, frfs: FrfSet, references: tuple[int, ...] = ()) -> None:
    """One line naming the file's data sets 58 that were not used, by why (nothing dropped
    silently: a damaged header can turn an FRF into another function type or another node's)."""
    meta = frfs.metadata
    ignored = meta.get("ignored_data_sets") or []
    unused = meta.get("unused_data_sets") or []
    parts = []
    if ignored:
        parts.append(
            f"{opt.noun(len(ignored), 'data set')} {_listed(ignored)} of another function type "
            "than FRF (4) or coherence (6)"
        )
    against = (
        f"references {', '.join(map(str, references))}"
        if len(references) > 1
        else f"reference node {frfs.reference_node}"
    )
    if "not_against_reference" not in meta:  # an FRF set built before the reasons were kept
        if unused:
            parts.append(
                f"{opt.noun(len(unused), 'data set')} {_listed(unused)} not against {against}, "
                "in another direction or a reciprocal pair's second"
            )
    else:
        parts += _unused_by_kind(meta, against)
    if parts:
        opt.say(console, "not used from the file: " + "; ".join(parts), "dim")


def _unused_by_kind(meta: dict[str, Any], against: str) -> list[str]:
    """The left-out data sets by why: not against the reference, another direction (its
    points named), a reciprocal pair's second."""
    parts = []
    other = meta.get("not_against_reference") or []
    if other:
        parts.append(f"{opt.noun(len(other), 'data set')} {_listed(other)} not against {against}")
    turned = meta.get("other_direction")
    if turned:
        nodes = turned["nodes"]
        parts.append(
            f"{opt.plural(len(nodes), 'point')} struck along {turned['direction']} (nodes "
            f"{_listed(nodes)}) while the others are along {turned['usual']}: left out, a mode "
            f"shape here has one direction (data sets {_listed(turned['data_sets'])})"
        )
    second = meta.get("reciprocal_second") or []
    if second:
        parts.append(
            f"{opt.noun(len(second), 'data set')} {_listed(second)}: a reciprocal pair's second "
            "(the one with the sensor at the reference kept)"
        )
    return parts


def _listed(numbers: list[int]) -> str:
    return ", ".join(map(str, numbers[:8])) + (
        f" … ({len(numbers)} in all)" if len(numbers) > 8 else ""
    )


def print_modes(
    console: Console, identification: Identification, parser: argparse.ArgumentParser
) -> None:
    """The identified modes as a table, with the fit quality and the modes dropped (the
    library's words for its parameters said as the command's options)."""
    import numpy as np
    from rich.table import Table

    from racketdyn.modal.identify import NO_FORCE, no_force_words

    model = identification.model
    # the support is a racket test's word (free or hand); a beam or a wing is supported as
    # its lab says, which the file does not
    numbered = str(model.metadata.get("naming", "")).startswith("modes numbered")
    support = "" if numbered else f" ({model.support})"
    table = Table(
        title=opt.plain(
            f"{opt.plural(model.n_modes, 'mode')}{support}, "
            f"{identification.band_hz[0]:g}–{identification.band_hz[1]:g} Hz"
        )
    )
    for column in ("mode", "frequency (Hz)", "damping (%)", "name", "orders stable"):
        table.add_column(column)
    orders = identification.selected.orders_stable()
    at_peak = identification.selected.flags("at_peak")
    for k in range(model.n_modes):
        table.add_row(
            str(k + 1),
            f"{model.frequency[k]:.2f}",
            f"{100 * model.damping_ratio[k]:.3f}",
            opt.plain(model.names[k]),
            "pinned at peak" if at_peak[k] else "pair fit" if orders[k] is None else str(orders[k]),
        )
    console.print(table)
    note = identification.band_note
    band = f"{identification.band_hz[0]:g}–{identification.band_hz[1]:g} Hz"
    given = note == "given"
    opt.say(
        console, f"band {band}: " + ("as given (--band)" if given else opt.in_flags(note, parser))
    )
    force = identification.frfs.force_band_hz
    if given and force is not None and identification.band_hz[1] > force:
        opt.say(
            console,
            f"{no_force_words(force)}: peaks above it are the response's noise over almost no "
            "force (a harder hammer tip puts force there)",
            "yellow",
        )
    if orders_note := model.metadata.get("orders_note"):
        opt.say(console, opt.in_flags(orders_note, parser), "yellow")
    if peaks_note := model.metadata.get("peaks_note"):
        opt.say(console, opt.in_flags(peaks_note, parser), "yellow")
    where = identification.misfit
    fit_line = (
        f"median fit error {np.median(identification.fit.error):.2%}"
        if where is None
        else opt.in_flags(where.sentence(), parser)
    )
    condition = f"design matrix condition {identification.fit.condition_number:.3g}"
    opt.say(console, f"{fit_line}; {condition}")
    others = identification.frfs.metadata.get("not_against_reference")
    if (
        where is not None
        and where.cause == "poles"
        and others
        and len(identification.references) < 2
    ):
        opt.say(
            console,
            "the file holds FRFs against other references too (data sets "
            f"{_listed(list(others))}): --reference all fits them together, which parts modes "
            "one reference sees as one",
            "yellow",
        )
    noise = identification.noise_frfs
    if noise is not None and noise.noise_nodes:
        opt.say(console, noise.sentence(), "yellow")
    narrow = identification.half_power_lines < 1.0
    if narrow.any():
        spacing = float(np.median(np.diff(identification.frfs.frequency)))
        at = ", ".join(f"{f:.1f}" for f in model.frequency[narrow])
        opt.say(
            console,
            f"damping at {at} Hz: the half-power width 2ζf is under one line ({spacing:.3g} Hz), "
            "so the lines do not resolve it; the fit's value, for a longer record to confirm",
            "yellow",
        )
    for line in model.metadata.get("kept", []):
        opt.say(console, f"kept {line}")
    said = ("constants", "edge", "merged", "unsettled", "line")  # the rest: noise's candidates
    later = [d for d in identification.dropped_modes if d.stage in said]
    for row in later:
        opt.say(console, f"left out {row.frequency_hz:.2f} Hz: {opt.in_flags(row.reason, parser)}")
    unforced = [d.frequency_hz for d in identification.dropped_modes if d.stage == NO_FORCE]
    if unforced:
        opt.say(
            console,
            f"left out {opt.plural(len(unforced), 'clear peak')} at {min(unforced):.6g}–"
            f"{max(unforced):.6g} Hz: {no_force_words(force or 0.0)}, so they are the "
            "response's noise over almost none, not modes (each in dropped_modes.csv)",
        )
        later += [d for d in identification.dropped_modes if d.stage == NO_FORCE]
    candidates = len(identification.dropped_modes) - len(later)
    if candidates:
        opt.say(
            console,
            f"{opt.plural(candidates, 'candidate pole')} not taken as "
            f"{'a mode' if candidates == 1 else 'modes'}; each with its reason in "
            "dropped_modes.csv",
            "dim",
        )
    conjugated = identification.frfs.metadata.get("conjugated")
    if conjugated:
        opt.say(
            console,
            f"FRFs conjugated: their {conjugated}, the conjugate convention e^(-iωt) of some "
            "analysers (identification assumes e^(iωt))",
        )
    if identification.scaling_note:
        opt.say(console, f"shapes: {identification.scaling_note}")
    if not model.has_locations:
        from racketdyn.workflows.identify import coordinates_note

        opt.say(console, opt.in_flags(coordinates_note(model), parser), "bold")
    naming = model.metadata.get("naming")
    if naming:
        opt.say(console, opt.in_flags(naming, parser), "dim")


def run_identify(args: argparse.Namespace, console: Console) -> int:
    """Run ``identify``."""
    # six figures: the helper imports matplotlib while we import the library and identify
    opt.start_figure_helper(args)
    from racketdyn.plotting.steps import identify_figures
    from racketdyn.workflows.identify import run_identify as identify

    options, ball_at = _options(args)
    with opt.progress_display(console) as progress:
        result = identify(
            args.frfs,
            args.out,
            opt.setup_from_args(args, figures=identify_figures, progress=progress),
            options,
            support=args.support,
            ball_at=ball_at,
            names_from=args.names_from,
        )
    assert result.identification is not None
    references_note(console, result.identification)
    unused_note(console, result.identification.frfs, result.identification.references)
    print_modes(console, result.identification, args.parser)
    opt.print_written(console, result.written)
    return 0


def run_compare(args: argparse.Namespace, console: Console) -> int:
    """Run ``compare``."""
    from racketdyn.errors import InputError
    from racketdyn.plotting.steps import compare_figures
    from racketdyn.workflows.identify import run_compare as compare

    options, ball_at = _options(args)
    ball_options = ("ball_mass", "e_bg", "e_bg_table", "ball_law")
    if ball_at is not None:
        given = [name for name in ball_options if getattr(args, name) is not None]
        if given:
            flags = ", ".join("--" + name.replace("_", "-") for name in given)
            raise InputError(
                f"{flags}: the ball of the Fig. 15 check of free against hand-held; with "
                "--ball-at there is no Fig. 15 check"
            )
        return _run_compare_ball(args, console, ball_at, options)
    if args.support is not None:
        raise InputError(
            "--support: compare takes the support from its two files (free, hand); --support "
            "is for --ball-at (both tests on one support)"
        )
    with opt.progress_display(console) as progress:
        result = compare(
            args.free,
            args.hand,
            args.out,
            opt.setup_from_args(args, figures=compare_figures, progress=progress),
            options,
            speed=opt.one_number("--speed", args.speed),
        )
    assert result.free is not None
    assert result.hand is not None
    print_modes(console, result.free, args.parser)
    print_modes(console, result.hand, args.parser)
    comparison = result.comparison
    if comparison is not None:
        for row in comparison.rows:
            if row["note"]:
                free_hz = row["frequency_free_hz"]
                support, frequency = (
                    ("hand", row["frequency_hand_hz"]) if math.isnan(free_hz) else ("free", free_hz)
                )
                opt.say(console, f"{row['mode']} ({support}, {frequency:.1f} Hz): {row['note']}")
                continue
            opt.say(
                console,
                f"{row['mode']}: {row['frequency_free_hz']:.1f} → {row['frequency_hand_hz']:.1f} "
                f"Hz ({row['frequency_shift_percent']:+.1f} %), damping "
                f"×{row['damping_ratio_hand_over_free']:.1f}, MAC {row['mac']:.3f}",
            )
        nodes = "; ".join(
            f"{label} {', '.join(f'{x * 1e3:.0f}' for x in found)} mm"
            for label, found in (("free", comparison.nodes_free), ("hand", comparison.nodes_hand))
            if len(found)
        )
        if nodes:
            opt.say(console, f"first mode's nodes on the axis: {nodes}")
    if result.not_a_racket:
        opt.say(console, f"compare: {result.not_a_racket}")
    opt.print_written(console, result.written)
    return 0


def _run_compare_ball(
    args: argparse.Namespace,
    console: Console,
    ball_at: tuple[float, float],
    options: IdentifyOptions,
) -> int:
    """``compare --ball-at``: the racket alone against the racket with a ball (Figs 9a, 9b)."""
    import math

    from racketdyn.plotting.steps import compare_ball_figures
    from racketdyn.workflows.identify import run_compare_ball

    with opt.progress_display(console) as progress:
        result = run_compare_ball(
            args.free,
            args.hand,
            args.out,
            opt.setup_from_args(args, figures=compare_ball_figures, progress=progress),
            options,
            ball_at=ball_at,
            support=args.support or "free",
        )
    assert result.alone is not None
    assert result.with_ball is not None
    print_modes(console, result.alone, args.parser)
    print_modes(console, result.with_ball, args.parser)
    ball = [r for r in result.rows if math.isnan(r["frequency_alone_hz"])]
    frame = [r for r in result.rows if math.isfinite(r["frequency_shift_percent"])]
    if ball:
        opt.say(
            console,
            f"new with the ball: {ball[0]['mode']} at {ball[0]['frequency_ball_hz']:.1f} Hz "
            f"(ζ = {100 * ball[0]['damping_ball']:.1f} %)",
        )
    else:
        opt.say(console, "no mode of the ball on the strings identified (see the naming above)")
    if frame:
        worst = max(frame, key=lambda r: abs(r["frequency_shift_percent"]))
        opt.say(
            console,
            f"racket modes with the ball: {len(frame)} paired by MAC, the largest shift "
            f"{worst['frequency_shift_percent']:+.1f} % ({worst['mode']})",
        )
    opt.print_written(console, result.written)
    return 0
