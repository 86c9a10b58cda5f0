"""A model that reads squares asked about an anchor that is not one: each pose moved to where the square it reads
has the real anchor's gap.

The built-in progress models read the anchor as a square of the mover's side, whatever the anchor is (they are
trained on people's equal squares, and fed real outlines they plan a tray onto its anchor: docs/learning.md).
Beside an anchor wider than that square (a 16 cm bottle 5.6 cm across beside a 4 cm cube) the square's gap is
larger than the real one by the difference of their reaches, so the closest the hand lets the mover come still
reads as half a block apart: the model never rates it "next to", and the search settles wherever the model
overrates some other path, blocks away.

So the model is shown the motion it was trained on: every mover pose is moved along its bearing from the anchor by
the difference between the anchor's real reach towards it (its outline, ``core.geometry.radial_extent``) and the
square's reach in the same direction. The gap the model reads is then the gap to the real anchor, and its
distance, bearing, turn and step columns are those of a square anchor that far away; the model itself is
unchanged. The mover is read as the square of its own size, as before. Only an anchor that is not a cube is read
so: cube anchors, and so every scene of cubes, plan exactly as before.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.geometry import radial_extent


def _square_reach(phi: np.ndarray) -> np.ndarray:
    """A unit square's reach from its centre in direction ``phi`` (its own frame)."""
    return 0.5 / np.maximum(np.abs(np.cos(phi)), np.abs(np.sin(phi)))


def as_squares(mover: np.ndarray, anchor: np.ndarray, size: float, outline: np.ndarray) -> np.ndarray:
    """The mover's poses (T,3, metres) moved along their bearing from the anchor (a pose (3,) or one per frame)
    so that a square anchor of side ``size`` is as far from each as the anchor's real ``outline`` (metres, its own
    frame) is from the pose given. Yaws are kept."""
    m = np.array(mover, float).reshape(-1, 3)
    a = np.asarray(anchor, float)
    a = np.broadcast_to(a, m.shape) if a.ndim == 1 else a.reshape(-1, 3)
    rel = m[:, :2] - a[:, :2]
    d = np.hypot(rel[:, 0], rel[:, 1])
    to_mover = np.arctan2(rel[:, 1], rel[:, 0]) - a[:, 2]
    far = np.maximum(d - (radial_extent(outline, to_mover) - size * _square_reach(to_mover)), 1e-6)
    m[:, :2] = a[:, :2] + rel * (far / np.maximum(d, 1e-12))[:, None]
    return m


class SquaresScorer:
    """The action's progress model asked about every motion as if the anchor were the square it reads, at the
    real anchor's gaps (:func:`as_squares`)."""

    def __init__(self, model: Any, outline: np.ndarray):
        self.model, self.outline = model, np.asarray(outline, float)

    def __getattr__(self, name: str) -> Any:  # anchors, viewpoint... as the model declares them
        return getattr(self.model, name)

    def final_batch(self, movers: list[np.ndarray], anchors: Any, size: float, **context) -> np.ndarray:
        each = (lambda i: anchors[i]) if isinstance(anchors, list) else (lambda i: anchors)
        moved = [as_squares(m, each(i), size, self.outline) for i, m in enumerate(movers)]
        return self.model.final_batch(moved, anchors, size, **context)

    def curve(self, mover: np.ndarray, anchor: np.ndarray, size: float, **context) -> np.ndarray:
        return self.model.curve(as_squares(mover, anchor, size, self.outline), anchor, size, **context)


def squares_scorer(model: Any, anchor: Any, anchors: int = 1) -> Any:
    """``model`` wrapped in :class:`SquaresScorer` where it needs it: it reads squares (``reads_outlines``
    False), one anchor (``anchors``), and the ``anchor`` object (a ``SceneObject``) is not a cube."""
    if anchors != 1 or getattr(anchor, "shape", "cube") == "cube" or getattr(model, "reads_outlines", False):
        return model
    return SquaresScorer(model, anchor.footprint(np.zeros(3)))
