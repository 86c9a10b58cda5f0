"""Benchmark the taught composite "row" (issue 21 part 3): rows of 3, 4 and 5 blocks on random scenes.

    nice .venv/bin/python benchmarks/bench_rows.py --no-render                  # the goal size: 100 x 3 sizes
    nice .venv/bin/python benchmarks/bench_rows.py --scenes 20 --sizes 4 --json rows.json

Each scene is ``teach/rows.py: row_scene(seed, n)``: n 4 cm cubes scattered on the table (A and B as the
evaluation's random two-block scenes, the others anywhere in the arm's workspace), seeds --seed ..
--seed+N-1 (disjoint from the teach page's scenes 0..N and its performance scenes 100000+). The sentence
is "make a row of A, B, ... and X" with the blocks in scene order; it runs as ``perform`` runs it (a chain
of the learned single action, each clause planned by the learned progress model towards the recipe's
slot, one episode in PyBullet, without video). A scene ends as a row when every consecutive gap is at most
0.35 block side, every centre lies within 0.25 side of the fitted line and no block was knocked (moved
> 1 mm by a clause that did not move it) (``chain/composite.py: row_verdict``). Sizes are interleaved
scene by scene, and every scene's row is appended to ``--rows`` as it finishes, so a run cut short still
reports every size evenly.

Goal (issue 21): >= 95 % rows for each of 3, 4 and 5 blocks, with the recipe taught from <= 10 rows of
2 and 3 blocks recorded on the teach page (the built-in ``row`` bundle: tests/teach/test_teach_rows_browser.py).
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path


def run_one(n: int, seed: int, out: Path, plugins: list, bundle_dir: Path | None) -> dict:
    """Perform a row of ``n`` on scene ``seed``; one result row."""
    from l2p_bullet.chain import perform_chain
    from l2p_bullet.errors import L2PError
    from l2p_bullet.teach.rows import row_scene, row_sentence

    scene = row_scene(seed, n)
    names = [o.name for o in scene.objects]
    sentence = row_sentence("make a row of", names)
    t0 = time.perf_counter()
    row: dict = {"blocks": n, "seed": seed, "sentence": sentence}
    try:
        r = perform_chain(sentence, scene, out_dir=out / f"{n}-{seed}", render=False, force=True, seed=seed,
                          plugins=plugins)
    except L2PError as e:  # refused up front (a clause that cannot be planned): counted as not a row
        row.update(success=False, refused=True, reason=f"{type(e).__name__}: {e}")
    else:
        row.update(success=r.success, refused=False, completed=r.completed, reason=r.verdict()["reason"],
                   row=r.row, clause_failures=[c.failed_stage or "judge" for c in r.results if not c.success],
                   target_errors_m=[c.plan.extra.get("target_error_m") if c.plan else None for c in r.results],
                   final_errors_m=[c.final_error_m for c in r.results])
    row["seconds"] = round(time.perf_counter() - t0, 2)
    return row


def report(rows: list[dict]) -> str:
    lines = ["blocks  scenes  rows     %      refused  clause-failed  max gap  max off  knocked  s/scene"]
    for n in sorted({r["blocks"] for r in rows}):
        rs = [r for r in rows if r["blocks"] == n]
        ok = sum(r["success"] for r in rs)
        judged = [r["row"] for r in rs if r.get("row")]
        lines.append(
            f"{n:>6}  {len(rs):>6}  {ok:>4}  {100 * ok / len(rs):>6.1f}  {sum(r['refused'] for r in rs):>7}  "
            f"{sum(bool(r.get('clause_failures')) for r in rs):>13}  "
            f"{max((j['max_gap_sides'] for j in judged), default=float('nan')):>7.2f}  "
            f"{max((j['max_offset_sides'] for j in judged), default=float('nan')):>7.2f}  "
            f"{sum(bool(j['knocked']) for j in judged):>7}  {sum(r['seconds'] for r in rs) / len(rs):>7.1f}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", type=int, default=100, help="scenes per row length (goal size 100)")
    ap.add_argument("--sizes", default="3,4,5", help="row lengths, comma-separated")
    ap.add_argument("--seed", type=int, default=50_000, help="first scene seed")
    ap.add_argument("--composite", default=None, help="a composite bundle folder to use instead of the installed row")
    ap.add_argument("--no-render", action="store_true", help="accepted for symmetry: the benchmark never renders")
    ap.add_argument("--out", default=None, help="run folders (default: a temporary one, deleted)")
    ap.add_argument("--rows", default=None, help="append each scene's result row here (JSON lines)")
    ap.add_argument("--json", dest="json_out", default=None, help="also write the rows and the table here")
    args = ap.parse_args(argv)

    from l2p_bullet.plugins import registry

    sizes = [int(s) for s in args.sizes.split(",") if s.strip()]
    plugins = registry.discover()
    bundle_dir = Path(args.composite) if args.composite else None
    if bundle_dir is not None:
        plugins.append(registry.local("row", bundle_dir))
    tmp = None if args.out else tempfile.TemporaryDirectory(prefix="bench-rows-")
    out = Path(args.out or tmp.name)
    rows: list[dict] = []
    started = time.perf_counter()
    try:
        for i in range(args.scenes):
            for n in sizes:
                row = run_one(n, args.seed + i, out, plugins, bundle_dir)
                rows.append(row)
                if args.rows:
                    with open(args.rows, "a") as f:
                        f.write(json.dumps(row) + "\n")
                print(f"[{time.perf_counter() - started:7.0f}s] {n} blocks, seed {row['seed']}: "
                      f"{'row' if row['success'] else 'NOT a row'} ({row['reason'][:100]})", file=sys.stderr)
    finally:
        if tmp is not None:
            tmp.cleanup()
    text = report(rows)
    print(text)
    if args.json_out:
        Path(args.json_out).write_text(json.dumps({"rows": rows, "table": text}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
