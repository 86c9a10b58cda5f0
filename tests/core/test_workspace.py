"""The workspace's geometry (core/workspace.py): the disk alone, and the disk cut by an arm's reach ring (issue 22)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from l2p_bullet.core.scene import Workspace
from l2p_bullet.core.workspace import DISK_RADIUS, START_RADIUS

# the geometry's known points were worked out on the 0.25 m disk (the default until 2026-11-27): kept on it
DISK = Workspace(radius=0.25)
KUKA = Workspace(radius=0.25, ring=(-0.6, 0.0, 0.43, 0.77))  # the KUKA iiwa's: its hole bites the disk's near side
PANDA_RING = (-0.53, 0.0, 0.27, 0.79)  # the Panda's ring (embodiment/sim/arms.py)


def test_the_default_disk_is_the_measured_one_and_starts_stay_in_the_old_disk():
    assert Workspace().radius == DISK_RADIUS == 0.35 and START_RADIUS == 0.25
    # the Panda's ring holds the 0.25 m start disk, not the 0.35 m one: starts are drawn in the plain old disk
    panda = Workspace(ring=PANDA_RING)
    assert not panda.holds_disk(DISK_RADIUS) and panda.holds_disk(START_RADIUS)
    assert panda.starts() == Workspace(radius=0.25) == DISK.starts()
    # the KUKA's ring bites the old disk too: its starts keep the ring (as bench_arms drew them before)
    assert Workspace(ring=KUKA.ring).starts() == KUKA
    assert Workspace(radius=0.2).starts() == Workspace(radius=0.2)  # a smaller disk is its own start disk


def test_the_disk_alone_keeps_its_old_rules():
    assert DISK.contains([[0.0, 0.0], [0.25, 0.0], [0.2501, 0.0]]).tolist() == [True, True, False]
    assert DISK.contains([[0.24, 0.0]], margin=0.02).tolist() == [False]
    assert DISK.clearance([[0.1, 0.0]])[0] == pytest.approx(0.15)
    assert DISK.farthest_from([0.1, 0.0])[0] == pytest.approx(0.35)
    assert DISK.nearest_inside([[0.5, 0.0]])[0] == pytest.approx([0.25, 0.0])
    assert DISK.segments_inside([-0.2, 0.0], [[0.2, 0.0], [0.3, 0.0]]).tolist() == [True, False]
    assert DISK.inner_radius == 0.25 and DISK.to_dict() == {"x": 0.0, "y": 0.0, "r": 0.25}
    assert DISK.area() == pytest.approx(math.pi * 0.25 ** 2, rel=0.01)


def test_the_ring_cuts_the_disk():
    # inside the disk: the centre, the hole (0.38 m from the base), beyond the far edge (0.80 m), a side
    assert KUKA.contains([[0.0, 0.0], [-0.22, 0.0], [0.2, 0.0], [-0.15, 0.2]]).tolist() == [True, False, False, True]
    assert KUKA.inner_radius == pytest.approx(0.17)
    assert math.pi * 0.17 ** 2 < KUKA.area() < math.pi * 0.25 ** 2  # more than the old shrunk disk
    assert not KUKA.empty and Workspace(radius=0.25, ring=(-0.6, 0.0, 0.9, 1.2)).empty
    assert "0.43-0.77 m of the arm's base" in KUKA.describe()


def test_a_straight_move_through_the_hole_is_refused_and_one_around_it_accepted():
    a = np.array([-0.18, 0.13])  # 0.44 m from the base, on one side of the hole
    b, c = np.array([-0.18, -0.13]), np.array([0.0, -0.13])  # the other side; a point beyond the hole's reach
    assert KUKA.contains(np.array([a, b, c])).all()
    assert KUKA.segments_inside(a, np.array([b, c])).tolist() == [False, True]  # a->b passes 0.42 m from the base
    assert KUKA.segments_inside(c, b[None]).tolist() == [True]  # ... so round the hole: a->c->b
    assert DISK.segments_inside(a, b[None]).tolist() == [True]  # the disk alone is convex
    assert KUKA.path_inside(np.array([a, b])) == 1 and KUKA.path_inside(np.array([a, c, b])) is None


def test_clearance_nearest_and_farthest_on_known_points():
    assert KUKA.clearance([[0.0, 0.0]])[0] == pytest.approx(0.17)  # the ring's far and near circles both 0.17 away
    assert KUKA.clearance([[-0.22, 0.0]])[0] == pytest.approx(-0.05)  # 5 cm into the hole
    assert KUKA.nearest_inside([[-0.24, 0.0]])[0] == pytest.approx([-0.17, 0.0])  # pushed out of the hole
    assert KUKA.nearest_inside([[0.3, 0.0]])[0] == pytest.approx([0.17, 0.0])  # pulled in to the far circle
    q = KUKA.nearest_inside([[0.1, 0.3]], margin=0.01)[0]  # beyond the disk's rim: onto the shrunk rim
    assert KUKA.contains(q, margin=0.01 - 1e-6)[0] and np.hypot(*q) == pytest.approx(0.24)
    corner = KUKA.nearest_inside([[-0.3, 0.2]])[0]  # nearest where the hole's circle meets the rim
    assert np.hypot(*corner) == pytest.approx(0.25) and np.hypot(corner[0] + 0.6, corner[1]) == pytest.approx(0.43)
    d, far = KUKA.farthest_from([0.1, 0.0])
    grid = np.stack(np.meshgrid(np.linspace(-0.25, 0.25, 301), np.linspace(-0.25, 0.25, 301)), -1).reshape(-1, 2)
    inside = grid[KUKA.contains(grid)]
    assert KUKA.contains(far, -1e-7)[0]
    assert d >= np.hypot(*(inside - [0.1, 0.0]).T).max() - 1e-9  # no grid point of the region is farther
    assert d < 0.1 + 0.25  # the disk's answer, (-0.25, 0), lies in the hole


def test_rays_meet_the_region_past_the_hole():
    u = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0]])
    assert KUKA.rays_meet([-0.15, 0.0], u, 0.0).tolist() == [True, True, True]
    assert KUKA.rays_meet([-0.15, 0.0], u, 0.05).tolist() == [True, False, True]  # west: only the hole beyond
    assert KUKA.rays_meet([0.0, 0.0], u, 0.2).tolist() == [False, False, True]


def test_the_outline_follows_the_region():
    arcs = KUKA.outline(360)
    pts = np.concatenate(arcs)
    assert len(arcs) == 4  # the rim's two sides, the far circle's arc, the hole's arc
    assert np.abs(KUKA.clearance(pts)).max() < 1e-6
    assert len(DISK.outline(8)) == 1 and len(DISK.outline(8)[0]) == 9


def test_random_starts_are_drawn_in_the_old_disk_for_every_seed():
    # the same seeds give the same scenes as before the disk grew: a draw with a block beyond 0.25 m is redrawn
    # (random_scene's mover reaches 0.27 m from the centre, so some first draws fall outside and are redrawn)
    from l2p_bullet.core.scene import random_between_scene, random_scene
    from l2p_bullet.evaluate.chains import chain_scenes

    scenes = [random_scene(s) for s in range(300)] + [random_between_scene(s) for s in range(100)]
    scenes += [c.scene for c in chain_scenes(60, 5200)]
    r = np.array([np.hypot(*o.xy) for s in scenes for o in s.objects])
    assert r.max() <= START_RADIUS + 1e-9 and r.max() > 0.24
    assert all(s.workspace == Workspace() for s in scenes)  # planned in the whole (larger) disk
