"""execute_path: a 2-D path of one block, executed by the arm in PyBullet and recorded.

This is the embodiment's one entry point (docs/INTERFACES.md): ``perform`` and ``replay`` both call it.
The path is checked before anything is simulated (inside the workspace, no collision with another
block, starts where the block is, reachable by the arm), so a bad path fails fast with a clear error.
The checks are in ``path_checks.py`` and what an execution leaves (its record, honesty measures and summary)
in ``outcome.py``; their names are re-exported here, where every caller reads them.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..arms import PANDA, ArmSpec, reach
from ..core.contracts import approach_end_frame, trajectory_poses
from ..core.runfolder import write_summary
from ..core.scene import Scene
from ..core.timing import StageClock
from ..errors import ExecutionError, ReachError
from ..manners.spec import MannerSpec
from . import motion, smoothing
from .manners import carry_lift, manner_of, tall_pace
from .outcome import Execution, execution_summary, honesty, render_info
from .path_checks import MAX_YAW_RAD, START_TOLERANCE, check_for, check_path, check_waypoints, checked_path
from .record import Recorder
from .render import Film
from .sim.camera import RenderSettings, framed_for
from .sim.primitives import Primitives
from .sim.world import World

if TYPE_CHECKING:  # the simulator loads only when a path is executed
    from .sim.world import World

__all__ = [  # execute.py's own names and those of path_checks.py and outcome.py, which callers read from here
    "DEFAULT_RENDER", "MAX_YAW_RAD", "START_TOLERANCE", "Execution", "act", "arm_primitives", "check_for",
    "check_path", "check_waypoints", "checked_path", "choose_grasp_yaw", "execute_path", "execution_summary",
    "grasp_candidates", "honesty", "manner_of", "render_info",
]

DEFAULT_RENDER = RenderSettings()


def execute_path(scene: Scene, mover: str, path: np.ndarray, *, out_dir: Path | None,
                 render: RenderSettings | None = DEFAULT_RENDER, seed: int = 0,
                 progress_fn: Callable[..., np.ndarray] | None = None,
                 meta: dict | None = None, on_stage: Callable[[str], None] | None = None,
                 world: World | None = None, summary: bool = True, arm: ArmSpec | None = None,
                 manner: MannerSpec | str | None = None, approach_to: np.ndarray | None = None,
                 pace: str | None = None) -> Execution:
    """Engage ``mover``, slide it along ``path`` (N,3, scene frame), disengage, and record it all.

    ``out_dir`` None records nothing to disk (frames are still returned); ``render`` None renders
    nothing. ``seed`` is recorded only: the simulation is deterministic. ``on_stage`` is told each
    stage's name as it starts. ``world``: an open :class:`~.sim.world.World` to run in instead of a new
    one (a batch keeps one per process); it is reset to ``scene`` first (the run records exactly what
    it would in a new world) and left open. A world made here is closed here. ``summary`` False leaves
    summary.json to the caller, who starts from :func:`execution_summary` (``perform`` adds its own fields
    and writes the file once). ``arm``: the arm to use (default: the world's, else the Panda). ``manner``
    (l2p_bullet/manners; None: slide) says how the block follows the
    path: slid, carried in the air or pushed (embodiment/manners.py); a run of any manner but slide records
    it (``manner`` in trajectory.json and summary.json, the gripper per frame), a slide's files are unchanged.
    ``approach_to``: where the plan's approach slide ends (plan.json's ``extra.approach.to``, "around" from
    afar): the learned progress is read from the frame the mover got there (trajectory.json's ``action_from``),
    as the planner scored the plan; None (every other plan): from the first frame. ``pace`` (the sentence's
    "slowly", "gently": smoothing.PACES; None: normal) scales every motion's limits and is recorded.
    """

    meta = dict(meta or {})
    if pace is not None:
        meta["pace"] = pace
    meta.setdefault("mover", mover)
    how = manner_of(manner)
    if how.name != "slide":
        meta["manner"] = how.name
    clock = StageClock(on_stage)
    clock.stage("check", "check")
    arm = arm or (world.robot.spec if world is not None else PANDA)
    if world is not None and world.robot.spec != arm:
        raise ExecutionError(f'the world given holds the arm "{world.robot.spec.name}", not "{arm.name}"')
    p, angles = check_for(how, scene, mover, path, arm)
    clock.stage("setup", "setup")
    own = world is None
    if own:  # the world only simulates: rendering happens in the film's own worlds (embodiment/render.py)
        world = World(scene, arm=arm, visuals=False)
    film = None
    try:
        if not own:
            world.reset(scene)  # a caller's world; rendering happens in the film's own worlds
        prims = arm_primitives(world, render, out_dir, [(mover, p, how.motion)])
        prims.pace = smoothing.pace(pace)
        if how.motion != "push":  # a tall object held: softer starts and stops (the push holds nothing)
            prims.pace = tall_pace(prims.pace, scene.get(mover))
        film = prims.recorder.film
        if how.name != "slide":
            prims.recorder.gripper = True
        slide, removed, grasp = _perform(prims, mover, p, angles, clock, how, scene)
        # the video's frames are drawn while the arm moves; waiting for the last ones takes seconds: say so
        clock.stage("record", "record" if film is None else
                    f"record: the video's {len(film.states)} frames ({film.settings.renderer})")
        recorder = prims.recorder
        recorder.finish_images()
        first = 0
        if approach_to is not None:
            first = approach_end_frame(trajectory_poses(recorder.frames, mover), approach_to, world.sizes[mover])
            meta["action_from"] = first
        recorder.fill_progress(mover, meta.get("anchors") or meta.get("anchor"), progress_fn, first=first)
        deviation, lift, displaced = honesty(recorder.frames, mover, p, slide, world.rests)
        stats = _stats(prims) | {"grasp": grasp}
        files = _write_files(recorder, out_dir, meta, world.sizes, render)
        clock.stop()
        execution = Execution(recorder.frames, {k: round(v, 4) for k, v in clock.timings.items()}, files,
                              max_deviation_m=deviation, anchor_displacement_m=max(displaced.values(), default=0.0),
                              max_lift_m=lift, constraint_removed=removed, duration_s=world.time, stats=stats,
                              displacements_m=displaced, render=render_info(render, film),
                              settled_m=dict(world.settled), rests_m=dict(world.rests))
        if out_dir is not None:
            files["summary"] = Path(out_dir) / "summary.json"
            if summary:
                write_summary(files["summary"], execution_summary(execution, meta, seed, render))
        return execution
    finally:
        if film is not None:
            film.close()
        if own:
            world.close()


def arm_primitives(world: World, render: RenderSettings | None, out_dir: Path | None = None, paths=None):
    """The arm's primitives with a recorder attached to ``world`` and, when rendering, the film that draws
    its frames (embodiment/render.py; their PNGs go to ``out_dir/frames``, or where the recorder writes).
    ``paths`` ((mover, path, manner name) of each plan) frame the ``auto`` camera (sim/camera.py)."""
    if render is not None and paths:
        render = framed_for(render, world.scene, paths, world.robot.tool_pose()[0], world.robot.base_xyz)

    film = None if render is None else Film(world.scene, render, None if out_dir is None else Path(out_dir) / "frames",
                                            arm=world.robot.spec)
    if film is not None:
        film.paths = [(mover, path) for mover, path, *_ in paths or ()]
    try:  # the arm's set-up takes a while: a Ctrl-C there must not leave the film's workers behind
        return Primitives(world, Recorder(world, film))
    except BaseException:
        if film is not None:
            film.close()
        raise




def _perform(prims, mover: str, path: np.ndarray, angles: list[float | None],
             clock: StageClock, manner: MannerSpec | None = None,
             scene: Scene | None = None) -> tuple[slice, bool, dict]:
    """The arm's part, stage by stage: reach (choose the grasp yaw, every IK solved before anything
    moves), engage, move, disengage. Returns the frames recorded while sliding, whether the grasp's
    constraint is gone, and the grasp chosen (for the summary)."""
    rest = prims.pose.copy()
    start, end, grasp = act(prims, scene or prims.world.scene, mover, path, angles, rest, manner,
                            stage=lambda name: clock.stage(name, name), first_frame=True)
    return slice(start, end), prims.world.sim.constraint_count() == 0, grasp


def act(prims, scene: Scene, mover: str, path: np.ndarray, angles: list[float | None], rest: np.ndarray,
        manner: MannerSpec | None = None, *, stage: Callable[[str], None] = lambda name: None,
        first_frame: bool = False) -> tuple[int, int, dict]:
    """Move ``mover`` along the checked ``path`` (from :func:`check_for`) in the manner asked, back to ``rest``:
    a slide (grasp, slide, release), a carry (grasp, lift, carry, lower, release) or a push (embodiment/push.py).
    ``stage`` is told each stage as it starts; ``first_frame`` records the world before the arm moves (a
    chain records it once, before its first clause). Returns the first and end frame of the move and the
    grasp's summary (a push's: how the push went)."""
    recorder = prims.recorder
    how = manner_of(manner)
    if how.motion == "push":
        from .push import push  # the push controller: only for a push

        stage("reach")
        if first_frame:
            recorder()
        stage("move")
        start = len(recorder.frames)
        info = push(prims, mover, path, rest)
        return start, info.pop("end_frame"), info
    lift = carry_lift(scene, mover, path) if how.motion == "carry" else 0.0
    stage("reach")
    tool_yaw, grasp = choose_grasp_yaw(prims, mover, path, angles, rest, lift)
    if first_frame:
        recorder()  # the first frame: the world before the arm moves
    stage("engage")
    prims.engage(mover, tool_yaw=tool_yaw)
    stage("move")
    start = len(recorder.frames)
    if lift > 0:
        prims.carry(path, lift)
        grasp = grasp | {"lift_m": round(lift, 6)}
    else:
        prims.move(path)
    end = len(recorder.frames)
    stage("disengage")
    prims.disengage(rest)
    return start, end, grasp


def grasp_candidates(path: np.ndarray, angles: list[float | None], base_xy: tuple[float, float],
                     arm: ArmSpec = PANDA, widths: list[float] | None = None) -> list[float]:
    """Grasp offsets (tool yaw minus the path's unwrapped block yaw, for one of the allowed grasp ``angles``)
    that keep the wrist inside its range over the whole slide, best centred first (``reach.wrist_offsets``);
    with ``widths`` (per angle, a non-cube mover's), the narrowest width the wrist reaches first."""
    dense = np.concatenate(motion.slide_chunks(path)) if len(path) > 1 else path
    v = reach.wrist_values(dense[:, :2], dense[:, 2], base_xy, arm)
    lo, hi = float(v.min()), float(v.max())
    found = {round(off, 12): 0.0 if widths is None else round(w, 4)
             for angle, w in zip(angles, widths or [0.0] * len(angles), strict=True)
             for off in reach.wrist_offsets(lo, hi, angle, arm)}
    return sorted(found, key=lambda off: (found[off], max(hi - off, off - lo), abs(off)))


def choose_grasp_yaw(prims, mover: str, path: np.ndarray, angles: list[float | None],
                      rest: np.ndarray, lift: float = 0.0) -> tuple[float, dict]:
    """The tool's yaw at the grasp (unwrapped: it decides the wrist's branch) whose whole episode the arm
    reaches: candidates from the wrist model, best centred first (``grasp_candidates``); for each, the
    approach, descent, slide, retract and return IK are solved as the arm will run them, before anything
    moves. Every candidate is tried: a wrist turning +-2 turns (a UR's) has eight, and the approach from where
    the arm rests can leave its range on the best-centred three (bench_arms.py seed 220017 "around" on the
    UR3e + Robotiq: the fourth reaches). ReachError (the first candidate's) if none works."""
    base = (prims.robot.base_xyz[0], prims.robot.base_xyz[1])
    obj = prims.world.scene.get(mover)
    widths = None if obj.shape == "cube" else [reach.grasp_width(obj, a) for a in angles]
    candidates = grasp_candidates(path, angles, base, prims.robot.spec, widths)
    if not candidates:
        raise ReachError(f'no grasp keeps the arm\'s wrist inside its range while "{mover}" turns along this path '
                         f"({np.ptp(path[:, 2]):.1f} rad); turn the block less")
    first_error = None
    for off in candidates:
        tool_yaw = float(path[0, 2] + off)
        try:
            prims.check_engage_and_slide(mover, path, tool_yaw, rest, lift)
            width = {} if widths is None else {"width_m": round(reach.grasp_width(obj, off), 6)}
            return tool_yaw, width | {"yaw_offset_deg": round(float(np.degrees(off)), 3),
                              "angle_deg": round(float(np.degrees(off % np.pi)), 3),
                              "angles_allowed_deg": [None if a is None else round(float(np.degrees(a)), 3)
                                                     for a in angles]}
        except ReachError as e:
            first_error = first_error or e
    raise first_error


def _stats(prims) -> dict:
    """The counts summary.json reports under ``execution``."""
    recorder = prims.recorder
    return {
        "physics_steps": prims.world.steps,
        "ik_solves": prims.ik_solves,
        "rendered_frames": len(recorder.images),
        "render_s": round(recorder.render_s, 4),
        "max_lateral_acc": round(max((t.max_lateral_acc for _, t in prims.timed), default=0.0), 4),
    }


def _write_files(recorder, out_dir: Path | None, meta: dict, sizes: dict[str, float],
                 render: RenderSettings | None) -> dict[str, Path]:
    """trajectory.json and, when rendering, frames, video and contact sheet; name -> path."""
    if out_dir is None:
        return {}
    out_dir = Path(out_dir)
    files = {"trajectory": out_dir / "trajectory.json"}
    recorder.write_trajectory(files["trajectory"], meta, sizes)
    if recorder.film is not None:
        text = meta.get("sentence") or meta.get("caption")  # a replayed demonstration has no sentence of its own
        caption = text if meta.get("manner") is None else f'{meta["manner"]}: {text}'
        files |= recorder.write_images(out_dir, render.video, caption)
    return files


