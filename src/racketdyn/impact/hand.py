"""The hand and arm holding the grip: the ``hand`` support of the transient impact model.

The approximate method models a hand-held racket as pinned at the grip (paper, section 3.3).
The transient model can instead hold the grip with a hand and an arm that have mass, stiffness
and damping: :class:`racketdyn.hand.Hand`, the one hand that the virtual rig's hand-held test
holds the racket with too (its model, defaults and sources are there).  This module keeps the
name ``racketdyn.impact.hand.Hand``; :mod:`racketdyn.impact.system` builds the hand into the
equations of motion.
"""

from __future__ import annotations

from racketdyn.hand import GRIP_POINTS, Hand

__all__ = ["GRIP_POINTS", "Hand"]
