"""What an action is lives in the action: each built-in's module declares an ``ActionSpec`` (``ACTION``) next
to its bundle, the stages read it, and a plugin's module can declare one the same way."""

from __future__ import annotations

import math

import numpy as np
import pytest
from plugin_fixtures import copy_builtin_as_plugin, make_bundle, make_dist

from l2p_bullet.actions import BUILTIN, ActionSpec, Training
from l2p_bullet.core.vocabulary import ACTIONS, GRADED_FOLDERS, SOURCE_NAMES
from l2p_bullet.errors import FailedToLoadPlugin
from l2p_bullet.judge.rules import rule_verdict
from l2p_bullet.learning.trainset import DataConfig
from l2p_bullet.plugins import registry


def test_each_builtin_is_loaded_with_its_spec_through_the_entry_point():
    plugins = registry.discover()
    for name in ACTIONS:
        bundle = registry.load(name, plugins)
        assert bundle.spec is BUILTIN[name], name
    assert ACTIONS == ("closer", "away", "next-to", "past", "around")
    assert SOURCE_NAMES["next-to"] == "SlideNext" and GRADED_FOLDERS["SlideAroundDiscrete"] == "around"


def _arc(turns: float, radius: float = 2.0, n: int = 400) -> np.ndarray:
    t = np.linspace(0.0, 2 * math.pi * turns, n)
    return np.column_stack([radius * np.cos(t), radius * np.sin(t), np.zeros(n)])


def test_the_rule_judge_reads_the_thresholds_its_action_declares():
    need = BUILTIN["around"].thresholds["turns"]
    anchor = np.zeros(3)
    assert not rule_verdict("around", _arc(need - 0.03), anchor, 1.0).success
    assert rule_verdict("around", _arc(need + 0.03), anchor, 1.0).success
    gain = BUILTIN["away"].thresholds["gain"]
    line = lambda d: np.column_stack([np.linspace(2.0, 2.0 + d, 50), np.zeros(50), np.zeros(50)])  # noqa: E731
    assert not rule_verdict("away", line(gain - 0.05), anchor, 1.0).success
    assert rule_verdict("away", line(gain + 0.05), anchor, 1.0).success


def test_the_training_set_options_are_the_actions_own():
    d = DataConfig()
    for name, spec in BUILTIN.items():
        t = spec.training
        assert d.negatives[name] == list(t.negatives)
        assert (name in d.twist_actions) == t.twist and (name in d.detour_actions) == t.detour
        assert (name in d.unscaled) == (not t.scaled)
        assert d.turn_label.get(name) == t.turn_label and d.net_label.get(name) == t.net_label
        assert d.scale_ranges.get(name) == t.scale_range and d.approach.get(name) == t.approach


def test_a_plugin_declares_its_spec_the_same_way(tmp_path, monkeypatch):
    root = tmp_path / "site"
    folder = copy_builtin_as_plugin(root, "around", "circling", ["circling"])
    (folder / "__init__.py").write_text(
        "from l2p_bullet.actions.spec import ActionSpec, Training\n"
        "ACTION = ActionSpec(name='circling', source_name='', sentence='move A circling B',\n"
        "                    thresholds={'turns': 0.5}, training=Training(turn_label=0.5))\n")
    monkeypatch.syspath_prepend(str(root))
    bundle = registry.load("circling", registry.discover())
    assert isinstance(bundle.spec, ActionSpec) and bundle.spec.training.turn_label == 0.5


def test_a_plugin_whose_spec_is_not_one_is_refused_with_its_name(tmp_path, monkeypatch):
    root = tmp_path / "site"
    folder = copy_builtin_as_plugin(root, "around", "wobbly", ["wobbly"], dist="l2p-wobbly")
    (folder / "__init__.py").write_text("ACTION = {'name': 'wobbly'}\n")
    monkeypatch.syspath_prepend(str(root))
    with pytest.raises(FailedToLoadPlugin, match="wobbly.*ActionSpec"):
        registry.load("wobbly", registry.discover())


def test_an_untrained_plugin_declares_training_options_its_training_set_takes(tmp_path, monkeypatch):
    from l2p_bullet.learning.train_progress import declared_spec  # imports torch: only this test needs it

    root = tmp_path / "site"
    make_bundle(root / "l2p_test_swirl", "swirl", ["swirling"], weights=False, init=(
        "from l2p_bullet.actions.spec import ActionSpec, Training\n"
        "ACTION = ActionSpec(name='swirl', source_name='', sentence='move A swirling B',\n"
        "                    training=Training(negatives=('past',), twist=True, scaled=False, turn_label=0.5))\n"))
    make_dist(root, "l2p-swirl", {"swirl": "l2p_test_swirl"})
    monkeypatch.syspath_prepend(str(root))
    with pytest.raises(FailedToLoadPlugin):  # no weights yet: no bundle to load, but a spec to train by
        registry.load("swirl", registry.discover())
    spec = declared_spec("swirl")
    assert spec is not None and spec.training.turn_label == 0.5
    d = DataConfig(random_negatives=0).with_action(spec)
    assert d.negatives["swirl"] == ["past"] and d.turn_label["swirl"] == 0.5
    assert "swirl" in d.twist_actions and "swirl" in d.unscaled and "swirl" not in d.detour_actions
    assert DataConfig().with_action(None) == DataConfig() and declared_spec("not-installed") is None


def test_each_builtin_names_its_own_rule_set_kept_in_its_own_module():
    from l2p_bullet.judge import rules
    from l2p_bullet.judge.rulesets import around, away, closer, next_to, past

    for spec, module in zip(BUILTIN.values(), (closer, away, next_to, past, around), strict=True):
        assert spec.rules == spec.name and set(module.RULES) == {spec.name}, spec.name
        assert rules.RULES[spec.rules] is module.RULES[spec.name]
    assert rules.AROUND_TURNS == BUILTIN["around"].thresholds["turns"] and rules.closer_room(5.0) == 4.0


def test_random_negatives_and_clear_feedback_read_the_action_spec():
    from l2p_bullet.actions import Violation
    from l2p_bullet.learning.feedback_targets import FeedbackConfig
    from l2p_bullet.learning.trainset import violates

    anchor = np.zeros((2, 3))
    toward, off = np.array([[6.0, 0, 0], [2.0, 0, 0]]), np.array([[2.0, 0, 0], [6.0, 0, 0]])
    # a plugin declaring "closer"'s checks is judged the same way; without any, it has no random negatives
    mine = ActionSpec("nearer", "Nearer", "move A nearer B", training=Training(violation=Violation(ends_farther=0.5)))
    assert violates(mine, off, anchor) and not violates(mine, toward, anchor)
    assert violates("closer", off, anchor) and not violates("closer", toward, anchor)
    with pytest.raises(ValueError, match="declares no random negatives"):
        violates(ActionSpec("still", "Still", "keep A still"), off, anchor)
    clear = FeedbackConfig().clear
    assert clear["around"] == BUILTIN["around"].training.clear_grades and "closer" not in clear


def test_a_scaffolded_plugin_declares_its_spec_as_the_builtins_do(tmp_path, monkeypatch):
    from l2p_bullet.plugins.scaffold import scaffold

    s = scaffold("amid", ["amid"], tmp_path / "l2p-amid", anchors=2, judge="between")
    make_dist(s.root, s.dist_name, {"amid": s.module})
    monkeypatch.syspath_prepend(str(s.root))
    spec = registry.action_spec("amid", registry.discover())
    assert isinstance(spec, ActionSpec) and spec.name == "amid" and spec.rules == "between"
    assert spec.sentence == "move A amid B and C" and spec.training == Training()
    assert DataConfig(random_negatives=0).with_action(spec) == DataConfig(random_negatives=0)


def test_a_scaffolded_composite_declares_a_sentence_over_a_list_of_objects(tmp_path):
    """A composite's phrase takes the objects as a list ("line up A, B and C"), not "move A <phrase> B"."""
    from l2p_bullet.plugins.scaffold import scaffold

    s = scaffold("tidy", ["line up"], tmp_path / "l2p-tidy", kind="composite")
    text = (s.package_dir / "__init__.py").read_text()
    assert 'sentence="line up A, B and C"' in text and "move A line up" not in text
    assert 'l2p-bullet perform "line up A, B and C"' in (s.root / "README.md").read_text()
