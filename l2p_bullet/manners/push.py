"""push: no grasp; the closed fingers push the block's face opposite the direction of travel."""

from .spec import MannerSpec

MANNER = MannerSpec(
    name="push", verbs=("push", "nudge", "shove", "flick", "poke", "bump", "give ... a push", "give ... a nudge",
                        "give ... a shove"),
    motion="push", signature="no-grasp",
    description="no grasp: the closed fingers push the face opposite the travel, re-planned from the block's pose",
)
