"""Manners of motion (issue 23): the registry, the verb that picks a manner, the physical signatures, and the
errors for a verb or manner that does not exist. No simulator here (tests/embodiment/test_manners_sim.py)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from l2p_bullet.arms import PANDA
from l2p_bullet.core.scene import Scene, SceneObject, default_scene
from l2p_bullet.embodiment.manners import carry_lift, carry_refusal, push_outline
from l2p_bullet.errors import InfeasibleError, LanguageError
from l2p_bullet.judge.manners import signature_verdict
from l2p_bullet.language import parse
from l2p_bullet.manners import registry
from l2p_bullet.manners.spec import MannerSpec
from l2p_bullet.pipeline import prepare, resolve

PHRASES = {"past": "past", "next to": "next-to", "around": "around", "closer to": "closer"}


def test_the_builtins_register_through_the_entry_point_group():
    from importlib import metadata

    found = {e.name: e.value for e in metadata.entry_points(group=registry.GROUP)}
    assert found == {"slide": "l2p_bullet.manners.slide", "carry": "l2p_bullet.manners.carry",
                     "push": "l2p_bullet.manners.push"}
    names = [m.name for m in registry.discover()]
    assert names == sorted(names) and set(names) >= {"slide", "carry", "push"}
    assert registry.broken() == []
    table = registry.verb_table()
    assert table["drag"] == "slide" and table["bring"] == "slide" and table["shove"] == "push"
    assert table["pick up ... and put"] == "carry"


@pytest.mark.parametrize("sentence, verb, manner", [
    ("move A past B", "move", "slide"),
    ("slide A past B", "slide", "slide"),
    ("drag the red block next to the green one", "drag", "slide"),
    ("put A next to B", "put", "slide"),
    ("carry A around B", "carry", "carry"),
    ("bring A next to B", "bring", "slide"),
    ("lift A and put it next to B", "lift", "carry"),
    ("Please pick up the red block and put it next to the green one.", "pick up", "carry"),
    ("push A past B", "push", "push"),
    ("nudge A closer to B", "nudge", "push"),
    ("shove the red cube past B", "shove", "push"),
])
def test_the_verb_picks_the_manner(sentence, verb, manner):
    cmd = parse(sentence, default_scene(), PHRASES)
    assert (cmd.verb, cmd.manner, cmd.mover, cmd.anchor) == (verb, manner, "A", "B")


def test_an_unknown_verb_is_one_line_with_did_you_mean():
    with pytest.raises(LanguageError, match=r'"crry" is not a verb I know \(known: move, slide, push, shift, put, '
                                            r'.*carry.*\)\. Did you mean "carry"\?'):
        parse("crry A past B", default_scene(), PHRASES)
    with pytest.raises(LanguageError, match=r'"pick" asks for "pick \.\.\. up and put"'):
        parse("pick A up past B", default_scene(), PHRASES)


def test_lifting_toward_a_place_is_a_carry():
    """"lift A past B", "pick up A next to B": the lift says the manner, the preposition where it ends."""
    for sentence, action in (("lift A past B", "past"), ("pick up A next to B", "next-to")):
        cmd = parse(sentence, default_scene(), PHRASES)
        assert (cmd.manner, cmd.action, cmd.mover, cmd.anchor) == ("carry", action, "A", "B")


def test_an_unknown_manner_is_one_line_with_did_you_mean():
    from l2p_bullet.errors import UnknownPluginError

    with pytest.raises(UnknownPluginError, match=r'^unknown manner "cary" \(known: carry, push, slide\)\. '
                                                 r'Did you mean "carry"\? List them with: l2p-bullet manners$') as e:
        registry.get("cary")
    assert (e.value.kind, e.value.name, e.value.known) == ("manner", "cary", ("carry", "push", "slide"))
    assert registry.get(None).name == "slide"
    with pytest.raises(ValueError, match="motion must be one of"):
        MannerSpec("fly", ("fly",), motion="fly", signature="lifted")


def test_a_carry_refuses_an_object_wider_than_the_gripper_before_anything_moves():
    scene = default_scene()
    assert carry_refusal(scene, "A") is None
    narrow = replace(PANDA, gripper_opening=0.03)
    why = carry_refusal(scene, "A", narrow)
    assert why is not None and "5.0 cm wide" in why and "opens 3.0 cm" in why
    big = Scene([SceneObject("A", "red", 0.08, (0.08, -0.08), 0.0), SceneObject("B", "green", 0.05, (0.0, 0.05), 0.0)])
    cmd = resolve("carry A past B", big)
    assert cmd.manner == "carry"
    prepare("carry A past B", big)  # 8 cm: the Panda's fingers open 8 cm, so it is carried


def test_a_carry_refuses_an_object_heavier_than_the_arms_payload_by_the_scene_files_mass():
    """The scene file's "mass" is what counts (a 0.1 kg block unless it says), against the chosen arm's payload."""
    data = {"objects": [{"name": "A", "color": "red", "size": 0.05, "xy": [0.08, -0.08], "mass": 4.0},
                        {"name": "B", "color": "green", "size": 0.05, "xy": [0.0, 0.05]}]}
    heavy = Scene.from_dict(data)
    assert heavy.get("A").mass == 4.0
    with pytest.raises(InfeasibleError) as e:
        prepare("carry A past B", heavy)
    assert e.value.check == "carry" and "weighs 4 kg" in str(e.value) and "panda lifts at most 3 kg" in str(e.value)
    prepare("slide A past B", heavy)  # sliding or pushing it is not lifting it
    prepare("carry A past B", heavy, arm="xarm6")  # the xArm6's rated payload is 5 kg
    assert carry_refusal(default_scene(), "A") is None  # a block without "mass" weighs 0.1 kg


def test_carry_lift_clears_the_tallest_object_under_the_path():
    scene = Scene([SceneObject("A", "red", 0.04, (0.10, 0.0), 0.0), SceneObject("B", "green", 0.06, (0.0, 0.0), 0.0),
                   SceneObject("C", "blue", 0.08, (0.0, 0.18), 0.0)])
    over_b = np.array([[0.10, 0.0, 0.0], [-0.10, 0.0, 0.0]])
    assert carry_lift(scene, "A", over_b) == pytest.approx(0.06 + 0.02)  # C is far from the path
    away = np.array([[0.10, 0.0, 0.0], [0.10, -0.15, 0.0]])
    assert carry_lift(scene, "A", away) == pytest.approx(0.03)  # nothing under it: the least lift


def test_the_push_outline_holds_the_block_and_the_pusher():
    r = np.linalg.norm(push_outline(0.04), axis=1)
    assert np.allclose(r, r[0]) and r[0] > 0.04 / np.sqrt(2) and r[0] < 0.04


def _frames(zs, size=0.04, grasped=None, opening=0.0):
    return [{"poses": {"A": [0.0, 0.0, size / 2 + z, 0.0]}, "grasped": grasped,
             "gripper": {"opening_m": opening, "holding": grasped, "contact": None}} for z in zs]


def test_the_physical_signatures():
    assert signature_verdict("on-table", _frames([0.0, 0.002, 0.0]), "A", 0.02).success
    assert not signature_verdict("on-table", _frames([0.0, 0.004, 0.0]), "A", 0.02).success
    assert signature_verdict("lifted", _frames([0.0, 0.03, 0.0]), "A", 0.02).success
    low = signature_verdict("lifted", _frames([0.0, 0.015, 0.0]), "A", 0.02)
    assert not low.success and "at least 2 cm" in low.reason
    assert not signature_verdict("lifted", _frames([0.0, 0.03, 0.02]), "A", 0.02).success  # never set down
    assert signature_verdict("no-grasp", _frames([0.0, 0.0]), "A", 0.02).success
    assert not signature_verdict("no-grasp", _frames([0.0, 0.0], grasped="A"), "A", 0.02).success
    assert not signature_verdict("no-grasp", _frames([0.0, 0.0], opening=0.01), "A", 0.02).success


def test_a_chain_keeps_each_clauses_manner():
    from l2p_bullet.chain.clauses import resolve_clauses
    from l2p_bullet.plugins import registry as plugins

    scene = Scene([SceneObject("A", "red", 0.04, (0.09, -0.06), 0.0), SceneObject("B", "green", 0.04, (0.0, 0.0), 0.0),
                   SceneObject("C", "blue", 0.04, (-0.1, 0.1), 0.0)])
    clauses = resolve_clauses("lift A and put it past B, then around C, then push C next to A", scene,
                              plugins.discover())
    assert [(c.command.manner, c.command.action, c.command.mover) for c in clauses] == [
        ("carry", "past", "A"), ("carry", "around", "A"), ("push", "next-to", "C")]


def test_infeasible_carry_is_refused_before_anything_moves():
    from l2p_bullet.embodiment.manners import check_manner

    narrow = replace(PANDA, gripper_opening=0.03)
    check_manner(registry.get("carry"), default_scene(), "A")
    check_manner(registry.get("slide"), default_scene(), "A", narrow)  # a slide does not close the fingers on it
    with pytest.raises(InfeasibleError, match="cannot carry \"A\": it is 5.0 cm wide") as e:
        check_manner(registry.get("carry"), default_scene(), "A", narrow)
    assert e.value.check == "carry"


def test_a_push_is_refused_where_the_hand_would_sweep_over_a_tall_block():
    from l2p_bullet.embodiment.manners import push_refusal

    scene = Scene([SceneObject("A", "red", 0.04, (0.10, 0.0), 0.0), SceneObject("B", "green", 0.04, (0.0, 0.0), 0.0),
                   SceneObject("C", "blue", 0.08, (0.0, 0.09), 0.0)])
    past = np.array([[0.10, -0.06, 0.0], [-0.10, -0.06, 0.0]])
    scene = scene.with_pose("A", np.array([0.10, -0.06, 0.0]))
    why = push_refusal(scene, "A", past)
    assert why is not None and '"C" (8 cm tall)' in why
    far = Scene([o if o.name != "C" else SceneObject("C", "blue", 0.08, (0.0, 0.22), 0.0) for o in scene.objects])
    assert push_refusal(far, "A", past) is None
    low = Scene([o if o.name != "C" else SceneObject("C", "blue", 0.04, (0.0, 0.09), 0.0) for o in scene.objects])
    assert push_refusal(low, "A", past) is None


def test_the_planner_lets_a_carried_block_pass_over_bystanders_but_not_over_the_anchor():
    from l2p_bullet.planning.world2d import World2D

    scene = Scene([SceneObject("A", "red", 0.04, (0.10, 0.0), 0.0), SceneObject("B", "green", 0.04, (0.0, 0.0), 0.0),
                   SceneObject("C", "blue", 0.04, (0.0, 0.12), 0.0)])
    start = np.array([0.10, 0.0, 0.0])
    through_b = np.array([[-0.10, 0.0, 0.0]])
    start_c = np.array([0.10, 0.12, 0.0])
    slide = World2D(scene, "A")
    assert (
        not slide.moves_free(start, through_b)[0] and not slide.moves_free(start_c, np.array([[-0.10, 0.12, 0.0]]))[0]
    )
    carry = World2D(scene, "A", over=frozenset({"C"}))  # C a bystander, B the anchor
    assert not carry.moves_free(start, through_b)[0]
    assert carry.moves_free(start_c, np.array([[-0.10, 0.12, 0.0]]))[0]  # over C
    assert not carry.moves_free(start_c, np.array([[0.0, 0.12, 0.0]]))[0]  # but not set down on it


def test_a_push_with_no_room_for_the_hand_behind_the_block_is_refused():
    from l2p_bullet.embodiment.manners import check_manner

    scene = Scene([SceneObject("A", "red", 0.04, (0.045, 0.0), 0.0), SceneObject("B", "green", 0.04, (0.0, 0.0), 0.0)])
    away = np.array([[0.045, 0.0, 0.0], [0.15, 0.0, 0.0]])
    with pytest.raises(InfeasibleError, match='no room for the pushing hand behind "A": it would come down on "B"'):
        check_manner(registry.get("push"), scene, "A", path=away)
    check_manner(registry.get("push"), scene, "A", path=np.array([[0.045, 0.0, 0.0], [0.045, 0.12, 0.0]]))


def test_a_carry_lifts_over_the_top_of_a_tall_object_not_its_side():
    """carry_lift clears the tallest object near the path by its height: a cylinder 8 cm tall and 4 cm wide
    (3.5 cm in blocks) beside the path needs the block lifted above 8 cm, not above 3.5 cm."""
    from l2p_bullet.embodiment.manners import CLEARANCE

    scene = Scene.from_dict({"objects": [
        {"name": "A", "color": "red", "size": 0.04, "xy": [0.1, 0.0], "yaw": 0.0},
        {"name": "B", "color": "green", "size": 0.04, "xy": [-0.1, 0.0], "yaw": 0.0},
        {"name": "C", "color": "blue", "shape": "cylinder", "radius": 0.02, "height": 0.08, "xy": [0.0, 0.05],
         "yaw": 0.0}]}).validate()
    path = np.array([[0.1, 0.0, 0.0], [-0.03, 0.0, 0.0]])  # passes 5 cm from the cylinder's axis
    assert carry_lift(scene, "A", path) >= 0.08 + CLEARANCE - 1e-9


def _manners_cli(*args: str, site=None) -> tuple[int, str]:
    """``l2p-bullet manners ARGS`` in a fresh Python (the registry is read once per process), with ``site``
    (a folder of installed-looking distributions) first on the path."""
    import os
    import subprocess
    import sys

    env = dict(os.environ)
    if site is not None:
        env["PYTHONPATH"] = os.pathsep.join(p for p in (str(site), env.get("PYTHONPATH")) if p)
    p = subprocess.run([sys.executable, "-m", "l2p_bullet.cli", "manners", *args], capture_output=True, text=True,
                       env=env, timeout=120)
    return p.returncode, p.stdout + p.stderr


def _manner_package(site, dist: str, version: str, specs: str, entry_points: str):
    """An installed-looking manner plugin in ``site``: the module ``dist`` with dashes as underscores holding
    ``specs`` (MannerSpec lines), and its distribution declaring ``entry_points`` in "l2p_bullet.manners"."""
    module = dist.replace("-", "_")
    (site / module).mkdir(parents=True)
    (site / module / "__init__.py").write_text("from l2p_bullet.manners.spec import MannerSpec\n" + specs)
    info = site / f"{module}-{version}.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: {version}\n")
    (info / "entry_points.txt").write_text("[l2p_bullet.manners]\n" + entry_points)
    return site


def test_manners_lists_every_manner_with_its_verbs_and_package():
    import json

    rc, out = _manners_cli()
    assert rc == 0, out
    lines = out.splitlines()
    assert lines[0].startswith("carry  carry, lift ... and put") and "[l2p-bullet " in lines[0]
    assert any(line.startswith("slide  slide, move") and "(and any verb no manner claims)" in line for line in lines)
    assert "(above the other objects)" in lines[1]  # carry is airborne
    rc, out = _manners_cli("--json")
    got = {m["name"]: m for m in json.loads(out)["manners"]}
    assert rc == 0 and set(got) == {"slide", "carry", "push"} and json.loads(out)["broken"] == []
    assert got["push"]["verbs"][:3] == ["push", "nudge", "shove"] and "give ... a push" in got["push"]["verbs"]
    assert got["push"]["signature"] == "no-grasp"
    assert got["carry"]["airborne"] and got["slide"]["default"]
    assert got["slide"]["over"] == "carry" and "move" in got["slide"]["loose"] and "drag" not in got["slide"]["loose"]
    assert any("where the other objects block its way: carry over them" in line for line in lines)


def test_a_third_party_manner_is_listed_and_a_broken_one_named_with_its_package(tmp_path):
    """A manner plugin installs like an action: an entry point in "l2p_bullet.manners". One that claims a
    built-in's verb is left out, named with its package (what to uninstall), and the listing exits 1."""
    import json

    site = _manner_package(tmp_path / "site", "l2p-roll", "0.3",
                           "MANNER = MannerSpec(name='roll', verbs=('roll',), motion='slide', signature='on-table', "
                           "description='rolls')\n"
                           "SHOVE = MannerSpec(name='shove2', verbs=('shove',), motion='push', signature='no-grasp')\n",
                           "roll = l2p_roll\nshove2 = l2p_roll:SHOVE\n")
    rc, out = _manners_cli(site=site)
    assert rc == 1, out
    assert "roll   roll  [l2p-roll 0.3]" in out
    assert 'shove2: the verb "shove" is already the manner "push"\'s (package l2p-roll 0.3)' in out
    rc, out = _manners_cli("--json", site=site)
    d = json.loads(out)
    assert rc == 1 and {m["name"] for m in d["manners"]} == {"slide", "carry", "push", "roll"}
    assert [b["name"] for b in d["broken"]] == ["shove2"]


def test_a_plugin_that_sorts_first_cannot_take_a_builtins_verb_or_name(tmp_path):
    """Entry points were read in name order, so a plugin whose entry point sorts before a built-in's ("poke"
    before "push", "aaa" before "carry") kept the verb or the name, and the built-in was listed as broken
    "(package l2p-bullet ...)": what to uninstall was the project itself. The built-ins are read first."""
    import json

    site = _manner_package(
        tmp_path / "site",
        "l2p-poke",
        "0.1",
        "MANNER = MannerSpec(name='poke', verbs=('poke', 'push'), motion='push', signature='no-grasp')\n"
        "CARRY = MannerSpec(name='carry', verbs=('tote',), motion='carry', signature='lifted', "
        "airborne=True)\n",
        "poke = l2p_poke\naaa = l2p_poke:CARRY\n",
    )
    rc, out = _manners_cli("--json", site=site)
    d = json.loads(out)
    assert rc == 1, out
    assert [m["name"] for m in d["manners"]] == ["carry", "push", "slide"], out
    assert {m["name"]: m["package"] for m in d["manners"]}["push"].startswith("l2p-bullet "), out
    broken = {b["name"]: b["error"] for b in d["broken"]}
    assert set(broken) == {"poke", "aaa"}, out
    assert all(r.endswith("(package l2p-poke 0.1)") for r in broken.values()), out
