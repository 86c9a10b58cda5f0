"""``l2p-bullet improve``: "hot" feedback, rounds of perform -> grade -> re-train.

Each round performs the action (no rendering) on N seeded scenes with the current bundle, collects a
grade for every run, fine-tunes the current bundle's progress model on the demonstrations plus every
grade collected so far (and any static ``--feedback``), and keeps the result::

    DIR/round-<k>/runs/seed-<s>/   the run folders (trajectory.json, plan.json, summary.json)
    DIR/round-<k>/grades.csv       the round's grades, in the review export's columns
    DIR/round-<k>/bundle/          the re-trained bundle (its [policy] and [judge] kept), written as
                                   bundle.part/ and renamed once fine-tuning finished
    DIR/round-<k>/metrics.json     success and final progress of the round's runs, agreement with people

Grades come from the rule judge (``judge="rules"``: 10 x its score on the executed trajectory, the
original's automatic feedback) or from people: a review database or export (``judge=FILE``) holding
grades of this round's runs. People need time to grade, so a round whose runs have no grades in the
file yet stops with a message; re-running the same command resumes there (finished rounds are kept,
run folders already performed are reused), as it does after a Ctrl-C. Nothing is overwritten without
``force``, which replaces only what improve wrote (``improve.json``, ``round-<k>/``): a folder holding
anything else is refused.

Scenes are ``random_scene(seed)`` with seeds 1000 + 100 (k - 1) + i: the benchmarks use 0-99,
automatic feedback 5000 on, REINFORCE 10 000 and up.
"""

from __future__ import annotations

import json
import re
import shutil
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..actions import BUILTIN
from ..core.contracts import PROGRESS_FILE, load_motion
from ..core.folders import check_writable
from ..core.scene import random_scene
from ..data.grades import GradeRow, write_grades
from ..errors import DataError, L2PError, RunFolderError, listed, plural
from ..judge import RuleJudge
from ..pipeline import perform
from ..plugins.bundle import load_bundle, sha256_file, write_progress_bundle
from ..plugins.registry import locate
from .feedback import (
    GRADE_MAX,
    FeedbackItem,
    folder_agreement,
    items_from_rows,
    load_feedback,
    original_items,
    read_grades,
    score_items,
)
from .feedback_targets import FeedbackConfig

IMPROVE_SEEDS = 1000
"""Scene seed of round 1's first run; round k, run i uses IMPROVE_SEEDS + 100 (k - 1) + i."""
MAX_SCENES, MAX_ROUNDS = 100, 40

SENTENCES = {a: spec.sentence for a, spec in BUILTIN.items()}
"""The sentence each built-in action's rounds perform (its ``ActionSpec.sentence``)."""


@dataclass
class RoundResult:
    """What one round did (also its metrics.json)."""

    round: int
    bundle: str
    seeds: list[int]
    success_rate: float
    mean_final_progress: float
    n_grades: int
    n_grades_total: int
    mean_grade: float
    agreement: dict[str, float] = field(default_factory=dict)
    agreement_mean: float = float("nan")
    agreement_in_sample: bool = False
    seconds: float = 0.0

    def to_dict(self) -> dict:
        return {k: (round(v, 4) if isinstance(v, float) else v) for k, v in self.__dict__.items()}


def _eta(done: int, total: int, t0: float) -> str:
    """``(12s, ETA 48s)``: the time since ``t0`` and what the rest should take at that pace (evaluate's
    ProgressBar is a floor up: learning may not import evaluate)."""
    dt = time.perf_counter() - t0
    left = dt / done * (total - done) if done else 0.0
    return f"({_duration(dt)}, ETA {_duration(left)})"


def _duration(seconds: float) -> str:
    m, s = divmod(int(round(seconds)), 60)
    return f"{m}m{s:02d}s" if m else f"{s}s"


def round_seeds(k: int, scenes: int) -> list[int]:
    return [IMPROVE_SEEDS + 100 * (k - 1) + i for i in range(scenes)]


def improve(action: str, rounds: int, out: Path, *, scenes: int = 10, judge: str = "rules",
            feedback: Sequence[str] = (), seed: int = 0, force: bool = False,
            feedback_cfg: FeedbackConfig | None = None,
            log: Callable[[str], None] | None = None) -> list[RoundResult]:
    """Run ``rounds`` rounds of hot feedback for the installed (or given folder's) ``action`` into ``out``."""
    if not 1 <= scenes <= MAX_SCENES or not 1 <= rounds <= MAX_ROUNDS:
        raise DataError(f"improve takes 1-{MAX_SCENES} scenes and 1-{MAX_ROUNDS} rounds")
    name, current = locate(action)
    if name not in SENTENCES:
        raise DataError(f'improve performs the built-in actions ({", ".join(SENTENCES)}), not "{name}"')
    _check_judge(judge)
    static, skipped = load_feedback(feedback)  # a typo in --feedback fails here, before anything is written
    out = Path(out)
    check_writable(out, "--out", DataError)
    if not (current / PROGRESS_FILE).is_file():
        raise DataError(f"{current} holds no {PROGRESS_FILE}: train the action first (l2p-bullet train {name})")
    settings = {"action": name, "scenes": scenes, "judge": judge, "feedback": list(feedback), "seed": seed,
                "started_from": str(current),  # and what it held: a bundle re-trained since is another start
                "started_from_sha256": sha256_file(current / PROGRESS_FILE)}
    _claim(out, settings, force)
    say = log or (lambda _m: None)
    for s in skipped:
        say(f"warning: left out reviewed run {s.id}: {s.reason}")
    collected: list[FeedbackItem] = []
    results = []
    for k in range(1, rounds + 1):
        rd = out / f"round-{k}"
        done = rd / "metrics.json"
        if done.is_file() and (rd / "bundle" / "manifest.toml").is_file():
            say(f"round {k}: already done, kept ({rd})")
            collected += _round_items(rd, judge, name, round_seeds(k, scenes), say)
            current = rd / "bundle"
            results.append(RoundResult(**json.loads(done.read_text())))
            continue
        t0 = time.perf_counter()
        seeds = round_seeds(k, scenes)
        say(f"round {k}/{rounds}: performing {name} on {plural(scenes, 'scene')} with {current}")
        summaries = _perform_round(name, current, rd / "runs", seeds, say)
        items = _round_items(rd, judge, name, seeds, say)
        collected += items
        say(f"round {k}/{rounds}: {plural(len(items), 'graded run')} (mean grade "
            f"{np.mean([it.grade for it in items]):.1f}); fine-tuning the progress model on "
            f"{plural(len(collected) + len(static), 'graded motion')} ({len(collected)} from the rounds, "
            f"{len(static)} from --feedback)")
        bundle_dir = rd / "bundle"
        if bundle_dir.exists():  # a bundle with no metrics.json: an unfinished round's, fine-tuned again
            shutil.rmtree(bundle_dir)
        part = _retrain(name, current, rd / "bundle.part", static + collected, seed, feedback_cfg, k, judge, say)
        # read from bundle.part, recorded as bundle/: renamed only once fine-tuned and measured, so that a
        # round stopped (Ctrl-C) before leaves no bundle/ that looks re-trained
        res = _metrics(k, part, bundle_dir, seeds, summaries, items, len(collected), static)
        res.seconds = round(time.perf_counter() - t0, 1)
        part.rename(bundle_dir)
        done.write_text(json.dumps(res.to_dict(), indent=1) + "\n")
        say(f"round {k}/{rounds}: success {100 * res.success_rate:.0f} %, mean final progress "
            f"{res.mean_final_progress:.2f}, agreement with people {res.agreement_mean:.2f}"
            + (" (in sample)" if res.agreement_in_sample else "") + f" ({res.seconds:.0f} s)")
        results.append(res)
        current = bundle_dir
    return results


def _check_judge(judge: str) -> None:
    """``--judge`` is "rules" or a review database/export that reads as one (a scene file or a folder is
    refused here, before a round is performed, not after)."""
    if judge == "rules":
        return
    p = Path(judge)
    if p.is_dir():
        raise DataError(f'--judge must be "rules" or a review database/export file; {judge} is a folder')
    if not p.is_file():
        raise DataError(f'--judge must be "rules" or a review database/export file; {judge} does not exist')
    try:
        read_grades(p)
    except L2PError as e:  # a scene file, a CSV of something else ...
        raise DataError(f'--judge must be "rules" or a review database/export file: {e}') from None


ROUND = re.compile(r"round-[1-9][0-9]*")
ROUND_FILES = ("runs", "grades.csv", "grades.csv.part", "bundle", "bundle.part", "metrics.json")
"""What improve writes: OUT/improve.json and OUT/round-<k>/ holding these (and nothing else of anyone's)."""


def _foreign(out: Path) -> list[str]:
    """The entries of ``out`` improve did not write (relative names, sorted); symbolic links always count."""
    found = []
    for p in sorted(out.iterdir()):
        if p.is_symlink() or not (p.name == "improve.json" and p.is_file() or ROUND.fullmatch(p.name) and p.is_dir()):
            found.append(p.name)
        elif p.is_dir():
            found += [f"{p.name}/{q.name}" for q in sorted(p.iterdir()) if q.is_symlink() or q.name not in ROUND_FILES]
    return found


def _claim(out: Path, settings: dict, force: bool) -> None:
    """Create ``out`` for these settings, or resume it if it holds rounds of the very same ones.

    ``force`` replaces only what improve wrote (improve.json and the round-<k> folders): a folder holding
    anything else is refused, with or without it (nothing a person wrote is deleted)."""
    f = out / "improve.json"
    if out.is_symlink() or (out.exists() and not out.is_dir()):
        raise RunFolderError(f"{out} is not a folder (or is a symbolic link); choose another --out")
    if out.exists() and any(out.iterdir()):
        foreign = _foreign(out)
        try:
            old = json.loads(f.read_text())
        except (OSError, ValueError):
            old = None
        if foreign or not isinstance(old, dict):
            shown = listed(foreign) or "no improve.json"
            raise RunFolderError(f"{out} already exists and holds files l2p-bullet did not write ({shown}); choose "
                                 "another --out (--force never deletes them)")
        if "started_from_sha256" not in old and "started_from_sha256" in settings:  # from before the digest
            old = old | {"started_from_sha256": settings["started_from_sha256"]}
        if old == settings and not force:  # the same command again: go on where it stopped
            return
        if not force:
            raise RunFolderError(f"{out} holds rounds of other improve settings (its improve.json); choose another "
                                 "--out, or pass --force to replace those rounds")
        # only improve.json and round-<k>/, checked above; improve.json last, so that a run stopped half-way
        # leaves a folder that is still improve's (and --force replaces it again)
        for p in sorted(out.iterdir(), key=lambda p: p.name == "improve.json"):
            shutil.rmtree(p) if p.is_dir() else p.unlink()
    out.mkdir(parents=True, exist_ok=True)
    f.write_text(json.dumps(settings, indent=1) + "\n")


def _perform_round(name: str, bundle_dir: Path, runs: Path, seeds: list[int], say) -> list[dict]:
    """Perform (no rendering) on each seed's scene, reusing run folders a stopped round already finished.

    Every 5 runs a line with the count and an ETA (the runs reused are left out of it, so that they do
    not make the ETA too short)."""

    bundle = load_bundle(bundle_dir)
    todo = [s for s in seeds if not _performed(runs / f"seed-{s}")]
    if len(todo) < len(seeds):
        say(f"  reusing {plural(len(seeds) - len(todo), 'run')} performed before")
    t0, done = time.perf_counter(), 0
    out = []
    for s in seeds:
        folder = runs / f"seed-{s}"
        summary = folder / "summary.json"
        if s in todo:
            try:
                perform(SENTENCES[name], random_scene(s), out_dir=folder, seed=s, render=False, force=True,
                        bundle=bundle)
            except L2PError as e:
                say(f"  seed {s}: failed ({e})")
        d = json.loads(summary.read_text()) if summary.is_file() else {"ok": False}
        out.append(d)
        if s in todo:
            done += 1
            if done % 5 == 0 or done == len(todo):
                say(f"  performed {done}/{plural(len(todo), 'run')} {_eta(done, len(todo), t0)}")
    return out


def _performed(folder: Path) -> bool:
    """Did a stopped round already perform this run (its summary says ok)?"""
    try:
        summary = json.loads((folder / "summary.json").read_text())
    except (OSError, ValueError):  # missing, or cut short by a kill: performed again
        return False
    return isinstance(summary, dict) and bool(summary.get("ok"))


def _round_items(rd: Path, judge: str, name: str, seeds: list[int], say) -> list[FeedbackItem]:
    """This round's graded runs: judged by the rules (written to grades.csv) or looked up in the file."""
    runs = [rd / "runs" / f"seed-{s}" for s in seeds]
    runs = [r for r in runs if (r / "trajectory.json").is_file()]
    if judge == "rules":
        rows = [_rule_row(name, r) for r in runs]
    else:
        wanted = {r.name for r in runs} | {str(r.resolve()) for r in runs}
        rows = [r for r in read_grades(judge)
                if r.run_id in wanted or (r.run_path and str(Path(r.run_path).resolve()) in wanted)]
        if not any(r.mode == "graded" and r.grade is not None for r in rows):
            raise DataError(f"{judge} holds no grades of the runs in {rd / 'runs'} yet: review them in the review "
                            "app, then run the same command again to go on from this round")
    write_grades(rows, rd / "grades.csv", force=True)  # this round's own record, rewritten when it is resumed
    items, skipped = items_from_rows(rows, rd)
    for s in skipped:
        say(f"warning: left out run {s.id}: {s.reason}")
    return items


def _rule_row(name: str, run: Path) -> GradeRow:
    """The rule judge's grade (10 x score) of a run's executed trajectory, as an export row."""

    traj = run / "trajectory.json"
    m = load_motion(traj)
    v = RuleJudge(name).judge(m.mover, m.anchor, m.size)
    now = time.strftime("%Y-%m-%dT%H:%M:%S")
    return GradeRow(run_id=run.name, run_path=str(run.resolve()), trajectory_sha256=sha256_file(traj),
                    action=name, sentence=SENTENCES[name], mode="graded", reviewer="rules",
                    grade=round(GRADE_MAX * float(v.score), 3), comment=v.reason, view="2d", created_at=now,
                    updated_at=now, source="rules")


def _retrain(name: str, current: Path, out: Path, items: list[FeedbackItem], seed: int,
             fcfg: FeedbackConfig | None, k: int, judge: str, say: Callable[[str], None]) -> Path:
    """Fine-tune the current bundle's ensemble on the demonstrations and ``items`` into a copy of it.

    ``out`` is the round's temporary bundle.part/: a copy of the current bundle until the fine-tuned
    weights are written. It is removed if the fine-tuning fails or is interrupted (a round stopped there
    left bundle/ holding the untouched copy, which looked like a re-trained bundle). A line after each
    ensemble member gives the ETA (the fine-tuning took seconds with no output)."""
    # lazy: these modules import torch; only when a network is trained
    from .progress_net import ProgressModel, ensemble_arrays
    from .train_progress import (
        ProgressTrainConfig,
        all_demos,
        feedback_digest,
        train_action,
        training_section,
    )

    if out.exists():
        shutil.rmtree(out)
    try:
        shutil.copytree(current, out)
        bundle = load_bundle(out)
        base = ProgressModel.from_bundle(bundle)
        fcfg = fcfg or FeedbackConfig()
        cfg = ProgressTrainConfig(hidden=base.model_cfg.hidden, ensemble=base.model_cfg.ensemble)
        epochs, t0 = [0], [time.perf_counter()]

        def tick() -> None:  # once per member-epoch; a line per ensemble member
            epochs[0] += 1
            if epochs[0] % fcfg.epochs == 0:
                n = epochs[0] // fcfg.epochs
                say(f"  fine-tuned {n}/{plural(cfg.ensemble, 'ensemble member')} "
                    f"{_eta(n, cfg.ensemble, t0[0])}")

        def stage(message: str) -> None:  # the ETA counts from the built training set, as train's does
            t0[0] = time.perf_counter()

        result = train_action(name, all_demos(), seed=seed, cfg=cfg, feedback=items, feedback_cfg=fcfg,
                              base=base.nets, tick=tick, on_stage=stage)
        training = training_section(result, cfg, seed, f"l2p-bullet improve {name} (round {k}, judge {judge})")
        training["feedback"] = {"round": k, "judge": judge, "started_from": str(current), "n_items": len(items),
                                "n_sequences": result.n_feedback, "digest": feedback_digest(items), **fcfg.to_dict()}
        write_progress_bundle(out, name, ensemble_arrays(result.model.nets), result.model.model_cfg,
                              result.model.qsr_cfg, training=training, metrics={})
    except BaseException:
        shutil.rmtree(out, ignore_errors=True)
        raise
    return out


def _metrics(k: int, bundle_dir: Path, final_dir: Path, seeds: list[int], summaries: list[dict],
             items: list[FeedbackItem], n_total: int, static: list[FeedbackItem]) -> RoundResult:
    """The round's runs (success by the bundle's judge, final progress) and the new bundle's agreement with
    the 90 graded demos (in sample when the study's grades were among the feedback). The bundle is read
    from ``bundle_dir`` and recorded as ``final_dir``, where it is renamed to once these are known."""

    bundle = load_bundle(bundle_dir)
    graded = [it for it in original_items() if it.action == bundle.name]
    agree = folder_agreement(graded, score_items(bundle.progress_model(), graded))
    return RoundResult(
        round=k,
        bundle=str(final_dir),
        seeds=seeds,
        success_rate=float(np.mean([bool(s.get("success")) for s in summaries])),
        mean_final_progress=float(np.mean([s.get("final_progress") or 0.0 for s in summaries])),
        n_grades=len(items),
        n_grades_total=n_total,
        mean_grade=float(np.mean([it.grade for it in items if it.grade is not None] or [np.nan])),
        agreement={f: round(float(v), 4) for f, v in agree.items()},
        agreement_mean=float(np.mean(list(agree.values()))),
        agreement_in_sample=any(it.source == "original" for it in static),
    )
