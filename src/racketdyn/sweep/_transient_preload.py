"""Preloaded by the forkserver of a local Dask cluster for a transient sweep
(:func:`racketdyn.sweep.executors.start_early`).

Importing this module runs one compiled transient impact, so numba loads the kernel's
machine code (0.3 s from its cache; the whole compile, about 6 s, on a fresh install) once in
the forkserver, and every worker forked from it starts with the kernel in memory instead of
loading it in its first task.  A sweep of another method does not preload it.
"""

from __future__ import annotations

import logging

import numpy as np

from racketdyn import Ball, default_racket
from racketdyn.impact.transient import predict_transient


def _load_the_kernel() -> None:
    racket = default_racket()
    centre = np.array([[racket.head.centre_x_m, racket.head.centre_y_m]])
    logging.getLogger("racketdyn").disabled = True  # no warning from a forkserver
    try:
        predict_transient(racket, Ball(), centre, [20.0], supports="free", engine="compiled")
    except Exception:  # a forkserver whose preload raises dies; the workers load it instead
        pass
    finally:
        logging.getLogger("racketdyn").disabled = False


_load_the_kernel()
