"""``train`` and ``score``: learn an action's progress model into a bundle, and score a motion with one.

ACTION is a built-in action name (closer, away, next-to, past, around, or an alias such as next_to) or
the path of a bundle folder; :func:`l2p_bullet.plugins.bundle.resolve_action` decides which (the plugin
registry can replace that one function). torch is imported inside the command bodies.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import click

from .common import force_option, seed_option


def _resolve(spec: str):
    from ..plugins.bundle import resolve_action

    return resolve_action(spec)


def _resolve_for_training(action: str, out_dir: str | None, demo_files: tuple[str, ...]) -> tuple[str, bool]:
    """(action name, is it a plugin action) for ``train``.

    Built-in names and bundle folders resolve as everywhere else. A plugin action (``l2p-bullet
    new-action``) is trained before its package is installed, so it is recognised by the manifest the
    scaffold put in ``--out``, which must name it, and it needs the author's ``--demos``.
    """
    from ..errors import BundleError
    from ..plugins.bundle import read_manifest

    try:
        return _resolve(action)[0], False
    except BundleError:
        out = Path(out_dir) if out_dir else None
        if out is None or not (out / "manifest.toml").is_file():
            raise
        if str(read_manifest(out).get("name", "")) != action:
            raise
        if not demo_files:
            raise BundleError(f'the plugin action "{action}" has no shipped demonstrations: give yours with '
                              "--demos FILE (capture-session .npz, see the plugin's README)") from None
        return action, True


@click.command()
@click.argument("action")
@click.option("--demos", "demo_files", multiple=True, type=click.Path(dir_okay=False),
              help="Capture session files (.npz) of ACTION to train on instead of the shipped ones (repeatable).")
@click.option("--out", "out_dir", type=click.Path(file_okay=False), default=None,
              help="Bundle folder to write (default: runs/bundles/<action>).")
@seed_option
@force_option
@click.option("--ensemble", type=click.IntRange(min=1), default=None, help="Number of LSTMs averaged (default from the trainer).")
@click.option("--epochs", type=click.IntRange(min=1), default=None, help="Epochs per ensemble member (default from the trainer).")
def train(action: str, demo_files: tuple[str, ...], out_dir: str | None, seed: int, force: bool,
          ensemble: int | None, epochs: int | None) -> None:
    """Train ACTION's progress model on the human demonstrations and write a bundle.

    Deterministic for a seed; a few tens of seconds per action on 2 CPU cores. The other actions'
    shipped demonstrations serve as negatives.

    \b
    Examples:
      l2p-bullet train around --out my_around
      l2p-bullet train closer --demos SlideToward_Session1.npz --seed 3 --out closer_s1
    """
    import dataclasses

    from ..errors import RunFolderError
    from ..learning.train_progress import TrainConfig, all_demos, train_action
    from ..learning.trainset import DataConfig
    from ..plugins.bundle import write_progress_bundle

    name, plugin = _resolve_for_training(action, out_dir, demo_files)
    out = Path(out_dir) if out_dir else Path("runs") / "bundles" / name
    # a scaffolded plugin's manifest without weights is a template to fill, not a bundle to protect
    if (out / "manifest.toml").exists() and (out / "progress.safetensors").exists() and not force:
        raise RunFolderError(f"{out} already holds a bundle; pass --force to overwrite it")
    cfg = TrainConfig()
    if ensemble is not None:
        cfg = dataclasses.replace(cfg, ensemble=ensemble)
    if epochs is not None:
        cfg = dataclasses.replace(cfg, epochs=epochs)
    if plugin:  # the author's demonstrations; the built-in actions' shipped ones are the negatives
        from ..learning.demos import load_demos

        demos = {**all_demos(), name: load_demos(name, list(demo_files))}
    else:
        demos = all_demos({name: list(demo_files)} if demo_files else None)
    with click.progressbar(length=cfg.ensemble * cfg.epochs, label=f"training {name}", file=sys.stderr) as bar:
        # a plugin action has no rule telling a random motion is not it: no random negatives
        data_cfg = DataConfig(random_negatives=0) if plugin else None
        result = train_action(name, demos, seed=seed, cfg=cfg, data_cfg=data_cfg, tick=lambda: bar.update(1))
    cmd = (f"l2p-bullet train {name} --seed {seed}" + "".join(f" --demos {f}" for f in demo_files)
           + (f" --ensemble {ensemble}" if ensemble else "") + (f" --epochs {epochs}" if epochs else ""))
    from ..learning.train_progress import training_section

    write_progress_bundle(out, name, result.model, training=training_section(result, cfg, seed, cmd),
                          metrics={"train_loss": round(result.final_loss, 6)})
    click.echo(f"wrote {out} ({result.seconds:.1f} s, {result.n_sequences} sequences)")


@click.command()
@click.argument("action")
@click.argument("file", type=click.Path(dir_okay=False))
def score(action: str, file: str) -> None:
    """Score a motion FILE with ACTION's progress model and print JSON.

    FILE is a scoring input {"size", "mover", "anchor"}, a plan.json or a trajectory.json. The motion
    is resampled to the model's frame spacing; the output has one progress value per input frame.
    """
    from ..core.contracts import load_motion
    from ..plugins.bundle import load_bundle

    name, folder = _resolve(action)
    motion = load_motion(file)
    model = load_bundle(folder).progress_model()
    curve = model.curve(motion.mover, motion.anchor, motion.size)
    click.echo(json.dumps({"action": name, "progress": [round(float(v), 4) for v in curve],
                           "final": round(float(curve[-1]), 4)}))


COMMANDS: list[click.Command] = [train, score]
