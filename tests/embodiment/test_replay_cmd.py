"""The ``replay`` command end to end: demonstrations, scoring inputs, plans, run folders, bad input."""

from __future__ import annotations

import errno
import json
import os

import numpy as np
import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.core.scene import default_scene
from l2p_bullet.data.demos import get_demo
from l2p_bullet.embodiment import motion
from l2p_bullet.embodiment.retarget import to_anchor_frame


def _replay(*args):
    return CliRunner().invoke(main, ["replay", *args])


@pytest.fixture(scope="module")
def demo_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("runs") / "past0"
    r = _replay("--demo", "past:0", "--out", str(out), "--width", "160", "--height", "120", "--render-fps", "5")
    assert r.exit_code == 0, r.output
    return out, r


def test_demo_replay_writes_the_run_folder(demo_run):
    out, r = demo_run
    assert f"run folder: {out}\nvideo: {out / 'video.mp4'}" in r.stdout  # as perform says it (issue 26)
    assert "[" in r.stderr and "s] execute: " in r.stderr  # stage lines in perform's style
    for name in ("trajectory.json", "plan.json", "summary.json", "video.mp4", "contact_sheet.png"):
        assert (out / name).stat().st_size > 0, name
    import json

    listed = json.loads((out / "summary.json").read_text())["files"]  # every file, plan.json included
    assert {"trajectory", "plan", "summary"} <= set(listed) and listed["plan"] == "plan.json"
    frames = sorted((out / "frames").glob("*.png"))
    assert len(frames) > 10
    import imageio.v2 as imageio

    assert imageio.imread(frames[0]).shape == (120, 160, 3)
    assert imageio.imread(out / "contact_sheet.png").shape[1] == 4 * 160
    with imageio.get_reader(out / "video.mp4") as video:  # a real, decodable video of every frame
        decoded = [f for f in video]
    from l2p_bullet.embodiment.overlay import strip_height

    # every frame, with the caption strip (sentence, learned progress) under it
    assert len(decoded) == len(frames) and decoded[0].shape == (120 + strip_height(120), 160, 3)


def test_demo_replay_keeps_the_demo_relative_to_the_anchor(demo_run):
    out, _ = demo_run
    traj = json.loads((out / "trajectory.json").read_text())
    assert traj["action"] == "past" and traj["mover"] == "A" and traj["anchor"] == "B"
    held = np.array([[f["poses"]["A"][i] for i in (0, 1, 3)] for f in traj["frames"] if f["grasped"] == "A"])
    b = default_scene().get("B")
    got = to_anchor_frame(held, b.pose, b.size)  # in block units around B
    demo = get_demo("past", 0)
    want = to_anchor_frame(demo.event_mover, demo.event_anchor, demo.size)
    # every executed point lies near the demonstrated relative path (block units; smoothing and the
    # documented fix-ups may move it a little), and both ends match
    d = motion.polyline_distance(got[:, :2], want[:, :2])
    summary = json.loads((out / "summary.json").read_text())
    fix = summary["replay"]["retarget"]["max_fix_m"] / b.size
    assert d.max() < 0.2 + fix
    assert np.hypot(*(got[-1, :2] - want[-1, :2])) < 0.2 + fix
    assert summary["execution"]["max_deviation_m"] < 0.003 and summary["execution"]["anchor_displacement_m"] < 0.001
    plan = json.loads((out / "plan.json").read_text())
    assert plan["mover"] == "A" and len(plan["path"]) == len(plan["progress"])


def test_existing_run_folder_needs_force(demo_run, tmp_path):
    out, _ = demo_run
    r = _replay("--demo", "past:0", "--out", str(out), "--no-render")
    assert r.exit_code == 2 and "already holds a finished run" in r.output and "--force" in r.output


def test_replay_a_scoring_input_and_its_plan(tmp_path):
    # a straight slide of 2 blocks towards the anchor, in a 0.15 m-block frame somewhere else
    size = 0.15
    anchor = [[2.0, 1.0, 0.5]] * 10
    t = np.linspace(0, 1, 10)[:, None]
    start, end = np.array([2.0 + 4 * size, 1.0, 0.5]), np.array([2.0 + 2 * size, 1.0, 0.5])
    mover = (start + t * (end - start)).tolist()
    src = tmp_path / "motion.json"
    src.write_text(json.dumps({"size": size, "mover": mover, "anchor": anchor}))
    r = _replay(str(src), "--out", str(tmp_path / "a"), "--no-render")
    assert r.exit_code == 0, r.output
    traj = json.loads((tmp_path / "a" / "trajectory.json").read_text())
    b = default_scene().get("B")
    a_end = np.array(traj["frames"][-1]["poses"]["A"])
    assert np.hypot(*(a_end[:2] - b.xy)) == pytest.approx(2 * b.size, abs=0.003)  # 2 blocks from B
    # the plan.json it wrote replays to the same place
    r = _replay(str(tmp_path / "a" / "plan.json"), "--out", str(tmp_path / "b"), "--no-render")
    assert r.exit_code == 0, r.output
    traj_b = json.loads((tmp_path / "b" / "trajectory.json").read_text())
    assert np.allclose(traj_b["frames"][-1]["poses"]["A"][:2], a_end[:2], atol=0.002)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        ([], "give either PATH_JSON or --demo"),
        (["--demo", "around"], "expects ACTION:INDEX"),
        (["--demo", "around:999"], "there is no index 999"),
        (["--demo", "aroud:0"], 'Did you mean "around"'),
        (["--demo", "past:0", "--mover", "C"], 'no object named "C"'),
    ],
)
def test_bad_input_is_one_clear_line(tmp_path, args, message):
    r = _replay(*args, "--out", str(tmp_path / "x"), "--no-render")
    lines = r.output.strip().splitlines()
    assert r.exit_code == 2 and len(lines) == 1 and lines[0].startswith("error: "), r.output
    assert message in lines[0] and "Traceback" not in r.output
    assert not (tmp_path / "x").exists()  # refused before the run folder is made, not a failed run left in it


def test_missing_path_file(tmp_path):
    r = _replay(str(tmp_path / "nope.json"), "--no-render", "--out", str(tmp_path / "x"))
    assert (
        r.exit_code == 2 and r.output == f"error: cannot read {tmp_path / 'nope.json'}: {os.strerror(errno.ENOENT)}\n"
    )
    assert not (tmp_path / "x").exists()


@pytest.mark.slow
def test_a_plan_replays_on_the_scene_it_records(tmp_path):
    """Issue 26: a plan made with --scene replayed on the default scene ran into B and left a failed
    folder; a plan from a three-block scene replayed without C. plan.json records its scene now."""
    from l2p_bullet.core.scene import random_between_scene, save_scene

    scene = random_between_scene(2)
    save_scene(scene, tmp_path / "three.json")
    r = CliRunner().invoke(main, ["plan", "move A closer to B", "--scene", str(tmp_path / "three.json"), "--no-plot",
                                  "--out", str(tmp_path / "p")])
    assert r.exit_code == 0, r.output
    doc = json.loads((tmp_path / "p" / "plan.json").read_text())
    assert doc["scene"] == scene.to_dict() and doc["scene_sha256"] == scene.digest()
    out = tmp_path / "r"
    r = _replay(str(tmp_path / "p" / "plan.json"), "--no-render", "--out", str(out))
    assert r.exit_code == 0, r.output
    traj = json.loads((out / "trajectory.json").read_text())
    assert "C" in traj["frames"][0]["poses"]  # replayed with the plan's third block
    assert json.loads((out / "plan.json").read_text())["scene_sha256"] == scene.digest()
    r = _replay(str(tmp_path / "p"), "--no-render", "--out", str(tmp_path / "r-folder"))  # a run folder: its plan
    assert r.exit_code == 0, r.output
    assert json.loads((tmp_path / "r-folder" / "trajectory.json").read_text())["frames"][-1] == traj["frames"][-1]
    # another --scene: refused in one line, before any folder is made
    save_scene(default_scene(), tmp_path / "default.json")
    r = _replay(str(tmp_path / "p" / "plan.json"), "--no-render", "--scene", str(tmp_path / "default.json"),
                "--out", str(tmp_path / "r2"))
    assert r.exit_code == 2 and "planned on another scene" in r.output and len(r.output.strip().splitlines()) == 1
    assert not (tmp_path / "r2").exists()
    # the same scene named again is fine
    r = _replay(str(tmp_path / "p" / "plan.json"), "--no-render", "--scene", str(tmp_path / "three.json"),
                "--out", str(tmp_path / "r3"))
    assert r.exit_code == 0, r.output


def test_quiet_replay_prints_only_its_result(tmp_path):
    """-q as perform's: no progress lines on stderr, the result on stdout."""
    r = CliRunner().invoke(main, ["replay", "--demo", "next-to:0", "--no-render", "-q", "--out", str(tmp_path / "q")])
    assert r.exit_code == 0, r.output
    assert r.stderr == "" and r.stdout.startswith("replayed demonstration") and "run folder: " in r.stdout
    loud = CliRunner().invoke(main, ["replay", "--demo", "next-to:0", "--no-render", "--out", str(tmp_path / "l")])
    assert "execute: " in loud.stderr
