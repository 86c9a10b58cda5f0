"""Files of people's work are replaced whole: a temporary file of each writer's own, flushed to disk, then
renamed; two writers at once never share a temporary file nor leave half a file (two teach servers on one
plugin wrote one ``demos.json.tmp``: a FileNotFoundError for one, invalid JSON for the next start)."""

from __future__ import annotations

import json
import os
import threading

import pytest

from l2p_bullet.composite.bundle import read_demos, write_demos
from l2p_bullet.composite.recipe import Demonstration, Segment
from l2p_bullet.core import atomic
from l2p_bullet.core.atomic import write_atomic
from l2p_bullet.core.scene import random_scene


def _demo(seed: int) -> Demonstration:
    scene = random_scene(seed)
    a = scene.get("B")
    samples = [[i / 30, a.xy[0], a.xy[1] + 0.004 * i, a.yaw] for i in range(31)]
    return Demonstration(scene.to_dict(), ["A", "B"], [Segment("B", samples)], seed)


@pytest.mark.slow
def test_two_writers_at_once_leave_a_whole_file_and_no_error(tmp_path):
    lists = [[_demo(s)] * n for s, n in ((1, 3), (2, 7))]
    errors: list[BaseException] = []

    def writer(demos: list[Demonstration]) -> None:
        try:
            for _ in range(150):
                write_demos(tmp_path, demos)
        except BaseException as e:  # noqa: BLE001 - every failure is the test's finding
            errors.append(e)

    threads = [threading.Thread(target=writer, args=(d,)) for d in lists]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors[:3]
    assert len(read_demos(tmp_path)) in (3, 7)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["demos.json"]  # no temporary file left


def test_the_data_is_on_disk_before_the_rename(tmp_path, monkeypatch):
    calls: list[str] = []
    real_fsync, real_replace = os.fsync, os.replace
    monkeypatch.setattr(atomic.os, "fsync", lambda fd: (calls.append("fsync"), real_fsync(fd))[1])
    monkeypatch.setattr(atomic.os, "replace", lambda a, b: (calls.append("replace"), real_replace(a, b))[1])
    write_demos(tmp_path, [_demo(1)])
    assert calls[:2] == ["fsync", "replace"], calls


def test_a_failed_write_leaves_the_old_file_and_no_temporary_one(tmp_path):
    path = tmp_path / "manifest.toml"
    path.write_text("old")
    with pytest.raises(RuntimeError), atomic.atomic_file(path) as f:
        f.write(b"half")
        raise RuntimeError("disk full")
    assert path.read_text() == "old" and [p.name for p in tmp_path.iterdir()] == ["manifest.toml"]


def test_the_file_gets_the_mode_open_would_give_it(tmp_path):
    old = os.umask(0o022)
    try:
        write_atomic(tmp_path / "demos.json", json.dumps({"schema": 1, "demos": []}))
    finally:
        os.umask(old)
    assert (tmp_path / "demos.json").stat().st_mode & 0o777 == 0o644
