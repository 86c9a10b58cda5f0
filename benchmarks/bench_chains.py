"""Benchmark chains of instructions (issue 21 part 4): ``l2p-bullet evaluate --chains K``, judged as CALVIN is.

    .venv/bin/python benchmarks/bench_chains.py                       # 50 chains of 5, 1 worker
    .venv/bin/python benchmarks/bench_chains.py --chains 1000 --workers 8 --json out.json   # the goal size
    .venv/bin/python benchmarks/bench_chains.py --draw sentence --chains 100 --seed 8000   # drawn whole, refusals

Random scenes of 3-5 blocks (``evaluate/chains.py``: seeded, seeds --seed .. --seed+N-1), one chain of K
clauses each, drawn over the installed one-anchor actions and random mover/anchor pairs; a clause that
cannot be planned from the state the previous clauses' plans predict is drawn again (counted); with
``--draw sentence`` the chain's clauses are drawn first and the chain is planned as a whole, or refused up
front (the refusals counted by clause and check; issue 44). Each chain is performed as ``perform`` performs
one (one episode, each clause re-planned from the simulated world) and every clause judged on its own
frames by its action's judge. Printed: success of the first 1..K clauses, the average number completed,
per-action clause success, failures by stage, the largest move of a block a clause did not move, time per
chain.

Goal (issue 21): on 1,000 chains of 5, average completed >= 4.8, one-clause success equal to today's
single-action success within 1 %, no block other than the mover moved > 1 mm, no crash, no failure
half-way through a clause's execution. The default size here (50) is what a shared machine runs in
minutes; the goal size is 1,000.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--chains", type=int, default=50, help="number of chains (one scene each); goal size 1000")
    ap.add_argument("--clauses", type=int, default=5, help="clauses per chain (K)")
    ap.add_argument("--seed", type=int, default=0, help="first scene seed")
    ap.add_argument("--draw", choices=("clause", "sentence"), default="clause",
                    help="draw each clause until it plans (clause), or the whole sentence first (sentence)")
    ap.add_argument("--workers", type=int, default=1, help="worker processes")
    ap.add_argument("--out", default=None, help="evaluation folder (default: a temporary one)")
    ap.add_argument("--json", dest="json_out", default=None, help="also write the numbers here")
    args = ap.parse_args(argv)

    from l2p_bullet.evaluate.chains import chain_report, chain_report_text
    from l2p_bullet.evaluate.runner import EvaluationConfig, evaluate, load_rows

    with tempfile.TemporaryDirectory(prefix="bench-chains-") as tmp:
        out = Path(args.out) if args.out else Path(tmp) / "eval"
        config = EvaluationConfig(chains=args.clauses, scenes=args.chains, seed=args.seed, chain_draw=args.draw)
        t0 = time.perf_counter()
        summary = evaluate(config, out, workers=args.workers, progressbar=True)
        wall = time.perf_counter() - t0
        rows = load_rows(out)
    rep = chain_report(rows)
    per_chain = [r["total_s"] for r in rows if r.get("total_s") is not None]
    rep |= {"wall_s": round(wall, 1), "workers": args.workers, "seed": args.seed, "draw": args.draw,
            "seconds_per_chain": round(sum(per_chain) / len(per_chain), 2) if per_chain else None,
            "runs": summary.ran, "errors_text": sorted({str(r["error"])[:120] for r in rows if r.get("error")})}
    print(chain_report_text(rep))
    print(f"{len(rows)} chains in {wall:.0f} s with {args.workers} worker(s), "
          f"{rep['seconds_per_chain']} s per chain in the worker")
    if args.json_out:
        Path(args.json_out).write_text(json.dumps(rep, indent=1, default=float) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
