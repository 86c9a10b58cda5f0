"""The viewer-frame rules (plugins pick them: ``[judge] rules = "left-of"``, ``right-of``, ``in-front-of``,
``behind``): the mover ends on that side of the anchor as the viewer sees it (its offset from the anchor
within 45 degrees of the viewer's left, right, towards the viewer, away from it), near it (centre distance at
most :data:`NEAR` blocks) and not overlapping it (their real outlines where one is not a cube, unit squares
where both are: ``footprints.py``). The viewer is the ``viewer`` keyword, the robot's base by default."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ...core.frames import VIEWPOINTS, viewer_offset
from ..base import Verdict
from ..footprints import overlap as footprint_overlap

NEAR = 4.0
"""Largest centre distance (blocks) at which the viewer-frame sides (plugins' rule sets) still count as near."""

SIDES: dict[str, tuple[float, float, str]] = {
    "left-of": (1.0, 0.0, "left of"), "right-of": (-1.0, 0.0, "right of"),
    "in-front-of": (0.0, -1.0, "in front of"), "behind": (0.0, 1.0, "behind"),
}
"""Viewer-frame rules: the direction (lateral, depth) of the side, in the viewer's frame, and its words."""


def side(name: str) -> Callable[..., Verdict]:
    """The viewer-frame rule for one side of the anchor (see the module docstring)."""
    lat_dir, dep_dir, words = SIDES[name]

    def rule(rel: np.ndarray, d: np.ndarray, mover: np.ndarray, anchor: np.ndarray, size: float, *,
             viewer: np.ndarray | None = None, outlines: list[np.ndarray] | None = None,
             **_: object) -> Verdict:
        v = np.asarray(VIEWPOINTS["robot"] if viewer is None else viewer, float)
        lat, dep = viewer_offset(mover[-1, :2] / size, anchor[-1, :2] / size, v[:2] / size)
        r = max(float(np.hypot(lat, dep)), 1e-9)
        along = (lat * lat_dir + dep * dep_dir) / r  # cosine of the angle from the side's direction
        overlap = footprint_overlap(np.r_[rel[-1], mover[-1, 2]], np.r_[0.0, 0.0, anchor[-1, 2]], size, outlines)
        score = float(np.clip(along, 0, 1)) * (1.0 if r <= NEAR else 0.5) * (0.0 if overlap else 1.0)
        ok = along >= math.cos(math.radians(45)) - 1e-9 and r <= NEAR and not overlap
        why = (f"ends {math.degrees(math.acos(float(np.clip(along, -1, 1)))):.0f} deg from straight {words} the "
               f"anchor as the viewer sees it ({lat:+.2f} blocks to its left, {dep:+.2f} behind), "
               f"{r:.2f} blocks away" + (" (overlapping it)" if overlap else ""))
        return Verdict(ok, score, why)

    return rule


RULES = {name: side(name) for name in SIDES}
