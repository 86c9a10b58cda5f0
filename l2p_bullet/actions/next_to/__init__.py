"""Built-in action: next-to. Its bundle (manifest.toml and weights) lives in this folder; what else it is (the
thresholds of its rule judge: the mover ends with at most ``gap`` blocks between the two footprints, not
overlapping; its training-set options and planner-domain extras; its names) is declared here
(:class:`~l2p_bullet.actions.spec.ActionSpec`).
The rule itself is ``judge/rulesets/next_to.py`` (named by ``rules``).
"""

from ..spec import ActionSpec, Planning, Training, Violation

ACTION = ActionSpec(
    name="next-to",
    rules="next-to",
    source_name="SlideNext",
    sentence="move A next to B",
    thresholds={"gap": 0.5},
    # where people's own "next to" ends: 36 of their 40 ended within 0.15 blocks (median 0.03), every one of
    # the 26 whose two blocks were both seen at the end within 0.13 (docs/perform.md, "Already next to")
    planning=Planning(holds_within=0.15),
    training=Training(negatives=("away", "past", "around"), scaled=False, twist=True,
                      violation=Violation(ends_farther=0.5, stays_off=(2.5, 0.25), strays=(9.0, 8.0)),
                      wrong_motions=("reversed",), graded_wrong="moves-out"),
)
