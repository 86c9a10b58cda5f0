"""Alphabet blocks named by one letter, called as people say letters aloud ("the letter eye", "the oh", "toward ay"),
a toy named by its kind that "block" does not pick where a plain block is there too, and the framings a teacher and
children use. Checked on sentences of each kind (not the corpora's own lines), and on what must stay refused."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.errors import L2PError
from l2p_bullet.language.references import resolve_object

LETTERS = "heldout48.tsv"
"""Alphabet blocks A (red, 5 cm), I (yellow), O (blue), X (red, 4 cm), a green bucket, a yellow toy truck (a box)."""


@pytest.mark.parametrize("sentence, expect", [
    # a letter said as a word: after "the letter", after "the", or as the whole reference
    ("push the letter ex toward the truck", "push:closer X truck"),
    ("slide letter oh around the bucket", "slide:around O bucket"),
    ("move the bucket next to the eye", "slide:next-to bucket I"),
    ("carry ex past the bucket", "carry:past X bucket"),
    ("move the truck closer to eye", "slide:closer truck I"),
    ("shove ay toward the truck", "push:closer A truck"),
    ("slide the big letter A away from the bucket", "slide:away A bucket"),
    ("move block ex next to the truck", "slide:next-to X truck"),
])
def test_a_letter_said_aloud(sentence: str, expect: str, plugins) -> None:
    assert read(sentence, plugins, LETTERS) == expect


@pytest.mark.parametrize("sentence", [
    "move the truck next to you",  # "you" is the robot, never U
    "move the bucket next to em",  # "em" is them as typed
    "put the red block by the truck",  # A and X are both red blocks
    "move the yellow one past the bucket",  # the cube and the truck are both yellow
])
def test_what_stays_refused(sentence: str, plugins) -> None:
    with pytest.raises(L2PError):
        read(sentence, plugins, LETTERS)


@pytest.mark.parametrize("sentence, expect", [
    # the letter on a block, said as written or aloud
    ("push the blue one with the O on it past the truck", "push:past O truck"),
    ("move the red block with an ex toward the bucket", "slide:closer X bucket"),
    ("slide the block with the letter eye on it next to the truck", "slide:next-to I truck"),
    # "the a block": no second article after "the"
    ("carry the a block around the bucket", "carry:around A bucket"),
    ("move the i one next to the truck", "slide:next-to I truck"),
    # lists of letters: said aloud without commas, a group's letters after a colon, the alphabet's order
    ("line up ex oh and ay", "row X,O,A"),
    ("put the blocks in a line: o, i, x", "row O,I,X"),
    ("make a row of the truck, the bucket and the blue block with the O", "row truck,bucket,O"),
    ("line up the letters in alphabetical order", "row A,I,O,X"),
    ("could we put the four letter blocks in a row in ABC order", "row A,I,O,X"),
])
def test_letters_on_blocks_and_in_lists(sentence: str, expect: str, plugins) -> None:
    assert read(sentence, plugins, LETTERS) == expect


@pytest.mark.parametrize("sentence, expect", [
    # whom a teacher speaks to, before or after the command; "we" asked as "let's"
    ("Kids, push the truck past the bucket, then move the letter A toward it.",
     "push:past truck bucket ; slide:closer A truck"),
    ("Could we slide block O around the truck, everyone?", "slide:around O truck"),
    ("let's take our time and push the A block toward the truck", "push:closer A truck pace=slow"),
    # "now" joining steps
    ("slide the truck toward A, now push it past the bucket, and now move it next to O",
     "slide:closer truck A ; push:past truck bucket ; slide:next-to truck O"),
    # a step told as what the mover does ("it goes"), and "back" to somewhere
    ("push O past the truck, then it moves around the bucket, then back next to A",
     "push:past O truck ; push:around O bucket ; push:next-to O A"),
    # over an object to its other side; a carry through the air told with its pace on the way
    ("carry the truck over the bucket to the far side", "carry:past truck bucket"),
    ("lift the X block through the air, slowly, and put it down beside the truck", "carry:next-to X truck pace=slow"),
    # how the wished-for block rests; "barely"; the farthest "away from"; the very back; texting's "rn"
    ("i want the truck parked beside the bucket", "slide:next-to truck bucket"),
    ("push the O block barely past the truck", "push:past O truck extent=little"),
    ("move the block furthest away from the truck toward the bucket", "slide:closer A bucket"),
    ("take the block at the very back past the bucket", "slide:past O bucket"),
    ("move A next to the truck rn", "slide:next-to A truck"),
    # a toy truck driven; a pail is a bucket
    ("drive the truck around the pail", "slide:around truck bucket"),
])
def test_a_teachers_and_childrens_framings(sentence: str, expect: str, plugins) -> None:
    assert read(sentence, plugins, LETTERS) == expect


@pytest.mark.parametrize("sentence", [
    "move the blue block with the X on it toward the truck",  # X is red: the words disagree
    "put the yellow blocks in ABC order",  # no letter group named
    "line up the three letter blocks in ABC order",  # there are four
    "move a block next to the truck",  # "a block" is any of them
])
def test_letters_that_stay_refused(sentence: str, plugins) -> None:
    with pytest.raises(L2PError):
        read(sentence, plugins, LETTERS)


def _toys() -> Scene:
    """A yellow cube U, a yellow box named "van", a yellow slab (a block by its kind), a grey tray alone in grey."""
    return Scene([SceneObject("U", "yellow", 0.04, (0.0, 0.1)),
                  SceneObject("van", "yellow", 0.05, (0.1, 0.0), shape="box", dims=(0.1, 0.05, 0.05)),
                  SceneObject("tray", "gray", 0.05, (-0.1, 0.0), shape="box", dims=(0.15, 0.09, 0.02)),
                  SceneObject("Q", "blue", 0.04, (0.0, -0.1)),
                  SceneObject("slab", "blue", 0.05, (-0.15, -0.1), shape="box", dims=(0.1, 0.1, 0.02))])


@pytest.mark.parametrize("said, expect", [
    ("the yellow block", "U"),  # the van is a van, not a block
    ("the gray block", "tray"),  # alone in its colour, the tray is the block meant
    ("the yellow van", "van"),
])
def test_a_thing_named_by_its_kind_is_no_block_beside_one(said: str, expect: str) -> None:
    assert resolve_object(said, _toys()) == expect


@pytest.mark.parametrize("said", [
    "the blue block",  # a slab is a block: Q or the slab
    "the yellow one",  # "one" is any object: U or the van
    "you",  # the robot
])
def test_a_block_by_its_kind_is_still_asked(said: str) -> None:
    with pytest.raises(L2PError):
        resolve_object(said, _toys())
