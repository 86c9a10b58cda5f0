"""Run folders: never overwrite one unless asked; default names are timestamped; summary.json is written here."""

from __future__ import annotations

import json
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


def write_summary(path: Path, summary: dict) -> None:
    """Write a run folder's summary.json (numpy numbers and paths become plain JSON)."""
    path.write_text(json.dumps(summary, indent=1, default=_json_default) + "\n")


def _json_default(v: object) -> object:
    import numpy as np

    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, Path):
        return str(v)
    raise TypeError(f"not JSON serialisable: {type(v).__name__}")
