"""Episodes to export: performed runs (run folders) and the shipped human demonstrations, replayed by the arm.

An :class:`Episode` is what every export format writes: the sentence (the task), the trajectory.json
frames the simulator recorded (30 fps) and, when the run was rendered, its camera images (at the
render rate, 10 fps by default). Nothing here depends on an export format.
"""

from __future__ import annotations

import json
import tempfile
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core.contracts import frame_rate, load_json_file, trajectory_poses
from ..core.folders import unfinished
from ..core.runfolder import MARKER, run_folder_command
from ..core.scene import default_scene
from ..core.vocabulary import ACTIONS, canonical_action
from ..data.demos import load_demos
from ..embodiment.record import TRAJECTORY_FPS
from ..embodiment.replay import motion_source, run_replay
from ..embodiment.sim.camera import RenderSettings
from ..errors import DataError, PathError
from ..evaluate.tasks import sentence_for
from ..plugins import registry


@dataclass
class Episode:
    """One performed (or replayed) motion with its sentence; ``images`` (H,W,3) uint8 at ``image_fps``."""

    task: str
    frames: list[dict]
    fps: float
    mover: str
    anchor: str
    source: str
    images: list[np.ndarray] | None = None
    image_fps: float | None = None
    extra: dict = field(default_factory=dict)
    arm: str = "panda"  # the arm that performed it (trajectory.json's arm name): its joints are each frame's "arm"


def run_folders(paths: list[str | Path]) -> list[Path]:
    """Run folders (holding trajectory.json) among ``paths``: a run folder itself, or any folder below
    which run folders lie (an evaluation's folder, ``runs/``), sorted; a folder named twice (or found again
    under another one named) is exported once."""
    out: list[Path] = []
    for p in map(Path, paths):
        if (p / "trajectory.json").is_file() or _broken_off(p):
            out.append(p)
        elif p.is_dir():
            # not hidden ones (a run put aside by --force), as review
            found = sorted({t.parent for name in ("trajectory.json", MARKER) for t in p.rglob(name)
                            if not any(part.startswith(".") for part in t.relative_to(p).parent.parts)
                            and (name == "trajectory.json" or _broken_off(t.parent))})
            if not found:
                raise PathError(f"{p} holds no run folder (no trajectory.json in it or below it)")
            out += found
        else:
            raise PathError(f"{p} is not a run folder")
    seen: set[Path] = set()
    return [p for p in out if not (p.resolve() in seen or seen.add(p.resolve()))]


def _broken_off(folder: Path) -> bool:
    """A run folder whose run stopped before it wrote trajectory.json (interrupted, failed): the command
    skips it with a note, as it skips one that stopped later, instead of refusing the whole export."""
    return ((folder / MARKER).is_file() and not (folder / "trajectory.json").exists()
            and run_folder_command(folder) not in ("evaluate", "export") and unfinished(folder) is not None)


def episode_from_run(run: str | Path) -> Episode:
    """A run folder as an episode: trajectory.json, the sentence, and frames/*.png when it was rendered."""
    run = Path(run)
    # load_json_file, not json.loads: a run folder from elsewhere may hold a trajectory.json nested past the
    # recursion limit, or linked to /dev/zero (read until memory ran out): one-line errors instead
    traj = load_json_file(run / "trajectory.json", PathError)
    summary = load_json_file(run / "summary.json", PathError) if (run / "summary.json").exists() else {}
    for doc, name in ((traj, "trajectory.json"), (summary, "summary.json")):
        if not isinstance(doc, dict):
            raise PathError(f"{run}/{name} is not a JSON object")
    for key in ("frames", "mover", "anchor", "fps"):
        if key not in traj:
            raise PathError(f'{run}/trajectory.json lacks "{key}"')
    task = traj.get("sentence") or summary.get("sentence")
    if not task:
        action = traj.get("action") or "an action"
        task = f"move {traj['mover']} {action} {traj['anchor']}"
    fps = frame_rate(traj["fps"], f"{run}/trajectory.json")
    check_frames(traj["frames"], traj["mover"], traj["anchor"], f"{run}/trajectory.json")
    render = summary.get("render")
    images, image_fps = _read_images(run / "frames"), render.get("fps") if isinstance(render, dict) else None
    image_fps = frame_rate(image_fps, f"{run}/summary.json", "render.fps") if images and image_fps is not None else None
    return Episode(task, traj["frames"], fps, traj["mover"], traj["anchor"], str(run),
                   images or None, image_fps if images else None,
                   {"action": traj.get("action"), "success": summary.get("success")},
                   str((traj.get("arm") or {}).get("name") or "panda"))


def check_frames(frames: object, mover: object, anchor: object, source: str) -> None:
    """What an export reads of every frame, checked before anything is written: every object's pose
    ([x, y, z, yaw], the mover's and the anchor's among them) and the tool's ``ee`` ([x, y, z]) of finite
    numbers, ``grasped``, and the arm's joints (as many in every frame); a crafted trajectory.json is one
    line, not a KeyError in the middle of a dataset."""
    if not isinstance(frames, list) or not frames:
        raise PathError(f'{source}: "frames" must be a non-empty list')
    if not (isinstance(mover, str) and isinstance(anchor, str)):
        raise PathError(f'{source}: "mover" and "anchor" must be object names')
    try:
        for f in frames:
            if "grasped" not in f:
                raise KeyError("grasped")
        values = np.array([[*f["poses"][mover], *f["poses"][anchor], *f["ee"]] for f in frames], float)
        joints = np.array([f.get("arm") or [] for f in frames], float)
        progress = np.array([np.nan if f.get("progress") is None else f["progress"] for f in frames], float)
        poses = [np.asarray(v, float) for f in frames for v in f["poses"].values()]
    except (KeyError, TypeError, ValueError, IndexError, AttributeError) as e:
        raise PathError(f"{source}: a malformed frame ({type(e).__name__}: {str(e)[:80]}); every frame needs "
                        f'"poses" of {mover[:40]} and {anchor[:40]}, "ee" and "grasped"') from None
    if (values.shape != (len(frames), 11) or not np.all(np.isfinite(values)) or joints.ndim != 2 or progress.ndim != 1
            or any(p.shape != (4,) or not np.isfinite(p).all() for p in poses)):
        raise PathError(f'{source}: every frame\'s poses must be [x, y, z, yaw] and its "ee" [x, y, z] '
                        '(finite numbers), its "arm" as many joint angles as the other frames\'')


def episodes_from_run(run: str | Path) -> list[Episode]:
    """A run folder as episodes: one, or for a chain run one per clause (its frames, blocks, sentence and
    images; ``extra["chain"]`` names the chain and the clause), so every exported task is one action."""
    from ..chain.segments import segment_docs

    ep = episode_from_run(run)  # first: it reads trajectory.json bounded, segment_docs then reads a checked file
    docs = segment_docs(run) if (Path(run) / "trajectory.json").is_file() else None
    if docs is None:
        return [ep]
    try:
        verdicts = {c.get("clause"): c.get("success") for c in json.loads((Path(run) / "summary.json").read_text())
                    .get("clauses", [])}
    except (OSError, ValueError, AttributeError):
        verdicts = {}
    out = []
    for d in docs:
        images = None
        if ep.images and ep.image_fps:
            t0, t1 = d["frames"][0]["t"], d["frames"][-1]["t"]
            images = [im for i, im in enumerate(ep.images) if t0 - 1e-6 <= i / ep.image_fps <= t1 + 1e-6] or None
        out.append(Episode(d["sentence"], d["frames"], ep.fps, d["mover"], d["anchor"], ep.source, images,
                           ep.image_fps if images else None, ep.extra | {"action": d["action"], "chain": d["chain"],
                                                                    "success": verdicts.get(d["chain"]["clause"])},
                           ep.arm))
    return out


def _read_images(folder: Path) -> list[np.ndarray]:
    """The run's frames/*.png as RGB arrays; a frame that cannot be read (empty, cut short: an interrupted
    render) is a one-line PathError naming it. Read with Pillow, the PNG reader imageio would use: imageio
    tries every plugin on a broken file and ends with advice to install another one."""
    if not folder.is_dir():
        return []
    from PIL import Image, UnidentifiedImageError  # lazy: only when a run's frames are exported

    images = []
    for f in sorted(folder.glob("*.png")):
        try:
            with Image.open(f) as im:
                images.append(np.asarray(im.convert("RGB")))
        except (OSError, ValueError, SyntaxError, UnidentifiedImageError) as e:
            why = "an empty file" if f.stat().st_size == 0 else (str(e).splitlines() or [type(e).__name__])[0]
            raise PathError(f"cannot read the frame image {f} ({why}); render the run again") from None
    return images


def demo_specs(specs: list[str]) -> list[tuple[str, int]]:
    """``all``, ``ACTION`` (all its demonstrations) or ``ACTION:INDEX`` -> (action, index) pairs."""

    out: list[tuple[str, int]] = []
    for spec in specs:
        name, sep, index = spec.partition(":")
        actions = list(ACTIONS) if name.strip().lower() == "all" else [canonical_action(name)]
        for a in actions:
            n = len(load_demos(a))
            if sep:
                if not index.strip().isdigit() or int(index) >= n:
                    raise DataError(f'--demos {spec}: "{a}" has demonstrations 0..{n - 1}')
                out.append((a, int(index)))
            else:
                out += [(a, i) for i in range(n)]
    return out


def demo_episodes(specs: list[str], render: bool | object = True, plugins: list | None = None) -> Iterator[Episode]:
    """The shipped human demonstrations, retargeted onto the default scene and performed by the arm
    (``embodiment.replay``, as ``l2p-bullet replay --demo``), with the action's learned progress per frame.

    ``render``: True (the default video settings: 640x480 at 15 fps from the viewer camera), False, or a
    ``RenderSettings``."""
    if isinstance(specs, str):  # "past:3" would be read letter by letter ('unknown action "p"')
        specs = [specs]
    plugins = registry.discover() if plugins is None else plugins
    scene = default_scene()
    settings = RenderSettings() if render is True else (render or None)
    for action, index in demo_specs(specs):
        source = motion_source(None, f"{action}:{index}", scene, "A", "B")
        with tempfile.TemporaryDirectory(prefix="l2p-export-") as td:
            ex = run_replay(scene, source, Path(td), settings)
            images = _read_images(Path(td) / "frames")
        model = registry.load(action, plugins).progress_model()
        m, a = trajectory_poses(ex.frames, "A"), trajectory_poses(ex.frames, "B")
        for f, v in zip(ex.frames, model.curve(m, a, scene.get("A").size), strict=True):
            f["progress"] = round(float(v), 6)
        yield Episode(sentence_for(action, "A", "B", plugins), ex.frames, TRAJECTORY_FPS, "A", "B",
                      f"demo {action}:{index}", images or None, settings.fps if images else None,
                      {"action": action, "demo": source.info.get("source", {}).get("demo")})


EXPORT_FILES: tuple[str, ...] = ("episodes.jsonl", "meta", "meta/*", "data", "data/*", "videos", "videos/*")
"""What an export writes into its folder (fnmatch patterns, ``*`` spans sub-folders): the plain format's
one file, or a LeRobot dataset's meta/, data/ and videos/. ``--force`` replaces only such a folder."""


def write_jsonl(episodes: Iterable[Episode], out: str | Path) -> Path:
    """The plain format: ``OUT/episodes.jsonl``, one episode per line (task, source, fps, names, frames).

    ``out`` is the caller's folder (``l2p-bullet export`` claims it with ``core.runfolder.run_folder``).
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "episodes.jsonl"
    with path.open("w") as f:
        for e in episodes:
            f.write(json.dumps({"task": e.task, "source": e.source, "fps": e.fps, "mover": e.mover, "anchor": e.anchor,
                                "extra": e.extra, "frames": e.frames}, default=str, separators=(",", ":")) + "\n")
    return path
