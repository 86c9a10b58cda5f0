"""Rows said in other words: a group named first and its items after, "in a neat row", "line ... up in a row", "the
following objects: ...", "row up", "make row", "form / build a line with / outta", "in the order I've said them", and
the joins "thereafter" and ", after" before a verb; the rules the tenth to thirteenth authors' misses prompted,
checked on sentences of each kind (not the corpora's own lines)."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError


@pytest.mark.parametrize("sentence, expect", [
    ("Put the three cubes in a row: blue, red, green.", "row C,A,B"),
    ("line up the cubes - green, blue, red - then move the duck past A", "row B,C,A ; slide:past duck A"),
    ("Line the cubes up in this order: red, green, blue.", "row A,B,C"),
    ("row up the two cubes, red and blue", "row A,C"),
    ("Arrange the duck, A and E in a tidy row.", "row duck,A,E"),
    ("Please line A, C and the duck up in a row, then push B past E.", "row A,C,duck ; push:past B E"),
    ("make a row out of the following three objects: the duck, the red cube, the yellow box", "row duck,A,D"),
    ("make row: duck, red cube, blue cube", "row duck,A,C"),
    ("Put A, B and C in a single line; thereafter, move the duck away from E.", "row A,B,C ; slide:away duck E"),
    ("Make a row of A, B and C, after push the duck past E.", "row A,B,C ; push:past duck E"),
    ("Form a straight line of the duck, A and E.", "row duck,A,E"),
    ("build a row with A, C and the duck, then push B past E", "row A,C,duck ; push:past B E"),
    ("make a line outta E, A, C", "row E,A,C"),
    ("line A, the duck and C up in a row, in the order I've said them", "row A,duck,C"),
    ("I'd like E, the duck and A lined up, please", "row E,duck,A"),  # a row wished for
    ("we want A, C and E in a row, then move the duck past B", "row A,C,E ; slide:past duck B"),
    ("put in line E, C and A, after move the duck past B", "row E,C,A ; slide:past duck B"),  # "in line", a learner's
    ("line up C, A and E in a nice little row", "row C,A,E"),
    ("E, the duck, A - line them up", "row E,duck,A"),  # named first, then lined up as "them"
    ("take A, C and E and put them in a row", "row A,C,E"),
])
def test_rows_said_in_other_words(plugins, sentence, expect):
    assert read(sentence, plugins) == expect


@pytest.mark.parametrize("sentence", [
    "Put the two cubes in a row: red, blue, green.",   # three items for "the two cubes"
    "Put the three cubes in a row: red, blue, pink.",  # no pink cube
    "move A past B, after the duck",                   # "after" before an object joins nothing
])
def test_what_a_person_would_ask_about_stays_refused(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins)


@pytest.mark.parametrize("sentence, expect", [
    ("Put the three cubes in a row: the blue one, the red one and the green one.", "row C,A,B"),
    ("Put the three cubes in a row: the green one, then the red one, then the blue one. After that, move the duck "
     "past E.", "row B,A,C ; slide:past duck E"),
    ("Line up A, the duck and C, in that order - then move B next to E.", "row A,duck,C ; slide:next-to B E"),
])
def test_rows_told_item_by_item_after_a_group(plugins, sentence, expect):
    assert read(sentence, plugins) == expect


def test_a_row_told_item_by_item_after_its_own_word(plugins):
    assert read("Row please: the duck, then A, then C.", plugins) == "row duck,A,C"
