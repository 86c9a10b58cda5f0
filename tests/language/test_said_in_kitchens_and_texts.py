"""Sentences of the kitchen table and of texting: a thing called by what it holds ("the ketchup bottle", "the butter
packet", "the blue bottle"), a noun that narrows a place ("the box at the back" is the box farthest back, never
the plate behind it), a relative clause with "stands" / "sits", "Without dragging it, ..." before the command,
the words people add after a command on a table whose names hold digits ("block2, nice"), a topic said before the
command without a comma ("okay the bowl move it ..."), a thing's name said as a shape noun ("the can"), hesitations
("um"), a colour said by a thing of that colour ("the lemon coloured cube"), and texting ("da", "2" for "to", "the
blue 1", "2wards"). Checked on sentences of each kind (not the corpora's own lines), and what must stay refused: two
places where one is left unread, a kind no object is, a pace or a manner said before the verb that no reader reads
or that the verb contradicts."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

KITCHEN = "heldout38.tsv"
"""LIBERO's grocery meshes: a blue ketchup bottle lying, a yellow butter packet, a red soup can, a yellow milk
carton at the back, a red coffee mug with a handle, a white saucer behind the mug."""
BLOCKS = "heldout39.tsv"
"""block1-3 (red, yellow, blue 4 cm cubes) in a front row, block4 a small red cube, block5 a green cylinder, a
brown box at the back."""
INDEXED = "heldout37.tsv"
"""cube_0 and cube_1 red, cube_2 blue, cube_3 small green, bowl_0 a white bowl, target a flat yellow disc."""


@pytest.mark.parametrize("sentence, expect, table", [
    # a thing called by what it holds, or by the vessel it is
    ("slide the ketchup bottle away from the saucer", "slide:away ketchup_1 plate_1", KITCHEN),
    ("put the blue bottle next to the milk", "slide:next-to ketchup_1 milk_1", KITCHEN),
    ("move the butter pack past the soup can", "slide:past butter_1 alphabet_soup_1", KITCHEN),
    ("push the stick of butter toward the mug", "push:closer butter_1 red_coffee_mug_1", KITCHEN),
    # a noun narrows a place or a relation to the objects it names
    ("slide the box in the back closer to the butter", "slide:closer milk_1 butter_1", KITCHEN),
    ("move the box nearest the robot past the mug", "slide:past milk_1 red_coffee_mug_1", KITCHEN),
    # a relative clause with a verb of standing
    ("move the mug that sits on the right away from the ketchup", "slide:away red_coffee_mug_1 ketchup_1", KITCHEN),
    ("push the carton which stands at the back toward the plate", "push:closer milk_1 plate_1", KITCHEN),
    # "without dragging it" before the command asks for a carry; "without lifting it" keeps a slide
    ("Without dragging it, put the soup can by the butter", "carry:next-to alphabet_soup_1 butter_1", KITCHEN),
    ("without sliding it along the table, move the mug past the milk", "carry:past red_coffee_mug_1 milk_1", KITCHEN),
    ("Without lifting it, move the mug past the milk", "slide:past red_coffee_mug_1 milk_1", KITCHEN),
    # words added after a command, on a table whose names hold digits
    ("slide block4 toward block1, that would be great", "slide:closer block4 block1", BLOCKS),
    ("push block5 past block3, nice", "push:past block5 block3", BLOCKS),
    # texting: "da", "2" for "to", "1" for "one", "2wards"
    ("slide da small green cube 2 da target", "slide:closer cube_3 target", INDEXED),
    ("put cube 3 next 2 da red 1 in front", "slide:next-to cube_3 cube_0", INDEXED),
    ("push da bowl 2wards da blue 1", "push:closer bowl_0 cube_2", INDEXED),
    # a topic before the command without a comma, and the object before "you" with "this" or a modal
    ("ok the blue one move it past the bowl", "slide:past cube_2 bowl_0", INDEXED),
    ("the green cube, this you push away from the target", "push:away cube_3 target", INDEXED),
    ("The bowl you should move next to cube 0.", "slide:next-to bowl_0 cube_0", INDEXED),
    # a thing's name said as a shape noun: the thing, not a plain cylinder beside it
    ("put the can next to the marker", "slide:next-to coke_can marker", "heldout40.tsv"),
    # hesitations anywhere, as a transcript leaves them; a colour said by a thing of that colour
    ("um the blue cube um move it next to the ball", "slide:next-to blue ball", "heldout41.tsv"),
    ("move the tomato coloured cube toward the cup", "slide:closer red cup", "heldout41.tsv"),
    ("slide the sky-colored cube past the ball", "slide:past blue ball", "heldout41.tsv"),
    ("With much care, lift the can past the marker", "carry:past coke_can marker pace=careful", "heldout40.tsv"),
    ("With the utmost care, lift the can past the marker", "carry:past coke_can marker pace=careful", "heldout40.tsv"),
])
def test_read(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence, table", [
    # two places said, one of which no reader reads: the other would pick another object
    ("move the one far over on the right side in the middle of the table next to block1", BLOCKS),
    # a kind no object is, on a table whose names hold digits (the lenient reading must not read past it)
    ("move the cereal box next to block3", BLOCKS),
    # a pace before the verb in words no reader reads: never read past
    ("With great attention, lift the can past the marker", "heldout40.tsv"),
    # the verb drags, and "without dragging it" asks not to
    ("Without dragging it, slide the mug past the milk", KITCHEN),
])
def test_stays_refused(plugins, sentence, table):
    with pytest.raises(L2PError):
        read(sentence, plugins, table)
