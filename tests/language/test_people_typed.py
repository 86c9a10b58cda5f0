"""Sentences as the fourth and fifth held-out authors typed them: each rule the misses of their first reading
prompted, checked on sentences of the kind (not the corpus's own lines), and the slips that must stay refused."""

from __future__ import annotations

import pytest
from corpus import notation, scene

from l2p_bullet.chain.clauses import resolve_clauses
from l2p_bullet.errors import L2PError
from l2p_bullet.language import typos
from l2p_bullet.plugins import registry


@pytest.fixture(scope="module")
def plugins():
    return registry.discover()


def read(sentence: str, plugins, name: str = "corpus.tsv") -> str:
    return notation(resolve_clauses(sentence, scene(name), plugins))


@pytest.mark.parametrize("sentence, expect", [
    # greetings and thanks as sentences of their own
    ("Good afternoon! Please push C past A. Many thanks.", "push:past C A"),
    ("hi there, move B around C pls", "slide:around B C"),
    # the end stated instead of the motion
    ("The aim is for the duck to end up next to A.", "slide:next-to duck A"),
    ("Make sure C ends up closer to the duck.", "slide:closer C duck"),
    ("Make it so that B is next to E.", "slide:next-to B E"),
    ("A should be pushed past C.", "push:past A C"),
    # a motion and then where it should end
    ("Push C toward A until it is next to it.", "push:next-to C A"),
    # objects shown first, "them both", "do the same"
    ("See the duck? Push it away from B.", "push:away duck B"),
    ("Pick up C. Put it next to the duck.", "carry:next-to C duck"),
    ("Take A and E and push them both toward C.", "push:closer A C ; push:closer E C"),
    ("Move A next to B. Now do the same with C.", "slide:next-to A B ; slide:next-to C B"),
    ("move C toward B, then past it", "slide:closer C B ; slide:past C B"),
    # manner words
    ("Slide, don't carry, A toward the duck.", "slide:closer A duck"),
    ("Move C around B without lifting it.", "slide:around C B"),
    ("take your time and push A past B", "push:past A B pace=slow"),
    ("move A further away from B", "slide:away A B"),
    ("move A much further away from B", "slide:away A B extent=far"),
    # slips of the keyboard
    ("pls mvoe the bleu cube past teh red one", "slide:past C A"),
    ("Slide the yelow box around B.", "slide:around D B"),
    ("Lift E, carry it past C, and set it down.", "carry:past E C"),
    ("Carry A around B, then set it down next to C.", "carry:around A B ; carry:next-to A C"),
    ("Carry A around B, then put it next to C.", "carry:around A B ; slide:next-to A C"),  # no "down": a slide
    ("Let's have C next to the duck.", "slide:next-to C duck"),
    ("Move B in a circle around C.", "slide:around B C"),
    # rows
    ("Make a row: A, C, B.", "row A,C,B"),
    ("line up a c b", "row A,C,B"),
])
def test_sentences_people_type_read_as_meant(plugins, sentence, expect):
    assert read(sentence, plugins) == expect


@pytest.mark.parametrize("sentence", [
    "Carry A past B without lifting it.",  # two manners at once
    "See the duck?",  # shows, asks for nothing
    "mvoe the cube past B",  # a slip mended, the description still fits three cubes
    "Move A next to B. Now do the same with B.",  # B cannot be moved next to itself
])
def test_what_a_person_would_ask_about_stays_refused(plugins, sentence):
    with pytest.raises(L2PError):
        resolve_clauses(sentence, scene(), plugins)


def test_a_slip_is_mended_only_to_the_one_word_it_is_near():
    known = frozenset({"move", "mode", "the", "red"})
    assert typos.near("teh", known) == "the"
    assert typos.near("mvoe", known) == "move"
    assert typos.near("mose", known) is None  # one keystroke from both move and mode: not guessed
    assert typos.near("rad", known) is None  # a replaced letter in a three-letter word is another word
    assert typos.mend("mvoe Teh box", known, ["box"]) == "move The box"
    assert typos.mend("move mvoe", known, ["mvoe"]) == "move mvoe"  # an object's name is never mended


def test_a_sentence_that_reads_as_typed_is_never_mended(plugins):
    """"move A past B" reads as typed; a mended reading is only tried after a refusal."""
    assert read("move A past B", plugins) == "slide:past A B"
