"""Benchmark of the embodiment: one replay of a circle of A around B on the default scene.

Prints a table: physics steps per second, IK per second, ms per rendered frame, the cost of a new
world against reusing one (World.reset), wall time per stage, and the project's execute_path against the same loop
written as bare pybullet calls (same tool
targets, same rates, same bodies), as a ratio, without and with rendering.

    .venv/bin/python benchmarks/bench_embodiment.py [--repeats 3]
    .venv/bin/python benchmarks/bench_embodiment.py --repeats 1 --arc 30 --samples 1 --resolution 64x48 --fps 2

Timings are the best of ``--repeats`` runs (the machine is shared; the minimum is the least noisy).
``--arc`` shortens the circle (degrees of it) and ``--samples`` the micro measures (tens of steps, frames,
worlds): a smoke run goes through the same code in a few seconds.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from l2p_bullet.core.scene import default_scene  # noqa: E402
from l2p_bullet.embodiment.execute import execute_path  # noqa: E402
from l2p_bullet.embodiment.sim import primitives  # noqa: E402
from l2p_bullet.embodiment.sim.camera import RenderSettings  # noqa: E402

RENDER = RenderSettings(width=320, height=240, fps=10.0)


def circle_path(scene, n=121, arc=360.0):
    a, b = scene.get("A"), scene.get("B")
    c, p0 = np.array(b.xy), np.array(a.xy)
    r = float(np.hypot(*(p0 - c)))
    ang = math.atan2(p0[1] - c[1], p0[0] - c[0]) + np.linspace(0, math.radians(arc), n)
    return np.column_stack([c[0] + r * np.cos(ang), c[1] + r * np.sin(ang), np.full(n, a.yaw)])


def project_run(render, arc=360.0):
    """execute_path, also capturing the tool targets and stages it commanded (for the bare loop)."""
    scene = default_scene()
    captured: list[tuple[str, np.ndarray]] = []
    original = primitives.Primitives.run

    def spy(self, timed, stage, joints=None):
        captured.append((stage, self._control_samples(timed)))
        return original(self, timed, stage, joints)

    primitives.Primitives.run = spy
    try:
        t0 = time.perf_counter()
        ex = execute_path(scene, "A", circle_path(scene, arc=arc), out_dir=None, render=render, meta={"anchor": "B"})
        wall = time.perf_counter() - t0
    finally:
        primitives.Primitives.run = original
    return wall, ex, captured


def bare_run(captured, render):
    """The same episode in bare pybullet: IK on the simulated arm per control step, interpolated joint
    targets, 240 Hz physics, a fixed constraint, poses sampled at 30 fps, frames at the render's fps (every 24
    steps at 10 fps)."""
    import pybullet as pb
    import pybullet_data

    from l2p_bullet.arms import PANDA
    from l2p_bullet.embodiment.sim.arms import arm_urdf
    from l2p_bullet.embodiment.sim.world import urdf_path

    t0 = time.perf_counter()
    cid = pb.connect(pb.DIRECT)
    pb.setAdditionalSearchPath(pybullet_data.getDataPath(), physicsClientId=cid)
    pb.setGravity(0, 0, -9.81, physicsClientId=cid)
    pb.setTimeStep(1 / 240, physicsClientId=cid)
    pb.loadURDF(urdf_path("table.urdf"), useFixedBase=True, physicsClientId=cid)
    blocks = {}
    for o in default_scene().objects:
        blocks[o.name] = pb.loadURDF(urdf_path("block.urdf"), [o.xy[0], o.xy[1], o.size / 2],
                                     pb.getQuaternionFromEuler([0, 0, o.yaw]), physicsClientId=cid)
    robot = pb.loadURDF(arm_urdf(PANDA, visuals=render is not None), [-0.53, 0, 0], useFixedBase=True,
                        physicsClientId=cid)
    joints = list(range(7))
    for j, q in zip(joints, PANDA.home, strict=True):
        pb.resetJointState(robot, j, q, physicsClientId=cid)
    if render is not None:
        view = pb.computeViewMatrix((0.5, -0.5, 0.6), (-0.15, 0, 0.1), (0, 0, 1))
        proj = pb.computeProjectionMatrixFOV(50, render.width / render.height, 0.05, 3.0)
    q_prev = np.array(PANDA.home)
    steps, frames, images, cons = 0, [], 0, None
    every = max(1, round(240 / render.fps)) if render is not None else 0
    forces, gains = [87.0] * 4 + [12.0] * 3, [PANDA.position_gain] * 7

    def step():
        nonlocal steps, images
        pb.stepSimulation(physicsClientId=cid)
        steps += 1
        if steps % 8 == 0:
            frames.append([pb.getBasePositionAndOrientation(b, physicsClientId=cid) for b in blocks.values()]
                          + [pb.getLinkState(robot, 11, physicsClientId=cid)[4]])
        if render is not None and steps % every == 0:
            pb.getCameraImage(render.width, render.height, view, proj, renderer=pb.ER_TINY_RENDERER,
                              shadow=0, flags=pb.ER_NO_SEGMENTATION_MASK, physicsClientId=cid)
            images += 1

    def hold(n=24):
        for _ in range(n):
            pb.setJointMotorControlArray(robot, joints, pb.POSITION_CONTROL, targetPositions=q_prev.tolist(),
                                         forces=forces, positionGains=gains, physicsClientId=cid)
            step()

    for stage, poses in captured:
        if stage == "slide" and cons is None:
            hold()
            cons = pb.createConstraint(robot, 11, blocks["A"], -1, pb.JOINT_FIXED, [0, 0, 0], [0, 0, -0.036],
                                       [0, 0, 0], physicsClientId=cid)
        if stage == "retract" and cons is not None:
            pb.removeConstraint(cons, physicsClientId=cid)
            cons = None
            hold()
        for p in poses:
            orn = pb.getQuaternionFromEuler([math.pi, 0, p[3]])
            q = np.array(pb.calculateInverseKinematics(robot, 11, p[:3].tolist(), orn, maxNumIterations=10,
                                                       physicsClientId=cid)[:7])
            for i in range(1, 5):
                pb.setJointMotorControlArray(robot, joints, pb.POSITION_CONTROL,
                                             targetPositions=(q_prev + (q - q_prev) * (i / 4)).tolist(),
                                             forces=forces, positionGains=gains, physicsClientId=cid)
                step()
            q_prev = q
    pb.disconnect(cid)
    return time.perf_counter() - t0, steps, images


def micro(samples=10):
    """Steps/s, IK/s and ms per frame measured on their own (``samples`` x 100 steps, x 40 IK, frames, worlds)."""
    from l2p_bullet.embodiment.sim.camera import Camera
    from l2p_bullet.embodiment.sim.world import World

    out = {}
    world = World(default_scene())
    t = time.perf_counter()
    for _ in range(100 * samples):
        world.step()
    out["physics steps/s (world.step, idle arm)"] = 100 * samples / (time.perf_counter() - t)
    kin, q = world.robot.kin, np.array(world.robot.spec.home)
    targets = [(0.1 * math.cos(a), 0.05 + 0.1 * math.sin(a), 0.061, 0.2) for a in np.linspace(0, 6.28, 40 * samples)]
    q = kin.solve(targets[0][:3], targets[0][3], q, seeds=world.robot.spec.ik_seeds)
    t = time.perf_counter()
    for p in targets:
        q = kin.solve(p[:3], p[3], q)
    out["IK/s (project: seeded, FK-checked)"] = len(targets) / (time.perf_counter() - t)
    out["IK/s (bare calculateInverseKinematics, 10 it.)"] = len(targets) / bare_ik(targets)
    for w, h in ((320, 240), (640, 480)):
        cam = Camera(world, RenderSettings(width=w, height=h, renderer="tiny"))
        cam.render()
        t = time.perf_counter()
        for _ in range(samples):
            cam.render()
        out[f"ms per frame, tiny {w}x{h}"] = (time.perf_counter() - t) / samples * 1000
    world.close()
    for visuals in (False, True):
        t = time.perf_counter()
        for _ in range(samples):
            World(default_scene(), visuals=visuals).close()
        out[f"ms per new World (visuals={visuals})"] = (time.perf_counter() - t) / samples * 1000
        with World(default_scene(), visuals=visuals) as world:
            t = time.perf_counter()
            for _ in range(samples):
                world.reset(default_scene())
            out[f"ms per World.reset (visuals={visuals})"] = (time.perf_counter() - t) / samples * 1000
    return out


def bare_ik(targets) -> float:
    """Seconds for PyBullet's own IK (10 iterations, no checks) on a bare copy of the IK twin."""
    import pybullet as pb

    from l2p_bullet.arms import PANDA
    from l2p_bullet.embodiment.sim.arms import arm_urdf

    cid = pb.connect(pb.DIRECT)
    body = pb.loadURDF(arm_urdf(PANDA, visuals=False, collisions=False), [-0.53, 0, 0], useFixedBase=True,
                       physicsClientId=cid)
    orn = pb.getQuaternionFromEuler([math.pi, 0, 0.2])
    t = time.perf_counter()
    for p in targets:
        pb.calculateInverseKinematics(body, 11, p[:3], orn, maxNumIterations=10, physicsClientId=cid)
    wall = time.perf_counter() - t
    pb.disconnect(cid)
    return wall


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--resolution", default=f"{RENDER.width}x{RENDER.height}",
                    help="frame size of the rendered runs, WxH (a small one for a smoke run)")
    ap.add_argument("--fps", type=float, default=RENDER.fps, help="frames per second of the rendered runs")
    ap.add_argument("--arc", type=float, default=360.0, help="degrees of the circle around B the runs go")
    ap.add_argument("--samples", type=int, default=10, help="micro measures: x 100 steps, x 40 IK, frames, worlds")
    args = ap.parse_args()
    w, h = (int(v) for v in args.resolution.split("x"))
    render_settings = dataclasses.replace(RENDER, width=w, height=h, fps=args.fps)
    rows = []
    for label, render in (("no rendering", None), (f"rendering {w}x{h} @ {args.fps:g} fps", render_settings)):
        proj = min((project_run(render, args.arc) for _ in range(args.repeats)), key=lambda r: r[0])
        wall, ex, captured = proj
        bare = min((bare_run(captured, render) for _ in range(args.repeats)), key=lambda r: r[0])
        rows.append((label, wall, ex, bare))
    m = micro(args.samples)
    print("| measure | value |\n|---|---|")
    for k, v in m.items():
        print(f"| {k} | {v:,.1f} |")
    for label, wall, ex, bare in rows:
        steps = ex.stats["physics_steps"]
        print(f"| {label}: simulated time | {ex.duration_s:.1f} s, {steps} physics steps, "
              f"{ex.stats['ik_solves']} IK, {ex.stats['rendered_frames']} frames |")
        for stage, s in ex.timings.items():
            print(f"| {label}: stage {stage} | {s * 1000:.0f} ms |")
        print(f"| {label}: physics steps/s over the whole run | {steps / wall:,.0f} |")
        print(f"| {label}: execute_path wall | {wall:.2f} s |")
        print(f"| {label}: bare pybullet loop wall | {bare[0]:.2f} s ({bare[1]} steps, {bare[2]} frames) |")
        print(f"| {label}: ratio project / bare | **{wall / bare[0]:.2f}x** |")
        print(f"| {label}: block deviation / B moved | {ex.max_deviation_m * 1000:.2f} mm / "
              f"{ex.anchor_displacement_m * 1000:.2f} mm |")


if __name__ == "__main__":
    main()
