"""carry: grasp, lift above every object under the path, follow the learned path in the air, lower, release."""

from .spec import MannerSpec

MANNER = MannerSpec(
    name="carry", verbs=("carry", "lift ... and put", "pick up ... and put", "lift ... and place",
                         "pick up ... and place", "pick ... up and put", "lift ... and drop", "pick up ... and drop",
                         "lift ... and set", "pick up ... and set", "grab ... and put", "grab ... and place",
                         "grab ... and drop", "grab ... and set", "hoist ... and put", "hoist ... and drop", "lift",
                         "pick up", "hoist", "airlift", "fly"),
    motion="carry", signature="lifted", airborne=True,
    description="grasp, lift clear of every object under the path, carry it along the path, set it down",
)
