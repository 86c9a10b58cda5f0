"""A run that came near first ("around" from afar, planning/approach.py) records where its action proper began
(trajectory.json's ``action_from``, a chain segment's too), and its learned progress, ``score`` and
``recognize`` read the motion from there, as the planner scored the plan (issue 21)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from l2p_bullet.chain import perform_chain
from l2p_bullet.chain.segments import segments_of
from l2p_bullet.cli import main
from l2p_bullet.core.contracts import approach_end_frame, load_motion
from l2p_bullet.core.scene import Scene
from l2p_bullet.errors import PathError
from l2p_bullet.pipeline import perform

FAR = {"objects": [{"name": "A", "color": "red", "size": 0.04, "xy": [0.02, -0.16], "yaw": 0.3},
                   {"name": "B", "color": "green", "size": 0.04, "xy": [-0.02, 0.10]}]}


@pytest.fixture(scope="module")
def far_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("far") / "run"
    return perform("move A around B", Scene.from_dict(FAR), out_dir=out, render=False, seed=3), out


def test_the_approach_end_is_the_first_arrival_not_the_circle_coming_back():
    size = 0.04
    slide = np.c_[np.linspace(0.3, 0.1, 60), np.zeros(60)]
    ring = np.linspace(0, 2 * math.pi, 120)[1:]
    circle = np.c_[0.1 * np.cos(ring), 0.1 * np.sin(ring)]  # a full turn ends where the slide did
    track = np.vstack([np.repeat(slide[:1], 10, axis=0), slide, circle])
    assert approach_end_frame(track, np.array([0.1, 0.0, 0.0]), size) == 69
    assert approach_end_frame(track[:5], np.array([0.1, 0.0]), size) == 0  # never got there: the nearest frame


def test_a_run_that_came_near_first_reads_its_progress_from_where_the_action_began(far_run):
    r, out = far_run
    traj = json.loads((out / "trajectory.json").read_text())
    k, frames = traj["action_from"], traj["frames"]
    to = np.asarray(r.plan.extra["approach"]["to"][:2])
    assert 0 < k < len(frames) and np.hypot(*(np.asarray(frames[k]["poses"]["A"][:2]) - to)) < 0.005
    assert {f["progress"] for f in frames[:k + 1]} == {frames[k]["progress"]}  # the approach holds the first value
    assert r.final_progress == pytest.approx(r.planned_progress, abs=0.01)  # the run reads as it was planned
    summary = json.loads((out / "summary.json").read_text())
    assert summary["final_progress"] == pytest.approx(r.final_progress, abs=1e-6)

    scored = json.loads(
        CliRunner().invoke(main, ["score", "around", str(out / "trajectory.json")], catch_exceptions=False).output
    )
    assert scored["final"] == pytest.approx(r.final_progress, abs=1e-3)
    assert len(scored["progress"]) == len(frames)  # one value per frame of the file, as before
    assert load_motion(out / "trajectory.json").action_from == k


def test_a_run_without_an_approach_has_no_action_from(tmp_path):
    near = {"objects": [dict(FAR["objects"][0], xy=[0.02, -0.02]), FAR["objects"][1]]}
    perform("move A around B", Scene.from_dict(near), out_dir=tmp_path / "run", render=False, seed=3)
    traj = json.loads((tmp_path / "run" / "trajectory.json").read_text())
    assert "action_from" not in traj and "action_from" not in json.loads(
        (tmp_path / "run" / "summary.json").read_text()
    )


def test_a_bad_action_from_is_a_clear_error(far_run, tmp_path):
    _, out = far_run
    doc = json.loads((out / "trajectory.json").read_text())
    doc["action_from"] = len(doc["frames"]) + 5
    bad = tmp_path / "trajectory.json"
    bad.write_text(json.dumps(doc))
    with pytest.raises(PathError, match='"action_from" must be a frame index'):
        load_motion(bad)
    segs = {"segments": [{"first_frame": 0, "last_frame": 3, "action_from": 9, "mover": "A", "anchors": ["B"]}],
            "frames": doc["frames"][:4], "objects": doc["objects"]}
    with pytest.raises(PathError, match="malformed segment"):
        segments_of(segs)


@pytest.mark.slow
def test_a_chain_clause_that_came_near_first_records_it_in_its_segment(tmp_path):
    scene = Scene.from_dict({"objects": [*FAR["objects"],
                                         {"name": "C", "color": "blue", "size": 0.04, "xy": [0.13, -0.17]}]})
    r = perform_chain("move C next to A, then move A around B", scene, out_dir=tmp_path / "chain", render=False, seed=3)
    traj = json.loads((tmp_path / "chain" / "trajectory.json").read_text())
    seg = traj["segments"][1]
    assert "action_from" not in traj["segments"][0] and seg["first_frame"] < seg["action_from"] <= seg["last_frame"]
    clause = r.results[1]
    assert clause.final_progress == pytest.approx(float(clause.plan.progress[-1]), abs=0.02)
    scored = json.loads(CliRunner().invoke(main, ["score", "around", str(tmp_path / "chain" / "trajectory.json")],
                                           catch_exceptions=False).output)
    assert scored["segments"][1]["final"] == pytest.approx(clause.final_progress, abs=1e-3)
