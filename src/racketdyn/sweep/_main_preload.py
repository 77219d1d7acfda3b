"""Preloaded first by the forkserver (:func:`racketdyn.sweep.executors._start_forkserver`):
import the main script there once, as each worker would import it.

Python asks the forkserver to preload ``__main__`` but, before 3.13.8, never does (CPython
gh-126631, gh-137996), so every worker forked from it ran the script's top level again.  Its
own preload, where it works, runs the script with the forkserver's ``sys.argv`` (``['-c']``)
and ``sys.path`` (without the script's folder): a script that reads its arguments or imports
a module beside it at its top level raised there and killed the forkserver — a traceback,
then a pool that failed its tasks or hung, or a local Dask cluster whose nannies failed to
start.  Here the script's ``sys.argv`` and ``sys.path`` (passed in :data:`ENVIRONMENT` by the
process that starts the forkserver) are set first, as ``multiprocessing.spawn.prepare`` sets
them in a worker; a script that still raises is left to each worker, as without a preload.

A script read from standard input (``python - < study.py``) has ``__file__ == "<stdin>"``,
which each worker tried to run as a file, and died: the pool lost every design, a local Dask
cluster's nannies failed to start.  No file, nothing to import: the forkserver's own
``__main__`` takes that name, so that ``multiprocessing.spawn.prepare`` in each worker finds
the main module in place and, as for ``python -c``, imports none.
"""

from __future__ import annotations

import json
import os
import sys

ENVIRONMENT = "RACKETDYN_FORKSERVER_MAIN"
"""Environment variable holding the main script's path, ``sys.argv`` and ``sys.path`` (JSON)
while the forkserver starts; removed by both processes."""


def _import_main() -> None:
    from multiprocessing import process, spawn

    raw = os.environ.pop(ENVIRONMENT, None)
    if not raw:
        return
    data = json.loads(raw)
    if not os.path.isfile(data["main_path"]):  # "<stdin>": no script to import
        sys.modules["__main__"].__file__ = data["main_path"]
        return
    sys.argv = list(data["sys_argv"])
    sys.path = list(data["sys_path"])
    process.current_process()._inheriting = True  # type: ignore[attr-defined]
    try:
        spawn.import_main_path(data["main_path"])
    except BaseException:  # SystemExit too: each worker imports the script itself instead
        pass
    finally:
        del process.current_process()._inheriting  # type: ignore[attr-defined]


_import_main()
