"""Run folders: never overwrite one unless asked; default names are timestamped."""

from __future__ import annotations

import shutil
import time
from pathlib import Path

from ..errors import RunFolderError


def prepare_run_folder(out: str | Path | None, force: bool = False, prefix: str = "run",
                       root: str | Path = "runs") -> Path:
    """Create and return the run folder.

    ``out=None`` gives ``runs/<prefix>-YYYYmmdd-HHMMSS`` (a suffix is added if that exists). An existing,
    non-empty ``out`` is an error unless ``force`` is true, in which case it is emptied first.
    """
    if out is None:
        base = Path(root) / f"{prefix}-{time.strftime('%Y%m%d-%H%M%S')}"
        path, n = base, 1
        while path.exists():
            n += 1
            path = base.with_name(f"{base.name}-{n}")
    else:
        path = Path(out)
        if path.exists() and not path.is_dir():
            raise RunFolderError(f"{path} exists and is not a folder")
        if path.exists() and any(path.iterdir()):
            if not force:
                raise RunFolderError(f"run folder {path} already exists; pass --force to overwrite it")
            shutil.rmtree(path)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise RunFolderError(f"cannot create run folder {path}: {e.strerror or e}") from None
    return path
