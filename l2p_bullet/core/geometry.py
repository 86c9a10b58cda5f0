"""Small, dependency-free 2-D geometry shared by the scene, the 2-D simulator and the evaluator."""

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
