"""What a rendered ``perform "move A around B"`` costs, per video setting, side by side in one run.

    .venv/bin/python benchmarks/bench_render.py [--repeats 1] [--json out.json]

Each setting runs ``l2p-bullet perform "move A around B"`` on the default scene in a fresh process (as a
user's command does, start-up included), one setting after the other, ``--repeats`` rounds. Reported:
wall seconds of the command, CPU seconds of it and every process it started (the render workers),
the episode's simulated duration, and wall / simulated (the goal of issue 24: at most 1 for 640x480 at
15 fps). The machine's load average is printed before and after: on a shared machine compare the
ratios of one run, not absolute seconds across runs.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SETTINGS = [  # name, extra perform options, render workers (None: the default pool)
    ("no video", ["--no-render"], None),
    ("320x240 10 fps tiny, in-process (the video before issue 24)",
     ["--resolution", "320x240", "--fps", "10", "--renderer", "tiny", "--camera", "robot"], 0),
    ("640x480 15 fps egl, pool (the default)", [], None),
    ("640x480 15 fps tiny, pool", ["--renderer", "tiny"], None),
    ("640x480 15 fps egl, in-process", [], 0),
    ("640x480 30 fps egl, pool", ["--fps", "30"], None),
]


def run_one(options: list[str], workers: int | None, out: Path) -> dict:
    env = dict(os.environ)
    if workers is not None:
        env["L2P_RENDER_WORKERS"] = str(workers)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "l2p_bullet.cli", "perform", "move A around B", "--out", str(out),
                    "--force", "-q", *options], check=True, env=env, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    summary = json.loads((out / "summary.json").read_text())
    render = summary.get("render") or {}
    return {"wall_s": wall, "cpu_s": cpu, "simulated_s": summary["simulated_s"],
            "frames": summary["execution"]["rendered_frames"], "renderer": render.get("renderer"),
            "workers": render.get("workers"), "wait_s": render.get("wait_s")}


def _median(values: list[float]) -> float:
    return sorted(values)[len(values) // 2]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--only", type=int, nargs="*", help="indices of SETTINGS to run (default: all)")
    ap.add_argument("--json", type=Path, default=None)
    args = ap.parse_args()
    chosen = [SETTINGS[i] for i in args.only] if args.only else SETTINGS
    load0 = os.getloadavg()
    print(f"cores {os.cpu_count()}, load average before {load0[0]:.1f} {load0[1]:.1f} {load0[2]:.1f}", flush=True)
    rows: dict[str, list[dict]] = {name: [] for name, _, _ in chosen}
    with tempfile.TemporaryDirectory(prefix="bench-render-") as td:
        for _ in range(args.repeats):
            for name, options, workers in chosen:
                r = run_one(options, workers, Path(td) / "run")
                rows[name].append(r)
                print(f"  {name}: {r['wall_s']:.1f} s wall, {r['cpu_s']:.1f} s CPU, {r['frames']} frames "
                      f"({r['renderer']}, workers {r['workers']})", file=sys.stderr, flush=True)
    load1 = os.getloadavg()
    print(f"load average after {load1[0]:.1f} {load1[1]:.1f} {load1[2]:.1f}")
    print(f"{'setting':<62} {'wall s':>7} {'CPU s':>7} {'sim s':>6} {'wall/sim':>8} {'frames':>6}  renderer")
    table = []
    for name, rs in rows.items():
        row = {"setting": name, **{k: _median([r[k] for r in rs]) for k in ("wall_s", "cpu_s", "simulated_s")},
               "frames": rs[0]["frames"], "renderer": rs[0]["renderer"], "runs": rs}
        row["wall_per_sim"] = row["wall_s"] / row["simulated_s"]
        table.append(row)
        print(f"{name:<62} {row['wall_s']:7.1f} {row['cpu_s']:7.1f} {row['simulated_s']:6.1f} "
              f"{row['wall_per_sim']:8.2f} {row['frames']:6d}  {row['renderer'] or '-'}")
    if args.json:
        args.json.write_text(json.dumps({"load_before": load0, "load_after": load1, "rows": table}, indent=1))


if __name__ == "__main__":
    main()
