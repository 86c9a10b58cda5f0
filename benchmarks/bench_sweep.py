"""The blocked-around sweep with and without the per-yaw projection (``geometry.posed_separation``), side by side.

For each shipped arm, the stress benchmark's scenes of ``--seeds`` (``bench_objects.object_scene``, drawn in the
arm's start disk and planned in its workspace) get feasibility's ``blocked-around`` check for "move A around B"
twice in a row: once with every grid polygon placed and projected (``separation``, the way before 2026-11-27's
eighth session) and once projected per distinct yaw. Prints per arm the seconds each way, their ratio, and how many
verdicts (refused or not, and the refusal's text) differ: goal none.

    cd benchmarks && ../.venv/bin/python bench_sweep.py --scenes 40
"""

from __future__ import annotations

import argparse
import time

from bench_objects import object_scene

ARMS = (("panda", 974_000), ("xarm6", 975_000), ("kuka-iiwa", 976_000))


def _verdict(check, scene) -> str:
    from l2p_bullet.errors import InfeasibleError

    try:
        check(scene, "A", "B")
    except InfeasibleError as e:
        return f"{e.check}: {e}"
    return "ok"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", type=int, default=40, help="scenes per arm (seeds 974000.. panda, 975000.. xarm6, "
                                                              "976000.. kuka-iiwa)")
    ap.add_argument("--arms", default=",".join(a for a, _ in ARMS), help="comma-separated arms (default: all three)")
    args = ap.parse_args()
    from l2p_bullet.arms import fit_scene, fit_workspace
    arms = [(a, base) for a, base in ARMS if a in args.arms.split(",")]
    if unknown := set(args.arms.split(",")) - {a for a, _ in ARMS}:
        ap.error(f"--arms: unknown {', '.join(sorted(unknown))} (known: {', '.join(a for a, _ in ARMS)})")
    from l2p_bullet.core.geometry import posed_separation, separation
    from l2p_bullet.core.workspace import Workspace
    from l2p_bullet.planning import sweep, world2d
    from l2p_bullet.planning.world2d import place_outline
    from l2p_bullet.plugins import arms as arm_plugins

    ways = {"placed": lambda o, p, q: separation(place_outline(o, p), q), "per yaw": posed_separation}
    print(
        "| arm | scenes | refused | placed s | per-yaw s | ratio | verdicts differing |\n"
        "|---|---:|---:|---:|---:|---:|---:|"
    )
    try:
        for arm, base in arms:
            radius = fit_workspace(Workspace(), arm_plugins.get(arm)).starts().inner_radius
            seconds, verdicts = {w: 0.0 for w in ways}, {w: [] for w in ways}
            for i in range(args.scenes):
                scene = fit_scene(object_scene(base + i, radius, Workspace())[0], arm_plugins.get(arm))
                for way, fn in ways.items():
                    world2d.posed_separation = fn  # World2D.shortfall's, which the sweep calls
                    t = time.perf_counter()
                    verdicts[way].append(_verdict(sweep.blocked_around, scene))
                    seconds[way] += time.perf_counter() - t
            differ = sum(a != b for a, b in zip(*verdicts.values(), strict=True))
            refused = sum(v != "ok" for v in verdicts["per yaw"])
            print(f"| {arm} | {args.scenes} | {refused} | {seconds['placed']:.1f} | {seconds['per yaw']:.1f} | "
                  f"{seconds['placed'] / seconds['per yaw']:.1f}x | {differ} |", flush=True)
    finally:
        world2d.posed_separation = posed_separation


if __name__ == "__main__":
    main()
