"""The checks a path passes before the arm moves: finite waypoints inside the workspace, a start where the
block is, no collision of the block or of the hand holding it with another object, and the grasp angles that
keep the hand clear; as each manner needs them (a carried block only where it is set down).

Apart from :mod:`.execute` because chains (chain/forecast.py) check every clause's path against the scene
they predict, long before (and without) an arm to run it: these checks read the scene and the arm's model in
``arms/``, never the simulator.
"""

from __future__ import annotations

import numpy as np

from ..arms import PANDA, ArmSpec, reach
from ..core.scene import Scene
from ..errors import InfeasibleError, PathError
from ..manners.spec import MannerSpec
from . import motion
from .manners import check_carry_path, check_manner

START_TOLERANCE = 0.003  # m: a path must start where its block is


def check_path(scene: Scene, mover: str, path: np.ndarray, arm: ArmSpec = PANDA) -> np.ndarray:
    """Validate a mover path against the scene; return it cleaned (yaw unwrapped, repeats merged)."""
    return checked_path(scene, mover, path, arm)[0]


MAX_YAW_RAD = 1e4
"""A yaw beyond this many radians (1,600 turns) is a unit mistake or garbage, not a motion."""


def check_waypoints(scene: Scene, mover: str, path: np.ndarray) -> None:
    """Finite numbers, sane yaws and every waypoint inside the workspace: checked on the waypoints
    *before* the path is densified (the disk is convex, so a path between waypoints inside it stays inside;
    with an arm's reach ring each straight move is checked against the ring's hole too,
    ``Workspace.path_inside``). A waypoint 1e5 m away used to ask for gigabytes of dense points before being
    refused."""
    try:
        p = np.asarray(path, dtype=float)
    except (TypeError, ValueError, OverflowError) as e:
        raise PathError(f'the path of "{mover}" is not a list of [x, y, yaw] numbers ({str(e)[:80]})') from None
    if p.ndim != 2 or p.shape[1] != 3 or len(p) == 0:
        raise PathError(f'the path of "{mover}" must be a list of [x, y, yaw] waypoints (got shape {p.shape})')
    if not np.isfinite(p).all():
        k = int(np.argmin(np.isfinite(p).all(axis=1)))
        raise PathError(f'the path of "{mover}" has a number that is not finite at waypoint {k}')
    if np.abs(p[:, 2]).max() > MAX_YAW_RAD:
        raise PathError(f'the path of "{mover}" turns the block by more than {MAX_YAW_RAD:g} rad (a unit mistake?)')
    ws = scene.workspace
    k = ws.path_inside(p)
    if k is not None and ws.ring is None:
        r = float(np.hypot(*(p[k, :2] - np.array(ws.center))))
        raise PathError(f'the path of "{mover}" leaves the workspace at waypoint {k} ({p[k, 0]:.4g}, {p[k, 1]:.4g}), '
                        f"{r:.4g} m from its centre (radius {ws.radius} m)")
    if k is not None:
        what = f"at waypoint {k}" if k == 0 or not ws.contains(p[k, :2])[0] else f"between waypoints {k - 1} and {k}"
        raise PathError(f'the path of "{mover}" leaves the workspace {what} ({p[k, 0]:.4g}, {p[k, 1]:.4g}): '
                        f"it is {ws.describe()}")


def checked_path(
    scene: Scene, mover: str, path: np.ndarray, arm: ArmSpec = PANDA
) -> tuple[np.ndarray, list[float | None]]:
    """:func:`check_path`, and the grasp angles whose hand clears every other object along the whole path
    (``[None]`` when the hand never reaches beyond the block: any multiple of 90 degrees will do): the
    square angles that do, else those of a 5 degree grid."""
    obj = scene.get(mover)
    check_waypoints(scene, mover, path)
    p = motion.clean_path(path)
    start_gap = float(np.hypot(*(p[0, :2] - np.array(obj.xy))))
    if start_gap > START_TOLERANCE:
        raise PathError(f'the path starts at ({p[0, 0]:.3f}, {p[0, 1]:.3f}) but block "{mover}" is at '
                        f"({obj.xy[0]:.3f}, {obj.xy[1]:.3f}), {start_gap * 1000:.0f} mm away")
    dense = np.concatenate(motion.slide_chunks(p, radius=0.0)) if len(p) > 1 else p
    inside = scene.workspace.contains(dense[:, :2])
    if not inside.all():
        k = int(np.argmin(inside))
        r = float(np.hypot(*(dense[k, :2] - np.array(scene.workspace.center))))
        raise PathError(
            f'the path of "{mover}" leaves the workspace at ({dense[k, 0]:.3f}, {dense[k, 1]:.3f}), '
            + (
                f"{r:.3f} m from its centre (radius {scene.workspace.radius} m)"
                if scene.workspace.ring is None
                else f"outside {scene.workspace.describe()}"
            )
        )
    hit = reach.blocked_by(scene, mover, dense, None, hand=False)  # the block itself
    if hit is not None:
        pose = dense[hit[1]]
        raise PathError(f'the path of "{mover}" runs into "{hit[0]}" at ({pose[0]:.3f}, {pose[1]:.3f})')
    shaped = obj.shape != "cube"
    if not shaped and not reach.hand_matters(scene, mover, arm):
        return p, [None]
    first_hit = None
    # a box, cylinder or mesh: only the angles its width fits, narrowest first (a cube fits any square one)
    for angles in (
        (reach.width_angles(obj, arm),) if shaped else (reach.SQUARE_ANGLES, np.arange(0.0, np.pi, reach.ANGLE_STEP))
    ):
        clear = []
        for angle in angles:
            hit = reach.blocked_by(scene, mover, dense, float(angle), arm)
            if hit is None:
                clear.append(float(angle))
            elif first_hit is None:
                first_hit = hit
        if clear:
            return p, clear
    if first_hit is None:
        raise PathError(f'no grasp angle fits "{mover}" between the open fingers (see the "grasp-width" check)')
    pose = dense[first_hit[1]]
    raise PathError(f'the hand holding "{mover}" would knock "{first_hit[0]}" at ({pose[0]:.3f}, {pose[1]:.3f}) '
                    "whichever way it turns")



def check_for(manner: MannerSpec, scene: Scene, mover: str, path: np.ndarray,
              arm: ArmSpec = PANDA) -> tuple[np.ndarray, list[float | None]]:
    """:func:`checked_path` as the manner needs it: a carried block may pass over other objects (only where it is
    set down must be clear, and the hand is above everything), an object the manner cannot handle is refused."""
    check_manner(manner, scene, mover, arm, path=np.asarray(path, float) if manner.motion == "push" else None)
    if manner.motion != "carry":
        return checked_path(scene, mover, path, arm)
    check_waypoints(scene, mover, path)
    p = motion.clean_path(path)
    obj = scene.get(mover)
    start_gap = float(np.hypot(*(p[0, :2] - np.array(obj.xy))))
    if start_gap > START_TOLERANCE:
        raise PathError(f'the path starts at ({p[0, 0]:.3f}, {p[0, 1]:.3f}) but block "{mover}" is at '
                        f"({obj.xy[0]:.3f}, {obj.xy[1]:.3f}), {start_gap * 1000:.0f} mm away")
    check_carry_path(scene, mover, p)
    if obj.shape == "cube":
        return p, [None]
    # the fingers close across the object: only the angles whose width fits, narrowest first
    angles = reach.width_angles(obj, arm)[:reach.MAX_WIDTH_HOLDS]
    if not angles:
        raise InfeasibleError(f'cannot carry "{mover}": no grasp angle fits it between the {arm.name}\'s fingers '
                              f"({arm.gripper_opening * 100:.1f} cm); slide or push it instead")
    return p, angles
