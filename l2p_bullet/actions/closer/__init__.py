"""Built-in action: closer. Its bundle (manifest.toml and weights) lives in this folder; what else it is (the
thresholds of its rule judge: the centre distance shrinks steadily and closes at least ``share`` of the room
there was; its room check; the bound on how far its planned paths go back; its training-set options and
planner-domain extras; the touching finding of its evaluation report; its names) is declared here
(:class:`~l2p_bullet.actions.spec.ActionSpec`).
The rule itself is ``judge/rulesets/closer.py`` (named by ``rules``).
"""

from ..spec import ActionSpec, Bound, Planning, Touching, Training, Violation

THRESHOLDS = {"share": 0.5,
              "goes_back_within": 0.18}  # share of its room: the most any of people's 41 went back (0.176)

ACTION = ActionSpec(
    name="closer",
    rules="closer",
    source_name="SlideToward",
    sentence="move A closer to B",
    thresholds=THRESHOLDS,
    # from within 1.8 blocks the model rates a back-and-forth wiggle above a straight slide to touching, a
    # motion no person made: candidates going back farther than people did are scored down (bounds.py)
    # ("closes-at-least", bounds.py, is not declared: in chains it left "closer" from 1.25 blocks short of half
    # its room, docs/planning.md)
    planning=Planning(checks=("room-closer",),
                      bound=Bound("goes-back-within", THRESHOLDS["goes_back_within"])),
    training=Training(negatives=("away", "past", "around"), scale_range=(0.45, 1.7), twist=True, detour=True,
                      violation=Violation(ends_farther=0.5, strays=(9.0, 8.0)),
                      wrong_motions=("backs-off", "reversed"), graded_wrong="goes-back", near_starts=True),
    touching=Touching(also="next-to", also_words="next to",
                      note='People graded closer motions ending with the blocks touching as wrong '
                           '("the blocks touched").'),
)
