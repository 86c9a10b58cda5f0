"""Training plans, the shipped one among them: :data:`SHIPPED` is what ``l2p-bullet train``, ``teach`` and
``make bundles`` use (recorded in each manifest's ``[training.recipe]``, the name that file contract keeps).
The others were compared with it on the grade-free suite (``research/generalise.py``); the
session-split models they give are cached on disk so a table can be re-printed without re-training. ("Recipe"
is a composite's learned row, ``composite/recipe.py``; a training plan is how a progress model's set is made
and trained.)

A training plan is the current training set (:func:`trainset.build`, unchanged: its sequences and their hashes
are those of ``l2p-bullet train``) plus optional extra sequences appended after it, drawn from their own
generator so the current part stays bit-identical. Which extras an action gets, and of which kind, its spec
declares (``ActionSpec.training``: ``wrong_motions``, ``graded_wrong``, ``grid_copies``, ``strays``,
``near_starts``); the kinds are made in :mod:`.extra_motions` (:data:`WRONG_MOTIONS`, :data:`GRADED_WRONGS`):

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

The motions these extras are made of are in :mod:`.extra_motions` (its kinds re-exported here). The training
options of :class:`ProgressTrainConfig` (weight decay, an ordinal head) are the rest. The trainer
(:mod:`l2p_bullet.learning.train_progress`) reads a plan; a plan never calls the trainer.

Nothing here reads a grade.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..actions import BUILTIN, ActionSpec, Training
from ..data.demos import UNTRUSTED, Demo
from ..progress.features import QSRConfig
from . import motions as g
from .extra_motions import (
    GRADED_FAR,
    GRADED_WRONGS,
    NEAR_END,
    NEAR_MIN_CLOSING,
    NEAR_START,
    STRAY_RINGS,
    WRONG_MOTIONS,
    _event_views,
    _graded,
    _near,
    _strayed,
    _wrong,
)
from .trainset import DataConfig, TrainingSequence, _labelled, build

__all__ = [  # the plans' own names and the kinds of extra motion (extra_motions.py), read from here
    "GRADED_FAR", "GRADED_WRONGS", "NEAR_END", "NEAR_MIN_CLOSING", "NEAR_START", "PARTIAL_CUTS", "SHIPPED",
    "STRAY_RINGS", "WRONG_MOTIONS", "ProgressTrainConfig", "TrainingPlan", "declared", "extend", "extras",
    "own_trusted", "plans", "shipped_extension", "training_set",
]


@dataclass(frozen=True)
class ProgressTrainConfig:
    """Optimisation settings (written to the manifest's ``[training]``)."""

    hidden: int = 32
    ensemble: int = 5
    epochs: int = 30
    batch: int = 32
    lr: float = 0.01
    end_weight: float = 2.0
    """Extra weight of the squared error at the event's end frame (or a negative's last frame)."""
    threads: int = 1
    """Intra-op threads while training: tiny LSTMs gain nothing from more, and spinning threads stall
    badly when the cores are shared."""
    weight_decay: float = 0.0
    """Decoupled weight decay (AdamW) when above 0; 0 is plain Adam, the shipped plan."""
    levels: int = 1
    """Thresholds of an ordinal read-out (``ModelConfig.levels``): above 1, each is trained with binary
    cross-entropy on whether the frame's label is past it (thresholds at (2k + 1) / (2 levels))."""

    def to_dict(self) -> dict:
        out = {k: getattr(self, k) for k in ("hidden", "ensemble", "epochs", "batch", "lr", "end_weight")}
        # the later options only when used: older manifests and caches keep matching
        return out | {k: getattr(self, k) for k in ("weight_decay", "levels") if getattr(self, k) != getattr(
            ProgressTrainConfig, k)}


PARTIAL_CUTS = (0.3, 0.6)
"""Where ``planner_partials`` stops a planner-domain copy, as fractions of its length."""


@dataclass(frozen=True)
class TrainingPlan:
    """How one progress model's training set is made (the current set plus the extras switched on here, for
    the actions that declare them) and trained (:attr:`train`)."""

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
    """With ``planner_positives``: actions that declare ``grid_copies`` (around) also get copies snapped to
    the 2-D study's grid."""
    strays: bool = False
    trusted_own: bool = False
    """Leave the action's own untrusted shipped demonstrations out of its own set (:func:`own_trusted`)."""
    near_starts: bool = False
    """Actions that declare ``near_starts`` (closer): people's endings made short, as full events
    (:func:`_near`)."""

    def extras_dict(self) -> dict:
        """The options that add to the current training set (empty for the current plan): what a
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


SHIPPED = TrainingPlan("planner-graded-nogrid", planner_positives=True, planner_negatives=True,
                       planner_partials=True, graded_wrongs=True, grid=False)
"""The plan ``l2p-bullet train`` (so ``make bundles`` and ``teach``) trains with, training settings from
the command (5 LSTMs x 30 epochs by default): planner-graded-nogrid, the one that cleared the rule committed
before the plans were compared (docs/learning.md: strengthened suite 0.438 against the current plan's 0.321, 33 goals
against 26; planning and perform 100 % on the 30-scene benchmarks). Its extras are written into every bundle's
manifest (``[training.recipe]``)."""


def shipped_extension(action: str, demos: dict[str, list[Demo]], qcfg: QSRConfig, data_cfg: DataConfig,
                      seed: int, spec: ActionSpec | None = None
                      ) -> Callable[[list[TrainingSequence]], list[TrainingSequence]]:
    """:data:`SHIPPED`'s extension of the set :func:`trainset.build` made with ``data_cfg`` (a plugin's own
    data settings are kept, and the extras its ``spec`` declares added; a viewer-frame or two-anchor plugin
    gets nothing added)."""
    return functools.partial(extend, dataclasses.replace(SHIPPED, data=data_cfg), action, demos, qcfg, seed,
                             spec=spec)


def own_trusted(plan: TrainingPlan, action: str, demos: dict[str, list[Demo]]) -> dict[str, list[Demo]]:
    """``demos`` as ``action`` trains on them with ``plan``: with ``trusted_own``, its own list without the
    ids of :data:`data.demos.UNTRUSTED` (the other actions' lists, its negatives, unchanged). Call it on the
    shipped demonstrations only: a user's own files are taken as they are (their ids could coincide)."""
    if not plan.trusted_own or not any(d.id in UNTRUSTED for d in demos.get(action, [])):
        return demos
    return {**demos, action: [d for d in demos[action] if d.id not in UNTRUSTED]}


def plans(ensemble: int, epochs: int) -> dict[str, TrainingPlan]:
    """The training plans compared on the grade-free suite, at a given ensemble size and length of training."""
    t = ProgressTrainConfig(ensemble=ensemble, epochs=epochs)
    small = dataclasses.replace(t, hidden=16)
    on = {"planner_positives": True, "planner_negatives": True}  # every planner-domain plan has these
    graded = {**on, "planner_partials": True, "graded_wrongs": True}
    return {r.name: r for r in [
        TrainingPlan("current", train=t),
        TrainingPlan("small", train=small),
        TrainingPlan("planner", train=t, **on),
        TrainingPlan("contrastive", train=t, contrastive=True),
        TrainingPlan("planner+contrastive", train=t, **on, contrastive=True),
        TrainingPlan("around-convex", train=t, turn_power=2.0),
        TrainingPlan("all", train=t, **on, contrastive=True, turn_power=2.0),
        # tried against the strengthened suite (docs/learning.md), one setting each
        TrainingPlan("planner-partial", train=t, **on, planner_partials=True),
        TrainingPlan("decay", train=dataclasses.replace(t, weight_decay=0.01)),
        TrainingPlan("small-decay", train=dataclasses.replace(small, weight_decay=0.01)),
        TrainingPlan("ordinal", train=dataclasses.replace(t, levels=4)),
        # chosen after the strengthened suite's table (docs/learning.md)
        TrainingPlan("planner-graded", train=t, **graded),
        # planner-graded without around's grid copies (with them its around planned 90 %)
        TrainingPlan("planner-graded-nogrid", train=t, **graded, grid=False),
        # around's strays with partial credit (for the far corner the planning check found)
        TrainingPlan("planner-graded-nogrid-strays", train=t, **graded, grid=False, strays=True),
        # the shipped plan with around's own glitched demonstration left out (not its negatives)
        TrainingPlan("planner-graded-nogrid-trusted", train=t, **graded, grid=False, trusted_own=True),
        # the shipped plan with closer's endings made short (chains start closer from near)
        TrainingPlan("planner-graded-nogrid-near", train=t, **graded, grid=False, near_starts=True),
    ]}


def declared(action: str, spec: ActionSpec | None = None) -> Training:
    """What ``action`` declares about its training (``ActionSpec.training``): ``spec``'s when given (a
    plugin's), else the built-in's; a plugin that declares nothing gets no per-action extras."""
    found = spec if spec is not None else BUILTIN.get(action)
    return found.training if found is not None else Training()


def extras(plan: TrainingPlan, action: str, demos: dict[str, list[Demo]], qcfg: QSRConfig, neg_weight: float,
           seed: int, spec: ActionSpec | None = None) -> list[TrainingSequence]:
    """The plan's extra sequences for ``action`` (empty for the current plan); the per-action ones of the
    kinds its spec declares (:func:`declared`)."""
    rng = np.random.default_rng(seed + 25)
    stray_rng = np.random.default_rng(seed + 26)  # its own: the plan's other extras stay bit-identical
    near_rng = np.random.default_rng(seed + 27)  # the same
    dc = plan.data
    if qcfg.viewer or qcfg.anchors > 1:  # mirror images and one-anchor snapping would be wrong there
        return []
    own = declared(action, spec)
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
        for way, tail, left in _graded(e, rng, own.graded_wrong):
            ev = g.straight_moves(way, 0.25 * e.size)
            head = _labelled(ev, a[:1].repeat(len(ev), 0), e.size, 0, len(ev) - 1, qcfg, dc, True, turns)
            full = g.straight_moves(np.vstack([way, tail]), 0.25 * e.size)
            x = _labelled(full, a[:1].repeat(len(full), 0), e.size, 0, len(full) - 1, qcfg, dc, False).x
            k, top = len(head.y), float(head.y[-1])
            y = np.concatenate([head.y, np.linspace(top, top * left, len(x) - k + 1)[1:]]).astype(np.float32)
            out.append(TrainingSequence(x, y, positive=True, end=len(x) - 1))

    def add_strays(e: g.Event) -> None:
        got = _strayed(e, stray_rng, near)
        if got is None:
            return
        way, f0, f1, left = got
        m = g.straight_moves(way, 0.25 * e.size)
        s = _labelled(m, np.repeat(e.anchor[None], len(m), axis=0), e.size, 0, len(m) - 1, qcfg, dc, True, turns)
        f = np.linspace(0.0, 1.0, len(s.y))  # the resampled frames are evenly spaced in arc length
        s.y = (s.y * np.interp(f, [f0, f1], [1.0, left])).astype(np.float32)
        out.append(s)

    near = (spec or BUILTIN[action]).thresholds["near"] if plan.strays and own.strays else None  # its rule's
    for d in demos.get(action, []):
        for e in _event_views(d, dc):
            if plan.graded_wrongs:
                add_graded(e)
            if plan.planner_partials:
                add_partials(g.domain(e, "straight", int(rng.integers(1, 4))), e)
                add_partials(g.domain(e, "rings", int(rng.integers(1, 4))), e)
            if plan.planner_positives:
                add(g.domain(e, "rings", int(rng.integers(1, 4))), e, True)
                if own.grid_copies and plan.grid:
                    add(g.domain(e, "grid", int(rng.integers(2, 5))), e, True)
            if plan.planner_negatives:  # wrong motions are per meaning: those its action declares
                for w in _wrong(e, rng, own.wrong_motions):
                    add(w, e, False)
            if plan.strays and own.strays:
                add_strays(e)
    if plan.near_starts and own.near_starts:  # after the rest, so that it keeps its order
        for d in demos.get(action, []):
            for e in _event_views(d, dc):
                for m in _near(e, near_rng):
                    add(m, e, True)
    if plan.contrastive:
        for other in dc.negatives.get(action, [o for o in demos if o != action]):
            for d in demos.get(other, []):
                for e in _event_views(d, dc):
                    add(g.domain(e, "straight", int(rng.integers(1, 4))), e, False)
                    add(g.domain(e, "rings", int(rng.integers(1, 4))), e, False)
    return out


def extend(plan: TrainingPlan, action: str, demos: dict[str, list[Demo]], qcfg: QSRConfig, seed: int,
           seqs: list[TrainingSequence], spec: ActionSpec | None = None) -> list[TrainingSequence]:
    """The current training set ``seqs`` (:func:`trainset.build`'s) plus the plan's extras and label
    power: what :func:`train_progress.train_action` trains on when given this as its ``extend``."""
    neg_w = next((s.weight for s in seqs if not s.positive), 1.0)
    seqs = seqs + extras(plan, action, demos, qcfg, neg_w, seed, spec)
    if plan.turn_power != 1.0 and action in plan.data.turn_label:
        for s in seqs:
            if s.positive:
                s.y = (s.y ** plan.turn_power).astype(np.float32)
    return seqs


def training_set(plan: TrainingPlan, action: str, demos: dict[str, list[Demo]], qcfg: QSRConfig,
                 seed: int = 0) -> list[TrainingSequence]:
    """:func:`trainset.build` (the current plan, bit for bit) plus the plan's extras (of the shipped
    ``demos``: :func:`own_trusted` applies)."""
    demos = own_trusted(plan, action, demos)
    return extend(plan, action, demos, qcfg, seed, build(action, demos, qcfg, plan.data, seed=seed))
