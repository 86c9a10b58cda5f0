"""What the default video shows: is the mover seen, how big is a block, what does the video cost.

    .venv/bin/python benchmarks/bench_pictures.py [--renderer egl] [--json out.json]

For "push A past B" and "move A around B" on the default scene, ``l2p-bullet perform`` runs once per camera,
``viewer`` (the fixed camera behind the robot: the video before the framed camera) and ``auto`` (the framed
one, now the default), in a fresh process each. Then, for every video frame (15 fps of simulated time,
rebuilt from trajectory.json's poses and joints), the mover's pixels are counted in PyBullet's segmentation
buffer twice with the run's camera: with everything in the scene, and with the mover alone (the arm and
the other blocks moved far away). Reported:

- visible: the share of frames where the mover shows at least a quarter of its unoccluded area (goal >= 90 %);
- cube px: the pixels of an unoccluded 4 cm cube at the mover's start, at 640x480 (goal >= 1,500);
- wall/sim: the rendered perform's wall seconds (start-up included) over the episode's simulated seconds.

The machine's load average is printed: wall/sim depends on it; the other two do not.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

SENTENCES = ("push A past B", "move A around B")
CAMERAS = ("viewer", "auto")
FAR = (50.0, 50.0, 50.0)


def perform(sentence: str, camera: str, out: Path, renderer: str, fps: float | None = None,
            resolution: str | None = None) -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "l2p_bullet.cli", "perform", sentence, "--out", str(out), "--force", "-q",
                    "--camera", camera, "--renderer", renderer, *([] if fps is None else ["--fps", str(fps)]),
                    *([] if resolution is None else ["--resolution", resolution])],
                   check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def _quat(yaw: float) -> tuple[float, float, float, float]:
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def measure(run: Path) -> dict:
    """Visible share and cube pixels of one run folder, with the camera its summary.json records."""
    from l2p_bullet.core.scene import Scene, SceneObject
    from l2p_bullet.embodiment.render import movable_joints
    from l2p_bullet.embodiment.sim.camera import Camera, CameraPose, RenderSettings
    from l2p_bullet.embodiment.sim.robot import ARM
    from l2p_bullet.embodiment.sim.world import World

    summary = json.loads((run / "summary.json").read_text())
    traj = json.loads((run / "trajectory.json").read_text())
    render = summary["render"]
    pose = CameraPose(**{k: tuple(v) if isinstance(v, list) else v for k, v in render["camera"].items()})
    settings = RenderSettings(render["width"], render["height"], renderer="tiny", camera=pose)
    plan = json.loads((run / "plan.json").read_text())
    scene = Scene.from_dict(plan["scene"])
    mover = traj["mover"]
    every = max(1, round(traj["fps"] / render["fps"]))
    with World(scene, visuals=True) as world:
        sim, pb = world.sim, world.sim._pb
        cam = Camera(world, settings)
        joints = movable_joints(world)
        ids = dict(sim._bodies)
        arm_pose = sim.base_pose(ARM)

        def seg() -> np.ndarray:
            img = pb.getCameraImage(settings.width, settings.height, cam.view, cam.proj, renderer=pb.ER_TINY_RENDERER,
                                    physicsClientId=sim._id)
            return np.asarray(img[4]).reshape(settings.height, settings.width)

        seen = []
        for f in traj["frames"][::every]:
            sim.reset_joints(ARM, joints, f["arm"])
            for name, p in f["poses"].items():
                sim.set_base_pose(name, p[:3], _quat(p[3]))
            full = int((seg() == ids[mover]).sum())
            sim.set_base_pose(ARM, FAR, (0, 0, 0, 1))
            for name in f["poses"]:
                if name != mover:
                    sim.set_base_pose(name, FAR, (0, 0, 0, 1))
            alone = int((seg() == ids[mover]).sum())
            sim.set_base_pose(ARM, *arm_pose)
            seen.append(full >= 0.25 * alone if alone else False)
    start = traj["frames"][0]["poses"][mover]
    cube = Scene([SceneObject("cube", "red", 0.04, (start[0], start[1]), 0.0)])
    with World(cube, visuals=True) as world:
        sim, pb = world.sim, world.sim._pb
        cam = Camera(world, settings)
        sim.set_base_pose(ARM, FAR, (0, 0, 0, 1))
        img = pb.getCameraImage(settings.width, settings.height, cam.view, cam.proj, renderer=pb.ER_TINY_RENDERER,
                                physicsClientId=sim._id)
        cube_px = int((np.asarray(img[4]).reshape(settings.height, settings.width) == sim._bodies["cube"]).sum())
    return {"frames": len(seen), "visible": float(np.mean(seen)), "cube_px": cube_px,
            "simulated_s": summary["simulated_s"], "pose": render["camera"]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--renderer", default="egl", choices=("egl", "tiny"))
    ap.add_argument("--json", type=Path, default=None)
    ap.add_argument("--sentences", default=",".join(SENTENCES), help="comma-separated (default: both)")
    ap.add_argument("--fps", type=float, default=None, help="video frames per second (default: perform's)")
    ap.add_argument("--resolution", default=None,
                    help="video frame size WxH (default: perform's; the cube's pixels are then at that size)")
    args = ap.parse_args()
    sentences = [s for s in args.sentences.split(",") if s]
    load0 = os.getloadavg()
    print(f"cores {os.cpu_count()}, load average before {load0[0]:.1f} {load0[1]:.1f} {load0[2]:.1f}", flush=True)
    rows = []
    with tempfile.TemporaryDirectory(prefix="bench-pictures-") as td:
        for sentence in sentences:
            for camera in CAMERAS:
                out = Path(td) / f"{camera}-{sentence.replace(' ', '_')}"
                wall = perform(sentence, camera, out, args.renderer, args.fps, args.resolution)
                m = measure(out)
                rows.append({"sentence": sentence, "camera": camera, "wall_s": wall, **m,
                             "wall_over_sim": wall / m["simulated_s"]})
                print(f"  {sentence} / {camera}: {m['visible']:.0%} visible, cube {m['cube_px']} px, "
                      f"{wall:.1f} s wall", file=sys.stderr, flush=True)
    load1 = os.getloadavg()
    print(f"load average after {load1[0]:.1f} {load1[1]:.1f} {load1[2]:.1f}")
    print(f"{'sentence':<18} {'visible (>=25 %)':>23} {'4 cm cube px':>19} {'wall/sim':>17}")
    print(f"{'':<18} {'viewer':>11} {'auto':>11} {'viewer':>9} {'auto':>9} {'viewer':>8} {'auto':>8}")
    for sentence in sentences:
        v, a = (next(r for r in rows if r["sentence"] == sentence and r["camera"] == c) for c in CAMERAS)
        print(f"{sentence:<18} {v['visible']:>11.0%} {a['visible']:>11.0%} {v['cube_px']:>9} {a['cube_px']:>9} "
              f"{v['wall_over_sim']:>8.2f} {a['wall_over_sim']:>8.2f}")
    print("goals: visible >= 90 %, cube >= 1500 px, wall/sim <= 1 on a quiet two-core machine")
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
