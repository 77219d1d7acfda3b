"""Ctrl-C during a long command other than ``sweep``: one line, the folder as it was, exit 130.

The command runs as a subprocess in its own session and gets SIGINT (as a terminal sends on
Ctrl-C) once its step has started writing into its staging folder.
"""

from __future__ import annotations

import os
import signal
import sys
import time
from pathlib import Path

import pytest

import racketdyn
from terminal import popen_as_from_a_terminal

needs_proc = pytest.mark.skipif(not hasattr(os, "killpg"), reason="needs POSIX signals")


@needs_proc
@pytest.mark.slow
def test_ctrl_c_in_a_step_is_one_line_and_leaves_the_folder_as_it_was(tmp_path: Path) -> None:
    out = tmp_path / "rig"
    out.mkdir()
    (out / "notes.txt").write_text("the user's own file\n")
    env = dict(os.environ, PYTHONPATH=str(Path(racketdyn.__file__).parents[1]))
    stdout, stderr = tmp_path / "stdout", tmp_path / "stderr"
    with stdout.open("w") as out_file, stderr.open("w") as err_file:
        process = popen_as_from_a_terminal(
            [sys.executable, "-m", "racketdyn.cli", "rig", "--out", str(out)],
            stdout=out_file,
            stderr=err_file,
            env=env,
            start_new_session=True,
        )
        try:
            deadline = time.monotonic() + 120
            while not list(out.glob(".racketdyn-staging-*")) and process.poll() is None:
                assert time.monotonic() < deadline, "the step never started"
                time.sleep(0.05)
            assert process.poll() is None, "the step finished before it could be interrupted"
            time.sleep(0.5)  # well inside the step's work
            os.killpg(process.pid, signal.SIGINT)
            process.wait(timeout=60)
        finally:
            if process.poll() is None:
                process.kill()
    said = stdout.read_text() + stderr.read_text()
    assert process.returncode == 130, said
    assert "Traceback" not in said
    assert "KeyboardInterrupt" not in said
    lines = [line for line in said.splitlines() if "interrupted" in line]
    assert len(lines) == 1, said
    assert str(out) in " ".join(said.split())  # names the folder (the line may wrap)
    assert sorted(p.name for p in out.iterdir()) == ["notes.txt"]  # no staging, no lock
