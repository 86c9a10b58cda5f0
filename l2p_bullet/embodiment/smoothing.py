"""Time parameterisation of an end-effector path with ruckig: velocity, acceleration and jerk limits.

Ruckig is run on one degree of freedom only: the arc length ``s`` of the exact geometric path (with its
corners already rounded, see :mod:`l2p_bullet.embodiment.motion`), from rest to rest. The timed ``s(t)`` is then
mapped back onto the path, so the end effector never leaves the geometric path (no blending error),
whatever the limits. ruckig's intermediate waypoints (its multi-waypoint input) are never used: the
community build sends such problems to a remote server.

Along a curve the path's own curvature adds an acceleration v^2 / r that a 1-DoF profile cannot see, so
each rest-to-rest chunk's speed limit is lowered to sqrt(a_lat / kappa_max) before planning, and the
result is checked afterwards (:attr:`Timed.max_lateral_acc`, computed with the x-y curvature and the
full path speed, which bounds the x-y speed from above).
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass

import numpy as np

ROT_RADIUS = 0.05
"""Metres of path length one radian of yaw counts as: the yaw turns at most v / ROT_RADIUS rad/s."""


@dataclass(frozen=True)
class Limits:
    """Limits along the path (m/s, m/s^2, m/s^3) and on the curvature's acceleration v^2/r (m/s^2)."""

    velocity: float = 0.1
    acceleration: float = 0.5
    jerk: float = 5.0
    lateral: float = 0.5


@dataclass(frozen=True)
class Pace:
    """How a sentence's manner adverb ("slowly", "gently") changes every motion of its clause: factors on
    the ruckig limits. A gentle or careful motion lowers acceleration and jerk more than speed, so the
    block starts and stops softly; a fast one raises all three within what the arms track (docs/manners.md)."""

    name: str
    velocity: float = 1.0
    acceleration: float = 1.0
    jerk: float = 1.0

    def apply(self, lim: Limits) -> Limits:
        if (self.velocity, self.acceleration, self.jerk) == (1.0, 1.0, 1.0):
            return lim
        return Limits(lim.velocity * self.velocity, lim.acceleration * self.acceleration, lim.jerk * self.jerk,
                      lim.lateral * self.acceleration)


NORMAL_PACE = Pace("normal")
PACES: dict[str, Pace] = {p.name: p for p in (
    Pace("slow", velocity=0.5, acceleration=0.5, jerk=0.5),
    Pace("fast", velocity=1.5, acceleration=1.5, jerk=1.5),
    Pace("gentle", velocity=0.6, acceleration=0.3, jerk=0.3),
    Pace("careful", velocity=0.5, acceleration=0.35, jerk=0.35),
)}
"""The paces a sentence may ask for (language/words.PACES maps the adverbs to these names)."""


def pace(name: str | None) -> Pace:
    """The pace called ``name``; the normal one for None."""
    return NORMAL_PACE if name is None else PACES[name]


@dataclass
class Timed:
    """A chunk sampled at a fixed period: ``poses[k]`` ([x, y, z, yaw]) is the target at ``t[k]``."""

    t: np.ndarray
    poses: np.ndarray
    s: np.ndarray  # arc length reached at each sample
    velocity_limit: float  # the speed limit used (after the curvature cap)
    max_lateral_acc: float  # the largest v^2 * kappa along the timed path

    @property
    def duration(self) -> float:
        return float(self.t[-1]) if len(self.t) else 0.0


def path_parameter(poses: np.ndarray, rot_radius: float = ROT_RADIUS) -> np.ndarray:
    """Cumulative path length of dense poses (M,4): translation plus yaw weighted by ``rot_radius``."""
    d = np.diff(poses, axis=0)
    step = np.sqrt(np.sum(d[:, :3] ** 2, axis=1) + (rot_radius * d[:, 3]) ** 2)
    return np.concatenate([[0.0], np.cumsum(step)])


def curvature(poses: np.ndarray, step: float = 0.002) -> np.ndarray:
    """Curvature (1/m) of the x-y track at each sample, from headings on a uniform re-sampling.

    Re-sampling every ``step`` metres of x-y arc length first keeps second differences of unevenly
    spaced samples (tiny pieces next to long ones) from inventing curvature spikes. A track that does
    not move in x-y (a turn in place) has zero curvature.
    """
    xy = np.asarray(poses, float)[:, :2]
    seg = np.hypot(*np.diff(xy, axis=0).T)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    length = float(arc[-1])
    if length < 2 * step:
        return np.zeros(len(xy))
    u = np.linspace(0.0, length, int(math.ceil(length / step)) + 1)
    h = u[1] - u[0]
    pts = np.column_stack([np.interp(u, arc, xy[:, 0]), np.interp(u, arc, xy[:, 1])])
    d = np.diff(pts, axis=0)
    heading = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    k = np.abs(np.diff(heading)) / h  # at u[1:-1]
    return np.interp(arc, u[1:-1], k)


def ruckig_module():
    """The ruckig extension, imported on first use (only when a path is timed) with Ctrl-C held back.

    A Ctrl-C whose KeyboardInterrupt is raised while the extension's module initialisation runs kills
    the process by SIGSEGV (measured: a rendering perform Ctrl-C'd as its first clause was timed, the
    fault in ``create_module``), so the import is one step a stop cannot split; the stop follows it."""
    module = sys.modules.get("ruckig")
    if module is None:
        from .sim.bullet import ctrl_c_deferred

        with ctrl_c_deferred():
            import ruckig as module
    return module


def _profile(length: float, lim: Limits, v_max: float):
    rk = ruckig_module()
    otg, inp, traj = rk.Ruckig(1), rk.InputParameter(1), rk.Trajectory(1)
    inp.current_position, inp.target_position = [0.0], [float(length)]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [v_max], [lim.acceleration], [lim.jerk]
    try:
        result = otg.calculate(inp, traj)
    except rk.RuckigError:
        # its profile search fails on a length that lies exactly on the border between two profile shapes (1 cm
        # plus one ulp at 0.1 m/s, 0.5 m/s^2, 5 m/s^3: where the acceleration limit is just reached); a length
        # a nanometre longer lies on one side of it, and the sampled path is clipped to the real length
        inp.target_position = [float(length) + max(1e-9, 1e-9 * float(length))]
        result = otg.calculate(inp, traj)
    if result not in (rk.Result.Working, rk.Result.Finished):  # pragma: no cover - ruckig rejects bad input
        raise ValueError(f"ruckig could not time a path of length {length} ({result})")
    return traj


def time_parameterise(poses: np.ndarray, lim: Limits, dt: float) -> Timed:
    """Time a dense rest-to-rest path (M,4) under ``lim``; samples every ``dt``, last sample at the end."""
    poses = np.asarray(poses, float)
    s = path_parameter(poses)
    length = float(s[-1])
    if length < 1e-9:
        return Timed(np.zeros(1), poses[-1:].copy(), np.zeros(1), 0.0, 0.0)
    kappa = curvature(poses)
    k_max = float(kappa.max())
    v_max = lim.velocity if k_max < 1e-9 else min(lim.velocity, math.sqrt(lim.lateral / k_max))
    traj = _profile(length, lim, v_max)
    n = max(1, math.ceil(traj.duration / dt - 1e-9))
    t = np.arange(n + 1) * dt
    t[-1] = min(t[-1], traj.duration)
    st = np.empty(n + 1)
    vt = np.empty(n + 1)
    for k, tk in enumerate(t):
        pos, vel, _ = traj.at_time(float(tk))
        st[k], vt[k] = pos[0], vel[0]
    st = np.clip(st, 0.0, length)
    st[-1] = length
    out = np.stack([np.interp(st, s, poses[:, i]) for i in range(4)], axis=1)
    lateral = float(np.max(vt**2 * np.interp(st, s, kappa)))
    return Timed(t, out, st, v_max, lateral)
