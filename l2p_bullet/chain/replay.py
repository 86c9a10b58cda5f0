"""``replay`` of a chain run's plan.json: every clause's executed plan, in order, in one episode again.

The chain's plan.json keeps the scene the chain started from and each clause's plan as executed; the
simulation is deterministic, so replaying them in that scene reproduces the run (each clause's path still
has to start where its block is: replayed in another scene, it is refused as one-clause replays are).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..core.contracts import Plan
from ..core.scene import Scene
from ..core.timing import StageClock
from ..errors import L2PError, PathError
from ..judge import judge_for
from ..language import Command, manner_of_sentence
from ..plugins import registry
from .clauses import MAX_CLAUSES, Clause, resolve_clauses
from .forecast import Step
from .run import _execute


def is_chain_plan(doc: object) -> bool:
    """A chain run's plan.json (it lists its clauses' plans)."""
    return isinstance(doc, dict) and isinstance(doc.get("clauses"), list) and isinstance(doc.get("chain"), dict)


def check_chain_plan(doc: dict, source: str = "plan.json") -> None:
    """Refuse a chain plan.json with more clauses than a chain may have (a run stops at MAX_CLAUSES: a longer
    list is no run's, and replaying it would run for as long as its author liked)."""
    if len(doc["clauses"]) > MAX_CLAUSES:
        raise PathError(f"{source} lists {len(doc['clauses'])} clauses; a chain has at most {MAX_CLAUSES}")


def replay_chain(doc: dict, out: Path, *, scene: Scene | None = None, render_settings: Any = None, seed: int = 0,
                 on_stage=None, plugins: list | None = None, arm: str | None = None, path: str | None = None):
    """Execute the clauses' plans of ``doc`` (a chain's plan.json) into the run folder ``out``; returns the
    :class:`~l2p_bullet.chain.run.ChainResult` (verdicts by the installed actions' judges). ``arm``: who
    executes it (default the Panda; the scene's workspace is fitted to its reach). ``path``: the file ``doc`` was
    read from, recorded as a one-clause replay records its source (plan.json's and summary.json's ``replay``)."""
    from ..embodiment import arm_plugins

    source = "plan.json"
    check_chain_plan(doc, source if path is None else str(path))
    if scene is None:
        scene = Scene.from_dict(doc["chain"].get("scene"), source=f"{source}: chain.scene").validate()
    spec = arm_plugins.get(arm)
    scene = arm_plugins.fit_scene(scene, spec)
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
        if cmd is None or (cmd.mover, cmd.action, cmd.anchors, cmd.manner) != (plan.mover, plan.action, anchors, manner):
            cmd = Command("move", plan.mover, plan.action, plan.action, plan.anchor, text, anchors, manner)
        steps.append(Step(Clause(i, text, cmd), bundle, bundle.progress_model(), judge_for(bundle), plan))
    if not steps:
        raise PathError(f"{source}: no clause of the chain has a plan to replay")
    sentence = str(doc["chain"].get("sentence") or "; ".join(s.clause.text for s in steps))
    clock = StageClock(on_stage)
    return _execute(sentence, scene, steps, Path(out), clock, plugins, planner="replay", seed=seed,
                    render=render_settings is not None, budget=None, threshold=None,
                    render_settings=render_settings, world=None, replan=False, arm=spec,
                    replay={"source": {"plan": None if path is None else str(path)}})
