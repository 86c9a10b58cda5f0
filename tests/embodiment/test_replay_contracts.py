"""A one-clause replay's run folder against DESIGN.md section 4 (contract audit, 2026-11-28): a finished replay
says ``ok`` as every other finished run does, and the replay of a plan keeps the sentence it was planned for
(trajectory.json's ``sentence`` was null, where a chain's replay keeps the chain's), also through a replay of
the replay, whose manner it names (a carry's replay replayed again was slid)."""

from __future__ import annotations

import json

from click.testing import CliRunner

from l2p_bullet.cli import main


def _run(*args):
    r = CliRunner().invoke(main, list(args))
    assert r.exit_code == 0, r.output
    return r


def test_the_replay_of_a_plan_keeps_its_sentence_and_says_ok(tmp_path):
    plan = tmp_path / "plan"
    _run("plan", "carry A past B", "--out", str(plan), "--no-plot")
    first, again = tmp_path / "replay", tmp_path / "again"
    _run("replay", str(plan / "plan.json"), "--no-render", "--out", str(first))
    _run("replay", str(first / "plan.json"), "--no-render", "--out", str(again))
    for out in (first, again):
        traj = json.loads((out / "trajectory.json").read_text())
        summary = json.loads((out / "summary.json").read_text())
        assert traj["sentence"] == summary["sentence"] == "carry A past B"
        assert summary["ok"] is True
        assert traj["manner"] == summary["manner"] == "carry"  # the replay of the replay is carried too
        assert json.loads((out / "plan.json").read_text())["sentence"] == "carry A past B"


def test_a_demonstration_replay_says_ok_and_has_no_sentence(tmp_path):
    out = tmp_path / "demo"
    _run("replay", "--demo", "next-to:0", "--no-render", "--out", str(out))
    summary = json.loads((out / "summary.json").read_text())
    assert summary["ok"] is True and summary["sentence"] is None  # no sentence was said: none is made up
    assert json.loads((out / "trajectory.json").read_text())["sentence"] is None


def _cube_obj(path):
    """A unit cube as an .obj (scaled to a block by the scene's ``scale``)."""
    v = [(x, y, z) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]
    quads = [(1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)]
    path.write_text("".join(f"v {x:g} {y:g} {z:g}\n" for x, y, z in v)
                    + "".join(f"f {a} {b} {c}\nf {a} {c} {d}\n" for a, b, c, d in quads))


def test_a_plan_on_a_scene_with_its_own_mesh_replays_with_that_scene_file(tmp_path):
    """plan.json's ``scene`` names the mesh by its absolute path, outside the run folder: docs/perform.md
    ("Paths") says ``--scene`` the original file replays it (without it, ``--mesh-dir``); --scene was refused
    with the recorded scene's mesh error before it was compared."""
    folder = tmp_path / "scene"
    folder.mkdir()
    _cube_obj(folder / "cube.obj")
    scene = folder / "scene.json"
    scene.write_text(json.dumps({"objects": [
        {"name": "A", "color": "red", "shape": "mesh", "mesh": "cube.obj", "scale": 0.04, "xy": [0.05, -0.1]},
        {"name": "B", "color": "green", "size": 0.05, "xy": [0.0, 0.05]}]}))
    plan = tmp_path / "plan"
    _run("plan", "move A closer to B", "--scene", str(scene), "--out", str(plan), "--no-plot")
    out = tmp_path / "replay"
    _run("replay", str(plan / "plan.json"), "--scene", str(scene), "--no-render", "--out", str(out))
    assert json.loads((out / "plan.json").read_text())["scene_sha256"] == json.loads(
        (plan / "plan.json").read_text())["scene_sha256"]
    _run("replay", str(plan / "plan.json"), "--mesh-dir", str(folder), "--no-render", "--out", str(tmp_path / "r2"))
