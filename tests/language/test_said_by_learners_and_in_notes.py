"""Sentences as learners, note-takers and dictation write them: the verb last and the place after its object (Korean,
Japanese, Turkish order: "A to B near move"), a Turkish keyboard's dotless i ("slıde"), words with their vowels left
out ("psh", "gntly", "scrwdrvr"), a name cut short ("tape_meas"), Portuguese-shaped prepositions ("in the side of",
"closer of", "pass X by Y"), a fruit emoji's whole name ("GREEN APPLE"), a reason said after the command, a
correction ("Actually make that ...", "sorry, the red can, ..."), the previous command again to another place, a place
said alone after the object shown, a box called by what it holds, tool brands and trade words, dictation's "ranch" for
the wrench, "the cube" for a box as long as it is wide and tall, a corner as both its sides. And what must stay
refused: "next to them both" (one move, one place), a word with a vowel inside that only looks shortened ("min"), a
6 x 4 x 4 cm box among cubes. Checked on sentences of each kind (not the corpora's own lines)."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

LETTERS = "heldout77.tsv"
"""A red, B blue, C green, D bigger blue (cubes), E yellow cylinder, F long white block."""
FRUIT = "heldout78.tsv"
"""apple (red), green_apple, lemon, lime, banana, plate."""
WORKSHOP = "heldout79.tsv"
"""hammer, screwdriver, wrench, tape_measure, drill, screw_box."""
SHAPES = "heldout80.tsv"
"""red_cube, blue_cube, green_cube, red_can, blue_can, tray."""


@pytest.mark.parametrize("sentence, expect, table", [
    # the verb last, the place after its object
    ("C to A near move", "slide:closer C A", LETTERS),
    ("F around C go", "slide:around F C", LETTERS),
    ("green block red block toward push", "push:closer C A", LETTERS),
    ("the yellow cylinder go past the white block", "slide:past E F", LETTERS),
    # a Turkish keyboard; vowels left out
    ("slıde E next to C", "slide:next-to E C", LETTERS),
    ("psh A twrds F", "push:closer A F", LETTERS),
    ("slwly mve B bsde C", "slide:next-to B C pace=slow", LETTERS),
    ("scrwdrvr nxt to drill", "slide:next-to screwdriver drill", WORKSHOP),
    ("tape_meas around hammer", "slide:around tape_measure hammer", WORKSHOP),
    # learners' prepositions
    ("put the E in the side of the A", "slide:next-to E A", LETTERS),
    ("bring the F closer of the B", "slide:closer F B", LETTERS),
    ("pass the D by the E", "slide:past D E", LETTERS),
    ("I want E to pass by F", "slide:past E F", LETTERS),
    ("the A passes by the C", "slide:past A C", LETTERS),
    ("nudge C little away from A", "push:away C A extent=little", LETTERS),
    # a fruit emoji by its whole name
    ("put the \U0001f34f next to the plate", "slide:next-to green_apple plate", FRUIT),
    ("\U0001f34e around \U0001f34b", "slide:around apple lemon", FRUIT),
    # a reason after the command
    ("move the lime next to the plate so the kids can reach it", "slide:next-to lime plate", FRUIT),
    # a correction
    ("Slide the blue can past the tray. Actually make that past the green cube.", "slide:past blue_can green_cube",
     SHAPES),
    ("push the blue cube, sorry, the blue can, toward the tray", "push:closer blue_can tray", SHAPES),
    # the previous command again, to another place
    ("carry the red cube past the tray, then do it again past the blue can",
     "carry:past red_cube tray ; carry:past red_cube blue_can", SHAPES),
    ("move the green cube next to the tray. ok now do the same with the red cube, thanks",
     "slide:next-to green_cube tray ; slide:next-to red_cube tray", SHAPES),
    # a place said alone after the object shown
    ("Lemon. Away from the banana.", "slide:away lemon banana", FRUIT),
    # a box called by what it holds; tool brands and trade words; dictation
    ("put the screws by the claw", "slide:next-to screw_box hammer", WORKSHOP),
    ("move the DeWalt away from the spanner", "slide:away drill wrench", WORKSHOP),
    ("move the ranch toward the drill", "slide:closer wrench drill", WORKSHOP),
    ("the metal thing next to the hammer", "slide:next-to wrench hammer", WORKSHOP),
    # "the cube" for a box as long as it is wide and tall
    ("move the biggest cube next to E", "slide:next-to D E", LETTERS),
    # a corner is both its sides
    ("move the thing at the front left past the drill", "slide:past hammer drill", WORKSHOP),
])
def test_read(plugins, sentence, expect, table):
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence, table", [
    # one move is made beside one object, never once beside each of two
    ("move the tray next to the red cube, then the green cube next to them both", SHAPES),
    # four cubes: "the cube" is asked; three alike small ones: "the small cube" too
    ("move the cube away from E", LETTERS),
    ("move the small cube past E", LETTERS),
    # two blue cubes
    ("move the blue block next to E", LETTERS),
    # "gray" and "green" both sound like "great": asked, never guessed
    ("move the great cube next to the tray", SHAPES),
])
def test_stays_refused(plugins, sentence, table):
    with pytest.raises(L2PError):
        read(sentence, plugins, table)


def test_a_word_with_a_vowel_inside_is_no_shortened_word():
    """"min" stays "min" (no "mini"), "par" no "paper"; "gntly" is gently, not gentle; "psh" is push, not pushes."""
    from l2p_bullet.language.typos import unvowelled

    known = frozenset({"mini", "paper", "gently", "gentle", "push", "pushes", "then", "than", "thin"})
    assert unvowelled("min", known) is None
    assert unvowelled("par", known) is None
    assert unvowelled("gntly", known) == "gently"
    assert unvowelled("psh", known) == "push"
    assert unvowelled("thn", known) is None  # then, than or thin: not guessed


def test_a_cube_said_alone_is_a_box_alike_on_every_side(plugins):
    """A 6 x 4 x 4 cm box beside two 5 cm cubes: "the two cubes" are the cubes, and "the bigger of them" one of them."""
    from l2p_bullet.chain.clauses import resolve_clauses
    from l2p_bullet.core.scene import Scene

    scene = Scene.from_dict({"objects": [
        {"name": "long", "color": "gray", "shape": "box", "dims": [0.06, 0.04, 0.04], "xy": [-0.12, 0.10]},
        {"name": "small", "color": "gray", "shape": "box", "dims": [0.04, 0.04, 0.04], "xy": [0.10, 0.12]},
        {"name": "big", "color": "gray", "shape": "box", "dims": [0.06, 0.06, 0.06], "xy": [0.02, -0.10]},
        {"name": "can", "color": "red", "shape": "cylinder", "radius": 0.03, "height": 0.1, "xy": [-0.10, -0.12]},
    ]})
    [clause] = resolve_clauses("move the biggest cube next to the can", scene, plugins)
    assert clause.command.mover == "big"
    with pytest.raises(L2PError, match="ambiguous"):
        resolve_clauses("move the cube next to the can", scene, plugins)
