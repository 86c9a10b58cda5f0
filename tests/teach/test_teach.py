"""The teach app's API and the demos file it writes: validated on write, read back by the loader,
appended to, never half-written; bad requests are 4xx with a message."""

from __future__ import annotations

import numpy as np
import pytest
from teach_fixtures import live  # noqa: F401 - fixture

from l2p_bullet.core.scene import random_between_scene, random_scene
from l2p_bullet.data.demos import DEMO_BLOCK_SIZE, load_demos, load_session
from l2p_bullet.teach.lesson import CONTEXT


def clear_scene(offset=(0.0, 0.075)):
    """(seed, scene, goal): the first random scene where A slides straight to B + ``offset`` (1.5 blocks to
    the robot's left) without coming within 1.5 blocks of B."""
    for seed in range(100):
        scene = random_scene(seed)
        a, b = np.array(scene.get("A").xy), np.array(scene.get("B").xy)
        goal = b + offset
        t = np.clip((b - a) @ (goal - a) / ((goal - a) @ (goal - a)), 0, 1)
        if np.linalg.norm(a + t * (goal - a) - b) > 0.075:
            return seed, scene, goal
    raise AssertionError("no clear scene")


def slide(scene, goal_xy, seconds: float = 1.5, rest: float = 0.5, rate: float = 60.0, seed: int = 0) -> dict:
    """A recording of A resting, sliding in a straight line to ``goal_xy``, resting: start/end marked at the slide."""
    a = scene.get("A")
    t_rest = np.arange(0, rest, 1 / rate)
    t_move = np.arange(0, seconds, 1 / rate)
    start = np.array(a.xy)
    rows = [[t, *start, a.yaw] for t in t_rest]
    for t in t_move:
        p = start + (np.asarray(goal_xy) - start) * t / seconds
        rows.append([rest + t, *p, a.yaw])
    rows += [[rest + seconds + t, *goal_xy, a.yaw] for t in t_rest]
    return {"scene": seed, "samples": rows, "start": rest, "end": rest + seconds}


def test_a_saved_demonstration_is_the_recording_in_the_capture_format(live):  # noqa: F811
    s = live(frame="viewer")
    seed, scene, goal = clear_scene()  # goal: 1.5 blocks to the robot's left of B
    status, r = s.call("POST", "/api/demos", slide(scene, goal, seed=seed))
    assert status == 200, r
    assert r["count"] == 1
    arrays = load_session(s.action.demos)
    k = DEMO_BLOCK_SIZE / scene.get("A").size
    assert np.allclose(arrays["viewer_xy"], np.array([-0.53, 0.0]) * k)
    (d,) = load_demos("left-of", [s.action.demos])
    assert d.start >= CONTEXT and len(d.mover) - 1 - d.end >= CONTEXT  # rest around the event
    assert np.allclose(d.mover[d.start, :2] / k, scene.get("A").xy, atol=1e-3)
    assert np.allclose(d.mover[d.end, :2] / k, goal, atol=2e-3)
    assert np.allclose(d.anchor[:, :2] / k, scene.get("B").xy)
    assert (d.end - d.start) == pytest.approx(1.5 * 30, abs=2)  # 30 frames per second

    status, r = s.call("POST", "/api/demos", slide(scene, goal, seconds=1.0, seed=seed))  # appended, not replaced
    assert status == 200 and r["count"] == 2
    ds = load_demos("left-of", [s.action.demos])
    assert len(ds) == 2 and np.allclose(ds[0].mover, d.mover)


def test_two_anchor_demonstrations_carry_both_anchors(live):  # noqa: F811
    s = live("between", "between", anchors=2)
    scene = random_between_scene(0)
    mid = (np.array(scene.get("B").xy) + np.array(scene.get("C").xy)) / 2
    rec = slide(scene, mid)
    a = np.array(scene.get("A").xy)
    # go round the anchors: via a point beside the segment's middle on A's side
    e = np.array(scene.get("C").xy) - np.array(scene.get("B").xy)
    n = np.array([-e[1], e[0]]) / np.linalg.norm(e)
    via = mid + n * np.sign((a - mid) @ n) * 0.12
    rows = [r for r in rec["samples"] if r[0] < 0.5]
    rows += [[0.5 + t, *(a + (via - a) * t), 0.0] for t in np.linspace(0, 1, 40)]
    rows += [[1.5 + t, *(via + (mid - via) * t), 0.0] for t in np.linspace(0, 1, 40)]
    rows += [[2.6 + t, *mid, 0.0] for t in np.linspace(0, 0.5, 20)]
    yaw = scene.get("A").yaw
    rows = [[t, x, y, yaw] for t, x, y, _ in rows]
    status, r = s.call("POST", "/api/demos", {"scene": 0, "samples": rows, "start": 0.5, "end": 2.5})
    assert status == 200, r
    arrays = load_session(s.action.demos)
    assert arrays["more_poses"].shape[0] == 1 and arrays["event_anchors"].tolist() == [[1, 2]]
    (d,) = load_demos("between", [s.action.demos])
    k = DEMO_BLOCK_SIZE / scene.get("A").size
    assert np.allclose(d.more_anchors[0][:, :2] / k, scene.get("C").xy)


@pytest.mark.parametrize("change, field", [
    (lambda r, sc: r["samples"].__setitem__(0, [0.0, 0.2, 0.2, 0.0]), None),  # does not start at A
    (lambda r, sc: r.update(start=r["end"] + 0.1), None),  # start after end
    (lambda r, sc: r.update(end=r["start"] + 0.05), None),  # too short
    (lambda r, sc: r.update(samples=r["samples"][:1]), "samples"),  # a single sample
    (lambda r, sc: r.update(extra=1), "extra"),  # unknown field
    (lambda r, sc: r.update(scene=-1), "scene"),
    (lambda r, sc: r["samples"].__setitem__(3, [0.1, 0.0, 0.0]), "samples"),  # a row of 3
])
def test_bad_recordings_are_refused_with_a_message_and_nothing_is_written(live, change, field):  # noqa: F811
    s = live()
    seed, scene, goal = clear_scene()
    rec = slide(scene, goal, seed=seed)
    change(rec, scene)
    status, r = s.call("POST", "/api/demos", rec)
    assert status in (400, 422) and isinstance(r["error"], str) and r["error"], r
    if field:
        assert field in r["error"]
    assert not s.action.demos.exists()


def test_a_slide_through_the_anchor_is_refused(live):  # noqa: F811
    s = live()
    scene = random_scene(0)
    a, b = np.array(scene.get("A").xy), np.array(scene.get("B").xy)
    status, r = s.call("POST", "/api/demos", slide(scene, b + (b - a) / np.linalg.norm(b - a) * 0.1))
    assert status == 400 and "through block B" in r["error"]
    assert not s.action.demos.exists()


def test_malformed_json_training_without_demos_and_unknown_runs(live):  # noqa: F811
    s = live()
    status, r = s.call("POST", "/api/demos", raw=b"{not json")
    assert status == 422 and "JSON" in r["error"]
    status, r = s.call("POST", "/api/train")
    assert status == 400 and "no demonstrations" in r["error"]
    status, r = s.call("GET", "/api/runs/3/video")
    assert status == 404 and r["error"]
    status, r = s.call("GET", "/api/scene?seed=-4")
    assert status == 422
    status, cfg = s.call("GET", "/api/config")
    assert (cfg["action"], cfg["frame"], cfg["anchors"], cfg["count"]) == ("left-of", "relative", 1, 0)
    assert s.url.startswith("http://127.0.0.1:")
