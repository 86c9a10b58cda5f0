"""The scoring API shared by the torch and the numpy progress models.

Both models differ only in ``forward_features`` (the LSTM ensemble's forward pass); resampling, feature
extraction and mapping resampled frames back to input frames are the same, so they live here once.
Torch-free: ``perform`` scores with the numpy model and must never import torch.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.contracts import hold_before
from ..core.frames import parse_frame
from .features import QSRConfig, batch_features


def shared_prefix(feats: np.ndarray, lengths: np.ndarray | None) -> tuple[np.ndarray, int]:
    """(lengths, P): how many leading frames every sequence of the batch shares.

    A planner's candidates all extend the same path: those P frames go through the LSTMs once, at batch
    size 1, and only the rest runs for the whole batch. Every sequence keeps at least its last frame.
    """
    B, K = feats.shape[:2]
    lengths = np.full(B, K) if lengths is None else np.asarray(lengths)
    P = 0
    if B > 1:
        same = np.all(feats == feats[:1], axis=(0, 2))
        P = K if same.all() else int(np.argmin(same))
        P = min(P, int(lengths.min()) - 1)
    return lengths, P


class ScoringMixin:
    """``final_batch``/``curve_batch``/``curve``/``final`` on top of a subclass's ``forward_features``.

    Every call takes two optional keywords, needed only by actions that declare them
    (:mod:`l2p_bullet.core.frames`): ``more_anchors``, one entry per further anchor (a two-anchor
    action's second reference object; the same forms as ``anchors``), and ``viewer``, the viewpoint
    ``(2,)`` in the motions' metric frame (a viewer-frame action; default: its declared viewpoint in the
    scene frame, the robot's base for ``frame = "viewer"``). A third, ``outlines``, gives the objects' real
    footprints (metres, own frames, the mover's first) where one is not a cube: the gap columns measure
    them (:mod:`l2p_bullet.progress.features`); without it they read unit squares, as the bundles were trained.
    """

    qsr_cfg: QSRConfig
    # False: the bundles were trained on unit squares; fed real outlines, the planner slid a tray onto its anchor
    # (it rode up 3.5 mm: not a slide). A model trained on outlines sets True; the rule judges read them anyway.
    reads_outlines = False

    def forward_features(self, feats: np.ndarray, lengths: np.ndarray | None = None) -> np.ndarray:
        raise NotImplementedError

    @property
    def anchors(self) -> int:
        """Reference objects the model reads: 1, or 2 for a two-anchor action."""
        return self.qsr_cfg.anchors

    @property
    def viewpoint(self) -> np.ndarray | None:
        """The declared viewpoint in the scene frame (metres), None for a relative model."""
        return parse_frame(self.qsr_cfg.frame).viewpoint_xy()

    def _run(self, movers: list[np.ndarray], anchors: Any, size: float, more_anchors: list | None = None,
             viewer: Any = None, outlines: list | None = None):
        movers = [np.asarray(m, float) for m in movers]
        n_more = self.qsr_cfg.anchors - 1
        if len(more_anchors or []) != n_more:
            raise ValueError(f"this progress model reads {n_more + 1} anchor(s); got {len(more_anchors or []) + 1}")
        kw: dict[str, Any] = {}
        if n_more:
            kw["more_anchors"] = more_anchors
        if self.qsr_cfg.viewer:
            kw["viewer"] = self.viewpoint if viewer is None else viewer
        if outlines is not None:
            kw["outlines"] = outlines
        feats, lengths, rss = batch_features(movers, anchors, size, self.qsr_cfg, **kw)
        return self.forward_features(feats, lengths), lengths, rss

    def final_batch(self, movers: list[np.ndarray], anchors: Any, size: float, *, more_anchors: list | None = None,
                    viewer: Any = None, outlines: list | None = None) -> np.ndarray:
        """Final progress ``(B,)`` of every motion, in one forward pass for the whole batch."""
        if len(movers) == 0:
            return np.zeros(0)
        out, lengths, _ = self._run(movers, anchors, size, more_anchors, viewer, outlines)
        return out[np.arange(len(lengths)), lengths - 1]

    def curve_batch(self, movers: list[np.ndarray], anchors: Any, size: float, *, more_anchors: list | None = None,
                    viewer: Any = None, outlines: list | None = None) -> list[np.ndarray]:
        """Per-input-frame progress of every motion (a frame gets the value of the last resampled frame
        at or before its arc length: frames where the block stands still repeat the value)."""
        if len(movers) == 0:
            return []
        out, lengths, rss = self._run(movers, anchors, size, more_anchors, viewer, outlines)
        curves = []
        for i, rs in enumerate(rss):
            k = np.searchsorted(rs.arc, rs.input_arc + 1e-9, side="right") - 1
            curves.append(out[i, np.clip(k, 0, lengths[i] - 1)])
        return curves

    def curve(self, mover: np.ndarray, anchor: np.ndarray, size: float, *, more_anchors: list | None = None,
              viewer: Any = None, outlines: list | None = None) -> np.ndarray:
        """Per-input-frame progress ``(T,)`` of one motion; ``anchor`` is ``(T, 3)`` or one pose ``(3,)``."""
        anchor = np.asarray(anchor, float)
        return self.curve_batch([mover], anchor if anchor.ndim == 1 else [anchor], size,
                                more_anchors=_one(more_anchors), viewer=viewer, outlines=outlines)[0]

    def resampled(self, mover: np.ndarray, anchor: np.ndarray, size: float, *, more_anchors: list | None = None,
                  viewer: Any = None, outlines: list | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Progress on the model's own arc-length resampling of one motion, and each resampled frame's
        share of the motion's arc length (0 to 1): the ramp the training label follows on an event, so a
        benchmark can compare the whole curve with it (docs/learning.md, recognition's third pass)."""
        anchor = np.asarray(anchor, float)
        out, lengths, rss = self._run([mover], anchor if anchor.ndim == 1 else [anchor], size,
                                      _one(more_anchors), viewer, outlines)
        arc = np.asarray(rss[0].arc, float)
        share = arc / arc[-1] if arc[-1] > 0 else np.linspace(0.0, 1.0, len(arc))
        return out[0, : lengths[0]], share

    def final(self, mover: np.ndarray, anchor: np.ndarray, size: float, *, more_anchors: list | None = None,
              viewer: Any = None, outlines: list | None = None) -> float:
        anchor = np.asarray(anchor, float)
        return float(self.final_batch([mover], anchor if anchor.ndim == 1 else [anchor], size,
                                      more_anchors=_one(more_anchors), viewer=viewer, outlines=outlines)[0])


def curve_from(model: Any, first: int, mover: np.ndarray, anchor: np.ndarray, size: float, *,
               more_anchors: list | None = None, **kw: Any) -> np.ndarray:
    """Per-frame progress ``(T,)`` of a motion whose action begins at frame ``first`` (after an approach
    slide, trajectory.json's ``action_from``): the model reads only frames ``first`` on, as the planner
    scored them, and the frames before hold the action's first value (as plan.json's lead-in does).
    ``anchor`` and each of ``more_anchors`` are tracks (T,3) or single poses (3,)."""

    def cut(x: Any) -> Any:
        a = np.asarray(x, float)
        return a[first:] if a.ndim == 2 else a

    more = {"more_anchors": [cut(a) for a in more_anchors]} if more_anchors else {}
    return hold_before(model.curve(np.asarray(mover, float)[first:], cut(anchor), size, **more, **kw), first)


def _one(more_anchors: list | None) -> list | None:
    """One motion's further anchors (each a pose or a track) in the batch calls' form."""
    if more_anchors is None:
        return None
    return [
        x if np.asarray(x).ndim == 1 else [np.asarray(x, float)] for x in (np.asarray(a, float) for a in more_anchors)
    ]
