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
  imports, plugin discovery, planning, simulation, files) on a few scenes, each run side by side with the
  floor, a bare script that only imports pybullet and numpy, loads the same bodies and steps the same
  number of physics steps; ``l2p-bullet plan`` with and without its plot; ``l2p-bullet --help``.

Goals (issues 5, 12): 95 % or more per action; a fresh ``perform --no-render`` median 0.5 s or less (the
floor shows what the machine allows); ``--help`` under 0.3 s.
"""

from __future__ import annotations

import argparse
import json
import os
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
STAGES = ("parse", "load", "plan", "execute", "judge", "total")


def cli() -> list[str]:
    exe = Path(sys.executable).with_name("l2p-bullet")
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "l2p_bullet.cli"]


FLOOR = """
import sys, time
import numpy
import pybullet as pb
table, block, arm, steps = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
blocks = [float(v) for v in sys.argv[5:]]
c = pb.connect(pb.DIRECT)
pb.setGravity(0, 0, -9.81, physicsClientId=c)
pb.setTimeStep(1 / 240, physicsClientId=c)
pb.loadURDF(table, [0, 0, 0], useFixedBase=True, physicsClientId=c)
for i in range(0, len(blocks), 3):
    x, y, size = blocks[i:i + 3]
    pb.loadURDF(block, [x, y, size / 2], globalScaling=size / 0.05, physicsClientId=c)
pb.loadURDF(arm, [-0.53, 0, 0], useFixedBase=True, physicsClientId=c)
for _ in range(steps):
    pb.stepSimulation(physicsClientId=c)
"""
"""The floor: a fresh Python that imports pybullet and numpy, loads the same table, blocks and arm (the
arm's URDF as the project loads it without rendering) and steps the physics as often as the run did."""


def child_env() -> dict[str, str]:
    """The environment of the fresh processes: Python may write its bytecode caches, as it does for a user
    (a development shell that sets PYTHONDONTWRITEBYTECODE would recompile the package on every start)."""
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def timed_run(cmd: list[str]) -> tuple[float, subprocess.CompletedProcess]:
    t = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True, env=child_env())
    return time.perf_counter() - t, r


def help_time(repeats: int = 5) -> float:
    """Median wall time of ``l2p-bullet --help`` as a fresh process."""
    return statistics.median(timed_run([*cli(), "--help"])[0] for _ in range(repeats))


def cold_perform_times(seeds: list[int], tmp: Path, actions: list[str]) -> list[dict]:
    """``l2p-bullet perform --no-render`` as fresh processes (what a user waits for), each followed by the
    floor (FLOOR) stepping as many physics steps in the same scene: side by side, so that the machine's
    load hits both alike. One unmeasured run first writes the bytecode caches."""
    from l2p_bullet.arms import PANDA
    from l2p_bullet.core.scene import random_scene, save_scene
    from l2p_bullet.embodiment.sim.arms import arm_urdf
    from l2p_bullet.embodiment.sim.world import urdf_path

    arm = arm_urdf(PANDA, visuals=False)
    out = []
    for i, seed in enumerate([seeds[0], *seeds]):
        action = actions[i % len(actions)]
        scene = random_scene(seed)
        scene_file = tmp / f"cold-{seed}.json"
        save_scene(scene, scene_file)
        folder = tmp / f"cold-{i}-{seed}-{action}"
        dt, r = timed_run([*cli(), "perform", SENTENCES[action], "--scene", str(scene_file), "--no-render",
                           "--quiet", "--out", str(folder)])
        if r.returncode != 0:
            print(f"  cold run {action} seed {seed} failed: {r.stderr.strip()}", file=sys.stderr)
            continue
        steps = json.loads((folder / "summary.json").read_text())["execution"]["physics_steps"]
        blocks = [str(v) for o in scene.objects for v in (o.xy[0], o.xy[1], o.size)]
        floor, f = timed_run([sys.executable, "-c", FLOOR, urdf_path("table.urdf"), urdf_path("block.urdf"), arm,
                              str(steps), *blocks])
        if f.returncode != 0:
            raise RuntimeError(f"the floor script failed: {f.stderr[-500:]}")
        if i > 0:
            out.append({"action": action, "seed": seed, "perform_s": dt, "floor_s": floor, "steps": steps})
    return out


def cold_plan_times(repeats: int, tmp: Path) -> dict[str, float]:
    """``l2p-bullet plan`` as fresh processes, with its plot and with ``--no-plot``: medians (s)."""
    times: dict[str, list[float]] = {"plot": [], "no-plot": []}
    for i in range(repeats + 1):
        for kind, extra in (("plot", []), ("no-plot", ["--no-plot"])):
            dt, r = timed_run([*cli(), "plan", "move A around B", "--out", str(tmp / f"plan-{kind}-{i}"), *extra])
            if r.returncode != 0:
                raise RuntimeError(f"plan failed: {r.stderr[-500:]}")
            if i > 0:  # the first round writes the bytecode caches
                times[kind].append(dt)
    return {k: statistics.median(v) for k, v in times.items()}


def python_start_time(repeats: int = 5) -> float:
    """Median wall time of a fresh ``python -c pass`` (the interpreter's own start)."""
    return statistics.median(timed_run([sys.executable, "-c", "pass"])[0] for _ in range(repeats))


def evaluate_rows(actions: list[str], scenes: int, render: bool, tmp: Path, workers: int) -> list[dict]:
    """``l2p-bullet evaluate`` on seeds 0..scenes-1 (each run plans with its scene's seed, as before);
    its rows in this benchmark's shape. Stage times are measured inside the worker, per run."""
    from l2p_bullet.evaluate.runner import EvaluationConfig, evaluate, load_rows

    out = tmp / ("render" if render else "fast")
    evaluate(EvaluationConfig(actions=actions, scenes=scenes, render_every=1 if render else 0), out,
             workers=workers, progressbar=True)
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
        "runs": len(rows),
        "errors": len(rows) - len(ok),
        "success_rate": sum(r["success"] for r in rows) / max(len(rows), 1),
        "mean_final_progress": statistics.fmean(r["final_progress"] or 0.0 for r in ok) if ok else float("nan"),
        "mean_max_deviation_mm": 1000 * mean("max_deviation_m"),
        "worst_max_deviation_mm": 1000 * worst("max_deviation_m"),
        "mean_final_error_mm": 1000 * mean("final_error_m"),
        "worst_anchor_displacement_mm": 1000 * worst("anchor_displacement_m"),
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
        plan_cold = cold_plan_times(args.cold, tmp) if args.cold else {}
    fast = {a: summarise([r for r in rows if r["action"] == a and not r["render"]]) for a in actions}
    rendered = {a: summarise([r for r in rows if r["action"] == a and r["render"]]) for a in actions}
    h = help_time()
    print_table(
        f"perform without rendering, {args.scenes} random scenes per action "
        "(l2p-bullet evaluate, stage seconds inside the worker)",
        fast,
    )
    if args.render_scenes:
        print_table(f"perform with rendering, first {args.render_scenes} scenes per action", rendered)
    if cold:
        perf = [c["perform_s"] for c in cold]
        floor = [c["floor_s"] for c in cold]
        ratio = [c["perform_s"] / c["floor_s"] for c in cold]
        print(f"\ncold `l2p-bullet perform --no-render` (fresh process): median {statistics.median(perf):.2f} s, "
              f"max {max(perf):.2f} s over {len(cold)} runs (goal: median <= 0.5 s)")
        print(
            f"the floor (fresh python: import pybullet and numpy, load the same bodies, step as many physics "
            f"steps, median {statistics.median([c['steps'] for c in cold]):.0f}): "
            f"median {statistics.median(floor):.2f} s; "
            f"perform / floor, run by run: median {statistics.median(ratio):.2f}x, max {max(ratio):.2f}x"
        )
        print(f"`python -c pass`: median {python_start_time():.3f} s")
    if plan_cold:
        print(f"cold `l2p-bullet plan`: median {plan_cold['plot']:.2f} s with plan.png, "
              f"{plan_cold['no-plot']:.2f} s with --no-plot")
    print(f"`l2p-bullet --help`: median {h:.3f} s")
    print(f"benchmark wall time {time.perf_counter() - t_all:.0f} s")
    if args.json:
        args.json.write_text(json.dumps({"rows": rows, "fast": fast, "rendered": rendered, "cold": cold,
                                         "plan_cold_s": plan_cold, "help_s": h}, indent=1))


if __name__ == "__main__":
    main()
