"""Session bundles (research/sessions.py): models trained on one person's capture session, cached on disk."""

from __future__ import annotations

import pytest

from research import sessions


@pytest.mark.slow
def test_session_models_are_reused_only_while_data_and_recipe_match(tmp_path, monkeypatch):
    """``research/sessions.py`` keeps a cached session bundle only when it was trained on the same demonstrations
    with the same seed and recipe; otherwise it trains again (here: a sentinel that says it would)."""
    import shutil

    from l2p_bullet.learning.train_progress import ProgressTrainConfig, all_demos, data_digest
    from l2p_bullet.learning.training_plan import SHIPPED
    from l2p_bullet.learning.training_plan import TrainingPlan as Recipe
    from l2p_bullet.learning.trainset import DataConfig
    from l2p_bullet.plugins.bundle import builtin_bundle_dir, update_manifest

    class Trains(Exception):
        pass

    def train(*args, **kwargs):
        raise Trains

    monkeypatch.setattr(sessions, "train", train)
    folder = tmp_path / "Session1" / "closer"
    shutil.copytree(builtin_bundle_dir("closer"), folder)
    digest = data_digest(all_demos(sessions={"Session1"}))
    update_manifest(folder, "training", {"data_digest": digest, "seed": 0, "data": DataConfig().to_dict(),
                                         **ProgressTrainConfig().to_dict(),
                                         "recipe": {"name": SHIPPED.name, **SHIPPED.extras_dict()}})
    assert sessions.session_bundles("Session1", tmp_path / "Session1", actions=("closer",)) == {"closer": folder}
    with pytest.raises(Trains):  # a recipe that adds to the training set
        sessions.session_bundles("Session1", tmp_path / "Session1", actions=("closer",),
                                 recipe=Recipe("x", planner_positives=True))
    with pytest.raises(Trains):  # another seed
        sessions.session_bundles("Session1", tmp_path / "Session1", actions=("closer",), seed=1)
    with pytest.raises(Trains):  # the other session's demonstrations
        sessions.session_bundles("Session2", tmp_path / "Session1", actions=("closer",))
    update_manifest(folder, "training", {"epochs": 29})
    with pytest.raises(Trains):  # another recipe
        sessions.session_bundles("Session1", tmp_path / "Session1", actions=("closer",))
