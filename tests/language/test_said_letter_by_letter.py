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
