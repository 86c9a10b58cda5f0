"""Plan the mover's 2-D path for an action: search for moves that make the learned progress rise to 1.

The planners differ only in where candidate moves come from and how the search keeps them (see
docs/planning.md):

- ``greedy``    the paper's baseline: random moves around the mover, keep the best, back up when none helps;
- ``beam``      beam search over the same random moves;
- ``discrete``  greedy search with back-up over the qualitative space, cardinal direction x quantised
                distance around the anchor;
- ``reinforce`` greedy search with back-up over moves proposed by the action's REINFORCE-trained Gaussian
                policy (stored in its bundle);
- ``mixed``     greedy search with back-up over all of the above at once (one forward pass per step);
- ``default``   an alias (``DEFAULT``), unless the bundle's ``[policy]`` section names another planner.

Every planner maximises the action's learned progress model: the model alone decides which move is
better. The 2-D simulator only says which moves are legal; the judge (``judge/``) judges the result afterwards,
and an action's rule judge also says whether a path the model rates done may end the search (problem.held_short).
"""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Sequence

import numpy as np

from ..actions import ActionSpec, Planning
from ..arms import PANDA, ArmSpec
from ..arms.reach import Wrist
from ..core.contracts import Plan
from ..core.scene import Scene
from ..core.threads import torch_threads
from ..errors import InfeasibleError, PlanError, UnknownPlannerError
from ..judge.base import judge_context
from ..judge.footprints import outlines_of
from ..judge.rules import RULE_SPECS, RULES, RuleJudge
from . import approach, policy  # called as policy.load_policy: a test stands in a policy there
from .already import already, standing_plan
from .bounds import BoundScorer, people_weights
from .detour import around_route
from .feasibility import check_moves, grasp_holds
from .nearer import nearer_path
from .problem import FRAME_STEP, Node, Problem, finish
from .proposals import MixedProposer, discrete_moves, random_moves
from .refine import refine
from .search import beam, greedy
from .squares import squares_scorer
from .world2d import World2D, interpolate

PLANNERS: dict[str, str] = {
    "greedy": "random search with back-up (the paper's baseline)",
    "beam": "beam search over random moves",
    "discrete": "greedy search over cardinal direction x distance around the anchor",
    "reinforce": "greedy search over moves proposed by the action's REINFORCE policy",
    "mixed": "greedy search over the discrete cells, the policy's proposals and random moves together",
    "default": "the action's preferred planner (see DEFAULT)",
}
DEFAULT = "mixed"

THRESHOLD = 0.9
"""Stop when the learned progress reaches this (the models rise to about 1 at an event's end)."""

BUDGETS = {"greedy": 40, "beam": 15, "discrete": 30, "reinforce": 30, "mixed": 20}
"""Default step budgets (a step = one batch of candidates scored in one forward pass)."""

TARGET_BUDGET = 2
"""With a target (a composite's slot) the default budget is doubled: a slot that a block of the row hides
takes a way round, which costs steps (chosen after two 5-block rows of the benchmark's seeds 50035 and
50049 stopped one approach point short of their slot; the reported run uses other seeds)."""

SHORT_REACH = 5
"""Without a target the default budget is this many times ``BUDGETS``. Every search stops as soon as the
progress reaches the threshold, so a plan that reached it within ``BUDGETS`` steps is the same step for step;
only a search that would have ended short of it goes on. Why: starts close to the anchor, where most proposals
collide, ended the budget at progress 0.2-0.7 (a "closer" 1.4-2.2 blocks away: 16 of 39 analysis starts,
seeds 5000+; 12 with 5x the budget, 10 with the final refinement too, ``refine.py``)."""

CHECK_CAP = 20_000
"""With the default budget, a plan's searches take no step once this many candidate moves have been proposed
(all its grasp holds together; ``Problem.check_cap``), and a grasp hold is not tried when none are left;
``extra["bounded"]`` says so. A deterministic bound on a plan's work, unlike a time limit: the same seed gives
the same plan on any machine and load. Why: a search short of the threshold goes on to ``SHORT_REACH`` x its
budget, about 19,300 candidates (100 steps of about 190, most blocked near the anchor, each tested for
legality), and then the second grasp hold did the same again: 20-50 s plans (plan only, 2 busy cores),
minutes within a benchmark. 20,000 is one grasp's whole long search plus its refinement. Chosen on plans only
of ``benchmarks/bench_objects.py`` seeds 951000-951038 (panda, 174 plans): every plan that reached the
threshold with one grasp spent at most 19,414; 16 plans spent 38,500-39,600 with two grasps, all short of the
threshold but one ("next-to" seed 951037: 32,594, the second grasp reached it after 68 steps), which the cap
ends short."""

CANDIDATES = {"greedy": 32, "beam": 48, "discrete": 0, "reinforce": 16, "mixed": 16}
BEAM_WIDTH = 4


def resolve_planner(name: str, settings: dict | None = None) -> str:
    """The concrete planner behind ``name`` ("default" follows the bundle's settings); UnknownPlannerError if
    unknown."""
    key = name.strip().lower()
    if key not in PLANNERS:
        raise UnknownPlannerError(name, PLANNERS)
    if key == "default":
        key = str((settings or {}).get("planner", DEFAULT))
        if key not in PLANNERS or key == "default":
            raise UnknownPlannerError(key, [p for p in PLANNERS if p != "default"], "the bundle's [policy] names an ")
    return key


def plan(scene: Scene, mover: str, anchor: str | Sequence[str], bundle, *, planner: str = "default", seed: int = 0,
         budget: int | None = None, threshold: float | None = None, time_limit: float | None = None,
         target: np.ndarray | None = None, arm: ArmSpec = PANDA, airborne: bool = False,
         outline: np.ndarray | None = None, pusher: tuple[float, float] | None = None) -> Plan:
    """Plan ``mover``'s path for the bundle's action relative to ``anchor`` in ``scene``.

    ``anchor`` is one object's name, or the names of every reference object of a two-anchor action
    ("between B and C": ``("B", "C")``); every object but the mover is an obstacle either way, so the
    anchors are never touched. Deterministic for a seed. ``budget`` counts search steps (forward passes of
    the progress model); ``time_limit`` (seconds), when given, also ends the search (for equal-time
    comparisons).

    The world's obstacles are what the arm meets: the mover's outline, grown against each taller object
    by the hand beside it (``arms.reach``). When the hand's orientation matters, each grasp angle
    whose hand clears the start (``reach.holds``) is planned and the plan reaching the higher progress is
    kept (``extra["grasp_angle_deg"]``, None when any multiple of 90 degrees will do). Paths that no grasp
    yaw can follow within the wrist's range are illegal.
    A mover that starts closer than the margin to another object may move away from it (world2d.py).
    ``target`` ([x, y, yaw]): where the mover should end (a composite's slot): the model's scores are
    weighted by the end's closeness to it and it is proposed from every node (target.py).
    ``airborne`` (a manner that carries the block, l2p_bullet/manners): objects other than the anchors are
    obstacles only where a move ends (the block may be set down there), not along the way (World2D's
    ``over``); the anchors stay obstacles all the way (the block goes past or around them, not over them). ``outline``
    (K,2,
    block frame): what the manner puts at block height, tested against every other object instead of the
    block and the hand beside it. ``pusher`` (a push, ``embodiment.manners.push_pusher``): the fingers' depth and
    half width, tested behind the block along every move (World2D); nothing is held, so no hand beside it.
    """
    settings = dict(getattr(bundle, "manifest", {}).get("policy", {}))
    name = resolve_planner(planner, settings)
    anchors = [anchor] if isinstance(anchor, str) else list(anchor)
    anchor = anchors[0]
    if mover in anchors:
        raise PlanError(f'the mover and the anchor are the same object "{mover}"')
    anchor_obj = scene.get(anchor)
    more_poses = [scene.get(a).pose for a in anchors[1:]]
    model = bundle.progress_model()
    # the objects' real footprints for the model's gap features, where one is not a cube (progress/features.py)
    footprints = outlines_of([scene.get(o) for o in (mover, *anchors)]) if getattr(model, "reads_outlines", False) \
        else None
    # a model that reads squares is asked about an anchor that is not a cube as a square at its real gaps
    model = squares_scorer(model, anchor_obj, len(anchors))
    needed = getattr(model, "anchors", 1)
    if len(anchors) != needed:
        raise PlanError(f'the action "{bundle.name}" takes {needed} reference object(s), '
                        f"not {len(anchors)} ({', '.join(anchors)})")
    spec = rule_spec(bundle)
    if target is None:  # a composite's slot is planned to the slot, wherever the mover stands
        verdict = already(scene, mover, anchors, spec)
        if verdict is not None:  # the relation already holds: nothing to move (already.py)
            return standing_plan(scene, mover, anchors, str(bundle.name), name, verdict, model)
    holds = grasp_holds(scene, mover, arm)  # InfeasibleError when no grasp's hand clears the start
    deadline = None if time_limit is None else time.perf_counter() + time_limit
    # a composite's slot (target) is planned to the slot alone: no lead-in and no bound from people's data
    lead_in = spec.planning.lead_in if target is None and spec is not None else None
    bound = None if target is not None else _people_bound(bundle, spec)  # bounds.py
    # a composite's slot is planned to the slot alone; elsewhere the model's "done" ends the search only where
    # the action's rule judge agrees (problem.held_short)
    accepts = None if target is not None else _rule_accepts(bundle, scene, mover, anchors, model)
    best, refused, bounded, spent = None, None, False, 0
    def world_of(hold) -> tuple[World2D, Wrist]:
        outlines = hold.outlines if outline is None else {o.name: outline for o in scene.objects if o.name != mover}
        if pusher is not None:  # nothing is held: the block's own outline, the fingers behind it (World2D)
            outlines = {} if outline is None else outlines
        over = frozenset(o.name for o in scene.objects if airborne and o.name != mover and o.name not in anchors)
        return (World2D(scene, mover, outlines=outlines, over=over, pusher=pusher),
                Wrist(hold.angle, base_xy=arm.mount[:2], arm=arm))

    for hold in holds:
        cap = None if budget is not None or CHECK_CAP is None else CHECK_CAP - spent
        if cap is not None and cap <= 0:
            bounded = True  # the earlier grasps spent the plan's candidates: this one is not tried
            break
        world, wrist = world_of(hold)
        arcs = target is None and any(b.name not in anchors for b in world.obstacles)
        routes: dict[tuple, np.ndarray | None] = {}  # a way round from each approach end asked about
        way_round = functools.partial(_way_round, world, anchor_obj.pose, routes, lead_in)
        try:  # from afar: first a straight slide to where people start it (approach.py); among bystanders to
            # an end with a way round the anchor
            lead = approach.lead_in(world, anchor_obj.pose, lead_in.near, lead_in.approach,
                                    FRAME_STEP * world.size, wrist, mover, anchor,
                                    way_round=way_round if arcs else None) if lead_in else None
        except InfeasibleError as e:
            refused = e
            continue
        scorer = (_target_scorer(model, target, world) if target is not None
                  else BoundScorer(model, bound) if bound is not None else model)
        problem = Problem(
            world=world,
            model=scorer,
            anchor_pose=anchor_obj.pose,
            size=world.size,
            threshold=float(threshold if threshold is not None else settings.get("threshold", THRESHOLD)),
            budget=int(
                budget if budget is not None else BUDGETS[name] * (TARGET_BUDGET if target is not None else SHORT_REACH)
            ),
            rng=np.random.default_rng(seed),
            wrist=wrist,
            more_anchor_poses=more_poses,
            viewer=getattr(model, "viewpoint", None),
            lead_in=lead,
            check_cap=cap,
            reach=_reach(lead_in) * world.size if lead_in else None,
            outlines=footprints,
            accepts=accepts,
        )
        problem.deadline = deadline
        if not (arcs and lead_in):
            route = None
        elif lead is not None and _route_key(world, anchor_obj.pose, lead_in, lead) in routes:
            route = routes[_route_key(world, anchor_obj.pose, lead_in, lead)]
        else:
            route = around_route(world, anchor_obj.pose, lead_in.near, start=None if lead is None else lead[-1],
                                 swept=0.0 if lead is None else _route_key(world, anchor_obj.pose, lead_in, lead)[-1])
        with torch_threads(1):  # a test double or a caller may score in torch: small batches, one thread
            node, stopped, steps = _search(name, problem, bundle, target, arcs=arcs, route=route)
            if route is not None and stopped != "threshold":  # the search stalled: the way round as it is
                node, stopped = _follow(problem, route, node, stopped)
            refined = 0
            if target is None and stopped != "threshold":  # short of the threshold: polish the last move locally
                node, refined = refine(problem, node)
                stopped = "threshold" if node.progress >= problem.threshold else stopped
        bounded, spent = bounded or problem.bounded, spent + problem.checked
        if best is None or node.progress > best[1].progress + 1e-9:
            best = (problem, node, stopped, steps, hold, refined)
        if stopped == "threshold":
            break  # good enough: the first grasp (the roomier one) reached the threshold
    if best is None:
        raise refused  # no grasp has a way to come near (a lead-in from afar)
    problem, node, stopped, steps, hold, refined = best
    result = finish(problem, node, action=str(bundle.name), mover=mover, anchor=anchor, planner=name,
                    stopped=stopped, steps=steps, more_anchors=anchors[1:])
    if target is None:  # "closer" from touching or level: the room is in turning square, sliding in (nearer.py)
        way = nearer_path(scene, mover, anchor, spec, result.path[-1], problem.world, problem.wrist,
                          turns=pusher is None)
        for other in (h for h in holds if way is None and h is not hold):  # a grasp with the fingers aside
            way = nearer_path(scene, mover, anchor, spec, result.path[-1], *world_of(other), turns=pusher is None)
            hold = other if way is not None else hold
        if way is not None:
            searched = result.path[-1].round(6).tolist()
            frames = interpolate(way, FRAME_STEP * problem.size)
            p = float(problem.model.final_batch([frames], problem.anchor_pose, problem.size, **problem.context)[0])
            result = finish(problem, Node(way, frames, p, yaw=float(way[-1, 2])), action=str(bundle.name),
                            mover=mover, anchor=anchor, planner=name, stopped=stopped, steps=steps,
                            more_anchors=anchors[1:])
            result.extra["nearer"] = {"searched_end": searched}
    check_moves(scene, mover, anchor, result.path, action=str(bundle.name), stopped=stopped,
                progress=float(node.progress), steps=steps)  # a plan that goes nowhere is never a run
    if refined:
        result.extra["refine_passes"] = refined
    if bounded:  # a new field, only where CHECK_CAP ended a search that would have gone on
        result.extra["bounded"] = True
    result.extra["grasp_angle_deg"] = None if hold.angle is None else round(math.degrees(hold.angle), 6)
    if problem.lead_in is not None:  # a new field, only where there is an approach
        result.extra["approach"] = {"frames": len(problem.lead_in), "to": problem.lead_in[-1].round(6).tolist(),
                                    "blocks": lead_in.approach}
    if target is not None:
        result.extra["target"] = np.round(np.asarray(target, float), 6).tolist()
        result.extra["target_error_m"] = round(float(np.hypot(*(result.path[-1, :2] - np.asarray(target)[:2]))), 6)
    if name in ("reinforce", "mixed") and _policy_is_stale(bundle):
        result.extra["note"] = ("the bundle's policy was trained against another progress model: "
                                "re-train it: l2p-bullet train-policy")
    return result


PEOPLE_BOUNDS: dict[str, functools.partial] = {
    name: people_weights((spec.planning.bound, *spec.planning.more_bounds)) for name, spec in RULE_SPECS.items()
    if spec.planning.bound is not None}
"""Per rule judge, the bound from people's data its candidates are weighted by (bounds.py, declared by the
action that declares the rule set: ``ActionSpec.planning.bound``); an action judged by that rule judge (a
plugin's too) is planned within it. benchmarks/bench_thresholds.py turns one off to measure it."""


def rule_spec(bundle) -> ActionSpec | None:
    """The spec whose planning declarations (room checks, bound, lead-in) and thresholds plan the bundle's
    action: its own when its module declares how it is planned, else that of the action declaring the rule set
    its manifest names (``[judge] rules``: a plugin judged by "closer" is planned as closer), else None."""
    own = getattr(bundle, "spec", None)
    if isinstance(own, ActionSpec) and own.planning != Planning():
        return own
    return RULE_SPECS.get(_rules(bundle))


def _people_bound(bundle, spec: ActionSpec | None) -> functools.partial | None:
    """The bound from people's data the bundle's candidates are weighted by: its rule set's
    (:data:`PEOPLE_BOUNDS`), or the one a plugin's own spec declares."""
    if spec is None or spec is RULE_SPECS.get(_rules(bundle)):
        return PEOPLE_BOUNDS.get(_rules(bundle))
    return None if spec.planning.bound is None else people_weights((spec.planning.bound, *spec.planning.more_bounds))


def _rule_accepts(bundle, scene: Scene, mover: str, anchors: list[str], model):
    """Whether the action's rule judge (its manifest's ``[judge] rules``) accepts a path's frames, judged as a
    chain's forecast and ``perform`` judge a plan (``judge.plan_verdict``): the anchors' poses, the viewpoint, the
    real outlines where an object is not a cube. None for an action judged otherwise (a learned or a plugin's
    own judge): the model alone then says when the search is done."""
    rules = _rules(bundle)
    if rules not in RULES:
        return None
    judge = RuleJudge(rules)
    poses = [scene.get(a).pose for a in anchors]
    context = judge_context(poses, getattr(model, "viewpoint", None), judge=judge,
                            outlines=outlines_of([scene.get(o) for o in (mover, *anchors)]))
    size = scene.get(mover).size

    def accepts(frames: np.ndarray) -> bool:
        return bool(judge.judge(frames, poses[0], size, **context).success)

    return accepts


def _target_scorer(model, target: np.ndarray, world: World2D):
    from .problem import FRAME_STEP
    from .target import TargetScorer

    return TargetScorer(model, target, world, FRAME_STEP * world.size)


def _policy_is_stale(bundle) -> bool:
    """The policy records the digest of the progress model it learned to please; a re-trained model
    leaves it usable (it only proposes moves) but no longer tuned."""
    manifest = getattr(bundle, "manifest", {}) or {}
    trained = manifest.get("policy", {}).get("progress_sha256")
    current = manifest.get("weights", {}).get("progress.safetensors", {}).get("sha256")
    return bool(trained and current and trained != current)


def _follow(problem: Problem, route: np.ndarray, best, stopped: str):
    """The path along ``route``'s corners (detour.py), scored by the model move by move, if it beats ``best``
    (the search's best node); the wrist and the 2-D world check every move as they check the search's."""
    node = problem.root()
    for corner in route[1:]:
        kids = problem.children([node], [corner[None]])
        if not kids:
            return best, stopped
        node = kids[0]
    if node.progress <= best.progress:
        return best, stopped
    return node, ("threshold" if node.progress >= problem.threshold else stopped)


def _reach(lead_in) -> float:
    """How far from the anchor (blocks) a move of the search may end: the lead-in's ``reach`` (as far as people
    went), but never beyond ``near``, which the rule allows once the mover came near: a move ending between the two
    makes a plan the judge rejects ("around" a whole turn round, out to 4.08 blocks)."""
    return min(lead_in.reach, lead_in.near)


def _route_key(world: World2D, anchor_pose: np.ndarray, lead_in, frames: np.ndarray) -> tuple:
    """An approach's end pose and how far round the anchor it went since it came near (approach.swept_near)."""
    swept = approach.swept_near(frames, anchor_pose, lead_in.near * world.size)
    return (*np.asarray(frames, float)[-1], swept)


def _way_round(world: World2D, anchor_pose: np.ndarray, routes: dict, lead_in, frames: np.ndarray) -> bool:
    """Whether the 2-D world has a way round the anchor within ``lead_in.near`` from the end of the approach
    ``frames``, its turn counted from where they came near, as the rule counts it (detour.py); kept in
    ``routes``, so the approach's way is not searched twice."""
    key = _route_key(world, anchor_pose, lead_in, frames)
    routes[key] = around_route(world, anchor_pose, lead_in.near, start=frames[-1], swept=key[-1])
    return routes[key] is not None


def _rules(bundle) -> str | None:
    """The rule judge the bundle's manifest names (``[judge] rules``), if any."""
    spec = (getattr(bundle, "manifest", {}) or {}).get("judge") or {}
    rules = spec.get("rules") if isinstance(spec, dict) else None
    return rules if isinstance(rules, str) else None


def _search(name: str, problem: Problem, bundle, target: np.ndarray | None = None, arcs: bool = False,
            route: np.ndarray | None = None):
    """Run planner ``name``. ``arcs``: the mixed planner also proposes short arcs around the anchor
    (proposals.arc_moves), and ``route``'s corners (a way round the anchor, detour.py); both are set only
    where other objects than the anchors stand (bystanders), so that two-block scenes plan as before."""
    if target is not None:
        from .target import TargetProposer

        n = CANDIDATES[name]
        base = {"greedy": random_moves, "beam": random_moves, "discrete": discrete_moves,
                "mixed": MixedProposer(_policy_proposer(bundle, required=False))}.get(name)
        proposer = TargetProposer(base or _policy_proposer(bundle), target)
        return beam(problem, proposer, n, BEAM_WIDTH) if name == "beam" else greedy(problem, proposer, n)
    n = CANDIDATES[name]
    if name == "greedy":
        return greedy(problem, random_moves, n)
    if name == "beam":
        return beam(problem, random_moves, n, BEAM_WIDTH)
    if name == "discrete":
        return greedy(problem, discrete_moves, n)
    if name == "mixed":
        return greedy(problem, MixedProposer(_policy_proposer(bundle, required=False), arcs=arcs, route=route), n)
    return greedy(problem, _policy_proposer(bundle), n)


def _policy_proposer(bundle, required: bool = True):
    net = policy.load_policy(bundle)
    if net is None and not required:
        return None
    if net is None:
        raise PlanError(
            f'the action "{bundle.name}" has no trained policy in its bundle; train one with '
            f'"l2p-bullet train-policy {bundle.name}" or pick another planner (known: {", ".join(PLANNERS)})'
        )
    return policy.PolicyProposer(net)
