"""Sentences -> Command: verbs, polite forms, names and colour phrases, longest phrase, clear errors."""

from __future__ import annotations

import pytest

from l2p_bullet.core.scene import Scene, SceneObject, default_scene
from l2p_bullet.errors import LanguageError, UnknownObjectError
from l2p_bullet.language import Command, parse

# The phrases the five built-in manifests declare (the parser gets them from the registry in perform).
PHRASES = {
    "closer to": "closer", "nearer to": "closer", "toward": "closer", "towards": "closer",
    "away from": "away", "next to": "next-to", "beside": "next-to", "alongside": "next-to",
    "past": "past", "around": "around", "round": "around",
}


@pytest.fixture
def scene() -> Scene:
    return default_scene()


@pytest.fixture
def crowded() -> Scene:
    return Scene([
        SceneObject("A", "red", 0.05, (0.10, 0.0)),
        SceneObject("B", "green", 0.05, (0.0, 0.10)),
        SceneObject("C", "blue", 0.05, (-0.10, 0.0)),
        SceneObject("D", "blue", 0.05, (0.0, -0.10)),
    ]).validate()


@pytest.mark.parametrize("sentence, expected", [
    ("move A around B", ("move", "A", "around", "around", "B")),
    ("Please slide the red block around the green one.", ("slide", "A", "around", "around", "B")),
    ("push the red cube closer to B", ("push", "A", "closer to", "closer", "B")),
    ("shift A towards the green block", ("shift", "A", "towards", "closer", "B")),
    ("Put B away from A!", ("put", "B", "away from", "away", "A")),
    ("MOVE a next to b", ("move", "A", "next to", "next-to", "B")),
    ("could you move block A beside the green cube, please?", ("move", "A", "beside", "next-to", "B")),
    ("Slide A alongside B", ("slide", "A", "alongside", "next-to", "B")),
    ("move a red block past B", ("move", "A", "past", "past", "B")),
    ("Kindly move A round B", ("move", "A", "round", "around", "B")),
    ("push the red one nearer to the green one", ("push", "A", "nearer to", "closer", "B")),
])
def test_parses(scene, sentence, expected):
    cmd = parse(sentence, scene, PHRASES)
    assert isinstance(cmd, Command)
    assert (cmd.verb, cmd.mover, cmd.preposition, cmd.action, cmd.anchor) == expected


def test_longest_phrase_wins(scene):
    phrases = {"left of": "short", "to the left of": "long", "to": "tiny"}
    cmd = parse("move A to the left of B", scene, phrases)
    assert (cmd.preposition, cmd.action, cmd.mover, cmd.anchor) == ("to the left of", "long", "A", "B")
    assert parse("move A left of B", scene, phrases).action == "short"


def test_phrases_are_compared_normalised(scene):
    assert parse("move A  Next   To B", scene, {"Next to": "next-to"}).action == "next-to"


def test_colour_in_a_larger_scene(crowded):
    assert parse("move the green block next to A", crowded, PHRASES).mover == "B"
    assert parse("move C next to D", crowded, PHRASES).anchor == "D"


@pytest.mark.parametrize("sentence, words", [
    ("move A arround B", ['"arround" is not a preposition', 'Did you mean "around"?', "installed:", "away from"]),
    ("move A on top of B", ['"on top of" is not a preposition', "next to"]),
    ("move A to the left of B", ['"to the left of" is not a preposition']),
    ("move A", ["no preposition", "installed:"]),
    ("move A around", ["reference block", '"around"']),
    ("move A around A", ['both "A"', "itself"]),
    ("move the red block around the red one", ['both "A"']),
    ("", ["empty"]),
    ("   ", ["empty"]),
    ("please", ["asks for nothing"]),
    ("mvoe A around B", ['"mvoe" is not a verb', 'Did you mean "move"?']),
    ("jump A around B", ['"jump" is not a verb', "move, slide, push, shift, put"]),
    ("move around B", ["block to move"]),
])
def test_language_errors_say_what_was_not_understood(scene, sentence, words):
    with pytest.raises(LanguageError) as e:
        parse(sentence, scene, PHRASES)
    msg = str(e.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, msg


@pytest.mark.parametrize("sentence, words", [
    ("move C around B", ['"C"', "A (red), B (green)"]),
    ("move the purple block around B", ["no purple block"]),
    ("move the red bloc around B", ['Did you mean "the red block"?']),
    ("move the rde block around B", ['"rde" is not a colour', 'Did you mean "red"?']),
])
def test_unknown_objects(scene, sentence, words):
    with pytest.raises(UnknownObjectError) as e:
        parse(sentence, scene, PHRASES)
    for w in words:
        assert w in str(e.value), str(e.value)


def test_ambiguous_colour(crowded):
    with pytest.raises(LanguageError, match=r"ambiguous: 2 blue blocks \(C, D\)"):
        parse("move the blue block next to A", crowded, PHRASES)


def test_no_installed_phrases(scene):
    with pytest.raises(LanguageError, match="no action plugins"):
        parse("move A around B", scene, {})


def test_exact_name_beats_determiner(scene):
    odd = Scene([SceneObject("a", "red", 0.05, (0.1, 0.0)), SceneObject("the cube", "blue", 0.05, (-0.1, 0.0))])
    cmd = parse("move a around the cube", odd.validate(), PHRASES)
    assert (cmd.mover, cmd.anchor) == ("a", "the cube")


@pytest.mark.parametrize("sentence, said", [
    ("move A around B, then", '"then"'), ("move A past B and then", '"and then"'),
    ("move the red block next to B after that", '"after that"'),
])
def test_a_sentence_ending_with_a_joining_word_says_no_clause_follows(scene, sentence, said):
    """Not 'no block called "B then"' (audit, 2026-11-27): the slip is the dangling join, not the block."""
    with pytest.raises(LanguageError, match=f"ends with {said} but no clause follows"):
        parse(sentence, scene, PHRASES)


def test_two_blocks_after_a_one_block_preposition_say_so(crowded):
    with pytest.raises(LanguageError, match='"around" takes one reference block, but "B and C" names two'):
        parse("move A around B and C", crowded, PHRASES)
    assert parse("move A around B", crowded, PHRASES).anchor == "B"  # and a block named like a join still parses
    named = Scene(
        [SceneObject("A", "red", 0.05, (0.1, 0.0)), SceneObject("then", "green", 0.05, (0.0, 0.1))]
    ).validate()
    assert parse("move A around then", named, PHRASES).anchor == "then"
