"""Fuzzing the inputs a user hands the CLI (issue 15): scene files, scoring inputs (and plan.json /
trajectory.json look-alikes) and bundle manifests. Whatever the file holds, the command exits 0, or 2
with one ``error:`` line; never a traceback, and never more than a fixed amount of memory.

The CLI runs in a worker process (tests/fuzz_worker.py) whose address space is capped with
``RLIMIT_AS`` at what it uses after start-up plus :data:`MARGIN`: an input that made it allocate
gigabytes (the issue's 1e5-metre motion took 3 GB) fails the test with a MemoryError traceback.
Examples are derandomised so CI runs the same ones every time.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
import tomli_w
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from l2p_bullet.data.demos import load_session
from l2p_bullet.errors import DataError
from l2p_bullet.plugins.bundle import MANIFEST, builtin_bundle_dir

MARGIN = 1 << 30
"""Memory the CLI may use on top of its start-up footprint (1 GiB)."""
FUZZ = settings(max_examples=40, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])


class Worker:
    """The CLI in a worker process with a memory limit (tests/fuzz_worker.py); ``fork``: each request in a worker of
    its own, forked from this one after its start-up (``limit`` is then the last request's)."""

    def __init__(self, cwd: Path, fork: bool = False):
        env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
        self.proc = subprocess.Popen([sys.executable, str(Path(__file__).parents[1] / "fuzz_worker.py"), str(MARGIN),
                                      *(["--fork"] if fork else [])],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env, cwd=cwd)
        ready = json.loads(self.proc.stdout.readline())
        self.limit = ready["limit"]

    def run(self, args: list[str], cwd: Path) -> dict:
        self.proc.stdin.write(json.dumps({"args": args, "cwd": str(cwd)}) + "\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        assert line, f"the worker died on {args}"
        resp = json.loads(line)
        self.limit = resp.get("limit", self.limit)
        return resp

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait(timeout=30)


@pytest.fixture(scope="module")
def worker(tmp_path_factory):
    w = Worker(tmp_path_factory.mktemp("fuzz"))
    yield w
    w.close()


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    """A worker of its own for each request (forked after start-up, its limit set there)."""
    w = Worker(tmp_path_factory.mktemp("fresh"), fork=True)
    yield w
    w.close()


def _no_constant(name: str) -> None:
    raise AssertionError(f"{name} in JSON output")


def check(resp: dict, worker: Worker) -> None:
    assert resp["exception"] is None, resp["exception"]
    assert resp["exit_code"] in (0, 2), resp
    lines = resp["output"].strip().splitlines()
    if resp["exit_code"] == 2:
        assert len(lines) == 1 and lines[0].startswith("error: ") and len(lines[0]) < 2000, resp["output"][:3000]
    assert resp["peak_rss"] < worker.limit


# --- strategies ------------------------------------------------------------------------------------
weird = st.one_of(
    st.integers(-10**400, 10**400), st.floats(width=64), st.sampled_from([1e-300, 1e300, 5e-324, 0.0, -0.0, 1e5, 1e12]),
)
plausible = st.floats(-0.3, 0.3)
number = st.one_of(plausible, plausible, weird)
scalar = st.one_of(st.none(), st.booleans(), weird, st.text(max_size=12))
value = st.recursive(scalar, lambda c: st.lists(c, max_size=4) | st.dictionaries(st.text(max_size=6), c, max_size=4),
                     max_leaves=8)
pose = st.one_of(st.lists(number, min_size=3, max_size=3), st.lists(number, max_size=5), value)
poses = st.one_of(st.lists(pose, min_size=1, max_size=6), value)
scene_object = st.fixed_dictionaries(
    {"name": st.sampled_from(["A", "B", "C"]) | value, "color": st.sampled_from(["red", "green", "blue"]) | value,
     "size": st.floats(0.01, 0.09) | weird | value, "xy": st.lists(number, min_size=2, max_size=2) | value},
    optional={"yaw": number | value, "shape": st.sampled_from(["cube", "sphere"]) | value},
)
scene_doc = st.one_of(st.fixed_dictionaries({"objects": st.lists(scene_object, max_size=4)}), value)
scoring_doc = st.one_of(
    st.fixed_dictionaries({"size": st.floats(0.01, 0.2) | weird | value, "mover": poses, "anchor": poses}),
    st.fixed_dictionaries({"schema": st.just(1), "action": st.just("past") | value, "mover": st.just("A") | value,
                           "anchor": st.just("B") | value, "size": st.floats(0.01, 0.2) | weird | value,
                           "anchor_pose": pose, "start": pose, "path": poses},
                          optional={"progress": value}),
    st.fixed_dictionaries({"mover": st.just("A") | value, "anchor": st.just("B") | value,
                           "objects": st.fixed_dictionaries({"A": st.fixed_dictionaries({"size": number | value})})
                           | value,
                           "frames": st.lists(st.fixed_dictionaries({"poses": st.fixed_dictionaries(
                               {"A": pose, "B": pose}) | value}), max_size=4) | value}),
    value,
)


def _file_bytes(doc, raw: bytes | None) -> bytes:
    return raw if raw is not None else json.dumps(doc).encode()


raw_or_none = st.one_of(st.none(), st.none(), st.none(), st.binary(max_size=40))


@FUZZ
@given(doc=scene_doc, raw=raw_or_none)
def test_any_scene_file_is_a_plan_or_one_line_error(worker, tmp_path_factory, doc, raw):
    d = tmp_path_factory.mktemp("scene")
    (d / "scene.json").write_bytes(_file_bytes(doc, raw))
    resp = worker.run(["plan", "move A past B", "--scene", "scene.json", "--out", "out", "--planner", "greedy",
                       "--budget", "2"], d)
    check(resp, worker)


@FUZZ
@given(doc=scoring_doc, raw=raw_or_none)
def test_any_scoring_input_is_a_score_or_one_line_error(worker, tmp_path_factory, doc, raw):
    d = tmp_path_factory.mktemp("score")
    (d / "motion.json").write_bytes(_file_bytes(doc, raw))
    resp = worker.run(["score", "past", "motion.json"], d)
    check(resp, worker)
    if resp["exit_code"] == 0:
        out = json.loads(resp["output"], parse_constant=_no_constant)
        assert all(0.0 <= v <= 1.0 for v in out["progress"])


SECTIONS = ["", "features", "model", "policy", "weights", "judge", "metrics", "training"]
toml_value = st.recursive(
    st.one_of(st.booleans(), st.integers(-2**63, 2**63 - 1), st.floats(width=64), st.text(max_size=10)),
    lambda c: st.lists(c, max_size=3) | st.dictionaries(st.text(min_size=1, max_size=6), c, max_size=3),
    max_leaves=6,
)


@pytest.fixture(scope="module")
def bundle_template(tmp_path_factory) -> tuple[Path, dict]:
    folder = tmp_path_factory.mktemp("bundle") / "b"
    shutil.copytree(builtin_bundle_dir("past"), folder)
    motion = folder.parent / "motion.json"
    motion.write_text(json.dumps({"size": 0.15, "mover": [[0.4, 0, 0], [0.2, 0.1, 0.3], [0.0, 0.3, 0.5]],
                                  "anchor": [[0, 0, 0]]}))
    return folder, tomllib.loads((folder / MANIFEST).read_text())


_SHIPPED = tomllib.loads((builtin_bundle_dir("past") / MANIFEST).read_text())
PATHS = [("", k) for k in _SHIPPED] + [(sec, k) for sec in ("features", "model", "policy", "weights", "judge")
                                        for k in _SHIPPED[sec]]
"""Every field of a real manifest that the code reads ([training] and [metrics] are notes)."""


@settings(FUZZ, max_examples=250)
@given(target=st.sampled_from(PATHS) | st.tuples(st.sampled_from(SECTIONS), st.text(min_size=1, max_size=12)),
       new=st.one_of(st.none(), toml_value), raw=st.one_of(st.none(), st.none(), st.none(), st.binary(max_size=60)))
def test_any_manifest_loads_or_is_a_one_line_error(worker, bundle_template, target, new, raw):
    folder, manifest = bundle_template
    section, key = target
    man = json.loads(json.dumps(manifest))
    table = man if not section else man.get(section)
    if isinstance(table, dict):
        if new is None:
            table.pop(key, None)
        else:
            table[key] = new
    elif new is not None:
        man[section] = new
    try:
        text = tomli_w.dumps(man).encode() if raw is None else raw
    except (TypeError, ValueError):
        return
    (folder / MANIFEST).write_bytes(text)
    resp = worker.run(["score", str(folder), "motion.json"], folder.parent)
    check(resp, worker)


@settings(FUZZ, max_examples=30)
@given(depth=st.integers(1, 3000), kind=st.sampled_from(["array", "inline", "dotted", "header", "comment"]),
       where=st.sampled_from(["start", "end"]))
def test_any_manifest_structure_is_bounded(worker, bundle_template, depth, kind, where):
    """Manifests by structure (issue 27.2): nesting of every kind and any size load or are one line."""
    folder, manifest = bundle_template
    extra = {"array": "deep = " + "[" * depth + "]" * depth,
             "inline": "deep = " + "{a = " * depth + "1" + "}" * depth,
             "dotted": ".".join(["d"] * depth) + " = 1",
             "header": "[" + ".".join(["t"] * depth) + "]\nk = 1",
             "comment": "# " + "x" * (depth * 400)}[kind]
    shipped = tomli_w.dumps(manifest)
    text = extra + "\n" + shipped if where == "start" and kind in ("array", "inline", "dotted", "comment") \
        else shipped + "\n" + extra + "\n"
    (folder / MANIFEST).write_text(text)
    resp = worker.run(["score", str(folder), "motion.json"], folder.parent)
    check(resp, worker)


_PLAN = {"schema": 1, "action": "past", "mover": "A", "anchor": "B", "size": 0.05, "anchor_pose": [0.0, 0.05, 0.0],
         "start": [0.05, -0.1, 0.3], "planner": "mixed"}
far = st.one_of(st.sampled_from([1e5, 1e10, -1e12, 1e300, 3.0, 10**300, -(10**300), 10**20]),
                st.integers(10**5, 10**400), st.floats(min_value=1.0, max_value=1e308))
"""A coordinate outside the workspace (a disk of radius 0.25 m): the path must be refused up front."""


@settings(FUZZ, max_examples=25)
@given(n=st.integers(2, 6), k=st.integers(0, 5), axis=st.integers(0, 1), value=far,
       kind=st.sampled_from(["plan", "motion"]))
def test_any_far_waypoint_is_refused_up_front_in_bounded_memory(worker, tmp_path_factory, n, k, axis, value, kind):
    """Issue 27.4: one waypoint at y = 1e5 m took 3.2 GB; a 300-digit coordinate was a traceback; each left
    a failed run folder. The waypoints are checked before the path is densified or a folder is made."""
    folder = tmp_path_factory.mktemp("replay")
    path = [[0.05 + 0.01 * i, -0.1 + 0.01 * i, 0.3] for i in range(n)]
    path[min(k, n - 1)][axis] = value
    if kind == "plan":
        doc = {**_PLAN, "path": path}
    else:  # a scoring input: fitted into the workspace unless it is farther than 1000 block sides (50 m)
        if abs(value) < 100:
            value *= 1e3
            path[min(k, n - 1)][axis] = value
        doc = {"size": 0.05, "mover": path, "anchor": [[0.0, 0.05, 0.0]]}
    (folder / "p.json").write_text(json.dumps(doc))
    resp = worker.run(["replay", "p.json", "--no-render", "--out", "run"], folder)
    check(resp, worker)
    assert resp["exit_code"] == 2, resp["output"]
    assert not (folder / "run").exists(), "a path refused up front left a run folder"


# --- unbounded reads (issue 27.6): devices, sparse weights, arrays that declare more than they hold ----
@pytest.mark.parametrize("args", [["perform", "move A past B", "--scene", "/dev/zero", "--no-render", "--out", "r"],
                                  ["plan", "move A past B", "--scene", "/dev/zero", "--out", "r"],
                                  ["score", "around", "/dev/zero"], ["replay", "/dev/zero", "--no-render"]])
def test_a_device_as_an_input_file_is_read_with_a_bound(worker, tmp_path, args):
    resp = worker.run(args, tmp_path)
    check(resp, worker)
    assert resp["exit_code"] == 2 and "larger than" in resp["output"], resp["output"]
    assert not (tmp_path / "r").exists()


@pytest.mark.parametrize("declared", ["as the file", "16 GiB"])
def test_a_huge_sparse_weights_file_is_refused_before_it_is_read(worker, tmp_path, declared):
    """A 16 GiB sparse policy.safetensors used to be read whole before its digest was checked."""
    folder = tmp_path / "b"
    shutil.copytree(builtin_bundle_dir("past"), folder)
    (folder.parent / "motion.json").write_text(json.dumps({"size": 0.05, "mover": [[0.4, 0, 0], [0.2, 0.1, 0.3]],
                                                           "anchor": [[0, 0, 0]]}))
    policy = folder / "policy.safetensors"
    head = policy.read_bytes()[:4096]
    with policy.open("r+b") as f:
        f.truncate(16 * 2**30)  # sparse: no disk, but 16 GiB to read
        f.write(head)
    if declared == "16 GiB":
        man = tomllib.loads((folder / MANIFEST).read_text())
        man["weights"]["policy.safetensors"]["bytes"] = 16 * 2**30
        (folder / MANIFEST).write_text(tomli_w.dumps(man))
    resp = worker.run(["score", str(folder), "motion.json"], tmp_path)
    check(resp, worker)
    assert resp["exit_code"] == 2 and "policy.safetensors is" in resp["output"], resp["output"]


def _npz_declaring(path: Path, shape: tuple[int, ...], member: str = "shell_pose.npy") -> None:
    """A valid-looking session file whose ``shell_pose`` header declares ``shape`` but holds 24 bytes
    (in the zip member ``member``: numpy reads ``shell_pose`` as the array ``shell_pose`` too)."""
    import io
    import zipfile

    import numpy as np

    arrays = {"stella_pose": np.zeros((5, 3)), "event_start_end": np.array([[0, 4]]), "event_mover": np.array([0])}
    with zipfile.ZipFile(path, "w") as zf:
        for name, a in arrays.items():
            buf = io.BytesIO()
            np.lib.format.write_array(buf, a)
            zf.writestr(name + ".npy", buf.getvalue())
        buf = io.BytesIO()
        np.lib.format.write_array_header_1_0(buf, {"descr": "<f8", "fortran_order": False, "shape": shape})
        zf.writestr(member, buf.getvalue() + b"\0" * 24)


@pytest.mark.parametrize("shape", [(10**11, 3), (2**62, 3), (10**6, 10**6)])
def test_an_npz_declaring_a_huge_array_is_refused_before_it_is_loaded(worker, tmp_path, shape):
    _npz_declaring(tmp_path / "huge.npz", shape)
    resp = worker.run(["train", "around", "--demos", "huge.npz", "--out", "b"], tmp_path)
    check(resp, worker)
    assert resp["exit_code"] == 2 and "declares shape" in resp["output"], resp["output"]


RUN_READERS = {
    "review": ["review", "run", "--db", "r.sqlite", "--port", "0"],
    "export": ["export", "run", "out"],
    "export rerun": ["export", "run", "--format", "rerun", "out.rrd"],
}


@pytest.mark.parametrize("command", list(RUN_READERS))
@pytest.mark.parametrize("trajectory", ["linked to /dev/zero", "nested 100,000 deep"])
def test_a_run_folder_from_elsewhere_is_read_bounded(fresh, tmp_path, command, trajectory):
    """A run folder someone hands over (a tarball keeps links) whose trajectory.json never ends or nests past
    the recursion limit: review and export used to read /dev/zero until memory ran out, and print a
    RecursionError traceback. A worker of its own: the Rerun SDK's threads take much of a shared worker's
    address space, and the 64 MiB bounded read must fit in what is left."""
    run = tmp_path / "run"
    run.mkdir()
    if trajectory == "linked to /dev/zero":
        (run / "trajectory.json").symlink_to("/dev/zero")
    else:
        (run / "trajectory.json").write_text("[" * 100_000 + "]" * 100_000)
    resp = fresh.run(RUN_READERS[command], tmp_path)
    assert resp["exception"] is None, resp["exception"]
    last = resp["output"].strip().splitlines()[-1]  # export's progress line may come first
    assert resp["exit_code"] == 2 and last.startswith("error: ") and "trajectory.json" in last, resp["output"][-3000:]
    assert resp["peak_rss"] < resp["limit"]


def _grades_file(folder: Path, kind: str) -> str:
    """A grades file as a stranger might hand it over (docs/review.md's export, damaged)."""
    from l2p_bullet.data.grades import EXPORT_FIELDS

    if kind == "a CSV cell of 200,000 characters":
        row = dict.fromkeys(EXPORT_FIELDS, "") | {"action": "past", "mode": "graded", "grade": "5", "run_id": "r",
                                                  "comment": "x" * 200_000}
        (folder / "g.csv").write_text(",".join(EXPORT_FIELDS) + "\n" + ",".join(row[k] for k in EXPORT_FIELDS) + "\n")
        return "g.csv"
    if kind == "JSON lines nested 100,000 deep":
        (folder / "g.jsonl").write_text("[" * 100_000 + "]" * 100_000 + "\n")
        return "g.jsonl"
    (folder / "g.jsonl").symlink_to("/dev/zero")
    return "g.jsonl"


GRADE_READERS = {"report": lambda f: ["report", "--db", f, "--out", "rep"],
                 "train --feedback": lambda f: ["train", "past", "--feedback", f, "--out", "b"]}


@pytest.mark.parametrize("command", list(GRADE_READERS))
@pytest.mark.parametrize("kind", ["a CSV cell of 200,000 characters", "JSON lines nested 100,000 deep",
                                  "linked to /dev/zero"])
def test_a_grades_file_from_elsewhere_is_a_one_line_error(fresh, tmp_path, command, kind):
    """``report --db`` and ``train --feedback`` read grades files people hand over: csv's field limit and
    JSON's recursion limit were tracebacks, and report read a link to /dev/zero until memory ran out.
    (train --feedback refuses a link to a device before reading it: no file.)"""
    name = _grades_file(tmp_path, kind)
    resp = fresh.run(GRADE_READERS[command](name), tmp_path)
    assert resp["exception"] is None, resp["exception"]
    last = resp["output"].strip().splitlines()[-1]
    assert resp["exit_code"] == 2 and last.startswith("error: ") and name in last, resp["output"][-3000:]
    assert resp["peak_rss"] < resp["limit"]


@pytest.mark.parametrize("content", ["linked to /dev/zero", "nested 100,000 deep"])
def test_an_evaluation_scene_file_is_read_bounded(fresh, tmp_path, content):
    """``evaluate --scene-file``'s JSON lines: a line nested past the recursion limit was a RecursionError
    traceback, and a file linked to /dev/zero was read until memory ran out."""
    if content == "linked to /dev/zero":
        (tmp_path / "scenes.jsonl").symlink_to("/dev/zero")
    else:
        (tmp_path / "scenes.jsonl").write_text("[" * 100_000 + "]" * 100_000 + "\n")
    resp = fresh.run(["evaluate", "--scene-file", "scenes.jsonl", "--out", "ev"], tmp_path)
    check(resp, fresh)
    assert resp["exit_code"] == 2 and "scenes.jsonl" in resp["output"], resp["output"][-3000:]


@pytest.mark.parametrize("member", ["shell_pose", "shell_pose.NPY"])
def test_an_npz_member_not_named_npy_is_checked_too(worker, tmp_path, member):
    """numpy loads a member without the .npy suffix under its own name: its header is checked the same."""
    _npz_declaring(tmp_path / "huge.npz", (10**11, 3), member)
    resp = worker.run(["train", "around", "--demos", "huge.npz", "--out", "b"], tmp_path)
    check(resp, worker)
    assert resp["exit_code"] == 2 and "declares shape" in resp["output"], resp["output"]


def test_an_npz_member_that_is_not_an_array_is_refused(tmp_path):
    """numpy hands back a member that is not an array as bytes: refused, not an AttributeError traceback."""
    import zipfile

    import numpy as np

    np.savez(tmp_path / "bytes.npz", shell_pose=np.zeros((5, 3)), stella_pose=np.ones((5, 3)),
             event_start_end=np.array([[0, 4]]), event_mover=np.array([0]))
    with zipfile.ZipFile(tmp_path / "bytes.npz", "a") as zf:
        zf.writestr("more_poses", b"hello, not an array")
    with pytest.raises(DataError, match='"more_poses" is not a numpy array'):
        load_session(tmp_path / "bytes.npz")


def test_an_npz_member_the_loader_does_not_read_is_left_alone(tmp_path):
    """A session with a member of its own (notes) loads as before the member check: only what is read must be
    an array."""
    import zipfile

    import numpy as np

    np.savez(tmp_path / "notes.npz", shell_pose=np.zeros((5, 3)), stella_pose=np.ones((5, 3)),
             event_start_end=np.array([[0, 4]]), event_mover=np.array([0]))
    with zipfile.ZipFile(tmp_path / "notes.npz", "a") as zf:
        zf.writestr("notes.txt", b"captured on Tuesday")
    arrays = load_session(tmp_path / "notes.npz")
    assert sorted(arrays) == ["event_mover", "event_start_end", "shell_pose", "stella_pose"]


def test_a_forked_workers_limit_is_a_fresh_workers(worker, fresh, tmp_path):
    """A request answered in a worker forked for it alone is capped as in a worker started for it: its start-up
    footprint plus :data:`MARGIN` (the two start-ups differ by what the last one imported, not by gigabytes)."""
    resp = fresh.run(["perform", "move A past B", "--scene", "missing.json", "--no-render", "--out", "r"], tmp_path)
    assert resp["exit_code"] == 2 and resp["exception"] is None, resp
    assert abs(resp["limit"] - worker.limit) < MARGIN // 4 and resp["peak_rss"] < resp["limit"]
