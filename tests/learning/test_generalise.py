"""The training plans (learning/training_plan.py) and the planner-domain motions they add (learning/motions.py)."""

from __future__ import annotations

import numpy as np
import pytest

from l2p_bullet.learning import motions as g
from l2p_bullet.learning.train_progress import all_demos
from l2p_bullet.learning.training_plan import TrainingPlan, plans, training_set
from l2p_bullet.learning.trainset import DataConfig, build
from l2p_bullet.progress.features import QSRConfig


@pytest.fixture(scope="module")
def held_out() -> dict[str, list[g.Event]]:
    return {a: g.events(ds) for a, ds in all_demos(sessions={"Session2"}).items()}


_SETS: dict[tuple[str, str], list] = {}


def _session2_set(plan: str, action: str) -> list:
    """``training_set(plans(1, 1)[plan], action, <Session2's demonstrations>)``, built once for the module: several
    tests compare the same sets (a second or so each); they only read them."""
    if (plan, action) not in _SETS:
        _SETS[plan, action] = training_set(plans(1, 1)[plan], action, all_demos(sessions={"Session2"}), QSRConfig())
    return _SETS[plan, action]


def test_planner_domain_keeps_the_ends_and_moves_in_straight_lines(held_out):
    e = held_out["closer"][0]
    s = g.domain(e, "straight", 3)
    assert np.allclose(s[0], e.mover[0]) and np.allclose(s[-1], e.mover[-1])
    step = np.linalg.norm(np.diff(s[:, :2], axis=0), axis=1)
    assert step.max() <= 0.25 * e.size + 1e-9
    # three moves: the heading changes at most twice
    heading = np.round(np.arctan2(*np.diff(s[:, 1::-1], axis=0).T), 6)
    assert len(np.unique(heading)) <= 3


def test_snapped_moves_end_on_the_planner_rings_and_the_study_grid(held_out):
    e = held_out["around"][0]
    rings = g.domain(e, "rings")
    r = np.hypot(*(rings[-1, :2] - e.anchor[:2])) / e.size
    assert np.min(np.abs(r - np.array([1.25, 1.75, 2.5, 3.5, 5.0, 6.5]))) < 1e-6
    grid = g.domain(e, "grid")
    ij = (grid[-1, :2] - e.anchor[:2]) / (g.GRID_BLOCKS * e.size)
    assert np.allclose(ij, np.round(ij)) and np.any(np.round(ij) != 0)


@pytest.mark.slow
def test_the_current_recipe_is_the_shipped_training_set_bit_for_bit():
    demos = all_demos(sessions={"Session1"})
    q = QSRConfig()
    cur = training_set(plans(1, 1)["current"], "past", demos, q)
    ref = build("past", demos, q, DataConfig())
    assert len(cur) == len(ref)
    assert all(
        np.array_equal(a.x, b.x) and np.array_equal(a.y, b.y) and a.weight == b.weight
        for a, b in zip(cur, ref, strict=True)
    )


@pytest.mark.slow
def test_recipe_extras_append_planner_domain_sequences():
    demos = all_demos(sessions={"Session1"})
    q = QSRConfig()
    base = build("closer", demos, q, DataConfig())
    plan = TrainingPlan("x", planner_positives=True, planner_negatives=True, contrastive=True)
    more = training_set(plan, "closer", demos, q)
    extra = more[len(base):]
    n_own = 2 * len(demos["closer"])
    assert sum(s.positive for s in extra) == n_own  # one ring-snapped copy per event and mirror image
    negs = [s for s in extra if not s.positive]
    assert len(negs) == 2 * n_own + 4 * sum(len(demos[b]) for b in DataConfig().negatives["closer"])
    assert all(float(s.y.max()) == 0.0 for s in negs)
    assert all(0.0 < float(s.y[s.end]) <= 1.0 for s in extra if s.positive)


@pytest.mark.slow
def test_planner_partials_are_planner_motions_stopped_early_with_partial_labels():
    demos = all_demos(sessions={"Session1"})
    q = QSRConfig()
    base = build("next-to", demos, q, DataConfig())
    more = training_set(TrainingPlan("x", planner_partials=True), "next-to", demos, q)
    extra = more[len(base):]
    assert len(extra) == 2 * 2 * 2 * len(demos["next-to"])  # 2 views x (straight, rings) x 2 cuts
    assert all(s.positive and s.end == len(s.y) - 1 for s in extra)
    ends = np.array([s.y[-1] for s in extra])
    # frames are ~evenly spaced in arc length: labels end near the cut (a short motion has few frames)
    assert abs(np.median(ends[0::2]) - 0.3) < 0.03 and abs(np.median(ends[1::2]) - 0.6) < 0.03
    assert np.all(ends[0::2] < ends[1::2] + 1e-6) and ends.max() < 0.8


@pytest.mark.slow
def test_train_uses_the_shipped_recipe_and_says_so(tmp_path):
    from click.testing import CliRunner

    from l2p_bullet.cli import main
    from l2p_bullet.learning.training_plan import SHIPPED
    from l2p_bullet.plugins.bundle import read_manifest

    out = tmp_path / "next_to"
    r = CliRunner().invoke(main, ["train", "next-to", "--ensemble", "1", "--epochs", "1", "--out", str(out)])
    assert r.exit_code == 0, r.output
    t = read_manifest(out)["training"]
    assert t["recipe"] == {"name": SHIPPED.name, **SHIPPED.extras_dict()}
    assert t["n_sequences"] == len(training_set(SHIPPED, "next-to", all_demos(), QSRConfig()))


@pytest.mark.slow
def test_strays_add_around_corners_out_on_the_far_rings_with_the_credit_near_leaves():
    """``strays`` (sixth round): around alone gets them, from their own generator (what the recipe had
    before is bit-identical), each with one corner on the 5- or 6.5-block ring and 0.6 / 0 of its label
    from there; the other actions' sets are unchanged."""
    from l2p_bullet.learning.training_plan import STRAY_RINGS

    demos = all_demos(sessions={"Session1"})
    q = QSRConfig()
    r0 = plans(1, 1)["planner-graded-nogrid"]
    r1 = plans(1, 1)["planner-graded-nogrid-strays"]
    before, after = training_set(r0, "around", demos, q), training_set(r1, "around", demos, q)
    same = [a for a, b in zip(after, before, strict=False) if np.array_equal(a.x, b.x) and np.array_equal(a.y, b.y)]
    assert len(same) < len(before) < len(after)  # strays sit among them, after each event's other extras
    old = {(a.x.tobytes(), a.y.tobytes()) for a in before}
    new = [s for s in after if (s.x.tobytes(), s.y.tobytes()) not in old]
    assert len(after) - len(before) == len(new) and 0.9 * 2 * len(demos["around"]) <= len(new) <= 2 * len(
        demos["around"]
    )
    assert all(s.positive and s.end == len(s.y) - 1 for s in new)
    ends = np.array([s.y[-1] for s in new])
    assert np.all(ends <= 0.6 + 1e-6) and np.sum(ends < 1e-6) > 0.2 * len(new) and np.sum(ends > 0.3) > 0.2 * len(new)
    assert STRAY_RINGS == (5.0, 6.5)
    for a in ("closer", "past"):
        x, y = training_set(r0, a, demos, q), training_set(r1, a, demos, q)
        assert len(x) == len(y) and all(
            np.array_equal(u.x, v.x) and np.array_equal(u.y, v.y) for u, v in zip(x, y, strict=True)
        )


def test_trusted_own_leaves_untrusted_demos_out_of_the_own_list_only():
    """``trusted_own`` (seventh round): around trains without around/Session2/e05; the other actions still
    see it among their negatives (their lists are the very same), and a recipe without it changes nothing."""
    from l2p_bullet.data.demos import UNTRUSTED
    from l2p_bullet.learning.training_plan import SHIPPED, own_trusted

    demos = all_demos()
    r = plans(1, 1)["planner-graded-nogrid-trusted"]
    assert r.trusted_own and r.extras_dict() == SHIPPED.extras_dict() | {"trusted_own": True}
    ids = [d.id for d in own_trusted(r, "around", demos)["around"]]
    assert "around/Session2/e05" in UNTRUSTED and not set(ids) & set(UNTRUSTED)
    assert ids == [d.id for d in demos["around"] if d.id not in UNTRUSTED] and len(ids) == len(demos["around"]) - 1
    for a in ("closer", "away", "next-to", "past"):
        assert own_trusted(r, a, demos) is demos
        assert all(x is y for x, y in zip(own_trusted(r, "around", demos)[a], demos[a], strict=True))
    assert own_trusted(SHIPPED, "around", demos) is demos


@pytest.mark.slow
def test_trusted_own_changes_around_set_alone():
    """The other four actions' training sets are bit-identical with ``trusted_own`` (e05 stays among their
    negatives); around's is the one built without e05, and differs from the shipped one."""
    demos = all_demos(sessions={"Session2"})
    q = QSRConfig()
    r0, r1 = plans(1, 1)["planner-graded-nogrid"], plans(1, 1)["planner-graded-nogrid-trusted"]

    def same(x: list, y: list) -> bool:
        return len(x) == len(y) and all(np.array_equal(u.x, v.x) and np.array_equal(u.y, v.y) and u.weight == v.weight
                                        for u, v in zip(x, y, strict=True))

    for a in ("closer", "away", "next-to", "past"):
        assert same(_session2_set(r0.name, a), training_set(r1, a, demos, q))
    without = {**demos, "around": [d for d in demos["around"] if d.id != "around/Session2/e05"]}
    assert len(without["around"]) == len(demos["around"]) - 1
    trusted = training_set(r1, "around", demos, q)
    assert same(trusted, training_set(r0, "around", without, q))
    assert not same(trusted, _session2_set(r0.name, "around"))


@pytest.mark.slow
def test_train_applies_trusted_own_when_the_shipped_recipe_has_it(tmp_path, monkeypatch):
    """``l2p-bullet train around`` (so ``make bundles``) trains on the set without e05 once SHIPPED has
    ``trusted_own``, records it, and its data digest is that of the demonstrations it used."""
    from click.testing import CliRunner

    from l2p_bullet.cli import main
    from l2p_bullet.learning import train_progress as tp
    from l2p_bullet.learning import training_plan as rc
    from l2p_bullet.learning.train_progress import data_digest
    from l2p_bullet.plugins.bundle import read_manifest

    trusted = plans(1, 1)["planner-graded-nogrid-trusted"]
    shipped = rc.dataclasses.replace(rc.SHIPPED, name=trusted.name, trusted_own=True)
    monkeypatch.setattr(rc, "SHIPPED", shipped)  # the plan the extras extend
    monkeypatch.setattr(tp, "SHIPPED", shipped)  # the plan the trainer reads
    out = tmp_path / "around"
    r = CliRunner().invoke(main, ["train", "around", "--ensemble", "1", "--epochs", "1", "--out", str(out)])
    assert r.exit_code == 0, r.output
    t = read_manifest(out)["training"]
    demos = all_demos()
    assert t["recipe"]["trusted_own"] is True
    assert t["n_sequences"] == len(training_set(trusted, "around", demos, QSRConfig()))
    nogrid = plans(1, 1)["planner-graded-nogrid"]
    assert t["n_sequences"] < len(training_set(nogrid, "around", demos, QSRConfig()))
    assert t["data_digest"] == data_digest(rc.own_trusted(trusted, "around", demos)) != data_digest(demos)


@pytest.mark.slow
def test_near_starts_are_short_full_closers_added_after_closers_set_alone(held_out):
    """``near_starts`` (eighth round): closer's set is the shipped one plus, at its end, people's endings made
    short (start within 1.25-2.5 blocks, end 1.05-1.2 blocks from the anchor, labelled full); the other actions'
    sets are the very same."""
    from l2p_bullet.learning.training_plan import NEAR_END, NEAR_START, SHIPPED, _near

    demos = all_demos(sessions={"Session2"})
    q = QSRConfig()
    r0, r1 = plans(1, 1)["planner-graded-nogrid"], plans(1, 1)["planner-graded-nogrid-near"]
    assert r1.extras_dict() == SHIPPED.extras_dict() | {"near_starts": True}
    base, near = _session2_set(r0.name, "closer"), training_set(r1, "closer", demos, q)
    assert len(near) > len(base)
    assert all(
        np.array_equal(u.x, v.x) and np.array_equal(u.y, v.y) for u, v in zip(base, near[: len(base)], strict=True)
    )
    assert all(s.positive and s.y[-1] == 1.0 for s in near[len(base):])
    rng = np.random.default_rng(0)
    for e in held_out["closer"]:
        for m in _near(e, rng):
            d = np.hypot(*(m[:, :2] - e.anchor[:2]).T) / e.size
            assert NEAR_END[0] - 1e-9 <= d[-1] <= NEAR_END[1] + 1e-9 and d[0] <= NEAR_START[1] + 1e-9
            assert d[0] - d[-1] >= 0.1 - 1e-9
    for a in ("away", "next-to"):
        x, y = _session2_set(r0.name, a), training_set(r1, a, demos, q)
        assert len(x) == len(y) and all(
            np.array_equal(u.x, v.x) and np.array_equal(u.y, v.y) for u, v in zip(x, y, strict=True)
        )
