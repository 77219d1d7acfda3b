"""Preloaded by each worker of a local Dask cluster (:func:`~.executors.make_executor`).

Forked from a forkserver that has already imported distributed, a worker has neither the
SIGINT disposition nor the logging level its nanny's environment asks for: leave Ctrl-C to the
main process (which stops the sweep) and log what ``DASK_LOGGING__DISTRIBUTED`` says.
"""

from __future__ import annotations

import contextlib
import logging
import os
import signal
from typing import Any


def dask_setup(worker: Any) -> None:
    """Called by distributed as the worker starts.

    Parameters
    ----------
    worker : distributed.Worker
        The worker (unused).
    """
    with contextlib.suppress(ValueError):  # not the main thread: the worker keeps its own
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    level = os.environ.get("DASK_LOGGING__DISTRIBUTED")
    if level:
        logging.getLogger("distributed").setLevel(level.upper())
