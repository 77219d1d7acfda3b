"""Data of the interactive face maps, drawn in the page by ``static/face_map.js``.

The plots are drawn by the report's own small scripts (``static/*.js``), not by a plotting
library: the page must stay under 6 MB with everything inline (its PNG figures took ≈ 5.5 MB of
the demo's 5.75 MB page before they were embedded with a palette; now 1.9 of 2.1 MB).  Plotly
(the well-kept candidate, its bundled ``plotly.min.js`` inlined once) adds 4.8 MB — with the
figures as drawn then, a 10.7 MB page, interactive after ≈ 1.2 s in headless Chromium — and its
smallest partial bundle (≈ 1 MB) was measured against that budget too; a small library such as
uPlot draws lines but not coloured points over the face.  The scripts are
tested on their own in Chromium (``tests/test_report_js.py``).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from racketdyn.racket import HeadEllipse

__all__ = ["map_spec"]


def map_spec(
    head: HeadEllipse | None,
    map_id: str,
    groups: list[dict[str, Any]],
    fields: list[tuple[str, str, int]],
    colour: int,
    initial: int,
    xy: NDArray[np.float64],
    marks: list[dict[str, Any]],
    best: str,
) -> dict[str, Any]:
    """Data of an interactive face map: one panel per support, one group per speed.

    Parameters
    ----------
    head : HeadEllipse or None
        The string-bed outline drawn under the points, m.
    map_id : str
        Id of the map's element in the page.
    groups : list of dict
        One group per button (a ball speed): ``label``, colour ``range`` and ``panels``, each
        panel a ``label`` and ``rows`` of values in the order of ``fields`` plus a status (empty
        when the row is valid).
    fields : list of (name, unit, decimals)
        The columns of a row, x and y (mm) first.
    colour : int
        The column that colours the points.
    initial : int
        The group shown first.
    xy : ndarray, shape (n, 2)
        Every point shown, m: sets the frame and the dot size.
    marks : list of dict
        Vertical dashed lines at ``x`` (mm) with a ``label``.
    best : str
        ``"max"`` rings the largest value of each panel; empty for none.

    Returns
    -------
    dict
        The map's entry of the page's JSON data; lengths in mm.
    """
    xs, ys = xy[:, 0] * 1e3, xy[:, 1] * 1e3
    if head is not None:
        xs = np.append(
            xs,
            [
                1e3 * (head.centre_x_m - head.half_length_m),
                1e3 * (head.centre_x_m + head.half_length_m),
            ],
        )
        ys = np.append(
            ys,
            [
                1e3 * (head.centre_y_m - head.half_width_m),
                1e3 * (head.centre_y_m + head.half_width_m),
            ],
        )
    span = max(float(np.ptp(xs)), float(np.ptp(ys)), 1.0)
    pad = 0.06 * span
    font = 0.035 * (float(xs.max() - xs.min()) + 2 * pad)
    frame = [
        round(float(xs.min()) - pad, 1),
        round(float(xs.max()) + pad, 1),
        round(float(ys.min()) - pad, 1),
        round(float(ys.max()) + pad + (0.9 * len(marks) + 0.6) * font, 1),
    ]
    # dots of 0.42 of the median distance to the nearest neighbour: a grid reads as a heat map
    unique = np.unique(np.round(xy * 1e3, 1), axis=0)
    if len(unique) > 1:
        from scipy.spatial import cKDTree

        distance, _ = cKDTree(unique).query(unique, k=2)
        radius = 0.42 * float(np.median(np.asarray(distance)[:, 1]))
    else:
        radius = 0.02 * span
    radius = float(np.clip(radius, 0.006 * span, 0.04 * span))
    return {
        "id": map_id,
        "frame": frame,
        "radius": round(radius, 2),
        "font": round(font, 1),
        "head": None
        if head is None
        else [
            round(head.centre_x_m * 1e3, 2),
            round(head.centre_y_m * 1e3, 2),
            round(head.half_length_m * 1e3, 2),
            round(head.half_width_m * 1e3, 2),
        ],
        "fields": [list(f) for f in fields],
        "colour": colour,
        "best": best,
        "groups": groups,
        "initial": initial,
        "marks": marks,
    }
