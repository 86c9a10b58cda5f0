"""Checks of what a user hands Plan2D-v0 and Arm-v0: constructor arguments, reset options, actions.

Why a module of its own: each check turns a mistake into a one-line :class:`~l2p_bullet.errors.L2PError`
that says what to do, where it used to surface as a numpy ``ValueError`` from inside ``step``, an
``AttributeError`` from inside ``reset``, or nothing at all (a threshold of 5, an unknown option key),
and plan2d.py keeps only the episode.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from numbers import Integral, Real
from typing import Any

import numpy as np
from gymnasium import spaces
from gymnasium.error import ResetNeeded

from ..core.scene import MAX_SIZE, MIN_SIZE, Scene
from ..errors import L2PError, SceneError, did_you_mean

RESET_OPTIONS = ("scene", "mover", "anchor")
"""The keys ``reset(options=...)`` understands; any other is an error (a typo like "scen" used to be ignored)."""


class EnvError(L2PError, ValueError):
    """A bad constructor argument, reset option or action for Plan2D-v0 / Arm-v0.

    Also a ``ValueError``: the constructor raised plain ``ValueError`` for a bad ``size`` or ``render_mode``
    before, and code that catches that keeps working.
    """


class EnvResetNeeded(L2PError, ResetNeeded):
    """``step()`` with no episode running: before the first ``reset()``, after a failed one, or after the episode ended.

    Also Gymnasium's ``ResetNeeded``, the error its order-enforcing wrapper (``gym.make``) raises for a
    step before the first reset, so that every "call reset() first" reads and catches the same, wrapped or not.
    """


def number(name: str, value: object, lo: float, hi: float = math.inf, *, lo_open: bool = False) -> float:
    """``value`` as a float in [lo, hi] (or (lo, hi] with ``lo_open``), else a one-line :class:`EnvError`."""
    ok = isinstance(value, Real) and not isinstance(value, bool) and math.isfinite(float(value))
    if ok:
        v = float(value)
        ok = (v > lo if lo_open else v >= lo) and v <= hi
    if not ok:
        rng = (
            f"in {'(' if lo_open else '['}{lo:g}, {hi:g}]"
            if math.isfinite(hi)
            else f"{'>' if lo_open else '>='} {lo:g}"
        )
        raise EnvError(f"{name} must be a finite number {rng}, got {value!r}")
    return float(value)


def check_args(*, render_mode: str | None, render_modes: list[str], max_steps: object, max_move: object,
               threshold: object, size: object, illegal_penalty: object) -> dict[str, Any]:
    """The constructor's arguments, checked against the ranges docs/envs.md gives; returns them as floats/ints."""
    if render_mode is not None and render_mode not in render_modes:
        raise EnvError(f"render_mode must be one of {render_modes} or None, got {render_mode!r}")
    if not isinstance(max_steps, Integral) or isinstance(max_steps, bool) or max_steps < 1:
        raise EnvError(f"max_steps must be a whole number >= 1, got {max_steps!r}")
    return {"max_steps": int(max_steps),
            "max_move": number("max_move", max_move, 0.0, lo_open=True),
            # progress is in [0, 1]: a threshold above 1 could never be reached, one of 0 is reached at reset
            "threshold": None if threshold is None else number("threshold", threshold, 0.0, 1.0, lo_open=True),
            "size": number("size (the block side, m)", size, MIN_SIZE, MAX_SIZE),
            "illegal_penalty": number("illegal_penalty", illegal_penalty, 0.0)}


def check_options(options: object) -> tuple[Scene | None, str, str]:
    """``reset``'s options as (scene or None for a random one, mover, anchor), checked before anything changes.

    ``scene`` is a :class:`Scene` or a dict in the scene-file format (``Scene.from_dict``); a path is refused
    rather than read, so that a reset never touches the disk (load it once with ``load_scene``).
    """
    if options is None:
        options = {}
    if not isinstance(options, Mapping):
        raise EnvError(
            f"reset options must be a dict with keys {', '.join(RESET_OPTIONS)}, got {type(options).__name__}"
        )
    for key in options:
        if key not in RESET_OPTIONS:
            raise EnvError(f"unknown reset option {key!r} (known: {', '.join(RESET_OPTIONS)})."
                           + did_you_mean(str(key), RESET_OPTIONS))
    mover, anchor = options.get("mover", "A"), options.get("anchor", "B")
    for key, name in (("mover", mover), ("anchor", anchor)):
        if not isinstance(name, str) or not name:
            raise EnvError(f"options['{key}'] must be an object's name (a non-empty str), got {name!r}")
    if mover == anchor:
        raise EnvError(f'options: the mover and the anchor are both "{mover}": name two different objects')
    scene = options.get("scene")
    if scene is None:
        return None, mover, anchor
    if isinstance(scene, dict):
        scene = Scene.from_dict(scene, source="options['scene']")
    elif not isinstance(scene, Scene):
        raise SceneError(f"options['scene'] must be a Scene or a dict in the scene-file format, got "
                         f"{type(scene).__name__} (for a file: options={{'scene': load_scene(path)}})")
    scene.validate()
    check_names(scene, mover, anchor)
    return scene, mover, anchor


def check_names(scene: Scene, mover: str, anchor: str) -> None:
    """Both objects exist in ``scene`` (:class:`~l2p_bullet.errors.UnknownObjectError` otherwise)."""
    scene.get(mover)
    scene.get(anchor)


def check_action(action: object, space: spaces.Box, what: str | None = None) -> np.ndarray:
    """``action`` as the space's count of float64 numbers (any shape holding them: (3,), (1, 3), (3, 1)),
    clipped to ``space``; ``what`` names the numbers in errors (default: a block move's dx, dy, dyaw).

    +-inf is clipped to the bound like any large number; NaN has no bound to clip to (``np.clip`` passes
    it through, and the move then failed the workspace test as if it were illegal), so it is an error.
    """
    try:
        arr = np.asarray(action)
    except Exception:  # an object numpy cannot make an array of
        arr = np.asarray(None)
    n = int(np.prod(space.shape))
    want = (f"3 numbers (dx, dy, dyaw) in the action space Box(3,): |dx|, |dy| <= {float(space.high[0]):g}, "
            f"|dyaw| <= {float(space.high[2]):.4g}") if what is None else f"{n} numbers ({what}) in [-1, 1]"
    if arr.dtype.kind not in "iuf":
        raise EnvError(f"an action must be {want}, got {_short(action)}")
    a = arr.astype(np.float64).reshape(-1)
    if a.size != n:
        got = f"an array of shape {arr.shape}" if isinstance(action, np.ndarray) else _short(action)
        raise EnvError(f"an action must be {want}, got {got}")
    if np.isnan(a).any():
        raise EnvError(f"an action must be {want}, got NaN in {a.tolist()}")
    return np.clip(a, space.low, space.high)


def _short(value: object) -> str:
    text = repr(value).replace("\n", " ")
    return f"{type(value).__name__} {text[:60]}{'...' if len(text) > 60 else ''}"
