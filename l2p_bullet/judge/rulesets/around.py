"""The rule of "around": the mover sweeps nearly a full turn around the anchor (at least ``turns`` of a turn)
while staying near it (centre distance at most ``near`` blocks).

A mover that starts farther than ``near`` blocks must first come near: the rule reads the motion from the
first frame within ``near`` blocks on (the approach is not judged, what follows is, to its last frame).
People's own "around" demonstrations all start near (1.4-4.5 blocks, median 2.5: they set the blocks
down); a sentence like "move A around B" with A across the table means going there and round it, which a
rule that judged the whole motion could never pass (the planner would have to refuse such a start up front).
A motion that starts near is judged from its first frame.
"""

from __future__ import annotations

import math

import numpy as np

from ...actions.around import ACTION
from ...core.geometry import swept_angle
from ..base import Verdict

AROUND_TURNS = ACTION.thresholds["turns"]
"""Share of a full turn around the anchor that "around" must sweep."""
AROUND_NEAR = ACTION.thresholds["near"]
"""Largest centre distance (blocks) of "around", from the first frame that comes this near on."""
AROUND_APPROACH = ACTION.thresholds["approach"]
"""Centre distance (blocks) a mover starting farther than ``near`` is first slid to, straight towards the
anchor, before "around" is planned (planning/approach.py): where people's demonstrations start (median)."""


def around(rel: np.ndarray, d: np.ndarray, *_: object, **__: object) -> Verdict:
    near = np.flatnonzero(np.asarray(d, float) <= AROUND_NEAR)
    i0 = int(near[0]) if len(near) else 0  # never near: the whole motion, as far as ever
    turns = abs(swept_angle(rel[i0:])) / (2 * math.pi)
    far = float(d[i0:].max())
    score = float(np.clip(turns, 0, 1)) * (1.0 if far <= AROUND_NEAR else 0.5)
    ok = turns >= AROUND_TURNS and far <= AROUND_NEAR
    came = f"came within {AROUND_NEAR:g} blocks from {float(d[0]):.2f}, then " if i0 > 0 else ""
    return Verdict(ok, score, f"{came}swept {turns:.2f} of a turn around the anchor, at most {far:.2f} blocks away")


RULES = {ACTION.rules: around}
