"""Benchmark feedback from people's grades: agreement with people, cross-validated, for each kind of feedback.

    nice -n 10 .venv/bin/python benchmarks/bench_feedback.py                  # the full table (~30-40 min, 1 core)
    .venv/bin/python benchmarks/bench_feedback.py --quick                    # 1 LSTM x 5 epochs, 2 folds (smoke)
    .venv/bin/python benchmarks/bench_feedback.py --only shipped,cold        # some columns only

Columns (Spearman(final progress, mean grade) per graded folder, 15 demos each, and the mean of the six):

- shipped:   the installed bundles, never trained on grades (what docs/learning.md reports);
- demos:     the same recipe re-trained here on the demonstrations only (the base every fine-tuning starts from);
- cold:      the original project's cold feedback, cross-validated: only the clear cases of the training
             folds (mean grade <= 3.5 -> 0, >= 7 -> 1; away <= 4.5, around 1.5 / 5.5, as in its code),
             fine-tuned 10 epochs on those alone;
- rules:     automatic feedback, as ``train --feedback-judge rules``: the demonstration-trained model plans
             30 scenes (seeds 5000 on; random search with back-up stopped after 40, 6 and 2 steps), the
             rule judge grades the plans 10 x its score, the model is fine-tuned on them; it sees no
             grade, so it is scored on all 90 demos without folds;
- grades:    ``train --feedback`` (target = mean grade / 10), cross-validated with nested selection: each
             outer fold chooses the feedback weight among ``--weights`` by a 3-fold inner CV on its own
             training folds; the folds reported were never used to choose anything;
- head:      a model of the grade with few parameters instead of a fine-tuned LSTM: a ridge regression of
             grade / 10 on six numbers of a motion's last frame (the shipped model's final progress as a
             logit, log distance ratio to the start, gap, angle swept, path length, displacement), fitted per
             action on the training folds, the ridge strength chosen by a 3-fold inner CV among
             ``HEAD_ALPHAS``; repeated over ``--head-seeds`` fold seeds (the column is their mean, and the
             spread of the six-folder mean over seeds is printed: the noise of a 15-demo CV).

k = 5 folds stratified by folder, fold seed 0, model seed 0. One torch thread throughout.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from pathlib import Path

import numpy as np
import torch

COLUMNS = ("shipped", "demos", "cold", "rules", "grades", "head")
HEAD_COLUMNS = ("log_dist_ratio", "gap", "swept_abs", "path_length", "displacement")
HEAD_ALPHAS = (0.3, 1.0, 3.0, 10.0, 30.0, 100.0)


def log(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="1 LSTM x 5 epochs, 2 folds, one weight (smoke run)")
    ap.add_argument("--only", default=",".join(COLUMNS), help="comma-separated columns to compute")
    ap.add_argument("--folds", type=int, default=5)
    ap.add_argument("--fold-seed", type=int, default=0)
    ap.add_argument("--weights", default="0.3,1.0,3.0", help="feedback weights the inner CV chooses among")
    ap.add_argument("--head-seeds", type=int, default=10, help="fold seeds the head column is averaged over")
    ap.add_argument("--judge-scenes", type=int, default=30)
    ap.add_argument("--json", type=Path, default=None, help="also write every prediction and choice here")
    ap.add_argument("--base-cache", type=Path, default=None,
                    help="folder keeping the demonstration-only ensembles between runs (re-trained when the "
                         "training settings differ)")
    args = ap.parse_args()
    torch.set_num_threads(1)

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # research/ sits beside the package, not in it
    from l2p_bullet.core.vocabulary import ACTIONS, GRADED_FOLDERS
    from l2p_bullet.judge import RuleJudge
    from l2p_bullet.learning.feedback import folder_agreement, original_items, score_items
    from l2p_bullet.learning.feedback_targets import judge_items
    from l2p_bullet.learning.train_progress import JUDGE_SEEDS, ProgressTrainConfig, all_demos
    from l2p_bullet.plugins.bundle import builtin_bundle_dir, load_bundle
    from research.agreement_cv import FineTuner, cross_validate, select

    cfg = ProgressTrainConfig()
    k, weights = args.folds, [float(w) for w in args.weights.split(",")]
    if args.quick:
        cfg = dataclasses.replace(cfg, ensemble=1, epochs=5)
        k, weights = 2, weights[:1]
    cols = [c for c in args.only.split(",") if c]
    items = original_items()
    t0 = time.perf_counter()
    tuner = FineTuner(
        all_demos(), cfg=cfg, log=log, base=_cached_base(args.base_cache, cfg) if args.base_cache else None
    )
    res: dict[str, dict] = {}

    if "shipped" in cols:
        bundles = {a: load_bundle(builtin_bundle_dir(a)) for a in ACTIONS}
        finals = {}
        for a in ACTIONS:
            finals.update(score_items(bundles[a].progress_model(), [it for it in items if it.action == a]))
        res["shipped"] = {"spearman": folder_agreement(items, finals), "finals": finals}
    if "demos" in cols:
        log("demos only")
        finals = {}
        for a in ACTIONS:
            finals.update(score_items(tuner(a, [], {}), [it for it in items if it.action == a]))
        res["demos"] = {"spearman": folder_agreement(items, finals), "finals": finals}
    if "cold" in cols:
        log("cold feedback (the original's clear cases, feedback only), cross-validated")
        rep = cross_validate(tuner, items, k=k, seed=args.fold_seed, grid=({"target": "clear", "demo_fraction": 0.0},),
                             log=log)
        res["cold"] = {"spearman": rep.spearman, "finals": rep.finals}
    if "rules" in cols:
        log(f"automatic feedback: rule-judged plans on {args.judge_scenes} scenes per action")
        finals = {}
        for a in ACTIONS:
            auto = judge_items(a, tuner(a, [], {}), range(JUDGE_SEEDS, JUDGE_SEEDS + args.judge_scenes), RuleJudge(a),
                               log=log)
            finals.update(score_items(tuner(a, auto, {}), [it for it in items if it.action == a]))
        res["rules"] = {"spearman": folder_agreement(items, finals), "finals": finals}
    if "grades" in cols:
        log(f"grades, nested CV over weights {weights}")
        rep = cross_validate(tuner, items, k=k, seed=args.fold_seed, grid=[{"weight": w} for w in weights],
                             log=log)
        res["grades"] = {"spearman": rep.spearman, "finals": rep.finals, "choices": rep.choices}
        for c in rep.choices:
            print(f"fold {c['fold']}: chose {c['setting']} (inner means {c['inner_mean']})")
        if len(weights) > 1:
            log("the weight for the shipped bundles: the same choice, by a CV over all 90 demos")
            best, scores = select(tuner, items, [{"weight": w} for w in weights], k, args.fold_seed, log)
            res["grades"]["shipped_choice"] = {"setting": best, "cv_means": scores}
            print(f"for the shipped bundles (CV over all 90, selection-biased, not a result): {best}, "
                  f"means {dict(zip(weights, scores, strict=True))}")
    if "head" in cols:
        log(f"grade head (ridge on the last frame), nested CV, fold seeds 0-{args.head_seeds - 1}")
        means, per = [], []
        for seed in range(args.head_seeds):
            rep = cross_validate(_head_trainer(items), items, k=k, seed=seed,
                                 grid=[{"alpha": a} for a in HEAD_ALPHAS])
            per.append(rep.spearman)
            means.append(rep.mean)
        res["head"] = {"spearman": {f: float(np.mean([p[f] for p in per])) for f in per[0]}, "seed_means": means}
        print(f"head: six-folder mean per fold seed {np.round(means, 3).tolist()}: "
              f"{np.mean(means):.3f} +- {np.std(means):.3f} (s.d.)")

    shown = [c for c in COLUMNS if c in res]
    print(f"\n## Agreement with people: Spearman(final progress, mean grade), {k}-fold CV where trained on grades\n")
    print("| folder | action | " + " | ".join(shown) + " |\n|---|---|" + "---:|" * len(shown))
    for folder in GRADED_FOLDERS:
        print(f"| {folder} | {GRADED_FOLDERS[folder]} | "
              + " | ".join(f"{res[c]['spearman'][folder]:.2f}" for c in shown) + " |")
    print("| mean of the six folders | | " + " | ".join(f"{np.mean(list(res[c]['spearman'].values())):.2f}"
                                                   for c in shown) + " |")
    print("| mean of the five actions' own folders (docs' earlier convention) | | "
          + " | ".join(f"{np.mean([v for f, v in res[c]['spearman'].items() if f != 'SlideAroundDiscrete']):.2f}"
                       for c in shown) + " |")
    print("| lowest action | | " + " | ".join(f"{_lowest(res[c]['spearman']):.2f}" for c in shown) + " |")
    print(f"\n{cfg.ensemble} LSTMs x {cfg.epochs} epochs, {time.perf_counter() - t0:.0f} s in all")
    if args.json:
        args.json.write_text(json.dumps(res, indent=1, default=float) + "\n")


def _cached_base(folder: Path, cfg) -> dict:
    """The demonstration-only ensembles of every action from ``folder`` (bundles written by an earlier run),
    trained and stored there when missing or trained with other settings."""
    from l2p_bullet.core.vocabulary import ACTIONS
    from l2p_bullet.learning.progress_net import ProgressModel, ensemble_arrays
    from l2p_bullet.learning.train_progress import all_demos, train_action, training_section
    from l2p_bullet.learning.trainset import DataConfig
    from l2p_bullet.plugins.bundle import load_bundle, write_progress_bundle

    out, demos = {}, all_demos()
    for a in ACTIONS:
        d = folder / a
        want = {"data": DataConfig().to_dict(), **cfg.to_dict()}
        try:
            b = load_bundle(d)
            t = b.manifest["training"]
            if {k: t.get(k) for k in want} == want:
                out[a] = ProgressModel.from_bundle(b).nets
                continue
        except Exception:  # missing or stale: train it below
            pass
        log(f"  training {a} on the demonstrations for the cache ({cfg.ensemble} x {cfg.epochs} epochs)")
        r = train_action(a, demos, cfg=cfg)
        write_progress_bundle(d, a, ensemble_arrays(r.model.nets), r.model.model_cfg, r.model.qsr_cfg,
                              training=training_section(r, cfg, 0, "bench_feedback.py base"), metrics={})
        out[a] = r.model.nets
    return out


def _head_trainer(items: list):
    """Trainer for :func:`cross_validate`: per action, a ridge regression of grade / 10 on the last frame's
    numbers (:data:`HEAD_COLUMNS` and the shipped model's final progress as a logit), standardised on
    the training items; ``alpha`` penalises every weight but the intercept."""
    from l2p_bullet.plugins.bundle import builtin_bundle_dir, load_bundle
    from l2p_bullet.progress.features import feature_names, motion_features

    models, rows = {}, {}
    for it in items:
        if it.action not in models:
            m = load_bundle(builtin_bundle_dir(it.action)).progress_model()
            models[it.action] = m, [feature_names(m.qsr_cfg).index(c) for c in HEAD_COLUMNS]
        m, cols = models[it.action]
        p = float(np.clip(m.final_batch([it.mover], [it.anchor], it.size)[0], 1e-3, 1 - 1e-3))
        f, _ = motion_features(it.mover, it.anchor, it.size, m.qsr_cfg)
        rows[(it.mover.tobytes(), it.anchor.tobytes())] = np.r_[np.log(p / (1 - p)), f[-1, cols]]

    class Head:
        def __init__(self, train: list, alpha: float):
            A = np.array([rows[(it.mover.tobytes(), it.anchor.tobytes())] for it in train])
            y = np.array([it.grade for it in train]) / 10.0
            self.mu, self.sd, self.y0 = A.mean(0), A.std(0) + 1e-9, y.mean()
            Z = (A - self.mu) / self.sd
            self.w = np.linalg.solve(Z.T @ Z + alpha * np.eye(Z.shape[1]), Z.T @ (y - self.y0))

        def final_batch(self, movers, anchors, size):
            A = np.array([rows[(m.tobytes(), a.tobytes())] for m, a in zip(movers, anchors, strict=True)])
            return ((A - self.mu) / self.sd) @ self.w + self.y0

    return lambda action, train, setting: Head([it for it in train if it.action == action], setting["alpha"])


def _lowest(sp: dict[str, float]) -> float:
    """The lowest per-action agreement (around: the mean of its two folders)."""
    from l2p_bullet.core.vocabulary import GRADED_FOLDERS

    per: dict[str, list[float]] = {}
    for folder, v in sp.items():
        per.setdefault(GRADED_FOLDERS[folder], []).append(v)
    return min(float(np.mean(v)) for v in per.values())


if __name__ == "__main__":
    main()
