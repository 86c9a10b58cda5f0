"""Two `l2p-bullet evaluate --chains 5` runs compared seed for seed, on the seeds both ran.

    python benchmarks/compare_chain_runs.py OLD_DIR NEW_DIR

Prints a table (CALVIN's success of the first 1..5 clauses, the average completed, the chains refused up front and
their causes, planning a chain against its clauses alone) for each run, then every seed whose chain completed a
different number of clauses, worse ones with the new run's refusal. Only the runs' results.sqlite is read (the
evaluate contract, docs/evaluate.md); nothing is written.
"""

from __future__ import annotations

import argparse
import json
import re
import sqlite3
import statistics
import sys
from collections import Counter
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Chain:
    """One seed's chain as a run recorded it."""

    completed: int
    refused: str | None  # the refusal's cause ("blocked-around"), None where the chain was performed
    error: str
    ratio: float | None  # planning the chain over planning its clauses alone


def load(folder: Path) -> dict[int, Chain]:
    """Each seed's chain of the run in ``folder``."""
    db = folder / "results.sqlite"
    if not db.is_file():
        raise SystemExit(f"error: {db} does not exist: give an `l2p-bullet evaluate --chains` output folder")
    out = {}
    with sqlite3.connect(f"file:{db}?mode=ro", uri=True) as con:
        for seed, completed, kind, error, timings in con.execute(
                "select seed, completed, error_type, error, timings from runs"):
            cause = re.search(r"\(([a-z-]+)\)", error or "") if kind == "refused" else None
            t = json.loads(timings or "{}")
            ratio = t["forecast"] / t["forecast_alone"] if t.get("forecast") and t.get("forecast_alone") else None
            out[seed] = Chain(completed or 0, (cause.group(1) if cause else "?") if kind == "refused" else None,
                              error or "", ratio)
    return out


def row(name: str, chains: list[Chain]) -> str:
    """A table row: CALVIN's 1..5, the average, the refusals and their causes, the planning ratios."""
    n = len(chains)
    calvin = " | ".join(f"{100 * sum(c.completed >= k for c in chains) / n:.1f} %" for k in range(1, 6))
    refused = Counter(c.refused for c in chains if c.refused)
    causes = ", ".join(f"{k} {v}" for k, v in refused.most_common())
    ratios = [c.ratio for c in chains if c.ratio is not None]
    planning = f"{statistics.fmean(ratios):.2f} mean, {statistics.median(ratios):.2f} median" if ratios else "-"
    return (f"| {name} | {calvin} | {sum(c.completed for c in chains) / n:.2f} | {sum(refused.values())} of {n}"
            f"{f' ({causes})' if causes else ''} | {planning} |")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old", type=Path)
    parser.add_argument("new", type=Path)
    args = parser.parse_args(argv)
    old, new = load(args.old), load(args.new)
    seeds = sorted(set(old) & set(new))
    if not seeds:
        print("error: the two runs share no seed", file=sys.stderr)
        return 2
    print(f"{len(seeds)} seeds both ran, {seeds[0]}-{seeds[-1]}\n")
    print("| run | 1 | 2 | 3 | 4 | 5 | average completed | refused up front | planning / clauses alone |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    print(row(str(args.old), [old[s] for s in seeds]))
    print(row(str(args.new), [new[s] for s in seeds]))
    changed = [s for s in seeds if old[s].completed != new[s].completed]
    more = sum(new[s].completed > old[s].completed for s in changed)
    print(f"\n{len(changed)} chains changed: {more} completed more, {len(changed) - more} fewer")
    for s in changed:
        print(f"  {s}: {old[s].completed} -> {new[s].completed}"
              + (f"  {new[s].error[:120]}" if new[s].completed < old[s].completed else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
