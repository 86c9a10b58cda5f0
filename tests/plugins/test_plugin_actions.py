"""Every command that takes an action works for a plugin action too (issue 9's bugs: ``plan`` called the
built-in-only evaluator, ``score`` only knew built-in names), and a malformed plan.json is a one-line
error everywhere it is read."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner
from plugin_fixtures import copy_builtin_as_plugin

from l2p_bullet.cli import main
from l2p_bullet.plugins import registry


@pytest.fixture
def plugin(tmp_path, monkeypatch):
    """An installed plugin action "toward-test" (phrase "towards the side of") with real weights and no rules."""
    root = tmp_path / "site"
    root.mkdir()
    copy_builtin_as_plugin(root, "closer", "toward-test", ["towards the side of"])
    monkeypatch.syspath_prepend(str(root))
    registry._LOADED.clear()
    yield "toward-test"
    registry._LOADED.clear()


def test_plan_works_for_a_plugin_action_and_its_judge_is_its_progress_model(plugin, tmp_path):
    out = tmp_path / "plan"
    r = CliRunner().invoke(main, ["plan", "move A towards the side of B", "--out", str(out), "--json"])
    assert r.exit_code == 0, r.output
    summary = json.loads(r.output)
    assert summary["action"] == plugin
    verdict = json.loads((out / "plan.json").read_text())["verdict"]
    assert verdict["judge"] == "progress-model"
    assert verdict["success"] == (summary["final_progress"] >= 0.5)


def test_score_works_for_an_installed_plugin_action(plugin, tmp_path):
    motion = tmp_path / "m.json"
    motion.write_text(json.dumps({"size": 0.15, "mover": [[0.9, 0, 0], [0.5, 0, 0], [0.2, 0, 0]],
                                  "anchor": [[0, 0, 0]]}))
    r = CliRunner().invoke(main, ["score", plugin, str(motion)])
    assert r.exit_code == 0, r.output
    d = json.loads(r.output)
    assert d["action"] == plugin and len(d["progress"]) == 3 and 0.0 <= d["final"] <= 1.0
    # the plugin is a renamed copy of "closer": the same weights give the same numbers
    builtin = json.loads(CliRunner().invoke(main, ["score", "closer", str(motion)]).output)
    assert d["progress"] == builtin["progress"]


@pytest.mark.parametrize("bad", [{"size": "big"}, {"size": [1]}, {"anchor_pose": "here"}, {"action": None, "path": 3}])
def test_a_malformed_plan_json_is_a_one_line_error_for_score_and_replay(tmp_path, bad):
    good = {"schema": 1, "action": "closer", "mover": "A", "anchor": "B", "size": 0.05,
            "anchor_pose": [0.0, 0.05, 0.0], "start": [0.05, -0.1, 0.3],
            "path": [[0.05, -0.1, 0.3], [0.02, -0.02, 0.3]], "progress": [0.0, 0.5], "planner": "greedy",
            "stopped": "budget"}
    plan = tmp_path / "plan.json"
    plan.write_text(json.dumps(good | bad))
    for args in (["score", "closer", str(plan)], ["replay", str(plan), "--no-render", "--out", str(tmp_path / "r")]):
        r = CliRunner().invoke(main, args)
        lines = r.output.strip().splitlines()
        assert r.exit_code == 2 and len(lines) == 1 and lines[0].startswith("error: "), (args, r.output)
        assert "plan.json" in lines[0]
