"""Object shapes: what planning, grasping and the simulator need to know about a box, a cylinder or a mesh.

A scene object is a cube (the default, written down directly in ``core/scene.py``), a ``box`` with
``dims`` [x, y, z], a ``cylinder`` with ``radius`` and ``height``, or a ``mesh`` read from an OBJ, STL or
GLB file (times ``scale``, turned by ``rpy``). :func:`geometry` turns each into a :class:`Geometry` in the
object's own frame, whose origin is the **reference point**: the object's centre of mass (a solid of
uniform density), which is a cube's, a box's and a cylinder's centre, as before. A scene's ``xy`` and ``yaw``
place it, trajectory.json's ``z`` is its height above the table and the simulator's body frame is there:

- ``points``: the shape's points (the simulator collides a box or a cylinder with their convex hull, a mesh
  with its convex decomposition, so a mug is hollow and a concave part has its dent);
- ``footprint``: the convex outline on the table (the points seen from above), counter-clockwise;
- ``height``, ``rest_z`` (the reference point's height above the table when the object stands on it),
  ``com`` (the centre of mass's offset from the bounding box's centre, for the record), ``volume``;
- widths: :meth:`Geometry.width` is the distance between two parallel vertical planes that squeeze the
  footprint along a direction; the narrowest one is across one of the outline's edges.

**The size in blocks.** The learned features measure lengths in "block sides" (the human demonstrations
used 15 cm squares, DESIGN.md section 2). For any footprint the side used is the **square root of the
footprint's area**: the side of the square that covers as much table. It is a cube's side exactly, grows
with the object in both directions (a 2:1 box is 1.41 short sides, not 1 or 2), and depends on the
outline only, like everything the 2-D planner sees (the cube-equivalent side, the cube root of the volume,
would make a flat plate "small" though it covers the table like a big block).

trimesh is imported only for meshes (its import costs 0.3-0.5 s, paid by no cube, box or cylinder scene).
A mesh file is bounded before it is parsed: its size on disk (:data:`MAX_MESH_BYTES`), a binary STL's
declared triangle count; then its face count (:data:`MAX_MESH_FACES`) and volume. A mesh need not be closed:
a watertight one is weighed exactly, any other by what its surface winds round (``core/solid.py``); what the
simulator collides with is its convex decomposition (``embodiment/sim/decompose.py``).
"""

from __future__ import annotations

import io
import math
import os
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import SceneError, did_you_mean, sizes
from . import solid
from .bounded import read_bounded
from .geometry import convex_hull
from .mesh_files import bounded_resolver

SHAPES = ("cube", "box", "cylinder", "mesh")
MESH_SUFFIXES = (".obj", ".stl", ".glb")
MIN_EXTENT, MAX_EXTENT = 0.01, 0.25
"""Every extent of a non-cube object (metres): thinner than 1 cm the fingertips miss it; wider than 25 cm it
no longer fits the workspace's 25 cm radius with room to move."""
MAX_MESH_BYTES = 16 * 1024 * 1024
"""A mesh file larger than this is refused before it is read (a 10-million-face mesh is 500 MB); it bounds what
a mesh reads in all, the files it names (a GLB's buffers and images, an OBJ's materials) included."""
MIN_SCALE, MAX_SCALE = 1e-6, 1e6
"""A mesh's ``scale``: from micrometres to kilometres per file unit; beyond, its volume (scale cubed) is no
number (1e308 cubed overflows) and no object of 1-25 cm comes out anyway."""
MAX_MESH_FACES = 200_000
"""A mesh with more triangles is refused (its hull is what the arm meets; decimate it first)."""
CYLINDER_SIDES = 16
"""A cylinder's outline is the regular polygon with this many sides drawn around its circle: the
footprint the planner keeps clear is never smaller than the cylinder (at most 2 % wider, 1.3 % larger)."""
BLOCK_MASS, BLOCK_FRICTION = 0.1, 0.5
"""urdf/block.urdf's mass (kg) and friction: what any object has unless its scene entry says ``mass`` or
``friction`` (the simulator spawns it so, and a carry checks this mass against the arm's payload)."""
MAX_MASS, MAX_FRICTION = 5.0, 2.0
"""Largest ``mass`` (kg) and ``friction`` coefficient an object may have (the arm holds 0.1-kg blocks with a
100 N constraint; a heavier object or a stickier table is not what it was measured with)."""
PYBULLET_DATA = "pybullet_data:"
"""Prefix of a mesh path inside the installed pybullet_data (ready objects such as the duck)."""


@dataclass(frozen=True)
class Geometry:
    """One shape in its own frame (origin: the reference point, see the module docstring)."""

    points: np.ndarray  # (N,3) the shape's points (a box's, a cylinder's collision hull; a mesh's vertices)
    faces: np.ndarray  # (M,3) triangles of ``points`` for drawing
    footprint: np.ndarray  # (K,2) convex outline on the table, counter-clockwise
    height: float
    com: tuple[float, float, float]
    volume: float
    rest_z: float = math.nan  # nan: height / 2 (a symmetric solid)
    file_origin: tuple[float, float, float] = (0.0, 0.0, 0.0)  # a mesh file's origin in this frame (drawing)

    @property
    def rest(self) -> float:
        """The reference point's height above the table when the object stands on it."""
        return self.height / 2 if math.isnan(self.rest_z) else self.rest_z

    @property
    def area(self) -> float:
        x, y = self.footprint[:, 0], self.footprint[:, 1]
        return float(0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))

    @property
    def size(self) -> float:
        """The side in blocks: the square root of the footprint's area (module docstring)."""
        return math.sqrt(self.area)

    @property
    def inradius(self) -> float:
        """Distance from the reference point to the outline's nearest edge (a cube: half its side)."""
        return float(min(_edge_distances(self.footprint)))

    def width(self, direction: float) -> float:
        """Extent of the footprint along ``direction`` (radians, object frame): the gap two fingers closing
        along that direction must open to."""
        u = np.array([math.cos(direction), math.sin(direction)])
        d = self.footprint @ u
        return float(d.max() - d.min())

    def narrowest(self) -> tuple[float, float]:
        """(width, direction) of the narrowest squeeze: across one of the outline's edges."""
        f = self.footprint
        e = np.roll(f, -1, axis=0) - f
        dirs = np.arctan2(e[:, 0], -e[:, 1])  # each edge's normal
        widths = [self.width(float(a)) for a in dirs]
        k = int(np.argmin(widths))
        return widths[k], float(dirs[k] % math.pi)


def _edge_distances(poly: np.ndarray) -> np.ndarray:
    e = np.roll(poly, -1, axis=0) - poly
    n = np.linalg.norm(e, axis=1)
    return np.abs(e[:, 0] * poly[:, 1] - e[:, 1] * poly[:, 0]) / np.maximum(n, 1e-15)


def _prism(outline: np.ndarray, height: float) -> np.ndarray:
    h = height / 2
    return np.vstack([np.column_stack([outline, np.full(len(outline), -h)]),
                      np.column_stack([outline, np.full(len(outline), h)])])


def _prism_faces(k: int) -> np.ndarray:
    """Triangles (outward, counter-clockwise seen from outside) of :func:`_prism`'s points."""
    i = np.arange(k)
    j = (i + 1) % k
    fan = np.arange(1, k - 1)
    bottom = np.column_stack([np.zeros(k - 2, int), fan + 1, fan])
    top = np.column_stack([np.full(k - 2, k), k + fan, k + fan + 1])
    sides = np.vstack([np.column_stack([i, j, k + j]), np.column_stack([i, k + j, k + i])])
    return np.vstack([bottom, top, sides]).astype(np.int64)


def box(dims: tuple[float, float, float]) -> Geometry:
    x, y, z = (d / 2 for d in dims)
    outline = np.array([[-x, -y], [x, -y], [x, y], [-x, y]])
    return Geometry(_prism(outline, dims[2]), _prism_faces(4), outline, float(dims[2]), (0.0, 0.0, 0.0),
                    float(dims[0] * dims[1] * dims[2]))


def cylinder(radius: float, height: float) -> Geometry:
    a = (np.arange(CYLINDER_SIDES) + 0.5) * 2 * math.pi / CYLINDER_SIDES
    r = radius / math.cos(math.pi / CYLINDER_SIDES)  # the polygon around the circle, not inside it
    outline = np.column_stack([r * np.cos(a), r * np.sin(a)])
    return Geometry(_prism(outline, height), _prism_faces(CYLINDER_SIDES), outline, float(height), (0.0, 0.0, 0.0),
                    float(math.pi * radius**2 * height))


def resolve_mesh(text: str, base: Path | None, trusted: tuple[Path, ...] = ()) -> Path:
    """The file a scene's ``"mesh"`` names. A relative path is read from the scene file's folder ``base`` and
    must stay inside it; ``pybullet_data:NAME`` is a ready object of the installed pybullet_data; an
    absolute path is accepted only inside ``base``, pybullet_data or a folder in ``trusted`` (given by the
    user), or anywhere when ``base`` is None: a scene that comes from no file (built in Python, or handed
    to an evaluation worker after its file was checked) is the program's own, not a file's claim."""
    root = pybullet_data_root()
    if text.startswith(PYBULLET_DATA):
        path, allowed = (root / text[len(PYBULLET_DATA):]).resolve(), (root,)
    else:
        p = Path(text)
        if not p.is_absolute() and base is None:
            raise SceneError(f'mesh "{text[:200]}": a relative path needs the scene file it is relative to')
        path = (p if p.is_absolute() else base / p).resolve()
        allowed = tuple(d.resolve() for d in ((base,) if base is not None else ()) + tuple(trusted))
        if p.is_absolute():  # a scene written by this program names ready objects by their full path
            allowed = None if base is None else allowed + (root,)
    if allowed is not None and not any(path == d or d in path.parents for d in allowed):
        where = "the installed pybullet_data" if text.startswith(PYBULLET_DATA) else "the scene file's folder"
        raise SceneError(f'mesh "{text[:200]}" is outside {where}; put the mesh next to the scene file, '
                         "or name its folder on the command line (--mesh-dir DIR)")
    if path.suffix.lower() not in MESH_SUFFIXES:
        raise SceneError(f'mesh "{text[:200]}": not a mesh file name (expected {", ".join(MESH_SUFFIXES)})')
    if not path.is_file():
        raise SceneError(f'mesh "{text[:200]}": no such file ({path})')
    return path


@lru_cache(maxsize=1)
def pybullet_data_root() -> Path:
    """The installed pybullet_data folder, located without importing it (pybullet stays in sim/)."""
    import importlib.util

    spec = importlib.util.find_spec("pybullet_data")
    if spec is None or not spec.submodule_search_locations:  # pragma: no cover - pybullet depends on it
        raise SceneError("pybullet_data is not installed")
    return Path(next(iter(spec.submodule_search_locations))).resolve()


MAX_OUTLINE = 16
"""Most corners a footprint keeps: the planner's and the checks' polygon tests cost grows with them (a
21-corner duck made the blocked-around check take 4.4 s); :func:`simplify` drops the rest conservatively."""


def simplify(outline: np.ndarray, most: int = MAX_OUTLINE) -> np.ndarray:
    """A convex outline with at most ``most`` corners that contains ``outline``: edges are dropped one at a
    time, the one whose removal (its neighbours extended to meet) adds the least area, so what the planner
    keeps clear is never smaller than the object."""
    poly = [np.asarray(p, float) for p in outline]
    while len(poly) > most:
        best = None
        n = len(poly)
        for i in range(n):  # drop the edge poly[i] -> poly[i + 1]
            a0, a1, b0, b1 = poly[i - 1], poly[i], poly[(i + 1) % n], poly[(i + 2) % n]
            d1, d2 = a1 - a0, b1 - b0
            den = d1[0] * d2[1] - d1[1] * d2[0]
            if den <= 1e-15:  # the neighbours do not meet ahead: dropping this edge would open the outline
                continue
            s = ((b0[0] - a0[0]) * d2[1] - (b0[1] - a0[1]) * d2[0]) / den
            x = a0 + s * d1
            added = 0.5 * abs((b0[0] - a1[0]) * (x[1] - a1[1]) - (b0[1] - a1[1]) * (x[0] - a1[0]))
            if best is None or added < best[0]:
                best = (added, i, x)
        if best is None:  # pragma: no cover - a convex outline always has an edge to drop
            break
        _, i, x = best
        poly[i] = x
        del poly[(i + 1) % n]
    return np.array(poly)


def _check_size(path: Path) -> None:
    """Refuse a file too large to read, before reading it (its size, and a binary STL's declared count)."""
    size = os.stat(path).st_size
    if size > MAX_MESH_BYTES:
        have, most = sizes(size, MAX_MESH_BYTES)
        raise SceneError(f"mesh {path.name}: {have} is more than the {most} a mesh may have; decimate it (its "
                         "convex hull is what the arm meets)")
    if path.suffix.lower() == ".stl" and size >= 84:
        with open(path, "rb") as f:
            head = f.read(84)
        if not head[:5].lower().startswith(b"solid"):
            n = int.from_bytes(head[80:84], "little")
            if n > MAX_MESH_FACES:
                raise SceneError(f"mesh {path.name}: {n} triangles, more than the {MAX_MESH_FACES} a mesh may have")


def _rotation(rpy: tuple[float, float, float]) -> np.ndarray:
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


@lru_cache(maxsize=64)
def mesh(path: str, scale: float, rpy: tuple[float, float, float], mtime_ns: int = 0) -> Geometry:
    """A mesh file's geometry (cached per file, scale, rotation and modification time)."""
    p = Path(path)
    if not (is_number(scale) and MIN_SCALE <= scale <= MAX_SCALE):
        raise SceneError(f'mesh {p.name}: "scale" must be from {MIN_SCALE:g} to {MAX_SCALE:g} (got {str(scale)[:30]})')
    _check_size(p)
    import trimesh

    raw = read_bounded(p, MAX_MESH_BYTES, SceneError, f"mesh {p.name}")
    resolver = bounded_resolver(p, MAX_MESH_BYTES - len(raw), MAX_MESH_BYTES)
    try:
        m = trimesh.load(io.BytesIO(raw), force="mesh", process=True, file_type=p.suffix.lower()[1:],
                         resolver=resolver)
    except Exception as e:  # any parser's complaint about a file that is not a mesh
        if resolver.refused:
            raise resolver.refused from None
        raise SceneError(f"mesh {p.name}: not a readable {p.suffix.lower()[1:].upper()} mesh "
                         f"({type(e).__name__}: {str(e)[:120]})") from None
    if resolver.refused:  # a parser that shrugs off a missing material must not shrug off the limit
        raise resolver.refused
    if not isinstance(m, trimesh.Trimesh) or len(m.faces) == 0:
        raise SceneError(f"mesh {p.name}: the file holds no triangles")
    if len(m.faces) > MAX_MESH_FACES:
        raise SceneError(f"mesh {p.name}: {len(m.faces)} triangles, more than the {MAX_MESH_FACES} a mesh may have")
    with np.errstate(all="ignore"):  # a flat mesh divides by its zero volume: refused just below
        return _measure(m, p, scale, rpy)


def _measure(m, p: Path, scale: float, rpy: tuple[float, float, float]) -> Geometry:
    m.merge_vertices(merge_tex=True, merge_norm=True)  # texture seams split vertices: not holes
    v = np.asarray(m.vertices, float) * scale @ _rotation(rpy).T
    if not np.all(np.isfinite(v)):
        raise SceneError(f"mesh {p.name}: non-finite vertex coordinates")
    if m.is_watertight:  # a closed surface weighs exactly
        volume, center = abs(float(m.volume)), np.asarray(m.center_mass, float)
    else:  # holes, open rims, flipped triangles: what the surface winds round (core/solid.py)
        volume, center = solid.solid(m.vertices, m.faces)
    volume *= scale**3
    if not volume > 1e-12:
        raise SceneError(f"mesh {p.name}: no volume (a flat or inside-out surface)")
    lo, hi = v.min(axis=0), v.max(axis=0)
    com = (center * scale) @ _rotation(rpy).T
    v = v - com
    outline = simplify(convex_hull(v[:, :2]))
    return Geometry(v, np.asarray(m.faces, np.int64), outline, float(hi[2] - lo[2]),
                    tuple(float(c) for c in com - (lo + hi) / 2), volume, float(com[2] - lo[2]),
                    tuple(float(-c) for c in com))


def is_number(v: object) -> bool:
    """A JSON number that is a finite float (a 300-digit integer is not a coordinate)."""
    if isinstance(v, bool) or not isinstance(v, int | float):
        return False
    try:
        return math.isfinite(float(v))
    except OverflowError:
        return False


@lru_cache(maxsize=256)
def geometry(shape: str, dims: tuple | None, radius: float | None, height: float | None, mesh_path: str | None,
             scale: float = 1.0, rpy: tuple = (0.0, 0.0, 0.0)) -> Geometry:
    """A non-cube object's geometry (cached: the planner asks for footprints thousands of times)."""
    if shape == "box":
        return box(dims)
    if shape == "cylinder":
        return cylinder(radius, height)
    if shape == "mesh":
        return mesh(mesh_path, scale, rpy, Path(mesh_path).stat().st_mtime_ns)
    raise SceneError(f'unknown object shape "{shape}" (known: {", ".join(SHAPES)})')


def read_fields(raw: dict, where: str, base: Path | None, mesh_dirs: tuple[Path, ...]) -> dict:
    """The shape fields of one scene-file object as ``SceneObject`` keyword arguments, checked (one-line
    SceneError naming the object); the geometry is built once here, so a bad mesh fails at load time."""
    shape = raw.get("shape", "cube")
    if shape not in SHAPES:
        raise SceneError(
            f'{where}: unknown shape "{shape}" (known: {", ".join(SHAPES)}).' + did_you_mean(shape, SHAPES)
        )
    need = {"cube": (), "box": ("dims",), "cylinder": ("radius", "height"), "mesh": ("mesh",)}[shape]
    for key in need:
        if key not in raw:
            raise SceneError(f'{where}: a {shape} needs the field "{key}"')
    out: dict = {}
    for key, hi in (("mass", MAX_MASS), ("friction", MAX_FRICTION)):
        if key in raw:
            if not (is_number(raw[key]) and 0.0 < raw[key] <= hi):
                raise SceneError(f'{where}: "{key}" must be a number above 0 and at most {hi}')
            out[key] = float(raw[key])
    if shape == "box":
        d = raw["dims"]
        if not (isinstance(d, list | tuple) and len(d) == 3 and all(is_number(v) for v in d)):
            raise SceneError(f'{where}: "dims" must be three finite numbers [x, y, z] in metres')
        out["dims"] = tuple(float(v) for v in d)
    elif shape == "cylinder":
        for key in ("radius", "height"):
            if not is_number(raw[key]):
                raise SceneError(f'{where}: "{key}" must be a finite number (metres)')
        out["radius"], out["height_m"] = float(raw["radius"]), float(raw["height"])
    elif shape == "mesh":
        if not isinstance(raw["mesh"], str) or not raw["mesh"]:
            raise SceneError(f'{where}: "mesh" must be a file name (.obj, .stl or .glb)')
        scale = raw.get("scale", 1.0)
        if not is_number(scale) or not scale > 0:
            raise SceneError(f'{where}: "scale" must be a positive finite number')
        rpy = raw.get("rpy", [0.0, 0.0, 0.0])
        if not (isinstance(rpy, list | tuple) and len(rpy) == 3 and all(is_number(v) for v in rpy)):
            raise SceneError(f'{where}: "rpy" must be three finite numbers [roll, pitch, yaw] in radians')
        try:
            path = resolve_mesh(raw["mesh"], base, tuple(mesh_dirs))
        except SceneError as e:
            raise SceneError(f"{where}: {e}") from None
        out.update(mesh=str(path), scale=float(scale), rpy=tuple(float(v) for v in rpy))
    if shape != "cube":
        check_extents(shape, out.get("dims"), out.get("radius"), out.get("height_m"), out.get("mesh"),
                      out.get("scale", 1.0), out.get("rpy", (0.0, 0.0, 0.0)), where)
    return out


def check_extents(shape: str, dims, radius, height, mesh_path, scale, rpy, where: str) -> Geometry:
    """A non-cube object's dimensions: finite, positive and within ``MIN_EXTENT``-``MAX_EXTENT``."""
    if shape == "box" and not (dims and len(dims) == 3 and all(is_number(v) and v > 0 for v in dims)):
        raise SceneError(f'{where}: box "dims" must be three positive finite numbers')
    if shape == "cylinder" and not all(is_number(v) and v > 0 for v in (radius, height)):
        raise SceneError(f'{where}: cylinder "radius" and "height" must be positive finite numbers')
    try:
        g = geometry(shape, None if dims is None else tuple(dims), radius, height, mesh_path, scale, tuple(rpy))
    except SceneError as e:
        raise SceneError(str(e) if str(e).startswith(where) else f"{where}: {e}") from None
    ext = (*(np.ptp(g.footprint, axis=0)), g.height)
    if not all(MIN_EXTENT - 1e-9 <= e <= MAX_EXTENT + 1e-9 for e in ext):
        raise SceneError(f'{where}: its extents {", ".join(f"{e * 100:.1f}" for e in ext)} cm (x, y, height) '
                         f"must each be {MIN_EXTENT * 100:.0f}-{MAX_EXTENT * 100:.0f} cm")
    return g


def fields(o) -> dict:
    """A non-cube object's fields in the scene file (a cube writes none: its file stays as it was)."""
    out: dict = {}
    if o.shape == "box":
        out["dims"] = list(o.dims)
    elif o.shape == "cylinder":
        out.update(radius=o.radius, height=o.height_m)
    elif o.shape == "mesh":
        p, root = Path(o.mesh), pybullet_data_root()
        out.update(mesh=PYBULLET_DATA + p.relative_to(root).as_posix() if root in p.parents else o.mesh, scale=o.scale)
        if any(o.rpy):
            out["rpy"] = list(o.rpy)
    for key in ("mass", "friction"):
        if getattr(o, key) is not None:
            out[key] = getattr(o, key)
    return out
