"""What the simulator collides a mesh with: its convex decomposition, computed once and kept by its digest.

Bullet collides moving bodies with convex shapes only, so a mesh is split into convex parts (PyBullet's
built-in V-HACD, :func:`.bullet.vhacd`): a mug stays hollow, a concave part keeps its dent, a mesh with
holes or open rims is decomposed as the solid its voxels enclose. V-HACD rather than CoACD (PyPI) because
it ships with PyBullet and, on the meshes measured (docs/perform.md), it needed a tenth of CoACD's CPU time
for as close a fit.

The result is an OBJ file of parts in the mesh file's own frame and units (the scene's ``scale`` and
``rpy`` apply to it as to the drawing), named by the SHA-256 of the mesh file's bytes and the parameters
below, so a changed mesh is decomposed afresh and an unchanged one never again. It is kept next to the mesh
(``.l2p-collision/`` in the mesh's folder), or in the user's cache folder where that folder cannot be
written or belongs to an installed package (pybullet_data's ready objects).
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from functools import lru_cache
from pathlib import Path

import numpy as np

from ...core.shapes import pybullet_data_root
from .bullet import vhacd

PARAMS = {"resolution": 100_000, "concavity": 0.0025, "maxNumVerticesPerCH": 64, "minVolumePerCH": 0.0001}
"""V-HACD's settings (its defaults, written down so that they are part of the cache key)."""
FOLDER = ".l2p-collision"
"""The cache folder's name next to a mesh."""


def user_cache() -> Path:
    """The user's cache folder for decompositions ($XDG_CACHE_HOME or ~/.cache, then l2p-bullet/collision)."""
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "l2p-bullet" / "collision"


def digest(mesh: Path) -> str:
    """The cache key: the mesh file's bytes and the decomposition's settings."""
    h = hashlib.sha256(Path(mesh).read_bytes())
    h.update(json.dumps(PARAMS, sort_keys=True).encode())
    return h.hexdigest()[:32]


def _folders(mesh: Path) -> list[Path]:
    """Where the decomposition may be kept, first choice first."""
    beside = mesh.parent / FOLDER
    root = pybullet_data_root()
    if root == mesh.parent or root in mesh.parents:
        return [user_cache()]
    return [beside, user_cache()]


def parts_file(mesh: str | Path) -> Path | None:
    """The OBJ file of the mesh's convex parts (mesh frame and units), decomposed now unless kept already;
    None for a convex mesh and where V-HACD finds no parts (the simulator collides with the mesh's hull)."""
    p = Path(mesh)
    st = p.stat()
    return _parts_file(str(p), st.st_mtime_ns, st.st_size)


@lru_cache(maxsize=64)
def _parts_file(path: str, mtime_ns: int, size: int) -> Path | None:
    """:func:`parts_file`, once per file version and process (a batch loads the same mesh run after run)."""
    mesh = Path(path)
    name = f"{mesh.stem[:60]}-{digest(mesh)}.obj"
    folders = _folders(mesh)
    for folder in folders:
        if (folder / name).is_file():
            return folder / name
    import trimesh

    m = trimesh.load(str(mesh), force="mesh", process=True, file_type=mesh.suffix.lower()[1:])
    if _convex(m):  # its hull is its shape, exactly (V-HACD's voxels would grow it by half a voxel)
        return None
    for folder in folders:
        try:
            folder.mkdir(parents=True, exist_ok=True)
            return _decompose(m, mesh.name, folder / name)
        except _NoParts:
            return None
        except OSError:  # a read-only folder (or a file in the cache folder's place): the next one
            continue
    raise OSError(f"no folder to keep the decomposition of {mesh.name} in ({', '.join(map(str, folders))})")


def _convex(m, tol: float = 1e-6) -> bool:
    """Whether a mesh is a closed convex surface: every vertex on the inner side of every triangle's plane
    (``tol`` of its size). Checked here in numpy (trimesh's own check needs scipy)."""
    if not m.is_watertight or len(m.faces) * len(m.vertices) > 5e7:
        return False
    v = np.asarray(m.vertices, float)
    tri = v[np.asarray(m.faces)]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n *= np.sign(float(m.volume)) or 1.0  # outwards
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    d = np.einsum("ij,ij->i", n, tri[:, 0])
    size = float(np.ptp(v, axis=0).max())
    for s in range(0, len(n), 4096):
        if ((v @ n[s:s + 4096].T) - d[s:s + 4096] > tol * size).any():
            return False
    return True


class _NoParts(Exception):
    """V-HACD wrote no convex part."""


def _decompose(m, name: str, out: Path) -> Path:
    """V-HACD on the mesh ``m``'s triangles (written as an OBJ), its parts written atomically to ``out``."""
    with tempfile.TemporaryDirectory(dir=out.parent) as tmp:
        src, dst, log = Path(tmp, "in.obj"), Path(tmp, "out.obj"), Path(tmp, "log.txt")
        lines = [f"v {x:.9g} {y:.9g} {z:.9g}" for x, y, z in m.vertices]
        lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in m.faces]
        src.write_text("\n".join(lines) + "\n")
        vhacd(str(src), str(dst), str(log), **PARAMS)
        if not dst.is_file() or "\nv " not in "\n" + dst.read_text(errors="replace"):
            raise _NoParts(name)
        os.replace(dst, out)
    return out
