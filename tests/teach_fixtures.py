"""A scaffolded plugin and a live teach server for the teach page's tests (Chromium: review_fixtures)."""

from __future__ import annotations

from pathlib import Path

import http_client
import pytest


def small_video():
    """The performance's video for the page's tests: what the page shows does not depend on its size, and
    the default (640x480 at 15 fps) costs most of a minute on two cores for a row of four blocks. The
    default video itself is played in Chromium by tests/review/test_review_browser.py."""
    from l2p_bullet.embodiment.sim.camera import RenderSettings

    return RenderSettings(width=320, height=240, fps=5, workers=0)


class Live:
    """The teach app for a fresh plugin ``name`` (scaffolded in ``root``), served on 127.0.0.1 in a thread."""

    def __init__(self, root: Path, name: str, phrase: str, frame: str = "relative", anchors: int = 1,
                 ensemble: int = 1, epochs: int = 2, seed: int = 0):
        from l2p_bullet.learning.train_progress import BundleTrainer, ProgressTrainConfig
        from l2p_bullet.plugins.scaffold import scaffold
        from l2p_bullet.teach.app import create_app
        from l2p_bullet.teach.lesson import Lesson, find_action
        from l2p_bullet.web.server import start

        self.root = scaffold(name, [phrase], root / f"l2p-{name}", frame=frame, anchors=anchors).root
        self.action = find_action(name, self.root)
        trainer = BundleTrainer(ProgressTrainConfig(ensemble=ensemble, epochs=epochs))
        self.lesson = Lesson(self.action, trainer, seed=seed, render_settings=small_video())
        self.server = start(create_app(self.lesson), name="teach-server")
        self.url = self.server.url

    def call(self, method: str, path: str, body=None, raw: bytes | None = None):
        """(status, JSON body) of one request."""
        return http_client.call(self.url, method, path, body, raw)

    def stop(self) -> None:
        self.server.stop()


@pytest.fixture
def live(tmp_path):
    servers = []

    def start(name: str = "left-of", phrase: str = "to the left of", **kw) -> Live:
        s = Live(tmp_path, name, phrase, **kw)
        servers.append(s)
        return s

    yield start
    for s in servers:
        s.stop()


class Rows:
    """The teach app of a composite plugin ("make a blorp of"), served on 127.0.0.1 in a thread."""

    def __init__(self, root):
        import http_client

        from l2p_bullet.plugins.scaffold import scaffold
        from l2p_bullet.teach.app import create_app
        from l2p_bullet.teach.lesson import find_action
        from l2p_bullet.teach.rows import RowLesson
        from l2p_bullet.web.server import start

        self.action = find_action(
            "blorp", scaffold("blorp", ["make a blorp of"], root / "l2p-blorp", kind="composite").root
        )
        self.lesson = RowLesson(self.action, None)
        self.server = start(create_app(self.lesson), name="teach-rows")
        self.call = lambda method, path, body=None, raw=None: http_client.call(self.server.url, method, path, body, raw)
        self.scene = self.lesson.scene(1)  # three blocks: A, B, C

    def drag(self, block: str, dx: float = 0.0, dy: float = 0.12, n: int = 31, seconds: float = 1.0,
             t0: float = 0.0) -> dict:
        o = self.scene.get(block)
        return {"block": block, "samples": [[t0 + seconds * i / (n - 1), o.xy[0] + dx * i / (n - 1),
                                             o.xy[1] + dy * i / (n - 1), o.yaw] for i in range(n)]}

    def post(self, *segments) -> tuple[int, dict]:
        return self.call("POST", "/api/rows", {"scene": 1, "segments": list(segments)})
