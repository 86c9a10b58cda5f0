"""A dead end of a chain's search (forecast.py): the first failure met, the blocks whose poses its check reads
(so the search jumps back past the clauses that moved none of them), and how a chain is refused with it.

Kept apart from the search itself: what a failed check reads is a fact about the checks (planning.feasibility,
planning/sweep.py), not about the order the search tries ends in.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..core.scene import GRIPPER_MARGIN, Scene
from ..errors import InfeasibleError, L2PError, PathError, PlanError
from ..judge.rules import AROUND_NEAR
from .clause import Clause, named


@dataclass
class Dead(Exception):
    """A subtree of the search with no way through: the first failure found (already named) and the blocks
    whose poses its check reads (None: every block)."""

    error: L2PError
    clause: int
    blocks: frozenset[str] | None
    scene: Scene | None = None  # the predicted scene the failed check was made in
    command: Any = None  # the failed clause's command
    reads: frozenset[str] | None = None  # the blocks its check reads (``blocks`` before it was widened)

    @property
    def room(self) -> str | None:
        """The room check that failed (one an earlier clause's end can meet: AIM_CHECKS), else None."""
        check = self.error.check if isinstance(self.error, InfeasibleError) else None
        return check if check in AIM_CHECKS and self.scene is not None else None


AIM_CHECKS = ("room-around", "blocked-around", "room-away", "room-closer")
"""The feasibility checks an earlier clause's end can be aimed to pass (aims.py): they read where blocks stand."""


ANCHOR_ONLY = ("room-around",)
"""The room checks that read where the anchor stands and not where the mover does (the room round an anchor is
the workspace's about it; the mover's size alone counts): an earlier clause that moved only the mover cannot
change them, so the search goes straight back to the clauses that moved the anchor."""


AHEAD_CHECKS = ("room-around", "room-away")
"""The room checks a clause's end is measured against as soon as it is planned, before the clauses between: they
read the later clause's mover, its anchor and the workspace alone (no hold, no bystander), so where the clause
leaves its mover decides them exactly when no clause between moves what they read."""


@dataclass(frozen=True)
class Ahead:
    """A later clause's room check that an earlier clause's end decides (:func:`ahead_of`)."""

    clause: Clause
    check: str
    thresholds: Mapping[str, float]


def ahead_of(clauses: list[Clause], k: int, plugins: list) -> list[Ahead]:
    """The room checks of the clauses after ``clauses[k]`` (:data:`AHEAD_CHECKS`, those their actions declare,
    as ``pipeline.check_feasible`` finds them) that read ``clauses[k]``'s mover and nothing any clause between
    moves: a chain whose clause ``k`` leaves its mover where one fails is certain to fail there, so the search
    knows it before it plans the clauses between (each a search) and aims the clause's end at once."""
    from ..judge.rules import RULE_SPECS  # lazy, as the checks' own imports

    mover, out = clauses[k].command.mover, []
    for later in clauses[k + 1:]:
        cmd = later.command
        info = next((p for p in plugins if p.name == cmd.action), None)
        judge = (info.manifest.get("judge") if info is not None else None) or {}
        rules = judge.get("rules") if isinstance(judge, dict) else None
        spec = RULE_SPECS.get(rules) if isinstance(rules, str) else None
        between = {c.command.mover for c in clauses[k + 1:later.index - 1]}
        for check in spec.planning.checks if spec is not None else ():
            reads = reads_of(check, cmd) if check in AHEAD_CHECKS else None
            if reads is not None and mover in reads and not reads & between:
                out.append(Ahead(later, check, spec.thresholds))
    return out


def ahead_fails(a: Ahead, scene: Scene) -> InfeasibleError | None:
    """``a``'s check made in ``scene`` (the later clause's mover and anchor where they will stand): its error, or
    None when it passes."""
    from ..planning.feasibility import ROOM_CHECKS  # lazy: the planner loads only when a chain is forecast

    try:
        ROOM_CHECKS[a.check](scene, a.clause.command.mover, a.clause.command.anchor, [], a.thresholds)
    except InfeasibleError as e:
        return e
    return None


def reads_of(check: str | None, command: Any) -> frozenset[str] | None:
    """The blocks whose poses a failed check reads: a room check's anchors (and its mover, but for
    :data:`ANCHOR_ONLY`); any other check's, every block (None)."""
    if not check or not check.startswith("room-"):
        return None
    anchors = frozenset(command.anchors)
    return anchors if check in ANCHOR_ONLY else anchors | {command.mover}


def around_reads(scene: Scene, command: Any, bundle: Any) -> frozenset[str]:
    """The blocks "blocked-around" reads (planning/sweep.py): the anchors, and every block a pose of the mover
    within ``near`` blocks of the anchor can touch; the mover too when it starts within ``near`` (its way round
    must start where it stands; from afar the check reads every place it can first come near, wherever it
    starts). A block farther out is not in the way: another end of the clause that left it there cannot clear
    the way round."""
    from ..planning import rule_spec  # lazy: the planner loads only when a chain is forecast

    spec = rule_spec(bundle)
    near = (spec.thresholds.get("near") if spec is not None else None) or AROUND_NEAR
    m, a = scene.get(command.mover), np.asarray(scene.get(command.anchor).xy, float)
    reach = near * m.size + _radius(m) + GRIPPER_MARGIN + 1e-6
    starts_near = float(np.hypot(*(np.asarray(m.xy, float) - a))) <= near * m.size + 1e-9
    return frozenset({*command.anchors} | ({command.mover} if starts_near else set()) | {
        o.name for o in scene.objects if float(np.hypot(*(np.asarray(o.xy, float) - a))) - _radius(o) <= reach})


def _radius(o: Any) -> float:
    """How far the object's footprint reaches from its centre."""
    return float(np.hypot(*(o.footprint() - np.asarray(o.xy, float)).T).max())


def wider(d: Dead, c: Clause) -> Dead:
    """``d`` raised past ``c`` once every end of ``c`` failed: which ends ``c`` has depends on where its anchors
    stand too (a block sent past an anchor on the workspace's rim ends by the rim), so a clause that moved
    one of them is tried again as well."""
    return d if d.blocks is None else replace(d, blocks=d.blocks | set(c.command.anchors))


def kind(e: L2PError) -> str:
    return "plan" if isinstance(e, PlanError) else "path" if isinstance(e, PathError) else type(e).__name__


def refusal(d: Dead, clauses: list[Clause], plans: int, dead_ends: dict[str, int]) -> L2PError:
    """The first failure, named by its clause, with what the search tried before it gave up."""
    c, e = clauses[d.clause - 1], d.error
    first = f"clause {c.index} ({e.check if isinstance(e, InfeasibleError) else kind(e)})"
    others = {k: n for k, n in dead_ends.items() if k != first}
    tried = "" if d.clause == 1 or not others else (
        "; no other end state of the clauses before it keeps it possible (" + str(plans) + " plans; "
        + "the other end states tried met " + ", ".join(f"{k} x{n}" for k, n in others.items()) + ")")
    if isinstance(e, InfeasibleError):
        e.details["clause"] = c.index
        return named(e, f"{c.label()} cannot be planned ({e.check})", tried)
    if isinstance(e, PlanError):
        return named(PlanError(str(e)), f"{c.label()} cannot be planned (plan)", tried)
    if isinstance(e, PathError):
        return named(PathError(str(e)), f"{c.label()} cannot be planned (path)", tried)
    return named(e, c.label(), tried)
