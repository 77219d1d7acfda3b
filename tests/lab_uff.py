"""Public test helper: Universal Files laid out as modal labs export them (issue 12).

Layouts studied in public exports (LMS Test.Lab, ArtemiS, OROS geometries in pyuff's data
folder): node coordinates in the lab's own frame with z kept (data set 15), FRFs (data set 58,
function type 4) with the response and excitation nodes and their direction codes as measured —
roving hammer, roving accelerometer (one excitation node), several references.  Written with
racketdyn's own data-set builder and pyuff, our own numbers only.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from racketdyn.io.uff import _Axes, _Ends, _record_set, _write_sets


def write_lab_uff(
    path: Path,
    nodes: dict[int, tuple[float, float, float]],
    frequency: NDArray[np.float64],
    frfs: Sequence[tuple[int, int, int, int, NDArray[np.complex128]]],
    *,
    geometry: bool = True,
) -> Path:
    """Write node coordinates (m) and accelerances ``(rsp_node, rsp_dir, ref_node, ref_dir,
    values)`` (m/s²/N) to a Universal File; ``geometry=False`` leaves data set 15 out (a file
    of FRFs only, as labs export them without their geometry)."""
    numbers = sorted(nodes)
    sets: list[dict] = [
        {
            "type": 15,
            "node_nums": numbers,
            "def_cs": [0] * len(numbers),
            "disp_cs": [0] * len(numbers),
            "color": [0] * len(numbers),
            "x": [nodes[n][0] for n in numbers],
            "y": [nodes[n][1] for n in numbers],
            "z": [nodes[n][2] for n in numbers],
        }
    ]
    if not geometry:
        sets = []
    for k, (rsp, rsp_dir, ref, ref_dir, values) in enumerate(frfs, start=1):
        dset = _record_set(
            4,
            _Ends(rsp, ref),
            _Axes("frequency", "acceleration", "force"),
            frequency,
            values,
            (f"H {rsp}:{rsp_dir} / {ref}:{ref_dir}",),
            binary=False,
            number=k,
        )
        dset["rsp_dir"], dset["ref_dir"] = rsp_dir, ref_dir
        sets.append(dset)
    return _write_sets(Path(path), sets)
