"""Sentences of tables whose names do not say what the objects are: toys named by a child (Rex, Daisy, Max, Nemo), each
with the kind its scene file declares ("kind": "toy dinosaur"), said by kind ("the dino", "the moo cow", "the
doggy", "the red house", "the water") or by name and kind at once ("Rex the dinosaur", "Max, our dog", "Daisy (the
cow)"; a kind that names another object is asked); "him" and "her" after a clause that moved one animal next to
another (asked, as either may be meant); and the YCB object set as its files name it ("002_master_chef_can"): by the
number it opens with ("005", "obj 6", "item 010"), by its words without the number ("cracker_box"), by the products'
brands ("the Spam", "the Cheez-It box", "the coffee"), with an Australian's "plonk", "stick", "heaps" and "up the
front"; building bricks by the size codes their names hold ("the red two by four" for brick_2x4_red, "the rightmost
brick" among those the names call bricks); Hinglish paces and extents ("jaldi", "thoda"). Also what must not change a
reading: "for a pic" is no "pick" (a lift), "park it" after "shove it" is no push. Checked on sentences of each kind
(not the corpora's own lines), and what must stay refused."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

FARM = "heldout51.tsv"
"""Rex (a toy dinosaur), Daisy (a toy cow), Max (a toy dog), Nemo (a toy fish), a red barn, a flat blue pond."""
OFFICE = "heldout52.tsv"
"""stapler, mug, phone (lying flat), notebook (lying flat), pen_holder, mouse."""
BRICKS = "heldout53.tsv"
"""brick_2x4_red, brick_2x2_red, brick_2x2_blue, brick_1x4_yellow, plate_4x4_green, minifig."""
YCB = "heldout50.tsv"
"""002_master_chef_can, 003_cracker_box, 004_sugar_box, 005_tomato_soup_can, 006_mustard_bottle,
010_potted_meat_can."""


@pytest.mark.parametrize("sentence, expect, table", [
    # a declared kind, and its everyday names
    ("push the dino toward the water", "push:closer Rex pond", FARM),
    ("slide the doggy past the moo cow", "slide:past Max Daisy", FARM),
    ("move the clownfish next to the red house", "slide:next-to Nemo barn", FARM),
    # "her" after a clause that moved a dog next to a cow: the cow
    ("slide Max next to Daisy, then push her toward the barn", "slide:next-to Max Daisy ; push:closer Daisy barn",
     FARM),
    # a name said with its kind
    ("carry Nemo the fish around the pond", "carry:around Nemo pond", FARM),
    ("move Max, our dog, away from the barn", "slide:away Max barn", FARM),
    ("push Daisy (the cow) toward Rex", "push:closer Daisy Rex", FARM),
    # "him" after a clause whose anchor is no animal is the block moved
    ("move Max to the pond and then take him around the barn", "slide:closer Max pond ; slide:around Max barn", FARM),
    # a pic is a photo, not a lift
    ("slide nemo toward the barn for a pic", "slide:closer Nemo barn", FARM),
    # the YCB set: the number a name opens with, its words without it, and the brands
    ("slide 006 past item 010", "slide:past 006_mustard_bottle 010_potted_meat_can", YCB),
    ("move obj 2 toward the 005", "slide:closer 002_master_chef_can 005_tomato_soup_can", YCB),
    ("push sugar_box away from cracker_box", "push:away 004_sugar_box 003_cracker_box", YCB),
    ("move the Spam next to the Cheez-It box", "slide:next-to 010_potted_meat_can 003_cracker_box", YCB),
    ("slide the Campbell's can toward the coffee", "slide:closer 005_tomato_soup_can 002_master_chef_can", YCB),
    ("carry the French's around the Domino box", "carry:around 006_mustard_bottle 004_sugar_box", YCB),
    # Australian turns: plonk, stick, heaps, up the front, "for us"; an object taken, then moved as "it"
    ("plonk the coffee next to the Spam", "slide:next-to 002_master_chef_can 010_potted_meat_can", YCB),
    ("push the mustard heaps further from the soup", "push:away 006_mustard_bottle 005_tomato_soup_can extent=far",
     YCB),
    ("the red one up the front, shove it toward the sugar", "push:closer 005_tomato_soup_can 004_sugar_box", YCB),
    ("stick the Spam, the coffee and the soup in a row for us",
     "row 010_potted_meat_can,002_master_chef_can,005_tomato_soup_can", YCB),
    ("ok take the mustard and slide it past the Spam", "slide:past 006_mustard_bottle 010_potted_meat_can", YCB),
    # bricks by their size codes as people say them, and by what the names call bricks
    ("slide the red two by four toward the baseplate", "slide:closer brick_2x4_red plate_4x4_green", BRICKS),
    ("push the 2 x 2 blue past the minifigure", "push:past brick_2x2_blue minifig", BRICKS),
    ("move the rightmost brick toward the mini fig", "slide:closer brick_1x4_yellow minifig", BRICKS),
    # Hinglish paces and extents; a clause's own verb, "park"; a pencil holder
    ("jaldi jaldi push the stapler toward the mug", "push:closer stapler mug pace=fast", OFFICE),
    ("move the mug thoda away from the phone", "slide:away mug phone extent=little", OFFICE),
    ("shove the mouse past the stapler, then park it next to the mug",
     "push:past mouse stapler ; slide:next-to mouse mug", OFFICE),
    ("move the phone around the pencil holder", "slide:around phone pen_holder", OFFICE),
])
def test_read(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence, table", [
    # a name and a kind that name two objects
    ("move Rex the cow past the pond", FARM),
    # "her" after a clause that moved one animal next to another, neither of them a she by kind: either
    ("slide Max next to Rex, then push her toward the barn", FARM),
    # two objects shown before a statement of the end: what follows picks among them
    ("Nemo and Max both need moving: Nemo goes next to Rex, and the other one goes around the pond", FARM),
    # "the can" fits three cans
    ("move the can past the sugar box", YCB),
    # a number no name opens or ends with
    ("move obj 7 toward the 005", YCB),
    # the two red bricks are 2 cm apart from the left; a phone and a notebook both lie flat; a pencil cup is the
    # pen holder or the mug; an extent said before the verb is not dropped; a verb unknown is not the verb before
    ("move the leftmost brick toward the plate", BRICKS),
    ("push the flat thing toward the mug", OFFICE),
    ("move the phone around the pencil cup", OFFICE),
    ("thoda sa move the mouse towards the phone", OFFICE),
    ("shove the mouse past the stapler, then wedge it next to the mug", OFFICE),
])
def test_stays_refused(plugins, sentence, table):
    with pytest.raises(L2PError):
        read(sentence, plugins, table)
