"""Motions resampled by **arc length** of the mover's path (``spacing`` blocks apart), in block units: the
progress of "around" depends on where the block went, not on how fast a person slid it, and a planner's
straight moves given by their end points become frames like a demonstration's. The grid is fixed, so a path's
prefix resamples to the frames of the path itself (candidates extending one path share their prefix).

A motion is refused (:class:`~l2p_bullet.errors.MotionError`) before it is resampled when it cannot be in
bounded memory: non-finite poses, a block size that is not a positive number, or a motion that travels or
spreads beyond :data:`MAX_BLOCKS` block sides.

Apart from the features (``features.py``, which re-exports these names) because it is the step before them, with
its own question (where the frames fall, and whether a motion can be scored at all) and its own bounds; the
features read only the resampled poses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import MotionError
from .qsr import QSRConfig

MAX_BLOCKS = 1000.0
"""Longest path and widest spread of a motion, in block sides, that is scored. The human demonstrations
travel at most 29 block sides (59 with the training set's augmentations) and stay within 14 of the
anchor; the planner's paths within a 0.25 m disk. A motion beyond this is a unit mistake (millimetres
read as metres, a wrong block size): resampling it every 0.25 block would take gigabytes."""


@dataclass
class Resampled:
    """A motion resampled by arc length: poses in block units and where each input frame falls."""

    mover: np.ndarray  # (K, 3), x/y in blocks
    anchor: np.ndarray  # (K, 3)
    arc: np.ndarray  # (K,) arc length of each resampled frame (blocks)
    input_arc: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (T,) arc length of input frames
    times: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (K,) fractional input-frame index
    more: list[np.ndarray] = field(default_factory=list)  # (K, 3) per further anchor, blocks


def _as_track(poses: np.ndarray, n: int) -> np.ndarray:
    a = np.asarray(poses, dtype=float)
    if a.ndim == 1:
        a = np.repeat(a[None], n, axis=0)
    return a


def _tracks(anchors: list[np.ndarray] | np.ndarray, ms: list[np.ndarray], what: str = "anchor") -> list[np.ndarray]:
    """One ``(T,3)`` track per motion from one shared pose ``(3,)``, or one track/pose per motion."""
    shared = not isinstance(anchors, list)
    if shared and np.asarray(anchors).ndim != 1:
        anchors = [np.asarray(anchors, float)] if len(ms) == 1 else list(anchors)
        shared = False
    as_ = [_as_track(anchors if shared else anchors[i], len(m)) for i, m in enumerate(ms)]
    for m, a in zip(ms, as_, strict=True):
        if a.shape != m.shape:
            raise ValueError(f"{what} must be (3,) or {m.shape}, got {a.shape}")
    return as_


def resample_batch(movers: list[np.ndarray], anchors: list[np.ndarray] | np.ndarray, size: float,
                   cfg: QSRConfig = QSRConfig(), more_anchors: list | None = None) -> list[Resampled]:
    """Resample motions at arc lengths 0, spacing, 2 spacing, ... of the mover's path, plus its end.

    The grid is fixed (not stretched to fit each path), so a path's prefix resamples to the same frames
    as the path itself: scoring many candidates that extend one path shares their common prefix.
    ``anchors`` is one pose ``(3,)`` for all, or one ``(T,3)`` track or ``(3,)`` pose per motion;
    ``more_anchors`` one such entry per further anchor (two-anchor actions).
    Angles are unwrapped before interpolating. A motion that does not move becomes a single frame:
    standing still is never a long sequence. One vectorised pass for the whole batch.
    """
    ms = [np.asarray(m, dtype=float) for m in movers]
    for m in ms:
        if m.ndim != 2 or m.shape[1] != 3 or len(m) == 0:
            raise ValueError(f"mover must be (T, 3) poses, got shape {m.shape}")
    as_ = _tracks(anchors, ms)
    T = np.array([len(m) for m in ms])
    first = np.concatenate([[0], np.cumsum(T)[:-1]])
    M, A = np.concatenate(ms), np.concatenate(as_)
    _check_extent(M, A, T, first, size)
    M_raw = M
    M = np.column_stack([M[:, :2] / size, np.unwrap(M[:, 2])])
    A = np.column_stack([A[:, :2] / size, np.unwrap(A[:, 2])])
    step = np.linalg.norm(np.diff(M[:, :2], axis=0, prepend=M[:1, :2]), axis=1)
    step[first] = 0.0
    cum = np.cumsum(step)
    arc = cum - np.repeat(cum[first], T)  # per-path arc length of every input frame
    total = arc[first + T - 1]
    if not np.all(total <= MAX_BLOCKS):
        raise MotionError(f"the mover travels {float(np.max(total)):.3g} block sides (blocks of {size:.3g} m); at most "
                          f"{MAX_BLOCKS:g} are scored: are the poses in metres and the block size right?",
                          float(np.max(total)), MAX_BLOCKS)
    total = np.where(total < 1e-9, 0.0, total)
    # query arc lengths: the fixed grid below the total, then the total itself
    n_grid = np.where(total > 0, np.floor(total / cfg.spacing - 1e-9).astype(int) + 1, 0)
    K = n_grid + 1
    path_of_q = np.repeat(np.arange(len(ms)), K)
    k_in_path = np.arange(K.sum()) - np.repeat(np.concatenate([[0], np.cumsum(K)[:-1]]), K)
    q = np.where(k_in_path < n_grid[path_of_q], k_in_path * cfg.spacing, total[path_of_q])
    # one global monotone abscissa: paths separated by offsets, static frames by a tiny epsilon
    offset = np.concatenate([[0.0], np.cumsum(total + 1.0)[:-1]])
    local = np.arange(len(M)) - np.repeat(first, T)
    xs = arc + np.repeat(offset, T) + local * 1e-9
    t_glob = np.interp(q + offset[path_of_q] + 0.5e-9 * (q > 0), xs, np.arange(len(M), dtype=float))
    t_glob = np.clip(t_glob, first[path_of_q], (first + T - 1)[path_of_q])
    i0 = np.floor(t_glob).astype(int)
    i1 = np.minimum(i0 + 1, (first + T - 1)[path_of_q])
    w = (t_glob - i0)[:, None]
    Mq, Aq = M[i0] * (1 - w) + M[i1] * w, A[i0] * (1 - w) + A[i1] * w
    Xq = []
    for extra in more_anchors or []:
        X = np.concatenate(_tracks(extra, ms, "a further anchor"))
        _check_extent(M_raw, X, T, first, size)
        X = np.column_stack([X[:, :2] / size, np.unwrap(X[:, 2])])
        Xq.append(X[i0] * (1 - w) + X[i1] * w)
    out, qs = [], np.concatenate([[0], np.cumsum(K)])
    for i in range(len(ms)):
        sl = slice(qs[i], qs[i + 1])
        out.append(Resampled(Mq[sl], Aq[sl], q[sl], arc[first[i]:first[i] + T[i]], t_glob[sl] - first[i],
                             [x[sl] for x in Xq]))
    return out


def _check_extent(M: np.ndarray, A: np.ndarray, T: np.ndarray, first: np.ndarray, size: float) -> None:
    """Refuse (:class:`MotionError`) what cannot be scored in bounded memory: a block size that is not a
    positive number, non-finite poses, or poses farther than MAX_BLOCKS block sides from the anchor's start."""
    if not (isinstance(size, int | float | np.floating) and math.isfinite(size) and size > 0):
        raise MotionError(f"the block size must be a positive number of metres (got {size!r:.30})")
    if not (np.all(np.isfinite(M)) and np.all(np.isfinite(A))):
        raise MotionError("the motion contains non-finite poses (NaN or infinity)")
    ref = np.repeat(A[first, :2], T, axis=0)
    with np.errstate(over="ignore"):
        extent = max(float(np.max(np.abs(M[:, :2] - ref))), float(np.max(np.abs(A[:, :2] - ref)))) / size
    if not extent <= MAX_BLOCKS:
        raise MotionError(f"the motion spreads over {extent:.3g} block sides (blocks of {size:.3g} m); at most "
                          f"{MAX_BLOCKS:g} are scored: are the poses in metres and the block size right?",
                          extent, MAX_BLOCKS)


def resample(mover: np.ndarray, anchor: np.ndarray, size: float, cfg: QSRConfig = QSRConfig(),
             more_anchors: list | None = None) -> Resampled:
    """Resample one motion (see :func:`resample_batch`); ``anchor`` (and each of ``more_anchors``) is
    ``(T,3)`` or one pose ``(3,)``."""
    anchor = np.asarray(anchor, float)
    more = (
        None
        if more_anchors is None
        else [np.asarray(x, float) if np.asarray(x).ndim == 1 else [np.asarray(x, float)] for x in more_anchors]
    )
    return resample_batch([mover], anchor if anchor.ndim == 1 else [anchor], size, cfg, more)[0]

