"""The rule judges: did the mover do what the action says? The mechanism: :data:`RULES` (every rule set by
name), :func:`rule_verdict` and :class:`RuleJudge`; each rule set itself lives in its own module of
``judge/rulesets/`` (a built-in action's in the one its ``ActionSpec.rules`` names), the geometry they share in
``judge/footprints.py``.

Why rules and not the learned model: the planner maximises the learned progress model, so judging its
paths with the same model would only measure how well the planner exploits it. These rules are written
from the meaning of the words, in **units of block size** (the original evaluator used absolute
thresholds, which broke as soon as the blocks changed size, and its "next to" rule was wrong):

- closer:  the centre distance shrinks steadily and closes at least half of the room there was
           (room = start distance - the distance at which the two touch: 1 block for two cubes, where two
           squares touch face to face); the score also grows with the distance covered (people graded
           short moves down);
- away:    the centre distance grows steadily, by at least one block (score: the growth less the
           largest step back);
- next-to: the mover ends adjacent: the gap between the two footprints is at most half a block (and
           they do not overlap);
- past:    the mover crosses from one side of the anchor to the other along its overall direction of
           travel (starting at least half a block before it and ending at least half a block beyond it),
           passes near it (closest centre distance at most 4 blocks) and does not circle it (turns at
           most half a turn around it: more is going around);
- around:  the mover sweeps nearly a full turn around the anchor (at least 0.8 turn) while staying near
           it (centre distance at most 4 blocks), read from the first frame that near on (a mover that
           starts farther first comes near; the approach is not judged).

For plugin actions (a manifest's ``[judge] rules = "..."``):

- between:     a two-anchor rule: the mover ends on the segment between the two anchors (its centre
               projects strictly between theirs and lies within half a block of the line through them)
               without touching either;
- left-of, right-of, in-front-of, behind: viewer-frame rules: the mover ends on that side of the anchor
               as the viewer sees it (its offset from the anchor within 45 degrees of the viewer's left,
               right, towards the viewer, away from it), near it (centre distance at most 4 blocks) and
               not overlapping it. The viewer is the ``viewer`` keyword, the robot's base by default.

The numbers above are declared by each built-in action (``l2p_bullet/actions/<name>/__init__.py``,
``ActionSpec.thresholds``) and read by its rule set's module; the constants below are re-exported from there.

"Steadily" allows wobbles of half a block against the running best. Every rule also gives a graded
``score`` in [0, 1] (used for the correlation with people's grades; ``success`` is the yes/no verdict).
Motions are read in the anchor's frame (mover minus anchor), so a moving anchor is handled too.

**Footprints.** Where an object a verdict reads is not a cube, the caller gives ``outlines`` (each object's
real footprint, ``footprints.outlines_of``) and the rules that read footprints measure them: the gap and the
overlap of "next to", "between" and the viewer-frame sides, and the touching distance of "closer"'s room.
The rules that read where the mover goes relative to the anchor's centre ("away", "past", "around": centre
distances and turns, their thresholds fitted on people's demonstrations that way) read centres for every
shape. Without ``outlines`` (every object a cube) every rule reads unit squares, bit for bit as before.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..actions import BUILTIN, ActionSpec
from ..core.vocabulary import canonical_action
from ..errors import PathError, UnknownActionError
from .base import Verdict
from .footprints import WOBBLE, relative, square_gap
from .rulesets import around, away, between, closer, next_to, past, sides
from .rulesets.around import AROUND_APPROACH, AROUND_NEAR, AROUND_TURNS
from .rulesets.away import AWAY_GAIN
from .rulesets.closer import CLOSER_SHARE, closer_room, went_back
from .rulesets.next_to import NEXT_TO_GAP
from .rulesets.past import PAST_MARGIN, PAST_MAX_TURN_DEG, PAST_NEAR
from .rulesets.sides import NEAR, SIDES

__all__ = ["RULES", "RULE_SPECS", "TWO_ANCHOR_RULES", "RuleJudge", "rule_verdict", "square_gap",
           "closer_room", "went_back", "WOBBLE",
           "CLOSER_SHARE", "AWAY_GAIN", "NEXT_TO_GAP", "PAST_MARGIN", "PAST_NEAR", "PAST_MAX_TURN_DEG",
           "AROUND_TURNS", "AROUND_NEAR", "AROUND_APPROACH", "NEAR", "SIDES"]

RULES: dict[str, Callable[..., Verdict]] = {
    **closer.RULES, **away.RULES, **next_to.RULES, **past.RULES, **around.RULES, **between.RULES, **sides.RULES,
}
"""Rule sets by name; a bundle's manifest picks one with ``[judge] rules = "<name>"``."""

TWO_ANCHOR_RULES = between.TWO_ANCHOR
"""Rule sets that read two reference objects (``anchors=``)."""

RULE_SPECS: dict[str, ActionSpec] = {s.rules: s for s in BUILTIN.values() if s.rules}
"""Rule set name -> the built-in action that declares it: its thresholds and how it is planned (room checks,
bound, lead-in), which the stages look up for any action judged by that rule set (a plugin's too)."""


def rule_verdict(action: str, mover: np.ndarray, anchor: np.ndarray, size: float, *,
                 anchors: list[np.ndarray] | None = None, viewer: np.ndarray | None = None,
                 outlines: list[np.ndarray] | None = None) -> Verdict:
    """Judge a motion by the rules named ``action``: ``mover`` (T,3) and ``anchor`` (T,3) or (3,) poses in
    metres, blocks of side ``size``; ``anchors`` every reference object of a two-anchor rule, ``viewer``
    the viewpoint (2,) of a viewer-frame rule (default: the robot's base, scene frame); ``outlines`` the
    objects' real footprints (mover, then every anchor; metres, own frames) where one is not a cube, None
    for unit squares (module docstring).

    Frames must be dense enough that the mover turns less than half a turn around the anchor between
    two of them (``planning.world2d.interpolate`` gives that).
    """
    if action in RULES:
        name = action
    else:
        try:
            name = canonical_action(action)
        except UnknownActionError:
            raise UnknownActionError(action, RULES, "(no rule judge has that name)") from None
    mover = np.asarray(mover, float).reshape(-1, 3)
    anchor_arr = np.asarray(anchor, float).reshape(-1, 3)
    _check_motion(mover, anchor_arr, size)
    if len(anchor_arr) == 1:
        anchor_arr = np.repeat(anchor_arr, len(mover), axis=0)
    rel, d = relative(mover, anchor_arr, size)
    context = {k: v for k, v in (("anchors", anchors), ("viewer", viewer), ("outlines", outlines)) if v is not None}
    return RULES[name](rel, d, mover, anchor_arr, size, **context)


def _check_motion(mover: np.ndarray, anchor: np.ndarray, size: float) -> None:
    """A PathError (one line) for what no rule can read: an empty motion, poses that are not finite, an
    anchor track of another length, a block side that is not a positive length (an IndexError or a NaN
    verdict from deep inside before)."""
    if not len(mover):
        raise PathError("the motion has no frames: a rule judges at least one pose of the mover")
    if not len(anchor) or (len(anchor) != 1 and len(anchor) != len(mover)):
        raise PathError(
            f"the anchor has {len(anchor)} poses for the mover's {len(mover)}: give one pose, or one per frame"
        )
    if not (np.isfinite(mover).all() and np.isfinite(anchor).all()):
        raise PathError("the motion holds a pose that is not a finite number (NaN or infinity)")
    if isinstance(size, bool) or not isinstance(size, int | float | np.floating) or not 0 < size < np.inf:
        raise PathError(f"the block side must be a positive length in metres (got {str(size)[:20]})")


class RuleJudge:
    """The :class:`~l2p_bullet.judge.base.Judge` over one of :data:`RULES` (the progress model is not asked)."""

    name = "rules"
    reads_outlines = True  # given the objects' footprints where one is not a cube (judge_context)

    def __init__(self, rules: str):
        if rules not in RULES:
            raise UnknownActionError(rules, RULES, "(no rule judge has that name)")
        self.rules = rules

    def judge(self, mover: np.ndarray, anchor: np.ndarray, size: float, *,
              final_progress: float | None = None, anchors: list[np.ndarray] | None = None,
              viewer: np.ndarray | None = None, outlines: list[np.ndarray] | None = None) -> Verdict:
        return rule_verdict(self.rules, mover, anchor, size, anchors=anchors, viewer=viewer, outlines=outlines)
