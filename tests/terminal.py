"""Start a command as a terminal would, for the tests that press Ctrl-C."""

from __future__ import annotations

import signal
import subprocess
from typing import Any


def popen_as_from_a_terminal(*args: Any, **kwargs: Any) -> subprocess.Popen[Any]:
    """:class:`subprocess.Popen` whose child takes SIGINT as a terminal's child does.

    A test run started in the background (``nohup``, ``&``, some CI runners) ignores SIGINT,
    and an ignored signal stays ignored across ``exec``: the child would never see the Ctrl-C
    the test sends.  A caught signal is reset to its default across ``exec``, so SIGINT is
    caught here while the child starts.
    """
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        return subprocess.Popen(*args, **kwargs)
    finally:
        signal.signal(signal.SIGINT, previous)
