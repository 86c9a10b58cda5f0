"""``perform`` asks which object a word no object has means ("the tin" on a bar whose shaker is called "shaker"),
performs with the answer, and keeps the word in the scene file only on a yes; Enter refuses as before, and a script
(not a terminal, or ``--json``) is never asked."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from l2p_bullet.chain.clauses import resolve_clauses
from l2p_bullet.cli import main
from l2p_bullet.commands.asking import ask_words, keep_words
from l2p_bullet.core.scene import load_scene
from l2p_bullet.errors import UnknownObjectError
from l2p_bullet.plugins import registry

BAR = Path(__file__).parents[1] / "language" / "heldout109_scene.json"
"""shaker, jigger, lime, rocks_glass, bottle, bar_mat."""


def _bar(tmp_path: Path) -> Path:
    return Path(shutil.copy(BAR, tmp_path / "bar.json"))


def _perform(tmp_path: Path, *args: str, answers: str = ""):
    return CliRunner().invoke(main, ["perform", "tin next to the wedge", "--scene", str(tmp_path / "bar.json"),
                                     "--no-render", "-q", "--out", str(tmp_path / "run"), *args], input=answers)


def test_the_words_asked_for_are_performed_and_kept_on_a_yes(tmp_path):
    scene_file = _bar(tmp_path)
    r = _perform(tmp_path, "--ask", answers="Shaker\ncork\nthe green one\n\ny\n")  # a name in any case, a name no
    # object has (asked again), a description ("the green one": the lime)
    assert r.exit_code == 0, r.output
    assert 'Which object is "tin"?' in r.output and 'Which object is "wedge"?' in r.output
    assert 'no block called "cork"' in r.output and "Say one of: shaker, jigger" in r.output
    assert "Read with your words as: slide shaker next-to lime. Go on?" in r.output
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert (summary["mover"], summary["anchor"], summary["success"]) == ("shaker", "lime", True)
    kinds = {o["name"]: o.get("kind") for o in json.loads(scene_file.read_text())["objects"]}
    assert kinds == {"shaker": "tin", "jigger": None, "lime": "wedge", "rocks_glass": None, "bottle": None,
                     "bar_mat": None}
    said = resolve_clauses("move the tin past the wedge", load_scene(scene_file), registry.discover())
    assert [(c.command.mover, c.command.anchor) for c in said] == [("shaker", "lime")]  # read without asking


@pytest.mark.parametrize(("answers", "said"), [
    ("\n", 'error: no block called "tin"'),  # Enter: refused as before
    ("shaker\nlime\nn\n", "read as slide shaker next-to lime is not what was meant"),  # no to the reading
])
def test_enter_or_a_no_to_the_reading_performs_and_writes_nothing(tmp_path, answers, said):
    scene_file = _bar(tmp_path)
    before = scene_file.read_bytes()
    r = _perform(tmp_path, "--ask", answers=answers)
    assert r.exit_code == 2 and said in r.output
    assert scene_file.read_bytes() == before and not (tmp_path / "run").exists()


def test_a_script_is_never_asked(tmp_path):
    _bar(tmp_path)
    r = _perform(tmp_path, answers="shaker\nlime\ny\n")  # not a terminal: no question, the refusal
    assert r.exit_code == 2 and "Which object" not in r.output
    r = _perform(tmp_path, "--json", answers="shaker\nlime\ny\n")
    out = json.loads(r.stdout)
    assert (out["ok"], out["unknown_word"]) == (False, "tin") and "Which object" not in r.output


def test_a_no_keeps_the_file_and_a_kind_it_had_is_kept(tmp_path):
    scene_file = _bar(tmp_path)
    raw = json.loads(scene_file.read_text())
    raw["objects"][0]["kind"] = "cocktail shaker"
    scene_file.write_text(json.dumps(raw))
    answers = iter(["shaker", "lime"])
    scene, taught = ask_words("move the tin next to the wedge", load_scene(scene_file), registry.discover(),
                              prompt=lambda *a, **k: next(answers), confirm=lambda *a, **k: True)
    assert taught == {"tin": "shaker", "wedge": "lime"}
    assert scene.get("shaker").kind == "cocktail shaker tin" and scene.get("lime").kind == "wedge"
    before = scene_file.read_bytes()
    assert not keep_words(str(scene_file), taught, confirm=lambda *a, **k: False)
    assert scene_file.read_bytes() == before
    assert keep_words(str(scene_file), taught, confirm=lambda *a, **k: True)
    assert load_scene(scene_file).get("shaker").kind == "cocktail shaker tin"
    assert not list(tmp_path.glob(".*.new"))


def test_a_word_that_cannot_be_a_kind_is_not_asked(tmp_path):
    _bar(tmp_path)
    asked = []
    with pytest.raises(UnknownObjectError) as e:  # digits: a kind is words of letters
        ask_words("move the thing2 next to the lime", load_scene(tmp_path / "bar.json"), registry.discover(),
                  prompt=lambda *a, **k: asked.append(a) or "shaker")
    assert 'no block called "the thing2"' in str(e.value) and not asked


def test_plan_asks_too_and_its_plan_records_the_words(tmp_path):
    _bar(tmp_path)
    r = CliRunner().invoke(main, ["plan", "tin next to the wedge", "--scene", str(tmp_path / "bar.json"), "--ask",
                                  "--no-plot", "--out", str(tmp_path / "plan")], input="shaker\nlime\n\nn\n")
    assert r.exit_code == 0, r.output
    plan = json.loads((tmp_path / "plan" / "plan.json").read_text())
    kinds = {o["name"]: o.get("kind") for o in plan["scene"]["objects"]}
    assert (kinds["shaker"], kinds["lime"]) == ("tin", "wedge")  # replay PLAN.json reads the same words
    assert "kind" not in (tmp_path / "bar.json").read_text()  # no to keeping them


def test_a_word_read_as_a_colour_is_asked_too():
    """"the tucker box" reads "tucker" as a colour no object has: asked, "tucker" calls the sandwich box ("the sanger
    box" is not asked about: "sanger" may be a slip of "orange", and a colour's slip is never taught as a kind)."""
    picnic = load_scene(Path(__file__).parents[1] / "language" / "heldout116_scene.json")
    answers = iter(["napkins", "sandwich_box"])
    scene, taught = ask_words("put the serviettes snug up against the tucker box", picnic, registry.discover(),
                              prompt=lambda *a, **k: next(answers), confirm=lambda *a, **k: True)
    assert taught == {"serviettes": "napkins", "tucker": "sandwich_box"}
    with pytest.raises(UnknownObjectError, match="Did you mean"):
        ask_words("put the napkins snug up against the sanger box", picnic, registry.discover(),
                  prompt=lambda *a, **k: pytest.fail("asked about a slip of a colour"))


def test_a_scene_file_given_by_a_link_stays_a_link(tmp_path):
    target = _bar(tmp_path)
    link = tmp_path / "link.json"
    link.symlink_to(target)
    assert keep_words(str(link), {"tin": "shaker"}, confirm=lambda *a, **k: True)
    assert link.is_symlink() and load_scene(target).get("shaker").kind == "tin"


def test_a_description_still_unknown_after_its_word_asks_its_word_before():
    """"the tablet strip": "strip" answered as the blister pack still leaves "tablet" unread, so "tablet" is asked."""
    pharmacy = load_scene(Path(__file__).parents[1] / "language" / "heldout114_scene.json")
    asked, answers = [], iter(["blister_pack", "blister_pack"])
    scene, taught = ask_words("Put the tablet strip near to the cream tube.", pharmacy, registry.discover(),
                              prompt=lambda q, **k: asked.append(q.split('"')[1]) or next(answers),
                              confirm=lambda *a, **k: True)
    assert asked == ["strip", "tablet"]  # "the cream tube" is the hand cream already
    assert taught == {"strip": "blister_pack", "tablet": "blister_pack"}
    said = resolve_clauses("Put the tablet strip near to the cream tube.", scene, registry.discover())
    assert [(c.command.mover, c.command.anchor) for c in said] == [("blister_pack", "hand_cream")]


def test_a_verbless_commands_unknown_description_is_asked_about(tmp_path):
    """"the old tin next to the wedge" (no verb, no object called so): its words are asked about as a command's."""
    asked: list[str] = []
    answers = iter(["shaker", "lime"])

    def prompt(question: str, **_: object) -> str:
        asked.append(question.split("?")[0])
        return next(answers)

    scene, taught = ask_words("the old tin next to the wedge", load_scene(BAR), registry.discover(), prompt=prompt,
                              confirm=lambda *a, **k: True)
    assert asked == ['Which object is "tin"', 'Which object is "wedge"']
    assert taught == {"tin": "shaker", "wedge": "lime"}
    said = resolve_clauses("the old tin next to the wedge", scene, registry.discover())
    assert [(c.command.mover, c.command.action, c.command.anchor) for c in said] == [("shaker", "next-to", "lime")]
