"""Where an arm may put blocks: the scene's workspace fitted to the arm's reach ring.

What the arm reaches decides where blocks may stand: where its ``reach`` ring (measured by ``l2p-bullet arms
--check``) does not hold the scene's workspace disk, the workspace is the disk intersected with the ring
(``Workspace.ring``, core/workspace.py), and :func:`fit_scene` refuses a scene with a block outside it, naming
the arm and its ring.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..core.scene import Scene, Workspace
from ..errors import SceneError
from .spec import ArmSpec

TOOL_SPAN = (-0.008, 0.11)
"""The tool heights (m) a block of height h asks for, from h + TOOL_SPAN[0] (its grasp) to h + TOOL_SPAN[1] (its top
plus the hover): what the ring's test heights are for the 2-8 cm blocks they were chosen for (0.012 to 0.19 m,
``embodiment/arm_measure.py: REACH_HEIGHTS``)."""


def reach_for(spec: ArmSpec, heights=None) -> tuple[float, float]:
    """(near, far): the ring the arm reaches the tool heights of blocks of ``heights`` (m) at, from its rows per
    height (``ArmSpec.reach_heights``: every row from the last at or below the lowest such height to the first at or
    above the highest, since between two rows nothing was measured); ``reach`` where it has no rows, no heights
    are given or they lie beyond its rows. Never narrower than ``reach``. Why: ``reach`` holds every block 2-8 cm
    tall, and a ring held to an 8 cm block's hover and a 2 cm block's grasp refused "around" next to a UR3e's rim
    with 4 cm cubes that it reaches (docs/arms.md)."""
    rows = sorted(spec.reach_heights)
    hs = [float(h) for h in heights or ()]
    if not rows or not hs:
        return spec.reach
    lo, hi = min(hs) + TOOL_SPAN[0], max(hs) + TOOL_SPAN[1]
    zs = [z for z, _, _ in rows]
    if lo < zs[0] - 1e-9 or hi > zs[-1] + 1e-9:
        return spec.reach
    first = max(i for i, z in enumerate(zs) if z <= lo + 1e-9)
    last = min(i for i, z in enumerate(zs) if z >= hi - 1e-9)
    used = rows[first:last + 1]
    return (min(spec.reach[0], max(r[1] for r in used)), max(spec.reach[1], min(r[2] for r in used)))


def fit_workspace(workspace: Workspace, spec: ArmSpec, heights=None) -> Workspace:
    """The workspace an arm gets: unchanged when its reach ring around its mount holds the whole disk, else the disk
    intersected with the ring (every shipped arm's ring cuts the 0.35 m disk); the ring for blocks of ``heights``
    (m) where the arm declares one per height (:func:`reach_for`), else its ``reach``."""
    near, far = reach_for(spec, heights)
    cut = replace(workspace, ring=(float(spec.mount[0]), float(spec.mount[1]), float(near), float(far)))
    return workspace if cut.holds_disk(workspace.radius) else cut


def fit_scene(scene: Scene, spec: ArmSpec) -> Scene:
    """``scene`` with its workspace fitted to the arm and to its objects' heights (:func:`fit_workspace`);
    SceneError naming the arm and its ring when a block stands outside what the arm reaches."""
    ws = fit_workspace(scene.workspace, spec, [o.height for o in scene.objects])
    if ws == scene.workspace:
        return scene
    near, far = ws.ring[2:]  # the ring fit_workspace cut the workspace with
    if ws.empty:
        raise SceneError(f'the arm "{spec.name}" reaches the table only {near:.2f}-{far:.2f} m '
                         f"from its base, which leaves nothing of the workspace around {scene.workspace.center}")
    base = np.array(ws.ring[:2])
    for o in scene.objects:
        if not ws.contains(np.array(o.xy))[0]:
            r = float(np.hypot(*(np.asarray(o.xy) - base)))
            if near <= r <= far:  # in the ring but off the disk (an unvalidated scene)
                raise SceneError(f'object "{o.name}" at ({o.xy[0]:.3f}, {o.xy[1]:.3f}) is outside the workspace of '
                                 f'the arm "{spec.name}" ({ws.describe()})')
            way = "outward" if r < near else "inward"
            raise SceneError(
                f'object "{o.name}" at ({o.xy[0]:.3f}, {o.xy[1]:.3f}) is {r:.2f} m from the base of the arm '
                f'"{spec.name}", '
                f"which reaches the table only {near:.2f}-{far:.2f} m from its base; move it {way} "
                f"or choose another arm (l2p-bullet arms)"
            )
    return replace(scene, workspace=ws)
