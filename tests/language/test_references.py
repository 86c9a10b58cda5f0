"""Object references as people say them: shape nouns that restrict, size adjectives, a kind's everyday names,
"that cylinder" and "the other red cube" across clauses, relations to "you", and typos in reference words.

Two tables: the corpus's (three 4 cm cubes, a flat box, the duck, a tall cylinder) and heldout5's (a 5 cm and a
3 cm red cube, a white cube and a white mug, a gray can, a short blue cylinder F, a green box D)."""

from __future__ import annotations

import pytest
from corpus import REFUSE, resolve, scene, score

from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.errors import LanguageError, UnknownObjectError
from l2p_bullet.language import Context, resolve_object


@pytest.fixture(scope="module")
def two_reds() -> Scene:
    return scene("heldout5.tsv")


@pytest.fixture(scope="module")
def six() -> Scene:
    return scene("corpus.tsv")


def _refused(text: str, s: Scene, context: Context | None = None) -> str:
    with pytest.raises((LanguageError, UnknownObjectError)) as e:
        resolve_object(text, s, context=context)
    return str(e.value)


@pytest.mark.parametrize("text, name", [
    ("the white cube", "C"),   # the mug is white too, and no cube
    ("the white block", "C"),  # several white objects: the block-shaped one is meant
    ("the white box", "C"),
    ("the green box", "D"),
    ("the gray can", "can"),
])
def test_shape_nouns_restrict(two_reds, text, name):
    assert resolve_object(text, two_reds) == name


def test_block_covers_any_object_when_the_rest_picks_one(six):
    """The first corpus's author calls the purple cylinder "the purple block": a colour alone decides there."""
    assert resolve_object("the purple block", six) == "E"
    assert resolve_object("the red box", six) == "A"


def test_a_block_is_never_a_mesh_of_another_kind(two_reds, six):
    """A mug, a duck or a bottle is no block: "the big white block" beside a big white mug is the white cube, and
    "the block" alone never lists the duck."""
    assert resolve_object("the big white block", two_reds) == "C"
    assert "duck" not in _refused("the block", six)


@pytest.mark.parametrize("text, said", [
    ("the blue cube", "nothing in the scene"),  # the only blue object is a cylinder
    ("the white one", "C, mug"),
    ("the cylinder", "can, F"),
])
def test_a_shape_noun_that_fits_nothing_or_two_readings_is_refused(two_reds, text, said):
    assert said in _refused(text, two_reds)


@pytest.mark.parametrize("text, name", [
    ("the big red cube", "A"), ("the large red cube", "A"), ("the bigger red cube", "A"),
    ("the small red cube", "B"), ("the tiny red block", "B"), ("the little red block", "B"),
    ("the smaller red one", "B"),
    ("the big white thing", "mug"), ("the small white thing", "C"),
    ("the short cylinder", "F"), ("the tall cylinder", "can"), ("the small cube", "B"),
])
def test_size_adjectives_decide_among_what_the_rest_leaves(two_reds, text, name):
    assert resolve_object(text, two_reds) == name


def test_sizes_that_differ_little_are_a_tie(two_reds, six):
    assert "mug, can" in _refused("the tall one", two_reds)      # 10 and 11 cm
    # big / small compare bulk, as "the biggest" does: a 3 cm cube (27 cm3) is smaller than a 4 cm-wide, 4 cm-tall
    # cylinder (64 cm3) though their footprints' areas are 3.0 and 3.6 cm squared
    assert resolve_object("the small one", two_reds) == "B"
    assert "A, B, C" in _refused("the big cube", six)            # three 4 cm cubes
    assert "A, B, C" in _refused("the small cube", six)          # three 4 cm cubes
    assert resolve_object("the tall one", six) == "E"            # 9 cm among 4-6 cm
    assert resolve_object("the little red cube", six) == "A"     # one red object: the size word is read past


@pytest.mark.parametrize("text, name", [
    ("the cup", "mug"), ("the coffee mug", "mug"), ("the white coffee cup", "mug"),
    ("the tin can", "can"), ("the soda can", "can"),
])
def test_a_kinds_everyday_name(two_reds, text, name):
    assert resolve_object(text, two_reds) == name


def test_a_kinds_name_resolves_only_where_one_object_is_of_that_kind(six):
    assert resolve_object("the bird", six) == "duck"
    assert resolve_object("the rubber duck", six) == "duck"
    mugs = Scene((SceneObject("m1", "white", 0.05, (0.1, 0.0), shape="mesh", mesh="pybullet_data:objects/mug.obj"),
                  SceneObject("m2", "red", 0.05, (-0.1, 0.0), shape="mesh", mesh="pybullet_data:objects/mug.obj"),
                  SceneObject("A", "green", 0.04, (0.0, 0.1))))
    assert "m1, m2" in _refused("the cup", mugs)                 # two mugs: never a guess
    assert resolve_object("the red mug", mugs) == "m2"           # the kind of a mesh: its file's stem


def test_that_cylinder_is_the_previous_clauses_cylinder(plugins, two_reds):
    got = resolve("Slide the green box toward the blue cylinder, then slide that cylinder toward the mug.",
                  two_reds, plugins)
    assert got == "slide:closer D F ; slide:closer F mug"
    assert resolve_object("this cube", two_reds, context=Context("F", "C")) == "C"
    with pytest.raises(LanguageError, match="ambiguous: F .* or C"):  # the block moved, or the one named last
        resolve_object("that block", two_reds, context=Context("F", "C"))
    assert resolve_object("that same block", two_reds, context=Context("F", "C")) == "F"
    assert "earlier clause" in _refused("that cylinder", two_reds)


def test_the_other_one_of_a_kind(plugins, two_reds):
    got = resolve("Move the big red cube toward the mug, then move the other red cube toward the mug too.",
                  two_reds, plugins)
    assert got == "slide:closer A mug ; slide:closer B mug"
    got = resolve("Move the white cube away from the can. Then move the other white object toward the can.",
                  two_reds, plugins)
    assert got == "slide:away C can ; slide:closer mug can"


def test_the_other_one_after_one_of_a_described_pair_is_its_twin(plugins, two_reds, six):
    """After "the small red cube", "the other one" is the other red cube (both authors who wrote so meant it);
    after a mover named by its letter it may as well be the anchor, and is asked."""
    assert resolve("Move the small red cube next to F, then move the other one next to the mug.",
                   two_reds, plugins) == "slide:next-to B F ; slide:next-to A mug"
    assert resolve("Move B next to F, then move the other one next to the mug.", two_reds, plugins) == REFUSE
    assert resolve("move A next to B, then move the other one around C", six, plugins) == \
        "slide:next-to A B ; slide:around B C"


@pytest.mark.parametrize("text, name", [
    ("the cube nearest to you", "B"),
    ("the red cube nearer to you", "B"),
    ("the red cube at the back", "A"),
    ("the red cube in the front", "B"),
    ("the object at the back", "can"),   # x 0.15 (away from the robot), A 0.10
    ("the frontmost object", "F"),       # x -0.15, B -0.12
    ("whatever is closest to the big red cube", "mug"),
    ("the object directly behind the white cube", "can"),
    ("the object farthest from the small red cube", "can"),
    ("the cube that is white", "C"),
])
def test_relations_as_people_say_them(two_reds, text, name):
    assert resolve_object(text, two_reds) == name


def test_distances_are_told_apart_against_their_length(two_reds, six):
    """3 cm decide "nearest" between 12 and 15 cm, not between 38.5 and 41.3 cm (F and B from the robot): asked;
    under 3 cm is asked at any length (B 16.4 cm and A 19.0 cm from the duck)."""
    assert "B, F" in _refused("the object nearest to you", two_reds)
    assert resolve_object("the one nearest A", six) == "E"  # E 12.0 cm from A, B 15.0 cm
    assert "A, B" in _refused("the block nearest the duck", six)


def test_a_relative_clause_reads_as_the_adjective(six):
    assert resolve_object("the cube that is red", six) == "A"
    assert resolve_object("the block which is closest to C", six) == "B"


@pytest.mark.parametrize("sentence, expect", [
    ("Please, move the blu cylnder around the mug.", "slide:around F mug"),
    ("move teh big red cube past the mug", "slide:past A mug"),
    ("move the tiny red blok past the cup", "slide:past B mug"),
])
def test_slips_in_reference_words_are_mended_in_a_refused_sentence(plugins, two_reds, sentence, expect):
    """The reader of typing slips (language/typos.py) knows the reference words, size words and kinds' names."""
    assert resolve(sentence, two_reds, plugins) == expect


def test_kind_names_and_size_words_are_known_words():
    from l2p_bullet.language.reference_words import REFERENCE_WORDS

    assert {"cup", "bird", "tiny", "bigger", "you", "whatever"} <= REFERENCE_WORDS


def test_what_a_relation_measures_from(six, two_reds):
    """For "move the object nearest the cylinder away from it": "it" is what the mover's relation measures from."""
    from l2p_bullet.language.references import measured_from

    assert measured_from("the object nearest the cylinder", six) == "E"
    assert measured_from("the object closest to the green box", two_reds) == "D"
    assert measured_from("the object nearest to you", two_reds) is None
    assert measured_from("the big red cube", two_reds) is None


@pytest.mark.slow
@pytest.mark.parametrize("name, reached", [("heldout4.tsv", {"reference": 19, "relation": 19}),
                                           ("heldout5.tsv", {"reference": 19, "relation": 18})])
def test_the_fourth_and_fifth_authors_references(plugins, name, reached):
    """Written cold and read once (docs/language.md); the reference rules they prompted keep their references and
    relations reached, and no reference, relation or pronoun sentence resolved wrong (a refusal beats a wrong
    block)."""
    table, misses = score(plugins, name)
    wrong = [(c.sentence, got) for c, got in misses
             if got != REFUSE and c.category in ("reference", "relation", "pronoun")]
    assert not wrong, f"wrong resolutions: {wrong}"
    for category, least in reached.items():
        assert table[category]["right"] >= least, (category, dict(table[category]))
