"""Benchmark chains of instructions (issue 21 part 4): ``l2p-bullet evaluate --chains K``, judged as CALVIN is.

    .venv/bin/python benchmarks/bench_chains.py                       # 50 chains of 5, 1 worker
    .venv/bin/python benchmarks/bench_chains.py --chains 1000 --workers 8 --json out.json   # the goal size
    .venv/bin/python benchmarks/bench_chains.py --draw sentence --chains 100 --seed 8000   # drawn whole, refusals
    .venv/bin/python benchmarks/bench_chains.py --plan-only --chains 200 --seed 11000   # refusals, nothing run

Random scenes of 3-5 blocks (``evaluate/chains.py``: seeded, seeds --seed .. --seed+N-1), one chain of K
clauses each, drawn over the installed one-anchor actions and random mover/anchor pairs; a clause that
cannot be planned from the state the previous clauses' plans predict is drawn again (counted); with
``--draw sentence`` the chain's clauses are drawn first and the chain is planned as a whole, or refused up
front (the refusals counted by clause and check; issue 44). Each chain is performed as ``perform`` performs
one (one episode, each clause re-planned from the simulated world) and every clause judged on its own
frames by its action's judge. Printed: success of the first 1..K clauses, the average number completed,
per-action clause success, failures by stage, the largest move of a block a clause did not move, time per
chain.

Goal (issue 21): on 1,000 chains of 5, average completed >= 4.8, one-clause success equal to today's
single-action success within 1 %, no block other than the mover moved > 1 mm, no crash, no failure
half-way through a clause's execution. The default size here (50) is what a shared machine runs in
minutes; the goal size is 1,000.

``--plan-only`` (drawn whole): the chains are drawn and planned as a whole as ``--draw sentence`` does, in this
process, and nothing is performed: printed are the refusals by clause and check, the planning ratio, and how many
planned clauses their judge accepts on the plan (what the run would have to do). Seconds, not minutes, a chain.
With ``--json`` each chain's row carries every clause's chosen end and its planned end pose, so two commits' runs
can be compared plan for plan.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--chains", type=int, default=50, help="number of chains (one scene each); goal size 1000")
    ap.add_argument("--clauses", type=int, default=5, help="clauses per chain (K)")
    ap.add_argument("--seed", type=int, default=0, help="first scene seed")
    ap.add_argument("--draw", choices=("clause", "sentence"), default="clause",
                    help="draw each clause until it plans (clause), or the whole sentence first (sentence)")
    ap.add_argument("--workers", type=int, default=1, help="worker processes")
    ap.add_argument("--out", default=None, help="evaluation folder (default: a temporary one)")
    ap.add_argument("--json", dest="json_out", default=None, help="also write the numbers here")
    ap.add_argument("--plan-only", action="store_true",
                    help="draw whole and plan only: refusals and the planning ratio, nothing performed")
    ap.add_argument("--list", action="store_true", help="with --plan-only: one line per chain")
    args = ap.parse_args(argv)
    if args.plan_only:
        return plan_only(args)

    from l2p_bullet.evaluate.chains import chain_report, chain_report_text
    from l2p_bullet.evaluate.runner import EvaluationConfig, evaluate, load_rows

    with tempfile.TemporaryDirectory(prefix="bench-chains-") as tmp:
        out = Path(args.out) if args.out else Path(tmp) / "eval"
        config = EvaluationConfig(chains=args.clauses, scenes=args.chains, seed=args.seed, chain_draw=args.draw)
        t0 = time.perf_counter()
        summary = evaluate(config, out, workers=args.workers, progressbar=True)
        wall = time.perf_counter() - t0
        rows = load_rows(out)
    rep = chain_report(rows)
    per_chain = [r["total_s"] for r in rows if r.get("total_s") is not None]
    rep |= {"wall_s": round(wall, 1), "workers": args.workers, "seed": args.seed, "draw": args.draw,
            "seconds_per_chain": round(sum(per_chain) / len(per_chain), 2) if per_chain else None,
            "runs": summary.ran, "errors_text": sorted({str(r["error"])[:120] for r in rows if r.get("error")})}
    print(chain_report_text(rep))
    print(f"{len(rows)} chains in {wall:.0f} s with {args.workers} worker(s), "
          f"{rep['seconds_per_chain']} s per chain in the worker")
    if args.json_out:
        Path(args.json_out).write_text(json.dumps(rep, indent=1, default=float) + "\n")
    return 0


def plan_chain(seed: int, clauses_k: int, plugins: list, actions: list[str]) -> dict:
    """One chain of ``--draw sentence`` drawn and planned as the worker does (evaluate/chains.py: run_chain), not
    performed: its refusal or the judge's verdicts on its planned clauses, and its planning seconds."""
    import numpy as np

    from l2p_bullet.arms import fit_scene
    from l2p_bullet.chain.forecast import Search, forecast
    from l2p_bullet.errors import L2PError
    from l2p_bullet.evaluate.chains import chain_rng, chain_scenes, draw_sentence
    from l2p_bullet.plugins import arms as arm_plugins

    spec = chain_scenes(1, seed)[0]
    arm = arm_plugins.get("panda")
    scene = fit_scene(spec.scene.validate(), arm)
    clauses = draw_sentence(scene, clauses_k, actions, chain_rng(seed, clauses_k), plugins)
    search, t0 = Search(), time.perf_counter()
    row = {"seed": seed, "sentence": ", then ".join(c.text for c in clauses)}
    try:
        steps = forecast(clauses, scene, plugins, planner="default", seed=seed, arm=arm, search=search)
    except L2PError as e:
        return row | {"refused": str(e), "plans": search.plans, "forecast": time.perf_counter() - t0}
    return row | {"refused": None, "plans": search.plans, "forecast": time.perf_counter() - t0,
                  "alone": search.kept_seconds, "changed": list(search.changed),
                  "ends": [s.end.to_dict() for s in steps], "plan_ends": [np.round(s.forecast.path[-1], 6).tolist()
                                                                     for s in steps],
                  "accepted": [bool(s.forecast.extra["verdict"]["success"]) for s in steps]}


def plan_only(args: argparse.Namespace) -> int:
    """``--plan-only``: the chains planned as a whole, refusals and planning ratio counted, nothing performed."""
    import os
    import statistics

    for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):  # one core, as a pool's worker
        os.environ.setdefault(name, "1")  # (numpy not imported yet: its threads fight on a shared machine)

    from l2p_bullet.evaluate.chains import refusal_causes
    from l2p_bullet.evaluate.runner import BUILTIN_PACKAGE
    from l2p_bullet.plugins import registry

    plugins = registry.discover()
    actions = [p.name for p in plugins if p.ok and p.package == BUILTIN_PACKAGE]
    t0 = time.perf_counter()
    rows = []
    for seed in range(args.seed, args.seed + args.chains):
        r = plan_chain(seed, args.clauses, plugins, actions)
        rows.append(r)
        if args.list:
            what = r["refused"] or (f"planned, judge accepts {sum(r['accepted'])}/{len(r['accepted'])}, "
                                    f"ratio {r['forecast'] / max(r['alone'], 1e-9):.2f}, changed {r['changed']}")
            print(f"{seed}: {what} [{r['plans']} plans] :: {r['sentence']}", flush=True)
    refused = [r for r in rows if r["refused"]]
    planned = [r for r in rows if not r["refused"]]
    ratios = [r["forecast"] / r["alone"] for r in planned if r["alone"]]
    causes = refusal_causes([{"error": r["refused"]} for r in refused])
    rejected = sum(not a for r in planned for a in r["accepted"])
    rep = {"chains": len(rows), "refused": len(refused), "refused_by": causes,
           "refused_seeds": [r["seed"] for r in refused],
           "ratio_mean": statistics.fmean(ratios) if ratios else None,
           "ratio_of_sums": (sum(r["forecast"] for r in planned) / sum(r["alone"] for r in planned)) if planned
           else None, "ratio_max": max(ratios, default=None),
           "clauses_judge_rejects": rejected, "ends_changed": sum(bool(r["changed"]) for r in planned),
           "wall_s": round(time.perf_counter() - t0, 1)}
    print(f"plan only, {len(rows)} chains from seed {args.seed}: refused {len(refused)} "
          f"({100 * len(refused) / max(len(rows), 1):.1f} %)" + (": " + ", ".join(f"{c} {n}" for c, n in
                                                                          causes.items()) if causes else ""))
    print(f"refused seeds: {rep['refused_seeds']}")
    if ratios:
        print(f"planning a chain / its clauses alone: {rep['ratio_mean']:.2f} mean, {rep['ratio_of_sums']:.2f} of "
              f"the sums, {rep['ratio_max']:.1f} at most; planned clauses their judge rejects on the plan: "
              f"{rejected}; chains with another end: {rep['ends_changed']}; {rep['wall_s']:.0f} s")
    if args.json_out:
        Path(args.json_out).write_text(json.dumps(rep | {"rows": rows}, indent=1, default=float) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
