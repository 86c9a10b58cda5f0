"""Sentences of tables whose names are two words ("salt shaker", "tip_box") or carry a measure ("beaker_250"): a name
said as its parts without their joint ("tips box"), two names run together in a list typed without commas (never read
as one object), a name said with its everyday kind ("the pepper pot", "the tea mug", "the Erlenmeyer", "the tube
rack"), a measure said before its noun ("the 500 ml beaker", "the 250ml", "250 beaker"; a length stays a size), an
object shown before a verb that then has no object ("Tip box, move past the vial"), a step's label with its number
("Step 4. Move ..."), a clause said once more ("... a lot closer to the rack? much closer"), "same" as a protocol says
"it", "back toward" after a step, British framings ("sat next to", "whilst you're there", "sorry to be a pain", "the
right hand shaker"), a lift said with "pop it", and a manner said after a dash ("X round Y - carry it, don't drag").
Checked on sentences of each kind (not the corpora's own lines), and what must stay refused."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

BREAKFAST = "heldout47.tsv"
"""salt shaker (white) and pepper shaker (black) at the front, a brown cutting board back left, a white tea cup back
right, a blue sugar bowl in the middle, a yellow butter dish front right."""
BENCH = "heldout49.tsv"
"""beaker_250 front left, beaker_500 back left (both white cylinders), a white flask, a blue tip_box front right, a
white rack at the back, a small brown vial in the middle."""
DIGITS = "heldout31.tsv"
"""block1 ... block5 and a white brick: numbered objects whose sizes people say in centimetres."""


@pytest.mark.parametrize("sentence, expect, table", [
    # a name of two words, and its everyday kinds
    ("nudge the tea mug toward the sugar pot", "push:closer tea cup sugar bowl", BREAKFAST),
    ("carry the pepper pot past the chopping board", "carry:past pepper shaker cutting board", BREAKFAST),
    ("slide the cuppa away from the salt", "slide:away tea cup salt shaker", BREAKFAST),
    ("push the Erlenmeyer toward the tips box", "push:closer flask tip_box", BENCH),
    ("move the test tube holder past the vial", "slide:past rack vial", BENCH),
    ("Bring the vial to tip box.", "slide:closer vial tip_box", BENCH),
    # names run together in a list without commas
    ("line up the sugar bowl tea cup and butter dish", "row sugar bowl,tea cup,butter dish", BREAKFAST),
    # a measure before the noun
    ("slide the 250 ml beaker around the rack", "slide:around beaker_250 rack", BENCH),
    ("push the 500ml away from the flask", "push:away beaker_500 flask", BENCH),
    ("move 500 beaker next to the 250 mL one", "slide:next-to beaker_500 beaker_250", BENCH),
    ("move the 5 cm block past the brick", "slide:past block3 block4", DIGITS),  # a length is a size: not block5
    # an object shown, then a verb whose object it is
    ("Rack, slide past the flask.", "slide:past rack flask", BENCH),
    ("Butter dish: please push toward the cup", "push:closer butter dish tea cup", BREAKFAST),
    # a step's label and number; "same" for the object moved; a clause said once more
    ("Step 1. Slide the vial toward the rack. Step 2. Push same past the flask.",
     "slide:closer vial rack ; push:past vial flask", BENCH),
    ("could the vial be a bit closer to the flask? a bit closer", "slide:closer vial flask extent=little", BENCH),
    ("move the flask past the rack, then back toward the vial", "slide:past flask rack ; slide:closer flask vial",
     BENCH),
    # British framings and a lift said with "pop it"
    ("I'd like the pepper sat beside the butter dish, if that's ok", "slide:next-to pepper shaker butter dish",
     BREAKFAST),
    ("sorry to be a pain, shift the cup away from the board whilst you're at it",
     "slide:away tea cup cutting board", BREAKFAST),
    ("move the left hand shaker past the sugar bowl", "slide:past salt shaker sugar bowl", BREAKFAST),
    ("pick up the butter dish and pop it next to the board", "carry:next-to butter dish cutting board", BREAKFAST),
    ("Sugar bowl, I want it at the far side of the cup.", "slide:past sugar bowl tea cup", BREAKFAST),
    ("2. Transfer the vial next to the flask", "slide:next-to vial flask", BENCH),
    # a verbless clause, a dash, and how it is moved
    ("vial round the rack - carry it, don't drag", "carry:around vial rack", BENCH),
])
def test_read(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence, table", [
    # two names said as one object: asked, never one of them
    ("move the butter dish salt shaker past the cup", BREAKFAST),
    # "pot" fits the shakers and the bowl alike
    ("move the pot past the cup", BREAKFAST),
    # the clause said again with "again" is a step of its own, and needs its mover
    ("move the vial closer to the rack. closer again", BENCH),
])
def test_stays_refused(plugins, sentence, table):
    with pytest.raises(L2PError):
        read(sentence, plugins, table)
