"""Two objects moved alike in one clause: named together where the mover stands, the order said at the end, or
"the same" / "too" after a clause; the rules the tenth to thirteenth authors' misses prompted, checked on sentences
of each kind (not the corpora's own lines), and what must stay refused."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError


@pytest.mark.parametrize("sentence, expect", [
    ("Move both A and C closer to the duck.", "slide:closer A duck ; slide:closer C duck"),
    ("push the red cube and the blue cube away from B", "push:away A B ; push:away C B"),
    ("A + C -> both around B", "slide:around A B ; slide:around C B"),
    ("Move A and C past B, the blue one first.", "slide:past C B ; slide:past A B"),
    ("Move A and C past B, C first", "slide:past C B ; slide:past A B"),
    ("carry A and C next to the duck, first the blue, then the red", "carry:next-to C duck ; carry:next-to A duck"),
    ("Take A and C and move each of them past B, the red one first.", "slide:past A B ; slide:past C B"),
    ("Move A around B, and the duck too.", "slide:around A B ; slide:around duck B"),
    ("move A around B, then same for C", "slide:around A B ; slide:around C B"),
    ("Push A toward B, then do same with C.", "push:closer A B ; push:closer C B"),
])
def test_two_objects_moved_alike(plugins, sentence, expect):
    assert read(sentence, plugins) == expect


@pytest.mark.parametrize("sentence", [
    "Move A and C past B, the green one first.",   # B is not one of the two moved
    "Move A and B past B.",                        # B cannot be moved past itself
    "Move A around B, and B too.",                 # B is what A moved around
    "Move A and the cube closer to the duck.",     # "the cube" is one of three
])
def test_what_a_person_would_ask_about_stays_refused(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins)


@pytest.mark.parametrize("sentence, expect", [
    ("A and C: move the first one past B and the second one next to the duck",
     "slide:past A B ; slide:next-to C duck"),
    ("the duck and A: the first one goes around B, the second one goes past E", "slide:around duck B ; slide:past A E"),
    ("Push the blue cube, not the red one, toward the duck.", "push:closer C duck"),
])
def test_two_objects_shown_then_each_named(plugins, sentence, expect):
    assert read(sentence, plugins) == expect


@pytest.mark.parametrize("sentence", [
    "A and C: move the first one past B and the second one away from it",  # "it": B, or A?
    "Push the blue cube, not the blue cube, toward the duck.",             # rules out what it moves
])
def test_what_is_asked_about_when_shown_then_named(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins)


@pytest.mark.parametrize("sentence, expect", [
    ("Move A and C, both of them, closer to the duck.", "slide:closer A duck ; slide:closer C duck"),
    ("move both cubes A and C past B", "slide:past A B ; slide:past C B"),
    ("A and C go next to the duck, C first and then A", "slide:next-to C duck ; slide:next-to A duck"),
])
def test_two_objects_said_otherwise(plugins, sentence, expect):
    assert read(sentence, plugins) == expect
