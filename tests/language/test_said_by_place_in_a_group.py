"""Objects said by their place in a group or on the table (language/group_places.py): the middle one of a group in a
line, the n-th counted from a side, an end of a row, a corner, the table's edge, the middle of everything; and what
stays refused (places under a place tie, a group in no line, an even group's middle, an ordinal counted from no
side that the two ends read differently). Sentences of each kind, none of them a corpus line, on a table built here."""

from __future__ import annotations

import pytest
from corpus import REFUSE, resolve

from l2p_bullet.core.scene import Scene

TABLE = {"objects": [
    *({"name": f"Y{k + 1}", "color": "yellow", "size": 0.03, "xy": [x, 0.12]}
      for k, x in enumerate((-0.16, -0.08, 0.0, 0.08, 0.16))),
    {"name": "G1", "color": "green", "shape": "cylinder", "radius": 0.02, "height": 0.05, "xy": [-0.12, -0.20]},
    {"name": "G2", "color": "green", "shape": "cylinder", "radius": 0.02, "height": 0.05, "xy": [-0.02, -0.15]},
    {"name": "G3", "color": "green", "shape": "cylinder", "radius": 0.02, "height": 0.05, "xy": [0.08, -0.10]},
    {"name": "O1", "color": "orange", "size": 0.04, "xy": [0.27, -0.25]},
    {"name": "O2", "color": "orange", "size": 0.04, "xy": [0.25, -0.02]},
    {"name": "W1", "color": "white", "size": 0.02, "xy": [-0.30, -0.12]},
    {"name": "W2", "color": "white", "size": 0.02, "xy": [-0.30, -0.02]},
    {"name": "W3", "color": "white", "size": 0.02, "xy": [-0.30, 0.005]},
    {"name": "K1", "color": "black", "size": 0.03, "xy": [-0.05, 0.30]},
    {"name": "K2", "color": "black", "size": 0.03, "xy": [0.05, 0.30]},
    {"name": "K3", "color": "black", "size": 0.03, "xy": [0.0, 0.22]},
]}
"""Five yellow cubes in a row from the front to the back, three green cylinders in a slanting line, two orange
cubes, three small white cubes across the front whose two on the left stand 2.5 cm apart (a place tie), and three
black cubes in a triangle on the left."""


@pytest.fixture(scope="module")
def table() -> Scene:
    return Scene.from_dict(TABLE)


@pytest.mark.parametrize("sentence, expect", [
    # the middle of an odd group in a line, however said
    ("slide the middle yellow cube toward O1", "slide:closer Y3 O1"),
    ("push the middle green cylinder past O2", "push:past G2 O2"),
    ("move the central green one next to O1", "slide:next-to G2 O1"),
    ("move the cylinder green of the middle toward O2", "slide:closer G2 O2"),
    ("move the yellow cube in the middle of the row away from O1", "slide:away Y3 O1"),
    ("move the middle one of the three green cylinders toward O2", "slide:closer G2 O2"),
    # counted from a side
    ("push the second yellow cube from the front toward O1", "push:closer Y2 O1"),
    ("push the second yellow cube from the rear toward O1", "push:closer Y4 O1"),
    ("move the fourth yellow cube counting from the rear past O2", "slide:past Y2 O2"),
    ("move the last yellow cube from the front toward O2", "slide:closer Y5 O2"),
    ("move the first green cylinder from the right toward O2", "slide:closer G1 O2"),
    ("move the 2nd green cylinder from the left around O2", "slide:around G2 O2"),
    ("move the second-to-last yellow cube from the front toward O1", "slide:closer Y4 O1"),
    ("move the second last cylinder from the left toward O1", "slide:closer G2 O1"),
    ("move the yellow cube second from the front toward O1", "slide:closer Y2 O1"),
    # counted from no side: the same object from either end
    ("move the third yellow one toward O1", "slide:closer Y3 O1"),
    ("move the second green cylinder toward O1", "slide:closer G2 O1"),
    # ends of a row
    ("move the yellow cube at the back end toward O1", "slide:closer Y5 O1"),
    ("move the yellow cube on the front end toward O1", "slide:closer Y1 O1"),
    ("move the white cube on the right end past O2", "slide:past W1 O2"),
    ("move the far right cylinder toward O2", "slide:closer G1 O2"),
    # corners
    ("move the front-right cylinder toward O2", "slide:closer G1 O2"),
    ("slide the back left yellow cube toward O1", "slide:closer Y5 O1"),
    ("move the cylinder in the back-right corner toward O2", "slide:closer G3 O2"),
    ("move the orange cube at the rear right toward Y1", "slide:closer O1 Y1"),
    # the table's edges and sides
    ("move the cylinder closest to the right edge toward O2", "slide:closer G1 O2"),
    ("move the yellow cube nearest the back of the table toward O1", "slide:closer Y5 O1"),
    ("move the orange cube farthest from the left edge toward Y1", "slide:closer O1 Y1"),
    ("move the cylinder at the front of the table toward O2", "slide:closer G1 O2"),
    ("move the orange block with the smallest y toward Y1", "slide:closer O1 Y1"),
    # the robot's view said, and a place said with "kept"
    ("move the cylinder furthest to the left, as the robot sees it, toward O2", "slide:closer G3 O2"),
    ("move the orange cube on the robot's left toward Y1", "slide:closer O2 Y1"),
    ("push the cube kept at the back right toward Y1", "push:closer O1 Y1"),
    # a half of the table beside the robot
    ("move the cylinder nearest the robot on the right side toward O2", "slide:closer G1 O2"),
])
def test_said_by_place(plugins, table, sentence, expect):
    assert resolve(sentence, table, plugins) == expect


@pytest.mark.parametrize("sentence", [
    "move the middle white cube toward O1",  # W2 and W3 2.5 cm apart: the middle is a tie
    "move the second white cube from the right toward O1",  # the same tie, counted
    "move the middle orange cube toward Y1",  # two: no middle
    "move the middle black cube toward Y1",  # a triangle: none is between the others
    "move the second black cube toward Y1",  # and no order without a side
    "move the second yellow cube toward O1",  # Y2 from the front, Y4 from the back: asked
    "move the first green cylinder toward O1",  # G1 or G3
    "move the sixth yellow cube from the front toward O1",  # there are five
    "move the middle red cube toward O1",  # none is red
    "move the second purple cube from the left toward O1",
    "move the thing in the middle of everything toward O1",  # Y2 and Y3 all but equally near the centre
    "move the second to last yellow cube toward O1",  # Y4 from the front, Y2 from the back
    "move the first from the left toward O1",  # K1 and K2 side by side on the left
    "move the cylinder nearest the robot on the left side toward O1",  # every cylinder is on the right
])
def test_stays_refused(plugins, table, sentence):
    assert resolve(sentence, table, plugins) == REFUSE


@pytest.mark.parametrize("sentence, expect", [
    ("move the thing in the middle of everything toward O1", "slide:closer G3 O1"),
    ("push the one in the centre of all the objects past O2", "push:past G3 O2"),
    ("move the cylinder in the middle of them all toward O1", "slide:closer G3 O1"),
])
def test_the_middle_of_everything(plugins, table, sentence, expect):
    """Of the cylinders and the orange cubes, the one nearest their centre."""
    assert resolve(sentence, table.only(("G1", "G2", "G3", "O1", "O2")), plugins) == expect
