"""The review app's HTTP API on a live uvicorn server over real runs: order, answers, conflicts, bad requests."""

from __future__ import annotations

import json
import shutil
import threading

import pytest
from review_fixtures import live, run_folder  # noqa: F401 - fixtures

from l2p_bullet.review.store import Store


def _answer(s, reviewer: str, item: dict, grade: int = 5, **extra):
    return s.call("POST", "/api/answer", {"reviewer": reviewer, "key": item["key"], "view": item["view"],
                                          "grade": grade, **extra})


def _next(s, reviewer: str) -> dict | None:
    status, body = s.call("GET", f"/api/next?reviewer={reviewer}")
    assert status == 200, body
    return body["item"]


def test_grade_every_run_then_a_restarted_server_has_them_all(live, tmp_path):  # noqa: F811
    s = live()
    status, cfg = s.call("GET", "/api/config")
    assert status == 200 and cfg["mode"] == "graded" and cfg["items"] == 4 and cfg["labels"] == []
    seen = []
    while (item := _next(s, "ann")) is not None:
        assert item["sentence"].startswith("move A") and item["answer"] is None
        status, body = _answer(s, "ann", item, grade=len(seen) + 3, comment=f"run {len(seen)}")
        assert status == 200, body
        seen.append(item["key"])
    assert len(set(seen)) == 4
    unrendered = [i for i in s.queue.items if i.run.video is None]
    assert [i.view for i in unrendered] == ["2d"]  # no video: shown from above instead
    s.stop()
    again = live(db=tmp_path / "reviews.sqlite")  # a new server on the same file
    status, hist = again.call("GET", "/api/history?reviewer=ann")
    assert [(a["key"], a["grade"], a["comment"]) for a in hist["answers"]] == [
        (k, i + 3, f"run {i}") for i, k in enumerate(seen)]
    assert hist["progress"] == {"answered": 4, "total": 4}
    assert _next(again, "ann") is None


def test_reviewers_are_spread_over_runs_and_the_order_is_stable(live):  # noqa: F811
    s = live()
    first = _next(s, "ann")
    assert _next(s, "ann") == first  # a reload shows the same run
    assert _answer(s, "ann", first)[0] == 200
    assert _next(s, "bob")["key"] != first["key"]  # bob starts where nobody has answered yet


def test_skipped_runs_come_last(live):  # noqa: F811
    s = live()
    first = _next(s, "ann")
    status, _ = s.call("POST", "/api/skip", {"reviewer": "ann", "key": first["key"], "view": first["view"]})
    assert status == 200
    order = []
    while (item := _next(s, "ann")) is not None:
        order.append(item["key"])
        _answer(s, "ann", item)
    assert order[-1] == first["key"] and len(order) == 4


def test_changing_an_earlier_answer_and_a_second_window(live):  # noqa: F811
    s = live()
    item = _next(s, "ann")
    _, saved = _answer(s, "ann", item, grade=4)
    status, body = _answer(s, "ann", item, grade=6)  # another window that still shows the run as new
    assert status == 409 and "already answered" in body["error"]
    status, body = _answer(s, "ann", item, grade=6, replaces=saved["answer"]["updated_at"])
    assert status == 200 and body["answer"]["grade"] == 6
    status, body = s.call("GET", f"/api/item/{item['key']}?view={item['view']}&reviewer=ann")
    assert body["item"]["answer"]["grade"] == 6
    assert [e["grade"] for e in s.store.log()] == [4, 6]


def test_two_reviewers_at_once_lose_nothing(live):  # noqa: F811
    s = live()
    errors = []

    def reviewer(name: str) -> None:
        try:
            while (item := _next(s, name)) is not None:
                status, body = _answer(s, name, item, grade=len(name))
                if status != 200:
                    errors.append(body)
                    return
        except Exception as e:  # pragma: no cover - reported below
            errors.append(repr(e))

    threads = [threading.Thread(target=reviewer, args=(n,)) for n in ("ann", "bob", "carla", "dmitri")]
    for t in threads:
        t.start()
    for t in threads:
        t.join(60)
    assert not errors
    grades = Store(s.store.path).grades()
    assert len(grades) == 16 and len({(g.run_id, g.reviewer) for g in grades}) == 16
    assert all(g.grade == len(g.reviewer) for g in grades)


def test_a_run_that_changed_or_disappeared_is_not_graded(live, run_folder):  # noqa: F811
    s = live()
    item = _next(s, "ann")
    run = s.queue.runs[item["key"]]
    (run.path / "trajectory.json").write_text(json.dumps({"frames": []}))
    status, body = _answer(s, "ann", item)
    assert status == 409 and body["reason"] == "changed"
    assert _next(s, "ann")["key"] != item["key"]
    _, cfg = s.call("GET", "/api/config")
    assert cfg["problems"] == [{"run": run.run_id, "problem": "changed"}]
    other = _next(s, "ann")
    shutil.rmtree(s.queue.runs[other["key"]].path)
    status, body = _answer(s, "ann", other)
    assert status == 410 and body["reason"] == "missing"
    assert s.store.grades() == []


BAD = [
    (b"{not json", "not valid JSON"),
    (b"[]", None),
    (b'{"reviewer": "ann"}', "key"),
    (json.dumps({"reviewer": "ann", "key": "KEY", "view": "VIEW", "grade": 11}).encode(), "grade"),
    (json.dumps({"reviewer": "ann", "key": "KEY", "view": "VIEW", "grade": -1}).encode(), "grade"),
    (json.dumps({"reviewer": "ann", "key": "KEY", "view": "VIEW", "grade": "7"}).encode(), "grade"),
    (json.dumps({"reviewer": "ann", "key": "KEY", "view": "VIEW", "grade": 7.5}).encode(), "grade"),
    (json.dumps({"reviewer": "ann", "key": "KEY", "view": "VIEW", "grade": True}).encode(), "grade"),
    (json.dumps({"reviewer": "ann", "key": "KEY", "view": "4d", "grade": 7}).encode(), "view"),
    (json.dumps({"reviewer": "", "key": "KEY", "view": "VIEW", "grade": 7}).encode(), "reviewer"),
    (json.dumps({"reviewer": "a\u0007b", "key": "KEY", "view": "VIEW", "grade": 7}).encode(), "name"),
    (json.dumps({"reviewer": "x" * 41, "key": "KEY", "view": "VIEW", "grade": 7}).encode(), "reviewer"),
    (json.dumps({"reviewer": "ann", "key": "KEY", "view": "VIEW", "grade": 7, "admin": True}).encode(), "admin"),
    (
        json.dumps({"reviewer": "ann", "key": "KEY", "view": "VIEW", "grade": 7, "comment": "x" * 2001}).encode(),
        "comment",
    ),
    (json.dumps({"reviewer": "ann", "key": "KEY", "view": "VIEW", "grade": 7, "label": "past"}).encode(), "label"),
    (json.dumps({"reviewer": "ann", "key": "KEY", "view": "VIEW"}).encode(), "grade"),
    (json.dumps({"reviewer": "ann", "key": "0123456789abcdef", "view": "VIEW", "grade": 7}).encode(), "no run"),
    (json.dumps({"reviewer": "ann", "key": "../../etc/passwd", "view": "VIEW", "grade": 7}).encode(), "key"),
]


def test_bad_requests_get_a_4xx_with_a_message(live):  # noqa: F811
    s = live()
    item = _next(s, "ann")
    key = item["key"]
    for raw, words in BAD:
        raw = raw.replace(b"KEY", key.encode()).replace(b"VIEW", item["view"].encode())
        status, body = s.call("POST", "/api/answer", raw=raw)
        assert 400 <= status < 500, (raw, status, body)
        assert isinstance(body, dict) and body["error"], (raw, body)
        if words:
            assert words in body["error"], (raw, body)
    for path in ("/api/next", "/api/item/zz?view=3d&reviewer=ann", f"/api/media/{key}/frames/999",
                 f"/api/media/{key}/frames/-1", "/api/media/0123456789abcdef/motion", "/nothing-here"):
        status, body = s.call("GET", path)
        assert 400 <= status < 500 and body["error"], (path, status, body)
    status, body = s.call("GET", "/api/config", headers={"Host": "evil.example"})
    assert status == 400  # only 127.0.0.1 / localhost may talk to it (no DNS rebinding)
    assert s.store.grades() == []


def test_blind_mode_never_tells_the_action(live):  # noqa: F811
    s = live(mode="blind")
    _, cfg = s.call("GET", "/api/config")
    assert [(lk["label"], lk["key"]) for lk in cfg["labels"]] == [
        ("closer", "c"), ("away", "a"), ("next-to", "n"), ("past", "p"), ("around", "r"), ("none", "x")]
    item = _next(s, "ann")
    assert item["sentence"] is None and item["video"] is None
    status, motion = s.call("GET", item["motion"])
    assert status == 200 and not {"sentence", "action", "progress"} & set(motion)
    assert s.call("GET", f"/api/media/{item['key']}/video")[0] == 404
    assert _answer(s, "ann", item)[0] == 400  # a label is required
    assert _answer(s, "ann", item, label="sideways")[0] == 400
    status, body = _answer(s, "ann", item, grade=6, label="none")
    assert status == 200 and body["answer"]["label"] == "none"
    (g,) = s.store.grades()
    assert (g.mode, g.label, g.grade) == ("blind", "none", 6)


@pytest.mark.parametrize("view", ["2d", "both"])
def test_views(live, view):  # noqa: F811
    s = live(view=view)
    views = sorted(i.view for i in s.queue.items)
    assert views == (["2d"] * 4 if view == "2d" else ["2d"] * 4 + ["3d"] * 3)


# --- the commands ----------------------------------------------------------------------------------
@pytest.mark.slow
def test_review_command_serves_on_loopback_until_interrupted(run_folder, tmp_path):  # noqa: F811
    """The real ``l2p-bullet review``: prints its URL, answers, and a Ctrl+C leaves the database whole."""
    import signal
    import subprocess
    import sys
    import urllib.request

    db = tmp_path / "r.sqlite"
    proc = subprocess.Popen([sys.executable, "-m", "l2p_bullet.cli", "review", str(run_folder), "--db", str(db),
                             "--port", "0"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        lines = [proc.stdout.readline() for _ in range(2)]
        url = lines[1].split()[1]
        assert url.startswith("http://127.0.0.1:"), lines
        with urllib.request.urlopen(url + "api/config", timeout=30) as r:
            assert json.loads(r.read())["items"] == 4
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(30)
    assert len(Store(db).app_runs()) == 4


@pytest.mark.slow
def test_import_export_and_report_commands(tmp_path):
    from click.testing import CliRunner

    from l2p_bullet.cli import main

    db, out = tmp_path / "r.sqlite", tmp_path / "g.csv"
    run = CliRunner().invoke
    r = run(main, ["review", "--import-original", "--db", str(db)])
    assert r.exit_code == 0 and "90 graded demos, 180 grades (180 new)" in r.output
    r = run(main, ["review", "--export", str(out), "--db", str(db)])
    assert r.exit_code == 0 and out.read_text().count("\n") == 181
    r = run(main, ["review", "--export", str(out), "--db", str(db)])
    assert r.exit_code == 2 and "--force" in r.output
    r = run(main, ["report", "--db", str(db), "--json"])
    assert r.exit_code == 0, r.output
    rep = json.loads(r.output)
    assert len(rep["graded"]["original"]) == 6 and rep["blind"] is None
    assert (tmp_path / "r-report" / "table1.png").stat().st_size > 0
    r = run(main, ["report", "--db", str(out)])  # the export reads the same
    assert r.exit_code == 0 and "closer (SlideToward) | 15 | 30 | 2d | 5.23 | 1.13" in r.output
    for args in (["review"], ["report", "--db", str(tmp_path / "none.sqlite")],
                 ["review", "--export", str(tmp_path / "x.csv"), "--db", str(tmp_path / "none.sqlite")],
                 ["review", str(tmp_path / "no-such-runs")]):
        r = run(main, args)
        assert r.exit_code == 2 and r.output.startswith("error: ") and r.output.count("\n") == 1, (args, r.output)


def test_docs_list_the_blind_mode_keys_the_page_uses():
    """Issue 26: docs/review.md said `a` away, `r` around while the page used `a` for around (the keys
    followed the plugins' discovery order). The docs' key table is checked against the one table in
    code (label_keys over blind_labels), in any discovery order."""
    import re
    from pathlib import Path

    from l2p_bullet.review.queue import blind_labels, label_keys

    doc = (Path(__file__).resolve().parents[2] / "docs" / "review.md").read_text()
    row = next(line for line in doc.splitlines() if line.startswith("| letters shown on the buttons"))
    documented = re.findall(r"`([a-z])` ([a-z-]+)", row)
    builtins = ["closer", "away", "next-to", "past", "around"]
    for order in (builtins, sorted(builtins), list(reversed(builtins))):
        served = [(k["key"], "none" if k["label"] == "none" else k["label"]) for k in label_keys(blind_labels(order))]
        assert [(k, "none" if label == "none" else label) for k, label in documented] == served


def test_media_files_removed_while_serving_are_json_not_500(live):  # noqa: F811
    """A frame or the video removed while the server ran was a 500 (FileNotFoundError in FileResponse); a frame
    linking out of its run folder was served."""
    import http.client

    s = live()
    run = next(r for r in s.queue.runs.values() if r.video is not None and r.frames)
    host, port = s.url.split("//")[1].rstrip("/").rsplit(":", 1)

    def raw(method: str, path: str, headers: dict | None = None) -> tuple[int, str, bytes]:
        conn = http.client.HTTPConnection(host, int(port), timeout=30)
        conn.request(method, path, headers=headers or {})
        r = conn.getresponse()
        out = r.status, r.getheader("content-type"), r.read()
        conn.close()
        return out

    video = f"/api/media/{run.key}/video"
    assert raw("HEAD", video)[:2] == (200, "video/mp4")  # HEAD where GET is (was a 405)
    status, ctype, body = raw("GET", video, {"Range": "bytes=abc"})  # was 400 text/plain
    assert 400 <= status < 500 and ctype == "application/json" and json.loads(body)["error"], (status, body)
    secret = run.path.parent / "secret.png"  # a run folder from elsewhere whose frame links out of it
    secret.write_bytes(b"not the reviewer's to see")
    (run.path / "frames" / "0001.png").unlink()
    (run.path / "frames" / "0001.png").symlink_to(secret)
    status, body = s.call("GET", f"/api/media/{run.key}/frames/1")
    assert status == 404 and "links outside its run folder" in body["error"], body
    (run.path / "frames" / "0000.png").unlink()
    status, body = s.call("GET", f"/api/media/{run.key}/frames/0")
    assert status == 410 and body["reason"] == "missing" and "0000.png" in body["error"], body
    run.video.unlink()
    status, body = s.call("GET", video)
    assert status == 410 and body["reason"] == "missing" and run.video.name in body["error"], body
