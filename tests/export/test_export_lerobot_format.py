"""``export --format lerobot`` against LeRobot itself: every object's pose, the arm's joints and the images
in the dataset, its files checked against LeRobot's v3.0 layout, and loaded with ``LeRobotDataset``.

The episodes are made up here (no simulator): three blocks in one scene, two in another, so the state's
object columns, the NaN of an absent block and the images are known exactly.

LeRobot (0.4.4) pins torch < 2.11 and so cannot join the project's environment (torch 2.13). The loading
test runs LeRobot where it can be imported: in this Python, or in the one ``L2P_LEROBOT_PYTHON`` names
(a separate virtual environment with lerobot), in a subprocess without network.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from l2p_bullet.embodiment import arm_measure
from l2p_bullet.errors import PathError
from l2p_bullet.export.episodes import Episode, check_frames
from l2p_bullet.export.lerobot import ACTION_NAMES, STATE_NAMES, VIDEO_KEY, write_lerobot
from l2p_bullet.plugins import arms as arm_plugins

pa = pytest.importorskip("pyarrow")
pq = pytest.importorskip("pyarrow.parquet")

JOINTS = len(arm_measure.joint_names(arm_plugins.get("panda")))


def made_up(objects: list[str], n: int, seed: int, images: bool) -> Episode:
    """An episode of ``n`` frames at 10 fps (images at the same rate) whose every value is known."""
    rng = np.random.default_rng(seed)
    frames = []
    for t in range(n):
        poses = {o: [round(float(v), 6) for v in (*rng.uniform(-0.3, 0.3, 2), 0.02 + 0.01 * k, rng.uniform(-3, 3))]
                 for k, o in enumerate(objects)}
        frames.append({"t": t / 10, "poses": poses, "ee": [round(float(v), 6) for v in rng.uniform(-0.5, 0.5, 3)],
                       "grasped": "A" if t >= n // 2 else None, "progress": t / (n - 1),
                       "arm": [round(float(v), 6) for v in rng.uniform(-1, 1, JOINTS)]})
    pictures = (
        [np.full((48, 64, 3), (40 * seed + 20, 20 * t, 230 - 20 * t), np.uint8) for t in range(n)] if images else None
    )
    return Episode(f"move A past {objects[1]}", frames, 10.0, "A", objects[1], f"made-up {seed}", pictures,
                   10.0 if images else None)


@pytest.fixture()
def episodes() -> list[Episode]:
    return [made_up(["A", "B", "C"], 12, 1, True), made_up(["A", "D"], 8, 2, True)]


def test_the_state_holds_every_objects_pose_in_scene_order_and_the_joints(episodes, tmp_path):
    info = write_lerobot(episodes, tmp_path / "ds", video=False)
    names = info["features"]["observation.state"]["names"]
    objects = ["A", "B", "C", "D"]  # the first scene's order, then the block only the second one has
    assert names == STATE_NAMES + [f"{o}_{p}" for o in objects for p in ("x", "y", "z", "yaw")]
    assert info["features"]["observation.state"]["shape"] == [len(names)] == [10 + 16]
    data = pq.read_table(tmp_path / "ds/data/chunk-000/file-000.parquet").to_pydict()
    state = np.array(data["observation.state"], np.float64)
    lo = 0
    for ep in episodes:
        n = len(ep.frames)
        for k, o in enumerate(objects):
            got = state[lo:lo + n, 10 + 4 * k:14 + 4 * k]
            if o in ep.frames[0]["poses"]:
                np.testing.assert_allclose(got, [f["poses"][o] for f in ep.frames], atol=1e-6)
            else:
                assert np.isnan(got).all()  # absent from this scene: no made-up pose
        np.testing.assert_allclose(state[lo:lo + n, :3], [[f["poses"]["A"][i] for i in (0, 1, 3)] for f in ep.frames],
                                   atol=1e-6)  # the role-named values stay where they were
        np.testing.assert_allclose(np.array(data["observation.joints"][lo:lo + n]), [f["arm"] for f in ep.frames],
                                   atol=1e-6)
        lo += n
    stats = json.loads((tmp_path / "ds/meta/stats.json").read_text())["observation.state"]
    assert np.all(np.isfinite(stats["mean"])) and len(stats["mean"]) == 26  # NaNs left out of the statistics
    assert stats["max"][10 + 4 * 3] == pytest.approx(state[12:, 22].max())  # D's x: the second episode's alone


@pytest.mark.parametrize("pose", [[0.1, 0.2, 0.02], [0.1, 0.2, 0.02, float("nan")], "C"])
def test_every_objects_pose_is_checked_before_anything_is_written(pose):
    """The state now holds every block: a third block's broken pose is one line, not a ragged array."""
    frames = made_up(["A", "B", "C"], 3, 1, False).frames
    frames[1]["poses"]["C"] = pose
    with pytest.raises(PathError, match="poses must be|malformed frame"):
        check_frames(frames, "A", "B", "trajectory.json")


def test_the_files_follow_lerobots_v3_layout(episodes, tmp_path):
    """What LeRobot 0.4's ``LeRobotDatasetMetadata`` and ``LeRobotDataset`` read (lerobot/datasets/utils.py,
    lerobot_dataset.py): info.json's keys and path templates, one parquet column per non-video feature of
    its shape, the episodes' frame and video ranges, the statistics of every feature."""
    out = tmp_path / "ds"
    info = write_lerobot(episodes, out)
    assert info["codebase_version"] == "v3.0" and info["fps"] == 10
    for key in ("robot_type", "total_episodes", "total_frames", "total_tasks", "chunks_size", "data_files_size_in_mb",
                "video_files_size_in_mb", "fps", "splits", "data_path", "video_path", "features"):
        assert key in info, key
    assert info["data_path"] == "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
    assert info["video_path"] == "videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4"
    features = info["features"]
    for key in ("timestamp", "frame_index", "episode_index", "index", "task_index"):  # LeRobot's DEFAULT_FEATURES
        assert features[key]["shape"] == [1]
    video = features[VIDEO_KEY]
    assert video["dtype"] == "video" and video["shape"] == [48, 64, 3]
    assert video["names"] == ["height", "width", "channels"] and video["info"]["video.fps"] == 10

    table = pq.read_table(out / info["data_path"].format(chunk_index=0, file_index=0))
    columns = {k for k, f in features.items() if f["dtype"] != "video"}
    assert set(table.column_names) == columns
    arrow = {"float32": pa.float32(), "int64": pa.int64()}
    for k in columns:
        typ = table.schema.field(k).type
        shape, dtype = features[k]["shape"], arrow[features[k]["dtype"]]
        if pa.types.is_fixed_size_list(typ):  # datasets.Sequence(length=n), LeRobot's vectors
            assert [typ.list_size] == shape and typ.value_type == dtype, k
        else:
            assert shape == [1] and typ == dtype, k
    assert features["action"]["names"] == ACTION_NAMES
    assert table.num_rows == info["total_frames"] == 20

    eps = pq.read_table(out / "meta/episodes/chunk-000/file-000.parquet").to_pylist()
    assert [e["episode_index"] for e in eps] == [0, 1] and [e["length"] for e in eps] == [12, 8]
    assert [(e["dataset_from_index"], e["dataset_to_index"]) for e in eps] == [(0, 12), (12, 20)]
    episode_index = table.column("episode_index").to_pylist()
    assert episode_index == [0] * 12 + [1] * 8 and table.column("index").to_pylist() == list(range(20))
    assert table.column("frame_index").to_pylist() == list(range(12)) + list(range(8))
    for e in eps:
        assert e[f"videos/{VIDEO_KEY}/from_timestamp"] == pytest.approx(e["dataset_from_index"] / 10)
        assert e[f"videos/{VIDEO_KEY}/to_timestamp"] == pytest.approx(e["dataset_to_index"] / 10)
        assert e[f"videos/{VIDEO_KEY}/chunk_index"] == 0 and e[f"videos/{VIDEO_KEY}/file_index"] == 0
        assert e["data/chunk_index"] == 0 and e["meta/episodes/chunk_index"] == 0
    assert (out / info["video_path"].format(video_key=VIDEO_KEY, chunk_index=0, file_index=0)).is_file()
    stats = json.loads((out / "meta/stats.json").read_text())
    assert set(stats) == set(features) - {"timestamp", "frame_index", "episode_index", "index", "task_index"}
    for k, st in stats.items():
        for s in ("min", "max", "mean", "std", "count"):
            assert s in st, (k, s)
            assert f"stats/{k}/{s}" in eps[0], (k, s)  # per-episode statistics, as LeRobot aggregates them


LOADER = textwrap.dedent("""
    import json, sys
    from lerobot.datasets.lerobot_dataset import LeRobotDataset

    ds = LeRobotDataset("local/l2p-export", root=sys.argv[1])
    out = {"len": len(ds), "episodes": ds.num_episodes, "fps": ds.fps, "cameras": ds.meta.camera_keys,
           "names": ds.meta.features["observation.state"]["names"], "items": []}
    for i in (0, 11, 12, len(ds) - 1):
        item = ds[i]
        out["items"].append({k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in item.items()})
    print(json.dumps(out))
""")


def lerobot_python() -> str | None:
    """A Python that imports lerobot: this one, or ``L2P_LEROBOT_PYTHON``'s."""
    for python in (sys.executable, os.environ.get("L2P_LEROBOT_PYTHON")):
        if python and subprocess.run([python, "-c", "import lerobot.datasets.lerobot_dataset"],
                                     capture_output=True, timeout=300).returncode == 0:
            return python
    return None


@pytest.mark.slow
def test_lerobots_own_dataset_class_loads_the_export(episodes, tmp_path):
    python = lerobot_python()
    if python is None:
        pytest.skip("lerobot is not installed: it pins torch < 2.11 and cannot join this environment's torch; "
                    "set L2P_LEROBOT_PYTHON to a Python of a separate virtual environment with lerobot")
    write_lerobot(episodes, tmp_path / "ds")
    env = os.environ | {"HF_HOME": str(tmp_path / "hf"), "HF_HUB_OFFLINE": "1", "HF_DATASETS_OFFLINE": "1"}
    env.pop("PYTHONPATH", None)  # LeRobot's Python reads the files only, never this project's code
    r = subprocess.run([python, "-c", LOADER, str(tmp_path / "ds")], capture_output=True, text=True, env=env,
                       timeout=600, cwd=tmp_path)
    assert r.returncode == 0, r.stderr[-3000:]
    got = json.loads(r.stdout.strip().splitlines()[-1])
    assert got["len"] == 20 and got["episodes"] == 2 and got["fps"] == 10 and got["cameras"] == [VIDEO_KEY]
    assert got["names"][10:14] == ["A_x", "A_y", "A_z", "A_yaw"] and len(got["names"]) == 26
    for item, (ep, t) in zip(got["items"], ((0, 0), (0, 11), (1, 0), (1, 7)), strict=True):
        source = episodes[ep]
        frame = source.frames[t]
        assert item["episode_index"] == ep and item["frame_index"] == t and item["task"] == source.task
        state = np.array(item["observation.state"], np.float64)
        np.testing.assert_allclose(state[10:14], frame["poses"]["A"], atol=1e-6)
        np.testing.assert_allclose(item["observation.joints"], frame["arm"], atol=1e-6)
        assert np.isnan(state[18:22]).all() == (ep == 1)  # C: only in the first scene
        image = np.array(item[VIDEO_KEY])  # (3, H, W) in [0, 1], decoded by LeRobot from the video
        assert image.shape == (3, 48, 64)
        want = source.images[t].astype(float).mean((0, 1)) / 255
        np.testing.assert_allclose(image.mean((1, 2)), want, atol=0.03)  # lossy, but this frame's colour
