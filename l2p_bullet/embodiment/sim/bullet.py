"""The simulator facade: the one place in the project that calls PyBullet.

Like panda-gym's ``PyBullet`` class, one :class:`Bullet` owns one DIRECT ``BulletClient`` and knows the
bodies loaded into it by name; the world, the robot, the grasp and the camera ask it for poses, joint
states, constraints, IK and images and never see a body id, a client id or the ``pybullet`` module.
What touches the C library can thus be read (and replaced) in one file.

The methods call the ``pybullet`` module's functions with the client id rather than going through
``BulletClient``'s attribute wrapper, which costs a few microseconds per call: the physics step, the joint
command, pose reads and IK run thousands of times an episode (benchmarks/bench_embodiment.py holds the
whole loop within a small factor of bare pybullet).

It runs past the ~400 lines a module is held to, on purpose: the file is the list of everything the project
asks of the C library (some forty thin methods, most a few lines, grouped by what they serve: the simulation,
bodies, joints, constraints, contacts, the camera), plus the guards every call into it needs (the quiet
descriptors, the deferred Ctrl-C). Split by topic, a second module would either call ``pybullet`` too, and the
one place to read (and replace) the simulator would be two, or reach into this class's client and body table.

PyBullet prints "pybullet build time" on import and "argv[0]=" on connect straight to the C-level
file descriptors, and the EGL plugin prints on load, on every frame and on exit. Printed into the middle
of a command's output (or a JSON answer) that breaks things, so those calls run inside
:func:`quiet_stdout`.
"""

from __future__ import annotations

import contextlib
import importlib.util
import os
import signal
import sys
import threading
import weakref
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...errors import ExecutionError
from .urdf_check import check_urdf

Vec3 = Sequence[float]
Quat = Sequence[float]


def _flush_c_stdio() -> None:
    try:
        import ctypes

        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError):  # pragma: no cover - no libc: nothing buffered we can reach
        pass


@contextlib.contextmanager
def quiet_stdout():
    """Send file descriptors 1 and 2 to /dev/null for the duration (Python's streams flushed first).

    Only ever wraps an import, a connect, a plugin or an EGL frame: nothing a user needs to see is
    printed there.
    """
    fds = [1, 2]  # the C library writes to the descriptors, whatever Python's sys.stdout is now
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (AttributeError, ValueError):  # pragma: no cover - a closed or odd stream
            pass
    saved = [os.dup(fd) for fd in fds]
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        for fd in fds:
            os.dup2(devnull, fd)
        yield
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        _flush_c_stdio()  # C stdio buffers what it printed; flush it while it still goes nowhere
        for fd, keep in zip(fds, saved, strict=True):
            os.dup2(keep, fd)
            os.close(keep)
        os.close(devnull)


def _obj_vertices(path: str) -> np.ndarray:
    """The vertices (N,3) of an arm's collision mesh: a Wavefront .obj read directly (the Panda's), any other
    format (.stl: the xArm's and the KUKA's) through trimesh."""
    if not path.lower().endswith(".obj"):
        import trimesh  # lazy: only arms with non-.obj collision meshes need it

        return np.asarray(trimesh.load(path, force="mesh").vertices, float)
    with open(path) as f:
        return np.array([[float(v) for v in line.split()[1:4]] for line in f if line.startswith("v ")])


def vhacd(source: str, target: str, log: str, **params: float) -> None:
    """PyBullet's built-in V-HACD: the convex decomposition of the OBJ ``source`` written to the OBJ ``target``
    (one ``o`` group per convex part, which :meth:`Bullet.load_convex` loads as one compound body). It prints
    its progress on the C-level stdout: silenced."""
    with quiet_stdout():
        import pybullet as pb

        pb.vhacd(source, target, log, **params)


@dataclass(frozen=True)
class JointInfo:
    """What the controller and IK need to know of one joint of a body."""

    index: int
    movable: bool  # not a fixed joint (IK returns one value per movable joint, in joint order)
    lower: float
    upper: float
    max_force: float
    name: str = ""  # the joint's name in the arm's description (the LeRobot export's joint names)
    parent: int = -1  # the index of the link it hangs from (-1: the base)
    link: str = ""  # the name of the link it moves


@contextlib.contextmanager
def ctrl_c_deferred():
    """Hold Ctrl-C (and SIGTERM and SIGHUP, which the command turns into the same stop) back until the block
    is done, then deliver it.

    Why: an interrupt that lands inside ``BulletClient.__init__`` (while ``connect`` runs) leaves a client
    connected but never recorded, and a half-made BulletClient whose ``__del__`` prints a traceback at exit
    ("no attribute '_client'"). Making a client and registering its disconnection is therefore one step that
    a stop cannot split; the stop is raised right after it, by the handler that was there. Only the main
    thread receives Python's signals, and only Python-level handlers can be swapped here: elsewhere, or for a
    signal left to its default action, this does nothing.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    held = {s: h for s in _DEFERRED if callable(h := signal.getsignal(s))}
    caught: list[int] = []
    for s in held:
        signal.signal(s, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        for s, h in held.items():
            signal.signal(s, h)
        if caught:
            held[caught[0]](caught[0], None)


_DEFERRED = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, n))


def _disconnect(client) -> None:
    """Disconnect a BulletClient once and mark it so (its own ``__del__`` then does nothing)."""
    if client._client >= 0:
        with quiet_stdout():  # the EGL plugin says goodbye on the C-level stdout
            client.disconnect()
        client._client = -1


class Bullet:
    """One DIRECT PyBullet client and its bodies, by name. :meth:`close` it (or use ``with``) when done.

    Bodies are loaded with a name (:meth:`load_urdf`) and every other method takes that name. Nothing
    is global: two instances never see each other's bodies.
    """

    def __init__(self) -> None:
        with ctrl_c_deferred():
            with quiet_stdout():
                # lazy: pybullet loads only when a world is made
                import pybullet as pb
                import pybullet_data
                from pybullet_utils import bullet_client

                client = bullet_client.BulletClient(connection_mode=pb.DIRECT)
            self._pb, self._client = pb, client
            self._id: int = client._client
            # disconnect when this object goes, or at interpreter exit while pybullet still works (a
            # BulletClient left to its own __del__ at shutdown prints a TypeError from a half-torn-down module)
            self._finalize = weakref.finalize(self, _disconnect, client)
        self._bodies: dict[str, int] = {}
        self._physics: tuple[float, tuple[float, float, float]] | None = None
        self.egl = False  # whether the EGL renderer plugin is loaded (see load_egl)
        pb.setAdditionalSearchPath(pybullet_data.getDataPath(), physicsClientId=self._id)

    # --- the simulation ----------------------------------------------------------------------
    def set_physics(self, time_step: float, gravity: tuple[float, float, float] = (0.0, 0.0, -9.81)) -> None:
        """Time step (s) and gravity (m/s^2); kept across :meth:`reset`."""
        self._physics = (time_step, gravity)
        self._pb.setGravity(*gravity, physicsClientId=self._id)
        self._pb.setTimeStep(time_step, physicsClientId=self._id)

    def reset(self) -> None:
        """Remove every body and constraint and start the physics afresh (the client stays connected).

        PyBullet rebuilds its dynamics world, so bodies loaded afterwards in the same order as into a new
        client simulate bit for bit like them (a run on a reset world equals a run on a new one).
        """
        self._pb.resetSimulation(physicsClientId=self._id)
        self._bodies.clear()
        if self._physics is not None:
            self.set_physics(*self._physics)

    def load_egl(self) -> None:
        """Load the EGL renderer plugin; ExecutionError where it does not load.

        Load it before any body: bodies loaded earlier never reach it (their images come out empty).
        It is never unloaded explicitly (unloading segfaulted here): disconnecting the client ends it.
        """

        spec = importlib.util.find_spec("eglRenderer")
        with quiet_stdout():
            plugin = (self._pb.loadPlugin(spec.origin, "_eglRendererPlugin", physicsClientId=self._id)
                      if spec and spec.origin else -1)
        if plugin < 0:
            raise ExecutionError("the EGL renderer plugin does not load here; use --renderer tiny")
        self.egl = True

    def step(self) -> None:
        self._pb.stepSimulation(physicsClientId=self._id)

    def close(self) -> None:
        """Disconnect (idempotent)."""
        if self._id >= 0:
            self._finalize()
            self._id = -1
            self._bodies.clear()

    def __enter__(self) -> Bullet:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # --- bodies ------------------------------------------------------------------------------
    def load_urdf(self, name: str, path: str, position: Vec3, orientation: Quat = (0.0, 0.0, 0.0, 1.0), *,
                  fixed: bool = False, scale: float = 1.0) -> None:
        """Load a URDF as body ``name`` (names are unique within a client)."""
        if name in self._bodies:
            raise ValueError(f'a body named "{name}" is already loaded')
        check_urdf(path)  # PyBullet kills the process on two root links or 200,000 chained ones
        self._bodies[name] = self._pb.loadURDF(path, list(position), list(orientation), useFixedBase=fixed,
                                               globalScaling=scale, physicsClientId=self._id)

    def add_visual(self, name: str, shape: str, dims: Sequence[float], rgba: Sequence[float]) -> None:
        """A body ``name`` that is only seen, never touched (no collision shape, no mass): ``shape`` "box"
        (``dims``: half extents) or "cylinder" (``dims``: radius, length)."""
        if name in self._bodies:
            raise ValueError(f'a body named "{name}" is already loaded')
        pb = self._pb
        kw = ({"halfExtents": list(dims)} if shape == "box" else {"radius": dims[0], "length": dims[1]})
        visual = pb.createVisualShape(pb.GEOM_BOX if shape == "box" else pb.GEOM_CYLINDER, rgbaColor=list(rgba),
                                      physicsClientId=self._id, **kw)
        self._bodies[name] = pb.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=-1,
                                                baseVisualShapeIndex=visual, physicsClientId=self._id)

    def load_sdf(self, name: str, path: str, position: Vec3) -> None:
        """Load the one model of an SDF file as body ``name``, its base link's frame at ``position`` (an SDF
        places its model where the file says; a base of zero mass stays fixed there)."""
        if name in self._bodies:
            raise ValueError(f'a body named "{name}" is already loaded')
        pb = self._pb
        bodies = pb.loadSDF(path, physicsClientId=self._id)
        if len(bodies) != 1:
            for b in bodies:
                pb.removeBody(b, physicsClientId=self._id)
            raise ValueError(f"{path} holds {len(bodies)} models; an arm's SDF must hold exactly one")
        b = bodies[0]
        inertial = pb.getDynamicsInfo(b, -1, physicsClientId=self._id)[3]  # the base's pose is its inertial frame's
        pb.resetBasePositionAndOrientation(b, [position[i] + inertial[i] for i in range(3)], [0.0, 0.0, 0.0, 1.0],
                                           physicsClientId=self._id)
        self._bodies[name] = b

    def load_convex(self, name: str, points: np.ndarray, position: Vec3, orientation: Quat, *, mass: float,
                    visual: tuple, parts: tuple | None = None) -> None:
        """A rigid body whose collision shape is the convex hull of ``points`` (N,3, body frame, whose origin
        is the centre of mass), or with ``parts`` ("mesh", OBJ file of convex parts, scale, frame position,
        frame roll-pitch-yaw) the compound of those parts; drawn as ``visual``: ("box", half extents),
        ("cylinder", radius, length) or ("mesh", file, scale, frame position, frame roll-pitch-yaw). The EGL
        renderer draws no mesh given by its vertices (measured: such bodies came out invisible), so a
        drawing is always a primitive or a file."""
        if name in self._bodies:
            raise ValueError(f'a body named "{name}" is already loaded')
        pb, cid = self._pb, self._id
        if parts is None:
            col = pb.createCollisionShape(pb.GEOM_MESH, vertices=np.asarray(points, float).tolist(),
                                          physicsClientId=cid)
        else:
            _, path, scale, pos, rpy = parts
            col = pb.createCollisionShape(pb.GEOM_MESH, fileName=str(path), meshScale=[scale] * 3,
                                          collisionFramePosition=list(pos),
                                          collisionFrameOrientation=pb.getQuaternionFromEuler(list(rpy)),
                                          physicsClientId=cid)
        if visual[0] == "box":
            vis = pb.createVisualShape(pb.GEOM_BOX, halfExtents=list(visual[1]), physicsClientId=cid)
        elif visual[0] == "cylinder":
            vis = pb.createVisualShape(pb.GEOM_CYLINDER, radius=visual[1], length=visual[2], physicsClientId=cid)
        else:
            _, path, scale, pos, rpy = visual
            vis = pb.createVisualShape(pb.GEOM_MESH, fileName=str(path), meshScale=[scale] * 3,
                                       visualFramePosition=list(pos),
                                       visualFrameOrientation=pb.getQuaternionFromEuler(list(rpy)), physicsClientId=cid)
        self._bodies[name] = pb.createMultiBody(baseMass=mass, baseCollisionShapeIndex=col,
                                                baseVisualShapeIndex=vis, basePosition=list(position),
                                                baseOrientation=list(orientation), physicsClientId=cid)
        # a hull's default 1 mm margin grows it outwards: it would stand 1 mm high and the fingertips, sent to
        # its nominal top, would press 2 mm into it (DESIGN.md section 2: 3 mm gave 400 N)
        pb.changeDynamics(self._bodies[name], -1, collisionMargin=0.0, physicsClientId=cid)

    def set_dynamics(self, name: str, *, mass: float | None = None, friction: float | None = None) -> None:
        """The base link's mass (kg) and lateral friction coefficient, where given."""
        kw = {k: v for k, v in (("mass", mass), ("lateralFriction", friction)) if v is not None}
        if kw:
            self._pb.changeDynamics(self._bodies[name], -1, physicsClientId=self._id, **kw)

    def set_color(self, name: str, rgba: Sequence[float]) -> None:
        """Colour of the body's base link."""
        self._pb.changeVisualShape(self._bodies[name], -1, rgbaColor=list(rgba), physicsClientId=self._id)

    def base_pose(self, name: str) -> tuple[Vec3, Quat]:
        """Position and orientation quaternion (x, y, z, w) of the body's base."""
        return self._pb.getBasePositionAndOrientation(self._bodies[name], physicsClientId=self._id)

    def link_pose(self, name: str, link: int) -> tuple[Vec3, Quat]:
        """World pose of the link's URDF frame, forward kinematics computed from the joints now."""
        s = self._pb.getLinkState(self._bodies[name], link, computeForwardKinematics=True,
                                  physicsClientId=self._id)
        return s[4], s[5]

    def aabb(self, name: str, link: int) -> tuple[Vec3, Vec3]:
        """Lower and upper corner of the link's axis-aligned bounding box (its collision shapes)."""
        return self._pb.getAABB(self._bodies[name], link, physicsClientId=self._id)

    def collision_vertices(self, name: str, link: int) -> np.ndarray:
        """World coordinates (N,3) of the vertices of the link's mesh and box collision shapes, where
        they are now (Bullet collides with their convex hulls, grown by its collision margin)."""
        pb = self._pb
        b = self._bodies[name]
        state = pb.getLinkState(b, link, computeForwardKinematics=True, physicsClientId=self._id)
        com_pos, com_orn = state[0], state[1]  # shape frames are given relative to the link's inertial frame
        out = []
        for shape in pb.getCollisionShapeData(b, link, physicsClientId=self._id):
            geom, dims, filename, pos, orn = shape[2], shape[3], shape[4], shape[5], shape[6]
            if geom == pb.GEOM_MESH and filename in (b"unknown_file", "unknown_file"):
                # a URDF cylinder, which Bullet meshes itself and names no file: the link's box holds it
                lo, hi = self.aabb(name, link)
                corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
                out.append(np.array(corners))
                continue
            if geom == pb.GEOM_MESH:
                local = _obj_vertices(filename.decode() if isinstance(filename, bytes) else filename) * np.asarray(dims)
            elif geom == pb.GEOM_BOX:
                local = (
                    np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
                    * np.asarray(dims)
                    / 2
                )
            else:
                continue
            w_pos, w_orn = pb.multiplyTransforms(com_pos, com_orn, pos, orn)
            rot = np.array(pb.getMatrixFromQuaternion(w_orn)).reshape(3, 3)
            out.append(local @ rot.T + np.asarray(w_pos))
        return np.concatenate(out) if out else np.empty((0, 3))

    # --- joints ------------------------------------------------------------------------------
    def joints(self, name: str) -> list[JointInfo]:
        """Every joint of the body, in index order."""
        b, pb = self._bodies[name], self._pb
        out = []
        for j in range(pb.getNumJoints(b, physicsClientId=self._id)):
            info = pb.getJointInfo(b, j, physicsClientId=self._id)
            out.append(JointInfo(j, info[2] != pb.JOINT_FIXED, info[8], info[9], info[10], info[1].decode(), info[16],
                                 info[12].decode()))
        return out

    def link_name(self, name: str, link: int) -> str:
        """The URDF name of the body's link ``link`` (the child of joint ``link``)."""
        return self._pb.getJointInfo(self._bodies[name], link, physicsClientId=self._id)[12].decode()

    def joint_positions(self, name: str, joints: Sequence[int]) -> np.ndarray:
        states = self._pb.getJointStates(self._bodies[name], list(joints), physicsClientId=self._id)
        return np.array([s[0] for s in states])

    def reset_joints(self, name: str, joints: Sequence[int], positions: Sequence[float]) -> None:
        """Teleport the joints to ``positions``, at rest (no physics; for set-up and the IK twin)."""
        # One multi-joint call (the IK twin makes several per solve); velocities default to zero.
        values = positions.tolist() if isinstance(positions, np.ndarray) else positions  # plain floats: no scalars
        self._pb.resetJointStatesMultiDof(self._bodies[name], joints, [[float(v)] for v in values],
                                          physicsClientId=self._id)

    def control_joints(self, name: str, joints: Sequence[int], targets: Sequence[float], forces: Sequence[float],
                       gains: Sequence[float] | None = None) -> None:
        """Position control: the motors track ``targets`` during the next physics steps.

        ``gains`` None keeps PyBullet's default position gain.
        """
        extra = {} if gains is None else {"positionGains": gains}
        self._pb.setJointMotorControlArray(self._bodies[name], joints, self._pb.POSITION_CONTROL,
                                           targetPositions=targets, forces=forces, physicsClientId=self._id,
                                           **extra)

    def inverse_kinematics(self, name: str, link: int, position: Vec3, orientation: Quat, *, iterations: int,
                           threshold: float, lower: Sequence[float] | None = None,
                           upper: Sequence[float] | None = None, rest: Sequence[float] | None = None) -> tuple:
        """PyBullet's damped least squares, seeded from the body's joints now: one value per movable joint.

        With ``lower``, ``upper`` and ``rest`` (one per movable joint) the null-space variant, pulled
        towards ``rest``.
        """
        extra = {}
        if rest is not None:
            extra = dict(lowerLimits=list(lower), upperLimits=list(upper),
                         jointRanges=[u - lo for lo, u in zip(lower, upper, strict=True)], restPoses=list(rest))
        return self._pb.calculateInverseKinematics(self._bodies[name], link, position, orientation,
                                                   maxNumIterations=iterations, residualThreshold=threshold,
                                                   physicsClientId=self._id, **extra)

    # --- constraints -------------------------------------------------------------------------
    def fix(self, parent: str, parent_link: int, child: str, max_force: float) -> int:
        """Fix body ``child`` to ``parent``'s link at their relative pose now; returns the constraint's id."""
        pb, cid = self._pb, self._id
        link = pb.getLinkState(self._bodies[parent], parent_link, computeForwardKinematics=True,
                               physicsClientId=cid)
        c_pos, c_orn = pb.getBasePositionAndOrientation(self._bodies[child], physicsClientId=cid)
        # PyBullet places a constraint's parent frame relative to the link's centre of mass frame.
        inv_pos, inv_orn = pb.invertTransform(link[0], link[1])
        par_pos, par_orn = pb.multiplyTransforms(inv_pos, inv_orn, c_pos, c_orn)
        uid = pb.createConstraint(self._bodies[parent], parent_link, self._bodies[child], -1, pb.JOINT_FIXED,
                                  [0, 0, 0], parentFramePosition=par_pos, childFramePosition=[0, 0, 0],
                                  parentFrameOrientation=par_orn, childFrameOrientation=[0, 0, 0, 1],
                                  physicsClientId=cid)
        pb.changeConstraint(uid, maxForce=max_force, physicsClientId=cid)
        return uid

    def remove_constraint(self, uid: int) -> None:
        self._pb.removeConstraint(uid, physicsClientId=self._id)

    def constraint_count(self) -> int:
        return self._pb.getNumConstraints(physicsClientId=self._id)

    # --- contacts ----------------------------------------------------------------------------
    def contacts(self, a: str, b: str) -> list[tuple[Vec3, float]]:
        """Where bodies ``a`` and ``b`` touch after the last step: (point on ``b``, normal force in N) each."""
        pts = self._pb.getContactPoints(bodyA=self._bodies[a], bodyB=self._bodies[b], physicsClientId=self._id)
        return [(tuple(p[6]), float(p[9])) for p in pts]

    def has_collision(self, name: str, link: int) -> bool:
        """Whether link ``link`` of body ``name`` (-1: its base) has a collision shape."""
        return bool(self._pb.getCollisionShapeData(self._bodies[name], link, physicsClientId=self._id))

    def link_distance(self, name: str, a: int, b: int, within: float) -> float | None:
        """The signed distance (m; negative: overlapping) between the collision shapes of links ``a`` and ``b`` of
        body ``name`` as they stand now, or None when they are farther apart than ``within``."""
        pts = self._pb.getClosestPoints(bodyA=self._bodies[name], bodyB=self._bodies[name], distance=within,
                                        linkIndexA=a, linkIndexB=b, physicsClientId=self._id)
        return min(float(p[8]) for p in pts) if pts else None

    def is_resting(self, name: str, speed: float, spin: float) -> bool:
        """Whether body ``name`` moves slower than ``speed`` (m/s) and turns slower than ``spin`` (rad/s)."""
        v, w = self._pb.getBaseVelocity(self._bodies[name], physicsClientId=self._id)
        return bool(np.linalg.norm(v) < speed and np.linalg.norm(w) < spin)

    def ray_heights(self, name: str, xy: np.ndarray, z_from: float, z_to: float) -> np.ndarray:
        """Where vertical rays down through the points ``xy`` (N,2) from ``z_from`` to ``z_to`` first meet
        body ``name`` (its collision shapes): the height per ray, nan where another body or nothing is hit."""
        xy = np.asarray(xy, float).reshape(-1, 2)
        if not len(xy):
            return np.empty(0)
        hits = []
        for s in range(0, len(xy), 8192):  # PyBullet takes at most 16,384 rays a batch
            hits += self._pb.rayTestBatch([[x, y, z_from] for x, y in xy[s:s + 8192]],
                                          [[x, y, z_to] for x, y in xy[s:s + 8192]], physicsClientId=self._id)
        b = self._bodies[name]
        return np.array([h[3][2] if h[0] == b else np.nan for h in hits], float)

    # --- camera ------------------------------------------------------------------------------
    def view_matrix(self, eye: Vec3, target: Vec3, up: Vec3) -> tuple[float, ...]:
        """Column-major 4x4 view matrix, as the renderer takes it."""
        return self._pb.computeViewMatrix(eye, target, up, physicsClientId=self._id)

    def projection_matrix(self, fov: float, aspect: float, near: float, far: float) -> tuple[float, ...]:
        """Column-major 4x4 perspective projection (``fov`` vertical, degrees)."""
        return self._pb.computeProjectionMatrixFOV(fov, aspect, near, far, physicsClientId=self._id)

    def camera_image(self, width: int, height: int, view: Sequence[float], projection: Sequence[float],
                     hardware: bool = False, light: Vec3 | None = None, depth: bool = False) -> Any:
        """RGBA pixels, row-major; TinyRenderer (CPU) or, with ``hardware``, the EGL plugin. With ``depth``:
        (pixels, the depth buffer in 0..1, non-linear as OpenGL writes it).

        ``light`` (a direction towards the light) draws the scene lit from there, with shadows; None: no
        shadows, the renderer's default light."""
        pb = self._pb
        renderer = pb.ER_BULLET_HARDWARE_OPENGL if hardware else pb.ER_TINY_RENDERER
        quiet = quiet_stdout() if hardware else contextlib.nullcontext()  # the EGL plugin prints every frame
        lit = {} if light is None else {"shadow": 1, "lightDirection": list(light)}
        with quiet:
            image = pb.getCameraImage(width, height, view, projection, renderer=renderer,
                                      flags=pb.ER_NO_SEGMENTATION_MASK, physicsClientId=self._id,
                                      **({"shadow": 0} | lit))
        return (image[2], image[3]) if depth else image[2]

    def set_base_pose(self, name: str, position: Vec3, orientation: Quat) -> None:
        """Teleport the body's base (no physics: to draw a recorded state)."""
        self._pb.resetBasePositionAndOrientation(self._bodies[name], list(position), list(orientation),
                                                 physicsClientId=self._id)

    def visual_shapes(self, name: str) -> list[dict]:
        """The body's visual shapes: ``link`` (-1 the base), ``geometry`` ("mesh", "box", "sphere",
        "cylinder", "capsule" or "other"), ``dims``, ``file`` (a mesh's path), ``rgba``, and the shape's
        pose relative to the link's centre-of-mass frame (``pos``, ``orn``): what an exporter needs to
        draw the body elsewhere (export/rerun.py)."""
        pb = self._pb
        kinds = {pb.GEOM_MESH: "mesh", pb.GEOM_BOX: "box", pb.GEOM_SPHERE: "sphere",
                 pb.GEOM_CYLINDER: "cylinder", pb.GEOM_CAPSULE: "capsule"}
        out = []
        for s in pb.getVisualShapeData(self._bodies[name], physicsClientId=self._id):
            f = s[4].decode() if isinstance(s[4], bytes) else s[4]
            out.append({"link": s[1], "geometry": kinds.get(s[2], "other"), "dims": list(s[3]), "file": f,
                        "pos": list(s[5]), "orn": list(s[6]), "rgba": list(s[7])})
        return out

    def com_pose(self, name: str, link: int) -> tuple[Vec3, Quat]:
        """World pose of the link's centre-of-mass frame (-1: the base's), where visual shapes are placed."""
        if link < 0:
            pos, orn = self._pb.getBasePositionAndOrientation(self._bodies[name], physicsClientId=self._id)
            return pos, orn
        s = self._pb.getLinkState(self._bodies[name], link, computeForwardKinematics=True, physicsClientId=self._id)
        return s[0], s[1]

    def compose(self, a: tuple[Vec3, Quat], b: tuple[Vec3, Quat]) -> tuple[Vec3, Quat]:
        """The pose ``b`` given in frame ``a``, in the world."""
        return self._pb.multiplyTransforms(a[0], a[1], b[0], b[1])

    # --- rotations (PyBullet's own, so that results match its internals to the last bit) -----------
    def quaternion(self, roll: float, pitch: float, yaw: float) -> Quat:
        """Quaternion (x, y, z, w) of fixed-axis roll, pitch, yaw."""
        return self._pb.getQuaternionFromEuler([roll, pitch, yaw])

    def rotation_matrix(self, orientation: Quat) -> tuple[float, ...]:
        """Row-major 3x3 rotation matrix of a quaternion (x, y, z, w), as 9 numbers."""
        return self._pb.getMatrixFromQuaternion(orientation)
