"""Built-in action: around. Its bundle (manifest.toml and weights) lives in this folder; what else it is (the
thresholds of its rule judge: it sweeps at least ``turns`` of a full turn around the anchor, never farther
than ``near`` blocks once it has come that near; the ``approach`` distance a mover starting farther is
first slid to; the ``reach`` its planned moves stay within; its training-set options; its names) is declared here
(:class:`~l2p_bullet.actions.spec.ActionSpec`).
The rule itself is ``judge/rulesets/around.py`` (named by ``rules``).
"""

import math

from ..spec import ActionSpec, Training, Violation

ACTION = ActionSpec(
    name="around",
    rules="around",
    source_name="SlideAround",
    sentence="move A around B",
    thresholds={"turns": 0.8, "near": 4.0,
                "approach": 2.5,  # blocks: the median start of people's 40 demonstrations (tests/actions)
                "reach": 4.1},  # blocks: the farthest from the anchor any of people's trusted ones went (4.09)
    training=Training(negatives=("closer", "away", "next-to"), scale_range=(0.75, 1.2), turn_label=1.0,
                      violation=Violation(no_turn=(20.0, 2.0), strays=(9.0, math.inf)),
                      clear_grades=(1.5, 5.5)),
    graded_folders=("SlideAroundDiscrete",),
)
