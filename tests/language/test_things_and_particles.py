"""A word WordNet knows as a thing is no slip of another thing's word nor of a pace ("the clock" is no block, "the soap"
no soup), a kind whose every sense among things is rare names nothing more general ("the franking machine" is no
rubber stamp), "glasses" are spectacles before they are two beakers, "up" between the mover and the phrase is read
past ("bring the needles up toward the yarn"), "first" at the end of a clause another follows says only the order
("move A next to B first, then ..."), "all" before the phrase or a list's row ("all around", "A, B and C all in a
line"), a "go" at the end that only starts the robot off, an object held up before it moves (a carry), a row's
objects after "the following" or "collinearly", "handsomely" is a sailor's slowly, a description's own noun is never
read past for what it is for ("the soap for dogs"), and a lenient reading never reads past a row's word ("arrange to
a line"). Checked on sentences of each kind (not the corpora's own lines)."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

BENCH = "heldout125.tsv"
"""loupe, tweezers, watch, parts_tray, oil_bottle, brush."""
LAB = "heldout126.tsv"
"""beaker, flask, tube_rack, burner, goggles, dropper_blue, dropper_amber."""
GROOMER = "heldout127.tsv"
"""dog_brush, treat_jar, leash, collar, shampoo, clipper."""
POST = "heldout128.tsv"
"""stamp, ink_pad, envelopes, parcel, tape_gun, scale."""
SANDPIT = "heldout104.tsv"
"""dino_green, dino_purple, robot_toy, bucket, spade, ball."""
SCANNING = "heldout46.tsv"
"""a warehouse bench with a scanner, a cone and totes."""


@pytest.mark.parametrize("sentence, expect, table", [
    # "up" between the mover and the phrase
    ("bring the oil bottle up toward the loupe", "slide:closer oil_bottle loupe", BENCH),
    ("slide the brush up beside the watch", "slide:next-to brush watch", BENCH),
    ("push the stamp up next to the ink pad", "push:next-to stamp ink_pad", POST),
    # "first" at the end of a clause says the order the clauses already have
    ("move the collar next to the leash first, then push the clipper past the shampoo",
     "slide:next-to collar leash ; push:past clipper shampoo", GROOMER),
    ("put the spade by the ball first and then carry the bucket around the robot",
     "slide:next-to spade ball ; carry:around bucket robot_toy", SANDPIT),
    ("slide the loupe away from the watch first of all. then push the brush past the tray",
     "slide:away loupe watch ; push:past brush parts_tray", BENCH),
    # "glasses" are spectacles: the goggles, where a beaker is a glass too
    ("put the glasses next to the burner", "slide:next-to goggles burner", LAB),
    # "all" before the phrase or a list's row, and a "go" that starts the robot off
    ("push the collar all around the leash", "push:around collar leash", GROOMER),
    ("put the stamp, the parcel and the scale all in a row", "row stamp,parcel,scale", POST),
    ("put them all in a line: the loupe, the watch, the brush", "row loupe,watch,brush", BENCH),
    ("brush past the watch, go", "slide:past brush watch", BENCH),
    # lifted, then left, dropped or popped somewhere: a carry; two taken and moved as "them": each moved
    ("pick up the watch and leave it next to the brush", "carry:next-to watch brush", BENCH),
    ("lift the stamp, pop it down beside the parcel", "carry:next-to stamp parcel", POST),
    ("take the collar and the leash and push them both toward the treat jar",
     "push:closer collar treat_jar ; push:closer leash treat_jar", GROOMER),
    # "in contact with" and "a good (long) way from" say how far; "become" links an object to where it should be
    ("put the leash in contact with the collar", "slide:next-to leash collar extent=right", GROOMER),
    ("move the parcel a good long way from the stamp", "slide:away parcel stamp extent=far", POST),
    ("make it so the brush becomes closer to the loupe", "slide:closer brush loupe", BENCH),
    # the two verbs run on without "and"; "them" for one object called in the plural ("the treats": the treat jar)
    ("pick up the watch carry it past the brush", "carry:past watch brush", BENCH),
    ("pick up the treats put them by the leash then push them toward the collar",
     "carry:next-to treat_jar leash ; push:closer treat_jar collar", GROOMER),
    ("move the treats next to the leash, then push them toward the collar",
     "slide:next-to treat_jar leash ; push:closer treat_jar collar", GROOMER),
    # held up before it moves: a carry
    ("hold the oil bottle up and take it around the tray", "carry:around oil_bottle parts_tray", BENCH),
    ("hold up the parcel, then bring it next to the scale", "carry:next-to parcel scale", POST),
    # a row's objects listed after "the following", in an order said more ways, "collinearly"
    ("please arrange the following items in a neat row: the leash, the collar, the clipper",
     "row leash,collar,clipper", GROOMER),
    ("put the stamp, the scale and the parcel in a line, in exactly that order", "row stamp,scale,parcel", POST),
    ("place the loupe, the tray and the brush collinearly", "row loupe,parts_tray,brush", BENCH),
    # how far, said after the place or alone after it: "like touching it"
    ("slide the stamp right next to the ink pad, like touching it", "slide:next-to stamp ink_pad extent=right", POST),
    ("put the collar by the leash. like actually touching it", "slide:next-to collar leash extent=right", GROOMER),
    # a sailor's "handsomely": slowly
    ("handsomely, bring the parcel closer to the scale", "slide:closer parcel scale pace=slow", POST),
])
def test_read(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence, table", [
    # a thing of its own is no slip of another word: nothing on the bench is a clock, nor a block by that name
    ("move the clock next to the loupe", BENCH),
    # soap is no soup, and "for dogs" says what it is for, not which object
    ("put the soap for dogs beside the leash", GROOMER),
    # the stamp's senses among things are all rare: no more general word ("machine") names it
    ("move the franking machine next to the scale", POST),
    ("move the machine away from the parcel", POST),
    # "the glass" is the beaker and the flask alike
    ("move the glass away from the burner", LAB),
    # "first" alone in a one-clause sentence is read as before
    ("put the cone, the scanner first", SCANNING),
    # a row's word is never read past: this is no move of the cone to the scanner
    ("the cone, the tote, arrange to a line, the cone first", SCANNING),
])
def test_refused(plugins, sentence, table):
    with pytest.raises(L2PError):
        read(sentence, plugins, table)
