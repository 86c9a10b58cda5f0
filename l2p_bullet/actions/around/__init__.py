"""Built-in action: around. Its bundle (manifest.toml and weights) lives in this folder; what else it is (the
thresholds of its rule judge: it sweeps at least ``turns`` of a full turn around the anchor, never farther
than ``near`` blocks once it has come that near; its room checks; its lead-in: the ``approach`` distance a
mover starting farther is first slid to, the ``reach`` its planned moves stay within; its training-set
options and planner-domain extras; its names) is declared here (:class:`~l2p_bullet.actions.spec.ActionSpec`).
The rule itself is ``judge/rulesets/around.py`` (named by ``rules``).
"""

import math

from ..spec import ActionSpec, LeadIn, Planning, Training, Violation

# reach: the search's rings reach 5 and 6.5 blocks, and the learned model rates a circle with one corner out
# there done (0.99), a motion no person made (analysis starts, seeds 5000-5079: 5 of around's 8 failed plans;
# docs/planning.md); so around is planned inside the room people used, the model unchanged
THRESHOLDS = {"turns": 0.8, "near": 4.0,
              "approach": 2.5,  # blocks: the median start of people's 40 demonstrations (tests/planning)
              "reach": 4.1}  # blocks: the farthest any of people's 39 trusted ones went from it (4.09)

ACTION = ActionSpec(
    name="around",
    rules="around",
    source_name="SlideAround",
    sentence="move A around B",
    thresholds=THRESHOLDS,
    planning=Planning(checks=("room-around", "blocked-around"),
                      lead_in=LeadIn(near=THRESHOLDS["near"], approach=THRESHOLDS["approach"],
                                     reach=THRESHOLDS["reach"])),
    training=Training(negatives=("closer", "away", "next-to"), scale_range=(0.75, 1.2), turn_label=1.0,
                      violation=Violation(no_turn=(20.0, 2.0), strays=(9.0, math.inf)),
                      clear_grades=(1.5, 5.5), wrong_motions=("half-round-and-back",), grid_copies=True,
                      strays=True),
    graded_folders=("SlideAroundDiscrete",),
)
