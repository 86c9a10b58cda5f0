"""Sentences around the command: ones that ask for nothing ("Here's the situation.", "go"), ones that point at an
object ("I don't like where the duck is.", "The duck's too close to A."), and ends stated ("Expected result: ...",
"A ought to be further from B"); the rules the tenth to thirteenth authors' misses prompted, checked on sentences of
each kind (not the corpora's own lines), and what must stay refused."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError


@pytest.mark.parametrize("sentence, expect", [
    ("Here's the situation. The duck is crowding A. Move it away from B.", "slide:away duck B"),
    ("Let me explain. Push C past B.", "push:past C B"),
    ("end state: A next to B. go", "slide:next-to A B"),
    ("Move C around B. Can you manage that?", "slide:around C B"),
    ("I don't like where the duck is. Move it closer to C.", "slide:closer duck C"),
    ("The duck's too close to B. Could you move the duck away from it?", "slide:away duck B"),
    ("Expected result: A adjacent to the duck.", "slide:next-to A duck"),
    ("Desired outcome: C beside B", "slide:next-to C B"),
    ("C ought to be further from the duck. Would you see to that?", "slide:away C duck"),
])
def test_sentences_around_the_command(plugins, sentence, expect):
    assert read(sentence, plugins) == expect


@pytest.mark.parametrize("sentence", [
    "Move A past B. No, wait.",                 # a correction: asked, never read past
    "Move A past B. Then do that again.",       # a repeat asked for: not dropped as politeness
    "Move A past B. Then move it.",             # an unfinished command
    "Move A past B. Do it slowly.",             # a pace for a move already read
    "Here's the situation. Move it past B.",    # "it" points at nothing
    "Move A past B. 3 times.",                  # a number
])
def test_what_a_person_would_ask_about_stays_refused(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins)


@pytest.mark.parametrize("sentence, expect", [
    ("Hurry!! slide A closer to B", "slide:closer A B pace=fast"),
    ("Slide A closer to B. Slowly please.", "slide:closer A B pace=slow"),
    ("Push A past B, and take your time.", "push:past A B pace=slow"),
    ("Move D next to C, and then push that cube away from B.", "slide:next-to D C ; push:away C B"),
])
def test_paces_said_apart_and_that_cube(plugins, sentence, expect):
    assert read(sentence, plugins) == expect


def test_the_big_one_after_its_small_twin(plugins):
    assert read("Move the small red cube past the teddy, then slide the big one away from the can.", plugins,
                "heldout10.tsv") == "slide:past P teddy ; slide:away R can"


@pytest.mark.parametrize("sentence", [
    "Quickly! Move A slowly past B",                      # two paces
    "Move A closer to the duck and away from the duck.",  # two ends at once
])
def test_paces_and_ends_that_contradict_are_asked(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins)


@pytest.mark.parametrize("sentence, expect, table", [
    # what the sixteenth and seventeenth authors' misses prompted
    ("Move C away from the duck. Just a tiny bit though.", "slide:away C duck extent=little", "corpus.tsv"),
    ("move the duck past A? appreciate it", "slide:past duck A", "corpus.tsv"),
    ("push A closer to the duck, then C, same thing", "push:closer A duck ; push:closer C duck", "corpus.tsv"),
    ("the duck - carry him around B", "carry:around duck B", "corpus.tsv"),
    ("ok so the duck... move it all the way around B", "slide:around duck B", "corpus.tsv"),
    ("push C so it moves next to A", "push:next-to C A", "corpus.tsv"),
    ("move front white cube next to L", "slide:next-to K L", "heldout17.tsv"),
    ("Put in a line the duck, A and C.", "row duck,A,C", "corpus.tsv"),
    ("Row please: C, the duck, A.", "row C,duck,A", "corpus.tsv"),
    ("Put the three cubes in a row, green first, then red, then blue.", "row B,A,C", "corpus.tsv"),
    ("Move the duck past E, line up the three cubes (blue, red, green), then push D toward E.",
     "slide:past duck E ; row C,A,B ; push:closer D E", "corpus.tsv"),
    ("Move E away from the duck, after make a row with A, B and C.", "slide:away E duck ; row A,B,C", "corpus.tsv"),
])
def test_what_the_sixteenth_and_seventeenth_authors_prompted(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence", [
    "Move C around the duck. Just a tiny bit though.",   # "around" takes no extent
    "Move C far away from the duck. Just a tiny bit.",   # far, then a little
    "Put the two cubes in a row, green first, then red, then blue.",  # three items for two
])
def test_what_the_sixteenth_and_seventeenth_authors_prompted_still_asks(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins)
