"""The fallback judge: the action's own progress model, for actions nobody wrote rules for.

It is not independent of the planner (which maximises the same model), and its verdicts say so:
``judge`` is "progress-model" and the reason names the action.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .base import Verdict

THRESHOLD = 0.5
"""Final progress at or above which the progress-model judge calls a motion a success."""


class LearnedJudge:
    """Success when the action's learned progress at the end of the motion reaches ``threshold``."""

    name = "progress-model"
    reads_outlines = True  # its features measure gaps between the objects' real footprints

    def __init__(self, action: str, model: Any, threshold: float = THRESHOLD):
        self.action, self.model, self.threshold = action, model, float(threshold)

    def judge(self, mover: np.ndarray, anchor: np.ndarray, size: float, *,
              final_progress: float | None = None, anchors: list | None = None,
              viewer: np.ndarray | None = None, outlines: list[np.ndarray] | None = None) -> Verdict:
        kw: dict[str, Any] = {} if viewer is None else {"viewer": viewer}
        if anchors is not None and len(anchors) > 1:
            kw["more_anchors"] = list(anchors[1:])
        if outlines is not None and getattr(self.model, "reads_outlines", False):
            kw["outlines"] = outlines
        fp = float(self.model.final(mover, anchor, size, **kw)) if final_progress is None else float(final_progress)
        return Verdict(fp >= self.threshold, fp,
                       f"no rule-based judge for the plugin action {self.action}; its own progress model gives "
                       f"{fp:.2f} at the end (success at {self.threshold:.2f} or more)", self.name)
