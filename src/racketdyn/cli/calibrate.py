"""``racketdyn calibrate``: uncertain inputs fitted to measured rebound (issue 15)."""

from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt
from racketdyn.cli.validate import add_measured, hand_supports

if TYPE_CHECKING:
    from rich.console import Console

# racketdyn.impact.calibration.PARAMETERS (checked by tests/test_calibration.py)
PARAMETER_NAMES = (
    "e_bg",
    "string_stiffness_scale",
    "roll_inertia_kgm2",
    "frame_damping_scale",
    "first_bending_hz",
    "ball_stiffness_scale",
    "hand_stiffness_n_per_m",
    "hand_damping_ns_per_m",
    "hand_arm_mass_kg",
)


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "calibrate",
        "fit uncertain inputs (e_BG, string bed, roll inertia, damping, hand) to measured rebound",
        "Bounded weighted least squares of the named parameters against measured rebound "
        "ratios: calibration.json (values, standard errors, correlation, parameters the data "
        "cannot tell apart, fit / held-out / leave-one-out RMS), calibration_rows.csv, the "
        "calibrated racket.toml, run.json",
    )
    add_measured(p)
    p.add_argument(
        "--fit",
        required=True,
        metavar="NAME,NAME",
        help=f"parameters to fit, comma-separated: {', '.join(PARAMETER_NAMES)}; required",
    )
    p.add_argument(
        "--holdout",
        metavar="ROWS",
        help="rows of MEASURED.csv held out of the fit and predicted after it, numbered from 1 "
        "(first data row), a count, e.g. 3,7 (default: none)",
    )
    p.add_argument(
        "--model",
        choices=opt.IMPACT_MODELS,
        default="transient",
        help="the model fitted: transient (default; the hand support and the damping need it) "
        "or approx",
    )
    p.add_argument(
        "--no-loo",
        action="store_true",
        help="skip leave-one-out cross-validation (one refit per row) (default: run it)",
    )
    opt.add_uncertainty(p, sampled=False)
    opt.add_no_figures(p, "calibration.json, calibration_rows.csv")
    opt.add_out(p)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command."""
    from rich.table import Table

    from racketdyn.errors import InputError
    from racketdyn.impact.measured import OUTLIER_LIMIT, outlier_labels
    from racketdyn.plotting.steps import calibrate_figures
    from racketdyn.workflows.calibrate import run_calibrate

    holdout = []
    if args.holdout:
        for item in opt.parse_list("--holdout", args.holdout):
            if not item.isdigit():
                raise InputError(f"--holdout: {item!r} is not a row number (1, 2, …)")
            holdout.append(int(item))
    with opt.progress_display(console, lines=True) as progress:
        result = run_calibrate(
            args.out,
            args.measured,
            opt.parse_list("--fit", args.fit),
            opt.setup_from_args(
                args, hand_supports(args), figures=calibrate_figures, progress=progress
            ),
            holdout=holdout,
            method=args.model,
            leave_one_out=not args.no_loo,
            engine=args.engine,
            uncertainty=opt.uncertainty_from(args),
        )
    cal = result.calibration
    assert cal is not None
    table = Table(
        title=opt.plain(
            f"calibration ({cal.method}, {opt.plural(cal.n_fit, 'row')} fitted) → {result.out}"
        )
    )
    # the name a user types into --fit is never cut, a row is one line: the status cell says
    # one phrase and the reasons follow the table (80 columns, issue 27)
    table.add_column("parameter", justify="left", no_wrap=True)
    for column in ("start", "fitted", "std. error"):
        table.add_column(column, justify="right", no_wrap=True)
    table.add_column("status", justify="left", no_wrap=True)
    poor = cal.poor_fit
    reasons = []
    for k, name in enumerate(cal.names):
        ok = cal.identifiable[k]
        table.add_row(
            opt.plain(name),
            f"{cal.start[k]:.5g}",
            f"{cal.value[k]:.5g}" if ok else "–",
            f"{cal.standard_error[k]:.3g}" if ok else "–",
            ("ok, poor fit" if poor else "ok") if ok else "not identifiable",
        )
        if not ok:
            reasons.append(f"{name}: not identifiable: {cal.why[k]}")
    console.print(table)
    for reason in reasons:
        opt.say(console, reason, "yellow")
    # only what was run: no "held out nan (0 rows)" (issue 27)
    parts = [f"fit {cal.fit_rms:.4f}"]
    if cal.n_holdout:
        parts.append(f"held out {cal.holdout_rms:.4f} ({opt.plural(cal.n_holdout, 'row')})")
    if math.isfinite(cal.loo_rms):
        parts.append(f"leave-one-out {cal.loo_rms:.4f}")
    opt.say(
        console,
        f"RMS of the rebound ratio: {', '.join(parts)}; {opt.plural(cal.n_flagged, 'row')} flagged",
    )
    named = outlier_labels(result.measured, result.standardised) if result.measured else ()
    if named:
        opt.say(
            console,
            f"{opt.plural(len(named), 'row')} beyond ±{OUTLIER_LIMIT:g} standard deviations "
            f"after: {', '.join(named)} (z_after in calibration_rows.csv)",
            "yellow",
        )
    if poor:
        opt.say(
            console,
            f"the fit is poor: {poor}; see calibration_rows.csv for the rows that miss",
            "yellow",
        )
    opt.print_written(console, result.written)
    return 0
