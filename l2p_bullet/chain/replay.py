"""``replay``: a motion (a plan.json, a scoring input, a demonstration) or a chain run's plan.json executed by
the arm again, through one door (:func:`replay`) that reads the file once and picks the replayer.

A chain's plan.json: every clause's executed plan, in order, in one episode again.

The chain's plan.json keeps the scene the chain started from and each clause's plan as executed; the
simulation is deterministic, so replaying them in that scene reproduces the run (each clause's path still
has to start where its block is: replayed in another scene, it is refused as one-clause replays are).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..arms import fit_scene
from ..core.contracts import Plan, read_json
from ..core.runfolder import run_folder
from ..core.scene import Scene, load_scene
from ..core.timing import StageClock
from ..embodiment.replay import motion_source, replay_scene, run_replay
from ..errors import L2PError, PathError
from ..judge import judge_for
from ..language import Command, manner_of_sentence
from ..options import RunOptions
from ..pipeline import moved_text
from ..plugins import arms as arm_plugins
from ..plugins import registry
from .clause import MAX_CLAUSES, Clause
from .clauses import resolve_clauses
from .forecast import Step
from .run import ChainResult, _execute


@dataclass
class MotionReplay:
    """What ``replay`` did with one motion: what was replayed, the execution's result, the run folder."""

    label: str
    execution: Any  # embodiment.execute's result: duration, deviation, files
    out_dir: Path
    anchor: str | None = None  # the motion's reference block, when it has one: named apart from bystanders

    def text(self) -> list[str]:
        ex, video = self.execution, self.execution.files.get("video")
        return [f"replayed {self.label}: {ex.duration_s:.1f} s simulated, "
                f"block within {ex.max_deviation_m * 1000:.1f} mm of its path, "
                f"{moved_text(ex.displacements_m, [self.anchor] if self.anchor else [])}",
                f"run folder: {self.out_dir}" + (f"\nvideo: {video}" if video else " (no video: --no-render)")]


@dataclass
class ChainReplay:
    """What ``replay`` did with a chain run's plan.json: the file, the chain's result, the run folder."""

    source: str
    result: ChainResult
    out_dir: Path

    def text(self) -> list[str]:
        v = self.result.verdict()
        return [f"replayed the chain {self.source}: {v['completed']} of {v['clauses']} clauses done ({v['reason']})",
                f"run folder: {self.out_dir}"]


def replay(path: str | None, demo: str | None, options: RunOptions, *, scene_path: str | None = None,
           mesh_dirs: tuple = (), mover: str = "A", anchor: str = "B") -> MotionReplay | ChainReplay:
    """Replay ``path`` (a plan.json, a chain run's plan.json or a scoring input) or the demonstration ``demo``
    ("around:0") with the options' arm, seed and rendering into their run folder.

    ``scene_path`` (its meshes from its folder or ``mesh_dirs``): where to replay it; a plan.json's recorded
    scene otherwise (a mismatch is refused). ``mover``/``anchor``: the blocks of a demonstration or a scoring
    input. The run folder never replaces what it reads (``path``, ``scene_path``)."""
    arm = options.arm_spec()  # an unknown arm fails before anything is read or written
    render = options.render_settings if options.render else None
    inputs = tuple(p for p in (path, scene_path) if p)
    doc = read_json(path) if path is not None else None
    scene = None if scene_path is None else load_scene(scene_path, mesh_dirs)
    if is_chain_plan(doc):
        check_chain_plan(doc, str(path))  # before the run folder is made
        with run_folder(options.out_dir, force=options.force, prefix="replay", command="replay",
                        inputs=inputs) as folder:
            r = replay_chain(doc, folder, scene=scene, render_settings=render, seed=options.seed,
                             on_stage=options.on_stage, arm=arm, path=path)
        return ChainReplay(str(path), r, folder)
    scene = fit_scene(replay_scene(path, scene, scene_path, mesh_dirs), arm)  # what the arm reaches
    source = motion_source(path, demo, scene, mover, anchor)
    with run_folder(options.out_dir, force=options.force, prefix="replay", command="replay",
                    inputs=inputs) as folder:
        ex = run_replay(scene, source, folder, render, options.seed, on_stage=options.on_stage, arm=arm)
    return MotionReplay(source.label, ex, folder, source.anchor)


def is_chain_plan(doc: object) -> bool:
    """A chain run's plan.json (it lists its clauses' plans)."""
    return isinstance(doc, dict) and isinstance(doc.get("clauses"), list) and isinstance(doc.get("chain"), dict)


def check_chain_plan(doc: dict, source: str = "plan.json") -> None:
    """Refuse a chain plan.json with more clauses than a chain may have (a run stops at MAX_CLAUSES: a longer
    list is no run's, and replaying it would run for as long as its author liked)."""
    if len(doc["clauses"]) > MAX_CLAUSES:
        raise PathError(f"{source} lists {len(doc['clauses'])} clauses; a chain has at most {MAX_CLAUSES}")


def replay_chain(doc: dict, out: Path, *, scene: Scene | None = None, render_settings: Any = None, seed: int = 0,
                 on_stage=None, plugins: list | None = None, arm: str | None = None,
                 path: str | None = None) -> ChainResult:
    """Execute the clauses' plans of ``doc`` (a chain's plan.json) into the run folder ``out``; returns the
    :class:`~l2p_bullet.chain.run.ChainResult` (verdicts by the installed actions' judges). ``arm``: who
    executes it (default the Panda; the scene's workspace is fitted to its reach). ``path``: the file ``doc`` was
    read from, recorded as a one-clause replay records its source (plan.json's and summary.json's ``replay``)."""
    source = "plan.json"
    check_chain_plan(doc, source if path is None else str(path))
    if scene is None:
        scene = Scene.from_dict(doc["chain"].get("scene"), source=f"{source}: chain.scene").validate()
    spec = arm_plugins.get(arm)
    scene = fit_scene(scene, spec)
    plugins = registry.discover() if plugins is None else plugins
    try:  # the clauses' own words (verb, preposition) as the run recorded them; another --scene may lack a name
        said = {c.index: c.command for c in resolve_clauses(str(doc["chain"].get("sentence") or ""), scene, plugins)}
    except L2PError:
        said = {}
    steps = []
    executed = any(isinstance(c, dict) and c.get("plan") for c in doc["clauses"])
    for i, c in enumerate(doc["clauses"], start=1):
        # the plan a run executed, else (``l2p-bullet plan`` wrote the file) the up-front forecast
        raw = (c.get("plan") if executed else c.get("forecast")) if isinstance(c, dict) else None
        if not isinstance(raw, dict):
            break  # the run never planned this clause (it stopped before): nothing to replay from here on
        plan = Plan.from_dict(raw, source=f"{source}: clause {i}")
        text = str(c.get("text") or f"move {plan.mover} {plan.action} {plan.anchor}")
        anchors = tuple([plan.anchor, *plan.more_anchors])
        for name in (plan.mover, *anchors):
            scene.get(name)
        bundle = registry.load(plan.action, plugins)
        manner = manner_of_sentence(text)  # "carry A past B": carried again (its path may cross blocks)
        cmd = said.get(i)
        if cmd is None or (cmd.mover, cmd.action, cmd.anchors, cmd.manner) != (
            plan.mover,
            plan.action,
            anchors,
            manner,
        ):
            cmd = Command("move", plan.mover, plan.action, plan.action, plan.anchor, text, anchors, manner)
        steps.append(Step(Clause(i, text, cmd), bundle, bundle.progress_model(), judge_for(bundle), plan))
    if not steps:
        raise PathError(f"{source}: no clause of the chain has a plan to replay")
    sentence = str(doc["chain"].get("sentence") or "; ".join(s.clause.text for s in steps))
    clock = StageClock(on_stage)
    options = RunOptions(seed=seed, render=render_settings is not None, render_settings=render_settings)
    return _execute(sentence, scene, steps, Path(out), clock, plugins, options, spec, replan=False,
                    replay={"source": {"plan": None if path is None else str(path)}})
