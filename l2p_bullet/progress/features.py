"""Qualitative spatial features (QSR) of a mover relative to an anchor, per frame, in block units.

The paper describes a motion by four qualitative relations between the two blocks, per frame:
cardinal direction (CD), moving or static (MV), qualitative distance (QDC) and the qualitative
trajectory calculus QTC-C, plus their frame-to-frame changes and the blocks' relative rotation.
We compute those, and next to them the few continuous quantities they quantise (distance, gap,
bearing, the angle swept around the anchor), because an LSTM learns a graded progress far better
from "how close" than from "which distance bin" (a planner needs the gradient, people grade it).

Invariances (property-tested in ``tests/progress/test_features.py``):
- translating or rotating the whole scene changes nothing: bearings are measured from the first
  frame's anchor->mover direction, alignments in the anchor's own frame;
- scaling the scene together with the block size changes nothing: every length is divided by the
  block side before anything else.

Sequences are first resampled by **arc length** of the mover's path (``resample.py``: where the block
went, not how fast it was slid). Everything is vectorised numpy; a batch is a padded ``(B, T, F)`` array.

Two declarations of an action's manifest (:mod:`l2p_bullet.core.frames`; the configuration and the column
names are in ``qsr.py``) append columns; without them (the five built-in actions) the columns above are all
there is, unchanged:
- ``frame = "viewer"``: the mover's offset from the anchor as a viewer sees it (left/right, in front/
  behind), which turning the scene changes: "to the left of" needs it, and only it;
- ``anchors = 2``: the mover's place relative to the segment between the two anchors ("between").

**Footprints.** The ``gap`` columns (``gap``, ``gap2``) are the centre distance less how far each object
reaches from its centre towards the other: for cubes, unit squares of the mover's side (what the bundles were
trained on); where an object is not a cube, and the caller gives its real outline (``outlines``, metres, the
mover's first: ``judge.footprints.outlines_of``), how far that outline reaches in that direction
(``core.geometry.radial_extent``, which is the unit square's own formula for a unit square). Without
``outlines`` every column is what it always was, bit for bit. docs/learning.md says what this means for
the trained bundles.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.frames import viewer_offset
from ..core.geometry import radial_extent
from .qsr import TWO_ANCHOR_NAMES, VIEWER_NAMES, QSRConfig, feature_names
from .resample import MAX_BLOCKS, Resampled, resample, resample_batch

__all__ = [  # the features' own names, and those of qsr.py and resample.py, which callers read from here
    "MAX_BLOCKS", "TWO_ANCHOR_NAMES", "VIEWER_NAMES", "QSRConfig", "Resampled", "batch_features", "feature_names",
    "features", "features_batch", "motion_features", "resample", "resample_batch",
]


def _half_extent(phi: np.ndarray, outline: np.ndarray | None = None) -> np.ndarray:
    """Distance from an object's centre to its footprint's boundary in direction ``phi`` (its own frame):
    a unit square's without ``outline``, else that outline's (block units, own frame)."""
    if outline is None:
        return 0.5 / np.maximum(np.abs(np.cos(phi)), np.abs(np.sin(phi)))
    return radial_extent(outline, phi)


def features(mover: np.ndarray, anchor: np.ndarray, cfg: QSRConfig = QSRConfig(), *,
             more: list[np.ndarray] | None = None, viewer: np.ndarray | None = None,
             shapes: list[np.ndarray] | None = None) -> np.ndarray:
    """Per-frame features ``(K, F)`` of resampled poses in block units (see :func:`feature_names`);
    ``more`` the further anchors' resampled poses, ``viewer`` the viewpoint ``(2,)`` in block units,
    ``shapes`` the objects' outlines in block units (mover, anchors; None: unit squares)."""
    return features_batch(mover[None], anchor[None], np.array([len(mover)]), cfg,
                          more=None if more is None else [x[None] for x in more],
                          viewers=None if viewer is None else np.asarray(viewer, float)[None], shapes=shapes)[0]


def features_batch(movers: np.ndarray, anchors: np.ndarray, lengths: np.ndarray,
                   cfg: QSRConfig = QSRConfig(), *, more: list[np.ndarray] | None = None,
                   viewers: np.ndarray | None = None, shapes: list[np.ndarray] | None = None) -> np.ndarray:
    """Features of a padded batch ``(B, K, 3)`` of block-unit poses; frames past ``lengths`` are 0.
    ``shapes``: the outlines (K,2) of the mover and each anchor in block units, own frames, shared by the
    whole batch (None: unit squares, module docstring).

    Columns in :func:`feature_names` order: the continuous quantities, the one-hot cardinal direction
    and QDC bins, MV and QTC-C, then the frame-to-frame changes; then, when the configuration asks for
    them, the viewer-frame columns (``viewers`` (B, 2), block units) and the two-anchor columns
    (``more[0]`` (B, K, 3), the second anchor).
    """
    g = _Geometry.of(np.asarray(movers, float), np.asarray(anchors, float), np.asarray(lengths), cfg)
    n_cd = cfg.cd_sectors
    # cardinal direction: sector of the bearing, sector 0 = the side the mover started on
    cd = np.mod(np.round(g.rel / (2 * np.pi / n_cd)), n_cd).astype(int)
    qdc = np.searchsorted(np.asarray(cfg.qdc_edges), g.r)
    mv, qtc = _mv_qtc(g, cfg.moving_eps)
    d_dist = np.diff(g.rc, axis=1, prepend=g.rc[:, :1]) / cfg.spacing
    d_swept = np.diff(g.swept, axis=1, prepend=g.swept[:, :1]) / cfg.spacing
    d_rot = np.sin(np.diff(g.rot, axis=1, prepend=g.rot[:, :1]))
    shapes = [None, None, None] if shapes is None else list(shapes) + [None] * (3 - len(shapes))
    parts = [_continuous(g, cfg, shapes[0], shapes[1]), np.eye(n_cd)[cd], np.eye(len(cfg.qdc_edges) + 1)[qdc], mv, qtc,
             np.stack([np.clip(d_dist, -2, 2), np.clip(d_swept, -2, 2), d_rot,
                       _changed(cd), _changed(qdc), _changed(qtc)], axis=-1)]
    if cfg.viewer:
        if viewers is None:
            raise ValueError(f'the frame "{cfg.frame}" needs the viewpoint of every motion')
        parts.append(_viewer_columns(g, np.asarray(viewers, float).reshape(-1, 2), cfg))
    if cfg.anchors == 2:
        if not more:
            raise ValueError("two-anchor features need the second anchor's poses")
        parts.append(_two_anchor_columns(g, np.asarray(more[0], float), cfg, shapes[0], shapes[2]))
    out = np.concatenate(parts, axis=-1)
    out[~g.valid] = 0.0
    return out.astype(np.float32)


@dataclass
class _Geometry:
    """Per-frame geometry of a padded batch that several feature groups read (all ``(B, K)`` unless noted)."""

    m: np.ndarray  # (B, K, 3) mover poses, block units
    a: np.ndarray  # (B, K, 3) anchor poses
    valid: np.ndarray  # frames before each sequence's length
    d: np.ndarray  # (B, K, 2) anchor -> mover
    r: np.ndarray  # centre distance
    r_safe: np.ndarray  # the same, at least 1e-6
    rc: np.ndarray  # the same, clipped at cfg.max_distance
    rel: np.ndarray  # bearing measured from the first frame's: rotation invariant
    swept: np.ndarray  # the bearing unwrapped, 0 at the first frame and past the length
    phi_a: np.ndarray  # bearing in the anchor's frame
    phi_m: np.ndarray  # bearing of the anchor in the mover's frame
    rot: np.ndarray  # 4 x relative yaw: squares' rotation is only defined modulo 90 degrees
    step_m: np.ndarray  # (B, K, 2) mover's step from the previous frame
    step_a: np.ndarray  # (B, K, 2) anchor's step

    @classmethod
    def of(cls, m: np.ndarray, a: np.ndarray, lengths: np.ndarray, cfg: QSRConfig) -> _Geometry:
        K = m.shape[1]
        valid = np.arange(K)[None, :] < lengths[:, None]
        d = m[..., :2] - a[..., :2]
        r = np.linalg.norm(d, axis=-1)
        bearing = np.arctan2(d[..., 1], d[..., 0])  # world frame
        rel = bearing - bearing[:, :1]
        swept = np.unwrap(rel, axis=1)
        swept = np.where(valid, swept, 0.0)
        swept = swept - swept[:, :1]
        return cls(m, a, valid, d, r, np.maximum(r, 1e-6), np.minimum(r, cfg.max_distance), rel, swept,
                   bearing - a[..., 2], bearing + np.pi - m[..., 2], 4.0 * (m[..., 2] - a[..., 2]),
                   np.diff(m[..., :2], axis=1, prepend=m[:, :1, :2]), np.diff(a[..., :2], axis=1, prepend=a[:, :1, :2]))


def _continuous(g: _Geometry, cfg: QSRConfig, mover_shape: np.ndarray | None = None,
                anchor_shape: np.ndarray | None = None) -> np.ndarray:
    """The continuous columns (B, K, 15): how close, how far it turned, how aligned, how far it went."""
    B, K = g.r.shape
    gap = g.r - _half_extent(g.phi_a, anchor_shape) - _half_extent(g.phi_m, mover_shape)
    r0 = g.r_safe[:, :1]
    path = np.cumsum(np.linalg.norm(g.step_m, axis=-1), axis=1)
    disp = np.linalg.norm(g.m[..., :2] - g.m[:, :1, :2], axis=-1)
    first = np.zeros((B, K))
    first[:, 0] = 1.0
    mx = cfg.max_distance
    cont = [g.rc / 5.0, np.log(np.maximum(g.rc, 0.3)), np.clip(gap, -1.0, mx) / 5.0,
            np.clip(g.r - r0, -mx, mx) / 5.0, np.clip(np.log(g.r_safe / r0), -3, 3), np.cos(g.rel), np.sin(g.rel),
            np.clip(g.swept / np.pi, -4, 4), np.clip(np.abs(g.swept) / np.pi, 0, 4), np.cos(4.0 * g.phi_a),
            np.cos(g.rot), np.sin(g.rot), np.minimum(path, 4 * mx) / 10.0, np.minimum(disp, mx) / 5.0, first]
    return np.stack(cont, axis=-1)


def _clipped_change(x: np.ndarray, spacing: float) -> np.ndarray:
    """Change of a per-frame quantity (B, K) from the frame before, per block of travel, in [-2, 2]."""
    return np.clip(np.diff(x, axis=1, prepend=x[:, :1]) / spacing, -2, 2)


def _viewer_columns(g: _Geometry, viewers: np.ndarray, cfg: QSRConfig) -> np.ndarray:
    """The viewer-frame columns (B, K, 6) of :data:`VIEWER_NAMES`; ``viewers`` (B, 2) in block units."""
    lat, dep = viewer_offset(g.m[..., :2], g.a[..., :2], viewers[:, None, :])
    mx = cfg.max_distance
    return np.stack([np.clip(lat, -mx, mx) / 5.0, np.clip(dep, -mx, mx) / 5.0, dep / g.r_safe, lat / g.r_safe,
                     _clipped_change(lat, cfg.spacing), _clipped_change(dep, cfg.spacing)], axis=-1)


def _two_anchor_columns(g: _Geometry, c: np.ndarray, cfg: QSRConfig, mover_shape: np.ndarray | None = None,
                        second_shape: np.ndarray | None = None) -> np.ndarray:
    """The two-anchor columns (B, K, 8) of :data:`TWO_ANCHOR_NAMES`; ``c`` the second anchor (B, K, 3)."""
    b, m = g.a[..., :2], g.m[..., :2]
    e = c[..., :2] - b
    sep = np.linalg.norm(e, axis=-1)
    u = e / np.maximum(sep, 1e-6)[..., None]
    rel = m - b
    t = np.sum(rel * u, axis=-1) / np.maximum(sep, 1e-6)
    lateral = np.abs(rel[..., 0] * u[..., 1] - rel[..., 1] * u[..., 0])
    closest = b + np.clip(t, 0.0, 1.0)[..., None] * e
    seg = np.linalg.norm(m - closest, axis=-1)
    mid = np.linalg.norm(m - 0.5 * (b + c[..., :2]), axis=-1)
    d2 = m - c[..., :2]
    r2 = np.linalg.norm(d2, axis=-1)
    bearing2 = np.arctan2(d2[..., 1], d2[..., 0])
    gap2 = r2 - _half_extent(bearing2 - c[..., 2], second_shape) - _half_extent(bearing2 + np.pi - g.m[..., 2],
                                                                               mover_shape)
    mx = cfg.max_distance
    return np.stack([np.clip(t, -2.0, 3.0), np.minimum(lateral, mx) / 5.0, np.minimum(seg, mx) / 5.0,
                     np.minimum(mid, mx) / 5.0, np.minimum(r2, mx) / 5.0, np.clip(gap2, -1.0, mx) / 5.0,
                     np.minimum(sep, mx) / 5.0, _clipped_change(np.minimum(seg, mx), cfg.spacing)], axis=-1)


def _mv_qtc(g: _Geometry, eps: float) -> tuple[np.ndarray, np.ndarray]:
    """MV (B, K, 2: each block moving or static) and QTC-C (B, K, 4): k = moving towards (-) / away (+)
    from the other, l = to its left (-) / right (+), for the mover and the anchor."""
    u = g.d / g.r_safe[..., None]  # unit anchor->mover
    u_prev = np.concatenate([u[:, :1], u[:, :-1]], axis=1)

    def sign(v: np.ndarray) -> np.ndarray:
        return np.where(v > eps, 1.0, np.where(v < -eps, -1.0, 0.0))

    k_m = sign(np.sum(g.step_m * u_prev, axis=-1))
    k_a = sign(-np.sum(g.step_a * u_prev, axis=-1))
    l_m = sign(-(u_prev[..., 0] * g.step_m[..., 1] - u_prev[..., 1] * g.step_m[..., 0]))
    l_a = sign(u_prev[..., 0] * g.step_a[..., 1] - u_prev[..., 1] * g.step_a[..., 0])
    mv_m = (np.linalg.norm(g.step_m, axis=-1) > eps).astype(float)
    mv_a = (np.linalg.norm(g.step_a, axis=-1) > eps).astype(float)
    return np.stack([mv_m, mv_a], axis=-1), np.stack([k_m, k_a, l_m, l_a], axis=-1)


def _changed(x: np.ndarray) -> np.ndarray:
    """1 where a qualitative relation (B, K) or (B, K, n) differs from the frame before."""
    prev = np.concatenate([x[:, :1], x[:, :-1]], axis=1)
    diff = x != prev
    return (diff.any(axis=-1) if diff.ndim == 3 else diff).astype(float)


def motion_features(mover: np.ndarray, anchor: np.ndarray, size: float, cfg: QSRConfig = QSRConfig(), *,
                    more_anchors: list | None = None, viewer: np.ndarray | None = None,
                    outlines: list[np.ndarray] | None = None) -> tuple[np.ndarray, Resampled]:
    """Resample a metric motion and compute its features: ``(K, F)`` and the resampling.

    ``viewer`` is the viewpoint ``(2,)`` in the motion's metric frame (viewer-frame configurations);
    ``outlines`` the objects' real footprints in metres (module docstring), None for unit squares.
    """
    rs = resample(mover, anchor, size, cfg, more_anchors)
    v = None if viewer is None else np.asarray(viewer, float)[:2] / size
    return features(rs.mover, rs.anchor, cfg, more=rs.more or None, viewer=v, shapes=_in_blocks(outlines, size)), rs


def _in_blocks(outlines: list[np.ndarray] | None, size: float) -> list[np.ndarray] | None:
    """Outlines in metres as block units (None stays None: unit squares)."""
    return None if outlines is None else [np.asarray(o, float) / size for o in outlines]


def batch_features(movers: list[np.ndarray], anchors: list[np.ndarray] | np.ndarray, size: float,
                   cfg: QSRConfig = QSRConfig(), *, more_anchors: list | None = None,
                   viewer: np.ndarray | list | None = None, outlines: list[np.ndarray] | None = None
                   ) -> tuple[np.ndarray, np.ndarray, list[Resampled]]:
    """Resample every motion, pad, and compute features in one vectorised pass.

    Returns ``(B, K, F)`` features, ``(B,)`` lengths and the resamplings (to map back to input frames).
    ``anchors`` may be one pose ``(3,)`` shared by every motion, or one track/pose per motion; so may
    each entry of ``more_anchors``. ``viewer`` is one viewpoint ``(2,)`` (metres) for all, or one per motion.
    ``outlines``: the objects' real footprints in metres, mover first, shared by every motion (module
    docstring); None reads unit squares.
    """
    rss = resample_batch(movers, anchors, size, cfg, more_anchors)
    lengths = np.array([len(rs.arc) for rs in rss])
    K = int(lengths.max()) if len(rss) else 1
    M = np.zeros((len(rss), K, 3))
    A = np.zeros((len(rss), K, 3))
    X = [np.zeros((len(rss), K, 3)) for _ in more_anchors or []]
    for i, rs in enumerate(rss):
        n = lengths[i]
        M[i, :n], A[i, :n] = rs.mover, rs.anchor
        M[i, n:], A[i, n:] = rs.mover[-1], rs.anchor[-1]  # edge padding keeps diffs at 0
        for x, r in zip(X, rs.more, strict=True):
            x[i, :n], x[i, n:] = r, r[-1]
    viewers = None
    if viewer is not None:
        viewers = np.broadcast_to(np.asarray(viewer, float).reshape(-1, 2), (len(rss), 2))[:, :2] / size
    return (features_batch(M, A, lengths, cfg, more=X or None, viewers=viewers, shapes=_in_blocks(outlines, size)),
            lengths, rss)
