"""Robustness benchmark: every scene the validator accepts performs, or is refused up front with a reason.

    .venv/bin/python benchmarks/bench_robustness.py                    # 1,000 scenes x 5 actions, no rendering
    .venv/bin/python benchmarks/bench_robustness.py --scenes 60        # a quick look while developing
    .venv/bin/python benchmarks/bench_robustness.py --scenes 200 --jobs 2 --json rows.json

Scenes are drawn from seeds ``--seed-base + i`` (default 900000: no other benchmark or training run uses
seeds there) by :func:`stress_scene`, a harder mix than ``scene.random_scene``: every block 3-6 cm and
turned at random; the mover and the anchor placed, in turn, touching (a 0-5 mm gap between their
footprints), 1.4-7.7 mover sides apart centre to centre (the original study's range), or one of them at
the workspace's rim; in half the scenes 3-6 bystander blocks anywhere in the workspace. Every scene is
valid (``Scene.validate``). Each is performed with each action by ``pipeline.perform`` (no rendering).

Per action it prints how many runs were

- performed and judged successful / performed and judged unsuccessful (the rule judge on what the arm did),
- refused up front, by the check that refused them (``planning.feasibility``: a real impossibility),
- failed in planning or failed during execution (an L2PError after the checks: a defect),
- crashed (any other exception: a defect; the traceback is printed),

and how many runs moved the anchor or a bystander more than 1 mm (a defect; such a run is also judged
unsuccessful). Goals (issue 12): zero crashes, zero failures during execution, zero blocks disturbed.
"""

from __future__ import annotations

import argparse
import collections
import json
import math
import shutil
import statistics
import sys
import tempfile
import time
import traceback
from collections.abc import Callable, Collection
from pathlib import Path
from typing import Any

from bench_perform import SENTENCES  # the same sentence per action as the end-to-end benchmark

SEED_BASE = 900_000
COLORS = ("blue", "yellow", "orange", "purple", "white", "black", "gray", "brown", "pink", "cyan")


def stress_scene(seed: int):
    """A valid scene drawn from ``seed`` (see the module docstring); the same seed gives the same scene."""
    import numpy as np

    from l2p_bullet.core.scene import Scene, SceneObject
    from l2p_bullet.core.workspace import START_RADIUS, Workspace
    from l2p_bullet.errors import SceneError

    rng = np.random.default_rng(seed)
    kind = ("touching", "study", "rim")[seed % 3]
    radius = START_RADIUS  # the start disk: the same stress scenes as before the planning disk grew
    starts = Workspace(radius=START_RADIUS)
    for _ in range(2000):
        sa, sb = rng.uniform(0.03, 0.06, size=2)
        ya, yb = rng.uniform(0.0, math.pi / 2, size=2)
        if kind == "rim":  # one of the two near the rim, the other anywhere near it
            r = radius * math.sqrt(rng.uniform(0.8 ** 2, 1.0))
        else:
            r = radius * math.sqrt(rng.uniform())
        a0 = rng.uniform(-math.pi, math.pi)
        p0 = np.array([r * math.cos(a0), r * math.sin(a0)])
        direction = rng.uniform(-math.pi, math.pi)
        u = np.array([math.cos(direction), math.sin(direction)])
        if kind == "touching":
            gap = rng.uniform(0.0, 0.005)
            dist = _distance_for_gap(sa, ya, sb, yb, u, gap)
        else:
            dist = rng.uniform(1.4, 7.7) * sa
        p1 = p0 + dist * u
        b_xy, a_xy = (p0, p1) if rng.uniform() < 0.5 else (p1, p0)
        objects = [SceneObject("A", "red", float(sa), (float(a_xy[0]), float(a_xy[1])), float(ya)),
                   SceneObject("B", "green", float(sb), (float(b_xy[0]), float(b_xy[1])), float(yb))]
        try:
            Scene(objects, workspace=starts).validate()
        except SceneError:
            continue
        if rng.uniform() < 0.5:
            objects = _add_bystanders(objects, int(rng.integers(3, 7)), rng)
            if objects is None:
                continue
        return Scene(objects).validate(), kind
    raise RuntimeError(f"no valid stress scene for seed {seed}")  # pragma: no cover


def _distance_for_gap(sa: float, ya: float, sb: float, yb: float, u, gap: float) -> float:
    """Centre distance along ``u`` at which two squares' footprints are ``gap`` apart (bisection)."""
    import numpy as np

    from l2p_bullet.core.geometry import separation
    from l2p_bullet.core.scene import SceneObject

    a0 = SceneObject("a", "red", sa, (0.0, 0.0), ya)
    lo, hi = 0.0, (sa + sb)
    for _ in range(50):
        mid = (lo + hi) / 2
        b = SceneObject("b", "red", sb, (float(mid * u[0]), float(mid * u[1])), yb)
        if float(separation(a0.footprint()[None], b.footprint())[0]) < gap:
            lo = mid
        else:
            hi = mid
    return float(np.nextafter(hi, np.inf))


def _add_bystanders(objects: list, n: int, rng) -> list | None:
    from l2p_bullet.core.scene import Scene, SceneObject
    from l2p_bullet.core.workspace import START_RADIUS
    from l2p_bullet.errors import SceneError

    out = list(objects)
    for k in range(n):
        for _ in range(200):
            r, a = START_RADIUS * math.sqrt(rng.uniform()), rng.uniform(-math.pi, math.pi)
            o = SceneObject(f"C{k + 1}", COLORS[k % len(COLORS)], float(rng.uniform(0.03, 0.06)),
                            (r * math.cos(a), r * math.sin(a)), float(rng.uniform(0, math.pi / 2)))
            try:
                Scene([*out, o]).validate()
            except SceneError:
                continue
            out.append(o)
            break
        else:
            return None
    return out


def run_one(action: str, seed: int, tmp: Path, plugins: list) -> dict:
    """Perform ``action`` on the stress scene of ``seed``; classify what happened."""
    from l2p_bullet.pipeline import perform

    scene, kind = stress_scene(seed)
    out = tmp / f"{action}-{seed}"
    row = {"action": action, "seed": seed, "kind": kind, "objects": len(scene.objects)}
    return classify(row, out, lambda: perform(SENTENCES[action], scene, out_dir=out, seed=seed, render=False,
                                              plugins=plugins))


def classify(row: dict, out: Path, perform_it: Callable[[], Any], checks: Collection[str] | None = None) -> dict:
    """Run ``perform_it`` (one ``perform`` writing to ``out``) and add to ``row`` what happened (the
    outcome, its details, the seconds it took); ``out`` is removed. With ``checks`` a refusal also says
    whether it named one of them (``named``). Shared by this benchmark and bench_objects.py."""
    from l2p_bullet.errors import InfeasibleError, L2PError

    t = time.perf_counter()
    try:
        r = perform_it()
        d = r.to_dict()
        row |= {"outcome": "success" if r.success else "unsuccessful", "reason": r.verdict.get("reason"),
                "disturbed": d["disturbed"], "max_displacement_m": max(r.displacements_m.values(), default=0.0),
                "bounded": bool(r.plan.extra.get("bounded"))}  # planning.CHECK_CAP ended its search
    except InfeasibleError as e:
        row |= {"outcome": "refused", "check": e.check,
                **({"named": e.check in checks} if checks is not None else {}), "error": str(e)}
    except L2PError as e:
        stage = _failed_stage(out)
        row |= {"outcome": "plan-failed" if stage in ("load", "plan") else "exec-failed", "stage": stage,
                "error": f"{type(e).__name__}: {e}"}
    except Exception as e:  # noqa: BLE001 - a crash is what this benchmark is looking for
        row |= {"outcome": "crashed", "error": f"{type(e).__name__}: {e}", "traceback": traceback.format_exc()}
    row["seconds"] = round(time.perf_counter() - t, 3)
    shutil.rmtree(out, ignore_errors=True)
    return row


def _failed_stage(out: Path) -> str | None:
    try:
        return json.loads((out / "summary.json").read_text()).get("failed_stage")
    except (OSError, ValueError):
        return None


def _worker(args: tuple[list[tuple[str, int]], str]) -> list[dict]:
    jobs, tmp = args
    from l2p_bullet.plugins import registry

    plugins = registry.discover()
    return [run_one(a, s, Path(tmp), plugins) for a, s in jobs]


OUTCOMES = ("success", "unsuccessful", "refused", "plan-failed", "exec-failed", "crashed")


def print_table(rows: list[dict], actions: list[str]) -> None:
    head = (f"{'action':<8} {'runs':>5} {'success':>8} {'unsucc.':>8} {'refused':>8} {'plan-fail':>9} "
            f"{'exec-fail':>9} {'crashed':>8} {'disturbed':>9} {'median s':>8} {'max s':>7}")
    print(head)
    print("-" * len(head))
    for action in [*actions, "all"]:
        rs = [r for r in rows if action == "all" or r["action"] == action]
        if not rs:
            continue
        n = collections.Counter(r["outcome"] for r in rs)
        disturbed = sum(1 for r in rs if r.get("disturbed"))
        secs = [r["seconds"] for r in rs]
        print(
            f"{action:<8} {len(rs):5d} "
            + " ".join(f"{n[o]:>{w}d}" for o, w in zip(OUTCOMES, (8, 8, 8, 9, 9, 8), strict=True))
            + f" {disturbed:9d} {statistics.median(secs):8.2f} {max(secs):7.2f}"
        )
    refused = collections.Counter((r["action"], r["check"]) for r in rows if r["outcome"] == "refused")
    if refused:
        print("\nrefused up front, by check:")
        for (action, check), k in sorted(refused.items()):
            print(f"  {action:<8} {check:<12} {k}")
    kinds = collections.Counter((r["kind"], r["outcome"]) for r in rows)
    print("\nby scene kind (all actions): " + "; ".join(
        f"{kind}: " + ", ".join(f"{o} {kinds[(kind, o)]}" for o in OUTCOMES if kinds[(kind, o)])
        for kind in ("touching", "study", "rim")))
    for r in rows:
        if r["outcome"] in ("plan-failed", "exec-failed", "crashed") or r.get("disturbed"):
            print(f"\n{r['action']} seed {r['seed']} ({r['kind']}): {r['outcome']} "
                  f"{r.get('error', '')} {r.get('disturbed', '')}")
            if r.get("traceback"):
                print(r["traceback"])


def run_jobs(jobs: list[tuple[str, int]], processes: int, worker, run, prefix: str, *, extra: tuple = (),
             split: int = 8, line=None, save=None) -> list[dict]:
    """Every (action, seed) job's row, printing progress on stderr: in ``processes`` spawned processes when
    more than one (``worker`` takes a chunk, the temporary folder and ``extra``; ``split`` chunks per
    process), else here one by one (``run(action, seed, folder, plugins, *extra)``, one ``line(row)`` each).
    ``save(rows)`` is called after each chunk (each run with one process), so that what is done survives an
    interrupted run. The stress benchmarks (this one and bench_objects.py) share it."""
    t0 = time.perf_counter()
    rows: list[dict] = []
    with tempfile.TemporaryDirectory(prefix=prefix) as tmp:
        if processes > 1:
            import multiprocessing as mp

            chunks = [jobs[i::processes * split] for i in range(processes * split)]
            with mp.get_context("spawn").Pool(processes) as pool:
                for part in pool.imap_unordered(worker, [(c, tmp, *extra) for c in chunks if c]):
                    rows.extend(part)
                    print(f"  {len(rows)}/{len(jobs)} runs, {time.perf_counter() - t0:.0f} s", file=sys.stderr)
                    if save is not None:
                        save(rows)
        else:
            from l2p_bullet.plugins import registry

            plugins = registry.discover()
            for k, (action, seed) in enumerate(jobs):
                rows.append(run(action, seed, Path(tmp), plugins, *extra))
                r = rows[-1]
                print((line or _line)(r), file=sys.stderr)
                if save is not None:  # one by one too: a run stopped early keeps the rows it has
                    save(rows)
                if (k + 1) % 50 == 0:
                    print(f"  {k + 1}/{len(jobs)} runs, {time.perf_counter() - t0:.0f} s", file=sys.stderr)
    return rows


def _line(r: dict) -> str:
    return (f"{r['action']:<8} seed {r['seed']} {r['kind']:<8} {r['outcome']:<12} {r['seconds']:.2f}s "
            f"{r.get('check', '') or r.get('error', '')[:100]}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", type=int, default=1000, help="random stress scenes (seeds seed-base .. +N-1)")
    ap.add_argument("--seed-base", type=int, default=SEED_BASE)
    ap.add_argument("--actions", default=",".join(SENTENCES), help="comma-separated actions")
    ap.add_argument("--jobs", type=int, default=1, help="worker processes")
    ap.add_argument("--json", type=Path, default=None, help="also write every row here")
    args = ap.parse_args()
    actions = [a for a in args.actions.split(",") if a]
    jobs = [(a, args.seed_base + i) for i in range(args.scenes) for a in actions]
    t0 = time.perf_counter()
    rows = run_jobs(jobs, args.jobs, _worker, run_one, "bench-robust-")
    rows.sort(key=lambda r: (r["seed"], actions.index(r["action"])))
    print(f"\nrobustness: {args.scenes} stress scenes (seeds {args.seed_base}..{args.seed_base + args.scenes - 1}) "
          f"x {len(actions)} actions, no rendering, {time.perf_counter() - t0:.0f} s\n")
    print_table(rows, actions)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
