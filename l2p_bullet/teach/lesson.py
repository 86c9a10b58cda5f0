"""What the teach page does, without the web: scenes, recorded demonstrations, training, a performance.

A person teaching "to the left of" sees a random scene from above, drags the mover with the mouse and
marks where the action starts and ends. The page sends what it sampled (times and the mover's poses,
scene frame); :meth:`Lesson.save` turns it into one demonstration of the capture-session format
and appends it to the demos file:

- resampled to the captures' 30 frames per second (a quick drag is sampled on every mouse move, a still
  block by a timer), yaw unwrapped;
- rest before and after the event: the loader cuts 45 frames of context each side, so at least that many
  still frames are kept or added (what people do before and after a demonstration is not the event);
- scaled to the captures' 15 cm blocks (``DEMO_BLOCK_SIZE``: the loader takes every block to be that
  size), the viewer (the robot's base) written as ``viewer_xy``, a second anchor as ``more_poses`` and
  ``event_anchors``;
- validated before anything is written (the limits on samples, the swept-path check and duplicates:
  ``checks.py``): the recording starts where the block stands, the block moved
  during the event, never passed through another block and stayed on the table; the file is rewritten
  atomically and read back by ``load_session`` (``save_session``).

Training runs in a thread (:meth:`Lesson.train`): the trainer the command hands over
(``train_bundle`` with its settings; this module never imports torch) on every demos file of the plugin folder, then
``perform`` on a new random scene with the freshly trained bundle (the folder, not an
installed copy), with video. :meth:`Lesson.status` reports progress for the page to show.
"""

from __future__ import annotations

import math
import threading
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from ..core.frames import VIEWPOINTS, Frame, declaration
from ..core.scene import Scene, random_between_scene, random_scene
from ..core.vocabulary import ACTIONS, normalize_name
from ..data.demos import DEMO_BLOCK_SIZE, load_session, save_session
from ..data.tracking import page_samples, page_track
from ..errors import L2PError, TeachError
from ..pipeline import perform
from ..plugins import registry
from ..plugins.bundle import MANIFEST, read_manifest
from .checks import (
    MIN_FRAMES,
    MIN_TRAVEL,
    Duplicate,
    checked_samples,
    first_collision,
    fmt,
    same_demonstration,
    travel,
)

FPS = 30.0
"""Frames per second of the written demonstrations (the captures')."""

CONTEXT = 45
"""Still frames kept or added before the start and after the end (the loader's context)."""

BEFORE = 90
"""Frames of the recording before the start that are kept (older ones are dropped)."""


class Trainer(Protocol):
    """Trains a plugin's bundle (``learning.train_progress.BundleTrainer``; given by the command, so that
    this module never imports torch)."""

    ticks: int

    def __call__(self, action: str, out: Path, demo_files: list[str], seed: int = 0,
                 tick: Any = None) -> Any: ...


@dataclass(frozen=True)
class TaughtAction:
    """The action being taught: its plugin folder (``l2p-bullet new-action``) and what its manifest declares."""

    name: str
    phrases: tuple[str, ...]
    frame: Frame
    anchors: int
    root: Path  # the plugin project (pyproject.toml, demos/)
    bundle_dir: Path  # its package folder: manifest.toml, the weights once trained
    demos: Path  # the demos file recorded demonstrations are appended to
    composite: bool = False  # a composite action (manifest kind "composite"): taught with rows of drags

    @property
    def sentence(self) -> str:
        """What the page asks for: a composite's is its row of three (the scenes have 2 or 3 blocks)."""
        if self.composite:
            return f"{self.phrases[0]} A, B and C"
        return f"move A {self.phrases[0]} B" + (" and C" if self.anchors == 2 else "")


def find_action(name: str, root: str | Path | None = None, demos: str | Path | None = None) -> TaughtAction:
    """The scaffolded plugin ``name`` in ``root`` (default ``./l2p-<name>``); TeachError when it is not one."""
    root = Path(root) if root is not None else Path(f"l2p-{name}")
    bundle_dir = root / f"l2p_{name.replace('-', '_')}"
    if not (bundle_dir / MANIFEST).is_file():
        if normalize_name(name) in ACTIONS:  # new-action refuses an installed action's name
            raise TeachError(f'"{name}" is a built-in action, taught from the shipped demonstrations; teach a new '
                             f'one under a name of its own, e.g. l2p-bullet new-action my-{name} --phrase "..." '
                             "(see docs/perform.md), then l2p-bullet teach my-" + name)
        raise TeachError(f"{bundle_dir / MANIFEST} does not exist: create the plugin first, e.g. "
                         f'l2p-bullet new-action {name} --phrase "..." (see docs/perform.md), or give --plugin DIR')
    try:
        manifest = read_manifest(bundle_dir)
        frame, anchors = declaration(manifest)
    except L2PError as e:
        raise TeachError(str(e)) from None
    if str(manifest.get("name", "")) != name:
        raise TeachError(f'{bundle_dir / MANIFEST} describes the action "{manifest.get("name")}", not "{name}"')
    phrases = tuple(p for p in manifest.get("phrases", []) if isinstance(p, str) and p.strip())
    if not phrases:
        raise TeachError(f'{bundle_dir / MANIFEST}: "phrases" is empty')
    demos_file = Path(demos) if demos is not None else root / "demos" / f"{name}_taught.npz"
    if demos_file.suffix != ".npz":
        raise TeachError(f"the demos file must end in .npz, not {demos_file.name}")
    return TaughtAction(name, phrases, frame, anchors, root, bundle_dir, demos_file,
                        composite=manifest.get("kind") == "composite")


def demo_spans(events: np.ndarray, frames: int) -> list[tuple[int, int]] | None:
    """The frames ``[a, b)`` of each demonstration in a demos file the page wrote (:meth:`Lesson._append`:
    one after another, each with at least :data:`CONTEXT` frames before its event and exactly that many
    after it); None for a file not written that way (a capture session), whose frames cannot be told apart."""
    spans, a = [], 0
    for start, end in np.asarray(events, int):
        b = int(end) + CONTEXT + 1
        if start - a < CONTEXT or b > frames:
            return None
        spans.append((a, b))
        a = b
    return spans if a == frames else None


@dataclass
class Recording:
    """What the page sampled: ``samples`` (n, 4) rows ``[t, x, y, yaw]`` of the mover (seconds, scene
    frame), the times the person marked the event's start and end, and the scene it was recorded in."""

    scene: int
    samples: np.ndarray
    start: float
    end: float


@dataclass
class Job:
    """The training-and-performing job the page polls."""

    state: str = "idle"  # idle | training | performing | done | failed
    done: int = 0
    total: int = 0
    message: str = ""
    started: float = 0.0
    run: dict[str, Any] | None = None
    runs: list[Path] = field(default_factory=list)


class Lesson:
    """One teach page: scenes by seed, demonstrations appended to the demos file, one training at a time."""

    def __init__(self, action: TaughtAction, trainer: Trainer | None = None, *, seed: int = 0,
                 render_settings: Any = None):
        """``render_settings``: the video of the performance (a ``RenderSettings``; None: perform's default,
        640x480 at 15 fps). A smaller one makes the page's answer come sooner on a slow machine (the video
        of a row of four blocks takes most of a minute at the default on two cores)."""
        self.action, self.trainer, self.seed = action, trainer, seed
        self.render_settings = render_settings
        self.job = Job()
        self._lock = threading.Lock()
        self._thread: threading.Thread | None = None

    # --- scenes ---------------------------------------------------------------------------------
    def scene(self, seed: int) -> Scene:
        return random_between_scene(seed) if self.action.anchors == 2 else random_scene(seed)

    def scene_json(self, seed: int) -> dict[str, Any]:
        """A scene for the page: blocks (name, colour, rgb, size, pose), the mover, the anchors, the sentence."""
        scene = self.scene(seed)
        return {
            "seed": seed, "sentence": self.action.sentence, "mover": "A",
            "anchors": ["B", "C"] if self.action.anchors == 2 else ["B"],
            "objects": [{"name": o.name, "color": o.color, "rgb": [round(255 * c) for c in o.rgba[:3]],
                         "size": o.size, "x": o.xy[0], "y": o.xy[1], "yaw": o.yaw} for o in scene.objects],
            "workspace": scene.workspace.to_dict(),  # x, y, r; and the ring's fields for a ring
            "table": {"half_x": scene.table.half_x, "half_y": scene.table.half_y},
        }

    def config(self) -> dict[str, Any]:
        a = self.action
        viewer = a.frame.viewpoint_xy()
        return {"action": a.name, "phrases": list(a.phrases), "sentence": a.sentence, "frame": a.frame.name,
                "anchors": a.anchors, "demos": str(a.demos), "count": self.count(),
                "robot": list(VIEWPOINTS["robot"]), "viewer": None if viewer is None else viewer.tolist(),
                "fps": FPS, "seed": self.seed}

    def count(self) -> int:
        """Demonstrations in the demos file."""
        if not self.action.demos.exists():
            return 0
        return len(load_session(self.action.demos)["event_mover"])

    # --- recording ------------------------------------------------------------------------------
    def save(self, rec: Recording) -> dict[str, Any]:
        """Validate one recording, append it to the demos file; the file's path and demonstration count."""
        scene = self.scene(rec.scene)
        tracks, start, end = self._tracks(scene, rec)
        self._append(scene, tracks, start, end)
        return {"demos": str(self.action.demos), "count": self.count(), "frames": len(tracks[0]),
                "start": start, "end": end, **self.training_note()}

    def training_note(self) -> dict[str, str]:
        """A save during training is kept, but the model being trained read its demonstrations already:
        the page says so (``note``) rather than let the person believe the next performance uses it."""
        if self.job.state not in ("training", "performing"):
            return {}
        return {"note": "saved; training is under way with the demonstrations saved before it started, "
                        "so this one is not in the model being trained: train again to use it"}

    def _tracks(self, scene: Scene, rec: Recording) -> tuple[list[np.ndarray], int, int]:
        s = checked_samples(rec.samples)
        t = s[:, 0] - s[0, 0]
        start, end = rec.start - s[0, 0], rec.end - s[0, 0]
        if not (math.isfinite(start) and math.isfinite(end) and 0 <= start < end <= t[-1] + 1e-6):
            raise TeachError(
                "mark the start, move the block, then mark the end (start before end, both while recording)"
            )
        mover = scene.get("A")
        if np.hypot(*(s[0, 1:3] - mover.xy)) > 0.002:
            raise TeachError("the recording does not start where block A stands in this scene")
        track = page_track(s, FPS)  # to the frame at or after the last sample, which holds it
        n = len(track)
        # the event covers the marked interval: the frame at or before the start, at or after the end
        i0, i1 = int(np.floor(start * FPS + 1e-9)), min(int(np.ceil(end * FPS - 1e-9)), n - 1)
        if i1 - i0 < MIN_FRAMES:
            raise TeachError("the demonstration is too short: mark the start, slide the block, then mark the end")
        moved = travel(track[i0:i1 + 1], mover.size)
        if moved < MIN_TRAVEL:
            raise TeachError(f"block A moved {moved:.2f} blocks between start and end; slide it to where "
                             f'"{self.action.phrases[0]}" ends')
        # the samples the track was built from, not every sample: a detour at one instant is not saved
        self._check_track(scene, track, page_samples(np.column_stack([t, s[:, 1:3], np.unwrap(s[:, 3])])))
        lo = max(0, i0 - BEFORE)
        track = track[lo:i1 + CONTEXT + 1]
        i0, i1 = i0 - lo, i1 - lo
        pad_before, pad_after = max(0, CONTEXT - i0), max(0, CONTEXT - (len(track) - 1 - i1))
        track = np.vstack([np.repeat(track[:1], pad_before, 0), track, np.repeat(track[-1:], pad_after, 0)])
        i0, i1 = i0 + pad_before, i1 + pad_before
        names = ["B", "C"] if self.action.anchors == 2 else ["B"]
        others = [np.repeat(scene.get(k).pose[None], len(track), 0) for k in names]
        return [track, *others], i0, i1

    @staticmethod
    def _check_track(scene: Scene, track: np.ndarray, samples: np.ndarray) -> None:
        """The block's frames (``track``) stay on the table, and its path never passes through another
        block: ``samples`` ``[t, x, y, yaw]`` (t from 0, yaw unwrapped), the poses the page placed it at
        that the track is built from (the last at each instant, :func:`~l2p_bullet.data.tracking.page_samples`: the
        others are not in the track, so a detour among them must not pass for the saved path) and the
        jumps between them (:func:`~.checks.first_collision`, which allows a jump across a
        corner the page allowed; the frames lie on those jumps)."""
        mover = scene.get("A")
        for k, pose in enumerate(track):
            if not scene.table.contains(mover.footprint(pose)):
                raise TeachError(f"block A left the table at frame {k} ({fmt(pose[0])}, {fmt(pose[1])})")
        hit = first_collision(mover, samples[:, 1:], [(o, o.pose) for o in scene.objects if o.name != "A"])
        if hit is not None:
            frame = int(np.floor(samples[hit[0], 0] * FPS + 1e-9))
            raise TeachError(f"block A passed through block {hit[1]} at frame {frame}: slide it around")

    def _append(self, scene: Scene, tracks: list[np.ndarray], start: int, end: int) -> None:
        """Append the demonstration (scaled to the captures' block size) to the demos file, atomically."""
        k = DEMO_BLOCK_SIZE / scene.get("A").size
        new = [np.column_stack([t[:, :2] * k, t[:, 2]]) for t in tracks]
        viewer = np.asarray(VIEWPOINTS["robot"] if self.action.frame.relative else self.action.frame.viewpoint_xy()) * k
        anchors = [[1, 2]] if len(tracks) == 3 else None
        path = self.action.demos
        with self._lock:
            if path.exists():
                old = load_session(path)
                old_tracks = [old["shell_pose"], old["stella_pose"], *list(old.get("more_poses", []))]
                if len(old_tracks) != len(new):
                    raise TeachError(f"{path} holds {len(old_tracks)} blocks' tracks; this action's demonstrations "
                                     f"have {len(new)}: give another --demos file")
                if "viewer_xy" in old and not np.allclose(old["viewer_xy"], viewer):
                    raise TeachError(f"{path} was recorded from another viewpoint; give another --demos file")
                same = same_demonstration(old_tracks, old["event_start_end"], new, start, end)
                if same is not None:
                    raise Duplicate(f"this recording is demonstration {same + 1} of {path} already (the same scene "
                                    "and motion): record a new one")
                n0 = len(old_tracks[0])
                tracks_out = [np.vstack([o, t]) for o, t in zip(old_tracks, new, strict=True)]
                events = np.vstack([old["event_start_end"], [[start + n0, end + n0]]])
                movers = np.r_[old["event_mover"], 0]
                if anchors is not None:
                    anchors = np.vstack([old["event_anchors"], anchors])
                elif "event_anchors" in old:
                    anchors = np.vstack([old["event_anchors"], [[1]]])
                keep_viewer = old.get("viewer_xy")
            else:
                path.parent.mkdir(parents=True, exist_ok=True)
                tracks_out, events, movers, keep_viewer = new, np.array([[start, end]]), np.array([0]), viewer
            save_session(path, tracks_out, events, movers, anchors=anchors, viewer=keep_viewer)

    def remove(self, k: int) -> dict[str, Any]:
        """Remove demonstration ``k`` (1 = the first) from the demos file: its event and its frames (each
        demonstration the page saved is its own run of frames, :func:`demo_spans`); the file goes with
        the last one. The file's path and the demonstrations left."""
        path = self.action.demos
        with self._lock:
            if not path.exists():
                raise TeachError(f"there is no demonstration {k}: {path} holds none yet")
            old = load_session(path)
            events, frames = old["event_start_end"], len(old["shell_pose"])
            if not 1 <= k <= len(events):
                raise TeachError(f"there is no demonstration {k}: {path} holds {len(events)}")
            spans = demo_spans(events, frames)
            if spans is None:
                raise TeachError(f"{path} was not recorded on the teach page (its demonstrations are not one run of "
                                 "frames each): edit it with numpy, or record into another --demos file")
            if len(events) == 1:
                path.unlink()
                return {"demos": str(path), "count": 0, "removed": k}
            a, b = spans[k - 1]
            keep = np.r_[0:a, b:frames]
            tracks = [old["shell_pose"][keep], old["stella_pose"][keep], *[m[keep] for m in old.get("more_poses", [])]]
            ev = np.delete(events, k - 1, 0)
            ev[k - 1:] -= b - a
            anchors = np.delete(old["event_anchors"], k - 1, 0) if "event_anchors" in old else None
            save_session(path, tracks, ev, np.delete(old["event_mover"], k - 1), anchors=anchors,
                         viewer=old.get("viewer_xy"))
        return {"demos": str(path), "count": len(ev), "removed": k}

    # --- training and performing ----------------------------------------------------------------
    def train(self) -> dict[str, Any]:
        """Start training the plugin on its demonstrations, then performing it on a new scene (a thread)."""
        with self._lock:
            if self.trainer is None:
                raise TeachError("this teach page was started without a trainer")
            if self.job.state in ("training", "performing"):
                raise TeachError("training is already under way")
            files = sorted(self.action.demos.parent.glob("*.npz"))
            if not files:
                raise TeachError(f"no demonstrations in {self.action.demos.parent} yet: record some first")
            runs = self.job.runs
            self.job = Job(state="training", message="building the training set", started=time.time(), runs=runs)
            self._thread = threading.Thread(target=self._work, args=(files,), daemon=True, name="teach-train")
            self._thread.start()
        return self.status()

    def status(self) -> dict[str, Any]:
        j = self.job
        return {"state": j.state, "done": j.done, "total": j.total, "message": j.message,
                "seconds": round(time.time() - j.started, 1) if j.started else 0.0, "run": j.run,
                "count": self.count()}

    def wait(self, timeout: float = 600) -> dict[str, Any]:
        """Block until the job ends (tests and scripts)."""
        if self._thread is not None:
            self._thread.join(timeout)
        return self.status()

    def _work(self, files: list[Path]) -> None:
        try:
            self._train(files)
            self._perform()
        except L2PError as e:
            self.job.state, self.job.message = "failed", str(e)
        except Exception as e:  # the page must hear about it; the traceback goes to the server's log
            traceback.print_exc()
            self.job.state, self.job.message = "failed", f"internal error ({type(e).__name__}: {e})"

    def _train(self, files: list[Path]) -> None:
        self.job.total = self.trainer.ticks

        def tick() -> None:
            self.job.done += 1
            self.job.message = f"training: epoch {self.job.done} of {self.job.total}"

        self.trainer(self.action.name, self.action.bundle_dir, [str(f) for f in files], seed=self.seed, tick=tick)

    def _perform(self) -> None:
        self.job.state, self.job.message = "performing", "performing on a new scene"
        k = len(self.job.runs)
        seed = 100_000 + k  # scenes the page never shows for recording
        plugins = [p for p in registry.discover() if p.name != self.action.name]
        plugins.append(registry.local(self.action.name, self.action.bundle_dir))
        out = self.action.root / "runs" / f"teach-{k:03d}"
        r = perform(self.action.sentence, self.scene(seed), out_dir=out, seed=seed, force=True, plugins=plugins,
                    render_settings=self.render_settings)
        self.job.runs.append(out)
        self.job.run = {"id": k, "sentence": self.action.sentence, "scene": seed, "folder": str(out),
                        "verdict": r.verdict, "final_progress": r.final_progress,
                        "video": f"/api/runs/{k}/video" if "video" in r.files else None}
        self.job.state, self.job.message = "done", "done"

    def video(self, k: int) -> Path:
        if not 0 <= k < len(self.job.runs):
            raise TeachError(f"no run {k}")
        path = self.job.runs[k] / "video.mp4"
        if not path.is_file():
            raise TeachError(f"run {k} has no video")
        return path
