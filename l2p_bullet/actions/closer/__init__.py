"""Built-in action: closer. Its bundle (manifest.toml and weights) lives in this folder; what else it is (the
thresholds of its rule judge: the centre distance shrinks steadily and closes at least ``share`` of the room
there was; its training-set options; its names) is declared here
(:class:`~l2p_bullet.actions.spec.ActionSpec`).
The rule itself is ``judge/rulesets/closer.py`` (named by ``rules``).
"""

from ..spec import ActionSpec, Training, Violation

ACTION = ActionSpec(
    name="closer",
    rules="closer",
    source_name="SlideToward",
    sentence="move A closer to B",
    thresholds={"share": 0.5,
                "goes_back_within": 0.18},  # share of its room: the most any of people's 41 went back (0.176, up)
    training=Training(negatives=("away", "past", "around"), scale_range=(0.45, 1.7), twist=True, detour=True,
                      violation=Violation(ends_farther=0.5, strays=(9.0, 8.0))),
)
