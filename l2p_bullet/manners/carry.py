"""carry: grasp, lift above every object under the path, follow the learned path in the air, lower, release."""

from .spec import MannerSpec

MANNER = MannerSpec(
    name="carry", verbs=("carry", "lift ... and put", "pick up ... and put", "lift ... and place",
                         "pick up ... and place", "pick ... up and put", "lift", "pick up"),
    motion="carry", signature="lifted", airborne=True,
    description="grasp, lift clear of every object under the path, carry it along the path, set it down",
)
