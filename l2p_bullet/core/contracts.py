"""The file contracts of DESIGN.md section 4 that carry motions: plan.json, trajectory.json, scoring inputs.

The plan (:class:`Plan`) is also what the planner hands to the executor. Readers accept the three formats of DESIGN.md section 4 and say clearly what is wrong with a bad file:
- the scoring input ``{"size", "mover": [[x, y, theta], ...], "anchor": [...]}``;
- a run folder's ``plan.json``;
- a run folder's ``trajectory.json``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import PathError


@dataclass
class Plan:
    """The planner's output and plan.json's content (schema 1). Poses are [x, y, yaw] in the scene frame."""

    action: str
    mover: str
    anchor: str
    size: float
    anchor_pose: np.ndarray
    start: np.ndarray
    path: np.ndarray  # (N, 3), from start to goal
    progress: np.ndarray  # (N,), per path point
    planner: str
    stopped: str  # "threshold" | "budget"
    extra: dict = field(default_factory=dict)  # added fields (timings, steps...): contracts only grow

    def to_dict(self) -> dict:
        return {
            "schema": 1,
            "action": self.action,
            "mover": self.mover,
            "anchor": self.anchor,
            "size": float(self.size),
            "anchor_pose": [float(v) for v in self.anchor_pose],
            "start": [float(v) for v in self.start],
            "path": np.asarray(self.path, float).round(6).tolist(),
            "progress": np.asarray(self.progress, float).round(6).tolist(),
            "planner": self.planner,
            "stopped": self.stopped,
            **self.extra,
        }

    def save(self, path: str | Path) -> None:
        Path(path).write_text(json.dumps(self.to_dict(), indent=1) + "\n")

    @classmethod
    def from_dict(cls, d: dict, source: str = "plan") -> Plan:
        try:
            known = {"schema", "action", "mover", "anchor", "size", "anchor_pose", "start", "path",
                     "progress", "planner", "stopped"}
            return cls(
                action=str(d["action"]),
                mover=str(d["mover"]),
                anchor=str(d["anchor"]),
                size=float(d["size"]),
                anchor_pose=_poses(d["anchor_pose"], source, "anchor_pose").reshape(3),
                start=_poses(d["start"], source, "start").reshape(3),
                path=_poses(d["path"], source, "path"),
                progress=np.asarray(d.get("progress", []), float),
                planner=str(d.get("planner", "unknown")),
                stopped=str(d.get("stopped", "unknown")),
                extra={k: v for k, v in d.items() if k not in known},
            )
        except KeyError as e:
            raise PathError(f'{source}: plan is missing the field "{e.args[0]}"') from None
        except (TypeError, ValueError) as e:  # "size": "big", "action": {...}: a malformed plan, not a bug
            raise PathError(f"{source}: malformed plan ({e})") from None


@dataclass
class Motion:
    """Mover and anchor pose sequences of equal length, in one metric frame, blocks of side ``size``."""

    mover: np.ndarray  # (T, 3)
    anchor: np.ndarray  # (T, 3)
    size: float
    mover_name: str | None = None
    anchor_name: str | None = None
    action: str | None = None


def _poses(value: object, source: str, key: str) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise PathError(f'{source}: "{key}" must be numbers') from None
    if arr.ndim == 1:
        arr = arr[None]
    if arr.ndim != 2 or arr.shape[1] != 3 or len(arr) == 0:
        raise PathError(f'{source}: "{key}" must be a list of [x, y, theta] poses (got shape {arr.shape})')
    if not np.all(np.isfinite(arr)):
        raise PathError(f'{source}: "{key}" contains non-finite numbers')
    return arr


def trajectory_poses(frames: list[dict], name: str) -> np.ndarray:
    """(T,3) ``[x, y, yaw]`` of object ``name`` from trajectory.json frames (their poses are [x, y, z, yaw])."""
    return np.array([[f["poses"][name][0], f["poses"][name][1], f["poses"][name][3]] for f in frames], float)


def read_json(path: str | Path) -> dict:
    p = Path(path)
    try:
        data = json.loads(p.read_text())
    except OSError as e:
        raise PathError(f"cannot read {p}: {e.strerror or e}") from None
    except json.JSONDecodeError as e:
        raise PathError(f"{p} is not valid JSON (line {e.lineno}, column {e.colno}: {e.msg})") from None
    if not isinstance(data, dict):
        raise PathError(f"{p}: expected a JSON object")
    return data


def motion_from_dict(d: dict, source: str = "motion") -> Motion:
    """Interpret a scoring input, a plan.json or a trajectory.json as a :class:`Motion`."""
    if "frames" in d:  # trajectory.json
        try:
            mover, anchor = str(d["mover"]), str(d["anchor"])
            m_arr = trajectory_poses(d["frames"], mover)
            a_arr = trajectory_poses(d["frames"], anchor)
            size = float(d["objects"][mover]["size"])
        except (KeyError, TypeError, IndexError, ValueError) as e:
            raise PathError(f"{source}: not a valid trajectory.json ({type(e).__name__}: {e})") from None
        return Motion(_poses(m_arr, source, "frames"), _poses(a_arr, source, "frames"), size, mover, anchor,
                      d.get("action"))
    if "path" in d:  # plan.json
        plan = Plan.from_dict(d, source)
        anchor = np.repeat(plan.anchor_pose[None], len(plan.path), axis=0)
        return Motion(plan.path, anchor, plan.size, plan.mover, plan.anchor, plan.action)
    for key in ("size", "mover", "anchor"):
        if key not in d:
            raise PathError(
                f'{source}: missing "{key}" (expected a scoring input {{"size", "mover", "anchor"}}, '
                "a plan.json or a trajectory.json)"
            )
    mover = _poses(d["mover"], source, "mover")
    anchor = _poses(d["anchor"], source, "anchor")
    if len(anchor) == 1:
        anchor = np.repeat(anchor, len(mover), axis=0)
    if len(mover) != len(anchor):
        raise PathError(f'{source}: "mover" has {len(mover)} poses but "anchor" has {len(anchor)}')
    try:
        size = float(d["size"])
    except (TypeError, ValueError):
        raise PathError(f'{source}: "size" must be a number') from None
    if not size > 0:
        raise PathError(f'{source}: "size" must be positive')
    return Motion(mover, anchor, size)


def load_motion(path: str | Path) -> Motion:
    return motion_from_dict(read_json(path), source=str(path))
