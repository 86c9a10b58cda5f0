"""Colours as scene files write them: "grey", "silver", "navy", "light blue", "#c0c0c0" are shades of the twelve
basic colours. A scene with them loads, is drawn in each shade's own colour, is written back as it was written, and
its objects are called by the basic colour people call them by or by the shade itself."""

from __future__ import annotations

import json

import pytest

from l2p_bullet.chain.clauses import resolve_clauses
from l2p_bullet.core import colours
from l2p_bullet.core.scene import COLORS, Scene, SceneObject, load_scene
from l2p_bullet.embodiment.sim.world import World
from l2p_bullet.errors import L2PError, SceneError
from l2p_bullet.plugins import registry


@pytest.mark.parametrize("written, basic", [
    ("grey", "gray"), ("Grey", "gray"), ("silver", "gray"), ("navy", "blue"), ("gold", "yellow"), ("beige", "brown"),
    ("teal", "cyan"), ("maroon", "red"), ("magenta", "pink"), ("olive", "green"), ("violet", "purple"),
    ("light blue", "blue"), ("dark green", "green"), ("navy blue", "blue"), ("sky-blue", "blue"),
    ("light grey", "gray"), ("steelblue", "blue"), ("forestgreen", "green"), ("clear", "white"),
    ("#c0c0c0", "gray"), ("#F00", "red"), ("#1f3a93", "blue"), ("red", "red"),
])
def test_a_written_colour_is_a_shade_of_the_basic_colour_people_call_it(written, basic):
    got, shade = colours.read(written)
    assert got == basic
    assert shade == (None if written == basic else " ".join(written.lower().split()))


def test_every_colour_name_a_scene_may_write_has_a_basic_colour_and_a_colour_of_its_own():
    for name in colours.names():
        assert colours.basic_of(name) in COLORS, name
        assert all(0.0 <= c <= 1.0 for c in colours.rgb(name)), name
    assert colours.rgb("dark blue") != colours.rgb("blue") != colours.rgb("light blue")


@pytest.mark.parametrize("written", ["blurple", "dark", "red2", "#12345", "light"])
def test_a_word_that_is_no_colour_is_refused_with_the_colours_a_file_may_write(tmp_path, written):
    p = tmp_path / "s.json"
    p.write_text(json.dumps({"objects": [{"name": "A", "color": written, "size": 0.04, "xy": [0.1, 0.0]}]}))
    with pytest.raises(SceneError, match=r'unknown colour .*or a shade of one such as "navy"'):
        load_scene(p)


def _shaded(tmp_path):
    objects = [{"name": "A", "color": "silver", "size": 0.04, "xy": [0.1, 0.1]},
               {"name": "B", "color": "gray", "size": 0.04, "xy": [-0.1, 0.1]},
               {"name": "C", "color": "Light Blue", "size": 0.04, "xy": [0.1, -0.1]},
               {"name": "D", "color": "blue", "size": 0.04, "xy": [-0.1, -0.1]},
               {"name": "E", "color": "gold", "size": 0.04, "xy": [0.0, 0.2]},
               {"name": "F", "color": "#ff8800", "size": 0.04, "xy": [0.0, -0.2]}]
    p = tmp_path / "shades.json"
    p.write_text(json.dumps({"objects": objects}))
    return load_scene(p), objects


def test_a_scene_of_shades_loads_and_is_written_back_as_written(tmp_path):
    scene, objects = _shaded(tmp_path)
    assert [(o.color, o.shade) for o in scene.objects] == [
        ("gray", "silver"), ("gray", None), ("blue", "light blue"), ("blue", None), ("yellow", "gold"),
        ("orange", "#ff8800")]
    assert [o["color"] for o in scene.to_dict()["objects"]] == ["silver", "gray", "light blue", "blue", "gold",
                                                                "#ff8800"]
    again = tmp_path / "again.json"
    again.write_text(json.dumps(scene.to_dict()))
    assert load_scene(again) == scene


def test_a_shade_that_is_not_of_its_colour_is_refused():
    with pytest.raises(SceneError, match='the shade "navy" is not a shade of red'):
        Scene([SceneObject("A", "red", 0.04, (0.1, 0.0), shade="navy")]).validate()


def test_each_object_is_drawn_in_its_shades_own_colour(tmp_path):
    scene, _ = _shaded(tmp_path)
    with World(scene, visuals=False) as world:
        drawn = {o.name: world.sim.visual_shapes(o.name)[0]["rgba"] for o in scene.objects}
    assert drawn["A"] == pytest.approx([192 / 255] * 3 + [1.0], abs=1e-6)  # silver, not the basic grey
    assert drawn["B"] == pytest.approx(COLORS["gray"], abs=1e-6)
    assert drawn["F"] == pytest.approx([1.0, 0x88 / 255, 0.0, 1.0], abs=1e-6)
    assert drawn["C"] != drawn["D"]


@pytest.mark.parametrize("sentence, expect", [
    ("move the silver block next to the gold block", ("A", "E")),  # silver, beside a plain grey one
    ("move the light blue block around the orange one", ("C", "F")),
    ("move the light-blue cube past the yellow one", ("C", "E")),
    ("move the golden block away from the silver one", ("E", "A")),
])
def test_an_object_is_called_by_its_shade_or_its_basic_colour(tmp_path, sentence, expect):
    scene, _ = _shaded(tmp_path)
    (clause,) = resolve_clauses(sentence, scene, registry.discover())
    assert (clause.command.mover, *clause.command.anchors) == expect


def test_a_basic_colour_said_among_shades_of_it_is_the_one_the_file_calls_so(tmp_path):
    scene, _ = _shaded(tmp_path)
    for sentence, expect in (("move the blue block next to E", ("D", "E")), ("move the grey block past C", ("B", "C"))):
        (clause,) = resolve_clauses(sentence, scene, registry.discover())
        assert (clause.command.mover, *clause.command.anchors) == expect, sentence


def test_a_shade_word_is_never_mended_into_another_word_and_a_slip_in_it_is_mended(tmp_path):
    p = tmp_path / "s.json"
    p.write_text(json.dumps({"objects": [{"name": "A", "color": "burgundy", "size": 0.04, "xy": [0.1, 0.1]},
                                         {"name": "B", "color": "tan", "size": 0.04, "xy": [-0.1, 0.1]},
                                         {"name": "C", "color": "mauve", "size": 0.04, "xy": [0.1, -0.1]}]}))
    scene, plugins = load_scene(p), registry.discover()
    for sentence, expect in (("mvoe the mauve block next to the tan one", ("C", "B")),  # not "move the move block"
                             ("move the burgandy block past the mauve one", ("A", "C"))):
        (clause,) = resolve_clauses(sentence, scene, plugins)
        assert (clause.command.mover, *clause.command.anchors) == expect, sentence


def test_a_basic_colour_said_by_its_own_name_is_the_object_the_file_calls_so(tmp_path):
    """"the grey cube" beside a silver one is the grey one (people who mean the silver one say silver); "the blue
    cube" beside a navy one and a light blue one, neither called blue by the file, stays ambiguous."""
    p = tmp_path / "s.json"
    p.write_text(json.dumps({"objects": [{"name": "A", "color": "silver", "size": 0.04, "xy": [0.1, 0.1]},
                                         {"name": "B", "color": "grey", "size": 0.04, "xy": [-0.1, 0.1]},
                                         {"name": "C", "color": "navy", "size": 0.04, "xy": [0.1, -0.1]},
                                         {"name": "D", "color": "light blue", "size": 0.04, "xy": [-0.1, -0.1]}]}))
    scene, plugins = load_scene(p), registry.discover()
    (clause,) = resolve_clauses("move the grey cube next to the navy one", scene, plugins)
    assert (clause.command.mover, *clause.command.anchors) == ("B", "C")
    with pytest.raises(L2PError, match="ambiguous"):
        resolve_clauses("move the blue cube next to the grey one", scene, plugins)
