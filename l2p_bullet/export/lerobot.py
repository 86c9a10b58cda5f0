"""Write episodes as a LeRobot v3.0 dataset, with pyarrow and imageio-ffmpeg, without depending on lerobot.

Layout (LeRobotDataset v3.0: many episodes per file, episode boundaries in the metadata)::

    OUT/meta/info.json                              schema, fps, path templates, counts
    OUT/meta/stats.json                             per-feature min/max/mean/std/count
    OUT/meta/tasks.parquet                          task (the sentence) -> task_index
    OUT/meta/episodes/chunk-000/file-000.parquet    per episode: tasks, length, frame range, video range
    OUT/data/chunk-000/file-000.parquet             one row per frame
    OUT/videos/observation.images.front/chunk-000/file-000.mp4   every episode's frames, concatenated

Per frame: ``observation.state`` (mover x, y, yaw; anchor x, y, yaw; end effector x, y, z; grasped; then
every object's x, y, z, yaw in the scene's order, named ``<object>_x`` ... in info.json: a chain's other
blocks too), ``observation.joints`` (the arm's movable joints, named as the arm names them),
``observation.progress`` (the action's learned progress), ``action`` (the end effector's position and the
grasp at the next frame: where the arm was sent; the last frame repeats itself), the camera image when
the runs were rendered, and LeRobot's ``timestamp``, ``frame_index``, ``episode_index``, ``index``,
``task_index``. Metres and radians in the scene frame. Episodes from scenes with different objects share
one state layout (every object named in any of them, in order of appearance); an object an episode's
scene lacks is NaN there, not a made-up pose. With images the data is sampled at the video's
rate (15 fps by default: every second 30-fps trajectory frame, each matching one rendered image); without, at 30 fps.

``tasks.parquet`` carries pandas' metadata so that ``pandas.read_parquet`` gives LeRobot's table
(index ``task``, column ``task_index``); it is written by pyarrow alone.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np

from ..embodiment import arm_measure
from ..errors import MissingExtraError, PathError
from ..plugins import arms as arm_plugins
from .episodes import Episode

CODEBASE_VERSION = "v3.0"
VIDEO_KEY = "observation.images.front"
DATA_PATH = "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
VIDEO_PATH = "videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4"
EPISODES_PATH = "meta/episodes/chunk-000/file-000.parquet"
STATE_NAMES = ["mover_x", "mover_y", "mover_yaw", "anchor_x", "anchor_y", "anchor_yaw", "ee_x", "ee_y", "ee_z",
               "grasped"]
"""The state's first values, by role; every object's pose follows (:func:`state_names`)."""
POSE_NAMES = ("x", "y", "z", "yaw")
ACTION_NAMES = ["ee_x", "ee_y", "ee_z", "grasp"]


def _pyarrow():
    try:
        # lazy: pyarrow is an optional extra (l2p-bullet[export])
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        raise MissingExtraError("pyarrow", "export", "export --format lerobot") from None
    return pa, pq


def object_names(eps: Iterable[Episode]) -> list[str]:
    """Every object the episodes' frames pose, in the scene's order (the order trajectory.json records them,
    ``World.poses``); objects first met in a later episode follow."""
    return list(dict.fromkeys(name for ep in eps for name in ep.frames[0]["poses"]))


def state_names(objects: list[str]) -> list[str]:
    """``observation.state``'s names: :data:`STATE_NAMES`, then each object's x, y, z, yaw."""
    return STATE_NAMES + [f"{o}_{p}" for o in objects for p in POSE_NAMES]


def episode_arrays(ep: Episode, step: int, objects: list[str] | None = None) -> dict[str, np.ndarray]:
    """State (T, 10 + 4 per object), action (T,4), progress (T,), joints (T,J) of every ``step``-th frame.

    ``objects``: whose poses follow the first ten values (default: the episode's own); one the frame lacks
    is NaN."""
    frames = ep.frames[::step]
    objects = object_names([ep]) if objects is None else objects
    absent, width = [np.nan] * len(POSE_NAMES), len(STATE_NAMES) + len(POSE_NAMES) * len(objects)
    state = np.array([[*_xyyaw(f, ep.mover), *_xyyaw(f, ep.anchor), *f["ee"], float(f["grasped"] is not None),
                       *(v for o in objects for v in f["poses"].get(o, absent))]
                      for f in frames], np.float32).reshape(len(frames), width)
    action = np.concatenate([state[1:, 6:10], state[-1:, 6:10]]) if len(state) else np.zeros((0, 4), np.float32)
    progress = np.array([np.nan if f.get("progress") is None else f["progress"] for f in frames], np.float32)
    joints = np.array([f.get("arm") or [] for f in frames], np.float32)
    return {"state": state, "action": action, "progress": progress, "joints": joints}


def _xyyaw(frame: dict, name: str) -> list[float]:
    p = frame["poses"][name]
    return [p[0], p[1], p[3]]


def steps(episodes: list[Episode], video: bool) -> int:
    """How many times :func:`write_lerobot` calls its ``tick``: once per episode, again per episode encoded
    into the video, and once for the dataset's statistics (over every image: seconds on 2 cores)."""
    return len(episodes) * (2 if video else 1) + 1


def write_lerobot(episodes: Iterable[Episode], out: str | Path, *, video: bool | None = None,
                  tick: Callable[[], None] | None = None) -> dict:
    """Write ``episodes`` into the folder ``out`` as a LeRobot v3.0 dataset; returns info.json's content.

    ``out`` is the caller's: ``l2p-bullet export`` claims it with :func:`l2p_bullet.core.runfolder.run_folder`
    (never overwriting anything but a previous export of ours), files already in it are left alone.

    ``video`` None: images are written when every episode has them; True: they must; False: never.
    ``tick`` is called :func:`steps` times (the command's progress bar).
    """
    tick = tick or (lambda: None)
    pa, pq = _pyarrow()
    eps = list(episodes)
    if not eps:
        raise PathError("nothing to export: no run folders and no demonstrations")
    out = Path(out)
    with_images = [e.images is not None for e in eps]
    if video is None:
        video = all(with_images)
    if video and not all(with_images):
        missing = [e.source for e in eps if e.images is None][:3]
        raise PathError(f"some runs were not rendered ({', '.join(missing)}...): render them, or export --no-video")
    fps_values = {e.image_fps for e in eps} if video else {e.fps for e in eps}
    if len(fps_values) != 1:
        raise PathError(f"the episodes were recorded at different rates ({sorted(fps_values)})")
    fps = float(fps_values.pop())

    arm, names = _arm_joints(eps)
    objects = object_names(eps)
    snames = state_names(objects)
    tasks = list(dict.fromkeys(e.task for e in eps))
    columns: dict[str, list] = {k: [] for k in ("observation.state", "observation.progress", "action", "timestamp",
                                                "frame_index", "episode_index", "index", "task_index",
                                                "observation.joints")}
    episodes_meta: list[dict] = []
    all_images: list[np.ndarray] = []
    total = 0
    for i, ep in enumerate(eps):
        step = max(1, round(ep.fps / fps))
        arr = episode_arrays(ep, step, objects)
        n = len(arr["state"])
        if video:
            n = min(n, len(ep.images))
            all_images += ep.images[:n]
        if arr["joints"].shape[1:] != (len(names),):
            raise PathError(f"{ep.source}: its frames record {arr['joints'].shape[1:]} joints, not the {len(names)} "
                            f'of the arm "{arm.name}"')
        for k, v in (("observation.state", arr["state"][:n]), ("action", arr["action"][:n]),
                     ("observation.joints", arr["joints"][:n])):
            columns[k] += list(v)
        columns["observation.progress"] += arr["progress"][:n].tolist()
        columns["timestamp"] += (np.arange(n, dtype=np.float32) / np.float32(fps)).tolist()
        columns["frame_index"] += list(range(n))
        columns["episode_index"] += [i] * n
        columns["index"] += list(range(total, total + n))
        columns["task_index"] += [tasks.index(ep.task)] * n
        meta = {"episode_index": i, "tasks": [ep.task], "length": n, "data/chunk_index": 0, "data/file_index": 0,
                "dataset_from_index": total, "dataset_to_index": total + n,
                "meta/episodes/chunk_index": 0, "meta/episodes/file_index": 0, "l2p/source": ep.source,
                "l2p/extra": json.dumps(ep.extra, default=str)}
        if video:
            meta |= {
                f"videos/{VIDEO_KEY}/chunk_index": 0,
                f"videos/{VIDEO_KEY}/file_index": 0,
                f"videos/{VIDEO_KEY}/from_timestamp": total / fps,
                f"videos/{VIDEO_KEY}/to_timestamp": (total + n) / fps,
            }
        meta |= {f"stats/{k}/{s}": v for k, st in _stats(arr, n, ep.images[:n] if video else None).items()
                 for s, v in st.items()}
        episodes_meta.append(meta)
        total += n
        tick()

    data_file = out / DATA_PATH.format(chunk_index=0, file_index=0)
    data_file.parent.mkdir(parents=True, exist_ok=True)
    table = pa.table({
        "observation.state": _fixed(pa, columns["observation.state"], len(snames)),
        "observation.progress": pa.array(columns["observation.progress"], pa.float32()),
        "action": _fixed(pa, columns["action"], len(ACTION_NAMES)),
        "observation.joints": _fixed(pa, columns["observation.joints"], len(names)),
        "timestamp": pa.array(columns["timestamp"], pa.float32()),
        **{k: pa.array(columns[k], pa.int64()) for k in ("frame_index", "episode_index", "index", "task_index")},
    })
    pq.write_table(table, data_file, compression="snappy")
    features = _features(video, all_images[0].shape if video else None, fps, snames)
    features["observation.joints"] = {"dtype": "float32", "shape": [len(names)], "names": names}
    if video:
        ends = {m["dataset_to_index"] for m in episodes_meta}
        _write_video(all_images, out / VIDEO_PATH.format(video_key=VIDEO_KEY, chunk_index=0, file_index=0), fps,
                     lambda done: tick() if done in ends else None)
    ep_file = out / EPISODES_PATH
    ep_file.parent.mkdir(parents=True, exist_ok=True)
    pq.write_table(pa.Table.from_pylist(episodes_meta), ep_file)
    _write_tasks(pa, pq, tasks, out / "meta" / "tasks.parquet")
    stats = _stats({"state": np.array(columns["observation.state"]), "action": np.array(columns["action"]),
                    "progress": np.array(columns["observation.progress"], np.float32),
                    "joints": np.array(columns["observation.joints"], np.float32).reshape(total, len(names))}, total,
                   all_images if video else None)
    (out / "meta" / "stats.json").write_text(json.dumps(stats, indent=1) + "\n")
    tick()
    info = {
        "codebase_version": CODEBASE_VERSION, "robot_type": arm_measure.robot_type(arm), "total_episodes": len(eps),
        "total_frames": total, "total_tasks": len(tasks), "chunks_size": 1000, "data_files_size_in_mb": 100,
        "video_files_size_in_mb": 200, "fps": int(round(fps)), "splits": {"train": f"0:{len(eps)}"},
        "data_path": DATA_PATH, "video_path": VIDEO_PATH if video else None, "features": features,
    }
    (out / "meta" / "info.json").write_text(json.dumps(info, indent=4) + "\n")
    return info


def _arm_joints(eps: list[Episode]):
    """The one arm every episode was performed by, and its movable joints' names (each frame's ``arm``)."""
    arms = sorted({e.arm for e in eps})
    if len(arms) > 1:
        raise PathError(f"the episodes were performed by different arms ({', '.join(arms)}): a LeRobot dataset has "
                        "one robot, export each arm's runs on their own")
    arm = arm_plugins.get(arms[0])
    return arm, arm_measure.joint_names(arm)


def _fixed(pa, rows: list[np.ndarray], n: int):
    """A fixed-size list column (what ``datasets.Sequence(length=n)`` reads as)."""
    flat = np.asarray(rows, np.float32).reshape(-1)
    return pa.FixedSizeListArray.from_arrays(pa.array(flat, pa.float32()), n)


def _features(video: bool, shape: tuple | None, fps: float, snames: list[str]) -> dict:
    f = {
        "observation.state": {"dtype": "float32", "shape": [len(snames)], "names": snames},
        "observation.progress": {"dtype": "float32", "shape": [1], "names": None},
        "action": {"dtype": "float32", "shape": [len(ACTION_NAMES)], "names": ACTION_NAMES},
    }
    if video:
        h, w, c = shape
        f[VIDEO_KEY] = {"dtype": "video", "shape": [h, w, c], "names": ["height", "width", "channels"],
                        "info": {"video.height": h, "video.width": w, "video.codec": "h264", "video.pix_fmt": "yuv420p",
                                 "video.is_depth_map": False, "video.fps": int(round(fps)), "video.channels": c,
                                 "has_audio": False}}
    for k, dtype in (("timestamp", "float32"), ("frame_index", "int64"), ("episode_index", "int64"),
                     ("index", "int64"), ("task_index", "int64")):
        f[k] = {"dtype": dtype, "shape": [1], "names": None}
    return f


def _stats(arr: dict[str, np.ndarray], n: int, images: list[np.ndarray] | None) -> dict[str, dict]:
    """LeRobot's per-feature statistics (min, max, mean, std, count) as lists; images per channel in [0, 1]."""
    def one(x: np.ndarray) -> dict:
        # per value, over the frames that have it: an object absent from some scenes (NaN there) and the
        # progress of a run without a learned one must not blank the statistics of the rest
        x = np.asarray(x, np.float64)[:n].reshape(n, -1)
        ok = ~np.isnan(x)
        x = np.where(ok.any(0), x, 0.0)  # a value no frame has: zeros, as LeRobot's own empty statistics
        with np.errstate(invalid="ignore"):
            return {"min": np.nanmin(x, 0).tolist(), "max": np.nanmax(x, 0).tolist(), "mean": np.nanmean(x, 0).tolist(),
                    "std": np.nanstd(x, 0).tolist(), "count": [int(ok.any(1).sum())]}

    out = {"observation.state": one(arr["state"]), "action": one(arr["action"]),
           "observation.progress": one(arr["progress"]), "observation.joints": one(arr["joints"])}
    if images:
        px = np.stack(images[:: max(1, len(images) // 100)]).astype(np.float64) / 255.0  # (K,H,W,3), sampled
        chan = px.reshape(-1, px.shape[-1])
        out[VIDEO_KEY] = {s: [[[float(v)]] for v in f(chan)] for s, f in
                          (("min", lambda c: c.min(0)), ("max", lambda c: c.max(0)), ("mean", lambda c: c.mean(0)),
                           ("std", lambda c: c.std(0)))} | {"count": [len(images)]}
    return out


def _write_video(images: list[np.ndarray], path: Path, fps: float, written: Callable[[int], None]) -> None:
    import imageio.v2 as imageio

    path.parent.mkdir(parents=True, exist_ok=True)
    with imageio.get_writer(path, fps=fps, codec="libx264", quality=8, pixelformat="yuv420p",
                            macro_block_size=8, ffmpeg_log_level="error") as writer:
        for i, img in enumerate(images, start=1):
            writer.append_data(img)
            written(i)


def _write_tasks(pa, pq, tasks: list[str], path: Path) -> None:
    """tasks.parquet as ``pandas.DataFrame({"task_index": ...}, index=Index(tasks, name="task")).to_parquet``."""
    table = pa.table({"task_index": pa.array(range(len(tasks)), pa.int64()), "task": pa.array(tasks, pa.string())})
    pandas_meta = {
        "index_columns": ["task"], "column_indexes": [
            {"name": None, "field_name": None, "pandas_type": "unicode", "numpy_type": "object", "metadata": None}],
        "columns": [
            {"name": "task_index", "field_name": "task_index", "pandas_type": "int64", "numpy_type": "int64",
             "metadata": None},
            {"name": "task", "field_name": "task", "pandas_type": "unicode", "numpy_type": "object", "metadata": None}],
        "creator": {"library": "pyarrow", "version": pa.__version__}, "pandas_version": "2.2.0",
    }
    table = table.replace_schema_metadata({b"pandas": json.dumps(pandas_meta).encode()})
    pq.write_table(table, path)

