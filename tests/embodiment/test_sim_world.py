"""The simulated world's life cycle: reuse across runs, closing everything it opened, one door to PyBullet."""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

import l2p_bullet
from l2p_bullet.core.scene import Scene, SceneObject, default_scene
from l2p_bullet.embodiment.execute import execute_path
from l2p_bullet.embodiment.record import Recorder
from l2p_bullet.embodiment.sim.camera import RenderSettings
from l2p_bullet.embodiment.sim.primitives import Primitives
from l2p_bullet.embodiment.sim.world import World
from l2p_bullet.errors import SceneError

OTHER = Scene([SceneObject("A", "red", 0.05, (0.12, -0.1), 0.3), SceneObject("B", "green", 0.05, (-0.05, 0.08)),
               SceneObject("C", "blue", 0.04, (-0.1, -0.1))])


def _short_path(scene: Scene) -> np.ndarray:
    a = scene.get("A")
    return np.array([[a.xy[0], a.xy[1], a.yaw], [a.xy[0] + 0.04, a.xy[1] + 0.05, a.yaw + 0.2]])


def _open_connections() -> int:
    import pybullet as pb

    return sum(pb.getConnectionInfo(physicsClientId=i)["isConnected"] for i in range(256))


def test_close_disconnects_the_world_and_its_ik_twin():
    before = _open_connections()
    world = World(default_scene(), visuals=False)
    assert _open_connections() == before + 2  # the world's simulator and the arm's IK twin
    world.close()
    assert _open_connections() == before
    world.close()  # idempotent
    with World(default_scene(), visuals=False):
        pass
    assert _open_connections() == before


def test_a_failed_world_closes_what_it_opened():
    before = _open_connections()
    scene = Scene([SceneObject("<arm>", "red", 0.05, (0.1, 0.0)), SceneObject("B", "green", 0.05, (-0.1, 0.1))])
    with pytest.raises(SceneError, match="reserved"):
        World(scene, visuals=False)
    assert _open_connections() == before


def test_reset_clears_the_grasp_the_blocks_and_the_clock():
    world = World(default_scene(), visuals=False)
    try:
        prims = Primitives(world, Recorder(world))
        prims.engage("A")
        assert world.sim.constraint_count() == 1 and world.steps > 0
        world.reset(OTHER)
        assert world.sim.constraint_count() == 0 and world.steps == 0 and world.time == 0.0
        assert list(world.poses()) == ["A", "B", "C"]
        for o in OTHER.objects:
            assert np.allclose(world.pose(o.name), [o.xy[0], o.xy[1], o.size / 2, o.yaw], atol=1e-9)
        assert np.allclose(world.robot.joints(), world.robot.spec.home, atol=1e-12)
        world.reset(default_scene())
        with pytest.raises(KeyError):
            world.pose("C")  # gone with the scene it belonged to
    finally:
        world.close()


def test_a_reused_world_records_what_a_fresh_world_records(tmp_path):
    shared = World(default_scene(), visuals=False)
    opened = _open_connections()
    try:
        for k, scene in enumerate((OTHER, default_scene(), OTHER)):
            for how, world in (("fresh", None), ("reused", shared)):
                (tmp_path / f"{how}{k}").mkdir()
                execute_path(scene, "A", _short_path(scene), out_dir=tmp_path / f"{how}{k}", render=None,
                             meta={"anchor": "B"}, world=world)
            fresh, reused = ((tmp_path / f"{h}{k}" / "trajectory.json").read_bytes() for h in ("fresh", "reused"))
            assert fresh == reused, f"run {k} differs on a reused world"
        assert _open_connections() == opened  # a caller's world left open, the fresh ones all closed
    finally:
        shared.close()


@pytest.mark.slow
def test_a_world_without_visuals_is_filmed_by_the_films_own_world():
    """The simulating world never renders (embodiment/render.py draws its recorded states), so a caller's
    world loaded without the arm's visuals still gives a rendered run."""
    with World(default_scene(), visuals=False) as world:
        ex = execute_path(default_scene(), "A", _short_path(default_scene()), out_dir=None,
                          render=RenderSettings(width=80, height=60, renderer="tiny", workers=0), world=world)
        assert ex.stats["rendered_frames"] > 3
        world.reset(default_scene())  # still open


def test_only_the_facade_calls_pybullet():
    """bullet.py is the one door to the simulator: no other module imports pybullet."""
    root = Path(l2p_bullet.__file__).parent
    facade = root / "embodiment" / "sim" / "bullet.py"
    offenders = []
    for path in root.rglob("*.py"):
        if path == facade:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            if any(n == "pybullet" or n.startswith(("pybullet.", "pybullet_utils")) for n in names):
                offenders.append(str(path.relative_to(root)))
    assert offenders == []


def test_ctrl_c_while_a_client_is_made_waits_until_it_is_whole():
    """Ctrl-C inside client creation used to leave a half-made BulletClient (a traceback at exit)."""
    import signal

    from l2p_bullet.embodiment.sim.bullet import Bullet, ctrl_c_deferred

    before = signal.signal(signal.SIGINT, signal.default_int_handler)  # as at a terminal
    try:
        done = []
        with pytest.raises(KeyboardInterrupt):
            with ctrl_c_deferred():
                signal.raise_signal(signal.SIGINT)  # as if Ctrl-C came during connect
                done.append(Bullet())
        assert done and done[0]._client._client >= 0  # the client was made whole, then the interrupt came
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
        done[0].close()
    finally:
        signal.signal(signal.SIGINT, before)
