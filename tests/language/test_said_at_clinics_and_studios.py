"""Sentences as the hundred and thirty-third and fourth authors typed them (a veterinary exam table, a photographer's
desk): each rule the misses of their first reading prompted, checked on sentences of the kind (not the corpora's own
lines), and what must stay refused."""

from __future__ import annotations

import pytest
from corpus import REFUSE, read, resolve, scene

CLINIC, STUDIO = "heldout133.tsv", "heldout134.tsv"


@pytest.mark.parametrize("sentence, expect, table", [
    # one shape's objects of alike outlines told apart by their height (the 85 mm lens is 7 cm tall, the 50 mm 5 cm)
    ("push the small lens away from the flash", "push:away lens_50mm flash", STUDIO),
    ("carry the taller lens around the blower", "carry:around lens_85mm blower", STUDIO),
    ("slide the biggest lens past the card", "slide:past lens_85mm sd_card", STUDIO),
    # "back to it", "to it as well" after a clause
    ("slide the flash past the blower, then bring the card back to it",
     "slide:past flash blower ; slide:closer sd_card flash", STUDIO),
    ("move the card to the flash then the battery to it aswell",
     "slide:closer sd_card flash ; slide:closer battery_1 flash", STUDIO),
    # a declared kind's words turned about with "of"
    ("push the card of memory toward the blower", "push:closer sd_card blower", STUDIO),
    # a doubt said after the command
    ("slide the blower past the flash. It might be empty, not sure.", "slide:past blower flash", STUDIO),
    # "shall", and a wish ending in its verb
    ("the battery shall go next to the card", "slide:next-to battery_1 sd_card", STUDIO),
    ("the blower shall beside the flash stand", "slide:next-to blower flash", STUDIO),
    # rows said without a verb, or lined up as "them" before the list
    ("row of the flash, the card and the blower", "row flash,sd_card,blower", STUDIO),
    ("row of three: flash, card, blower", "row flash,sd_card,blower", STUDIO),
    ("line em up, flash, card, blower", "row flash,sd_card,blower", STUDIO),
    # "make pass ... beyond", a manner's noun after "with", a speed
    ("make pass the card beyond the flash", "slide:past sd_card flash", STUDIO),
    ("with gentleness push the card toward the flash", "push:closer sd_card flash pace=gentle", STUDIO),
    ("push the card past the flash at full speed", "push:past sd_card flash pace=fast", STUDIO),
    # "a small bit" as a little extent, an object shown with the care it asks for
    ("slide the card a small bit closer to the flash", "slide:closer sd_card flash extent=little", STUDIO),
    ("careful with the blower, push it past the flash", "push:past blower flash pace=careful", STUDIO),
    # a group said by its kind's plural before the clause that picks among it, never skipped
    ("the lenses, move the smaller one beside the camera", "slide:next-to lens_50mm camera_body", STUDIO),
    ("the lenses: push the bigger one toward the flash", "push:closer lens_85mm flash", STUDIO),
    # a depth and a side said with "side" after it: a corner
    ("move the thing at the back on the left side next to the flash", "slide:next-to lens_50mm flash", STUDIO),
    # a relation over a shape noun that names one object by its kind: among the boxes
    ("slide the frontmost box toward the bandage", "slide:closer thermometer bandage_blue", CLINIC),
])
def test_said_as_the_authors_said_it(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence, table", [
    ("move the biggest one next to the lime", "heldout109.tsv"),  # a wide low shaker, a tall thin bottle: a tie
    ("row of four: flash, card, blower", STUDIO),  # the count says another number
    ("make pass the card by the flash", STUDIO),  # "by" may be beside
    ("move the bigger pill bottle past the jar", CLINIC),  # two alike bottles, outline and height
    ("the pill bottles, move the bigger one past the jar", CLINIC),  # the group said first: alike still
])
def test_still_refused(plugins, sentence, table):
    assert resolve(sentence, scene(table), plugins) == REFUSE
