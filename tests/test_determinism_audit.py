"""Determinism audit (2026-11-28): the same sentence, scene, seed, arm and manner give the same plan, trajectory and
verdict whichever way the run is made. What the existing tests did not cover yet: another process (another working
folder, hash seed and thread counts) against the Python API; an evaluation worker's kept run folder after other runs
in the same worker against a fresh ``perform``; rendering against ``--no-render``; a reused Arm-v0 environment; a
replay of a replay; training in two processes with different thread counts.

Found and fixed with it: ``replay`` of a run's plan.json did not reproduce a push (plan.json rounded the path to
1e-6 m, and contact made the block end 1 mm and 6 degrees elsewhere: plan.json now holds the path as executed), and
a chain's replay recorded its clauses as "move ... next-to" (it now records the run's own words).

Kept as an xfail (not strict: a numpy whose kernels agree would pass it): a push is reproduced on one machine, not
across CPUs. numpy's BLAS kernel is chosen per CPU, so the planner's path differs in its last bit between kernels
(5.6e-17 m on random_scene(11)), and a push, which contact makes chaotic, then ends elsewhere. Slides and carries
do not change. docs/manners.md says so.
"""

from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from l2p_bullet.core.scene import Scene, random_scene, save_scene
from l2p_bullet.pipeline import perform

TIMING = {"seconds", "timings_s", "versions", "wall_s", "render_s", "wait_s"}


def _strip(doc):
    """A run file's JSON without what depends on the machine and the moment."""
    if isinstance(doc, dict):
        return {k: _strip(v) for k, v in doc.items() if k not in TIMING}
    if isinstance(doc, list):
        return [_strip(v) for v in doc]
    return doc


def _json(folder: Path, name: str):
    return _strip(json.loads((folder / name).read_text()))


def _same_run(a: Path, b: Path) -> None:
    """Byte-identical trajectories, and plan.json and summary.json equal but for timings and versions."""
    assert (a / "trajectory.json").read_bytes() == (b / "trajectory.json").read_bytes()
    assert _json(a, "plan.json") == _json(b, "plan.json")
    assert _json(a, "summary.json") == _json(b, "summary.json")


def _cli(args: list[str], cwd: Path, python: tuple[str, ...] = (), **env) -> subprocess.CompletedProcess:
    full = {**os.environ, **env}
    r = subprocess.run([sys.executable, *python, "-m", "l2p_bullet.cli", *args], cwd=cwd, env=full,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    return r


# sentence, scene seed, run seed, arm: the most sensitive manner (push) and a carry on another arm
CASES = [("push A past B", 11, 2, "panda"), ("carry A around B", 4, 1, "xarm6")]


@pytest.mark.slow
@pytest.mark.parametrize(("sentence", "scene_seed", "seed", "arm"), CASES)
def test_another_process_folder_hash_seed_and_thread_count_give_the_api_run(sentence, scene_seed, seed, arm, tmp_path):
    scene = random_scene(scene_seed)
    save_scene(scene, tmp_path / "scene.json")
    perform(sentence, scene, out_dir=tmp_path / "api", render=False, seed=seed, arm=arm)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    _cli(["perform", sentence, "--scene", str(tmp_path / "scene.json"), "--seed", str(seed), "--arm", arm,
          "--no-render", "-q", "--out", "../cli"], cwd=elsewhere, PYTHONHASHSEED="12345", OMP_NUM_THREADS="2",
         MKL_NUM_THREADS="2", OPENBLAS_NUM_THREADS="2")
    _same_run(tmp_path / "api", tmp_path / "cli")


@pytest.mark.slow
def test_an_evaluation_workers_kept_folder_after_other_runs_is_a_fresh_perform(tmp_path):
    """The worker keeps its worlds between runs (one per arm): a push on the xArm6 after a carry on it and a slide on
    the Panda records what a fresh ``perform`` records."""
    from l2p_bullet.evaluate.tasks import Task
    from l2p_bullet.evaluate.worker import Worker

    def task(name, scene, sentence, action, seed, arm, manner):
        return Task(run_id=name, index=0, scene_id=name, scene_source="test", scene=scene.to_dict(), mover="A",
                    anchor="B", action=action, sentence=sentence, planner="default", seed=seed, keep="all",
                    run_dir=str(tmp_path / name), arm=arm, manner=manner)

    worker = Worker()
    try:
        for t in (task("slide", random_scene(5), "move A around B", "around", 5, "panda", "slide"),
                  task("carry", random_scene(6), "carry A next to B", "next-to", 6, "xarm6", "carry"),
                  task("push", random_scene(11), "push A past B", "past", 2, "xarm6", "push")):
            row = worker.run(t)
            assert row["error"] is None, row["error"]
    finally:
        worker.close()
    perform("push A past B", random_scene(11), out_dir=tmp_path / "fresh", render=False, seed=2, arm="xarm6")
    _same_run(tmp_path / "push", tmp_path / "fresh")


@pytest.mark.slow
def test_rendering_adds_images_and_changes_no_motion(push_run, tmp_path):
    from l2p_bullet.embodiment.sim.camera import RenderSettings

    small = RenderSettings(width=64, height=48, fps=5.0, renderer="tiny", workers=0)
    perform("push A past B", random_scene(11), out_dir=tmp_path / "drawn", render=True, seed=2, render_settings=small)
    assert list((tmp_path / "drawn" / "frames").glob("*.png"))
    assert (push_run / "trajectory.json").read_bytes() == (tmp_path / "drawn" / "trajectory.json").read_bytes()
    assert _json(push_run, "plan.json") == _json(tmp_path / "drawn", "plan.json")
    a, b = _json(push_run, "summary.json"), _json(tmp_path / "drawn", "summary.json")
    assert a["verdict"] == b["verdict"] and a["final_progress"] == b["final_progress"]


def test_a_reused_arm_environment_repeats_a_seeded_episode():
    import gymnasium as gym

    import l2p_bullet.envs  # noqa: F401  (registers the ids)

    def episode(env, seed):
        env.action_space.seed(seed)
        obs, _ = env.reset(seed=seed)
        out = [obs]
        for _ in range(3):
            obs, r, term, trunc, _ = env.step(env.action_space.sample())
            out += [obs, np.array([r], np.float32)]
            if term or trunc:
                break
        return np.concatenate(out)

    fresh = gym.make("l2p_bullet/Arm-v0", action="around")
    first = episode(fresh, 7)
    fresh.close()
    reused = gym.make("l2p_bullet/Arm-v0", action="around")
    episode(reused, 3)
    episode(reused, 4)
    np.testing.assert_array_equal(episode(reused, 7), first)
    reused.close()


def _replay(plan: Path, out: Path) -> None:
    from click.testing import CliRunner

    from l2p_bullet.cli import main

    r = CliRunner().invoke(main, ["replay", str(plan), "--no-render", "--out", str(out)])
    assert r.exit_code == 0, r.output


@pytest.fixture(scope="module")
def push_run(tmp_path_factory) -> Path:
    """"push A past B" on random_scene(11) with seed 2, unrendered: performed once for the tests that compare a
    rendered run or a replay with it (they only read it)."""
    out = tmp_path_factory.mktemp("push") / "run"
    perform("push A past B", random_scene(11), out_dir=out, render=False, seed=2)
    return out


@pytest.fixture(scope="module")
def push_replay(push_run, tmp_path_factory) -> Path:
    """``push_run``'s plan.json replayed once (read only)."""
    out = tmp_path_factory.mktemp("push-replay") / "once"
    _replay(push_run / "plan.json", out)
    return out


def _poses(folder: Path) -> np.ndarray:
    frames = json.loads((folder / "trajectory.json").read_text())["frames"]
    return np.array([[v for name in sorted(f["poses"]) for v in f["poses"][name]] for f in frames])


@pytest.mark.slow
def test_a_replay_of_a_replay_is_byte_identical(push_replay, tmp_path):
    """A replay's plan.json holds exactly the path it executed, so replaying it again repeats it."""
    _replay(push_replay / "plan.json", tmp_path / "twice")
    assert (push_replay / "trajectory.json").read_bytes() == (tmp_path / "twice" / "trajectory.json").read_bytes()


@pytest.mark.slow
def test_replaying_a_push_runs_plan_reproduces_the_run(push_run, push_replay):
    """plan.json holds the path as executed: rounded to 1e-6 m, the replayed push ended 1 mm and 6 degrees away."""
    run, again = _poses(push_run), _poses(push_replay)
    assert run.shape == again.shape and np.array_equal(run, again)


@pytest.mark.slow
def test_a_chain_replay_records_the_clauses_as_the_run_did(tmp_path):
    """The run's own words (it recorded 'move' for a carried clause and 'next-to' for 'next to')."""
    from l2p_bullet.chain import perform_chain

    scene = Scene.from_dict({"objects": [
        {"name": "A", "color": "red", "size": 0.05, "xy": [-0.12, -0.05], "yaw": 0.0},
        {"name": "B", "color": "green", "size": 0.05, "xy": [0.02, 0.05], "yaw": 0.0},
        {"name": "C", "color": "blue", "size": 0.05, "xy": [0.12, -0.1], "yaw": 0.0}]})
    perform_chain("move A next to B, then carry C past A", scene, out_dir=tmp_path / "run", render=False, seed=7)
    _replay(tmp_path / "run" / "plan.json", tmp_path / "replay")
    run, again = (json.loads((tmp_path / d / "summary.json").read_text()) for d in ("run", "replay"))
    assert [c["verb"] for c in again["clauses"]] == [c["verb"] for c in run["clauses"]] == ["move", "carry"]
    assert again["command"] == run["command"]


def _openblas() -> bool:
    config = np.show_config(mode="dicts") if "mode" in np.show_config.__code__.co_varnames else {}
    blas = (config.get("Build Dependencies", {}).get("blas", {}) or {}).get("name", "")
    return "openblas" in blas.lower()


@pytest.mark.slow
@pytest.mark.skipif(platform.machine() not in ("x86_64", "AMD64") or not _openblas(),
                    reason="OPENBLAS_CORETYPE names x86 kernels of numpy's OpenBLAS")
@pytest.mark.xfail(strict=False, reason="numpy's BLAS kernel is chosen per CPU (SSE3 Prescott vs AVX2 Haswell round "
                   "differently): the planner's path differs in its last bit, and a push, chaotic by contact, ends "
                   "elsewhere on another machine (tenths of a radian in the arm, its progress, its verdict's wording)")
def test_a_push_does_not_depend_on_the_cpus_blas_kernel(tmp_path):
    """Both kernels are forced, so the outcome does not depend on which CPU runs the test (any x86-64 has both)."""
    scene = random_scene(11)
    save_scene(scene, tmp_path / "scene.json")
    for core in ("Haswell", "Prescott"):
        r = subprocess.run(
            [
                sys.executable,
                "-m",
                "l2p_bullet.cli",
                "perform",
                "push A past B",
                "--scene",
                str(tmp_path / "scene.json"),
                "--seed",
                "2",
                "--no-render",
                "-q",
                "--out",
                str(tmp_path / core),
            ],
            cwd=tmp_path,
            env={**os.environ, "OPENBLAS_CORETYPE": core},
            capture_output=True,
            text=True,
            timeout=120,
        )
        if r.returncode != 0:  # a CPU without that kernel: not the difference this test is about
            pytest.skip(f"the {core} kernel does not run here: {r.stderr[-300:]}")
    haswell, prescott = ((tmp_path / core / "trajectory.json").read_bytes() for core in ("Haswell", "Prescott"))
    # a flag, not the two files: where they differ pytest's explanation of ``==`` runs difflib over the two 120 kB
    # files in full when CI is set (a minute of CPU for this expected failure)
    same = haswell == prescott
    assert same, f"the trajectories differ ({len(haswell)} and {len(prescott)} bytes)"


@pytest.mark.slow
def test_training_in_two_processes_with_other_thread_counts_gives_the_same_weights(tmp_path):
    """tests/cli/test_score.py trains twice in one process; here two processes, 1 and 2 threads, another folder.
    The first lists its imports (``-X importtime``): a Python that trains does not import ``torch._dynamo``, which
    torch.optim's classes import (1.2 s; learning/adam.py, whose numbers tests/learning/test_adam.py holds to
    theirs)."""
    from l2p_bullet.data.demos import data_dir

    session = data_dir() / "captures" / "SlidePast_Session1.npz"
    args = ["train", "past", "--demos", str(session), "--ensemble", "1", "--epochs", "2", "--seed", "3"]
    first = _cli([*args, "--out", str(tmp_path / "a")], cwd=tmp_path, python=("-X", "importtime"),
                 OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    imported = {line.rsplit("|", 1)[-1].strip() for line in first.stderr.splitlines()
                if line.startswith("import time:")}
    assert "torch" in imported and "torch._dynamo" not in imported
    (tmp_path / "sub").mkdir()
    _cli([*args, "--out", "../b"], cwd=tmp_path / "sub", OMP_NUM_THREADS="2", MKL_NUM_THREADS="2",
         PYTHONHASHSEED="99")
    assert (tmp_path / "a" / "progress.safetensors").read_bytes() == (
        tmp_path / "b" / "progress.safetensors"
    ).read_bytes()
