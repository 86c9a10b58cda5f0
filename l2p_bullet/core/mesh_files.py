"""The files a mesh file names, read bounded: trimesh reads a GLB's external buffers and images and an OBJ's
materials and textures through a resolver, whole and unasked; :func:`bounded_resolver` is one that counts."""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import SceneError
from .bounded import read_bounded


def bounded_resolver(p: Path, budget: int, limit: int):
    """trimesh's resolver for the files a mesh names (a GLB's external buffers and images, an OBJ's
    materials and textures), reading them in the mesh's folder only and at most ``budget`` bytes in all: a
    400-byte GLB may name a 3 GB buffer beside it, which trimesh would read whole before complaining. ``limit``
    is what the message names (the whole mesh's); ``.refused`` holds the error once the budget is spent."""
    from trimesh.resolvers import FilePathResolver  # lazy: trimesh is imported only when a mesh is read

    class Bounded(FilePathResolver):
        refused: SceneError | None = None

        def get(self, name: str) -> bytes:
            nonlocal budget
            for candidate in (name.strip(), name.strip().lstrip("/"), os.path.split(name)[-1]):
                try:
                    path = self.absolute(candidate)
                except ValueError:
                    continue
                if path.is_file():
                    try:
                        data = read_bounded(path, budget, SceneError)
                    except SceneError:
                        self.refused = SceneError(
                            f"mesh {p.name} names {str(name)[:80]}, which takes it past the "
                            f"{limit / 2**20:g} MiB a mesh may read in all (its file, buffers and images)")
                        raise self.refused from None
                    budget -= len(data)
                    return data
            raise FileNotFoundError(name)

    return Bounded(str(p))
