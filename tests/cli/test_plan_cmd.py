"""``l2p-bullet plan``: the files it writes and its errors (with a stand-in bundle, no weights needed)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner
from planning_fakes import FakeBundle

from l2p_bullet.cli import main
from l2p_bullet.core.contracts import load_motion
from l2p_bullet.plugins import registry

PHRASES = {"around": "around", "past": "past", "next to": "next-to", "closer to": "closer", "away from": "away"}


@pytest.fixture
def fake_actions(monkeypatch):
    monkeypatch.setattr(registry, "phrase_table", lambda plugins=None: dict(PHRASES))
    monkeypatch.setattr(registry, "load", lambda name, plugins=None: FakeBundle(name))


def test_plan_writes_plan_json_and_a_plot(fake_actions, tmp_path):
    out = tmp_path / "run"
    r = CliRunner().invoke(main, ["plan", "move A around B", "--out", str(out), "--planner", "discrete", "--json"])
    assert r.exit_code == 0, r.output
    summary = json.loads(r.output.strip().splitlines()[-1])
    assert summary["action"] == "around" and summary["stopped"] == "threshold"
    plan = json.loads((out / "plan.json").read_text())
    assert plan["schema"] == 1 and plan["mover"] == "A" and plan["anchor"] == "B" and plan["planner"] == "discrete"
    assert len(plan["path"]) == len(plan["progress"]) > 2
    assert plan["verdict"]["success"] is True and plan["verdict"]["judge"] == "rules"
    motion = load_motion(out / "plan.json")  # readable by the scoring tools
    assert np.allclose(motion.mover[0], plan["start"])
    png = (out / "plan.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000
    again = CliRunner().invoke(main, ["plan", "move A around B", "--out", str(tmp_path / "bare"), "--no-plot"])
    assert again.exit_code == 0 and sorted(p.name for p in (tmp_path / "bare").iterdir()) == [
        ".l2p-run.json",
        "plan.json",
    ]
    # without --json: text in perform's style (issue 26)
    lines = again.stdout.strip().splitlines()
    assert lines[0].startswith('A around B: action "around", success on the plan (') and "final progress" in lines[1]
    assert lines[-1] == f"plan folder: {tmp_path / 'bare'} (no plot: --no-plot)"


def test_the_plot_shows_the_objects_and_the_path(tmp_path):
    """Pixels, not just a PNG header: the anchor's green, the mover's red footprints, the black path."""
    from PIL import Image

    from l2p_bullet.core.scene import default_scene
    from l2p_bullet.planning import plan
    from l2p_bullet.planning.plot import plot_plan

    scene = default_scene()
    p = plan(scene, "A", "B", FakeBundle("around"), planner="discrete")
    img = np.asarray(Image.open(plot_plan(p, scene, tmp_path / "plan.png")).convert("RGB")).astype(int)
    green = (img[..., 1] > 150) & (img[..., 0] < 60) & (img[..., 2] < 90)
    red = (img[..., 0] > 180) & (img[..., 1] < 120) & (img[..., 2] < 120)
    black = img.sum(-1) < 60
    assert green.sum() > 300 and red.sum() > 300 and black.sum() > 300


def test_plan_reads_a_scene_file_and_never_overwrites_without_force(fake_actions, tmp_path):
    scene = {"objects": [{"name": "A", "color": "red", "size": 0.04, "xy": [0.12, 0.0], "yaw": 0.0},
                         {"name": "B", "color": "green", "size": 0.04, "xy": [0.0, 0.0], "yaw": 0.0}]}
    (tmp_path / "scene.json").write_text(json.dumps(scene))
    out = tmp_path / "run"
    args = ["plan", "slide the red block next to the green one", "--scene", str(tmp_path / "scene.json"),
            "--out", str(out), "--seed", "3"]
    r = CliRunner().invoke(main, args)
    assert r.exit_code == 0, r.output
    assert json.loads((out / "plan.json").read_text())["size"] == 0.04
    again = CliRunner().invoke(main, args)
    assert again.exit_code == 2 and "--force" in again.output
    assert CliRunner().invoke(main, [*args, "--force"]).exit_code == 0


def test_an_unknown_planner_is_a_one_line_error_listing_the_planners(fake_actions, tmp_path):
    r = CliRunner().invoke(main, ["plan", "move A around B", "--planner", "astar", "--out", str(tmp_path / "x")])
    assert r.exit_code == 2
    assert "unknown planner" in r.output and "greedy, beam, discrete, reinforce, mixed, default" in r.output
    assert not (tmp_path / "x").exists()


def test_budget_and_threshold_reach_the_planner(fake_actions, tmp_path):
    out = tmp_path / "run"
    r = CliRunner().invoke(main, ["plan", "move A around B", "--out", str(out), "--planner", "greedy",
                                  "--budget", "2", "--threshold", "0.999"])
    assert r.exit_code == 0, r.output
    plan = json.loads((out / "plan.json").read_text())
    assert plan["stopped"] == "budget" and plan["steps"] == 2 and plan["threshold"] == 0.999
    bad = CliRunner().invoke(main, ["plan", "move A around B", "--threshold", "2"])
    assert bad.exit_code == 2 and "threshold" in bad.output


def test_plan_json_says_why_it_failed_as_json(tmp_path):
    """As perform --json: a script reads the failure on stdout (exit 2; the one-line error on stderr)."""
    r = CliRunner().invoke(main, ["plan", "move Z past A", "--json", "--out", str(tmp_path / "p")])
    assert r.exit_code == 2
    d = json.loads(r.stdout[: r.stdout.rindex("}") + 1])
    assert d["ok"] is False and d["error_type"] == "UnknownObjectError" and not (tmp_path / "p").exists()
