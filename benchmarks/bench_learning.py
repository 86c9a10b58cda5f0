"""Learning benchmark: training time, scoring throughput, session-split evaluation, agreement with people.

Prints (tables in Markdown, pasted into docs/learning.md):
1. training time per action (the shipped bundles' settings, all demonstrations);
2. scoring throughput of the shipped bundles, sequences/s at batch 1 and 256, for random paths and
   for planner-style candidates that extend one shared path;
3. the honest session split (train on one person, test on the other, both ways): held-out MSE, final
   progress on the same action's held-out demonstrations and the 5x5 discrimination matrix;
4. Spearman(final progress, mean human grade) per graded folder, for the shipped bundles (trained on
   all human demonstrations, never on grades) and for the session-split models' ensemble.

    .venv/bin/python benchmarks/bench_learning.py            # everything (~10-20 min on 2 busy cores)
    .venv/bin/python benchmarks/bench_learning.py --quick    # 1 LSTM x 10 epochs per model
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import numpy as np
import torch

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # research/ sits beside the package, not in it

from l2p_bullet.core.vocabulary import ACTIONS  # noqa: E402
from l2p_bullet.learning.agreement import graded_motions, model_agreement  # noqa: E402
from l2p_bullet.learning.progress_net import ProgressModel  # noqa: E402
from l2p_bullet.learning.train_progress import ProgressTrainConfig, all_demos, train_action  # noqa: E402
from l2p_bullet.plugins.bundle import builtin_bundle_dir, load_bundle  # noqa: E402
from research.heldout import session_split  # noqa: E402


def throughput(model, batch: int, shared_prefix: bool, repeats: int = 5) -> float:
    rng = np.random.default_rng(0)
    size = 0.05
    base = np.cumsum(np.concatenate([[[0.2, 0.1, 0]], rng.normal(0, 0.02, (20, 3))]), axis=0)
    if shared_prefix:  # the planner's candidates: the path so far plus one new move each
        movers = [np.concatenate([base, base[-1] + np.linspace(0, 1, 5)[1:, None] * rng.normal(0, 0.04, 3)])
                  for _ in range(batch)]
    else:
        movers = [np.cumsum(np.concatenate([[[0.2, 0.1, 0]], rng.normal(0, 0.02, (20, 3))]), axis=0)
                  for _ in range(batch)]
    model.final_batch(movers, np.zeros(3), size)  # warm-up
    t = time.perf_counter()
    for _ in range(repeats):
        model.final_batch(movers, np.zeros(3), size)
    return batch * repeats / (time.perf_counter() - t)


def probes() -> dict[str, np.ndarray]:
    """Motions a planner maximising progress could exploit, and plain instances for contrast (blocks)."""
    rng = np.random.default_rng(0)

    def line(p0, p1, n=40):
        return np.linspace(np.r_[p0, 0.0], np.r_[p1, 0.0], n)

    def circle(radius, turns):
        a = np.linspace(0, 2 * np.pi * turns, int(100 * turns) + 2)
        return np.column_stack([radius * np.cos(a), radius * np.sin(a), np.zeros(len(a))])

    return {
        "stand still": np.repeat([[3.0, 0, 0]], 30, axis=0),
        "jitter in place": np.r_[[[3.0, 0, 0]]] + np.cumsum(rng.normal(0, 0.03, (60, 3)), axis=0) * [1, 1, 0],
        "far jump (3 -> 15 blocks)": line((3, 0), (15, 2)),
        "far jump and back": np.concatenate([line((3, 0), (15, 2)), line((15, 2), (3.2, 0.5))]),
        "back and forth x5": np.concatenate([line((3, 0), (4, 0), 10), line((4, 0), (3, 0), 10)] * 5),
        "circle of radius 10": circle(10, 1),
        "closer 3 -> 1.5": line((3, 0), (1.5, 0)),
        "away 3 -> 7": line((3, 0), (7, 0)),
        "straight past at 2": np.column_stack([np.full(40, -2.0), np.linspace(-4, 4, 40), np.zeros(40)]),
        "half circle r=3": circle(3, 0.5),
        "full circle r=3": circle(3, 1),
    }


def fmt_matrix(m: np.ndarray) -> str:
    lines = ["| model \\ demos | " + " | ".join(ACTIONS) + " |", "|---" * (len(ACTIONS) + 1) + "|"]
    for i, a in enumerate(ACTIONS):
        lines.append(f"| {a} | " + " | ".join(f"{v:.2f}" for v in m[i]) + " |")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="1 LSTM x 10 epochs per model (smoke run)")
    ap.add_argument("--skip-split", action="store_true", help="skip the session split (10 trainings)")
    ap.add_argument(
        "--epochs", type=int, default=None, help="epochs per model (default: the recipe's; 10 with --quick)"
    )
    ap.add_argument("--actions", default=",".join(ACTIONS),
                    help="comma-separated actions whose training is timed (default: all five; one for a smoke run)")
    ap.add_argument("--write-metrics", action="store_true",
                    help="store the results in the shipped bundles' [metrics] (manifest only, weights untouched)")
    args = ap.parse_args()
    cfg = ProgressTrainConfig()
    if args.quick:
        cfg = dataclasses.replace(cfg, ensemble=1, epochs=10)
    if args.epochs:
        cfg = dataclasses.replace(cfg, epochs=args.epochs)
    torch.set_num_threads(1)

    print(f"## Training time (all demonstrations, {cfg.ensemble} LSTMs x {cfg.epochs} epochs, 1 thread)\n")
    demos = all_demos()
    print("| action | seconds | sequences |\n|---|---|---|")
    total = 0.0
    timed = [a for a in ACTIONS if a in args.actions.split(",")]
    for a in timed:
        r = train_action(a, demos, cfg=cfg)
        total += r.seconds
        print(f"| {a} | {r.seconds:.1f} | {r.n_sequences} |", flush=True)
    print(f"| {'all five' if len(timed) == len(ACTIONS) else 'these'} | {total:.1f} | |\n")

    print("## Scoring throughput of the shipped bundles (sequences/s, 21-move paths, ~80 frames)\n")
    print("| action | batch 1 | batch 256 random | batch 256 shared prefix (planner) | ms per 256-call |")
    print("|---|---|---|---|---|")
    models = {a: ProgressModel.from_bundle(load_bundle(builtin_bundle_dir(a))) for a in ACTIONS}
    for a, m in models.items():
        b1 = throughput(m, 1, False, repeats=20)
        br = throughput(m, 256, False)
        bs = throughput(m, 256, True)
        print(f"| {a} | {b1:.0f} | {br:.0f} | {bs:.0f} | {256e3 / bs:.0f} |", flush=True)
    print()

    print("## Exploit probes: final progress of the shipped bundles (anchor at the origin, block units)\n")
    print("| motion | " + " | ".join(ACTIONS) + " |\n" + "|---" * (len(ACTIONS) + 1) + "|")
    for name, mv in probes().items():
        print(f"| {name} | " + " | ".join(f"{models[a].final(mv, np.zeros(3), 1.0):.2f}" for a in ACTIONS) + " |")
    print()

    motions = graded_motions()
    ga = model_agreement(models, motions)
    print("## Agreement with people: Spearman(final progress, mean grade), 15 graded demos each\n")
    print("| folder | action | shipped bundle |\n|---|---|---|")
    for folder, v in ga.items():
        print(f"| {folder} | {_action(folder)} | {v['spearman']:.2f} |")
    five = [v["spearman"] for f, v in ga.items() if f != "SlideAroundDiscrete"]
    print(f"| mean of the five actions | | {np.mean(five):.2f} |")
    print(f"| mean of all six folders | | {np.mean([v['spearman'] for v in ga.values()]):.2f} |\n")

    metrics = {a: {} for a in ACTIONS}
    for folder, v in ga.items():
        key = "graded_spearman" + ("_discrete" if folder.endswith("Discrete") else "")
        metrics[_action(folder)][key] = round(float(v["spearman"]), 3)
    if args.skip_split:
        _write(metrics, args.write_metrics)
        return
    print("## Session split (train on one person's session, test on the other's; mean of both ways)\n")
    rep = session_split(cfg, on_model=lambda a, s, t: print(f"  trained {a} on {s} in {t:.1f} s", flush=True))
    print("\n| action | held-out MSE | final, same action (with context) | final, event only |")
    print("|---|---|---|---|")
    for a in ACTIONS:
        print(f"| {a} | {rep.mse[a]:.4f} | {rep.final_same[a]:.2f} | {rep.final_event_only[a]:.2f} |")
    print("\nDiscrimination matrix: row = model, column = held-out demonstrations of that action "
          "(final progress; the diagonal should be high, the rest low)\n")
    print(fmt_matrix(rep.matrix))
    for i, a in enumerate(ACTIONS):
        metrics[a].update({
            "split_mse": round(rep.mse[a], 4), "split_final_same": round(rep.final_same[a], 3),
            "split_final_event_only": round(rep.final_event_only[a], 3),
            "split_final_on_others": {b: round(float(rep.matrix[i, j]), 3) for j, b in enumerate(ACTIONS) if b != a},
            "split_note": "trained on one person's session, tested on the other's, both ways (bench_learning.py)",
        })
    _write(metrics, args.write_metrics)


def _write(metrics: dict, enabled: bool) -> None:
    if not enabled:
        return
    from l2p_bullet.plugins.bundle import update_manifest

    for a, values in metrics.items():
        update_manifest(builtin_bundle_dir(a), "metrics", values)
    print("\nwrote [metrics] into the five shipped manifests")


def _action(folder: str) -> str:
    from l2p_bullet.core.vocabulary import GRADED_FOLDERS

    return GRADED_FOLDERS[folder]


if __name__ == "__main__":
    main()
