"""A remark or a statement after the command (language/remarks.py): dropped only on the last try, and only where none of
its words could change what the command means. And what a topic said first is refused for, when it does not resolve."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError, UnknownObjectError
from l2p_bullet.language import remarks

TEA = "heldout93.tsv"  # kettle, teapot, sugar_jar, spoon, biscuit_tin, coaster, milk_jug
FRUIT = "heldout78.tsv"


@pytest.mark.parametrize("sentence, expect", [
    ("would you ever move the jug over next to the pot, thanks a million", "slide:next-to milk_jug teapot"),
    ("teapot should be next to coaster, that is the requirement", "slide:next-to teapot coaster"),
    ("move the jug next to the pot, good lad", "slide:next-to milk_jug teapot"),
    ("move the spoon past the kettle - it drips, honestly", "slide:past spoon kettle"),
    ("shift the tin away from the jug, its kinda in the way", "slide:away biscuit_tin milk_jug"),
])
def test_a_remark_after_the_command_is_read_past(plugins, sentence, expect):
    assert read(sentence, plugins, TEA) == expect


@pytest.mark.parametrize("name, sentence", [
    (TEA, "move the jug next to the pot, not the kettle"),  # a correction
    (TEA, "move the jug next to the pot, then the spoon"),  # another command
    (TEA, "move the jug next to the pot, the other way round"),  # points at another place
    (TEA, "move the jug past the pot, a fair way"),  # an extent
    (TEA, "move the jug past the pot, taking your time with it"),  # a pace said in a phrase
    (FRUIT, "line up: the lemon, the lime, the zorblax"),  # a list's last item is no remark
])
def test_a_part_that_could_change_the_meaning_is_never_dropped(plugins, name, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins, name)


def test_remarks_are_dropped_from_the_end_one_part_at_a_time():
    said = "move A next to B, it drips, honestly"
    assert remarks.without_remarks(said, frozenset({"a", "b", "move", "next"})) == [
        "move A next to B, it drips", "move A next to B"]
    # "in the way" is said of the object, never how far; "way" elsewhere may be ("a long way", "way past")
    assert remarks.without_remarks("move A past B, it's only in the way", frozenset()) == ["move A past B"]
    assert remarks.without_remarks("move A past B, a long way", frozenset()) == []
    assert remarks.without_remarks("move A past B, way past", frozenset({"past"})) == []
    assert remarks.without_remarks("move A next to B, C too", frozenset({"c"})) == []


@pytest.mark.parametrize("name, sentence, said", [
    ("heldout44.tsv", "the red thing nearest you, move it away from the green cube", '"nearest" is ambiguous'),
    (TEA, "the item which is farthest from you, kindly keep it near to spoon", '"farthest" is ambiguous'),
    (TEA, "the tallest thing on the tray, put it away from the pot", 'no block called "the tallest thing on the tray"'),
    ("heldout128.tsv", "the thing nearest the parcel move it past the scale", '"nearest" is ambiguous'),
])
def test_a_topic_that_does_not_resolve_is_refused_for_its_own_reason(plugins, name, sentence, said):
    """An object said first and taken up by "it" whose description resolves to none or to two: the refusal names the
    description's own trouble, never the grammar's "'the' is not a verb"."""
    with pytest.raises(L2PError) as refused:
        read(sentence, plugins, name)
    assert said in str(refused.value) and "not a verb" not in str(refused.value)


@pytest.mark.parametrize("sentence, missing", [
    ("the scale, move it next to the letters", "the letters"),
    ("the gray thing, move it next to the letters", "the letters"),
    ("the stamp - slide it past the mailbox", "the mailbox"),
    ("the scale move it next to the letters", "the letters"),  # no comma: a known verb and "it" after the topic
])
def test_a_topic_that_resolves_is_refused_for_the_object_its_command_names_and_the_table_lacks(plugins, sentence,
                                                                                                  missing):
    """The topic names an object and "it" takes it up; the command after it names one the table does not hold: the
    refusal says which (a word ``perform --ask`` can ask about), never the grammar's "'the' is not a verb"."""
    with pytest.raises(UnknownObjectError) as refused:
        read(sentence, plugins, "heldout128.tsv")  # stamp, ink_pad, envelopes, parcel, tape_gun, scale
    assert f'no block called "{missing}"' in str(refused.value) and "not a verb" not in str(refused.value)


def test_a_topic_whose_command_names_objects_on_the_table_is_read(plugins):
    assert read("the gray thing, move it next to the envelopes", plugins, "heldout128.tsv") == (
        "slide:next-to scale envelopes")


BENCH = "heldout125.tsv"  # loupe, tweezers, watch, parts_tray, oil_bottle, brush


@pytest.mark.parametrize("sentence, expect", [
    ("slide the brush toward the watch; the watch is an old one.", "slide:closer brush watch"),
    ("Carry the oil bottle past the loupe - the bottle might leak.", "carry:past oil_bottle loupe"),
    ("move the loupe next to the watch. Expected: loupe adjacent watch.", "slide:next-to loupe watch"),
])
def test_a_statement_after_the_command_is_read_past(plugins, sentence, expect):
    """A sentence after the command that only states how things are, or the step's expected outcome, asks for
    nothing more: read past on the last try."""
    assert read(sentence, plugins, BENCH) == expect


@pytest.mark.parametrize("sentence", [
    "move the loupe next to the watch. it is the brush that matters",  # names another object: which was meant?
    "move the loupe next to the watch. Expected: brush adjacent watch.",  # expects another object moved
    "move the loupe next to the watch; it should be right up against it",  # says how far
    "move the loupe next to the watch. the brush is next",  # another command, said as a state
])
def test_a_statement_that_could_change_the_command_is_kept(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins, BENCH)
