"""execute_path: a 2-D path of one block, executed by the arm in PyBullet and recorded.

This is the embodiment's one entry point (docs/INTERFACES.md): ``perform`` and ``replay`` both call it.
The path is checked before anything is simulated (inside the workspace, no collision with another
block, starts where the block is, reachable by the arm), so a bad path fails fast with a clear error.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core.geometry import polygons_overlap
from ..core.scene import Scene
from ..errors import PathError, ReachError
from . import motion
from .sim.camera import RenderSettings

START_TOLERANCE = 0.003  # m: a path must start where its block is
DEFAULT_RENDER = RenderSettings()


@dataclass
class Execution:
    """What happened. ``frames`` are trajectory.json's frames; distances in metres."""

    frames: list[dict]
    timings: dict[str, float]
    files: dict[str, Path]
    max_deviation_m: float  # the held block's largest distance from the planned path while sliding
    anchor_displacement_m: float  # the largest displacement of any block that was not held
    max_lift_m: float = 0.0  # how far the held block rose above resting on the table
    constraint_removed: bool = True
    duration_s: float = 0.0  # simulated time of the episode
    stats: dict = field(default_factory=dict)


def check_path(scene: Scene, mover: str, path: np.ndarray) -> np.ndarray:
    """Validate a mover path against the scene; return it cleaned (yaw unwrapped, repeats merged)."""
    obj = scene.get(mover)
    p = motion.clean_path(path)
    start_gap = float(np.hypot(*(p[0, :2] - np.array(obj.xy))))
    if start_gap > START_TOLERANCE:
        raise PathError(f'the path starts at ({p[0, 0]:.3f}, {p[0, 1]:.3f}) but block "{mover}" is at '
                        f"({obj.xy[0]:.3f}, {obj.xy[1]:.3f}), {start_gap * 1000:.0f} mm away")
    dense = np.concatenate(motion.slide_chunks(p, radius=0.0)) if len(p) > 1 else p
    inside = scene.workspace.contains(dense[:, :2])
    if not inside.all():
        k = int(np.argmin(inside))
        r = float(np.hypot(*(dense[k, :2] - np.array(scene.workspace.center))))
        raise PathError(f'the path of "{mover}" leaves the workspace at ({dense[k, 0]:.3f}, {dense[k, 1]:.3f}), '
                        f"{r:.3f} m from its centre (radius {scene.workspace.radius} m)")
    for other in scene.objects:
        if other.name == mover:
            continue
        fp = other.footprint()
        # Only poses whose bounding circles meet can overlap: test those (a few) exactly.
        reach = (obj.size + other.size) * np.sqrt(0.5)
        near = np.hypot(*(dense[:, :2] - np.array(other.xy)).T) < reach
        for pose in dense[near]:
            if polygons_overlap(obj.footprint(pose), fp):
                raise PathError(f'the path of "{mover}" runs into "{other.name}" at ({pose[0]:.3f}, {pose[1]:.3f})')
    return p


def execute_path(scene: Scene, mover: str, path: np.ndarray, *, out_dir: Path | None,
                 render: RenderSettings | None = DEFAULT_RENDER, seed: int = 0,
                 progress_fn: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
                 meta: dict | None = None, on_stage: Callable[[str], None] | None = None) -> Execution:
    """Engage ``mover``, slide it along ``path`` (N,3, scene frame), disengage, and record it all.

    ``out_dir`` None records nothing to disk (frames are still returned); ``render`` None renders
    nothing. ``seed`` is recorded only: the simulation is deterministic. ``on_stage`` is told each
    stage's name as it starts.
    """
    from .record import Recorder, write_summary
    from .sim.camera import Camera
    from .sim.primitives import Primitives
    from .sim.world import World

    meta = dict(meta or {})
    meta.setdefault("mover", mover)
    timings: dict[str, float] = {}
    clock = [time.perf_counter(), None]

    def stage(name: str) -> None:
        now = time.perf_counter()
        if clock[1] is not None:
            timings[clock[1]] = round(timings.get(clock[1], 0.0) + now - clock[0], 4)
        clock[0], clock[1] = now, name
        if on_stage is not None and name != "done":
            on_stage(name)

    stage("check")
    p = check_path(scene, mover, path)
    stage("setup")
    world = World(scene, visuals=render is not None, egl=render is not None and render.renderer == "egl")
    try:
        camera = Camera(world, render) if render is not None else None
        recorder = Recorder(world, camera)
        prims = Primitives(world, recorder)
        stage("reach")
        offset = _choose_grasp_yaw(prims, mover, p)
        recorder()
        rest = prims.pose.copy()
        stage("engage")
        prims.engage(mover, offset)
        stage("move")
        slide_from = len(recorder.frames)
        prims.move(p)
        slide_to = len(recorder.frames)
        stage("disengage")
        prims.disengage(rest)
        removed = world.client.getNumConstraints() == 0
        stage("record")
        files: dict[str, Path] = {}
        recorder.fill_progress(mover, meta.get("anchor"), progress_fn)
        deviation, lift, displaced = _honesty(recorder.frames, mover, p, slide_from, slide_to, world.sizes)
        stats = {
            "physics_steps": world.steps,
            "ik_solves": prims.ik_solves,
            "rendered_frames": len(recorder.images),
            "render_s": round(recorder.render_s, 4),
            "max_lateral_acc": round(max((t.max_lateral_acc for _, t in prims.timed), default=0.0), 4),
        }
        if out_dir is not None:
            out_dir = Path(out_dir)
            files["trajectory"] = out_dir / "trajectory.json"
            recorder.write_trajectory(files["trajectory"], meta, world.sizes)
            if camera is not None:
                files |= recorder.write_images(out_dir, render.video, meta.get("sentence"))
        stage("done")
        execution = Execution(recorder.frames, timings, files, deviation, displaced, lift, removed,
                              world.time, stats)
        if out_dir is not None:
            files["summary"] = out_dir / "summary.json"
            write_summary(files["summary"], _summary(execution, meta, seed, render))
        return execution
    finally:
        world.robot.close()
        world.close()


def _choose_grasp_yaw(prims, mover: str, path: np.ndarray) -> float:
    """The grasp yaw (a multiple of 90 deg relative to the block) whose whole slide the arm reaches.

    Candidates come best first from a wrist model; each is checked by solving the slide's IK at the
    control rate before anything moves. ReachError (the best candidate's) if none works.
    """
    base = (prims.robot.base_xyz[0], prims.robot.base_xyz[1])
    first_error = None
    for offset in motion.grasp_yaw_offsets(path, base)[:3]:
        try:
            _check_reach(prims, mover, path, offset)
            return offset
        except ReachError as e:
            first_error = first_error or e
    raise first_error


def _check_reach(prims, mover: str, path: np.ndarray, offset: float) -> None:
    """Approach, descent and slide IK, as the arm will run them (ReachError), before anything moves."""
    prims.check_engage_and_slide(mover, path, offset)


def _honesty(frames, mover, path, lo, hi, sizes) -> tuple[float, float, float]:
    """Deviation of the held block from the planned path (while sliding), its lift, others' motion."""
    xy = path[:, :2]
    slide = frames[lo:hi]
    deviation = 0.0
    if slide:
        pts = np.array([f["poses"][mover][:2] for f in slide])
        deviation = float(motion.polyline_distance(pts, xy).max())
    lift = max(f["poses"][mover][2] for f in frames) - sizes[mover] / 2
    displaced = 0.0
    for name in sizes:
        if name == mover:
            continue
        start = np.array(frames[0]["poses"][name][:2])
        moved = max(float(np.hypot(*(np.array(f["poses"][name][:2]) - start))) for f in frames)
        displaced = max(displaced, moved)
    return deviation, float(lift), displaced


def _summary(ex: Execution, meta: dict, seed: int, render: RenderSettings | None) -> dict:
    from .record import versions

    return {
        "schema": 1,
        **{k: meta.get(k) for k in ("sentence", "action", "mover", "anchor")},
        "seed": seed,
        "timings_s": ex.timings,
        "simulated_s": round(ex.duration_s, 4),
        "execution": {
            "max_deviation_m": round(ex.max_deviation_m, 6),
            "anchor_displacement_m": round(ex.anchor_displacement_m, 6),
            "max_lift_m": round(ex.max_lift_m, 6),
            "constraint_removed": ex.constraint_removed,
            **ex.stats,
        },
        "render": None if render is None else {"width": render.width, "height": render.height,
                                               "fps": render.fps, "renderer": render.renderer},
        "files": {k: v.name for k, v in ex.files.items()},
        "versions": versions(),
        **{k: v for k, v in meta.items() if k not in ("sentence", "action", "mover", "anchor")},
    }
