"""The teach page keeps what people record: one teach server per plugin folder (a second is refused,
naming the first), no save past what reading and training accept, and a way to remove a demonstration."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import numpy as np
import pytest
from teach_fixtures import live  # noqa: F401 - fixture
from test_teach import clear_scene, slide

from l2p_bullet.composite import bundle as composite_bundle
from l2p_bullet.composite.bundle import read_demos, write_demos
from l2p_bullet.composite.recipe import MAX_DEMOS, CompositeError
from l2p_bullet.data.demos import load_demos, load_session
from l2p_bullet.errors import TeachError
from l2p_bullet.teach.lock import claim_plugin


# --- one teach per plugin folder ------------------------------------------------------------------------
def test_a_second_teach_on_one_plugin_folder_is_refused_naming_the_first(tmp_path):
    first = claim_plugin(tmp_path, "http://127.0.0.1:18769/")
    try:
        with pytest.raises(TeachError) as info:
            claim_plugin(tmp_path, "http://127.0.0.1:18770/")
        assert f"pid {os.getpid()}" in str(info.value) and "127.0.0.1:18769" in str(info.value)
    finally:
        first.release()
    claim_plugin(tmp_path, "http://127.0.0.1:18770/").release()  # free once the first one stopped


@pytest.mark.slow
def test_two_teach_commands_on_one_plugin_give_one_server_and_one_clear_error(tmp_path):
    from l2p_bullet.plugins.scaffold import scaffold

    root = scaffold("rowy", ["set in a line"], tmp_path / "l2p-rowy", kind="composite").root
    cmd = [sys.executable, "-m", "l2p_bullet.cli", "teach", "rowy", "--plugin", str(root), "--port", "0"]
    first = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        line = first.stderr.readline()  # "teaching ...: open http://127.0.0.1:PORT/ ..."
        assert "open http://127.0.0.1:" in line, line + first.stderr.read()
        url = line.split("open ")[1].split()[0]
        second = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        assert second.returncode == 2, second.stderr
        err = second.stderr.strip()
        assert len(err.splitlines()) == 1 and err.startswith("error: another l2p-bullet teach"), err
        assert f"pid {first.pid}" in err and url in err, err
    finally:
        first.terminate()
        first.wait(timeout=30)
    third = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)  # the lock went with it
    try:
        assert "open http://127.0.0.1:" in third.stderr.readline()
    finally:
        third.terminate()
        third.wait(timeout=30)


# --- never saved past what is read back ----------------------------------------------------------------
def test_a_row_past_the_number_training_reads_is_refused_until_one_is_removed(rows):
    status, r = rows.post(rows.drag("B"), rows.drag("C"))
    assert status == 200, r
    demo = read_demos(rows.action.bundle_dir)[0]
    write_demos(rows.action.bundle_dir, [demo] * MAX_DEMOS)
    before = (rows.action.bundle_dir / "demos.json").read_bytes()
    status, r = rows.post(rows.drag("B", dy=0.13), rows.drag("C"))
    assert status == 400 and f"at most {MAX_DEMOS}" in r["error"] and "remove" in r["error"], r
    assert (rows.action.bundle_dir / "demos.json").read_bytes() == before
    status, r = rows.call("DELETE", f"/api/demos/{MAX_DEMOS}")
    assert status == 200 and r["count"] == MAX_DEMOS - 1 and r["removed"] == MAX_DEMOS, r
    status, r = rows.post(rows.drag("B", dy=0.13), rows.drag("C"))
    assert status == 200 and r["count"] == MAX_DEMOS, r


def test_a_row_that_would_grow_the_file_past_the_read_limit_is_refused(rows, monkeypatch):
    status, r = rows.post(rows.drag("B"), rows.drag("C"))
    assert status == 200, r
    path = rows.action.bundle_dir / "demos.json"
    before = path.read_bytes()
    monkeypatch.setattr(composite_bundle, "MAX_BYTES", len(before) + 100)  # the reader's limit, smaller
    status, r = rows.post(rows.drag("B", dy=0.13), rows.drag("C"))
    assert status == 400 and "MiB" in r["error"] and "read" in r["error"], r
    assert path.read_bytes() == before
    assert len(read_demos(rows.action.bundle_dir)) == 1  # still readable


def test_the_file_written_is_what_the_reader_accepts(tmp_path):
    (tmp_path / "demos.json").write_text('{"schema": 1, "demos": []}')
    with pytest.raises(CompositeError, match=f"at most {MAX_DEMOS}"):
        write_demos(tmp_path, [object()] * (MAX_DEMOS + 1))  # refused before anything is serialised
    assert json.loads((tmp_path / "demos.json").read_text()) == {"schema": 1, "demos": []}


# --- removing a demonstration -------------------------------------------------------------------------
def test_removing_a_row_keeps_the_others_in_order(rows):
    for dy in (0.12, 0.13, 0.14):
        assert rows.post(rows.drag("B", dy=dy), rows.drag("C"))[0] == 200
    kept = read_demos(rows.action.bundle_dir)
    status, r = rows.call("DELETE", "/api/demos/2")
    assert status == 200 and r["count"] == 2, r
    left = read_demos(rows.action.bundle_dir)
    assert [d.to_dict() for d in left] == [kept[0].to_dict(), kept[2].to_dict()]
    for k in (0, 3, "x"):
        status, r = rows.call("DELETE", f"/api/demos/{k}")
        assert status in (400, 422) and "error" in r, (k, r)
    import http_client

    status, r = http_client.call(rows.server.url, "DELETE", "/api/demos/1", headers={"Origin": "http://evil.example"})
    assert status == 403, r  # a page of another site cannot remove a demonstration
    assert len(read_demos(rows.action.bundle_dir)) == 2


@pytest.mark.slow
def test_removing_a_single_actions_demonstration_takes_its_frames_with_it(live):  # noqa: F811
    s = live()
    seed, scene, goal = clear_scene()
    for seconds in (1.5, 1.0, 2.0):
        assert s.call("POST", "/api/demos", slide(scene, goal, seconds=seconds, seed=seed))[0] == 200
    before = load_demos("left-of", [s.action.demos])
    status, r = s.call("DELETE", "/api/demos/2")
    assert status == 200 and r["count"] == 2, r
    after = load_demos("left-of", [s.action.demos])
    assert len(after) == 2
    for got, want in zip(after, [before[0], before[2]], strict=True):
        assert np.array_equal(got.mover, want.mover) and (got.start, got.end) == (want.start, want.end)
    assert len(load_session(s.action.demos)["shell_pose"]) == len(before[0].mover) + len(before[2].mover)
    for k in (2, 1):
        assert s.call("DELETE", f"/api/demos/{k}")[0] == 200
    assert not s.action.demos.exists() and s.call("GET", "/api/config")[1]["count"] == 0
    status, r = s.call("DELETE", "/api/demos/1")
    assert status == 400 and "holds none" in r["error"], r


@pytest.mark.slow
def test_the_page_removes_the_last_demonstration_on_a_second_click(rows, chromium):
    from review_fixtures import open_page

    for dy in (0.12, 0.13):
        assert rows.post(rows.drag("B", dy=dy), rows.drag("C"))[0] == 200
    page, errors = open_page(chromium, rows.server.url, 1200, 760)
    page.wait_for_function("() => document.body.dataset.count === '2'")
    page.click("#remove")
    assert "click again" in page.inner_text("#remove")
    time.sleep(0.2)
    assert rows.lesson.count() == 2  # one click only asks
    page.click("#remove")
    page.wait_for_function("() => document.body.dataset.count === '1'")
    assert rows.lesson.count() == 1 and "removed demonstration 2" in page.inner_text("#status")
    assert not errors
