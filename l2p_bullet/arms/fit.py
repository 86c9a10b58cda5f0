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


def fit_workspace(workspace: Workspace, spec: ArmSpec) -> Workspace:
    """The workspace an arm gets: unchanged when its reach ring around its mount holds the whole disk, else the disk
    intersected with the ring (every shipped arm's ring cuts the 0.35 m disk)."""
    cut = replace(
        workspace, ring=(float(spec.mount[0]), float(spec.mount[1]), float(spec.reach[0]), float(spec.reach[1]))
    )
    return workspace if cut.holds_disk(workspace.radius) else cut


def fit_scene(scene: Scene, spec: ArmSpec) -> Scene:
    """``scene`` with its workspace fitted to the arm (:func:`fit_workspace`); SceneError naming the arm and its ring
    when a block stands outside what the arm reaches."""
    ws = fit_workspace(scene.workspace, spec)
    if ws == scene.workspace:
        return scene
    if ws.empty:
        raise SceneError(f'the arm "{spec.name}" reaches the table only {spec.reach[0]:.2f}-{spec.reach[1]:.2f} m '
                         f"from its base, which leaves nothing of the workspace around {scene.workspace.center}")
    base = np.array(ws.ring[:2])
    for o in scene.objects:
        if not ws.contains(np.array(o.xy))[0]:
            r = float(np.hypot(*(np.asarray(o.xy) - base)))
            if spec.reach[0] <= r <= spec.reach[1]:  # in the ring but off the disk (an unvalidated scene)
                raise SceneError(f'object "{o.name}" at ({o.xy[0]:.3f}, {o.xy[1]:.3f}) is outside the workspace of '
                                 f'the arm "{spec.name}" ({ws.describe()})')
            way = "outward" if r < spec.reach[0] else "inward"
            raise SceneError(
                f'object "{o.name}" at ({o.xy[0]:.3f}, {o.xy[1]:.3f}) is {r:.2f} m from the base of the arm '
                f'"{spec.name}", '
                f"which reaches the table only {spec.reach[0]:.2f}-{spec.reach[1]:.2f} m from its base; move it {way} "
                f"or choose another arm (l2p-bullet arms)"
            )
    return replace(scene, workspace=ws)
