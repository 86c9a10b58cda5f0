"""The separating-axis gaps the planner and feasibility checks rest on."""

from __future__ import annotations

import math

import numpy as np

from l2p_bullet.core.geometry import convex_hull, posed_separation, separation
from l2p_bullet.planning.world2d import place_outline


def _polygon(rng, k: int, r: float) -> np.ndarray:
    return convex_hull(r * np.column_stack([np.cos(a := rng.uniform(0, 2 * math.pi, k)), np.sin(a)]))


def test_posed_separation_equals_placing_each_polygon():
    """The per-yaw shortcut gives separation()'s gaps for every pose: overlapping, touching and apart, on a grid
    of repeated yaws (as feasibility's sweep uses it) and on poses that share none."""
    rng = np.random.default_rng(3)
    for _ in range(20):
        outline, other = _polygon(rng, int(rng.integers(3, 12)), 0.03), _polygon(rng, int(rng.integers(3, 30)), 0.04)
        grid = np.column_stack([rng.uniform(-0.12, 0.12, (400, 2)), rng.choice(np.radians(np.arange(0, 360, 5)), 400)])
        loose = np.column_stack([rng.uniform(-0.12, 0.12, (50, 2)), rng.uniform(-math.pi, math.pi, 50)])
        for poses in (grid, loose):
            want = separation(place_outline(outline, poses), other)
            got = posed_separation(outline, poses, other)
            assert got.shape == want.shape
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)
            assert (want < 0).any() and (want > 0).any()  # both overlapping and separated poses were compared


def test_posed_separation_known_gap():
    """A unit square turned a quarter turn, 3 m right of another, is 2 m from it (and overlapping at 0.5 m)."""
    square = np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]])
    gaps = posed_separation(square, np.array([[3.0, 0.0, math.pi / 2], [0.5, 0.0, 0.0]]), square)
    np.testing.assert_allclose(gaps, [2.0, -0.5], atol=1e-12)
