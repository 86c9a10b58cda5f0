"""A person correcting themselves mid-sentence ("- no sorry, toward W", "- sorry, I mean the duck -", "not the red cube,
the blue one - ..."): what they meant is read; a sentence that does not say it corrects itself is still asked about."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError


@pytest.mark.parametrize("sentence, expect", [
    ("move A toward B - no sorry, toward C", "slide:closer A C"),
    ("Move A past B, oops I mean past the duck.", "slide:past A duck"),
    ("Move the red cube \u2014 sorry, I mean the blue one \u2014 past the duck.", "slide:past C duck"),
    ("Move A next to B - sorry, make that the duck", "slide:next-to A duck"),
    ("not the red cube, the blue one - push that one around B", "push:around C B"),
    ("Not A, it's C I mean - move it away from the duck.", "slide:away C duck"),
])
def test_corrections_read_as_meant(plugins, sentence, expect):
    assert read(sentence, plugins) == expect


@pytest.mark.parametrize("sentence", [
    "Move A past B, sorry for the trouble",      # "sorry" corrects nothing: ... asked
    "not A, A - move it past B",                 # the same object ruled out and meant
])
def test_what_is_not_said_as_a_correction_is_asked(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins)
