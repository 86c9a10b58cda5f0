"""Training recipes, the shipped one among them: :data:`SHIPPED` is what ``l2p-bullet train``, ``teach`` and
``make bundles`` use (recorded in each manifest's ``[training.recipe]``). The others were compared with it on the
grade-free suite (``research/generalise.py``); the session-split models they give are cached on
disk so a table can be re-printed without re-training.

A recipe is the current training set (:func:`trainset.build`, unchanged: its sequences and their hashes
are those of ``l2p-bullet train``) plus optional extra sequences appended after it, drawn from their own
generator so the current part stays bit-identical:

- ``planner_positives``: each own event (and its mirror image) as the planners make motions, straight
  moves through 1-3 of its own poses snapped to the discrete planner's rings (around also snapped to the
  2-D study's move grid), labelled like the event;
- ``planner_negatives``: wrong piecewise-straight motions made from each own event, label 0 on their
  tail like every negative: closer backs off 1.5-4 blocks and returns to its start distance, away goes
  out and comes back, closer / away / next-to run backwards, past goes to its closest approach and
  back, around goes half way round and straight back;
- ``contrastive``: the other actions' demonstrations (those ``DataConfig.negatives`` names) in the
  planner's domain too, straightened and snapped to the rings, as negatives;
- ``turn_power``: around's net-turn label raised to this power (2: half a turn earns 0.25, not 0.5);
- ``planner_partials``: each own event (and mirror) as straight moves and as ring-snapped moves through
  1-3 of its poses, stopped at 30 % and 60 % of that motion's length, labelled with the progress the
  whole motion has there (a planner's motion stopped early: partial credit, not full);
- ``graded_wrongs``: planner motions that undo part of the action, with the credit a rule leaves them:
  closer / away go on from the end back a random share u (0.2-1) of the way to the start and end with
  1 - u of the event's label; next-to goes on 1-5 blocks straight out from its place and ends with
  1 - blocks / 5 of it; the label falls linearly along the extra move.
- ``strays`` (around): its own path through 4-6 of its poses with one of them after the start (the end
  included) moved straight out to one of the planner's two outer rings (5 or 6.5 blocks), with the credit
  a rule leaves it: around means going round near the anchor (its rule's ``near``, 4 blocks), so the label
  keeps 1 - (ring - near) / (6.5 - near) of itself from that corner on (0.6 at 5 blocks, 0 at 6.5),
  falling linearly along the move out to it.

- ``near_starts`` (closer): each own event shrunk about the anchor to end 1.05-1.2 blocks from it (touching,
  with the planner's margin), cropped to start where it first comes within 1.25-2.5 blocks, as it is and as one
  straight move, labelled as full events: people's endings made short, because chains start "closer" 1.25-1.75
  blocks from the anchor and no person's demonstration started nearer than 3.6 (docs/learning.md, "closer from near":
  the suite's strengthened score fell, 0.4255 -> 0.4225, so it is not shipped).

``trusted_own`` changes the data, not what is added: the shipped demonstrations of the action being trained
whose tracking is not trusted (:data:`data.demos.UNTRUSTED`) are left out of its own set (its positives and
everything made from its own events), and kept wherever they are another action's negative, so the other
actions' sets are bit-identical (:func:`own_trusted`; docs/learning.md, "untrusted demonstrations": it passed the suite
and the planning checks but lowered around's agreement with people in SlideAround, so it is not shipped).

The training options of :class:`ProgressTrainConfig` (weight decay, an ordinal head) are the rest.

Nothing here reads a grade.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..actions.around import ACTION as AROUND
from ..core.vocabulary import ACTIONS
from ..data.demos import UNTRUSTED, Demo
from ..progress.features import QSRConfig
from . import motions as g
from .augment import mirror
from .train_progress import ProgressTrainConfig, TrainResult, train_action
from .trainset import DataConfig, TrainingSequence, _labelled, build

AROUND_NEAR = AROUND.thresholds["near"]
"""around's rule: never farther than this many blocks once near (``strays`` gives full credit up to it)."""

PARTIAL_CUTS = (0.3, 0.6)
"""Where ``planner_partials`` stops a planner-domain copy, as fractions of its length."""


@dataclass(frozen=True)
class Recipe:
    name: str
    data: DataConfig = field(default_factory=DataConfig)
    train: ProgressTrainConfig = field(default_factory=ProgressTrainConfig)
    planner_positives: bool = False
    planner_negatives: bool = False
    contrastive: bool = False
    turn_power: float = 1.0
    planner_partials: bool = False
    graded_wrongs: bool = False
    grid: bool = True
    """With ``planner_positives``: around also gets copies snapped to the 2-D study's grid."""
    strays: bool = False
    trusted_own: bool = False
    """Leave the action's own untrusted shipped demonstrations out of its own set (:func:`own_trusted`)."""
    near_starts: bool = False
    """closer: people's endings made short, as full events (:func:`_near`)."""

    def extras_dict(self) -> dict:
        """The options that add to the current training set (empty for the current recipe): what a
        bundle's manifest records besides the training settings."""
        keys = ("planner_positives", "planner_negatives", "contrastive", "planner_partials", "graded_wrongs",
                "strays", "trusted_own", "near_starts")
        out = {k: True for k in keys if getattr(self, k)} | ({"grid": False} if not self.grid else {})
        return out | ({"turn_power": self.turn_power} if self.turn_power != 1.0 else {})

    def describe(self) -> dict:
        return {"name": self.name, "planner_positives": self.planner_positives,
                "planner_negatives": self.planner_negatives, "contrastive": self.contrastive,
                "turn_power": self.turn_power, **self.train.to_dict(),
                **({"planner_partials": True} if self.planner_partials else {}),
                **({"graded_wrongs": True} if self.graded_wrongs else {}), **({"grid": False} if not self.grid else {}),
                **({"strays": True} if self.strays else {}), **({"trusted_own": True} if self.trusted_own else {}),
                **({"near_starts": True} if self.near_starts else {})}


SHIPPED = Recipe("planner-graded-nogrid", planner_positives=True, planner_negatives=True, planner_partials=True,
                 graded_wrongs=True, grid=False)
"""The recipe ``l2p-bullet train`` (so ``make bundles`` and ``teach``) trains with, training settings from
the command (5 LSTMs x 30 epochs by default): planner-graded-nogrid, the one that cleared the rule committed
before the recipes were compared (docs/learning.md: strengthened suite 0.438 against the current recipe's 0.321, 33 goals
against 26; planning and perform 100 % on the 30-scene benchmarks). Its extras are written into every bundle's
manifest (``[training.recipe]``)."""


def shipped_extension(action: str, demos: dict[str, list[Demo]], qcfg: QSRConfig, data_cfg: DataConfig,
                      seed: int) -> Callable[[list[TrainingSequence]], list[TrainingSequence]]:
    """:data:`SHIPPED`'s extension of the set :func:`trainset.build` made with ``data_cfg`` (a plugin's
    own data settings are kept; a viewer-frame or two-anchor plugin gets nothing added)."""
    return functools.partial(extend, dataclasses.replace(SHIPPED, data=data_cfg), action, demos, qcfg, seed)


def own_trusted(recipe: Recipe, action: str, demos: dict[str, list[Demo]]) -> dict[str, list[Demo]]:
    """``demos`` as ``action`` trains on them with ``recipe``: with ``trusted_own``, its own list without the
    ids of :data:`data.demos.UNTRUSTED` (the other actions' lists, its negatives, unchanged). Call it on the
    shipped demonstrations only: a user's own files are taken as they are (their ids could coincide)."""
    if not recipe.trusted_own or not any(d.id in UNTRUSTED for d in demos.get(action, [])):
        return demos
    return {**demos, action: [d for d in demos[action] if d.id not in UNTRUSTED]}


def recipes(ensemble: int, epochs: int) -> dict[str, Recipe]:
    """The recipes compared on the grade-free suite, at a given ensemble size and length of training."""
    t = ProgressTrainConfig(ensemble=ensemble, epochs=epochs)
    small = dataclasses.replace(t, hidden=16)
    return {r.name: r for r in [
        Recipe("current", train=t),
        Recipe("small", train=small),
        Recipe("planner", train=t, planner_positives=True, planner_negatives=True),
        Recipe("contrastive", train=t, contrastive=True),
        Recipe("planner+contrastive", train=t, planner_positives=True, planner_negatives=True, contrastive=True),
        Recipe("around-convex", train=t, turn_power=2.0),
        Recipe("all", train=t, planner_positives=True, planner_negatives=True, contrastive=True, turn_power=2.0),
        # tried against the strengthened suite (docs/learning.md), one setting each
        Recipe("planner-partial", train=t, planner_positives=True, planner_negatives=True, planner_partials=True),
        Recipe("decay", train=dataclasses.replace(t, weight_decay=0.01)),
        Recipe("small-decay", train=dataclasses.replace(small, weight_decay=0.01)),
        Recipe("ordinal", train=dataclasses.replace(t, levels=4)),
        # chosen after the strengthened suite's table (docs/learning.md)
        Recipe("planner-graded", train=t, planner_positives=True, planner_negatives=True, planner_partials=True,
               graded_wrongs=True),
        # planner-graded without around's grid copies (with them its around planned 90 %)
        Recipe("planner-graded-nogrid", train=t, planner_positives=True, planner_negatives=True,
               planner_partials=True, graded_wrongs=True, grid=False),
        # around's strays with partial credit (for the far corner the planning check found)
        Recipe("planner-graded-nogrid-strays", train=t, planner_positives=True, planner_negatives=True,
               planner_partials=True, graded_wrongs=True, grid=False, strays=True),
        # the shipped recipe with around's own glitched demonstration left out (not its negatives)
        Recipe("planner-graded-nogrid-trusted", train=t, planner_positives=True, planner_negatives=True,
               planner_partials=True, graded_wrongs=True, grid=False, trusted_own=True),
        # the shipped recipe with closer's endings made short (chains start closer from near)
        Recipe("planner-graded-nogrid-near", train=t, planner_positives=True, planner_negatives=True,
               planner_partials=True, graded_wrongs=True, grid=False, near_starts=True),
    ]}


def _event_views(d: Demo, dcfg: DataConfig) -> list[g.Event]:
    """A demonstration's event and its mirror image, smoothed (metres)."""
    e = g.events([d], dcfg.smooth_frames)[0]
    return [e, dataclasses.replace(e, mover=mirror(e.mover), anchor=mirror(e.anchor[None])[0])]


def _wrong(e: g.Event, rng: np.random.Generator) -> list[np.ndarray]:
    """Wrong piecewise-straight motions made from an own event (module docstring)."""
    m, c, step = e.mover, e.anchor, 0.25 * e.size
    p0, p1 = m[0], m[-1]
    if e.action == "closer":
        d = p0[:2] - c[:2]
        r0 = max(float(np.linalg.norm(d)), 1e-9)
        out, back = p0.copy(), p0.copy()
        out[:2] = p0[:2] + d / r0 * rng.uniform(1.5, 4.0) * e.size
        back[:2] = c[:2] + d / r0 * (r0 + rng.uniform(-0.3, 0.3) * e.size)
        ways = [np.array([p0, out, back]), np.array([p1, p0])]
    elif e.action == "away":
        ways = [np.array([p0, p1, p0 + np.r_[rng.normal(0, 0.3 * e.size, 2), 0.0]]), np.array([p1, p0])]
    elif e.action == "next-to":
        ways = [np.array([p1, p0])]
    elif e.action == "past":
        k = int(np.argmin(np.hypot(*(m[:, :2] - c[:2]).T)))
        ways = [np.array([p0, m[k], p0])]
    else:
        half = g.waypoints(m[: max(2, len(m) // 2)], 2)
        ways = [np.concatenate([half, half[-2::-1]])]
    return [g.straight_moves(w, step) for w in ways]


def _graded(e: g.Event, rng: np.random.Generator) -> list[tuple[np.ndarray, np.ndarray, float]]:
    """Wrong planner motions that keep part of the credit (``graded_wrongs``): (the event as straight
    moves' waypoints, what follows it, the share of the event's final label left at the end)."""
    m, c = e.mover, e.anchor
    p0, p1 = m[0], m[-1]
    whole = g.waypoints(m, int(rng.integers(1, 4)))
    if e.action in ("closer", "away"):  # back a share u of the way to the start: 1 - u of it is left
        u = rng.uniform(0.2, 1.0)
        return [(whole, (p1 + u * (p0 - p1))[None], 1.0 - u)]
    if e.action == "next-to":  # k blocks straight out from its place beside the anchor
        k = rng.uniform(1.0, 5.0)
        q = p1.copy()
        q[:2] = c[:2] + (p1 - c)[:2] * (1 + k * e.size / max(float(np.linalg.norm((p1 - c)[:2])), 1e-9))
        return [(whole, q[None], max(0.0, 1.0 - k / GRADED_FAR))]
    return []


GRADED_FAR = 5.0
"""Blocks past its place at which a next-to keeps no credit (the planner's second-widest ring)."""

STRAY_RINGS = tuple(g.DISTANCES[-2:])
"""Where ``strays`` moves one of around's corners to (blocks from the anchor): the discrete planner's two
outer rings (``planning.proposals.DISTANCES``); at the outer one no credit is left."""


def _strayed(e: g.Event, rng: np.random.Generator, near: float) -> tuple[np.ndarray, float, float, float] | None:
    """around's ``strays`` copy of an own event: (waypoints with one moved out, where along the straight
    moves' length the move out to it starts and ends (fractions), the share of the label left from there);
    None when the chosen pose is already that far out."""
    n = int(rng.integers(4, 7))
    way = g.waypoints(e.mover, n)
    k = int(rng.integers(1, n + 1))
    far = float(rng.choice(STRAY_RINGS))
    r = float(np.linalg.norm(way[k, :2] - e.anchor[:2]))
    if r >= far * e.size or r < 1e-9:
        return None
    way = g.pushed_out(way, k, e.anchor, far, e.size)
    seg = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(way[:, :2], axis=0).T))])
    left = max(0.0, 1.0 - (far - near) / (STRAY_RINGS[-1] - near))
    return way, seg[k - 1] / seg[-1], seg[k] / seg[-1], left


NEAR_END = (1.05, 1.2)
"""Blocks (centre to centre) from the anchor at which a ``near_starts`` copy ends: touching, with the margin."""
NEAR_START = (1.25, 2.5)
"""Blocks from the anchor within which a ``near_starts`` copy starts (chains' "closer" clauses start 1.25-1.75)."""
NEAR_MIN_CLOSING = 0.1
"""Blocks a ``near_starts`` crop must close, or it is not made."""


def _near(e: g.Event, rng: np.random.Generator) -> list[np.ndarray]:
    """closer's ``near_starts`` copies of an own event: shrunk about the anchor to end :data:`NEAR_END` from it,
    cropped to start within :data:`NEAR_START`; as it is and as one straight move (none if it closes too little)."""
    c, size = e.anchor[:2], e.size
    d = np.hypot(*(e.mover[:, :2] - c).T) / size
    end, start = rng.uniform(*NEAR_END), rng.uniform(*NEAR_START)
    k = end / max(float(d[-1]), 1e-9)
    m = e.mover.copy()
    m[:, :2] = c + (m[:, :2] - c) * k
    i0 = int(np.flatnonzero(d * k <= start)[0])  # the last frame is at ``end`` < ``start``
    crop = m[i0:]
    if len(crop) < 2 or (d[i0] - d[-1]) * k < NEAR_MIN_CLOSING:
        return []
    return [crop, g.straight_moves(crop[[0, -1]], 0.25 * size)]


def extras(recipe: Recipe, action: str, demos: dict[str, list[Demo]], qcfg: QSRConfig, neg_weight: float,
           seed: int) -> list[TrainingSequence]:
    """The recipe's extra sequences for ``action`` (empty for the current recipe)."""
    rng = np.random.default_rng(seed + 25)
    stray_rng = np.random.default_rng(seed + 26)  # its own: the recipe's other extras stay bit-identical
    near_rng = np.random.default_rng(seed + 27)  # the same
    dc = recipe.data
    if qcfg.viewer or qcfg.anchors > 1:  # mirror images and one-anchor snapping would be wrong there
        return []
    turns = dc.turn_label.get(action)
    out: list[TrainingSequence] = []

    def add(m: np.ndarray, e: g.Event, positive: bool) -> None:
        a = np.repeat(e.anchor[None], len(m), axis=0)
        s = _labelled(m, a, e.size, 0, len(m) - 1, qcfg, dc, positive, turns if positive else None)
        if not positive:
            s.weight = neg_weight
        out.append(s)

    def add_partials(m: np.ndarray, e: g.Event) -> None:
        whole = _labelled(m, np.repeat(e.anchor[None], len(m), axis=0), e.size, 0, len(m) - 1, qcfg, dc, True, turns)
        for f in PARTIAL_CUTS:  # the resampled frames are evenly spaced in arc length
            k = max(1, int(round(f * whole.end)))
            out.append(TrainingSequence(whole.x[: k + 1], whole.y[: k + 1], positive=True, end=k))

    def add_graded(e: g.Event) -> None:
        a = np.repeat(e.anchor[None], 2, axis=0)
        for way, tail, left in _graded(e, rng):
            ev = g.straight_moves(way, 0.25 * e.size)
            head = _labelled(ev, a[:1].repeat(len(ev), 0), e.size, 0, len(ev) - 1, qcfg, dc, True, turns)
            full = g.straight_moves(np.vstack([way, tail]), 0.25 * e.size)
            x = _labelled(full, a[:1].repeat(len(full), 0), e.size, 0, len(full) - 1, qcfg, dc, False).x
            k, top = len(head.y), float(head.y[-1])
            y = np.concatenate([head.y, np.linspace(top, top * left, len(x) - k + 1)[1:]]).astype(np.float32)
            out.append(TrainingSequence(x, y, positive=True, end=len(x) - 1))

    def add_strays(e: g.Event) -> None:
        got = _strayed(e, stray_rng, AROUND_NEAR)
        if got is None:
            return
        way, f0, f1, left = got
        m = g.straight_moves(way, 0.25 * e.size)
        s = _labelled(m, np.repeat(e.anchor[None], len(m), axis=0), e.size, 0, len(m) - 1, qcfg, dc, True, turns)
        f = np.linspace(0.0, 1.0, len(s.y))  # the resampled frames are evenly spaced in arc length
        s.y = (s.y * np.interp(f, [f0, f1], [1.0, left])).astype(np.float32)
        out.append(s)

    for d in demos.get(action, []):
        for e in _event_views(d, dc):
            if recipe.graded_wrongs:
                add_graded(e)
            if recipe.planner_partials:
                add_partials(g.domain(e, "straight", int(rng.integers(1, 4))), e)
                add_partials(g.domain(e, "rings", int(rng.integers(1, 4))), e)
            if recipe.planner_positives:
                add(g.domain(e, "rings", int(rng.integers(1, 4))), e, True)
                if action == "around" and recipe.grid:
                    add(g.domain(e, "grid", int(rng.integers(2, 5))), e, True)
            if recipe.planner_negatives and action in ACTIONS:  # wrong motions are per built-in meaning
                for w in _wrong(e, rng):
                    add(w, e, False)
            if recipe.strays and action == "around":
                add_strays(e)
    if recipe.near_starts and action == "closer":  # after the rest, so that it keeps its order
        for d in demos.get(action, []):
            for e in _event_views(d, dc):
                for m in _near(e, near_rng):
                    add(m, e, True)
    if recipe.contrastive:
        for other in dc.negatives.get(action, [o for o in demos if o != action]):
            for d in demos.get(other, []):
                for e in _event_views(d, dc):
                    add(g.domain(e, "straight", int(rng.integers(1, 4))), e, False)
                    add(g.domain(e, "rings", int(rng.integers(1, 4))), e, False)
    return out


def extend(recipe: Recipe, action: str, demos: dict[str, list[Demo]], qcfg: QSRConfig, seed: int,
           seqs: list[TrainingSequence]) -> list[TrainingSequence]:
    """The current training set ``seqs`` (:func:`trainset.build`'s) plus the recipe's extras and label
    power: what :func:`train_progress.train_action` trains on when given this as its ``extend``."""
    neg_w = next((s.weight for s in seqs if not s.positive), 1.0)
    seqs = seqs + extras(recipe, action, demos, qcfg, neg_w, seed)
    if recipe.turn_power != 1.0 and action in recipe.data.turn_label:
        for s in seqs:
            if s.positive:
                s.y = (s.y ** recipe.turn_power).astype(np.float32)
    return seqs


def training_set(recipe: Recipe, action: str, demos: dict[str, list[Demo]], qcfg: QSRConfig,
                 seed: int = 0) -> list[TrainingSequence]:
    """:func:`trainset.build` (the current recipe, bit for bit) plus the recipe's extras (of the shipped
    ``demos``: :func:`own_trusted` applies)."""
    demos = own_trusted(recipe, action, demos)
    return extend(recipe, action, demos, qcfg, seed, build(action, demos, qcfg, recipe.data, seed=seed))


def train(recipe: Recipe, action: str, demos: dict[str, list[Demo]], seed: int = 0,
          tick: Callable[[], None] | None = None) -> TrainResult:
    """The recipe's ensemble for ``action``: :func:`train_progress.train_action` (members seeded
    ``seed * 1000 + i``) on :func:`training_set` (of the shipped ``demos``: :func:`own_trusted` applies)."""
    q = QSRConfig()
    demos = own_trusted(recipe, action, demos)
    return train_action(action, demos, seed=seed, qsr_cfg=q, data_cfg=recipe.data, cfg=recipe.train, tick=tick,
                        extend=functools.partial(extend, recipe, action, demos, q, seed))
