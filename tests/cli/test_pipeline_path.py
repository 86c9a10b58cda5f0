"""One pipeline path: ``perform``, ``plan`` and the evaluation worker go through the same stages
(``pipeline.prepare``, ``pipeline.judged_plan``), so the same sentence, scene and seed give the same plan and
the same verdict on it whichever door it came in by; a bad option is refused by all three alike."""

from __future__ import annotations

import json

import numpy as np
import pytest

from l2p_bullet import pipeline
from l2p_bullet.core.scene import default_scene
from l2p_bullet.errors import PlanError
from l2p_bullet.evaluate.tasks import Task
from l2p_bullet.evaluate.worker import Worker


def _task(mode: str, **kw) -> Task:
    scene = default_scene().to_dict()
    return Task(run_id="t", index=0, scene_id="default", scene_source="default", scene=scene, mover="A",
                anchor="B", action="next-to", sentence="move A next to B", planner="default", seed=3, mode=mode, **kw)


def test_plan_and_the_evaluation_worker_give_one_plan_and_verdict(tmp_path):
    r = pipeline.plan_sentence("move A next to B", default_scene(), out_dir=tmp_path / "plan", seed=3, plot=False)
    worker = Worker()
    try:
        row = worker.run(_task("plan", keep="all", run_dir=str(tmp_path / "worker")))
    finally:
        worker.close()
    assert row["error"] is None, row
    kept = json.loads((tmp_path / "worker" / "plan.json").read_text())
    assert np.array_equal(
        np.asarray(kept["path"]), np.asarray(json.loads((r.out_dir / "plan.json").read_text())["path"])
    )
    assert kept["verdict"] == r.verdict and row["success"] == int(r.verdict["success"])
    assert row["score"] == r.verdict["score"] and kept["sentence"] == "move A next to B"


def test_a_bad_option_is_refused_by_every_door(tmp_path):
    with pytest.raises(PlanError, match="budget"):
        pipeline.prepare("move A next to B", default_scene(), budget=0)
    with pytest.raises(PlanError, match="budget"):
        pipeline.plan_sentence("move A next to B", default_scene(), out_dir=tmp_path / "p", budget=0)
    assert not (tmp_path / "p").exists()
    worker = Worker()
    try:  # the worker used to skip check_options: the row now names the same error
        row = worker.run(_task("plan", budget=0))
    finally:
        worker.close()
    assert row["error_type"] == "PlanError" and "budget" in row["error"]


@pytest.mark.slow
def test_perform_plans_and_judges_its_plan_as_plan_does_and_writes_one_summary(tmp_path):
    r = pipeline.plan_sentence("move A next to B", default_scene(), out_dir=tmp_path / "plan", seed=3, plot=False)
    p = pipeline.perform("move A next to B", default_scene(), out_dir=tmp_path / "run", seed=3, render=False)
    assert np.array_equal(p.plan.path, r.plan.path) and p.planned_verdict == r.verdict
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    # execute's fields and perform's, in the one file written at the end
    assert summary["execution"]["max_deviation_m"] >= 0 and summary["verdict"] == p.verdict
    assert {"check", "move", "record", "parse", "feasibility", "load", "plan", "execute", "total"} <= set(
        summary["timings_s"]
    )
    assert summary["files"]["summary"] == "summary.json" and summary["files"]["plan"] == "plan.json"


def test_the_python_front_door_checks_its_arguments_before_the_disk(tmp_path):
    """A library user's mistakes (API audit, 2026-11-27): a scene that is not a Scene, bad render settings, are
    one-line L2PErrors before any folder exists; a seed drawn from numpy (np.int64) is a seed."""
    from l2p_bullet.embodiment.sim.camera import RenderSettings
    from l2p_bullet.errors import ExecutionError, SceneError

    with pytest.raises(SceneError, match="must be a l2p_bullet.core.scene.Scene"):
        pipeline.plan_sentence("move A past B", default_scene().to_dict(), out_dir=tmp_path / "p")
    for bad, said in ((RenderSettings(width=-1), r"video width must be a whole number of pixels .*\(got -1\)"),
                      ("big", r"render_settings must be a RenderSettings \(got str\)")):
        with pytest.raises(ExecutionError, match=said):
            pipeline.perform("move A past B", default_scene(), out_dir=tmp_path / "r", render_settings=bad)
    assert not (tmp_path / "p").exists() and not (tmp_path / "r").exists()
    a = pipeline.plan_sentence("move A past B", default_scene(), out_dir=tmp_path / "a", seed=np.int64(3), plot=False)
    b = pipeline.plan_sentence("move A past B", default_scene(), out_dir=tmp_path / "b", seed=3, plot=False)
    assert np.array_equal(a.plan.path, b.plan.path)
