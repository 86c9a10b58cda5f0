"""``l2p-bullet teach`` as started from the command line: the page is served before torch is imported (the trainer
is made when the page first trains), and what it trains with is the command's ``--ensemble`` and ``--epochs``."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.plugins.scaffold import scaffold

SERVED = """\
import sys
from l2p_bullet.web import server
server.serve = lambda app, sock: print("torch imported:", "torch" in sys.modules)
from l2p_bullet.cli import main
main(["teach", sys.argv[1], "--plugin", sys.argv[2], "--port", "0"])
"""


def test_the_page_is_served_before_torch_is_imported(tmp_path: Path):
    root = scaffold("lefty", ["lefty phrase"], tmp_path / "l2p-lefty").root
    r = subprocess.run([sys.executable, "-c", SERVED, "lefty", str(root)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.strip() == "torch imported: False", (r.stdout, r.stderr[-2000:])


def test_the_page_trains_with_the_commands_ensemble_and_epochs(tmp_path: Path, monkeypatch):
    from l2p_bullet.learning import train_progress
    from l2p_bullet.teach import app
    from l2p_bullet.web import server

    root = scaffold("lefty", ["lefty phrase"], tmp_path / "l2p-lefty").root
    lessons, trained = [], []
    made = app.create_app
    monkeypatch.setattr(app, "create_app", lambda lesson, host: lessons.append(lesson) or made(lesson, host))
    monkeypatch.setattr(server, "serve", lambda a, sock: sock.close())
    monkeypatch.setattr(train_progress, "train_bundle", lambda *a, **kw: trained.append((a, kw)) or "done")
    r = CliRunner().invoke(main, ["teach", "lefty", "--plugin", str(root), "--port", "0", "--ensemble", "2",
                                  "--epochs", "3"])
    assert r.exit_code == 0, r.output
    (lesson,) = lessons
    assert lesson.trainer.ticks == 6
    assert lesson.trainer("lefty", tmp_path / "out", ["a.npz"], seed=4) == "done"
    (args, kw), = trained
    assert args == ("lefty", tmp_path / "out") and kw["demo_files"] == ["a.npz"] and kw["seed"] == 4
    assert (kw["cfg"].ensemble, kw["cfg"].epochs, kw["force"]) == (2, 3, True)
