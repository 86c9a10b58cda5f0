"""What ``l2p-bullet report`` writes: the report as text (report.md, what the command prints), report.json
without the plotting points, the tables as CSV and the plots (plots.py), into a folder taken by the
run-folder rules (:func:`report_folder`: an earlier report there is replaced, nothing else ever).

Apart from the tables (``report.py``, which re-exports these names) because the tables are computed from the
grades alone, while this is only their form on screen and on disk and the folder they go in.
"""

from __future__ import annotations

import contextlib
import csv
import json
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from ..errors import ReviewError
from .plots import plot_all


def _fmt(v, digits: int = 2) -> str:
    if v is None:
        return "n/a"
    return f"{v:.{digits}f}" if isinstance(v, float) else str(v)


def _md(header: list[str], rows: list[list]) -> str:
    lines = [
        "| " + " | ".join(header) + " |",
        "|" + "|".join("---" if i == 0 else "---:" for i in range(len(header))) + "|",
    ]
    lines += ["| " + " | ".join(_fmt(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def render_text(rep: dict) -> str:
    out = [f"Review report: {rep['source']}: {rep['answers']} answers from {rep['reviewers']} reviewers"]
    head = ["action", "runs", "grades", "view", "mean grade", "disparity", "Spearman final progress",
            "Spearman judge"]
    for key, title in (("original", "the original study (imported, 2-D, two graders who knew the action)"),
                       ("app", "runs graded here (the sentence shown)")):
        t = rep["graded"][key]
        if t:
            out += ["", f"Question 1, grades: {title}", _md(head, [
                [r["group"], r["runs"], r["grades"], r["views"], r["mean_grade"], r["disparity"],
                 r["spearman_final_progress"], r["spearman_judge"]] for r in t])]
    b = rep["blind"]
    if b:
        c = b["confusion"]
        out += ["", f"Question 2, blind labels: {b['labels']} labels of {b['items']} runs; share of each row's labels",
                _md(["true \\ label"] + c["cols"] + ["n"],
                    [[r] + [float(v) if np.isfinite(v) else None for v in s] + [sum(n)]
                     for r, s, n in zip(c["rows"], c["shares"], c["counts"], strict=True)]),
                f"Fleiss' kappa {_fmt(b['fleiss']['kappa'], 3)} over {b['fleiss']['items']} runs labelled by two or "
                f"more people ({_fmt(b['fleiss']['raters_per_item'], 1)} each on average); "
                f"labels matching the run's action: {_fmt(b['accuracy'])}"]
    if rep["views"]:
        out += ["", "Question 3, the same runs graded as the 3-D video and as the 2-D animation",
                _md(["action", "runs", "mean 2-D", "mean 3-D", "3-D minus 2-D", "Spearman 2-D vs 3-D"],
                    [[v["action"], v["runs"], v["mean_2d"], v["mean_3d"], v["mean_3d_minus_2d"], v["spearman_2d_3d"]]
                     for v in rep["views"]])]
    if rep["problems"]:
        out += ["", "Not counted (the run is not the one that was graded):"]
        out += [f"  {p['run_id']}: {p['problem']} ({p['answers']} answers) {p['run_path']}" for p in rep["problems"]]
    if rep["notes"]:
        out += [""] + [f"note: {n}" for n in rep["notes"]]
    return "\n".join(out)


def _public(rep: dict) -> dict:
    """The report without the plotting points (what --json prints and report.json holds)."""
    def strip(x):
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items() if not k.startswith("_")}
        if isinstance(x, list):
            return [strip(v) for v in x]
        return x
    return strip(rep)


REPORT_FILES: tuple[str, ...] = ("report.md", "report.json", "table1_original.csv", "table1_app.csv", "confusion.csv",
                                 "table1.png", "agreement.png", "confusion.png", "views.png")
"""What :func:`write_grade_report` writes: recorded in the report folder's marker, so that ``--force``
recognises them (and only them) later."""


@contextlib.contextmanager
def report_folder(folder: Path, db: Path) -> Iterator[Path]:
    """``with report_folder(out, db) as folder:`` the folder for a report, by the run-folder rules
    (:func:`~l2p_bullet.core.runfolder.run_folder`): a new or empty folder, or one holding an earlier report of
    this command and nothing else, which is replaced (a report is made again after every grading session:
    asking for ``--force`` each time would only teach people to type it); never a folder with a person's
    files (their own ``report.md``), a run folder of another command, or one that is or holds the grades file.
    The earlier report stays aside until the new one is written, and comes back if writing it fails. A
    folder without the marker (an older version's) that holds only report files is taken as an earlier report."""
    from ..core.runfolder import run_folder

    _adopt_old_report(folder)
    with run_folder(folder, force=True, command="report", files=REPORT_FILES, inputs=(db,),
                    restore_on_error=True) as out:
        yield out


def _adopt_old_report(folder: Path) -> None:
    """Mark a report folder written before the marker existed as report's, so the rules above replace it (the
    earlier report is kept aside until the new one is written). Only a folder of report files whose
    report.json is a report's (the keys :func:`build_report` always writes): a person's own report.md and
    report.json are never taken for one. Any other folder is left as it is, and refused there if not ours."""
    from ..core.runfolder import MARKER

    if not folder.is_dir() or folder.is_symlink() or (folder / MARKER).exists():
        return
    entries = list(folder.iterdir())
    if not ({"report.md", "report.json"} <= {p.name for p in entries}
            and all(p.is_file() and not p.is_symlink() and p.name in REPORT_FILES for p in entries)):
        return
    try:
        written = json.loads((folder / "report.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return
    if not (isinstance(written, dict) and REPORT_KEYS <= set(written)):
        return
    try:
        (folder / MARKER).write_text(json.dumps({"tool": "l2p-bullet", "command": "report",
                                                 "files": list(REPORT_FILES), "finished": "before the marker"}) + "\n")
    except OSError as e:
        raise ReviewError(f"cannot write the report into {folder}: {e.strerror or e}") from None


REPORT_KEYS = frozenset({"source", "answers", "reviewers", "graded", "blind", "views", "problems"})
"""Keys every report.json that ``report`` wrote has (:func:`build_report`): how an earlier report is told apart."""


def write_grade_report(rep: dict, folder: Path) -> list[Path]:
    """report.md, report.json, table CSVs and PNG plots into ``folder``; returns the files written."""

    try:
        folder.mkdir(parents=True, exist_ok=True)
        files = [folder / "report.md", folder / "report.json"]
        files[0].write_text(render_text(rep) + "\n", encoding="utf-8")
        files[1].write_text(json.dumps(_public(rep), indent=1, default=str) + "\n", encoding="utf-8")
        for key in ("original", "app"):
            t = _public(rep["graded"][key])
            if t:
                p = folder / f"table1_{key}.csv"
                with open(p, "w", newline="", encoding="utf-8") as f:
                    w = csv.DictWriter(f, fieldnames=list(t[0]))
                    w.writeheader()
                    w.writerows(t)
                files.append(p)
        if rep["blind"]:
            p = folder / "confusion.csv"
            c = rep["blind"]["confusion"]
            with open(p, "w", newline="", encoding="utf-8") as f:
                w = csv.writer(f)
                w.writerow(["true_label", *c["cols"], "n"])
                for r, s, n in zip(c["rows"], c["shares"], c["counts"], strict=True):
                    w.writerow([r, *[f"{v:.3f}" for v in s], sum(n)])
            files.append(p)
        files += plot_all(rep, folder)
    except OSError as e:
        raise ReviewError(f"cannot write the report into {folder}: {e.strerror or e}") from None
    return files
