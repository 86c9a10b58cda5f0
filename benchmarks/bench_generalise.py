"""Validation without grades (issue 25): the suite of ``research/generalise.py`` for training recipes.

For each recipe, every action's model is trained on one person's capture session and scored on the
other person's demonstrations, both ways (10 trainings a recipe, cached under ``--cache``): full and
partial events, the other actions' events, the same events as planner moves, and exploit probes made
from them. Prints one Markdown table per recipe and a summary (the suite score, goals met). No grade
is read.

    nice -n 10 .venv/bin/python benchmarks/bench_generalise.py --recipes current,planner --ensemble 3 --epochs 20
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import torch

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # research/ sits beside the package, not in it

from l2p_bullet.core.vocabulary import ACTIONS  # noqa: E402
from l2p_bullet.learning.training_plan import plans  # noqa: E402
from research import generalise as g  # noqa: E402
from research.heldout import FOLDS  # noqa: E402
from research.sessions import run_suite  # noqa: E402


def table(name: str, reps: dict[str, g.ActionReport]) -> str:
    head = ("| action | full | 25/50/75 % | partial MAE | monotone | worst other (contained) | "
            "straight / rings / grid | domain gap | probe / plain | probe below |")
    lines = [f"### {name}: suite score {g.suite_score(reps):.3f}, strengthened {g.strong_score(reps):.3f}\n",
             head + " ordered (all: chains) |", "|" + "---|" * 11]
    for a in ACTIONS:
        r = reps[a]
        worst = max((b for b in r.row if b not in g.CONTAINED.get(a, ())), key=lambda b: r.row[b])
        cont = "" if a not in g.CONTAINED else f" ({r.contained:.2f})"
        lines.append(
            f"| {a} | {r.full:.2f} | {'/'.join(f'{p:.2f}' for p in r.partial)} | {r.partial_mae:.2f} | "
            f"{r.monotone:.0%} | {r.off:.2f} {worst}{cont} | "
            f"{' / '.join(f'{r.domains[k]:.2f}' for k in g.DOMAINS)} | {r.domain_gap:.2f} | "
            f"{r.probe:.2f} / {r.plain:.2f} | {r.probe_below:.0%} | {r.ordered['all']:.0%}: "
            + ", ".join(f"{k} {v:.0%}" for k, v in r.ordered.items() if k != "all") + " |")
    met = {a: sum(g.goals_met(reps[a]).values()) for a in ACTIONS}
    lines.append("\ngoals met (full >= 0.8, off <= 0.2, monotone >= 90 %, ordered >= 80 %): "
                 + ", ".join(f"{a} {n}/4" for a, n in met.items()))
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--recipes", default="current", help="comma-separated names (or 'all-recipes')")
    ap.add_argument("--ensemble", type=int, default=3)
    ap.add_argument("--epochs", type=int, default=20)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--cache", type=Path, default=Path("runs/generalise"),
                    help="trained session-split models are kept here (outside git)")
    ap.add_argument("--trusted-only", action="store_true",
                    help="train without the demonstrations whose tracking is not trusted (data.demos.UNTRUSTED; "
                         "they are never scored): the fifth round's variant (use its own --cache)")
    ap.add_argument("--one-way", action="store_true",
                    help="train on Session 1 and score on Session 2 only (5 trainings a recipe; a smoke run)")
    args = ap.parse_args()
    torch.set_num_threads(1)
    known = plans(args.ensemble, args.epochs)
    names = list(known) if args.recipes == "all-recipes" else args.recipes.split(",")
    unknown = [n for n in names if n not in known]
    if unknown:
        sys.exit(f"error: unknown recipe(s) {', '.join(unknown)} (known: {', '.join(known)})")
    summary = []
    for n in names:
        t0 = time.perf_counter()
        reps = run_suite(known[n], args.cache, log=lambda s: print(s, file=sys.stderr, flush=True), seed=args.seed,
                         untrusted=not args.trusted_only, folds=1 if args.one_way else len(FOLDS))
        print(table(f"{n} ({args.ensemble} LSTMs x {args.epochs} epochs, seed {args.seed})", reps) + "\n", flush=True)
        summary.append((n, g.suite_score(reps), g.strong_score(reps),
                        sum(sum(g.goals_met(r).values()) for r in reps.values()), time.perf_counter() - t0))
    print("| recipe | suite score | strengthened | goals met (of 20) | seconds |\n|---|---:|---:|---:|---:|")
    for n, s, s2, m, t in summary:
        print(f"| {n} | {s:.3f} | {s2:.3f} | {m} | {t:.0f} |")


if __name__ == "__main__":
    main()
