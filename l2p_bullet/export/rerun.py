"""Run folders as a Rerun recording (``export RUNS... --format rerun OUT.rrd``): a 3-D replay to scrub.

Researchers already use the Rerun viewer for robot data; one ``.rrd`` file opens there (``rerun OUT.rrd``)
with, per run, under ``/<run name>/``:

- ``world/arm/<link>/<k>``: the arm's visual meshes (Panda ``.obj`` files, in ``mesh``) posed frame by frame, from
  the joints trajectory.json records per frame (``arm``; runs recorded before it have no arm);
- ``world/objects/<name>``: each block as a box of its size and colour, posed frame by frame;
- ``world/plan``: the 2-D plan (plan.json's path) as a line strip on the table top;
- ``progress``: the learned progress per frame, a scalar series;
- ``camera/image``: the rendered frames (frames/NNNN.png) at the video's rate;
- ``sentence`` (a text document) and ``segments`` (a text log entry at each clause's first frame, for a
  chain's trajectory.json ``segments``).

Everything is on one timeline, ``time`` (seconds of simulated time from the run's start). Coordinates
are the scene file's: metres, z up from the table top. The poses come from the files, the arm's link
poses from the simulator's forward kinematics at the recorded joints (the arm's meshes are pybullet's,
posed by the facade; nothing is simulated). ``rerun-sdk`` is the optional extra ``l2p-bullet[rerun]``.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from ..core.contracts import frame_rate, load_json_file
from ..errors import DataError, PathError

TIMELINE = "time"
TABLE_RGBA = (181, 148, 108, 255)


def _rerun():
    try:
        import rerun as rr
    except ImportError:
        raise PathError("--format rerun needs the rerun-sdk package: pip install 'l2p-bullet[rerun]'") from None
    return rr


def entity_name(run: Path) -> str:
    """The run's entity root: its folder name, with only characters an entity path keeps."""
    return re.sub(r"[^A-Za-z0-9_.-]", "_", run.name) or "run"


def write_rerun(runs: list[Path], out: Path) -> dict:
    """Write ``runs`` (run folders) into the recording ``out``; returns what was written."""
    rr = _rerun()
    for run in runs:  # every run checked before the recording is opened: a refused one leaves no partial .rrd
        check_run(run)
    rec = rr.RecordingStream("l2p_bullet", recording_id=f"l2p-export-{out.stem}")
    rec.save(str(out))
    names: list[str] = []
    try:
        for run in runs:
            name = entity_name(run)
            while name in names:
                name += "_"
            names.append(name)
            log_run(rr, rec, run, name)
    finally:
        rec.flush()
        rec.disconnect()
    return {"out": str(out), "runs": len(runs), "entities": [f"/{n}" for n in names]}


def _read(path: Path) -> dict:
    # load_json_file: bounded (a file linked to /dev/zero) and one line for JSON nested past the recursion limit
    doc = load_json_file(path, DataError)
    if not isinstance(doc, dict):
        raise DataError(f"{path}: not a JSON object")
    return doc


def check_run(run: Path) -> None:
    """What a crafted run folder may get wrong, said in one line before anything is written: its frames
    (what an episode export reads), its segments (1 to 10, contiguous) and the rate of its images."""
    from ..chain.segments import segments_of  # lazy, as episodes: they load the planner and the simulator
    from .episodes import check_frames

    source = f"{run}/trajectory.json"
    traj = _read(run / "trajectory.json")
    check_frames(traj.get("frames"), traj.get("mover"), traj.get("anchor"), source)
    if traj.get("segments") is not None:
        segments_of(traj, source)
    if (run / "frames").is_dir() and (run / "summary.json").is_file():
        render = _read(run / "summary.json").get("render")
        if isinstance(render, dict) and render.get("fps") is not None:
            frame_rate(render["fps"], f"{run}/summary.json", "render.fps")


def log_run(rr, rec, run: Path, name: str) -> None:
    """Log one run folder under ``/<name>/``."""
    traj = _read(run / "trajectory.json")
    frames = traj.get("frames") or []
    if not frames:
        raise DataError(f"{run / 'trajectory.json'}: no frames")
    t = np.array([float(f["t"]) for f in frames])
    time = [rr.TimeColumn(TIMELINE, duration=t)]
    root = f"/{name}"
    rec.log(root, rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    rec.log(f"{root}/sentence", rr.TextDocument(str(traj.get("sentence") or "")), static=True)
    rec.log(f"{root}/world/table", rr.Boxes3D(centers=[[0, 0, -0.01]], half_sizes=[[0.4, 0.4, 0.01]],
                                               colors=[TABLE_RGBA], fill_mode="solid"), static=True)
    objects = traj.get("objects") or {}
    for obj, info in objects.items():
        size = float(info.get("size", 0.05))
        rgba = _rgba(info.get("shade") or info.get("color"))
        path = f"{root}/world/objects/{entity_name(Path(obj))}"
        rec.log(path, rr.Boxes3D(half_sizes=[[size / 2] * 3], colors=[rgba], fill_mode="solid"), static=True)
        poses = np.array([f["poses"][obj] for f in frames], float)
        quats = np.array([_yaw_quat(y) for y in poses[:, 3]])
        rec.send_columns(path, indexes=time, columns=rr.Transform3D.columns(translation=poses[:, :3], quaternion=quats))
    progress = [f.get("progress") for f in frames]
    keep = np.array([p is not None for p in progress])
    if keep.any():
        rec.send_columns(f"{root}/progress", indexes=[rr.TimeColumn(TIMELINE, duration=t[keep])],
                         columns=rr.Scalars.columns(scalars=np.array([p for p in progress if p is not None], float)))
    _log_plan(rr, rec, run, root)
    _log_arm(rr, rec, traj, frames, time, root)
    _log_images(rr, rec, run, root)
    for seg in traj.get("segments") or []:
        if isinstance(seg, dict) and isinstance(seg.get("first_frame"), int) and 0 <= seg["first_frame"] < len(t):
            rec.set_time(TIMELINE, duration=float(t[seg["first_frame"]]))
            text = seg.get("text") or seg.get("sentence") or ""
            rec.log(f"{root}/segments", rr.TextLog(f"clause {seg.get('clause', '?')}: {text}"))
    rec.reset_time()


def _log_plan(rr, rec, run: Path, root: str) -> None:
    if not (run / "plan.json").is_file():
        return
    plan = _read(run / "plan.json")
    path = np.asarray(plan.get("path") or [], float).reshape(-1, 3) if plan.get("path") else np.empty((0, 3))
    if len(path) >= 2:
        strip = np.column_stack([path[:, :2], np.full(len(path), 0.001)])
        rec.log(f"{root}/world/plan", rr.LineStrips3D([strip], colors=[(40, 120, 255, 255)], radii=[0.002]),
                static=True)


def _log_arm(rr, rec, traj: dict, frames: list[dict], time: list, root: str) -> None:
    """The arm's visual meshes, posed at each frame's recorded joints (forward kinematics in a world of
    its own; runs recorded without the arm's joints have no arm)."""
    arm = traj.get("arm")
    if not isinstance(arm, dict) or not all(isinstance(f.get("arm"), list) for f in frames):
        return
    from ..embodiment.sim.robot import ARM
    from ..embodiment.sim.world import World

    joints = [int(j) for j in arm.get("joints", [])]
    q = np.array([f["arm"] for f in frames], float)
    if q.shape[1:] != (len(joints),):
        raise DataError("trajectory.json: every frame's arm must have one value per joint of the arm")
    from ..plugins import arms as arm_plugins

    with World(_scene(traj, frames[0]), arm=arm_plugins.get(str(arm.get("name") or "panda")), visuals=True) as world:
        sim = world.sim
        shapes = [s for s in sim.visual_shapes(ARM) if s["geometry"] == "mesh" and Path(s["file"]).is_file()]
        pos = np.zeros((len(shapes), len(frames), 3))
        orn = np.zeros((len(shapes), len(frames), 4))
        for i, values in enumerate(q):
            sim.reset_joints(ARM, joints, values)
            for k, s in enumerate(shapes):
                p, o = sim.compose(sim.com_pose(ARM, s["link"]), (s["pos"], s["orn"]))
                pos[k, i], orn[k, i] = p, o
    for k, s in enumerate(shapes):
        path = f"{root}/world/arm/link{s['link'] + 1}/{k}"  # link -1 is the base: "link0", as the meshes say
        rgba = [int(round(255 * max(0.0, min(1.0, c)))) for c in s["rgba"]]
        rec.log(f"{path}/mesh", rr.Asset3D(path=s["file"], albedo_factor=rgba), static=True)
        if any(abs(d - 1.0) > 1e-9 for d in s["dims"]):  # the mesh's own scale, below the posed link frame
            rec.log(f"{path}/mesh", rr.Transform3D(scale=s["dims"]), static=True)
        rec.send_columns(path, indexes=time, columns=rr.Transform3D.columns(translation=pos[k], quaternion=orn[k]))


def _log_images(rr, rec, run: Path, root: str) -> None:
    folder = run / "frames"
    pngs = sorted(folder.glob("[0-9][0-9][0-9][0-9].png")) if folder.is_dir() else []
    if not pngs:
        return
    summary = _read(run / "summary.json") if (run / "summary.json").is_file() else {}
    render = summary.get("render") if isinstance(summary.get("render"), dict) else {}
    fps = frame_rate(render["fps"], f"{run}/summary.json", "render.fps") if render.get("fps") is not None else 10.0
    for i, png in enumerate(pngs):
        rec.set_time(TIMELINE, duration=i / fps)
        rec.log(f"{root}/camera/image", rr.EncodedImage(path=png, media_type="image/png"))


def _scene(traj: dict, first: dict):
    """The scene of the run's first frame (the arm's world needs one; only the arm is read from it)."""
    from ..core.scene import COLORS, Scene, SceneObject

    objs = []
    for name, info in (traj.get("objects") or {}).items():
        x, y, _, yaw = first["poses"][name]
        colour = info.get("color") if info.get("color") in COLORS else "gray"
        objs.append(SceneObject(name, colour, float(info.get("size", 0.05)), (float(x), float(y)), float(yaw)))
    return Scene(objs)


def _rgba(colour: object) -> tuple[int, int, int, int]:
    """A trajectory's colour (its shade where it has one) as 8-bit RGBA; grey where it is no colour."""
    from ..core import colours

    r, g, b, a = colours.rgba("gray", colour if isinstance(colour, str) else None)
    return (round(255 * r), round(255 * g), round(255 * b), round(255 * a))


def _yaw_quat(yaw: float) -> tuple[float, float, float, float]:
    """Quaternion (x, y, z, w) of a turn ``yaw`` about +z."""
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))
