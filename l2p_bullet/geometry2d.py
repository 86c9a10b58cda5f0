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
