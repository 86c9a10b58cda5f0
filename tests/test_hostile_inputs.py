"""Hostile and careless inputs, one row each: every one a one-line error (or a correct result), nothing a user
made lost, bounded memory and time.

The rows: a GLB naming a huge external buffer, an absurd mesh scale, sizes that must read apart, invisible
characters in errors, URDFs that crash PyBullet (two root links, a quarter of a million chained links) and
their malformed cousins, a Ray address nobody answers on, crafted run folders (frame rates, segments, a
chain plan of too many clauses), composite bundles with loose digests and loose booleans, and an export
that is refused or meets an interrupted run.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import socket
import struct
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main, one_line
from l2p_bullet.core import shapes
from l2p_bullet.core.scene import default_scene, load_scene
from l2p_bullet.errors import L2PError, PathError, PluginError, SceneError, sizes

ROW = Path(__file__).resolve().parents[1] / "l2p_bullet" / "actions" / "row"


def _one_line_error(result) -> str:
    lines = result.output.strip().splitlines()
    assert result.exit_code == 2 and lines and lines[-1].startswith("error: "), result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return lines[-1]


# --- meshes ------------------------------------------------------------------------------------------------
def _glb(path: Path, external: str | None) -> None:
    """A 5 cm cube as a GLB; with ``external`` its buffer lies in that sibling file, as the glTF spec allows."""
    import trimesh

    data = trimesh.creation.box((0.05, 0.05, 0.05)).export(file_type="glb")
    (jlen,) = struct.unpack_from("<I", data, 12)
    doc = json.loads(data[20:20 + jlen])
    binary = data[20 + jlen + 8:]
    if external is None:
        path.write_bytes(data)
        return
    doc["buffers"][0]["uri"] = external
    (path.parent / external).write_bytes(binary)
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    path.write_bytes(struct.pack("<4sII", b"glTF", 2, 20 + len(js)) + struct.pack("<I4s", len(js), b"JSON") + js)


def _mesh_scene(folder: Path, mesh: str, **fields) -> Path:
    d = default_scene().to_dict()
    d["objects"][0].update(shape="mesh", mesh=mesh, **fields)
    path = folder / "scene.json"
    path.write_text(json.dumps(d))
    return path


def test_a_glb_with_a_small_external_buffer_loads(tmp_path):
    _glb(tmp_path / "cube.glb", "cube.bin")
    scene = load_scene(_mesh_scene(tmp_path, "cube.glb"))
    assert scene.objects[0].shape == "mesh" and (tmp_path / "cube.glb").stat().st_size < 2000


def test_a_glb_naming_a_huge_external_buffer_is_refused_unread(tmp_path, monkeypatch):
    """A 400-byte GLB naming a 3 GB sibling .bin took 3.2 GB resident: the buffer counts toward the mesh limit
    and is never read past it (a sparse file here: nothing is written to disk)."""
    _glb(tmp_path / "cube.glb", "big.bin")
    with open(tmp_path / "big.bin", "r+b") as f:
        f.truncate(3 * 2**30)
    read = []
    real = shapes.read_bounded

    def spy(path, limit, error, label=""):
        data = real(path, limit, error, label)
        read.append(len(data))
        return data

    monkeypatch.setattr(shapes, "read_bounded", spy)
    with pytest.raises(SceneError, match="names big.bin, which takes it past the 16 MiB a mesh may read in all"):
        load_scene(_mesh_scene(tmp_path, "cube.glb"))
    assert sum(read) <= shapes.MAX_MESH_BYTES + 1  # the 3 GB never came in


@pytest.mark.parametrize("scale", [1e308, 1e7, 1e-9])
def test_an_absurd_mesh_scale_is_a_scene_error(tmp_path, scale):
    _glb(tmp_path / "cube.glb", None)
    with pytest.raises(SceneError, match='"scale" must be from 1e-06 to 1e\\+06'):
        load_scene(_mesh_scene(tmp_path, "cube.glb", scale=scale))


def test_sizes_over_a_limit_read_apart(tmp_path):
    """"17 MB is more than the 17 MB": a size and its limit are printed precisely enough to differ."""
    assert sizes(17_000_000, 16 * 2**20) == ("16.2 MiB", "16.0 MiB")
    assert sizes(16 * 2**20 + 1, 16 * 2**20) == ("16,777,217 bytes", "16,777,216 bytes")
    with open(tmp_path / "big.stl", "wb") as f:
        f.truncate(17_000_000)
    with pytest.raises(SceneError) as e:
        load_scene(_mesh_scene(tmp_path, "big.stl"))
    assert "16.2 MiB is more than the 16.0 MiB" in str(e.value)


# --- what errors echo -------------------------------------------------------------------------------------
@pytest.mark.parametrize("char", ["\u202e", "\u200b", "\u2066", "\ufeff", "\x9b", "\u2028"])
def test_invisible_characters_are_escaped_in_errors(char):
    line = one_line(f"unknown object \"A{char}B\"")
    assert char not in line and f"\\u{ord(char):04x}" in line


def test_a_right_to_left_override_in_a_path_is_shown_escaped(tmp_path):
    """A folder named "runs<RLO>nosj.txt" printed raw reads "runstxt.json" reversed in a terminal."""
    folder = tmp_path / "runs\u202enosj.txt"
    folder.mkdir()
    r = CliRunner().invoke(main, ["export", str(folder), str(tmp_path / "out")])
    line = _one_line_error(r)
    assert "holds no run folder" in line and "runs\\u202enosj.txt" in line and "\u202e" not in r.output


# --- URDFs ------------------------------------------------------------------------------------------------
def _chain_urdf(path: Path, links: int, roots: int = 1) -> Path:
    parts = ['<robot name="r">']
    parts += [f'<link name="l{i}"/>' for i in range(links)]
    parts += [f'<joint name="j{i}" type="fixed"><parent link="l{i - 1}"/><child link="l{i}"/></joint>'
              for i in range(roots, links)]
    path.write_text("".join(parts) + "</robot>")
    return path


URDFS = {  # name: (text, what the one-line error says)
    "two-roots": ('<robot name="r"><link name="a"/><link name="b"/></robot>', "has 2 root links"),
    "no-link": ('<robot name="r"></robot>', "has no link"),
    "not-robot": ('<sdf><link name="a"/></sdf>', "not <robot>"),
    "not-xml": ("<robot><link name='a'>", "not valid XML"),
    "entities": ('<?xml version="1.0"?><!DOCTYPE r [<!ENTITY x "y">]><robot name="r"><link name="a"/></robot>',
                 "declares XML entities"),
    "unknown-link": ('<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/>'
                     '<child link="zz"/></joint></robot>', 'names the child link "zz"'),
    "two-parents": ('<robot name="r"><link name="a"/><link name="b"/><link name="c"/>'
                    '<joint name="j1" type="fixed"><parent link="a"/><child link="c"/></joint>'
                    '<joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint></robot>',
                    "is the child of two joints"),
    "cycle": ('<robot name="r"><link name="a"/><link name="b"/><link name="c"/>'
              '<joint name="j1" type="fixed"><parent link="b"/><child link="c"/></joint>'
              '<joint name="j2" type="fixed"><parent link="c"/><child link="b"/></joint></robot>',
              "is not reached from the root link"),
    "same-name": ('<robot name="r"><link name="a"/><link name="a"/></robot>', 'two links are named "a"'),
}


@pytest.mark.parametrize("case", sorted(URDFS))
def test_a_malformed_urdf_is_refused_before_pybullet(tmp_path, case):
    from l2p_bullet.embodiment.sim.bullet import Bullet
    from l2p_bullet.embodiment.sim.urdf_check import check_urdf

    text, said = URDFS[case]
    path = tmp_path / f"{case}.urdf"
    path.write_text(text)
    with pytest.raises(PluginError, match=said):  # the check alone (PyBullet never reached: it may crash)
        check_urdf(str(path))
    with Bullet() as sim, pytest.raises(PluginError, match=said):  # and the facade runs it
        sim.load_urdf("arm", str(path), (0.0, 0.0, 0.0))


def test_too_many_links_and_too_many_bytes_are_refused(tmp_path):
    from l2p_bullet.embodiment.sim.urdf_check import MAX_URDF_BYTES, MAX_URDF_LINKS, check_urdf

    with pytest.raises(PluginError, match=f"has {MAX_URDF_LINKS + 1} links"):
        check_urdf(str(_chain_urdf(tmp_path / "long.urdf", MAX_URDF_LINKS + 1)))
    check_urdf(str(_chain_urdf(tmp_path / "ok.urdf", 40)))  # a long arm is fine
    with open(tmp_path / "huge.urdf", "wb") as f:
        f.truncate(MAX_URDF_BYTES + 1)
    with pytest.raises(PluginError, match="larger than 16 MiB"):
        check_urdf(str(tmp_path / "huge.urdf"))


@pytest.mark.parametrize("chain", [False, True])
def test_perform_with_an_arm_whose_urdf_has_two_roots_makes_no_folder(tmp_path, chain):
    """``perform --arm`` of such an arm crashed PyBullet and left a partial run folder."""
    import dataclasses

    from l2p_bullet.arms import PANDA
    from l2p_bullet.chain import perform_chain
    from l2p_bullet.pipeline import perform

    urdf = tmp_path / "bad.urdf"
    urdf.write_text(URDFS["two-roots"][0])
    arm = dataclasses.replace(PANDA, name="bad", urdf=str(urdf))
    out = tmp_path / "run"
    sentence = "move A closer to B, then move A away from B" if chain else "move A closer to B"
    with pytest.raises(PluginError, match="has 2 root links"):
        (perform_chain if chain else perform)(sentence, default_scene(), out_dir=out, render=False, arm=arm)
    assert not out.exists()


def _new_arm(tmp_path: Path, urdf: Path) -> subprocess.CompletedProcess:
    # a subprocess: on the old code PyBullet ended the process with a segmentation fault (exit 139)
    return subprocess.run([sys.executable, "-m", "l2p_bullet.cli", "new-arm", "bad", "--urdf", str(urdf), "--out",
                           str(tmp_path / "l2p-arm-bad")], capture_output=True, text=True, timeout=120,
                          cwd=tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("links,roots", [(3, 2), (224_678, 1)])
def test_new_arm_refuses_urdfs_that_crashed_pybullet(tmp_path, links, roots):
    urdf = _chain_urdf(tmp_path / "bad.urdf", links, roots)
    r = _new_arm(tmp_path, urdf)
    assert r.returncode == 2, (r.returncode, r.stderr[-500:])
    lines = r.stderr.strip().splitlines()
    assert lines[-1].startswith("error: ") and len(lines) <= 2, r.stderr[-500:]  # after "reading and measuring"
    assert ("root links" in r.stderr) if roots > 1 else ("more than the" in r.stderr or "links" in r.stderr)
    assert not (tmp_path / "l2p-arm-bad").exists()


# --- Ray ------------------------------------------------------------------------------------------------
@pytest.mark.slow
def test_ray_at_an_address_nobody_answers_on_gives_up(tmp_path):
    """``evaluate --ray 127.0.0.1:1`` was still waiting after 615 s; a listener that never speaks Ray too. In a
    subprocess: Ray's connecting thread, given up, stays blocked until its process ends."""
    pytest.importorskip("ray")
    env = {**os.environ, "L2P_RAY_CONNECT_TIMEOUT": "2"}
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen(4)
        for address, said in (("127.0.0.1:1", 'cannot reach Ray at "127.0.0.1:1"'),
                              (f"127.0.0.1:{s.getsockname()[1]}", "did not answer within 2 s")):
            t = time.monotonic()
            r = subprocess.run(
                [
                    sys.executable,
                    "-m",
                    "l2p_bullet.cli",
                    "evaluate",
                    "--ray",
                    address,
                    "--scenes",
                    "1",
                    "--actions",
                    "closer",
                    "--no-render",
                    "--out",
                    str(tmp_path / address.replace(":", "-")),
                ],
                capture_output=True,
                text=True,
                timeout=120,
                env=env,
                cwd=tmp_path,
            )
            errors = [line for line in r.stderr.splitlines() if line.startswith("error: ")]
            assert r.returncode == 2 and len(errors) == 1 and said in errors[0], r.stderr[-1500:]
            assert time.monotonic() - t < 60


# --- crafted run folders ----------------------------------------------------------------------------------
def _run(folder: Path, *, fps: object = 30.0, frames: int = 12, segments: list | None = None,
         poses: dict | None = None) -> Path:
    """A trajectory.json by hand: as much of a run folder as export reads."""
    folder.mkdir(parents=True)
    doc = {"sentence": "move A next to B", "action": "next-to", "mover": "A", "anchor": "B", "fps": fps,
           "objects": {"A": {"size": 0.04}, "B": {"size": 0.04}, "C": {"size": 0.04}},
           "frames": [{"t": i / 30, "poses": {n: [0.4 + 0.01 * i, 0.1 * k, 0.02, 0.0] for k, n in enumerate("ABC")},
                       "ee": [0.4, 0.0, 0.1], "grasped": None, "arm": [0.0] * JOINTS} for i in range(frames)]}
    if segments is not None:
        doc["segments"] = segments
    for f in doc["frames"] if poses is not None else []:
        f["poses"] = poses
    (folder / "trajectory.json").write_text(json.dumps(doc))
    return folder


JOINTS = 9
"""The Panda's movable joints (each frame's "arm")."""


def _seg(clause: int, first: int, last: int) -> dict:
    return {"clause": clause, "text": "move A next to B", "action": "next-to", "mover": "A", "anchors": ["B"],
            "anchor": "B", "first_frame": first, "last_frame": last}


BAD_RUNS = {  # name: (keyword arguments of _run, what the error says)
    "fps-zero": ({"fps": 0}, '"fps" must be a frame rate above 0'),
    "fps-negative": ({"fps": -30}, '"fps" must be a frame rate above 0'),
    "fps-huge": ({"fps": 1e300}, "at most 1000 per second"),
    "fps-text": ({"fps": "30"}, '"fps" must be a frame rate'),
    "fps-bool": ({"fps": True}, '"fps" must be a frame rate'),
    "segments-too-many": ({"frames": 40, "segments": [_seg(k + 1, 3 * k, 3 * k + 2) for k in range(11)]},
                          '"segments" must list 1 to 10 clauses \\(got 11\\)'),
    "segments-empty": ({"segments": []}, '"segments" must list 1 to 10 clauses \\(got 0\\)'),
    "segments-overlap": ({"segments": [_seg(1, 0, 6), _seg(2, 4, 11)]}, "do not follow the previous clause"),
    "segments-gap": ({"segments": [_seg(1, 0, 4), _seg(2, 7, 11)]}, "do not follow the previous clause"),
    "segments-late-start": ({"segments": [_seg(1, 2, 11)]}, "do not follow the previous clause"),
    "frames-empty": ({"frames": 0}, '"frames" must be a non-empty list'),
    "frames-no-pose": ({"frames": 3, "poses": {"A": [0, 0, 0, 0]}}, "a malformed frame"),
    "frames-short-pose": ({"frames": 3, "poses": {"A": [0, 0, 0, 0], "B": [0, 0, 0]}}, "must be \\[x, y, z, yaw\\]"),
    "fps-nan-as-null": ({"fps": None}, '"fps" must be a frame rate'),
    "segments-not-a-list": ({"segments": {"a": 1}}, '"segments" must list 1 to 10 clauses'),
}


@pytest.mark.parametrize("case", sorted(BAD_RUNS))
@pytest.mark.parametrize("fmt", ["json", "lerobot"])
def test_a_crafted_run_folder_is_refused_and_export_leaves_nothing(tmp_path, case, fmt):
    if fmt == "lerobot":
        pytest.importorskip("pyarrow")
    kwargs, said = BAD_RUNS[case]
    run = _run(tmp_path / "runs" / "r", **kwargs)
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["export", str(run), str(out), "--format", fmt])
    line = _one_line_error(r)
    assert re.search(said, line), line
    assert not out.exists()  # nothing partial, no summary.json saying ok: false
    # the fixed input exports at once into the same OUT, without --force
    shutil.rmtree(run)
    _run(run, segments=[_seg(1, 0, 5), _seg(2, 6, 11)] if "segments" in case else None)
    r = CliRunner().invoke(main, ["export", str(run), str(out), "--format", fmt])
    assert r.exit_code == 0, r.output


@pytest.mark.parametrize("case", ["fps-zero", "frames-no-pose", "segments-overlap", "segments-too-many"])
def test_a_crafted_run_folder_leaves_no_partial_rerun_recording(tmp_path, case):
    pytest.importorskip("rerun")
    kwargs, said = BAD_RUNS[case]
    run = _run(tmp_path / "runs" / "r", **kwargs)
    if case == "fps-zero":  # the recording reads the images' rate: a rendered run's summary.json
        (run / "trajectory.json").write_text((run / "trajectory.json").read_text().replace('"fps": 0', '"fps": 30'))
        (run / "frames").mkdir()
        (run / "summary.json").write_text(json.dumps({"ok": True, "render": {"fps": 0}}))
        said = '"render.fps" must be a frame rate above 0'
    out = tmp_path / "out.rrd"
    line = _one_line_error(CliRunner().invoke(main, ["export", str(run), str(out), "--format", "rerun"]))
    assert re.search(said, line), line
    assert not out.exists()


def test_a_refused_export_into_an_empty_folder_leaves_it_empty(tmp_path):
    run = _run(tmp_path / "runs" / "r", fps=0)
    out = tmp_path / "out"
    out.mkdir()
    _one_line_error(CliRunner().invoke(main, ["export", str(run), str(out)]))
    assert out.is_dir() and not any(out.iterdir())


def test_a_refused_forced_export_puts_the_earlier_one_back(tmp_path):
    good, bad = _run(tmp_path / "runs" / "good"), _run(tmp_path / "runs" / "bad", fps=-1)
    out = tmp_path / "out"
    assert CliRunner().invoke(main, ["export", str(good), str(out)]).exit_code == 0
    before = (out / "episodes.jsonl").read_bytes()
    _one_line_error(CliRunner().invoke(main, ["export", str(bad), str(out), "--force"]))
    assert (out / "episodes.jsonl").read_bytes() == before


def test_a_folder_holding_an_interrupted_run_exports_the_rest_with_a_note(tmp_path):
    """A run stopped before it wrote trajectory.json failed the whole export ("holds no run folder")."""
    from l2p_bullet.core.runfolder import run_folder

    good = _run(tmp_path / "runs" / "good")
    stopped = tmp_path / "runs" / "stopped"
    with pytest.raises(KeyboardInterrupt), run_folder(stopped, command="perform"):
        raise KeyboardInterrupt
    assert not (stopped / "trajectory.json").exists()
    for given in ([tmp_path / "runs"], [good, stopped]):
        out = tmp_path / f"out-{len(given)}"
        r = CliRunner().invoke(main, ["export", *map(str, given), str(out)])
        assert r.exit_code == 0, r.output
        assert f"skipped {stopped}: its run was interrupted" in r.output
        assert len((out / "episodes.jsonl").read_text().splitlines()) == 1
    r = CliRunner().invoke(main, ["export", str(stopped), str(tmp_path / "out-none")])
    assert "none of the 1 run folders given finished" in _one_line_error(r)


def test_segments_of_accepts_what_a_chain_writes():
    from l2p_bullet.chain.segments import segments_of

    doc = {"frames": [{}] * 12, "objects": {"A": {}, "B": {}}, "segments": [_seg(1, 0, 5), _seg(2, 6, 11)]}
    assert len(segments_of(doc)) == 2
    with pytest.raises(PathError, match="do not follow"):
        segments_of(doc | {"segments": [_seg(1, 0, 5), _seg(2, 5, 11)]})


def test_replay_refuses_a_chain_plan_of_more_clauses_than_a_chain_has(tmp_path):
    """A 60-clause plan.json was replayed; chains stop at 10 clauses."""
    plan = tmp_path / "plan.json"
    plan.write_text(json.dumps({"schema": 1, "chain": {"sentence": "x", "scene": default_scene().to_dict()},
                                "clauses": [{"plan": None}] * 60}))
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["replay", str(plan), "--no-render", "--out", str(out)])
    assert "lists 60 clauses; a chain has at most 10" in _one_line_error(r)
    assert not out.exists()


# --- composite bundles ------------------------------------------------------------------------------------
def _row_copy(tmp_path: Path) -> Path:
    folder = tmp_path / "row"
    shutil.copytree(ROW, folder, ignore=shutil.ignore_patterns("__pycache__"))
    return folder


def _drop_digest(folder: Path, name: str) -> None:
    man = (folder / "manifest.toml").read_text()
    start = man.index(f'[weights."{name}"]')
    end = man.find("[", start + 1)
    (folder / "manifest.toml").write_text(man[:start] + (man[end:] if end > 0 else ""))


def _edit_recipe(folder: Path, **fields) -> None:
    """recipe.json with ``fields`` changed and its digest recorded again (as a careful forger would)."""
    from l2p_bullet.plugins.bundle import sha256_file

    doc = json.loads((folder / "recipe.json").read_text()) | fields
    text = json.dumps(doc)
    (folder / "recipe.json").write_text(text)
    man = (folder / "manifest.toml").read_text()
    old = man.split('[weights."recipe.json"]', 1)[1].split('sha256 = "', 1)[1][:64]
    (folder / "manifest.toml").write_text(man.replace(old, sha256_file(folder / "recipe.json")))


COMPOSITES = {  # name: (how the bundle is spoilt, what the error says)
    "no-recipe-digest": (lambda f: _drop_digest(f, "recipe.json"), 'records no sha256 of recipe.json'),
    "demos-changed": (lambda f: (f / "demos.json").write_text('{"schema": 1, "demos": []}'),
                      "demos.json is not the file its manifest records"),
    "demos-gone": (lambda f: (f / "demos.json").unlink(), "demos.json is missing"),
    "monotone-no": (lambda f: _edit_recipe(f, monotone="no"), '"monotone" must be true or false'),
    "aligned-one": (lambda f: _edit_recipe(f, aligned=1), '"aligned" must be true or false'),
    "nan-angle": (lambda f: _edit_recipe(f, axis_offset_deg=float("nan")), "NaN is not a JSON number"),
    "demos-text": (lambda f: _edit_recipe(f, demos="6"), '"demos" must be a whole number'),
    "huge-angle": (lambda f: _edit_recipe(f, axis_offset_deg=1e9), "axis_offset_deg=1000000000"),
}


@pytest.mark.parametrize("case", sorted(COMPOSITES))
def test_a_loose_composite_bundle_is_refused(tmp_path, case):
    from l2p_bullet.composite.bundle import read_recipe

    folder = _row_copy(tmp_path)
    assert read_recipe(folder).monotone is True  # the copy as shipped reads
    spoil, said = COMPOSITES[case]
    spoil(folder)
    with pytest.raises(L2PError, match=said):
        read_recipe(folder)


def test_a_composite_without_demos_json_still_reads(tmp_path):
    from l2p_bullet.composite.bundle import read_recipe

    folder = _row_copy(tmp_path)
    _drop_digest(folder, "demos.json")
    (folder / "demos.json").unlink()
    assert read_recipe(folder).action == "next-to"

