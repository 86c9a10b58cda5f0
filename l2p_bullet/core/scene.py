"""The scene: blocks on a table, the table itself and the arm's workspace.

Frame (the scene file's frame, DESIGN.md section 4): metres on the table top, origin at the table's
centre, +x pointing away from the robot's base, +y to the robot's left, yaw in radians about +z.

The robot base stands off the table's near edge at ``ROBOT_BASE_XY``: a Panda with its gripper pointing
down reaches grasp points at table height from about 0.27 m to 0.79 m from its base (DESIGN.md, reach note; at every
height up to 0.19 m).
A disk about the table's centre (0.35 m) bounds the
workspace: every block centre, and every point of a planned path, must lie inside it. For an
arm whose reach ring does not hold the disk (every shipped arm's), the
workspace is the disk intersected with that ring, a region with a bite out of its near side:
``core/workspace.py`` (:class:`Workspace`, imported from here) holds its geometry, and
``arms/fit.py: fit_workspace`` sets the ring. Random scenes are drawn in the old 0.25 m disk
(``START_RADIUS``), so the same seeds give the same scenes as before.

A block's footprint is its outline on the table: a cube's is its square, rotated by its yaw, written
down directly (importing trimesh to derive it from a box mesh cost 0.3-0.5 s of every command's start;
tests/core/test_scene.py checks the two agree). A box, a cylinder or a mesh takes its outline, height and
widths from ``core/shapes.py`` (trimesh for meshes only); its ``size`` is the side in blocks that module
defines (the square root of the footprint's area), so the planner's and the features' units stay "block
sides" for every shape.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..errors import SceneError, UnknownObjectError, did_you_mean
from . import colours, shapes
from .colours import COLORS  # the basic colours; a scene file may write a shade of one ("navy")
from .contracts import load_json_file
from .geometry import polygons_overlap
from .shapes import MAX_FRICTION, MAX_MASS
from .shapes import is_number as _is_number
from .workspace import START_RADIUS, Workspace

ROBOT_BASE_XY: tuple[float, float] = (-0.53, 0.0)
"""Where the arm's base stands in the scene frame (off the table's near edge, facing +x)."""

GRIPPER_MARGIN: float = 0.005
"""Clearance (metres) the 2-D planner keeps between the mover's footprint and any other object.

The arm grasps from above with its fingers closed and resting on the block's top (a fixed constraint,
like a suction cup), so nothing of the gripper reaches down beside the block: obstacles are inflated
only by this safety margin, not by the fingers' footprint (DESIGN.md, the finger note)."""

FACE_MARGIN: float = 0.001
"""Clearance (metres) a "closer" may end at where the mover meets the anchor face to face and nothing of the hand
is between them (planning/nearer.py): the held block tracks its plan within a millimetre (DESIGN.md: gain 0.6,
0.7 mm), so two bare faces set down this far apart do not touch. :data:`GRIPPER_MARGIN` would keep a start level
with the anchor 1-1.2 cm away from closing the half of the room the rule asks for."""

MIN_SIZE, MAX_SIZE = 0.02, 0.08
"""Block sides the gripper can hold (metres): the Panda's fingers open to 0.08 m."""


@dataclass(frozen=True)
class Table:
    """A rectangular table top centred at the origin; ``height`` is its top above the floor."""

    half_x: float = 0.4
    half_y: float = 0.4
    height: float = 0.0

    def contains(self, points: np.ndarray) -> bool:
        p = np.asarray(points, dtype=float).reshape(-1, 2)
        return bool(np.all(np.abs(p[:, 0]) <= self.half_x + 1e-9) and np.all(np.abs(p[:, 1]) <= self.half_y + 1e-9))


_UNIT_SQUARE = np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]])
"""A unit cube's outline on the table, counter-clockwise."""


@dataclass(frozen=True)
class SceneObject:
    """One object on the table; ``xy``/``yaw`` its pose (of its reference point, ``core/shapes.py``).

    ``size`` is a cube's side in metres; for any other shape the side in blocks its footprint gives
    (:func:`shaped` computes it). A ``box`` has ``dims``, a ``cylinder`` ``radius`` and ``height``, a
    ``mesh`` the resolved file ``mesh``, ``scale`` and ``rpy``; ``mass`` (kg) and ``friction`` are optional
    for every shape (None: the cube's 0.1 kg and 0.5), and so is ``kind``, what the object is in everyday words,
    which sentences may call it by where its name does not say ("the cow" for Daisy).
    """

    name: str
    color: str
    size: float
    xy: tuple[float, float]
    yaw: float = 0.0
    shape: str = "cube"
    dims: tuple[float, float, float] | None = None
    radius: float | None = None
    height_m: float | None = None  # a cylinder's height as given (``height`` is any shape's)
    mesh: str | None = None
    scale: float = 1.0
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    mass: float | None = None  # kg; None: shapes.BLOCK_MASS
    friction: float | None = None
    kind: str | None = None  # what the object is, in everyday words ("toy cow" for a toy named Daisy)
    shade: str | None = None  # the colour as the scene file writes it, where it is not a basic one ("navy")

    @property
    def rgba(self) -> tuple[float, float, float, float]:
        """What the renderer draws the object in: its shade's own colour, else its basic colour's."""
        return colours.rgba(self.color, self.shade)

    @property
    def mass_kg(self) -> float:
        """The object's mass: its own ``mass``, else a block's (``shapes.BLOCK_MASS``, urdf/block.urdf's) - what
        the simulator spawns and what a carry checks against the arm's payload."""
        return shapes.BLOCK_MASS if self.mass is None else float(self.mass)

    @property
    def pose(self) -> np.ndarray:
        """[x, y, yaw] as an array."""
        return np.array([self.xy[0], self.xy[1], self.yaw], dtype=float)

    @property
    def geometry(self) -> shapes.Geometry:
        """Footprint, height, centre of mass and collision points (a cube's too, for uniform callers)."""
        if self.shape == "cube":
            return shapes.box((self.size, self.size, self.size))
        return shapes.geometry(self.shape, self.dims, self.radius, self.height_m, self.mesh, self.scale, self.rpy)

    @property
    def height(self) -> float:
        """Height of the object's top above the table (metres)."""
        return self.size if self.shape == "cube" else self.geometry.height

    @property
    def rest(self) -> float:
        """Height of the object's reference point (its centre of mass) above the table when it stands on it:
        what trajectory.json's z is measured against (a cube: half its side)."""
        return self.size / 2 if self.shape == "cube" else self.geometry.rest

    @property
    def inradius(self) -> float:
        """Distance from the reference point to the footprint's nearest edge: two objects' centres are never
        nearer than the sum of theirs (a cube: half its side)."""
        return self.size / 2 if self.shape == "cube" else self.geometry.inradius

    def footprint(self, pose: np.ndarray | None = None) -> np.ndarray:
        """The object's outline (K,2) on the table at ``pose`` ([x, y, yaw], default its own)."""
        x, y, yaw = self.pose if pose is None else np.asarray(pose, dtype=float)
        c, s = math.cos(yaw), math.sin(yaw)
        rot = np.array([[c, -s], [s, c]])
        local = _UNIT_SQUARE * self.size if self.shape == "cube" else self.geometry.footprint
        return local @ rot.T + np.array([x, y])

    def moved(self, pose: np.ndarray) -> SceneObject:
        return replace(self, xy=(float(pose[0]), float(pose[1])), yaw=float(pose[2]))


@dataclass
class Scene:
    """Objects on a table with a workspace. Validate with :meth:`validate` (load does it for you)."""

    objects: list[SceneObject]
    table: Table = field(default_factory=Table)
    workspace: Workspace = field(default_factory=Workspace)

    @property
    def names(self) -> list[str]:
        return [o.name for o in self.objects]

    def get(self, name: str) -> SceneObject:
        """The object called ``name``; a clear error with a suggestion otherwise."""
        for o in self.objects:
            if o.name == name:
                return o
        raise UnknownObjectError(
            f'no object named "{name}" in the scene (objects: {", ".join(self.names)}).'
            + did_you_mean(name, self.names)
        )

    def with_pose(self, name: str, pose: np.ndarray) -> Scene:
        self.get(name)
        return Scene([o.moved(pose) if o.name == name else o for o in self.objects], self.table, self.workspace)

    def only(self, names) -> Scene:
        """This scene with only the objects ``names`` (its table and workspace kept): where a description is read
        among a group the sentence named before ("the cube" of the two a clause named)."""
        return Scene([o for o in self.objects if o.name in names], self.table, self.workspace)

    def validate(self) -> Scene:
        """Raise :class:`SceneError` naming the first problem found; return self when all is well."""
        if not self.objects:
            raise SceneError("the scene has no objects")
        seen: set[str] = set()
        for o in self.objects:
            if not o.name or not isinstance(o.name, str):
                raise SceneError("every object needs a non-empty name")
            if o.name in seen:
                raise SceneError(f'two objects are named "{o.name}": names must be unique')
            seen.add(o.name)
            if o.color not in COLORS:
                raise SceneError(
                    f'object "{o.name}": unknown colour "{o.color}" (known: {", ".join(COLORS)}, or a shade of '
                    'one such as "navy", "light blue" or "#1f3a93").' + did_you_mean(o.color, colours.names())
                )
            if o.shade is not None and colours.basic_of(o.shade) != o.color:
                raise SceneError(f'object "{o.name}": the shade "{o.shade}" is not a shade of {o.color}')
            if o.shape == "cube" and not (MIN_SIZE <= o.size <= MAX_SIZE):
                raise SceneError(
                    f'object "{o.name}": size {o.size:.3g} m is outside what the gripper holds '
                    f"({MIN_SIZE}-{MAX_SIZE} m)"
                )
            if o.shape != "cube":
                shapes.check_extents(
                    o.shape, o.dims, o.radius, o.height_m, o.mesh, o.scale, o.rpy, f'object "{o.name}"'
                )
            for key, hi in (("mass", MAX_MASS), ("friction", MAX_FRICTION)):
                v = getattr(o, key)
                if v is not None and not (_is_number(v) and 0.0 < v <= hi):
                    raise SceneError(f'object "{o.name}": "{key}" must be a number above 0 and at most {hi}')
            if not all(math.isfinite(v) for v in (*o.xy, o.yaw)):
                raise SceneError(f'object "{o.name}": pose must be finite numbers')
            if not self.table.contains(o.footprint()):
                raise SceneError(
                    f'object "{o.name}" at ({_m(o.xy[0])}, {_m(o.xy[1])}) is off the table '
                    f"(the table spans +-{self.table.half_x} m in x and +-{self.table.half_y} m in y)"
                )
            if not self.workspace.contains(np.array(o.xy))[0]:
                raise SceneError(
                    f'object "{o.name}" at ({_m(o.xy[0])}, {_m(o.xy[1])}) is outside the arm\'s workspace '
                    f"({self.workspace.describe()})"
                )

        for i, a in enumerate(self.objects):
            for b in self.objects[i + 1 :]:
                if polygons_overlap(a.footprint(), b.footprint()):
                    raise SceneError(f'objects "{a.name}" and "{b.name}" overlap')
        return self

    # --- the scene file (DESIGN.md section 4) -------------------------------------------------
    def to_dict(self) -> dict:
        return {
            "objects": [
                {"name": o.name, "color": o.shade or o.color, "size": o.size, "xy": [o.xy[0], o.xy[1]], "yaw": o.yaw}
                | ({} if o.shape == "cube" else {"shape": o.shape}) | shapes.fields(o)
                | ({"kind": o.kind} if o.kind else {})
                for o in self.objects
            ]
        }

    def digest(self) -> str:
        """sha256 of the scene file's canonical JSON: what plan.json records as ``scene_sha256``."""
        import hashlib
        import json

        return hashlib.sha256(json.dumps(self.to_dict(), sort_keys=True).encode()).hexdigest()

    @classmethod
    def from_dict(cls, data: object, source: str = "scene", base: Path | None = None,
                  mesh_dirs: tuple[Path, ...] = ()) -> Scene:
        """The scene a scene file's JSON describes. ``base``: the file's folder (relative mesh paths are read
        from it and must stay in it); ``mesh_dirs``: other folders whose meshes the user trusts."""
        if not isinstance(data, dict) or "objects" not in data:
            raise SceneError(f'{source}: expected a JSON object with an "objects" list')
        objs = data["objects"]
        if not isinstance(objs, list):
            raise SceneError(f'{source}: "objects" must be a list')
        if len(objs) > MAX_OBJECTS:
            raise SceneError(f"{source}: {len(objs)} objects; a scene holds at most {MAX_OBJECTS}")
        out = []
        for i, raw in enumerate(objs):
            where = f"{source}: object {i}"
            if not isinstance(raw, dict):
                raise SceneError(f"{where} must be a JSON object")
            unknown = [k for k in raw if k not in OBJECT_FIELDS]
            if unknown:  # a misspelt "yaw" would otherwise put the block at yaw 0 without a word
                name = raw.get("name")
                who = f" ({name[:MAX_NAME]})" if isinstance(name, str) else ""
                key = str(unknown[0])[:MAX_NAME]
                raise SceneError(
                    f'{where}{who}: unknown field "{key}" (known: {", ".join(OBJECT_FIELDS)}).'
                    + did_you_mean(key, list(OBJECT_FIELDS))
                )
            for key in (
                ("name", "color", "size", "xy") if raw.get("shape", "cube") == "cube" else ("name", "color", "xy")
            ):
                if key not in raw:
                    raise SceneError(f'{where} is missing the field "{key}"')
            if not isinstance(raw["name"], str) or not 0 < len(raw["name"]) <= MAX_NAME:
                raise SceneError(f'{where}: "name" must be a text of 1 to {MAX_NAME} characters')
            if not isinstance(raw["color"], str) or len(raw["color"]) > MAX_NAME:
                raise SceneError(f'{where} ({raw["name"]}): "color" must be a colour name such as "red"')
            if not isinstance(raw.get("shape", "cube"), str) or len(raw.get("shape", "cube")) > MAX_NAME:
                raise SceneError(f'{where} ({raw["name"]}): "shape" must be a shape name such as "cube"')
            xy = raw["xy"]
            if not (isinstance(xy, list | tuple) and len(xy) == 2 and all(_is_number(v) for v in xy)):
                raise SceneError(f'{where} ({raw["name"]}): "xy" must be two numbers [x, y] in metres')
            if "size" in raw and not _is_number(raw["size"]):
                raise SceneError(f'{where} ({raw["name"]}): "size" must be a number (metres)')
            yaw = raw.get("yaw", 0.0)
            if not _is_number(yaw):
                raise SceneError(f'{where} ({raw["name"]}): "yaw" must be a number (radians)')
            extra = shapes.read_fields(raw, f'{where} ({raw["name"]})', base, mesh_dirs)
            kind = raw.get("kind")
            if kind is not None and not (isinstance(kind, str) and len(kind) <= MAX_NAME and KIND.match(kind)):
                raise SceneError(f'{where} ({raw["name"]}): "kind" must be words of letters saying what the object '
                                 f'is, such as "toy cow" (at most {MAX_NAME} characters)')
            try:
                color, shade = colours.read(raw["color"])
            except ValueError:
                color, shade = " ".join(raw["color"].lower().split()), None  # validate() names it
            obj = SceneObject(
                name=str(raw["name"]),
                color=color,
                shade=shade,
                size=float(raw.get("size", 0.0)),
                xy=(float(xy[0]), float(xy[1])),
                yaw=float(yaw),
                shape=str(raw.get("shape", "cube")),
                kind=kind,
                **extra,
            )
            out.append(obj if obj.shape == "cube" else replace(obj, size=obj.geometry.size))
        return cls(out)


def shaped(name: str, color: str, xy: tuple[float, float], yaw: float = 0.0, *, shape: str = "box",
           **fields) -> SceneObject:
    """A non-cube object from its shape's fields (``dims``, ``radius`` + ``height_m``, ``mesh`` ...), its
    ``size`` computed (the side in blocks, ``core/shapes.py``)."""
    o = SceneObject(name, color, 0.0, (float(xy[0]), float(xy[1])), float(yaw), shape, **fields)
    return replace(o, size=o.geometry.size)


OBJECT_FIELDS = ("name", "color", "size", "xy", "yaw", "shape", "dims", "radius", "height", "mesh", "scale", "rpy",
                 "mass", "friction", "kind")
"""Every field a scene file's object may have (docs/DESIGN.md section 4, core/shapes.py); any other is refused."""
MAX_OBJECTS = 100
"""Most objects a scene file may hold (the workspace fits far fewer blocks; validation is quadratic)."""
MAX_NAME = 64
"""Longest object name, colour or shape a scene file may give (they are echoed in error messages)."""
KIND = re.compile(r"^[^\W\d_]+(?:[ '-][^\W\d_]+)*$")
"""An object's declared kind: words of letters joined by spaces, hyphens or apostrophes ("toy cow", "T-rex"), no
longer than MAX_NAME (checked where it is read)."""


def _m(v: float) -> str:
    """A coordinate in an error message: millimetre precision, or 3 digits when it is absurdly large."""
    return f"{v:.3f}" if abs(v) < 1e4 else f"{v:.3g}"


def load_scene(path: str | Path, mesh_dirs: tuple[str | Path, ...] = ()) -> Scene:
    """Read and validate a scene file; every problem becomes a :class:`SceneError` naming the file.

    Mesh paths are read relative to the file's folder and must stay inside it, or inside the installed
    pybullet_data (``pybullet_data:NAME``) or one of ``mesh_dirs`` (folders the user names)."""
    p = Path(path)
    return Scene.from_dict(load_json_file(p, SceneError, "scene file"), source=str(p), base=p.resolve().parent,
                           mesh_dirs=tuple(Path(d) for d in mesh_dirs)).validate()


def save_scene(scene: Scene, path: str | Path) -> None:
    Path(path).write_text(json.dumps(scene.to_dict(), indent=2) + "\n")


def default_scene() -> Scene:
    """Blocks A (red) and B (green), 5 cm cubes, as in DESIGN.md's example."""
    return Scene(
        [
            SceneObject("A", "red", 0.05, (0.05, -0.10), 0.3),
            SceneObject("B", "green", 0.05, (0.0, 0.05), 0.0),
        ]
    ).validate()


def random_scene(seed: int, size: float = 0.05) -> Scene:
    """A valid two-block scene drawn from ``seed``: anchor B near the centre, mover A 2-4 block sizes away.

    The anchor stays within 0.07 m of the centre so that every action (even "around" and "away from")
    has room to be performed inside the workspace.
    """
    rng = np.random.default_rng(seed)
    for _ in range(1000):
        r, a = 0.07 * math.sqrt(rng.uniform()), rng.uniform(-math.pi, math.pi)
        b_xy = (r * math.cos(a), r * math.sin(a))
        d, a2 = rng.uniform(2.0, 4.0) * size, rng.uniform(-math.pi, math.pi)
        a_xy = (b_xy[0] + d * math.cos(a2), b_xy[1] + d * math.sin(a2))
        objects = [
            SceneObject("A", "red", size, a_xy, float(rng.uniform(0, math.pi / 2))),
            SceneObject("B", "green", size, b_xy, float(rng.uniform(0, math.pi / 2))),
        ]
        try:  # drawn in the start disk (the same scenes for the same seeds since before the planning disk grew)
            Scene(objects, workspace=Workspace(radius=START_RADIUS)).validate()
        except SceneError:
            continue
        return Scene(objects).validate()
    raise SceneError(f"could not draw a valid random scene for seed {seed}")  # pragma: no cover


def random_between_scene(seed: int, size: float = 0.05) -> Scene:
    """A valid three-block scene drawn from ``seed``, for two-anchor actions ("move A between B and C").

    The anchors B (green) and C (blue) lie 3-4.5 block sizes apart, their midpoint within 0.05 m of the
    centre; the mover A (red) starts 2-4 block sizes from that midpoint, not already between them (its
    centre projects outside the segment or lies more than 1.5 blocks off it) and not touching either.
    """
    rng = np.random.default_rng(seed)
    for _ in range(1000):
        r, a = 0.05 * math.sqrt(rng.uniform()), rng.uniform(-math.pi, math.pi)
        mid = np.array([r * math.cos(a), r * math.sin(a)])
        phi = rng.uniform(-math.pi, math.pi)
        half = 0.5 * rng.uniform(3.0, 4.5) * size * np.array([math.cos(phi), math.sin(phi)])
        b_xy, c_xy = mid - half, mid + half
        d, a2 = rng.uniform(2.0, 4.0) * size, rng.uniform(-math.pi, math.pi)
        a_xy = mid + d * np.array([math.cos(a2), math.sin(a2)])
        e, rel = c_xy - b_xy, a_xy - b_xy
        t = float(rel @ e / (e @ e))
        off = abs(float(rel[0] * e[1] - rel[1] * e[0])) / float(np.linalg.norm(e)) / size
        if 0.0 < t < 1.0 and off < 1.5:
            continue
        objects = [
            SceneObject("A", "red", size, (float(a_xy[0]), float(a_xy[1])), float(rng.uniform(0, math.pi / 2))),
            SceneObject("B", "green", size, (float(b_xy[0]), float(b_xy[1])), float(rng.uniform(0, math.pi / 2))),
            SceneObject("C", "blue", size, (float(c_xy[0]), float(c_xy[1])), float(rng.uniform(0, math.pi / 2))),
        ]
        try:  # drawn in the start disk, as random_scene
            Scene(objects, workspace=Workspace(radius=START_RADIUS)).validate()
        except SceneError:
            continue
        scene = Scene(objects)
        if min(np.linalg.norm(a_xy - b_xy), np.linalg.norm(a_xy - c_xy)) < 1.6 * size:
            continue  # touching or nearly: the planner refuses a mover that starts touching
        return scene
    raise SceneError(f"could not draw a valid three-block scene for seed {seed}")  # pragma: no cover
