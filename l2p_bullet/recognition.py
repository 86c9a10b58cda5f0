"""Recognition: which installed action does a motion show, and of which blocks?

The paper separates learning to recognise an action from learning to perform it; a progress model does
both, because it was trained to say how far a motion has got through its action (0 for the other
actions' motions, which are its negatives). So every installed action's model scores the motion, for
each block that moved against each other block (a two-anchor action against each pair of other blocks),
and the readings are ranked by their final progress: the best one is the answer ("A moved past B: 0.91").

Choices, and what they were chosen on (the session split of ``benchmarks/bench_recognize.py``: looked
at on Session 1 -> 2 only, Session 2 -> 1 held out; docs/learning.md, "Recognition"):
- readings are ranked by the raw final progress; dividing each action's by its mean on its own training
  demonstrations changed no answer on 1 -> 2 and is not done. Ties (equal floats) keep the models' order;
- a block "moved" when it got at least :data:`MOVED_SIDES` of its side from where it started; if none
  did, the one that moved most is the mover (a tiny motion still gets readings);
- motions captured from people (``--demo``) are smoothed as the training recipe smooths them
  (``data.demos.SMOOTH_FRAMES``, the training recipe's window) and cut to the annotated event, as ``replay --demo``
  executes it.
Numpy only (no torch): the same models ``perform`` plans with.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import permutations
from pathlib import Path
from typing import Any

import numpy as np

from .core.contracts import Plan, block_size, motion_from_dict, read_json, trajectory_poses
from .core.geometry import moving_average
from .core.scene import MAX_OBJECTS
from .core.vocabulary import canonical_action
from .data.demos import SMOOTH_FRAMES, get_demo
from .errors import L2PError, PathError
from .plugins import registry
from .plugins.bundle import load_bundle

MOVED_SIDES = 0.5
"""How far (block sides, from its start) a block must get to count as moved. A still block read as a
mover only adds readings, but the people's static block drifts in the captures, and a drift beside the
mover can read as a small "next to". On Session 1 -> 2: 0.5 and reading only the block that moved most
give the same answers; 0.25, 0.1 and 0 (every block) each lose two of the 91 demonstrations that way."""

MAX_READINGS = 5000
"""Most (action, mover, anchors) readings one call scores: a bound on the work for a hostile file."""


@dataclass
class Tracks:
    """Named blocks' poses ``(T, 3)`` over one motion, in one metric frame, with each block's side."""

    poses: dict[str, np.ndarray]
    sizes: dict[str, float]
    source: str = ""
    viewer: np.ndarray | None = None  # (2,) the viewpoint, when the file gives one

    def displacement(self, name: str) -> float:
        """How far block ``name`` got from its start, in its own block sides."""
        p = self.poses[name][:, :2]
        return float(np.max(np.hypot(*(p - p[0]).T))) / self.sizes[name]

    def moved(self) -> list[str]:
        """The blocks that moved (:data:`MOVED_SIDES`), or the one that moved most if none did."""
        moved = [n for n in self.poses if self.displacement(n) >= MOVED_SIDES]
        return moved or [max(self.poses, key=self.displacement)]


@dataclass(frozen=True)
class Recogniser:
    """One action as recognition uses it: its name, the phrase its readings are written with, its model."""

    action: str
    phrase: str
    model: Any  # a progress model (progress.model.NumpyProgressModel or anything with its scoring API)


@dataclass(frozen=True)
class Reading:
    action: str
    phrase: str
    mover: str
    anchors: tuple[str, ...]
    final: float

    @property
    def claim(self) -> str:
        """What the reading says happened: "A moved past B"."""
        return f"{self.mover} moved {self.phrase} {' and '.join(self.anchors)}"

    @property
    def sentence(self) -> str:
        return f"{self.claim}: {self.final:.2f}"

    def to_dict(self) -> dict:
        return {"action": self.action, "mover": self.mover, "anchors": list(self.anchors),
                "final": round(self.final, 4), "sentence": self.sentence}


@dataclass
class Recognition:
    source: str
    moved: list[str]
    readings: list[Reading]  # best first
    skipped: list[dict] = field(default_factory=list)  # installed actions that could not be loaded, and why

    @property
    def best(self) -> Reading:
        return self.readings[0]

    def to_dict(self) -> dict:
        return {"source": self.source, "moved": self.moved, "best": self.best.to_dict(),
                "sentence": self.best.sentence, "readings": [r.to_dict() for r in self.readings],
                "skipped": self.skipped}


def recognize(tracks: Tracks, recognisers: list[Recogniser]) -> Recognition:
    """Every recogniser's final progress for every moved block against every other block (or pair of
    other blocks, for a two-anchor action), best first (:class:`Recognition`)."""
    names = list(tracks.poses)
    if len(names) < 2:
        raise PathError(f"{tracks.source}: recognition needs at least two blocks (a mover and a reference)")
    moved = tracks.moved()
    n = len(moved) * sum(math.perm(len(names) - 1, getattr(r.model, "anchors", 1)) for r in recognisers)
    if n > MAX_READINGS:  # counted before any list is built: a hostile file must not exhaust memory
        raise PathError(f"{tracks.source}: {len(moved)} moved blocks among {len(names)} give {n} readings; at most "
                        f"{MAX_READINGS} are scored (recognise fewer blocks at a time)")
    if not n:
        raise PathError(f"{tracks.source}: none of the actions reads {len(names) - 1} reference block(s)")
    jobs = []  # (order, recogniser, mover, anchor tuples)
    for order, r in enumerate(recognisers):
        for m in moved:
            groups = list(permutations([x for x in names if x != m], getattr(r.model, "anchors", 1)))
            if groups:
                jobs.append((order, r, m, groups))
    ranked = []
    for order, r, m, groups in jobs:
        for j, (g, final) in enumerate(zip(groups, _finals(r.model, tracks, m, groups), strict=True)):
            ranked.append((-final, order, moved.index(m), j, Reading(r.action, r.phrase, m, g, float(final))))
    ranked.sort(key=lambda t: t[:4])
    return Recognition(tracks.source, moved, [t[-1] for t in ranked])


def _finals(model: Any, tracks: Tracks, mover: str, groups: list[tuple[str, ...]]) -> np.ndarray:
    """One batch: ``mover``'s final progress against each group of anchors."""
    m = tracks.poses[mover]
    anchors = [tracks.poses[g[0]] for g in groups]
    kw: dict[str, Any] = {"viewer": tracks.viewer}
    if len(groups[0]) > 1:
        kw["more_anchors"] = [[tracks.poses[g[i]] for g in groups] for i in range(1, len(groups[0]))]
    return model.final_batch([m] * len(groups), anchors, tracks.sizes[mover], **kw)


# --- what recognition reads ------------------------------------------------------------------------
def read_tracks(path: str | Path) -> Tracks:
    """A run folder (its ``trajectory.json``), a ``trajectory.json`` (every object's poses), a ``plan.json``
    or a scoring input (mover and anchors; unnamed blocks are called A, B, C), checked by the same readers
    as ``l2p-bullet score``."""
    p = Path(path)
    if p.is_dir():
        if not (p / "trajectory.json").is_file():
            raise PathError(f"{p} is a folder without trajectory.json (give a run folder, a trajectory.json, "
                            "a plan.json or a scoring input)")
        p = p / "trajectory.json"
    elif not p.exists():
        raise PathError(f"{p} does not exist")
    d = read_json(p)
    src = str(p)
    motion = motion_from_dict(d, source=src)  # the contract's own checks first
    if "frames" in d:
        return _trajectory_tracks(d, src, motion.viewer, motion.action_from)
    if "path" in d:
        plan = Plan.from_dict(d, source=src)
        names = [plan.mover, *plan.anchors]
    else:
        names = ["A", "B", "C"][: 2 + len(motion.more_anchors)]
    if len(set(names)) != len(names):
        raise PathError(f"{src}: the mover and the anchors must be different blocks (got {names})")
    poses = dict(zip(names, [motion.mover, motion.anchor, *motion.more_anchors], strict=True))
    return Tracks(poses, {n: motion.size for n in names}, src, motion.viewer)


def _trajectory_tracks(d: dict, src: str, viewer: np.ndarray | None, first: int = 0) -> Tracks:
    """Every object of a trajectory.json (whose mover and anchors the contract reader has checked), from frame
    ``first`` on (``action_from``: a run that came near first is read from where its action began, as
    ``score`` and the planner read it)."""
    objects = d["objects"]
    if not isinstance(objects, dict):
        raise PathError(f'{src}: not a valid trajectory.json ("objects" must map names to objects)')

    if len(objects) > MAX_OBJECTS:
        raise PathError(f"{src}: {len(objects)} objects; a scene holds at most {MAX_OBJECTS}")
    poses, sizes = {}, {}
    for name, obj in objects.items():
        try:
            track = trajectory_poses(d["frames"], name)
            size = obj["size"]
        except (KeyError, IndexError, TypeError, ValueError, OverflowError):
            raise PathError(f'{src}: not a valid trajectory.json (the poses of "{str(name)[:40]}" must be '
                            "[x, y, z, yaw] in every frame, and the object needs a size)") from None
        if not np.all(np.isfinite(track)):
            raise PathError(f'{src}: the poses of "{str(name)[:40]}" contain non-finite numbers')
        poses[name], sizes[name] = track[first:], block_size(size, src, f"objects.{str(name)[:40]}.size")
    return Tracks(poses, sizes, src, viewer)


def demo_tracks(spec: str) -> Tracks:
    """``--demo ACTION:INDEX``: a shipped human demonstration (the order of ``replay --demo``), the mover
    called A and the other block B, smoothed as the training recipe smooths captures, cut to the event."""
    action, sep, index = spec.partition(":")
    if not sep or not index.strip().lstrip("-").isdigit():
        raise PathError(f'--demo expects ACTION:INDEX, e.g. around:0 (got "{spec}")')
    return demo_event_tracks(get_demo(canonical_action(action), int(index)))


def demo_event_tracks(demo: Any) -> Tracks:
    """A :class:`data.demos.Demo` as recognition reads it (see :func:`demo_tracks`)."""
    w = SMOOTH_FRAMES
    ev = slice(demo.start, demo.end + 1)
    m, a = (moving_average(t, w)[ev] if w > 1 and len(t) >= 3 else t[ev] for t in (demo.mover, demo.anchor))
    return Tracks({"A": m, "B": a}, {"A": demo.size, "B": demo.size}, f"demonstration {demo.id}", demo.viewer)


# --- which actions ---------------------------------------------------------------------------------
def recognisers(specs: list[str] | tuple[str, ...] = ()) -> tuple[list[Recogniser], list[dict]]:
    """The actions to recognise with: ``specs`` (installed names or bundle folders, as ``score`` takes),
    else every usable installed action; and the installed ones left out, each with its reason."""
    out, skipped = [], []
    if specs:
        for spec in specs:
            name, folder = registry.locate(spec)
            bundle = load_bundle(folder) if Path(spec).is_dir() else registry.load(name)
            out.append(_recogniser(name, bundle))
        return out, skipped
    plugins = registry.discover()
    for info in plugins:
        try:
            if not info.ok:
                raise L2PError(info.error)
            out.append(_recogniser(info.name, registry.load(info.name, plugins)))
        except L2PError as e:
            skipped.append({"action": info.name, "reason": str(e)})
    return out, skipped


def _recogniser(name: str, bundle: Any) -> Recogniser:
    return Recogniser(name, str((bundle.phrases or [name])[0]), bundle.progress_model())
