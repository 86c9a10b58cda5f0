"""Objects said by their proportions and by what kind of thing they look like ("the stick", "the slab", "the log",
"the long white one", "the flat square", "the stubby block"), for boxes, cylinders and meshes alike; a mesh named
after a shape ("cube", "cylinder") is that shape. Checked on tables of their own (not the corpora's lines): a word
picks the object whose proportions it describes, of several the clearly best fitting one, and is asked about where
two fit about as well."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from l2p_bullet.chain.clauses import resolve_clauses
from l2p_bullet.core.scene import Scene, SceneObject, shaped
from l2p_bullet.errors import L2PError
from l2p_bullet.language.partitives import group_of
from l2p_bullet.language.proportions import PROFILES, fitting, proportions
from l2p_bullet.language.reference_words import SHAPE_ADJECTIVES, SOFT_ADJECTIVES
from l2p_bullet.language.references import resolve_object
from l2p_bullet.language.shape_words import SHAPE_NOUNS
from l2p_bullet.language.synonyms import kind_groups, shape_of

MESHES = Path(__file__).parent / "meshes"


def _box(name: str, color: str, x: float, y: float, dims: tuple[float, float, float], yaw: float = 0.0):
    return shaped(name, color, (x, y), yaw, shape="box", dims=dims)


def _cylinder(name: str, color: str, x: float, y: float, radius: float, height: float):
    return shaped(name, color, (x, y), shape="cylinder", radius=radius, height_m=height)


def _mesh(name: str, color: str, x: float, y: float, mesh: str, scale: float = 1.0, rpy=(0.0, 0.0, 0.0)):
    return shaped(name, color, (x, y), shape="mesh", mesh=str(MESHES / mesh), scale=scale, rpy=rpy)


def _brick_and_bar() -> Scene:
    """Two white blocks told apart by proportions alone: an 8 x 4 x 4 cm brick and a 12 x 3 x 3 cm bar."""
    return Scene([SceneObject("g", "green", 0.04, (-0.12, 0.10)), SceneObject("r", "red", 0.05, (0.0, -0.02)),
                  _box("w1", "white", -0.13, -0.10, (0.08, 0.04, 0.04)),
                  _box("w2", "white", 0.13, -0.11, (0.12, 0.03, 0.03), 1.2),
                  _cylinder("k", "black", 0.02, 0.17, 0.02, 0.05)])


def _stirrer_table() -> Scene:
    """A coffee stirrer (a 16 x 1 x 1 cm mesh), a 9 x 4 x 4 cm box, a 6 x 6 x 3 cm box, two cubes and a bowl."""
    return Scene([SceneObject("c1", "red", 0.05, (-0.10, 0.08), 0.3),
                  _box("b1", "blue", 0.09, 0.12, (0.09, 0.04, 0.04), 1.0),
                  _box("b2", "pink", 0.11, -0.07, (0.06, 0.06, 0.03)),
                  SceneObject("c2", "yellow", 0.035, (-0.02, -0.03), 0.7),
                  _mesh("bowl", "white", -0.13, -0.12, "bowl.glb", 0.22, (math.pi / 2, 0.0, 0.0)),
                  _mesh("stirrer", "brown", 0.02, 0.17, "stirrer.obj")])


def _toys() -> Scene:
    """Meshes named after their shapes: a 4.8 cm toy cube, a cylinder lying on its side, a prism; a mug, a ball and a
    3.5 cm cube."""
    return Scene([_mesh("cube", "red", -0.12, 0.09, "cube.obj", 0.55),
                  _mesh("cylinder", "blue", 0.10, 0.12, "cylinder.obj", 0.55),
                  _mesh("prism", "yellow", 0.12, -0.08, "prism.obj", 0.55),
                  _mesh("mug", "white", -0.12, -0.11, "mug.obj", 0.6),
                  _mesh("soccerball", "white", 0.0, -0.02, "soccerball.obj", 0.05),
                  SceneObject("cube_small", "green", 0.035, (0.01, 0.17), 0.4)])


@pytest.mark.parametrize("said, expect", [
    ("the white brick", "w1"), ("the brick", "w1"), ("the brick-shaped piece", "w1"),
    ("the stubby white block", "w1"), ("the short white one", "w1"),
    ("the white bar", "w2"), ("the bar", "w2"), ("the white beam", "w2"), ("the stick", "w2"),
    ("the long white thing", "w2"), ("the long thin white bar", "w2"), ("the long skinny white bar", "w2"),
    ("the skinny white ruler-looking thing", "w2"), ("the bar-shaped part", "w2"),
    ("the black tube", "k"), ("the tube", "k"),
])
def test_two_blocks_are_told_apart_by_their_proportions(said: str, expect: str) -> None:
    assert resolve_object(said, _brick_and_bar()) == expect


@pytest.mark.parametrize("said, expect", [
    ("the stick", "stirrer"), ("the wooden stick", "stirrer"), ("the popsicle stick", "stirrer"),
    ("the swizzle stick", "stirrer"), ("the brown stick", "stirrer"),
    ("the bar", "b1"), ("the long block", "b1"), ("the long rectangular block", "b1"), ("the blue bar", "b1"),
    ("the slab", "b2"), ("the pink tile", "b2"), ("the flat square", "b2"), ("the pink slab", "b2"),
    ("the dish", "bowl"), ("the container", "bowl"),
])
def test_a_mesh_and_boxes_are_told_apart_by_their_proportions(said: str, expect: str) -> None:
    assert resolve_object(said, _stirrer_table()) == expect


@pytest.mark.parametrize("said, expect", [
    ("the red block", "cube"), ("the red cube", "cube"), ("the red square thing", "cube"), ("the big cube", "cube"),
    ("the larger of the two cubes", "cube"), ("the smallest cube", "cube_small"),
    ("the log", "cylinder"), ("the blue log", "cylinder"), ("the roll", "cylinder"), ("the tube thing", "cylinder"),
    ("the triangle", "prism"), ("the triangle prism", "prism"),
    ("the sphere", "soccerball"), ("the football", "soccerball"), ("the cup", "mug"),
])
def test_a_mesh_named_after_a_shape_is_that_shape(said: str, expect: str) -> None:
    assert resolve_object(said, _toys()) == expect


def test_a_block_is_asked_where_a_mesh_cube_and_a_cube_both_are_one(plugins) -> None:
    with pytest.raises(L2PError, match="cube_small"):
        resolve_clauses("Put the block next to the ball.", _toys(), plugins)
    assert resolve_object("the block nearest the mug", _toys()) == "cube"  # the toy block, not the mug itself


@pytest.mark.parametrize("said", [
    "the bar", "the white bar", "the stick", "the long one",  # two 12 cm bars: neither fits clearly better
])
def test_two_objects_that_fit_alike_are_asked_about(said: str) -> None:
    scene = Scene([_box("a", "white", -0.1, 0.1, (0.12, 0.03, 0.03)), _box("b", "white", 0.1, 0.1, (0.12, 0.032, 0.03)),
                   SceneObject("c", "red", 0.04, (0.0, -0.1))])
    with pytest.raises(L2PError, match="a, b|a and b"):
        resolve_object(said, scene)


def test_a_kind_of_thing_never_names_what_is_called_by_its_own_kind() -> None:
    """The bowl lies flat as a slab does, but a bowl is "the bowl", never "the slab"."""
    scene = Scene([_mesh("bowl", "white", -0.13, -0.12, "bowl.glb", 0.22, (math.pi / 2, 0.0, 0.0)),
                   SceneObject("c", "red", 0.04, (0.1, 0.0))])
    with pytest.raises(L2PError):
        resolve_object("the slab", scene)
    assert resolve_object("the flat one", scene) == "bowl"  # an adjective describes anything


def test_proportions_are_measured_from_footprint_and_height_whatever_the_shape() -> None:
    toys, table = _toys(), _stirrer_table()
    lying = proportions(toys.get("cylinder"))
    assert lying.round and lying.length > lying.height and shape_of(toys.get("cylinder")) == "cylinder"
    assert shape_of(toys.get("cube")) == "cube" and shape_of(toys.get("prism")) == "mesh"
    stirrer = proportions(table.get("stirrer"))
    assert stirrer.elongation > 10 and not stirrer.round
    slab = proportions(table.get("b2"))
    assert slab.flatness == pytest.approx(2.0) and slab.squareness == pytest.approx(1.0)
    standing = proportions(_cylinder("k", "black", 0, 0, 0.02, 0.11))
    assert standing.standing > 2 and standing.round and standing.filled < 0.9


def test_an_object_called_so_by_its_kind_fits_the_word_perfectly(tmp_path: Path) -> None:
    table = _stirrer_table()
    pool = list(table.objects)
    assert [o.name for o in fitting(["stick"], pool, kind_groups(table))] == ["stirrer"]
    assert [o.name for o in fitting(["stick"], pool, {})] == ["b1"]  # a stirrer is a kind of its own, but ...
    (tmp_path / "gizmo.obj").write_bytes((MESHES / "stirrer.obj").read_bytes())  # ... a kind no one knows
    gizmo = shaped("gizmo", "brown", (0.02, 0.17), shape="mesh", mesh=str(tmp_path / "gizmo.obj"))
    assert [o.name for o in fitting(["stick"], [*pool[:-1], gizmo], {})] == ["gizmo"]  # is seen by its proportions
    assert [o.name for o in fitting(["flat"], pool[:1], {})] == ["c1"]  # an adjective is read past on one object
    assert fitting(["slab"], pool[:1], {}) == []  # a noun never


def test_every_word_of_proportions_is_a_word_the_reader_knows() -> None:
    """A noun of proportions is a shape noun (known to every reader of nouns, never mended as a slip: "the tube thing"
    is not "the cube thing"), an adjective a shape or soft adjective (read past on one object)."""
    for word, profile in PROFILES.items():
        known = SHAPE_NOUNS if profile.noun else set(SHAPE_ADJECTIVES) | SOFT_ADJECTIVES
        assert word in known, word


def test_upright_and_flat_describe_meshes_too() -> None:
    scene = Scene([_mesh("nut", "gray", 0.05, -0.02, "nut.stl"), _mesh("bolt", "gray", 0.15, -0.10, "bolt.stl"),
                   SceneObject("c", "red", 0.04, (-0.1, 0.1))])
    assert resolve_object("the upright fastener", scene) == "bolt"
    assert resolve_object("the flat gray thing", scene) == "nut"
    assert resolve_object("the flat one", scene) == "nut"


@pytest.mark.parametrize("said, expect", [
    ("the block at the back on the right", "b2"), ("the block on the right at the back", "b2"),
    ("the block on the left in front", "c1"),
])
def test_a_depth_and_a_side_said_together_are_a_corner(said: str, expect: str) -> None:
    assert resolve_object(said, _stirrer_table()) == expect


def test_a_corner_is_as_far_as_toward_the_nearer_of_its_sides() -> None:
    """The red cube is 10 cm in front and 8 cm left; the stirrer 17 cm left but 2 cm behind the middle: in front on the
    left is the cube, though the stirrer is about as far along the corner's diagonal. Two blocks as far in front and on
    the left as each other are asked."""
    assert resolve_object("the one in front on the left", _stirrer_table()) == "c1"
    twins = Scene([SceneObject("p", "red", 0.04, (-0.10, 0.12)), SceneObject("q", "blue", 0.04, (-0.12, 0.10)),
                   SceneObject("r", "green", 0.04, (0.10, -0.10))])
    with pytest.raises(L2PError, match="p, q"):
        resolve_object("the one in front on the left", twins)


def test_a_group_or_a_relation_takes_every_object_a_word_admits() -> None:
    """One object said ("the bar") is the clearly best fitting; a group ("the bars") or the objects a relation
    chooses among ("the stick nearest the bowl") are all that the word admits, so a near tie there is asked."""
    assert group_of("the bars", _brick_and_bar()) == ("w1", "w2")
    assert resolve_object("the bar", _brick_and_bar()) == "w2"
    table = _stirrer_table()
    assert resolve_object("the bar nearest the bowl", table) == "b1"
    with pytest.raises(L2PError, match="b1, stirrer"):
        resolve_object("the stick nearest the bowl", table)
