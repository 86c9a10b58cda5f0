"""The nouns that also name a shape ("the box", "the stick", "the log"): read by the descriptions, the pointers
back and the kind tables, which must never give such a word to one object."""

from __future__ import annotations

SHAPE_NOUNS = {"cube": "cube", "cubes": "cube", "dice": "cube", "die": "cube",
               "box": "box", "boxes": "box", "bar": "box", "bars": "box",
               "stick": "box", "sticks": "box", "brick": "box", "bricks": "box", "rectangle": "box",
               "rectangles": "box",
               "cylinder": "cylinder",
               "can": "cylinder", "cylinders": "cylinder"}
"""Nouns that also name a shape: alone ("the box") they pick objects of that shape; with a colour ("the red
box", "the white cube") any block-shaped object (a cube or a box: people call any block a box or a
cube), never a cylinder or a mesh."""
SHAPE_NOUNS |= dict.fromkeys(("rod", "rods", "pole", "poles", "dowel", "dowels", "skewer", "wand", "beam", "beams",
                              "girder", "girders", "rail", "rails", "plank", "planks", "board", "boards", "ruler",
                              "rulers", "slab", "slabs", "tile", "tiles", "slate", "slates", "plate", "pad", "post",
                              "posts", "pillar", "pillars", "column", "columns", "tower", "towers"), "box")
SHAPE_NOUNS |= dict.fromkeys(("disc", "discs", "disk", "disks", "puck", "pucks", "coin", "coins", "log", "logs",
                              "roll", "rolls", "tube", "tubes", "pipe", "pipes"), "cylinder")
"""And the nouns of proportions (language/proportions.py reads them: "the stick", "the slab", "the log"), with the
shape they most often are, for the readers that ask a noun's shape ("that log" points back to a cylinder)."""
