"""The session's kept labellings (tests/learning/conftest.py) are what labelling makes, handed out as copies."""

from __future__ import annotations

import numpy as np

from l2p_bullet.learning import training_plan, trainset
from l2p_bullet.progress.features import QSRConfig


def test_a_kept_labelling_is_a_fresh_copy_of_what_labelling_makes(_labelled_once):
    real = _labelled_once
    m = np.column_stack([np.linspace(3, 1, 30), np.zeros(30), np.zeros(30)])
    args = (m, np.zeros((30, 3)), 1.0, 0.0, 29.0, QSRConfig(), trainset.DataConfig(), True)
    made, a, b = real(*args), trainset._labelled(*args), training_plan._labelled(*args)
    for s in (a, b):
        assert np.array_equal(made.x, s.x) and np.array_equal(made.y, s.y)
        assert (made.positive, made.end, made.weight, made.frame_w) == (s.positive, s.end, s.weight, s.frame_w)
    a.weight, a.x[:] = 5.0, 0.0  # build sets the negatives' weights on what it gets
    again = trainset._labelled(*args)
    assert again.weight == 1.0 and np.array_equal(again.x, made.x)
