"""``l2p-bullet export --format lerobot``: a LeRobot v3.0 dataset read back with pyarrow and ffmpeg."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.core.scene import random_scene
from l2p_bullet.embodiment.sim.camera import RenderSettings
from l2p_bullet.export.episodes import demo_episodes, episode_from_run
from l2p_bullet.export.lerobot import VIDEO_KEY, write_lerobot
from l2p_bullet.pipeline import perform

pa = pytest.importorskip("pyarrow")
pq = pytest.importorskip("pyarrow.parquet")

TINY = RenderSettings(width=64, height=48, fps=10.0)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    root = tmp_path_factory.mktemp("runs")
    out = []
    for i, sentence in enumerate(("move A closer to B", "move A past B")):
        r = perform(sentence, random_scene(i), out_dir=root / f"run{i}", seed=i, render=True, render_settings=TINY)
        out.append(r.out_dir)
    return out


@pytest.mark.slow
def test_runs_and_a_demo_read_back_frame_for_frame(runs, tmp_path):
    import imageio.v2 as imageio

    episodes = [episode_from_run(r) for r in runs] + list(demo_episodes(["next-to:0"], render=TINY))
    out = tmp_path / "ds"
    info = write_lerobot(episodes, out)
    meta = json.loads((out / "meta" / "info.json").read_text())
    assert meta == info and meta["codebase_version"] == "v3.0" and meta["fps"] == 10
    assert meta["total_episodes"] == 3 and meta["total_tasks"] == 3

    data = pq.read_table(out / "data/chunk-000/file-000.parquet").to_pydict()
    eps = pq.read_table(out / "meta/episodes/chunk-000/file-000.parquet").to_pylist()
    tasks = pq.read_table(out / "meta/tasks.parquet")
    assert json.loads(tasks.schema.metadata[b"pandas"])["index_columns"] == ["task"]  # LeRobot's task index
    task_of = dict(zip(tasks.column("task_index").to_pylist(), tasks.column("task").to_pylist(), strict=True))
    assert len(data["index"]) == meta["total_frames"] == sum(e["length"] for e in eps)
    assert data["index"] == list(range(meta["total_frames"]))

    for ep, source in zip(eps, episodes, strict=True):
        lo, hi = ep["dataset_from_index"], ep["dataset_to_index"]
        assert ep["tasks"] == [source.task] and task_of[data["task_index"][lo]] == source.task
        frames = source.frames[::3][: hi - lo]  # 30 fps trajectory, 10 fps video: every third frame
        state = np.array(data["observation.state"][lo:hi])
        mover = np.array([[f["poses"]["A"][0], f["poses"]["A"][1], f["poses"]["A"][3]] for f in frames])
        np.testing.assert_allclose(state[:, :3], mover, atol=1e-6)
        ee = np.array([f["ee"] for f in frames])
        action = np.array(data["action"][lo:hi])
        np.testing.assert_allclose(action[:-1, :3], ee[1:], atol=1e-6)  # the action is where the arm went next
        grasped = np.array([f["grasped"] is not None for f in frames], float)
        np.testing.assert_array_equal(state[:, 9], grasped)
        assert grasped.any() and not grasped[0]
        assert data["frame_index"][lo:hi] == list(range(hi - lo))
        assert data["timestamp"][hi - 1] == pytest.approx((hi - lo - 1) / 10)
        assert ep[f"videos/{VIDEO_KEY}/from_timestamp"] == pytest.approx(lo / 10)
        assert np.isfinite(data["observation.progress"][hi - 1])
        assert len(source.images) >= hi - lo

    reader = imageio.get_reader(out / f"videos/{VIDEO_KEY}/chunk-000/file-000.mp4")
    video = [np.asarray(f) for f in reader]
    assert len(video) == meta["total_frames"]
    assert video[0].shape == (48, 64, 3)
    first = episodes[0].images[0].astype(float)
    assert np.abs(video[0].astype(float) - first).mean() < 12  # lossy, but the same picture


def test_cli_exports_plain_json_by_default_and_lerobot_without_video(runs, tmp_path):
    r = CliRunner().invoke(main, ["export", str(runs[0]), str(tmp_path / "plain")])
    assert r.exit_code == 0, r.output
    line = json.loads((tmp_path / "plain" / "episodes.jsonl").read_text().splitlines()[0])
    assert line["task"] == "move A closer to B" and len(line["frames"]) > 10
    # named twice, and found again under its parent
    twice = CliRunner().invoke(main, ["export", str(runs[0]), str(runs[0]) + "/", str(runs[0].parent),
                                      str(tmp_path / "once"), "--json"])
    assert twice.exit_code == 0 and json.loads(twice.stdout)["episodes"] == 2, twice.output
    r = CliRunner().invoke(main, ["export", str(runs[0].parent), "--format", "lerobot", "--no-video",
                                  str(tmp_path / "lr"), "--json"])
    assert r.exit_code == 0, r.output
    # progress with an ETA on stderr (issue 26: 20 s of silence), the summary alone on stdout (JSON with --json)
    assert "export: reading [" in r.stderr and "2/2 episodes (100%)" in r.stderr and "ETA" in r.stderr
    assert "export: writing [" in r.stderr and json.loads(r.stdout)["episodes"] == 2
    info = json.loads((tmp_path / "lr" / "meta" / "info.json").read_text())
    assert info["fps"] == 30 and info["video_path"] is None and info["total_episodes"] == 2
    assert VIDEO_KEY not in info["features"]
    again = CliRunner().invoke(main, ["export", str(runs[0]), "--format", "lerobot", str(tmp_path / "lr")])
    assert again.exit_code == 2 and "--force" in again.output  # nothing is overwritten without asking


def test_export_force_replaces_only_a_previous_export(runs, tmp_path):
    """--force may replace an export of ours, never a folder holding someone else's file."""
    out = tmp_path / "plain"
    assert CliRunner().invoke(main, ["export", str(runs[0]), str(out)]).exit_code == 0
    assert CliRunner().invoke(main, ["export", str(runs[0]), str(out), "--force"]).exit_code == 0
    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "thesis.txt").write_text("x")
    r = CliRunner().invoke(main, ["export", str(runs[0]), str(foreign), "--force"])
    assert r.exit_code == 2 and r.output.startswith("error: ") and (foreign / "thesis.txt").read_text() == "x"
