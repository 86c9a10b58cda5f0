"""A composite action taught in a real browser (headless Debian Chromium via Playwright): the test drags
blocks on the teach page into rows of 2 and 3 (6 demonstrations), trains the composite (each drag
recognised by the installed actions, the recipe learned), and the page performs a row of 4 blocks."""

from __future__ import annotations

import json
import math
import os
import shutil

import numpy as np
import pytest
from review_fixtures import open_page
from teach_fixtures import small_video

pytestmark = pytest.mark.slow(50)  # a row of four blocks taught, trained and performed

SEEDS = range(6)
"""Demonstrations recorded: scenes 0..5 (even seeds have 2 blocks, odd ones 3): 3 rows of 2, 3 of 3."""


@pytest.fixture
def rows(tmp_path):
    from l2p_bullet.plugins.scaffold import scaffold
    from l2p_bullet.teach.app import create_app
    from l2p_bullet.teach.lesson import find_action
    from l2p_bullet.teach.rows import RowLesson
    from l2p_bullet.web.server import start

    root = scaffold("row", ["make a row of", "line up"], tmp_path / "l2p-row", kind="composite").root
    lesson = RowLesson(find_action("row", root), None, seed=0, render_settings=small_video())
    server = start(create_app(lesson), name="teach-rows")
    yield lesson, server.url
    server.stop()


def _free(scene, poses: dict, block: str, path: list[np.ndarray]) -> bool:
    """Whether ``block`` can slide along ``path`` (x, y, yaw points) without touching another block."""
    from l2p_bullet.core.geometry import polygons_overlap

    obj = scene.get(block)
    for p, q in zip(path[:-1], path[1:], strict=True):
        for f in np.linspace(0, 1, 25):
            foot = obj.footprint(p + (q - p) * f)
            if not scene.table.contains(foot):
                return False
            if any(polygons_overlap(foot, scene.get(n).footprint(poses[n]), margin=0.003) for n in poses if n != block):
                return False
    return True


def _plan_row(scene, names: list[str], gap: float) -> list[list[np.ndarray]] | None:
    """How a person would lay the row: from the first block along one of its faces, each block turned
    like it and dropped ``gap`` sides beyond the previous one, straight or round by one side-step."""
    base = scene.get(names[0])
    for k in range(4):
        a = base.yaw + k * math.pi / 2
        u, w = np.array([math.cos(a), math.sin(a)]), np.array([-math.sin(a), math.cos(a)])
        poses = {o.name: o.pose.copy() for o in scene.objects}
        drags = []
        for j, n in enumerate(names[1:], 1):
            start = poses[n]
            turn = base.yaw + round((start[2] - base.yaw) / (math.pi / 2)) * math.pi / 2
            goal = np.r_[np.asarray(base.xy) + j * base.size * (1 + gap) * u, turn]
            options = [[start, goal]] + [[start, np.r_[goal[:2] + s * 2.5 * base.size * v, turn], goal]
                                         for v in (w, u) for s in (1, -1)]
            path = next((p for p in options if _free(scene, poses, n, p)), None)
            if path is None:
                break
            drags.append((n, path))
            poses[n] = goal
        else:
            return drags
    return None


def _drag(page, block: str, path: list[np.ndarray]) -> None:
    """Press on the block's centre, move the mouse along ``path`` (turning it with Q / W), let go."""
    to_page = "([x, y]) => window.teach.toPage(x, y)"
    b = page.evaluate(f"window.teach.block('{block}')")
    page.mouse.move(*page.evaluate(to_page, [b["x"], b["y"]]))
    page.mouse.down()
    page.wait_for_function(f"() => document.body.dataset.dragging === '{block}'")
    turn = path[-1][2] - b["yaw"]
    for _ in range(int(round(abs(turn) / (math.pi / 36)))):  # 5 degrees a key press
        page.keyboard.press("q" if turn > 0 else "w")
        page.wait_for_timeout(20)
    for p, q in zip(path[:-1], path[1:], strict=True):
        steps = max(8, int(np.hypot(*(q - p)[:2]) / 0.004))
        for f in np.linspace(0, 1, steps + 1)[1:]:
            page.mouse.move(*page.evaluate(to_page, [float(v) for v in (p + (q - p) * f)[:2]]))
            page.wait_for_timeout(15)
    page.mouse.up()


def test_rows_dragged_on_the_page_teach_a_row_performed_with_four_blocks(rows, chromium):
    from l2p_bullet.composite.bundle import read_demos, read_recipe

    lesson, url = rows
    page, errors = open_page(chromium, url, 1200, 760)  # the lesson starts at seed 0
    page.wait_for_function("() => document.body.dataset.state === 'ready'")
    rng = np.random.default_rng(21)
    gaps = []
    for i, seed in enumerate(SEEDS):
        assert page.get_attribute("body", "data-seed") == str(seed)
        scene, names = lesson.scene(seed), lesson.names(seed)
        assert page.inner_text("#sentence") == f"“make a row of {', '.join(names[:-1])} and {names[-1]}”"
        gap = float(rng.uniform(0.12, 0.25))  # a person's spacing varies a little
        plan = _plan_row(scene, names, gap)
        assert plan is not None, f"scene {seed}: no free way to lay the row"
        for k, (block, path) in enumerate(plan, 1):
            _drag(page, block, path)
            page.wait_for_function(f"() => document.body.dataset.segments === '{k}'")
            got = page.evaluate(f"window.teach.block('{block}')")
            assert np.hypot(got["x"] - path[-1][0], got["y"] - path[-1][1]) < 0.003  # the page followed the mouse
        gaps.append(gap)
        page.keyboard.press("Enter")
        page.wait_for_function(f"() => document.body.dataset.saved === '{i + 1}'")
    assert not errors

    demos = read_demos(lesson.action.bundle_dir)
    assert [len(d.segments) for d in demos] == [len(lesson.names(s)) - 1 for s in SEEDS]
    assert len(demos) <= 10

    page.keyboard.press("t")
    page.wait_for_function("() => ['done', 'failed'].includes(document.body.dataset.train)", timeout=480_000)
    assert page.get_attribute("body", "data-train") == "done", page.inner_text("#train-status")
    recipe = read_recipe(lesson.action.bundle_dir)
    # Learned, not written: the drags read most often as "next to" the block before, and nearly all as
    # "next to" or "closer to" (the pair people themselves confuse, issue 21: the shipped models of the
    # issue-25 recipe read 5 of 9 as next to and 3 as closer), the row grown in the named order from the
    # first block, the spacing the person used (median of what was dragged).
    readings = recipe.evidence["actions"]
    assert recipe.action == "next-to" and readings["next-to"] == max(readings.values()), recipe.evidence
    assert (readings["next-to"] + readings.get("closer", 0)) / recipe.evidence["segments"] >= 0.75, recipe.evidence
    assert recipe.anchor == "previous" and recipe.evidence["anchor_votes"].get("previous", 0) >= 3
    assert recipe.order == "named" and recipe.monotone and recipe.aligned
    assert abs(recipe.spacing - float(np.median(gaps))) < 0.05
    run = lesson.job.run
    assert run["sentence"] == "make a row of A, B, C and D"
    assert run["verdict"]["success"], run["verdict"]
    assert run["verdict"]["row"]["max_gap_sides"] <= 0.35 and run["verdict"]["row"]["max_offset_sides"] <= 0.25
    assert "a row" in page.inner_text("#verdict")
    page.wait_for_function("() => document.getElementById('video').readyState >= 1", timeout=30_000)
    assert not errors
    keep = os.environ.get("L2P_KEEP_ROW_BUNDLE")  # how the shipped row bundle was made (docs/learning.md)
    if keep:
        shutil.copytree(lesson.action.bundle_dir, keep, dirs_exist_ok=True)
        (lesson.action.root / "runs" / "teach-000" / "summary.json").is_file() and shutil.copy(
            lesson.action.root / "runs" / "teach-000" / "summary.json", os.path.join(keep, "teach-run-summary.json"))
    assert json.loads((lesson.action.bundle_dir / "recipe.json").read_text())["demos"] == len(SEEDS)
