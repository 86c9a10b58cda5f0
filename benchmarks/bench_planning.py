"""Benchmark the 2-D planners: every planner x action on the same seeded random scenes.

    .venv/bin/python benchmarks/bench_planning.py                       # 50 scenes, all planners
    .venv/bin/python benchmarks/bench_planning.py --scenes 10 --planners discrete,greedy --json out.json
    .venv/bin/python benchmarks/bench_planning.py --bundles /tmp/bundles  # bundles in <dir>/<action>/

For each action (its installed bundle, or ``--bundles DIR/<action>``), planner and scene
(``scene.random_scene(seed)``, seeds 0..N-1; the policies are trained on seeds from 10 000 on) it plans
in-process (``l2p-bullet evaluate``'s plan mode, ``workers=0``; a direct loop for ``--bundles``) and reports:

- success: the project's rule judges (``judge/rules.py``) on the planned path; the planner never
  sees it, it maximises the action's learned progress model;
- progress: the learned model's value at the path's end (what the planner maximised);
- threshold: how often the planner stopped because progress passed the threshold (vs. its budget);
- steps (forward passes of the model) and wall time per plan, in-process, model already loaded.

With ``reinforce`` among the planners it also runs ``greedy@=t``: random search with back-up given, on
each scene, the wall time the REINFORCE planner took there (and no step limit), the issue's
equal-time comparison.

Goals (issue 4): every action >= 95 % success with the default planner, < 1 s per plan on 2 cores, and
REINFORCE better than random search with back-up at equal time.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

ACTIONS = ("closer", "away", "next-to", "past", "around")


def load(action: str, root: Path | None):
    from l2p_bullet.plugins import registry
    from l2p_bullet.plugins.bundle import load_bundle

    return load_bundle(root / action) if root else registry.load(action)


def run(action: str, bundle, planner: str, seeds: list[int], time_limits: list[float] | None = None,
        installed: bool = True) -> list[dict]:
    """One planner on the seeded scenes: through ``evaluate``'s plan mode for an installed bundle (in this
    process, ``workers=0``: a plan's time is not shared with a neighbour), else a direct loop over
    ``planning.plan`` for a bundle folder (``--bundles``), judged by the same rules."""
    if installed:
        return _run_evaluate(action, planner, seeds, time_limits)
    from l2p_bullet.core.scene import random_scene
    from l2p_bullet.judge.rules import rule_verdict
    from l2p_bullet.planning import plan

    rows = []
    for i, seed in enumerate(seeds):
        kw = {} if time_limits is None else {"time_limit": time_limits[i], "budget": 10**6}
        t = time.perf_counter()
        p = plan(random_scene(seed), "A", "B", bundle, planner=planner, seed=seed, **kw)
        dt = time.perf_counter() - t
        v = rule_verdict(action, p.path, p.anchor_pose, p.size)
        rows.append({"action": action, "planner": planner if time_limits is None else "greedy@=t", "seed": seed,
                     "success": v.success, "score": v.score, "reason": v.reason,
                     "progress": p.extra["final_progress"], "stopped": p.stopped, "steps": p.extra["steps"],
                     "seconds": dt})
    return rows


def _run_evaluate(action: str, planner: str, seeds: list[int], time_limits: list[float] | None) -> list[dict]:
    from dataclasses import replace

    from l2p_bullet.evaluate.runner import run_tasks
    from l2p_bullet.evaluate.scenes import random_scenes
    from l2p_bullet.evaluate.tasks import make_tasks

    specs = [s for seed in seeds for s in random_scenes(1, seed)]
    tasks = make_tasks(specs, [action], planner=planner, mode="plan")
    if time_limits is not None:
        tasks = [replace(t, time_limit=tl, budget=10**6) for t, tl in zip(tasks, time_limits, strict=True)]
    got: list[dict] = []
    run_tasks(tasks, workers=0, ray=None, on_row=got.append)
    rows = []
    for r in sorted(got, key=lambda r: r["idx"]):
        if r["error"]:
            raise SystemExit(f"{action} {planner} seed {r['seed']}: {r['error']}")
        rows.append({"action": action, "planner": planner if time_limits is None else "greedy@=t", "seed": r["seed"],
                     "success": bool(r["success"]), "score": r["score"], "reason": r["reason"],
                     "progress": r["final_progress"], "stopped": r["stopped"], "steps": r["plan_steps"],
                     "seconds": r["plan_s"]})
    return rows


def summarise(rows: list[dict]) -> dict:
    return {
        "n": len(rows),
        "success": sum(r["success"] for r in rows) / len(rows),
        "progress": statistics.fmean(r["progress"] for r in rows),
        "threshold": sum(r["stopped"] == "threshold" for r in rows) / len(rows),
        "steps": statistics.fmean(r["steps"] for r in rows),
        "seconds": statistics.fmean(r["seconds"] for r in rows),
        "max_seconds": max(r["seconds"] for r in rows),
    }


def table(summary: dict[tuple[str, str], dict]) -> str:
    lines = ["| action | planner | success | progress | stopped at threshold | steps | s / plan | max s |",
             "|---|---|---:|---:|---:|---:|---:|---:|"]
    for (action, planner), s in summary.items():
        lines.append(f"| {action} | {planner} | {100 * s['success']:.0f} % | {s['progress']:.3f} | "
                     f"{100 * s['threshold']:.0f} % | {s['steps']:.1f} | {s['seconds']:.3f} | {s['max_seconds']:.2f} |")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", type=int, default=50, help="random scenes (seeds 0..N-1)")
    ap.add_argument("--planners", default="default,greedy,beam,discrete,reinforce")
    ap.add_argument("--actions", default=",".join(ACTIONS))
    ap.add_argument("--bundles", type=Path, default=None, help="folder with one bundle per action (default: installed)")
    ap.add_argument("--json", type=Path, default=None, help="also write every row and the summary here")
    args = ap.parse_args()

    from l2p_bullet.planning import resolve_planner

    seeds = list(range(args.scenes))
    rows: list[dict] = []
    summary: dict[tuple[str, str], dict] = {}
    t0 = time.perf_counter()
    for action in [a for a in args.actions.split(",") if a]:
        bundle = load(action, args.bundles)
        bundle.progress_model()  # load (and warm up) outside the timings
        settings = bundle.manifest.get("policy", {})
        for planner in [p for p in args.planners.split(",") if p]:
            label = f"default ({resolve_planner('default', settings)})" if planner == "default" else planner
            if planner == "reinforce" and bundle.policy_arrays() is None:
                print(f"{action}: no policy in the bundle, skipping reinforce", file=sys.stderr)
                continue
            r = run(action, bundle, planner, seeds, installed=args.bundles is None)
            for x in r:
                x["planner"] = label
            rows += r
            summary[(action, label)] = summarise(r)
            print(f"{action:8s} {label:22s} {summary[(action, label)]}", file=sys.stderr, flush=True)
            if planner == "reinforce":
                eq = run(action, bundle, "greedy", seeds, time_limits=[x["seconds"] for x in r],
                         installed=args.bundles is None)
                rows += eq
                summary[(action, "greedy@=t")] = summarise(eq)
                print(f"{action:8s} {'greedy@=t':22s} {summary[(action, 'greedy@=t')]}", file=sys.stderr, flush=True)
    from l2p_bullet.learning.agreement import demo_acceptance, rule_agreement

    agree, accept = rule_agreement(), demo_acceptance()
    print("\nThe evaluator: Spearman with people's grades (90 graded 2-D demos) "
          + ", ".join(f"{k} {v:.2f}" for k, v in agree.items())
          + "; accepts of the people's capture demos " + ", ".join(f"{k} {100 * v:.0f} %" for k, v in accept.items()))
    print(f"\n{args.scenes} random scenes per cell, {time.perf_counter() - t0:.0f} s in all\n")
    print(table(summary))
    if args.json:
        args.json.write_text(json.dumps({"summary": {f"{a}/{p}": s for (a, p), s in summary.items()},
                                         "rows": rows}, indent=1) + "\n")


if __name__ == "__main__":
    main()
