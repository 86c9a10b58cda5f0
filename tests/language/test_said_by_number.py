"""Objects named by numbers as people say them (language/numbers.py): "#3", "number 3", "no. 3", "object three",
"cube 1" for Cube_01, a description with the number in apposition ("the red one, number 2") that must agree with it,
a numbered step's label before its instruction ("Step 1: ..."), a row of spelled numbers without commas; and what
stays as it was: a count ("the two cubes", "both") is never a name, a spelled number names nothing where the scene has
no such number, "the first block" is still a place in a group. Also the two size and shape readings these tables
asked for: a 5.5 cm cube is the biggest beside 4.5 cm ones, and a cube is no brick where a brick-shaped box is there.
Sentences of each kind, none of them a corpus line, on tables built here."""

from __future__ import annotations

import pytest
from corpus import REFUSE, resolve

from l2p_bullet.chain.clauses import resolve_clauses
from l2p_bullet.core.scene import Scene
from l2p_bullet.errors import L2PError
from l2p_bullet.language.numbers import number_of, numbered

DIGITS = {"objects": [
    {"name": "1", "color": "orange", "size": 0.035, "xy": [-0.15, 0.10]},
    {"name": "2", "color": "orange", "size": 0.05, "xy": [0.03, 0.14]},
    {"name": "3", "color": "purple", "size": 0.04, "xy": [0.16, 0.08]},
    {"name": "4", "color": "purple", "shape": "box", "dims": [0.09, 0.04, 0.04], "xy": [-0.12, -0.04]},
    {"name": "5", "color": "white", "shape": "cylinder", "radius": 0.02, "height": 0.06, "xy": [0.05, -0.05]},
    {"name": "6", "color": "black", "size": 0.045, "xy": [-0.02, -0.17]},
]}
"""Six objects named "1" to "6": two orange cubes (3.5 and 5 cm), a purple cube and a purple brick-shaped box, a white
cylinder, a black cube."""

FILES = {"objects": [
    {"name": "Box_01", "color": "red", "size": 0.04, "xy": [-0.14, 0.10]},
    {"name": "Box_02", "color": "green", "size": 0.05, "xy": [0.12, 0.12]},
    {"name": "Can_01", "color": "blue", "shape": "cylinder", "radius": 0.02, "height": 0.07, "xy": [0.02, -0.06]},
    {"name": "Ball_3", "color": "yellow", "shape": "cylinder", "radius": 0.025, "height": 0.05, "xy": [-0.1, -0.15]},
    {"name": "plate", "color": "white", "shape": "box", "dims": [0.1, 0.1, 0.01], "xy": [0.15, -0.15]},
]}
"""Names as a simulator's files give them: two objects numbered 1 (Box_01, Can_01), a Box_02, a Ball_3, a plate."""

LETTERS = {"objects": [
    {"name": "A", "color": "red", "size": 0.04, "xy": [-0.12, 0.1]},
    {"name": "B", "color": "red", "size": 0.04, "xy": [0.12, 0.1]},
    {"name": "C", "color": "blue", "size": 0.05, "xy": [0.0, -0.12]},
]}
"""Nothing numbered: a spelled number names nothing here."""

SIZES = {"objects": [
    {"name": "P", "color": "red", "size": 0.045, "xy": [-0.15, 0.1]},
    {"name": "Q", "color": "red", "size": 0.055, "xy": [0.0, 0.12]},
    {"name": "R", "color": "blue", "size": 0.045, "xy": [0.15, 0.1]},
    {"name": "S", "color": "green", "size": 0.035, "xy": [-0.1, -0.12]},
    {"name": "T", "color": "green", "size": 0.04, "xy": [0.1, -0.12]},
    {"name": "U", "color": "blue", "shape": "box", "dims": [0.08, 0.04, 0.04], "xy": [0.0, -0.2]},
]}
"""A 5.5 cm cube beside two 4.5 cm ones; a 3.5 and a 4 cm green cube (a tie); a blue cube and a blue brick."""


@pytest.fixture(scope="module")
def digits() -> Scene:
    return Scene.from_dict(DIGITS)


@pytest.fixture(scope="module")
def files() -> Scene:
    return Scene.from_dict(FILES)


def refusal(sentence: str, scene: Scene, plugins) -> str:
    """The one-line error ``sentence`` is refused with."""
    with pytest.raises(L2PError) as e:
        resolve_clauses(sentence, scene, plugins)
    return str(e.value).splitlines()[0]


def test_numbers_said():
    assert [number_of(w) for w in ("6", "06", "#6", "six", "Six.", "sixty", "6cm", "one")] == [6, 6, 6, 6, 6, None,
                                                                                               None, 1]


def test_numbered_names():
    table = numbered(Scene.from_dict(FILES))
    assert table == {1: ("Box_01", "Can_01"), 2: ("Box_02",), 3: ("Ball_3",)}
    assert numbered(Scene.from_dict(LETTERS)) == {}


@pytest.mark.parametrize("sentence, expect", [
    # a number with its marks
    ("shove #3 toward #6", "push:closer 3 6"),
    ("move # 3 past # 1", "slide:past 3 1"),
    ("slide number 4 around number 2", "slide:around 4 2"),
    ("put no. 1 beside no. 5", "slide:next-to 1 5"),
    ("nudge nr 6 a bit closer to nr 3", "push:closer 6 3 extent=little"),
    # spelled out where the scene has the number
    ("move five past one", "slide:past 5 1"),
    ("please push six toward three thanks", "push:closer 6 3"),
    ("carry number four around number one", "carry:around 4 1"),
    ("move five around six then push it toward two", "slide:around 5 6 ; push:closer 5 2"),
    ("I want three next to four", "slide:next-to 3 4"),
    # a label before the number
    ("move object two away from object five", "slide:away 2 5"),
    ("slide item 3 toward item 1", "slide:closer 3 1"),
    ("push cube no. 2 next to cylinder no. 5", "push:next-to 2 5"),
    ("move the cube 6 next to the cylinder 5", "slide:next-to 6 5"),
    ("move block four past block six", "slide:past 4 6"),
    ("move cube 4 toward 1", "slide:closer 4 1"),  # a brick-shaped box is called a cube as a label
    # a description with the number in apposition, agreeing with it
    ("move the big orange one, number 2, next to 6", "slide:next-to 2 6"),
    ("move the orange one, number 1, past 3", "slide:past 1 3"),
    ("Please put the white cylinder, #5, beside the purple box, #4.", "slide:next-to 5 4"),
    ("push the black cube number 6 toward the purple one number 3", "push:closer 6 3"),
    ("the orange one, number 1 - slide it away from 5", "slide:away 1 5"),
    ("the purple one, #3, carry it around 6", "carry:around 3 6"),
    ("number 6: a bit closer to 2", "slide:closer 6 2 extent=little"),
    # a numbered step's label is no object's name
    ("Step 2: move 4 past 6.", "slide:past 4 6"),
    ("Task 1: push 3 toward 5, then slide 1 next to 2.", "push:closer 3 5 ; slide:next-to 1 2"),
    # rows of numbers
    ("put five three and one in a line", "row 5,3,1"),
    ("line up six, two and four", "row 6,2,4"),
    ("line up the white one number 5, the black one number 6 and the orange one number 1", "row 5,6,1"),
])
def test_said_by_number(plugins, digits, sentence, expect):
    assert resolve(sentence, digits, plugins) == expect


@pytest.mark.parametrize("sentence, expect", [
    # counts and pointers stay what they were
    ("move the two orange cubes next to 5", "slide:next-to 1 5 ; slide:next-to 2 5"),
    ("push both purple ones toward 6", "push:closer 3 6 ; push:closer 4 6"),
    ("move the larger of the two orange cubes past 5", "slide:past 2 5"),
    ("move the smaller one of the two orange cubes next to 6", "slide:next-to 1 6"),
    ("of the two orange cubes, move 2 toward 5 and the other one past 6", "slide:closer 2 5 ; slide:past 1 6"),
    ("move 3 next to 5, then the other purple one too", "slide:next-to 3 5 ; slide:next-to 4 5"),
    ("put the 1 next to the 2", "slide:next-to 1 2"),
    ("move the cube nearest number 2 next to 5", "slide:next-to 3 5"),  # measured from 2, never 2 itself
    ("move the cube left of no. 3 toward 5", "slide:closer 2 5"),
])
def test_counts_stay_counts(plugins, digits, sentence, expect):
    assert resolve(sentence, digits, plugins) == expect


@pytest.mark.parametrize("sentence", [
    "move the two next to 5",  # a count, or a pointer: never 2 by name
    "move the one next to 5",
    "move one cube next to 5",
    "slide number 9 toward 2",  # no 9 on the table
    "move #7 next to 1",
    "move object eight past 3",
    "move cylinder 2 next to 3",  # 2 is a cube
    "move the first cube next to 5",  # an ordinal is a place in a group, and these stand in no line
])
def test_stays_refused(plugins, digits, sentence):
    assert resolve(sentence, digits, plugins) == REFUSE


@pytest.mark.parametrize("sentence, said", [
    ("move the white one, number 2, next to 6", ['"the white one" and number 2', "2 is an orange cube",
                                                 '"the white one" is 5']),
    ("move the purple one, number 6, toward 1", ['"the purple one" and number 6', "6 is a black cube",
                                                 '"the purple one" fits 3, 4']),
    ("move the big orange one, number 1, toward 5", ['"the big orange one" and number 1', '"the big orange one" is 2',
                                                     "1 is an orange cube"]),
    ("the white one, number 3 - push it past 1", ['"the white one" and number 3', "3 is a purple cube"]),
    ("Could you move the black cube, #1, toward 5?", ['"the black cube" and number 1', "1 is an orange cube"]),
])
def test_a_description_against_its_number(plugins, digits, sentence, said):
    """Refused with one line that names what the description and the number each name."""
    error = refusal(sentence, digits, plugins)
    assert all(s in error for s in said), error
    assert "move" not in error.split(" and number")[0]


@pytest.mark.parametrize("sentence, expect", [
    ("move box 1 next to the plate", "slide:next-to Box_01 plate"),
    ("move box one next to box two", "slide:next-to Box_01 Box_02"),
    ("push can 1 toward ball 3", "push:closer Can_01 Ball_3"),
    ("move the can no. 1 past the plate", "slide:past Can_01 plate"),
    ("move the red one, number 1, toward the plate", "slide:closer Box_01 plate"),
    ("move 2 next to 3", "slide:next-to Box_02 Ball_3"),
    ("move two next to three", "slide:next-to Box_02 Ball_3"),
    ("line up 3, 2 and the plate", "row Ball_3,Box_02,plate"),
    ("move cube 2 toward the plate", "slide:closer Box_02 plate"),
])
def test_file_names_by_number(plugins, files, sentence, expect):
    assert resolve(sentence, files, plugins) == expect


@pytest.mark.parametrize("sentence, said", [
    ("move number 1 next to the plate", "2 objects are numbered 1 (Box_01, Can_01)"),
    ("move 1 next to the plate", "2 objects are numbered 1"),
    ("move object one next to the plate", "2 objects are numbered 1"),
    ("move the green one, number 1, toward the plate", 'nothing numbered 1 is "the green one"'),
])
def test_file_names_asked(plugins, files, sentence, said):
    """Two objects numbered 1: the number alone is asked about."""
    assert said in refusal(sentence, files, plugins)


@pytest.mark.parametrize("sentence", [
    "move two next to three",
    "move number one next to C",
    "put the two red cubes next to C",
])
def test_no_number_on_the_table(plugins, sentence):
    """Where nothing is numbered, numbers are read as before: counts, or refused."""
    expect = "slide:next-to A C ; slide:next-to B C" if "red cubes" in sentence else REFUSE
    assert resolve(sentence, Scene.from_dict(LETTERS), plugins) == expect


@pytest.mark.parametrize("sentence, expect", [
    ("move the biggest cube toward S", "slide:closer Q S"),  # 5.5 cm beside 4.5 cm: clearly the biggest
    ("move the big red cube next to R", "slide:next-to Q R"),
    ("move the blue brick past P", "slide:past U P"),  # a cube is no brick where a brick-shaped box is there
    ("move the blue cube past P", "slide:past R P"),
    ("move the blue box past P", REFUSE),  # people call cubes boxes: asked, as before
    ("move the small green cube toward P", REFUSE),  # 3.5 and 4 cm: a tie, as before
])
def test_sizes_and_bricks(plugins, sentence, expect):
    assert resolve(sentence, Scene.from_dict(SIZES), plugins) == expect
