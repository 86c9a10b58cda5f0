"""Recording an episode from the simulated world: trajectory.json, frames, video, contact sheet, summary.

The :class:`Recorder` is called after every physics step and samples the world itself (not the plan) at
a fixed rate. For the video it only notes the state on every k-th step and hands it to a
:class:`~.render.Film`, whose worker processes draw it off the simulation's critical path (one frame
costs as much as hundreds of physics steps). PyBullet's own MP4 logging writes nothing in DIRECT mode,
so the video is written here with imageio-ffmpeg.
"""

from __future__ import annotations

import platform
import sys
from collections.abc import Callable, Iterator
from importlib import metadata
from pathlib import Path

import numpy as np

from ..core.contracts import dumps_json, hold_before, trajectory_poses
from .overlay import overlay, progress_at
from .render import capture, movable_joints, write_pngs

TRAJECTORY_FPS = 30.0


def _r(v: float) -> float:
    return round(float(v), 6)


class Recorder:
    """Samples trajectory frames every ``1/fps`` s and images every ``1/render_fps`` s of sim time."""

    def __init__(self, world, film=None, fps: float = TRAJECTORY_FPS):
        self.world, self.film, self.fps = world, film, fps
        self.traj_every = max(1, round(1.0 / (fps * world.dt)))
        self.render_every = max(1, round(1.0 / (film.settings.fps * world.dt))) if film else 0
        self.frames: list[dict] = []
        self.images: list[np.ndarray] = []
        self.image_times: list[float] = []  # sim time of each image (the video's caption strip needs it)
        self.render_s = 0.0
        self.grasped: str | None = None
        # a manner other than slide records the gripper per frame (the fingers' opening, m) and, for a
        # push, where the hand touches the block (``contact``: [x, y, z] or null; set by the push controller)
        self.gripper = False
        self.contact: list[float] | None = None

    def __call__(self) -> None:
        """Record after a physics step (also called once before the first step)."""
        n = self.world.steps
        if n % self.traj_every == 0:
            self.frames.append(self.snapshot())
        if self.render_every and n % self.render_every == 0:
            self.film.add(capture(self.world))
            self.image_times.append(self.world.time)

    def finish_images(self) -> None:
        """Wait for the film's frames (drawn while the episode ran): ``images`` and ``render_s``."""
        if self.film is not None and not self.images:
            self.images = self.film.finish()
            self.render_s = self.film.render_s

    def snapshot(self) -> dict:
        poses = {name: [_r(v) for v in pose] for name, pose in self.world.poses().items()}
        ee, _ = self.world.robot.tool_pose()
        frame = {"t": _r(self.world.time), "poses": poses, "ee": [_r(v) for v in ee],
                 "grasped": self.grasped, "progress": None, "arm": [_r(v) for v in self._arm_joints()]}
        if self.gripper:
            frame["gripper"] = {"opening_m": _r(self.world.robot.finger_opening()), "holding": self.grasped,
                                "contact": None if self.contact is None else [_r(v) for v in self.contact]}
        return frame

    def _arm_joints(self) -> np.ndarray:
        """The arm's movable joints now (trajectory.json's ``arm``: a replay in 3-D needs the whole arm)."""
        from .render import movable_joints
        from .sim.robot import ARM

        return self.world.sim.joint_positions(ARM, movable_joints(self.world))

    # --- writing ------------------------------------------------------------------------------
    def fill_progress(self, mover: str | None, anchor: str | list[str] | None,
                      progress_fn: Callable[..., np.ndarray] | None, first: int = 0) -> None:
        """Set every frame's ``progress`` from ``progress_fn(mover (T,3), anchor (T,3))``; else null.

        ``anchor`` may list several reference objects (a two-anchor action): the further ones' tracks
        are then passed as a third argument, a list of (T,3) arrays. ``first`` > 0 (the action begins after
        an approach slide): the function reads frames ``first`` on only, and the frames before hold the
        action's first value, as plan.json's lead-in does.
        """
        names = [anchor] if isinstance(anchor, str) else list(anchor or [])
        if progress_fn is None or mover is None or not names or not self.frames:
            return
        m, a, *more = (trajectory_poses(self.frames[first:], n) for n in [mover, *names])
        args = (m, a) + ((more,) if more else ())
        values = np.asarray(progress_fn(*args), dtype=float).reshape(-1)
        if len(values) != len(self.frames) - first:
            raise ValueError(f"progress_fn returned {len(values)} values for {len(self.frames) - first} frames")
        for f, v in zip(self.frames, hold_before(values, first), strict=True):
            f["progress"] = _r(v)

    def write_trajectory(self, path: Path, meta: dict, sizes: dict[str, float]) -> None:
        doc = {
            "schema": 1,
            "sentence": meta.get("sentence"),
            "action": meta.get("action"),
            "mover": meta.get("mover"),
            "anchor": meta.get("anchor"),
            # a two-anchor action's every reference object, a viewer-frame action's viewpoint (only then)
            **{k: meta[k] for k in ("anchors", "viewer") if meta.get(k) is not None},
            **({"segments": meta["segments"]} if meta.get("segments") is not None else {}),  # a chain's clauses
            **({"manner": meta["manner"]} if meta.get("manner") is not None else {}),  # not slide
            # the first frame of the action proper where the plan came near first (only then)
            **({"action_from": meta["action_from"]} if meta.get("action_from") else {}),
            "fps": self.fps,
            "objects": {name: {"size": size, **_colour(self.world, name), **_shape(self.world, name)}
                        for name, size in sizes.items()},
            # the arm whose movable joints each frame's "arm" lists (in this order), where its base stands
            "arm": {"name": self.world.robot.spec.name, "joints": movable_joints(self.world),
                    "base": [_r(v) for v in self.world.robot.base_xyz]},
            "frames": self.frames,
        }
        path.write_text(dumps_json(doc, separators=(",", ":")) + "\n")

    def write_images(self, out: Path, video: str = "mp4", sentence: str | list[str] | None = None) -> dict[str, Path]:
        """The video and contact_sheet.png (frames/NNNN.png the film's workers wrote); returns name -> path.

        Only the video gets the caption strip (``sentence`` and the learned progress, embodiment/overlay.py);
        the frames stay the raw renders; the contact sheet's panels are captioned with their time (and, for
        a chain, their clause). ``sentence`` may be a list, one caption per
        image (a chain captions each image with the clause being performed).
        """
        # lazy: imageio (and its ffmpeg plugin) only when a video is written
        import imageio.v2 as imageio


        self.finish_images()
        if not self.images:
            return {}
        files: dict[str, Path] = {"frames": out / "frames"}
        if self.film.folder is None:  # the film drew them without writing them
            files["frames"].mkdir(exist_ok=True)
            write_pngs(files["frames"], 0, self.images)
        fps = self.film.settings.fps
        shown = progress_at(self.image_times, np.array([f["t"] for f in self.frames]),
                            [f["progress"] for f in self.frames])
        texts = sentence if isinstance(sentence, list) else [sentence] * len(self.images)
        # a generator: each frame is captioned while ffmpeg (another process) encodes the ones before it
        captioned = (overlay(img, t, p) for img, t, p in zip(self._with_inset(), texts, shown, strict=True))
        if video == "gif":
            files["video"] = out / "video.gif"
            imageio.mimwrite(files["video"], list(captioned), duration=1000.0 / fps, loop=0)
        else:
            files["video"] = out / "video.mp4"
            # x264's "veryfast" preset: half the encoding time of its default for a file about 8 % larger
            with imageio.get_writer(files["video"], fps=fps, codec="libx264", quality=7, pixelformat="yuv420p",
                                    macro_block_size=8, ffmpeg_params=["-preset", "veryfast"]) as writer:
                for img in captioned:
                    writer.append_data(img)
        files["contact_sheet"] = out / "contact_sheet.png"
        clauses = sentence if isinstance(sentence, list) else None  # a chain's panels name their clause
        imageio.imwrite(
            files["contact_sheet"],
            contact_sheet(
                self.images,
                times=self.image_times if len(self.image_times) == len(self.images) else None,
                captions=clauses,
            ),
        )
        return files

    def _with_inset(self) -> Iterator[np.ndarray]:
        """The video's images with the top-view inset (embodiment/inset.py) drawn from each frame's state;
        the images as they are where the film has no inset or its states do not match them."""
        film = self.film
        if not film.settings.inset or len(film.states) != len(self.images):
            yield from self.images
            return
        from .inset import InsetPainter, plan_inset

        s = film.settings
        view = plan_inset(film.scene, film.paths, film.states, s.width, s.height, s.camera)
        if view is None:
            yield from self.images
            return
        painter = InsetPainter(view)
        for img, state in zip(self.images, film.states, strict=True):
            yield painter.draw(img, state)


def _colour(world, name: str) -> dict:
    scene = getattr(world, "scene", None)
    obj = next((o for o in scene.objects if o.name == name), None) if scene is not None else None
    return {} if obj is None else {"color": obj.color} | ({"shade": obj.shade} if obj.shade else {})


def _shape(world, name: str) -> dict:
    """A non-cube object's shape in trajectory.json (fields added, a cube's entry unchanged): its scene-file
    fields, its height and its centre's height standing (``z`` of the frames is that centre)."""
    scene = getattr(world, "scene", None)
    obj = next((o for o in scene.objects if o.name == name), None) if scene is not None else None
    if obj is None or obj.shape == "cube":
        return {}
    from ..core import shapes

    return {"shape": obj.shape, **shapes.fields(obj), "height": obj.height, "rest_z": world.rests[name]}


def contact_sheet(images: list[np.ndarray], n: int = 8, cols: int = 4, times: list[float] | None = None,
                  captions: list[str | None] | None = None) -> np.ndarray:
    """``n`` frames evenly spread over the episode (first and last included), in a grid. With ``times``
    (each image's simulated time, s) every panel gets a caption strip: its time and, from ``captions``
    (one per image: a chain's clause being performed), its clause."""
    from .overlay import panel_caption

    idx = np.unique(np.linspace(0, len(images) - 1, min(n, len(images))).round().astype(int))
    panels = []
    for i in idx:
        if times is None:
            panels.append(images[i])
            continue
        clause = captions[i] if captions is not None else None
        panels.append(panel_caption(images[i], f"{times[i]:.1f} s" + (f"  {clause}" if clause else "")))
    h, w, _ = panels[0].shape
    rows = -(-len(idx) // cols)
    sheet = np.full((rows * h, cols * w, 3), 255, dtype=np.uint8)
    for k, panel in enumerate(panels):
        r, c = divmod(k, cols)
        sheet[r * h : (r + 1) * h, c * w : (c + 1) * w] = panel
    return sheet


def versions() -> dict[str, str]:
    """Versions of everything that can change a result."""
    out = {"python": sys.version.split()[0], "platform": _platform()}
    for pkg in ("l2p-bullet", "pybullet", "numpy", "ruckig", "torch"):
        try:
            out[pkg] = metadata.version(pkg)
        except metadata.PackageNotFoundError:
            out[pkg] = "not installed"
    return out


def _platform() -> str:
    """platform.platform() without the processor name, which Python finds by running ``uname -p`` in a
    subprocess (20-30 ms of every run)."""
    u = platform.uname()
    libc = "".join(platform.libc_ver()) if u.system == "Linux" else ""
    return "-".join(p for p in (u.system, u.release, u.machine, "with" if libc else "", libc) if p)
