"""Composite actions (l2p_bullet/composite): the list grammar, one plugin mechanism with two kinds, the
recipe learned from the shipped demonstrations, the row's clauses and slots, the target the planner
is given, the row verdict, and the teach page's checks of a row's drags."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from l2p_bullet.core.scene import Scene, load_scene
from l2p_bullet.errors import LanguageError, TeachError, UnknownObjectError

ROOT = Path(__file__).resolve().parents[2]
ROW = ROOT / "l2p_bullet" / "actions" / "row"


@pytest.fixture(scope="module")
def four() -> Scene:
    return load_scene(ROOT / "examples" / "four_blocks.json")


def test_a_list_of_blocks_is_read_in_order_by_name_or_colour(four):
    from l2p_bullet.language import parse_list

    phrases = {"make a row of": "row", "line up": "row"}
    c = parse_list("Please make a row of A, B, C and D.", four, phrases)
    assert (c.action, c.phrase, c.objects) == ("row", "make a row of", ("A", "B", "C", "D"))
    assert parse_list("line up the blue block, A and the green one", four, phrases).objects == ("C", "A", "B")
    assert parse_list("move A next to B", four, phrases) is None
    with pytest.raises(LanguageError, match="at least two blocks"):
        parse_list("line up A", four, phrases)
    with pytest.raises(LanguageError, match="more than once"):
        parse_list("line up A, B and A", four, phrases)
    with pytest.raises(UnknownObjectError):
        parse_list("line up A, B and Q", four, phrases)


def test_one_entry_point_group_two_kinds():
    from l2p_bullet.plugins import registry

    actions, composites = registry.discover(), registry.discover("composite")
    assert "row" not in {p.name for p in actions} and {"next-to", "around"} <= {p.name for p in actions}
    assert [p.name for p in composites if p.ok] == ["row"]
    assert "make a row of" not in registry.phrase_table(actions + composites)  # never a preposition
    assert registry.composites(actions)[0].name == "row"


def test_the_shipped_recipe_is_what_its_demonstrations_teach():
    """Re-learning from the shipped demos.json with the shipped actions gives the shipped recipe.json."""
    import json

    from l2p_bullet.composite.bundle import read_demos, read_recipe
    from l2p_bullet.composite.recipe import learn
    from l2p_bullet.recognition import recognisers

    demos = read_demos(ROW)
    assert 1 <= len(demos) <= 10 and {len(d.names) for d in demos} == {2, 3}
    recipe = learn(demos, recognisers()[0])
    assert recipe.to_dict() == json.loads((ROW / "recipe.json").read_text())
    assert read_recipe(ROW).to_dict() == recipe.to_dict()


def test_the_learned_gaps_are_where_the_drags_left_the_blocks():
    """The spacing is learned from where each drag put its block (its last sample), not from a frame
    short of it: until 2026-11-28 one gap of the shipped demonstrations read 0.2141 sides for 0.202."""
    from l2p_bullet.composite.bundle import read_demos
    from l2p_bullet.composite.recipe import learn, row_gaps
    from l2p_bullet.recognition import recognisers

    demos = read_demos(ROW)
    dropped, expected = [], []
    for d in demos:
        scene = Scene.from_dict(d.scene)
        xy = {o.name: np.asarray(o.xy, float) for o in scene.objects}
        for s in d.segments:
            xy[s.block] = np.asarray(s.samples[-1][1:3], float)
            dropped.append(float(np.hypot(*(s.track()[-1, :2] - xy[s.block]))))
        gaps, _, _ = row_gaps(np.array([xy[n] for n in d.names]), np.array([scene.get(n).size for n in d.names]))
        expected += [round(float(g), 4) for g in gaps]
    assert max(dropped) < 1e-9
    assert learn(demos, recognisers()[0]).evidence["gaps_sides"] == expected


def test_a_recipe_says_what_it_learned_and_refuses_what_it_cannot_perform():
    from l2p_bullet.composite.recipe import CompositeError, Recipe

    good = {"action": "next-to", "anchor": "previous", "stays": 0, "order": "named", "spacing": 0.2,
            "monotone": True, "axis_offset_deg": 0.0, "aligned": True, "demos": 3}
    assert Recipe.from_dict(good).spacing == 0.2
    for bad in ({"anchor": "middle"}, {"spacing": -1}, {"order": "any"}, {"demos": "x"}):
        with pytest.raises(CompositeError):
            Recipe.from_dict({**good, **bad})


def test_a_row_sentence_becomes_clauses_of_the_learned_action_with_slots_on_one_line(four):
    from l2p_bullet.chain import is_chain, resolve_clauses
    from l2p_bullet.composite.bundle import read_recipe
    from l2p_bullet.plugins import registry

    recipe = read_recipe(ROW)
    assert is_chain("make a row of A, B, C and D") and not is_chain("move A next to B")
    clauses = resolve_clauses("make a row of A, B, C and D", four, registry.discover())
    assert [c.text for c in clauses] == ["move B next to A", "move C next to B", "move D next to C"]
    # the slots as if each block landed where it should: one line, the learned pitch, A's yaw
    scene, pitch = four, 0.04 * (1 + recipe.spacing)
    slots = []
    for c in clauses:
        s = c.target(scene)
        slots.append(s)
        scene = scene.with_pose(c.command.mover, s)
    xy = np.array([four.get("A").xy] + [s[:2] for s in slots])
    assert np.allclose(np.linalg.norm(np.diff(xy, axis=0), axis=1), pitch)
    d = np.diff(xy, axis=0)
    assert np.allclose(d[1:], d[:1], atol=1e-9)  # straight
    assert all(abs(s[2] - four.get("A").yaw) < 1e-9 for s in slots)
    for s in slots:  # inside the arm's workspace
        assert math.hypot(*s[:2]) < four.workspace.radius


def test_the_planner_ends_at_the_target_and_the_model_still_scores(four):
    from l2p_bullet import planning
    from l2p_bullet.plugins import registry

    bundle = registry.load("next-to")
    a = four.get("A")
    target = np.r_[np.asarray(a.xy) + [0.0, -0.048], a.yaw]  # below A, 0.2 side apart
    plan = planning.plan(four, "B", "A", bundle, seed=0, target=target)
    assert plan.extra["target_error_m"] < 1e-6 and np.allclose(plan.path[-1, :2], target[:2])
    assert plan.extra["final_progress"] >= 0.9 and plan.stopped == "threshold"
    free = planning.plan(four, "B", "A", bundle, seed=0)
    assert "target" not in free.extra


def test_the_row_verdict_measures_gaps_line_and_knocks(four):
    from l2p_bullet.chain.composite import row_verdict

    a = four.get("A")
    row = four
    for k, n in enumerate("BCD", 1):
        row = row.with_pose(n, np.r_[a.xy[0] + k * 0.048, a.xy[1], a.yaw])
    ok = row_verdict(row, list("ABCD"))
    assert ok["success"] and ok["max_gap_sides"] == pytest.approx(0.2) and ok["max_offset_sides"] < 1e-6
    far = row.with_pose("D", np.r_[a.xy[0] + 3 * 0.048 + 0.01, a.xy[1], a.yaw])
    assert not row_verdict(far, list("ABCD"))["success"]
    off = row.with_pose("C", np.r_[a.xy[0] + 2 * 0.048, a.xy[1] + 0.02, a.yaw])
    assert "off the line" in row_verdict(off, list("ABCD"))["reason"]
    assert "knocked A" in row_verdict(row, list("ABCD"), {"A": 0.002})["reason"]


def test_the_teach_page_checks_the_drags_of_a_row(tmp_path):
    from l2p_bullet.composite.bundle import read_demos
    from l2p_bullet.plugins.scaffold import scaffold
    from l2p_bullet.teach.lesson import find_action
    from l2p_bullet.teach.rows import RowLesson

    root = scaffold("row", ["make a row of"], tmp_path / "l2p-row", kind="composite").root
    s = RowLesson(find_action("row", root), None)
    scene = s.scene(0)  # two blocks
    a, b = scene.get("A"), scene.get("B")
    options = [np.r_[np.asarray(a.xy) + 0.048 * np.array([math.cos(a.yaw + k * math.pi / 2),
                                                          math.sin(a.yaw + k * math.pi / 2)]), a.yaw] for k in range(4)]
    drag = None
    for g in options:  # the first free straight drag
        t = np.linspace(0, 1, 30)[:, None]
        track = b.pose[None] + (g - b.pose)[None] * t
        try:
            s._check_drag(scene, "B", track, {o.name: o.pose for o in scene.objects}, 1)
        except TeachError:
            continue
        drag = np.column_stack([np.linspace(0, 1, 30), track])
        break
    assert drag is not None
    with pytest.raises(TeachError, match="does not start where block B stood"):
        s.save_row(0, [{"block": "B", "samples": (drag + [0, 0.01, 0, 0]).tolist()}])
    with pytest.raises(TeachError, match="the sentence does not name"):
        s.save_row(0, [{"block": "Z", "samples": drag.tolist()}])
    through = np.column_stack([np.linspace(0, 1, 30), b.pose[None] + (np.r_[a.xy, b.yaw] - b.pose)[None] * t * 1.0])
    with pytest.raises(TeachError, match="passed through block A"):
        s.save_row(0, [{"block": "B", "samples": through.tolist()}])
    assert s.save_row(0, [{"block": "B", "samples": drag.tolist()}])["count"] == 1
    assert len(read_demos(s.action.bundle_dir)) == 1 and s.count() == 1


def test_the_axis_avoids_blocks_that_are_not_in_the_row_and_row_blocks_still_waiting():
    from l2p_bullet.chain.composite import choose_axis
    from l2p_bullet.composite.bundle import read_recipe
    from l2p_bullet.core.scene import SceneObject

    recipe = read_recipe(ROW)
    pitch = 0.04 * (1 + recipe.spacing)

    def scene(c_xy, d_xy):
        return Scene(
            [
                SceneObject("A", "red", 0.04, (0.0, 0.0), 0.0),
                SceneObject("B", "green", 0.04, (0.0, 0.15), 0.0),
                SceneObject("C", "blue", 0.04, c_xy, 0.0),
                SceneObject("D", "yellow", 0.04, d_xy, 0.0),
            ]
        ).validate()

    # C waits on +x's slot 1 (it moves second, after B fills slot 1); D (not in the row) sits on -x's slot 2
    u = choose_axis(scene((pitch, 0.0), (-2 * pitch, 0.0)), "A", ["B", "C"], recipe)
    assert abs(u[0]) < 1e-9 and abs(abs(u[1]) - 1) < 1e-9
    # C on its own slot (+x, slot 2) is no obstacle: it is the block that goes there
    u = choose_axis(scene((2 * pitch, 0.0), (-2 * pitch, 0.0)), "A", ["B", "C"], recipe)
    assert np.allclose(u, [1.0, 0.0])


@pytest.mark.slow
def test_perform_a_row_of_four_from_the_command_line(tmp_path):
    import json

    from click.testing import CliRunner

    from l2p_bullet.cli import main

    def perform(sentence: str, out: Path):
        scene = str(ROOT / "examples" / "four_blocks.json")
        return CliRunner().invoke(main, ["perform", sentence, "--scene", scene, "--no-render", "--out", str(out)])

    out = tmp_path / "run"
    r = perform("make a row of A, B, C and D", out)
    assert r.exit_code == 0, r.output
    assert "row: a row (largest gap" in r.output and "chain: success, 3 of 3 clauses done" in r.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["success"] and summary["row"]["success"] and summary["row"]["knocked"] == {}
    assert [c["text"] for c in summary["clauses"]] == ["move B next to A", "move C next to B", "move D next to C"]
    plan = json.loads((out / "plan.json").read_text())
    assert all(c["plan"]["target_error_m"] < 0.001 for c in plan["clauses"][1:])  # each clause reached its slot
    bad = perform("line up A, B and Z", tmp_path / "bad")
    assert bad.exit_code == 2 and 'no block called "Z"' in bad.output and not (tmp_path / "bad").exists()


def test_a_demos_file_too_large_or_nested_too_deep_is_a_one_line_error(tmp_path):
    """Read bounded, parsed with one-line errors: nesting past the recursion limit was a RecursionError traceback."""
    from l2p_bullet.composite.bundle import MAX_BYTES, read_demos
    from l2p_bullet.composite.recipe import CompositeError

    (tmp_path / "demos.json").write_text("[" * 100_000 + "]" * 100_000)
    with pytest.raises(CompositeError, match="cannot read .*RecursionError"):
        read_demos(tmp_path)
    (tmp_path / "demos.json").write_bytes(b" " * (MAX_BYTES + 1))
    with pytest.raises(CompositeError, match="larger than"):
        read_demos(tmp_path)


def test_a_composite_scaffold_says_how_it_is_taught_and_train_refuses_it(tmp_path, monkeypatch):
    """`new-action --composite` wrote the single action's README (train on .npz files, progress.safetensors,
    "move A <phrase> B"), and `train` followed it: a progress model went into the composite's bundle, which
    `actions` then listed as usable and every sentence of it refused ("has no recipe.json"). The README says
    how a composite is taught; `train` refuses its folder, naming teach; an untaught one, installed, is
    listed with recipe.json missing and the teach command."""
    from click.testing import CliRunner

    from l2p_bullet.cli import main
    from l2p_bullet.learning.synthetic import write_sessions
    from l2p_bullet.plugins import registry
    from l2p_bullet.plugins.scaffold import scaffold

    made = scaffold("row2", ["put in a line"], tmp_path / "l2p-row2", kind="composite")
    readme = (made.root / "README.md").read_text()
    assert "l2p-bullet teach row2 --plugin l2p-row2" in readme and 'perform "put in a line A, B, C and D"' in readme
    assert "l2p-bullet train row2" not in readme and "progress.safetensors" not in readme, readme
    manifest = (made.package_dir / "manifest.toml").read_text()
    assert "l2p-bullet teach row2" in manifest and "l2p-bullet train" not in manifest, manifest
    write_sessions(str(tmp_path / "demos"), "left-of")
    monkeypatch.chdir(tmp_path)
    r = CliRunner().invoke(main, ["train", "row2", "--demos", "demos", "--out", "l2p-row2/l2p_row2",
                                  "--ensemble", "1", "--epochs", "1"])
    assert r.exit_code == 2, r.output
    assert "composite" in r.output and "l2p-bullet teach row2 --plugin l2p-row2" in r.output, r.output
    assert sorted(p.name for p in made.package_dir.iterdir()) == ["__init__.py", "manifest.toml"]
    info = registry.local("row2", made.package_dir)
    assert info.kind == "composite" and "recipe.json missing" in info.error and "l2p-bullet teach row2" in info.error
    assert "l2p-bullet train" not in info.error, info.error
