"""Small, dependency-free 2-D geometry shared by the scene, the 2-D world, the judges and the learning code."""

from __future__ import annotations

import numpy as np


def edge_normals(polys: np.ndarray) -> np.ndarray:
    """Unit edge normals of polygons (..., K, 2) -> (..., K, 2): the separating axes a polygon contributes. A
    zero-length edge (``convex_hull`` makes none) gives a zero vector instead of NaN."""
    e = np.roll(polys, -1, axis=-2) - polys
    n = np.stack([-e[..., 1], e[..., 0]], axis=-1)
    return n / np.maximum(np.linalg.norm(n, axis=-1, keepdims=True), 1e-12)


def polygons_overlap(a: np.ndarray, b: np.ndarray, margin: float = 0.0) -> bool:
    """Separating-axis test for two convex polygons (K,2); touching within ``margin`` counts as overlap.

    ``margin`` > 0 inflates the test: polygons closer than ``margin`` along some axis overlap.
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    for axis in np.concatenate([edge_normals(a), edge_normals(b)]):
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


def convex_hull(points: np.ndarray) -> np.ndarray:
    """Convex hull (K,2) of 2-D points, counter-clockwise, without repeated or collinear points (monotone chain)."""
    pts = sorted({(round(float(x), 12), round(float(y), 12)) for x, y in np.asarray(points, float).reshape(-1, 2)})
    if len(pts) <= 2:
        return np.array(pts, float)

    def cross(o, a, b) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list = []
    upper: list = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1], float)


def separation(polys: np.ndarray, other: np.ndarray) -> np.ndarray:
    """Separating-axis gap between each convex polygon of ``polys`` (M,K,2) and the convex polygon ``other``
    (L,2): the largest separation along their edge normals, negative when they overlap (metres)."""
    polys = np.asarray(polys, float)
    other = np.asarray(other, float)
    axes = np.concatenate([edge_normals(polys), np.broadcast_to(edge_normals(other), (len(polys), len(other), 2))],
                          axis=1)  # (M,A,2)
    pm = np.einsum("mad,mkd->mak", axes, polys)
    po = np.einsum("mad,ld->mal", axes, other)
    gap = np.maximum(po.min(-1) - pm.max(-1), pm.min(-1) - po.max(-1))
    return gap.max(-1)


def posed_separation(outline: np.ndarray, poses: np.ndarray, other: np.ndarray) -> np.ndarray:
    """``separation`` of the convex ``outline`` (K,2) placed at each of ``poses`` (N,3: x, y, yaw) from the convex
    polygon ``other`` (L,2), without placing N polygons.

    Why: on a dense grid of poses (feasibility's blocked-around sweep, up to ~10^5 poses against each nearby
    object) placing every polygon and projecting every vertex on every axis was a third of a stress run's time
    (profiled on benchmarks/bench_objects.py). Each axis and both polygons' extents along it depend only on the
    yaw, and a grid has few yaws: they are computed once per distinct yaw, and each pose only adds its
    translation's projection. The numbers are ``separation``'s up to rounding (tests/core/test_geometry.py).
    """
    outline = np.asarray(outline, float)
    other = np.asarray(other, float)
    poses = np.asarray(poses, float).reshape(-1, 3)
    yaws, which = np.unique(poses[:, 2], return_inverse=True)
    c, s = np.cos(yaws)[:, None], np.sin(yaws)[:, None]
    turned = np.stack([outline[None, :, 0] * c - outline[None, :, 1] * s,
                       outline[None, :, 0] * s + outline[None, :, 1] * c], axis=-1)  # (Y,K,2) about the origin
    axes = np.concatenate([edge_normals(turned), np.broadcast_to(edge_normals(other), (len(yaws), len(other), 2))],
                          axis=1)  # (Y,A,2)
    pm = np.einsum("yad,ykd->yak", axes, turned)
    po = np.einsum("yad,ld->yal", axes, other)
    below = (po.min(-1) - pm.max(-1))[which]  # (N,A): other's low end minus the turned outline's high end
    above = (pm.min(-1) - po.max(-1))[which]
    shift = np.einsum("nad,nd->na", axes[which], poses[:, :2])  # each pose's translation along each axis
    return np.maximum(below - shift, above + shift).max(-1)


def nearest_centres(m, a) -> float:
    """A bound (m) the two objects' centres are never nearer than: the sum of their footprints' inradii (two
    cubes: the half sides' sum, written as it always was so a cube scene's numbers stay bit-identical)."""
    if m.shape == "cube" and a.shape == "cube":
        return (m.size + a.size) / 2
    return m.inradius + a.inradius


def radial_extent(outline: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Distance from an outline's origin to its boundary in the directions ``phi`` (radians, the outline's
    frame; any shape of array), in the outline's units. The origin is inside (a convex outline around the
    object's centre of mass). For a unit square it is ``0.5 / max(|cos phi|, |sin phi|)``."""
    poly = np.asarray(outline, float)
    e = np.roll(poly, -1, axis=0) - poly
    n = np.column_stack([e[:, 1], -e[:, 0]]) / np.maximum(np.linalg.norm(e, axis=1), 1e-15)[:, None]
    n *= np.where(np.sum(n * poly, axis=1) < 0, -1.0, 1.0)[:, None]  # outward, whichever way the outline turns
    h = np.sum(n * poly, axis=1)  # each edge's distance from the origin
    phi = np.asarray(phi, float)
    dots = np.cos(phi)[..., None] * n[:, 0] + np.sin(phi)[..., None] * n[:, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(dots > 1e-12, h / dots, np.inf)
    return r.min(axis=-1)
