"""Tasks: one run of one action on one scene, as plain data a worker process (or a Ray actor) can receive.

A task carries everything its run depends on (the scene as a dict, the sentence, planner, seed, mode,
rendering), so a run's result depends on the task alone, never on which worker ran it or what that
worker ran before: the reason parallel results equal serial ones, run for run.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from pathlib import Path

from ..errors import EvaluationError
from ..manners import registry as manner_registry
from ..options import RunOptions
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
    chain_draw: str = "clause"  # chain mode: "clause" (each drawn until it plans) or "sentence" (drawn whole first)
    arm: str = "panda"  # the arm that performs it (l2p-bullet arms)
    more_anchors: tuple[str, ...] = ()  # a two-anchor action's further reference blocks ("between B and C": C)
    manner: str = "slide"  # the manner of motion (l2p_bullet/manners): the sentence's verb says it

    def to_dict(self) -> dict:
        return asdict(self)

    def options(self, out: str | Path | None = None) -> RunOptions:
        """What the task asks of its run (planner, seed, budget, threshold, arm, rendering), into ``out``."""
        return RunOptions(planner=self.planner, seed=self.seed, budget=self.budget, threshold=self.threshold,
                          arm=self.arm, render=self.render, out_dir=out, force=True)


def sentence_for(action: str, mover: str, anchor: str | Sequence[str], plugins: list, verb: str = "move") -> str:
    """``move MOVER <the action's first phrase> ANCHOR [and ANCHOR]``, e.g. "move A closer to B",
    "move A between B and C" (one anchor per reference block the action declares); ``verb`` picks the
    manner ("carry A past B")."""
    info = registry.find(action, plugins)
    phrase = info.phrases[0] if info.phrases else action
    anchors = [anchor] if isinstance(anchor, str) else list(anchor)
    return f"{verb} {mover} {phrase} {' and '.join(anchors)}"


def anchors_for(spec: SceneSpec, n: int) -> list[str] | None:
    """The ``n`` reference blocks of a run on ``spec``: its anchor, then the scene's next blocks in order
    (neither mover nor anchor); None when the scene has too few blocks for an ``n``-anchor action."""
    others = [name for name in spec.scene.names if name not in (spec.mover, spec.anchor)]
    return [spec.anchor, *others[: n - 1]] if len(others) >= n - 1 else None


def skipped(scenes: list[SceneSpec], actions: list[str], plugins: list) -> dict[str, str]:
    """action -> why some or all of its runs are left out of the evaluation (printed before it starts).

    A two-anchor action ("between") runs only on scenes with a block besides the mover and the anchor;
    :func:`make_tasks` leaves the other scenes out for it, rather than asking "move A between B".
    """
    from ..plugins import registry

    out: dict[str, str] = {}
    for a in actions:
        info = registry.find(a, plugins)
        if info.anchors < 2:
            continue
        short = sum(anchors_for(s, info.anchors) is None for s in scenes)
        if short:
            need = info.anchors + 1
            out[info.name] = (f'"{info.name}" names {info.anchors} reference blocks: skipped on {short} of '
                              f"{len(scenes)} scenes with fewer than {need} blocks (add blocks with --bystanders "
                              f"{need - 2}, or give a --scene-file with {need} blocks per scene)")
    return out


def make_tasks(scenes: list[SceneSpec], actions: list[str], *, planner: str = "default", mode: str = "perform",
               render_every: int = 0, keep: str = "none", out_dir: str | None = None, plugins: list | None = None,
               budget: int | None = None, threshold: float | None = None,
               arm: str = "panda", manners: Sequence[str] = ("slide",)) -> list[Task]:
    """Every scene x action x manner, scene-major (all actions of scene 0 first), numbered in that order. A
    run of a manner other than slide has it in its run id and folder name (a slide's are as before).

    ``render_every`` K > 0 renders (and keeps) every K-th run of each action: runs 0, K, 2K, ...
    """
    if mode not in MODES:
        raise EvaluationError(f'unknown mode "{mode}" (known: {", ".join(MODES)})')
    if keep not in KEEP:
        raise EvaluationError(f'unknown --keep "{keep}" (known: {", ".join(KEEP)})')
    plugins = registry.discover() if plugins is None else plugins
    infos = [registry.find(a, plugins) for a in actions]
    tasks: list[Task] = []
    for i, spec in enumerate(scenes):
        for info in infos:
            action, anchors = info.name, anchors_for(spec, info.anchors)
            if anchors is None:  # too few blocks for this action (see skipped)
                continue
            render = mode == "perform" and render_every > 0 and i % render_every == 0
            for manner in manners:
                tag = "" if manner == "slide" else f"|{manner}"
                run_id = f"{spec.id}|{action}|{planner}|{mode}{tag}"
                run_dir = None if out_dir is None else \
                    f"{out_dir}/runs/{_safe(spec.id)}--{action}--{planner}--{mode}{tag.replace('|', '--')}"
                verb = manner_registry.sentence_verb(manner)
                tasks.append(Task(run_id, len(tasks), spec.id, spec.source, spec.scene.to_dict(), spec.mover,
                                  spec.anchor, action, sentence_for(action, spec.mover, anchors, plugins, verb),
                                  planner, spec.seed, mode, render, keep, run_dir, budget, threshold,
                                  more_anchors=tuple(anchors[1:]), arm=arm, manner=manner))
    return tasks


def _safe(text: str) -> str:
    """A file-name-safe form of a scene id ("random/17+2by" -> "random-17+2by")."""
    return re.sub(r"[^A-Za-z0-9+._-]+", "-", text).strip("-")
