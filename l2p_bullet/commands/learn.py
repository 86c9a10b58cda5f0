"""``train``, ``train-policy`` and ``score``: learn an action's progress model and move policy into a
bundle, and score a motion with one.

ACTION is an installed action (built-in or plugin; ``next_to`` = ``next-to``) or the path of a bundle
folder (:func:`l2p_bullet.plugins.registry.locate`). The commands only parse options: the logic is in
:mod:`l2p_bullet.learning` (torch, imported inside the command bodies) and :mod:`l2p_bullet.progress`.
"""

from __future__ import annotations

import shlex
import time
from pathlib import Path
from typing import Any

import click

from .common import file_of_run_folder, force_option, greedy_options, seed_option


@click.command("train", cls=greedy_options("--demos"))
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
@click.option(
    "--ensemble", type=click.IntRange(min=1), default=None, help="Number of LSTMs averaged (default from the trainer)."
)
@click.option(
    "--epochs", type=click.IntRange(min=1), default=None, help="Epochs per ensemble member (default from the trainer)."
)
@click.option("--feedback", "feedback", multiple=True, metavar="SOURCE",
              help='People\'s grades to fine-tune on (repeatable): "original" (the study\'s 90 graded demos), '
                   "a review export (.csv, .jsonl) or a review database (.sqlite, .db).")
@click.option("--feedback-judge", type=click.Choice(["rules"]), default=None,
              help="Also fine-tune on the installed bundle's plans graded by the rule judge (automatic feedback).")
@click.option("--judge-scenes", type=click.IntRange(min=1), default=30, show_default=True,
              help="Scenes planned for --feedback-judge (seeds 5000 on).")
def train_cmd(action: str, demo_files: tuple[str, ...], out_dir: str | None, seed: int, force: bool,
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

    from ..errors import plural
    from ..evaluate.progressbar import ProgressBar
    from ..learning.feedback_targets import FeedbackConfig
    from ..learning.train_policy import policy_command
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
    extra = f", {plural(result.n_feedback, 'feedback sequence')}" if result.n_feedback else ""
    click.echo(f"wrote {out} ({result.seconds:.1f} s, {plural(result.n_sequences, 'sequence')}{extra})")
    # the bundle's policy, if any, was trained for the old progress model: what to run next
    policy = policy_command(action, out)
    click.echo("next: " + (f"{policy} (its move policy), then " if policy else "")
               + f"l2p-bullet score {shlex.quote(str(out))} MOTION or l2p-bullet recognize MOTION --action "
               f"{shlex.quote(str(out))}")


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

    from ..evaluate.progressbar import ProgressBar
    from ..learning.train_policy import PolicyTrainConfig, train_policy_into

    cfg = PolicyTrainConfig(seed=seed)
    cfg = dataclasses.replace(cfg, iterations=iterations or cfg.iterations, episodes=episodes or cfg.episodes)
    # evaluate's bar, in iterations, after the last one's number (from 0, as the summary's kept iteration)
    # and final progress: the "iter 10" lines every ten iterations gave neither the total nor an ETA
    # (in a log, a line every 5 % or 10 s)
    bar = ProgressBar(cfg.iterations, unit="iterations", label=f"{action} policy:")

    def tick(progress: float) -> None:
        bar.label = f"{action} policy: iter {bar.done:4d}  final progress {progress:.3f}"
        bar.advance()

    try:
        # a Ctrl-C or failure removes the copy this run made, and its note says what was kept
        folder, copied, settings = train_policy_into(action, bundle_dir, out_dir, force, cfg, log=None, tick=tick)
    finally:
        if bar.done:  # a refused folder is one line, with no empty line before it on a terminal
            bar.close()
    t = settings["training"]
    where = f"a copy of the {action} bundle in {folder}" if copied else folder
    click.echo(f"wrote the {action} policy into {where} (final progress, mean of the first / last "
               f"{t['window']} iterations: {t['final_progress_first']} -> {t['final_progress_last']}; "
               f"kept iteration {t['kept_iteration']}, its window's mean {t['final_progress_kept']}; "
               f"{t['seconds']} s)")
    click.echo(f"next: {_policy_next_step(action, folder, copied)}")


def _policy_next_step(action: str, folder: Path, copied: bool) -> str:
    """What to do with a trained policy: perform plans with the installed bundle only, so a copy (or an
    uninstalled plugin's bundle) is used by copying it there (or installing the plugin)."""
    from ..learning.train_policy import installed
    from ..plugins.registry import locate

    if installed(folder):
        return (f"perform and plan use it now; measure it with l2p-bullet evaluate --actions "
                f"{shlex.quote(action)} --scenes 10 --report")
    q = shlex.quote(str(folder))
    use = f"l2p-bullet score {q} MOTION or l2p-bullet recognize MOTION --action {q}"
    if not copied:
        return f"{use}; to perform with it, install the plugin this bundle belongs to (pip install -e ...)"
    source = locate(action)[1]
    return (f"{use}; to perform with it, copy its files into {shlex.quote(str(source))} (or train there: "
            f"l2p-bullet train-policy {shlex.quote(action)} --bundle {shlex.quote(str(source))} --force)")


@click.command("improve")
@click.argument("action")
@click.option(
    "--rounds", type=click.IntRange(1, 40), default=2, show_default=True, help="Rounds of perform, grade, re-train."
)
@click.option("--scenes", type=click.IntRange(1, 100), default=10, show_default=True,
              help="Seeded scenes performed per round (seeds 1000 + 100 (round - 1) + i).")
@click.option(
    "--judge",
    default="rules",
    show_default=True,
    metavar="rules|FILE",
    help="Who grades the runs: the rule judge, or people (a review database or export holding grades of the runs).",
)
@click.option("--feedback", "feedback", multiple=True, metavar="SOURCE",
              help='Grades to fine-tune on in every round as well (repeatable), e.g. "original".')
@click.option("--out", "out_dir", type=click.Path(file_okay=False), default=None,
              help="Folder for the rounds (default: runs/improve/<action>).")
@seed_option
@force_option
def improve_cmd(action: str, rounds: int, scenes: int, judge: str, feedback: tuple[str, ...], out_dir: str | None,
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
    from ..errors import plural
    from ..learning.improve import improve as run_improve

    out = Path(out_dir) if out_dir else Path("runs") / "improve" / action.replace("_", "-")
    try:
        results = run_improve(action, rounds, out, scenes=scenes, judge=judge, feedback=feedback, seed=seed,
                              force=force, log=lambda m: click.echo(m, err=True))
    except KeyboardInterrupt as e:
        # the same command resumes (finished rounds and performed runs are kept): say which, in full
        e.add_note(f"finished rounds are kept in {out}")
        e.add_note("continue with: " + _improve_command(action, rounds, scenes, judge, feedback, out, seed, force))
        raise
    for r in results:
        click.echo(
            f"round {r.round}: success {100 * r.success_rate:.0f} %, final progress {r.mean_final_progress:.2f}, "
            f"{plural(r.n_grades, 'grade')} (mean {r.mean_grade:.1f}), agreement {r.agreement_mean:.2f} "
            f"-> {r.bundle}"
        )
    last = shlex.quote(results[-1].bundle)
    click.echo(f"next: l2p-bullet score {last} MOTION or l2p-bullet recognize MOTION --action {last}; its move "
               f"policy is the first bundle's: l2p-bullet train-policy {shlex.quote(action)} --bundle {last}")


def _improve_command(action: str, rounds: int, scenes: int, judge: str, feedback: tuple[str, ...], out: Path,
                     seed: int, force: bool) -> str:
    """The command line that continues an interrupted ``improve``: the settings it was given (improve.json
    must match them to resume), defaults left out, --out always (a default folder is named in full)."""
    args = ["l2p-bullet", "improve", action, "--rounds", str(rounds), "--scenes", str(scenes)]
    if judge != "rules":
        args += ["--judge", judge]
    for f in feedback:
        args += ["--feedback", f]
    args += ["--out", str(out)]
    if seed:
        args += ["--seed", str(seed)]
    return shlex.join(args)  # never --force: it starts over (improve.json already holds these settings)


@click.command("score")
@click.argument("action")
@click.argument("file", type=click.Path())
def score_cmd(action: str, file: str) -> None:
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


COMMANDS: list[click.Command] = [train_cmd, train_policy_cmd, improve_cmd, score_cmd]
