"""slide: the block is held from above (a constraint, the closed fingers on its top) and slid on the table."""

from .spec import MannerSpec

MANNER = MannerSpec(
    name="slide", verbs=("slide", "move", "shift", "drag", "glide", "put", "place", "set", "position", "circle", "get",
                         "take", "relocate", "reposition", "bring", "scoot", "send", "tuck", "pop", "loop", "approach",
                         "translate", "displace", "transfer", "drive", "plonk", "stick", "park", "drop"),
    motion="slide", signature="on-table",
    description="grasp from above and slide the block on the table (within 3 mm of it)", default=True,
    # the verbs that say where, not how: where the other objects leave a slide no way round, the block is carried
    # over them (a person lifts it over what is in the way); "slide", "drag", "shift", "glide", "scoot" and
    # "drive" say how, and are refused there
    loose=("move", "put", "place", "set", "position", "circle", "get", "take", "relocate", "reposition", "bring",
           "send", "tuck", "pop", "loop", "approach", "translate", "displace", "transfer", "plonk", "stick", "park",
           "drop"),
    over="carry",
)
