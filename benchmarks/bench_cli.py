"""Benchmark: wall time of the CLI commands a user waits for, against the targets of issue 11.

``racketdyn --help`` (≤ 0.3 s), ``racketdyn predict`` with defaults (≤ 3 s), ``racketdyn
identify`` on the demo's 69 free-free FRFs with the demo's band (≤ 3 s) and ``racketdyn demo``
(≤ 30 s), each run as a fresh process through the installed ``racketdyn`` script, end to end
(start-up, imports, computation, figures, files). The machine is shared, so each command is
repeated and the minimum wall time is printed, with the CPU time (user + system) of that run
and its ratio to the target (≤ 1 meets it). A benchmark prints; it does not assert.

Run: ``python benchmarks/bench_cli.py`` (≈ 3–4 min; ``--repeat N`` for the short commands,
``--demo-repeat N`` for the demo, ``--skip-demo`` to make the FRFs with ``rig`` + ``frf``
instead, as the demo does, and leave the demo out).

``--profile`` runs predict, identify and the demo once each in a fresh process with timers
around the steps instead (wall and CPU time), every figure drawn in that process, and prints
where the time goes: imports, computation, building figures, drawing them (layout, Agg, PNG)
and writing the other files; for the demo also each step.
"""

from __future__ import annotations

import argparse
import functools
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

TARGETS_S = {"--help": 0.3, "predict": 3.0, "identify": 3.0, "demo": 30.0}
DEMO_FAULTS = ["--double-hits", "0.03", "--overloads", "0.01"]
"""What the demo's rig step adds (racketdyn demo, cli.py): a few bad hits."""
DEMO_FRF = ["--exp-window", "0.1", "--force-range", "200"]
DEMO_BAND = ["--band", "40,850"]


def racketdyn_script() -> str:
    """The ``racketdyn`` script of this interpreter's environment (else the one on PATH)."""
    beside = Path(sys.executable).parent / "racketdyn"
    if beside.is_file():
        return str(beside)
    found = shutil.which("racketdyn")
    if found is None:
        raise SystemExit("no racketdyn script: pip install -e . first")
    return found


def timed(argv: Sequence[str]) -> tuple[float, float]:
    """Run ``racketdyn argv`` once; its wall time and CPU time (user + system), s."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(
        [racketdyn_script(), *argv],
        check=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        env={**os.environ, "COLUMNS": "100"},
    )
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def best_of(
    argv: Sequence[str], repeats: int, fresh_out: Path | None = None
) -> tuple[float, float]:
    """The fastest of ``repeats`` runs (wall, CPU of that run); a fresh ``--out`` each time."""
    runs = []
    for k in range(repeats):
        extra: list[str] = []
        if fresh_out is not None:
            extra = ["--out", str(fresh_out / f"run{k}")]
        runs.append(timed([*argv, *extra]))
    return min(runs)


def line(name: str, wall: float, cpu: float, target: float) -> str:
    ratio = wall / target
    verdict = "meets" if ratio <= 1.0 else "misses"
    return (
        f"{name:<32s} {wall:7.2f} s  (CPU {cpu:6.2f} s)  target {target:5.1f} s  "
        f"ratio {ratio:5.2f}  {verdict}"
    )


def make_frfs(work: Path) -> Path:
    """The demo's free-free FRFs (69 points) by the demo's own rig and frf steps."""
    script = racketdyn_script()
    rig, frf = work / "rig", work / "frf_free"
    for argv in (
        ["rig", "--support", "free", *DEMO_FAULTS, "--out", str(rig)],
        ["frf", str(rig / "hammer_free.uff"), *DEMO_FRF, "--out", str(frf)],
    ):
        subprocess.run([script, *argv], check=True, stdout=subprocess.DEVNULL)
    return frf / "frfs.uff"


def benchmark(repeats: int, demo_repeats: int, skip_demo: bool) -> None:
    print(f"racketdyn CLI, {os.cpu_count()} cores, best of {repeats} (demo: {demo_repeats})")
    print(f"load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        wall, cpu = best_of(["--help"], repeats)
        print(line("racketdyn --help", wall, cpu, TARGETS_S["--help"]), flush=True)
        wall, cpu = best_of(["predict"], repeats, work / "predict")
        print(line("racketdyn predict (defaults)", wall, cpu, TARGETS_S["predict"]), flush=True)
        if skip_demo:
            frfs = make_frfs(work)
        else:
            wall, cpu = best_of(["demo"], demo_repeats, work / "demo")
            frfs = work / "demo" / "run0" / "frf_free" / "frfs.uff"
            demo_line = line("racketdyn demo", wall, cpu, TARGETS_S["demo"])
        wall, cpu = best_of(["identify", str(frfs), *DEMO_BAND], repeats, work / "identify")
        print(line("racketdyn identify (69 FRFs)", wall, cpu, TARGETS_S["identify"]))
        if not skip_demo:
            print(demo_line)
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")


# --- where the time goes ---------------------------------------------------------------------
class _Clock:
    """Inclusive wall and CPU time of the outermost calls of wrapped functions, by category."""

    def __init__(self) -> None:
        self.wall: dict[str, float] = {}
        self.cpu: dict[str, float] = {}
        self.depth: dict[str, int] = {}

    def wrap(self, owner: Any, name: str, category: str, inside: str | None = None) -> None:
        """Time ``owner.name`` under ``category`` (only while ``inside`` runs, if given)."""
        original = getattr(owner, name)

        @functools.wraps(original)
        def timed_call(*args: Any, **kwargs: Any) -> Any:
            if (inside is not None and not self.depth.get(inside)) or self.depth.get(category):
                return original(*args, **kwargs)
            self.depth[category] = 1
            wall, cpu = time.perf_counter(), time.process_time()
            try:
                return original(*args, **kwargs)
            finally:
                self.depth[category] = 0
                self.wall[category] = self.wall.get(category, 0.0) + time.perf_counter() - wall
                self.cpu[category] = self.cpu.get(category, 0.0) + time.process_time() - cpu

        setattr(owner, name, timed_call)

    def get(self, category: str) -> tuple[float, float]:
        return self.wall.get(category, 0.0), self.cpu.get(category, 0.0)

    def rest(self, total: str, *parts: str) -> tuple[float, float]:
        """``total`` less ``parts``, wall and CPU."""
        wall, cpu = self.get(total)
        for part in parts:
            wall, cpu = wall - self.get(part)[0], cpu - self.get(part)[1]
        return wall, cpu


def _row(label: str, times: tuple[float, float], indent: int = 2) -> str:
    return f"{' ' * indent}{label:<{50 - indent}s} {times[0]:6.2f} s wall  {times[1]:6.2f} s CPU"


def _profile(argv: Sequence[str]) -> None:
    """Run one command in this process with timers around the steps; print where time goes."""
    import builtins

    wall, cpu = time.perf_counter(), time.process_time()
    import racketdyn.cli as cli

    start_wall, start_cpu = time.perf_counter() - wall, time.process_time() - cpu
    wall, cpu = time.perf_counter(), time.process_time()
    import matplotlib.figure
    import matplotlib.layout_engine
    import PIL.Image

    import racketdyn.plotting.figures as figures
    import racketdyn.plotting.registry as registry
    import racketdyn.workflows.figure_data as figure_data

    plotting_wall, plotting_cpu = time.perf_counter() - wall, time.process_time() - cpu

    clock = _Clock()
    clock.wrap(builtins, "__import__", "imports")
    for name in dir(figures):
        if name.startswith("write_"):
            clock.wrap(figures, name, "figures")
    # every step's hook draws through the registry since issue 23 (imported at each call)
    clock.wrap(registry, "write_figures", "figures")
    # what the figures draw is computed by the steps (issue 23), before the workflows import it
    for name in ("paper_figures", "transient_curves", "swing_axis_curves", "identified_rebound"):
        clock.wrap(figure_data, name, "figure data")
    clock.wrap(figure_data, "write_figure_data", "figures.nc")
    clock.wrap(matplotlib.figure.Figure, "savefig", "savefig", inside="figures")
    png = sys.modules.get("racketdyn.plotting._png")  # one drawing pass instead of savefig
    if png is not None:
        clock.wrap(png, "write_png", "savefig", inside="figures")
    clock.wrap(matplotlib.layout_engine.ConstrainedLayoutEngine, "execute", "layout", "savefig")
    clock.wrap(PIL.Image.Image, "save", "png", inside="savefig")
    if argv[0] == "demo":
        import racketdyn.html_report

        clock.wrap(racketdyn.html_report, "write_report", "report")
    clock.wrap(cli, "main", "command")
    steps: list[tuple[str, float, float, float]] = []
    run_step = getattr(cli, "_run_step", None)  # the demo's steps (cli.py of 2026-11)
    if run_step is not None:

        def timed_step(step: list[str], *args: Any) -> None:
            wall, cpu, drawing = time.perf_counter(), time.process_time(), clock.get("figures")[1]
            run_step(step, *args)
            drawing = clock.get("figures")[1] - drawing
            steps.append((step[0], time.perf_counter() - wall, time.process_time() - cpu, drawing))

        cli._run_step = timed_step
    cli.main(list(argv))
    print(f"\n== racketdyn {' '.join(argv[:2])} …  (one run, timers around the steps)")
    print(_row("start-up: importing the CLI (fresh process)", (start_wall, start_cpu)))
    print(_row("importing the figures (matplotlib), done lazily", (plotting_wall, plotting_cpu)))
    print(_row("the command", clock.get("command")))
    print(_row("imports while it runs", clock.get("imports"), 4))
    print(_row("figures", clock.get("figures"), 4))
    print(_row("drawing: constrained layout", clock.get("layout"), 6))
    print(_row("drawing: Agg", clock.rest("savefig", "layout", "png"), 6))
    print(_row("drawing: PNG encoding and writing", clock.get("png"), 6))
    building = clock.rest("figures", "savefig")
    print(_row("building artists (plot calls, subplots)", building, 6))
    if "report" in clock.wall:
        print(_row("HTML report", clock.get("report"), 4))
    print(_row("the figures' data, computed by the steps", clock.get("figure data"), 4))
    print(_row("figures.nc (xarray, netCDF)", clock.get("figures.nc"), 4))
    rest = clock.rest("command", "imports", "figures", "report", "figure data", "figures.nc")
    print(_row("computation and the other files", rest, 4))
    for name, wall, cpu, drawing in steps:
        print(
            f"    step {name:<10s} {wall:6.2f} s wall  {cpu:6.2f} s CPU, "
            f"of which figures {drawing:5.2f} s CPU"
        )


def profile(which: str) -> None:
    """Profile each command in its own fresh process (imports counted once per command)."""
    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        frfs = make_frfs(work)
        commands = {
            "predict": ["predict", "--out", str(work / "predict")],
            "identify": ["identify", str(frfs), *DEMO_BAND, "--out", str(work / "identify")],
            "demo": ["demo", "--out", str(work / "demo")],
        }
        for name, argv in commands.items():
            if which not in ("all", name):
                continue
            here = str(Path(__file__).parent)
            code = f"import sys; sys.path.insert(0, {here!r}); import bench_cli; "
            code += f"bench_cli._profile({argv!r})"
            # every figure drawn in the profiled process (no helper process), to see it all
            env = {**os.environ, "RACKETDYN_FIGURE_WORKERS": "0"}
            subprocess.run([sys.executable, "-c", code], check=True, env=env)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs of each short command (3)")
    parser.add_argument("--demo-repeat", type=int, default=2, help="runs of the demo (2)")
    parser.add_argument(
        "--skip-demo", action="store_true", help="FRFs by rig + frf; leave the demo out"
    )
    parser.add_argument(
        "--profile",
        nargs="?",
        const="all",
        choices=["all", "predict", "identify", "demo"],
        help="where the time goes (timers around the steps) instead of the benchmark",
    )
    args = parser.parse_args()
    if args.profile:
        profile(args.profile)
    else:
        benchmark(args.repeat, args.demo_repeat, args.skip_demo)


if __name__ == "__main__":
    main()
