"""Run folders as the review app sees them: identity, fingerprint, what can be shown, the motion for 2-D.

A run is identified by its folder (``run_id`` = folder name + a short hash of its absolute path), and
its content by the sha256 of its ``trajectory.json``, recorded with every grade: a folder that was
re-made (``perform --force``) or edited after it was graded is then told apart from the one people saw.
"""

from __future__ import annotations

import hashlib
import json
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from ..core.bounded import read_bounded
from ..core.contracts import MAX_JSON_BYTES
from ..core.folders import unfinished
from ..errors import ReviewError
from ..plugins.bundle import sha256_file

VIEWS = ("3d", "2d")
"""What a reviewer is shown: "3d" the rendered video (or its raw frames), "2d" a top-down animation."""


def run_id_for(folder: Path) -> str:
    """A stable id for a run folder: its name and 8 hex digits of its absolute path."""
    path = str(Path(folder).resolve())
    return f"{Path(path).name}-{hashlib.sha256(path.encode()).hexdigest()[:8]}"


def item_key(run_id: str) -> str:
    """The opaque key the browser uses for a run: folder names may name the action (blind mode)."""
    return hashlib.sha256(run_id.encode()).hexdigest()[:16]


@dataclass(frozen=True)
class RunInfo:
    """One run folder: where it is, what it holds, and its trajectory's fingerprint when it was read."""

    run_id: str
    path: Path
    trajectory_sha256: str
    action: str
    sentence: str
    duration_s: float
    video: Path | None  # the captioned video (names the sentence: never shown in blind mode)
    frames: int  # raw rendered frames in frames/ (0 when rendered without them or not at all)
    render_fps: float | None
    camera: str | None = None  # the camera preset the video was filmed with ("custom"; None: not rendered)

    @property
    def key(self) -> str:
        return item_key(self.run_id)

    def views(self, mode: str) -> tuple[str, ...]:
        """The views this run can be shown in: "3d" needs the video (graded) or the raw frames (blind)."""
        has_3d = bool(self.frames) if mode == "blind" else (self.video is not None or bool(self.frames))
        return VIEWS if has_3d else ("2d",)

    def current_sha256(self) -> str | None:
        """The trajectory's sha256 now, or None if the file is gone."""
        try:
            return sha256_file(self.path / "trajectory.json")
        except OSError:
            return None


def read_run(folder: str | Path) -> RunInfo:
    """Read a run folder written by ``perform`` or ``replay``; ReviewError says what is wrong with it."""
    folder = Path(folder)
    traj = folder / "trajectory.json"
    if not traj.exists():
        raise ReviewError(f"{folder} is not a run folder (it has no trajectory.json)")
    try:
        # bounded: a trajectory.json linked to /dev/zero was read until memory ran out
        raw = read_bounded(traj, MAX_JSON_BYTES, ReviewError, str(traj))
        doc = json.loads(raw)
        frames = doc["frames"]
        duration = float(frames[-1]["t"]) if frames else 0.0
        action, sentence = str(doc.get("action") or ""), str(doc.get("sentence") or "")
        doc["mover"], doc["anchor"]  # noqa: B018 - a trajectory without them cannot be drawn
    except FileNotFoundError:
        raise ReviewError(f"{folder} is not a run folder (it has no trajectory.json)") from None
    except OSError as e:
        raise ReviewError(f"cannot read {traj}: {e.strerror or e}") from None
    except (ValueError, KeyError, TypeError, IndexError, RecursionError) as e:  # RecursionError: nested too deep
        raise ReviewError(f"{traj} is not a valid trajectory.json ({type(e).__name__}: {str(e)[:120]})") from None
    video = next((folder / n for n in ("video.mp4", "video.gif") if (folder / n).is_file()), None)
    n_frames = len(list((folder / "frames").glob("[0-9][0-9][0-9][0-9].png"))) if (folder / "frames").is_dir() else 0
    fps = _render_fps(folder)
    if fps is None and n_frames and duration > 0:
        fps = n_frames / duration
    return RunInfo(run_id_for(folder), folder.resolve(), hashlib.sha256(raw).hexdigest(), action, sentence,
                   duration, video, n_frames, fps, _camera(folder))


def _camera(folder: Path) -> str | None:
    """The name of the camera that filmed the run; runs rendered before cameras were named used the one
    now called "robot" (across the table, facing the robot)."""
    try:
        render = json.loads((folder / "summary.json").read_text()).get("render")
        if not isinstance(render, dict):
            return None
        cam = render.get("camera")
        return str(cam.get("name") or "custom") if isinstance(cam, dict) else "robot"
    except (OSError, ValueError, TypeError, AttributeError):
        return None


def _render_fps(folder: Path) -> float | None:
    try:
        render = json.loads((folder / "summary.json").read_text()).get("render") or {}
        return float(render["fps"]) if render.get("fps") else None
    except (OSError, ValueError, TypeError, KeyError, AttributeError):
        return None


def _stderr(note: str) -> None:
    print(note, file=sys.stderr)


def find_runs(paths: list[str | Path], note: Callable[[str], None] = _stderr) -> list[RunInfo]:
    """The finished run folders named, or found (recursively, sorted) under the folders named.

    An unfinished one is skipped with ``note`` (a line on stderr); none left is a ReviewError."""
    runs: dict[str, RunInfo] = {}
    skipped: set[Path] = set()  # a folder named twice is noted once
    for p in map(Path, paths):
        if not p.exists():
            raise ReviewError(f"{p} does not exist")
        if (p / "trajectory.json").is_file():
            found = [p]
        elif not p.is_dir():
            raise ReviewError(f"{p} is a file, not a run folder (a run folder holds a trajectory.json: give the "
                              "folder, or a folder of run folders)")
        else:
            found = sorted({t.parent for t in p.rglob("trajectory.json")
                            if not any(part.startswith(".") for part in t.relative_to(p).parts)})
            if not found:
                raise ReviewError(f"no run folders under {p} (a run folder holds a trajectory.json: "
                                  "make some with l2p-bullet perform or replay)")
        for folder in found:
            why = unfinished(folder)
            if why:
                if folder.resolve() not in skipped:
                    note(why)
                skipped.add(folder.resolve())
                continue
            run = read_run(folder)
            runs.setdefault(run.run_id, run)
    if skipped and not runs:
        raise ReviewError(f"nothing to review: none of the {len(skipped)} run folders given finished "
                          "(see the notes above)")
    return list(runs.values())


def motion_for_browser(run: RunInfo, *, blind: bool) -> dict:
    """What the page draws: poses per frame (x, y, yaw), sizes, and the learned progress per frame.

    Blind mode leaves out the sentence, the action and the progress (the progress is the run's own
    action's model: it would hint at the answer).
    """
    try:
        doc = json.loads((run.path / "trajectory.json").read_text())
        frames = doc["frames"]
        names = list(doc.get("objects") or frames[0]["poses"])
        out = {
            "fps": doc.get("fps"),
            "t": [f["t"] for f in frames],
            "mover": doc["mover"],
            "anchor": doc["anchor"],
            "objects": {n: {"size": float((doc.get("objects") or {}).get(n, {}).get("size", 0.05)),
                            "poses": [[p[0], p[1], p[3]] for p in (f["poses"][n] for f in frames)]}
                        for n in names},
            "duration": run.duration_s,
        }
    except (OSError, ValueError, KeyError, TypeError, IndexError) as e:
        raise ReviewError(f"cannot read the motion of {run.path}: {type(e).__name__}: {e}") from None
    segs = doc.get("segments")
    if isinstance(segs, list):  # a chain run: the page follows the clause being performed
        keys = ("first_frame", "last_frame", "mover", "anchor") + (() if blind else ("clause", "text", "action"))
        out["segments"] = [{k: s.get(k) for k in keys} for s in segs if isinstance(s, dict)]
    if not blind:
        out |= {"sentence": run.sentence, "action": run.action, "progress": [f.get("progress") for f in frames]}
    return out
