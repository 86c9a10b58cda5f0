"""``l2p-bullet teach``: record demonstrations of a new preposition in the browser, train it, watch it.

The web stack (FastAPI, uvicorn) is imported inside the command only, so ``l2p-bullet --help`` and
``perform`` never load it.
"""

from __future__ import annotations

import click

from .common import seed_option


@click.command("teach")
@click.argument("action")
@click.option("--plugin", "plugin_dir", type=click.Path(file_okay=False), default=None,
              help="The plugin project made by new-action (default: ./l2p-ACTION).")
@click.option("--demos", "demos", type=click.Path(dir_okay=False), default=None,
              help="Demos file the recordings are appended to (default: PLUGIN/demos/ACTION_taught.npz).")
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to listen on. Anything but 127.0.0.1 lets other machines write demonstrations.")
@click.option("--port", type=click.IntRange(0, 65535), default=8766, show_default=True, help="Port (0: any free one).")
@click.option("--ensemble", type=click.IntRange(min=1), default=None, help="LSTMs the train button trains (default 5).")
@click.option("--epochs", type=click.IntRange(min=1), default=None, help="Epochs per LSTM (default 30).")
@seed_option
def teach_cmd(action: str, plugin_dir: str | None, demos: str | None, host: str, port: int,
              ensemble: int | None, epochs: int | None, seed: int) -> None:
    """Record demonstrations of ACTION in the browser, then train it and watch it performed.

    ACTION is a plugin made by new-action. The page shows a random scene from above: drag block A with
    the mouse (wheel or Q / W rotates it), mark the start (S) and the end (E), save (Enter). Each
    demonstration is appended to the demos file; "train and perform" trains the plugin on every demos
    file of PLUGIN/demos and performs it on a new scene, with video.

    A composite action (new-action --composite) is taught with whole rows: drag the named blocks one after
    another (each drag is one step), save (Enter); "train and perform" learns the recipe from the rows and
    performs a row of four blocks.

    "Remove the last demonstration" (two clicks) takes back a mistaken one. One teach page per plugin:
    a second teach on the same plugin is refused, naming the first one's process and address.

    \b
    Example:
      l2p-bullet new-action left-of --phrase "to the left of" --frame viewer --judge left-of
      l2p-bullet teach left-of          # then open http://127.0.0.1:8766/
    """
    import dataclasses
    from pathlib import Path

    from ..learning.training_plan import ProgressTrainConfig
    from ..teach.lesson import Lesson, find_action

    taught = find_action(action, plugin_dir, demos)  # a wrong name fails before anything listens
    cfg = ProgressTrainConfig()
    cfg = dataclasses.replace(cfg, ensemble=ensemble or cfg.ensemble, epochs=epochs or cfg.epochs)
    from ..plugins.bundle import read_manifest
    from ..teach.rows import RowLesson

    composite = read_manifest(taught.bundle_dir).get("kind") == "composite"
    lesson = (RowLesson if composite else Lesson)(taught, _Trainer(cfg), seed=seed)
    lesson.count()  # an unreadable demos file is a one-line error now, not on the first save

    from ..teach.app import create_app
    from ..web.apps import is_loopback
    from ..web.server import bind, serve, url_of

    sock = bind(host, port)
    from ..teach.lock import claim_plugin

    try:  # one page per plugin folder: two would overwrite each other's demonstrations
        claim_plugin(taught.root, url_of(sock))  # held until the process ends
    except BaseException:
        sock.close()
        raise
    if not is_loopback(host):  # as review says it: off loopback the Host check is off too
        click.echo(f"warning: listening on {host}: anyone who can reach this machine can write demonstrations "
                   "and start training", err=True)
    click.echo(f"teaching \"{taught.sentence}\": open {url_of(sock)} (Ctrl+C to stop)", err=True)
    click.echo(f"demonstrations go to {Path(lesson.config()['demos'])}", err=True)
    serve(create_app(lesson, host), sock)


class _Trainer:
    """The page's trainer, ``learning.train_progress.BundleTrainer``, made when the page first trains: its module
    imports torch, seconds of the page's start that a page refused (another teach holds the plugin), closed
    unused, or teaching a composite (whose recipe needs no LSTM) would spend for nothing."""

    def __init__(self, cfg) -> None:
        self.cfg = cfg
        self._made = None

    def _trainer(self):
        if self._made is None:
            from ..learning.train_progress import BundleTrainer

            self._made = BundleTrainer(self.cfg)
        return self._made

    @property
    def ticks(self) -> int:
        return self._trainer().ticks

    def __call__(self, *args, **kwargs):
        return self._trainer()(*args, **kwargs)


COMMANDS: list[click.Command] = [teach_cmd]
