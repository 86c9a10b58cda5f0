"""``l2p-bullet review`` (the review web app, import, export) and ``l2p-bullet report``.

The web stack (FastAPI, uvicorn) and matplotlib are imported inside the commands only, so
``l2p-bullet --help`` and ``perform`` never load them.
"""

from __future__ import annotations

import json
import shlex
from pathlib import Path

import click

DEFAULT_DB = Path("runs") / "reviews.sqlite"


def _default_db(runs: tuple[str, ...]) -> Path:
    """Next to the runs: ``<parent of the first run folder>/reviews.sqlite``; else runs/reviews.sqlite."""
    if not runs:
        return DEFAULT_DB
    first = Path(runs[0])
    return (first.parent if (first / "trajectory.json").is_file() else first) / "reviews.sqlite"


@click.command("review")
@click.argument("runs", nargs=-1, type=click.Path(), metavar="[RUN_OR_FOLDER]...")
@click.option("--db", "db", type=click.Path(dir_okay=False), default=None,
              help="Review database (SQLite; default: reviews.sqlite next to the runs, else runs/reviews.sqlite).")
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to listen on. Anything but 127.0.0.1 lets other machines submit grades.")
@click.option("--port", type=click.IntRange(0, 65535), default=8765, show_default=True, help="Port (0: any free one).")
@click.option("--mode", type=click.Choice(["graded", "blind"]), default="graded", show_default=True,
              help="graded: the sentence is shown, people grade 0-10; blind: no sentence, people pick the action.")
@click.option("--view", type=click.Choice(["3d", "2d", "both"]), default="3d", show_default=True,
              help="What people watch: the video (3d), a top-down animation (2d), or each run in both, "
                   "graded separately (question 3 of the evaluation).")
@click.option("--import-original", "import_original", is_flag=True,
              help="Import the 2018 study's grades (90 graded 2-D demos, two graders each) into the database.")
@click.option("--export", "export", type=click.Path(dir_okay=False), default=None,
              help="Write every answer to FILE.csv or FILE.jsonl (docs/review.md) and exit.")
@click.option("--force", is_flag=True, help="Overwrite the --export file if it exists.")
@click.option("--regrade-changed", is_flag=True,
              help="Serve runs whose trajectory.json changed since they were graded, as new versions "
                   "(the old grades are kept, marked stale).")
def review_cmd(runs: tuple[str, ...], db: str | None, host: str, port: int, mode: str, view: str,
               import_original: bool, export: str | None, force: bool, regrade_changed: bool) -> None:
    """Let people grade runs in a browser; their answers go to a SQLite file.

    RUN_OR_FOLDER: run folders (perform, replay) or folders holding them.

    \b
    Examples:
      l2p-bullet review runs/                     # grade every run under runs/ (http://127.0.0.1:8765/)
      l2p-bullet review runs/ --mode blind        # people pick which action each run shows
      l2p-bullet review --import-original         # the 2018 study's grades, for l2p-bullet report
      l2p-bullet review --export grades.csv       # every answer, for analysis or feedback learning
    """
    from ..errors import ReviewError
    from ..review.store import Store

    if not runs and not import_original and not export:
        raise ReviewError("nothing to do: give run folders to review (e.g. l2p-bullet review runs/), "
                          "--import-original or --export FILE")
    run_infos = []
    if runs:
        from ..review.runs import find_runs

        run_infos = find_runs(list(runs))  # a bad folder fails before a database is created
    db_path = Path(db) if db else _default_db(runs)
    if not runs and not import_original and not db_path.exists():
        raise ReviewError(f"no review database at {db_path} to export from (give --db FILE)")
    if db is None and db_path == DEFAULT_DB:
        db_path.parent.mkdir(exist_ok=True)  # the default place for runs and their reviews
    store = Store(db_path)
    if store.migrated_from and store.migrated_from < _schema_version():
        click.echo(f"review database {store.path}: schema migrated from version {store.migrated_from}", err=True)
    if import_original:
        from ..review.original import import_original as do_import

        r = do_import(store)
        click.echo(f"imported the original study into {store.path}: {r.demos} graded demos, {r.grades} grades "
                   f"({r.added} new)")
        # what the grades are for: the report's tables (its --db is named even where it is the default)
        click.echo(f"next: l2p-bullet report --db {shlex.quote(str(store.path))}")
    if export:
        n = store.export(export, force=force)
        click.echo(f"wrote {n} answers to {export}")
    if not run_infos:
        return
    _serve(store, run_infos, host, port, mode, view, regrade_changed)


def _schema_version() -> int:
    from ..data.review_schema import SCHEMA_VERSION

    return SCHEMA_VERSION


def _serve(store, run_infos, host: str, port: int, mode: str, view: str, regrade_changed: bool) -> None:
    from ..plugins import registry
    from ..review.app import create_app
    from ..review.queue import ReviewQueue
    from ..web.apps import is_loopback
    from ..web.server import bind, serve, url_of

    reg = store.register_runs(run_infos, accept_changed=regrade_changed)
    changed = {run.run_id for run, _, _ in reg.changed}
    for run, _old, n in reg.changed:
        what = "served again as a new version" if regrade_changed else "NOT served (--regrade-changed serves it)"
        click.echo(f"warning: {run.path}/trajectory.json changed since it was registered ({n} answers were for the "
                   f"old one and are kept): {what}", err=True)
    served = [r for r in run_infos if regrade_changed or r.run_id not in changed]
    labels = [p.name for p in registry.discover() if p.ok]
    queue = ReviewQueue(store, served, mode=mode, view=view, labels=labels)
    queue.problems.update({rid: "changed" for rid in changed if not regrade_changed})  # the page says so too
    app = create_app(queue, host=host)
    sock = bind(host, port)
    if not is_loopback(host):
        click.echo(f"warning: listening on {host}: anyone who can reach this machine can submit grades", err=True)
    click.echo(f"reviewing {len(served)} runs ({len(queue.items)} items, {mode} mode, view {view}); answers go to "
               f"{store.path}")
    click.echo(f"open {url_of(sock)} in a browser; Ctrl+C stops (every answer is saved as it is submitted)")
    serve(app, sock)


@click.command("report")
@click.option("--db", "db", type=click.Path(dir_okay=False), default=str(DEFAULT_DB), show_default=True,
              help="Review database, or a grades export (.csv / .jsonl).")
@click.option("--out", "out", type=click.Path(file_okay=False), default=None,
              help="Folder for the tables (CSV, Markdown) and plots (PNG); default: <db>-report next to the database.")
@click.option("--json", "as_json", is_flag=True, help="Print the report as JSON.")
def report_cmd(db: str, out: str | None, as_json: bool) -> None:
    """The evaluation's tables from the grades.

    Table 1 (mean grade, evaluator disparity), the blind confusion matrix and Fleiss' kappa, how the
    learned progress and the judges rank runs against people (Spearman), 2-D vs 3-D grades. The tables
    and plots go to a new folder, or replace an earlier report of this command there (never other files).
    """
    from ..errors import ReviewError
    from ..review.report import (
        build_report,
        read_report_grades,
        render_text,
        report_folder,
        write_grade_report,
    )

    path = Path(db)
    if not path.exists():
        raise ReviewError(f"no review database at {path}: grade some runs with l2p-bullet review, or import the "
                          "original study with l2p-bullet review --import-original")
    rep = build_report(read_report_grades(path), source=str(path))
    folder = Path(out) if out else path.with_name(path.stem + "-report")
    with report_folder(folder, path):  # after the grades are read: a bad file costs no folder
        files = write_grade_report(rep, folder)
    if as_json:
        click.echo(json.dumps(rep, indent=1, default=str))
        return
    click.echo(render_text(rep))
    click.echo(f"\ntables and plots: {folder} ({len(files)} files)")


COMMANDS: list[click.Command] = [review_cmd, report_cmd]
