"""Built-in action: past. Its bundle (manifest.toml and weights) lives in this folder; what else it is (the
thresholds of its rule judge: it crosses from ``margin`` blocks before the anchor to ``margin`` beyond, within
``near`` blocks, turning at most ``max_turn_deg`` around it; the bounds ``passes_within`` and
``starts_before`` its planned paths keep to; its training-set options and planner-domain extras; its names) is
declared here (:class:`~l2p_bullet.actions.spec.ActionSpec`).
The rule itself is ``judge/rulesets/past.py`` (named by ``rules``).
"""

import math

from ..spec import ActionSpec, Bound, Planning, Training, Violation

THRESHOLDS = {"margin": 0.5, "near": 4.0, "max_turn_deg": 180.0,
              # blocks: people's 43 passed the anchor at a median 1.9, nine in ten within 3.23 (90 % quantile)
              "passes_within": 3.2,
              # share of the start distance: 39 of people's 43 (90 %, the 10 % quantile 0.512 rounded down)
              # started before the anchor by at least half their distance from it, along their overall direction
              "starts_before": 0.5}

ACTION = ActionSpec(
    name="past",
    rules="past",
    source_name="SlidePast",
    sentence="move A past B",
    thresholds=THRESHOLDS,
    # the model rates a pass 4-5 blocks away done, a motion no person made: candidates passing farther than
    # people did are scored down (planning/bounds.py); so are those that, from beside the anchor, slide along
    # it instead of crossing to its far side, as people's starts from beside it are too few to teach it
    planning=Planning(bound=Bound("passes-within", THRESHOLDS["passes_within"]),
                      more_bounds=(Bound("starts-before", THRESHOLDS["starts_before"]),)),
    training=Training(negatives=("closer", "away", "next-to", "around"), approach=(1.0, 4.0),
                      violation=Violation(no_turn=(20.0, 2.0), max_turn_deg=270.0, strays=(9.0, math.inf)),
                      wrong_motions=("to-closest-and-back",)),
)
