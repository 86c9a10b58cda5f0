"""Ends said as wishes in more ways ("What I should like is for the saucer to be standing beside the lamp", "goal is
the ball ending up past the nut", "need Q clear of the lamp"), relations said as learners and hurried typists say them
("near of", "close to", "more far of", "out of the way of", "as close as possible to", "rly far from") and rows with
their order or their look said after them. Checked on sentences of each kind (not the corpora's own lines), and what
must stay refused."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

HOUSEHOLD = "heldout27.tsv"
"""A zucchini, a gamepad, a white lamp, a brown crate, a white saucer, orange cubes O (4 cm) and Q (5 cm)."""
LINE = "heldout29.tsv"
"""Red cubes A, B, C in a line across the front; D a blue cylinder, E a green bar, F a white 5 cm cube, G a yellow
3 cm cube."""


@pytest.mark.parametrize("sentence, expect", [
    ("What I'd really like, if possible, is for the crate to be sitting beside the saucer.",
     "slide:next-to crate saucer"),
    ("Ideally the lamp ends up sat beside the crate.", "slide:next-to lamp crate"),
    ("the saucer should come near to the gamepad", "slide:closer saucer gamepad"),
    ("goal is the crate ending up past the lamp", "slide:past crate lamp"),
    ("It would be lovely if the gamepad were to end up beside the saucer.", "slide:next-to gamepad saucer"),
    ("need O clear of the zucchini", "slide:away O zucchini"),
    ("get the crate out of the way of the lamp", "slide:away crate lamp"),
    ("Push Q as close as possible to the crate.", "push:next-to Q crate extent=right"),
    ("I want that the crate stays more far of the lamp", "slide:away crate lamp"),
    ("bring the saucer near of the lamp", "slide:closer saucer lamp"),
    ("move the lamp close to the crate", "slide:closer lamp crate"),
    ("put the saucer rly far from the crate", "slide:away saucer crate extent=far"),
    ("arrange the lamp, the crate and O in a line, in that order thanks", "row lamp,crate,O"),
    ("put the saucer, Q and the crate in a nice neat row", "row saucer,Q,crate"),
])
def test_said_otherwise(plugins, sentence, expect):
    assert read(sentence, plugins, HOUSEHOLD) == expect


@pytest.mark.parametrize("sentence, expect", [
    # a reason, a time or a restatement after the command is read past
    ("move G away from D, it keeps falling over", "slide:away G D"),
    ("push F closer to E so I can reach it", "push:closer F E"),
    ("put the cylinder beside the bar before my boss sees it", "slide:next-to D E"),
    ("slide G past F because it's in the way", "slide:past G F"),
    ("Final state: G on the far side of F, i.e. past it.", "slide:past G F"),
    # a group or an object shown first, by whoever is told to look
    ("Look at the red blocks. Push the one on the left end toward G.", "push:closer C G"),  # +y: the left
    ("Everyone see the white cube? Robot, move it past the bar.", "slide:past F E"),
    ("Watch the bar: move it around the cylinder.", "slide:around E D"),
    # more verbs of sliding, and "until they touch"
    ("tuck G right up against F", "slide:next-to G F extent=right"),
    ("pop the cylinder next to the bar", "slide:next-to D E"),
    ("keep pushing G toward F until they touch", "push:next-to G F extent=right"),
    ("slide G toward F until both of them are touching, if you could", "slide:next-to G F extent=right"),
    ("Push G right next to F, please, so they're touching.", "push:next-to G F extent=right"),
    ("move the cylinder, if you would, past the bar", "slide:past D E"),
    # a comparative's yardstick said as the table now; a row's kind said before its items; a pace said alone
    ("G should end up closer to F than it is now.", "slide:closer G F"),
    ("put in a line: F, G, D", "row F,G,D"),
    ("Arrange in a line, in this order: E, D, G.", "row E,D,G"),
    ("Move G past the bar. No hurry at all.", "slide:past G E pace=slow"),
    # touching said as the relation; a carry said by where the object goes, after a polite opening
    ("put G touching F", "slide:next-to G F extent=right"),
    ("goal: the cylinder touching the bar", "slide:next-to D E extent=right"),
    ("could you pick G up in the air and take it around F", "carry:around G F"),
    # learners' and everyday relations; a topic and where it goes; a plan said as what will happen
    ("slide G up to F", "slide:next-to G F"),
    ("put the cylinder to the side of the bar", "slide:next-to D E"),
    ("move G for the side of F", "slide:next-to G F"),
    ("push G for the other side of F", "push:past G F"),
    ("the bar, away from the cylinder.", "slide:away E D"),
    ("the bar.. push it toward the white cube", "push:closer E F"),
    ("The green rectangle is going to go past the cylinder.", "slide:past E D"),
])
def test_said_with_more_around_it(plugins, sentence, expect):
    assert read(sentence, plugins, LINE) == expect


@pytest.mark.parametrize("sentence", [
    "The lamp is close to the crate.",      # how the table is: nothing asked
    "put the crate close",                  # close to what
    "move the saucer near of",              # no object after the relation
    "Move O past Q without touching it",    # "touching" there is how it passes, not where it ends
    "move the saucer up to the left",       # a place, not an object
])
def test_what_stays_refused(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins, HOUSEHOLD)
