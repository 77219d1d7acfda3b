"""``racketdyn sweep``: a design sweep — racket variants × points × speeds."""

from __future__ import annotations

import argparse
import logging
from typing import TYPE_CHECKING, Any

from racketdyn.cli import options as opt

if TYPE_CHECKING:
    from rich.console import Console

    from racketdyn.sweep import SweepSpec


def add(commands: Any) -> None:
    """Register the command."""
    p = opt.command(
        commands,
        "sweep",
        "a design sweep: racket variants × points × speeds (sweep.zarr, figures)",
        "A design sweep from a spec TOML (docs/sweep-file.md), its designs computed in tasks "
        "on the engine chosen: sweep.zarr, summary.csv, figures, run.json; Ctrl-C keeps the "
        "finished designs (exit 130) and the same command resumes",
    )
    p.add_argument("spec", help="sweep spec TOML (docs/sweep-file.md)")
    opt.add_out(p, "; run again to resume")
    engine = p.add_mutually_exclusive_group()
    engine.add_argument(
        "--serial",
        action="store_true",
        help="run in this process (default: this process for a small sweep, else two processes)",
    )
    engine.add_argument(
        "--workers",
        type=int,
        metavar="N",
        help="a local pool of N processes, a count (default: chosen by size)",
    )
    engine.add_argument(
        "--dask-local",
        type=int,
        metavar="N",
        help="a local Dask cluster of N worker processes, a count (default: none)",
    )
    engine.add_argument(
        "--scheduler",
        metavar="tcp://HOST:PORT",
        help="a running Dask scheduler to use (default: none)",
    )
    p.add_argument(
        "--shared-store",
        action="store_true",
        help="--out is on a path every Dask worker can write, the same path on each: the "
        "--scheduler cluster's workers write their own chunks of sweep.zarr (default: this "
        "process writes them from the results sent back; workers on this machine always write)",
    )
    p.add_argument(
        "--task-timeout",
        type=float,
        metavar="S",
        help="seconds a task may run before its worker is stopped and the task run again "
        "elsewhere, s (default: 10 × the longest task so far, at least 60 s)",
    )
    opt.add_uncertainty(p, workers=False, tables="the sweep spec")
    opt.add_no_figures(p, "sweep.zarr")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace, console: Console) -> int:
    """Run the command; Ctrl-C stops it with one line (what was kept, the command that resumes)
    and exit status 130."""
    import shlex

    try:
        return _run(args, console)
    except KeyboardInterrupt as interrupt:
        from racketdyn.sweep import SweepInterrupted

        resume = "racketdyn " + shlex.join(args.argv)
        if isinstance(interrupt, SweepInterrupted):
            kept = (  # counted now that every worker has stopped
                f"{interrupt.count_kept()} of {interrupt.total} designs kept in "
                f"{interrupt.parts_dir}"
            )
        else:
            kept = f"the finished designs are kept in {args.out}"
        console.print(f"interrupted: {kept}; resume with: {resume}", markup=False, soft_wrap=True)
        return 130


def _run(args: argparse.Namespace, console: Console) -> int:
    import importlib.util
    from pathlib import Path

    from racketdyn.errors import InputError
    from racketdyn.plotting.steps import sweep_figures
    from racketdyn.sweep import load_sweep_spec
    from racketdyn.sweep.executors import DASK_MISSING, check_local_workers
    from racketdyn.sweep.runner import SECONDS_PER_IMPACT
    from racketdyn.workflows.sweep import run_sweep_step

    if args.task_timeout is not None and not args.task_timeout > 0:
        raise InputError(
            f"--task-timeout must be a number of seconds above 0 (got {args.task_timeout})"
        )
    for option, count in (("--workers", args.workers), ("--dask-local", args.dask_local)):
        if count is not None:  # before anything starts or prints
            check_local_workers(option, count)
    if args.serial:
        engine, workers = "serial", None
    elif args.workers is not None:
        engine, workers = "process", args.workers
    elif args.dask_local is not None:
        engine, workers = "dask-local", args.dask_local
    elif args.scheduler is not None:
        engine, workers = "dask", None
    else:
        engine, workers = "auto", None
    if engine.startswith("dask") and importlib.util.find_spec("distributed") is None:
        option = "--dask-local" if engine == "dask-local" else "--scheduler"
        raise InputError(f"{option}: {DASK_MISSING} (or use --workers N)")
    spec = _with_uncertainty(load_sweep_spec(Path(args.spec)), args)
    sampled = (
        ""
        if spec.uncertainty is None
        else f", each with {spec.uncertainty.samples} samples of "
        f"{', '.join(x.name for x in spec.uncertainty.spreads)} ({spec.uncertainty_source})"
    )
    opt.say(
        console,
        f"{spec.name}: {len(spec.designs)} designs × {spec.impacts_per_design:,} impacts "
        f"= {spec.n_impacts:,} impacts{sampled} → {args.out}",
    )
    work_s = (
        len(spec.designs)
        * spec.work_per_design
        * SECONDS_PER_IMPACT.get(spec.method, max(SECONDS_PER_IMPACT.values()))
    )
    if engine in WORKERS_PAY_S and work_s < WORKERS_PAY_S[engine][0]:
        opt.say(
            console,
            f"about {work_s:.1f} s of work on one core: {WORKERS_PAY_S[engine][1]}; --serial is "
            "as fast or faster for a sweep this small",
            "yellow",
        )
    if engine.startswith("dask") and not args.verbose:
        import distributed  # noqa: F401  (importing it sets its loggers to INFO: quieten them)

        logging.getLogger("distributed").setLevel(logging.WARNING)
    # no refresh thread: a process pool forks its workers while this process runs one thread
    with opt.progress_display(console, thread=False) as progress:
        result = run_sweep_step(
            spec,
            args.out,
            opt.setup_from_args(args, figures=sweep_figures, progress=progress),
            engine=engine,  # type: ignore[arg-type]
            workers=workers,
            scheduler=args.scheduler,
            task_timeout=args.task_timeout,
            shared_store=args.shared_store,
        )
    record, out = result.record, result.out
    console.print(
        f"[bold]{record['impacts']:,}[/] impacts, {record['designs']} designs "
        f"({record['ran']} run, {record['resumed']} resumed) on {record['engine']} "
        f"in {record['wall_time_s']:.1f} s"
    )
    opt.say(console, f"  time: {_where_time_went(record)}")
    if spec.uncertainty is not None and result.dataset is not None:
        opt.say(console, _base_band(result.dataset))
    restarts = _restarts(record, args.task_timeout)
    if restarts:
        opt.say(console, restarts, "yellow")
    for text, count in record["status_counts"].items():
        if text not in ("ok", "task failed") and count:
            opt.say(
                console,
                f"{count:,} {opt.noun(count, 'impact')}: {text}; "
                f"{opt.noun(count, 'its result is', 'their results are')} NaN",
                "yellow",
            )
    for note in record.get("notes", []):  # a note names "[impacts] grid": text, not a style
        opt.say(console, note, "yellow")
    for failure in result.failed:
        opt.say(console, f"{failure['task_id']} failed: {failure['error']}", "red")
    opt.print_written(console, [out / name for name in record["outputs"]])
    if result.failed:
        opt.say(
            console,
            f"{len(result.failed)} of {opt.plural(record['designs'], 'design')} failed "
            "(NaN, status 3); "
            f"details in {out / 'failures.json'}; run the same command again to retry them",
            "red",
        )
        return 1
    return 0


def _with_uncertainty(spec: SweepSpec, args: argparse.Namespace) -> SweepSpec:
    """The spec with the uncertainty of the options: ``--uncertainty FILE`` (or
    ``literature``) over the spec's ``[uncertainty]``, ``none`` without one; ``--samples`` and
    ``--seed`` for either."""
    from dataclasses import replace

    from racketdyn.errors import InputError
    from racketdyn.io.uncertainty_file import LITERATURE

    if args.uncertainty is None:
        if spec.uncertainty is None:
            for name, default in (("samples", 256), ("seed", 0)):
                if getattr(args, name) != default:
                    raise InputError(
                        f"--{name} is for --uncertainty: give an uncertainty file (or a sweep "
                        "spec with [uncertainty] tables)"
                    )
            return spec
        return replace(
            spec, uncertainty=replace(spec.uncertainty, samples=args.samples, seed=args.seed)
        )
    built_in = spec.racket_source.startswith("built-in")
    racket = None if built_in or args.uncertainty != LITERATURE else spec.racket_source
    found = opt.uncertainty_from(argparse.Namespace(**{**vars(args), "racket": racket}))
    source = "" if found is None else f"--uncertainty {args.uncertainty}"
    if spec.uncertainty is not None and found is not None:
        source += " (over the spec's [uncertainty])"
    return replace(spec, uncertainty=found, uncertainty_source=source)


def _base_band(dataset: Any) -> str:
    """The first design's rebound ratio at the face centre with its 90 % band (or why it has
    none), at the summary speeds and the first support."""
    from racketdyn.sweep import summary_metrics

    metrics = summary_metrics(dataset.isel(design=[0])).isel(design=0, support=0)
    value, low, high = (
        float(metrics[name])
        for name in ("centre_rebound_ratio", *(f"centre_rebound_ratio_{q}" for q in ("p05", "p95")))
    )
    where = (
        f"rebound ratio at the centre, design 0, {metrics.attrs['ball_speed_mps']:g} m/s, "
        f"{metrics['support'].item()}"
    )
    if low == low and high == high:
        return f"  {where}: {value:.3f} ({low:.3f}–{high:.3f}, 90 %)"
    return f"  {where}: {value:.3f}; {metrics['band_note'].item() or 'no band'}"


WORKERS_PAY_S = {
    "process": (0.5, "too little to share out between workers"),
    "dask-local": (2.0, "a local Dask cluster takes about a second to start"),
}
"""Below this much work on one core (s, estimated), workers save next to nothing or cost more
than they save: the command says so, and why.  A process pool forks its workers in milliseconds, but
the last tasks share out unevenly and every part is written and read (README's 3,726-impact
study: 0.6 s on two workers against 0.5 s serial; 264,060 impacts, about 1.3 s of work: 1.2
against 1.4 s, 2026-11-26); a local Dask cluster starts in 0.7-0.8 s (its forkserver's imports
and the scheduler), which a sweep must earn back."""


def _where_time_went(record: dict[str, Any]) -> str:
    """Where the wall time went, from run.json: start, tasks, writing, engine shutdown,
    finishing the store, summary."""
    spent = record.get("time_s", {})
    parts = [f"start {spent['start']:.1f} s"] if "start" in spent else []
    if "tasks" in spent:
        first = record.get("first_result_s")
        parts.append(
            f"tasks {spent['tasks']:.1f} s"
            + (f" (first result after {first:.1f} s)" if first is not None else "")
        )
        writer = {"workers": "by the workers", "main process": "by this process"}.get(
            record.get("store", {}).get("chunk_writer", "workers"),
            "by the workers and this process",
        )
        parts.append(f"writing chunks {record.get('chunk_write_time_s', 0.0):.1f} s ({writer})")
    parts += [
        f"{name} {spent[key]:.1f} s"
        for name, key in (
            ("engine shutdown", "shutdown"),
            ("finishing the store", "finishing"),
            ("summary", "summary"),
        )
        if key in spent
    ]
    return ", ".join(parts)


def _restarts(record: dict[str, Any], task_timeout: float | None) -> str:
    """What ran again, from run.json: tasks past the task timeout, process pools replaced,
    designs retried after an error ("" if none).  Without it a ``--task-timeout`` shorter
    than the tasks doubled the wall time without a word (a new-user trial, 2026-11-26)."""
    said = []
    if record.get("timed_out"):
        limit = "" if task_timeout is None else f" ({task_timeout:g} s)"
        said.append(f"{opt.plural(record['timed_out'], 'task')} ran past the task timeout{limit}")
    if record.get("pools_replaced"):
        said.append(f"{opt.plural(record['pools_replaced'], 'process pool')} replaced")
    if record.get("retried"):
        said.append(f"{opt.plural(record['retried'], 'design')} retried after an error")
    if not said:
        return ""
    hint = " (see --task-timeout)" if record.get("timed_out") else ""
    return "ran again: " + "; ".join(said) + hint
