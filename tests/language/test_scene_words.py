"""The words for a scene's objects (their names, fond forms, kinds and the kinds' everyday names) are made once per
scene, not once per word looked up: reading one sentence asks for them hundreds of times. What they are depends on
the objects' names and mesh files alone, so a scene changed in place is read afresh, and an answer a caller changes
changes nothing for the next. The polite openings and closings are looked up by the word they start or end with,
and the first of the table's order that fits is still the one read past."""

from __future__ import annotations

import itertools

from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.language import naming, synonyms, words
from l2p_bullet.language.naming import name_words
from l2p_bullet.language.synonyms import kind_groups, kind_words


def _mugs() -> Scene:
    mesh = "pybullet_data:objects/mug.obj"
    return Scene([SceneObject("m1", "white", 0.05, (0.1, 0.0), shape="mesh", mesh=mesh),
                  SceneObject("duck", "yellow", 0.05, (0.0, 0.1)),
                  SceneObject("m2", "red", 0.05, (-0.1, 0.0), shape="mesh", mesh=mesh)])


def test_a_scenes_words_are_made_once_and_follow_its_objects():
    synonyms.kind_groups_of.cache_clear()
    naming.name_words_of.cache_clear()
    scene = _mugs()
    assert kind_groups(scene)["cup"] == frozenset({"m1", "m2"}) and kind_words(scene)["bird"] == "duck"
    first = name_words(scene)
    assert first["ducky"] == "duck" and first["m1"] == "m1" and "mug" not in first  # two mugs: "mug" names neither
    for _ in range(5):
        assert name_words(_mugs()) == first and kind_groups(scene) == kind_groups(_mugs())
    assert synonyms.kind_groups_of.cache_info().misses == 1 and naming.name_words_of.cache_info().misses == 1
    first["cup"] = "m1"  # what a caller does with its answer is its own
    kind_groups(scene)["mug"] = frozenset({"m1"})
    assert "cup" not in name_words(scene) and kind_groups(scene)["mug"] == frozenset({"m1", "m2"})
    scene.objects[2] = SceneObject("m2", "red", 0.05, (-0.1, 0.0))  # no longer a mug: the other is the one mug
    assert name_words(scene)["cup"] == "m1" and kind_words(scene)["mug"] == "m1"


def _scan(low: list[str], table) -> tuple[str, ...] | None:
    """The first entry of the whole table that starts ``low`` (the old way: every entry tried)."""
    return next((e for e in table if tuple(low[: len(e)]) == e), None)


def test_the_polite_words_are_found_by_their_first_and_last_word_in_the_tables_order():
    for table, index, at in ((words.POLITE_PREFIXES, words._PREFIXES_BY_FIRST, 0),
                             (words.POLITE_SUFFIXES, words._SUFFIXES_BY_LAST, -1)):
        assert [e for entries in index.values() for e in entries] == sorted(table, key=lambda e: (
            list(index).index(e[at]), table.index(e)))
        for entries in index.values():
            assert [table.index(e) for e in entries] == sorted(table.index(e) for e in entries)
    table = words.POLITE_PREFIXES
    vocabulary = sorted({w for e in table for w in e})[:40]
    for low in itertools.product(vocabulary[:12], repeat=2):
        low = [*low, "push", "A"]
        want = _scan(low, table)
        got = next((e for e in words._PREFIXES_BY_FIRST.get(low[0], ()) if tuple(low[: len(e)]) == e), None)
        assert got == want, low
    assert words.strip_polite("Could you please push A past B please thank you".split()) == "push A past B".split()
    assert words.strip_polite("please".split()) == []
