"""The push's fingertip height on a mesh's real shape (embodiment/push_height.py) and the face it pushes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from l2p_bullet.arms.builtin import PANDA
from l2p_bullet.core.scene import Scene, shaped
from l2p_bullet.embodiment.manners import PUSH_TIP_Z, push_tip_ceiling, tip_refusal
from l2p_bullet.embodiment.push_height import push_height


def _triangles(mesh) -> np.ndarray:
    return np.asarray(mesh.vertices, float)[np.asarray(mesh.faces)]


def _stick(radius: float = 0.005, length: float = 0.12):
    """A round stick lying on the table (a coffee stirrer): its sides slope in above and below its middle."""
    import trimesh

    return trimesh.creation.cylinder(radius=radius, height=length, sections=24,
                                     transform=trimesh.transformations.rotation_matrix(math.pi / 2, [1, 0, 0]))


def test_upright_sides_keep_the_default_height():
    import trimesh

    for mesh in (trimesh.creation.box(extents=(0.05, 0.03, 0.04)), trimesh.creation.cylinder(0.02, 0.08, sections=32)):
        assert push_height(_triangles(mesh), PANDA.hand_profile, PUSH_TIP_Z, math.inf) == PUSH_TIP_Z


def test_a_round_stick_is_pushed_at_its_middle_not_above_it():
    """At 6 mm the tapered fingertips meet a 1 cm stick's upper shoulder and press it into the table."""
    z = push_height(_triangles(_stick()), PANDA.hand_profile, PUSH_TIP_Z, math.inf)
    assert 0.002 <= z < PUSH_TIP_Z


def test_the_face_pushed_is_measured_on_the_pushed_side():
    """Pushed along +x, the hand meets the face at -x: an outline reaching 5.5 cm ahead of its centre and 3.5 cm
    behind is bitten from 3.5 cm (measuring the far side put the fingers 2 cm short of it: a camera stayed put)."""
    from l2p_bullet.embodiment.push import Pusher

    p = Pusher.__new__(Pusher)
    p.outline = np.array([[0.055, -0.02], [0.055, 0.02], [-0.035, 0.02], [-0.035, -0.02]])
    assert p.support(np.zeros(3), 0.0) == pytest.approx(0.035)
    assert p.support(np.zeros(3), math.pi) == pytest.approx(0.055)
    assert p.support(np.array([0.0, 0.0, math.pi]), 0.0) == pytest.approx(0.055)  # the block turned round


def test_the_tip_ceiling_is_where_the_tip_check_turns():
    """A push made up to the ceiling passes the rule that passed it at the default height; above it, not."""
    tall = shaped("M", "yellow", (0.0, 0.0), 0.0, shape="box", dims=(0.05, 0.04, 0.09))
    top = push_tip_ceiling(tall)
    assert PUSH_TIP_Z < top < 0.09
    assert tip_refusal(Scene([tall]), "M") is None
    widen = next(d for d, _, hy in PANDA.hand_profile if hy > 0.05)
    friction = 1 / 3
    assert friction * (top + widen) == pytest.approx(0.04 / 2)
    squat = shaped("M", "yellow", (0.0, 0.0), 0.0, shape="box", dims=(0.05, 0.04, 0.03))
    assert push_tip_ceiling(squat) == math.inf


def _prism(folder):
    """A 6 cm triangle, 3 cm tall: its outline reaches 3.5 cm from its centre at a corner, 1.7 cm at a side."""
    import trimesh

    a = np.radians([90.0, 210.0, 330.0])
    tri = 0.03464 * np.column_stack([np.cos(a), np.sin(a)])
    v = np.vstack([np.column_stack([tri, np.zeros(3)]), np.column_stack([tri, np.full(3, 0.03)])])
    f = [[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]]
    path = folder / "prism.obj"
    trimesh.Trimesh(v, f, process=True).export(path)
    return path


@pytest.mark.slow
def test_a_mesh_pushed_corner_first_moves(tmp_path):
    """Pushed corner first (bench_objects' "push past" scene), the hand meets the triangle's flat back 1.7 cm
    from its centre; measured on the corner ahead it stopped 9 mm short and pressed nothing until the push's
    time ran out (a camera of the held-out meshes did the same)."""
    r, moved = _push_past(tmp_path, _prism(tmp_path), 0.506)
    assert moved > 0.1, r.grasp
    assert r.grasp["push"]["stopped"] == "end", r.grasp
    assert r.verdict["success"], r.verdict
    assert max(r.displacements_m.get(k, 0.0) for k in ("A", "B")) < 0.001


def _push_past(tmp_path, mesh, yaw: float):
    """``mesh`` pushed past B in bench_objects' "push past" scene: the result and how far the mesh moved (m)."""
    import json

    from l2p_bullet.pipeline import perform

    m = {"name": "M", "color": "yellow", "shape": "mesh", "mesh": str(mesh), "scale": 1.0, "xy": [0.1, -0.08],
         "yaw": yaw}
    scene = Scene.from_dict({"objects": [m, {"name": "B", "color": "green", "size": 0.04, "xy": [0.0, 0.1]},
                                         {"name": "A", "color": "red", "size": 0.04, "xy": [-0.1, 0.0]}]})
    r = perform("push M past B", scene.validate(), out_dir=tmp_path / "run", render=False)
    frames = json.loads((tmp_path / "run" / "trajectory.json").read_text())["frames"]
    return r, float(np.hypot(*(np.array(frames[-1]["poses"]["M"][:2]) - frames[0]["poses"]["M"][:2])))


def _u_shape(folder=None):
    """A 9 x 5 x 3 cm U (a gamepad's two grips and its body), open towards -y: a 6 cm wide, 3 cm deep notch
    between its arms, wider than the closed fingers."""
    import trimesh

    parts = [trimesh.creation.box(extents=e, transform=trimesh.transformations.translation_matrix(c))
             for e, c in (((0.09, 0.02, 0.03), (0.0, 0.015, 0.015)), ((0.015, 0.031, 0.03), (-0.0375, -0.0095, 0.015)),
                          ((0.015, 0.031, 0.03), (0.0375, -0.0095, 0.015)))]
    u = trimesh.util.concatenate(parts)  # three closed boxes in one file, as model packages ship them
    if folder is None:
        return u
    path = folder / "u.obj"
    u.export(path)
    return path


def test_the_hand_meets_a_concave_side_where_its_fingers_fit_in():
    """The hand advancing on the U's open side fits between its arms and meets its body, 3 cm behind the
    outline's support there; on its closed side it meets the outline's support plus its own half thickness."""
    from l2p_bullet.embodiment.push_height import contact_reach, hand_front

    u = _u_shape()
    angles, reach = contact_reach(_triangles(u), PANDA.hand_profile, PUSH_TIP_Z)
    top = float(hand_front(PANDA.hand_profile, np.array([0.03 - PUSH_TIP_Z]))[0])
    back, mouth = np.argmin(np.abs(angles - math.pi / 2)), np.argmin(np.abs(angles - 3 * math.pi / 2))
    assert reach[back] == pytest.approx(0.025 + top, abs=0.0015)
    assert reach[mouth] == pytest.approx(-0.005 + top, abs=0.0015)  # the body, not the arms' ends at -0.025
    side = np.argmin(np.abs(angles))
    assert reach[side] == pytest.approx(0.045 + top, abs=0.0015)


@pytest.mark.slow
def test_a_mesh_pushed_on_its_concave_side_moves(tmp_path, monkeypatch):
    """Pushed on its open side (bench_objects' "push past" scene), the fingers fit between the U's arms: the
    push measured from its outline stopped them inside the notch, short of its body, and pressed nothing until
    the push's time ran out (a gamepad of the held-out meshes did the same)."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    r, moved = _push_past(tmp_path, _u_shape(tmp_path), -0.14)
    assert moved > 0.1, r.grasp
    assert r.verdict["success"], r.verdict
    assert max(r.displacements_m.get(k, 0.0) for k in ("A", "B")) < 0.001


@pytest.mark.slow
def test_a_tall_mesh_is_pushed_from_where_the_hand_s_body_meets_it(tmp_path, monkeypatch):
    """A 12.5 cm box 4.2 cm thin (the tip check lets its push through) is met first by the hand's body, 5 cm up
    and 7 mm thicker than the fingers: bitten from the fingers' front, the body pressed it 15 mm deep there,
    and it turned and tipped over before the end of the push."""
    import trimesh

    from l2p_bullet.pipeline import perform

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    box = trimesh.creation.box(extents=(0.06, 0.042, 0.125),
                               transform=trimesh.transformations.translation_matrix((0.0, 0.0, 0.0625)))
    box.export(tmp_path / "tall.obj")
    m = {"name": "M", "color": "yellow", "shape": "mesh", "mesh": str(tmp_path / "tall.obj"), "scale": 1.0,
         "xy": [0.1, -0.08], "yaw": 0.5, "mass": 0.1}
    scene = Scene.from_dict({"objects": [m, {"name": "B", "color": "green", "size": 0.04, "xy": [0.0, 0.1]},
                                         {"name": "A", "color": "red", "size": 0.04, "xy": [-0.1, 0.0]}]})
    r = perform("push M past B", scene.validate(), out_dir=tmp_path / "run", render=False)
    assert r.grasp["push"]["stopped"] == "end" and not r.grasp["push"]["tipped"], r.grasp
    assert r.verdict["success"], r.verdict
