"""The two searches over a proposal distribution: greedy with back-up (the paper's) and beam search.

Both stop as soon as the best path's progress reaches the threshold ("threshold") or the step budget is
spent ("budget"); a step is one batch of candidates scored in one forward pass. Both return the best
path seen, which is not always the last one tried.
"""

from __future__ import annotations

from .problem import Node, Problem, Proposer

IMPROVE = 1e-4
"""A move must raise progress by more than this to be kept (otherwise the greedy search backs up)."""


def greedy(problem: Problem, proposer: Proposer, candidates: int) -> tuple[Node, str, int]:
    """Random search with back-up: keep the candidate that raises progress most; back up when none does.

    Backing up marks the abandoned move as dead at its parent, so a deterministic proposal set (the
    discrete space) tries its next-best move instead of the same one again; with such a set, a start
    from which no move helps ends the search (nothing new can happen). A random set draws new moves each
    step, so a batch with no legal move at the start is drawn again: from a block touching the anchor most
    moves run into it, or put a pusher's fingers into it, and one batch of them says nothing of the next.
    """
    fixed = getattr(proposer, "deterministic", False)
    root = problem.root()
    best, stack, steps = root, [root], 0
    while problem.go_on(best, steps):
        steps += 1
        node = stack[-1]
        kids = problem.children([node], [proposer(problem, node, candidates)])
        top = max(kids, key=lambda k: k.progress, default=None)
        if top is not None and top.progress > node.progress + IMPROVE:
            stack.append(top)
            if top.progress > best.progress:
                best = top
        elif len(stack) > 1:
            stack.pop()
            stack[-1].dead.append(node.pose.copy())
        elif fixed:
            break  # nothing new to try from the start: no point spending the budget
    return best, ("threshold" if best.progress >= problem.threshold else "budget"), steps


def beam(problem: Problem, proposer: Proposer, candidates: int, width: int) -> tuple[Node, str, int]:
    """Beam search: expand every path of the beam, keep the ``width`` best of parents and children.

    Keeping parents in the pool is the beam's back-up: a step whose children are all worse leaves the
    beam as it was (a deterministic proposal set then stops early, as nothing new can happen).
    """
    root = problem.root()
    beam_, best, steps = [root], root, 0
    while problem.go_on(best, steps):
        steps += 1
        per = max(1, candidates // len(beam_))
        kids = problem.children(beam_, [proposer(problem, b, per) for b in beam_])
        pool = sorted(kids + beam_, key=lambda k: k.progress, reverse=True)[:width]
        if all(any(p is b for b in beam_) for p in pool) and getattr(proposer, "deterministic", False):
            break
        beam_ = pool
        if beam_[0].progress > best.progress:
            best = beam_[0]
    return best, ("threshold" if best.progress >= problem.threshold else "budget"), steps
