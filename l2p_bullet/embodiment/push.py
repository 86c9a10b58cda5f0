"""push: the block follows the learned path pushed by the closed fingers, with no grasp and no constraint.

The fingers, closed, make a flat pusher about 4-6 cm wide (across the tool's x axis) and 2-3 cm thick
(along it): the tool's x axis points along the push, so the wide side lies on the block's face opposite the
direction of travel and the block is driven by contact and friction only (PyBullet's contact physics, the
scene's friction). A push is closed loop, at the control rate (60 Hz):

1. observe the block's pose and find how far along the planned path it is (the nearest point, never
   going back);
2. aim at a point :data:`LOOKAHEAD` block sides further along the path (so drift sideways is steered back)
   and put the pusher on the block's far side from it, :data:`PRESS` inside the block's face (the face's
   distance from the centre along that direction is the support of the block's footprint: a cube's square,
   another shape's own outline, so a round or long object is bitten as deep as a cube);
3. move the hand there at most :data:`SPEED`, its yaw turning at most :data:`TURN_RATE`.

When the direction to push turns by more than :data:`FACE_TURN` from the side the hand is on (a sharp
corner of the path, or the block turned away), or the wrist would run out of range, the hand goes round:
up above the block, over to the new side, down, and pushes on. A block that tips over, or escapes the hand
by more than :data:`ESCAPE` sides (a cylinder that rolls away), ends the push and is *reported* in the run's
``grasp.push`` (``tipped`` / ``escaped``), not hidden; a push that runs out of time or of repositions stops
where it is. Every frame records where the hand touches the block (``gripper.contact``).
"""

from __future__ import annotations

import math

import numpy as np

from ..arms import reach
from ..core.geometry import separation
from ..errors import ReachError
from .manners import PUSH_CLEARANCE, PUSH_FACE_TURN, PUSH_GAP, PUSH_LOOKAHEAD, PUSH_SHIFT, PUSH_TIP_Z, push_tip_ceiling
from .push_height import contact_reach, push_height
from .push_path import drop_spurs
from .sim.primitives import APPROACH, DESCEND, HOVER, SETTLE_S
from .sim.robot import ARM

SPEED = 0.05  # m/s: the hand's largest speed while pushing
BIAS_TICKS = 6  # control periods over which the block's motion direction is observed ...
BIAS_MOVE = 0.002  # m: ... when it moved at least this far in them
BIAS_GAIN = 0.1  # per control period: how fast the drift's estimate follows what is observed
BIAS_MAX = math.radians(30.0)  # the largest correction of the push's direction for the drift
SIDE_SPEED = 0.01  # m/s: the hand's largest speed across the push beyond what the push's turn asks
TURN_RATE = 1.5  # rad/s: the pusher's largest turn while pushing
LOOKAHEAD = PUSH_LOOKAHEAD  # block sides ahead along the path
PRESS = 0.008  # m inside the block's face: the push's bite (the arm's position control makes it a force)
TIP_Z = PUSH_TIP_Z  # m: the fingertips' height above the table while pushing (low: the push does not tip the block)
STALL_S = 1.5  # s without 1 mm of progress along the path: the push is stuck (a corner caught): go round
FACE_TURN = PUSH_FACE_TURN  # a turn beyond this from the pushing side changes face (go round)
GAP = PUSH_GAP  # m between the pusher and the block when the hand comes down on a new side
CLEAR = 0.012  # m above the block's top when the hand goes round
STOP = 0.0005  # m from the path's end: done
ESCAPE = 2.0  # block sides between the hand and the block: it got away
MAX_REPOSITIONS = 30
SHIFT = PUSH_SHIFT  # m: how far the pusher may slide along the block's face to keep clear of another object
CLEARANCE = PUSH_CLEARANCE  # m kept between the pusher and every other object
WRIST_MARGIN = 0.25  # rad kept from the wrist's limits
TIME_PER_M = 40.0  # s of pushing allowed per metre of path (plus SLACK_S): then the push stops where it is
SLACK_S = 20.0
DEEPEN = 0.00025  # m per control period a mesh's bite deepens while the hand is at its target and it stays put
DEEPEST = 0.02  # m: the most a mesh's bite deepens beyond PRESS
STILL = 0.00005  # m in a control period: a mesh that moved less than this, the hand at its target, is not pushed


class Pusher:
    """The closed-loop push of one block along one path; :meth:`run` does it and returns what happened."""

    def __init__(self, prims, mover: str, path: np.ndarray):
        self.prims, self.world, self.robot = prims, prims.world, prims.world.robot
        self.mover, self.size = mover, float(prims.world.sizes[mover])
        xy = np.asarray(path, float)[:, :2]
        keep = np.concatenate([[True], np.hypot(*np.diff(xy, axis=0).T) > 1e-9])
        self.xy = drop_spurs(xy[keep], self.size)
        seg = np.hypot(*np.diff(self.xy, axis=0).T) if len(self.xy) > 1 else np.zeros(0)
        self.arc = np.concatenate([[0.0], np.cumsum(seg)])
        self.sigma = 0.0
        ext = reach.hand_extent(self.size / 2, self.robot.spec) or (0.0145, 0.03)
        self.half = float(ext[0])  # the pusher's half thickness along the push
        obj = self.world.scene.get(mover)
        # a mesh's sides may slope where the default height meets them: the height where they stand upright
        surface = self.world.surfaces.get(mover)
        self.tip_z = TIP_Z if surface is None else push_height(surface, self.robot.spec.hand_profile, TIP_Z,
                                                               push_tip_ceiling(obj, self.robot.spec))
        self.z = self.tip_z + self.robot.drop
        self.dt = 1.0 / 60.0
        self.repositions, self.contact_frames, self.ticks = 0, 0, 0
        self.events: list[str] = []
        ext_top = reach.hand_extent(self.size - TIP_Z + 0.005, self.robot.spec) or (self.half, 0.03)
        self.width = float(ext_top[1])  # the pusher's half width across the push, up to above the block
        self.others = [n for n in self.world.sizes if n != mover]
        self.shifted = 0
        # a shape's own outline (its frame) for the face's support; a cube keeps the square's formula
        self.outline = None if obj.shape == "cube" else np.asarray(obj.footprint(np.zeros(3)), float)
        # where the hand's front meets a mesh from each side (its frame)
        self.reach = contact_reach(surface, self.robot.spec.hand_profile, self.tip_z) if surface is not None else None
        # how much deeper than PRESS the hand presses a mesh: its face is estimated (the hand's profile is its
        # collision shapes' bounding boxes, a concave side lets the fingers in), and a hand that reached its
        # target without moving the object (short of it, or touching it too lightly) presses on
        self.deeper = 0.0

    # --- geometry ----------------------------------------------------------------------------------
    def block(self) -> np.ndarray:
        p = self.world.pose(self.mover)
        return np.array([p[0], p[1], p[3]])

    def at(self, s: float) -> np.ndarray:
        """The path's point at arc length ``s``; beyond the end, on along the path's last direction (so
        the aim does not swing round the end point as the block closes on it)."""
        total = float(self.arc[-1])
        if s > total:
            return self.xy[-1] + self.tangent() * (s - total)
        return np.array([np.interp(s, self.arc, self.xy[:, 0]), np.interp(s, self.arc, self.xy[:, 1])])

    def tangent(self) -> np.ndarray:
        """The path's direction at its end (unit), from its last half block."""
        total = float(self.arc[-1])
        back = np.array([np.interp(max(0.0, total - self.size / 2), self.arc, self.xy[:, i]) for i in (0, 1)])
        d = self.xy[-1] - back
        n = float(np.hypot(*d))
        return d / n if n > 1e-9 else np.array([1.0, 0.0])

    def progress(self, b: np.ndarray) -> float:
        """The block's arc length along the path: the nearest point ahead of the last (within a window)."""
        hi = self.sigma + 3 * self.size
        sel = np.flatnonzero((self.arc[1:] >= self.sigma - 1e-9) & (self.arc[:-1] <= hi))
        best, best_d = self.sigma, math.inf
        for i in sel:
            a, c = self.xy[i], self.xy[i + 1]
            ab = c - a
            t = float(np.clip(np.dot(b[:2] - a, ab) / max(float(np.dot(ab, ab)), 1e-18), 0.0, 1.0))
            s = self.arc[i] + t * (self.arc[i + 1] - self.arc[i])
            d = float(np.hypot(*(a + t * ab - b[:2])))
            if s >= self.sigma - 1e-9 and d < best_d - 1e-12:
                best, best_d = s, d
        self.sigma = max(self.sigma, best)
        return self.sigma

    def support(self, b: np.ndarray, phi: float) -> float:
        """The distance from the block's centre to its face opposite direction ``phi`` (the face the hand pushes
        when it pushes along ``phi``): its footprint's support there (for a cube the square's, ``size / 2 (|cos|
        + |sin|)``). The square of a round or long object's size reaches past its real face on some sides (5 mm
        on a 4 cm round object's diagonal), where a bite measured from it is too shallow to move the object: the
        hand presses until the push's time runs out. An outline that is not symmetric about the centre (a camera
        whose body reaches 5.5 cm ahead of its centre of mass and 3.5 cm behind) is measured on the pushed side:
        its far side's support put the fingers 2 cm short of the face they push."""
        a = phi - b[2]
        if self.outline is not None:
            return float(np.max(self.outline @ -np.array([math.cos(a), math.sin(a)])))
        return self.size / 2 * (abs(math.cos(a)) + abs(math.sin(a)))

    def contact_pose(self, b: np.ndarray, phi: float, yaw: float, back: float) -> tuple[np.ndarray, bool]:
        """(tool pose, clear): the pusher's face ``back`` m behind the block's face opposite ``phi``, slid along
        that face (up to :data:`SHIFT`) when its middle would touch another object; ``clear`` is False when no
        place was (the unslid pose is given then). A mesh's face is where the hand's front meets it
        (:func:`contact_reach`), not its outline's support plus a half thickness: the fingers fit into a
        concave side (a gamepad's, between its grips: they stopped inside it, never touching, until the push's
        time ran out), and the hand's body, thicker than the fingers, meets a tall object first (a 12.5 cm
        potion bottle bitten 15 mm deep 5 cm up turned and tipped over)."""
        r = self.support(b, phi) + self.half
        if self.reach is not None and len(self.reach[0]):  # a mesh: where the hand's front meets it
            angles, reach = self.reach
            a = (phi - b[2] + math.pi) % (2 * math.pi)  # from the object's centre towards the hand
            r = float(np.interp(a, np.append(angles, 2 * math.pi), np.append(reach, reach[0])))
        r += back
        pose = np.array([b[0] - r * math.cos(phi), b[1] - r * math.sin(phi), self.z, yaw])
        if self.clear(pose[:2], phi):
            return pose, True
        across = np.array([-math.sin(phi), math.cos(phi)])
        for k in range(1, 7):
            for sign in (1.0, -1.0):
                xy = pose[:2] + sign * across * SHIFT * k / 6
                if self.clear(xy, phi):
                    self.shifted += 1
                    return np.array([xy[0], xy[1], self.z, yaw]), True
        return pose, False

    def come_down(self, b: np.ndarray, phi: float) -> tuple[np.ndarray, bool]:
        """(tool pose, clear): where the hand comes down to push along ``phi``: :data:`GAP` behind the block's face,
        or nearer it (down to a quarter of that) where another object leaves no room for the gap. The planner keeps
        room behind a pushed block for the fingers and the gap together, and the block, pushed a few millimetres
        aside on the way, can leave the gap short between it and a block it was pushed along (measured: a study start
        touching the anchor, pushed along it and then away, stopped "blocked" at the turn); the fingers come down
        straight, so a smaller gap still clears the block."""
        pose, clear = self.contact_pose(b, phi, 0.0, GAP)
        for back in (GAP / 2, GAP / 4):
            if clear:
                break
            nearer, clear = self.contact_pose(b, phi, 0.0, back)
            pose = nearer if clear else pose
        return pose, clear

    def clear(self, xy: np.ndarray, phi: float) -> bool:
        """Whether the pusher (a rectangle: ``half`` along ``phi``, ``width`` across) centred at ``xy`` keeps
        :data:`CLEARANCE` from every other object's footprint where it is now."""
        if not self.others:
            return True
        c, s = math.cos(phi), math.sin(phi)
        hx, hy = self.half + CLEARANCE, self.width + CLEARANCE
        rect = np.array([[xy[0] + c * dx - s * dy, xy[1] + s * dx + c * dy]
                         for dx, dy in ((hx, hy), (-hx, hy), (-hx, -hy), (hx, -hy))])
        for name in self.others:
            p = self.world.pose(name)
            foot = self.world.scene.get(name).footprint(np.array([p[0], p[1], p[3]]))  # its own outline
            if float(separation(rect[None], foot)[0]) < 0.0:
                return False
        return True

    def yaw_for(self, phi: float, near: float, pos: np.ndarray, margin: float = WRIST_MARGIN) -> float:
        """The tool yaw pushing along ``phi`` (the pusher is symmetric: phi + k pi) nearest ``near`` whose
        wrist stays ``margin`` inside its range, else the one most inside it. While pushing the loop asks
        with half the margin the hand comes down with (hysteresis): a yaw chosen at the edge of the full
        margin, a few mm from where the push then goes, would otherwise send the hand round and back for
        ever (measured: random_scene(5001) "around", 23 times round at one spot until the time ran out)."""
        spec = self.robot.spec
        cands = [phi + k * math.pi for k in range(-6, 7)]
        base = tuple(self.robot.base_xyz[:2])

        def wrist(y: float) -> float:
            return float(reach.wrist_values(pos[:2], np.array([y]), base)[0]) - math.pi / 4 + spec.wrist_offset

        ok = [y for y in cands if abs(wrist(y)) <= spec.wrist_limit - margin]
        if ok:
            return min(ok, key=lambda y: abs(y - near))
        return min(cands, key=lambda y: abs(wrist(y)))

    # --- motion ------------------------------------------------------------------------------------
    def tick(self, pose: np.ndarray) -> None:
        """One control period towards ``pose``: IK, then the physics steps, recording the contact."""
        prims = self.prims
        prims._period(prims.solve(pose[None])[0], on_step=self._touch)
        self.contact_frames += prims.recorder.contact is not None
        prims.pose = pose.copy()
        self.ticks += 1

    def _touch(self) -> None:
        """After a physics step: where the hand touches the block (the mean contact point), for the recorder."""
        pts = self.world.sim.contacts(ARM, self.mover)
        self.prims.recorder.contact = list(np.mean([p for p, _ in pts], axis=0)) if pts else None

    def limited(self, b: np.ndarray, target: np.ndarray, side: float, dside: float) -> np.ndarray:
        """``target`` as far as the hand gets in one control period: at most :data:`SPEED` along the push
        (``side``), and across it :data:`SIDE_SPEED` plus what the side's turn this period (``dside``) moves
        the pusher round the block. The target is pressed only :data:`PRESS` into the block's face, so
        catching up with a block that drifted a few mm aside made up a third of each step: the hand moved
        up to 34 degrees off the push and its friction dragged the block further aside (measured:
        random_scene(5010) "next to", the block 10 mm off a straight path with the hand pointing 20 degrees
        back at it). The turn's share keeps the pusher behind the block on a curve ("around")."""
        u = np.array([math.cos(side), math.sin(side)])
        n = np.array([-u[1], u[0]])
        step = target[:2] - self.prims.pose[:2]
        speed = SPEED * self.prims.pace.velocity  # "push A slowly past B": the clause's pace
        along = float(np.clip(np.dot(step, u), -speed * self.dt, speed * self.dt))
        lim = SIDE_SPEED * self.dt + float(np.hypot(*(target[:2] - b[:2]))) * dside
        out = target.copy()
        out[:2] = self.prims.pose[:2] + along * u + float(np.clip(np.dot(step, n), -lim, lim)) * n
        return out

    def go_round(self, b: np.ndarray, phi: float) -> bool:
        """Up above the block, over to the side opposite ``phi``, down to pushing height (the hand's
        yaw turns in the air, where the pusher may swap fingers). False, and the hand stays where it is,
        when that side has no room for the hand (it would come down on another object: measured once,
        random_scene(5004) "next to", the anchor thrown 86 cm)."""
        prims = self.prims
        target, clear = self.come_down(b, phi)
        if not clear:  # the path's own direction here, which the planner kept room behind the block for
            phi = self.leg()
            target, clear = self.come_down(b, phi)
        if not clear:
            return False
        top = float(self.world.heights[self.mover]) + CLEAR + self.robot.drop  # over its top, whatever its shape
        up = prims.pose.copy()
        up[2] = max(up[2], top)
        prims.go(up, DESCEND, "push-up")
        target[3] = self.yaw_for(phi, prims.pose[3], target)
        over = target.copy()
        over[2] = top
        prims.go(over, APPROACH, "push-over", short_turn=False)
        prims.go(target, DESCEND, "push-down")
        self.repositions += 1
        self.deeper = 0.0  # another side: its own face
        return True

    def run(self) -> dict:
        prims = self.prims
        end = self.xy[-1]
        total = float(self.arc[-1])
        b = self.block()
        phi = self._aim(b)
        # from the rest pose: above the pushing side, then down beside the block
        start, clear = self.come_down(b, phi)
        start[3] = self.yaw_for(phi, prims.pose[3], start)
        blocked = not clear  # no room to come down (push_refusal says so before anything moves)
        if not blocked:
            above = start.copy()
            above[2] = start[2] + HOVER
            prims.go(above, APPROACH, "approach", short_turn=False)
            prims.go(start, DESCEND, "descend")
        self.repositions = 0
        side = phi
        limit = TIME_PER_M * total / min(1.0, self.prims.pace.velocity) + SLACK_S
        t0 = self.world.time
        stopped = "blocked" if blocked else "end"
        best, best_t = 0.0, self.world.time
        self.bias, self.trail = 0.0, []
        while stopped == "end":
            b = self.block()
            s = self.progress(b)
            to_end = float(np.hypot(*(b[:2] - end)))
            # at the end, or level with it (pushing on would overshoot); only near the end of the path, not where
            # a path that crosses itself passes its end early (random_scene(5010) "around" stopped there)
            if total - s < self.size / 2 and (to_end < STOP or float(np.dot(end - b[:2], self.tangent())) < STOP):
                break
            if s > best + 0.001:
                best, best_t = s, self.world.time
            elif self.world.time - best_t > STALL_S:  # stuck: come at it afresh
                if self.repositions >= MAX_REPOSITIONS:
                    stopped = "repositions"
                    break
                if not self.go_round(b, self._aim(b)):
                    stopped = "blocked"
                    break
                side, best_t = self._aim(b), self.world.time
                self.bias, self.trail = 0.0, []
                continue
            if self.world.tilt(self.mover) > math.radians(20.0):
                stopped = "tipped"
                break
            if float(np.hypot(*(prims.pose[:2] - b[:2]))) > ESCAPE * self.size + self.half + self.size:
                stopped = "escaped"
                break
            if self.world.time - t0 > limit:
                stopped = "time"
                break
            phi = self._aim(b) - self.drift(b, side)
            turn = abs((phi - side + math.pi) % (2 * math.pi) - math.pi)
            want_yaw = self.yaw_for(phi, prims.pose[3], prims.pose, WRIST_MARGIN / 2)
            if turn > FACE_TURN or abs(want_yaw - prims.pose[3]) > math.pi / 2:
                if self.repositions >= MAX_REPOSITIONS:
                    stopped = "repositions"
                    break
                if not self.go_round(b, phi):
                    stopped = "blocked"
                    break
                side, best_t = phi, self.world.time  # the time going round is not a stall
                self.bias, self.trail = 0.0, []
                continue
            dside = float(np.clip((phi - side + math.pi) % (2 * math.pi) - math.pi,
                                  -TURN_RATE * self.dt, TURN_RATE * self.dt))
            side += dside
            target, _ = self.contact_pose(b, side, 0.0, -PRESS - self.deeper)
            target[3] = prims.pose[3] + float(np.clip(want_yaw - prims.pose[3], -TURN_RATE * self.dt,
                                                      TURN_RATE * self.dt))
            step = self.limited(b, target, side, abs(dside))
            self.tick(step)
            if (self.reach is not None and float(np.hypot(*(step[:2] - target[:2]))) < 1e-4
                    and float(np.hypot(*(self.block()[:2] - b[:2]))) < STILL):
                self.deeper = min(self.deeper + DEEPEN, DEEPEST)
        end_frame = len(prims.recorder.frames)
        self.retreat()
        if stopped != "end":
            self.events.append(stopped)
        return {"end_frame": end_frame, "push": {
            "stopped": stopped, "repositions": self.repositions, "control_ticks": self.ticks,
            "shifted_ticks": self.shifted,
            "contact_ticks": self.contact_frames, "tipped": stopped == "tipped", "escaped": stopped == "escaped",
            "pusher_half_thickness_m": round(self.half, 6), "fingertips_z_m": self.tip_z}}

    def drift(self, b: np.ndarray, side: float) -> float:
        """How far (rad, signed, at most :data:`BIAS_MAX`) the block's own motion turns from the direction
        it is pushed in, estimated from its observed track: pushed on a face at an angle, the block slides
        along the pusher rather than going where it is pushed, a bias the look-ahead alone left standing
        (measured: random_scene(5018) "next to", the block drifting 1 mm aside per 8 mm pushed, 11 mm off
        the path at the end). The push aims that much the other way."""
        self.trail.append((b[:2].copy(), side))
        if len(self.trail) > BIAS_TICKS:
            self.trail.pop(0)
        (p0, s0), (p1, _) = self.trail[0], self.trail[-1]
        d = p1 - p0
        if float(np.hypot(*d)) >= BIAS_MOVE:
            err = (math.atan2(d[1], d[0]) - s0 + math.pi) % (2 * math.pi) - math.pi
            self.bias += BIAS_GAIN * (err - self.bias)
        return float(np.clip(self.bias, -BIAS_MAX, BIAS_MAX))

    def leg(self) -> float:
        """The direction of the path's straight leg the block is on (at :attr:`sigma`): the planner's move, behind
        which it kept room for the fingers. The aim (:data:`LOOKAHEAD` ahead of a block that lags the path by a
        few millimetres) turns past it at a corner, towards the object the block was pushed along."""
        i = int(np.clip(np.searchsorted(self.arc, self.sigma + 1e-9, side="right") - 1, 0, len(self.xy) - 2))
        d = self.xy[i + 1] - self.xy[i]
        return math.atan2(d[1], d[0])

    def _aim(self, b: np.ndarray) -> float:
        s = self.sigma
        ahead = self.at(s + LOOKAHEAD * self.size)
        d = ahead - b[:2]
        if float(np.hypot(*d)) < 1e-6:
            d = self.xy[-1] - self.xy[max(0, len(self.xy) - 2)]
        return math.atan2(d[1], d[0])

    def retreat(self) -> None:
        """Back off the block, up, and let the recording show it at rest."""
        prims = self.prims
        prims.recorder.contact = None
        back = prims.pose.copy()
        back[0] -= GAP * math.cos(prims.pose[3])
        back[1] -= GAP * math.sin(prims.pose[3])
        b = self.block()
        if np.hypot(*(back[:2] - b[:2])) < np.hypot(*(prims.pose[:2] - b[:2])):  # the tool's x may point away
            back[0] += 2 * GAP * math.cos(prims.pose[3])
            back[1] += 2 * GAP * math.sin(prims.pose[3])
        prims.go(back, DESCEND, "push-back")
        up = prims.pose.copy()
        up[2] = self.size + CLEAR + self.robot.drop + HOVER
        prims.go(up, DESCEND, "retract")
        prims.hold(SETTLE_S)


def push(prims, mover: str, path: np.ndarray, rest: np.ndarray) -> dict:
    """Push ``mover`` along ``path`` (N,3; its yaw is not controlled: a push turns the block as contact
    makes it), then retreat to ``rest``. Returns the grasp-field summary (``push``: how it went) and the
    first frame after the push (``end_frame``). ReachError when the arm cannot follow."""
    pusher = Pusher(prims, mover, path)
    try:
        info = pusher.run()
    except ReachError:
        raise
    prims.go(rest, APPROACH, "rest", short_turn=False)
    return info
