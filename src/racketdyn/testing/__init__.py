"""Test helpers for racketdyn and for code built on it: structures whose modes are known exactly.

As :mod:`xarray.testing` does for xarray, this package gives users the oracles racketdyn's own
tests use, so a lab can check its own pipeline (its exports, its band, its windows) against a
truth before it trusts a racket's numbers:

- :func:`beam_frfs` (:mod:`racketdyn.testing.free_beam`): FRFs of a free–free aluminium bar,
  analytic modes (Blevins' roots of ``cos βL cosh βL = 1``), on any line in space, with noise;
- :func:`records_for` (:mod:`racketdyn.testing.records`): hammer time records of a known modal
  system through an anti-aliased acquisition;
- :func:`assert_modes_match`: identified modes against a truth, with the tolerances said.

Nothing here is used by racketdyn's computations; it imports only the core nouns.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from racketdyn.modal.mac import mac
from racketdyn.modal.model import ModalModel
from racketdyn.testing.free_beam import BeamTest, beam_frfs, mode_shapes, natural_frequencies
from racketdyn.testing.records import Modes, half_sine, records_for

__all__ = [
    "BeamTest",
    "Modes",
    "assert_modes_match",
    "beam_frfs",
    "half_sine",
    "mode_shapes",
    "natural_frequencies",
    "records_for",
]


def assert_modes_match(
    identified: ModalModel,
    frequency_hz: ArrayLike,
    *,
    frequency_rtol: float = 2e-3,
    shapes: ArrayLike | None = None,
    mac_min: float = 0.98,
) -> None:
    """Assert that every true mode was identified, and nothing else.

    Each true frequency must have an identified one within ``frequency_rtol`` (relative), one
    identified mode per true mode; with ``shapes`` (the true shapes at the identified model's
    points, ``(n_points, n_modes)``) each pair's MAC must reach ``mac_min``.

    Parameters
    ----------
    identified : ModalModel
        The model to check (e.g. ``racketdyn.modal.identify(...).model``).
    frequency_hz : array_like (n_modes,)
        The true natural frequencies, Hz.
    frequency_rtol : float
        Relative tolerance on each frequency (default 0.2 %).
    shapes : array_like, optional
        True mode shapes at the identified model's points.
    mac_min : float
        Least MAC of each pair.

    Raises
    ------
    AssertionError
        Naming the first mode missed, the spurious ones, or the pair whose MAC is low.
    """
    truth = np.atleast_1d(np.asarray(frequency_hz, dtype=float))
    found = np.asarray(identified.frequency, dtype=float)
    pairs = []
    for k, f in enumerate(truth):
        j = int(np.argmin(np.abs(found - f))) if found.size else -1
        if j < 0 or abs(found[j] / f - 1.0) > frequency_rtol:
            near = f"nearest {found[j]:.4g} Hz" if j >= 0 else "no mode identified"
            raise AssertionError(f"true mode {k + 1} at {f:.4g} Hz not found ({near})")
        pairs.append((k, j))
    extra = sorted(set(range(found.size)) - {j for _, j in pairs})
    if extra:
        listed = ", ".join(f"{found[j]:.4g} Hz" for j in extra)
        raise AssertionError(f"identified modes not in the truth: {listed}")
    if shapes is not None:
        true_shapes = np.asarray(shapes, dtype=float)
        for k, j in pairs:
            value = float(
                mac(true_shapes[:, k : k + 1], identified.mode_shapes[:, j : j + 1])[0, 0]
            )
            if value < mac_min:
                raise AssertionError(
                    f"true mode {k + 1} at {truth[k]:.4g} Hz: MAC {value:.3f} < {mac_min}"
                )
