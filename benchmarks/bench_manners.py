"""Benchmark the manners of motion (issue 23): carry and push on study-like starts, for each of the five actions.

    .venv/bin/python benchmarks/bench_manners.py                        # 20 study starts, slide, carry, push
    .venv/bin/python benchmarks/bench_manners.py --scenes 75 --manners carry,push,slide --json out.json
    .venv/bin/python benchmarks/bench_manners.py --source random --seed 5000   # analysis scenes (not reported)

Scenes: the start configurations of the original study's graded 2-D demonstrations
(``evaluate.scenes.study_scenes``) with two 4 cm cubes (the study's blocks 1.4-7.7 sides apart), the first
``--scenes`` of them in the study's order; ``--source random`` draws ``core.scene.random_scene`` scenes from
seed ``--seed`` instead (4 cm, the analysis set: settings were looked at on seeds 5000+ only). Each run is
``pipeline.perform`` in this process, rendering off, planning seeded by the scene's seed.

Per action and manner it prints:

- success: the action's rule judge on the executed trajectory, with the manner's physical signature
  (judge/manners.py) and the 1 mm rule for the anchor; refused: the scene refused before anything moved;
- final within 0.5 side: the block's final position within half a side of the plan's end;
- path within 0.5 side: its largest distance from the planned path while moved within half a side;
- both: the two together (the push goal: 90 % of runs);
- anchor moved > 1 mm: runs in which the arm moved the other block;
- lift (carry): the largest lift of the block (cm, mean); repositions (push): the hand going round (mean);
- seconds per run (mean);
- plan passes the rule: the action's rule judge on the 2-D plan, before the arm moved; success where it does:
  the executed success among those runs (what the manner's execution costs).

Slide is the reference: its failures on the same starts are the planner's (the plan misses the rule), which
carry and push inherit; a run that ended in an error (the arm could not reach a pose) counts as a failure.

Goals: carry >= 98 % success; push >= 90 % success, with final and path within 0.5 side on >= 90 % of runs;
no other object moved more than 1 mm.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

SENTENCES = {
    "closer": "{verb} A closer to B",
    "away": "{verb} A away from B",
    "next-to": "{verb} A next to B",
    "past": "{verb} A past B",
    "around": "{verb} A around B",
}
VERBS = {"slide": "move", "carry": "carry", "push": "push"}
SIZE = 0.04


def scenes(source: str, n: int, seed: int) -> list:
    from l2p_bullet.core.scene import random_scene
    from l2p_bullet.evaluate.scenes import SceneSpec, study_scenes

    if source == "study":
        return study_scenes(SIZE, seed)[:n]
    return [SceneSpec(f"random/{s}", random_scene(s, SIZE), s) for s in range(seed, seed + n)]


def one(spec, action: str, manner: str, out: Path, world) -> dict:
    from l2p_bullet.embodiment.motion import polyline_distance
    from l2p_bullet.errors import InfeasibleError, L2PError
    from l2p_bullet.pipeline import perform

    sentence = SENTENCES[action].format(verb=VERBS[manner])
    t0 = time.perf_counter()
    try:
        r = perform(sentence, spec.scene, out_dir=out, seed=spec.seed, render=False, world=world)
    except InfeasibleError as e:
        return {"refused": True, "reason": str(e)[:160]}
    except L2PError as e:
        return {"refused": False, "error": str(e)[:160], "success": False}
    traj = json.loads((out / "trajectory.json").read_text())
    summary = json.loads((out / "summary.json").read_text())
    xy = np.array([f["poses"]["A"][:2] for f in traj["frames"]])
    path_dev = float(polyline_distance(xy, r.plan.path[:, :2]).max())
    size = spec.scene.get("A").size
    grasp = summary.get("grasp") or {}
    return {"refused": False, "success": r.success, "reason": r.verdict.get("reason", "")[:200],
            "plan_ok": bool(r.planned_verdict.get("success")),
            "final_m": r.final_error_m, "path_m": path_dev,
            "final_ok": r.final_error_m <= 0.5 * size, "path_ok": path_dev <= 0.5 * size,
            "anchor_m": r.anchor_displacement_m, "lift_m": summary.get("execution", {}).get("max_lift_m", 0.0),
            "repositions": (grasp.get("push") or {}).get("repositions"),
            "stopped": (grasp.get("push") or {}).get("stopped"), "seconds": time.perf_counter() - t0}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", type=int, default=20)
    ap.add_argument("--source", choices=("study", "random"), default="study")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--manners", default="slide,carry,push")
    ap.add_argument("--actions", default=",".join(SENTENCES))
    ap.add_argument("--json", type=Path)
    a = ap.parse_args(argv)
    from l2p_bullet.embodiment.sim.world import World

    specs = scenes(a.source, a.scenes, a.seed)
    rows = []
    with tempfile.TemporaryDirectory() as tmp, World(specs[0].scene, visuals=False) as world:
        for manner in a.manners.split(","):
            for action in a.actions.split(","):
                for k, spec in enumerate(specs):
                    out = Path(tmp) / f"{manner}-{action}-{k}"
                    row = {"manner": manner, "action": action, "scene": spec.id} | one(spec, action, manner, out, world)
                    rows.append(row)
                    print(f"{manner:6s} {action:8s} {spec.id:14s} "
                          + ("refused" if row["refused"] else
                             f"{'ok ' if row['success'] else 'FAIL'} final {row.get('final_m', 0) * 1000:5.1f} mm "
                             f"path {row.get('path_m', 0) * 1000:5.1f} mm {row.get('stopped') or ''} "
                             f"{'' if row['success'] else row.get('reason') or row.get('error')}"), file=sys.stderr)
    if a.json:
        a.json.write_text(json.dumps(rows, indent=1))
    print(table(rows, a))
    return 0


def table(rows: list[dict], a) -> str:
    lines = [f"{a.source} starts, {a.scenes} scenes from seed {a.seed}, 4 cm cubes",
             "| manner | action | runs | refused | success | final within 0.5 side | path within 0.5 side | both "
             "| anchor moved > 1 mm | final mm (mean / max) | lift cm / repositions (mean) | s per run "
             "| plan passes the rule | success where it does |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|"]
    for manner in a.manners.split(","):
        for action in [*a.actions.split(","), "all"]:
            rs = [r for r in rows if r["manner"] == manner and (action == "all" or r["action"] == action)]
            run = [r for r in rs if not r["refused"]]
            if not rs:
                continue
            n = max(1, len(run))

            def pct(key: str, runs: list = run, count: int = n) -> str:
                return f"{100 * sum(bool(r.get(key)) for r in runs) / count:.0f} %"

            both = sum(bool(r.get("final_ok") and r.get("path_ok")) for r in run)
            planned = [r for r in run if r.get("plan_ok")]
            fin = [r["final_m"] * 1000 for r in run if "final_m" in r]
            lifts = [r["lift_m"] for r in run if r.get("lift_m") is not None]
            extra = (f"{np.mean(lifts) * 100 if lifts else 0:.1f} cm" if manner == "carry"
                     else f"{np.mean([r.get('repositions') or 0 for r in run]):.1f}" if manner == "push" else "")
            lines.append(
                f"| {manner} | {action} | {len(run)} | {len(rs) - len(run)} | {pct('success')} | {pct('final_ok')} "
                f"| {pct('path_ok')} | {100 * both / n:.0f} % | {sum(r.get('anchor_m', 0) > 0.001 for r in run)} "
                f"| {np.mean(fin) if fin else 0:.1f} / {max(fin) if fin else 0:.1f} | {extra} "
                f"| {np.mean([r.get('seconds', 0) for r in run]):.2f} | {pct('plan_ok')} "
                f"| {pct('success', planned, max(1, len(planned)))} |")
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
