"""Bundles trained on one capture session: models that have never seen the other person's motions.

The two capture sessions of each action were recorded by different people (data README), so a model
trained on Session 1 of every action and tested on Session 2 is tested on people it never saw. This is
the shipped training recipe unchanged (:data:`training_plan.SHIPPED`, what ``l2p-bullet train`` uses, with its
default settings, the other actions' demonstrations of the same session as negatives); only the demonstrations are
restricted, for all five actions at once: training "closer" on Session 1 with the other actions'
Session 2 demonstrations as negatives would show it the test person. SlideToward's extra Session 3 is
left out (as in :data:`heldout.FOLDS`). ``benchmarks/bench_recognize.py`` recognises the held-out
session with these bundles; they are written as ordinary bundle folders (``l2p-bullet score`` and
``recognize --actions`` read them) and re-used while their data digest and recipe still match.

The grade-free suite's session-split models (:func:`split_models`, :func:`run_suite`,
``benchmarks/bench_generalise.py``) are the same bundles, trained with the recipe compared
(:mod:`l2p_bullet.learning.training_plan`; the shipped one by default): one function trains on one session.
"""

from __future__ import annotations

import tempfile
from collections.abc import Callable
from pathlib import Path

from l2p_bullet.core.vocabulary import ACTIONS
from l2p_bullet.learning.progress_net import ProgressModel, ensemble_arrays
from l2p_bullet.learning.train_progress import all_demos, data_digest, training_section
from l2p_bullet.learning.train_progress import train_plan as train
from l2p_bullet.learning.training_plan import SHIPPED, own_trusted
from l2p_bullet.learning.training_plan import TrainingPlan as Recipe
from l2p_bullet.plugins.bundle import (
    MANIFEST,
    PROGRESS_FILE,
    load_bundle,
    read_manifest,
    write_progress_bundle,
)

from . import generalise as g
from .heldout import FOLDS
from .ordered_probes import ordered


def session_bundles(session: str, out: str | Path, *, actions: tuple[str, ...] = ACTIONS, seed: int = 0,
                    command: str = "", log: Callable[[str], None] | None = None,
                    recipe: Recipe | None = None, untrusted: bool = True) -> dict[str, Path]:
    """Train each of ``actions`` on capture ``session`` (e.g. "Session1") into ``out/<action>/``, with
    ``recipe`` (:mod:`l2p_bullet.learning.training_plan`; when None its :data:`SHIPPED`, what ``l2p-bullet train``
    uses);
    ``untrusted`` False: without the demonstrations whose tracking is not trusted (``all_demos``).

    A folder whose manifest already records the same data digest, seed and recipe is kept as it is
    (training all five takes minutes), so a benchmark can call this every time. Returns action -> folder.
    """
    out = Path(out)
    recipe = recipe or SHIPPED
    demos = all_demos(sessions={session}, untrusted=untrusted)
    folders = {}
    for action in actions:
        folder = out / action
        folders[action] = folder
        used = own_trusted(recipe, action, demos)  # what it trains on (its manifest's digest)
        if _current(folder, data_digest(used), seed, recipe):
            continue
        if log:
            log(f"training {action} on {session} ({len(used[action])} demonstrations) into {folder}")
        result = train(recipe, action, demos, seed)
        training = training_section(result, recipe.train, seed, command, recipe.data) | {"sessions": [session]}
        if recipe.extras_dict():  # as ``l2p-bullet train`` writes it; absent: the recipe before issue 25
            training["recipe"] = {"name": recipe.name, **recipe.extras_dict()}
        write_progress_bundle(folder, action, ensemble_arrays(result.model.nets), result.model.model_cfg,
                              result.model.qsr_cfg, training=training,
                              metrics={"train_loss": round(result.final_loss, 6)})
        if log:
            log(f"  {action}: {result.seconds:.0f} s, {result.n_sequences} sequences")
    return folders


def _current(folder: Path, digest: str, seed: int, recipe: Recipe) -> bool:
    """Does ``folder`` hold a bundle trained on exactly these demonstrations with this recipe?"""
    if not ((folder / MANIFEST).is_file() and (folder / PROGRESS_FILE).is_file()):
        return False
    t = read_manifest(folder).get("training", {})
    return (t.get("data_digest") == digest and t.get("seed") == seed and t.get("data") == recipe.data.to_dict()
            and all(t.get(k) == v for k, v in recipe.train.to_dict().items())
            and all(t.get(k) is None for k in ("weight_decay", "levels") if k not in recipe.train.to_dict())
            and {k: v for k, v in t.get("recipe", {}).items() if k != "name"} == recipe.extras_dict())


def split_models(recipe: Recipe, cache: Path | None, log: Callable[[str], None] | None = None,
                 seed: int = 0, untrusted: bool = True, folds: int = len(FOLDS)) -> list[dict[str, ProgressModel]]:
    """Per fold of :data:`heldout.FOLDS` (the first ``folds`` of them), every action's model trained on the fold's
    training session: :func:`session_bundles` under ``cache/<recipe>/s<seed>/<session>/`` (a temporary folder
    when None)."""
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp) if cache is None else Path(cache)
        models = []
        for train_s, _ in FOLDS[:folds]:
            folders = session_bundles(train_s, root / recipe.name / f"s{seed}" / train_s, seed=seed, recipe=recipe,
                                      log=log, command=f"bench_generalise recipe {recipe.name}", untrusted=untrusted)
            models.append({a: ProgressModel.from_bundle(load_bundle(f)) for a, f in folders.items()})
        return models


def run_suite(recipe: Recipe, cache: Path | None, log: Callable[[str], None] | None = None,
              seed: int = 0, untrusted: bool = True, folds: int = len(FOLDS)) -> dict[str, g.ActionReport]:
    """The suite for a recipe: its session-split models, scored on the other person's events, both ways
    (with the ordered probes of :mod:`.ordered_probes`; ``folds`` 1: one way only, a smoke run). The
    demonstrations whose tracking is not trusted are never scored; ``untrusted`` False also trains without them."""
    trained = split_models(recipe, cache, log, seed, untrusted, folds)
    reports = []
    for (_, test_s), models in zip(FOLDS[:folds], trained, strict=True):
        test = {a: g.events(ds) for a, ds in all_demos(sessions={test_s}, untrusted=False).items()}
        fold = g.score_fold(models, test)
        for a, r in fold.items():
            r.ordered = ordered(models[a], test[a])
        reports.append(fold)
    return g.merge(reports)


def bundle_seconds(folder: str | Path) -> float:
    """The training time recorded in a bundle's manifest (what a cached bundle cost to make)."""
    return float(read_manifest(Path(folder)).get("training", {}).get("seconds", float("nan")))
