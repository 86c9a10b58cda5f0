"""Real run folders, a live review server and a real Chromium for the review app's tests.

The runs are made once per test session by ``perform`` (small renders, so it stays quick): three
rendered runs and one without rendering (its only view is the 2-D animation). Under pytest-xdist the
workers share them: the first to need them makes them in the run's common temporary folder while the
others wait on a lock.
"""

from __future__ import annotations

import fcntl
import shutil
from pathlib import Path

import http_client
import pytest

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--no-first-run"]
LABELS = ["closer", "away", "next-to", "past", "around"]
RUNS = [("move A closer to B", 1, True), ("move A next to B", 2, True), ("move A past B", 3, True),
        ("move A away from B", 4, False)]


def make_runs(root: Path, shared: Path) -> Path:
    """Perform the four runs into ``shared`` once; every call copies them into ``root`` (cheap)."""
    src = shared / "review-runs-original"
    with open(shared / "review-runs.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file is closed
        if not (shared / "review-runs.done").exists():
            from l2p_bullet.core.scene import random_scene
            from l2p_bullet.embodiment.sim.camera import RenderSettings
            from l2p_bullet.pipeline import perform

            shutil.rmtree(src, ignore_errors=True)  # a worker that failed half-way
            for i, (sentence, seed, render) in enumerate(RUNS):
                perform(sentence, random_scene(seed), out_dir=src / f"run{i}", render=render,
                        render_settings=RenderSettings(width=320, height=240, fps=5, workers=0))
            (shared / "review-runs.done").touch()
    shutil.copytree(src, root, dirs_exist_ok=True)
    return root


@pytest.fixture
def run_folder(tmp_path_factory, request) -> Path:
    """A fresh copy of the four real runs (tests may change or delete them)."""
    base = tmp_path_factory.getbasetemp()
    # an xdist worker's base folder lies in the run's own folder, which all its workers share
    shared = base.parent if hasattr(request.config, "workerinput") else base
    return make_runs(tmp_path_factory.mktemp("runs") / "runs", shared)


class Live:
    """A review app served by uvicorn on 127.0.0.1 (a free port) in a thread, over ``runs``."""

    def __init__(self, db: Path, runs: Path, mode: str = "graded", view: str = "3d"):
        from l2p_bullet.review.app import create_app
        from l2p_bullet.review.queue import ReviewQueue
        from l2p_bullet.review.runs import find_runs
        from l2p_bullet.review.store import Store
        from l2p_bullet.web.server import start

        self.store = Store(db)
        infos = find_runs([runs])
        self.store.register_runs(infos)
        self.queue = ReviewQueue(self.store, infos, mode=mode, view=view, labels=LABELS)
        self.server = start(create_app(self.queue))
        self.url = self.server.url

    def call(self, method: str, path: str, body=None, raw: bytes | None = None, headers: dict | None = None):
        """(status, JSON body) of one request."""
        return http_client.call(self.url, method, path, body, raw, headers)

    def stop(self) -> None:
        self.server.stop()


@pytest.fixture
def live(tmp_path, run_folder):
    servers = []

    def start(mode: str = "graded", view: str = "3d", db: Path | None = None) -> Live:
        s = Live(db or tmp_path / "reviews.sqlite", run_folder, mode, view)
        servers.append(s)
        return s

    yield start
    for s in servers:
        s.stop()


def open_page(browser, url: str, width: int, height: int):
    """A new page of ``browser`` at ``url`` (its own context) and the list its JavaScript errors go to."""
    context = browser.new_context(viewport={"width": width, "height": height})
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(url)
    return page, errors
