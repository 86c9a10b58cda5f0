"""``train``, ``train-policy`` and ``score``: learn an action's progress model and move policy into a
bundle, and score a motion with one.

ACTION is an installed action (built-in or plugin; ``next_to`` = ``next-to``) or the path of a bundle
folder (:func:`l2p_bullet.plugins.registry.locate`). The commands only parse options: the logic is in
:mod:`l2p_bullet.learning` (torch, imported inside the command bodies) and :mod:`l2p_bullet.progress`.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import click

from .common import file_of_run_folder, force_option, greedy_options, seed_option


@click.command(cls=greedy_options("--demos"))
@click.argument("action")
@click.option("--demos", "demo_files", multiple=True, type=click.Path(),
              help="Capture session files (.npz) of ACTION to train on instead of the shipped ones: one or "
                   "more (--demos demos/*.npz), a folder of them, or the option repeated.")
@click.option("--out", "out_dir", type=click.Path(file_okay=False), default=None,
              help="Bundle folder to write (default: runs/bundles/<action>).")
@seed_option
@click.option("--force", is_flag=True,
              help="Overwrite the manifest and progress weights if --out already holds a trained bundle of "
                   "ACTION (other files in it, e.g. policy.safetensors, are kept; a folder that is not a bundle "
                   "is never written to).")
@click.option("--ensemble", type=click.IntRange(min=1), default=None, help="Number of LSTMs averaged (default from the trainer).")
@click.option("--epochs", type=click.IntRange(min=1), default=None, help="Epochs per ensemble member (default from the trainer).")
@click.option("--feedback", "feedback", multiple=True, metavar="SOURCE",
              help='People\'s grades to fine-tune on (repeatable): "original" (the study\'s 90 graded demos), '
                   "a review export (.csv, .jsonl) or a review database (.sqlite, .db).")
@click.option("--feedback-judge", type=click.Choice(["rules"]), default=None,
              help="Also fine-tune on the installed bundle's plans graded by the rule judge (automatic feedback).")
@click.option("--judge-scenes", type=click.IntRange(min=1), default=30, show_default=True,
              help="Scenes planned for --feedback-judge (seeds 5000 on).")
def train(action: str, demo_files: tuple[str, ...], out_dir: str | None, seed: int, force: bool,
          ensemble: int | None, epochs: int | None, feedback: tuple[str, ...], feedback_judge: str | None,
          judge_scenes: int) -> None:
    """Train ACTION's progress model on the human demonstrations and write a bundle.

    Deterministic for a seed; a few tens of seconds per action on 2 CPU cores. The other actions'
    shipped demonstrations serve as negatives. With --feedback, the model is then fine-tuned so that
    its progress at the end of each graded motion follows the people's mean grade (docs/learning.md).

    \b
    Examples:
      l2p-bullet train around --out my_around
      l2p-bullet train closer --demos SlideToward_Session1.npz --seed 3 --out closer_s1
      l2p-bullet train left-of --demos l2p-left-of/demos/*.npz --out l2p-left-of/l2p_left_of
      l2p-bullet train past --feedback original --feedback reviews.csv --out past_fb
    """
    import dataclasses

    from ..evaluate.progressbar import ProgressBar
    from ..learning.feedback_targets import FeedbackConfig
    from ..learning.train_progress import ProgressTrainConfig, train_bundle

    cfg = ProgressTrainConfig()
    cfg = dataclasses.replace(cfg, ensemble=ensemble or cfg.ensemble, epochs=epochs or cfg.epochs)
    fcfg = FeedbackConfig()
    ticks = cfg.ensemble * (cfg.epochs + (fcfg.epochs if feedback or feedback_judge else 0))
    # evaluate's bar, in epochs: redrawn on a terminal, a line every few percent in a log (click's bar
    # printed only its label there, and nothing for 30 s); the ETA counts from the first epoch
    # (printed once the files are read: a bad file stays a one-line error)
    bar = ProgressBar(ticks, unit="epochs", label=f"training {action}")

    def stage(message: str) -> None:
        built = not message.startswith("building")
        click.echo(f"training {action}: {message}" + (f", {cfg.ensemble} x {cfg.epochs} epochs" if built else ""),
                   err=True)
        bar.t0 = time.perf_counter()

    try:
        out, result = train_bundle(action, Path(out_dir) if out_dir else None, demo_files=demo_files, seed=seed,
                                   cfg=cfg, force=force, tick=bar.advance, feedback=feedback,
                                   feedback_judge=feedback_judge, judge_scenes=judge_scenes, feedback_cfg=fcfg,
                                   log=lambda m: click.echo(m, err=True), on_stage=stage)
    finally:
        bar.close()
    extra = f", {result.n_feedback} feedback sequences" if result.n_feedback else ""
    click.echo(f"wrote {out} ({result.seconds:.1f} s, {result.n_sequences} sequences{extra})")


@click.command("train-policy")
@click.argument("action")
@click.option("--bundle", "bundle_dir", type=click.Path(file_okay=False, exists=True), default=None,
              help="Train in this bundle folder, in place (its policy is replaced). Default: a copy of "
                   "ACTION's bundle in --out; the installed bundle is never changed unless named here.")
@click.option("--out", "out_dir", type=click.Path(file_okay=False), default=None,
              help="New folder for the copy of ACTION's bundle with the trained policy "
                   "(default: runs/train-policy-<timestamp>; must not exist).")
@click.option("--force", is_flag=True,
              help="Allow --bundle to be a bundle of the installed l2p-bullet package or of an installed "
                   "plugin (what make bundles does to the shipped bundles).")
@click.option("--iterations", type=click.IntRange(min=1), default=None, help="REINFORCE iterations (default 300).")
@click.option("--episodes", type=click.IntRange(min=1), default=None, help="Episodes per iteration (default 48).")
@seed_option
def train_policy_cmd(action: str, bundle_dir: str | None, out_dir: str | None, force: bool, iterations: int | None,
                     episodes: int | None, seed: int) -> None:
    """Train ACTION's move policy by REINFORCE against its progress model.

    The reward is the rise of the action's learned progress in the 2-D simulator, on random scenes
    the benchmarks never use (docs/planning.md). Minutes on 2 cores; deterministic for a seed.

    \b
    Examples:
      l2p-bullet train-policy around                        (a trained copy in runs/train-policy-<time>)
      l2p-bullet train-policy left-of --bundle l2p-left-of/l2p_left_of
      l2p-bullet train-policy around --bundle l2p_bullet/actions/around --force   (make bundles)
    """
    import dataclasses

    from ..learning.train_policy import PolicyTrainConfig, policy_folder, train_policy_bundle

    folder, copied = policy_folder(action, bundle_dir, out_dir, force)
    cfg = PolicyTrainConfig(seed=seed)
    cfg = dataclasses.replace(cfg, iterations=iterations or cfg.iterations, episodes=episodes or cfg.episodes)
    settings = train_policy_bundle(folder, cfg, log=lambda s: click.echo(s, err=True))
    t = settings["training"]
    where = f"a copy of the {action} bundle in {folder}" if copied else folder
    click.echo(f"wrote the {action} policy into {where} (final progress, mean of the first / last "
               f"{t['window']} iterations: {t['final_progress_first']} -> {t['final_progress_last']}; "
               f"kept iteration {t['kept_iteration']}, its window's mean {t['final_progress_kept']}; "
               f"{t['seconds']} s)")


@click.command()
@click.argument("action")
@click.option("--rounds", type=click.IntRange(1, 40), default=2, show_default=True, help="Rounds of perform, grade, re-train.")
@click.option("--scenes", type=click.IntRange(1, 100), default=10, show_default=True,
              help="Seeded scenes performed per round (seeds 1000 + 100 (round - 1) + i).")
@click.option("--judge", default="rules", show_default=True, metavar="rules|FILE",
              help="Who grades the runs: the rule judge, or people (a review database or export holding grades of the runs).")
@click.option("--feedback", "feedback", multiple=True, metavar="SOURCE",
              help='Grades to fine-tune on in every round as well (repeatable), e.g. "original".')
@click.option("--out", "out_dir", type=click.Path(file_okay=False), default=None,
              help="Folder for the rounds (default: runs/improve/<action>).")
@seed_option
@force_option
def improve(action: str, rounds: int, scenes: int, judge: str, feedback: tuple[str, ...], out_dir: str | None,
            seed: int, force: bool) -> None:
    """Hot feedback: perform ACTION on seeded scenes, grade the runs, re-train, repeat.

    Each round's runs, grades (grades.csv), re-trained bundle and metrics are kept in
    OUT/round-<k>/. With a review file as --judge, a round stops until its runs are graded there; run
    the same command again to go on (finished rounds are kept). Nothing is overwritten without --force,
    which replaces only improve's own files (improve.json, round-<k>/), never a folder holding others.

    \b
    Examples:
      l2p-bullet improve past --rounds 3 --scenes 10
      l2p-bullet improve away --judge reviews.sqlite --out runs/improve/away
    """
    from ..learning.improve import improve as run_improve

    out = Path(out_dir) if out_dir else Path("runs") / "improve" / action.replace("_", "-")
    results = run_improve(action, rounds, out, scenes=scenes, judge=judge, feedback=feedback, seed=seed,
                          force=force, log=lambda m: click.echo(m, err=True))
    for r in results:
        click.echo(f"round {r.round}: success {100 * r.success_rate:.0f} %, final progress {r.mean_final_progress:.2f}, "
                   f"{r.n_grades} grades (mean {r.mean_grade:.1f}), agreement {r.agreement_mean:.2f} -> {r.bundle}")


@click.command()
@click.argument("action")
@click.argument("file", type=click.Path())
def score(action: str, file: str) -> None:
    """Score a motion FILE with ACTION's progress model and print JSON.

    FILE is a scoring input {"size", "mover", "anchor"}, a plan.json, a trajectory.json or a run folder
    (its trajectory.json). The motion is resampled to the model's frame spacing; the output has one
    progress value per input frame.
    """
    from ..core.contracts import dumps_json

    click.echo(dumps_json(score_file(action, file_of_run_folder(file, "trajectory.json"))))


def score_file(action: str, path: str | Path) -> dict[str, Any]:
    """``l2p-bullet score``: per-frame progress of the motion in ``path`` under ``action``'s model.

    ``action`` is an installed action (built-in or plugin) or a bundle folder. Returns
    ``{"action", "progress": [per input frame], "final"}`` rounded to 4 digits (DESIGN.md section 4).
    """
    # inside: every command module is imported when the CLI starts, and numpy with the registry is not cheap
    from ..chain.segments import score_segments
    from ..core.contracts import load_motion
    from ..errors import PathError
    from ..plugins.bundle import load_bundle
    from ..plugins.registry import locate
    from ..progress.scoring import curve_from

    name, folder = locate(action)
    motion = load_motion(path)
    model = load_bundle(folder).progress_model()
    if len(motion.more_anchors) + 1 != model.anchors:
        raise PathError(f'{path}: the action "{name}" reads {model.anchors} reference block(s), the motion gives '
                        f"{len(motion.more_anchors) + 1}" + (' (add "more_anchors")' if model.anchors > 1 else ""))
    kw = {"more_anchors": motion.more_anchors} if motion.more_anchors else {}
    # a run that came near first (trajectory.json's action_from): the action is read from there, as planned
    curve = curve_from(model, motion.action_from, motion.mover, motion.anchor, motion.size, viewer=motion.viewer, **kw)
    out = {"action": name, "progress": [round(float(v), 4) for v in curve], "final": round(float(curve[-1]), 4)}
    segments = score_segments(path, model)  # a chain's trajectory.json: each clause's frames, its own blocks
    return out if segments is None else out | {"segments": segments}


COMMANDS: list[click.Command] = [train, train_policy_cmd, improve, score]
