"""A script of benchmarks/ imported as a module, and a run folder's results.sqlite made from rows: what the tests of
the scripts that read `l2p-bullet evaluate` runs (compare_chain_runs.py, forced_refusals.py) share."""

from __future__ import annotations

import importlib.util
import sqlite3
import sys
from pathlib import Path
from types import ModuleType

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"


def script(name: str) -> ModuleType:
    """``benchmarks/<name>.py`` imported (registered under its name: a dataclass in it looks its module up)."""
    spec = importlib.util.spec_from_file_location(name, BENCHMARKS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def run_folder(folder: Path, columns: str, rows: list[tuple]) -> Path:
    """``folder`` made with a results.sqlite whose ``runs`` table has ``columns`` ("seed integer, ...") and ``rows``."""
    folder.mkdir()
    with sqlite3.connect(folder / "results.sqlite") as con:
        con.execute(f"create table runs ({columns})")
        con.executemany(f"insert into runs values ({', '.join('?' * len(rows[0]))})", rows)
    return folder
