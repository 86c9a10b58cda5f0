"""A model that reads squares asked about objects that are not squares: each pose moved to where two squares have
the real gap.

The built-in progress models read every object as a square of the mover's side (they were trained on people's
equal squares, and fed real outlines they planned a tray onto its anchor: docs/learning.md). Near an object wider
than that square (a 16 cm bottle 5.5 cm across beside a 4 cm cube) the square's gap is larger than the real one by
the difference of their reaches, so the closest the hand lets the mover come still reads as half a block apart:
the model never rates it "next to", and the search settles wherever the model overrates some other path (the
bottle's "next to" ended 2.2 blocks away).

So the model is shown the motion it was trained on: every mover pose is moved along its bearing from the anchor by
the difference between the real reaches (the mover's outline towards the anchor plus the anchor's towards the
mover, ``core.geometry.radial_extent``) and the squares' reaches in the same directions. The gap the model reads is
then the real gap, and its distance, bearing, turn and step columns are those of two squares that far apart; the
model itself is unchanged. Among cubes nothing is moved (:func:`l2p_bullet.judge.footprints.outlines_of` gives no
outlines), so cube scenes plan exactly as before.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.geometry import radial_extent


def _square_reach(phi: np.ndarray) -> np.ndarray:
    """A unit square's reach from its centre in direction ``phi`` (its own frame)."""
    return 0.5 / np.maximum(np.abs(np.cos(phi)), np.abs(np.sin(phi)))


def as_squares(mover: np.ndarray, anchor: np.ndarray, size: float, outlines: list[np.ndarray]) -> np.ndarray:
    """The mover's poses (T,3, metres) moved along their bearing from the anchor (a pose (3,) or one per frame)
    so that two squares of side ``size`` there have the gap the real ``outlines`` (mover's, anchor's: metres, own
    frames) have at the poses given. Yaws are kept."""
    m = np.array(mover, float).reshape(-1, 3)
    a = np.asarray(anchor, float)
    a = np.broadcast_to(a, m.shape) if a.ndim == 1 else a.reshape(-1, 3)
    rel = m[:, :2] - a[:, :2]
    d = np.hypot(rel[:, 0], rel[:, 1])
    bearing = np.arctan2(rel[:, 1], rel[:, 0])
    to_mover, to_anchor = bearing - a[:, 2], bearing + np.pi - m[:, 2]
    real = radial_extent(outlines[1], to_mover) + radial_extent(outlines[0], to_anchor)
    square = size * (_square_reach(to_mover) + _square_reach(to_anchor))
    far = np.maximum(d - (real - square), 1e-6)
    m[:, :2] = a[:, :2] + rel * (far / np.maximum(d, 1e-12))[:, None]
    return m


class SquaresScorer:
    """The action's progress model asked about every motion as two squares at the motion's real gaps
    (:func:`as_squares`): a one-anchor model that does not read outlines, in a scene where the mover or the
    anchor is not a cube."""

    def __init__(self, model: Any, outlines: list[np.ndarray]):
        self.model, self.outlines = model, [np.asarray(o, float) for o in outlines[:2]]

    def __getattr__(self, name: str) -> Any:  # anchors, viewpoint... as the model declares them
        return getattr(self.model, name)

    def _anchor(self, anchors: Any, i: int) -> Any:
        a = np.asarray(anchors, float) if not isinstance(anchors, list) else None
        return anchors[i] if a is None else a

    def final_batch(self, movers: list[np.ndarray], anchors: Any, size: float, **context) -> np.ndarray:
        moved = [as_squares(m, self._anchor(anchors, i), size, self.outlines) for i, m in enumerate(movers)]
        return self.model.final_batch(moved, anchors, size, **context)

    def curve(self, mover: np.ndarray, anchor: np.ndarray, size: float, **context) -> np.ndarray:
        return self.model.curve(as_squares(mover, anchor, size, self.outlines), anchor, size, **context)


def squares_scorer(model: Any, outlines: list[np.ndarray] | None, anchors: int = 1) -> Any:
    """``model`` wrapped in :class:`SquaresScorer` where it needs it: it reads squares (``reads_outlines``
    False), it reads one anchor, and ``outlines`` (``judge.footprints.outlines_of``: None among cubes) are given."""
    if outlines is None or anchors != 1 or getattr(model, "reads_outlines", False):
        return model
    return SquaresScorer(model, outlines)
