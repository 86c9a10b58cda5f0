"""One place per rule: each action's judge, room checks, bound, lead-in, training extras and report finding
are declared by its spec (``l2p_bullet/actions/<name>/__init__.py``), and the stages look them up; no stage
names an action. A plugin's spec supplies the same and is planned and trained by it."""

from __future__ import annotations

import ast
import dataclasses
from pathlib import Path

import numpy as np
import pytest

import l2p_bullet
from l2p_bullet.actions import BUILTIN, ActionSpec, Bound, LeadIn, Planning, Training
from l2p_bullet.core.scene import default_scene
from l2p_bullet.errors import InfeasibleError
from l2p_bullet.judge.rules import RULE_SPECS
from l2p_bullet.planning import PEOPLE_BOUNDS, feasibility, rule_spec

PKG = Path(l2p_bullet.__file__).parent
HOME = PKG / "actions"
"""Where the rules live: each action's module (and the spec's shape)."""
RESEARCH = {f"learning/{m}.py" for m in ("generalise", "agreement_cv", "ordered_probes", "feedback_targets",
                                         "heldout", "synthetic", "sessions")}
"""Experiments on the shipped five (not stages of the product), leaving the package."""
NAMES = ({s.name for s in BUILTIN.values()} | {s.name.replace("-", "_") for s in BUILTIN.values()}
         | {s.source_name for s in BUILTIN.values()})


def _docstrings(tree: ast.AST) -> set[int]:
    """The string constants that stand alone as statements (module, class, function, attribute docstrings)."""
    out = set()
    for node in ast.walk(tree):
        for stmt in getattr(node, "body", []) if isinstance(getattr(node, "body", None), list) else []:
            if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant):
                out.add(id(stmt.value))
    return out


def _where(parents: dict[int, ast.AST], node: ast.AST) -> str:
    up = parents.get(id(node))
    while isinstance(up, ast.Tuple | ast.List | ast.Set):
        up = parents.get(id(up))
    if isinstance(up, ast.Compare):
        membership = any(isinstance(o, ast.In | ast.NotIn) for o in up.ops)
        return "a membership test" if membership else "a comparison"
    if isinstance(up, ast.Dict):
        return "a dict key" if any(k is node for k in up.keys) else "a dict value"
    if isinstance(up, ast.Subscript):
        return "a subscript"
    return "a literal"


def named_actions(root: Path = PKG) -> list[str]:
    """Every built-in action's name written as a string in code outside the rules' home (docstrings aside)."""
    found = []
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root).as_posix()
        if path.is_relative_to(HOME) or rel in RESEARCH:
            continue
        tree = ast.parse(path.read_text())
        docs = _docstrings(tree)
        parents = {id(c): n for n in ast.walk(tree) for c in ast.iter_child_nodes(n)}
        for node in ast.walk(tree):
            if (isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value in NAMES
                    and id(node) not in docs):
                found.append(f"{rel}:{node.lineno}: {node.value!r} in {_where(parents, node)}")
    return found


def test_no_stage_names_an_action():
    """A name written in a stage is a branch on it (a comparison, a membership test, a dict keyed by it, a
    default argument that picks it): the stage then knows the action, and a plugin cannot be what it knows."""
    found = named_actions()
    assert not found, ("stages name actions; declare it in the action's spec (l2p_bullet/actions/<name>/) "
                       "and look it up instead:\n  " + "\n  ".join(found))


def test_the_scan_sees_a_branch_on_a_name(tmp_path):
    (tmp_path / "stage.py").write_text('"""around is fine in a docstring."""\n'
                                       'def f(rules):\n'
                                       '    if rules == "around":\n        return {"past": 1}\n'
                                       '    return rules in ("closer", "x")\n')
    found = named_actions(tmp_path)
    assert [f.split(": ", 1)[1] for f in found] == ["'around' in a comparison", "'past' in a dict key",
                                                    "'closer' in a membership test"]


def test_each_rule_set_is_planned_by_the_spec_that_declares_it():
    assert RULE_SPECS == {s.rules: s for s in BUILTIN.values()}
    bounded = {n for n, s in RULE_SPECS.items() if s.planning.bound is not None}
    assert set(PEOPLE_BOUNDS) == bounded == {"past", "closer", "away"}
    assert [n for n, s in RULE_SPECS.items() if s.planning.lead_in is not None] == ["around"]
    for spec in BUILTIN.values():
        assert set(spec.planning.checks) <= set(feasibility.ROOM_CHECKS) <= set(feasibility.CHECKS)

    class Judged:  # a plugin bundle without a spec, judged by a built-in rule set: planned as that action
        manifest = {"judge": {"rules": "around"}}

    assert rule_spec(Judged()) is BUILTIN["around"]
    Judged.manifest = {"judge": {"entry": "pkg:judge"}}
    assert rule_spec(Judged()) is None


def test_a_plugins_own_spec_declares_its_room_checks_with_its_thresholds():
    """A plugin "afar" (judged by its own code) that must end ``gain`` blocks farther declares the away room
    check: refused where no point of the workspace is that much farther, with its own number; declaring none,
    never."""
    scene = default_scene()
    afar = ActionSpec("afar", "", "move A afar from B", thresholds={"gain": 1.0},
                      planning=Planning(checks=("room-away",)))
    feasibility.check(scene, "A", "B", afar)  # room enough for 1 block more
    much = dataclasses.replace(afar, thresholds={"gain": 50.0})
    with pytest.raises(InfeasibleError, match="away needs 50 block more") as e:
        feasibility.check(scene, "A", "B", much)
    assert e.value.check == "room-away"
    feasibility.check(scene, "A", "B", dataclasses.replace(much, planning=Planning()))  # no check declared


def test_a_plugins_own_spec_declares_how_it_is_planned():
    class Own:  # a plugin bundle whose module declares how it is planned: its spec wins over its rule set's
        manifest = {"judge": {"rules": "closer"}}
        spec = ActionSpec("ring", "", "move A ring B", planning=Planning(
            bound=Bound("passes-within", 2.0), lead_in=LeadIn(near=3.0, approach=2.0, reach=3.5)))

    assert rule_spec(Own()) is Own.spec
    Own.spec = ActionSpec("plain", "", "move A plain B")  # declares nothing: planned by its rule set
    assert rule_spec(Own()) is BUILTIN["closer"]


def test_a_plugins_spec_declares_the_training_extras_it_gets():
    from l2p_bullet.data.demos import load_demos
    from l2p_bullet.learning.training_plan import SHIPPED, declared, extras
    from l2p_bullet.progress.features import QSRConfig

    demos = {"mine": load_demos("closer")[:2]}
    plain = extras(SHIPPED, "mine", demos, QSRConfig(), 1.0, 0)
    mine = ActionSpec("mine", "", "move A mine B", training=Training(wrong_motions=("reversed", "backs-off")))
    more = extras(SHIPPED, "mine", demos, QSRConfig(), 1.0, 0, spec=mine)
    assert declared("mine") == Training() and declared("mine", mine) is mine.training
    negatives = [s for s in more if not s.positive and s.weight == 1.0]
    assert len(more) - len(plain) == len(negatives) == 2 * 2 * 2  # 2 demonstrations x mirror x 2 kinds
    assert all(np.all(s.y == 0) for s in negatives)


def test_a_declared_kind_no_stage_makes_is_refused_in_one_line_naming_the_known_ones():
    """Each kind an action may declare is one a stage makes, and a typo in a plugin's spec is a ValueError
    when its module is imported (the registry reports it with the plugin's name), not a KeyError while
    planning."""
    from l2p_bullet.actions import spec as s
    from l2p_bullet.errors import PluginError
    from l2p_bullet.learning import training_plan
    from l2p_bullet.planning import bounds

    assert set(s.ROOM_CHECKS) == set(feasibility.ROOM_CHECKS) == set(feasibility.READS)
    assert set(s.BOUND_KINDS) == set(bounds.WEIGHTS)
    assert set(s.WRONG_MOTIONS) == set(training_plan.WRONG_MOTIONS)
    assert set(s.GRADED_WRONGS) == set(training_plan.GRADED_WRONGS)
    with pytest.raises(ValueError, match="unknown room check 'room-closr' .known: room-closer, room-away"):
        Planning(checks=("room-closr",))
    with pytest.raises(ValueError, match="unknown bound 'passes'"):
        Bound("passes", 3.0)
    with pytest.raises(ValueError, match="unknown wrong motion 'back'"):
        Training(wrong_motions=("reversed", "back"))
    with pytest.raises(ValueError, match="unknown graded wrong motion"):
        Training(graded_wrong="out")
    bare = ActionSpec("bare", "", "move A bare B", planning=Planning(checks=("room-closer",)))
    with pytest.raises(PluginError, match='"bare" declares the room check "room-closer".*add share'):
        feasibility.check(default_scene(), "A", "B", bare)
