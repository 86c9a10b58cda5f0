"""The teach page for a composite action ("make a row of A, B and C"): whole rows, segmented into drags.

A scene has 2 or 3 blocks (even seeds 2, odd seeds 3; 4 cm cubes scattered on the table). The sentence
names them in order; the person drags the blocks one after another. The page segments the motion the
simple way: a block is moving while it is dragged, so each drag (pointer down on a block .. pointer up) is
one segment, sampled on every move. :meth:`RowLesson.save_row` checks the drags (each starts where its
block then stood, stays on the table, never passes through another block; the row lasts 5 frames and
moves each of its blocks half a side) and appends the demonstration
to the bundle's ``demos.json``. "Train" learns the recipe from every demonstration there
(composite/recipe.py: each drag recognised as one of the installed actions) and performs a row of four
on a new scene, with video.
"""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..chain import perform_chain
from ..chain.composite import row_verdict
from ..composite.bundle import read_demos, write_demos, write_recipe
from ..composite.recipe import CompositeError, Demonstration, Segment, learn
from ..core.contracts import read_json, trajectory_poses
from ..core.scene import Scene, random_scene
from ..data.tracking import page_samples
from ..errors import TeachError
from ..evaluate.scenes import add_bystanders
from ..plugins import registry
from ..recognition import recognisers
from .checks import (
    MAX_SPEED,
    MIN_FRAMES,
    MIN_TRAVEL,
    Duplicate,
    checked_samples,
    first_collision,
    fmt,
    travel,
)
from .lesson import FPS, Job, Lesson

BLOCK = 0.04
"""Block side of the scenes (m): the rows benchmark's cubes."""

PERFORM_BLOCKS = 4
"""How many blocks the row performed after training has: more than any demonstration (recursion)."""


def row_scene(seed: int, blocks: int, size: float = BLOCK) -> Scene:
    """``blocks`` cubes scattered on the table, deterministic for ``seed`` (A, B like ``random_scene``,
    the others placed at random: evaluate.scenes.add_bystanders)."""
    return add_bystanders(random_scene(seed, size), blocks - 2, seed)


def row_sentence(phrase: str, names: list[str]) -> str:
    return f"{phrase} {', '.join(names[:-1])} and {names[-1]}"


def same_row(a: Demonstration, b: Demonstration) -> bool:
    """Whether ``b`` is ``a`` posted again: the same scene and drags, the samples equal once each drag's
    times start at 0 (a page that sends absolute times sends a re-post shifted)."""
    if a.scene != b.scene or [s.block for s in a.segments] != [s.block for s in b.segments]:
        return False
    for sa, sb in zip(a.segments, b.segments, strict=True):
        x, y = np.asarray(sa.samples, float), np.asarray(sb.samples, float)
        if x.shape != y.shape:
            return False
        x[:, 0] -= x[0, 0]
        y[:, 0] -= y[0, 0]
        if not np.allclose(x, y, rtol=0, atol=1e-6):
            return False
    return True


class RowLesson(Lesson):
    """:class:`Lesson` for a composite action: scenes of 2-3 blocks, rows of drags, a recipe learned."""

    def scene(self, seed: int) -> Scene:
        return row_scene(seed, 2 + seed % 2)

    def names(self, seed: int) -> list[str]:
        return [o.name for o in self.scene(seed).objects]

    def scene_json(self, seed: int) -> dict[str, Any]:
        scene, names = self.scene(seed), self.names(seed)
        return {
            "seed": seed, "sentence": row_sentence(self.action.phrases[0], names), "mover": None,
            "movers": names[1:], "anchors": [], "composite": True,
            "objects": [{"name": o.name, "color": o.color, "rgb": [round(255 * c) for c in o.rgba[:3]],
                         "size": o.size, "x": o.xy[0], "y": o.xy[1], "yaw": o.yaw} for o in scene.objects],
            "workspace": scene.workspace.to_dict(),  # x, y, r; and the ring's fields for a ring
            "table": {"half_x": scene.table.half_x, "half_y": scene.table.half_y},
        }

    def config(self) -> dict[str, Any]:
        return {
            **super().config(),
            "composite": True,
            "sentence": row_sentence(self.action.phrases[0], ["A", "B", "C"]),
            "demos": str(self.action.bundle_dir / "demos.json"),
        }

    def count(self) -> int:
        return len(read_demos(self.action.bundle_dir))

    # --- recording ------------------------------------------------------------------------------
    def save(self, rec: Any) -> dict[str, Any]:
        """A single action's recording (``/api/demos``) has no place in a composite's rows."""
        raise TeachError("this teach page records composite rows: drag the blocks one after another and "
                         "save the row with /api/rows")

    def save_row(self, seed: int, segments: list[dict[str, Any]]) -> dict[str, Any]:
        """Check the drags of one row and append it to ``demos.json``; the count and the file.

        Each drag meets the single action's limits (``teach/checks.py``) before it is resampled: at most
        :data:`~.checks.MAX_SAMPLES` finite samples over :data:`~.checks.MAX_SECONDS`. The minimums are
        the row's, not each drag's, because the page cannot drop one drag (the person would record the
        whole row again for a small corrective nudge or a quick flick): the drags last
        :data:`~.checks.MIN_FRAMES` frames in all, and each block they move travels
        :data:`~.checks.MIN_TRAVEL` blocks over its drags. A drag that moves its block in no time (its
        samples at one instant), or faster than a hand drags a block (:data:`~.checks.MAX_SPEED` on
        average: a token span of a microsecond is a teleport too), is refused; a fast one is checked on its
        path like any other. The path checked, and the travel counted, are those of the samples the
        saved track is built from (:func:`~l2p_bullet.data.tracking.page_samples`), not of samples it drops."""
        scene, names = self.scene(seed), self.names(seed)
        if not segments:
            raise TeachError("drag the blocks into a row first (nothing was dragged)")
        drags = [Segment(str(s["block"]), s["samples"]) for s in segments]
        demo = Demonstration(scene.to_dict(), names, drags, seed)
        try:
            demo.check()
        except CompositeError as e:
            raise TeachError(str(e)) from None
        for k, s in enumerate(demo.segments, 1):
            s.samples = checked_samples(s.samples, f"drag {k}").tolist()
        poses = {o.name: o.pose.copy() for o in scene.objects}
        travelled: dict[str, float] = {}
        seconds = 0.0
        for k, s in enumerate(demo.segments, 1):
            samples, track = np.asarray(s.samples, float), s.track()
            if np.hypot(*(track[0, :2] - poses[s.block][:2])) > 0.002:
                raise TeachError(f"drag {k} does not start where block {s.block} stood")
            span = samples[-1, 0] - samples[0, 0]
            if span <= 0 and np.abs(samples[:, 1:] - samples[0, 1:]).max() > 0.002:
                raise TeachError(f"drag {k} moves block {s.block} in no time (all its samples at one instant): "
                                 "slide it")
            kept = page_samples(samples)
            seconds += span
            size = scene.get(s.block).size
            moved = travel(kept[:, 1:], size)
            travelled[s.block] = travelled.get(s.block, 0.0) + moved
            self._check_drag(scene, s.block, track, poses, k, kept)
            if span > 0 and moved * size / span > MAX_SPEED:
                raise TeachError(f"drag {k} moves block {s.block} at {fmt(moved * size / span)} m/s; a hand drags "
                                 f"a block at most {MAX_SPEED:g} m/s: slide it")
            poses[s.block] = samples[-1, 1:]  # where the page left it (the track's last frame, page_track)
        if seconds < MIN_FRAMES / FPS:
            raise TeachError(f"the drags last {fmt(seconds)} s in all: slide the blocks into a row")
        for block, moved in travelled.items():
            if moved < MIN_TRAVEL:
                raise TeachError(f"the drags moved block {block} {moved:.2f} blocks in all; a block the row moves "
                                 f"travels at least {MIN_TRAVEL} blocks")
        moved = {s.block for s in demo.segments}
        if len(moved) < len(names) - 1:
            raise TeachError(f"a row of {len(names)} moves {len(names) - 1} blocks; "
                             f"{', '.join(n for n in names[1:] if n not in moved)} did not move")
        with self._lock:
            old = read_demos(self.action.bundle_dir)
            same = next((i for i, d in enumerate(old, 1) if same_row(d, demo)), None)
            if same is not None:
                raise Duplicate(f"this row is demonstration {same} of {self.action.bundle_dir / 'demos.json'} "
                                "already (the same scene and drags): record a new one")
            demos = old + [demo]
            try:  # refused past what reading and training accept: a file saved past it is lost for good
                write_demos(self.action.bundle_dir, demos)
            except CompositeError as e:
                raise TeachError(str(e)) from None
        return {"demos": str(self.action.bundle_dir / "demos.json"), "count": len(demos),
                "segments": len(demo.segments), **self.training_note()}

    def remove(self, k: int) -> dict[str, Any]:
        """Remove row ``k`` (1 = the first) from ``demos.json``; the file and the rows left."""
        with self._lock:
            demos = read_demos(self.action.bundle_dir)
            if not 1 <= k <= len(demos):
                raise TeachError(f"there is no demonstration {k}: {self.action.bundle_dir / 'demos.json'} holds "
                                 f"{len(demos)}")
            del demos[k - 1]
            write_demos(self.action.bundle_dir, demos)
        return {"demos": str(self.action.bundle_dir / "demos.json"), "count": len(demos), "removed": k}

    @staticmethod
    def _check_drag(scene: Scene, block: str, track: np.ndarray, poses: dict, k: int,
                    samples: np.ndarray | None = None) -> None:
        """The block's frames (``track``) stay on the table, and its path (``samples`` ``[t, x, y, yaw]``,
        the poses the page placed it at that ``track`` is built from, :func:`~l2p_bullet.data.tracking.page_samples`,
        and
        the jumps between them; ``track`` without them) never passes
        through another block where it then stood: :func:`~.checks.first_collision`, which allows a jump
        across a corner that the page allowed, not one through a block."""
        obj = scene.get(block)
        path = track if samples is None else np.column_stack([samples[:, 1:3], np.unwrap(samples[:, 3])])
        for pose in np.vstack([track, path[-1:]]):
            if not scene.table.contains(obj.footprint(pose)):
                raise TeachError(f"drag {k}: block {block} left the table")
        try:
            hit = first_collision(obj, path, [(o, poses[o.name]) for o in scene.objects if o.name != block])
        except TeachError as e:
            raise TeachError(f"drag {k}: {e}") from None
        if hit is not None:
            raise TeachError(f"drag {k}: block {block} passed through block {hit[1]}")

    # --- training and performing ----------------------------------------------------------------
    def train(self) -> dict[str, Any]:
        with self._lock:
            if self.job.state in ("training", "performing"):
                raise TeachError("training is already under way")
            if not self.count():
                raise TeachError("no rows recorded yet: drag the blocks into a row and save it first")
            runs = self.job.runs
            self.job = Job(state="training", message="recognising the drags", started=time.time(), runs=runs, total=1)

            self._thread = threading.Thread(target=self._work, args=([],), daemon=True, name="teach-rows")
            self._thread.start()
        return self.status()

    def _train(self, files: list[Path]) -> None:
        learn_bundle(self.action.bundle_dir)
        self.job.done = 1

    def _perform(self) -> None:
        self.job.state, self.job.message = "performing", f"performing a row of {PERFORM_BLOCKS} on a new scene"
        k = len(self.job.runs)
        seed = 100_000 + k
        scene = row_scene(seed, PERFORM_BLOCKS)
        names = [o.name for o in scene.objects]
        sentence = row_sentence(self.action.phrases[0], names)
        plugins = registry.discover() + [registry.local(self.action.name, self.action.bundle_dir)]
        out = self.action.root / "runs" / f"teach-{k:03d}"
        r = perform_chain(sentence, scene, out_dir=out, seed=seed, force=True, plugins=plugins,
                          render_settings=self.render_settings)
        row = row_verdict(final_scene(out, scene), names, _displaced(r))
        self.job.runs.append(out)
        verdict = {"success": r.success and row["success"], "judge": "row", "reason": row["reason"],
                   "chain": r.verdict(), "row": row}
        self.job.run = {"id": k, "sentence": sentence, "scene": seed, "folder": str(out), "verdict": verdict,
                        "final_progress": None, "video": f"/api/runs/{k}/video" if "video" in r.files else None}
        self.job.state, self.job.message = "done", "done"


def learn_bundle(bundle_dir: Path) -> Any:
    """Learn the recipe from the bundle's ``demos.json`` with the installed actions; write ``recipe.json``."""
    demos = read_demos(bundle_dir)
    recipe = learn(demos, recognisers()[0])
    write_recipe(bundle_dir, recipe)
    return recipe


def final_scene(run: Path, scene: Scene) -> Scene:
    """``scene`` with every block where the run's last frame has it."""
    frames = read_json(run / "trajectory.json")["frames"]
    out = scene
    for o in scene.objects:
        p = trajectory_poses(frames[-1:], o.name)[-1]
        out = out.with_pose(o.name, p[[0, 1, 3]] if len(p) == 4 else p)
    return out


def _displaced(result: Any) -> dict[str, float]:
    """Blocks moved > 1 mm by a clause that did not move them (the chain's judge already fails on them)."""
    out: dict[str, float] = {}
    for c in result.results:
        for k, v in c.displacements_m.items():
            out[k] = max(out.get(k, 0.0), float(v))
    return out
