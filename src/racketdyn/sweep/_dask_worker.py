"""Preloaded by each worker of a local Dask cluster (:func:`~.executors.make_executor`).

Forked from a forkserver that has already imported distributed, a worker has neither the
SIGINT disposition nor the logging level its nanny's environment asks for: leave Ctrl-C to the
main process (which stops the sweep) and log what ``DASK_LOGGING__DISTRIBUTED`` says.

A local cluster's scheduler lives in the main process: a worker that can no longer reach it
in a heartbeat is watching the sweep end (Ctrl-C, a closing cluster), and distributed logs that
at error level with a traceback.  Where the main process shows no info of distributed, that
one message is dropped (:class:`_EndingHeartbeat`); every other error still prints.
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
    if level and logging.getLevelName(level.upper()) in QUIET_LEVELS:
        logging.getLogger("distributed.worker").addFilter(_EndingHeartbeat())


class _EndingHeartbeat(logging.Filter):
    """Drops distributed's "Failed to communicate with scheduler during heartbeat." record."""

    def filter(self, record: logging.LogRecord) -> bool:
        return not str(record.msg).startswith(HEARTBEAT_LOST)


QUIET_LEVELS = (logging.WARNING, logging.ERROR, logging.CRITICAL)
"""The workers' levels of a sweep whose main process shows no info of distributed."""

HEARTBEAT_LOST = "Failed to communicate with scheduler during heartbeat"
"""The start of the message distributed's worker logs when its heartbeat finds the scheduler
gone (``distributed.worker.Worker.heartbeat``)."""
