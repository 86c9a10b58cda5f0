"""Whether an arm's pose folds it into itself: its links' collision shapes checked pairwise.

PyBullet's IK knows nothing of an arm's volume: near its base, pointing down, it happily answers with the hand
folded back through the forearm. Measuring what an arm reaches (embodiment/arm_measure.py) must refuse such
poses, or the ring it measures holds points the arm can only reach through itself. The check runs on a third,
private copy of the arm that has every collision shape (the world's copy drops some for speed,
``ArmSpec.collision_free_links``) and is never stepped.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...arms import ArmSpec
from .arms import ARM, arm_urdf, load_arm
from .bullet import Bullet

OVERLAP = 0.001
"""How far (m) two links' shapes must overlap to count: less is Bullet's contact margin and mesh rounding."""


class SelfCollision:
    """The arm with all its collision shapes; :meth:`overlap` tells whether joints put two of its links into each
    other. Pairs joined by a joint touch by construction and are not checked, nor pairs already overlapping at the
    arm's home (meshes that overlap where they are mounted, a gripper's linkage), nor the gripper's links among
    themselves (the fingers are held closed, against each other)."""

    def __init__(self, spec: ArmSpec, base_xyz):
        self.spec, self.sim = spec, Bullet()
        try:
            load_arm(self.sim, arm_urdf(replace(spec, collision_free_links=()), visuals=False), tuple(base_xyz))
            info = self.sim.joints(ARM)
            self.sim.reset_joints(ARM, spec.finger_joints, spec.finger_closed)
            links = [j for j in (-1, *(j.index for j in info)) if self.sim.has_collision(ARM, j)]
            parent = {j.index: j.parent for j in info}
            gripper = set(spec.finger_joints) | set(spec.fingertip_links)
            pairs = [(a, b) for i, a in enumerate(links) for b in links[i + 1:]
                     if parent.get(b) != a and parent.get(a) != b and not (a in gripper and b in gripper)]
            self.set(np.asarray(spec.home, float))
            self.pairs = [(a, b) for a, b in pairs if not self._overlapping(a, b)]
        except BaseException:
            self.sim.close()
            raise

    def set(self, q: np.ndarray) -> None:
        self.sim.reset_joints(ARM, self.spec.arm_joints, q)

    def overlap(self, q: np.ndarray) -> tuple[str, str] | None:
        """The names of the first two links the arm's joints ``q`` put into each other (more than :data:`OVERLAP`),
        or None."""
        self.set(np.asarray(q, float))
        for a, b in self.pairs:
            if self._overlapping(a, b):
                return self._name(a), self._name(b)
        return None

    def _overlapping(self, a: int, b: int) -> bool:
        d = self.sim.link_distance(ARM, a, b, 0.0)
        return d is not None and d < -OVERLAP

    def _name(self, link: int) -> str:
        return "base" if link < 0 else self.sim.link_name(ARM, link)

    def close(self) -> None:
        self.sim.close()
