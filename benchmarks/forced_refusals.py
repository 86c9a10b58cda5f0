"""Which chains an `l2p-bullet evaluate --chains` run refused up front could not be planned whatever the search does.

    python benchmarks/forced_refusals.py RUN_DIR [RUN_DIR ...]

A refusal is forced by the drawn start where the refused clause's mover and anchor are both where the scene put
them (no clause before it moves either) and the clause is refused on the start scene even carried over the other
objects (a carry's room checks read the mover, the anchor and the workspace alone, `planning/feasibility.check`):
no end state of the clauses before it can change what the check reads. Prints one row per refusal and the count;
reads the runs' results.sqlite (the evaluate contract, docs/evaluate.md) and writes nothing.
"""

from __future__ import annotations

import argparse
import re
import sqlite3
import sys
from pathlib import Path

from l2p_bullet.arms import PANDA, fit_scene
from l2p_bullet.errors import L2PError
from l2p_bullet.evaluate.chains import chain_scenes
from l2p_bullet.pipeline import carried_over, check_feasible, resolve
from l2p_bullet.plugins import registry

REFUSED = re.compile(r'clause (?P<k>\d+) \("(?P<clause>[^"]+)"\) cannot be planned \((?P<check>[a-z-]+)\)')
SCENE = re.compile(r"chain/(?P<seed>\d+)(?:/(?P<blocks>\d+)b)?$")


def refusals(folder: Path) -> list[tuple[str, str, str]]:
    """(scene id, sentence, refusal) of every chain the run in ``folder`` refused up front."""
    db = folder / "results.sqlite"
    if not db.is_file():
        raise SystemExit(f"error: {db} does not exist: give an `l2p-bullet evaluate --chains` output folder")
    with sqlite3.connect(f"file:{db}?mode=ro", uri=True) as con:
        return list(con.execute("select scene_id, sentence, error from runs where error_type = 'refused'"))


def forced(scene_id: str, sentence: str, error: str, plugins: list) -> tuple[str, bool]:
    """(what the row says, whether the start forces the refusal)."""
    m, s = REFUSED.match(error), SCENE.match(scene_id)
    if m is None or s is None:
        return f"{scene_id}: not a refusal of a drawn chain's clause", False
    k, clause = int(m.group("k")), m.group("clause")
    blocks = int(s.group("blocks")) if s.group("blocks") else None
    scene = fit_scene(chain_scenes(1, int(s.group("seed")), blocks)[0].scene.validate(), PANDA)
    before = [c.split()[1] for c in re.split(r",\s*then\s+", sentence)[:k - 1]]
    command = resolve(clause, scene, plugins)
    moved = sorted({command.mover, command.anchor} & set(before))
    carried = carried_over(command, "its slide is refused") or command
    try:
        check_feasible(carried, scene, plugins, PANDA)
        start = "carried, planned on the start scene"
    except L2PError:
        start = "carried, refused on the start scene"
    is_forced = not moved and start.endswith("refused on the start scene")
    row = f"| {scene_id} | {k} | {m.group('check')} | {clause} | {', '.join(moved) or '-'} | {start} | " \
          f"{'**forced**' if is_forced else '-'} |"
    return row, is_forced


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", type=Path, nargs="+")
    args = parser.parse_args(argv)
    plugins = registry.discover()
    rows = sorted(r for folder in args.runs for r in refusals(folder))
    print("| scene | clause | check | the clause | moved before it | on the start scene | forced |")
    print("|---|---:|---|---|---|---|---|")
    count = 0
    for scene_id, sentence, error in rows:
        row, is_forced = forced(scene_id, sentence, error, plugins)
        count += is_forced
        print(row)
    print(f"\nforced by the start: {count} of {len(rows)} refused")
    return 0


if __name__ == "__main__":
    sys.exit(main())
