"""Bundles trained on one capture session: models that have never seen the other person's motions.

The two capture sessions of each action were recorded by different people (data README), so a model
trained on Session 1 of every action and tested on Session 2 is tested on people it never saw. This is
the shipped training recipe unchanged (:func:`train_progress.train_action` with its default settings,
the other actions' demonstrations of the same session as negatives); only the demonstrations are
restricted, for all five actions at once: training "closer" on Session 1 with the other actions'
Session 2 demonstrations as negatives would show it the test person. SlideToward's extra Session 3 is
left out (as in :data:`validation.FOLDS`). ``benchmarks/bench_recognize.py`` recognises the held-out
session with these bundles; they are written as ordinary bundle folders (``l2p-bullet score`` and
``recognize --actions`` read them) and re-used while their data digest and recipe still match.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..core.vocabulary import ACTIONS
from ..plugins.bundle import MANIFEST, PROGRESS_FILE, read_manifest, write_progress_bundle
from .progress_net import ensemble_arrays
from .train_progress import ProgressTrainConfig, all_demos, data_digest, train_action, training_section
from .trainset import DataConfig


def session_bundles(session: str, out: str | Path, *, actions: tuple[str, ...] = ACTIONS, seed: int = 0,
                    command: str = "", log: Callable[[str], None] | None = None) -> dict[str, Path]:
    """Train each of ``actions`` on capture ``session`` (e.g. "Session1") into ``out/<action>/``.

    A folder whose manifest already records the same data digest, seed and recipe is kept as it is
    (training all five takes minutes), so a benchmark can call this every time. Returns action -> folder.
    """
    out = Path(out)
    demos = all_demos(sessions={session})
    digest = data_digest(demos)
    cfg, data_cfg = ProgressTrainConfig(), DataConfig()
    folders = {}
    for action in actions:
        folder = out / action
        folders[action] = folder
        if _current(folder, digest, seed, cfg, data_cfg):
            continue
        if log:
            log(f"training {action} on {session} ({len(demos[action])} demonstrations) into {folder}")
        result = train_action(action, demos, seed=seed, cfg=cfg, data_cfg=data_cfg)
        training = training_section(result, cfg, seed, command, data_cfg) | {"sessions": [session]}
        write_progress_bundle(folder, action, ensemble_arrays(result.model.nets), result.model.model_cfg,
                              result.model.qsr_cfg, training=training,
                              metrics={"train_loss": round(result.final_loss, 6)})
        if log:
            log(f"  {action}: {result.seconds:.0f} s, {result.n_sequences} sequences")
    return folders


def _current(folder: Path, digest: str, seed: int, cfg: ProgressTrainConfig, data_cfg: DataConfig) -> bool:
    """Does ``folder`` hold a bundle trained on exactly these demonstrations with this recipe?"""
    if not ((folder / MANIFEST).is_file() and (folder / PROGRESS_FILE).is_file()):
        return False
    t = read_manifest(folder).get("training", {})
    return (t.get("data_digest") == digest and t.get("seed") == seed and t.get("data") == data_cfg.to_dict()
            and all(t.get(k) == v for k, v in cfg.to_dict().items()))


def bundle_seconds(folder: str | Path) -> float:
    """The training time recorded in a bundle's manifest (what a cached bundle cost to make)."""
    return float(read_manifest(Path(folder)).get("training", {}).get("seconds", float("nan")))
