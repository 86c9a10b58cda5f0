"""``perform`` for a chain: every clause resolved and forecast up front, then executed by the same arm in
one continuous PyBullet episode, each clause re-planned from where the world really left the blocks.

    resolve    every clause against the scene (clauses.py): names, colours, did-you-mean, per clause
    forecast   the whole chain planned in 2-D from the predicted end states (forecast.py): a clause that
               cannot be planned is refused with its index and the check, before anything moves or is
               written
    execute    per clause: plan from the simulated world's real poses (the first clause's forecast is
               already that), check the path, choose the grasp, engage, slide, release, retreat to rest;
               one recorder keeps sampling across clauses, so the frames are one episode
    judge      per clause, on its own frames: the action's judge, and the 1 mm rule for every block it does
               not move; the first clause that fails stops the chain and says why

One run folder (files.py writes it): trajectory.json with ``segments``, plan.json with one plan per clause,
summary.json with a verdict per clause and for the chain, and a video captioned with the current clause.
A one-clause sentence never comes here: ``perform`` runs it as it always has (byte-identical files).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .. import planning
from ..core.contracts import Plan, approach_end_frame, trajectory_poses
from ..core.runfolder import run_folder, write_summary
from ..core.scene import Scene
from ..core.timing import StageClock
from ..embodiment import arm_plugins
from ..embodiment.manners import manner_planning
from ..embodiment.sim.arms import PANDA, ArmSpec, check_description
from ..errors import ExecutionError, InfeasibleError, L2PError
from ..judge import judge_context
from ..judge.manners import manner_verdict
from ..manners import registry as manners
from ..pipeline import check_feasible, check_options, check_render_settings, check_scene, disturbance_verdict
from ..plugins import registry
from ..progress.scoring import curve_from
from .clauses import Clause, resolve_clauses
from .files import merge_timings
from .forecast import Step, forecast


@dataclass
class ClauseResult:
    """What one clause did; ``verdict`` is its judge's verdict with the 1 mm rule applied."""

    clause: Clause
    plan: Plan | None
    verdict: dict[str, Any]
    first_frame: int
    last_frame: int
    final_progress: float | None = None
    max_deviation_m: float = 0.0
    final_error_m: float | None = None
    displacements_m: dict[str, float] = field(default_factory=dict)
    grasp: dict[str, Any] = field(default_factory=dict)
    failed_stage: str | None = None  # "plan", "path", "reach", "execute" when the clause broke off
    action_from: int | None = None  # after an approach slide: the episode's frame where the action proper starts

    @property
    def success(self) -> bool:
        return bool(self.verdict.get("success"))

    def to_dict(self) -> dict[str, Any]:
        c = self.clause.command
        return {
            "clause": self.clause.index, "text": self.clause.text, "sentence": c.sentence, "verb": c.verb,
            "action": c.action, "mover": c.mover, "anchor": c.anchor, "anchors": list(c.anchors),
            "success": self.success, "verdict": self.verdict, "final_progress": _round(self.final_progress),
            "planned_progress": None if self.plan is None or not len(self.plan.progress)
            else _round(float(self.plan.progress[-1])),
            "first_frame": self.first_frame, "last_frame": self.last_frame,
            "max_deviation_m": _round(self.max_deviation_m), "final_error_m": _round(self.final_error_m),
            "displacements_m": {k: _round(v) for k, v in self.displacements_m.items()},
            "grasp": self.grasp, **({"failed_stage": self.failed_stage} if self.failed_stage else {}),
            **({"action_from": self.action_from} if self.action_from is not None else {}),
            **({} if c.manner == "slide" else {"manner": c.manner}),
        }


@dataclass
class ChainResult:
    """What a chain did: per clause results (up to and including the first failure)."""

    sentence: str
    clauses: list[Clause]
    results: list[ClauseResult]
    out_dir: Path
    timings: dict[str, float]
    files: dict[str, Path] = field(default_factory=dict)
    row: dict[str, Any] | None = None  # a composite's verdict on the whole (chain/composite.py: row_verdict)

    @property
    def completed(self) -> int:
        """Clauses done successfully before the first failure (CALVIN's 'tasks completed in a row')."""
        n = 0
        for r in self.results:
            if not r.success:
                break
            n += 1
        return n

    @property
    def success(self) -> bool:
        return self.completed == len(self.clauses) and (self.row is None or bool(self.row["success"]))

    def verdict(self) -> dict[str, Any]:
        """The chain's verdict: success, how far it got, and the first failed clause's reason."""
        n = len(self.clauses)
        failed = next((r for r in self.results if not r.success), None)
        if failed is None and self.row is not None and not self.row["success"]:
            return {"success": False, "completed": n, "clauses": n, "reason": f"all {n} clauses done, but {self.row['reason']}"}
        if failed is None:
            return {"success": True, "completed": n, "clauses": n, "reason": f"all {n} clauses done"}
        return {"success": False, "completed": self.completed, "clauses": n, "failed_clause": failed.clause.index,
                "reason": f"{failed.clause.label()} failed: {failed.verdict.get('reason', '')}; "
                          f"the chain stopped there ({self.completed} of {n} done)"}

    def to_dict(self) -> dict[str, Any]:
        return {"sentence": self.sentence, "chain": True, "out_dir": str(self.out_dir), "verdict": self.verdict(),
                "success": self.success, "completed": self.completed, "clauses": [r.to_dict() for r in self.results],
                **({"row": self.row} if self.row is not None else {}),
                "timings": {k: round(v, 4) for k, v in self.timings.items()},
                "files": {k: str(v) for k, v in self.files.items()}}


def _round(v: float | None) -> float | None:
    return None if v is None else round(float(v), 6)


def perform_chain(sentence: str, scene: Scene, *, out_dir: str | Path | None = None, planner: str = "default",
                  seed: int = 0, render: bool = True, force: bool = False, budget: int | None = None,
                  threshold: float | None = None, on_stage=None, plugins: list | None = None,
                  render_settings: Any = None, world: Any = None, bundles: dict | None = None,
                  steps: list[Step] | None = None, arm: str | ArmSpec | None = None) -> ChainResult:
    """Resolve, forecast, execute and judge a chain of clauses; write one run folder.

    Everything a user can get wrong (a clause's words, a block not in the scene, a clause that cannot be
    planned from the predicted state) is an L2PError naming the clause, raised before any folder is made.
    ``world``: an open simulator world to run in (reset to ``scene`` first); ``bundles``: action name ->
    loaded bundle, to reuse across runs; ``steps``: the chain already resolved and forecast (``evaluate
    --chains`` draws it clause by clause): ``sentence`` must be their texts joined. ``arm``: an arm's name
    (``l2p-bullet arms``) or spec, default the Panda; the scene's workspace is fitted to its reach first.
    """
    clock = StageClock(on_stage)
    clock.stage("parse")
    check_options(planner, seed, budget, threshold)
    check_scene(scene)
    if render:
        check_render_settings(render_settings)
    plugins = registry.discover() if plugins is None else plugins
    arm = arm_plugins.get(arm)  # an unknown arm fails before anything is planned or written
    check_description(arm)  # a URDF PyBullet would crash on: refused before a folder is made
    scene = arm_plugins.fit_scene(scene, arm)
    if steps is None:
        clauses = resolve_clauses(sentence, scene, plugins)
        clock.stage("forecast", f"planning the {len(clauses)} clauses from their predicted states")
        steps = forecast(clauses, scene, plugins, planner=planner, seed=seed, budget=budget, threshold=threshold,
                         bundles=bundles, arm=arm)
    clock.stop()
    with run_folder(out_dir, force=force, prefix="perform", command="perform") as out:
        try:
            return _execute(sentence, scene, steps, out, clock, plugins, planner=planner, seed=seed, render=render,
                            budget=budget, threshold=threshold, render_settings=render_settings, world=world,
                            arm=arm)
        except L2PError as e:
            clock.stop()
            write_summary(out / "summary.json", {"schema": 1, "sentence": sentence, "chain": True, "ok": False,
                                                 "failed_stage": clock.last, "error": str(e),
                                                 "timings_s": clock.timings})
            raise


def scene_now(scene: Scene, world: Any) -> Scene:
    """``scene`` with every block where the simulated world has it now (x, y, yaw)."""
    poses = world.poses()
    return Scene([o.moved(poses[o.name][[0, 1, 3]]) for o in scene.objects], scene.table, scene.workspace)


def _execute(sentence: str, scene: Scene, steps: list[Step], out: Path, clock: StageClock, plugins: list, *,
             planner: str,
             seed: int, render: bool, budget: int | None, threshold: float | None, render_settings: Any,
             world: Any, replan: bool = True, arm: ArmSpec = PANDA, replay: dict | None = None) -> ChainResult:
    """Execute ``steps`` in one episode in ``world`` (or a new one) and write the run folder into ``out``.
    ``replan`` False executes each step's ``forecast`` as it is (``replay`` of a chain's plan.json; ``replay``:
    where the plans came from, recorded as a one-clause replay records it)."""
    # lazy: the arm's modules (and files.py, which records with them) load only when a chain is performed
    from ..embodiment import execute as ex
    from ..embodiment.sim.world import World
    from .files import write_run

    settings = (ex.DEFAULT_RENDER if render_settings is None else render_settings) if render else None
    own = world is None
    clock.stage("setup", "setting up the simulated world")
    if own:  # the world only simulates: the film's own worlds draw the frames (embodiment/render.py)
        world = World(scene, arm=arm, visuals=False)
    elif world.robot.spec != arm:
        raise ExecutionError(f'the world given holds the arm "{world.robot.spec.name}", not "{arm.name}"')
    prims = None
    try:
        if not own:
            world.reset(scene)  # a caller's world; rendering happens in the film's own worlds
        prims = ex.arm_primitives(world, settings, out)
        prims.recorder.gripper = any(s.clause.command.manner != "slide" for s in steps)  # issue 23
        rest = prims.pose.copy()
        prims.recorder()  # the first frame: the world before the arm moves
        results: list[ClauseResult] = []
        for k, step in enumerate(steps):
            c = step.clause
            clock.stage(f"clause {c.index}", f"{c.label()}: planning from the blocks' real poses, then executing")
            first = 0 if k == 0 else len(prims.recorder.frames)
            r = _clause(step, scene_now(scene, world), prims, rest, plugins, first=first, replan=replan and k > 0,
                        planner=planner, seed=seed, budget=budget, threshold=threshold, arm=arm)
            results.append(r)
            if not r.success:
                break
        film = prims.recorder.film
        clock.stage("record", "writing the run folder" + ("" if film is None else
                    f" and the video's {len(film.states)} frames ({film.settings.renderer})"))
        result = ChainResult(sentence, [s.clause for s in steps], results, out, {})
        write_run(result, steps, prims, world, settings, seed, scene, replay=replay)
        if steps and steps[0].clause.target is not None:  # a composite: is the whole what it should be?
            from .composite import judge_row  # lazy: composite.py imports clauses.py, this module's peer

            result.row = judge_row(result, steps, scene_now(scene, world), out / "summary.json")
        clock.stop()
        clock.timings["total"] = clock.elapsed
        result.timings = dict(clock.timings)
        merge_timings(out / "summary.json", result.timings)
        return result
    finally:
        if prims is not None and prims.recorder.film is not None:
            prims.recorder.film.close()  # its render workers stop, also when a clause failed half-way
        if own:
            world.close()


def _clause(step: Step, now: Scene, prims: Any, rest: np.ndarray, plugins: list, *, first: int, replan: bool, planner: str, seed: int,
            budget: int | None, threshold: float | None, arm: ArmSpec = PANDA) -> ClauseResult:
    """Plan ``step``'s clause from ``now`` (or take its forecast when not ``replan``: the first clause's was
    planned from this very state), execute it with the arm, judge its frames (from frame ``first`` on)."""
    from ..embodiment import execute as ex

    cmd, rec = step.clause.command, prims.recorder
    plan, stage = None, "plan"
    try:
        if not replan:
            plan = step.forecast  # planned from the very scene the world was loaded with (or replayed as is)
        else:
            check_feasible(cmd, now, plugins, arm)
            target = step.clause.target
            plan = planning.plan(now, cmd.mover, list(cmd.anchors), step.bundle, planner=planner, seed=seed,
                                 budget=budget, threshold=threshold, target=None if target is None else target(now),
                                 arm=arm, **manner_planning(manners.get(cmd.manner), now.get(cmd.mover).size, arm))
            plan.extra.setdefault("sentence", step.clause.text)
        stage = "path"
        p, angles = ex.check_for(ex.manner_of(cmd.manner), now, cmd.mover, plan.path, arm)
        stage = "reach"

        def on(name: str) -> None:
            nonlocal stage
            stage = "reach" if name == "reach" else "execute"

        s0, s1, grasp = ex.act(prims, now, cmd.mover, p, angles, rest, ex.manner_of(cmd.manner), stage=on)
        slide = slice(s0 - first, s1 - first)
    except L2PError as e:
        _let_go(prims, rest)
        if len(rec.frames) <= first:
            # broke off before the arm moved (plan, path, reach): the world stands still for one frame, so the
            # clause's segment names a frame the trajectory has (it named frame N of N: readers refused the run)
            prims.hold(rec.traj_every * prims.world.dt)  # exactly one trajectory frame
        check = f" ({e.check})" if isinstance(e, InfeasibleError) else ""
        last = max(first, len(rec.frames) - 1)
        return ClauseResult(step.clause, plan, {"success": False, "reason": f"{stage}{check}: {e}"}, first, last,
                            failed_stage=stage)
    last = len(rec.frames) - 1
    frames = rec.frames[first:last + 1]
    size = now.get(cmd.mover).size
    kw = {"more_anchors": [trajectory_poses(frames, a) for a in cmd.more_anchors]} if cmd.more_anchors else {}
    mover, anchor = trajectory_poses(frames, cmd.mover), trajectory_poses(frames, cmd.anchor)
    start = 0 if plan.approach_to is None else approach_end_frame(mover, plan.approach_to, size)
    values = curve_from(step.model, start, mover, anchor, size, **kw)  # after an approach, as planned
    for f, v in zip(frames, values, strict=True):
        f["progress"] = round(float(v), 6)
    deviation, _lift, displaced = ex.honesty(frames, cmd.mover, p, slide, prims.world.rests)
    final_progress = float(values[-1]) if len(values) else None
    context = judge_context([trajectory_poses(frames, a) for a in cmd.anchors], step.viewer)
    verdict = disturbance_verdict(step.judge.judge(mover, anchor, size, final_progress=final_progress,
                                                   **context).to_dict(), displaced, cmd.anchor)
    verdict = manner_verdict(verdict, manners.get(cmd.manner), frames, cmd.mover, now.get(cmd.mover).rest)
    return ClauseResult(step.clause, plan, verdict, first, last, action_from=first + start if start else None,
                        final_progress=final_progress,
                        max_deviation_m=deviation, final_error_m=float(np.hypot(*(mover[-1, :2] - plan.path[-1, :2]))),
                        displacements_m=displaced, grasp=grasp)


def _let_go(prims: Any, rest: np.ndarray) -> None:
    """After a clause broke off while holding its block: release it and retreat, so the recording ends
    with the arm clear (best effort: the failure itself is what the summary reports)."""
    if prims.grasp is None:
        return
    try:
        prims.disengage(rest)
    except (L2PError, ExecutionError):
        pass
