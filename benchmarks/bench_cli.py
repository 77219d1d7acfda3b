"""Benchmark: wall time of the CLI commands a user waits for, against the targets of issue 11.

``racketdyn --help`` (≤ 0.3 s), ``racketdyn predict`` with defaults (≤ 3 s), ``racketdyn
identify`` on the demo's 69 free-free FRFs with the demo's band (≤ 3 s) and ``racketdyn demo``
(≤ 30 s), and ``predict --no-figures`` (the floor under predict's figures: its imports,
computation and files), each run as a fresh process through the installed ``racketdyn`` script,
end to end (start-up, imports, computation, figures, files). The machine is shared, so each
command is repeated and the minimum wall time is printed, with the CPU time (user + system) of
that run and its ratio to the target (≤ 1 meets it). A benchmark prints; it does not assert.
First it prints the host: the libraries' versions, the import times of scipy.optimize and
matplotlib.pyplot in a fresh process, and a fixed Python loop, so that runs on two hosts (or two
library versions) can be told apart from a change in racketdyn.

Run: ``python benchmarks/bench_cli.py`` (≈ 3–4 min; ``--repeat N`` for the short commands,
``--demo-repeat N`` for the demo, ``--skip-demo`` to make the FRFs with ``rig`` + ``frf``
instead, as the demo does, and leave the demo out). The commands run this checkout's ``src``
(first on ``PYTHONPATH``), whatever racketdyn the environment has installed.

``--baseline REV`` (a git revision of this repository, or a folder holding a racketdyn
``src``) runs each short command of that version too, in turn with this one (A B A B …), and
prints both and the ratio this/baseline of their medians and of each pair: the old path in
the same run, on the same machine load (issue 27's speed work: ``--baseline 733f5c0``).

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
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

TARGETS_S = {"--help": 0.3, "predict": 3.0, "identify": 3.0, "demo": 30.0}
DEMO_FAULTS = ["--double-hits", "0.03", "--overloads", "0.01"]
"""What the demo's rig step adds (racketdyn demo, cli.py): a few bad hits."""
DEMO_FRF = ["--exp-window", "0.1", "--force-range", "200"]
DEMO_BAND = ["--band", "40,850"]
FLOOR_IMPORTS = "numpy, scipy.interpolate, xarray"
"""The libraries every ``predict`` imports whatever it draws (host line: the floor under it)."""


def racketdyn_script() -> str:
    """The ``racketdyn`` script of this interpreter's environment (else the one on PATH)."""
    beside = Path(sys.executable).parent / "racketdyn"
    if beside.is_file():
        return str(beside)
    found = shutil.which("racketdyn")
    if found is None:
        raise SystemExit("no racketdyn script: pip install -e . first")
    return found


SRC = Path(__file__).resolve().parents[1] / "src"
"""This checkout's sources: what the commands run (before any installed racketdyn)."""


def _env(src: Path = SRC) -> dict[str, str]:
    """The environment of a command: ``src`` first on ``PYTHONPATH``, a fixed width, and
    Python's bytecode caches written and read (``PYTHONDONTWRITEBYTECODE`` dropped: with it,
    every command compiles racketdyn's modules from source again, which an installed racketdyn
    never does; the first run of a command writes them)."""
    path = os.pathsep.join(p for p in (str(src), os.environ.get("PYTHONPATH", "")) if p)
    env = {**os.environ, "COLUMNS": "100", "PYTHONPATH": path}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def bytecode_line() -> str:
    """Whether this environment forbids bytecode caches (the commands are run without)."""
    if os.environ.get("PYTHONDONTWRITEBYTECODE"):
        return (
            "host: PYTHONDONTWRITEBYTECODE is set here; the commands run without it (their "
            "first run writes the bytecode caches)"
        )
    return "host: bytecode caches written and read"


def timed(argv: Sequence[str], src: Path = SRC) -> tuple[float, float]:
    """Run ``racketdyn argv`` once (the racketdyn of ``src``); its wall time and CPU time
    (user + system, with its helper processes), s."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(
        [racketdyn_script(), *argv],
        check=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        env=_env(src),
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


def _load() -> str:
    return " ".join(f"{v:.2f}" for v in os.getloadavg())


def paired(name: str, argv: Sequence[str], repeats: int, fresh_out: Path, baseline: Path) -> None:
    """Run ``argv`` of this checkout (A) and of ``baseline`` (B) in turn, ``repeats`` times
    each after one warm-up of each; print the medians and minima and the ratios A/B."""
    runs: dict[str, list[tuple[float, float]]] = {"A": [], "B": []}
    load = _load()
    for k in range(repeats + 1):
        for which, src in (("A", SRC), ("B", baseline)):
            out = ["--out", str(fresh_out / f"{which}{k}")]
            result = timed([*argv, *out], src)
            if k:  # the first of each warms the caches
                runs[which].append(result)
    walls = {w: [r[0] for r in runs[w]] for w in runs}
    cpus = {w: [r[1] for r in runs[w]] for w in runs}
    pairs = sorted(a / b for a, b in zip(walls["A"], walls["B"], strict=True))
    print(f"{name}  ({repeats} runs each, load average {load} before, {_load()} after)")
    for which, label in (("A", "this checkout"), ("B", f"baseline {baseline}")):
        wall, cpu = statistics.median(walls[which]), statistics.median(cpus[which])
        print(
            f"  {label:<40s} wall median {wall:6.2f} s (min {min(walls[which]):6.2f})  "
            f"CPU median {cpu:6.2f} s"
        )
    print(
        f"  ratio this/baseline: wall of medians "
        f"{statistics.median(walls['A']) / statistics.median(walls['B']):5.2f}, pairs "
        f"{pairs[0]:.2f}–{statistics.median(pairs):.2f}–{pairs[-1]:.2f} (min–median–max); "
        f"CPU of medians {statistics.median(cpus['A']) / statistics.median(cpus['B']):5.2f}",
        flush=True,
    )


def baseline_src(revision: str, work: Path) -> Path:
    """The ``src`` of ``revision``: a folder holding one as it is, else the revision of this
    repository exported there (``git archive``)."""
    given = Path(revision)
    if (given / "racketdyn").is_dir():
        return given
    if (given / "src" / "racketdyn").is_dir():
        return given / "src"
    archive = subprocess.run(
        ["git", "-C", str(SRC.parent), "archive", revision, "src"],
        check=True,
        capture_output=True,
    ).stdout
    subprocess.run(["tar", "-x", "-C", str(work)], input=archive, check=True)
    return work / "src"


def compare(repeats: int, revision: str) -> None:
    """This checkout against ``revision``: ``predict`` with defaults and ``identify`` on the
    demo's 69 FRFs, paired runs."""
    print(f"racketdyn CLI against {revision}, {os.cpu_count()} cores, {repeats} paired runs")
    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        (work / "baseline").mkdir()
        baseline = baseline_src(revision, work / "baseline")
        paired("racketdyn predict (defaults)", ["predict"], repeats, work / "predict", baseline)
        frfs = make_frfs(work)
        paired(
            "racketdyn identify (69 FRFs)",
            ["identify", str(frfs), *DEMO_BAND],
            repeats,
            work / "identify",
            baseline,
        )


def make_frfs(work: Path) -> Path:
    """The demo's free-free FRFs (69 points) by the demo's own rig and frf steps."""
    script = racketdyn_script()
    rig, frf = work / "rig", work / "frf_free"
    for argv in (
        ["rig", "--support", "free", *DEMO_FAULTS, "--out", str(rig)],
        ["frf", str(rig / "hammer_free.uff"), *DEMO_FRF, "--out", str(frf)],
    ):
        subprocess.run([script, *argv], check=True, stdout=subprocess.DEVNULL, env=_env())
    return frf / "frfs.uff"


HOST_LIBRARIES = ("numpy", "scipy", "matplotlib", "xarray", "pandas", "numba")
"""The libraries whose versions and import times set a command's start-up (issue 27: scipy
1.17 imports its optimize ≈ 0.6 s slower than 1.15 on the same host, its array-API decorators
parsing docstrings at import)."""


def host_lines() -> list[str]:
    """What the host and its libraries are, to tell a slower host from a slower racketdyn:
    the versions, a fresh process's ``import scipy.optimize`` and ``import matplotlib.pyplot``
    (best of 3), and a fixed pure-Python loop (best of 3), each in s."""
    from importlib.metadata import PackageNotFoundError, version

    def installed(name: str) -> str:
        try:
            return f"{name} {version(name)}"
        except PackageNotFoundError:
            return f"{name} absent"

    def fresh_import(module: str) -> float:
        code = f"import time; t = time.perf_counter(); import {module}; "
        code += "print(time.perf_counter() - t)"
        runs = [
            float(subprocess.run([sys.executable, "-c", code], check=True,
                                 capture_output=True, text=True).stdout)
            for _ in range(3)
        ]  # fmt: skip
        return min(runs)

    def loop() -> float:
        start = time.perf_counter()
        total = 0
        for k in range(2_000_000):
            total += k % 7
        return time.perf_counter() - start

    python_loop = min(loop() for _ in range(3))
    return [
        "host: " + ", ".join(installed(name) for name in HOST_LIBRARIES),
        f"host: import scipy.optimize {fresh_import('scipy.optimize'):.2f} s, import "
        f"matplotlib.pyplot {fresh_import('matplotlib.pyplot'):.2f} s (fresh process, best of "
        f"3); a 2·10⁶-step Python loop {python_loop:.2f} s (best of 3)",
        f"host: import numpy, scipy.interpolate, xarray {fresh_import(FLOOR_IMPORTS):.2f} s "
        "(what any predict imports before racketdyn's own modules: its shapes' spline, its "
        "figures.nc; fresh process, best of 3)",
        bytecode_line(),
    ]


def benchmark(repeats: int, demo_repeats: int, skip_demo: bool) -> None:
    print(f"racketdyn CLI, {os.cpu_count()} cores, best of {repeats} (demo: {demo_repeats})")
    print(f"load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    for text in host_lines():
        print(text, flush=True)
    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        wall, cpu = best_of(["--help"], repeats)
        print(line("racketdyn --help", wall, cpu, TARGETS_S["--help"]), flush=True)
        wall, cpu = best_of(["predict"], repeats, work / "predict")
        print(line("racketdyn predict (defaults)", wall, cpu, TARGETS_S["predict"]), flush=True)
        wall, cpu = best_of(["predict", "--no-figures"], repeats, work / "bare")
        bare = line("  the same, --no-figures", wall, cpu, TARGETS_S["predict"])
        print(f"{bare}  (the floor under the figures)", flush=True)
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
def time_demo_steps(
    steps: list[tuple[str, float, float, float]], drawn: Callable[[], float]
) -> None:
    """Time each of the demo's steps (``racketdyn.cli.demo.steps``' calls) as it runs: its
    command's name, wall, CPU and the part of ``drawn()`` (CPU spent drawing figures) it took,
    appended to ``steps``."""
    from racketdyn.cli import demo

    chain_of = demo.steps

    def timed_chain(*args: Any, **kwargs: Any) -> list[tuple[str, list[str], Callable[[], object]]]:
        def timed(command: list[str], call: Callable[[], object]) -> Callable[[], object]:
            def run() -> object:
                wall, cpu, drawing = time.perf_counter(), time.process_time(), drawn()
                result = call()
                steps.append(
                    (
                        command[1],
                        time.perf_counter() - wall,
                        time.process_time() - cpu,
                        drawn() - drawing,
                    )
                )
                return result

            return run

        return [(label, c, timed(c, call)) for label, c, call in chain_of(*args, **kwargs)]

    demo.steps = timed_chain


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
    clock.wrap(builtins, "__import__", "imports while drawing", inside="figures")
    for name in dir(figures):
        if name.startswith("write_"):
            clock.wrap(figures, name, "figures")
    # every step's hook draws through the registry since issue 23 (imported at each call)
    clock.wrap(registry, "write_figures", "figures")
    # what the figures draw is computed by the steps (issue 23), before the workflows import it
    for name in ("paper_figures", "transient_curves", "swing_axis_curves", "identified_rebound"):
        clock.wrap(figure_data, name, "figure data")
    # imported by name into the steps; since issue 27 written inside write_figures (deferred)
    import racketdyn.workflows.identify as identify_step
    import racketdyn.workflows.predict as predict_step
    import racketdyn.workflows.run as run_module

    for owner, name in (
        (figure_data, "write_figure_data"),
        (predict_step, "write_figure_data"),
        (identify_step, "write_figure_data"),
        (run_module, "write_pending"),  # predict's and identify's: to_xarray and the file
    ):
        clock.wrap(owner, name, "figures.nc")
        clock.wrap(owner, name, "figures.nc while drawing", inside="figures")
    clock.wrap(matplotlib.figure.Figure, "savefig", "savefig", inside="figures")
    png = sys.modules.get("racketdyn.plotting._png")  # one drawing pass instead of savefig
    if png is not None:
        clock.wrap(png, "write_png", "savefig", inside="figures")
    clock.wrap(matplotlib.layout_engine.ConstrainedLayoutEngine, "execute", "layout", "savefig")
    clock.wrap(PIL.Image.Image, "save", "png", inside="savefig")
    if argv[0] == "demo":
        import racketdyn.report  # the demo imports write_report from it when it runs

        clock.wrap(racketdyn.report, "write_report", "report")
    clock.wrap(cli, "main", "command")
    steps: list[tuple[str, float, float, float]] = []
    if argv[0] == "demo":
        time_demo_steps(steps, lambda: clock.get("figures")[1])
    cli.main(list(argv))
    print(f"\n== racketdyn {' '.join(argv[:2])} …  (one run, timers around the steps)")
    print(_row("start-up: importing the CLI (fresh process)", (start_wall, start_cpu)))
    print(_row("importing the figures (matplotlib), done lazily", (plotting_wall, plotting_cpu)))
    print(_row("the command", clock.get("command")))
    print(_row("imports while it runs", clock.get("imports"), 4))
    print(
        _row(
            "of which inside the figures (counted there too)", clock.get("imports while drawing"), 6
        )
    )
    nested = "figures.nc while drawing"
    print(_row("figures (figures.nc apart)", clock.rest("figures", nested), 4))
    print(_row("drawing: constrained layout", clock.get("layout"), 6))
    print(_row("drawing: Agg", clock.rest("savefig", "layout", "png"), 6))
    print(_row("drawing: PNG encoding and writing", clock.get("png"), 6))
    building = clock.rest("figures", "savefig", nested)
    print(_row("building artists (plot calls, subplots)", building, 6))
    if "report" in clock.wall:
        print(_row("HTML report", clock.get("report"), 4))
    print(_row("the figures' data, computed by the steps", clock.get("figure data"), 4))
    print(_row("figures.nc (xarray, netCDF)", clock.get("figures.nc"), 4))
    nc = clock.rest("figures.nc", nested)  # written outside the figures
    outside = clock.rest("imports", "imports while drawing")  # the others are in the figures'
    rest = clock.rest("command", "figures", "report", "figure data")
    rest = (rest[0] - nc[0] - outside[0], rest[1] - nc[1] - outside[1])
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
            env = {**_env(), "RACKETDYN_FIGURE_WORKERS": "0"}
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
    parser.add_argument(
        "--baseline",
        metavar="REV",
        help="also run predict and identify of this git revision (or src folder), in turn "
        "with this checkout, and print the ratios",
    )
    args = parser.parse_args()
    if args.profile:
        profile(args.profile)
    elif args.baseline:
        compare(max(args.repeat, 5), args.baseline)
    else:
        benchmark(args.repeat, args.demo_repeat, args.skip_demo)


if __name__ == "__main__":
    main()
