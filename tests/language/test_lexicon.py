"""Words looked up in WordNet (language/lexicon.py): tried only after every other reading has refused a sentence, for
words no table of the toolkit gives an object; a word that so names two objects names neither."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.core.scene import Scene
from l2p_bullet.errors import L2PError
from l2p_bullet.language import lexicon, synonyms

LAB = "heldout88.tsv"  # beaker, flask, tube_rack, burner, petri_dish, goggles
TOYS = "heldout92.tsv"  # car_1, car_2, truck, garage, block_red, block_green, cone


@pytest.mark.parametrize("name, sentence, expect", [
    (LAB, "Push the flask away from the specs, quick.", "push:away flask goggles pace=fast"),  # more general
    (LAB, "Erlenmeyer next to the Bunsen.", "slide:next-to flask burner"),  # made after a person: the name alone
    (LAB, "move the thermos past the rack", "slide:past flask tube_rack"),  # more particular
    ("heldout86.tsv", "move the bobbin next to the scissors", "slide:next-to thread_spool fabric_scissors"),  # no
    # button tin, as a sound amiss once read it
    (TOYS, "zoom the truck super fast round the cone", "slide:around truck cone pace=fast"),  # a verb that moves
    (TOYS, "scoot the cone away from the garage", "slide:away cone garage"),
    (TOYS, "move the lorry past the cone", "slide:past truck cone"),
])
def test_a_word_wordnet_relates_to_one_object_names_it(plugins, name, sentence, expect):
    assert read(sentence, plugins, name) == expect


@pytest.mark.parametrize("name, sentence", [
    (TOYS, "move the automobile next to the cone"),  # both cars are automobiles: asked, never guessed
    (TOYS, "throw the cone past the truck"),  # a motion the actions cannot make stays refused
    (TOYS, "move the keyboard next to the cone"),  # not on the table
    (LAB, "move the vessel next to the rack"),  # flask and beaker alike
])
def test_a_word_that_names_two_objects_or_none_is_refused(plugins, name, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins, name)


def test_words_are_looked_up_only_on_the_last_try():
    """Outside :func:`lexicon.looking_up` the kind tables are the toolkit's own: a sentence the grammar reads is read
    exactly as without WordNet."""
    scene = Scene.from_dict({"objects": [
        {"name": "goggles", "color": "black", "shape": "box", "dims": [0.15, 0.06, 0.05], "xy": [0.1, 0.1]},
        {"name": "flask", "color": "cyan", "shape": "cylinder", "radius": 0.045, "height": 0.14, "xy": [-0.1, -0.1]}]})
    assert "specs" not in synonyms.kind_groups(scene)
    with lexicon.looking_up():
        assert synonyms.kind_groups(scene)["specs"] == {"goggles"}
        assert synonyms.kind_words(scene)["thermos"] == "flask"
    assert "thermos" not in synonyms.kind_words(scene)


def test_a_rare_sense_names_nothing():
    """A word names an object only through its own first sense among things: "keyboard" is a rack for keys only in
    its second; "pot" is the can's word in no sense a person means ("can" is a tin can, not a toilet)."""
    assert "keyboard" not in lexicon.words_for("holder")
    assert "pot" not in lexicon.words_for("can")
    assert {"specs", "spectacles"} <= lexicon.words_for("goggles")


def test_a_kinds_own_synonyms_name_it_unless_they_name_a_kind_people_look_for():
    """The words of a kind's own senses name it whatever they first mean ("engine" is a motor first, a locomotive in
    its third sense; "cork" a fishing float's), but a word that is a kind of its own ("phone": a telephone before a
    headphone) names no other kind's object."""
    assert {"engine", "engines"} <= lexicon.words_for("locomotive")
    assert "cork" in lexicon.words_for("bobber")
    assert "phone" in lexicon.words_for("headphones")
    assert "phone" not in lexicon.words_for("headphones", frozenset({"phone"}))


def test_motion_verbs_are_read_only_where_the_toolkit_knows_no_word():
    known = frozenset({"slide", "the", "cone"})
    assert lexicon.moving_verbs_read("zoom the cone", known, frozenset()) == "move the cone"
    assert lexicon.moving_verbs_read("slide the cone", known, frozenset()) == "slide the cone"
    assert lexicon.moving_verbs_read("toss the cone", known, frozenset({"toss"})) == "toss the cone"


@pytest.mark.parametrize("sentence, expect", [
    ("slide the cheap silver teaspoon away from the sugar jar", "slide:away spoon sugar_jar"),
    ("move my lovely old kettle next to the teapot", "slide:next-to kettle teapot"),
])
def test_an_adjective_no_one_knows_is_read_past_before_a_noun_of_the_scene(plugins, sentence, expect):
    assert read(sentence, plugins, "heldout93.tsv") == expect


@pytest.mark.parametrize("sentence", [
    "move the porcelain saucer next to the kettle",  # a noun the scene lacks is kept, and refused
    "slide the cube between tray and can closer to teddy",  # a relation is never an adjective
])
def test_a_word_that_could_pick_another_object_is_kept(plugins, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins, "heldout93.tsv" if "saucer" in sentence else "heldout10.tsv")
