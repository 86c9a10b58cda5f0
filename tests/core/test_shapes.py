"""Scene objects with shapes (issue 22): boxes, cylinders and meshes load, measure and refuse bad input."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from l2p_bullet.arms import reach
from l2p_bullet.core import shapes
from l2p_bullet.core.scene import Scene, default_scene, load_scene, save_scene
from l2p_bullet.errors import InfeasibleError, SceneError
from l2p_bullet.planning import feasibility

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "objects"

TETRA = "v 0 0 0\nv 0.04 0 0\nv 0 0.04 0\nv 0 0 0.04\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n"
"""A closed tetrahedron (outward faces), 4 cm legs."""


def _scene(tmp_path, objects, name="scene.json") -> Path:
    p = tmp_path / name
    p.write_text(json.dumps({"objects": objects}))
    return p


def _box(name="A", dims=(0.06, 0.03, 0.04), xy=(0.05, -0.1), **kw) -> dict:
    return {"name": name, "color": "red", "shape": "box", "dims": list(dims), "xy": list(xy)} | kw


CUBE_B = {"name": "B", "color": "green", "size": 0.05, "xy": [0.0, 0.06]}


def test_box_cylinder_and_mesh_load_with_their_measures(tmp_path):
    (tmp_path / "tetra.obj").write_text(TETRA)
    scene = load_scene(_scene(tmp_path, [
        _box(), CUBE_B,
        {"name": "C", "color": "blue", "shape": "cylinder", "radius": 0.02, "height": 0.07, "xy": [-0.1, 0.0]},
        {"name": "D", "color": "yellow", "shape": "mesh", "mesh": "tetra.obj", "scale": 1.0, "xy": [0.1, 0.1],
         "mass": 0.2, "friction": 0.8}]))
    a, c, d = scene.get("A"), scene.get("C"), scene.get("D")
    assert a.size == pytest.approx(math.sqrt(0.06 * 0.03)) and a.height == pytest.approx(0.04)
    assert a.inradius == pytest.approx(0.015)
    assert c.height == pytest.approx(0.07) and c.geometry.narrowest()[0] == pytest.approx(0.04)
    assert c.size == pytest.approx(math.sqrt(math.pi) * 0.02, rel=0.01)  # a circle's area, within the polygon's 1 %
    # the tetrahedron: its reference point is its centre of mass, a quarter of the way up
    g = d.geometry
    assert g.height == pytest.approx(0.04) and g.rest == pytest.approx(0.01)
    assert g.volume == pytest.approx(0.04**3 / 6)
    assert np.allclose(g.points.mean(axis=0), 0.0, atol=1e-12)  # vertices' mean = a tetrahedron's centroid
    assert d.mass == 0.2 and d.friction == 0.8
    # the footprint is the outline seen from above, turned by the yaw
    turned = a.footprint(np.array([0.0, 0.0, math.pi / 2]))
    assert np.ptp(turned, axis=0) == pytest.approx([0.03, 0.06])


def test_scene_round_trips_and_a_cube_scene_is_unchanged(tmp_path):
    (tmp_path / "tetra.obj").write_text(TETRA)
    src = _scene(tmp_path, [_box(), CUBE_B, {"name": "D", "color": "yellow", "shape": "mesh", "mesh": "tetra.obj",
                                             "scale": 1.5, "rpy": [0.1, 0.0, 0.0], "xy": [0.1, 0.1]}])
    scene = load_scene(src)
    again = Scene.from_dict(scene.to_dict(), base=tmp_path).validate()  # the mesh path is now absolute, inside
    assert again.to_dict() == scene.to_dict() and again.digest() == scene.digest()
    cubes = default_scene().to_dict()
    assert all(set(o) == {"name", "color", "size", "xy", "yaw"} for o in cubes["objects"])
    save_scene(scene, tmp_path / "copy.json")
    assert load_scene(tmp_path / "copy.json").to_dict() == scene.to_dict()


def test_ready_objects_from_pybullet_data():
    scene = load_scene(EXAMPLES / "objects.json")
    duck = scene.get("duck")
    assert duck.shape == "mesh" and scene.to_dict()["objects"][2]["mesh"] == "pybullet_data:duck_vhacd.obj"
    assert 0.03 < duck.geometry.narrowest()[0] < 0.08 and 0.05 < duck.height < 0.07


@pytest.mark.parametrize("obj, needle", [
    (_box(dims=[0.05, -0.03, 0.04]), "positive finite"),
    (_box(dims=[0.05, 0.03]), "three finite numbers"),
    (_box(dims=[0.5, 0.03, 0.04]), "must each be 1-25 cm"),
    (_box(mass=-1), "mass"),
    (_box(friction="high"), "friction"),
    ({"name": "A", "color": "red", "shape": "cylinder", "radius": 0.0, "height": 0.05, "xy": [0, 0]}, "positive"),
    ({"name": "A", "color": "red", "shape": "cylinder", "radius": 0.02, "xy": [0, 0]}, 'needs the field "height"'),
    ({"name": "A", "color": "red", "shape": "sphere", "xy": [0, 0]}, 'unknown shape "sphere"'),
    ({"name": "A", "color": "red", "shape": "mesh", "mesh": "x.ply", "xy": [0, 0]}, "not a mesh file name"),
    ({"name": "A", "color": "red", "shape": "mesh", "mesh": "missing.obj", "xy": [0, 0]}, "no such file"),
])
def test_bad_shapes_are_one_line_errors(tmp_path, obj, needle):
    with pytest.raises(SceneError) as e:
        load_scene(_scene(tmp_path, [obj, CUBE_B]))
    msg = str(e.value)
    assert needle in msg and "\n" not in msg and "object 0 (A)" in msg


def test_non_finite_dims_are_refused():
    # the scene file's reader refuses NaN and Infinity already; a scene built in Python meets the same rule
    for bad in (float("nan"), float("inf")):
        with pytest.raises(SceneError, match="three finite numbers"):
            Scene.from_dict({"objects": [_box(dims=[0.05, 0.03, bad]), CUBE_B]})


@pytest.mark.parametrize("name, content, needle", [
    ("flat.obj", "v 0 0 0\nv 0.04 0 0\nv 0 0.04 0\nf 1 2 3\nf 1 3 2\n", "no volume"),
    ("text.obj", "this is not a mesh\njust words\n", "no triangles"),
    ("junk.stl", "x" * 60, "mesh junk.stl: "),
    ("junk.glb", "glTF but not really", "not a readable GLB"),
])
def test_bad_mesh_files_are_one_line_errors(tmp_path, name, content, needle):
    (tmp_path / name).write_text(content)
    with pytest.raises(SceneError) as e:
        load_scene(_scene(tmp_path, [{"name": "A", "color": "red", "shape": "mesh", "mesh": name, "xy": [0.05, -0.1]},
                                     CUBE_B]))
    assert needle in str(e.value) and "\n" not in str(e.value)


def test_huge_meshes_are_refused_before_they_are_read(tmp_path, monkeypatch):
    # a binary STL that declares 10 million triangles: refused from its 84-byte header
    (tmp_path / "big.stl").write_bytes(b"\0" * 80 + (10_000_000).to_bytes(4, "little") + b"\0" * 100)
    with pytest.raises(SceneError, match="10000000 triangles"):
        load_scene(_scene(tmp_path, [{"name": "A", "color": "red", "shape": "mesh", "mesh": "big.stl",
                                      "xy": [0.05, -0.1]}, CUBE_B]))
    # a file over the size limit: refused from its size on disk (a sparse file: nothing is written or read)
    with open(tmp_path / "big.obj", "wb") as f:
        f.truncate(shapes.MAX_MESH_BYTES + 1)
    with pytest.raises(SceneError, match="bytes is more than the 16,777,216 bytes"):
        load_scene(_scene(tmp_path, [{"name": "A", "color": "red", "shape": "mesh", "mesh": "big.obj",
                                      "xy": [0.05, -0.1]}, CUBE_B]))
    # a parsed mesh with too many faces (the limit lowered so the test stays small)
    monkeypatch.setattr(shapes, "MAX_MESH_FACES", 3)
    shapes.mesh.cache_clear()
    shapes.geometry.cache_clear()
    (tmp_path / "tetra.obj").write_text(TETRA)
    with pytest.raises(SceneError, match="4 triangles, more than the 3"):
        load_scene(_scene(tmp_path, [{"name": "A", "color": "red", "shape": "mesh", "mesh": "tetra.obj",
                                      "xy": [0.05, -0.1]}, CUBE_B]))


def test_mesh_paths_outside_the_scene_folder_are_refused(tmp_path):
    outside = tmp_path / "meshes"
    outside.mkdir()
    (outside / "tetra.obj").write_text(TETRA)
    folder = tmp_path / "scenes"
    folder.mkdir()
    for ref in ("../meshes/tetra.obj", str(outside / "tetra.obj"), "pybullet_data:../../../etc/passwd.obj"):
        src = _scene(folder, [{"name": "A", "color": "red", "shape": "mesh", "mesh": ref, "xy": [0.05, -0.1]}, CUBE_B])
        with pytest.raises(SceneError, match="is outside"):
            load_scene(src)
    # a symlink inside the folder that points out of it is outside too
    (folder / "link.obj").symlink_to(outside / "tetra.obj")
    src = _scene(
        folder, [{"name": "A", "color": "red", "shape": "mesh", "mesh": "link.obj", "xy": [0.05, -0.1]}, CUBE_B]
    )
    with pytest.raises(SceneError, match="is outside"):
        load_scene(src)
    # a folder the user names (the command line's --mesh-dir) is trusted, absolute or relative
    src = _scene(folder, [{"name": "A", "color": "red", "shape": "mesh", "mesh": str(outside / "tetra.obj"),
                           "xy": [0.05, -0.1]}, CUBE_B])
    assert load_scene(src, mesh_dirs=(outside,)).get("A").shape == "mesh"


def test_grasp_width_picks_the_narrow_side_and_refuses_what_no_grasp_fits():
    scene = load_scene(EXAMPLES / "objects.json")
    box = scene.get("A")  # 6 x 3 cm: the fingers close across the 3 cm side
    angles = reach.width_angles(box)
    assert reach.grasp_width(box, angles[0]) == pytest.approx(0.03)
    assert all(reach.grasp_width(box, a) <= 0.08 + 1e-9 for a in angles)
    holds = feasibility.grasp_holds(scene, "A")
    assert holds and reach.grasp_width(box, holds[0].angle) == pytest.approx(0.03)

    ball = load_scene(EXAMPLES / "ball.json")
    with pytest.raises(InfeasibleError) as e:
        feasibility.check(ball, "ball", "B", "around")
    assert e.value.check == "grasp-width" and "panda" in str(e.value)
    assert e.value.details["width_m"] > e.value.details["opening_m"] == 0.08
    # the ball is a fine anchor: only the mover must fit between the fingers
    feasibility.grasp_width(ball, "B")


def test_a_wide_box_is_refused_but_a_long_one_is_grasped_across(tmp_path):
    wide = load_scene(_scene(tmp_path, [_box(dims=(0.09, 0.09, 0.03), xy=(0.08, -0.1)), CUBE_B]))
    with pytest.raises(InfeasibleError) as e:
        feasibility.check(wide, "A", "B")
    assert e.value.check == "grasp-width" and e.value.details["width_m"] == pytest.approx(0.09)
    long = load_scene(_scene(tmp_path, [_box(dims=(0.2, 0.04, 0.03), xy=(0.08, -0.12), yaw=0.4), CUBE_B]))
    assert [round(reach.grasp_width(long.get("A"), a), 4) for a in reach.width_angles(long.get("A"))][:1] == [0.04]


def test_simplified_outlines_contain_the_object():
    a = np.linspace(0.0, 2 * math.pi, 40, endpoint=False)
    circle = np.column_stack([np.cos(a), np.sin(a)]) * 0.02
    outline = shapes.simplify(circle, 12)
    assert len(outline) == 12
    edges = np.roll(outline, -1, axis=0) - outline
    rel = circle[None, :, :] - outline[:, None, :]
    assert (edges[:, None, 0] * rel[..., 1] - edges[:, None, 1] * rel[..., 0] >= -1e-12).all()  # all inside
    area = 0.5 * abs(
        np.dot(outline[:, 0], np.roll(outline[:, 1], -1)) - np.dot(outline[:, 1], np.roll(outline[:, 0], -1))
    )
    assert math.pi * 0.02**2 < area < 1.03 * math.pi * 0.02**2


def test_the_hand_keeps_clear_of_objects_taller_than_the_held_one(tmp_path):
    # a 2 cm-tall box beside a 7 cm cylinder and a 1.5 cm one: only the tall one meets the fingers and hand
    scene = load_scene(_scene(tmp_path, [
        _box(dims=(0.05, 0.025, 0.02), xy=(0.05, -0.1)),
        {"name": "T", "color": "green", "shape": "cylinder", "radius": 0.02, "height": 0.07, "xy": [0.05, 0.0]},
        {"name": "L", "color": "blue", "shape": "cylinder", "radius": 0.02, "height": 0.015, "xy": [-0.05, -0.1]}]))
    angle = reach.width_angles(scene.get("A"))[0]
    outlines = reach.hold_outlines(scene, "A", angle)
    assert set(outlines) == {"T"}
    foot = scene.get("A").footprint(np.zeros(3))
    assert np.ptp(outlines["T"], axis=0).max() > np.ptp(foot, axis=0).max()  # the hand reaches beyond the box


def test_a_mesh_with_holes_is_weighed_as_the_solid_it_winds_round(tmp_path):
    """Meshes as packages ship them have holes: one is weighed by its winding numbers, not refused."""
    import trimesh

    from l2p_bullet.core import solid

    closed = trimesh.creation.box(extents=(0.05, 0.03, 0.04))
    closed.apply_translation((0.01, 0.0, 0.02))
    volume, com = solid.solid(closed.vertices, closed.faces)  # the estimate against the exact closed answer
    assert volume == pytest.approx(closed.volume, rel=0.02) and np.allclose(com, closed.center_mass, atol=1e-3)
    lid = np.flatnonzero(closed.face_normals[:, 2] > 0.9)  # the top's two triangles taken off: a tray
    tray = trimesh.Trimesh(closed.vertices, np.delete(closed.faces, lid, axis=0), process=False)
    assert not tray.is_watertight
    tray.export(tmp_path / "tray.obj")
    scene = load_scene(_scene(tmp_path, [{"name": "A", "color": "red", "shape": "mesh", "mesh": "tray.obj",
                                          "xy": [0.05, -0.1]}, CUBE_B]))
    g = scene.get("A").geometry
    assert g.height == pytest.approx(0.04) and g.narrowest()[0] == pytest.approx(0.03)
    assert 0.3 * closed.volume < g.volume < 1.02 * closed.volume  # what the open top lets it wind round
    assert g.rest < 0.02  # its centre of mass below the middle: the open top weighs least
