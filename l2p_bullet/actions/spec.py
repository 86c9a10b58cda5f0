"""What an action is, in one place: :class:`ActionSpec`, declared by each action's module as ``ACTION``.

A built-in action's module (``l2p_bullet/actions/<name>/__init__.py``, the entry point's target, next to its
bundle) declares its name in the study's data, an example sentence, the thresholds its rule judge and the
feasibility room check read, and how its training set differs from the defaults. The stages hold the
algorithms and read these values: ``core/vocabulary.py`` (names), ``judge/rulesets/`` (rule judges),
``planning/feasibility.py`` (room checks, through the rules' thresholds), ``learning/trainset.py``
(``DataConfig``'s defaults), ``learning/improve.py`` (sentences). A plugin's module may declare an
``ACTION`` the same way; the registry hands it over with the bundle (``Bundle.spec``).

Pure declarations on the lowest floor above ``errors`` (docs/DESIGN.md, "Floors"): every stage may read
them, they import nothing of the package.
"""

from __future__ import annotations

from dataclasses import dataclass, field


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
