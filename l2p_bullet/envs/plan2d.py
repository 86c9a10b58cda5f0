"""``l2p_bullet/Plan2D-v0``: the 2-D planning problem as a Gymnasium environment.

One episode = one sentence "move A <action> B" on one scene. The agent moves the mover block by
(dx, dy, dyaw) per step, in block units in the scene's frame; the reward is the increase of the
action's learned progress over the whole motion so far (the numpy model of the action's bundle: no
torch at step time), exactly what the project's planners maximise. The episode is

- terminated when the progress reaches the action's threshold (its bundle's ``[policy] threshold``, else
  0.9), or when a move is illegal: it collides with another block (inflated by the gripper margin) or
  leaves the arm's workspace (the block then stays where it was; ``info["illegal"]`` says which);
- truncated after ``max_steps`` moves (12, the planners' ``max_moves``).

An action is 3 numbers (any array shape holding 3) clipped to the action space (+-inf to its bounds);
NaN, another count or a non-number is a one-line :class:`~.checks.EnvError`. ``step`` with no episode
running (before the first ``reset``, after a failed one, or once the episode has terminated or been
truncated) raises :class:`~.checks.EnvResetNeeded`, Gymnasium's ``ResetNeeded``: Gymnasium leaves a step
after the end undefined, and here it would go on scoring a motion that has already been judged (or, in
Arm-v0, move an arm whose last move failed), so a loop that forgets to reset fails at once instead.

Observation (float32, 7): mover x, y (block units from the workspace centre), yaw; anchor x, y, yaw;
the progress so far. Scenes come from ``core.scene.random_scene`` seeded by the environment's RNG, so
``reset(seed=s)`` is deterministic; ``reset(options={"scene": scene_or_dict})`` poses a given one.
Positions in the observation are clipped to +-``POSITION_BOUND`` blocks (see there).
"""

from __future__ import annotations

import math
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from ..core.geometry import wrap_angle
from ..core.scene import Scene, random_scene
from ..planning import THRESHOLD
from ..planning.problem import FRAME_STEP, MAX_TURN
from ..planning.world2d import World2D, segment_frames
from ..plugins import registry
from .checks import EnvResetNeeded, check_action, check_args, check_names, check_options

POSITION_BOUND = 16.0
"""Block units: the start disk's radius (0.25 m) over the smallest block (0.02 m) is 12.5. The planning disk is
0.35 m (17.5 smallest blocks): an observation beyond 16 is clipped, so the observation space stays what agents
were trained on.
So with blocks under 0.35 / 16 = 0.022 m a mover near the disk's edge reads as at 16 (``pose`` has the truth);
the episode does not end there, as the workspace test, not the observation, decides what is legal."""


class Plan2DEnv(gym.Env):
    """See the module docstring. ``action`` names an installed action (built-in or plugin); it is
    required, so that no action is chosen without a word."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 4}

    def __init__(self, action: str | None = None, render_mode: str | None = None, max_steps: int = 12,
                 max_move: float = 2.0, threshold: float | None = None, size: float = 0.05,
                 illegal_penalty: float = 0.0):
        if action is None:  # no silent default: a policy trained on "around" by omission is a wasted afternoon
            from ..errors import PluginError
            from . import ENVS

            env_id = next((k for k, v in ENVS.items() if v.endswith(f":{type(self).__name__}")), "l2p_bullet/Plan2D-v0")
            names = ", ".join(p.name for p in registry.discover() if p.ok)
            raise PluginError(f'say which action the environment is for: gym.make("{env_id}", action="around") '
                              f"(installed: {names})")
        args = check_args(render_mode=render_mode, render_modes=self.metadata["render_modes"], max_steps=max_steps,
                          max_move=max_move, threshold=threshold, size=size, illegal_penalty=illegal_penalty)
        self.bundle = registry.load(action)
        self.action_name = self.bundle.name
        self.model = self.bundle.progress_model()
        settings = self.bundle.manifest.get("policy", {})
        threshold = args["threshold"]
        self.threshold = float(threshold if threshold is not None else settings.get("threshold", THRESHOLD))
        self.render_mode, self.max_steps, self.max_move = render_mode, args["max_steps"], args["max_move"]
        self.size, self.illegal_penalty = args["size"], args["illegal_penalty"]
        b = POSITION_BOUND
        self.state_space = spaces.Box(np.array([-b, -b, -math.pi, -b, -b, -math.pi, 0.0], np.float32),
                                      np.array([b, b, math.pi, b, b, math.pi, 1.0], np.float32), dtype=np.float32)
        self.observation_space = self.state_space  # Arm-v0's image modes wrap it in a Dict
        m = self.max_move
        self.action_space = spaces.Box(np.array([-m, -m, -MAX_TURN], np.float32),
                                       np.array([m, m, MAX_TURN], np.float32), dtype=np.float32)
        self.scene: Scene | None = None
        self.mover, self.anchor = "A", "B"
        self._no_episode: str | None = "no episode has started"  # why step() must wait for a reset; None: it may go

    # --- the episode ---------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        """Start an episode. The options are checked before anything changes (a bad one used to leave the old
        pose in the new scene); whatever fails, the old episode is over: step() then asks for a reset."""
        self._no_episode = "the last reset() failed"
        scene, mover, anchor = check_options(options)  # nothing else has changed yet, the RNG included
        super().reset(seed=seed)
        if scene is None:
            scene = random_scene(int(self.np_random.integers(0, 2**31 - 1)), self.size)
            check_names(scene, mover, anchor)
        world2d = World2D(scene, mover)
        self.scene, self.mover, self.anchor, self.world2d = scene, mover, anchor, world2d
        self.block = self.world2d.size
        self.anchor_pose = self.scene.get(self.anchor).pose
        self.pose = self.scene.get(self.mover).pose.copy()
        self.waypoints = [self.pose.copy()]
        self.frames = self.pose[None].copy()
        self.steps = 0
        self._start_episode()
        self.progress = self._score()
        self._no_episode = None
        return self._obs(), self._info()

    def step(self, action):
        if self._no_episode is not None:
            raise EnvResetNeeded(f"Cannot call env.step() before calling env.reset(): {self._no_episode}")
        a = check_action(action, self.action_space)
        target = self.pose + np.array([a[0] * self.block, a[1] * self.block, a[2]])
        self.steps += 1
        illegal = self._illegal(target)
        reward = -self.illegal_penalty if illegal else 0.0
        info_extra: dict[str, Any] = {}
        if not illegal:
            reached, info_extra = self._move(target)
            if reached is None:  # the arm could not do it (Arm-v0): the episode ends there
                illegal = info_extra.get("illegal", "arm")
                reward = -self.illegal_penalty
            else:
                seg = segment_frames(self.pose, reached, FRAME_STEP * self.block)
                self.frames = np.vstack([self.frames, seg])
                self.pose = reached
                self.waypoints.append(reached.copy())
                before, self.progress = self.progress, self._score()
                reward = self.progress - before
        terminated = bool(illegal) or self.progress >= self.threshold
        truncated = not terminated and self.steps >= self.max_steps
        if terminated or truncated:
            self._no_episode = "the episode has ended (terminated or truncated)"
        info = self._info() | info_extra | ({"illegal": illegal} if illegal else {})
        return self._obs(), float(reward), terminated, truncated, info

    # --- hooks Arm-v0 overrides ----------------------------------------------------------------
    def _start_episode(self) -> None:
        """Called by reset once the scene is set (Arm-v0 builds its world here)."""

    def _move(self, target: np.ndarray) -> tuple[np.ndarray | None, dict]:
        """Carry out a legal move; return where the mover ended (None: it could not) and extra info."""
        return target, {}

    def _anchor_now(self) -> np.ndarray:
        return self.anchor_pose

    # --- helpers -------------------------------------------------------------------------------
    def _illegal(self, target: np.ndarray) -> str | None:
        if not bool(self.world2d.workspace.segments_inside(self.pose[:2], target[None, :2])[0]):
            return "workspace"  # the end outside, or (an arm's reach ring) the move through the ring's hole
        if not bool(self.world2d.moves_free(self.pose, target[None])[0]):
            return "collision"
        return None

    def _score(self) -> float:
        return float(np.clip(self.model.final(self.frames, self._anchor_now(), self.block), 0.0, 1.0))

    def _obs(self) -> np.ndarray:
        c, s = np.array(self.scene.workspace.center), self.block
        m, an = self.pose, self._anchor_now()
        obs = [(m[0] - c[0]) / s, (m[1] - c[1]) / s, wrap_angle(m[2]), (an[0] - c[0]) / s, (an[1] - c[1]) / s,
               wrap_angle(an[2]), self.progress]
        box = self.state_space
        return np.clip(np.array(obs, np.float32), box.low, box.high)

    def _info(self) -> dict[str, Any]:
        return {"progress": self.progress, "steps": self.steps, "action": self.action_name}

    @property
    def path(self) -> np.ndarray:
        """The mover's waypoints so far (n,3), scene frame, metres: a path ``execute_path`` can perform."""
        return np.array(self.waypoints)

    def render(self):
        if self.render_mode != "rgb_array" or self.scene is None:
            return None
        return _draw(self.scene, self.mover, self.path, self.pose)


def _draw(scene: Scene, mover: str, path: np.ndarray, pose: np.ndarray, px: int = 240) -> np.ndarray:
    """A top view of the workspace: blocks, the mover where it is now and its path so far (H, W, 3) uint8."""
    # lazy: matplotlib takes about a second to import; only when a figure is drawn
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure


    fig = Figure(figsize=(px / 80, px / 80), dpi=80)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    r = scene.workspace.radius
    if scene.workspace.ring is None:
        ax.add_patch(matplotlib.patches.Circle(scene.workspace.center, r, fill=False, color="0.6"))
    for arc in scene.workspace.outline() if scene.workspace.ring is not None else []:
        ax.plot(arc[:, 0], arc[:, 1], color="0.6", lw=1)
    for o in scene.objects:
        fp = o.footprint(pose if o.name == mover else None)
        ax.fill(fp[:, 0], fp[:, 1], color=o.rgba[:3])
    ax.plot(path[:, 0], path[:, 1], "k.-", lw=1, ms=3)
    ax.set_xlim(-r * 1.05, r * 1.05)
    ax.set_ylim(-r * 1.05, r * 1.05)
    ax.set_aspect("equal")
    ax.axis("off")
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())[:, :, :3].copy()
