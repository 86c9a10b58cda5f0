"""Sentences of shelves and desks as people type them: a name written as one compound word said by its last noun ("the
brush" for the toothbrush, "my paste", "the black book" for the sketchbook), brands and British words ("the Colgate",
"the rubber"), a dataset's numbered names ("the box" is the cracker box, not the banana modelled as one), names
heard amiss ("the racer" for the razor, "the water char"), a label said by its letter and number ("p2"), a list laid
out in a line; and the readings that must not be made: "it" moved while a description means its own block, two
commands read as one across a comma, "the other one" where a third twin stands. Checked on sentences of each kind (not
the corpora's own lines), and what must stay refused."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

LAB = "heldout73.tsv"
"""003_cracker_box, 005_tomato_soup_can, 011_banana, 024_bowl, 025_mug, 037_scissors (YCB names; four are red)."""
BATHROOM = "heldout74.tsv"
"""toothbrush, toothpaste, razor (black), shampoo, soap_dish, comb (black)."""
ART = "heldout75.tsv"
"""paintbrush, water_jar, palette, paint_tube, sketchbook, eraser."""
OFFICE = "heldout76.tsv"
"""pen_1, pen_2, pen_3 (three alike black pens), notepad, stapler, mug."""


@pytest.mark.parametrize("sentence, expect, table", [
    # a compound name's last noun
    ("slide the brush away from the comb", "slide:away toothbrush comb", BATHROOM),
    ("put my paste by the shampoo", "slide:next-to toothpaste shampoo", BATHROOM),
    ("move the brush past the palette", "slide:past paintbrush palette", ART),
    ("push the black book toward the jar", "push:closer sketchbook water_jar", ART),
    # brands and British words
    ("move the Colgate next to the comb", "slide:next-to toothpaste comb", BATHROOM),
    ("put the Gillette away from the soap dish", "slide:away razor soap_dish", BATHROOM),
    ("slide the rubber around the palette", "slide:around eraser palette", ART),
    ("move the swingline closer to the mug", "slide:closer stapler mug", OFFICE),
    # a dataset's names: the box is the one named so
    ("put the banana next to the box", "slide:next-to 011_banana 003_cracker_box", LAB),
    ("put the banana past the can, then bring it back next to the box",
     "slide:past 011_banana 005_tomato_soup_can ; slide:next-to 011_banana 003_cracker_box", LAB),
    # heard amiss
    ("move the racer next to the comb", "slide:next-to razor comb", BATHROOM),
    ("put my razor by the shampoo", "slide:next-to razor shampoo", BATHROOM),
    ("move the water char next to the brush", "slide:next-to water_jar paintbrush", ART),
    # a label by its letter and number
    ("move p2 closer to p1", "slide:closer pen_2 pen_1", OFFICE),
    ("put P3 beside the stapler", "slide:next-to pen_3 stapler", OFFICE),
    # laid out in a line
    ("Lay out the sketchpad, the palette and the water pot in a line.", "row sketchbook,palette,water_jar", ART),
    # "them" for a thing called by a plural: the scissors, not the two blocks moved
    ("move the soup away from the scissors, then push the box back toward them",
     "slide:away 005_tomato_soup_can 037_scissors ; push:closer 003_cracker_box 037_scissors", LAB),
    # "it" moved, the other words naming their own block: "it" is the other one of the clause before
    ("put the razor next to the comb, then move it away from the razor",
     "slide:next-to razor comb ; slide:away comb razor", BATHROOM),
])
def test_read(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence, table", [
    # "it" is the comb moved; "the black one" is the comb or the razor: never the soap dish moved instead
    ("put the comb past the soap dish, then move it next to the black one", BATHROOM),
    # two commands across a comma, the first naming nothing on the table: not "away from the comb"
    ("shampoo away from the edge, comb beside razor", BATHROOM),
    # "the other one" after two of three alike pens: the one named before, or the third
    ("move p2 closer to p1, then move the other one closer to the mug", OFFICE),
    ("move pen 2 closer to pen 1, then move the other one closer to the mug", OFFICE),
    # four red things: "the red one" is asked
    ("move the red one next to the banana", LAB),
    # no racer on a table with a ring: "the orange" is a colour, never the ring heard so
    ("Move the orange thing next to the lego.", "heldout18.tsv"),
])
def test_stays_refused(plugins, sentence, table):
    with pytest.raises(L2PError):
        read(sentence, plugins, table)


def test_a_noun_two_compound_names_end_with_is_asked(plugins):
    """A toothbrush and a paintbrush: "the brush" is either; each by its whole name is itself."""
    from l2p_bullet.chain.clauses import resolve_clauses
    from l2p_bullet.core.scene import Scene, SceneObject

    scene = Scene([SceneObject("toothbrush", "blue", 0.03, (-0.10, 0.08)),
                   SceneObject("paintbrush", "brown", 0.03, (0.10, 0.10)),
                   SceneObject("sketchbook", "black", 0.05, (0.0, -0.12))]).validate()
    with pytest.raises(L2PError, match="ambiguous"):
        resolve_clauses("move the brush next to the book", scene, plugins)
    [clause] = resolve_clauses("move the paintbrush next to the book", scene, plugins)
    assert (clause.command.mover, clause.command.anchor) == ("paintbrush", "sketchbook")
