"""Behaviour fingerprint of an l2p-bullet checkout (refactor check: output must stay byte-identical).

Usage: .venv/bin/python benchmarks/fingerprint.py . > out.txt   (run before and after a refactor; cmp the two)

Prints, deterministically:
  1. sha256 of the five built-in training sets (trainset.build per action, all demonstrations, default configs)
  2. the 2-D plans (``l2p-bullet plan``, in-process through click) of the shipped bundles on seeded scenes,
     all five actions: waypoints and progress rounded to 1e-9, verdict, planner, stopped; or the error
  3. sha256 of executed trajectory.json (``perform --no-render``, seeded), timing fields excluded, plus the
     summary's verdict
  4. the rule judges' and the shipped models' agreement with people's grades (learning/agreement.py)
Public names are looked up with fallbacks (a rename elsewhere should not break the script); the CLI is
driven in-process so parsing, feasibility, loading and judging are all covered.
"""

from __future__ import annotations

import hashlib
import importlib
import json
import math
import os
import pkgutil
import sys
import tempfile
from pathlib import Path

REPO = Path(sys.argv[1]).resolve()
sys.path.insert(0, str(REPO))
os.chdir(REPO)
os.environ.setdefault("PYTHONHASHSEED", "0")

import numpy as np  # noqa: E402

import l2p_bullet  # noqa: E402

assert Path(l2p_bullet.__file__).resolve().is_relative_to(REPO), l2p_bullet.__file__
TMP = "<tmp>"
ACTIONS = ("closer", "away", "next-to", "past", "around")
PHRASE = {"closer": "closer to", "away": "away from", "next-to": "next to", "past": "past", "around": "around"}


def find(attr: str, *modules: str):
    """``attr`` from the first of ``modules`` that has it, else from any l2p_bullet module that has it."""
    for m in modules:
        try:
            mod = importlib.import_module(m)
        except ImportError:
            continue
        if hasattr(mod, attr):
            return getattr(mod, attr)
    for info in pkgutil.walk_packages(l2p_bullet.__path__, "l2p_bullet."):
        try:
            mod = importlib.import_module(info.name)
        except Exception:
            continue
        if hasattr(mod, attr) and callable(getattr(mod, attr)):
            return getattr(mod, attr)
    raise SystemExit(f"fingerprint: cannot find {attr}")


def out(line: str) -> None:
    sys.stdout.write(line + "\n")


def r9(x):
    if isinstance(x, float):
        return None if math.isnan(x) else round(x, 9) + 0.0
    if isinstance(x, dict):
        return {k: r9(v) for k, v in sorted(x.items())}
    if isinstance(x, list | tuple):
        return [r9(v) for v in x]
    return x


# ---------------------------------------------------------------- 1. training sets
def training_sets() -> None:
    build = find("build", "l2p_bullet.learning.trainset")
    DataConfig = find("DataConfig", "l2p_bullet.learning.trainset")
    QSRConfig = find("QSRConfig", "l2p_bullet.progress.features")
    load_demos = find("load_demos", "l2p_bullet.data.demos", "l2p_bullet.learning.demos")
    demos = {a: list(load_demos(a)) for a in ACTIONS}
    for a in ACTIONS:
        seqs = build(a, demos, QSRConfig(), DataConfig(), seed=0)
        h = hashlib.sha256()
        for s in seqs:
            h.update(np.ascontiguousarray(s.x, np.float32).tobytes())
            h.update(np.ascontiguousarray(s.y, np.float32).tobytes())
            h.update(repr((float(s.weight), bool(s.positive), int(s.end))).encode())
            if s.frame_w is not None:
                h.update(np.ascontiguousarray(s.frame_w, np.float64).tobytes())
        out(f"trainset {a}: n={len(seqs)} pos={sum(bool(s.positive) for s in seqs)} sha256={h.hexdigest()}")


# ---------------------------------------------------------------- scenes
def scenes() -> list[tuple[str, dict]]:
    random_scene = find("random_scene", "l2p_bullet.core.scene")
    default_scene = find("default_scene", "l2p_bullet.core.scene")
    s = [("default", default_scene().to_dict())]
    s += [(f"random{i}", random_scene(i).to_dict()) for i in range(1, 17)]
    # refused by feasibility (out of the arm's reach) and a scene with a bystander
    rim = default_scene().to_dict()  # anchor near the workspace's rim: the room checks refuse some actions
    rim["objects"][0]["xy"], rim["objects"][1]["xy"] = [0.14, 0.0], [0.22, 0.0]
    s.append(("rim", rim))
    wide = default_scene().to_dict()  # mover and anchor on opposite rims: no room to go away
    wide["objects"][0]["xy"], wide["objects"][1]["xy"] = [0.21, 0.0], [-0.21, 0.0]
    s.append(("wide", wide))
    tall = default_scene().to_dict()  # a small mover beside a tall block: the grasp check refuses it
    tall["objects"][0].update(size=0.02, xy=[0.0, 0.0])
    tall["objects"][1]["xy"] = [-0.1, 0.0]
    tall["objects"].append({"name": "C", "color": "blue", "size": 0.08, "xy": [0.055, 0.0], "yaw": 0.0})
    s.append(("tall", tall))
    by = default_scene().to_dict()
    by["objects"].append({"name": "C", "color": "blue", "size": 0.05, "xy": [0.08, 0.08], "yaw": 0.0})
    s.append(("bystander", by))
    return s


def invoke(args: list[str]) -> tuple[int, str]:
    from click.testing import CliRunner

    main = find("main", "l2p_bullet.cli")
    res = CliRunner().invoke(main, args, catch_exceptions=True)
    last = (res.output.strip().splitlines() or [""])[-1]
    err = f" {last}" if res.exit_code else ""
    if res.exception is not None and not isinstance(res.exception, SystemExit):
        err = f" EXC {type(res.exception).__name__}: {res.exception}"
    return res.exit_code, err.replace(TMP, "<tmp>")


# ---------------------------------------------------------------- 2. plans
def plans(tmp: Path, sc: list[tuple[str, dict]]) -> None:
    for k, (name, scene) in enumerate(sc):
        sp = tmp / f"{name}.json"
        sp.write_text(json.dumps(scene))
        for j, a in enumerate(ACTIONS):
            seed = 7 * k + j
            d = tmp / f"plan-{name}-{a}"
            code, err = invoke(["plan", f"move A {PHRASE[a]} B", "--scene", str(sp), "--seed", str(seed),
                                "--out", str(d), "--no-plot", "--force"])
            if code != 0 or not (d / "plan.json").exists():
                out(f"plan {name} {a} seed={seed}: exit={code}{err}")
                continue
            p = json.loads((d / "plan.json").read_text())
            keep = {k2: p.get(k2) for k2 in ("action", "planner", "stopped", "start", "anchor_pose", "grasp_angle_deg")}
            # to 1e-6 m, as plan.json rounded it until 2026-11-28 (it now holds the path as executed), so that the
            # fingerprint compares with earlier ones
            keep["path"] = np.asarray(p["path"], float).round(6).tolist()
            keep["progress"] = p["progress"]
            keep["verdict"] = p.get("verdict")
            out(f"plan {name} {a} seed={seed}: " + json.dumps(r9(keep), sort_keys=True))


# ---------------------------------------------------------------- 3. executed trajectories
TIMING = {"timings", "timings_s", "created", "created_at", "finished_at", "started_at", "wall_s", "date", "time",
          "elapsed_s", "seconds", "host", "hostname", "versions", "version", "path"}


def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if k not in TIMING}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x


def performs(tmp: Path, sc: list[tuple[str, dict]]) -> None:
    picks = [
        ("default", "around", 0),
        ("default", "past", 1),
        ("random1", "closer", 2),
        ("random2", "away", 3),
        ("random3", "next-to", 4),
        ("bystander", "around", 5),
        ("random4", "around", 6),
        ("rim", "around", 7),
        ("rim", "closer", 8),
    ]
    for name, a, seed in picks:
        d = tmp / f"perform-{name}-{a}"
        code, err = invoke(["perform", f"move A {PHRASE[a]} B", "--scene", str(tmp / f"{name}.json"), "--seed",
                            str(seed), "--out", str(d), "--no-render", "--force", "--quiet"])
        t = d / "trajectory.json"
        if code != 0 or not t.exists():
            out(f"perform {name} {a} seed={seed}: exit={code}{err}")
            continue
        traj = strip(json.loads(t.read_text()))
        h = hashlib.sha256(json.dumps(traj, sort_keys=True).encode()).hexdigest()
        summ = json.loads((d / "summary.json").read_text())
        v = summ.get("verdict")
        keys = sorted(k for k in summ if k not in TIMING)
        out(f"perform {name} {a} seed={seed}: frames={len(traj['frames'])} trajectory_sha256={h} "
            f"verdict={json.dumps(r9(v), sort_keys=True)} summary_keys={keys}")


# ---------------------------------------------------------------- 3b. the evaluate batch (in-process worker)
ROW_SKIP = {"plan_s", "execute_s", "total_s", "wall_s", "timings", "worker", "finished_at", "run_id", "run_dir"}


def evaluations(tmp: Path) -> None:
    import sqlite3

    for tag, args in (("plan-only", ["--scenes", "3", "--seed", "100", "--plan-only"]),
                      ("perform", ["--scenes", "1", "--seed", "200", "--actions", "around,next-to", "--no-render"])):
        d = tmp / f"eval-{tag}"
        code, err = invoke(["evaluate", *args, "--workers", "0", "--out", str(d), "--quiet"])
        if code != 0:
            out(f"evaluate {tag}: exit={code}{err}")
            continue
        db = sqlite3.connect(d / "results.sqlite")
        db.row_factory = sqlite3.Row
        rows = [dict(r) for r in db.execute("SELECT * FROM runs ORDER BY idx")]
        db.close()
        for r in rows:
            keep = {k: v for k, v in sorted(r.items()) if k not in ROW_SKIP}
            out(f"evaluate {tag} row {r['idx']}: " + json.dumps(r9(keep), sort_keys=True))


# ---------------------------------------------------------------- 4. agreement
def agreement() -> None:
    mods = ("l2p_bullet.learning.agreement",)
    rule_agreement = find("rule_agreement", *mods)
    model_agreement = find("model_agreement", *mods)
    ra = rule_agreement()
    out("rule_agreement " + json.dumps({k: repr(v) for k, v in sorted(ra.items())}))
    discover = find("discover", "l2p_bullet.plugins.registry")
    load = find("load", "l2p_bullet.plugins.registry")
    plugins = discover()
    models = {a: load(a, plugins).progress_model() for a in ACTIONS}
    ma = model_agreement(models)
    for folder, row in sorted(ma.items()):
        finals = np.asarray(row["finals"], float)
        out(f"model_agreement {folder}: spearman={row['spearman']!r} finals_sha256="
            f"{hashlib.sha256(np.round(finals, 9).tobytes()).hexdigest()}")


def main() -> None:
    with tempfile.TemporaryDirectory(prefix="l2p-fp-") as t:
        global TMP
        TMP = t
        tmp = Path(t)
        training_sets()
        sc = scenes()
        plans(tmp, sc)
        performs(tmp, sc)
        evaluations(tmp)
        agreement()


if __name__ == "__main__":
    main()
