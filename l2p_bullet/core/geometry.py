"""Small, dependency-free 2-D geometry shared by the scene, the 2-D world, the judges and the learning code."""

from __future__ import annotations

import numpy as np


def _axes(poly: np.ndarray) -> np.ndarray:
    edges = np.roll(poly, -1, axis=0) - poly
    normals = np.stack([-edges[:, 1], edges[:, 0]], axis=1)
    return normals / np.linalg.norm(normals, axis=1, keepdims=True)


def polygons_overlap(a: np.ndarray, b: np.ndarray, margin: float = 0.0) -> bool:
    """Separating-axis test for two convex polygons (K,2); touching within ``margin`` counts as overlap.

    ``margin`` > 0 inflates the test: polygons closer than ``margin`` along some axis overlap.
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    for axis in np.concatenate([_axes(a), _axes(b)]):
        pa, pb = a @ axis, b @ axis
        if pa.max() + margin <= pb.min() + 1e-12 or pb.max() + margin <= pa.min() + 1e-12:
            return False
    return True


def wrap_angle(a: np.ndarray | float) -> np.ndarray | float:
    """Wrap angles to (-pi, pi]."""
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def moving_average(poses: np.ndarray, window: int) -> np.ndarray:
    """Centred moving average of a pose sequence (N,3), edges padded with the end poses, yaw unwrapped first.

    Shared by the replay (capture jitter would read as tight curves and slow the arm) and the training set
    (jitter would read as motion); callers decide what to do with short sequences and the end points.
    """
    p = np.array(poses, dtype=float)
    p[:, 2] = np.unwrap(p[:, 2])
    kernel = np.ones(window) / window
    pad = window // 2
    padded = np.pad(p, ((pad, window - 1 - pad), (0, 0)), mode="edge")
    return np.stack([np.convolve(padded[:, j], kernel, mode="valid") for j in range(3)], axis=1)


def unwrapped_bearing(d: np.ndarray) -> np.ndarray:
    """Bearing (radians) of offsets ``d`` (T, 2+) seen from the origin, unwrapped along the track."""
    return np.unwrap(np.arctan2(d[:, 1], d[:, 0]))


def swept_angle(points: np.ndarray, centre: np.ndarray | None = None) -> float:
    """Signed angle (radians) a point track (T, 2+) sweeps around ``centre`` (default the origin), frame to
    frame: positive counter-clockwise, a full circle is 2 pi, going out and back sweeps 0. One copy for
    the judges, the policy's features and the training set's turn labels. Frames must be dense enough
    that the track turns less than half a turn between two of them."""
    p = np.asarray(points, float)
    if len(p) < 2:
        return 0.0
    d = p[:, :2] if centre is None else p[:, :2] - np.asarray(centre, float)[:2]
    ang = unwrapped_bearing(d)
    return float(ang[-1] - ang[0])
