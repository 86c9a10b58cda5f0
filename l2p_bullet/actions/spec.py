"""What an action is, in one place: :class:`ActionSpec`, declared by each action's module as ``ACTION``.

A built-in action's module (``l2p_bullet/actions/<name>/__init__.py``, the entry point's target, next to its
bundle) declares its name in the study's data, an example sentence, the rule set that judges it and the
thresholds that rule reads, how it is planned (:class:`Planning`: its up-front room checks, the bound from
people's data on the planner's candidates, the lead-in from afar), how its training set differs from the
defaults and what its training plan adds (:class:`Training`), and the finding its evaluation report adds.
The stages hold the algorithms, keyed by what they do, and look these declarations up; none of them
branches on an action's name (``tests/test_layout.py`` checks): ``core/vocabulary.py`` (names),
``judge/rulesets/`` (rule judges), ``planning/`` (room checks, bounds, lead-in), ``learning/trainset.py``
(``DataConfig``'s defaults), ``learning/training_plan.py`` (planner-domain extras), ``learning/improve.py``
(sentences), ``evaluate/report.py`` (findings). A plugin's module may declare an ``ACTION`` the same way; the
registry hands it over with the bundle (``Bundle.spec``).

Pure declarations on the lowest floor above ``errors`` (docs/DESIGN.md, "Floors"): every stage may read
them, they import nothing of the package.
"""

from __future__ import annotations

from dataclasses import dataclass, field

ROOM_CHECKS = ("room-closer", "room-away", "room-around", "blocked-around")
"""The room checks an action may declare (``Planning.checks``; ``planning.feasibility.ROOM_CHECKS``)."""
BOUND_KINDS = ("passes-within", "goes-back-within", "starts-before", "closes-at-least", "grows-at-least")
"""The kinds of bound from people's data (``Bound.kind``; ``planning.bounds.WEIGHTS`` weighs by them)."""
WRONG_MOTIONS = ("backs-off", "out-and-back", "reversed", "to-closest-and-back", "half-round-and-back")
"""The kinds of wrong planner motion (``Training.wrong_motions``; ``training_plan.WRONG_MOTIONS``)."""
GRADED_WRONGS = ("goes-back", "moves-out")
"""The kinds of graded wrong motion (``Training.graded_wrong``; ``learning.training_plan.GRADED_WRONGS``)."""


def _known(what: str, given: tuple[str, ...], known: tuple[str, ...]) -> None:
    """ValueError (one line, naming the known ones) for a declared kind no stage makes: a plugin's typo is
    reported when its module is imported, not as a KeyError deep in planning or training."""
    unknown = [g for g in given if g not in known]
    if unknown:
        raise ValueError(f"unknown {what} {', '.join(map(repr, unknown))} (known: {', '.join(known)})")


@dataclass(frozen=True)
class Violation:
    """When a random straight-line motion (block units) is clearly not even a *partial* instance of an action,
    so that its training set may label it a negative (``learning.trainset.violates``). Each check that is set
    is one way to fail; None: not checked. Partial instances keep a partial progress (the planner climbs it),
    so only motions that went the wrong way fail."""

    ends_farther: float | None = None
    """It ends at least this many blocks farther from the anchor than it started."""
    ends_nearer: float | None = None
    """It ends at least this many blocks nearer than it started."""
    stays_off: tuple[float, float] | None = None
    """It ends more than ``[0]`` blocks away having closed less than ``[1]`` blocks."""
    strays: tuple[float, float] | None = None
    """It goes more than ``[0]`` blocks away, from a start nearer than ``[1]`` blocks."""
    no_turn: tuple[float, float] | None = None
    """It turns less than ``[0]`` degrees around the anchor over more than ``[1]`` blocks of travel."""
    max_turn_deg: float | None = None
    """It turns more than this many degrees around the anchor."""


@dataclass(frozen=True)
class Training:
    """How an action's training set differs from the defaults (``learning.trainset.DataConfig``; why each
    option exists is said there and in docs/learning.md)."""

    negatives: tuple[str, ...] = ()
    """Actions whose demonstrations are its negatives (one that is, or begins, this action is left out)."""
    scaled: bool = True
    """Copies stretched about the anchor (not for next-to: a stretched next-to ends apart)."""
    scale_range: tuple[float, float] | None = None
    """Stretch factors of those copies, when not ``DataConfig.scale_range``."""
    approach: tuple[float, float] | None = None
    """Copies that start this many blocks farther back along their first direction."""
    shortened: tuple[float, float] | None = None
    """Copies shrunk about their own start by these factors: the same motion stopped sooner is complete."""
    twist: bool = False
    """Copies whose bearing drifts: a drifting bearing does not change the action's meaning."""
    detour: bool = False
    """Copies that first move the other way: the net motion is still the action."""
    turn_label: float | None = None
    """Labelled by the net turn swept, in these many turns, instead of by arc length."""
    net_label: float | None = None
    """Dip/back-off copies labelled by net gain less this times the inward motion."""
    violation: Violation | None = None
    """Which random motions are its negatives; None: none are (a plugin without one trains without them)."""
    clear_grades: tuple[float, float] | None = None
    """The original's cold feedback ("clear" targets) for it: mean grade <= [0] is 0, >= [1] is 1, when not
    the default of ``learning.feedback_targets.FeedbackConfig.clear``."""
    wrong_motions: tuple[str, ...] = ()
    """The wrong planner motions a training plan's ``planner_negatives`` makes from each of its events, by
    kind (``learning.training_plan.WRONG_MOTIONS``): "backs-off" (out 1.5-4 blocks and back to its start
    distance), "out-and-back" (to the end and back near the start), "reversed" (end to start),
    "to-closest-and-back" (to its closest approach and back), "half-round-and-back" (half of it and straight
    back)."""
    graded_wrong: str | None = None
    """The planner motion that undoes part of it and keeps the credit a rule leaves it (a plan's
    ``graded_wrongs``, ``learning.training_plan.GRADED_WRONGS``): "goes-back" (back a share of the way to the
    start), "moves-out" (1-5 blocks straight out from where it ends); None: none."""
    grid_copies: bool = False
    """A plan's planner positives also snapped to the 2-D study's move grid (its demonstrations were graded
    there)."""
    strays: bool = False
    """A plan's ``strays``: copies with one corner moved out to the planner's outer rings, with the credit its
    rule's ``near`` threshold leaves them."""
    near_starts: bool = False
    """A plan's ``near_starts``: its events made short near the anchor, as full events."""

    def __post_init__(self) -> None:
        _known("wrong motion", tuple(self.wrong_motions), WRONG_MOTIONS)
        graded = () if self.graded_wrong is None else (self.graded_wrong,)
        _known("graded wrong motion", graded, GRADED_WRONGS)


@dataclass(frozen=True)
class LeadIn:
    """How a rule that reads a motion from its first frame within ``near`` blocks of the anchor (and sweeps
    round it from there) is planned: a mover starting farther is first slid straight to ``approach`` blocks
    (``planning/approach.py``), no move of the search ends beyond ``reach`` blocks, and among bystanders a way
    round within ``near`` is offered (``planning/detour.py``). All in blocks, from people's demonstrations."""

    near: float
    approach: float
    reach: float


@dataclass(frozen=True)
class Bound:
    """A bound from people's demonstrations on the candidates the planner ranks (``planning/bounds.py``): a
    candidate beyond it is scored down. ``kind`` names the measure (``planning.bounds.WEIGHTS``):
    "passes-within" (its closest centre distance to the anchor, blocks), "goes-back-within" (how far its
    centre distance went back, as a share of its room); ``within``: the most people's demonstrations went;
    "starts-before" (how far before the anchor it starts along its overall direction, as a share of its start
    distance); ``within``: the least people's demonstrations started so (a least, not a most); "closes-at-least"
    (how much its centre distance closed from start to end, as a share of its room); ``within``: the least
    the rule accepts (a least); "grows-at-least" (how many blocks its centre distance grew from start to end,
    from afar); ``within``: the least people's demonstrations grew it (a least)."""

    kind: str
    within: float

    def __post_init__(self) -> None:
        _known("bound", (self.kind,), BOUND_KINDS)


@dataclass(frozen=True)
class Planning:
    """How an action is planned besides maximising its progress model (``planning/``)."""

    checks: tuple[str, ...] = ()
    """The up-front room checks that apply to it, by the name their refusal carries
    (``planning.feasibility.ROOM_CHECKS``: "room-closer", "room-away", "room-around", "blocked-around"), run
    in this order with its thresholds."""
    bound: Bound | None = None
    lead_in: LeadIn | None = None
    more_bounds: tuple[Bound, ...] = ()
    """Bounds from people's data besides :attr:`bound`, all applied together (their weights multiply)."""
    holds_within: float | None = None
    """Blocks: where the footprints start at most this far apart and the rule judge accepts the start as it
    stands, the relation already holds and nothing is moved (``planning/already.py``: the run says so and
    succeeds); None: never (the action asks for a motion, as "closer" and "away" do)."""

    def __post_init__(self) -> None:
        _known("room check", tuple(self.checks), ROOM_CHECKS)


@dataclass(frozen=True)
class Touching:
    """An evaluation report's finding for an action whose runs may end touching the anchor
    (``evaluate/report.py``): how many do, and how many ``also``'s judge accepts (``also_words``: how the
    report names that action); ``note`` says why it matters."""

    also: str
    also_words: str
    note: str


@dataclass(frozen=True)
class ActionSpec:
    """One action: what the stages read about it besides its bundle (phrases, features, weights)."""

    name: str
    """Canonical name ("next-to"); the entry point's and the bundle's name."""
    source_name: str
    """What the original study's data calls it (capture files, graded folders): "SlideNext"."""
    sentence: str
    """An example sentence that performs it ("move A next to B"): ``l2p-bullet improve`` performs it."""
    thresholds: dict[str, float] = field(default_factory=dict)
    """The numbers its rule judge (the rule set :attr:`rules` names) and its feasibility room
    check read, in blocks, turns or degrees as named."""
    training: Training = field(default_factory=Training)
    graded_folders: tuple[str, ...] = ()
    """Further folders of the graded 2-D demonstrations that show it ("SlideAroundDiscrete")."""
    rules: str | None = None
    """The rule set that judges it, by name (``judge/rulesets/``; a built-in's own, a plugin's one of those
    shipped: "between", "left-of", ...); None: it has none, its learned model judges."""
    planning: Planning = field(default_factory=Planning)
    """How it is planned; a plugin that declares none is planned as the rule set its manifest names
    (``planning.rule_spec``)."""
    touching: Touching | None = None
    """The evaluation report's touching finding for it; None: none."""
