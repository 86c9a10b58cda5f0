"""The file contracts of DESIGN.md section 4 that carry motions: plan.json, trajectory.json, scoring inputs.

The plan (:class:`Plan`) is also what the planner hands to the executor. Readers accept the three formats of DESIGN.md
section 4 and say clearly what is wrong with a bad file:
- the scoring input ``{"size", "mover": [[x, y, theta], ...], "anchor": [...]}``;
- a run folder's ``plan.json``;
- a run folder's ``trajectory.json``.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import L2PError, PathError, sizes
from .bounded import read_bounded

MAX_SEED = 2**32 - 1
"""Seeds are what numpy's and torch's generators accept alike: 0 to 2**32 - 1 (summary.json's ``seed``,
every command's ``--seed``, a scene file's per-line seed)."""

MAX_JSON_BYTES = 64 * 1024 * 1024
"""The largest JSON input read (a scene, a plan, a trajectory, a scoring input): a 20 s run's
trajectory.json is about 150 kB, so this only stops a file that would exhaust memory."""


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
    more_anchors: list[str] = field(default_factory=list)  # a two-anchor action's further anchors
    more_anchor_poses: np.ndarray | None = None  # (k, 3), their poses
    viewer: np.ndarray | None = None  # (2,) the viewpoint of a viewer-frame action, scene frame

    @property
    def approach_to(self) -> np.ndarray | None:
        """Where the plan's approach slide ends ([x, y, yaw], "around" from afar: ``extra.approach.to``), the
        start of the action proper; None for a plan without one."""
        approach = self.extra.get("approach")
        to = approach.get("to") if isinstance(approach, dict) else None
        return None if to is None else np.asarray(to, float)

    @property
    def anchors(self) -> list[str]:
        """Every reference object, the first being ``anchor``."""
        return [self.anchor, *self.more_anchors]

    def to_dict(self) -> dict:
        more = {}
        if self.more_anchors:  # only for two-anchor actions: a one-anchor plan.json reads as it always did
            poses = np.asarray(self.more_anchor_poses, float).reshape(-1, 3)
            more["anchors"] = self.anchors
            more["anchor_poses"] = [[float(v) for v in self.anchor_pose]] + [[float(v) for v in p] for p in poses]
        if self.viewer is not None:
            more["viewer"] = [float(v) for v in self.viewer]
        return {
            "schema": 1,
            "action": self.action,
            "mover": self.mover,
            "anchor": self.anchor,
            "size": float(self.size),
            "anchor_pose": [float(v) for v in self.anchor_pose],
            "start": [float(v) for v in self.start],
            # the path exactly as executed: replay reads it back and must move the block the same way (a push is
            # chaotic enough that a path rounded to 1e-6 m ended 1 mm and 6 degrees elsewhere)
            "path": np.asarray(self.path, float).tolist(),
            "progress": np.asarray(self.progress, float).round(6).tolist(),
            "planner": self.planner,
            "stopped": self.stopped,
            **more,
            **self.extra,
        }

    def save(self, path: str | Path) -> None:
        Path(path).write_text(dumps_json(self.to_dict(), indent=1) + "\n")

    @classmethod
    def from_dict(cls, d: dict, source: str = "plan") -> Plan:
        try:
            known = {"schema", "action", "mover", "anchor", "size", "anchor_pose", "start", "path",
                     "progress", "planner", "stopped", "anchors", "anchor_poses", "viewer"}
            anchors = d.get("anchors", [d["anchor"]])
            if not isinstance(anchors, list) or not 1 <= len(anchors) <= 2 or str(anchors[0]) != str(d["anchor"]):
                raise ValueError('"anchors" must be a list starting with "anchor"')
            more_poses = None
            if len(anchors) > 1:
                more_poses = _poses(d["anchor_poses"], source, "anchor_poses")
                if len(more_poses) != len(anchors):
                    raise ValueError('"anchor_poses" must hold one pose per entry of "anchors"')
                more_poses = more_poses[1:]
            return cls(
                action=str(d["action"]),
                mover=str(d["mover"]),
                anchor=str(d["anchor"]),
                size=block_size(d["size"], source),
                anchor_pose=_poses(d["anchor_pose"], source, "anchor_pose").reshape(3),
                start=_poses(d["start"], source, "start").reshape(3),
                path=_poses(d["path"], source, "path"),
                progress=np.asarray(d.get("progress", []), float),
                planner=str(d.get("planner", "unknown")),
                stopped=str(d.get("stopped", "unknown")),
                extra={k: v for k, v in d.items() if k not in known},
                more_anchors=[str(a) for a in anchors[1:]],
                more_anchor_poses=more_poses,
                viewer=_viewer(d.get("viewer"), source),
            )
        except KeyError as e:
            raise PathError(f'{source}: plan is missing the field "{e.args[0]}"') from None
        except (TypeError, ValueError, OverflowError) as e:  # "size": "big", "action": {...}: malformed, not a bug
            raise PathError(f"{source}: malformed plan ({str(e)[:120]})") from None


@dataclass
class Motion:
    """Mover and anchor pose sequences of equal length, in one metric frame, blocks of side ``size``."""

    mover: np.ndarray  # (T, 3)
    anchor: np.ndarray  # (T, 3)
    size: float
    mover_name: str | None = None
    anchor_name: str | None = None
    action: str | None = None
    more_anchors: list[np.ndarray] = field(default_factory=list)  # (T, 3) per further anchor (two-anchor actions)
    viewer: np.ndarray | None = None  # (2,) viewpoint in the same frame, when the file gives one
    action_from: int = 0  # a trajectory.json's first frame of the action proper (after an approach slide)


MIN_SIZE_M, MAX_SIZE_M = 1e-4, 1e3
"""Block sides a motion file may give (metres): anything outside is a unit mistake, not a block."""


def block_size(value: object, source: str, key: str = "size") -> float:
    """A motion's block side from a file: a finite number of metres within [MIN_SIZE_M, MAX_SIZE_M]."""
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        raise PathError(f'{source}: "{key}" must be a number (the block side in metres)')
    try:
        size = float(value)
    except (TypeError, ValueError, OverflowError):
        raise PathError(f'{source}: "{key}" must be a number (the block side in metres)') from None
    if not MIN_SIZE_M <= size <= MAX_SIZE_M:
        raise PathError(f'{source}: "{key}" is {size:.3g} m; a block side must be between {MIN_SIZE_M:g} and '
                        f"{MAX_SIZE_M:g} m")
    return size


def _poses(value: object, source: str, key: str) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError, RecursionError):
        raise PathError(f'{source}: "{key}" must be numbers') from None
    if arr.ndim == 1:
        arr = arr[None]
    if arr.ndim != 2 or arr.shape[1] != 3 or len(arr) == 0:
        raise PathError(f'{source}: "{key}" must be a list of [x, y, theta] poses (got shape {arr.shape})')
    if not np.all(np.isfinite(arr)):
        raise PathError(f'{source}: "{key}" contains non-finite numbers')
    return arr


def _viewer(value: object, source: str) -> np.ndarray | None:
    if value is None:
        return None
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        v = np.zeros(0)
    if v.shape != (2,) or not np.all(np.isfinite(v)):
        raise PathError(f'{source}: "viewer" must be a point [x, y]')
    return v


def trajectory_poses(frames: list[dict], name: str) -> np.ndarray:
    """(T,3) ``[x, y, yaw]`` of object ``name`` from trajectory.json frames (their poses are [x, y, z, yaw])."""
    return np.array([[f["poses"][name][0], f["poses"][name][1], f["poses"][name][3]] for f in frames], float)


def approach_end_frame(track: np.ndarray, to: np.ndarray, size: float) -> int:
    """The frame of an executed ``track`` (T,>=2, metres) where a plan's approach slide ends (plan.json's
    ``extra.approach.to``): the action proper starts there, and its learned progress is read from there on,
    as the planner scored it (planning/approach.py).

    The slide is straight towards ``to`` and the arm rounds the corner after it by at most
    ``motion.CORNER_RADIUS`` (2 cm), so the mover's distance to ``to`` falls until it turns: the first local
    minimum within half a block (at least 2.5 cm) is the end. A full circle comes back to the same point at
    its end, so the last minimum is not it. Without such a frame (a track that never got there): the
    nearest frame."""
    d = np.hypot(*(np.asarray(track, float)[:, :2] - np.asarray(to, float)[:2]).T)
    if not len(d):
        return 0
    near = np.flatnonzero(d <= max(0.5 * size, 0.025))
    if not len(near):
        return int(np.argmin(d))
    k = int(near[0])
    while k + 1 < len(d) and d[k + 1] <= d[k]:
        k += 1
    return k


def hold_before(values: np.ndarray, first: int) -> np.ndarray:
    """Per-frame progress ``values`` of the action proper (frames ``first`` on) padded to the whole episode:
    the frames of the approach before it hold the action's first value, as plan.json's lead-in does (one
    rule for the recorder, ``score`` and a chain's clauses)."""
    values = np.asarray(values, float).reshape(-1)
    if not first:
        return values
    return np.r_[np.full(first, values[0] if len(values) else np.nan), values]


MAX_FPS = 1000.0
"""Highest frame rate a run folder may state (trajectories are recorded at 30 fps, videos at 10-30)."""


def frame_rate(value: object, source: str, key: str = "fps") -> float:
    """A run folder's frame rate, checked: a number above 0 and at most :data:`MAX_FPS` (0 divides by zero,
    -30 or 1e300 would be written into an exported dataset's meta/info.json)."""
    ok = isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)
    if not (ok and 0 < value <= MAX_FPS):
        raise PathError(f'{source}: "{key}" must be a frame rate above 0 and at most {MAX_FPS:g} per second '
                        f"(got {str(value)[:30]})")
    return float(value)


def action_from(doc: dict, source: str = "trajectory.json") -> int:
    """trajectory.json's ``action_from`` (a run whose plan came near first: the first frame of the action
    proper), checked against its frames; 0 where there is none (every other run: the whole episode)."""
    k = doc.get("action_from", 0)
    n = len(doc.get("frames") or [])
    if isinstance(k, bool) or not isinstance(k, int) or not 0 <= k < max(n, 1):
        raise PathError(f'{source}: "action_from" must be a frame index below {n} (got {str(k)[:20]})')
    return k


def dumps_json(value: object, **kwargs) -> str:
    """``json.dumps`` for every JSON this tool writes or prints: NaN and infinities become null (JSON has
    no such numbers; strict readers reject Python's ``NaN`` literal), numpy values and paths plain JSON."""
    return json.dumps(_finite(value), allow_nan=False, default=_json_default, **kwargs)


def _finite(v: object) -> object:
    if isinstance(v, float):
        return v if math.isfinite(v) else None
    if isinstance(v, dict):
        return {k: _finite(x) for k, x in v.items()}
    if isinstance(v, list | tuple):
        return [_finite(x) for x in v]
    if isinstance(v, np.generic | np.ndarray):
        return _finite(v.tolist())
    return v


def _json_default(v: object) -> object:
    if isinstance(v, Path):
        return str(v)
    raise TypeError(f"not JSON serialisable: {type(v).__name__}")


def _no_constant(name: str) -> float:
    raise ValueError(f"{name} is not a JSON number")


def load_json_file(path: str | Path, error: type[L2PError] = PathError, what: str = "") -> object:
    """Parse a JSON file, every failure a one-line ``error`` naming the file.

    Not UTF-8, too large (:data:`MAX_JSON_BYTES`), nested too deep, an integer too long to read, or the
    ``NaN``/``Infinity`` literals Python's json would otherwise accept: all are the user's file, not a bug.
    """
    p = Path(path)
    label = f"{what} {p}" if what else str(p)
    try:
        if p.is_file() and p.stat().st_size > MAX_JSON_BYTES:
            have, most = sizes(p.stat().st_size, MAX_JSON_BYTES)
            raise error(f"{label} is {have}; the limit is {most}")
    except OSError as e:
        raise error(f"cannot read {label}: {e.strerror or e}") from None
    raw = read_bounded(p, MAX_JSON_BYTES, error, label)  # /dev/zero or a FIFO: the size is found by reading
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise error(f"{label} is not UTF-8 text (byte {e.start}); save it as UTF-8 JSON") from None
    try:
        return json.loads(text, parse_constant=_no_constant)
    except json.JSONDecodeError as e:
        raise error(f"{label} is not valid JSON (line {e.lineno}, column {e.colno}: {e.msg})") from None
    except RecursionError:
        raise error(f"{label} is nested too deeply to be a JSON file of this tool") from None
    except ValueError as e:  # NaN/Infinity literals, integers beyond Python's digit limit
        raise error(f"{label} is not valid JSON ({str(e)[:120]})") from None


def read_json(path: str | Path) -> dict:
    data = load_json_file(path)
    if not isinstance(data, dict):
        raise PathError(f"{path}: expected a JSON object")
    return data


def motion_from_dict(d: dict, source: str = "motion") -> Motion:
    """Interpret a scoring input, a plan.json or a trajectory.json as a :class:`Motion`."""
    if "frames" in d:  # trajectory.json
        try:
            mover, anchor = str(d["mover"]), str(d["anchor"])
            names = d.get("anchors", [anchor])
            if not isinstance(names, list) or not 1 <= len(names) <= 2:
                raise TypeError('"anchors" must be a list of one or two object names')
            more = [str(a) for a in names[1:]]
            m_arr = trajectory_poses(d["frames"], mover)
            a_arr = trajectory_poses(d["frames"], anchor)
            x_arr = [_poses(trajectory_poses(d["frames"], a), source, "frames") for a in more]
            size = block_size(d["objects"][mover]["size"], source, f"objects.{mover[:40]}.size")
        except KeyError as e:
            raise PathError(f"{source}: not a valid trajectory.json (missing {str(e)[:80]})") from None
        except IndexError:
            raise PathError(f"{source}: not a valid trajectory.json (every pose in \"frames\" must be "
                            "[x, y, z, yaw])") from None
        except (TypeError, ValueError, OverflowError) as e:
            raise PathError(f"{source}: not a valid trajectory.json ({type(e).__name__}: {str(e)[:80]})") from None
        return Motion(_poses(m_arr, source, "frames"), _poses(a_arr, source, "frames"), size, mover, anchor,
                      d.get("action"), x_arr, _viewer(d.get("viewer"), source), action_from(d, source))
    if "path" in d:  # plan.json
        plan = Plan.from_dict(d, source)
        anchor = np.repeat(plan.anchor_pose[None], len(plan.path), axis=0)
        more = [
            np.repeat(p[None], len(plan.path), axis=0) for p in (plan.more_anchor_poses if plan.more_anchors else [])
        ]
        return Motion(plan.path, anchor, plan.size, plan.mover, plan.anchor, plan.action, more, plan.viewer)
    for key in ("size", "mover", "anchor"):
        if key not in d:
            raise PathError(
                f'{source}: missing "{key}" (expected a scoring input {{"size", "mover", "anchor"}}, '
                "a plan.json or a trajectory.json)"
            )
    mover = _poses(d["mover"], source, "mover")
    tracks = []
    raw_more = d.get("more_anchors", [])
    if not isinstance(raw_more, list) or len(raw_more) > 1:
        raise PathError(f'{source}: "more_anchors" must be a list of at most one pose sequence')
    for key, value in [("anchor", d["anchor"])] + [(f"more_anchors[{i}]", v) for i, v in enumerate(raw_more)]:
        track = _poses(value, source, key)
        if len(track) == 1:
            track = np.repeat(track, len(mover), axis=0)
        if len(mover) != len(track):
            raise PathError(f'{source}: "mover" has {len(mover)} poses but "{key}" has {len(track)}')
        tracks.append(track)
    return Motion(mover, tracks[0], block_size(d["size"], source), more_anchors=tracks[1:],
                  viewer=_viewer(d.get("viewer"), source))


def load_motion(path: str | Path) -> Motion:
    return motion_from_dict(read_json(path), source=str(path))


# --- an action bundle's folder (plugins/bundle.py reads and writes it; progress/ and learning/ read the
# weights): the file names are part of the contract, kept here so that no reader imports a writer's floor.
MANIFEST = "manifest.toml"
PROGRESS_FILE = "progress.safetensors"
POLICY_FILE = "policy.safetensors"
