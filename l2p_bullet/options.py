"""What a run is asked to do: one :class:`RunOptions`, checked once at the front door, handed down whole.

``perform``, ``plan``, ``replay`` and the evaluation worker take the same choices (planner, seed, budget,
threshold, the arm, rendering, the output folder); each stage reads the fields it needs from one object
instead of a dozen parameters passed along by hand, so a new option is added in one place. :func:`admit`
makes the up-front checks every door makes, in the order that lets a typo fail in milliseconds, before
anything is loaded, planned or written.
"""

from __future__ import annotations

import numbers
from collections.abc import Callable
from dataclasses import dataclass, fields, replace
from pathlib import Path
from typing import Any

from .arms import ArmSpec, fit_scene
from .core.contracts import MAX_SEED
from .core.scene import Scene
from .embodiment.sim.arms import check_description
from .embodiment.sim.camera import RenderSettings
from .errors import ExecutionError, PlanError, SceneError
from .planning import resolve_planner
from .plugins import arms as arm_plugins

StageFn = Callable[[str], None]


@dataclass(frozen=True)
class RunOptions:
    """The choices of one run (``l2p-bullet perform/plan`` options, or a caller's): defaults are the CLI's."""

    planner: str = "default"
    seed: int = 0
    budget: int | None = None  # search steps at most (None: the planner's)
    threshold: float | None = None  # stop planning at this learned progress (None: 0.9 or the bundle's)
    arm: str | ArmSpec | None = None  # an arm's name (``l2p-bullet arms``) or spec; None: the Panda
    render: bool = True  # frames and a video (perform, replay)
    render_settings: RenderSettings | None = None  # None: the defaults
    out_dir: str | Path | None = None  # the run folder (None: runs/<command>-<time>)
    force: bool = False  # replace a finished run of l2p-bullet in ``out_dir``
    plot: bool = True  # plan.png beside plan.json (plan)
    on_stage: StageFn | None = None  # progress messages (None: quiet)

    @classmethod
    def of(cls, options: RunOptions | None = None, **changes: Any) -> RunOptions:
        """``options`` (default: the defaults) with ``changes``: the keyword spelling callers already use
        (``perform(sentence, scene, seed=3, render=False)``); an unknown name is a TypeError, as a call's."""
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(changes) - known)
        if unknown:
            raise TypeError(f"unknown run option(s) {', '.join(unknown)} (known: {', '.join(sorted(known))})")
        return replace(options or cls(), **changes)

    def check(self) -> RunOptions:
        """Self, once every option that can be checked without work is valid; else the first problem's
        one-line error. numpy's integers and floats count as numbers (a seed drawn from a generator)."""
        check_options(self.planner, self.seed, self.budget, self.threshold)
        if self.render:
            check_render_settings(self.render_settings)
        return self

    def arm_spec(self) -> ArmSpec:
        """The arm that performs (an unknown name fails here, before anything is planned or written)."""
        return arm_plugins.get(self.arm)


def admit(scene: object, options: RunOptions) -> tuple[Scene, ArmSpec]:
    """The up-front checks of every front door, in order: the options, the scene, the arm; returns the scene
    with its workspace fitted to the arm's reach (a block beyond it is refused) and the arm."""
    options.check()
    scene = check_scene(scene)
    arm = options.arm_spec()
    check_description(arm)  # a URDF PyBullet would crash on: refused before a folder is made
    return fit_scene(scene, arm), arm


def check_options(planner: str, seed: int, budget: int | None = None, threshold: float | None = None) -> None:
    """The planning options of ``perform``/``plan`` (and ``evaluate``'s), checked before any folder is touched."""
    resolve_planner(planner)
    if not _integer(seed) or not 0 <= seed <= MAX_SEED:
        raise PlanError(f"the seed must be an integer from 0 to {MAX_SEED} (got {str(seed)[:20]})")
    if budget is not None and (not _integer(budget) or budget < 1):
        raise PlanError(f"the budget must be a positive number of search steps (got {str(budget)[:20]})")
    if threshold is not None and not (isinstance(threshold, numbers.Real) and not isinstance(threshold, bool)
                                      and 0.0 <= threshold <= 1.0):
        raise PlanError(f"the threshold must be a progress between 0 and 1 (got {str(threshold)[:20]})")


def check_scene(scene: object) -> Scene:
    """``scene`` as the front door takes it: a :class:`Scene` (``core.scene.load_scene`` reads a file), checked."""
    if not isinstance(scene, Scene):
        raise SceneError(f"the scene must be a l2p_bullet.core.scene.Scene (got {type(scene).__name__}); read a "
                         "scene file with load_scene(path), or build one with Scene.from_dict(...)")
    return scene.validate()


def check_render_settings(settings: object) -> None:
    """None (the defaults) or valid :class:`~l2p_bullet.embodiment.sim.camera.RenderSettings`."""
    if settings is None:
        return
    if not isinstance(settings, RenderSettings):
        raise ExecutionError(f"render_settings must be a RenderSettings (got {type(settings).__name__})")
    settings.check()


def _integer(v: object) -> bool:
    return isinstance(v, numbers.Integral) and not isinstance(v, bool)
