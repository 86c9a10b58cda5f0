"""Benchmark ``perform``: every action on the same seeded random scenes, judged on what the arm did.

    .venv/bin/python benchmarks/bench_perform.py                 # 30 scenes, render on 3 per action
    .venv/bin/python benchmarks/bench_perform.py --scenes 5 --render-scenes 0 --json out.json

For each action and scene (``scene.random_scene(seed)``) it runs ``l2p-bullet evaluate`` (``pipeline.perform``
in a worker process that keeps its bundles and world, ``--workers 1`` by default) with rendering off, and on
a subset with rendering on, then prints per action:

- success rate: the project's rule-based evaluator on the *executed* trajectory (trajectory.json
  from the simulator), not on the plan;
- plan vs execution: the block's largest distance from the planned path during the slide, its final
  distance from the plan's goal, and how far the anchor was pushed;
- wall time per stage (parse, load, plan, execute, evaluate, total) inside the worker, per run;
- the cold command-line cost: ``l2p-bullet perform --no-render`` as a fresh process (Python start,
  imports, torch) on a few scenes, and ``l2p-bullet --help``.

Goals (issue 5): 95 % or more per action; perform without rendering under 3 s per command on 2 cores;
``--help`` under 0.3 s.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SENTENCES = {
    "closer": "move A closer to B",
    "away": "move A away from B",
    "next-to": "move A next to B",
    "past": "move A past B",
    "around": "move A around B",
}
STAGES = ("parse", "load", "plan", "execute", "evaluate", "total")


def cli() -> list[str]:
    exe = Path(sys.executable).with_name("l2p-bullet")
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "l2p_bullet.cli"]


def help_time(repeats: int = 5) -> float:
    """Median wall time of ``l2p-bullet --help`` as a fresh process."""
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        subprocess.run([*cli(), "--help"], check=True, capture_output=True)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def cold_perform_times(seeds: list[int], tmp: Path, actions: list[str]) -> list[float]:
    """``l2p-bullet perform --no-render`` as fresh processes: what a user waits for."""
    from l2p_bullet.core.scene import random_scene, save_scene

    out = []
    for i, seed in enumerate(seeds):
        action = actions[i % len(actions)]
        scene_file = tmp / f"cold-{seed}.json"
        save_scene(random_scene(seed), scene_file)
        t = time.perf_counter()
        r = subprocess.run([*cli(), "perform", SENTENCES[action], "--scene", str(scene_file), "--no-render",
                            "--quiet", "--out", str(tmp / f"cold-{seed}-{action}")], capture_output=True, text=True)
        if r.returncode != 0:
            print(f"  cold run {action} seed {seed} failed: {r.stderr.strip()}", file=sys.stderr)
        else:
            out.append(time.perf_counter() - t)
    return out


def evaluate_rows(actions: list[str], scenes: int, render: bool, tmp: Path, workers: int) -> list[dict]:
    """``l2p-bullet evaluate`` on seeds 0..scenes-1 (each run plans with its scene's seed, as before);
    its rows in this benchmark's shape. Stage times are measured inside the worker, per run."""
    from l2p_bullet.evaluate.runner import EvaluationConfig, evaluate, load_rows

    out = tmp / ("render" if render else "fast")
    evaluate(EvaluationConfig(actions=actions, scenes=scenes, render_every=1 if render else 0), out,
             workers=workers, progress=True)
    rows = []
    for r in load_rows(out):
        ok = r["error"] is None
        rows.append({"action": r["action"], "seed": r["seed"], "render": render, "ok": ok,
                     "success": bool(r["success"]), "error": r["error"], "reason": r["reason"],
                     "final_progress": r["final_progress"], "max_deviation_m": r["max_deviation_m"],
                     "final_error_m": r["final_error_m"], "anchor_displacement_m": r["anchor_displacement_m"],
                     "timings": r["timings"] or {}})
    return rows


def summarise(rows: list[dict]) -> dict:
    ok = [r for r in rows if r["ok"]]
    def mean(key: str) -> float:
        return statistics.fmean(r[key] for r in ok) if ok else float("nan")
    def worst(key: str) -> float:
        return max((r[key] for r in ok), default=float("nan"))
    return {
        "runs": len(rows), "errors": len(rows) - len(ok),
        "success_rate": sum(r["success"] for r in rows) / max(len(rows), 1),
        "mean_final_progress": statistics.fmean(r["final_progress"] or 0.0 for r in ok) if ok else float("nan"),
        "mean_max_deviation_mm": 1000 * mean("max_deviation_m"), "worst_max_deviation_mm": 1000 * worst("max_deviation_m"),
        "mean_final_error_mm": 1000 * mean("final_error_m"), "worst_anchor_displacement_mm": 1000 * worst("anchor_displacement_m"),
        "time_s": {s: statistics.fmean(r["timings"].get(s, 0.0) for r in ok) if ok else float("nan") for s in STAGES},
        "max_total_s": max((r["timings"]["total"] for r in ok), default=float("nan")),
    }


def print_table(title: str, summary: dict[str, dict]) -> None:
    print(f"\n{title}")
    head = (f"{'action':<8} {'success':>8} {'progress':>8} {'dev mm':>7} {'dev max':>7} {'end mm':>7} "
            f"{'anchor':>7} " + " ".join(f"{s:>8}" for s in STAGES) + f" {'max tot':>8}")
    print(head)
    print("-" * len(head))
    for action, s in summary.items():
        t = s["time_s"]
        print(f"{action:<8} {100 * s['success_rate']:7.0f}% {s['mean_final_progress']:8.2f} "
              f"{s['mean_max_deviation_mm']:7.1f} {s['worst_max_deviation_mm']:7.1f} {s['mean_final_error_mm']:7.1f} "
              f"{s['worst_anchor_displacement_mm']:7.2f} " + " ".join(f"{t[k]:8.2f}" for k in STAGES)
              + f" {s['max_total_s']:8.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", type=int, default=30, help="random scenes (seeds 0..N-1)")
    ap.add_argument("--render-scenes", type=int, default=3, help="of those, how many also run with rendering")
    ap.add_argument("--cold", type=int, default=5, help="fresh-process perform runs to time")
    ap.add_argument("--actions", default=",".join(SENTENCES), help="comma-separated actions")
    ap.add_argument("--workers", type=int, default=1,
                    help="evaluate's worker processes (1: stage times without a neighbour on the cores)")
    ap.add_argument("--json", type=Path, default=None, help="also write every row and the summary here")
    args = ap.parse_args()

    actions = [a for a in args.actions.split(",") if a]
    t_all = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="bench-perform-") as td:
        tmp = Path(td)
        rows = evaluate_rows(actions, args.scenes, False, tmp, args.workers)
        if args.render_scenes:
            rows += evaluate_rows(actions, args.render_scenes, True, tmp, args.workers)
        cold = cold_perform_times(list(range(args.cold)), tmp, actions) if args.cold else []
    fast = {a: summarise([r for r in rows if r["action"] == a and not r["render"]]) for a in actions}
    rendered = {a: summarise([r for r in rows if r["action"] == a and r["render"]]) for a in actions}
    h = help_time()
    print_table(f"perform without rendering, {args.scenes} random scenes per action (l2p-bullet evaluate, stage seconds inside the worker)", fast)
    if args.render_scenes:
        print_table(f"perform with rendering, first {args.render_scenes} scenes per action", rendered)
    if cold:
        print(f"\ncold `l2p-bullet perform --no-render` (fresh process): median {statistics.median(cold):.2f} s, "
              f"max {max(cold):.2f} s over {len(cold)} runs")
    print(f"`l2p-bullet --help`: median {h:.3f} s")
    print(f"benchmark wall time {time.perf_counter() - t_all:.0f} s")
    if args.json:
        args.json.write_text(json.dumps({"rows": rows, "fast": fast, "rendered": rendered, "cold_s": cold,
                                         "help_s": h}, indent=1))


if __name__ == "__main__":
    main()
