"""Planner thresholds on chain starts (issue 21): each clause start of seeded chains, planned in 2-D at each threshold.

    .venv/bin/python benchmarks/bench_thresholds.py --seed 5300 --chains 100 --draw-with $OLD   # the choice
    .venv/bin/python benchmarks/bench_thresholds.py --seed 5400 --chains 150 --draw-with $OLD \\
        --thresholds closer=0.95,0.97 away=0.97,0.99 next-to=0.9,0.97 past=0.9,0.99          # the confirmation

    with OLD="closer=0.95 away=0.97 next-to=0.9 past=0.9 around=0.9", the thresholds before the choice
    (docs/planning.md, "Thresholds on chain starts")

    .venv/bin/python benchmarks/bench_thresholds.py --seed 5300 --chains 100 --thresholds closer=0.97 \
        --bounds-off closer       # closer's going-back bound (planning/bounds.py), off and on: 97 / 98 of 103
    .venv/bin/python benchmarks/bench_thresholds.py --seed 5300 --chains 100 --thresholds past=0.99 \
        --bounds-off past:ends_beyond   # at bd00abd only (not adopted, docs/planning.md): past's end, off and on
    .venv/bin/python benchmarks/bench_thresholds.py --seed 5300 --chains 100 --thresholds around=0.9 \
        --turning-off             # around's turning way round (planning/detour.py), off and on: 70 / 72 of 77

The clause starts are the states ``evaluate --chains 5`` draws over the five built-in actions
(``evaluate/chains.draw_chain``: each clause from the end state the earlier clauses' plans predict, in the
Panda's workspace), which depend on the thresholds in force while they are drawn: the bundles' own, or
``--draw-with``'s. Each start whose clause is action A
is planned again with A's ``[policy] threshold`` set to each value asked, and the 2-D plan is judged by A's rule
judge, as the chain's forecast judges it; a refusal counts as a failure. Printed: successes per action and
threshold, and the seconds spent planning. The models are not touched; the rule judges are read only here, to
report, never by the planner.

``--bounds-off A ...``: the bounds from people's data of those actions (``planning.PEOPLE_BOUNDS``: past's room,
closer's going back; a built-in action's name is its rule judge's) are off while the chains are drawn, as before
they were in, and each of their rows is planned twice, with the bound off and on: how a bound was chosen and
confirmed (docs/planning.md). ``--turning-off``: the same for the way round that turns the block
(``detour.TURN_COST``, with the squared yaws; around's rows).
"""

from __future__ import annotations

import argparse
import contextlib
import sys
import time

DEFAULT = ("closer=0.95,0.97,0.99", "away=0.97,0.99", "next-to=0.9,0.95,0.97,0.99", "past=0.9,0.95,0.97,0.99",
           "around=0.9,0.95,0.97")


def set_threshold(action: str, threshold: float, plugins: list):
    """The loaded (and cached: ``registry.load``) bundle of ``action``, planning to ``threshold`` from now on."""
    from l2p_bullet.plugins import registry

    bundle = registry.load(action, plugins)
    bundle.manifest.setdefault("policy", {})["threshold"] = threshold
    return bundle


def starts(seed: int, chains: int, clauses: int, actions: list[str], plugins: list, arm) -> list[tuple]:
    """(seed, predicted scene, clause) for every clause of the chains of seeds ``seed`` .. ``seed + chains - 1``."""
    from l2p_bullet.arms import fit_scene
    from l2p_bullet.evaluate.chains import chain_rng, chain_scenes, draw_chain

    out = []
    for spec in chain_scenes(chains, seed):
        scene = fit_scene(spec.scene.validate(), arm)
        steps, _ = draw_chain(scene, clauses, actions, chain_rng(spec.seed, clauses), plugins, planner="default",
                              seed=spec.seed, budget=None, threshold=None, arm=arm)
        for step in steps:
            out.append((spec.seed, scene, step.clause))
            scene = scene.with_pose(step.clause.command.mover, step.forecast.path[-1])
    return out


@contextlib.contextmanager
def bounds_off(rules: set[str]):
    """The planner without the bounds from people's data of the rule judges named (``planning.PEOPLE_BOUNDS``)."""
    import l2p_bullet.planning as planning

    real = planning.PEOPLE_BOUNDS
    planning.PEOPLE_BOUNDS = {name: weight for name, weight in real.items() if name not in rules}
    try:
        yield
    finally:
        planning.PEOPLE_BOUNDS = real


@contextlib.contextmanager
def turning_off(off: bool = True):
    """The planner without the way round that turns the block (``planning.detour.TURN_COST`` None), if ``off``."""
    from l2p_bullet.planning import detour

    real = detour.TURN_COST
    detour.TURN_COST = None if off else real
    try:
        yield
    finally:
        detour.TURN_COST = real


def judged(pairs: list[tuple], action: str, threshold: float, plugins: list, arm) -> tuple[int, int, float]:
    """Successes, starts and seconds for ``action``'s starts planned with ``threshold``."""
    from l2p_bullet.chain.forecast import forecast
    from l2p_bullet.errors import L2PError

    bundle = set_threshold(action, threshold, plugins)
    ok = n = 0
    t0 = time.perf_counter()
    for seed, scene, clause in pairs:
        if clause.command.action != action:
            continue
        n += 1
        try:
            step = forecast([clause], scene, plugins, planner="default", seed=seed, budget=None, threshold=None,
                            bundles={action: bundle}, arm=arm)[0]
        except L2PError:
            continue
        ok += bool(step.forecast.extra["verdict"]["success"])
    return ok, n, time.perf_counter() - t0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, default=5300, help="first chain seed (analysis seeds: 5000 on)")
    ap.add_argument("--chains", type=int, default=100)
    ap.add_argument("--clauses", type=int, default=5)
    ap.add_argument("--thresholds", nargs="+", default=list(DEFAULT), help="ACTION=T,T,... (default: the sweep)")
    ap.add_argument("--draw-with", nargs="*", default=[], help="ACTION=T: thresholds while the chains are drawn")
    ap.add_argument("--bounds-off", nargs="*", default=[], metavar="ACTION",
                    help="these actions' bounds from people's data off while drawn; their rows planned off and on")
    ap.add_argument("--turning-off", action="store_true",
                    help="around's turning way round off while drawn; around's rows planned off and on")
    args = ap.parse_args(argv)

    from l2p_bullet.plugins import arms as arm_plugins
    from l2p_bullet.plugins import registry

    plugins = registry.discover()
    arm = arm_plugins.get("panda")
    grid = {a: [float(t) for t in ts.split(",")] for a, ts in (s.split("=", 1) for s in args.thresholds)}
    actions = ["around", "away", "closer", "next-to", "past"]
    for a, t in (d.split("=", 1) for d in args.draw_with):
        set_threshold(a, float(t), plugins)
    import l2p_bullet.planning as planning

    off = set(args.bounds_off)
    if off - set(planning.PEOPLE_BOUNDS):
        ap.error(f"--bounds-off: no bound from people's data: {', '.join(sorted(off - set(planning.PEOPLE_BOUNDS)))} "
                 f"(those with one: {', '.join(sorted(planning.PEOPLE_BOUNDS))})")
    t0 = time.perf_counter()
    turning = {"around"} if args.turning_off else set()
    with bounds_off(off), turning_off(bool(turning)):
        pairs = starts(args.seed, args.chains, args.clauses, actions, plugins, arm)
    print(f"{len(pairs)} clause starts of chain seeds {args.seed}-{args.seed + args.chains - 1} "
          f"({time.perf_counter() - t0:.0f} s)\n")
    print("| action | threshold | bound | successes | starts | s |\n|---|---:|---|---:|---:|---:|")
    for action, thresholds in grid.items():
        for t in thresholds:
            for bound in (("off", "on") if action in off | turning else ("on",)):
                with bounds_off(off if bound == "off" else set()), turning_off(bound == "off" and action in turning):
                    ok, n, s = judged(pairs, action, t, plugins, arm)
                print(f"| {action} | {t:g} | {bound} | {ok} | {n} | {s:.0f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
