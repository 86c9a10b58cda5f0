"""Benchmark single clauses on the study's starts, touching and level ones apart: each action in each manner.

    .venv/bin/python benchmarks/bench_clauses.py --split dev --kinds study,touching,level --manners slide --plan-only
    .venv/bin/python benchmarks/bench_clauses.py --split held-out --manners slide,carry,push --json out.json

Scenes: the distinct start configurations of the original study's graded 2-D demonstrations
(``evaluate.scenes.study_scenes``, two 4 cm cubes, as ``bench_manners.py``), split by their order: the
development split is starts 0-37 (planning seeds 6100 on), the held-out split starts 38-74 (seeds 6300 on).
Each start is run three ways:

- ``study``: as the study had it (1.4-7.7 blocks apart);
- ``touching``: the mover slid along its bearing from the anchor until the footprints are 0-5 mm apart
  (drawn from the seed), both yaws kept: where a clause that ends at the anchor leaves it;
- ``level``: the mover turned square to the anchor and set beside one of its faces (the face nearest the
  study's bearing), 0.1-0.5 block apart (drawn), its faces level with the anchor's: where "next to" leaves it.

Each run is ``pipeline.perform`` in this process, rendering off, planning seeded by the scene's seed; with
``--plan-only`` only the 2-D plan is made and judged by the action's rule (what a slide inherits). Printed: the
success rate per manner x action x kind among the runs not refused by a room check (a real impossibility:
"closer" to a block it touches; the count refused is given beside it; a "no-motion" refusal, the planner's,
counts as a failure), and for "past" the closest approach to the anchor of the plans
(people: median 1.9 blocks, 90 % within 3.2).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np
from bench_manners import SENTENCES as MANNER_SENTENCES
from bench_manners import SIZE, VERBS

SENTENCES = {**MANNER_SENTENCES, "towards": "{verb} A towards B"}
SPLITS = {"dev": (slice(0, 38), 6100), "held-out": (slice(38, None), 6300)}
KINDS = ("study", "touching", "level")


def _gap(scene, mover: str = "A", anchor: str = "B") -> float:
    from l2p_bullet.core.geometry import separation

    a, b = scene.get(mover), scene.get(anchor)
    return float(separation(a.footprint()[None], b.footprint())[0])


def _placed(scene, xy, yaw):
    from l2p_bullet.core.scene import Scene

    objs = [replace(o, xy=(float(xy[0]), float(xy[1])), yaw=float(yaw)) if o.name == "A" else o for o in scene.objects]
    return Scene(objs, scene.table, scene.workspace)


def variant(spec, kind: str, seed: int):
    """The study start ``spec`` as ``kind`` (module docstring), or None when it does not fit the workspace."""
    from l2p_bullet.errors import SceneError

    if kind == "study":
        return spec.scene
    rng = np.random.default_rng([seed, KINDS.index(kind)])
    a, b = spec.scene.get("A"), spec.scene.get("B")
    bearing = math.atan2(a.xy[1] - b.xy[1], a.xy[0] - b.xy[0])
    if kind == "touching":
        gap, yaw, u = rng.uniform(0.0, 0.005), a.yaw, np.array([math.cos(bearing), math.sin(bearing)])
    else:
        face = b.yaw + round((bearing - b.yaw) / (math.pi / 2)) * (math.pi / 2)
        gap, yaw, u = rng.uniform(0.1, 0.5) * SIZE, b.yaw, np.array([math.cos(face), math.sin(face)])
    lo, hi = 0.5 * SIZE, 2.0 * SIZE  # centre distances: overlapping .. apart; bisect for the gap
    for _ in range(40):
        mid = (lo + hi) / 2
        s = _placed(spec.scene, np.asarray(b.xy) + mid * u, yaw)
        lo, hi = (mid, hi) if _gap(s) < gap else (lo, mid)
    scene = _placed(spec.scene, np.asarray(b.xy) + hi * u, yaw)
    try:
        return scene.validate()
    except SceneError:
        return None


def starts(split: str, kinds: list[str]) -> list[tuple[str, str, object, int]]:
    """(id, kind, scene, seed) of the split's starts, each kind."""
    from l2p_bullet.evaluate.scenes import study_scenes

    sl, base = SPLITS[split]
    out = []
    for i, spec in enumerate(study_scenes(SIZE)[sl]):
        seed = base + i
        for kind in kinds:
            scene = variant(spec, kind, seed)
            if scene is not None:
                out.append((f"{spec.id}/{kind}", kind, scene, seed))
    return out


def closest(path: np.ndarray, anchor_xy, size: float) -> float:
    return float(np.hypot(*(np.asarray(path)[:, :2] - np.asarray(anchor_xy)[:2]).T).min() / size)


def one(sentence: str, scene, seed: int, out: Path, world, plan_only: bool) -> dict:
    from l2p_bullet.errors import InfeasibleError, L2PError
    from l2p_bullet.pipeline import perform

    try:
        if plan_only:
            from l2p_bullet.pipeline import judged_plan, prepare

            p, verdict = judged_plan(prepare(sentence, scene, seed=seed))
            return {"refused": False, "success": bool(verdict["success"]), "reason": verdict.get("reason", ""),
                    "closest": closest(p.path, p.anchor_pose, p.size)}
        r = perform(sentence, scene, out_dir=out, seed=seed, render=False, world=world)
    except InfeasibleError as e:
        # a room check is a real impossibility ("closer" to a block it touches); "no-motion" is the planner's
        return {"refused": e.check != "no-motion", "check": e.check, "success": False, "reason": str(e)[:160]}
    except L2PError as e:
        return {"refused": False, "success": False, "reason": str(e)[:160]}
    except Exception as e:  # noqa: BLE001  a crash is a failure of that run, not the end of the benchmark
        return {"refused": False, "success": False, "crashed": type(e).__name__, "reason": f"crashed: {e!r}"[:160]}
    traj = json.loads((out / "trajectory.json").read_text())
    xy = np.array([f["poses"]["A"][:2] for f in traj["frames"]])
    b = scene.get("B").xy
    return {"refused": False, "success": bool(r.success), "reason": r.verdict.get("reason", "")[:200],
            "closest": float(np.hypot(*(xy - np.asarray(b)).T).min() / scene.get("A").size),
            "moved": float(np.hypot(*(xy[-1] - xy[0])) / scene.get("A").size)}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--split", choices=tuple(SPLITS), default="dev")
    ap.add_argument("--kinds", default=",".join(KINDS))
    ap.add_argument("--manners", default="slide,carry,push")
    ap.add_argument("--actions", default="closer,away,next-to,past,around")
    ap.add_argument("--every", type=int, default=1, help="every k-th start of the split only (a quick look)")
    ap.add_argument("--plan-only", action="store_true", help="judge the 2-D plan only (no arm)")
    ap.add_argument("--json", type=Path, help="append every row to this JSON-lines file")
    a = ap.parse_args(argv)
    from l2p_bullet.embodiment.sim.world import World

    specs = starts(a.split, a.kinds.split(","))
    if a.every > 1:
        specs = [s for s in specs if (int(s[3]) - SPLITS[a.split][1]) % a.every == 0]
    rows = []
    with tempfile.TemporaryDirectory() as tmp, World(specs[0][2], visuals=False) as world:
        for manner in a.manners.split(","):
            for action in a.actions.split(","):
                for k, (sid, kind, scene, seed) in enumerate(specs):
                    sentence = SENTENCES[action].format(verb=VERBS[manner])
                    out = Path(tmp) / f"{manner}-{action}-{k}"
                    row = {"manner": manner, "action": action, "id": sid, "kind": kind, "seed": seed} | one(
                        sentence, scene, seed, out, world, a.plan_only)
                    rows.append(row)
                    if a.json:  # as it goes: a long run cut short keeps what it measured
                        with a.json.open("a") as f:
                            f.write(json.dumps(row) + "\n")
                    if not row["success"]:
                        print(f"{manner:6s} {action:8s} {sid:22s} {'refused' if row['refused'] else 'FAIL'} "
                              f"{row['reason']}", file=sys.stderr, flush=True)
    print(table(rows, a))
    return 0


def table(rows: list[dict], a) -> str:
    kinds = a.kinds.split(",")
    lines = [f"{a.split} split, {'2-D plans' if a.plan_only else 'performed'}, 4 cm cubes",
             "| manner | action | " + " | ".join(kinds) + " | all |", "|---|---|" + "---:|" * (len(kinds) + 1)]
    for manner in a.manners.split(","):
        for action in a.actions.split(","):
            cells = []
            for kind in [*kinds, None]:
                rs = [r for r in rows if r["manner"] == manner and r["action"] == action and kind in (None, r["kind"])]
                run = [r for r in rs if not r["refused"]]
                ok = sum(r["success"] for r in run)
                refused = f", {len(rs) - len(run)} refused" if len(rs) > len(run) else ""
                cells.append(f"{ok}/{len(run)} ({100 * ok / max(1, len(run)):.0f} %{refused})")
            lines.append(f"| {manner} | {action} | " + " | ".join(cells) + " |")
    past = [r["closest"] for r in rows if r["action"] == "past" and "closest" in r]
    if past:
        q = np.percentile(past, [10, 50, 90])
        lines.append(f"\npast, closest approach (blocks): 10 % {q[0]:.2f}, median {q[1]:.2f}, 90 % {q[2]:.2f}, "
                     f"> 3.2: {100 * np.mean(np.array(past) > 3.2):.0f} %, n = {len(past)} "
                     "(people: median 1.9, 90 % within 3.2)")
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
