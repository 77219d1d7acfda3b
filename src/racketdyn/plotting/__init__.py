"""Presentation: figures (matplotlib, ``ax=`` in, ``ax`` out) and the files of each step.

``primitives`` holds the plot functions, ``figures`` the figures each step writes. Importing
this package loads matplotlib (with the Agg backend: files, not windows); the computation
layers never import it.
"""

from racketdyn.measurement.records import FRF_UNITS
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
    plot_racket_mode_3d,
    plot_racket_node_lines,
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
    "plot_racket_mode_3d",
    "plot_racket_node_lines",
    "plot_speed_curves",
    "plot_stabilisation",
    "plot_swing_along_axis",
    "plot_swing_map",
    "plot_twist_curve",
]
