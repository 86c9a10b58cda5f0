"""What a hostile or broken page may post to the teach app (single action and composite rows): refused
with a 4xx and a readable message before anything is resampled or written, never a duplicate, never a
block passing through another between two frames."""

from __future__ import annotations

import json
import time

import numpy as np
import pytest
from teach_fixtures import live  # noqa: F401 - fixture
from test_teach import clear_scene, slide

from l2p_bullet.core.scene import random_scene


def test_a_valid_row_is_saved_once(rows):
    status, r = rows.post(rows.drag("B"), rows.drag("C"))
    assert status == 200 and r["count"] == 1, r
    status, r = rows.post(rows.drag("B", t0=500.0), rows.drag("C", t0=501.0))  # the same row, times shifted
    assert status == 409 and "already" in r["error"], r
    assert rows.lesson.count() == 1


@pytest.mark.parametrize("seconds", [1e6, 1e300])
def test_a_drag_over_the_duration_limit_is_refused_at_once(rows, seconds):
    """A span of 1e6 s used to resample to 3e7 frames (minutes, ~1 GB); 1e300 s was a 500."""
    t = time.monotonic()
    status, r = rows.post(rows.drag("B", seconds=seconds), rows.drag("C"))
    assert status == 400 and "at most 600 s" in r["error"] and len(r["error"]) < 200, r
    assert time.monotonic() - t < 5
    assert rows.lesson.count() == 0


def test_a_jump_through_a_block_is_refused_however_fast(rows):
    """A drag whose samples share one instant (or 10 ms apart) skipped the collision check; a drag now has
    no duration minimum of its own (the row has), so the 10 ms jump is refused for its path."""
    a, b = np.array(rows.scene.get("A").xy), np.array(rows.scene.get("B").xy)
    far = a + (a - b) / np.linalg.norm(a - b) * 0.08  # the far side of A from B
    c = rows.drag("C")
    for dt, words in ((0.0, "in no time"), (0.01, "passed through block A"), (1.0, "passed through block A")):
        jump = {"block": "B", "samples": [[0.0, *b, 0.0], [dt, *far, 0.0]]}
        jump["samples"] = [[t, x, y, rows.scene.get("B").yaw] for t, x, y, _ in jump["samples"]]
        status, r = rows.post(jump, c)
        assert status == 400 and words in r["error"], (dt, r)
    # the same jump in one frame of a longer drag: the swept path between the two frames is checked
    o = rows.scene.get("B")
    samples = [[0.0, *b, o.yaw], [1 / 30, *far, o.yaw], [1.0, *far, o.yaw]]
    status, r = rows.post({"block": "B", "samples": samples}, c)
    assert status == 400 and "passed through block A" in r["error"], r
    assert rows.lesson.count() == 0


def test_drags_that_move_nothing_are_refused(rows):
    status, r = rows.post(rows.drag("B", dy=0.0), rows.drag("C", dy=0.0))
    assert status == 400 and "moved block B 0.00 blocks" in r["error"], r
    status, r = rows.post(rows.drag("B", n=2, seconds=0.05), rows.drag("C", n=2, seconds=0.05))  # 3 frames in all
    assert status == 400 and "last 0.1 s in all" in r["error"], r
    status, r = rows.post(rows.drag("B"), rows.drag("C", dy=0.01))  # C nudged 1 cm and nothing else
    assert status == 400 and "moved block C 0.25 blocks in all" in r["error"], r
    assert rows.lesson.count() == 0


@pytest.mark.parametrize("span, words", [(0.0, "moves block B in no time"), (1e-6, "moves block B at 1.2e+05 m/s")])
def test_a_teleport_to_a_free_spot_is_refused(rows, span, words):
    """A drag whose samples share one instant was refused, but any positive span passed: 0.12 m in a
    microsecond was saved. A drag faster than a hand (3 m/s on average) is refused, naming the speed."""
    b = rows.scene.get("B")
    jump = {"block": "B", "samples": [[0.0, *b.xy, b.yaw], [span, b.xy[0], b.xy[1] + 0.12, b.yaw]]}
    status, r = rows.post(jump, rows.drag("C"))
    assert status == 400 and f"drag 1 {words}" in r["error"] and "\n" not in r["error"], r
    assert rows.lesson.count() == 0


def _a_between_b_and_c(scene):
    """``scene`` with A at the origin, B 2 sides below it, C out of the way (a free path around A)."""
    return (scene.with_pose("A", np.zeros(3)).with_pose("B", np.array([0.0, -0.08, 0.0]))
            .with_pose("C", np.array([0.2, 0.2, 0.0])))


def test_a_detour_at_one_instant_does_not_hide_a_drag_through_a_block(rows):
    """Every sample was checked, but the saved 30-fps track keeps only the last sample at each instant:
    B going around A in samples that all share t = 1 passed, while the track went straight through A."""
    scene = _a_between_b_and_c(rows.scene)
    rows.lesson.scene = lambda seed: scene
    c = {"block": "C", "samples": [[0.0, 0.2, 0.2, 0.0], [1.0, 0.2, 0.26, 0.0]]}
    around = [[0, 0, -0.08, 0], [1, 0.1, -0.08, 0], [1, 0.1, 0.08, 0], [1, 0, 0.08, 0]]
    status, r = rows.post({"block": "B", "samples": around}, c)
    assert status == 400 and "block B passed through block A" in r["error"], r
    assert rows.lesson.count() == 0
    # the same detour in time is a path around A, and saved
    timed = [[0, 0, -0.08, 0], [1, 0.1, -0.08, 0], [2, 0.1, 0.08, 0], [3, 0, 0.08, 0]]
    status, r = rows.post({"block": "B", "samples": timed}, c)
    assert status == 200 and r["count"] == 1, r


def test_a_detour_at_one_instant_does_not_hide_a_slide_through_the_anchor(live):  # noqa: F811
    """The single action's route (``/api/demos``) had the same hole: the check saw A go around B, the
    saved track went through it."""
    s = live()
    scene = random_scene(1).with_pose("B", np.zeros(3)).with_pose("A", np.array([0.0, -0.08, 0.0]))
    scene = scene.with_pose("C", np.array([0.25, 0.25, 0.0])) if "C" in scene.names else scene
    s.lesson.scene = lambda seed: scene
    around = [[0, 0, -0.08, 0], [1, 0.1, -0.08, 0], [1, 0.1, 0.08, 0], [1, 0, 0.08, 0], [1.5, 0, 0.08, 0]]
    status, r = s.call("POST", "/api/demos", {"scene": 1, "samples": around, "start": 0.0, "end": 1.5})
    assert status == 400 and "passed through block B" in r["error"], r
    assert not s.action.demos.exists()
    timed = [[0, 0, -0.08, 0], [1, 0.1, -0.08, 0], [2, 0.1, 0.08, 0], [3, 0, 0.08, 0], [3.5, 0, 0.08, 0]]
    status, r = s.call("POST", "/api/demos", {"scene": 1, "samples": timed, "start": 0.0, "end": 3.5})
    assert status == 200, r


def test_a_nudge_and_a_flick_are_part_of_the_row(rows):
    """Each drag had to last 5 frames and move its block half a side: a small corrective nudge (2 frames,
    a quarter side) or a quick flick failed the whole row, which the page cannot save without it."""
    flick = rows.drag("B", dy=0.1, n=4, seconds=0.05)
    nudge = rows.drag("B", dy=0.01, n=3, seconds=0.06, t0=2.0)
    nudge["samples"] = [[t, x, y + 0.1, w] for t, x, y, w in nudge["samples"]]
    status, r = rows.post(flick, nudge, rows.drag("C", t0=3.0))
    assert status == 200 and r["segments"] == 3, r


def page_drag(scene, block: str, pointer: list, speed: float, hz: float = 120.0) -> dict:
    """A drag as teach.js made it before its chords were checked: the block follows the pointer (along the
    straight legs through ``pointer``, at ``speed`` m/s, a pointer event every 1/``hz`` s) to every pose
    that overlaps no other block, and is sampled there; where the pose overlaps one it stays put."""
    from l2p_bullet.core.geometry import polygons_overlap

    o = scene.get(block)
    others = [p for p in scene.objects if p.name != block]
    legs = np.asarray(pointer, float)
    cum = np.r_[0, np.cumsum(np.linalg.norm(np.diff(legs, axis=0), axis=1))]
    samples = [[0.0, *legs[0], o.yaw]]
    for t in np.arange(1, int(cum[-1] / speed * hz) + 1) / hz:
        d = t * speed
        i = min(np.searchsorted(cum, d, side="right") - 1, len(legs) - 2)
        p = legs[i] + (legs[i + 1] - legs[i]) * (d - cum[i]) / (cum[i + 1] - cum[i])
        pose = np.array([*p, o.yaw])
        if not any(polygons_overlap(o.footprint(pose), q.footprint(), margin=0.0) for q in others):
            samples.append([float(t), *p, o.yaw])
    return {"block": block, "samples": samples}


@pytest.mark.parametrize("speed, cut", [(0.6, 0.002), (0.6, 0.008), (1.0, 0.004), (1.0, 0.008), (0.1, 0.004)])
def test_a_drag_hugging_a_block_around_its_corner_is_saved(rows, speed, cut):
    """The page stops a block against another and lets it jump once the pointer clears the corner; that
    jump cut the corner by millimetres and the swept-path check refused every such row (0 of 40 passed at
    0.6-1 m/s with 2-8 mm cuts). A straight jump through the block is still refused."""
    s = 0.04
    scene = rows.scene.with_pose("A", np.zeros(3)).with_pose("B", np.array([s, -0.03, 0.0]))
    scene = scene.with_pose("C", np.array([0.2, 0.2, 0.0]))
    rows.lesson.scene = lambda seed: scene  # B slides up A's right face, then around its corner
    pointer = [[s, -0.03], [s, s - cut], [s - cut, s], [-0.02, s]]  # the pointer cuts the corner
    c = {"block": "C", "samples": [[0.0, 0.2, 0.2, 0.0], [1.0, 0.2, 0.26, 0.0]]}
    drag = page_drag(scene, "B", pointer, speed)
    status, r = rows.post(drag, c)
    assert status == 200, r
    through = {"block": "B", "samples": [[0.0, s, -0.03, 0.0], [0.01, -s, 0.0, 0.0], [1.0, -s, 0.0, 0.0]]}
    status, r = rows.post(through, c)
    assert status == 400 and "passed through block A" in r["error"], r


def test_the_composite_page_points_single_recordings_to_rows(rows):
    status, r = rows.call(
        "POST", "/api/demos", {"scene": 1, "samples": [[0, 0, 0, 0], [1, 0, 0, 0]], "start": 0, "end": 1}
    )
    assert status == 400 and "/api/rows" in r["error"], r
    assert rows.action.sentence == rows.call("GET", "/api/config")[1]["sentence"] == "make a blorp of A, B and C"


BAD_SAMPLES = [
    ("strings", lambda rec: rec["samples"].__setitem__(3, ["0", "1", "2", "3"]), 422, "number"),
    ("NaN", lambda rec: rec["samples"][3].__setitem__(1, float("nan")), 422, "finite number"),
    ("Infinity", lambda rec: rec["samples"][3].__setitem__(3, float("inf")), 422, "finite number"),
    ("far off", lambda rec: [r.__setitem__(2, 1e300) for r in rec["samples"][40:]], 400, "1e+300 m"),
    ("huge yaw", lambda rec: (rec["samples"][5].__setitem__(3, 1e308), rec["samples"][6].__setitem__(3, -1e308)),
     400, "a yaw of 1e+308 rad"),
]


@pytest.mark.parametrize("name, change, status, words", BAD_SAMPLES, ids=[b[0] for b in BAD_SAMPLES])
def test_samples_are_finite_numbers_of_a_sane_size(live, name, change, status, words):  # noqa: F811
    s = live()
    seed, scene, goal = clear_scene()
    rec = slide(scene, goal, seed=seed)
    change(rec)
    code, r = s.call("POST", "/api/demos", raw=json.dumps(rec).encode())
    assert code == status and words in r["error"] and len(r["error"]) < 200, r
    assert not s.action.demos.exists()


def test_a_huge_yaw_is_refused_before_any_arithmetic(live):  # noqa: F811
    """A yaw of +-1e308 went through np.unwrap (overflow warnings) and was said to leave the table."""
    from l2p_bullet.errors import TeachError
    from l2p_bullet.teach.lesson import Recording

    s = live()
    seed, scene, goal = clear_scene()
    rec = slide(scene, goal, seed=seed)
    samples = np.array(rec["samples"])
    samples[5, 3], samples[6, 3] = 1e308, -1e308
    with np.errstate(all="raise"), pytest.raises(TeachError, match="a yaw of 1e"):
        s.lesson.save(Recording(seed, samples, rec["start"], rec["end"]))


def test_a_jump_through_the_anchor_between_two_frames_is_refused(live):  # noqa: F811
    """A sample 1/30 s after the start on the far side of B used to be saved: only the frames were checked."""
    s = live()
    scene = random_scene(1)
    a, b = scene.get("A"), np.array(scene.get("B").xy)
    far = b + (b - a.xy) / np.linalg.norm(b - a.xy) * 0.12
    rows = [[0.0, *a.xy, a.yaw], [1 / 30, *far, a.yaw], [2.0, *far, a.yaw]]
    status, r = s.call("POST", "/api/demos", {"scene": 1, "samples": rows, "start": 0.0, "end": 1.0})
    assert status == 400 and "passed through block B" in r["error"], r
    assert not s.action.demos.exists()


def test_the_same_recording_twice_is_a_409_and_a_save_during_training_says_so(live):  # noqa: F811
    s = live()
    seed, scene, goal = clear_scene()
    rec = slide(scene, goal, seed=seed)
    assert s.call("POST", "/api/demos", rec)[0] == 200
    status, r = s.call("POST", "/api/demos", rec)
    assert status == 409 and "demonstration 1" in r["error"], r
    shifted = dict(rec, samples=[[t + 1234.5, *rest] for t, *rest in rec["samples"]], start=rec["start"] + 1234.5,
                   end=rec["end"] + 1234.5)
    assert s.call("POST", "/api/demos", shifted)[0] == 409
    assert s.lesson.count() == 1
    s.lesson.job.state = "training"  # as while the trainer runs (it read the demos file when it started)
    status, r = s.call("POST", "/api/demos", slide(scene, goal, seconds=1.0, seed=seed))
    assert status == 200 and r["count"] == 2 and "not in the model being trained" in r["note"], r
    s.lesson.job.state = "idle"


def test_train_takes_an_empty_body_or_a_json_object(live):  # noqa: F811
    s = live()
    for raw in (b"{{{ not json", b"[1, 2]", b'"train"'):
        status, r = s.call("POST", "/api/train", raw=raw)
        assert status == 422, (raw, status, r)
    assert s.lesson.job.state == "idle"
    assert s.call("POST", "/api/train", raw=b"{}")[1]["error"].startswith("no demonstrations")


def test_a_demonstration_sliding_a_around_bs_corner_is_saved(live):  # noqa: F811
    """The single action's check is the rows' one: A slid up B's face and around its corner at 1 m/s
    (the pointer cutting the corner by 8 mm) is saved; the jump straight through B stays refused above."""
    s = live()
    scene = random_scene(1)
    size = scene.get("A").size
    scene = scene.with_pose("B", np.zeros(3)).with_pose("A", np.array([size, -0.03, 0.0]))
    scene = scene.with_pose("C", np.array([0.25, 0.25, 0.0])) if "C" in scene.names else scene
    s.lesson.scene = lambda seed: scene
    cut = 0.008
    drag = page_drag(scene, "A", [[size, -0.03], [size, size - cut], [size - cut, size], [-0.02, size]], 1.0)
    rows = drag["samples"] + [[drag["samples"][-1][0] + 0.5, *drag["samples"][-1][1:]]]
    status, r = s.call("POST", "/api/demos", {"scene": 1, "samples": rows, "start": 0.0, "end": rows[-1][0]})
    assert status == 200, r
