"""Benchmark ``l2p-bullet evaluate``: throughput against a fresh process per run, scaling, Ray; the confusion matrix.

    .venv/bin/python benchmarks/bench_evaluate.py                      # 20 runs per backend, no matrix
    .venv/bin/python benchmarks/bench_evaluate.py --runs 40 --confusion 100 --json out.json

Part 1, side by side on the same runs (seeded random scenes x the five actions, ``--no-render``):

- ``one process per run``: ``l2p-bullet perform --no-render`` as a fresh process for every run, one
  after another (what a shell loop over the CLI, or the old benchmark's cold runs, cost);
- ``evaluate --workers 1`` and ``--workers 2``: the local process pool (workers keep their bundles and
  their PyBullet world across runs);
- ``evaluate --ray local --workers 2``: an embedded Ray on this machine, actors instead of processes.

Each is timed from the command's start to its last row (process and Ray start-up included) and also
in steady state (from the first row to the last, start-up excluded); runs/s per worker is the steady
rate divided by the workers. For the pool it also reports the CPU seconds its workers used per run: on a
shared machine the wall-clock ratio measures the other jobs too, while equal CPU per run with 1 and 2
workers says the pool itself adds nothing that would keep 2 idle cores from doing twice the work. The rows of the three
evaluate backends are checked equal apart from
timings (and their success counted against the fresh processes' own verdicts).

Part 2 (``--confusion N``): N seeded random scenes per action on the pool, and the 5 x 5 judge- and
model-based confusion matrices (rows asked, columns recognised), and the "closer ends touching" count.

Goals (issue 13): >= 1.8x from 1 to 2 workers on the 2-core machine; Ray local within 10 % of the pool.
The machine is shared: the script prints the load average before and after each part.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ACTIONS = ("closer", "away", "next-to", "past", "around")


def cli() -> list[str]:
    exe = Path(sys.executable).with_name("l2p-bullet")
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "l2p_bullet.cli"]


def load() -> str:
    return " ".join(f"{v:.2f}" for v in os.getloadavg())


def fresh_processes(scenes: int, actions: list[str], tmp: Path) -> dict:
    """Every scene x action as ``l2p-bullet perform --no-render`` in its own process (scene-major)."""
    from l2p_bullet.core.scene import random_scene, save_scene
    from l2p_bullet.evaluate.tasks import sentence_for
    from l2p_bullet.plugins import registry

    plugins = registry.discover()
    t0 = time.perf_counter()
    ok = firsts = 0
    first_done = None
    for seed in range(scenes):
        scene_file = tmp / f"scene-{seed}.json"
        save_scene(random_scene(seed), scene_file)
        for a in actions:
            r = subprocess.run([*cli(), "perform", sentence_for(a, "A", "B", plugins), "--scene", str(scene_file),
                                "--seed", str(seed), "--no-render", "--quiet", "--json", "--out",
                                str(tmp / f"fresh-{seed}-{a}")], capture_output=True, text=True)
            firsts += 1
            if first_done is None:
                first_done = time.perf_counter()
            if r.returncode == 0:
                ok += bool(json.loads(r.stdout)["verdict"]["success"])
    total = time.perf_counter() - t0
    n = scenes * len(actions)
    return {"backend": "one process per run", "workers": 1, "runs": n, "seconds": total,
            "steady_seconds": time.perf_counter() - first_done, "success": ok}


def evaluate_backend(scenes: int, actions: list[str], tmp: Path, workers: int, ray: str | None) -> tuple[dict, list]:
    from l2p_bullet.evaluate.runner import EvaluationConfig, evaluate, load_rows

    name = f"evaluate --ray {ray} --workers {workers}" if ray else f"evaluate --workers {workers}"
    out = tmp / name.replace(" ", "_")
    t0 = time.time()
    cpu0 = _children_cpu()
    s = evaluate(EvaluationConfig(actions=actions, scenes=scenes), out, workers=workers, ray=ray, progressbar=False)
    cpu = _children_cpu() - cpu0
    rows = load_rows(out)
    finished = sorted(r["finished_at"] for r in rows)
    return {"backend": name, "workers": workers, "runs": s.ran, "seconds": s.seconds,
            "steady_seconds": finished[-1] - finished[0], "first_row_s": finished[0] - t0,
            "success": sum(bool(r["success"]) for r in rows), "errors": s.errors,
            # CPU seconds the pool's workers used per run (reaped children; Ray's workers are not ours to reap)
            "worker_cpu_s_per_run": None if ray else cpu / max(s.ran, 1)}, rows


def _children_cpu() -> float:
    import resource

    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def throughput(runs: int, actions: list[str], ray: bool) -> list[dict]:
    from l2p_bullet.evaluate.results import comparable

    scenes = max(1, runs // len(actions))
    results, reference = [], None
    with tempfile.TemporaryDirectory(prefix="bench-evaluate-") as td:
        tmp = Path(td)
        plan = [(1, None), (2, None)] + ([(2, "local")] if ray else [])
        for workers, address in plan:
            print(
                f"  {('ray ' if address else '') + f'{workers} worker(s)'}: load {load()}", file=sys.stderr, flush=True
            )
            res, rows = evaluate_backend(scenes, actions, tmp, workers, address)
            got = [comparable(r) for r in rows]
            reference = reference or got
            res["rows_equal_to_1_worker"] = got == reference
            results.append(res)
        print(f"  one process per run: load {load()}", file=sys.stderr, flush=True)
        results.insert(0, fresh_processes(scenes, actions, tmp))
    for r in results:
        r["runs_per_s"] = r["runs"] / r["seconds"]
        steady_runs = max(r["runs"] - 1, 1)
        r["steady_runs_per_s"] = steady_runs / r["steady_seconds"] if r["steady_seconds"] > 0 else float("nan")
        r["steady_per_worker"] = r["steady_runs_per_s"] / r["workers"]
    return results


def print_throughput(results: list[dict]) -> None:
    base = results[0]["runs_per_s"]
    pool1 = next(r for r in results if r["backend"] == "evaluate --workers 1")
    print("\n| backend | runs | wall s | runs/s | steady runs/s | steady runs/s per worker | vs one process per run "
          "| vs 1 worker (steady) | worker CPU s / run | rows = 1 worker's |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for r in results:
        eq = "-" if "rows_equal_to_1_worker" not in r else ("yes" if r["rows_equal_to_1_worker"] else "NO")
        print(f"| {r['backend']} | {r['runs']} | {r['seconds']:.1f} | {r['runs_per_s']:.2f} | "
              f"{r['steady_runs_per_s']:.2f} | {r['steady_per_worker']:.2f} | {r['runs_per_s'] / base:.2f}x | "
              f"{r['steady_runs_per_s'] / pool1['steady_runs_per_s']:.2f}x | {_cpu(r)} | {eq} |")
    pool2 = next((r for r in results if r["backend"] == "evaluate --workers 2"), None)
    ray2 = next((r for r in results if "ray" in r["backend"]), None)
    if pool2 and ray2:
        print(
            f"\nRay local vs the pool, 2 workers: "
            f"steady {ray2['steady_runs_per_s'] / pool2['steady_runs_per_s']:.2f}x, "
            f"with start-up {ray2['runs_per_s'] / pool2['runs_per_s']:.2f}x"
        )


def _cpu(r: dict) -> str:
    v = r.get("worker_cpu_s_per_run")
    return "-" if v is None else f"{v:.2f}"


def confusion_matrix(scenes: int, workers: int, out: Path | None) -> dict:
    from l2p_bullet.evaluate.report import report_text, write_report
    from l2p_bullet.evaluate.runner import EvaluationConfig, evaluate, load_rows

    ctx = tempfile.TemporaryDirectory(prefix="bench-confusion-") if out is None else None
    folder = Path(ctx.name) if ctx else out
    resume = (folder / "results.sqlite").exists()
    s = evaluate(None if resume else EvaluationConfig(actions=list(ACTIONS), scenes=scenes), folder,
                 workers=workers, resume=resume, progressbar=True)
    rows = load_rows(folder)
    _, files = write_report(rows, folder)
    print(f"\n{len(rows)} runs ({s.ran} now, {s.seconds:.0f} s, {workers} workers)\n")
    print(report_text(rows))
    data = json.loads(files["json"].read_text())
    if ctx:
        ctx.cleanup()
    return data


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=20, help="runs per backend in part 1 (scenes x actions)")
    ap.add_argument("--no-ray", action="store_true", help="skip --ray local")
    ap.add_argument("--actions", default=",".join(ACTIONS), help="comma-separated actions of part 1")
    ap.add_argument("--confusion", type=int, default=0, help="part 2: scenes per action (0: skip)")
    ap.add_argument("--confusion-out", type=Path, default=None,
                    help="keep part 2's evaluation here (resumed if it exists; PNGs and report.json land there)")
    ap.add_argument("--workers", type=int, default=2, help="workers for part 2")
    ap.add_argument("--json", type=Path, default=None)
    args = ap.parse_args()
    out: dict = {"load_before": load()}
    if args.runs:
        print(f"part 1: {args.runs} runs per backend, load {load()}", file=sys.stderr)
        out["throughput"] = throughput(args.runs, [a for a in args.actions.split(",") if a], ray=not args.no_ray)
        print_throughput(out["throughput"])
    if args.confusion:
        print(f"part 2: {args.confusion} scenes per action, load {load()}", file=sys.stderr)
        out["confusion"] = confusion_matrix(args.confusion, args.workers, args.confusion_out)
    out["load_after"] = load()
    print(f"\nload average (1, 5, 15 min) before {out['load_before']}, after {out['load_after']} (2 cores)")
    if args.json:
        args.json.write_text(json.dumps(out, indent=1, default=str) + "\n")


if __name__ == "__main__":
    main()
