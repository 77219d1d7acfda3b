"""Presentation: figures (matplotlib, ``ax=`` in, ``ax`` out) and the files of each step.

``primitives`` holds the plot functions, ``figures`` the figures each step writes, ``steps``
the figure hooks the workflows take (``hook(result, out) -> paths``), ``sweep`` a sweep's
summary figures.  matplotlib (with the Agg backend: files, not windows) loads when a plot
module is first used: the names below are loaded lazily (SPEC 1, as :mod:`racketdyn`), so the
CLI can hand a hook to a workflow without paying for matplotlib when no figure is drawn.  The
computation layers never import this package.
"""

import importlib
from typing import TYPE_CHECKING, Any

from racketdyn.measurement.records import FRF_UNITS

if TYPE_CHECKING:
    from racketdyn.plotting.primitives import (
        SUPPORT_STYLE,
        plot_along_axis,
        plot_contact_map,
        plot_face_map,
        plot_frame_amplitude,
        plot_frf,
        plot_mac,
        plot_mode_3d,
        plot_node_lines,
        plot_oblique_curve,
        plot_outline,
        plot_speed_curves,
        plot_stabilisation,
        plot_swing_along_axis,
        plot_swing_map,
        plot_twist_curve,
    )

__all__ = [
    "FRF_UNITS",
    "SUPPORT_STYLE",
    "plot_along_axis",
    "plot_contact_map",
    "plot_face_map",
    "plot_frame_amplitude",
    "plot_frf",
    "plot_mac",
    "plot_mode_3d",
    "plot_node_lines",
    "plot_oblique_curve",
    "plot_outline",
    "plot_speed_curves",
    "plot_stabilisation",
    "plot_swing_along_axis",
    "plot_swing_map",
    "plot_twist_curve",
]


def __getattr__(name: str) -> Any:
    """Import :mod:`racketdyn.plotting.primitives` (and matplotlib) on first use of a name."""
    if name in __all__:
        value = getattr(importlib.import_module("racketdyn.plotting.primitives"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'racketdyn.plotting' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
