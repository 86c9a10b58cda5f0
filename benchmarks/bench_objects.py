"""Object stress benchmark (issue 22): scenes of mixed shapes perform, or are refused up front with a check.

    .venv/bin/python benchmarks/bench_objects.py                       # 1,000 scenes x 5 actions, no rendering
    .venv/bin/python benchmarks/bench_objects.py --scenes 40           # a quick look while developing
    .venv/bin/python benchmarks/bench_objects.py --scenes 200 --jobs 2 --json rows.json
    .venv/bin/python benchmarks/bench_objects.py --meshes DIR       # each mesh of DIR x 4 sentences, per mesh
    .venv/bin/python benchmarks/collect_meshes.py /tmp/meshes       # everyday meshes from public packages:
    .venv/bin/python benchmarks/bench_objects.py --meshes /tmp/meshes/tuned      # then each set
    .venv/bin/python benchmarks/bench_objects.py --meshes /tmp/meshes/held-out

Scenes are drawn from seeds ``--seed-base + i`` (default 950000: no other benchmark or training run uses
seeds there) by :func:`object_scene`. Every object is a cube (3-6 cm), a 2:1 box (short side 2.5-4 cm,
2-6 cm tall), a cylinder (radius 1.5-3 cm, 2-7 cm tall) or, exactly once per scene, a mesh: pybullet_data's
duck (``duck_vhacd.obj`` standing up, scale 0.03-0.045: 5-7 cm long). The mover A and the anchor B are
placed, in turn (by seed), with each mover shape, touching (a 0-5 mm gap between their footprints), 1.4-7.7 mover sizes
apart centre to
centre (the original study's range; a size is the side in blocks of ``core/shapes.py``), or one of them at
the workspace's rim; 2-5 bystanders of the same mix lie anywhere in the workspace (the duck among them when
it is neither A nor B). Every scene is valid (``Scene.validate``). Each is performed with each action by
``pipeline.perform`` (no rendering) on the default arm (the Panda). The objects are drawn in the arm's start
disk (0.25 m, the KUKA's 0.17 m); since the 0.35 m workspace of 2026-11-27 they are planned in the arm's
workspace (the 0.35 m disk cut by its ring), as ``perform`` plans a user's scene; ``--old-disk`` plans in the
start disk, as every row measured before did.

Per action it prints the outcomes of ``bench_robustness.py`` (success, unsuccessful, refused by check,
plan-failed, exec-failed: an error after the arm started, crashed: any other exception) and how many runs
moved an object other than the mover more than 1 mm, then the same by the mover's shape. Goals (issue 22):
zero crashes, zero failures half-way through execution, zero objects disturbed, and every refusal names a
check of ``planning.feasibility.CHECKS``.
"""

from __future__ import annotations

import argparse
import collections
import json
import math
import time
from pathlib import Path

from bench_perform import SENTENCES
from bench_robustness import COLORS, OUTCOMES, classify, print_table, run_jobs

SEED_BASE = 950_000
DUCK = "pybullet_data:duck_vhacd.obj"
SHAPES = ("cube", "box", "cylinder", "mesh")


def _object(name: str, color: str, kind: str, xy, yaw: float, rng):
    """One object of ``kind`` with sizes drawn from ``rng`` (module docstring)."""
    from l2p_bullet.core import shapes
    from l2p_bullet.core.scene import SceneObject, shaped

    xy = (float(xy[0]), float(xy[1]))
    if kind == "cube":
        return SceneObject(name, color, float(rng.uniform(0.03, 0.06)), xy, float(yaw))
    if kind == "box":
        s = float(rng.uniform(0.025, 0.04))
        return shaped(name, color, xy, yaw, shape="box", dims=(2 * s, s, float(rng.uniform(0.02, 0.06))))
    if kind == "cylinder":
        return shaped(name, color, xy, yaw, shape="cylinder", radius=float(rng.uniform(0.015, 0.03)),
                      height_m=float(rng.uniform(0.02, 0.07)))
    path = str(shapes.resolve_mesh(DUCK, None))
    return shaped(name, color, xy, yaw, shape="mesh", mesh=path, scale=float(rng.uniform(0.03, 0.045)),
                  rpy=(math.pi / 2, 0.0, 0.0))


def object_scene(seed: int, radius: float = 0.25, plan_in=None):
    """A valid mixed-shape scene drawn from ``seed`` inside a workspace of ``radius`` (an arm's fitted disk;
    0.25 m, the Panda's, gives the same scenes as before): (scene, kind, mover's shape). The scene plans in
    ``plan_in`` (a Workspace; None: the disk the objects were drawn in, as every row before 2026-11-27's
    0.35 m workspace did)."""
    import numpy as np

    from l2p_bullet.core.scene import Scene, Workspace
    from l2p_bullet.errors import SceneError

    rng = np.random.default_rng(seed)
    kind = ("touching", "study", "rim")[seed % 3]
    mover = SHAPES[(seed // 3) % 4]  # every pair of scene kind and mover shape in 12 seeds
    # the duck: the mover, else the anchor in half the scenes, else a bystander
    mesh_at = 0 if mover == "mesh" else int(rng.integers(1, 3))
    for _ in range(2000):
        kinds = [mover, "mesh" if mesh_at == 1 else str(rng.choice(SHAPES[:3]))]
        ya, yb = rng.uniform(0.0, math.pi, size=2)
        r = radius * math.sqrt(rng.uniform(0.8**2, 1.0) if kind == "rim" else rng.uniform())
        a0 = rng.uniform(-math.pi, math.pi)
        p0 = np.array([r * math.cos(a0), r * math.sin(a0)])
        direction = rng.uniform(-math.pi, math.pi)
        u = np.array([math.cos(direction), math.sin(direction)])
        a = _object("A", "red", kinds[0], (0.0, 0.0), ya, rng)
        b = _object("B", "green", kinds[1], (0.0, 0.0), yb, rng)
        dist = (
            _distance_for_gap(a, b, u, rng.uniform(0.0, 0.005))
            if kind == "touching"
            else rng.uniform(1.4, 7.7) * a.size
        )
        p1 = p0 + dist * u
        b_xy, a_xy = (p0, p1) if rng.uniform() < 0.5 else (p1, p0)
        objects = [a.moved(np.array([a_xy[0], a_xy[1], ya])), b.moved(np.array([b_xy[0], b_xy[1], yb]))]
        try:
            Scene(objects, workspace=Workspace(radius=radius)).validate()
        except SceneError:
            continue
        extra = ["mesh"] if mesh_at == 2 else []
        extra += [str(rng.choice(("cube", "box", "cylinder"))) for _ in range(int(rng.integers(2, 6)) - len(extra))]
        objects = _add_bystanders(objects, extra, rng, radius)
        if objects is None:
            continue
        return Scene(objects, workspace=plan_in or Workspace(radius=radius)).validate(), kind, kinds[0]
    raise RuntimeError(f"no valid object scene for seed {seed}")  # pragma: no cover


def _distance_for_gap(a, b, u, gap: float) -> float:
    """Centre distance along ``u`` at which the two footprints are ``gap`` apart (bisection)."""
    import numpy as np

    from l2p_bullet.core.geometry import separation

    fa = a.footprint(np.array([0.0, 0.0, a.yaw]))
    lo, hi = 0.0, 0.5
    for _ in range(50):
        mid = (lo + hi) / 2
        fb = b.footprint(np.array([mid * u[0], mid * u[1], b.yaw]))
        if float(separation(fa[None], fb)[0]) < gap:
            lo = mid
        else:
            hi = mid
    return float(np.nextafter(hi, np.inf))


def _add_bystanders(objects: list, kinds: list[str], rng, radius: float = 0.25) -> list | None:
    from l2p_bullet.core.scene import Scene, Workspace
    from l2p_bullet.errors import SceneError

    out = list(objects)
    for k, kind in enumerate(kinds):
        for _ in range(200):
            r, a = radius * math.sqrt(rng.uniform()), rng.uniform(-math.pi, math.pi)
            o = _object(f"C{k + 1}", COLORS[k % len(COLORS)], kind, (r * math.cos(a), r * math.sin(a)),
                        float(rng.uniform(0, math.pi)), rng)
            try:
                Scene([*out, o], workspace=Workspace(radius=radius)).validate()
            except SceneError:
                continue
            out.append(o)
            break
        else:
            return None
    return out


def run_one(action: str, seed: int, tmp: Path, plugins: list, arm: str = "panda", old_disk: bool = False) -> dict:
    """Perform ``action`` with ``arm`` on the object scene of ``seed`` (drawn inside that arm's start disk) in
    the product's workspace (the 0.35 m disk cut by the arm's ring), or with ``old_disk`` in the start disk
    itself, as the rows before 2026-11-27's wider workspace were; classify what happened
    (bench_robustness.classify)."""
    from l2p_bullet.arms import fit_workspace
    from l2p_bullet.core.scene import Workspace
    from l2p_bullet.pipeline import perform
    from l2p_bullet.planning.feasibility import CHECKS
    from l2p_bullet.plugins import arms as arm_plugins

    # the largest disk about the centre the arm reaches: the KUKA's scenes stay those its stress rows were drawn
    # in (0.17 m, before its workspace became the disk cut by its ring, issue 22): a part of that workspace
    radius = fit_workspace(Workspace(), arm_plugins.get(arm)).starts().inner_radius  # the start disk's
    scene, kind, shape = object_scene(seed, radius, None if old_disk else Workspace())
    out = tmp / f"{action}-{seed}"
    row = {"action": action, "seed": seed, "kind": kind, "shape": shape, "objects": len(scene.objects)}
    return classify(row, out, lambda: perform(SENTENCES[action], scene, out_dir=out, seed=seed, render=False,
                                              plugins=plugins, arm=arm), checks=CHECKS)


def _worker(args: tuple[list[tuple[str, int]], str, str, bool]) -> list[dict]:
    jobs, tmp, arm, old_disk = args
    from l2p_bullet.plugins import registry

    plugins = registry.discover()
    return [run_one(a, s, Path(tmp), plugins, arm, old_disk) for a, s in jobs]


def print_shapes(rows: list[dict]) -> None:
    """Outcomes by the mover's shape, and the refusals that name no known check (goal: none)."""
    print("\nby the mover's shape (all actions):")
    for shape in ("cube", "box", "cylinder", "mesh"):
        rs = [r for r in rows if r["shape"] == shape]
        n = collections.Counter(r["outcome"] for r in rs)
        disturbed = sum(1 for r in rs if r.get("disturbed"))
        print(f"  {shape:<9} {len(rs):5d} runs: " + ", ".join(f"{o} {n[o]}" for o in OUTCOMES if n[o])
              + f"; disturbed {disturbed}")
    bounded = [r for r in rows if r.get("bounded")]
    print(f"\nplans whose search the work cap ended (planning.CHECK_CAP): {len(bounded)} of "
          f"{sum(r['outcome'] in ('success', 'unsuccessful') for r in rows)} performed, "
          f"{sum(r['outcome'] == 'success' for r in bounded)} of them successes")
    unnamed = [r for r in rows if r["outcome"] == "refused" and not r.get("named")]
    print(f"\nrefusals naming no known check: {len(unnamed)}")
    for r in unnamed:
        print(f"  {r['action']} seed {r['seed']}: {r.get('check')!r} {r.get('error', '')[:120]}")


def _line(r: dict) -> str:
    return (f"{r['action']:<8} seed {r['seed']} {r['kind']:<8} {r['shape']:<8} {r['outcome']:<12} {r['seconds']:.2f}s "
            f"{r.get('check', '') or r.get('error', '')[:100]}")


MESH_SENTENCES = {"around": "move M around B", "next-to": "move A next to M", "push-past": "push M past B",
                  "carry-closer": "carry M closer to B"}
"""``--meshes``: each mesh M as the mover going around, as the anchor of next to, pushed past and carried closer."""
MESH_EXTENT = 0.06
"""m: a mesh with no entry in the folder's meshes.json is scaled so that its largest extent is this."""


def mesh_scene(path: Path, entry: dict):
    """The scene of ``--meshes``: the mesh M (scaled and turned as ``entry`` says, or to :data:`MESH_EXTENT`) and
    4 cm cubes B and A, where the four sentences plan successfully with a 4 cm cube as M."""
    import numpy as np
    import trimesh

    from l2p_bullet.core.scene import Scene
    from l2p_bullet.core.shapes import _rotation

    rpy = [float(v) for v in entry.get("rpy", (0.0, 0.0, 0.0))]
    scale = entry.get("scale")
    if scale is None:
        m = trimesh.load(str(path), force="mesh")
        scale = MESH_EXTENT / float(np.ptp(np.asarray(m.vertices) @ _rotation(tuple(rpy)).T, axis=0).max())
    mesh = {"name": "M", "color": "yellow", "shape": "mesh", "mesh": str(path.resolve()), "scale": float(scale),
            "rpy": rpy, "xy": [0.1, -0.08]}
    return Scene.from_dict({"objects": [mesh, {"name": "B", "color": "green", "size": 0.04, "xy": [0.0, 0.1]},
                                        {"name": "A", "color": "red", "size": 0.04, "xy": [-0.1, 0.0]}]}).validate()


def mesh_rows(folder: Path, tmp: Path) -> list[dict]:
    """Every mesh of ``folder`` x :data:`MESH_SENTENCES`, performed (no rendering) and classified; a scene that is
    refused as it loads (a mesh that falls over, is too big) is one row per sentence with that refusal."""
    from bench_robustness import classify

    from l2p_bullet.errors import L2PError
    from l2p_bullet.pipeline import perform
    from l2p_bullet.planning.feasibility import CHECKS
    from l2p_bullet.plugins import registry

    plugins = registry.discover()
    table = json.loads((folder / "meshes.json").read_text()) if (folder / "meshes.json").is_file() else {}
    rows = []
    for path in sorted(p for p in folder.iterdir() if p.suffix.lower() in (".obj", ".stl", ".glb")):
        for action, sentence in MESH_SENTENCES.items():
            row = {"mesh": path.name, "action": action}
            t = time.perf_counter()
            try:
                scene = mesh_scene(path, table.get(path.name, {}))
            except L2PError as e:
                rows.append(row | {"outcome": "refused", "check": "scene", "error": str(e), "seconds": 0.0})
                print(f"{path.name:<28} {action:<13} refused: {e}", flush=True)
                continue
            out = tmp / f"{path.stem}-{action}"
            rows.append(classify(row, out, lambda s=sentence, sc=scene, o=out: perform(s, sc, out_dir=o, render=False,
                                                                             plugins=plugins),
                                 checks=CHECKS))
            r = rows[-1]
            r["seconds"] = round(time.perf_counter() - t, 3)
            print(f"{path.name:<28} {action:<13} {r['outcome']:<12} {r['seconds']:6.1f}s "
                  f"{r.get('reason') or r.get('error', '')}"[:240], flush=True)
    return rows


def print_meshes(rows: list[dict]) -> None:
    """Per mesh: the outcome of each sentence, and how many runs moved another object more than 1 mm."""
    actions = list(MESH_SENTENCES)
    print(f"\n{'mesh':<28} " + " ".join(f"{a:<13}" for a in actions) + " disturbed")
    for mesh in sorted({r["mesh"] for r in rows}):
        rs = {r["action"]: r for r in rows if r["mesh"] == mesh}
        print(f"{mesh:<28} " + " ".join(f"{rs[a]['outcome'] if a in rs else '-':<13}" for a in actions)
              + f" {sum(1 for r in rs.values() if r.get('disturbed'))}")
    n = collections.Counter(r["outcome"] for r in rows)
    print(f"\n{len(rows)} runs: " + ", ".join(f"{o} {c}" for o, c in sorted(n.items())))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", type=int, default=1000, help="random object scenes (seeds seed-base .. +N-1)")
    ap.add_argument("--seed-base", type=int, default=SEED_BASE)
    ap.add_argument("--actions", default=",".join(SENTENCES), help="comma-separated actions")
    ap.add_argument("--jobs", type=int, default=1, help="worker processes")
    ap.add_argument("--arm", default="panda", help="the arm (l2p-bullet arms); scenes are drawn inside its workspace")
    ap.add_argument("--json", type=Path, default=None, help="also write every row here")
    ap.add_argument("--old-disk", action="store_true",
                    help="plan in the disk the scene was drawn in (the rows measured before 2026-11-27's 0.35 m "
                         "workspace), not the product's workspace")
    ap.add_argument("--meshes", type=Path, default=None,
                    help="a folder of meshes (.obj, .stl, .glb; an optional meshes.json gives each its scale and "
                         "rpy): each x around, next to (as anchor), push past, carry closer, one table per mesh")
    args = ap.parse_args()
    if args.meshes is not None:
        import tempfile

        with tempfile.TemporaryDirectory(prefix="bench-meshes-") as tmp:
            rows = mesh_rows(args.meshes, Path(tmp))
        print_meshes(rows)
        if args.json:
            args.json.write_text(json.dumps(rows, indent=1))
        return
    actions = [a for a in args.actions.split(",") if a]
    jobs = [(a, args.seed_base + i) for i in range(args.scenes) for a in actions]
    t0 = time.perf_counter()
    save = (lambda rows: args.json.write_text(json.dumps(rows, indent=1))) if args.json else None
    rows = run_jobs(
        jobs,
        args.jobs,
        _worker,
        run_one,
        "bench-objects-",
        extra=(args.arm, args.old_disk),
        split=16,
        line=_line,
        save=save,
    )
    rows.sort(key=lambda r: (r["seed"], actions.index(r["action"])))
    print(
        f"\nobjects: {args.scenes} mixed-shape scenes (seeds {args.seed_base}..{args.seed_base + args.scenes - 1}) "
        f"x {len(actions)} actions, arm {args.arm}, "
        f"planned in {'the start disk' if args.old_disk else 'its workspace'}, "
        f"no rendering, {time.perf_counter() - t0:.0f} s\n"
    )
    print_table(rows, actions)
    print_shapes(rows)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
