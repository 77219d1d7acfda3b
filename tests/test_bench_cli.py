"""The CLI benchmark's own machinery (benchmarks/bench_cli.py): a benchmark prints, but what it
prints must come from the code it claims to time."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import bench_cli


def test_the_profile_times_each_step_of_the_demo(monkeypatch: pytest.MonkeyPatch) -> None:
    """``bench_cli.py --profile demo`` printed no step at all: it looked for ``cli._run_step``,
    which the demo no longer has (its steps are ``racketdyn.cli.demo.steps``' calls).  Each
    call is now timed as it runs, under its command's name."""
    from racketdyn.cli import demo

    ran: list[str] = []

    def chain(out: Path, racket: str | None) -> list[tuple[str, list[str], object]]:
        return [
            (label, ["racketdyn", label], lambda label=label: ran.append(label))
            for label in ("rig", "frf")
        ]

    monkeypatch.setattr(demo, "steps", chain)
    steps: list[tuple[str, float, float, float]] = []
    bench_cli.time_demo_steps(steps, lambda: 0.0)
    for _, _, call in demo.steps(Path("."), None):
        call()
    assert ran == ["rig", "frf"]
    assert [name for name, *_ in steps] == ["rig", "frf"]
    assert all(wall >= 0 and cpu >= 0 and drawing == 0 for _, wall, cpu, drawing in steps)


@pytest.mark.slow
def test_the_host_is_said_with_its_libraries() -> None:
    """The host's lines name the libraries whose versions set the start-up."""
    lines = bench_cli.host_lines()
    assert lines[0].startswith("host: numpy ")
    assert "scipy " in lines[0]
    assert "import scipy.optimize" in lines[1]


def test_the_commands_run_from_cached_bytecode(monkeypatch: pytest.MonkeyPatch) -> None:
    """With ``PYTHONDONTWRITEBYTECODE`` set (as on the session's host) every timed command
    compiled racketdyn's ≈ 100 modules from source again (≈ 0.5–1 s of each command's CPU),
    which an installed racketdyn never does; the warm-up runs now write the caches, and the
    host's lines say whether the setting was there."""
    monkeypatch.setenv("PYTHONDONTWRITEBYTECODE", "1")
    assert "PYTHONDONTWRITEBYTECODE" not in bench_cli._env()
    assert "PYTHONDONTWRITEBYTECODE" in bench_cli.bytecode_line()
