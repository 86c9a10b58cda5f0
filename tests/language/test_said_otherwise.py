"""Sentences said as the eighteenth to twenty-first authors said them: paces said as "no rush", two objects said to
be too close to a third and then "them", everyday names of a torus, a cone and a prism, "over to", a group said in
the plural and the one picked among it, how the table is now, and places too close to tell apart. Checked on
sentences of each kind (not the corpora's own lines), and what must stay refused."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

NEW_TABLE = "heldout18.tsv"
"""Cubes P (blue, 4 cm), Q (yellow, 4.5 cm) and W (blue, 3 cm), a torus named ring, a lego brick, a can, a cone."""


@pytest.mark.parametrize("sentence, expect", [
    ("no rush, slide A past B", "slide:past A B pace=slow"),
    ("Move A past B. No hurry.", "slide:past A B pace=slow"),
    ("don't rush - push A toward B", "push:closer A B pace=slow"),
    ("A and C are both too close to the duck. Move them away from it.", "slide:away A duck ; slide:away C duck"),
    ("A and C are too close to B. Push them away.", "push:away A B ; push:away C B"),
    ("See A and C? Move them away from B.", "slide:away A B ; slide:away C B"),
    ("bring A over to B", "slide:closer A B"),
    ("carry A over to the other side of B", "carry:past A B"),
    ("Move A over to next to B", "slide:next-to A B"),
    ("carry A to right next to B", "carry:next-to A B extent=right"),
    ("Push with your fingers A in direction of B", "push:closer A B"),
])
def test_said_on_the_corpus_table(plugins, sentence, expect):
    assert read(sentence, plugins) == expect


@pytest.mark.parametrize("sentence, expect", [
    ("slide the donut toward the can", "slide:closer ring can"),
    ("move the doughnut past P", "slide:past ring P"),
    ("push the traffic cone away from W", "push:away cone W"),
    ("move the pylon around the hoop", "slide:around cone ring"),
    ("put the red brick next to the can", "slide:next-to lego can"),
    ("move the biggest of the blue cubes past the can", "slide:past P can"),
    ("move the smallest of the three cubes around the lego", "slide:around W lego"),
    ("Of the two blue cubes, push the small one toward the cone", "push:closer W cone"),
    ("of the 2 blue cubes move the one nearer the robot past the can", "slide:past P can"),
    ("move the cube furthest to the right toward the can", "slide:closer P can"),
    ("Right now P is far from the can. Put it next to the can.", "slide:next-to P can"),
    ("Right now P is too close to the can. Move it away.", "slide:away P can"),
    ("push the small blue cube toward the big one", "push:closer W P"),
    ("move the big blue cube past the small one, then push the small one away from it",
     "slide:past P W ; push:away W P"),
    ("move the lego past the big one", "slide:past lego can"),
])
def test_said_on_a_new_table(plugins, sentence, expect):
    assert read(sentence, plugins, NEW_TABLE) == expect


def test_flat_is_the_clearly_lowest(plugins):
    """The tile is 1 cm high among 4-8 cm objects: "the flat thing"."""
    assert read("move the flat thing away from the mug", plugins, "heldout19.tsv") == "slide:away tile mug"


@pytest.mark.parametrize("sentence", [
    "A and C are too close to B. Move it away.",         # "it": A or C
    "move A over B",                                     # over: past it, or on top of it
    "of the 3 blue cubes move the small one past the can",  # there are two
    "move the leftmost cube past the can",               # Q and W are 2 cm apart sideways
    "Currently the ring is next to the cone.",           # how the table is, not a goal
])
def test_what_a_person_would_ask_about_stays_refused(plugins, sentence):
    table = "corpus.tsv" if sentence.startswith(("A ", "move A")) else NEW_TABLE
    with pytest.raises(L2PError):
        read(sentence, plugins, table)
