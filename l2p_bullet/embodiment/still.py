"""A run in which the arm moves nothing: the relation the sentence asks for already holds
(``planning/already.py``). The world is set up as for any run and recorded standing still for one frame, so
the run folder holds what every run's does (trajectory.json with the scene as it stands, the arm at rest,
the progress of that frame) and every reader reads it as it reads a run that moved."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..arms import PANDA, ArmSpec
from ..core.scene import Scene
from ..core.timing import StageClock
from .execute import Execution, _write_files, arm_primitives
from .sim.world import World


def stand_still(scene: Scene, mover: str, *, out_dir: Path | None, progress_fn: Callable[..., np.ndarray] | None = None,
                meta: dict | None = None, world: World | None = None, arm: ArmSpec | None = None,
                on_stage: Callable[[str], None] | None = None) -> Execution:
    """The world of ``scene`` recorded for one trajectory frame with the arm at rest (``execute_path``'s
    arguments of the same names; nothing is rendered: there is no motion to film)."""
    meta = dict(meta or {})
    meta.setdefault("mover", mover)
    clock = StageClock(on_stage)
    clock.stage("setup", "setup")
    arm = arm or (world.robot.spec if world is not None else PANDA)
    own = world is None
    if own:
        world = World(scene, arm=arm, visuals=False)
    try:
        if not own:
            world.reset(scene)
        prims = arm_primitives(world, None, out_dir)
        clock.stage("record", "record")
        prims.hold(prims.recorder.traj_every * world.dt)  # exactly one trajectory frame
        recorder = prims.recorder
        recorder.fill_progress(mover, meta.get("anchors") or meta.get("anchor"), progress_fn)
        files = _write_files(recorder, out_dir, meta, world.sizes, None)
        clock.stop()
        displaced = {n: 0.0 for n in world.rests if n != mover}
        return Execution(recorder.frames, {k: round(v, 4) for k, v in clock.timings.items()}, files,
                         max_deviation_m=0.0, anchor_displacement_m=0.0, max_lift_m=0.0, constraint_removed=True,
                         duration_s=world.time, stats={"physics_steps": world.steps, "ik_solves": 0,
                                                       "rendered_frames": 0, "render_s": 0.0,
                                                       "max_lateral_acc": 0.0},
                         displacements_m=displaced, render=None, settled_m=dict(world.settled),
                         rests_m=dict(world.rests))
    finally:
        if own:
            world.close()
