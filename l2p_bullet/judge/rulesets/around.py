"""The rule of "around": the mover sweeps nearly a full turn around the anchor (at least ``turns`` of a turn)
while staying near it (centre distance at most ``near`` blocks)."""

from __future__ import annotations

import math

import numpy as np

from ...actions.around import ACTION
from ...core.geometry import swept_angle
from ..base import Verdict

AROUND_TURNS = ACTION.thresholds["turns"]
"""Share of a full turn around the anchor that "around" must sweep."""
AROUND_NEAR = ACTION.thresholds["near"]
"""Largest centre distance (blocks) of "around"."""


def around(rel: np.ndarray, d: np.ndarray, *_: object, **__: object) -> Verdict:
    turns = abs(swept_angle(rel)) / (2 * math.pi)
    far = float(d.max())
    score = float(np.clip(turns, 0, 1)) * (1.0 if far <= AROUND_NEAR else 0.5)
    ok = turns >= AROUND_TURNS and far <= AROUND_NEAR
    return Verdict(ok, score, f"swept {turns:.2f} of a turn around the anchor, at most {far:.2f} blocks away")


RULES = {ACTION.rules: around}
