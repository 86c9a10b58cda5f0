"""``perform`` of any sentence: a chain of clauses, every clause resolved and forecast up front, then
executed by the same arm in one continuous PyBullet episode, each clause re-planned from where the world
really left the blocks.

    resolve    every clause against the scene (clauses.py): names, colours, did-you-mean, per clause
    forecast   the whole chain planned in 2-D from the predicted end states (forecast.py): a clause that
               cannot be planned is refused with its index and the check, before anything moves or is
               written
    execute    per clause: the plan for the simulated world's real poses (replan.py: the forecast's own where
               the world stands where it was predicted, else planned again), check the path, choose the grasp,
               engage, slide, release, retreat to rest;
               one recorder keeps sampling across clauses, so the frames are one episode
    judge      per clause, on its own frames: the action's judge, and the 1 mm rule for every block it does
               not move; the first clause that fails stops the chain and says why

One run folder (files.py writes it): trajectory.json with ``segments``, plan.json with one plan per clause,
summary.json with a verdict per clause and for the chain, and a video captioned with the current clause.
A sentence of one clause is a chain of one: it is resolved here too, then performed by the pipeline's stages
after the parse (``pipeline.prepare_command``, ``perform_prepared``), whose run folder is the one-clause
layout (DESIGN.md section 4), so ``perform`` and every caller take one path for every sentence.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..arms import ArmSpec
from ..core.contracts import Plan, approach_end_frame, trajectory_poses
from ..core.runfolder import add_to_summary, run_folder, write_summary
from ..core.scene import Scene
from ..core.timing import StageClock
from ..embodiment.manners import tall_pace
from ..embodiment.smoothing import pace as pace_of
from ..errors import ExecutionError, InfeasibleError, L2PError
from ..judge import judge_context
from ..judge.footprints import outlines_of
from ..judge.manners import manner_verdict
from ..manners import registry as manners
from ..options import RunOptions, admit
from ..pipeline import (
    PerformResult,
    check_feasible,
    disturbance_verdict,
    feasible_as,
    perform_prepared,
    prepare_command,
)
from ..planning.already import already_said, is_standing
from ..plugins import registry
from ..progress.scoring import curve_from
from .clause import Clause
from .clauses import one_clause, resolve_clauses
from .composite import judge_row
from .files import merge_timings
from .forecast import Step, forecast
from .replan import on_rim, replanned


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
            **({"manner_why": c.manner_why} if c.manner_why else {}),
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
            return {
                "success": False,
                "completed": n,
                "clauses": n,
                "reason": f"all {n} clauses done, but {self.row['reason']}",
            }
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

    def text(self) -> list[str]:
        """What ``perform`` prints for a chain: one line per clause, the row's (a composite), the chain's."""
        out = []
        for c in self.results:
            fp = "n/a" if c.final_progress is None else f"{c.final_progress:.2f}"
            out.append(f'{c.clause.index}. {c.clause.command.sentence}: "{c.clause.command.action}", '
                       f'{"success" if c.success else "FAILED"} ({c.verdict.get("reason", "")}), final progress {fp}')
        v, row = self.verdict(), self.row
        if row is not None:  # a composite ("make a row of ..."): the whole judged too
            out.append(f'row: {row["reason"]} (largest gap {row["max_gap_sides"]:.2f} side, farthest from the '
                       f'line {row["max_offset_sides"]:.2f} side)')
        video = self.files.get("video")
        return out + [f'chain: {"success" if self.success else "FAILED"}, {v["completed"]} of {v["clauses"]} clauses '
                      f'done, {self.timings.get("total", 0):.1f} s',
                      f"run folder: {self.out_dir}" + (f"\nvideo: {video}" if video else " (no video: --no-render)")]


def _round(v: float | None) -> float | None:
    return None if v is None else round(float(v), 6)


def perform_chain(
    sentence: str,
    scene: Scene,
    options: RunOptions | None = None,
    *,
    plugins: list | None = None,
    world: Any = None,
    bundles: dict | None = None,
    steps: list[Step] | None = None,
    **changes: Any,
) -> ChainResult | PerformResult:
    """Perform any sentence (the front door of ``perform``): resolve its clauses, forecast and execute them,
    judge each; write one run folder. ``options`` (with ``changes`` by name: ``RunOptions.of``) are checked
    once, up front, with the scene and the arm (its reach fits the scene's workspace first).

    A lone clause (no composite) is a chain of one, performed by the pipeline's stages and written in the
    one-clause layout: its :class:`~l2p_bullet.pipeline.PerformResult` is returned. Everything a user can get
    wrong (a clause's words, a block not in the scene, a clause that cannot be planned from the predicted
    state) is an L2PError naming the clause, raised before any folder is made. ``world``: an open simulator
    world to run in (reset to ``scene`` first); ``bundles``: action name -> loaded bundle, to reuse across
    runs; ``steps``: the chain already resolved and forecast (``evaluate --chains`` draws it clause by
    clause): ``sentence`` must be their texts joined.
    """
    opts = RunOptions.of(options, **changes)
    clock = StageClock(opts.on_stage)
    clock.stage("parse")
    scene, arm = admit(scene, opts)  # a typo, a bad scene or an unknown arm fails before anything is written
    plugins = registry.discover() if plugins is None else plugins
    if steps is None:
        clauses = resolve_clauses(sentence, scene, plugins)
        if one_clause(clauses):
            cmd = clauses[0].command
            bundle = (bundles or {}).get(cmd.action)
            return perform_prepared(prepare_command(cmd, scene, arm, plugins, opts, bundle=bundle, clock=clock), clock,
                                    world=world)
        clock.stage("forecast", f"planning the {len(clauses)} clauses from their predicted states")
        steps = forecast(clauses, scene, plugins, replace(opts, arm=arm), bundles=bundles)
    clock.stop()
    with run_folder(opts.out_dir, force=opts.force, prefix="perform", command="perform") as out:
        try:
            return _execute(sentence, scene, steps, out, clock, plugins, opts, arm, world=world)
        except L2PError as e:
            clock.stop()
            write_summary(out / "summary.json", {"schema": 1, "sentence": sentence, "chain": True, "ok": False,
                                                 "failed_stage": clock.last, "error": str(e),
                                                 "timings_s": clock.timings})
            raise
        except KeyboardInterrupt:  # run_folder marks the run interrupted; where it was is worth keeping
            clock.stop()
            stage, _, clause = clock.last.partition(" ")  # "setup", "clause 2", "record"
            add_to_summary(out, {"sentence": sentence, "chain": True, "interrupted_stage": stage,
                                 **({"interrupted_clause": int(clause)} if clause else {}), "timings_s": clock.timings})
            raise


def scene_now(scene: Scene, world: Any) -> Scene:
    """``scene`` with every block where the simulated world has it now (x, y, yaw)."""
    poses = world.poses()
    return Scene([o.moved(poses[o.name][[0, 1, 3]]) for o in scene.objects], scene.table, scene.workspace)


def _execute(sentence: str, scene: Scene, steps: list[Step], out: Path, clock: StageClock, plugins: list,
             options: RunOptions, arm: ArmSpec, *, world: Any = None, replan: bool = True,
             replay: dict | None = None) -> ChainResult:
    """Execute ``steps`` by ``arm`` in one episode in ``world`` (or a new one) and write the run folder into
    ``out``. ``replan`` False executes each step's ``forecast`` as it is (``replay`` of a chain's plan.json;
    ``replay``: where the plans came from, recorded as a one-clause replay records it)."""
    # lazy: the arm's modules (and files.py, which records with them) load only when a chain is performed
    from ..embodiment import execute as ex
    from ..embodiment.sim.world import World
    from .files import write_run

    render_settings = options.render_settings
    settings = (ex.DEFAULT_RENDER if render_settings is None else render_settings) if options.render else None
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
        prims = ex.arm_primitives(world, settings, out, [(s.clause.command.mover, s.forecast.path,
                                                           manners.get(s.clause.command.manner).motion)
                                                          for s in steps])
        prims.recorder.gripper = any(s.clause.command.manner != "slide" for s in steps)  # a carry grips
        rest = prims.pose.copy()
        prims.recorder()  # the first frame: the world before the arm moves
        results: list[ClauseResult] = []
        for k, step in enumerate(steps):
            c = step.clause
            clock.stage(f"clause {c.index}", f"{c.label()}: planning from the blocks' real poses, then executing")
            first = 0 if k == 0 else len(prims.recorder.frames)
            r = _clause(step, scene_now(scene, world), prims, rest, plugins, options, arm, first=first,
                        replan=replan and k > 0, later=steps[k + 1:])
            results.append(r)
            if not r.success:
                break
        film = prims.recorder.film
        clock.stage("record", "writing the run folder" + ("" if film is None else
                    f" and the video's {len(film.states)} frames ({film.settings.renderer})"))
        result = ChainResult(sentence, [s.clause for s in steps], results, out, {})
        write_run(result, steps, prims, world, settings, options.seed, scene, replay=replay)
        # each composite in the chain ("make a row of A, B and C, then ..."): is the whole what it should be?
        # Judged once its steps have all run; the first that is not a row is the chain's row verdict.
        for group in dict.fromkeys(s.clause.group for s in steps if s.clause.group is not None):
            members = [s for s in steps if s.clause.group == group]
            if members[-1].clause.index > len(results):
                break
            result.row = judge_row(result, members, scene_now(scene, world), out / "summary.json")
            if not result.row["success"]:
                break
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


def _clause(step: Step, now: Scene, prims: Any, rest: np.ndarray, plugins: list, options: RunOptions,
            arm: ArmSpec, *, first: int, replan: bool, later: Sequence[Step] = ()) -> ClauseResult:
    """Plan ``step``'s clause from ``now`` (or take its forecast when not ``replan``: the first clause's was
    planned from this very state; ``later``: the clauses after it, whose checks its re-plan keeps passing where it
    can), execute it with the arm, judge its frames (from frame ``first`` on)."""
    from ..embodiment import execute as ex

    cmd, rec = step.clause.command, prims.recorder
    plan, stage, standing = None, "plan", False
    try:
        if not replan:
            plan = step.forecast  # planned from the very scene the world was loaded with (or replayed as is)
        else:
            now = on_rim(now)  # a block the arm left a hair beyond the workspace's edge: planned from the edge
            done_as = feasible_as(cmd, now, plugins, arm, check=check_feasible)
            if done_as is not cmd:  # the manner the blocks leave it from here (a slide's way blocked: carried)
                cmd, step = done_as, replace(step, clause=replace(step.clause, command=done_as))
            # the end state the chain was planned with (ends.py): the planner's own, or the one that keeps the
            # later clauses possible
            plan = replanned(step, now, options, arm, later=later, plugins=plugins)
            plan.extra.setdefault("sentence", step.clause.text)
        standing = is_standing(plan)  # the relation already holds: the world stands still, the arm at rest
        if standing:
            prims.hold(rec.traj_every * prims.world.dt)  # exactly one trajectory frame
            p, slide, grasp = plan.path, slice(0, 0), {}
        else:
            stage = "path"
            p, angles = ex.check_for(ex.manner_of(cmd.manner), now, cmd.mover, plan.path, arm)
            stage = "reach"

            def on(name: str) -> None:
                nonlocal stage
                stage = "reach" if name == "reach" else "execute"

            prims.pace = pace_of(cmd.pace)  # this clause's "slowly", "gently" (the next clause may differ)
            if ex.manner_of(cmd.manner).motion != "push":  # a tall object held: softer starts and stops
                prims.pace = tall_pace(prims.pace, now.get(cmd.mover))
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
    outlines = outlines_of([now.get(o) for o in (cmd.mover, *cmd.anchors)])
    if outlines is not None and getattr(step.model, "reads_outlines", False):
        kw["outlines"] = outlines
    mover, anchor = trajectory_poses(frames, cmd.mover), trajectory_poses(frames, cmd.anchor)
    start = 0 if plan.approach_to is None else approach_end_frame(mover, plan.approach_to, size)
    values = curve_from(step.model, start, mover, anchor, size, **kw)  # after an approach, as planned
    for f, v in zip(frames, values, strict=True):
        f["progress"] = round(float(v), 6)
    deviation, _lift, displaced = ex.honesty(frames, cmd.mover, p, slide, prims.world.rests)
    final_progress = float(values[-1]) if len(values) else None
    context = judge_context([trajectory_poses(frames, a) for a in cmd.anchors], step.viewer, judge=step.judge,
                            outlines=outlines)
    verdict = disturbance_verdict(step.judge.judge(mover, anchor, size, final_progress=final_progress,
                                                   **context).to_dict(), displaced, cmd.anchor)
    if not standing:  # nothing moved, in no manner: the verb's manner has nothing to show
        verdict = manner_verdict(verdict, manners.get(cmd.manner), frames, cmd.mover,
                                 prims.world.rests[cmd.mover])
    verdict = already_said(verdict, plan)
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
