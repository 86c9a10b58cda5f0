"""Arms benchmark (issue 22): every shipped arm performs the five built-in actions on study-like starts.

    .venv/bin/python benchmarks/bench_arms.py                      # 20 scenes per arm, 3 timed per action
    .venv/bin/python benchmarks/bench_arms.py --scenes 6 --timed 1 # a quick look while developing
    .venv/bin/python benchmarks/bench_arms.py --arms xarm6 --json rows.json
    .venv/bin/python benchmarks/bench_arms.py --ik fitted,general --scenes 4 --timed 0   # the IKs side by side

Scenes: for each arm, seeds ``--seed-base + i`` (default 220000, used by nothing else) draw a study-like
start (:func:`study_like_scene`): two 4 cm cubes, the mover 1.4-7.7 of its sides from the anchor (the original
study's range), both turned at random, the pair put at a random place and translated into the workspace's disk
(``evaluate.scenes._fit_into_disk``). The KUKA's workspace is that disk cut by its reach ring (``l2p-bullet arms``,
issue 22): a draw with a block outside the ring (half a side and 1 mm in from its edges, as from the disk's rim)
is rejected and the next one drawn from the same generator; before 2026-11-27 the KUKA's scenes were drawn the
same way in the 0.17 m disk it then had. The same scene and seed go
to every action. Each run is ``pipeline.perform`` without rendering, in one process that keeps the arm's world
(as ``l2p-bullet evaluate`` does), judged by the action's rule judge on what the arm did.

Per arm and action it prints the success rate (a refusal up front counts as a failure, and is counted by its
check), failures and crashes. Timing: a fresh ``l2p-bullet perform --no-render --arm NAME`` process (what a
user waits for) on the first ``--timed`` scenes of each action, each run side by side with the Panda on the
same scene (the Panda reaches every scene of every arm), median ratio. Goals: >= 95 % per arm and action;
the fresh median within 1.5x of the Panda's.
"""

from __future__ import annotations

import argparse
import collections
import json
import math
import statistics
import sys
import tempfile
import time
from pathlib import Path

from bench_perform import SENTENCES, cli, timed_run

SEED_BASE = 220_000
SIZE = 0.04


def study_like_scene(seed: int, workspace):
    """Two 4 cm cubes (A the mover, B the anchor) 1.4-7.7 sides apart, any yaw, inside ``workspace`` (a Workspace, or
    the radius of a disk about the table's centre): drawn in its disk, rejected when outside its ring."""
    import numpy as np

    from l2p_bullet.core.scene import Scene, SceneObject, Workspace
    from l2p_bullet.errors import SceneError
    from l2p_bullet.evaluate.scenes import _fit_into_disk

    ws = workspace if isinstance(workspace, Workspace) else Workspace(radius=float(workspace))
    ws = ws.starts()  # the start disk (0.25 m, cut by the ring where it bites): the same scenes as before 2026-11-27
    radius = ws.radius
    rng = np.random.default_rng(seed)
    for _ in range(1000):
        r, a = radius * math.sqrt(rng.uniform()), rng.uniform(-math.pi, math.pi)
        d, b = rng.uniform(1.4, 7.7) * SIZE, rng.uniform(-math.pi, math.pi)
        anchor = np.array([r * math.cos(a), r * math.sin(a)])
        xy = _fit_into_disk(np.array([anchor + d * np.array([math.cos(b), math.sin(b)]), anchor]),
                            radius - SIZE / 2 - 1e-3)
        ya, yb = rng.uniform(-math.pi, math.pi, size=2)
        if ws.ring is not None and not ws.contains(xy, SIZE / 2 + 1e-3).all():
            continue  # the arm's ring cuts the disk: redraw
        scene = Scene([SceneObject("A", "red", SIZE, (float(xy[0, 0]), float(xy[0, 1])), float(ya)),
                       SceneObject("B", "green", SIZE, (float(xy[1, 0]), float(xy[1, 1])), float(yb))])
        try:
            return scene.validate()
        except SceneError:
            continue
    raise RuntimeError(f"no valid scene for seed {seed}")  # pragma: no cover


IK_KINDS = ("installed", "fitted", "general")


def ik_variant(spec, kind: str):
    """``spec`` with the inverse kinematics ``kind``: "installed" as the arm declares it; "fitted" without restarts
    (``ik_restarts`` 0: the seeds put in the arm's plane by its wrist model, nothing else); "general" with the
    restarts ``new-arm`` writes (``arms.spec.IK_RESTARTS``) and joints unwrapped by whole turns."""
    from dataclasses import replace

    from l2p_bullet.arms.spec import IK_RESTARTS

    if kind == "installed":
        return spec
    return replace(spec, ik_restarts=0 if kind == "fitted" else IK_RESTARTS)


def ik_accuracy(spec, label: str) -> dict:
    """The IK on the arm's reach ring: 5 distances from its near to its far edge, azimuths 0 and +-0.5 rad, the
    grasp, mid and hover heights, the wrist at 0 and +-1 rad, seeded as the ring measurement seeds it
    (``arm_measure.reaches``): how many it solves, the position and yaw error of what it returns (forward
    kinematics), and the time per solve."""
    import numpy as np

    from l2p_bullet.embodiment import arm_measure
    from l2p_bullet.embodiment.sim.robot import Kinematics
    from l2p_bullet.errors import ReachError

    kin = Kinematics(spec, spec.mount)
    near, far = spec.reach
    solved = tried = 0
    pos_err, yaw_err, times = [], [], []
    try:
        for r in np.linspace(near, far, 5):
            for az in (0.0, -0.5, 0.5):
                for z in (0.012, 0.1, 0.19):
                    for w in arm_measure.wrist_turns(spec):
                        x, y = spec.mount[0] + r * math.cos(az), spec.mount[1] + r * math.sin(az)
                        yaw = spec.wrist_offset + az - w
                        seeds = [arm_measure._in_plane(spec, np.asarray(s, float), az, w)
                                 for s in (spec.home, *spec.ik_seeds)]
                        tried += 1
                        t = time.perf_counter()
                        try:
                            q = kin.solve((x, y, z), yaw, seeds[0], seeds=tuple(tuple(s) for s in seeds[1:]))
                        except ReachError:
                            times.append(time.perf_counter() - t)
                            continue
                        times.append(time.perf_counter() - t)
                        solved += 1
                        got, orn = kin.fk(q)
                        m = kin.sim.rotation_matrix(orn)
                        pos_err.append(float(np.linalg.norm(got - (x, y, z))))
                        yaw_err.append(abs(math.remainder(math.atan2(m[3], m[0]) - yaw, 2 * math.pi)))
        # cold: from the home alone, not put in the arm's plane, no other seed (what a first guess far off leaves)
        cold = 0
        for r in np.linspace(near, far, 5):
            for az in (-0.5, 0.5):
                for w in arm_measure.wrist_turns(spec):
                    x, y = spec.mount[0] + r * math.cos(az), spec.mount[1] + r * math.sin(az)
                    try:
                        kin.solve((x, y, 0.1), spec.wrist_offset + az - w, np.asarray(spec.home, float))
                        cold += 1
                    except ReachError:
                        pass
    finally:
        kin.close()
    return {"arm": label, "solved": solved, "tried": tried, "cold_solved": cold, "cold_tried": 30,
            "pos_mm_max": round(max(pos_err, default=0.0) * 1000, 3),
            "pos_mm_median": round(statistics.median(pos_err) * 1000, 3) if pos_err else None,
            "yaw_deg_max": round(math.degrees(max(yaw_err, default=0.0)), 3),
            "solve_ms_median": round(statistics.median(times) * 1000, 2),
            "solve_ms_max": round(max(times) * 1000, 1)}


def run_arm(arm: str, seeds: list[int], actions: list[str], tmp: Path, scenes_of: str | None = None,
            ik: str = "installed") -> list[dict]:
    """Every action on every scene with ``arm``, in this process (one world kept); one row per run. ``scenes_of``:
    draw the scenes for that arm's workspace instead (the Panda on the KUKA's smaller disk); ``ik``: the arm's
    inverse kinematics (:func:`ik_variant`), named in the rows' label unless "installed"."""
    from l2p_bullet.arms import fit_workspace
    from l2p_bullet.core.scene import Workspace
    from l2p_bullet.embodiment.sim.world import World
    from l2p_bullet.errors import InfeasibleError, L2PError
    from l2p_bullet.pipeline import perform
    from l2p_bullet.plugins import arms as arm_plugins

    spec = ik_variant(arm_plugins.get(arm), ik)
    ws = fit_workspace(Workspace(), arm_plugins.get(scenes_of or arm))
    label = arm if scenes_of is None or scenes_of == arm else f"{arm} ({scenes_of}'s scenes)"
    label += "" if ik == "installed" else f" [{ik}]"
    rows = []
    world = None
    try:
        for seed in seeds:
            scene = study_like_scene(seed, ws)
            if world is None:
                world = World(scene, arm=spec, visuals=False)
            for action in actions:
                row = {"arm": label, "seed": seed, "action": action, "outcome": "success"}
                t, cpu = time.perf_counter(), time.process_time()
                try:
                    r = perform(SENTENCES[action], scene, out_dir=tmp / f"{arm}-{seed}-{action}", render=False,
                                force=True, seed=seed, world=world, arm=spec)
                    row.update(success=bool(r.success), reason=r.verdict.get("reason"),
                               anchor_mm=round(r.anchor_displacement_m * 1000, 2),
                               final_error_mm=round(r.final_error_m * 1000, 2))
                    row["outcome"] = "success" if r.success else "unsuccessful"
                except InfeasibleError as e:
                    row.update(success=False, outcome=f"refused:{e.check}", reason=str(e))
                except L2PError as e:
                    row.update(success=False, outcome="failed", reason=f"{type(e).__name__}: {e}")
                except Exception as e:  # noqa: BLE001 - a crash is a defect the table must show
                    row.update(success=False, outcome="crash", reason=f"{type(e).__name__}: {e}")
                row["wall_s"] = round(time.perf_counter() - t, 3)
                row["cpu_s"] = round(time.process_time() - cpu, 3)  # steadier than wall time on a shared machine
                rows.append(row)
                print(f"  {label} {seed} {action}: {row['outcome']} ({row['wall_s']} s)", file=sys.stderr, flush=True)
    finally:
        if world is not None:
            world.close()
    return rows


def study_workspace(arm: str):
    """The arm's workspace (its scenes are drawn in it)."""
    from l2p_bullet.arms import fit_workspace
    from l2p_bullet.core.scene import Workspace
    from l2p_bullet.plugins import arms as arm_plugins

    return fit_workspace(Workspace(), arm_plugins.get(arm))


def fresh_times(arm: str, seeds: list[int], actions: list[str], timed: int, tmp: Path) -> list[dict]:
    """Fresh ``perform --no-render`` with ``arm`` and with the Panda, side by side on the same scenes."""
    from l2p_bullet.arms import fit_workspace
    from l2p_bullet.core.scene import Workspace, save_scene
    from l2p_bullet.plugins import arms as arm_plugins

    ws = fit_workspace(Workspace(), arm_plugins.get(arm))
    out = []
    timed_run([*cli(), "--help"])  # bytecode caches written before anything is measured
    for action in actions:
        for seed in seeds[:timed]:
            scene_file = tmp / f"fresh-{arm}-{seed}.json"
            save_scene(study_like_scene(seed, ws), scene_file)
            row = {"arm": arm, "action": action, "seed": seed}
            for who in (arm, "panda"):
                dt, r = timed_run([*cli(), "perform", SENTENCES[action], "--scene", str(scene_file), "--no-render",
                                   "--quiet", "--arm", who, "--seed", str(seed), "--force",
                                   "--out", str(tmp / f"fresh-{who}-{seed}-{action}")])
                row["panda_s" if who == "panda" else "arm_s"] = round(dt, 3) if r.returncode == 0 else None
            out.append(row)
    return out


def table(rows: list[dict], times: list[dict], actions: list[str], arms: list[str]) -> str:
    lines = [
        "| arm | " + " | ".join(actions) + " | all | refused (check: n) | failed / crashed | anchor moved, max mm | "
        "fresh perform median s (arm / Panda, same scenes) | ratio |",
        "|---|" + "---|" * (len(actions) + 6),
    ]
    for arm in arms:
        mine = [r for r in rows if r["arm"] == arm]
        cells = []
        for a in actions:
            rs = [r for r in mine if r["action"] == a]
            cells.append(f"{sum(r['success'] for r in rs) / max(len(rs), 1):.0%} ({len(rs)})")
        refused = collections.Counter(r["outcome"].split(":", 1)[1] for r in mine if r["outcome"].startswith("refused"))
        bad = sum(r["outcome"] == "failed" for r in mine), sum(r["outcome"] == "crash" for r in mine)
        t = [x for x in times if x["arm"] == arm and x["arm_s"] is not None and x["panda_s"] is not None]
        ta = statistics.median(x["arm_s"] for x in t) if t else float("nan")
        tp = statistics.median(x["panda_s"] for x in t) if t else float("nan")
        ratio = statistics.median(x["arm_s"] / x["panda_s"] for x in t) if t else float("nan")
        moved = max((r.get("anchor_mm", 0.0) for r in mine), default=0.0)
        lines.append(f"| {arm} | " + " | ".join(cells)
                     + f" | {sum(r['success'] for r in mine) / max(len(mine), 1):.1%} | "
                     + (", ".join(f"{k}: {v}" for k, v in sorted(refused.items())) or "0")
                     + f" | {bad[0]} / {bad[1]} | {moved:.1f} | "
                     + (f"{ta:.2f} / {tp:.2f} ({len(t)} runs) | {ratio:.2f}x |" if t else "- | - |"))
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--arms", default="panda,xarm6,kuka-iiwa")
    ap.add_argument("--actions", default=",".join(SENTENCES))
    ap.add_argument("--scenes", type=int, default=20, help="scenes per arm (each performed with every action)")
    ap.add_argument("--timed", type=int, default=3, help="scenes per action timed as fresh processes (0: none)")
    ap.add_argument("--seed-base", type=int, default=SEED_BASE)
    ap.add_argument("--json", default=None, help="write every row and timing here")
    ap.add_argument("--ik", default="installed",
                    help="comma-separated inverse kinematics to run each arm with, side by side on the same scenes: "
                         "installed (as the arm declares it), fitted (no restarts), general (restarts); with more "
                         "than one, also each one's accuracy on the arm's reach ring")
    args = ap.parse_args()
    iks = [k.strip() for k in args.ik.split(",") if k.strip()]
    if any(k not in IK_KINDS for k in iks):
        ap.error(f"--ik takes {', '.join(IK_KINDS)}")
    arms = [a.strip() for a in args.arms.split(",") if a.strip()]
    actions = [a.strip() for a in args.actions.split(",") if a.strip()]
    seeds = list(range(args.seed_base, args.seed_base + args.scenes))
    rows, times, accuracy = [], [], []
    labels = list(arms) if iks == ["installed"] else [f"{a} [{k}]" for a in arms for k in iks]
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="bench-arms-") as d:
        tmp = Path(d)
        for arm in arms:
            if iks != ["installed"]:
                from l2p_bullet.plugins import arms as arm_plugins

                for k in iks:
                    rows += run_arm(arm, seeds, actions, tmp, ik=k)
                    accuracy.append(ik_accuracy(ik_variant(arm_plugins.get(arm), k), f"{arm} [{k}]"))
                continue
            rows += run_arm(arm, seeds, actions, tmp)
            if arm != "panda" and "panda" in arms and study_workspace(arm) != study_workspace("panda"):
                rows += run_arm("panda", seeds, actions, tmp, scenes_of=arm)  # the same scenes, for comparison
                labels.insert(labels.index(arm) + 1, f"panda ({arm}'s scenes)")
            if args.timed and arm != "panda":
                times += fresh_times(arm, seeds, actions, args.timed, tmp)
    print(f"{args.scenes} study-like scenes per arm (seeds {seeds[0]}-{seeds[-1]}), {len(rows)} runs, "
          f"{time.perf_counter() - t0:.0f} s\n")
    print(table(rows, times, actions, labels))
    if accuracy:
        print("\n| arm [IK] | ring poses solved | cold (home seed only) | position error, median / max mm | "
              "yaw error, max deg | in-process perform, median wall / CPU s | CPU vs the first IK, paired median | "
              "solve, median / max ms |\n|---|---|---|---|---|---|---|---|")
        for a in accuracy:
            walls = [r["wall_s"] for r in rows if r["arm"] == a["arm"]]
            cpus = {(r["seed"], r["action"]): r["cpu_s"] for r in rows if r["arm"] == a["arm"]}
            first = {(r["seed"], r["action"]): r["cpu_s"] for r in rows
                     if r["arm"] == f"{a['arm'].split(' [')[0]} [{iks[0]}]"}
            ratio = statistics.median(cpus[k] / first[k] for k in cpus if first.get(k))
            print(f"| {a['arm']} | {a['solved']} / {a['tried']} | {a['cold_solved']} / {a['cold_tried']} | "
                  f"{a['pos_mm_median']} / {a['pos_mm_max']} | "
                  f"{a['yaw_deg_max']} | {statistics.median(walls):.3f} / {statistics.median(cpus.values()):.3f} | "
                  f"{ratio:.2f}x | "
                  f"{a['solve_ms_median']} / {a['solve_ms_max']} |")
    for r in rows:
        if r["outcome"] in ("failed", "crash", "unsuccessful"):
            print(f"  {r['arm']} {r['action']} seed {r['seed']}: {r['outcome']}: {r.get('reason')}")
    if args.json:
        Path(args.json).write_text(json.dumps({"rows": rows, "times": times, "ik_accuracy": accuracy}, indent=1) + "\n")


if __name__ == "__main__":
    main()
