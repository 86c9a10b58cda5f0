"""carry: grasp, lift above every object under the path, follow the learned path in the air, lower, release."""

from .spec import MannerSpec

MANNER = MannerSpec(
    name="carry", verbs=("carry", "lift ... and put", "pick up ... and put", "lift ... and place",
                         "pick up ... and place", "pick ... up and put", "lift ... and drop", "pick up ... and drop",
                         "lift ... and set", "pick up ... and set", "grab ... and put", "grab ... and place",
                         "grab ... and drop", "grab ... and set", "hoist ... and put", "hoist ... and drop",
                         "lift ... and take", "lift ... and bring", "lift ... and move", "lift ... and carry",
                         "pick up ... and take", "pick up ... and bring", "pick up ... and move",
                         "pick up ... and carry", "grab ... and carry", "raise ... and carry", "raise ... and put",
                         "raise ... and move", "raise ... and take", "raise ... and bring", "lift ... and pop",
                         "pick up ... and pop", "pick ... up and pop", "pick ... up and place", "pick ... up and set",
                         "pick ... up and carry", "pick ... up and move", "pick ... up and bring", "lift",
                         "pick up", "hoist", "airlift", "fly"),
    motion="carry", signature="lifted", airborne=True,
    description="grasp, lift clear of every object under the path, carry it along the path, set it down",
)
