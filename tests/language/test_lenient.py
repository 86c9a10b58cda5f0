"""The lenient reading (language/lenient.py): a command found among words the grammar does not know, tried only
after every other reading refused, and refused itself wherever a word read past could change the meaning."""

from __future__ import annotations

import pytest
from corpus import read, scene

from l2p_bullet.errors import L2PError
from l2p_bullet.language import lenient, parse
from l2p_bullet.plugins import registry


@pytest.mark.parametrize("sentence, expect", [
    # a manner said in passing, between the verb and the object
    ("Push with the fingers A around B, slow please.", "push:around A B pace=slow"),
    # the object described with words the grammar lacks, the command wrapped in a wish
    ("My hope is the rubber duck sitting on the other side of C.", "slide:past duck C"),
    ("the duck should be like, away from B", "slide:away duck B"),
    # a pace said as an adjective at the end
    ("carry A around B, careful", "carry:around A B pace=careful"),
])
def test_a_command_among_unknown_words_is_read(plugins, sentence, expect):
    assert read(sentence, plugins) == expect


@pytest.mark.parametrize("sentence", [
    "Push A, not B, toward C.",                     # a negation may pick another object
    "could you move A toward B - or rather C",      # a correction not said as one ("sorry", "no wait")
    "Please, can you pass A by B?",                 # "by": beside or past, and "pass" says which
    "Slide A over toward B so they touch.",         # "touch" asks for a tight gap
    "I noticed the duck standing next to C yesterday.",  # a statement asks for nothing
    "Yesterday the duck was next to C, I noticed.",
    "move the fat purple thing A toward C",         # a colour read past would have named E
    "grab A and B with care and put the things toward C",  # two objects before the phrase
    "move A toward B, then",                        # a join left over
    "push A 3 cm toward B",                         # a number the actions cannot take
])
def test_words_that_could_change_the_meaning_stop_it(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins)


def test_it_is_tried_only_after_the_grammar_refused(plugins):
    """parse() alone refuses what the lenient reading reads: it is allowed only inside reading_past, which
    resolve_clauses enters last, so a sentence the grammar reads is read as it always was."""
    s = scene("corpus.tsv")
    phrases = registry.phrase_table(plugins)
    with pytest.raises(L2PError):
        parse("the duck should be like, away from B", s, phrases)
    assert not lenient.allowed()
    with lenient.reading_past():
        assert lenient.allowed()
        cmd = parse("the duck should be like, away from B", s, phrases)
    assert (cmd.manner, cmd.mover, cmd.action, cmd.anchor) == ("slide", "duck", "away", "B")
    assert not lenient.allowed()
