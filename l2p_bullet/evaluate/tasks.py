"""Tasks: one run of one action on one scene, as plain data a worker process (or a Ray actor) can receive.

A task carries everything its run depends on (the scene as a dict, the sentence, planner, seed, mode,
rendering), so a run's result depends on the task alone, never on which worker ran it or what that
worker ran before: the reason parallel results equal serial ones, run for run.
"""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass

from ..errors import EvaluationError
from ..plugins import registry
from .scenes import SceneSpec

MODES = ("perform", "plan", "chain")
KEEP = ("none", "failed", "all")


@dataclass(frozen=True)
class Task:
    """One run. ``run_id`` (scene id, action, planner, mode) is the results table's primary key."""

    run_id: str
    index: int
    scene_id: str
    scene_source: str
    scene: dict
    mover: str
    anchor: str
    action: str
    sentence: str
    planner: str
    seed: int
    mode: str = "perform"
    render: bool = False
    keep: str = "none"
    run_dir: str | None = None  # where the run folder goes when it is kept
    budget: int | None = None
    threshold: float | None = None
    time_limit: float | None = None  # seconds of planning (equal-time comparisons); plan mode only
    chain_length: int = 0  # chain mode: clauses per chain, drawn by the worker over chain_actions (chains.py)
    chain_actions: tuple[str, ...] = ()

    def to_dict(self) -> dict:
        return asdict(self)


def sentence_for(action: str, mover: str, anchor: str, plugins: list) -> str:
    """``move MOVER <the action's first phrase> ANCHOR``, e.g. "move A closer to B"."""
    info = registry.find(action, plugins)
    phrase = info.phrases[0] if info.phrases else action
    return f"move {mover} {phrase} {anchor}"


def make_tasks(scenes: list[SceneSpec], actions: list[str], *, planner: str = "default", mode: str = "perform",
               render_every: int = 0, keep: str = "none", out_dir: str | None = None, plugins: list | None = None,
               budget: int | None = None, threshold: float | None = None) -> list[Task]:
    """Every scene x action, scene-major (all actions of scene 0 first), numbered in that order.

    ``render_every`` K > 0 renders (and keeps) every K-th run of each action: runs 0, K, 2K, ...
    """
    if mode not in MODES:
        raise EvaluationError(f'unknown mode "{mode}" (known: {", ".join(MODES)})')
    if keep not in KEEP:
        raise EvaluationError(f'unknown --keep "{keep}" (known: {", ".join(KEEP)})')
    plugins = registry.discover() if plugins is None else plugins
    names = [registry.find(a, plugins).name for a in actions]
    tasks: list[Task] = []
    for i, spec in enumerate(scenes):
        for action in names:
            render = mode == "perform" and render_every > 0 and i % render_every == 0
            run_id = f"{spec.id}|{action}|{planner}|{mode}"
            run_dir = None if out_dir is None else f"{out_dir}/runs/{_safe(spec.id)}--{action}--{planner}--{mode}"
            tasks.append(Task(run_id, len(tasks), spec.id, spec.source, spec.scene.to_dict(), spec.mover, spec.anchor,
                              action, sentence_for(action, spec.mover, spec.anchor, plugins), planner, spec.seed,
                              mode, render, keep, run_dir, budget, threshold))
    return tasks


def _safe(text: str) -> str:
    """A file-name-safe form of a scene id ("random/17+2by" -> "random-17+2by")."""
    return re.sub(r"[^A-Za-z0-9+._-]+", "-", text).strip("-")
