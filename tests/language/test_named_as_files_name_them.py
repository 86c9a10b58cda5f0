"""Objects named as users' files name them ("coffee_mug", "cube_b", "RedCube2"), called by the words of their names,
their kinds' everyday names and, for a one-letter name, the letter as dictation spells it ("block cue"). Checked on
sentences of each kind (not the corpora's own lines), and on what must stay refused: a word two objects share, a
spelled letter where it is a word of its own."""

from __future__ import annotations

from pathlib import Path

import pytest
from corpus import read

from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.errors import L2PError
from l2p_bullet.language.references import resolve_object
from l2p_bullet.language.synonyms import name_parts

GROCERIES = "heldout26.tsv"
"""LIBERO's ketchup_bottle (red), butter_box (yellow), alphabet_soup (red, soup_can.obj), milk_carton (white),
coffee_mug (blue); green cubes cube_a (4.5 cm) and cube_b (3 cm)."""
HOUSEHOLD = "heldout27.tsv"
"""A zucchini, a gamepad (joypad.obj), a lamp (tablelamp.obj), a crate (woodenbox.obj), a saucer (plate.obj); orange
cubes O (4 cm) and Q (5 cm)."""
WORKSHOP = "heldout28.tsv"
"""A red jello (gelatin_box.obj), a white ball (pingpong.obj), a black camera, a gray nut and bolt; gray cube P, yellow
cube Y."""
MESHES = Path(__file__).parent / "meshes"


@pytest.mark.parametrize("sentence, expect, table", [
    # a name's words, however the file joins them
    ("push cube a toward the ketchup bottle", "push:closer cube_a ketchup_bottle", GROCERIES),
    ("move Cube A past the alphabet soup", "slide:past cube_a alphabet_soup", GROCERIES),
    ("slide the milk carton next to cube_b", "slide:next-to milk_carton cube_b", GROCERIES),
    # a name's words are its kinds: the head noun and the others
    ("carry the coffee toward the carton", "carry:closer coffee_mug milk_carton", GROCERIES),
    ("push the ketchup past the butter", "push:past ketchup_bottle butter_box", GROCERIES),
    ("move the bottle around the soup", "slide:around ketchup_bottle alphabet_soup", GROCERIES),
    # the mesh file's words are kinds too: the soup is a can, a tin
    ("slide the tin away from the cup", "slide:away alphabet_soup coffee_mug", GROCERIES),
    ("push the can of soup toward the big cube", "push:closer alphabet_soup cube_a", GROCERIES),
    ("move the red tin past the carton of milk", "slide:past alphabet_soup milk_carton", GROCERIES),
    ("put the bottle of ketchup next to the soup can", "slide:next-to ketchup_bottle alphabet_soup", GROCERIES),
    # a box mesh by its name is a box; a mug is a cup
    ("push the yellow box toward the teacup", "push:closer butter_box coffee_mug", GROCERIES),
    ("move the tomato sauce next to the coffee cup", "slide:next-to ketchup_bottle coffee_mug", GROCERIES),
    ("slide the packet past the mug", "slide:past butter_box coffee_mug", GROCERIES),
    # everyday words for kinds the reader did not know
    ("push the gamepad toward the zucchini", "push:closer gamepad zucchini", HOUSEHOLD),
    ("move the joystick next to the marrow", "slide:next-to gamepad zucchini", HOUSEHOLD),
    ("carry the games controller past the light", "carry:past gamepad lamp", HOUSEHOLD),
    ("slide the table lamp toward the dish", "slide:closer lamp saucer", HOUSEHOLD),
    ("move the vegetable around the plate", "slide:around zucchini saucer", HOUSEHOLD),
    ("push the joypad away from the desk lamp", "push:away gamepad lamp", HOUSEHOLD),
    ("move the webcam toward the pingpong ball", "slide:closer camera ball", WORKSHOP),
    ("carry the ping-pong ball past the jelly", "carry:past ball jello", WORKSHOP),
    ("slide the gelatine box next to the screw", "slide:next-to jello bolt", WORKSHOP),
    ("push the M6 nut toward the hex bolt", "push:closer nut bolt", WORKSHOP),
    ("move the metal nut past the cam", "slide:past nut camera", WORKSHOP),
    ("push the round piece toward the green box", "push:closer D E", "heldout29.tsv"),
    # a letter said as dictation writes it, where a one-letter name exists
    ("slide block cue past the saucer", "slide:past Q saucer", HOUSEHOLD),
    ("push the cube oh toward the lamp", "push:closer O lamp", HOUSEHOLD),
    ("move the zucchini next to cue", "slide:next-to zucchini Q", HOUSEHOLD),
    ("slide the ball toward cube pee", "slide:closer ball P", WORKSHOP),
    ("move the nut next to block why", "slide:next-to nut Y", WORKSHOP),
])
def test_named_as_files_name_them(sentence: str, expect: str, table: str, plugins) -> None:
    assert read(sentence, plugins, table) == expect


@pytest.mark.parametrize("sentence, table", [
    ("push the cube toward the mug", GROCERIES),  # two cubes
    ("move the box next to the mug", GROCERIES),  # the butter box and the milk carton are boxes
    ("move the red thing next to the mug", GROCERIES),  # the ketchup and the soup
    ("move the metal part toward the ball", WORKSHOP),  # the nut and the bolt
    ("push the fastener toward the camera", WORKSHOP),
    ("move the hardware past the jello", WORKSHOP),
    ("move owe next to the lamp", HOUSEHOLD),  # "owe" alone is a word of its own ("oh" alone is O: letters.py)
    ("move the lamp next to you", HOUSEHOLD),  # "you" is the robot, and U is not on the table
    ("slide the zucchini toward cube zed", HOUSEHOLD),  # no Z on the table
    ("move the lamp next to em", HOUSEHOLD),  # "em" alone is "them" as typed
    ("push the light orange cube toward the crate", HOUSEHOLD),  # a shade, never the lamp
    ("move the cucumber past the lamp", HOUSEHOLD),  # a cucumber is not a courgette
])
def test_what_stays_refused(sentence: str, table: str, plugins) -> None:
    with pytest.raises(L2PError):
        read(sentence, plugins, table)


def _mesh(name: str, color: str, x: float, mesh: str) -> SceneObject:
    return SceneObject(name, color, 0.05, (x, 0.0), shape="mesh", mesh=str(MESHES / mesh))


def _pantry() -> Scene:
    """A butter box beside a real box, a soup can beside a cylinder, two names that share "coffee"."""
    return Scene([_mesh("butter_box", "yellow", 0.1, "butter.obj"),
                  SceneObject("box1", "yellow", 0.05, (0.0, 0.1), shape="box", dims=(0.08, 0.04, 0.04)),
                  _mesh("alphabet_soup", "red", -0.1, "soup_can.obj"),
                  SceneObject("RedCylinder2", "red", 0.05, (0.0, -0.1), shape="cylinder", radius=0.02,
                              height_m=0.06),
                  _mesh("coffee_mug", "blue", 0.2, "coffee_mug.obj"),
                  SceneObject("coffeeBeans", "brown", 0.04, (0.2, 0.2)),
                  SceneObject("milk-carton", "white", 0.05, (-0.2, 0.2))])


@pytest.mark.parametrize("said, expect", [
    ("the butter", "butter_box"), ("the butter box", "butter_box"), ("the soup tin", "alphabet_soup"),
    ("the tin of soup", "alphabet_soup"), ("the mug", "coffee_mug"), ("the coffee beans", "coffeeBeans"),
    ("red cylinder 2", "RedCylinder2"), ("the milk carton", "milk-carton"), ("the milk", "milk-carton"),
    ("the blue cup", "coffee_mug"), ("the carton", "milk-carton"), ("the brown coffee", "coffeeBeans"),
    # "can" names the soup can, a thing of that name, before the red cylinder it only looks like
    ("the can", "alphabet_soup"), ("the red can", "alphabet_soup"),
])
def test_a_names_words_name_it(said: str, expect: str) -> None:
    assert resolve_object(said, _pantry()) == expect


@pytest.mark.parametrize("said", [
    "the box",  # the butter box and the real box
    "the yellow box",
    "the coffee",  # the mug and the beans
])
def test_a_word_two_names_share_is_asked(said: str) -> None:
    with pytest.raises(L2PError):
        resolve_object(said, _pantry())


def test_a_name_said_as_a_description_that_fits_another_is_asked() -> None:
    scene = Scene([SceneObject("red_cube", "red", 0.05, (0.1, 0.0)), SceneObject("B", "red", 0.05, (0.0, 0.1)),
                   SceneObject("cube_a", "green", 0.05, (-0.1, 0.0)), SceneObject("A", "green", 0.04, (0.0, -0.1))])
    for said in ("the red cube", "cube a"):
        with pytest.raises(L2PError):
            resolve_object(said, scene)
    assert resolve_object("red_cube", scene) == "red_cube"
    assert resolve_object("cube_a", scene) == "cube_a"


def test_a_names_words_split_as_files_join_them() -> None:
    assert name_parts("coffee_mug") == ("coffee", "mug")
    assert name_parts("milk-carton") == ("milk", "carton")
    assert name_parts("RedCube2") == ("red", "cube", "2")
    assert name_parts("obj3") == ("obj", "3")
    assert name_parts("XLBox") == ("xl", "box")
