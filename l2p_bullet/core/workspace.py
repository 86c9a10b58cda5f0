"""The workspace: where every block centre and every planned path point must lie (``core/scene.py``).

It is the scene's disk (``center``, ``radius``: :data:`DISK_RADIUS`, 0.35 m around the table's centre) and, for
an arm whose reach ring does not hold the disk, the disk *intersected with its ring* (``ring`` = base x, base y,
near, far; ``arms/fit.py: fit_workspace``): no shipped arm's ring holds the 0.35 m disk, so
every arm plans in its ring-cut disk. Cutting, rather than shrinking the disk about its centre until the ring
holds it (0.17 m for the KUKA), keeps what the arm reaches.

What was drawn, trained or chosen on the 0.25 m disk stays on it: seeded random starts are drawn in
:meth:`Workspace.starts` (:data:`START_RADIUS`, the same scenes for the same seeds), and the learned policy's
features divide by ``planning/policy.py: FEATURE_RADIUS``.

The ring's inner hole makes the region non-convex: a straight move between two points inside it may cut
through the hole, so a segment is inside only when its closest approach to the base is at least ``near``
(:meth:`Workspace.segments_inside`; the disk and the ring's outer circle are convex, so for them the end
points suffice). Every caller asks this class rather than measuring distances to the centre itself, so the
geometry lives in one place (tests/core/test_workspace.py). With ``ring=None`` every method computes what
the callers computed before, in the same floating-point operations.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

_TOL = 1e-9
"""Slack (m) every membership test allows, as the disk test always has."""

DISK_RADIUS = 0.35
"""The planning disk's radius (m) about the table's centre, before an arm's ring cuts it. Measured, not tuned
(``benchmarks/measure_disk.py``, docs/arms.md): every shipped arm reaches every probe of a 0.30,
0.35 or 0.38 m disk cut by its ring, pointing down, at both reach heights and its wrist range; 0.38 m would put a
4 cm cube turned 45 degrees at the rim 8 mm over the table's edge (half side 0.4 m), 0.35 m keeps every cube up
to 6 cm on the table at any yaw."""

START_RADIUS = 0.25
"""Where seeded random starts are drawn (m): the disk every benchmark and evaluation scene set was drawn in before
the planning disk grew, kept so that the same seeds give byte-identical starts (:meth:`Workspace.starts`)."""


@dataclass(frozen=True)
class Workspace:
    """The disk the gripper reaches pointing down at block height, and for an arm whose reach ring does not
    hold the disk, that ring: ``ring`` = (base x, base y, near, far) metres (see the module docstring)."""

    center: tuple[float, float] = (0.0, 0.0)
    radius: float = DISK_RADIUS
    ring: tuple[float, float, float, float] | None = None

    # --- distances ---------------------------------------------------------------------------------
    def _points(self, points: np.ndarray) -> np.ndarray:
        return np.asarray(points, dtype=float).reshape(-1, 2)

    def _base_d(self, p: np.ndarray) -> np.ndarray:
        bx, by = self.ring[0], self.ring[1]
        return np.hypot(p[:, 0] - bx, p[:, 1] - by)

    def contains(self, points: np.ndarray, margin: float = 0.0) -> np.ndarray:
        """Per point (flattened to (N,)): inside the region shrunk by ``margin``."""
        p = self._points(points)
        d = np.hypot(p[:, 0] - self.center[0], p[:, 1] - self.center[1])
        ok = d <= self.radius - margin + _TOL
        if self.ring is not None:
            db = self._base_d(p)
            ok &= (db >= self.ring[2] + margin - _TOL) & (db <= self.ring[3] - margin + _TOL)
        return ok

    def clearance(self, points: np.ndarray) -> np.ndarray:
        """Per point: its distance to the region's boundary, positive inside, negative outside. Inside it is
        exact (the least of the distances to the disk's rim and the ring's two circles); outside its size is
        at most the distance to the region (never more: a test ``clearance >= -slack`` keeps every point
        within ``slack`` of the region, which is what the refusals that favour the arm need)."""
        p = self._points(points)
        out = self.radius - np.hypot(p[:, 0] - self.center[0], p[:, 1] - self.center[1])
        if self.ring is not None:
            db = self._base_d(p)
            out = np.minimum(out, np.minimum(db - self.ring[2], self.ring[3] - db))
        return out

    def segments_inside(self, start: np.ndarray, ends: np.ndarray, margin: float = 0.0) -> np.ndarray:
        """Per straight segment from ``start`` (2,) to each of ``ends`` (M,2): every point of it is inside
        (both end points, and with a ring its closest approach to the base at least ``near``)."""
        a = np.asarray(start, float).reshape(2)
        b = self._points(ends)
        ok = self.contains(b, margin) & bool(self.contains(a, margin)[0])
        if self.ring is None or not ok.any():
            return ok
        base = np.array(self.ring[:2])
        ab = b - a
        t = np.clip(((base - a) @ ab.T) / np.maximum((ab * ab).sum(1), 1e-18), 0.0, 1.0)
        closest = a + t[:, None] * ab
        return ok & (np.hypot(closest[:, 0] - base[0], closest[:, 1] - base[1]) >= self.ring[2] + margin - _TOL)

    def path_inside(self, path: np.ndarray, margin: float = 0.0) -> int | None:
        """The index of the first waypoint of ``path`` (N,>=2) whose straight move from the one before leaves
        the region (0: the first waypoint itself is outside), or None when the whole path stays inside."""
        p = np.asarray(path, float)[:, :2]
        inside = self.contains(p, margin)
        if not inside.all():
            return int(np.argmin(inside))
        if self.ring is None:
            return None
        for k in range(1, len(p)):
            if not self.segments_inside(p[k - 1], p[k:k + 1], margin)[0]:
                return k
        return None

    # --- points of the region --------------------------------------------------------------------------
    def _circles(self, margin: float) -> list[tuple[np.ndarray, float, bool]]:
        """(centre, radius, region inside it?) of each boundary circle, shrunk by ``margin``."""
        out = [(np.array(self.center, float), self.radius - margin, True)]
        if self.ring is not None:
            base = np.array(self.ring[:2], float)
            out += [(base, self.ring[3] - margin, True), (base, self.ring[2] + margin, False)]
        return out

    def _corners(self, margin: float) -> np.ndarray:
        """Where two boundary circles cross (K,2)."""
        circles = self._circles(margin)
        out = []
        for i in range(len(circles)):
            for j in range(i + 1, len(circles)):
                (c1, r1, _), (c2, r2, _) = circles[i], circles[j]
                d = float(np.hypot(*(c2 - c1)))
                if d < 1e-12 or d > r1 + r2 or d < abs(r1 - r2):
                    continue
                x = (d * d + r1 * r1 - r2 * r2) / (2 * d)
                h = float(np.sqrt(max(r1 * r1 - x * x, 0.0)))
                u = (c2 - c1) / d
                out += [c1 + x * u + h * np.array([-u[1], u[0]]), c1 + x * u - h * np.array([-u[1], u[0]])]
        return np.array(out).reshape(-1, 2)

    def nearest_inside(self, points: np.ndarray, margin: float = 0.0) -> np.ndarray:
        """Per point (N,2): the nearest point of the region shrunk by ``margin`` (the point itself when it is
        inside). Exact: the nearest point lies on a boundary arc (the point's radial projection onto that
        arc's circle) or where two circles cross. ValueError when the shrunk region is empty."""
        p = self._points(points)
        cands = [p[:, None, :]]
        for c, r, _ in self._circles(margin):
            v = p - c
            n = np.hypot(v[:, 0], v[:, 1])[:, None]
            towards = np.array(self.center, float) - c  # a point at a circle's centre: project along this
            fallback = towards / np.hypot(*towards) if np.hypot(*towards) > 1e-12 else np.array([1.0, 0.0])
            u = np.where(n > 1e-12, v / np.maximum(n, 1e-12), fallback)
            cands.append((c + r * u)[:, None, :])
        corners = self._corners(margin)
        if len(corners):
            cands.append(np.broadcast_to(corners, (len(p), len(corners), 2)))
        cands = np.concatenate(cands, axis=1)  # (N, K, 2)
        ok = self.contains(cands.reshape(-1, 2), margin - 1e-7).reshape(cands.shape[:2])
        if not ok.any(1).all():
            raise ValueError("the workspace is empty")
        d = np.where(ok, np.hypot(*(cands - p[:, None, :]).transpose(2, 0, 1)), np.inf)
        return cands[np.arange(len(p)), np.argmin(d, axis=1)]

    def farthest_from(self, point: np.ndarray) -> tuple[float, np.ndarray]:
        """(distance, point): the point of the region farthest from ``point`` (2,). Exact: it lies on a
        boundary arc where the line through ``point`` and that arc's centre meets it, or where two circles
        cross. With no ring this is the disk's radius plus the distance to its centre."""
        q = np.asarray(point, float).reshape(2)
        cands = []
        for c, r, _ in self._circles(0.0):
            v = c - q
            n = float(np.hypot(*v))
            u = v / n if n > 1e-12 else np.array([1.0, 0.0])
            cands += [c + r * u, c - r * u]
        cands = np.concatenate([np.array(cands), self._corners(0.0)])
        cands = cands[self.contains(cands, -1e-7)]
        if not len(cands):
            raise ValueError("the workspace is empty")
        d = np.hypot(cands[:, 0] - q[0], cands[:, 1] - q[1])
        k = int(np.argmax(d))
        return float(d[k]), cands[k]

    def rays_meet(self, origin: np.ndarray, directions: np.ndarray, start: float) -> np.ndarray:
        """Per unit direction (K,2): whether the ray ``origin + t u``, ``t >= start``, meets the region. Exact
        (each circle's interval along the ray, the hole's cut out), with a slack of ``1e-9`` m that favours
        meeting it."""
        o = np.asarray(origin, float).reshape(2)
        u = np.asarray(directions, float).reshape(-1, 2)
        lo, hi = np.full(len(u), float(start)), np.full(len(u), np.inf)
        hole_lo, hole_hi = np.full(len(u), np.inf), np.full(len(u), -np.inf)
        for c, r, inner in self._circles(0.0):
            rel = o - c
            b = u @ rel
            disc = b * b - (rel @ rel - r * r)
            root = np.sqrt(np.maximum(disc, 0.0))
            if inner:
                lo = np.where(disc >= 0, np.maximum(lo, -b - root), np.inf)
                hi = np.minimum(hi, np.where(disc >= 0, -b + root, -np.inf))
            else:
                hole_lo, hole_hi = np.where(disc > 0, -b - root, np.inf), np.where(disc > 0, -b + root, -np.inf)
        some = lo <= hi + _TOL
        return some & ~((hole_lo < lo - _TOL) & (hi + _TOL < hole_hi))

    def holds_disk(self, radius: float) -> bool:
        """Whether the ring (if any) holds the whole disk of ``radius`` about the centre (no ring: always)."""
        return self.ring is None or self._ring_room(radius) >= radius

    def starts(self) -> Workspace:
        """Where random starts are drawn: the disk of :data:`START_RADIUS` (or this one's, if smaller), cut by the
        ring only where the ring does not hold it (what ``fit_workspace`` gave that disk), so that the scene sets
        of every seed are the ones drawn before the planning disk grew."""
        r = min(self.radius, START_RADIUS)
        return Workspace(self.center, r, None if self.holds_disk(r) else self.ring)

    # --- describing it ---------------------------------------------------------------------------------
    def outline(self, n: int = 360) -> list[np.ndarray]:
        """The region's boundary for drawing: polylines (k,2), one per arc (the whole circle, closed, with no
        ring); ``n`` points round the disk, as densely spaced on the ring's circles."""
        ang = np.linspace(0.0, 2 * np.pi, n + 1)
        circles = self._circles(0.0)
        if self.ring is None:
            c, r, _ = circles[0]
            return [np.column_stack([c[0] + r * np.cos(ang), c[1] + r * np.sin(ang)])]
        out = []
        for c, r, _ in circles:
            k = max(n, int(round(n * r / max(self.radius, 1e-9))))
            ang = np.linspace(0.0, 2 * np.pi, k, endpoint=False)
            pts = np.column_stack([c[0] + r * np.cos(ang), c[1] + r * np.sin(ang)])
            on = self.contains(pts, -1e-7)
            if on.all():
                out.append(np.vstack([pts, pts[:1]]))
                continue
            if not on.any():
                continue
            shift = int(np.argmin(on))  # start the walk at a point off the boundary: runs do not wrap
            pts, on = np.roll(pts, -shift, axis=0), np.roll(on, -shift)
            edges = np.flatnonzero(np.diff(np.concatenate([[0], on.astype(int), [0]])))
            out += [pts[s:e] for s, e in zip(edges[::2], edges[1::2], strict=True) if e - s >= 2]
        return out

    def describe(self) -> str:
        """The region in words, for messages: the disk, and the ring's distances from the arm's base."""
        disk = f"a disk of radius {self.radius} m around {self.center}"
        if self.ring is None:
            return disk
        return (f"{disk}, within {self.ring[2]:.2f}-{self.ring[3]:.2f} m of the arm's base at "
                f"({self.ring[0]:.2f}, {self.ring[1]:.2f})")

    def to_dict(self) -> dict:
        """The workspace for pictures and JSON (the teach pages): x, y, r, and the ring's fields when set."""
        out = {"x": self.center[0], "y": self.center[1], "r": self.radius}
        if self.ring is not None:
            out |= {"base_x": self.ring[0], "base_y": self.ring[1], "near": self.ring[2], "far": self.ring[3]}
        return out

    @property
    def inner_radius(self) -> float:
        """The largest disk about the centre inside the region (the radius itself with no ring): what an arm
        whose ring bites into the disk would get if the disk were shrunk to fit the ring."""
        return self.radius if self.ring is None else max(self._ring_room(self.radius), 0.0)

    def _ring_room(self, radius: float) -> float:
        """The largest disk about the centre, at most ``radius``, that the ring holds (negative: none)."""
        d = float(np.hypot(self.center[0] - self.ring[0], self.center[1] - self.ring[1]))
        return min(radius, self.ring[3] - d, d - self.ring[2])

    def area(self, step: float = 0.002) -> float:
        """The region's area (m^2), counted on a grid of ``step`` metres (for reports, not for decisions)."""
        g = np.arange(-self.radius, self.radius + step / 2, step)
        x, y = np.meshgrid(self.center[0] + g, self.center[1] + g)
        return float(self.contains(np.column_stack([x.ravel(), y.ravel()])).sum() * step * step)

    @property
    def empty(self) -> bool:
        """No point of the disk lies in the ring."""
        if self.ring is None:
            return self.radius <= 0.0
        d = float(np.hypot(self.center[0] - self.ring[0], self.center[1] - self.ring[1]))
        return self.radius <= 0.0 or d + self.radius <= self.ring[2] or d - self.radius >= self.ring[3]
