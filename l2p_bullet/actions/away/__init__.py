"""Built-in action: away. Its bundle (manifest.toml and weights) lives in this folder; what else it is (the
thresholds of its rule judge: the centre distance grows steadily, by at least ``gain`` blocks; its training-
set options and planner-domain extras; its room check; the least growth its planned paths from afar keep to; its
names) is declared here
(:class:`~l2p_bullet.actions.spec.ActionSpec`).
The rule itself is ``judge/rulesets/away.py`` (named by ``rules``).
"""

from ..spec import ActionSpec, Bound, Planning, Training, Violation

THRESHOLDS = {"gain": 1.0,
              "grows_at_least": 1.8}  # blocks: 35 of people's 37 grew the distance by at least this (5 % quantile)

ACTION = ActionSpec(
    name="away",
    rules="away",
    source_name="SlideAway",
    sentence="move A away from B",
    thresholds=THRESHOLDS,
    # from afar the model rates a growth of 0.7 blocks done, short of the rule's one: candidates from there
    # growing the distance less than people did are scored down (planning/bounds.py)
    planning=Planning(checks=("room-away",), bound=Bound("grows-at-least", THRESHOLDS["grows_at_least"])),
    training=Training(negatives=("closer", "next-to", "around"), shortened=(0.75, 0.95),
                      twist=True, detour=True, net_label=1.5,
                      violation=Violation(ends_nearer=0.5), clear_grades=(4.5, 7.0),
                      wrong_motions=("out-and-back", "reversed"), graded_wrong="goes-back"),
)
