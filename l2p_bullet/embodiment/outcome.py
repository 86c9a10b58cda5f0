"""What an execution leaves: the :class:`Execution` record, the honesty measures (how far the held block
strayed from its path, how far the others were pushed) and what summary.json says about it.

Apart from :mod:`.execute`, whose stages produce it, because other episodes are measured and summarised the
same way without those stages: a chain's clauses (chain/run.py, chain/files.py), a run that stands still
(still.py), a replay's summary (replay.py).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core.contracts import trajectory_poses
from . import motion
from .record import versions
from .sim.camera import RenderSettings


@dataclass
class Execution:
    """What happened. ``frames`` are trajectory.json's frames; distances in metres."""

    frames: list[dict]
    timings: dict[str, float]
    files: dict[str, Path]
    max_deviation_m: float  # the held block's largest distance from the planned path while sliding
    anchor_displacement_m: float  # the largest displacement of any block that was not held
    max_lift_m: float = 0.0  # how far the held block rose above resting on the table
    constraint_removed: bool = True
    duration_s: float = 0.0  # simulated time of the episode
    stats: dict = field(default_factory=dict)
    displacements_m: dict[str, float] = field(default_factory=dict)  # per block not held: its largest displacement
    render: dict | None = None  # how the frames were drawn (renderer used, camera, workers, wait): summary.json
    settled_m: dict[str, float] = field(default_factory=dict)  # per object, how far it moved settling (mesh scenes)
    # per object, its centre's height above the table as it rests at the start (settled, in a mesh scene): what
    # the manner judges measure 'on the table' from
    rests_m: dict[str, float] = field(default_factory=dict)


def honesty(frames: list[dict], mover: str, path: np.ndarray, slide: slice,
             rests: dict[str, float]) -> tuple[float, float, dict[str, float]]:
    """Deviation of the held block from the planned path (while sliding), its lift (above ``rests``, each
    object's centre height standing: a cube's half side), each other block's largest displacement from
    where it started."""
    deviation = 0.0
    if frames[slide]:
        pts = trajectory_poses(frames[slide], mover)[:, :2]
        deviation = float(motion.polyline_distance(pts, path[:, :2]).max())
    lift = max(f["poses"][mover][2] for f in frames) - rests[mover]
    displaced = {}
    for name in rests:
        if name != mover:
            xy = trajectory_poses(frames, name)[:, :2]
            displaced[name] = float(np.hypot(*(xy - xy[0]).T).max())
    return deviation, float(lift), displaced


def render_info(render: RenderSettings | None, film) -> dict | None:
    """summary.json's ``render``: the settings asked for and what the film did (the renderer it could start,
    EGL or Tiny; its workers; how long the episode waited for its frames)."""
    if render is None or film is None:
        return None
    return {"width": render.width, "height": render.height, "fps": render.fps, "renderer": film.renderer,
            "camera": film.settings.camera.to_dict(), "workers": film.workers, "wait_s": round(film.wall_s, 4)}


def execution_summary(ex: Execution, meta: dict, seed: int, render: RenderSettings | None) -> dict:
    """What summary.json says about an execution (a replay's whole summary; the start of perform's)."""
    return {
        "schema": 1,
        **{k: meta.get(k) for k in ("sentence", "action", "mover", "anchor")},
        "seed": seed,
        "timings_s": ex.timings,
        "simulated_s": round(ex.duration_s, 4),
        "execution": {
            "max_deviation_m": round(ex.max_deviation_m, 6),
            "anchor_displacement_m": round(ex.anchor_displacement_m, 6),
            "displacements_m": {k: round(v, 6) for k, v in ex.displacements_m.items()},
            "max_lift_m": round(ex.max_lift_m, 6),
            "constraint_removed": ex.constraint_removed,
            **ex.stats,
            # how far each object moved settling before the episode: its figures above count from there
            **({"settled_m": {k: round(v, 6) for k, v in ex.settled_m.items()}} if ex.settled_m else {}),
        },
        "render": ex.render,
        "files": {k: v.name for k, v in ex.files.items()},
        "versions": versions(),
        **{k: v for k, v in meta.items() if k not in ("sentence", "action", "mover", "anchor")},
    }
