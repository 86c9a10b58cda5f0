"""The training sets these tests build, each sequence's features computed once per test session.

The modules here build the sets of many plans and actions to compare them (a plan's extras, the sets another plan
leaves alone, the shipped set bit for bit); the same demonstrations come back as positives of one action and
negatives of the others, so most sequences were labelled four or five times (48,000 labellings, 9,500 of them
different, a minute of CPU). :func:`_labelled_once` keeps each by a digest of everything it is made from and hands
out fresh copies (``build`` sets the negatives' weights on what it gets). That a labelling is the same every time
it is made is checked where nothing is kept: ``cli/test_score.py`` trains twice in one process and
``test_determinism_audit.py`` in two.
"""

from __future__ import annotations

import dataclasses
import hashlib
import pickle

import pytest

from l2p_bullet.learning import feedback_targets, training_plan, trainset


def _copy(s: trainset.TrainingSequence) -> trainset.TrainingSequence:
    return dataclasses.replace(s, x=s.x.copy(), y=s.y.copy(), frame_w=None if s.frame_w is None else s.frame_w.copy())


KEPT: dict[bytes, trainset.TrainingSequence] = {}
"""Labellings by digest, for the whole session; they are handed out only while a module of this folder runs."""


@pytest.fixture(scope="module", autouse=True)
def _labelled_once():
    """Labelling kept for this module's tests (put back after it: tests elsewhere label anew)."""
    real, kept = trainset._labelled, KEPT

    def labelled(*args, **kwargs) -> trainset.TrainingSequence:
        key = hashlib.sha256(pickle.dumps((args, sorted(kwargs.items())), protocol=5)).digest()
        if key not in kept:
            kept[key] = real(*args, **kwargs)
        return _copy(kept[key])

    with pytest.MonkeyPatch.context() as patch:
        for module in (trainset, training_plan, feedback_targets):  # the two import it by name
            patch.setattr(module, "_labelled", labelled)
        yield real

