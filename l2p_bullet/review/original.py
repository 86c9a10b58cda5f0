"""The 2018 study's grades (``data/sim/human_eval_2d_demos.jsonl``) as rows of the review database.

90 generated 2-D demonstrations (6 folders x 15), each graded 0-10 by two people who knew the action's
name: 180 answers, ``source = "original"``, mode "graded", view "2d" (they watched the original 2-D
simulator). A demo becomes a run ``original:<demo id>`` with no folder; its fingerprint is the sha256 of
its JSON line, so a change to the shipped data shows up as a new version, like a changed run folder.
The import is idempotent: importing again adds nothing and changes nothing.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass

from ..core.vocabulary import GRADED_FOLDERS
from ..data.demos import load_graded_demos
from .store import Store, now


@dataclass(frozen=True)
class ImportResult:
    demos: int
    grades: int  # answers in the data
    added: int  # answers new to this database


def grader_name(key: str) -> str:
    """ "annotator_1_son" -> "son" (the name the spreadsheet and the comments use)."""
    return key.rsplit("_", 1)[-1].lower()


def import_original(store: Store) -> ImportResult:
    demos = load_graded_demos()
    t = now()
    grades = added = 0
    with store.transaction() as conn:
        for d in demos:
            run_id = f"original:{d['id']}"
            sha = hashlib.sha256(json.dumps(d, sort_keys=True, separators=(",", ":")).encode()).hexdigest()
            conn.execute(
                "INSERT OR IGNORE INTO runs (run_id, path, trajectory_sha256, action, sentence, registered_at, "
                "source, demo_id, folder) VALUES (?, '', ?, ?, ?, ?, 'original', ?, ?)",
                (run_id, sha, GRADED_FOLDERS[d["folder"]], d["action"], t, d["id"], d["folder"]),
            )
            comments = {grader_name(k): v for k, v in (d.get("comments_vi") or {}).items()}
            for key, grade in d["scores_txt"].items():
                who = grader_name(key)
                grades += 1
                cur = conn.execute(
                    "INSERT OR IGNORE INTO answers (run_id, trajectory_sha256, reviewer, mode, view, grade, "
                    "label, comment, created_at, updated_at) VALUES (?, ?, ?, 'graded', '2d', ?, NULL, ?, ?, ?)",
                    (run_id, sha, who, int(grade), comments.get(who) or "", t, t),
                )
                added += cur.rowcount
    return ImportResult(len(demos), grades, added)
