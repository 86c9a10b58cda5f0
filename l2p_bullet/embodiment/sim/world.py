"""The simulated world: one simulator (DIRECT) holding the table, the scene's blocks and an arm.

Nothing is global: every :class:`World` owns its own :class:`~.bullet.Bullet`, so two worlds (or two
tests) never see each other's bodies. The world frame is the scene frame lifted to 3-D: z = 0 is the
table top, so a block's centre height above the table is simply its z.

A world can be reused for run after run (a batch evaluator keeps one per worker process):
:meth:`World.reset` puts it in exactly the state of a new ``World(scene)``, so what a run records does
not depend on what the world did before.
"""

from __future__ import annotations

import json
import math
from collections import OrderedDict
from importlib import resources
from pathlib import Path

import numpy as np

from ...arms import PANDA, ArmSpec
from ...core.scene import Scene
from ...core.shapes import BLOCK_FRICTION
from ...errors import SceneError
from . import decompose
from .bullet import Bullet
from .robot import ARM, Robot

PHYSICS_HZ = 240.0
BLOCK_URDF_SIZE = 0.05  # the side of urdf/block.urdf; other sizes load it with globalScaling
TABLE = "<table>"  # the table's body name (blocks go by their scene names, the arm is robot.ARM)


def urdf_path(name: str) -> str:
    """Absolute path of a URDF the project ships (inside the installed package)."""
    return str(Path(str(resources.files("l2p_bullet") / "urdf" / name)))


def _visual(o, g) -> tuple:
    """How the simulator draws a non-cube object (``Bullet.load_convex``): a box or a cylinder as itself, a
    mesh from its file (an OBJ or STL as given; a GLB, which PyBullet does not read, as an OBJ of its
    triangles written once to the cache folder)."""
    if o.shape == "box":
        return ("box", tuple(d / 2 for d in o.dims))
    if o.shape == "cylinder":
        return ("cylinder", o.radius, o.height_m)
    path = Path(o.mesh)
    if path.suffix.lower() == ".glb":
        return ("mesh", _obj_copy(g), 1.0, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    return ("mesh", path, o.scale, g.file_origin, o.rpy)


def _parts(o, g) -> tuple | None:
    """A mesh's convex decomposition placed as its drawing is (``Bullet.load_convex``'s ``parts``); None for a
    box or a cylinder (their hull is their shape) and where the decomposition finds no parts."""
    if o.shape != "mesh":
        return None
    path = decompose.parts_file(o.mesh)
    return None if path is None else ("mesh", path, o.scale, g.file_origin, o.rpy)


def _placed_parts(parts: tuple) -> tuple[np.ndarray, np.ndarray]:
    """The vertices (V,3; body frame) and triangles (T,3 vertex indices) of a decomposition's file, placed as
    ``_parts`` says (each convex part's file lists its hull's faces)."""
    from ...core.shapes import _rotation

    _, path, scale, origin, rpy = parts
    v, f = [], []
    with open(path) as fh:
        for line in fh:
            if line.startswith("v "):
                v.append([float(c) for c in line.split()[1:4]])
            elif line.startswith("f "):
                f.append([int(c.split("/")[0]) - 1 for c in line.split()[1:4]])
    v = (np.asarray(v, float) * scale) @ _rotation(tuple(rpy)).T + np.asarray(origin, float)
    return v, np.asarray(f, np.int64).reshape(-1, 3)


def _parts_bottom(parts: tuple) -> float:
    """The lowest point (body frame) of a decomposition placed as ``_parts`` says: a convex part's lowest
    point is one of its vertices (Bullet's bounding box of a turned compound is looser, by millimetres)."""
    return float(_placed_parts(parts)[0][:, 2].min())


def _triangles(o, g, parts: tuple | None) -> np.ndarray:
    """A mesh's collision surface (T,3,3) in the body frame: the triangles of its convex parts placed as
    ``_parts`` says, or, without parts, its own triangles (then a convex mesh: its hull)."""
    if parts is None:
        return np.asarray(g.points, float)[np.asarray(g.faces, np.int64)]
    v, f = _placed_parts(parts)
    return v[f]


def _tops(tri: np.ndarray, xy: np.ndarray) -> np.ndarray:
    """Where a vertical ray through each point ``xy`` (N,2) first meets the triangles ``tri`` (T,3,3) coming
    down: the highest crossing, nan where none is crossed. Exact, unlike Bullet's ray test, which misses a
    convex hull without collision margin (measured: every ray through a 5 x 7.5 cm box)."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    e1, e2 = b[:, :2] - a[:, :2], c[:, :2] - a[:, :2]
    den = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    # a wall seen edge-on is met by no vertical ray (either winding counts: a file may have them flipped)
    keep = np.abs(den) > 1e-14
    a, b, c, e1, e2, den = a[keep], b[keep], c[keep], e1[keep], e2[keep], den[keep]
    out = np.full(len(xy), np.nan)
    lo, hi = tri[..., :2].reshape(-1, 2).min(axis=0), tri[..., :2].reshape(-1, 2).max(axis=0)
    near = np.flatnonzero(np.all((xy >= lo) & (xy <= hi), axis=1))  # only rays over the object can meet it
    step = max(1, (1 << 20) // max(1, len(a)))
    for s in range(0, len(near), step):
        rays = near[s:s + step]
        q = xy[rays, None, :] - a[None, :, :2]
        u = (q[..., 0] * e2[:, 1] - q[..., 1] * e2[:, 0]) / den
        w = (e1[:, 0] * q[..., 1] - e1[:, 1] * q[..., 0]) / den
        inside = (u >= -1e-9) & (w >= -1e-9) & (u + w <= 1 + 1e-9)
        z = np.where(inside, a[:, 2] + u * (b[:, 2] - a[:, 2]) + w * (c[:, 2] - a[:, 2]), -np.inf)
        top = z.max(axis=1)
        out[rays] = np.where(np.isfinite(top), top, np.nan)
    return out


def _obj_copy(g) -> str:
    """An OBJ file of ``g``'s triangles (body frame) in the user's cache, named by its content."""
    import hashlib
    import os
    import tempfile

    lines = [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in g.points] + [
        f"f {a + 1} {b + 1} {c + 1}" for a, b, c in g.faces
    ]
    text = "\n".join(lines) + "\n"
    folder = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "l2p-bullet" / "meshes"
    folder.mkdir(parents=True, exist_ok=True)
    out = folder / f"{hashlib.sha256(text.encode()).hexdigest()[:24]}.obj"
    if not out.is_file():
        with tempfile.NamedTemporaryFile("w", dir=folder, suffix=".tmp", delete=False) as f:
            f.write(text)
        os.replace(f.name, out)
    return str(out)


RAY_SPACING = 0.002
"""m between the rays that find where the hand meets a mesh, and the clearance kept above what they find."""
SETTLE_MAX_S = 2.0
"""Longest time (s) the objects may take to come to rest after being set down."""
REST_SPEED, REST_SPIN = 0.002, 0.02
"""At rest: every object slower than this (m/s) and turning slower than this (rad/s)."""
ADOPT_TILT = math.radians(1.0)
"""A mesh that comes to rest tilted more than this lies otherwise than it was set down (it rocked onto a
corner, or fell over and rests on its side): :func:`settled_scene` makes the pose it rests in its own."""


def settle(world: World) -> dict[str, float]:
    """Step ``world``'s objects (the arm not loaded yet: it is away) until every one is at rest, then put each
    back at the scene's ``xy`` and ``yaw`` in the pose it settled into (resting on the table is the same
    anywhere on it): a mesh that rocks onto its feet or slides a little when set down does so before the
    episode, not in its first frames where it would be blamed on the arm. Returns how far (m) each object's
    centre moved while settling; SceneError, naming the object and how far it moved, for one that is still
    moving after :data:`SETTLE_MAX_S`. One that falls over and then rests is at rest: it lies on its side
    (:func:`settled_scene`)."""
    sim, names = world.sim, list(world.sizes)
    start = {n: world.pose(n) for n in names}
    for step in range(round(SETTLE_MAX_S / world.dt)):
        sim.step()
        if step >= 12 and all(sim.is_resting(n, REST_SPEED, REST_SPIN) for n in names):
            break
    moved = {n: float(np.linalg.norm(world.pose(n)[:3] - start[n][:3])) for n in names}
    for n in names:
        if not sim.is_resting(n, REST_SPEED, REST_SPIN):
            raise SceneError(f'object "{n}" does not come to rest on the table: it moved {moved[n] * 1000:.0f} mm in '
                             f"the {SETTLE_MAX_S:g} s after it was set down (it rolls or rocks); turn it (\"rpy\") so "
                             "that it stands")
    for n in names:  # back where the scene put it, in the pose it rests in
        now = world.pose(n)
        turn = sim.quaternion(0.0, 0.0, float(start[n][3] - now[3]))
        pos, orn = sim.base_pose(n)
        _, orn = sim.compose(((0.0, 0.0, 0.0), turn), ((0.0, 0.0, 0.0), orn))
        sim.set_base_pose(n, (start[n][0], start[n][1], pos[2]), orn)
        world.rests[n] = float(pos[2])
    return {n: round(m, 9) for n, m in moved.items()}


SETTLED_KEPT = 8
"""Settled scenes :func:`settled_state` keeps (a process settles each scene once)."""
_settled: OrderedDict[str, dict] = OrderedDict()


def _scene_key(scene: Scene) -> str:
    """What decides how a scene settles: its objects as written, and each mesh file's size and time (a file
    edited in place settles anew)."""
    files = []
    for o in scene.objects:
        if o.shape == "mesh":
            st = Path(o.mesh).stat()
            files.append((str(o.mesh), st.st_size, st.st_mtime_ns))
    return json.dumps([scene.to_dict(), files], sort_keys=True, default=str)


def settled_state(scene: Scene) -> dict[str, tuple]:
    """Each object's settled pose in ``scene``: name -> (position, orientation, centre's height above the
    table, how far (m) it moved while settling), from :func:`settle` in a simulator of the table and the
    objects alone (the arm is away while they settle), done once per scene and process: the feasibility
    check that refuses an object that never rests and the world the run then executes in share one settling,
    and every world of the scene starts from the same poses. SceneError as :func:`settle` raises it."""
    key = _scene_key(scene)
    if key in _settled:
        _settled.move_to_end(key)
        return _settled[key]
    table = World.__new__(World)  # the table and the objects only: no arm, nothing drawn
    table.sim, table.visuals, table.dt, table.robot = Bullet(), False, 1.0 / PHYSICS_HZ, None
    try:
        table.sim.set_physics(table.dt)
        table._place(scene, drawn=False)
        moved = settle(table)
        state = {n: (*table.sim.base_pose(n), table.rests[n], moved[n]) for n in table.sizes}
    finally:
        table.close()
    _settled[key] = state
    while len(_settled) > SETTLED_KEPT:
        _settled.popitem(last=False)
    return state


def settled_scene(scene: Scene) -> Scene:
    """``scene`` with every mesh that comes to rest tilted (more than :data:`ADOPT_TILT`) turned as it rests:
    its ``rpy`` the turn it settled into, so that its footprint, height, centre's height and grasp, and every
    world loaded from the returned scene, are those of how it lies, not of how the scene set it down (a long
    object stood on its end lies on its side). The same ``scene`` where nothing tilts; SceneError as
    :func:`settled_state` raises it. The returned scene's settled state is the same settling's, so it is
    neither settled again nor different."""
    from dataclasses import replace

    from ...core.shapes import _rotation

    if not any(o.shape == "mesh" for o in scene.objects):
        return scene
    state = settled_state(scene)
    objects, level = [], {}
    for o in scene.objects:
        pos, orn, rest, moved = state[o.name]
        m = _matrix(orn)
        if o.shape != "mesh" or math.acos(min(1.0, abs(m[2, 2]))) <= ADOPT_TILT:
            objects.append(o)
            continue
        turn = _rotation((0.0, 0.0, -o.yaw)) @ m  # how it rests, less the scene's own yaw
        r = turn @ _rotation(o.rpy)
        rpy = (math.atan2(r[2, 1], r[2, 2]), -math.asin(max(-1.0, min(1.0, r[2, 0]))), math.atan2(r[1, 0], r[0, 0]))
        turned = replace(o, rpy=tuple(float(v) for v in rpy))
        objects.append(replace(turned, size=turned.geometry.size))
        half = o.yaw / 2
        level[o.name] = (pos, (0.0, 0.0, math.sin(half), math.cos(half)), rest, moved)  # its body frame level now
    if not level:
        return scene
    out = replace(scene, objects=objects).validate()
    _settled[_scene_key(out)] = {n: level.get(n, s) for n, s in state.items()}
    while len(_settled) > SETTLED_KEPT:
        _settled.popitem(last=False)
    return out


def _matrix(orn) -> np.ndarray:
    """The rotation matrix of quaternion ``orn`` (x, y, z, w)."""
    x, y, z, w = (float(c) for c in orn)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


class World:
    """Table + blocks + arm in one DIRECT simulator. Close it (or use ``with``) when done.

    ``visuals=False`` loads the arm without its visual meshes (for runs that render nothing).
    ``egl=True`` loads PyBullet's EGL renderer plugin first: bodies loaded before it never reach it
    (their images come out empty).
    """

    def __init__(self, scene: Scene, arm: ArmSpec = PANDA, visuals: bool = True, egl: bool = False):
        self.sim = Bullet()
        self.visuals = visuals
        self.dt = 1.0 / PHYSICS_HZ
        self.robot: Robot | None = None
        try:
            self.sim.set_physics(self.dt)
            if egl:
                self.sim.load_egl()
            self.robot = Robot(self.sim, arm, base_xyz=arm.mount, visuals=visuals)
            self._load(scene)
        except BaseException:
            self.close()
            raise

    def _load(self, scene: Scene) -> None:
        """Table, then the blocks in scene order (a mesh scene's in the poses they settle into:
        :func:`settled_state`), then the arm at home: the same order every time, so the physics engine's
        internal order (which decides the last bits of a result) is the same too."""
        self._place(scene)
        self.settled: dict[str, float] = {}  # how far each object moved while settling (mesh scenes)
        if any(o.shape == "mesh" for o in scene.objects):
            for n, (pos, orn, rest, moved) in settled_state(scene).items():
                self.sim.set_base_pose(n, pos, orn)
                self.rests[n] = rest
                self.settled[n] = moved
        self.robot.load()

    def _place(self, scene: Scene, drawn: bool = True) -> None:
        """The table and the objects as the scene sets them down (not yet settled); ``drawn`` False gives a
        non-cube object a token drawing instead of its own (nothing is drawn while a scene settles)."""
        reserved = [o.name for o in scene.objects if o.name in (TABLE, ARM)]
        if reserved:
            raise SceneError(f'"{reserved[0]}" is reserved for the simulator; name the block otherwise')
        sim = self.sim
        self.scene = scene  # what the world was loaded with (a film's painters load the same)
        self.steps = 0
        sim.load_urdf(TABLE, urdf_path("table.urdf"), (0.0, 0.0, 0.0), fixed=True)
        self.sizes: dict[str, float] = {}
        self.heights: dict[str, float] = {}  # each object's top above the table, standing
        self.rests: dict[str, float] = {}  # each object's centre (of mass) above the table, standing
        self.surfaces: dict[str, np.ndarray] = {}  # a mesh's collision triangles, body frame (fingertip_height)
        for o in scene.objects:
            orn = sim.quaternion(0.0, 0.0, o.yaw)
            if o.shape == "cube":
                sim.load_urdf(o.name, urdf_path("block.urdf"), (o.xy[0], o.xy[1], o.size / 2), orn,
                              scale=o.size / BLOCK_URDF_SIZE)
                rest = o.size / 2
            else:  # its convex hull (a mesh: its convex parts), its centre of mass at the body's origin
                g = o.geometry
                rest = g.rest
                parts = _parts(o, g)
                sim.load_convex(o.name, g.points, (o.xy[0], o.xy[1], rest), orn,
                                mass=o.mass_kg, visual=_visual(o, g) if drawn else ("box", (1e-3,) * 3), parts=parts)
                if o.shape == "mesh":
                    self.surfaces[o.name] = _triangles(o, g, parts)
                if parts is not None:  # the parts' bottom, not the mesh's lowest vertex, stands on the table
                    rest = -_parts_bottom(parts)
                    sim.set_base_pose(o.name, (o.xy[0], o.xy[1], rest), orn)
                sim.set_dynamics(o.name, friction=BLOCK_FRICTION)
            sim.set_dynamics(o.name, mass=o.mass, friction=o.friction)
            sim.set_color(o.name, o.rgba)
            self.sizes[o.name] = o.size
            self.heights[o.name] = o.height
            self.rests[o.name] = rest

    def reset(self, scene: Scene) -> None:
        """Start over with ``scene``: old blocks and any grasp gone, the new blocks in place, the arm at
        home, the step counter at zero. Afterwards the world simulates exactly like ``World(scene)`` made
        with the same arm, visuals and renderer (what a run records is byte-identical)."""
        self.sim.reset()
        self._load(scene)

    # --- state -----------------------------------------------------------------------------
    def pose(self, name: str) -> np.ndarray:
        """[x, y, z, yaw] of a block (z: its centre above the table top)."""
        pos, orn = self.sim.base_pose(name)
        x, y, z, w = orn
        yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
        return np.array([pos[0], pos[1], pos[2], yaw])

    def tilt(self, name: str) -> float:
        """Angle (radians) between the block's up axis and the world's: 0 when it sits flat."""
        _, orn = self.sim.base_pose(name)
        m = self.sim.rotation_matrix(orn)
        # m is row-major: the world z components of the block's three axes are m[6], m[7], m[8];
        # a cube may rest on any face, so take the axis closest to vertical.
        return math.acos(min(1.0, max(abs(m[6]), abs(m[7]), abs(m[8]))))

    def poses(self) -> dict[str, np.ndarray]:
        """Every block's :meth:`pose`, in scene order."""
        return {name: self.pose(name) for name in self.sizes}

    def fingertip_height(self, name: str, tool_yaw: float) -> float:
        """Where the closed fingertips come to rest when the hand, turned to ``tool_yaw``, is lowered straight
        down over object ``name``'s centre of mass: the lowest height at which no layer of the hand's profile
        (``ArmSpec.hand_profile``: its half extents at each height above the fingertips) is inside the object,
        measured with vertical rays on its collision triangles (:func:`_tops`). A box's, a cylinder's or a
        cube's is its top (their tops are flat); a mesh's may be lower than its highest point, which can lie to one side
        (a duck's head), so the fingers hold its body."""
        top = self.heights[name]
        if self.scene.get(name).shape != "mesh":
            return top
        x, y = self.pose(name)[:2]
        c, s = math.cos(tool_yaw), math.sin(tool_yaw)
        pts, depth = [], []
        for d, hx, hy in self.robot.spec.hand_profile or ((0.0, 0.01, 0.01),):
            if d > top:
                break
            # rays RAY_SPACING apart at most: a thin wall (a tray's, a mug's) between two would be missed
            gx, gy = (a.ravel() for a in np.meshgrid(*(np.linspace(-h, h, 1 + math.ceil(2 * h / RAY_SPACING))
                                                       for h in (hx, hy))))
            pts.append(np.column_stack([x + c * gx - s * gy, y + s * gx + c * gy]))
            depth.append(np.full(len(gx), d))
        pos, orn = self.sim.base_pose(name)
        tri = self.surfaces[name] @ np.asarray(self.sim.rotation_matrix(orn), float).reshape(3, 3).T + np.asarray(pos)
        hit = _tops(tri, np.vstack(pts)) - np.concatenate(depth)
        return min(top, float(np.nanmax(hit)) + RAY_SPACING) if np.isfinite(hit).any() else top

    @property
    def time(self) -> float:
        return self.steps * self.dt

    def step(self) -> None:
        self.sim.step()
        self.steps += 1

    def close(self) -> None:
        """Disconnect the simulator and the arm's IK twin (idempotent)."""
        if self.robot is not None:
            self.robot.close()
        self.sim.close()

    def __enter__(self) -> World:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
