"""Bad scene files give a SceneError that names the problem (and the CLI prints it on one line)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.core.scene import default_scene, load_scene, save_scene
from l2p_bullet.errors import SceneError


def _write(tmp_path, objects, name="scene.json"):
    p = tmp_path / name
    p.write_text(json.dumps({"objects": objects}))
    return p


def _obj(name="A", color="red", size=0.05, xy=(0.05, -0.10), yaw=0.0):
    return {"name": name, "color": color, "size": size, "xy": list(xy), "yaw": yaw}


def test_default_scene_round_trips(tmp_path):
    p = tmp_path / "s.json"
    save_scene(default_scene(), p)
    assert load_scene(p).to_dict() == default_scene().to_dict()


def test_unreadable_json_names_the_line(tmp_path):
    p = tmp_path / "bad.json"
    p.write_text('{"objects": [\n  {"name": "A",,}\n]}')
    with pytest.raises(SceneError, match=r"not valid JSON \(line 2"):
        load_scene(p)


def test_missing_file(tmp_path):
    with pytest.raises(SceneError, match="cannot read scene file"):
        load_scene(tmp_path / "nope.json")


@pytest.mark.parametrize("field", ["name", "color", "size", "xy"])
def test_missing_field_is_named(tmp_path, field):
    obj = _obj()
    del obj[field]
    p = _write(tmp_path, [obj, _obj("B", "green", xy=(0.0, 0.05))])
    with pytest.raises(SceneError, match=f'missing the field "{field}"'):
        load_scene(p)


def test_duplicate_names(tmp_path):
    p = _write(tmp_path, [_obj("A"), _obj("A", "green", xy=(0.0, 0.1))])
    with pytest.raises(SceneError, match='two objects are named "A"'):
        load_scene(p)


def test_overlapping_blocks(tmp_path):
    p = _write(tmp_path, [_obj("A", xy=(0.0, 0.0)), _obj("B", "green", xy=(0.03, 0.0))])
    with pytest.raises(SceneError, match='"A" and "B" overlap'):
        load_scene(p)


def test_touching_but_apart_blocks_are_fine(tmp_path):
    p = _write(tmp_path, [_obj("A", xy=(0.0, 0.0)), _obj("B", "green", xy=(0.051, 0.0))])
    assert load_scene(p).names == ["A", "B"]


def test_block_off_the_table(tmp_path):
    p = _write(tmp_path, [_obj("A", xy=(0.39, 0.0)), _obj("B", "green", xy=(0.0, 0.05))])
    with pytest.raises(SceneError, match='"A" .* is off the table'):
        load_scene(p)


def test_block_outside_the_workspace(tmp_path):
    p = _write(tmp_path, [_obj("A", xy=(0.26, 0.26)), _obj("B", "green", xy=(0.0, 0.05))])  # 0.37 m out, on the table
    with pytest.raises(SceneError, match="outside the arm's workspace"):
        load_scene(p)


def test_cli_prints_scene_error_on_one_line(tmp_path):
    p = _write(tmp_path, [_obj("A"), _obj("A", "green", xy=(0.0, 0.1))])
    r = CliRunner().invoke(main, ["replay", "--demo", "past:0", "--scene", str(p), "--no-render",
                                  "--out", str(tmp_path / "run")])
    assert r.exit_code == 2
    lines = [line for line in r.output.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: ") and 'two objects are named "A"' in lines[0]
    assert "Traceback" not in r.output


def test_a_cubes_footprint_is_the_outline_of_its_mesh():
    """The square is written down (no trimesh import per command); it must be what the box mesh gives."""
    import trimesh

    from l2p_bullet.core.scene import SceneObject

    mesh = trimesh.creation.box(extents=(0.05, 0.05, 0.05))
    pts = np.unique(np.round(mesh.vertices[:, :2], 9), axis=0)
    order = np.argsort(np.arctan2(pts[:, 1], pts[:, 0]))
    assert np.allclose(SceneObject("A", "red", 0.05, (0.0, 0.0)).footprint(), pts[order])


def test_an_unknown_object_field_is_refused_with_a_suggestion():
    """A misspelt "yaw" used to be ignored, leaving the block at yaw 0 without a word (CLI audit, 2026-11-27)."""
    from l2p_bullet.core.scene import OBJECT_FIELDS, Scene, default_scene

    doc = default_scene().to_dict()
    doc["objects"][0]["yaww"] = 0.3
    with pytest.raises(SceneError, match=r'object 0 \(A\): unknown field "yaww" .*Did you mean "yaw"'):
        Scene.from_dict(doc)
    from pathlib import Path

    from l2p_bullet.core.scene import load_scene

    shaped = load_scene(Path(__file__).resolve().parents[2] / "examples" / "objects" / "objects.json")
    for scene in (default_scene(), shaped):  # what the project writes (boxes, cylinders, meshes) it reads back
        assert all(k in OBJECT_FIELDS for o in scene.to_dict()["objects"] for k in o)
        assert Scene.from_dict(scene.to_dict()).to_dict() == scene.to_dict()


def test_a_declared_kind_is_kept_and_a_bad_one_refused(tmp_path):
    """"kind" says what an object is where its name does not ("Daisy", a toy cow): read back as written, left out of
    a scene that declares none (whose digest is unchanged), and refused on one line where it is no words."""
    from l2p_bullet.core.scene import Scene

    plain = load_scene(_write(tmp_path, [_obj("Daisy")]))
    kinded = load_scene(_write(tmp_path, [{**_obj("Daisy"), "kind": "toy cow"}], "k.json"))
    assert kinded.get("Daisy").kind == "toy cow" and plain.get("Daisy").kind is None
    assert kinded.to_dict()["objects"][0]["kind"] == "toy cow" and "kind" not in plain.to_dict()["objects"][0]
    assert Scene.from_dict(kinded.to_dict()).to_dict() == kinded.to_dict()
    assert plain.digest() == Scene.from_dict({"objects": [_obj("Daisy")]}).digest() != kinded.digest()
    for bad in ("", "cow 2", 7, "x" * 80, "cow; rm -rf"):
        with pytest.raises(SceneError, match=r'object 0 \(Daisy\): "kind" must be words'):
            load_scene(_write(tmp_path, [{**_obj("Daisy"), "kind": bad}], "bad.json"))
