"""Where "past" passes: within the room people passed the anchor in.

The learned model of "past" rates a mover that slides by the anchor 4-5 blocks away done (0.98-0.997), a
motion no person made: people's 43 demonstrations pass it at most 3.70 blocks away (``ActionSpec.thresholds
["passes_within"]`` of past, rounded up to 3.8; tests/planning). Chains meet such plans where a clause starts
6-10 blocks from the anchor (analysis seeds 5300-5399: 10 of past's 19 failed plans passed 4.0-4.9 blocks
away; docs/planning.md). So, like "around"'s reach, a planner setting from people's data: the model is
unchanged, and its final progress of a candidate path is weighted by how far beyond that room the path's
closest approach lies, ``exp(-excess / SCALE_SIDES)``; a path that comes within it keeps the model's score.
The weight is smooth, not a cut, so that a mover starting far away sees every step nearer pay. The plan's
per-frame ``curve`` (what the plan and the video show) stays the model's own; its ``extra.final_progress`` is
the score the search ranked by, the model's own wherever the path passes within the room.
"""

from __future__ import annotations

from typing import Any

import numpy as np

SCALE_SIDES = 1.0
"""Blocks of closest approach beyond the room at which a candidate's score is multiplied by 1/e (as
``target.SCALE_SIDES``; not tuned)."""


def pass_weight(movers: list[np.ndarray], anchor_pose: np.ndarray, size: float, within: float) -> np.ndarray:
    """Per path (T,3 centres): 1 where its closest centre distance to the anchor is at most ``within`` blocks,
    else exp(-(closest - within) / SCALE_SIDES)."""
    a = np.asarray(anchor_pose, float)[:2]
    closest = np.array([np.hypot(*(np.asarray(m, float)[:, :2] - a).T).min() for m in movers]) / size
    return np.exp(-np.clip(closest - within, 0.0, None) / SCALE_SIDES)


class PassScorer:
    """The action's progress model with its final progress weighted by :func:`pass_weight`."""

    def __init__(self, model: Any, within: float):
        self.model, self.within = model, float(within)

    def __getattr__(self, name: str) -> Any:  # anchors, viewpoint... as the model declares them
        return getattr(self.model, name)

    def final_batch(self, movers: list[np.ndarray], anchors: Any, size: float, **context) -> np.ndarray:
        p = np.asarray(self.model.final_batch(movers, anchors, size, **context), float)
        return p * pass_weight(movers, anchors, size, self.within)

    def curve(self, mover: np.ndarray, anchor: np.ndarray, size: float, **context) -> np.ndarray:
        return self.model.curve(mover, anchor, size, **context)


__all__ = ["PassScorer", "pass_weight", "SCALE_SIDES"]
