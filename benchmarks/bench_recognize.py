"""Recognition benchmark: which action is this motion, on people the models never saw.

Each built-in action's progress model is trained on one capture session (one person; all five actions'
demonstrations of that session, the shipped recipe unchanged: ``research/sessions.py``) and
the other session's demonstrations are recognised with ``l2p-bullet recognize``'s own code
(:func:`l2p_bullet.recognition.recognize`: every action's final progress for each moved block
against the other, ranked; the demonstration smoothed and cut to its event as ``recognize --demo``
does). Both ways: Session 1 -> 2 (where the recognition settings were looked at) and Session 2 -> 1
(held out). SlideToward's extra Session 3 is not used. Prints per split the confusion matrix (rows:
the demonstrated action, columns: the best reading's action), the five-way accuracy over the
demonstrations, the accuracy with "closer" and "next to" merged (people confuse them too), the
per-action recall, and how often the best reading names the block that really moved.

    nice .venv/bin/python benchmarks/bench_recognize.py                  # trains 2 x 5 models if not cached
    nice .venv/bin/python benchmarks/bench_recognize.py --cache /tmp/rec  # elsewhere
    nice .venv/bin/python benchmarks/bench_recognize.py --rule mse        # a tried whole-curve ranking

The session models are cached in ``--cache`` (default ``benchmarks/.cache/recognize``, not in git) and
re-used while their demonstrations and recipe are unchanged; training all ten takes a few minutes of one
core (the time is printed from their manifests).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # research/ sits beside the package, not in it

from l2p_bullet.core.vocabulary import ACTIONS  # noqa: E402
from l2p_bullet.learning.train_progress import all_demos  # noqa: E402
from l2p_bullet.plugins.bundle import load_bundle  # noqa: E402
from l2p_bullet.recognition import Reading, Recogniser, Tracks, demo_event_tracks, recognize  # noqa: E402
from research.sessions import bundle_seconds, session_bundles  # noqa: E402

FOLDS = [("Session1", "Session2"), ("Session2", "Session1")]
MERGED = ("closer", "next-to")
"""The two actions people confuse (the 3-D study) and the merged accuracy counts as one."""


def recognisers(folders: dict[str, Path]) -> list[Recogniser]:
    out = []
    for action, folder in folders.items():
        b = load_bundle(folder)
        out.append(Recogniser(action, b.phrases[0], b.progress_model()))
    return out


def ramp_best(tracks: Tracks, models: list[Recogniser], rule: str) -> Reading:
    """The best reading by a tried rule that reads the whole curve (docs/learning.md, recognition's third
    pass; not adopted): ``mse``/``mae``, the lowest mean squared/absolute distance of the resampled curve to
    the arc-length ramp its training label follows; ``final-mae``, the highest final minus that distance.
    The readings are :func:`recognize`'s own (ties keep its order); only their ranking differs."""
    model = {r.action: r.model for r in models}

    def key(reading: Reading) -> float:
        p, s = model[reading.action].resampled(tracks.poses[reading.mover], tracks.poses[reading.anchors[0]],
                                               tracks.sizes[reading.mover], viewer=tracks.viewer)
        gap = np.abs(p - s)
        return float({"mse": np.mean(gap ** 2), "mae": np.mean(gap), "final-mae": np.mean(gap) - p[-1]}[rule])

    return min(recognize(tracks, models).readings, key=key)


def evaluate_split(models: list[Recogniser], test: str, rule: str = "final") -> dict:
    """Confusion counts (truth x best reading), and how often the best reading's mover is the real one."""
    conf = np.zeros((len(ACTIONS), len(ACTIONS)), int)
    right_mover = 0
    demos = all_demos(sessions={test})
    for i, a in enumerate(ACTIONS):
        for d in demos[a]:
            tracks = demo_event_tracks(d)
            best = recognize(tracks, models).best if rule == "final" else ramp_best(tracks, models, rule)
            conf[i, ACTIONS.index(best.action)] += 1
            right_mover += best.mover == "A"
    n = int(conf.sum())
    ia, ib = (ACTIONS.index(x) for x in MERGED)
    merged_right = np.trace(conf) + conf[ia, ib] + conf[ib, ia]
    return {"conf": conf, "n": n, "five": np.trace(conf) / n, "merged": merged_right / n,
            "recall": np.diag(conf) / conf.sum(1), "right_mover": right_mover / n}


def fmt(name: str, r: dict) -> str:
    lines = [
        f"**{name}** ({r['n']} demonstrations): five-way {100 * r['five']:.1f} %, closer+next-to merged "
        f"{100 * r['merged']:.1f} %, balanced (mean recall) {100 * np.mean(r['recall']):.1f} %, "
        f"best reading names the real mover {100 * r['right_mover']:.0f} %",
        "",
        "| shown \\ recognised | " + " | ".join(ACTIONS) + " | recall |",
        "|---" + "|---:" * (len(ACTIONS) + 1) + "|",
    ]
    for i, a in enumerate(ACTIONS):
        cells = [f"**{v}**" if i == j else str(v) for j, v in enumerate(r["conf"][i])]
        lines.append(f"| {a} | " + " | ".join(cells) + f" | {100 * r['recall'][i]:.0f} % |")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cache", default="benchmarks/.cache/recognize", help="Folder of the session models.")
    ap.add_argument("--seed", type=int, default=0, help="Training seed of the session models.")
    ap.add_argument("--rule", choices=["final", "mse", "mae", "final-mae"], default="final",
                    help="How readings are ranked: final progress (recognize's rule) or a tried whole-curve rule.")
    ap.add_argument("--quick", action="store_true",
                    help="1 LSTM x 2 epochs per session model (smoke run; use its own --cache)")
    ap.add_argument("--one-way", action="store_true",
                    help="only Session 1 -> 2 (5 session models trained instead of 10; a smoke run)")
    args = ap.parse_args()
    folds = FOLDS[:1] if args.one_way else FOLDS
    recipe = None
    if args.quick:
        import dataclasses

        from l2p_bullet.learning.training_plan import SHIPPED

        recipe = dataclasses.replace(SHIPPED, train=dataclasses.replace(SHIPPED.train, ensemble=1, epochs=2))
    cmd = "nice .venv/bin/python benchmarks/bench_recognize.py" + (
        f" --cache {args.cache}" if args.cache != "benchmarks/.cache/recognize" else "") + (
        f" --seed {args.seed}" if args.seed else "") + (f" --rule {args.rule}" if args.rule != "final" else "") + (
        " --quick" if args.quick else "") + (" --one-way" if args.one_way else "")
    t0 = time.perf_counter()
    folders = {
        s: session_bundles(
            s,
            Path(args.cache) / s,
            seed=args.seed,
            command=cmd,
            recipe=recipe,
            log=lambda m: print(m, file=sys.stderr, flush=True),
        )
        for s in dict.fromkeys(train for train, _ in folds)
    }
    t_train = time.perf_counter() - t0
    recorded = {s: sum(bundle_seconds(f) for f in fs.values()) for s, fs in folders.items()}
    results = {}
    t1 = time.perf_counter()
    for train, test in folds:
        results[(train, test)] = evaluate_split(recognisers(folders[train]), test, args.rule)
    t_rec = time.perf_counter() - t1
    print(f"# Recognition on people the models never saw ({cmd})\n")
    size = "1 LSTM x 2 epochs" if args.quick else "5 LSTMs x 30 epochs"
    print("Session models: shipped recipe ({}, seed {}), trained in {:.0f} s (Session1) and "
          "{:.0f} s (Session2) as recorded in their manifests; {:.0f} s spent training in this run (0 when cached)."
          .format(size, args.seed, recorded["Session1"], recorded.get("Session2", float("nan")), t_train))
    print(f"Recognising the {sum(r['n'] for r in results.values())} demonstrations: {t_rec:.1f} s.\n")
    for (train, test), r in results.items():
        tag = " (settings looked at here)" if train == "Session1" else " (held out)"
        print(fmt(f"train {train} -> recognise {test}{tag}", r) + "\n")
    both = sum(r["conf"] for r in results.values())
    n = int(both.sum())
    ia, ib = (ACTIONS.index(x) for x in MERGED)
    together = "Both splits together" if len(folds) > 1 else "The one split"
    print(f"**{together}** ({n}): five-way {100 * np.trace(both) / n:.1f} %, merged "
          f"{100 * (np.trace(both) + both[ia, ib] + both[ib, ia]) / n:.1f} %")


if __name__ == "__main__":
    main()
