"""The front door: a sentence in, a run folder out. ``perform`` and ``plan`` run the stages of DESIGN.md.

    parse      sentence -> Command, against the phrases of the installed plugins (registry, language)
    feasibility  the scene against what the arm can do (planning.feasibility): a scene it cannot do
               is refused here, with the check that failed (InfeasibleError.check), before anything is
               planned, moved or written
    load       the one plugin the command needs -> Bundle, and its progress model (scored in numpy:
               perform never imports torch)
    plan       planning.plan -> Plan (2-D path of the mover), saved as plan.json
    execute    embodiment.execute.execute_path: the arm performs the path in PyBullet; trajectory.json
               gets the progress model's value per frame, so a run can be read without the model
    judge      the bundle's judge (rules for the built-in actions) on the *executed* trajectory (what the
               simulator did, not what was planned): a plan the arm cannot follow must not count as success,
               and neither does a run in which the anchor or another block moved more than 1 mm

Each stage is timed; the timings, the verdict and the final progress go into summary.json, written once
at the end (execute's own fields first). The cheap checks (options, sentence, feasibility, plugin, run
folder) run before the expensive ones so that a typo or an impossible scene costs milliseconds, not a
planning run, and never touches the disk.

One path for every caller: :func:`prepare` (parse, feasibility, load) and :func:`judged_plan` (plan, and
the judge's verdict on it; an optional time limit) are the stages ``perform``, ``plan`` and the
evaluation worker (``evaluate/worker.py``) share. The options travel as one checked
:class:`~l2p_bullet.options.RunOptions`; :func:`prepare_command`, :func:`perform_prepared` and
:func:`plan_prepared` are the same stages for a command already resolved (l2p_bullet/chain's front door
resolves every sentence as a chain, and performs a lone clause through them). What the stages hand back and
write (:class:`PerformResult`, :class:`PlanResult`, the disturbance rule, a run's summary.json) is in
``results.py``.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from .. import planning
from ..arms import PANDA, ArmSpec
from ..core.contracts import Plan, trajectory_poses
from ..core.runfolder import run_folder, write_summary
from ..core.scene import Scene
from ..core.timing import StageClock
from ..embodiment.manners import check_manner, manner_planning
from ..errors import InfeasibleError, L2PError, LanguageError, PluginError, listed
from ..judge import judge_context, judge_for, plan_verdict
from ..judge.footprints import outlines_of
from ..judge.manners import manner_verdict
from ..language import Command, Context, parse
from ..manners import registry as manners
from ..options import RunOptions, admit
from ..planning import feasibility
from ..planning.already import already_said, is_standing
from ..planning.extent import apply_extent
from ..planning.plot import plot_plan
from ..planning.squares import squares_scorer
from ..plugins import registry
from .results import DISTURBED_M, PerformResult, PlanResult, disturbance_verdict, moved_text, perform_summary

__all__ = [  # the front door's names; the results' own (results.py) are re-exported for every caller
    "BLOCKED", "DISTURBED_M", "PerformResult", "PlanResult", "Prepared", "carried_over", "check_feasible",
    "disturbance_verdict", "feasible_as", "judged_plan", "moved_text", "perform", "perform_prepared", "plan_prepared",
    "plan_sentence", "prepare", "prepare_command", "resolve", "scene_fields",
]

BLOCKED = "\0blocked:"
"""Action name given to a blocked phrase while parsing, so that the sentence's own phrase is found."""


def resolve(sentence: str, scene: Scene, plugins: list | None = None, context: Context | None = None) -> Command:
    """Parse ``sentence`` against the installed plugins' phrases (no plugin is imported).

    A sentence whose preposition belongs to a broken plugin, or is claimed by two plugins, gets that
    plugin's error (naming it), not "not a preposition I know"; every other phrase keeps working.
    """
    plugins = registry.discover() if plugins is None else plugins
    table = registry.phrase_table(plugins)
    blocked = registry.blocked_phrases(plugins)
    if not table and not blocked and plugins:
        bad = registry.broken(plugins)
        raise PluginError(f"none of the {len(plugins)} installed action plugins can be used (first: "
                          f"{bad[0].label()}: {bad[0].error}); see: l2p-bullet actions")
    try:
        cmd = parse(sentence, scene, {**{p: BLOCKED + p for p in blocked}, **table}, registry.anchor_counts(plugins),
                    extents=registry.extent_table(plugins), context=context)
    except LanguageError as e:
        unknown = [p for p in registry.broken(plugins) if not p.phrases]  # broken before its phrases were read
        if not unknown or "preposition" not in str(e):
            raise
        names = listed([p.label() for p in unknown])
        raise LanguageError(f"{e} Broken plugins whose phrases cannot be read, one may own it: {names} "
                            "(see: l2p-bullet actions --check)") from None
    if cmd.action.startswith(BLOCKED):
        raise blocked[cmd.action[len(BLOCKED):]]
    return cmd


def check_feasible(cmd: Command, scene: Scene, plugins: list, arm: ArmSpec = PANDA) -> None:
    """Refuse (InfeasibleError, with ``.check``) a scene the arm cannot do for ``cmd``: the arm's checks, and
    the room checks of the rule judge the action's manifest names (``[judge] rules``), if any, and the manner's
    (a carry refuses an object too wide or too heavy for the gripper)."""
    info = next((p for p in plugins if p.name == cmd.action), None)
    spec = (info.manifest.get("judge") if info is not None else None) or {}
    rules = spec.get("rules") if isinstance(spec, dict) else None
    manner = manners.get(cmd.manner)
    feasibility.check(scene, cmd.mover, cmd.anchor, rules if isinstance(rules, str) else None, arm,
                      turns=manner.motion != "push",  # a push does not turn the block (embodiment/push.py)
                      airborne=manner.airborne)
    check_manner(manner, scene, cmd.mover, arm)


OVER_CHECKS = {"blocked-around": 'no way round "{anchor}"', "boxed-in": "no move at all"}
"""The refusals a loose verb's block is carried past (``MannerSpec.over``), with what they leave the manner: the
other objects in the way of its path, which a block carried above them does not meet."""


def feasible_as(cmd: Command, scene: Scene, plugins: list, arm: ArmSpec = PANDA, *,
                check: Callable[..., None] = check_feasible) -> Command:
    """``cmd`` as the arm can do it in ``scene``: itself when ``check`` (:func:`check_feasible`) passes; where the
    other objects leave its manner no way round the anchor or no move at all (:data:`OVER_CHECKS`), it
    :func:`carried_over` them when that passes; else the first refusal, with the carry's own where it is refused
    too (the rim alone leaves too little: moving the other objects would not help)."""
    try:
        check(cmd, scene, plugins, arm)
        return cmd
    except InfeasibleError as e:
        over = carried_over(cmd, f"{OVER_CHECKS[e.check].format(anchor=cmd.anchor)} ({e})") if e.check in OVER_CHECKS \
            else None
        if over is None:
            raise
        try:
            check(over, scene, plugins, arm)
        except InfeasibleError as carried:  # the slide's reason first, then why lifting it does not help
            raise InfeasibleError(e.check, f"{e}; carried over the other objects instead: {carried}", e.details) \
                from None
        except L2PError:
            raise e from None
        return over


def carried_over(cmd: Command, why: str) -> Command | None:
    """``cmd`` carried over the other objects (its manner's ``over``), where its verb names no manner ("move",
    ``MannerSpec.loose``) and its manner leaves the block ``why`` (kept in ``manner_why``); None where the verb
    says how ("slide"), the manner has no ``over``, or the manner is already not the verb's own."""
    manner = manners.get(cmd.manner)
    if not manner.over or cmd.verb not in manner.loose or cmd.manner_why:
        return None
    return replace(cmd, manner=manner.over, manner_why=f"carried over the other objects, which leave a {manner.name} "
                   f"{why}")


@dataclass
class Prepared:
    """What the cheap stages found (options checked, sentence parsed, scene feasible, plugin loaded):
    everything ``perform``, ``plan`` and an evaluation worker need before the expensive stages."""

    command: Command
    scene: Scene
    bundle: Any
    model: Any  # the bundle's numpy progress model
    judge: Any  # judge_for(bundle)
    arm: ArmSpec = PANDA  # the arm that performs it (its reach has fitted the scene's workspace)
    options: RunOptions = field(default_factory=RunOptions)  # checked; the stages after read them here


def prepare(sentence: str, scene: Scene, options: RunOptions | None = None, *, plugins: list | None = None,
            bundle: Any = None, clock: StageClock | None = None, **changes: Any) -> Prepared:
    """The stages before anything is planned or written: parse, feasibility, load (timed on ``clock``).

    A typo in an option, a sentence that names nothing, a scene the arm cannot do or a broken plugin
    fails here in milliseconds, before the disk is touched. ``options`` (with ``changes`` by name, e.g.
    ``seed=3``: ``RunOptions.of``): the arm's reach fits the scene's workspace (a block beyond it is refused).
    ``bundle``: use that loaded bundle instead of the installed plugin's (it must be the sentence's action).
    """
    opts = RunOptions.of(options, **changes)
    clock = clock or StageClock(opts.on_stage)
    clock.stage("parse")
    scene, arm = admit(scene, opts)  # a typo must fail before anything is loaded or written
    plugins = registry.discover() if plugins is None else plugins
    cmd = resolve(sentence, scene, plugins)
    return prepare_command(cmd, scene, arm, plugins, opts, bundle=bundle, clock=clock)


def prepare_command(cmd: Command, scene: Scene, arm: ArmSpec, plugins: list, options: RunOptions, *,
                    bundle: Any = None, clock: StageClock | None = None) -> Prepared:
    """:func:`prepare`'s stages after the parse, for ``cmd`` resolved in ``scene`` (admitted: checked and
    fitted to ``arm`` by :func:`~l2p_bullet.options.admit`): feasibility, then the plugin and its progress
    model."""
    clock = clock or StageClock(options.on_stage)
    clock.stage("feasibility")  # not "check": that is execute's own first sub-stage in summary.json
    cmd = feasible_as(cmd, scene, plugins, arm)
    if any(o.shape == "mesh" for o in scene.objects):  # a mesh that never comes to rest is refused now, by name
        from ..embodiment.sim.world import settled_scene

        # decomposes new meshes (kept) and settles the scene once: the run starts from the poses it rests in
        scene = settled_scene(scene)
    clock.stage("load", f'loading the plugin "{cmd.action}" and its progress model')
    if bundle is None:
        bundle = registry.load(cmd.action, plugins)  # a broken plugin fails here, before the disk is touched
    elif bundle.name != cmd.action:
        raise PluginError(f'the sentence asks for "{cmd.action}" but the bundle given is "{bundle.name}"')
    model = bundle.progress_model()
    judge = judge_for(bundle)
    clock.stop()
    return Prepared(cmd, scene, bundle, model, judge, arm, options)


def judged_plan(p: Prepared, options: RunOptions | None = None, *, time_limit: float | None = None,
                **changes: Any) -> tuple[Plan, dict[str, Any]]:
    """Plan the prepared command in 2-D and judge the plan with the bundle's judge: (plan, verdict).

    The plan maximises the action's learned progress; the judge only reads the result (the planner never
    sees it). The options are the prepared ones unless ``options`` or ``changes`` (by name) say otherwise.
    ``time_limit`` (seconds) also ends the search (an evaluation's equal-time comparisons).
    """
    cmd, opts = p.command, RunOptions.of(options or p.options, **changes)
    result = planning.plan(
        p.scene,
        cmd.mover,
        list(cmd.anchors),
        p.bundle,
        planner=opts.planner,
        seed=opts.seed,
        budget=opts.budget,
        threshold=opts.threshold,
        time_limit=time_limit,
        arm=p.arm,
        **manner_planning(manners.get(cmd.manner), p.scene.get(cmd.mover).size, p.arm),
    )
    result = apply_extent(result, cmd.extent, p.judge, p.scene)  # "far away from", "a bit closer to"
    result.extra.setdefault("sentence", cmd.sentence)
    result.extra.update(scene_fields(p.scene))  # replay PLAN.json executes it on this scene
    verdict = plan_verdict(p.judge, result, final_progress=result.extra.get("final_progress"),
                           outlines=outlines_of([p.scene.get(o) for o in (cmd.mover, *cmd.anchors)]))
    return result, already_said(verdict, result)


def perform(sentence: str, scene: Scene, options: RunOptions | None = None, *, plugins: list | None = None,
            world: Any = None, bundle: Any = None, **changes: Any) -> PerformResult:
    """Parse, plan, execute, record and judge the one action ``sentence`` asks for in ``scene``; write the run
    folder (``options``, with ``changes`` by name: ``RunOptions.of``). A chain's sentence goes through
    :func:`l2p_bullet.chain.perform_chain`, the front door for every sentence.

    ``world``: an open simulator world to execute in (``execute_path`` resets it to ``scene`` first, so
    the run records what a new world would); a batch (``l2p-bullet evaluate``) keeps one per process.

    Raises an :class:`L2PError` subclass for anything a user can get wrong (sentence, plugin, run
    folder, unreachable plan); the run folder, once created, gets a summary.json naming the stage that
    failed, so a failed run is still explained on disk. ``bundle`` performs with that loaded bundle
    instead of the installed plugin's (``l2p-bullet improve`` tries each round's re-trained bundle).
    """
    opts = RunOptions.of(options, **changes)
    clock = StageClock(opts.on_stage)
    p = prepare(sentence, scene, opts, plugins=plugins, bundle=bundle, clock=clock)
    return perform_prepared(p, clock, world=world)


def perform_prepared(p: Prepared, clock: StageClock, *, world: Any = None) -> PerformResult:
    """:func:`perform`'s stages after :func:`prepare`: plan, execute, judge, written into the run folder."""
    cmd, opts = p.command, p.options
    with run_folder(opts.out_dir, force=opts.force, prefix="perform", command="perform") as out:
        try:
            return _run(p, out, clock, world)
        except L2PError as e:
            clock.stop()
            write_summary(out / "summary.json", {
                "schema": 1, "sentence": cmd.sentence, "action": cmd.action, "ok": False,
                "failed_stage": clock.last, "error": str(e), "timings_s": clock.timings,
            })
            raise
        except KeyboardInterrupt:
            clock.stop()  # run_folder marks the run interrupted; the stage it was in is worth keeping
            write_summary(out / "summary.json", {
                **_summary_or_empty(out / "summary.json"), "sentence": cmd.sentence, "action": cmd.action,
                "interrupted_stage": clock.last, "timings_s": clock.timings})
            raise


def _summary_or_empty(path: Path) -> dict:
    try:
        d = json.loads(path.read_text())
    except (OSError, ValueError):
        return {"schema": 1}
    return d if isinstance(d, dict) else {"schema": 1}


def _run(p: Prepared, out: Path, clock: StageClock, world: Any = None) -> PerformResult:
    # lazy: the arm's modules (execution, recording, the simulator's facade) only when something is performed;
    # ``plan`` and the up-front refusals never load them
    from ..embodiment import execute

    cmd, scene, bundle, model, judge = p.command, p.scene, p.bundle, p.model, p.judge
    opts = p.options
    render, render_settings, seed = opts.render, opts.render_settings, opts.seed
    size = scene.get(cmd.mover).size
    clock.stage("plan", f"planning with the {opts.planner} planner")
    plan, planned_verdict = judged_plan(p)
    clock.stop()
    plan.save(out / "plan.json")
    viewer = getattr(model, "viewpoint", None)
    outlines = outlines_of([scene.get(o) for o in (cmd.mover, *cmd.anchors)])
    scorer = squares_scorer(model, scene.get(cmd.anchor), len(cmd.anchors))  # as the plan was scored

    def progress_fn(mover: np.ndarray, anchor: np.ndarray, more: list | None = None) -> np.ndarray:
        kw = {"more_anchors": more} if more else {}
        if outlines is not None and getattr(model, "reads_outlines", False):
            kw["outlines"] = outlines
        return np.asarray(scorer.curve(mover, anchor, size, **kw), float).reshape(-1)

    meta = {"sentence": cmd.sentence, "action": cmd.action, "anchor": cmd.anchor, "mover": cmd.mover}
    if cmd.more_anchors:
        meta["anchors"] = list(cmd.anchors)
    if cmd.manner != manners.DEFAULT:  # a slide's files name no manner
        meta["manner"] = cmd.manner
    if cmd.manner_why:
        meta["manner_why"] = cmd.manner_why
    if viewer is not None:
        meta["viewer"] = [float(v) for v in viewer]
    kwargs: dict[str, Any] = {"render": None}
    if render:
        kwargs = {} if render_settings is None else {"render": render_settings}
    stage_cb = (lambda s: clock.on_stage(f"  execute: {s}")) if clock.on_stage else None
    if is_standing(plan):  # the relation already holds: the arm stays at rest (planning/already.py)
        from ..embodiment.still import stand_still

        clock.stage("execute", "nothing to move: the relation already holds")
        kwargs = {"render": None}
        ex = stand_still(scene, cmd.mover, out_dir=out, progress_fn=progress_fn, meta=meta, world=world, arm=p.arm,
                         on_stage=stage_cb)
    else:
        clock.stage("execute", "executing with the arm" + ("" if render else " (no rendering)"))
        ex = execute.execute_path(scene, cmd.mover, plan.path, out_dir=out, seed=seed, progress_fn=progress_fn,
                                  meta=meta, on_stage=stage_cb, world=world, summary=False, arm=p.arm,
                                  manner=cmd.manner, approach_to=plan.approach_to, pace=cmd.pace, **kwargs)

    clock.stage("judge")
    mover, anchor = trajectory_poses(ex.frames, cmd.mover), trajectory_poses(ex.frames, cmd.anchor)
    prog = [f.get("progress") for f in ex.frames]
    final_progress = float(prog[-1]) if prog and prog[-1] is not None else None
    context = judge_context([trajectory_poses(ex.frames, a) for a in cmd.anchors], viewer, judge=judge,
                            outlines=outlines)
    verdict = disturbance_verdict(judge.judge(mover, anchor, size, final_progress=final_progress, **context).to_dict(),
                                  ex.displacements_m, cmd.anchor)
    if not is_standing(plan):  # nothing moved, in no manner: the verb's manner has nothing to show
        verdict = manner_verdict(verdict, manners.get(cmd.manner), ex.frames, cmd.mover,
                                 ex.rests_m.get(cmd.mover, scene.get(cmd.mover).rest))
    verdict = already_said(verdict, plan)
    final_error = float(np.hypot(*(mover[-1, :2] - plan.path[-1, :2])))
    clock.stop()
    clock.timings["total"] = clock.elapsed

    result = PerformResult(
        command=cmd, out_dir=out, plan=plan, verdict=verdict, final_progress=final_progress,
        planned_progress=float(plan.progress[-1]) if len(plan.progress) else float("nan"),
        max_deviation_m=float(ex.max_deviation_m), anchor_displacement_m=float(ex.anchor_displacement_m),
        final_error_m=final_error, timings=dict(clock.timings),
        files={"plan": out / "plan.json", **{k: Path(v) for k, v in ex.files.items()}},
        displacements_m=dict(ex.displacements_m), grasp=dict(ex.stats.get("grasp", {})),
        planned_verdict=planned_verdict,
    )
    base = execute.execution_summary(ex, meta, seed, kwargs.get("render", execute.DEFAULT_RENDER))
    base["arm"] = p.arm.name
    write_summary(out / "summary.json", perform_summary(base, result, bundle, seed))  # written once, here
    return result


def plan_sentence(sentence: str, scene: Scene, options: RunOptions | None = None, *,
                  plugins: list | None = None, **changes: Any) -> PlanResult:
    """Plan the one action ``sentence`` asks for in 2-D only and write plan.json (and plan.png unless
    ``plot`` is off) with the bundle's judge's verdict; ``options`` as :func:`perform`'s (the arm's reach and
    hand shape the plan). A chain's sentence goes through :func:`l2p_bullet.chain.plan.plan_chain`.
    """
    return plan_prepared(prepare(sentence, scene, RunOptions.of(options, **changes), plugins=plugins))


def plan_prepared(p: Prepared) -> PlanResult:
    """:func:`plan_sentence`'s stages after :func:`prepare` (:func:`judged_plan`); the verdict goes into
    plan.json's ``verdict``."""
    cmd, opts = p.command, p.options
    result, verdict = judged_plan(p)
    result.extra["verdict"] = verdict
    with run_folder(opts.out_dir, force=opts.force, prefix="plan", command="plan") as folder:
        result.save(folder / "plan.json")
        if opts.plot:
            plot_plan(result, p.scene, folder / "plan.png")  # the workspace fitted to the arm
    return PlanResult(cmd, result, verdict, folder)


def scene_fields(scene: Scene) -> dict[str, Any]:
    """What plan.json records of the scene it was planned on, so that ``replay PLAN.json`` executes it
    there: the scene itself (a few objects) and its digest."""
    return {"scene": scene.to_dict(), "scene_sha256": scene.digest()}


