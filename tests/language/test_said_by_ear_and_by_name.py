"""Sentences of tables whose names say more than they should, and of speech-to-text: a name that is a colour ("the
orange block" beside the fruit named "orange"), a name with a place word in it where the object no longer stands
("the left block" beside left_block on the right: asked), a name with a size word ("the small box" is small_box where
it is the smaller box), numbered steps ("1. ...", "2) ..."), a target disc called goal, target or marker, the soda
can beside the soup can, "the front mug", homophones a transcript leaves ("next two", "a round", "passed", "a way
from", "slow Lee", "bowel"), the verb said last in German order, the words of Indian English ("keep X beside Y", "do
the needful", "itself"), and a pace said in Spanish ("rapido", "con cuidado"). Checked on sentences of each kind (not
the corpora's own lines), and what must stay refused."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

FRUIT = "heldout42.tsv"
"""orange (the fruit) front left, a red apple, a yellow lemon, a white bowl and a white plate, a green 4 cm cube, an
orange 5 cm cube named "block" in the middle."""
TASK = "heldout43.tsv"
"""Blue cubes left_block (standing back right) and right_block (front left), brown boxes big_box and small_box, a
flat green disc named goal in the middle, a gray post named obstacle."""
SPANISH = "heldout45.tsv"
"""A bilingual classroom: caja (a box), pelota (a ball), taza (a mug), lata (a green can), cubo_rojo, cubo_azul."""
PARCELS = "heldout46.tsv"
"""Parcels SKU-1042 and SKU-3307 (brown boxes), SKU-2210 (a white tube standing), a blue tote, an orange cone (a
4 x 7 cm cylinder), a black scanner."""
CLEANUP = "heldout44.tsv"
"""mug_1 white (front left), mug_2 blue (back), can_1 a soda can, can_2 a soup can (both red), box_1 a yellow
gelatin box, block_1 a red cube, block_2 a green cube."""


@pytest.mark.parametrize("sentence, expect, table", [
    # a colour that names an object is the colour before a noun; the name alone is the fruit
    ("slide the orange cube toward the bowl", "slide:closer block bowl", FRUIT),
    ("push the lemon away from the orange block", "push:away lemon block", FRUIT),
    ("move the orange fruit past the plate", "slide:past orange plate", FRUIT),
    ("move the orange past the plate", "slide:past orange plate", FRUIT),
    # a name with a size word: the object it names where the size word picks it too
    ("slide the goal next to the small box", "slide:next-to goal small_box", TASK),
    ("carry right_block past the big box", "carry:past right_block big_box", TASK),
    # goal, target and marker call each other
    ("push the target toward the post", "push:closer goal obstacle", TASK),
    ("move the green marker past the small box", "slide:past goal small_box", TASK),
    # numbered steps and Indian English
    ("1. Move big_box past goal. 2) Slide small_box toward the goal.",
     "slide:past big_box goal ; slide:closer small_box goal", TASK),
    ("Kindly keep small_box beside the goal itself.", "slide:next-to small_box goal", TASK),
    ("Please do the needful and move the obstacle away from goal only", "slide:away obstacle goal", TASK),
    ("right_block -> other side of the post", "slide:past right_block obstacle", TASK),
    ("Don't drag small_box, lift it and put it next to the post", "carry:next-to small_box obstacle", TASK),
    # a soda can is not a soup can; a place word before a kind
    ("slide the coke toward the white mug", "slide:closer can_1 mug_1", CLEANUP),
    ("push the soda can past the green cube", "push:past can_1 block_2", CLEANUP),
    ("move the soup can next to the box", "slide:next-to can_2 box_1", CLEANUP),
    ("move the back mug toward the soup can", "slide:closer mug_2 can_2", CLEANUP),
    ("slide the front mug next to the jello", "slide:next-to mug_1 box_1", CLEANUP),
    # a pace said before "make ... go" is kept
    ("Make slowly the red cube go to the box", "slide:closer block_1 box_1 pace=slow", CLEANUP),
    # a heading, a box called by what it is, hugging
    ("Target config: small_box next to the post", "slide:next-to small_box obstacle", TASK),
    ("push the big crate toward the goal", "push:closer big_box goal", TASK),
    ("slide the smaller carton past the post", "slide:past small_box obstacle", TASK),
    ("I need right_block hugging the post", "slide:next-to right_block obstacle extent=right", TASK),
    # "pass" before a preposition of passing; a clause with its extent and preposition alone is a step
    ("pass the soup can just beyond the green cube", "slide:past can_2 block_2 extent=little", CLEANUP),
    ("move the red cube past the box, then right next to the soup can",
     "slide:past block_1 box_1 ; slide:next-to block_1 can_2 extent=right", CLEANUP),
    ("carry the coke over beside the blue mug, if it isn't too much bother", "carry:next-to can_1 mug_2", CLEANUP),
    # a pace said in Spanish among English words
    ("despacio, slide the pelota toward la caja", "slide:closer pelota caja pace=slow", SPANISH),
    ("push la taza past the lata con cuidado", "push:past taza lata pace=careful", SPANISH),
    # what speech-to-text hears
    ("slide the lemon next two the bowel", "slide:next-to lemon bowl", FRUIT),
    ("move the apple a round the plate", "slide:around apple plate", FRUIT),
    ("push the green cube passed the bowl", "push:past cube bowl", FRUIT),
    ("slide the apple a way from the lemon", "slide:away apple lemon", FRUIT),
    ("slow Lee slide the plate toward the bowel", "slide:closer plate bowl pace=slow", FRUIT),
    # the verb said last
    ("The apple to the bowl push.", "push:closer apple bowl", FRUIT),
    ("Slowly the lemon past the plate bring, bitte.", "slide:past lemon plate pace=slow", FRUIT),
    ("The bowl must farther from the apple be.", "slide:away bowl apple", FRUIT),
])
def test_read(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence, table", [
    # a name and a place that pick two objects
    ("move the left block next to the goal", TASK),
    ("slide the right block past the obstacle", TASK),
    # the orange colour fits the fruit and the block
    ("move the orange thing past the plate", FRUIT),
    ("slide the lemon around the orange Würfel", FRUIT),
    # citrus: the orange or the lemon
    ("move the citrus next to the bowl", FRUIT),
    # a can said by neither its contents nor a place
    ("move the can next to the box", CLEANUP),
    # a word of proportions fits the cone and the tube alike: the clause before naming the cone does not choose it
    ("slide the scanner around the cone, then push the tube toward the tote", PARCELS),
    # a clause that names a thing is never read past as asking for nothing
    ("slide the cone past the scanner, then footy two", PARCELS),
])
def test_stays_refused(plugins, sentence, table):
    with pytest.raises(L2PError):
        read(sentence, plugins, table)
