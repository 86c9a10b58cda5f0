"""Sentences with words people add after or inside a command, and motions said as what an object is made to do: a
manner ruled out at the end ("..., but don't drag it"), politeness at the end or inside without commas, a goal said
after "until it touches", "make X turn around Y", an extent said before the object ("approach a little the crate to
Q"), a doubled intensifier, an end said with "X's" for "X is", and a bare "against" (a plain next-to, where "up
against" is a tight one). Checked on sentences of each kind (not the corpora's own lines), and what must stay
refused."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

LINE = "heldout29.tsv"
"""Red cubes A, B, C in a line across the front; D a blue cylinder, E a green bar, F a white 5 cm cube, G a yellow
3 cm cube."""
HOUSEHOLD = "heldout27.tsv"
"""A zucchini, a gamepad, a white lamp, a brown crate, a white saucer, orange cubes O (4 cm) and Q (5 cm)."""


@pytest.mark.parametrize("sentence, expect, table", [
    # a manner ruled out at the end: a slide or a carry not dragged is a carry; a push stays a push
    ("move F next to D but don't drag it", "carry:next-to F D", LINE),
    ("put G by D, and don't drag it.", "carry:next-to G D", LINE),
    ("lift F around D, don't drag it", "carry:around F D", LINE),
    ("push F past D, don't drag it", "push:past F D", LINE),
    ("move F past D, don't lift it", "slide:past F D", LINE),
    # politeness at the end and between words
    ("move the crate closer to the lamp, if it's not too much trouble", "slide:closer crate lamp", HOUSEHOLD),
    ("crate a bit closer to the lamp, thats it", "slide:closer crate lamp extent=little", HOUSEHOLD),
    ("The crate please only a little nearer to the lamp.", "slide:closer crate lamp extent=little", HOUSEHOLD),
    ("the saucer pls past the crate", "slide:past saucer crate", HOUSEHOLD),
    # a goal after the motion: "until it touches"
    ("keep pushing F toward D until it touches it", "push:next-to F D extent=right", LINE),
    ("slide G toward E until it touches", "slide:next-to G E extent=right", LINE),
    # a motion said as what the object is made to do
    ("Please, can you make F turn around D?", "slide:around F D", LINE),
    ("make G go past E", "slide:past G E", LINE),
    ("make G go a bit closer to E", "slide:closer G E extent=little", LINE),
    # verbs: "loop" (around), "approach ... to"
    ("loop the crate round the lamp", "slide:around crate lamp", HOUSEHOLD),
    ("approach the crate to the lamp", "slide:closer crate lamp", HOUSEHOLD),
    # an extent said between the verb and the object
    ("approach a little the crate to the lamp", "slide:closer crate lamp extent=little", HOUSEHOLD),
    ("move a bit the saucer closer to O", "slide:closer saucer O extent=little", HOUSEHOLD),
    ("move a little cube closer to the crate", "slide:closer O crate", HOUSEHOLD),  # "a little cube": the 4 cm one
    # a doubled intensifier
    ("move F very very far from D", "slide:away F D extent=far", LINE),
    ("push G really really far away from E", "push:away G E extent=far", LINE),
    # an end said with "X's" for "X is"
    ("make it so the crate's not so close to the lamp", "slide:away crate lamp", HOUSEHOLD),
    ("I want it so the saucer's farther from the crate", "slide:away saucer crate", HOUSEHOLD),
    # a bare "against" is a plain next-to; "up against" a tight one
    ("set G against E", "slide:next-to G E", LINE),
    ("set G up against E", "slide:next-to G E extent=right", LINE),
])
def test_said_with_tails_and_causes(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence, table", [
    ("drag F past D, don't drag it", LINE),              # asks two things
    ("slide G past E, dont drag it", LINE),
    ("the crate's next to the lamp", HOUSEHOLD),         # tells how the table is
    ("make the crate", HOUSEHOLD),                       # says nothing of where
    ("The duck please past the crate", HOUSEHOLD),       # no duck on this table
])
def test_what_stays_refused(plugins, sentence, table):
    with pytest.raises(L2PError):
        read(sentence, plugins, table)


def test_a_drag_ruled_out_after_a_drag_is_named(plugins):
    with pytest.raises(L2PError, match='drags the block and "dont drag it" asks not to'):
        read("slide G past E, dont drag it", plugins, LINE)


@pytest.mark.parametrize("sentence, expect, table", [
    ("lift F thru the air past D", "carry:past F D", LINE),
    ("get F next to D, really close, touching it", "slide:next-to F D extent=right", LINE),
    ("Please to arrange in a line F, G and D.", "row F,G,D", LINE),
    ("Put in a row D, E and F, please.", "row D,E,F", LINE),
])
def test_said_by_learners_and_texters(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


def test_a_closeness_said_after_a_motion_that_has_none_is_refused(plugins):
    with pytest.raises(L2PError, match="right extent"):
        read("move F away from D, really close", plugins, LINE)


SIMULATED = "heldout30.tsv"
"""ManiSkill's apple and beaker, Roboschool's potion bottle, Cube_01 and Cube_02 (blue), Cube_03 (yellow) and a
green Cylinder_01."""
TWO_GREEN = "heldout31.tsv"
"""block1 a green cube in front, block2 a green cube at the back, block3 red, block4 a white brick, block5 a white
bar, block6 a black cylinder."""


@pytest.mark.parametrize("sentence, expect, table", [
    ("move the green tin next to the apple", "slide:next-to Cylinder_01 Apple_01", SIMULATED),  # named a cylinder
    ("put the white cup by the apple", "slide:next-to Beaker_01 Apple_01", SIMULATED),          # a beaker is a cup
    ("Move the white measuring cup away from the big blue cube.", "slide:away Beaker_01 Cube_02", SIMULATED),
    ("ok chat: cylinder past cube 2", "slide:past Cylinder_01 Cube_02", SIMULATED),
    ("move the green cube in front next to the red cube", "slide:next-to block1 block3", TWO_GREEN),
    ("Put the red cube next to the green cube behind.", "slide:next-to block3 block2", TWO_GREEN),
])
def test_kinds_and_places_said_otherwise(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


def test_a_tin_is_the_can_where_one_is_there(plugins):
    """heldout5's table has a can and a plain cylinder F: "the tin" is the can, never a guess between the two."""
    assert read("move the tin next to the mug", plugins, "heldout5.tsv") == "slide:next-to can mug"


def test_one_object_said_two_ways_that_disagree_is_refused(plugins):
    with pytest.raises(L2PError, match="said two ways"):
        read("The yellow cube, nearest the robot, put it next to the beaker.", plugins, SIMULATED)
    assert read("the yellow cube, the small one, put it next to the beaker", plugins, SIMULATED) == \
        "slide:next-to Cube_03 Beaker_01"


def test_the_one_long_block_on_a_table_is_the_stick(plugins):
    """An 8 x 4 x 4 cm bar is "the stick" where nothing thinner is there; beside a 12 x 3 cm bar it is the brick."""
    assert read("move the green stick next to H", plugins, "heldout36.tsv") == "slide:next-to G H"
    assert read("put the white stick next to block3", plugins, TWO_GREEN) == "slide:next-to block5 block3"


def test_a_row_said_is_never_read_past(plugins):
    """Rows of the table are not read yet: "the leftmost one in the middle row" is asked, never read as "the leftmost
    one in the middle" (another object) by leaving "row" over."""
    with pytest.raises(L2PError):
        read("Move H next to the leftmost one in the middle row.", plugins, "heldout36.tsv")
