"""Ordered probes (research/ordered_probes.py): variants whose order a rule fixes, not a grade."""

from __future__ import annotations

import numpy as np
import pytest

from l2p_bullet.core.geometry import swept_angle
from l2p_bullet.core.vocabulary import ACTIONS
from l2p_bullet.learning.train_progress import all_demos
from research import generalise as g
from research import ordered_probes as op


@pytest.fixture(scope="module")
def held_out() -> dict[str, list[g.Event]]:
    return {a: g.events(ds)[:3] for a, ds in all_demos(sessions={"Session2"}).items()}


def _end_r(w: np.ndarray, e: g.Event) -> float:
    return float(np.hypot(*(w[-1, :2] - e.anchor[:2])) / e.size)


def _r(p: np.ndarray, e: g.Event) -> float:
    return float(np.hypot(*(p[:2] - e.anchor[:2])) / e.size)


def test_every_action_has_its_chains_and_reasons(held_out):
    for a in ACTIONS:
        ch = op.chains(held_out[a][0])
        assert set(ch) == set(op.CHAINS[a]), a
        assert all(len(v) >= 2 for v in ch.values())


def test_chains_are_what_they_say(held_out):
    for e in held_out["closer"]:
        lo, half, whole = op.chains(e)["undone"]
        assert np.allclose(lo[-1], e.mover[0]) and np.allclose(whole[-1], e.mover[-1])
        assert _end_r(lo, e) > _end_r(half, e) > _end_r(whole, e)
    for e in held_out["next-to"]:
        far, near, whole = op.chains(e)["overshot"]
        assert _end_r(far, e) == pytest.approx(_end_r(whole, e) + 4, abs=1e-6)
        assert _end_r(near, e) == pytest.approx(_end_r(whole, e) + 2, abs=1e-6)
    for e in held_out["around"]:
        turns = [abs(swept_angle(g.straight_moves(w, 0.25 * e.size), e.anchor)) / (2 * np.pi)
                 for w in op.chains(e)["arcs"]]
        assert turns == pytest.approx([0.25, 0.5, 0.75, 1.0], abs=1e-6)
        far, ring, own = op.chains(e)["strays"]
        assert [_r(w[2], e) for w in (far, ring)] == pytest.approx([6.5, 5.0], abs=1e-6)
        assert np.allclose(np.delete(far, 2, 0), np.delete(own, 2, 0)) and np.allclose(own, g.waypoints(e.mover, 4))
        short = op.chains(e)["shortened"]
        arc = [g._arc(g.straight_moves(w, 0.01))[-1] for w in short]
        assert arc[0] < arc[1] < arc[2]


class _Rule:
    """A stand-in scorer that knows each chain's order: around by turn, the others by end distance."""

    def __init__(self, action: str, flip: bool = False):
        self.action, self.sign = action, -1.0 if flip else 1.0

    def __call__(self, model, motions, evs):
        out = []
        for m, e in zip(motions, evs, strict=True):
            r = np.hypot(*(m[-1, :2] - e.anchor[:2])) / e.size
            r0 = np.hypot(*(m[0, :2] - e.anchor[:2])) / e.size
            v = {"closer": r0 - r, "away": r - r0, "next-to": -abs(r - 1.2),
                 "past": g._arc(m)[-1] * (r > r0 - 1e-9 or r > 1.5),
                 "around": abs(swept_angle(m, e.anchor)) + 0.001 * g._arc(m)[-1]
                 - max(0.0, float(np.hypot(*(m[:, :2] - e.anchor[:2]).T).max()) / e.size - 4.0)}[self.action]
            out.append(self.sign * v)
        return np.array(out)


def test_a_scorer_that_follows_the_rules_orders_the_chains_and_its_reverse_does_not(held_out):
    good = op.ordered(None, held_out["around"], _Rule("around"))
    # strays: snapped to the rings, a corner on the 6.5 ring can change which side of the anchor a straight move
    # passes, hence the net turn; for the first event that turns one pair of the 12 round even for the rule
    assert good["arcs"] == 1.0 and good["strays"] > 0.9 and good["all"] > 0.8
    bad = op.ordered(None, held_out["around"], _Rule("around", flip=True))
    assert bad["arcs"] == 0.0 and bad["all"] < 0.2
    assert op.ordered(None, held_out["closer"], _Rule("closer"))["undone"] == 1.0
