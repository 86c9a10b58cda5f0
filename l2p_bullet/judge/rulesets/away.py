"""The rule of "away": the centre distance grows steadily, by at least ``gain`` blocks (score: the growth less
the largest step back)."""

from __future__ import annotations

import numpy as np

from ...actions.away import ACTION
from ..base import Verdict
from ..footprints import WOBBLE

AWAY_GAIN = ACTION.thresholds["gain"]
"""Blocks the centre distance must grow by for "away"."""


def away(rel: np.ndarray, d: np.ndarray, *_: object, **__: object) -> Verdict:
    gained = float(d[-1]) - float(d[0])
    drop = float(np.max(np.maximum.accumulate(d) - d))
    score = float(np.clip((gained - drop) / 6.0, 0, 1))
    ok = gained >= AWAY_GAIN and drop <= WOBBLE
    return Verdict(ok, score, f"distance grew by {gained:.2f} blocks (start {d[0]:.2f}), went back {drop:.2f} blocks")


RULES = {ACTION.rules: away}
