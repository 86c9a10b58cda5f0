"""A chain's run folder keeps DESIGN.md section 4's contracts in every way it can end (contract audit,
2026-11-28): segments within the frames recorded when a clause breaks off before the arm moves, the chain's
verdict agreeing with a composite's row verdict, ``plan`` of a chain recording its scene as a one-clause plan
does, and ``replay`` of a chain's plan.json marked as a replay as a one-clause replay is."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from l2p_bullet.chain import perform_chain
from l2p_bullet.chain import run as chain_run
from l2p_bullet.chain.clauses import Clause
from l2p_bullet.chain.composite import judge_row
from l2p_bullet.chain.run import ChainResult, ClauseResult
from l2p_bullet.chain.segments import score_segments, segments_of
from l2p_bullet.cli import main
from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.errors import PlanError
from l2p_bullet.language import Command
from l2p_bullet.plugins import registry


def four_blocks() -> Scene:
    return Scene([SceneObject("A", "red", 0.04, (0.10, -0.08), 0.2), SceneObject("B", "green", 0.04, (0.0, 0.02), 0.0),
                  SceneObject("C", "blue", 0.04, (-0.12, -0.06), 0.4),
                  SceneObject("D", "yellow", 0.04, (-0.06, 0.10), 0.1)]).validate()


@pytest.mark.slow
def test_a_clause_that_breaks_off_before_the_arm_moves_has_a_frame_of_its_own(tmp_path, monkeypatch):
    """Clause 2 cannot be re-planned from the real state (its stage: plan): nothing moved, but its segment
    and its summary entry must still name frames the trajectory has (they named frame N of N frames, and
    score, export and review refused the run as malformed)."""

    def refuse(*args, **kwargs):
        raise PlanError("no legal move from here")

    monkeypatch.setattr(chain_run, "check_feasible", refuse)  # the run-time re-plan only (the forecast passed)
    out = tmp_path / "run"
    r = perform_chain("move A next to B, then move C past B", four_blocks(), out_dir=out, render=False)
    assert not r.success and r.completed == 1 and r.results[1].failed_stage == "plan"
    doc = json.loads((out / "trajectory.json").read_text())
    n = len(doc["frames"])
    segs = segments_of(doc)  # raised PathError: frames N..N of N
    assert [(s["clause"], s["first_frame"]) for s in segs] == [(1, 0), (2, segs[0]["last_frame"] + 1)]
    assert segs[-1]["last_frame"] == n - 1 and segs[1]["first_frame"] <= segs[1]["last_frame"]
    times = np.array([f["t"] for f in doc["frames"]])
    assert np.allclose(np.diff(times), 1 / doc["fps"], atol=2e-6)  # still sampled at fps
    summary = json.loads((out / "summary.json").read_text())
    assert [(c["first_frame"], c["last_frame"]) for c in summary["clauses"]] == [
        (s["first_frame"], s["last_frame"]) for s in segs]
    assert summary["chain"]["failed_clause"] == 2 and not summary["success"]
    scored = score_segments(out / "trajectory.json", registry.load("past").progress_model())
    assert [s["clause"] for s in scored] == [1, 2]


def test_a_composite_whose_blocks_are_no_row_fails_its_chain_verdict_too(tmp_path):
    """Every clause done but the blocks are no row: summary.json's ``chain`` says so, as ``verdict`` and
    ``success`` do (it kept the clauses' "all 2 clauses done", success true, beside success false)."""
    scene = four_blocks()

    class Slot:  # what judge_row reads of a composite's slot: the block that stays
        stay = "A"

    clauses = [Clause(i, t, Command("move", m, "next to", "next-to", a, t, (a,)), target=Slot())
               for i, (t, m, a) in enumerate([("move B next to A", "B", "A"), ("move C next to B", "C", "B")], 1)]
    results = [ClauseResult(c, None, {"success": True, "reason": "ends next to it"}, 0, 0,
                            displacements_m={"D": 0.0}) for c in clauses]
    result = ChainResult("make a row of A, B and C", clauses, results, tmp_path, {})
    steps = [type("Step", (), {"clause": c})() for c in clauses]
    summary = tmp_path / "summary.json"
    summary.write_text(json.dumps({"schema": 1, "ok": True, "chain": result.verdict(), "success": True,
                                   "verdict": {"success": True, "reason": "all 2 clauses done"}}))
    row = judge_row(result, steps, scene, summary)  # A, B and C lie nowhere near a row in four_blocks
    assert not row["success"]
    s = json.loads(summary.read_text())
    assert s["success"] is False and s["verdict"]["success"] is False
    assert s["chain"] == result.verdict() and s["chain"]["success"] is False
    assert s["chain"]["reason"] == s["verdict"]["reason"]


def test_plan_of_a_chain_records_its_scene_as_a_one_clause_plan_does(tmp_path):
    scene_file = tmp_path / "scene.json"
    scene_file.write_text(json.dumps(four_blocks().to_dict()))
    out = tmp_path / "plan"
    r = CliRunner().invoke(main, ["plan", "move A next to B, then move C past B", "--scene", str(scene_file),
                                  "--out", str(out), "--no-plot", "--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads((out / "plan.json").read_text())
    assert doc["scene"] == doc["chain"]["scene"] == four_blocks().to_dict()
    assert doc["scene_sha256"] == Scene.from_dict(doc["scene"]).digest() == four_blocks().digest()


@pytest.mark.slow
def test_replay_of_a_chain_writes_a_replays_plan_and_summary(tmp_path):
    """A replay's plan.json records the motion it replayed, not a plan (planner and stopped "replay", progress
    null, ``replay`` naming the source) and its summary.json says where it came from: a chain's too."""
    scene_file = tmp_path / "scene.json"
    scene_file.write_text(json.dumps(four_blocks().to_dict()))
    plan_dir = tmp_path / "plan"
    r = CliRunner().invoke(main, ["plan", "move A next to B, then move C past B", "--scene", str(scene_file),
                                  "--out", str(plan_dir), "--no-plot"])
    assert r.exit_code == 0, r.output
    out = tmp_path / "replay"
    r = CliRunner().invoke(main, ["replay", str(plan_dir / "plan.json"), "--no-render", "--out", str(out)])
    assert r.exit_code == 0, r.output
    plan = json.loads((out / "plan.json").read_text())
    source = {"source": {"plan": str(plan_dir / "plan.json")}}
    assert plan["planner"] == plan["stopped"] == "replay" and plan["replay"] == source
    assert plan["progress"] == [None] * len(plan["path"])
    for c in plan["clauses"]:
        assert c["plan"]["planner"] == c["plan"]["stopped"] == "replay"
        assert c["plan"]["progress"] == [None] * len(c["plan"]["path"])
    assert plan["scene_sha256"] == four_blocks().digest()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["replay"] == source and summary["ok"] is True
    assert summary["chain"]["completed"] == 2, summary["chain"]
    # the replay's plan.json replays again (its clauses are plans, their progress unknown)
    again = tmp_path / "again"
    r = CliRunner().invoke(main, ["replay", str(out / "plan.json"), "--no-render", "--out", str(again)])
    assert r.exit_code == 0, r.output
    a, b = (json.loads(Path(d, "trajectory.json").read_text())["frames"] for d in (out, again))
    assert len(a) == len(b) and a[-1]["poses"] == b[-1]["poses"]
