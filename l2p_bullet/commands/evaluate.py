"""``l2p-bullet evaluate``: every scene x action on a process pool or Ray, one results table, a report."""

from __future__ import annotations

import json
import sys
import time

import click

from .common import MAX_SEED


@click.command("evaluate")
@click.option("--actions", default=None,
              help="Comma-separated actions (default: the built-in ones; installed plugins are named, not run).")
@click.option(
    "--scenes", type=int, default=None, help="N seeded random scenes (default 10; seeds --seed .. --seed+N-1)."
)
@click.option("--scene-file", type=click.Path(dir_okay=False), default=None,
              help="A JSON-lines file, one scene per line (optional id, mover, anchor, seed per line).")
@click.option("--study", is_flag=True, default=None, help="The original study's start configurations (75 scenes).")
@click.option("--bystanders", type=int, default=None,
              help="Add K bystander blocks to every scene (0-10); with --chains, every scene has 2 + K blocks.")
@click.option("--seed", type=click.IntRange(0, MAX_SEED), default=None,
              help=f"First random scene seed, 0 to {MAX_SEED} (default 0).")
@click.option("--planner", default=None, help="Planner for every run (default: each action's own).")
@click.option("--plan-only", "plan_only", is_flag=True, default=None, help="Plan in 2-D only; no arm, no physics.")
@click.option(
    "--render-every", type=int, default=None, help="Render (and keep) every K-th run of each action (default 0: none)."
)
@click.option("--no-render", is_flag=True, help="Render nothing (the same as --render-every 0).")
@click.option("--keep", type=click.Choice(["none", "failed", "all"]), default=None,
              help="Run folders to keep besides the rendered ones (default: none).")
@click.option("--workers", type=int, default=None,
              help="Worker processes, at most 256 (default: the cores; 0: in this process).")
@click.option("--ray", "ray_address", default=None,
              help="Run on Ray: a cluster ADDRESS, auto, or local (an embedded Ray). Needs l2p-bullet[ray].")
@click.option("--out", "out", type=click.Path(file_okay=False), default=None,
              help="Evaluation folder (default runs/evaluate-<timestamp>): results.sqlite, kept runs, report. "
                   "A new evaluation needs a new or empty folder.")
@click.option("--resume", is_flag=True, help="Continue the evaluation in --out: skip the runs already recorded.")
@click.option("--retry-errors", is_flag=True, help="With --resume: run again the runs that ended in an error.")
@click.option("--report", is_flag=True,
              help="Print success per action and the confusion matrices, save them as PNG. Alone with --out: "
                   "report what is recorded there and run nothing.")
@click.option("--parquet", type=click.Path(dir_okay=False), default=None,
              help="Also write the results table as Parquet, to a new file (never overwritten).")
@click.option("--quiet", "-q", is_flag=True, help="No progress bar.")
@click.option("--json", "as_json", is_flag=True, help="Print the summary (and the report's numbers) as JSON.")
@click.option(
    "--arm", default=None, metavar="NAME", help="The arm that performs every run (default panda; l2p-bullet arms)."
)
@click.option("--manners", default=None,
              help="Comma-separated manners of motion, every run in each (default: slide): slide,carry,push.")
@click.option("--chains", type=int, default=None,
              help="K: one chain of K clauses per scene, scenes of 3-5 blocks (CALVIN-style; docs/evaluate.md).")
@click.option("--chain-draw", type=click.Choice(["clause", "sentence"]), default=None,
              help="How a chain is drawn: each clause until it plans (clause, the default), or the whole "
                   "sentence first, then planned as a whole or refused (sentence).")
def evaluate_cmd(actions, scenes, scene_file, study, bystanders, seed, planner, plan_only, render_every, no_render,
                 keep, workers, ray_address, out, resume, retry_errors, report, parquet, quiet, as_json,
                 arm, chains, manners, chain_draw) -> None:
    """Perform (or plan) every scene x action and record one row per run in OUT/results.sqlite.

    \b
    Examples:
      l2p-bullet evaluate --scenes 100 --workers 2 --out runs/eval --report
      l2p-bullet evaluate --study --actions closer,next-to --report
      l2p-bullet evaluate --scenes 1000 --ray auto --out runs/big
      l2p-bullet evaluate --out runs/big --resume          (after Ctrl-C)
      l2p-bullet evaluate --out runs/eval --report         (report what is recorded)
      l2p-bullet evaluate --chains 5 --scenes 50 --out runs/chains --report
      l2p-bullet evaluate --chains 5 --chain-draw sentence --scenes 50 --report
      l2p-bullet evaluate --scenes 20 --manners slide,carry,push --report
    Every run is judged by every installed action's judge and scored by every progress model: the
    report's confusion matrices (rows = asked, columns = recognised).
    """
    from pathlib import Path

    from ..evaluate.runner import evaluate, load_rows

    _check_lists(actions=actions, manners=manners)
    given = {"actions": [a.strip() for a in actions.split(",") if a.strip()] if actions else None,
             "scenes": scenes, "scene_file": scene_file, "study": study, "bystanders": bystanders, "seed": seed,
             "planner": planner, "mode": "plan" if plan_only else None,
             "render_every": 0 if no_render else render_every, "keep": keep, "chains": chains, "arm": arm,
             "chain_draw": chain_draw,
             "manners": [m.strip() for m in manners.split(",") if m.strip()] if manners else None}
    given = {k: v for k, v in given.items() if v is not None}
    folder = Path(out) if out else Path("runs") / f"evaluate-{time.strftime('%Y%m%d-%H%M%S')}"
    report_only = report and not resume and not given and out is not None
    _check_options(given, out, folder, resume=resume, retry_errors=retry_errors, report_only=report_only,
                   parquet=parquet)
    summary = None
    if not report_only:
        config = _config(given, folder, resume)
        try:
            summary = evaluate(config, folder, workers=workers, ray=ray_address, resume=resume,
                               retry_errors=retry_errors, progressbar=not quiet)
        except KeyboardInterrupt:
            n = len(load_rows(folder)) if (folder / "results.sqlite").exists() else 0
            click.echo(f"\ninterrupted: {n} runs recorded in {folder}; continue with: "
                       f"l2p-bullet evaluate --out {folder} --resume", err=True)
            sys.exit(130)
    rows = load_rows(folder)
    if parquet:
        from ..evaluate.results import ResultsStore

        with ResultsStore(folder) as store:
            store.to_parquet(parquet, exclusive=True)
    out_json: dict = {"out": str(folder), "rows": len(rows)}
    if summary is not None:
        out_json.update(total=summary.total, skipped=summary.skipped, ran=summary.ran, failed=summary.failed,
                        errors=summary.errors, seconds=round(summary.seconds, 3),
                        runs_per_s=round(summary.runs_per_s, 4), backend=summary.backend, workers=summary.workers,
                        skipped_actions=summary.notes)
        if not as_json:
            click.echo(f"{summary.ran} runs in {summary.seconds:.1f} s ({summary.runs_per_s:.2f} runs/s, "
                       f"{summary.backend}, {summary.workers} workers); {summary.skipped} already recorded; "
                       f"{summary.failed} failed, {summary.errors} errors; results: {folder / 'results.sqlite'}")
    if report and any(r.get("mode") == "chain" for r in rows):
        from ..evaluate.chains import write_chain_report

        text, files = write_chain_report(rows, folder)
        out_json["report"] = json.loads(files["json"].read_text())
        if not as_json:
            click.echo(text)
            click.echo(f"rows per clause: {files['clauses']}")
    elif report:
        from ..evaluate.report import write_report

        text, files = write_report(rows, folder)
        out_json["report"] = json.loads(files["json"].read_text())
        if not as_json:
            click.echo(text)
            click.echo("plots: " + ", ".join(str(p) for k, p in files.items() if k != "json"))
    if as_json:
        click.echo(json.dumps(out_json, indent=1, default=str))


def _check_lists(**lists: str | None) -> None:
    """``--actions ""`` must not quietly mean every action (nor ``--manners ""`` the default one)."""
    from ..errors import EvaluationError

    for name, text in lists.items():
        if text is not None and not [v for v in text.split(",") if v.strip()]:
            raise EvaluationError(f"--{name} needs at least one name (leave --{name} out for the default)")


def _check_options(given: dict, out: str | None, folder, *, resume: bool, retry_errors: bool, report_only: bool,
                   parquet: str | None) -> None:
    """The options that only make sense together, checked before anything is made or run."""
    from ..errors import EvaluationError
    from ..evaluate.folder import check_parquet_path, stored_settings
    from ..evaluate.runner import EvaluationConfig, check_chains

    if resume and out is None:
        raise EvaluationError("--resume needs --out FOLDER: the evaluation to continue")
    if retry_errors and not resume:
        raise EvaluationError("--retry-errors needs --resume: it runs again the recorded runs that ended in an "
                              "error")
    if "chains" in given:
        check_chains(given["chains"])
    if not resume:
        EvaluationConfig(**given).check()
    if report_only and stored_settings(folder) is None:
        raise EvaluationError(f"nothing to report in {folder}: it holds no evaluation (no results.sqlite with "
                              "settings); to run a new one and report it, give its settings too (e.g. --scenes 10)")
    if parquet:
        check_parquet_path(parquet, folder)


def _config(given: dict, folder, resume: bool):
    """The evaluation's settings: the options given over the defaults, or (``--resume``) over the stored ones."""
    from ..evaluate.folder import stored_settings
    from ..evaluate.runner import EvaluationConfig

    if not resume:
        return EvaluationConfig(**given)
    if not given:
        return None
    stored = stored_settings(folder)
    if stored is None:
        return EvaluationConfig(**given)  # evaluate() says there is nothing to resume
    return EvaluationConfig.from_dict({**stored, **given})


COMMANDS: list[click.Command] = [evaluate_cmd]
