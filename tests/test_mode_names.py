"""Issue 25, item 5: a racket mode's name only as confident as its shape at the points.

A new user's invented racket (``lab_rackets.TRIAL_RACKET_104``: 276 g, 104 sq in, 166 Hz,
head-heavy) through ``rig`` (``--response-snr 45 --force-snr 55``, the rig's stream of seed 1,
10 averages), ``frf --force-window 0.01`` and ``identify --racket`` (in memory, as
``tests/test_racket_data.py`` makes the rig's FRFs).  The rig's truth has pairs of modes of
opposite symmetry closer than their half-power widths (ζ 0.5 %: 3.5 Hz at 700 Hz): the 3-node
twisting and the all-in-phase membrane at 702.0/703.4 Hz, the (2, 0) membrane and the 6-node
twisting at 1475.5/1480.5 Hz.  The identification fits one pole to each pair, of both shapes
(MAC 0.58 and 0.42 with the two truth modes; 0.66 and 0.29), and the namer named them
"3-node twisting" and "6-node twisting" as if they were the truth's; a mix that took a name a
clean mode also took left the clean one "… (2)" (the trial's 1553 Hz "7-node twisting").
"""

from __future__ import annotations

import numpy as np
import pytest

from costly import costly
from lab_rackets import TRIAL_RACKET_104
from racketdyn.io import load_racket
from racketdyn.modal.identify import Identification, identify
from racketdyn.modal.mac import mac
from racketdyn.modal.model import ModalModel
from racketdyn.racket_modal.identify import name_if_racket
from racketdyn.rig import SensorNoise
from test_racket_data import measured_frfs

SAME_MODE_MAC = 0.8
"""Least MAC (every point) of an identified mode with the rig's truth mode whose name it bears
for the name to stand alone: :data:`racketdyn.racket_modal.shapes.FRAME_MAC`, the namer's own
least match of a frame shape with a reference mode."""


@pytest.fixture(scope="module")
@costly
def invented(
    tmp_path_factory: pytest.TempPathFactory,
) -> tuple[ModalModel, Identification, str]:
    """The rig's truth of the invented racket, free, ``identify --racket`` of its FRFs and the
    sentence saying how its modes were named (run.json's ``naming``)."""
    from racketdyn.workflows.rig import support_stream

    path = tmp_path_factory.mktemp("invented") / "mine.toml"
    path.write_text(TRIAL_RACKET_104, encoding="utf-8")
    racket = load_racket(path)
    frfs, truth = measured_frfs(
        racket,
        "free",
        SensorNoise(force_snr_db=55.0, response_snr_db=45.0),
        10,
        (0.01, None),
        seed=np.random.default_rng(support_stream(1, "free")),
    )
    found, naming = name_if_racket(identify(frfs, support="free"), racket, True)
    return truth, found, naming


@pytest.mark.slow
def test_a_mode_of_two_shapes_is_named_a_mix(
    invented: tuple[ModalModel, Identification, str],
) -> None:
    """Every identified mode that bears a truth mode's name alone matches that mode (MAC ≥
    :data:`SAME_MODE_MAC`); a mode that matches no truth mode so is named a mix, of kind
    ``unknown``, its reason saying so; no name is given twice ("… (2)")."""
    truth, found, naming = invented
    model = found.model
    shapes = mac(model.mode_shapes, truth.mode_shapes_at(model.locations))
    mixes = 0
    for k, name in enumerate(model.names):
        if name in truth.names:
            j = truth.names.index(name)
            assert shapes[k, j] >= SAME_MODE_MAC, (model.frequency[k], name, shapes[k, j])
        if np.max(shapes[k]) < SAME_MODE_MAC:
            mixes += 1
            assert "mixed with" in name, (model.frequency[k], name, np.max(shapes[k]))
            assert model.kinds[k] == "unknown"
            assert f"{model.frequency[k]:.1f} Hz (" in naming.split("; unknown: ")[1]
        assert not name.endswith("(2)"), model.names
    # the two pairs of opposite symmetry: each one pole, each named as the mix it is
    assert mixes >= 2, [(f, n) for f, n in zip(model.frequency, model.names, strict=True)]
