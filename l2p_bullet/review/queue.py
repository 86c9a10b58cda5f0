"""The review queue: which runs are served, in which order each reviewer sees them, and what they answer.

Plain Python over the :class:`~l2p_bullet.review.store.Store` (the web app, app.py, is a thin layer on
top), so the ordering and the checks are tested without a server.

Order: a reviewer gets, among the items (run x view) they have not answered, the one with the fewest
answers from everybody, ties broken by a shuffle that is fixed per reviewer (sha256 of reviewer, run
and view): reviewers who start together spread over different runs, and a reload shows the same next
run. Items the reviewer skipped come last, oldest skip first.

A run whose folder disappeared or whose trajectory.json no longer has the sha256 it was registered
with is taken out of the queue and reported (:attr:`ReviewQueue.problems`); an answer is checked
against the file on disk before it is stored, so nothing is graded against a trajectory nobody saw.
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass

from ..errors import ReviewError
from .runs import VIEWS, RunInfo
from .store import MODES, NONE_LABEL, Answer, AnswerConflict, GradeRow, Store

VIEW_CHOICES = ("3d", "2d", "both")
RESERVED_KEYS = set("0123456789st")
"""Keys the page uses for grades (0-9, t = 10) and skip (s): never a label's key."""


class NotFound(ReviewError):
    """An item key that is not served here."""


@dataclass(frozen=True)
class Item:
    run: RunInfo
    view: str

    @property
    def key(self) -> tuple[str, str]:
        return self.run.run_id, self.view


def blind_labels(names: list[str]) -> list[str]:
    """Blind mode's labels in a fixed order, whatever order the plugins were discovered in: the built-in
    actions in the vocabulary's order (closer, away, next-to, past, around), then plugins by name, then
    "none". The order decides the keys (:func:`label_keys`), so a grader's keys never change with how
    packages happen to be installed (or "a" could be around on one machine and away in the docs)."""
    from ..core.vocabulary import ACTIONS

    names = [n for n in dict.fromkeys(names) if n != NONE_LABEL]
    return [a for a in ACTIONS if a in names] + sorted(n for n in names if n not in ACTIONS) + [NONE_LABEL]


def label_keys(labels: list[str]) -> list[dict]:
    """A one-letter key per blind-mode label: its first free letter ("none" prefers x). The one table of
    blind-mode keys: served to the page (``/api/config``), which shows it, and checked against
    docs/review.md (tests/review/test_review_app.py)."""
    used, out = set(RESERVED_KEYS), []
    for label in labels:
        letters = ("x" if label == NONE_LABEL else "") + "".join(ch for ch in label.lower() if ch.isalpha())
        key = next((ch for ch in letters if ch not in used), None)
        if key is None:
            key = next((ch for ch in "abcdefghijklmnopqrstuvwxyz" if ch not in used), "")
        used.add(key)
        out.append({"label": label, "key": key})
    return out


def check_reviewer(name: str) -> str:
    name = " ".join(str(name).split())
    if not 1 <= len(name) <= 40 or any(ord(ch) < 32 or ord(ch) == 127 for ch in name):
        raise ReviewError("a reviewer's name must be 1 to 40 printable characters")
    return name


class ReviewQueue:
    """The runs served in one mode, the store they are graded into, and the labels of blind mode."""

    def __init__(self, store: Store, runs: list[RunInfo], mode: str = "graded", view: str = "3d",
                 labels: list[str] | None = None):
        if mode not in MODES:
            raise ReviewError(f'unknown mode "{mode}" (known: {", ".join(MODES)})')
        if view not in VIEW_CHOICES:
            raise ReviewError(f'unknown view "{view}" (known: {", ".join(VIEW_CHOICES)})')
        self.store, self.mode, self.view = store, mode, view
        self.runs = {r.key: r for r in runs}
        wanted = VIEWS if view == "both" else (view,)
        self.items: list[Item] = []
        for r in runs:
            views = tuple(v for v in wanted if v in r.views(mode)) or ("2d",)
            self.items += [Item(r, v) for v in views]
        self.labels = blind_labels(list(labels or []))
        self.problems: dict[str, str] = {}  # run_id -> "missing" | "changed"
        self._stat = {r.run_id: _stat(r) for r in runs}

    # --- checks ---------------------------------------------------------------------------------
    def problem_of(self, run: RunInfo, full: bool = False) -> str | None:
        """None if the run's trajectory is the registered one; else "missing" or "changed" (and recorded).

        Cheap unless the file's size or time changed (then, or with ``full``, it is hashed).
        """
        if run.run_id in self.problems:
            return self.problems[run.run_id]
        st = _stat(run)
        if st is None:
            self.problems[run.run_id] = "missing"
        elif full or st != self._stat[run.run_id]:
            sha = run.current_sha256()
            if sha is None:
                self.problems[run.run_id] = "missing"
            elif sha != run.trajectory_sha256:
                self.problems[run.run_id] = "changed"
        return self.problems.get(run.run_id)

    # --- queue ----------------------------------------------------------------------------------
    def next_item(self, reviewer: str) -> Item | None:
        reviewer = check_reviewer(reviewer)
        counts = self.store.counts(self.mode)
        skipped = self.store.skips(reviewer, self.mode)
        mine = {(g.run_id, g.view) for g in self.store.grades(reviewer, self.mode) if not g.stale}

        def order(it: Item):
            k = it.key
            return (k in skipped, skipped.get(k, ""), counts.get(k, 0), _shuffle(reviewer, it))

        for it in sorted((it for it in self.items if it.key not in mine), key=order):
            if self.problem_of(it.run) is None:
                return it
        return None

    def progress(self, reviewer: str) -> dict:
        mine = {(g.run_id, g.view) for g in self.history_rows(reviewer)}
        return {"answered": len(mine), "total": len(self.items)}

    def item(self, key: str, view: str) -> Item:
        run = self.runs.get(key)
        if run is None:
            raise NotFound(f'no run "{key}" is served here')
        it = Item(run, view)
        if it not in self.items:
            raise ReviewError(f'run "{key}" is not shown in the "{view}" view here')
        return it

    # --- answers --------------------------------------------------------------------------------
    def answer(self, reviewer: str, key: str, view: str, grade: int | None, label: str | None = None,
               comment: str = "", replaces: str | None = None) -> GradeRow:
        reviewer = check_reviewer(reviewer)
        it = self.item(key, view)
        if grade is None:
            raise ReviewError("a grade (0-10) is required")
        if self.mode == "blind":
            if label not in self.labels:
                raise ReviewError(f'blind mode needs a label: one of {", ".join(self.labels)}')
        elif label is not None:
            raise ReviewError("graded mode takes no label (the action is known)")
        problem = self.problem_of(it.run, full=True)
        if problem == "missing":
            raise AnswerConflict(f"the run folder {it.run.path} disappeared: not graded", "missing")
        if problem == "changed":
            raise AnswerConflict(f"{it.run.path / 'trajectory.json'} changed since the review started: not graded "
                                 "(restart the review to grade the new version)", "changed")
        return self.store.save_answer(Answer(it.run.run_id, reviewer, self.mode, view, grade, label, comment.strip()),
                                      it.run.trajectory_sha256, replaces)

    def skip(self, reviewer: str, key: str, view: str) -> None:
        it = self.item(key, view)
        self.store.skip(it.run.run_id, it.run.trajectory_sha256, check_reviewer(reviewer), self.mode, view)

    def history_rows(self, reviewer: str) -> list[GradeRow]:
        """This reviewer's answers to the runs served here, oldest first."""
        served = {(it.run.run_id, it.run.trajectory_sha256) for it in self.items}
        return [g for g in self.store.grades(check_reviewer(reviewer), self.mode)
                if (g.run_id, g.trajectory_sha256) in served]

    def answer_of(self, reviewer: str, it: Item) -> GradeRow | None:
        return next((g for g in self.history_rows(reviewer) if (g.run_id, g.view) == it.key), None)


def _stat(run: RunInfo) -> tuple[int, int] | None:
    try:
        st = os.stat(run.path / "trajectory.json")
    except OSError:
        return None
    return st.st_mtime_ns, st.st_size


def _shuffle(reviewer: str, it: Item) -> str:
    return hashlib.sha256(f"{reviewer}\0{it.run.run_id}\0{it.view}".encode()).hexdigest()
